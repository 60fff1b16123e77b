/**
 * @file report.c
 * @brief `spall validate --report DIR`: a Markdown page with the table of
 *        checks and, per case, PNG plots of the series the cases attached
 *        (measured time histories against references, see vreport_series).
 */
#define _POSIX_C_SOURCE 200809L
#include "validation/validation.h"

#include "io/plot.h"
#include "spall/error.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

static double check_err(const struct vcheck *c)
{
    double e = fabs(c->measured - c->reference);
    if (c->relative && c->reference != 0.0)
        e /= fabs(c->reference);
    return e;
}

/* Markdown-safe copy (pipes would break the table) */
static void md(FILE *f, const char *s)
{
    for (; *s; s++)
        fputs(*s == '|' ? "\\|" : (char[2]){*s, 0}, f);
}

/* the registry's maturity note of a case (NULL if none or not a registered case) */
static const char *case_status(const char *name)
{
    size_t n = 0;
    const struct vcase *cases = validation_cases(&n);
    for (size_t k = 0; k < n; k++)
        if (strcmp(cases[k].name, name) == 0)
            return cases[k].status;
    return NULL;
}

static int write_plot(const struct vreport *r, size_t first, const char *png,
                      struct spall_error *err)
{
    const struct vseries *s0 = &r->series[first];
    size_t n = 0;
    for (size_t k = first; k < r->n_series; k++)
        n += strcmp(r->series[k].case_name, s0->case_name) == 0 &&
             strcmp(r->series[k].plot, s0->plot) == 0;
    struct plot_series *ser = calloc(n, sizeof *ser);
    struct plot_refline *refs = calloc(n, sizeof *refs);
    if (!ser || !refs) {
        free(ser);
        free(refs);
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory writing the report");
    }
    struct plot_spec spec = {0};
    spec.title = s0->plot;
    size_t ns = 0, nr = 0;
    for (size_t k = first; k < r->n_series; k++) {
        const struct vseries *v = &r->series[k];
        if (strcmp(v->case_name, s0->case_name) != 0 || strcmp(v->plot, s0->plot) != 0)
            continue;
        if (!spec.xlabel && v->xlabel[0])
            spec.xlabel = v->xlabel;
        if (!spec.ylabel && v->ylabel[0])
            spec.ylabel = v->ylabel;
        if (v->kind == VSERIES_XMARK || v->kind == VSERIES_YMARK) {
            refs[nr].axis = v->kind == VSERIES_XMARK ? 'x' : 'y';
            refs[nr].value = v->kind == VSERIES_XMARK ? v->x[0] : v->y[0];
            refs[nr++].label = v->label[0] ? v->label : NULL;
        } else {
            ser[ns].label = v->label[0] ? v->label : NULL;
            ser[ns].x = v->x;
            ser[ns].y = v->y;
            ser[ns].n = v->n;
            ser[ns++].style = v->kind == VSERIES_REF      ? PLOT_DASHED
                              : v->kind == VSERIES_POINTS ? PLOT_POINTS
                                                          : PLOT_LINE;
        }
    }
    spec.series = ser;
    spec.n_series = ns;
    spec.refs = refs;
    spec.n_refs = nr;
    int rc = plot_png(png, &spec, err);
    free(ser);
    free(refs);
    return rc;
}

int vreport_write_report(const struct vreport *r, const char *dir, struct spall_error *err)
{
    if (mkdir(dir, 0777) != 0 && errno != EEXIST)
        return spall_error_set(err, SPALL_ERR_IO, "cannot create report directory '%s': %s", dir,
                               strerror(errno));
    char path[4096];
    snprintf(path, sizeof path, "%s/report.md", dir);
    FILE *f = fopen(path, "w");
    if (!f)
        return spall_error_set(err, SPALL_ERR_IO, "cannot write '%s': %s", path, strerror(errno));
    size_t pass = 0;
    for (size_t k = 0; k < r->n; k++)
        pass += r->checks[k].pass;
    fprintf(f, "# spall validation report\n\n%zu checks: %zu passed, %zu failed.\n\n", r->n, pass,
            r->n - pass);
    fprintf(f, "| case | quantity | unit | reference | measured | error | tolerance | result | "
               "kind |\n"
               "|---|---|---|---|---|---|---|---|---|\n");
    for (size_t k = 0; k < r->n; k++) {
        const struct vcheck *c = &r->checks[k];
        fprintf(f, "| %s | ", c->case_name);
        md(f, c->quantity);
        fprintf(f, " | %s | %.6g | %.6g | ", c->unit, c->reference, c->measured);
        if (c->relative)
            fprintf(f, "%.3g %% | %.3g %% | ", 100.0 * check_err(c), 100.0 * c->tolerance);
        else
            fprintf(f, "%.3g | %.3g | ", check_err(c), c->tolerance);
        fprintf(f, "%s | %s |\n", c->pass ? "PASS" : c->known_gap ? "FAIL (known gap)" : "**FAIL**",
                vkind_name(c->kind));
    }
    int rc = SPALL_OK;
    const char *last_case = NULL;
    size_t plot_no = 0;
    for (size_t k = 0; k < r->n; k++) {
        const struct vcheck *c = &r->checks[k];
        if (last_case && strcmp(last_case, c->case_name) == 0)
            continue;
        last_case = c->case_name;
        fprintf(f, "\n## %s\n\n", c->case_name);
        const char *status = case_status(c->case_name);
        if (status) {
            fprintf(f, "Status: ");
            md(f, status);
            fprintf(f, "\n\n");
        }
        for (size_t j = k; j < r->n && strcmp(r->checks[j].case_name, c->case_name) == 0; j++) {
            fprintf(f, "- ");
            md(f, r->checks[j].quantity);
            fprintf(f, " (%s): %s. Source: ", vkind_name(r->checks[j].kind),
                    r->checks[j].pass ? "PASS" : "FAIL");
            md(f, r->checks[j].source);
            if (r->checks[j].note[0]) {
                fprintf(f, ". Note: ");
                md(f, r->checks[j].note);
            }
            fprintf(f, "\n");
        }
        /* one PNG per distinct plot of this case, in order of first use */
        for (size_t s = 0; s < r->n_series && rc == SPALL_OK; s++) {
            const struct vseries *v = &r->series[s];
            if (strcmp(v->case_name, c->case_name) != 0)
                continue;
            int seen = 0;
            for (size_t q = 0; q < s && !seen; q++)
                seen = strcmp(r->series[q].case_name, v->case_name) == 0 &&
                       strcmp(r->series[q].plot, v->plot) == 0;
            if (seen)
                continue;
            char png[4096], name[128];
            snprintf(name, sizeof name, "%s_%zu.png", c->case_name, ++plot_no);
            snprintf(png, sizeof png, "%s/%s", dir, name);
            rc = write_plot(r, s, png, err);
            fprintf(f, "\n![%s](%s)\n", v->plot, name);
        }
    }
    if (fclose(f) != 0 && rc == SPALL_OK)
        rc = spall_error_set(err, SPALL_ERR_IO, "cannot write '%s'", path);
    return rc;
}
