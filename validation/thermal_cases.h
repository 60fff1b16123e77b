/** @file thermal_cases.h @brief Validation cases of the thermal lattice (validation/thermal_*.c). */
#ifndef SPALL_THERMAL_CASES_H
#define SPALL_THERMAL_CASES_H

struct vreport;
struct spall_error;

/** 1D conduction from a fixed-temperature end against erfc ([Wang2010] sec. 2.2). */
int thermal_case_conduction(struct vreport *r, struct spall_error *err);
/** Free thermal expansion of a uniformly heated plate: strain alpha dT ([Wang2010] Eq. 21). */
int thermal_case_expansion(struct vreport *r, struct spall_error *err);

#endif
