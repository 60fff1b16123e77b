/**
 * @file sph_access.c
 * @brief Read-only views of a built SPH model for callers above the model
 *        (sph.h): counters, per-particle kinematics, materials.
 */
#include "models/sph/sph_internal.h"

#include <string.h>

const struct sph_material *sph_material_get(const struct model *m, int k)
{
    return &m->mat[k];
}

void sph_stats_get(const struct model *m, struct sph_stats *out)
{
    memset(out, 0, sizeof *out);
    out->n_builds = m->n_builds;
    out->t_neighbor = m->t_neighbor;
    out->cspm_fallbacks = m->cspm_fallbacks;
    out->h_factor = m->opt.kern.h_factor;
    if (m->tl) {
        out->tl_rerefs = m->tl->rerefs;
        out->t_reref = m->tl->t_reref;
        out->tl_hgrown = m->tl->hgrown;
        out->tl_jmin = m->tl->jmin;
        out->tl_kmax = m->tl->kmax;
    }
    out->iface_pairs = m->ifs.pairs;
    out->total_lagrangian = m->opt.tl.total_lagrangian;
    out->n_total = m->form ? m->n_total : 0;
    out->nl_radius = m->nl_radius;
    out->qmax = m->qmax;
    out->as_smooth = m->opt.visc.as_smooth;
}

double *sph_artificial_stress_data(struct model *m, int c)
{
    return m->R[c];
}

void sph_state_rates(const struct model *m, size_t i, double *drho, double dS[6])
{
    *drho = m->drho[i];
    for (int c = 0; c < 6; c++)
        dS[c] = m->dS[c][i];
}

double *sph_stress_rate_data(struct model *m, int c)
{
    return m->dS[c];
}

double sph_plastic_work(const struct model *m, size_t i)
{
    return m->wp[i];
}

const uint8_t *sph_formulations(const struct model *m)
{
    return m->form;
}

const struct neighbor_list *sph_neighbors(const struct model *m)
{
    return m->nl;
}

size_t sph_interface_partners(const struct model *m, size_t i, const int32_t **idx)
{
    if (!m->ifs.off) {
        *idx = NULL;
        return 0;
    }
    *idx = m->ifs.idx + m->ifs.off[i];
    return m->ifs.off[i + 1] - m->ifs.off[i];
}

double sph_smoothing_length(const struct model *m, size_t i)
{
    return m->h[i];
}

double sph_spacing(const struct model *m, size_t i)
{
    return m->dx[i];
}

void sph_velocity_gradient(const struct model *m, size_t i, double L[9])
{
    for (int c = 0; c < 9; c++)
        L[c] = m->L[c][i];
}

void sph_set_cspm(struct model *m, bool on)
{
    m->opt.kern.cspm = on;
}

void sph_set_split_loops(struct model *m)
{
    m->loops.split_pairs = true;
    m->loops.tl_split = true;
}

void sph_set_scalar_rows(struct model *m)
{
    m->loops.scalar_rows = true;
}

void sph_refresh_pressure(struct model *m, struct sim *s)
{
    sph_update_pressure(m, s, SPH_FORM_ALL);
}
