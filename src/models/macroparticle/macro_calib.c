/**
 * @file macro_calib.c
 * @brief Macro-particle calibration ([Saitoh] Eqs. 10, 11, 13-15).
 */
#include "core/mathconst.h"
#include "models/macroparticle/macro_calib.h"
#include "models/macroparticle/macro_internal.h"

#include "spall/error.h"

#include <math.h>
#include <string.h>


double macro_eq15_modulus(double rho, double atom_mass, double e0, double p, double q)
{
    return SPALL_PI * rho * p * q * e0 / (MACRO_PACKING * 72.0 * atom_mass);
}

double macro_debye_omega(double theta_d)
{
    return MACRO_KB * theta_d / MACRO_HBAR;
}

int macro_calibrate(struct macro_calib *c, struct spall_error *err)
{
    if (!(c->rho > 0.0) || !isfinite(c->rho))
        return spall_error_set(err, SPALL_ERR_PHYSICS, "macro-particle: density %g; expected > 0",
                               c->rho);
    if (!(c->atom_mass > 0.0) || !isfinite(c->atom_mass))
        return spall_error_set(err, SPALL_ERR_PHYSICS,
                               "macro-particle: atomic mass %g kg; expected > 0", c->atom_mass);
    if (!(c->e0 > 0.0) || !isfinite(c->e0))
        return spall_error_set(err, SPALL_ERR_PHYSICS,
                               "macro-particle: cohesive energy %g J; expected > 0", c->e0);
    if (!(c->p > 0.0) || !(c->q > c->p) || !isfinite(c->q))
        return spall_error_set(err, SPALL_ERR_PHYSICS,
                               "macro-particle: exponents [%g, %g]; expected [p, q] with "
                               "q > p > 0 (attractive p, repulsive q)", c->p, c->q);
    if (!(c->r0 > 0.0) || !isfinite(c->r0))
        return spall_error_set(err, SPALL_ERR_PHYSICS, "macro-particle: spacing %g m; expected > 0",
                               c->r0);
    const double taper = c->taper > 0.0 ? c->taper : 1.2;
    const double cutoff = c->cutoff > 0.0 ? c->cutoff : 1.35;
    if (!(taper >= 1.0) || !(cutoff > taper) || !isfinite(cutoff))
        return spall_error_set(err, SPALL_ERR_PHYSICS, "macro-particle: taper %g and cut-off %g "
                               "(units of r0); expected 1 <= taper < cutoff", taper, cutoff);
    if (c->mode == MACRO_CAL_LATTICE && (c->e_target < 0.0 || !isfinite(c->e_target)))
        return spall_error_set(err, SPALL_ERR_PHYSICS, "macro-particle: target Young's modulus "
                               "%g Pa; expected > 0", c->e_target);
    const double r0 = c->r0;
    c->n_atom = (c->rho * SPALL_PI * r0 * r0 * r0 / 6.0) / (c->atom_mass * MACRO_PACKING);
    c->p_atom = c->n_atom * c->e0;
    c->mass = c->rho * r0 * r0 * r0 / sqrt(2.0);
    /* Eq. 15 from the seed's depth P_atom/6, whatever the mode */
    c->E = (c->p_atom / 6.0) * c->p * c->q / (r0 * r0) / (2.0 * r0);
    struct macro_pair w;
    memset(&w, 0, sizeof w);
    w.D = c->p_atom / 6.0;
    w.p = c->p;
    w.q = c->q;
    w.r0 = r0;
    w.r_on = taper * r0;
    w.r_c = cutoff * r0;
    struct macro_fcc_constants fc;
    int rc = macro_fcc_elastic(&w, &fc, err);
    if (rc)
        return rc;
    c->d_scale = 1.0;
    if (c->mode == MACRO_CAL_LATTICE)
        c->d_scale = (c->e_target > 0.0 ? c->e_target : c->E) / fc.e100;
    /* every lattice constant is linear in D */
    c->D = c->d_scale * c->p_atom / 6.0;
    c->k = c->D * c->p * c->q / (r0 * r0);
    c->E_fcc100 = c->d_scale * fc.e100;
    c->nu_fcc100 = fc.nu100;
    c->c11 = c->d_scale * fc.c11;
    c->c12 = c->d_scale * fc.c12;
    c->c44 = c->d_scale * fc.c44;
    c->pressure = c->d_scale * fc.pressure;
    return SPALL_OK;
}
