/**
 * @file balance.c
 * @brief Measured imbalance and Zoltan repartitioning (migrate.h).
 *
 * A particle's work is 1 + its intact half-bonds: the force loop visits
 * every half-bond of the row (a broken one costs a distance test only)
 * plus the per-particle update.  As a body fragments and broken bonds
 * concentrate on some ranks, this estimate follows the cost, unlike the
 * bond count at set-up that weights the first partition.
 */
#include "core/parallel/migrate.h"
#include "core/parallel/spatial.h"
#include "core/parallel/decomp.h"
#include "core/parallel/decomp_internal.h"

#include "core/bond_list.h"
#include "core/model.h"
#include "core/parallel/comm.h"
#include "core/particles.h"
#include "core/sim.h"
#include "spall/error.h"

#include <stdlib.h>
#include <string.h>

#ifdef SPALL_HAVE_MPI
#include <mpi.h>
#include <zoltan.h>
#endif

static const struct bond_list *work_bonds(const struct sim *s)
{
    return s->ops->halo_bonds ? s->ops->halo_bonds(s->model)
           : s->ops->bonds    ? s->ops->bonds(s->model)
                              : NULL;
}

double par_imbalance(const struct sim *s)
{
    if (!s->par)
        return 1.0;
    const struct bond_list *bl = work_bonds(s);
    double w = 0.0;
    for (size_t i = 0; i < s->p->n_owned; i++)
        w += par_particle_work(bl, i, 1);
    /* integer-valued sums: exact in any order */
    uint64_t total = par_sum_u64((uint64_t)w);
    double mx = par_max_double(w);
    double mean = (double)total / (double)par_size();
    return mean > 0.0 ? mx / mean : 1.0;
}

void par_balance_stats(const struct sim *s, long *rebalances, unsigned long long *migrated)
{
    *rebalances = s->par ? s->par->rebalances : 0;
    *migrated = s->par ? s->par->migrated : 0;
}

long par_layouts(const struct sim *s)
{
    return s->par ? s->par->layouts : 0;
}

#ifdef SPALL_HAVE_MPI

void par_balance_free(struct par_decomp *d)
{
    struct Zoltan_Struct *zz = d->zz;
    if (zz)
        Zoltan_Destroy(&zz);
    d->zz = NULL;
}

/* A Zoltan RCB object kept for the run: with KEEP_CUTS and RCB_REUSE each
 * repartition starts from the previous cuts, so a small change of the
 * weights moves few particles. */
static struct Zoltan_Struct *balancer(struct par_decomp *d)
{
    if (d->zz)
        return d->zz;
    struct Zoltan_Struct *zz = par_zoltan_rcb(1);
    d->zz = zz;
    return zz;
}

int par_rcb_dest(struct Zoltan_Struct *zz, struct par_zobjs *z, int **dest, size_t *leaving,
                 struct spall_error *err)
{
    par_zoltan_queries(zz, z);
    int changes, ngid, nlid, nimp, nexp = 0;
    ZOLTAN_ID_PTR imp_g = NULL, imp_l = NULL, exp_g = NULL, exp_l = NULL;
    int *imp_p = NULL, *imp_parts = NULL, *exp_p = NULL, *exp_parts = NULL;
    int zrc = Zoltan_LB_Partition(zz, &changes, &ngid, &nlid, &nimp, &imp_g, &imp_l, &imp_p,
                                  &imp_parts, &nexp, &exp_g, &exp_l, &exp_p, &exp_parts);
    const size_t n = z->hi - z->lo;
    int rc = SPALL_OK;
    *dest = malloc((n ? n : 1) * sizeof **dest);
    if (zrc != ZOLTAN_OK)
        rc = spall_error_set(err, SPALL_ERR_INTERNAL, "Zoltan RCB repartition failed (%d)", zrc);
    else if (!*dest)
        rc = spall_error_set(err, SPALL_ERR_NOMEM, "out of memory rebalancing");
    if (!rc) {
        for (size_t i = 0; i < n; i++)
            (*dest)[i] = par_rank();
        for (int k = 0; k < nexp; k++)
            (*dest)[exp_l[k]] = exp_parts[k];
    }
    *leaving = rc ? 0 : (size_t)nexp;
    Zoltan_LB_Free_Part(&imp_g, &imp_l, &imp_p, &imp_parts);
    Zoltan_LB_Free_Part(&exp_g, &exp_l, &exp_p, &exp_parts);
    return rc;
}

int par_rebalance(struct sim *s, double *before, double *after, unsigned long long *moved,
                  struct spall_error *err)
{
    *moved = 0;
    *before = *after = par_imbalance(s);
    struct par_decomp *d = s->par;
    if (!d)
        return SPALL_OK;
    /* the owned particles at their current positions (the partition follows
     * the deformed body), weighted by 1 + intact half-bonds */
    struct par_zobjs z = {0, s->p->n_owned, s->p->gid, s->p->x, s->dim, work_bonds(s), 1};
    struct Zoltan_Struct *zz = balancer(d);
    int rc = zz ? SPALL_OK : spall_error_set(err, SPALL_ERR_INTERNAL, "Zoltan_Create failed");
    if ((rc = par_agree(rc, err)))
        return rc;
    int *dest = NULL;
    size_t leaving = 0;
    rc = par_rcb_dest(zz, &z, &dest, &leaving, err);
    if (!(rc = par_agree(rc, err)))
        rc = par_migrate(s, dest, moved, err);
    free(dest);
    if (!rc) /* a model on spatial ghosts: its ghosts around the new owned set */
        rc = par_spatial_init(s, err);
    if (rc)
        return rc;
    d->rebalances++;
    *after = par_imbalance(s);
    return SPALL_OK;
}

#else

void par_balance_free(struct par_decomp *d)
{
    (void)d;
}

int par_rebalance(struct sim *s, double *before, double *after, unsigned long long *moved,
                  struct spall_error *err)
{
    (void)s;
    (void)err;
    *before = *after = 1.0;
    *moved = 0;
    return SPALL_OK;
}

#endif
