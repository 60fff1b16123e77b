/**
 * @file run_balance.c
 * @brief Rebalancing during `spall run` (run_balance.h).
 */
#include "io/run_balance.h"

#include "core/model.h"
#include "core/options.h"
#include "core/parallel/comm.h"
#include "core/sim.h"
#include "spall/error.h"

#include <errno.h>
#include <math.h>
#include <string.h>

int run_balance_parse(const struct deck_node *root, struct par_balance_opts *o,
                      struct spall_error *err)
{
    static const char *const keys[] = {"rebalance_every", "imbalance_threshold", "setup", NULL};
    static const char *const setups[] = {"distributed", "replicated", NULL};
    int setup = 0; /* read again by io/deck_setup_dist.c, which decides */
    o->rebalance_every = 0;
    o->imbalance_threshold = 1.1;
    const struct deck_node *m = deck_get(root, "parallel");
    if (!m)
        return SPALL_OK;
    int rc;
    if ((rc = deck_expect_map(m, "the parallel mapping", err)) ||
        (rc = deck_long(m, "rebalance_every", false, 0, 2000000000L, &o->rebalance_every, err)) ||
        (rc = deck_double(m, "imbalance_threshold", false, 1.0, INFINITY,
                          &o->imbalance_threshold, err)) ||
        (rc = deck_enum(m, "setup", false, setups, &setup, err)) ||
        (rc = deck_check_unused(m, "parallel", keys, err)))
        return rc;
    return SPALL_OK;
}

int run_balance_check(const struct sim *s, const struct par_balance_opts *o,
                      struct spall_error *err)
{
    if (o->rebalance_every <= 0)
        return SPALL_OK;
    if (!s->ops->migrate_arrays)
        return spall_error_set_key(err, SPALL_ERR_INPUT, "parallel.rebalance_every",
                                   "distributed runs: model '%s' cannot migrate particles; "
                                   "leave parallel.rebalance_every at 0",
                                   s->ops->name);
    /* do the model's options allow it (the thermal lattice does not)? */
    struct par_model_arrays probe;
    memset(&probe, 0, sizeof probe);
    return s->ops->migrate_arrays(s->model, &probe, err);
}

static void csv_row(struct run_balance *b, const struct sim *s, double imb)
{
    if (b->csv) {
        fprintf(b->csv, "%ld,%.9g,%.6f\n", s->step, s->t, imb);
        fflush(b->csv);
    }
}

int run_balance_begin(struct run_balance *b, const struct sim *s,
                      const struct par_balance_opts *o, const char *dir,
                      struct spall_error *err)
{
    memset(b, 0, sizeof *b);
    b->opt = *o;
    if (!s->par)
        return SPALL_OK;
    int rc = run_balance_check(s, o, err); /* run_par_setup asked already */
    char path[1200];
    snprintf(path, sizeof path, "%s/balance.csv", dir);
    if (!rc && par_rank() == 0) {
        if (!(b->csv = fopen(path, "w")))
            rc = spall_error_set(err, SPALL_ERR_IO, "cannot write '%s': %s", path,
                                 strerror(errno));
        else
            fputs("step,time,imbalance\n", b->csv);
    }
    if ((rc = par_agree(rc, err)))
        return rc;
    double imb = par_imbalance(s);
    b->worst = imb;
    csv_row(b, s, imb);
    return SPALL_OK;
}

int run_balance_step(struct run_balance *b, struct sim *s, int history_row, FILE *log,
                     struct spall_error *err)
{
    if (!s->par)
        return SPALL_OK;
    if (b->opt.rebalance_every > 0 && s->step % b->opt.rebalance_every == 0) {
        double imb = par_imbalance(s);
        b->worst = fmax(b->worst, imb);
        if (imb >= b->opt.imbalance_threshold) {
            double before, after;
            unsigned long long moved;
            int rc = par_rebalance(s, &before, &after, &moved, err);
            if (rc)
                return rc;
            if (log)
                fprintf(log, "rebalance: step %ld, t = %.6g s, imbalance %.4f -> %.4f, %llu "
                             "particles migrated\n",
                        s->step, s->t, before, after, moved);
        }
    }
    if (history_row) {
        double imb = par_imbalance(s);
        b->worst = fmax(b->worst, imb);
        csv_row(b, s, imb);
    }
    return SPALL_OK;
}

void run_balance_end(struct run_balance *b, const struct sim *s, FILE *log)
{
    if (s && s->par) {
        long n = 0;
        unsigned long long moved = 0;
        par_balance_stats(s, &n, &moved);
        double imb = par_imbalance(s);
        if (log)
            fprintf(log, "rebalances: %ld (%llu particles migrated); imbalance (max/mean work "
                         "per rank) final %.4f, largest seen %.4f; per history row in "
                         "balance.csv\n",
                    n, moved, imb, fmax(b->worst, imb));
    }
    if (b->csv)
        fclose(b->csv);
    b->csv = NULL;
}
