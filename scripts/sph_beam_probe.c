/**
 * @file sph_beam_probe.c
 * @brief Diagnostic runs of the sph-beam-large cantilever (docs/validation.md,
 *        "Why the updated form tears at the clamp corner"): histories of the
 *        tension-side clamp corner particle (0.5, 4.5) mm -- its stress, the
 *        gap to its ghost / fixed partner, the artificial stress, the CSPM
 *        matrix, and the x-acceleration of the corner split into the pairs
 *        across the clamp plane and the pairs inside the beam (stress, AS and
 *        AV parts).  Not part of the build; scripts/sph_beam_probe.sh
 *        compiles it against build/libspall.a.
 *
 * usage: sph_beam_probe KERNEL fixed|mirror "EXTRA MODEL KEYS" END SAMPLE
 *                       [FORCE] [DT_FACTOR] [DX_MM]
 * env:   LOAD=point (the load on the one tip particle nearest mid-depth;
 *        default: shared by the tip column), RAMP=linear|quadratic|step,
 *        CLAMP_COLS=n (fixed clamp depth in columns, default 3),
 *        TI=predictor_corrector (default leapfrog), CS=alpha (conservative
 *        smoothing of the velocity after each step, the thesis' Eq. 2.27
 *        read as a velocity update; default 0 = off),
 *        HFAC (default 1.4).
 */
#include "validation/lattice_cases.h"

#include "core/neighbor.h"
#include "core/particles.h"
#include "core/sim.h"
#include "models/sph/sph_internal.h"
#include "models/sph/sph_kernels.h"
#include "spall/error.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static size_t find(const struct particles *p, double x, double y)
{
    size_t best = 0;
    double b = INFINITY;
    for (size_t i = 0; i < p->n; i++) {
        double d = hypot(p->x0[0][i] - x, p->x0[1][i] - y);
        if (d < b) {
            b = d;
            best = i;
        }
    }
    return best;
}

/* x-acceleration of particle i split into partners across the plane x = 0
 * (k = 0) and inside the beam (k = 1): stress, AS, AV parts.  Mirrored
 * clamp: the ghosts are rebuilt as the images of the free particles (the
 * engine puts them back at rest after each step). */
static void split(const struct model *m, const struct particles *p, size_t i, double out[2][3])
{
    memset(out, 0, 6 * sizeof(double));
    const double hi = m->h[i], hd = hi * hi;
    double Wd, Fd;
    sph_kernel_eval(m->opt.kernel, m->alpha, m->dx[i], hi, hd, &Wd, &Fd);
    const double ri2 = 1.0 / (m->rho[i] * m->rho[i]);
    for (size_t j = 0; j < p->n; j++) {
        if (j == i)
            continue;
        for (int img = 0; img < 2; img++) {
            double xj = p->x[0][j], yj = p->x[1][j], vxj = p->v[0][j], vyj = p->v[1][j];
            double Bj[4] = {m->Bi[0][j], m->Bi[1][j], m->Bi[3][j], m->Bi[4][j]};
            if (img)
                continue; /* the ghosts are in place (sph_clamp_begin) */
            double xij[2] = {p->x[0][i] - xj, p->x[1][i] - yj};
            double r = hypot(xij[0], xij[1]);
            if (r >= m->qmax * hi)
                continue;
            double W, F;
            sph_kernel_eval(m->opt.kernel, m->alpha, r, hi, hd, &W, &F);
            double g0[2] = {xij[0] * F, xij[1] * F}, gi[2], gj[2];
            for (int b = 0; b < 2; b++) {
                gi[b] = m->Bi[0 * 3 + b][i] * g0[0] + m->Bi[1 * 3 + b][i] * g0[1];
                gj[b] = Bj[0 * 2 + b] * g0[0] + Bj[1 * 2 + b] * g0[1];
            }
            const double rj2 = 1.0 / (m->rho[j] * m->rho[j]), mj = m->m2[j];
            double st = (m->sig[SXX][i] * gi[0] + m->sig[SXY][i] * gi[1]) * ri2 +
                        (m->sig[SXX][j] * gj[0] + m->sig[SXY][j] * gj[1]) * rj2;
            double f1 = W / Wd, fn = f1 * f1 * f1 * f1;
            double as = fn * ((m->R[SXX][i] + m->R[SXX][j]) * g0[0] +
                              (m->R[SXY][i] + (img ? m->R[SXY][j] : m->R[SXY][j])) * g0[1]);
            double vx = (p->v[0][i] - vxj) * xij[0] + (p->v[1][i] - vyj) * xij[1], Pi = 0.0;
            if (vx < 0.0) {
                double mu = hi * vx / (r * r + 0.01 * hi * hi);
                double cb = 0.5 * (m->c[i] + m->c[j]);
                Pi = (-m->opt.av_a * cb * mu + m->opt.av_b * mu * mu) /
                     (0.5 * (m->rho[i] + m->rho[j]));
            }
            const int k = (img || p->x0[0][j] < 0.0) ? 0 : 1;
            out[k][0] += mj * st;
            out[k][1] += mj * as;
            out[k][2] += mj * (-Pi * g0[0]);
        }
    }
}

/* Conservative smoothing of the velocity (seed 004 Eq. 2.27 read as a
 * velocity update, flow chart step 9): v_i += a sum_j 2 m_j/(rho_i + rho_j)
 * (v_j - v_i) W_ij over the current neighbours (ghosts in place), free
 * particles only; the kinetic energy it removes is returned. */
static double smooth_velocity(struct model *m, struct sim *s, double a, double *dv[2])
{
    struct particles *p = s->p;
    const size_t n = p->n;
    if (m->clamp)
        sph_clamp_begin(m, s);
    double ke0 = 0.0, ke1 = 0.0;
    for (size_t i = 0; i < n; i++) {
        dv[0][i] = dv[1][i] = 0.0;
        if (s->no_drift_velocity[i]) /* velocity prescribed by a BC */
            continue;
        const double hi = m->h[i];
        for (size_t k = m->nl->offset[i]; k < m->nl->offset[i + 1]; k++) {
            size_t j = (size_t)m->nl->idx[k];
            double r = hypot(p->x[0][i] - p->x[0][j], p->x[1][i] - p->x[1][j]);
            if (r >= m->qmax * hi)
                continue;
            double W, F;
            sph_kernel_eval(m->opt.kernel, m->alpha, r, hi, hi * hi, &W, &F);
            double w = a * 2.0 * m->m2[j] / (m->rho[i] + m->rho[j]) * W;
            dv[0][i] += w * (p->v[0][j] - p->v[0][i]);
            dv[1][i] += w * (p->v[1][j] - p->v[1][i]);
        }
    }
    if (m->clamp)
        sph_clamp_end(m, s);
    for (size_t i = 0; i < n; i++) {
        if (s->no_drift_velocity[i]) /* velocity prescribed by a BC */
            continue;
        ke0 += 0.5 * p->mass[i] * (p->v[0][i] * p->v[0][i] + p->v[1][i] * p->v[1][i]);
        p->v[0][i] += dv[0][i];
        p->v[1][i] += dv[1][i];
        ke1 += 0.5 * p->mass[i] * (p->v[0][i] * p->v[0][i] + p->v[1][i] * p->v[1][i]);
    }
    return ke0 - ke1;
}

int main(int argc, char **argv)
{
    if (argc < 6) {
        fprintf(stderr, "usage: %s KERNEL fixed|mirror EXTRA END SAMPLE [FORCE] [DTF] [DX_MM]\n",
                argv[0]);
        return 2;
    }
    const char *kern = argv[1], *extra = argv[3];
    const int mirror = !strcmp(argv[2], "mirror");
    const double tend = atof(argv[4]), samp = atof(argv[5]);
    const double force = argc > 6 ? atof(argv[6]) : 17500.0;
    const double dtf = argc > 7 ? atof(argv[7]) : 0.5;
    const double dx = (argc > 8 ? atof(argv[8]) : 1.0) * 1e-3;
    const double hfac = getenv("HFAC") ? atof(getenv("HFAC")) : 1.4;
    const int cols = getenv("CLAMP_COLS") ? atoi(getenv("CLAMP_COLS")) : 3;
    const int point = getenv("LOAD") && !strcmp(getenv("LOAD"), "point");
    const char *ramp = getenv("RAMP") ? getenv("RAMP") : "quadratic";
    char deck[4096], fn[160], tipbox[160];
    if (!strcmp(ramp, "step"))
        snprintf(fn, sizeof fn, "{type: constant}");
    else
        snprintf(fn, sizeof fn, "{type: %s_ramp, duration: 1.5e-3}", ramp);
    /* point load: the tip particle just above mid-depth (x = 99.5, y = 0.5 mm) */
    if (point)
        snprintf(tipbox, sizeof tipbox, "{min: [%.17g, %.17g], max: [0.101, %.17g]}",
                 0.1 - dx, 0.0, dx);
    else
        snprintf(tipbox, sizeof tipbox, "{min: [%.17g, -1], max: [0.101, 1]}", 0.1 - dx);
    const double xmin = mirror ? -0.005 : -cols * dx;
    snprintf(deck, sizeof deck,
             "model: {type: sph, kernel: %s, h_factor: %g, plane: stress,\n"
             "        time_integration: %s, %s%s}\n"
             "materials: {steel: {density: 7800, youngs_modulus: 210.0e9, poisson_ratio: 0.3}}\n"
             "lattice: {type: square, spacing: %.17g, origin: [%.17g, %.17g], "
             "thickness: 1.0e-3}\n"
             "body: {geometry: {box: {min: [%.17g, -0.005], max: [0.1, 0.005]}}, "
             "material: steel}\n"
             "groups:\n"
             "  clamp: {box: {min: [-0.01, -1], max: [0.0, 1]}}\n"
             "  tip: {box: %s}\n"
             "boundary_conditions:\n"
             "  - {group: clamp, type: fixed}\n"
             "  - {group: tip, type: force, components: [y], value: %.17g,\n"
             "     function: %s}\n"
             "run: {end_time: %.17g, dt_factor: %g}\n",
             kern, hfac, getenv("TI") ? getenv("TI") : "leapfrog", extra,
             mirror ? ", clamp: {group: clamp, point: [0, 0], normal: [1, 0]}" : "", dx,
             0.5 * dx, 0.5 * dx, xmin, tipbox, -force, fn, tend, dtf);
    struct sim *s = NULL;
    struct spall_error err = {0};
    if (vlat_build("sph_beam_probe", deck, &s, &err)) {
        fprintf(stderr, "%s\n", err.msg);
        return 1;
    }
    struct particles *p = s->p;
    struct model *m = s->model;
    const size_t c = find(p, 0.5 * dx, 0.005 - 0.5 * dx), nx = find(p, 1.5 * dx, 0.005 - 0.5 * dx);
    const size_t cl = find(p, -0.5 * dx, 0.005 - 0.5 * dx), bot = find(p, 0.5 * dx, 0.5 * dx - 0.005);
    const size_t tip = find(p, 0.1 - 0.5 * dx, 0.5 * dx);
    const double E = 210e9, rho0 = 7800;
    int rc = sim_initial_forces(s, &err);
    double next = 0.0;
    printf("# t[ms] tip[mm] gapC/dx gapN/dx sxx/E syy/E sxy/E rho/rho0 Rxx*rho^2/sxx detB "
           "|Binv| vC[m/s] | ax across: stress AS AV | ax beam: stress AS AV | bottom sxx/E "
           "gapB/dx | fallbacks\n");
    const struct group *tg = &s->groups[sim_find_group(s, "tip")];
    double acc = 0.0, tacc = 0.0, umax = 0.0;
    const double cs = getenv("CS") ? atof(getenv("CS")) : 0.0;
    double *dv[2] = {calloc(p->n, sizeof(double)), calloc(p->n, sizeof(double))}, kelost = 0.0;
    while (!rc && !sim_done(s)) {
        const double dt = s->dt;
        if ((rc = sim_step(s, &err)))
            break;
        double uy = 0.0; /* tip column mean, as sph_beam_run (validation/sph_beam_plate.c) */
        for (size_t q = 0; q < tg->n; q++)
            uy += p->x[1][tg->idx[q]] - p->x0[1][tg->idx[q]];
        uy /= (double)tg->n;
        umax = fmax(umax, -uy);
        if (s->t >= 1.5e-3) {
            acc += -uy * dt;
            tacc += dt;
        }
        if (cs > 0.0)
            kelost += smooth_velocity(s->model, s, cs, dv);
        if (s->t + 1e-12 < next)
            continue;
        next += samp;
        const double gx = mirror ? 2.0 * p->x[0][c] : p->x[0][c] - p->x[0][cl];
        const double gn = hypot(p->x[0][nx] - p->x[0][c], p->x[1][nx] - p->x[1][c]);
        const double gb = mirror ? 2.0 * p->x[0][bot] : p->x[0][bot] - p->x[0][find(p, -0.5 * dx, 0.5 * dx - 0.005)];
        double B[4] = {m->Bi[0][c], m->Bi[1][c], m->Bi[3][c], m->Bi[4][c]};
        double det = B[0] * B[3] - B[1] * B[2];
        double nrm = sqrt(B[0] * B[0] + B[1] * B[1] + B[2] * B[2] + B[3] * B[3]);
        double sp[2][3];
        if (mirror) /* the ghosts at their images, as in the force call */
            sph_clamp_begin(m, s);
        split(m, p, c, sp);
        if (mirror)
            sph_clamp_end(m, s);
        double r2 = m->rho[c] * m->rho[c];
        printf("%.4f %7.2f %.3f %.3f %+.4f %+.4f %+.4f %.4f %+.3f %.3f %.3f %8.2f | %+.3e %+.3e "
               "%+.3e | %+.3e %+.3e %+.3e | %+.4f %.3f | %zu | f/m %+.3e\n",
               s->t * 1e3, -(p->x[1][tip] - p->x0[1][tip]) * 1e3, gx / dx, gn / dx,
               m->sig[SXX][c] / E, m->sig[SYY][c] / E, m->sig[SXY][c] / E, m->rho[c] / rho0,
               m->sig[SXX][c] != 0 ? m->R[SXX][c] * r2 / m->sig[SXX][c] : 0.0, 1.0 / det, nrm,
               hypot(p->v[0][c], p->v[1][c]), sp[0][0], sp[0][1], sp[0][2], sp[1][0], sp[1][1],
               sp[1][2], m->sig[SXX][bot] / E, gb / dx, m->cspm_fallbacks, p->f[0][c] / p->mass[c]);
        fflush(stdout);
        if (!(fabs(p->x[1][tip]) < 1.0) || gx / dx > 3.0)
            break; /* torn: enough said */
    }
    { /* the largest stretch of an initially adjacent pair, and where */
        double best = 1.0;
        size_t bi = 0, bj = 0;
        for (size_t i = 0; i < p->n; i++)
            for (size_t j = i + 1; j < p->n; j++) {
                double X = p->x0[0][j] - p->x0[0][i], Y = p->x0[1][j] - p->x0[1][i];
                double R2 = X * X + Y * Y;
                if (R2 > 1.0201 * dx * dx)
                    continue;
                double st = hypot(p->x[0][j] - p->x[0][i], p->x[1][j] - p->x[1][i]) / sqrt(R2);
                if (st > best) {
                    best = st;
                    bi = i;
                    bj = j;
                }
            }
        printf("# STRETCH max %.3f between (%.1f, %.1f) and (%.1f, %.1f) mm\n", best,
               p->x0[0][bi] * 1e3, p->x0[1][bi] * 1e3, p->x0[0][bj] * 1e3, p->x0[1][bj] * 1e3);
    }
    printf("# RESULT t_end %.4f ms, tip-column mean deflection 1.5-3 ms %.2f mm (%+.2f %% vs "
           "81.1), max %.2f mm\n",
           s->t * 1e3, tacc > 0 ? acc / tacc * 1e3 : NAN,
           tacc > 0 ? (acc / tacc / 81.1e-3 - 1.0) * 100.0 : NAN, umax * 1e3);
    printf("# velocity smoothing removed %.4g J of kinetic energy\n", kelost);
    free(dv[0]);
    free(dv[1]);
    if (rc)
        printf("# STOP %s at t = %.4f ms\n", err.msg, s->t * 1e3);
    sim_destroy(&s);
    return 0;
}
