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
    out->h_factor = m->opt.h_factor;
    out->tl_rerefs = m->tl_rerefs;
    out->t_reref = m->t_reref;
    out->tl_hgrown = m->tl_hgrown;
    out->tl_jmin = m->tl_jmin;
    out->tl_kmax = m->tl_kmax;
    out->iface_pairs = m->iface_pairs;
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
    m->opt.cspm = on;
}

void sph_refresh_pressure(struct model *m, struct sim *s)
{
    sph_update_pressure(m, s, SPH_FORM_ALL);
}
