/**
 * @file geometry.c
 * @brief Primitives, composites and pre-crack tests (see geometry.h).
 *
 * Boundary points count as inside: every primitive accepts points within
 * 1e-9 of its own size outside the exact surface, so lattice sites that fall
 * on a box face (x = lo + k r0 == hi) are kept despite rounding.
 */
#include "core/geometry.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/** Relative tolerance of geom_contains (fraction of the shape's size). */
#define GEOM_REL_TOL 1e-9
/** Relative tolerance of the orientation tests in precrack_cuts. */
#define PRECRACK_REL_TOL 1e-12

static struct geom *geom_alloc(enum geom_kind kind)
{
    struct geom *g = calloc(1, sizeof *g);
    if (g)
        g->kind = kind;
    return g;
}

struct geom *geom_box(const double lo[3], const double hi[3])
{
    struct geom *g = geom_alloc(GEOM_BOX);
    if (!g)
        return NULL;
    for (int d = 0; d < 3; d++) {
        /* Accept corners given in any order. */
        g->a[d] = fmin(lo[d], hi[d]);
        g->b[d] = fmax(lo[d], hi[d]);
    }
    return g;
}

struct geom *geom_sphere(const double center[3], double radius)
{
    struct geom *g = geom_alloc(GEOM_SPHERE);
    if (!g)
        return NULL;
    memcpy(g->a, center, sizeof g->a);
    g->radius = radius;
    return g;
}

struct geom *geom_cylinder(const double p0[3], const double p1[3], double radius)
{
    struct geom *g = geom_alloc(GEOM_CYLINDER);
    if (!g)
        return NULL;
    memcpy(g->a, p0, sizeof g->a);
    memcpy(g->b, p1, sizeof g->b);
    g->radius = radius;
    return g;
}

struct geom *geom_halfspace(const double point[3], const double normal[3])
{
    struct geom *g = geom_alloc(GEOM_HALFSPACE);
    if (!g)
        return NULL;
    memcpy(g->a, point, sizeof g->a);
    memcpy(g->b, normal, sizeof g->b);
    return g;
}

struct geom *geom_polygon(const double *xy, size_t n_vertices)
{
    struct geom *g = geom_alloc(GEOM_POLYGON);
    if (!g)
        return NULL;
    g->poly = malloc(2 * (n_vertices ? n_vertices : 1) * sizeof(double));
    if (!g->poly) {
        free(g);
        return NULL;
    }
    if (n_vertices)
        memcpy(g->poly, xy, 2 * n_vertices * sizeof(double));
    g->n_poly = n_vertices;
    return g;
}

struct geom *geom_combine(enum geom_kind kind, struct geom **children, size_t n)
{
    bool ok = (kind == GEOM_UNION || kind == GEOM_INTERSECTION || kind == GEOM_DIFFERENCE) &&
              n > 0 && children != NULL;
    for (size_t i = 0; ok && i < n; i++)
        ok = children[i] != NULL;
    struct geom *g = ok ? geom_alloc(kind) : NULL;
    if (g) {
        g->child = malloc(n * sizeof *g->child);
        if (!g->child) {
            free(g);
            g = NULL;
        }
    }
    if (!g) {
        /* Ownership was transferred: destroy the children on failure too. */
        for (size_t i = 0; children && i < n; i++)
            geom_destroy(&children[i]);
        return NULL;
    }
    memcpy(g->child, children, n * sizeof *g->child);
    g->n_child = n;
    return g;
}

struct geom *geom_clone(const struct geom *g)
{
    if (!g)
        return NULL;
    struct geom *c = geom_alloc(g->kind);
    if (!c)
        return NULL;
    memcpy(c->a, g->a, sizeof c->a);
    memcpy(c->b, g->b, sizeof c->b);
    c->radius = g->radius;
    if (g->poly) {
        size_t nv = g->n_poly ? g->n_poly : 1;
        c->poly = malloc(2 * nv * sizeof(double));
        if (!c->poly) {
            free(c);
            return NULL;
        }
        memcpy(c->poly, g->poly, 2 * nv * sizeof(double));
        c->n_poly = g->n_poly;
    }
    if (g->n_child) {
        c->child = calloc(g->n_child, sizeof *c->child);
        if (!c->child) {
            geom_destroy(&c);
            return NULL;
        }
        c->n_child = g->n_child;
        for (size_t i = 0; i < g->n_child; i++) {
            c->child[i] = geom_clone(g->child[i]);
            if (!c->child[i]) {
                geom_destroy(&c);
                return NULL;
            }
        }
    }
    return c;
}

void geom_destroy(struct geom **pg)
{
    if (!pg || !*pg)
        return;
    struct geom *g = *pg;
    for (size_t i = 0; i < g->n_child; i++)
        geom_destroy(&g->child[i]);
    free(g->child);
    free(g->poly);
    free(g);
    *pg = NULL;
}

/* ------------------------------------------------------------------ */
/* Point containment                                                   */
/* ------------------------------------------------------------------ */

static bool box_contains(const struct geom *g, const double x[3], int dim)
{
    double size = 0.0;
    for (int d = 0; d < dim; d++)
        size = fmax(size, g->b[d] - g->a[d]);
    double tol = GEOM_REL_TOL * size;
    for (int d = 0; d < dim; d++)
        if (!(x[d] >= g->a[d] - tol && x[d] <= g->b[d] + tol))
            return false;
    return true;
}

static bool sphere_contains(const struct geom *g, const double x[3], int dim)
{
    double r2 = 0.0;
    for (int d = 0; d < dim; d++) {
        double dx = x[d] - g->a[d];
        r2 += dx * dx;
    }
    double rt = g->radius * (1.0 + GEOM_REL_TOL);
    return g->radius >= 0.0 && r2 <= rt * rt;
}

static bool cylinder_contains(const struct geom *g, const double x[3], int dim)
{
    if (dim < 3) /* 2D: disc of `radius` around p0; 1D: interval. */
        return sphere_contains(g, x, dim);
    double u[3], w[3], len2 = 0.0, t = 0.0;
    for (int d = 0; d < 3; d++) {
        u[d] = g->b[d] - g->a[d];
        w[d] = x[d] - g->a[d];
        len2 += u[d] * u[d];
        t += w[d] * u[d];
    }
    double len = sqrt(len2);
    double tol = GEOM_REL_TOL * fmax(len, g->radius);
    if (g->radius < 0.0 || len2 == 0.0)
        return false;
    /* t/len is the axial coordinate measured from p0. */
    double axial = t / len;
    if (axial < -tol || axial > len + tol)
        return false;
    double rad2 = 0.0;
    for (int d = 0; d < 3; d++) {
        double rd = w[d] - u[d] * (t / len2);
        rad2 += rd * rd;
    }
    double rt = g->radius + tol;
    return rad2 <= rt * rt;
}

static bool halfspace_contains(const struct geom *g, const double x[3], int dim)
{
    double s = 0.0, nn = 0.0, scale = 0.0;
    for (int d = 0; d < dim; d++) {
        s += (x[d] - g->a[d]) * g->b[d];
        nn += g->b[d] * g->b[d];
        scale = fmax(scale, fmax(fabs(x[d]), fabs(g->a[d])));
    }
    if (nn == 0.0)
        return true; /* degenerate normal: the whole space */
    /* An unbounded shape has no size: the tolerance is relative to the
     * coordinates, which is what rounding of (x - point) scales with. */
    return s / sqrt(nn) <= GEOM_REL_TOL * scale;
}

/** Squared distance from point (px,py) to segment (ax,ay)-(bx,by). */
static double seg_dist2(double px, double py, double ax, double ay, double bx, double by)
{
    double ex = bx - ax, ey = by - ay;
    double wx = px - ax, wy = py - ay;
    double l2 = ex * ex + ey * ey;
    double t = l2 > 0.0 ? (wx * ex + wy * ey) / l2 : 0.0;
    t = fmin(1.0, fmax(0.0, t));
    double dx = wx - t * ex, dy = wy - t * ey;
    return dx * dx + dy * dy;
}

static bool polygon_contains(const struct geom *g, const double x[3], int dim)
{
    size_t n = g->n_poly;
    if (n < 3)
        return false;
    const double *v = g->poly;
    double px = x[0], py = dim >= 2 ? x[1] : 0.0;
    double xmin = v[0], xmax = v[0], ymin = v[1], ymax = v[1];
    for (size_t i = 1; i < n; i++) {
        xmin = fmin(xmin, v[2 * i]);
        xmax = fmax(xmax, v[2 * i]);
        ymin = fmin(ymin, v[2 * i + 1]);
        ymax = fmax(ymax, v[2 * i + 1]);
    }
    double tol = GEOM_REL_TOL * fmax(xmax - xmin, ymax - ymin);
    /* Boundary first, so points on an edge are inside whatever the ray says. */
    for (size_t i = 0, j = n - 1; i < n; j = i++) {
        if (seg_dist2(px, py, v[2 * j], v[2 * j + 1], v[2 * i], v[2 * i + 1]) <= tol * tol)
            return true;
    }
    /* Even-odd rule: count edges crossed by the ray from p towards +x. */
    bool in = false;
    for (size_t i = 0, j = n - 1; i < n; j = i++) {
        double xi = v[2 * i], yi = v[2 * i + 1], xj = v[2 * j], yj = v[2 * j + 1];
        if ((yi > py) != (yj > py)) {
            double xc = xi + (py - yi) * (xj - xi) / (yj - yi);
            if (px < xc)
                in = !in;
        }
    }
    return in;
}

bool geom_contains(const struct geom *g, const double x[3], int dim)
{
    if (!g)
        return false;
    switch (g->kind) {
    case GEOM_BOX:
        return box_contains(g, x, dim);
    case GEOM_SPHERE:
        return sphere_contains(g, x, dim);
    case GEOM_CYLINDER:
        return cylinder_contains(g, x, dim);
    case GEOM_HALFSPACE:
        return halfspace_contains(g, x, dim);
    case GEOM_POLYGON:
        return polygon_contains(g, x, dim);
    case GEOM_UNION:
        for (size_t i = 0; i < g->n_child; i++)
            if (geom_contains(g->child[i], x, dim))
                return true;
        return false;
    case GEOM_INTERSECTION:
        for (size_t i = 0; i < g->n_child; i++)
            if (!geom_contains(g->child[i], x, dim))
                return false;
        return g->n_child > 0;
    case GEOM_DIFFERENCE:
        if (g->n_child == 0 || !geom_contains(g->child[0], x, dim))
            return false;
        for (size_t i = 1; i < g->n_child; i++)
            if (geom_contains(g->child[i], x, dim))
                return false;
        return true;
    }
    return false;
}

/* ------------------------------------------------------------------ */
/* Bounding boxes                                                      */
/* ------------------------------------------------------------------ */

bool geom_bounds(const struct geom *g, int dim, double lo[3], double hi[3])
{
    for (int d = 0; d < 3; d++)
        lo[d] = hi[d] = 0.0;
    if (!g)
        return false;
    switch (g->kind) {
    case GEOM_BOX:
        for (int d = 0; d < dim; d++) {
            lo[d] = g->a[d];
            hi[d] = g->b[d];
        }
        return true;
    case GEOM_SPHERE:
        for (int d = 0; d < dim; d++) {
            lo[d] = g->a[d] - g->radius;
            hi[d] = g->a[d] + g->radius;
        }
        return true;
    case GEOM_CYLINDER:
        if (dim < 3) {
            for (int d = 0; d < dim; d++) {
                lo[d] = g->a[d] - g->radius;
                hi[d] = g->a[d] + g->radius;
            }
            return true;
        }
        /* Conservative: both end discs padded by the radius in every axis. */
        for (int d = 0; d < 3; d++) {
            lo[d] = fmin(g->a[d], g->b[d]) - g->radius;
            hi[d] = fmax(g->a[d], g->b[d]) + g->radius;
        }
        return true;
    case GEOM_HALFSPACE:
        return false;
    case GEOM_POLYGON:
        if (g->n_poly == 0 || dim > 2) /* in 3D the polygon is an infinite prism */
            return false;
        for (int d = 0; d < dim; d++) {
            lo[d] = hi[d] = g->poly[d];
            for (size_t i = 1; i < g->n_poly; i++) {
                lo[d] = fmin(lo[d], g->poly[2 * i + (size_t)d]);
                hi[d] = fmax(hi[d], g->poly[2 * i + (size_t)d]);
            }
        }
        return true;
    case GEOM_UNION:
        for (size_t i = 0; i < g->n_child; i++) {
            double clo[3], chi[3];
            if (!geom_bounds(g->child[i], dim, clo, chi))
                return false;
            for (int d = 0; d < dim; d++) {
                lo[d] = i ? fmin(lo[d], clo[d]) : clo[d];
                hi[d] = i ? fmax(hi[d], chi[d]) : chi[d];
            }
        }
        return g->n_child > 0;
    case GEOM_INTERSECTION: {
        bool any = false;
        for (size_t i = 0; i < g->n_child; i++) {
            double clo[3], chi[3];
            if (!geom_bounds(g->child[i], dim, clo, chi))
                continue; /* unbounded children do not limit the box */
            for (int d = 0; d < dim; d++) {
                lo[d] = any ? fmax(lo[d], clo[d]) : clo[d];
                hi[d] = any ? fmin(hi[d], chi[d]) : chi[d];
            }
            any = true;
        }
        return any;
    }
    case GEOM_DIFFERENCE:
        return g->n_child > 0 && geom_bounds(g->child[0], dim, lo, hi);
    }
    return false;
}

/* ------------------------------------------------------------------ */
/* Pre-cracks                                                          */
/* ------------------------------------------------------------------ */

/** Sign of v with |v| <= tol treated as zero. */
static int sign_tol(double v, double tol)
{
    return v > tol ? 1 : (v < -tol ? -1 : 0);
}

/** Orientation of c relative to the directed line a->b (2x cross product). */
static double orient2(const double a[2], const double b[2], const double c[2])
{
    return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
}

static bool cuts_2d(const struct precrack *c, const double xi[3], const double xj[3])
{
    const double A[2] = {c->a[0], c->a[1]}, B[2] = {c->b[0], c->b[1]};
    const double P[2] = {xi[0], xi[1]}, Q[2] = {xj[0], xj[1]};
    double lab = sqrt((B[0] - A[0]) * (B[0] - A[0]) + (B[1] - A[1]) * (B[1] - A[1]));
    double lpq = sqrt((Q[0] - P[0]) * (Q[0] - P[0]) + (Q[1] - P[1]) * (Q[1] - P[1]));
    double lmax = fmax(lab, lpq);
    /* |orient(A,B,P)| = |AB| * dist(P, line AB): tolerance relative to lengths. */
    double tol_ab = PRECRACK_REL_TOL * lab * lmax;
    double tol_pq = PRECRACK_REL_TOL * lpq * lmax;
    int s1 = sign_tol(orient2(A, B, P), tol_ab);
    int s2 = sign_tol(orient2(A, B, Q), tol_ab);
    int s3 = sign_tol(orient2(P, Q, A), tol_pq);
    int s4 = sign_tol(orient2(P, Q, B), tol_pq);
    /* Collinear bond and crack (or a zero-length one): the bond runs along
     * the crack line and is not separated by it. */
    if ((s1 == 0 && s2 == 0) || (s3 == 0 && s4 == 0))
        return false;
    /* Touching (one sign zero) counts as crossing. */
    return s1 * s2 <= 0 && s3 * s4 <= 0;
}

static bool cuts_3d(const struct precrack *c, const double xi[3], const double xj[3])
{
    const double *o = c->origin, *e1 = c->e1, *e2 = c->e2;
    double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                   e1[0] * e2[1] - e1[1] * e2[0]};
    double nn = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (nn == 0.0)
        return false; /* degenerate rectangle */
    double dp = 0.0, dq = 0.0, lpq2 = 0.0;
    for (int d = 0; d < 3; d++) {
        dp += (xi[d] - o[d]) * n[d];
        dq += (xj[d] - o[d]) * n[d];
        lpq2 += (xj[d] - xi[d]) * (xj[d] - xi[d]);
    }
    dp /= nn; /* signed distances to the plane */
    dq /= nn;
    double tol = PRECRACK_REL_TOL * sqrt(lpq2);
    int sp = sign_tol(dp, tol), sq = sign_tol(dq, tol);
    if (sp == 0 && sq == 0)
        return false; /* bond lies in the crack plane */
    if (sp * sq > 0)
        return false;
    /* Intersection point X = P + u (Q - P), then its (s,t) in the rectangle. */
    double u = dp / (dp - dq);
    double w[3];
    for (int d = 0; d < 3; d++)
        w[d] = xi[d] + u * (xj[d] - xi[d]) - o[d];
    double g11 = 0, g12 = 0, g22 = 0, r1 = 0, r2 = 0;
    for (int d = 0; d < 3; d++) {
        g11 += e1[d] * e1[d];
        g12 += e1[d] * e2[d];
        g22 += e2[d] * e2[d];
        r1 += e1[d] * w[d];
        r2 += e2[d] * w[d];
    }
    double det = g11 * g22 - g12 * g12;
    double s = (r1 * g22 - r2 * g12) / det;
    double t = (r2 * g11 - r1 * g12) / det;
    const double et = 1e-12;
    return s >= -et && s <= 1.0 + et && t >= -et && t <= 1.0 + et;
}

bool precrack_cuts(const struct precrack *c, const double xi[3], const double xj[3])
{
    if (!c)
        return false;
    if (c->dim == 1) {
        /* 1D: the crack is the point a[0]; touching counts. */
        double lo = fmin(xi[0], xj[0]), hi = fmax(xi[0], xj[0]);
        return c->a[0] >= lo && c->a[0] <= hi && lo < hi;
    }
    if (c->dim == 2)
        return cuts_2d(c, xi, xj);
    if (c->dim == 3)
        return cuts_3d(c, xi, xj);
    return false;
}
