/**
 * @file sph_restart.c
 * @brief Restart state of the SPH model (updated and total Lagrangian):
 *        every per-particle array (state, state at step n and rates of the
 *        predictor-corrector, stresses, CSPM matrices, XSPH velocities,
 *        smoothing lengths), the neighbour list with the positions it was
 *        built at, the interface pair list, and after a TLSPH re-reference
 *        the new reference pair data ([Meng2021] ch. 3).  Without a
 *        re-reference the reference data are rebuilt by init from the deck.
 *
 * The lists are saved by global id, so a distributed run's checkpoint is
 * the one-rank file (below).  With symmetry planes the list spans the
 * mirror ghosts, which are not particles of the run: it is not saved but
 * found again after the load from the build positions and list radius
 * (sph_symmetry.c: sph_symmetry_restore on one rank, sph_symmetry_list
 * after the partition on several), on any rank count.
 */
#include "models/sph/sph_internal.h"

#include "core/field_state.h"
#include "core/neighbor.h"
#include "core/parallel/comm.h"
#include "core/parallel/decomp.h"
#include "core/parallel/gather.h"
#include "core/particles.h"
#include "core/sim.h"
#include "models/sph/sph_tlsph_data.h"
#include "spall/error.h"

#include <stdio.h>
#include <stdlib.h>

static int grow(void **a, size_t rows, size_t size, struct spall_error *err)
{
    void *g = realloc(*a, (rows ? rows : 1) * size);
    if (!g)
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory (sph restart)");
    *a = g;
    return SPALL_OK;
}

/* ---- the updated-Lagrangian neighbour list and the interface list -------
 *
 * Both are registered as bond lists of the owned rows (offsets and
 * partners), as macro_restart.c does with its Verlet list: a distributed
 * run writes each owned row at its serial place with the partners by
 * global id (io/checkpoint_par.c), and its rows are in the serial order
 * (ascending partner gid, sph_ulpar.c), so the file is the one-rank file,
 * whose partners are indices = global ids.  The slots and dataset names
 * are those of format 1: one-rank checkpoints are unchanged.  A load always
 * goes into the whole body (before any partition), where index = gid. */

static int nl_set_rows(void *ctx, size_t rows, struct spall_error *err)
{
    struct model *m = ctx;
    struct neighbor_list *nl = m->nl;
    if (nl->offset[m->ck_list.n] != rows) /* the offsets are read first */
        return spall_error_set(err, SPALL_ERR_INPUT,
                               "sph neighbour list: %zu pairs, its offsets say %zu", rows,
                               nl->offset[m->ck_list.n]);
    int rc = grow((void **)&nl->idx, rows, sizeof *nl->idx, err);
    /* the bond view of a run about to be partitioned aliases the rows */
    if (!rc && sph_ul_view(m))
        rc = spall_error_set(err, SPALL_ERR_NOMEM, "out of memory (sph restart)");
    return rc;
}

static int if_set_rows(void *ctx, size_t rows, struct spall_error *err)
{
    struct model *m = ctx;
    if (m->ifs.off[m->ck_iface.n] != rows)
        return spall_error_set(err, SPALL_ERR_INPUT,
                               "sph interface list: %zu pairs, its offsets say %zu", rows,
                               m->ifs.off[m->ck_iface.n]);
    if (rows > m->ifs.cap) {
        int rc = grow((void **)&m->ifs.idx, rows, sizeof *m->ifs.idx, err);
        if (rc)
            return rc;
        m->ifs.cap = rows;
    }
    return SPALL_OK;
}

/* Distributed runs: the partners of the owned rows of @p bl by global id
 * into *gid. */
static int partner_gids(const struct sim *s, const struct bond_list *bl, int32_t **gid,
                        struct spall_error *err)
{
    const size_t ns = bl->offset[bl->n];
    int rc = grow((void **)gid, ns, sizeof **gid, err);
    for (size_t k = 0; k < ns && !rc; k++)
        (*gid)[k] = (int32_t)s->p->gid[bl->partner[k]];
    return rc;
}

/* Offsets and partners of the owned rows of a list as slots NAME_offset
 * and NAME_partner. */
static int register_rows(struct model *m, const struct sim *s, struct field_state *fs,
                         const char *name, struct bond_list *bl, size_t **offset,
                         int32_t **partner, int32_t **gid, field_state_set_rows_fn set_rows,
                         struct spall_error *err)
{
    *bl = (struct bond_list){.n = s->p->n_owned, .offset = *offset, .partner = *partner};
    void **data = (void **)partner;
    int rc = SPALL_OK;
    if (s->par) {
        rc = partner_gids(s, bl, gid, err);
        data = (void **)gid;
    }
    char nm[FIELD_STATE_NAME_LEN];
    snprintf(nm, sizeof nm, "sph.%s_offset", name);
    if (!rc)
        rc = field_state_add_offsets(fs, nm, (void **)offset, bl, err);
    snprintf(nm, sizeof nm, "sph.%s_partner", name);
    if (!rc)
        rc = field_state_add_bond_list(fs, nm, FIELD_I32, data, bl, 1, set_rows, m, err);
    return rc;
}

/* ---- TLSPH reference after a re-reference -------------------------------- */

static int tl_set_idx(void *ctx, size_t rows, struct spall_error *err)
{
    struct sph_tl *t = ((struct model *)ctx)->tl->ref;
    return grow((void **)&t->nl->idx, rows, sizeof *t->nl->idx, err);
}

static int tl_set_pair(void *ctx, size_t rows, struct spall_error *err)
{
    struct sph_tl *t = ((struct model *)ctx)->tl->ref;
    return grow((void **)&t->pair, rows, sizeof *t->pair, err);
}

/* Called before the band is read, after the rows (the slots load in their
 * order): a run about to be partitioned (mpirun) lends the loaded rows,
 * not those of set-up, to the partition (sph_localize.c). */
static int tl_loaded(void *ctx, size_t rows, struct spall_error *err)
{
    (void)rows;
    return sph_tl_halo_refresh(ctx, err);
}

/* A distributed run writes the serial file (sph_localize.c keeps the rows
 * in the serial order): the partners of the owned rows by global id, each
 * row's split and the band in serial indices (the rows' places in the
 * serial list from the row lengths of the whole body).  Collective. */
static int tl_par_views(struct model *m, struct spall_error *err)
{
    const struct sim *s = m->sim;
    const struct sph_tl *t = m->tl->ref;
    const size_t no = s->p->n_owned, ng = par_n_global(s), *off = t->nl->offset;
    const size_t ns = off[no];
    double *len = malloc((no ? no : 1) * sizeof *len), *all = malloc((ng + 1) * sizeof *all);
    int rc = grow((void **)&m->ck_tlgid, ns, sizeof *m->ck_tlgid, err);
    if (!rc)
        rc = grow((void **)&m->ck_tlup, no, sizeof *m->ck_tlup, err);
    if (!rc && (!len || !all))
        rc = spall_error_set(err, SPALL_ERR_NOMEM, "out of memory (sph restart)");
    int64_t band = 0;
    for (size_t i = 0; i < no && !rc; i++) {
        len[i] = (double)(off[i + 1] - off[i]); /* exact: < 2^53 */
        for (size_t k = off[i]; k < off[i + 1]; k++) {
            const int64_t d = t->rgid[k] - s->p->gid[i];
            band = d > band ? d : -d > band ? -d : band;
            m->ck_tlgid[k] = (int32_t)t->rgid[k];
        }
    }
    rc = par_agree(rc, err);
    if (!rc)
        rc = par_gather_by_gid(s, len, all, err);
    if (!rc) { /* the serial offset of each row, then the split in it */
        double at = 0.0;
        for (size_t g = 0; g < ng; g++) {
            const double l = all[g];
            all[g] = at;
            at += l;
        }
        for (size_t i = 0; i < no; i++)
            m->ck_tlup[i] = (int64_t)all[s->p->gid[i]] + (int64_t)(t->up[i] - off[i]);
    }
    free(len);
    free(all);
    m->ck_tlband = -par_min_i64(-band);
    return rc;
}

static int register_tl(struct model *m, size_t n, struct field_state *fs, struct spall_error *err)
{
    struct sph_tl *t = m->tl->ref;
    _Static_assert(sizeof(struct tl_pair) == 2 * sizeof(double), "pair constants: 2 doubles");
    /* the formulation's counters and guard values (a run without TLSPH
     * bodies has none) */
    double *dv[] = {&m->tl->jmin, &m->tl->kmax};
    const char *dn[] = {"sph.tl_jmin", "sph.tl_kmax"};
    void *iv[] = {&m->tl->rerefs, &m->tl->reref_step, &m->tl->hgrown};
    const char *in[] = {"sph.tl_rerefs", "sph.tl_reref_step", "sph.tl_hgrown"};
    int rc = SPALL_OK;
    for (size_t k = 0; k < 2 && !rc; k++)
        rc = field_state_add_values(fs, dn[k], FIELD_F64, dv[k], 1, err);
    for (size_t k = 0; k < 3 && !rc; k++)
        rc = field_state_add_values(fs, in[k], FIELD_I64, iv[k], 1, err);
    /* the packed blocks: per particle, in gid order on any rank count */
    if (!rc)
        rc = field_state_add_particle_array(fs, "sph.tl_pack", FIELD_F64, (void **)&t->pk, n,
                                            TL_STRIDE, err);
    if (!rc)
        rc = field_state_add_particle_array(fs, "sph.tl_self", FIELD_F64, (void **)&t->self, n,
                                            TL_SELF, err);
    /* the reference list, its pair constants and row split change only at
     * a re-reference; without reference updates init rebuilds them from
     * the deck (a distributed run has none, sph_localize.c) */
    if (rc || !(m->opt.tl.reref_every || m->opt.tl.reref_distortion > 0.0))
        return rc;
    /* the owned rows as bonds (the serial layout from any rank count; a
     * distributed run names the partners by global id) */
    const bool par = m->sim->par != NULL;
    m->ck_tl = (struct bond_list){.n = n, .offset = t->nl->offset, .partner = t->nl->idx};
    if (par && (rc = tl_par_views(m, err)))
        return rc;
    rc = field_state_add_offsets(fs, "sph.tl_offset", (void **)&t->nl->offset, &m->ck_tl, err);
    if (!rc)
        rc = field_state_add_bond_list(fs, "sph.tl_partner", FIELD_I32,
                                       par ? (void **)&m->ck_tlgid : (void **)&t->nl->idx,
                                       &m->ck_tl, 1, tl_set_idx, m, err);
    if (!rc)
        rc = field_state_add_bond_list(fs, "sph.tl_pair", FIELD_F64, (void **)&t->pair,
                                       &m->ck_tl, 2, tl_set_pair, m, err);
    if (!rc)
        rc = field_state_add_particle_array(fs, "sph.tl_up", FIELD_I64,
                                            par ? (void **)&m->ck_tlup : (void **)&t->up, n, 1,
                                            err);
    if (!rc)
        rc = field_state_add_values_hook(fs, "sph.tl_band", FIELD_I64,
                                         par ? (void *)&m->ck_tlband : (void *)&t->band, 1,
                                         tl_loaded, m, err);
    return rc;
}

/* Symmetry planes: the mirror ghosts are rebuilt, not saved.  Their count
 * at the last build (the whole body's: in a distributed run summed over
 * the ranks at each build, sph_symmetry_list) is saved as a check; its
 * load marks the rebuild (sph_symmetry_restore at the next force call on
 * one rank; on several, sph_symmetry_list after the partition). */
static int sym_loaded(void *ctx, size_t rows, struct spall_error *err)
{
    struct model *m = ctx;
    if (rows != 1)
        return spall_error_set(err, SPALL_ERR_INPUT, "sph symmetry ghosts: %zu values", rows);
    m->sym_restore = true;
    return SPALL_OK;
}

static int register_symmetry(struct model *m, const struct sim *s, struct field_state *fs,
                             struct spall_error *err)
{
    if (!s->par)
        m->sym_ghosts = (int64_t)sph_symmetry_ghosts(m);
    return field_state_add_values_hook(fs, "sph.symmetry_ghosts", FIELD_I64, &m->sym_ghosts, 1,
                                       sym_loaded, m, err);
}

int sph_register_state(struct model *m, struct sim *s, struct field_state *fs,
                       struct spall_error *err)
{
    _Static_assert(sizeof(size_t) == 8 && sizeof(long) == 8 && sizeof(uint32_t) == 4,
                   "counters are saved as int64, contact counts as int32");
    const size_t n = s->p->n_owned;
    const bool sym = m->opt.bound.symmetry[0] || m->opt.bound.symmetry[1] ||
                     m->opt.bound.symmetry[2];
    if (s->p->n != n && !s->par) /* a distributed run's are the ranks' spatial ghosts */
        return spall_error_set(err, SPALL_ERR_INTERNAL,
                               "sph: %zu particles beside the %zu owned cannot be checkpointed",
                               s->p->n - n, n);
    double **a[SPH_N_ARRAYS];
    size_t na = sph_state_arrays(m, a);
    char nm[FIELD_STATE_NAME_LEN];
    int rc = SPALL_OK;
    for (size_t k = 0; k < na && !rc; k++) {
        snprintf(nm, sizeof nm, "sph.array.%zu", k);
        rc = field_state_add_particle_array(fs, nm, FIELD_F64, (void **)a[k], n, 1, err);
    }
    if (!rc)
        rc = field_state_add_particle_array(fs, "sph.failed", FIELD_U8, (void **)&m->failed, n, 1,
                                            err);
    if (!rc && sym)
        rc = register_symmetry(m, s, fs, err);
    else if (!rc && m->nl)
        rc = register_rows(m, s, fs, "list", &m->ck_list, &m->nl->offset, &m->nl->idx,
                           &m->ck_gid, nl_set_rows, err);
    if (!rc && m->ifs.off) {
        rc = register_rows(m, s, fs, "iface", &m->ck_iface, &m->ifs.off, &m->ifs.idx,
                           &m->ck_igid, if_set_rows, err);
        if (!rc)
            rc = field_state_add_particle_array(fs, "sph.iface_e", FIELD_F64, (void **)&m->ifs.e,
                                                n, 1, err);
        if (!rc)
            rc = field_state_add_particle_array(fs, "sph.iface_w", FIELD_F64, (void **)&m->ifs.w,
                                                n, 1, err);
        if (!rc)
            rc = field_state_add_particle_array(fs, "sph.iface_np", FIELD_I32,
                                                (void **)&m->ifs.np, n, 1, err);
    }
    double *dv[] = {&m->wall.energy, &m->ax.surface_z, &m->ifs.energy, &m->ifs.omega2,
                    &m->nl_radius};
    const char *dn[] = {"wall_energy", "surface_z", "iface_energy", "iface_omega2",
                        "list_radius"};
    for (size_t k = 0; k < sizeof dv / sizeof dv[0] && !rc; k++) {
        snprintf(nm, sizeof nm, "sph.%s", dn[k]);
        rc = field_state_add_values(fs, nm, FIELD_F64, dv[k], 1, err);
    }
    if (!rc)
        rc = field_state_add_values(fs, "sph.wall_force", FIELD_F64, m->wall.force, 3, err);
    /* an interface with a variable h, or TLSPH bodies behind it whose
     * reference updates grow h: the last build's h_max, with which a
     * distributed restart trims and splits the list it rebuilds
     * (sph_ulpar.c; one rank reads the split list; the latter also keep
     * each particle's h of the build, the last of sph_state_arrays).  Only
     * there: other checkpoints keep their datasets */
    if (!rc && (m->opt.kern.variable_h || m->h_build) && m->opt.iface.kind != SPH_IFACE_NONE)
        rc = field_state_add_values(fs, "sph.list_hmax", FIELD_F64, &m->nl_hmax, 1, err);
    void *iv[] = {&m->n_builds, &m->ax.builds, &m->cspm_fallbacks, &m->n_pairs,
                  &m->ifs.pairs};
    const char *in[] = {"list_builds", "axis_builds", "cspm_fallbacks", "pairs",
                        "iface_pairs"};
    for (size_t k = 0; k < sizeof iv / sizeof iv[0] && !rc; k++) {
        snprintf(nm, sizeof nm, "sph.%s", in[k]);
        rc = field_state_add_values(fs, nm, FIELD_I64, iv[k], 1, err);
    }
    if (!rc && m->tl)
        rc = register_tl(m, n, fs, err);
    return rc;
}
