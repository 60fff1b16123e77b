/**
 * @file validation.h
 * @brief Built-in validation cases (`spall validate`): each case runs the
 *        engine on a benchmark and records checks of the form
 *        reference / measured / error / tolerance / source -> PASS or FAIL.
 *
 * A case that does not reach its reference stays in the suite: its check is
 * recorded with `known_gap` set and the gap explained in `note`; it still
 * counts as FAIL (exit status non-zero) so it can never silently pass.
 */
#ifndef SPALL_VALIDATION_H
#define SPALL_VALIDATION_H

#include <stdbool.h>
#include <stddef.h>
#include <stdio.h>

#include "spall/error.h"

struct spall_error;
struct vpar;

/** What a case (or one of its checks) is compared against, so that the
 *  summary does not count a regression number as evidence of physics. */
enum vkind {
    VKIND_VALIDATION = 0,   /**< an experiment, or an independent published / FE result */
    VKIND_VERIFICATION = 1, /**< an exact or analytical solution of the model's own equations */
    VKIND_REGRESSION = 2    /**< numbers of our own library (reference tables, digest check
                                 values computed from the same formulas) */
};

/** "validation", "verification" or "regression". */
const char *vkind_name(enum vkind kind);

struct vcheck {
    char case_name[48];
    char quantity[96];
    char unit[16];
    double reference;
    double measured;
    double tolerance;  /**< relative (fraction) if relative, else absolute in unit */
    bool relative;
    char source[160];  /**< where the reference comes from */
    char note[320];    /**< why this tolerance; explanation of a gap */
    bool known_gap;
    bool pass;
    enum vkind kind;   /**< the case's kind unless the case overrides it (vreport_set_kind) */
};

/** How a recorded series is drawn in the report's plots. */
enum vseries_kind {
    VSERIES_LINE = 0,   /**< measured curve */
    VSERIES_REF = 1,    /**< reference curve (dashed) */
    VSERIES_POINTS = 2, /**< points (e.g. experimental values) */
    VSERIES_XMARK = 3,  /**< vertical marker at x[0] (e.g. a reference arrival time) */
    VSERIES_YMARK = 4   /**< horizontal marker at y[0] (e.g. a reference level) */
};

/** One series attached to a case for `spall validate --report`; series with
 *  the same (case, plot) share one PNG. */
struct vseries {
    char case_name[48];
    char plot[80];      /**< plot title, unique within the case */
    char xlabel[48], ylabel[48];
    char label[80];     /**< legend / marker label */
    enum vseries_kind kind;
    double *x, *y;      /**< owned copies */
    size_t n;
};

struct vreport {
    struct vcheck *checks;
    size_t n, cap;
    struct vseries *series; /**< only filled when keep_series is set */
    size_t n_series, cap_series;
    int keep_series;        /**< set by `--report`: cases record their time histories */
    FILE *log;         /**< extra lines printed by cases (may be NULL) */
    int quick;         /**< reduced sizes for the test suite */
    int full;          /**< `--full`: also the convergence studies and largest resolutions
                            that a VTIER_REDUCED case leaves out of its standard tier */
    const char *current_case;
    enum vkind current_kind; /**< kind given to the checks recorded next */
    struct vpar *par;  /**< under mpirun: how the current case runs (vpar.h); NULL: one rank */
};

/** Record a check; error = |measured - reference| (/|reference| if relative);
 *  pass = error <= tolerance. */
int vreport_check(struct vreport *r, const char *quantity, const char *unit, double reference,
                  double measured, double tolerance, bool relative, const char *source,
                  const char *note, struct spall_error *err);
/** Record a yes/no check (reference 1, measured 1 or 0). */
int vreport_check_true(struct vreport *r, const char *quantity, bool ok, const char *source,
                       const char *note, struct spall_error *err);
/** Set the kind of the last recorded check (a check of a kind other than its
 *  case's, e.g. one experiment check in a regression case). */
void vreport_set_kind(struct vreport *r, enum vkind kind);
/** Mark the last recorded check as a known, documented gap. */
void vreport_mark_gap(struct vreport *r, const char *note);
/** Informational line (printed under the table). */
void vreport_info(struct vreport *r, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;
/** Attach a series (copied; at most 2000 points kept, evenly strided) to the
 *  current case's plot @p plot.  A no-op unless r->keep_series is set, so
 *  cases may call it unconditionally. */
int vreport_series(struct vreport *r, const char *plot, const char *xlabel, const char *ylabel,
                   const char *label, enum vseries_kind kind, const double *x, const double *y,
                   size_t n, struct spall_error *err);
/** Attach a marker line (VSERIES_XMARK at x = value, VSERIES_YMARK at y = value). */
int vreport_marker(struct vreport *r, const char *plot, const char *label, enum vseries_kind kind,
                   double value, struct spall_error *err);
/** Write DIR/report.md: the table of checks and, per case, one PNG per plot
 *  (DIR/<case>_<k>.png).  DIR is created if missing. */
int vreport_write_report(const struct vreport *r, const char *dir, struct spall_error *err);
void vreport_free(struct vreport *r);

/** How `spall validate --quick` and the ctest gate (tests/test_validation_quick.c)
 *  run a case. */
enum vgate {
    VGATE_OFF = 0,   /**< too slow for the gate: full runs only */
    VGATE_QUICK = 1, /**< the reduced configuration, r->quick = 1 (the case says what it cuts) */
    VGATE_FULL = 2   /**< fast enough as it is: the full configuration, r->quick = 0 */
};

/** What `spall validate` without flags (the standard tier: every case at its
 *  working resolution, each in <= 3 min on 2 cores) runs of a case; `--full`
 *  runs every case completely (r->full = 1). */
enum vtier {
    VTIER_ALL = 0,      /**< the whole case fits the standard tier: --full adds nothing */
    VTIER_REDUCED = 1,  /**< the standard tier runs its reduced configuration (r->quick = 1:
                             the working resolution, no convergence levels); --full runs it
                             complete */
    VTIER_FULL_ONLY = 2 /**< a convergence study, or no configuration of it fits 3 min:
                             --full (or naming the case) only */
};

/** "standard", "standard (reduced)" or "full only". */
const char *vtier_name(enum vtier tier);

struct vcase {
    const char *name;   /**< e.g. "lattice-patch" */
    const char *title;  /**< one line */
    enum vkind kind;    /**< default kind of its checks */
    enum vgate gate;    /**< configuration in `--quick` and the ctest gate */
    /** Maturity where the PASS/FAIL of the checks alone would mislead (e.g. a
     *  pass that holds at one resolution only); NULL if none. */
    const char *status;
    int (*run)(struct vreport *r, struct spall_error *err);
    enum vtier tier;    /**< what the standard tier runs of it */
    /** Last recorded wall time of the full configuration (s; an upper bound,
     *  measured on the shared machine; 0: not recorded or = the standard tier). */
    double full_wall_s;
    /** VTIER_REDUCED / VTIER_FULL_ONLY: what --full adds and its last measured
     *  values with their resolution and date, so that both the standard and the
     *  full values are in the case; NULL for VTIER_ALL. */
    const char *full_note;
};

/** What the Markdown reference (vreport_write_markdown) knows about one
 *  registered case besides the checks it recorded. */
struct vmd_case {
    int ran;        /**< 0: not run, the reference gives its registry entry only */
    int quick;      /**< it ran in its reduced configuration (r->quick) */
    int full;       /**< it ran in its full configuration (r->full) */
    double wall_s;  /**< its wall time in this run, s */
    double cpu_s;   /**< the CPU time of the process (all threads) during it, s */
    char error[SPALL_ERROR_MSG_LEN]; /**< the case stopped with this error ("" if none) */
};

/** What the Markdown reference says about the whole run. */
struct vmd_run {
    double wall_s;     /**< wall time of all the cases run, s */
    double cpu_s;      /**< CPU time of the process (all threads) over them, s */
    double load[2];    /**< 1-min load average at the start and the end (< 0: unknown) */
    int threads;       /**< OMP_NUM_THREADS (0: unset) */
    const char *what;  /**< which run: "the standard tier", "the gate (`--quick`)", ... */
    size_t n_selected; /**< cases the run selected */
    size_t n_done;     /**< of them done when the page was written (< n_selected: in progress) */
};

/** Wall clock for the per-case times, s (monotonic). */
double vclock_wall(void);
/** CPU time of the process, all threads, s (what a loaded machine does not
 *  inflate as it does the wall time). */
double vclock_cpu(void);
/** The 1-minute load average (/proc/loadavg), or -1 where unknown. */
double vclock_load(void);
/** Whether `spall validate` runs case @p c: @p named (the user named it),
 *  @p quick (--quick: the gate), @p full (--full: everything). */
bool vtier_selected(const struct vcase *c, bool named, bool quick, bool full);
/** vreport_begin_case for a selected case, setting r->quick and r->full for
 *  the run's tier (a named VTIER_FULL_ONLY case runs complete). */
void vreport_begin_tier(struct vreport *r, const struct vcase *c, bool named, bool quick,
                        bool full);

/** Write @p path, the validation reference (docs/notes/validation-log.md): a header
 *  naming @p command and the git revision, a summary table and one section
 *  per registered case (@p md[k] describes validation_cases()[k], @p n of
 *  them) with its checks: reference, measured, tolerance, source, note. */
int vreport_write_markdown(const struct vreport *r, const struct vmd_case *md, size_t n,
                           const struct vmd_run *run, const char *path, const char *command,
                           struct spall_error *err);

/** All built-in cases (registry in validation/cases.c). */
const struct vcase *validation_cases(size_t *n);
/** Start recording the checks of case @p c (sets current_case, current_kind
 *  and quick from the case's gate when @p gate_run is set). */
void vreport_begin_case(struct vreport *r, const struct vcase *c, bool gate_run);

#endif
