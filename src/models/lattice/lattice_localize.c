/**
 * @file lattice_localize.c
 * @brief model_ops.localize of the lattice model (distributed runs,
 *        core/parallel/decomp.h): keep the bond rows of the rank's owned
 *        particles, partners renumbered to local indices, in their serial
 *        order (ascending partner gid), so every owned particle's force sum
 *        is the serial one bit for bit.  Ghost rows are emptied: a ghost's
 *        force is its owner's business.  Each half-bond decides its own
 *        breaking from |x_j - x_i| and the rest length, which are bitwise
 *        symmetric (lattice_forces.c), so the two halves of a bond that
 *        crosses ranks break in the same step without any message.
 */
#include "models/lattice/lattice_internal.h"

#include "core/bond_list.h"
#include "models/lattice/lattice_thermal.h"
#include "core/model.h"
#include "core/parallel/decomp.h"
#include "core/parallel/migrate.h"
#include "core/particles.h"
#include "core/sim.h"
#include "spall/error.h"

#include <stdlib.h>
#include <string.h>

/* Angular springs: per half-bond the angle that starts at it (its second
 * arm's place in the row, reference angle, state) and the force buffer.
 * The buffer holds 4 doubles per local half-bond: 2 for the slot's own
 * value and room for the 2 of a reverse half received from another rank
 * (at most one per local half-bond; lattice_compute_forces). */
static int angles_localize(struct model *m, const struct bond_rows *rows,
                           struct spall_error *err)
{
    const size_t nh = rows->n_half;
    uint8_t *b = bond_rows_gather(rows, m->ang_b, sizeof *b);
    double *phi0 = bond_rows_gather(rows, m->ang_phi0, sizeof *phi0);
    uint8_t *st = bond_rows_gather(rows, m->ang_state, sizeof *st);
    double *buf = calloc(4 * (nh ? nh : 1), sizeof *buf);
    if (!b || !phi0 || !st || !buf) {
        free(b);
        free(phi0);
        free(st);
        free(buf);
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory localising angular springs");
    }
    free(m->ang_b);
    m->ang_b = b;
    free(m->ang_phi0);
    m->ang_phi0 = phi0;
    free(m->ang_state);
    m->ang_state = st;
    free(m->ang_buf);
    m->ang_buf = buf;
    return SPALL_OK;
}

int lattice_localize(struct model *m, struct sim *sim, const size_t *keep, size_t n_keep,
                     size_t n_owned, const int64_t *new_of_old, struct spall_error *err)
{
    (void)sim;
    if (!keep) /* only asked whether it can */
        return SPALL_OK;
    struct bond_rows rows;
    int rc = bond_list_localize(m->bl, keep, n_keep, n_owned, new_of_old, &rows, err);
    if (rc)
        return rc;
    const size_t nh = rows.n_half;
    double *kappa = m->kappa ? bond_rows_gather(&rows, m->kappa, sizeof *kappa) : NULL;
    double *diss = array_gather(m->diss, sizeof *diss, keep, n_keep);
    /* thermal lattice: temperatures of owned and ghosts (the halo refreshes
     * the ghosts' each conduction sub-step, lattice_thermal.c) */
    rc = lattice_thermal_localize(m, keep, n_keep, &rows, err);
    if (!rc && m->ang_b)
        rc = angles_localize(m, &rows, err);
    bond_rows_free(&rows);
    if (rc || (m->kappa && !kappa) || !diss) {
        free(kappa);
        free(diss);
        return rc ? rc : spall_error_set(err, SPALL_ERR_NOMEM, "out of memory localising bonds");
    }
    free(m->kappa);
    m->kappa = kappa;
    free(m->diss);
    m->diss = diss;
    m->n_half = nh;
    m->half_known = false; /* the rows changed (also caught by bl->gen) */
    return SPALL_OK;
}

/* model_ops.migrate_arrays: the bond rows, the dissipated energy per
 * particle and the softening history per half-bond travel with a particle;
 * the thermal lattice's heating, heat capacity, conductances, reference
 * rest lengths and E(T) factors too (lattice_thermal.c, whose caches of
 * them lattice_migrated renews).  Angular springs: each half-bond's angle
 * (second arm, reference angle, state). */
int lattice_migrate_arrays(struct model *m, struct par_model_arrays *a, struct spall_error *err)
{
    (void)err;
    a->bl = m->bl;
    a->n_half = &m->n_half;
    a->n_particle = 1;
    a->particle[0] = (void **)&m->diss;
    a->particle_size[0] = sizeof *m->diss;
    a->n_bond = 0;
    if (m->kappa) {
        a->bond[a->n_bond] = (void **)&m->kappa;
        a->bond_size[a->n_bond++] = sizeof *m->kappa;
    }
    if (m->ang_b) { /* angles: their half-bond's state; the buffer (4 doubles, scratch) */
        void **arr[4] = {(void **)&m->ang_b, (void **)&m->ang_phi0, (void **)&m->ang_state,
                         (void **)&m->ang_buf};
        const size_t sz[4] = {sizeof *m->ang_b, sizeof *m->ang_phi0, sizeof *m->ang_state,
                              4 * sizeof *m->ang_buf};
        for (int k = 0; k < 4; k++) {
            a->bond[a->n_bond] = arr[k];
            a->bond_size[a->n_bond++] = sz[k];
        }
    }
    lattice_thermal_migrate_arrays(m, a);
    return SPALL_OK;
}

/* model_ops.migrated: the thermal lattice's particle count and E(T) view */
int lattice_migrated(struct model *m, struct sim *sim, struct spall_error *err)
{
    (void)err;
    lattice_thermal_migrated(m, sim->p->n);
    return SPALL_OK;
}
