/**
 * @file lattice_kernels.h
 * @brief What the lattice's linear force loops share (lattice_forces.c:
 *        every half-bond evaluated from its own row; lattice_half.c: each
 *        bond once): the view of the arrays, the bond vector, the rare
 *        breaking path.  Not part of the public interface.
 */
#ifndef SPALL_LATTICE_KERNELS_H
#define SPALL_LATTICE_KERNELS_H

#include "models/lattice/lattice_internal.h"

#include <math.h>
#include <stddef.h>
#include <stdint.h>

/* Half-bonds per block of the linear loops: the block's scratch (bond
 * vectors and coefficients, 4 x 8 B per half-bond) stays in L1. */
#define LATTICE_BLOCK 256

/* The linear loops in two versions picked once at load time by the CPU (GCC
 * function multi-versioning): x86-64-v3 (four-lane sqrt and division) and
 * the build's baseline.  The files are built without FP contraction (ISO C
 * mode) and with -fno-math-errno (a sqrt the compiler may vectorise), so
 * both versions round every operation alike: the same bits on any CPU and
 * thread.  SPALL_NO_CLONES builds the baseline only. */
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && defined(__linux__) &&     \
    !defined(SPALL_NO_CLONES)
#define LATTICE_CLONES __attribute__((target_clones("arch=x86-64-v3", "default")))
#else
#define LATTICE_CLONES
#endif

/** Arrays the hot loops read, copied into locals once per call so that the
 *  compiler need not reload them after every store into the force arrays. */
struct lattice_view {
    const size_t *restrict offset;
    const int32_t *restrict partner;
    const double *restrict rest;        /* NULL when compacted: */
    const uint16_t *restrict rest_idx;  /* rest = rest_tab[rest_idx[s]] */
    const double *restrict rest_tab;
    const uint8_t *restrict state;
    const uint8_t *restrict type;
    const size_t *restrict reverse;
    const double *restrict ang_buf;
    const double *restrict kscale; /* NULL unless an E(T) table is given */
    const int32_t *restrict mat;
    const double *restrict x0, *restrict x1, *restrict x2;
    double *restrict f0, *restrict f1, *restrict f2;
    const double *const *u; /* drift velocities: x_n = x - dt_drift u */
    double dt_drift;
    int set_forces; /* add_force sets f = 0 + fi (the owned forces were not
                       cleared: lattice_set_forces), else f += fi */
};

/** The view of the model's and the particles' arrays for one force call. */
struct lattice_view lattice_make_view(const struct model *m, struct sim *sim);

/** Reference length of half-bond s (bond_rest on the view's copies). */
LATTICE_INLINE double view_rest(const struct lattice_view *v, size_t s)
{
    return v->rest_idx ? v->rest_tab[v->rest_idx[s]] : v->rest[s];
}

/** dx = x_j - x_i for the first @p dim components; returns |dx|^2. */
LATTICE_INLINE double bond_vec(const struct lattice_view *v, size_t i, size_t j, const int dim,
                               double dx[3])
{
    dx[0] = v->x0[j] - v->x0[i];
    double r2 = dx[0] * dx[0];
    if (dim > 1) {
        dx[1] = v->x1[j] - v->x1[i];
        r2 += dx[1] * dx[1];
    }
    if (dim > 2) {
        dx[2] = v->x2[j] - v->x2[i];
        r2 += dx[2] * dx[2];
    }
    return r2;
}

/** r - r_n: the bond's length change over this step (x_n = x - dt u). */
double lattice_bond_dr(const struct lattice_view *v, size_t i, size_t j, int dim,
                       const double dx[3], double r);

/** Rare path: half-bond s of particle i breaks now (length r, stretch st;
 *  dr = r - r_n over the step).  Books half the released energy on i as the
 *  Verlet kicks left it and returns the post-fracture force coefficient.
 *  The intact force acted only at x_n, half a step, and the broken law's
 *  from x_{n+1}: the energy the kicks took out differs from the intact
 *  energy at x_{n+1} by (f_i - f_b) dr / 2, which booking U_i - U_b at the
 *  break would leave in the account (first order in dt).  Not inlined:
 *  rare (lattice_forces.c). */
double lattice_break_half(struct model *m, size_t i, size_t s, const struct lattice_bond_law *bw,
                          double rest, double r, double dr);

/** The linear loop over the owned rows [lo, hi) with each bond evaluated
 *  once (lattice_half.c): @p ring, this thread's zeroed ring of row sums,
 *  dim arrays of mask + 1 entries (lattice_half_ring), zero again on
 *  return.  Returns the rows its stencil blocks took. */
size_t lattice_half_range(struct model *m, const struct lattice_view *v, size_t lo, size_t hi,
                        double *ring, size_t mask, int dim, int multi, int gather);

/* Row i's force: every force call writes each owned row once, so "set"
 * gives f = 0 + fi, the bits of f += fi on cleared forces (+0 + fi, also
 * for fi = -0), without reading f. */
LATTICE_INLINE void add_force(const struct lattice_view *v, size_t i, const int dim,
                              const double fi[3])
{
    if (v->set_forces) {
        v->f0[i] = 0.0 + fi[0];
        if (dim > 1)
            v->f1[i] = 0.0 + fi[1];
        if (dim > 2)
            v->f2[i] = 0.0 + fi[2];
        return;
    }
    v->f0[i] += fi[0];
    if (dim > 1)
        v->f1[i] += fi[1];
    if (dim > 2)
        v->f2[i] += fi[2];
}

#endif
