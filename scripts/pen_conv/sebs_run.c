/* scratch driver (2026-12-02): one pen-sph-sebs shot at dx1 = d/N with the
 * case's target, shot and grid (validation/pen_sph_sebs.c) but the finest
 * spacing changed: the resolution check of docs/validation.md, pen-sph-sebs.
 * usage: sebs_run D_UM V0 E_MPA N */
#include "validation/pen_sph_setup.h"
#include "spall/error.h"
#include <stdio.h>
#include <stdlib.h>

int main(int argc, char **argv)
{
    if (argc != 5) {
        fprintf(stderr, "usage: sebs_run D_UM V0 E_MPA N\n");
        return 2;
    }
    const double d = atof(argv[1]) * 1e-6, v0 = atof(argv[2]), E = atof(argv[3]) * 1e6;
    const double N = atof(argv[4]);
    struct pen_sph_target t = pen_sph_target_sebs(E);
    struct pen_sph_shot s = {.d = d, .rho_p = 7800.0, .v0 = v0};
    struct pen_sph_grid g = {.dx1_d = 1.0 / N, .width = 1.0, .depth = 1.5, .t_end = 1.6e-6,
                             .cavity_depth = 0.0};
    struct pen_sph_outcome o;
    struct spall_error err = {0};
    if (pen_sph_setup_run(&t, &s, &g, &o, &err)) {
        fprintf(stderr, "sebs_run: %s\n", err.msg);
        return 1;
    }
    printf("d %.0f um v0 %.0f E %.0f MPa d/%g: %zu particles, P_max %.2f um at %.0f ns (%s), "
           "energy balance %.3g, %.1f s\n",
           d * 1e6, v0, E * 1e-6, N, o.n, o.pmax * 1e6, o.t_pmax * 1e9,
           o.at_rest ? "at rest" : "end time", o.balance, o.secs);
    pen_sph_outcome_free(&o);
    return 0;
}
