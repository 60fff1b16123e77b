/*
 * Spatial ghosts (core/parallel/sghost.h) under mpirun: on a particle cloud
 * split over the ranks (slabs, and a random interleaving whose boxes all
 * overlap), the ghost set of every rank equals the brute-force set (the
 * particles of other ranks within range + skin of the rank's box, in
 * ascending id, positions exact); after every particle moves less than
 * skin/2 no rebuild is asked for, the refreshed ghosts carry the owners'
 * new positions, and every cross-rank pair within the range has its
 * partner among the ghosts; a move past skin/2 asks for a rebuild; a move
 * past the skin stops every rank with the particle's id.  With mirror
 * planes (par_sghost_set_mirror: SPH's symmetry planes), on a cloud that
 * straddles them, the set is the brute-force set of the particles whose
 * position or an image lies within range + skin of the box, and every image
 * within the range of an owned particle has its source among the owned
 * particles and the ghosts (some sources being ghosts by their image only).
 * With forced sends (par_sghost_set_forced) the set is the brute-force set
 * plus the bond partners held elsewhere, each once, and only for that build.
 * Run: mpirun -np N test_par_sghost (N = 1 is valid: no ghosts).
 */
#include "core/parallel/comm.h"
#include "core/parallel/sghost.h"
#include "spall/error.h"
#include "tests/mpi/par_check.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define M 1500

static uint64_t rng_state;

static double urand(void)
{
    rng_state = rng_state * 6364136223846793005ull + 1442695040888963407ull;
    return (double)(rng_state >> 11) * 0x1.0p-53;
}

struct cloud {
    int dim;
    double x[3][M];
    int owner[M];
};

static void make_cloud(struct cloud *c, int dim, int interleave, int size)
{
    rng_state = 12345u + (uint64_t)dim * 7u + (uint64_t)interleave;
    c->dim = dim;
    for (int j = 0; j < M; j++) {
        for (int d = 0; d < 3; d++)
            c->x[d][j] = d < dim ? urand() : 0.0;
        c->owner[j] = interleave ? (int)(urand() * size) % size
                                 : (int)(c->x[0][j] * size) % size;
    }
}

/* squared distance of particle j (or, with mirror planes, of the nearest of
 * it and its images) to the box */
static double dist2_box(const struct cloud *c, int j, const double *lo, const double *hi,
                        unsigned mirror)
{
    double best = INFINITY;
    for (unsigned mk = 0; mk < 8; mk++) {
        if (mk & ~mirror)
            continue;
        double r2 = 0.0;
        for (int d = 0; d < c->dim; d++) {
            double p = (mk >> d & 1u) ? -c->x[d][j] : c->x[d][j];
            double u = p < lo[d] ? lo[d] - p : p > hi[d] ? p - hi[d] : 0.0;
            r2 += u * u;
        }
        best = fmin(best, r2);
    }
    return best;
}

/* this rank's owned particles, ascending id (= index in the cloud) */
static size_t owned_of(const struct cloud *c, int rank, double *x[3], int64_t *gid)
{
    size_t n = 0;
    for (int j = 0; j < M; j++)
        if (c->owner[j] == rank) {
            for (int d = 0; d < 3; d++)
                x[d][n] = c->x[d][j];
            gid[n++] = j;
        }
    return n;
}

/* the box of @p rank's particles; 0 when it owns none */
static int owned_box(const struct cloud *c, int rank, double lo[3], double hi[3])
{
    int any = 0;
    for (int d = 0; d < 3; d++) {
        lo[d] = INFINITY;
        hi[d] = -INFINITY;
    }
    for (int j = 0; j < M; j++)
        if (c->owner[j] == rank) {
            any = 1;
            for (int d = 0; d < c->dim; d++) {
                lo[d] = fmin(lo[d], c->x[d][j]);
                hi[d] = fmax(hi[d], c->x[d][j]);
            }
        }
    return any;
}

static void check_against_brute_force(const struct cloud *c, const struct par_sghost *g,
                                      double range, double skin, unsigned mirror,
                                      const char *what)
{
    const int rank = par_rank();
    double lo[3], hi[3];
    const int any = owned_box(c, rank, lo, hi);
    const double cut2 = (range + skin) * (range + skin);
    size_t q = 0, ng = par_sghost_count(g);
    const int64_t *gg = par_sghost_gid(g);
    for (int j = 0; j < M && any; j++) {
        if (c->owner[j] == rank || dist2_box(c, j, lo, hi, mirror) > cut2)
            continue;
        CHECK(q < ng && gg[q] == j, "%s: ghost %zu should be particle %d (got %lld)", what, q, j,
              q < ng ? (long long)gg[q] : -1LL);
        if (q < ng && gg[q] == j) {
            for (int d = 0; d < c->dim; d++)
                CHECK(par_sghost_x(g, d)[q] == c->x[d][j], "%s: ghost %d position", what, j);
            CHECK(par_sghost_owner(g)[q] == c->owner[j], "%s: ghost %d owner", what, j);
        }
        q++;
    }
    CHECK(q == ng, "%s: %zu ghosts, brute force %zu", what, ng, q);
}

static void run_case(int dim, int interleave)
{
    const int size = par_size(), rank = par_rank();
    static struct cloud c;
    make_cloud(&c, dim, interleave, size);
    const double range = dim == 3 ? 0.08 : 0.04, skin = 0.3 * range;
    char what[64];
    snprintf(what, sizeof what, "%dD %s", dim, interleave ? "interleaved" : "slabs");
    double *x[3];
    for (int d = 0; d < 3; d++)
        x[d] = calloc(M, sizeof(double));
    int64_t *gid = calloc(M, sizeof *gid);
    struct par_sghost *g = NULL;
    struct spall_error err = {0};
    int rc = par_sghost_create(&g, dim, range, skin, &err);
    CHECK(!rc, "create: %s", err.msg);
    size_t n = owned_of(&c, rank, x, gid);
    rc = par_sghost_build(g, n, (const double *const *)x, gid, &err);
    CHECK(!rc, "build: %s", err.msg);
    check_against_brute_force(&c, g, range, skin, 0, what);
    if (size > 1 && !interleave && M / size > 50)
        CHECK(par_sghost_count(g) > 0 && par_sghost_count(g) < M - n,
              "%s: ghosts %zu: expected some, not all", what, par_sghost_count(g));

    /* every particle moves by less than skin/2 (the same moves on all ranks) */
    rng_state = 999u + (uint64_t)dim;
    for (int j = 0; j < M; j++) {
        double u[3] = {0, 0, 0}, r2 = 0.0;
        for (int d = 0; d < dim; d++) {
            u[d] = urand() - 0.5;
            r2 += u[d] * u[d];
        }
        double s = 0.49 * skin * urand() / (sqrt(r2) + 1e-300);
        for (int d = 0; d < dim; d++)
            c.x[d][j] += s * u[d];
    }
    n = owned_of(&c, rank, x, gid);
    int rebuild = -1;
    rc = par_sghost_check(g, (const double *const *)x, &rebuild, &err);
    CHECK(!rc && rebuild == 0, "%s: moves < skin/2: rc %d, rebuild %d", what, rc, rebuild);
    par_sghost_update(g, (const double *const *)x);
    /* refreshed positions, and the skin's promise: every pair within the
     * range across ranks has the partner among this rank's ghosts */
    const int64_t *gg = par_sghost_gid(g);
    size_t ng = par_sghost_count(g);
    long pairs = 0;
    for (size_t q = 0; q < ng; q++)
        for (int d = 0; d < dim; d++)
            CHECK(par_sghost_x(g, d)[q] == c.x[d][gg[q]], "%s: refreshed ghost %lld", what,
                  (long long)gg[q]);
    for (size_t i = 0; i < n; i++)
        for (int j = 0; j < M; j++) {
            if (c.owner[j] == rank)
                continue;
            double r2 = 0.0;
            for (int d = 0; d < dim; d++)
                r2 += (c.x[d][j] - x[d][i]) * (c.x[d][j] - x[d][i]);
            if (r2 > range * range)
                continue;
            pairs++;
            size_t lo = 0, hi = ng;
            while (lo < hi) {
                size_t mid = (lo + hi) / 2;
                if (gg[mid] < j)
                    lo = mid + 1;
                else
                    hi = mid;
            }
            CHECK(lo < ng && gg[lo] == j, "%s: pair %lld-%d within range, partner not a ghost",
                  what, (long long)gid[i], j);
        }
    if (size > 1 && !interleave)
        CHECK(par_sum_u64((uint64_t)pairs) > 0, "%s: no cross-rank pairs: the test proves little",
              what);

    /* one particle past skin/2: every rank is asked to rebuild */
    const int mover = M / 2;
    c.x[0][mover] += 0.6 * skin;
    n = owned_of(&c, rank, x, gid);
    rc = par_sghost_check(g, (const double *const *)x, &rebuild, &err);
    CHECK(!rc && rebuild == 1, "%s: move > skin/2: rc %d, rebuild %d", what, rc, rebuild);
    rc = par_sghost_build(g, n, (const double *const *)x, gid, &err);
    CHECK(!rc, "rebuild: %s", err.msg);
    check_against_brute_force(&c, g, range, skin, 0, what);
    rc = par_sghost_check(g, (const double *const *)x, &rebuild, &err);
    CHECK(!rc && rebuild == 0, "%s: after the rebuild: rc %d, rebuild %d", what, rc, rebuild);

    /* one particle past the whole skin: every rank stops, naming it */
    c.x[dim - 1][mover] += 1.5 * skin;
    n = owned_of(&c, rank, x, gid);
    struct spall_error e2 = {0};
    rc = par_sghost_check(g, (const double *const *)x, &rebuild, &e2);
    char want[32];
    snprintf(want, sizeof want, "particle %d moved", mover);
    CHECK(rc == SPALL_ERR_UNSTABLE && strstr(e2.msg, want), "%s: move > skin: rc %d, '%s'",
          what, rc, e2.msg);
    par_sghost_destroy(&g);
    for (int d = 0; d < 3; d++)
        free(x[d]);
    free(gid);
}

/* Mirror planes through the origin (x = 0, and y = 0 in 3D) on a cloud
 * centred on them, split in slabs along x: a rank far from the planes
 * holds the sources of the images that reach it. */
static void run_mirror_case(int dim)
{
    const int size = par_size(), rank = par_rank();
    const unsigned mirror = dim == 3 ? 3u : 1u;
    static struct cloud c;
    make_cloud(&c, dim, 0, size);
    for (int j = 0; j < M; j++)
        for (int d = 0; d < dim; d++)
            c.x[d][j] -= 0.5;
    const double range = dim == 3 ? 0.08 : 0.04, skin = 0.3 * range;
    char what[64];
    snprintf(what, sizeof what, "%dD mirrored", dim);
    double *x[3];
    for (int d = 0; d < 3; d++)
        x[d] = calloc(M, sizeof(double));
    int64_t *gid = calloc(M, sizeof *gid);
    struct par_sghost *g = NULL;
    struct spall_error err = {0};
    int rc = par_sghost_create(&g, dim, range, skin, &err);
    CHECK(!rc, "create: %s", err.msg);
    par_sghost_set_mirror(g, mirror);
    size_t n = owned_of(&c, rank, x, gid);
    rc = par_sghost_build(g, n, (const double *const *)x, gid, &err);
    CHECK(!rc, "build: %s", err.msg);
    check_against_brute_force(&c, g, range, skin, mirror, what);
    /* every image within the range of an owned particle: its source held */
    const int64_t *gg = par_sghost_gid(g);
    const size_t ng = par_sghost_count(g);
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (size_t i = 0; i < n; i++)
        for (int d = 0; d < dim; d++) {
            lo[d] = fmin(lo[d], x[d][i]);
            hi[d] = fmax(hi[d], x[d][i]);
        }
    uint64_t by_image = 0; /* ghosts farther than range + skin from the box themselves */
    for (size_t q = 0; q < ng; q++)
        by_image += dist2_box(&c, (int)gg[q], lo, hi, 0) > (range + skin) * (range + skin);
    for (size_t i = 0; i < n; i++)
        for (int j = 0; j < M; j++)
            for (unsigned mk = 1; mk < 8; mk++) {
                if ((mk & ~mirror) || c.owner[j] == rank)
                    continue;
                double r2 = 0.0;
                for (int d = 0; d < dim; d++) {
                    double u = ((mk >> d & 1u) ? -c.x[d][j] : c.x[d][j]) - x[d][i];
                    r2 += u * u;
                }
                if (r2 > range * range)
                    continue;
                size_t a = 0, b = ng;
                while (a < b) {
                    size_t mid = (a + b) / 2;
                    if (gg[mid] < j)
                        a = mid + 1;
                    else
                        b = mid;
                }
                CHECK(a < ng && gg[a] == j,
                      "%s: image %u of %d within range of %lld, source not a ghost", what, mk, j,
                      (long long)gid[i]);
            }
    if (size > 2)
        CHECK(par_sum_u64(by_image) > 0,
              "%s: no ghost held for its image alone: the test proves little", what);
    par_sghost_destroy(&g);
    for (int d = 0; d < 3; d++)
        free(x[d]);
    free(gid);
}

/* Forced sends (par_sghost_set_forced; TLSPH reference partners behind an
 * interface, spatial.c): particle j is bonded to j ^ 1 (a symmetric bond
 * set, the partners scattered over the cloud); every rank sends its owned
 * particles to the owners of their partners.  The ghost set must be the
 * brute-force set plus the partners held elsewhere, each once, ascending;
 * the next build, without forced sends, the brute-force set again. */
static void run_forced_case(int dim)
{
    const int size = par_size(), rank = par_rank();
    static struct cloud c;
    make_cloud(&c, dim, 0, size);
    const double range = dim == 3 ? 0.08 : 0.04, skin = 0.3 * range;
    char what[64];
    snprintf(what, sizeof what, "%dD forced sends", dim);
    double *x[3];
    for (int d = 0; d < 3; d++)
        x[d] = malloc(M * sizeof(double));
    int64_t *gid = malloc(M * sizeof *gid);
    size_t *idx = malloc(M * sizeof *idx);
    int *to = malloc(M * sizeof *to);
    const size_t n = owned_of(&c, rank, x, gid);
    size_t nf = 0;
    for (size_t i = 0; i < n; i++) {
        const int k = (int)(gid[i] ^ 1);
        if (c.owner[k] != rank) {
            idx[nf] = i;
            to[nf++] = c.owner[k];
        }
    }
    struct spall_error err = {0};
    struct par_sghost *g = NULL;
    int rc = par_sghost_create(&g, dim, range, skin, &err);
    CHECK(!rc, "create: %s", err.msg);
    rc = par_sghost_set_forced(g, nf, idx, to, &err);
    CHECK(!rc, "forced: %s", err.msg);
    rc = par_sghost_build(g, n, (const double *const *)x, gid, &err);
    CHECK(!rc, "build: %s", err.msg);
    double lo[3], hi[3];
    const int any = owned_box(&c, rank, lo, hi);
    const double cut2 = (range + skin) * (range + skin);
    const int64_t *gg = par_sghost_gid(g);
    size_t q = 0, ng = par_sghost_count(g), partner_only = 0;
    for (int j = 0; j < M && any; j++) {
        const int near = dist2_box(&c, j, lo, hi, 0) <= cut2, bonded = c.owner[j ^ 1] == rank;
        if (c.owner[j] == rank || !(near || bonded))
            continue;
        partner_only += !near;
        CHECK(q < ng && gg[q] == j, "%s: ghost %zu should be particle %d (got %lld)", what, q, j,
              q < ng ? (long long)gg[q] : -1LL);
        CHECK(q >= ng || par_sghost_owner(g)[q] == c.owner[j], "%s: ghost %d owner", what, j);
        q++;
    }
    CHECK(q == ng, "%s: %zu ghosts, expected %zu", what, ng, q);
    CHECK(size == 1 || par_sum_u64(partner_only) > 0,
          "%s: no ghost held for its partner alone: the test proves little", what);
    rc = par_sghost_build(g, n, (const double *const *)x, gid, &err);
    CHECK(!rc, "rebuild: %s", err.msg);
    snprintf(what, sizeof what, "%dD after forced sends", dim);
    check_against_brute_force(&c, g, range, skin, 0, what);
    par_sghost_destroy(&g);
    for (int d = 0; d < 3; d++)
        free(x[d]);
    free(gid);
    free(idx);
    free(to);
}

int main(int argc, char **argv)
{
    if (par_world_init(&argc, &argv))
        return 1;
    for (int dim = 2; dim <= 3; dim++)
        for (int inter = 0; inter <= 1; inter++)
            run_case(dim, inter);
    for (int dim = 2; dim <= 3; dim++)
        run_mirror_case(dim);
    for (int dim = 2; dim <= 3; dim++)
        run_forced_case(dim);
    int total = (int)par_sum_u64((uint64_t)failures);
    if (par_rank() == 0)
        printf("test_par_sghost: %d ranks, %s\n", par_size(), total ? "FAILED" : "ok");
    par_world_finalize();
    return total ? 1 : 0;
}
