/**
 * @file macro_forces.c
 * @brief Macro-particle forces: Mie pairs over a cut-off ([Saitoh] Eqs. 2-5,
 *        13, written in the consistent form of spec/macroparticle.md), pair
 *        plasticity (Eq. 16), Langevin dissipation and random forces
 *        (Eqs. 6-9, 17-22), and the Verlet neighbour list with a skin.
 *
 * Neighbours: a full cell-list list (core/neighbor.h) of radius r_c + skin,
 * rebuilt when some particle moved more than skin/2 since the last build
 * (then no pair can have crossed r_c unseen).  Macro-particles may slip and
 * meet new partners; a pair's plastic state lives in per-slot arrays and is
 * carried to the new list by merging the old and new partner lists of each
 * particle, both sorted by the partner's global id (on one rank the index;
 * on a distributed run the rows are sorted by gid, so every particle sums
 * its partners in the serial order, docs/parallel.md).
 * A pair that leaves the list (r > r_c + skin) forgets its plastic offset.
 *
 * Each particle sums over its full list in list order and writes only its
 * own force, energy and state: no atomics, and the result is bitwise
 * independent of the thread count.  The default loop (macro_half.c)
 * evaluates each pair once and hands both ends the same numbers; the
 * reference loop here (deck pair_loop: full) evaluates it from both ends
 * (the two slots of a pair evolve identically).
 *
 * Plasticity (Eq. 16 leaves the route open; our choice): the elastic stretch
 * of a pair is e = r - r0 - dr0.  While |e| <= e_y + h kappa the pair is
 * elastic on the shifted branch phi_E(r - dr0) (= phi_U, the constant C_phi
 * does not change forces).  Past it the excess is converted into slip:
 * d = (|e| - e_y - h kappa)/(1 + h), dr0 += sign(e) d, kappa += d, so the
 * plastic route has tangent stiffness t = h/(1+h) of the elastic one at the
 * yield point (linear isotropic hardening of the pair) and unloading
 * follows the elastic branch shifted by dr0.  The same yield stretch acts in
 * compression.  Plastic work F d is booked as dissipated energy.
 *
 * Langevin forces: absolute F = -gamma v + sigma xi with sigma =
 * eta_CG sqrt(2 gamma k_B T / dt) (Eq. 17-22) or pairwise F_ij = mu (v_j -
 * v_i) + sigma_p xi_ij, xi_ij = -xi_ji (both ends draw the same numbers from
 * the key (min gid, max gid) and apply them with opposite signs).  The
 * forces use the velocities the integrator hands to the force call (the
 * half-step ones with velocity Verlet).
 */
#include "models/macroparticle/macro_internal.h"

#include "core/neighbor.h"
#include "core/particles.h"
#include "core/sim.h"
#include "core/step_passes.h"
#include "spall/error.h"

#include <stdlib.h>
#include <string.h>
#ifdef _OPENMP
#include <omp.h>
#endif

static void macro_forces_full(struct model *m, struct sim *sim);

/* The partner's global id of slot @p s: the slot's key when the list keeps
 * them (distributed runs), else the index (one rank: index = gid). */
static inline int64_t slot_gid(const struct neighbor_list *nl, const int64_t *pg, size_t s)
{
    return pg ? pg[s] : (int64_t)nl->idx[s];
}

/** Move the per-slot plastic state from list @p old to list @p nw, for the
 *  rows [0, rows) (the same particles in both: owned particles keep their
 *  index between re-layouts).  Both lists' rows ascend in the partner's
 *  global id, which identifies the pair across rebuilds and re-layouts. */
static void carry_state(const struct neighbor_list *old, const int64_t *opg, const double *odr,
                        const double *oka, const uint8_t *oen, const struct neighbor_list *nw,
                        const int64_t *npg, size_t rows, double *ndr, double *nka, uint8_t *nen)
{
#pragma omp parallel for schedule(static) if (rows >= MACRO_OMP_MIN)
    for (size_t i = 0; i < rows; i++) {
        size_t a = old->offset[i], ae = old->offset[i + 1];
        for (size_t s = nw->offset[i]; s < nw->offset[i + 1]; s++) {
            const int64_t j = slot_gid(nw, npg, s);
            while (a < ae && slot_gid(old, opg, a) < j)
                a++;
            if (a < ae && slot_gid(old, opg, a) == j) {
                ndr[s] = odr[a];
                nka[s] = oka[a];
                nen[s] = oen[a];
            }
        }
    }
}

/* Row i ascending in the partners' global ids (distributed runs: ghosts
 * follow the owned particles locally; on one rank index = gid already).
 * The local layout holds the owned particles [0, n_own) and then the
 * ghosts, each in ascending gid (core/parallel/decomp.h), and a row
 * ascends in local index: an owned run and a ghost run, each ascending in
 * gid, so the row is in order already when one run is empty or the first
 * ghost's gid exceeds the last owned one's (all rows but a few near the
 * rank's boundary).  The others: insertion sort (rows are short, 12
 * partners in the first FCC shell). */
static void sort_rows_by_gid(struct neighbor_list *nl, const int64_t *gid, size_t n_own)
{
    const size_t n = nl->n;
#pragma omp parallel for schedule(static) if (n >= MACRO_OMP_MIN)
    for (size_t i = 0; i < n; i++) {
        int32_t *r = nl->idx + nl->offset[i];
        const size_t len = nl->offset[i + 1] - nl->offset[i];
        if (len < 2 || (size_t)r[len - 1] < n_own || (size_t)r[0] >= n_own)
            continue; /* one run */
        size_t lo = 1, hi = len - 1; /* the first ghost: r[lo - 1] owned, r[hi] a ghost */
        while (lo < hi) {
            const size_t mid = lo + (hi - lo) / 2;
            if ((size_t)r[mid] < n_own)
                lo = mid + 1;
            else
                hi = mid;
        }
        if (gid[r[lo - 1]] < gid[r[lo]])
            continue; /* the runs in order */
        for (size_t k = 1; k < len; k++) {
            int32_t v = r[k];
            size_t q = k;
            while (q > 0 && gid[r[q - 1]] > gid[v]) {
                r[q] = r[q - 1];
                q--;
            }
            r[q] = v;
        }
    }
}

int macro_list_build(struct model *m, struct sim *sim, bool count, struct spall_error *err)
{
    struct particles *p = sim->p;
    const size_t n = p->n;
    const double skin = m->skin_ratio * m->pp.r0;
    /* one rank: from the current positions; distributed: from the build
     * positions the engine set (core/parallel/spatial.c) */
    const bool dist = sim->par != NULL;
    struct neighbor_list *nl = NULL;
    struct neighbor_pairs *pairs = NULL;
    if (!dist && !m->pair_full && !(pairs = malloc(sizeof *pairs)))
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory for macro-particle pairs");
    /* one rank: the pair loop's table comes with the list (macro_half.c) */
    int rc = neighbor_list_build_pairs(&nl, pairs, sim->dim, n, dist ? m->xb : p->x,
                                       m->pp.r_c + skin, err);
    if (rc) {
        free(pairs);
        return rc;
    }
    if (dist)
        sort_rows_by_gid(nl, p->gid, p->n_owned);
    size_t ns = nl->offset[n];
    double *ndr = calloc(ns ? ns : 1, sizeof *ndr), *nka = calloc(ns ? ns : 1, sizeof *nka);
    uint8_t *nen = calloc(ns ? ns : 1, 1);
    int64_t *npg = dist ? malloc((ns ? ns : 1) * sizeof *npg) : NULL;
    if (!ndr || !nka || !nen || (dist && !npg)) {
        free(ndr);
        free(nka);
        free(nen);
        free(npg);
        neighbor_pairs_free(pairs);
        free(pairs);
        neighbor_list_destroy(&nl);
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory for macro-particle pairs");
    }
    for (size_t s = 0; s < ns && npg; s++)
        npg[s] = p->gid[nl->idx[s]];
    /* an elastic run never writes the plastic state: all zeros, as calloc
     * made the new arrays */
    if (m->nl && (isfinite(m->pp.e_y) || m->pstate_read)) {
        size_t rows = p->n_owned < m->nl->n ? p->n_owned : m->nl->n;
        carry_state(m->nl, m->pgid, m->dr0, m->kappa, m->engaged, nl, npg, rows, ndr, nka, nen);
    }
    macro_adopt_pairs(m, nl, npg, ndr, nka, nen);
    macro_half_invalidate(m, pairs);
    if (!dist)
        for (int d = 0; d < sim->dim; d++)
            memcpy(m->xb[d], p->x[d], n * sizeof(double));
    if (count)
        m->n_builds++;
    return SPALL_OK;
}

void macro_adopt_pairs(struct model *m, struct neighbor_list *nl, int64_t *pgid, double *dr0,
                       double *kappa, uint8_t *engaged)
{
    macro_par_release(m); /* a list lent to a migration probe is not kept */
    macro_half_epot_sync(m); /* from the old list's pair values */
    macro_half_invalidate(m, NULL);
    neighbor_list_destroy(&m->nl);
    free(m->pgid);
    free(m->dr0);
    free(m->kappa);
    free(m->engaged);
    m->nl = nl;
    m->pgid = pgid;
    m->dr0 = dr0;
    m->kappa = kappa;
    m->engaged = engaged;
}

int macro_neighbors_update(struct model *m, struct sim *sim, bool force, struct spall_error *err)
{
    struct particles *p = sim->p;
    const size_t n = p->n;
    const double skin = m->skin_ratio * m->pp.r0;
    if (!force && sim->par)
        return SPALL_OK; /* distributed: the engine's test, over all ranks (spatial.c) */
    if (!force && m->nl && m->nl->n == n &&
        4.0 * step_max_shift2(sim->dim, n, p->x, m->xb) < skin * skin)
        return SPALL_OK;
    return macro_list_build(m, sim, true, err);
}

/* The reference pair loop (macro_forces_full) runs over each particle's list in
 * chunks of MACRO_CHUNK slots, in passes: the geometry (gathers, r^2, sqrt)
 * and the pair law (macro_mie_chunk: divisions and powers; c = -f/r; the
 * force and virial terms) with no dependence between slots, which the
 * compiler vectorises; between them,
 * when plasticity or pairwise damping is on, a scalar pass over the slots
 * in list order updates the plastic state and adds the pairwise Langevin
 * forces; last, a scalar pass adds energy, force and virial terms in list
 * order.
 * Every operation and the order of every sum are those of the one-pass
 * loop (a slot's values are computed exactly as there), so the results do
 * not change, bit for bit.  The kernels are cloned (MACRO_CLONES,
 * macro_internal.h).  The default loop, macro_half.c, evaluates each pair
 * once and gives these same bits. */
/** Pair vectors x_j - x_i, squared distances and distances of nb slots. */
MACRO_CLONES void macro_chunk_geom(size_t nb, int dim, const double xi[3],
                                   double *const *restrict x, const int32_t *restrict idx,
                                   double *restrict gx, double *restrict gy, double *restrict gz,
                                   double *restrict r2, double *restrict r)
{
    const double *restrict x0 = x[0], *restrict x1 = dim > 1 ? x[1] : x[0];
    const double *restrict x2 = dim > 2 ? x[2] : x[0];
    const double xi0 = xi[0], xi1 = xi[1], xi2 = xi[2];
    for (size_t k = 0; k < nb; k++) {
        const size_t j = (size_t)idx[k];
        const double ex = x0[j] - xi0;
        const double ey = dim > 1 ? x1[j] - xi1 : 0.0;
        const double ez = dim > 2 ? x2[j] - xi2 : 0.0;
        gx[k] = ex;
        gy[k] = ey;
        gz[k] = ez;
        r2[k] = ex * ex + ey * ey + ez * ez;
        r[k] = sqrt(r2[k]);
    }
}

/** Pair energy ph, force on i t[0..2] = c (x_j - x_i) (c > 0: attraction),
 *  virial terms t[3..8] (xx yy zz xy yz zx, halved per end) and ok =
 *  whether the slot counts (inside the list radius, not at zero distance,
 *  elastic distance re in (0, r_c)). */
MACRO_CLONES static void macro_chunk_pair(const struct macro_pair *w, size_t nb,
                                          const double *restrict gx,
                                          const double *restrict gy,
                                          const double *restrict gz,
                                          const double *restrict r2,
                                          const double *restrict rd,
                                          const double *restrict re, double rlist2,
                                          double *restrict ph, double (*restrict t)[MACRO_CHUNK],
                                          unsigned char *restrict ok)
{
    double fk[MACRO_CHUNK];
    const double r_c = w->r_c;
    macro_mie_chunk(w, nb, re, ph, fk);
    for (size_t k = 0; k < nb; k++) {
        const double r = rd[k], fr = fk[k], dx[3] = {gx[k], gy[k], gz[k]};
        const double c = -fr / r; /* force on i along dx (attraction > 0) */
        t[0][k] = c * dx[0];
        t[1][k] = c * dx[1];
        t[2][k] = c * dx[2];
        t[3][k] = 0.5 * c * dx[0] * dx[0];
        t[4][k] = 0.5 * c * dx[1] * dx[1];
        t[5][k] = 0.5 * c * dx[2] * dx[2];
        t[6][k] = 0.5 * c * dx[0] * dx[1];
        t[7][k] = 0.5 * c * dx[1] * dx[2];
        t[8][k] = 0.5 * c * dx[2] * dx[0];
        /* the loop's skip tests, without short circuits (they would keep the
         * vectoriser off): NaN distances count, as they did */
        ok[k] = (unsigned char)(!(r2[k] >= rlist2) & (r2[k] != 0.0) & !(re[k] >= r_c) &
                                !(re[k] <= 0.0));
    }
}

int macro_compute_forces(struct model *m, struct sim *sim, struct spall_error *err)
{
    /* this call makes the pair values and energies anew (none is read in
     * between): a list rebuilt now need not write the last call's first */
    m->epot_lazy = 0;
    int rc = macro_neighbors_update(m, sim, false, err);
    if (rc)
        return rc;
    if (!m->pair_full)
        return macro_forces_half(m, sim, err);
    macro_forces_full(m, sim);
    return SPALL_OK;
}

/** The reference loop (deck pair_loop: full): every pair evaluated from
 *  both ends, each end keeping its own slot's state. */
static void macro_forces_full(struct model *m, struct sim *sim)
{
    struct particles *p = sim->p;
    const struct neighbor_list *nl = m->nl;
    const struct macro_pair w = m->pp;
    const size_t n = p->n_owned;
    const int dim = sim->dim;
    const bool plastic = isfinite(w.e_y);
    const double dt = sim_step_dt(sim) > 0.0 ? sim_step_dt(sim) : 1.0; /* this step's noise */
    const double kT = MACRO_KB * m->temperature;
    const double g = m->damping == MACRO_DAMP_ABSOLUTE ? m->gamma_used : 0.0;
    const double mu = m->damping == MACRO_DAMP_PAIRWISE ? m->mu_used : 0.0;
    const double sg = m->eta_cg * sqrt(2.0 * g * kT / dt);
    const double sp = m->eta_cg * sqrt(2.0 * mu * kT / dt);
    const uint64_t seed = sim->seed, step = (uint64_t)m->n_calls;
    const double rlist2 = (w.r_c + m->skin_ratio * w.r0) * (w.r_c + m->skin_ratio * w.r0);
    double *const *x = p->x, *const *v = p->v, *const *f = p->f;
    const int64_t *gid = p->gid;
    uint8_t *eng = m->engaged;
    double *dr0 = m->dr0, *kap = m->kappa, *epot = m->epot, *sig = m->sig, *wd = m->wdiss;
    m->n_calls++;
#pragma omp parallel for schedule(dynamic, 256) if (n >= MACRO_OMP_MIN)
    for (size_t i = 0; i < n; i++) {
        double xi[3] = {0, 0, 0}, vi[3] = {0, 0, 0}, fi[3] = {0, 0, 0}, fl[3] = {0, 0, 0};
        for (int d = 0; d < dim; d++) {
            xi[d] = x[d][i];
            vi[d] = v[d][i];
        }
        double e = 0.0, s6[6] = {0, 0, 0, 0, 0, 0}, wplast = 0.0;
        for (size_t s0 = nl->offset[i]; s0 < nl->offset[i + 1]; s0 += MACRO_CHUNK) {
            const size_t nb = nl->offset[i + 1] - s0 < MACRO_CHUNK ? nl->offset[i + 1] - s0
                                                                   : MACRO_CHUNK;
            double gx[MACRO_CHUNK], gy[MACRO_CHUNK], gz[MACRO_CHUNK], rr2[MACRO_CHUNK];
            double rr[MACRO_CHUNK], rre[MACRO_CHUNK], phk[MACRO_CHUNK], t[9][MACRO_CHUNK];
            unsigned char ok[MACRO_CHUNK];
            macro_chunk_geom(nb, dim, xi, x, nl->idx + s0, gx, gy, gz, rr2, rr);
            const double *re_k = rr;
            if (plastic || mu > 0.0) {
                for (size_t k = 0; k < nb; k++) {
                    const size_t s = s0 + k, j = (size_t)nl->idx[s];
                    const double r = rr[k];
                    double re = r;
                    rre[k] = re;
                    if (rr2[k] >= rlist2 || rr2[k] == 0.0)
                        continue;
                    if (plastic) {
                        re = macro_plastic_update(&w, r, &dr0[s], &kap[s], &eng[s], &wplast);
                        rre[k] = re;
                    }
                    if (mu > 0.0 && r < w.r_c) {
                        double xr[3] = {0, 0, 0};
                        uint64_t ga = (uint64_t)gid[i], gb = (uint64_t)gid[j];
                        double sgn = ga < gb ? 1.0 : -1.0;
                        if (sp > 0.0)
                            macro_gauss3(seed, step, ga < gb ? ga : gb, ga < gb ? gb : ga, xr);
                        for (int d = 0; d < dim; d++)
                            fl[d] += mu * (v[d][j] - vi[d]) + sgn * sp * xr[d];
                    }
                }
                re_k = rre;
            }
            macro_chunk_pair(&w, nb, gx, gy, gz, rr2, rr, re_k, rlist2, phk, t, ok);
            for (size_t k = 0; k < nb; k++) {
                if (!ok[k])
                    continue;
                const double phi = phk[k];
                e += 0.5 * phi;
                for (int d = 0; d < dim; d++)
                    fi[d] += t[d][k];
                for (int c = 0; c < 6; c++)
                    s6[c] += t[3 + c][k];
            }
        }
        if (g > 0.0) {
            double xr[3] = {0, 0, 0};
            if (sg > 0.0)
                macro_gauss3(seed, step, (uint64_t)gid[i], UINT64_MAX, xr);
            for (int d = 0; d < dim; d++)
                fl[d] += -g * vi[d] + sg * xr[d];
        }
        double pw = 0.0;
        for (int d = 0; d < dim; d++) {
            f[d][i] += fi[d] + fl[d];
            pw += fl[d] * vi[d];
        }
        epot[i] = e;
        for (int k = 0; k < 6; k++)
            sig[6 * i + k] = s6[k];
        wd[i] += wplast - pw * dt;
    }
}
