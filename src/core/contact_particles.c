/**
 * @file contact_particles.c
 * @brief Particle-particle contact (see contact_particles.h): Verlet
 *        candidate lists (reach d + skin, cell-list build, rebuilt on a
 *        skin/2 displacement), per-particle gather of a repulsive power-law
 *        penalty between particles of different bodies and unbonded
 *        particles of one body.
 */
#include "core/contact_particles.h"

#include "core/field_state.h"

#include "core/bond_list.h"
#include "core/exact_sum.h"
#include "core/parallel/comm.h"
#include "core/parallel/decomp.h"
#include "core/parallel/migrate.h"
#include "core/parallel/psum.h"
#include "core/parallel/sghost.h"
#include "core/particles.h"
#include "core/sim.h"
#include "core/model.h"
#include "spall/error.h"

#include <math.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

struct particle_contact {
    struct particle_contact_params prm;
    size_t cap;          /* particles the scratch arrays hold */
    size_t *cell;        /* cell of each particle */
    size_t *order;       /* particles sorted by cell (stable: ascending index) */
    double *epart;       /* half the energy of the pairs of particle i */
    uint32_t *npart;     /* pairs of particle i */
    size_t *start;       /* cell_cap: first slot of each cell in order[] */
    size_t *fill;        /* cell_cap: fill cursor of the counting sort */
    size_t cell_cap;
    double skin;         /* candidate lists reach d + skin */
    double *xref[3];     /* positions at the last build */
    size_t *off;         /* cap + 1: candidates of i are nbr[off[i] .. off[i+1]) */
    int32_t *nbr;
    size_t nbr_cap;
    size_t n_built;      /* particles at the last build */
    bool built;          /* the lists were built (on every rank alike: a collective build) */
    size_t rebuilds;
    double energy;
    size_t pairs;
    /* distributed runs: the particles of other ranks within d + skin of the
     * owned ones (core/parallel/sghost.h), seen through a combined view
     * (owned [0, n_owned), then these ghosts in ascending gid) */
    struct par_sghost *sg;
    double *vx[3];       /* view positions */
    int64_t *vgid;
    int32_t *vbody;
    double *gbody;       /* scratch: bodies as doubles for the exchange */
    size_t vcap;
    long layouts;        /* the re-layouts seen at the last build (par_layouts) */
    struct bond_list ckbl; /* the owned rows of the lists, as a checkpoint sees them */
    int32_t *ck_gid;     /* distributed checkpoint: the candidates' global ids */
};

/* The particles contact sees: on one rank the particle arrays; on a
 * distributed run the owned particles and the spatial ghosts of c->sg. */
struct cview {
    size_t n, no;
    double *x[3];
    const int32_t *body;
    const int64_t *gid;
};

int particle_contact_create(struct particle_contact **out,
                            const struct particle_contact_params *prm, struct spall_error *err)
{
    *out = NULL;
    if (!(prm->distance > 0.0) || !isfinite(prm->distance))
        return spall_error_set_key(err, SPALL_ERR_PHYSICS, "contact.distance",
                                   "contact: distance must be positive and finite (got %g m)",
                                   prm->distance);
    if (!(prm->stiffness > 0.0) || !isfinite(prm->stiffness))
        return spall_error_set_key(err, SPALL_ERR_PHYSICS, "contact.stiffness",
                                   "contact: stiffness must be positive and finite (got %g N/m)",
                                   prm->stiffness);
    if (!(prm->exponent >= 1.0 && prm->exponent <= 2.0))
        return spall_error_set_key(err, SPALL_ERR_PHYSICS, "contact.exponent",
                                   "contact: exponent must lie in [1, 2] (got %g)", prm->exponent);
    struct particle_contact *c = calloc(1, sizeof *c);
    if (!c)
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory creating the contact");
    c->prm = *prm;
    /* skin 0.5 d: rebuilt when a particle has moved 0.25 d (impact-spall
     * at 260 m/s: every ~14 steps); measured faster than 0.3 d and 0.15 d,
     * and the reach 1.5 d stays below a triangular lattice's unbonded
     * second neighbours (sqrt 3 r0) */
    c->skin = 0.5 * prm->distance;
    *out = c;
    return SPALL_OK;
}

void particle_contact_destroy(struct particle_contact **pc)
{
    if (!pc || !*pc)
        return;
    struct particle_contact *c = *pc;
    free(c->cell);
    free(c->order);
    free(c->epart);
    free(c->npart);
    free(c->start);
    free(c->fill);
    for (int d = 0; d < 3; d++)
        free(c->xref[d]);
    free(c->off);
    free(c->nbr);
    par_sghost_destroy(&c->sg);
    for (int d = 0; d < 3; d++)
        free(c->vx[d]);
    free(c->vgid);
    free(c->vbody);
    free(c->gbody);
    free(c->ck_gid);
    free(c);
    *pc = NULL;
}

static int reserve(struct particle_contact *c, size_t n, size_t ncell, struct spall_error *err)
{
    if (n > c->cap) {
        size_t *a = realloc(c->cell, n * sizeof *a);
        if (a)
            c->cell = a;
        size_t *b = realloc(c->order, n * sizeof *b);
        if (b)
            c->order = b;
        double *e = realloc(c->epart, n * sizeof *e);
        if (e)
            c->epart = e;
        uint32_t *q = realloc(c->npart, n * sizeof *q);
        if (q)
            c->npart = q;
        size_t *o = realloc(c->off, (n + 1) * sizeof *o);
        if (o)
            c->off = o;
        if (!a || !b || !e || !q || !o)
            return spall_error_set(err, SPALL_ERR_NOMEM, "contact: out of memory for %zu particles",
                                   n);
        c->cap = n;
    }
    if (ncell + 1 > c->cell_cap) {
        size_t *s = realloc(c->start, (ncell + 1) * sizeof *s);
        if (s)
            c->start = s;
        size_t *f = realloc(c->fill, (ncell + 1) * sizeof *f);
        if (f)
            c->fill = f;
        if (!s || !f)
            return spall_error_set(err, SPALL_ERR_NOMEM, "contact: out of memory for %zu cells",
                                   ncell);
        c->cell_cap = ncell + 1;
    }
    return SPALL_OK;
}

/* True when i and j are bonded in the model's list (any state: a broken
 * bond's repulsion is the model's).  Rows hold a dozen partners or so. */
static inline int bonded(const struct bond_list *bl, const int64_t *pgid, size_t i, int64_t gj)
{
    if (!bl || i >= bl->n)
        return 0;
    for (size_t k = bl->offset[i]; k < bl->offset[i + 1]; k++)
        if (pgid[bl->partner[k]] == gj)
            return 1;
    return 0;
}

/* Row i of the candidate lists in the serial order: ascending cell, then
 * ascending gid within a cell (one rank: the stable counting sort's
 * ascending index, which is the gid).  Distributed runs hold the ghosts
 * after the owned particles, so their rows are sorted into that order. */
static void sort_row(int32_t *r, size_t len, const size_t *cell, const int64_t *gid)
{
    for (size_t k = 1; k < len; k++) {
        int32_t v = r[k];
        size_t q = k;
        while (q > 0 && (cell[r[q - 1]] > cell[v] ||
                         (cell[r[q - 1]] == cell[v] && gid[r[q - 1]] > gid[v]))) {
            r[q] = r[q - 1];
            q--;
        }
        r[q] = v;
    }
}

/* Candidate lists (CSR over owned particles): every eligible partner j
 * within d + skin of i at build time, in cell order.  Eligible = not in the
 * model's bond list (fixed for the run, so the eligibility of a pair never
 * changes) and, for models without one, of another body.  Built with a cell list of edge
 * >= d + skin over the current bounding box (cells <= 4 n + 64), two passes
 * (count, fill) gathered per particle: the same lists for any thread count.
 * A distributed run takes the bounding box and n of the whole body, so the
 * cells and hence every row's order are the serial ones. */
static int build_candidates(struct particle_contact *c, const struct sim *s,
                            const struct cview *v, struct spall_error *err)
{
    const struct particles *p = s->p;
    const int dim = s->dim;
    const size_t n = v->n, no = v->no;
    const double reach = c->prm.distance + c->skin;
    double lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
    int finite = 1;
    for (int d = 0; d < dim; d++) {
        lo[d] = INFINITY;
        hi[d] = -INFINITY;
        for (size_t i = 0; i < no; i++) {
            lo[d] = fmin(lo[d], v->x[d][i]);
            hi[d] = fmax(hi[d], v->x[d][i]);
        }
        if (s->par) { /* collective: every rank takes the same branch below */
            lo[d] = par_min_double(lo[d]);
            hi[d] = par_max_double(hi[d]);
        }
        finite &= isfinite(lo[d]) && isfinite(hi[d]);
    }
    if (!finite)
        return SPALL_OK; /* the integrator reports the non-finite particle */
    const size_t n_all = s->par ? par_n_global(s) : n;
    double h = reach;
    size_t nc[3] = {1, 1, 1}, ncell = 1;
    for (;;) {
        ncell = 1;
        for (int d = 0; d < dim; d++) {
            nc[d] = (size_t)floor((hi[d] - lo[d]) / h) + 1;
            ncell *= nc[d];
        }
        if (ncell <= 4 * n_all + 64)
            break;
        h *= 2.0;
    }
    int rc = reserve(c, n, ncell, err);
    if (rc)
        return rc;
    memset(c->start, 0, (ncell + 1) * sizeof *c->start);
    for (size_t i = 0; i < n; i++) {
        size_t id = 0;
        for (int d = dim - 1; d >= 0; d--) {
            double f = floor((v->x[d][i] - lo[d]) / h);
            size_t q = f > 0.0 ? (size_t)f : 0; /* a ghost may lie off the box: clamped */
            if (q >= nc[d])
                q = nc[d] - 1;
            id = id * nc[d] + q;
        }
        c->cell[i] = id;
        c->start[id + 1]++;
    }
    for (size_t q = 0; q < ncell; q++)
        c->start[q + 1] += c->start[q];
    /* counting sort, stable: ascending particle index inside a cell */
    memcpy(c->fill, c->start, ncell * sizeof *c->fill);
    for (size_t i = 0; i < n; i++)
        c->order[c->fill[c->cell[i]]++] = i;
    const int32_t *body = v->body;
    const int64_t *gid = v->gid;
    const struct bond_list *bl = s->ops && s->ops->bonds ? s->ops->bonds(s->model) : NULL;
    const double r2max = reach * reach;
    for (int pass = 0; pass < 2; pass++) {
        if (pass == 1) {
            c->off[0] = 0;
            for (size_t i = 0; i < no; i++)
                c->off[i + 1] = c->off[i] + c->npart[i];
            size_t need = c->off[no];
            if (need > c->nbr_cap) {
                int32_t *q = realloc(c->nbr, (need ? need : 1) * sizeof *q);
                if (!q)
                    return spall_error_set(err, SPALL_ERR_NOMEM,
                                           "contact: out of memory for %zu candidate pairs", need);
                c->nbr = q;
                c->nbr_cap = need;
            }
        }
#pragma omp parallel for schedule(static) if (no > SPALL_OMP_MIN_PARTICLES)
        for (size_t i = 0; i < no; i++) {
            size_t ci[3] = {0, 0, 0}, c0[3] = {0, 0, 0}, c1[3] = {0, 0, 0};
            for (int d = 0; d < dim; d++) {
                size_t q = (size_t)floor((v->x[d][i] - lo[d]) / h);
                ci[d] = q >= nc[d] ? nc[d] - 1 : q;
                c0[d] = ci[d] > 0 ? ci[d] - 1 : 0;
                c1[d] = ci[d] + 1 < nc[d] ? ci[d] + 1 : ci[d];
            }
            const int32_t bi = body ? body[i] : 0;
            uint32_t cnt = 0;
            size_t w = pass ? c->off[i] : 0;
            for (size_t gz = c0[2]; gz <= c1[2]; gz++)
                for (size_t gy = c0[1]; gy <= c1[1]; gy++)
                    for (size_t gx = c0[0]; gx <= c1[0]; gx++) {
                        size_t id = (gz * nc[1] + gy) * nc[0] + gx;
                        for (size_t s2 = c->start[id]; s2 < c->start[id + 1]; s2++) {
                            size_t j = c->order[s2];
                            if (j == i)
                                continue;
                            double r2 = 0.0;
                            for (int d = 0; d < dim; d++) {
                                double dx = v->x[d][j] - v->x[d][i];
                                r2 += dx * dx;
                            }
                            if (!(r2 < r2max))
                                continue;
                            /* bonded pairs (any body, e.g. a peridynamic
                             * family reaching into another body) are the
                             * model's; unbonded ones of one body only in
                             * bonded models */
                            const int32_t bj = body ? body[j] : 0;
                            if ((bi == bj && !bl) || bonded(bl, p->gid, i, gid[j]))
                                continue;
                            if (pass)
                                c->nbr[w++] = (int32_t)j;
                            cnt++;
                        }
                    }
            c->npart[i] = cnt;
            if (pass && s->par)
                sort_row(c->nbr + c->off[i], cnt, c->cell, gid);
        }
    }
    /* the build positions are a per-particle array of the engine on a
     * distributed run (core/parallel/decomp.c): a partition or migration
     * replaces them by arrays of p->n rows, so they keep that length */
    size_t nx = p->n > no ? p->n : no;
    nx = nx ? nx : 1; /* never NULL: the engine carries it (par_slot_add skips NULL) */
    for (int d = 0; d < dim; d++) {
        double *x = realloc(c->xref[d], nx * sizeof *x);
        if (!x)
            return spall_error_set(err, SPALL_ERR_NOMEM, "contact: out of memory for %zu particles",
                                   nx);
        c->xref[d] = x;
        memcpy(c->xref[d], v->x[d], no * sizeof(double));
    }
    c->n_built = no;
    c->built = true;
    return SPALL_OK;
}

enum rebuild { REBUILD_NONE, REBUILD_NOW, REBUILD_AT_REF };

/* A distributed run whose owned set changed since the lists were built
 * (the partition, also after a restart, or a rebalance) while the build
 * positions travelled with the particles: the lists are rebuilt from those
 * positions, which gives the serial lists of the last build (the same
 * pairs, the same cells, the same order) without a rebuild the serial run
 * does not make.  The same answer on every rank. */
static bool relaid_out(const struct particle_contact *c, const struct sim *s, long reb)
{
    return s->par && c->built && (!c->sg || reb != c->layouts);
}

/* REBUILD_NOW when some particle moved more than skin/2 since the lists
 * were built (then a pair could have come from beyond d + skin to within
 * d), on any rank; max is exact, so the answer does not depend on the
 * thread or rank count.  Else REBUILD_AT_REF after a re-layout
 * (relaid_out). */
static enum rebuild needs_rebuild(struct particle_contact *c, const struct sim *s)
{
    const struct particles *p = s->p;
    /* a rebalance's or the distributed set-up's migration, which also
     * moves particles between ranks after the lists were built */
    const long reb = par_layouts(s);
    const bool relaid = relaid_out(c, s, reb);
    const double lim = 0.25 * c->skin * c->skin;
    double m2 = 0.0;
    const size_t no = p->n_owned;
    const int dim = s->dim;
    if (!c->built || (!relaid && c->n_built != no)) {
        m2 = INFINITY;
    } else {
#pragma omp parallel for schedule(static) reduction(max : m2) if (no > SPALL_OMP_MIN_PARTICLES)
        for (size_t i = 0; i < no; i++) {
            double r2 = 0.0;
            for (int d = 0; d < dim; d++) {
                double dx = p->x[d][i] - c->xref[d][i];
                r2 += dx * dx;
            }
            m2 = r2 > m2 ? r2 : m2;
        }
    }
    if (s->par)
        m2 = par_max_double(m2 != m2 ? INFINITY : m2);
    c->layouts = reb;
    if (!(m2 <= lim)) /* a NaN forces a rebuild */
        return REBUILD_NOW;
    return relaid ? REBUILD_AT_REF : REBUILD_NONE;
}

/* Room for a view of @p n particles. */
static int view_reserve(struct particle_contact *c, size_t n, struct spall_error *err)
{
    if (n <= c->vcap)
        return SPALL_OK;
    int bad = 0;
    for (int d = 0; d < 3; d++) {
        double *x = realloc(c->vx[d], n * sizeof *x);
        if (x)
            c->vx[d] = x;
        bad |= !x;
    }
    int64_t *g = realloc(c->vgid, n * sizeof *g);
    if (g)
        c->vgid = g;
    int32_t *b = realloc(c->vbody, n * sizeof *b);
    if (b)
        c->vbody = b;
    double *gb = realloc(c->gbody, n * sizeof *gb);
    if (gb)
        c->gbody = gb;
    if (bad || !g || !b || !gb)
        return spall_error_set(err, SPALL_ERR_NOMEM, "contact: out of memory for %zu particles",
                               n);
    c->vcap = n;
    return SPALL_OK;
}

/* The distributed view: owned particles, then the spatial ghosts (rebuilt
 * with the lists: @p rebuild; else their positions refreshed); @p at the
 * owned positions (the current ones, or the build positions of a
 * re-layout, whose ghosts then come with theirs).  Collective; errors
 * agreed. */
static int dist_view(struct particle_contact *c, struct sim *s, int rebuild, double *const *at,
                     struct cview *v, struct spall_error *err)
{
    struct particles *p = s->p;
    const int dim = s->dim;
    const size_t no = p->n_owned;
    int rc = SPALL_OK;
    if (!c->sg)
        rc = par_sghost_create(&c->sg, dim, c->prm.distance, c->skin, err);
    if ((rc = par_agree(rc, err)))
        return rc;
    const double *x[3] = {at[0], dim > 1 ? at[1] : NULL, dim > 2 ? at[2] : NULL};
    if (rebuild) {
        if ((rc = par_sghost_build(c->sg, no, x, p->gid, err)))
            return rc;
    } else {
        par_sghost_update(c->sg, x);
    }
    const size_t ng = par_sghost_count(c->sg), n = no + ng;
    rc = view_reserve(c, n, err);
    if ((rc = par_agree(rc, err)))
        return rc;
    for (int d = 0; d < dim; d++) {
        memcpy(c->vx[d], at[d], no * sizeof(double));
        memcpy(c->vx[d] + no, par_sghost_x(c->sg, d), ng * sizeof(double));
    }
    if (rebuild) {
        memcpy(c->vgid, p->gid, no * sizeof(int64_t));
        memcpy(c->vgid + no, par_sghost_gid(c->sg), ng * sizeof(int64_t));
        for (size_t i = 0; i < no; i++)
            c->gbody[i] = p->body ? (double)p->body[i] : 0.0;
        if ((rc = par_sghost_values(c->sg, c->gbody, c->gbody + no, 1, err)))
            return rc;
        for (size_t i = 0; i < n; i++)
            c->vbody[i] = (int32_t)c->gbody[i];
    }
    *v = (struct cview){n, no, {c->vx[0], c->vx[1], c->vx[2]}, c->vbody, c->vgid};
    return SPALL_OK;
}

/* REBUILD_AT_REF: the lists of the last build from the build positions
 * (not counted as a build: the serial run made none), then the view at
 * the current positions (@p v).  Collective; errors agreed. */
static int rebuild_at_ref(struct particle_contact *c, struct sim *s, struct cview *v,
                          struct spall_error *err)
{
    int rc = dist_view(c, s, 1, c->xref, v, err);
    if (rc)
        return rc;
    rc = reserve(c, v->n, 0, err);
    if (!rc)
        rc = build_candidates(c, s, v, err);
    if ((rc = par_agree(rc, err)))
        return rc;
    return dist_view(c, s, 0, s->p->x, v, err);
}

int particle_contact_forces(struct sim *s, struct spall_error *err)
{
    struct particle_contact *c = s->pcontact;
    if (!c)
        return SPALL_OK;
    struct particles *p = s->p;
    const int dim = s->dim;
    const size_t no = p->n_owned;
    c->energy = 0.0;
    c->pairs = 0;
    if ((s->par ? par_n_global(s) : p->n) < 2)
        return SPALL_OK;
    const enum rebuild rebuild = needs_rebuild(c, s);
    struct cview v = {p->n, no, {p->x[0], p->x[1], p->x[2]}, p->body, p->gid};
    int rc = rebuild == REBUILD_AT_REF ? rebuild_at_ref(c, s, &v, err)
             : s->par                  ? dist_view(c, s, rebuild == REBUILD_NOW, p->x, &v, err)
                                       : SPALL_OK;
    if (rc)
        return rc;
    if (rebuild == REBUILD_NOW) {
        rc = reserve(c, v.n, 0, err);
        if (!rc)
            rc = build_candidates(c, s, &v, err);
        if (s->par)
            rc = par_agree(rc, err);
        if (rc)
            return rc;
        c->rebuilds++;
    }
    /* non-finite positions (the lists were not built): the integrator reports them */
    int skip = c->n_built != no;
    if (s->par)
        skip = par_max_double(skip) > 0.0;
    if (skip)
        return SPALL_OK;
    const double dc = c->prm.distance, k = c->prm.stiffness, ex = c->prm.exponent;
    const double d2 = dc * dc;
    const double rn1 = 1.0 / (ex + 1.0);
    double *const *x = v.x;
#pragma omp parallel for schedule(static) if (no > SPALL_OMP_MIN_PARTICLES)
    for (size_t i = 0; i < no; i++) {
        double fi[3] = {0, 0, 0}, e = 0.0;
        uint32_t np = 0;
        for (size_t q = c->off[i]; q < c->off[i + 1]; q++) {
            size_t j = (size_t)c->nbr[q];
            double dx[3] = {0, 0, 0}, r2 = 0.0;
            for (int d = 0; d < dim; d++) {
                dx[d] = x[d][j] - x[d][i];
                r2 += dx[d] * dx[d];
            }
            if (!(r2 < d2) || r2 == 0.0)
                continue;
            double r = sqrt(r2);
            double u = (dc - r) / dc; /* overlap delta / d in (0, 1] */
            double un = ex == 1.0 ? u : pow(u, ex);
            double F = k * dc * un; /* repulsive magnitude */
            e += 0.5 * k * dc * dc * un * u * rn1;
            np++;
            for (int d = 0; d < dim; d++)
                fi[d] -= F * dx[d] / r;
        }
        for (int d = 0; d < dim; d++)
            p->f[d][i] += fi[d];
        c->epart[i] = e;
        c->npart[i] = np;
    }
    /* exact sums and integer counts: diagnostics identical for any thread
     * and rank count (collective when distributed) */
    struct xsum acc;
    xsum_init(&acc);
    uint64_t npairs = 0;
    for (size_t i = 0; i < no; i++) {
        xsum_add(&acc, c->epart[i]);
        npairs += c->npart[i];
    }
    par_xsum_finish(s, &acc, 1, &c->energy);
    if (s->par)
        npairs = par_sum_u64(npairs);
    c->pairs = (size_t)(npairs / 2);
    return SPALL_OK;
}

double particle_contact_energy(const struct sim *s)
{
    return s->pcontact ? s->pcontact->energy : 0.0;
}

size_t particle_contact_pairs(const struct sim *s)
{
    return s->pcontact ? s->pcontact->pairs : 0;
}

double particle_contact_stable_dt(const struct sim *s)
{
    const struct particle_contact *c = s->pcontact;
    if (!c || s->p->n_owned == 0)
        return INFINITY;
    double m_min = INFINITY;
    for (size_t i = 0; i < s->p->n_owned; i++)
        m_min = fmin(m_min, s->p->mass[i]);
    const double z = s->dim == 1 ? 2.0 : s->dim == 2 ? 6.0 : 12.0;
    double omega2 = 2.0 * z * c->prm.exponent * c->prm.stiffness / m_min;
    return 2.0 / sqrt(omega2);
}

/* ---- restart state (core/field_state.h) ---------------------------------- */

static size_t cand_rows(const void *ctx)
{
    const struct particle_contact *c = ctx;
    return c->n_built ? c->off[c->n_built] : 0;
}

static int cand_set_rows(void *ctx, size_t rows, struct spall_error *err)
{
    struct particle_contact *c = ctx;
    if (rows > c->nbr_cap) {
        int32_t *q = realloc(c->nbr, rows * sizeof *q);
        if (!q)
            return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory (contact restart)");
        c->nbr = q;
        c->nbr_cap = rows;
    }
    return cand_rows(c) == rows ? SPALL_OK
                                : spall_error_set(err, SPALL_ERR_INPUT,
                                                  "contact candidate list: %zu entries, its "
                                                  "offsets say %zu",
                                                  rows, cand_rows(c));
}

void **particle_contact_built_at(struct particle_contact *c, int d)
{
    return (void **)&c->xref[d];
}

/* A distributed checkpoint: the lists must be those of the owned set (a
 * rebalance may have just moved particles), and the candidates are written
 * by global id (the serial file's candidate of a row is its index there,
 * which is the gid).  Collective. */
static int dist_checkpoint_lists(struct particle_contact *c, struct sim *s,
                                 struct spall_error *err)
{
    const long reb = par_layouts(s);
    int rc = SPALL_OK;
    if (relaid_out(c, s, reb)) {
        struct cview v;
        rc = rebuild_at_ref(c, s, &v, err);
        c->layouts = reb;
    }
    if (rc)
        return rc;
    const size_t no = s->p->n_owned, ns = c->n_built == no ? c->off[no] : 0;
    int32_t *g = realloc(c->ck_gid, (ns ? ns : 1) * sizeof *g);
    if (!g)
        rc = spall_error_set(err, SPALL_ERR_NOMEM, "out of memory (contact checkpoint)");
    else
        c->ck_gid = g;
    for (size_t q = 0; q < ns && !rc; q++)
        c->ck_gid[q] = (int32_t)c->vgid[c->nbr[q]];
    return par_agree(rc, err);
}

int particle_contact_register_state(struct sim *s, struct field_state *fs, struct spall_error *err)
{
    struct particle_contact *c = s->pcontact;
    if (!c)
        return SPALL_OK;
    int rc = s->par ? dist_checkpoint_lists(c, s, err) : SPALL_OK;
    if (rc)
        return rc;
    /* the candidate lists with the positions they were built at: a list
     * rebuilt at another step would order the pair sums differently */
    const size_t no = s->p->n_owned;
    if (c->n_built != no)
        return spall_error_set(err, SPALL_ERR_INTERNAL, "contact lists not built");
    c->ckbl = (struct bond_list){.n = no, .offset = c->off, .partner = c->nbr};
    rc = field_state_add_offsets(fs, "contact.offset", (void **)&c->off, &c->ckbl, err);
    if (!rc)
        rc = field_state_add_bond_list(fs, "contact.candidates", FIELD_I32,
                                       s->par ? (void **)&c->ck_gid : (void **)&c->nbr, &c->ckbl,
                                       1, cand_set_rows, c, err);
    char nm[FIELD_STATE_NAME_LEN];
    for (int d = 0; d < s->dim && !rc; d++) {
        snprintf(nm, sizeof nm, "contact.built_at.%d", d);
        rc = field_state_add_particle_array(fs, nm, FIELD_F64, (void **)&c->xref[d], no, 1, err);
    }
    if (!rc)
        rc = field_state_add_values(fs, "contact.rebuilds", FIELD_I64, &c->rebuilds, 1, err);
    if (!rc)
        rc = field_state_add_values(fs, "contact.energy", FIELD_F64, &c->energy, 1, err);
    if (!rc)
        rc = field_state_add_values(fs, "contact.pairs", FIELD_I64, &c->pairs, 1, err);
    return rc;
}
