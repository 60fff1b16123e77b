/*
 * The model contract: every registered model and formulation must pass these
 * checks.  The list comes from the registry itself (models/registry.c:
 * model_names, model_find) and each model's own fixtures (struct
 * model_ops.fixtures, src/models/<model>/<model>_fixture.c): adding a model
 * is a folder and one registry line, and this test picks it up; a model
 * without a fixture fails here.
 *
 * A fixture gives the deck's model and material (named `m`) and a lattice;
 * the test fills a disc (2D) or sphere (3D) centred on a lattice site with
 * it, perturbs the state deterministically and checks, for each fixture:
 *   1. Newton's third law: |sum f| <= 1e-12 sum |f| and |sum r x f| <= 1e-12
 *      sum |r||f| (r from the centre of mass) in every step, and momentum
 *      and angular momentum kept to 1e-12 of sum m|v| and sum m|x||v|;
 *   2. frame invariance: the run from R S + c (R a rotation, c a
 *      translation, applied to the reference configuration through the
 *      deck's lattice origin and angle, and to the perturbation) equals R
 *      times the run from S, to 1e-10 of the largest displacement/velocity;
 *   3. second-order energy error: max |energy balance| over the same time
 *      at dt and dt/2, ratio in [3, 5];
 *   4. bitwise the same state on 1 and 2 OpenMP threads, on a body larger
 *      than SPALL_OMP_MIN_PARTICLES so that every parallel loop runs split;
 *   5. field_pack / field_unpack of every stored registered per-particle
 *      field (what migration and restart use) restores it byte for byte.
 * A fixture may state an allowance (torque, a lattice-symmetric rotation)
 * only for a property of its method, with the measured value (struct
 * model_fixture.why); the test prints it.  Each check reports every
 * fixture before it fails.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "core/fields.h"
#include "core/mathconst.h"
#include "core/lattice_gen.h"
#include "core/particles.h"
#include "core/sim.h"
#include "io/deck.h"
#include "io/deck_build.h"
#include "core/model.h"
#include "models/registry.h"
#include "spall/error.h"

#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MAX_FIXTURES 64
/* Steps of a contract run: long enough for waves to cross the body (~9
 * spacings) once or more, short enough for a few seconds under ASan. */
#define RUN_STEPS 40
/* Body radius in spacings: 2D ~60, 3D ~100-150 particles; not close to a
 * lattice shell radius, so boundary sites are kept or dropped the same way
 * in a rotated frame. */
#define RADIUS_2D 4.3
#define RADIUS_3D 2.9
#define DEG (SPALL_PI / 180.0)

/* A rigid motion: x -> R x + c.  2D: R is the deck's lattice angle.  3D:
 * lattices have no angle key, so R is the 120 degree rotation about
 * (1, 1, 1) (x -> y -> z -> x), which maps the cubic lattices and a sphere
 * centred on a site onto themselves: the deck only moves the origin. */
struct frame {
    double angle_deg; /**< 2D: the angle; 3D: any non-zero value selects R */
    double c[3];
};

static const struct frame base_frame = {0.0, {0.0, 0.0, 0.0}};

/* Every fixture of every registered model. */
static size_t all_fixtures(const struct model_fixture **out)
{
    size_t n = 0;
    for (const char *const *name = model_names(); *name; name++) {
        const struct model_ops *ops = model_find(*name);
        assert_non_null(ops);
        if (!ops->fixtures || !ops->fixtures[0].label) {
            print_error("model '%s' has no contract fixture (struct model_ops.fixtures, "
                        "src/models/<model>/*_fixture.c)\n",
                        *name);
            fail();
        }
        for (const struct model_fixture *f = ops->fixtures; f->label; f++) {
            assert_true(n < MAX_FIXTURES);
            out[n++] = f;
        }
    }
    assert_true(n > 0);
    return n;
}

/* One check of one fixture: prints what failed and counts it (every
 * fixture is reported before the test fails). */
static int failed(int ok, const struct model_fixture *fx, const char *what, double value)
{
    if (!ok)
        printf("  FAIL %s: %s (%.3e)\n", fx->label, what, value);
    return !ok;
}

/* Why a fixture has an allowance, printed with its result. */
static void print_why(const struct model_fixture *fx)
{
    if (fx->why)
        printf("    (%s: %s)\n", fx->label, fx->why);
}

/* Run one check (returning its failures) on every fixture; fail after all
 * were reported. */
static void for_every_fixture(int (*check)(const struct model_fixture *fx))
{
    const struct model_fixture *fx[MAX_FIXTURES];
    size_t n = all_fixtures(fx);
    int bad = 0;
    for (size_t k = 0; k < n; k++)
        bad += check(fx[k]);
    assert_int_equal(bad, 0);
}

static int fixture_dim(const struct model_fixture *fx)
{
    int kind = lattice_kind_from_name(fx->lattice);
    assert_true(kind >= 0);
    return lattice_kind_dim((enum lattice_kind)kind);
}

/* out = R a, or R^T a with @p inverse. */
static void rotate_dir(const struct frame *fr, int dim, const double a[3], double out[3],
                       int inverse)
{
    double R[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    if (dim == 2) {
        double t = fr->angle_deg * DEG;
        R[0][0] = R[1][1] = cos(t);
        R[1][0] = sin(t);
        R[0][1] = -R[1][0];
        R[2][2] = 0.0; /* no third component in 2D */
    } else if (fr->angle_deg != 0.0) { /* x -> y -> z -> x */
        static const double C[3][3] = {{0, 0, 1}, {1, 0, 0}, {0, 1, 0}};
        memcpy(R, C, sizeof R);
    }
    for (int r = 0; r < 3; r++) {
        out[r] = 0.0;
        for (int c = 0; c < 3; c++)
            out[r] += (inverse ? R[c][r] : R[r][c]) * a[c];
    }
}

static void rotate(const struct frame *fr, int dim, const double a[3], double out[3])
{
    rotate_dir(fr, dim, a, out, 0);
}

/* The fixture's body of radius radius_dx spacings in frame @p fr, at a fixed
 * step (the contract compares runs step by step). */
static struct sim *build(const struct model_fixture *fx, const struct frame *fr, double radius_dx)
{
    const int dim = fixture_dim(fx);
    char centre[128], angle[64] = "", text[4096];
    if (dim == 2) {
        snprintf(centre, sizeof centre, "[%.17g, %.17g]", fr->c[0], fr->c[1]);
        snprintf(angle, sizeof angle, ", angle: %.17g", fr->angle_deg);
    } else {
        snprintf(centre, sizeof centre, "[%.17g, %.17g, %.17g]", fr->c[0], fr->c[1], fr->c[2]);
    }
    int len = snprintf(text, sizeof text,
                       "%slattice: {type: %s, spacing: %.17g, origin: %s%s}\n"
                       "body: {geometry: {sphere: {center: %s, radius: %.17g}}, material: m}\n"
                       "run: {steps: 1000}\n",
                       fx->deck, fx->lattice, fx->spacing, centre, angle, centre,
                       radius_dx * fx->spacing);
    assert_true(len > 0 && (size_t)len < sizeof text);
    struct deck *d = NULL;
    struct sim *s = NULL;
    struct run_output ro;
    struct spall_error err = {0};
    int rc = deck_load_string(&d, fx->label, text, &err);
    if (!rc)
        rc = deck_build_sim(d, &s, &ro, &err);
    deck_destroy(&d);
    if (rc) {
        print_error("%s: %s\n", fx->label, err.msg);
        fail();
    }
    s->adaptive_dt = false;
    return s;
}

/* Deterministic pseudo-random number in [-1, 1) (splitmix64 of @p key). */
static double unit_random(uint64_t key)
{
    uint64_t z = key + 0x9e3779b97f4a7c15ull;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    z ^= z >> 31;
    return (double)(z >> 11) * 0x1.0p-52 - 1.0;
}

/* Velocity scale of the perturbations: 1e-4 of the sound speed, estimated
 * from the stable step, so strains stay ~1e-3 (elastic for every fixture). */
static double velocity_scale(const struct sim *s)
{
    return 1e-4 * s->lattice.spacing / s->dt_limit;
}

/* Random displacement (1e-3 spacing) and velocity of base particle i. */
static void perturbation(const struct sim *s, size_t i, double du[3], double v[3])
{
    const double vs = velocity_scale(s);
    for (int d = 0; d < 3; d++) {
        du[d] = d < s->dim ? 1e-3 * s->lattice.spacing * unit_random(6 * i + (uint64_t)d) : 0.0;
        v[d] = d < s->dim ? vs * unit_random(6 * i + 3 + (uint64_t)d) : 0.0;
    }
}

/* Give particle j of @p s the perturbation of base particle match[j] (j
 * without @p match) rotated into frame @p fr; recompute the forces. */
static void set_state(struct sim *s, const struct sim *base, const struct frame *fr,
                      const size_t *match)
{
    struct particles *p = s->p;
    for (size_t j = 0; j < p->n; j++) {
        double du[3], v[3], rdu[3], rv[3];
        perturbation(base, match ? match[j] : j, du, v);
        rotate(fr, s->dim, du, rdu);
        rotate(fr, s->dim, v, rv);
        for (int d = 0; d < s->dim; d++) {
            p->x[d][j] = p->x0[d][j] + rdu[d];
            p->v[d][j] = rv[d];
        }
    }
    struct spall_error err = {0};
    if (sim_initial_forces(s, &err)) {
        print_error("%s\n", err.msg);
        fail();
    }
}

static void run_steps(struct sim *s, long n, const char *label)
{
    struct spall_error err = {0};
    for (long k = 0; k < n; k++)
        if (sim_step(s, &err)) {
            print_error("%s: step %ld: %s\n", label, k, err.msg);
            fail();
        }
}

/* Check 1 on the current forces: returns |sum f| / sum |f| and sets
 * @p torque_ratio = |sum r x f| / sum |r||f| (r from the centre of mass). */
static double newton_residual(const struct sim *s, double *torque_ratio)
{
    const struct particles *p = s->p;
    double com[3] = {0, 0, 0}, mass = 0.0;
    for (size_t i = 0; i < p->n; i++) {
        mass += p->mass[i];
        for (int d = 0; d < s->dim; d++)
            com[d] += p->mass[i] * p->x[d][i];
    }
    double F[3] = {0, 0, 0}, T[3] = {0, 0, 0}, sf = 0.0, st = 0.0;
    for (size_t i = 0; i < p->n; i++) {
        double r[3] = {0, 0, 0}, f[3] = {0, 0, 0};
        for (int d = 0; d < s->dim; d++) {
            r[d] = p->x[d][i] - com[d] / mass;
            f[d] = p->f[d][i];
            F[d] += f[d];
        }
        T[0] += r[1] * f[2] - r[2] * f[1];
        T[1] += r[2] * f[0] - r[0] * f[2];
        T[2] += r[0] * f[1] - r[1] * f[0];
        double fn = sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
        sf += fn;
        st += sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]) * fn;
    }
    *torque_ratio = sqrt(T[0] * T[0] + T[1] * T[1] + T[2] * T[2]) / st;
    return sqrt(F[0] * F[0] + F[1] * F[1] + F[2] * F[2]) / sf;
}

/* Momentum P, angular momentum L about the origin, and their scales
 * sum m|v|, sum m|x||v|. */
static void momenta(const struct sim *s, double P[3], double L[3], double *sp, double *sl)
{
    const struct particles *p = s->p;
    memset(P, 0, 3 * sizeof *P);
    memset(L, 0, 3 * sizeof *L);
    *sp = *sl = 0.0;
    for (size_t i = 0; i < p->n; i++) {
        double x[3] = {0, 0, 0}, v[3] = {0, 0, 0}, m = p->mass[i];
        for (int d = 0; d < s->dim; d++) {
            x[d] = p->x[d][i];
            v[d] = p->v[d][i];
            P[d] += m * v[d];
        }
        L[0] += m * (x[1] * v[2] - x[2] * v[1]);
        L[1] += m * (x[2] * v[0] - x[0] * v[2]);
        L[2] += m * (x[0] * v[1] - x[1] * v[0]);
        double vn = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
        *sp += m * vn;
        *sl += m * sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]) * vn;
    }
}

static double radius_of(const struct model_fixture *fx)
{
    return fixture_dim(fx) == 2 ? RADIUS_2D : RADIUS_3D;
}

static double dist3(const double a[3], const double b[3])
{
    return sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                (a[2] - b[2]) * (a[2] - b[2]));
}

/* Component array @p x of particle i as a 3-vector (zero beyond dim). */
static void vec_of(int dim, double *const x[3], size_t i, double out[3])
{
    for (int d = 0; d < 3; d++)
        out[d] = d < dim ? x[d][i] : 0.0;
}

/* 1. Newton's third law and the momenta. */
static int newton_momentum(const struct model_fixture *fx)
{
    int bad = 0;
    struct sim *s = build(fx, &base_frame, radius_of(fx));
    set_state(s, s, &base_frame, NULL);
    double P0[3], L0[3], sp, sl, P[3], L[3], spk, slk;
    momenta(s, P0, L0, &sp, &sl);
    double worst_f = 0.0, worst_t = 0.0, worst_p = 0.0, worst_l = 0.0;
    for (long step = 0; step <= RUN_STEPS; step++) {
        if (step > 0)
            run_steps(s, 1, fx->label);
        double tr, fr = newton_residual(s, &tr);
        worst_f = fmax(worst_f, fr);
        worst_t = fmax(worst_t, tr);
        momenta(s, P, L, &spk, &slk);
        worst_p = fmax(worst_p, dist3(P, P0) / sp);
        worst_l = fmax(worst_l, dist3(L, L0) / sl);
    }
    printf("  %-28s %zu particles: |sum f|/sum|f| %.2e, |sum r x f|/sum|r||f| %.2e, "
           "momentum %.2e, angular momentum %.2e\n",
           fx->label, s->p->n, worst_f, worst_t, worst_p, worst_l);
    if (fx->torque > 0.0)
        print_why(fx);
    /* pair forces cancel to round-off: ~1e-16 per pair, summed (1e-17
     * measured); a model whose pair forces are not central may have a
     * torque, stated with its measured value in its fixture */
    const double tol_t = fmax(1e-12, fx->torque);
    bad += failed(worst_f <= 1e-12, fx, "net force", worst_f);
    bad += failed(worst_t <= tol_t, fx, "net torque", worst_t);
    bad += failed(worst_p <= 1e-12, fx, "momentum drift", worst_p);
    bad += failed(worst_l <= tol_t, fx, "angular momentum drift", worst_l);
    sim_destroy(&s);
    return bad;
}

/* Base particle matching each particle of @p s (built in frame @p fr): the
 * one whose reference position maps onto it. */
static size_t *match_particles(const struct sim *s, const struct sim *base, const struct frame *fr)
{
    assert_int_equal(s->p->n, base->p->n);
    size_t n = s->p->n, *match = malloc(n * sizeof *match);
    assert_non_null(match);
    for (size_t j = 0; j < n; j++) {
        double x[3], y[3], rel[3];
        vec_of(s->dim, s->p->x0, j, x);
        for (int d = 0; d < 3; d++)
            rel[d] = x[d] - fr->c[d];
        rotate_dir(fr, s->dim, rel, y, 1);
        size_t best = n;
        for (size_t i = 0; i < n; i++) {
            double xb[3];
            vec_of(base->dim, base->p->x0, i, xb);
            if (dist3(xb, y) < 1e-6 * s->lattice.spacing)
                best = i;
        }
        assert_true(best < n);
        match[j] = best;
    }
    return match;
}

/* 2. Run from S and from R S + c; compare R(result) with the second run. */
static void frame_invariance(const struct model_fixture *fx, const struct frame *fr,
                             double *err_u, double *err_v)
{
    double rad = radius_of(fx);
    struct sim *a = build(fx, &base_frame, rad), *b = build(fx, fr, rad);
    size_t *match = match_particles(b, a, fr);
    set_state(a, a, &base_frame, NULL);
    set_state(b, a, fr, match);
    b->dt = a->dt;
    run_steps(a, RUN_STEPS, fx->label);
    run_steps(b, RUN_STEPS, fx->label);
    double umax = 0.0, vmax = 0.0, eu = 0.0, ev = 0.0;
    const int dim = a->dim;
    for (size_t j = 0; j < b->p->n; j++) {
        size_t i = match[j];
        double xa[3], x0a[3], va[3], xb[3], x0b[3], vb[3], ua[3], ub[3], rua[3], rva[3];
        vec_of(dim, a->p->x, i, xa);
        vec_of(dim, a->p->x0, i, x0a);
        vec_of(dim, a->p->v, i, va);
        vec_of(dim, b->p->x, j, xb);
        vec_of(dim, b->p->x0, j, x0b);
        vec_of(dim, b->p->v, j, vb);
        for (int d = 0; d < 3; d++) {
            ua[d] = xa[d] - x0a[d];
            ub[d] = xb[d] - x0b[d];
        }
        rotate(fr, dim, ua, rua);
        rotate(fr, dim, va, rva);
        umax = fmax(umax, dist3(ua, (double[3]){0, 0, 0}));
        vmax = fmax(vmax, dist3(va, (double[3]){0, 0, 0}));
        eu = fmax(eu, dist3(rua, ub));
        ev = fmax(ev, dist3(rva, vb));
    }
    *err_u = eu / umax;
    *err_v = ev / vmax;
    free(match);
    sim_destroy(&a);
    sim_destroy(&b);
}

static int frame_check(const struct model_fixture *f)
{
    int bad = 0;
    /* c: several body sizes away, not a lattice vector; the angle: no
     * symmetry of any 2D lattice unless the fixture asks for one */
    const struct frame moved = {0.0, {0.0173, -0.0091, 0.0057}};
    const struct frame turned = {f->rotation_deg != 0.0 ? f->rotation_deg : 37.0,
                                 {0.0173, -0.0091, 0.0057}};
    double tu, tv, ru, rv;
    frame_invariance(f, &moved, &tu, &tv);
    frame_invariance(f, &turned, &ru, &rv);
    printf("  %-28s translated: u %.2e v %.2e; rotated (%s): u %.2e v %.2e\n", f->label, tu,
           tv, fixture_dim(f) == 3 ? "120 deg about [111]" : "deck angle", ru, rv);
    if (f->rotation_deg != 0.0)
        print_why(f);
    /* the same arithmetic up to the rounding of the positions (|c| ~ 20
     * spacings) and of the rotation: <= 2e-11 measured after RUN_STEPS
     * steps of these random (particle-scale) motions */
    bad += failed(tu <= 1e-10, f, "translation: displacement", tu);
    bad += failed(tv <= 1e-10, f, "translation: velocity", tv);
    bad += failed(ru <= 1e-10, f, "rotation: displacement", ru);
    bad += failed(rv <= 1e-10, f, "rotation: velocity", rv);
    return bad;
}

/* Largest |energy balance| over @p steps steps of @p dt from a smooth
 * velocity field (no position perturbation: the body starts unstressed),
 * sampled every @p every steps. */
static double energy_error(const struct model_fixture *fx, double dt_scale, long steps,
                           long every)
{
    struct sim *s = build(fx, &base_frame, radius_of(fx));
    const double vs = velocity_scale(s), R = radius_of(fx) * fx->spacing;
    /* a uniform stretch-and-shear rate plus a spin: the low modes */
    static const double A[3][3] = {{0.5, 1.0, 0.3}, {-0.6, -0.2, 0.4}, {0.5, -0.3, 0.15}};
    struct particles *p = s->p;
    for (size_t i = 0; i < p->n; i++)
        for (int d = 0; d < s->dim; d++) {
            double v = 0.0;
            for (int e = 0; e < s->dim; e++)
                v += A[d][e] * p->x[e][i] / R;
            p->v[d][i] = 10.0 * vs * v;
        }
    struct spall_error err = {0};
    assert_int_equal(sim_initial_forces(s, &err), 0);
    s->dt *= dt_scale;
    double worst = 0.0, scale = s->energy.kinetic;
    for (long k = 1; k <= steps; k++) {
        run_steps(s, 1, fx->label);
        if (k % every == 0) {
            sim_update_energy(s);
            worst = fmax(worst, fabs(s->energy.balance));
        }
    }
    sim_destroy(&s);
    return worst / scale;
}

/* 3. Second-order energy error of an elastic free body. */
static int energy_order(const struct model_fixture *fx)
{
    int bad = 0;
    double e1 = energy_error(fx, 1.0, RUN_STEPS, 1);
    double e2 = energy_error(fx, 0.5, 2 * RUN_STEPS, 2);
    printf("  %-28s max |energy error| / kinetic: %.3e at dt, %.3e at dt/2, ratio %.3f\n",
           fx->label, e1, e2, e1 / e2);
    /* second order: 4, within the higher-order terms at the models'
     * default steps */
    bad += failed(e1 / e2 >= 3.0 && e1 / e2 <= 5.0, fx, "energy error ratio", e1 / e2);
    return bad;
}

/* Every stored field's bytes for particles [0, n), concatenated. */
static unsigned char *stored_bytes(const struct sim *s, size_t *len)
{
    const struct field_registry *reg = s->fields;
    size_t n = s->p->n, total = 0;
    for (size_t k = 0; k < reg->n; k++)
        total += field_packed_size(&reg->fields[k]) * n;
    unsigned char *out = malloc(total ? total : 1), *at = out;
    assert_non_null(out);
    for (size_t k = 0; k < reg->n; k++) {
        const struct field_desc *f = &reg->fields[k];
        size_t sz = field_packed_size(f);
        if (sz == 0)
            continue;
        size_t comp = sz / (size_t)f->ncomp;
        for (int c = 0; c < f->ncomp; c++) {
            memcpy(at, *f->comp[c], comp * n);
            at += comp * n;
        }
    }
    *len = total;
    return out;
}

/* 4. One and two threads, bitwise. */
static int threads_check(const struct model_fixture *fx)
{
    const int saved = omp_get_max_threads();
    int bad = 0;
    /* a body above SPALL_OMP_MIN_PARTICLES, so that the loops with a
     * size threshold run on two threads too */
    double rad = fixture_dim(fx) == 2 ? 38.0 : 10.5;
    unsigned char *bytes[2];
    size_t len[2], np = 0;
    for (int t = 0; t < 2; t++) {
        omp_set_num_threads(t + 1);
        struct sim *s = build(fx, &base_frame, rad);
        assert_true(s->p->n > SPALL_OMP_MIN_PARTICLES);
        np = s->p->n;
        set_state(s, s, &base_frame, NULL);
        run_steps(s, 5, fx->label);
        bytes[t] = stored_bytes(s, &len[t]);
        sim_destroy(&s);
    }
    omp_set_num_threads(saved);
    printf("  %-28s %zu particles, 5 steps: %zu bytes of stored fields %s on 1 and 2 "
           "threads\n",
           fx->label, np, len[0],
           len[0] == len[1] && memcmp(bytes[0], bytes[1], len[0]) == 0 ? "identical"
                                                                       : "differ");
    bad += failed(len[0] == len[1] && memcmp(bytes[0], bytes[1], len[0]) == 0, fx,
                  "1 and 2 threads differ", 0.0);
    free(bytes[0]);
    free(bytes[1]);
    return bad;
}

/* 5. Pack every particle's stored fields, scramble, unpack: byte-identical. */
static int pack_unpack(const struct model_fixture *fx)
{
    int bad = 0;
    struct sim *s = build(fx, &base_frame, radius_of(fx));
    set_state(s, s, &base_frame, NULL);
    run_steps(s, 5, fx->label);
    const struct field_registry *reg = s->fields;
    const size_t np = s->p->n;
    size_t per = 0, stored = 0;
    char skipped[512] = "";
    for (size_t f = 0; f < reg->n; f++) {
        size_t sz = field_packed_size(&reg->fields[f]);
        per += sz;
        if (sz)
            stored++;
        else if (strlen(skipped) + FIELD_NAME_LEN + 2 < sizeof skipped) {
            strcat(skipped, " ");
            strcat(skipped, reg->fields[f].name);
        }
    }
    size_t len_before;
    unsigned char *before = stored_bytes(s, &len_before);
    unsigned char *buf = malloc(per * np + 1);
    assert_non_null(buf);
    unsigned char *at = buf;
    for (size_t i = 0; i < np; i++)
        for (size_t f = 0; f < reg->n; f++) {
            field_pack(&reg->fields[f], i, at);
            at += field_packed_size(&reg->fields[f]);
        }
    for (size_t f = 0; f < reg->n; f++) { /* scramble */
        const struct field_desc *d = &reg->fields[f];
        size_t sz = field_packed_size(d);
        for (int c = 0; sz && c < d->ncomp; c++)
            memset(*d->comp[c], 0xA5, sz / (size_t)d->ncomp * np);
    }
    at = buf;
    for (size_t i = 0; i < np; i++)
        for (size_t f = 0; f < reg->n; f++) {
            field_unpack(&reg->fields[f], i, at);
            at += field_packed_size(&reg->fields[f]);
        }
    size_t len_after;
    unsigned char *after = stored_bytes(s, &len_after);
    printf("  %-28s %zu stored fields (%zu B/particle) round-trip; computed, skipped:%s\n",
           fx->label, stored, per, skipped[0] ? skipped : " none");
    bad += failed(len_before == len_after && memcmp(before, after, len_before) == 0, fx,
                  "pack/unpack changed the state", 0.0);
    free(before);
    free(after);
    free(buf);
    sim_destroy(&s);
    return bad;
}

/* The checks, each run on every fixture (one cmocka test per check). */
static int (*const checks[])(const struct model_fixture *fx) = {
    newton_momentum, frame_check, energy_order, threads_check, pack_unpack};

static void test_contract(void **state)
{
    int (*const *check)(const struct model_fixture *) = *state;
    for_every_fixture(*check);
}

int main(void)
{
    static const char *const names[] = {"newton_third_law_and_momenta", "frame_invariance",
                                        "energy_second_order", "threads_bitwise",
                                        "pack_unpack_round_trip"};
    struct CMUnitTest tests[sizeof checks / sizeof checks[0]];
    for (size_t k = 0; k < sizeof checks / sizeof checks[0]; k++)
        tests[k] = (struct CMUnitTest){.name = names[k], .test_func = test_contract,
                                       .initial_state = (void *)&checks[k]};
    return cmocka_run_group_tests(tests, NULL, NULL);
}
