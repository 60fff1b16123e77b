/**
 * Bad decks: every error names file:line:column and what was expected,
 * with status SPALL_ERR_INPUT (or SPALL_ERR_PHYSICS for impossible physics).
 * Each case is a valid base deck with one defect.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "core/sim.h"
#include "io/deck.h"
#include "io/deck_build.h"
#include "spall/error.h"

#include <stdio.h>
#include <string.h>

struct bad_case {
    const char *name;
    const char *yaml;
    int status;          /* expected status */
    const char *where;   /* expected "L:C" after the file name, NULL: any position */
    const char *expect;  /* substring of the message */
};

#define BASE_MODEL "model: {type: lattice}\n"
#define BASE_MAT                                                                                  \
    "materials:\n"                                                                                \
    "  m: {density: 1000, youngs_modulus: 1.0e9, poisson_ratio: 0.3333333333333333,\n"           \
    "      failure_strain: 0.05}\n"
#define BASE_LAT "lattice: {type: triangular, spacing: 0.001}\n"
#define BASE_GEO "geometry:\n  plate: {box: {min: [0, 0], max: [0.01, 0.01]}}\n"
#define BASE_BODY "body: {geometry: plate, material: m}\n"
#define BASE_RUN "run: {steps: 10}\n"

static const struct bad_case cases[] = {
    {"syntax error", BASE_MODEL "materials: [unclosed\n", SPALL_ERR_INPUT, "2:", "YAML syntax"},
    {"bad indentation", "model:\n  type: lattice\n law: linear\n", SPALL_ERR_INPUT, "3:", "YAML"},
    {"empty deck", "", SPALL_ERR_INPUT, "1:1", "empty"},
    {"unknown top-level key",
     BASE_MODEL BASE_MAT BASE_LAT BASE_GEO BASE_BODY BASE_RUN "outptu: {}\n", SPALL_ERR_INPUT,
     "10:1", "unknown key 'outptu'"},
    {"unknown material key",
     BASE_MODEL "materials:\n  m: {density: 1000, youngs_modulus: 1.0e9, poisson_ratio: 0.3333333333333333,\n"
                "      failure_strain: 0.05, colour: red}\n" BASE_LAT BASE_GEO BASE_BODY BASE_RUN,
     SPALL_ERR_INPUT, "4:29", "unknown key 'colour'"},
    {"wrong type", BASE_MODEL "materials:\n  m: {density: heavy, youngs_modulus: 1.0e9, poisson_ratio: 0.3333333333333333,\n"
                              "      failure_strain: 0.05}\n" BASE_LAT BASE_GEO BASE_BODY BASE_RUN,
     SPALL_ERR_INPUT, "3:", "number"},
    {"missing required key (spacing)", BASE_MODEL BASE_MAT "lattice: {type: triangular}\n" BASE_GEO
                                                           BASE_BODY BASE_RUN,
     SPALL_ERR_INPUT, "5:10", "spacing"},
    {"missing model", BASE_MAT BASE_LAT BASE_GEO BASE_BODY BASE_RUN, SPALL_ERR_INPUT, NULL, "model"},
    {"negative density", BASE_MODEL "materials:\n  m: {density: -5, youngs_modulus: 1.0e9, poisson_ratio: 0.3333333333333333,\n"
                                    "      failure_strain: 0.05}\n" BASE_LAT BASE_GEO BASE_BODY BASE_RUN,
     SPALL_ERR_INPUT, "3:", "> 0"},
    {"poisson ratio out of range", BASE_MODEL "materials:\n  m: {density: 1000, youngs_modulus: 1.0e9, poisson_ratio: 1.2,\n"
                                              "      failure_strain: 0.05}\n" BASE_LAT BASE_GEO BASE_BODY BASE_RUN,
     0, "3:", "poisson_ratio"},
    {"unknown model type", "model: {type: fem}\n" BASE_MAT BASE_LAT BASE_GEO BASE_BODY BASE_RUN,
     SPALL_ERR_INPUT, "1:15", "lattice"},
    {"unknown lattice type", BASE_MODEL BASE_MAT "lattice: {type: hexagonal, spacing: 0.001}\n" BASE_GEO
                                                 BASE_BODY BASE_RUN,
     SPALL_ERR_INPUT, "5:17", "triangular"},
    {"rings body in the lattice model",
     BASE_MODEL BASE_MAT BASE_LAT BASE_GEO
     "bodies:\n  - {geometry: plate, material: m, lattice: {type: rings, origin: [0.005, 0.005]}}\n"
     BASE_RUN,
     SPALL_ERR_INPUT, "9:", "needs a model that takes each particle's own volume"},
    {"rings lattice in the lattice model",
     BASE_MODEL BASE_MAT "lattice: {type: rings, spacing: 0.001}\n" BASE_GEO BASE_BODY BASE_RUN,
     SPALL_ERR_INPUT, "5:", "lattice type 'rings' needs a model"},
    {"3D body lattice in a 2D run",
     BASE_MODEL BASE_MAT BASE_LAT BASE_GEO
     "bodies:\n  - {geometry: plate, material: m, lattice: {type: shells}}\n" BASE_RUN,
     SPALL_ERR_INPUT, "9:", "'shells' is 3D; expected a 2D type"},
    {"unknown material name", BASE_MODEL BASE_MAT BASE_LAT BASE_GEO "body: {geometry: plate, material: steel}\n" BASE_RUN,
     SPALL_ERR_INPUT, "8:", "unknown material 'steel'"},
    {"unknown geometry name", BASE_MODEL BASE_MAT BASE_LAT BASE_GEO "body: {geometry: slab, material: m}\n" BASE_RUN,
     SPALL_ERR_INPUT, "8:", "unknown geometry 'slab'"},
    {"empty geometry", BASE_MODEL BASE_MAT BASE_LAT
     "geometry:\n  plate: {box: {min: [0.5, 0.5], max: [0.5001, 0.5001]}}\n" BASE_BODY BASE_RUN,
     SPALL_ERR_INPUT, "8:", "no lattice site"},
    {"unknown group in a BC", BASE_MODEL BASE_MAT BASE_LAT BASE_GEO BASE_BODY BASE_RUN
     "boundary_conditions:\n  - {group: grip, type: fixed}\n", SPALL_ERR_INPUT, "11:", "unknown group 'grip'"},
    {"empty group", BASE_MODEL BASE_MAT BASE_LAT BASE_GEO BASE_BODY BASE_RUN
     "groups:\n  far: {box: {min: [5, 5], max: [6, 6]}}\n", SPALL_ERR_INPUT, "11:", "no particle"},
    {"bad BC type", BASE_MODEL BASE_MAT BASE_LAT BASE_GEO BASE_BODY BASE_RUN
     "boundary_conditions:\n  - {group: all, type: glue}\n", SPALL_ERR_INPUT, "11:", "fixed, velocity"},
    {"bad component", BASE_MODEL BASE_MAT BASE_LAT BASE_GEO BASE_BODY BASE_RUN
     "boundary_conditions:\n  - {group: all, type: fixed, components: [w]}\n", SPALL_ERR_INPUT, "11:",
     "component 'w'"},
    {"vector of wrong length", BASE_MODEL BASE_MAT BASE_LAT
     "geometry:\n  plate: {box: {min: [0], max: [0.01, 0.01]}}\n" BASE_BODY BASE_RUN, SPALL_ERR_INPUT,
     "7:", "min"},
    {"run without length", BASE_MODEL BASE_MAT BASE_LAT BASE_GEO BASE_BODY "run: {dt: 1.0e-9}\n",
     SPALL_ERR_INPUT, "9:", "end_time"},
    {"time step above the stability limit", BASE_MODEL BASE_MAT BASE_LAT BASE_GEO BASE_BODY
     "run: {steps: 10, dt: 1.0}\n", SPALL_ERR_PHYSICS, "9:", "stability limit"},
    {"duplicate key", BASE_MODEL BASE_MAT BASE_LAT BASE_GEO BASE_BODY BASE_RUN "run: {steps: 5}\n",
     SPALL_ERR_INPUT, "10:1", "duplicate"},
    {"non-finite number", BASE_MODEL BASE_MAT "lattice: {type: triangular, spacing: .nan}\n" BASE_GEO
                                              BASE_BODY BASE_RUN,
     SPALL_ERR_INPUT, "5:", "spacing"},
    {"box max below min", BASE_MODEL BASE_MAT BASE_LAT
     "geometry:\n  plate: {box: {min: [0, 0], max: [-0.01, 0.01]}}\n" BASE_BODY BASE_RUN,
     SPALL_ERR_INPUT, "7:", "max"},
    {"shape cycle", BASE_MODEL BASE_MAT BASE_LAT "geometry:\n  a: {union: [b]}\n  b: {union: [a]}\n"
                                                 "body: {geometry: a, material: m}\n" BASE_RUN,
     SPALL_ERR_INPUT, NULL, "deeper"},
    {"negative field_every", BASE_MODEL BASE_MAT BASE_LAT BASE_GEO BASE_BODY BASE_RUN
     "output: {fields: [position], field_every: -3}\n", SPALL_ERR_INPUT, "10:", "field_every"},
};

static void run_case(const struct bad_case *c)
{
    struct deck *d = NULL;
    struct sim *s = NULL;
    struct run_output ro;
    struct spall_error err = {0};
    int rc = deck_load_string(&d, "bad.yaml", c->yaml, &err);
    if (rc == 0)
        rc = deck_build_sim(d, &s, &ro, &err);
    print_message("case '%s': rc %d: %s\n", c->name, rc, err.msg);
    if (c->status)
        assert_int_equal(rc, c->status);
    else
        assert_true(rc == SPALL_ERR_INPUT || rc == SPALL_ERR_PHYSICS);
    assert_null(s);
    assert_true(strncmp(err.msg, "bad.yaml:", 9) == 0);
    if (c->where) {
        char pre[64];
        snprintf(pre, sizeof pre, "bad.yaml:%s", c->where);
        assert_true(strncmp(err.msg, pre, strlen(pre)) == 0);
    }
    assert_non_null(strstr(err.msg, c->expect));
    /* one line */
    assert_null(strchr(err.msg, '\n'));
    deck_destroy(&d);
}

static void test_all_cases(void **state)
{
    (void)state;
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++)
        run_case(&cases[k]);
}

static void test_case_count(void **state)
{
    (void)state;
    assert_true(sizeof cases / sizeof cases[0] >= 15);
}

static void test_valid_base_builds(void **state)
{
    (void)state;
    struct deck *d = NULL;
    struct sim *s = NULL;
    struct run_output ro;
    struct spall_error err = {0};
    const char *yaml = BASE_MODEL BASE_MAT BASE_LAT BASE_GEO BASE_BODY BASE_RUN;
    assert_int_equal(deck_load_string(&d, "good.yaml", yaml, &err), 0);
    int rc = deck_build_sim(d, &s, &ro, &err);
    if (rc)
        print_message("%s\n", err.msg);
    assert_int_equal(rc, 0);
    assert_non_null(s);
    assert_true(s->dt > 0.0 && s->dt <= s->dt_limit);
    sim_destroy(&s);
    deck_destroy(&d);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_case_count),
        cmocka_unit_test(test_valid_base_builds),
        cmocka_unit_test(test_all_cases),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
