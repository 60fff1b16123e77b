/**
 * @file impact_spall.c
 * @brief Validation case "impact-spall": [Wang2010] sec. 4.2 flyer-plate spall.
 *        Target 5.2 x 0.68 cm hit by a flyer 5.2 x 0.20 cm or 2.6 x 0.20 cm
 *        at 260 m/s; E = 163.24 GPa, sigma_TS = 478.25 MPa, rho = 8900 kg/m^3,
 *        every boundary free.  Deck: examples/impact_spall.
 *
 * Choices (docs/notes/validation-log.md):
 *  - failure criterion: bond failure strain 0.02 (SPALL_EPS_MAX).  The seed
 *    lists sigma_TS = 478.25 MPa and eps_max = 0.10, which disagree
 *    (sigma_TS / E = 0.0029).  With 0.10 nothing breaks (the whole pulse is a
 *    bond strain of 0.0214); with 0.0029 (Eq. 26, a quasi-static strength)
 *    the lattice's ringing and corner releases break ~70 % of the target.  A
 *    spall (dynamic tensile) strength lies well above the quasi-static one;
 *    0.02 sits just below the bond strain of the full reflected tension.
 *  - flyer and target are two bodies (bonds never cross bodies) touching
 *    through the core particle contact (core/contact_particles.h): distance
 *    r0 (no force at t = 0), stiffness = the bond stiffness E r0, repulsive
 *    only, so the interface cannot pull when the flyer's release arrives.
 * Measured after 8 us (two wave transits of the target): the target's
 * particles damaged during the run (fracture density > 0, away from the
 * impact face) -> the crack row (the most damaged row), the spalled-layer
 * thickness on the axis, the share of damage within +-2 rows of the crack
 * (parallel to the far face), the crack's x-extent, and the time the spall
 * plane first breaks vs 1D wave theory.
 */
#include "validation/impact_cases.h"
#include "validation/lattice_cases.h"
#include "validation/validation.h"
#include "validation/vpar.h"

#include "core/contact_particles.h"
#include "core/fields.h"
#include "core/parallel/comm.h"
#include "core/particles.h"
#include "core/sim.h"
#include "spall/error.h"

#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define SPALL_R0 0.2e-3
#define SPALL_H_TARGET 0.0068
#define SPALL_H_FLYER 0.0020
/* bond failure strain: the spall criterion (docs/notes/validation-log.md): between the
 * lattice's spurious tensions (ringing, corner releases) and the bond strain
 * 0.75 v / (2 c_p) = 0.0214 of the full reflected tension at the spall plane */
#define SPALL_EPS_MAX 0.020
/* softening variant: full separation at 1.5 eps_max (a modest tail; our
 * choice, not fitted; 0.04 and the seed's sigma_TS/E -> 0.10 were tried,
 * docs/notes/validation-log.md) */
#define SPALL_SOFT_EF 0.030
#define SPALL_EDGE_ZONE 0.003
#define SPALL_OPEN 1.0e-4
#define SPALL_GAP                                                                                 \
    "gap: besides the spall plane, the corners break: the target's free sides (long flyer) and "   \
    "the impact face under the flyer's edges (short flyer; the spall crack also runs on ~0.3 cm "  \
    "past each flyer edge); see docs/notes/validation-log.md"

int impact_spall_deck(char *buf, size_t len, double flyer_width, double r0, double end_time,
                      double eps_max)
{
    char keys[64];
    snprintf(keys, sizeof keys, "failure_strain: %.17g", eps_max);
    return impact_spall_deck_law(buf, len, flyer_width, r0, end_time, "linear", keys);
}

int impact_spall_deck_law(char *buf, size_t len, double flyer_width, double r0, double end_time,
                          const char *law, const char *fail_keys)
{
    double row = 0.5 * sqrt(3.0) * r0;
    int kt = (int)floor(SPALL_H_TARGET / row + 1e-9);     /* target rows 0..kt-1 */
    int kf = (int)floor(SPALL_H_FLYER / row + 1e-9);      /* flyer rows kt..kt+kf-1 */
    double y_if = (kt - 0.5) * row;                       /* interface, between rows */
    double y_top = (kt + kf - 0.5) * row;
    double x0 = 0.5 * (0.052 - flyer_width), x1 = x0 + flyer_width;
    /* contact stiffness = the bond stiffness k = E r0 of the plane-stress
     * triangular lattice (thickness 2 r0 / sqrt 3): the interface is as
     * stiff in compression as the lattice; distance r0: no force at t = 0 */
    int n = snprintf(buf, len,
                     "title: flyer-plate spall ([Wang2010] sec. 4.2)\n"
                     "model: {type: lattice, law: %s}\n"
                     "materials:\n"
                     "  metal: {density: 8900, youngs_modulus: 163.24e9,\n"
                     "          poisson_ratio: 0.3333333333333333, %s}\n"
                     "lattice: {type: triangular, spacing: %.17g}\n"
                     "geometry:\n"
                     "  target: {box: {min: [-1.0e-5, -1.0e-5], max: [0.05201, %.17g]}}\n"
                     "  flyer: {box: {min: [%.17g, %.17g], max: [%.17g, %.17g]}}\n"
                     "bodies:\n"
                     "  - {geometry: target, material: metal}\n"
                     "  - {geometry: flyer, material: metal}\n"
                     "contact: {distance: %.17g, stiffness: %.17g}\n"
                     "groups: {flyer: flyer}\n"
                     "initial_velocity: [{group: flyer, value: [0, -260.0]}]\n"
                     "run: {end_time: %.17g}\n",
                     law, fail_keys, r0, y_if, x0 - 1e-5, y_if, x1 + 1e-5, y_top, r0, 163.24e9 * r0,
                     end_time);
    return n > 0 && (size_t)n < len ? SPALL_OK : SPALL_ERR_INTERNAL;
}

/* The run's particles by global id, on every rank (vpar.h): the serial
 * order and values on any rank count, so every measurement below is the
 * serial one.  x0, y0, body once; y (current) and the fracture density
 * when measured. */
struct spall_whole {
    size_t n;
    double *x0, *y0, *body, *y;
};

static void spall_whole_free(struct spall_whole *w)
{
    free(w->x0);
    free(w->y0);
    free(w->body);
    free(w->y);
    memset(w, 0, sizeof *w);
}

static int spall_whole_init(const struct sim *s, struct spall_whole *w, struct spall_error *err)
{
    const struct particles *p = s->p;
    memset(w, 0, sizeof *w);
    w->n = vpar_n(s);
    double *b = malloc((p->n ? p->n : 1) * sizeof *b);
    int rc = b ? SPALL_OK : spall_error_set(err, SPALL_ERR_NOMEM, "impact-spall: out of memory");
    if (s->par) /* every rank gathers, or none */
        rc = par_agree(rc, err);
    if (rc)
        return rc;
    for (size_t i = 0; i < p->n; i++)
        b[i] = (double)p->body[i];
    /* vpar_whole agrees over the ranks itself: all fail alike */
    if ((w->x0 = vpar_whole(s, p->x0[0], err)) && (w->y0 = vpar_whole(s, p->x0[1], err)))
        w->body = vpar_whole(s, b, err);
    free(b);
    return w->body ? SPALL_OK : err->code;
}

/* The fracture density of every particle by global id (collective). */
static double *whole_field(const struct sim *s, const struct field_desc *f,
                           struct spall_error *err)
{
    const size_t n = s->p->n;
    double *local = malloc((n ? n : 1) * sizeof *local);
    if (!local) {
        spall_error_set(err, SPALL_ERR_NOMEM, "impact-spall: out of memory");
        return NULL;
    }
    field_gather_f64(f, n, local);
    double *w = vpar_whole(s, local, err);
    free(local);
    return w;
}

/* The opened spall crack, measured from the separation of the material on
 * either side of the crack row kc: per column of width r0 (reference x), the
 * mean vertical displacement of the target rows kc+3..kc+5 minus that of the
 * rows kc-5..kc-3.  The crack is open where this exceeds SPALL_OPEN (0.1 mm,
 * ~4x the largest elastic stretch of those six rows, 6 rows x eps_max/0.75).
 * Returns the length of the open stretch through the flyer's centre [m] and,
 * over that stretch, the spread (max - min) of the columns' crack row (the
 * damage-weighted mean row within +-4 rows of kc) in *row_spread. */
static double open_crack(const struct spall_whole *w, const double *fd, double r0, double row,
                         int kc, double *row_spread)
{
    enum { NB = 512 };
    double up[NB] = {0}, dn[NB] = {0}, wk[NB] = {0}, wt[NB] = {0};
    int nu[NB] = {0}, nd[NB] = {0};
    int nb = (int)floor(0.052 / r0) + 1;
    if (nb > NB)
        nb = NB;
    for (size_t i = 0; i < w->n; i++) {
        if (w->body[i] != 0.0)
            continue;
        int k = (int)lround(w->y0[i] / row);
        int b = (int)floor(w->x0[i] / r0);
        if (b < 0 || b >= nb)
            continue;
        double dy = w->y[i] - w->y0[i];
        if (k >= kc + 3 && k <= kc + 5) {
            up[b] += dy;
            nu[b]++;
        } else if (k >= kc - 5 && k <= kc - 3) {
            dn[b] += dy;
            nd[b]++;
        }
        if (fd[i] > 0.0 && abs(k - kc) <= 4) {
            wt[b] += fd[i];
            wk[b] += fd[i] * k;
        }
    }
    int bc = (int)floor(0.026 / r0);
    int lo = bc, hi = bc - 1;
#define SPALL_IS_OPEN(b)                                                                          \
    (nu[b] > 0 && nd[b] > 0 && up[b] / nu[b] - dn[b] / nd[b] > SPALL_OPEN)
    while (lo - 1 >= 0 && SPALL_IS_OPEN(lo - 1))
        lo--;
    if (SPALL_IS_OPEN(bc)) {
        hi = bc;
        while (hi + 1 < nb && SPALL_IS_OPEN(hi + 1))
            hi++;
    } else {
        lo = bc;
    }
#undef SPALL_IS_OPEN
    double rmin = INFINITY, rmax = -INFINITY;
    for (int b = lo; b <= hi; b++)
        if (wt[b] > 0.0) {
            rmin = fmin(rmin, wk[b] / wt[b]);
            rmax = fmax(rmax, wk[b] / wt[b]);
        }
    *row_spread = hi >= lo && rmax >= rmin ? rmax - rmin : INFINITY;
    return hi >= lo ? (hi - lo + 1) * r0 : 0.0;
}

static int run_spall(struct vreport *r, double flyer_width, const char *label, const char *law,
                     const char *fail_keys, struct spall_error *err)
{
    char deck[2048];
    double r0 = SPALL_R0;
    double row = 0.5 * sqrt(3.0) * r0;
    if (impact_spall_deck_law(deck, sizeof deck, flyer_width, r0, 8.0e-6, law, fail_keys))
        return spall_error_set(err, SPALL_ERR_INTERNAL, "impact-spall: deck buffer too small");
    struct sim *s = NULL;
    double *fd = NULL, *vy = NULL;
    struct spall_whole w = {0};
    int *hist = NULL;
    double *t_first = NULL;
    int rc = vlat_build("impact-spall", deck, &s, err);
    if (rc)
        return rc;
    /* mpirun: the measurements below read the particles by global id */
    if ((rc = vpar_distribute(r, s, err)) || (rc = spall_whole_init(s, &w, err)))
        goto done;
    const struct field_desc *f = field_registry_find(s->fields, "fracture_density");
    if (!f) {
        rc = spall_error_set(err, SPALL_ERR_INTERNAL, "impact-spall: no fracture_density field");
        goto done;
    }
    int kt = (int)floor(SPALL_H_TARGET / row + 1e-9);
    int kf = (int)floor(SPALL_H_FLYER / row + 1e-9);
    hist = calloc((size_t)kt + 1, sizeof *hist);
    t_first = malloc(((size_t)kt + 1) * sizeof *t_first);
    if (!hist || !t_first) {
        rc = spall_error_set(err, SPALL_ERR_NOMEM, "impact-spall: out of memory");
        goto done;
    }
    for (int k = 0; k <= kt; k++)
        t_first[k] = INFINITY;
    /* run, recording when the flyer lets go of the target (no contact pair
     * left) and, every 5 steps, when each row on the axis first breaks */
    const double c_p = sqrt(163.24e9 / (8900.0 * (1.0 - 1.0 / 9.0)));
    const double hf = kf * row, ht = kt * row;
    const int gf = sim_find_group(s, "flyer");
    double v_flyer = NAN; /* flyer's mean velocity at 2 h_f / c (1D: 0) */
    while (!sim_done(s)) {
        if ((rc = sim_step(s, err)))
            goto done;
        if (isnan(v_flyer) && s->t >= 2.0 * hf / c_p && gf >= 0) {
            /* the flyer group is the flyer body (body 1): summed in
             * global-id order, the group's own order */
            if (!(vy = vpar_whole(s, s->p->v[1], err))) {
                rc = err->code;
                goto done;
            }
            double sum = 0.0;
            size_t nf = 0;
            for (size_t i = 0; i < w.n; i++)
                if (w.body[i] == 1.0) {
                    sum += vy[i];
                    nf++;
                }
            v_flyer = nf ? sum / (double)nf : 0.0;
        }
        if (s->step % 5 == 0 && s->t < 4.0e-6) {
            free(fd);
            if (!(fd = whole_field(s, f, err))) {
                rc = err->code;
                goto done;
            }
            for (size_t i = 0; i < w.n; i++) {
                int k = (int)lround(w.y0[i] / row);
                if (k >= 0 && k < kt && fd[i] > 0.0 && !isfinite(t_first[k]) &&
                    fabs(w.x0[i] - 0.026) < 0.25 * flyer_width)
                    t_first[k] = s->t;
            }
        }
    }
    free(fd);
    if (!(fd = whole_field(s, f, err)) || !(w.y = vpar_whole(s, s->p->x[1], err))) {
        rc = err->code;
        goto done;
    }
    sim_update_energy(s);
    /* damage of the target away from the impact face (whose bonds were cut) */
    size_t total = 0;
    for (size_t i = 0; i < w.n; i++) {
        int k = (int)lround(w.y0[i] / row);
        if (k >= 0 && k < kt - 3 && fd[i] > 0.0) {
            hist[k]++;
            total++;
        }
    }
    int kc = 0;
    for (int k = 1; k < kt - 3; k++)
        if (hist[k] > hist[kc])
            kc = k;
    size_t near = 0, off_sides = 0, off_flyer_edges = 0;
    double xmin = INFINITY, xmax = -INFINITY;
    const double fx0 = 0.5 * (0.052 - flyer_width), fx1 = fx0 + flyer_width;
    for (size_t i = 0; i < w.n; i++) {
        int k = (int)lround(w.y0[i] / row);
        if (k >= 0 && k < kt - 3 && fd[i] > 0.0 && abs(k - kc) > 2) {
            double x = w.x0[i];
            /* where the off-plane damage sits: the target's free sides or
             * below the short flyer's edges (corner releases, shear) */
            if (x < SPALL_EDGE_ZONE || x > 0.052 - SPALL_EDGE_ZONE)
                off_sides++;
            else if (flyer_width < 0.05 &&
                     (fabs(x - fx0) < SPALL_EDGE_ZONE || fabs(x - fx1) < SPALL_EDGE_ZONE))
                off_flyer_edges++;
        }
        if (k >= 0 && k < kt - 3 && fd[i] > 0.0 && abs(k - kc) <= 2) {
            near++;
            if (w.x0[i] < xmin)
                xmin = w.x0[i];
            if (w.x0[i] > xmax)
                xmax = w.x0[i];
        }
    }
    /* spalled-layer thickness on the axis, where the 1D wave picture holds
     * (central half of the flyer): the damage-weighted mean row of the
     * damaged particles there within +-2 rows of kc; the crack runs between
     * the two rows that share its broken bonds, i.e. at that mean + 1/2 row */
    double wsum = 0.0, wk = 0.0;
    for (size_t i = 0; i < w.n; i++) {
        int k = (int)lround(w.y0[i] / row);
        if (k >= 0 && k < kt - 3 && fd[i] > 0.0 && abs(k - kc) <= 2 &&
            fabs(w.x0[i] - 0.026) < 0.25 * flyer_width) {
            wsum += fd[i];
            wk += fd[i] * k;
        }
    }
    double thick = wsum > 0.0 ? (wk / wsum + 0.5) * row : 0.0;
    double share = total ? (double)near / (double)total : 0.0;
    double length = near ? xmax - xmin : 0.0;
    double spread = INFINITY;
    double open_len = open_crack(&w, fd, r0, row, kc, &spread);
    /* 1D wave theory ([Wang2010] sec. 4.2): the flyer's release reaches the
     * interface, which cannot pull, at 2 h_f / c; the release from the far
     * face meets the flyer's at h_f from it at (h_t + h_f) / c.  h = rows x
     * row height as discretised, c = sqrt(E / (rho (1 - nu^2))) the
     * plane-stress longitudinal speed of the nu = 1/3 lattice */
    double t_sp = INFINITY;
    for (int k = kc - 2; k <= kc + 2; k++)
        if (k >= 0 && k < kt)
            t_sp = fmin(t_sp, t_first[k]);
    char q[96];
    snprintf(q, sizeof q, "%s: spall starts at (h_t + h_f) / c", label);
    if ((rc = vreport_check(r, q, "s", (ht + hf) / c_p, t_sp, 0.1 * (ht + hf) / c_p, false,
                            "1D elastic waves: the far-face and flyer releases meet at h_f "
                            "from the far face",
                            "10 %: dispersed fronts; the bonds break on the rise of the tension "
                            "(eps_max = 0.02 vs the full 0.0214); first break sampled every 5 steps",
                            err)))
        goto done;
    if (!(fabs(t_sp - (ht + hf) / c_p) <= 0.1 * (ht + hf) / c_p))
        vreport_mark_gap(r, "the spall plane breaks at another time than the 1D waves predict");
    snprintf(q, sizeof q, "%s: spalled layer thickness", label);
    if ((rc = vreport_check(r, q, "m", SPALL_H_FLYER, thick, r0, false,
                            "[Wang2010] sec. 4.2: the spalled layer is as thick as the flyer",
                            "one lattice spacing (the brief's tolerance); the crack sits where "
                            "the release waves from the flyer's back and the target's far face "
                            "meet",
                            err)))
        goto done;
    if (fabs(thick - SPALL_H_FLYER) > r0)
        vreport_mark_gap(r, SPALL_GAP);
    snprintf(q, sizeof q, "%s: opened crack parallel to the far face", label);
    bool parallel = open_len > 0.0 && spread <= 2.0;
    if ((rc = vreport_check_true(r, q, parallel, "[Wang2010] sec. 4.2, Fig. 17",
                                 "along the opened crack the columns' crack row stays within "
                                 "+-1 row (spread <= 2 rows)",
                                 err)))
        goto done;
    if (!parallel)
        vreport_mark_gap(r, SPALL_GAP);
    snprintf(q, sizeof q, "%s: damage concentrated on the spall plane", label);
    if ((rc = vreport_check_true(r, q, total > 0 && share >= 0.8,
                                 "[Wang2010] sec. 4.2, Fig. 17",
                                 ">= 80 % of the target's damage (away from the impact face) "
                                 "within +-2 rows of one row",
                                 err)))
        goto done;
    if (!(total > 0 && share >= 0.8))
        vreport_mark_gap(r, SPALL_GAP);
    if (flyer_width < 0.05) {
        snprintf(q, sizeof q, "%s: opened crack shorter than the flyer", label);
        if ((rc = vreport_check_true(r, q, open_len > 0.0 && open_len < flyer_width,
                                     "[Wang2010] sec. 4.2 (vs MD of Krivtsov)",
                                     "qualitative: the edge release waves of the short flyer "
                                     "shorten the tensile zone; opened = separation > 0.1 mm",
                                     err)))
            goto done;
        if (!(open_len > 0.0 && open_len < flyer_width))
            vreport_mark_gap(r, SPALL_GAP);
    }
    vreport_info(r, "%s flyer %.1f cm: %zu particles, dt = %.3g s; damaged target particles %zu, "
                    "%.0f %% within +-2 rows of row %d (y = %.3f mm), spalled layer %.3f mm, "
                    "damage x-extent there %.2f cm; opened crack %.2f cm, its row spread %.2f rows",
                 label, flyer_width * 100, w.n, s->dt, total, 100 * share, kc, kc * row * 1e3,
                 thick * 1e3, length * 100, open_len * 100, spread);
    vreport_info(r, "%s: flyer's mean velocity at 2 h_f / c = %.3g us: %.1f m/s (1D equal "
                    "impedance: 0, from -260); spall plane first broken at %.3g us; energy "
                    "balance %.3g of the initial energy (broken bonds booked as dissipated)",
                 label, 2e6 * hf / c_p, v_flyer, t_sp * 1e6,
                 s->energy.balance / s->energy.initial_total);
    vreport_info(r, "%s: off-plane damage %zu particles: %zu within %.0f mm of the target's free "
                    "sides, %zu within %.0f mm of the flyer's edges, %zu elsewhere",
                 label, total - near, off_sides, SPALL_EDGE_ZONE * 1e3, off_flyer_edges,
                 SPALL_EDGE_ZONE * 1e3, total - near - off_sides - off_flyer_edges);
done:
    free(fd);
    free(vy);
    spall_whole_free(&w);
    free(hist);
    free(t_first);
    sim_destroy(&s);
    return rc;
}

int impact_case_spall(struct vreport *r, struct spall_error *err)
{
    char keys[128];
    snprintf(keys, sizeof keys, "failure_strain: %.17g", SPALL_EPS_MAX);
    int rc = run_spall(r, 0.052, "long flyer", "linear", keys, err);
    if (!rc)
        rc = run_spall(r, 0.026, "short flyer", "linear", keys, err);
    /* variant: cohesive softening (lattice_softening.h) from the same onset
     * eps_0 = 0.02 to full separation at SPALL_SOFT_EF (docs/notes/validation-log.md) */
    snprintf(keys, sizeof keys, "onset_strain: %.17g, failure_strain: %.17g", SPALL_EPS_MAX,
             SPALL_SOFT_EF);
    if (!rc)
        rc = run_spall(r, 0.026, "short flyer, softening", "softening", keys, err);
    return rc;
}
