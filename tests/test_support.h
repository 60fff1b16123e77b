/**
 * @file test_support.h
 * @brief Helpers shared by the cmocka tests: build a simulation from YAML
 *        text through the validation layer's vlat_build (one copy instead
 *        of one per test file).  Include after <cmocka.h>.
 */
#ifndef SPALL_TEST_SUPPORT_H
#define SPALL_TEST_SUPPORT_H

#include "core/sim.h"
#include "spall/error.h"
#include "validation/lattice_cases.h"

/** The simulation of @p yaml, or NULL with the cause printed (for tests
 *  that also feed decks the engine must refuse). */
static inline struct sim *test_build(const char *yaml)
{
    struct sim *s = NULL;
    struct spall_error err = {0, ""};
    if (vlat_build("test", yaml, &s, &err)) {
        print_error("%s\n", err.msg);
        return NULL;
    }
    return s;
}

/** The simulation of @p yaml; the test fails (cause printed) if it does not
 *  build. */
static inline struct sim *test_build_ok(const char *yaml)
{
    struct sim *s = test_build(yaml);
    assert_non_null(s);
    return s;
}

#endif
