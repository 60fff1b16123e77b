/**
 * @file bandwidth.c
 * @brief Memory-bandwidth probe behind the lattice roofline
 *        (docs/performance.md, "Roofline of the lattice step"): simple
 *        kernels over arrays of several sizes, to tell write-allocate
 *        traffic and the reach of the shared L3 apart.  A standalone
 *        program, not part of the build (CMake globs bench/ only, not its
 *        subfolders):
 *
 *            cc -std=c11 -O3 -march=x86-64-v2 -fopenmp bench/probe/bandwidth.c -o bandwidth
 *            ./bandwidth [threads [rounds]]
 *
 * Every (size, kernel) cell is timed in shuffled rounds (a loaded machine
 * then hits each cell in different moments) and the best is printed, in
 * STREAM's count: 8 B per array an element reads or writes, no
 * write-allocate traffic.  A normal store to a line not in the cache reads
 * that line first, so where the bandwidth is the limit the plain write,
 * copy and triad show less than their non-temporal forms (which skip the
 * read) by 16/8, 24/16 and 32/24, and "a += q b" (its stores hit lines it
 * has read: 24 B real) matches the non-temporal triad.
 */
#include <emmintrin.h>
#include <omp.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

enum kernel { RD, WR, WRNT, COPY, COPYNT, TRIAD, TRIADNT, UPD, NK };
static const char *const kernel_name[NK] = {"read",  "write", "wr-nt", "copy",
                                            "cp-nt", "triad", "tr-nt", "update"};
/* STREAM's bytes per element */
static const double kernel_bytes[NK] = {8, 8, 8, 16, 16, 24, 24, 24};

/* One sweep of kernel @p k over [0, n) (n a multiple of 8, the arrays
 * 16-byte aligned); returns a sum of what a read-only kernel read. */
static double sweep(int k, double *restrict a, const double *restrict b,
                    const double *restrict c, size_t n)
{
    const double q = 3.0;
    switch (k) {
    case RD: { /* four vector sums: latency would bound one */
        __m128d s0 = _mm_setzero_pd(), s1 = s0, s2 = s0, s3 = s0;
        for (size_t i = 0; i < n; i += 8) {
            s0 = _mm_add_pd(s0, _mm_load_pd(b + i));
            s1 = _mm_add_pd(s1, _mm_load_pd(b + i + 2));
            s2 = _mm_add_pd(s2, _mm_load_pd(b + i + 4));
            s3 = _mm_add_pd(s3, _mm_load_pd(b + i + 6));
        }
        double t[2];
        _mm_storeu_pd(t, _mm_add_pd(_mm_add_pd(s0, s1), _mm_add_pd(s2, s3)));
        return t[0] + t[1];
    }
    case WR:
        for (size_t i = 0; i < n; i++)
            a[i] = q;
        break;
    case WRNT: {
        const __m128d v = _mm_set1_pd(q);
        for (size_t i = 0; i < n; i += 2)
            _mm_stream_pd(a + i, v);
        _mm_sfence();
        break;
    }
    case COPY:
        for (size_t i = 0; i < n; i++)
            a[i] = b[i];
        break;
    case COPYNT:
        for (size_t i = 0; i < n; i += 2)
            _mm_stream_pd(a + i, _mm_load_pd(b + i));
        _mm_sfence();
        break;
    case TRIAD:
        for (size_t i = 0; i < n; i++)
            a[i] = b[i] + q * c[i];
        break;
    case TRIADNT: {
        const __m128d qq = _mm_set1_pd(q);
        for (size_t i = 0; i < n; i += 2)
            _mm_stream_pd(a + i,
                          _mm_add_pd(_mm_load_pd(b + i), _mm_mul_pd(qq, _mm_load_pd(c + i))));
        _mm_sfence();
        break;
    }
    default: /* UPD */
        for (size_t i = 0; i < n; i++)
            a[i] += q * b[i];
        break;
    }
    return 0.0;
}

/* Array sizes [MiB per array]. */
#define N_SIZES 8
static const size_t size_mib[N_SIZES] = {8, 16, 24, 32, 48, 64, 128, 512};

int main(int argc, char **argv)
{
    const int threads = argc > 1 ? atoi(argv[1]) : 1, rounds = argc > 2 ? atoi(argv[2]) : 5;
    if (threads < 1 || rounds < 1) {
        fprintf(stderr, "usage: bandwidth [threads [rounds]]\n");
        return 2;
    }
    omp_set_num_threads(threads);
    double best[N_SIZES][NK] = {{0.0}}, keep = 0.0;
    for (int r = 0; r < rounds; r++)
        for (int s0 = 0; s0 < N_SIZES; s0++) {
            const int s = (s0 + 3 * r) % N_SIZES;
            const size_t n = size_mib[s] << 17; /* doubles */
            double *a = aligned_alloc(64, n * sizeof *a), *b = aligned_alloc(64, n * sizeof *b),
                   *c = aligned_alloc(64, n * sizeof *c);
            if (!a || !b || !c) {
                fprintf(stderr, "out of memory at %zu MiB per array\n", size_mib[s]);
                return 1;
            }
#pragma omp parallel for schedule(static)
            for (size_t i = 0; i < n; i++) { /* first touch by the sweeping thread */
                a[i] = 0.0;
                b[i] = 1.0;
                c[i] = 2.0;
            }
            const int reps = size_mib[s] < 170 ? (int)(512 / size_mib[s]) : 3;
            for (int k0 = 0; k0 < NK; k0++) {
                const int k = (k0 + r + s) % NK;
                for (int rep = 0; rep < reps; rep++) {
                    const double t0 = omp_get_wtime();
#pragma omp parallel reduction(+ : keep)
                    {
                        /* static shares, cut at multiples of 8 elements */
                        const size_t nt = (size_t)omp_get_num_threads();
                        const size_t t = (size_t)omp_get_thread_num();
                        const size_t lo = (n * t / nt) & ~(size_t)7;
                        const size_t hi = t + 1 == nt ? n : (n * (t + 1) / nt) & ~(size_t)7;
                        keep += sweep(k, a + lo, b + lo, c + lo, hi - lo);
                    }
                    const double dt = omp_get_wtime() - t0;
                    const double bw = dt > 0.0 ? 1e-9 * kernel_bytes[k] * (double)n / dt : 0.0;
                    if (bw > best[s][k])
                        best[s][k] = bw;
                }
            }
            free(a);
            free(b);
            free(c);
        }
    printf("threads %d, best of %d rounds, GB/s in STREAM's count (no write-allocate)\n",
           threads, rounds);
    printf("MiB/array");
    for (int k = 0; k < NK; k++)
        printf(" %7s", kernel_name[k]);
    printf("\n");
    for (int s = 0; s < N_SIZES; s++) {
        printf("%9zu", size_mib[s]);
        for (int k = 0; k < NK; k++)
            printf(" %7.1f", best[s][k]);
        printf("\n");
    }
    return keep < 0.0; /* the read kernel's sums are used */
}
