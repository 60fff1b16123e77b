/**
 * @file tiers.c
 * @brief The tiers of `spall validate`: which cases a run selects and in
 *        which configuration (--quick: the ctest gate; no flag: the standard
 *        tier, every case at its working resolution; --full: everything),
 *        and the clocks behind the per-case wall times of the report.
 */
#define _POSIX_C_SOURCE 200809L

#include "validation/validation.h"

#include <stdio.h>
#include <time.h>

const char *vtier_name(enum vtier tier)
{
    switch (tier) {
    case VTIER_REDUCED:
        return "standard (reduced)";
    case VTIER_FULL_ONLY:
        return "full only";
    case VTIER_ALL:
        break;
    }
    return "standard";
}

bool vtier_selected(const struct vcase *c, bool named, bool quick, bool full)
{
    if (named || full)
        return true;
    if (quick)
        return c->gate != VGATE_OFF;
    return c->tier != VTIER_FULL_ONLY;
}

void vreport_begin_tier(struct vreport *r, const struct vcase *c, bool named, bool quick,
                        bool full)
{
    vreport_begin_case(r, c, quick && !named);
    if (quick && named)
        r->quick = 1; /* a named case under --quick: its reduced configuration */
    else if (!quick)
        r->quick = !full && c->tier == VTIER_REDUCED;
    /* a named full-only case has no smaller configuration: it runs complete */
    r->full = !r->quick && (full || c->tier == VTIER_FULL_ONLY);
}

double vclock_wall(void)
{
    struct timespec ts;
    if (clock_gettime(CLOCK_MONOTONIC, &ts) != 0)
        return 0.0;
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

double vclock_cpu(void)
{
    struct timespec ts;
    if (clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts) != 0)
        return 0.0;
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

double vclock_load(void)
{
    /* Linux only; elsewhere the report says "unknown" */
    FILE *f = fopen("/proc/loadavg", "r");
    if (!f)
        return -1.0;
    double l1 = -1.0;
    if (fscanf(f, "%lf", &l1) != 1)
        l1 = -1.0;
    fclose(f);
    return l1;
}
