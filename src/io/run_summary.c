/**
 * @file run_summary.c
 * @brief The summary of a built simulation (run_summary.h).  `spall
 *        calibrate DECK.yaml` prints the same lines the run log starts with,
 *        from the same builder, so the time step and constants it shows are
 *        the run's, not a re-derivation that could drift from it.
 */
#include "io/run_summary.h"

#include "core/lattice_gen.h"
#include "core/model.h"
#include "core/parallel/decomp.h"
#include "core/particles.h"
#include "core/sim.h"
#include "io/deck.h"
#include "io/deck_build.h"
#include "io/setup_check.h"

#include <stdbool.h>
#include <string.h>

void run_summary_write(FILE *f, const struct sim *s)
{
    /* the whole body's counts (a distributed set-up is partitioned here) */
    fprintf(f, "model: %s\ndimension: %d\nparticles: %zu\n", s->ops->name, s->dim,
            s->par ? par_n_global(s) : s->p->n);
    if (s->ops->interactions)
        fprintf(f, "interactions: %zu\n",
                par_interactions_global(s, s->ops->interactions(s->model, s)));
    fprintf(f, "lattice: %s, spacing %.6g m", lattice_kind_name(s->lattice.kind),
            s->lattice.spacing);
    /* 3D has no thickness; 1D a cross-section; the defaults are deck_build's */
    const bool tri = s->lattice.kind == LATTICE_TRIANGULAR ||
                     s->lattice.kind == LATTICE_TRIPLE_HONEYCOMB;
    if (s->dim == 1)
        fprintf(f, ", cross-section %.6g m^2%s", s->thickness,
                s->thickness_given ? "" : " (default: r0^2)");
    else if (s->dim == 2)
        fprintf(f, ", thickness %.6g m%s", s->thickness,
                s->thickness_given ? ""
                : tri              ? " (default: 2 r0/sqrt(3), volume r0^3 per particle)"
                                   : " (default: r0)");
    fprintf(f, "\n");
    fprintf(f, "materials:");
    for (size_t k = 0; k < s->n_materials; k++)
        fprintf(f, "%s %s (index %zu, density %.6g kg/m^3)", k ? "," : "",
                s->materials[k].name, k, s->materials[k].density);
    fprintf(f, "\nprecut_bonds: %zu\n", s->n_precut);
    /* steps: with an adaptive dt only an estimate; a fixed-dt run takes one
     * more per frame time inside a step (run.log's steps_done is the count) */
    fprintf(f, "dt: %.6g s (stability limit %.6g s, factor %.3g)\nsteps: %ld%s\nend_time: %.6g s\n",
            s->dt, s->dt_limit, s->dt / s->dt_limit, s->n_steps,
            s->adaptive_dt ? " (estimate: adaptive dt; steps_done at the end)" : "",
            s->end_time);
    if (s->ops->describe) {
        char buf[4096] = "";
        s->ops->describe(s->model, s, buf, sizeof buf);
        fprintf(f, "model_constants: |\n");
        for (char *line = strtok(buf, "\n"); line; line = strtok(NULL, "\n"))
            fprintf(f, "  %s\n", line);
    }
}

int run_summary_of_deck(const char *name, const char *text, FILE *out, struct spall_error *err)
{
    struct deck *d = NULL;
    struct sim *s = NULL;
    struct run_output ro;
    int rc = text ? deck_load_string(&d, name, text, err) : deck_load_file(&d, name, err);
    if (rc)
        return rc;
    if (!(rc = setup_check_units(d, err)) && !(rc = deck_build_sim(d, &s, &ro, err))) {
        fprintf(out, "# the simulation as `spall run` builds it (nothing run or written)\n"
                     "deck: %s\ntitle: %s\n",
                name, ro.title);
        run_summary_write(out, s);
    }
    sim_destroy(&s);
    deck_destroy(&d);
    return rc;
}
