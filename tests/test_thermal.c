/* Tests for the thermal lattice's deck handling (lattice_thermal.c):
 * refusals with a reason, and the temperature field / history columns. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "core/fields.h"
#include "core/particles.h"
#include "core/sim.h"
#include "io/deck.h"
#include "io/deck_build.h"
#include "core/model.h"
#include "spall/error.h"

#include <stdio.h>
#include <string.h>

static int build(const char *mat_extra, const char *model_extra, struct sim **s,
                 struct spall_error *err)
{
    char yaml[2048];
    snprintf(yaml, sizeof yaml,
             "model: {type: lattice, law: linear%s}\n"
             "materials:\n"
             "  m: {density: 1000, youngs_modulus: 1.0e9, failure_strain: 0.01%s}\n"
             "lattice: {type: chain, spacing: 1.0e-3}\n"
             "geometry:\n"
             "  rod: {box: {min: [-0.0005], max: [0.0105]}}\n"
             "body: {geometry: rod, material: m}\n"
             "groups:\n"
             "  end: {box: {min: [-0.001], max: [0.0005]}}\n"
             "run: {end_time: 1.0e-6}\n",
             model_extra, mat_extra);
    struct deck *d = NULL;
    int rc = deck_load_string(&d, "test_thermal", yaml, err);
    if (rc)
        return rc;
    struct run_output ro;
    rc = deck_build_sim(d, s, &ro, err);
    deck_destroy(&d);
    return rc;
}

static void test_refusals(void **state)
{
    (void)state;
    struct sim *s = NULL;
    struct spall_error err = {0};
    assert_int_equal(build(", conductivity: 3", "", &s, &err), SPALL_ERR_INPUT);
    assert_non_null(strstr(err.msg, "specific_heat"));
    assert_null(s);
    assert_int_equal(build(", specific_heat: -1", "", &s, &err), SPALL_ERR_INPUT);
    assert_non_null(strstr(err.msg, "specific_heat"));
    assert_int_not_equal(build(", specific_heat: 800",
                               ", thermal: {boundary: [{group: nowhere, temperature: 400}]}", &s,
                               &err),
                         SPALL_OK);
    assert_non_null(strstr(err.msg, "nowhere"));
    sim_destroy(&s);
    assert_int_not_equal(build("", ", thermal: {boundary: [{group: end, temperature: 400}]}", &s,
                               &err),
                         SPALL_OK);
    assert_non_null(strstr(err.msg, "specific_heat"));
    sim_destroy(&s);
}

static void test_field_and_history(void **state)
{
    (void)state;
    struct sim *s = NULL;
    struct spall_error err = {0};
    int rc = build(", specific_heat: 800, initial_temperature: 350",
                   ", thermal: {boundary: [{group: end, temperature: 400}]}", &s, &err);
    if (rc)
        fprintf(stderr, "%s\n", err.msg);
    assert_int_equal(rc, SPALL_OK);
    const struct field_desc *f = field_registry_find(s->fields, "temperature");
    assert_non_null(f);
    double T[16];
    assert_true(s->p->n_owned <= 16);
    field_gather_f64(f, s->p->n_owned, T);
    assert_true(T[0] == 400.0); /* the fixed end */
    assert_true(T[5] == 350.0);
    const char *names[MODEL_HISTORY_MAX];
    double vals[MODEL_HISTORY_MAX];
    size_t n = s->ops->history(s->model, s, names, vals);
    int found = 0;
    for (size_t k = 0; k < n; k++)
        found |= strcmp(names[k], "temperature_max [K]") == 0 && vals[k] == 400.0;
    assert_true(found);
    sim_destroy(&s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_refusals),
        cmocka_unit_test(test_field_and_history),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
