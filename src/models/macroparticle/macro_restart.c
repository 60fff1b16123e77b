/**
 * @file macro_restart.c
 * @brief Restart state of the macro-particle model: the Verlet list with
 *        the positions it was built at (a rebuild changes the pair order,
 *        hence the round-off), the per-pair plastic offsets and slips, the
 *        random-stream counter of the Langevin forces ([Salmon2011]: the
 *        noise is a function of (seed, call, pair), so the counter is all
 *        the generator's state) and the energy accumulators.
 */
#include "models/macroparticle/macro_internal.h"

#include "core/field_state.h"
#include "core/neighbor.h"
#include "core/particles.h"
#include "core/sim.h"
#include "spall/error.h"

#include <stdio.h>
#include <stdlib.h>

static size_t pair_rows(const void *ctx)
{
    const struct model *m = ctx;
    return m->nl ? m->nl->offset[m->nl->n] : 0;
}

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
    m->half_ok = false; /* the list is replaced */
    if (m->nl->offset[m->nl->n] != rows)
        return spall_error_set(err, SPALL_ERR_INPUT,
                               "macro-particle pair list: %zu pairs, its offsets say %zu", rows,
                               m->nl->offset[m->nl->n]);
    return pair_resize((void **)&m->nl->idx, rows, sizeof *m->nl->idx, err);
}

static int set_dr0(void *ctx, size_t rows, struct spall_error *err)
{
    return pair_resize((void **)&((struct model *)ctx)->dr0, rows, sizeof(double), err);
}

static int set_kappa(void *ctx, size_t rows, struct spall_error *err)
{
    return pair_resize((void **)&((struct model *)ctx)->kappa, rows, sizeof(double), err);
}

static int set_engaged(void *ctx, size_t rows, struct spall_error *err)
{
    return pair_resize((void **)&((struct model *)ctx)->engaged, rows, 1, err);
}

int macro_register_state(struct model *m, struct sim *sim, struct field_state *fs,
                         struct spall_error *err)
{
    _Static_assert(sizeof(size_t) == 8 && sizeof(long) == 8, "counters are saved as int64");
    size_t n = sim->p->n;
    if (sim->par) /* a signal's checkpoint; a deck's checkpoints are refused before the run */
        return spall_error_set(err, SPALL_ERR_INPUT,
                               "distributed runs: the macro-particle pair lists cannot be "
                               "checkpointed across ranks yet; run on one rank (without mpirun) "
                               "to checkpoint, see docs/parallel.md");
    if (!m->nl || m->nl->n != n || sim->p->n != sim->p->n_owned)
        return spall_error_set(err, SPALL_ERR_INTERNAL, "macro-particle list not built");
    int rc = field_state_add_array(fs, "macro.list_offset", FIELD_I64, (void **)&m->nl->offset,
                                   n + 1, 1, err);
    if (!rc)
        rc = field_state_add_list(fs, "macro.list_partner", FIELD_I32, (void **)&m->nl->idx, 1,
                                  pair_rows, set_idx, m, err);
    if (!rc)
        rc = field_state_add_list(fs, "macro.plastic_offset", FIELD_F64, (void **)&m->dr0, 1,
                                  pair_rows, set_dr0, m, err);
    if (!rc)
        rc = field_state_add_list(fs, "macro.plastic_slip", FIELD_F64, (void **)&m->kappa, 1,
                                  pair_rows, set_kappa, m, err);
    if (!rc)
        rc = field_state_add_list(fs, "macro.engaged", FIELD_U8, (void **)&m->engaged, 1,
                                  pair_rows, set_engaged, m, err);
    char nm[FIELD_STATE_NAME_LEN];
    for (int d = 0; d < sim->dim && !rc; d++) {
        snprintf(nm, sizeof nm, "macro.list_built_at.%d", d);
        rc = field_state_add_array(fs, nm, FIELD_F64, (void **)&m->xb[d], n, 1, err);
    }
    if (!rc)
        rc = field_state_add_values(fs, "macro.force_calls", FIELD_I64, &m->n_calls, 1, err);
    if (!rc)
        rc = field_state_add_values(fs, "macro.list_builds", FIELD_I64, &m->n_builds, 1, err);
    /* energies and virial of the last force call (history, fields) */
    if (!rc)
        rc = field_state_add_array(fs, "macro.epot", FIELD_F64, (void **)&m->epot, n, 1, err);
    if (!rc)
        rc = field_state_add_array(fs, "macro.virial", FIELD_F64, (void **)&m->sig, n, 6, err);
    if (!rc)
        rc = field_state_add_array(fs, "macro.dissipated", FIELD_F64, (void **)&m->wdiss, n, 1,
                                   err);
    return rc;
}
