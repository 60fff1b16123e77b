/**
 * @file pen_sph_sebs.c
 * @brief Validation case "pen-sph-sebs" (issue 7 item 4c): rigid steel
 *        spheres into 40 vol% SEBS gel, axisymmetric SPH
 *        (validation/pen_sph_setup.c), against the Modified Clift-Gauvin
 *        model with the thesis' fit (b): R = 25 MPa, eta = 4.5e-2 Pa s
 *        ([Meng2021] sec. 4.2.2.2, Fig. 4.5; compared with SPH in Fig. 4.28).
 *
 * Cases (data/penetration/sebs_steel_cases.csv, [Meng2021] sec. 4.5): 20 um
 * at 215 m/s, 16 um at 440, 13 um at 630, 12 um at 735, 22 um at 300, each
 * at E = 40 and 50 MPa (the thesis' range, sec. 4.5.1).  Target: SEBS of
 * Tab. 4.3 (pen_sph_target_sebs: AV (2, 1), XSPH 0.08); steel 7800 kg/m^3
 * (Tab. 4.4).  Grid: d/10 at the shot line; the gelatin deck's lengths
 * scaled by d / 7.38 um, its depths by a further 1.5 so that the finest
 * level (20.3 d deep) holds the deepest case (MCG + nose: 13.3 d at
 * 12 um / 735 m/s) and the bottom (51 d) is far.
 *
 * Convention: P_max is the depth of the sphere's tip below the initial
 * surface, compared with the model's P_max + d/2 (the experimental
 * convention, Eq. 4.7), as pen-sph-gelatin compares with Poncelet + d/2:
 * Eq. 4.7 is the only convention the thesis states for experimental
 * depths, and it fitted R and eta to the experimental P_max points
 * (approach b); it does not say which point of the sphere its SEBS depths
 * refer to, so the comparison with the model without the nose
 * is printed too.  Tolerance 15 %: issue 7 item 4c.
 */
#include "validation/pen_sph_setup.h"
#include "validation/validation.h"

#include "spall/error.h"
#include "spall/penetration.h"

#include <math.h>
#include <stdio.h>

#define SEBS_RHO_P 7800.0 /* steel, [Meng2021] Tab. 4.4 */
#define SEBS_RHO_T 875.0  /* 40 vol% SEBS, Tab. 4.3 */
#define SEBS_TOL 0.15     /* issue 7 item 4c */

/* The five shots (d [m], v0 [m/s]) of data/penetration/sebs_steel_cases.csv. */
static const double sebs_shots[5][2] = {
    {20e-6, 215.0}, {16e-6, 440.0}, {13e-6, 630.0}, {12e-6, 735.0}, {22e-6, 300.0}};

/** The grid of every pen-sph-sebs run and of examples/pen_sph_sebs_*. */
static struct pen_sph_grid sebs_grid(void)
{
    struct pen_sph_grid g = {.dx1_d = 0.1, .width = 1.0, .depth = 1.5, .t_end = 1.6e-6,
                             .cavity_depth = 0.0};
    return g;
}

static int mcg_reference(double d, double v0, struct pen_result *res, struct spall_error *err)
{
    struct pen_params p = {.model = PEN_MCG, .d = d, .rho_p = SEBS_RHO_P, .rho_t = SEBS_RHO_T,
                           .eta = 4.5e-2, .R = 25.0e6};
    return pen_solve(&p, v0, 0, NULL, NULL, NULL, 0, res, err);
}

/* Mark the check just recorded as a known gap of @p gap_case if it failed. */
static void gap_if_failed(struct vreport *r, const char *gap_case)
{
    if (!r->checks[r->n - 1].pass)
        vreport_mark_gap(r, gap_case);
}

/* The model's P(t) (no nose) at the SPH's history times, for the report. */
static int mcg_series(struct vreport *r, const char *plot, double d, double v0,
                      const struct pen_sph_outcome *o, struct spall_error *err)
{
    if (!r->keep_series || o->nh == 0)
        return SPALL_OK;
    struct pen_params p = {.model = PEN_MCG, .d = d, .rho_p = SEBS_RHO_P, .rho_t = SEBS_RHO_T,
                           .eta = 4.5e-2, .R = 25.0e6};
    struct pen_result res;
    double tt[256], pp[256];
    const double tmax = o->t[o->nh - 1];
    for (int k = 0; k < 256; k++)
        tt[k] = tmax * k / 255.0;
    int rc = pen_solve(&p, v0, 256, tt, pp, NULL, 0, &res, err);
    if (!rc)
        for (int k = 0; k < 256; k++)
            pp[k] += 0.5 * d;
    if (!rc)
        rc = vreport_series(r, plot, "t after contact [s]", "tip depth P [m]",
                            "Modified-CG + d/2 (R = 25 MPa, eta = 4.5e-2)", VSERIES_REF, tt, pp,
                            256, err);
    return rc;
}

int pen_case_sph_sebs(struct vreport *r, struct spall_error *err)
{
    static const double Es[2] = {40.0e6, 50.0e6};
    const struct pen_sph_grid g = sebs_grid();
    /* reduced (the standard tier, ~2 min): E = 40 MPa, where the d/15 runs
     * miss the 15 % first, and its two extreme shots (slowest and fastest,
     * the shots of pen-sph-sebs-convergence); the full run: all ten */
    const int n_e = r->quick ? 1 : 2;
    for (int e = 0; e < n_e; e++) {
        const struct pen_sph_target tgt = pen_sph_target_sebs(Es[e]);
        for (int k = 0; k < 5; k++) {
            if (r->quick && k != 0 && k != 3)
                continue;
            const double d = sebs_shots[k][0], v0 = sebs_shots[k][1];
            struct pen_sph_shot shot = {.d = d, .rho_p = SEBS_RHO_P, .v0 = v0};
            struct pen_result ref;
            int rc = mcg_reference(d, v0, &ref, err);
            if (rc)
                return rc;
            struct pen_sph_outcome o;
            if ((rc = pen_sph_setup_run(r, &tgt, &shot, &g, &o, err)))
                return rc;
            const double pref = ref.p_max + 0.5 * d;
            vreport_info(r,
                         "%.0f um at %.0f m/s, E = %.0f MPa: %zu particles, P_max = %.2f um at "
                         "%.0f ns after contact (%s); Modified-CG %.2f um + d/2 = %.2f um, T_f "
                         "%.0f ns, Re(v0) %.0f; vs model without nose %+.1f %%; end P = %.2f "
                         "um, V = %.1f m/s; cavity at %.1f um: D1max %.1f um, D2max %.1f um; "
                         "energy balance %.2g of the input; %.1f s",
                         d * 1e6, v0, Es[e] * 1e-6, o.n, o.pmax * 1e6, o.t_pmax * 1e9,
                         o.at_rest ? "sphere at rest" : "end time reached", ref.p_max * 1e6,
                         pref * 1e6, ref.t_f * 1e9, ref.re_max,
                         100.0 * (o.pmax / ref.p_max - 1.0), o.p_end * 1e6, o.v_end,
                         15.0 * d / 7.38e-6, o.d1max * 1e6, o.d2max * 1e6, o.balance, o.secs);
            char plot[80], q[96];
            snprintf(plot, sizeof plot, "P(t), %.0f um at %.0f m/s, E = %.0f MPa", d * 1e6, v0,
                     Es[e] * 1e-6);
            rc = vreport_series(r, plot, "t after contact [s]", "tip depth P [m]",
                                "SPH (axisymmetric)", VSERIES_LINE, o.t, o.P, o.nh, err);
            if (!rc)
                rc = mcg_series(r, plot, d, v0, &o, err);
            pen_sph_outcome_free(&o);
            if (rc)
                return rc;
            snprintf(q, sizeof q, "P_max, %.0f um at %.0f m/s, E = %.0f MPa", d * 1e6, v0,
                     Es[e] * 1e-6);
            if ((rc = vreport_check(r, q, "m", pref, o.pmax, SEBS_TOL, true,
                                    "Modified-CG (R = 25 MPa, eta = 4.5e-2 Pa s, fit b, sec. "
                                    "4.2.2.2) + d/2 (Eq. 4.7)",
                                    "15 %: issue 7 item 4c; tip depth vs the experimental "
                                    "convention with the nose",
                                    err)))
                return rc;
            gap_if_failed(r, "GAP: docs/notes/validation-log.md (pen-sph-sebs)");
        }
    }
    return SPALL_OK;
}

/* "pen-sph-sebs-convergence" (issue 7 items 3 and 4c): the SEBS shots in
 * the converging form of pen-sph-gelatin-convergence.  The case's deck
 * (AV length h, contact on particle centres) deepens every shot by 22-27 %
 * from d/10 to d/15: its AV shrinks with h.  Here the AV length is fixed
 * at the case's h at d/10 (0.13 d: the thesis' AV (2, 1) at the case's
 * resolution, a viscosity ~ q_a c L that no longer changes with dx) and
 * the sphere meets the particles' surfaces (contact_offset dx1/2), so that
 * every level solves the same equations.  Two shots, the slowest and the
 * fastest (20 um at 215 m/s, 12 um at 735 m/s), E = 40 MPa, at d/10, d/15,
 * d/20.  Checks: the change d/15 -> d/20 within 3 % and a Richardson order
 * >= 0.5 (the gelatin convergence case's criteria), and the d/20 depth
 * against Modified-CG + d/2 within 15 % (item 4c). */
#define CONV_GAP "GAP: docs/notes/validation-log.md (pen-sph-sebs-convergence)"
int pen_case_sph_sebs_convergence(struct vreport *r, struct spall_error *err)
{
    static const double N[3] = {10.0, 15.0, 20.0};
    static const int pick[2] = {0, 3};
    int rc;
    for (int k = 0; k < 2; k++) {
        const double d = sebs_shots[pick[k]][0], v0 = sebs_shots[pick[k]][1];
        struct pen_sph_target tgt = pen_sph_target_sebs(40.0e6);
        tgt.av_length = 0.13 * d;
        const struct pen_sph_shot shot = {.d = d, .rho_p = SEBS_RHO_P, .v0 = v0};
        struct pen_result ref;
        if ((rc = mcg_reference(d, v0, &ref, err)))
            return rc;
        const double pref = ref.p_max + 0.5 * d;
        double h[3], f[3];
        for (int l = 0; l < 3; l++) {
            struct pen_sph_grid g = sebs_grid();
            g.dx1_d = 1.0 / N[l];
            g.surface_contact = 1;
            struct pen_sph_outcome o;
            if ((rc = pen_sph_setup_run(r, &tgt, &shot, &g, &o, err)))
                return rc;
            h[l] = g.dx1_d * d;
            f[l] = o.pmax;
            vreport_info(r,
                         "%.0f um at %.0f m/s, converging form, d/%.0f: %zu particles, P_max "
                         "%.2f um at %.0f ns (%s), %+.1f %% vs Modified-CG + d/2 = %.2f um; "
                         "energy balance %.2g of the input; %.1f s",
                         d * 1e6, v0, N[l], o.n, o.pmax * 1e6, o.t_pmax * 1e9,
                         o.at_rest ? "sphere at rest" : "end time reached",
                         100.0 * (o.pmax / pref - 1.0), pref * 1e6, o.balance, o.secs);
            pen_sph_outcome_free(&o);
        }
        char q[128];
        snprintf(q, sizeof q, "P_max d/15 vs d/20, %.0f um at %.0f m/s", d * 1e6, v0);
        if ((rc = vreport_check(r, q, "m", f[2], f[1], 0.03, true,
                                "this model at d/20 (converging form)",
                                "3 %: as pen-sph-gelatin-convergence", err)))
            return rc;
        gap_if_failed(r, CONV_GAP);
        double p = 0.0, finf = 0.0;
        struct spall_error e = {0};
        const int rich = pen_richardson(h, f, &p, &finf, &e) == SPALL_OK;
        if (rich)
            vreport_info(r, "%.0f um at %.0f m/s: Richardson P_max(dx -> 0) = %.2f um (order "
                         "%.2f), %+.1f %% vs Modified-CG + d/2",
                         d * 1e6, v0, finf * 1e6, p, 100.0 * (finf / pref - 1.0));
        else
            vreport_info(r, "%.0f um at %.0f m/s: no Richardson estimate (%s)", d * 1e6, v0,
                         e.msg);
        snprintf(q, sizeof q, "P_max converges d/10 -> d/20 (order >= 0.5), %.0f um at %.0f m/s",
                 d * 1e6, v0);
        if ((rc = vreport_check_true(r, q, rich && p >= 0.5, "this model at d/10, d/15, d/20",
                                     "a converging sequence", err)))
            return rc;
        gap_if_failed(r, CONV_GAP);
        snprintf(q, sizeof q, "P_max at d/20, %.0f um at %.0f m/s, E = 40 MPa", d * 1e6, v0);
        if ((rc = vreport_check(r, q, "m", pref, f[2], SEBS_TOL, true,
                                "Modified-CG (R = 25 MPa, eta = 4.5e-2 Pa s, fit b) + d/2",
                                "15 %: issue 7 item 4c", err)))
            return rc;
        gap_if_failed(r, CONV_GAP);
    }
    return SPALL_OK;
}
