/* The model registry (src/models/registry.c): every listed name finds its
 * model, whose model_ops carries the same name, and unknown names find none. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "core/lattice_gen.h"
#include "core/model.h"
#include "models/registry.h"

#include <string.h>

static void test_names_find_their_models(void **state)
{
    (void)state;
    size_t n = 0;
    for (const char *const *name = model_names(); *name; name++, n++) {
        const struct model_ops *ops = model_find(*name);
        assert_non_null(ops);
        assert_string_equal(ops->name, *name);
    }
    assert_int_equal(n, 5); /* lattice, peridynamics, macroparticle, sph, tlsph */
    assert_null(model_find("no_such_model"));
}

/* The lattice names are the enum's order: name -> kind -> name round trip. */
static void test_lattice_names_round_trip(void **state)
{
    (void)state;
    int k = 0;
    for (const char *const *name = lattice_kind_names(); *name; name++, k++) {
        assert_int_equal(lattice_kind_from_name(*name), k);
        assert_string_equal(lattice_kind_name((enum lattice_kind)k), *name);
    }
    assert_int_equal(k, LATTICE_SHELLS + 1);
    assert_int_equal(lattice_kind_from_name("no_such_lattice"), -1);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_names_find_their_models),
        cmocka_unit_test(test_lattice_names_round_trip),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
