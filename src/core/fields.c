#include "core/fields.h"

#include "spall/error.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int field_registry_create(struct field_registry **out, struct spall_error *err)
{
    *out = calloc(1, sizeof **out);
    if (!*out)
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory creating field registry");
    return SPALL_OK;
}

void field_registry_destroy(struct field_registry **reg)
{
    if (!reg || !*reg)
        return;
    free((*reg)->fields);
    free(*reg);
    *reg = NULL;
}

int field_registry_add(struct field_registry *reg, const struct field_desc *desc,
                       struct spall_error *err)
{
    if (desc->ncomp < 1 || desc->ncomp > 9)
        return spall_error_set(err, SPALL_ERR_INTERNAL, "field '%s': %d components", desc->name,
                               desc->ncomp);
    if (desc->parity != FIELD_EVEN) {
        /* the reflection negates stored doubles in place; a computed field
         * follows from the state it is computed from */
        const int need = desc->parity == FIELD_VECTOR ? 0 : desc->parity == FIELD_SYMTENSOR ? 6 : 9;
        if (desc->compute || desc->type != FIELD_F64)
            return spall_error_set(err, SPALL_ERR_INTERNAL,
                                   "field '%s': a reflection parity needs a stored double field",
                                   desc->name);
        if (need ? desc->ncomp != need : desc->ncomp > 3)
            return spall_error_set(err, SPALL_ERR_INTERNAL,
                                   "field '%s': %d components do not fit its reflection parity",
                                   desc->name, desc->ncomp);
    }
    if (field_registry_find(reg, desc->name))
        return spall_error_set(err, SPALL_ERR_INTERNAL, "field '%s' registered twice", desc->name);
    if (reg->n == reg->cap) {
        size_t cap = reg->cap * 2 + 8;
        struct field_desc *f = realloc(reg->fields, cap * sizeof *f);
        if (!f)
            return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory registering fields");
        reg->fields = f;
        reg->cap = cap;
    }
    reg->fields[reg->n++] = *desc;
    return SPALL_OK;
}

int field_registry_add_f64(struct field_registry *reg, const char *name, const char *unit,
                           int ncomp, double **comp[], unsigned flags, struct spall_error *err)
{
    return field_registry_add_f64_parity(reg, name, unit, ncomp, comp, flags, FIELD_EVEN, err);
}

int field_registry_add_f64_parity(struct field_registry *reg, const char *name, const char *unit,
                                  int ncomp, double **comp[], unsigned flags,
                                  enum field_parity parity, struct spall_error *err)
{
    struct field_desc d;
    memset(&d, 0, sizeof d);
    strncpy(d.name, name, sizeof d.name - 1);
    strncpy(d.unit, unit, sizeof d.unit - 1);
    d.ncomp = ncomp;
    d.type = FIELD_F64;
    d.flags = flags;
    for (int c = 0; c < ncomp && c < 9; c++)
        d.comp[c] = (void **)comp[c];
    d.parity = parity;
    return field_registry_add(reg, &d, err);
}

int field_registry_add_computed(struct field_registry *reg, const char *name, const char *unit,
                                int ncomp, unsigned flags, field_compute_fn fn, const void *ctx,
                                struct spall_error *err)
{
    struct field_desc d;
    memset(&d, 0, sizeof d);
    snprintf(d.name, sizeof d.name, "%s", name);
    snprintf(d.unit, sizeof d.unit, "%s", unit);
    d.ncomp = ncomp;
    d.type = FIELD_F64;
    d.flags = flags;
    d.compute = fn;
    d.ctx = ctx;
    return field_registry_add(reg, &d, err);
}

const struct field_desc *field_registry_find(const struct field_registry *reg, const char *name)
{
    for (size_t k = 0; k < reg->n; k++)
        if (strcmp(reg->fields[k].name, name) == 0)
            return &reg->fields[k];
    return NULL;
}

void *field_stored_data(const struct field_registry *reg, const char *name, int c)
{
    const struct field_desc *f = field_registry_find(reg, name);
    if (!f || f->compute || c < 0 || c >= f->ncomp || !f->comp[c])
        return NULL;
    return *f->comp[c];
}

unsigned field_parity_planes(enum field_parity par, int c)
{
    /* symmetric storage xx yy zz xy yz xz: the two indices of component c */
    static const int sa[6] = {0, 1, 2, 0, 1, 0}, sb[6] = {0, 1, 2, 1, 2, 2};
    int a, b;
    switch (par) {
    case FIELD_VECTOR: return c >= 0 && c < 3 ? 1u << c : 0u;
    case FIELD_SYMTENSOR:
        if (c < 0 || c >= 6)
            return 0u;
        a = sa[c];
        b = sb[c];
        break;
    case FIELD_TENSOR:
        if (c < 0 || c >= 9)
            return 0u;
        a = c / 3;
        b = c % 3;
        break;
    case FIELD_EVEN:
    default: return 0u;
    }
    /* x_a x_b changes sign when exactly one of a, b is the plane's axis */
    return a == b ? 0u : (1u << a) | (1u << b);
}

double field_reflect_sign(enum field_parity par, int c, unsigned planes)
{
    unsigned odd = field_parity_planes(par, c) & planes, flips = 0;
    for (; odd; odd &= odd - 1)
        flips++;
    return flips & 1u ? -1.0 : 1.0;
}

void field_reflect(const struct field_registry *reg, size_t i, int k)
{
    if (k < 0 || k > 2)
        return;
    for (size_t q = 0; q < reg->n; q++) {
        const struct field_desc *f = &reg->fields[q];
        if (f->parity == FIELD_EVEN)
            continue;
        for (int c = 0; c < f->ncomp; c++)
            if (field_parity_planes(f->parity, c) & (1u << k)) {
                double *a = *(double **)f->comp[c];
                a[i] = -a[i];
            }
    }
}

static double value_as_double(const struct field_desc *f, int c, size_t i)
{
    const void *arr = *f->comp[c];
    switch (f->type) {
    case FIELD_F64: return ((const double *)arr)[i];
    case FIELD_I32: return (double)((const int32_t *)arr)[i];
    case FIELD_I64: return (double)((const int64_t *)arr)[i];
    case FIELD_U8: return (double)((const uint8_t *)arr)[i];
    }
    return 0.0;
}

void field_gather_f64(const struct field_desc *f, size_t n, double *out)
{
    if (f->compute) {
        f->compute(f->ctx, n, out);
        return;
    }
    for (int c = 0; c < f->ncomp; c++)
        for (size_t i = 0; i < n; i++)
            out[i * (size_t)f->ncomp + (size_t)c] = value_as_double(f, c, i);
}

static size_t type_size(enum field_type t)
{
    switch (t) {
    case FIELD_F64: return 8;
    case FIELD_I32: return 4;
    case FIELD_I64: return 8;
    case FIELD_U8: return 1;
    }
    return 8;
}

size_t field_packed_size(const struct field_desc *f)
{
    return f->compute ? 0 : type_size(f->type) * (size_t)f->ncomp;
}

void field_pack(const struct field_desc *f, size_t i, void *buf)
{
    if (f->compute)
        return;
    size_t s = type_size(f->type);
    for (int c = 0; c < f->ncomp; c++)
        memcpy((char *)buf + (size_t)c * s, (const char *)*f->comp[c] + i * s, s);
}

void field_unpack(const struct field_desc *f, size_t i, const void *buf)
{
    if (f->compute)
        return;
    size_t s = type_size(f->type);
    for (int c = 0; c < f->ncomp; c++)
        memcpy((char *)*f->comp[c] + i * s, (const char *)buf + (size_t)c * s, s);
}
