/**
 * @file output_bonds.h
 * @brief Optional output of the bonds of a lattice or peridynamics run as
 *        line cells (the pseudo field `bonds` of output.fields): one
 *        DIR/bonds_NNNNNN.h5 per field frame and the index DIR/bonds.xdmf
 *        (layout in output_bonds.c, docs/postprocessing.md).  Serial runs;
 *        driven by the field writer (output_hdf5.c).
 */
#ifndef SPALL_OUTPUT_BONDS_H
#define SPALL_OUTPUT_BONDS_H

#include <stddef.h>

struct sim;
struct spall_error;
struct bond_writer;

/** The name that asks for the bonds in output.fields. */
#define OUTPUT_BONDS "bonds"

/** SPALL_ERR_INPUT unless @p s has a bond list and runs on one process. */
int bond_writer_check(const struct sim *s, struct spall_error *err);
int bond_writer_create(struct bond_writer **out, const char *dir, const struct sim *s,
                       struct spall_error *err);
/** Write the bonds of the current state beside field frame @p frame (whose
 *  /position they index) and rewrite bonds.xdmf; @p time_text is the
 *  frame's time as the fields' index writes it. */
int bond_writer_write(struct bond_writer *w, const struct sim *s, size_t frame,
                      const char *time_text, struct spall_error *err);
void bond_writer_destroy(struct bond_writer **w);

#endif
