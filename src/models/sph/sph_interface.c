/**
 * @file sph_interface.c
 * @brief Interface between SPH bodies (`model.interface: bodies | materials`,
 *        issue 7 item 5, the deformable projectile): the kernel sums
 *        (density, stress, artificial viscosity, XSPH, CSPM) stay inside a
 *        body, and two bodies touch through a frictionless penalty between
 *        their particles.
 *
 * Why: with the plain SPH sums across a material boundary (silica
 * rho = 1850 kg/m^3, E = 72 GPa against gelatin 1030 kg/m^3, 20 MPa) the
 * stiff particles slip through the soft ones (docs/notes/penetration-log.md: the
 * silica's mean velocity at 25 ns -1123 m/s against -649 m/s for the rigid
 * sphere): the continuity equation and XSPH mix the two velocity fields,
 * and nothing keeps the particles of one material out of the other.  The
 * standard remedy is to keep the sums inside each body and to couple the
 * bodies by contact (penalty contact between SPH bodies: Campbell,
 * Vignjevic & Libersky, Comput. Methods Appl. Mech. Engrg. 184 (2000) 49,
 * whose kernel-based contact potential this simplifies to a pair spring;
 * the particle-particle penalty of the DEM; cited from memory).
 *
 * Pairs: particles i, j of different groups (body index, or material index
 * with `interface: materials`, for a target made of several graded
 * lattices) closer than the contact distance d_ij = f (dx_i + dx_j) / 2
 * (f = `interface_distance`, default 1: the spacing at which two lattices
 * touch face to face, each particle standing for a cell of its spacing)
 * repel with
 *
 *     F = k_ij w_ij delta,   delta = d_ij - r > 0,   U = k_ij w_ij delta^2 / 2,
 *
 *     k_ij = eta min(rho0_i dx_i^dim, rho0_j dx_j^dim) (max(c0_i, c0_j) / d_ij)^2
 *
 * (eta = `interface_stiffness`, default 1; the same scaling as the model's
 * rigid wall, sph_rates.c: the pair's oscillation frequency sqrt(k / m) is
 * the stiffer material's c0 / d, as fast as the SPH sums themselves and
 * stable at the SPH step; the overlap under a pressure p is
 * delta / d ~ p / (eta rho c_max^2), 1-4 % for the gelatin shock).  The
 * weight w_ij is the thickness in plane 2D, 1 in 3D, and the mean ring
 * circumference pi (R_i + R_j) in axisymmetric runs (each particle is a
 * ring of mass 2 pi R mu, mu the planar mass; R the hoop radius with the
 * floor of sph_axisym.c): the pair force is the same on both rings, so the
 * axial momentum is conserved exactly, and the radial derivative of w,
 * -pi k delta^2 / 2 on each ring (not floored), keeps F = -grad U so
 * that the penalty conserves energy.  k_ij is built from each particle's
 * rest mass measure and rest sound speed, constant in the run, so U is a
 * potential (no energy jump when anything else changes).
 *
 * Why not the core particle contact (`contact:`, core/contact_particles.c):
 * its k [N/m] is one constant for every pair, while an axisymmetric pair
 * of rings must push in proportion to their circumference (rings near the
 * axis have masses ~ r: a constant k would fling them), its stable step
 * uses the smallest ring mass, and its distance is one number where the
 * graded lattices need (dx_i + dx_j)/2; it also keeps its own cell list,
 * where the SPH list already holds every candidate.  In plane 2D / 3D it
 * would work for bodies, but the kernel sums would still couple them.
 *
 * Candidates: at each neighbour-list build (sph_rates.c) the pairs of
 * different groups are moved out of the kernel list into the interface
 * list, kept when closer than d_ij + the list's skin (the rebuild test
 * guarantees that no pair farther than that at the build can come within
 * d_ij before the next build).  The hot pair loops thus never see the
 * groups' boundary; the split is serial, O(pairs), once per build.
 *
 * Axis images (axisymmetric): the penalty acts between real rings only.
 * The image of ring j lies at (-r_j, z_j): it comes within d_ij of ring i
 * only if r_i + r_j < d_ij, i.e. both within a spacing of the axis, where
 * particles start at r >= dx/2.
 *
 * The core rigid impactor acts on particle centres: a target particle
 * touches when its centre reaches the impactor's surface, so target
 * material overlaps a rigid sphere by half a spacing, its effective radius
 * is R - dx_t/2.  f = dx_p / (dx_p + dx_t) would give the same convention
 * here (target centres on the projectile particles' outer faces), but at
 * f = 0.4 (silica 0.5 um into gelatin 0.75 um) the gel particles slipped
 * between the silica's surface particles and the run gained 167 % of the
 * sphere's energy in 100 ns: f is refused below 0.5; only f = 1 is
 * validated.
 */
#include "core/mathconst.h"
#include "models/sph/sph_internal.h"
#include "models/sph/sph_pairs.h"

#include "core/neighbor.h"
#include "core/particles.h"
#include "core/sim.h"
#include "spall/error.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>


static inline int32_t iface_group(const struct model *m, const struct particles *p, size_t i)
{
    return m->opt.iface.kind == SPH_IFACE_BODIES ? p->body[i] : p->material[i];
}

static inline double hoop_r(const struct model *m, const double *x0, size_t i)
{
    double r = x0[i], f = 0.25 * m->dx[i];
    return r > f ? r : f;
}

/* Rest mass measure rho0 dx^dim (planar mass per thickness in 2D and in the
 * meridian plane of an axisymmetric run; mass in 3D). */
static inline double mu0(const struct model *m, const struct particles *p, size_t i)
{
    double d = m->dx[i];
    return m->mat[p->material[i]].rho0 * (m->dim == 2 ? d * d : d * d * d);
}

/* The per-particle arrays for @p n particles (a distributed run's local
 * count changes with its ghosts at each build). */
static int iface_arrays(struct model *m, size_t n)
{
    if (!m->ifs.c0) {
        m->ifs.c0 = calloc(m->n_mat ? m->n_mat : 1, sizeof *m->ifs.c0);
        if (!m->ifs.c0)
            return -1;
        for (size_t k = 0; k < m->n_mat; k++)
            m->ifs.c0[k] = sph_sound_speed(&m->mat[k], m->mat[k].rho0, 0.0);
    }
    if (m->ifs.off && n <= m->ifs.n_alloc)
        return 0;
    size_t *off = realloc(m->ifs.off, (n + 1) * sizeof *off);
    if (off)
        m->ifs.off = off;
    double *e = realloc(m->ifs.e, (n ? n : 1) * sizeof *e);
    if (e)
        m->ifs.e = e;
    double *w = realloc(m->ifs.w, (n ? n : 1) * sizeof *w);
    if (w)
        m->ifs.w = w;
    uint32_t *np = realloc(m->ifs.np, (n ? n : 1) * sizeof *np);
    if (np)
        m->ifs.np = np;
    if (!off || !e || !w || !np)
        return -1;
    for (size_t i = m->ifs.n_alloc; i < n; i++) { /* as calloc'ed before a first force call */
        e[i] = w[i] = 0.0;
        np[i] = 0;
    }
    m->ifs.n_alloc = n;
    return 0;
}

int sph_interface_split(struct model *m, struct sim *s, double *const x[3], double skin_abs,
                        struct spall_error *err)
{
    const struct particles *p = s->p;
    struct neighbor_list *nl = m->nl;
    const size_t n = nl->n;
    const int dim = m->dim;
    if (iface_arrays(m, n))
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory (sph interface)");
    const double fd = 0.5 * m->opt.iface.distance;
    size_t w = 0, wi = 0, start = 0;
    m->ifs.off[0] = 0;
    for (size_t i = 0; i < n; i++) {
        const size_t end = nl->offset[i + 1];
        const int32_t gi = iface_group(m, p, i);
        for (size_t k = start; k < end; k++) {
            const size_t j = (size_t)nl->idx[k];
            if (!m->form) {
                if (iface_group(m, p, j) == gi) {
                    nl->idx[w++] = nl->idx[k];
                    continue;
                }
            } else if (m->form[i] == m->form[j]) {
                /* bodies split by formulation (sph_forms.c): a TLSPH body's
                 * own pairs live in its reference list (sph_tlsph.c), not
                 * here; the updated form keeps its groups' pairs */
                if (m->form[i] == SPH_FORM_TOTAL && p->body[i] == p->body[j])
                    continue;
                if (m->form[i] == SPH_FORM_UPDATED && iface_group(m, p, j) == gi) {
                    nl->idx[w++] = nl->idx[k];
                    continue;
                }
            }
            const double r2 = sph_dist2(x, dim, i, j);
            const double reach = fd * (m->dx[i] + m->dx[j]) + skin_abs;
            if (r2 > reach * reach)
                continue;
            if (wi == m->ifs.cap) {
                size_t cap = m->ifs.cap ? 2 * m->ifs.cap : 1024;
                int32_t *q = realloc(m->ifs.idx, cap * sizeof *q);
                if (!q)
                    return spall_error_set(err, SPALL_ERR_NOMEM,
                                           "out of memory (sph interface, %zu pairs)", cap);
                m->ifs.idx = q;
                m->ifs.cap = cap;
            }
            m->ifs.idx[wi++] = (int32_t)j;
        }
        start = end;
        nl->offset[i + 1] = w;
        m->ifs.off[i + 1] = wi;
    }
    return SPALL_OK;
}

void sph_interface_forces(struct model *m, struct sim *s)
{
    struct particles *p = s->p;
    const size_t n = p->n_owned;
    const int dim = m->dim;
    const bool axi = m->opt.kern.plane == SPH_PLANE_AXISYMMETRIC;
    const double t = dim == 2 ? s->thickness : 1.0;
    const double eta = m->opt.iface.stiffness, fd = 0.5 * m->opt.iface.distance;
    double *ei = m->ifs.e, *wi = m->ifs.w;
    if (!m->ifs.off) {
        m->ifs.energy = 0.0;
        m->ifs.pairs = 0;
        return;
    }
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < n; i++) {
        double fi[3] = {0, 0, 0}, e = 0.0, om2 = 0.0;
        size_t np = 0;
        const double mui = mu0(m, p, i), ci = m->ifs.c0[p->material[i]];
        const double Ri = axi ? hoop_r(m, p->x[0], i) : 0.0;
        /* the radial derivative of the ring weight vanishes on the floor */
        const double dwdr = axi && p->x[0][i] > 0.25 * m->dx[i] ? SPALL_PI : 0.0;
        for (size_t q = m->ifs.off[i]; q < m->ifs.off[i + 1]; q++) {
            const size_t j = (size_t)m->ifs.idx[q];
            double dxv[3] = {0, 0, 0}, r2 = 0.0;
            for (int d = 0; d < dim; d++) {
                dxv[d] = p->x[d][i] - p->x[d][j];
                r2 += dxv[d] * dxv[d];
            }
            const double dc = fd * (m->dx[i] + m->dx[j]);
            if (!(r2 < dc * dc) || r2 == 0.0)
                continue;
            const double r = sqrt(r2), delta = dc - r;
            const double muj = mu0(m, p, j), cj = m->ifs.c0[p->material[j]];
            const double cm = ci > cj ? ci : cj;
            const double k = eta * (mui < muj ? mui : muj) * cm * cm / (dc * dc);
            const double wgt = axi ? SPALL_PI * (Ri + hoop_r(m, p->x[0], j)) : t;
            const double F = k * wgt * delta;
            for (int d = 0; d < dim; d++)
                fi[d] += F * dxv[d] / r;
            if (axi)
                fi[0] -= 0.5 * k * delta * delta * dwdr;
            e += 0.25 * k * wgt * delta * delta; /* half the pair's energy */
            om2 += k * (1.0 / mui + 1.0 / muj);
            np++;
        }
        for (int d = 0; d < dim; d++)
            p->f[d][i] += fi[d];
        ei[i] = e;
        wi[i] = om2;
        m->ifs.np[i] = (uint32_t)np;
    }
    /* fixed-order sums: diagnostics identical for any thread count */
    double etot = 0.0, om2max = 0.0;
    size_t npairs = 0;
    for (size_t i = 0; i < n; i++) {
        etot += ei[i];
        npairs += m->ifs.np[i];
        if (wi[i] > om2max)
            om2max = wi[i];
    }
    if (s->par) /* the whole body's, in the serial order (sph_ulpar.c) */
        sph_par_iface_totals(m, s, &etot, &npairs, &om2max);
    m->ifs.energy = etot;
    m->ifs.pairs = npairs / 2;
    m->ifs.omega2 = om2max;
}

double sph_interface_stable_dt(const struct model *m)
{
    /* a particle pressed by its contacts: omega^2 <= sum_j k_ij (1/mu_i + 1/mu_j)
     * (Gershgorin); 2 / omega is the leapfrog limit, which the engine then
     * scales by c_s (0.3): omega dt = 0.6 at most.  With eta = 1 this
     * rarely binds (omega ~ 1.8 c_max / d for two contacts, against the SPH
     * step 0.39 d / c) */
    return m->ifs.omega2 > 0.0 ? 2.0 / sqrt(m->ifs.omega2) : INFINITY;
}
