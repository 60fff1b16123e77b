/**
 * @file sph_beam_plate.c
 * @brief SPH validation cases "sph-gradient" and "sph-beam".
 *
 * sph-gradient: a linear velocity field v = A x + b on a free 2D block and
 *   a free 3D block; CSPM ([Meng2021] Eqs. 3.10-3.11) must return A at every
 *   particle, surfaces and corners included (the plain SPH gradient of
 *   Eq. 3.31 loses up to half of it there: reported, not checked).
 * sph-beam: [Meng2021] sec. 3.4.1 / Table 3.4, the cantilever under an end
 *   load ramped quadratically to 1.75 kN over 1.5 ms and held to 3 ms; the
 *   time mean of the tip deflection over 1.5-3.0 ms against the static
 *   FL^3/3EI + 6FL/5GA = 33.59 mm, for each of the six kernels; tolerance =
 *   the thesis' own error for that kernel (each kernel must do at least as
 *   well as the thesis); CSPM and the leapfrog (sph_leapfrog.c), plus a
 *   total-Lagrangian row (Wendland tolerance) and a quintic row with the
 *   kernel-averaged artificial stress (sph_as_smooth.c: the pointwise one
 *   makes the quintic blow up).  Main rows: the thesis' clamp of fixed
 *   particles; then the same updated-form rows with the mirrored clamp
 *   (model.clamp, sph_clamp.c), checked against the same tolerances.
 * sph-plate: validation/sph_plate.c.
 */
#include "validation/lattice_cases.h"
#include "validation/sph_beam.h"
#include "validation/sph_cases.h"
#include "validation/validation.h"

#include "core/particles.h"
#include "core/sim.h"
#include "core/model.h"
#include "models/sph/sph.h"
#include "spall/error.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- sph-gradient ------------------------------------------------------ */

static int gradient_block(struct vreport *r, int dim, struct spall_error *err)
{
    char deck[2048];
    if (dim == 2)
        snprintf(deck, sizeof deck,
                 "model: {type: sph, kernel: wendland, h_factor: 1.5, adaptive_dt: false}\n"
                 "materials: {m: {density: 1000, youngs_modulus: 1.0e9, poisson_ratio: 0.3}}\n"
                 "lattice: {type: square, spacing: 1.0e-3, origin: [0.0005, 0.0005]}\n"
                 "body: {geometry: {box: {min: [0, 0], max: [0.012, 0.007]}}, material: m}\n"
                 "run: {steps: 1}\n");
    else
        snprintf(deck, sizeof deck,
                 "model: {type: sph, kernel: wendland, h_factor: 1.5, adaptive_dt: false}\n"
                 "materials: {m: {density: 1000, youngs_modulus: 1.0e9, poisson_ratio: 0.3}}\n"
                 "lattice: {type: sc, spacing: 1.0e-3, origin: [0.0005, 0.0005, 0.0005]}\n"
                 "body: {geometry: {box: {min: [0, 0, 0], max: [0.008, 0.006, 0.005]}}, "
                 "material: m}\n"
                 "run: {steps: 1}\n");
    struct sim *s = NULL;
    int rc = vlat_build(dim == 2 ? "sph_gradient_2d" : "sph_gradient_3d", deck, &s, err);
    if (rc)
        return rc;
    const double A[3][3] = {{3.0, -1.0, 0.5}, {2.0, 0.7, -0.4}, {-1.2, 0.9, 1.1}};
    struct particles *p = s->p;
    double errmax[2] = {0, 0};
    for (int pass = 0; pass < 2 && !rc; pass++) {
        sph_set_cspm(s->model, pass == 0);
        for (size_t i = 0; i < p->n; i++)
            for (int a = 0; a < dim; a++) {
                double v = 0.1 * a;
                for (int b = 0; b < dim; b++)
                    v += A[a][b] * p->x[b][i];
                p->v[a][i] = v;
            }
        if ((rc = sim_initial_forces(s, err)))
            break;
        for (size_t i = 0; i < p->n; i++) {
            double L[9];
            sph_velocity_gradient(s->model, i, L);
            for (int a = 0; a < dim; a++)
                for (int b = 0; b < dim; b++)
                    errmax[pass] = fmax(errmax[pass], fabs(L[a * 3 + b] - A[a][b]) / 3.0);
        }
    }
    if (!rc) {
        struct sph_stats st;
        sph_stats_get(s->model, &st);
        char q[96];
        snprintf(q, sizeof q, "%dD CSPM velocity gradient, max error / |A|", dim);
        rc = vreport_check(r, q, "1", 0.0, errmax[0], 1e-10, false,
                           "exact for linear fields by construction ([Meng2021] Eq. 3.11)",
                           "round-off only; includes the free surfaces and corners", err);
        vreport_info(r, "%dD: plain SPH gradient (Eq. 3.31) max error / |A| = %.3f (surface "
                     "deficiency CSPM removes); CSPM fallbacks = %zu",
                     dim, errmax[1], st.cspm_fallbacks);
    }
    sim_destroy(&s);
    return rc;
}

int sph_case_gradient(struct vreport *r, struct spall_error *err)
{
    int rc = gradient_block(r, 2, err);
    if (!rc)
        rc = gradient_block(r, 3, err);
    return rc;
}

/* ---- sph-beam ---------------------------------------------------------- */

const char *const SPH_BEAM_KERNELS[6] = {"cubic_spline",  "gaussian",      "quintic_spline",
                                         "wendland",      "double_cosine", "hyperbolic"};
/* [Meng2021] Table 3.4: mean error over 1.5-3.0 ms [%] */
static const double BEAM_THESIS_ERR[6] = {2.55, 8.11, 7.96, 9.58, 17.62, 8.86};

/* Largest stretch |x_i - x_j| / |X_i - X_j| over initially adjacent pairs
 * (distance dx): elastic bending at 81 mm keeps it near 1.01; a crack
 * opens it to several. */
static double max_pair_stretch(const struct particles *p, double dx)
{
    double best = 1.0;
    for (size_t i = 0; i < p->n; i++)
        for (size_t j = i + 1; j < p->n; j++) {
            double X0 = p->x0[0][j] - p->x0[0][i], X1 = p->x0[1][j] - p->x0[1][i];
            double R2 = X0 * X0 + X1 * X1;
            if (R2 > 1.0201 * dx * dx)
                continue;
            double x0 = p->x[0][j] - p->x[0][i], x1 = p->x[1][j] - p->x[1][i];
            best = fmax(best, sqrt((x0 * x0 + x1 * x1) / R2));
        }
    return best;
}

void sph_beam_deck(const char *kernel, double force, double hfac, const char *extra,
                   enum sph_beam_clamp clamp, char *deck, size_t len)
{
    /* the mirrored clamp needs each ghost's mirror image in the beam and a
     * clamp as deep as the widest support (3h = 4.2 mm at h = 1.4 dx): 5
     * columns; the thesis' fixed clamp keeps its 3 columns */
    const bool mirror = clamp == SPH_BEAM_MIRROR;
    const char *ckey = mirror ? ", clamp: {group: clamp, point: [0, 0], normal: [1, 0]}" : "";
    /* the edge clamp: one fixed column, the thesis' "left edge of the beam
     * is fixed" ([Meng2021] sec. 3.4.1, Fig. 3.5) read literally */
    const double xmin = mirror ? -0.005 : clamp == SPH_BEAM_EDGE ? -0.001 : -0.003;
    /* leapfrog: the predictor-corrector is unstable for these undamped
     * elastic beams at dt_factor 0.5 (sph_leapfrog.c) */
    snprintf(deck, len,
             "model: {%skernel: %s, h_factor: %g, plane: stress,\n"
             "        time_integration: leapfrog, %s%s}\n"
             "materials: {steel: {density: 7800, youngs_modulus: 210.0e9, poisson_ratio: 0.3}}\n"
             "lattice: {type: square, spacing: 1.0e-3, origin: [0.0005, 0.0005], "
             "thickness: 1.0e-3}\n"
             "body: {geometry: {box: {min: [%.17g, -0.005], max: [0.1, 0.005]}}, "
             "material: steel}\n"
             "groups:\n"
             "  clamp: {box: {min: [-0.01, -1], max: [0.0, 1]}}\n"
             "  tip: {box: {min: [0.099, -1], max: [0.101, 1]}}\n"
             "boundary_conditions:\n"
             "  - {group: clamp, type: fixed}\n"
             "  - {group: tip, type: force, components: [y], value: %.17g,\n"
             "     function: {type: quadratic_ramp, duration: 1.5e-3}}\n"
             "run: {end_time: 3.0e-3, dt_factor: 0.5}\n",
             strncmp(extra, "type:", 5) == 0 ? "" : "type: sph, ", kernel, hfac, extra, ckey,
             xmin, -force);
}

int sph_beam_build(const char *kernel, double force, double hfac, const char *extra,
                   enum sph_beam_clamp clamp, struct sim **out, struct spall_error *err)
{
    char deck[3072];
    sph_beam_deck(kernel, force, hfac, extra, clamp, deck, sizeof deck);
    int rc = vlat_build("sph_beam", deck, out, err);
    if (!rc)
        (*out)->energy_blowup = SPH_BEAM_ENERGY_BLOWUP;
    return rc;
}

double sph_beam_kinetic_ratio(const struct sim *s)
{
    const struct particles *p = s->p;
    const double input = fabs(s->energy.initial_total) + fabs(s->energy.external);
    double ke = 0.0;
    for (size_t i = 0; i < p->n_owned; i++)
        for (int d = 0; d < s->dim; d++)
            ke += 0.5 * p->mass[i] * p->v[d][i] * p->v[d][i];
    return input > 0.0 ? ke / input : 0.0;
}

int sph_beam_run(const char *kernel, double force, double hfac, const char *extra,
                 enum sph_beam_clamp clamp, struct sph_beam_result *out,
                 struct spall_error *err)
{
    out->mean = out->final = out->max = out->stretch = NAN;
    out->peak_ratio = out->peak_time = 0.0;
    struct sim *s = NULL;
    int rc = sph_beam_build(kernel, force, hfac, extra, clamp, &s, err);
    if (rc)
        return rc;
    int g = sim_find_group(s, "tip");
    const struct group *tip = &s->groups[g];
    double acc = 0.0, tacc = 0.0, uy = 0.0, umax = 0.0;
    while (!sim_done(s)) {
        double dt = s->dt;
        if ((rc = sim_step(s, err)))
            break;
        const double ratio = sph_beam_kinetic_ratio(s);
        if (ratio > out->peak_ratio) {
            out->peak_ratio = ratio;
            out->peak_time = s->t;
        }
        uy = 0.0;
        for (size_t q = 0; q < tip->n; q++) {
            size_t i = tip->idx[q];
            uy += s->p->x[1][i] - s->p->x0[1][i];
        }
        uy /= (double)tip->n;
        umax = fmax(umax, -uy);
        if (s->t >= 1.5e-3) {
            acc += -uy * dt;
            tacc += dt;
        }
    }
    sim_update_energy(s);
    out->mean = tacc > 0 ? acc / tacc : NAN;
    out->final = -uy;
    out->max = umax;
    out->stretch = max_pair_stretch(s->p, 1.0e-3);
    out->balance = s->energy.balance;
    out->external = s->energy.external;
    sim_destroy(&s);
    return rc;
}

/* One beam run, an unstable run recorded as NaN with its message. */
int sph_beam_run_or_note(struct vreport *r, const char *what, const char *kernel, double force,
                         double hfac, const char *extra, enum sph_beam_clamp clamp,
                         struct sph_beam_result *res, struct spall_error *err)
{
    int rc = sph_beam_run(kernel, force, hfac, extra, clamp, res, err);
    if (rc == SPALL_ERR_UNSTABLE) {
        vreport_info(r, "%s: %s", what, err->msg);
        err->code = 0;
        err->msg[0] = 0;
        res->mean = NAN;
        return SPALL_OK;
    }
    if (!rc)
        vreport_info(r, "%s: mean %.2f mm, max %.2f mm, at 3 ms %.2f mm, max pair stretch %.3f, "
                     "energy balance %.3g J of %.3g J input, peak kinetic energy %.3g times "
                     "the work put in (t = %.3g ms)",
                     what, res->mean * 1e3, res->max * 1e3, res->final * 1e3, res->stretch,
                     res->balance, res->external, res->peak_ratio, res->peak_time * 1e3);
    return rc;
}

/* One row of sph-beam: kernel type (0-5), variant (0 = the thesis'
 * settings, 1 = TLSPH, 2 = kernel-averaged AS) and clamp form. */
struct beam_row {
    int kernel, variant;
    enum sph_beam_clamp clamp;
};

int sph_case_beam(struct vreport *r, struct spall_error *err)
{
    const double ref = 33.59e-3;
    const char *thesis = "cspm: true, viscosity: [0.1, 0.1], artificial_stress: 0.5, xsph: 0.5";
    /* main rows: the thesis' fixed-particle clamp (types 1-6, TLSPH, the
     * quintic with the averaged AS); then the same kernels with the
     * mirrored clamp (sph_clamp.c; not with TLSPH) */
    struct beam_row rows[15];
    int nr = 0;
    for (int c = 0; c < 2; c++) {
        for (int k = 0; k < 6; k++)
            rows[nr++] = (struct beam_row){k, 0, c ? SPH_BEAM_MIRROR : SPH_BEAM_FIXED};
        if (!c)
            rows[nr++] = (struct beam_row){3, 1, SPH_BEAM_FIXED};
        rows[nr++] = (struct beam_row){2, 2, c ? SPH_BEAM_MIRROR : SPH_BEAM_FIXED};
    }
    for (int q0 = 0; q0 < nr; q0++) {
        const struct beam_row *w = &rows[q0];
        /* reduced (the standard tier): two of the fifteen rows at the same dx,
         * the thesis' type 1 kernel and TLSPH, both with the thesis' clamp */
        if (r->quick && !(w->clamp == SPH_BEAM_FIXED &&
                          (w->variant == 1 || (w->variant == 0 && w->kernel == 0))))
            continue;
        const char *kern = SPH_BEAM_KERNELS[w->kernel];
        const char *cl = w->clamp == SPH_BEAM_MIRROR ? "mirrored clamp" : "fixed clamp";
        char extra[256];
        if (w->variant == 1)
            snprintf(extra, sizeof extra, "type: tlsph, viscosity: [0.1, 0.1], "
                                          "hourglass: 1.0");
        else
            snprintf(extra, sizeof extra, "%s%s", thesis,
                     w->variant == 2 ? ", artificial_stress_smoothing: true" : "");
        const double tol = BEAM_THESIS_ERR[w->kernel];
        char q[128], note[320];
        if (w->variant == 0)
            snprintf(q, sizeof q, "type %d %s, %s: mean tip deflection 1.5-3 ms", w->kernel + 1,
                     kern, cl);
        else if (w->variant == 1)
            snprintf(q, sizeof q, "TLSPH wendland, %s: mean tip deflection 1.5-3 ms", cl);
        else
            snprintf(q, sizeof q, "type 3 quintic_spline, averaged AS, %s: mean tip deflection",
                     cl);
        struct sph_beam_result res;
        int rc = sph_beam_run_or_note(r, q, kern, 1750.0, 1.2, extra, w->clamp, &res, err);
        if (rc)
            return rc;
        snprintf(note, sizeof note,
                 "tolerance = the thesis' own mean error for %s (%.2f %%; the thesis clamps "
                 "with fixed particles); deflection at 3 ms %.2f mm",
                 w->variant == 0 ? "this kernel" : w->variant == 1 ? "Wendland" : "the quintic",
                 tol, res.final * 1e3);
        if ((rc = vreport_check(r, q, "m", ref, isfinite(res.mean) ? res.mean : NAN, tol / 100.0,
                                true, "[Meng2021] Table 3.4 (static FL^3/3EI + 6FL/5GA)", note,
                                err)))
            return rc;
        if (!r->checks[r->n - 1].pass) {
            char gap[400];
            if (!isfinite(res.mean) && w->kernel == 2 && w->variant == 0)
                snprintf(gap, sizeof gap,
                         "GAP: the run went unstable (measured: the quintic blows up at ~1.1 ms "
                         "with either clamp; cause: the pointwise artificial stress R_i follows "
                         "particle-scale stress noise, a linear instability from t = 0 that "
                         "AV + XSPH damp for the other kernels; the averaged-AS row runs); see "
                         "docs/notes/validation-log.md");
            else if (!isfinite(res.mean)) /* the quintic's cause is not this row's */
                snprintf(gap, sizeof gap,
                         "GAP: the run went unstable (the info line names the step); this row "
                         "is not known to: its last full runs were stable (the pointwise AS "
                         "transient peaks below %g times the work put in); see "
                         "docs/notes/validation-log.md",
                         SPH_BEAM_ENERGY_BLOWUP);
            else
                snprintf(gap, sizeof gap,
                         "GAP: measured %.2f mm (%+.2f %%, tolerance %.2f %%): stable, smooth "
                         "run; %s; see docs/notes/validation-log.md",
                         res.mean * 1e3, (res.mean - ref) / ref * 100.0, tol,
                         w->clamp == SPH_BEAM_FIXED
                             ? "the fixed clamp's soft root (measured: 2.5-4 % more "
                               "deflection than the mirrored clamp)"
                             : "SPH bending at 10 rows is this much soft");
            vreport_mark_gap(r, gap);
        }
    }
    return SPALL_OK;
}

/* sph-plate: validation/sph_plate.c */
