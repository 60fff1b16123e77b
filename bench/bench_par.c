/**
 * @file bench_par.c
 * @brief `spall bench` under mpirun (docs/parallel.md, "validate and bench
 *        under mpirun"): the case's sim is partitioned like `spall run`'s,
 *        and the result describes the whole distributed run.
 *
 * Rates are the whole body's particles (and bonds) times steps over the
 * slowest rank's loop time (every step waits for it).  The halo is the
 * position/velocity exchange before each force call (core/parallel/
 * gather.h, par_halo_volume); the extra one-double halos of LPS dilatations
 * and thermal temperatures are not counted.
 */
#include "bench/bench.h"

#include "core/parallel/comm.h"
#include "core/parallel/gather.h"
#include "core/sim.h"
#include "io/run_par.h"
#include "spall/error.h"

#include <stdint.h>
#include <stdio.h>
#include <string.h>

int bench_distribute(struct sim *s, const char *name, struct spall_error *err)
{
    char why[SPALL_ERROR_MSG_LEN];
    int rc = run_par_distribute_sim(s, why, sizeof why, err);
    if (!rc && why[0])
        rc = spall_error_set(err, SPALL_ERR_INPUT, "'%s' does not run distributed: %s", name,
                             why);
    return rc;
}

/* Integer sum over the ranks of a non-negative quantity, in units of 1e-9
 * (timings and byte counts: exact and independent of the order). */
static double sum_ranks(double v)
{
    v = v > 0.0 ? v : 0.0;
    return par_size() > 1 ? 1e-9 * (double)par_sum_u64((uint64_t)(v * 1e9 + 0.5)) : v;
}

void bench_fill(const struct sim *s, const char *name, int threads, size_t n_body,
                size_t bonds_body, double wall, double cpu, double rss0, double rss_built,
                double rss_held, struct bench_result *out)
{
    struct par_halo_volume h;
    par_halo_volume(s, &h);
    memset(out, 0, sizeof *out);
    snprintf(out->name, sizeof out->name, "%s", name);
    out->threads = threads;
    out->ranks = par_size();
    out->particles = n_body;
    out->bonds = bonds_body;
    out->steps = s->step;
    out->seconds = par_max_double(wall);
    out->cpu_seconds = sum_ranks(cpu);
    const double held = s->par ? (double)(h.owned + h.ghosts) : (double)n_body;
    out->ghosts = (size_t)par_sum_u64(h.ghosts);
    out->particle_steps_per_s =
        out->seconds > 0 ? (double)out->particles * (double)out->steps / out->seconds : 0;
    out->bond_steps_per_s =
        out->seconds > 0 ? (double)out->bonds * (double)out->steps / out->seconds : 0;
    const double held_all = sum_ranks(held);
    out->bytes_per_particle = held_all > 0 ? sum_ranks(rss_held - rss0) / held_all : 0.0;
    out->setup_bytes_per_particle =
        n_body ? par_max_double(rss_built - rss0) / (double)n_body : 0.0;
    if (out->steps > 0) {
        out->halo_bytes_per_step =
            sum_ranks((double)h.bytes * (double)h.exchanges) / (double)out->steps;
        out->halo_seconds_per_step = par_max_double(h.seconds) / (double)out->steps;
    }
}
