/**
 * @file bench.h
 * @brief Throughput benchmarks (`spall bench`).  Never timed tests: numbers
 *        are printed (and written as JSON), not asserted.
 */
#ifndef SPALL_BENCH_H
#define SPALL_BENCH_H

#include <stddef.h>

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
    double bytes_per_particle;  /**< resident memory growth / particles */
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

/** CPU seconds of this process, all threads (CLOCK_PROCESS_CPUTIME_ID). */
double bench_cpu_seconds(void);

/** Resident set size of this process [bytes] (from /proc/self/statm). */
double bench_rss_bytes(void);

#endif
