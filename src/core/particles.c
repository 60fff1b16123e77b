#include "core/particles.h"

#include "spall/error.h"

#include <stdlib.h>
#include <string.h>
#ifdef _OPENMP
#include <omp.h>
#endif

static int grow_array(void **ptr, size_t elem, size_t cap)
{
    void *q = realloc(*ptr, elem * (cap ? cap : 1));
    if (!q)
        return -1;
    *ptr = q;
    return 0;
}

int particles_create(struct particles **out, int dim, size_t cap, struct spall_error *err)
{
    *out = NULL;
    if (dim < 1 || dim > 3)
        return spall_error_set(err, SPALL_ERR_INPUT, "dimension must be 1, 2 or 3 (got %d)", dim);
    struct particles *p = calloc(1, sizeof *p);
    if (!p)
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory creating particles");
    p->dim = dim;
    int rc = particles_reserve(p, cap ? cap : 16, err);
    if (rc) {
        particles_destroy(&p);
        return rc;
    }
    *out = p;
    return SPALL_OK;
}

void particles_destroy(struct particles **pp)
{
    if (!pp || !*pp)
        return;
    struct particles *p = *pp;
    for (int d = 0; d < 3; d++) {
        free(p->x[d]);
        free(p->x0[d]);
        free(p->v[d]);
        free(p->f[d]);
    }
    free(p->mass);
    free(p->volume);
    free(p->gid);
    free(p->material);
    free(p->body);
    free(p);
    *pp = NULL;
}

int particles_reserve(struct particles *p, size_t cap, struct spall_error *err)
{
    if (cap <= p->cap)
        return SPALL_OK;
    int bad = 0;
    for (int d = 0; d < p->dim; d++) {
        bad |= grow_array((void **)&p->x[d], sizeof(double), cap);
        bad |= grow_array((void **)&p->x0[d], sizeof(double), cap);
        bad |= grow_array((void **)&p->v[d], sizeof(double), cap);
        bad |= grow_array((void **)&p->f[d], sizeof(double), cap);
    }
    bad |= grow_array((void **)&p->mass, sizeof(double), cap);
    bad |= grow_array((void **)&p->volume, sizeof(double), cap);
    bad |= grow_array((void **)&p->gid, sizeof(int64_t), cap);
    bad |= grow_array((void **)&p->material, sizeof(int32_t), cap);
    bad |= grow_array((void **)&p->body, sizeof(int32_t), cap);
    if (bad)
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory growing particles to %zu", cap);
    p->cap = cap;
    return SPALL_OK;
}

int particles_append(struct particles *p, const double pos[3], int32_t material,
                     size_t *index, struct spall_error *err)
{
    if (p->n == p->cap) {
        int rc = particles_reserve(p, p->cap * 2 + 16, err);
        if (rc)
            return rc;
    }
    size_t i = p->n;
    for (int d = 0; d < p->dim; d++) {
        p->x[d][i] = pos[d];
        p->x0[d][i] = pos[d];
        p->v[d][i] = 0.0;
        p->f[d][i] = 0.0;
    }
    p->mass[i] = 0.0;
    p->volume[i] = 0.0;
    p->gid[i] = (int64_t)i;
    p->material[i] = material;
    p->body[i] = 0;
    p->n++;
    p->n_owned++;
    if (index)
        *index = i;
    return SPALL_OK;
}

void particles_masses_changed(struct particles *p)
{
    p->mass_checked = 0;
    p->mass_uniform = 0.0;
}

void particles_zero_forces(struct particles *p)
{
    /* each thread clears its own static share (the share it will fill in
     * the force loops), not one thread the whole array */
    const size_t n = p->n;
    const int dim = p->dim;
#pragma omp parallel if (n > SPALL_OMP_MIN_PARTICLES)
    {
#ifdef _OPENMP
        const size_t nt = (size_t)omp_get_num_threads(), t = (size_t)omp_get_thread_num();
#else
        const size_t nt = 1, t = 0;
#endif
        const size_t lo = n * t / nt, hi = n * (t + 1) / nt;
        for (int d = 0; d < dim; d++)
            memset(p->f[d] + lo, 0, (hi - lo) * sizeof(double));
    }
}
