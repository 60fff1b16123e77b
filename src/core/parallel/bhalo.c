/**
 * @file bhalo.c
 * @brief Per-half-bond halo (bhalo.h): the plan (reverse index, send slots,
 *        counts per rank) and the exchange.
 */
#include "core/parallel/bhalo.h"
#include "core/parallel/decomp_internal.h"

#include "core/bond_list.h"
#include "core/parallel/comm.h"
#include "core/particles.h"
#include "core/sim.h"
#include "spall/error.h"

#include <stdint.h>
#include <stdlib.h>

#ifdef SPALL_HAVE_MPI
#include <mpi.h>

struct par_bhalo {
    size_t nh;         /**< half-bonds of the local rows the plan was built for */
    size_t *rev;       /**< per half-bond: reverse slot, or nh + received position */
    size_t *send_slot; /**< half-bonds whose values are sent, rank-major */
    size_t n_send, n_recv;
    int *scount, *sdispl, *rcount, *rdispl; /**< per rank, in doubles */
    double *sbuf, *rbuf;
};

void par_bhalo_free(struct par_decomp *d)
{
    struct par_bhalo *b = d ? d->bhalo : NULL;
    if (!b)
        return;
    free(b->rev);
    free(b->send_slot);
    free(b->scount);
    free(b->sdispl);
    free(b->rcount);
    free(b->rdispl);
    free(b->sbuf);
    free(b->rbuf);
    free(b);
    d->bhalo = NULL;
}

/* Slot of the half-bond j->i in j's row (rows ascend by partner gid), or
 * SIZE_MAX when the row lacks it (an asymmetric list). */
static size_t find_reverse(const struct bond_list *bl, const int64_t *gid, size_t j, size_t i)
{
    size_t lo = bl->offset[j], hi = bl->offset[j + 1];
    const int64_t g = gid[i];
    while (lo < hi) {
        size_t mid = lo + (hi - lo) / 2;
        if (gid[bl->partner[mid]] < g)
            lo = mid + 1;
        else
            hi = mid;
    }
    return lo < bl->offset[j + 1] && (size_t)bl->partner[lo] == i ? lo : SIZE_MAX;
}

/* The owner rank of every ghost, from the position halo's receive lists. */
static int *ghost_owners(const struct sim *s)
{
    const struct par_decomp *d = s->par;
    const size_t no = s->p->n_owned, ng = s->p->n - no;
    const int w = 2 * s->dim, size = par_size();
    int *go = malloc((ng ? ng : 1) * sizeof *go);
    if (!go)
        return NULL;
    for (size_t g = 0; g < ng; g++)
        go[g] = -1;
    for (int r = 0; r < size; r++)
        for (int k = d->recv_displs[r] / w; k < (d->recv_displs[r] + d->recv_counts[r]) / w; k++)
            go[d->recv_idx[k] - no] = r;
    return go;
}

static int build(const struct sim *s, const struct bond_list *bl, struct par_bhalo *b,
                 struct spall_error *err)
{
    const struct particles *p = s->p;
    const size_t no = p->n_owned, n = p->n, ng = n - no, nh = bl->offset[bl->n];
    const int size = par_size();
    b->nh = nh;
    int *go = ghost_owners(s);
    size_t *base = calloc(ng + 1, sizeof *base); /* per ghost: its first received position */
    size_t *fill = calloc(ng + 1, sizeof *fill);
    size_t *spos = calloc((size_t)size, sizeof *spos);
    b->rev = malloc((nh ? nh : 1) * sizeof *b->rev);
    b->scount = calloc((size_t)size, sizeof(int));
    b->sdispl = calloc((size_t)size, sizeof(int));
    b->rcount = calloc((size_t)size, sizeof(int));
    b->rdispl = calloc((size_t)size, sizeof(int));
    int rc = SPALL_OK;
    if (!go || !base || !fill || !spos || !b->rev || !b->scount || !b->sdispl || !b->rcount ||
        !b->rdispl) {
        rc = spall_error_set(err, SPALL_ERR_NOMEM, "out of memory for the per-bond halo");
        goto out;
    }
    /* counts: a half-bond to a ghost of rank r is sent to r, and its reverse
     * half comes from r (bonds are symmetric, so the counts match) */
    for (size_t i = 0; i < no; i++)
        for (size_t k = bl->offset[i]; k < bl->offset[i + 1]; k++) {
            size_t j = (size_t)bl->partner[k];
            if (j < no)
                continue;
            if (go[j - no] < 0) {
                rc = spall_error_set(err, SPALL_ERR_INTERNAL,
                                     "per-bond halo: ghost %lld has no owner in the halo lists",
                                     (long long)p->gid[j]);
                goto out;
            }
            b->scount[go[j - no]]++;
            fill[j - no]++;
        }
    for (int r = 0; r < size; r++) {
        b->rcount[r] = b->scount[r];
        b->sdispl[r] = r ? b->sdispl[r - 1] + b->scount[r - 1] : 0;
        b->rdispl[r] = b->sdispl[r];
        spos[r] = (size_t)b->sdispl[r];
    }
    b->n_send = b->n_recv = size ? (size_t)(b->sdispl[size - 1] + b->scount[size - 1]) : 0;
    /* received positions: ghosts rank-major, ascending gid (= local index)
     * within a rank, each ghost's half-bonds in ascending owned gid */
    {
        size_t *at = calloc((size_t)size, sizeof *at);
        if (!at) {
            rc = spall_error_set(err, SPALL_ERR_NOMEM, "out of memory for the per-bond halo");
            goto out;
        }
        for (int r = 0; r < size; r++)
            at[r] = (size_t)b->rdispl[r];
        for (size_t g = 0; g < ng; g++)
            if (go[g] >= 0) {
                base[g] = at[go[g]];
                at[go[g]] += fill[g];
                fill[g] = 0;
            }
        free(at);
    }
    b->send_slot = malloc((b->n_send ? b->n_send : 1) * sizeof *b->send_slot);
    b->sbuf = malloc((b->n_send ? b->n_send : 1) * PAR_BHALO_MAX_WIDTH * sizeof *b->sbuf);
    b->rbuf = malloc((b->n_recv ? b->n_recv : 1) * PAR_BHALO_MAX_WIDTH * sizeof *b->rbuf);
    if (!b->send_slot || !b->sbuf || !b->rbuf) {
        rc = spall_error_set(err, SPALL_ERR_NOMEM, "out of memory for the per-bond halo");
        goto out;
    }
    for (size_t i = 0; i < no; i++)
        for (size_t k = bl->offset[i]; k < bl->offset[i + 1]; k++) {
            size_t j = (size_t)bl->partner[k];
            if (j >= no) {
                b->send_slot[spos[go[j - no]]++] = k;
                b->rev[k] = nh + base[j - no] + fill[j - no]++;
            } else if ((b->rev[k] = find_reverse(bl, p->gid, j, i)) == SIZE_MAX) {
                rc = spall_error_set(err, SPALL_ERR_INTERNAL,
                                     "bond list is not symmetric: a bond has no reverse half");
                goto out;
            }
        }
out:
    free(go);
    free(base);
    free(fill);
    free(spos);
    return rc;
}

const size_t *par_bhalo_reverse(const struct sim *s, const struct bond_list *bl,
                                size_t *n_recv, struct spall_error *err)
{
    struct par_decomp *d = s->par;
    struct par_bhalo *b;
    if (!d->bhalo) { /* every rank builds in the same call: agree on the outcome */
        int rc = (b = calloc(1, sizeof *b))
                     ? SPALL_OK
                     : spall_error_set(err, SPALL_ERR_NOMEM, "out of memory for the per-bond halo");
        d->bhalo = b;
        if (!rc)
            rc = build(s, bl, b, err);
        if ((rc = par_agree(rc, err))) {
            par_bhalo_free(d);
            return NULL;
        }
    }
    b = d->bhalo;
    *n_recv = b->n_recv;
    return b->rev;
}

const double *par_bhalo_exchange(const struct sim *s, const double *val, int ncomp)
{
    struct par_decomp *d = s->par;
    struct par_bhalo *b = d->bhalo;
    const int size = par_size();
    if (ncomp < 1 || ncomp > PAR_BHALO_MAX_WIDTH) /* a programming error, not an input one */
        MPI_Abort(MPI_COMM_WORLD, 3);
    const size_t w = (size_t)ncomp;
    for (size_t q = 0; q < b->n_send; q++)
        for (size_t c = 0; c < w; c++)
            b->sbuf[q * w + c] = val[b->send_slot[q] * w + c];
    MPI_Request *req = d->req;
    int nreq = 0;
    for (int r = 0; r < size; r++)
        if (b->rcount[r])
            MPI_Irecv(b->rbuf + (size_t)b->rdispl[r] * w, b->rcount[r] * ncomp, MPI_DOUBLE, r,
                      23, MPI_COMM_WORLD, &req[nreq++]);
    for (int r = 0; r < size; r++)
        if (b->scount[r])
            MPI_Isend(b->sbuf + (size_t)b->sdispl[r] * w, b->scount[r] * ncomp, MPI_DOUBLE, r,
                      23, MPI_COMM_WORLD, &req[nreq++]);
    MPI_Waitall(nreq, req, MPI_STATUSES_IGNORE);
    return b->rbuf;
}

#else /* no MPI: s->par is never set */

void par_bhalo_free(struct par_decomp *d)
{
    (void)d;
}

const size_t *par_bhalo_reverse(const struct sim *s, const struct bond_list *bl,
                                size_t *n_recv, struct spall_error *err)
{
    (void)s;
    *n_recv = 0;
    return bl->reverse ? bl->reverse
                       : (spall_error_set(err, SPALL_ERR_INTERNAL, "no reverse bond index"), NULL);
}

const double *par_bhalo_exchange(const struct sim *s, const double *val, int ncomp)
{
    (void)s;
    (void)val;
    (void)ncomp;
    return NULL;
}

#endif
