/**
 * @file pd_lps_cases.c
 * @brief Validation cases of the state-based peridynamic formulations
 *        (issue 26 item 4): "pd-lps-patch" (E and nu of the linear
 *        peridynamic solid, [Silling2007], for nu = 0.1, 0.3, 0.45 in plane
 *        stress, plane strain and 3D) and "pd-lps-waves" (P-wave speed).
 *        The EPS bar is in pd_eps_bar.c.
 *
 * Patch: a homogeneous strain imposed on every particle of a block (dx = 1
 * mm, delta = 3.015 dx), the virial stress of the particle nearest the
 * centre (complete family) read back: uniaxial strain eps_xx gives C11 and
 * C12, from which E and nu follow (2D plane stress: nu = C12/C11, E = C11 (1
 * - nu^2); plane strain and 3D: nu = C12 / (C11 + C12), E = C11 (1 + nu)(1 -
 * 2 nu)/(1 - nu)).  2D on the triangular lattice, whose fourth moment of the
 * family is isotropic; 3D on the simple-cubic and fcc lattices, whose fourth
 * moment is cubic: there E and nu along [100] differ from the isotropic
 * values (two shear moduli, one alpha: docs/decks.md), recorded as they are
 * (known gaps); and on the square, sc and fcc lattices with
 * influence_correction cubic (pd_lps.c), which removes that anisotropy.
 * At the default rule (delta = 3.015 dx, linear partial volumes, influence
 * one) surface_correction position_aware (pd_lps_pals.c, [Mitchell2015])
 * meets 1 % for every nu in plane stress and plane strain on the triangular
 * and square lattices and in 3D on sc and fcc: its influences are fitted to
 * each discrete family, so the lattice's fourth moment no longer matters (in
 * 3D they fit the coordinate strains' energies, which give C11 and C12).
 */
#include "validation/lattice_cases.h"
#include "validation/pd_cases.h"
#include "validation/validation.h"
#include "validation/vpar.h"

#include "core/fields.h"
#include "core/particles.h"
#include "core/sim.h"
#include "spall/error.h"

#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define LPS_E 1.0e9

/* Particle nearest the point c (reference positions). */
static size_t nearest(const struct particles *p, const double *c)
{
    size_t best = 0;
    double bd = INFINITY;
    for (size_t i = 0; i < p->n; i++) {
        double d2 = 0.0;
        for (int a = 0; a < p->dim; a++)
            d2 += (p->x0[a][i] - c[a]) * (p->x0[a][i] - c[a]);
        if (d2 < bd) {
            bd = d2;
            best = i;
        }
    }
    return best;
}

/* sigma_xx / eps and sigma_yy / eps of particle i under uniaxial strain eps_xx */
static int uniaxial(struct sim *s, size_t i, double *c11, double *c12, struct spall_error *err)
{
    struct particles *p = s->p;
    const double eps = 1e-7;
    const struct field_desc *f = field_registry_find(s->fields, "stress");
    if (!f)
        return spall_error_set(err, SPALL_ERR_INTERNAL, "pd-lps-patch: no stress field");
    const size_t nc = (size_t)field_symtensor_ncomp(s->dim);
    double *out = malloc(p->n * nc * sizeof *out);
    if (!out)
        return spall_error_set(err, SPALL_ERR_NOMEM, "pd-lps-patch: out of memory");
    for (int a = 0; a < p->dim; a++)
        for (size_t q = 0; q < p->n; q++)
            p->x[a][q] = p->x0[a][q] * (a == 0 ? 1.0 + eps : 1.0);
    field_gather_f64(f, p->n, out);
    *c11 = out[i * nc] / eps;
    *c12 = out[i * nc + 1] / eps;
    free(out);
    return SPALL_OK;
}

/* One configuration of the patch test. */
struct lps_form {
    const char *name;
    const char *lattice;
    int plane;         /* 0: 3D, 1: plane stress, 2: plane strain */
    bool corrected;    /* influence_correction cubic */
    bool cell;         /* partial_volume_rule cell, delta = LPS_CELL_M dx */
    bool pals;         /* surface_correction position_aware */
};

/* delta / dx of the cell-rule rows: the first m (of 3.015, 4.015, ...) from
 * which every nu is inside 1 % on sc and fcc with that rule
 * (pd_lps_patch_study); at the default 3.015 it misses (sc nu = 0.1: -2.1 %) */
#define LPS_CELL_M 4.015

/* E and nu of the particle nearest the centre of the block under uniaxial
 * strain; hf: delta / dx (0: the default 3.015), rule: partial_volume_rule */
static int lps_patch_run(const struct lps_form *f, double nu, double hf, const char *rule,
                         double *E_m, double *nu_m, struct spall_error *err)
{
    char deck[1024], model[256];
    double c[3];
    snprintf(model, sizeof model, "formulation: lps%s%s%s%s%s%s",
             f->plane == 1 ? ", plane: plane_stress" : f->plane == 2 ? ", plane: plane_strain" : "",
             f->corrected ? ", influence_correction: cubic" : "", rule ? ", partial_volume_rule: " : "",
             rule ? rule : "", f->pals ? ", surface_correction: position_aware" : "",
             hf > 0.0 ? ", horizon_factor: " : "");
    if (hf > 0.0) {
        const size_t w = strlen(model);
        snprintf(model + w, sizeof model - w, "%.17g", hf);
    }
    /* the block holds the centre particle's whole family: half-width >= delta
     * + the cell's reach + the offset of the nearest site (fcc: 0.8 dx) */
    const double half = hf > 0.0 ? 1e-3 * (hf + 1.7) : 0.00525;
    if (f->plane) {
        snprintf(deck, sizeof deck,
                 "model: {type: peridynamics, %s}\n"
                 "materials:\n  m: {density: 1000, youngs_modulus: %g, poisson_ratio: %g}\n"
                 "lattice: {type: %s, spacing: 1.0e-3, thickness: 1.0e-3}\n"
                 "geometry:\n  p: {box: {min: [0, 0], max: [0.0205, 0.0205]}}\n"
                 "body: {geometry: p, material: m}\nrun: {end_time: 1.0}\n",
                 model, LPS_E, nu, f->lattice);
        c[0] = c[1] = 0.01;
        c[2] = 0.0;
    } else {
        snprintf(deck, sizeof deck,
                 "model: {type: peridynamics, %s}\n"
                 "materials:\n  m: {density: 1000, youngs_modulus: %g, poisson_ratio: %g}\n"
                 "lattice: {type: %s, spacing: 1.0e-3}\n"
                 "geometry:\n  p: {box: {min: [0, 0, 0], max: [%.17g, %.17g, %.17g]}}\n"
                 "body: {geometry: p, material: m}\nrun: {end_time: 1.0}\n",
                 model, LPS_E, nu, f->lattice, 2 * half, 2 * half, 2 * half);
        c[0] = c[1] = c[2] = hf > 0.0 ? half : 0.005;
    }
    struct sim *s = NULL;
    int rc = vlat_build("pd_lps_patch", deck, &s, err);
    if (rc)
        return rc;
    double c11 = 0.0, c12 = 0.0;
    rc = uniaxial(s, nearest(s->p, c), &c11, &c12, err);
    sim_destroy(&s);
    if (rc)
        return rc;
    if (f->plane == 1) {
        *nu_m = c12 / c11;
        *E_m = c11 * (1.0 - *nu_m * *nu_m);
    } else {
        *nu_m = c12 / (c11 + c12);
        *E_m = c11 * (1.0 + *nu_m) * (1.0 - 2.0 * *nu_m) / (1.0 - *nu_m);
    }
    return SPALL_OK;
}

/* The cause of the 3D gap, measured: nu = 0.1 (the most sensitive value:
 * the error of C11 and C12 is alpha times that of the fourth moment, large
 * against the bulk part when mu / K is) on sc and fcc for m = 3.015 ...
 * 6.015 with the linear and the cell rule.  The linear rule's error swings
 * with m (sc: -5.3, -0.1, +0.2, -1.5 % in nu), the cell rule's falls to
 * within 0.7 % from m = 4.015 on. */
static int pd_lps_patch_study(struct vreport *r, struct spall_error *err)
{
    static const char *const lat[] = {"sc", "fcc"}, *const rules[] = {"linear", "cell"};
    for (int q = 0; q < 2; q++)
        for (int k = 0; k < 2; k++) {
            char line[256];
            int w = snprintf(line, sizeof line, "%s, %s rule, nu = 0.1, (E, nu) error %% at "
                             "m = 3.015/4.015/5.015/6.015:", lat[q], rules[k]);
            for (int j = 0; j < 4; j++) {
                const struct lps_form f = {"", lat[q], 0, false, k == 1, false};
                double E_m, nu_m;
                int rc = lps_patch_run(&f, 0.1, 3.015 + j, rules[k], &E_m, &nu_m, err);
                if (rc)
                    return rc;
                if (w > 0 && (size_t)w < sizeof line)
                    w += snprintf(line + w, sizeof line - (size_t)w, " (%+.2f, %+.2f)",
                                  100.0 * (E_m / LPS_E - 1.0), 100.0 * (nu_m / 0.1 - 1.0));
            }
            vreport_info(r, "pd-lps-patch: %s", line);
        }
    return SPALL_OK;
}

int pd_case_lps_patch(struct vreport *r, struct spall_error *err)
{
    static const double nus[] = {0.1, 0.3, 0.45};
    /* triangular (2D); cubic 3D as they are; with influence_correction cubic
     * (pd_lps.c) on the square, sc and fcc lattices; the cell rule
     * (pd_cellvol.c) at delta = LPS_CELL_M dx on sc and fcc */
    static const struct lps_form forms[] = {
        {"plane stress", "triangular", 1, false, false, false},
        {"plane strain", "triangular", 2, false, false, false},
        {"3D sc", "sc", 0, false, false, false},
        {"3D fcc", "fcc", 0, false, false, false},
        {"plane stress square, corrected", "square", 1, true, false, false},
        {"3D sc, corrected", "sc", 0, true, false, false},
        {"3D fcc, corrected", "fcc", 0, true, false, false},
        {"3D sc, cell volumes, delta = 4.015 dx", "sc", 0, false, true, false},
        {"3D fcc, cell volumes, delta = 4.015 dx", "fcc", 0, false, true, false},
        /* the default rule (3.015 dx, linear partial volumes, influence one)
         * with the position-aware influences (pd_lps_pals.c) */
        {"plane stress, position-aware", "triangular", 1, false, false, true},
        {"plane strain, position-aware", "triangular", 2, false, false, true},
        {"plane stress square, position-aware", "square", 1, false, false, true},
        {"plane strain square, position-aware", "square", 2, false, false, true},
        {"3D sc, position-aware", "sc", 0, false, false, true},
        {"3D fcc, position-aware", "fcc", 0, false, false, true},
    };
    const int nf = (int)(sizeof forms / sizeof forms[0]);
    int rc;
    for (int fm = 0; fm < nf; fm++) {
        double q4[3][2]; /* the uncorrected 3D rows: q4 from C11 and from C12, per nu */
        for (int k = 0; k < 3; k++) {
            const struct lps_form *f = &forms[fm];
            const double nu = nus[k];
            double E_m, nu_m;
            if ((rc = lps_patch_run(f, nu, f->cell ? LPS_CELL_M : 0.0, f->cell ? "cell" : NULL,
                                    &E_m, &nu_m, err)))
                return rc;
            const bool tri = f->plane && !f->corrected && strcmp(f->lattice, "square") != 0;
            const bool plain3 = !f->plane && !f->corrected && !f->cell && !f->pals;
            char q[96];
            const char *src = tri ? "input E, nu; triangular lattice, interior particle"
                                  : "input E, nu; cubic lattice, [100], interior particle";
            const char *note =
                f->pals && f->plane ? "1 %: issue 26 item 4; the position-aware influences make "
                                      "each discrete family's dilatation and deviatoric energy "
                                      "exact for every homogeneous strain ([Mitchell2015])"
                : f->pals ? "1 %: issue 26 item 4; the position-aware influences make each "
                            "discrete family's dilatation exact for every homogeneous strain "
                            "and its deviatoric energy for the coordinate strains "
                            "([Mitchell2015]), so C11 and C12 exactly"
                : tri ? "1 %: issue 26 item 4; the triangular family's fourth moment is isotropic"
                : f->corrected ? "1 %: issue 26 item 4; the corrected influence makes the "
                                 "fullest family's fourth moment isotropic"
                : f->cell ? "1 %: issue 26 item 4; cells cut by the horizon weighted by their "
                            "volume inside it ([Seleson2014]): nu = 0.1 within 0.7 % for m = "
                            "4.015 to 6.015 on sc and fcc (the linear rule: -1.5 to +1.7 %)"
                          : "1 %: issue 26 item 4; the cubic family's fourth moment is not "
                            "isotropic (C44 != (C11 - C12)/2)";
            const char *gap = "cubic lattice, delta = 3.015 dx, linear partial volumes: the "
                              "family's fourth moment sum w n_x^4 / sum w is 0.2016 (sc), "
                              "0.1995 (fcc) against the isotropic 1/5, and the measured C11, "
                              "C12 imply that moment at every nu (info line): the whole error; the "
                              "cell rule at delta = 4.015 dx meets 1 % (rows below)";
            snprintf(q, sizeof q, "%s nu = %.2f: E", f->name, nu);
            if ((rc = vreport_check(r, q, "Pa", LPS_E, E_m, 0.01, true, src, note, err)))
                return rc;
            if (plain3 && !r->checks[r->n - 1].pass)
                vreport_mark_gap(r, gap);
            snprintf(q, sizeof q, "%s nu = %.2f: Poisson's ratio", f->name, nu);
            if ((rc = vreport_check(r, q, "1", nu, nu_m, 0.01, true, src, note, err)))
                return rc;
            if (plain3 && !r->checks[r->n - 1].pass)
                vreport_mark_gap(r, gap);
            /* The cause of the gap, measured: with K = m / 3 I (cubic symmetry) and
             * alpha = 15 mu / m the LPS moduli along [100] are C11 = k + 15 mu (q4 -
             * 1/9), C12 = k - 15 mu (q4 / 2 - 1/18), q4 = sum w n_x^4 / sum w (w =
             * omega beta |xi|^2 V; isotropic: 1/5).  The q4 both imply, equal for
             * every nu, say that this one moment is the whole error. */
            const double mu = LPS_E / (2.0 * (1.0 + nu)), kb = LPS_E / (3.0 * (1.0 - 2.0 * nu));
            const double dn = (1.0 + nu_m) * (1.0 - 2.0 * nu_m);
            q4[k][0] = E_m * (1.0 - nu_m) / dn - kb;
            q4[k][0] = q4[k][0] / (15.0 * mu) + 1.0 / 9.0;
            q4[k][1] = 1.0 / 9.0 - 2.0 * (E_m * nu_m / dn - kb) / (15.0 * mu);
        }
        if (!forms[fm].plane && !forms[fm].corrected && !forms[fm].cell && !forms[fm].pals)
            vreport_info(r, "pd-lps-patch: %s: q4 = sum w n_x^4 / sum w implied by C11 / C12 "
                         "(cause of the gap, see the code): %.5f / %.5f, %.5f / %.5f, %.5f / "
                         "%.5f for nu = %.2f, %.2f, %.2f (isotropic 0.2)", forms[fm].name, q4[0][0],
                         q4[0][1], q4[1][0], q4[1][1], q4[2][0], q4[2][1], nus[0], nus[1],
                         nus[2]);
    }
    /* --quick and the ctest gate: every check, not the study (info lines only,
     * 16 builds up to delta = 6.015 dx: most of the case's time) */
    return r->quick ? SPALL_OK : pd_lps_patch_study(r, err);
}

/*
 * "pd-lps-waves": P wave of the LPS plate.  Set-up as pd-waves' 2D plate
 * (pd_waves.c): E = 200 GPa, rho = 7850 kg/m^3, here nu = 0.3 on the
 * triangular lattice, plane stress, 0.2 x 0.02 m, dx = 1 mm, delta = 3.015
 * dx; the left end driven at 1 m/s, the right end fixed, the top and bottom
 * rows held in y (uniaxial strain): the front moves at sqrt(E / (rho (1 -
 * nu^2))).  Measured by the mean arrival (centroid of the velocity rise) at
 * L/4 and L/2, as in pd_waves.c.
 */
#define LPW_E 200e9
#define LPW_RHO 7850.0
#define LPW_NU 0.3
#define LPW_V 1.0

int pd_case_lps_waves(struct vreport *r, struct spall_error *err)
{
    char deck[2048];
    snprintf(deck, sizeof deck,
             "model: {type: peridynamics, formulation: lps}\n"
             "materials:\n  steel: {density: %g, youngs_modulus: %g, poisson_ratio: %g}\n"
             "lattice: {type: triangular, spacing: 1.0e-3, thickness: 1.0e-3}\n"
             "geometry:\n  plate: {box: {min: [-0.0005, -0.0001], max: [0.2005, 0.0201]}}\n"
             "body: {geometry: plate, material: steel}\n"
             "groups:\n  left: {box: {min: [-0.001, -1], max: [0.0005, 1]}}\n"
             "  right: {box: {min: [0.1995, -1], max: [0.201, 1]}}\n"
             "  edges_lo: {box: {min: [-1, -1], max: [1, 0.0004]}}\n"
             "  edges_hi: {box: {min: [-1, 0.0190], max: [1, 1]}}\n"
             "boundary_conditions:\n"
             "  - {group: left, type: velocity, components: [x], value: %g}\n"
             "  - {group: right, type: fixed}\n"
             "  - {group: edges_lo, type: fixed, components: [y]}\n"
             "  - {group: edges_hi, type: fixed, components: [y]}\n"
             "probes:\n  - {name: q, position: [0.05, 0.01]}\n"
             "  - {name: h, position: [0.1, 0.01]}\n"
             "run: {end_time: 1.0}\n",
             LPW_RHO, LPW_E, LPW_NU, LPW_V);
    struct sim *s = NULL;
    int rc = vlat_build("pd_lps_wave", deck, &s, err);
    size_t np = s ? s->p->n : 0;
    if (!rc && (rc = vpar_distribute(r, s, err))) /* mpirun: probes from their owners */
        sim_destroy(&s);
    if (rc)
        return rc;
    const double c_ref = sqrt(LPW_E / (LPW_RHO * (1 - LPW_NU * LPW_NU)));
    const double t_end = 0.1 / c_ref * 1.6; /* front past L/2, reflection not back */
    while (s->t < t_end && !rc)
        rc = sim_step(s, err);
    double c_meas = NAN;
    if (!rc) /* the probes by global id (vpar.h) */
        c_meas = vpar_probe_wave_speed(s, LPW_V);
    sim_destroy(&s);
    if (rc)
        return rc;
    if ((rc = vreport_check(r, "2D plate, uniaxial strain, P wave speed (LPS, nu = 0.3)", "m/s",
                            c_ref, c_meas, 0.02, true,
                            "sqrt(E/(rho(1-nu^2))), plane-stress P wave",
                            "2 %: as pd-waves (issue 4); mean-arrival timing", err)))
        return rc;
    vreport_info(r, "pd-lps-waves: %zu particles; c = %.2f m/s (%+.2f %%), ref %.2f m/s", np,
                 c_meas, 100.0 * (c_meas / c_ref - 1.0), c_ref);
    return SPALL_OK;
}
