/**
 * @file postprocess.c
 * @brief `spall plot` and `spall fragments` (see postprocess.h): small CSV
 *        readers over the files a run writes (history.csv: io/history.c;
 *        fragments.csv: core/fragments.c) and plots through io/plot.h.
 */
#include "io/postprocess.h"

#include "io/plot.h"
#include "spall/error.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/** A CSV table of doubles: a header of names, then rows.  Lines starting
 *  with '#' are comments. */
struct table {
    char **names;
    size_t ncol;
    double *v; /* row-major, nrow x ncol */
    size_t nrow, cap;
};

static void table_free(struct table *t)
{
    for (size_t c = 0; c < t->ncol; c++)
        free(t->names[c]);
    free(t->names);
    free(t->v);
    memset(t, 0, sizeof *t);
}

static char *read_line(FILE *f)
{
    size_t cap = 256, len = 0;
    char *s = malloc(cap);
    int ch;
    if (!s)
        return NULL;
    while ((ch = fgetc(f)) != EOF && ch != '\n') {
        if (len + 1 == cap) {
            char *q = realloc(s, cap *= 2);
            if (!q) {
                free(s);
                return NULL;
            }
            s = q;
        }
        s[len++] = (char)ch;
    }
    if (ch == EOF && len == 0) {
        free(s);
        return NULL;
    }
    if (len && s[len - 1] == '\r')
        len--;
    s[len] = '\0';
    return s;
}

static int table_read(struct table *t, const char *path, struct spall_error *err)
{
    memset(t, 0, sizeof *t);
    FILE *f = fopen(path, "r");
    if (!f)
        return spall_error_set(err, SPALL_ERR_IO, "cannot open '%s'", path);
    int rc = SPALL_OK;
    long lineno = 0;
    char *line;
    while ((line = read_line(f))) {
        lineno++;
        if (line[0] == '#' || line[0] == '\0') {
            free(line);
            continue;
        }
        if (!t->names) { /* header */
            size_t n = 1;
            for (const char *c = line; *c; c++)
                n += *c == ',';
            t->names = calloc(n, sizeof *t->names);
            if (!t->names) {
                free(line);
                rc = spall_error_set(err, SPALL_ERR_NOMEM, "out of memory reading '%s'", path);
                break;
            }
            char *save = line;
            for (size_t c = 0; c < n; c++) {
                char *comma = strchr(save, ',');
                if (comma)
                    *comma = '\0';
                t->names[c] = malloc(strlen(save) + 1);
                if (t->names[c])
                    strcpy(t->names[c], save);
                t->ncol++;
                save = comma ? comma + 1 : save + strlen(save);
            }
            free(line);
            continue;
        }
        if (t->nrow == t->cap) {
            size_t cap = t->cap ? 2 * t->cap : 256;
            double *v = realloc(t->v, cap * t->ncol * sizeof *v);
            if (!v) {
                free(line);
                rc = spall_error_set(err, SPALL_ERR_NOMEM, "out of memory reading '%s'", path);
                break;
            }
            t->v = v;
            t->cap = cap;
        }
        char *p = line;
        for (size_t c = 0; c < t->ncol && !rc; c++) {
            char *end;
            double x = strtod(p, &end);
            if (end == p || (*end != ',' && *end != '\0') || (*end == '\0' && c + 1 < t->ncol))
                rc = spall_error_set(err, SPALL_ERR_INPUT,
                                     "%s:%ld:%ld: expected %zu numbers separated by commas",
                                     path, lineno, (long)(p - line) + 1, t->ncol);
            t->v[t->nrow * t->ncol + c] = x;
            p = *end ? end + 1 : end;
        }
        free(line);
        if (rc)
            break;
        t->nrow++;
    }
    fclose(f);
    if (!rc && !t->names)
        rc = spall_error_set(err, SPALL_ERR_INPUT, "'%s' has no header line", path);
    if (rc)
        table_free(t);
    return rc;
}

/** Column whose name is @p want, with or without its " [unit]". */
static long table_find(const struct table *t, const char *want)
{
    size_t wl = strlen(want);
    for (size_t c = 0; c < t->ncol; c++) {
        const char *n = t->names[c];
        if (strcmp(n, want) == 0 || (strncmp(n, want, wl) == 0 && strncmp(n + wl, " [", 2) == 0))
            return (long)c;
    }
    return -1;
}

static int unknown_column(const struct table *t, const char *path, const char *want,
                          struct spall_error *err)
{
    char list[SPALL_ERROR_MSG_LEN / 2];
    size_t len = 0;
    list[0] = '\0';
    for (size_t c = 0; c < t->ncol && len + 1 < sizeof list; c++) {
        int m = snprintf(list + len, sizeof list - len, "%s%s", c ? ", " : "", t->names[c]);
        if (m < 0)
            break;
        len += (size_t)m;
    }
    return spall_error_set(err, SPALL_ERR_INPUT, "'%s' has no column '%.64s'; its columns: %s",
                           path, want, list);
}

static char *join(const char *dir, const char *name)
{
    size_t n = strlen(dir) + strlen(name) + 2;
    char *p = malloc(n);
    if (p)
        snprintf(p, n, "%s/%s", dir, name);
    return p;
}

/** The "[unit]" of a column name ("" if none). */
static void unit_of(const char *name, char *out, size_t size)
{
    const char *b = strstr(name, " [");
    const char *e = b ? strchr(b, ']') : NULL;
    if (!b || !e) {
        out[0] = '\0';
        return;
    }
    snprintf(out, size, "%.*s", (int)(e - b - 2), b + 2);
}

int post_plot_history(const char *run_dir, const char *const *columns, size_t n_columns,
                      const char *png_path, size_t *rows_out, struct spall_error *err)
{
    static const char *const energy[] = {"kinetic", "strain", "dissipated", "damping",
                                         "external_work", "energy_balance"};
    char *path = join(run_dir, "history.csv");
    if (!path)
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory");
    struct table t;
    int rc = table_read(&t, path, err);
    if (rc) {
        free(path);
        return rc;
    }
    long tc = table_find(&t, "time");
    size_t want_n = n_columns ? n_columns : sizeof energy / sizeof energy[0];
    long *cols = calloc(want_n, sizeof *cols);
    double *x = malloc((t.nrow ? t.nrow : 1) * sizeof *x);
    double *y = malloc((t.nrow ? t.nrow : 1) * want_n * sizeof *y);
    struct plot_series *ser = calloc(want_n, sizeof *ser);
    size_t ns = 0;
    if (!cols || !x || !y || !ser) {
        rc = spall_error_set(err, SPALL_ERR_NOMEM, "out of memory");
        goto done;
    }
    if (tc < 0) {
        rc = unknown_column(&t, path, "time", err);
        goto done;
    }
    for (size_t k = 0; k < want_n; k++) {
        long c = table_find(&t, n_columns ? columns[k] : energy[k]);
        if (c < 0 && n_columns) {
            rc = unknown_column(&t, path, columns[k], err);
            goto done;
        }
        if (c >= 0)
            cols[ns++] = c;
    }
    if (ns == 0) {
        rc = spall_error_set(err, SPALL_ERR_INPUT, "'%s' has none of the energy columns", path);
        goto done;
    }
    for (size_t i = 0; i < t.nrow; i++)
        x[i] = t.v[i * t.ncol + (size_t)tc];
    char unit[32] = "", u[32];
    int same = 1;
    for (size_t k = 0; k < ns; k++) {
        double *yk = y + k * (t.nrow ? t.nrow : 1);
        for (size_t i = 0; i < t.nrow; i++)
            yk[i] = t.v[i * t.ncol + (size_t)cols[k]];
        ser[k] = (struct plot_series){.label = t.names[cols[k]], .x = x, .y = yk, .n = t.nrow,
                                      .style = PLOT_LINE};
        unit_of(t.names[cols[k]], u, sizeof u);
        if (k == 0)
            strcpy(unit, u);
        else if (strcmp(unit, u) != 0)
            same = 0;
    }
    char ylabel[64];
    if (same && unit[0])
        snprintf(ylabel, sizeof ylabel, "[%s]", unit);
    else
        snprintf(ylabel, sizeof ylabel, "value (units in the legend)");
    char title[256];
    snprintf(title, sizeof title, "%s/history.csv", run_dir);
    struct plot_spec spec = {.title = title, .xlabel = t.names[tc], .ylabel = ylabel,
                             .series = ser, .n_series = ns};
    rc = plot_png(png_path, &spec, err);
    if (!rc && rows_out)
        *rows_out = t.nrow;
done:
    free(cols);
    free(x);
    free(y);
    free(ser);
    table_free(&t);
    free(path);
    return rc;
}

static int by_mass_desc(const void *a, const void *b)
{
    double ma = ((const double *)a)[1], mb = ((const double *)b)[1];
    return (ma < mb) - (ma > mb);
}

int post_fragments(const char *run_dir, const char *csv_path, const char *png_path,
                   size_t *count_out, struct spall_error *err)
{
    char *path = join(run_dir, "fragments.csv");
    if (!path)
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory");
    FILE *probe = fopen(path, "r");
    if (!probe) {
        int rc = spall_error_set(err, SPALL_ERR_IO,
                                 "no '%s': it is written at the end of a run of a bonded model "
                                 "(lattice, peridynamics)", path);
        free(path);
        return rc;
    }
    fclose(probe);
    struct table t;
    int rc = table_read(&t, path, err);
    if (rc) {
        free(path);
        return rc;
    }
    long cp = table_find(&t, "particles"), cm = table_find(&t, "mass");
    size_t n = t.nrow;
    double *pm = malloc((n ? n : 1) * 2 * sizeof *pm); /* (particles, mass) pairs */
    double *lx = malloc((n ? n : 1) * sizeof *lx), *ly = malloc((n ? n : 1) * sizeof *ly);
    FILE *out = NULL;
    if (!pm || !lx || !ly) {
        rc = spall_error_set(err, SPALL_ERR_NOMEM, "out of memory");
        goto done;
    }
    if (cp < 0 || cm < 0) {
        rc = unknown_column(&t, path, cp < 0 ? "particles" : "mass", err);
        goto done;
    }
    double total = 0;
    for (size_t i = 0; i < n; i++) {
        pm[2 * i] = t.v[i * t.ncol + (size_t)cp];
        pm[2 * i + 1] = t.v[i * t.ncol + (size_t)cm];
        total += pm[2 * i + 1];
    }
    qsort(pm, n, 2 * sizeof *pm, by_mass_desc);
    out = fopen(csv_path, "w");
    if (!out) {
        rc = spall_error_set(err, SPALL_ERR_IO, "cannot create '%s'", csv_path);
        goto done;
    }
    /* N(>= m): the cumulative count of fragments at least as heavy, the usual
     * way to show a fragment mass distribution */
    fprintf(out, "# fragment distribution of %s (%zu fragments, %.10g kg)\n", path, n, total);
    fprintf(out, "rank,particles,mass [kg],count_at_least_this_mass,mass_fraction_at_least\n");
    double cum = 0;
    size_t np = 0;
    for (size_t i = 0; i < n; i++) {
        cum += pm[2 * i + 1];
        fprintf(out, "%zu,%.0f,%.10g,%zu,%.10g\n", i + 1, pm[2 * i], pm[2 * i + 1], i + 1,
                total > 0 ? cum / total : 0.0);
        if (pm[2 * i + 1] > 0) {
            lx[np] = log10(pm[2 * i + 1]);
            ly[np++] = log10((double)(i + 1));
        }
    }
    if (fclose(out) != 0) {
        out = NULL;
        rc = spall_error_set(err, SPALL_ERR_IO, "cannot write '%s'", csv_path);
        goto done;
    }
    out = NULL;
    struct plot_series ser = {.label = "fragments", .x = lx, .y = ly, .n = np,
                              .style = PLOT_POINTS};
    char title[256];
    snprintf(title, sizeof title, "fragment mass distribution: %zu fragments", n);
    struct plot_spec spec = {.title = title, .xlabel = "log10 fragment mass [kg]",
                             .ylabel = "log10 number of fragments at least this heavy",
                             .series = &ser, .n_series = 1};
    rc = plot_png(png_path, &spec, err);
    if (!rc && count_out)
        *count_out = n;
done:
    if (out)
        fclose(out);
    free(pm);
    free(lx);
    free(ly);
    table_free(&t);
    free(path);
    return rc;
}
