/**
 * @file report.c
 * @brief `spall validate --report DIR`: a Markdown page with the table of
 *        checks and, per case, PNG plots of the series the cases attached
 *        (measured time histories against references, see vreport_series);
 *        `spall validate --markdown FILE`: the validation reference page
 *        (docs/validation.md), one section per registered case.
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

/* the registry's entry of a case (NULL if not a registered case) */
static const struct vcase *find_case(const char *name)
{
    size_t n = 0;
    const struct vcase *cases = validation_cases(&n);
    for (size_t k = 0; k < n; k++)
        if (strcmp(cases[k].name, name) == 0)
            return &cases[k];
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
        const struct vcase *vc = find_case(c->case_name);
        if (vc && vc->status) {
            fprintf(f, "Status: ");
            md(f, vc->status);
            fprintf(f, "\n\n");
        }
        /* beside a reduced standard run: the full tier's last recorded values */
        if (vc && vc->full_note) {
            fprintf(f, "Full tier (`--full`), last recorded: ");
            md(f, vc->full_note);
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

/* ---- `spall validate --markdown FILE`: the validation reference ---- */

static const char *const gate_text[] = {"full runs only", "reduced (`--quick`)", "full"};

/* the checks [*first, *end) the case @p name recorded (the checks of a case are contiguous) */
static void case_checks(const struct vreport *r, const char *name, size_t *first, size_t *end)
{
    size_t k = 0;
    while (k < r->n && strcmp(r->checks[k].case_name, name) != 0)
        k++;
    *first = k;
    while (k < r->n && strcmp(r->checks[k].case_name, name) == 0)
        k++;
    *end = k;
}

/* one word for a case's outcome: PASS, FAIL (known gaps), FAIL, ERROR, not run */
static const char *case_result(const struct vmd_case *m, const struct vreport *r, size_t first,
                               size_t end)
{
    if (!m->ran)
        return "not run";
    if (m->error[0])
        return "**ERROR**";
    int fail = 0, unknown = 0;
    for (size_t k = first; k < end; k++) {
        fail |= !r->checks[k].pass;
        unknown |= !r->checks[k].pass && !r->checks[k].known_gap;
    }
    return unknown ? "**FAIL**" : fail ? "PASS except known gaps" : "PASS";
}

static void md_value(FILE *f, const struct vcheck *c, double v)
{
    if (strcmp(c->unit, "yes=1") == 0)
        fputs(v == 1.0 ? "yes" : v == 0.0 ? "no" : "?", f);
    else
        fprintf(f, "%.6g", v);
}

static void md_case_table(FILE *f, const struct vreport *r, size_t first, size_t end)
{
    fprintf(f, "| quantity | unit | reference | measured | error | tolerance | result | source |\n"
               "|---|---|---|---|---|---|---|---|\n");
    for (size_t k = first; k < end; k++) {
        const struct vcheck *c = &r->checks[k];
        bool yes_no = strcmp(c->unit, "yes=1") == 0;
        fputs("| ", f);
        md(f, c->quantity);
        fprintf(f, " | %s | ", yes_no ? "" : c->unit);
        md_value(f, c, c->reference);
        fputs(" | ", f);
        md_value(f, c, c->measured);
        if (yes_no)
            fputs(" | | | ", f);
        else if (c->relative)
            fprintf(f, " | %.3g %% | %.3g %% | ", 100.0 * check_err(c), 100.0 * c->tolerance);
        else
            fprintf(f, " | %.3g | %.3g | ", check_err(c), c->tolerance);
        fprintf(f, "%s | ", c->pass ? "PASS" : c->known_gap ? "known gap" : "**FAIL**");
        md(f, c->source);
        fputs(" |\n", f);
    }
}

/* the notes (why this tolerance, cause of a gap), each distinct note once
 * with the quantities it belongs to */
static void md_case_notes(FILE *f, const struct vreport *r, size_t first, size_t end)
{
    int any = 0;
    for (size_t k = first; k < end; k++) {
        const struct vcheck *c = &r->checks[k];
        int seen = 0;
        for (size_t j = first; j < k && !seen; j++)
            seen = strcmp(r->checks[j].note, c->note) == 0;
        if (!c->note[0] || seen)
            continue;
        fputs(any++ ? "" : "\nNotes:\n", f); /* a list may start right after a line */
        fputs("- ", f);
        int gap = 0, n_q = 0;
        for (size_t j = k; j < end; j++) {
            if (strcmp(r->checks[j].note, c->note) != 0)
                continue;
            gap |= r->checks[j].known_gap;
            fputs(n_q++ ? ", " : "", f);
            md(f, r->checks[j].quantity);
        }
        fputs(gap ? " (**known gap**): " : ": ", f);
        md(f, c->note);
        fputs("\n", f);
    }
}

static const char *run_config(const struct vmd_case *m)
{
    return m->quick ? "reduced" : m->full ? "full" : "standard";
}

static void md_case(FILE *f, const struct vreport *r, const struct vcase *c,
                    const struct vmd_case *m)
{
    size_t first, end;
    case_checks(r, c->name, &first, &end);
    fprintf(f, "\n### %s\n\n", c->name);
    md(f, c->title);
    fprintf(f, ".\n\nKind: %s. Gate: %s. Tier: %s. ", vkind_name(c->kind), gate_text[c->gate],
            vtier_name(c->tier));
    if (m->ran)
        fprintf(f, "Measured here in the %s configuration: %s (%zu checks, %.0f s wall, %.0f s "
                   "CPU).",
                run_config(m), case_result(m, r, first, end), end - first, m->wall_s, m->cpu_s);
    else
        fprintf(f, "Not run for this page (%s): run it with `spall validate %s` (Release build); "
                   "its last recorded measurements are in "
                   "[notes/validation-log.md](notes/validation-log.md).",
                c->tier == VTIER_FULL_ONLY ? "full tier only" : "not selected", c->name);
    /* the full tier in the same paragraph: the page stays short (issue 19) */
    fputs(c->full_note ? "" : "\n", f);
    if (c->full_note) {
        fputs(" Full tier (`--full`): ", f);
        md(f, c->full_note);
        if (c->full_wall_s > 0.0)
            fprintf(f, " Last recorded wall time of the full configuration: %.0f min (shared "
                       "machine, an upper bound).", c->full_wall_s / 60.0);
        fputs("\n", f);
    }
    if (c->status) {
        fputs("\nStatus: ", f);
        md(f, c->status);
        fputs("\n", f);
    }
    if (m->error[0]) {
        fputs("\nThe case stopped with an error: ", f);
        md(f, m->error);
        fputs("\n", f);
    }
    if (end > first) {
        fputs("\n", f);
        md_case_table(f, r, first, end);
        md_case_notes(f, r, first, end);
    }
}

/* the tiers, this run's wall time and load, and the estimate of --full */
static void md_tiers(FILE *f, const struct vmd_case *m, const struct vcase *cases, size_t n,
                     const struct vmd_run *run)
{
    fprintf(f, "Tiers: `spall validate --quick` is the ctest gate (reduced configurations); "
               "`spall validate` is the standard tier, every case at its working resolution, "
               "each meant to take at most 3 min on 2 cores, with the same references and "
               "tolerances as the full run (a check that misses its reference only at the "
               "standard resolution is a known gap of that tier, with the cause); "
               "`spall validate --full` adds the convergence studies and the largest "
               "resolutions. A case whose standard value differs from its full value gives "
               "both: the table shows the standard run, \"Full tier\" the last full values "
               "with their resolution.\n\n");
    int any_quick = 0, any_full = 0;
    size_t n_ran = 0;
    double full_est = 0.0;
    size_t n_unknown = 0;
    for (size_t k = 0; k < n; k++) {
        n_ran += m[k].ran != 0;
        any_quick |= m[k].ran && m[k].quick;
        any_full |= m[k].ran && m[k].full;
        if (cases[k].full_wall_s > 0.0)
            full_est += cases[k].full_wall_s;
        else if (m[k].ran && !m[k].quick && (m[k].full || cases[k].tier == VTIER_ALL))
            full_est += m[k].cpu_s; /* the wall time of an idle machine, one thread */
        else
            n_unknown++;
    }
    /* a reduced standard-tier case runs its quick configuration: the CLI
     * names the run, the configurations alone cannot */
    const char *cfg = run->what ? run->what
                      : any_quick ? "the gate (`--quick`)"
                      : any_full  ? "the full tier"
                                  : "the standard tier";
    fprintf(f, "This run: %s, %zu cases, **%.1f min wall** (%.0f s; %.0f s CPU)", cfg, n_ran,
            run->wall_s / 60.0, run->wall_s, run->cpu_s);
    if (run->n_done < run->n_selected)
        fprintf(f, " so far: **in progress, %zu of the %zu selected cases done** when this page "
                   "was written",
                run->n_done, run->n_selected);
    if (run->load[0] >= 0.0 && run->load[1] >= 0.0)
        fprintf(f, ", 1-min load average %.2f at the start and %.2f at the end", run->load[0],
                run->load[1]);
    if (run->threads > 0)
        fprintf(f, ", OMP_NUM_THREADS=%d", run->threads);
    fprintf(f, ". Wall times are measured on the machine that generated this page; on a "
               "shared machine they are upper bounds.\n\n");
    if (!any_full)
        fprintf(f, "The full tier (`--full`) was not run end to end for this page. Estimate "
                   "(not a measurement): %.1f h, the sum of the last recorded full wall times "
                   "of the registry (measured on the shared machine) and of this run's CPU "
                   "times for the cases whose full run is their standard run%s.\n\n",
                full_est / 3600.0, n_unknown ? " (cases with no recorded time are left out)"
                                             : "");
}

int vreport_write_markdown(const struct vreport *r, const struct vmd_case *md_cases, size_t n,
                           const struct vmd_run *run, const char *path, const char *command,
                           struct spall_error *err)
{
    size_t n_reg = 0;
    const struct vcase *cases = validation_cases(&n_reg);
    if (n != n_reg)
        return spall_error_set(err, SPALL_ERR_INTERNAL,
                               "markdown: %zu case descriptions for %zu registered cases", n,
                               n_reg);
    FILE *f = fopen(path, "w");
    if (!f)
        return spall_error_set(err, SPALL_ERR_IO, "cannot write '%s': %s", path, strerror(errno));
    size_t n_ran = 0, pass = 0;
    for (size_t k = 0; k < n; k++)
        n_ran += md_cases[k].ran != 0;
    for (size_t k = 0; k < r->n; k++)
        pass += r->checks[k].pass;
    fprintf(f,
            "# Validation reference\n\n"
            "> Generated by `%s` (spall %s, git %s) from the case registry "
            "(validation/cases.c) and the checks the cases record. Do not edit this file: "
            "change the case and regenerate it with a Release build.\n\n",
            command, SPALL_VERSION, SPALL_GIT_REV);
    fprintf(f,
            "Every built-in case of `spall validate` has a section below: what it checks, its "
            "kind (validation: an experiment or an independent published / FE result; "
            "verification: an exact or analytical solution of the model's own equations; "
            "regression: numbers of our own library), and each check's reference, measured "
            "value, error, tolerance, result and source, with the reason for the tolerance or "
            "the cause of a known gap. A known gap counts as a failure of `spall validate`; the "
            "gate (`spall validate --quick`, ctest `validation_*`) accepts it by name only. "
            "The dated investigations behind the cases are in "
            "[notes/validation-log.md](notes/validation-log.md).\n\n");
    md_tiers(f, md_cases, cases, n, run);
    fprintf(f, "%zu of %zu cases measured here, %zu checks: %zu pass, %zu fail.\n\n", n_ran, n,
            r->n, pass, r->n - pass);
    fprintf(f, "| case | kind | gate | tier | checks | wall (CPU) [s] | result |\n"
               "|---|---|---|---|---|---|---|\n");
    for (size_t k = 0; k < n; k++) {
        size_t first, end;
        case_checks(r, cases[k].name, &first, &end);
        char n_checks[24] = "-", wall[48] = "-";
        if (md_cases[k].ran) {
            snprintf(n_checks, sizeof n_checks, "%zu", end - first);
            snprintf(wall, sizeof wall, "%.1f (%.1f)", md_cases[k].wall_s, md_cases[k].cpu_s);
        }
        fprintf(f, "| [%s](#%s) | %s | %s | %s | %s | %s | %s%s |\n", cases[k].name,
                cases[k].name, vkind_name(cases[k].kind), gate_text[cases[k].gate],
                vtier_name(cases[k].tier), n_checks, wall,
                case_result(&md_cases[k], r, first, end), cases[k].status ? " (see status)" : "");
    }
    fprintf(f, "\n## Cases\n");
    for (size_t k = 0; k < n; k++)
        md_case(f, r, &cases[k], &md_cases[k]);
    if (fclose(f) != 0)
        return spall_error_set(err, SPALL_ERR_IO, "cannot write '%s'", path);
    return SPALL_OK;
}
