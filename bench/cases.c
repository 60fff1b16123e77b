/**
 * @file cases.c
 * @brief Registry of `spall bench` cases: concatenates the per-model tables
 *        (one line per model) into one list.
 */
#include "bench/bench.h"

#include <stdlib.h>

struct bench_table {
    const struct bench_case *cases;
    const size_t *n;
};

static const struct bench_table tables[] = {
    {bench_lattice_cases, &bench_lattice_n_cases},
    /* impact table entry */
    {bench_impact_cases, &bench_impact_n_cases},

    /* peridynamics table entry */
    {bench_pd_cases, &bench_pd_n_cases},

    /* macro-particle table entry */
    {bench_macro_cases, &bench_macro_n_cases},

    /* sph table entry */
    {bench_sph_cases, &bench_sph_n_cases},
    {bench_pen_cases, &bench_pen_n_cases},

};


/* A flat copy would need storage; instead index through the tables. */
const struct bench_case *bench_case_at(size_t k)
{
    for (size_t t = 0; t < sizeof tables / sizeof tables[0]; t++) {
        if (k < *tables[t].n)
            return &tables[t].cases[k];
        k -= *tables[t].n;
    }
    return NULL;
}

size_t bench_case_count(void)
{
    size_t n = 0;
    for (size_t t = 0; t < sizeof tables / sizeof tables[0]; t++)
        n += *tables[t].n;
    return n;
}
