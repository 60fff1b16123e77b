/**
 * @file vpar.c
 * @brief `spall validate` under mpirun (vpar.h).
 */
#include "validation/vpar.h"

#include "core/parallel/comm.h"
#include "core/parallel/decomp.h"
#include "core/parallel/gather.h"
#include "core/particles.h"
#include "core/sim.h"
#include "io/run_par.h"
#include "spall/error.h"
#include "validation/validation.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The cases that run distributed: their models run distributed
 * (docs/parallel.md) and their measurements read particles by global id
 * (vpar_at, vpar_gather, probes).  A case whose sims turn out to be refused
 * still runs correctly (serially, with the refusal as its note). */
static const char *const distributed_cases[] = {
    "lattice-chain-break", "lattice-waves",   "thermal-conduction", "thermal-expansion",
    "pd-waves",            "pd-bimaterial-bar", "pd-lps-waves",       "pd-branching",
    "pd-kalthoff",         "lattice-threads",   "impact-nylon",       "impact-vinylester",
    "sph-rings",           "impact-spall",      "macro-rod-elastic",  "macro-rod-large",
    "macro-rod-plastic",   "pen-sph-gelatin",   "pen-sph-gelatin-sweep", "pen-sph-gelatin-modulus",
    "pen-sph-gelatin-convergence", "pen-sph-gelatin-av", "pen-sph-sebs", "pen-sph-sebs-convergence",
    "sph-taylor-3d",
};

/* Why the other cases run on rank 0 alone, by name prefix (first match). */
static const struct {
    const char *prefix, *reason;
} serial_reasons[] = {
    /* the model runs distributed (or in part: SPH's total-Lagrangian form,
     * docs/parallel.md), the case's measurements do not yet */
    {"sph-", "its measurements read SPH particles by local index"},
    {"pen-", "no particle run (analytical models and data)"},
    {"macro-", "macro-particles run distributed, but the case's measurements read them by "
               "local index"},
    {"", "not adapted to a distributed run yet (it reads particle arrays, bonds or model "
         "state by local index)"},
};

const char *vpar_serial_reason(const char *name)
{
    for (size_t k = 0; k < sizeof distributed_cases / sizeof distributed_cases[0]; k++)
        if (strcmp(name, distributed_cases[k]) == 0)
            return NULL;
    size_t k = 0;
    while (strncmp(name, serial_reasons[k].prefix, strlen(serial_reasons[k].prefix)) != 0)
        k++;
    return serial_reasons[k].reason;
}

static void note_serial(struct vreport *r, const char *reason)
{
    if (r->par->noted)
        return;
    r->par->noted = true;
    if (par_rank() == 0 && r->log)
        fprintf(r->log, "  serial: %s\n", reason);
}

bool vpar_begin_case(struct vreport *r, const struct vcase *c)
{
    struct vpar *v = r->par;
    memset(v, 0, sizeof *v);
    const char *why = vpar_serial_reason(c->name);
    v->all_ranks = why == NULL;
    if (!v->all_ranks) {
        v->serial = true;
        note_serial(r, why);
    }
    return v->all_ranks || par_rank() == 0;
}

int vpar_distribute(struct vreport *r, struct sim *s, struct spall_error *err)
{
    struct vpar *v = r ? r->par : NULL; /* no report (a unit test): one rank */
    if (!v || v->serial) /* one rank, or the case continues serially on rank 0 */
        return SPALL_OK;
    char why[SPALL_ERROR_MSG_LEN];
    int rc = run_par_distribute_sim(s, why, sizeof why, err);
    if (rc || !why[0]) {
        v->distributed = v->distributed || !rc;
        return rc;
    }
    /* refused: the case goes on with this sim whole.  Before any sim of it
     * was distributed, rank 0 runs the rest alone (no collective is left
     * to pair with); afterwards the case may still step its distributed
     * sims, so every rank runs this one as one rank does. */
    char note[SPALL_ERROR_MSG_LEN + 64];
    snprintf(note, sizeof note, "%s%s", why,
             v->distributed ? " (this sim runs whole on every rank)" : "");
    note_serial(r, note);
    if (v->distributed)
        return SPALL_OK;
    v->serial = true;
    if (par_rank() == 0)
        return SPALL_OK;
    v->left = true;
    return spall_error_set(err, SPALL_ERR_INTERNAL, "rank %d leaves the serial case", par_rank());
}

double vpar_at(const struct sim *s, const double *local, int64_t gid)
{
    return par_value_at(s, local, gid);
}

void vpar_values(const struct sim *s, const double *local, const int64_t *gid, size_t k,
                 double *out)
{
    par_values_at(s, local, gid, k, out);
}

int vpar_gather(const struct sim *s, const double *local, double *global,
                struct spall_error *err)
{
    return par_gather_by_gid(s, local, global, err);
}

size_t vpar_n(const struct sim *s)
{
    return par_n_global(s);
}

double *vpar_whole(const struct sim *s, const double *local, struct spall_error *err)
{
    const size_t n = par_n_global(s);
    double *w = malloc((n ? n : 1) * sizeof *w);
    int rc = w ? SPALL_OK
               : spall_error_set(err, SPALL_ERR_NOMEM, "out of memory for %zu particle values", n);
    if (s->par)
        rc = par_agree(rc, err); /* every rank takes part in the gather, or none */
    if (!rc)
        rc = par_gather_by_gid(s, local, w, err);
    if (rc) {
        free(w);
        return NULL;
    }
    return w;
}

double vpar_probe_wave_speed(const struct sim *s, double v_behind)
{
    double uq[3], uh[3], v[3];
    run_probe(s, 0, uq, v);
    run_probe(s, 1, uh, v);
    double ta_q = s->t - uq[0] / v_behind;
    double ta_h = s->t - uh[0] / v_behind;
    return (vpar_at(s, s->p->x0[0], (int64_t)s->probes[1].particle) -
            vpar_at(s, s->p->x0[0], (int64_t)s->probes[0].particle)) /
           (ta_h - ta_q);
}
