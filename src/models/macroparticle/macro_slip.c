/**
 * @file macro_slip.c
 * @brief Centro-symmetry, slip vectors and slip-plane normals of the FCC
 *        macro-particle lattice (definitions in macro_slip.h).
 */
#include "core/mathconst.h"
#include "models/macroparticle/macro_slip.h"

#include "core/neighbor.h"
#include "spall/error.h"

#include <math.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#define SLIP_OMP_MIN 2048

void macro_centro_symmetry(size_t n, double *const x[3], const struct neighbor_list *cur,
                           double r0, double *csp)
{
#pragma omp parallel for schedule(static) if (n >= SLIP_OMP_MIN)
    for (size_t i = 0; i < n; i++) {
        /* the 12 nearest partners by insertion into a sorted buffer */
        double r[12][3], d2[12];
        int m = 0;
        for (size_t s = cur->offset[i]; s < cur->offset[i + 1]; s++) {
            size_t j = (size_t)cur->idx[s];
            double u[3], q = 0.0;
            for (int d = 0; d < 3; d++) {
                u[d] = x[d][j] - x[d][i];
                q += u[d] * u[d];
            }
            if (m == 12 && q >= d2[11])
                continue;
            int k = m < 12 ? m++ : 11;
            while (k > 0 && d2[k - 1] > q) {
                d2[k] = d2[k - 1];
                memcpy(r[k], r[k - 1], sizeof r[k]);
                k--;
            }
            d2[k] = q;
            memcpy(r[k], u, sizeof u);
        }
        /* the m/2 smallest of the m(m-1)/2 pair sums, by partial selection */
        double best[6];
        int nb = 0, want = m / 2;
        for (int a = 0; a < m; a++)
            for (int b = a + 1; b < m; b++) {
                double q = 0.0;
                for (int d = 0; d < 3; d++) {
                    double w = r[a][d] + r[b][d];
                    q += w * w;
                }
                if (nb == want && (want == 0 || q >= best[nb - 1]))
                    continue;
                int k = nb < want ? nb++ : want - 1;
                while (k > 0 && best[k - 1] > q) {
                    best[k] = best[k - 1];
                    k--;
                }
                best[k] = q;
            }
        double c = 0.0;
        for (int k = 0; k < nb; k++)
            c += best[k];
        csp[i] = c / (r0 * r0) + (double)(12 - 2 * want);
    }
}

void macro_slip_vectors(size_t n, double *const x[3], double *const x0[3],
                        const struct neighbor_list *ref, double thr, double *slip,
                        double *normal, int *n_slipped)
{
    const double thr2 = thr * thr;
#pragma omp parallel for schedule(static) if (n >= SLIP_OMP_MIN)
    for (size_t i = 0; i < n; i++) {
        double sv[3] = {0, 0, 0}, nm[3] = {0, 0, 0}, blen = 0.0;
        int ns = 0;
        for (size_t s = ref->offset[i]; s < ref->offset[i + 1]; s++) {
            size_t j = (size_t)ref->idx[s];
            double du[3], q = 0.0, b[3], bb = 0.0;
            for (int d = 0; d < 3; d++) {
                b[d] = x0[d][j] - x0[d][i];
                du[d] = (x[d][j] - x[d][i]) - b[d];
                q += du[d] * du[d];
                bb += b[d] * b[d];
            }
            if (q <= thr2)
                continue;
            ns++;
            blen += sqrt(bb);
            for (int d = 0; d < 3; d++) {
                sv[d] -= du[d];
                nm[d] += b[d];
            }
        }
        double nl = sqrt(nm[0] * nm[0] + nm[1] * nm[1] + nm[2] * nm[2]);
        /* one slipped (111) layer: 3 partners whose mean bond is sqrt(2/3)
         * = 0.82 of a bond, along the normal.  Fewer than 3 partners (a
         * dislocation core, a surface step) or a mean below 0.35 of a bond
         * (partners on both sides) carry no plane: normal 0 (unclear) */
        const bool plane = ns >= 3 && nl > 0.35 * blen; /* |sum|/ns > 0.35 blen/ns */
        for (int d = 0; d < 3; d++) {
            if (slip)
                slip[3 * i + d] = ns ? sv[d] / ns : 0.0;
            if (normal)
                normal[3 * i + d] = plane ? nm[d] / nl : 0.0;
        }
        if (n_slipped)
            n_slipped[i] = ns;
    }
}

int macro_slip_analyse(size_t n, double *const x[3], double *const x0[3], double r0, double thr,
                       double tol_deg, struct macro_slip_stats *out, struct spall_error *err)
{
    memset(out, 0, sizeof *out);
    out->n = n;
    struct neighbor_list *ref = NULL, *cur = NULL;
    double *csp = calloc(n ? n : 1, sizeof *csp), *nrm = calloc(3 * (n ? n : 1), sizeof *nrm);
    int *ns = calloc(n ? n : 1, sizeof *ns);
    int rc = SPALL_OK;
    if (!csp || !nrm || !ns) {
        rc = spall_error_set(err, SPALL_ERR_NOMEM, "out of memory (slip analysis)");
        goto done;
    }
    if ((rc = neighbor_list_build_pairs(&ref, NULL, 3, n, x0, 1.1 * r0, err)) ||
        (rc = neighbor_list_build_pairs(&cur, NULL, 3, n, x, 1.5 * r0, err)))
        goto done;
    macro_centro_symmetry(n, x, cur, r0, csp);
    macro_slip_vectors(n, x, x0, ref, thr, NULL, nrm, ns);
    static const double fam111[4][3] = {{1, 1, 1}, {1, 1, -1}, {1, -1, 1}, {-1, 1, 1}};
    static const double fam100[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    static const double fam110[6][3] = {{1, 1, 0}, {1, -1, 0}, {1, 0, 1},
                                        {1, 0, -1}, {0, 1, 1}, {0, 1, -1}};
    const double ct = cos(tol_deg * SPALL_PI / 180.0);
    double cs = 0.0;
    size_t nfull = 0;
    for (size_t i = 0; i < n; i++) {
        if (ref->offset[i + 1] - ref->offset[i] == 12) {
            cs += csp[i];
            nfull++;
            out->n_fault += csp[i] >= 0.5 && csp[i] < 2.0;
        }
        if (ns[i] == 0)
            continue;
        out->n_slipped++;
        const double *u = nrm + 3 * i;
        if (u[0] == 0.0 && u[1] == 0.0 && u[2] == 0.0) {
            out->n_unclear++;
            continue;
        }
        bool done_i = false;
        for (int k = 0; k < 4 && !done_i; k++) {
            double c = fabs(u[0] * fam111[k][0] + u[1] * fam111[k][1] + u[2] * fam111[k][2]) /
                       sqrt(3.0);
            if (c >= ct) {
                out->n_111[k]++;
                done_i = true;
            }
        }
        for (int k = 0; k < 3 && !done_i; k++)
            if (fabs(u[0] * fam100[k][0] + u[1] * fam100[k][1] + u[2] * fam100[k][2]) >= ct) {
                out->n_100++;
                done_i = true;
            }
        for (int k = 0; k < 6 && !done_i; k++)
            if (fabs(u[0] * fam110[k][0] + u[1] * fam110[k][1] + u[2] * fam110[k][2]) /
                    sqrt(2.0) >= ct) {
                out->n_110++;
                done_i = true;
            }
        if (!done_i)
            out->n_other++;
    }
    out->csp_mean = nfull ? cs / (double)nfull : 0.0;
done:
    neighbor_list_destroy(&ref);
    neighbor_list_destroy(&cur);
    free(csp);
    free(nrm);
    free(ns);
    return rc;
}
