/**
 * @file integrator.c
 * @brief The time step: velocity Verlet (equivalent to the leapfrog of seed
 *        000 Eqs. 22-24: the half-step velocities are the leapfrog
 *        velocities), the predictor-corrector and the state leapfrog;
 *        boundary conditions, gravity, damping, the energy account and the
 *        instability checks.
 *
 * One step, t -> t + dt (the model hooks and where they are called:
 * core/model.h):
 *   1. v(t+dt/2) = v(t) + dt/2 f(t)/m; prescribed components overwritten
 *   2. x(t+dt)   = x(t) + dt v(t+dt/2) (+ dt u, the model's drift velocity)
 *   3. f(t+dt)   = model forces + loads + gravity + damping(v(t+dt/2))
 *   4. v(t+dt)   = v(t+dt/2) + dt/2 f(t+dt)/m; prescribed components set and
 *      the force that took (the reaction) recorded per BC
 *   5. model end_step (bond breaking), adaptive dt, NaN and energy checks.
 * This file alone moves x, changes v, t, dt and the damping coefficient;
 * the model sees only its hooks.
 * sim_reflect_particle mirrors one particle through the field registry's
 * parities plus the integrator's own velocity copies (v_half).
 */
#include "core/bc_work.h"
#include "core/contact_particles.h"
#include "core/exact_sum.h"
#include "core/fields.h"
#include "core/parallel/decomp.h"
#include "core/parallel/comm.h"
#include "core/parallel/psum.h"
#include "core/parallel/step.h"
#include "core/parallel/spatial.h"
#include "core/particles.h"
#include "core/rigid.h"
#include "core/sim.h"
#include "core/model.h"
#include "core/step_passes.h"
#include "spall/error.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Prescribed velocity of BC b at time t, component d. */
static double bc_velocity(const struct bc *b, int d, double t)
{
    if (b->kind == BC_FIXED)
        return 0.0;
    return b->value[d] * time_function_eval(&b->tf, t);
}

static int bc_prescribes_velocity(const struct bc *b)
{
    return b->kind == BC_FIXED || b->kind == BC_VELOCITY;
}

/* Loads (force / traction) shared equally by the group's particles. */
static void apply_loads(struct sim *s, double t)
{
    struct particles *p = s->p;
    for (size_t k = 0; k < s->n_bcs; k++) {
        struct bc *b = &s->bcs[k];
        if (bc_prescribes_velocity(b))
            continue;
        const struct group *g = &s->groups[b->group];
        const size_t gn = sim_group_count(s, b->group); /* over all ranks */
        if (gn == 0)
            continue;
        double scale = time_function_eval(&b->tf, t);
        double total[3] = {0, 0, 0};
        for (int d = 0; d < s->dim; d++) {
            if (!(b->comp_mask & (1u << d)))
                continue;
            total[d] = b->value[d] * scale * (b->kind == BC_TRACTION ? b->area : 1.0);
            double per = total[d] / (double)gn;
            for (size_t q = 0; q < g->n; q++)
                p->f[d][g->idx[q]] += per;
        }
        memcpy(b->reaction, total, sizeof total);
    }
}

/* Gravity and mass-proportional damping, F = m g - c m v_half. */
static void apply_body_forces(struct sim *s)
{
    struct particles *p = s->p;
    const size_t n = p->n_owned;
    for (int d = 0; d < s->dim; d++) {
        const double g = s->gravity[d];
        const double c = s->damping;
        if (g == 0.0 && c == 0.0)
            continue;
        double *restrict f = p->f[d];
        const double *restrict v = p->v[d];
        const double *restrict m = p->mass;
#pragma omp parallel for schedule(static) if (n > SPALL_OMP_MIN_PARTICLES)
        for (size_t i = 0; i < n; i++)
            f[i] += m[i] * (g - c * v[i]);
    }
}

/* Energy removed by damping and work of gravity over the drift dx = v dt.
 * Every sum of the energy account is exact (core/exact_sum.h): the same
 * value, rounded once, for any order, thread count and rank count. */
static void account_body_work(struct sim *s, double dt)
{
    if (s->damping == 0.0 && s->gravity[0] == 0.0 && s->gravity[1] == 0.0 && s->gravity[2] == 0.0)
        return;
    const struct particles *p = s->p;
    const size_t n = p->n_owned;
    const int dim = s->dim;
    const double c = s->damping, *g = s->gravity;
    const bool grav = g[0] != 0.0 || g[1] != 0.0 || g[2] != 0.0;
    struct xsum acc[2];
    xsum_init(&acc[0]);
    xsum_init(&acc[1]);
    /* one term per particle and sum (adding zeros would not change an exact
     * sum); exact partial sums per thread, whose merge does not depend on
     * the thread count or on which thread merges first */
#pragma omp parallel if (n > SPALL_OMP_MIN_PARTICLES)
    {
        struct xsum part[2];
        xsum_init(&part[0]);
        xsum_init(&part[1]);
#pragma omp for schedule(static) nowait
        for (size_t i = 0; i < n; i++) {
            double v2 = 0.0, gv = 0.0;
            for (int d = 0; d < dim; d++) {
                const double v = p->v[d][i];
                v2 += v * v;
                gv += g[d] * v;
            }
            if (c != 0.0)
                xsum_add(&part[0], c * p->mass[i] * v2 * dt);
            if (grav)
                xsum_add(&part[1], p->mass[i] * gv * dt);
        }
#pragma omp critical(spall_exact_sum)
        {
            xsum_merge(&acc[0], &part[0]);
            xsum_merge(&acc[1], &part[1]);
        }
    }
    double out[2];
    par_xsum_finish(s, acc, 2, out); /* over all ranks when distributed */
    s->energy.damping += out[0];
    s->energy.external += out[1];
}

/* Set prescribed velocity components at time t (the previous imposition was
 * at @p t_prev); with @p record (the second half kick), store the force each
 * BC needed to impose them (m dv/(dt/2) - nothing else), i.e. the reaction,
 * and accumulate the constraint's work (core/bc_work.h).  Distributed,
 * g->idx lists the owned members and the exact sums complete over all
 * ranks.  With @p fsave, before the kick instead of after it: each member's
 * velocity is the one the kick would give it (its expression, so its bits),
 * its force goes to fsave (member by member in BC order; the count is
 * returned) and becomes -0.0, with which the kick leaves the imposed
 * velocity as it is (vb + -0.0 = vb for every vb), so a member of a second
 * BC sees the first one's velocity, as after the kick. */
static size_t impose_velocities(struct sim *s, double t_prev, double t, double half_dt,
                                int record, double *fsave)
{
    struct particles *p = s->p;
    size_t nsave = 0;
    for (size_t k = 0; k < s->n_bcs; k++) {
        struct bc *b = &s->bcs[k];
        if (!bc_prescribes_velocity(b))
            continue;
        const struct group *g = &s->groups[b->group];
        struct xsum acc[4]; /* reaction x, y, z; work */
        for (int d = 0; d < 4; d++)
            xsum_init(&acc[d]);
        for (int d = 0; d < s->dim; d++) {
            if (!(b->comp_mask & (1u << d)))
                continue;
            const double vb = bc_velocity(b, d, t), vp = bc_velocity(b, d, t_prev);
            const double v_drift = record ? vp : vb;
            for (size_t q = 0; q < g->n; q++) {
                size_t i = g->idx[q];
                double vi = p->v[d][i];
                if (fsave) {
                    vi = vi + half_dt * p->f[d][i] / p->mass[i];
                    fsave[nsave++] = p->f[d][i];
                    p->f[d][i] = -0.0;
                }
                double dv = vb - vi;
                xsum_add(&acc[d], p->mass[i] * dv / half_dt);
                xsum_add(&acc[3], bc_constraint_work(p->mass[i], vp, vi, vb, v_drift));
                p->v[d][i] = vb;
            }
        }
        double out[4];
        par_xsum_finish(s, acc, 4, out);
        if (record) {
            for (int d = 0; d < 3; d++)
                b->reaction[d] = out[d];
        }
        b->work += out[3];
        s->energy.external += out[3];
    }
    return nsave;
}

/* The forces impose_velocities saved before the kick put back, last saved
 * first (a member of two BCs gets its own force back last). */
static void restore_prescribed_forces(struct sim *s, const double *fsave, size_t nsave)
{
    size_t q = nsave;
    for (size_t k = s->n_bcs; k-- > 0;) {
        const struct bc *b = &s->bcs[k];
        if (!bc_prescribes_velocity(b))
            continue;
        const struct group *g = &s->groups[b->group];
        for (int d = s->dim; d-- > 0;)
            if (b->comp_mask & (1u << d))
                for (size_t m = g->n; m-- > 0;)
                    s->p->f[d][g->idx[m]] = fsave[--q];
    }
}

/* Room for need doubles in *buf (capacity *cap), kept between steps;
 * false, the buffer unchanged, when memory is short. */
static bool reserve_doubles(double **buf, size_t *cap, size_t need)
{
    if (need > *cap) {
        double *b = realloc(*buf, need * sizeof *b);
        if (!b)
            return false;
        *buf = b;
        *cap = need;
    }
    return true;
}

/* Room for the kinetic-energy block sums of the owned particles. */
static bool kinetic_room(struct sim *s)
{
    return reserve_doubles(&s->kinetic_part, &s->kinetic_part_cap,
                           3 * ((s->p->n_owned + STEP_SUM_BLOCK - 1) / STEP_SUM_BLOCK));
}

/* Prescribed velocities for the predicted state (no work, no reaction). */
static void impose_velocities_silent(struct sim *s, double t)
{
    struct particles *p = s->p;
    for (size_t k = 0; k < s->n_bcs; k++) {
        const struct bc *b = &s->bcs[k];
        if (!bc_prescribes_velocity(b))
            continue;
        const struct group *g = &s->groups[b->group];
        for (int d = 0; d < s->dim; d++)
            if (b->comp_mask & (1u << d)) {
                double vb = bc_velocity(b, d, t);
                for (size_t q = 0; q < g->n; q++)
                    p->v[d][g->idx[q]] = vb;
            }
    }
}

static void kick(struct sim *s, double half_dt)
{
    step_kick(s->p, half_dt);
}

/* Positions of the particles whose velocity components a condition sets
 * (the velocity BCs' members, component by component, in BC order), over
 * the fused kick and drift, which drifted them with the kicked velocity:
 * @p save keeps them before the pass, else each becomes x_saved + dt v
 * with v now the imposed velocity, the drift the separate passes would
 * have done after the imposition (a member of two BCs gets the same value
 * twice). */
static void prescribed_positions(struct sim *s, double dt, bool save)
{
    size_t q = 0;
    for (size_t k = 0; k < s->n_bcs; k++) {
        const struct bc *b = &s->bcs[k];
        if (!bc_prescribes_velocity(b))
            continue;
        const struct group *g = &s->groups[b->group];
        for (int d = 0; d < s->dim; d++) {
            if (!(b->comp_mask & (1u << d)))
                continue;
            double *x = s->p->x[d];
            const double *v = s->p->v[d];
            for (size_t m = 0; m < g->n; m++, q++) {
                const size_t i = g->idx[m];
                if (save)
                    s->drift_save[q] = x[i];
                else
                    x[i] = s->drift_save[q] + dt * v[i];
            }
        }
    }
}

/* Room for prescribed_positions and the positions saved: false, saving
 * nothing, when memory is short (the step then kicks, imposes and drifts
 * in separate passes). */
static bool save_prescribed(struct sim *s)
{
    size_t need = 0;
    for (size_t k = 0; k < s->n_bcs; k++)
        if (bc_prescribes_velocity(&s->bcs[k]))
            need += s->groups[s->bcs[k].group].n * (size_t)s->dim;
    if (!reserve_doubles(&s->drift_save, &s->drift_save_cap, need))
        return false;
    prescribed_positions(s, 0.0, true);
    return true;
}

double *const *sim_drift_velocities(const struct sim *s, double *dt)
{
    *dt = sim_step_dt(s); /* the step actually taken (shortened to land on a time) */
    /* the predictor-corrector copies p->v into v_half right after drift() */
    return s->integrator == INTEGRATOR_PREDICTOR_CORRECTOR ? s->v_half : s->p->v;
}

/* The model's drift velocity u (XSPH): x += dt u after x += dt v (two
 * roundings, as when the model moved x itself), except where a BC
 * prescribes the velocity (s->no_drift_velocity, sim_prepare). */
static void drift_extra(struct sim *s, double dt)
{
    const double *u[3] = {NULL, NULL, NULL};
    if (!s->ops->drift_velocity || !s->ops->drift_velocity(s->model, s, u))
        return;
    struct particles *p = s->p;
    const size_t n = p->n_owned;
    const uint8_t *fixed = s->no_drift_velocity;
#pragma omp parallel for schedule(static) if (n > SPALL_OMP_MIN_PARTICLES)
    for (size_t i = 0; i < n; i++)
        if (!fixed[i])
            for (int d = 0; d < s->dim; d++)
                p->x[d][i] += dt * u[d][i];
}

/* Work of the loads over the drift: sum over loaded particles of F . dx
 * (each particle's share of the load: the total over all ranks' members). */
static void account_load_work(struct sim *s, double dt)
{
    const struct particles *p = s->p;
    for (size_t k = 0; k < s->n_bcs; k++) {
        struct bc *b = &s->bcs[k];
        if (bc_prescribes_velocity(b))
            continue;
        const struct group *g = &s->groups[b->group];
        const size_t gn = sim_group_count(s, b->group);
        if (gn == 0)
            continue;
        struct xsum acc;
        xsum_init(&acc);
        for (int d = 0; d < s->dim; d++) {
            if (!(b->comp_mask & (1u << d)))
                continue;
            double per = b->reaction[d] / (double)gn;
            for (size_t q = 0; q < g->n; q++)
                xsum_add(&acc, per * p->v[d][g->idx[q]] * dt);
        }
        double w;
        par_xsum_finish(s, &acc, 1, &w);
        b->work += w;
        s->energy.external += w;
    }
}

/* Axisymmetric runs (x = r): a particle that crossed the axis goes on as
 * the mirror image of its ring (the same ring), r -> -r with every odd
 * quantity (sim_reflect_particle), before the force call sees it. */
static void reflect_axis(struct sim *s)
{
    const struct particles *p = s->p;
    for (size_t i = 0; i < p->n_owned; i++)
        if (p->x[0][i] < 0.0)
            sim_reflect_particle(s, i, 0);
}

/* All forces at the current state.  @p state_dt > 0: the leapfrog's force
 * call, which also advances the model's state by state_dt (compute_forces_kick).
 * @p owned_zeroed: the fused kick and drift cleared the owned forces, or
 * the model's force call writes them (model_ops.sets_forces). */
static int compute_all_forces(struct sim *s, double state_dt, bool owned_zeroed,
                              struct spall_error *err)
{
    if (!owned_zeroed)
        particles_zero_forces(s->p);
    else
        for (int d = 0; d < s->dim; d++) /* the ghosts' */
            memset(s->p->f[d] + s->p->n_owned, 0, (s->p->n - s->p->n_owned) * sizeof(double));
    int rc = SPALL_OK;
    /* ghosts take their owners' drifted positions (spatial ghosts rebuilt first when due) */
    if (s->par && (rc = par_ghosts_step(s, err)))
        return rc;
    if (s->axisymmetric)
        reflect_axis(s);
    rc = state_dt > 0.0 ? s->ops->compute_forces_kick(s->model, s, state_dt, err)
                        : s->ops->compute_forces(s->model, s, err);
    if (rc)
        return rc;
    double c;
    if (s->ops->damping && s->ops->damping(s->model, s, &c))
        s->damping = c; /* adaptive dynamic relaxation */
    rigid_contact_forces(s); /* impactor contact (issue 3) */
    if ((rc = particle_contact_forces(s, err))) /* body-body contact (issue 3) */
        return rc;
    apply_loads(s, s->t);
    apply_body_forces(s);
    return SPALL_OK;
}

void sim_update_energy(struct sim *s)
{
    const struct particles *p = s->p;
    /* exact sum: diagnostics identical for any thread and rank count */
    struct xsum acc;
    xsum_init(&acc);
    for (size_t i = 0; i < p->n_owned; i++) {
        double v2 = 0.0;
        for (int d = 0; d < s->dim; d++)
            v2 += p->v[d][i] * p->v[d][i];
        xsum_add(&acc, 0.5 * p->mass[i] * v2);
    }
    double ke;
    par_xsum_finish(s, &acc, 1, &ke);
    struct model_energy me = {0, 0};
    if (s->ops->energy)
        s->ops->energy(s->model, s, &me);
    double rke, rstrain, rdiss, rext; /* rigid impactors (issue 3) */
    rigid_energy(s, &rke, &rstrain, &rdiss, &rext);
    ke += rke;
    me.strain += rstrain + particle_contact_energy(s);
    me.dissipated += rdiss;
    s->energy.kinetic = ke;
    s->energy.strain = me.strain;
    s->energy.model_dissipated = me.dissipated;
    double total = ke + me.strain + me.dissipated + s->energy.damping - s->energy.external - rext;
    s->energy.balance = total - s->energy.initial_total;
}

int sim_initial_forces(struct sim *s, struct spall_error *err)
{
    int rc = compute_all_forces(s, 0.0, false, err);
    if (s->par) /* distributed set-up: the sums below are collective */
        rc = par_agree(rc, err);
    if (rc)
        return rc;
    impose_velocities(s, 0.0, 0.0, 0.5 * s->dt, 1, NULL);
    /* the initial imposition is a set-up, not work done during the run */
    s->energy.external = 0.0;
    for (size_t k = 0; k < s->n_bcs; k++)
        s->bcs[k].work = 0.0;
    s->energy.initial_total = 0.0;
    sim_update_energy(s);
    s->energy.initial_total = s->energy.kinetic + s->energy.strain + s->energy.model_dissipated;
    s->energy.balance = 0.0;
    return SPALL_OK;
}

/* Find the first particle with a non-finite velocity (a non-finite position
 * makes the forces and hence the velocity non-finite in the same step).
 * The kinetic energy (only the blow-up check reads it) is summed in fixed
 * blocks of particles (STEP_SUM_BLOCK), by the second kick
 * (s->kinetic_fused) or here, the blocks in parallel, and their sums in
 * block order: the same bits on any number of threads, and no serial pass
 * over the particles every step. */
static int check_finite(struct sim *s, size_t *bad, double *kinetic)
{
    const struct particles *p = s->p;
    const double *m = p->mass;
    const size_t n = p->n_owned, nb = (n + STEP_SUM_BLOCK - 1) / STEP_SUM_BLOCK;
    const int dim = s->dim;
    double acc[3] = {0.0, 0.0, 0.0};
    double *part = s->kinetic_fused || kinetic_room(s) ? s->kinetic_part : NULL;
    if (part && !s->kinetic_fused) {
#pragma omp parallel for schedule(static) if (n > SPALL_OMP_MIN_PARTICLES)
        for (size_t b = 0; b < nb; b++) {
            const size_t lo = b * STEP_SUM_BLOCK, hi = n - lo < STEP_SUM_BLOCK ? n : lo + STEP_SUM_BLOCK;
            for (int d = 0; d < dim; d++)
                part[3 * b + (size_t)d] = step_block_mv2(m, p->v[d], lo, hi);
        }
    }
    if (part) {
        for (size_t b = 0; b < nb; b++)
            for (int d = 0; d < dim; d++)
                acc[d] += part[3 * b + (size_t)d];
    } else { /* no memory for the block sums: the same blocks in turn */
        for (size_t lo = 0; lo < n; lo += STEP_SUM_BLOCK)
            for (int d = 0; d < dim; d++)
                acc[d] += step_block_mv2(m, p->v[d], lo,
                                         n - lo < STEP_SUM_BLOCK ? n : lo + STEP_SUM_BLOCK);
    }
    s->kinetic_fused = false;
    *kinetic = 0.0;
    for (int d = 0; d < dim; d++) {
        *kinetic += 0.5 * acc[d]; /* a NaN or Inf in v makes acc non-finite */
        if (!isfinite(acc[d])) {
            for (size_t i = 0; i < n; i++)
                if (!isfinite(p->v[d][i]) || !isfinite(p->x[d][i])) {
                    *bad = i;
                    return 1;
                }
        }
    }
    return 0;
}

static int unstable_error(const struct sim *s, size_t bad, struct spall_error *err)
{
    return spall_error_set(err, SPALL_ERR_UNSTABLE,
                           "run went unstable at step %ld, t = %.6g s: particle %zu (id %lld) "
                           "has a non-finite position or velocity",
                           s->step, s->t, bad, (long long)s->p->gid[bad]);
}

/* A force call that failed on non-finite positions or velocities (the
 * neighbour search refuses them as input) is an unstable run, not bad input. */
static int unstable_or(const struct sim *s, int rc, struct spall_error *err)
{
    const struct particles *p = s->p;
    for (size_t i = 0; i < p->n_owned; i++)
        for (int d = 0; d < s->dim; d++)
            if (!isfinite(p->x[d][i]) || !isfinite(p->v[d][i]))
                return unstable_error(s, i, err);
    return rc;
}

/* Energy blow-up: mechanical energy far above everything ever put in. */
static int energy_blew_up(const struct sim *s, double *ratio)
{
    double input = fabs(s->energy.initial_total) + fabs(s->energy.external);
    double now = s->energy.kinetic + fabs(s->energy.strain);
    if (!(input > 0.0)) {
        *ratio = 0.0;
        return 0;
    }
    *ratio = now / input;
    return !isfinite(now) || *ratio > s->energy_blowup;
}

static size_t fastest_particle(const struct sim *s)
{
    size_t best = 0;
    double vmax = -1.0;
    for (size_t i = 0; i < s->p->n_owned; i++) {
        double v2 = 0;
        for (int d = 0; d < s->dim; d++)
            v2 += s->p->v[d][i] * s->p->v[d][i];
        if (!(v2 <= vmax)) {
            vmax = v2;
            best = i;
            if (isnan(v2))
                break;
        }
    }
    return best;
}

/* The energy blow-up check.  The full account (kinetic + |strain|) costs
 * about one force call, so it runs every energy_check_every steps and at
 * the last (0: never); every step the kinetic energy alone (from the NaN
 * pass, nearly free) screens: kinetic > limit x input is a blow-up by the
 * same criterion (the mechanical energy is at least the kinetic). */
static int check_energy(struct sim *s, double kinetic, struct spall_error *err)
{
    const long every = s->energy_check_every;
    const double input = fabs(s->energy.initial_total) + fabs(s->energy.external);
    const bool due = every > 0 && (s->step % every == 0 || sim_done(s));
    if (!due && !(input > 0.0 && !(kinetic <= s->energy_blowup * input)))
        return SPALL_OK;
    sim_update_energy(s);
    double ratio = 0.0;
    if (!energy_blew_up(s, &ratio))
        return SPALL_OK;
    size_t i = s->par ? 0 : fastest_particle(s);
    long long id = s->par ? (long long)par_fastest_gid(s) : (long long)s->p->gid[i];
    if (s->par) /* a local index means nothing to the user: the gid twice, as serial */
        i = (size_t)id;
    return spall_error_set(err, SPALL_ERR_UNSTABLE,
                           "run went unstable at step %ld, t = %.6g s: mechanical energy "
                           "is %.3g times the energy put in (limit run.energy_blowup = "
                           "%g); fastest particle %zu (id %lld)",
                           s->step, s->t, ratio, s->energy_blowup, i, id);
}

/* A target closer than this (times dt) counts as reached: the rounding
 * sim_prepare allows when it counts the steps to end_time. */
#define STEP_LAND_TOL 1e-9

/* The step before any landing: dt, or the rest of a fixed-dt step that was
 * split at an output time (the steps stay on the grid k dt). */
static double planned_step(const struct sim *s)
{
    if (!s->adaptive_dt && s->dt_rest > 0.0 && s->dt_rest < s->dt)
        return s->dt_rest;
    return s->dt;
}

double sim_step_length(const struct sim *s, double *landing)
{
    const double planned = planned_step(s);
    const double tol = STEP_LAND_TOL * s->dt;
    double h = planned;
    *landing = NAN;
    /* an output time: split the step unless the rest would be negligible */
    const double to_stop = s->stop_time - s->t;
    if (to_stop > tol && to_stop < planned - tol) {
        h = to_stop;
        *landing = s->stop_time;
    }
    /* end_time: the last step is shortened to land on it (issue 24 item 2:
     * a step that overshoots end_time reports a state the user never asked
     * for) */
    const double to_end = s->end_time - s->t;
    if (to_end > 0.0 && to_end <= h) {
        h = to_end;
        *landing = s->end_time;
    }
    return h;
}

/* One step of length dt from s->t, ending at @p landing when that is a
 * number (the target exactly, not t + dt rounded). */
static int advance(struct sim *s, double dt, double landing, struct spall_error *err)
{
    const double half = 0.5 * dt;
    const int pc = s->integrator == INTEGRATOR_PREDICTOR_CORRECTOR;
    const double t_mid = s->t + half;
    /* one pass for the kick, the drift and (not for the predictor-corrector,
     * which kicks with these forces again) clearing the forces; the
     * particles whose velocity a BC sets in between are drifted again */
    const bool fused = save_prescribed(s);
    if (fused) /* a model that sets the forces needs them not cleared */
        step_kick_drift(s->p, half, dt, !pc && !s->ops->sets_forces);
    else
        kick(s, half);
    rigid_kick(s, half, t_mid);
    impose_velocities(s, s->t, t_mid, half, 0, NULL);
    if (fused)
        prescribed_positions(s, dt, false);
    else
        step_drift(s->p, dt);
    drift_extra(s, dt);
    rigid_drift(s, dt);
    account_body_work(s, dt);
    account_load_work(s, dt);
    s->t = isnan(landing) ? s->t + dt : landing;
    s->step++;
    int rc = SPALL_OK;
    if (pc) {
        /* forces of step n+1 see v_pred = v_n + dt a_n = v_half + dt/2 a_n */
        for (int d = 0; d < s->dim; d++)
            memcpy(s->v_half[d], s->p->v[d], s->p->n_owned * sizeof(double));
        kick(s, half);
        impose_velocities_silent(s, s->t);
    }
    if (pc && s->ops->advance_state &&
        (rc = s->ops->advance_state(s->model, s, dt, MODEL_STAGE_PREDICT, err)))
        return unstable_or(s, rc, err);
    const double state_dt = s->integrator == INTEGRATOR_LEAPFROG ? dt : 0.0;
    rc = compute_all_forces(s, state_dt, fused && !pc, err);
    if (s->par && (rc = par_agree(rc, err))) /* one rank's failure stops all */
        return rc;
    if (rc)
        return unstable_or(s, rc, err);
    if (pc)
        for (int d = 0; d < s->dim; d++)
            memcpy(s->p->v[d], s->v_half[d], s->p->n_owned * sizeof(double));
    /* the second kick forms the kinetic-energy sums of the NaN check with
     * the velocities the step ends with (one pass over m and v less): the
     * velocity conditions go first (impose_velocities' fsave), and where
     * something after the kick sets velocities (no-slip impactors, the
     * corrector's model stage) or the sums are per rank (par_check_finite)
     * the check sums them itself */
    s->kinetic_fused = fused && !pc && !s->par && !rigid_sets_velocities(s) && kinetic_room(s);
    if (s->kinetic_fused) {
        const size_t nsave = impose_velocities(s, t_mid, s->t, half, 1, s->drift_save);
        step_kick_sum(s->p, half, s->kinetic_part);
        restore_prescribed_forces(s, s->drift_save, nsave);
        rigid_kick(s, half, s->t);
    } else {
        kick(s, half);
        rigid_kick(s, half, s->t);
        impose_velocities(s, t_mid, s->t, half, 1, NULL);
    }
    rigid_no_slip(s, dt);
    if (pc && s->ops->advance_state &&
        (rc = s->ops->advance_state(s->model, s, dt, MODEL_STAGE_CORRECT, err)))
        return unstable_or(s, rc, err);
    rc = s->ops->end_step(s->model, s, err);
    if (s->par && (rc = par_agree(rc, err))) /* a failure on any rank stops all */
        return rc;
    return rc ? unstable_or(s, rc, err) : SPALL_OK;
}

/* particles.mass_uniform, at a run's first step and after
 * particles_masses_changed: whether every owned mass of every rank is one
 * positive double (a NaN mass counts as different). */
static void check_uniform_mass(struct sim *s)
{
    struct particles *p = s->p;
    double lo = INFINITY, hi = -INFINITY;
    for (size_t i = 0; i < p->n_owned; i++) {
        const double m = p->mass[i];
        lo = m < lo ? m : lo;
        hi = m > hi ? m : hi;
        if (m != m)
            hi = INFINITY;
    }
    if (s->par) {
        lo = par_min_double(lo);
        hi = par_max_double(hi);
    }
    p->mass_uniform = lo == hi && lo > 0.0 && lo < INFINITY ? lo : 0.0;
    p->mass_checked = 1;
}

int sim_step(struct sim *s, struct spall_error *err)
{
    if (!s->p->mass_checked)
        check_uniform_mass(s);
    /* the engine owns dt: a step is shortened here, for every model, to land
     * on end_time or the driver's output time; the hooks see the step
     * actually taken in s->dt_step (sim_step_dt) and the nominal s->dt, which
     * the stiffnesses scaled by the step keep (a penalty k = eta m / dt^2 of
     * a short step would be a stiff spring for all the steps after it) */
    const double planned = planned_step(s);
    double landing;
    const double h = sim_step_length(s, &landing);
    s->dt_step = h;
    int rc = advance(s, h, landing, err);
    s->dt_step = 0.0;
    if (rc)
        return rc;
    if (!s->adaptive_dt) {
        /* a split step (an output time inside it): its rest comes next and
         * the run takes one step more */
        const bool split = !isnan(landing) && landing != s->end_time && h < planned;
        s->dt_rest = split ? planned - h : 0.0;
        s->n_split += split;
    } else {
        /* e.g. SPH, Eq. 3.38: the limit moves with the sound speed and
         * particle velocities (sim_step_length keeps it off end_time) */
        double lim = fmin(s->ops->stable_dt(s->model, s), particle_contact_stable_dt(s));
        if (s->par) /* the smallest over all ranks: min is exact in any order */
            lim = par_min_double(lim);
        double dt_new = s->dt_factor * lim;
        if (dt_new > 0.0 && isfinite(dt_new))
            s->dt = dt_new;
    }
    size_t bad = 0;
    double kinetic = 0.0;
    if (s->par) {
        int64_t g = 0;
        if (par_check_finite(s, &g, &kinetic))
            return spall_error_set(err, SPALL_ERR_UNSTABLE,
                                   "run went unstable at step %ld, t = %.6g s: particle %lld (id "
                                   "%lld) has a non-finite position or velocity",
                                   s->step, s->t, (long long)g, (long long)g);
    } else if (check_finite(s, &bad, &kinetic)) {
        return unstable_error(s, bad, err);
    }
    return check_energy(s, kinetic, err);
}

bool sim_done(const struct sim *s)
{
    if (s->adaptive_dt)
        return s->t >= s->end_time * (1.0 - 1e-12);
    return s->step >= s->n_steps + s->n_split;
}

void sim_reflect_particle(struct sim *s, size_t i, int k)
{
    if (k < 0 || k >= s->dim || i >= s->p->n)
        return;
    field_reflect(s->fields, i, k);
    /* the integrator's private velocity copy: within a predictor-corrector
     * step, v_half is what the corrector kicks from (sim_step restores it
     * after the predicted-velocity force call), so it must be mirrored
     * with p->v, else the particle resumes the unreflected velocity */
    if (s->v_half[k])
        s->v_half[k][i] = -s->v_half[k][i];
}

void sim_group_reaction(const struct sim *s, int g, double out[3])
{
    out[0] = out[1] = out[2] = 0.0;
    for (size_t k = 0; k < s->n_bcs; k++) {
        if (s->bcs[k].group != g)
            continue;
        for (int d = 0; d < 3; d++)
            out[d] += s->bcs[k].reaction[d];
    }
}
