/* examples/api/plate.c: drive a spall simulation from C through the public
 * API (include/spall/sim.h, include/spall/setup.h, docs/api.md).
 *
 *   plate [DECK | --calls] [OUT_DIR]
 *
 * Builds the simulation of DECK (default plate.yaml: an epoxy plate with a
 * hole pulled apart), or with --calls the same plate set up by C calls
 * without a deck (setup_plate below), advances it in ten equal intervals
 * of its end time,
 * printing the grip force, the energies and the largest fracture density
 * read from the field registry, and writes HDF5/XDMF frames into OUT_DIR
 * if given.  Exit status: 0, or the spall status of the failing call. */
#include <spall/setup.h>
#include <spall/sim.h>
#include <spall/spall.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int fail(const struct spall_error *err)
{
    fprintf(stderr, "plate: %s\n", err->msg);
    return err->code;
}

/* The plate of plate.yaml, key for key: a 20 mm x 40 mm epoxy plate with a
 * hole of radius 4 mm on a triangular lattice of spacing 0.5 mm, grips
 * moving apart at 5 m/s each after a 20 us ramp. */
static int setup_plate(struct spall_setup *s, struct spall_error *err)
{
    const struct spall_material epoxy = {.density = 1100,
                                         .youngs_modulus = 3.26e9,
                                         .poisson_ratio = 0.3333333333333333,
                                         .tensile_strength = 62.86e6};
    const double plate_min[2] = {0, 0}, plate_max[2] = {0.020, 0.040};
    const double center[2] = {0.010, 0.020};
    const double bottom_min[2] = {-1, -1}, bottom_max[2] = {1, 0.0015};
    const double top_min[2] = {-1, 0.0385}, top_max[2] = {1, 1};
    const double down[2] = {0, -5.0}, up[2] = {0, 5.0};
    const char *const fields[] = {"position", "velocity", "displacement", "fracture_density"};
    int rc = spall_setup_model(s, "lattice", err);
    if (!rc)
        rc = spall_setup_text(s, "model.law", "linear", err);
    if (!rc)
        rc = spall_setup_material(s, "epoxy", &epoxy, err);
    if (!rc)
        rc = spall_setup_lattice(s, "triangular", 0.5e-3, err);
    if (!rc)
        rc = spall_setup_box(s, "plate", 2, plate_min, plate_max, err);
    if (!rc)
        rc = spall_setup_circle(s, "hole", 2, center, 0.004, err);
    if (!rc)
        rc = spall_setup_difference(s, "specimen", "plate", "hole", err);
    if (!rc)
        rc = spall_setup_body(s, "specimen", "epoxy", err);
    if (!rc)
        rc = spall_setup_group_box(s, "bottom", 2, bottom_min, bottom_max, err);
    if (!rc)
        rc = spall_setup_group_box(s, "top", 2, top_min, top_max, err);
    if (!rc)
        rc = spall_setup_velocity_bc(s, "bottom", 2, down, 2.0e-5, err);
    if (!rc)
        rc = spall_setup_velocity_bc(s, "top", 2, up, 2.0e-5, err);
    if (!rc)
        rc = spall_setup_end_time(s, 1.5e-4, err);
    if (!rc)
        rc = spall_setup_number(s, "output.field_interval", 1.0e-5, err);
    if (!rc)
        rc = spall_setup_texts(s, "output.fields", fields, 4, err);
    return rc;
}

int main(int argc, char **argv)
{
    const char *deck = argc > 1 ? argv[1] : "plate.yaml";
    struct spall_error err = {0};
    struct spall_sim *sim = NULL;
    if (strcmp(deck, "--calls") == 0) {
        struct spall_setup *setup = NULL;
        int rc = spall_setup_create(&setup, &err);
        if (!rc)
            rc = setup_plate(setup, &err);
        if (!rc)
            rc = spall_sim_create_setup(&sim, setup, &err);
        spall_setup_destroy(&setup);
        if (rc)
            return fail(&err);
    } else if (spall_sim_create_file(&sim, deck, &err)) {
        return fail(&err);
    }

    struct spall_sim_info info;
    spall_sim_get_info(sim, &info);
    printf("libspall %s: %s model, %dD, %zu particles, %zu bonds, dt %.3g s, end %.3g s\n",
           spall_version(), info.model, info.dim, info.particles, info.interactions, info.dt,
           info.end_time);
    if (argc > 2 && spall_sim_output_open(sim, argv[2], true, &err)) {
        int rc = fail(&err);
        spall_sim_destroy(&sim);
        return rc;
    }

    struct spall_field_info damage;
    double *buf = NULL;
    int rc = spall_sim_field_info(sim, "fracture_density", &damage, &err);
    if (!rc) {
        buf = malloc(info.particles * (size_t)damage.ncomp * sizeof *buf);
        if (!buf)
            rc = spall_error_set(&err, SPALL_ERR_NOMEM, "out of memory");
    }
    printf("%10s %12s %12s %12s %12s\n", "time [s]", "F_top [N]", "kinetic [J]", "strain [J]",
           "max damage");
    for (int k = 1; k <= 10 && !rc; k++) {
        rc = spall_sim_run_to(sim, info.end_time * k / 10.0, &err);
        double force[3];
        if (!rc)
            rc = spall_sim_group_reaction(sim, "top", force, &err);
        if (!rc)
            rc = spall_sim_field_read(sim, "fracture_density", buf,
                                      info.particles * (size_t)damage.ncomp, &err);
        if (rc)
            break;
        double dmax = 0.0;
        for (size_t i = 0; i < info.particles; i++)
            dmax = buf[i] > dmax ? buf[i] : dmax;
        struct spall_energy e;
        spall_sim_energy(sim, &e);
        struct spall_sim_info now;
        spall_sim_get_info(sim, &now);
        printf("%10.4g %12.5g %12.5g %12.5g %12.4f\n", now.time, force[1], e.kinetic, e.strain,
               dmax);
    }
    if (!rc)
        printf("frames written: %zu\n", spall_sim_frames(sim));
    free(buf);
    spall_sim_destroy(&sim);
    return rc ? fail(&err) : 0;
}
