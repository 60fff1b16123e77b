/*
 * Spatial ghosts in the step (core/parallel/spatial.h) under mpirun: a
 * macro-particle block is built twice on every rank, once kept whole (the
 * one-rank reference) and once distributed.  Then the particles of rank 0
 * next to another rank's particles jump past the nearest of them, to 0.3
 * of their distance beyond it (far past skin/2, so the lists and the
 * ghosts are rebuilt, and they land inside another rank's region),
 * identically in both.  After one force
 * call: exactly one ghost rebuild; each rank's ghosts are the particles of
 * other ranks within range + skin of its owned particles' box (brute
 * force, ascending gid, positions exact); every owned particle's force
 * equals the reference's bit for bit; and some moved particle is a ghost
 * of a rank whose box it entered.
 * Run: mpirun -np N test_par_spatial (N >= 2).
 */
#include "core/model.h"
#include "core/parallel/comm.h"
#include "core/parallel/decomp.h"
#include "core/parallel/spatial.h"
#include "core/particles.h"
#include "core/sim.h"
#include "io/deck.h"
#include "io/deck_build.h"
#include "spall/error.h"
#include "tests/mpi/par_check.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char *deck_text =
    "model: {type: macroparticle}\n"
    "materials:\n"
    "  al: {density: 2700, atomic_mass_u: 26.98, cohesive_energy_ev: 3.39, exponents: [4, 9],\n"
    "       yield_strain: 0.002, hardening: 0.1}\n"
    "lattice: {type: fcc, spacing: 1.0e-3}\n"
    "geometry:\n"
    "  blk: {box: {min: [0, 0, 0], max: [0.0040001, 0.0040001, 0.0060001]}}\n"
    "body: {geometry: blk, material: al}\n"
    "run: {steps: 10}\n";

static struct sim *build(struct run_output *ro)
{
    struct spall_error err = {0};
    struct deck *d = NULL;
    struct sim *s = NULL;
    if (deck_load_string(&d, "spatial.yaml", deck_text, &err) ||
        deck_build_sim(d, &s, ro, &err)) {
        fprintf(stderr, "rank %d: cannot build the deck: %s\n", par_rank(), err.msg);
        failures++;
    }
    deck_destroy(&d);
    return s;
}

static int forces(struct sim *s)
{
    struct spall_error err = {0};
    particles_zero_forces(s->p);
    int rc = s->par ? par_ghosts_step(s, &err) : 0;
    if (!rc)
        rc = s->ops->compute_forces(s->model, s, &err);
    CHECK(rc == 0, "force call: %s", err.msg);
    return rc;
}

int main(int argc, char **argv)
{
    if (par_world_init(&argc, &argv))
        return 1;
    const int size = par_size(), rank = par_rank();
    struct run_output ro_a, ro_b;
    struct sim *ref = build(&ro_a), *dis = build(&ro_b);
    struct spall_error err = {0};
    if (!ref || !dis || par_distribute(dis, &err)) {
        fprintf(stderr, "rank %d: set-up failed: %s\n", rank, err.msg);
        return 1;
    }
    const size_t ng = ref->p->n, no = dis->p->n_owned;
    struct par_spatial_model sm;
    memset(&sm, 0, sizeof sm);
    dis->ops->spatial_ghosts(dis->model, &sm);
    const double cut = sm.range + sm.skin, r0 = 1.0e-3; /* lattice.spacing: r0 */
    /* every particle's owner (owned particles are in ascending gid) */
    int *owner = calloc(ng, sizeof *owner);
    uint64_t *own = calloc(ng, sizeof *own);
    for (size_t i = 0; i < no; i++)
        own[dis->p->gid[i]] = (uint64_t)rank;
    par_sum_u64_array(own, ng);
    for (size_t g = 0; g < ng; g++)
        owner[g] = (int)own[g];
    /* the jump: each particle of rank 0 with another rank's particle within
     * 1.1 r0 jumps past the nearest such particle, 0.3 of the distance beyond */
    double (*jump)[3] = calloc(ng, sizeof *jump);
    size_t jumped = 0;
    for (size_t g = 0; g < ng; g++) {
        double best = 1.21 * r0 * r0;
        long k = -1;
        for (size_t h = 0; h < ng; h++) {
            if (owner[h] == owner[g])
                continue;
            double r2 = 0.0;
            for (int d = 0; d < 3; d++)
                r2 += pow(ref->p->x[d][h] - ref->p->x[d][g], 2);
            if (r2 < best) {
                best = r2;
                k = (long)h;
            }
        }
        if (k < 0 || owner[g] != 0) /* rank 0's border particles only */
            continue;
        for (int d = 0; d < 3; d++)
            jump[g][d] = 1.3 * (ref->p->x[d][k] - ref->p->x[d][g]);
        jumped++;
    }
    CHECK(jumped > 0, "no particle next to another rank");
    for (size_t g = 0; g < ng; g++)
        for (int d = 0; d < 3; d++)
            ref->p->x[d][g] += jump[g][d];
    for (size_t i = 0; i < no; i++)
        for (int d = 0; d < 3; d++)
            dis->p->x[d][i] += jump[dis->p->gid[i]][d];
    long before = par_spatial_rebuilds(dis);
    forces(ref);
    forces(dis);
    CHECK(par_spatial_rebuilds(dis) == before + 1, "rebuilds %ld -> %ld",
          before, par_spatial_rebuilds(dis));
    /* forces bit for bit */
    size_t differ = 0;
    for (size_t i = 0; i < no; i++)
        for (int d = 0; d < 3; d++)
            differ += dis->p->f[d][i] != ref->p->f[d][dis->p->gid[i]];
    CHECK(differ == 0, "%zu force components differ from one rank", differ);
    /* the ghosts: brute force around the owned box */
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (size_t i = 0; i < no; i++)
        for (int d = 0; d < 3; d++) {
            lo[d] = fmin(lo[d], dis->p->x[d][i]);
            hi[d] = fmax(hi[d], dis->p->x[d][i]);
        }
    size_t q = no, wrong = 0, entered = 0;
    for (size_t g = 0; g < ng; g++) {
        if (owner[g] == rank)
            continue;
        double r2 = 0.0;
        int inside = 1;
        for (int d = 0; d < 3; d++) {
            double x = ref->p->x[d][g];
            double u = x < lo[d] ? lo[d] - x : x > hi[d] ? x - hi[d] : 0.0;
            inside &= u == 0.0;
            r2 += u * u;
        }
        if (r2 > cut * cut)
            continue;
        int ok = q < dis->p->n && dis->p->gid[q] == (int64_t)g;
        for (int d = 0; d < 3 && ok; d++)
            ok = dis->p->x[d][q] == ref->p->x[d][g];
        wrong += !ok;
        entered += inside && (jump[g][0] != 0.0 || jump[g][1] != 0.0 || jump[g][2] != 0.0);
        q += ok;
    }
    CHECK(wrong == 0 && q == dis->p->n, "ghosts: %zu wrong, %zu of %zu matched", wrong, q - no,
          dis->p->n - no);
    CHECK(size < 2 || par_sum_u64(entered) > 0, "no moved particle entered another rank's box");
    int total = (int)par_sum_u64((uint64_t)failures);
    if (rank == 0)
        printf("test_par_spatial: %d ranks, %zu particles moved, %s\n", size, jumped,
               total ? "FAILED" : "ok");
    free(owner);
    free(own);
    free(jump);
    sim_destroy(&ref);
    sim_destroy(&dis);
    par_world_finalize();
    return total ? 1 : 0;
}
