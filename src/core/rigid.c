/**
 * @file rigid.c
 * @brief Rigid impactors and supports (see rigid.h): shapes as signed
 *        distance functions, contact laws, dynamics and diagnostics.
 *
 * The contact loops are serial on purpose: they visit only the particles in
 * the impactor's bounding box (a cheap O(N) filter) and sum the impactor's
 * force in a fixed order, so the result is bitwise independent of the number
 * of threads.  On a distributed run each rank visits its owned particles and
 * records each contact's terms keyed by gid; par_ordered_reduce adds the
 * contacts of all ranks in gid order (the serial order) and hands every rank
 * the sums, so every rank moves each impactor as one rank would
 * (docs/parallel.md).
 */
#include "core/rigid.h"

#include "core/parallel/decomp.h"
#include "core/particles.h"
#include "core/sim.h"
#include "spall/error.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static double dot3(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

int rigid_add(struct sim *s, const struct impactor *im, struct spall_error *err)
{
    if (!s->rigid) {
        s->rigid = calloc(1, sizeof *s->rigid);
        if (!s->rigid)
            return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory adding impactor");
    }
    struct rigid_set *rs = s->rigid;
    for (size_t k = 0; k < rs->n; k++)
        if (strcmp(rs->im[k].name, im->name) == 0)
            return spall_error_set(err, SPALL_ERR_INPUT, "impactor '%s' defined twice", im->name);
    struct impactor *grown = realloc(rs->im, (rs->n + 1) * sizeof *grown);
    if (!grown)
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory adding impactor");
    rs->im = grown;
    rs->im[rs->n] = *im;
    struct impactor *q = &rs->im[rs->n];
    memcpy(q->x0, q->x, sizeof q->x0);
    if (q->motion == RIGID_FREE)
        memcpy(q->v0, q->v, sizeof q->v0);
    else
        for (int d = 0; d < 3; d++)
            q->v[d] = q->v0[d] * time_function_eval(&q->tf, 0.0);
    rs->n++;
    return SPALL_OK;
}

void rigid_set_destroy(struct rigid_set **rs)
{
    if (!rs || !*rs)
        return;
    for (size_t k = 0; k < (*rs)->n; k++)
        time_function_free(&(*rs)->im[k].tf);
    free((*rs)->im);
    free((*rs)->par_key);
    free((*rs)->par_row);
    free(*rs);
    *rs = NULL;
}

/* Rounded box in the (rho, s) half plane: rho in [0, R], s in [s0, s1],
 * corners rounded by re.  Returns the distance and the gradient (g_rho, g_s). */
static double rounded_box(double rho, double s, double R, double s0, double s1, double re,
                          double g[2])
{
    double hs = 0.5 * (s1 - s0), cs = 0.5 * (s1 + s0);
    double sgn = s >= cs ? 1.0 : -1.0;
    double qx = rho - (R - re), qy = fabs(s - cs) - (hs - re);
    double ox = qx > 0 ? qx : 0, oy = qy > 0 ? qy : 0;
    double out = sqrt(ox * ox + oy * oy);
    double phi;
    if (out > 0) {
        g[0] = ox / out;
        g[1] = sgn * oy / out;
        phi = out - re;
    } else if (qx > qy) {
        g[0] = 1.0;
        g[1] = 0.0;
        phi = qx - re;
    } else {
        g[0] = 0.0;
        g[1] = sgn;
        phi = qy - re;
    }
    return phi;
}

double rigid_distance(const struct impactor *im, const double x[3], double n[3])
{
    double r[3] = {x[0] - im->x[0], x[1] - im->x[1], x[2] - im->x[2]};
    if (im->shape == RIGID_WALL) {
        memcpy(n, im->axis, 3 * sizeof *n);
        return dot3(r, im->axis);
    }
    if (im->shape == RIGID_SPHERE) {
        double d = sqrt(dot3(r, r));
        if (d > 0) {
            for (int k = 0; k < 3; k++)
                n[k] = r[k] / d;
        } else {
            n[0] = 1.0;
            n[1] = n[2] = 0.0;
        }
        return d - im->radius;
    }
    /* axisymmetric: s = depth behind the tip along -axis, rho = lateral */
    const double *a = im->axis;
    double h = dot3(r, a);
    double s = -h;
    double lat[3] = {r[0] - h * a[0], r[1] - h * a[1], r[2] - h * a[2]};
    double rho = sqrt(dot3(lat, lat));
    double rhat[3] = {0, 0, 0};
    if (rho > 0)
        for (int k = 0; k < 3; k++)
            rhat[k] = lat[k] / rho;
    double g[2];
    double phi;
    if (im->shape == RIGID_CYLINDER) {
        phi = rounded_box(rho, s, im->radius, 0.0, im->length, im->edge_radius, g);
    } else {
        /* round nose: sphere of radius Rn centred Rn behind the tip, cut where
         * it meets the shank radius R (depth s_j), union the shank */
        double Rn = im->nose_radius, R = im->radius;
        double sj = Rn - sqrt(Rn * Rn - R * R);
        double gc[2];
        double phic = rounded_box(rho, s, R, sj, im->length, 0.0, gc);
        double ds = s - Rn; /* depth relative to the sphere centre */
        double dsph = sqrt(rho * rho + ds * ds);
        double phis = dsph - Rn;
        double gs[2] = {dsph > 0 ? rho / dsph : 0.0, dsph > 0 ? ds / dsph : -1.0};
        /* sphere cut to s <= sj: max(phis, s - sj) */
        double phicap = phis;
        double gcap[2] = {gs[0], gs[1]};
        if (s - sj > phis) {
            phicap = s - sj;
            gcap[0] = 0.0;
            gcap[1] = 1.0;
        }
        if (phicap <= phic) {
            phi = phicap;
            g[0] = gcap[0];
            g[1] = gcap[1];
        } else {
            phi = phic;
            g[0] = gc[0];
            g[1] = gc[1];
        }
    }
    /* d/ds points along -axis */
    for (int k = 0; k < 3; k++)
        n[k] = g[0] * rhat[k] - g[1] * a[k];
    double nn = sqrt(dot3(n, n));
    if (nn > 0)
        for (int k = 0; k < 3; k++)
            n[k] /= nn;
    return phi;
}

/* Axis-aligned box holding the impactor; a wall has none (all particles). */
static int bounding_box(const struct impactor *im, double lo[3], double hi[3])
{
    double c[3], R;
    if (im->shape == RIGID_WALL)
        return 0;
    if (im->shape == RIGID_SPHERE) {
        memcpy(c, im->x, sizeof c);
        R = im->radius;
    } else {
        double half = 0.5 * im->length;
        double rad = im->shape == RIGID_ROUND_NOSE && im->nose_radius > im->radius
                         ? im->nose_radius
                         : im->radius;
        for (int d = 0; d < 3; d++)
            c[d] = im->x[d] - half * im->axis[d];
        R = sqrt(half * half + rad * rad);
    }
    R += im->contact_offset;
    for (int d = 0; d < 3; d++) {
        lo[d] = c[d] - R;
        hi[d] = c[d] + R;
    }
    return 1;
}

static int in_box(const double x[3], const double lo[3], const double hi[3], int dim)
{
    for (int d = 0; d < dim; d++)
        if (x[d] < lo[d] || x[d] > hi[d])
            return 0;
    return 1;
}

static void particle_pos(const struct particles *p, int dim, size_t i, double x[3])
{
    x[0] = x[1] = x[2] = 0.0;
    for (int d = 0; d < dim; d++)
        x[d] = p->x[d][i];
}

void rigid_kick(struct sim *s, double half_dt, double t)
{
    if (!s->rigid)
        return;
    for (size_t k = 0; k < s->rigid->n; k++) {
        struct impactor *im = &s->rigid->im[k];
        if (im->motion == RIGID_PRESCRIBED) {
            double f = time_function_eval(&im->tf, t);
            for (int d = 0; d < 3; d++)
                im->v[d] = im->v0[d] * f;
            continue;
        }
        for (int d = 0; d < s->dim; d++) {
            double g = im->gravity ? s->gravity[d] : 0.0;
            im->v[d] += half_dt * (im->f_pen[d] / im->mass + g);
        }
    }
}

void rigid_drift(struct sim *s, double dt)
{
    if (!s->rigid)
        return;
    for (size_t k = 0; k < s->rigid->n; k++) {
        struct impactor *im = &s->rigid->im[k];
        for (int d = 0; d < s->dim; d++) {
            if (im->motion == RIGID_FREE && im->gravity)
                im->gravity_work += im->mass * s->gravity[d] * im->v[d] * dt;
            if (im->motion == RIGID_PRESCRIBED)
                im->drive_work -= im->f_pen[d] * im->v[d] * dt;
            im->x[d] += dt * im->v[d];
        }
    }
}

/* Signed gap between particle centre x and the body's contact surface
 * (penalty and no-slip contact alike): contact_offset pushes the surface
 * out, since a particle stands for a cell of its spacing and its surface,
 * dx/2 ahead of its centre, meets the body. */
static inline double contact_gap(const struct impactor *im, const double x[3], double nrm[3])
{
    return rigid_distance(im, x, nrm) - im->contact_offset;
}

/* Distributed runs: one row of a rank's contact terms (at most 9 numbers,
 * rigid_par_prepare); the reducers below add them in the serial loops'
 * order, particle by particle in gid order. */
#define RIGID_PAR_COLS 9

int rigid_par_prepare(struct sim *s, struct spall_error *err)
{
    struct rigid_set *rs = s->rigid;
    if (!rs || !s->par)
        return SPALL_OK;
    size_t n = s->p->n_owned ? s->p->n_owned : 1;
    free(rs->par_key);
    free(rs->par_row);
    rs->par_key = malloc(n * sizeof *rs->par_key);
    rs->par_row = malloc(n * RIGID_PAR_COLS * sizeof *rs->par_row);
    rs->par_cap = rs->par_key && rs->par_row ? n : 0;
    if (!rs->par_cap)
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory for impactor contacts of %zu "
                               "particles", n);
    return SPALL_OK;
}

/* rows: f (3), 1/2 k delta^2, friction loss -> f_pen (3), energy, loss, count */
static void reduce_penalty(const double *rows, size_t n, int ncol, double *out, const void *ctx)
{
    const int dim = *(const int *)ctx;
    double fp[3] = {0.0, 0.0, 0.0}, e = 0.0, fl = 0.0;
    for (size_t q = 0; q < n; q++) {
        const double *r = rows + q * (size_t)ncol;
        for (int d = 0; d < dim; d++)
            fp[d] -= r[d];
        e += r[3];
        fl += r[4];
    }
    memcpy(out, fp, sizeof fp);
    out[3] = e;
    out[4] = fl;
    out[5] = (double)n;
}

/* rows: m dv (3), f dx (3), kinetic change (3) per component ->
 * J (3), push work, kinetic change, count */
static void reduce_no_slip(const double *rows, size_t n, int ncol, double *out, const void *ctx)
{
    const int dim = *(const int *)ctx;
    double J[3] = {0.0, 0.0, 0.0}, push = 0.0, ke = 0.0;
    for (size_t q = 0; q < n; q++) {
        const double *r = rows + q * (size_t)ncol;
        for (int d = 0; d < dim; d++) {
            push -= r[3 + d];
            J[d] += r[d];
            ke += r[6 + d];
        }
    }
    memcpy(out, J, sizeof J);
    out[3] = push;
    out[4] = ke;
    out[5] = (double)n;
}

/* A distributed run whose owned set grew since rigid_par_prepare: grow the
 * rows first (the loops write one per contact, at most n_owned). */
static void par_rows_fit(struct sim *s)
{
    if (s->par && s->p->n_owned > s->rigid->par_cap)
        rigid_par_prepare(s, NULL); /* on failure par_cap is 0 and no row is written */
}

void rigid_contact_forces(struct sim *s)
{
    if (!s->rigid)
        return;
    par_rows_fit(s);
    struct particles *p = s->p;
    const int dim = s->dim;
    const double dt = s->dt > 0 ? s->dt : 1.0;
    for (size_t k = 0; k < s->rigid->n; k++) {
        struct impactor *im = &s->rigid->im[k];
        memset(im->f_pen, 0, sizeof im->f_pen);
        im->pen_energy = 0.0;
        if (im->contact != RIGID_PENALTY)
            continue;
        double lo[3], hi[3];
        int boxed = bounding_box(im, lo, hi);
        size_t nc = 0;
        double floss = 0.0;
        struct rigid_set *rs = s->rigid;
        /* stiffness_dt first_contact: k = eta m / dt^2 with the dt of the
         * first contact step (stored below once a particle touched),
         * constant after: a k that follows the adaptive dt (SPH: dt drops
         * 6x as the first particle is hit) stiffens compressed springs and
         * creates energy */
        const double dk = im->stiffness_frozen && im->k_dt > 0.0 ? im->k_dt : dt;
        for (size_t i = 0; i < p->n_owned; i++) {
            double x[3], nrm[3];
            particle_pos(p, dim, i, x);
            if (boxed && !in_box(x, lo, hi, dim))
                continue;
            double phi = contact_gap(im, x, nrm);
            if (!(phi < 0.0))
                continue;
            double m = p->mass[i];
            double kc = im->stiffness > 0 ? im->stiffness : im->stiffness_factor * m / (dk * dk);
            double fn = -kc * phi;
            double f[3] = {fn * nrm[0], fn * nrm[1], fn * nrm[2]};
            double fl = 0.0; /* friction loss: adding +0 leaves floss as it is */
            if (im->friction > 0.0) {
                double vr[3] = {0, 0, 0};
                for (int d = 0; d < dim; d++)
                    vr[d] = p->v[d][i] - im->v[d];
                double vn = dot3(vr, nrm);
                double vt[3] = {vr[0] - vn * nrm[0], vr[1] - vn * nrm[1], vr[2] - vn * nrm[2]};
                double vts = sqrt(dot3(vt, vt));
                if (vts > 0.0) {
                    /* Coulomb, capped so it never reverses the slip in one step */
                    double ft = im->friction * fn;
                    double stick = m * vts / dt;
                    if (stick < ft)
                        ft = stick;
                    for (int d = 0; d < 3; d++)
                        f[d] -= ft * vt[d] / vts;
                    fl = ft * vts * dt;
                    floss += fl;
                }
            }
            for (int d = 0; d < dim; d++) {
                p->f[d][i] += f[d];
                im->f_pen[d] -= f[d];
            }
            im->pen_energy += 0.5 * kc * phi * phi;
            if (s->par && nc < rs->par_cap) {
                double *row = rs->par_row + nc * RIGID_PAR_COLS;
                memcpy(row, f, sizeof f);
                row[3] = 0.5 * kc * phi * phi;
                row[4] = fl;
                rs->par_key[nc] = p->gid[i];
            }
            nc++;
        }
        if (s->par) { /* every rank: the contacts of all ranks, in gid order */
            double out[6];
            size_t nr = nc < rs->par_cap ? nc : rs->par_cap; /* < nc only without memory */
            par_ordered_reduce(rs->par_key, rs->par_row, nr, RIGID_PAR_COLS, reduce_penalty, &dim,
                               out, 6);
            for (int d = 0; d < 3; d++)
                im->f_pen[d] = out[d];
            im->pen_energy = out[3];
            floss = out[4];
            nc = (size_t)out[5];
        }
        /* axisymmetric run: the rings' radial forces cancel around the
         * circumference; an impactor on the axis feels only the axial one */
        if (s->axisymmetric)
            im->f_pen[0] = 0.0;
        im->friction_loss += floss;
        im->n_contact = nc;
        if (im->stiffness_frozen && nc > 0 && !(im->k_dt > 0.0))
            im->k_dt = dt;
    }
}

bool rigid_sets_velocities(const struct sim *s)
{
    for (size_t k = 0; s->rigid && k < s->rigid->n; k++)
        if (s->rigid->im[k].contact == RIGID_NO_SLIP)
            return true;
    return false;
}

void rigid_no_slip(struct sim *s, double dt)
{
    if (!s->rigid)
        return;
    par_rows_fit(s);
    struct particles *p = s->p;
    const int dim = s->dim;
    size_t moved = 0; /* contacts put back on a surface, over all ranks */
    for (size_t k = 0; k < s->rigid->n; k++) {
        struct impactor *im = &s->rigid->im[k];
        if (im->contact != RIGID_NO_SLIP)
            continue;
        memset(im->f_noslip, 0, sizeof im->f_noslip);
        double lo[3], hi[3];
        int boxed = bounding_box(im, lo, hi);
        double J[3] = {0, 0, 0}, ke_p = 0.0, push = 0.0;
        size_t nc = 0;
        struct rigid_set *rs = s->rigid;
        for (size_t i = 0; i < p->n_owned; i++) {
            double x[3], nrm[3];
            particle_pos(p, dim, i, x);
            if (boxed && !in_box(x, lo, hi, dim))
                continue;
            double phi = contact_gap(im, x, nrm);
            if (!(phi < 0.0))
                continue;
            double m = p->mass[i];
            double *row = s->par && nc < rs->par_cap ? rs->par_row + nc * RIGID_PAR_COLS : NULL;
            if (row)
                memset(row, 0, RIGID_PAR_COLS * sizeof *row);
            for (int d = 0; d < dim; d++) {
                /* back onto the surface along the normal ([Wang2010] Fig. 9);
                 * the work against the particle's current force is the
                 * energy the correction puts in */
                double dx = -phi * nrm[d];
                p->x[d][i] += dx;
                double pw = p->f[d][i] * dx;
                push -= pw;
                double dv = im->v[d] - p->v[d][i];
                J[d] += m * dv;
                double dke = 0.5 * m * (im->v[d] * im->v[d] - p->v[d][i] * p->v[d][i]);
                ke_p += dke;
                p->v[d][i] = im->v[d];
                if (row) {
                    row[d] = m * dv;
                    row[3 + d] = pw;
                    row[6 + d] = dke;
                }
            }
            if (row)
                rs->par_key[nc] = p->gid[i];
            nc++;
        }
        if (s->par) { /* every rank: the contacts of all ranks, in gid order */
            double out[6];
            size_t nr = nc < rs->par_cap ? nc : rs->par_cap; /* < nc only without memory */
            par_ordered_reduce(rs->par_key, rs->par_row, nr, RIGID_PAR_COLS, reduce_no_slip, &dim,
                               out, 6);
            memcpy(J, out, sizeof J);
            push = out[3];
            ke_p = out[4];
            nc = (size_t)out[5];
        }
        im->n_contact = nc;
        im->push_work += push;
        moved += nc;
        if (nc == 0)
            continue;
        if (s->axisymmetric)
            J[0] = 0.0; /* radial ring momenta cancel (see rigid_contact_forces) */
        if (im->motion == RIGID_FREE) {
            double ke0 = 0.0, ke1 = 0.0;
            for (int d = 0; d < dim; d++) {
                ke0 += 0.5 * im->mass * im->v[d] * im->v[d];
                im->v[d] -= J[d] / im->mass;
                ke1 += 0.5 * im->mass * im->v[d] * im->v[d];
            }
            im->noslip_loss -= ke_p + ke1 - ke0;
        } else {
            double w = 0.0;
            for (int d = 0; d < dim; d++)
                w += J[d] * im->v[d];
            im->drive_work += w;
            im->noslip_loss += w - ke_p;
        }
        for (int d = 0; d < dim; d++)
            im->f_noslip[d] = -J[d] / dt;
    }
    /* the ghosts of moved particles take their new positions now: the
     * energy account and fragments of this step read bonds to ghosts */
    if (s->par && moved)
        par_halo_x(s);
}

static double impactor_ke(const struct impactor *im, const double *v)
{
    if (im->motion != RIGID_FREE)
        return 0.0;
    return 0.5 * im->mass * dot3(v, v);
}

void rigid_energy(const struct sim *s, double *kinetic, double *strain, double *dissipated,
                  double *external)
{
    *kinetic = *strain = *dissipated = *external = 0.0;
    if (!s->rigid)
        return;
    for (size_t k = 0; k < s->rigid->n; k++) {
        const struct impactor *im = &s->rigid->im[k];
        *kinetic += impactor_ke(im, im->v);
        *strain += im->pen_energy;
        *dissipated += im->friction_loss + im->noslip_loss;
        *external += im->gravity_work + im->drive_work + im->push_work;
    }
}

double rigid_absorbed(const struct impactor *im)
{
    return impactor_ke(im, im->v0) - impactor_ke(im, im->v) + im->gravity_work + im->drive_work;
}

static const char *axis_name(int d)
{
    return d == 0 ? "x" : d == 1 ? "y" : "z";
}

size_t rigid_history_names(const struct sim *s, size_t k, char store[][96])
{
    const char *nm = s->rigid->im[k].name;
    size_t c = 0;
    for (int d = 0; d < s->dim; d++)
        snprintf(store[c++], 96, "%s_force_%s [N]", nm, axis_name(d));
    for (int d = 0; d < s->dim; d++)
        snprintf(store[c++], 96, "%s_%s [m]", nm, axis_name(d));
    for (int d = 0; d < s->dim; d++)
        snprintf(store[c++], 96, "%s_u%s [m]", nm, axis_name(d));
    for (int d = 0; d < s->dim; d++)
        snprintf(store[c++], 96, "%s_v%s [m/s]", nm, axis_name(d));
    snprintf(store[c++], 96, "%s_absorbed [J]", nm);
    snprintf(store[c++], 96, "%s_contacts", nm);
    return c;
}

size_t rigid_history_values(const struct sim *s, size_t k, double *v)
{
    const struct impactor *im = &s->rigid->im[k];
    size_t c = 0;
    for (int d = 0; d < s->dim; d++)
        v[c++] = im->f_pen[d] + im->f_noslip[d];
    for (int d = 0; d < s->dim; d++)
        v[c++] = im->x[d];
    for (int d = 0; d < s->dim; d++)
        v[c++] = im->x[d] - im->x0[d];
    for (int d = 0; d < s->dim; d++)
        v[c++] = im->v[d];
    v[c++] = rigid_absorbed(im);
    v[c++] = (double)im->n_contact;
    return c;
}
