/*
 * The validation gate: runs every built-in validation case that has a fast
 * configuration (gate VGATE_QUICK or VGATE_FULL in validation/cases.c), in
 * that configuration, and asserts that it runs and that every check it
 * records passes, except the known gaps listed below by case and quantity.
 *
 * A known gap is accepted only by name: a failing check not marked known_gap
 * fails; a gap not on the list fails; a listed gap that now passes, or that
 * the case no longer records, fails too (update the list, never silently).
 * The accepted gaps are printed.
 *
 * Usage: test_validation_quick [GROUP] runs one model family (the groups
 * below; CMakeLists.txt registers one ctest test per group so that ctest -j
 * runs them in parallel); without an argument every group runs.
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
#define MAX_PREFIXES 4

/** A model family: the cases whose name starts with one of the prefixes; a
 *  case belongs to the group with the longest matching prefix, so a heavy
 *  case can have a group (and a ctest label) of its own. */
struct gate_group {
    const char *name;
    const char *prefixes[MAX_PREFIXES];
};

static const struct gate_group groups[] = {
    {"lattice", {"lattice-", "abg-", "thermal-"}},
    {"impact", {"impact-"}},
    {"pd", {"pd-"}},
    {"pd-fracture", {"pd-branching", "pd-kalthoff", "pd-lamina-a", "pd-lamina-b"}},
    {"macro", {"macro-"}},
    {"sph", {"sph-"}},
    {"sph-rings", {"sph-rings"}},
    {"pen", {"pen-"}},
};
#define N_GROUPS (sizeof groups / sizeof groups[0])

/** Length of the longest prefix of group @p g that @p case_name starts with (0: none). */
static size_t group_match(const struct gate_group *g, const char *case_name)
{
    size_t best = 0;
    for (size_t p = 0; p < MAX_PREFIXES && g->prefixes[p]; p++) {
        size_t len = strlen(g->prefixes[p]);
        if (len > best && strncmp(case_name, g->prefixes[p], len) == 0)
            best = len;
    }
    return best;
}

/** The group a case belongs to (longest matching prefix); NULL if none. */
static const struct gate_group *case_group(const char *case_name)
{
    const struct gate_group *best = NULL;
    size_t best_len = 0;
    for (size_t g = 0; g < N_GROUPS; g++) {
        size_t len = group_match(&groups[g], case_name);
        if (len > best_len) {
            best_len = len;
            best = &groups[g];
        }
    }
    return best;
}

/** A check that fails in the gate's configuration and is accepted by name;
 *  the cause of each gap is in the check's note and docs/validation.md. */
struct known_gap {
    const char *case_name;
    const char *quantity;
};

static const struct known_gap known_gaps[] = {
    /* #3 item 5a: the brittle beam snaps at the peak, no post-peak tearing work */
    {"impact-nylon", "absorbed energy"},
    {"impact-nylon", "softening G_f 3 kJ/m^2: absorbed energy"},
    /* #3 item 5d: the crack branches, the spalled plate's ends bend open */
    {"impact-spall", "long flyer: damage concentrated on the spall plane"},
    {"impact-spall", "short flyer: opened crack parallel to the far face"},
    {"impact-spall", "short flyer: damage concentrated on the spall plane"},
    {"impact-spall", "short flyer: opened crack shorter than the flyer"},
    {"impact-spall", "short flyer, softening: opened crack parallel to the far face"},
    {"impact-spall", "short flyer, softening: damage concentrated on the spall plane"},
    {"impact-spall", "short flyer, softening: opened crack shorter than the flyer"},
    /* #5 item 1: that Table 1 row follows Eq. 15 for neither metal */
    {"macro-calibration", "Table 1 Al p=5 q=9: E (Eq. 15, e0 = 3.36 eV)"},
    {"macro-calibration", "Table 1 Cu p=5 q=9: E (Eq. 15, e0 = 3.52 eV)"},
    /* #27 item 4: the source's band 0.30-0.33; the lattice's bulk nu is 1/3 */
    {"macro-rod-elastic", "rod n_phi = 8: Poisson's ratio (0.30-0.33)"},
    /* #5 item 5: a band collapses along the axis instead of {111} glide */
    {"macro-rod-large", "n_phi = 4, free ends: compressive collapse strain"},
    {"macro-rod-large", "n_phi = 4, free ends: share of slip normals on {111} after collapse"},
    /* #4 item 5c: the first bonds break at a corner of the stepped hole edge */
    {"pd-lamina-a", "A-0: crack start, distance from the hole's centre line"},
    /* #26 item 4: at delta = 3.015 dx with linear partial volumes the cubic families'
     * fourth moment is not isotropic (LPS E, nu along [100]); the cell rule meets 1 % at
     * delta = 4.015 dx (rows "cell volumes") */
    {"pd-lps-patch", "3D sc nu = 0.10: E"},
    {"pd-lps-patch", "3D sc nu = 0.10: Poisson's ratio"},
    {"pd-lps-patch", "3D sc nu = 0.30: E"},
    {"pd-lps-patch", "3D sc nu = 0.30: Poisson's ratio"},
    {"pd-lps-patch", "3D sc nu = 0.45: E"},
    {"pd-lps-patch", "3D fcc nu = 0.10: Poisson's ratio"},
    /* the LPS surface correction fits axial stretches only (pd_lps_surface.c): the
     * surface families' deviatoric shear energy and the corner / edge families'
     * off-diagonal moment, split by the case's info line; halves with a 2x larger body */
    {"pd-lps-surface", "plane stress triangular plate 11 dx, nu = 0.10: shear modulus"},
    {"pd-lps-surface", "plane stress triangular plate 11 dx, nu = 0.30: shear modulus"},
    {"pd-lps-surface", "plane stress triangular plate 11 dx, nu = 0.45: shear modulus"},
    {"pd-lps-surface", "3D sc cube 8 dx (cubic-corrected), nu = 0.10: shear modulus"},
    {"pd-lps-surface", "3D sc cube 8 dx (cubic-corrected), nu = 0.30: shear modulus"},
    {"pd-lps-surface", "3D sc cube 8 dx (cubic-corrected), nu = 0.45: shear modulus"},
    /* #26 item 4: EPS strip, the old drive (ramps of 2 wave transits) kept as rows: the
     * velocity reversal's inertia in the gauge (the checked drive's 4 transits pass) */
    {"pd-eps-bar", "ramps 2 transits: centre: unloading elastic slope"},
    {"pd-eps-bar", "ramps 2 transits: section: unloading elastic slope"},
    /* #6 item 7c: no published length or radius for this set-up was found */
    {"sph-taylor-2d", "published final length / radius for this set-up found"},
    /* #6 item 7g: second-hand experiment; cause not separated (quick: d/20) */
    {"sph-debris-cloud", "hole diameter in the plate"},
    {"sph-debris-cloud", "cloud length / width (99 % mass) at 20 us"},
    /* #7 item 4a: Poncelet's P(t) is flat near the maximum */
    {"pen-gelatin-time", "gelatin 1290 m/s: Poncelet T_f (Eq. 4.3) vs 200-250 ns"},
    {NULL, NULL}};

static bool gap_listed(const char *case_name, const char *quantity)
{
    for (size_t k = 0; known_gaps[k].case_name; k++)
        if (strcmp(known_gaps[k].case_name, case_name) == 0 &&
            strcmp(known_gaps[k].quantity, quantity) == 0)
            return true;
    return false;
}

static const struct vcase *find_case(const char *name)
{
    size_t n = 0;
    const struct vcase *c = validation_cases(&n);
    for (size_t k = 0; k < n; k++)
        if (strcmp(c[k].name, name) == 0)
            return &c[k];
    return NULL;
}

/** Registry sanity: unique names, a title and a run function each, the
 *  lattice cases present, every case in a group, the four cases
 *  the gate runs as they are, and every listed gap naming a gated case. */
static void test_registry(void **state)
{
    (void)state;
    size_t n = 0;
    const struct vcase *c = validation_cases(&n);
    assert_non_null(c);
    assert_true(n >= 5);
    for (size_t k = 0; k < n; k++) {
        assert_non_null(c[k].name);
        assert_non_null(c[k].title);
        assert_non_null(c[k].run);
        assert_true(strlen(c[k].name) > 0 && strlen(c[k].name) < 48);
        assert_true(c[k].status == NULL || strlen(c[k].status) > 0);
        for (size_t q = k + 1; q < n; q++)
            assert_string_not_equal(c[k].name, c[q].name);
        if (!case_group(c[k].name))
            print_message("case %s is in no gate group (add its prefix to one)\n", c[k].name);
        assert_non_null(case_group(c[k].name));
    }
    static const char *const expected[] = {"lattice-patch", "lattice-waves", "lattice-energy",
                                           "lattice-chain-break", "lattice-threads"};
    for (size_t e = 0; e < sizeof expected / sizeof expected[0]; e++)
        assert_non_null(find_case(expected[e]));
    /* issue 27 item 3: these run in the gate as they are */
    static const char *const full[] = {"pd-kalthoff", "impact-epoxy", "pd-branching",
                                       "macro-calibration"};
    for (size_t e = 0; e < sizeof full / sizeof full[0]; e++) {
        const struct vcase *vc = find_case(full[e]);
        assert_non_null(vc);
        assert_int_equal(vc->gate, VGATE_FULL);
    }
    for (size_t k = 0; known_gaps[k].case_name; k++) {
        const struct vcase *vc = find_case(known_gaps[k].case_name);
        if (!vc || vc->gate == VGATE_OFF)
            print_message("listed gap %s: %s names no gated case\n", known_gaps[k].case_name,
                          known_gaps[k].quantity);
        assert_true(vc && vc->gate != VGATE_OFF);
    }
}

/** Run one case in its gate configuration; every check passes or is a
 *  listed known gap, and every listed gap of the case is recorded and fails. */
static void test_case(void **state)
{
    const struct vcase *vc = *state;
    struct vreport r;
    memset(&r, 0, sizeof r);
    r.log = stdout;
    vreport_begin_case(&r, vc, true);
    struct spall_error err = {0};
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
        const bool listed = gap_listed(vc->name, c->quantity);
        if (c->pass && listed) {
            failed++;
            print_message("LISTED GAP NOW PASSES %s: %s (measured %g): remove it from the "
                          "known_gaps list of tests/test_validation_quick.c\n",
                          vc->name, c->quantity, c->measured);
        } else if (!c->pass && c->known_gap && listed) {
            print_message("accepted known gap %s: %s: reference %g, measured %g, tolerance "
                          "%g%s\n",
                          vc->name, c->quantity, c->reference, c->measured, c->tolerance,
                          c->relative ? " (relative)" : "");
        } else if (!c->pass) {
            failed++;
            print_message("FAIL %s: %s: reference %g, measured %g, tolerance %g%s%s (%s)\n",
                          vc->name, c->quantity, c->reference, c->measured, c->tolerance,
                          c->relative ? " (relative)" : "",
                          c->known_gap ? "; a known gap not on the gate's list" : "", c->note);
        }
    }
    /* a listed gap the case no longer records is a stale entry */
    for (size_t g = 0; known_gaps[g].case_name; g++) {
        if (strcmp(known_gaps[g].case_name, vc->name) != 0)
            continue;
        bool seen = false;
        for (size_t k = 0; k < r.n && !seen; k++)
            seen = strcmp(r.checks[k].quantity, known_gaps[g].quantity) == 0;
        if (!seen) {
            failed++;
            print_message("LISTED GAP NOT RECORDED %s: %s\n", vc->name, known_gaps[g].quantity);
        }
    }
    size_t n_checks = r.n;
    vreport_free(&r);
    assert_int_equal(rc, SPALL_OK);
    assert_true(n_checks > 0);
    assert_int_equal(failed, 0);
}

int main(int argc, char **argv)
{
    const struct gate_group *only = NULL;
    if (argc > 1) {
        for (size_t g = 0; g < N_GROUPS && !only; g++)
            if (strcmp(argv[1], groups[g].name) == 0)
                only = &groups[g];
        if (!only) {
            fprintf(stderr, "test_validation_quick: unknown group '%s'\n", argv[1]);
            return 2;
        }
    }
    size_t n = 0;
    const struct vcase *cases = validation_cases(&n);
    static struct CMUnitTest tests[MAX_TESTS];
    size_t nt = 0;
    tests[nt++] = (struct CMUnitTest)cmocka_unit_test(test_registry);
    for (size_t k = 0; k < n && nt < MAX_TESTS; k++) {
        if (cases[k].gate == VGATE_OFF || (only && case_group(cases[k].name) != only))
            continue;
        tests[nt++] = (struct CMUnitTest){cases[k].name, test_case, NULL, NULL,
                                          (void *)&cases[k]};
    }
    return _cmocka_run_group_tests(only ? only->name : "validation_quick", tests, nt, NULL,
                                   NULL);
}
