/**
 * @file output_xdmf.c
 * @brief Field metadata and rigid-body meshes for the XDMF index (see
 *        output_xdmf.h).
 *
 * Measured with Debian 12's ParaView 5.11 (tests/client, docs/postprocessing.md):
 *  - neither Xdmf3ReaderS (ParaView's default for .xdmf) nor the legacy
 *    XDMF reader turns <Information> elements into arrays, and Xdmf3ReaderS
 *    skips HyperSlab and Function DataItems ("Skipping unrecognized array
 *    type"), so per-component views or zero-padded 2D vectors cannot be
 *    built in the index from the n x 2 datasets: the component names and
 *    units go into <Information Name="components"/"unit"> for scripts and
 *    other readers, and ParaView shows its own labels (X Y Z; XX YY ZZ XY YZ
 *    XZ for 6 components, which is spall's symmetric-tensor order);
 *  - a frame written as a spatial collection (particles + one Uniform grid
 *    per rigid body, inline XML coordinates) is read by both readers as a
 *    multiblock data set, one block per grid: the impactors are drawn by the
 *    default Surface representation with no user action.
 * Shapes follow rigid_distance() (core/rigid.c): a sphere, and the
 * axisymmetric cylinder / flat punch (rounded edges) and round nose are
 * surfaces of revolution of their meridian profile (rho, h), h along the
 * axis from the tip; in 2D the same profile mirrored about the axis is the
 * body's plane section.  A wall is drawn as a square (3D) or a thin strip
 * (2D) a little larger than the particles' bounding box, centred on it; so
 * are the planes a model enforces itself (model_ops.planes: the SPH
 * model.wall and symmetry planes), as grids "model_NAME" beside the
 * impactors' "impactor_NAME".
 */
#include "io/output_xdmf.h"

#include "core/fields.h"
#include "core/mathconst.h"
#include "core/model.h"
#include "core/parallel/comm.h"
#include "core/particles.h"
#include "core/rigid.h"
#include "core/sim.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum xdmf_kind xdmf_field_kind(int ncomp, int dim, int parity)
{
    if (ncomp == 1)
        return XDMF_SCALAR;
    if (parity == FIELD_VECTOR || (parity == FIELD_EVEN && ncomp == dim))
        return ncomp <= 3 ? XDMF_VECTOR : XDMF_OTHER;
    if (parity == FIELD_SYMTENSOR ||
        (parity == FIELD_EVEN && ncomp == field_symtensor_ncomp(dim) && dim > 1))
        return (ncomp == 3 || ncomp == 6) ? XDMF_SYMTENSOR : XDMF_OTHER;
    if (parity == FIELD_TENSOR || (parity == FIELD_EVEN && ncomp == dim * dim))
        return (ncomp == 4 || ncomp == 9) ? XDMF_TENSOR : XDMF_OTHER;
    return XDMF_OTHER;
}

const char *xdmf_attribute_type(enum xdmf_kind kind, int ncomp)
{
    switch (kind) {
    case XDMF_SCALAR: return "Scalar";
    case XDMF_VECTOR: return ncomp == 3 ? "Vector" : "Matrix";
    case XDMF_SYMTENSOR: return ncomp == 6 ? "Tensor6" : "Matrix";
    case XDMF_TENSOR: return ncomp == 9 ? "Tensor" : "Matrix";
    default: return "Matrix";
    }
}

const char *xdmf_component_names(enum xdmf_kind kind, int ncomp)
{
    switch (kind) {
    case XDMF_VECTOR: return ncomp == 2 ? "x y" : "x y z";
    /* core/fields.h FIELD_SYMTENSOR order: xx yy zz xy yz xz (2D: xx yy xy) */
    case XDMF_SYMTENSOR: return ncomp == 3 ? "xx yy xy" : "xx yy zz xy yz xz";
    case XDMF_TENSOR: return ncomp == 4 ? "xx xy yx yy" : "xx xy xz yx yy yz zx zy zz";
    default: return NULL;
    }
}

int xdmf_file_ncomp(enum xdmf_kind kind, int ncomp)
{
    return kind == XDMF_SYMTENSOR && ncomp == 3 ? 6 : ncomp;
}

void xdmf_widen_symtensor(double *b, size_t n)
{
    /* back to front: row i's new place (6i..) never overlaps the unread rows (< 3i) */
    for (size_t i = n; i-- > 0;) {
        const double xx = b[3 * i], yy = b[3 * i + 1], xy = b[3 * i + 2];
        double *r = b + 6 * i;
        r[0] = xx, r[1] = yy, r[2] = 0.0, r[3] = xy, r[4] = 0.0, r[5] = 0.0;
    }
}

/* ---------------------------------------------------------------- meshes */

#define XDMF_PROFILE_MAX 48 /* points of a meridian profile */
#define XDMF_ARC_STEPS 8    /* segments of a quarter circle */
#define XDMF_RING 24        /* segments around the axis (3D) */

struct str {
    char *s;
    size_t len, cap;
    int bad;
};

static void str_add(struct str *b, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;

static void str_add(struct str *b, const char *fmt, ...)
{
    if (b->bad)
        return;
    va_list ap;
    va_start(ap, fmt);
    int k = vsnprintf(NULL, 0, fmt, ap);
    va_end(ap);
    if (k < 0) {
        b->bad = 1;
        return;
    }
    if (b->len + (size_t)k + 1 > b->cap) {
        size_t cap = b->cap ? b->cap : 4096;
        while (cap < b->len + (size_t)k + 1)
            cap *= 2;
        char *s = realloc(b->s, cap);
        if (!s) {
            b->bad = 1;
            return;
        }
        b->s = s;
        b->cap = cap;
    }
    va_start(ap, fmt);
    vsnprintf(b->s + b->len, b->cap - b->len, fmt, ap);
    va_end(ap);
    b->len += (size_t)k;
}

/** A triangle mesh being built (points and index triples). */
struct mesh {
    double (*p)[3];
    size_t np, cap_p;
    size_t (*t)[3];
    size_t nt, cap_t;
    int bad;
};

static size_t mesh_point(struct mesh *m, double x, double y, double z)
{
    if (m->np == m->cap_p) {
        size_t cap = m->cap_p ? 2 * m->cap_p : 64;
        void *q = realloc(m->p, cap * sizeof *m->p);
        if (!q) {
            m->bad = 1;
            return 0;
        }
        m->p = q;
        m->cap_p = cap;
    }
    m->p[m->np][0] = x;
    m->p[m->np][1] = y;
    m->p[m->np][2] = z;
    return m->np++;
}

static void mesh_tri(struct mesh *m, size_t a, size_t b, size_t c)
{
    if (m->bad)
        return;
    if (m->nt == m->cap_t) {
        size_t cap = m->cap_t ? 2 * m->cap_t : 64;
        void *q = realloc(m->t, cap * sizeof *m->t);
        if (!q) {
            m->bad = 1;
            return;
        }
        m->t = q;
        m->cap_t = cap;
    }
    m->t[m->nt][0] = a;
    m->t[m->nt][1] = b;
    m->t[m->nt][2] = c;
    m->nt++;
}

struct profile {
    double rho[XDMF_PROFILE_MAX], h[XDMF_PROFILE_MAX];
    int n;
};

static void prof_add(struct profile *pr, double rho, double h)
{
    if (pr->n < XDMF_PROFILE_MAX) {
        pr->rho[pr->n] = rho > 0 ? rho : 0.0;
        pr->h[pr->n] = h;
        pr->n++;
    }
}

/** Quarter arc about (rc, hc) of radius r from angle a0 to a1 (excluded a0). */
static void prof_arc(struct profile *pr, double rc, double hc, double r, double a0, double a1)
{
    for (int k = 1; k <= XDMF_ARC_STEPS; k++) {
        double a = a0 + (a1 - a0) * k / XDMF_ARC_STEPS;
        prof_add(pr, rc + r * cos(a), hc + r * sin(a));
    }
}

/** Meridian profile from the front pole (rho = 0) to the back pole; h is
 *  measured along the axis from the reference point im->x. */
static void profile_of(const struct impactor *im, struct profile *pr)
{
    pr->n = 0;
    const double half_pi = 0.5 * SPALL_PI;
    if (im->shape == RIGID_SPHERE) {
        prof_add(pr, 0.0, im->radius);
        for (int k = 1; k <= 2 * XDMF_ARC_STEPS; k++) {
            double th = SPALL_PI * k / (2 * XDMF_ARC_STEPS);
            prof_add(pr, im->radius * sin(th), im->radius * cos(th));
        }
        return;
    }
    double R = im->radius, L = im->length;
    if (im->shape == RIGID_CYLINDER) {
        double e = im->edge_radius;
        if (e > R)
            e = R;
        if (e > 0.5 * L)
            e = 0.5 * L;
        prof_add(pr, 0.0, 0.0);
        prof_add(pr, R - e, 0.0);
        if (e > 0)
            prof_arc(pr, R - e, -e, e, half_pi, 0.0);
        prof_add(pr, R, -(L - e));
        if (e > 0)
            prof_arc(pr, R - e, -(L - e), e, 0.0, -half_pi);
        prof_add(pr, 0.0, -L);
        return;
    }
    /* round nose: sphere of radius Rn centred Rn behind the tip up to the
     * shank radius R, then the shank to the back end */
    double Rn = im->nose_radius > R ? im->nose_radius : R;
    double phij = asin(R / Rn);
    prof_add(pr, 0.0, 0.0);
    for (int k = 1; k <= 2 * XDMF_ARC_STEPS; k++) {
        double ph = phij * k / (2 * XDMF_ARC_STEPS);
        prof_add(pr, Rn * sin(ph), -Rn + Rn * cos(ph));
    }
    prof_add(pr, R, -L);
    prof_add(pr, 0.0, -L);
}

static void unit_perp(const double a[3], double e1[3], double e2[3])
{
    /* the coordinate axis least aligned with a, made orthogonal to it */
    int k = 0;
    for (int c = 1; c < 3; c++)
        if (fabs(a[c]) < fabs(a[k]))
            k = c;
    double t[3] = {0, 0, 0};
    t[k] = 1.0;
    double d = t[0] * a[0] + t[1] * a[1] + t[2] * a[2];
    for (int c = 0; c < 3; c++)
        e1[c] = t[c] - d * a[c];
    double nn = sqrt(e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2]);
    for (int c = 0; c < 3; c++)
        e1[c] /= nn;
    e2[0] = a[1] * e1[2] - a[2] * e1[1];
    e2[1] = a[2] * e1[0] - a[0] * e1[2];
    e2[2] = a[0] * e1[1] - a[1] * e1[0];
}

/** 2D: the profile and its mirror image as one convex polygon, fanned from
 *  its centroid (every shape of rigid.h is convex). */
static void mesh_revolve_2d(struct mesh *m, const struct impactor *im, const double a[3],
                            const struct profile *pr)
{
    double lat[3] = {-a[1], a[0], 0.0};
    size_t first = m->np;
    for (int side = 0; side < 2; side++) {
        double sg = side ? -1.0 : 1.0;
        for (int k = 0; k < pr->n; k++) {
            int i = side ? pr->n - 1 - k : k;
            if (pr->rho[i] == 0.0 && side == 1)
                continue; /* the poles are already in */
            double r = sg * pr->rho[i], h = pr->h[i];
            mesh_point(m, im->x[0] + r * lat[0] + h * a[0], im->x[1] + r * lat[1] + h * a[1], 0.0);
        }
    }
    size_t n = m->np - first;
    double c[2] = {0, 0};
    for (size_t i = first; i < m->np; i++) {
        c[0] += m->p[i][0] / (double)n;
        c[1] += m->p[i][1] / (double)n;
    }
    size_t ic = mesh_point(m, c[0], c[1], 0.0);
    for (size_t i = 0; i < n; i++)
        mesh_tri(m, ic, first + i, first + (i + 1) % n);
}

/** 3D: surface of revolution of the profile about the axis. */
static void mesh_revolve_3d(struct mesh *m, const struct impactor *im, const double a[3],
                            const struct profile *pr)
{
    double e1[3], e2[3];
    unit_perp(a, e1, e2);
    size_t ring_start[XDMF_PROFILE_MAX];
    for (int i = 0; i < pr->n; i++) {
        ring_start[i] = m->np;
        int nseg = pr->rho[i] > 0 ? XDMF_RING : 1;
        for (int j = 0; j < nseg; j++) {
            double ph = 2.0 * SPALL_PI * j / XDMF_RING;
            double r = pr->rho[i], h = pr->h[i];
            double u = r * cos(ph), v = r * sin(ph);
            mesh_point(m, im->x[0] + u * e1[0] + v * e2[0] + h * a[0],
                       im->x[1] + u * e1[1] + v * e2[1] + h * a[1],
                       im->x[2] + u * e1[2] + v * e2[2] + h * a[2]);
        }
    }
    for (int i = 0; i + 1 < pr->n; i++) {
        size_t s0 = ring_start[i], s1 = ring_start[i + 1];
        int pole0 = pr->rho[i] == 0.0, pole1 = pr->rho[i + 1] == 0.0;
        for (int j = 0; j < XDMF_RING; j++) {
            size_t j1 = (size_t)((j + 1) % XDMF_RING);
            if (pole0 && pole1)
                break;
            if (pole0)
                mesh_tri(m, s0, s1 + (size_t)j, s1 + j1);
            else if (pole1)
                mesh_tri(m, s0 + (size_t)j, s1, s0 + j1);
            else {
                mesh_tri(m, s0 + (size_t)j, s1 + (size_t)j, s1 + j1);
                mesh_tri(m, s0 + (size_t)j, s1 + j1, s0 + j1);
            }
        }
    }
}

/** A wall: a square (3D) or a thin strip behind the line (2D), 1.2 times
 *  the particles' bounding-box diagonal wide, centred on the box's centre
 *  projected onto the wall. */
static void mesh_wall(struct mesh *m, const struct sim *s, const struct impactor *im, size_t n)
{
    double lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
    /* a distributed run's n counts every rank's particles: the box of the
     * owned ones, then min and max over the ranks (exact, collective: every
     * rank indexes each frame) */
    const size_t nl = s->par ? s->p->n_owned : n;
    for (int c = 0; c < s->dim; c++) {
        lo[c] = nl ? s->p->x[c][0] : INFINITY;
        hi[c] = nl ? lo[c] : -INFINITY;
        for (size_t i = 1; i < nl; i++) {
            double v = s->p->x[c][i];
            lo[c] = v < lo[c] ? v : lo[c];
            hi[c] = v > hi[c] ? v : hi[c];
        }
        if (s->par) {
            lo[c] = par_min_double(lo[c]);
            hi[c] = par_max_double(hi[c]);
        }
        if (!n)
            lo[c] = hi[c] = im->x[c];
    }
    double diag = 0, ctr[3];
    for (int c = 0; c < 3; c++) {
        diag += (hi[c] - lo[c]) * (hi[c] - lo[c]);
        ctr[c] = 0.5 * (lo[c] + hi[c]);
    }
    double half = 0.6 * sqrt(diag);
    if (!(half > 0))
        half = 1.0;
    const double *a = im->axis;
    double d = 0;
    for (int c = 0; c < 3; c++)
        d += (ctr[c] - im->x[c]) * a[c];
    for (int c = 0; c < 3; c++)
        ctr[c] -= d * a[c];
    if (s->dim < 3) {
        double t[3] = {-a[1], a[0], 0.0}, w = half / 20.0;
        size_t p0 = mesh_point(m, ctr[0] - half * t[0], ctr[1] - half * t[1], 0.0);
        size_t p1 = mesh_point(m, ctr[0] + half * t[0], ctr[1] + half * t[1], 0.0);
        size_t p2 = mesh_point(m, ctr[0] + half * t[0] - w * a[0], ctr[1] + half * t[1] - w * a[1], 0.0);
        size_t p3 = mesh_point(m, ctr[0] - half * t[0] - w * a[0], ctr[1] - half * t[1] - w * a[1], 0.0);
        mesh_tri(m, p0, p1, p2);
        mesh_tri(m, p0, p2, p3);
        return;
    }
    double e1[3], e2[3];
    unit_perp(a, e1, e2);
    size_t q[4];
    for (int k = 0; k < 4; k++) {
        double u = (k == 1 || k == 2) ? half : -half, v = k >= 2 ? half : -half;
        q[k] = mesh_point(m, ctr[0] + u * e1[0] + v * e2[0], ctr[1] + u * e1[1] + v * e2[1],
                          ctr[2] + u * e1[2] + v * e2[2]);
    }
    mesh_tri(m, q[0], q[1], q[2]);
    mesh_tri(m, q[0], q[2], q[3]);
}

/** The model's own planes (model_ops.planes: an SPH wall, symmetry planes). */
static size_t model_planes(const struct sim *s, struct model_plane *out)
{
    return s->ops && s->ops->planes && s->model ? s->ops->planes(s->model, s, out) : 0;
}

size_t xdmf_rigid_count(const struct sim *s)
{
    struct model_plane pl[MODEL_PLANES_MAX];
    return (s->rigid ? s->rigid->n : 0) + model_planes(s, pl);
}

/** Impactor names come from the deck: keep XML- and path-safe characters. */
static void safe_name(char *out, size_t size, const char *name, size_t k)
{
    size_t j = 0;
    for (const char *c = name; *c && j + 1 < size; c++) {
        int ok = (*c >= 'a' && *c <= 'z') || (*c >= 'A' && *c <= 'Z') ||
                 (*c >= '0' && *c <= '9') || *c == '_' || *c == '-' || *c == '.';
        out[j++] = ok ? *c : '_';
    }
    out[j] = '\0';
    if (j == 0)
        snprintf(out, size, "%zu", k);
}

static void write_mesh(struct str *b, const struct mesh *m, const char *kind, const char *name)
{
    str_add(b,
            "        <Grid Name=\"%s_%s\" GridType=\"Uniform\">\n"
            "          <Topology TopologyType=\"Triangle\" NumberOfElements=\"%zu\">\n"
            "            <DataItem Dimensions=\"%zu 3\" NumberType=\"Int\" Format=\"XML\">",
            kind, name, m->nt, m->nt);
    for (size_t i = 0; i < m->nt; i++)
        str_add(b, "%s%zu %zu %zu", i ? " " : "", m->t[i][0], m->t[i][1], m->t[i][2]);
    str_add(b,
            "</DataItem>\n"
            "          </Topology>\n"
            "          <Geometry GeometryType=\"XYZ\">\n"
            "            <DataItem Dimensions=\"%zu 3\" NumberType=\"Float\" Precision=\"8\""
            " Format=\"XML\">",
            m->np);
    for (size_t i = 0; i < m->np; i++)
        str_add(b, "%s%.9g %.9g %.9g", i ? " " : "", m->p[i][0], m->p[i][1], m->p[i][2]);
    str_add(b, "</DataItem>\n          </Geometry>\n        </Grid>\n");
}

char *xdmf_rigid_grids(const struct sim *s, size_t n_particles)
{
    struct str b = {0};
    str_add(&b, "%s", "");
    for (size_t k = 0; s->rigid && k < s->rigid->n && !b.bad; k++) {
        const struct impactor *im = &s->rigid->im[k];
        struct mesh m = {0};
        if (im->shape == RIGID_WALL) {
            mesh_wall(&m, s, im, n_particles);
        } else {
            double a[3] = {im->axis[0], im->axis[1], im->axis[2]};
            if (im->shape == RIGID_SPHERE) { /* any axis: the plane's second one */
                a[0] = a[2] = 0.0;
                a[1] = 1.0;
            }
            struct profile pr;
            profile_of(im, &pr);
            if (s->dim < 3)
                mesh_revolve_2d(&m, im, a, &pr);
            else
                mesh_revolve_3d(&m, im, a, &pr);
        }
        char name[64];
        safe_name(name, sizeof name, im->name, k);
        if (m.bad)
            b.bad = 1;
        else
            write_mesh(&b, &m, "impactor", name);
        free(m.p);
        free(m.t);
    }
    /* the model's own planes, drawn as walls are */
    struct model_plane pl[MODEL_PLANES_MAX];
    size_t np = model_planes(s, pl);
    for (size_t k = 0; k < np && !b.bad; k++) {
        struct impactor wall = {.shape = RIGID_WALL};
        for (int c = 0; c < 3; c++) {
            wall.x[c] = pl[k].point[c];
            wall.axis[c] = pl[k].normal[c];
        }
        struct mesh m = {0};
        mesh_wall(&m, s, &wall, n_particles);
        if (m.bad)
            b.bad = 1;
        else
            write_mesh(&b, &m, "model", pl[k].name);
        free(m.p);
        free(m.t);
    }
    if (b.bad) {
        free(b.s);
        return NULL;
    }
    return b.s;
}
