/**
 * @file bench_pen.c
 * @brief Issue 7 item 6: the 1290 m/s gelatin case (validation case
 *        pen-sph-gelatin's deck: axisymmetric SPH, silica 7.38 um, graded
 *        spacing d/10, 3834 particles, 260 ns) timed as a whole (scale 1)
 *        or for its first 300 steps (reduced scale).  Target of the issue:
 *        the whole case under 5 minutes on 2 cores.
 */
#include "bench/bench.h"

#include "spall/error.h"
#include "validation/pen_cases.h"

#include <stdio.h>

static int bench_pen_gelatin(int threads, double scale, struct bench_result *out,
                             struct spall_error *err)
{
    char yaml[4096];
    const double d = 7.38e-6;
    pen_sph_deck(yaml, sizeof yaml, 1290.0, 20.0e6, d / 10.0, 1.0, 260e-9);
    int rc = bench_run_deck("pen-gelatin", yaml, threads, scale < 1.0 ? 300 : 0, out, err);
    if (rc)
        return rc;
    snprintf(out->note, sizeof out->note,
             "%s: axisymmetric SPH, rigid sphere, adaptive dt",
             scale < 1.0 ? "first 300 steps" : "whole case, 260 ns");
    return rc;
}

const struct bench_case bench_pen_cases[] = {
    {"pen-gelatin", "1290 m/s silica into gelatin (pen-sph-gelatin deck), axisymmetric SPH",
     bench_pen_gelatin},
};
const size_t bench_pen_n_cases = sizeof bench_pen_cases / sizeof bench_pen_cases[0];
