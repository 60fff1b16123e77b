/**
 * @file impact_cases.h
 * @brief Validation cases of the rigid impactors with the lattice model
 *        (issue 3, [Wang2010] sec. 3.2-4.2), registered in validation/cases.c;
 *        numbers tabulated in docs/notes/validation-log.md.
 */
#ifndef SPALL_VALIDATION_IMPACT_CASES_H
#define SPALL_VALIDATION_IMPACT_CASES_H

#include <stddef.h>

struct spall_error;
struct vreport;

/** "impact-nylon": [Wang2010] sec. 3.2.1 drop-weight indentation of nylon-6,6. */
int impact_case_nylon(struct vreport *r, struct spall_error *err);
/** "impact-vinylester": [Wang2010] sec. 3.2.2, vinyl ester at 1.91 m/s. */
int impact_case_vinylester(struct vreport *r, struct spall_error *err);
/** Deck text of the indentation rig (also behind examples/impact_*). */
int impact_indent_deck(char *buf, size_t len, double rho, double E, double sigma, double v0,
                       double r0, double end_time);

/** Same rig with axial law @p law and extra material keys @p extra
 *  (", key: value" text, "" for none), e.g. the softening law's. */
int impact_indent_deck_law(char *buf, size_t len, const char *law, const char *extra, double rho,
                           double E, double sigma, double v0, double r0, double end_time);

/** "impact-spall": [Wang2010] sec. 4.2 flyer-plate spall, both flyer widths. */
int impact_case_spall(struct vreport *r, struct spall_error *err);
/** Deck text of the spall case (flyer + target, interface pre-cut). */
int impact_spall_deck(char *buf, size_t len, double flyer_width, double r0, double end_time,
                      double eps_max);

/** Same with axial law @p law and its failure keys @p fail_keys (deck text). */
int impact_spall_deck_law(char *buf, size_t len, double flyer_width, double r0, double end_time,
                          const char *law, const char *fail_keys);

/** "impact-epoxy": [Wang2010] sec. 3.1 epoxy plate with holes, cracks link holes. */
int impact_case_epoxy(struct vreport *r, struct spall_error *err);

/** "impact-punch": [Wang2010] sec. 3.2.3 3D vinyl ester punch-shear. */
int impact_case_punch(struct vreport *r, struct spall_error *err);
/** Deck text of the punch-shear case (also used by bench/bench_impact.c). */
int impact_punch_deck(char *buf, size_t len, double r0, const char *contact, double end_time);

#endif
