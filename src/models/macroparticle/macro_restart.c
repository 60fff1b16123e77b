/**
 * @file macro_restart.c
 * @brief Restart state of the macro-particle model: the Verlet list with
 *        the positions it was built at (a rebuild changes the pair order,
 *        hence the round-off), the per-pair plastic offsets and slips, the
 *        random-stream counter of the Langevin forces ([Salmon2011]: the
 *        noise is a function of (seed, call, pair), so the counter is all
 *        the generator's state) and the energy accumulators.
 *
 * The list is registered as a bond list of the owned rows (its offsets,
 * partners and per-pair state), the rest per particle: a distributed run
 * writes each owned row at its serial place, with the partners by global
 * id, so its checkpoint is the one-rank file (docs/restart.md).  A restart
 * on any rank count reads that file into the whole body, whose partition
 * keeps each owned row's pair state by partner gid (macro_par.c).
 */
#include "models/macroparticle/macro_internal.h"

#include "core/field_state.h"
#include "core/neighbor.h"
#include "core/particles.h"
#include "core/sim.h"
#include "spall/error.h"

#include <stdio.h>
#include <stdlib.h>

/* A pair array of @p rows entries of @p size bytes at *a (contents follow). */
static int pair_resize(void **a, size_t rows, size_t size, struct spall_error *err)
{
    void *g = realloc(*a, (rows ? rows : 1) * size);
    if (!g)
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory (macro-particle restart)");
    *a = g;
    return SPALL_OK;
}

static int set_idx(void *ctx, size_t rows, struct spall_error *err)
{
    struct model *m = ctx;
    macro_half_invalidate(m, NULL); /* the list is replaced */
    if (m->nl->offset[m->nl->n] != rows)
        return spall_error_set(err, SPALL_ERR_INPUT,
                               "macro-particle pair list: %zu pairs, its offsets say %zu", rows,
                               m->nl->offset[m->nl->n]);
    return pair_resize((void **)&m->nl->idx, rows, sizeof *m->nl->idx, err);
}

static int set_dr0(void *ctx, size_t rows, struct spall_error *err)
{
    ((struct model *)ctx)->pstate_read = true;
    return pair_resize((void **)&((struct model *)ctx)->dr0, rows, sizeof(double), err);
}

static int set_kappa(void *ctx, size_t rows, struct spall_error *err)
{
    ((struct model *)ctx)->pstate_read = true;
    return pair_resize((void **)&((struct model *)ctx)->kappa, rows, sizeof(double), err);
}

static int set_engaged(void *ctx, size_t rows, struct spall_error *err)
{
    ((struct model *)ctx)->pstate_read = true;
    return pair_resize((void **)&((struct model *)ctx)->engaged, rows, 1, err);
}

/* Distributed runs: the partners of the owned rows by global id (the
 * serial file's partner of a row is its index there, which is the gid). */
static int partner_gids(struct model *m, size_t n_owned, struct spall_error *err)
{
    const size_t ns = m->nl->offset[n_owned];
    int rc = pair_resize((void **)&m->ck_gid, ns, sizeof *m->ck_gid, err);
    for (size_t s = 0; s < ns && !rc; s++)
        m->ck_gid[s] = (int32_t)m->pgid[s];
    return rc;
}

int macro_register_state(struct model *m, struct sim *sim, struct field_state *fs,
                         struct spall_error *err)
{
    _Static_assert(sizeof(size_t) == 8 && sizeof(long) == 8, "counters are saved as int64");
    macro_half_epot_sync(m); /* the checkpoint saves epot */
    const size_t n = sim->p->n, no = sim->p->n_owned;
    if (!m->nl || m->nl->n != n || (sim->par && !m->pgid))
        return spall_error_set(err, SPALL_ERR_INTERNAL, "macro-particle list not built");
    /* the owned rows as a bond list: a distributed checkpoint writes each
     * row at its serial place (io/checkpoint_par.c), so the file is the
     * serial one whatever the rank count */
    m->ckbl = (struct bond_list){.n = no, .offset = m->nl->offset, .partner = m->nl->idx};
    void **partner = (void **)&m->nl->idx;
    int rc = SPALL_OK;
    if (sim->par) {
        rc = partner_gids(m, no, err);
        partner = (void **)&m->ck_gid;
    }
    if (!rc)
        rc = field_state_add_offsets(fs, "macro.list_offset", (void **)&m->nl->offset, &m->ckbl,
                                     err);
    if (!rc)
        rc = field_state_add_bond_list(fs, "macro.list_partner", FIELD_I32, partner, &m->ckbl,
                                       1, set_idx, m, err);
    if (!rc)
        rc = field_state_add_bond_list(fs, "macro.plastic_offset", FIELD_F64, (void **)&m->dr0,
                                       &m->ckbl, 1, set_dr0, m, err);
    if (!rc)
        rc = field_state_add_bond_list(fs, "macro.plastic_slip", FIELD_F64, (void **)&m->kappa,
                                       &m->ckbl, 1, set_kappa, m, err);
    if (!rc)
        rc = field_state_add_bond_list(fs, "macro.engaged", FIELD_U8, (void **)&m->engaged,
                                       &m->ckbl, 1, set_engaged, m, err);
    char nm[FIELD_STATE_NAME_LEN];
    for (int d = 0; d < sim->dim && !rc; d++) {
        snprintf(nm, sizeof nm, "macro.list_built_at.%d", d);
        rc = field_state_add_particle_array(fs, nm, FIELD_F64, (void **)&m->xb[d], no, 1, err);
    }
    if (!rc)
        rc = field_state_add_values(fs, "macro.force_calls", FIELD_I64, &m->n_calls, 1, err);
    if (!rc)
        rc = field_state_add_values(fs, "macro.list_builds", FIELD_I64, &m->n_builds, 1, err);
    /* energies and virial of the last force call (history, fields) */
    if (!rc)
        rc = field_state_add_particle_array(fs, "macro.epot", FIELD_F64, (void **)&m->epot, no,
                                            1, err);
    if (!rc)
        rc = field_state_add_particle_array(fs, "macro.virial", FIELD_F64, (void **)&m->sig, no,
                                            6, err);
    if (!rc)
        rc = field_state_add_particle_array(fs, "macro.dissipated", FIELD_F64,
                                            (void **)&m->wdiss, no, 1, err);
    return rc;
}
