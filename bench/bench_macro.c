/**
 * @file bench_macro.c
 * @brief Macro-particle throughput: the rod of [Saitoh] section 2.6 at
 *        n_phi = 16, n_h/n_phi = 4 (51 413 particles, the paper's count),
 *        tension, 500 steps, no output.
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

static int bench_macro_rod(int threads, double scale, struct bench_result *out,
                           struct spall_error *err)
{
    /* scale shrinks the rod length (n_h cells), not the resolution */
    const double D = 14.0e-3, a = D / 16.0, r0 = a / sqrt(2.0);
    double n_h = fmax(2.0, round(64.0 * scale));
    const double L = n_h * a, e = 1e-7 * D;
    long steps = scale < 1.0 ? 50 : 500;
    char yaml[2048];
    snprintf(yaml, sizeof yaml,
             "model: {type: macroparticle, damping: pairwise, mu: 1.0e-3}\n"
             "materials:\n"
             "  al: {density: 2700, atomic_mass_u: 26.98, cohesive_energy_ev: 3.39,\n"
             "       exponents: [4, 9], debye_temperature: 428}\n"
             "lattice: {type: fcc, spacing: %.17g}\n"
             "geometry:\n"
             "  rod: {cylinder: {base: [0, 0, %.17g], top: [0, 0, %.17g], radius: %.17g}}\n"
             "body: {geometry: rod, material: al}\n"
             "groups:\n"
             "  bottom: {box: {min: [-1, -1, -1], max: [1, 1, %.17g]}}\n"
             "  top: {box: {min: [-1, -1, %.17g], max: [1, 1, 1]}}\n"
             "boundary_conditions:\n"
             "  - {group: bottom, type: velocity, components: [z], value: -0.5}\n"
             "  - {group: top, type: velocity, components: [z], value: 0.5}\n"
             "run: {steps: %ld, max_particles: 1e9}\n",
             r0, -e, L + e, 0.5 * D + e, 0.25 * r0, L - 0.25 * r0, steps);
    int rc = bench_run_deck("macro-rod", yaml, threads, 0, out, err);
    if (rc)
        return rc;
    snprintf(out->note, sizeof out->note,
             "[Saitoh] sec. 2.6 rod n_phi 16, n_h %g (paper: 51 413 particles at n_h/n_phi 4); "
             "list pairs r < 1.45 r0", n_h);
    return rc;
}

/* Macro-particle cases, listed by bench/cases.c. */
const struct bench_case bench_macro_cases[] = {
    {"macro-rod", "macro-particle Al rod, n_phi 16, n_h/n_phi 4 (~51k particles), 500 steps",
     bench_macro_rod},
};
const size_t bench_macro_n_cases = sizeof bench_macro_cases / sizeof bench_macro_cases[0];
