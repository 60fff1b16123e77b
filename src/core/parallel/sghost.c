/**
 * @file sghost.c
 * @brief Spatial ghosts: range + skin around each rank's bounding box
 *        (sghost.h).
 */
#include "core/parallel/sghost.h"

#include "core/parallel/comm.h"
#include "spall/error.h"

#include <math.h>
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>

#ifdef SPALL_HAVE_MPI
#include <mpi.h>
#endif

struct par_sghost {
    int dim;
    double range, skin;
    unsigned mirror;  /**< bit d: also the images in the plane x_d = 0 (par_sghost_set_mirror) */
    size_t n_owned;
    double *x_build;  /**< owned positions at the build, n_owned * dim */
    int64_t *gid_own; /**< owned ids at the build (to name a particle) */
    size_t n_ghost;
    int64_t *ggid;
    double *gx[3];
    int *gowner;
    /* refresh lists of the last build (particles, rank-major) */
    int *scount, *sdispl, *rcount, *rdispl;
    size_t *send_idx; /**< owned index of each particle sent */
    size_t *recv_idx; /**< ghost slot of each particle received */
    size_t n_send, n_recv;
    double *sbuf, *rbuf;
    long builds;
    /* sends of the next build whatever the distance (par_sghost_set_forced):
     * owned indices, rank r's at [fstart[r], fstart[r + 1]) */
    size_t *fidx, *fstart;
};

int par_sghost_set_forced(struct par_sghost *g, size_t n, const size_t *idx, const int *rank,
                          struct spall_error *err)
{
    const int size = par_size();
    free(g->fidx);
    free(g->fstart);
    g->fidx = malloc((n ? n : 1) * sizeof *g->fidx);
    g->fstart = calloc((size_t)size + 2, sizeof *g->fstart);
    if (!g->fidx || !g->fstart) {
        free(g->fidx);
        free(g->fstart);
        g->fidx = g->fstart = NULL;
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory (spatial ghosts, %zu sends)",
                               n);
    }
    /* grouped by rank (a counting sort; the order within a rank is free) */
    for (size_t k = 0; k < n; k++)
        if (rank[k] >= 0 && rank[k] < size)
            g->fstart[rank[k] + 2]++;
    for (int r = 0; r < size; r++)
        g->fstart[r + 2] += g->fstart[r + 1];
    for (size_t k = 0; k < n; k++)
        if (rank[k] >= 0 && rank[k] < size)
            g->fidx[g->fstart[rank[k] + 1]++] = idx[k];
    return SPALL_OK;
}

static void release_build(struct par_sghost *g)
{
    free(g->x_build);
    free(g->gid_own);
    free(g->ggid);
    for (int d = 0; d < 3; d++)
        free(g->gx[d]);
    free(g->gowner);
    free(g->scount);
    free(g->sdispl);
    free(g->rcount);
    free(g->rdispl);
    free(g->send_idx);
    free(g->recv_idx);
    free(g->sbuf);
    free(g->rbuf);
    const int dim = g->dim;
    const double range = g->range, skin = g->skin;
    const unsigned mirror = g->mirror;
    const long builds = g->builds;
    size_t *fidx = g->fidx, *fstart = g->fstart;
    memset(g, 0, sizeof *g);
    g->fidx = fidx;
    g->fstart = fstart;
    g->dim = dim;
    g->range = range;
    g->skin = skin;
    g->mirror = mirror;
    g->builds = builds;
}

int par_sghost_create(struct par_sghost **out, int dim, double range, double skin,
                      struct spall_error *err)
{
    *out = NULL;
    if (dim < 1 || dim > 3 || !(range > 0.0) || !(skin > 0.0) || !isfinite(range + skin))
        return spall_error_set(err, SPALL_ERR_INTERNAL,
                               "spatial ghosts: need 1-3 dimensions and a positive finite range "
                               "and skin (got dim %d, range %g m, skin %g m)",
                               dim, range, skin);
    struct par_sghost *g = calloc(1, sizeof *g);
    if (!g)
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory (spatial ghosts)");
    g->dim = dim;
    g->range = range;
    g->skin = skin;
    *out = g;
    return SPALL_OK;
}

int par_sghost_set_range(struct par_sghost *g, double range, double skin,
                         struct spall_error *err)
{
    if (!(range > 0.0) || !(skin > 0.0) || !isfinite(range + skin))
        return spall_error_set(err, SPALL_ERR_INTERNAL,
                               "spatial ghosts: need a positive finite range and skin (got "
                               "range %g m, skin %g m)",
                               range, skin);
    g->range = range;
    g->skin = skin;
    return SPALL_OK;
}

void par_sghost_destroy(struct par_sghost **gp)
{
    if (!gp || !*gp)
        return;
    release_build(*gp);
    free((*gp)->fidx);
    free((*gp)->fstart);
    free(*gp);
    *gp = NULL;
}

size_t par_sghost_count(const struct par_sghost *g)
{
    return g->n_ghost;
}

const int64_t *par_sghost_gid(const struct par_sghost *g)
{
    return g->ggid;
}

const double *par_sghost_x(const struct par_sghost *g, int d)
{
    return g->gx[d];
}

const int *par_sghost_owner(const struct par_sghost *g)
{
    return g->gowner;
}

long par_sghost_builds(const struct par_sghost *g)
{
    return g->builds;
}

void par_sghost_set_mirror(struct par_sghost *g, unsigned planes)
{
    g->mirror = planes & 7u;
}

void par_sghost_lists(const struct par_sghost *g, struct par_sghost_lists *out)
{
    *out = (struct par_sghost_lists){g->scount, g->sdispl, g->rcount,  g->rdispl,
                                     g->send_idx, g->recv_idx, g->n_send, g->n_recv};
}

int par_sghost_check(const struct par_sghost *g, const double *const x[3], int *rebuild,
                     struct spall_error *err)
{
    const int dim = g->dim;
    double worst = 0.0;
    int64_t past = INT64_MAX; /* smallest id that moved more than the skin */
    double past_d = 0.0;
    for (size_t i = 0; i < g->n_owned; i++) {
        double r2 = 0.0;
        for (int d = 0; d < dim; d++) {
            double u = x[d][i] - g->x_build[i * (size_t)dim + (size_t)d];
            r2 += u * u;
        }
        if (!(r2 <= g->skin * g->skin) && g->gid_own[i] < past) {
            past = g->gid_own[i];
            past_d = sqrt(r2);
        }
        if (r2 > worst || r2 != r2)
            worst = r2 != r2 ? INFINITY : r2;
    }
    worst = par_max_double(worst);
    int64_t bad = par_min_i64(past);
    *rebuild = worst > 0.25 * g->skin * g->skin;
    if (bad == INT64_MAX)
        return SPALL_OK;
    /* the owner knows the distance; hand it to everyone so all say the same */
    double shown = bad == past ? past_d : 0.0;
    shown = par_max_double(shown);
    return spall_error_set(err, SPALL_ERR_UNSTABLE,
                           "spatial ghosts: particle %lld moved %.6g m since the last ghost "
                           "build, more than the skin %.6g m: interactions within the range "
                           "%.6g m may have been missed (rebuild the ghosts when a particle has "
                           "moved skin/2, or enlarge the skin)",
                           (long long)bad, shown, g->skin, g->range);
}

#ifdef SPALL_HAVE_MPI

/* squared distance from point @p p to the box [lo, hi] */
static double box_dist2(const double *p, const double *lo, const double *hi, int dim)
{
    double r2 = 0.0;
    for (int d = 0; d < dim; d++) {
        double u = p[d] < lo[d] ? lo[d] - p[d] : p[d] > hi[d] ? p[d] - hi[d] : 0.0;
        r2 += u * u;
    }
    return r2;
}

/* Is @p p, or with mirror planes one of its images (every combination of
 * the planes x_d = 0 in @p mirror), within sqrt(cut2) of the box [lo, hi]? */
static bool near_box(unsigned mirror, const double *p, const double *lo, const double *hi,
                     int dim, double cut2)
{
    for (unsigned mk = 0; mk < 8; mk++) {
        if (mk & ~mirror)
            continue;
        double q[3] = {p[0], p[1], p[2]};
        for (int d = 0; d < dim; d++)
            if (mk >> d & 1u)
                q[d] = -q[d];
        if (box_dist2(q, lo, hi, dim) <= cut2)
            return true;
    }
    return false;
}

struct gid_slot {
    int64_t gid;
    size_t k;
};

static int cmp_gid_slot(const void *a, const void *b)
{
    const struct gid_slot *x = a, *y = b;
    return (x->gid > y->gid) - (x->gid < y->gid);
}

static int build_lists(struct par_sghost *g, size_t n, const double *const x[3],
                       const int64_t *gid, const double *boxes, struct spall_error *err)
{
    const int size = par_size(), rank = par_rank(), dim = g->dim;
    const size_t bw = 7; /* lo[3], hi[3], non-empty flag */
    const double cut2 = (g->range + g->skin) * (g->range + g->skin);
    g->scount = calloc((size_t)size, sizeof(int));
    g->sdispl = calloc((size_t)size, sizeof(int));
    g->rcount = calloc((size_t)size, sizeof(int));
    g->rdispl = calloc((size_t)size, sizeof(int));
    struct gid_slot *order = malloc((n ? n : 1) * sizeof *order);
    if (!g->scount || !g->sdispl || !g->rcount || !g->rdispl || !order) {
        free(order);
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory (spatial ghosts)");
    }
    /* ascending gid within each destination, whatever the owned order */
    for (size_t i = 0; i < n; i++)
        order[i] = (struct gid_slot){gid[i], i};
    qsort(order, n, sizeof *order, cmp_gid_slot);
    /* the forced sends as a flag per (rank, owned index) row of one rank at
     * a time: mark[i] = r + 1 while rank r's list is made */
    int *mark = calloc(n ? n : 1, sizeof *mark);
    if (!mark) {
        free(order);
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory (spatial ghosts)");
    }
    size_t total = 0;
    for (int pass = 0; pass < 2; pass++) {
        if (pass == 1) {
            g->send_idx = malloc((total ? total : 1) * sizeof *g->send_idx);
            if (!g->send_idx) {
                free(order);
                free(mark);
                return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory (spatial ghosts)");
            }
        }
        size_t at = 0;
        for (int r = 0; r < size; r++) {
            const double *b = boxes + (size_t)r * bw;
            if (r == rank)
                continue;
            for (size_t f = g->fstart ? g->fstart[r] : 0; g->fstart && f < g->fstart[r + 1]; f++)
                if (g->fidx[f] < n)
                    mark[g->fidx[f]] = r + 1;
            for (size_t k = 0; k < n; k++) {
                size_t i = order[k].k;
                double p[3] = {0.0, 0.0, 0.0};
                for (int d = 0; d < dim; d++)
                    p[d] = x[d][i];
                if (mark[i] != r + 1 &&
                    (b[6] == 0.0 || !near_box(g->mirror, p, b, b + 3, dim, cut2)))
                    continue;
                if (pass == 0) {
                    g->scount[r]++;
                    total++;
                } else {
                    g->send_idx[at++] = i;
                }
            }
        }
    }
    free(order);
    free(mark);
    MPI_Alltoall(g->scount, 1, MPI_INT, g->rcount, 1, MPI_INT, MPI_COMM_WORLD);
    int as = 0, ar = 0;
    for (int r = 0; r < size; r++) {
        g->sdispl[r] = as;
        g->rdispl[r] = ar;
        as += g->scount[r];
        ar += g->rcount[r];
    }
    g->n_send = (size_t)as;
    g->n_recv = (size_t)ar;
    return SPALL_OK;
}

int par_sghost_build(struct par_sghost *g, size_t n, const double *const x[3],
                     const int64_t *gid, struct spall_error *err)
{
    release_build(g);
    const int size = par_size(), dim = g->dim;
    g->n_owned = n;
    g->x_build = malloc((n ? n : 1) * (size_t)dim * sizeof *g->x_build);
    g->gid_own = malloc((n ? n : 1) * sizeof *g->gid_own);
    if (!g->x_build || !g->gid_own)
        return par_agree(spall_error_set(err, SPALL_ERR_NOMEM, "out of memory (spatial ghosts)"),
                         err);
    double box[7] = {INFINITY, INFINITY, INFINITY, -INFINITY, -INFINITY, -INFINITY, 0.0};
    for (size_t i = 0; i < n; i++) {
        g->gid_own[i] = gid[i];
        for (int d = 0; d < dim; d++) {
            double v = x[d][i];
            g->x_build[i * (size_t)dim + (size_t)d] = v;
            box[d] = v < box[d] ? v : box[d];
            box[3 + d] = v > box[3 + d] ? v : box[3 + d];
        }
    }
    box[6] = n > 0;
    g->builds++;
    if (size == 1 || !par_active())
        return SPALL_OK;
    double *boxes = malloc((size_t)size * 7 * sizeof *boxes);
    int rc = boxes ? SPALL_OK
                   : spall_error_set(err, SPALL_ERR_NOMEM, "out of memory (spatial ghosts)");
    if ((rc = par_agree(rc, err))) {
        free(boxes);
        return rc;
    }
    MPI_Allgather(box, 7, MPI_DOUBLE, boxes, 7, MPI_DOUBLE, MPI_COMM_WORLD);
    rc = build_lists(g, n, x, gid, boxes, err);
    free(boxes);
    free(g->fidx); /* for this build only */
    free(g->fstart);
    g->fidx = g->fstart = NULL;
    if ((rc = par_agree(rc, err)))
        return rc;
    /* the ids and positions of what each rank receives */
    const size_t ns = g->n_send, nr = g->n_recv;
    int64_t *sg = malloc((ns ? ns : 1) * sizeof *sg), *rg = malloc((nr ? nr : 1) * sizeof *rg);
    g->sbuf = malloc((ns ? ns : 1) * (size_t)dim * sizeof *g->sbuf);
    g->rbuf = malloc((nr ? nr : 1) * (size_t)dim * sizeof *g->rbuf);
    g->ggid = malloc((nr ? nr : 1) * sizeof *g->ggid);
    g->gowner = malloc((nr ? nr : 1) * sizeof *g->gowner);
    g->recv_idx = malloc((nr ? nr : 1) * sizeof *g->recv_idx);
    struct gid_slot *slot = malloc((nr ? nr : 1) * sizeof *slot);
    for (int d = 0; d < dim; d++)
        g->gx[d] = malloc((nr ? nr : 1) * sizeof *g->gx[d]);
    rc = SPALL_OK;
    if (!sg || !rg || !g->sbuf || !g->rbuf || !g->ggid || !g->gowner || !g->recv_idx || !slot)
        rc = SPALL_ERR_NOMEM;
    for (int d = 0; d < dim; d++)
        if (!g->gx[d])
            rc = SPALL_ERR_NOMEM;
    if (rc)
        spall_error_set(err, rc, "out of memory (spatial ghosts)");
    if ((rc = par_agree(rc, err))) {
        free(sg);
        free(rg);
        free(slot);
        return rc;
    }
    for (size_t k = 0; k < ns; k++)
        sg[k] = gid[g->send_idx[k]];
    MPI_Alltoallv(sg, g->scount, g->sdispl, MPI_INT64_T, rg, g->rcount, g->rdispl, MPI_INT64_T,
                  MPI_COMM_WORLD);
    for (int r = 0; r < size; r++)
        for (int k = g->rdispl[r]; k < g->rdispl[r] + g->rcount[r]; k++)
            slot[k] = (struct gid_slot){rg[k], (size_t)k};
    /* ghosts in ascending gid (a particle has one owner: no duplicates) */
    qsort(slot, nr, sizeof *slot, cmp_gid_slot);
    g->n_ghost = nr;
    for (size_t q = 0; q < nr; q++) {
        g->ggid[q] = slot[q].gid;
        g->recv_idx[slot[q].k] = q;
    }
    for (int r = 0; r < size; r++)
        for (int k = g->rdispl[r]; k < g->rdispl[r] + g->rcount[r]; k++)
            g->gowner[g->recv_idx[k]] = r;
    free(sg);
    free(rg);
    free(slot);
    par_sghost_update(g, x);
    return SPALL_OK;
}

void par_sghost_update(struct par_sghost *g, const double *const x[3])
{
    const int size = par_size(), dim = g->dim;
    if (size == 1 || !par_active())
        return;
    for (size_t k = 0; k < g->n_send; k++)
        for (int d = 0; d < dim; d++)
            g->sbuf[k * (size_t)dim + (size_t)d] = x[d][g->send_idx[k]];
    MPI_Request *req = malloc(2 * (size_t)size * sizeof *req);
    int nreq = 0;
    /* neighbours only: a rank far from this one exchanges nothing with it */
    for (int r = 0; r < size && req; r++)
        if (g->rcount[r])
            MPI_Irecv(g->rbuf + (size_t)g->rdispl[r] * (size_t)dim, g->rcount[r] * dim,
                      MPI_DOUBLE, r, 23, MPI_COMM_WORLD, &req[nreq++]);
    for (int r = 0; r < size && req; r++)
        if (g->scount[r])
            MPI_Isend(g->sbuf + (size_t)g->sdispl[r] * (size_t)dim, g->scount[r] * dim,
                      MPI_DOUBLE, r, 23, MPI_COMM_WORLD, &req[nreq++]);
    if (!req) { /* no room for requests: the same exchange, blocking */
        MPI_Alltoallv(g->sbuf, g->scount, g->sdispl, MPI_DOUBLE, g->rbuf, g->rcount, g->rdispl,
                      MPI_DOUBLE, MPI_COMM_WORLD);
    } else {
        MPI_Waitall(nreq, req, MPI_STATUSES_IGNORE);
        free(req);
    }
    for (size_t k = 0; k < g->n_recv; k++)
        for (int d = 0; d < dim; d++)
            g->gx[d][g->recv_idx[k]] = g->rbuf[k * (size_t)dim + (size_t)d];
}

int par_sghost_values(struct par_sghost *g, const double *owned, double *ghost, int ncomp,
                      struct spall_error *err)
{
    const int size = par_size();
    if (size == 1 || !par_active())
        return SPALL_OK;
    const size_t w = (size_t)ncomp;
    double *sb = malloc((g->n_send ? g->n_send : 1) * w * sizeof *sb);
    double *rb = malloc((g->n_recv ? g->n_recv : 1) * w * sizeof *rb);
    int *cnt = malloc(4 * (size_t)size * sizeof *cnt);
    int rc = sb && rb && cnt ? SPALL_OK
                             : spall_error_set(err, SPALL_ERR_NOMEM,
                                               "out of memory (spatial ghost values)");
    if ((rc = par_agree(rc, err))) {
        free(sb);
        free(rb);
        free(cnt);
        return rc;
    }
    for (size_t k = 0; k < g->n_send; k++)
        for (size_t c = 0; c < w; c++)
            sb[k * w + c] = owned[g->send_idx[k] * w + c];
    for (int r = 0; r < size; r++) {
        cnt[r] = g->scount[r] * ncomp;
        cnt[size + r] = g->sdispl[r] * ncomp;
        cnt[2 * size + r] = g->rcount[r] * ncomp;
        cnt[3 * size + r] = g->rdispl[r] * ncomp;
    }
    MPI_Alltoallv(sb, cnt, cnt + size, MPI_DOUBLE, rb, cnt + 2 * size, cnt + 3 * size,
                  MPI_DOUBLE, MPI_COMM_WORLD);
    for (size_t k = 0; k < g->n_recv; k++)
        for (size_t c = 0; c < w; c++)
            ghost[g->recv_idx[k] * w + c] = rb[k * w + c];
    free(sb);
    free(rb);
    free(cnt);
    return SPALL_OK;
}

#else /* serial build: one rank, no ghosts */

int par_sghost_values(struct par_sghost *g, const double *owned, double *ghost, int ncomp,
                      struct spall_error *err)
{
    (void)g;
    (void)owned;
    (void)ghost;
    (void)ncomp;
    (void)err;
    return SPALL_OK;
}

int par_sghost_build(struct par_sghost *g, size_t n, const double *const x[3],
                     const int64_t *gid, struct spall_error *err)
{
    release_build(g);
    const int dim = g->dim;
    g->n_owned = n;
    g->x_build = malloc((n ? n : 1) * (size_t)dim * sizeof *g->x_build);
    g->gid_own = malloc((n ? n : 1) * sizeof *g->gid_own);
    if (!g->x_build || !g->gid_own)
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory (spatial ghosts)");
    for (size_t i = 0; i < n; i++) {
        g->gid_own[i] = gid[i];
        for (int d = 0; d < dim; d++)
            g->x_build[i * (size_t)dim + (size_t)d] = x[d][i];
    }
    g->builds++;
    return SPALL_OK;
}

void par_sghost_update(struct par_sghost *g, const double *const x[3])
{
    (void)g;
    (void)x;
}

#endif
