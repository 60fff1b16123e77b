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

#define RENDER_NAME_LEN 64

/** Component selection: a component index >= 0, or one of these. */
enum { RENDER_MAGNITUDE = -1, RENDER_AUTO = -2 };

/** Rendering options (zero-initialised = defaults, except the NaN fields,
 *  see render_options_default). */
struct render_options {
    const char *field;   /**< dataset name, e.g. "fracture_density"; NULL: the first the
                              frame has of fracture_density, damage, plastic strain,
                              velocity, displacement (render_pick_field) */
    const char *component_name; /**< x, y, z, xx, yy, zz, xy, yz, xz (tensors), mag or
                              an index: resolved against the field (overrides component) */
    int slice_axis;      /**< 3D: the axis the slice is normal to, 0 1 2 = x y z
                              (default z); the picture shows the other two */
    int component;       /**< index, RENDER_MAGNITUDE, or RENDER_AUTO (magnitude for
                              vectors of position/velocity/displacement/force, else 0) */
    int width;           /**< image width in pixels (height follows the aspect) */
    bool reference;      /**< draw at reference positions (default: current) */
    bool categorical;    /**< distinct colours per integer value (ids) */
    double vmin, vmax;   /**< colour range; NaN: the data's range */
    double slice_z;      /**< 3D: slice plane's coordinate along slice_axis; NaN: the middle */
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

/** The particle fields of frame @p h5_path (datasets but time and step),
 *  at most @p max names; 0 when the file cannot be read. */
size_t render_frame_fields(const char *h5_path, char (*names)[RENDER_NAME_LEN], size_t max);

/** The field to draw: @p wanted if the frame has it (else SPALL_ERR_INPUT
 *  listing the fields it has), or the default when @p wanted is NULL. */
int render_pick_field(const char *h5_path, const char *wanted, char *out, size_t len,
                      struct spall_error *err);

/** Component @p name of field @p field with @p nvc components in a @p dim
 *  dimensional run: x y z (vectors), xx yy zz xy yz xz (symmetric tensors:
 *  3 components in 2D, 6 in 3D, yx etc. accepted), xx xy ... zz (3x3),
 *  mag, or an index 0-8; SPALL_ERR_INPUT naming the valid ones. */
int render_component_index(const char *name, const char *field, size_t nvc, size_t dim,
                           int *comp, struct spall_error *err);

/** Permute n points xyz[3i + c] so that @p axis becomes the third coordinate
 *  (the depth of the slice) and the other two the drawing plane. */
void render_slice_axis(double *xyz, size_t n, int axis);

/** Read one HDF5 frame (io/output.h layout) and draw the chosen field. */
int render_frame_png(const char *h5_path, const char *png_path, const struct render_options *o,
                     struct spall_error *err);

#endif
