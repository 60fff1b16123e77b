/* Tests for the macro-particle model (src/models/macroparticle/): calibration
 * formulas, the Mie kernel, the counter-based random numbers, bitwise
 * independence of the thread count (Langevin + plasticity + neighbour
 * rebuilds) and deck errors. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "core/particles.h"
#include "core/sim.h"
#include "io/deck.h"
#include "io/deck_build.h"
#include "models/macroparticle/macro_calib.h"
#include "models/macroparticle/macro_pair.h"
#include "core/model.h"
#include "spall/error.h"

#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static struct macro_calib al(double r0)
{
    struct macro_calib c;
    memset(&c, 0, sizeof c);
    c.rho = 2700.0;
    c.atom_mass = 26.98 * MACRO_AMU;
    c.e0 = 3.39 * MACRO_EV;
    c.p = 4;
    c.q = 9;
    c.r0 = r0;
    return c;
}

static void test_calibration(void **state)
{
    (void)state;
    struct spall_error err = {0};
    struct macro_calib a = al(1e-3), b = al(3e-3);
    assert_int_equal(macro_calibrate(&a, &err), SPALL_OK);
    assert_int_equal(macro_calibrate(&b, &err), SPALL_OK);
    /* Eq. 15 is independent of r0 and equals phi''/(2 r0) */
    assert_true(fabs(a.E / b.E - 1.0) < 1e-12);
    double e15 = macro_eq15_modulus(2700.0, 26.98 * MACRO_AMU, 3.39 * MACRO_EV, 4, 9);
    assert_true(fabs(a.E / e15 - 1.0) < 1e-12);
    assert_true(fabs(a.D - a.p_atom / 6.0) < 1e-12 * a.D);
    /* Table 1, Al p=4 q=9 with e0 = 3.36 eV: 68.8 GPa */
    double t1 = macro_eq15_modulus(2700.0, 26.98 * MACRO_AMU, 3.36 * MACRO_EV, 4, 9);
    assert_true(fabs(t1 / 68.8e9 - 1.0) < 0.002);
    /* mass: N_atom m agrees with rho r0^3/sqrt2 to the 0.74 rounding */
    assert_true(fabs(a.n_atom * a.atom_mass / a.mass - 1.0) < 1e-3);
    struct macro_calib bad = al(1e-3);
    bad.q = 3;
    assert_int_equal(macro_calibrate(&bad, &err), SPALL_ERR_PHYSICS);
    assert_non_null(strstr(err.msg, "exponents"));
}

static void test_mie_kernel(void **state)
{
    (void)state;
    struct macro_pair w = {.D = 2.0, .p = 4, .q = 9, .r0 = 1.0, .r_on = 1.2, .r_c = 1.35,
                           .e_y = INFINITY, .h = 0.0, .ip = 4, .iq = 9};
    double e, f, e1, f1, e2, f2;
    macro_mie(&w, 1.0, &e, &f);
    assert_true(fabs(e + 2.0) < 1e-12);
    assert_true(fabs(f) < 1e-12);
    double h = 1e-5;
    macro_mie(&w, 1.0 - h, &e1, &f1);
    macro_mie(&w, 1.0 + h, &e2, &f2);
    double k = (f1 - f2) / (2.0 * h);
    assert_true(fabs(k / (2.0 * 4 * 9) - 1.0) < 1e-6); /* phi'' = D p q / r0^2 */
    /* force = -dphi/dr, also inside the taper */
    for (double r = 0.9; r < 1.34; r += 0.037) {
        macro_mie(&w, r - h, &e1, &f1);
        macro_mie(&w, r + h, &e2, &f2);
        macro_mie(&w, r, &e, &f);
        assert_true(fabs(-(e2 - e1) / (2.0 * h) - f) < 1e-6 * (1.0 + fabs(f)));
    }
    macro_mie(&w, 1.35 - 1e-9, &e, &f);
    assert_true(fabs(e) < 1e-12 && fabs(f) < 1e-6); /* continuous at r_c */
    /* non-integer path agrees with the integer one */
    struct macro_pair w2 = w;
    w2.ip = w2.iq = 0;
    macro_mie(&w2, 1.1, &e1, &f1);
    macro_mie(&w, 1.1, &e2, &f2);
    assert_true(fabs(e1 - e2) < 1e-12 && fabs(f1 - f2) < 1e-12);
}

/* The chunked pair law of the force loop (macro_mie_chunk) gives the bits
 * of macro_mie at every distance inside the cut-off, taper included, on
 * each of its paths (4-9 and 6-12 unrolled, other integers, non-integer
 * exponents) and a partial chunk. */
static void test_mie_chunk_bitwise(void **state)
{
    (void)state;
    struct macro_pair w = {.D = 0.914277, .p = 4, .q = 9, .r0 = 6.187e-4, .r_on = 1.2 * 6.187e-4,
                           .r_c = 1.35 * 6.187e-4, .e_y = INFINITY, .h = 0.0, .ip = 4, .iq = 9};
    for (int variant = 0; variant < 4; variant++) {
        struct macro_pair v = w;
        if (variant == 1) { /* non-integer exponents: pow() in both */
            v.p = 4.5;
            v.q = 9.25;
            v.ip = v.iq = 0;
        } else if (variant == 2) { /* Lennard-Jones' exponents (their own loop) */
            v.p = 6;
            v.q = 12;
            v.ip = 6;
            v.iq = 12;
        } else if (variant == 3) { /* other integers: powers array by array */
            v.p = 4;
            v.q = 10;
            v.ip = 4;
            v.iq = 10;
        }
        const size_t nb = MACRO_CHUNK - 3;
        double r[MACRO_CHUNK], phi[MACRO_CHUNK], fr[MACRO_CHUNK];
        int tapered = 0;
        for (size_t k = 0; k < nb; k++) {
            r[k] = v.r0 * (0.85 + 0.4999 * (double)k / (double)nb);
            tapered += r[k] > v.r_on;
        }
        assert_true(tapered > 5);
        macro_mie_chunk(&v, nb, r, phi, fr);
        for (size_t k = 0; k < nb; k++) {
            double e1, f1;
            macro_mie(&v, r[k], &e1, &f1);
            assert_memory_equal(&e1, &phi[k], sizeof e1);
            assert_memory_equal(&f1, &fr[k], sizeof f1);
        }
    }
}

/* The pair values of the once-per-pair loop (macro_mie_pairs: energy and
 * force in one loop for the written-out exponents, the switch's pairs made
 * again) are macro_mie's, halved and divided, bit for bit, on each path, at
 * distances below the switch, inside it and beyond the cut-off, and +0 both
 * for the pairs that do not count (beyond the list radius, coincident,
 * elastic distance at or beyond r_c or not positive). */
static void test_mie_pairs_bitwise(void **state)
{
    (void)state;
    const double r0 = 6.187e-4;
    for (int variant = 0; variant < 4; variant++) {
        static const double ex[4][2] = {{4, 9}, {6, 12}, {4, 10}, {4.5, 9.25}};
        const bool whole = variant < 3;
        struct macro_pair v = {.D = 0.914277, .p = ex[variant][0], .q = ex[variant][1],
                               .r0 = r0, .r_on = 1.2 * r0, .r_c = 1.35 * r0, .e_y = INFINITY,
                               .ip = whole ? (int)ex[variant][0] : 0,
                               .iq = whole ? (int)ex[variant][1] : 0};
        const size_t nb = MACRO_CHUNK - 1;
        const double rlist2 = (1.45 * r0) * (1.45 * r0);
        double r2[MACRO_CHUNK], rd[MACRO_CHUNK], re[MACRO_CHUNK], ph[MACRO_CHUNK],
            c[MACRO_CHUNK];
        int tapered = 0, out = 0;
        for (size_t k = 0; k < nb; k++) {
            rd[k] = r0 * (0.85 + 0.7 * (double)k / (double)nb); /* to 1.55 r0 */
            r2[k] = rd[k] * rd[k];
            re[k] = k % 5 == 3 ? rd[k] - 0.01 * r0 : rd[k]; /* a plastic offset */
            tapered += re[k] > v.r_on && re[k] < v.r_c;
        }
        r2[7] = 0.0;        /* coincident */
        re[11] = -1e-9;     /* elastic distance not positive */
        re[13] = v.r_c;     /* at the cut-off */
        assert_true(tapered > 5);
        macro_mie_pairs(&v, nb, r2, rd, re, rlist2, ph, c);
        for (size_t k = 0; k < nb; k++) {
            double e, f, pe = 0.0, pc = 0.0;
            macro_mie(&v, re[k], &e, &f);
            if (r2[k] < rlist2 && r2[k] != 0.0 && re[k] < v.r_c && re[k] > 0.0) {
                pe = 0.5 * e;
                pc = -f / rd[k];
            } else {
                out++;
            }
            assert_memory_equal(&pe, &ph[k], sizeof pe);
            assert_memory_equal(&pc, &c[k], sizeof pc);
        }
        assert_true(out > 5);
    }
}

static void test_gauss(void **state)
{
    (void)state;
    double s = 0, s2 = 0, g[3], g2[3];
    const int n = 20000;
    for (int k = 0; k < n; k++) {
        macro_gauss3(7, (uint64_t)k, 3, 5, g);
        for (int d = 0; d < 3; d++) {
            s += g[d];
            s2 += g[d] * g[d];
        }
    }
    s /= 3.0 * n;
    s2 /= 3.0 * n;
    assert_true(fabs(s) < 0.03);
    assert_true(fabs(s2 - 1.0) < 0.03);
    /* a pure function of its key; different keys differ */
    macro_gauss3(7, 11, 3, 5, g);
    macro_gauss3(7, 11, 3, 5, g2);
    assert_memory_equal(g, g2, sizeof g);
    macro_gauss3(7, 11, 5, 3, g2);
    assert_true(g[0] != g2[0]);
}

static const char *const BLOCK =
    "model: {type: macroparticle, damping: pairwise, mu: 2.0e-3, temperature: 1.0e12}\n"
    "materials:\n"
    "  al: {density: 2700, atomic_mass_u: 26.98, cohesive_energy_ev: 3.39, exponents: [4, 9],\n"
    "       debye_temperature: 428, yield_strain: 0.002, hardening: 0.1}\n"
    "lattice: {type: fcc, spacing: 1.0e-3}\n"
    "geometry:\n"
    "  block: {box: {min: [0, 0, 0], max: [11.3e-3, 11.3e-3, 14.1e-3]}}\n"
    "body: {geometry: block, material: al}\n"
    "groups:\n"
    "  top: {box: {min: [-1, -1, 13.2e-3], max: [1, 1, 1]}}\n"
    "  bottom: {box: {min: [-1, -1, -1], max: [1, 1, 0.3e-3]}}\n"
    "boundary_conditions:\n"
    "  - {group: top, type: velocity, components: [z], value: 40.0}\n"
    "  - {group: bottom, type: fixed}\n"
    "run: {steps: 120, seed: 99}\n";

static void run_block(int threads, double **xout, size_t *n, double *builds, double *plastic)
{
    omp_set_num_threads(threads);
    struct spall_error err = {0};
    struct deck *d = NULL;
    struct sim *s = NULL;
    struct run_output ro;
    assert_int_equal(deck_load_string(&d, "block", BLOCK, &err), SPALL_OK);
    int rc = deck_build_sim(d, &s, &ro, &err);
    if (rc)
        fprintf(stderr, "%s\n", err.msg);
    assert_int_equal(rc, SPALL_OK);
    while (!sim_done(s))
        assert_int_equal(sim_step(s, &err), SPALL_OK);
    *n = s->p->n_owned;
    *xout = malloc(3 * *n * sizeof(double));
    for (int c = 0; c < 3; c++)
        memcpy(*xout + c * *n, s->p->x[c], *n * sizeof(double));
    const char *names[MODEL_HISTORY_MAX];
    double values[MODEL_HISTORY_MAX];
    size_t nh = s->ops->history(s->model, s, names, values);
    for (size_t k = 0; k < nh; k++) {
        if (strcmp(names[k], "neighbor_builds") == 0)
            *builds = values[k];
        if (strcmp(names[k], "plastic_pairs") == 0)
            *plastic = values[k];
    }
    sim_destroy(&s);
    deck_destroy(&d);
}

static void test_threads_bitwise(void **state)
{
    (void)state;
    double *x1 = NULL, *x2 = NULL, b1 = 0, b2 = 0, p1 = 0, p2 = 0;
    size_t n1 = 0, n2 = 0;
    run_block(1, &x1, &n1, &b1, &p1);
    run_block(2, &x2, &n2, &b2, &p2);
    assert_int_equal(n1, n2);
    assert_true(n1 >= 2048); /* above MACRO_OMP_MIN: the force loop runs threaded */
    assert_true(b1 > 1.0);   /* the list was rebuilt during the run */
    assert_true(p1 > 0.0);   /* some pairs went plastic */
    assert_memory_equal(x1, x2, 3 * n1 * sizeof(double));
    free(x1);
    free(x2);
}

/* The small aluminium block every deck-error case starts from; each case
 * changes only the model keys or the material keys it is about. */
static void macro_block_deck(char *buf, size_t cap, const char *model_keys,
                             const char *material_keys)
{
    snprintf(buf, cap,
             "model: {type: macroparticle%s}\nmaterials:\n  al: {density: 2700, %s}\n"
             "lattice: {type: fcc, spacing: 1e-3}\n"
             "geometry:\n  b: {box: {min: [0,0,0], max: [3e-3,3e-3,3e-3]}}\n"
             "body: {geometry: b, material: al}\nrun: {steps: 1}\n",
             model_keys, material_keys);
}

static void test_deck_errors(void **state)
{
    (void)state;
    static const char ok_material[] = "atomic_mass_u: 27, cohesive_energy_ev: 3.39, exponents: [4, 9]";
    const struct {
        const char *model_keys, *material_keys, *want;
    } bad[] = {
        {"", "cohesive_energy_ev: 3.39, exponents: [4, 9]", "atomic_mass_u"},
        {"", "atomic_mass_u: 27, cohesive_energy_ev: 3.39, exponents: [9, 4]", "exponents"},
        {", temperature: 300", ok_material, "damping"},
        {"", "atomic_mass_u: 27, cohesive_energy_ev: 3.39, exponents: [4, 9], youngs_modulus: 7e10",
         "youngs_modulus"},
        {", calibration: chain", ok_material, "calibration"},
    };
    for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++) {
        char text[512];
        macro_block_deck(text, sizeof text, bad[k].model_keys, bad[k].material_keys);
        struct spall_error err = {0};
        struct deck *d = NULL;
        struct sim *s = NULL;
        struct run_output ro;
        assert_int_equal(deck_load_string(&d, "bad", text, &err), SPALL_OK);
        assert_int_not_equal(deck_build_sim(d, &s, &ro, &err), SPALL_OK);
        assert_non_null(strstr(err.msg, bad[k].want));
        sim_destroy(&s);
        deck_destroy(&d);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_calibration),
        cmocka_unit_test(test_mie_kernel),
        cmocka_unit_test(test_mie_chunk_bitwise),
        cmocka_unit_test(test_mie_pairs_bitwise),
        cmocka_unit_test(test_gauss),
        cmocka_unit_test(test_threads_bitwise),
        cmocka_unit_test(test_deck_errors),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
