/**
 * @file pd_restart.c
 * @brief Restart state of the peridynamics model: bond states and the
 *        energy they released, the mixed-mode history, the plastic
 *        extension state of formulation eps, the dilatation of the last
 *        force call of lps and eps (and P of the position-aware LPS), and
 *        the adaptive dynamic relaxation's previous forces and coefficient.  Families,
 *        reference lengths and micromodulus coefficients are rebuilt from
 *        the deck by init.
 */
#include "models/peridynamics/pd_internal.h"

#include "core/bond_list.h"
#include "core/field_state.h"
#include "core/particles.h"
#include "core/sim.h"
#include "spall/error.h"

#include <stdio.h>

_Static_assert(sizeof(bool) == 1, "the ADR flag is saved as one byte");

int pd_register_state(struct model *m, struct sim *sim, struct field_state *fs,
                      struct spall_error *err)
{
    size_t n = sim->p->n_owned;
    int rc = field_state_add_bond_array(fs, "pd.bond_state", FIELD_U8, (void **)&m->bl->state,
                                        m->bl, 1, err);
    if (!rc)
        rc = field_state_add_particle_array(fs, "pd.dissipated", FIELD_F64, (void **)&m->diss, n,
                                            1, err);
    /* matrix_crack: fiber_plane: per half-bond, by bond (any rank count) */
    if (!rc && m->fresh)
        rc = field_state_add_bond_array(fs, "pd.fresh", FIELD_U8, (void **)&m->fresh, m->bl, 1,
                                        err);
    if (!rc && m->mm_g)
        rc = field_state_add_particle_array(fs, "pd.mixed_g", FIELD_F64, (void **)&m->mm_g, n,
                                            1, err);
    if (!rc && m->mm_beta)
        rc = field_state_add_particle_array(fs, "pd.mixed_beta", FIELD_F64,
                                            (void **)&m->mm_beta, n, 1, err);
    if (!rc && m->lps.ep) /* formulation eps: the plastic extension state */
        rc = field_state_add_bond_array(fs, "pd.eps_plastic", FIELD_F64, (void **)&m->lps.ep,
                                        m->bl, 1, err);
    /* The dilatation of the last force call prices a half-bond that breaks
     * in the first call after a restart (break_order immediate: its t e / 2
     * at the theta before the call, lps_row_settle of pd_lps_kernel.c; eps
     * the same, the rest of eps' per-call state hs is rewritten by pass 1
     * before it is read).  Default lps and eps: theta; position_aware: theta
     * and P (pd_lps_pals.c), its own pair. */
    if (!rc && m->lps.pp)
        rc = field_state_add_particle_array(fs, "pd.pals_theta_p", FIELD_F64,
                                            (void **)&m->lps.pp, n, 2, err);
    else if (!rc && m->opt.lps)
        rc = field_state_add_particle_array(fs, "pd.lps_theta", FIELD_F64,
                                            (void **)&m->lps.theta, n, 1, err);
    char nm[FIELD_STATE_NAME_LEN];
    for (int d = 0; d < sim->dim && !rc; d++)
        if (m->f_prev[d]) { /* ADR: this step's and the previous step's forces */
            snprintf(nm, sizeof nm, "pd.adr_forces.%d", d);
            rc = field_state_add_particle_array(fs, nm, FIELD_F64, (void **)&m->f_prev[d], n, 2,
                                                err);
        }
    if (!rc)
        rc = field_state_add_values(fs, "pd.adr_damping", FIELD_F64, &m->adr_damping, 1, err);
    if (!rc)
        rc = field_state_add_values(fs, "pd.adr_estimated", FIELD_U8, &m->adr_estimated, 1, err);
    return rc;
}
