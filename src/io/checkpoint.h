/**
 * @file checkpoint.h
 * @brief Checkpoints: the complete state of a run in one HDF5 file, and
 *        restart from it (docs/restart.md).
 *
 * A checkpoint holds the particle fields marked FIELD_RESTART in the field
 * registry (in global-id order), every slot of the restart state registry
 * (core/field_state.h: engine and model state), the output counters that
 * let history.csv and the XDMF index continue, the model name, the deck's
 * fingerprint (its option tree as key=value lines, less the keys a restart
 * may change), the format version and a checksum over all of it.
 * Files are written to a temporary name and renamed (checkpoint_files.c).
 */
#ifndef SPALL_CHECKPOINT_H
#define SPALL_CHECKPOINT_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "core/fields.h"

struct deck;
struct deck_node;
struct field_state;
struct sim;
struct spall_error;

/** Format of the files this build writes; it reads this one and older. */
#define CHECKPOINT_FORMAT_VERSION 1

/** Deck `output.checkpoint`. */
struct checkpoint_options {
    bool on;
    double every_time;    /**< s of simulated time (0: unused) */
    long every_steps;     /**< steps (0: unused) */
    double every_minutes; /**< wall-clock minutes (0: unused) */
    long keep;            /**< complete checkpoints kept (default 2) */
};

/** Parse `checkpoint:` of the output mapping @p output (may be NULL). */
int checkpoint_parse_options(const struct deck_node *output, struct checkpoint_options *o,
                             struct spall_error *err);

/** The run driver's counters saved with the state. */
struct checkpoint_meta {
    int64_t frames;        /**< field frames written so far */
    int64_t history_bytes; /**< length of history.csv after the checkpoint's row */
    double next_frame_t;   /**< next frame time (output.field_interval) */
    double next_ckpt_t;    /**< next checkpoint time (every_time) */
    const char *xdmf_grids;/**< the XDMF index's grid entries */
    char *xdmf_owned;      /**< checkpoint_read: the same, malloc'd (caller frees) */
    size_t xdmf_len;
};

/** The deck's fingerprint: one "path=value" line per scalar, in document
 *  order, without the keys a restart may change (run.end_time, run.steps,
 *  run.threads, output intervals and checkpoint settings, title,
 *  description).  Returns a malloc'd string (NULL: out of memory). */
char *checkpoint_deck_fingerprint(const struct deck_node *root);

/** File-access properties of checkpoint files read, and written by a
 *  serial run (checkpoint_write_par uses MPI-IO).  Close with H5Pclose. */
int64_t checkpoint_fapl(void);

/** Write the state of @p s (its registry @p fs) into @p path. */
int checkpoint_write(const char *path, const struct sim *s, const struct field_state *fs,
                     const struct deck *d, const struct checkpoint_meta *meta,
                     struct spall_error *err);

/** Read @p path into the freshly prepared @p s built from @p d.  Refused
 *  (SPALL_ERR_INPUT, one line naming the file and the cause) when it is
 *  not a complete checkpoint, of another model, format or deck (err->key
 *  names the first differing deck key).  Fills @p meta. */
int checkpoint_read(const char *path, struct sim *s, const struct field_state *fs,
                    const struct deck *d, struct checkpoint_meta *meta, struct spall_error *err);

/* Shared by the serial (checkpoint.c) and the distributed writer
 * (checkpoint_par.c): the file's magic, the checksum (FNV-1a, 64 bit, over
 * the bytes of every dataset in the order written) and HDF5's native type
 * of a field type. */
#define CHECKPOINT_MAGIC "spall-checkpoint"
#define CHECKPOINT_HASH_SEED 0xcbf29ce484222325ULL
void checkpoint_hash(uint64_t *h, const void *data, size_t bytes);
int64_t checkpoint_h5_type(enum field_type t);

/* checkpoint_par.c -------------------------------------------------------- */

/** Distributed run: every rank writes its owned particles' rows, at their
 *  global ids, into the one file @p path, which then holds exactly what a
 *  serial checkpoint of the same state holds (the serial layout), so a
 *  restart may use any rank count.  Collective; the result is agreed over
 *  the ranks.  Rank 0 adds the checksum after all ranks have closed. */
int checkpoint_write_par(const char *path, const struct sim *s, const struct field_state *fs,
                         const struct deck *d, const struct checkpoint_meta *meta,
                         struct spall_error *err);

/** Refuse (SPALL_ERR_INPUT naming the slot) state that a distributed run
 *  cannot write in the serial layout yet (slots in a rank's own order). */
int checkpoint_par_check(const struct field_state *fs, struct spall_error *err);

/* checkpoint_files.c ------------------------------------------------------ */

/** DIR/checkpoint_<step>.h5 written through a temporary file and renamed,
 *  then all but the newest @p keep complete checkpoints removed.  The name
 *  written is put in @p written (may be NULL). */
int checkpoint_save(const char *dir, long keep, const struct sim *s, const struct field_state *fs,
                    const struct deck *d, const struct checkpoint_meta *meta, char *written,
                    size_t len, struct spall_error *err);

/** @p arg is a checkpoint file or a run directory (its newest checkpoint):
 *  the file in @p file, its directory in @p dir. */
int checkpoint_locate(const char *arg, char *file, size_t file_len, char *dir, size_t dir_len,
                      struct spall_error *err);

#endif
