/**
 * @file lattice_softening.h
 * @brief Irreversible cohesive-softening axial law (`law: softening`) of the
 *        lattice model: bilinear envelope with a per-bond damage history.
 *
 * Envelope (strain e = s - 1 of the bond, F = k r_rest * sigma_hat(e)):
 *   sigma_hat = e                               0 <= e <= e0   (elastic)
 *   sigma_hat = e0 (ef - e) / (ef - e0)         e0 < e < ef    (softening)
 *   sigma_hat = 0                               e >= ef        (broken)
 * with e0 = sigma_TS / E ([Wang2010] Eq. 26, the brittle law's eps_max) and ef
 * the strain of full separation.  The history variable kappa = the largest
 * tensile strain reached beyond e0; damage d(kappa) = 1 - sigma_hat(kappa) /
 * kappa, and below kappa the bond unloads and reloads along the secant
 * F = (1 - d) k r_rest e (no healing).  Compression (e <= 0) always uses the
 * intact stiffness (crack closure; the spec's post-fracture repulsion).
 * This is the standard bilinear cohesive law of smeared/cohesive crack
 * models (Hillerborg, Modeer & Petersson, Cem. Concr. Res. 6 (1976) 773;
 * Bazant & Oh, Mater. Struct. 16 (1983) 155) applied to one lattice bond.
 *
 * Energies per bond, in units of k r_rest^2 (exact for the bilinear law):
 *   stored (tension)   u = (1 - d) e^2 / 2
 *   dissipated         w_d(kappa) = W(kappa) - sigma_hat(kappa) kappa / 2,
 *                      W = int_0^kappa sigma_hat de
 *   total at ef        w_d(ef) = e0 ef / 2   (area under the envelope)
 * Fracture energy: a crack plane cut by n_s bonds per unit area of shell s
 * (stiffness k_s, rest length r_s) takes G_f = sum_s n_s k_s r_s^2 e0 ef / 2;
 * lattice_model.c inverts this for ef (triangular lattice: see there).
 */
#ifndef SPALL_LATTICE_SOFTENING_H
#define SPALL_LATTICE_SOFTENING_H

#include "models/lattice/lattice_laws.h"

#include <stdint.h>

/** Secant factor 1 - d of a bond whose history is @p kappa (strain). */
LATTICE_INLINE double lattice_soft_secant(double e0, double ef, double kappa)
{
    if (kappa <= e0)
        return 1.0;
    if (kappa >= ef)
        return 0.0;
    return e0 * (ef - kappa) / ((ef - e0) * kappa);
}

/** Dissipated energy / (k r_rest^2) once the history reached @p kappa. */
LATTICE_INLINE double lattice_soft_dissipated(double e0, double ef, double kappa)
{
    if (kappa <= e0)
        return 0.0;
    if (kappa >= ef)
        return 0.5 * e0 * ef;
    const double a = e0 / (ef - e0);
    const double W = 0.5 * e0 * e0 + a * (kappa - e0) * (2.0 * ef - kappa - e0) * 0.5;
    return W - 0.5 * a * (ef - kappa) * kappa;
}

/** Force coefficient c (f_i = c dx) of half-bond s of particle i under the
 *  softening law at stretch @p st; advances the history *kappa, books half
 *  the newly dissipated energy on *diss_i and marks the half broken at ef.
 *  Both halves of a bond see the same stretch bitwise and hold their own
 *  kappa, so they stay identical without any shared write. */
LATTICE_INLINE double lattice_soft_coef(double e0, double ef, double k, double rest, double st,
                                        double *kappa, uint8_t *state, double *diss_i,
                                        uint8_t broken_bit)
{
    const double e = st - 1.0;
    if (e <= 0.0)
        return -k * (1.0 - st) / st; /* compression: intact law */
    double kap = *kappa;
    if (LATTICE_UNLIKELY(e > e0 && e > kap)) {
        const double knew = e < ef ? e : ef;
        *diss_i += 0.5 * k * rest * rest *
                   (lattice_soft_dissipated(e0, ef, knew) - lattice_soft_dissipated(e0, ef, kap));
        *kappa = kap = e;
        if (e >= ef) {
            *state |= broken_bit;
            return 0.0; /* stretched and broken: no attraction */
        }
    }
    return -k * lattice_soft_secant(e0, ef, kap) * (1.0 - st) / st;
}

/** Stored energy [J] of an unbroken softening bond (tension: secant). */
LATTICE_INLINE double lattice_soft_energy(double e0, double ef, double k, double rest, double st,
                                          double kappa)
{
    const double e = st - 1.0;
    const double f = e > 0.0 ? lattice_soft_secant(e0, ef, kappa) : 1.0;
    return 0.5 * f * k * rest * rest * e * e;
}

#endif
