/**
 * @file bench_impact.c
 * @brief Punch-shear throughput (issue 3, item 7): the impact-punch case's
 *        deck (3D FCC vinyl ester plate, ~10 000 particles, no-slip plunger),
 *        200 steps (20 at reduced scale), no output.
 */
#include "bench/bench.h"

#include "core/particles.h"
#include "core/sim.h"
#include "io/deck.h"
#include "io/deck_build.h"
#include "models/model.h"
#include "spall/error.h"
#include "validation/impact_cases.h"

#include <omp.h>
#include <stdio.h>
#include <string.h>

static int bench_punch(int threads, double scale, struct bench_result *out,
                       struct spall_error *err)
{
    char yaml[3072];
    /* scale < 1: a coarser lattice (fewer particles), fewer steps */
    double r0 = scale < 1.0 ? 4.0e-3 : 2.5e-3;
    if (impact_punch_deck(yaml, sizeof yaml, r0, "no_slip", 1.0))
        return spall_error_set(err, SPALL_ERR_INTERNAL, "bench impact-punch: deck too long");
    int rc = bench_run_deck("impact-punch", yaml, threads, scale < 1.0 ? 20 : 200, out, err);
    if (rc)
        return rc;
    snprintf(out->note, sizeof out->note,
             "3D FCC r0 = %.1f mm, plunger no-slip contact + clamps; serial contact loop",
             r0 * 1e3);
    return rc;
}

const struct bench_case bench_impact_cases[] = {
    {"impact-punch", "punch-shear plate (seed 000 sec. 3.2.3), 3D FCC, rigid plunger",
     bench_punch},
};
const size_t bench_impact_n_cases = sizeof bench_impact_cases / sizeof bench_impact_cases[0];
