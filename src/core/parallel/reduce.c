/**
 * @file reduce.c
 * @brief Values of the whole run on a distributed run (decomp.h): probes
 *        from their owner, and the fragment graph gathered on rank 0 in
 *        global-id order.  (Sums over particles are exact and need no
 *        gather: psum.h.)
 */
#include "core/parallel/decomp.h"
#include "core/parallel/decomp_internal.h"

#include "core/bond_list.h"
#include "core/fragments.h"
#include "core/model.h"
#include "core/parallel/comm.h"
#include "core/particles.h"
#include "core/sim.h"
#include "spall/error.h"

#include <stdlib.h>
#include <string.h>

#ifdef SPALL_HAVE_MPI
#include <mpi.h>
#endif

#ifdef SPALL_HAVE_MPI

struct keyed {
    int64_t key;
    size_t at;
};

static int cmp_keyed(const void *a, const void *b)
{
    int64_t x = ((const struct keyed *)a)->key, y = ((const struct keyed *)b)->key;
    return (x > y) - (x < y);
}

/* Gather (key, row) pairs to rank 0 and sort them by key there; returns the
 * sorted rows (rank 0; NULL elsewhere) and their number in *n_all. */
static double *gather_sorted(const int64_t *key, const double *rows, size_t n, int ncol,
                             size_t *n_all)
{
    const int size = par_size(), rank = par_rank();
    int cnt = (int)n, *counts = NULL, *displs = NULL, *dcounts = NULL, *ddispls = NULL;
    if (rank == 0) {
        counts = malloc((size_t)size * sizeof *counts);
        displs = malloc((size_t)size * sizeof *displs);
        dcounts = malloc((size_t)size * sizeof *dcounts);
        ddispls = malloc((size_t)size * sizeof *ddispls);
    }
    MPI_Gather(&cnt, 1, MPI_INT, counts, 1, MPI_INT, 0, MPI_COMM_WORLD);
    size_t total = 0;
    if (rank == 0)
        for (int r = 0; r < size; r++) {
            displs[r] = (int)total;
            ddispls[r] = (int)(total * (size_t)ncol);
            dcounts[r] = counts[r] * ncol;
            total += (size_t)counts[r];
        }
    int64_t *keys = rank == 0 ? malloc((total ? total : 1) * sizeof *keys) : NULL;
    double *vals = rank == 0 ? malloc((total ? total : 1) * (size_t)ncol * sizeof *vals) : NULL;
    MPI_Gatherv(key, cnt, MPI_INT64_T, keys, counts, displs, MPI_INT64_T, 0, MPI_COMM_WORLD);
    MPI_Gatherv(rows, cnt * ncol, MPI_DOUBLE, vals, dcounts, ddispls, MPI_DOUBLE, 0,
                MPI_COMM_WORLD);
    double *sorted = NULL;
    if (rank == 0) {
        struct keyed *ix = malloc((total ? total : 1) * sizeof *ix);
        sorted = malloc((total ? total : 1) * (size_t)ncol * sizeof *sorted);
        for (size_t q = 0; q < total; q++) {
            ix[q].key = keys[q];
            ix[q].at = q;
        }
        qsort(ix, total, sizeof *ix, cmp_keyed);
        for (size_t q = 0; q < total; q++)
            memcpy(sorted + q * (size_t)ncol, vals + ix[q].at * (size_t)ncol,
                   (size_t)ncol * sizeof *sorted);
        free(ix);
    }
    free(keys);
    free(vals);
    free(counts);
    free(displs);
    free(dcounts);
    free(ddispls);
    *n_all = total;
    return sorted;
}

void par_probe(const struct sim *s, size_t k, double u[3], double v[3])
{
    const struct par_decomp *d = s->par;
    double buf[6] = {0, 0, 0, 0, 0, 0};
    if (d->probe_owner[k] == par_rank()) {
        size_t i = d->probe_local[k];
        for (int c = 0; c < s->dim; c++) {
            buf[c] = s->p->x[c][i] - s->p->x0[c][i];
            buf[3 + c] = s->p->v[c][i];
        }
    }
    MPI_Bcast(buf, 6, MPI_DOUBLE, d->probe_owner[k], MPI_COMM_WORLD);
    memcpy(u, buf, 3 * sizeof *u);
    memcpy(v, buf + 3, 3 * sizeof *v);
}

/* Rank 0 rebuilds the whole particle set (gid, mass, velocity) and the
 * whole bond graph (partner gids, states) in global-id order: the serial
 * arrays, so fragments_compute sees what a serial run sees. */
int par_fragments(const struct sim *s, struct fragments *f, struct spall_error *err)
{
    const struct bond_list *bl = s->ops->bonds ? s->ops->bonds(s->model) : NULL;
    const struct particles *p = s->p;
    const size_t n = p->n_owned;
    const int dim = s->dim, ncol = 2 + dim;
    /* per particle: row length, mass, v; per half-bond: partner gid, state */
    double *rows = malloc((n ? n : 1) * (size_t)ncol * sizeof *rows);
    size_t nh = bl ? bl->offset[n] : 0;
    int64_t *pg = malloc((nh ? nh : 1) * sizeof *pg);
    int rc = SPALL_OK;
    if (!rows || !pg)
        rc = spall_error_set(err, SPALL_ERR_NOMEM, "out of memory gathering fragments");
    for (size_t i = 0; i < n && !rc; i++) {
        rows[i * (size_t)ncol] = (double)(bl ? bl->offset[i + 1] - bl->offset[i] : 0);
        rows[i * (size_t)ncol + 1] = p->mass[i];
        for (int c = 0; c < dim; c++)
            rows[i * (size_t)ncol + 2 + (size_t)c] = p->v[c][i];
        for (size_t q = bl ? bl->offset[i] : 0; q < (bl ? bl->offset[i + 1] : 0); q++)
            pg[q] = (bl->state[q] & BOND_BROKEN) ? -1 - p->gid[bl->partner[q]]
                                                 : p->gid[bl->partner[q]];
    }
    rc = par_agree(rc, err);
    if (rc) {
        free(rows);
        free(pg);
        return rc;
    }
    size_t total = 0;
    double *sorted = gather_sorted(p->gid, rows, n, ncol, &total);
    /* the half-bonds in the owners' order, then re-ordered by gid on rank 0 */
    const int size = par_size(), rank = par_rank();
    int cnt = (int)nh, *counts = NULL, *displs = NULL;
    if (rank == 0) {
        counts = malloc((size_t)size * sizeof *counts);
        displs = malloc((size_t)size * sizeof *displs);
    }
    MPI_Gather(&cnt, 1, MPI_INT, counts, 1, MPI_INT, 0, MPI_COMM_WORLD);
    size_t nh_all = 0;
    if (rank == 0)
        for (int r = 0; r < size; r++) {
            displs[r] = (int)nh_all;
            nh_all += (size_t)counts[r];
        }
    int64_t *all_pg = rank == 0 ? malloc((nh_all ? nh_all : 1) * sizeof *all_pg) : NULL;
    int64_t *all_gid = rank == 0 ? malloc((total ? total : 1) * sizeof *all_gid) : NULL;
    MPI_Gatherv(pg, cnt, MPI_INT64_T, all_pg, counts, displs, MPI_INT64_T, 0, MPI_COMM_WORLD);
    /* the gids in the owners' order, to find each row's half-bonds */
    int gcnt = (int)n;
    int *gcounts = rank == 0 ? malloc((size_t)size * sizeof *gcounts) : NULL;
    int *gdispls = rank == 0 ? malloc((size_t)size * sizeof *gdispls) : NULL;
    MPI_Gather(&gcnt, 1, MPI_INT, gcounts, 1, MPI_INT, 0, MPI_COMM_WORLD);
    if (rank == 0) {
        size_t acc = 0;
        for (int r = 0; r < size; r++) {
            gdispls[r] = (int)acc;
            acc += (size_t)gcounts[r];
        }
    }
    MPI_Gatherv(p->gid, gcnt, MPI_INT64_T, all_gid, gcounts, gdispls, MPI_INT64_T, 0,
                MPI_COMM_WORLD);
    if (rank == 0) {
        struct particles *fp = NULL;
        struct bond_list fb;
        memset(&fb, 0, sizeof fb);
        size_t *src_off = malloc((total + 1) * sizeof *src_off); /* by gid: start in all_pg */
        fb.offset = calloc(total + 1, sizeof *fb.offset);
        fb.partner = malloc((nh_all ? nh_all : 1) * sizeof *fb.partner);
        fb.state = calloc(nh_all ? nh_all : 1, 1);
        rc = particles_create(&fp, dim, total ? total : 1, err);
        if (!rc && (!src_off || !fb.offset || !fb.partner || !fb.state))
            rc = spall_error_set(err, SPALL_ERR_NOMEM, "out of memory gathering fragments");
        if (!rc) {
            /* owners' order -> gid: the gathered rows of gid g start at src_off[g] */
            size_t acc = 0;
            for (size_t q = 0; q < total; q++) {
                size_t g = (size_t)all_gid[q];
                src_off[g] = acc;
                acc += (size_t)sorted[g * (size_t)ncol];
            }
            fp->n = fp->n_owned = total;
            fb.n = total;
            size_t w = 0;
            for (size_t g = 0; g < total; g++) {
                const double *r = sorted + g * (size_t)ncol;
                size_t len = (size_t)r[0];
                fp->gid[g] = (int64_t)g;
                fp->mass[g] = r[1];
                for (int c = 0; c < dim; c++)
                    fp->v[c][g] = r[2 + c];
                for (size_t q = 0; q < len; q++) {
                    int64_t v = all_pg[src_off[g] + q];
                    fb.partner[w] = (int32_t)(v < 0 ? -1 - v : v);
                    fb.state[w++] = v < 0 ? BOND_BROKEN : 0;
                }
                fb.offset[g + 1] = w;
            }
            rc = fragments_compute(f, fp, dim, &fb, err);
        }
        particles_destroy(&fp);
        free(src_off);
        free(fb.offset);
        free(fb.partner);
        free(fb.state);
    }
    free(all_pg);
    free(all_gid);
    free(counts);
    free(displs);
    free(gcounts);
    free(gdispls);
    free(sorted);
    free(rows);
    free(pg);
    return par_agree(rc, err);
}

#else

void par_probe(const struct sim *s, size_t k, double u[3], double v[3])
{
    size_t i = s->probes[k].particle;
    for (int c = 0; c < 3; c++) {
        u[c] = c < s->dim ? s->p->x[c][i] - s->p->x0[c][i] : 0.0;
        v[c] = c < s->dim ? s->p->v[c][i] : 0.0;
    }
}

int par_fragments(const struct sim *s, struct fragments *f, struct spall_error *err)
{
    return fragments_of_sim(f, s, err);
}

#endif
