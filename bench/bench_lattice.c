/**
 * @file bench_lattice.c
 * @brief Lattice-model throughput: 2D triangular α model, 1 000 000
 *        particles, 500 steps, no output (issue: engine core, item 8).
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
#include <unistd.h>

double bench_rss_bytes(void)
{
    FILE *f = fopen("/proc/self/statm", "r");
    if (!f)
        return 0.0;
    long size = 0, rss = 0;
    if (fscanf(f, "%ld %ld", &size, &rss) != 2)
        rss = 0;
    fclose(f);
    return (double)rss * (double)sysconf(_SC_PAGESIZE);
}

int bench_run_deck(const char *name, const char *yaml, int threads, long max_steps,
                   struct bench_result *out, struct spall_error *err)
{
    omp_set_num_threads(threads);
    double rss0 = bench_rss_bytes();
    struct deck *d = NULL;
    struct sim *s = NULL;
    struct run_output ro;
    int rc = deck_load_string(&d, name, yaml, err);
    if (!rc)
        rc = deck_build_sim(d, &s, &ro, err);
    if (rc) {
        deck_destroy(&d);
        return rc;
    }
    double rss1 = bench_rss_bytes();
    double t0 = omp_get_wtime();
    while (!sim_done(s) && !rc && (max_steps <= 0 || s->step < max_steps))
        rc = sim_step(s, err);
    double wall = omp_get_wtime() - t0;
    memset(out, 0, sizeof *out);
    snprintf(out->name, sizeof out->name, "%s", name);
    out->threads = threads;
    out->particles = s->p->n_owned;
    out->bonds = s->ops->interactions ? s->ops->interactions(s->model, s) : 0;
    out->steps = s->step;
    out->seconds = wall;
    out->particle_steps_per_s = wall > 0 ? (double)out->particles * (double)out->steps / wall : 0;
    out->bond_steps_per_s = wall > 0 ? (double)out->bonds * (double)out->steps / wall : 0;
    out->bytes_per_particle = (rss1 - rss0) / (double)out->particles;
    sim_destroy(&s);
    deck_destroy(&d);
    return rc;
}

static int bench_lattice2d(int threads, double scale, struct bench_result *out,
                           struct spall_error *err)
{
    /* 1000 x 1000 sites of a triangular lattice: width 1000 r0, height
     * 999 rows * sqrt(3)/2 r0 */
    double r0 = 1e-3;
    int n_side = (int)lround(1000.0 * sqrt(scale));
    if (n_side < 10)
        n_side = 10;
    double w = (n_side - 0.5) * r0, h = ((n_side - 1) * sqrt(3.0) / 2.0 + 0.25) * r0;
    long steps = scale < 1.0 ? 50 : 500;
    char yaml[2048];
    snprintf(yaml, sizeof yaml,
             "model: {type: lattice, law: linear}\n"
             "materials:\n"
             "  pmma: {density: 1140, youngs_modulus: 3.0e9, poisson_ratio: 0.3333333333333333,\n"
             "         failure_strain: 0.02}\n"
             "lattice: {type: triangular, spacing: %.17g}\n"
             "geometry:\n"
             "  plate: {box: {min: [%.17g, %.17g], max: [%.17g, %.17g]}}\n"
             "body: {geometry: plate, material: pmma}\n"
             "groups:\n"
             "  left: {box: {min: [-1, -1], max: [%.17g, 1]}}\n"
             "boundary_conditions:\n"
             "  - {group: left, type: velocity, components: [x], value: -1.0}\n"
             "run: {steps: %ld, max_particles: 1e9}\n",
             r0, -0.25 * r0, -0.25 * r0, w, h, 0.5 * r0, steps);
    int rc = bench_run_deck("lattice2d", yaml, threads, 0, out, err);
    if (!rc)
        snprintf(out->note, sizeof out->note,
                 "2D triangular alpha model, linear law, velocity-loaded edge");
    return rc;
}

/* Lattice cases, listed by bench/cases.c. */
const struct bench_case bench_lattice_cases[] = {
    {"lattice2d", "2D triangular alpha lattice, 1e6 particles, 500 steps", bench_lattice2d},
};
const size_t bench_lattice_n_cases = sizeof bench_lattice_cases / sizeof bench_lattice_cases[0];
