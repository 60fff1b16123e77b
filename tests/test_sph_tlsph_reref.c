/**
 * @file test_sph_tlsph_reref.c
 * @brief TLSPH re-referencing (model.reference_update, sph_tlsph_reref.c):
 *        an update leaves the material state and the particles bitwise
 *        untouched and gives F = I at the same positions; momentum stays
 *        exact and kinetic + internal energy as good as without updates; a
 *        bar with updates is bitwise the same on 1, 2 and 5 threads and with
 *        the stages run one after the other; the det F guard measures
 *        against the new reference and still stops an inverted one; h
 *        grows where the new neighbourhood is flat (isotropy); a mixed
 *        updated/TLSPH run conserves momentum with updates; bad keys are
 *        refused.
 */
#include "core/particles.h"
#include "core/sim.h"
#include "core/model.h"
#include "core/fields.h"
#include "models/sph/sph.h"
#include "spall/error.h"

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "tests/test_support.h"
#include "tests/test_tlsph_bar.h"
#include "tests/test_sph_two_bodies.h"

#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static void run_to_end(struct sim *s)
{
    struct spall_error err = {0};
    while (!sim_done(s))
        assert_int_equal(sim_step(s, &err), 0);
}

/* The model's counters (reference updates, det F range, h growths, ...). */
static struct sph_stats stats(const struct model *m)
{
    struct sph_stats st;
    sph_stats_get(m, &st);
    return st;
}

/* Component c of the run's stored field @p name (the model's own array). */
static const double *field(const struct sim *s, const char *name, int c)
{
    const double *a = field_stored_data(s->fields, name, c);
    assert_non_null(a);
    return a;
}

/* Everything an update must not change, packed per particle. */
enum { NSTATE = 17 };
static void snapshot(const struct sim *s, double *out)
{
    const struct model *m = s->model;
    const double *S[6], *P = field(s, "pressure", 0), *rho = field(s, "density", 0);
    const double *e = field(s, "internal_energy", 0), *ep = field(s, "plastic_strain", 0);
    for (int c = 0; c < 6; c++)
        S[c] = field(s, "deviatoric_stress", c);
    for (size_t i = 0; i < s->p->n; i++) {
        double *q = out + NSTATE * i;
        for (int d = 0; d < 3; d++) {
            q[d] = s->p->x[d][i];
            q[3 + d] = s->p->v[d][i];
        }
        for (int c = 0; c < 6; c++)
            q[6 + c] = S[c][i];
        q[12] = P[i];
        q[13] = rho[i];
        q[14] = e[i];
        q[15] = ep[i];
        q[16] = sph_plastic_work(m, i);
    }
}

static void test_update_keeps_state(void **state)
{
    (void)state;
    omp_set_num_threads(1);
    struct sim *s = test_tlsph_bar("", 60); /* 60 steps into the impact: plastic foot */
    run_to_end(s);
    struct model *m = s->model;
    const size_t n = s->p->n;
    double *a = malloc(NSTATE * n * sizeof *a), *b = malloc(NSTATE * n * sizeof *b);
    double *f0 = malloc(3 * n * sizeof *f0);
    assert_non_null(a);
    assert_non_null(b);
    assert_non_null(f0);
    struct spall_error err = {0};
    /* a force call on the step's final state first (P from the corrected
     * rho, e): the forces to compare with after the update */
    particles_zero_forces(s->p);
    assert_int_equal(s->ops->compute_forces(m, s, &err), 0);
    snapshot(s, a);
    for (size_t i = 0; i < n; i++)
        for (int d = 0; d < 3; d++)
            f0[3 * i + d] = s->p->f[d][i];
    double epmax = 0.0;
    const double *ep = field(s, "plastic_strain", 0);
    for (size_t i = 0; i < n; i++)
        epmax = fmax(epmax, ep[i]);
    const double kmax0 = stats(m).tl_kmax, jmin0 = stats(m).tl_jmin;
    const size_t pairs0 = sph_tlsph_pairs(m);
    assert_int_equal(sph_tlsph_reref(m, s, &err), 0);
    assert_int_equal(stats(m).tl_rerefs, 1);
    snapshot(s, b);
    assert_memory_equal(a, b, NSTATE * n * sizeof *a);
    /* the force call at the same positions: F = I (B0 B0^-1 to round-off) */
    particles_zero_forces(s->p);
    assert_int_equal(s->ops->compute_forces(m, s, &err), 0);
    double dev = 0.0, fd = 0.0, fs = 0.0;
    for (size_t i = 0; i < n; i++) {
        double F[9];
        sph_tlsph_deformation(m, i, F);
        for (int c = 0; c < 9; c++)
            dev = fmax(dev, fabs(F[c] - (c % 4 == 0 ? 1.0 : 0.0)));
        for (int d = 0; d < 3; d++) {
            fd += fabs(s->p->f[d][i] - f0[3 * i + d]);
            fs += fabs(f0[3 * i + d]);
        }
    }
    print_message("before: max ep %.3f, det F >= %.4f, distortion <= %.4f, %zu pairs; after "
                  "the update: max |F - I| = %.3g, det F >= %.15g, distortion <= %.15g, %zu "
                  "pairs; forces differ by %.3g (L1, relative)\n",
                  epmax, jmin0, kmax0, pairs0, dev, stats(m).tl_jmin, stats(m).tl_kmax,
                  sph_tlsph_pairs(m), fd / fs);
    assert_true(epmax > 0.05 && kmax0 > 1.001); /* the update had something to reset */
    assert_true(dev < 1e-12);
    assert_true(fabs(stats(m).tl_jmin - 1.0) < 1e-12 && fabs(stats(m).tl_kmax - 1.0) < 1e-12);
    /* the predictor-corrector's force call only computes rates: the
     * carried state (S, P from the same rho and e, ...) is still the same */
    snapshot(s, b);
    assert_memory_equal(a, b, NSTATE * n * sizeof *a);
    free(a);
    free(b);
    free(f0);
    sim_destroy(&s);
}

/* A free block set spinning and stretching (test_sph_tlsph.c), 300 steps:
 * momentum to round-off and kinetic + internal energy to 1 %, with updates
 * every 25 steps as without.  Returns the relative energy change. */
static double free_block(const char *extra)
{
    char yaml[1024];
    snprintf(yaml, sizeof yaml,
             "model: {type: tlsph, kernel: wendland, h_factor: 1.005,\n"
             "        viscosity: [0.5, 0.5]%s}\n"
             "materials: {m: {density: 1000, youngs_modulus: 1.0e7, poisson_ratio: 0.3}}\n"
             "lattice: {type: sc, spacing: 1.0e-3, origin: [0.0005, 0.0005, 0.0005]}\n"
             "body: {geometry: {box: {min: [0, 0, 0], max: [0.006, 0.005, 0.004]}}, "
             "material: m}\n"
             "groups: {left: {box: {min: [0, 0, 0], max: [0.002, 1, 1]}},\n"
             "         top: {box: {min: [0.004, 0, 0.002], max: [1, 1, 1]}}}\n"
             "initial_velocity: [{group: left, value: [-1.0, 0.3, 0.2]},\n"
             "                   {group: top, value: [0.8, -0.4, 0.5]}]\n"
             "run: {steps: 300}\n",
             extra);
    omp_set_num_threads(1);
    struct sim *s = test_build_ok(yaml);
    double p0[3], p1[3];
    test_momentum_3d(s, p0);
    const double e0 = test_mech_energy(s);
    run_to_end(s);
    const double e1 = test_mech_energy(s);
    const double pscale = test_momentum_3d(s, p1);
    for (int d = 0; d < 3; d++)
        assert_true(fabs(p1[d] - p0[d]) < 1e-12 * pscale);
    print_message("%s: %zu updates, energy %.9g -> %.9g\n", extra[0] ? extra : "no updates",
                  stats(s->model).tl_rerefs, e0, e1);
    sim_destroy(&s);
    return (e1 - e0) / e0;
}

static void test_conservation(void **state)
{
    (void)state;
    const double d0 = free_block("");
    const double d1 = free_block(", reference_update: {every: 25}");
    assert_true(fabs(d0) < 1e-2);
    assert_true(fabs(d1) < 1e-2);
}

/* x and v of the bar after 150 steps with updates every 20 steps. */
static void bar_state(int threads, const char *extra, bool split, double *xs, size_t nx)
{
    omp_set_num_threads(threads);
    struct sim *s = test_tlsph_bar(extra, 150);
    if (split)
        sph_set_split_loops(s->model);
    run_to_end(s);
    assert_int_equal(stats(s->model).tl_rerefs, 7);
    test_pack_xv(s, xs, nx);
    sim_destroy(&s);
}

static void test_deterministic(void **state)
{
    (void)state;
    enum { NX = 6 * 400 };
    static double ref[NX], got[NX];
    static const char *const tint[2] = {
        " reference_update: {every: 20},",
        " time_integration: leapfrog, hourglass: 1.0, reference_update: {every: 20},"};
    for (int k = 0; k < 2; k++) {
        bar_state(1, tint[k], true, ref, NX);
        assert_true(ref[6 * 250] != 0.0);
        const int threads[3] = {1, 2, 5};
        for (int t = 0; t < 3; t++) {
            bar_state(threads[t], tint[k], false, got, NX);
            assert_memory_equal(ref, got, sizeof ref);
        }
    }
}

/* A 2D TLSPH block whose positions are mapped (compression to 30 % in x,
 * or simple shear gamma = 10) before step 1, with @p extra model keys:
 * the return code of @p steps steps, det F and distortion of the last. */
static int mapped_block(const char *extra, int map, long steps, double *jmin, double *kmax,
                        size_t *updates, char *msg, size_t len)
{
    char yaml[1024];
    snprintf(yaml, sizeof yaml,
             "model: {type: tlsph, plane: strain%s}\n"
             "materials: {m: {density: 1000, youngs_modulus: 1.0e7, poisson_ratio: 0.3}}\n"
             "lattice: {type: square, spacing: 1.0e-3, origin: [0.0005, 0.0005]}\n"
             "body: {geometry: {box: {min: [0, 0], max: [0.006, 0.006]}}, material: m}\n"
             "run: {steps: %ld}\n",
             extra, steps);
    struct sim *s = test_build_ok(yaml);
    for (size_t i = 0; i < s->p->n; i++) {
        if (map == 0)
            s->p->x[0][i] *= 0.3;
        else
            s->p->x[0][i] += (map == 1 ? 10.0 : 2.0) * s->p->x[1][i];
    }
    struct spall_error err = {0};
    int rc = 0;
    while (!rc && !sim_done(s))
        rc = sim_step(s, &err);
    *jmin = stats(s->model).tl_jmin;
    *kmax = stats(s->model).tl_kmax;
    *updates = stats(s->model).tl_rerefs;
    snprintf(msg, len, "%s", err.msg);
    sim_destroy(&s);
    return rc;
}

static void test_guard(void **state)
{
    (void)state;
    omp_set_num_threads(1);
    double j, k;
    size_t nu;
    char msg[SPALL_ERROR_MSG_LEN];
    /* the guard acts in the force call, before the step's update */
    assert_int_equal(mapped_block(", det_f_range: [0.5, 2], reference_update: {every: 1}", 0, 3,
                                  &j, &k, &nu, msg, sizeof msg),
                     SPALL_ERR_UNSTABLE);
    assert_non_null(strstr(msg, "outside det_f_range [0.5, 2]"));
    assert_int_equal(nu, 0);
    /* det F = 0.3 at step 1 (default range), then measured from the
     * compressed configuration: 1 */
    assert_int_equal(mapped_block(", reference_update: {every: 1}", 0, 1, &j, &k, &nu, msg,
                                  sizeof msg),
                     0);
    print_message("compressed, step 1: det F >= %.4f, %zu update\n", j, nu);
    assert_true(fabs(j - 0.3) < 1e-9 && nu == 1);
    assert_int_equal(mapped_block(", reference_update: {every: 1}", 0, 2, &j, &k, &nu, msg,
                                  sizeof msg),
                     0);
    print_message("compressed, step 2: det F >= %.15g\n", j);
    assert_true(fabs(j - 1.0) < 1e-6 && nu == 2);
    /* the distortion trigger: shear gamma = 2 gives (2 + 4)/2 = 3 at step 1
     * > 2.5 -> update -> 1 at step 2 */
    assert_int_equal(mapped_block(", reference_update: {distortion: 2.5}", 2, 2, &j, &k, &nu,
                                  msg, sizeof msg),
                     0);
    print_message("sheared, step 2: distortion <= %.15g, %zu update\n", k, nu);
    assert_true(fabs(k - 1.0) < 1e-6 && nu == 1);
    /* gamma = 10 (distortion 51 > 20): the 6 mm wide block's rows no longer
     * overlap (10 mm shift per row), so the updated reference has no 2D
     * neighbourhood (B0 singular, identity fallback): the guard catches the
     * singular F at the next force call */
    assert_int_equal(mapped_block(", reference_update: {distortion: 20}", 1, 2, &j, &k, &nu,
                                  msg, sizeof msg),
                     SPALL_ERR_UNSTABLE);
    assert_non_null(strstr(msg, "inverted or singular"));
    assert_int_equal(nu, 1);
    /* without the trigger the guard's max_distortion still stops it */
    assert_int_equal(mapped_block(", max_distortion: 20", 1, 2, &j, &k, &nu, msg, sizeof msg),
                     SPALL_ERR_UNSTABLE);
    assert_non_null(strstr(msg, "distortion 51"));
}

/* A 2D block (h = 1.005 dx: support 2.01 dx) stretched 2.2x in x before
 * step 1 and re-referenced after it: with the initial h its x partners
 * leave the support, the new neighbourhood is a column (B0 singular) and
 * the guard stops step 2; the isotropy pass grows h until they are back
 * (F = I at step 2). */
static int stretched_block(const char *upd, size_t *grown, double *hmax, double *jmin,
                           char *msg, size_t len)
{
    char yaml[1024];
    snprintf(yaml, sizeof yaml,
             "model: {type: tlsph, plane: strain, h_factor: 1.005,\n"
             "        reference_update: {every: 1%s}}\n"
             "materials: {m: {density: 1000, youngs_modulus: 1.0e7, poisson_ratio: 0.3}}\n"
             "lattice: {type: square, spacing: 1.0e-3, origin: [0.0005, 0.0005]}\n"
             "body: {geometry: {box: {min: [0, 0], max: [0.006, 0.006]}}, material: m}\n"
             "run: {steps: 2}\n",
             upd);
    struct sim *s = test_build_ok(yaml);
    for (size_t i = 0; i < s->p->n; i++)
        s->p->x[0][i] *= 2.2;
    struct spall_error err = {0};
    int rc = 0;
    while (!rc && !sim_done(s))
        rc = sim_step(s, &err);
    *grown = stats(s->model).tl_hgrown;
    *hmax = 0.0;
    for (size_t i = 0; i < s->p->n; i++)
        *hmax = fmax(*hmax, sph_smoothing_length(s->model, i) / (1.005 * sph_spacing(s->model, i)));
    *jmin = stats(s->model).tl_jmin;
    snprintf(msg, len, "%s", err.msg);
    sim_destroy(&s);
    return rc;
}

static void test_isotropy(void **state)
{
    (void)state;
    omp_set_num_threads(1);
    size_t grown;
    double hmax, jmin;
    char msg[SPALL_ERROR_MSG_LEN];
    assert_int_equal(stretched_block(", isotropy: 0", &grown, &hmax, &jmin, msg, sizeof msg),
                     SPALL_ERR_UNSTABLE);
    print_message("isotropy 0: %s\n", msg);
    assert_non_null(strstr(msg, "inverted or singular"));
    assert_int_equal(grown, 0);
    assert_int_equal(stretched_block("", &grown, &hmax, &jmin, msg, sizeof msg), 0);
    print_message("isotropy 0.2: %zu growths, max h / h0 = %.3f, det F >= %.15g at step 2\n",
                  grown, hmax, jmin);
    assert_true(grown > 0 && hmax > 1.1 && hmax <= 2.0 + 1e-12);
    assert_true(fabs(jmin - 1.0) < 1e-6);
}

/* Formulation per body (sph_forms.c): an updated-form target and a TLSPH
 * projectile (re-referenced every 50 steps) collide through the interface
 * penalty (the deck of test_sph_forms.c): momentum to round-off, energy to
 * 1 %, and the updated list keeps its own radius (with the skin) across
 * the TLSPH updates. */
static void test_mixed_bodies(void **state)
{
    (void)state;
    omp_set_num_threads(1);
    struct sim *s = test_two_bodies("sph", ", interface: bodies, body_formulation: {proj: total},\n"
                                    "        reference_update: {every: 50}",
                                    10.0, 0.0);
    assert_non_null(s);
    const struct model *m = s->model;
    double P0[2], P[2], dp = 0.0;
    test_momentum_2d(s, P0);
    const double ke0 = s->energy.kinetic;
    struct spall_error err = {0};
    size_t contact = 0;
    while (!sim_done(s)) {
        assert_int_equal(sim_step(s, &err), 0);
        test_momentum_2d(s, P);
        for (int d = 0; d < 2; d++)
            dp = fmax(dp, fabs(P[d] - P0[d]) / fabs(P0[1]));
        const struct sph_stats st = stats(m);
        contact = st.iface_pairs > contact ? st.iface_pairs : contact;
        double hmax = 0.0;
        for (size_t i = 0; i < s->p->n; i++)
            hmax = fmax(hmax, sph_smoothing_length(m, i));
        assert_true(st.nl_radius > 1.1 * st.qmax * hmax); /* skin 0.2 kept */
    }
    sim_update_energy(s);
    print_message("mixed: %zu updates, %ld steps, |dP|/P0 %.3g, energy %.4g of KE0\n",
                  stats(m).tl_rerefs, s->step, dp, s->energy.balance / ke0);
    assert_true(stats(m).tl_rerefs >= 2 && contact > 0);
    assert_true(dp < 1e-12);
    assert_true(fabs(s->energy.balance / ke0) < 1e-2);
    sim_destroy(&s);
}

static void refused_form(const char *type, const char *model_extra, const char *needle)
{
    char yaml[1024];
    snprintf(yaml, sizeof yaml,
             "model: {type: %s, plane: strain%s}\n"
             "materials: {m: {density: 1000, youngs_modulus: 1.0e7, poisson_ratio: 0.3}}\n"
             "lattice: {type: square, spacing: 1.0e-3, origin: [0.0005, 0.0005]}\n"
             "body: {geometry: {box: {min: [0, 0], max: [0.004, 0.004]}}, material: m}\n"
             "run: {steps: 1}\n",
             type, model_extra);
    test_deck_refused(yaml, needle);
}

static void refused(const char *model_extra, const char *needle)
{
    refused_form("tlsph", model_extra, needle);
}

static void test_refused(void **state)
{
    (void)state;
    refused(", reference_update: {every: 0}", "every");
    refused(", reference_update: {every: 2.5}", "every");
    refused(", reference_update: {distortion: 1}", "expected k > 1");
    refused(", reference_update: {distortion: 0.5}", "distortion");
    refused(", max_distortion: 10, reference_update: {distortion: 20}",
            "expected k < max_distortion (10)");
    refused(", reference_update: {}", "names no trigger");
    refused(", reference_update: {evry: 3}", "unknown key 'evry'");
    refused(", reference_update: {every: 3, isotropy: 1.5}", "isotropy");
    refused(", reference_update: 5", "every: N and/or distortion: k");
    refused_form("sph", ", reference_update: {every: 5}",
                 "re-references total-Lagrangian bodies");
    /* the old key of the formulation names the two models that replace it */
    refused_form("sph", ", formulation: total", "type: tlsph (total Lagrangian)");
    refused_form("tlsph", ", formulation: updated", "type: sph (updated Lagrangian)");
    /* the position is named */
    refused(", reference_update: {distortion: 1}", "bad:1:");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_update_keeps_state),
        cmocka_unit_test(test_conservation),
        cmocka_unit_test(test_deterministic),
        cmocka_unit_test(test_guard),
        cmocka_unit_test(test_isotropy),
        cmocka_unit_test(test_mixed_bodies),
        cmocka_unit_test(test_refused),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
