/**
 * @file sph_tlsph_ref.c
 * @brief Total-Lagrangian SPH: the reference configuration -- the fixed
 *        neighbour list, the pair constants, B0^-1 and the packed blocks
 *        (built at set-up and on a re-reference, sph_tlsph_reref.c) -- and
 *        the accessors.  The force sweep and the formulas: sph_tlsph.c.
 */
#include "models/sph/sph_tlsph_data.h"

#include "core/bond_list.h"
#include "core/neighbor.h"
#include "core/parallel/comm.h"
#include "core/particles.h"
#include "core/sim.h"
#include "spall/error.h"

#include <math.h>
#include <omp.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

static void sph_tl_destroy(struct sph_tl **tl)
{
    if (!tl || !*tl)
        return;
    struct sph_tl *t = *tl;
    neighbor_list_destroy(&t->nl);
    free(t->pk);
    free(t->pair);
    free(t->self);
    free(t->up);
    free(t->rown);
    free(t->prev);
    free(t->halo);
    free(t->rgid);
    free(t);
    *tl = NULL;
}

void sph_tlsph_destroy(struct sph_tlsph **tl)
{
    if (!tl || !*tl)
        return;
    sph_tl_destroy(&(*tl)->ref);
    bond_list_destroy(&(*tl)->halo);
    free(*tl);
    *tl = NULL;
}

static int sph_tl_alloc(struct sph_tl **out, size_t n, size_t np, struct spall_error *err)
{
    struct sph_tl *t = calloc(1, sizeof *t);
    int bad = !t;
    if (t) {
        const size_t nn = n ? n : 1, pp = np ? np : 1;
        bad |= !(t->pk = calloc(nn * TL_STRIDE, sizeof(double)));
        bad |= !(t->self = calloc(nn * TL_SELF, sizeof(double)));
        bad |= !(t->pair = calloc(pp, sizeof *t->pair));
        bad |= !(t->up = calloc(nn, sizeof *t->up));
    }
    *out = t;
    if (bad) {
        sph_tl_destroy(out);
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory (TLSPH pair constants)");
    }
    return SPALL_OK;
}

/* The reference configuration is an input: the deck's positions (p->x0)
 * and rest volumes at the start, the current ones on a re-reference
 * (sph_tlsph_reref.c).  p->x0 itself is never changed (output, groups). */
/* The hourglass constant of the pair in row a with partner b (the volumes
 * in the row's order: the constant need not be symmetric in its last bits). */
static inline double pair_hg(double kappa, double Ea, double Eb, double Va, double Vb, double W,
                             double r2)
{
    return kappa * 0.5 * (Ea + Eb) * Va * Vb * W / r2;
}

/* A distributed re-reference (sph_tlsph_reref.c): the rows are built over
 * the n local particles, the owned ones and every particle of other ranks
 * within the list radius (par_spatial_regather), in the serial order
 * (ascending gid); the ghosts' rows stay empty. */
int sph_tlsph_reference(struct model *m, struct sim *s, double *const Xr[3], const double *rho,
                        struct spall_error *err)
{
    struct particles *p = s->p;
    const size_t n = p->n, no = p->n_owned; /* serial: n = no */
    const int dim = m->dim;
    double hmax = 0.0;
    for (size_t i = 0; i < no; i++)
        hmax = fmax(hmax, m->h[i]);
    if (s->par)
        hmax = par_max_double(hmax);
    if (!m->tl && !(m->tl = calloc(1, sizeof *m->tl)))
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory (TLSPH state)");
    sph_tl_destroy(&m->tl->ref);
    const double radius = m->qmax * hmax;
    if (!m->nl) /* a mixed run's updated list keeps its own radius (with skin) */
        m->nl_radius = radius;
    const double t0 = omp_get_wtime();
    struct neighbor_list *nl = NULL;
    int rc = neighbor_list_build(&nl, dim, n, Xr, radius, err);
    if (!rc && s->par && sph_rows_by_gid(nl, no, n, p->gid))
        rc = spall_error_set(err, SPALL_ERR_NOMEM, "out of memory (TLSPH reference rows)");
    if (rc) {
        neighbor_list_destroy(&nl);
        return rc;
    }
    if (m->form || rho) {
        /* bodies split by formulation (sph_forms.c): only the pairs inside
         * one TLSPH body; the others' rows stay empty.  A re-reference (rho
         * given; h may have grown per particle, sph_tlsph_reref.c) also
         * drops the pairs beyond their support qmax (h_i + h_j)/2 (W = 0) */
        size_t w = 0, start = 0;
        for (size_t i = 0; i < n; i++) {
            const size_t end = nl->offset[i + 1];
            for (size_t k = start;
                 k < end && i < no && (!m->form || m->form[i] == SPH_FORM_TOTAL); k++) {
                const size_t j = (size_t)nl->idx[k];
                if (m->form && (m->form[j] != SPH_FORM_TOTAL || p->body[j] != p->body[i]))
                    continue;
                double r2 = 0.0, sup = 0.5 * m->qmax * (m->h[i] + m->h[j]);
                for (int d = 0; d < dim && rho; d++)
                    r2 += (Xr[d][i] - Xr[d][j]) * (Xr[d][i] - Xr[d][j]);
                if (!rho || r2 < sup * sup)
                    nl->idx[w++] = nl->idx[k];
            }
            start = end;
            nl->offset[i + 1] = w;
        }
    }
    m->t_neighbor += omp_get_wtime() - t0;
    m->n_builds++;
    const size_t *off = nl->offset;
    const int32_t *nb = nl->idx;
    if ((rc = sph_tl_alloc(&m->tl->ref, n, off[n], err))) {
        neighbor_list_destroy(&nl);
        return rc;
    }
    struct sph_tl *t = m->tl->ref;
    t->nl = nl;
    t->band = 0;
    if (s->par && !(t->prev = malloc((off[no] ? off[no] : 1) * sizeof *t->prev)))
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory (TLSPH reverse pairs)");
#ifdef TL_CLONED
    __builtin_cpu_init(); /* what the ifunc resolver of TL_CLONES checks */
    t->wide = __builtin_cpu_supports("x86-64-v3");
#endif
    for (size_t i = 0; i < n; i++) {
        /* rows are sorted ascending (neighbor.c): the upper part j > i,
         * the pairs stage 2 evaluates, starts at up[i] */
        size_t u = off[i];
        while (u < off[i + 1] && (size_t)nb[u] < i)
            u++;
        t->up[i] = u;
        for (size_t k = off[i]; k < off[i + 1]; k++) {
            const size_t j = (size_t)nb[k], d = j > i ? j - i : i - j;
            t->band = d > t->band ? d : t->band;
        }
        double *q = t->pk + i * TL_STRIDE;
        for (int c = 0; c < 9; c++)
            q[TL_FD + c] = (c % 4 == 0) ? 1.0 : 0.0;
        q[TL_VOL] = m->m2[i] / (rho ? rho[i] : m->mat[p->material[i]].rho0);
        q[TL_M] = m->m2[i];
        for (int d = 0; d < 3; d++)
            q[TL_X0 + d] = d < dim ? Xr[d][i] : 0.0;
    }
    const double kappa = m->opt.tl.hourglass;
    size_t fallbacks = 0;
#pragma omp parallel for schedule(static) reduction(+ : fallbacks)
    for (size_t i = 0; i < no; i++) {
        if (sph_skip(m, i, SPH_FORM_TOTAL))
            continue;
        const double Ei = m->mat[p->material[i]].E;
        double B[9] = {0};
        for (size_t k = off[i]; k < off[i + 1]; k++) {
            size_t j = (size_t)nb[k];
            double hb = 0.5 * (m->h[i] + m->h[j]), X[3] = {0, 0, 0}, r2 = 0.0;
            for (int d = 0; d < dim; d++) {
                X[d] = Xr[d][i] - Xr[d][j];
                r2 += X[d] * X[d];
            }
            double W, F;
            sph_kernel_eval(m->opt.kern.kernel, m->alpha, sqrt(r2), hb, pow(hb, dim), &W, &F);
            const double Vi = t->pk[i * TL_STRIDE + TL_VOL], V = t->pk[j * TL_STRIDE + TL_VOL];
            struct tl_pair *pr = &t->pair[k];
            const double Ej = m->mat[p->material[j]].E;
            pr->F = F;
            pr->hg = pair_hg(kappa, Ei, Ej, Vi, V, W, r2);
            /* distributed: the pair in j's row (the same F, W and r2: the
             * difference only changes sign, the mean h is commutative) */
            if (t->prev)
                t->prev[k] = (struct tl_pair){F, pair_hg(kappa, Ej, Ei, V, Vi, W, r2)};
            for (int a = 0; a < dim; a++)
                for (int b = 0; b < dim; b++)
                    B[a * 3 + b] += -X[a] * V * F * X[b];
        }
        double Bi[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1}, inv[9];
        if (fabs(sph_inverse(dim, B, inv)) > 1e-3)
            memcpy(Bi, inv, sizeof Bi);
        else
            fallbacks++;
        for (int c = 0; c < 9; c++)
            m->Bi[c][i] = t->self[i * TL_SELF + TL_BI + c] = Bi[c];
    }
    m->cspm_fallbacks += s->par ? par_sum_u64(fallbacks) : fallbacks; /* the whole body's */
    return s->par ? sph_tl_par_rows(m, s, err) : SPALL_OK;
}

int sph_tlsph_init(struct model *m, struct sim *s, struct spall_error *err)
{
    return sph_tlsph_reference(m, s, s->p->x0, NULL, err);
}

const struct sph_formulation sph_form_total = {
    .name = "total",
    .init = sph_tlsph_init,
    .rates = sph_tlsph_rates,
    .end_step = sph_tlsph_reref_step, /* model.reference_update */
};

size_t sph_tlsph_pairs(const struct model *m)
{
    const struct sph_tl *t = m->tl ? m->tl->ref : NULL;
    if (t && m->sim && m->sim->par) /* the whole body's (sph_localize.c) */
        return m->tl->pairs_all;
    return t && t->nl ? t->nl->offset[t->nl->n] : 0;
}

void sph_tlsph_deformation(const struct model *m, size_t i, double F[9])
{
    const double *fd = m->tl->ref->pk + i * TL_STRIDE + TL_FD; /* stored by columns */
    for (int c = 0; c < 9; c++)
        F[c] = fd[c % 3 * 3 + c / 3];
}
