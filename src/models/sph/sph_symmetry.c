/**
 * @file sph_symmetry.c
 * @brief Mirror (symmetry) planes x = 0 and / or y = 0 for SPH by ghost
 *        particles: a quarter of a Taylor bar with two planes costs a
 *        quarter of the full bar.
 *
 * Every real particle closer to a plane than the neighbour radius gets a
 * ghost at its mirror image (and, near both planes of a quarter model, a
 * third ghost mirrored in both).  A ghost carries its source's scalars (h,
 * rho, c, m, dx) and its velocity and tensors reflected: for the plane
 * x = 0, v_x -> -v_x and the shear components with one x index (xy, xz)
 * change sign (the signs are the core's field parities, core/fields.h,
 * the same that sim_reflect_particle applies).  Ghosts only act as neighbours; their rates are never
 * computed.  The pair force between a particle and the ghost of itself or
 * of a neighbour is then exactly the force the missing half of the body
 * would exert on it (the mirrored half moves as the mirror image), which
 * is what a symmetry plane means: zero normal velocity and zero shear
 * traction on it.
 *
 * Ghost identities (source, mirror mask) are fixed at each neighbour build
 * and positions refreshed every step; the list is rebuilt when a real
 * particle moved more than half the skin, the same criterion as
 * sph_neighbors_update (ghost displacements equal their sources').
 * A particle must be a ghost whenever it can come within the kernel
 * support of a real particle: its image lies 2 d from it (d its distance
 * to the plane) and at least d from any particle on the real side, so
 * d < neighbour radius suffices.
 *
 * Distributed (sph_ulpar.c; docs/parallel.md, "Updated-Lagrangian SPH on
 * spatial ghosts"): a rank mirrors every particle it holds, owned or
 * spatial ghost, near a plane.  The engine's ghost set holds the source of
 * every image within the list radius of an owned particle (its box test
 * also tries the particles' images, par_sghost_set_mirror), and the images
 * follow the owned and ghost particles in ascending (source gid, mask), as
 * the serial ghosts follow the real particles in (index = gid, mask): each
 * owned row, real partners merged by gid and then the images, is the
 * serial row, summed term for term.  The list is built by
 * sph_symmetry_list at the engine's rebuilds; each force call refreshes
 * the images from their sources after the halo (sph_symmetry_src).
 */
#include "models/sph/sph_internal.h"

#include "core/fields.h"
#include "core/neighbor.h"
#include "core/parallel/comm.h"
#include "core/particles.h"
#include "core/sim.h"
#include "spall/error.h"

#include <math.h>
#include <omp.h>
#include <stdlib.h>
#include <string.h>

#define SYM_NARR 23 /* x3 v3 h rho c m2 dx sr6 R6 */

struct sph_sym {
    size_t cap;      /**< capacity of every buffer */
    size_t n_ghost;
    int32_t *gsrc;   /**< source real particle of ghost k */
    uint8_t *gmask;  /**< bit d: mirrored in plane x_d = 0 */
    double *buf[SYM_NARR];
    bool built;      /**< m->nl is the real + ghost list */
};

void sph_symmetry_destroy(struct sph_sym **psym)
{
    if (!psym || !*psym)
        return;
    struct sph_sym *g = *psym;
    for (int k = 0; k < SYM_NARR; k++)
        free(g->buf[k]);
    free(g->gsrc);
    free(g->gmask);
    free(g);
    *psym = NULL;
}

static int sym_reserve(struct sph_sym *g, size_t need, struct spall_error *err)
{
    if (need <= g->cap)
        return SPALL_OK;
    size_t cap = need + need / 4 + 16;
    for (int k = 0; k < SYM_NARR; k++) {
        double *q = realloc(g->buf[k], cap * sizeof(double));
        if (!q)
            return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory for %zu sph ghosts", cap);
        g->buf[k] = q;
    }
    int32_t *s = realloc(g->gsrc, cap * sizeof *s);
    if (s)
        g->gsrc = s;
    uint8_t *mk = realloc(g->gmask, cap);
    if (mk)
        g->gmask = mk;
    if (!s || !mk)
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory for %zu sph ghosts", cap);
    g->cap = cap;
    return SPALL_OK;
}

/* Ghost list: every (particle, mirror mask) whose image may enter a real
 * particle's support before the next build, over the @p n particles taken
 * in the order @p order (NULL: index order) at positions @p xs. */
static int sym_find_ghosts(struct model *m, size_t n, const size_t *order,
                           const double *const xs[3], double radius, struct spall_error *err)
{
    struct sph_sym *g = m->sym;
    const bool sx = m->opt.bound.symmetry[0], sy = m->opt.bound.symmetry[1];
    size_t ng = 0;
    for (int pass = 0; pass < 2; pass++) {
        ng = 0;
        for (size_t q = 0; q < n; q++) {
            const size_t j = order ? order[q] : q;
            bool nx = sx && fabs(xs[0][j]) < radius, ny = sy && fabs(xs[1][j]) < radius;
            for (uint8_t mask = 1; mask <= 3; mask++) {
                if (((mask & 1) && !nx) || ((mask & 2) && !ny))
                    continue;
                if (pass == 1) {
                    g->gsrc[ng] = (int32_t)j;
                    g->gmask[ng] = mask;
                }
                ng++;
            }
        }
        if (pass == 0) {
            int rc = sym_reserve(g, n + ng, err);
            if (rc)
                return rc;
        }
    }
    g->n_ghost = ng;
    return SPALL_OK;
}

/* Copy the data of the @p n particles held and write the ghosts' mirrored
 * data after them. */
static void sym_fill(struct model *m, struct sim *s, size_t n)
{
    struct sph_sym *g = m->sym;
    const struct particles *p = s->p;
    const size_t ng = g->n_ghost;
    const int dim = m->dim;
    double **b = g->buf;
    const double *srcs[SYM_NARR] = {p->x[0], p->x[1], dim == 3 ? p->x[2] : NULL,
                                     p->v[0], p->v[1], dim == 3 ? p->v[2] : NULL,
                                     m->h,    m->rho,  m->c,
                                     m->m2,   m->dx};
    for (int c = 0; c < 6; c++) {
        srcs[11 + c] = m->sr[c];
        srcs[17 + c] = m->R[c];
    }
    for (int k = 0; k < SYM_NARR; k++)
        if (srcs[k])
            memcpy(b[k], srcs[k], n * sizeof(double));
    /* reflection signs for masks 1 (x), 2 (y), 3 (both), from the core's
     * parities (core/fields.h, the ones sim_reflect_particle uses): of the
     * vector components (x, v) and of the symmetric tensors (sr, R, stored
     * xx yy zz xy yz xz) */
    double vsign[4][3], tsign[4][6];
    for (unsigned mk = 0; mk < 4; mk++) {
        for (int d = 0; d < 3; d++)
            vsign[mk][d] = field_reflect_sign(FIELD_VECTOR, d, mk);
        for (int c = 0; c < 6; c++)
            tsign[mk][c] = field_reflect_sign(FIELD_SYMTENSOR, c, mk);
    }
#pragma omp parallel for schedule(static)
    for (size_t k = 0; k < ng; k++) {
        const size_t j = (size_t)g->gsrc[k], o = n + k;
        const int mk = g->gmask[k];
        for (int d = 0; d < dim; d++) {
            double sg = vsign[mk][d];
            b[d][o] = sg * srcs[d][j];
            b[3 + d][o] = sg * srcs[3 + d][j];
        }
        for (int q = 6; q < 11; q++)
            b[q][o] = srcs[q][j];
        for (int c = 0; c < 6; c++) {
            b[11 + c][o] = tsign[mk][c] * srcs[11 + c][j];
            b[17 + c][o] = tsign[mk][c] * srcs[17 + c][j];
        }
    }
}

/* The pair loop's view of the n held particles and their ghosts. */
static void sym_src(const struct sph_sym *g, size_t n, int dim, struct sph_pair_src *src)
{
    memset(src, 0, sizeof *src);
    src->n_all = n + g->n_ghost;
    for (int d = 0; d < dim; d++) {
        src->x[d] = g->buf[d];
        src->v[d] = g->buf[3 + d];
    }
    src->h = g->buf[6];
    src->rho = g->buf[7];
    src->c = g->buf[8];
    src->m2 = g->buf[9];
    src->dx = g->buf[10];
    for (int c = 0; c < 6; c++) {
        src->sr[c] = g->buf[11 + c];
        src->R[c] = g->buf[17 + c];
    }
}

static int sym_create(struct model *m, struct spall_error *err)
{
    if (!m->sym && !(m->sym = calloc(1, sizeof *m->sym)))
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory for sph symmetry");
    return SPALL_OK;
}

bool sph_symmetry_built(const struct model *m)
{
    return m->sym && m->sym->built;
}

int sph_symmetry_list(struct model *m, struct sim *s, bool moved, struct spall_error *err)
{
    const struct particles *p = s->p;
    const size_t n = p->n, no = p->n_owned;
    const int dim = m->dim;
    int rc = sym_create(m, err);
    if (rc)
        return rc;
    struct sph_sym *g = m->sym;
    /* the held particles in ascending gid: the owned run and the ghost
     * run (each ascending) merged, the serial order of their images */
    size_t *order = malloc((n ? n : 1) * sizeof *order);
    if (!order)
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory for sph symmetry");
    for (size_t a = 0, b = no, w = 0; w < n; w++)
        order[w] = b == n || (a < no && p->gid[a] < p->gid[b]) ? a++ : b++;
    const double *xs[3] = {m->x_build[0], m->x_build[1], dim == 3 ? m->x_build[2] : NULL};
    rc = sym_find_ghosts(m, n, order, xs, m->nl_radius, err);
    free(order);
    if (rc)
        return rc;
    /* the build positions: the particles' and their images' */
    for (int d = 0; d < dim; d++)
        memcpy(g->buf[d], m->x_build[d], n * sizeof(double));
    for (size_t k = 0; k < g->n_ghost; k++)
        for (int d = 0; d < dim; d++)
            g->buf[d][n + k] = field_reflect_sign(FIELD_VECTOR, d, g->gmask[k]) *
                               m->x_build[d][g->gsrc[k]];
    /* the whole body's image count, as one rank counts it: each image
     * once, on the rank that owns its source (a restart's check, and the
     * value a checkpoint saves) */
    uint64_t mine = 0;
    for (size_t k = 0; k < g->n_ghost; k++)
        mine += (size_t)g->gsrc[k] < no;
    const int64_t total = (int64_t)par_sum_u64(mine);
    neighbor_list_destroy(&m->nl);
    double *xb[3] = {g->buf[0], g->buf[1], dim == 3 ? g->buf[2] : NULL};
    if ((rc = neighbor_list_build_pairs(&m->nl, NULL, dim, n + g->n_ghost, xb, m->nl_radius,
                                        err)))
        return rc;
    /* after a checkpoint's load (the partition of a restart): the build
     * positions and radius are the checkpoint's, so this is the list of its
     * last build, which the serial run holds and sph_symmetry_restore finds
     * on one rank (not counted as a build) */
    if (m->sym_restore) {
        m->sym_restore = false;
        g->built = true;
        if (total != m->sym_ghosts)
            return spall_error_set(err, SPALL_ERR_INPUT,
                                   "sph symmetry: %lld mirror ghosts at the checkpoint's build "
                                   "positions, the checkpoint says %lld",
                                   (long long)total, (long long)m->sym_ghosts);
    }
    m->sym_ghosts = total;
    if (moved)
        g->built = true;
    return SPALL_OK;
}

void sph_symmetry_src(struct model *m, struct sim *s, struct sph_pair_src *src)
{
    sym_fill(m, s, s->p->n);
    sym_src(m->sym, s->p->n, m->dim, src);
}

int sph_symmetry_update(struct model *m, struct sim *s, struct sph_pair_src *src,
                        struct spall_error *err)
{
    const struct particles *p = s->p;
    const size_t n = p->n_owned;
    const int dim = m->dim;
    if (!m->sym) {
        m->sym = calloc(1, sizeof *m->sym);
        if (!m->sym)
            return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory for sph symmetry");
    }
    struct sph_sym *g = m->sym;
    double hmax = 0.0;
    for (size_t i = 0; i < n; i++)
        hmax = fmax(hmax, m->h[i]);
    bool rebuild = !g->built || !m->nl;
    if (!rebuild)
        rebuild = m->qmax * hmax + 2.0 * sqrt(sph_max_move2(m, p)) > m->nl_radius;
    int rc;
    if (rebuild) {
        m->nl_radius = m->qmax * hmax * (1.0 + m->opt.kern.skin);
        const double *xs[3] = {p->x[0], p->x[1], dim == 3 ? p->x[2] : NULL};
        if ((rc = sym_find_ghosts(m, n, NULL, xs, m->nl_radius, err)))
            return rc;
    }
    sym_fill(m, s, n);
    if (rebuild) {
        double t0 = omp_get_wtime();
        neighbor_list_destroy(&m->nl);
        double *xb[3] = {g->buf[0], g->buf[1], dim == 3 ? g->buf[2] : NULL};
        if ((rc = neighbor_list_build_pairs(&m->nl, NULL, dim, n + g->n_ghost, xb, m->nl_radius,
                                            err)))
            return rc;
        for (int d = 0; d < dim; d++)
            memcpy(m->x_build[d], p->x[d], n * sizeof(double));
        /* before a partition (more than one rank): the work of the real
         * partners (the view aliased the list just freed) */
        if (sph_ul_view_held(m, n))
            return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory (SPH neighbour rows)");
        g->built = true;
        m->n_builds++;
        m->t_neighbor += omp_get_wtime() - t0;
    }
    sym_src(g, n, dim, src);
    return SPALL_OK;
}

int sph_symmetry_restore(struct model *m, struct sim *s, struct spall_error *err)
{
    if (!m->sym) {
        m->sym = calloc(1, sizeof *m->sym);
        if (!m->sym)
            return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory for sph symmetry");
    }
    struct sph_sym *g = m->sym;
    struct particles *p = s->p;
    const size_t n = p->n_owned;
    const int dim = m->dim;
    /* the build saw the positions it stored in x_build: the ghost search and
     * the list read p->x, so they run once more with the particles at those
     * positions (pointers swapped, nothing copied), with the radius of that
     * build (m->nl_radius, restored; h may have changed since) */
    double *now[3] = {NULL, NULL, NULL};
    for (int d = 0; d < dim; d++) {
        now[d] = p->x[d];
        p->x[d] = m->x_build[d];
    }
    const double *xs[3] = {p->x[0], p->x[1], dim == 3 ? p->x[2] : NULL};
    int rc = sym_find_ghosts(m, n, NULL, xs, m->nl_radius, err);
    if (!rc) {
        sym_fill(m, s, n); /* the positions; the rest is refilled by the next update */
        neighbor_list_destroy(&m->nl);
        double *xb[3] = {g->buf[0], g->buf[1], dim == 3 ? g->buf[2] : NULL};
        rc = neighbor_list_build_pairs(&m->nl, NULL, dim, n + g->n_ghost, xb, m->nl_radius, err);
    }
    for (int d = 0; d < dim; d++)
        p->x[d] = now[d];
    g->built = !rc;
    if (!rc && (int64_t)g->n_ghost != m->sym_ghosts)
        rc = spall_error_set(err, SPALL_ERR_INPUT,
                             "sph symmetry: %zu mirror ghosts at the checkpoint's build "
                             "positions, the checkpoint says %lld",
                             g->n_ghost, (long long)m->sym_ghosts);
    return rc;
}

size_t sph_symmetry_ghosts(const struct model *m)
{
    return m->sym ? m->sym->n_ghost : 0;
}
