/**
 * @file test_energy_pd_fracture.c
 * @brief Energy account of a breaking peridynamic chain
 *        (src/models/peridynamics/pd_forces.c, PMB [SillingAskari2005]):
 *        a chain held at one end and pulled at the other until its bonds
 *        pass the critical stretch; the work of the pull equals kinetic +
 *        strain energy + the energy the broken bonds held when they broke
 *        (booked as dissipated, each bond once, as the integrator paid it).
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "tests/test_support.h"

#include <stdio.h>

/* The chain held at one end and pulled at the other past s0 under
 * model.break_order @p order; returns the balance / dissipated energy. */
static double pulled_chain_balance(const char *order)
{
    char deck[1024];
    snprintf(deck, sizeof deck,
             "model: {type: peridynamics, break_order: %s}\n"
             "materials: {m: {density: 1000, youngs_modulus: 1.0e9, critical_stretch: 0.005}}\n"
             "lattice: {type: chain, spacing: 1.0e-3, thickness: 1.0e-6}\n"
             "body: {geometry: {box: {min: [-0.0005], max: [0.0105]}}, material: m}\n"
             "groups:\n"
             "  l: {box: {min: [-0.001], max: [0.0005]}}\n"
             "  r: {box: {min: [0.0095], max: [0.011]}}\n"
             "boundary_conditions:\n"
             "  - {group: l, type: fixed}\n"
             "  - {group: r, type: velocity, value: 5.0}\n"
             "run: {dt: 2.0e-8, steps: 1000}\n",
             order);
    struct sim *s = test_build_ok(deck);
    struct spall_error err = {0};
    sim_update_energy(s);
    while (!sim_done(s))
        assert_int_equal(sim_step(s, &err), SPALL_OK);
    sim_update_energy(s);
    const struct energy_account *a = &s->energy;
    print_message("%s: W = %.6e, KE = %.6e, strain = %.6e, dissipated = %.6e, balance = %.3e\n",
                  order, a->external, a->kinetic, a->strain, a->model_dissipated, a->balance);
    assert_true(a->model_dissipated > 0.0);
    const double rel = a->balance / a->model_dissipated;
    sim_destroy(&s);
    return rel;
}

static void test_pulled_chain_breaks_with_balanced_energy(void **state)
{
    (void)state;
    /* a bond that breaks within a step is booked at 1/4 coef e_{n+1} e_n per
     * half-bond (pd_forces.c), what the Verlet kicks left of its energy:
     * measured 2e-6 of the dissipated energy (tolerance 1e-4).  Booking its
     * energy at the break, 1/4 coef e_{n+1}^2, leaves 0.9 % (first order in
     * dt); a breaking bond booked twice, 100 % */
    assert_true(fabs(pulled_chain_balance("immediate")) < 1.0e-4);
}

static void test_next_step_breaking_balances_to_second_order(void **state)
{
    (void)state;
    /* next_step: the bond's force at x_{n+1} acts half a step after the
     * break, booked with de ~ e_{n+1} - e_n: measured 4e-5 of the
     * dissipated energy (tolerance 5e-4); booked at the break it was -0.43 %
     * of the input, with the immediate formula -0.86 % */
    assert_true(fabs(pulled_chain_balance("next_step")) < 5.0e-4);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_pulled_chain_breaks_with_balanced_energy),
        cmocka_unit_test(test_next_step_breaking_balances_to_second_order),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
