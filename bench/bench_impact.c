/**
 * @file bench_impact.c
 * @brief Punch-shear throughput (issue 3, item 7): the impact-punch case's
 *        deck (3D FCC vinyl ester plate, ~10 000 particles, no-slip plunger),
 *        200 steps (20 at reduced scale), no output; and the impact-spall
 *        deck with and without the particle contact (its price).
 */
#include "bench/bench.h"

#include "core/particles.h"
#include "core/sim.h"
#include "io/deck.h"
#include "io/deck_build.h"
#include "core/model.h"
#include "spall/error.h"
#include "validation/impact_cases.h"

#include <omp.h>
#include <stdio.h>
#include <string.h>

static int bench_punch(int threads, double scale, struct bench_result *out,
                       struct spall_error *err)
{
    char yaml[3072];
    /* scale < 1: a coarser lattice (fewer particles), fewer steps */
    double r0 = scale < 1.0 ? 4.0e-3 : 2.5e-3;
    if (impact_punch_deck(yaml, sizeof yaml, r0, "no_slip", 1.0))
        return spall_error_set(err, SPALL_ERR_INTERNAL, "bench impact-punch: deck too long");
    int rc = bench_run_deck("impact-punch", yaml, threads, scale < 1.0 ? 20 : 200, out, err);
    if (rc)
        return rc;
    snprintf(out->note, sizeof out->note,
             "3D FCC r0 = %.1f mm, plunger no-slip contact + clamps; serial contact loop",
             r0 * 1e3);
    return rc;
}

/* Flyer-plate spall (impact-spall's deck, long flyer): two lattice bodies
 * touching through the particle contact; @p with_contact 0 drops the
 * `contact:` line (the flyer then passes through) to price the contact. */
static int bench_spall_common(int threads, double scale, int with_contact,
                              struct bench_result *out, struct spall_error *err)
{
    char yaml[2048];
    double r0 = scale < 1.0 ? 0.4e-3 : 0.2e-3;
    if (impact_spall_deck(yaml, sizeof yaml, 0.052, r0, 1.0, 0.02))
        return spall_error_set(err, SPALL_ERR_INTERNAL, "bench impact-spall: deck too long");
    if (!with_contact) {
        char *a = strstr(yaml, "contact:");
        char *b = a ? strchr(a, '\n') : NULL;
        if (!b)
            return spall_error_set(err, SPALL_ERR_INTERNAL, "bench impact-spall: no contact line");
        memmove(a, b + 1, strlen(b + 1) + 1);
    }
    int rc = bench_run_deck(with_contact ? "impact-spall" : "impact-spall-nocontact", yaml,
                            threads, scale < 1.0 ? 20 : 200, out, err);
    if (rc)
        return rc;
    snprintf(out->note, sizeof out->note, "2D triangular r0 = %.1f mm, %s", r0 * 1e3,
             with_contact ? "flyer-target particle contact (Verlet lists)"
                          : "same deck without contact: the lattice alone");
    return rc;
}

static int bench_spall(int threads, double scale, struct bench_result *out,
                       struct spall_error *err)
{
    return bench_spall_common(threads, scale, 1, out, err);
}

static int bench_spall_nocontact(int threads, double scale, struct bench_result *out,
                                 struct spall_error *err)
{
    return bench_spall_common(threads, scale, 0, out, err);
}

const struct bench_case bench_impact_cases[] = {
    {"impact-punch", "punch-shear plate ([Wang2010] sec. 3.2.3), 3D FCC, rigid plunger",
     bench_punch},
    {"impact-spall", "flyer-plate spall ([Wang2010] sec. 4.2), two bodies + particle contact",
     bench_spall},
    {"impact-spall-nocontact", "the impact-spall deck without contact (prices the contact)",
     bench_spall_nocontact},
};
const size_t bench_impact_n_cases = sizeof bench_impact_cases / sizeof bench_impact_cases[0];
