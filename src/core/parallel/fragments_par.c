/**
 * @file fragments_par.c
 * @brief Fragments of a distributed run (decomp.h): connected components
 *        over intact bonds found without gathering the bond graph, with the
 *        ids, masses and velocities of one rank, bit for bit; and the
 *        generic halo of per-particle values the label rounds use.
 *
 * Labels.  A fragment's id is the smallest gid of its particles
 * (core/fragments.h).  Each rank first joins its owned particles over the
 * intact bonds between them (union-find, the smaller local index as root:
 * owned particles are in ascending gid, so each local component's root is
 * its smallest gid).  A local component that has an intact bond to a ghost
 * continues on another rank; its label is lowered to the smallest label
 * seen across such bonds, round by round, with one halo exchange of the
 * labels per round, until no label changes on any rank (an integer
 * reduction).  Both halves of a bond are intact or broken together (each
 * half decides from bitwise symmetric quantities, docs/parallel.md), so at
 * that point every fragment carries one label: its smallest gid.  The
 * rounds needed grow with how often one fragment crosses rank boundaries in
 * a chain, not with its size (the local union-find covers the rest).
 *
 * Sums.  A fragment's mass, momentum and kinetic energy are floating-point
 * sums that the serial run forms particle by particle in gid order
 * (fragment_add).  A local component without bonds to ghosts is a whole
 * fragment: its owner sums it in gid order.  The particles of fragments
 * that cross ranks go, as (label, gid, mass, v) rows, to rank label mod
 * size, which sorts them by (label, gid) and sums each fragment in that
 * order.  Rank 0 then collects the finished fragments (one small record
 * each, which fragments.csv needs anyway) and orders them by id, the serial
 * order.  Nothing here depends on the rank count.
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

/* The position halo's lists and buffers (build_halo: 2 dim doubles per
 * particle, so up to 2 dim values per particle fit without allocating). */
void par_halo_values(const struct sim *s, double *vals, int ncomp)
{
    struct par_decomp *d = s->par;
    const int size = par_size(), w = 2 * s->dim;
    if (ncomp > w) /* a programming error, not an input one */
        MPI_Abort(MPI_COMM_WORLD, 3);
    for (size_t k = 0; k < d->n_send; k++)
        memcpy(d->sbuf + k * (size_t)ncomp, vals + d->send_idx[k] * (size_t)ncomp,
               (size_t)ncomp * sizeof *vals);
    MPI_Request *req = d->req;
    int nreq = 0;
    for (int r = 0; r < size; r++)
        if (d->recv_counts[r])
            MPI_Irecv(d->rbuf + d->recv_displs[r] / w * ncomp, d->recv_counts[r] / w * ncomp,
                      MPI_DOUBLE, r, 19, MPI_COMM_WORLD, &req[nreq++]);
    for (int r = 0; r < size; r++)
        if (d->send_counts[r])
            MPI_Isend(d->sbuf + d->send_displs[r] / w * ncomp, d->send_counts[r] / w * ncomp,
                      MPI_DOUBLE, r, 19, MPI_COMM_WORLD, &req[nreq++]);
    MPI_Waitall(nreq, req, MPI_STATUSES_IGNORE);
    for (size_t k = 0; k < d->n_recv; k++)
        memcpy(vals + d->recv_idx[k] * (size_t)ncomp, d->rbuf + k * (size_t)ncomp,
               (size_t)ncomp * sizeof *vals);
}

/* The labelling workspace: root of each owned particle, the label of each
 * root (as a double: gids < 2^53 travel exactly), and whether the root's
 * component has an intact bond to a ghost. */
struct labels {
    size_t *root;
    double *val;          /**< owned + ghosts: the particle's current label */
    unsigned char *cross; /**< per root */
    size_t *edge;         /**< intact owned->ghost half-bonds: (root, ghost) pairs */
    size_t n_edge;
};

static void labels_free(struct labels *L)
{
    free(L->root);
    free(L->val);
    free(L->cross);
    free(L->edge);
}

/* Collective.  ok = 0: this rank could not allocate; every rank then fails
 * (after the same collectives). */
static int labels_compute(const struct sim *s, struct labels *L, struct spall_error *err)
{
    const struct bond_list *bl = s->ops->bonds ? s->ops->bonds(s->model) : NULL;
    const struct particles *p = s->p;
    const size_t n = p->n_owned, nt = p->n;
    memset(L, 0, sizeof *L);
    size_t ne = 0;
    for (size_t i = 0; bl && i < n; i++)
        for (size_t k = bl->offset[i]; k < bl->offset[i + 1]; k++)
            ne += !(bl->state[k] & BOND_BROKEN) && (size_t)bl->partner[k] >= n;
    L->root = malloc((n ? n : 1) * sizeof *L->root);
    L->val = malloc((nt ? nt : 1) * sizeof *L->val);
    L->cross = calloc(n ? n : 1, 1);
    L->edge = malloc((ne ? 2 * ne : 1) * sizeof *L->edge);
    int ok = L->root && L->val && L->cross && L->edge;
    if (ok) {
        size_t *parent = L->root;
        fragments_union_local(parent, bl, n);
        for (size_t i = 0; i < n; i++) /* flatten: root[i] is the final root */
            parent[i] = fragments_root(parent, i);
        /* the intact bonds to ghosts: the component goes on on another rank */
        for (size_t i = 0; bl && i < n; i++)
            for (size_t k = bl->offset[i]; k < bl->offset[i + 1]; k++)
                if (!(bl->state[k] & BOND_BROKEN) && (size_t)bl->partner[k] >= n) {
                    L->edge[2 * L->n_edge] = i;
                    L->edge[2 * L->n_edge++ + 1] = (size_t)bl->partner[k];
                }
        for (size_t e = 0; e < L->n_edge; e++) {
            L->edge[2 * e] = parent[L->edge[2 * e]];
            L->cross[L->edge[2 * e]] = 1;
        }
        for (size_t i = 0; i < n; i++)
            L->val[i] = (double)p->gid[parent[i]];
    }
    if (par_sum_u64(ok ? 0u : 1u) != 0) {
        labels_free(L);
        memset(L, 0, sizeof *L);
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory labelling fragments");
    }
    /* label rounds: lower each crossing component to the smallest label
     * across its bonds to ghosts, until no rank changes one */
    for (;;) {
        par_halo_values(s, L->val, 1);
        uint64_t changed = 0;
        for (size_t e = 0; e < L->n_edge; e++) {
            size_t r = L->edge[2 * e], j = L->edge[2 * e + 1];
            if (L->val[j] < L->val[r]) {
                L->val[r] = L->val[j];
                changed = 1;
            }
        }
        if (par_sum_u64(changed) == 0)
            break;
        for (size_t i = 0; i < n; i++)
            L->val[i] = L->val[L->root[i]];
    }
    return SPALL_OK;
}

int par_fragment_labels(const struct sim *s, int64_t *label, struct spall_error *err)
{
    struct labels L;
    int rc = labels_compute(s, &L, err);
    if (!rc && !label)
        rc = spall_error_set(err, SPALL_ERR_NOMEM, "out of memory labelling fragments");
    for (size_t i = 0; !rc && i < s->p->n_owned; i++)
        label[i] = (int64_t)L.val[L.root[i]];
    labels_free(&L);
    return par_agree(rc, err);
}

/* A crossing fragment's particle, on its way to the rank that sums it. */
struct frag_row {
    int64_t label, gid;
    double mass, v[3];
};

static int cmp_row(const void *a, const void *b)
{
    const struct frag_row *x = a, *y = b;
    if (x->label != y->label)
        return (x->label > y->label) - (x->label < y->label);
    return (x->gid > y->gid) - (x->gid < y->gid);
}

static int cmp_info(const void *a, const void *b)
{
    int64_t x = ((const struct fragment_info *)a)->id, y = ((const struct fragment_info *)b)->id;
    return (x > y) - (x < y);
}

/* Append a fresh fragment to @p out, growing it. */
static struct fragment_info *info_push(struct fragment_info **out, size_t *n, size_t *cap,
                                       int64_t id)
{
    if (*n == *cap) {
        size_t c = *cap ? 2 * *cap : 64;
        struct fragment_info *g = realloc(*out, c * sizeof *g);
        if (!g)
            return NULL;
        *out = g;
        *cap = c;
    }
    struct fragment_info *fi = &(*out)[(*n)++];
    memset(fi, 0, sizeof *fi);
    fi->id = id;
    return fi;
}

/* This rank's finished fragments: its local ones and the crossing ones it
 * sums (see the file comment). */
static int my_fragments(const struct sim *s, const struct labels *L, struct fragment_info **out,
                        size_t *n_out)
{
    const struct particles *p = s->p;
    const size_t n = p->n_owned;
    const int size = par_size(), dim = s->dim;
    size_t cap = 0, nf = 0;
    int bad = 0;
    *out = NULL;
    /* local fragments: in order of their root, particles in gid order */
    size_t *slot = malloc((n ? n : 1) * sizeof *slot);
    int *scnt = calloc(4 * (size_t)size, sizeof *scnt);
    bad = !slot || !scnt;
    for (size_t i = 0; !bad && i < n; i++) {
        size_t r = L->root[i];
        if (L->cross[r])
            continue;
        if (r == i) {
            if (!info_push(out, &nf, &cap, p->gid[i])) {
                bad = 1;
                break;
            }
            slot[i] = nf - 1;
        }
        double v[3] = {0.0, 0.0, 0.0};
        for (int d = 0; d < dim; d++)
            v[d] = p->v[d][i];
        fragment_add(&(*out)[slot[r]], p->gid[i], p->mass[i], v, dim);
    }
    /* crossing fragments: rows to rank label mod size */
    struct frag_row *srow = NULL, *rrow = NULL;
    size_t ns = 0, nr = 0;
    int *sdsp = scnt ? scnt + size : NULL, *rcnt = scnt ? scnt + 2 * size : NULL,
        *rdsp = scnt ? scnt + 3 * size : NULL;
    for (size_t i = 0; !bad && i < n; i++)
        if (L->cross[L->root[i]]) {
            scnt[(int64_t)L->val[L->root[i]] % size]++;
            ns++;
        }
    if (!bad)
        srow = malloc((ns ? ns : 1) * sizeof *srow);
    bad = bad || !srow;
    bad = par_sum_u64(bad ? 1u : 0u) != 0; /* the exchange below is collective */
    if (bad) {
        free(slot);
        free(scnt);
        free(srow);
        return 1;
    }
    for (int r = 0, acc = 0; r < size; r++) {
        sdsp[r] = acc;
        acc += scnt[r];
    }
    int *fill = rcnt; /* scratch until the counts are exchanged */
    memset(fill, 0, (size_t)size * sizeof *fill);
    for (size_t i = 0; i < n; i++) {
        size_t r = L->root[i];
        if (!L->cross[r])
            continue;
        int64_t lab = (int64_t)L->val[r];
        int to = (int)(lab % size);
        struct frag_row *w = &srow[sdsp[to] + fill[to]++];
        memset(w, 0, sizeof *w);
        w->label = lab;
        w->gid = p->gid[i];
        w->mass = p->mass[i];
        for (int d = 0; d < dim; d++)
            w->v[d] = p->v[d][i];
    }
    MPI_Alltoall(scnt, 1, MPI_INT, rcnt, 1, MPI_INT, MPI_COMM_WORLD);
    for (int r = 0, acc = 0; r < size; r++) {
        rdsp[r] = acc;
        acc += rcnt[r];
        nr += (size_t)rcnt[r];
    }
    MPI_Datatype row_t;
    MPI_Type_contiguous((int)sizeof(struct frag_row), MPI_BYTE, &row_t);
    MPI_Type_commit(&row_t);
    rrow = malloc((nr ? nr : 1) * sizeof *rrow);
    bad = par_sum_u64(rrow ? 0u : 1u) != 0;
    if (!bad)
        MPI_Alltoallv(srow, scnt, sdsp, row_t, rrow, rcnt, rdsp, row_t, MPI_COMM_WORLD);
    MPI_Type_free(&row_t);
    if (!bad) {
        qsort(rrow, nr, sizeof *rrow, cmp_row);
        struct fragment_info *fi = NULL;
        for (size_t q = 0; q < nr && !bad; q++) {
            if (q == 0 || rrow[q].label != rrow[q - 1].label) {
                fi = info_push(out, &nf, &cap, rrow[q].label);
                if (!fi) {
                    bad = 1;
                    break;
                }
            }
            fragment_add(fi, rrow[q].gid, rrow[q].mass, rrow[q].v, dim);
        }
    }
    for (size_t q = 0; q < nf && !bad; q++)
        fragment_finish(&(*out)[q], dim);
    free(slot);
    free(scnt);
    free(srow);
    free(rrow);
    *n_out = nf;
    return bad;
}

int par_fragments(const struct sim *s, struct fragments *f, struct spall_error *err)
{
    struct labels L;
    int rc = labels_compute(s, &L, err);
    if (rc)
        return rc; /* agreed: every rank failed */
    const size_t n = s->p->n_owned;
    struct fragment_info *mine = NULL;
    size_t nf = 0;
    int bad = my_fragments(s, &L, &mine, &nf);
    int64_t *lab = malloc((n ? n : 1) * sizeof *lab);
    bad = bad || !lab;
    for (size_t i = 0; !bad && i < n; i++)
        lab[i] = (int64_t)L.val[L.root[i]];
    labels_free(&L);
    if (par_sum_u64(bad ? 1u : 0u) != 0) {
        free(mine);
        free(lab);
        return par_agree(spall_error_set(err, SPALL_ERR_NOMEM, "out of memory summing fragments"),
                         err);
    }
    /* the finished fragments to rank 0, in id order there */
    const int size = par_size(), rank = par_rank();
    int cnt = (int)nf, *counts = NULL, *displs = NULL; /* in fragments */
    struct fragment_info *all = NULL;
    size_t n_all = 0;
    if (rank == 0)
        counts = malloc(2 * (size_t)size * sizeof *counts);
    int ok0 = rank != 0 || counts; /* rank 0's memory decides for all */
    par_bcast(&ok0, sizeof ok0, 0);
    if (ok0)
        MPI_Gather(&cnt, 1, MPI_INT, counts, 1, MPI_INT, 0, MPI_COMM_WORLD);
    if (ok0 && rank == 0) {
        displs = counts + size;
        for (int r = 0; r < size; r++) {
            displs[r] = (int)n_all;
            n_all += (size_t)counts[r];
        }
        all = malloc((n_all ? n_all : 1) * sizeof *all);
        ok0 = all != NULL;
    }
    par_bcast(&ok0, sizeof ok0, 0);
    if (ok0) {
        MPI_Datatype info_t;
        MPI_Type_contiguous((int)sizeof *mine, MPI_BYTE, &info_t);
        MPI_Type_commit(&info_t);
        MPI_Gatherv(mine, cnt, info_t, all, counts, displs, info_t, 0, MPI_COMM_WORLD);
        MPI_Type_free(&info_t);
    }
    if (!ok0) {
        rc = spall_error_set(err, SPALL_ERR_NOMEM, "out of memory collecting fragments");
    } else if (rank == 0) {
        qsort(all, n_all, sizeof *all, cmp_info);
        rc = fragments_set(f, all, n_all, lab, n, err);
    } else {
        rc = fragments_set(f, NULL, 0, lab, n, err);
    }
    free(counts);
    free(all);
    free(mine);
    free(lab);
    return par_agree(rc, err);
}

#else /* no MPI: s->par is never set */

void par_halo_values(const struct sim *s, double *vals, int ncomp)
{
    (void)s;
    (void)vals;
    (void)ncomp;
}

int par_fragment_labels(const struct sim *s, int64_t *label, struct spall_error *err)
{
    (void)s;
    (void)label;
    return spall_error_set(err, SPALL_ERR_INTERNAL, "distributed fragments in a build without MPI");
}

int par_fragments(const struct sim *s, struct fragments *f, struct spall_error *err)
{
    return fragments_of_sim(f, s, err);
}

#endif
