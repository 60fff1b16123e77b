/**
 * @file test_support.h
 * @brief Helpers shared by the cmocka tests: build a simulation from YAML
 *        text through the validation layer's vlat_build (one copy instead
 *        of one per test file).  Include after <cmocka.h>.
 */
#ifndef SPALL_TEST_SUPPORT_H
#define SPALL_TEST_SUPPORT_H

#include "core/bond_list.h"
#include "core/particles.h"
#include "core/sim.h"
#include "io/deck.h"
#include "io/deck_build.h"
#include "spall/error.h"
#include "validation/lattice_cases.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

/** The simulation of @p yaml, or NULL with the cause printed (for tests
 *  that also feed decks the engine must refuse). */
static inline struct sim *test_build(const char *yaml)
{
    struct sim *s = NULL;
    struct spall_error err = {0};
    if (vlat_build("test", yaml, &s, &err)) {
        print_error("%s\n", err.msg);
        return NULL;
    }
    return s;
}

/** The simulation of @p yaml; the test fails (cause printed) if it does not
 *  build. */
static inline struct sim *test_build_ok(const char *yaml)
{
    struct sim *s = test_build(yaml);
    assert_non_null(s);
    return s;
}

/** Step @p s to its end; the test fails (cause printed) on an error. */
static inline void test_run_to_end(struct sim *s)
{
    struct spall_error err = {0};
    while (!sim_done(s)) {
        int rc = sim_step(s, &err);
        if (rc)
            print_error("%s\n", err.msg);
        assert_int_equal(rc, 0);
    }
}

/** @p yaml must be refused as bad input (SPALL_ERR_INPUT, no simulation)
 *  with a message that contains @p needle. */
static inline void test_deck_refused(const char *yaml, const char *needle)
{
    struct deck *d = NULL;
    struct sim *s = NULL;
    struct run_output ro;
    struct spall_error err = {0};
    assert_int_equal(deck_load_string(&d, "bad", yaml, &err), 0);
    assert_int_equal(deck_build_sim(d, &s, &ro, &err), SPALL_ERR_INPUT);
    print_message("refused: %s\n", err.msg);
    assert_non_null(strstr(err.msg, needle));
    deck_destroy(&d);
    assert_null(s);
}

/** Total momentum of a 2D run. */
static inline void test_momentum_2d(const struct sim *s, double P[2])
{
    P[0] = P[1] = 0.0;
    for (size_t i = 0; i < s->p->n; i++)
        for (int d = 0; d < 2; d++)
            P[d] += s->p->mass[i] * s->p->v[d][i];
}

/** Total momentum of a 3D run into @p P; returns sum m |v_d| over all
 *  particles and components (the scale for a round-off tolerance). */
static inline double test_momentum_3d(const struct sim *s, double P[3])
{
    double scale = 0.0;
    P[0] = P[1] = P[2] = 0.0;
    for (size_t i = 0; i < s->p->n; i++)
        for (int d = 0; d < 3; d++) {
            P[d] += s->p->mass[i] * s->p->v[d][i];
            scale += s->p->mass[i] * fabs(s->p->v[d][i]);
        }
    return scale;
}

/** Kinetic + strain energy of @p s, refreshed. */
static inline double test_mech_energy(struct sim *s)
{
    sim_update_energy(s);
    return s->energy.kinetic + s->energy.strain;
}

/** x and v of every particle of a 3D run into @p xs (6 values per
 *  particle, zero-padded to @p nx): the state that bitwise checks compare. */
static inline void test_pack_xv(const struct sim *s, double *xs, size_t nx)
{
    memset(xs, 0, nx * sizeof *xs);
    for (size_t i = 0; i < s->p->n && 6 * i + 5 < nx; i++)
        for (int d = 0; d < 3; d++) {
            xs[6 * i + d] = s->p->x[d][i];
            xs[6 * i + 3 + d] = s->p->v[d][i];
        }
}

/** Smallest distance between particles of different bodies (2D, O(N^2):
 *  small tests only). */
static inline double test_min_cross_distance(const struct sim *s)
{
    double best = INFINITY;
    for (size_t i = 0; i < s->p->n; i++)
        for (size_t j = i + 1; j < s->p->n; j++) {
            if (s->p->body[i] == s->p->body[j])
                continue;
            double dx = s->p->x[0][i] - s->p->x[0][j], dy = s->p->x[1][i] - s->p->x[1][j];
            best = fmin(best, sqrt(dx * dx + dy * dy));
        }
    return best;
}

/** A copy (free it) of the bond states of @p bl, *nh of them. */
static inline uint8_t *test_copy_states(const struct bond_list *bl, size_t *nh)
{
    *nh = bl->offset[bl->n];
    uint8_t *st = malloc(*nh ? *nh : 1);
    assert_non_null(st);
    memcpy(st, bl->state, *nh);
    return st;
}

#endif
