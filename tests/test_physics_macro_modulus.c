/**
 * @file test_physics_macro_modulus.c
 * @brief The macro-particle crystal's elastic constants, measured from the
 *        model's pair forces (virial stress) of a homogeneously strained FCC
 *        block, against their lattice-sum values ([Saitoh] Eqs. 10-15 in
 *        the form of spec/macroparticle.md).
 *
 * Lattice sum (Cauchy-Born, central pairs): the Mie pair phi(r) of depth D
 * has phi'(r0) = 0 and phi''(r0) = k = D p q / r0^2; with the taper from
 * 1.2 r0 and the cut-off at 1.35 r0 only the 12 nearest neighbours
 * (second shell at sqrt2 r0) act.  With the volume r0^3 / sqrt2 per
 * particle, C_abcd = (1 / 2 Omega) sum_nb k r0^2 n_a n_b n_c n_d gives
 *   C11 = sqrt2 k / r0,   C12 = C44 = k / (sqrt2 r0),
 *   E_[100] = (C11 - C12)(C11 + 2 C12)/(C11 + C12) = 4 k / (3 sqrt2 r0),
 *   nu_[100] = C12 / (C11 + C12) = 1/3.
 * D is the deck's (calibration eq15): D = P_atom / 6, P_atom = N_atom e0,
 * N_atom = (rho pi r0^3 / 6) / (0.74 m_atom) ([Saitoh] Eqs. 10, 13).
 *
 * Measurement: the block's positions are set to x0 + eps x0_x e_x (uniaxial
 * strain, both signs), one force evaluation, the virial stress ("stress"
 * field) of the particles whose whole cut-off sphere lies inside the block
 * (for them Cauchy-Born is exact: the strained lattice is perfect).  The
 * central difference over +-eps = 1e-5 leaves the anharmonic error
 * O((phi'''' r0^2 / phi'') eps^2) ~ 1e-8; the tolerance (1e-6) covers it
 * and round-off (measured 5e-10).  The virial is tied to the force array by
 * sum_i x_i f_i,x = -sum_i V_i sigma_xx,i.  A pair force off by a factor
 * (x1.15) moves C11, C12 and E by that factor (measured +0.150).
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "core/fields.h"
#include "core/mathconst.h"
#include "tests/test_assert.h"
#include "tests/test_support.h"

#include <stdio.h>
#include <stdlib.h>

#define AMU 1.66053906660e-27 /* kg (CODATA 2018) */
#define EV 1.602176634e-19    /* J (exact) */

static const double RHO = 2700.0, MASS_U = 26.98, E0_EV = 3.39, P_EXP = 4.0, Q_EXP = 9.0;
static const double R0 = 1.0e-3;
static const double BOX = 8.0e-3; /* about 5.7 cubic cells a side */

/* Mean sigma_xx and sigma_yy of the interior particles at the uniaxial
 * strain eps_xx = @p eps; returns how many particles were averaged. */
static size_t strained_stress(struct sim *s, const double *x0, double eps, double sig[2])
{
    struct particles *p = s->p;
    const size_t n = p->n_owned;
    for (size_t i = 0; i < n; i++)
        for (int d = 0; d < 3; d++) {
            p->x[d][i] = x0[3 * i + d] * (d == 0 ? 1.0 + eps : 1.0);
            p->v[d][i] = 0.0;
        }
    struct spall_error err = {0};
    assert_int_equal(sim_initial_forces(s, &err), SPALL_OK);
    const struct field_desc *f = field_registry_find(s->fields, "stress");
    assert_non_null(f);
    assert_int_equal(f->ncomp, 6);
    double *st = malloc(6 * n * sizeof *st);
    assert_non_null(st);
    f->compute(f->ctx, n, st);
    /* lattice bounds (the sites of the block) */
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (size_t i = 0; i < n; i++)
        for (int d = 0; d < 3; d++) {
            lo[d] = fmin(lo[d], x0[3 * i + d]);
            hi[d] = fmax(hi[d], x0[3 * i + d]);
        }
    /* the forces behind the virial: for pair forces, sum_i x_i f_i,x =
     * -sum_pairs c (dx_x)^2 = -sum_i V_i sigma_xx,i over the whole free
     * block (round-off), so the stress below is the forces' stress */
    double wf = 0.0, wv = 0.0, wscale = 0.0;
    for (size_t i = 0; i < n; i++) {
        wf += p->x[0][i] * p->f[0][i];
        wv += p->volume[i] * st[6 * i + 0];
        wscale += fabs(p->x[0][i] * p->f[0][i]);
    }
    assert_true(fabs(wf + wv) < 1e-10 * wscale);
    const double margin = 1.4 * R0; /* beyond the cut-off (1.35 r0) */
    size_t m = 0;
    sig[0] = sig[1] = 0.0;
    for (size_t i = 0; i < n; i++) {
        int inside = 1;
        for (int d = 0; d < 3; d++)
            inside &= x0[3 * i + d] - lo[d] > margin && hi[d] - x0[3 * i + d] > margin;
        if (!inside)
            continue;
        sig[0] += st[6 * i + 0];
        sig[1] += st[6 * i + 1];
        m++;
    }
    free(st);
    assert_true(m > 0);
    sig[0] /= (double)m;
    sig[1] /= (double)m;
    return m;
}

/* The FCC aluminium block of the tests, with @p extra material keys (""
 * or ", yield_strain: ..."); its rest positions into *x0 (owned). */
static struct sim *fcc_block(const char *extra, double **x0)
{
    char yaml[1024];
    snprintf(yaml, sizeof yaml,
             "model: {type: macroparticle}\n"
             "materials:\n"
             "  al: {density: %g, atomic_mass_u: %g, cohesive_energy_ev: %g, exponents: [%g, %g]%s}\n"
             "lattice: {type: fcc, spacing: %g}\n"
             "body: {geometry: {box: {min: [0, 0, 0], max: [%g, %g, %g]}}, material: al}\n"
             "run: {steps: 1}\n",
             RHO, MASS_U, E0_EV, P_EXP, Q_EXP, extra, R0, BOX, BOX, BOX);
    struct sim *s = test_build_ok(yaml);
    const size_t n = s->p->n_owned;
    *x0 = malloc(3 * n * sizeof **x0);
    assert_non_null(*x0);
    for (size_t i = 0; i < n; i++)
        for (int d = 0; d < 3; d++)
            (*x0)[3 * i + d] = s->p->x[d][i];
    return s;
}

static void test_fcc_modulus_lattice_sum(void **state)
{
    (void)state;
    double *x0 = NULL;
    struct sim *s = fcc_block("", &x0);
    const size_t n = s->p->n_owned;
    const double eps = 1.0e-5;
    double sp[2], sm[2];
    const size_t m = strained_stress(s, x0, eps, sp);
    strained_stress(s, x0, -eps, sm);
    const double C11 = (sp[0] - sm[0]) / (2.0 * eps), C12 = (sp[1] - sm[1]) / (2.0 * eps);
    const double E = (C11 - C12) * (C11 + 2.0 * C12) / (C11 + C12), nu = C12 / (C11 + C12);
    /* the lattice sum from the deck's inputs */
    const double n_atom = (RHO * SPALL_PI * R0 * R0 * R0 / 6.0) / (0.74 * MASS_U * AMU);
    const double D = n_atom * E0_EV * EV / 6.0, k = D * P_EXP * Q_EXP / (R0 * R0);
    const double C11_ls = sqrt(2.0) * k / R0, C12_ls = k / (sqrt(2.0) * R0);
    const double E_ls = 4.0 * k / (3.0 * sqrt(2.0) * R0);
    print_message("%zu particles (%zu interior): C11 = %.6e (sum %.6e), C12 = %.6e (sum %.6e), "
                  "E100 = %.6e (sum %.6e, rel. %.2e), nu = %.8f\n",
                  n, m, C11, C11_ls, C12, C12_ls, E, E_ls, E / E_ls - 1.0, nu);
    assert_true(m >= 8);
    assert_true(fabs(C11 / C11_ls - 1.0) < 1e-6);
    assert_true(fabs(C12 / C12_ls - 1.0) < 1e-6);
    assert_true(fabs(E / E_ls - 1.0) < 1e-6);
    assert_true(fabs(nu - 1.0 / 3.0) < 1e-6);
    free(x0);
    sim_destroy(&s);
}

/* Pair plasticity ([Saitoh] Eq. 16 in the form of docs/decks.md): beyond
 * the yield surface |e| = e_y + h kappa the plastic route has the tangent
 * t = hardening of the elastic stiffness, the slip d = excess / (1 + h) with
 * h = t / (1 - t).  The block is pulled in one jump to a uniaxial strain that
 * takes every pair with a component along x past yield, then probed by
 * +-delta: unloading follows the elastic branch (tangent C11 of the pairs at
 * their current elastic stretch), reloading back to the yield surface stays
 * elastic, and a further +delta is plastic, so C11_plastic / C11_elastic = t.
 * Both tangents are taken at the same elastic stretch, so the Mie pair's
 * anharmonicity cancels to O(delta); what does not scale with t is the
 * geometric (initial-stress) stiffness of the pairs' finite force turning
 * with the strain, of the order of the stress itself: c_pl / c_el = t +
 * (1 - t) c_geo / c_el with |c_geo| <~ 2 |sigma_xx| (measured 3.8e-4 against
 * the bound 2 |sigma_xx| / c_el).  A return without the hardening factor
 * leaves the pair inside its new surface (ratio ~1). */
static void test_fcc_plastic_tangent(void **state)
{
    (void)state;
    const double t = 0.1, yield = 1.0e-4;
    char extra[96];
    snprintf(extra, sizeof extra, ", yield_strain: %g, hardening: %g", yield, t);
    double *x0 = NULL;
    struct sim *s = fcc_block(extra, &x0);
    /* pairs along (1, +-1, 0) and (1, 0, +-1) stretch by ~eps/2: 5 x yield */
    const double eps = 1.0e-3, delta = 1.0e-6;
    double s0[2], sm[2], sr[2], sp[2];
    strained_stress(s, x0, 0.0, s0); /* the pairs engage at rest */
    strained_stress(s, x0, eps, s0); /* the jump: every stretched pair yields */
    strained_stress(s, x0, eps - delta, sm);
    strained_stress(s, x0, eps, sr);
    strained_stress(s, x0, eps + delta, sp);
    const double c_el = (s0[0] - sm[0]) / delta, c_re = (sr[0] - sm[0]) / delta;
    const double c_pl = (sp[0] - sr[0]) / delta;
    print_message("elastic unloading C11 %.6e, reloading %.6e, plastic %.6e: ratio %.6f (t = %g)\n",
                  c_el, c_re, c_pl, c_pl / c_el, t);
    assert_true(c_el > 0.0);
    assert_near(c_re / c_el, 1.0, 1.0e-6); /* reloading retraces the elastic branch */
    const double geo = 2.0 * fabs(s0[0]) / c_el; /* initial-stress stiffness bound */
    print_message("sigma_xx %.4e Pa: geometric bound %.3e\n", s0[0], geo);
    assert_true(geo < 0.1 * t);
    assert_near(c_pl / c_el, t, geo);
    free(x0);
    sim_destroy(&s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_fcc_modulus_lattice_sum),
        cmocka_unit_test(test_fcc_plastic_tangent),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
