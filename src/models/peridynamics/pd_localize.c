/**
 * @file pd_localize.c
 * @brief model_ops.localize of the peridynamic model (distributed runs,
 *        core/parallel/decomp.h).  The bond-based kernel (PMB, PDLM) gathers over each owned
 *        particle's family; families keep their serial order (ascending
 *        partner gid) with the partners renumbered to local indices, so
 *        each force sum is the serial one bit for bit; a bond's two halves
 *        decide breaking from the same bitwise-symmetric stretch.
 */
#include "models/peridynamics/pd_internal.h"

#include "core/bond_list.h"
#include "core/model.h"
#include "core/parallel/decomp.h"
#include "core/particles.h"
#include "core/sim.h"
#include "spall/error.h"

#include <stdlib.h>

int pd_localize(struct model *m, struct sim *sim, const size_t *keep, size_t n_keep,
                size_t n_owned, const int64_t *new_of_old, struct spall_error *err)
{
    (void)sim;
    const char *what = m->opt.lps                  ? "formulation lps is"
                       : m->opt.quasi == PD_QS_ADR ? "quasi-static adr is"
                       : m->ortho || m->mixed      ? "laminae (orthotropic materials) are"
                       : m->fresh || m->twin       ? "matrix_crack: fiber_plane is"
                                                   : NULL;
    if (what)
        return spall_error_set(err, SPALL_ERR_INPUT,
                               "distributed runs: peridynamics' %s not distributed yet; run on "
                               "one rank (without mpirun), see docs/parallel.md",
                               what);
    if (!keep) /* only asked whether it can */
        return SPALL_OK;
    size_t *oh = NULL, nh = 0;
    int rc = bond_list_localize(m->bl, keep, n_keep, n_owned, new_of_old, &oh, &nh, err);
    if (rc)
        return rc;
    double *coef = array_gather(m->coef, sizeof *coef, oh, nh);
    size_t *n_init = array_gather(m->n_init, sizeof *n_init, keep, n_keep);
    size_t *n_init_f = array_gather(m->n_init_f, sizeof *n_init_f, keep, n_keep);
    double *diss = array_gather(m->diss, sizeof *diss, keep, n_keep);
    free(oh);
    if (!coef || !n_init || !n_init_f || !diss) {
        free(coef);
        free(n_init);
        free(n_init_f);
        free(diss);
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory localising bonds");
    }
    free(m->coef);
    m->coef = coef;
    free(m->n_init);
    m->n_init = n_init;
    free(m->n_init_f);
    m->n_init_f = n_init_f;
    free(m->diss);
    m->diss = diss;
    m->n_half = nh;
    return SPALL_OK;
}
