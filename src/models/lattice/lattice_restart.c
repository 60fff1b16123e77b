/**
 * @file lattice_restart.c
 * @brief Restart state of the lattice model: what breaks, softens and
 *        dissipates during a run.  The bonds, angles and their reference
 *        lengths and angles are rebuilt from the deck by init and the
 *        pre-cracks; only their evolving state is saved (the rest lengths
 *        only where thermal expansion moves them).
 */
#include "models/lattice/lattice_internal.h"

#include "core/bond_list.h"
#include "core/field_state.h"
#include "core/particles.h"
#include "core/sim.h"
#include "models/lattice/lattice_thermal.h"
#include "spall/error.h"

int lattice_register_state(struct model *m, struct sim *sim, struct field_state *fs,
                           struct spall_error *err)
{
    struct bond_list *bl = m->bl;
    int rc = field_state_add_bond_array(fs, "lattice.bond_state", FIELD_U8, (void **)&bl->state,
                                        bl, 1, err);
    /* thermal expansion moves the rest lengths; otherwise they are stored
     * compacted (bond_list_compact_rest), never change and init rebuilds
     * them */
    if (!rc && bl->rest)
        rc = field_state_add_bond_array(fs, "lattice.bond_rest", FIELD_F64, (void **)&bl->rest,
                                        bl, 1, err);
    if (!rc && m->angular) /* one per half-bond: the angle that starts at it */
        rc = field_state_add_bond_array(fs, "lattice.angle_state", FIELD_U8,
                                        (void **)&m->ang_state, bl, 1, err);
    if (!rc && m->kappa) /* one per half-bond (m->n_half == the rows of bl) */
        rc = field_state_add_bond_array(fs, "lattice.softening_kappa", FIELD_F64,
                                        (void **)&m->kappa, bl, 1, err);
    if (!rc)
        rc = field_state_add_particle_array(fs, "lattice.dissipated", FIELD_F64,
                                            (void **)&m->diss, sim->p->n_owned, 1, err);
    if (!rc)
        rc = lattice_thermal_register_state(m, sim->p->n_owned, fs, err);
    return rc;
}
