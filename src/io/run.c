/**
 * @file run.c
 * @brief `spall run`: deck -> checked simulation -> output directory with
 *        run.log, history.csv and HDF5/XDMF frames, with a progress bar.
 *
 * Order matters for the "no half-written output" promise: the deck is parsed
 * and the simulation fully prepared (all input and physics checks) before the
 * output directory is touched.  An existing non-empty directory is refused
 * unless `overwrite` is set.  If the run goes unstable, the frames written so
 * far stay valid (each frame is written to a temporary name and renamed) and
 * the log says where and why it stopped.
 */
#include "spall/spall.h"

#include "core/bond_list.h"
#include "core/fragments.h"
#include "core/parallel/comm.h"
#include "core/parallel/decomp.h"
#include "core/particles.h"
#include "core/rigid.h"
#include "core/sim.h"
#include "io/deck.h"
#include "io/deck_build.h"
#include "io/output.h"
#include "io/run_balance.h"
#include "io/run_par.h"
#include "io/run_restart.h"
#include "io/run_summary.h"
#include "io/run_util.h"
#include "io/setup_check.h"
#include "io/setup_check_sim.h"
#include "core/model.h"

#include <errno.h>
#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

const char *spall_version(void)
{
    return SPALL_VERSION;
}

const char *spall_git_revision(void)
{
    return SPALL_GIT_REV;
}

#define HIST_MAX 128

struct history_layout {
    const char *names[HIST_MAX];
    char storage[HIST_MAX][192];
    size_t n;
    size_t n_model; /* model columns start at n - n_model */
    struct fragments *frag; /* bonded models: fragment columns at the end */
};

static void hist_add(struct history_layout *h, const char *fmt, const char *a, const char *b)
{
    if (h->n >= HIST_MAX)
        return;
    snprintf(h->storage[h->n], sizeof h->storage[h->n], fmt, a, b);
    h->names[h->n] = h->storage[h->n];
    h->n++;
}

static const char *axis_name(int d)
{
    return d == 0 ? "x" : d == 1 ? "y" : "z";
}

static void history_columns(const struct sim *s, struct history_layout *h)
{
    h->n = 0;
    hist_add(h, "step%s%s", "", "");
    hist_add(h, "time [s]%s%s", "", "");
    hist_add(h, "kinetic [J]%s%s", "", "");
    hist_add(h, "strain [J]%s%s", "", "");
    hist_add(h, "dissipated [J]%s%s", "", "");
    hist_add(h, "damping [J]%s%s", "", "");
    hist_add(h, "external_work [J]%s%s", "", "");
    hist_add(h, "energy_balance [J]%s%s", "", "");
    for (size_t k = 0; k < s->n_probes; k++)
        for (int d = 0; d < s->dim; d++)
            hist_add(h, "%s_u%s [m]", s->probes[k].name, axis_name(d));
    for (size_t k = 0; k < s->n_probes; k++)
        for (int d = 0; d < s->dim; d++)
            hist_add(h, "%s_v%s [m/s]", s->probes[k].name, axis_name(d));
    for (size_t k = 0; k < s->n_bcs; k++)
        for (int d = 0; d < s->dim; d++) {
            char nm[128];
            snprintf(nm, sizeof nm, "bc%zu_%s", k, s->groups[s->bcs[k].group].name);
            hist_add(h, "%s_force_%s [N]", nm, axis_name(d));
        }
    if (s->rigid) /* impactors (issue 3) */
        for (size_t k = 0; k < s->rigid->n; k++) {
            char nm[RIGID_HISTORY_COLS][96];
            size_t m = rigid_history_names(s, k, nm);
            for (size_t q = 0; q < m; q++)
                hist_add(h, "%.95s%s", nm[q], "");
        }
    h->n_model = 0;
    if (s->ops->history) {
        const char *names[MODEL_HISTORY_MAX];
        double vals[MODEL_HISTORY_MAX];
        size_t m = s->ops->history(s->model, s, names, vals);
        for (size_t k = 0; k < m; k++)
            hist_add(h, "%s%s", names[k], "");
        h->n_model = m;
    }
    if (h->frag) { /* core/fragments.h: computed at history times only */
        hist_add(h, "fragments [1]%s%s", "", "");
        hist_add(h, "fragments_10plus [1]%s%s", "", "");
        hist_add(h, "fragment_singles [1]%s%s", "", "");
        hist_add(h, "largest_fragment_mass [kg]%s%s", "", "");
        hist_add(h, "second_fragment_mass [kg]%s%s", "", "");
        hist_add(h, "fragment_cm_kinetic [J]%s%s", "", "");
    }
}

static void history_values(const struct sim *s, const struct history_layout *h, double *v)
{
    size_t c = 0;
    v[c++] = (double)s->step;
    v[c++] = s->t;
    v[c++] = s->energy.kinetic;
    v[c++] = s->energy.strain;
    v[c++] = s->energy.model_dissipated;
    v[c++] = s->energy.damping;
    v[c++] = s->energy.external;
    v[c++] = s->energy.balance;
    double pu[3], pv[3]; /* distributed: from the probe's owner (run_par.c) */
    for (size_t k = 0; k < s->n_probes; k++) {
        run_probe(s, k, pu, pv);
        for (int d = 0; d < s->dim; d++)
            v[c++] = pu[d];
    }
    for (size_t k = 0; k < s->n_probes; k++) {
        run_probe(s, k, pu, pv);
        for (int d = 0; d < s->dim; d++)
            v[c++] = pv[d];
    }
    for (size_t k = 0; k < s->n_bcs; k++)
        for (int d = 0; d < s->dim; d++)
            v[c++] = s->bcs[k].reaction[d];
    if (s->rigid) /* impactors (issue 3) */
        for (size_t k = 0; k < s->rigid->n && c < h->n; k++)
            c += rigid_history_values(s, k, v + c);
    if (h->n_model) {
        const char *names[MODEL_HISTORY_MAX];
        double vals[MODEL_HISTORY_MAX];
        size_t m = s->ops->history(s->model, s, names, vals);
        for (size_t k = 0; k < m && c < h->n; k++)
            v[c++] = vals[k];
    }
    struct fragment_summary fs;
    if (h->frag && c + 6 <= h->n && run_fragments(h->frag, s, NULL) == SPALL_OK) {
        fragments_summarise(h->frag, &fs);
        v[c++] = (double)fs.count;
        v[c++] = (double)fs.ge10;
        v[c++] = (double)fs.singles;
        v[c++] = fs.largest_mass;
        v[c++] = fs.second_mass;
        v[c++] = fs.kinetic_cm;
    }
    while (c < h->n)
        v[c++] = 0.0;
}

/* Whether an output of this loop may read the model's stress after the
 * coming step (sim.stress_skip is its negation): a history row, a frame, the
 * last step, or any step of a run that writes checkpoints (their times are
 * not all known in advance).  Predicted with the step's own length and
 * landing (sim_step_length: the step takes the same), so a step that is
 * read is never skipped; the last step is counted before a split can move
 * it.  A checkpoint on a signal between outputs may save an older stress:
 * nothing reads it before the next force call forms it again. */
static bool stress_read_after_step(const struct sim *s, const struct run_output *ro,
                                   long hist_every, double next_frame_t, bool ckpt)
{
    const long k = s->step + 1;
    if (ckpt || s->adaptive_dt || k % hist_every == 0 || k >= s->n_steps + s->n_split)
        return true;
    if (ro->field_interval > 0.0) {
        double landing;
        const double h = sim_step_length(s, &landing);
        const double t = isnan(landing) ? s->t + h : landing;
        return t >= next_frame_t - 1e-12 * ro->field_interval;
    }
    return ro->field_every > 0 && k % ro->field_every == 0;
}

static void write_log_header(FILE *log, const struct spall_run_options *opt, const struct deck *d,
                             const struct sim *s, const struct run_output *ro)
{
    time_t now = time(NULL);
    char when[64];
    strftime(when, sizeof when, "%Y-%m-%dT%H:%M:%SZ", gmtime(&now));
    fprintf(log, "# spall run log\n");
    fprintf(log, "version: %s\ngit_revision: %s\nbuild_type: %s\nstarted: %s\n", spall_version(),
            spall_git_revision(), SPALL_BUILD_TYPE, when);
    fprintf(log, "deck: %s\ntitle: %s\nthreads: %d\n", opt->deck_path, ro->title,
            omp_get_max_threads());
    run_summary_write(log, s);
    fprintf(log, "deck_echo: |\n");
    const char *t = d->text ? d->text : "";
    while (*t) {
        const char *e = strchr(t, '\n');
        size_t len = e ? (size_t)(e - t) : strlen(t);
        fprintf(log, "  %.*s\n", (int)len, t);
        t += len + (e ? 1 : 0);
    }
    fflush(log);
}

int spall_run(const struct spall_run_options *opt, struct spall_run_result *res,
              struct spall_error *err)
{
    memset(res, 0, sizeof *res);
    struct deck *d = NULL;
    struct sim *s = NULL;
    struct run_output ro;
    struct field_writer *fw = NULL;
    struct history_writer *hw = NULL;
    struct fragments *frag = NULL;
    FILE *log = NULL;
    struct run_ckpt ck;
    memset(&ck, 0, sizeof ck);
    struct run_balance rb;
    memset(&rb, 0, sizeof rb);
    int rc = deck_load_file(&d, opt->deck_path, err);
    if (!rc)
        rc = par_fault("deck", err);
    if (!rc)
        rc = setup_check_units(d, err); /* unit slips, before anything is built */
    /* mpirun: a deck one rank cannot read stops all before the set-up's
     * collectives (docs/parallel.md, "Error agreement") */
    if ((rc = run_par_agree(rc, err)))
        goto done;
    if (opt->threads > 0)
        omp_set_num_threads(opt->threads);
    struct setup_report setup = {0};
    char setup_note[256] = ""; /* distributed or replicated set-up, for run.log */
    rc = deck_build_sim_setup(d, &s, &ro, !opt->restart, setup_note, sizeof setup_note, err);
    rc = run_par_setup_window(s, rc, err); /* mpirun: each rank built its region */
    if (!rc)
        rc = setup_check_sim(d, s, &setup, err); /* set-ups that cannot be right */
    if ((rc = run_par_setup(s, &ro, rc, err))) { /* mpirun: refusals, agreed */
        if (s && err->key[0]) /* a refusal naming a deck key: at its position */
            deck_locate_error(d->root, err);
        goto done;
    }
    if (opt->threads <= 0 && ro.threads > 0)
        omp_set_num_threads(ro.threads);

    /* a restart reads its checkpoint here, before any output is touched */
    char dir[1024];
    if ((rc = run_par_agree(run_ckpt_begin(&ck, opt, d, &ro.checkpoint, s, dir, sizeof dir, err),
                            err)))
        goto done;
    bool resume = ck.restarted && run_ckpt_same_dir(&ck);
    /* the free disk space is each rank's own view: agreed */
    if ((rc = run_par_agree(setup_check_cost(d, s, &ro, dir, opt->yes, &setup, err), err)))
        goto done;

    /* all checks passed: now, and only now, touch the file system */
    snprintf(res->out_dir, sizeof res->out_dir, "%s", dir);
    if (ck.restarted && !resume && run_par_root())
        rc = run_ckpt_copy_outputs(&ck, opt->overwrite, err);
    else if (!ck.restarted && run_par_root())
        rc = run_prepare_out_dir(dir, opt->overwrite, err);
    char path[1200];
    snprintf(path, sizeof path, "%s/run.log", dir);
    if (!rc && run_par_root() && !(log = fopen(path, resume ? "a" : "w")))
        rc = spall_error_set(err, SPALL_ERR_IO, "cannot write '%s': %s", path, strerror(errno));
    if ((rc = run_par_agree(rc, err))) /* only rank 0 writes files */
        goto done;
    if (!resume && log)
        write_log_header(log, opt, d, s, &ro);
    if (log && setup_note[0])
        fprintf(log, "%s\n", setup_note);
    if (run_par_root()) /* the warnings once, not per rank */
        setup_report_print(&setup, log, stderr);
    if (ck.restarted)
        run_ckpt_log_restart(&ck, s, log);
    if ((rc = run_par_distribute(s, log, err))) /* mpirun: owned + ghosts */
        goto done;
    if ((rc = run_balance_begin(&rb, s, &ro.parallel, dir, err))) /* mpirun: balance.csv */
        goto done;

    struct history_layout hl;
    if (s->ops->bonds && s->ops->bonds(s->model))
        rc = fragments_create(&frag, par_n_global(s), err);
    if ((rc = run_par_agree(rc, err)))
        goto done;
    hl.frag = frag;
    history_columns(s, &hl);
    snprintf(path, sizeof path, "%s/history.csv", dir);
    if (run_par_root())
        rc = ck.restarted ? history_writer_resume(&hw, path, (long)ck.meta.history_bytes, hl.n, err)
                          : history_writer_create(&hw, path, hl.names, hl.n, err);
    if ((rc = run_par_agree(rc, err)))
        goto done;
    int frames_on = ro.field_interval > 0.0 || ro.field_every > 0;
    if (!frames_on) {
        /* default: 20 frames over the run */
        ro.field_every = s->n_steps / 20 > 0 ? s->n_steps / 20 : 1;
        frames_on = 1;
    }
    rc = field_writer_create(&fw, dir, s, ro.n_fields ? ro.fields : NULL, ro.n_fields, err);
    if (!rc)
        rc = par_fault("output_open", err);
    if ((rc = run_par_agree(rc, err)))
        goto done;
    long hist_every = ro.history_every > 0 ? ro.history_every
                                            : (s->n_steps / 2000 > 0 ? s->n_steps / 2000 : 1);
    s->energy_check_every = hist_every; /* the blow-up check of sim_step at the history rows */
    double hv[HIST_MAX];
    double next_frame_t = ro.field_interval;
    if (ck.restarted) { /* the checkpoint's rows and frames are on disk */
        next_frame_t = ck.meta.next_frame_t;
        rc = run_par_agree(field_writer_resume(fw, (size_t)ck.meta.frames, ck.meta.xdmf_grids,
                                               ck.meta.xdmf_len, err),
                           err);
    } else {
        history_values(s, &hl, hv);
        if (!(rc = run_par_agree(hw ? history_writer_append(hw, hv, err) : 0, err)))
            rc = run_par_agree(field_writer_write(fw, s, err), err);
    }
    if (rc)
        goto done;

    struct progress pr;
    progress_start(&pr, run_par_root() ? opt->progress : 0, s->n_steps, par_n_global(s));
    progress_set_every(&pr, opt->progress_every);
    double t0 = omp_get_wtime();
    run_signals_install();
    while (!sim_done(s)) {
        s->stop_time = ro.field_interval > 0.0 ? next_frame_t : 0.0; /* frames land on time */
        s->stress_skip = !stress_read_after_step(s, &ro, hist_every, next_frame_t, ck.opt.on);
        rc = sim_step(s, err);
        if (rc)
            break;
        int last = sim_done(s);
        const int hist_row = s->step % hist_every == 0 || last;
        if (hist_row) {
            /* sim_step checked the energy at this step: the account is current */
            history_values(s, &hl, hv);
            if ((rc = run_par_agree(hw ? history_writer_append(hw, hv, err) : 0, err)))
                break;
        }
        int frame = 0;
        if (ro.field_interval > 0.0) {
            if (s->t >= next_frame_t - 1e-12 * ro.field_interval) {
                frame = 1;
                while (next_frame_t <= s->t + 1e-12 * ro.field_interval)
                    next_frame_t += ro.field_interval;
            }
        } else if (ro.field_every > 0 && s->step % ro.field_every == 0) {
            frame = 1;
        }
        if (frame || last) {
            if ((rc = run_par_agree(field_writer_write(fw, s, err), err)))
                break;
        }
        if ((rc = run_balance_step(&rb, s, hist_row, log, err))) /* mpirun: rebalancing */
            break;
        int sig = run_signal_agreed(); /* distributed: the same step on every rank */
        /* agreed: a rank that failed before the checkpoint's file was
         * opened meets the others' first agreement inside the write */
        if ((ck.opt.on || sig) &&
            (rc = run_par_agree(run_ckpt_maybe(&ck, s, hw, fw, next_frame_t, sig != 0, log, err),
                                err)))
            break;
        progress_update_sim(&pr, s);
        if ((res->signal = sig))
            break;
    }
    run_signals_restore();
    s->stress_skip = false; /* the loop's outputs are written */
    double wall = omp_get_wtime() - t0;
    progress_finish(&pr);
    res->steps = s->step;
    res->time = s->t;
    res->wall_seconds = wall;
    res->particles = par_n_global(s);
    res->bonds = s->ops->interactions
                     ? par_interactions_global(s, s->ops->interactions(s->model, s)) : 0;
    res->particle_steps_per_s = wall > 0 ? (double)res->particles * (double)s->step / wall : 0;
    res->frames = field_writer_frames(fw);
    if (log) {
        fprintf(log, "steps_done: %ld\ntime_reached: %.6g s\nwall_seconds: %.3f\n", s->step,
                s->t, wall);
        fprintf(log, "particle_steps_per_s: %.4g\nframes: %zu\n", res->particle_steps_per_s,
                res->frames);
        const double input = fabs(s->energy.initial_total) + fabs(s->energy.external);
        if (input > 0.0) /* the fraction is what tells a user whether to trust a run */
            fprintf(log, "energy_balance_final: %.6g J (input %.6g J; %.3g %% of the input)\n",
                    s->energy.balance, input, 100.0 * s->energy.balance / input);
        else
            fprintf(log, "energy_balance_final: %.6g J (no energy put in)\n", s->energy.balance);
        run_par_log_end(s, log);
    }
    if (!rc && hl.frag) { /* the fragment table of the final state */
        snprintf(path, sizeof path, "%s/fragments.csv", dir);
        if (!(rc = run_fragments(hl.frag, s, err)) && run_par_root())
            rc = fragments_write_csv(hl.frag, path, s->t, err);
        rc = run_par_agree(rc, err);
    }
    run_balance_end(&rb, rc ? NULL : s, log); /* collective: every rank */
    snprintf(res->checkpoint, sizeof res->checkpoint, "%s", ck.last);
    if (rc && log)
        fprintf(log, "status: FAILED: %s\n", err->msg);
    else if (res->signal && log)
        fprintf(log, "status: interrupted by signal %d at step %ld, t = %.6g s; checkpoint %s; "
                     "continue with: spall run %s --restart %s\n",
                res->signal, s->step, s->t, ck.last, opt->deck_path, dir);
    else if (log)
        fprintf(log, "status: completed\n");
done:
    run_balance_end(&rb, NULL, NULL);
    run_ckpt_end(&ck);
    fragments_destroy(&frag);
    if (log)
        fclose(log);
    field_writer_destroy(&fw);
    history_writer_destroy(&hw);
    sim_destroy(&s);
    deck_destroy(&d);
    return rc;
}
