/**
 * @file pd_cellvol.c
 * @brief Partial volumes of the cell rule (deck `model.partial_volume_rule:
 *        cell`, formulation lps/eps): beta_ij = the fraction of the
 *        neighbour's lattice cell that lies inside the horizon sphere of i.
 *
 * The one-point quadrature of a family integral sum_j f(xi_j) beta_j V_j
 * ([Seleson2014]: partial areas of the cells cut by the horizon; here the
 * Voronoi cell of the lattice, in 2D and 3D) takes each site's cell as its
 * integration region.  With the exact cut fraction the cells tile the
 * sphere, so sum_j beta_j V_j is the sphere's volume (minus the particle's
 * own cell).  The linear rule beta = (delta + dx/2 - xi)/dx (pd_forces.c)
 * puts the fourth moment sum w n_x^4 / sum w of a simple-cubic family at
 * 0.2016 for delta = 3.015 dx (isotropic: 0.2), and its error swings with
 * m; with the cell rule it is 0.2006 there and nu of the LPS within 0.7 %
 * from m = 4.015 on (validation/pd_lps_cases.c, docs/decks.md).
 *
 * The cell is the Voronoi cell of the lattice, {s : s . n_k <= |n_k|^2 / 2}
 * over the nearest-neighbour vectors n_k (sc: cube, fcc: rhombic
 * dodecahedron, square: square, triangular: hexagon).  Its part inside the
 * sphere is integrated along one axis exactly (an interval: the cell's
 * linear constraints and the sphere's chord) and over the others by the
 * midpoint rule.  That axis is tilted against every face of the cells
 * (3D: (1, 2, 4)/sqrt21, 2D: 0.3 rad off y), so that the chord length is
 * continuous (no face parallel to it): the midpoint rule then errs by
 * O(1/N^2) (kinks only; the cell volumes come out within 1e-5,
 * tests/test_pd_lps_cell.c).  By the cell's symmetry beta depends on the sorted absolute
 * offsets in the lattice frame (triangular: absolute only); those are
 * rounded to 1e-6 dx and each distinct one integrated once, from the
 * rounded values, so that both ends of a bond, every rank and every run
 * get the same beta bit for bit.
 */
#include "models/peridynamics/pd_cellvol.h"

#include "core/mathconst.h"
#include "spall/error.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#define CV_QUANT 1.0e6   /* offsets rounded to 1e-6 dx */
#define CV_N3 256        /* midpoint points per outer axis, 3D */
#define CV_N2 8192       /* midpoint points of the outer axis, 2D */
#define CV_MAX 65536     /* distinct cut offsets before refusing (off-lattice sites) */

struct cv_entry {
    int64_t key[3];
    double beta;
};

double pd_cellvol_reach(enum lattice_kind kind)
{
    switch (kind) {
    case LATTICE_SC:
        return 0.5 * sqrt(3.0); /* cube corner */
    case LATTICE_FCC:
    case LATTICE_SQUARE:
        return 0.5 * sqrt(2.0); /* rhombic dodecahedron's 4-fold vertex; square corner */
    case LATTICE_TRIANGULAR:
        return 1.0 / sqrt(3.0); /* hexagon vertex */
    default:
        return 0.0;
    }
}

int pd_cellvol_init(struct pd_cellvol *c, enum lattice_kind kind, int dim, double delta_dx,
                    double angle, struct spall_error *err)
{
    *c = (struct pd_cellvol){.kind = kind, .dim = dim, .m = delta_dx, .angle = angle};
    int nc = 0;
    switch (kind) {
    case LATTICE_SC:
    case LATTICE_SQUARE: /* +-e_a: cube, square */
        for (int a = 0; a < (kind == LATTICE_SC ? 3 : 2); a++)
            for (int sg = -1; sg <= 1; sg += 2) {
                c->nv[nc][0] = c->nv[nc][1] = c->nv[nc][2] = 0.0;
                c->nv[nc++][a] = sg;
            }
        break;
    case LATTICE_FCC: /* the 12 vectors (+-1, +-1, 0)/sqrt2 and their permutations */
        for (int a = 0; a < 3; a++)
            for (int s1 = -1; s1 <= 1; s1 += 2)
                for (int s2 = -1; s2 <= 1; s2 += 2) {
                    c->nv[nc][a] = 0.0;
                    c->nv[nc][(a + 1) % 3] = s1 * sqrt(0.5);
                    c->nv[nc++][(a + 2) % 3] = s2 * sqrt(0.5);
                }
        break;
    case LATTICE_TRIANGULAR: /* rows along x (lattice frame) */
        for (int k = 0; k < 6; k++) {
            c->nv[nc][0] = cos(k * SPALL_PI / 3.0);
            c->nv[nc][1] = sin(k * SPALL_PI / 3.0);
            c->nv[nc++][2] = 0.0;
        }
        break;
    default:
        return spall_error_set_key(err, SPALL_ERR_INPUT, "model.partial_volume_rule",
                                   "partial_volume_rule cell is for the triangular, square, "
                                   "sc and fcc lattices (got %s)", lattice_kind_name(kind));
    }
    if ((dim == 3) != (kind == LATTICE_SC || kind == LATTICE_FCC))
        return spall_error_set(err, SPALL_ERR_INTERNAL, "cell partial volumes: lattice %s in "
                               "%dD", lattice_kind_name(kind), dim);
    c->nc = nc;
    /* the integration frame: rows t1, (t2,) d with d the tilted chord axis */
    double F[3][3] = {{0}};
    if (dim == 3) {
        const double s21 = sqrt(21.0), s20 = sqrt(20.0), s420 = sqrt(420.0);
        const double d[3] = {1.0 / s21, 2.0 / s21, 4.0 / s21};
        const double t1[3] = {0.0, 4.0 / s20, -2.0 / s20}; /* d x e_x, normalised */
        const double t2[3] = {-20.0 / s420, 2.0 / s420, 4.0 / s420}; /* d x t1 */
        for (int a = 0; a < 3; a++) {
            F[0][a] = t1[a];
            F[1][a] = t2[a];
            F[2][a] = d[a];
        }
    } else {
        const double th = 0.3;
        F[0][0] = cos(th);
        F[0][1] = -sin(th);
        F[1][0] = sin(th);
        F[1][1] = cos(th);
    }
    memcpy(c->frame, F, sizeof F);
    for (int k = 0; k < nc; k++) {
        double v[3];
        for (int a = 0; a < 3; a++)
            v[a] = F[a][0] * c->nv[k][0] + F[a][1] * c->nv[k][1] + F[a][2] * c->nv[k][2];
        for (int a = 0; a < 3; a++)
            c->nv[k][a] = v[a];
    }
    c->reach = pd_cellvol_reach(kind);
    c->vcell = -1.0;
    c->vcell = pd_cellvol_cut(c, (const double[3]){0, 0, 0}, INFINITY);
    return SPALL_OK;
}

void pd_cellvol_free(struct pd_cellvol *c)
{
    free(c->tab);
    c->tab = NULL;
    c->n = c->cap = 0;
}

/* Length of the cell's chord along the last axis at outer coordinates u
 * (units of dx), inside the sphere of radius r about -o. */
static double chord(const struct pd_cellvol *c, const double *u, const double *o, double r)
{
    const int last = c->dim - 1;
    double lo = -INFINITY, hi = INFINITY;
    for (int k = 0; k < c->nc; k++) {
        double rhs = 0.5; /* |n_k|^2 / 2, unit vectors */
        for (int a = 0; a < last; a++)
            rhs -= c->nv[k][a] * u[a];
        const double az = c->nv[k][last];
        if (az > 1e-12)
            hi = fmin(hi, rhs / az);
        else if (az < -1e-12)
            lo = fmax(lo, rhs / az);
        else if (rhs < 0.0)
            return 0.0;
    }
    if (isfinite(r)) {
        double q = r * r;
        for (int a = 0; a < last; a++)
            q -= (o[a] + u[a]) * (o[a] + u[a]);
        if (q <= 0.0)
            return 0.0;
        const double h = sqrt(q);
        lo = fmax(lo, -o[last] - h);
        hi = fmin(hi, -o[last] + h);
    }
    return hi > lo ? hi - lo : 0.0;
}

double pd_cellvol_cut(const struct pd_cellvol *c, const double *o_lat, double r)
{
    const double R = c->reach;
    double v = 0.0, u[2], o[3];
    for (int a = 0; a < 3; a++)
        o[a] = c->frame[a][0] * o_lat[0] + c->frame[a][1] * o_lat[1] + c->frame[a][2] * o_lat[2];
    if (c->dim == 3) {
        const double h = 2.0 * R / CV_N3;
        for (int i = 0; i < CV_N3; i++) {
            u[0] = -R + (i + 0.5) * h;
            for (int j = 0; j < CV_N3; j++) {
                u[1] = -R + (j + 0.5) * h;
                v += chord(c, u, o, r);
            }
        }
        v *= h * h;
    } else {
        const double h = 2.0 * R / CV_N2;
        for (int i = 0; i < CV_N2; i++) {
            u[0] = -R + (i + 0.5) * h;
            v += chord(c, u, o, r);
        }
        v *= h;
    }
    return c->vcell > 0.0 ? v / c->vcell : v;
}

/* Symmetry-reduced, rounded key of the offset e (m, lattice frame in units
 * of dx afterwards). */
static void reduce(const struct pd_cellvol *c, const double *e, double dx, int64_t *key)
{
    double v[3] = {e[0] / dx, e[1] / dx, c->dim == 3 ? e[2] / dx : 0.0};
    if (c->dim == 2) { /* into the lattice frame, as lattice_gen rotates it */
        const double cs = cos(c->angle), sn = sin(c->angle);
        const double x = cs * v[0] + sn * v[1], y = -sn * v[0] + cs * v[1];
        v[0] = x;
        v[1] = y;
    }
    for (int a = 0; a < 3; a++)
        v[a] = fabs(v[a]);
    if (c->kind != LATTICE_TRIANGULAR) /* cubic cells: any permutation of the axes */
        for (int a = 0; a < c->dim; a++)
            for (int b = a + 1; b < c->dim; b++)
                if (v[b] > v[a]) {
                    const double t = v[a];
                    v[a] = v[b];
                    v[b] = t;
                }
    for (int a = 0; a < 3; a++)
        key[a] = (int64_t)llround(v[a] * CV_QUANT);
}

int pd_cellvol_beta(struct pd_cellvol *c, const double *e, double dx, double *beta,
                    struct spall_error *err)
{
    int64_t key[3];
    reduce(c, e, dx, key);
    double o[3], r2 = 0.0;
    for (int a = 0; a < 3; a++) {
        o[a] = (double)key[a] / CV_QUANT;
        r2 += o[a] * o[a];
    }
    const double xi = sqrt(r2);
    if (xi + c->reach <= c->m) {
        *beta = 1.0;
        return SPALL_OK;
    }
    if (xi - c->reach >= c->m) {
        *beta = 0.0;
        return SPALL_OK;
    }
    for (size_t k = 0; k < c->n; k++)
        if (c->tab[k].key[0] == key[0] && c->tab[k].key[1] == key[1] &&
            c->tab[k].key[2] == key[2]) {
            *beta = c->tab[k].beta;
            return SPALL_OK;
        }
    if (c->n == c->cap) {
        if (c->cap >= CV_MAX)
            return spall_error_set_key(err, SPALL_ERR_INPUT, "model.partial_volume_rule",
                                       "partial_volume_rule cell: over %d distinct cut "
                                       "offsets (sites off the %s lattice?)", CV_MAX,
                                       lattice_kind_name(c->kind));
        const size_t nc = c->cap ? 2 * c->cap : 64;
        struct cv_entry *t = realloc(c->tab, nc * sizeof *t);
        if (!t)
            return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory for cell volumes");
        c->tab = t;
        c->cap = nc;
    }
    const double b = pd_cellvol_cut(c, o, c->m);
    c->tab[c->n++] = (struct cv_entry){.key = {key[0], key[1], key[2]}, .beta = b};
    *beta = b;
    return SPALL_OK;
}
