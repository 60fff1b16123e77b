/**
 * @file sph_as_smooth.c
 * @brief Kernel-averaged artificial stress (model.artificial_stress_smoothing):
 *        R_i replaced by sum_j V_j R_j W_ij / sum_j V_j W_ij over i and its
 *        neighbours before the force pass.
 *
 * Why: the Monaghan-Gray artificial stress ([Meng2021] Eqs. 2.23-2.26) takes
 * R_i from particle i's own stress.  Monaghan's stability analysis treats
 * R as the constant stress of a pre-stressed state; but R_i, recomputed
 * every step, also follows the particle-scale stress of the near-zero-energy
 * modes of the SPH gradient (the checkerboard-like modes the velocity
 * gradient hardly sees).  Linearised, the force operator becomes
 * S_in (S_in - zeta S_f): S_in the gradient's Fourier symbol, S_f that of the
 * narrow f^n grad W kernel.  Where S_in nearly vanishes and S_f does not,
 * the product is negative: exponential growth at a rate independent of the
 * load (R is homogeneous of degree one in the stress) and of the time step.
 * Measured on the [Meng2021] cantilever (docs/validation.md, sph-beam): with
 * AS 0.5 and no AV every kernel grows from t = 0 (identical growth at 17.5 N
 * and 1.75 kN, and at dt_factor 0.5 and 0.2), none does without AS, and
 * neither the quintic nor the Wendland does with R smoothed here (the
 * others not measured without AV); with AV and XSPH the quintic blows up
 * at 1.75 kN, at 17.5 kN (AS 0.9) every kernel.  The kernel average keeps
 * R of the macroscopic stress, which is what the pre-stress analysis
 * assumes, and removes its response to particle-scale noise.
 *
 * Shepard normalisation: a uniform R stays exact at surfaces.  Gather over
 * the full neighbour list of i in list order: bitwise independent of the
 * thread count.  Not in [Meng2021] (an option, default off).
 */
#include "models/sph/sph_internal.h"
#include "models/sph/sph_pairs.h"

#include "core/neighbor.h"
#include "core/particles.h"
#include "core/sim.h"

#include <math.h>
#include <string.h>

void sph_artificial_stress_smooth(struct model *m, const struct sim *s)
{
    const struct particles *p = s->p;
    const size_t n = p->n_owned;
    const size_t *off = m->nl->offset;
    const int32_t *nb = m->nl->idx;
    const enum sph_kernel kern = m->opt.kern.kernel;
    const struct sph_support sp = sph_support_of(m);
    const int dim = m->dim;
    const double alpha = m->alpha;
#pragma omp parallel for schedule(static) firstprivate(sp)
    for (size_t i = 0; i < n; i++) {
        const double hi = m->h[i];
        double W0, F0;
        sph_kernel_eval(kern, alpha, 0.0, hi, dim == 2 ? hi * hi : hi * hi * hi, &W0, &F0);
        double w = m->m2[i] / m->rho[i] * W0, ws = w;
        double acc[6];
        for (int c = 0; c < 6; c++)
            acc[c] = w * m->R[c][i];
        for (size_t k = off[i]; k < off[i + 1]; k++) {
            const size_t j = (size_t)nb[k];
            double W, F;
            if (!sph_pair_kernel(&sp, dim, sph_dist2(p->x, dim, i, j), 0.5 * (hi + m->h[j]), &W,
                                 &F))
                continue;
            w = m->m2[j] / m->rho[j] * W;
            ws += w;
            for (int c = 0; c < 6; c++)
                acc[c] += w * m->R[c][j];
        }
        for (int c = 0; c < 6; c++)
            m->Rs[c][i] = acc[c] / ws;
    }
    for (int c = 0; c < 6; c++)
        memcpy(m->R[c], m->Rs[c], n * sizeof(double));
}
