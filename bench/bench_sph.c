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
#include "core/profile.h"
#include "core/sim.h"
#include "io/deck.h"
#include "io/deck_build.h"
#include "core/model.h"
#include "core/parallel/comm.h"
#include "models/sph/sph.h"
#include "spall/error.h"

#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <string.h>
#include <time.h>

/* CPU seconds of the whole process (all threads): on a shared, oversubscribed
 * machine the wall clock mostly measures the other jobs, the CPU time of
 * the loop what this code costs per core. */
static double sph_cpu_seconds(void)
{
    struct timespec ts;
    if (clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts) != 0)
        return 0.0;
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* Build @p yaml, time its steps, fill @p out like bench_run_deck (memory:
 * resident set after the build / particles) and report the share of the
 * loop's wall time spent building neighbour lists and how many builds. */
static int sph_bench_run(const char *name, const char *yaml, int threads, bool split,
                         struct bench_result *out, double *nb_share, size_t *builds,
                         double *t_setup_nb, double shape[4], double *cpu, double *rr,
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
    if (!rc && par_size() > 1) /* it reads this rank's particle arrays (bench_par.c) */
        rc = bench_distribute(s, name, err);
    /* the timed loop alone describes a distributed run (bench_fill); the
     * bar's shape and the re-referencing figures read one rank's arrays */
    if (!rc && s->par && (shape || rr))
        rc = spall_error_set(err, SPALL_ERR_INPUT,
                             "'%s' does not run distributed yet: its measurements read the "
                             "particle arrays of one rank",
                             name);
    if (rc) {
        sim_destroy(&s);
        return rc;
    }
    if (split)
        sph_set_split_loops(s->model);
    double rss = bench_rss_bytes();
    struct sph_stats st;
    sph_stats_get(s->model, &st);
    const double tn0 = st.t_neighbor;
    *t_setup_nb = tn0;
    double t0 = omp_get_wtime(), c0 = sph_cpu_seconds();
    while (!sim_done(s) && !rc)
        rc = sim_step(s, err);
    double wall = omp_get_wtime() - t0;
    *cpu = sph_cpu_seconds() - c0;
    sph_stats_get(s->model, &st);
    *nb_share = (st.t_neighbor - tn0) / wall; /* rank 0's share when distributed */
    *builds = st.n_builds;
    if (s->par) {
        /* whole-run rates over the slowest rank; pairs are each rank's list
         * (a pair across ranks is listed on both) */
        const size_t n_body = (size_t)par_sum_u64(s->p->n_owned);
        const size_t pairs = (size_t)par_sum_u64(s->ops->interactions(s->model, s));
        bench_fill(s, name, threads, n_body, pairs, wall, *cpu, 0.0, rss, bench_rss_bytes(),
                   out);
        sim_destroy(&s);
        return rc;
    }
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
    if (shape) {
        /* Taylor bar: length = axial extent + dx, mushroom radius = largest
         * radius of the impact face's particles + dx/2 (as validation/sph_taylor.c) */
        const struct particles *p = s->p;
        const double dx = sph_spacing(s->model, 0);
        double zmax = -INFINITY, zmin = INFINITY, rmax = 0.0;
        for (size_t i = 0; i < p->n_owned; i++) {
            zmax = fmax(zmax, p->x[2][i]);
            zmin = fmin(zmin, p->x[2][i]);
            if (p->x0[2][i] < 1.5 * dx)
                rmax = fmax(rmax, hypot(p->x[0][i], p->x[1][i]));
        }
        shape[0] = zmax - zmin + dx;
        shape[1] = rmax + 0.5 * dx;
        /* the mushroom's outer radius 0.5 mm and 1 mm above the wall, where
         * the FE reference converges (core/profile.h; validation/fe/taylor_cu) */
        for (int k = 0; k < 2 && !rc; k++)
            rc = profile_radius(p, 0.5e-3 * (k + 1), dx, 0.5 * dx, &shape[2 + k], err);
    }
    if (rr) {
        /* TLSPH re-referencing: updates, their wall time, h growths, partners per particle */
        const struct model *m = s->model;
        double hmax = 0.0;
        for (size_t i = 0; i < s->p->n_owned; i++)
            hmax = fmax(hmax, sph_smoothing_length(m, i) / (st.h_factor * sph_spacing(m, i)));
        rr[0] = (double)st.tl_rerefs;
        rr[1] = st.t_reref;
        rr[2] = hmax;
        rr[3] = (double)sph_tlsph_pairs(m) / (double)s->p->n_owned;
    }
    sim_destroy(&s);
    return rc;
}

/* The copper bar deck: @p form "updated" (model sph) or "total" (tlsph), h = @p hf dx,
 * viscosity [q_a, q_b]; dx = 0.4 mm / scale^(1/3). */
static void sph_taylor_deck(char *yaml, size_t size, double scale, const char *form, double hf,
                            double qa, double qb, long steps, const char *extra)
{
    char run[128];
    if (steps > 0)
        snprintf(run, sizeof run, "run: {steps: %ld, max_particles: 1e9}\n", steps);
    else /* to rest (the bar leaves the wall at ~ 50 us), adaptive dt */
        snprintf(run, sizeof run, "run: {end_time: 8.0e-5, max_particles: 1e9}\n");
    const double dx = 0.4e-3 / cbrt(scale > 0.0 ? scale : 1.0);
    snprintf(yaml, size,
             "model: {type: %s, kernel: wendland, h_factor: %.17g, viscosity: [%g, %g],\n"
             "        adaptive_dt: %s,%s\n"
             "        wall: {point: [0, 0, 0], normal: [0, 0, 1]}}\n"
             "materials:\n"
             "  copper: {density: 8930, youngs_modulus: 117.0e9, poisson_ratio: 0.35,\n"
             "           yield: power, yield_a: 0.4e9, yield_b: 0.1e9, yield_n: 1.0}\n"
             "lattice: {type: sc, spacing: %.17g, origin: [%.17g, %.17g, %.17g]}\n"
             "body: {geometry: {cylinder: {base: [0, 0, 0], top: [0, 0, 0.0324], "
             "radius: 0.0032}}, material: copper}\n"
             "initial_velocity: [{group: all, value: [0, 0, -227.0]}]\n"
             "%s",
             strcmp(form, "total") == 0 ? "tlsph" : "sph", hf, qa, qb, steps > 0 ? "false" : "true",
             extra, dx, 0.5 * dx, 0.5 * dx, 0.5 * dx,
             run);
}

/* @p split: the verification loops (sph_set_split_loops) */
static int sph_taylor_loops(const char *name, const char *form, double hf, double qa, double qb,
                            const char *extra, bool split, int threads, double scale,
                            struct bench_result *out, struct spall_error *err)
{
    char yaml[2048];
    sph_taylor_deck(yaml, sizeof yaml, scale, form, hf, qa, qb, 200, extra);
    double nb_share = 0.0;
    size_t builds = 0;
    double t_setup = 0.0, cpu = 0.0;
    int rc = sph_bench_run(name, yaml, threads, split, out, &nb_share, &builds, &t_setup, NULL,
                           &cpu, NULL, err);
    if (rc)
        return rc;
    snprintf(out->note, sizeof out->note,
             "%s, h = %.4g dx, dx = %.3g mm, %.1f neighbours; neighbour search %.1f %% "
             "(%zu builds, set-up %.2g s); loop CPU %.3g s = %.3g p-steps/CPU-s",
             form, hf, 0.4 / cbrt(scale > 0.0 ? scale : 1.0),
             2.0 * (double)out->bonds / (double)out->particles, 100.0 * nb_share, builds,
             t_setup, cpu, (double)out->particles * (double)out->steps / cpu);
    return rc;
}

static int sph_taylor_case(const char *name, const char *form, double hf, double qa, double qb,
                           const char *extra, int threads, double scale, struct bench_result *out,
                           struct spall_error *err)
{
    return sph_taylor_loops(name, form, hf, qa, qb, extra, false, threads, scale, out, err);
}

/* updated form, h = 1.5 dx (Wendland support 3 dx: ~ 110 neighbours) */
static int bench_sph_taylor(int threads, double scale, struct bench_result *out,
                            struct spall_error *err)
{
    return sph_taylor_case("sph-taylor-cu", "updated", 1.5, 1.0, 1.0, "", threads, scale, out,
                           err);
}

/* The LAMMPS MACHDYN race at a matched neighbour count: MACHDYN's TLSPH
 * examples set the kernel radius (atom diameter) to 2.01 dx
 * (examples/PACKAGES/machdyn/aluminum_strip_pull), i.e. 32 neighbours on
 * a simple-cubic lattice; the Wendland kernel with h = 1.005 dx has the
 * same support 2.01 dx.  Total-Lagrangian form (fixed reference list). */
static int bench_sph_taylor_tl(int threads, double scale, struct bench_result *out,
                               struct spall_error *err)
{
    return sph_taylor_case("sph-taylor-cu-tl", "total", 1.005, 1.0, 1.0, "", threads, scale, out,
                           err);
}

/* the same with the TLSPH stages run one after the other over all
 * particles (sph_set_split_loops) instead of pipelined in one sweep
 * (sph_tlsph.c): same arithmetic, bitwise the same result; what the
 * pipeline's cache reuse is worth */
static int bench_sph_taylor_tl_split(int threads, double scale, struct bench_result *out,
                                     struct spall_error *err)
{
    return sph_taylor_loops("sph-taylor-cu-tl-split", "total", 1.005, 1.0, 1.0, "", true,
                            threads, scale, out, err);
}

/* The race's accuracy half: the bar run to rest (80 us, adaptive dt),
 * final length and mushroom radius. */
static int sph_taylor_rest(const char *name, const char *form, double hf, const char *extra,
                           double scale, int threads, struct bench_result *out,
                           struct spall_error *err)
{
    char yaml[2048];
    sph_taylor_deck(yaml, sizeof yaml, scale, form, hf, 1.0, 1.0, 0, extra);
    double nb_share = 0.0, t_setup = 0.0, shape[4] = {0, 0, 0, 0}, cpu = 0.0;
    size_t builds = 0;
    double rr[4] = {0, 0, 0, 0};
    int rc = sph_bench_run(name, yaml, threads, false, out, &nb_share, &builds, &t_setup,
                           shape, &cpu, rr, err);
    if (rc)
        return rc;
    snprintf(out->note, sizeof out->note,
             "to 80 us, %s, h = %.4g dx, dx = %.3g mm: final length %.3f mm, mushroom radius "
             "%.3f mm, at 0.5 / 1 mm above the wall %.3f / %.3f mm (L0 32.4, R0 3.2; FE "
             "21.39, 7.19, 6.80-6.82 / 6.22-6.26); loop CPU %.3g s",
             form, hf, 0.4 / cbrt(scale > 0.0 ? scale : 1.0), shape[0] * 1e3, shape[1] * 1e3,
             shape[2] * 1e3, shape[3] * 1e3, cpu);
    if (rr[0] > 0.0) {
        const size_t len = strlen(out->note);
        snprintf(out->note + len, sizeof out->note - len,
                 "; %.0f reference updates (%.3g s wall), h <= %.3g h0, %.1f partners at the end",
                 rr[0], rr[1], rr[2], rr[3]);
    }
    return rc;
}

static int bench_sph_taylor_rest(int threads, double scale, struct bench_result *out,
                                 struct spall_error *err)
{
    return sph_taylor_rest("sph-taylor-cu-rest", "total", 1.005, "", scale, threads, out, err);
}

static int bench_sph_taylor_rest_ul(int threads, double scale, struct bench_result *out,
                                    struct spall_error *err)
{
    return sph_taylor_rest("sph-taylor-cu-rest-ul32", "updated", 1.005, "", scale, threads, out,
                           err);
}

/* the sph-taylor-cu bar (updated form, h = 1.5 dx) run to rest: what
 * spall's updated form gives against the FE reference of the race's
 * accuracy half (validation/fe/taylor_cu) */
static int bench_sph_taylor_rest_ul15(int threads, double scale, struct bench_result *out,
                                      struct spall_error *err)
{
    return sph_taylor_rest("sph-taylor-cu-rest-ul", "updated", 1.5, "", scale, threads, out,
                           err);
}

/* the _rest_ul bar with Balsara's switch (sph_rates.c: the updated form's
 * two-pass loops): the AV in shear against the FE reference, as the
 * TLSPH _rest_bal bar */
static int bench_sph_taylor_rest_ulbal(int threads, double scale, struct bench_result *out,
                                       struct spall_error *err)
{
    return sph_taylor_rest("sph-taylor-cu-rest-ulbal", "updated", 1.5,
                           " viscosity_switch: balsara,", scale, threads, out, err);
}

/* TLSPH with the staggered leapfrog: one force call per step and the plain
 * time-step limit (sph_model.c skips the |B0^-1| reduction for it), and
 * hourglass 1 (as the TLSPH beam): with the default 0.1 the mushroom's rim
 * inverts after ~20 us at dx = 0.4 mm */
static int bench_sph_taylor_rest_lf(int threads, double scale, struct bench_result *out,
                                    struct spall_error *err)
{
    return sph_taylor_rest("sph-taylor-cu-rest-lf", "total", 1.005,
                           " time_integration: leapfrog, hourglass: 1.0,", scale, threads, out,
                           err);
}

/* TLSPH with re-referencing (sph_tlsph_reref.c): the _rest_lf bar with the
 * default hourglass 0.1 (which alone inverts the rim at dx = 0.4 mm) and
 * the reference replaced by the current configuration whenever a
 * particle's distortion passes 1.2 */
static int bench_sph_taylor_rest_rr(int threads, double scale, struct bench_result *out,
                                    struct spall_error *err)
{
    return sph_taylor_rest("sph-taylor-cu-rest-rr", "total", 1.005,
                           " time_integration: leapfrog, reference_update: {distortion: 1.2},",
                           scale, threads, out, err);
}

/* the _rest_lf bar with Balsara's switch on the AV (viscosity_switch:
 * balsara, sph_tlsph.c): the AV at [1, 1] turns 14-22 % of the impact
 * energy into heat instead of plastic work, and that is the bar's excess
 * length (docs/performance.md, "Taylor bar accuracy") */
static int bench_sph_taylor_rest_bal(int threads, double scale, struct bench_result *out,
                                     struct spall_error *err)
{
    return sph_taylor_rest("sph-taylor-cu-rest-bal", "total", 1.005,
                           " time_integration: leapfrog, hourglass: 1.0, viscosity_switch: "
                           "balsara,",
                           scale, threads, out, err);
}

/* the _rest_bal bar with re-referencing (distortion 1.2): below dx = 0.4 mm
 * the fixed reference inverts at the impact face's axis (det F <= 0 at
 * 18-27 us for dx = 0.3 and 0.25 mm, with or without the switch) */
static int bench_sph_taylor_rest_rrbal(int threads, double scale, struct bench_result *out,
                                       struct spall_error *err)
{
    return sph_taylor_rest("sph-taylor-cu-rest-rrbal", "total", 1.005,
                           " time_integration: leapfrog, hourglass: 1.0, viscosity_switch: "
                           "balsara, reference_update: {distortion: 1.2},",
                           scale, threads, out, err);
}

/* throughput of the configuration the race's accuracy half reports
 * (sph-taylor-cu-rest-bal: leapfrog, hourglass 1, Balsara's switch),
 * 200 steps: what the accurate bar costs per particle-step */
static int bench_sph_taylor_tl_bal(int threads, double scale, struct bench_result *out,
                                   struct spall_error *err)
{
    return sph_taylor_case("sph-taylor-cu-tl-bal", "total", 1.005, 1.0, 1.0,
                           " time_integration: leapfrog, hourglass: 1.0, viscosity_switch: "
                           "balsara,",
                           threads, scale, out, err);
}

/* the same count with the updated form (its list carries the 20 % skin) */
static int bench_sph_taylor_ul32(int threads, double scale, struct bench_result *out,
                                 struct spall_error *err)
{
    return sph_taylor_case("sph-taylor-cu-ul32", "updated", 1.005, 1.0, 1.0, "", threads, scale,
                           out, err);
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
             "run: {steps: %ld, max_particles: 1e9}\n",
             dx, 0.5 * dx, 0.5 * dx, steps);
    double nb_share = 0.0;
    size_t builds = 0;
    double t_setup = 0.0, cpu = 0.0;
    int rc = sph_bench_run("sph-rings-2d", yaml, threads, false, out, &nb_share, &builds,
                           &t_setup, NULL, &cpu, NULL, err);
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
    {"sph-taylor-cu", "3D copper Taylor bar (LAMMPS race), dx = 0.4 mm, 200 steps",
     bench_sph_taylor},
    {"sph-taylor-cu-tl", "3D copper Taylor bar, total-Lagrangian, support 2.01 dx (32 neighbours, "
     "the MACHDYN count), 200 steps", bench_sph_taylor_tl},
    {"sph-taylor-cu-tl-split", "sph-taylor-cu-tl with the TLSPH stages one after the other "
     "(sph_set_split_loops), not pipelined", bench_sph_taylor_tl_split},
    {"sph-taylor-cu-rest", "the sph-taylor-cu-tl bar run to rest (80 us): final length and "
     "radius", bench_sph_taylor_rest},
    {"sph-taylor-cu-rest-lf", "the sph-taylor-cu-rest bar, leapfrog (plain dt limit), hourglass 1",
     bench_sph_taylor_rest_lf},
    {"sph-taylor-cu-rest-rr", "the sph-taylor-cu-rest-lf bar, hourglass 0.1, reference updated "
     "when the distortion passes 1.2", bench_sph_taylor_rest_rr},
    {"sph-taylor-cu-rest-bal", "the sph-taylor-cu-rest-lf bar with Balsara's switch on the "
     "artificial viscosity", bench_sph_taylor_rest_bal},
    {"sph-taylor-cu-rest-rrbal", "the sph-taylor-cu-rest-bal bar with the reference updated "
     "when the distortion passes 1.2", bench_sph_taylor_rest_rrbal},
    {"sph-taylor-cu-tl-bal", "sph-taylor-cu-tl in the accurate bar's settings (leapfrog, "
     "hourglass 1, Balsara's switch), 200 steps", bench_sph_taylor_tl_bal},
    {"sph-taylor-cu-rest-ul32", "the sph-taylor-cu-ul32 bar run to rest (80 us)",
     bench_sph_taylor_rest_ul},
    {"sph-taylor-cu-rest-ul", "the sph-taylor-cu bar (updated form, h = 1.5 dx) run to rest "
     "(80 us)", bench_sph_taylor_rest_ul15},
    {"sph-taylor-cu-rest-ulbal", "the sph-taylor-cu-rest-ul bar with Balsara's switch",
     bench_sph_taylor_rest_ulbal},
    {"sph-taylor-cu-ul32", "3D copper Taylor bar, updated form, support 2.01 dx, 200 steps",
     bench_sph_taylor_ul32},
    {"sph-rings-2d", "2D rubber rings (Gray et al. 2001), artificial stress, dx = 0.5 mm, 200 steps",
     bench_sph_rings},
};
const size_t bench_sph_n_cases = sizeof bench_sph_cases / sizeof bench_sph_cases[0];
