/**
 * @file sph_material.c
 * @brief Constitutive models of the SPH solid ([Meng2021] sec. 3.3):
 *        linear EOS, Mie-Grueneisen (Eqs. 3.24-3.27) and its C_k form
 *        (Eqs. 4.13-4.15), Jaumann-rate deviatoric stress (Eqs. 3.28-3.30),
 *        elastic / perfectly plastic / A + B ep^n (Eq. 4.12) / Johnson-Cook
 *        yield with von Mises radial return, and failure.
 */
#include "models/sph/sph_internal.h"

#include "core/particles.h"
#include "core/sim.h"
#include "core/options.h"
#include "spall/error.h"

#include <math.h>
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>

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
    if (m->dim == 2 && m->opt.kern.plane != SPH_PLANE_AXISYMMETRIC) { /* axisym: L[8] = v_r/r */
        if (m->opt.kern.plane == SPH_PLANE_STRESS && !m->failed[i]) {
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
     * gels "break at maximum stress ~ yield", [Meng2021] sec. 4.3.2) */
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

/* One `materials:` entry of an SPH run (docs/decks.md, SPH material keys):
 * elastic constants, EOS, yield, rate and failure laws, checked. */
int sph_material_parse(struct model *m, struct sim *sim, int index,
                       const struct deck_node *node, struct spall_error *err)
{
    static const char *const keys[] = {
        "density", "youngs_modulus", "poisson_ratio", "bulk_modulus", "shear_modulus", "eos",
        "sound_speed", "hugoniot_slope", "gruneisen", "reference_pressure", "yield",
        "yield_stress", "yield_a", "yield_b", "yield_n", "jc_c", "jc_m", "melt_temperature",
        "room_temperature", "reference_strain_rate", "specific_heat", "taylor_quinney", "failure",
        "failure_value", "failed_tension", "rate_model", "cs_d", "cs_q", NULL};
    static const char *const rates[] = {"none", "cowper_symonds", NULL};
    static const char *const eoss[] = {"linear", "mie_gruneisen", "mie_gruneisen_ck", NULL};
    static const char *const ylds[] = {"elastic", "perfect", "power", "johnson_cook", NULL};
    static const char *const fails[] = {"none", "stress", "plastic_strain", NULL};
    if ((size_t)index >= m->n_mat) {
        struct sph_material *q = realloc(m->mat, ((size_t)index + 1) * sizeof *q);
        if (!q)
            return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory for materials");
        memset(q + m->n_mat, 0, ((size_t)index + 1 - m->n_mat) * sizeof *q);
        m->mat = q;
        m->n_mat = (size_t)index + 1;
    }
    struct sph_material mt;
    memset(&mt, 0, sizeof mt);
    mt.rho0 = sim->materials[index].density;
    mt.Troom = 293.0;
    mt.eps0 = 1.0;
    mt.beta_tq = 0.9;
    mt.Tm = INFINITY;
    int eos = 0, yld = 0, fl = 0, rt = 0, rc;
    bool has_e = deck_peek(node, "youngs_modulus") != NULL;
    if (has_e) {
        if ((rc = deck_double_pos(node, "youngs_modulus", true, &mt.E, err)) ||
            (rc = deck_double(node, "poisson_ratio", true, -0.999, 0.4999, &mt.nu, err)))
            return rc;
        mt.K = mt.E / (3.0 * (1.0 - 2.0 * mt.nu));
        mt.G = mt.E / (2.0 * (1.0 + mt.nu));
    } else {
        if ((rc = deck_double_pos(node, "bulk_modulus", true, &mt.K, err)) ||
            (rc = deck_double(node, "shear_modulus", true, 0.0, INFINITY, &mt.G, err)))
            return rc;
        mt.E = 9.0 * mt.K * mt.G / (3.0 * mt.K + mt.G);
        mt.nu = (3.0 * mt.K - 2.0 * mt.G) / (2.0 * (3.0 * mt.K + mt.G));
    }
    if ((rc = deck_enum(node, "eos", false, eoss, &eos, err)) ||
        (rc = deck_enum(node, "yield", false, ylds, &yld, err)) ||
        (rc = deck_enum(node, "failure", false, fails, &fl, err)) ||
        (rc = deck_enum(node, "rate_model", false, rates, &rt, err)))
        return rc;
    mt.rate = (enum sph_rate)rt;
    /* Cowper-Symonds D, q: required and > 0 with rate_model cowper_symonds */
    bool cs = mt.rate == SPH_RATE_COWPER_SYMONDS;
    if ((rc = deck_double_pos(node, "cs_d", cs, &mt.cs_d, err)) ||
        (rc = deck_double_pos(node, "cs_q", cs, &mt.cs_q, err)))
        return rc;
    mt.eos = (enum sph_eos)eos;
    mt.yield = (enum sph_yield)yld;
    mt.failure = (enum sph_failure)fl;
    if (mt.eos != SPH_EOS_LINEAR &&
        ((rc = deck_double_pos(node, "sound_speed", true, &mt.mg_c, err)) ||
         (rc = deck_double_pos(node, "hugoniot_slope", true, &mt.mg_s, err)) ||
         (rc = deck_double(node, "gruneisen", true, 0.0, 10.0, &mt.mg_gamma, err)) ||
         (rc = deck_double(node, "reference_pressure", false, -INFINITY, INFINITY, &mt.mg_p0,
                           err))))
        return rc;
    bool need_a = mt.yield == SPH_YIELD_POWER || mt.yield == SPH_YIELD_JOHNSON_COOK;
    bool jc = mt.yield == SPH_YIELD_JOHNSON_COOK;
    if ((rc = deck_double_pos(node, "yield_stress", mt.yield == SPH_YIELD_PERFECT, &mt.sy, err)) ||
        (rc = deck_double_pos(node, "yield_a", need_a, &mt.A, err)) ||
        (rc = deck_double(node, "yield_b", false, 0.0, INFINITY, &mt.B, err)) ||
        (rc = deck_double(node, "yield_n", false, 0.0, 10.0, &mt.n, err)) ||
        (rc = deck_double(node, "jc_c", false, 0.0, 10.0, &mt.jc_c, err)) ||
        (rc = deck_double(node, "jc_m", false, 0.0, 10.0, &mt.jc_m, err)) ||
        (rc = deck_double_pos(node, "melt_temperature", false, &mt.Tm, err)) ||
        (rc = deck_double_pos(node, "room_temperature", false, &mt.Troom, err)) ||
        (rc = deck_double_pos(node, "reference_strain_rate", false, &mt.eps0, err)) ||
        (rc = deck_double_pos(node, "specific_heat", jc, &mt.cp, err)) ||
        (rc = deck_double(node, "taylor_quinney", false, 0.0, 1.0, &mt.beta_tq, err)) ||
        (rc = deck_double_pos(node, "failure_value", mt.failure != SPH_FAIL_NONE, &mt.fail_value,
                              err)) ||
        (rc = deck_bool(node, "failed_tension", false, &mt.failed_tension, err)) ||
        (rc = deck_check_unused(node, "material", keys, err)))
        return rc;
    if (cs && jc)
        return deck_error_key(err, node, "rate_model",
                              "rate_model cowper_symonds with yield johnson_cook: JC has its own "
                              "rate term");
    if (jc && !(mt.Tm > mt.Troom))
        return deck_error_key(err, node, "melt_temperature",
                              "melt_temperature %g K must exceed room_temperature %g K", mt.Tm,
                              mt.Troom);
    mt.parsed = true;
    m->mat[index] = mt;
    return SPALL_OK;
}
