#define _POSIX_C_SOURCE 200809L
/**
 * @file run_restart.c
 * @brief Checkpoints, restart and signals of `spall run` (run_restart.h).
 */
#include "io/run_restart.h"

#include "core/field_state.h"
#include "core/parallel/comm.h"
#include "core/sim.h"
#include "io/output.h"
#include "io/run_util.h"
#include "spall/error.h"
#include "spall/spall.h"

#include <errno.h>
#include <omp.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>

/* The one piece of process-wide state: a signal handler can only talk to
 * the loop through a flag. */
static volatile sig_atomic_t g_signal;

static void on_signal(int sig)
{
    g_signal = sig;
}

static const int k_signals[] = {SIGTERM, SIGINT, SIGUSR1};
static struct sigaction g_old[3];

void run_signals_install(void)
{
    g_signal = 0;
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_signal;
    sigemptyset(&sa.sa_mask);
    for (int k = 0; k < 3; k++)
        sigaction(k_signals[k], &sa, &g_old[k]);
}

void run_signals_restore(void)
{
    for (int k = 0; k < 3; k++)
        sigaction(k_signals[k], &g_old[k], NULL);
}

int run_signal_pending(void)
{
    return (int)g_signal;
}

int run_signal_agreed(void)
{
    /* the batch system signals every rank, mpirun forwards SIGUSR1 to all,
     * but not necessarily within the same step: the highest signal any rank
     * has seen stops all of them after this step */
    if (par_size() <= 1)
        return run_signal_pending();
    return (int)-par_min_i64(-(int64_t)g_signal);
}

static int collect_state(struct run_ckpt *c, struct sim *s, struct spall_error *err)
{
    if (c->fs)
        return SPALL_OK;
    int rc = field_state_create(&c->fs, err);
    if (!rc)
        rc = sim_register_state(s, c->fs, err);
    if (!rc && par_size() > 1) /* refused before the run, not at its first checkpoint */
        rc = checkpoint_par_check(c->fs, err);
    return rc;
}

int run_ckpt_begin(struct run_ckpt *c, const struct spall_run_options *opt, const struct deck *d,
                   const struct checkpoint_options *co, struct sim *s, char *out_dir,
                   size_t out_len, struct spall_error *err)
{
    memset(c, 0, sizeof *c);
    c->opt = *co;
    if (c->opt.keep < 1)
        c->opt.keep = 2;
    c->deck = d;
    c->last_step = -1;
    c->next_t = c->opt.every_time;
    c->wall_last = omp_get_wtime();
    /* a model that cannot be checkpointed is refused now, not mid-run */
    if (c->opt.on && collect_state(c, s, err))
        return err->code;
    if (!opt->restart) {
        if (opt->out_dir)
            snprintf(out_dir, out_len, "%s", opt->out_dir);
        else
            run_default_out_dir(opt->deck_path, out_dir, out_len);
        snprintf(c->dir, sizeof c->dir, "%s", out_dir);
        return SPALL_OK;
    }
    int rc = checkpoint_locate(opt->restart, c->file, sizeof c->file, c->src_dir,
                               sizeof c->src_dir, err);
    if (!rc)
        rc = collect_state(c, s, err);
    if (!rc)
        rc = par_fault("restart", err);
    if (!rc) /* each rank reads the whole file itself; the caller agrees */
        rc = checkpoint_read(c->file, s, c->fs, d, &c->meta, err);
    if (rc)
        return rc;
    c->restarted = true;
    c->next_t = c->meta.next_ckpt_t;
    snprintf(out_dir, out_len, "%s", opt->out_dir ? opt->out_dir : c->src_dir);
    snprintf(c->dir, sizeof c->dir, "%s", out_dir);
    return SPALL_OK;
}

bool run_ckpt_same_dir(const struct run_ckpt *c)
{
    struct stat a, b;
    if (stat(c->dir, &a) != 0 || stat(c->src_dir, &b) != 0)
        return false;
    return a.st_dev == b.st_dev && a.st_ino == b.st_ino;
}

static int copy_file(const char *from, const char *to, long bytes, struct spall_error *err)
{
    FILE *in = fopen(from, "rb");
    if (!in)
        return spall_error_set(err, SPALL_ERR_INPUT, "cannot read '%s': %s", from,
                               strerror(errno));
    FILE *out = fopen(to, "wb");
    if (!out) {
        fclose(in);
        return spall_error_set(err, SPALL_ERR_IO, "cannot write '%s': %s", to, strerror(errno));
    }
    char buf[65536];
    long left = bytes;
    int bad = 0;
    while (!bad && (bytes < 0 || left > 0)) {
        size_t want = sizeof buf;
        if (bytes >= 0 && (long)want > left)
            want = (size_t)left;
        size_t got = fread(buf, 1, want, in);
        if (got == 0)
            break;
        bad = fwrite(buf, 1, got, out) != got;
        left -= (long)got;
    }
    bad |= ferror(in) || (bytes >= 0 && left != 0);
    fclose(in);
    bad |= fclose(out) != 0;
    if (bad)
        return spall_error_set(err, SPALL_ERR_IO, "cannot copy '%s' to '%s'", from, to);
    return SPALL_OK;
}

int run_ckpt_copy_outputs(struct run_ckpt *c, bool overwrite, struct spall_error *err)
{
    int rc = run_prepare_out_dir(c->dir, overwrite, err);
    char from[1300], to[1300];
    snprintf(from, sizeof from, "%s/history.csv", c->src_dir);
    snprintf(to, sizeof to, "%s/history.csv", c->dir);
    if (!rc)
        rc = copy_file(from, to, (long)c->meta.history_bytes, err);
    for (int64_t k = 0; k < c->meta.frames && !rc; k++) {
        snprintf(from, sizeof from, "%s/fields_%06lld.h5", c->src_dir, (long long)k);
        snprintf(to, sizeof to, "%s/fields_%06lld.h5", c->dir, (long long)k);
        rc = copy_file(from, to, -1, err);
    }
    return rc;
}

int run_ckpt_maybe(struct run_ckpt *c, struct sim *s, const struct history_writer *hw,
                   const struct field_writer *fw, double next_frame_t, bool force, FILE *log,
                   struct spall_error *err)
{
    bool due = force;
    if (c->opt.every_steps > 0 && s->step % c->opt.every_steps == 0)
        due = true;
    if (c->opt.every_time > 0 && s->t >= c->next_t - 1e-12 * c->opt.every_time) {
        due = true;
        while (c->next_t <= s->t + 1e-12 * c->opt.every_time)
            c->next_t += c->opt.every_time;
    }
    double now = omp_get_wtime();
    if (c->opt.every_minutes > 0) {
        bool late = now - c->wall_last >= 60.0 * c->opt.every_minutes;
        /* the ranks' clocks differ: a checkpoint is collective, so any rank's
         * "due" makes it due for all */
        if (par_size() > 1)
            late = par_min_i64(-(int64_t)late) < 0;
        due |= late;
    }
    if (!due || (force && c->last_step == s->step)) /* a signal right after a checkpoint */
        return SPALL_OK;
    /* the owners may have replaced their arrays (a new pair list): the
     * slots are registered afresh for every checkpoint */
    field_state_destroy(&c->fs);
    int rc = collect_state(c, s, err);
    if (!rc)
        rc = par_fault("checkpoint", err);
    if (rc) /* distributed: the caller agrees (run.c) */
        return rc;
    struct checkpoint_meta m = {.frames = (int64_t)field_writer_frames(fw),
                                /* distributed: rank 0 writes history.csv */
                                .history_bytes = hw ? history_writer_bytes(hw) : 0,
                                .next_frame_t = next_frame_t,
                                .next_ckpt_t = c->next_t};
    m.xdmf_grids = field_writer_grids(fw, &m.xdmf_len);
    rc = checkpoint_save(c->dir, c->opt.keep, s, c->fs, c->deck, &m, c->last, sizeof c->last,
                         err);
    double w = omp_get_wtime();
    if (!rc)
        c->last_step = s->step;
    if (!rc && log) {
        fprintf(log, "checkpoint: %s (step %ld, t = %.17g s, %.3f s to write)\n", c->last,
                s->step, s->t, w - now);
        fflush(log);
    }
    c->wall_last = w;
    return rc;
}

void run_ckpt_log_restart(const struct run_ckpt *c, const struct sim *s, FILE *log)
{
    if (!log) /* distributed: rank 0 writes run.log */
        return;
    time_t now = time(NULL);
    char when[64];
    strftime(when, sizeof when, "%Y-%m-%dT%H:%M:%SZ", gmtime(&now));
    fprintf(log, "# restart\nrestarted: %s\nrestart_from: %s\nrestart_step: %ld\n"
                 "restart_time: %.17g s\nthreads: %d\nend_time: %.6g s\n",
            when, c->file, s->step, s->t, omp_get_max_threads(), s->end_time);
    fflush(log);
}

void run_ckpt_end(struct run_ckpt *c)
{
    field_state_destroy(&c->fs);
    free(c->meta.xdmf_owned);
    c->meta.xdmf_owned = NULL;
}
