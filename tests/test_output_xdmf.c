/*
 * Tests of the XDMF metadata and rigid-body meshes (io/output_xdmf.c, issue
 * 23): the attribute type and component names of each kind of field in 2D
 * and 3D, that every vertex of the mesh written for a sphere, a rounded flat
 * punch, a round nose (2D and 3D) lies on the body's surface as
 * rigid_distance() defines it, that a wall's mesh lies in its plane and spans
 * the particles, and that a run with impactors writes bodies.xdmf, one
 * spatial collection per frame with one grid per body, beside fields.xdmf
 * (ParaView opens both: tests/client), through a checkpoint round trip.
 */
#define _POSIX_C_SOURCE 200809L
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "tests/test_support.h"

#include "core/fields.h"
#include "core/particles.h"
#include "core/rigid.h"
#include "core/sim.h"
#include "io/output.h"
#include "io/output_xdmf.h"
#include "spall/error.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static void test_kinds(void **state)
{
    (void)state;
    /* 2D: velocity (vector parity), lattice stress (computed, 3 = xx yy xy) */
    enum xdmf_kind k = xdmf_field_kind(2, 2, FIELD_VECTOR);
    assert_int_equal(k, XDMF_VECTOR);
    assert_string_equal(xdmf_attribute_type(k, 2), "Matrix");
    assert_string_equal(xdmf_component_names(k, 2), "x y");
    k = xdmf_field_kind(2, 2, FIELD_EVEN); /* displacement: computed */
    assert_string_equal(xdmf_component_names(k, 2), "x y");
    k = xdmf_field_kind(3, 2, FIELD_EVEN);
    assert_int_equal(k, XDMF_SYMTENSOR);
    assert_string_equal(xdmf_attribute_type(k, 3), "Matrix");
    assert_string_equal(xdmf_component_names(k, 3), "xx yy xy");
    /* SPH's deviatoric stress keeps 6 components in 2D too */
    k = xdmf_field_kind(6, 2, FIELD_SYMTENSOR);
    assert_string_equal(xdmf_attribute_type(k, 6), "Tensor6");
    assert_string_equal(xdmf_component_names(k, 6), "xx yy zz xy yz xz");
    /* 3D */
    k = xdmf_field_kind(3, 3, FIELD_EVEN);
    assert_string_equal(xdmf_attribute_type(k, 3), "Vector");
    assert_string_equal(xdmf_component_names(k, 3), "x y z");
    k = xdmf_field_kind(6, 3, FIELD_EVEN);
    assert_string_equal(xdmf_attribute_type(k, 6), "Tensor6");
    k = xdmf_field_kind(9, 3, FIELD_EVEN);
    assert_string_equal(xdmf_attribute_type(k, 9), "Tensor");
    assert_string_equal(xdmf_component_names(k, 9), "xx xy xz yx yy yz zx zy zz");
    k = xdmf_field_kind(1, 3, FIELD_EVEN);
    assert_string_equal(xdmf_attribute_type(k, 1), "Scalar");
    assert_null(xdmf_component_names(k, 1));
    k = xdmf_field_kind(5, 3, FIELD_EVEN);
    assert_string_equal(xdmf_attribute_type(k, 5), "Matrix");
    assert_null(xdmf_component_names(k, 5));
}

/** The coordinates of grid @p name in @p xml (malloc'd, *np points). */
static double *grid_points(const char *xml, const char *name, size_t *np)
{
    char needle[96];
    snprintf(needle, sizeof needle, "<Grid Name=\"impactor_%s\"", name);
    const char *g = strstr(xml, needle);
    assert_non_null(g);
    const char *geo = strstr(g, "<Geometry");
    assert_non_null(geo);
    const char *dim = strstr(geo, "Dimensions=\"");
    assert_non_null(dim);
    *np = strtoul(dim + strlen("Dimensions=\""), NULL, 10);
    const char *v = strchr(dim, '>') + 1;
    double *p = malloc(3 * *np * sizeof *p);
    assert_non_null(p);
    char *end;
    for (size_t i = 0; i < 3 * *np; i++) {
        p[i] = strtod(v, &end);
        assert_true(end != v);
        v = end;
    }
    assert_true(strncmp(v, "</DataItem>", 11) == 0);
    return p;
}

/** Every vertex on the surface (|distance| < tol), but a 2D fan centre inside. */
static void check_on_surface(const struct impactor *im, const double *p, size_t np, int dim,
                             double tol)
{
    size_t inside = 0;
    for (size_t i = 0; i < np; i++) {
        double nrm[3];
        double d = rigid_distance(im, p + 3 * i, nrm);
        if (dim == 2 && d < -tol) {
            inside++;
            continue;
        }
        if (fabs(d) > tol)
            fprintf(stderr, "%s: vertex %zu (%g %g %g) at distance %g\n", im->name, i, p[3 * i],
                    p[3 * i + 1], p[3 * i + 2], d);
        assert_true(fabs(d) <= tol);
    }
    assert_int_equal(inside, dim == 2 ? 1 : 0);
}

static const char *deck_2d =
    "model: {type: lattice}\n"
    "materials:\n"
    "  m: {density: 1000, youngs_modulus: 1.0e9, poisson_ratio: 0.3333333333333333,\n"
    "      failure_strain: 1.0}\n"
    "lattice: {type: triangular, spacing: 1.0e-3}\n"
    "body: {geometry: {box: {min: [0, 0], max: [0.02, 0.004]}}, material: m}\n"
    "impactors:\n"
    "  - {name: ball, shape: sphere, position: [0.005, 0.009], radius: 0.004,\n"
    "     mass: 1.0, velocity: [0, -1]}\n"
    "  - {name: punch, shape: cylinder, position: [0.012, 0.006], radius: 0.003,\n"
    "     edge_radius: 0.001, length: 0.01, axis: [0, -1], mass: 1.0}\n"
    "  - {name: tup, shape: round_nose, position: [0.018, 0.006], radius: 0.002,\n"
    "     nose_radius: 0.003, length: 0.008, axis: [0.6, -0.8], mass: 1.0}\n"
    "  - {name: floor, shape: wall, position: [0, -0.001], normal: [0, 1],\n"
    "     motion: prescribed}\n"
    "run: {steps: 1}\n";

static const char *deck_3d =
    "model: {type: lattice}\n"
    "materials:\n"
    "  m: {density: 1000, youngs_modulus: 1.0e9, poisson_ratio: 0.25, failure_strain: 1.0}\n"
    "lattice: {type: sc, spacing: 1.0e-3}\n"
    "body: {geometry: {box: {min: [0, 0, 0], max: [0.006, 0.006, 0.003]}}, material: m}\n"
    "impactors:\n"
    "  - {name: ball, shape: sphere, position: [0.003, 0.003, 0.008], radius: 0.004,\n"
    "     mass: 1.0}\n"
    "  - {name: punch, shape: cylinder, position: [0.003, 0.003, 0.005], radius: 0.002,\n"
    "     edge_radius: 0.0005, length: 0.01, axis: [0, 0, -1], mass: 1.0}\n"
    "  - {name: tup, shape: round_nose, position: [0.01, 0.003, 0.005], radius: 0.002,\n"
    "     nose_radius: 0.004, length: 0.006, axis: [-0.6, 0, -0.8], mass: 1.0}\n"
    "  - {name: floor, shape: wall, position: [0, 0, -0.001], normal: [0, 0, 1],\n"
    "     motion: prescribed}\n"
    "run: {steps: 1}\n";

static void check_deck(const char *yaml, int dim)
{
    struct sim *s = test_build_ok(yaml);
    assert_int_equal(s->dim, dim);
    assert_int_equal(xdmf_rigid_count(s), 4);
    char *xml = xdmf_rigid_grids(s, s->p->n_owned);
    assert_non_null(xml);
    const char *names[] = {"ball", "punch", "tup"};
    for (int k = 0; k < 3; k++) {
        size_t np;
        double *p = grid_points(xml, names[k], &np);
        /* the vertices on the surface, to the 9 significant digits the index
         * writes: coordinates below 0.1 m are off by at most 5e-11 m each */
        check_on_surface(&s->rigid->im[k], p, np, dim, 1e-10);
        free(p);
    }
    /* the wall: in its plane, wider than the particles' extent */
    size_t np;
    double *p = grid_points(xml, "floor", &np);
    const struct impactor *w = &s->rigid->im[3];
    double lo = 1e30, hi = -1e30;
    for (size_t i = 0; i < np; i++) {
        double nrm[3];
        double d = rigid_distance(w, p + 3 * i, nrm);
        assert_true(d <= 1e-10 && d >= -0.01);
        lo = fmin(lo, p[3 * i]);
        hi = fmax(hi, p[3 * i]);
    }
    assert_true(np == 4);
    assert_true(lo < 0.0 && hi > (dim == 2 ? 0.02 : 0.006));
    free(p);
    /* well-formed enough for the readers: as many grids as bodies, closed */
    size_t grids = 0;
    for (const char *q = xml; (q = strstr(q, "<Grid ")); q++)
        grids++;
    assert_int_equal(grids, 4);
    size_t closes = 0;
    for (const char *q = xml; (q = strstr(q, "</Grid>")); q++)
        closes++;
    assert_int_equal(closes, 4);
    free(xml);
    sim_destroy(&s);
}

static void test_meshes_2d(void **state)
{
    (void)state;
    check_deck(deck_2d, 2);
}

static void test_meshes_3d(void **state)
{
    (void)state;
    check_deck(deck_3d, 3);
}

static char *slurp(const char *dir, const char *name)
{
    char path[256];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    FILE *f = fopen(path, "rb");
    assert_non_null(f);
    char *x = calloc(1 << 20, 1);
    assert_non_null(x);
    size_t len = fread(x, 1, (1 << 20) - 1, f);
    fclose(f);
    x[len] = '\0';
    return x;
}

static size_t count(const char *x, const char *needle)
{
    size_t k = 0;
    for (const char *q = x; (q = strstr(q, needle)); q++)
        k++;
    return k;
}

/** A run with impactors: fields.xdmf holds the particles only (with units
 *  and component names), bodies.xdmf one spatial collection per frame with
 *  one grid per body; both survive a checkpoint's round trip of
 *  field_writer_grids / field_writer_resume. */
static void test_bodies_index(void **state)
{
    (void)state;
    struct sim *s = test_build_ok(deck_2d);
    char dir[] = "/tmp/spall_xdmf_XXXXXX";
    assert_non_null(mkdtemp(dir));
    struct spall_error err = {0};
    struct field_writer *w = NULL;
    const char *names[] = {"velocity", "stress"};
    for (size_t i = 0; i < s->p->n_owned; i++) /* 0.1 % strain along x: a stress to write */
        s->p->x[0][i] *= 1.001;
    assert_int_equal(field_writer_create(&w, dir, s, names, 2, &err), SPALL_OK);
    assert_int_equal(field_writer_write(w, s, &err), SPALL_OK);
    assert_int_equal(field_writer_write(w, s, &err), SPALL_OK);
    char *fields = slurp(dir, "fields.xdmf"), *bodies = slurp(dir, "bodies.xdmf");
    assert_int_equal(count(fields, "CollectionType=\"Spatial\""), 0);
    assert_int_equal(count(fields, "impactor_"), 0);
    assert_int_equal(count(fields, "GridType=\"Uniform\""), 2);
    assert_non_null(strstr(fields, "<Attribute Name=\"velocity\" AttributeType=\"Matrix\" Center=\"Node\">\n"
                                   "          <Information Name=\"unit\" Value=\"m/s\"/>\n"
                                   "          <Information Name=\"components\" Value=\"x y\"/>\n"));
    /* the 2D symmetric tensor widened to a Tensor6 (xdmf_file_ncomp), so
     * that ParaView names its components */
    assert_non_null(strstr(fields, "<Attribute Name=\"stress\" AttributeType=\"Tensor6\" Center=\"Node\">\n"
                                   "          <Information Name=\"unit\" Value=\"Pa\"/>\n"
                                   "          <Information Name=\"components\" Value=\"xx yy zz xy yz xz\"/>\n"));
    {
        char h5[96];
        snprintf(h5, sizeof h5, "%s/fields_000000.h5", dir);
        double *data = NULL;
        size_t n = 0, nc = 0;
        assert_int_equal(field_frame_read(h5, "stress", &data, &n, &nc, NULL, &err), SPALL_OK);
        const struct field_desc *f = field_registry_find(s->fields, "stress");
        assert_non_null(f);
        assert_int_equal(f->ncomp, 3);
        assert_int_equal(nc, 6);
        assert_int_equal(n, s->p->n_owned);
        double *g = malloc(n * 3 * sizeof *g);
        assert_non_null(g);
        field_gather_f64(f, n, g);
        double smax = 0.0;
        for (size_t i = 0; i < n; i++) {
            const double *r = data + 6 * i;
            assert_true(r[0] == g[3 * i] && r[1] == g[3 * i + 1] && r[3] == g[3 * i + 2]);
            assert_true(r[2] == 0.0 && r[4] == 0.0 && r[5] == 0.0);
            smax = fmax(smax, fabs(g[3 * i]) + fabs(g[3 * i + 1]) + fabs(g[3 * i + 2]));
        }
        assert_true(smax > 0.0);
        free(g);
        free(data);
    }
    assert_int_equal(count(bodies, "CollectionType=\"Spatial\""), 2);
    assert_int_equal(count(bodies, "<Grid Name=\"impactor_"), 8);
    assert_int_equal(count(bodies, "<Time Value=\"0\"/>"), 2);
    assert_non_null(strstr(bodies, "<Grid Name=\"bodies_000001\""));
    /* checkpoint round trip: a new writer resumed from the saved text
     * rewrites both indexes byte for byte */
    size_t len;
    const char *g = field_writer_grids(w, &len);
    char *copy = malloc(len + 1);
    assert_non_null(copy);
    memcpy(copy, g, len);
    field_writer_destroy(&w);
    char path[256];
    snprintf(path, sizeof path, "%s/bodies.xdmf", dir);
    remove(path);
    assert_int_equal(field_writer_create(&w, dir, s, names, 2, &err), SPALL_OK);
    assert_int_equal(field_writer_resume(w, 2, copy, len, &err), SPALL_OK);
    char *fields2 = slurp(dir, "fields.xdmf"), *bodies2 = slurp(dir, "bodies.xdmf");
    assert_string_equal(fields, fields2);
    assert_string_equal(bodies, bodies2);
    field_writer_destroy(&w);
    free(copy);
    free(fields);
    free(bodies);
    free(fields2);
    free(bodies2);
    for (int k = 0; k < 2; k++) {
        snprintf(path, sizeof path, "%s/fields_%06d.h5", dir, k);
        remove(path);
    }
    snprintf(path, sizeof path, "%s/fields.xdmf", dir);
    remove(path);
    snprintf(path, sizeof path, "%s/bodies.xdmf", dir);
    remove(path);
    rmdir(dir);
    sim_destroy(&s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_kinds),
        cmocka_unit_test(test_meshes_2d),
        cmocka_unit_test(test_meshes_3d),
        cmocka_unit_test(test_bodies_index),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
