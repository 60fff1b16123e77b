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
    omp_set_num_threads(threads);
    double rss0 = bench_rss_bytes();
    struct deck *d = NULL;
    struct sim *s = NULL;
    struct run_output ro;
    int rc = deck_load_string(&d, "impact-punch", yaml, err);
    if (!rc)
        rc = deck_build_sim(d, &s, &ro, err);
    if (rc) {
        deck_destroy(&d);
        return rc;
    }
    double rss1 = bench_rss_bytes();
    long steps = scale < 1.0 ? 20 : 200;
    double t0 = omp_get_wtime();
    for (long k = 0; k < steps && !rc; k++)
        rc = sim_step(s, err);
    double wall = omp_get_wtime() - t0;
    memset(out, 0, sizeof *out);
    snprintf(out->name, sizeof out->name, "impact-punch");
    out->threads = threads;
    out->particles = s->p->n_owned;
    out->bonds = s->ops->interactions ? s->ops->interactions(s->model, s) : 0;
    out->steps = s->step;
    out->seconds = wall;
    out->particle_steps_per_s = wall > 0 ? (double)out->particles * (double)out->steps / wall : 0;
    out->bond_steps_per_s = wall > 0 ? (double)out->bonds * (double)out->steps / wall : 0;
    out->bytes_per_particle = (rss1 - rss0) / (double)out->particles;
    snprintf(out->note, sizeof out->note,
             "3D FCC r0 = %.1f mm, plunger no-slip contact + clamps; serial contact loop",
             r0 * 1e3);
    sim_destroy(&s);
    deck_destroy(&d);
    return rc;
}

const struct bench_case bench_impact_cases[] = {
    {"impact-punch", "punch-shear plate (seed 000 sec. 3.2.3), 3D FCC, rigid plunger",
     bench_punch},
};
const size_t bench_impact_n_cases = sizeof bench_impact_cases / sizeof bench_impact_cases[0];
