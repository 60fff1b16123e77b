/**
 * @file step.c
 * @brief Distributed replicas of the integrator's sums (step.h).  Each
 *        term is the serial loop's expression, evaluated by the particle's
 *        owner; rank 0 adds them in the serial loop's order.
 */
#include "core/parallel/step.h"

#include "core/bc_work.h"
#include "core/parallel/comm.h"
#include "core/parallel/decomp.h"
#include "core/particles.h"
#include "core/sim.h"

#include <math.h>
#include <stdlib.h>

#ifdef SPALL_HAVE_MPI
#include <mpi.h>
#endif

/* Row-major chains: out[0] = sum over rows, then columns 0, 2, 4, ...;
 * out[1] over columns 1, 3, 5, ... (the serial loop i outer, d inner with
 * two accumulators). */
static void reduce_pairs_rowmajor(const double *rows, size_t n, int ncol, double *out,
                                  const void *ctx)
{
    (void)ctx;
    double a = 0.0, b = 0.0;
    for (size_t q = 0; q < n; q++)
        for (int c = 0; c + 1 < ncol; c += 2) {
            a += rows[q * (size_t)ncol + (size_t)c];
            b += rows[q * (size_t)ncol + (size_t)c + 1];
        }
    out[0] = a;
    out[1] = b;
}

void par_body_work(struct sim *s, double dt)
{
    const struct particles *p = s->p;
    const int dim = s->dim, ncol = 2 * dim;
    double *rows = malloc((p->n_owned ? p->n_owned : 1) * (size_t)ncol * sizeof *rows);
    double out[2] = {0.0, 0.0};
    if (rows) {
        for (size_t i = 0; i < p->n_owned; i++)
            for (int d = 0; d < dim; d++) {
                double v = p->v[d][i];
                rows[i * (size_t)ncol + 2 * (size_t)d] = s->damping * p->mass[i] * v * v * dt;
                rows[i * (size_t)ncol + 2 * (size_t)d + 1] = p->mass[i] * s->gravity[d] * v * dt;
            }
        par_ordered_reduce(p->gid, rows, p->n_owned, ncol, reduce_pairs_rowmajor, NULL, out, 2);
    }
    free(rows);
    s->energy.damping += out[0];
    s->energy.external += out[1];
}

/* Columns [0, dim): reactions, summed per column; [dim, 2 dim): work, one
 * chain over the masked columns in order (d outer, members inner). */
struct bc_ctx {
    int dim;
    unsigned mask;
};

static void reduce_bc(const double *rows, size_t n, int ncol, double *out, const void *ctx)
{
    const struct bc_ctx *c = ctx;
    double work = 0.0;
    for (int d = 0; d < c->dim; d++) {
        double r = 0.0;
        if (c->mask & (1u << d))
            for (size_t q = 0; q < n; q++) {
                r += rows[q * (size_t)ncol + (size_t)d];
                work += rows[q * (size_t)ncol + (size_t)(c->dim + d)];
            }
        out[d] = r;
    }
    out[c->dim] = work;
}

void par_bc_velocities(struct sim *s, struct bc *b, const double vp[3], const double vb[3],
                       double half_dt, int record)
{
    struct particles *p = s->p;
    const struct group *g = &s->groups[b->group];
    const int dim = s->dim, ncol = 2 * dim;
    double *rows = calloc((g->n ? g->n : 1) * (size_t)ncol, sizeof *rows);
    int64_t *key = malloc((g->n ? g->n : 1) * sizeof *key);
    double out[4] = {0, 0, 0, 0};
    if (rows && key) {
        for (size_t q = 0; q < g->n; q++)
            key[q] = par_group_key(s, b->group, q);
        for (int d = 0; d < dim; d++) {
            if (!(b->comp_mask & (1u << d)))
                continue;
            for (size_t q = 0; q < g->n; q++) {
                size_t i = g->idx[q];
                double dv = vb[d] - p->v[d][i];
                rows[q * (size_t)ncol + (size_t)d] = p->mass[i] * dv / half_dt;
                rows[q * (size_t)ncol + (size_t)(dim + d)] = bc_constraint_work(
                    p->mass[i], vp[d], p->v[d][i], vb[d], record ? vp[d] : vb[d]);
                p->v[d][i] = vb[d];
            }
        }
        struct bc_ctx c = {dim, b->comp_mask};
        par_ordered_reduce(key, rows, g->n, ncol, reduce_bc, &c, out, dim + 1);
    }
    free(rows);
    free(key);
    if (record) {
        for (int d = 0; d < 3; d++)
            b->reaction[d] = d < dim ? out[d] : 0.0;
    }
    b->work += out[dim];
    s->energy.external += out[dim];
}

static void reduce_chain_masked(const double *rows, size_t n, int ncol, double *out,
                                const void *ctx)
{
    const struct bc_ctx *c = ctx;
    double w = 0.0;
    for (int d = 0; d < ncol; d++)
        if (c->mask & (1u << d))
            for (size_t q = 0; q < n; q++)
                w += rows[q * (size_t)ncol + (size_t)d];
    out[0] = w;
}

double par_load_work(const struct sim *s, const struct bc *b, double dt)
{
    const struct particles *p = s->p;
    const struct group *g = &s->groups[b->group];
    const int dim = s->dim;
    const double gn = (double)sim_group_count(s, b->group);
    double *rows = calloc((g->n ? g->n : 1) * (size_t)dim, sizeof *rows);
    int64_t *key = malloc((g->n ? g->n : 1) * sizeof *key);
    double w = 0.0;
    if (rows && key) {
        for (size_t q = 0; q < g->n; q++) {
            key[q] = par_group_key(s, b->group, q);
            for (int d = 0; d < dim; d++) {
                double per = b->reaction[d] / gn;
                rows[q * (size_t)dim + (size_t)d] = per * p->v[d][g->idx[q]] * dt;
            }
        }
        struct bc_ctx c = {dim, b->comp_mask};
        par_ordered_reduce(key, rows, g->n, dim, reduce_chain_masked, &c, &w, 1);
    }
    free(rows);
    free(key);
    return w;
}

double par_kinetic(const struct sim *s)
{
    const struct particles *p = s->p;
    double *rows = malloc((p->n_owned ? p->n_owned : 1) * sizeof *rows);
    double ke = 0.0;
    if (rows) {
        for (size_t i = 0; i < p->n_owned; i++) {
            double v2 = 0.0;
            for (int d = 0; d < s->dim; d++)
                v2 += p->v[d][i] * p->v[d][i];
            rows[i] = 0.5 * p->mass[i] * v2;
        }
        par_sum_owned(s, rows, 1, &ke);
    }
    free(rows);
    return ke;
}

int par_check_finite(const struct sim *s, int64_t *bad_gid, double *kinetic)
{
    /* the serial check: per component, the kinetic sum; where it is not
     * finite, the first particle (by gid) with a non-finite v or x in it */
    const struct particles *p = s->p;
    double acc[3] = {0, 0, 0};
    int64_t bad[3] = {INT64_MAX, INT64_MAX, INT64_MAX};
    for (int d = 0; d < s->dim; d++)
        for (size_t i = 0; i < p->n_owned; i++) {
            double v = p->v[d][i];
            acc[d] += p->mass[i] * v * v;
            if ((!isfinite(v) || !isfinite(p->x[d][i])) && p->gid[i] < bad[d])
                bad[d] = p->gid[i];
        }
#ifdef SPALL_HAVE_MPI
    /* reduce on rank 0 and broadcast: an allreduce may round differently
     * on different ranks, and every rank must take the same branch below */
    double tot[3] = {0, 0, 0};
    MPI_Reduce(acc, tot, 3, MPI_DOUBLE, MPI_SUM, 0, MPI_COMM_WORLD);
    MPI_Bcast(tot, 3, MPI_DOUBLE, 0, MPI_COMM_WORLD);
    for (int d = 0; d < 3; d++)
        acc[d] = tot[d];
    MPI_Allreduce(MPI_IN_PLACE, bad, 3, MPI_INT64_T, MPI_MIN, MPI_COMM_WORLD);
#endif
    *kinetic = 0.0;
    for (int d = 0; d < s->dim; d++) {
        *kinetic += 0.5 * acc[d];
        if (!isfinite(acc[d]) && bad[d] != INT64_MAX) {
            *bad_gid = bad[d];
            return 1;
        }
    }
    return 0;
}

int64_t par_fastest_gid(const struct sim *s)
{
    const struct particles *p = s->p;
    double vmax = -1.0;
    int64_t best = INT64_MAX;
    for (size_t i = 0; i < p->n_owned; i++) {
        double v2 = 0.0;
        for (int d = 0; d < s->dim; d++)
            v2 += p->v[d][i] * p->v[d][i];
        if (isnan(v2))
            v2 = INFINITY; /* the serial scan stops at the first NaN */
        if (v2 > vmax || (v2 == vmax && p->gid[i] < best)) {
            vmax = v2;
            best = p->gid[i];
        }
    }
    double gmax = par_max_double(vmax);
    return par_min_i64(vmax == gmax ? best : INT64_MAX);
}
