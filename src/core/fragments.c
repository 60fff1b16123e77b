/**
 * @file fragments.c
 * @brief Connected components over intact bonds (see fragments.h).
 */
#include "core/fragments.h"

#include "core/bond_list.h"
#include "core/fields.h"
#include "core/particles.h"
#include "core/sim.h"
#include "core/model.h"
#include "core/parallel/decomp.h"
#include "spall/error.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

struct fragments {
    size_t cap;                 /**< particles the workspace holds */
    size_t n;                   /**< particles of the last compute */
    size_t *parent;             /**< union-find forest */
    size_t *frag_of;            /**< root -> fragment index (SIZE_MAX: none) */
    int64_t *label;             /**< per particle: fragment id */
    struct fragment_info *info; /**< fragments (n_frag <= n) */
    size_t n_frag;
};

int fragments_create(struct fragments **out, size_t n, struct spall_error *err)
{
    *out = NULL;
    struct fragments *f = calloc(1, sizeof *f);
    size_t m = n ? n : 1;
    if (f) {
        f->parent = malloc(m * sizeof *f->parent);
        f->frag_of = malloc(m * sizeof *f->frag_of);
        f->label = malloc(m * sizeof *f->label);
        f->info = malloc(m * sizeof *f->info);
    }
    if (!f || !f->parent || !f->frag_of || !f->label || !f->info) {
        fragments_destroy(&f);
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory for fragments of %zu particles",
                               n);
    }
    f->cap = n;
    *out = f;
    return SPALL_OK;
}

void fragments_destroy(struct fragments **f)
{
    if (!f || !*f)
        return;
    free((*f)->parent);
    free((*f)->frag_of);
    free((*f)->label);
    free((*f)->info);
    free(*f);
    *f = NULL;
}

void fragment_add(struct fragment_info *fi, int64_t gid, double m, const double v[3], int dim)
{
    double v2 = 0.0;
    fi->count++;
    fi->mass += m;
    if (gid < fi->id)
        fi->id = gid;
    for (int d = 0; d < dim; d++) {
        fi->vcm[d] += m * v[d]; /* momentum until fragment_finish */
        v2 += v[d] * v[d];
    }
    fi->kinetic += 0.5 * m * v2;
}

void fragment_finish(struct fragment_info *fi, int dim)
{
    double v2 = 0.0;
    for (int d = 0; d < dim; d++) {
        fi->vcm[d] = fi->mass > 0.0 ? fi->vcm[d] / fi->mass : 0.0;
        v2 += fi->vcm[d] * fi->vcm[d];
    }
    fi->kinetic_cm = 0.5 * fi->mass * v2;
}

int fragments_set(struct fragments *f, const struct fragment_info *info, size_t n_frag,
                  const int64_t *label, size_t n, struct spall_error *err)
{
    if (n_frag > f->cap || n > f->cap)
        return spall_error_set(err, SPALL_ERR_INTERNAL,
                               "fragments workspace holds %zu particles, %zu fragments and %zu "
                               "labels given", f->cap, n_frag, n);
    if (n_frag)
        memcpy(f->info, info, n_frag * sizeof *info);
    if (n)
        memcpy(f->label, label, n * sizeof *label);
    f->n_frag = n_frag;
    f->n = n;
    return SPALL_OK;
}

static size_t uf_find(size_t *parent, size_t i)
{
    while (parent[i] != i) {
        parent[i] = parent[parent[i]]; /* path halving */
        i = parent[i];
    }
    return i;
}

size_t fragments_root(size_t *parent, size_t i)
{
    return uf_find(parent, i);
}

void fragments_union_local(size_t *parent, const struct bond_list *bl, size_t n)
{
    for (size_t i = 0; i < n; i++)
        parent[i] = i;
    if (!bl)
        return;
    /* union over intact bonds; the smaller root index wins, so every root is
     * the smallest particle index of its component, whatever the bond order */
    for (size_t i = 0; i < n; i++)
        for (size_t k = bl->offset[i]; k < bl->offset[i + 1]; k++) {
            if (bl->state[k] & BOND_BROKEN)
                continue;
            size_t j = (size_t)bl->partner[k];
            if (j <= i || j >= n) /* each bond once; ghosts are not ours */
                continue;
            size_t a = uf_find(parent, i), b = uf_find(parent, j);
            if (a < b)
                parent[b] = a;
            else if (b < a)
                parent[a] = b;
        }
}

int fragments_compute(struct fragments *f, const struct particles *p, int dim,
                      const struct bond_list *bl, struct spall_error *err)
{
    const size_t n = p->n_owned;
    if (n > f->cap)
        return spall_error_set(err, SPALL_ERR_INTERNAL,
                               "fragments workspace holds %zu particles, %zu given", f->cap, n);
    if (bl && bl->n < n)
        return spall_error_set(err, SPALL_ERR_INTERNAL, "bond list has %zu rows for %zu particles",
                               bl->n, n);
    size_t *parent = f->parent;
    fragments_union_local(parent, bl, n);
    /* fragments in order of their smallest index; sums in particle order */
    f->n_frag = 0;
    for (size_t i = 0; i < n; i++)
        f->frag_of[i] = SIZE_MAX;
    for (size_t i = 0; i < n; i++) {
        size_t r = uf_find(parent, i);
        size_t q = f->frag_of[r];
        if (q == SIZE_MAX) {
            q = f->frag_of[r] = f->n_frag++;
            struct fragment_info *fi = &f->info[q];
            memset(fi, 0, sizeof *fi);
            fi->id = p->gid[i];
        }
        double v[3] = {0.0, 0.0, 0.0};
        for (int d = 0; d < dim; d++)
            v[d] = p->v[d][i];
        fragment_add(&f->info[q], p->gid[i], p->mass[i], v, dim);
    }
    for (size_t q = 0; q < f->n_frag; q++)
        fragment_finish(&f->info[q], dim);
    for (size_t i = 0; i < n; i++)
        f->label[i] = f->info[f->frag_of[uf_find(parent, i)]].id;
    f->n = n;
    return SPALL_OK;
}

size_t fragments_count(const struct fragments *f)
{
    return f->n_frag;
}

const struct fragment_info *fragments_list(const struct fragments *f)
{
    return f->info;
}

const int64_t *fragments_labels(const struct fragments *f)
{
    return f->label;
}

void fragments_summarise(const struct fragments *f, struct fragment_summary *out)
{
    memset(out, 0, sizeof *out);
    out->count = f->n_frag;
    for (size_t q = 0; q < f->n_frag; q++) {
        const struct fragment_info *fi = &f->info[q];
        out->singles += fi->count == 1;
        out->ge10 += fi->count >= 10;
        out->total_mass += fi->mass;
        out->kinetic_cm += fi->kinetic_cm;
        if (fi->mass > out->largest_mass) {
            out->second_mass = out->largest_mass;
            out->largest_mass = fi->mass;
        } else if (fi->mass > out->second_mass) {
            out->second_mass = fi->mass;
        }
    }
}

static int by_mass_desc(const void *a, const void *b)
{
    const struct fragment_info *x = a, *y = b;
    if (x->mass != y->mass)
        return x->mass < y->mass ? 1 : -1;
    return (x->id > y->id) - (x->id < y->id);
}

int fragments_write_csv(const struct fragments *f, const char *path, double time,
                        struct spall_error *err)
{
    struct fragment_info *sorted = malloc((f->n_frag ? f->n_frag : 1) * sizeof *sorted);
    if (!sorted)
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory writing '%s'", path);
    memcpy(sorted, f->info, f->n_frag * sizeof *sorted);
    qsort(sorted, f->n_frag, sizeof *sorted, by_mass_desc);
    FILE *out = fopen(path, "w");
    if (!out) {
        free(sorted);
        return spall_error_set(err, SPALL_ERR_IO, "cannot write '%s': %s", path, strerror(errno));
    }
    fprintf(out, "# fragments at t = %.10g s (connected components over intact bonds)\n", time);
    fprintf(out, "fragment_id,particles,mass [kg],vcm_x [m/s],vcm_y [m/s],vcm_z [m/s],"
                 "kinetic [J],kinetic_cm [J]\n");
    for (size_t q = 0; q < f->n_frag; q++) {
        const struct fragment_info *fi = &sorted[q];
        fprintf(out, "%lld,%zu,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g\n", (long long)fi->id, fi->count,
                fi->mass, fi->vcm[0], fi->vcm[1], fi->vcm[2], fi->kinetic, fi->kinetic_cm);
    }
    free(sorted);
    if (fclose(out) != 0)
        return spall_error_set(err, SPALL_ERR_IO, "cannot write '%s'", path);
    return SPALL_OK;
}

static const struct bond_list *sim_bonds(const struct sim *s)
{
    return s->ops && s->ops->bonds ? s->ops->bonds(s->model) : NULL;
}

int fragments_of_sim(struct fragments *f, const struct sim *s, struct spall_error *err)
{
    const struct bond_list *bl = sim_bonds(s);
    if (!bl) {
        f->n = f->n_frag = 0;
        return SPALL_OK;
    }
    return fragments_compute(f, s->p, s->dim, bl, err);
}

/* computed field: a fresh workspace per frame (frames are rare; a failure to
 * allocate writes -1, which no gid takes) */
static void field_fragment_id(const void *ctx, size_t n, double *out)
{
    const struct sim *s = ctx;
    if (s->par) { /* distributed: collective label rounds (parallel/fragments_par.c) */
        int64_t *lab = malloc((n ? n : 1) * sizeof *lab);
        int rc = par_fragment_labels(s, lab, NULL); /* takes part even without memory */
        for (size_t i = 0; i < n; i++)
            out[i] = rc == SPALL_OK && lab && i < s->p->n_owned ? (double)lab[i] : -1.0;
        free(lab);
        return;
    }
    struct fragments *f = NULL;
    if (fragments_create(&f, s->p->n_owned, NULL) == SPALL_OK &&
        fragments_of_sim(f, s, NULL) == SPALL_OK && f->n == s->p->n_owned) {
        for (size_t i = 0; i < n; i++)
            out[i] = i < f->n ? (double)f->label[i] : -1.0;
    } else {
        for (size_t i = 0; i < n; i++)
            out[i] = -1.0;
    }
    fragments_destroy(&f);
}

int fragments_register_field(struct sim *s, struct spall_error *err)
{
    if (!sim_bonds(s))
        return SPALL_OK;
    struct field_desc d;
    memset(&d, 0, sizeof d);
    strcpy(d.name, "fragment_id");
    strcpy(d.unit, "1");
    d.ncomp = 1;
    d.type = FIELD_F64;
    d.flags = FIELD_OUTPUT;
    d.compute = field_fragment_id;
    d.ctx = s;
    return field_registry_add(s->fields, &d, err);
}
