/**
 * @file lattice_gen.c
 * @brief Fill a region with lattice sites (see lattice_gen.h).
 *
 * Every lattice is enumerated on an integer grid in its own frame, which is
 * then mapped to space:
 *  - chain:      x = i r0
 *  - triangular: x = (i + (j mod 2)/2) r0, y = j (sqrt(3)/2) r0, rotated by `angle`
 *  - square:     x = i r0, y = j r0, rotated by `angle`
 *  - sc:         (i, j, k) r0
 *  - fcc:        (i, j, k) a/2 with i + j + k even, a = sqrt(2) r0 — the same
 *                set as the cubic cell with its 4-site basis, but enumerated
 *                row by row so the order is strictly x-fastest.
 * The index ranges cover the region's bounding box (mapped into the lattice
 * frame for rotated 2D lattices); geom_contains decides which sites are kept.
 */
#include "core/lattice_gen.h"

#include "core/geometry.h"
#include "core/lattice_polar.h"
#include "core/particles.h"
#include "spall/error.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/** Largest lattice index from the origin (the (long) conversion must be defined). */
#define LATTICE_MAX_INDEX 1.0e15

/* The deck's names of the lattice kinds, in the order of enum lattice_kind. */
static const char *const lattice_names[] = {"chain", "triangular", "square", "sc", "fcc",
                                            "triple_honeycomb", "rings", "shells", NULL};
#define N_LATTICE_KINDS ((int)(sizeof lattice_names / sizeof lattice_names[0]) - 1)

/** The triple honeycomb has the triangular lattice's sites and shells. */
static enum lattice_kind geometry_kind(enum lattice_kind kind)
{
    return kind == LATTICE_TRIPLE_HONEYCOMB ? LATTICE_TRIANGULAR : kind;
}

int lattice_kind_from_name(const char *name)
{
    if (!name)
        return -1;
    for (int k = 0; k < N_LATTICE_KINDS; k++)
        if (strcmp(name, lattice_names[k]) == 0)
            return k;
    return -1;
}

const char *lattice_kind_name(enum lattice_kind kind)
{
    if ((int)kind < 0 || (int)kind >= N_LATTICE_KINDS)
        return "unknown";
    return lattice_names[kind];
}

const char *const *lattice_kind_names(void)
{
    return lattice_names;
}

int lattice_kind_dim(enum lattice_kind kind)
{
    switch (kind) {
    case LATTICE_CHAIN:
        return 1;
    case LATTICE_TRIANGULAR:
    case LATTICE_SQUARE:
    case LATTICE_TRIPLE_HONEYCOMB:
    case LATTICE_RINGS:
        return 2;
    case LATTICE_SC:
    case LATTICE_FCC:
    case LATTICE_SHELLS:
        return 3;
    }
    return 0;
}

/** Grid step per axis in the lattice frame (before rotation). */
static void lattice_steps(const struct lattice_spec *s, double step[3])
{
    double r0 = s->spacing;
    step[0] = step[1] = step[2] = r0;
    if (geometry_kind(s->kind) == LATTICE_TRIANGULAR)
        step[1] = r0 * sqrt(3.0) / 2.0;
    if (s->kind == LATTICE_FCC)
        step[0] = step[1] = step[2] = r0 * sqrt(2.0) / 2.0; /* a/2 */
}

/** Site (i,j,k) in lattice-frame coordinates relative to the origin;
 *  returns false if the index triple is not a site (FCC parity). */
static bool lattice_local(const struct lattice_spec *s, const double step[3], long i, long j,
                          long k, double loc[3])
{
    loc[0] = (double)i * step[0];
    loc[1] = (double)j * step[1];
    loc[2] = (double)k * step[2];
    switch (geometry_kind(s->kind)) {
    case LATTICE_TRIANGULAR:
        if (j % 2 != 0) /* odd rows (also negative ones) shifted by r0/2 */
            loc[0] = ((double)i + 0.5) * step[0];
        return true;
    case LATTICE_FCC:
        return (i + j + k) % 2 == 0;
    default:
        return true;
    }
}

/** Site position of index (i, j, k) in space; false when not a site. */
static bool site_position(const struct lattice_spec *spec, const double step[3], bool rotated,
                          double ca, double sa, long i, long j, long k, double pos[3])
{
    double loc[3];
    if (!lattice_local(spec, step, i, j, k, loc))
        return false;
    memcpy(pos, spec->origin, 3 * sizeof(double));
    if (rotated) {
        pos[0] += ca * loc[0] - sa * loc[1];
        pos[1] += sa * loc[0] + ca * loc[1];
    } else {
        for (int d = 0; d < lattice_kind_dim(spec->kind); d++)
            pos[d] += loc[d];
    }
    return true;
}

/** Estimated number of sites of the index box inside @p region: the kept
 *  fraction of a regular sub-grid of at most 64 points per axis. */
static double estimate_sites(const struct lattice_spec *spec, const struct geom *region, int dim,
                             const double step[3], bool rotated, double ca, double sa,
                             const long imin[3], const long imax[3], double candidates)
{
    enum { SAMPLES = 64 };
    long n[3], len[3];
    for (int d = 0; d < 3; d++) {
        len[d] = imax[d] - imin[d] + 1;
        n[d] = len[d] < SAMPLES ? len[d] : SAMPLES;
    }
    double hit = 0.0, tried = 0.0;
    for (long c = 0; c < n[2]; c++)
        for (long b = 0; b < n[1]; b++)
            for (long a = 0; a < n[0]; a++) {
                double pos[3];
                tried += 1.0;
                /* odd offsets so FCC parity and row shifts are sampled too */
                long i = imin[0] + a * len[0] / n[0] + (b + c) % 2; /* evenly spread */
                long j = imin[1] + b * len[1] / n[1], k = imin[2] + c * len[2] / n[2];
                if (site_position(spec, step, rotated, ca, sa, i, j, k, pos) &&
                    geom_contains(region, pos, dim))
                    hit += 1.0;
            }
    return tried > 0.0 ? candidates * hit / tried : candidates;
}

/* The index box of a fill: everything lattice_fill needs before it
 * enumerates (checked spacing and region, steps, rotation, index ranges). */
struct fill_box {
    int ldim, dim;
    double step[3];
    bool rotated;
    double ca, sa;
    long imin[3], imax[3];
    double candidates, limit;
};

/* The checks every fill starts with; the region's bounding box. */
static int fill_bounds(const struct particles *p, const struct lattice_spec *spec,
                       const struct geom *region, double lo[3], double hi[3],
                       struct spall_error *err)
{
    int ldim = lattice_kind_dim(spec->kind);
    if (ldim == 0)
        return spall_error_set(err, SPALL_ERR_INPUT, "unknown lattice kind %d", (int)spec->kind);
    if (!(spec->spacing > 0.0) || !isfinite(spec->spacing))
        return spall_error_set(err, SPALL_ERR_INPUT, "lattice spacing must be positive (got %g m)",
                               spec->spacing);
    if (p->dim < ldim)
        return spall_error_set(err, SPALL_ERR_INPUT,
                               "%s lattice is %dD but the particles are %dD",
                               lattice_kind_name(spec->kind), ldim, p->dim);
    if (!geom_bounds(region, p->dim, lo, hi))
        return spall_error_set(err, SPALL_ERR_INPUT,
                               "region is unbounded (intersect a half-space with a bounded shape)");
    for (int d = 0; d < p->dim; d++)
        if (!isfinite(lo[d]) || !isfinite(hi[d]))
            return spall_error_set(err, SPALL_ERR_INPUT, "region has a non-finite bounding box");
    return SPALL_OK;
}

static int fill_box_make(const struct particles *p, const struct lattice_spec *spec,
                         const struct geom *region, struct fill_box *b, struct spall_error *err)
{
    memset(b, 0, sizeof *b);
    double lo[3], hi[3];
    int rc = fill_bounds(p, spec, region, lo, hi, err);
    if (rc)
        return rc;
    int ldim = lattice_kind_dim(spec->kind);
    b->ldim = ldim;
    b->dim = p->dim;
    b->limit = p->max_n ? (double)p->max_n : SPALL_MAX_PARTICLES_DEFAULT;
    lattice_steps(spec, b->step);
    b->rotated = ldim == 2 && spec->angle != 0.0;
    b->ca = b->rotated ? cos(spec->angle) : 1.0;
    b->sa = b->rotated ? sin(spec->angle) : 0.0;

    /* Bounding box in the lattice frame: map the corners of the spatial box
     * (only x,y rotate; for 1D/3D lattices this is a plain shift). */
    double llo[3] = {0, 0, 0}, lhi[3] = {0, 0, 0};
    if (b->rotated) {
        for (int c = 0; c < 4; c++) {
            double X = ((c & 1) ? hi[0] : lo[0]) - spec->origin[0];
            double Y = ((c & 2) ? hi[1] : lo[1]) - spec->origin[1];
            double u = b->ca * X + b->sa * Y, v = -b->sa * X + b->ca * Y; /* R(-angle) */
            llo[0] = c ? fmin(llo[0], u) : u;
            lhi[0] = c ? fmax(lhi[0], u) : u;
            llo[1] = c ? fmin(llo[1], v) : v;
            lhi[1] = c ? fmax(lhi[1], v) : v;
        }
    } else {
        for (int d = 0; d < ldim; d++) {
            llo[d] = lo[d] - spec->origin[d];
            lhi[d] = hi[d] - spec->origin[d];
        }
    }
    /* Index ranges padded by one step (the triangular row shift and rounding). */
    b->candidates = 1.0;
    for (int d = 0; d < ldim; d++) {
        double a = floor(llo[d] / b->step[d]) - 1.0, e = ceil(lhi[d] / b->step[d]) + 1.0;
        if (!(e >= a)) /* an empty bounding box (disjoint intersection) */
            return spall_error_set(err, SPALL_ERR_INPUT,
                                   "contains no lattice site (%s, spacing %g m): its bounding box "
                                   "is empty",
                                   lattice_kind_name(spec->kind), spec->spacing);
        if (!(fabs(a) < LATTICE_MAX_INDEX && fabs(e) < LATTICE_MAX_INDEX))
            return spall_error_set(err, SPALL_ERR_INPUT,
                                   "lies %.3g lattice steps from the lattice origin (spacing %g m); "
                                   "expected at most %.0e",
                                   fmax(fabs(a), fabs(e)), spec->spacing, LATTICE_MAX_INDEX);
        if (!(e - a < LATTICE_MAX_CANDIDATES))
            return spall_error_set(err, SPALL_ERR_INPUT,
                                   "region is too large for lattice spacing %g m", spec->spacing);
        b->candidates *= e - a + 1.0;
        b->imin[d] = (long)a;
        b->imax[d] = (long)e;
    }
    if (b->candidates > LATTICE_MAX_CANDIDATES)
        return spall_error_set(err, SPALL_ERR_INPUT,
                               "region would need %.3g lattice candidates at spacing %g m",
                               b->candidates, spec->spacing);
    return SPALL_OK;
}

static int limit_error(double n, const struct lattice_spec *spec, double limit,
                       struct spall_error *err)
{
    return spall_error_set(err, SPALL_ERR_INPUT,
                           "would hold about %.3g particles at lattice spacing %g m, more "
                           "than the limit of %.3g (run.max_particles); coarsen the "
                           "spacing or raise the limit",
                           n, spec->spacing, limit);
}

/* Append the sites of the outer index layers [l0, l1) (layer = the last
 * lattice axis's index - imin) in the generation order. */
static int fill_layers(struct particles *p, const struct lattice_spec *spec,
                       const struct geom *region, int32_t material, const struct fill_box *b,
                       long l0, long l1, double limit, size_t *added, struct spall_error *err)
{
    const int od = b->ldim - 1; /* the outermost loop's axis */
    long lo[3], hi[3];
    memcpy(lo, b->imin, sizeof lo);
    memcpy(hi, b->imax, sizeof hi);
    lo[od] = b->imin[od] + l0;
    hi[od] = b->imin[od] + l1 - 1;
    for (long k = lo[2]; k <= hi[2]; k++) {
        for (long j = lo[1]; j <= hi[1]; j++) {
            for (long i = lo[0]; i <= hi[0]; i++) {
                double pos[3];
                if (!site_position(spec, b->step, b->rotated, b->ca, b->sa, i, j, k, pos) ||
                    !geom_contains(region, pos, b->dim))
                    continue;
                int rc = lattice_append_site(p, pos, material, limit, spec->spacing, err);
                if (rc)
                    return rc;
                (*added)++;
            }
        }
    }
    return SPALL_OK;
}

int lattice_fill(struct particles *p, const struct lattice_spec *spec, const struct geom *region,
                 int32_t material, size_t *n_added, struct spall_error *err)
{
    if (n_added)
        *n_added = 0;
    struct fill_box b;
    if (lattice_kind_is_polar(spec->kind)) {
        double lo[3], hi[3];
        int rc = fill_bounds(p, spec, region, lo, hi, err);
        if (rc)
            return rc;
        double limit = p->max_n ? (double)p->max_n : SPALL_MAX_PARTICLES_DEFAULT;
        size_t polar_added = 0;
        rc = lattice_polar_fill(p, spec, region, lo, hi, limit, material, &polar_added, err);
        if (n_added)
            *n_added = polar_added;
        return rc;
    }
    int rc = fill_box_make(p, spec, region, &b, err);
    if (rc)
        return rc;
    /* Refuse a fill beyond the particle limit before allocating: the kept
     * fraction of the candidates, estimated on a regular sub-grid. */
    if ((double)p->n + b.candidates > b.limit) {
        double est = estimate_sites(spec, region, b.dim, b.step, b.rotated, b.ca, b.sa, b.imin,
                                    b.imax, b.candidates);
        if ((double)p->n + est > b.limit)
            return limit_error((double)p->n + est, spec, b.limit, err);
    }
    const int od = b.ldim - 1;
    size_t added = 0;
    rc = fill_layers(p, spec, region, material, &b, 0, b.imax[od] - b.imin[od] + 1, b.limit,
                     &added, err);
    if (n_added)
        *n_added = added;
    if (rc)
        return rc;
    if (added == 0)
        return spall_error_set(err, SPALL_ERR_INPUT, "contains no lattice site (%s, spacing %g m)",
                               lattice_kind_name(spec->kind), spec->spacing);
    return SPALL_OK;
}

void lattice_split_layers(const size_t *cnt, size_t n_layers, int size, size_t *first)
{
    size_t total = 0;
    for (size_t l = 0; l < n_layers; l++)
        total += cnt[l];
    /* rank r starts at the first layer whose preceding sites reach r N / P:
     * contiguous blocks, balanced by count to within one layer */
    size_t l = 0, acc = 0;
    first[0] = 0;
    for (int r = 1; r < size; r++) {
        const double target = (double)total * (double)r / (double)size;
        while (l < n_layers && (double)(acc + cnt[l]) <= target) {
            acc += cnt[l];
            l++;
        }
        first[r] = l;
    }
    first[size] = n_layers;
}

int lattice_fill_window(struct particles *p, const struct lattice_spec *spec,
                        const struct geom *region, int32_t material, struct lattice_window *w,
                        struct spall_error *err)
{
    w->gid_first = 0;
    w->n_below = w->n_own = w->n_total = 0;
    if (lattice_kind_is_polar(spec->kind) || w->size < 1 || w->rank < 0 || w->rank >= w->size)
        return spall_error_set(err, SPALL_ERR_INTERNAL, "lattice window: not for %s lattices",
                               lattice_kind_name(spec->kind));
    struct fill_box b;
    int rc = fill_box_make(p, spec, region, &b, err);
    if (rc)
        return rc;
    const int od = b.ldim - 1;
    const size_t nl = (size_t)(b.imax[od] - b.imin[od] + 1);
    size_t *cnt = calloc(nl, sizeof *cnt), *first = malloc(((size_t)w->size + 1) * sizeof *first);
    if (!cnt || !first) {
        free(cnt);
        free(first);
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory counting lattice sites");
    }
    /* pass 1, on every rank: the sites of each outer layer (positions only,
     * nothing stored), so every rank knows the whole split and each site's
     * global id = its place in the serial generation order */
    for (long k = b.imin[2]; k <= b.imax[2]; k++)
        for (long j = b.imin[1]; j <= b.imax[1]; j++)
            for (long i = b.imin[0]; i <= b.imax[0]; i++) {
                double pos[3];
                if (site_position(spec, b.step, b.rotated, b.ca, b.sa, i, j, k, pos) &&
                    geom_contains(region, pos, b.dim)) {
                    const long idx[3] = {i, j, k};
                    cnt[idx[od] - b.imin[od]]++;
                }
            }
    size_t total = 0;
    for (size_t l = 0; l < nl; l++)
        total += cnt[l];
    w->n_total = total;
    if (total == 0)
        rc = spall_error_set(err, SPALL_ERR_INPUT, "contains no lattice site (%s, spacing %g m)",
                             lattice_kind_name(spec->kind), spec->spacing);
    else if ((double)w->n_prior + (double)total > b.limit)
        rc = limit_error((double)w->n_prior + (double)total, spec, b.limit, err);
    if (!rc) {
        lattice_split_layers(cnt, nl, w->size, first);
        /* the halo: whole layers within w->halo of the rank's own ones (a
         * layer is step[od] thick, rotation included: rows stay rows) */
        const size_t h = (size_t)ceil(w->halo / b.step[od]) + 1;
        const size_t o0 = first[w->rank], o1 = first[w->rank + 1];
        const size_t l0 = o0 > h ? o0 - h : 0, l1 = o1 + h < nl ? o1 + h : nl;
        size_t before = 0;
        for (size_t l = 0; l < l0; l++)
            before += cnt[l];
        for (size_t l = l0; l < o0; l++)
            w->n_below += cnt[l];
        for (size_t l = o0; l < o1; l++)
            w->n_own += cnt[l];
        w->gid_first = (int64_t)before;
        /* the window's sites are counted: reserve them at once (appending
         * one by one doubles the arrays past them, up to twice the
         * window's particle memory at the set-up's peak) */
        size_t n_win = 0;
        for (size_t l = l0; l < l1; l++)
            n_win += cnt[l];
        rc = particles_reserve(p, p->n + n_win, err);
        size_t added = 0;
        /* the limit is the whole body's (checked above), not this rank's */
        if (!rc)
            rc = fill_layers(p, spec, region, material, &b, (long)l0, (long)l1, INFINITY,
                             &added, err);
    }
    free(cnt);
    free(first);
    return rc;
}

int lattice_append_site(struct particles *p, const double pos[3], int32_t material, double limit,
                        double spacing, struct spall_error *err)
{
    if ((double)p->n >= limit)
        return spall_error_set(err, SPALL_ERR_INPUT,
                               "holds more than the limit of %.3g particles (run.max_particles) at "
                               "lattice spacing %g m; coarsen the spacing or raise the limit",
                               limit, spacing);
    return particles_append(p, pos, material, NULL, err);
}

/* Shell radii in units of r0 and their populations for a bulk site.
 * Triangular: 1, sqrt3, 2, sqrt7, 3.  Square: 1, sqrt2, 2, sqrt5.
 * SC: 1, sqrt2, sqrt3, 2.  FCC: 1, sqrt2 (= a), sqrt3, 2. */
#define LATTICE_MAX_SHELL 5

static double shell_factor(enum lattice_kind kind, int shell)
{
    static const double tri[LATTICE_MAX_SHELL] = {1.0, 1.7320508075688772, 2.0,
                                                  2.6457513110645907, 3.0};
    static const double sq[LATTICE_MAX_SHELL] = {1.0, 1.4142135623730951, 2.0,
                                                 2.2360679774997898, 0.0};
    static const double sc[LATTICE_MAX_SHELL] = {1.0, 1.4142135623730951, 1.7320508075688772,
                                                 2.0, 0.0};
    static const double fcc[LATTICE_MAX_SHELL] = {1.0, 1.4142135623730951, 1.7320508075688772,
                                                  2.0, 0.0};
    if (shell < 1)
        return 0.0;
    if (kind == LATTICE_CHAIN)
        return (double)shell;
    if (shell > LATTICE_MAX_SHELL)
        return 0.0;
    switch (geometry_kind(kind)) {
    case LATTICE_TRIANGULAR:
        return tri[shell - 1];
    case LATTICE_SQUARE:
        return sq[shell - 1];
    case LATTICE_SC:
        return sc[shell - 1];
    case LATTICE_FCC:
        return fcc[shell - 1];
    default:
        return 0.0;
    }
}

double lattice_shell_distance(const struct lattice_spec *spec, int shell)
{
    return shell_factor(spec->kind, shell) * spec->spacing;
}

int lattice_shell_count(enum lattice_kind kind, int shell)
{
    static const int tri[LATTICE_MAX_SHELL] = {6, 6, 6, 12, 6};
    static const int sq[LATTICE_MAX_SHELL] = {4, 4, 4, 8, 0};
    static const int sc[LATTICE_MAX_SHELL] = {6, 12, 8, 6, 0};
    static const int fcc[LATTICE_MAX_SHELL] = {12, 6, 24, 12, 0};
    if (shell < 1)
        return 0;
    if (kind == LATTICE_CHAIN)
        return 2;
    if (shell > LATTICE_MAX_SHELL)
        return 0;
    switch (geometry_kind(kind)) {
    case LATTICE_TRIANGULAR:
        return tri[shell - 1];
    case LATTICE_SQUARE:
        return sq[shell - 1];
    case LATTICE_SC:
        return sc[shell - 1];
    case LATTICE_FCC:
        return fcc[shell - 1];
    default:
        return 0;
    }
}

double lattice_site_volume(const struct lattice_spec *spec, double thickness_or_area)
{
    double r0 = spec->spacing;
    switch (geometry_kind(spec->kind)) {
    case LATTICE_CHAIN:
        return r0 * thickness_or_area;
    case LATTICE_TRIANGULAR:
        /* Area of the hexagonal Voronoi cell, sqrt(3)/2 r0^2, times t; with
         * t = 2 r0/sqrt(3) this is r0^3, the paper's choice ([Wang2010]). */
        return sqrt(3.0) / 2.0 * r0 * r0 * thickness_or_area;
    case LATTICE_SQUARE:
    case LATTICE_RINGS:
        return r0 * r0 * thickness_or_area;
    case LATTICE_SC:
    case LATTICE_SHELLS:
        return r0 * r0 * r0;
    case LATTICE_FCC: {
        double a = sqrt(2.0) * r0; /* 4 sites per cubic cell */
        return a * a * a / 4.0;
    }
    default:
        break;
    }
    return 0.0;
}

double lattice_site_volume_at(const struct lattice_spec *spec, const double pos[3],
                              double thickness_or_area)
{
    if (lattice_kind_is_polar(spec->kind))
        return lattice_polar_site_volume(spec, pos, thickness_or_area);
    return lattice_site_volume(spec, thickness_or_area);
}

int lattice_sublattice(const struct lattice_spec *spec, const double pos[2])
{
    if (geometry_kind(spec->kind) != LATTICE_TRIANGULAR || !(spec->spacing > 0.0))
        return -1;
    /* back to the lattice frame, then oblique coordinates on a1 = (r0, 0),
     * a2 = (r0/2, sqrt3 r0/2): site = a a1 + b a2.  A step along a1 is
     * +1 in colour, along a2 (60 deg) -1, along a2 - a1 (120 deg) +1 again,
     * so colour = (a - b) mod 3 gives nearest neighbours different colours. */
    double X = pos[0] - spec->origin[0], Y = pos[1] - spec->origin[1];
    double ca = cos(spec->angle), sa = sin(spec->angle);
    double u = ca * X + sa * Y, v = -sa * X + ca * Y;
    double b = floor(v / (spec->spacing * sqrt(3.0) / 2.0) + 0.5);
    double a = floor(u / spec->spacing - 0.5 * b + 0.5);
    long c = (long)fmod(a - b, 3.0);
    return (int)((c + 3) % 3);
}
