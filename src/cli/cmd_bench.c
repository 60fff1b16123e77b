#include "cli/cli.h"

#include "bench/bench.h"
#include "core/parallel/comm.h"
#include "spall/error.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static void bench_usage(FILE *out)
{
    fprintf(out, "usage: spall bench [CASE ...] [--list] [--threads N[,M...]] [--scale S]\n"
                 "                   [--json FILE]\n"
                 "\n"
                 "Throughput benchmarks: particle-steps/s, bond-steps/s (bonds counted once)\n"
                 "and resident memory per particle.  Default threads: 1 and 2.\n"
                 "--scale S in (0, 16] multiplies the problem size (particle count; the\n"
                 "spacing of the lattice cases shrinks as S^(-1/dim)): S < 1 for quick\n"
                 "runs, S > 1 for resolution studies of the cases run to rest.\n"
                 "Under mpirun (mpirun -np N spall bench lattice2d pd3d) the cases whose\n"
                 "model runs distributed are partitioned as in spall run; the rates are the\n"
                 "whole run's (slowest rank's time), with the halo's bytes and seconds per\n"
                 "step and the memory per particle held, ghosts included (docs/parallel.md).\n");
}

int cli_bench(int argc, char **argv)
{
    size_t n_cases = bench_case_count();
    const char *json = NULL;
    int threads[8] = {1, 2};
    int n_threads = 2;
    double scale = 1.0;
    const char *wanted[32];
    size_t n_wanted = 0;
    for (int k = 1; k < argc; k++) {
        const char *a = argv[k];
        if (strcmp(a, "-h") == 0 || strcmp(a, "--help") == 0) {
            bench_usage(stdout);
            return 0;
        } else if (strcmp(a, "--list") == 0) {
            for (size_t c = 0; c < n_cases; c++)
                printf("%-16s %s\n", bench_case_at(c)->name, bench_case_at(c)->title);
            return 0;
        } else if (strcmp(a, "--json") == 0 && k + 1 < argc) {
            json = argv[++k];
        } else if (strcmp(a, "--scale") == 0 && k + 1 < argc) {
            scale = strtod(argv[++k], NULL);
            if (!(scale > 0.0 && scale <= 16.0)) {
                fprintf(stderr, "spall bench: --scale needs a number in (0, 16]\n");
                return 2;
            }
        } else if (strcmp(a, "--threads") == 0 && k + 1 < argc) {
            n_threads = 0;
            char *s = argv[++k];
            while (*s && n_threads < 8) {
                char *end = NULL;
                long t = strtol(s, &end, 10);
                if (t <= 0 || end == s) {
                    fprintf(stderr, "spall bench: --threads needs positive integers like 1,2\n");
                    return 2;
                }
                threads[n_threads++] = (int)t;
                s = *end == ',' ? end + 1 : end;
            }
        } else if (a[0] == '-') {
            fprintf(stderr, "spall bench: unknown or incomplete option '%s' (see --help)\n", a);
            return 2;
        } else {
            size_t c = 0;
            while (c < n_cases && strcmp(bench_case_at(c)->name, a) != 0)
                c++;
            if (c == n_cases) {
                /* names typed on the command line use hyphens (like validation
                 * cases and options); the old underscore names name the new */
                char alt[64];
                snprintf(alt, sizeof alt, "%s", a);
                for (char *q = alt; *q; q++)
                    *q = *q == '_' ? '-' : *q;
                size_t old = 0;
                while (old < n_cases && strcmp(bench_case_at(old)->name, alt) != 0)
                    old++;
                if (old < n_cases && strcmp(alt, a) != 0)
                    fprintf(stderr, "spall bench: case '%s' is now called '%s' (case names "
                                    "are written with hyphens)\n",
                            a, alt);
                else
                    fprintf(stderr, "spall bench: unknown case '%s' (see spall bench --list)\n",
                            a);
                return 2;
            }
            if (n_wanted < 32)
                wanted[n_wanted++] = a;
        }
    }
    /* under mpirun rank 0 alone prints and writes the JSON */
    if (par_size() > 1 && par_rank() != 0) {
        json = NULL;
        if (!freopen("/dev/null", "w", stdout) || !freopen("/dev/null", "w", stderr))
            return 4;
    }
    FILE *jf = NULL;
    if (json && !(jf = fopen(json, "w"))) {
        fprintf(stderr, "spall bench: cannot write '%s'\n", json);
        return 4;
    }
    if (jf)
        fprintf(jf, "[\n");
    int first = 1, status = 0;
    printf("%-12s %7s %10s %10s %6s %9s %14s %14s %10s\n", "case", "threads", "particles", "bonds",
           "steps", "seconds", "particle-st/s", "bond-steps/s", "B/particle");
    for (size_t c = 0; c < n_cases; c++) {
        int sel = n_wanted == 0;
        for (size_t w = 0; w < n_wanted; w++)
            sel |= strcmp(wanted[w], bench_case_at(c)->name) == 0;
        if (!sel)
            continue;
        for (int t = 0; t < n_threads; t++) {
            struct bench_result r;
            memset(&r, 0, sizeof r);
            struct spall_error err = {0};
            int rc = bench_case_at(c)->run(threads[t], scale, &r, &err);
            if (rc) {
                fprintf(stderr, "spall bench: %s: %s\n", bench_case_at(c)->name, err.msg);
                status = cli_exit_status(rc);
                continue;
            }
            printf("%-12s %7d %10zu %10zu %6ld %9.3f %14.4g %14.4g %10.1f\n", r.name, r.threads,
                   r.particles, r.bonds, r.steps, r.seconds, r.particle_steps_per_s,
                   r.bond_steps_per_s, r.bytes_per_particle);
            if (r.ranks > 1)
                printf("    mpi: %d ranks x %d threads; %zu ghosts (%.2f %% of the particles); "
                       "halo %.4g bytes/step, %.3g s/step (slowest rank); %.1f B/particle held "
                       "after the partition, %.1f B/particle while building the whole body\n",
                       r.ranks, r.threads, r.ghosts,
                       100.0 * (double)r.ghosts / (double)(r.particles ? r.particles : 1),
                       r.halo_bytes_per_step, r.halo_seconds_per_step, r.bytes_per_particle,
                       r.setup_bytes_per_particle);
            if (r.note[0])
                printf("    %s\n", r.note);
            fflush(stdout);
            if (jf) {
                fprintf(jf,
                        "%s  {\"case\": \"%s\", \"threads\": %d, \"particles\": %zu, \"bonds\": %zu, "
                        "\"steps\": %ld, \"seconds\": %.6g, \"cpu_seconds\": %.6g, "
                        "\"particle_steps_per_s\": %.6g, "
                        "\"bond_steps_per_s\": %.6g, \"bytes_per_particle\": %.1f, "
                        "\"ranks\": %d, \"ghosts\": %zu, \"halo_bytes_per_step\": %.6g, "
                        "\"halo_seconds_per_step\": %.6g, \"setup_bytes_per_particle\": %.1f}",
                        first ? "" : ",\n", r.name, r.threads, r.particles, r.bonds, r.steps,
                        r.seconds, r.cpu_seconds, r.particle_steps_per_s, r.bond_steps_per_s,
                        r.bytes_per_particle, r.ranks, r.ghosts, r.halo_bytes_per_step,
                        r.halo_seconds_per_step, r.setup_bytes_per_particle);
                first = 0;
            }
        }
    }
    if (jf) {
        fprintf(jf, "\n]\n");
        fclose(jf);
    }
    par_bcast(&status, sizeof status, 0); /* one exit status on every rank */
    return status;
}
