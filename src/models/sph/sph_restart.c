/**
 * @file sph_restart.c
 * @brief Restart state of the SPH model (updated and total Lagrangian):
 *        every per-particle array (state, state at step n and rates of the
 *        predictor-corrector, stresses, CSPM matrices, XSPH velocities,
 *        smoothing lengths), the neighbour list with the positions it was
 *        built at, the interface pair list, and after a TLSPH re-reference
 *        the new reference pair data ([Meng2021] ch. 3).  Without a
 *        re-reference the reference data are rebuilt by init from the deck.
 */
#include "models/sph/sph_internal.h"

#include "core/field_state.h"
#include "core/neighbor.h"
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

/* ---- the updated-Lagrangian neighbour list and the interface list ------- */

static size_t nl_rows(const void *ctx)
{
    const struct neighbor_list *nl = ((const struct model *)ctx)->nl;
    return nl ? nl->offset[nl->n] : 0;
}

static int nl_set_rows(void *ctx, size_t rows, struct spall_error *err)
{
    struct neighbor_list *nl = ((struct model *)ctx)->nl;
    return grow((void **)&nl->idx, rows, sizeof *nl->idx, err);
}

static size_t if_rows(const void *ctx)
{
    const struct model *m = ctx;
    return m->ifs.off[m->sim->p->n_owned];
}

static int if_set_rows(void *ctx, size_t rows, struct spall_error *err)
{
    struct model *m = ctx;
    if (rows > m->ifs.cap) {
        int rc = grow((void **)&m->ifs.idx, rows, sizeof *m->ifs.idx, err);
        if (rc)
            return rc;
        m->ifs.cap = rows;
    }
    return SPALL_OK;
}

/* ---- TLSPH reference after a re-reference -------------------------------- */

static size_t tl_rows(const void *ctx)
{
    const struct sph_tl *t = ((const struct model *)ctx)->tl->ref;
    return t->nl->offset[t->nl->n];
}

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
    rc = field_state_add_array(fs, "sph.tl_offset", FIELD_I64, (void **)&t->nl->offset, n + 1, 1,
                               err);
    if (!rc)
        rc = field_state_add_list(fs, "sph.tl_partner", FIELD_I32, (void **)&t->nl->idx, 1,
                                  tl_rows, tl_set_idx, m, err);
    if (!rc)
        rc = field_state_add_list(fs, "sph.tl_pair", FIELD_F64, (void **)&t->pair, 2, tl_rows,
                                  tl_set_pair, m, err);
    if (!rc)
        rc = field_state_add_array(fs, "sph.tl_up", FIELD_I64, (void **)&t->up, n, 1, err);
    if (!rc)
        rc = field_state_add_values(fs, "sph.tl_band", FIELD_I64, &t->band, 1, err);
    return rc;
}

int sph_register_state(struct model *m, struct sim *s, struct field_state *fs,
                       struct spall_error *err)
{
    _Static_assert(sizeof(size_t) == 8 && sizeof(long) == 8 && sizeof(uint32_t) == 4,
                   "counters are saved as int64, contact counts as int32");
    const size_t n = s->p->n_owned;
    if (m->sym || (s->p->n != n && !s->par)) /* a distributed run's are the ranks' ghosts */
        return spall_error_set(err, SPALL_ERR_INPUT,
                               "sph: runs with symmetry planes (ghost particles) cannot be "
                               "checkpointed yet");
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
    if (!rc && m->nl) {
        rc = field_state_add_array(fs, "sph.list_offset", FIELD_I64, (void **)&m->nl->offset,
                                   m->nl->n + 1, 1, err);
        if (!rc)
            rc = field_state_add_list(fs, "sph.list_partner", FIELD_I32, (void **)&m->nl->idx, 1,
                                      nl_rows, nl_set_rows, m, err);
    }
    if (!rc && m->ifs.off) {
        rc = field_state_add_array(fs, "sph.iface_offset", FIELD_I64, (void **)&m->ifs.off, n + 1,
                                   1, err);
        if (!rc)
            rc = field_state_add_list(fs, "sph.iface_partner", FIELD_I32, (void **)&m->ifs.idx, 1,
                                      if_rows, if_set_rows, m, err);
        if (!rc)
            rc = field_state_add_array(fs, "sph.iface_e", FIELD_F64, (void **)&m->ifs.e, n, 1, err);
        if (!rc)
            rc = field_state_add_array(fs, "sph.iface_w", FIELD_F64, (void **)&m->ifs.w, n, 1, err);
        if (!rc)
            rc = field_state_add_array(fs, "sph.iface_np", FIELD_I32, (void **)&m->ifs.np, n, 1,
                                       err);
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
