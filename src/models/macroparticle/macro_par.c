/**
 * @file macro_par.c
 * @brief Distributed macro-particle runs (docs/parallel.md, "Spatial
 *        ghosts in the step"): the model's side of core/parallel/spatial.h.
 *
 * The partition keeps each rank's owned particles (no bond ghosts: the
 * model has no fixed bonds); macro_localize keeps their partner rows with
 * the pair state keyed by the partner's global id.  The engine then builds
 * the spatial ghosts around the positions of the last list build and calls
 * macro_spatial_rebuilt, which rebuilds the list from those positions (the
 * serial list, since the serial run built it from the same positions) and
 * carries the state over by gid.  From then on the engine takes the serial
 * rebuild test over all ranks, so the lists are rebuilt in the same steps
 * from the same positions as on one rank; each row is sorted by partner
 * gid, so each owned particle sums its pairs in the serial order.
 */
#include "models/macroparticle/macro_internal.h"
#include "models/macroparticle/macro_slip.h"

#include "core/bond_list.h"
#include "core/neighbor.h"
#include "core/parallel/comm.h"
#include "core/parallel/migrate.h"
#include "core/parallel/sghost.h"
#include "core/parallel/spatial.h"
#include "core/particles.h"
#include "core/sim.h"
#include "spall/error.h"

#include <stdlib.h>
#include <string.h>

/* Replace *a (elements of @p size bytes) by a[keep[0..n)). */
static int gather(void **a, size_t size, const size_t *keep, size_t n)
{
    void *g = array_gather(*a, size, keep, n ? n : 0);
    if (!g)
        return -1;
    free(*a);
    *a = g;
    return 0;
}

/* The gauge's owned members from the flags that travel with the
 * particles (the sums over them are exact: their order does not matter). */
static void gauge_from_flags(struct model *m, size_t n_owned)
{
    m->n_lo = m->n_hi = m->n_mid = 0;
    for (size_t i = 0; i < n_owned; i++) {
        if (m->gflag[i] & 1)
            m->lo_idx[m->n_lo++] = i;
        if (m->gflag[i] & 2)
            m->hi_idx[m->n_hi++] = i;
        if (m->gflag[i] & 4)
            m->mid_idx[m->n_mid++] = i;
    }
}

int macro_localize(struct model *m, struct sim *sim, const size_t *keep, size_t n_keep,
                   size_t n_owned, const int64_t *new_of_old, struct spall_error *err)
{
    if (!keep)
        return SPALL_OK;
    macro_half_epot_sync(m); /* epot is renumbered below */
    const struct particles *p = sim->p;
    const struct neighbor_list *ol = m->nl;
    /* the owned rows, state keyed by the partner's gid (the list is rebuilt
     * around the spatial ghosts right after, par_spatial_init) */
    size_t *off = calloc(n_keep + 1, sizeof *off);
    int bad = !off;
    for (size_t k = 0; k < n_owned && !bad; k++)
        off[k + 1] = off[k] + ol->offset[keep[k] + 1] - ol->offset[keep[k]];
    for (size_t k = n_owned; k < n_keep && !bad; k++)
        off[k + 1] = off[k];
    const size_t ns = bad ? 0 : off[n_keep];
    int32_t *idx = malloc((ns ? ns : 1) * sizeof *idx);
    int64_t *pg = malloc((ns ? ns : 1) * sizeof *pg);
    double *dr0 = malloc((ns ? ns : 1) * sizeof *dr0), *kap = malloc((ns ? ns : 1) * sizeof *kap);
    uint8_t *eng = malloc(ns ? ns : 1);
    struct neighbor_list *nl = calloc(1, sizeof *nl);
    bad = bad || !idx || !pg || !dr0 || !kap || !eng || !nl;
    for (size_t k = 0; k < n_owned && !bad; k++)
        for (size_t a = ol->offset[keep[k]], s = off[k]; s < off[k + 1]; a++, s++) {
            const int32_t j = ol->idx[a];
            idx[s] = new_of_old[j] >= 0 ? (int32_t)new_of_old[j] : -1;
            pg[s] = m->pgid ? m->pgid[a] : p->gid[j];
            dr0[s] = m->dr0[a];
            kap[s] = m->kappa[a];
            eng[s] = m->engaged[a];
        }
    for (int d = 0; d < 3 && !bad; d++)
        bad = gather((void **)&m->xb[d], sizeof(double), keep, n_keep);
    if (!bad)
        bad = gather((void **)&m->epot, sizeof(double), keep, n_keep) ||
              gather((void **)&m->sig, 6 * sizeof(double), keep, n_keep) ||
              gather((void **)&m->wdiss, sizeof(double), keep, n_keep) ||
              gather((void **)&m->gflag, 1, keep, n_keep);
    if (bad) {
        free(off);
        free(idx);
        free(pg);
        free(dr0);
        free(kap);
        free(eng);
        free(nl);
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory localising macro-particles");
    }
    nl->n = n_keep;
    nl->offset = off;
    nl->idx = idx;
    macro_adopt_pairs(m, nl, pg, dr0, kap, eng);
    gauge_from_flags(m, n_owned);
    /* the reference neighbours (slip fields) name particles of the whole
     * body; a distributed run refuses those fields (macro_model.c) */
    neighbor_list_destroy(&m->nl0);
    return SPALL_OK;
}

int macro_spatial_ghosts(struct model *m, struct par_spatial_model *sp)
{
    sp->range = m->pp.r_c;
    sp->skin = m->skin_ratio * m->pp.r0;
    sp->xb = m->xb;
    int k = 0;
    for (int d = 0; d < 3; d++) {
        sp->particle[k] = (void **)&m->xb[d];
        sp->particle_size[k++] = sizeof(double);
    }
    sp->particle[k] = (void **)&m->epot;
    sp->particle_size[k++] = sizeof(double);
    sp->particle[k] = (void **)&m->sig;
    sp->particle_size[k++] = 6 * sizeof(double);
    sp->particle[k] = (void **)&m->wdiss;
    sp->particle_size[k++] = sizeof(double);
    sp->particle[k] = (void **)&m->gflag;
    sp->particle_size[k++] = 1;
    sp->n_particle = k;
    return 0;
}

/* After a migration (par_migrate replaced the lent list's arrays): the
 * list takes the migrated rows, in their serial order, with the partners
 * resolved to the new local indices. */
static void adopt_migrated(struct model *m)
{
    if (!m->mbl.offset || m->mbl.offset == m->nl->offset)
        return;
    m->nl->n = m->mbl.n;
    m->nl->offset = m->mbl.offset;
    m->nl->idx = m->mbl.partner;
    m->half_ok = false; /* the once-per-pair arrays (macro_half.c) describe the old list */
    free(m->mbl.state);
    memset(&m->mbl, 0, sizeof m->mbl);
}

int macro_spatial_rebuilt(struct model *m, struct sim *sim, bool moved, struct spall_error *err)
{
    adopt_migrated(m);
    gauge_from_flags(m, sim->p->n_owned);
    return macro_list_build(m, sim, moved, err);
}

void macro_par_release(struct model *m)
{
    if (m->nl && m->mbl.offset == m->nl->offset) { /* lent, not migrated: the view's own state */
        free(m->mbl.state);
    } else if (m->mbl.offset) { /* migrated, never adopted (a failed run) */
        free(m->mbl.offset);
        free(m->mbl.partner);
        free(m->mbl.state);
    }
    memset(&m->mbl, 0, sizeof m->mbl);
}

int macro_migrate_arrays(struct model *m, struct par_model_arrays *a, struct spall_error *err)
{
    if (!m->nl)
        return spall_error_set(err, SPALL_ERR_INTERNAL, "macro-particle list not built");
    macro_half_epot_sync(m); /* epot travels with the particles */
    adopt_migrated(m);
    macro_par_release(m);
    /* the partner list as a bond list (a zero state per pair): a migrant
     * takes its row with every pair's plastic state, keyed by partner gid */
    const size_t ns = m->nl->offset[m->nl->n];
    uint8_t *st = calloc(ns ? ns : 1, 1);
    if (!st)
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory (macro-particle migration)");
    m->mbl = (struct bond_list){.n = m->nl->n, .offset = m->nl->offset, .partner = m->nl->idx,
                                .state = st};
    m->n_half = ns;
    memset(a, 0, sizeof *a);
    a->bl = &m->mbl;
    a->n_half = &m->n_half;
    struct par_spatial_model sp;
    macro_spatial_ghosts(m, &sp);
    a->n_particle = sp.n_particle;
    for (int k = 0; k < sp.n_particle; k++) {
        a->particle[k] = sp.particle[k];
        a->particle_size[k] = sp.particle_size[k];
    }
    void **pa[] = {(void **)&m->dr0, (void **)&m->kappa, (void **)&m->engaged,
                   (void **)&m->pgid};
    const size_t ps[] = {sizeof(double), sizeof(double), sizeof(uint8_t), sizeof(int64_t)};
    for (int k = 0; k < 4; k++) {
        a->bond[k] = pa[k];
        a->bond_size[k] = ps[k];
    }
    a->n_bond = 4;
    return SPALL_OK;
}

/* ---- slip fields of a distributed run ------------------------------------ */

struct slip_set {
    size_t n;         /**< owned + reference ghosts, in ascending gid */
    double *x[3], *x0[3];
    size_t *owned_at; /**< where each owned particle lies in the set */
    double *out;      /**< 3 per particle of the set */
    double *xo, *xg;  /**< current positions of the owned (3 each) and the ghosts */
};

static void slip_set_free(struct slip_set *t)
{
    for (int d = 0; d < 3; d++) {
        free(t->x[d]);
        free(t->x0[d]);
    }
    free(t->owned_at);
    free(t->out);
    free(t->xo);
    free(t->xg);
}

static int cmp_gid_idx(const void *a, const void *b, const int64_t *gid)
{
    int64_t x = gid[*(const size_t *)a], y = gid[*(const size_t *)b];
    return (x > y) - (x < y);
}

/* Owned indices by ascending gid (they already are, after the partition
 * and every migration; insertion sort keeps that cheap and certain). */
static void owned_by_gid(size_t *o, size_t n, const int64_t *gid)
{
    for (size_t i = 0; i < n; i++) {
        size_t k = i;
        while (k > 0 && cmp_gid_idx(&o[k - 1], &i, gid) > 0) {
            o[k] = o[k - 1];
            k--;
        }
        o[k] = i;
    }
}

int macro_slip_par(const struct model *m, const struct sim *sim, double *slip, double *normal,
                   struct spall_error *err)
{
    const struct particles *p = sim->p;
    const size_t no = p->n_owned;
    const double r0 = m->pp.r0;
    struct par_sghost *g = NULL;
    struct slip_set t;
    memset(&t, 0, sizeof t);
    /* the reference neighbours (x0 within 1.1 r0) of every owned particle
     * are ghosts of a set built on the reference positions, wherever the
     * particles are now (the skin only widens the box test) */
    int rc = par_agree(par_sghost_create(&g, 3, 1.1 * r0, 0.05 * r0, err), err);
    const double *x0[3] = {p->x0[0], p->x0[1], p->x0[2]};
    if (!rc)
        rc = par_sghost_build(g, no, x0, p->gid, err);
    const size_t ng = rc ? 0 : par_sghost_count(g), n = no + ng;
    int bad = 0;
    if (!rc) {
        t.n = n;
        t.xo = malloc(3 * (no ? no : 1) * sizeof *t.xo);
        t.xg = malloc(3 * (ng ? ng : 1) * sizeof *t.xg);
        t.owned_at = malloc((no ? no : 1) * sizeof *t.owned_at);
        t.out = malloc(3 * (n ? n : 1) * sizeof *t.out);
        bad = !t.xo || !t.xg || !t.owned_at || !t.out;
        for (int d = 0; d < 3 && !bad; d++) {
            t.x[d] = malloc((n ? n : 1) * sizeof(double));
            t.x0[d] = malloc((n ? n : 1) * sizeof(double));
            bad = !t.x[d] || !t.x0[d];
        }
        for (size_t i = 0; i < no && !bad; i++)
            for (int d = 0; d < 3; d++)
                t.xo[3 * i + d] = p->x[d][i];
        rc = par_agree(bad ? spall_error_set(err, SPALL_ERR_NOMEM, "out of memory (slip fields)")
                           : SPALL_OK,
                       err);
    }
    if (!rc)
        rc = par_sghost_values(g, t.xo, t.xg, 3, err);
    size_t *ord = rc ? NULL : malloc((no ? no : 1) * sizeof *ord);
    if (!rc && !ord)
        rc = spall_error_set(err, SPALL_ERR_NOMEM, "out of memory (slip fields)");
    struct neighbor_list *ref = NULL;
    if (!rc) {
        /* one set in ascending gid: each list row then holds its partners
         * in the serial order, so the sums are the one-rank ones */
        owned_by_gid(ord, no, p->gid);
        const int64_t *ggid = par_sghost_gid(g);
        for (size_t a = 0, b = 0, k = 0; k < n; k++) {
            const bool own = b >= ng || (a < no && p->gid[ord[a]] < ggid[b]);
            for (int d = 0; d < 3; d++) {
                t.x0[d][k] = own ? p->x0[d][ord[a]] : par_sghost_x(g, d)[b];
                t.x[d][k] = own ? p->x[d][ord[a]] : t.xg[3 * b + d];
            }
            if (own)
                t.owned_at[ord[a++]] = k;
            else
                b++;
        }
        rc = neighbor_list_build_pairs(&ref, NULL, 3, n, t.x0, 1.1 * r0, err);
    }
    for (int w = 0; w < 2 && !rc; w++) {
        double *dst = w ? normal : slip;
        if (!dst)
            continue;
        macro_slip_vectors(n, t.x, t.x0, ref, 0.25 * r0, w ? NULL : t.out, w ? t.out : NULL, NULL);
        for (size_t i = 0; i < no; i++)
            memcpy(dst + 3 * i, t.out + 3 * t.owned_at[i], 3 * sizeof(double));
    }
    neighbor_list_destroy(&ref);
    free(ord);
    slip_set_free(&t);
    par_sghost_destroy(&g);
    return rc;
}
