/**
 * @file sph_localize.c
 * @brief model_ops.localize of the SPH model (distributed runs,
 *        core/parallel/decomp.h): the total-Lagrangian formulation, whose
 *        reference partner lists are fixed at set-up and so play the part
 *        of a bond model's families.  The ghosts of a rank are the
 *        reference partners of its owned particles (held elsewhere); each
 *        owned row keeps its serial order (ascending gid) with the partners
 *        renumbered, so the deformation gradient's sums are the serial
 *        ones; the force stage gathers (sph_tlsph.c, tl_rates_par) with the
 *        constants each pair has in its partner's row (prev).
 *
 * The updated-Lagrangian form finds its partners by a neighbour search on
 * the spatial ghosts (sph_ulpar.c); this file dispatches to it.  TLSPH
 * bodies behind an interface (split_forms) use both: the spatial ghosts of
 * the current list extended by the reference partners (sph_tl_spatial_ghosts,
 * sph_tl_relayout renumbering the reference rows by gid after each ghost
 * build).  A distributed re-reference (sph_tlsph_reref.c) ends in
 * sph_tl_par_rows.
 */
#include "models/sph/sph_internal.h"
#include "models/sph/sph_tlsph_data.h"

#include "core/bond_list.h"
#include "core/fields.h"
#include "core/neighbor.h"
#include "core/parallel/comm.h"
#include "core/parallel/migrate.h"
#include "core/parallel/spatial.h"
#include "core/particles.h"
#include "core/sim.h"
#include "spall/error.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

/* The reference list as a bond list (partners only): the halo and the
 * partition's weights (1 + partners) read it; its rows follow the list's. */
static int halo_list(struct model *m, struct spall_error *err)
{
    if (m->tl->halo)
        return SPALL_OK;
    const struct neighbor_list *nl = m->tl->ref->nl;
    const size_t n = nl->n, nh = nl->offset[n];
    struct bond_list *bl = calloc(1, sizeof *bl);
    if (bl) {
        bl->n = n;
        bl->offset = malloc((n + 1) * sizeof *bl->offset);
        bl->partner = malloc((nh ? nh : 1) * sizeof *bl->partner);
        bl->state = calloc(nh ? nh : 1, sizeof *bl->state);
    }
    if (!bl || !bl->offset || !bl->partner || !bl->state) {
        bond_list_destroy(&bl);
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory (SPH halo list)");
    }
    memcpy(bl->offset, nl->offset, (n + 1) * sizeof *bl->offset);
    memcpy(bl->partner, nl->idx, nh * sizeof *bl->partner);
    m->tl->halo = bl;
    return SPALL_OK;
}

int sph_tl_halo_refresh(struct model *m, struct spall_error *err)
{
    if (!m->tl || !m->tl->halo)
        return SPALL_OK;
    bond_list_destroy(&m->tl->halo);
    return halo_list(m, err);
}

const struct bond_list *sph_halo_bonds(const struct model *m)
{
    /* the updated form: its neighbour list, for the partition's work
     * (1 + partners); its ghosts are the spatial ones (sph_ulpar.c) */
    return m->tl ? m->tl->halo : m->ulview;
}

/* The array is a stored field of the registry (the engine compacts it). */
static bool in_registry(const struct sim *s, const void *a)
{
    const struct field_registry *reg = s->fields;
    for (size_t k = 0; k < reg->n; k++)
        for (int c = 0; c < reg->fields[k].ncomp && reg->fields[k].comp[c]; c++)
            if (*reg->fields[k].comp[c] == a)
                return true;
    return false;
}

/* prev[k] of pair (i, j) = the constants of (j, i) in j's row (rows sorted
 * ascending; the reference list is symmetric). */
static int reverse_pairs(const struct sph_tl *t, struct tl_pair **prev, struct spall_error *err)
{
    const size_t n = t->nl->n, *off = t->nl->offset;
    const int32_t *nb = t->nl->idx;
    *prev = malloc((off[n] ? off[n] : 1) * sizeof **prev);
    if (!*prev)
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory (TLSPH reverse pairs)");
    for (size_t i = 0; i < n; i++)
        for (size_t k = off[i]; k < off[i + 1]; k++) {
            const size_t j = (size_t)nb[k];
            size_t lo = off[j], hi = off[j + 1];
            while (lo < hi) {
                const size_t mid = lo + (hi - lo) / 2;
                if ((size_t)nb[mid] < i)
                    lo = mid + 1;
                else
                    hi = mid;
            }
            if (lo == off[j + 1] || (size_t)nb[lo] != i)
                return spall_error_set(err, SPALL_ERR_INTERNAL,
                                       "TLSPH: the reference list is not symmetric (%zu, %zu)", i,
                                       j);
            (*prev)[k] = t->pair[lo];
        }
    return SPALL_OK;
}

/* Replace *a by a[keep[0, n)] (elements of @p size bytes). */
static int gather(void *pa, size_t size, const size_t *keep, size_t n)
{
    void **a = pa;
    void *b = array_gather(*a, size, keep, n ? n : 0);
    if (!b)
        return -1;
    free(*a);
    *a = b;
    return 0;
}

/* Per listed pair: its row's particle; per particle: the first pair of
 * its row whose partner comes later in the serial order (serial index =
 * gid), i.e. the split of sph_tlsph.c's force stage. */
static void row_split(struct sph_tl *t, const int64_t *gid)
{
    const size_t n = t->nl->n, *off = t->nl->offset;
    const int32_t *nb = t->nl->idx;
    for (size_t i = 0; i < n; i++) {
        size_t u = off[i];
        while (u < off[i + 1] && gid[nb[u]] < gid[i])
            u++;
        t->up[i] = u;
        for (size_t k = off[i]; k < off[i + 1]; k++)
            t->rown[k] = (int32_t)i;
    }
}

/* The local reference list of the n particles from the halo list (owned
 * rows resolved, ghost rows empty), the split of each row at the serial
 * order @p serial (per local particle) and the halo buffer. */
static int rebuild_list(struct model *m, size_t n, const int64_t *serial, struct spall_error *err)
{
    struct sph_tl *t = m->tl->ref;
    const struct bond_list *bl = m->tl->halo;
    const size_t nh = bl->offset[bl->n];
    size_t *off = malloc((n + 1) * sizeof *off);
    int32_t *idx = malloc((nh ? nh : 1) * sizeof *idx);
    size_t *up = malloc((n ? n : 1) * sizeof *up);
    int32_t *rown = malloc((nh ? nh : 1) * sizeof *rown);
    double *halo = calloc((n ? n : 1) * TL_HALO, sizeof *halo);
    if (!off || !idx || !up || !rown || !halo || bl->n != n) {
        free(off);
        free(idx);
        free(up);
        free(rown);
        free(halo);
        return spall_error_set(err, bl->n != n ? SPALL_ERR_INTERNAL : SPALL_ERR_NOMEM,
                               "SPH: cannot rebuild the TLSPH reference list of this rank");
    }
    int64_t *rgid = malloc((nh ? nh : 1) * sizeof *rgid);
    if (!rgid) {
        free(off);
        free(idx);
        free(up);
        free(rown);
        free(halo);
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory (TLSPH partner ids)");
    }
    memcpy(off, bl->offset, (n + 1) * sizeof *off);
    memcpy(idx, bl->partner, nh * sizeof *idx);
    for (size_t k = 0; k < nh; k++) /* the rows' partners by id (sph_tl_relayout) */
        rgid[k] = serial[idx[k]];
    free(t->rgid);
    t->rgid = rgid;
    free(t->nl->offset);
    free(t->nl->idx);
    t->nl->offset = off;
    t->nl->idx = idx;
    t->nl->n = n;
    free(t->up);
    t->up = up;
    free(t->rown);
    t->rown = rown;
    free(t->halo);
    t->halo = halo;
    row_split(t, serial);
    return SPALL_OK;
}

static int localize_tl(struct model *m, const size_t *keep, size_t n_keep, size_t n_owned,
                       const int64_t *new_of_old, struct spall_error *err)
{
    struct sph_tl *t = m->tl->ref;
    m->tl->pairs_all = t->nl->offset[t->nl->n]; /* the serial m->n_pairs (restart state) */
    struct tl_pair *prev = NULL;
    int rc = reverse_pairs(t, &prev, err);
    struct bond_rows rows;
    if (!rc)
        rc = bond_list_localize(m->tl->halo, keep, n_keep, n_owned, new_of_old, &rows, err);
    if (rc) {
        free(prev);
        return rc;
    }
    /* per pair: the constants in both orientations; per particle: the
     * packed blocks (their reference part is set up once) */
    struct tl_pair *npair = bond_rows_gather(&rows, t->pair, sizeof *npair);
    struct tl_pair *nprev = bond_rows_gather(&rows, prev, sizeof *nprev);
    int64_t *serial = malloc((n_keep ? n_keep : 1) * sizeof *serial);
    free(prev);
    bond_rows_free(&rows);
    if (!npair || !nprev || !serial || gather(&t->pk, TL_STRIDE * sizeof(double), keep, n_keep) ||
        gather(&t->self, TL_SELF * sizeof(double), keep, n_keep)) {
        free(npair);
        free(nprev);
        free(serial);
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory localising TLSPH");
    }
    free(t->pair);
    t->pair = npair;
    free(t->prev);
    t->prev = nprev;
    /* the serial split of each row: partners of lower serial index first
     * (their rows scatter into i), then the upper part i's row runs */
    for (size_t i = 0; i < n_keep; i++)
        serial[i] = (int64_t)keep[i];
    rc = rebuild_list(m, n_keep, serial, err);
    free(serial);
    return rc;
}

int sph_localize(struct model *m, struct sim *sim, const size_t *keep, size_t n_keep,
                 size_t n_owned, const int64_t *new_of_old, struct spall_error *err)
{
    int rc = m->tl ? halo_list(m, err) : SPALL_OK;
    if (rc || !keep) /* only asked whether it can (and for the halo list) */
        return rc;
    /* the updated form's list is rebuilt around the spatial ghosts right
     * after (sph_ulpar.c, par_spatial_init); so is a split run's (both) */
    if (!m->tl || m->form) {
        sph_ul_localize(m);
        /* the interface's per-particle values of the last force call (a
         * restart's, checkpointed; NULL without an interface) */
        if (m->ifs.e && (gather(&m->ifs.e, sizeof *m->ifs.e, keep, n_keep) ||
                         gather(&m->ifs.w, sizeof *m->ifs.w, keep, n_keep) ||
                         gather(&m->ifs.np, sizeof *m->ifs.np, keep, n_keep)))
            return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory localising SPH state");
        if (m->ifs.e)
            m->ifs.n_alloc = n_keep;
    }
    if (m->tl && (rc = localize_tl(m, keep, n_keep, n_owned, new_of_old, err)))
        return rc;
    if (m->form && gather(&m->form, 1, keep, n_keep))
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory localising SPH forms");
    /* the model's own per-particle arrays (the registry's are the engine's) */
    double **a[SPH_N_ARRAYS];
    const size_t na = sph_state_arrays(m, a);
    for (size_t k = 0; k < na; k++)
        if (*a[k] && !in_registry(sim, *a[k]) && gather(a[k], sizeof(double), keep, n_keep))
            return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory localising SPH state");
    return SPALL_OK;
}

/* model_ops.migrate_arrays: the reference rows (as the halo list) with
 * each pair's constants in both orientations, every per-particle array of
 * the model (those that are registry fields are the engine's: the
 * migration takes each array once) and the packed blocks, whose reference
 * part (mass, volume, X0, B0^-1) a particle keeps for life. */
int sph_migrate_arrays(struct model *m, struct par_model_arrays *a, struct spall_error *err)
{
    if (!m->tl)
        return sph_ul_migrate_arrays(m, m->sim, a, err);
    struct sph_tl *t = m->tl->ref;
    a->bl = m->tl->halo;
    m->tl->n_half = t->nl->offset[t->nl->n];
    a->n_half = &m->tl->n_half;
    double **arr[SPH_N_ARRAYS];
    const size_t na = sph_state_arrays(m, arr);
    if (na + 5 > PAR_MIGRATE_MAX_ARRAYS)
        return spall_error_set(err, SPALL_ERR_INTERNAL, "SPH: %zu arrays to migrate", na + 5);
    a->n_particle = 0;
    for (size_t k = 0; k < na; k++) {
        a->particle[a->n_particle] = (void **)arr[k];
        a->particle_size[a->n_particle++] = sizeof(double);
    }
    a->particle[a->n_particle] = (void **)&t->pk;
    a->particle_size[a->n_particle++] = TL_STRIDE * sizeof(double);
    a->particle[a->n_particle] = (void **)&t->self;
    a->particle_size[a->n_particle++] = TL_SELF * sizeof(double);
    /* TLSPH bodies behind an interface: the interface's per-particle values
     * of the last force call go with their particles, as in the updated
     * form (sph_ul_migrate_arrays; sph_ul_migrated takes them as sized for
     * the new layout) */
    void **ia[] = {(void **)&m->ifs.e, (void **)&m->ifs.w, (void **)&m->ifs.np};
    const size_t is[] = {sizeof *m->ifs.e, sizeof *m->ifs.w, sizeof *m->ifs.np};
    for (size_t k = 0; k < 3 && m->form && m->ifs.e; k++) {
        a->particle[a->n_particle] = ia[k];
        a->particle_size[a->n_particle++] = is[k];
    }
    a->n_bond = 2;
    a->bond[0] = (void **)&t->pair;
    a->bond_size[0] = sizeof *t->pair;
    a->bond[1] = (void **)&t->prev;
    a->bond_size[1] = sizeof *t->prev;
    return SPALL_OK;
}

/* model_ops.migrated: the reference list, the row split and the halo
 * scratch of the new owned + ghost particles. */
int sph_migrated(struct model *m, struct sim *sim, struct spall_error *err)
{
    if (!m->tl)
        return sph_ul_migrated(m, sim->p->n, err);
    int rc = m->form ? sph_ul_migrated(m, sim->p->n, err) : SPALL_OK; /* the current list: rebuilt */
    if (!rc)
        rc = rebuild_list(m, sim->p->n, sim->p->gid, err);
    /* m->form follows the particles (the ghosts are rebuilt next) */
    return rc || !m->form ? rc : sph_tl_relayout(m, sim, err);
}

int sph_tl_par_rows(struct model *m, struct sim *sim, struct spall_error *err)
{
    /* the reference rows of the owned particles (ghost rows empty) as the
     * halo list, then the rows' split, partner ids and scratch */
    const struct particles *p = sim->p;
    struct sph_tl *t = m->tl->ref;
    m->tl->pairs_all = (size_t)par_sum_u64((uint64_t)t->nl->offset[p->n_owned]);
    bond_list_destroy(&m->tl->halo);
    int rc = halo_list(m, err);
    return rc ? rc : rebuild_list(m, p->n, p->gid, err);
}

void sph_tl_spatial_ghosts(struct model *m, struct par_spatial_model *sp)
{
    if (!m->tl)
        return;
    /* stage 1 of an owned particle reads its partners' reference block
     * (mass, volume, X0) and the force stage B0^-1 of the pair's rows:
     * the packed blocks travel whole (the halo of each force call
     * refreshes their current part) */
    struct sph_tl *t = m->tl->ref;
    int k = sp->n_particle;
    sp->particle[k] = (void **)&t->pk;
    sp->particle_size[k++] = TL_STRIDE * sizeof(double);
    sp->particle[k] = (void **)&t->self;
    sp->particle_size[k++] = TL_SELF * sizeof(double);
    sp->n_particle = k;
    sp->bonds = m->tl->halo;
}

/* Local index of global id @p g among ids ascending in [lo, hi), or -1. */
static long find_gid(const int64_t *gid, size_t lo, size_t hi, int64_t g)
{
    const size_t end = hi;
    while (lo < hi) {
        const size_t mid = lo + (hi - lo) / 2;
        if (gid[mid] < g)
            lo = mid + 1;
        else
            hi = mid;
    }
    return lo < end && gid[lo] == g ? (long)lo : -1;
}

/* Grow @p off (rows [0, from] set) to n rows; the new rows empty. */
static size_t *rows_to(size_t *off, size_t from, size_t n)
{
    size_t *o = realloc(off, (n + 1) * sizeof *o);
    for (size_t i = from + 1; o && i <= n; i++)
        o[i] = o[from];
    return o;
}

int sph_tl_relayout(struct model *m, struct sim *sim, struct spall_error *err)
{
    const struct particles *p = sim->p;
    const size_t n = p->n, no = p->n_owned;
    if (m->form) { /* every local particle's, ghosts included (the interface split) */
        uint8_t *f = realloc(m->form, n ? n : 1);
        if (!f)
            return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory (SPH forms)");
        m->form = f;
        for (size_t i = 0; i < n; i++)
            f[i] = (size_t)p->body[i] < m->n_bodies ? m->body_total[p->body[i]] : 0;
    }
    if (!m->tl)
        return SPALL_OK;
    struct sph_tl *t = m->tl->ref;
    struct bond_list *bl = m->tl->halo;
    const size_t nh = t->nl->offset[no];
    /* ghost rows are empty: rows [0, no) hold every pair */
    size_t *o1 = rows_to(t->nl->offset, no, n);
    if (o1)
        t->nl->offset = o1;
    size_t *o2 = rows_to(bl->offset, no, n);
    if (o2)
        bl->offset = o2;
    size_t *up = realloc(t->up, (n ? n : 1) * sizeof *up);
    if (up)
        t->up = up;
    double *halo = realloc(t->halo, (n ? n : 1) * TL_HALO * sizeof *halo);
    if (halo)
        t->halo = halo;
    if (!o1 || !o2 || !up || !halo)
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory (TLSPH rows)");
    t->nl->n = n;
    bl->n = n;
    for (size_t k = 0; k < nh; k++) {
        long j = find_gid(p->gid, 0, no, t->rgid[k]);
        if (j < 0)
            j = find_gid(p->gid, no, n, t->rgid[k]);
        if (j < 0)
            return spall_error_set(err, SPALL_ERR_INTERNAL,
                                   "TLSPH: reference partner %lld is not held by this rank",
                                   (long long)t->rgid[k]);
        t->nl->idx[k] = (int32_t)j;
        bl->partner[k] = (int32_t)j;
    }
    row_split(t, p->gid);
    return SPALL_OK;
}
