/**
 * @file time_function.h
 * @brief Scalar load factors f(t) multiplying boundary-condition values.
 *
 * constant: f = 1.
 * linear_ramp: f = t/t_ramp for t < t_ramp, then 1.
 * quadratic_ramp: f = (t/t_ramp)^2 for t < t_ramp, then 1 (held) — the
 *   thesis' cantilever load.
 * table: piecewise-linear through (t_k, f_k), held constant outside.
 */
#ifndef SPALL_TIME_FUNCTION_H
#define SPALL_TIME_FUNCTION_H

#include <stddef.h>

enum time_function_kind { TF_CONSTANT, TF_LINEAR_RAMP, TF_QUADRATIC_RAMP, TF_TABLE };

struct time_function {
    enum time_function_kind kind;
    double t_ramp;   /**< ramp duration [s] */
    size_t n;        /**< table points */
    double *t, *f;   /**< table (owned), t strictly increasing */
};

double time_function_eval(const struct time_function *tf, double t);
void time_function_free(struct time_function *tf);

#endif
