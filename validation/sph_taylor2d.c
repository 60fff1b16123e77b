/**
 * @file sph_taylor2d.c
 * @brief SPH validation case "sph-taylor-2d": the iron rod of seed 004
 *        sec. 3.4.2 (Table 3.5, after Libersky & Petschek 1991) on a rigid
 *        wall, elastic-perfectly plastic with the Mie-Grueneisen EOS.
 *
 * Material (Table 3.5): E = 208 GPa, G = 80 GPa (nu = 0.3), sigma_y =
 * 600 MPa, Mie-Grueneisen C = 3630 m/s, S = 1.80, Gamma = 1.80; density
 * 7850 kg/m^3 (iron; the table gives none).
 * Geometry and speed: Libersky & Petschek (1991) and Libersky et al. (1993)
 * could not be retrieved here, and the thesis gives neither (its 2050
 * particles at dx = 1.058 mm would make a rod of 2295 mm^2, inconsistent
 * with any Taylor specimen).  Chosen: the classic Armco-iron Taylor
 * specimen of Wilkins & Guinan (1973), L0 = 25.4 mm, D0 = 7.62 mm, 221 m/s,
 * which, as far as I recall, is the test SPH papers of that period
 * reproduce -- not verified against the paper.
 * Form: plane strain (the seed's "2D"), half model with a mirror plane at
 * x = 0 (sph_symmetry.c).  SPH_TAYLOR2D_FORM is the single place to switch
 * to the axisymmetric form once it is merged (pen-sph branch).
 * Wendland, h = 1.5 dx (thesis), AV (1, 1), XSPH 0.1, 80 us (the thesis
 * stops at 50 us; the rod is still moving then, so both are reported).
 *
 * No reference final length exists for this set-up (the thesis compares
 * shapes with EPIC-2 in a figure only), so the checks are: (1) the length
 * is converged in dx (two finest spacings within 1 %); (2) Taylor's (1948)
 * one-dimensional estimate of the yield stress from the measured final
 * length L and undeformed length X, sigma_T = rho v^2 (L0 - X) /
 * (2 (L0 - L) ln(L0 / X)), against the plane-strain flow stress
 * 2 sigma_y / sqrt(3) (uniaxial compression with no out-of-plane strain),
 * within 25 % (Taylor's theory ignores elasticity and the mushroom; its
 * estimates scatter by ~10-20 % in the literature).
 */
#include "validation/lattice_cases.h"
#include "validation/sph_cases.h"
#include "validation/validation.h"

#include "core/particles.h"
#include "core/sim.h"
#include "models/model.h"
#include "models/sph/sph_internal.h"
#include "spall/error.h"

#include <math.h>
#include <omp.h>
#include <stdio.h>

/** The model keys that select the 2D form: plane strain with a mirror
 *  plane at x = 0.  Axisymmetric: replace by the axisymmetric key of the
 *  pen-sph branch once merged (the rod's axis is x = 0 in both). */
#define SPH_TAYLOR2D_FORM "plane: strain, symmetry: x"

#define T2D_L0 25.4e-3
#define T2D_D0 7.62e-3
#define T2D_V0 221.0
#define T2D_RHO 7850.0
#define T2D_SY 600.0e6

int sph_taylor2d_run(int n, double t1, double t2, struct sph_taylor2d_result *out,
                     struct spall_error *err)
{
    const double dx = T2D_D0 / n;
    char deck[3072];
    snprintf(deck, sizeof deck,
             "model: {type: sph, kernel: wendland, h_factor: 1.5, viscosity: [1.0, 1.0],\n"
             "        xsph: 0.1, %s, wall: {point: [0, 0], normal: [0, 1]}}\n"
             "materials:\n"
             "  iron: {density: %.17g, youngs_modulus: 208.0e9, poisson_ratio: 0.3,\n"
             "         eos: mie_gruneisen, sound_speed: 3630, hugoniot_slope: 1.80,\n"
             "         gruneisen: 1.80, yield: perfect, yield_stress: %.17g}\n"
             "lattice: {type: square, spacing: %.17g, origin: [%.17g, %.17g]}\n"
             "body: {geometry: {box: {min: [0, 0], max: [%.17g, %.17g]}}, material: iron}\n"
             "initial_velocity: [{group: all, value: [0, %.17g]}]\n"
             "run: {end_time: %.17g, dt_factor: 0.3}\n",
             SPH_TAYLOR2D_FORM, T2D_RHO, T2D_SY, dx, 0.5 * dx, 0.5 * dx, 0.5 * T2D_D0, T2D_L0,
             -T2D_V0, t2);
    struct sim *s = NULL;
    int rc = vlat_build("sph_taylor2d", deck, &s, err);
    if (rc)
        return rc;
    const struct particles *p = s->p;
    const struct model *m = s->model;
    double t0 = omp_get_wtime();
    int stage = 0;
    while (!rc && stage < 2) {
        if (sim_done(s) || s->t >= (stage == 0 ? t1 : t2) * (1.0 - 1e-12)) {
            /* length = extent along the axis (the rod rebounds and flies off) */
            double ymax = -INFINITY, ymin = INFINITY, rmax = 0.0, ylow = INFINITY;
            for (size_t i = 0; i < p->n; i++) {
                ymax = fmax(ymax, p->x[1][i]);
                ymin = fmin(ymin, p->x[1][i]);
            }
            for (size_t i = 0; i < p->n; i++) {
                if (p->x0[1][i] < 1.5 * dx)
                    rmax = fmax(rmax, p->x[0][i]);
                /* the undeformed part: particles of the axis column that
                 * stayed below 0.2 % plastic strain (the engineering offset
                 * yield); X runs from the lowest one to the end */
                if (p->x0[0][i] < dx && m->ep[i] < 2e-3)
                    ylow = fmin(ylow, p->x[1][i]);
            }
            out->len[stage] = ymax - ymin + dx;
            out->rad[stage] = rmax + 0.5 * dx;
            out->undeformed[stage] = ymax - ylow + dx;
            stage++;
            if (sim_done(s))
                break;
            continue;
        }
        rc = sim_step(s, err);
    }
    double vy = 0.0, mt = 0.0;
    for (size_t i = 0; i < p->n; i++) {
        vy += p->mass[i] * p->v[1][i];
        mt += p->mass[i];
    }
    out->v_end = vy / mt;
    out->particles = p->n;
    out->seconds = omp_get_wtime() - t0;
    sim_destroy(&s);
    return rc;
}

/* Taylor (1948): sigma = rho v^2 (L0 - X) / (2 (L0 - L) ln(L0 / X)). */
static double taylor_stress(double L, double X)
{
    return T2D_RHO * T2D_V0 * T2D_V0 * (T2D_L0 - X) / (2.0 * (T2D_L0 - L) * log(T2D_L0 / X));
}

int sph_case_taylor2d(struct vreport *r, struct spall_error *err)
{
    static const int series[3] = {16, 32, 48};
    const int last = r->quick ? 0 : 2;
    struct sph_taylor2d_result res[3];
    for (int k = 0; k <= last; k++) {
        int rc = sph_taylor2d_run(series[k], 50e-6, 80e-6, &res[k], err);
        if (rc)
            return rc;
        vreport_info(r, "2D Taylor rod, %d across (%zu particles in the half model, dx = %.4g "
                     "mm): L = %.3f / %.3f mm, R = %.3f / %.3f mm at 50 / 80 us, undeformed "
                     "X = %.2f mm, mean v at 80 us %.2f m/s (%.0f s)",
                     series[k], res[k].particles, T2D_D0 / series[k] * 1e3, res[k].len[0] * 1e3,
                     res[k].len[1] * 1e3, res[k].rad[0] * 1e3, res[k].rad[1] * 1e3,
                     res[k].undeformed[1] * 1e3, res[k].v_end, res[k].seconds);
    }
    const struct sph_taylor2d_result *f = &res[last];
    int rc;
    if (last > 0) {
        double change = fabs(f->len[1] - res[last - 1].len[1]) / f->len[1];
        if ((rc = vreport_check(r, "final length change, two finest dx", "1", 0.0, change, 0.01,
                                false, "convergence (no published length for this set-up)",
                                "1 %: the 3D case's target accuracy", err)))
            return rc;
        if (!r->checks[r->n - 1].pass)
            vreport_mark_gap(r, "GAP: the length still falls ~1.6 % per refinement (n = 32 -> "
                                "48); see docs/validation.md");
    }
    double sT = taylor_stress(f->len[1], f->undeformed[1]);
    if ((rc = vreport_check(r, "Taylor (1948) flow stress from L and X", "Pa",
                            2.0 * T2D_SY / sqrt(3.0), sT, 0.25, true,
                            "plane-strain flow stress 2 sigma_y / sqrt 3, sigma_y 600 MPa "
                            "(seed 004 Table 3.5)",
                            "25 %: 1D rigid-plastic theory, no elasticity, no mushroom", err)))
        return rc;
    return SPALL_OK;
}
