/**
 * @file pd_interface_crack.c
 * @brief Validation case "pd-interface-crack" (issue 26 item 4): a crack
 *        runs along the weaker interface between two materials.
 *
 * A 30 x 20 mm plane-stress plate (triangular lattice, dx = 0.5 mm, delta =
 * 3.015 dx, formulation lps) of two materials split by a straight interface
 * at 45 deg through its centre (a: E = 2 GPa on the upper left, b: E = 1 GPa
 * on the lower right, nu = 0.3, rho = 1000 kg/m^3, critical stretch 0.01
 * each), its left and right 1.5 mm strips pulled apart at -/+ 2 m/s along x.
 * In a homogeneous plate a tensile crack runs across the load (at 90 deg to
 * x); with the interface's critical stretch 0.002 (model.interfaces, the
 * weakest link) the crack must follow the interface at 45 deg instead.
 * Measured when the interface has come apart:
 *  - only bonds that join the two materials break (count of broken bulk
 *    half-bonds = 0);
 *  - the direction of the crack, the principal axis of the broken bonds'
 *    midpoints (their second moment), is the interface's 45 deg within 2 deg
 *    (a lattice row of the triangular lattice is at 60 deg, the zigzag of
 *    cut bonds along a 45 deg line averages to it);
 *  - the crack runs through: at least 90 % of the half-bonds that join the
 *    two materials are cut (the run stops there, or at 150 us);
 * and, as the control, with a strong interface (critical stretch 0.05) no
 * interface bond has broken when a bulk crack has started (100 bulk
 * half-bonds cut).
 */
#include "validation/lattice_cases.h"
#include "validation/pd_cases.h"
#include "validation/validation.h"

#include "core/bond_list.h"
#include "core/mathconst.h"
#include "core/particles.h"
#include "core/sim.h"
#include "models/peridynamics/pd.h"
#include "spall/error.h"

#include <math.h>
#include <stdbool.h>
#include <stdio.h>

#define IC_T_END 1.5e-4

struct crack_stats {
    size_t n_ifc, n_bulk;   /* broken half-bonds: interface, bulk */
    double angle_deg;       /* principal axis of the interface cracks' midpoints */
    double cover;           /* broken / all interface half-bonds */
    double t;               /* when measured [s] */
};

/* Broken half-bonds of @p s by kind, the crack's direction and the share of
 * the interface cut. */
static void crack_stats(const struct sim *s, struct crack_stats *cs)
{
    const struct bond_list *bl = pd_bonds(s->model);
    const struct particles *p = s->p;
    /* midpoints of the broken interface bonds: mean and second moment; and
     * the share of the interface's half-bonds broken */
    double n = 0.0, mx = 0.0, my = 0.0, sxx = 0.0, syy = 0.0, sxy = 0.0;
    size_t n_all = 0;
    cs->n_ifc = cs->n_bulk = 0;
    for (int pass = 0; pass < 2; pass++) {
        for (size_t i = 0; i < p->n; i++)
            for (size_t k = bl->offset[i]; k < bl->offset[i + 1]; k++) {
                const size_t j = (size_t)bl->partner[k];
                n_all += pass == 0 && p->material[i] != p->material[j];
                if (!(bl->state[k] & BOND_BROKEN))
                    continue;
                if (p->material[i] == p->material[j]) {
                    cs->n_bulk += pass == 0;
                    continue;
                }
                const double x = 0.5 * (p->x0[0][i] + p->x0[0][j]);
                const double y = 0.5 * (p->x0[1][i] + p->x0[1][j]);
                if (pass == 0) {
                    cs->n_ifc++;
                    n += 1.0;
                    mx += x;
                    my += y;
                } else {
                    sxx += (x - mx) * (x - mx);
                    syy += (y - my) * (y - my);
                    sxy += (x - mx) * (y - my);
                }
            }
        if (pass == 0 && n > 0.0) {
            mx /= n;
            my /= n;
        }
    }
    cs->angle_deg = 0.5 * atan2(2.0 * sxy, sxx - syy) * 180.0 / SPALL_PI;
    cs->cover = n_all ? (double)cs->n_ifc / (double)n_all : 0.0;
}

static int run_plate(double s0_ifc, bool weak, struct crack_stats *cs,
                     struct spall_error *err)
{
    char deck[2048];
    snprintf(deck, sizeof deck,
             "model: {type: peridynamics, formulation: lps, plane: plane_stress,\n"
             "        interfaces: [{materials: [a, b], critical_stretch: %g}]}\n"
             "materials:\n"
             "  a: {density: 1000, youngs_modulus: 2.0e9, poisson_ratio: 0.3, "
             "critical_stretch: 0.01}\n"
             "  b: {density: 1000, youngs_modulus: 1.0e9, poisson_ratio: 0.3, "
             "critical_stretch: 0.01}\n"
             "lattice: {type: triangular, spacing: 5.0e-4, thickness: 1.0e-3}\n"
             "body: {geometry: {box: {min: [0, 0], max: [0.030, 0.020]}}, material: a}\n"
             "regions: [{geometry: {halfspace: {point: [0.015, 0.010], normal: [-1, 1]}}, "
             "material: b}]\n"
             "groups:\n  l: {box: {min: [-1, -1], max: [0.0015, 1]}}\n"
             "  r: {box: {min: [0.0285, -1], max: [1, 1]}}\n"
             "boundary_conditions:\n"
             "  - {group: l, type: velocity, components: [x], value: -2.0}\n"
             "  - {group: r, type: velocity, components: [x], value: 2.0}\n"
             "run: {end_time: 1.0}\n",
             s0_ifc);
    struct sim *s = NULL;
    int rc = vlat_build("pd_interface_crack", deck, &s, err);
    if (rc)
        return rc;
    /* stop when the crack has run through the interface (weak) or a bulk
     * crack has started (control): every 20 steps */
    while (s->t < IC_T_END && !rc) {
        for (int k = 0; k < 20 && !rc; k++)
            rc = sim_step(s, err);
        crack_stats(s, cs);
        if ((weak && cs->cover >= 0.9) || (!weak && cs->n_bulk >= 100))
            break;
    }
    cs->t = s->t;
    sim_destroy(&s);
    return rc;
}
int pd_case_interface_crack(struct vreport *r, struct spall_error *err)
{
    struct crack_stats weak, strong;
    int rc = run_plate(0.002, true, &weak, err);
    if (rc || (rc = run_plate(0.05, false, &strong, err)))
        return rc;
    vreport_info(r, "pd-interface-crack: weak interface at %.1f us: %zu interface, %zu bulk "
                 "half-bonds broken, angle %.2f deg, cover %.3f; strong interface at %.1f us: "
                 "%zu interface, %zu bulk", weak.t * 1e6, weak.n_ifc, weak.n_bulk,
                 weak.angle_deg, weak.cover, strong.t * 1e6, strong.n_ifc, strong.n_bulk);
    const char *src = "the interface: a straight line at 45 deg through the plate";
    if ((rc = vreport_check_true(r, "weak interface: interface bonds break", weak.n_ifc > 0,
                                 src, "issue 26 item 4", err)) ||
        (rc = vreport_check(r, "weak interface: broken bulk half-bonds", "1", 0.0,
                            (double)weak.n_bulk, 0.0, false, src,
                            "0: the crack stays on the interface", err)) ||
        (rc = vreport_check(r, "weak interface: crack direction", "deg", 45.0, weak.angle_deg,
                            2.0, false, src,
                            "2 deg: principal axis of the broken bonds' midpoints", err)) ||
        (rc = vreport_check_true(r, "weak interface: crack runs through (>= 90 % of the "
                                 "interface bonds cut)", weak.cover >= 0.9, src,
                                 "the two materials come apart along the interface", err)) ||
        (rc = vreport_check(r, "strong interface: broken interface half-bonds", "1", 0.0,
                            (double)strong.n_ifc, 0.0, false,
                            "control: interface critical stretch 5x the bulk's",
                            "0: the bulk breaks first", err)))
        return rc;
    return SPALL_OK;
}
