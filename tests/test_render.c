/* Tests for io/render.h and io/plot.h: synthetic particle frames drawn to
 * PNG (size, colours at particle locations), a frame read back from HDF5,
 * x-y plots and the validation report page. */
#define _POSIX_C_SOURCE 200809L

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <cairo.h>
#include <hdf5.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "io/plot.h"
#include "io/render.h"
#include "spall/error.h"
#include "validation/validation.h"

/* fontconfig (loaded by cairo's text drawing) keeps its caches until exit by
 * design; tell LeakSanitizer (ASan builds) that these are not our leaks. */
const char *__lsan_default_suppressions(void);
const char *__lsan_default_suppressions(void) { return "leak:libfontconfig\n"; }

#define NX 40
#define NY 20

/* a 40 x 20 square grid (spacing 1 mm): value 0 on the left half, 1 on the right */
static void grid(double *pos, double *val)
{
    for (int j = 0; j < NY; j++)
        for (int i = 0; i < NX; i++) {
            size_t k = (size_t)(j * NX + i);
            pos[3 * k] = 1e-3 * i;
            pos[3 * k + 1] = 1e-3 * j;
            pos[3 * k + 2] = 0.0;
            val[k] = i < NX / 2 ? 0.0 : 1.0;
        }
}

static void pixel(cairo_surface_t *s, int x, int y, int rgb[3])
{
    const unsigned char *d = cairo_image_surface_get_data(s);
    int stride = cairo_image_surface_get_stride(s);
    uint32_t p = *(const uint32_t *)(d + (size_t)y * (size_t)stride + 4 * (size_t)x);
    rgb[0] = (int)((p >> 16) & 255);
    rgb[1] = (int)((p >> 8) & 255);
    rgb[2] = (int)(p & 255);
}

static int window_has(cairo_surface_t *s, int x0, int y0, int r, int g, int b)
{
    int rgb[3];
    for (int y = y0 - 5; y <= y0 + 5; y++)
        for (int x = x0 - 5; x <= x0 + 5; x++) {
            pixel(s, x, y, rgb);
            if (abs(rgb[0] - r) < 12 && abs(rgb[1] - g) < 12 && abs(rgb[2] - b) < 12)
                return 1;
        }
    return 0;
}

/* find the drawn particle area along the middle row of the image: the first
 * and last non-white pixel left of the colour bar */
static void check_halves(const char *png)
{
    cairo_surface_t *s = cairo_image_surface_create_from_png(png);
    assert_int_equal(cairo_surface_status(s), CAIRO_STATUS_SUCCESS);
    int W = cairo_image_surface_get_width(s), H = cairo_image_surface_get_height(s);
    assert_true(W >= 600 && W <= 820);
    assert_true(H > 200 && H < 600);
    /* particle area: 40 x 20 sites + 1 spacing margin -> aspect 42:22 */
    int y = 40 + (int)(0.5 * (W - 150) * 22.0 / 42.0);
    int rgb[3];
    int xl = -1, xr = -1;
    for (int x = 0; x < W - 130; x++) {
        pixel(s, x, y, rgb);
        if (rgb[0] + rgb[1] + rgb[2] < 3 * 250) {
            if (xl < 0)
                xl = x;
            xr = x;
        }
    }
    assert_true(xl >= 0 && xr > xl + 100);
    /* a quarter in from the left: viridis(0) = (68, 1, 84); from the right:
     * viridis(1) = (253, 231, 37); discs leave small gaps on a square grid, so
     * look in a small window around the point */
    assert_true(window_has(s, xl + (xr - xl) / 4, y, 68, 1, 84));
    assert_true(window_has(s, xr - (xr - xl) / 4, y, 253, 231, 37));
    assert_false(window_has(s, xl + (xr - xl) / 4, y, 253, 231, 37));
    cairo_surface_destroy(s);
}

static void test_render_points(void **state)
{
    (void)state;
    double pos[3 * NX * NY], val[NX * NY];
    grid(pos, val);
    struct render_options o;
    render_options_default(&o, "fracture_density");
    struct render_points d = {NX * NY, pos, NULL, val, 1.5e-3, "fracture density (1)"};
    char png[64];
    snprintf(png, sizeof png, "render_test_%d.png", (int)getpid());
    struct spall_error err = {0};
    assert_int_equal(render_points_png(png, &d, &o, &err), SPALL_OK);
    check_halves(png);
    /* bad width refused */
    o.width = 10;
    assert_int_equal(render_points_png(png, &d, &o, &err), SPALL_ERR_INPUT);
    assert_non_null(strstr(err.msg, "width"));
    unlink(png);
}

static void write_ds(hid_t f, const char *name, const double *data, hsize_t n, hsize_t nc)
{
    hsize_t dims[2] = {n, nc};
    hid_t sp = H5Screate_simple(nc == 1 ? 1 : 2, dims, NULL);
    hid_t ds = H5Dcreate2(f, name, H5T_NATIVE_DOUBLE, sp, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    H5Dwrite(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, data);
    H5Dclose(ds);
    H5Sclose(sp);
}

/* the same picture through an HDF5 frame, with a 2-component field whose
 * x component carries the halves */
static void test_render_frame(void **state)
{
    (void)state;
    static double pos[3 * NX * NY], val[NX * NY], vel[2 * NX * NY];
    grid(pos, val);
    for (size_t k = 0; k < NX * NY; k++) {
        vel[2 * k] = 5.0 * val[k];
        vel[2 * k + 1] = 0.0;
    }
    char h5[64], png[64];
    snprintf(h5, sizeof h5, "render_frame_%d.h5", (int)getpid());
    snprintf(png, sizeof png, "render_frame_%d.png", (int)getpid());
    hid_t f = H5Fcreate(h5, H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
    assert_true(f >= 0);
    double t = 2e-4;
    hid_t sp = H5Screate(H5S_SCALAR);
    hid_t ds = H5Dcreate2(f, "time", H5T_NATIVE_DOUBLE, sp, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    H5Dwrite(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, &t);
    H5Dclose(ds);
    H5Sclose(sp);
    write_ds(f, "position", pos, NX * NY, 3);
    write_ds(f, "velocity", vel, NX * NY, 2);
    H5Fclose(f);
    struct render_options o;
    render_options_default(&o, "velocity");
    o.component = 0;
    struct spall_error err = {0};
    assert_int_equal(render_frame_png(h5, png, &o, &err), SPALL_OK);
    check_halves(png);
    /* magnitude gives the same picture here */
    o.component = RENDER_MAGNITUDE;
    assert_int_equal(render_frame_png(h5, png, &o, &err), SPALL_OK);
    check_halves(png);
    o.component = 2;
    assert_int_equal(render_frame_png(h5, png, &o, &err), SPALL_ERR_INPUT);
    assert_non_null(strstr(err.msg, "component"));
    render_options_default(&o, "no_such_field");
    assert_int_not_equal(render_frame_png(h5, png, &o, &err), SPALL_OK);
    assert_non_null(strstr(err.msg, "no_such_field"));
    unlink(h5);
    unlink(png);
}

static void test_plot(void **state)
{
    (void)state;
    double x[50], y[50], yr[50];
    for (int k = 0; k < 50; k++) {
        x[k] = k * 1e-3;
        y[k] = sin(0.2 * k);
        yr[k] = sin(0.2 * k) + 0.1;
    }
    struct plot_series ser[2] = {{"measured", x, y, 50, PLOT_LINE}, {"reference", x, yr, 50, PLOT_DASHED}};
    struct plot_refline ref = {'x', 0.02, "arrival"};
    struct plot_spec spec = {"test plot", "t [s]", "u [m]", 640, 400, ser, 2, &ref, 1};
    char png[64];
    snprintf(png, sizeof png, "plot_test_%d.png", (int)getpid());
    struct spall_error err = {0};
    assert_int_equal(plot_png(png, &spec, &err), SPALL_OK);
    cairo_surface_t *s = cairo_image_surface_create_from_png(png);
    assert_int_equal(cairo_surface_status(s), CAIRO_STATUS_SUCCESS);
    assert_int_equal(cairo_image_surface_get_width(s), 640);
    assert_int_equal(cairo_image_surface_get_height(s), 400);
    /* the first series' colour (Okabe-Ito blue 0, 115, 179) appears */
    int found = 0, rgb[3];
    for (int yy = 0; yy < 400 && !found; yy++)
        for (int xx = 0; xx < 640 && !found; xx++) {
            pixel(s, xx, yy, rgb);
            found = abs(rgb[0] - 0) < 20 && abs(rgb[1] - 115) < 20 && abs(rgb[2] - 179) < 20;
        }
    assert_true(found);
    cairo_surface_destroy(s);
    unlink(png);
    double ticks[16];
    size_t nt = plot_nice_ticks(0.0, 1.0, 5, ticks, 16);
    assert_int_equal(nt, 6);
    assert_true(fabs(ticks[5] - 1.0) < 1e-12);
}

static void test_report(void **state)
{
    (void)state;
    struct vreport r = {0};
    r.keep_series = 1;
    r.current_case = "demo-case";
    struct spall_error err = {0};
    double x[3] = {0, 1, 2}, y[3] = {0, 1, 4};
    assert_int_equal(vreport_check(&r, "q", "m", 1.0, 1.001, 0.01, true, "src", "note", &err), 0);
    assert_int_equal(vreport_series(&r, "p", "x", "y", "meas", VSERIES_LINE, x, y, 3, &err), 0);
    assert_int_equal(vreport_marker(&r, "p", "ref", VSERIES_XMARK, 1.5, &err), 0);
    char dir[64], path[128];
    snprintf(dir, sizeof dir, "report_test_%d", (int)getpid());
    assert_int_equal(vreport_write_report(&r, dir, &err), SPALL_OK);
    snprintf(path, sizeof path, "%s/report.md", dir);
    FILE *f = fopen(path, "r");
    assert_non_null(f);
    char buf[4096];
    size_t n = fread(buf, 1, sizeof buf - 1, f);
    buf[n] = '\0';
    fclose(f);
    assert_non_null(strstr(buf, "| demo-case | q | m |"));
    assert_non_null(strstr(buf, "demo-case_1.png"));
    unlink(path);
    snprintf(path, sizeof path, "%s/demo-case_1.png", dir);
    assert_int_equal(access(path, R_OK), 0);
    unlink(path);
    rmdir(dir);
    vreport_free(&r);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_render_points),
        cmocka_unit_test(test_render_frame),
        cmocka_unit_test(test_plot),
        cmocka_unit_test(test_report),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
