/**
 * @file pen_sph_setup.c
 * @brief General deck builder and runner of the axisymmetric SPH
 *        penetration model (pen_sph_setup.h): the gelatin deck of
 *        validation/pen_sph.c generalised to any target, projectile and
 *        resolution, lengths scaled with the projectile diameter.
 *
 * Why scale with d: the thesis sizes its model by the projectile (L_sph =
 * 2 d around the shot line, dx1 from the projectile's element size, seed
 * 004 sec. 4.3.2 and 4.5.1), and a penetration scales with d at a fixed
 * v0 when the resistance is a stress (Eq. 4.6: P_max / d depends on v0
 * only).  The gelatin deck (d = 7.38 um) is the reference geometry, so the
 * builder at d = 7.38 um, dx1 = 0.75 um, depth 1 writes the gelatin deck.
 */
#include "validation/lattice_cases.h"
#include "validation/pen_sph_setup.h"
#include "validation/vpar.h"

#include "core/mathconst.h"
#include "core/particles.h"
#include "core/rigid.h"
#include "core/sim.h"
#include "spall/error.h"

#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The reference geometry: the gelatin deck's lengths [m] at d = 7.38 um. */
#define SETUP_D_REF 7.38e-6
#define SETUP_GAP_REF 0.25e-6
#define SETUP_CAVITY_REF 15.0e-6
static const double setup_r_ref[4] = {8e-6, 20e-6, 48e-6, 144e-6};
static const double setup_z_ref[4] = {100e-6, 130e-6, 170e-6, 250e-6};

struct pen_sph_target pen_sph_target_gelatin(double E)
{
    /* [Meng2021] Tab. 4.3; AV and XSPH of sec. 4.4.1; no failure, as
     * pen_sph_deck (validation/pen_sph.c explains why) */
    struct pen_sph_target t = {.name = "gelatin", .rho = 1030.0, .E = E, .nu = 0.499,
                               .A = 21.0e6, .B = 1.0e4, .n = 0.1, .fail = 0.0,
                               .c0 = 1520.0, .S = 1.8, .gamma = 0.0,
                               .av_a = 0.5, .av_b = 0.2, .xsph = 0.015};
    return t;
}

struct pen_sph_target pen_sph_target_sebs(double E)
{
    /* [Meng2021] Tab. 4.3 (B = 0.01 MPa); AV (2, 1) and XSPH 0.08 of sec. 4.5.1:
     * alpha_cs = 0.08 chosen from Fig. 4.21, (q_a, q_b) = (2, 1) "does not
     * lead to much difference" (Fig. 4.22); failure at sigma_vm = A as for
     * gelatin ("SEBS gel breaks after reaching maximum stress which is close
     * to the yield-stress value", sec. 4.3.1) */
    struct pen_sph_target t = {.name = "sebs", .rho = 875.0, .E = E, .nu = 0.495,
                               .A = 25.0e6, .B = 1.0e4, .n = 0.1, .fail = 25.0e6,
                               .c0 = 1520.0, .S = 1.87, .gamma = 0.0,
                               .av_a = 2.0, .av_b = 1.0, .xsph = 0.08};
    return t;
}

double pen_sph_setup_gap(const struct pen_sph_shot *s)
{
    return SETUP_GAP_REF * s->d / SETUP_D_REF;
}

static double round_up(double x, double q)
{
    return ceil(x / q - 1e-9) * q;
}

static int positive(double x)
{
    return isfinite(x) && x > 0.0;
}

static int check_inputs(const struct pen_sph_target *t, const struct pen_sph_shot *s,
                        const struct pen_sph_grid *g, struct spall_error *err)
{
    const struct {
        const char *what;
        double v;
    } need[] = {{"target density", t->rho},     {"Young's modulus", t->E},
                {"yield A", t->A},
                {"sound speed c0", t->c0},      {"projectile diameter", s->d},
                {"projectile density", s->rho_p}, {"impact speed", s->v0},
                {"dx1/d", g->dx1_d},            {"width", g->width},
                {"depth", g->depth},            {"end time", g->t_end}};
    for (size_t k = 0; k < sizeof need / sizeof need[0]; k++)
        if (!positive(need[k].v))
            return spall_error_set(err, SPALL_ERR_INPUT, "pen_sph_setup: %s must be > 0 (got %g)",
                                   need[k].what, need[k].v);
    if (!(t->nu > 0.0 && t->nu < 0.5))
        return spall_error_set(err, SPALL_ERR_INPUT,
                               "pen_sph_setup: Poisson's ratio must be in (0, 0.5) (got %g)",
                               t->nu);
    if (!(t->B >= 0.0 && t->n >= 0.0 && t->S >= 0.0 && t->gamma >= 0.0 && t->av_a >= 0.0 &&
          t->av_b >= 0.0 && t->av_length >= 0.0 && t->xsph >= 0.0 && g->cavity_depth >= 0.0 &&
          t->fail >= 0.0))
        return spall_error_set(err, SPALL_ERR_INPUT,
                               "pen_sph_setup: B, n, S, Gamma, AV, AV length, XSPH, failure "
                               "stress and cavity depth must be >= 0");
    if (!t->name || !*t->name)
        return spall_error_set(err, SPALL_ERR_INPUT, "pen_sph_setup: target has no name");
    return SPALL_OK;
}

#define SETUP_APPEND(...)                                                                   \
    do {                                                                                    \
        int w_ = snprintf(buf + off, off < len ? len - off : 0, __VA_ARGS__);               \
        off += w_ > 0 ? (size_t)w_ : 0;                                                     \
    } while (0)

int pen_sph_setup_deck(char *buf, size_t len, const struct pen_sph_target *t,
                       const struct pen_sph_shot *s, const struct pen_sph_grid *g,
                       struct spall_error *err)
{
    int rc = check_inputs(t, s, g, err);
    if (rc)
        return rc;
    const double scale = s->d / SETUP_D_REF, dx1 = g->dx1_d * s->d;
    double r[4], z[4];
    for (int k = 0; k < 4; k++) {
        /* level k's edges: multiples of level k+1's spacing (8 dx1 for the last) */
        double q = dx1 * (double)(1 << (k + 1 < 3 ? k + 1 : 3));
        r[k] = round_up(setup_r_ref[k] * scale * (k >= 2 ? g->width : 1.0), q);
        z[k] = round_up(setup_z_ref[k] * scale * g->depth, q);
    }
    const double R = 0.5 * s->d, M = s->rho_p * SPALL_PI * s->d * s->d * s->d / 6.0;
    const double cav = g->cavity_depth > 0.0 ? g->cavity_depth : SETUP_CAVITY_REF * scale;
    size_t off = 0;
    /* fail <= 0: no failure (the RADIOSS LAW3 reading of [Meng2021] sec. 4.3.2,
     * see validation/pen_sph.c); > 0: von Mises failure stress */
    char failure[64];
    if (t->fail > 0.0)
        snprintf(failure, sizeof failure, "failure: stress, failure_value: %.9g", t->fail);
    else
        snprintf(failure, sizeof failure, "failure: none");
    /* AV options only when set, so the default deck stays the gelatin deck */
    char avx[96] = "";
    if (t->av_length > 0.0)
        snprintf(avx, sizeof avx, ", viscosity_length: %.9g", t->av_length);
    if (t->av_balsara)
        snprintf(avx + strlen(avx), sizeof avx - strlen(avx), ", viscosity_switch: balsara");
    SETUP_APPEND("model: {type: sph, plane: axisymmetric, kernel: wendland, h_factor: 1.3,\n"
                 "        viscosity: [%.9g, %.9g]%s, xsph: %.9g, cavity_depth: %.9g}\n"
                 "materials:\n"
                 "  %s: {density: %.9g, youngs_modulus: %.9g, poisson_ratio: %.9g,\n"
                 "       eos: mie_gruneisen_ck, sound_speed: %.9g, hugoniot_slope: %.9g,\n"
                 "       gruneisen: %.9g, yield: power, yield_a: %.9g, yield_b: %.9g, "
                 "yield_n: %.9g,\n"
                 "       %s}\n"
                 "lattice: {type: square, spacing: %.9g}\n"
                 "geometry:\n",
                 t->av_a, t->av_b, avx, t->xsph, cav, t->name, t->rho, t->E, t->nu, t->c0, t->S,
                 t->gamma, t->A, t->B, t->n, failure, dx1);
    for (int k = 0; k < 4; k++)
        SETUP_APPEND("  l%d: {box: {min: [0, %.9g], max: [%.9g, 0]}}\n", k + 1, -z[k], r[k]);
    SETUP_APPEND("bodies:\n");
    for (int k = 0; k < 4; k++) {
        double sp = dx1 * (double)(1 << k);
        char geo[64];
        if (k == 0)
            snprintf(geo, sizeof geo, "l1");
        else
            snprintf(geo, sizeof geo, "{difference: [l%d, l%d]}", k + 1, k);
        SETUP_APPEND("  - {geometry: %s, material: %s, lattice: {spacing: %.9g, "
                     "origin: [%.9g, %.9g]}}\n",
                     geo, t->name, sp, 0.5 * sp, -0.5 * sp);
    }
    /* surface_contact: the gel particles' surfaces (dx1/2 ahead of their
     * centres) meet the sphere, whose effective radius is otherwise d/2 -
     * dx1/2 and grows with refinement (docs/notes/validation-log.md, pen-sph-gelatin,
     * "The rest: the entry") */
    char offset[64] = "";
    if (g->surface_contact)
        snprintf(offset, sizeof offset, ", contact_offset: %.9g", 0.5 * dx1);
    SETUP_APPEND("impactors:\n"
                 "  - {name: sphere, shape: sphere, position: [0, %.9g], radius: %.9g,\n"
                 "     mass: %.9g, velocity: [0, %.9g], gravity: false, contact: penalty%s%s}\n"
                 "run: {end_time: %.9g}\n",
                 R + pen_sph_setup_gap(s), R, M, -s->v0,
                 g->k_first_contact ? ",\n     stiffness_dt: first_contact" : "", offset,
                 g->t_end);
    if (off >= len)
        return spall_error_set(err, SPALL_ERR_INPUT,
                               "pen_sph_setup: deck needs %zu bytes, buffer has %zu", off + 1,
                               len);
    return SPALL_OK;
}

/* (h0^p - h1^p) / (h1^p - h2^p): rises with p for h0 > h1 > h2 */
static double rich_ratio(const double h[3], double p)
{
    return (pow(h[0], p) - pow(h[1], p)) / (pow(h[1], p) - pow(h[2], p));
}

int pen_richardson(const double h[3], const double f[3], double *p, double *f_inf,
                   struct spall_error *err)
{
    if (!(h[2] > 0.0 && h[1] > h[2] && h[0] > h[1]))
        return spall_error_set(err, SPALL_ERR_INPUT,
                               "pen_richardson: spacings must decrease (%g, %g, %g)", h[0], h[1],
                               h[2]);
    const double d01 = f[0] - f[1], d12 = f[1] - f[2];
    if (!(d01 * d12 > 0.0))
        return spall_error_set(err, SPALL_ERR_INPUT,
                               "pen_richardson: not monotonic (differences %g, %g): no "
                               "convergence order",
                               d01, d12);
    const double target = d01 / d12;
    double lo = 0.05, hi = 20.0;
    if (!(target > rich_ratio(h, lo) && target < rich_ratio(h, hi)))
        return spall_error_set(err, SPALL_ERR_INPUT,
                               "pen_richardson: differences %g then %g do not shrink as any "
                               "order p in [%g, %g] would make them",
                               d01, d12, lo, hi);
    for (int k = 0; k < 200 && hi - lo > 1e-12; k++) {
        double mid = 0.5 * (lo + hi);
        if (rich_ratio(h, mid) < target)
            lo = mid;
        else
            hi = mid;
    }
    *p = 0.5 * (lo + hi);
    const double C = d12 / (pow(h[1], *p) - pow(h[2], *p));
    *f_inf = f[2] - C * pow(h[2], *p);
    return SPALL_OK;
}

void pen_sph_outcome_free(struct pen_sph_outcome *o)
{
    free(o->t);
    free(o->P);
    o->t = o->P = NULL;
    o->nh = 0;
}

static int history_push(struct pen_sph_outcome *o, size_t *cap, double t, double P)
{
    if (o->nh == *cap) {
        size_t nc = *cap ? 2 * *cap : 1024;
        double *a = realloc(o->t, nc * sizeof *a);
        if (!a)
            return -1;
        o->t = a;
        double *b = realloc(o->P, nc * sizeof *b);
        if (!b)
            return -1;
        o->P = b;
        *cap = nc;
    }
    o->t[o->nh] = t;
    o->P[o->nh] = P;
    o->nh++;
    return 0;
}

int pen_sph_setup_run(struct vreport *r, const struct pen_sph_target *t,
                      const struct pen_sph_shot *s, const struct pen_sph_grid *g,
                      struct pen_sph_outcome *o, struct spall_error *err)
{
    char deck[4096];
    *o = (struct pen_sph_outcome){0};
    int rc = pen_sph_setup_deck(deck, sizeof deck, t, s, g, err);
    if (rc)
        return rc;
    struct sim *sim = NULL;
    if ((rc = vlat_build("pen_sph_setup", deck, &sim, err)))
        return rc;
    /* mpirun: the impactor's state is the same on every rank, the cavity
     * diameters and the energy are sums over all ranks (vpar.h) */
    if ((rc = vpar_distribute(r, sim, err))) {
        sim_destroy(&sim);
        return rc;
    }
    if (!sim->rigid || sim->rigid->n < 1) {
        sim_destroy(&sim);
        return spall_error_set(err, SPALL_ERR_INTERNAL, "pen_sph_setup: deck has no impactor");
    }
    const struct impactor *im = &sim->rigid->im[0];
    const double R = im->radius, t_contact = pen_sph_setup_gap(s) / s->v0;
    const double e_in = 0.5 * im->mass * s->v0 * s->v0;
    size_t cap = 0;
    o->pmax = -INFINITY;
    o->n = vpar_n(sim);
    double t0 = omp_get_wtime();
    while (!sim_done(sim) && !rc) {
        if ((rc = sim_step(sim, err)))
            break;
        const double P = -(im->x[1] - R), tc = sim->t - t_contact;
        if (P > o->pmax) {
            o->pmax = P;
            o->t_pmax = tc;
        }
        o->d1max = fmax(o->d1max, vlat_history(sim, "cavity_D1 [m]"));
        o->d2max = fmax(o->d2max, vlat_history(sim, "cavity_D2 [m]"));
        if (sim->step % 10 == 0 && history_push(o, &cap, tc, P)) {
            rc = spall_error_set(err, SPALL_ERR_NOMEM, "out of memory (pen_sph_setup history)");
            break;
        }
        o->p_end = P;
        o->v_end = -im->v[1];
        if (tc > 0.0 && !(im->v[1] < 0.0) && !o->at_rest) {
            o->at_rest = 1; /* P_max reached; the cavity may still grow */
            if (!(g->t_rebound > 0.0))
                break;
        }
        if (o->at_rest && g->t_rebound > 0.0) {
            /* rebound ([Meng2021] sec. 5: observed after P_max, never
             * modelled there): V > 0 is upward, the sphere leaving */
            if (!o->rebounded && im->v[1] > 0.0) {
                o->rebounded = 1;
                o->t_rev = tc;
            }
            if (o->rebounded && im->v[1] > o->v_reb) {
                o->v_reb = im->v[1];
                o->t_reb = tc;
            }
            if (tc >= g->t_rebound)
                break;
        }
    }
    o->recovery = o->pmax - o->p_end;
    o->secs = omp_get_wtime() - t0;
    sim_update_energy(sim);
    o->balance = sim->energy.balance / e_in;
    sim_destroy(&sim);
    if (rc)
        pen_sph_outcome_free(o);
    return rc;
}
