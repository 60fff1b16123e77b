/**
 * @file test_restart.c
 * @brief Exact restart (issue 21): for every model and formulation, N steps
 *        uninterrupted vs a checkpoint at N/2 and a restart from it give
 *        bitwise the same final positions and velocities, the same final
 *        checkpoint (its checksum covers every particle field, bond state,
 *        damage, plastic history and counter) and the same history.csv and
 *        XDMF text.  The restart runs with another thread count than the
 *        first run, into another directory (a continued copy); the first
 *        case also continues in place.
 */
#define _POSIX_C_SOURCE 200809L
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>
#include <hdf5.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "io/output.h"
#include "spall/error.h"
#include "spall/spall.h"

struct restart_case {
    const char *label;
    const char *deck;  /**< everything but run and output */
    long steps;        /**< N (even) */
    const char *bonds; /**< state dataset of bond flags that must hold broken bonds, or NULL */
};

/* ---- decks ----------------------------------------------------------------- */

#define PLATE_2D                                                                                 \
    "lattice: {type: triangular, spacing: 1.0e-3}\n"                                             \
    "geometry:\n"                                                                                \
    "  plate: {box: {min: [0, 0], max: [0.02, 0.03]}}\n"                                         \
    "  hole: {circle: {center: [0.01, 0.015], radius: 0.003}}\n"                                 \
    "  specimen: {difference: [plate, hole]}\n"                                                  \
    "body: {geometry: specimen, material: m}\n"                                                  \
    "groups:\n"                                                                                  \
    "  bottom: {box: {min: [-1, -1], max: [1, 0.0015]}}\n"                                       \
    "  top: {box: {min: [-1, 0.0285], max: [1, 1]}}\n"                                           \
    "probes:\n"                                                                                  \
    "  - {name: centre, position: [0.005, 0.015]}\n"

#define PULL_2D                                                                                  \
    "boundary_conditions:\n"                                                                     \
    "  - {group: bottom, type: velocity, components: [x, y], value: [0, -20.0]}\n"               \
    "  - {group: top, type: velocity, components: [x, y], value: [0, 20.0]}\n"

#define SPH_ROD(MODEL_EXTRA, XSPH) SPH_ROD_OF("sph", MODEL_EXTRA, XSPH)
#define SPH_ROD_OF(TYPE, MODEL_EXTRA, XSPH)                                                     \
    "model:\n"                                                                                   \
    "  type: " TYPE "\n"                                                                         \
    "  kernel: wendland\n"                                                                       \
    "  h_factor: 1.5\n"                                                                          \
    "  viscosity: [1.0, 1.0]\n" XSPH MODEL_EXTRA                                                 \
    "  wall: {point: [0, 0], normal: [0, 1]}\n"                                                  \
    "materials:\n"                                                                               \
    "  iron: {density: 7850, youngs_modulus: 208.0e9, poisson_ratio: 0.3,\n"                     \
    "         eos: mie_gruneisen, sound_speed: 3630, hugoniot_slope: 1.80, gruneisen: 1.80,\n"   \
    "         yield: perfect, yield_stress: 600.0e6}\n"                                          \
    "lattice: {type: square, spacing: 2.38125e-4, origin: [1.190625e-4, 1.190625e-4]}\n"        \
    "body: {geometry: {box: {min: [0, 0], max: [0.00381, 0.008]}}, material: iron}\n"           \
    "initial_velocity: [{group: all, value: [0, -221.0]}]\n"

static const struct restart_case k_cases[] = {
    {"lattice-fracture",
     "model: {type: lattice, law: linear}\n"
     "materials:\n"
     "  m: {density: 1100, youngs_modulus: 3.26e9, poisson_ratio: 0.3333333333333333,\n"
     "      tensile_strength: 62.86e6}\n" PLATE_2D PULL_2D,
     400, "state/lattice.bond_state"},
    {"lattice-softening-thermal",
     "model: {type: lattice, law: softening}\n"
     "materials:\n"
     "  m: {density: 1100, youngs_modulus: 3.26e9, poisson_ratio: 0.3333333333333333,\n"
     "      tensile_strength: 40.0e6, failure_strain: 0.03, specific_heat: 1000,\n"
     "      conductivity: 50, thermal_expansion: 1.0e-4, power_density: 1.0e12,\n"
     "      melting_temperature: 600,\n"
     "      youngs_modulus_table: [[293.15, 3.26e9], [800, 1.0e9]]}\n" PLATE_2D PULL_2D,
     400, "state/lattice.bond_state"},
    {"pd-adr",
     "model: {type: peridynamics, variant: pdlm, quasi_static: adr}\n"
     "materials:\n"
     "  t700: {density: 1550, fiber_modulus: 130.0e9, transverse_modulus: 8.5e9,\n"
     "         shear_modulus: 4.5e9, major_poisson_ratio: 0.3, matrix_fracture_energy: 300,\n"
     "         mode2_fracture_energy: 800, fiber_fracture_energy: 60.0e3, fiber_angle: 0}\n"
     "lattice: {type: triangular, spacing: 1.0e-3, thickness: 1.0e-4}\n"
     "geometry:\n"
     "  p: {box: {min: [-0.0004, -0.0001], max: [0.0201, 0.0065]}}\n"
     "body: {geometry: p, material: t700}\n"
     "groups:\n"
     "  left: {box: {min: [-1, -1], max: [0.0006, 1]}}\n"
     "  right: {box: {min: [0.0191, -1], max: [1, 1]}}\n"
     "boundary_conditions:\n"
     "  - {group: left, type: fixed, components: [x, y]}\n"
     "  - {group: right, type: traction, components: [x], value: 400.0e6}\n"
     "probes:\n"
     "  - {name: end, position: [0.02, 0.003]}\n",
     300, NULL},
    {"pd-fracture",
     "model: {type: peridynamics}\n"
     "materials:\n"
     "  glass: {density: 2440, youngs_modulus: 72.0e9, fracture_energy: 3.8}\n"
     "lattice: {type: square, spacing: 5.0e-4, thickness: 1.0e-3}\n"
     "geometry:\n"
     "  plate: {box: {min: [-1.0e-5, -1.0e-5], max: [0.02001, 0.01001]}}\n"
     "body: {geometry: plate, material: glass}\n"
     "precracks:\n"
     "  - {from: [-0.001, 0.00525], to: [0.008, 0.00525]}\n"
     "groups:\n"
     "  top: {box: {min: [-1, 0.0089], max: [1, 1]}}\n"
     "  bottom: {box: {min: [-1, -1], max: [1, 0.0011]}}\n"
     "boundary_conditions:\n"
     "  - {group: top, type: velocity, components: [y], value: 2.0,\n"
     "     function: {type: linear_ramp, duration: 6.0e-6}}\n"
     "  - {group: bottom, type: velocity, components: [y], value: -2.0,\n"
     "     function: {type: linear_ramp, duration: 6.0e-6}}\n",
     300, "state/pd.bond_state"},
    {"pd-eps", /* the plastic extension state of formulation eps (pd.eps_plastic) */
     "model: {type: peridynamics, formulation: eps}\n"
     "materials:\n"
     "  m: {density: 1000, youngs_modulus: 1.0e9, poisson_ratio: 0.3, yield_stress: 5.0e6,\n"
     "      critical_stretch: 0.5}\n" PLATE_2D PULL_2D,
     300, NULL},
    {"macro-langevin-plastic",
     "model: {type: macroparticle, damping: pairwise, temperature: 300, eta_cg: 2000}\n"
     "materials:\n"
     "  al: {density: 2700, atomic_mass_u: 26.98, cohesive_energy_ev: 3.39, exponents: [4, 9],\n"
     "       debye_temperature: 428, yield_strain: 0.002}\n"
     "lattice: {type: fcc, spacing: 1.2374368670764582e-3}\n"
     "geometry:\n"
     "  rod: {box: {min: [0, 0, 0], max: [0.004, 0.004, 0.008]}}\n"
     "body: {geometry: rod, material: al}\n"
     "groups:\n"
     "  bottom: {box: {min: [-1, -1, -1], max: [1, 1, 3.0e-4]}}\n"
     "  top: {box: {min: [-1, -1, 0.0077], max: [1, 1, 1]}}\n"
     "boundary_conditions:\n"
     "  - {group: bottom, type: velocity, components: [z], value: -20}\n"
     "  - {group: top, type: velocity, components: [z], value: 20}\n",
     300, NULL},
    {"rigid-penalty",
     "model: {type: lattice, law: linear}\n"
     "materials:\n"
     "  m: {density: 1100, youngs_modulus: 3.26e9, poisson_ratio: 0.3333333333333333,\n"
     "      tensile_strength: 62.86e6}\n"
     "lattice: {type: triangular, spacing: 1.0e-3}\n"
     "geometry:\n"
     "  plate: {box: {min: [0, 0], max: [0.03, 0.006]}}\n"
     "body: {geometry: plate, material: m}\n"
     "impactors:\n"
     "  - {name: ball, shape: sphere, position: [0.015, 0.0105], radius: 0.004, mass: 0.05,\n"
     "     velocity: [0, -60], contact: penalty, friction: 0.3}\n"
     "  - {name: floor, shape: wall, position: [0, -0.0005], normal: [0, 1]}\n",
     400, "state/lattice.bond_state"},
    {"rigid-noslip",
     "model: {type: lattice, law: linear}\n"
     "materials:\n"
     "  m: {density: 1100, youngs_modulus: 3.26e9, poisson_ratio: 0.3333333333333333,\n"
     "      tensile_strength: 62.86e6}\n"
     "lattice: {type: triangular, spacing: 1.0e-3}\n"
     "geometry:\n"
     "  plate: {box: {min: [0, 0], max: [0.03, 0.006]}}\n"
     "body: {geometry: plate, material: m}\n"
     "groups:\n"
     "  base: {box: {min: [-1, -1], max: [1, 0.0005]}}\n"
     "boundary_conditions:\n"
     "  - {group: base, type: fixed, components: [x, y]}\n"
     "impactors:\n"
     "  - {name: tup, shape: round_nose, position: [0.015, 0.0062], radius: 0.003,\n"
     "     mass: 0.05, velocity: [0, -60], contact: no_slip}\n",
     400, "state/lattice.bond_state"},
    {"particle-contact",
     "model: {type: lattice, law: linear}\n"
     "materials:\n"
     "  m: {density: 1100, youngs_modulus: 3.26e9, poisson_ratio: 0.3333333333333333,\n"
     "      tensile_strength: 62.86e6}\n"
     "lattice: {type: triangular, spacing: 1.0e-3}\n"
     "geometry:\n"
     "  target: {box: {min: [0, 0], max: [0.03, 0.006]}}\n"
     "  flyer: {box: {min: [0.01, 0.0075], max: [0.02, 0.0115]}}\n"
     "bodies:\n"
     "  - {geometry: target, material: m}\n"
     "  - {geometry: flyer, material: m}\n"
     "groups:\n"
     "  flyer_g: {box: {min: [0.0095, 0.007], max: [0.0205, 0.012]}}\n"
     "initial_velocity:\n"
     "  - {group: flyer_g, value: [0, -150]}\n"
     "contact: {distance: 1.0e-3, stiffness: 3.26e6}\n",
     400, "state/lattice.bond_state"},
    {"sph-updated", SPH_ROD("", "  xsph: 0.1\n"), 300, NULL},
    {"sph-leapfrog-cspm",
     SPH_ROD("  time_integration: leapfrog\n  cspm: true\n  artificial_stress: 0.3\n",
             "  xsph: 0.1\n"),
     300, NULL},
    {"sph-interface-bodies",
     "model: {type: sph, kernel: wendland, h_factor: 1.5, viscosity: [1.0, 1.0],\n"
     "        interface: bodies}\n"
     "materials:\n"
     "  iron: {density: 7850, youngs_modulus: 208.0e9, poisson_ratio: 0.3,\n"
     "         eos: mie_gruneisen, sound_speed: 3630, hugoniot_slope: 1.80, gruneisen: 1.80,\n"
     "         yield: perfect, yield_stress: 600.0e6}\n"
     "lattice: {type: square, spacing: 2.5e-4, origin: [1.25e-4, 1.25e-4]}\n"
     "geometry:\n"
     "  target: {box: {min: [0, 0], max: [0.006, 0.002]}}\n"
     "  rod: {box: {min: [0.002, 0.00225], max: [0.004, 0.005]}}\n"
     "bodies:\n"
     "  - {geometry: target, material: iron}\n"
     "  - {geometry: rod, material: iron}\n"
     "groups:\n"
     "  rod_g: {box: {min: [0.0019, 0.0022], max: [0.0041, 0.0051]}}\n"
     "initial_velocity:\n"
     "  - {group: rod_g, value: [0, -300]}\n",
     300, NULL},
    {"sph-total",
     SPH_ROD_OF("tlsph", "  reference_update: {every: 70}\n", ""), 300, NULL},
    /* symmetry planes: the mirror ghosts and their list are rebuilt after
     * the load at the checkpoint's build positions (sph_symmetry_restore);
     * the half rod of plane x = 0, and a reduced 3D quarter Taylor bar
     * (examples/sph_taylor_3d: planes x = 0 and y = 0) whose list is
     * rebuilt twice after the checkpoint */
    {"sph-symmetry", SPH_ROD("  symmetry: x\n", "  xsph: 0.1\n"), 300, NULL},
    {"sph-symmetry-3d",
     "model:\n"
     "  type: sph\n"
     "  kernel: wendland\n"
     "  h_factor: 1.5\n"
     "  viscosity: [1.0, 1.0]\n"
     "  xsph: 0.1\n"
     "  symmetry: xy\n"
     "  wall: {point: [0, 0, 0], normal: [0, 0, 1]}\n"
     "materials:\n"
     "  iron: {density: 7850, youngs_modulus: 208.0e9, poisson_ratio: 0.3,\n"
     "         eos: mie_gruneisen, sound_speed: 3630, hugoniot_slope: 1.80, gruneisen: 1.80,\n"
     "         yield: perfect, yield_stress: 600.0e6}\n"
     "lattice: {type: sc, spacing: 2.38125e-4, origin: [1.190625e-4, 1.190625e-4, 1.190625e-4]}\n"
     "body: {geometry: {intersection: [{cylinder: {base: [0, 0, 0], top: [0, 0, 0.003],\n"
     "                                             radius: 0.0012}},\n"
     "                                 {box: {min: [0, 0, -1], max: [1, 1, 1]}}]},\n"
     "       material: iron}\n"
     "initial_velocity: [{group: all, value: [0, 0, -221.0]}]\n",
     200, NULL},
    /* more than SPALL_OMP_MIN_PARTICLES: the restart's one thread and the
     * first run's two threads both really run */
    {"lattice-threads",
     "model: {type: lattice, law: linear}\n"
     "materials:\n"
     "  m: {density: 1100, youngs_modulus: 3.26e9, poisson_ratio: 0.3333333333333333,\n"
     "      tensile_strength: 30.0e6}\n"
     "lattice: {type: triangular, spacing: 1.0e-3}\n"
     "geometry:\n"
     "  plate: {box: {min: [0, 0], max: [0.07, 0.07]}}\n"
     "  hole: {circle: {center: [0.035, 0.035], radius: 0.005}}\n"
     "  specimen: {difference: [plate, hole]}\n"
     "body: {geometry: specimen, material: m}\n"
     "groups:\n"
     "  bottom: {box: {min: [-1, -1], max: [1, 0.0015]}}\n"
     "  top: {box: {min: [-1, 0.0685], max: [1, 1]}}\n"
     "boundary_conditions:\n"
     "  - {group: bottom, type: velocity, components: [x, y], value: [0, -40.0]}\n"
     "  - {group: top, type: velocity, components: [x, y], value: [0, 40.0]}\n",
     120, NULL},
};

/* ---- helpers --------------------------------------------------------------- */

static char *slurp(const char *path, size_t *len)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    fseek(f, 0, SEEK_END);
    long n = ftell(f);
    fseek(f, 0, SEEK_SET);
    char *b = malloc((size_t)n + 1);
    if (b && fread(b, 1, (size_t)n, f) != (size_t)n) {
        free(b);
        b = NULL;
    }
    fclose(f);
    if (b) {
        b[n] = '\0';
        *len = (size_t)n;
    }
    return b;
}

static void assert_same_text(const char *a, const char *b)
{
    size_t la = 0, lb = 0;
    char *ta = slurp(a, &la), *tb = slurp(b, &lb);
    assert_non_null(ta);
    assert_non_null(tb);
    if (la != lb || memcmp(ta, tb, la) != 0)
        fail_msg("'%s' and '%s' differ (%zu and %zu bytes)", a, b, la, lb);
    free(ta);
    free(tb);
}

static void assert_same_field(const char *a, const char *b, const char *field)
{
    double *da = NULL, *db = NULL, ta = 0, tb = 0;
    size_t na = 0, nb = 0, ca = 0, cb = 0;
    struct spall_error err = {0};
    assert_int_equal(field_frame_read(a, field, &da, &na, &ca, &ta, &err), 0);
    assert_int_equal(field_frame_read(b, field, &db, &nb, &cb, &tb, &err), 0);
    assert_int_equal(na, nb);
    assert_int_equal(ca, cb);
    assert_memory_equal(&ta, &tb, sizeof ta);
    if (memcmp(da, db, na * ca * sizeof *da) != 0)
        fail_msg("%s of '%s' and '%s' differ", field, a, b);
    free(da);
    free(db);
}

static int64_t h5_i64(const char *path, const char *name)
{
    hid_t f = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
    assert_true(f >= 0);
    hid_t d = H5Dopen2(f, name, H5P_DEFAULT);
    assert_true(d >= 0);
    int64_t v = 0;
    assert_true(H5Dread(d, H5T_NATIVE_INT64, H5S_ALL, H5S_ALL, H5P_DEFAULT, &v) >= 0);
    H5Dclose(d);
    H5Fclose(f);
    return v;
}

/* Half-bonds flagged broken (bit 0) in @p name of checkpoint @p path. */
static size_t h5_broken(const char *path, const char *name)
{
    hid_t f = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
    assert_true(f >= 0);
    hid_t d = H5Dopen2(f, name, H5P_DEFAULT);
    assert_true(d >= 0);
    hid_t sp = H5Dget_space(d);
    hsize_t n = 0;
    H5Sget_simple_extent_dims(sp, &n, NULL);
    uint8_t *v = malloc(n ? n : 1);
    assert_non_null(v);
    assert_true(H5Dread(d, H5T_NATIVE_UINT8, H5S_ALL, H5S_ALL, H5P_DEFAULT, v) >= 0);
    size_t broken = 0;
    for (hsize_t k = 0; k < n; k++)
        broken += v[k] & 1u;
    free(v);
    H5Sclose(sp);
    H5Dclose(d);
    H5Fclose(f);
    return broken;
}

static void run_ok(const char *deck, const char *out, const char *restart, int threads)
{
    struct spall_run_options opt = {.deck_path = deck, .out_dir = out, .progress = 0,
                                    .threads = threads, .quiet = true, .restart = restart};
    struct spall_run_result res;
    struct spall_error err = {0};
    int rc = spall_run(&opt, &res, &err);
    if (rc)
        fail_msg("spall_run %s (restart %s): %s", deck, restart ? restart : "-", err.msg);
    assert_int_equal(res.signal, 0);
}

static void check_case(const struct restart_case *c)
{
    char tmp[] = "/tmp/spall_restart_XXXXXX";
    assert_non_null(mkdtemp(tmp));
    char deck[256], a[256], b[256], mid[320], end_a[320], end_b[320];
    snprintf(deck, sizeof deck, "%s/deck.yaml", tmp);
    FILE *f = fopen(deck, "w");
    assert_non_null(f);
    long n = c->steps, half = c->steps / 2;
    fprintf(f, "%srun: {steps: %ld}\noutput: {field_every: %ld, history_every: 7,\n"
               "         checkpoint: {every_steps: %ld, keep: 4}}\n",
            c->deck, n, n / 4, half);
    fclose(f);
    snprintf(a, sizeof a, "%s/a", tmp);
    snprintf(b, sizeof b, "%s/b", tmp);
    snprintf(mid, sizeof mid, "%s/checkpoint_%010ld.h5", a, half);
    run_ok(deck, a, NULL, 2);
    run_ok(deck, b, mid, 1); /* continued copy, another thread count */
    print_message("%s: restarted from step %ld of %ld\n", c->label, half, n);

    char pa[320], pb[320];
    snprintf(pa, sizeof pa, "%s/history.csv", a);
    snprintf(pb, sizeof pb, "%s/history.csv", b);
    assert_same_text(pa, pb);
    snprintf(pa, sizeof pa, "%s/fields.xdmf", a);
    snprintf(pb, sizeof pb, "%s/fields.xdmf", b);
    assert_same_text(pa, pb);
    snprintf(pa, sizeof pa, "%s/fields_000004.h5", a); /* the last frame, step N */
    snprintf(pb, sizeof pb, "%s/fields_000004.h5", b);
    assert_same_field(pa, pb, "position");
    assert_same_field(pa, pb, "velocity");
    snprintf(end_a, sizeof end_a, "%s/checkpoint_%010ld.h5", a, n);
    snprintf(end_b, sizeof end_b, "%s/checkpoint_%010ld.h5", b, n);
    /* the checksum covers every particle field and state slot */
    assert_true(h5_i64(end_a, "checksum") == h5_i64(end_b, "checksum"));
    if (c->bonds) { /* bonds broke after the checkpoint: the restart carried fracture on */
        size_t at_half = h5_broken(mid, c->bonds), at_end = h5_broken(end_b, c->bonds);
        print_message("%s: broken half-bonds %zu at the checkpoint, %zu at the end\n", c->label,
                      at_half, at_end);
        assert_true(at_end > at_half);
    }
    char cmd[600];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", tmp);
    assert_int_equal(system(cmd), 0);
}

static void test_restart_models(void **state)
{
    (void)state;
    for (size_t k = 0; k < sizeof k_cases / sizeof k_cases[0]; k++)
        check_case(&k_cases[k]);
}

/* Continuing in the run's own directory (no -o): history.csv is cut back to
 * the checkpoint's row and continued, frames renumber from the checkpoint. */
static void test_restart_in_place(void **state)
{
    (void)state;
    char tmp[] = "/tmp/spall_restart_XXXXXX";
    assert_non_null(mkdtemp(tmp));
    char deck[256], a[256], c[256], mid[320], pa[320], pc[320];
    snprintf(deck, sizeof deck, "%s/deck.yaml", tmp);
    FILE *f = fopen(deck, "w");
    assert_non_null(f);
    fprintf(f, "%srun: {steps: 200}\noutput: {field_every: 25, history_every: 3,\n"
               "         checkpoint: {every_steps: 60, keep: 2}}\n",
            k_cases[0].deck);
    fclose(f);
    snprintf(a, sizeof a, "%s/a", tmp);
    snprintf(c, sizeof c, "%s/c", tmp);
    run_ok(deck, a, NULL, 2);
    run_ok(deck, c, NULL, 2);
    /* keep: 2 leaves the checkpoints of steps 180 and 120 */
    snprintf(mid, sizeof mid, "%s/checkpoint_%010d.h5", c, 60);
    assert_int_equal(access(mid, F_OK), -1);
    snprintf(mid, sizeof mid, "%s/checkpoint_%010d.h5", c, 120);
    assert_int_equal(access(mid, F_OK), 0);
    run_ok(deck, NULL, mid, 1);
    snprintf(pa, sizeof pa, "%s/history.csv", a);
    snprintf(pc, sizeof pc, "%s/history.csv", c);
    assert_same_text(pa, pc);
    snprintf(pa, sizeof pa, "%s/fields.xdmf", a);
    snprintf(pc, sizeof pc, "%s/fields.xdmf", c);
    assert_same_text(pa, pc);
    snprintf(pa, sizeof pa, "%s/fields_000008.h5", a);
    snprintf(pc, sizeof pc, "%s/fields_000008.h5", c);
    assert_same_field(pa, pc, "position");
    assert_same_field(pa, pc, "velocity");
    /* run.log records the restart */
    snprintf(pc, sizeof pc, "%s/run.log", c);
    size_t len = 0;
    char *log = slurp(pc, &len);
    assert_non_null(log);
    assert_non_null(strstr(log, "restart_from: "));
    assert_non_null(strstr(log, "restart_step: 120"));
    free(log);
    char cmd[600];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", tmp);
    assert_int_equal(system(cmd), 0);
}

/* every_time: checkpoints at simulated times; --restart RUN_DIR continues
 * from the newest, and the result equals a run that wrote no checkpoint. */
static void test_restart_every_time(void **state)
{
    (void)state;
    char tmp[] = "/tmp/spall_restart_XXXXXX";
    assert_non_null(mkdtemp(tmp));
    char plain[256], ckd[256], a[256], b[256], pa[320], pb[320];
    snprintf(plain, sizeof plain, "%s/plain.yaml", tmp);
    snprintf(ckd, sizeof ckd, "%s/ckpt.yaml", tmp);
    FILE *f = fopen(plain, "w");
    assert_non_null(f);
    fprintf(f, "%srun: {end_time: 3.0e-5}\noutput: {field_interval: 1.0e-5, history_every: 5}\n",
            k_cases[0].deck);
    fclose(f);
    f = fopen(ckd, "w");
    assert_non_null(f);
    fprintf(f, "%srun: {end_time: 2.0e-5}\noutput: {field_interval: 1.0e-5, history_every: 5,\n"
               "  checkpoint: {every_time: 0.7e-5, keep: 1}}\n",
            k_cases[0].deck);
    fclose(f);
    snprintf(a, sizeof a, "%s/a", tmp);
    snprintf(b, sizeof b, "%s/b", tmp);
    run_ok(plain, a, NULL, 2);
    run_ok(ckd, b, NULL, 2); /* stops at 2e-5 ... */
    /* ... and is continued to 3e-5: the checkpoint and output keys may change */
    run_ok(plain, NULL, b, 1);
    snprintf(pa, sizeof pa, "%s/history.csv", a);
    snprintf(pb, sizeof pb, "%s/history.csv", b);
    assert_same_text(pa, pb);
    snprintf(pa, sizeof pa, "%s/fields.xdmf", a);
    snprintf(pb, sizeof pb, "%s/fields.xdmf", b);
    assert_same_text(pa, pb);
    snprintf(pa, sizeof pa, "%s/fields_000003.h5", a);
    snprintf(pb, sizeof pb, "%s/fields_000003.h5", b);
    assert_same_field(pa, pb, "position");
    assert_same_field(pa, pb, "velocity");
    char cmd[600];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", tmp);
    assert_int_equal(system(cmd), 0);
}

/* A checkpoint of a newer format is refused, naming both versions, before
 * anything is written. */
static void test_restart_newer_format(void **state)
{
    (void)state;
    char tmp[] = "/tmp/spall_restart_XXXXXX";
    assert_non_null(mkdtemp(tmp));
    char deck[256], a[256], b[256], ck[320];
    snprintf(deck, sizeof deck, "%s/deck.yaml", tmp);
    FILE *f = fopen(deck, "w");
    assert_non_null(f);
    fprintf(f, "%srun: {steps: 20}\noutput: {checkpoint: {every_steps: 10}}\n", k_cases[0].deck);
    fclose(f);
    snprintf(a, sizeof a, "%s/a", tmp);
    snprintf(b, sizeof b, "%s/b", tmp);
    run_ok(deck, a, NULL, 1);
    snprintf(ck, sizeof ck, "%s/checkpoint_%010d.h5", a, 10);
    hid_t h = H5Fopen(ck, H5F_ACC_RDWR, H5P_DEFAULT);
    assert_true(h >= 0);
    hid_t d = H5Dopen2(h, "version", H5P_DEFAULT);
    int64_t v = 2;
    assert_true(H5Dwrite(d, H5T_NATIVE_INT64, H5S_ALL, H5S_ALL, H5P_DEFAULT, &v) >= 0);
    H5Dclose(d);
    H5Fclose(h);
    struct spall_run_options opt = {.deck_path = deck, .out_dir = b, .progress = 0,
                                    .quiet = true, .restart = ck};
    struct spall_run_result res;
    struct spall_error err = {0};
    assert_int_equal(spall_run(&opt, &res, &err), SPALL_ERR_INPUT);
    print_message("refused: %s\n", err.msg);
    assert_non_null(strstr(err.msg, "format version 2, this spall reads versions 1 to 1"));
    assert_int_equal(access(b, F_OK), -1);
    char cmd[600];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", tmp);
    assert_int_equal(system(cmd), 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_restart_newer_format),
        cmocka_unit_test(test_restart_every_time),
        cmocka_unit_test(test_restart_in_place),
        cmocka_unit_test(test_restart_models),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
