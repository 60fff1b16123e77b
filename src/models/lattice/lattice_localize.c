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

int lattice_localize(struct model *m, struct sim *sim, const size_t *keep, size_t n_keep,
                     size_t n_owned, const int64_t *new_of_old, struct spall_error *err)
{
    (void)sim;
    if (m->angular) /* angles centred on ghosts would need ghosts of ghosts */
        return spall_error_set(err, SPALL_ERR_INPUT,
                               "distributed runs: the lattice model's angular springs are not "
                               "distributed yet; run on one rank (without mpirun), see "
                               "docs/parallel.md");
    if (!keep) /* only asked whether it can */
        return SPALL_OK;
    size_t *oh = NULL, nh = 0;
    int rc = bond_list_localize(m->bl, keep, n_keep, n_owned, new_of_old, &oh, &nh, err);
    if (rc)
        return rc;
    double *kappa = m->kappa ? array_gather(m->kappa, sizeof *kappa, oh, nh) : NULL;
    double *diss = array_gather(m->diss, sizeof *diss, keep, n_keep);
    /* thermal lattice: temperatures of owned and ghosts (the halo refreshes
     * the ghosts' each conduction sub-step, lattice_thermal.c) */
    rc = lattice_thermal_localize(m, keep, n_keep, oh, nh, err);
    free(oh);
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
    return SPALL_OK;
}

/* model_ops.migrate_arrays: the bond rows, the dissipated energy per
 * particle and the softening history per half-bond travel with a particle.
 * The thermal lattice keeps per-particle and per-bond state whose owners
 * (th->n, m->kscale) a moved array would leave behind: refused. */
int lattice_migrate_arrays(struct model *m, struct par_model_arrays *a, struct spall_error *err)
{
    if (lattice_thermal_enabled(m))
        return spall_error_set_key(err, SPALL_ERR_INPUT, "parallel.rebalance_every",
                                   "distributed runs: the thermal lattice cannot migrate "
                                   "particles yet; leave parallel.rebalance_every at 0");
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
    return SPALL_OK;
}
