/**
 * @file rigid.h
 * @brief Rigid impactors and supports usable by every particle model: sphere,
 *        cylinder / flat punch (optionally rounded edge), round-nose indenter
 *        and plane wall, with free dynamics M a = R_F + M g ([Wang2010] sec. 3.2)
 *        or prescribed motion, and two contact laws:
 *
 *  - no_slip ([Wang2010] sec. 3.2, Fig. 9): at the end of each step every
 *    particle inside the impactor is put back on its surface along the
 *    surface normal and takes the impactor's velocity; the momentum this
 *    imposes, sum of M_p dv_p, is taken from the impactor (so momentum is
 *    conserved exactly) and sum M_p dv_p / dt is the resistant force R_F.
 *  - penalty: F_n = k delta n on each penetrating particle (delta the depth,
 *    n the outward surface normal), k = eta m_p / dt^2 (eta < 1: the contact
 *    spring alone has omega dt = sqrt(eta) < 2, Verlet-stable) or given;
 *    Coulomb friction |F_t| = min(mu F_n, m_p |v_t| / dt) opposing the
 *    tangential relative velocity (the cap regularises stick: friction never
 *    reverses the slip within a step).  The impactor takes -sum F.
 *
 * Energy: impactor kinetic energy counts as kinetic, penalty energy
 * 1/2 k delta^2 as strain, friction and the velocity matching of no_slip as
 * dissipated, the work of gravity / the prescribed drive / the no_slip
 * position correction as external work.
 * Contact search: a bounding-box filter over the particles, O(N) per step.
 */
#ifndef SPALL_RIGID_H
#define SPALL_RIGID_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "core/time_function.h"

struct sim;
struct spall_error;

enum rigid_shape { RIGID_SPHERE, RIGID_CYLINDER, RIGID_ROUND_NOSE, RIGID_WALL };
enum rigid_motion { RIGID_FREE, RIGID_PRESCRIBED };
enum rigid_contact { RIGID_NO_SLIP, RIGID_PENALTY };

/** One rigid body.  Vectors always have 3 components (z = 0 in 2D). */
struct impactor {
    char name[64];
    enum rigid_shape shape;
    enum rigid_motion motion;
    enum rigid_contact contact;
    double radius;       /**< sphere / cylinder radius [m] */
    double length;       /**< cylinder / round-nose length behind the tip [m] */
    double edge_radius;  /**< cylinder: rounding of the edges [m] */
    double nose_radius;  /**< round-nose: radius of the spherical nose (>= radius) [m] */
    double axis[3];      /**< unit: direction the tip faces (cylinder, round-nose);
                              wall: outward normal (towards the body) */
    double mass;         /**< kg (free motion) */
    bool gravity;        /**< free motion: feels sim->gravity */
    double x[3], x0[3];  /**< reference point: sphere centre, tip centre, wall point */
    double v[3], v0[3];  /**< m/s; prescribed: v = v0 f(t) */
    struct time_function tf;
    double stiffness_factor; /**< eta in k = eta m / dt^2 */
    double stiffness;        /**< k [N/m] per particle; 0: from eta */
    bool stiffness_frozen;   /**< eta: dt of the first contact step, not of each step */
    double k_dt;             /**< frozen: that dt (0 before the first contact) */
    double friction;         /**< Coulomb mu */
    double contact_offset;   /**< contact surface pushed out by this [m] along its
                                  normal (the particles' half spacing: their
                                  surfaces, not centres, meet the body) */
    /* state / diagnostics */
    double f_pen[3];     /**< penalty force of the body on the impactor [N] */
    double f_noslip[3];  /**< no-slip resistant force of the last step [N] */
    double pen_energy;   /**< sum 1/2 k delta^2 [J] */
    double friction_loss, noslip_loss; /**< dissipated [J] */
    double push_work;    /**< work of the no-slip position correction [J] */
    double drive_work;   /**< work of the prescribed drive [J] */
    double gravity_work; /**< work of gravity on the impactor [J] */
    size_t n_contact;    /**< particles in contact */
};

/** The impactors of a simulation (owned by struct sim). */
struct rigid_set {
    struct impactor *im;
    size_t n;
    /* distributed runs: this rank's contacts of one impactor, one row each
     * keyed by gid, reduced in gid order (rigid_par_prepare) */
    int64_t *par_key;
    double *par_row;
    size_t par_cap; /**< rows they hold */
};

/** Append a copy of @p im (takes ownership of its time function). */
int rigid_add(struct sim *s, const struct impactor *im, struct spall_error *err);
void rigid_set_destroy(struct rigid_set **rs);

/** Signed distance of point @p x to the impactor surface (< 0 inside) and
 *  the outward unit normal. */
double rigid_distance(const struct impactor *im, const double x[3], double n[3]);

/** Integrator hooks; all are no-ops when the simulation has no impactor. */
void rigid_kick(struct sim *s, double half_dt, double t);
void rigid_drift(struct sim *s, double dt);
void rigid_contact_forces(struct sim *s);
void rigid_no_slip(struct sim *s, double dt);
/** Whether rigid_no_slip can set particle velocities (a no-slip impactor). */
bool rigid_sets_velocities(const struct sim *s);
/** Distributed runs, after the partition (and after any change of the
 *  owned set): room for one contact row per owned particle, so that the
 *  contact loops never allocate (and never fail on one rank only).  Every rank sums the contacts of all ranks in gid
 *  order, so the impactors' state is the serial one on every rank. */
int rigid_par_prepare(struct sim *s, struct spall_error *err);
/** Energies of the impactors: kinetic, strain (penalty), dissipated, external. */
void rigid_energy(const struct sim *s, double *kinetic, double *strain, double *dissipated,
                  double *external);
/** Energy the impactor has given to the body so far: initial KE - KE +
 *  gravity work + drive work [J]. */
double rigid_absorbed(const struct impactor *im);

/** history.csv columns of impactor k (names into @p store), count returned. */
#define RIGID_HISTORY_COLS 14
size_t rigid_history_names(const struct sim *s, size_t k, char store[][96]);
size_t rigid_history_values(const struct sim *s, size_t k, double *v);

#endif
