/**
 * @file pd_calib.c
 * @brief Peridynamic constants: PMB micromodulus and critical stretch
 *        (digest table of [PDLM2019]), the PDLM lattice constants, the virial
 *        stress of a particle, and the orthotropic-lamina calibration by a
 *        patch test through the model's own bond coefficients.
 *
 * Derivations (docs/decks.md, peridynamics section):
 *  - c from equating the PD energy density of a complete family under a
 *    uniform strain to the classical one (Silling & Askari 2005 Eq. 21):
 *    3D c = 18 K / (pi delta^4) (nu = 1/4); plane stress c = 9 E / (pi t
 *    delta^3) (nu = 1/3); plane strain c = 48 E / (5 pi t delta^3) (nu = 1/4);
 *    1D c = 2 E / (A delta^2).
 *  - s0 from the energy of all bonds crossing a unit crack, each holding
 *    w = c s0^2 xi / 2 per V_i V_j (Silling & Askari 2005 Eq. 26-27):
 *    3D  G0 = pi c s0^2 delta^5 / 10       -> s0 = sqrt(5 G0 / (9 K delta));
 *    2D  G0 = c t s0^2 delta^4 / 4         -> plane stress sqrt(4 pi G0 / (9 E delta)),
 *                                             plane strain sqrt(5 pi G0 / (12 E delta));
 *    1D  G0 = A c s0^2 delta^3 / 6         -> s0 = sqrt(3 G0 / (E delta)).
 *  - PDLM (triangular, nearest neighbours, spacing dx): a central spring k on
 *    the triangular lattice gives E t = 2 k / sqrt3 (nu = 1/3); the bond force
 *    c s V^2 = k (l - dx) gives c = k dx / V^2, V = sqrt3/2 dx^2 t.  A crack
 *    along a lattice row cuts 2 bonds per dx: G t = (2/dx) k s0^2 dx^2 / 2,
 *    s0 = sqrt(G t / (k dx)) = sqrt(2 G / (sqrt3 E dx)).
 */
#include "core/fields.h"
#include "models/peridynamics/pd_internal.h"

#include "core/bond_list.h"
#include "core/particles.h"
#include "core/sim.h"
#include "spall/error.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

double pd_micromodulus(int dim, enum pd_plane plane, double E, double K, double delta,
                       double thickness)
{
    switch (dim) {
    case 1: return 2.0 * E / (thickness * delta * delta);
    case 2:
        return plane == PD_PLANE_STRESS ? 9.0 * E / (SPALL_PI * thickness * pow(delta, 3))
                                        : 48.0 * E / (5.0 * SPALL_PI * thickness * pow(delta, 3));
    default: return 18.0 * K / (SPALL_PI * pow(delta, 4));
    }
}

double pd_critical_stretch(int dim, double c, double G0, double delta, double thickness)
{
    if (!(G0 > 0.0))
        return INFINITY;
    switch (dim) {
    case 1: return sqrt(6.0 * G0 / (thickness * c * pow(delta, 3)));
    case 2: return sqrt(4.0 * G0 / (c * thickness * pow(delta, 4)));
    default: return sqrt(10.0 * G0 / (SPALL_PI * c * pow(delta, 5)));
    }
}

/* LPS critical stretch from G0 (ordinary state-based form used with Peridigm's
 * LPS; [MadenciOterkus2014] ch. 6): 3D G0 = (3 mu + (3/4)^4 (k - 5 mu / 3)) s0^2
 * delta, 2D G0 = (6 mu / pi + 16 / (9 pi^2) (k - 2 mu)) s0^2 delta.  At the Cauchy
 * ratio (3D nu = 1/4, plane stress 1/3, plane strain 1/4) the k term vanishes
 * and both equal the PMB values above (checked in tests/test_pd_model.c). */
double pd_lps_critical_stretch(int dim, double kd, double mu, double G0, double delta)
{
    if (!(G0 > 0.0))
        return INFINITY;
    double a = dim == 3 ? 3.0 * mu + pow(0.75, 4) * (kd - 5.0 * mu / 3.0)
                        : 6.0 * mu / SPALL_PI + 16.0 / (9.0 * SPALL_PI * SPALL_PI) * (kd - 2.0 * mu);
    return a > 0.0 ? sqrt(G0 / (a * delta)) : INFINITY;
}

double pd_pdlm_micromodulus(double E, double dx, double thickness)
{
    double k = sqrt(3.0) * E * thickness / 2.0;
    double V = sqrt(3.0) / 2.0 * dx * dx * thickness;
    return k * dx / (V * V);
}

double pd_pdlm_critical_stretch(double E, double G, double dx)
{
    return G > 0.0 ? sqrt(2.0 * G / (sqrt(3.0) * E * dx)) : INFINITY;
}

void pd_particle_eval(const struct model *m, const struct sim *sim, size_t i, double *energy,
                      double *stress)
{
    if (m->opt.lps) {
        pd_lps_particle_eval(m, sim, i, energy, stress);
        return;
    }
    const struct particles *p = sim->p;
    const struct bond_list *bl = m->bl;
    const int dim = sim->dim;
    double e = 0.0, sg[6] = {0, 0, 0, 0, 0, 0};
    for (size_t s = bl->offset[i]; s < bl->offset[i + 1]; s++) {
        if (bl->state[s] & BOND_BROKEN)
            continue;
        size_t j = (size_t)bl->partner[s];
        double r[3] = {0, 0, 0}, r0[3] = {0, 0, 0}, l = 0.0;
        for (int d = 0; d < dim; d++) {
            r[d] = p->x[d][j] - p->x[d][i];
            r0[d] = p->x0[d][j] - p->x0[d][i];
            l += r[d] * r[d];
        }
        l = sqrt(l);
        const double c = pd_coef(m, s);
        double dl = l - pd_rest(m, s);
        e += 0.25 * c * dl * dl; /* half of the bond's energy */
        if (stress) {
            double g = 0.5 * c * dl / l; /* F = g' r, half to this particle */
            pd_add_bond_virial(sg, dim, g, r, r0);
        }
    }
    if (energy)
        *energy = e;
    if (stress) {
        int nc = field_symtensor_ncomp(dim);
        for (int c = 0; c < nc; c++)
            stress[c] = sg[c] / p->volume[i];
    }
}

/* Particle of material k with the most bonds, nearest the centroid of those. */
size_t pd_patch_particle(const struct model *m, const struct sim *sim, int k)
{
    const struct particles *p = sim->p;
    const struct bond_list *bl = m->bl;
    size_t best_len = 0;
    double cx = 0.0, cy = 0.0;
    size_t cnt = 0;
    for (size_t i = 0; i < p->n_owned; i++) {
        size_t len = bl->offset[i + 1] - bl->offset[i];
        if (p->material[i] != k)
            continue;
        if (len > best_len) {
            best_len = len;
            cx = cy = 0.0;
            cnt = 0;
        }
        if (len == best_len) {
            cx += p->x0[0][i];
            cy += p->x0[1][i];
            cnt++;
        }
    }
    cx /= (double)(cnt ? cnt : 1);
    cy /= (double)(cnt ? cnt : 1);
    size_t best = 0;
    double dmin = INFINITY;
    for (size_t i = 0; i < p->n_owned; i++) {
        if (p->material[i] != k || bl->offset[i + 1] - bl->offset[i] != best_len)
            continue;
        double d = hypot(p->x0[0][i] - cx, p->x0[1][i] - cy);
        if (d < dmin) {
            dmin = d;
            best = i;
        }
    }
    return best;
}

/* Material-axes stiffness (Voigt 11, 22, 12 with engineering shear) of
 * particle i: apply each unit strain state (in material axes) as a uniform
 * displacement field, read the virial stress, rotate back. */
void pd_patch_stiffness(struct model *m, struct sim *sim, size_t i, double th, double C[3][3])
{
    struct particles *p = sim->p;
    const double eps = 1e-7, c = cos(th), s = sin(th);
    for (int col = 0; col < 3; col++) {
        double e11 = col == 0 ? eps : 0.0, e22 = col == 1 ? eps : 0.0;
        double e12 = col == 2 ? 0.5 * eps : 0.0; /* tensor shear */
        /* global strain = R e R^T, R = [[c, -s], [s, c]] */
        double gxx = c * c * e11 + s * s * e22 - 2.0 * c * s * e12;
        double gyy = s * s * e11 + c * c * e22 + 2.0 * c * s * e12;
        double gxy = c * s * (e11 - e22) + (c * c - s * s) * e12;
        for (size_t q = 0; q < p->n; q++) {
            double X = p->x0[0][q], Y = p->x0[1][q];
            p->x[0][q] = X + gxx * X + gxy * Y;
            p->x[1][q] = Y + gxy * X + gyy * Y;
        }
        double sg[3];
        pd_particle_eval(m, sim, i, NULL, sg);
        /* material stress = R^T sigma R */
        double s11 = c * c * sg[0] + s * s * sg[1] + 2.0 * c * s * sg[2];
        double s22 = s * s * sg[0] + c * c * sg[1] - 2.0 * c * s * sg[2];
        double s12 = -c * s * sg[0] + c * s * sg[1] + (c * c - s * s) * sg[2];
        C[0][col] = s11 / eps;
        C[1][col] = s22 / eps;
        C[2][col] = s12 / eps;
    }
    for (size_t q = 0; q < p->n; q++) {
        p->x[0][q] = p->x0[0][q];
        p->x[1][q] = p->x0[1][q];
    }
}

int pd_invert3(double A[3][3], double B[3][3])
{
    double det = A[0][0] * (A[1][1] * A[2][2] - A[1][2] * A[2][1]) -
                 A[0][1] * (A[1][0] * A[2][2] - A[1][2] * A[2][0]) +
                 A[0][2] * (A[1][0] * A[2][1] - A[1][1] * A[2][0]);
    if (!(fabs(det) > 0.0))
        return -1;
    B[0][0] = (A[1][1] * A[2][2] - A[1][2] * A[2][1]) / det;
    B[0][1] = (A[0][2] * A[2][1] - A[0][1] * A[2][2]) / det;
    B[0][2] = (A[0][1] * A[1][2] - A[0][2] * A[1][1]) / det;
    B[1][0] = (A[1][2] * A[2][0] - A[1][0] * A[2][2]) / det;
    B[1][1] = (A[0][0] * A[2][2] - A[0][2] * A[2][0]) / det;
    B[1][2] = (A[0][2] * A[1][0] - A[0][0] * A[1][2]) / det;
    B[2][0] = (A[1][0] * A[2][1] - A[1][1] * A[2][0]) / det;
    B[2][1] = (A[0][1] * A[2][0] - A[0][0] * A[2][1]) / det;
    B[2][2] = (A[0][0] * A[1][1] - A[0][1] * A[1][0]) / det;
    return 0;
}

/* Sum of coef xi^2 / 2 over the fiber (want_fiber) or matrix bonds crossing
 * a segment of length L through particle c along direction th (the crack
 * plane), per unit length: the energy per unit crack length at unit s0. */
static double crossing_energy(const struct model *m, const struct sim *sim, size_t c, double th,
                              int want_fiber, double L)
{
    const struct particles *p = sim->p;
    const struct bond_list *bl = m->bl;
    /* crack line through c shifted by a quarter spacing off the sites */
    double tx = cos(th), ty = sin(th), nx = -ty, ny = tx;
    double ox = p->x0[0][c] + 0.25 * m->dx * nx, oy = p->x0[1][c] + 0.25 * m->dx * ny;
    double sum = 0.0;
    for (size_t i = 0; i < p->n_owned; i++) {
        double ai = (p->x0[0][i] - ox) * nx + (p->x0[1][i] - oy) * ny;
        if (ai >= 0.0 || ai < -2.0 * m->delta)
            continue;
        for (size_t s = bl->offset[i]; s < bl->offset[i + 1]; s++) {
            if ((int)(bl->type[s] & 1u) != want_fiber)
                continue;
            size_t j = (size_t)bl->partner[s];
            double aj = (p->x0[0][j] - ox) * nx + (p->x0[1][j] - oy) * ny;
            if (aj <= 0.0)
                continue;
            double t0 = ai / (ai - aj);
            double px = p->x0[0][i] + t0 * (p->x0[0][j] - p->x0[0][i]) - ox;
            double py = p->x0[1][i] + t0 * (p->x0[1][j] - p->x0[1][i]) - oy;
            double along = px * tx + py * ty;
            if (fabs(along) > 0.5 * L)
                continue;
            double xi = bl->rest[s];
            sum += 0.5 * m->coef[s] * xi * xi;
        }
    }
    return sum / L;
}

int pd_calibrate_ortho(struct model *m, struct sim *sim, int k, double achieved[4],
                       struct spall_error *err)
{
    struct pd_material *mt = &m->mat[k];
    size_t i = pd_patch_particle(m, sim, k);
    double A[3][3], B[3][3], C[3][3], S[3][3];
    int rc;
    mt->c_f = 1.0;
    mt->c_m = 0.0;
    if ((rc = pd_build_coefficients(m, sim, err)))
        return rc;
    pd_patch_stiffness(m, sim, i, mt->fiber_angle, A);
    mt->c_f = 0.0;
    mt->c_m = 1.0;
    if ((rc = pd_build_coefficients(m, sim, err)))
        return rc;
    pd_patch_stiffness(m, sim, i, mt->fiber_angle, B);
    /* targets: plane-stress reduced stiffnesses Q11, Q22 ([PDLM2019]: c_f, c_m from
     * the energies of the uniaxial strain states eps11 and eps22) */
    double nu21 = mt->nu12 * mt->E2 / mt->E1, den = 1.0 - mt->nu12 * nu21;
    double Q11 = mt->E1 / den, Q22 = mt->E2 / den;
    double det = A[0][0] * B[1][1] - B[0][0] * A[1][1];
    if (!(fabs(det) > 0.0))
        return spall_error_set(err, SPALL_ERR_PHYSICS,
                               "orthotropic calibration: fiber and matrix bonds give dependent "
                               "stiffnesses (is the family complete?)");
    mt->c_f = (Q11 * B[1][1] - B[0][0] * Q22) / det;
    mt->c_m = (A[0][0] * Q22 - A[1][1] * Q11) / det;
    if (!(mt->c_f > 0.0) || !(mt->c_m > 0.0))
        return spall_error_set(err, SPALL_ERR_PHYSICS,
                               "orthotropic calibration: E1 = %g Pa and E2 = %g Pa need a "
                               "negative bond micromodulus on this lattice (c_f = %g, c_m = %g); "
                               "E1 must exceed about 3 E2", mt->E1, mt->E2, mt->c_f, mt->c_m);
    if ((rc = pd_build_coefficients(m, sim, err)))
        return rc;
    pd_patch_stiffness(m, sim, i, mt->fiber_angle, C);
    if (pd_invert3(C, S))
        return spall_error_set(err, SPALL_ERR_PHYSICS, "orthotropic calibration: singular "
                               "stiffness");
    achieved[0] = 1.0 / S[0][0];
    achieved[1] = 1.0 / S[1][1];
    achieved[2] = 1.0 / S[2][2];
    achieved[3] = -S[0][1] / S[0][0];
    /* critical stretches: Silling-Askari energy of the bonds crossing a unit
     * crack (thickness t): along the fibers only matrix bonds cross and
     * must absorb G_Ic; across the fibers the fiber bonds absorb G_f. */
    double L = 2.0 * m->delta + 2.0 * m->dx;
    double em = crossing_energy(m, sim, i, mt->fiber_angle, 0, L);
    double ef = crossing_energy(m, sim, i, mt->fiber_angle + 0.5 * SPALL_PI, 1, L);
    double t = sim->thickness;
    mt->s0_m = (mt->GIc > 0.0 && em > 0.0) ? sqrt(mt->GIc * t / em) : INFINITY;
    mt->s0_f = (mt->Gf > 0.0 && ef > 0.0) ? sqrt(mt->Gf * t / ef) : INFINITY;
    return SPALL_OK;
}
