/**
 * @file sph_clamp.c
 * @brief Mirrored (ghost) clamp for SPH: model.clamp {group, point, normal}.
 *
 * Why: a clamp made of fixed particles (v = 0 behind the clamp plane) is a
 * kinked velocity field to the kernel: a fixed particle next to the plane
 * sees moving material on one side only, so its velocity gradient, hence
 * its stress, is about half that of the material it stands for, and the
 * pair force across the plane (sigma_i + sigma_j) transmits too little
 * moment.  Measured on the oscillating plate (docs/validation.md,
 * sph-plate) this softness did not go away with dx.
 *
 * A built-in end is u = 0 on the plane.  Its ghost continuation is the odd
 * reflection v_g = -v_m (m the mirror image of g): it vanishes on the plane
 * and continues every velocity field that is linear near it exactly, so
 * the CSPM velocity gradient of a particle next to the plane is that of
 * the full support.  The ghost's stress is the mirror's (sigma_g =
 * sigma_m: the stress field continues evenly to lowest order).  To pair
 * these with an odd velocity such that the clamp does no work, the ghost's
 * corrected gradient matrix is B_g^-1 = -R B_m^-1 (R = I - 2 n n^T the
 * reflection): with the ghost at the geometric image x_g = R x_m, the pair
 * terms of a particle i with the ghost of j and of j with the ghost of i
 * then cancel in the power balance sum_i (v_i . f_i + m_i de_i/dt), i.e.
 * kinetic + internal energy of the free particles is conserved by the
 * semi-discrete equations, as without a clamp (for B = I the ghost acts
 * with the tensor -sigma R: sigma_nn and the tangential-force /
 * normal-gradient shear kept, the others reversed).  Copying sigma alone
 * with odd velocities, or letting the ghosts evolve their own stress, was
 * measured to blow up within a fraction of a period (10 rows).
 *
 * How: the clamp group must carry a `fixed` boundary condition, so the
 * integrator keeps it at rest between force calls.  Around each force call
 * (sph_model.c) the clamp particles within reach of the plane take v_g =
 * -v_m and x_g = R x_m, after the stress pass (sph_rates.c, one call) rho,
 * c, sigma, the artificial stress R_i of their mirror and B_g^-1 = -R
 * B_m^-1, and afterwards rest at their reference positions again with no
 * internal energy of their own; nothing inside the pair loops changes.
 * Mirror pairs are found once on the reference positions: every clamp
 * particle closer to the plane than 2 (kernel support + skin) must have a
 * non-clamp particle at its mirror image (within dx/4), i.e. the lattice
 * must be symmetric about the plane, else the deck is refused.  Deeper
 * clamp particles stay at rest (only ghosts within one support of the
 * plane act on free particles).  Updated formulation, two-pass loops only.
 * The artificial viscosity and artificial stress across the plane are
 * not energy-paired (the AV still only damps in the measured runs).
 *
 * Distributed (docs/parallel.md, "Updated-Lagrangian SPH on spatial
 * ghosts"): the pairs are kept by global id; a clamp particle and its
 * image may be owned by different ranks, up to two list radii apart, so
 * the images' owners hand their values to every rank (core/parallel/
 * share.h: x and v before the rebuild test of each force call, the
 * engine's place hook; rho, c, sigma, R and B^-1 after the stress pass),
 * and each clamp particle's owner applies the serial formulas to them.
 * The halos that follow carry the clamp particles' values to the ranks
 * that hold them as ghosts.
 */
#include "models/sph/sph_internal.h"

#include "core/parallel/gather.h"
#include "core/parallel/share.h"
#include "core/particles.h"
#include "core/sim.h"
#include "core/options.h"
#include "spall/error.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

struct sph_clamp {
    char group[SPALL_NAME_LEN];
    double point[3], normal[3]; /**< plane; normal points out of the clamp */
    size_t n;                   /**< mirrored pairs */
    size_t *ghost, *mirror;     /**< clamp particle, its mirror image (serial indices) */
    int group_index;            /**< the clamp group (its owned members: s->groups) */
    /* distributed runs: the pairs by global id, their owned ends and the
     * table of the images' values (sph_clamp_localize) */
    int64_t *ggid, *mgid;       /**< clamp particle, mirror image */
    size_t *own_g, *own_m;      /**< owned index of each end or SIZE_MAX */
    size_t *rows;               /**< pairs whose image this rank owns */
    size_t n_rows;
    double *vals, *tab;         /**< their values; the whole table */
};

/* Doubles per pair in the shared tables: x and v; rho, c, sigma, R, B^-1. */
#define CLAMP_W_MOTION 6
#define CLAMP_W_STRESS 23

void sph_clamp_destroy(struct sph_clamp **pc)
{
    if (!pc || !*pc)
        return;
    free((*pc)->ghost);
    free((*pc)->mirror);
    free((*pc)->ggid);
    free((*pc)->mgid);
    free((*pc)->own_g);
    free((*pc)->own_m);
    free((*pc)->rows);
    free((*pc)->vals);
    free((*pc)->tab);
    free(*pc);
    *pc = NULL;
}

int sph_clamp_parse(const struct deck_node *node, int dim, struct sph_clamp **out,
                    struct spall_error *err)
{
    static const char *const keys[] = {"group", "point", "normal", NULL};
    *out = NULL;
    const char *g = NULL;
    double pt[3] = {0, 0, 0}, nr[3] = {0, 0, 0};
    int rc;
    if ((rc = deck_expect_map(node, "a mapping with group, point and normal", err)) ||
        (rc = deck_string(node, "group", true, &g, err)) ||
        (rc = deck_vector(node, "point", true, (size_t)dim, (size_t)dim, pt, err)) ||
        (rc = deck_vector(node, "normal", true, (size_t)dim, (size_t)dim, nr, err)) ||
        (rc = deck_check_unused(node, "model.clamp", keys, err)))
        return rc;
    double nn = nr[0] * nr[0] + nr[1] * nr[1] + nr[2] * nr[2];
    if (!(nn > 0.0))
        return deck_error_key(err, node, "normal", "clamp normal is zero");
    if (strlen(g) >= SPALL_NAME_LEN)
        return deck_error_key(err, node, "group", "group name too long");
    struct sph_clamp *c = calloc(1, sizeof *c);
    if (!c)
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory (sph clamp)");
    strcpy(c->group, g);
    for (int d = 0; d < 3; d++) {
        c->point[d] = pt[d];
        c->normal[d] = nr[d] / sqrt(nn);
    }
    *out = c;
    return SPALL_OK;
}

int sph_clamp_init(struct model *m, struct sim *s, struct spall_error *err)
{
    struct sph_clamp *c = m->clamp;
    const struct particles *p = s->p;
    const int dim = m->dim;
    int gi = sim_find_group(s, c->group);
    if (gi < 0)
        return spall_error_set_key(err, SPALL_ERR_INPUT, "model.clamp",
                                   "model.clamp: no group '%s'", c->group);
    bool fixed = false;
    for (size_t k = 0; k < s->n_bcs; k++)
        if (s->bcs[k].group == gi && s->bcs[k].kind == BC_FIXED &&
            (s->bcs[k].comp_mask & ((1u << dim) - 1u)) == ((1u << dim) - 1u))
            fixed = true;
    if (!fixed)
        return spall_error_set_key(err, SPALL_ERR_INPUT, "model.clamp",
                                   "model.clamp: group '%s' needs a fixed boundary condition on "
                                   "every component (the clamp particles rest between force calls)",
                                   c->group);
    const struct group *g = &s->groups[gi];
    c->group_index = gi;
    uint8_t *in = calloc(p->n_owned ? p->n_owned : 1, 1);
    c->ghost = malloc((g->n ? g->n : 1) * sizeof(size_t));
    c->mirror = malloc((g->n ? g->n : 1) * sizeof(size_t));
    c->ggid = malloc((g->n ? g->n : 1) * sizeof *c->ggid);
    c->mgid = malloc((g->n ? g->n : 1) * sizeof *c->mgid);
    if (!in || !c->ghost || !c->mirror || !c->ggid || !c->mgid) {
        free(in);
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory (sph clamp)");
    }
    for (size_t q = 0; q < g->n; q++)
        in[g->idx[q]] = 1;
    double hmax = 0.0;
    for (size_t i = 0; i < p->n_owned; i++)
        hmax = fmax(hmax, m->h[i]);
    const double reach = 2.0 * m->qmax * hmax * (1.0 + m->opt.kern.skin);
    /* candidate images: free particles within reach (+ a spacing) of the plane */
    size_t *cand = malloc((p->n_owned ? p->n_owned : 1) * sizeof(size_t)), nc = 0;
    if (!cand) {
        free(in);
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory (sph clamp)");
    }
    for (size_t j = 0; j < p->n_owned; j++) {
        double d = 0.0;
        for (int a = 0; a < dim; a++)
            d += (p->x0[a][j] - c->point[a]) * c->normal[a];
        if (!in[j] && d > -m->dx[j] && d < reach + m->dx[j])
            cand[nc++] = j;
    }
    int rc = SPALL_OK;
    c->n = 0;
    for (size_t q = 0; q < g->n && !rc; q++) {
        size_t i = g->idx[q];
        double d = 0.0, Xm[3] = {0, 0, 0};
        for (int a = 0; a < dim; a++)
            d += (p->x0[a][i] - c->point[a]) * c->normal[a];
        if (d > 0.0 || -d > reach)
            continue; /* on the free side (not mirrored), or too deep to matter */
        for (int a = 0; a < dim; a++)
            Xm[a] = p->x0[a][i] - 2.0 * d * c->normal[a];
        /* nearest free particle to the image, among the layer within reach
         * of the plane (once; quadratic in the layer's size) */
        size_t best = (size_t)-1;
        double b2 = INFINITY;
        for (size_t q2 = 0; q2 < nc; q2++) {
            size_t j = cand[q2];
            double r2 = 0.0;
            for (int a = 0; a < dim; a++) {
                double dd = p->x0[a][j] - Xm[a];
                r2 += dd * dd;
            }
            if (r2 < b2) {
                b2 = r2;
                best = j;
            }
        }
        if (best == (size_t)-1 || sqrt(b2) > 0.25 * m->dx[i])
            rc = spall_error_set_key(err, SPALL_ERR_INPUT, "model.clamp",
                                     "model.clamp: clamp particle id %lld (depth %.4g m) has no "
                                     "free particle at its mirror image (nearest %.3g m away); the "
                                     "lattice must be symmetric about the clamp plane",
                                     (long long)p->gid[i], -d, sqrt(b2));
        c->ghost[c->n] = i;
        c->mirror[c->n] = best;
        c->ggid[c->n] = p->gid[i];
        c->mgid[c->n] = best == (size_t)-1 ? -1 : p->gid[best];
        c->n++;
    }
    free(in);
    free(cand);
    return rc;
}

void sph_clamp_begin(const struct model *m, struct sim *s)
{
    const struct sph_clamp *c = m->clamp;
    const double *n = c->normal, *P = c->point;
    struct particles *p = s->p;
    const int dim = m->dim;
    for (size_t k = 0; k < c->n; k++) {
        size_t g = c->ghost[k], j = c->mirror[k];
        double d = 0.0;
        for (int a = 0; a < dim; a++)
            d += (p->x[a][j] - P[a]) * n[a];
        for (int a = 0; a < dim; a++) {
            p->v[a][g] = -p->v[a][j];
            p->x[a][g] = p->x[a][j] - 2.0 * d * n[a]; /* R x_m: the geometric image */
        }
    }
}

/* -R = 2 n n^T - I of the clamp plane. */
static void minus_reflection(const struct sph_clamp *c, int dim, double mR[9])
{
    const double *n = c->normal;
    memset(mR, 0, 9 * sizeof *mR);
    for (int a = 0; a < dim; a++)
        for (int b = 0; b < dim; b++)
            mR[a * 3 + b] = 2.0 * n[a] * n[b] - (a == b ? 1.0 : 0.0);
}

/* Clamp particle g takes the stress state of its image: rho, c, sigma, R
 * and B_g^-1 = -R B_m^-1, from the image's values @p u (23 doubles in the
 * order of CLAMP_W_STRESS: rho, c, sigma 6, R 6, B^-1 9). */
static void stress_from(const struct model *m, const double mR[9], size_t g, const double *u)
{
    const int dim = m->dim;
    m->rho[g] = u[0];
    m->c[g] = u[1];
    for (int q = 0; q < 6; q++) {
        m->sig[q][g] = u[2 + q];
        m->R[q][g] = u[8 + q];
    }
    for (int a = 0; a < dim; a++)
        for (int b = 0; b < dim; b++) {
            double acc = 0.0;
            for (int q = 0; q < dim; q++)
                acc += mR[a * 3 + q] * u[14 + q * 3 + b];
            m->Bi[a * 3 + b][g] = acc;
        }
}

/* The stress values of particle j, in the order stress_from reads them. */
static void stress_of(const struct model *m, size_t j, double *u)
{
    u[0] = m->rho[j];
    u[1] = m->c[j];
    for (int q = 0; q < 6; q++) {
        u[2 + q] = m->sig[q][j];
        u[8 + q] = m->R[q][j];
    }
    for (int q = 0; q < 9; q++)
        u[14 + q] = m->Bi[q][j];
}

int sph_clamp_stress(const struct model *m, struct sim *s, struct spall_error *err)
{
    const struct sph_clamp *c = m->clamp;
    double mR[9];
    minus_reflection(c, m->dim, mR);
    if (!s->par) {
        for (size_t k = 0; k < c->n; k++) {
            double u[CLAMP_W_STRESS];
            stress_of(m, c->mirror[k], u);
            stress_from(m, mR, c->ghost[k], u);
        }
        return SPALL_OK;
    }
    for (size_t q = 0; q < c->n_rows; q++)
        stress_of(m, c->own_m[c->rows[q]], c->vals + q * CLAMP_W_STRESS);
    int rc = par_share_rows(c->n, CLAMP_W_STRESS, c->rows, c->n_rows, c->vals, c->tab, err);
    if (rc)
        return rc;
    for (size_t k = 0; k < c->n; k++)
        if (c->own_g[k] != SIZE_MAX)
            stress_from(m, mR, c->own_g[k], c->tab + k * CLAMP_W_STRESS);
    return SPALL_OK;
}

int sph_clamp_localize(struct model *m, struct sim *s, struct spall_error *err)
{
    struct sph_clamp *c = m->clamp;
    const size_t n = c->n ? c->n : 1;
    if (!c->own_g) {
        c->own_g = malloc(n * sizeof *c->own_g);
        c->own_m = malloc(n * sizeof *c->own_m);
        c->rows = malloc(n * sizeof *c->rows);
        c->vals = malloc(n * CLAMP_W_STRESS * sizeof *c->vals);
        c->tab = malloc(n * CLAMP_W_STRESS * sizeof *c->tab);
        if (!c->own_g || !c->own_m || !c->rows || !c->vals || !c->tab)
            return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory (sph clamp)");
    }
    c->n_rows = 0;
    for (size_t k = 0; k < c->n; k++) {
        c->own_g[k] = par_owned_index(s, c->ggid[k]);
        c->own_m[k] = par_owned_index(s, c->mgid[k]);
        if (c->own_m[k] != SIZE_MAX)
            c->rows[c->n_rows++] = k;
    }
    return SPALL_OK;
}

int sph_clamp_place(struct model *m, struct sim *s, struct spall_error *err)
{
    const struct sph_clamp *c = m->clamp;
    const double *n = c->normal, *P = c->point;
    struct particles *p = s->p;
    const int dim = m->dim;
    for (size_t q = 0; q < c->n_rows; q++) {
        const size_t j = c->own_m[c->rows[q]];
        double *u = c->vals + q * CLAMP_W_MOTION;
        for (int a = 0; a < 3; a++) {
            u[a] = a < dim ? p->x[a][j] : 0.0;
            u[3 + a] = a < dim ? p->v[a][j] : 0.0;
        }
    }
    int rc = par_share_rows(c->n, CLAMP_W_MOTION, c->rows, c->n_rows, c->vals, c->tab, err);
    if (rc)
        return rc;
    /* sph_clamp_begin's formulas on the image's x and v */
    for (size_t k = 0; k < c->n; k++) {
        const size_t g = c->own_g[k];
        if (g == SIZE_MAX)
            continue;
        const double *xj = c->tab + k * CLAMP_W_MOTION, *vj = xj + 3;
        double d = 0.0;
        for (int a = 0; a < dim; a++)
            d += (xj[a] - P[a]) * n[a];
        for (int a = 0; a < dim; a++) {
            p->v[a][g] = -vj[a];
            p->x[a][g] = xj[a] - 2.0 * d * n[a];
        }
    }
    return SPALL_OK;
}

void sph_clamp_end(const struct model *m, struct sim *s)
{
    const struct sph_clamp *c = m->clamp;
    struct particles *p = s->p;
    for (size_t k = 0; k < c->n; k++) {
        size_t g = s->par ? c->own_g[k] : c->ghost[k];
        if (g == SIZE_MAX)
            continue; /* distributed: owned by another rank */
        for (int a = 0; a < m->dim; a++) {
            p->v[a][g] = 0.0;
            p->x[a][g] = p->x0[a][g];
        }
    }
    /* the clamp does no work: its particles store no energy of their own
     * (their rates, driven by mirrored neighbours, are not physical); the
     * group holds the owned members */
    const struct group *gr = &s->groups[c->group_index];
    for (size_t k = 0; k < gr->n; k++)
        m->e[gr->idx[k]] = 0.0;
}
