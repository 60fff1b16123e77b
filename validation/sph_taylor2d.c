/**
 * @file sph_taylor2d.c
 * @brief SPH validation case "sph-taylor-2d": the iron rod of [Meng2021]
 *        sec. 3.4.2 (Table 3.5, after Libersky & Petschek 1991) on a rigid
 *        wall, elastic-perfectly plastic with the Mie-Grueneisen EOS.
 *
 * Material (Table 3.5): E = 208 GPa, G = 80 GPa (nu = 0.3), sigma_y =
 * 600 MPa, Mie-Grueneisen C = 3630 m/s, S = 1.80, Gamma = 1.80; density
 * 7850 kg/m^3 (iron; the table gives none).
 * Geometry and speed: Libersky & Petschek (1991) and Libersky et al. (1993)
 * could not be retrieved here, and the thesis gives neither (its 2050
 * particles at dx = 1.058 mm would make a rod of 2295 mm^2, inconsistent
 * with any Taylor specimen).  Chosen: the Armco-iron Taylor specimen of
 * Wilkins & Guinan (1973), L0 = 25.4 mm, D0 = 7.62 mm, 221 m/s (from
 * memory, not verified).  Corroboration found: PySPH's Taylor-bar example
 * (pypr/pysph, pysph/examples/solid_mech/taylor_bar.py) uses exactly the
 * Table 3.5 iron constants with a 25.4 mm x 7.6 mm bar, at 200 m/s.
 *
 * Form: axisymmetric (x = r, the axis x = 0; sph_axisym.c) -- a cylinder is
 * axisymmetric; the seed's "2D" plane-strain rod is an infinite slab and is
 * run once (n = 32) for comparison.  Both use the model's penalty wall
 * (k per particle mass, fixed in time).  Wendland, h = 1.5 dx (thesis),
 * AV (1, 1), XSPH 0.1, sampled at 50 us (the thesis' end time) and 80 us.
 *
 * No published final length / radius was found for this set-up (the thesis
 * compares shapes with EPIC-2 in a figure only).  The independent reference
 * is a converged finite-element run of the same rod (CalculiX,
 * validation/fe/taylor_iron/README.md): L = 19.67 mm and the outer radius
 * 6.99 mm 0.5 mm above the face; the full case checks the n = 48 length
 * and that radius against it within 2 % (the 3D-bar tolerance) for
 * the thesis AV and for Balsara's switch.  The other checks are:
 * (1) convergence: the Richardson-extrapolated discretisation error of the
 * final length at n = 48 within 1 % (n = 16, 32, 48 across the diameter);
 * (2) Taylor's (1948) one-dimensional estimate of the flow stress from the
 * final length L and the undeformed length X, sigma_T = rho v^2 (L0 - X) /
 * (2 (L0 - L) ln(L0 / X)), against sigma_y (uniaxial: the axisymmetric rod)
 * within 25 % (no elasticity, no mushroom in Taylor's theory; its estimates
 * scatter by ~10-20 % in the literature); (3) the missing published value,
 * recorded as a gap.  The full case also runs two AV forms without the h
 * in the AV's length (issue 6 item 7c): a fixed `viscosity_length` and
 * Balsara's switch, each with check (1) (docs/notes/validation-log.md).
 */
#include "validation/lattice_cases.h"
#include "validation/pen_sph_setup.h"
#include "validation/sph_cases.h"
#include "validation/validation.h"

#include "core/fields.h"
#include "core/particles.h"
#include "core/profile.h"
#include "core/sim.h"
#include "core/model.h"
#include "spall/error.h"

#include <math.h>
#include <omp.h>
#include <stdio.h>

#define T2D_L0 25.4e-3
#define T2D_D0 7.62e-3
#define T2D_V0 221.0
#define T2D_RHO 7850.0
#define T2D_SY 600.0e6
/* Finite-element reference of this rod (validation/fe/taylor_iron/README.md):
 * CalculiX C3D20R, 20-degree axisymmetric wedge, implicit, NLGEOM, the face
 * held at u_z = 0 (frictionless); linear elastic with the SPH material's
 * small-strain moduli (K = rho C^2 = 103.4 GPa, G = 80 GPa), perfectly
 * plastic 600 MPa; at rest (44.5 us).  Length and the outer radius 0.5 mm
 * and 1 mm above the impact face, converged over NR = 2, 3, 4, 6 elements
 * across the radius (the face radius is not: a lip at the corner). */
#define T2D_FE_L 19.67e-3
#define T2D_FE_R05 6.99e-3
#define T2D_FE_R1 6.59e-3

int sph_taylor2d_run(int n, int axisymmetric, const char *av, double t1, double t2,
                     struct sph_taylor2d_result *out, struct spall_error *err)
{
    const double dx = T2D_D0 / n;
    /* Plane strain: half model, mirror plane x = 0.  Axisymmetric: x = r,
     * the rod's axis is x = 0.  Both: the model's penalty wall (a particle
     * closer than dx/2 is pushed, k per particle mass, fixed in time).  A
     * rigid `wall` impactor (k = eta M / dt^2) created +2.9 % of the impact
     * energy here when the adaptive step halved during contact. */
    const char *form = axisymmetric ? "plane: axisymmetric" : "plane: strain, symmetry: x";
    char deck[3072];
    snprintf(deck, sizeof deck,
             "model: {type: sph, kernel: wendland, h_factor: 1.5, viscosity: [1.0, 1.0],\n"
             "        xsph: 0.1, %s, wall: {point: [0, 0], normal: [0, 1]}%s%s}\n"
             "materials:\n"
             "  iron: {density: %.17g, youngs_modulus: 208.0e9, poisson_ratio: 0.3,\n"
             "         eos: mie_gruneisen, sound_speed: 3630, hugoniot_slope: 1.80,\n"
             "         gruneisen: 1.80, yield: perfect, yield_stress: %.17g}\n"
             "lattice: {type: square, spacing: %.17g, origin: [%.17g, %.17g]}\n"
             "body: {geometry: {box: {min: [0, 0], max: [%.17g, %.17g]}}, material: iron}\n"
             "initial_velocity: [{group: all, value: [0, %.17g]}]\n"
             "run: {end_time: %.17g, dt_factor: 0.3}\n",
             form, av && *av ? ", " : "", av ? av : "", T2D_RHO, T2D_SY, dx, 0.5 * dx, 0.5 * dx, 0.5 * T2D_D0, T2D_L0, -T2D_V0, t2);
    struct sim *s = NULL;
    int rc = vlat_build("sph_taylor2d", deck, &s, err);
    if (rc)
        return rc;
    const struct particles *p = s->p;
    sim_update_energy(s);
    const double e0 = s->energy.kinetic;
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
            /* the model's plastic strain, read in place from the field registry */
            const double *ep = field_stored_data(s->fields, "plastic_strain", 0);
            if (!ep) {
                rc = spall_error_set(err, SPALL_ERR_INTERNAL, "sph_taylor2d: no plastic_strain field");
                break;
            }
            for (size_t i = 0; i < p->n; i++) {
                if (p->x0[1][i] < 1.5 * dx)
                    rmax = fmax(rmax, p->x[0][i]);
                /* the undeformed part: particles of the axis column that
                 * stayed below 0.2 % plastic strain (the engineering offset
                 * yield); X runs from the lowest one to the end */
                if (p->x0[0][i] < dx && ep[i] < 2e-3)
                    ylow = fmin(ylow, p->x[1][i]);
            }
            out->len[stage] = ymax - ymin + dx;
            out->rad[stage] = rmax + 0.5 * dx;
            out->undeformed[stage] = ymax - ylow + dx;
            /* the mushroom's outer radius 0.5 mm and 1 mm above the impact
             * face (its surface dx/2 below the lowest centre; the rod has
             * left the wall by 80 us), where the FE reference converges
             * (validation/fe/taylor_iron) */
            for (int k = 0; k < 2 && !rc; k++)
                rc = profile_radius(p, ymin - 0.5 * dx + 0.5e-3 * (k + 1), dx, 0.5 * dx,
                                    &out->prof[stage][k], err);
            sim_update_energy(s);
            out->balance[stage] = s->energy.balance / e0;
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

/* Richardson extrapolation from three spacings h_k = 1 / n_k: the order p
 * solves (L1 - L2) / (L2 - L3) = (h1^p - h2^p) / (h2^p - h3^p) (bisection on
 * [0.25, 6]; 0 when the sequence is not monotone or p leaves that range),
 * and L_inf = L3 - (L2 - L3) h3^p / (h2^p - h3^p). */
static double t2d_richardson(const int n[3], const double L[3], double *p_out)
{
    const double h[3] = {1.0 / n[0], 1.0 / n[1], 1.0 / n[2]};
    const double d12 = L[0] - L[1], d23 = L[1] - L[2];
    *p_out = 0.0;
    if (d12 * d23 <= 0.0)
        return L[2];
    const double ratio = d12 / d23;
    double lo = 0.25, hi = 6.0;
#define T2D_F(q) ((pow(h[0], q) - pow(h[1], q)) / (pow(h[1], q) - pow(h[2], q)) - ratio)
    if (T2D_F(lo) * T2D_F(hi) > 0.0)
        return L[2];
    for (int it = 0; it < 200; it++) {
        double mid = 0.5 * (lo + hi);
        if (T2D_F(lo) * T2D_F(mid) <= 0.0)
            hi = mid;
        else
            lo = mid;
    }
#undef T2D_F
    const double p = 0.5 * (lo + hi);
    *p_out = p;
    return L[2] - d23 * pow(h[2], p) / (pow(h[1], p) - pow(h[2], p));
}

/* Final length and outer radius 0.5 mm above the face at n = 48 against the
 * FE reference, 2 % each (the tolerance for the 3D bar, item 7d). */
static int t2d_fe_checks(struct vreport *r, const char *label,
                         const struct sph_taylor2d_result *f, const char *gap_note,
                         struct spall_error *err)
{
    static const char *src = "CalculiX C3D20R axisymmetric wedge, converged "
                             "(validation/fe/taylor_iron)";
    char q[160], note[240];
    const double ref[2] = {T2D_FE_L, T2D_FE_R05}, meas[2] = {f->len[1], f->prof[1][0]};
    const char *what[2] = {"final length", "outer radius 0.5 mm above the face"};
    for (int k = 0; k < 2; k++) {
        snprintf(q, sizeof q, "%s at n = 48, %s, against FE", what[k], label);
        int rc = vreport_check(r, q, "m", ref[k], meas[k], 0.02, true, src,
                               "2 %: the issue's tolerance for the 3D bar (item 7d)", err);
        if (rc)
            return rc;
        if (!r->checks[r->n - 1].pass) {
            snprintf(note, sizeof note, "GAP: %s", gap_note);
            vreport_mark_gap(r, note);
        }
    }
    return SPALL_OK;
}

/* One alternative AV form on n = 16, 32, 48: its rows, a Richardson fit of
 * the final length and foot radius (pen_richardson), Taylor's estimate per
 * run, and the convergence check: an order >= 0.5 must exist and the
 * extrapolated error of L at n = 48 must be within 1 %.  @p res[2] may be
 * given (reuse) when the form equals the thesis form at n = 48. */
static int t2d_form(struct vreport *r, const char *label, const char *av,
                    struct sph_taylor2d_result res[3], int have_last, int fe_checks,
                    struct spall_error *err)
{
    static const int series[3] = {16, 32, 48};
    int rc;
    for (int k = 0; k < 3; k++) {
        if (k < 2 || !have_last)
            if ((rc = sph_taylor2d_run(series[k], 1, av, 50e-6, 80e-6, &res[k], err)))
                return rc;
        vreport_info(r, "%s, %d across: L = %.3f mm, R = %.3f mm, R(0.5 mm) = %.3f mm, X = %.2f "
                     "mm at 80 us, energy balance %+.2f %%, Taylor sigma %.0f MPa (%.0f s%s)",
                     label, series[k], res[k].len[1] * 1e3, res[k].rad[1] * 1e3,
                     res[k].prof[1][0] * 1e3,
                     res[k].undeformed[1] * 1e3, 100.0 * res[k].balance[1],
                     taylor_stress(res[k].len[1], res[k].undeformed[1]) * 1e-6, res[k].seconds,
                     k == 2 && have_last ? "; the thesis-form run, identical here" : "");
    }
    const double h[3] = {1.0 / series[0], 1.0 / series[1], 1.0 / series[2]};
    const double L[3] = {res[0].len[1], res[1].len[1], res[2].len[1]};
    const double R[3] = {res[0].rad[1], res[1].rad[1], res[2].rad[1]};
    double p = 0.0, Linf = 0.0, pr = 0.0, Rinf = 0.0;
    struct spall_error e2 = {0};
    int okL = !pen_richardson(h, L, &p, &Linf, &e2) && p >= 0.5;
    if (okL)
        vreport_info(r, "%s: L_inf = %.3f mm (order %.2f)", label, Linf * 1e3, p);
    else
        vreport_info(r, "%s: no Richardson order >= 0.5 for L (%s; order %.2f)", label,
                     e2.msg[0] ? e2.msg : "order below 0.5", p);
    e2.msg[0] = '\0';
    if (!pen_richardson(h, R, &pr, &Rinf, &e2) && pr >= 0.5)
        vreport_info(r, "%s: R_inf = %.3f mm (order %.2f)", label, Rinf * 1e3, pr);
    else
        vreport_info(r, "%s: no Richardson order >= 0.5 for R (%s)", label,
                     e2.msg[0] ? e2.msg : "order below 0.5");
    vreport_info(r, "%s at n = 48 against the FE reference: L %+.2f %%, R(0.5 mm) %+.2f %%, "
                 "R(1 mm) %+.2f %%", label, 100.0 * (L[2] / T2D_FE_L - 1.0),
                 100.0 * (res[2].prof[1][0] / T2D_FE_R05 - 1.0),
                 100.0 * (res[2].prof[1][1] / T2D_FE_R1 - 1.0));
    char q[160];
    snprintf(q, sizeof q, "final length at n = 48, %s: Richardson error estimate", label);
    if (okL)
        rc = vreport_check(r, q, "1", 0.0, fabs(L[2] - Linf) / Linf, 0.01, false,
                           "convergence, n = 16, 32, 48 across",
                           "1 %: the 3D case's target accuracy", err);
    else {
        snprintf(q, sizeof q, "final length, %s: Richardson order >= 0.5 exists", label);
        rc = vreport_check_true(r, q, false, "convergence, n = 16, 32, 48 across",
                                "no order >= 0.5: no estimate, not converged", err);
    }
    if (rc)
        return rc;
    if (!r->checks[r->n - 1].pass)
        vreport_mark_gap(r, "GAP: this AV form does not converge the length either; see "
                            "docs/notes/validation-log.md");
    if (fe_checks)
        return t2d_fe_checks(r, label, &res[2], "see docs/notes/validation-log.md", err);
    return SPALL_OK;
}

int sph_case_taylor2d(struct vreport *r, struct spall_error *err)
{
    static const int series[3] = {16, 32, 48};
    const int last = r->quick ? 0 : 2;
    struct sph_taylor2d_result res[3], ps;
    int rc;
    /* the main check: the axisymmetric rod (a cylinder is axisymmetric) */
    for (int k = 0; k <= last; k++) {
        if ((rc = sph_taylor2d_run(series[k], 1, NULL, 50e-6, 80e-6, &res[k], err)))
            return rc;
        vreport_info(r, "axisymmetric Taylor rod, %d across (%zu rings, dx = %.4g mm): L = %.3f / "
                     "%.3f mm, foot radius R = %.3f / %.3f mm at 50 / 80 us, outer radius "
                     "%.3f / %.3f mm 0.5 / 1 mm above the face at 80 us, undeformed X = %.2f "
                     "mm, mean v at 80 us %+.2f m/s, energy balance %+.2f %% of E_kin0 (%.0f s)",
                     series[k], res[k].particles, T2D_D0 / series[k] * 1e3, res[k].len[0] * 1e3,
                     res[k].len[1] * 1e3, res[k].rad[0] * 1e3, res[k].rad[1] * 1e3,
                     res[k].prof[1][0] * 1e3, res[k].prof[1][1] * 1e3,
                     res[k].undeformed[1] * 1e3, res[k].v_end, 100.0 * res[k].balance[1],
                     res[k].seconds);
    }
    /* the plane-strain form (the seed's "2D"), one spacing, for comparison */
    if ((rc = sph_taylor2d_run(r->quick ? 16 : 32, 0, NULL, 50e-6, 80e-6, &ps, err)))
        return rc;
    vreport_info(r, "plane-strain rod (comparison), %d across: L = %.3f mm, foot half-width %.3f "
                 "mm at 80 us, energy balance %+.2f %% (%.0f s)", r->quick ? 16 : 32,
                 ps.len[1] * 1e3, ps.rad[1] * 1e3, 100.0 * ps.balance[1], ps.seconds);
    const struct sph_taylor2d_result *f = &res[last];
    if (last > 0) {
        const double L[3] = {res[0].len[1], res[1].len[1], res[2].len[1]};
        const double R[3] = {res[0].rad[1], res[1].rad[1], res[2].rad[1]};
        double p = 0.0, pr = 0.0;
        double Linf = t2d_richardson(series, L, &p);
        double Rinf = t2d_richardson(series, R, &pr);
        /* no order from the data (the increments do not shrink): assume
         * first order, the order of the artificial viscosity (~ h) */
        if (!(p > 0.0))
            Linf = L[2] - (L[1] - L[2]) * series[1] / (double)(series[2] - series[1]);
        vreport_info(r, "Richardson: L_inf = %.3f mm (order %.2f; 0: no order in [0.25, 6], "
                     "first order assumed), R_inf = %.3f mm (order %.2f; 0: none in [0.25, 6], "
                     "R_inf = R at n = 48)", Linf * 1e3, p, Rinf * 1e3, pr);
        double est = fabs(f->len[1] - Linf) / Linf;
        if ((rc = vreport_check(r, "final length at n = 48: Richardson error estimate", "1", 0.0,
                                est, 0.01, false,
                                "convergence, n = 16, 32, 48 across (no published length for "
                                "this set-up)",
                                "1 %: the 3D case's target accuracy", err)))
            return rc;
        if (!r->checks[r->n - 1].pass)
            vreport_mark_gap(r, "GAP: the length is not converged to 1 % at n = 48; see "
                                "docs/notes/validation-log.md");
        /* against the FE reference (the 3D-bar tolerance, item 7d) */
        vreport_info(r, "FE reference (CalculiX, validation/fe/taylor_iron): L = %.2f mm, outer "
                     "radius %.2f / %.2f mm 0.5 / 1 mm above the face; Richardson L_inf above: "
                     "%+.2f %% against it", T2D_FE_L * 1e3, T2D_FE_R05 * 1e3, T2D_FE_R1 * 1e3,
                     100.0 * (Linf / T2D_FE_L - 1.0));
        if ((rc = t2d_fe_checks(r, "thesis AV (length h)", f,
                                "the AV (length h) holds the rod long and its foot narrow at "
                                "n = 48; see docs/notes/validation-log.md",
                                err)))
            return rc;
        /* The convergence gap was put down to the AV (its viscous stress
         * ~ rho c h |grad v| shrinks with h).  Two forms that remove that:
         * (a) a fixed AV length L = the h of the n = 48 run (1.5 D0 / 48),
         * so the finest run is the thesis-form run itself (reused: mu_ij is
         * then identical) and the coarser runs carry no more AV than it;
         * (b) Balsara's switch (AV off in shear). */
        struct sph_taylor2d_result fl[3], bal[3];
        fl[2] = res[2];
        char av[64];
        snprintf(av, sizeof av, "viscosity_length: %.17g", 1.5 * T2D_D0 / series[2]);
        if ((rc = t2d_form(r, "AV length fixed at 0.238 mm", av, fl, 1, 0, err)))
            return rc;
        if ((rc = t2d_form(r, "AV with Balsara switch", "viscosity_switch: balsara", bal, 0, 1,
                           err)))
            return rc;
    }
    /* Taylor (1948), uniaxial: the axisymmetric rod's flow stress is sigma_y */
    double sT = taylor_stress(f->len[1], f->undeformed[1]);
    if ((rc = vreport_check(r, "Taylor (1948) flow stress from L and X", "Pa", T2D_SY, sT, 0.25,
                            true, "sigma_y 600 MPa ([Meng2021] Table 3.5; uniaxial: axisymmetric)",
                            "25 %: 1D rigid-plastic theory, no elasticity, no mushroom", err)))
        return rc;
    if ((rc = vreport_check_true(r, "published final length / radius for this set-up found",
                                 false,
                                 "Libersky & Petschek (1991) / Libersky et al. (1993), EPIC-2; "
                                 "Wilkins & Guinan (1973) test",
                                 "not retrievable here: measured values reported only", err)))
        return rc;
    vreport_mark_gap(r, "GAP: no published final length / radius to compare with (references "
                        "not found); see docs/notes/validation-log.md");
    return SPALL_OK;
}
