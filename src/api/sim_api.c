/**
 * @file sim_api.c
 * @brief The public C API of include/spall/sim.h (and spall_sim_create_setup
 *        of include/spall/setup.h): a thin layer over the deck
 *        reader (io/deck.c, io/deck_build.c), the engine (core/sim.h), the
 *        field registry (core/fields.h) and the frame writer (io/output.h).
 *
 * The handle keeps the parsed deck alive: the output settings (field names)
 * point into it.  Frames follow the schedule of `spall run` (io/run.c):
 * output.field_interval, else output.field_every, else 20 frames over the run.
 */
#include "spall/sim.h"
#include "spall/setup.h"

#include "api/setup_internal.h"

#include "core/fields.h"
#include "core/model.h"
#include "core/particles.h"
#include "core/sim.h"
#include "io/deck.h"
#include "io/deck_build.h"
#include "io/output.h"
#include "io/run_util.h"
#include "io/setup_check.h"
#include "io/setup_check_sim.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

struct spall_sim {
    struct deck *deck;
    struct sim *sim;
    struct run_output ro;
    struct field_writer *fw; /**< NULL until spall_sim_output_open */
    double next_frame_t;     /**< field_interval schedule */
    struct setup_report setup; /**< the set-up checks' warnings and estimate */
};

static int create_from_deck(struct spall_sim **out, struct deck *d, struct spall_error *err)
{
    struct spall_sim *h = calloc(1, sizeof *h);
    if (!h) {
        deck_destroy(&d);
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory creating a simulation");
    }
    h->deck = d;
    /* the set-up checks of spall run (unit slips, set-ups that cannot be
     * right, the cost); refusals are errors, warnings are kept for
     * spall_sim_warning.  No output directory yet: the disk is checked by
     * spall_sim_output_open's writes, not here. */
    int rc = setup_check_units(d, err);
    if (!rc)
        rc = deck_build_sim(d, &h->sim, &h->ro, err);
    if (!rc)
        rc = setup_check_sim(d, h->sim, &h->setup, err);
    if (!rc)
        rc = setup_check_cost(d, h->sim, &h->ro, NULL, false, &h->setup, err);
    if (rc) {
        spall_sim_destroy(&h);
        return rc;
    }
    struct sim *s = h->sim;
    /* the full energy blow-up check at the history interval of `spall run` */
    long every = h->ro.history_every > 0 ? h->ro.history_every : s->n_steps / 2000;
    s->energy_check_every = every > 0 ? every : 1;
    if (h->ro.field_interval <= 0.0 && h->ro.field_every <= 0)
        h->ro.field_every = s->n_steps / 20 > 0 ? s->n_steps / 20 : 1;
    *out = h;
    return SPALL_OK;
}

int spall_sim_create_file(struct spall_sim **out, const char *path, struct spall_error *err)
{
    if (!out)
        return spall_error_set(err, SPALL_ERR_INPUT, "spall_sim_create_file: out is NULL");
    *out = NULL;
    if (!path)
        return spall_error_set(err, SPALL_ERR_INPUT, "spall_sim_create_file: path is NULL");
    struct deck *d = NULL;
    int rc = deck_load_file(&d, path, err);
    return rc ? rc : create_from_deck(out, d, err);
}

int spall_sim_create_string(struct spall_sim **out, const char *yaml, const char *name,
                            struct spall_error *err)
{
    if (!out)
        return spall_error_set(err, SPALL_ERR_INPUT, "spall_sim_create_string: out is NULL");
    *out = NULL;
    if (!yaml)
        return spall_error_set(err, SPALL_ERR_INPUT, "spall_sim_create_string: yaml is NULL");
    struct deck *d = NULL;
    int rc = deck_load_string(&d, name ? name : "<string>", yaml, err);
    return rc ? rc : create_from_deck(out, d, err);
}

size_t spall_sim_warning_count(const struct spall_sim *s)
{
    return s ? s->setup.n_warn : 0;
}

const char *spall_sim_warning(const struct spall_sim *s, size_t k)
{
    return s && k < s->setup.n_warn ? s->setup.warn[k] : NULL;
}

const char *spall_sim_estimate(const struct spall_sim *s)
{
    return s ? s->setup.estimate : "";
}

void spall_sim_destroy(struct spall_sim **s)
{
    if (!s || !*s)
        return;
    field_writer_destroy(&(*s)->fw);
    sim_destroy(&(*s)->sim);
    deck_destroy(&(*s)->deck);
    free(*s);
    *s = NULL;
}

/* ---------------------------------------------------------------- stepping */

/** After a step: a frame if one is due by the deck's schedule, or @p last. */
static int frame_if_due(struct spall_sim *h, bool last, struct spall_error *err)
{
    if (!h->fw)
        return SPALL_OK;
    const struct sim *s = h->sim;
    const double iv = h->ro.field_interval;
    bool frame = last;
    if (iv > 0.0) {
        if (s->t >= h->next_frame_t - 1e-12 * iv) {
            frame = true;
            while (h->next_frame_t <= s->t + 1e-12 * iv)
                h->next_frame_t += iv;
        }
    } else if (h->ro.field_every > 0 && s->step % h->ro.field_every == 0) {
        frame = true;
    }
    return frame ? field_writer_write(h->fw, s, err) : SPALL_OK;
}

/* The next frame time of the deck's schedule (0: none), where the engine
 * lands a step (sim_step_length). */
static double next_stop(const struct spall_sim *h)
{
    return h->fw && h->ro.field_interval > 0.0 ? h->next_frame_t : 0.0;
}

static int one_step(struct spall_sim *h, struct spall_error *err)
{
    h->sim->stop_time = next_stop(h);
    int rc = sim_step(h->sim, err);
    return rc ? rc : frame_if_due(h, false, err);
}

int spall_sim_step(struct spall_sim *s, long n, struct spall_error *err)
{
    if (!s)
        return spall_error_set(err, SPALL_ERR_INPUT, "spall_sim_step: simulation is NULL");
    if (n < 0)
        return spall_error_set(err, SPALL_ERR_INPUT, "spall_sim_step: negative step count %ld", n);
    for (long k = 0; k < n; k++) {
        int rc = one_step(s, err);
        if (rc)
            return rc;
    }
    return SPALL_OK;
}

int spall_sim_run_to(struct spall_sim *s, double t, struct spall_error *err)
{
    if (!s)
        return spall_error_set(err, SPALL_ERR_INPUT, "spall_sim_run_to: simulation is NULL");
    if (!isfinite(t))
        return spall_error_set(err, SPALL_ERR_INPUT, "spall_sim_run_to: time %g is not finite", t);
    /* the same relative tolerance as the frame schedule: a target that is a
     * sum of steps in decimal is not re-crossed for a rounding difference */
    const double tol = 1e-12 * fabs(t);
    while (s->sim->t < t - tol) {
        int rc = one_step(s, err);
        if (rc)
            return rc;
    }
    return SPALL_OK;
}

int spall_sim_run(struct spall_sim *s, struct spall_error *err)
{
    if (!s)
        return spall_error_set(err, SPALL_ERR_INPUT, "spall_sim_run: simulation is NULL");
    while (!sim_done(s->sim)) {
        s->sim->stop_time = next_stop(s);
        int rc = sim_step(s->sim, err);
        if (rc)
            return rc;
        if ((rc = frame_if_due(s, sim_done(s->sim), err)))
            return rc;
    }
    return SPALL_OK;
}

/* ---------------------------------------------------------------- state */

void spall_sim_get_info(const struct spall_sim *h, struct spall_sim_info *info)
{
    memset(info, 0, sizeof *info);
    if (!h)
        return;
    const struct sim *s = h->sim;
    info->dim = s->dim;
    info->axisymmetric = s->axisymmetric;
    info->model = s->ops->name;
    info->particles = s->p->n_owned;
    info->interactions = s->ops->interactions ? s->ops->interactions(s->model, s) : 0;
    info->time = s->t;
    info->step = s->step;
    info->dt = s->dt;
    info->dt_limit = s->dt_limit;
    info->end_time = s->end_time;
    info->done = sim_done(s);
}

void spall_sim_energy(struct spall_sim *h, struct spall_energy *e)
{
    memset(e, 0, sizeof *e);
    if (!h)
        return;
    struct sim *s = h->sim;
    sim_update_energy(s);
    e->kinetic = s->energy.kinetic;
    e->strain = s->energy.strain;
    e->dissipated = s->energy.model_dissipated;
    e->damping = s->energy.damping;
    e->external = s->energy.external;
    e->balance = s->energy.balance;
}

static void fill_info(const struct field_desc *f, struct spall_field_info *info)
{
    memset(info, 0, sizeof *info);
    snprintf(info->name, sizeof info->name, "%s", f->name);
    snprintf(info->unit, sizeof info->unit, "%s", f->unit[0] ? f->unit : "1");
    info->ncomp = f->ncomp;
    info->output = (f->flags & FIELD_OUTPUT) != 0;
}

size_t spall_sim_field_count(const struct spall_sim *s)
{
    return s ? s->sim->fields->n : 0;
}

int spall_sim_field_at(const struct spall_sim *s, size_t k, struct spall_field_info *info,
                       struct spall_error *err)
{
    if (!s || k >= s->sim->fields->n)
        return spall_error_set(err, SPALL_ERR_INPUT, "field index %zu out of range (%zu fields)",
                               k, s ? s->sim->fields->n : (size_t)0);
    fill_info(&s->sim->fields->fields[k], info);
    return SPALL_OK;
}

/** The field @p name, or an SPALL_ERR_INPUT listing the registered names. */
static const struct field_desc *find_field(const struct spall_sim *s, const char *name,
                                           struct spall_error *err)
{
    const struct field_registry *reg = s->sim->fields;
    const struct field_desc *f = name ? field_registry_find(reg, name) : NULL;
    if (f)
        return f;
    char list[SPALL_ERROR_MSG_LEN / 2] = "";
    size_t len = 0;
    for (size_t k = 0; k < reg->n; k++) {
        int m = snprintf(list + len, sizeof list - len, "%s%s", k ? ", " : "", reg->fields[k].name);
        if (m < 0 || (size_t)m >= sizeof list - len)
            break;
        len += (size_t)m;
    }
    spall_error_set(err, SPALL_ERR_INPUT, "unknown field '%.64s'; the %s model registers: %s",
                    name ? name : "(null)", s->sim->ops->name, list);
    return NULL;
}

int spall_sim_field_info(const struct spall_sim *s, const char *name,
                         struct spall_field_info *info, struct spall_error *err)
{
    if (!s)
        return spall_error_set(err, SPALL_ERR_INPUT, "spall_sim_field_info: simulation is NULL");
    const struct field_desc *f = find_field(s, name, err);
    if (!f)
        return SPALL_ERR_INPUT;
    fill_info(f, info);
    return SPALL_OK;
}

int spall_sim_field_read(const struct spall_sim *s, const char *name, double *out,
                         size_t capacity, struct spall_error *err)
{
    if (!s || !out)
        return spall_error_set(err, SPALL_ERR_INPUT, "spall_sim_field_read: %s is NULL",
                               s ? "out" : "simulation");
    const struct field_desc *f = find_field(s, name, err);
    if (!f)
        return SPALL_ERR_INPUT;
    size_t n = s->sim->p->n_owned;
    size_t need = n * (size_t)f->ncomp;
    if (capacity < need)
        return spall_error_set(err, SPALL_ERR_INPUT,
                               "field '%s' needs %zu doubles (%zu particles x %d), buffer holds %zu",
                               f->name, need, n, f->ncomp, capacity);
    field_gather_f64(f, n, out);
    return SPALL_OK;
}

int spall_sim_group_reaction(const struct spall_sim *s, const char *group, double out[3],
                             struct spall_error *err)
{
    if (!s || !group)
        return spall_error_set(err, SPALL_ERR_INPUT, "spall_sim_group_reaction: %s is NULL",
                               s ? "group" : "simulation");
    int g = sim_find_group(s->sim, group);
    if (g < 0)
        return spall_error_set(err, SPALL_ERR_INPUT, "no particle group '%.64s' in the deck",
                               group);
    out[0] = out[1] = out[2] = 0.0;
    sim_group_reaction(s->sim, g, out);
    return SPALL_OK;
}

/* ---------------------------------------------------------------- output */

int spall_sim_output_open(struct spall_sim *s, const char *dir, bool overwrite,
                          struct spall_error *err)
{
    if (!s || !dir || !dir[0])
        return spall_error_set(err, SPALL_ERR_INPUT, "spall_sim_output_open: %s",
                               s ? "no directory given" : "simulation is NULL");
    if (s->fw)
        return spall_error_set(err, SPALL_ERR_INPUT,
                               "spall_sim_output_open: an output directory is already open");
    int rc = run_prepare_out_dir(dir, overwrite, err);
    if (!rc)
        rc = field_writer_create(&s->fw, dir, s->sim, s->ro.n_fields ? s->ro.fields : NULL,
                                 s->ro.n_fields, err);
    if (!rc)
        rc = field_writer_write(s->fw, s->sim, err);
    if (rc) {
        field_writer_destroy(&s->fw);
        return rc;
    }
    /* the next frame on the deck's interval grid after the current time */
    const double iv = s->ro.field_interval;
    s->next_frame_t = iv;
    while (iv > 0.0 && s->next_frame_t <= s->sim->t + 1e-12 * iv)
        s->next_frame_t += iv;
    return SPALL_OK;
}

int spall_sim_write_frame(struct spall_sim *s, struct spall_error *err)
{
    if (!s || !s->fw)
        return spall_error_set(err, SPALL_ERR_INPUT, "spall_sim_write_frame: %s",
                               s ? "no output directory open (spall_sim_output_open)"
                                 : "simulation is NULL");
    return field_writer_write(s->fw, s->sim, err);
}

size_t spall_sim_frames(const struct spall_sim *s)
{
    return s ? field_writer_frames(s->fw) : 0;
}

/* ---------------------------------------------------------------- set-up by calls */

int spall_sim_create_setup(struct spall_sim **out, const struct spall_setup *setup,
                           struct spall_error *err)
{
    if (!out)
        return spall_error_set(err, SPALL_ERR_INPUT, "spall_sim_create_setup: out is NULL");
    *out = NULL;
    if (!setup)
        return spall_error_set(err, SPALL_ERR_INPUT, "spall_sim_create_setup: setup is NULL");
    struct deck *d = NULL;
    int rc = setup_deck_copy(setup, &d, err);
    return rc ? rc : create_from_deck(out, d, err);
}
