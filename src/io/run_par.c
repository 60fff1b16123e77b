/**
 * @file run_par.c
 * @brief Distributed pieces of `spall run` (run_par.h).
 */
#include "io/run_par.h"

#include "core/fields.h"
#include "core/fragments.h"
#include "core/model.h"
#include "core/parallel/comm.h"
#include "core/parallel/decomp.h"
#include "core/parallel/setup_dist.h"
#include "core/parallel/spatial.h"
#include "core/particles.h"
#include "core/rigid.h"
#include "core/sim.h"
#include "io/deck_build.h"
#include "io/run_balance.h"
#include "spall/error.h"
#include "spall/spall.h"

#include <stdio.h>

bool run_par_on(void)
{
    return par_size() > 1;
}

bool run_par_root(void)
{
    return par_rank() == 0;
}

int run_par_agree(int rc, struct spall_error *err)
{
    return run_par_on() ? par_agree(rc, err) : rc;
}

int run_par_setup(const struct sim *s, const struct run_output *ro, int rc,
                  struct spall_error *err)
{
    if (!run_par_on())
        return rc;
    if (!rc && s)
        rc = par_check_supported(s, err);
    for (size_t k = 0; !rc && s && ro && k < ro->n_fields; k++) {
        const struct field_desc *f = field_registry_find(s->fields, ro->fields[k]);
        if (f && (f->flags & FIELD_SERIAL))
            rc = spall_error_set_key(err, SPALL_ERR_INPUT, "output.fields",
                                     "distributed runs (%d MPI ranks): field '%s' is computed on "
                                     "one rank only; run without mpirun or leave it out",
                                     par_size(), f->name);
    }
    if (!rc && s)
        rc = run_balance_check(s, &ro->parallel, err);
    return par_agree(rc, err);
}

int run_par_setup_window(struct sim *s, int rc, struct spall_error *err)
{
    if (!run_par_on())
        return rc;
    rc = par_agree(rc, err); /* the window's set-up is collective from here */
    if (!rc && s->setup)
        rc = par_agree(par_setup_distribute(s, err), err);
    return rc;
}

int run_par_distribute(struct sim *s, FILE *log, struct spall_error *err)
{
    if (!run_par_on())
        return SPALL_OK;
    /* a distributed set-up is partitioned already (run_par_setup_window) */
    int rc = s->par ? SPALL_OK : par_distribute(s, err);
    if (!rc) /* impactors: contact rows of the owned particles */
        rc = par_agree(rigid_par_prepare(s, err), err);
    if (rc)
        return rc;
    char buf[8192] = "";
    par_describe(s, buf, sizeof buf);
    if (log && s->setup) /* the distributed set-up's blocks to the partition */
        fprintf(log, "setup_partition: blocks of layers (imbalance %.4g) -> Zoltan RCB (%.4g), "
                "%llu particles migrated\n", s->setup->imbalance[0], s->setup->imbalance[1],
                s->setup->moved);
    if (log) {
        fputs(buf, log);
        fflush(log);
    }
    return SPALL_OK;
}

int run_par_distribute_sim(struct sim *s, char *why, size_t len, struct spall_error *err)
{
    if (len)
        why[0] = '\0';
    if (!run_par_on())
        return SPALL_OK;
    struct spall_error refused = {0};
    if (par_check_supported(s, &refused)) { /* the same decision on every rank */
        snprintf(why, len, "%s", refused.msg);
        return SPALL_OK;
    }
    return run_par_distribute(s, NULL, err);
}

void run_probe(const struct sim *s, size_t k, double u[3], double v[3])
{
    if (s->par) {
        par_probe(s, k, u, v);
        return;
    }
    size_t i = s->probes[k].particle;
    for (int d = 0; d < 3; d++) {
        u[d] = d < s->dim ? s->p->x[d][i] - s->p->x0[d][i] : 0.0;
        v[d] = d < s->dim ? s->p->v[d][i] : 0.0;
    }
}

int run_fragments(struct fragments *f, const struct sim *s, struct spall_error *err)
{
    return s->par ? par_fragments(s, f, err) : fragments_of_sim(f, s, err);
}

void run_par_log_end(const struct sim *s, FILE *log)
{
    if (!s->par || !log)
        return;
    long calls = 0;
    double secs = 0.0;
    par_halo_stats(s, &calls, &secs);
    fprintf(log, "halo_exchanges: %ld (rank 0: %.3f s exchanging ghost positions)\n", calls, secs);
    if (s->ops->spatial_ghosts) /* docs/parallel.md: how often the neighbour search moved */
        fprintf(log, "spatial_ghost_rebuilds: %ld in %ld steps\n", par_spatial_rebuilds(s),
                s->step);
}
