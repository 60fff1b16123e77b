/**
 * @file field_state.h
 * @brief Restart state registry: everything a run needs to continue
 *        exactly, declared once by its owner.
 *
 * The per-particle fields marked FIELD_RESTART in the field registry
 * (core/fields.h) are one part of a run's state.  The rest is owned by the
 * engine and the models and has other shapes: per-half-bond arrays (bond
 * states, softening history), lists whose length changes during the run
 * (SPH partner lists), and scalars (counters, accumulators, the integrator's
 * t, dt and step).  Each owner registers these here as *slots*; the
 * checkpoint writer (io/checkpoint.c) saves every slot and the reader puts
 * the values back, so the I/O layer never knows which model runs.
 *
 * A slot is one of:
 *  - an array the owner allocates (the address of its pointer is kept, so a
 *    realloc is seen), with a fixed row count or a row-count callback, and
 *    optionally a set_rows callback that resizes the owner's storage before
 *    a load (variable-length data);
 *  - values at a fixed address (scalars and small fixed arrays).
 * A row holds `width` values of the slot's type.  Slots hold addresses into
 * the owners' structures, which may be replaced during a run (a rebuilt
 * pair list): a registry is filled right before one save or one load and
 * then dropped.
 */
#ifndef SPALL_FIELD_STATE_H
#define SPALL_FIELD_STATE_H

#include <stddef.h>

#include "core/fields.h"

struct bond_list;
struct sim;
struct spall_error;

#define FIELD_STATE_NAME_LEN 64

/** How a slot's rows map onto the run's particles: what a distributed
 *  checkpoint (io/checkpoint_par.c) needs to write every rank's rows at
 *  their place in the serial layout. */
enum field_state_layout {
    FIELD_STATE_GLOBAL = 0,  /**< the same values on every rank (scalars, counters) */
    FIELD_STATE_LOCAL,       /**< rows in the rank's own order: serial runs only */
    FIELD_STATE_PARTICLE,    /**< one row per owned particle, in local order */
    FIELD_STATE_HALF_BOND,   /**< one row per half-bond of @c bonds' owned rows */
    FIELD_STATE_OFFSETS      /**< @c bonds' row offsets (owned rows + 1): a distributed
                                  checkpoint writes the serial ones, a particle's row at
                                  its global id */
};

/** Rows currently held by the owner. */
typedef size_t (*field_state_rows_fn)(const void *ctx);
/** Make room for @p rows rows before a load (the owner reallocates and
 *  updates the array pointer the slot refers to). */
typedef int (*field_state_set_rows_fn)(void *ctx, size_t rows, struct spall_error *err);

struct field_state_slot {
    char name[FIELD_STATE_NAME_LEN];
    enum field_type type;
    size_t width;      /**< values per row */
    void **data;       /**< array slot: address of the owner's array pointer */
    void *direct;      /**< fixed slot: the values themselves */
    size_t rows_fixed; /**< rows when @c rows is NULL */
    field_state_rows_fn rows;
    field_state_set_rows_fn set_rows;
    void *ctx;
    enum field_state_layout layout;
    const struct bond_list *bonds; /**< FIELD_STATE_HALF_BOND: the rows' bond list */
};

struct field_state {
    struct field_state_slot *slots;
    size_t n, cap;
};

int field_state_create(struct field_state **out, struct spall_error *err);
void field_state_destroy(struct field_state **fs);

/** Register an owner-allocated array of @p rows rows of @p width values
 *  (the array pointer is read when the slot is saved or loaded); its rows
 *  are in the run's own order (FIELD_STATE_LOCAL). */
int field_state_add_array(struct field_state *fs, const char *name, enum field_type type,
                          void **data, size_t rows, size_t width, struct spall_error *err);

/** Register an array of one row of @p width values per owned particle
 *  (@p n_owned rows, local order). */
int field_state_add_particle_array(struct field_state *fs, const char *name,
                                   enum field_type type, void **data, size_t n_owned,
                                   size_t width, struct spall_error *err);

/** Register an array of one row of @p width values per half-bond of the
 *  owned particles' rows of @p bonds (bonds->offset[bonds->n] rows). */
int field_state_add_bond_array(struct field_state *fs, const char *name, enum field_type type,
                               void **data, const struct bond_list *bonds, size_t width,
                               struct spall_error *err);

/** As field_state_add_bond_array for a list whose rows change during the
 *  run (a pair list rebuilt from a neighbour search): @p set_rows resizes
 *  the array before a load. */
int field_state_add_bond_list(struct field_state *fs, const char *name, enum field_type type,
                              void **data, const struct bond_list *bonds, size_t width,
                              field_state_set_rows_fn set_rows, void *ctx,
                              struct spall_error *err);

/** Register the row offsets of @p bonds (int64, bonds->n + 1 values, the
 *  array at *@p data): in a serial file the offsets themselves, from a
 *  distributed run the serial ones (FIELD_STATE_OFFSETS). */
int field_state_add_offsets(struct field_state *fs, const char *name, void **data,
                            const struct bond_list *bonds, struct spall_error *err);

/** Register a variable-length array: @p rows gives its current length and
 *  @p set_rows (may be NULL when the length cannot change) resizes it. */
int field_state_add_list(struct field_state *fs, const char *name, enum field_type type,
                         void **data, size_t width, field_state_rows_fn rows,
                         field_state_set_rows_fn set_rows, void *ctx, struct spall_error *err);

/** Register @p count values stored at @p values (scalars, small arrays). */
int field_state_add_values(struct field_state *fs, const char *name, enum field_type type,
                           void *values, size_t count, struct spall_error *err);

/** As field_state_add_values, with @p loaded called before a load (with the
 *  checkpoint's count in place of a row count, as a set_rows callback): the
 *  owner learns that its values come from a checkpoint.  The values are
 *  alike on every rank (FIELD_STATE_GLOBAL), so a distributed run saves
 *  them as one rank does. */
int field_state_add_values_hook(struct field_state *fs, const char *name, enum field_type type,
                                void *values, size_t count, field_state_set_rows_fn loaded,
                                void *ctx, struct spall_error *err);

/** Look a slot up by name; NULL if absent. */
const struct field_state_slot *field_state_find(const struct field_state *fs, const char *name);

/** Rows the slot holds now. */
size_t field_state_slot_rows(const struct field_state_slot *s);
/** Bytes of one value of @p type. */
size_t field_state_type_size(enum field_type type);
/** The slot's values (rows * width of them); NULL when it holds none. */
void *field_state_slot_data(const struct field_state_slot *s);

/** Prepare slot @p s to receive @p rows rows (set_rows, or a check that the
 *  fixed length matches); SPALL_ERR_INPUT naming the slot on a mismatch. */
int field_state_slot_resize(const struct field_state_slot *s, size_t rows, struct spall_error *err);

/** Register the engine's own state (time, step, dt, damping, energy
 *  account, boundary-condition accumulators, predictor-corrector
 *  velocities, the forces of the last step, rigid impactors), then the
 *  model's (model_ops.register_state).  Fails naming the model when it
 *  declares no restart state. */
int sim_register_state(struct sim *s, struct field_state *fs, struct spall_error *err);

#endif
