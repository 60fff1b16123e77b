/**
 * @file lattice_cases.h
 * @brief Validation cases of the lattice (HLPM) model, run by `spall validate`
 *        through the registry in validation/cases.c, and the small helpers
 *        they share (validation/lattice_common.c).
 *
 * Every case records checks with reference, measured value, tolerance, the
 * source of the reference and the reason for the tolerance; the numbers are
 * tabulated in docs/notes/validation-log.md.
 */
#ifndef SPALL_VALIDATION_LATTICE_CASES_H
#define SPALL_VALIDATION_LATTICE_CASES_H

#include <stddef.h>

struct sim;
struct spall_error;
struct vreport;

/** "lattice-patch": uniform strain -> E, nu of every calibrated lattice. */
int lattice_case_patch(struct vreport *r, struct spall_error *err);
/** "lattice-waves": [Wang2010] section 4.1 wave speeds, 1D chain and 2D strip. */
int lattice_case_waves(struct vreport *r, struct spall_error *err);
/** "lattice-energy": energy conservation of an elastic alpha-beta plate. */
int lattice_case_energy(struct vreport *r, struct spall_error *err);
/** "lattice-chain-break": a slowly pulled chain breaks at eps_max (Eq. 26). */
int lattice_case_chain_break(struct vreport *r, struct spall_error *err);
/** "lattice-threads": 1 and 2 OpenMP threads give bitwise identical runs. */
int lattice_case_threads(struct vreport *r, struct spall_error *err);
/** "abg-patch": triple honeycomb (alpha-beta-gamma) lattice for nu > 1/3:
 *  relaxed patch test, clamped finite block, P-wave speed (lattice_abg.c). */
int lattice_case_abg(struct vreport *r, struct spall_error *err);

/** Build a ready-to-step simulation from YAML text held in memory
 *  (deck_load_string + deck_build_sim); @p name appears in messages. */
int vlat_build(const char *name, const char *yaml, struct sim **out, struct spall_error *err);

/** Value of the model's history column @p column (e.g. "bonds_broken");
 *  NaN when the model has no such column. */
double vlat_history(const struct sim *s, const char *column);

/** Index of the group called @p name, or a SPALL_ERR_INTERNAL error. */
int vlat_group(const struct sim *s, const char *name, int *index, struct spall_error *err);

#endif
