/**
 * @file macro_lattice.c
 * @brief Elastic constants of the perfect FCC lattice of macro-particles by
 *        direct summation over every site inside the cut-off (Cauchy-Born),
 *        and the "lattice" calibration that sets the well depth from them.
 *
 * Why: [Saitoh] Eq. 14 (E = phi''(r0) / 2 r0) treats one pair as a chain
 * link; the FCC crystal of the same pairs is stiffer.  With nearest pairs
 * only, C11 = 2 C12 = 2 C44 = sqrt2 phi''/r0 and E_[100] = (2 sqrt2/3)
 * phi''/r0 = 1.886 x Eq. 15, so a rod of the seed's calibration converges to
 * 1.886 x the fitted modulus (docs/validation.md, macro-rod-elastic).  The
 * lattice calibration scales D so that E_[100] of the lattice equals the
 * target (Eq. 15 by default).  All constants are linear in D, hence the
 * one-line rescale.
 *
 * Born term of a pair potential (zero temperature, reference volume V per
 * site r0^3/sqrt2):
 *   C_abcd = 1/(2V) sum_j (phi'' - phi'/r) x_a x_b x_c x_d / r^2,
 *   sigma_ab = 1/(2V) sum_j phi' x_a x_b / r   (residual stress).
 * With a cut-off beyond the first shell the lattice at r0 is not in
 * equilibrium (sigma != 0); the constants are then the Born term at r0 and
 * the residual pressure is reported (the default cut-off, 1.35 r0, keeps
 * the first shell only and sigma = 0 exactly).
 */
#include "models/macroparticle/macro_internal.h"

#include "spall/error.h"

#include <string.h>

/** phi' and phi'' of the tapered Mie pair at r (central differences of the
 *  analytic force: the taper makes phi'' piecewise). */
static void pair_derivs(const struct macro_pair *w, double r, double *d1, double *d2)
{
    double e, f, ep, fp, em, fm;
    const double h = 1e-6 * w->r0;
    macro_mie(w, r, &e, &f);
    macro_mie(w, r + h, &ep, &fp);
    macro_mie(w, r - h, &em, &fm);
    *d1 = -f;
    *d2 = -(fp - fm) / (2.0 * h);
}

int macro_fcc_elastic(const struct macro_pair *w, struct macro_fcc_constants *out,
                      struct spall_error *err)
{
    memset(out, 0, sizeof *out);
    if (!(w->r0 > 0.0) || !(w->r_c > w->r0) || !(w->D > 0.0))
        return spall_error_set(err, SPALL_ERR_PHYSICS, "macro-particle lattice sum: spacing %g, "
                               "cut-off %g, depth %g; expected 0 < r0 < r_c, D > 0", w->r0,
                               w->r_c, w->D);
    const double a = sqrt(2.0) * w->r0, vol = w->r0 * w->r0 * w->r0 / sqrt(2.0);
    static const double basis[4][3] = {{0, 0, 0}, {0.5, 0.5, 0}, {0.5, 0, 0.5}, {0, 0.5, 0.5}};
    const int nc = (int)ceil(w->r_c / a) + 1;
    double c11 = 0.0, c12 = 0.0, c44 = 0.0, sxx = 0.0;
    int nn = 0;
    for (int i = -nc; i <= nc; i++)
        for (int j = -nc; j <= nc; j++)
            for (int k = -nc; k <= nc; k++)
                for (int b = 0; b < 4; b++) {
                    const double x = (i + basis[b][0]) * a, y = (j + basis[b][1]) * a,
                                 z = (k + basis[b][2]) * a;
                    const double r = sqrt(x * x + y * y + z * z);
                    if (r < 1e-9 * w->r0 || r >= w->r_c)
                        continue;
                    double d1, d2;
                    pair_derivs(w, r, &d1, &d2);
                    const double g = (d2 - d1 / r) / (r * r);
                    c11 += g * x * x * x * x;
                    c12 += g * x * x * y * y;
                    c44 += g * y * y * z * z; /* C_yzyz, = C12 for central pairs (Cauchy) */
                    sxx += d1 * x * x / r;
                    nn++;
                }
    out->c11 = c11 / (2.0 * vol);
    out->c12 = c12 / (2.0 * vol);
    out->c44 = c44 / (2.0 * vol);
    out->pressure = -sxx / (2.0 * vol);
    out->neighbours = nn;
    const double s = out->c11 + out->c12;
    if (!(out->c11 - out->c12 > 0.0) || !(s > 0.0) || !(out->c11 + 2.0 * out->c12 > 0.0))
        return spall_error_set(err, SPALL_ERR_PHYSICS, "macro-particle lattice sum: unstable "
                               "lattice (C11 %g, C12 %g Pa) for cut-off %g r0", out->c11,
                               out->c12, w->r_c / w->r0);
    out->e100 = (out->c11 - out->c12) * (out->c11 + 2.0 * out->c12) / s;
    out->nu100 = out->c12 / s;
    return SPALL_OK;
}
