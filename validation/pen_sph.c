/**
 * @file pen_sph.c
 * @brief Validation cases of the SPH penetration model (issue 7 item 3):
 *        a rigid silica sphere (d = 7.38 um, 1850 kg/m^3) into 10 wt %
 *        gelatin, axisymmetric SPH (src/models/sph/sph_axisym.c) with the
 *        core penalty impactor (src/core/rigid.c), [Meng2021] sec. 4.3-4.4.
 *
 * Deck (pen_sph_deck, identical to examples/pen_sph_gelatin at dx1 =
 * 0.75 um): gelatin E (20 MPa), nu = 0.499, A + B ep^n (21 MPa, 0.01 MPa,
 * 0.1), Mie-Grueneisen C_k form (1520 m/s, S = 1.8, no Gamma), no failure
 * (failure: none); AV (0.5, 0.2), XSPH 0.015, Wendland, h = 1.3 dx.
 * Why no failure: [Meng2021] sec. 4.3.2 calls the law "elastic-plastic
 * hydrodynamic" (RADIOSS, the polynomial EOS of Eq. 4.13) and lists only
 * E, nu, A, B, n, c0, S (Tab. 4.3); in that family of laws (/MAT/LAW3) the
 * "maximum stress" caps the flow stress and the only failure is a plastic
 * strain, off unless given.  Sec. 4.6.1 says a stiffer target "stops the
 * projectile more quickly" because the end of the penetration is
 * "predominantly elastic-plastic": failure at sigma_vm = A (the former
 * default, kept as a deck option) removes every intact particle around the
 * sphere, makes E irrelevant and P_max 10 % deep and 70 ns late
 * (docs/notes/validation-log.md, pen-sph-gelatin).
 * Graded spacing: dx1 for r <= 8 um (L_sph ~ 2 d) and z >= -100 um, then
 * 2, 4, 8 dx1 out to r = 144 um (x width) and z = -250 um; every level's
 * edges are multiples of the next level's spacing.  The sphere starts
 * 0.25 um above the surface; P(t) is the depth of its tip below the
 * initial surface (the experimental convention, P_Exp = P_Poncelet + d/2,
 * [Meng2021] Eq. 4.7) and time is counted from first contact.  A run stops
 * when the sphere has stopped (V <= 0: P_max reached) or at its end time.
 *
 * Cases: "pen-sph-gelatin" (1290 m/s at d/10: P_max, its time, cavity,
 * and the rebound after P_max: the run goes on to 320 ns after contact;
 * d/10 to keep the full suite affordable: d/15 (8166 particles, ~4x the
 * CPU) is 12.9 % deeper and d/20 (14844, ~14x) 22.3 %, not converged,
 * docs/notes/validation-log.md),
 * "pen-sph-gelatin-sweep" (200-1420 m/s at d/10 vs Poncelet + d/2),
 * "pen-sph-gelatin-modulus" (E = 1, 10, 20, 40 MPa at d/10: trend),
 * "pen-sph-gelatin-convergence" (d/10, d/15, d/20, d/25 and 1.5x width at d/15,
 * 1290 m/s, in the converging form: fixed AV length + contact offset;
 * Richardson estimate when the sequence converges),
 * "pen-sph-gelatin-av" (two AV forms at d/10, d/15, d/20: fixed viscous
 * length, Balsara switch).
 */
#include "validation/lattice_cases.h"
#include "validation/pen_cases.h"
#include "validation/pen_sph_setup.h"
#include "validation/validation.h"

#include "spall/error.h"
#include "spall/penetration.h"

#include <math.h>
#include <stdio.h>

#define PEN_D 7.38e-6
#define PEN_RHO_P 1850.0

/* The gelatin grid: finest spacing @p dx1 [m], the two outer levels scaled
 * by @p width; penalty stiffness frozen at first contact. */
static struct pen_sph_grid gelatin_grid(double dx1, double width, double t_end)
{
    return (struct pen_sph_grid){.dx1_d = dx1 / PEN_D, .width = width, .depth = 1.0,
                                 .t_end = t_end, .cavity_depth = 15.0e-6, .k_first_contact = 1};
}

/* The deck of the file comment: the general builder (validation/
 * pen_sph_setup.c) at d = 7.38 um with the gelatin target. */
void pen_sph_deck(char *buf, size_t len, double v0, double E, double dx1, double width,
                  double t_end)
{
    const struct pen_sph_target t = pen_sph_target_gelatin(E);
    const struct pen_sph_shot s = {PEN_D, PEN_RHO_P, v0};
    const struct pen_sph_grid g = gelatin_grid(dx1, width, t_end);
    struct spall_error err = {0};
    if (pen_sph_setup_deck(buf, len, &t, &s, &g, &err) && len > 0)
        buf[0] = '\0'; /* an empty deck then fails to build, naming the deck */
}

static int pen_sph_run(struct vreport *r, double v0, double E, double dx1, double width,
                       double t_end, struct pen_sph_outcome *o, struct spall_error *err)
{
    const struct pen_sph_target t = pen_sph_target_gelatin(E);
    const struct pen_sph_shot s = {PEN_D, PEN_RHO_P, v0};
    const struct pen_sph_grid g = gelatin_grid(dx1, width, t_end);
    return pen_sph_setup_run(r, &t, &s, &g, o, err);
}

static int poncelet_nose(double v0, double *out, struct spall_error *err)
{
    struct pen_params pp = {.model = PEN_PONCELET, .d = PEN_D, .rho_p = PEN_RHO_P,
                            .rho_t = 1030.0, .cd = 0.375, .R = 21.0e6};
    struct pen_result res;
    int rc = pen_poncelet(&pp, v0, 0, NULL, NULL, NULL, &res, err);
    *out = res.p_max + 0.5 * PEN_D;
    return rc;
}

static void run_info(struct vreport *r, const char *what, const struct pen_sph_outcome *o)
{
    vreport_info(r,
                 "%s: %zu particles, P_max = %.2f um at %.0f ns after contact (P_max/d = %.2f), "
                 "end: P = %.2f um, V = %.0f m/s; cavity at 15 um: D1max %.2f um, D2max %.2f um; "
                 "energy balance %.2g of the input; %.0f s",
                 what, o->n, o->pmax * 1e6, o->t_pmax * 1e9, o->pmax / PEN_D, o->p_end * 1e6,
                 o->v_end, o->d1max * 1e6, o->d2max * 1e6, o->balance, o->secs);
}

/* Rebound window: the run goes on after P_max to 320 ns after contact,
 * before the wave reflected at the target's bottom (z = -252 um,
 * 2 x 252 um / 1520 m/s = 331 ns) is back at the sphere. */
#define PEN_REBOUND_END 320.0e-9

int pen_case_sph_gelatin(struct vreport *r, struct spall_error *err)
{
    struct pen_sph_outcome o = {0};
    const struct pen_sph_target t = pen_sph_target_gelatin(20.0e6);
    const struct pen_sph_shot s = {PEN_D, PEN_RHO_P, 1290.0};
    struct pen_sph_grid g = gelatin_grid(0.75e-6, 1.0, 450.0e-9);
    g.t_rebound = PEN_REBOUND_END;
    int rc = pen_sph_setup_run(r, &t, &s, &g, &o, err);
    if (rc)
        return rc;
    run_info(r, "1290 m/s, E = 20 MPa, dx1 = 0.75 um (d/10), run on to 320 ns", &o);
    vreport_info(r,
                 "rebound: V turns upward at %.1f ns after contact (%.1f ns after P_max); "
                 "peak upward speed %.1f m/s (%.2f %% of v0, %.3f %% of the input energy) at "
                 "%.0f ns%s; tip recovery at %.0f ns: %.2f um (%.1f %% of P_max)",
                 o.t_rev * 1e9, (o.t_rev - o.t_pmax) * 1e9, o.v_reb, o.v_reb / 1290.0 * 100.0,
                 (o.v_reb / 1290.0) * (o.v_reb / 1290.0) * 100.0,
                 o.t_reb * 1e9, o.t_reb >= PEN_REBOUND_END - 1e-9 ? " (still rising)" : "",
                 PEN_REBOUND_END * 1e9, o.recovery * 1e6, o.recovery / o.pmax * 100.0);
    vreport_series(r, "P(t), 1290 m/s", "t after contact [s]", "P [m]", "SPH (axisymmetric)",
                   VSERIES_LINE, o.t, o.P, o.nh, err);
    vreport_marker(r, "P(t), 1290 m/s", "experiment ~67 um", VSERIES_YMARK, 67.0e-6, err);
    double pn = 0.0;
    if ((rc = poncelet_nose(1290.0, &pn, err)))
        goto out;
    if ((rc = vreport_check(r, "P_max, 1290 m/s", "m", 67.0e-6, o.pmax, 0.10, true,
                            "experiment ~67 um (Veysset et al., [Meng2021] sec. 4.4.2.1)",
                            "10 %: the thesis' SPH matched the experiment within its scatter",
                            err)))
        goto out;
    if (!r->checks[r->n - 1].pass)
        vreport_mark_gap(r, "GAP: docs/notes/validation-log.md (pen-sph-gelatin)");
    if ((rc = vreport_check(r, "time of P_max after contact", "s", 225.0e-9, o.t_pmax, 25.0e-9,
                            false, "experiment: P_max reached 200-250 ns after impact",
                            "the experimental window", err)))
        goto out;
    if (!r->checks[r->n - 1].pass)
        vreport_mark_gap(r, "GAP: docs/notes/validation-log.md (pen-sph-gelatin)");
    if ((rc = vreport_check(r, "P_max/d vs Poncelet + d/2, 1290 m/s", "1", pn / PEN_D,
                            o.pmax / PEN_D, 0.10, true,
                            "Poncelet C_d = 0.375, R = 21 MPa, Eq. 4.6 + d/2 (Eq. 4.7)",
                            "10 %: issue 7", err)))
        goto out;
    if (!r->checks[r->n - 1].pass)
        vreport_mark_gap(r, "GAP: docs/notes/validation-log.md (pen-sph-gelatin)");
    /* the speed and recovery have no measured reference (the thesis shows
     * none): a sign test, the numbers go to the info line above */
    if ((rc = vreport_check_true(r, "sphere rebounds after P_max (V turns upward, tip recovers)",
                                 o.rebounded && o.t_rev >= o.t_pmax && o.recovery > 0.0,
                                 "[Meng2021] sec. 5: micro-particles rebound after reaching "
                                 "P_max in the experiments (its ref. 188)",
                                 "sign test; run on to 320 ns (bottom reflection at 331 ns)",
                                 err)))
        goto out;
out:
    pen_sph_outcome_free(&o);
    return rc;
}

int pen_case_sph_sweep(struct vreport *r, struct spall_error *err)
{
    static const double v0s[4] = {200.0, 700.0, 1050.0, 1420.0};
    static const double tend[4] = {200e-9, 400e-9, 450e-9, 450e-9};
    for (int k = 0; k < 4; k++) {
        struct pen_sph_outcome o = {0};
        int rc = pen_sph_run(r, v0s[k], 20.0e6, 0.75e-6, 1.0, tend[k], &o, err);
        if (rc)
            return rc;
        char what[96], q[96];
        snprintf(what, sizeof what, "%.0f m/s, E = 20 MPa, dx1 = 0.75 um (d/10)", v0s[k]);
        run_info(r, what, &o);
        pen_sph_outcome_free(&o);
        double pn = 0.0;
        if ((rc = poncelet_nose(v0s[k], &pn, err)))
            return rc;
        snprintf(q, sizeof q, "P_max/d vs Poncelet + d/2, %.0f m/s", v0s[k]);
        if ((rc = vreport_check(r, q, "1", pn / PEN_D, o.pmax / PEN_D, 0.10, true,
                                "Poncelet C_d = 0.375, R = 21 MPa, Eq. 4.6 + d/2",
                                "10 %: issue 7", err)))
            return rc;
        if (!r->checks[r->n - 1].pass)
            vreport_mark_gap(r, "GAP: docs/notes/validation-log.md (pen-sph-gelatin-sweep)");
    }
    return SPALL_OK;
}

int pen_case_sph_modulus(struct vreport *r, struct spall_error *err)
{
    static const double Es[4] = {1.0e6, 10.0e6, 20.0e6, 40.0e6};
    double pm[4];
    for (int k = 0; k < 4; k++) {
        struct pen_sph_outcome o = {0};
        int rc = pen_sph_run(r, 1290.0, Es[k], 0.75e-6, 1.0, 450.0e-9, &o, err);
        if (rc)
            return rc;
        char what[96];
        snprintf(what, sizeof what, "1290 m/s, E = %.0f MPa, dx1 = 0.75 um", Es[k] * 1e-6);
        run_info(r, what, &o);
        pm[k] = o.pmax;
        pen_sph_outcome_free(&o);
    }
    bool mono = pm[0] > pm[1] && pm[1] > pm[2] && pm[2] > pm[3];
    int rc = vreport_check_true(r, "P_max decreases as E grows (1, 10, 20, 40 MPa)", mono,
                                "[Meng2021] Fig. 4.13 / Table 4.5; sec. 4.6.1 (a stiffer target "
                                "stops the projectile more quickly)",
                                "the thesis' trend", err);
    if (!rc && !mono)
        vreport_mark_gap(r, "GAP: docs/notes/validation-log.md (pen-sph-gelatin-modulus)");
    if (rc)
        return rc;
    /* Fig. 4.13 (b): case 2 (E = 20 MPa) has the smallest error vs ~67 um */
    bool closest = true;
    for (int k = 0; k < 4; k++)
        if (k != 2 && fabs(pm[k] - 67.0e-6) < fabs(pm[2] - 67.0e-6))
            closest = false;
    rc = vreport_check_true(r, "E = 20 MPa closest to the experiment's 67 um", closest,
                            "[Meng2021] Fig. 4.13 (b)", "the thesis' choice of E", err);
    if (!rc && !closest)
        vreport_mark_gap(r, "GAP: docs/notes/validation-log.md (pen-sph-gelatin-modulus)");
    return rc;
}

/* Largest |P_a(t) - P_b(t)| over the common time span (b interpolated
 * linearly at a's samples), relative to b's P_max. */
static double history_gap(const struct pen_sph_outcome *a, const struct pen_sph_outcome *b)
{
    double worst = 0.0;
    size_t j = 0;
    for (size_t k = 0; k < a->nh; k++) {
        double t = a->t[k];
        while (j + 1 < b->nh && b->t[j + 1] < t)
            j++;
        if (j + 1 >= b->nh || t < b->t[0])
            continue;
        double w = (t - b->t[j]) / (b->t[j + 1] - b->t[j]);
        double pb = b->P[j] + w * (b->P[j + 1] - b->P[j]);
        worst = fmax(worst, fabs(a->P[k] - pb));
    }
    return worst / b->pmax;
}

/* Tip depth at time @p tq after contact (linear in the history), NAN if
 * the run ended before. */
static double p_at(const struct pen_sph_outcome *o, double tq)
{
    for (size_t k = 1; k < o->nh; k++)
        if (o->t[k - 1] <= tq && tq <= o->t[k]) {
            double w = (tq - o->t[k - 1]) / (o->t[k] - o->t[k - 1]);
            return o->P[k - 1] + w * (o->P[k] - o->P[k - 1]);
        }
    return NAN;
}

/* The spacings of the resolution study: d/10, d/15, d/20, d/25 (0.75, 0.5,
 * 0.375, 0.3 um: the finest level halves from d/10 to d/20); the AV-form
 * case runs the first three. */
static const double conv_dx[4] = {0.75e-6, 0.5e-6, 0.375e-6, 0.3e-6};
static const char *const conv_name[4] = {"d/10", "d/15", "d/20", "d/25"};

/* Info lines of one resolution sequence @p o[n] (n = 3 or 4, the first n
 * spacings of conv_dx; form @p form): P at 50, 100, 200 ns, P_max and its
 * time, the Richardson estimate of P_max from the finest three levels if
 * they converge monotonically (with n = 4 also from the coarsest three:
 * the two estimates' spread is a measure of its uncertainty) and its
 * distance to the experiment's 67 um; returns 1 if P_max converges over
 * the finest three with a Richardson order p >= 0.5 (the linear AV term
 * and the contact layer are O(dx): order 1 expected once resolved).
 * Smaller increments alone do not count: with the spacings 0.75, 0.5,
 * 0.375 um an increment ratio below ln 1.5 / ln(4/3) = 1.41 means P_max
 * still grows like ln(1/dx) or faster, i.e. no limit is in sight. */
static int sequence_info(struct vreport *r, const char *form, const struct pen_sph_outcome *o,
                         int n)
{
    for (int k = 0; k < n; k++)
        vreport_info(r,
                     "%s, %s (%zu particles): P(50, 100, 200 ns) = %.2f, %.2f, %.2f um; "
                     "P_max %.2f um at %.0f ns; energy balance %.2g; %.0f s",
                     form, conv_name[k], o[k].n, p_at(&o[k], 50e-9) * 1e6,
                     p_at(&o[k], 100e-9) * 1e6, p_at(&o[k], 200e-9) * 1e6, o[k].pmax * 1e6,
                     o[k].t_pmax * 1e9, o[k].balance, o[k].secs);
    for (int k = 1; k < n; k++)
        vreport_info(r, "%s: P_max increment %s -> %s %+.2f um (%+.2f %%); max |P(t) "
                     "difference| / P_max %.3f",
                     form, conv_name[k - 1], conv_name[k], (o[k].pmax - o[k - 1].pmax) * 1e6,
                     100.0 * (o[k].pmax / o[k - 1].pmax - 1.0), history_gap(&o[k - 1], &o[k]));
    int conv = 0;
    for (int s = n - 3; s >= 0; s--) {
        const double f[3] = {o[s].pmax, o[s + 1].pmax, o[s + 2].pmax};
        double p = 0.0, finf = 0.0;
        struct spall_error e = {0};
        const int rich = pen_richardson(&conv_dx[s], f, &p, &finf, &e) == SPALL_OK;
        if (rich)
            vreport_info(r,
                         "%s, %s-%s: Richardson P_max(dx -> 0) = %.2f um (order %.2f), %+.1f %% "
                         "vs the experiment's 67 um; %s is %.1f %% short of it",
                         form, conv_name[s], conv_name[s + 2], finf * 1e6, p,
                         100.0 * (finf / 67e-6 - 1.0), conv_name[s + 2],
                         100.0 * (1.0 - f[2] / finf));
        else
            vreport_info(r, "%s, %s-%s: no Richardson estimate (%s)", form, conv_name[s],
                         conv_name[s + 2], e.msg);
        if (s == n - 3)
            conv = rich && p >= 0.5;
    }
    return conv;
}

/* "pen-sph-gelatin-convergence" (issue 7 item 3): P(t) must not change when
 * the target is refined or made wider.  Run in the converging form of the
 * gelatin deck: AV length fixed at 0.65 um (viscosity_length: h at d/15,
 * where the thesis set (0.5, 0.2)) and the sphere's contact on the gel's
 * particle surfaces (contact_offset = dx1/2, builder flag surface_contact).
 * The cases' deck (AV with h, contact on particle centres) cannot converge:
 * every refinement changes the equations (the AV's h) and the sphere's
 * effective radius (d/2 - dx1/2); the other gelatin cases keep it because
 * their numbers are compared with the thesis at the thesis' resolution
 * (docs/notes/validation-log.md, pen-sph-gelatin, "The rest: the entry").
 * Levels d/10, d/15, d/20, d/25 (d/25: 23 133 particles, about half of
 * the case's time) and d/15 with the target 1.5x wider.
 * Tolerances: 3 % for the change of P_max between the two finest levels (a
 * third of the 10 % of the comparisons with the experiment, item 4a, so
 * that the resolution does not decide them; at a low order the distance to
 * the limit is several times the last change, so the Richardson check
 * stays); 2 % for the width (nothing
 * physical changes: only the side wave, back at the shot line at 189 ns in
 * the full-width target and 284 ns in the wider one, before or around
 * P_max). */
int pen_case_sph_convergence(struct vreport *r, struct spall_error *err)
{
    struct pen_sph_outcome o[4] = {{0}}, w = {0};
    struct pen_sph_target t = pen_sph_target_gelatin(20.0e6);
    t.av_length = 1.3 * 0.5e-6;
    const struct pen_sph_shot s = {PEN_D, PEN_RHO_P, 1290.0};
    int rc = SPALL_OK;
    for (int k = 0; k < 5 && !rc; k++) {
        /* k = 4: d/15 with the two outer radial levels 1.5x wider (to 216 um) */
        struct pen_sph_grid g = gelatin_grid(conv_dx[k < 4 ? k : 1], k < 4 ? 1.0 : 1.5, 300.0e-9);
        g.surface_contact = 1;
        rc = pen_sph_setup_run(r, &t, &s, &g, k < 4 ? &o[k] : &w, err);
    }
    if (rc)
        goto out;
    for (int k = 0; k < 4; k++) {
        char what[64];
        snprintf(what, sizeof what, "%s, full width", conv_name[k]);
        run_info(r, what, &o[k]);
    }
    run_info(r, "d/15, 1.5x width (outer levels to 216 um)", &w);
    static const char form[] = "AV length 0.65 um + contact offset dx1/2";
    const int conv = sequence_info(r, form, o, 4);
    vreport_info(r, "%s, d/10: P_max %.2f um; the cases' deck (AV with h, contact on centres) "
                 "at d/10 is pen-sph-gelatin's P_max",
                 form, o[0].pmax * 1e6);
    if ((rc = vreport_check(r, "P_max d/20 vs d/25", "m", o[3].pmax, o[2].pmax, 0.03, true,
                            "this model at d/25 (converging form)",
                            "3 %: a third of the 10 % against the experiment", err)))
        goto out;
    if (!r->checks[r->n - 1].pass)
        vreport_mark_gap(r, "GAP: docs/notes/validation-log.md (pen-sph-gelatin-convergence)");
    if ((rc = vreport_check(r, "max |P(t) d/20 - P(t) d/25| / P_max(d/25)", "1", 0.0,
                            history_gap(&o[2], &o[3]), 0.03, false,
                            "this model at d/25 (converging form)",
                            "3 %: the whole P(t), not only its maximum", err)))
        goto out;
    if (!r->checks[r->n - 1].pass)
        vreport_mark_gap(r, "GAP: docs/notes/validation-log.md (pen-sph-gelatin-convergence)");
    if ((rc = vreport_check_true(r,
                                 "P_max converges d/15 -> d/20 -> d/25 (Richardson order >= 0.5)",
                                 conv, "this model at d/15, d/20, d/25 (converging form)",
                                 "a converging sequence with a usable limit", err)))
        goto out;
    if (!r->checks[r->n - 1].pass)
        vreport_mark_gap(r, "GAP: docs/notes/validation-log.md (pen-sph-gelatin-convergence)");
    if ((rc = vreport_check(r, "P_max 1.5x vs full width (d/15)", "m", o[1].pmax, w.pmax, 0.02,
                            true, "this model, full width (converging form)",
                            "2 %: the far field must not matter", err)))
        goto out;
    if (!r->checks[r->n - 1].pass)
        vreport_mark_gap(r, "GAP: docs/notes/validation-log.md (pen-sph-gelatin-convergence)");
    if ((rc = vreport_check(r, "max |P(t) 1.5x - P(t) full width| / P_max (d/15)", "1", 0.0,
                            history_gap(&w, &o[1]), 0.02, false,
                            "this model, full width (converging form)",
                            "2 %: the far field must not matter", err)))
        goto out;
    if (!r->checks[r->n - 1].pass)
        vreport_mark_gap(r, "GAP: docs/notes/validation-log.md (pen-sph-gelatin-convergence)");
out:
    for (int k = 0; k < 4; k++)
        pen_sph_outcome_free(&o[k]);
    pen_sph_outcome_free(&w);
    return rc;
}

/* "pen-sph-gelatin-av": two documented AV forms (docs/decks.md) at d/10,
 * d/15, d/20 — (a) viscosity_length L = 0.65 um = h at d/15 (the thesis
 * calibrated (0.5, 0.2) at dx1 = 0.48 um ~ d/15): a viscosity ~ q_a c L that
 * does not shrink with dx; (b) Balsara's switch (AV off in shear).  Not
 * tuned: both keep (0.5, 0.2). */
int pen_case_sph_av_forms(struct vreport *r, struct spall_error *err)
{
    static const char *const form[2] = {"AV (0.5, 0.2), viscosity_length 0.65 um",
                                        "AV (0.5, 0.2), Balsara switch"};
    int rc = SPALL_OK;
    for (int f = 0; f < 2 && !rc; f++) {
        struct pen_sph_outcome o[3] = {{0}};
        struct pen_sph_target t = pen_sph_target_gelatin(20.0e6);
        if (f == 0)
            t.av_length = 1.3 * 0.5e-6;
        else
            t.av_balsara = 1;
        const struct pen_sph_shot s = {PEN_D, PEN_RHO_P, 1290.0};
        for (int k = 0; k < 3 && !rc; k++) {
            const struct pen_sph_grid g = gelatin_grid(conv_dx[k], 1.0, 450.0e-9);
            rc = pen_sph_setup_run(r, &t, &s, &g, &o[k], err);
        }
        if (!rc) {
            const int shrink = sequence_info(r, form[f], o, 3);
            char q[160];
            snprintf(q, sizeof q, "%s: P_max converges d/10 -> d/20 (Richardson order >= 0.5)",
                     form[f]);
            rc = vreport_check_true(r, q, shrink, "this model at d/10, d/15, d/20",
                                    "a converging sequence", err);
            if (!rc && !r->checks[r->n - 1].pass)
                vreport_mark_gap(r, "GAP: docs/notes/validation-log.md (pen-sph-gelatin-av)");
        }
        for (int k = 0; k < 3; k++)
            pen_sph_outcome_free(&o[k]);
    }
    return rc;
}
