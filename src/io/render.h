/**
 * @file render.h
 * @brief Pictures of particle fields (PNG through cairo): each particle a
 *        filled disc coloured by one scalar (a field component, the magnitude
 *        of a vector field, or a categorical id), with a colour bar, a length
 *        scale bar and the time.
 *
 * 2D runs are drawn directly (x right, y up).  3D runs are drawn as a slice:
 * the particles within 0.6 spacing of the plane z = slice_z (default: the
 * middle of the body's z range) seen along -z.  A slice shows interior
 * cracks and fragments, which a projection would hide behind the surface.
 * The particle spacing (disc size) is the median nearest-neighbour distance of
 * a deterministic sample of particles in the reference configuration.
 */
#ifndef SPALL_RENDER_H
#define SPALL_RENDER_H

#include <stdbool.h>
#include <stddef.h>

struct spall_error;

/** Component selection: a component index >= 0, or one of these. */
enum { RENDER_MAGNITUDE = -1, RENDER_AUTO = -2 };

/** Rendering options (zero-initialised = defaults, except the NaN fields,
 *  see render_options_default). */
struct render_options {
    const char *field;   /**< dataset name, e.g. "fracture_density" */
    int component;       /**< index, RENDER_MAGNITUDE, or RENDER_AUTO (magnitude for
                              vectors of position/velocity/displacement/force, else 0) */
    int width;           /**< image width in pixels (height follows the aspect) */
    bool reference;      /**< draw at reference positions (default: current) */
    bool categorical;    /**< distinct colours per integer value (ids) */
    double vmin, vmax;   /**< colour range; NaN: the data's range */
    double slice_z;      /**< 3D: slice plane; NaN: the middle */
    const char *title;   /**< NULL: the field name */
};

/** Defaults: component auto, width 800, vmin = vmax = slice_z = NaN,
 *  categorical for fragment_id, material and id. */
void render_options_default(struct render_options *o, const char *field);

/** Particle data to draw: n particles, positions pos[i*3 + c] (3 components,
 *  z = 0 in 2D), reference positions ref (may be NULL), one value each. */
struct render_points {
    size_t n;
    const double *pos, *ref;
    const double *value;
    double time;          /**< s (NaN: not shown) */
    const char *label;    /**< colour-bar label, e.g. "velocity |.| [m/s]" */
};

/** Draw @p d into @p png_path. */
int render_points_png(const char *png_path, const struct render_points *d,
                      const struct render_options *o, struct spall_error *err);

/** Read one HDF5 frame (io/output.h layout) and draw the chosen field. */
int render_frame_png(const char *h5_path, const char *png_path, const struct render_options *o,
                     struct spall_error *err);

#endif
