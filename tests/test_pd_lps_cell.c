/*
 * Tests of the cell partial-volume rule (model.partial_volume_rule: cell,
 * src/models/peridynamics/pd_cellvol.c) of the linear peridynamic solid:
 * the integrated cells have the lattices' site volumes; the cut fractions
 * tile the horizon sphere (sum_j beta_j V_j = the sphere's volume less the
 * particle's own cell, which no other rule does); beta is the same for
 * every image of an offset under the cell's symmetry; the rule is refused
 * with pair forces and without partial volumes.  E and nu with the rule
 * are checked by `spall validate pd-lps-patch` (in the ctest gate,
 * validation_pd: sc and fcc at delta = 4.015 dx within 1 %).
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "core/mathconst.h"
#include "models/peridynamics/pd_cellvol.h"
#include "tests/test_support.h"

#include <math.h>
#include <stdbool.h>
#include <stdio.h>

/* lattice site (i, j, k) of kind in units of the spacing; false: not a site */
static bool site(enum lattice_kind k, int i, int j, int l, double *x)
{
    switch (k) {
    case LATTICE_SC:
    case LATTICE_SQUARE:
        x[0] = i;
        x[1] = j;
        x[2] = l;
        return true;
    case LATTICE_FCC:
        x[0] = i * sqrt(0.5);
        x[1] = j * sqrt(0.5);
        x[2] = l * sqrt(0.5);
        return ((i + j + l) % 2 + 2) % 2 == 0;
    case LATTICE_TRIANGULAR:
        x[0] = i + 0.5 * j;
        x[1] = 0.5 * sqrt(3.0) * j;
        x[2] = 0.0;
        return l == 0;
    default:
        return false;
    }
}

static void test_cells_tile_the_sphere(void **state)
{
    (void)state;
    const enum lattice_kind kinds[] = {LATTICE_SC, LATTICE_FCC, LATTICE_SQUARE,
                                       LATTICE_TRIANGULAR};
    const double vol[] = {1.0, sqrt(0.5), 1.0, 0.5 * sqrt(3.0)};
    for (int q = 0; q < 4; q++) {
        const int dim = q < 2 ? 3 : 2;
        for (double m = 3.015; m < 5.1; m += 1.0) {
            struct pd_cellvol c;
            struct spall_error err = {0};
            assert_int_equal(pd_cellvol_init(&c, kinds[q], dim, m, 0.0, &err), 0);
            const double vc = c.vcell;
            const int n = (int)ceil((m + 1.0) * 2.0);
            double sum = 0.0;
            for (int i = -n; i <= n; i++)
                for (int j = -n; j <= n; j++)
                    for (int l = (dim == 3 ? -n : 0); l <= (dim == 3 ? n : 0); l++) {
                        double x[3];
                        if ((i == 0 && j == 0 && l == 0) || !site(kinds[q], i, j, l, x))
                            continue;
                        double b;
                        assert_int_equal(pd_cellvol_beta(&c, x, 1.0, &b, &err), 0);
                        assert_true(b >= 0.0 && b <= 1.0);
                        sum += b * vol[q];
                    }
            const double ball = dim == 3 ? 4.0 / 3.0 * SPALL_PI * m * m * m : SPALL_PI * m * m;
            printf("  %s m = %.3f: cell %.8f (exact %.8f), sum beta V / (ball - V) - 1 = "
                   "%+.1e, %zu cut offsets\n",
                   lattice_kind_name(kinds[q]), m, vc, vol[q], sum / (ball - vol[q]) - 1.0, c.n);
            assert_true(fabs(vc / vol[q] - 1.0) < 1e-5);
            assert_true(fabs(sum / (ball - vol[q]) - 1.0) < 1e-5);
            /* an offset and an image of it under the cell's symmetry */
            double e1[3], e2[3], b1, b2;
            if (dim == 3) {
                site(kinds[q], 4, 2, 0, e1);
                site(kinds[q], 0, -2, 4, e2);
            } else {
                site(kinds[q], 3, 1, 0, e1);
                e2[0] = -e1[0];
                e2[1] = -e1[1];
                e2[2] = 0.0;
            }
            assert_int_equal(pd_cellvol_beta(&c, e1, 1.0, &b1, &err), 0);
            assert_int_equal(pd_cellvol_beta(&c, e2, 1.0, &b2, &err), 0);
            assert_true(b1 == b2);
            pd_cellvol_free(&c);
        }
    }
}

static void test_refused(void **state)
{
    (void)state;
    const char *models[] = {"{type: peridynamics, partial_volume_rule: cell}",
                            "{type: peridynamics, formulation: lps, partial_volume: false, "
                            "partial_volume_rule: cell}"};
    for (int k = 0; k < 2; k++) {
        char buf[1024];
        snprintf(buf, sizeof buf,
                 "model: %s\n"
                 "materials:\n  m: {density: 1000, youngs_modulus: 1e9, poisson_ratio: 0.25}\n"
                 "lattice: {type: sc, spacing: 1.0e-3}\n"
                 "geometry:\n  p: {box: {min: [0, 0, 0], max: [0.005, 0.005, 0.005]}}\n"
                 "body: {geometry: p, material: m}\nrun: {end_time: 1.0}\n",
                 models[k]);
        test_deck_refused(buf, "partial_volume_rule");
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_cells_tile_the_sphere),
        cmocka_unit_test(test_refused),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
