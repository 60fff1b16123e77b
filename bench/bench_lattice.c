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
#include "core/parallel/comm.h"
#include "spall/error.h"

#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

double bench_cpu_seconds(void)
{
    struct timespec ts;
    if (clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts) != 0)
        return 0.0;
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

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
    /* the whole body's counts, before a partition makes them local */
    const size_t n_body = s->p->n_owned;
    const size_t bonds = s->ops->interactions ? s->ops->interactions(s->model, s) : 0;
    rc = bench_distribute(s, name, err); /* mpirun: owned + ghosts; no-op on one rank */
    double rss2 = par_size() > 1 ? bench_rss_bytes() : rss1;
    par_barrier(); /* the loop starts together on every rank */
    double t0 = omp_get_wtime(), c0 = bench_cpu_seconds();
    while (!rc && !sim_done(s) && (max_steps <= 0 || s->step < max_steps))
        rc = sim_step(s, err);
    double wall = omp_get_wtime() - t0, cpu = bench_cpu_seconds() - c0;
    if (!rc)
        bench_fill(s, name, threads, n_body, bonds, wall, cpu, rss0, rss1, rss2, out);
    sim_destroy(&s);
    deck_destroy(&d);
    return rc;
}

/* STREAM-triad-like memory bandwidth [B/s] on @p threads threads:
 * a[i] = b[i] + q c[i] over three arrays of 2^23 doubles (64 MiB each,
 * twice the largest L3 of the project's VMs), best of 5 sweeps, counted as
 * STREAM does (24 B per element: no write-allocate traffic).  0 when out
 * of memory. */
static double triad_bandwidth(int threads)
{
    const size_t n = (size_t)1 << 23;
    double *a = malloc(n * sizeof *a), *b = malloc(n * sizeof *b), *c = malloc(n * sizeof *c);
    double best = 0.0;
    if (a && b && c) {
        omp_set_num_threads(threads);
#pragma omp parallel for schedule(static)
        for (size_t i = 0; i < n; i++) { /* first touch by the sweeping thread */
            a[i] = 0.0;
            b[i] = 1.0;
            c[i] = 2.0;
        }
        for (int rep = 0; rep < 5; rep++) {
            const double q = 3.0, t0 = omp_get_wtime();
#pragma omp parallel for schedule(static)
            for (size_t i = 0; i < n; i++)
                a[i] = b[i] + q * c[i];
            const double t = omp_get_wtime() - t0;
            if (t > 0.0 && 24.0 * (double)n / t > best)
                best = 24.0 * (double)n / t;
        }
    }
    free(a);
    free(b);
    free(c);
    return best;
}

/* Bytes the lattice2d step moves to and from memory per particle, counted
 * from the data layout (docs/performance.md, "Roofline of the lattice
 * step" and "Lattice step, round 3"): 2D, one bond type, h half-bonds per
 * particle, the rest lengths compacted to 2 B (bond_list_compact_rest).
 * Every array is streamed once per pass; the partners' positions come from
 * the caches (rows j = i +- 1, i +- n_side +- 1).  The rows take the
 * stencil blocks of the once-per-bond loop (lattice_half.c: no partners,
 * no row offsets read; the state and rest index of every slot, whose cache
 * lines hold the row's), and the first kick, the drift and the clearing of
 * the forces are one pass (core/step_passes.c). */
static double lattice2d_step_bytes(double h, double rest_bytes)
{
    const double kick_drift = 8 + 2 * (2 * 8 + 2 * 8 + 2 * 8); /* m; per dimension f read
                                                 and cleared, v and x read and written */
    const double force = 2 * 8 + 2 * 16 + h * (rest_bytes + 1); /* x_i, f read and
                                                 written; rest index, state */
    const double kick = 8 + 2 * (8 + 8 + 8); /* m; per dimension f, v read, v written */
    const double check = 8 + 2 * 8;          /* NaN check and kinetic energy: m, v */
    return kick_drift + force + kick + check;
}

static int bench_lattice2d(int threads, double scale, struct bench_result *out,
                           struct spall_error *err)
{
    const double bw = triad_bandwidth(threads);
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
    if (!rc) {
        const double halves = 2.0 * (double)out->bonds / (double)out->particles;
        const double bytes = lattice2d_step_bytes(halves, 2.0);
        const double rate = out->seconds > 0 ? bytes * (double)out->particles *
                                                   (double)out->steps / out->seconds
                                             : 0.0;
        const double cpu_rate = out->cpu_seconds > 0 ? (double)out->bonds * (double)out->steps /
                                                           out->cpu_seconds
                                                     : 0.0;
        snprintf(out->note, sizeof out->note,
                 "2D triangular alpha model, linear law, velocity-loaded edge; %.3g bond-steps "
                 "per CPU-second; triad bandwidth %.1f GB/s; the step moves %.0f B/particle: "
                 "%.1f GB/s = %.0f %% of the triad (roofline %.3g bond-steps/s)",
                 cpu_rate, 1e-9 * bw, bytes, 1e-9 * rate, bw > 0 ? 100.0 * rate / bw : 0.0,
                 bw * (double)out->bonds / ((double)out->particles * bytes));
    }
    return rc;
}

/* Lattice cases, listed by bench/cases.c. */
const struct bench_case bench_lattice_cases[] = {
    {"lattice2d", "2D triangular alpha lattice, 1e6 particles, 500 steps", bench_lattice2d},
};
const size_t bench_lattice_n_cases = sizeof bench_lattice_cases / sizeof bench_lattice_cases[0];
