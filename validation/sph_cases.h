/**
 * @file sph_cases.h
 * @brief Validation cases of the SPH model ([Meng2021] chapter 3), run by
 *        `spall validate` through validation/cases.c.  Numbers are
 *        tabulated in docs/notes/validation-log.md.
 */
#ifndef SPALL_VALIDATION_SPH_CASES_H
#define SPALL_VALIDATION_SPH_CASES_H

#include <stdbool.h>
#include <stddef.h>

struct vreport;
struct spall_error;

/** "sph-gradient": CSPM reproduces a linear velocity field's gradient
 *  exactly, free surfaces included (fast, quick suite). */
int sph_case_gradient(struct vreport *r, struct spall_error *err);
/** "sph-beam": cantilever, 1.75 kN, six kernels vs 33.59 mm (Table 3.4). */
int sph_case_beam(struct vreport *r, struct spall_error *err);
/** "sph-beam-large": cantilever, 17.5 kN, six kernels and TLSPH vs 81.1 mm,
 *  which kernels crack ([Meng2021] sec. 3.4.1). */
int sph_case_beam_large(struct vreport *r, struct spall_error *err);
/** "sph-leapfrog": the leapfrog keeps an undamped plate's energy (quick). */
int sph_case_leapfrog(struct vreport *r, struct spall_error *err);
/** "sph-plate": oscillating plate period vs thin-plate theory (Gray et al. 2001). */
int sph_case_plate(struct vreport *r, struct spall_error *err);
/** "sph-taylor-3d": 4340 steel Taylor bar, 181 m/s, Johnson-Cook (Table 3.6). */
int sph_case_taylor3d(struct vreport *r, struct spall_error *err);

/** One 3D Taylor-bar run (n particles across; quarter model with mirror
 *  planes when @p quarter; @p power_law: yield a + b eps_p^n without rate
 *  and heating instead of Johnson-Cook): final length, mushroom radius,
 *  outer radius 0.5 mm above the face (@p r05, may be NULL) [m], particle
 *  count, wall seconds.  Under mpirun the sim is distributed through
 *  @p r (vpar.h) and the bar's shape read by global id. */
int sph_taylor3d_run(struct vreport *r, int n, bool quarter, bool power_law, double *len,
                     double *rad, double *r05, size_t *np, double *secs, struct spall_error *err);

/** Outcome of one 2D Taylor-rod run (sph_taylor2d.c): [0] at t1, [1] at t2. */
struct sph_taylor2d_result {
    double len[2], rad[2], undeformed[2]; /**< final length, foot radius, undeformed length [m] */
    double prof[2][2]; /**< outer radius 0.5 mm / 1 mm above the impact face [m] (profile.h) */
    double balance[2];                    /**< energy balance / initial kinetic energy */
    double v_end;                         /**< mean axial velocity at t2 [m/s] */
    size_t particles;
    double seconds;
};
/** "sph-taylor-2d": iron rod of [Meng2021] Table 3.5 (Libersky & Petschek). */
int sph_case_taylor2d(struct vreport *r, struct spall_error *err);
/** One 2D rod run with @p n particles across the diameter, sampled at t1 and
 *  t2; @p axisymmetric: 1 = axisymmetric rod (r, z), 0 = plane strain;
 *  @p av: extra model keys for the artificial viscosity (e.g.
 *  "viscosity_length: 2.4e-4"), NULL or "" for the thesis form. */
int sph_taylor2d_run(int n, int axisymmetric, const char *av, double t1, double t2,
                     struct sph_taylor2d_result *out, struct spall_error *err);

/** Time the rings case runs: contact, rebound and separation. */
#define SPH_RINGS_END_TIME 1.0e-2

/** Outcome of one rubber-ring collision (sph_rings.c). */
struct sph_rings_result {
    size_t particles, components, singles;
    double v0, v_left, v_right;     /**< initial speed, final ring v_cm [m/s] */
    double balance_max, balance_end; /**< |E_kin + E_int - E_0| / E_0 */
    double kinetic_end;             /**< E_kin / E_0 at the end */
    double seconds;
};
/** "sph-rings": two rubber rings collide and rebound (Gray et al. 2001). */
int sph_case_rings(struct vreport *r, struct spall_error *err);
/** One collision with spacing @p dx until @p end_time (under mpirun
 *  distributed over the ranks of @p r, vpar.h). */
int sph_rings_run(struct vreport *r, double dx, double end_time, struct sph_rings_result *out,
                  struct spall_error *err);

/** Outcome of one debris-cloud run (sph_debris.c), measured at the end time. */
struct sph_debris_result {
    double length_max, width_max; /**< cloud extent behind the plate, 2 x max radius [m] */
    double length_q, width_q;     /**< the same as 99 % mass quantiles [m] */
    double hole_diameter;         /**< 2 x the smallest radius of plate material left in the plate [m] */
    double debris_mass_fraction;  /**< cloud mass / total mass */
    double momentum_error;        /**< |P_z(end) - P_z(0)| / |P_z(0)| */
    size_t particles, debris_particles;
    double seconds;
};
/** "sph-debris-cloud": Al sphere 10 mm on a 4 mm Al plate at 6.18 km/s
 *  ([Meng2021] chapter 2, Hiermaier et al. 1997), axisymmetric. */
int sph_case_debris(struct vreport *r, struct spall_error *err);
/** One debris-cloud run with @p n particles across the sphere's diameter, a
 *  plate of thickness @p plate [m], measured at @p time after contact [s]. */
int sph_debris_run(int n, double plate, double time, struct sph_debris_result *out,
                   struct spall_error *err);

#endif
