/**
 * @file plot.h
 * @brief Generic x-y line plots written as PNG through cairo: axes with
 *        "nice" ticks, labels, a legend, several series (lines or points) and
 *        reference lines (vertical or horizontal markers).  Used by
 *        `spall validate --report` for time histories against references,
 *        and shared helpers (ticks, colours, SI prefixes) used by render.c.
 */
#ifndef SPALL_PLOT_H
#define SPALL_PLOT_H

#include <stddef.h>

struct spall_error;

/** How a series is drawn. */
enum plot_style {
    PLOT_LINE = 0,   /**< solid polyline */
    PLOT_DASHED = 1, /**< dashed polyline (references) */
    PLOT_POINTS = 2  /**< filled dots (measurements, experimental points) */
};

/** One data series (borrowed arrays, n points). */
struct plot_series {
    const char *label; /**< legend entry (NULL: none) */
    const double *x, *y;
    size_t n;
    enum plot_style style;
};

/** A reference line across the whole plot: axis 'x' draws a vertical line at
 *  x = value, axis 'y' a horizontal one at y = value. */
struct plot_refline {
    char axis;
    double value;
    const char *label; /**< written next to the line (NULL: none) */
};

/** What to plot. */
struct plot_spec {
    const char *title, *xlabel, *ylabel;
    int width, height; /**< pixels; 0: 800 x 500 */
    const struct plot_series *series;
    size_t n_series;
    const struct plot_refline *refs;
    size_t n_refs;
};

/** Write the plot as a PNG.  Non-finite points are skipped; an empty plot
 *  (no finite point) still gets axes. */
int plot_png(const char *path, const struct plot_spec *spec, struct spall_error *err);

/** Up to @p max "nice" tick values (1, 2, 5 x 10^k steps, about @p target of
 *  them) inside [lo, hi]; returns how many were written. */
size_t plot_nice_ticks(double lo, double hi, int target, double *ticks, size_t max);

/** Colour of series k of the default palette (r, g, b in [0, 1]). */
void plot_palette(size_t k, double rgb[3]);

/** Format @p v compactly for a tick label (%g with up to 4 significant digits,
 *  -0 printed as 0). */
void plot_format_tick(char *buf, size_t len, double v, double step);

#endif
