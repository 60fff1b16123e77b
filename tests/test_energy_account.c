/**
 * @file test_energy_account.c
 * @brief The engine's energy account and boundary reactions against exact
 *        mechanics (src/core/integrator.c, src/core/rigid.c):
 *  - mass-proportional damping: a freely translating chain decays as
 *    v0 exp(-c t), and the energy booked as damping is the kinetic energy
 *    it lost;
 *  - gravity: a chain falling from rest moves by g t^2/2 at v = g t, and the
 *    work booked for gravity, M g u, is the kinetic energy it gained;
 *  - a velocity boundary condition stretching an elastic chain: the
 *    recorded reactions integrate to the momentum the chain gained
 *    (Newton's second law for the whole chain), their power R V integrates
 *    to the work booked, and that work is the chain's kinetic + strain energy;
 *  - penalty contact of a rigid sphere: the force on the sphere is minus the
 *    gradient of the booked contact energy (central difference), and the
 *    particles receive the opposite force (Newton's third law);
 *  - body-body contact (Hertz-like exponent): the contact force on a body is
 *    minus the gradient of the booked contact energy;
 *  - the damping and gravity work of a long chain (summed over threads in
 *    exact partial sums) is the same bit for bit on 1 and 2 threads.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "tests/test_assert.h"

#include "tests/test_support.h"

#include "core/contact_particles.h"
#include "core/rigid.h"

#include <float.h>
#include <omp.h>
#include <stdio.h>
#include <string.h>


/* 1D lattice chain of 11 particles, 1 mm apart (c = sqrt(E/rho) = 1000 m/s,
 * stable step ~ 1e-6 s) followed by @p extra deck lines. */
static struct sim *build_chain(const char *extra)
{
    char yaml[2048];
    snprintf(yaml, sizeof yaml,
             "model: {type: lattice, law: linear}\n"
             "materials: {m: {density: 1000, youngs_modulus: 1.0e9, failure_strain: 0.5}}\n"
             "lattice: {type: chain, spacing: 1.0e-3}\n"
             "body: {geometry: {box: {min: [-0.0005], max: [0.0105]}}, material: m}\n"
             "%s",
             extra);
    return test_build_ok(yaml);
}

static void steps(struct sim *s, int n)
{
    struct spall_error err = {0};
    for (int k = 0; k < n; k++) {
        int rc = sim_step(s, &err);
        if (rc)
            print_error("%s\n", err.msg);
        assert_int_equal(rc, SPALL_OK);
    }
}

static double total_mass(const struct sim *s)
{
    double M = 0.0;
    for (size_t i = 0; i < s->p->n_owned; i++)
        M += s->p->mass[i];
    return M;
}

static double momentum_x(const struct sim *s)
{
    double P = 0.0;
    for (size_t i = 0; i < s->p->n_owned; i++)
        P += s->p->mass[i] * s->p->v[0][i];
    return P;
}

/* Free chain moving rigidly at v0 with damping c: its springs stay at rest
 * length, so every particle obeys dv/dt = -c v, v = v0 exp(-c t).  Verlet
 * with the force of the half-step velocity multiplies v by (1 - c dt) per
 * step, a relative error N (c dt)^2 / 2 = c t (c dt) / 2 = 5e-4 at c t = 1,
 * c dt = 1e-3; the damping booked per step, c m v_half^2 dt, differs from
 * the kinetic energy lost in that step by a fraction c dt / 2 of it (5e-4).
 * A doubled damping force would leave exp(-2) instead of exp(-1); half the
 * damping energy booked would miss 43 % of the initial energy. */
static void test_damped_translation(void **state)
{
    (void)state;
    const double v0 = 2.0, c = 1.0e5, dt = 1.0e-8;
    const int N = 1000;
    char extra[512];
    snprintf(extra, sizeof extra,
             "initial_velocity: [{group: all, value: [%.17g]}]\n"
             "damping: %.17g\n"
             "run: {dt: %.17g, steps: %d}\n",
             v0, c, dt, N);
    struct sim *s = build_chain(extra);
    const double M = total_mass(s), ke0 = 0.5 * M * v0 * v0;
    steps(s, N);
    sim_update_energy(s);
    const double t = s->t, v_exact = v0 * exp(-c * t);
    print_message("v = %.10e, v0 exp(-ct) = %.10e (rel. %.2e); KE + damping = %.10e of KE0 %.10e\n",
                  s->p->v[0][0], v_exact, s->p->v[0][0] / v_exact - 1.0,
                  s->energy.kinetic + s->energy.damping, ke0);
    for (size_t i = 0; i < s->p->n_owned; i++)
        assert_near(s->p->v[0][i], v_exact, 1.0e-3 * v_exact);
    assert_near(s->energy.kinetic, 0.5 * M * v_exact * v_exact, 2.0e-3 * s->energy.kinetic);
    assert_near(s->energy.kinetic + s->energy.damping, ke0, 1.0e-3 * ke0);
    assert_true(fabs(s->energy.balance) < 1.0e-3 * ke0);
    sim_destroy(&s);
}

/* Damping and gravity work of a 6001-particle chain (above the OpenMP
 * threshold) after 20 steps on @p threads threads. */
static void body_work_on(int threads, double out[2])
{
    const int saved = omp_get_max_threads();
    omp_set_num_threads(threads);
    struct sim *s = test_build_ok(
        "model: {type: lattice, law: linear}\n"
        "materials: {m: {density: 1000, youngs_modulus: 1.0e9, failure_strain: 0.5}}\n"
        "lattice: {type: chain, spacing: 1.0e-3}\n"
        "body: {geometry: {box: {min: [-0.0005], max: [6.0005]}}, material: m}\n"
        "groups: {end: {box: {min: [-1], max: [0.0005]}}}\n"
        "boundary_conditions: [{group: end, type: velocity, components: [x], value: 3.0}]\n"
        "initial_velocity: [{group: all, value: [1.7]}]\n"
        "damping: 3.3e4\ngravity: [-9.8e3]\n"
        "run: {dt: 1.0e-8, steps: 20}\n");
    assert_true(s->p->n_owned > 6000);
    steps(s, 20);
    out[0] = s->energy.damping;
    out[1] = s->energy.external;
    sim_destroy(&s);
    omp_set_num_threads(saved);
}

static void test_body_work_thread_independent(void **state)
{
    (void)state;
    double one[2], two[2];
    body_work_on(1, one);
    body_work_on(2, two);
    print_message("damping %.17g / %.17g, external %.17g / %.17g\n", one[0], two[0], one[1],
                  two[1]);
    assert_true(one[0] > 0.0 && one[1] != 0.0);
    assert_memory_equal(one, two, sizeof one);
}

/* Chain falling from rest under gravity g: velocity Verlet integrates a
 * constant acceleration exactly, so u = g t^2 / 2 and v = g t to round-off;
 * the work of gravity over each drift is M g dx, summing to M g u exactly,
 * and it all became kinetic energy (M (g t)^2 / 2 = M g u). */
static void test_free_fall(void **state)
{
    (void)state;
    const double g = -9.8e4, dt = 1.0e-8; /* strong g: a visible fall in few steps */
    const int N = 500;
    char extra[512];
    snprintf(extra, sizeof extra, "gravity: [%.17g]\nrun: {dt: %.17g, steps: %d}\n", g, dt, N);
    struct sim *s = build_chain(extra);
    const double M = total_mass(s);
    const size_t n = s->p->n_owned;
    double x0[16];
    assert_true(n <= 16);
    for (size_t i = 0; i < n; i++)
        x0[i] = s->p->x[0][i];
    steps(s, N);
    sim_update_energy(s);
    const double t = s->t, u_exact = 0.5 * g * t * t;
    double xmax = 0.0;
    for (size_t i = 0; i < n; i++)
        xmax = fmax(xmax, fabs(x0[i]));
    /* round-off: each of the N drifts rounds x (up to xmax) by eps xmax / 2;
     * the springs see stretches of round-off size, eps x ~ 2e-18 m, whose
     * forces (E eps x / dx per unit area, against rho dx g) perturb the
     * acceleration by ~1e-11 of g */
    const double tol_u = N * DBL_EPSILON * xmax + 1e-10 * fabs(u_exact);
    for (size_t i = 0; i < n; i++) {
        assert_near(s->p->x[0][i] - x0[i], u_exact, tol_u);
        assert_near(s->p->v[0][i], g * t, 1.0e-10 * fabs(g * t));
    }
    const double work = M * g * u_exact;
    print_message("gravity work booked %.12e, M g u = %.12e, KE = %.12e\n",
                  s->energy.external, work, s->energy.kinetic);
    assert_near(s->energy.external, work, 1.0e-9 * work);
    assert_near(s->energy.kinetic, work, 1.0e-9 * work);
    assert_true(fabs(s->energy.balance) < 1.0e-9 * work);
    sim_destroy(&s);
}

/* Left end held (fixed), right end pulled at V from t = 0: waves run
 * through the chain and back.  The only external forces are the two
 * reactions, so P(t) - P(0) = integral of (R_fixed + R_pull) dt.  The
 * reaction recorded in a step is the constraint force of its second half
 * kick, m dv / (dt/2), which for a constant prescribed velocity equals the
 * force of the first half kick of the next step: the sum R dt over N steps
 * differs from the impulses applied only by the end terms (F_0 - F_N) dt / 2
 * (F_0 = 0 in the unstretched chain), bounded by max |R| dt.  The same
 * holds for the power: the work booked is sum R V dt up to V max |R| dt;
 * and that work is the energy the chain holds, kinetic + strain (velocity
 * Verlet conserves energy to (omega dt)^2 / 8 = 5e-5 for the chain's
 * fastest mode, omega = 2 c / dx = 2e6 1/s, at dt = 1e-8 s). */
static void test_pulled_chain_reactions(void **state)
{
    (void)state;
    const double V = 1.0, dt = 1.0e-8;
    const int N = 3000; /* 30 us: three transits of the 1 cm chain */
    char extra[1024];
    snprintf(extra, sizeof extra,
             "groups:\n"
             "  left: {box: {min: [-0.001], max: [0.0005]}}\n"
             "  right: {box: {min: [0.0095], max: [0.011]}}\n"
             "boundary_conditions:\n"
             "  - {group: left, type: fixed}\n"
             "  - {group: right, type: velocity, value: %.17g}\n"
             "run: {dt: %.17g, steps: %d}\n",
             V, dt, N);
    struct sim *s = build_chain(extra);
    assert_int_equal(s->n_bcs, 2);
    const struct bc *fixed = &s->bcs[0], *pull = &s->bcs[1];
    assert_int_equal(fixed->kind, BC_FIXED);
    assert_int_equal(pull->kind, BC_VELOCITY);
    sim_update_energy(s);
    const double P0 = momentum_x(s), E0 = s->energy.kinetic + s->energy.strain;
    double impulse = 0.0, power_work = 0.0, rmax = 0.0;
    for (int k = 0; k < N; k++) {
        steps(s, 1);
        impulse += (fixed->reaction[0] + pull->reaction[0]) * dt;
        power_work += pull->reaction[0] * V * dt;
        rmax = fmax(rmax, fmax(fabs(fixed->reaction[0]), fabs(pull->reaction[0])));
    }
    sim_update_energy(s);
    const double dP = momentum_x(s) - P0;
    const double dE = s->energy.kinetic + s->energy.strain - E0;
    const double W = pull->work + fixed->work;
    print_message("dP = %.10e, sum R dt = %.10e (end-term bound %.1e)\n", dP, impulse, 2 * rmax * dt);
    print_message("work booked %.10e (fixed end %.1e), sum R V dt = %.10e, KE + strain gained %.10e\n",
                  W, fixed->work, power_work, dE);
    assert_true(rmax > 0.0 && dE > 0.0);
    /* the pulled end gained V m once at the set-up; the chain then gains
     * momentum only from the reactions */
    assert_near(dP, impulse, 2.0 * rmax * dt);
    assert_near(fixed->work, 0.0, 1e-15 * W); /* the held end does not move */
    assert_near(pull->work, power_work, 2.0 * rmax * V * dt);
    assert_near(W, dE, 1.0e-4 * dE);
    assert_true(fabs(s->energy.balance) < 1.0e-4 * dE);
    /* the end-term bounds are small against what they bound */
    assert_true(2.0 * rmax * dt < 1.0e-2 * fabs(dP));
    sim_destroy(&s);
}

/* Booked penalty energy of the impactor at its reference point shifted by
 * @p dy along y (contact forces are recomputed there). */
static double pen_energy_at(struct sim *s, struct impactor *im, double y0, double dy)
{
    im->x[1] = y0 + dy;
    rigid_contact_forces(s);
    return im->pen_energy;
}

/* A rigid sphere pressed into a lattice block: the penalty force on it is
 * -dE/dX of E = sum k phi^2 / 2.  E is smooth in X while no particle
 * crosses the surface, so the central difference over +-h (h ~ 1e-4 of the
 * penetration) has a truncation error ~ (h/phi)^2 ~ 1e-8 and round-off
 * ~ eps E / h ~ 1e-12 of the force.  The particles get the opposite of the
 * sphere's force (Newton's third law) to round-off. */
static void test_penalty_force_is_energy_gradient(void **state)
{
    (void)state;
    const char *yaml =
        "model: {type: lattice}\n"
        "materials:\n"
        "  m: {density: 1000, youngs_modulus: 1.0e9, poisson_ratio: 0.3333333333333333,\n"
        "      failure_strain: 1.0}\n"
        "lattice: {type: triangular, spacing: 1.0e-3}\n"
        "body: {geometry: {box: {min: [0, 0], max: [0.02, 0.008]}}, material: m}\n"
        "impactors:\n"
        "  - {name: ball, shape: sphere, position: [0.0103, 0.0126], radius: 0.005,\n"
        "     mass: 0.005, velocity: [0, -1.0], contact: penalty, stiffness: 1.0e6}\n"
        "run: {steps: 10}\n";
    struct sim *s = test_build_ok(yaml);
    assert_non_null(s->rigid);
    struct impactor *im = &s->rigid->im[0];
    const double y0 = im->x[1];
    struct particles *p = s->p;

    /* the force at y0, with the particles' forces alone */
    for (int d = 0; d < s->dim; d++)
        memset(p->f[d], 0, p->n_owned * sizeof(double));
    rigid_contact_forces(s);
    const double fy = im->f_pen[1], fx = im->f_pen[0], E = im->pen_energy;
    print_message("%zu particles in contact, E = %.6e J, F = (%.6e, %.6e) N\n",
                  im->n_contact, E, fx, fy);
    assert_true(im->n_contact >= 2);
    assert_true(fy > 0.0); /* the block pushes the sphere up */
    double sum[2] = {0, 0}, scale = 0.0;
    for (size_t i = 0; i < p->n_owned; i++)
        for (int d = 0; d < 2; d++) {
            sum[d] += p->f[d][i];
            scale += fabs(p->f[d][i]);
        }
    assert_near(sum[0] + fx, 0.0, 1e-13 * scale);
    assert_near(sum[1] + fy, 0.0, 1e-13 * scale);

    /* -dE/dY by a central difference; the penetration is ~1e-4 m */
    const double h = 1.0e-8;
    const double dEdy = (pen_energy_at(s, im, y0, h) - pen_energy_at(s, im, y0, -h)) / (2.0 * h);
    print_message("-dE/dY = %.10e, F_y = %.10e (rel. %.2e)\n", -dEdy, fy, -dEdy / fy - 1.0);
    assert_near(-dEdy, fy, 1.0e-7 * fy);
    /* and sideways */
    const double x0 = im->x[0];
    im->x[1] = y0;
    im->x[0] = x0 + h;
    rigid_contact_forces(s);
    const double ep = im->pen_energy;
    im->x[0] = x0 - h;
    rigid_contact_forces(s);
    const double em = im->pen_energy;
    im->x[0] = x0;
    assert_near(-(ep - em) / (2.0 * h), fx, 1.0e-7 * fabs(fy));
    sim_destroy(&s);
}

/* Contact energy of the run after shifting body 1 by @p dy along y; the
 * contact forces land in p->f, zeroed first. */
static double contact_energy_at(struct sim *s, double dy, double F1[2])
{
    struct particles *p = s->p;
    struct spall_error err = {0};
    for (size_t i = 0; i < p->n_owned; i++)
        if (p->body[i] == 1)
            p->x[1][i] += dy;
    for (int d = 0; d < 2; d++)
        memset(p->f[d], 0, p->n_owned * sizeof(double));
    assert_int_equal(particle_contact_forces(s, &err), SPALL_OK);
    const double E = particle_contact_energy(s);
    F1[0] = F1[1] = 0.0;
    for (size_t i = 0; i < p->n_owned; i++)
        if (p->body[i] == 1)
            for (int d = 0; d < 2; d++)
                F1[d] += p->f[d][i];
    for (size_t i = 0; i < p->n_owned; i++)
        if (p->body[i] == 1)
            p->x[1][i] -= dy;
    return E;
}

/* Two lattice blocks, the upper one pushed 0.1 r0 into the lower: the
 * contact force on the upper block is -dE/dY of the booked energy (the sum
 * over pairs of k d^2 u^(n+1) / (n+1), n = 1.5), by a central difference
 * with h = 1e-5 of the overlap (truncation ~ (h/overlap)^2 ~ 1e-10), and the
 * lower block gets the opposite force. */
static void test_contact_force_is_energy_gradient(void **state)
{
    (void)state;
    const double r0 = 1.0e-3, row = 0.5 * sqrt(3.0) * r0;
    char yaml[2048];
    snprintf(yaml, sizeof yaml,
             "model: {type: lattice, law: linear}\n"
             "materials:\n"
             "  m: {density: 1000, youngs_modulus: 1.0e9, poisson_ratio: 0.3333333333333333,\n"
             "      failure_strain: 10}\n"
             "lattice: {type: triangular, spacing: 1.0e-3}\n"
             "geometry:\n"
             "  a: {box: {min: [-1e-5, -1e-5], max: [0.006, %.17g]}}\n"
             "  b: {box: {min: [-1e-5, %.17g], max: [0.006, %.17g]}}\n"
             "bodies: [{geometry: a, material: m}, {geometry: b, material: m}]\n"
             "contact: {distance: 1.0e-3, stiffness: 1.0e6, exponent: 1.5}\n"
             "run: {steps: 1}\n",
             3.5 * row, 3.5 * row, 7.5 * row);
    struct sim *s = test_build_ok(yaml);
    struct particles *p = s->p;
    assert_non_null(p->body);
    const double push = -0.1 * r0, h = 1.0e-5 * 0.1 * r0;
    for (size_t i = 0; i < p->n_owned; i++)
        if (p->body[i] == 1)
            p->x[1][i] += push;
    double F1[2], Fp[2], Fm[2];
    const double E = contact_energy_at(s, 0.0, F1);
    double F0[2] = {0, 0}, scale = 0.0;
    for (size_t i = 0; i < p->n_owned; i++)
        if (p->body[i] == 0)
            for (int d = 0; d < 2; d++) {
                F0[d] += p->f[d][i];
                scale += fabs(p->f[d][i]);
            }
    print_message("%zu contact pairs, E = %.6e J, F on the upper block = (%.6e, %.6e) N\n",
                  particle_contact_pairs(s), E, F1[0], F1[1]);
    assert_true(particle_contact_pairs(s) >= 4 && F1[1] > 0.0);
    assert_near(F0[0] + F1[0], 0.0, 1e-13 * scale);
    assert_near(F0[1] + F1[1], 0.0, 1e-13 * scale);
    const double dEdy = (contact_energy_at(s, h, Fp) - contact_energy_at(s, -h, Fm)) / (2.0 * h);
    print_message("-dE/dY = %.10e, F_y = %.10e (rel. %.2e)\n", -dEdy, F1[1], -dEdy / F1[1] - 1.0);
    assert_near(-dEdy, F1[1], 1.0e-7 * F1[1]);
    sim_destroy(&s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_damped_translation),
        cmocka_unit_test(test_free_fall),
        cmocka_unit_test(test_body_work_thread_independent),
        cmocka_unit_test(test_pulled_chain_reactions),
        cmocka_unit_test(test_penalty_force_is_energy_gradient),
        cmocka_unit_test(test_contact_force_is_energy_gradient),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
