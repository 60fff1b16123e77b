/**
 * @file fields.h
 * @brief Field registry: every per-particle quantity declared once.
 *
 * The core and each model register their per-particle arrays here (name,
 * components, unit, type, flags).  This single declaration drives HDF5/XDMF
 * output, restart and (later) MPI ghost exchange and migration packing, so
 * the I/O and parallel layers never know which model is running.
 *
 * A field is either *stored* (pointers to the owner's array pointers, so a
 * realloc by the owner is seen) or *computed* (a callback fills a buffer,
 * e.g. displacement = x - x0).
 */
#ifndef SPALL_FIELDS_H
#define SPALL_FIELDS_H

#include <stddef.h>
#include <stdint.h>

struct spall_error;

enum field_type { FIELD_F64, FIELD_I32, FIELD_I64, FIELD_U8 };

enum field_flags {
    FIELD_OUTPUT = 1u << 0,     /**< may be written to HDF5 */
    FIELD_DEFAULT = 1u << 1,    /**< written when the deck lists no fields */
    FIELD_RESTART = 1u << 2,    /**< needed to restart a run */
    FIELD_GHOST = 1u << 3,      /**< copied to ghosts every step */
    FIELD_MIGRATE = 1u << 4,    /**< travels with a particle to another rank */
    FIELD_SERIAL = 1u << 5      /**< computed from partners a distributed run does not hold:
                                     refused as output on more than one rank */
};

#define FIELD_NAME_LEN 48

/** How a field's components change under the reflection x_k -> -x_k of the
 *  current configuration (sim_reflect_particle, core/integrator.c).  Every
 *  stored field that carries state from one force call to the next must
 *  declare its parity; fields recomputed from that state in every force
 *  call, and computed fields, may stay FIELD_EVEN. */
enum field_parity {
    FIELD_EVEN = 0,  /**< scalars, labels, the reference configuration (default) */
    FIELD_VECTOR,    /**< component c (c < 3) is odd in plane c: position, velocity, force */
    FIELD_SYMTENSOR, /**< symmetric tensor, components xx yy zz xy yz xz: a shear
                          component ab (a != b) is odd in planes a and b */
    FIELD_TENSOR     /**< full 3x3 tensor, row-major (ab at 3a + b): ab odd in
                          planes a and b when a != b */
};

/** Components of a symmetric tensor field (stress, strain) in @p dim
 *  dimensions: 1 (xx), 3 in 2D, 6 in 3D (the FIELD_SYMTENSOR order). */
static inline int field_symtensor_ncomp(int dim)
{
    return dim == 1 ? 1 : dim == 2 ? 3 : 6;
}

/** Fills out[i*ncomp + c] for i in [0, n). */
typedef void (*field_compute_fn)(const void *ctx, size_t n, double *out);

struct field_desc {
    char name[FIELD_NAME_LEN]; /**< e.g. "velocity" */
    char unit[16];             /**< SI unit, e.g. "m/s" ("1" for none) */
    int ncomp;                 /**< 1..9 components */
    enum field_type type;
    unsigned flags;
    /** stored field: address of the owner's array pointer, one per component
     *  (component c of particle i is (*comp[c])[i]); NULL for computed fields */
    void **comp[9];
    field_compute_fn compute; /**< computed field (always FIELD_F64) */
    const void *ctx;          /**< passed to compute */
    enum field_parity parity; /**< reflection parity (stored FIELD_F64 only) */
};

struct field_registry {
    struct field_desc *fields;
    size_t n, cap;
};

int field_registry_create(struct field_registry **out, struct spall_error *err);
void field_registry_destroy(struct field_registry **reg);

/** Register a field; names must be unique. */
int field_registry_add(struct field_registry *reg, const struct field_desc *desc,
                       struct spall_error *err);

/** Convenience: register a stored double field with @p ncomp component arrays. */
int field_registry_add_f64(struct field_registry *reg, const char *name, const char *unit,
                           int ncomp, double **comp[], unsigned flags, struct spall_error *err);

/** As field_registry_add_f64, declaring the field's reflection parity. */
int field_registry_add_f64_parity(struct field_registry *reg, const char *name, const char *unit,
                                  int ncomp, double **comp[], unsigned flags,
                                  enum field_parity parity, struct spall_error *err);

/** Convenience: register a computed double field (values filled by @p fn
 *  with @p ctx when the field is written). */
int field_registry_add_computed(struct field_registry *reg, const char *name, const char *unit,
                                int ncomp, unsigned flags, field_compute_fn fn, const void *ctx,
                                struct spall_error *err);

/** Look a field up by name; NULL if absent. */
const struct field_desc *field_registry_find(const struct field_registry *reg, const char *name);

/** The owner's array of component @p c of the stored field @p name (cast it
 *  to the field's type: double * for FIELD_F64, uint8_t * for FIELD_U8, ...),
 *  for callers that read or set per-particle state in place; NULL when the
 *  field is absent or computed, or @p c out of range.  Valid until the owner
 *  reallocates (look it up again after particles are added). */
void *field_stored_data(const struct field_registry *reg, const char *name, int c);

/** Copy the values of particles [0, n) into @p out as doubles, interleaved
 *  (out[i*ncomp + c]); works for stored and computed fields of any type. */
void field_gather_f64(const struct field_desc *f, size_t n, double *out);

/** Planes (bit k: the plane x_k = 0) in which component @p c of a field of
 *  parity @p par changes sign. */
unsigned field_parity_planes(enum field_parity par, int c);

/** Sign (+1 or -1) of component @p c of a field of parity @p par after the
 *  reflections in every plane of @p planes (bit k: x_k = 0; two bits: the
 *  composition, e.g. the image in both planes of a quarter model). */
double field_reflect_sign(enum field_parity par, int c, unsigned planes);

/** Reflect particle @p i in the plane x_k = 0 in every stored field of the
 *  registry: the components odd in plane k change sign, nothing else is
 *  touched.  The integrator's private copies are not in the registry: use
 *  sim_reflect_particle (core/sim.h), which calls this. */
void field_reflect(const struct field_registry *reg, size_t i, int k);

/** Bytes one particle's value of this field occupies when packed. */
size_t field_packed_size(const struct field_desc *f);
/** Pack / unpack particle i's value (for MPI exchange and restart). */
void field_pack(const struct field_desc *f, size_t i, void *buf);
void field_unpack(const struct field_desc *f, size_t i, const void *buf);

#endif
