/**
 * @file step.c
 * @brief The integrator's per-step checks on a distributed run (step.h).
 *        The energy account's sums need nothing here: they are exact
 *        (core/exact_sum.h) and complete with one collective (psum.h).
 */
#include "core/parallel/step.h"

#include "core/exact_sum.h"
#include "core/parallel/comm.h"
#include "core/parallel/psum.h"
#include "core/particles.h"
#include "core/sim.h"
#include "core/step_passes.h"

#include <math.h>

int par_check_finite(const struct sim *s, int64_t *bad_gid, double *kinetic)
{
    /* the serial check (integrator.c, check_finite): per component the sum
     * of m v^2, a NaN or Inf in v makes it non-finite; only then, the first
     * particle (by gid) with a non-finite v or x in that component.  Each
     * rank's local sum (four interleaved lanes, step_block_mv2, vectorised
     * as the serial check's blocks) enters an exact accumulator, so the one
     * collective hands every rank the same totals and all take the same
     * branch.  The total's last bits depend on the partition either way;
     * only the blow-up pre-test (check_energy) reads it. */
    const struct particles *p = s->p;
    struct xsum acc[3];
    double tot[3] = {0.0, 0.0, 0.0};
    for (int d = 0; d < s->dim; d++) {
        xsum_init(&acc[d]);
        xsum_add(&acc[d], step_block_mv2(p->mass, p->v[d], 0, p->n_owned));
    }
    par_xsum_finish(s, acc, (size_t)s->dim, tot);
    *kinetic = 0.0;
    for (int d = 0; d < s->dim; d++) {
        *kinetic += 0.5 * tot[d];
        if (isfinite(tot[d]))
            continue;
        int64_t bad = INT64_MAX; /* owned particles are in ascending gid */
        for (size_t i = 0; i < p->n_owned && bad == INT64_MAX; i++)
            if (!isfinite(p->v[d][i]) || !isfinite(p->x[d][i]))
                bad = p->gid[i];
        bad = par_min_i64(bad); /* collective: every rank is in this branch */
        if (bad != INT64_MAX) {
            *bad_gid = bad;
            return 1;
        }
    }
    return 0;
}

int64_t par_fastest_gid(const struct sim *s)
{
    const struct particles *p = s->p;
    double vmax = -1.0;
    int64_t best = INT64_MAX;
    for (size_t i = 0; i < p->n_owned; i++) {
        double v2 = 0.0;
        for (int d = 0; d < s->dim; d++)
            v2 += p->v[d][i] * p->v[d][i];
        if (isnan(v2))
            v2 = INFINITY; /* the serial scan stops at the first NaN */
        if (v2 > vmax || (v2 == vmax && p->gid[i] < best)) {
            vmax = v2;
            best = p->gid[i];
        }
    }
    double gmax = par_max_double(vmax);
    return par_min_i64(vmax == gmax ? best : INT64_MAX);
}
