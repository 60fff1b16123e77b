/**
 * @file pd_compact.c
 * @brief Compact families of the bond-based kernel: each half-bond keeps
 *        its partner, its state and a 16-bit row of a table of the distinct
 *        (reference length, coefficient, bond type) triples, instead of an
 *        8-byte length, an 8-byte coefficient and a type byte.  On a
 *        regular lattice of one material a family has a few distinct
 *        lengths, and every particle's rows repeat them: at delta = 3.015 dx
 *        in 3D the family storage falls from 22 to 7 bytes per half-bond.
 *        The table holds the very doubles the arrays would hold, so every
 *        result is bit for bit that of `bond_storage: full`.  The set-up
 *        builds the rows directly, one half-bond at a time, and never holds
 *        the arrays: its peak memory stays near the run's (issue 25 item
 *        2).  Formulations with more per-bond data (lps, eps) and
 *        orthotropic laminae (their calibration rebuilds the coefficients
 *        of a built model; the mixed-mode and fiber-plane rules) keep the
 *        arrays, as does a problem with more than 65 535 distinct triples
 *        (e.g. a surface-corrected irregular body).
 */
#include "models/peridynamics/pd_internal.h"

#include "core/bond_list.h"
#include "core/distinct.h"
#include "core/particles.h"
#include "core/sim.h"
#include "spall/error.h"

#include <stdlib.h>
#include <string.h>

#define PD_KIND_MAX 65535u

/* The key of a half-bond: the bit patterns of its reference length and
 * coefficient, then its type (17 bytes, compared as bytes). */

bool pd_compact_eligible(const struct model *m)
{
    return !m->opt.full_bonds && !m->opt.lps && !m->opt.eps && !m->ortho && !m->mixed &&
           !m->fresh && !m->twin && m->coef && m->bl->rest && m->bl->type;
}

bool pd_compact_predicted(const struct model *m)
{
    /* pd_compact_eligible before the model exists: no lamina (so no mixed
     * mode, fiber plane or fiber bonds), and the options */
    bool ortho = false;
    for (size_t k = 0; k < m->n_mat; k++)
        ortho |= m->mat[k].ortho;
    /* lps / eps: their table holds omega beta (pd_lps_init), which their
     * surface correction scales bond by bond: the arrays then */
    return !m->opt.full_bonds && !m->opt.fiber_plane && !ortho &&
           !(m->opt.lps && (m->lps.surface || m->lps.pals));
}

int pd_kinds_from_table(struct model *m, unsigned char *tab, size_t nk,
                        struct spall_error *err)
{
    double *k_rest = malloc((nk ? nk : 1) * sizeof *k_rest);
    double *k_coef = malloc((nk ? nk : 1) * sizeof *k_coef);
    uint8_t *k_type = malloc((nk ? nk : 1) * sizeof *k_type);
    if (!k_rest || !k_coef || !k_type) {
        free(tab);
        free(k_rest);
        free(k_coef);
        free(k_type);
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory for peridynamic bonds");
    }
    for (size_t q = 0; q < nk; q++) {
        const unsigned char *r = tab + q * PD_KIND_KEY;
        memcpy(&k_rest[q], r, sizeof k_rest[q]);
        memcpy(&k_coef[q], r + sizeof(double), sizeof k_coef[q]);
        k_type[q] = r[2 * sizeof(double)];
    }
    free(tab);
    m->k_rest = k_rest;
    m->k_coef = k_coef;
    m->k_type = k_type;
    m->n_kind = nk;
    return SPALL_OK;
}

int pd_compact_build(struct model *m, struct sim *sim, struct spall_error *err)
{
    struct bond_list *bl = m->bl;
    const struct particles *p = sim->p;
    const size_t n = bl->n, nh = bl->offset[n], nm = m->n_mat;
    double *g = NULL;
    struct distinct16 *d = NULL;
    int rc = pd_surface_factors(m, sim, &g, err);
    if (!rc)
        rc = distinct16_create(&d, PD_KIND_KEY, PD_KIND_MAX, err);
    uint16_t *kind = rc ? NULL : malloc((nh ? nh : 1) * sizeof *kind);
    if (!rc && !kind)
        rc = spall_error_set(err, SPALL_ERR_NOMEM, "out of memory for peridynamic bonds");
    /* The keys in slot order, each from the values pd_build_coefficients,
     * the bond types of pd_init (isotropic: no fiber bit) and
     * pd_interfaces_apply store in the arrays, so that every row holds the
     * doubles `bond_storage: full` uses. */
    bool fits = nh > 0; /* no bonds: the (empty) arrays, no table */
    for (size_t i = 0; !rc && i < n && fits; i++)
        for (size_t s = bl->offset[i]; s < bl->offset[i + 1] && fits; s++) {
            const size_t j = (size_t)bl->partner[s];
            const uint8_t type = (uint8_t)(((size_t)p->material[i] * nm +
                                            (size_t)p->material[j]) * 2);
            const double rest = bond_rest(bl, s);
            const double coef = pd_interface_scale(m, sim, type, pd_bond_coef(m, sim, g, i, s));
            unsigned char key[PD_KIND_KEY];
            memcpy(key, &rest, sizeof rest);
            memcpy(key + sizeof rest, &coef, sizeof coef);
            key[2 * sizeof(double)] = type;
            const int32_t row = distinct16_add(d, key);
            fits = row >= 0;
            kind[s] = (uint16_t)(fits ? row : 0);
        }
    free(g);
    size_t nk = 0;
    unsigned char *tab = (!rc && fits) ? distinct16_take_table(d, &nk) : NULL;
    distinct16_destroy(&d);
    if (rc) {
        free(kind);
        return rc;
    }
    if (!tab) { /* more than PD_KIND_MAX distinct triples: the arrays, as pd_init builds them */
        free(kind);
        if ((rc = bond_list_expand_rest(bl, err)))
            return rc;
        if (!(bl->type = calloc(nh ? nh : 1, sizeof *bl->type)))
            return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory for peridynamic bonds");
        return SPALL_OK;
    }
    if ((rc = pd_kinds_from_table(m, tab, nk, err))) {
        free(kind);
        return rc;
    }
    m->kind = kind;
    /* the compact family holds the lengths (k_rest): the list keeps none */
    bond_list_drop_rest(bl);
    return SPALL_OK;
}

size_t pd_model_bytes(const struct model *m, size_t n)
{
    const struct bond_list *bl = m->bl;
    const size_t nh = bl ? bl->offset[bl->n] : 0;
    size_t b = bl ? bond_list_bytes(bl) : 0;
    b += (m->coef ? nh * sizeof(double) : 0) + (m->kind ? nh * sizeof(uint16_t) : 0);
    b += m->n_kind * (2 * sizeof(double) + sizeof(uint8_t));
    b += n * (2 * sizeof(size_t) + sizeof(double)); /* n_init, n_init_f, diss */
    for (int d = 0; d < 3; d++)
        b += m->f_prev[d] ? 2 * n * sizeof(double) : 0;
    /* formulation lps / eps (pd_lps.h): per particle m, theta, alpha, the
     * dilatation coefficient and the surface factor (eps: theta, scale and
     * d k theta / m again for the partners); per half-bond omega beta and
     * eps' plastic extension, reverse slot (serial) or reverse copy
     * (distributed) */
    const struct pd_lps *L = &m->lps;
    b += ((L->wvol ? 4 * n : 0) + (L->afac ? n : 0) + (L->hs ? 3 * n : 0)) * sizeof(double);
    b += ((L->ob ? nh : 0) + (L->ep ? nh : 0) + (L->epr ? nh : 0)) * sizeof(double);
    b += (L->rloc ? nh * sizeof *L->rloc : 0) + (L->rloc8 ? nh : 0);
    return b;
}
