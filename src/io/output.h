/**
 * @file output.h
 * @brief Result writers: HDF5 field frames with an XDMF index, history.csv.
 *
 * Field output is driven by the field registry only: the writer does not know
 * which model runs.  Each frame is DIR/fields_NNNNNN.h5 holding
 * /time, /step and one dataset per field (n x ncomp, float64; positions are
 * written as 3 components, padded with 0 in 1D/2D, so ParaView's XDMF reader
 * can use them as XYZ geometry).  DIR/fields.xdmf is rewritten after every
 * frame as a temporal collection of Polyvertex grids (one vertex cell per
 * particle through the frame's /connectivity dataset, which ParaView's
 * default Xdmf3ReaderS needs to make cells), so an interrupted run still
 * leaves a readable index of its last good frame.
 */
#ifndef SPALL_OUTPUT_H
#define SPALL_OUTPUT_H

#include <stddef.h>
#include <stdio.h>

struct sim;
struct spall_error;

struct field_writer;

/** @p names: fields to write (NULL/0: all with FIELD_DEFAULT).  Unknown names
 *  are refused listing the registered ones.  "position" is always written. */
int field_writer_create(struct field_writer **out, const char *dir, const struct sim *s,
                        const char *const *names, size_t n_names, struct spall_error *err);
/** The check of field_writer_create's @p names alone (deck_build_sim runs it
 *  before any output exists); *bad is the index of the refused name. */
int field_writer_check_names(const struct sim *s, const char *const *names, size_t n_names,
                             size_t *bad, struct spall_error *err);
/** Write one frame for the current state of @p s. */
int field_writer_write(struct field_writer *w, const struct sim *s, struct spall_error *err);
size_t field_writer_frames(const struct field_writer *w);
void field_writer_destroy(struct field_writer **w);
/** The XDMF grid entries written so far (for a checkpoint). */
const char *field_writer_grids(const struct field_writer *w, size_t *len);
/** Continue a run's frames: the next frame is number @p frames and the
 *  XDMF index starts with @p grids (from a checkpoint). */
int field_writer_resume(struct field_writer *w, size_t frames, const char *grids, size_t len,
                        struct spall_error *err);

/** history.csv: a header line of column names (with units in brackets) then
 *  one row per call, written with %.10g and flushed. */
struct history_writer;
int history_writer_create(struct history_writer **out, const char *path,
                          const char *const *columns, size_t n_columns, struct spall_error *err);
int history_writer_append(struct history_writer *h, const double *values, struct spall_error *err);
void history_writer_destroy(struct history_writer **h);
/** Bytes written to the file so far (header and rows). */
long history_writer_bytes(const struct history_writer *h);
/** Continue an existing history file: cut it to its first @p bytes (the
 *  rows up to a checkpoint) and append from there. */
int history_writer_resume(struct history_writer **out, const char *path, long bytes,
                          size_t n_columns, struct spall_error *err);

/** Read back a frame's dataset (for render and tests): allocates *data
 *  (n x ncomp doubles). */
int field_frame_read(const char *h5_path, const char *name, double **data, size_t *n,
                     size_t *ncomp, double *time, struct spall_error *err);

#endif
