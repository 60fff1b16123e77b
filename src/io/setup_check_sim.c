/**
 * @file setup_check_sim.c
 * @brief Set-ups that cannot be right, caught before step 0 (issue 24 item 1),
 *        and the run's cost against the machine.
 *
 * Why each check: a new user's decks that ran without a word and gave
 * nonsense (issue 24): an impactor that starts inside the body blows up a
 * few steps later with a message about energy; an SPH wall on the body's
 * face starts the run with 36 times the impact energy as strain energy; a
 * symmetry plane through the body doubles the particles near it; a probe 1 m
 * outside the body follows the nearest particle; a run of 6 M particles
 * writes hundreds of MB a minute with no estimate.  Each check measures the
 * set-up (a depth, a distance, an energy ratio) against one spacing or a
 * fraction, so legitimate decks (contact at a gap, bodies on the positive
 * side of their mirror planes) pass: no example deck trips one
 * (tests/cli/setup_check_sim.sh).
 */
#include "io/setup_check_sim.h"

#include "core/fields.h"
#include "core/geometry.h"
#include "core/model.h"
#include "core/options.h"
#include "core/parallel/decomp.h"
#include "core/parallel/setup_dist.h"
#include "core/particles.h"
#include "core/rigid.h"
#include "core/sim.h"
#include "io/deck_build.h"
#include "spall/error.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>
#include <sys/statvfs.h>

/* The names run.allow accepts, one per check. */
static const char *const check_names[] = {"overlap", "wall", "symmetry", "probe",
                                          "initial_strain", "cost", NULL};

/* A set-up farther than this many spacings from right is refused:
 * a quarter spacing is well inside a particle's own cell, so round-off in a
 * deck's coordinates never trips it, and the blunders (an impactor or wall
 * half a spacing or more into the body) always do. */
#define SETUP_SPACING_TOL 0.25
/* Initial strain energy above this fraction of the initial kinetic energy
 * (the energy put in by the deck at t = 0) is refused: an impact starts
 * unstrained, so only an overlap or a pre-stressed set-up gives one. */
#define SETUP_STRAIN_FRACTION 0.1
/* Particle-steps far beyond a day of any one machine (1e7 particle-steps/s
 * per thread is the upper end measured for these models, docs/performance.md,
 * so 1e13 is more than a day on 64 threads). */
#define SETUP_MAX_PARTICLE_STEPS 1e13
/* Warn above this output size or particle-steps (minutes to hours). */
#define SETUP_WARN_BYTES 1e10
#define SETUP_WARN_PARTICLE_STEPS 1e11

/* run.allow: which checks the deck turned off.  Unknown names are refused. */
static int read_allow(const struct deck *d, bool allow[], struct spall_error *err)
{
    size_t n_names = sizeof check_names / sizeof check_names[0] - 1;
    for (size_t k = 0; k < n_names; k++)
        allow[k] = false;
    const struct deck_node *run = d && d->root ? deck_peek(d->root, "run") : NULL;
    const struct deck_node *a = deck_peek(run, "allow");
    if (!a)
        return SPALL_OK;
    if (a->kind == DECK_SCALAR && !deck_is_empty_value(a)) {
        /* one name alone, as in allow: cost */
        for (size_t k = 0; k < n_names; k++)
            if (strcmp(a->scalar, check_names[k]) == 0) {
                allow[k] = true;
                return SPALL_OK;
            }
    }
    if (a->kind != DECK_SEQUENCE)
        return deck_error(err, a, "run.allow: expected a list of check names (overlap, wall, "
                                  "symmetry, probe, initial_strain, cost)");
    for (size_t i = 0; i < a->n; i++) {
        const struct deck_node *it = a->items[i];
        size_t k = 0;
        while (k < n_names && !(it->kind == DECK_SCALAR && strcmp(it->scalar, check_names[k]) == 0))
            k++;
        if (k == n_names)
            return deck_error(err, it, "run.allow: unknown check '%.64s'; expected one of: "
                                       "overlap, wall, symmetry, probe, initial_strain, cost",
                              it->kind == DECK_SCALAR ? it->scalar : "(not a name)");
        allow[k] = true;
    }
    return SPALL_OK;
}

static size_t check_index(const char *name)
{
    size_t k = 0;
    while (check_names[k] && strcmp(check_names[k], name) != 0)
        k++;
    return k;
}

/* "FILE:L:C: message" at key path @p key (else at @p fallback, else the
 * file), code SPALL_ERR_INPUT, err->key = key. */
static int positioned(const struct deck *d, struct spall_error *err, const char *key,
                      const char *fallback, const char *msg)
{
    spall_error_set_key(err, SPALL_ERR_INPUT, key, "%s", msg);
    if (deck_locate_error(d->root, err))
        return SPALL_ERR_INPUT;
    spall_error_set_key(err, SPALL_ERR_INPUT, fallback, "%s", msg);
    if (!deck_locate_error(d->root, err))
        spall_error_set(err, SPALL_ERR_INPUT, "%s: %s", d->path, msg);
    if (err)
        snprintf(err->key, sizeof err->key, "%s", key);
    return SPALL_ERR_INPUT;
}

/* A finding of check @p name: a refusal (@p refuse and not allowed) or a
 * warning line in @p rep (not allowed); nothing when the deck allows it. */
static int finding(const struct deck *d, const bool allow[], const char *name, bool refuse,
                   const char *key, const char *fallback, struct setup_report *rep,
                   struct spall_error *err, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 9, 10)))
#endif
    ;

static int finding(const struct deck *d, const bool allow[], const char *name, bool refuse,
                   const char *key, const char *fallback, struct setup_report *rep,
                   struct spall_error *err, const char *fmt, ...)
{
    if (allow[check_index(name)])
        return SPALL_OK;
    char msg[SPALL_ERROR_MSG_LEN - 200];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    char full[SPALL_ERROR_MSG_LEN - 100];
    snprintf(full, sizeof full, "%s (%s: run.allow: [%s])", msg,
             refuse ? "to run it anyway" : "to silence this", name);
    if (refuse)
        return positioned(d, err, key, fallback, full);
    if (rep && rep->n_warn < SETUP_WARN_MAX) {
        struct spall_error w = {0};
        positioned(d, &w, key, fallback, full);
        snprintf(rep->warn[rep->n_warn++], SETUP_LINE_LEN, "%s", w.msg);
    }
    return SPALL_OK;
}

/* Impactors: the deepest particle inside each one's contact surface. */
static int check_impactors(const struct deck *d, const struct sim *s, const bool allow[],
                           struct setup_report *rep, struct spall_error *err)
{
    if (!s->rigid)
        return SPALL_OK;
    const struct particles *p = s->p;
    const double tol = SETUP_SPACING_TOL * s->lattice.spacing;
    for (size_t k = 0; k < s->rigid->n; k++) {
        const struct impactor *im = &s->rigid->im[k];
        double depth = -INFINITY;
        size_t deepest = 0, inside = 0;
        for (size_t i = 0; i < p->n_owned; i++) {
            double x[3] = {0, 0, 0}, nrm[3];
            for (int c = 0; c < s->dim; c++)
                x[c] = p->x[c][i];
            double dd = im->contact_offset - rigid_distance(im, x, nrm);
            if (dd > tol)
                inside++;
            if (dd > depth) {
                depth = dd;
                deepest = i;
            }
        }
        if (!(depth > tol))
            continue;
        char key[64];
        snprintf(key, sizeof key, "impactors[%zu].position", k);
        int rc = finding(d, allow, im->shape == RIGID_WALL ? "wall" : "overlap", true, key,
                         "impactors", rep, err,
                         "impactor '%.60s' starts inside the body: %zu particle(s) within its "
                         "contact surface, the deepest (id %lld) %.3g m in (lattice spacing "
                         "%.3g m); likely cause: its position%s puts it into the body, which "
                         "makes a huge contact force at step 1; move it clear of the body",
                         im->name, inside, (long long)p->gid[deepest], depth, s->lattice.spacing,
                         im->shape == RIGID_WALL ? " or normal" : " or radius");
        if (rc)
            return rc;
    }
    return SPALL_OK;
}

/* SPH model.wall {point, normal} (a penalty closer than dx/2) and
 * model.symmetry planes (the body on the positive side, dx/2 off the
 * plane), read from the deck: io may not look into the model. */
static int check_sph_planes(const struct deck *d, const struct sim *s, const bool allow[],
                            struct setup_report *rep, struct spall_error *err)
{
    const struct deck_node *model = deck_peek(d->root, "model");
    const struct deck_node *type = deck_peek(model, "type");
    if (!type || type->kind != DECK_SCALAR ||
        (strcmp(type->scalar, "sph") != 0 && strcmp(type->scalar, "tlsph") != 0))
        return SPALL_OK;
    const struct particles *p = s->p;
    const double dx = s->lattice.spacing;
    const struct deck_node *w = deck_peek(model, "wall");
    double pt[3] = {0, 0, 0}, nv[3] = {0, 0, 0};
    if (w && deck_vector(w, "point", true, (size_t)s->dim, 3, pt, NULL) == SPALL_OK &&
        deck_vector(w, "normal", true, (size_t)s->dim, 3, nv, NULL) == SPALL_OK) {
        double nn = sqrt(nv[0] * nv[0] + nv[1] * nv[1] + nv[2] * nv[2]);
        double dmin = INFINITY;
        size_t at = 0, close = 0;
        for (size_t i = 0; nn > 0.0 && i < p->n_owned; i++) {
            double g = 0.0;
            for (int c = 0; c < s->dim; c++)
                g += (p->x[c][i] - pt[c]) * nv[c] / nn;
            if (g < 0.5 * dx - SETUP_SPACING_TOL * dx)
                close++;
            if (g < dmin) {
                dmin = g;
                at = i;
            }
        }
        if (close > 0) {
            int rc = finding(d, allow, "wall", true, "model.wall.point", "model.wall", rep, err,
                             "model.wall cuts the body: %zu particle(s) closer than dx/2 = "
                             "%.3g m to the wall (particle id %lld at %.3g m), each starting "
                             "with a penalty force; likely cause: the wall placed on the "
                             "body's face or inside it; put the wall dx/2 outside the body "
                             "(the particles' surfaces then touch it)",
                             close, 0.5 * dx, (long long)p->gid[at], dmin);
            if (rc)
                return rc;
        }
    }
    const struct deck_node *sym = deck_peek(model, "symmetry");
    if (!sym || sym->kind != DECK_SCALAR)
        return SPALL_OK;
    for (int c = 0; c < 2 && c < s->dim; c++) {
        if (!strchr(sym->scalar, "xy"[c]) || strcmp(sym->scalar, "none") == 0)
            continue;
        size_t below = 0, at = 0;
        double xmin = INFINITY;
        for (size_t i = 0; i < p->n_owned; i++) {
            if (p->x[c][i] < SETUP_SPACING_TOL * dx)
                below++;
            if (p->x[c][i] < xmin) {
                xmin = p->x[c][i];
                at = i;
            }
        }
        if (below == 0)
            continue;
        int rc = finding(d, allow, "symmetry", true, "model.symmetry", "model", rep, err,
                         "symmetry plane %c = 0 cuts the body: %zu particle(s) on or behind it "
                         "(particle id %lld at %c = %.3g m), which the mirror ghosts then "
                         "double; likely cause: the body not cut at the plane; intersect it "
                         "with a box from %c = 0 and put the lattice origin dx/2 = %.3g m off "
                         "the plane",
                         "xy"[c], below, (long long)p->gid[at], "xy"[c], xmin, "xy"[c], 0.5 * dx);
        if (rc)
            return rc;
    }
    return SPALL_OK;
}

/* Probes: a probe follows its nearest particle; farther than a spacing from
 * every particle it follows one the user did not mean. */
static int check_probes(const struct deck *d, const struct sim *s, const bool allow[],
                        struct setup_report *rep, struct spall_error *err)
{
    for (size_t k = 0; k < s->n_probes; k++) {
        const struct probe *pr = &s->probes[k];
        double r2 = 0.0;
        if (s->setup) /* each rank built its region: the whole body's nearest */
            r2 = s->setup->probe_d2[k];
        for (int c = 0; c < s->dim && !s->setup; c++) {
            double dd = s->p->x0[c][pr->particle] - pr->pos[c];
            r2 += dd * dd;
        }
        double r = sqrt(r2);
        if (!(r > s->lattice.spacing))
            continue;
        char key[64];
        snprintf(key, sizeof key, "probes[%zu].position", k);
        int rc = finding(d, allow, "probe", true, key, "probes", rep, err,
                         "probe '%.60s' is outside every body: its nearest particle is %.3g m "
                         "away (lattice spacing %.3g m), and that particle is what it would "
                         "record; likely cause: a position in other units or off the body",
                         pr->name, r, s->lattice.spacing);
        if (rc)
            return rc;
    }
    return SPALL_OK;
}

/* The initial strain energy against the energy the deck puts in at t = 0. */
static int check_initial_strain(const struct deck *d, const struct sim *s, const bool allow[],
                                struct setup_report *rep, struct spall_error *err)
{
    /* the macro-particle model's strain energy is its pair potential summed
     * over the lattice, not zero at rest (surface pairs, the cut-off: 764 J
     * for a 4 mm cube of aluminium), so it says nothing about an overlap */
    if (strcmp(s->ops->name, "macroparticle") == 0)
        return SPALL_OK;
    const double ke = s->energy.kinetic, se = s->energy.strain;
    rep->initial_strain_fraction = ke > 0.0 ? se / ke : 0.0;
    if (!(se > 0.0) || !(ke > 0.0) || !(se > SETUP_STRAIN_FRACTION * ke))
        return SPALL_OK;
    return finding(d, allow, "initial_strain", true, "run", "run", rep, err,
                   "the set-up starts with %.3g J of strain energy, %.3g times the %.3g J of "
                   "kinetic energy put in (limit %g); likely cause: bodies, impactors or walls "
                   "that overlap, or particles closer than the lattice spacing",
                   se, se / ke, ke, SETUP_STRAIN_FRACTION);
}

int setup_check_sim(const struct deck *d, const struct sim *s, struct setup_report *rep,
                    struct spall_error *err)
{
    bool allow[8];
    int rc = read_allow(d, allow, err);
    if (!rc)
        rc = check_impactors(d, s, allow, rep, err);
    if (!rc)
        rc = check_sph_planes(d, s, allow, rep, err);
    if (!rc)
        rc = check_probes(d, s, allow, rep, err);
    if (!rc)
        rc = check_initial_strain(d, s, allow, rep, err);
    return rc;
}

/* Bytes of one frame: every output field's components, 8 bytes each (the
 * writer's doubles; integer fields are smaller, so this is an upper bound). */
static double frame_bytes(const struct sim *s, const struct run_output *ro)
{
    double per = 0.0;
    if (ro->n_fields) {
        for (size_t k = 0; k < ro->n_fields; k++) {
            const struct field_desc *f = field_registry_find(s->fields, ro->fields[k]);
            per += f ? 8.0 * f->ncomp : 0.0;
        }
    } else {
        for (size_t k = 0; k < s->fields->n; k++)
            if (s->fields->fields[k].flags & FIELD_DEFAULT)
                per += 8.0 * s->fields->fields[k].ncomp;
    }
    return per * (double)par_n_global(s);
}

static void human_bytes(char *buf, size_t len, double b)
{
    const char *unit[] = {"B", "kB", "MB", "GB", "TB", "PB"};
    int u = 0;
    while (b >= 1000.0 && u < 5) {
        b /= 1000.0;
        u++;
    }
    snprintf(buf, len, "%.3g %s", b, unit[u]);
}

/* Free bytes on the file system that will hold @p dir (its nearest existing
 * ancestor); negative when unknown. */
static double free_bytes(const char *dir)
{
    char path[1024];
    snprintf(path, sizeof path, "%s", dir && dir[0] ? dir : ".");
    for (;;) {
        struct statvfs v;
        if (statvfs(path, &v) == 0)
            return (double)v.f_bavail * (double)v.f_frsize;
        char *slash = strrchr(path, '/');
        if (!slash)
            return statvfs(".", &v) == 0 ? (double)v.f_bavail * (double)v.f_frsize : -1.0;
        if (slash == path) {
            path[1] = '\0';
            return statvfs(path, &v) == 0 ? (double)v.f_bavail * (double)v.f_frsize : -1.0;
        }
        *slash = '\0';
    }
}

int setup_check_cost(const struct deck *d, const struct sim *s, const struct run_output *ro,
                     const char *out_dir, bool yes, struct setup_report *rep,
                     struct spall_error *err)
{
    bool allow[8];
    int rc = read_allow(d, allow, err);
    if (rc)
        return rc;
    if (yes)
        allow[check_index("cost")] = true;
    const double steps = (double)(s->n_steps > s->step ? s->n_steps - s->step : 0);
    const double n = (double)par_n_global(s); /* the whole body's */
    double frames;
    if (ro->field_interval > 0.0)
        frames = floor((s->end_time - s->t) / ro->field_interval) + 2.0;
    else if (ro->field_every > 0)
        frames = floor(steps / (double)ro->field_every) + 2.0;
    else
        frames = 21.0; /* the run driver's default: 20 frames and the first */
    long hist_every = ro->history_every > 0 ? ro->history_every
                                            : (s->n_steps / 2000 > 0 ? s->n_steps / 2000 : 1);
    const double hist = (steps / (double)hist_every + 2.0) * 20.0 * 16.0; /* ~20 columns */
    rep->particle_steps = n * steps;
    rep->output_bytes = frames * frame_bytes(s, ro) + hist;
    char size[32];
    human_bytes(size, sizeof size, rep->output_bytes);
    snprintf(rep->estimate, sizeof rep->estimate,
             "%.0f particles x %.0f steps%s = %.3g particle-steps; output about %s "
             "(%.0f frames)",
             n, steps, s->adaptive_dt ? " (estimate: adaptive dt)" : "", rep->particle_steps,
             size, frames);
    const double avail = free_bytes(out_dir);
    if (out_dir && avail >= 0.0 && rep->output_bytes > avail) {
        char fb[32];
        human_bytes(fb, sizeof fb, avail);
        return finding(d, allow, "cost", true, "output", "run", rep, err,
                       "the run would write about %s, more than the %s free where it writes; "
                       "likely cause: too many frames or fields for %.0f particles (raise "
                       "output.field_interval, list fewer output.fields) or a spacing in "
                       "other units; spall run --yes runs it anyway",
                       size, fb, n);
    }
    if (rep->particle_steps > SETUP_MAX_PARTICLE_STEPS)
        return finding(d, allow, "cost", true, "run", "run", rep, err,
                       "the run needs %.3g particle-steps (%s), far beyond a day of one "
                       "machine (limit %.0e); likely cause: a spacing or end_time in other "
                       "units; spall run --yes runs it anyway",
                       rep->particle_steps, rep->estimate, SETUP_MAX_PARTICLE_STEPS);
    if (rep->particle_steps > SETUP_WARN_PARTICLE_STEPS || rep->output_bytes > SETUP_WARN_BYTES)
        return finding(d, allow, "cost", false, "run", "run", rep, err,
                       "a large run: %s", rep->estimate);
    return SPALL_OK;
}

void setup_report_print(const struct setup_report *rep, FILE *log, FILE *warn_out)
{
    for (size_t k = 0; k < rep->n_warn; k++) {
        if (warn_out)
            fprintf(warn_out, "spall: warning: %s\n", rep->warn[k]);
        if (log)
            fprintf(log, "setup_warning: %s\n", rep->warn[k]);
    }
    if (log && rep->estimate[0])
        fprintf(log, "setup_estimate: %s\n", rep->estimate);
    if (warn_out && rep->estimate[0] && rep->n_warn == 0 && rep->particle_steps > 1e9)
        fprintf(warn_out, "spall: %s\n", rep->estimate);
}

void setup_empty_group_hint(const struct sim *s, const struct geom *g, char *buf, size_t len)
{
    buf[0] = '\0';
    double lo[3], hi[3];
    const double dx = s->lattice.spacing;
    if (!g || !(dx > 0.0) || !geom_bounds(g, s->dim, lo, hi))
        return;
    /* the body's extent, from its particles */
    double blo[3] = {INFINITY, INFINITY, INFINITY}, bhi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (size_t i = 0; i < s->p->n_owned; i++)
        for (int c = 0; c < s->dim; c++) {
            blo[c] = fmin(blo[c], s->p->x[c][i]);
            bhi[c] = fmax(bhi[c], s->p->x[c][i]);
        }
    int thin = -1;
    double w = INFINITY;
    for (int c = 0; c < s->dim; c++)
        if (hi[c] - lo[c] < dx && hi[c] - lo[c] < w) {
            w = hi[c] - lo[c];
            thin = c;
        }
    if (s->p->n_owned < 100 && dx > 0.0)
        snprintf(buf, len,
                 "likely cause: the lattice spacing %.3g m leaves the body only %zu "
                 "particle(s) (a spacing in mm or cm?); with a finer spacing the group "
                 "finds its particles",
                 dx, s->p->n_owned);
    else if (thin >= 0)
        snprintf(buf, len,
                 "likely cause: its region is %.3g m wide along %c, less than the lattice "
                 "spacing %.3g m, and falls between two rows of particles; make it at least "
                 "one spacing wide",
                 w, "xyz"[thin], dx);
    else
        for (int c = 0; c < s->dim; c++)
            if (hi[c] < blo[c] - dx || lo[c] > bhi[c] + dx) {
                snprintf(buf, len,
                         "likely cause: its region (%c from %.3g to %.3g m) lies outside the "
                         "body (%c from %.3g to %.3g m)",
                         "xyz"[c], lo[c], hi[c], "xyz"[c], blo[c], bhi[c]);
                break;
            }
}
