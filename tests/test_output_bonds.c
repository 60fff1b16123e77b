/* Tests for the bonds output (output.fields lists `bonds`: io/output_bonds.c):
 * each bond once with its state, beside the field frame; refused for an
 * unbonded model. */
#define _POSIX_C_SOURCE 200809L

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "tests/test_support.h"

#include "core/bond_list.h"
#include "core/model.h"
#include "core/particles.h"
#include "core/sim.h"
#include "io/output.h"
#include "spall/error.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* A 2D plate with a pre-crack through its middle (bonds crossing it start
 * broken); MODEL is the model mapping. */
#define PLATE_DECK(MODEL, MATERIAL)                                                          \
    "model: " MODEL "\n"                                                                     \
    "materials:\n  m: {density: 1000, youngs_modulus: 1.0e9, " MATERIAL "}\n"                \
    "lattice: {type: triangular, spacing: 1.0e-3}\n"                                         \
    "body: {geometry: {box: {min: [0, 0], max: [0.0105, 0.0105]}}, material: m}\n"           \
    "precracks: [{from: [0.00525, -0.001], to: [0.00525, 0.0055]}]\n"                        \
    "run: {steps: 1}\n"

/* Bonds i < j and broken ones, counted from the model's list. */
static void count_bonds(const struct sim *s, size_t *m, size_t *broken)
{
    const struct bond_list *bl = s->ops->bonds ? s->ops->bonds(s->model)
                                               : s->ops->halo_bonds(s->model);
    *m = *broken = 0;
    for (size_t i = 0; i < bl->n; i++)
        for (size_t k = bl->offset[i]; k < bl->offset[i + 1]; k++)
            if ((size_t)bl->partner[k] > i) {
                ++*m;
                *broken += (bl->state[k] & BOND_BROKEN) != 0;
            }
}

static char *slurp(const char *dir, const char *name)
{
    char path[256];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    FILE *f = fopen(path, "rb");
    assert_non_null(f);
    char *b = calloc(1, 1 << 16);
    assert_non_null(b);
    size_t got = fread(b, 1, (1 << 16) - 1, f);
    (void)got;
    fclose(f);
    return b;
}

static void check_model(const char *yaml)
{
    struct sim *s = test_build_ok(yaml);
    size_t m = 0, nbroken = 0;
    count_bonds(s, &m, &nbroken);
    assert_true(m > 100);
    assert_true(nbroken > 0 && nbroken < m);
    char dir[] = "/tmp/spall_bonds_XXXXXX";
    assert_non_null(mkdtemp(dir));
    struct spall_error err = {0};
    struct field_writer *w = NULL;
    const char *names[] = {"velocity", "bonds"};
    assert_int_equal(field_writer_create(&w, dir, s, names, 2, &err), SPALL_OK);
    assert_int_equal(field_writer_write(w, s, &err), SPALL_OK);
    assert_int_equal(field_writer_write(w, s, &err), SPALL_OK);
    char path[256];
    snprintf(path, sizeof path, "%s/bonds_000001.h5", dir);
    double *ij = NULL, *br = NULL, t = -1;
    size_t n = 0, nc = 0;
    assert_int_equal(field_frame_read(path, "connectivity", &ij, &n, &nc, &t, &err), SPALL_OK);
    assert_int_equal(n, m);
    assert_int_equal(nc, 2);
    assert_true(t == s->t);
    assert_int_equal(field_frame_read(path, "broken", &br, &n, &nc, NULL, &err), SPALL_OK);
    assert_int_equal(n, m);
    size_t nb = 0;
    for (size_t k = 0; k < m; k++) {
        assert_true(ij[2 * k] < ij[2 * k + 1]);
        assert_true(ij[2 * k + 1] < (double)s->p->n_owned);
        assert_true(br[k] == 0.0 || br[k] == 1.0);
        nb += br[k] == 1.0;
        /* a broken bond crosses the pre-crack at x = 5.25 mm */
        if (br[k] == 1.0) {
            double xa = s->p->x0[0][(size_t)ij[2 * k]], xb = s->p->x0[0][(size_t)ij[2 * k + 1]];
            assert_true((xa - 0.00525) * (xb - 0.00525) < 0.0);
        }
    }
    assert_int_equal(nb, nbroken);
    /* the index: two Polyline grids on the field frames' positions */
    char *x = slurp(dir, "bonds.xdmf");
    assert_non_null(strstr(x, "TopologyType=\"Polyline\""));
    assert_non_null(strstr(x, "fields_000001.h5:/position"));
    assert_non_null(strstr(x, "<Grid Name=\"bonds_000001\""));
    assert_null(strstr(x, "bonds_000002"));
    free(x);
    free(ij);
    free(br);
    field_writer_destroy(&w);
    sim_destroy(&s);
    char cmd[128];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    assert_int_equal(system(cmd), 0);
}

static void test_lattice(void **state)
{
    (void)state;
    check_model(PLATE_DECK("{type: lattice}", "poisson_ratio: 0.3333333333333333, "
                                              "failure_strain: 1.0"));
}

static void test_peridynamics(void **state)
{
    (void)state;
    check_model(PLATE_DECK("{type: peridynamics}", "critical_stretch: 0.01"));
}

/* an unbonded model: refused naming the model */
static void test_refused(void **state)
{
    (void)state;
    struct sim *s = test_build_ok("model: {type: sph}\n"
                                  "materials:\n  m: {density: 1000, youngs_modulus: 1.0e9,\n"
                                  "      poisson_ratio: 0.3}\n"
                                  "lattice: {type: square, spacing: 1.0e-3}\n"
                                  "body: {geometry: {box: {min: [0, 0], max: [0.005, 0.005]}},"
                                  " material: m}\n"
                                  "run: {steps: 1}\n");
    struct spall_error err = {0};
    struct field_writer *w = NULL;
    const char *names[] = {"bonds"};
    assert_int_equal(field_writer_create(&w, "/tmp", s, names, 1, &err), SPALL_ERR_INPUT);
    assert_null(w);
    assert_non_null(strstr(err.msg, "sph model has no bonds"));
    sim_destroy(&s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_lattice),
        cmocka_unit_test(test_peridynamics),
        cmocka_unit_test(test_refused),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
