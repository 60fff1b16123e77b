/**
 * @file bench_pd.c
 * @brief Peridynamics throughput: the 3D PMB block of bench/pd_vs_lammps.sh
 *        (SC lattice, delta = 3.015 dx, ends pulled apart so bonds break),
 *        48 x 32 x 32 sites, 100 steps, no output.
 */
#include "bench/bench.h"

#include "core/particles.h"
#include "core/sim.h"
#include "io/deck.h"
#include "io/deck_build.h"
#include "core/model.h"
#include "spall/error.h"

#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <string.h>

static int bench_pd3d(int threads, double scale, struct bench_result *out,
                      struct spall_error *err)
{
    const double dx = 1e-3;
    double f = cbrt(scale);
    int nx = (int)lround(48 * f), ny = (int)lround(32 * f);
    if (nx < 12)
        nx = 12;
    if (ny < 8)
        ny = 8;
    long steps = scale < 1.0 ? 20 : 100;
    char yaml[2048];
    snprintf(yaml, sizeof yaml,
             "model: {type: peridynamics, horizon_factor: 3.015, partial_volume_rule: lammps}\n"
             "materials:\n  glass: {density: 2440, bulk_modulus: 48.0e9, critical_stretch: 0.002}\n"
             "lattice: {type: sc, spacing: %.17g}\n"
             "geometry:\n  block: {box: {min: [-0.0005, -0.0005, -0.0005], max: [%.17g, %.17g, "
             "%.17g]}}\n"
             "body: {geometry: block, material: glass}\n"
             "groups:\n  left: {box: {min: [-1, -1, -1], max: [0.0015, 1, 1]}}\n"
             "  right: {box: {min: [%.17g, -1, -1], max: [1, 1, 1]}}\n"
             "boundary_conditions:\n"
             "  - {group: left, type: velocity, components: [x], value: -5.0}\n"
             "  - {group: right, type: velocity, components: [x], value: 5.0}\n"
             "run: {dt: 5.0e-8, dt_override: true, steps: %ld, max_particles: 1e9}\n",
             dx, (nx - 0.5) * dx, (ny - 0.5) * dx, (ny - 0.5) * dx, (nx - 2.5) * dx, steps);
    int rc = bench_run_deck("pd3d", yaml, threads, 0, out, err);
    if (rc)
        return rc;
    snprintf(out->note, sizeof out->note, "3D PMB, SC, delta 3.015 dx, pulled block (breaking)");
    return rc;
}

/* Peridynamics cases, listed by bench/cases.c. */
const struct bench_case bench_pd_cases[] = {
    {"pd3d", "3D PMB block, 48x32x32 SC sites, delta 3.015 dx, 100 steps", bench_pd3d},
};
const size_t bench_pd_n_cases = sizeof bench_pd_cases / sizeof bench_pd_cases[0];
