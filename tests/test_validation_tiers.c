/*
 * The tiers of `spall validate` (validation/tiers.c): which cases each tier
 * selects, in which configuration (r->quick, r->full) each runs, and that
 * the registry documents every case's tier: a case whose standard tier is
 * not its whole run says what --full adds and its last full values.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "validation/validation.h"

#include <string.h>

/* every registered case: a valid tier; a note exactly where the standard
 * tier differs from the full run; a reduced standard tier only where the
 * case has a reduced configuration that the gate runs or that is named */
static void test_registry_tiers(void **state)
{
    (void)state;
    size_t n = 0;
    const struct vcase *c = validation_cases(&n);
    size_t n_std = 0;
    for (size_t k = 0; k < n; k++) {
        assert_true(c[k].tier == VTIER_ALL || c[k].tier == VTIER_REDUCED ||
                    c[k].tier == VTIER_FULL_ONLY);
        if (c[k].tier == VTIER_ALL) {
            assert_null(c[k].full_note);
        } else {
            assert_non_null(c[k].full_note);
            assert_true(strlen(c[k].full_note) > 20);
        }
        assert_true(c[k].full_wall_s >= 0.0);
        n_std += vtier_selected(&c[k], false, false, false);
    }
    /* the standard tier keeps the cases of the gate */
    for (size_t k = 0; k < n; k++)
        if (c[k].gate != VGATE_OFF)
            assert_true(vtier_selected(&c[k], false, false, false));
    assert_true(n_std > 0 && n_std <= n);
}

static const struct vcase *find_tier(enum vtier tier, enum vgate gate)
{
    size_t n = 0;
    const struct vcase *c = validation_cases(&n);
    for (size_t k = 0; k < n; k++)
        if (c[k].tier == tier && c[k].gate == gate)
            return &c[k];
    return NULL;
}

/* selection: --full and named cases take everything, --quick the gate,
 * the standard tier all but the full-only cases */
static void test_selection(void **state)
{
    (void)state;
    const struct vcase *all = find_tier(VTIER_ALL, VGATE_FULL);
    const struct vcase *only = find_tier(VTIER_FULL_ONLY, VGATE_OFF);
    assert_non_null(all);
    assert_non_null(only);
    assert_true(vtier_selected(all, false, false, false));
    assert_false(vtier_selected(only, false, false, false));
    assert_false(vtier_selected(only, false, true, false));
    assert_true(vtier_selected(only, false, false, true));
    assert_true(vtier_selected(only, true, false, false));
}

/* configuration: (named, quick, full) -> (r->quick, r->full) */
static void expect_config(const struct vcase *c, bool named, bool quick, bool full, int want_quick,
                          int want_full)
{
    struct vreport r = {0};
    vreport_begin_tier(&r, c, named, quick, full);
    assert_int_equal(r.quick, want_quick);
    assert_int_equal(r.full, want_full);
    assert_string_equal(r.current_case, c->name);
}

static void test_configuration(void **state)
{
    (void)state;
    const struct vcase *all = find_tier(VTIER_ALL, VGATE_FULL);
    const struct vcase *all_q = find_tier(VTIER_ALL, VGATE_QUICK);
    const struct vcase *red = find_tier(VTIER_REDUCED, VGATE_QUICK);
    const struct vcase *only = find_tier(VTIER_FULL_ONLY, VGATE_OFF);
    assert_non_null(all_q);
    assert_non_null(red);
    /* the gate: as before the tiers (the case's gate) */
    expect_config(all, false, true, false, 0, 0);
    expect_config(all_q, false, true, false, 1, 0);
    expect_config(red, false, true, false, 1, 0);
    /* the standard tier: whole runs, the reduced configuration of a reduced case */
    expect_config(all, false, false, false, 0, 0);
    expect_config(all_q, false, false, false, 0, 0);
    expect_config(red, false, false, false, 1, 0);
    /* --full: everything complete */
    expect_config(all, false, false, true, 0, 1);
    expect_config(red, false, false, true, 0, 1);
    expect_config(only, false, false, true, 0, 1);
    /* named: the standard tier's configuration; a full-only case complete;
     * with --quick the reduced configuration */
    expect_config(red, true, false, false, 1, 0);
    expect_config(only, true, false, false, 0, 1);
    expect_config(all_q, true, true, false, 1, 0);
}

static void test_clocks(void **state)
{
    (void)state;
    double w0 = vclock_wall(), c0 = vclock_cpu();
    volatile double s = 0.0;
    for (int k = 0; k < 2000000; k++)
        s += 1e-9 * k;
    assert_true(vclock_wall() >= w0);
    assert_true(vclock_cpu() > c0);
    assert_true(s > 0.0);
    /* a load average, or -1 where the system gives none */
    double l = vclock_load();
    assert_true(l >= 0.0 || l == -1.0);
    assert_string_equal(vtier_name(VTIER_ALL), "standard");
    assert_string_equal(vtier_name(VTIER_FULL_ONLY), "full only");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_registry_tiers),
        cmocka_unit_test(test_selection),
        cmocka_unit_test(test_configuration),
        cmocka_unit_test(test_clocks),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
