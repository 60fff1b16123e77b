/**
 * @file sph_debris.c
 * @brief SPH validation case "sph-debris-cloud": hypervelocity impact of an
 *        aluminium sphere (d = 10 mm) on a 4 mm aluminium plate at
 *        6.18 km/s, axisymmetric -- the debris-cloud problem of [Meng2021]
 *        chapter 2 (Hiermaier et al., IJIE 20 (1997) 363, ref. [73]).
 *
 * The shot: [Meng2021] sec. 2 describes the Al-Al shot that Zhang & Liu
 * (EABE 83 (2017) 141, ref. [86]) reproduce from ref. [73] as a 1.0 cm Al
 * projectile on a 0.4 cm Al plate at 6180 m/s (ref. [73] itself: 0.15 to
 * 0.4 cm plates at 5.75 to 6.85 km/s).  Until this change the case used a
 * 2 mm plate (a guess); it now uses 4 mm (t/d = 0.4).
 *
 * Deck: examples/sph_debris_cloud/sph_debris_cloud.yaml (Al 1100,
 * Mie-Grueneisen with Steinberg's constants, elastic-perfectly plastic
 * 0.1 GPa, failure at plastic strain 0.5; Wendland, h = 1.3 dx, AV (1, 1),
 * XSPH 0.1), built here at dx = d/20, d/40, d/60 (quick: d/20 only).
 *
 * Measured at 20 us after contact: the debris cloud = all particles behind
 * the plate's rear face (z < -4 mm), plate and projectile material alike.
 * Length = axial extent from the rear face to the cloud's front; width =
 * 2 x the largest radius in the cloud.  Both also as mass quantiles (the
 * front / radius below which 99 % of the cloud's mass lies), because single
 * spalled particles set the extremes.  Hole = 2 x the smallest radius of
 * plate material still in the plate (moved less than a plate thickness).
 *
 * Reference values: ref. [73] could not be read here.  Its experimental
 * numbers were found only second-hand, in a course-project README that
 * cites ref. [73] (github: an "SPH HVI Solver -- AOE 5404" repository, Virginia
 * Tech, 2026; found with the code search): hole (crater) diameter 3.10 cm,
 * debris-cloud length / width 1.39 (experiment), 1.11 from ref. [73]'s own
 * 2D SPH; the time of the radiograph is not given there.  Checks: (1) axial
 * momentum to 0.1 %; (2) length and width converged (d/40 -> d/60 within
 * 5 %); (3) hole diameter against 31.0 mm and (4) length / width (99 %
 * mass) at 20 us against 1.39, both within 10 % -- the reference values are
 * unverified, the material is ours (not ref. [73]'s Johnson-Cook /
 * Tillotson) and the radiograph's time is unknown: failures are recorded as
 * documented gaps; (5) length / width against ref. [73]'s SPH value 1.11,
 * within 10 %.
 */
#include "validation/lattice_cases.h"
#include "validation/sph_cases.h"
#include "validation/validation.h"

#include "core/particles.h"
#include "core/sim.h"
#include "spall/error.h"

#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>

#define DEB_D 10.0e-3     /* sphere diameter [m] */
#define DEB_T 4.0e-3      /* plate thickness [m] (ref. [86]'s account of ref. [73]) */
#define DEB_RP 30.0e-3    /* plate radius [m] */
#define DEB_V0 6180.0     /* impact speed [m/s] */
#define DEB_TIME 20.0e-6  /* measurement time after contact [s] */
#define DEB_HOLE_REF 31.0e-3 /* hole diameter, experiment (second-hand, see above) [m] */
#define DEB_LW_REF 1.39      /* cloud length / width, experiment (second-hand) */
#define DEB_LW_SPH 1.11      /* the same from ref. [73]'s own 2D SPH (second-hand) */

struct deb_pair {
    double value, mass;
};

static int deb_cmp(const void *a, const void *b)
{
    double x = ((const struct deb_pair *)a)->value, y = ((const struct deb_pair *)b)->value;
    return (x > y) - (x < y);
}

/* The value below which a fraction q of the mass lies (pairs sorted here). */
static double deb_quantile(struct deb_pair *pr, size_t n, double q)
{
    if (n == 0)
        return 0.0;
    qsort(pr, n, sizeof *pr, deb_cmp);
    double total = 0.0, acc = 0.0;
    for (size_t i = 0; i < n; i++)
        total += pr[i].mass;
    for (size_t i = 0; i < n; i++) {
        acc += pr[i].mass;
        if (acc >= q * total)
            return pr[i].value;
    }
    return pr[n - 1].value;
}

int sph_debris_run(int n, double plate, double time, struct sph_debris_result *out,
                   struct spall_error *err)
{
    const double dx = DEB_D / n;
    char deck[3072];
    /* the sphere's centre at z = d/2: its lowest particle row lies dx/2
     * above the plate's top row (at -dx/2), the surfaces touch at t = 0 */
    snprintf(deck, sizeof deck,
             "model: {type: sph, plane: axisymmetric, kernel: wendland, h_factor: 1.3,\n"
             "        viscosity: [1.0, 1.0], xsph: 0.1}\n"
             "materials:\n"
             "  al: {density: 2707, youngs_modulus: 69.0e9, poisson_ratio: 0.33,\n"
             "       eos: mie_gruneisen, sound_speed: 5386, hugoniot_slope: 1.339,\n"
             "       gruneisen: 1.97, yield: perfect, yield_stress: 0.1e9,\n"
             "       failure: plastic_strain, failure_value: 0.5}\n"
             "lattice: {type: square, spacing: %.17g, origin: [%.17g, %.17g]}\n"
             "geometry:\n"
             "  plate: {box: {min: [0, %.17g], max: [%.17g, 0]}}\n"
             "  ball: {intersection: [{circle: {center: [0, %.17g], radius: %.17g}},\n"
             "                        {box: {min: [0, 0], max: [%.17g, %.17g]}}]}\n"
             "bodies:\n"
             "  - {geometry: plate, material: al}\n"
             "  - {geometry: ball, material: al}\n"
             "groups:\n"
             "  projectile: ball\n"
             "initial_velocity: [{group: projectile, value: [0, %.17g]}]\n"
             "run: {end_time: %.17g, dt_factor: 0.3}\n",
             dx, 0.5 * dx, 0.5 * dx, -plate, DEB_RP, 0.5 * DEB_D, 0.5 * DEB_D, 0.6 * DEB_D,
             1.1 * DEB_D, -DEB_V0, time);
    struct sim *s = NULL;
    int rc = vlat_build("sph_debris", deck, &s, err);
    if (rc)
        return rc;
    const struct particles *p = s->p;
    double pz0 = 0.0;
    for (size_t i = 0; i < p->n; i++)
        pz0 += p->mass[i] * p->v[1][i];
    double t0 = omp_get_wtime();
    while (!rc && !sim_done(s))
        rc = sim_step(s, err);
    out->seconds = omp_get_wtime() - t0;
    if (rc) {
        sim_destroy(&s);
        return rc;
    }
    struct deb_pair *zr = malloc((2 * p->n + 1) * sizeof *zr);
    if (!zr) {
        sim_destroy(&s);
        return spall_error_set(err, SPALL_ERR_NOMEM, "sph_debris: out of memory");
    }
    struct deb_pair *rr = zr + p->n;
    size_t nd = 0;
    double pz = 0.0, dmax = 0.0, rmax = 0.0, mdeb = 0.0, mtot = 0.0, rhole = DEB_RP;
    for (size_t i = 0; i < p->n; i++) {
        pz += p->mass[i] * p->v[1][i];
        mtot += p->mass[i];
        /* the hole: plate material still in the plate (moved less than one
         * plate thickness along the axis; the lip bends back but stays) */
        if (p->x0[1][i] < 0.0 && fabs(p->x[1][i] - p->x0[1][i]) < plate)
            rhole = fmin(rhole, p->x[0][i]);
        if (p->x[1][i] >= -plate)
            continue;
        double depth = -plate - p->x[1][i];
        zr[nd] = (struct deb_pair){depth, p->mass[i]};
        rr[nd] = (struct deb_pair){p->x[0][i], p->mass[i]};
        dmax = fmax(dmax, depth);
        rmax = fmax(rmax, p->x[0][i]);
        mdeb += p->mass[i];
        nd++;
    }
    out->hole_diameter = 2.0 * rhole;
    out->length_max = dmax;
    out->width_max = 2.0 * rmax;
    out->length_q = deb_quantile(zr, nd, 0.99);
    out->width_q = 2.0 * deb_quantile(rr, nd, 0.99);
    out->debris_mass_fraction = mdeb / mtot;
    out->momentum_error = fabs(pz - pz0) / fabs(pz0);
    out->particles = p->n;
    out->debris_particles = nd;
    free(zr);
    sim_destroy(&s);
    return SPALL_OK;
}

int sph_case_debris(struct vreport *r, struct spall_error *err)
{
    static const int series[3] = {20, 40, 60};
    const int last = r->quick ? 0 : 2;
    struct sph_debris_result res[3];
    for (int k = 0; k <= last; k++) {
        int rc = sph_debris_run(series[k], DEB_T, DEB_TIME, &res[k], err);
        if (rc)
            return rc;
        vreport_info(r, "debris cloud, d/%d (%zu particles, %zu in the cloud, %.1f %% of the "
                     "mass): at 20 us length %.2f mm (99 %% of the mass: %.2f), width %.2f mm "
                     "(99 %%: %.2f), L/W %.3f (99 %%: %.3f), hole %.2f mm, axial momentum "
                     "error %.2g (%.0f s)",
                     series[k], res[k].particles, res[k].debris_particles,
                     100.0 * res[k].debris_mass_fraction, res[k].length_max * 1e3,
                     res[k].length_q * 1e3, res[k].width_max * 1e3, res[k].width_q * 1e3,
                     res[k].length_max / res[k].width_max, res[k].length_q / res[k].width_q,
                     res[k].hole_diameter * 1e3, res[k].momentum_error, res[k].seconds);
    }
    const struct sph_debris_result *f = &res[last];
    int rc;
    if ((rc = vreport_check(r, "axial momentum, |P_z(20 us) - P_z(0)| / |P_z(0)|", "1", 0.0,
                            f->momentum_error, 1e-3, false,
                            "conservation: pair forces antisymmetric except the axis images",
                            "0.1 %: negligible against the 1 % cloud measures", err)))
        return rc;
    if (last > 0) {
        const struct sph_debris_result *g = &res[last - 1];
        double dl = fabs(f->length_q - g->length_q) / f->length_q;
        double dw = fabs(f->width_q - g->width_q) / f->width_q;
        if ((rc = vreport_check(r, "cloud length (99 % mass) change, d/40 -> d/60", "1", 0.0, dl,
                                0.05, false, "convergence",
                                "5 %: a cloud edge resolved to ~1 dx of d/40", err)))
            return rc;
        if (!r->checks[r->n - 1].pass)
            vreport_mark_gap(r, "GAP: cloud length not converged in dx; see "
                                "docs/notes/validation-log.md");
        if ((rc = vreport_check(r, "cloud width (99 % mass) change, d/40 -> d/60", "1", 0.0, dw,
                                0.05, false, "convergence",
                                "5 %: a cloud edge resolved to ~1 dx of d/40", err)))
            return rc;
        if (!r->checks[r->n - 1].pass)
            vreport_mark_gap(r, "GAP: cloud width not converged in dx; see "
                                "docs/notes/validation-log.md");
    }
    static const char src[] = "Hiermaier et al. 1997 ([Meng2021] ref. [73]) experiment, "
                              "second-hand (course-project README citing it)";
    if ((rc = vreport_check(r, "hole diameter in the plate", "m", DEB_HOLE_REF,
                            f->hole_diameter, 0.10, true, src,
                            "10 %: unverified value, our Al 1100 EPP material, not ref. [73]'s",
                            err)))
        return rc;
    if (!r->checks[r->n - 1].pass)
        vreport_mark_gap(r, "GAP: hole diameter outside 10 % of the second-hand experimental "
                            "value; see docs/notes/validation-log.md");
    if ((rc = vreport_check(r, "cloud length / width (99 % mass) at 20 us", "1", DEB_LW_REF,
                            f->length_q / f->width_q, 0.10, true, src,
                            "10 %: unverified value, radiograph time unknown (L/W still "
                            "grows at 20 us)",
                            err)))
        return rc;
    if (!r->checks[r->n - 1].pass)
        vreport_mark_gap(r, "GAP: cloud L/W outside 10 % of the second-hand experimental value "
                            "(ref. [73]'s own 2D SPH: 1.11); see docs/notes/validation-log.md");
    if ((rc = vreport_check(r, "cloud length / width (99 % mass) at 20 us vs ref. [73]'s SPH",
                            "1", DEB_LW_SPH, f->length_q / f->width_q, 0.10, true,
                            "Hiermaier et al. 1997 2D SPH, second-hand (same README)",
                            "10 %: same method class; time and their cloud edge not known",
                            err)))
        return rc;
    if (!r->checks[r->n - 1].pass)
        vreport_mark_gap(r, "GAP: cloud L/W outside 10 % of ref. [73]'s SPH value; see "
                            "docs/notes/validation-log.md");
    return SPALL_OK;
}
