/**
 * @file render.c
 * @brief Particle-field pictures (see render.h): HDF5 frame -> scalar per
 *        particle -> discs on a cairo surface, with colour bar, length scale
 *        and time.
 */
#include "core/mathconst.h"
#include "io/canvas.h"
#include "io/render.h"

#include "io/output.h"
#include "io/plot.h"
#include "spall/error.h"

#include <hdf5.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>


void render_options_default(struct render_options *o, const char *field)
{
    memset(o, 0, sizeof *o);
    o->field = field;
    o->component = RENDER_AUTO;
    o->width = 800;
    o->vmin = o->vmax = NAN;
    o->slice_z = NAN;
    o->slice_axis = 2;
    o->categorical = field && (strcmp(field, "fragment_id") == 0 || strcmp(field, "material") == 0 ||
                               strcmp(field, "id") == 0);
}

/* viridis, sampled every 0.1 (perceptually uniform, readable in grey) */
static void colormap(double t, double rgb[3])
{
    static const double v[11][3] = {
        {0.267, 0.005, 0.329}, {0.283, 0.141, 0.458}, {0.254, 0.265, 0.530}, {0.207, 0.372, 0.553},
        {0.164, 0.471, 0.558}, {0.128, 0.567, 0.551}, {0.134, 0.658, 0.518}, {0.267, 0.749, 0.441},
        {0.478, 0.821, 0.318}, {0.741, 0.873, 0.150}, {0.993, 0.906, 0.144}};
    if (!isfinite(t))
        t = 0.0;
    t = t < 0.0 ? 0.0 : t > 1.0 ? 1.0 : t;
    double s = t * 10.0;
    int k = (int)s;
    if (k >= 10)
        k = 9;
    double f = s - k;
    for (int c = 0; c < 3; c++)
        rgb[c] = v[k][c] + f * (v[k + 1][c] - v[k][c]);
}

/* distinct colours for integer ids: golden-ratio hue steps */
static void category_colour(double value, double rgb[3])
{
    long long id = (long long)llround(value);
    double h = fmod(0.13 + 0.6180339887498949 * (double)(id < 0 ? -id : id), 1.0) * 6.0;
    double s = 0.75, vv = (id % 3 == 0) ? 0.95 : (id % 3 == 1 ? 0.8 : 0.65);
    int i = (int)h;
    double f = h - i, p = vv * (1 - s), q = vv * (1 - s * f), t = vv * (1 - s * (1 - f));
    double r[6] = {vv, q, p, p, t, vv}, g[6] = {t, vv, vv, q, p, p}, b[6] = {p, p, t, vv, vv, q};
    rgb[0] = r[i % 6];
    rgb[1] = g[i % 6];
    rgb[2] = b[i % 6];
}

static void text_at(struct canvas *cr, double x, double y, const char *s, double ax, double ay)
{
    cairo_text_extents_t e;
    canvas_text_extents(cr, s, &e);
    canvas_move_to(cr, x - ax * e.width - e.x_bearing, y - ay * e.height - e.y_bearing);
    canvas_show_text(cr, s);
}

static void format_length(char *buf, size_t len, double L)
{
    if (L >= 1.0)
        snprintf(buf, len, "%g m", L);
    else if (L >= 1e-2)
        snprintf(buf, len, "%g cm", L * 1e2);
    else if (L >= 1e-3)
        snprintf(buf, len, "%g mm", L * 1e3);
    else if (L >= 1e-6)
        snprintf(buf, len, "%g um", L * 1e6);
    else
        snprintf(buf, len, "%g nm", L * 1e9);
}

static void format_time(char *buf, size_t len, double t)
{
    double a = fabs(t);
    if (a == 0.0 || a >= 1.0)
        snprintf(buf, len, "t = %.4g s", t);
    else if (a >= 1e-3)
        snprintf(buf, len, "t = %.4g ms", t * 1e3);
    else if (a >= 1e-6)
        snprintf(buf, len, "t = %.4g us", t * 1e6);
    else
        snprintf(buf, len, "t = %.4g ns", t * 1e9);
}

/* median nearest-neighbour distance of up to 256 evenly picked particles */
static double estimate_spacing(const double *pos, const unsigned char *keep, size_t n)
{
    double d[256];
    size_t m = 0, stride = n > 256 ? n / 256 : 1;
    for (size_t a = 0; a < n && m < 256; a += stride) {
        if (!keep[a])
            continue;
        double best = INFINITY;
        for (size_t b = 0; b < n; b++) {
            if (b == a || !keep[b])
                continue;
            double r2 = 0.0;
            for (int c = 0; c < 3; c++) {
                double dx = pos[3 * b + c] - pos[3 * a + c];
                r2 += dx * dx;
            }
            if (r2 > 0.0 && r2 < best)
                best = r2;
        }
        if (isfinite(best))
            d[m++] = sqrt(best);
    }
    if (m == 0)
        return NAN;
    for (size_t i = 1; i < m; i++) /* insertion sort, m <= 256 */
        for (size_t j = i; j > 0 && d[j] < d[j - 1]; j--) {
            double t = d[j];
            d[j] = d[j - 1];
            d[j - 1] = t;
        }
    return d[m / 2];
}

static void draw_colour_bar(struct canvas *cr, double x, double y, double h, double vmin,
                            double vmax)
{
    const int steps = 128;
    for (int k = 0; k < steps; k++) {
        double rgb[3];
        colormap((k + 0.5) / steps, rgb);
        canvas_set_source_rgb(cr, rgb[0], rgb[1], rgb[2]);
        canvas_rectangle(cr, x, y + h - (k + 1) * h / steps, 20, h / steps + 0.5);
        canvas_fill(cr);
    }
    canvas_set_source_rgb(cr, 0, 0, 0);
    canvas_rectangle(cr, x, y, 20, h);
    canvas_stroke(cr);
    double ticks[16];
    size_t nt = plot_nice_ticks(vmin, vmax, 5, ticks, 16);
    double step = nt > 1 ? ticks[1] - ticks[0] : fabs(vmax - vmin);
    canvas_set_font_size(cr, 12.0);
    for (size_t k = 0; k < nt; k++) {
        double yy = y + h - (ticks[k] - vmin) / (vmax - vmin) * h;
        char lab[48];
        plot_format_tick(lab, sizeof lab, ticks[k], step);
        canvas_move_to(cr, x + 20, yy);
        canvas_line_to(cr, x + 25, yy);
        canvas_stroke(cr);
        text_at(cr, x + 28, yy, lab, 0.0, 0.5);
    }
}

int render_points_png(const char *png_path, const struct render_points *d,
                      const struct render_options *o, struct spall_error *err)
{
    if (d->n == 0)
        return spall_error_set(err, SPALL_ERR_INPUT, "nothing to render: no particles");
    if (o->width < 200 || o->width > 8000)
        return spall_error_set(err, SPALL_ERR_INPUT, "image width %d px out of range [200, 8000]",
                               o->width);
    const size_t n = d->n;
    const double *geo = d->ref ? d->ref : d->pos; /* slice and spacing from the reference */
    unsigned char *keep = malloc(n);
    if (!keep)
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory rendering '%s'", png_path);
    double zmin = INFINITY, zmax = -INFINITY;
    for (size_t i = 0; i < n; i++) {
        zmin = fmin(zmin, geo[3 * i + 2]);
        zmax = fmax(zmax, geo[3 * i + 2]);
        keep[i] = 1;
    }
    double h = estimate_spacing(geo, keep, n);
    int is3d = zmax - zmin > 1e-9 * fmax(1e-30, fabs(zmax) + fabs(zmin)) && zmax > zmin;
    double zc = isfinite(o->slice_z) ? o->slice_z : 0.5 * (zmin + zmax);
    if (is3d) {
        size_t kept = 0;
        for (size_t i = 0; i < n; i++) {
            keep[i] = fabs(geo[3 * i + 2] - zc) <= 0.6 * h;
            kept += keep[i];
        }
        if (kept == 0) {
            free(keep);
            return spall_error_set(err, SPALL_ERR_INPUT,
                                   "no particle within 0.6 spacing of the slice %c = %g m",
                                   "xyz"[o->slice_axis >= 0 && o->slice_axis < 3 ? o->slice_axis : 2],
                                   zc);
        }
    }
    if (!isfinite(h) || h <= 0.0)
        h = 1.0;
    /* extent and colour range over the drawn particles */
    double xmin = INFINITY, xmax = -INFINITY, ymin = INFINITY, ymax = -INFINITY;
    double vmin = INFINITY, vmax = -INFINITY;
    for (size_t i = 0; i < n; i++) {
        if (!keep[i])
            continue;
        xmin = fmin(xmin, d->pos[3 * i]);
        xmax = fmax(xmax, d->pos[3 * i]);
        ymin = fmin(ymin, d->pos[3 * i + 1]);
        ymax = fmax(ymax, d->pos[3 * i + 1]);
        if (isfinite(d->value[i])) {
            vmin = fmin(vmin, d->value[i]);
            vmax = fmax(vmax, d->value[i]);
        }
    }
    if (isfinite(o->vmin))
        vmin = o->vmin;
    if (isfinite(o->vmax))
        vmax = o->vmax;
    if (!(isfinite(vmin) && isfinite(vmax))) {
        vmin = 0.0;
        vmax = 1.0;
    }
    if (vmax <= vmin) {
        double pad = fabs(vmin) > 0 ? 1e-3 * fabs(vmin) : 1.0;
        vmin -= pad;
        vmax += pad;
    }
    xmin -= h;
    xmax += h;
    ymin -= h;
    ymax += h;
    const double left = 20, right = 130, top = 40, bottom = 60;
    double maxw = o->width - left - right, maxh = 1.6 * o->width;
    double scale = fmin(maxw / (xmax - xmin), maxh / (ymax - ymin));
    double pw = scale * (xmax - xmin), ph = scale * (ymax - ymin);
    int W = (int)ceil(left + fmax(pw, 200.0) + right), H = (int)ceil(top + fmax(ph, 150.0) + bottom);
    struct canvas canvas, *cr = &canvas;
    int rc = canvas_open(cr, W, H, err);
    if (rc) {
        free(keep);
        return rc;
    }
    canvas_set_source_rgb(cr, 1, 1, 1);
    canvas_paint(cr);
    canvas_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
    canvas_set_line_width(cr, 1.0);
    double rad = fmax(0.7, 0.55 * h * scale);
    for (size_t i = 0; i < n; i++) {
        if (!keep[i])
            continue;
        double rgb[3];
        double v = d->value[i];
        if (!isfinite(v)) {
            rgb[0] = rgb[1] = rgb[2] = 0.6;
        } else if (o->categorical) {
            category_colour(v, rgb);
        } else {
            colormap((v - vmin) / (vmax - vmin), rgb);
        }
        double X = left + (d->pos[3 * i] - xmin) * scale;
        double Y = top + ph - (d->pos[3 * i + 1] - ymin) * scale;
        canvas_set_source_rgb(cr, rgb[0], rgb[1], rgb[2]);
        if (rad < 2.0)
            canvas_rectangle(cr, X - rad, Y - rad, 2 * rad, 2 * rad);
        else
            canvas_arc(cr, X, Y, rad, 0.0, 2.0 * SPALL_PI);
        canvas_fill(cr);
    }
    /* header: title / label and time */
    canvas_set_source_rgb(cr, 0, 0, 0);
    canvas_set_font_size(cr, 14.0);
    char buf[160];
    snprintf(buf, sizeof buf, "%s%s", d->label ? d->label : (o->title ? o->title : ""),
             is3d ? "" : "");
    text_at(cr, left, 12, buf, 0.0, 0.0);
    if (isfinite(d->time)) {
        format_time(buf, sizeof buf, d->time);
        text_at(cr, W - 10, 12, buf, 1.0, 0.0);
    }
    if (is3d) {
        canvas_set_font_size(cr, 11.0);
        snprintf(buf, sizeof buf, "slice %c = %.4g m",
                 "xyz"[o->slice_axis >= 0 && o->slice_axis < 3 ? o->slice_axis : 2], zc);
        text_at(cr, W - 10, 28, buf, 1.0, 0.0);
    }
    /* length scale: a 1/2/5 x 10^k length near a quarter of the width */
    double target = 0.25 * (xmax - xmin);
    double mag = pow(10.0, floor(log10(target)));
    double L = target / mag >= 5 ? 5 * mag : target / mag >= 2 ? 2 * mag : mag;
    double y_bar = top + ph + 25;
    canvas_set_line_width(cr, 3.0);
    canvas_move_to(cr, left, y_bar);
    canvas_line_to(cr, left + L * scale, y_bar);
    canvas_stroke(cr);
    canvas_set_line_width(cr, 1.0);
    format_length(buf, sizeof buf, L);
    canvas_set_font_size(cr, 12.0);
    text_at(cr, left + 0.5 * L * scale, y_bar + 6, buf, 0.5, 0.0);
    /* colour bar or category note */
    double bx = left + fmax(pw, 200.0) + 20, bh = fmin(fmax(ph * 0.8, 100.0), 400.0);
    if (o->categorical) {
        canvas_set_font_size(cr, 12.0);
        text_at(cr, bx, top + 10, "colour = id", 0.0, 0.0);
    } else {
        draw_colour_bar(cr, bx, top + 0.5 * (ph - bh), bh, vmin, vmax);
    }
    free(keep);
    return canvas_write_png(cr, png_path, "picture", err);
}

/* the dataset's "unit" attribute (empty if absent) */
static void read_unit(const char *h5_path, const char *name, char *unit, size_t len)
{
    unit[0] = '\0';
    H5E_auto2_t func;
    void *data;
    H5Eget_auto2(H5E_DEFAULT, &func, &data);
    H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
    hid_t f = H5Fopen(h5_path, H5F_ACC_RDONLY, H5P_DEFAULT);
    if (f >= 0) {
        if (H5Aexists_by_name(f, name, "unit", H5P_DEFAULT) > 0) {
            hid_t a = H5Aopen_by_name(f, name, "unit", H5P_DEFAULT, H5P_DEFAULT);
            hid_t t = a >= 0 ? H5Aget_type(a) : -1;
            if (t >= 0 && H5Tget_class(t) == H5T_STRING && !H5Tis_variable_str(t)) {
                size_t sz = H5Tget_size(t);
                char tmp[64];
                if (sz < sizeof tmp && H5Aread(a, t, tmp) >= 0) {
                    tmp[sz] = '\0';
                    snprintf(unit, len, "%s", tmp);
                }
            }
            if (t >= 0)
                H5Tclose(t);
            if (a >= 0)
                H5Aclose(a);
        }
        H5Fclose(f);
    }
    H5Eset_auto2(H5E_DEFAULT, func, data);
}

/* positions as n x 3 (pad 1D/2D with zeros) */
static int to_xyz(double *src, size_t n, size_t nc, double **out, struct spall_error *err)
{
    double *p = calloc(3 * n + 1, sizeof *p);
    if (!p)
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory rendering");
    for (size_t i = 0; i < n; i++)
        for (size_t c = 0; c < nc && c < 3; c++)
            p[3 * i + c] = src[i * nc + c];
    *out = p;
    return SPALL_OK;
}

int render_frame_png(const char *h5_path, const char *png_path, const struct render_options *opt,
                     struct spall_error *err)
{
    double *pos_raw = NULL, *val = NULL, *ref_raw = NULL, *pos = NULL, *ref = NULL, *scalar = NULL;
    size_t n = 0, npc = 0, nv = 0, nvc = 0;
    double time = NAN;
    /* the field: one the run wrote (render_select.c) */
    char fname[RENDER_NAME_LEN];
    int rc = render_pick_field(h5_path, opt->field, fname, sizeof fname, err);
    if (rc)
        return rc;
    struct render_options oo = *opt;
    const struct render_options *o = &oo;
    oo.field = fname;
    if (!opt->field) {
        struct render_options def;
        render_options_default(&def, fname);
        oo.categorical = def.categorical;
    }
    rc = field_frame_read(h5_path, "position", &pos_raw, &n, &npc, &time, err);
    if (rc)
        return rc;
    if (npc == 0)
        npc = 1;
    /* the run's dimension: positions are written with 3 components (the
     * XDMF geometry), zero beyond the run's own */
    size_t dim = npc;
    while (dim > 1) {
        size_t i = 0;
        while (i < n && pos_raw[i * npc + dim - 1] == 0.0)
            i++;
        if (i < n)
            break;
        dim--;
    }
    if (dim < 3 && o->slice_axis != 2) {
        rc = spall_error_set(err, SPALL_ERR_INPUT, "'%s' is a %zuD run: there is no slice to "
                             "choose (--slice is for 3D runs)", h5_path, dim);
        goto done;
    }
    if ((rc = field_frame_read(h5_path, o->field, &val, &nv, &nvc, NULL, err)))
        goto done;
    if (nvc == 0)
        nvc = 1;
    if (nv != n) {
        rc = spall_error_set(err, SPALL_ERR_INPUT, "'%s': field '%s' has %zu rows, position %zu",
                             h5_path, o->field, nv, n);
        goto done;
    }
    if ((rc = to_xyz(pos_raw, n, npc, &pos, err)))
        goto done;
    if (o->reference) {
        size_t nr = 0, nrc = 0;
        struct spall_error e2 = {0};
        if (field_frame_read(h5_path, "reference_position", &ref_raw, &nr, &nrc, NULL, &e2) == 0 &&
            nr == n) {
            if ((rc = to_xyz(ref_raw, n, nrc ? nrc : 1, &ref, err)))
                goto done;
        } else {
            free(ref_raw);
            ref_raw = NULL;
            if (field_frame_read(h5_path, "displacement", &ref_raw, &nr, &nrc, NULL, &e2) != 0 ||
                nr != n) {
                rc = spall_error_set(err, SPALL_ERR_INPUT,
                                     "'%s' has neither reference_position nor displacement; cannot "
                                     "draw the reference configuration",
                                     h5_path);
                goto done;
            }
            if ((rc = to_xyz(ref_raw, n, nrc ? nrc : 1, &ref, err)))
                goto done;
            for (size_t i = 0; i < 3 * n; i++)
                ref[i] = pos[i] - ref[i];
        }
    }
    render_slice_axis(pos, n, o->slice_axis); /* 3D: the slice axis becomes the depth */
    render_slice_axis(ref, n, o->slice_axis);
    int comp = o->component;
    if (o->component_name &&
        (rc = render_component_index(o->component_name, o->field, nvc, dim, &comp, err)))
        goto done;
    if (comp == RENDER_AUTO) {
        int vec = strcmp(o->field, "velocity") == 0 || strcmp(o->field, "displacement") == 0 ||
                  strcmp(o->field, "force") == 0 || strcmp(o->field, "position") == 0;
        comp = (nvc > 1 && vec) ? RENDER_MAGNITUDE : 0;
    }
    if (comp >= (int)nvc) {
        rc = spall_error_set(err, SPALL_ERR_INPUT, "field '%s' has %zu component(s); component %d "
                             "does not exist", o->field, nvc, comp);
        goto done;
    }
    scalar = malloc((n ? n : 1) * sizeof *scalar);
    if (!scalar) {
        rc = spall_error_set(err, SPALL_ERR_NOMEM, "out of memory rendering");
        goto done;
    }
    for (size_t i = 0; i < n; i++) {
        if (comp == RENDER_MAGNITUDE) {
            double s2 = 0.0;
            for (size_t c = 0; c < nvc; c++)
                s2 += val[i * nvc + c] * val[i * nvc + c];
            scalar[i] = sqrt(s2);
        } else {
            scalar[i] = val[i * nvc + (size_t)comp];
        }
    }
    char unit[64], label[160];
    read_unit(h5_path, o->field, unit, sizeof unit);
    char cname[16] = "";
    if (nvc > 1) {
        if (comp == RENDER_MAGNITUDE)
            snprintf(cname, sizeof cname, " |.|");
        else if (o->component_name)
            snprintf(cname, sizeof cname, " %.8s", o->component_name);
        else
            snprintf(cname, sizeof cname, " [%d]", comp);
    }
    snprintf(label, sizeof label, "%s%s%s%s%s", o->title ? o->title : o->field, cname,
             unit[0] ? " (" : "", unit, unit[0] ? ")" : "");
    struct render_points pts = {n, o->reference ? ref : pos, ref, scalar, time, label};
    rc = render_points_png(png_path, &pts, o, err);
done:
    free(pos_raw);
    free(val);
    free(ref_raw);
    free(pos);
    free(ref);
    free(scalar);
    return rc;
}
