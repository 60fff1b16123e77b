/* Tests for the public C API (include/spall/sim.h, src/api/sim_api.c). */
#define _POSIX_C_SOURCE 200809L

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/output.h"
#include "spall/sim.h"

#include "tests/test_api_deck.h" /* DECK: the strip */

static double *read_field(const struct spall_sim *s, const char *name, int *ncomp)
{
    struct spall_error err = {0};
    struct spall_field_info fi;
    assert_int_equal(spall_sim_field_info(s, name, &fi, &err), SPALL_OK);
    struct spall_sim_info info;
    spall_sim_get_info(s, &info);
    double *b = malloc(info.particles * (size_t)fi.ncomp * sizeof *b);
    assert_non_null(b);
    assert_int_equal(spall_sim_field_read(s, name, b, info.particles * (size_t)fi.ncomp, &err),
                     SPALL_OK);
    *ncomp = fi.ncomp;
    return b;
}

/* String and file decks give the same run, bit for bit; the driven edge
 * moves at the prescribed velocity; run_to stops at the first step past t. */
static void test_string_file_run(void **state)
{
    (void)state;
    char dir[] = "/tmp/spall_test_api_XXXXXX";
    assert_non_null(mkdtemp(dir));
    char path[64];
    snprintf(path, sizeof path, "%s/strip.yaml", dir);
    FILE *fp = fopen(path, "w");
    assert_non_null(fp);
    fputs(DECK, fp);
    fclose(fp);
    struct spall_error err = {0};
    struct spall_sim *a = NULL, *b = NULL;
    assert_int_equal(spall_sim_create_string(&a, DECK, "strip.yaml", &err), SPALL_OK);
    assert_int_equal(spall_sim_create_file(&b, path, &err), SPALL_OK);
    remove(path);
    remove(dir);
    struct spall_sim_info ia;
    spall_sim_get_info(a, &ia);
    assert_int_equal(ia.dim, 2);
    assert_string_equal(ia.model, "lattice");
    assert_true(ia.particles > 50 && ia.dt > 0.0);
    assert_int_equal(spall_sim_run_to(a, 2.0e-6, &err), SPALL_OK);
    spall_sim_get_info(a, &ia);
    assert_true(ia.time >= 2.0e-6 && ia.time - ia.dt < 2.0e-6);
    assert_int_equal(spall_sim_step(b, ia.step, &err), SPALL_OK);
    int nc = 0, nc2 = 0;
    double *xa = read_field(a, "position", &nc), *xb = read_field(b, "position", &nc2);
    assert_int_equal(nc, 2);
    assert_memory_equal(xa, xb, ia.particles * 2 * sizeof *xa);
    double *v = read_field(a, "velocity", &nc), *x0 = read_field(a, "reference_position", &nc2);
    size_t driven = 0;
    for (size_t i = 0; i < ia.particles; i++)
        if (x0[2 * i] < 0.0006) {
            assert_true(v[2 * i] == 0.6);
            driven++;
        }
    assert_true(driven > 0);
    struct spall_energy e;
    spall_sim_energy(a, &e);
    assert_true(e.kinetic > 0.0 && e.external > 0.0);
    double f[3];
    assert_int_equal(spall_sim_group_reaction(a, "left", f, &err), SPALL_OK);
    assert_true(f[0] > 0.0); /* pushing the strip in +x */
    assert_int_equal(spall_sim_run(a, &err), SPALL_OK);
    spall_sim_get_info(a, &ia);
    assert_true(ia.done);
    free(xa), free(xb), free(v), free(x0);
    spall_sim_destroy(&a);
    spall_sim_destroy(&b);
    assert_null(a);
}

/* DECK with its text @p from replaced by @p to, into @p out. */
static void replaced(char *out, size_t len, const char *from, const char *to)
{
    const char *at = strstr(DECK, from);
    assert_non_null(at);
    snprintf(out, len, "%.*s%s%s", (int)(at - DECK), DECK, to, at + strlen(from));
}

/* The set-up checks of spall run reach API users: a large run is a
 * warning with the estimate (silenced by run.allow: [cost]), a run far
 * beyond a day of the machine is refused at the deck key. */
static void test_setup_warnings(void **state)
{
    (void)state;
    struct spall_error err = {0};
    struct spall_sim *s = NULL;
    char deck[2048];
    assert_int_equal(spall_sim_create_string(&s, DECK, "strip.yaml", &err), SPALL_OK);
    assert_int_equal(spall_sim_warning_count(s), 0);
    assert_null(spall_sim_warning(s, 0));
    assert_non_null(strstr(spall_sim_estimate(s), "particles x"));
    spall_sim_destroy(&s);

    /* ~1e9 steps of ~120 particles: above the warning level (1e11
     * particle-steps), below the refusal (1e13) */
    replaced(deck, sizeof deck, "run: {end_time: 4.0e-6}", "run: {end_time: 400.0}");
    assert_int_equal(spall_sim_create_string(&s, deck, "large.yaml", &err), SPALL_OK);
    assert_int_equal(spall_sim_warning_count(s), 1);
    assert_non_null(strstr(spall_sim_warning(s, 0), "large.yaml:"));
    assert_non_null(strstr(spall_sim_warning(s, 0), "a large run"));
    assert_non_null(strstr(spall_sim_warning(s, 0), "run.allow: [cost]"));
    spall_sim_destroy(&s);

    replaced(deck, sizeof deck, "run: {end_time: 4.0e-6}",
             "run: {end_time: 400.0, allow: [cost]}");
    assert_int_equal(spall_sim_create_string(&s, deck, "allowed.yaml", &err), SPALL_OK);
    assert_int_equal(spall_sim_warning_count(s), 0);
    spall_sim_destroy(&s);

    replaced(deck, sizeof deck, "run: {end_time: 4.0e-6}", "run: {end_time: 4.0e+6}");
    assert_int_equal(spall_sim_create_string(&s, deck, "huge.yaml", &err), SPALL_ERR_INPUT);
    assert_null(s);
    assert_non_null(strstr(err.msg, "huge.yaml:"));
    assert_non_null(strstr(err.msg, "far beyond a day"));
}

/* Errors come back with messages and positions, never an exit. */
static void test_errors(void **state)
{
    (void)state;
    struct spall_error err = {0};
    struct spall_sim *s = (struct spall_sim *)&err; /* must be reset to NULL */
    char bad[2048];
    snprintf(bad, sizeof bad, "%s", DECK);
    char *p = strstr(bad, "spacing: 1.0e-3");
    memcpy(p, "spacing: -1e-03", 15);
    assert_int_equal(spall_sim_create_string(&s, bad, "bad.yaml", &err), SPALL_ERR_INPUT);
    assert_null(s);
    assert_non_null(strstr(err.msg, "bad.yaml:5:"));
    assert_non_null(strstr(err.msg, "spacing"));
    assert_int_equal(spall_sim_create_file(&s, "/nonexistent/deck.yaml", &err), SPALL_ERR_INPUT);
    assert_non_null(strstr(err.msg, "/nonexistent/deck.yaml"));

    assert_int_equal(spall_sim_create_string(&s, DECK, NULL, &err), SPALL_OK);
    double buf[4];
    assert_int_equal(spall_sim_field_read(s, "velocty", buf, 4, &err), SPALL_ERR_INPUT);
    assert_non_null(strstr(err.msg, "velocity"));
    assert_int_equal(spall_sim_field_read(s, "velocity", buf, 4, &err), SPALL_ERR_INPUT);
    assert_non_null(strstr(err.msg, "needs"));
    assert_int_equal(spall_sim_group_reaction(s, "middle", buf, &err), SPALL_ERR_INPUT);
    assert_int_equal(spall_sim_step(s, -1, &err), SPALL_ERR_INPUT);
    assert_int_equal(spall_sim_write_frame(s, &err), SPALL_ERR_INPUT);
    /* the registry listed by index agrees with look-up by name */
    size_t n = spall_sim_field_count(s);
    assert_true(n >= 4);
    for (size_t k = 0; k < n; k++) {
        struct spall_field_info a, b;
        assert_int_equal(spall_sim_field_at(s, k, &a, &err), SPALL_OK);
        assert_int_equal(spall_sim_field_info(s, a.name, &b, &err), SPALL_OK);
        assert_int_equal(a.ncomp, b.ncomp);
    }
    spall_sim_destroy(&s);
}

/* Frames on the deck's interval; the last frame holds the state read by the API. */
static void test_output(void **state)
{
    (void)state;
    char dir[] = "/tmp/spall_test_api_out_XXXXXX";
    assert_non_null(mkdtemp(dir));
    struct spall_error err = {0};
    struct spall_sim *s = NULL;
    assert_int_equal(spall_sim_create_string(&s, DECK, NULL, &err), SPALL_OK);
    assert_int_equal(spall_sim_output_open(s, dir, true, &err), SPALL_OK);
    assert_int_equal(spall_sim_run(s, &err), SPALL_OK);
    assert_int_equal(spall_sim_frames(s), 5); /* t = 0, 1, 2, 3, 4 us */
    char h5[128];
    snprintf(h5, sizeof h5, "%s/fields_000004.h5", dir);
    double *data = NULL, t = 0;
    size_t n = 0, nc = 0;
    assert_int_equal(field_frame_read(h5, "velocity", &data, &n, &nc, &t, &err), SPALL_OK);
    int ncomp = 0;
    double *v = read_field(s, "velocity", &ncomp);
    assert_int_equal(nc, 2);
    assert_memory_equal(data, v, n * nc * sizeof *v);
    free(data), free(v);
    spall_sim_destroy(&s);
    char cmd[160];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    assert_int_equal(system(cmd), 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_string_file_run),
        cmocka_unit_test(test_errors),
        cmocka_unit_test(test_setup_warnings),
        cmocka_unit_test(test_output),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
