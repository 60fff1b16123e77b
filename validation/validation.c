#include "validation/validation.h"

#include "spall/error.h"

#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

int vreport_check(struct vreport *r, const char *quantity, const char *unit, double reference,
                  double measured, double tolerance, bool relative, const char *source,
                  const char *note, struct spall_error *err)
{
    if (r->n == r->cap) {
        size_t cap = r->cap * 2 + 16;
        struct vcheck *c = realloc(r->checks, cap * sizeof *c);
        if (!c)
            return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory in validation report");
        r->checks = c;
        r->cap = cap;
    }
    struct vcheck *c = &r->checks[r->n++];
    memset(c, 0, sizeof *c);
    snprintf(c->case_name, sizeof c->case_name, "%s", r->current_case ? r->current_case : "");
    snprintf(c->quantity, sizeof c->quantity, "%s", quantity);
    snprintf(c->unit, sizeof c->unit, "%s", unit ? unit : "");
    snprintf(c->source, sizeof c->source, "%s", source ? source : "");
    snprintf(c->note, sizeof c->note, "%s", note ? note : "");
    c->reference = reference;
    c->measured = measured;
    c->tolerance = tolerance;
    c->relative = relative;
    c->kind = r->current_kind;
    double e = fabs(measured - reference);
    if (relative)
        e = reference != 0.0 ? e / fabs(reference) : e;
    c->pass = isfinite(measured) && e <= tolerance;
    return SPALL_OK;
}

int vreport_check_true(struct vreport *r, const char *quantity, bool ok, const char *source,
                       const char *note, struct spall_error *err)
{
    return vreport_check(r, quantity, "yes=1", 1.0, ok ? 1.0 : 0.0, 0.0, false, source, note, err);
}

const char *vkind_name(enum vkind kind)
{
    switch (kind) {
    case VKIND_VERIFICATION:
        return "verification";
    case VKIND_REGRESSION:
        return "regression";
    case VKIND_VALIDATION:
        break;
    }
    return "validation";
}

void vreport_set_kind(struct vreport *r, enum vkind kind)
{
    if (r->n > 0)
        r->checks[r->n - 1].kind = kind;
}

void vreport_begin_case(struct vreport *r, const struct vcase *c, bool gate_run)
{
    r->current_case = c->name;
    r->current_kind = c->kind;
    if (gate_run)
        r->quick = c->gate == VGATE_QUICK;
}

void vreport_mark_gap(struct vreport *r, const char *note)
{
    if (r->n == 0)
        return;
    struct vcheck *c = &r->checks[r->n - 1];
    c->known_gap = !c->pass;
    if (note)
        snprintf(c->note, sizeof c->note, "%s", note);
}

void vreport_info(struct vreport *r, const char *fmt, ...)
{
    if (!r->log)
        return;
    va_list ap;
    va_start(ap, fmt);
    fprintf(r->log, "  [%s] ", r->current_case ? r->current_case : "");
    vfprintf(r->log, fmt, ap);
    fprintf(r->log, "\n");
    va_end(ap);
}

int vreport_series(struct vreport *r, const char *plot, const char *xlabel, const char *ylabel,
                   const char *label, enum vseries_kind kind, const double *x, const double *y,
                   size_t n, struct spall_error *err)
{
    if (!r->keep_series)
        return SPALL_OK;
    if (r->n_series == r->cap_series) {
        size_t cap = r->cap_series * 2 + 8;
        struct vseries *t = realloc(r->series, cap * sizeof *t);
        if (!t)
            return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory in validation report");
        r->series = t;
        r->cap_series = cap;
    }
    const size_t max_pts = 2000;
    size_t stride = n > max_pts ? (n + max_pts - 1) / max_pts : 1;
    size_t m = n ? (n - 1) / stride + 1 : 0;
    double *cx = malloc((m ? m : 1) * sizeof *cx), *cy = malloc((m ? m : 1) * sizeof *cy);
    if (!cx || !cy) {
        free(cx);
        free(cy);
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory in validation report");
    }
    for (size_t k = 0; k < m; k++) {
        cx[k] = x[k * stride];
        cy[k] = y[k * stride];
    }
    struct vseries *sr = &r->series[r->n_series++];
    memset(sr, 0, sizeof *sr);
    snprintf(sr->case_name, sizeof sr->case_name, "%s", r->current_case ? r->current_case : "");
    snprintf(sr->plot, sizeof sr->plot, "%s", plot ? plot : "");
    snprintf(sr->xlabel, sizeof sr->xlabel, "%s", xlabel ? xlabel : "");
    snprintf(sr->ylabel, sizeof sr->ylabel, "%s", ylabel ? ylabel : "");
    snprintf(sr->label, sizeof sr->label, "%s", label ? label : "");
    sr->kind = kind;
    sr->x = cx;
    sr->y = cy;
    sr->n = m;
    return SPALL_OK;
}

int vreport_marker(struct vreport *r, const char *plot, const char *label, enum vseries_kind kind,
                   double value, struct spall_error *err)
{
    return vreport_series(r, plot, NULL, NULL, label, kind, &value, &value, 1, err);
}

void vreport_free(struct vreport *r)
{
    for (size_t k = 0; k < r->n_series; k++) {
        free(r->series[k].x);
        free(r->series[k].y);
    }
    free(r->series);
    r->series = NULL;
    r->n_series = r->cap_series = 0;
    free(r->checks);
    r->checks = NULL;
    r->n = r->cap = 0;
}
