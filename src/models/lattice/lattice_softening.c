/**
 * @file lattice_softening.c
 * @brief Deck keys and fracture energy -> full-separation strain of the
 *        cohesive softening law (lattice_softening.h).
 *
 * A straight crack between two lattice rows (along a lattice direction) cuts
 * n_s bonds of shell s per unit crack area.  Each cut bond, taken through
 * the whole bilinear envelope, dissipates k_s r_s^2 e0 ef / 2 (the area under
 * its force-elongation curve), so
 *     G_f = (e0 ef / 2) sum_s n_s k_s r_s^2  =>  ef = 2 G_f / (e0 sum_s ...).
 * Counting the cut bonds (t = thickness, A = chain cross-section):
 *   chain:       one bond per A                       -> k1 r0^2 / A
 *   triangular:  per length r0 of crack, 2 first-shell bonds (at +-60 deg)
 *                and 4 second-shell bonds (2 at +-30 deg crossing one row,
 *                and 2 vertical ones spanning two rows, from the row below
 *                and from the row two below)          -> (r0/t)(2 k1 + 12 k2)
 *   square:      per r0, 1 axis bond and 2 diagonals  -> (r0/t)(k1 + 4 k2)
 * This is the same bookkeeping as the brittle lattice's own "fracture
 * energy" (e0^2/2 instead of e0 ef/2).  Other lattices are refused: give
 * failure_strain there.  Energy held by angular springs at the moment their
 * arm breaks is dissipated too (lattice_forces.c) but is not counted here.
 */
#include "models/lattice/lattice_calib.h"
#include "models/lattice/lattice_internal.h"
#include "core/options.h"
#include "spall/error.h"

#include <math.h>

int lattice_soft_final_strain(const struct lattice_calib *c, double e0, double gf, double *ef,
                              struct spall_error *err)
{
    double sum; /* sum_s n_s k_s r_s^2 [J/m^2 per unit strain^2] */
    const double r0 = c->r0, t = c->thickness;
    if (!(r0 > 0.0) || !(t > 0.0))
        return spall_error_set(err, SPALL_ERR_INPUT, "fracture_energy needs the lattice spacing "
                               "and thickness");
    switch (c->kind) {
    case LATTICE_CHAIN: sum = c->k1 * r0 * r0 / t; break;
    case LATTICE_TRIANGULAR:
        sum = c->honeycomb_used ? 0.0 : (r0 / t) * (2.0 * c->k1 + 12.0 * c->k2);
        break;
    case LATTICE_SQUARE: sum = (r0 / t) * (c->k1 + 4.0 * c->k2); break;
    default: sum = 0.0; break;
    }
    if (!(sum > 0.0))
        return spall_error_set(err, SPALL_ERR_INPUT, "fracture_energy: bonds per unit crack "
                               "area are derived for the chain, triangular and square lattices "
                               "only; give failure_strain instead");
    *ef = 2.0 * gf / (e0 * sum);
    if (!(*ef > e0))
        return spall_error_set(err, SPALL_ERR_PHYSICS, "fracture_energy %g J/m^2 is below the "
                               "lattice's brittle limit %g J/m^2 (sum n k r^2 e0^2 / 2 with "
                               "e0 = %g): the law would need a snap-back", gf,
                               0.5 * sum * e0 * e0, e0);
    return SPALL_OK;
}

int lattice_soft_parse(const struct deck_node *node, const char *what, double eps,
                       struct lattice_material *mt, struct spall_error *err)
{
    /* onset e0 = sigma_TS / E ([Wang2010] Eq. 26) or given; full separation
     * ef given (eps, already read as failure_strain) or from the fracture
     * energy (converted in init, where the spring constants are known) */
    double sts = 0.0, e0 = 0.0, gf = 0.0;
    int rc;
    if ((rc = deck_double_pos(node, "tensile_strength", false, &sts, err)) ||
        (rc = deck_double_pos(node, "onset_strain", false, &e0, err)) ||
        (rc = deck_double_pos(node, "fracture_energy", false, &gf, err)))
        return rc;
    if ((sts > 0.0) == (e0 > 0.0))
        return deck_error(err, node, "%s: law softening: give exactly one of tensile_strength "
                          "[Pa] and onset_strain ([Wang2010] Eq. 26)", what);
    if ((gf > 0.0) == (eps > 0.0))
        return deck_error(err, node, "%s: law softening: give exactly one of fracture_energy "
                          "[J/m^2] and failure_strain (strain of full separation)", what);
    mt->eps_0 = e0 > 0.0 ? e0 : sts / mt->E;
    if (eps > 0.0 && !(eps > mt->eps_0))
        return deck_error_key(err, node, "failure_strain", "%s: failure_strain %g must exceed "
                              "the softening onset strain %g", what, eps, mt->eps_0);
    mt->gf = gf;
    mt->eps_t = eps > 0.0 ? eps : INFINITY; /* gf: set in init */
    mt->eps_t_given = true;
    return SPALL_OK;
}
