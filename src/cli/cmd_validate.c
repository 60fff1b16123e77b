#include "cli/cli.h"

#include "core/parallel/comm.h"
#include "core/parallel/gather.h"
#include "spall/error.h"
#include "validation/validation.h"
#include "validation/vpar.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static void validate_usage(FILE *out)
{
    fprintf(out, "usage: spall validate [CASE ...] [--list] [--quick | --full] [--json FILE]\n"
                 "                      [--report DIR] [--markdown FILE]\n"
                 "\n"
                 "Runs the built-in validation cases and prints, per case and quantity:\n"
                 "reference, measured, error, tolerance and PASS/FAIL (GAP marks a documented,\n"
                 "known gap, which also counts as a failure), and each case's wall time.\n"
                 "Exit status 1 on any failure.  Without --quick or --full: the standard\n"
                 "tier, every case at its working resolution (each <= 3 min on 2 cores;\n"
                 "the convergence studies and largest resolutions are left to --full).\n"
                 "  --list        list the cases and their tiers\n"
                 "  --quick       the gate of the test suite: every case with a fast\n"
                 "                configuration, in that configuration (named cases: their\n"
                 "                reduced configuration)\n"
                 "  --full        every case complete: convergence studies, largest\n"
                 "                resolutions (hours)\n"
                 "  --json FILE   also write the results and per-case wall times as JSON\n"
                 "  --report DIR  also write DIR/report.md with the table and PNG plots of\n"
                 "                each case's time histories against the references\n"
                 "  --markdown FILE\n"
                 "                also write FILE, the validation reference (docs/validation.md):\n"
                 "                one section per registered case with its checks and wall\n"
                 "                time; the cases outside the run get their registry entry only\n"
                 "Under mpirun the cases whose model runs distributed run on every rank with\n"
                 "the numbers of one rank; the others run on rank 0 with a 'serial:' note\n"
                 "(docs/parallel.md).\n");
}

static void json_string(FILE *f, const char *s)
{
    fputc('"', f);
    for (; *s; s++) {
        if (*s == '"' || *s == '\\')
            fprintf(f, "\\%c", *s);
        else if ((unsigned char)*s < 0x20)
            fprintf(f, "\\u%04x", (unsigned char)*s);
        else
            fputc(*s, f);
    }
    fputc('"', f);
}

static void json_number(FILE *f, double x)
{
    if (isfinite(x))
        fprintf(f, "%.10g", x);
    else
        fprintf(f, "null");
}

static double check_error(const struct vcheck *c)
{
    double e = fabs(c->measured - c->reference);
    if (c->relative && c->reference != 0.0)
        e /= fabs(c->reference);
    return e;
}

static int write_json(const char *path, const struct vreport *r, const struct vcase *cases,
                      const struct vmd_case *md, size_t n_cases)
{
    FILE *f = fopen(path, "w");
    if (!f)
        return -1;
    fprintf(f, "{\n  \"checks\": [\n");
    for (size_t k = 0; k < r->n; k++) {
        const struct vcheck *c = &r->checks[k];
        fprintf(f, "    {\"case\": ");
        json_string(f, c->case_name);
        fprintf(f, ", \"quantity\": ");
        json_string(f, c->quantity);
        fprintf(f, ", \"unit\": ");
        json_string(f, c->unit);
        fprintf(f, ", \"reference\": ");
        json_number(f, c->reference);
        fprintf(f, ", \"measured\": ");
        json_number(f, c->measured);
        fprintf(f, ", \"error\": ");
        json_number(f, check_error(c));
        fprintf(f, ", \"tolerance\": ");
        json_number(f, c->tolerance);
        fprintf(f, ", \"kind\": \"%s\"", vkind_name(c->kind));
        fprintf(f, ", \"relative\": %s, \"pass\": %s, \"known_gap\": %s, \"source\": ",
                c->relative ? "true" : "false", c->pass ? "true" : "false",
                c->known_gap ? "true" : "false");
        json_string(f, c->source);
        fprintf(f, ", \"note\": ");
        json_string(f, c->note);
        fprintf(f, "}%s\n", k + 1 < r->n ? "," : "");
    }
    fprintf(f, "  ],\n  \"cases\": [");
    const char *sep = "\n";
    for (size_t c = 0; c < n_cases; c++) {
        if (!md[c].ran)
            continue;
        fprintf(f, "%s    {\"case\": ", sep);
        json_string(f, cases[c].name);
        fprintf(f, ", \"tier\": \"%s\", \"config\": \"%s\", \"wall_s\": ",
                vtier_name(cases[c].tier),
                md[c].quick ? "quick" : md[c].full ? "full" : "standard");
        json_number(f, md[c].wall_s);
        fprintf(f, ", \"cpu_s\": ");
        json_number(f, md[c].cpu_s);
        fprintf(f, "}");
        sep = ",\n";
    }
    fprintf(f, "\n  ]\n}\n");
    return fclose(f);
}

static void print_check(const struct vcheck *c)
{
    char tol[48];
    if (c->relative)
        snprintf(tol, sizeof tol, "%.3g %%", 100.0 * c->tolerance);
    else
        snprintf(tol, sizeof tol, "%.3g %s", c->tolerance, c->unit);
    char errs[48];
    if (c->relative)
        snprintf(errs, sizeof errs, "%.3g %%", 100.0 * check_error(c));
    else
        snprintf(errs, sizeof errs, "%.3g", check_error(c));
    printf("  %-44s %-9s ref %-12.6g meas %-12.6g err %-10s tol %-10s %-12s %s\n", c->quantity,
           c->unit, c->reference, c->measured, errs, tol, vkind_name(c->kind),
           c->pass ? "PASS" : (c->known_gap ? "FAIL (known gap)" : "FAIL"));
    if (c->source[0])
        printf("      source: %s\n", c->source);
    if (c->note[0] && (!c->pass || c->known_gap))
        printf("      note: %s\n", c->note);
}

/* whether this run selects case @p c; *named: the user named it */
static bool run_case(const struct vcase *c, const char *const *wanted, size_t n_wanted, int quick,
                     int full, bool *named)
{
    bool nm = false;
    for (size_t w = 0; w < n_wanted; w++)
        nm |= strcmp(wanted[w], c->name) == 0;
    if (named)
        *named = nm;
    return n_wanted ? nm : vtier_selected(c, false, quick, full);
}

int cli_validate(int argc, char **argv)
{
    size_t n_cases = 0;
    const struct vcase *cases = validation_cases(&n_cases);
    int list = 0, quick = 0, full = 0;
    const char *json = NULL, *report = NULL, *markdown = NULL;
    const char *wanted[64];
    size_t n_wanted = 0;
    for (int k = 1; k < argc; k++) {
        const char *a = argv[k];
        if (strcmp(a, "-h") == 0 || strcmp(a, "--help") == 0) {
            validate_usage(stdout);
            return 0;
        } else if (strcmp(a, "--list") == 0) {
            list = 1;
        } else if (strcmp(a, "--quick") == 0) {
            quick = 1;
        } else if (strcmp(a, "--full") == 0) {
            full = 1;
        } else if (strcmp(a, "--json") == 0) {
            if (++k >= argc) {
                fprintf(stderr, "spall validate: --json needs a file name\n");
                return 2;
            }
            json = argv[k];
        } else if (strcmp(a, "--report") == 0) {
            if (++k >= argc) {
                fprintf(stderr, "spall validate: --report needs a directory\n");
                return 2;
            }
            report = argv[k];
        } else if (strcmp(a, "--markdown") == 0) {
            if (++k >= argc) {
                fprintf(stderr, "spall validate: --markdown needs a file name\n");
                return 2;
            }
            markdown = argv[k];
        } else if (a[0] == '-') {
            fprintf(stderr, "spall validate: unknown option '%s' (see --help)\n", a);
            return 2;
        } else {
            size_t c = 0;
            while (c < n_cases && strcmp(cases[c].name, a) != 0)
                c++;
            if (c == n_cases) {
                fprintf(stderr, "spall validate: unknown case '%s' (see spall validate --list)\n",
                        a);
                return 2;
            }
            if (n_wanted < 64)
                wanted[n_wanted++] = a;
        }
    }
    if (quick && full) {
        fprintf(stderr, "spall validate: --quick and --full exclude each other\n");
        return 2;
    }
    if (list) {
        static const char *const gate[] = {"", "  [quick]", "  [quick: full]"};
        static const char *const tier[] = {"", "  [standard: reduced]", "  [full only]"};
        for (size_t c = 0; c < n_cases; c++) {
            printf("%-28s %-12s %s%s%s\n", cases[c].name, vkind_name(cases[c].kind),
                   cases[c].title, gate[cases[c].gate], tier[cases[c].tier]);
            if (cases[c].status)
                printf("%-28s %-12s status: %s\n", "", "", cases[c].status);
        }
        return 0;
    }
    /* what the Markdown reference says about each registered case */
    struct vmd_case *md = calloc(n_cases, sizeof *md);
    if (!md) {
        fprintf(stderr, "spall validate: out of memory\n");
        return 4;
    }
    /* under mpirun rank 0 alone prints and writes files (validation/vpar.h) */
    struct vpar vp;
    memset(&vp, 0, sizeof vp);
    if (par_size() > 1 && par_rank() != 0 && !freopen("/dev/null", "w", stdout)) {
        free(md);
        return 4;
    }
    struct vreport rep = {0};
    rep.par = par_size() > 1 ? &vp : NULL;
    rep.log = stdout;
    rep.quick = quick;
    rep.keep_series = report != NULL;
    int failed_to_run = 0;
    const char *omp = getenv("OMP_NUM_THREADS");
    struct vmd_run run = {.load = {vclock_load(), -1.0}, .threads = omp ? atoi(omp) : 0};
    run.what = n_wanted ? "named cases"
               : quick  ? "the gate (`--quick`)"
               : full   ? "the full tier (`--full`)"
                        : "the standard tier";
    double t_run = vclock_wall(), cpu_run = vclock_cpu();
    char command[512] = "spall validate";
    for (int k = 1; k < argc; k++) {
        size_t len = strlen(command);
        snprintf(command + len, sizeof command - len, " %s", argv[k]);
    }
    for (size_t c = 0; c < n_cases; c++)
        run.n_selected += run_case(&cases[c], wanted, n_wanted, quick, full, NULL);
    for (size_t c = 0; c < n_cases; c++) {
        bool named = false;
        if (!run_case(&cases[c], wanted, n_wanted, quick, full, &named))
            continue;
        vreport_begin_tier(&rep, &cases[c], named, quick, full);
        md[c].quick = rep.quick;
        md[c].full = rep.full;
        printf("== %s: %s (%s)%s\n", cases[c].name, cases[c].title, vkind_name(cases[c].kind),
               rep.quick ? " (quick)" : rep.full ? " (full)" : "");
        if (cases[c].status)
            printf("  status: %s\n", cases[c].status);
        if (rep.par) /* the ranks start each case together; an idle rank sleeps */
            par_barrier_idle();
        if (rep.par && !vpar_begin_case(&rep, &cases[c]))
            continue; /* a serial case: rank 0 runs it */
        fflush(stdout);
        size_t first = rep.n;
        struct spall_error err = {0};
        double t_case = vclock_wall(), cpu_case = vclock_cpu();
        int rc = cases[c].run(&rep, &err);
        if (rc && rep.par && vp.left) /* this rank left a case that went serial */
            rc = SPALL_OK;
        md[c].wall_s = vclock_wall() - t_case;
        md[c].cpu_s = vclock_cpu() - cpu_case;
        if (rc) {
            printf("  ERROR: %s\n", err.msg);
            snprintf(md[c].error, sizeof md[c].error, "%s", err.msg);
            failed_to_run++;
        }
        for (size_t k = first; k < rep.n; k++)
            print_check(&rep.checks[k]);
        printf("  wall: %.1f s, CPU %.1f s\n", md[c].wall_s, md[c].cpu_s);
        fflush(stdout);
        md[c].ran = 1;
        /* a long run keeps its reference page current: the cases done so
         * far, marked in progress (the last write below is the whole run) */
        if (markdown && ++run.n_done < run.n_selected && par_rank() == 0) {
            run.wall_s = vclock_wall() - t_run;
            run.cpu_s = vclock_cpu() - cpu_run;
            run.load[1] = vclock_load();
            struct spall_error perr = {0};
            if (vreport_write_markdown(&rep, md, n_cases, &run, markdown, command, &perr))
                fprintf(stderr, "spall validate: %s\n", perr.msg);
        }
    }
    if (rep.par)
        par_barrier_idle(); /* rank 0 may still run a serial case */
    run.wall_s = vclock_wall() - t_run;
    run.cpu_s = vclock_cpu() - cpu_run;
    run.load[1] = vclock_load();
    size_t pass = 0, fail = 0;
    for (size_t k = 0; k < rep.n; k++)
        rep.checks[k].pass ? pass++ : fail++;
    fail += (size_t)failed_to_run;
    printf("%zu passed, %zu failed, %.1f s wall, %.1f s CPU\n", pass, fail, run.wall_s,
           run.cpu_s);
    int status = fail ? 1 : 0;
    struct spall_error err = {0};
    int rc = SPALL_OK;
    if (par_rank() != 0) /* files and the status are rank 0's */
        json = markdown = report = NULL;
    if (json && write_json(json, &rep, cases, md, n_cases) != 0) {
        fprintf(stderr, "spall validate: cannot write '%s'\n", json);
        status = 4;
    }
    if (status != 4 && markdown) {
        run.n_done = run.n_selected;
        rc = vreport_write_markdown(&rep, md, n_cases, &run, markdown, command, &err);
        if (rc == SPALL_OK)
            printf("markdown: %s\n", markdown);
    }
    if (status != 4 && rc == SPALL_OK && report) {
        rc = vreport_write_report(&rep, report, &err);
        if (rc == SPALL_OK)
            printf("report: %s/report.md\n", report);
    }
    if (rc) {
        fprintf(stderr, "spall: error: %s\n", err.msg);
        status = cli_exit_status(rc);
    }
    vreport_free(&rep);
    free(md);
    par_bcast(&status, sizeof status, 0); /* one exit status on every rank */
    return status;
}
