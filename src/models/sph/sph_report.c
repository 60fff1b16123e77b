/**
 * @file sph_report.c
 * @brief What the SPH model reports about a run: energies, history columns,
 *        the set-up description and the interaction count used for the
 *        pair-steps/s of `spall bench`.  Read-only over the model's state.
 */
#include <stdint.h>
#include <stdio.h>

#include "models/sph/sph_internal.h"
#include "core/model.h"
#include "core/neighbor.h"
#include "core/exact_sum.h"
#include "core/parallel/comm.h"
#include "core/parallel/psum.h"
#include "core/particles.h"
#include "core/sim.h"

void sph_energy(const struct model *m, const struct sim *sim, struct model_energy *out)
{
    const struct particles *p = sim->p;
    /* exact sum: the same for any thread and rank count (docs/parallel.md) */
    struct xsum acc;
    xsum_init(&acc);
    for (size_t i = 0; i < p->n_owned; i++)
        xsum_add(&acc, p->mass[i] * m->e[i]);
    double ie;
    par_xsum_finish(sim, &acc, 1, &ie);
    /* internal energy (elastic + plastic + AV heat) is the model's store;
     * the plastic work inside it is reported in history (plastic_work) */
    out->strain = ie + m->wall.energy + m->ifs.energy;
    out->dissipated = 0.0;
}

size_t sph_history(const struct model *m, const struct sim *sim, const char **names,
                          double *values)
{
    const struct particles *p = sim->p;
    double wp, epmax = 0.0;
    uint64_t nf = 0;
    struct xsum acc;
    xsum_init(&acc);
    for (size_t i = 0; i < p->n_owned; i++) {
        xsum_add(&acc, m->wp[i]);
        nf += m->failed[i];
        if (m->ep[i] > epmax)
            epmax = m->ep[i];
    }
    par_xsum_finish(sim, &acc, 1, &wp);
    if (sim->par) { /* max and integer sums: exact in any order */
        nf = par_sum_u64(nf);
        epmax = par_max_double(epmax);
    }
    size_t k = 0;
    names[k] = "plastic_work";
    values[k++] = wp;
    names[k] = "failed_particles";
    values[k++] = (double)nf;
    names[k] = "max_plastic_strain";
    values[k++] = epmax;
    names[k] = "cspm_fallbacks";
    values[k++] = (double)m->cspm_fallbacks;
    names[k] = "neighbor_builds";
    values[k++] = (double)m->n_builds;
    names[k] = "wall_force";
    values[k++] = m->opt.bound.wall ? m->wall.force[0] * m->opt.bound.wall_normal[0] +
                                    m->wall.force[1] * m->opt.bound.wall_normal[1] +
                                    m->wall.force[2] * m->opt.bound.wall_normal[2]
                              : 0.0;
    if (m->opt.tl.total_lagrangian) {
        names[k] = "min_det_F";
        values[k++] = m->tl ? m->tl->jmin : 0.0; /* over all ranks (sph_tlsph.c) */
        names[k] = "max_F_distortion";
        values[k++] = m->tl ? m->tl->kmax : 0.0;
        if (m->opt.tl.reref_every || m->opt.tl.reref_distortion > 0.0) {
            names[k] = "reference_updates";
            values[k++] = m->tl ? (double)m->tl->rerefs : 0.0;
        }
    }
    if (m->opt.iface.kind != SPH_IFACE_NONE) {
        names[k] = "interface_pairs";
        values[k++] = (double)m->ifs.pairs;
        names[k] = "interface_energy [J]";
        values[k++] = m->ifs.energy;
    }
    if (m->opt.kern.plane == SPH_PLANE_AXISYMMETRIC)
        k += sph_axisym_history(m, sim, names + k, values + k);
    return k;
}

/* The material's EOS, yield, rate and failure laws with their constants, so
 * that run.log records every number the model uses. */
static size_t sph_describe_laws(const struct sph_material *mt, char *buf, size_t len)
{
    size_t off = 0;
#define ADD(...)                                                                                   \
    do {                                                                                           \
        if (off < len)                                                                             \
            off += (size_t)snprintf(buf + off, len - off, __VA_ARGS__);                            \
    } while (0)
    if (mt->eos == SPH_EOS_LINEAR)
        ADD("    eos: linear (p = K eta, eta = rho/rho0 - 1), rho0 = %.6g kg/m^3\n", mt->rho0);
    else
        ADD("    eos: Mie-Grueneisen%s, rho0 = %.6g kg/m^3, C = %.6g m/s, S = %.6g, Gamma = %.6g, "
            "P0 = %.6g Pa\n",
            mt->eos == SPH_EOS_MIE_GRUNEISEN_CK ? " (C_k polynomial form, no energy term)" : "", mt->rho0, mt->mg_c,
            mt->mg_s, mt->mg_gamma, mt->mg_p0);
    switch (mt->yield) {
    case SPH_YIELD_ELASTIC:
        ADD("    yield: none (elastic)\n");
        break;
    case SPH_YIELD_PERFECT:
        ADD("    yield: perfectly plastic, sigma_y = %.6g Pa\n", mt->sy);
        break;
    case SPH_YIELD_POWER:
        ADD("    yield: A + B ep^n, A = %.6g Pa, B = %.6g Pa, n = %.6g\n", mt->A, mt->B, mt->n);
        break;
    case SPH_YIELD_JOHNSON_COOK:
        ADD("    yield: Johnson-Cook, A = %.6g Pa, B = %.6g Pa, n = %.6g, C = %.6g, m = %.6g, "
            "T_melt = %.6g K, T_room = %.6g K, eps0_dot = %.6g 1/s, c_p = %.6g J/(kg K), "
            "Taylor-Quinney %.3g\n",
            mt->A, mt->B, mt->n, mt->jc_c, mt->jc_m, mt->Tm, mt->Troom, mt->eps0, mt->cp,
            mt->beta_tq);
        break;
    }
    if (mt->rate == SPH_RATE_COWPER_SYMONDS)
        ADD("    rate: Cowper-Symonds, D = %.6g 1/s, q = %.6g\n", mt->cs_d, mt->cs_q);
    if (mt->failure == SPH_FAIL_STRESS)
        ADD("    failure: stress %.6g Pa%s\n", mt->fail_value,
            mt->failed_tension ? " (failed particles keep EOS tension)" : "");
    else if (mt->failure == SPH_FAIL_PLASTIC_STRAIN)
        ADD("    failure: plastic strain %.6g%s\n", mt->fail_value,
            mt->failed_tension ? " (failed particles keep EOS tension)" : "");
#undef ADD
    return off < len ? off : len;
}

void sph_describe(const struct model *m, const struct sim *sim, char *buf, size_t len)
{
    static const char *const kn[] = {"", "cubic_spline", "gaussian", "quintic_spline",
                                     "wendland", "double_cosine", "hyperbolic"};
    size_t off = 0;
    off += (size_t)snprintf(buf + off, len - off,
                            "sph: kernel %s (alpha_%d = %.10g / h^%d), h = %.3g dx, "
                            "neighbour radius %.4g m\n",
                            kn[m->opt.kern.kernel], sim->dim, m->alpha, sim->dim,
                            m->opt.kern.h_factor, m->nl_radius);
    for (size_t k = 0; k < m->n_mat && off < len; k++) {
        const struct sph_material *mt = &m->mat[k];
        off += (size_t)snprintf(buf + off, len - off,
                                "  material %s: E = %.4g Pa, nu = %.4g, K = %.4g Pa, G = %.4g Pa, "
                                "c0 = %.5g m/s\n",
                                k < sim->n_materials ? sim->materials[k].name : "?", mt->E,
                                mt->nu, mt->K, mt->G, sph_sound_speed(mt, mt->rho0, 0.0));
        if (off < len)
            off += sph_describe_laws(mt, buf + off, len - off);
    }
    if (m->form && off < len)
        sph_forms_describe(m, sim, buf + off, len - off);
}

size_t sph_interactions(const struct model *m, const struct sim *sim)
{
    /* rows of real particles only (with symmetry planes the list also
     * holds the ghosts' rows, which are never used) */
    size_t pairs = sph_tlsph_pairs(m); /* TLSPH reference list */
    if (m->nl) {
        size_t n = sim->p->n_owned < m->nl->n ? sim->p->n_owned : m->nl->n;
        pairs += m->nl->offset[n];
    }
    return pairs / 2;
}
