/**
 * @file canvas.h
 * @brief The cairo drawing calls of plot.c and render.c, through cairo
 *        loaded when a picture is drawn (dlopen) instead of at start-up.
 *
 * Linked, cairo and what it loads (pixman, X11, FreeType, fontconfig, PNG:
 * 1.8 MiB resident) were mapped by every process, every MPI rank included,
 * though only `plot`, `render` and post-processing draw
 * (docs/performance.md "State-based PD: distributed set-up memory").
 * canvas_X(c, ...) is cairo_X(cr, ...) on the canvas's context; cairo's
 * header gives the types only.  No global state: each canvas holds its own
 * handle and function table.
 */
#ifndef SPALL_IO_CANVAS_H
#define SPALL_IO_CANVAS_H

#include "spall/error.h"

#include <cairo.h>

/* X(name, (, parameters), (, arguments)): the drawing calls used, as
 * cairo_name(cr, ...); the lists start with their comma (none: empty) */
#define CANVAS_STRIP(...) __VA_ARGS__
#define CANVAS_DRAW_CALLS(X)                                                              \
    X(set_source_rgb, (, double r, double g, double b), (, r, g, b))                      \
    X(set_source_rgba, (, double r, double g, double b, double a), (, r, g, b, a))        \
    X(paint, (), ())                                                                      \
    X(select_font_face, (, const char *family, cairo_font_slant_t slant,                  \
                         cairo_font_weight_t weight), (, family, slant, weight))          \
    X(set_font_size, (, double size), (, size))                                           \
    X(set_line_width, (, double w), (, w))                                                \
    X(set_dash, (, const double *dashes, int n, double offset), (, dashes, n, offset))    \
    X(move_to, (, double x, double y), (, x, y))                                          \
    X(line_to, (, double x, double y), (, x, y))                                          \
    X(rectangle, (, double x, double y, double w, double h), (, x, y, w, h))              \
    X(arc, (, double x, double y, double r, double a0, double a1), (, x, y, r, a0, a1))   \
    X(stroke, (), ())                                                                     \
    X(fill, (), ())                                                                       \
    X(fill_preserve, (), ())                                                              \
    X(clip, (), ())                                                                       \
    X(save, (), ())                                                                       \
    X(restore, (), ())                                                                    \
    X(translate, (, double x, double y), (, x, y))                                        \
    X(rotate, (, double a), (, a))                                                        \
    X(show_text, (, const char *s), (, s))                                                \
    X(text_extents, (, const char *s, cairo_text_extents_t *e), (, s, e))

struct canvas_fns;

/** One picture: a w x h RGB image surface and its drawing context. */
struct canvas {
    void *lib;                   /**< libcairo's dlopen handle */
    struct canvas_fns *f;        /**< the functions looked up in it */
    cairo_surface_t *surf;
    cairo_t *cr;
};

/** Load cairo and make a w x h RGB24 image surface and its context.
 *  SPALL_ERR_IO naming the library when it cannot be loaded; on error
 *  nothing is held. */
int canvas_open(struct canvas *c, int w, int h, struct spall_error *err);
/** Write the canvas as PNG to @p path and close it (always closed);
 *  SPALL_ERR_IO "cannot write @p what '@p path'" with cairo's reason. */
int canvas_write_png(struct canvas *c, const char *path, const char *what,
                     struct spall_error *err);
/** Free the canvas without writing (safe on a zeroed or closed one). */
void canvas_close(struct canvas *c);

#define CANVAS_DECLARE(name, params, args) void canvas_##name(struct canvas *c CANVAS_STRIP params);
CANVAS_DRAW_CALLS(CANVAS_DECLARE)
#undef CANVAS_DECLARE

#endif
