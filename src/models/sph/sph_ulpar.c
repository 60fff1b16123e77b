/**
 * @file sph_ulpar.c
 * @brief The updated-Lagrangian SPH form distributed on spatial ghosts
 *        (core/parallel/spatial.h; docs/parallel.md, "Updated-Lagrangian
 *        SPH on spatial ghosts").
 *
 * The partition keeps each rank's owned particles with every per-particle
 * array of the model; the engine then keeps as ghosts the particles of
 * other ranks within the list radius (qmax h_max (1 + skin)) of the owned
 * particles' build positions, carrying what the list build reads (x_build,
 * h, dx, m2) and rho, c.  sph_spatial_rebuilt builds the list from the
 * build positions, as the serial run built it from the same positions,
 * and sorts each row by the partner's global id, the serial row order
 * (one rank: index = gid), so each owned particle sums its pairs term for
 * term as on one rank.  The rebuild test is the serial one (sph_rates.c,
 * sph_neighbors_update) on the largest move and h over all ranks, so the
 * lists are rebuilt in the same steps.
 *
 * Between rebuilds the halo of positions and velocities runs before every
 * force call (par_halo_x); the pair loops read more of a partner than that
 * (its density, sound speed, stress, ...), which its owner computes in the
 * same force call: sph_par_halo hands those to the ghosts in one exchange
 * per loop (the widths are sph_par_halo_width's).
 */
#include "models/sph/sph_internal.h"

#include "core/bond_list.h"
#include "core/neighbor.h"
#include "core/parallel/comm.h"
#include "core/parallel/decomp.h"
#include "core/parallel/gather.h"
#include "core/parallel/migrate.h"
#include "core/parallel/spatial.h"
#include "core/particles.h"
#include "core/sim.h"
#include "spall/error.h"

#include <math.h>
#include <omp.h>
#include <stdlib.h>
#include <string.h>

/* ---- the per-call halo of the pair loops' partner values ---- */

/* The arrays of @p set with the run's options; returns their count. */
static int halo_arrays(struct model *m, enum sph_halo_set set, double **a[40])
{
    int k = 0;
    a[k++] = &m->rho;
    a[k++] = &m->h;
    if (set == SPH_HALO_DENSITY)
        return k;
    if (set == SPH_HALO_AS_SMOOTH) {
        for (int c = 0; c < 6; c++)
            a[k++] = &m->R[c];
        return k;
    }
    if (set == SPH_HALO_AXI_GRADIENT || set == SPH_HALO_AXI_FORCES)
        a[k++] = &m->m2; /* the planar mass follows r (sph_axisym.c) */
    if (set == SPH_HALO_AXI_GRADIENT)
        return k;
    if (set == SPH_HALO_AXI_FORCES) {
        /* pass_forces_axi: sigma, B^-1, the axis weight, c (and L for
         * Balsara's switch) of the partner */
        a[k++] = &m->c;
        a[k++] = &m->ax.axl;
        for (int c = 0; c < 6; c++)
            a[k++] = &m->sig[c];
        for (int c = 0; c < 9; c++)
            if (c % 3 < 2 && c / 3 < 2) /* the (r, z) block */
                a[k++] = &m->Bi[c];
        for (int c = 0; c < 9 && m->opt.visc.av_balsara; c++)
            a[k++] = &m->L[c];
        return k;
    }
    a[k++] = &m->c;
    const bool as = m->opt.visc.as_zeta > 0.0;
    for (int c = 0; c < 6; c++)
        a[k++] = set == SPH_HALO_FUSED ? &m->sr[c] : &m->sig[c];
    for (int c = 0; c < 6 && as; c++)
        a[k++] = &m->R[c];
    if (set == SPH_HALO_SPLIT && m->opt.kern.cspm)
        for (int c = 0; c < 9; c++)
            a[k++] = &m->Bi[c];
    if (set == SPH_HALO_SPLIT && m->opt.visc.av_balsara) /* the partner's switch */
        for (int c = 0; c < 9; c++)
            a[k++] = &m->L[c];
    return k;
}

int sph_par_halo_width(const struct model *m, enum sph_halo_set set)
{
    double **a[40];
    return halo_arrays((struct model *)m, set, a);
}

int sph_par_halo(struct model *m, struct sim *s, enum sph_halo_set set, struct spall_error *err)
{
    double **a[40];
    const int w = halo_arrays(m, set, a);
    return sph_par_halo_arrays(s, a, w, err);
}

int sph_par_halo_arrays(struct sim *s, double **const *a, int w, struct spall_error *err)
{
    const struct particles *p = s->p;
    const size_t n = p->n, no = p->n_owned;
    double *buf = malloc((n ? n : 1) * (size_t)w * sizeof *buf);
    if (buf) /* owned rows packed (the halo sends those on its lists) */
        for (size_t i = 0; i < no; i++)
            for (int k = 0; k < w; k++)
                buf[i * (size_t)w + (size_t)k] = (*a[k])[i];
    /* every rank learns of a failed allocation before the exchange */
    if (par_sum_u64(!buf) || par_halo_block(s, buf, w)) {
        free(buf);
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory (SPH halo, %d values)", w);
    }
    for (size_t i = no; i < n; i++)
        for (int k = 0; k < w; k++)
            (*a[k])[i] = buf[i * (size_t)w + (size_t)k];
    free(buf);
    return SPALL_OK;
}

void sph_par_iface_totals(struct model *m, struct sim *s, double *energy, size_t *pairs,
                          double *omega2)
{
    /* the energy enters the energy account: summed as one rank sums it,
     * particle by particle in gid order, from the whole body's values */
    struct spall_error err = {0};
    double *e = malloc((par_n_global(s) ? par_n_global(s) : 1) * sizeof *e);
    const int bad = par_sum_u64(!e) > 0;
    if (!bad && !par_gather_by_gid(s, m->ifs.e, e, &err)) {
        double t = 0.0;
        for (size_t i = 0; i < par_n_global(s); i++)
            t += e[i];
        *energy = t;
    } else {
        *energy = NAN; /* out of memory: the energy account shows it */
    }
    free(e);
    *pairs = (size_t)par_sum_u64((uint64_t)*pairs);
    *omega2 = par_max_double(*omega2);
}

/* ---- spatial ghosts ---- */

/* The serial rebuild test (sph_neighbors_update) on the whole body. */
static bool rebuild_due(struct model *m, const struct sim *s, double d2max)
{
    double hmax = 0.0;
    for (size_t i = 0; i < s->p->n_owned; i++)
        if (m->h[i] > hmax)
            hmax = m->h[i];
    hmax = par_max_double(hmax);
    /* symmetry planes: the serial run builds its list over real and
     * mirrored particles at its first force call (sph_symmetry_update) */
    bool due = (m->opt.bound.symmetry[0] || m->opt.bound.symmetry[1]) && !sph_symmetry_built(m);
    due = due || !(m->qmax * hmax + 2.0 * sqrt(d2max) <= m->nl_radius);
    /* the radius of the list built now, the serial one (sph_neighbors_update):
     * the engine takes it as the ghost range (sph_spatial_ghosts) before it
     * builds the ghosts; with a variable h it has grown since the last build */
    if (due)
        m->nl_radius = m->qmax * hmax * (1.0 + m->opt.kern.skin);
    return due;
}

/* par_spatial_model.place: the mirrored clamp's particles (sph_clamp.c) */
static int clamp_place(struct model *m, struct sim *s, struct spall_error *err)
{
    return sph_clamp_place(m, s, err);
}

int sph_spatial_ghosts(struct model *m, struct par_spatial_model *sp)
{
    if (m->opt.tl.total_lagrangian && !m->opt.tl.split_forms)
        return 1; /* the reference list's bond ghosts (sph_localize.c) */
    /* range + skin covers the list radius, with a margin for the rounding
     * of the box test: an extra ghost is never listed by an owned row
     * farther than the list radius */
    sp->range = m->nl_radius;
    sp->skin = 1e-6 * m->nl_radius;
    sp->xb = m->x_build;
    sp->rebuild_due = rebuild_due;
    /* symmetry planes x = 0, y = 0: their images' sources are ghosts too */
    sp->mirror_planes = (m->opt.bound.symmetry[0] ? 1u : 0u) | (m->opt.bound.symmetry[1] ? 2u : 0u);
    sp->place = m->clamp ? clamp_place : NULL;
    int k = 0;
    for (int d = 0; d < m->dim; d++) {
        sp->particle[k] = (void **)&m->x_build[d];
        sp->particle_size[k++] = sizeof(double);
    }
    double **a[] = {&m->h, &m->dx, &m->m2, &m->rho, &m->c, &m->h_build};
    for (size_t q = 0; q < sizeof a / sizeof a[0] && k < PAR_SPATIAL_MAX_ARRAYS; q++) {
        sp->particle[k] = (void **)a[q];
        sp->particle_size[k++] = sizeof(double);
    }
    sp->n_particle = k;
    /* TLSPH bodies behind an interface: their reference partners too */
    sph_tl_spatial_ghosts(m, sp);
    return 0;
}

/* Every per-particle array of the model sized for the n local particles
 * (the engine re-laid out the carried ones; the rest keep their owned rows). */
int sph_resize_state(struct model *m, size_t n)
{
    double **a[SPH_N_ARRAYS];
    const size_t na = sph_state_arrays(m, a);
    for (size_t k = 0; k < na; k++) {
        double *b = realloc(*a[k], (n ? n : 1) * sizeof(double));
        if (!b)
            return -1;
        *a[k] = b;
    }
    return 0;
}

/* Each row in ascending partner gid: a row of the cell list is ascending
 * in local index, i.e. the owned partners (ascending gid) and then the
 * ghosts (ascending gid); the two runs are merged.  Partners from @p n_held
 * on (symmetry-plane images, already in the serial order) stay last. */
int sph_rows_by_gid(struct neighbor_list *nl, size_t n_owned, size_t n_held,
                    const int64_t *gid)
{
    size_t longest = 0;
    for (size_t i = 0; i < nl->n; i++)
        if (nl->offset[i + 1] - nl->offset[i] > longest)
            longest = nl->offset[i + 1] - nl->offset[i];
    int32_t *tmp = malloc((longest ? longest : 1) * sizeof *tmp);
    if (!tmp)
        return -1;
    for (size_t i = 0; i < nl->n; i++) {
        int32_t *r = nl->idx + nl->offset[i];
        const size_t len = nl->offset[i + 1] - nl->offset[i];
        size_t g = 0, e;
        while (g < len && (size_t)r[g] < n_owned)
            g++;
        for (e = g; e < len && (size_t)r[e] < n_held;)
            e++;
        size_t a = 0, b = g, w = 0;
        while (a < g || b < e)
            tmp[w++] = b == e || (a < g && gid[r[a]] < gid[r[b]]) ? r[a++] : r[b++];
        memcpy(r, tmp, e * sizeof *r);
    }
    free(tmp);
    return 0;
}

int sph_spatial_rebuilt(struct model *m, struct sim *sim, bool moved, struct spall_error *err)
{
    const struct particles *p = sim->p;
    const size_t n = p->n, no = p->n_owned;
    /* the serial build (sph_neighbors_update) at the build positions: the
     * radius of the whole body's largest h, the trim at the same skin.
     * The collectives run on every rank whatever fails (the engine agrees
     * on the error afterwards). */
    const double t0 = omp_get_wtime();
    double hmax = 0.0;
    for (size_t i = 0; i < no; i++)
        if (m->h[i] > hmax)
            hmax = m->h[i];
    hmax = par_max_double(hmax);
    int rc = sph_resize_state(m, n) ? spall_error_set(err, SPALL_ERR_NOMEM,
                                                  "out of memory (SPH state, %zu particles)", n)
                                : SPALL_OK;
    /* TLSPH bodies behind an interface: the reference rows by id, and
     * every local particle's formulation (the interface split reads it) */
    if (!rc && m->form)
        rc = sph_tl_relayout(m, sim, err);
    neighbor_list_destroy(&m->nl);
    /* a build (moved) has the radius of the whole body's h_max now; after a
     * partition, a migration or a re-reference the list is the last
     * build's again, with its radius and, for the interface split, its
     * h_max (a variable h, or a re-reference that grew h, has changed h_max
     * since; a restart reads both, sph_restart.c) */
    const bool fresh = moved || !(m->nl_radius > 0.0);
    if (fresh || !(m->opt.kern.variable_h || m->h_build))
        m->nl_hmax = hmax; /* (h fixed between builds: always the build's) */
    if (fresh)
        m->nl_radius = m->qmax * hmax * (1.0 + m->opt.kern.skin);
    /* and the trim of the build's smoothing lengths (the ghosts carry
     * theirs, sph_spatial_ghosts) */
    if (!rc && fresh && m->h_build)
        memcpy(m->h_build, m->h, n * sizeof *m->h);
    /* symmetry planes: over the held particles and their images, untrimmed
     * as the serial list of sph_symmetry_update (sph_symmetry.c) */
    const bool sym = m->opt.bound.symmetry[0] || m->opt.bound.symmetry[1];
    if (!rc)
        rc = sym ? sph_symmetry_list(m, sim, moved, err)
                 : neighbor_list_build_pairs(&m->nl, NULL, m->dim, n, m->x_build, m->nl_radius,
                                             err);
    if (!rc) {
        if (!sym && !m->opt.kern.variable_h) /* (h grows between builds: no trim) */
            sph_neighbors_trim(m, m->x_build, m->h_build ? m->h_build : m->h,
                               m->nl_radius - m->qmax * m->nl_hmax);
        if (sph_rows_by_gid(m->nl, no, n, p->gid))
            rc = spall_error_set(err, SPALL_ERR_NOMEM, "out of memory (SPH neighbour rows)");
    }
    /* the mirrored clamp's pairs among the owned particles (a partition
     * or a migration may have changed them) */
    if (!rc && m->clamp)
        rc = sph_clamp_localize(m, sim, err);
    /* the interface pairs leave the kernel rows, as in the serial build
     * (their rows follow the merged ones, so they are in gid order too) */
    if (!rc && m->opt.iface.kind != SPH_IFACE_NONE)
        rc = sph_interface_split(m, sim, m->x_build, m->nl_radius - m->qmax * m->nl_hmax, err);
    if (!rc && sph_ul_view(m))
        rc = spall_error_set(err, SPALL_ERR_NOMEM, "out of memory (SPH neighbour rows)");
    m->ul_pairs_all = (size_t)par_sum_u64(rc ? 0 : (uint64_t)m->nl->offset[no]);
    /* the serial count: bodies split by formulation count both lists'
     * pairs (sph_rates.c, compute_rates), also when a re-reference has
     * just found this list again (the reference count is the last force
     * call's until the next one, as on one rank) */
    m->n_pairs = m->ul_pairs_all + (m->form ? sph_tlsph_pairs(m) : 0);
    if (moved)
        m->n_builds++;
    m->t_neighbor += omp_get_wtime() - t0;
    return rc;
}

/* ---- partition and migration ---- */

/* Drop the bond view (its rows alias the list's). */
static void view_drop(struct model *m)
{
    if (m->ulview) {
        free(m->ulview->state);
        if (m->ulview_own) {
            free(m->ulview->offset);
            free(m->ulview->partner);
        }
    }
    free(m->ulview);
    m->ulview = NULL;
    m->ulview_own = false;
}

int sph_ul_view(struct model *m)
{
    if (par_size() < 2 || m->opt.tl.total_lagrangian || !m->nl)
        return 0;
    if (m->ulview_own)
        view_drop(m);
    const size_t ns = m->nl->offset[m->nl->n];
    struct bond_list *v = m->ulview ? m->ulview : calloc(1, sizeof *v);
    uint8_t *st = v ? realloc(v->state, ns ? ns : 1) : NULL;
    if (!st) {
        if (v && v != m->ulview)
            free(v);
        return -1;
    }
    memset(st, 0, ns ? ns : 1); /* intact: each partner counts as work */
    v->state = st;
    v->n = m->nl->n;
    v->offset = m->nl->offset;
    v->partner = m->nl->idx;
    m->ulview = v;
    return 0;
}

int sph_ul_view_held(struct model *m, size_t n_held)
{
    if (par_size() < 2 || m->opt.tl.total_lagrangian || !m->nl)
        return 0;
    view_drop(m);
    const struct neighbor_list *nl = m->nl;
    const size_t n = n_held < nl->n ? n_held : nl->n;
    size_t ns = 0;
    for (size_t k = 0; k < nl->offset[n]; k++)
        ns += (size_t)nl->idx[k] < n_held;
    struct bond_list *v = calloc(1, sizeof *v);
    if (!v)
        return -1;
    v->offset = malloc((n + 1) * sizeof *v->offset);
    v->partner = malloc((ns ? ns : 1) * sizeof *v->partner);
    v->state = calloc(ns ? ns : 1, 1); /* intact: each partner counts as work */
    m->ulview = v;
    m->ulview_own = true;
    if (!v->offset || !v->partner || !v->state) {
        view_drop(m);
        return -1;
    }
    v->n = n;
    size_t w = 0;
    for (size_t i = 0; i < n; i++) {
        v->offset[i] = w;
        for (size_t k = nl->offset[i]; k < nl->offset[i + 1]; k++)
            if ((size_t)nl->idx[k] < n_held)
                v->partner[w++] = nl->idx[k];
    }
    v->offset[n] = w;
    return 0;
}

void sph_ul_localize(struct model *m)
{
    view_drop(m);
    neighbor_list_destroy(&m->nl);
}

void sph_ul_release(struct model *m)
{
    bond_list_destroy(&m->ulmig);
    view_drop(m);
}

int sph_ul_migrate_arrays(struct model *m, struct sim *sim, struct par_model_arrays *a,
                          struct spall_error *err)
{
    /* no pair carries state: the migration is lent a list of empty rows,
     * and the list is rebuilt around the new ghosts (par_spatial_init) */
    bond_list_destroy(&m->ulmig);
    const size_t n = sim->p->n;
    struct bond_list *bl = calloc(1, sizeof *bl);
    if (bl) {
        bl->n = n;
        bl->offset = calloc(n + 1, sizeof *bl->offset);
        bl->partner = malloc(sizeof *bl->partner);
        bl->state = malloc(1);
    }
    if (!bl || !bl->offset || !bl->partner || !bl->state) {
        bond_list_destroy(&bl);
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory (SPH migration)");
    }
    m->ulmig = bl;
    memset(a, 0, sizeof *a);
    a->bl = bl;
    m->ul_half = 0;
    a->n_half = &m->ul_half;
    double **arr[SPH_N_ARRAYS];
    const size_t na = sph_state_arrays(m, arr);
    if (na + 3 > PAR_MIGRATE_MAX_ARRAYS)
        return spall_error_set(err, SPALL_ERR_INTERNAL, "SPH: %zu arrays to migrate", na + 3);
    for (size_t k = 0; k < na; k++) {
        a->particle[a->n_particle] = (void **)arr[k];
        a->particle_size[a->n_particle++] = sizeof(double);
    }
    /* the interface's per-particle values of the last force call go with
     * their particles: a checkpoint written after a rebalance, before the
     * next force call, holds them (NULL without an interface: skipped) */
    void **ia[] = {(void **)&m->ifs.e, (void **)&m->ifs.w, (void **)&m->ifs.np};
    const size_t is[] = {sizeof *m->ifs.e, sizeof *m->ifs.w, sizeof *m->ifs.np};
    for (size_t k = 0; k < 3 && m->ifs.e; k++) {
        a->particle[a->n_particle] = ia[k];
        a->particle_size[a->n_particle++] = is[k];
    }
    return SPALL_OK;
}

int sph_ul_migrated(struct model *m, size_t n, struct spall_error *err)
{
    (void)err;
    sph_ul_release(m); /* the rows came back empty; the list follows the ghosts */
    neighbor_list_destroy(&m->nl);
    if (m->ifs.e) /* the migration renewed them for the n local particles */
        m->ifs.n_alloc = n;
    return SPALL_OK;
}
