/**
 * @file plot.c
 * @brief x-y line plots with cairo (see plot.h).  Drawing only: no file
 *        format parsing, no global state; every call builds its own surface.
 */
#include "core/mathconst.h"
#include "io/canvas.h"
#include "io/plot.h"

#include "spall/error.h"

#include <math.h>
#include <stdio.h>
#include <string.h>


size_t plot_nice_ticks(double lo, double hi, int target, double *ticks, size_t max)
{
    if (!(isfinite(lo) && isfinite(hi)) || max == 0)
        return 0;
    if (hi < lo) {
        double t = lo;
        lo = hi;
        hi = t;
    }
    if (hi == lo) {
        ticks[0] = lo;
        return 1;
    }
    if (target < 2)
        target = 2;
    double raw = (hi - lo) / target;
    double mag = pow(10.0, floor(log10(raw)));
    double f = raw / mag;
    double step = (f < 1.5 ? 1.0 : f < 3.5 ? 2.0 : f < 7.5 ? 5.0 : 10.0) * mag;
    double first = ceil(lo / step - 1e-9) * step;
    size_t n = 0;
    for (double v = first; v <= hi + 1e-9 * step && n < max; v = first + step * (double)n) {
        ticks[n++] = fabs(v) < 1e-12 * step ? 0.0 : v;
    }
    return n;
}

void plot_format_tick(char *buf, size_t len, double v, double step)
{
    if (fabs(v) < 1e-12 * fabs(step))
        v = 0.0;
    snprintf(buf, len, "%.4g", v);
}

void plot_palette(size_t k, double rgb[3])
{
    /* colour-blind-friendly (Okabe-Ito) */
    static const double pal[8][3] = {{0.00, 0.45, 0.70}, {0.84, 0.37, 0.00}, {0.00, 0.62, 0.45},
                                     {0.80, 0.47, 0.65}, {0.34, 0.71, 0.91}, {0.90, 0.62, 0.00},
                                     {0.50, 0.50, 0.50}, {0.00, 0.00, 0.00}};
    memcpy(rgb, pal[k % 8], 3 * sizeof(double));
}

struct plot_box {
    double x0, y0, w, h;       /* plot area in pixels */
    double xmin, xmax, ymin, ymax;
};

static double px(const struct plot_box *b, double x)
{
    return b->x0 + (x - b->xmin) / (b->xmax - b->xmin) * b->w;
}

static double py(const struct plot_box *b, double y)
{
    return b->y0 + b->h - (y - b->ymin) / (b->ymax - b->ymin) * b->h;
}

static void widen(double *lo, double *hi)
{
    if (!(isfinite(*lo) && isfinite(*hi))) {
        *lo = 0.0;
        *hi = 1.0;
    } else if (*hi <= *lo) {
        double d = fabs(*lo) > 0 ? 0.05 * fabs(*lo) : 1.0;
        *lo -= d;
        *hi += d;
    } else {
        double d = 0.04 * (*hi - *lo);
        *lo -= d;
        *hi += d;
    }
}

static void data_range(const struct plot_spec *s, struct plot_box *b)
{
    b->xmin = b->ymin = INFINITY;
    b->xmax = b->ymax = -INFINITY;
    for (size_t k = 0; k < s->n_series; k++) {
        const struct plot_series *ser = &s->series[k];
        for (size_t i = 0; i < ser->n; i++) {
            if (!isfinite(ser->x[i]) || !isfinite(ser->y[i]))
                continue;
            b->xmin = fmin(b->xmin, ser->x[i]);
            b->xmax = fmax(b->xmax, ser->x[i]);
            b->ymin = fmin(b->ymin, ser->y[i]);
            b->ymax = fmax(b->ymax, ser->y[i]);
        }
    }
    for (size_t k = 0; k < s->n_refs; k++) {
        double v = s->refs[k].value;
        if (!isfinite(v))
            continue;
        if (s->refs[k].axis == 'x') {
            b->xmin = fmin(b->xmin, v);
            b->xmax = fmax(b->xmax, v);
        } else {
            b->ymin = fmin(b->ymin, v);
            b->ymax = fmax(b->ymax, v);
        }
    }
    widen(&b->xmin, &b->xmax);
    widen(&b->ymin, &b->ymax);
}

static void text_at(struct canvas *cr, double x, double y, const char *s, double ax, double ay)
{
    cairo_text_extents_t e;
    canvas_text_extents(cr, s, &e);
    canvas_move_to(cr, x - ax * e.width - e.x_bearing, y - ay * e.height - e.y_bearing);
    canvas_show_text(cr, s);
}

static void draw_axes(struct canvas *cr, const struct plot_spec *s, const struct plot_box *b)
{
    double ticks[32];
    char lab[48];
    canvas_set_font_size(cr, 12.0);
    /* grid + ticks */
    size_t nx = plot_nice_ticks(b->xmin, b->xmax, 6, ticks, 32);
    double step = nx > 1 ? ticks[1] - ticks[0] : 1.0;
    for (size_t k = 0; k < nx; k++) {
        double x = px(b, ticks[k]);
        canvas_set_source_rgb(cr, 0.9, 0.9, 0.9);
        canvas_move_to(cr, x, b->y0);
        canvas_line_to(cr, x, b->y0 + b->h);
        canvas_stroke(cr);
        canvas_set_source_rgb(cr, 0, 0, 0);
        plot_format_tick(lab, sizeof lab, ticks[k], step);
        text_at(cr, x, b->y0 + b->h + 6, lab, 0.5, 0.0);
    }
    size_t ny = plot_nice_ticks(b->ymin, b->ymax, 6, ticks, 32);
    step = ny > 1 ? ticks[1] - ticks[0] : 1.0;
    for (size_t k = 0; k < ny; k++) {
        double y = py(b, ticks[k]);
        canvas_set_source_rgb(cr, 0.9, 0.9, 0.9);
        canvas_move_to(cr, b->x0, y);
        canvas_line_to(cr, b->x0 + b->w, y);
        canvas_stroke(cr);
        canvas_set_source_rgb(cr, 0, 0, 0);
        plot_format_tick(lab, sizeof lab, ticks[k], step);
        text_at(cr, b->x0 - 6, y, lab, 1.0, 0.5);
    }
    canvas_set_source_rgb(cr, 0, 0, 0);
    canvas_rectangle(cr, b->x0, b->y0, b->w, b->h);
    canvas_stroke(cr);
    canvas_set_font_size(cr, 13.0);
    if (s->xlabel)
        text_at(cr, b->x0 + 0.5 * b->w, b->y0 + b->h + 28, s->xlabel, 0.5, 0.0);
    if (s->ylabel) {
        canvas_save(cr);
        canvas_translate(cr, 16, b->y0 + 0.5 * b->h);
        canvas_rotate(cr, -SPALL_PI / 2.0);
        text_at(cr, 0, 0, s->ylabel, 0.5, 0.5);
        canvas_restore(cr);
    }
    if (s->title) {
        canvas_set_font_size(cr, 14.0);
        text_at(cr, b->x0 + 0.5 * b->w, 10, s->title, 0.5, 0.0);
    }
}

static void draw_series(struct canvas *cr, const struct plot_series *ser, const struct plot_box *b,
                        const double rgb[3])
{
    canvas_set_source_rgb(cr, rgb[0], rgb[1], rgb[2]);
    if (ser->style == PLOT_POINTS) {
        for (size_t i = 0; i < ser->n; i++) {
            if (!isfinite(ser->x[i]) || !isfinite(ser->y[i]))
                continue;
            canvas_arc(cr, px(b, ser->x[i]), py(b, ser->y[i]), 3.5, 0, 2 * SPALL_PI);
            canvas_fill(cr);
        }
        return;
    }
    double dash[2] = {7.0, 4.0};
    canvas_set_dash(cr, dash, ser->style == PLOT_DASHED ? 2 : 0, 0.0);
    canvas_set_line_width(cr, 1.8);
    int pen = 0;
    for (size_t i = 0; i < ser->n; i++) {
        if (!isfinite(ser->x[i]) || !isfinite(ser->y[i])) {
            pen = 0;
            continue;
        }
        if (pen)
            canvas_line_to(cr, px(b, ser->x[i]), py(b, ser->y[i]));
        else
            canvas_move_to(cr, px(b, ser->x[i]), py(b, ser->y[i]));
        pen = 1;
    }
    canvas_stroke(cr);
    canvas_set_dash(cr, dash, 0, 0.0);
    canvas_set_line_width(cr, 1.0);
}

static void draw_refs(struct canvas *cr, const struct plot_spec *s, const struct plot_box *b)
{
    double dash[2] = {3.0, 3.0};
    canvas_set_font_size(cr, 11.0);
    for (size_t k = 0; k < s->n_refs; k++) {
        const struct plot_refline *r = &s->refs[k];
        if (!isfinite(r->value))
            continue;
        canvas_set_source_rgb(cr, 0.75, 0.1, 0.1);
        canvas_set_dash(cr, dash, 2, 0.0);
        if (r->axis == 'x') {
            double x = px(b, r->value);
            canvas_move_to(cr, x, b->y0);
            canvas_line_to(cr, x, b->y0 + b->h);
            canvas_stroke(cr);
            canvas_set_dash(cr, dash, 0, 0.0);
            if (r->label) {
                canvas_save(cr);
                canvas_translate(cr, x + 3, b->y0 + 4 + 0.0 * (double)k);
                canvas_rotate(cr, SPALL_PI / 2.0);
                text_at(cr, 0, 0, r->label, 0.0, 1.0);
                canvas_restore(cr);
            }
        } else {
            double y = py(b, r->value);
            canvas_move_to(cr, b->x0, y);
            canvas_line_to(cr, b->x0 + b->w, y);
            canvas_stroke(cr);
            canvas_set_dash(cr, dash, 0, 0.0);
            if (r->label)
                text_at(cr, b->x0 + b->w - 4, y - 3, r->label, 1.0, 1.0);
        }
    }
    canvas_set_dash(cr, dash, 0, 0.0);
}

static void draw_legend(struct canvas *cr, const struct plot_spec *s, const struct plot_box *b)
{
    size_t n = 0;
    double wmax = 0.0;
    canvas_set_font_size(cr, 12.0);
    for (size_t k = 0; k < s->n_series; k++) {
        if (!s->series[k].label)
            continue;
        cairo_text_extents_t e;
        canvas_text_extents(cr, s->series[k].label, &e);
        wmax = fmax(wmax, e.x_advance);
        n++;
    }
    if (n == 0)
        return;
    double lw = wmax + 48, lh = 18.0 * (double)n + 8;
    double x = b->x0 + 8, y = b->y0 + 8;
    canvas_set_source_rgba(cr, 1, 1, 1, 0.85);
    canvas_rectangle(cr, x, y, lw, lh);
    canvas_fill_preserve(cr);
    canvas_set_source_rgb(cr, 0.6, 0.6, 0.6);
    canvas_stroke(cr);
    size_t row = 0;
    for (size_t k = 0; k < s->n_series; k++) {
        const struct plot_series *ser = &s->series[k];
        if (!ser->label)
            continue;
        double rgb[3];
        plot_palette(k, rgb);
        double yy = y + 13 + 18.0 * (double)row++;
        double xs[2] = {x + 6, x + 34}, ys[2] = {yy, yy};
        /* identity mapping: px(x) = x, py(y) = -1 + 1 + y = y */
        const struct plot_box id = {.x0 = 0, .y0 = -1, .w = 1, .h = 1,
                                    .xmin = 0, .xmax = 1, .ymin = 0, .ymax = -1};
        struct plot_series sample = {NULL, xs, ys, 2, ser->style};
        if (ser->style == PLOT_POINTS) {
            double xm = 0.5 * (xs[0] + xs[1]);
            sample.x = &xm;
            sample.y = &ys[0];
            sample.n = 1;
            draw_series(cr, &sample, &id, rgb);
        } else {
            draw_series(cr, &sample, &id, rgb);
        }
        canvas_set_source_rgb(cr, 0, 0, 0);
        text_at(cr, x + 40, yy, ser->label, 0.0, 0.5);
    }
}

int plot_png(const char *path, const struct plot_spec *spec, struct spall_error *err)
{
    int w = spec->width > 0 ? spec->width : 800, h = spec->height > 0 ? spec->height : 500;
    if (w < 200 || h < 150 || w > 8000 || h > 8000)
        return spall_error_set(err, SPALL_ERR_INPUT, "plot size %d x %d px out of range", w, h);
    struct canvas canvas, *cr = &canvas;
    int rc = canvas_open(cr, w, h, err);
    if (rc)
        return rc;
    canvas_set_source_rgb(cr, 1, 1, 1);
    canvas_paint(cr);
    canvas_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
    canvas_set_line_width(cr, 1.0);
    struct plot_box b;
    data_range(spec, &b);
    b.x0 = 80;
    b.y0 = 34;
    b.w = w - b.x0 - 20;
    b.h = h - b.y0 - 60;
    draw_axes(cr, spec, &b);
    canvas_save(cr);
    canvas_rectangle(cr, b.x0, b.y0, b.w, b.h);
    canvas_clip(cr);
    for (size_t k = 0; k < spec->n_series; k++) {
        double rgb[3];
        plot_palette(k, rgb);
        draw_series(cr, &spec->series[k], &b, rgb);
    }
    draw_refs(cr, spec, &b);
    canvas_restore(cr);
    draw_legend(cr, spec, &b);
    return canvas_write_png(cr, path, "plot", err);
}
