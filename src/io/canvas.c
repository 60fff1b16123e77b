/**
 * @file canvas.c
 * @brief cairo loaded on first drawing (see canvas.h).
 */
#define _GNU_SOURCE /* RTLD_NODELETE */
#include "io/canvas.h"

#include <dlfcn.h>
#include <stdlib.h>
#include <string.h>

/* the soname of Debian's libcairo2 (the ABI the header describes) */
#define CANVAS_LIB "libcairo.so.2"

#define CANVAS_POINTER(name, params, args) void (*name)(cairo_t *cr CANVAS_STRIP params);
struct canvas_fns {
    CANVAS_DRAW_CALLS(CANVAS_POINTER)
    cairo_surface_t *(*image_surface_create)(cairo_format_t format, int w, int h);
    cairo_t *(*create)(cairo_surface_t *s);
    void (*destroy)(cairo_t *cr);
    void (*surface_flush)(cairo_surface_t *s);
    cairo_status_t (*surface_write_to_png)(cairo_surface_t *s, const char *path);
    void (*surface_destroy)(cairo_surface_t *s);
    const char *(*status_to_string)(cairo_status_t st);
};
#undef CANVAS_POINTER

/* dlsym's object pointer into a function pointer: ISO C has no cast
 * between the two, POSIX guarantees the representation (memcpy) */
static int look_up(void *lib, const char *name, void *fn, size_t size)
{
    char sym[64] = "cairo_";
    strncat(sym, name, sizeof sym - strlen(sym) - 1);
    void *p = dlsym(lib, sym);
    if (p)
        memcpy(fn, &p, size);
    return p != NULL;
}

static int load(struct canvas_fns *f, void *lib)
{
    int ok = 1;
#define CANVAS_LOOK_UP(name, params, args) ok &= look_up(lib, #name, &f->name, sizeof f->name);
    CANVAS_DRAW_CALLS(CANVAS_LOOK_UP)
#undef CANVAS_LOOK_UP
    ok &= look_up(lib, "image_surface_create", &f->image_surface_create,
                  sizeof f->image_surface_create);
    ok &= look_up(lib, "create", &f->create, sizeof f->create);
    ok &= look_up(lib, "destroy", &f->destroy, sizeof f->destroy);
    ok &= look_up(lib, "surface_flush", &f->surface_flush, sizeof f->surface_flush);
    ok &= look_up(lib, "surface_write_to_png", &f->surface_write_to_png,
                  sizeof f->surface_write_to_png);
    ok &= look_up(lib, "surface_destroy", &f->surface_destroy, sizeof f->surface_destroy);
    ok &= look_up(lib, "status_to_string", &f->status_to_string, sizeof f->status_to_string);
    return ok;
}

void canvas_close(struct canvas *c)
{
    if (c->f) {
        if (c->cr)
            c->f->destroy(c->cr);
        if (c->surf)
            c->f->surface_destroy(c->surf);
    }
    free(c->f);
    /* RTLD_NODELETE: cairo stays mapped once loaded (fontconfig keeps its
     * caches until exit, as when it was linked); the handle is released */
    if (c->lib)
        dlclose(c->lib);
    memset(c, 0, sizeof *c);
}

int canvas_open(struct canvas *c, int w, int h, struct spall_error *err)
{
    memset(c, 0, sizeof *c);
    if (!(c->lib = dlopen(CANVAS_LIB, RTLD_NOW | RTLD_LOCAL | RTLD_NODELETE))) {
        const char *why = dlerror();
        return spall_error_set(err, SPALL_ERR_IO, "cannot load %s for drawing: %s", CANVAS_LIB,
                               why ? why : "unknown reason");
    }
    if (!(c->f = calloc(1, sizeof *c->f))) {
        canvas_close(c);
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory for a picture");
    }
    if (!load(c->f, c->lib)) {
        free(c->f);
        c->f = NULL;
        canvas_close(c);
        return spall_error_set(err, SPALL_ERR_IO, "%s lacks a function spall draws with",
                               CANVAS_LIB);
    }
    c->surf = c->f->image_surface_create(CAIRO_FORMAT_RGB24, w, h);
    c->cr = c->f->create(c->surf);
    return SPALL_OK;
}

int canvas_write_png(struct canvas *c, const char *path, const char *what,
                     struct spall_error *err)
{
    c->f->destroy(c->cr);
    c->cr = NULL;
    c->f->surface_flush(c->surf);
    const cairo_status_t st = c->f->surface_write_to_png(c->surf, path);
    int rc = SPALL_OK;
    if (st != CAIRO_STATUS_SUCCESS)
        rc = spall_error_set(err, SPALL_ERR_IO, "cannot write %s '%s': %s", what, path,
                             c->f->status_to_string(st));
    canvas_close(c);
    return rc;
}

#define CANVAS_DEFINE(name, params, args)                     \
    void canvas_##name(struct canvas *c CANVAS_STRIP params) \
    {                                                        \
        c->f->name(c->cr CANVAS_STRIP args);                 \
    }
CANVAS_DRAW_CALLS(CANVAS_DEFINE)
#undef CANVAS_DEFINE
