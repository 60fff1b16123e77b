#define _POSIX_C_SOURCE 200809L
#include "io/run_util.h"

#include "core/sim.h"
#include "spall/error.h"

#include <dirent.h>
#include <errno.h>
#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

void run_default_out_dir(const char *deck_path, char *out, size_t len)
{
    const char *base = strrchr(deck_path, '/');
    base = base ? base + 1 : deck_path;
    snprintf(out, len, "%s", base);
    char *dot = strrchr(out, '.');
    if (dot && dot != out && (strcmp(dot, ".yaml") == 0 || strcmp(dot, ".yml") == 0))
        *dot = '\0';
    if (strcmp(out, deck_path) == 0 || out[0] == '\0') /* deck had no extension */
        snprintf(out, len, "%s.out", base);
}

static int mkdir_p(const char *dir, struct spall_error *err)
{
    char tmp[1024];
    snprintf(tmp, sizeof tmp, "%s", dir);
    for (char *p = tmp + 1; *p; p++) {
        if (*p != '/')
            continue;
        *p = '\0';
        if (mkdir(tmp, 0777) != 0 && errno != EEXIST)
            return spall_error_set(err, SPALL_ERR_IO, "cannot create directory '%s': %s", tmp,
                                   strerror(errno));
        *p = '/';
    }
    if (mkdir(tmp, 0777) != 0 && errno != EEXIST)
        return spall_error_set(err, SPALL_ERR_IO, "cannot create directory '%s': %s", tmp,
                               strerror(errno));
    return SPALL_OK;
}

static int is_result_file(const char *name)
{
    size_t n = strlen(name);
    if (strcmp(name, "run.log") == 0 || strcmp(name, "history.csv") == 0 ||
        strcmp(name, "fields.xdmf") == 0)
        return 1;
    if (strncmp(name, "fields_", 7) == 0 && n > 3 && strcmp(name + n - 3, ".h5") == 0)
        return 1;
    if (n > 4 && strcmp(name + n - 4, ".png") == 0)
        return 1;
    return 0;
}

int run_prepare_out_dir(const char *dir, bool overwrite, struct spall_error *err)
{
    struct stat st;
    if (stat(dir, &st) == 0) {
        if (!S_ISDIR(st.st_mode))
            return spall_error_set(err, SPALL_ERR_IO, "output path '%s' exists and is not a directory",
                                   dir);
        DIR *dd = opendir(dir);
        if (!dd)
            return spall_error_set(err, SPALL_ERR_IO, "cannot open output directory '%s': %s", dir,
                                   strerror(errno));
        int nonempty = 0;
        struct dirent *e;
        while ((e = readdir(dd)))
            if (strcmp(e->d_name, ".") && strcmp(e->d_name, ".."))
                nonempty = 1;
        closedir(dd);
        if (nonempty && !overwrite)
            return spall_error_set(err, SPALL_ERR_INPUT,
                                   "output directory '%s' already holds results; choose another "
                                   "with -o DIR or pass --overwrite",
                                   dir);
        if (nonempty) {
            dd = opendir(dir);
            if (!dd)
                return spall_error_set(err, SPALL_ERR_IO, "cannot open '%s'", dir);
            char path[2048];
            while ((e = readdir(dd))) {
                if (!is_result_file(e->d_name))
                    continue;
                snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
                if (unlink(path) != 0) {
                    closedir(dd);
                    return spall_error_set(err, SPALL_ERR_IO, "cannot remove old result '%s': %s",
                                           path, strerror(errno));
                }
            }
            closedir(dd);
        }
        return SPALL_OK;
    }
    return mkdir_p(dir, err);
}

void progress_start(struct progress *p, int mode, long n_steps, size_t n_particles)
{
    p->on = mode == 1 || (mode < 0 && isatty(STDERR_FILENO));
    p->batch = mode < 0 && !p->on;
    p->every = PROGRESS_BATCH_EVERY;
    p->n_steps = n_steps;
    p->n_particles = n_particles;
    p->t_start = omp_get_wtime();
    p->t_last = 0.0;
}

static void fmt_hms(double s, char *buf, size_t len)
{
    if (!(s >= 0) || s > 1e7) {
        snprintf(buf, len, "--:--:--");
        return;
    }
    long t = (long)(s + 0.5);
    snprintf(buf, len, "%02ld:%02ld:%02ld", t / 3600, (t / 60) % 60, t % 60);
}

void progress_update(struct progress *p, long step, double t, double end_time)
{
    if (!p->on)
        return;
    double now = omp_get_wtime();
    if (now - p->t_last < 0.2 && step != p->n_steps)
        return;
    p->t_last = now;
    double el = now - p->t_start;
    double frac = end_time > 0 ? t / end_time
                               : (p->n_steps > 0 ? (double)step / (double)p->n_steps : 1.0);
    if (frac > 1.0)
        frac = 1.0;
    double rate = el > 0 ? (double)p->n_particles * (double)step / el : 0.0;
    char eta[32];
    fmt_hms(frac > 0 ? el * (1.0 - frac) / frac : -1.0, eta, sizeof eta);
    int width = 24, fill = (int)(frac * width + 0.5);
    char bar[32];
    for (int k = 0; k < width; k++)
        bar[k] = k < fill ? '#' : '.';
    bar[width] = '\0';
    fprintf(stderr, "\r[%s] step %ld/%ld  t = %.4g/%.4g s  %5.1f%%  %.3g particle-steps/s  ETA %s ",
            bar, step, p->n_steps, t, end_time, 100.0 * frac, rate, eta);
    fflush(stderr);
}

void progress_set_every(struct progress *p, double seconds)
{
    if (seconds > 0.0 && isfinite(seconds))
        p->every = seconds;
}

/* One line per interval for logs of batch jobs: no carriage returns, and
 * the energy balance, the first sign of a run going wrong. */
static void progress_batch(struct progress *p, const struct sim *s)
{
    double now = omp_get_wtime();
    if (now - p->t_last < p->every)
        return;
    if (p->t_last == 0.0 && now - p->t_start < p->every)
        return;
    p->t_last = now;
    double el = now - p->t_start;
    const long planned = s->n_steps + s->n_split;
    double frac = s->end_time > 0 ? s->t / s->end_time
                                  : (planned > 0 ? (double)s->step / (double)planned : 1.0);
    if (frac > 1.0)
        frac = 1.0;
    double rate = el > 0 ? (double)p->n_particles * (double)s->step / el : 0.0;
    char eta[32];
    fmt_hms(frac > 0 ? el * (1.0 - frac) / frac : -1.0, eta, sizeof eta);
    double input = fabs(s->energy.initial_total) + fabs(s->energy.external);
    char bal[64];
    if (input > 0.0)
        snprintf(bal, sizeof bal, "%.3g of the energy put in", s->energy.balance / input);
    else
        snprintf(bal, sizeof bal, "%.3g J (no energy put in)", s->energy.balance);
    fprintf(stderr,
            "spall: progress: step %ld/%ld%s, t = %.4g/%.4g s (%.1f %%), %.3g particle-steps/s, "
            "ETA %s, energy balance %s\n",
            s->step, planned, s->adaptive_dt ? " (estimate)" : "", s->t, s->end_time,
            100.0 * frac, rate, eta, bal);
    fflush(stderr);
}

void progress_update_sim(struct progress *p, const struct sim *s)
{
    if (p->batch)
        progress_batch(p, s);
    else
        progress_update(p, s->step, s->t, s->end_time);
}

void progress_finish(struct progress *p)
{
    if (p->on)
        fprintf(stderr, "\n");
}
