/**
 * @file test_sph_rows.h
 * @brief Shared by test_sph_fused.c and test_sph_axisym_vec.c: a deck run
 *        with the vector rows and with the scalar rows (sph_set_scalar_rows)
 *        must give bitwise the same positions and velocities.  Include
 *        after tests/test_support.h.
 */
#ifndef SPALL_TEST_SPH_ROWS_H
#define SPALL_TEST_SPH_ROWS_H

#include "models/sph/sph.h"

/* Positions and velocities of two runs bit for bit. */
static inline void assert_bitwise(const struct sim *a, const struct sim *b)
{
    assert_int_equal(a->p->n, b->p->n);
    for (int k = 0; k < a->dim; k++) {
        assert_memory_equal(a->p->x[k], b->p->x[k], a->p->n * sizeof(double));
        assert_memory_equal(a->p->v[k], b->p->v[k], a->p->n * sizeof(double));
    }
}

static inline void vec_vs_scalar(const char *yaml, const char *what)
{
    struct sim *a = test_build(yaml);
    struct sim *b = test_build(yaml);
    assert_non_null(a);
    assert_non_null(b);
    sph_set_scalar_rows(b->model);
    test_run_to_end(a);
    test_run_to_end(b);
    double moved = 0.0;
    for (int k = 0; k < a->dim; k++)
        for (size_t i = 0; i < a->p->n; i++)
            moved = fmax(moved, fabs(a->p->x[k][i] - a->p->x0[k][i]));
    print_message("%s vector vs scalar rows: moved up to %.3g m\n", what, moved);
    assert_true(moved > 1e-6); /* something happened */
    assert_bitwise(a, b);
    sim_destroy(&a);
    sim_destroy(&b);
}

#endif
