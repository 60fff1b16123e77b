/**
 * @file bench.h
 * @brief Throughput benchmarks (`spall bench`).  Never timed tests: numbers
 *        are printed (and written as JSON), not asserted.
 */
#ifndef SPALL_BENCH_H
#define SPALL_BENCH_H

#include <stddef.h>

struct sim;
struct spall_error;

struct bench_result {
    char name[48];
    int threads;
    size_t particles;
    size_t bonds;               /**< interactions counted once */
    long steps;
    double seconds;             /**< wall time of the time loop only */
    double cpu_seconds;         /**< CPU time of the process (all threads) in the loop */
    double particle_steps_per_s;
    double bond_steps_per_s;
    double bytes_per_particle;  /**< resident memory growth / particles held (distributed:
                                     summed over the ranks, owned + ghosts, after the
                                     partition) */
    /* under mpirun (bench_par.c; serial: ranks 1, the rest 0) */
    int ranks;
    size_t ghosts;              /**< ghost particles summed over the ranks */
    double halo_bytes_per_step; /**< position-halo bytes sent per step, all ranks */
    double halo_seconds_per_step; /**< wall seconds per step in the halo, largest rank */
    double setup_bytes_per_particle; /**< a rank's growth while building the whole body
                                          (replicated set-up) / particles of the body */
    int uniform_mass;           /**< the run's masses were one value: its passes streamed
                                     none (particles.mass_uniform) */
    char note[384];
};

struct bench_case {
    const char *name;
    const char *title;
    /** Run with @p threads OpenMP threads; @p scale in (0, 16] scales the
     *  problem (1 = the documented size; < 1 quick runs, > 1 resolution
     *  studies). */
    int (*run)(int threads, double scale, struct bench_result *out, struct spall_error *err);
};

/** Number of cases and case k, in registry order (bench/cases.c). */
size_t bench_case_count(void);
const struct bench_case *bench_case_at(size_t k);

/* Per-model case tables, each defined in its bench_<model>.c. */
extern const struct bench_case bench_lattice_cases[];
extern const size_t bench_lattice_n_cases;
/* impact bench table */
extern const struct bench_case bench_impact_cases[];
extern const size_t bench_impact_n_cases;

/* peridynamics bench table */
extern const struct bench_case bench_pd_cases[];
extern const size_t bench_pd_n_cases;

/* macro-particle bench table */
extern const struct bench_case bench_macro_cases[];
extern const size_t bench_macro_n_cases;

/* sph bench table */
extern const struct bench_case bench_sph_cases[];
extern const size_t bench_sph_n_cases;
/* penetration (bench_pen.c) */
extern const struct bench_case bench_pen_cases[];
extern const size_t bench_pen_n_cases;


/** Build the simulation of YAML text @p yaml, run it on @p threads threads
 *  for its whole length or @p max_steps steps (when > 0) and fill @p out
 *  (time loop only; memory = resident growth while building).  The caller
 *  fills out->note. */
int bench_run_deck(const char *name, const char *yaml, int threads, long max_steps,
                   struct bench_result *out, struct spall_error *err);

/** Under mpirun: partition the built @p s over the ranks (no-op on one
 *  rank); a case whose model cannot run distributed is an error naming the
 *  reason.  Collective. */
int bench_distribute(struct sim *s, const char *name, struct spall_error *err);

/** Fill @p out's totals for the whole run from this rank's measurements
 *  (collective under mpirun): particles and bonds of the body (@p n_body,
 *  @p bonds_body, counted before the partition), the slowest rank's loop
 *  time @p wall, the CPU time of all ranks, memory (resident sizes before
 *  the build @p rss0, after it @p rss_built and after the partition
 *  @p rss_held) and the halo. */
void bench_fill(const struct sim *s, const char *name, int threads, size_t n_body,
                size_t bonds_body, double wall, double cpu, double rss0, double rss_built,
                double rss_held, struct bench_result *out);

/** CPU seconds of this process, all threads (CLOCK_PROCESS_CPUTIME_ID). */
double bench_cpu_seconds(void);

/** Resident set size of this process [bytes] (from /proc/self/statm). */
double bench_rss_bytes(void);

#endif
