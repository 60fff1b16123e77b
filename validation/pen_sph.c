/**
 * @file pen_sph.c
 * @brief Validation cases of the SPH penetration model (issue 7 item 3):
 *        a rigid silica sphere (d = 7.38 um, 1850 kg/m^3) into 10 wt %
 *        gelatin, axisymmetric SPH (src/models/sph/sph_axisym.c) with the
 *        core penalty impactor (src/core/rigid.c), seed 004 sec. 4.3-4.4.
 *
 * Deck (pen_sph_deck, identical to examples/pen_sph_gelatin at dx1 =
 * 0.75 um): gelatin E (20 MPa), nu = 0.499, A + B ep^n (21 MPa, 0.01 MPa,
 * 0.1), Mie-Grueneisen C_k form (1520 m/s, S = 1.8, no Gamma), no failure
 * (failure: none); AV (0.5, 0.2), XSPH 0.015, Wendland, h = 1.3 dx.
 * Why no failure: seed 004 sec. 4.3.2 calls the law "elastic-plastic
 * hydrodynamic" (RADIOSS, the polynomial EOS of Eq. 4.13) and lists only
 * E, nu, A, B, n, c0, S (Tab. 4.3); in that family of laws (/MAT/LAW3) the
 * "maximum stress" caps the flow stress and the only failure is a plastic
 * strain, off unless given.  Sec. 4.6.1 says a stiffer target "stops the
 * projectile more quickly" because the end of the penetration is
 * "predominantly elastic-plastic": failure at sigma_vm = A (the former
 * default, kept as a deck option) removes every intact particle around the
 * sphere, makes E irrelevant and P_max 10 % deep and 70 ns late
 * (docs/validation.md, pen-sph-gelatin).
 * Graded spacing: dx1 for r <= 8 um (L_sph ~ 2 d) and z >= -100 um, then
 * 2, 4, 8 dx1 out to r = 144 um (x width) and z = -250 um; every level's
 * edges are multiples of the next level's spacing.  The sphere starts
 * 0.25 um above the surface; P(t) is the depth of its tip below the
 * initial surface (the experimental convention, P_Exp = P_Poncelet + d/2,
 * seed 004 Eq. 4.7) and time is counted from first contact.  A run stops
 * when the sphere has stopped (V <= 0: P_max reached) or at its end time.
 *
 * Cases: "pen-sph-gelatin" (1290 m/s at d/10: P_max, its time, cavity;
 * d/10 to keep the full suite affordable: the d/15 run, 8166 particles,
 * costs ~6x and is ~14 % deeper, docs/validation.md),
 * "pen-sph-gelatin-sweep" (200-1420 m/s at d/10 vs Poncelet + d/2),
 * "pen-sph-gelatin-modulus" (E = 1, 10, 20, 40 MPa at d/10: trend),
 * "pen-sph-gelatin-convergence" (d/10, d/15 and half width at 1290 m/s).
 */
#include "validation/lattice_cases.h"
#include "validation/pen_cases.h"
#include "validation/validation.h"

#include "core/particles.h"
#include "core/rigid.h"
#include "core/sim.h"
#include "spall/error.h"
#include "spall/penetration.h"

#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>

#define PEN_D 7.38e-6
#define PEN_RHO_P 1850.0
#define PEN_GAP 0.25e-6

struct pen_sph_run {
    double pmax, t_pmax;  /**< deepest tip depth [m], its time after contact [s] */
    double d1max, d2max;  /**< largest cavity diameters at 15 um [m] */
    double p_end, v_end;  /**< depth and velocity at the end */
    double balance;       /**< energy balance / input */
    size_t n;             /**< particles */
    double secs;
    double *t, *P, *V;    /**< history (owned) */
    size_t nh;
};

static double round_up(double x, double q)
{
    return ceil(x / q - 1e-9) * q;
}

/* The deck of the file comment; width scales the two outer levels. */
void pen_sph_deck(char *buf, size_t len, double v0, double E, double dx1, double width,
                  double t_end)
{
    double r[4] = {8e-6, 20e-6, 48e-6 * width, 144e-6 * width};
    double z[4] = {100e-6, 130e-6, 170e-6, 250e-6};
    for (int k = 0; k < 4; k++) {
        double q = dx1 * (double)(1 << (k + 1 < 3 ? k + 1 : 3));
        r[k] = round_up(r[k], q);
        z[k] = round_up(z[k], q);
    }
    const double R = 0.5 * PEN_D, M = PEN_RHO_P * 3.141592653589793 * PEN_D * PEN_D * PEN_D / 6.0;
    size_t off = (size_t)snprintf(
        buf, len,
        "model: {type: sph, plane: axisymmetric, kernel: wendland, h_factor: 1.3,\n"
        "        viscosity: [0.5, 0.2], xsph: 0.015, cavity_depth: 15.0e-6}\n"
        "materials:\n"
        "  gelatin: {density: 1030, youngs_modulus: %.9g, poisson_ratio: 0.499,\n"
        "            eos: mie_gruneisen_ck, sound_speed: 1520, hugoniot_slope: 1.8,\n"
        "            gruneisen: 0, yield: power, yield_a: 21.0e6, yield_b: 1.0e4, yield_n: 0.1,\n"
        "            failure: none}\n"
        "lattice: {type: square, spacing: %.9g}\n"
        "geometry:\n",
        E, dx1);
    for (int k = 0; k < 4 && off < len; k++)
        off += (size_t)snprintf(buf + off, len - off,
                                "  l%d: {box: {min: [0, %.9g], max: [%.9g, 0]}}\n", k + 1, -z[k],
                                r[k]);
    off += (size_t)snprintf(buf + off, len - off, "bodies:\n");
    for (int k = 0; k < 4 && off < len; k++) {
        double s = dx1 * (double)(1 << k);
        char g[64];
        if (k == 0)
            snprintf(g, sizeof g, "l1");
        else
            snprintf(g, sizeof g, "{difference: [l%d, l%d]}", k + 1, k);
        off += (size_t)snprintf(buf + off, len - off,
                                "  - {geometry: %s, material: gelatin, lattice: {spacing: %.9g, "
                                "origin: [%.9g, %.9g]}}\n",
                                g, s, 0.5 * s, -0.5 * s);
    }
    if (off < len)
        snprintf(buf + off, len - off,
                 "impactors:\n"
                 "  - {name: sphere, shape: sphere, position: [0, %.9g], radius: %.9g,\n"
                 "     mass: %.9g, velocity: [0, %.9g], gravity: false, contact: penalty,\n"
                 "     stiffness_dt: first_contact}\n"
                 "run: {end_time: %.9g}\n",
                 R + PEN_GAP, R, M, -v0, t_end);
}

static void run_free(struct pen_sph_run *o)
{
    free(o->t);
    free(o->P);
    free(o->V);
    o->t = o->P = o->V = NULL;
}

static int pen_sph_run(double v0, double E, double dx1, double width, double t_end,
                       struct pen_sph_run *o, struct spall_error *err)
{
    char deck[4096];
    pen_sph_deck(deck, sizeof deck, v0, E, dx1, width, t_end);
    struct sim *s = NULL;
    int rc = vlat_build("pen_sph", deck, &s, err);
    if (rc)
        return rc;
    const struct impactor *im = &s->rigid->im[0];
    const double R = im->radius, t_contact = PEN_GAP / v0;
    size_t cap = 1024;
    o->t = malloc(cap * sizeof *o->t);
    o->P = malloc(cap * sizeof *o->P);
    o->V = malloc(cap * sizeof *o->V);
    if (!o->t || !o->P || !o->V) {
        run_free(o);
        sim_destroy(&s);
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory (pen_sph history)");
    }
    o->nh = 0;
    o->pmax = -INFINITY;
    o->d1max = o->d2max = 0.0;
    o->n = s->p->n;
    double t0 = omp_get_wtime(), e_in = 0.5 * im->mass * v0 * v0;
    while (!sim_done(s) && !rc) {
        if ((rc = sim_step(s, err)))
            break;
        double P = -(im->x[1] - R), t = s->t - t_contact;
        if (P > o->pmax) {
            o->pmax = P;
            o->t_pmax = t;
        }
        o->d1max = fmax(o->d1max, vlat_history(s, "cavity_D1 [m]"));
        o->d2max = fmax(o->d2max, vlat_history(s, "cavity_D2 [m]"));
        if (s->step % 10 == 0) {
            if (o->nh == cap) {
                cap *= 2;
                double *a = realloc(o->t, cap * sizeof *a);
                if (a)
                    o->t = a;
                double *b = realloc(o->P, cap * sizeof *b);
                if (b)
                    o->P = b;
                double *c = realloc(o->V, cap * sizeof *c);
                if (c)
                    o->V = c;
                if (!a || !b || !c) {
                    rc = spall_error_set(err, SPALL_ERR_NOMEM, "out of memory (pen_sph)");
                    break;
                }
            }
            o->t[o->nh] = t;
            o->P[o->nh] = P;
            o->V[o->nh] = -im->v[1];
            o->nh++;
        }
        o->p_end = P;
        o->v_end = -im->v[1];
        if (t > 0.0 && !(im->v[1] < 0.0))
            break; /* the sphere stopped: P_max reached (the cavity may still grow) */
    }
    o->secs = omp_get_wtime() - t0;
    sim_update_energy(s);
    o->balance = s->energy.balance / e_in;
    sim_destroy(&s);
    if (rc)
        run_free(o);
    return rc;
}

/* Poncelet (C_d = 0.375, R = 21 MPa) P_max + d/2 at v0 (Eq. 4.6, 4.7). */
static int poncelet_nose(double v0, double *out, struct spall_error *err)
{
    struct pen_params pp = {.model = PEN_PONCELET, .d = PEN_D, .rho_p = PEN_RHO_P,
                            .rho_t = 1030.0, .cd = 0.375, .R = 21.0e6};
    struct pen_result res;
    int rc = pen_poncelet(&pp, v0, 0, NULL, NULL, NULL, &res, err);
    *out = res.p_max + 0.5 * PEN_D;
    return rc;
}

static void run_info(struct vreport *r, const char *what, const struct pen_sph_run *o)
{
    vreport_info(r,
                 "%s: %zu particles, P_max = %.2f um at %.0f ns after contact (P_max/d = %.2f), "
                 "end: P = %.2f um, V = %.0f m/s; cavity at 15 um: D1max %.2f um, D2max %.2f um; "
                 "energy balance %.2g of the input; %.0f s",
                 what, o->n, o->pmax * 1e6, o->t_pmax * 1e9, o->pmax / PEN_D, o->p_end * 1e6,
                 o->v_end, o->d1max * 1e6, o->d2max * 1e6, o->balance, o->secs);
}

int pen_case_sph_gelatin(struct vreport *r, struct spall_error *err)
{
    struct pen_sph_run o = {0};
    int rc = pen_sph_run(1290.0, 20.0e6, 0.75e-6, 1.0, 450.0e-9, &o, err);
    if (rc)
        return rc;
    run_info(r, "1290 m/s, E = 20 MPa, dx1 = 0.75 um (d/10)", &o);
    vreport_series(r, "P(t), 1290 m/s", "t after contact [s]", "P [m]", "SPH (axisymmetric)",
                   VSERIES_LINE, o.t, o.P, o.nh, err);
    vreport_marker(r, "P(t), 1290 m/s", "experiment ~67 um", VSERIES_YMARK, 67.0e-6, err);
    double pn = 0.0;
    if ((rc = poncelet_nose(1290.0, &pn, err)))
        goto out;
    if ((rc = vreport_check(r, "P_max, 1290 m/s", "m", 67.0e-6, o.pmax, 0.10, true,
                            "experiment ~67 um (Veysset et al., seed 004 sec. 4.4.2.1)",
                            "10 %: the thesis' SPH matched the experiment within its scatter",
                            err)))
        goto out;
    if (!r->checks[r->n - 1].pass)
        vreport_mark_gap(r, "GAP: docs/validation.md (pen-sph-gelatin)");
    if ((rc = vreport_check(r, "time of P_max after contact", "s", 225.0e-9, o.t_pmax, 25.0e-9,
                            false, "experiment: P_max reached 200-250 ns after impact",
                            "the experimental window", err)))
        goto out;
    if (!r->checks[r->n - 1].pass)
        vreport_mark_gap(r, "GAP: docs/validation.md (pen-sph-gelatin)");
    if ((rc = vreport_check(r, "P_max/d vs Poncelet + d/2, 1290 m/s", "1", pn / PEN_D,
                            o.pmax / PEN_D, 0.10, true,
                            "Poncelet C_d = 0.375, R = 21 MPa, Eq. 4.6 + d/2 (Eq. 4.7)",
                            "10 %: issue 7", err)))
        goto out;
    if (!r->checks[r->n - 1].pass)
        vreport_mark_gap(r, "GAP: docs/validation.md (pen-sph-gelatin)");
out:
    run_free(&o);
    return rc;
}

int pen_case_sph_sweep(struct vreport *r, struct spall_error *err)
{
    static const double v0s[4] = {200.0, 700.0, 1050.0, 1420.0};
    static const double tend[4] = {200e-9, 400e-9, 450e-9, 450e-9};
    for (int k = 0; k < 4; k++) {
        struct pen_sph_run o = {0};
        int rc = pen_sph_run(v0s[k], 20.0e6, 0.75e-6, 1.0, tend[k], &o, err);
        if (rc)
            return rc;
        char what[96], q[96];
        snprintf(what, sizeof what, "%.0f m/s, E = 20 MPa, dx1 = 0.75 um (d/10)", v0s[k]);
        run_info(r, what, &o);
        run_free(&o);
        double pn = 0.0;
        if ((rc = poncelet_nose(v0s[k], &pn, err)))
            return rc;
        snprintf(q, sizeof q, "P_max/d vs Poncelet + d/2, %.0f m/s", v0s[k]);
        if ((rc = vreport_check(r, q, "1", pn / PEN_D, o.pmax / PEN_D, 0.10, true,
                                "Poncelet C_d = 0.375, R = 21 MPa, Eq. 4.6 + d/2",
                                "10 %: issue 7", err)))
            return rc;
        if (!r->checks[r->n - 1].pass)
            vreport_mark_gap(r, "GAP: docs/validation.md (pen-sph-gelatin-sweep)");
    }
    return SPALL_OK;
}

int pen_case_sph_modulus(struct vreport *r, struct spall_error *err)
{
    static const double Es[4] = {1.0e6, 10.0e6, 20.0e6, 40.0e6};
    double pm[4];
    for (int k = 0; k < 4; k++) {
        struct pen_sph_run o = {0};
        int rc = pen_sph_run(1290.0, Es[k], 0.75e-6, 1.0, 450.0e-9, &o, err);
        if (rc)
            return rc;
        char what[96];
        snprintf(what, sizeof what, "1290 m/s, E = %.0f MPa, dx1 = 0.75 um", Es[k] * 1e-6);
        run_info(r, what, &o);
        pm[k] = o.pmax;
        run_free(&o);
    }
    bool mono = pm[0] > pm[1] && pm[1] > pm[2] && pm[2] > pm[3];
    int rc = vreport_check_true(r, "P_max decreases as E grows (1, 10, 20, 40 MPa)", mono,
                                "seed 004 Fig. 4.13 / Table 4.5; sec. 4.6.1 (a stiffer target "
                                "stops the projectile more quickly)",
                                "the thesis' trend", err);
    if (!rc && !mono)
        vreport_mark_gap(r, "GAP: docs/validation.md (pen-sph-gelatin-modulus)");
    if (rc)
        return rc;
    /* Fig. 4.13 (b): case 2 (E = 20 MPa) has the smallest error vs ~67 um */
    bool closest = true;
    for (int k = 0; k < 4; k++)
        if (k != 2 && fabs(pm[k] - 67.0e-6) < fabs(pm[2] - 67.0e-6))
            closest = false;
    rc = vreport_check_true(r, "E = 20 MPa closest to the experiment's 67 um", closest,
                            "seed 004 Fig. 4.13 (b)", "the thesis' choice of E", err);
    if (!rc && !closest)
        vreport_mark_gap(r, "GAP: docs/validation.md (pen-sph-gelatin-modulus)");
    return rc;
}

/* Largest |P_a(t) - P_b(t)| over the common time span (b interpolated
 * linearly at a's samples), relative to b's P_max. */
static double history_gap(const struct pen_sph_run *a, const struct pen_sph_run *b)
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

int pen_case_sph_convergence(struct vreport *r, struct spall_error *err)
{
    struct pen_sph_run a = {0}, b = {0}, c = {0};
    int rc = pen_sph_run(1290.0, 20.0e6, 0.75e-6, 1.0, 300.0e-9, &a, err);
    if (!rc)
        rc = pen_sph_run(1290.0, 20.0e6, 0.5e-6, 1.0, 300.0e-9, &b, err);
    if (!rc)
        rc = pen_sph_run(1290.0, 20.0e6, 0.75e-6, 0.5, 300.0e-9, &c, err);
    if (rc)
        goto out;
    run_info(r, "d/10, full width", &a);
    run_info(r, "d/15, full width", &b);
    run_info(r, "d/10, half width (outer levels to 72 um)", &c);
    if ((rc = vreport_check(r, "P_max d/10 vs d/15", "m", b.pmax, a.pmax, 0.05, true,
                            "this model at d/15", "5 %: resolution study", err)))
        goto out;
    if (!r->checks[r->n - 1].pass)
        vreport_mark_gap(r, "GAP: docs/validation.md (pen-sph-gelatin-convergence)");
    if ((rc = vreport_check(r, "P_max half vs full width (d/10)", "m", a.pmax, c.pmax, 0.02, true,
                            "this model, full width", "2 %: the far field must not matter",
                            err)))
        goto out;
    if (!r->checks[r->n - 1].pass)
        vreport_mark_gap(r, "GAP: docs/validation.md (pen-sph-gelatin-convergence)");
    if ((rc = vreport_check(r, "max |P(t) d/10 - P(t) d/15| / P_max(d/15)", "1", 0.0,
                            history_gap(&a, &b), 0.05, false, "this model at d/15",
                            "5 %: the whole P(t), not only its maximum", err)))
        goto out;
    if (!r->checks[r->n - 1].pass)
        vreport_mark_gap(r, "GAP: docs/validation.md (pen-sph-gelatin-convergence)");
    if ((rc = vreport_check(r, "max |P(t) half - P(t) full width| / P_max", "1", 0.0,
                            history_gap(&c, &a), 0.02, false, "this model, full width",
                            "2 %: the far field must not matter", err)))
        goto out;
    if (!r->checks[r->n - 1].pass)
        vreport_mark_gap(r, "GAP: docs/validation.md (pen-sph-gelatin-convergence)");
out:
    run_free(&a);
    run_free(&b);
    run_free(&c);
    return rc;
}
