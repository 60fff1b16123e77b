/**
 * @file lattice_threads.c
 * @brief Validation case "lattice-threads": the same fracture run (an
 *        alpha-beta plate, nu = 0.2, with an edge pre-crack, pulled hard at
 *        the top and bottom grips until a crack runs) with 1 and with 2 OpenMP
 *        threads must give bitwise identical positions and the same number of
 *        broken bonds.
 *
 * Why it must hold (docs/architecture.md, "Threads and determinism"): the
 * force loops gather over two-sided bond lists, each particle summing its own
 * row in a fixed order, breaking is decided identically from both ends of a
 * bond, and the integrator's loops are element-wise.  No quantity that feeds
 * the trajectory depends on the thread count, so the only acceptable
 * difference is exactly zero.  A crack path is chaotic: a single differing
 * bit anywhere would grow into visibly different positions within the run.
 */
#include "validation/lattice_cases.h"
#include "validation/validation.h"
#include "validation/vpar.h"

#include "core/particles.h"
#include "core/sim.h"
#include "spall/error.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#ifdef _OPENMP
#include <omp.h>
#endif

static const char *const THREADS_DECK =
    "title: pre-cracked alpha-beta plate pulled apart\n"
    "model: {type: lattice, law: linear}\n"
    "materials:\n"
    "  polymer: {density: 1140, youngs_modulus: 3.0e9, poisson_ratio: 0.2, "
    "tensile_strength: 60.0e6}\n"
    "lattice: {type: triangular, spacing: 1.0e-3}\n"
    "geometry:\n"
    "  plate: {box: {min: [-0.0001, -0.0001], max: [0.0401, 0.0200]}}\n"
    "body: {geometry: plate, material: polymer}\n"
    "groups:\n"
    "  bottom: {box: {min: [-1, -1], max: [1, 0.0010]}}\n"
    "  top: {box: {min: [-1, 0.0190], max: [1, 1]}}\n"
    "precracks:\n"
    "  - {from: [-0.001, 0.00996], to: [0.015, 0.00996]}\n"
    "boundary_conditions:\n"
    "  - {group: bottom, type: velocity, components: [x, y], value: [0, -8.0],\n"
    "     function: {type: linear_ramp, duration: 1.0e-5}}\n"
    "  - {group: top, type: velocity, components: [x, y], value: [0, 8.0],\n"
    "     function: {type: linear_ramp, duration: 1.0e-5}}\n"
    "run: {end_time: 1.0e-3}\n";

struct threads_result {
    size_t n;
    double *x[2];
    double broken;
    double energy_total;
    long steps;
    int threads_used;
};

static void threads_result_free(struct threads_result *t)
{
    free(t->x[0]);
    free(t->x[1]);
    t->x[0] = t->x[1] = NULL;
}

static int threads_run(struct vreport *r, int nthreads, long steps, struct threads_result *res,
                       struct spall_error *err)
{
    memset(res, 0, sizeof *res);
#ifdef _OPENMP
    omp_set_num_threads(nthreads);
    res->threads_used = omp_get_max_threads();
#else
    res->threads_used = 1;
    (void)nthreads;
#endif
    struct sim *s = NULL;
    int rc = vlat_build("threads_plate", THREADS_DECK, &s, err);
    if (rc)
        return rc;
    if ((rc = vpar_distribute(r, s, err))) /* mpirun: R ranks x 1 and x 2 threads */
        goto done;
    for (long k = 0; k < steps; k++)
        if ((rc = sim_step(s, err)))
            goto done;
    sim_update_energy(s);
    res->n = vpar_n(s);
    res->steps = steps;
    res->broken = vlat_history(s, "bonds_broken");
    res->energy_total = s->energy.kinetic + s->energy.strain + s->energy.model_dissipated;
    for (int d = 0; d < 2; d++) /* the whole plate by global id (vpar.h) */
        if (!(res->x[d] = vpar_whole(s, s->p->x[d], err))) {
            rc = err->code;
            goto done;
        }
done:
    sim_destroy(&s);
    return rc;
}

int lattice_case_threads(struct vreport *r, struct spall_error *err)
{
    static const char *const src = "docs/architecture.md: results bitwise independent of the "
                                   "thread count (gather formulation, no atomics)";
    /* ~60 us of loading: the pre-crack has run well into the plate */
    long steps = r->quick ? 300 : 800;
#ifdef _OPENMP
    int saved = omp_get_max_threads();
#endif
    struct threads_result a, b;
    memset(&b, 0, sizeof b);
    int rc = threads_run(r, 1, steps, &a, err);
    if (!rc)
        rc = threads_run(r, 2, steps, &b, err);
#ifdef _OPENMP
    omp_set_num_threads(saved);
#endif
    if (rc)
        goto done;
    double dmax = 0.0;
    size_t ndiff = 0;
    for (int d = 0; d < 2; d++)
        for (size_t i = 0; i < a.n && a.n == b.n; i++) {
            double dx = fabs(a.x[d][i] - b.x[d][i]);
            /* bitwise: also catches -0.0 vs 0.0 and NaN payloads */
            if (memcmp(&a.x[d][i], &b.x[d][i], sizeof(double)) != 0)
                ndiff++;
            dmax = isnan(dx) ? INFINITY : fmax(dmax, dx);
        }
    if (a.n != b.n)
        dmax = INFINITY;
    if ((rc = vreport_check(r, "max |x(1 thread) - x(2 threads)|", "m", 0.0, dmax, 0.0, false,
                            src, "exactly 0: any non-zero difference is a race or an order "
                            "dependence", err)) ||
        (rc = vreport_check_true(r, "positions bitwise identical", ndiff == 0, src,
                                 "memcmp of every coordinate", err)) ||
        (rc = vreport_check(r, "broken bonds, 2 threads vs 1 thread", "bonds", a.broken,
                            b.broken, 0.0, false, src, "exactly equal", err)) ||
        (rc = vreport_check_true(r, "the run breaks bonds (test is meaningful)", a.broken >= 20.0,
                                 "pre-cracked plate pulled at 8 m/s per grip",
                                 "without fracture the breaking code paths are not exercised",
                                 err)))
        goto done;
    vreport_info(r, "%zu particles, %ld steps; threads used %d and %d; bonds broken %g and %g; "
                 "max |dx| = %g m, %zu coordinates differ; total energy %.17g vs %.17g J",
                 a.n, steps, a.threads_used, b.threads_used, a.broken, b.broken, dmax, ndiff,
                 a.energy_total, b.energy_total);
    if (b.threads_used < 2)
        vreport_info(r, "warning: the OpenMP runtime gave only %d thread(s); the comparison is "
                     "then trivial", b.threads_used);
done:
    threads_result_free(&a);
    threads_result_free(&b);
    return rc;
}
