/**
 * @file gather.c
 * @brief Values of particles by global id on every rank (gather.h).
 *
 * The owners' values travel as (gid, value) pairs in one MPI_Allgatherv
 * each: the values are copied, never combined, so what a caller computes
 * from them is what the serial run computes.
 */
#include "core/parallel/gather.h"

#include "core/parallel/comm.h"
#include "core/parallel/decomp.h"
#include "core/parallel/decomp_internal.h"
#include "core/particles.h"
#include "core/sim.h"
#include "spall/error.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <time.h>

#ifdef SPALL_HAVE_MPI
#include <mpi.h>
#endif

size_t par_owned_index(const struct sim *s, int64_t gid)
{
    const struct particles *p = s->p;
    if (!s->par) /* serial: the index is the gid unless a caller renumbered */
        return (gid >= 0 && (size_t)gid < p->n_owned && p->gid[gid] == gid) ? (size_t)gid
                                                                            : SIZE_MAX;
    /* owned particles are held in ascending gid (decomp.h) */
    size_t lo = 0, hi = p->n_owned;
    while (lo < hi) {
        size_t mid = lo + (hi - lo) / 2;
        if (p->gid[mid] < gid)
            lo = mid + 1;
        else
            hi = mid;
    }
    return lo < p->n_owned && p->gid[lo] == gid ? lo : SIZE_MAX;
}

#ifdef SPALL_HAVE_MPI
/* Every rank's @p n pairs (gid, value) to every rank; @p *total pairs.
 * Returns 0 or -1 when this rank is out of memory (it still took part). */
static int allgather_pairs(const int64_t *gid, const double *val, size_t n, int64_t **gid_all,
                           double **val_all, size_t *total)
{
    const int size = par_size();
    int cnt = (int)n;
    int *counts = malloc((size_t)size * sizeof *counts);
    int *displs = malloc((size_t)size * sizeof *displs);
    int ok = counts && displs;
    int all_ok = 0;
    MPI_Allreduce(&ok, &all_ok, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
    if (!all_ok) {
        free(counts);
        free(displs);
        return -1;
    }
    MPI_Allgather(&cnt, 1, MPI_INT, counts, 1, MPI_INT, MPI_COMM_WORLD);
    size_t t = 0;
    for (int r = 0; r < size; r++) {
        displs[r] = (int)t;
        t += (size_t)counts[r];
    }
    int64_t *g = malloc((t ? t : 1) * sizeof *g);
    double *v = malloc((t ? t : 1) * sizeof *v);
    ok = g && v;
    MPI_Allreduce(&ok, &all_ok, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
    if (all_ok) {
        MPI_Allgatherv(gid, cnt, MPI_INT64_T, g, counts, displs, MPI_INT64_T, MPI_COMM_WORLD);
        MPI_Allgatherv(val, cnt, MPI_DOUBLE, v, counts, displs, MPI_DOUBLE, MPI_COMM_WORLD);
    }
    free(counts);
    free(displs);
    if (!all_ok) {
        free(g);
        free(v);
        return -1;
    }
    *gid_all = g;
    *val_all = v;
    *total = t;
    return 0;
}
#endif

int par_gather_by_gid(const struct sim *s, const double *local, double *global,
                      struct spall_error *err)
{
    const struct particles *p = s->p;
    if (!s->par) {
        for (size_t i = 0; i < p->n_owned; i++)
            global[p->gid[i]] = local[i];
        return SPALL_OK;
    }
#ifdef SPALL_HAVE_MPI
    int64_t *g = NULL;
    double *v = NULL;
    size_t t = 0;
    if (allgather_pairs(p->gid, local, p->n_owned, &g, &v, &t))
        return par_agree(spall_error_set(err, SPALL_ERR_NOMEM,
                                         "out of memory gathering %zu particle values",
                                         par_n_global(s)),
                         err);
    for (size_t q = 0; q < t; q++)
        global[g[q]] = v[q];
    free(g);
    free(v);
    return par_agree(SPALL_OK, err);
#else
    (void)err;
    return SPALL_OK;
#endif
}

void par_values_at(const struct sim *s, const double *local, const int64_t *gid, size_t k,
                   double *out)
{
    if (!s->par) {
        for (size_t j = 0; j < k; j++)
            out[j] = local[par_owned_index(s, gid[j])];
        return;
    }
#ifdef SPALL_HAVE_MPI
    /* k is a handful of particles: one fixed-size MPI_Allgather of
     * (owned?, value) per particle and rank; the owner's value is taken */
    enum { CHUNK = 32 };
    const int size = par_size();
    double mine[2 * CHUNK];
    double *all = malloc((size_t)size * 2 * CHUNK * sizeof *all);
    int ok = all != NULL, all_ok = 0;
    MPI_Allreduce(&ok, &all_ok, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
    for (size_t j = 0; j < k; j++) /* what stays if a rank ran out of memory */
        out[j] = NAN;
    for (size_t j0 = 0; all_ok && j0 < k; j0 += CHUNK) {
        const size_t m = k - j0 < CHUNK ? k - j0 : CHUNK;
        for (size_t j = 0; j < m; j++) {
            size_t i = par_owned_index(s, gid[j0 + j]);
            mine[2 * j] = i != SIZE_MAX ? 1.0 : 0.0;
            mine[2 * j + 1] = i != SIZE_MAX ? local[i] : 0.0;
        }
        MPI_Allgather(mine, (int)(2 * m), MPI_DOUBLE, all, (int)(2 * m), MPI_DOUBLE,
                      MPI_COMM_WORLD);
        for (int r = 0; r < size; r++)
            for (size_t j = 0; j < m; j++)
                if (all[(size_t)r * 2 * m + 2 * j] != 0.0)
                    out[j0 + j] = all[(size_t)r * 2 * m + 2 * j + 1];
    }
    free(all);
#endif
}

double par_value_at(const struct sim *s, const double *local, int64_t gid)
{
    double v = 0.0;
    par_values_at(s, local, &gid, 1, &v);
    return v;
}

void par_halo_volume(const struct sim *s, struct par_halo_volume *out)
{
    const struct par_decomp *d = s->par;
    *out = (struct par_halo_volume){0};
    if (!d)
        return;
    out->owned = d->n_owned;
    out->ghosts = d->n_ghost;
    out->sent = d->n_send;
    /* positions and half-step velocities (par_describe counts the same) */
    out->bytes = d->n_send * 2u * (size_t)s->dim * sizeof(double);
    out->exchanges = d->halo_calls;
    out->seconds = d->comm_seconds;
}

void par_barrier_idle(void)
{
#ifdef SPALL_HAVE_MPI
    if (!par_active() || par_size() == 1)
        return;
    MPI_Request req;
    MPI_Ibarrier(MPI_COMM_WORLD, &req);
    int done = 0;
    const struct timespec ms = {0, 1000000};
    for (MPI_Test(&req, &done, MPI_STATUS_IGNORE); !done;
         MPI_Test(&req, &done, MPI_STATUS_IGNORE))
        nanosleep(&ms, NULL);
#endif
}
