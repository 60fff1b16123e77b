/**
 * @file lattice_break.c
 * @brief Validation case "lattice-chain-break": a chain ([Wang2010] sec. 4.1
 *        material: E = 3 GPa, sigma_TS = 60 MPa, rho = 1140 kg/m^3, r0 = 1 mm,
 *        L = 12.7 cm) held at the left end and pulled at the right end must
 *        break when its overall strain reaches eps_max = sigma_TS / E (Eq. 26).
 *
 * Quasi-static loading: the end velocity rises linearly to V = 0.5 m/s over a
 * ramp of 0.5 ms (6.4 wave transits L/c).  A step in velocity would launch a
 * strain wave of amplitude V/c = 3e-4 (1.5 % of eps_max) that doubles on
 * reflection; the ramp cuts the residual oscillation to about V/c times
 * (L/c)/T_ramp, i.e. well below 1 % of eps_max.  The strain added per step is
 * V dt / L = 1.2e-6 (0.006 % of eps_max).
 * Measured: (x_right - x_left)/(x0_right - x0_left) - 1 at the step in which
 * the model's history column bonds_broken first becomes positive (the model
 * decides breaking inside the force computation of that step, from those
 * positions).
 */
#include "validation/lattice_cases.h"
#include "validation/validation.h"
#include "validation/vpar.h"

#include "core/particles.h"
#include "core/sim.h"
#include "spall/error.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>

#define BREAK_E 3.0e9
#define BREAK_SIGMA 60.0e6
#define BREAK_V 0.5
#define BREAK_RAMP 5.0e-4

int lattice_case_chain_break(struct vreport *r, struct spall_error *err)
{
    char deck[1536];
    snprintf(deck, sizeof deck,
             "title: chain pulled apart slowly\n"
             "model: {type: lattice, law: linear}\n"
             "materials:\n"
             "  polymer: {density: 1140, youngs_modulus: %.17g, tensile_strength: %.17g}\n"
             "lattice: {type: chain, spacing: 1.0e-3}\n"
             "geometry:\n"
             "  bar: {box: {min: [-0.0005], max: [0.1275]}}\n"
             "body: {geometry: bar, material: polymer}\n"
             "groups:\n"
             "  left: {box: {min: [-0.001], max: [0.0005]}}\n"
             "  right: {box: {min: [0.1265], max: [0.128]}}\n"
             "boundary_conditions:\n"
             "  - {group: left, type: fixed}\n"
             "  - {group: right, type: velocity, components: [x], value: %.17g,\n"
             "     function: {type: linear_ramp, duration: %.17g}}\n"
             "run: {end_time: 1.0e-2}\n",
             BREAK_E, BREAK_SIGMA, BREAK_V, BREAK_RAMP);
    struct sim *s = NULL;
    int rc = vlat_build("chain_break", deck, &s, err);
    if (rc)
        return rc;
    int gl = 0, gr = 0;
    if ((rc = vlat_group(s, "left", &gl, err)) || (rc = vlat_group(s, "right", &gr, err)))
        goto done;
    const struct particles *p = s->p;
    /* global ids: the ends stay readable after distribution (vpar.h) */
    const int64_t ends[2] = {p->gid[s->groups[gl].idx[0]], p->gid[s->groups[gr].idx[0]]};
    const int64_t il = ends[0], ir = ends[1];
    const size_t n_particles = p->n;
    const double len0 = p->x0[0][ir] - p->x0[0][il];
    if ((rc = vpar_distribute(r, s, err)))
        goto done;
    const double eps_max = BREAK_SIGMA / BREAK_E;
    /* break expected at t = T_ramp / 2 + eps_max L / V; allow 50 % more */
    const double t_stop = 1.5 * (0.5 * BREAK_RAMP + eps_max * len0 / BREAK_V);
    double eps_break = NAN, t_break = NAN, broken = 0.0, eps_prev = 0.0;
    while (s->t < t_stop) {
        if ((rc = sim_step(s, err)))
            goto done;
        double x_end[2];
        vpar_values(s, p->x[0], ends, 2, x_end);
        double eps = (x_end[1] - x_end[0]) / len0 - 1.0;
        broken = vlat_history(s, "bonds_broken");
        if (!isfinite(broken)) {
            rc = spall_error_set(err, SPALL_ERR_INTERNAL,
                                 "lattice-chain-break: model has no 'bonds_broken' history");
            goto done;
        }
        if (broken > 0.0) {
            eps_break = eps;
            t_break = s->t;
            break;
        }
        eps_prev = eps;
    }
    rc = vreport_check(r, "overall strain at the first bond break", "1", eps_max, eps_break, 0.01,
                       true, "[Wang2010] Eq. 26: eps_max = sigma_TS / E = 60 MPa / 3 GPa",
                       "1 %: quasi-static ramped pull; the residual wave in the chain is ~0.2 % "
                       "of eps_max and the strain added per step 0.006 %",
                       err);
    if (!rc)
        vreport_info(r, "%zu particles, dt = %.4g s: first break at t = %.5g s (step %ld), overall "
                     "strain %.6g (previous step %.6g), eps_max = %.6g (%+.3f %%), %g bond(s) "
                     "broken in that step",
                     n_particles, s->dt, t_break, s->step, eps_break, eps_prev, eps_max,
                     100.0 * (eps_break / eps_max - 1.0), broken);
done:
    sim_destroy(&s);
    return rc;
}
