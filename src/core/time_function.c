#include "core/time_function.h"

#include <stdlib.h>

double time_function_eval(const struct time_function *tf, double t)
{
    switch (tf->kind) {
    case TF_CONSTANT:
        return 1.0;
    case TF_LINEAR_RAMP:
        if (tf->t_ramp <= 0.0 || t >= tf->t_ramp)
            return 1.0;
        return t <= 0.0 ? 0.0 : t / tf->t_ramp;
    case TF_QUADRATIC_RAMP:
        if (tf->t_ramp <= 0.0 || t >= tf->t_ramp)
            return 1.0;
        return t <= 0.0 ? 0.0 : (t / tf->t_ramp) * (t / tf->t_ramp);
    case TF_TABLE: {
        if (tf->n == 0)
            return 0.0;
        if (t <= tf->t[0])
            return tf->f[0];
        if (t >= tf->t[tf->n - 1])
            return tf->f[tf->n - 1];
        size_t lo = 0, hi = tf->n - 1; /* binary search: t[lo] <= t < t[hi] */
        while (hi - lo > 1) {
            size_t mid = (lo + hi) / 2;
            if (tf->t[mid] <= t)
                lo = mid;
            else
                hi = mid;
        }
        double w = (t - tf->t[lo]) / (tf->t[hi] - tf->t[lo]);
        return tf->f[lo] + w * (tf->f[hi] - tf->f[lo]);
    }
    }
    return 1.0;
}

void time_function_free(struct time_function *tf)
{
    free(tf->t);
    free(tf->f);
    tf->t = tf->f = NULL;
    tf->n = 0;
}
