/**
 * @file lattice_calib.c
 * @brief Spring constants of the HLPM lattices and the numerical patch test.
 *
 * Derivations (uniform strain eps, Cauchy-Born; every lattice here is a Bravais
 * lattice so there is no internal relaxation).  A bond of stiffness k, rest
 * length l and direction n stores k l^2 (n.eps.n)^2 / 2; summing over the
 * bonds of one site and dividing by the site volume gives the strain-energy
 * density, whose second derivatives are the elastic constants.
 *
 * Triangular lattice, spacing r0, plate thickness t, site area sqrt3/2 r0^2:
 *   three bond directions 60 deg apart, sum n_i n_j n_k n_l = 3/8 (dd+dd+dd), so
 *   lambda2 = mu2 = sqrt3 k / 4 (2D moduli per unit thickness times t), i.e.
 *   K2 = sqrt3 k / 2 and nu = 1/3 (the Cauchy value).
 *   Angular springs (energy k_phi dphi^2 / 2 on each of the 6 angles between
 *   adjacent bonds) only stiffen shear: a pure shear eps_xx = -eps_yy = e
 *   turns bond theta by -e sin(2 theta), the angle (theta, theta+60) by
 *   -sqrt3 e cos(2 theta + 60), and the 6 angles store 9/2 k_phi e^2, so
 *   mu2 = sqrt3 k / 4 + (3 sqrt3 / 2) k_phi / r0^2.
 *   Matching plane-stress E t = 2 K2 (1 - nu) and mu2 = E t / (2 (1 + nu)):
 *     k     = E t / (sqrt3 (1 - nu))
 *     k_phi = r0^2 E t (1 - 3 nu) / (6 sqrt3 (1 - nu^2))
 *   With the paper's t = 2 r0 / sqrt3 the first is [Wang2010] Eq. 16,
 *   S0 = 2 E r0 / (3 (1 - nu)); the second is E r0^3 (1 - 3nu) / (9 (1 - nu^2)),
 *   while Eq. 18 read as a moment per radian (k_phi = S_phi r0) gives
 *   sqrt3/18 instead of 1/9: a factor sqrt3/2 too small (the patch test shows
 *   the resulting E and nu; see lattice_paper_k_phi).
 *   Two layers: the second shell (6 bonds at sqrt3 r0) stores 3 times as much
 *   per unit k, so k1 + 3 k2 = sqrt3 E t / 2 and nu stays 1/3.  Default
 *   k2/k1 = 1/sqrt3: the same bar modulus k l for both shells.
 *   Area springs for nu > 1/3 (spall's own construction on the triangular
 *   lattice, kept as a Bravais alternative to the paper's alpha-beta-gamma
 *   triple honeycomb, which is the lattice kind triple_honeycomb,
 *   lattice_honeycomb.c):
 *   every lattice triangle (3 first-shell bonds, rest area A0 = sqrt3 r0^2/4)
 *   stores k_area (A/A0 - 1)^2 / 2.  Under uniform strain A/A0 - 1 = tr eps
 *   to first order, so it adds bulk only: 2 triangles per site of area
 *   sqrt3 r0^2 / 2 give d lambda2 = 4 k_area / (sqrt3 r0^2), mu unchanged:
 *     K2 = sqrt3 k / 2 + 4 k_area / (sqrt3 r0^2),  mu2 = sqrt3 k / 4.
 *   Matching mu2 = E t / (2 (1 + nu)) and K2 = E t / (2 (1 - nu)):
 *     k      = 2 E t / (sqrt3 (1 + nu))
 *     k_area = sqrt3 r0^2 E t (3 nu - 1) / (8 (1 - nu^2))  (>= 0 for nu >= 1/3)
 *   The triangle energy is split in three equal shares, one on each of its
 *   vertex angles (the angle structure below), so each share sees only its
 *   two arms: a share is off once either arm bond is broken.  Stable step:
 *   a share (k_s = k_area/3) has |grad A| = |opposite edge|/2, bounded by
 *   (r_a + r_b)/2 at the centre and r_b/2, r_a/2 at the arms; booking half
 *   of the Gershgorin row as for the angles gives a bulk site
 *   12 k_s r0^2 / A0^2 = 64 k_area / (3 r0^2).
 * Square lattice with diagonals (spacing a, site area a^2): axis springs k1,
 *   diagonals k2:  C11 = (k1 + k2)/t, C12 = C66 = k2/t.  Isotropy
 *   (C66 = (C11 - C12)/2) needs k1 = 2 k2; then nu = 1/3, E t = 8 k2 / 3:
 *   k2 = 3 E t / 8, k1 = 3 E t / 4.  Without diagonals C12 = C66 = 0: no
 *   shear stiffness, so one layer is refused.
 * Simple cubic (spacing a): nearest k1, face diagonals k2:
 *   C11 = (k1 + 2 k2)/a, C12 = C44 = k2/a; isotropy needs k1 = k2 = k, then
 *   nu = 1/4 and E = 5 k / (2 a): k = 2 E a / 5.
 * FCC (nearest distance r0, cube edge a = sqrt2 r0, 4 sites per a^3):
 *   C11 = 2k/a, C12 = C44 = k/a, Zener ratio 2 (anisotropic).  Voigt average:
 *   K = 4k/(3a), G_V = 4k/(5a), E_V = 2k/a, nu_V = 1/4, so k = E a / 2 =
 *   E r0 / sqrt2.  Along [100]: E_100 = 4k/(3a) = (2/3) E_V, nu_100 = 1/3.
 * Chain (area A): k = E A / r0.
 *
 * Stable time step ([Wang2010] Eq. 25, Omega dt < 2 applied to the highest
 * mode): Gershgorin on M^-1 H gives omega_max^2 <= max_i (row sum)/m_i, and
 * for a spring the off-diagonal block equals the diagonal one, so
 * omega_max^2 <= 2 Omega_i^2 with Omega_i^2 = sum_b |dF/dr|_b / m_i; hence
 * dt = sqrt2 / max Omega_i (exact for a uniform chain, omega = 2 sqrt(k/m)).
 * An angle (arms a, b) has |grad phi| = 1/r_a, 1/r_b at the arms and at most
 * 1/r_a + 1/r_b at the centre; its Hessian k_phi g g^T adds to particle x's
 * row at most k_phi |g_x| 2 (1/r_a + 1/r_b), of which we book half (the same
 * convention): (1/r_a + 1/r_b)^2 k_phi at the centre and
 * k_phi (1/r_a+1/r_b)/r_arm at each arm; a bulk site gets 48 k_phi / r0^2.
 */
#include "core/fields.h"
#include "models/lattice/lattice_calib.h"

#include "core/bond_list.h"
#include "core/geometry.h"
#include "core/lattice_gen.h"
#include "core/particles.h"
#include "core/sim.h"
#include "models/lattice/lattice_honeycomb.h"
#include "models/lattice/lattice_internal.h"
#include "core/model.h"
#include "spall/error.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

extern const struct model_ops lattice_model_ops;

static const double SQRT3 = 1.7320508075688772;
static const double SQRT2 = 1.4142135623730951;

double lattice_paper_k(double E, double nu, double r0, double t)
{
    double t_paper = 2.0 * r0 / SQRT3;
    return 2.0 * E * r0 / (3.0 * (1.0 - nu)) * (t / t_paper);
}

double lattice_paper_k_phi(double E, double nu, double r0, double t)
{
    double t_paper = 2.0 * r0 / SQRT3;
    double s_phi = SQRT3 * (1.0 - 3.0 * nu) * E * r0 * r0 / (18.0 * (1.0 - nu * nu));
    return s_phi * r0 * (t / t_paper);
}

static int refuse(struct spall_error *err, const char *fmt, const char *a)
{
    return spall_error_set(err, SPALL_ERR_PHYSICS, fmt, a);
}

int lattice_calibrate(struct lattice_calib *c, struct spall_error *err)
{
    const char *kn = lattice_kind_name(c->kind);
    if (!(c->E > 0.0) || !isfinite(c->E))
        return spall_error_set(err, SPALL_ERR_INPUT, "Young's modulus must be positive (got %g Pa)",
                               c->E);
    if (!(c->r0 > 0.0))
        return spall_error_set(err, SPALL_ERR_INPUT, "lattice spacing must be positive (got %g m)",
                               c->r0);
    int dim = lattice_kind_dim(c->kind);
    if (dim < 3 && !(c->thickness > 0.0))
        return spall_error_set(err, SPALL_ERR_INPUT,
                               "%s lattice needs a positive %s (got %g)", kn,
                               dim == 1 ? "cross-section area" : "thickness", c->thickness);
    const double E = c->E, r0 = c->r0, t = c->thickness;
    double nu = c->nu;
    int layers = c->layers;
    c->k1 = c->k2 = c->k_phi = c->k_area = 0.0;
    c->k_family[0] = c->k_family[1] = c->k_family[2] = 0.0;
    c->angular_used = c->area_used = c->honeycomb_used = 0;
    if (c->angular == 1 && c->kind != LATTICE_TRIANGULAR)
        return refuse(err, "angular springs are implemented for the triangular lattice only "
                           "(lattice '%s')", kn);
    if (c->second_layer_ratio != 0.0 &&
        (c->kind != LATTICE_TRIANGULAR || (layers != 2)))
        return refuse(err, "second_layer_ratio applies to a two-layer triangular lattice only "
                           "(lattice '%s'; square and sc ratios are fixed by isotropy)", kn);
    switch (c->kind) {
    case LATTICE_CHAIN:
        if (layers == 2)
            return refuse(err, "the %s lattice has one neighbour layer", kn);
        layers = 1;
        c->k1 = E * t / r0;
        break;
    case LATTICE_TRIANGULAR: {
        if (!(nu > -1.0))
            return spall_error_set(err, SPALL_ERR_PHYSICS,
                                   "Poisson's ratio %g is below -1 (not a stable solid)", nu);
        if (nu > 1.0 / 3.0 + LATTICE_NU_TOL) {
            /* area springs: central springs fix mu2 = sqrt3 k / 4, area
             * springs add bulk only (derivation at the top of this file) */
            if (!(nu < 1.0))
                return spall_error_set(err, SPALL_ERR_PHYSICS,
                                       "Poisson's ratio %g >= 1 is not a stable 2D solid", nu);
            if (layers == 2)
                return spall_error_set(err, SPALL_ERR_PHYSICS,
                                       "Poisson's ratio %g > 1/3 needs area springs (or the "
                                       "triple_honeycomb lattice), calibrated for layers: 1 "
                                       "only", nu);
            if (c->angular == 0)
                return spall_error_set(err, SPALL_ERR_PHYSICS,
                                       "Poisson's ratio %g > 1/3 on the triangular lattice needs "
                                       "area springs (angular: auto or on), or use the lattice "
                                       "triple_honeycomb (alpha-beta-gamma)", nu);
            layers = 1;
            c->k1 = 2.0 * E * t / (SQRT3 * (1.0 + nu));
            c->k_area = SQRT3 * r0 * r0 * E * t * (3.0 * nu - 1.0) / (8.0 * (1.0 - nu * nu));
            c->angular_used = 1;
            c->area_used = 1;
            break;
        }
        if (layers == 0)
            layers = 1;
        int cauchy = fabs(nu - 1.0 / 3.0) <= LATTICE_NU_TOL;
        if (layers == 2) {
            if (c->angular == 1)
                return refuse(err, "angular springs with two axial layers are not calibrated "
                                   "(lattice '%s'); use layers: 1", kn);
            if (!cauchy)
                return spall_error_set(err, SPALL_ERR_PHYSICS,
                                       "Poisson's ratio %g: a central-force triangular lattice "
                                       "has nu = 1/3; use angular springs (layers: 1)", nu);
            double ratio = c->second_layer_ratio > 0.0 ? c->second_layer_ratio : 1.0 / SQRT3;
            double kreq = SQRT3 * E * t / 2.0;
            c->k1 = kreq / (1.0 + 3.0 * ratio);
            c->k2 = ratio * c->k1;
            break;
        }
        int ang = c->angular == -1 ? !cauchy : c->angular;
        if (!ang && !cauchy)
            return spall_error_set(err, SPALL_ERR_PHYSICS,
                                   "Poisson's ratio %g: a central-force triangular lattice has "
                                   "nu = 1/3; use angular springs", nu);
        if (cauchy)
            nu = 1.0 / 3.0; /* within tolerance: the lattice's own value, k_phi = 0 */
        c->k1 = E * t / (SQRT3 * (1.0 - nu));
        c->k_phi = ang ? r0 * r0 * E * t * (1.0 - 3.0 * nu) / (6.0 * SQRT3 * (1.0 - nu * nu))
                       : 0.0;
        c->angular_used = ang;
        break;
    }
    case LATTICE_TRIPLE_HONEYCOMB: {
        /* alpha-beta-gamma ([Wang2010] Fig. 3d): central springs in three
         * honeycomb families, nu in [1/3, 1) (lattice_honeycomb.c) */
        if (layers == 2)
            return refuse(err, "the %s lattice has nearest-neighbour springs only (its three "
                               "honeycomb families); use layers: 1", kn);
        layers = 1;
        int rc = lattice_honeycomb_constants(E, nu, t, c->k_family, err);
        if (rc)
            return rc;
        c->k1 = c->k_family[1]; /* the stiffest: 6 of them at a site set dt */
        c->honeycomb_used = 1;
        break;
    }
    case LATTICE_SQUARE:
    case LATTICE_SC: {
        double cauchy_nu = c->kind == LATTICE_SQUARE ? 1.0 / 3.0 : 0.25;
        if (layers == 1)
            return refuse(err, "a %s lattice with nearest-neighbour springs only has no shear "
                               "stiffness; use layers: 2 (diagonals)", kn);
        layers = 2;
        if (fabs(nu - cauchy_nu) > LATTICE_NU_TOL)
            return spall_error_set(err, SPALL_ERR_PHYSICS,
                                   "Poisson's ratio %g: the isotropic central-force %s lattice "
                                   "has nu = %s", nu, kn, c->kind == LATTICE_SQUARE ? "1/3" : "1/4");
        if (c->kind == LATTICE_SQUARE) {
            c->k1 = 0.75 * E * t;
            c->k2 = 0.375 * E * t;
        } else {
            c->k1 = c->k2 = 0.4 * E * r0;
        }
        break;
    }
    case LATTICE_FCC:
        if (layers == 2)
            return refuse(err, "the %s lattice is calibrated with nearest-neighbour springs "
                               "only; use layers: 1", kn);
        layers = 1;
        if (fabs(nu - 0.25) > LATTICE_NU_TOL)
            return spall_error_set(err, SPALL_ERR_PHYSICS,
                                   "Poisson's ratio %g: a central-force fcc lattice has "
                                   "nu = 1/4 (Voigt average)", nu);
        c->k1 = E * r0 / SQRT2;
        break;
    default:
        return spall_error_set(err, SPALL_ERR_INPUT, "unknown lattice kind %d", (int)c->kind);
    }
    c->layers_used = layers;
    if (c->sigma_ts > 0.0)
        c->eps_max = c->sigma_ts / E; /* [Wang2010] Eq. 26 */

    struct lattice_spec spec;
    memset(&spec, 0, sizeof spec);
    spec.kind = c->kind;
    spec.spacing = r0;
    c->site_volume = lattice_site_volume(&spec, t);
    c->mass = c->rho > 0.0 ? c->rho * c->site_volume : 0.0;
    double stiff = lattice_shell_count(c->kind, 1) * c->k1;
    if (layers == 2)
        stiff += lattice_shell_count(c->kind, 2) * c->k2;
    stiff += 48.0 * c->k_phi / (r0 * r0);
    stiff += 64.0 * c->k_area / (3.0 * r0 * r0);
    c->dt = c->mass > 0.0 ? SQRT2 / sqrt(stiff / c->mass) : 0.0;
    c->paper_S0 = 2.0 * E * r0 / (3.0 * (1.0 - c->nu));
    c->paper_S_phi = SQRT3 * (1.0 - 3.0 * c->nu) * E * r0 * r0 / (18.0 * (1.0 - c->nu * c->nu));
    return SPALL_OK;
}

/* ---- patch test ------------------------------------------------------------ */

/** Average stress of the interior particles for the affine map
 *  x = x0 + eps x0 (eps given by its components). */
static int patch_state(struct model *m, struct sim *s, double eps[3][3], const bool *inner,
                       int relax, double *avg, double *f_max, struct spall_error *err)
{
    struct particles *p = s->p;
    int dim = p->dim;
    for (size_t i = 0; i < p->n; i++)
        for (int d = 0; d < dim; d++) {
            double v = p->x0[d][i];
            for (int e = 0; e < dim; e++)
                v += eps[d][e] * p->x0[e][i];
            p->x[d][i] = v;
        }
    int rc;
    if (relax && m->honeycomb && (rc = lattice_honeycomb_relax(m, s, inner, 1e-6 * s->lattice.spacing,
                                                      err)))
        return rc;
    particles_zero_forces(p);
    if ((rc = lattice_compute_forces(m, s, err)))
        return rc;
    int nc = field_symtensor_ncomp(dim);
    /* mean per sublattice, then over the sublattices (the triple honeycomb's
     * sites differ by colour and the block holds unequal numbers of each) */
    double sum[3][6];
    size_t cnt[3] = {0, 0, 0};
    memset(sum, 0, sizeof sum);
    *f_max = 0.0;
    for (size_t i = 0; i < p->n; i++) {
        if (!inner[i])
            continue;
        double sig[6];
        lattice_particle_eval(m, s, i, NULL, sig);
        int g = 0;
        if (m->honeycomb) {
            const double xi[2] = {p->x0[0][i], p->x0[1][i]};
            g = lattice_sublattice(&s->lattice, xi);
        }
        for (int c = 0; c < nc; c++)
            sum[g][c] += sig[c];
        for (int d = 0; d < dim; d++)
            *f_max = fmax(*f_max, fabs(p->f[d][i]));
        cnt[g]++;
    }
    int ng = 0;
    for (int c = 0; c < nc; c++)
        avg[c] = 0.0;
    for (int g = 0; g < 3; g++) {
        if (!cnt[g])
            continue;
        ng++;
        for (int c = 0; c < nc; c++)
            avg[c] += sum[g][c] / (double)cnt[g];
    }
    for (int c = 0; c < nc; c++)
        avg[c] /= (double)ng;
    return SPALL_OK;
}

int lattice_patch_test_full(const struct lattice_calib *cin, double strain,
                            int use_paper_constants, struct lattice_patch_result *res,
                            struct spall_error *err)
{
    memset(res, 0, sizeof *res);
    struct lattice_calib c = *cin;
    int rc = lattice_calibrate(&c, err);
    if (rc)
        return rc;
    if (use_paper_constants && c.kind != LATTICE_TRIANGULAR)
        return spall_error_set(err, SPALL_ERR_INPUT,
                               "the paper's constants ([Wang2010] Eqs. 16, 18) are for the "
                               "triangular lattice");
    const int dim = lattice_kind_dim(c.kind);
    struct sim s;
    memset(&s, 0, sizeof s);
    struct material mat;
    memset(&mat, 0, sizeof mat);
    strcpy(mat.name, "patch");
    mat.density = c.rho > 0.0 ? c.rho : 1000.0;
    s.dim = dim;
    s.materials = &mat;
    s.n_materials = 1;
    s.lattice.kind = c.kind;
    s.lattice.spacing = c.r0;
    s.thickness = c.thickness;
    s.thickness_given = true;
    struct model *m = NULL;
    struct geom *box = NULL;
    bool *inner = NULL;
    rc = particles_create(&s.p, dim, 0, err);
    if (rc)
        return rc;
    /* block of ~14 r0 (2D), 20 r0 (1D), 10 r0 (3D); interior = farther than
     * 2.6 r0 (beyond the second shell) from every face */
    double L = dim == 1 ? 20.0 : dim == 2 ? 14.0 : 10.0;
    double lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
    for (int d = 0; d < dim; d++)
        hi[d] = L * c.r0 * (1.0 + 1e-9);
    box = geom_box(lo, hi);
    if (!box) {
        rc = spall_error_set(err, SPALL_ERR_NOMEM, "out of memory in the patch test");
        goto done;
    }
    size_t added = 0;
    rc = lattice_fill(s.p, &s.lattice, box, 0, &added, err);
    if (rc)
        goto done;
    s.p->n_owned = s.p->n;
    double vol = lattice_site_volume(&s.lattice, s.thickness);
    inner = calloc(s.p->n, sizeof *inner);
    if (!inner) {
        rc = spall_error_set(err, SPALL_ERR_NOMEM, "out of memory in the patch test");
        goto done;
    }
    double margin = 2.6 * c.r0;
    for (size_t i = 0; i < s.p->n; i++) {
        s.p->volume[i] = vol;
        s.p->mass[i] = mat.density * vol;
        bool in = true;
        for (int d = 0; d < dim; d++)
            in = in && s.p->x0[d][i] > lo[d] + margin && s.p->x0[d][i] < hi[d] - margin;
        inner[i] = in;
        res->n_interior += in;
    }
    res->n_particles = s.p->n;
    if (res->n_interior == 0) {
        rc = spall_error_set(err, SPALL_ERR_INTERNAL, "patch test: no interior particle");
        goto done;
    }
    struct lattice_options opt = {LATTICE_LAW_LINEAR, c.layers_used, c.angular,
                                  c.second_layer_ratio};
    rc = lattice_model_new(&m, &s, &opt, err);
    if (rc)
        goto done;
    struct lattice_material mt;
    memset(&mt, 0, sizeof mt);
    mt.E = c.E;
    mt.nu = c.nu;
    mt.nu_given = true;
    mt.eps_t = INFINITY;
    mt.eps_c = INFINITY;
    mt.dphi_c = mt.dphi_t = INFINITY;
    if ((rc = lattice_model_set_material(m, 0, &mt, err)))
        goto done;
    if ((rc = lattice_model_ops.init(m, &s, err)))
        goto done;
    if (use_paper_constants)
        lattice_model_override(m, lattice_paper_k(c.E, c.nu, c.r0, c.thickness),
                               c.angular_used ? lattice_paper_k_phi(c.E, c.nu, c.r0, c.thickness)
                                              : 0.0);
    double e1[3][3] = {{0}}, e2[3][3] = {{0}}, s1[6], s2[6], f1, f2;
    e1[0][0] = strain;
    if (dim > 1) {
        e2[0][1] = strain; /* tensor shear eps_xy = strain */
        e2[1][0] = strain;
    }
    if ((rc = patch_state(m, &s, e1, inner, 1, s1, &f1, err)))
        goto done;
    res->C11 = s1[0] / strain;
    if (dim == 1) {
        res->E = res->E_100 = res->C11;
        res->f_interior_max = f1 / (c.k1 * c.r0 * strain);
        goto done;
    }
    if ((rc = patch_state(m, &s, e2, inner, 1, s2, &f2, err)))
        goto done;
    res->C12 = s1[1] / strain;
    res->C66 = s2[dim == 2 ? 2 : 3] / (2.0 * strain);
    res->f_interior_max = fmax(f1, f2) / (c.k1 * c.r0 * strain);
    if (dim == 2) {
        res->E = (res->C11 * res->C11 - res->C12 * res->C12) / res->C11; /* plane stress */
        res->nu = res->C12 / res->C11;
        res->E_100 = res->E;
        res->nu_100 = res->nu;
        res->E_affine = res->E;
        res->nu_affine = res->nu;
        if (m->honeycomb) { /* the same block without the sublattice shifts */
            double a1[6], fa;
            if ((rc = patch_state(m, &s, e1, inner, 0, a1, &fa, err)))
                goto done;
            double C11 = a1[0] / strain, C12 = a1[1] / strain;
            res->E_affine = (C11 * C11 - C12 * C12) / C11;
            res->nu_affine = C12 / C11;
        }
    } else {
        double C11 = res->C11, C12 = res->C12, C44 = res->C66;
        res->E_100 = (C11 - C12) * (C11 + 2.0 * C12) / (C11 + C12);
        res->nu_100 = C12 / (C11 + C12);
        double K = (C11 + 2.0 * C12) / 3.0, G = (C11 - C12 + 3.0 * C44) / 5.0;
        res->E = 9.0 * K * G / (3.0 * K + G);
        res->nu = (3.0 * K - 2.0 * G) / (2.0 * (3.0 * K + G));
    }
done:
    if (m)
        lattice_model_ops.destroy(&m);
    free(inner);
    geom_destroy(&box);
    particles_destroy(&s.p);
    return rc;
}

int lattice_patch_test(const struct lattice_calib *c, double strain, int use_paper_constants,
                       double *E_meas, double *nu_meas, struct spall_error *err)
{
    struct lattice_patch_result r;
    int rc = lattice_patch_test_full(c, strain, use_paper_constants, &r, err);
    if (rc)
        return rc;
    if (E_meas)
        *E_meas = r.E;
    if (nu_meas)
        *nu_meas = r.nu;
    return SPALL_OK;
}
