/**
 * @file geometry.h
 * @brief Solid geometry: primitives combined by union, intersection and
 *        difference (holes), and pre-cracks that cut bonds.
 *
 * Used to fill a body with lattice sites, to define named particle groups
 * (grips, probes' neighbourhoods, inclusions) and material regions.
 * A composite owns its children.  In 2D (dim = 2) the z coordinate is
 * ignored: a cylinder is then a disc (circle of `radius` around `center`),
 * a sphere a circle, a box a rectangle.  Units: m.
 */
#ifndef SPALL_GEOMETRY_H
#define SPALL_GEOMETRY_H

#include <stdbool.h>
#include <stddef.h>

struct spall_error;

enum geom_kind {
    GEOM_BOX,          /**< axis-aligned box lo..hi */
    GEOM_SPHERE,       /**< center, radius */
    GEOM_CYLINDER,     /**< finite cylinder: base center p0, top center p1, radius */
    GEOM_HALFSPACE,    /**< points x with (x - point)·normal <= 0 (normal points outward) */
    GEOM_POLYGON,      /**< 2D simple polygon (x,y) vertices, even-odd rule */
    GEOM_UNION,        /**< inside any child */
    GEOM_INTERSECTION, /**< inside all children */
    GEOM_DIFFERENCE    /**< inside child 0 and in none of children 1.. */
};

struct geom {
    enum geom_kind kind;
    double a[3];        /**< box lo / sphere & cylinder center or p0 / halfspace point */
    double b[3];        /**< box hi / cylinder p1 / halfspace normal */
    double radius;
    double *poly;       /**< polygon vertices x0,y0,x1,y1,... (owned) */
    size_t n_poly;      /**< number of polygon vertices */
    struct geom **child;/**< composite children (owned) */
    size_t n_child;
};

/* Constructors return NULL on out-of-memory.  Composites take ownership of
 * the children passed in (also on failure, where they are destroyed). */
struct geom *geom_box(const double lo[3], const double hi[3]);
struct geom *geom_sphere(const double center[3], double radius);
struct geom *geom_cylinder(const double p0[3], const double p1[3], double radius);
struct geom *geom_halfspace(const double point[3], const double normal[3]);
struct geom *geom_polygon(const double *xy, size_t n_vertices);
struct geom *geom_combine(enum geom_kind kind, struct geom **children, size_t n);
struct geom *geom_clone(const struct geom *g);
void geom_destroy(struct geom **g);

/** Is @p x inside @p g?  Boundary points count as inside (with a relative
 *  tolerance of 1e-9 of the shape's size) so lattice sites on a box face are kept. */
bool geom_contains(const struct geom *g, const double x[3], int dim);

/** Axis-aligned bounding box.  Returns false if unbounded (half-space
 *  without an enclosing intersection/difference parent). */
bool geom_bounds(const struct geom *g, int dim, double lo[3], double hi[3]);

/** A pre-crack: a segment a-b in 2D, or a planar rectangle in 3D spanned by
 *  corner `origin` and edges e1, e2.  Every bond whose segment crosses it is
 *  removed before the run. */
struct precrack {
    int dim;
    double a[3], b[3];          /**< 2D segment end points */
    double origin[3], e1[3], e2[3]; /**< 3D rectangle */
};

/** Does the straight segment xi-xj cross the pre-crack? (proper crossing;
 *  touching an end point counts as crossing) */
bool precrack_cuts(const struct precrack *c, const double xi[3], const double xj[3]);

#endif
