/**
 * @file sph_material.c
 * @brief Constitutive models of the SPH solid (seed 004 sec. 3.3):
 *        linear EOS, Mie-Grueneisen (Eqs. 3.24-3.27) and its C_k form
 *        (Eqs. 4.13-4.15), Jaumann-rate deviatoric stress (Eqs. 3.28-3.30),
 *        elastic / perfectly plastic / A + B ep^n (Eq. 4.12) / Johnson-Cook
 *        yield with von Mises radial return, and failure.
 */
#include "models/sph/sph_internal.h"

#include "core/particles.h"
#include "core/sim.h"

#include <math.h>

double sph_eos_pressure(const struct sph_material *mt, double rho, double e)
{
    double eta = rho / mt->rho0 - 1.0;
    switch (mt->eos) {
    case SPH_EOS_LINEAR:
        return mt->K * eta;
    case SPH_EOS_MIE_GRUNEISEN: {
        /* Eq. 3.27 */
        double a0 = mt->rho0 * mt->mg_c * mt->mg_c;
        double s1 = mt->mg_s - 1.0;
        double b0 = a0 * (1.0 + 2.0 * s1);
        double c0 = a0 * (2.0 * s1 + 3.0 * s1 * s1);
        /* Eq. 3.25; in tension the thesis prints a0 eta^3, which has no
         * tensile stiffness at all: the linear a0 eta is used instead */
        double ph = eta > 0.0 ? eta * (a0 + eta * (b0 + eta * c0)) : a0 * eta;
        return (1.0 - 0.5 * mt->mg_gamma * eta) * ph + mt->mg_gamma * rho * e; /* Eq. 3.24 */
    }
    case SPH_EOS_MIE_GRUNEISEN_CK: {
        /* Eqs. 4.13-4.15 (no energy term, as printed) */
        double c1 = mt->rho0 * mt->mg_c * mt->mg_c - 0.5 * mt->mg_gamma * mt->mg_p0;
        double c2 = (2.0 * mt->mg_s - 1.0) * c1;
        double c3 = (mt->mg_s - 1.0) * (3.0 * mt->mg_s - 1.0) * c1;
        if (eta > 0.0)
            return mt->mg_p0 + eta * (c1 + eta * (c2 + eta * c3));
        return mt->mg_p0 + c1 * eta;
    }
    }
    return 0.0;
}

double sph_sound_speed(const struct sph_material *mt, double rho, double e)
{
    double dpdrho;
    if (mt->eos == SPH_EOS_LINEAR) {
        dpdrho = mt->K / mt->rho0;
    } else {
        double d = 1e-6 * rho;
        dpdrho = (sph_eos_pressure(mt, rho + d, e) - sph_eos_pressure(mt, rho - d, e)) / (2.0 * d);
        if (!(dpdrho > 0.1 * mt->K / mt->rho0))
            dpdrho = 0.1 * mt->K / mt->rho0;
    }
    return sqrt(dpdrho + 4.0 * mt->G / (3.0 * rho));
}

double sph_rate_factor(const struct sph_material *mt, double epdot)
{
    /* Cowper-Symonds: sigma_y (1 + (epdot / D)^(1/q)); epdot is the
     * equivalent total deviatoric strain rate, as for the JC rate term */
    if (mt->rate != SPH_RATE_COWPER_SYMONDS || !(epdot > 0.0))
        return 1.0;
    return 1.0 + pow(epdot / mt->cs_d, 1.0 / mt->cs_q);
}

double sph_yield_stress(const struct sph_material *mt, double ep, double epdot, double T)
{
    switch (mt->yield) {
    case SPH_YIELD_ELASTIC:
        return INFINITY;
    case SPH_YIELD_PERFECT:
        return mt->sy * sph_rate_factor(mt, epdot);
    case SPH_YIELD_POWER: /* Eq. 4.12 */
        return (mt->A + mt->B * (ep > 0.0 ? pow(ep, mt->n) : 0.0)) * sph_rate_factor(mt, epdot);
    case SPH_YIELD_JOHNSON_COOK: {
        double base = mt->A + mt->B * (ep > 0.0 ? pow(ep, mt->n) : 0.0);
        double r = epdot / mt->eps0;
        double rate = 1.0 + (r > 1.0 ? mt->jc_c * log(r) : 0.0);
        double ts = (T - mt->Troom) / (mt->Tm - mt->Troom);
        double th = ts <= 0.0 ? 1.0 : ts >= 1.0 ? 0.0 : 1.0 - pow(ts, mt->jc_m);
        return base * rate * th;
    }
    }
    return INFINITY;
}

void sph_update_pressure_one(struct model *m, size_t i)
{
    const struct sph_material *mt = &m->mat[m->sim->p->material[i]];
    m->P[i] = sph_carried_pressure(mt, m->failed[i], sph_eos_pressure(mt, m->rho[i], m->e[i]));
    m->c[i] = sph_sound_speed(mt, m->rho[i], m->e[i]);
}

void sph_update_pressure(struct model *m, struct sim *s, int mine)
{
    const size_t n = s->p->n_owned;
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < n; i++)
        if (!sph_skip(m, i, mine))
            sph_update_pressure_one(m, i);
}

void sph_stress_rate(const struct model *m, size_t i, double *trD)
{
    const struct sph_material *mt = &m->mat[m->sim->p->material[i]];
    double L[3][3];
    for (int a = 0; a < 3; a++)
        for (int b = 0; b < 3; b++)
            L[a][b] = m->L[a * 3 + b][i];
    double D[3][3], W[3][3];
    for (int a = 0; a < 3; a++)
        for (int b = 0; b < 3; b++) {
            D[a][b] = 0.5 * (L[a][b] + L[b][a]);
            W[a][b] = 0.5 * (L[a][b] - L[b][a]);
        }
    const double G = mt->G;
    if (m->dim == 2 && m->opt.plane != SPH_PLANE_AXISYMMETRIC) { /* axisym: L[8] = v_r/r */
        if (m->opt.plane == SPH_PLANE_STRESS && !m->failed[i]) {
            /* sigma_zz stays 0: (K - 2G/3)(D_xx + D_yy + D_zz) + 2G D_zz = 0 */
            double lam = mt->K - 2.0 * G / 3.0;
            D[2][2] = -lam * (D[0][0] + D[1][1]) / (lam + 2.0 * G);
        } else {
            D[2][2] = 0.0;
        }
        m->L[8][i] = D[2][2];
    }
    double tr = D[0][0] + D[1][1] + D[2][2];
    *trD = tr;
    if (m->failed[i] || mt->G == 0.0) {
        for (int c = 0; c < 6; c++)
            m->dS[c][i] = 0.0;
        return;
    }
    double S[3][3];
    S[0][0] = m->S[SXX][i];
    S[1][1] = m->S[SYY][i];
    S[2][2] = m->S[SZZ][i];
    S[0][1] = S[1][0] = m->S[SXY][i];
    S[1][2] = S[2][1] = m->S[SYZ][i];
    S[0][2] = S[2][0] = m->S[SXZ][i];
    /* Jaumann rate (Eqs. 3.28-3.30): dS/dt = 2G D' + W S - S W */
    static const int ia[6] = {0, 1, 2, 0, 1, 0}, ib[6] = {0, 1, 2, 1, 2, 2};
    for (int c = 0; c < 6; c++) {
        int a = ia[c], b = ib[c];
        double r = 2.0 * G * (D[a][b] - (a == b ? tr / 3.0 : 0.0));
        for (int k = 0; k < 3; k++)
            r += W[a][k] * S[k][b] - S[a][k] * W[k][b];
        m->dS[c][i] = r;
    }
}

void sph_plastic_return(struct model *m, size_t i, double dt, bool commit)
{
    const struct particles *p = m->sim->p;
    const struct sph_material *mt = &m->mat[p->material[i]];
    if (m->failed[i]) {
        for (int c = 0; c < 6; c++)
            m->S[c][i] = 0.0;
        return;
    }
    double ss = 0.0;
    for (int c = 0; c < 6; c++)
        ss += (c < 3 ? 1.0 : 2.0) * m->S[c][i] * m->S[c][i];
    double seq = sqrt(1.5 * ss); /* sqrt(3 J2), J2 = S:S/2 */
    /* equivalent total deviatoric strain rate for the JC rate term */
    double epdot = 0.0;
    if (mt->yield == SPH_YIELD_JOHNSON_COOK || mt->rate != SPH_RATE_NONE) {
        double d[6];
        d[0] = m->L[0][i];
        d[1] = m->dim >= 2 ? m->L[4][i] : 0.0;
        d[2] = m->L[8][i];
        d[3] = m->dim >= 2 ? 0.5 * (m->L[1][i] + m->L[3][i]) : 0.0;
        d[4] = m->dim == 3 ? 0.5 * (m->L[5][i] + m->L[7][i]) : 0.0;
        d[5] = m->dim == 3 ? 0.5 * (m->L[2][i] + m->L[6][i]) : 0.0;
        double tr = (d[0] + d[1] + d[2]) / 3.0;
        double dd = 0.0;
        for (int c = 0; c < 6; c++) {
            double v = c < 3 ? d[c] - tr : d[c];
            dd += (c < 3 ? 1.0 : 2.0) * v * v;
        }
        epdot = sqrt(2.0 / 3.0 * dd);
    }
    /* with a rate law the failure stress scales like the yield stress (the
     * gels "break at maximum stress ~ yield", seed 004 sec. 4.3.2) */
    if (commit && mt->failure == SPH_FAIL_STRESS &&
        seq >= mt->fail_value * sph_rate_factor(mt, epdot)) {
        m->failed[i] = 1;
        for (int c = 0; c < 6; c++)
            m->S[c][i] = 0.0;
        return;
    }
    if (mt->yield == SPH_YIELD_ELASTIC)
        return;
    double sy = sph_yield_stress(mt, m->ep[i], epdot, m->T[i]);
    if (seq <= sy)
        return;
    double f = sy / seq; /* radial return, f = sigma_y / sqrt(3 J2) */
    for (int c = 0; c < 6; c++)
        m->S[c][i] *= f;
    if (!commit)
        return;
    double dep = (1.0 - f) * seq / (3.0 * mt->G);
    m->ep[i] += dep;
    double work = sy * dep; /* per unit volume */
    m->wp[i] += work * p->mass[i] / m->rho[i];
    if (mt->cp > 0.0)
        m->T[i] += mt->beta_tq * work / (m->rho[i] * mt->cp); /* Taylor-Quinney heating */
    if (mt->failure == SPH_FAIL_PLASTIC_STRAIN && m->ep[i] >= mt->fail_value) {
        m->failed[i] = 1;
        for (int c = 0; c < 6; c++)
            m->S[c][i] = 0.0;
    }
    (void)dt;
}
