/**
 * @file setup_dist.c
 * @brief Distributed set-up: each rank builds its region (setup_dist.h).
 */
#include "core/parallel/setup_dist.h"
#include "core/parallel/decomp.h"
#include "core/parallel/decomp_internal.h"
#include "core/parallel/migrate.h"
#include "core/parallel/psum.h"

#include "core/bond_list.h"
#include "core/distinct.h"
#include "core/lattice_gen.h"
#include "core/model.h"
#include "core/parallel/comm.h"
#include "core/particles.h"
#include "core/rigid.h"
#include "core/sim.h"
#include "spall/error.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#ifdef SPALL_HAVE_MPI
#include <mpi.h>
#include <zoltan.h>
#endif

int par_setup_create(struct par_setup **out, double halo, struct spall_error *err)
{
    *out = NULL;
    struct par_setup *ps = calloc(1, sizeof *ps);
    const int size = par_size();
    if (!ps)
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory for the distributed set-up");
    ps->rank = par_rank();
    ps->size = size;
    ps->halo = halo;
    *out = ps;
    return SPALL_OK;
}

void par_setup_destroy(struct par_setup **pps)
{
    if (!pps || !*pps)
        return;
    for (size_t b = 0; b < (*pps)->n_seg; b++)
        free((*pps)->seg[b].own_first);
    free((*pps)->seg);
    free((*pps)->probe_owner);
    free((*pps)->probe_gid);
    free((*pps)->probe_d2);
    free(*pps);
    *pps = NULL;
}

void par_setup_offsets(const size_t *n_own, int size, int64_t *own_first)
{
    own_first[0] = 0;
    for (int r = 0; r < size; r++)
        own_first[r + 1] = own_first[r] + (int64_t)n_own[r];
}

double par_setup_dt_limit(double local)
{
    return par_min_double(local);
}

/* The segment holding local particle @p i (a few bodies: a linear walk). */
static const struct par_setup_seg *seg_of(const struct par_setup *ps, size_t i)
{
    for (size_t b = 0; b < ps->n_seg; b++)
        if (i >= ps->seg[b].start && i < ps->seg[b].start + ps->seg[b].n)
            return &ps->seg[b];
    return NULL;
}

bool par_setup_in_block(const struct par_setup *ps, size_t i)
{
    const struct par_setup_seg *sg = seg_of(ps, i);
    return sg && i >= sg->lo && i < sg->lo + sg->n_own;
}

const struct par_setup *par_setup_window(const struct sim *s)
{
    return s->setup && !s->par ? s->setup : NULL;
}

#ifdef SPALL_HAVE_MPI

/* The rank whose block holds global id @p g: the body's segment (bodies
 * ascend in global id), then the last rank whose block starts at or
 * before it (blocks ascend with the rank). */
static int block_of(const struct par_setup *ps, int64_t g)
{
    size_t sb = 0;
    while (sb + 1 < ps->n_seg && ps->seg[sb + 1].own_first[0] <= g)
        sb++;
    const int64_t *own_first = ps->seg[sb].own_first;
    int a = 0, b = ps->size - 1;
    while (a < b) {
        int mid = (a + b + 1) / 2;
        if (own_first[mid] <= g)
            a = mid;
        else
            b = mid - 1;
    }
    return a;
}

/* The local index of global id @p g, or -1 where the window lacks it. */
static int64_t local_of(const struct par_setup *ps, int64_t g)
{
    for (size_t b = 0; b < ps->n_seg; b++) {
        const struct par_setup_seg *sg = &ps->seg[b];
        if (g >= sg->gid_first && g < sg->gid_first + (int64_t)sg->n)
            return (int64_t)sg->start + (g - sg->gid_first);
    }
    return -1;
}

int par_setup_halo_values(const struct sim *s, double *v, int ncomp, struct spall_error *err)
{
    const struct par_setup *ps = s->setup;
    const size_t n = s->p->n, nc = (size_t)ncomp;
    const int size = ps->size;
    /* each halo particle asks the rank whose block holds it, by global id,
     * in local order per rank (so the answers come back in that order) */
    int *cnt = calloc(4 * (size_t)size, sizeof *cnt);
    int *back = calloc(5 * (size_t)size, sizeof *back); /* the answers' counts, at */
    int *owner = malloc((n ? n : 1) * sizeof *owner);
    int rc = cnt && back && owner ? par_fault("halo_values", err)
                                  : spall_error_set(err, SPALL_ERR_NOMEM, "out of memory");
    int *sdsp = cnt ? cnt + size : NULL, *rcnt = cnt ? cnt + 2 * size : NULL;
    int *rdsp = cnt ? cnt + 3 * size : NULL;
    for (size_t i = 0; !rc && i < n; i++) {
        owner[i] = par_setup_in_block(ps, i) ? -1 : block_of(ps, s->p->gid[i]);
        if (owner[i] >= 0)
            cnt[owner[i]]++;
    }
    if ((rc = par_agree(rc, err))) {
        free(cnt);
        free(back);
        free(owner);
        return rc;
    }
    MPI_Alltoall(cnt, 1, MPI_INT, rcnt, 1, MPI_INT, MPI_COMM_WORLD);
    size_t ns = 0, nr = 0;
    for (int r = 0; r < size; r++) {
        sdsp[r] = (int)ns;
        rdsp[r] = (int)nr;
        ns += (size_t)cnt[r];
        nr += (size_t)rcnt[r];
    }
    int64_t *ask = malloc((ns ? ns : 1) * sizeof *ask), *asked = malloc((nr ? nr : 1) * sizeof *asked);
    double *ans = malloc((nr ? nr : 1) * nc * sizeof *ans), *got = malloc((ns ? ns : 1) * nc * sizeof *got);
    rc = ask && asked && ans && got ? SPALL_OK
                                    : spall_error_set(err, SPALL_ERR_NOMEM, "out of memory");
    if (!(rc = par_agree(rc, err))) {
        int *at = back + 4 * size; /* the next slot per rank */
        memcpy(at, sdsp, (size_t)size * sizeof *at);
        for (size_t i = 0; i < n; i++)
            if (owner[i] >= 0)
                ask[at[owner[i]]++] = s->p->gid[i];
        MPI_Alltoallv(ask, cnt, sdsp, MPI_INT64_T, asked, rcnt, rdsp, MPI_INT64_T, MPI_COMM_WORLD);
        for (size_t q = 0; q < nr; q++) {
            const int64_t loc = local_of(ps, asked[q]); /* in this rank's block */
            for (size_t c = 0; c < nc; c++)
                ans[q * nc + c] = loc >= 0 ? v[(size_t)loc * nc + c] : NAN;
        }
        int *bc = back, *bd = back + size, *ac = back + 2 * size, *ad = back + 3 * size;
        for (int r = 0; r < size; r++) {
            bc[r] = rcnt[r] * ncomp;
            bd[r] = rdsp[r] * ncomp;
            ac[r] = cnt[r] * ncomp;
            ad[r] = sdsp[r] * ncomp;
        }
        MPI_Alltoallv(ans, bc, bd, MPI_DOUBLE, got, ac, ad, MPI_DOUBLE, MPI_COMM_WORLD);
        memcpy(at, sdsp, (size_t)size * sizeof *at);
        for (size_t i = 0; i < n; i++)
            if (owner[i] >= 0) {
                const size_t q = (size_t)at[owner[i]]++;
                for (size_t c = 0; c < nc; c++)
                    v[i * nc + c] = got[q * nc + c];
            }
    }
    free(ask);
    free(asked);
    free(ans);
    free(got);
    free(cnt);
    free(back);
    free(owner);
    return rc;
}

int par_setup_filled(struct sim *s, const struct lattice_window *w, size_t first,
                     struct spall_error *err)
{
    struct par_setup *ps = s->setup;
    struct particles *p = s->p;
    struct par_setup_seg *seg = realloc(ps->seg, (ps->n_seg + 1) * sizeof *seg);
    int64_t *own_first = calloc((size_t)ps->size + 1, sizeof *own_first);
    size_t *counts = malloc((size_t)ps->size * sizeof *counts);
    uint64_t *c64 = malloc((size_t)ps->size * sizeof *c64);
    if (seg)
        ps->seg = seg;
    int rc = SPALL_OK;
    if (!seg || !own_first || !counts || !c64) {
        free(own_first);
        rc = spall_error_set(err, SPALL_ERR_NOMEM, "out of memory for the distributed set-up");
    } else {
        /* the body's serial positions follow all of the earlier bodies' */
        struct par_setup_seg *sg = &ps->seg[ps->n_seg++];
        sg->start = first;
        sg->n = p->n - first;
        sg->gid_first = ps->n_global + w->gid_first;
        sg->lo = first + w->n_below;
        sg->n_own = w->n_own;
        sg->own_first = own_first;
        for (size_t i = first; i < p->n; i++)
            p->gid[i] = sg->gid_first + (int64_t)(i - first);
    }
    if ((rc = par_agree(rc, err))) {
        free(counts);
        free(c64);
        return rc;
    }
    /* the offsets from the counts (an exclusive prefix sum over the ranks)
     * must be where the generator put the rank's first own site */
    uint64_t mine = (uint64_t)w->n_own, before = 0;
    MPI_Exscan(&mine, &before, 1, MPI_UINT64_T, MPI_SUM, MPI_COMM_WORLD);
    if (ps->rank == 0)
        before = 0; /* MPI_Exscan leaves rank 0's result undefined */
    MPI_Allgather(&mine, 1, MPI_UINT64_T, c64, 1, MPI_UINT64_T, MPI_COMM_WORLD);
    for (int r = 0; r < ps->size; r++)
        counts[r] = (size_t)c64[r];
    par_setup_offsets(counts, ps->size, own_first);
    const uint64_t all = (uint64_t)own_first[ps->size];
    for (int r = 0; r <= ps->size; r++)
        own_first[r] += ps->n_global;
    if ((int64_t)before != own_first[ps->rank] - ps->n_global ||
        (int64_t)before != w->gid_first + (int64_t)w->n_below || all != w->n_total)
        rc = spall_error_set(err, SPALL_ERR_INTERNAL,
                             "distributed set-up: rank %d's block starts at site %lld "
                             "by the counts, %lld by the generator (%llu of %zu sites)",
                             ps->rank, (long long)before,
                             (long long)(w->gid_first + (int64_t)w->n_below),
                             (unsigned long long)all, w->n_total);
    ps->n_global += (int64_t)w->n_total;
    free(counts);
    free(c64);
    return par_agree(rc, err);
}

size_t par_setup_count(const struct sim *s, const size_t *idx, size_t n)
{
    uint64_t m = 0;
    for (size_t q = 0; q < n; q++)
        m += par_setup_in_block(s->setup, idx[q]);
    return (size_t)par_sum_u64(m);
}

int par_setup_probe(struct sim *s, size_t k, struct spall_error *err)
{
    struct par_setup *ps = s->setup;
    struct probe *pr = &s->probes[k];
    int rc = SPALL_OK;
    if (k >= ps->n_probes) {
        int *o = realloc(ps->probe_owner, (k + 1) * sizeof *o);
        if (o)
            ps->probe_owner = o;
        int64_t *g = realloc(ps->probe_gid, (k + 1) * sizeof *g);
        if (g)
            ps->probe_gid = g;
        double *r2 = realloc(ps->probe_d2, (k + 1) * sizeof *r2);
        if (r2)
            ps->probe_d2 = r2;
        if (!o || !g || !r2)
            rc = spall_error_set(err, SPALL_ERR_NOMEM, "out of memory for probes");
        else
            ps->n_probes = k + 1;
    }
    /* before the search's reductions: a rank that failed since the last
     * agreement (this probe's own record, say) meets the others here */
    if ((rc = par_agree(rc, err)))
        return rc;
    /* the serial search over this rank's block: the first of the nearest */
    double best = INFINITY;
    size_t at = 0, n_own = 0;
    for (size_t b = 0; b < ps->n_seg; b++) {
        const struct par_setup_seg *sg = &ps->seg[b];
        n_own += sg->n_own;
        for (size_t i = sg->lo; i < sg->lo + sg->n_own; i++) {
            double d2 = 0.0;
            for (int d = 0; d < s->dim; d++) {
                double dx = s->p->x0[d][i] - pr->pos[d];
                d2 += dx * dx;
            }
            if (d2 < best) {
                best = d2;
                at = i;
            }
        }
    }
    const double gbest = par_min_double(best);
    const int64_t g = par_min_i64(n_own && best == gbest ? s->p->gid[at] : INT64_MAX);
    ps->probe_gid[k] = g;
    ps->probe_d2[k] = gbest;
    ps->probe_owner[k] = block_of(ps, g);
    const int64_t loc = local_of(ps, g);
    pr->particle = loc >= 0 ? (size_t)loc : SIZE_MAX;
    return SPALL_OK;
}

int par_setup_merge_table(void **table, size_t key_size, size_t *n_rows, uint16_t *idx,
                          size_t n_idx, struct spall_error *err)
{
    const int size = par_size(), rank = par_rank();
    /* a rank whose model failed to build its table meets the others here */
    int rc = par_agree(SPALL_OK, err);
    if (rc)
        return rc;
    /* a table on every rank or on none: the storage must agree */
    const int64_t have = *table ? 1 : 0;
    const int64_t lo = par_min_i64(have), hi = -par_min_i64(-have);
    if (lo != hi)
        return spall_error_set(err, SPALL_ERR_INPUT,
                               "distributed set-up: the ranks' compact bond tables disagree "
                               "(one rank's window holds more than 65 536 distinct values); "
                               "set parallel.setup: replicated");
    if (!have)
        return SPALL_OK;
    int mine = (int)(*n_rows * key_size);
    int *cnt = malloc((size_t)size * sizeof *cnt), *dsp = malloc((size_t)size * sizeof *dsp);
    uint16_t *remap = malloc((*n_rows ? *n_rows : 1) * sizeof *remap);
    rc = (cnt && dsp && remap) ? SPALL_OK : spall_error_set(err, SPALL_ERR_NOMEM, "out of memory");
    if ((rc = par_agree(rc, err))) {
        free(cnt);
        free(dsp);
        free(remap);
        return rc;
    }
    MPI_Allgather(&mine, 1, MPI_INT, cnt, 1, MPI_INT, MPI_COMM_WORLD);
    size_t total = 0;
    for (int r = 0; r < size; r++) {
        dsp[r] = (int)total;
        total += (size_t)cnt[r];
    }
    unsigned char *all = malloc(total ? total : 1);
    rc = all ? SPALL_OK : spall_error_set(err, SPALL_ERR_NOMEM, "out of memory");
    if (!(rc = par_agree(rc, err)))
        MPI_Allgatherv(*table, mine, MPI_BYTE, all, cnt, dsp, MPI_BYTE, MPI_COMM_WORLD);
    struct distinct16 *d = NULL;
    if (!rc)
        rc = distinct16_create(&d, key_size, 65536u, err);
    /* the same walk on every rank: the same union, row for row */
    for (int r = 0; !rc && r < size; r++)
        for (size_t q = 0; !rc && q < (size_t)cnt[r] / key_size; q++) {
            int32_t row = distinct16_add(d, all + (size_t)dsp[r] + q * key_size);
            if (row < 0)
                rc = spall_error_set(err, SPALL_ERR_INPUT,
                                     "distributed set-up: more than 65 536 distinct bond values "
                                     "over all ranks; set parallel.setup: replicated");
            else if (r == rank)
                remap[q] = (uint16_t)row;
        }
    size_t nm = 0;
    void *merged = rc ? NULL : distinct16_take_table(d, &nm);
    if (!rc && !merged)
        rc = spall_error_set(err, SPALL_ERR_NOMEM, "out of memory");
    if (!rc) {
        for (size_t k = 0; k < n_idx; k++)
            idx[k] = remap[idx[k]];
        free(*table);
        *table = merged;
        *n_rows = nm;
    }
    distinct16_destroy(&d);
    free(all);
    free(cnt);
    free(dsp);
    free(remap);
    return rc;
}

/* Groups keep the members of the rank's block, each keyed by its position
 * in the serial list (the members of lower blocks come first); probes go
 * to the rank whose block holds them. */
static int localize_sets(struct sim *s, struct par_decomp *d, const int64_t *new_of_old,
                         int failed, struct spall_error *err)
{
    const struct par_setup *ps = s->setup;
    d->n_groups = s->n_groups;
    d->group_n = calloc(s->n_groups + 1, sizeof *d->group_n);
    d->group_key = calloc(s->n_groups + 1, sizeof *d->group_key);
    d->probe_owner = calloc(s->n_probes + 1, sizeof *d->probe_owner);
    d->probe_local = calloc(s->n_probes + 1, sizeof *d->probe_local);
    int rc = failed;
    if (!rc && (!d->group_n || !d->group_key || !d->probe_owner || !d->probe_local))
        rc = spall_error_set(err, SPALL_ERR_NOMEM, "out of memory localising groups");
    /* per body: the group's members in the rank's block, those of the
     * lower ranks' blocks and the whole body's (a member's key is its
     * serial position: the earlier bodies' members, then the lower blocks') */
    const size_t ns = ps->n_seg ? ps->n_seg : 1;
    uint64_t *own = calloc(3 * ns, sizeof *own);
    if (!own && !rc)
        rc = spall_error_set(err, SPALL_ERR_NOMEM, "out of memory localising groups");
    if ((rc = par_agree(rc, err))) {
        free(own);
        return rc;
    }
    uint64_t *before = own + ns, *total = own + 2 * ns;
    for (size_t g = 0; g < s->n_groups; g++) {
        struct group *gr = &s->groups[g];
        memset(own, 0, 3 * ns * sizeof *own);
        for (size_t q = 0; q < gr->n; q++)
            for (size_t b = 0; b < ps->n_seg; b++) {
                const struct par_setup_seg *sg = &ps->seg[b];
                own[b] += gr->idx[q] >= sg->lo && gr->idx[q] < sg->lo + sg->n_own;
            }
        MPI_Exscan(own, before, (int)ns, MPI_UINT64_T, MPI_SUM, MPI_COMM_WORLD);
        MPI_Allreduce(own, total, (int)ns, MPI_UINT64_T, MPI_SUM, MPI_COMM_WORLD);
        if (ps->rank == 0)
            memset(before, 0, ns * sizeof *before);
        if (rc)
            continue; /* still in every collective */
        uint64_t all = 0;
        for (size_t b = 0; b < ns; b++) {
            before[b] += all; /* now the key of the rank's first member of body b */
            all += total[b];
        }
        d->group_n[g] = (size_t)all;
        d->group_key[g] = malloc((gr->n ? gr->n : 1) * sizeof *d->group_key[g]);
        if (!d->group_key[g]) {
            rc = spall_error_set(err, SPALL_ERR_NOMEM, "out of memory localising groups");
            continue;
        }
        size_t m = 0;
        for (size_t q = 0; q < gr->n; q++) {
            size_t i = gr->idx[q];
            for (size_t b = 0; b < ps->n_seg; b++) {
                const struct par_setup_seg *sg = &ps->seg[b];
                if (i < sg->lo || i >= sg->lo + sg->n_own)
                    continue;
                gr->idx[m] = (size_t)new_of_old[i];
                d->group_key[g][m++] = (int64_t)before[b]++;
            }
        }
        gr->n = m;
    }
    free(own);
    for (size_t k = 0; !rc && k < s->n_probes; k++) {
        d->probe_owner[k] = ps->probe_owner[k];
        size_t i = s->probes[k].particle;
        d->probe_local[k] = ps->probe_owner[k] == ps->rank ? (size_t)new_of_old[i] : 0;
        s->probes[k].particle = d->probe_local[k];
    }
    return rc;
}

static const struct bond_list *halo_list(const struct sim *s)
{
    return s->ops->halo_bonds ? s->ops->halo_bonds(s->model)
           : s->ops->bonds    ? s->ops->bonds(s->model)
                              : NULL;
}

/* The window as a decomposition: the block owned, its rows' partners in
 * other blocks as ghosts; the whole body's bond counts. */
static int localize_window(struct sim *s, struct par_decomp *d, uint64_t counts[2],
                           struct spall_error *err)
{
    const struct par_setup *ps = s->setup;
    const struct bond_list *bl = halo_list(s);
    const struct bond_list *bonds = s->ops->bonds ? s->ops->bonds(s->model) : bl;
    if (!bl)
        return spall_error_set(err, SPALL_ERR_INTERNAL,
                               "distributed set-up: model '%s' has no bond list", s->ops->name);
    const size_t n = s->p->n;
    int *owner = malloc((n ? n : 1) * sizeof *owner);
    int64_t *new_of_old = malloc((n ? n : 1) * sizeof *new_of_old);
    size_t *keep = malloc((n ? n : 1) * sizeof *keep);
    int rc = SPALL_OK;
    if (!owner || !new_of_old || !keep)
        rc = spall_error_set(err, SPALL_ERR_NOMEM, "out of memory partitioning");
    size_t n_keep = 0, n_owned = 0;
    if (!rc) {
        for (size_t i = 0; i < n; i++) {
            owner[i] = par_setup_in_block(ps, i) ? ps->rank : block_of(ps, s->p->gid[i]);
            new_of_old[i] = -1;
        }
        for (size_t b = 0; b < ps->n_seg; b++) /* the bodies in order: gid order */
            for (size_t i = ps->seg[b].lo; i < ps->seg[b].lo + ps->seg[b].n_own; i++) {
                new_of_old[i] = (int64_t)n_keep;
                keep[n_keep++] = i;
            }
        n_owned = n_keep;
        /* pre-cut and all half-bonds of the block's rows (the halo's rows
         * are incomplete and counted by their own blocks) */
        for (size_t k = 0; k < n_owned && bonds; k++)
            for (size_t q = bonds->offset[keep[k]]; q < bonds->offset[keep[k] + 1]; q++) {
                counts[0] += (bonds->state[q] & BOND_PRECUT) != 0;
                counts[1]++;
            }
        rc = par_keep_ghosts(s, d, bl, owner, new_of_old, keep, n_owned, n, &n_keep, err);
    }
    /* collective inside: every rank takes part even after a failure */
    rc = localize_sets(s, d, new_of_old, rc, err);
    if (!rc)
        rc = par_localize_kept(s, keep, n_keep, n_owned, new_of_old, err);
    free(owner);
    free(new_of_old);
    free(keep);
    return rc;
}

/* The layers' axis (z in 3D, y in 2D) as Zoltan sees it in the set-up's
 * partition: RCB_SET_DIRECTIONS only orders the cuts, how many run along
 * each axis follows the box's widths (Zoltan's set_preset_dir), so a body
 * wider across than along the layers (the LPS race's 36 x 24 x 24 block)
 * was cut across them on 2 ranks and half of it migrated (the peak per
 * rank above the replicated set-up's).  Stretched to just past the widest
 * axis (a monotone map: the same particles on either side of a median),
 * the axis takes the first cut.  NULL (no stretch) where it is the widest
 * already; else n_owned stretched coordinates. */
static double *layer_axis(const struct sim *s, int *axis, int *fail)
{
    const struct particles *p = s->p;
    const int L = s->dim - 1;
    double w[3] = {0.0, 0.0, 0.0}, wide = 0.0;
    for (int d = 0; d < s->dim; d++) {
        double lo = INFINITY, hi = -INFINITY;
        for (size_t i = 0; i < p->n_owned; i++) {
            lo = fmin(lo, p->x0[d][i]);
            hi = fmax(hi, p->x0[d][i]);
        }
        w[d] = par_max_double(hi) - par_min_double(lo);
        if (d != L)
            wide = fmax(wide, w[d]);
    }
    *axis = L;
    if (s->dim < 2 || !(w[L] > 0.0) || w[L] > wide)
        return NULL;
    const double f = 1.001 * wide / w[L];
    double *x = malloc((p->n_owned ? p->n_owned : 1) * sizeof *x);
    *fail = x == NULL;
    for (size_t i = 0; x && i < p->n_owned; i++)
        x[i] = f * p->x0[L][i];
    return x;
}

/* The blocks to the final decomposition: Zoltan RCB on the reference
 * positions weighted by 1 + bonds (as par_distribute), its first cut across
 * the blocks' layers (RCB_SET_DIRECTIONS and layer_axis) so that on 2 ranks
 * nothing moves and on more the moves stay within a block pair; the object
 * is kept for the run's rebalancing (its cuts are only the first guesses
 * of a repartition's medians).  The migration, which holds the moving
 * particles twice, runs only when a particle changes rank. */
static int setup_partition(struct sim *s, unsigned long long *moved, struct spall_error *err)
{
    struct par_decomp *d = s->par;
    struct Zoltan_Struct *zz = par_zoltan_rcb(1);
    if (zz && s->dim > 1)
        Zoltan_Set_Param(zz, "RCB_SET_DIRECTIONS", s->dim == 3 ? "5" : "3"); /* zxy, yzx */
    d->zz = zz;
    int axis = 0, fail = 0;
    double *stretched = layer_axis(s, &axis, &fail);
    int rc = zz ? SPALL_OK : spall_error_set(err, SPALL_ERR_INTERNAL, "Zoltan_Create failed");
    if (!rc && fail)
        rc = spall_error_set(err, SPALL_ERR_NOMEM, "out of memory partitioning");
    if ((rc = par_agree(rc, err))) {
        free(stretched);
        return rc;
    }
    double *pos[3] = {s->p->x0[0], s->p->x0[1], s->p->x0[2]};
    if (stretched)
        pos[axis] = stretched;
    struct par_zobjs z = {0, s->p->n_owned, s->p->gid, pos, s->dim, halo_list(s), 0};
    int *dest = NULL;
    size_t out = 0;
    rc = par_rcb_dest(zz, &z, &dest, &out, err);
    free(stretched);
    const uint64_t leaving = par_sum_u64((uint64_t)out);
    *moved = 0;
    if (!(rc = par_agree(rc, err)) && leaving)
        rc = par_migrate(s, dest, moved, err);
    free(dest);
    return rc;
}

int par_setup_distribute(struct sim *s, struct spall_error *err)
{
    struct par_setup *ps = s->setup;
    struct par_decomp *d = calloc(1, sizeof *d);
    if (!d)
        return par_agree(spall_error_set(err, SPALL_ERR_NOMEM, "out of memory"), err);
    double t0 = MPI_Wtime();
    uint64_t counts[2] = {0, 0};
    int rc = localize_window(s, d, counts, err);
    par_sum_u64_array(counts, 2);
    d->n_global = (size_t)ps->n_global;
    d->interactions = s->ops->interactions ? (size_t)(counts[1] / 2) : 0;
    float ver = 0.0f;
    if (!rc && Zoltan_Initialize(0, NULL, &ver) != ZOLTAN_OK)
        rc = spall_error_set(err, SPALL_ERR_INTERNAL, "Zoltan_Initialize failed");
    if ((rc = par_agree(rc, err))) {
        par_decomp_destroy(&d);
        return rc;
    }
    s->par = d;
    if (s->ops->setup_tables) /* the same rows of distinct values everywhere */
        rc = par_agree(s->ops->setup_tables(s->model, s, err), err);
    if (rc)
        return rc;
    s->n_precut = (size_t)(counts[0] / 2);
    /* the initial forces, BC reactions and energy account (sim_prepare
     * leaves them to here): the whole body's group sizes and sums, and the
     * block's rows are the serial ones, so this is the serial set-up */
    /* impactors: contact rows of the block; agreed before the initial
     * forces, whose sums are collective */
    if ((rc = par_agree(rigid_par_prepare(s, err), err)) ||
        (rc = par_agree(sim_initial_forces(s, err), err)))
        return rc;
    ps->imbalance[0] = par_imbalance(s);
    rc = setup_partition(s, &ps->moved, err);
    ps->imbalance[1] = rc ? 0.0 : par_imbalance(s);
    d->migrated = 0; /* the run's rebalancing statistics start here */
    d->setup_seconds = MPI_Wtime() - t0;
    return rc;
}

#else /* no MPI: never reached (the set-up distributes only on several ranks) */

int par_setup_filled(struct sim *s, const struct lattice_window *w, size_t first,
                     struct spall_error *err)
{
    (void)s;
    (void)w;
    (void)first;
    return spall_error_set(err, SPALL_ERR_INTERNAL, "distributed set-up in a build without MPI");
}

int par_setup_halo_values(const struct sim *s, double *v, int ncomp, struct spall_error *err)
{
    (void)s;
    (void)v;
    (void)ncomp;
    (void)err;
    return SPALL_OK;
}

size_t par_setup_count(const struct sim *s, const size_t *idx, size_t n)
{
    (void)s;
    (void)idx;
    return n;
}

int par_setup_probe(struct sim *s, size_t k, struct spall_error *err)
{
    (void)s;
    (void)k;
    (void)err;
    return SPALL_OK;
}

int par_setup_merge_table(void **table, size_t key_size, size_t *n_rows, uint16_t *idx,
                          size_t n_idx, struct spall_error *err)
{
    (void)table;
    (void)key_size;
    (void)n_rows;
    (void)idx;
    (void)n_idx;
    (void)err;
    return SPALL_OK;
}

int par_setup_distribute(struct sim *s, struct spall_error *err)
{
    (void)s;
    return spall_error_set(err, SPALL_ERR_INTERNAL, "distributed set-up in a build without MPI");
}

#endif
