/**
 * @file pd_plane.c
 * @brief Fiber-parallel matrix cracks on the PDLM lattice (deck
 *        `model.matrix_crack: fiber_plane`).
 *
 * Why: on the rotated triangular lattice every particle has two matrix bonds
 * to each neighbouring fiber row.  A stretch criterion breaks bonds one at a
 * time; when only one of the two matrix families breaks along a line, the
 * fiber bonds crossing that line are left as parallel links that rotate
 * freely (pair forces have no angular stiffness): a zero-energy "hinge band"
 * runs along a matrix-bond row, not along the fibers (seen on the 45 deg
 * open-hole lamina, docs/validation.md).  In a UD lamina a matrix crack is a
 * surface between fibers, so a broken matrix bond stands for a crack
 * segment on the fiber-parallel interface it crosses.
 *
 * Rule: when a matrix bond i-j breaks by stretch, its two zigzag neighbours
 * on the same interface (the other matrix bond of i towards j's fiber row,
 * and the other matrix bond of j towards i's row) break with it, at the end
 * of the step.  Bonds broken this way do not propagate further (no chain
 * reaction): the interface opens one segment per stretch-broken bond, and
 * the crack still grows only where bonds are stretched past s0.  Their
 * stored energy is booked as dissipated.
 *
 * Determinism and ranks: the force kernel only flags stretch-broken
 * half-bonds (each by its own particle).  At the end of the step each owned
 * particle names, by global id, the partners of its flagged bonds' twins
 * (a twin is in the same row, kept as a slot index, so localisation and
 * migration, which keep each row's order, carry it); distributed, the
 * names of a ghost come from its owner through the halo.  Then every owned
 * particle breaks its own half of each intact bond named from either end
 * and books that half's stored energy, walking its row in order: the same
 * bonds and the same sums on any thread and rank count.
 */
#include "models/peridynamics/pd_internal.h"

#include "core/bond_list.h"
#include "core/parallel/decomp.h"
#include "core/particles.h"
#include "core/sim.h"
#include "spall/error.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>

int pd_plane_init(struct model *m, struct sim *sim, struct spall_error *err)
{
    struct bond_list *bl = m->bl;
    const struct particles *p = sim->p;
    const size_t n = p->n, nh = bl->offset[n];
    if (!m->opt.fiber_plane)
        return SPALL_OK;
    if (m->opt.variant != PD_PDLM || m->opt.fiber_model != PD_FIBER_LATTICE || !m->ortho)
        return spall_error_set_key(err, SPALL_ERR_INPUT, "model.matrix_crack",
                                   "matrix_crack: fiber_plane needs variant "
                                   "pdlm, fiber_model lattice and an orthotropic lamina");
    /* a particle names at most one twin per bond of its row (pd_plane_end_step) */
    for (size_t i = 0; i < n; i++)
        if (bl->offset[i + 1] - bl->offset[i] > PD_PLANE_SLOTS)
            return spall_error_set_key(err, SPALL_ERR_INPUT, "model.matrix_crack",
                                       "matrix_crack: fiber_plane: a family of %zu bonds "
                                       "(the PDLM lattice's has at most %d)",
                                       bl->offset[i + 1] - bl->offset[i], PD_PLANE_SLOTS);
    m->twin = malloc((nh ? nh : 1) * sizeof *m->twin);
    m->fresh = calloc(nh ? nh : 1, 1);
    if (!m->twin || !m->fresh)
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory for fiber-plane twins");
    for (size_t i = 0; i < n; i++)
        for (size_t s = bl->offset[i]; s < bl->offset[i + 1]; s++) {
            m->twin[s] = PD_NO_TWIN;
            if (bl->type[s] & 1u)
                continue;
            size_t j = (size_t)bl->partner[s];
            const struct pd_material *a = &m->mat[p->material[i]], *b = &m->mat[p->material[j]];
            const struct pd_material *o = a->ortho ? a : b->ortho ? b : NULL;
            if (!o)
                continue;
            /* side of the fiber row: sign of xi . n, n = fiber normal */
            double nx = -sin(o->fiber_angle), ny = cos(o->fiber_angle);
            double side = (p->x0[0][j] - p->x0[0][i]) * nx + (p->x0[1][j] - p->x0[1][i]) * ny;
            size_t found = SIZE_MAX;
            int count = 0;
            for (size_t t = bl->offset[i]; t < bl->offset[i + 1]; t++) {
                if (t == s || (bl->type[t] & 1u))
                    continue;
                size_t k = (size_t)bl->partner[t];
                double sk = (p->x0[0][k] - p->x0[0][i]) * nx + (p->x0[1][k] - p->x0[1][i]) * ny;
                if (sk * side > 0.0) {
                    found = t;
                    count++;
                }
            }
            if (count == 1)
                m->twin[s] = (uint8_t)(found - bl->offset[i]);
        }
    return SPALL_OK;
}

/* whether the PD_PLANE_SLOTS names @p g hold global id @p id */
static bool named(const double *g, double id)
{
    for (int q = 0; q < PD_PLANE_SLOTS; q++)
        if (g[q] == id)
            return true;
    return false;
}

int pd_plane_end_step(struct model *m, const struct sim *sim, struct spall_error *err)
{
    struct bond_list *bl = m->bl;
    const struct particles *p = sim->p;
    const size_t n = p->n, no = p->n_owned;
    if (n > m->tw_cap) {
        double *g = realloc(m->tw_gid, n * PD_PLANE_SLOTS * sizeof *g);
        if (!g)
            return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory for fiber-plane twins");
        m->tw_gid = g;
        m->tw_cap = n;
    }
    double *tg = m->tw_gid;
    /* 1: each owned particle names the partners of its flagged bonds' twins
     * (gids < 2^53 are exact doubles; -1: no name) */
    for (size_t i = 0; i < no; i++) {
        double *g = tg + i * PD_PLANE_SLOTS;
        int c = 0;
        for (int q = 0; q < PD_PLANE_SLOTS; q++)
            g[q] = -1.0;
        for (size_t s = bl->offset[i]; s < bl->offset[i + 1]; s++) {
            if (!m->fresh[s])
                continue;
            m->fresh[s] = 0;
            if (m->twin[s] != PD_NO_TWIN)
                g[c++] = (double)p->gid[bl->partner[bl->offset[i] + m->twin[s]]];
        }
    }
    if (sim->par && par_halo_block(sim, tg, PD_PLANE_SLOTS))
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory sending fiber-plane twins");
    /* 2: each owned particle breaks its half of every intact bond named
     * from either end; its stored energy is dissipated */
    for (size_t i = 0; i < no; i++) {
        const double gi = (double)p->gid[i];
        for (size_t s = bl->offset[i]; s < bl->offset[i + 1]; s++) {
            if (bl->state[s] & BOND_BROKEN)
                continue;
            const size_t k = (size_t)bl->partner[s];
            if (!named(tg + i * PD_PLANE_SLOTS, (double)p->gid[k]) &&
                !named(tg + k * PD_PLANE_SLOTS, gi))
                continue;
            double ex = p->x[0][k] - p->x[0][i], ey = p->x[1][k] - p->x[1][i];
            double e0 = sqrt(ex * ex + ey * ey) - bl->rest[s];
            bl->state[s] |= BOND_BROKEN;
            m->diss[i] += 0.25 * m->coef[s] * e0 * e0;
        }
    }
    return SPALL_OK;
}
