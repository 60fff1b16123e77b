/**
 * @file pd_lps_surface.c
 * @brief Validation case "pd-lps-surface" (issue 26 item 1): the surface
 *        correction of the linear peridynamic solid (model.surface_correction
 *        with formulation lps, src/models/peridynamics/pd_lps_surface.c).
 *
 * Patch test on small bodies whose surfaces matter: a plane-stress plate of
 * 11 x 11 dx on the triangular lattice and a cube of 8 dx on the simple-cubic
 * lattice with influence_correction cubic (so that the interior is isotropic
 * and only the surfaces are tested), dx = 1 mm, delta = 3.015 dx: about half
 * of the particles have incomplete families.  A homogeneous uniaxial strain
 * eps_xx = 1e-7 is imposed on every particle; the body's mean stress, the
 * volume-weighted sum of the particles' virial stresses (= dW/d eps of the
 * whole body: the effective moduli of the homogeneous field), gives C11 and
 * C12 and from them E and nu (formulas of pd-lps-patch), and a simple shear
 * gamma_xy = 1e-7 gives G.  With the correction E, nu and G are checked
 * against the input within 1 %; without it the same quantities are recorded
 * for comparison in the note (not checked: the surface effect the correction
 * removes).  E and nu along the axes are what the correction's factors are
 * fitted to (uniaxial stretches), so they come out exact up to the symmetry
 * of the body; G is not fitted (a known gap where it misses).
 *
 * Cause of the shear gap, measured (2026-12-07): both parts of the
 * correction leave a shear term.  The surface families' deviatoric energy
 * under shear stays short (one a_i per particle, fitted to the axial
 * stretches), and the off-diagonal second moment K_xy of corner (2D) and
 * edge (3D) families, which part 1 leaves, gives a shear a dilatation.  The
 * factors of both are geometric (a_i and the bond factors do not depend on
 * the moduli), so G / G_ref - 1 = f_dev + (k / mu) f_dil for one body: fitted
 * to nu = 0.1 and 0.3, it predicts nu = 0.45 to 0.01 % (info line).  Plate
 * 11 dx: f_dev = -5.8 %, f_dil = +1.1 %; cube 8 dx: -9.1 %, +2.0 %.  The
 * measurement is not the cause (the same body-mean stress gives E and nu
 * to 1e-5 %); the resolution is: with the body 2x and 4x larger (plate 22,
 * 44 dx; cube 16, 32 dx) the plate's G errors are -2.2 / -1.1 % (nu = 0.1),
 * the cube's -4.1 / -2.0 % (nu = 0.1) and +0.25 / -0.96 % (nu = 0.45):
 * f_dev falls as 1 / L (surface layer), f_dil as 1 / L^2 (corners, edges).
 *
 * The rows with surface_correction position_aware (pd_lps_pals.c,
 * [Mitchell2015]): per-particle influences fitted to every homogeneous
 * strain (the plate) or to the six coordinate strains (the cube: uniaxial
 * strain and simple shear are among them), so E, nu and G are all met.
 */
#include "validation/lattice_cases.h"
#include "validation/pd_cases.h"
#include "validation/validation.h"

#include "core/fields.h"
#include "core/particles.h"
#include "core/sim.h"
#include "spall/error.h"

#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>

#define SURF_E 1.0e9
#define SURF_EPS 1.0e-7

/* E and nu of the body under eps_xx, G under the simple shear gamma_xy
 * (see the file comment) */
static int body_moduli(const char *deck, bool plane_stress, double *E, double *nu, double *G,
                       struct spall_error *err)
{
    struct sim *s = NULL;
    int rc = vlat_build("pd_lps_surface", deck, &s, err);
    if (rc)
        return rc;
    struct particles *p = s->p;
    const struct field_desc *f = field_registry_find(s->fields, "stress");
    const size_t nc = (size_t)field_symtensor_ncomp(s->dim);
    double *out = f ? malloc(p->n * nc * sizeof *out) : NULL;
    if (!out) {
        sim_destroy(&s);
        return spall_error_set(err, f ? SPALL_ERR_NOMEM : SPALL_ERR_INTERNAL,
                               "pd-lps-surface: no stress field or out of memory");
    }
    for (int a = 0; a < p->dim; a++)
        for (size_t q = 0; q < p->n; q++)
            p->x[a][q] = p->x0[a][q] * (a == 0 ? 1.0 + SURF_EPS : 1.0);
    field_gather_f64(f, p->n, out);
    double sxx = 0.0, syy = 0.0, sxy = 0.0, vol = 0.0;
    for (size_t q = 0; q < p->n; q++) {
        sxx += out[q * nc] * p->volume[q];
        syy += out[q * nc + 1] * p->volume[q];
        vol += p->volume[q];
    }
    /* simple shear x += gamma y: sigma_xy = G gamma (xy is component 2 in 2D, 3 in 3D) */
    for (int a = 0; a < p->dim; a++)
        for (size_t q = 0; q < p->n; q++)
            p->x[a][q] = p->x0[a][q] + (a == 0 ? SURF_EPS * p->x0[1][q] : 0.0);
    field_gather_f64(f, p->n, out);
    for (size_t q = 0; q < p->n; q++)
        sxy += out[q * nc + (p->dim == 2 ? 2 : 3)] * p->volume[q];
    *G = sxy / (vol * SURF_EPS);
    free(out);
    sim_destroy(&s);
    const double c11 = sxx / (vol * SURF_EPS), c12 = syy / (vol * SURF_EPS);
    if (plane_stress) {
        *nu = c12 / c11;
        *E = c11 * (1.0 - *nu * *nu);
    } else {
        *nu = c12 / (c11 + c12);
        *E = c11 * (1.0 + *nu) * (1.0 - 2.0 * *nu) / (1.0 - *nu);
    }
    return SPALL_OK;
}

/* The rows of surface_correction position_aware (pd_lps_pals.c): E, nu
 * and G of @p body (@p dim) at @p nu against the same references and
 * tolerances as the rows of true. */
static int pals_checks(struct vreport *r, const char *body, int dim, double nu, double E,
                       double nu_m, double G, struct spall_error *err)
{
    const char *note = dim == 2 ? "1 %: issue 26 item 1; position-aware influences "
                                  "([Mitchell2015]) exact for every homogeneous strain at every "
                                  "particle"
                                : "1 %: issue 26 item 1; position-aware influences "
                                  "([Mitchell2015]) exact for the six coordinate strains at "
                                  "every particle";
    const char *src = "input E, nu; homogeneous uniaxial strain, body-mean stress";
    char q[128];
    snprintf(q, sizeof q, "%s, nu = %.2f, position_aware: E", body, nu);
    int rc = vreport_check(r, q, "Pa", SURF_E, E, 0.01, true, src, note, err);
    if (rc)
        return rc;
    snprintf(q, sizeof q, "%s, nu = %.2f, position_aware: Poisson's ratio", body, nu);
    if ((rc = vreport_check(r, q, "1", nu, nu_m, 0.01, true, src, note, err)))
        return rc;
    snprintf(q, sizeof q, "%s, nu = %.2f, position_aware: shear modulus", body, nu);
    return vreport_check(r, q, "Pa", SURF_E / (2.0 * (1.0 + nu)), G, 0.01, true,
                         "E / (2 (1 + nu)); homogeneous simple shear, body-mean stress", note,
                         err);
}

int pd_case_lps_surface(struct vreport *r, struct spall_error *err)
{
    static const double nus[] = {0.1, 0.3, 0.45};
    static const char *const bodies[] = {"plane stress triangular plate 11 dx",
                                         "3D sc cube 8 dx (cubic-corrected)"};
    for (int b = 0; b < 2; b++) {
        double gerr[3], kmu[3]; /* G / G_ref - 1 with the correction, k / mu */
        for (int k = 0; k < 3; k++) {
            double E[3] = {0}, nu[3] = {0}, G[3] = {0}; /* false, true, position_aware */
            for (int corr = 0; corr < 3; corr++) {
                char deck[1024];
                const char *sc = corr == 2 ? "position_aware" : corr ? "true" : "false";
                if (b == 0)
                    snprintf(deck, sizeof deck,
                             "model: {type: peridynamics, formulation: lps, plane: "
                             "plane_stress, surface_correction: %s}\n"
                             "materials:\n  m: {density: 1000, youngs_modulus: %g, "
                             "poisson_ratio: %g}\n"
                             "lattice: {type: triangular, spacing: 1.0e-3, thickness: 1.0e-3}\n"
                             "geometry:\n  p: {box: {min: [0, 0], max: [0.0105, 0.0105]}}\n"
                             "body: {geometry: p, material: m}\nrun: {end_time: 1.0}\n",
                             sc, SURF_E, nus[k]);
                else
                    snprintf(deck, sizeof deck,
                             "model: {type: peridynamics, formulation: lps, "
                             "influence_correction: cubic, surface_correction: %s}\n"
                             "materials:\n  m: {density: 1000, youngs_modulus: %g, "
                             "poisson_ratio: %g}\n"
                             "lattice: {type: sc, spacing: 1.0e-3}\n"
                             "geometry:\n  p: {box: {min: [0, 0, 0], max: [0.0075, 0.0075, "
                             "0.0075]}}\n"
                             "body: {geometry: p, material: m}\nrun: {end_time: 1.0}\n",
                             sc, SURF_E, nus[k]);
                int rc = body_moduli(deck, b == 0, &E[corr], &nu[corr], &G[corr], err);
                if (rc)
                    return rc;
            }
            char q[128], note[256];
            snprintf(note, sizeof note,
                     "1 %%: issue 26 item 1; without the correction E = %.4g Pa (%+.2f %%), "
                     "nu = %.4g (%+.2f %%)",
                     E[0], 100.0 * (E[0] / SURF_E - 1.0), nu[0], 100.0 * (nu[0] / nus[k] - 1.0));
            const char *src = "input E, nu; homogeneous uniaxial strain, body-mean stress";
            snprintf(q, sizeof q, "%s, nu = %.2f: E", bodies[b], nus[k]);
            int rc = vreport_check(r, q, "Pa", SURF_E, E[1], 0.01, true, src, note, err);
            if (rc)
                return rc;
            snprintf(q, sizeof q, "%s, nu = %.2f: Poisson's ratio", bodies[b], nus[k]);
            if ((rc = vreport_check(r, q, "1", nus[k], nu[1], 0.01, true, src, note, err)))
                return rc;
            /* not fitted: the correction's energy factor comes from uniaxial stretches */
            const double Gref = SURF_E / (2.0 * (1.0 + nus[k]));
            snprintf(note, sizeof note,
                     "1 %%: not a fitted quantity (the factors come from uniaxial stretches); "
                     "without the correction G = %.4g Pa (%+.2f %%)", G[0],
                     100.0 * (G[0] / Gref - 1.0));
            snprintf(q, sizeof q, "%s, nu = %.2f: shear modulus", bodies[b], nus[k]);
            if ((rc = vreport_check(r, q, "Pa", Gref, G[1], 0.01, true,
                                    "E / (2 (1 + nu)); homogeneous simple shear, body-mean "
                                    "stress", note, err)))
                return rc;
            if (!r->checks[r->n - 1].pass)
                vreport_mark_gap(r, "the correction fits axial stretches only: surface "
                                 "families' deviatoric shear energy short (f_dev), corner / edge "
                                 "families' off-diagonal moment gives shear a dilatation (f_dil); "
                                 "G / G_ref - 1 = f_dev + (k / mu) f_dil (info line); a 2x larger "
                                 "body halves it (nu = 0.1: plate -2.2 %, cube -4.1 %)");
            if ((rc = pals_checks(r, bodies[b], b == 0 ? 2 : 3, nus[k], E[2], nu[2], G[2], err)))
                return rc;
            gerr[k] = G[1] / Gref - 1.0;
            /* bulk modulus of the dimension over mu: plane stress (1 + nu) / (1 - nu),
             * 3D 2 (1 + nu) / (3 (1 - 2 nu)) */
            kmu[k] = b == 0 ? (1.0 + nus[k]) / (1.0 - nus[k])
                            : 2.0 * (1.0 + nus[k]) / (3.0 * (1.0 - 2.0 * nus[k]));
        }
        /* the split of the shear error (file comment), fitted to the first two nu */
        const double f_dil = (gerr[1] - gerr[0]) / (kmu[1] - kmu[0]);
        const double f_dev = gerr[0] - kmu[0] * f_dil;
        vreport_info(r, "pd-lps-surface: %s: G / G_ref - 1 = f_dev + (k / mu) f_dil, from nu = "
                     "%.2f and %.2f: f_dev = %+.2f %%, f_dil = %+.2f %%; nu = %.2f predicted "
                     "%+.2f %%, measured %+.2f %%", bodies[b], nus[0], nus[1], 100.0 * f_dev,
                     100.0 * f_dil, nus[2], 100.0 * (f_dev + kmu[2] * f_dil), 100.0 * gerr[2]);
    }
    return SPALL_OK;
}
