/**
 * @file output_xdmf.h
 * @brief What the XDMF index says beyond the HDF5 data (io/output_hdf5.c
 *        writes the index): attribute types, component names and units of
 *        the fields, and the rigid impactors and walls as their own small
 *        triangle meshes, so that ParaView shows them (issue 23,
 *        docs/postprocessing.md).
 */
#ifndef SPALL_OUTPUT_XDMF_H
#define SPALL_OUTPUT_XDMF_H

#include <stddef.h>

struct sim;

/** What a field's components are, from its registered parity, its
 *  component count and the dimension. */
enum xdmf_kind { XDMF_SCALAR, XDMF_VECTOR, XDMF_SYMTENSOR, XDMF_TENSOR, XDMF_OTHER };

/** @p parity: the field's enum field_parity (core/fields.h). */
enum xdmf_kind xdmf_field_kind(int ncomp, int dim, int parity);

/** XDMF AttributeType: Scalar; Vector for 3-component vectors; Tensor6 and
 *  Tensor for 3D symmetric and full tensors; Matrix for everything else (2D
 *  vectors and tensors: "Vector" promises 3 components, and the legacy XDMF
 *  reader then reads the n x 2 data as n x 3). */
const char *xdmf_attribute_type(enum xdmf_kind kind, int ncomp);

/** Components a field of @p kind and @p ncomp has in the frame files: a 2D
 *  symmetric tensor (xx yy xy) is widened to the 3D order xx yy zz xy yz xz
 *  with zz = yz = xz = 0, so that ParaView reads a Tensor6 and names the
 *  components (a 3-column Matrix it labels X, Y, Z).  The 2D models'
 *  symmetric tensors are virial stresses of in-plane bond forces, whose
 *  out-of-plane components are zero.  Else @p ncomp. */
int xdmf_file_ncomp(enum xdmf_kind kind, int ncomp);

/** Widen @p n rows of xx yy xy (3 doubles each, at the front of @p b) in
 *  place to rows of xx yy 0 xy 0 0 (b holds 6 n doubles). */
void xdmf_widen_symtensor(double *b, size_t n);

/** Space-separated component names ("x y", "xx yy xy", ...) or NULL. */
const char *xdmf_component_names(enum xdmf_kind kind, int ncomp);

/** The impactors and walls of @p s (and the planes its model enforces,
 *  model_ops.planes) at the current time as XDMF Uniform grids of triangles with inline coordinates (a few kB each), for the
 *  frame's spatial collection.  Returns a malloc'd string ("" when @p s has
 *  none) or NULL when out of memory. */
char *xdmf_rigid_grids(const struct sim *s, size_t n_particles);

/** Number of grids (rigid bodies, model planes) xdmf_rigid_grids writes. */
size_t xdmf_rigid_count(const struct sim *s);

#endif
