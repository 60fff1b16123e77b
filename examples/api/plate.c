/* examples/api/plate.c: drive a spall simulation from C through the public
 * API (include/spall/sim.h, docs/api.md).
 *
 *   plate [DECK [OUT_DIR]]
 *
 * Builds the simulation of DECK (default plate.yaml: an epoxy plate with a
 * hole pulled apart), advances it in ten equal intervals of its end time,
 * printing the grip force, the energies and the largest fracture density
 * read from the field registry, and writes HDF5/XDMF frames into OUT_DIR
 * if given.  Exit status: 0, or the spall status of the failing call. */
#include <spall/sim.h>
#include <spall/spall.h>

#include <stdio.h>
#include <stdlib.h>

static int fail(const struct spall_error *err)
{
    fprintf(stderr, "plate: %s\n", err->msg);
    return err->code;
}

int main(int argc, char **argv)
{
    const char *deck = argc > 1 ? argv[1] : "plate.yaml";
    struct spall_error err = {0};
    struct spall_sim *sim = NULL;
    if (spall_sim_create_file(&sim, deck, &err))
        return fail(&err);

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
