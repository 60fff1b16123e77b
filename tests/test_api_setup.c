/* Tests for the deck-free set-up of the public C API (include/spall/setup.h,
 * src/api/setup_api.c, src/api/setup_typed.c). */
#define _POSIX_C_SOURCE 200809L

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "spall/setup.h"
#include "spall/sim.h"

#include "tests/test_api_deck.h" /* DECK: the strip, set up by calls below */

/* The same strip by calls: typed helpers and key paths.  @p spacing is the
 * lattice spacing (the 4th call sets it). */
static struct spall_setup *strip_setup(double spacing)
{
    struct spall_error err = {0};
    struct spall_setup *s = NULL;
    assert_int_equal(spall_setup_create(&s, &err), SPALL_OK);
    const struct spall_material polymer = {
        .density = 1140, .youngs_modulus = 3.0e9, .poisson_ratio = 0.3333333333333333};
    const double smin[2] = {-0.0004, -0.0001}, smax[2] = {0.0195, 0.0052};
    const double lmin[2] = {-0.001, -1}, lmax[2] = {0.0006, 1};
    const double rmin[2] = {0.0188, -1}, rmax[2] = {0.021, 1};
    const char *const x[] = {"x"};
    const char *const fields[] = {"position", "velocity"};
    assert_int_equal(spall_setup_model(s, "lattice", &err), SPALL_OK);              /* 1 */
    assert_int_equal(spall_setup_text(s, "model.law", "linear", &err), SPALL_OK);  /* 2 */
    assert_int_equal(spall_setup_text(s, "lattice.type", "triangular", &err), SPALL_OK);
    assert_int_equal(spall_setup_number(s, "lattice.spacing", spacing, &err), SPALL_OK); /* 4 */
    assert_int_equal(spall_setup_material(s, "polymer", &polymer, &err), SPALL_OK);
    assert_int_equal(spall_setup_number(s, "materials.polymer.failure_strain", 1.0, &err),
                     SPALL_OK);
    assert_int_equal(spall_setup_box(s, "strip", 2, smin, smax, &err), SPALL_OK);
    assert_int_equal(spall_setup_body(s, "strip", "polymer", &err), SPALL_OK);
    assert_int_equal(spall_setup_group_box(s, "left", 2, lmin, lmax, &err), SPALL_OK);
    assert_int_equal(spall_setup_group_box(s, "right", 2, rmin, rmax, &err), SPALL_OK);
    assert_int_equal(spall_setup_length(s, "boundary_conditions"), 0);
    assert_int_equal(spall_setup_text(s, "boundary_conditions[0].group", "left", &err),
                     SPALL_OK);
    assert_int_equal(spall_setup_text(s, "boundary_conditions[0].type", "velocity", &err),
                     SPALL_OK);
    assert_int_equal(spall_setup_texts(s, "boundary_conditions[0].components", x, 1, &err),
                     SPALL_OK);
    assert_int_equal(spall_setup_number(s, "boundary_conditions[0].value", 0.6, &err), SPALL_OK);
    assert_int_equal(spall_setup_length(s, "boundary_conditions"), 1);
    assert_int_equal(spall_setup_text(s, "boundary_conditions[1].group", "right", &err),
                     SPALL_OK);
    assert_int_equal(spall_setup_text(s, "boundary_conditions[1].type", "fixed", &err),
                     SPALL_OK);
    assert_int_equal(spall_setup_end_time(s, 4.0e-6, &err), SPALL_OK);
    assert_int_equal(spall_setup_number(s, "output.field_interval", 1.0e-6, &err), SPALL_OK);
    assert_int_equal(spall_setup_texts(s, "output.fields", fields, 2, &err), SPALL_OK);
    assert_int_equal(spall_setup_length(s, "boundary_conditions"), 2);
    assert_int_equal(spall_setup_length(s, "output.fields"), 2);
    return s;
}

static double *read_field(const struct spall_sim *s, const char *name, size_t *len)
{
    struct spall_error err = {0};
    struct spall_field_info fi;
    assert_int_equal(spall_sim_field_info(s, name, &fi, &err), SPALL_OK);
    struct spall_sim_info info;
    spall_sim_get_info(s, &info);
    *len = info.particles * (size_t)fi.ncomp;
    double *b = malloc(*len * sizeof *b);
    assert_non_null(b);
    assert_int_equal(spall_sim_field_read(s, name, b, *len, &err), SPALL_OK);
    return b;
}

/* The run set up by calls is the deck's, bit for bit; one setup makes two
 * equal simulations (the builder's marks do not stick to the setup). */
static void test_same_as_deck(void **state)
{
    (void)state;
    struct spall_error err = {0};
    struct spall_sim *a = NULL, *b = NULL, *c = NULL;
    assert_int_equal(spall_sim_create_string(&a, DECK, "strip.yaml", &err), SPALL_OK);
    struct spall_setup *setup = strip_setup(1.0e-3);
    assert_int_equal(spall_sim_create_setup(&b, setup, &err), SPALL_OK);
    assert_int_equal(spall_sim_create_setup(&c, setup, &err), SPALL_OK);
    spall_setup_destroy(&setup);
    assert_null(setup);
    struct spall_sim *sims[3] = {a, b, c};
    for (int k = 0; k < 3; k++)
        assert_int_equal(spall_sim_run(sims[k], &err), SPALL_OK);
    struct spall_sim_info ia, ib;
    spall_sim_get_info(a, &ia);
    spall_sim_get_info(b, &ib);
    assert_int_equal(ia.particles, ib.particles);
    assert_true(ia.particles > 100);
    assert_int_equal(ia.step, ib.step);
    assert_true(ia.time == ib.time);
    size_t na = 0, nb = 0, nc = 0;
    double *xa = read_field(a, "position", &na), *xb = read_field(b, "position", &nb);
    double *xc = read_field(c, "position", &nc);
    assert_int_equal(na, nb);
    assert_int_equal(na, nc);
    assert_memory_equal(xa, xb, na * sizeof *xa);
    assert_memory_equal(xa, xc, na * sizeof *xa);
    struct spall_energy ea, eb;
    spall_sim_energy(a, &ea);
    spall_sim_energy(b, &eb);
    assert_true(ea.kinetic > 0.0);
    assert_true(ea.kinetic == eb.kinetic && ea.strain == eb.strain);
    free(xa), free(xb), free(xc);
    for (int k = 0; k < 3; k++)
        spall_sim_destroy(&sims[k]);
}

/* Refusals: at the setter for a malformed path, at create for a bad value
 * (the builder's message points at the setter call), never an exit. */
static void test_errors(void **state)
{
    (void)state;
    struct spall_error err = {0};
    struct spall_setup *s = NULL;
    assert_int_equal(spall_setup_create(&s, &err), SPALL_OK);
    const char *bad[] = {"", "a..b", "a.", ".a", "[0]", "a[x]", "a[-1]", "a[1]", "a[0]b"};
    for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++) {
        assert_int_equal(spall_setup_number(s, bad[k], 1.0, &err), SPALL_ERR_INPUT);
        assert_true(strlen(err.msg) > 0);
    }
    assert_int_equal(spall_setup_number(s, "run.end_time", 1.0, &err), SPALL_OK);
    assert_int_equal(spall_setup_number(s, "run.end_time.x", 1.0, &err), SPALL_ERR_INPUT);
    assert_non_null(strstr(err.msg, "not a mapping"));
    assert_string_equal(err.key, "run.end_time.x");
    assert_int_equal(spall_setup_number(s, "run[0]", 1.0, &err), SPALL_ERR_INPUT);
    assert_int_equal(spall_setup_number(s, "run.dt", HUGE_VAL, &err), SPALL_ERR_INPUT);
    assert_int_equal(spall_setup_text(s, "run.dt", NULL, &err), SPALL_ERR_INPUT);
    assert_int_equal(spall_setup_box(s, "g", 4, NULL, NULL, &err), SPALL_ERR_INPUT);
    assert_int_equal(spall_setup_numbers(s, "v", NULL, 2, &err), SPALL_ERR_INPUT);
    assert_int_equal(spall_setup_length(s, "run"), 1);
    assert_int_equal(spall_setup_length(s, "nothing.here"), 0);
    spall_setup_destroy(&s);

    /* a bad value, refused by the deck builder where a deck's would be */
    s = strip_setup(-1e-3);
    struct spall_sim *sim = (struct spall_sim *)&err; /* must be reset to NULL */
    assert_int_equal(spall_sim_create_setup(&sim, s, &err), SPALL_ERR_INPUT);
    assert_null(sim);
    assert_non_null(strstr(err.msg, "spall_setup:4:"));
    assert_non_null(strstr(err.msg, "spacing"));
    /* replacing the value mends it */
    assert_int_equal(spall_setup_number(s, "lattice.spacing", 1.0e-3, &err), SPALL_OK);
    assert_int_equal(spall_sim_create_setup(&sim, s, &err), SPALL_OK);
    spall_sim_destroy(&sim);
    /* an unknown key is reported as in a deck */
    assert_int_equal(spall_setup_number(s, "run.end_tme", 1.0, &err), SPALL_OK);
    assert_int_equal(spall_sim_create_setup(&sim, s, &err), SPALL_ERR_INPUT);
    assert_non_null(strstr(err.msg, "end_tme"));
    spall_setup_destroy(&s);
    spall_setup_destroy(&s);
    assert_int_equal(spall_sim_create_setup(&sim, NULL, &err), SPALL_ERR_INPUT);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_same_as_deck),
        cmocka_unit_test(test_errors),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
