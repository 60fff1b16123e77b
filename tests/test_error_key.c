/**
 * Error locations travel as data (issue 19): a refusal about one input key
 * names it in err->key where it is raised (core, models), the deck layer
 * turns that key path into file:line:column without reading the message,
 * and a library caller without a deck reads the key itself.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "core/contact_particles.h"
#include "core/geometry.h"
#include "core/lattice_gen.h"
#include "core/particles.h"
#include "core/sim.h"
#include "io/deck.h"
#include "io/deck_build.h"
#include "core/model.h"
#include "models/registry.h"
#include "spall/error.h"

#include <stdio.h>
#include <string.h>

/* The record itself: set_key keeps the key, set and clear drop it, prefix
 * keeps it, the default key never overrides a more precise one. */
static void test_record(void **state)
{
    (void)state;
    struct spall_error err = {0};
    assert_int_equal(spall_error_set_key(&err, SPALL_ERR_INPUT, "model.clamp", "model.clamp: x %d",
                                         1),
                     SPALL_ERR_INPUT);
    assert_string_equal(err.key, "model.clamp");
    assert_string_equal(err.msg, "model.clamp: x 1");
    spall_error_prefix(&err, "material '%s': ", "m");
    assert_string_equal(err.key, "model.clamp");
    assert_string_equal(err.msg, "material 'm': model.clamp: x 1");
    spall_error_default_key(&err, "materials.%s", "m");
    assert_string_equal(err.key, "model.clamp"); /* the inner key wins */
    spall_error_set(&err, SPALL_ERR_PHYSICS, "no key");
    assert_string_equal(err.key, "");
    spall_error_default_key(&err, "materials.%s", "m");
    assert_string_equal(err.key, "materials.m");
    spall_error_clear(&err);
    assert_int_equal(err.code, SPALL_OK);
    assert_string_equal(err.key, "");
    /* a path that does not fit is dropped, never cut into another key */
    char longkey[SPALL_ERROR_KEY_LEN + 8];
    memset(longkey, 'a', sizeof longkey - 1);
    longkey[sizeof longkey - 1] = '\0';
    spall_error_set_key(&err, SPALL_ERR_INPUT, longkey, "long");
    assert_string_equal(err.key, "");
    spall_error_default_key(&err, "materials.%s", longkey);
    assert_string_equal(err.key, "");
    assert_int_equal(spall_error_set_key(NULL, SPALL_ERR_INPUT, "run.dt", "dropped"),
                     SPALL_ERR_INPUT);
}

/* Build @p yaml (named "k.yaml"); expects refusal @p code. */
static void refused(const char *yaml, int code, const char *key, const char *where,
                    const char *text)
{
    struct deck *d = NULL;
    struct sim *s = NULL;
    struct run_output ro;
    struct spall_error err = {0};
    int rc = deck_load_string(&d, "k.yaml", yaml, &err);
    if (rc == 0)
        rc = deck_build_sim(d, &s, &ro, &err);
    print_message("%s -> [%s] %s\n", key, err.key, err.msg);
    assert_int_equal(rc, code);
    assert_int_equal(err.code, code);
    assert_null(s);
    assert_string_equal(err.key, key); /* kept for the caller */
    char head[64];
    snprintf(head, sizeof head, "k.yaml:%s: ", where);
    assert_true(strncmp(err.msg, head, strlen(head)) == 0);
    assert_non_null(strstr(err.msg, text));
    deck_destroy(&d);
}

/* The deck positions below are counted by hand: line:column of the key
 * the refusal names (1-based, the key's first character). */
static void test_deck_positions(void **state)
{
    (void)state;
    /* SPH clamp refused at set-up (sph_clamp_init): the 'clamp' key */
    refused("model:\n"
            "  type: sph\n"
            "  kernel: cubic_spline\n"
            "  plane: strain\n"
            "  clamp: {group: clamp, point: [0, 0], normal: [1, 0]}\n"
            "materials:\n"
            "  r: {density: 1000, youngs_modulus: 2.0e6, poisson_ratio: 0.3975}\n"
            "lattice: {type: square, spacing: 2.0e-3, origin: [0.001, 0.001], thickness: 1.0}\n"
            "body: {geometry: {box: {min: [-0.01, -0.01], max: [0.04, 0.01]}}, material: r}\n"
            "groups:\n"
            "  clamp: {box: {min: [-1, -1], max: [0.0, 1]}}\n"
            "run: {steps: 2}\n",
            SPALL_ERR_INPUT, "model.clamp", "5:3", "model.clamp: group 'clamp' needs a fixed");
    /* time step above the limit (sim_prepare): the 'dt' key of 'run' */
    const char *lattice = "model: {type: lattice}\n"
                          "materials:\n"
                          "  m: {density: 1000, youngs_modulus: 1.0e9, "
                          "poisson_ratio: 0.3333333333333333, failure_strain: 0.05}\n"
                          "lattice: {type: triangular, spacing: 0.001}\n"
                          "body: {geometry: {box: {min: [0, 0], max: [0.01, 0.01]}}, material: m}\n";
    char yaml[2048];
    snprintf(yaml, sizeof yaml, "%srun:\n  steps: 10\n  dt: 1.0\n", lattice);
    refused(yaml, SPALL_ERR_PHYSICS, "run.dt", "8:3", "time step 1 s is above the stability");
    /* a peridynamics option refused at init (pd_init): the 'variant' key */
    refused("model: {type: peridynamics, variant: pdlm}\n"
            "materials:\n  m: {density: 1000, youngs_modulus: 1.0e9}\n"
            "lattice: {type: square, spacing: 0.001}\n"
            "body: {geometry: {box: {min: [0, 0], max: [0.01, 0.01]}}, material: m}\n"
            "run: {steps: 2}\n",
            SPALL_ERR_INPUT, "model.variant", "1:29", "variant pdlm needs the triangular");
    /* a sequence item: the second thermal boundary names no group */
    refused("model:\n"
            "  type: lattice\n"
            "  law: linear\n"
            "  thermal:\n"
            "    boundary:\n"
            "      - {group: end, temperature: 400}\n"
            "      - {group: nowhere, temperature: 300}\n"
            "materials:\n"
            "  m: {density: 1000, youngs_modulus: 1.0e9, failure_strain: 0.01, "
            "specific_heat: 800}\n"
            "lattice: {type: chain, spacing: 1.0e-3}\n"
            "body: {geometry: {box: {min: [-0.0005], max: [0.0105]}}, material: m}\n"
            "groups:\n"
            "  end: {box: {min: [-0.001], max: [0.0005]}}\n"
            "run: {end_time: 1.0e-6}\n",
            SPALL_ERR_INPUT, "model.thermal.boundary[1].group", "7:10",
            "model.thermal.boundary: no group named 'nowhere'");
    /* a material refused at init: the material's key under 'materials' */
    refused("model: {type: lattice, law: linear}\n"
            "materials:\n"
            "  a: {density: 1000, youngs_modulus: 1.0e9, failure_strain: 0.01, "
            "specific_heat: 800}\n"
            "  b: {density: 1000, youngs_modulus: 1.0e9, failure_strain: 0.01}\n"
            "lattice: {type: chain, spacing: 1.0e-3}\n"
            "body: {geometry: {box: {min: [-0.0005], max: [0.0105]}}, material: b}\n"
            "regions: [{geometry: {box: {min: [-0.001], max: [0.0005]}}, material: a}]\n"
            "run: {end_time: 1.0e-6}\n",
            SPALL_ERR_INPUT, "materials.b", "4:3", "material 'b' has no specific_heat");
}

/* A library caller without a deck: the key arrives as data, the message
 * carries no file position. */
static void test_library_caller(void **state)
{
    (void)state;
    struct spall_error err = {0};
    struct particle_contact *pc = NULL;
    struct particle_contact_params prm = {1e-3, -1.0, 1.0};
    assert_int_equal(particle_contact_create(&pc, &prm, &err), SPALL_ERR_PHYSICS);
    assert_null(pc);
    assert_string_equal(err.key, "contact.stiffness");

    /* a sim set up through the library API; dt above the limit refused by
     * sim_prepare names run.dt */
    struct sim *s = NULL;
    assert_int_equal(sim_create(&s, 2, &err), SPALL_OK);
    int index = -1;
    assert_int_equal(sim_add_material(s, "m", 1000.0, &index, &err), SPALL_OK);
    s->lattice.kind = LATTICE_TRIANGULAR;
    s->lattice.spacing = 1e-3;
    s->thickness = 1.0;
    s->thickness_given = true;
    const double lo[3] = {0, 0, 0}, hi[3] = {0.01, 0.01, 0};
    struct geom *g = geom_box(lo, hi);
    size_t added = 0;
    assert_int_equal(lattice_fill(s->p, &s->lattice, g, index, &added, &err), SPALL_OK);
    geom_destroy(&g);
    const double vol = lattice_site_volume(&s->lattice, s->thickness);
    for (size_t i = 0; i < s->p->n; i++) {
        s->p->volume[i] = vol;
        s->p->mass[i] = 1000.0 * vol;
    }
    assert_int_equal(sim_set_model(s, model_find("lattice"), NULL, &err), SPALL_OK);
    /* the model reads a material's constants from an option node */
    struct deck *d = NULL;
    assert_int_equal(deck_load_string(&d, "m", "{youngs_modulus: 1.0e9, poisson_ratio: "
                                                "0.3333333333333333, failure_strain: 0.05}",
                                      &err),
                     SPALL_OK);
    assert_int_equal(s->ops->parse_material(s->model, s, index, d->root, &err), SPALL_OK);
    deck_destroy(&d);
    s->dt = 1.0;
    s->n_steps = 10;
    assert_int_equal(sim_prepare(s, &err), SPALL_ERR_PHYSICS);
    print_message("[%s] %s\n", err.key, err.msg);
    assert_string_equal(err.key, "run.dt");
    assert_true(strncmp(err.msg, "time step 1 s is above", 22) == 0);
    sim_destroy(&s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_record),
        cmocka_unit_test(test_deck_positions),
        cmocka_unit_test(test_library_caller),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
