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
#include <stdbool.h>
#include <stdint.h>
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
    if (!rc) {
        bench_fill(s, name, threads, n_body, bonds, wall, cpu, rss0, rss1, rss2, out);
        out->uniform_mass = s->p->mass_uniform > 0.0;
    }
    sim_destroy(&s);
    deck_destroy(&d);
    return rc;
}

/* The lattice2d step's memory traffic (docs/performance.md, "Roofline of
 * the lattice step"): 2D, one bond type, h half-bonds per particle, the
 * rest lengths compacted to @p rest_bytes (bond_list_compact_rest), 8 B of
 * mass per pass that reads the masses or 0 with one uniform mass
 * (@p mass_bytes), the NaN check's kinetic sums formed in the second kick
 * (@p sum_in_kick; a distributed run sums them per rank instead).  Each
 * pass streams its arrays once: a line read from beyond the core's own
 * caches is counted once, a line written once more for its write-back; a
 * line written without being read (the forces, which the bond loop writes
 * over: model_ops.sets_forces) is read first all the same
 * (write-allocate).
 * The partners' positions come from the caches (rows j = i +- 1,
 * i +- n_side +- 1), as do a chunk's masses for its second component.  The
 * stencil blocks of the once-per-bond loop (lattice_half.c) read no
 * partners and no row offsets, but the state and rest index of every slot
 * (a row's upper slots share their cache lines with its lower ones); the
 * first kick and the drift are one pass (core/step_passes.c), which reads
 * the forces without clearing them.  Valgrind's cache simulation of the
 * step (2 MiB last level, the L2 of one core): docs/performance.md. */
struct lattice_traffic {
    double kick_drift, force, bond, kick, check;
};

static struct lattice_traffic lattice2d_traffic(double h, double rest_bytes, double mass_bytes,
                                                bool sum_in_kick)
{
    return (struct lattice_traffic){
        .kick_drift = mass_bytes + 2 * (8 + 2 * 8 + 2 * 8), /* m; per dimension f read, v
                                                               and x read and written */
        .force = 2 * 8 + 2 * 16,         /* bond loop: x_i; f written (read first) */
        .bond = h * (rest_bytes + 1),    /* and each slot's rest index and state */
        .kick = mass_bytes + 2 * (8 + 8 + 8),           /* m; f, v read, v written */
        .check = sum_in_kick ? 0.0 : 8 + 2 * 8, /* NaN check and kinetic energy: m, v */
    };
}

static double traffic_total(const struct lattice_traffic *t)
{
    return t->kick_drift + t->force + t->bond + t->kick + t->check;
}

/* Arrays of the replay: the step's streams without their arithmetic. */
struct replay {
    size_t n;
    double bond_bytes; /* per particle */
    bool mass;         /* the kicks stream m (else one uniform mass) */
    bool check;        /* the NaN check is a pass of its own (else in the second kick) */
    double *m, *x[2], *v[2], *f[2];
    uint64_t *bonds;
};

/* The replay in the versions the step's passes have (core/step_passes.c):
 * four lanes on x86-64-v3, picked at load time, else the baseline's two. */
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && defined(__linux__) &&     \
    !defined(SPALL_NO_CLONES)
#define REPLAY_CLONES __attribute__((noinline, target_clones("arch=x86-64-v3", "default")))
#else
#define REPLAY_CLONES
#endif

/* Particles per chunk of a replay pass (as core/step_passes.c's). */
#define REPLAY_CHUNK 2048

/* First bond word of particle @p i (the words of [i, j) are those the
 * bond bytes of these particles fill). */
static size_t bond_word(const struct replay *r, size_t i)
{
    return (size_t)ceil((double)i * r->bond_bytes / 8.0);
}

/* One step's passes over the thread's share [lo, hi) of the particles,
 * each array streamed as the step streams it (lattice2d_traffic), with a
 * multiply or an add where the step computes: the memory traffic alone.
 * Without r->mass the kicks multiply by a constant (one uniform mass);
 * without r->check the second kick also sums v (the kinetic sums).
 * Returns a sum the caller keeps (else the reads could be dropped). */
static inline double replay_passes(const struct replay *r, size_t lo, size_t hi, const bool mass,
                                   const bool check)
{
    const double q = 0x1p-20;
    uint64_t w = 0;
    double acc = 0.0;
    /* first kick and drift: m, f read; v, x read and written */
    for (size_t c = lo; c < hi; c += REPLAY_CHUNK) {
        const size_t e = hi - c < REPLAY_CHUNK ? hi : c + REPLAY_CHUNK;
        for (int d = 0; d < 2; d++) {
            double *restrict x = r->x[d], *restrict v = r->v[d], *restrict f = r->f[d];
            const double *restrict m = r->m;
            for (size_t i = c; i < e; i++) {
                const double vi = v[i] + q * f[i] * (mass ? m[i] : q);
                v[i] = vi;
                x[i] += q * vi;
            }
        }
    }
    /* bond loop: x read, f written over, the bond bytes read */
    for (size_t c = lo; c < hi; c += REPLAY_CHUNK) {
        const size_t e = hi - c < REPLAY_CHUNK ? hi : c + REPLAY_CHUNK;
        for (int d = 0; d < 2; d++) {
            const double *restrict x = r->x[d];
            double *restrict f = r->f[d];
            for (size_t i = c; i < e; i++)
                f[i] = q * x[i];
        }
        const uint64_t *restrict b = r->bonds;
        for (size_t k = bond_word(r, c); k < bond_word(r, e); k++)
            w += b[k];
    }
    /* second kick: m, f read, v read and written (and summed) */
    for (size_t c = lo; c < hi; c += REPLAY_CHUNK) {
        const size_t e = hi - c < REPLAY_CHUNK ? hi : c + REPLAY_CHUNK;
        for (int d = 0; d < 2; d++) {
            double *restrict v = r->v[d];
            const double *restrict f = r->f[d], *restrict m = r->m;
            for (size_t i = c; i < e; i++) {
                const double vi = v[i] + q * f[i] * (mass ? m[i] : q);
                v[i] = vi;
                if (!check)
                    acc += vi;
            }
        }
    }
    /* NaN check: m, v read */
    for (size_t c = lo; check && c < hi; c += REPLAY_CHUNK) {
        const size_t e = hi - c < REPLAY_CHUNK ? hi : c + REPLAY_CHUNK;
        for (int d = 0; d < 2; d++)
            for (size_t i = c; i < e; i++)
                acc += (mass ? r->m[i] : q) * r->v[d][i];
    }
    return acc + (double)(w & 1u);
}

REPLAY_CLONES static double replay_range(const struct replay *r, size_t lo, size_t hi)
{
    if (r->mass)
        return r->check ? replay_passes(r, lo, hi, true, true)
                        : replay_passes(r, lo, hi, true, false);
    return r->check ? replay_passes(r, lo, hi, false, true) : replay_passes(r, lo, hi, false, false);
}

static void replay_free(struct replay *r)
{
    free(r->m);
    for (int d = 0; d < 2; d++) {
        free(r->x[d]);
        free(r->v[d]);
        free(r->f[d]);
    }
    free(r->bonds);
}

/* Memory bandwidth [B/s] for the lattice2d step's own streams: its passes
 * replayed (replay_range) over arrays of its @p n particles on @p threads
 * threads, each thread sweeping the static share the step's passes give it
 * (and touching it first), best of REPLAY_REPS steps, the bytes per
 * particle-step of @p tr (lattice2d_traffic; @p mass: the kicks stream the
 * masses).  The step and this measurement move the same bytes through the same levels of the
 * memory hierarchy (a working set of the same size: on a VM with a large
 * shared L3 part of it may stay there), so the step's share of it is at
 * most 1 up to the noise of a timing.  0 when out of memory. */
#define REPLAY_REPS 20
static double replay_bandwidth(size_t n, const struct lattice_traffic *tr, bool mass,
                               int threads)
{
    const double bytes = traffic_total(tr);
    struct replay r = {.n = n, .bond_bytes = tr->bond, .mass = mass, .check = tr->check > 0.0};
    const size_t nw = bond_word(&r, n);
    int ok = (r.m = malloc(n * sizeof(double))) != NULL;
    for (int d = 0; d < 2; d++) {
        ok &= (r.x[d] = malloc(n * sizeof(double))) != NULL;
        ok &= (r.v[d] = malloc(n * sizeof(double))) != NULL;
        ok &= (r.f[d] = malloc(n * sizeof(double))) != NULL;
    }
    ok &= (r.bonds = malloc((nw ? nw : 1) * sizeof *r.bonds)) != NULL;
    double best = 0.0, keep = 0.0;
    if (ok) {
        omp_set_num_threads(threads);
#pragma omp parallel reduction(+ : keep)
        {
            const size_t nt = (size_t)omp_get_num_threads(), t = (size_t)omp_get_thread_num();
            const size_t lo = n * t / nt, hi = n * (t + 1) / nt;
            for (size_t i = lo; i < hi; i++) { /* first touch by the sweeping thread */
                r.m[i] = 1.0;
                for (int d = 0; d < 2; d++)
                    r.x[d][i] = r.v[d][i] = r.f[d][i] = 0.0;
            }
            for (size_t k = bond_word(&r, lo); k < bond_word(&r, hi); k++)
                r.bonds[k] = k;
#pragma omp barrier
            for (int rep = 0; rep < REPLAY_REPS; rep++) {
#pragma omp barrier
                double t0 = 0.0;
#pragma omp master
                t0 = omp_get_wtime();
                keep += replay_range(&r, lo, hi);
#pragma omp barrier
#pragma omp master
                {
                    const double dt = omp_get_wtime() - t0;
                    if (dt > 0.0 && bytes * (double)n / dt > best)
                        best = bytes * (double)n / dt;
                }
            }
        }
    }
    replay_free(&r);
    volatile double sink = keep; /* the replay's reads are used */
    (void)sink;
    return best;
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
    if (!rc) {
        const double halves = 2.0 * (double)out->bonds / (double)out->particles;
        const struct lattice_traffic tr =
            lattice2d_traffic(halves, 2.0, out->uniform_mass ? 0.0 : 8.0, par_size() == 1);
        const double bytes = traffic_total(&tr);
        /* after the run (its memory given back), not to disturb B/particle */
        const double bw = replay_bandwidth(out->particles, &tr, !out->uniform_mass, threads);
        const double rate = out->seconds > 0 ? bytes * (double)out->particles *
                                                   (double)out->steps / out->seconds
                                             : 0.0;
        const double cpu_rate = out->cpu_seconds > 0 ? (double)out->bonds * (double)out->steps /
                                                           out->cpu_seconds
                                                     : 0.0;
        snprintf(out->note, sizeof out->note,
                 "2D triangular alpha model, linear law, velocity-loaded edge; %.3g bond-steps "
                 "per CPU-second; the step moves %.0f B/particle: %.1f GB/s = %.0f %% of the "
                 "%.1f GB/s its passes reach replayed without their arithmetic (roofline %.3g "
                 "bond-steps/s)",
                 cpu_rate, bytes, 1e-9 * rate, bw > 0 ? 100.0 * rate / bw : 0.0, 1e-9 * bw,
                 bw * (double)out->bonds / ((double)out->particles * bytes));
    }
    return rc;
}

/* Lattice cases, listed by bench/cases.c. */
const struct bench_case bench_lattice_cases[] = {
    {"lattice2d", "2D triangular alpha lattice, 1e6 particles, 500 steps", bench_lattice2d},
};
const size_t bench_lattice_n_cases = sizeof bench_lattice_cases / sizeof bench_lattice_cases[0];
