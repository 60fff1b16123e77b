/**
 * @file bench_sph.c
 * @brief SPH throughput (issue 6 item 8): a 3D Taylor bar, the copper bar
 *        posed for the LAMMPS MACHDYN race (bench/sph_vs_lammps.sh):
 *        L0 = 32.4 mm, R0 = 3.2 mm, 227 m/s on a rigid wall, E = 117 GPa,
 *        nu = 0.35, rho = 8930 kg/m^3, sigma_y = 0.4 GPa + 0.1 GPa eps_p,
 *        dx = 0.4 mm (scale 1; scale s: dx = 0.4 mm / s^(1/3)), h = 1.5 dx
 *        (Wendland, support 3 dx: ~ 110 neighbours per particle).
 *        The note reports the share of wall time spent building neighbour
 *        lists.  Numbers are printed, never asserted.
 */
#include "bench/bench.h"

#include "core/particles.h"
#include "core/sim.h"
#include "io/deck.h"
#include "io/deck_build.h"
#include "models/model.h"
#include "models/sph/sph_internal.h"
#include "spall/error.h"

#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <string.h>

/* Build @p yaml, time its steps, fill @p out like bench_run_deck (memory:
 * resident set after the build / particles) and report the share of the
 * loop's wall time spent building neighbour lists and how many builds. */
static int sph_bench_run(const char *name, const char *yaml, int threads,
                         struct bench_result *out, double *nb_share, size_t *builds,
                         struct spall_error *err)
{
    omp_set_num_threads(threads);
    struct deck *d = NULL;
    struct sim *s = NULL;
    struct run_output ro;
    int rc = deck_load_string(&d, name, yaml, err);
    if (!rc)
        rc = deck_build_sim(d, &s, &ro, err);
    deck_destroy(&d);
    if (rc)
        return rc;
    double rss = bench_rss_bytes();
    const double tn0 = s->model->t_neighbor;
    double t0 = omp_get_wtime();
    while (!sim_done(s) && !rc)
        rc = sim_step(s, err);
    double wall = omp_get_wtime() - t0;
    memset(out, 0, sizeof *out);
    snprintf(out->name, sizeof out->name, "%s", name);
    out->threads = threads;
    out->particles = s->p->n_owned;
    out->bonds = s->ops->interactions(s->model, s);
    out->steps = s->step;
    out->seconds = wall;
    out->particle_steps_per_s = (double)out->particles * (double)out->steps / wall;
    out->bond_steps_per_s = (double)out->bonds * (double)out->steps / wall;
    out->bytes_per_particle = rss / (double)out->particles;
    *nb_share = (s->model->t_neighbor - tn0) / wall;
    *builds = s->model->n_builds;
    sim_destroy(&s);
    return rc;
}

static int bench_sph_taylor(int threads, double scale, struct bench_result *out,
                            struct spall_error *err)
{
    const double dx = 0.4e-3 / cbrt(scale > 0.0 ? scale : 1.0);
    const long steps = 200;
    char yaml[2048];
    snprintf(yaml, sizeof yaml,
             "model: {type: sph, kernel: wendland, h_factor: 1.5, viscosity: [1.0, 1.0],\n"
             "        adaptive_dt: false, wall: {point: [0, 0, 0], normal: [0, 0, 1]}}\n"
             "materials:\n"
             "  copper: {density: 8930, youngs_modulus: 117.0e9, poisson_ratio: 0.35,\n"
             "           yield: power, yield_a: 0.4e9, yield_b: 0.1e9, yield_n: 1.0}\n"
             "lattice: {type: sc, spacing: %.17g, origin: [%.17g, %.17g, %.17g]}\n"
             "body: {geometry: {cylinder: {base: [0, 0, 0], top: [0, 0, 0.0324], "
             "radius: 0.0032}}, material: copper}\n"
             "initial_velocity: [{group: all, value: [0, 0, -227.0]}]\n"
             "run: {steps: %ld}\n",
             dx, 0.5 * dx, 0.5 * dx, 0.5 * dx, steps);
    double nb_share = 0.0;
    size_t builds = 0;
    int rc = sph_bench_run("sph_taylor_cu", yaml, threads, out, &nb_share, &builds, err);
    if (rc)
        return rc;
    snprintf(out->note, sizeof out->note,
             "3D Cu Taylor bar dx = %.3g mm, %.1f neighbours/particle, neighbour search "
             "%.1f %% of wall time (%zu builds)",
             dx * 1e3, 2.0 * (double)out->bonds / (double)out->particles, 100.0 * nb_share,
             builds);
    return rc;
}

/* 2D plane strain: the two rubber rings of validation/sph_rings.c (Gray
 * et al. 2001), cubic spline h = 1.5 dx, AV, artificial stress 0.3 (the
 * 2D path with AS, i.e. the most expensive pair loop), dx = 0.5 mm. */
static int bench_sph_rings(int threads, double scale, struct bench_result *out,
                           struct spall_error *err)
{
    const double dx = 0.5e-3 / sqrt(scale > 0.0 ? scale : 1.0);
    const long steps = 200;
    char yaml[3072];
    snprintf(yaml, sizeof yaml,
             "model: {type: sph, kernel: cubic_spline, h_factor: 1.5, viscosity: [1.0, 1.0],\n"
             "        artificial_stress: 0.3, plane: strain, adaptive_dt: false}\n"
             "materials: {rubber: {density: 1000, youngs_modulus: 1.0e7, poisson_ratio: 0.3975}}\n"
             "lattice: {type: square, spacing: %.17g, origin: [%.17g, %.17g]}\n"
             "body: {geometry: {union: [\n"
             "  {difference: [{circle: {center: [-0.041, 0], radius: 0.04}},\n"
             "                {circle: {center: [-0.041, 0], radius: 0.03}}]},\n"
             "  {difference: [{circle: {center: [0.041, 0], radius: 0.04}},\n"
             "                {circle: {center: [0.041, 0], radius: 0.03}}]}]},\n"
             "       material: rubber}\n"
             "groups: {left: {box: {min: [-1, -1], max: [0, 1]}}}\n"
             "initial_velocity: [{group: left, value: [7.5, 0]}]\n"
             "run: {steps: %ld}\n",
             dx, 0.5 * dx, 0.5 * dx, steps);
    double nb_share = 0.0;
    size_t builds = 0;
    int rc = sph_bench_run("sph_rings_2d", yaml, threads, out, &nb_share, &builds, err);
    if (rc)
        return rc;
    snprintf(out->note, sizeof out->note,
             "2D rings dx = %.3g mm, %.1f neighbours/particle (listed, with skin), neighbour "
             "search %.1f %% of wall time",
             dx * 1e3, 2.0 * (double)out->bonds / (double)out->particles, 100.0 * nb_share);
    return rc;
}

/* SPH cases, listed by bench/cases.c. */
const struct bench_case bench_sph_cases[] = {
    {"sph_taylor_cu", "3D copper Taylor bar (LAMMPS race), dx = 0.4 mm, 200 steps",
     bench_sph_taylor},
    {"sph_rings_2d", "2D rubber rings (Gray et al. 2001), artificial stress, dx = 0.5 mm, 200 steps",
     bench_sph_rings},
};
const size_t bench_sph_n_cases = sizeof bench_sph_cases / sizeof bench_sph_cases[0];
