/*
 * Runs every built-in validation case marked in_quick (validation/cases.c)
 * with quick = 1 and asserts that it runs and that every check it records
 * passes (a documented known gap counts as a failure, as in `spall validate`).
 * One cmocka test per case, generated from the registry, plus a test of the
 * registry itself.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "spall/error.h"
#include "validation/validation.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#define MAX_TESTS 64

/** Registry sanity: unique names, a title and a run function each, the
 *  lattice cases present, and at least one case in the quick set. */
static void test_registry(void **state)
{
    (void)state;
    size_t n = 0;
    const struct vcase *c = validation_cases(&n);
    assert_non_null(c);
    assert_true(n >= 5);
    size_t quick = 0;
    for (size_t k = 0; k < n; k++) {
        assert_non_null(c[k].name);
        assert_non_null(c[k].title);
        assert_non_null(c[k].run);
        assert_true(strlen(c[k].name) > 0 && strlen(c[k].name) < 48);
        for (size_t q = k + 1; q < n; q++)
            assert_string_not_equal(c[k].name, c[q].name);
        quick += c[k].in_quick;
    }
    assert_true(quick > 0);
    static const char *const expected[] = {"lattice-patch", "lattice-waves", "lattice-energy",
                                           "lattice-chain-break", "lattice-threads"};
    for (size_t e = 0; e < sizeof expected / sizeof expected[0]; e++) {
        size_t k = 0;
        while (k < n && strcmp(c[k].name, expected[e]) != 0)
            k++;
        assert_true(k < n);
    }
}

/** Run one case in quick mode; every recorded check must pass. */
static void test_case(void **state)
{
    const struct vcase *vc = *state;
    struct vreport r;
    memset(&r, 0, sizeof r);
    r.log = stdout;
    r.quick = 1;
    r.current_case = vc->name;
    struct spall_error err = {0, ""};
    int rc = vc->run(&r, &err);
    if (rc)
        print_message("case %s failed to run: %s\n", vc->name, err.msg);
    size_t failed = 0;
    for (size_t k = 0; k < r.n; k++) {
        const struct vcheck *c = &r.checks[k];
        assert_string_equal(c->case_name, vc->name);
        /* every check documents where its reference comes from and why */
        assert_true(strlen(c->source) > 0);
        assert_true(strlen(c->note) > 0);
        if (!c->pass) {
            failed++;
            print_message("FAIL %s: %s: reference %g, measured %g, tolerance %g%s (%s)\n",
                          vc->name, c->quantity, c->reference, c->measured, c->tolerance,
                          c->relative ? " (relative)" : "", c->note);
        }
    }
    size_t n_checks = r.n;
    vreport_free(&r);
    assert_int_equal(rc, SPALL_OK);
    assert_true(n_checks > 0);
    assert_int_equal(failed, 0);
}

int main(void)
{
    size_t n = 0;
    const struct vcase *cases = validation_cases(&n);
    static struct CMUnitTest tests[MAX_TESTS];
    static const struct vcase *states[MAX_TESTS];
    size_t nt = 0;
    tests[nt++] = (struct CMUnitTest)cmocka_unit_test(test_registry);
    for (size_t k = 0; k < n && nt < MAX_TESTS; k++) {
        if (!cases[k].in_quick)
            continue;
        states[nt] = &cases[k];
        tests[nt] = (struct CMUnitTest){cases[k].name, test_case, NULL, NULL, (void *)states[nt]};
        nt++;
    }
    return _cmocka_run_group_tests("validation_quick", tests, nt, NULL, NULL);
}
