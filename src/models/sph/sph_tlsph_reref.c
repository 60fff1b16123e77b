/**
 * @file sph_tlsph_reref.c
 * @brief Re-referencing of total-Lagrangian SPH (issue 6 items 6 and 8):
 *        model.reference_update {every: N, distortion: k}.
 *
 * Why: TLSPH (sph_tlsph.c) keeps its kernel, partners and corrected
 * gradients on one reference configuration.  A Taylor bar's foot flows to
 * plastic strains of ~3: the fixed partners of a particle end up spread
 * along the flow and squeezed across it, and the hourglass force (the
 * mismatch x_ij - Fbar X_ij against that old reference) resists the flow.
 * The remedy of Lagrangian codes with large deformation (MACHDYN's
 * *UPDATE_CONSTANT / *UPDATE_PAIRWISE) is to restart the reference from
 * the current configuration now and then.
 *
 * An update at the end of a step (all fields at t_n+1):
 *   X := x,  V0 := m / rho (current density),
 *   reference list, W0, dW/dr / r, hourglass constants and B0^-1 rebuilt
 *   on X with the same radius rule (qmax max h; pairs kept within their
 *   own support qmax (h_i + h_j)/2),
 * so F = I on the new reference (B0 B0^-1, to round-off) and the next
 * force call sees F relative to x_n+1.  Nothing of the material state
 * changes: the stress enters TLSPH only through the Cauchy state (S, P
 * from rho and e, ep), integrated with L = dF/dt F^-1 (the Jaumann rate),
 * not through F itself, so S, P, rho, e, ep and the velocities carry over
 * bitwise; PK1 = J sigma F^-T = sigma right after the update, and with V0
 * = m/rho the force V0_i V0_j (P_i g_i + P_j g_j) is the corrected
 * updated-form force of the current configuration.  Momentum stays
 * exact (the new list is symmetric, G_ij = -G_ji); kinetic + internal
 * energy is continuous across the update (nothing stored is reset: the
 * hourglass work was already booked as heat).  What is lost is only the
 * hourglass memory of the old reference.  p->x0 (output displacement,
 * groups, the guard's message) keeps the deck's positions; the reference
 * lives in the TLSPH block (sph_tlsph.c).
 *
 * h: fixed between updates, but an update grows it (x1.2, up to 4 rounds,
 * at most 2 h0) where the current neighbourhood has gone flat: the foot of
 * the copper Taylor bar at dx = 0.4 mm, stretched ~2x radially with the
 * initial support 2.01 dx0, re-referenced onto a vertical column of
 * partners (B0 singular, det F = 6e-4 one step later) without it
 * (docs/performance.md, "Re-referencing").
 *
 * Trigger: every N steps since the last update, and/or when the largest
 * distortion kappa = (|F|^2/dim)/J^(2/dim) of the last force call (the det F
 * guard's measure, history column max_F_distortion) exceeds k.  Every TLSPH
 * particle is re-referenced at once (the rebuild is one O(N) neighbour
 * search, cheap against the steps in between: docs/performance.md).
 */
#include "models/sph/sph_internal.h"

#include "core/neighbor.h"
#include "core/parallel/comm.h"
#include "core/parallel/spatial.h"
#include "core/particles.h"
#include "core/sim.h"
#include "core/options.h"
#include "spall/error.h"

#include <limits.h>
#include <math.h>
#include <omp.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

/* Isotropy of particle i's kernel neighbourhood on the current positions:
 * M = sum_j V_j |dW/dr / r| x_ij (x) x_ij (the uncorrected B0, = I inside a
 * regular lattice, I/2 at a flat surface), s = dim^dim det M / (tr M)^dim in
 * [0, 1]: 1 for any M proportional to I, 0 when the partners lie on a
 * plane or a line.  One pass: every TLSPH particle with s < @p smin gets
 * h *= 1.2 (at most twice its initial h); *grown counts them. */
static int reref_isotropy_pass(struct model *m, struct sim *s, double smin, size_t *grown,
                               struct spall_error *err)
{
    /* distributed: the owned particles' rows over every particle within the
     * radius (par_spatial_regather), in the serial order; serially nl = n */
    const struct particles *p = s->p;
    const size_t n = p->n_owned, nl_n = p->n;
    const int dim = m->dim;
    double hmax = 0.0;
    for (size_t i = 0; i < n; i++)
        hmax = fmax(hmax, m->h[i]);
    if (s->par)
        hmax = par_max_double(hmax);
    struct neighbor_list *nl = NULL;
    int rc = neighbor_list_build(&nl, dim, nl_n, p->x, m->qmax * hmax, err);
    uint8_t *grow = rc ? NULL : calloc(n ? n : 1, 1);
    if (!rc && (!grow || (s->par && sph_rows_by_gid(nl, n, nl_n, p->gid))))
        rc = spall_error_set(err, SPALL_ERR_NOMEM, "out of memory (TLSPH reference update)");
    if (rc) {
        free(grow);
        neighbor_list_destroy(&nl);
        return rc;
    }
    size_t count = 0;
#pragma omp parallel for schedule(static) reduction(+ : count)
    for (size_t i = 0; i < n; i++) {
        if (sph_skip(m, i, SPH_FORM_TOTAL) || !(m->h[i] < 2.0 * m->opt.kern.h_factor * m->dx[i]))
            continue;
        double M[9] = {0};
        for (size_t k = nl->offset[i]; k < nl->offset[i + 1]; k++) {
            const size_t j = (size_t)nl->idx[k];
            if (m->form && (m->form[j] != SPH_FORM_TOTAL || p->body[j] != p->body[i]))
                continue;
            const double hb = 0.5 * (m->h[i] + m->h[j]);
            double X[3] = {0, 0, 0}, r2 = 0.0;
            for (int d = 0; d < dim; d++) {
                X[d] = p->x[d][i] - p->x[d][j];
                r2 += X[d] * X[d];
            }
            if (!(r2 > 0.0) || r2 >= m->qmax * m->qmax * hb * hb)
                continue;
            double W, F;
            sph_kernel_eval(m->opt.kern.kernel, m->alpha, sqrt(r2), hb, pow(hb, dim), &W, &F);
            const double w = fabs(F) * m->m2[j] / m->rho[j];
            for (int a = 0; a < dim; a++)
                for (int b = 0; b < dim; b++)
                    M[a * 3 + b] += w * X[a] * X[b];
        }
        double inv[9], tr = 0.0;
        for (int a = 0; a < dim; a++)
            tr += M[a * 4];
        M[8] = dim == 2 ? 1.0 : M[8];
        const double det = sph_inverse(dim, M, inv);
        const double iso = tr > 0.0 ? (dim == 3 ? 27.0 * det / (tr * tr * tr) : 4.0 * det / (tr * tr))
                                    : 0.0;
        if (iso < smin) {
            grow[i] = 1;
            count++;
        }
    }
    for (size_t i = 0; i < n; i++)
        if (grow[i])
            m->h[i] = fmin(1.2 * m->h[i], 2.0 * m->opt.kern.h_factor * m->dx[i]);
    free(grow);
    neighbor_list_destroy(&nl);
    *grown = count;
    if (!s->par)
        return SPALL_OK;
    /* the whole body's count (every rank takes the same branch), and the
     * partners' grown h for the next pass */
    *grown = (size_t)par_sum_u64((uint64_t)count);
    double **hh[1] = {&m->h};
    return sph_par_halo_arrays(s, hh, 1, err);
}

/* Distributed: every particle within the radius of the coming list (qmax
 * times the largest h the isotropy passes can reach: at most twice the
 * initial one) of an owned particle's current position becomes a ghost,
 * with what the passes and the reference read of it (x, m, the density and
 * material are the engine's; h, dx, m2 the model's), and the model's
 * arrays are sized for them (docs/parallel.md, "Re-referencing on several
 * ranks").  TLSPH bodies behind an interface also keep every spatial
 * ghost, with the whole record of one (sph_spatial_ghosts), and their
 * current list and interface pairs are found again among them: the list
 * of the last build, from its build positions and smoothing lengths
 * (sph_spatial_rebuilt, not moved). */
static int reref_regather(struct model *m, struct sim *s, struct spall_error *err)
{
    const struct particles *p = s->p;
    const bool iso = m->opt.tl.reref_isotropy > 0.0;
    double hb = 0.0;
    for (size_t i = 0; i < p->n_owned; i++) {
        const double hg = 2.0 * m->opt.kern.h_factor * m->dx[i];
        hb = fmax(hb, iso && m->h[i] < hg ? hg : m->h[i]);
    }
    hb = par_max_double(hb);
    struct par_spatial_model sm;
    memset(&sm, 0, sizeof sm);
    const bool split = m->opt.tl.split_forms;
    if (split) {
        sph_spatial_ghosts(m, &sm);
    } else {
        double **a[] = {&m->h, &m->dx, &m->m2};
        for (int k = 0; k < 3; k++) {
            sm.particle[k] = (void **)a[k];
            sm.particle_size[k] = sizeof(double);
        }
        sm.n_particle = 3;
    }
    int rc = par_spatial_regather(s, m->qmax * hb, &sm, split, err);
    if (rc)
        return rc;
    if (split) /* collective (it agrees on its errors after) */
        return par_agree(sph_spatial_rebuilt(m, s, false, err), err);
    if (sph_resize_state(m, s->p->n))
        rc = spall_error_set(err, SPALL_ERR_NOMEM, "out of memory (SPH state, %zu particles)",
                             s->p->n);
    return par_agree(rc, err);
}

int sph_tlsph_reref(struct model *m, struct sim *s, struct spall_error *err)
{
    const double t0 = omp_get_wtime();
    int rc = s->par ? reref_regather(m, s, err) : SPALL_OK;
    if (rc)
        return rc;
    /* h grows where the current neighbourhood has gone flat (the foot of a
     * Taylor bar: stretched 2x radially, squeezed axially, so with the
     * initial h the in-plane partners leave the support and B0 turns
     * singular); a few passes of 1.2x, as MACHDYN grows the radius of
     * particles with too few partners */
    for (int round = 0; round < 4 && m->opt.tl.reref_isotropy > 0.0; round++) {
        size_t grown = 0;
        if ((rc = reref_isotropy_pass(m, s, m->opt.tl.reref_isotropy, &grown, err)))
            return rc;
        m->tl->hgrown += grown;
        if (!grown)
            break;
    }
    /* V0 = m / rho with the current (continuity) density: the same mass
     * over the volume the particle fills now */
    rc = sph_tlsph_reference(m, s, s->p->x, m->rho, err);
    if (rc)
        return rc;
    m->tl->rerefs++;
    m->tl->reref_step = s->step;
    m->tl->t_reref += omp_get_wtime() - t0;
    return SPALL_OK;
}

int sph_tlsph_reref_step(struct model *m, struct sim *s, struct spall_error *err)
{
    const struct sph_options *o = &m->opt;
    if (!m->tl || (!o->tl.reref_every && !(o->tl.reref_distortion > 0.0)))
        return SPALL_OK;
    const bool due = (o->tl.reref_every > 0 && s->step - m->tl->reref_step >= o->tl.reref_every) ||
                     (o->tl.reref_distortion > 0.0 && m->tl->kmax > o->tl.reref_distortion);
    return due ? sph_tlsph_reref(m, s, err) : SPALL_OK;
}
