/**
 * @file lattice_honeycomb.c
 * @brief Triple honeycomb (alpha-beta-gamma) lattice: calibration, bond
 *        families and the sublattice relaxation of the patch test.
 *
 * Geometry ([Wang2010] Fig. 3d, Ostoja-Starzewski 2002 sec. 2): colour the
 * sites of a triangular lattice (spacing r0) with the three sublattices A, B,
 * C of spacing sqrt3 r0 (lattice_sublattice).  The bonds A-B with their sites
 * form a honeycomb lattice, and so do B-C and C-A; the three honeycombs
 * together use every nearest-neighbour bond once.  Their central springs get
 * the stiffnesses alpha, beta, gamma.  With alpha = beta = gamma this is the
 * plain triangular lattice (nu = 1/3).
 *
 * Moduli (our derivation, which reproduces the paper's formulas).  Unit cell:
 * one site of each colour, area 3 sqrt3 r0^2 / 2, three bonds of each
 * family.  From A the three B neighbours lie along n_1, n_2, n_3 (120 deg
 * apart); the same three vectors lead from B to C and from C to A.  Under a
 * uniform strain eps plus rigid sublattice shifts u_A, u_B, u_C a bond of
 * family f (internal shift d_f = u_B - u_A for A-B, etc.) stretches by
 *   delta = r0 n.eps.n + n.d_f,
 * and d_AB + d_BC + d_CA = 0.
 *  - Affine part (d = 0): with sum_k (n_k.eps.n_k)^2 = 3/8 ((tr eps)^2 +
 *    2 eps:eps), the cell stores (3 r0^2 / 16) S ((tr eps)^2 + 2 eps:eps),
 *    S = alpha + beta + gamma, so lambda t = mu_aff t = S / (4 sqrt3) and
 *    kappa t = S / (2 sqrt3).
 *  - Relaxation: using sum n_k = 0 and sum n_k n_k = 3/2 I, family f stores
 *    k_f/2 (aff + 2 r0 v.d_f + 3/2 |d_f|^2) with v = sum_k (n_k.eps.n_k) n_k.
 *    Dilatation gives v = 0: no relaxation, kappa is the affine one.  For a
 *    deviatoric strain (eps_xx = -eps_yy = e, eps_xy = g) |v|^2 = 9/4 (e^2 +
 *    g^2) in every orientation.  Minimising over d_f under sum d_f = 0
 *    (Lagrange) gives d_f = (2/3) r0 v (3 / (H k_f) - 1), H = sum 1/k_f, and
 *    lowers the cell energy by (3/4) r0^2 (e^2 + g^2) (S - 9/H).  Per area
 *    this removes (S - 9/H) / (4 sqrt3) from mu t:
 *        mu t = 9 / (4 sqrt3 H) = 3 sqrt3 / (4 (1/alpha + 1/beta + 1/gamma)).
 *    With equal families H = 3/k and the relaxation vanishes (the forces of
 *    the three families on a sublattice cancel), as for the triangular
 *    lattice.  mu / kappa = 3 h / (2 S) with h = 3 / H the harmonic mean:
 *    between 0 (one family soft: nu -> 1) and 1/2 (equal: nu = 1/3).  So the
 *    model covers nu in [1/3, 1) ([Wang2010] sec. 2.2) because the unequal
 *    families let the sublattices shift and soften shear, never bulk.
 * Calibration (plane stress, thickness t): kappa t = E t / (2 (1 - nu)) and
 * mu t = E t / (2 (1 + nu)) fix S and H; the third parameter is free.  We
 * take beta = gamma and alpha = x beta with x <= 1 (one softer family): with
 * rho = mu / kappa = (1 - nu) / (1 + nu), h / (S/3) = 9 x / ((1 + 2x)(x + 2))
 * = 2 rho, i.e. 4 rho x^2 + (10 rho - 9) x + 4 rho = 0, whose roots are x and
 * 1/x; the smaller one, written without cancellation,
 *        x = 8 rho / ((9 - 10 rho) + 3 sqrt((1 - 2 rho)(9 - 2 rho))),
 * then beta = S / (x + 2), alpha = x beta.  The choice x <= 1 keeps the
 * stiffest spring at most S/2 (the other root, one stiff family, would reach
 * S as nu -> 1, halving the stable step) and tends to the dice lattice (two
 * honeycombs) rather than a single honeycomb as nu -> 1.
 *
 * Patch test: under uniform strain the sublattices must be allowed to shift
 * (a 3-site basis is not a Bravais lattice), so lattice_honeycomb_relax finds
 * the shifts that zero the net force on each sublattice.  A dynamic run
 * needs no such help: the particles find the shifts themselves (the
 * validation case abg-patch checks a clamped finite block and the long-wave
 * speed, which both see the relaxed moduli).
 */
#include "models/lattice/lattice_honeycomb.h"

#include "core/bond_list.h"
#include "core/lattice_gen.h"
#include "core/particles.h"
#include "core/sim.h"
#include "models/lattice/lattice_calib.h"
#include "models/lattice/lattice_internal.h"
#include "spall/error.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static const double SQRT3 = 1.7320508075688772;

int lattice_honeycomb_constants(double E, double nu, double t, double k[3],
                                struct spall_error *err)
{
    k[0] = k[1] = k[2] = 0.0;
    if (!(nu < 1.0))
        return spall_error_set(err, SPALL_ERR_PHYSICS,
                               "Poisson's ratio %g >= 1 is not a stable 2D solid (the triple "
                               "honeycomb covers [1/3, 1))", nu);
    if (nu < 1.0 / 3.0 - LATTICE_NU_TOL)
        return spall_error_set(err, SPALL_ERR_PHYSICS,
                               "Poisson's ratio %g < 1/3: the triple honeycomb (alpha-beta-gamma, "
                               "central springs only) has shear/bulk = harmonic/(2 arithmetic "
                               "mean) of its springs <= 1/2, i.e. nu in [1/3, 1); use the "
                               "triangular lattice with angular springs (alpha-beta)", nu);
    if (nu < 1.0 / 3.0)
        nu = 1.0 / 3.0;
    const double S = SQRT3 * E * t / (1.0 - nu); /* 2 sqrt3 kappa t */
    const double rho = (1.0 - nu) / (1.0 + nu);  /* mu / kappa, in (0, 1/2] */
    const double disc = fmax((1.0 - 2.0 * rho) * (9.0 - 2.0 * rho), 0.0);
    const double x = 8.0 * rho / ((9.0 - 10.0 * rho) + 3.0 * sqrt(disc));
    const double beta = S / (x + 2.0);
    k[0] = x * beta;
    k[1] = k[2] = beta;
    if (!(k[0] > 0.0) || !isfinite(beta))
        return spall_error_set(err, SPALL_ERR_PHYSICS,
                               "triple honeycomb: no positive springs for nu = %g", nu);
    return SPALL_OK;
}

void lattice_honeycomb_moduli(const double k[3], double *kappa_t, double *mu_t)
{
    double S = k[0] + k[1] + k[2];
    double H = 1.0 / k[0] + 1.0 / k[1] + 1.0 / k[2];
    if (kappa_t)
        *kappa_t = S / (2.0 * SQRT3);
    if (mu_t)
        *mu_t = 9.0 / (4.0 * SQRT3 * H);
}

void lattice_honeycomb_retype(struct bond_list *bl, const struct particles *p,
                              const struct lattice_spec *spec)
{
    for (size_t i = 0; i < bl->n; i++) {
        const double xi[2] = {p->x0[0][i], p->x0[1][i]};
        const int ci = lattice_sublattice(spec, xi);
        for (size_t s = bl->offset[i]; s < bl->offset[i + 1]; s++) {
            if (bl->type[s] != 0)
                continue;
            const size_t j = (size_t)bl->partner[s];
            const double xj[2] = {p->x0[0][j], p->x0[1][j]};
            const int cj = lattice_sublattice(spec, xj);
            /* neighbours differ in colour; family = the colour not joined */
            bl->type[s] = (uint8_t)(ci == cj ? 0 : 3 - ci - cj);
        }
    }
}

/** Net force on the inner particles of sublattices 1 and 2 (x, y each). */
static int sublattice_force(struct model *m, struct sim *s, const bool *inner,
                            const int *colour, double g[4], struct spall_error *err)
{
    struct particles *p = s->p;
    particles_zero_forces(p);
    int rc = lattice_compute_forces(m, s, err);
    if (rc)
        return rc;
    memset(g, 0, 4 * sizeof *g);
    for (size_t i = 0; i < p->n; i++)
        if (inner[i] && colour[i] > 0) {
            g[2 * (colour[i] - 1)] += p->f[0][i];
            g[2 * (colour[i] - 1) + 1] += p->f[1][i];
        }
    return SPALL_OK;
}

/** Move sublattices 1 and 2 by d (4 numbers) relative to the current state. */
static void shift(struct particles *p, const int *colour, const double d[4], double sign)
{
    for (size_t i = 0; i < p->n; i++)
        if (colour[i] > 0) {
            p->x[0][i] += sign * d[2 * (colour[i] - 1)];
            p->x[1][i] += sign * d[2 * (colour[i] - 1) + 1];
        }
}

/** Solve the 4x4 system J d = b in place (partial pivoting); 0 if singular. */
static int solve4(double J[4][4], double b[4], double d[4])
{
    for (int c = 0; c < 4; c++) {
        int piv = c;
        for (int r = c + 1; r < 4; r++)
            if (fabs(J[r][c]) > fabs(J[piv][c]))
                piv = r;
        if (!(fabs(J[piv][c]) > 0.0))
            return 0;
        for (int q = 0; q < 4; q++) {
            double t = J[c][q];
            J[c][q] = J[piv][q];
            J[piv][q] = t;
        }
        double t = b[c];
        b[c] = b[piv];
        b[piv] = t;
        for (int r = c + 1; r < 4; r++) {
            double f = J[r][c] / J[c][c];
            for (int q = c; q < 4; q++)
                J[r][q] -= f * J[c][q];
            b[r] -= f * b[c];
        }
    }
    for (int r = 3; r >= 0; r--) {
        double v = b[r];
        for (int q = r + 1; q < 4; q++)
            v -= J[r][q] * d[q];
        d[r] = v / J[r][r];
    }
    return 1;
}

int lattice_honeycomb_relax(struct model *m, struct sim *s, const bool *inner, double h,
                            struct spall_error *err)
{
    struct particles *p = s->p;
    int *colour = malloc((p->n ? p->n : 1) * sizeof *colour);
    if (!colour)
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory in the patch test");
    for (size_t i = 0; i < p->n; i++) {
        const double xi[2] = {p->x0[0][i], p->x0[1][i]};
        colour[i] = lattice_sublattice(&s->lattice, xi);
    }
    int rc = SPALL_OK;
    for (int it = 0; it < 2 && !rc; it++) {
        double g0[4], J[4][4], b[4], d[4] = {0, 0, 0, 0};
        if ((rc = sublattice_force(m, s, inner, colour, g0, err)))
            break;
        for (int q = 0; q < 4; q++) {
            double e[4] = {0, 0, 0, 0}, g[4];
            e[q] = h;
            shift(p, colour, e, 1.0);
            rc = sublattice_force(m, s, inner, colour, g, err);
            shift(p, colour, e, -1.0);
            if (rc)
                break;
            for (int r = 0; r < 4; r++)
                J[r][q] = (g[r] - g0[r]) / h;
        }
        if (rc)
            break;
        for (int r = 0; r < 4; r++)
            b[r] = -g0[r];
        if (!solve4(J, b, d)) {
            rc = spall_error_set(err, SPALL_ERR_INTERNAL,
                                 "patch test: singular sublattice stiffness");
            break;
        }
        shift(p, colour, d, 1.0);
    }
    free(colour);
    return rc;
}
