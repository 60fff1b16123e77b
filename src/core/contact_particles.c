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
#include "core/particles.h"
#include "core/sim.h"
#include "core/model.h"
#include "spall/error.h"

#include <math.h>
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
    size_t n_built;      /* particles at the last build (0: never built) */
    size_t rebuilds;
    double energy;
    size_t pairs;
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
        int bad = !a || !b || !e || !q || !o;
        for (int d = 0; d < 3; d++) {
            double *x = realloc(c->xref[d], n * sizeof *x);
            if (x)
                c->xref[d] = x;
            bad |= !x;
        }
        if (bad)
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
static inline int bonded(const struct bond_list *bl, size_t i, size_t j)
{
    if (!bl || i >= bl->n)
        return 0;
    const int32_t jj = (int32_t)j;
    for (size_t k = bl->offset[i]; k < bl->offset[i + 1]; k++)
        if (bl->partner[k] == jj)
            return 1;
    return 0;
}

/* Candidate lists (CSR over owned particles): every eligible partner j
 * within d + skin of i at build time, in cell order.  Eligible = not in the
 * model's bond list (fixed for the run, so the eligibility of a pair never
 * changes) and, for models without one, of another body.  Built with a cell list of edge
 * >= d + skin over the current bounding box (cells <= 4 n + 64), two passes
 * (count, fill) gathered per particle: the same lists for any thread count. */
static int build_candidates(struct particle_contact *c, const struct sim *s,
                            struct spall_error *err)
{
    const struct particles *p = s->p;
    const int dim = s->dim;
    const size_t n = p->n, no = p->n_owned;
    const double reach = c->prm.distance + c->skin;
    double lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
    for (int d = 0; d < dim; d++) {
        lo[d] = INFINITY;
        hi[d] = -INFINITY;
        for (size_t i = 0; i < n; i++) {
            lo[d] = fmin(lo[d], p->x[d][i]);
            hi[d] = fmax(hi[d], p->x[d][i]);
        }
        if (!isfinite(lo[d]) || !isfinite(hi[d]))
            return SPALL_OK; /* the integrator reports the non-finite particle */
    }
    double h = reach;
    size_t nc[3] = {1, 1, 1}, ncell = 1;
    for (;;) {
        ncell = 1;
        for (int d = 0; d < dim; d++) {
            nc[d] = (size_t)floor((hi[d] - lo[d]) / h) + 1;
            ncell *= nc[d];
        }
        if (ncell <= 4 * n + 64)
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
            size_t q = (size_t)floor((p->x[d][i] - lo[d]) / h);
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
    const int32_t *body = p->body;
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
                size_t q = (size_t)floor((p->x[d][i] - lo[d]) / h);
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
                                double dx = p->x[d][j] - p->x[d][i];
                                r2 += dx * dx;
                            }
                            if (!(r2 < r2max))
                                continue;
                            /* bonded pairs (any body, e.g. a peridynamic
                             * family reaching into another body) are the
                             * model's; unbonded ones of one body only in
                             * bonded models */
                            const int32_t bj = body ? body[j] : 0;
                            if ((bi == bj && !bl) || bonded(bl, i, j))
                                continue;
                            if (pass)
                                c->nbr[w++] = (int32_t)j;
                            cnt++;
                        }
                    }
            c->npart[i] = cnt;
        }
    }
    for (int d = 0; d < dim; d++)
        memcpy(c->xref[d], p->x[d], n * sizeof(double));
    c->n_built = n;
    return SPALL_OK;
}

/* True when some particle moved more than skin/2 since the lists were built
 * (then a pair could have come from beyond d + skin to within d).  max is
 * exact, so the answer does not depend on the thread count. */
static int needs_rebuild(const struct particle_contact *c, const struct sim *s)
{
    const struct particles *p = s->p;
    if (c->n_built != p->n)
        return 1;
    const double lim = 0.25 * c->skin * c->skin;
    double m2 = 0.0;
    const size_t n = p->n;
    const int dim = s->dim;
#pragma omp parallel for schedule(static) reduction(max : m2) if (n > SPALL_OMP_MIN_PARTICLES)
    for (size_t i = 0; i < n; i++) {
        double r2 = 0.0;
        for (int d = 0; d < dim; d++) {
            double dx = p->x[d][i] - c->xref[d][i];
            r2 += dx * dx;
        }
        m2 = r2 > m2 ? r2 : m2;
    }
    return !(m2 <= lim); /* a NaN forces a rebuild */
}

int particle_contact_forces(struct sim *s, struct spall_error *err)
{
    struct particle_contact *c = s->pcontact;
    if (!c)
        return SPALL_OK;
    struct particles *p = s->p;
    const int dim = s->dim;
    const size_t n = p->n, no = p->n_owned;
    c->energy = 0.0;
    c->pairs = 0;
    if (n < 2)
        return SPALL_OK;
    if (needs_rebuild(c, s)) {
        int rc = reserve(c, n, 0, err);
        if (rc || (rc = build_candidates(c, s, err)))
            return rc;
        c->rebuilds++;
    }
    if (c->n_built != n)
        return SPALL_OK; /* non-finite positions: the integrator reports them */
    const double dc = c->prm.distance, k = c->prm.stiffness, ex = c->prm.exponent;
    const double d2 = dc * dc;
    const double rn1 = 1.0 / (ex + 1.0);
#pragma omp parallel for schedule(static) if (no > SPALL_OMP_MIN_PARTICLES)
    for (size_t i = 0; i < no; i++) {
        double fi[3] = {0, 0, 0}, e = 0.0;
        uint32_t np = 0;
        for (size_t q = c->off[i]; q < c->off[i + 1]; q++) {
            size_t j = (size_t)c->nbr[q];
            double dx[3] = {0, 0, 0}, r2 = 0.0;
            for (int d = 0; d < dim; d++) {
                dx[d] = p->x[d][j] - p->x[d][i];
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
    /* fixed-order sums: diagnostics identical for any thread count */
    double etot = 0.0;
    size_t npairs = 0;
    for (size_t i = 0; i < no; i++) {
        etot += c->epart[i];
        npairs += c->npart[i];
    }
    c->energy = etot;
    c->pairs = npairs / 2;
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

int particle_contact_register_state(struct sim *s, struct field_state *fs, struct spall_error *err)
{
    struct particle_contact *c = s->pcontact;
    if (!c)
        return SPALL_OK;
    /* the candidate lists with the positions they were built at: a list
     * rebuilt at another step would order the pair sums differently */
    if (c->n_built != s->p->n)
        return spall_error_set(err, SPALL_ERR_INTERNAL, "contact lists not built");
    size_t n = c->n_built;
    int rc = field_state_add_array(fs, "contact.offset", FIELD_I64, (void **)&c->off, n + 1, 1,
                                   err);
    if (!rc)
        rc = field_state_add_list(fs, "contact.candidates", FIELD_I32, (void **)&c->nbr, 1,
                                  cand_rows, cand_set_rows, c, err);
    char nm[FIELD_STATE_NAME_LEN];
    for (int d = 0; d < s->dim && !rc; d++) {
        snprintf(nm, sizeof nm, "contact.built_at.%d", d);
        rc = field_state_add_array(fs, nm, FIELD_F64, (void **)&c->xref[d], n, 1, err);
    }
    if (!rc)
        rc = field_state_add_values(fs, "contact.rebuilds", FIELD_I64, &c->rebuilds, 1, err);
    if (!rc)
        rc = field_state_add_values(fs, "contact.energy", FIELD_F64, &c->energy, 1, err);
    if (!rc)
        rc = field_state_add_values(fs, "contact.pairs", FIELD_I64, &c->pairs, 1, err);
    return rc;
}
