/**
 * @file bond_list.h
 * @brief Fixed bond lists (lattice springs, peridynamic families) in CSR form.
 *
 * Every bond i-j is stored twice, once in i's row and once in j's row
 * ("half-bonds"), so force loops gather per particle without atomics and the
 * result does not depend on the thread count.  Decisions taken on a bond
 * (breaking) are computed identically from both ends because
 * |x_j - x_i| == |x_i - x_j| bit for bit.
 * Per-half-bond data: partner index, reference length, state flags and a
 * model-defined type (e.g. neighbour shell, fiber/matrix).  `reverse[k]` is
 * the slot of the same bond in the partner's row (built on demand).
 */
#ifndef SPALL_BOND_LIST_H
#define SPALL_BOND_LIST_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

struct particles;
struct precrack;
struct spall_error;

enum bond_state_flags {
    BOND_BROKEN = 1u << 0,  /**< broken: no attraction, repulsion only */
    BOND_PRECUT = 1u << 1   /**< removed by a pre-crack before the run */
};

struct bond_list {
    size_t n;           /**< particles */
    size_t *offset;     /**< n+1 */
    int32_t *partner;   /**< local index of the partner */
    double *rest;       /**< reference length |x0_j - x0_i| [m]; NULL once compacted here
                             (rest_idx) or kept by a model elsewhere (peridynamics'
                             compact families, pd_compact.c) */
    uint16_t *rest_idx; /**< compacted (bond_list_compact_rest): rest length =
                             rest_tab[rest_idx[k]]; NULL otherwise */
    double *rest_tab;   /**< the distinct rest lengths, n_rest of them */
    size_t n_rest;
    uint8_t *state;     /**< enum bond_state_flags */
    uint8_t *type;      /**< model-defined; NULL as rest */
    size_t *reverse;    /**< optional: slot of j->i for slot i->j (NULL until built) */
    unsigned long gen;  /**< incremented whenever bond_list_replace swaps the arrays
                             (localize, migration), so that a model may cache what it
                             learnt about the rows (lattice_half.c) */
};

/** Reference length of half-bond @p k (either storage). */
static inline double bond_rest(const struct bond_list *bl, size_t k)
{
    return bl->rest_idx ? bl->rest_tab[bl->rest_idx[k]] : bl->rest[k];
}

/** Store the rest lengths as a 16-bit index into a table of their distinct
 *  values (the same doubles, bit for bit) when there are at most 65 536 of
 *  them, as on a regular lattice: 2 instead of 8 bytes per half-bond.  Only
 *  for a list whose rest lengths no longer change (not the thermal
 *  lattice's).  Leaves the list as it is when there are more distinct
 *  values; an error only when out of memory. */
int bond_list_compact_rest(struct bond_list *bl, struct spall_error *err);

/** The rows a localised list kept, in the old list's numbering, for the
 *  model's per-half-bond arrays (bond_rows_gather): row k < n_owned of the
 *  new list is the old row keep[k], whose slots started at
 *  old_offset[keep[k]]; ghosts' rows are empty.  A row map instead of an
 *  old index per kept half-bond (8 B each, the distributed set-up's peak,
 *  docs/performance.md "State-based PD: distributed set-up memory"). */
struct bond_rows {
    size_t *old_offset;  /**< the old list's offsets (owned: bond_rows_free) */
    const size_t *keep;  /**< the caller's keep[0..n_owned) */
    size_t n_owned;
    size_t n_half;       /**< kept half-bonds: the new list's offset[n] */
    bool ascending;      /**< keep[0..n_owned) ascending: rows move in place */
};

/** Distributed runs (model_ops.localize): keep the rows of particles
 *  keep[0..n_owned) in their order, partners renumbered by @p new_of_old,
 *  and give keep[n_owned..n_keep) (the ghosts) empty rows; the reverse map
 *  is dropped.  When keep[0..n_owned) is ascending (both set-ups) the
 *  arrays are compacted in place and shrunk, so the old and the new list
 *  never coexist.  The struct keeps its address (the restart registry
 *  holds its members').  @p rows (bond_rows_free it; it reads @p keep)
 *  maps the kept half-bonds to their old slots for bond_rows_gather of the
 *  model's per-half-bond arrays. */
int bond_list_localize(struct bond_list *bl, const size_t *keep, size_t n_keep, size_t n_owned,
                       const int64_t *new_of_old, struct bond_rows *rows,
                       struct spall_error *err);

/** A new array (free it) of the kept rows of @p a (elements of @p size
 *  bytes, one per old half-bond), in the new list's slot order; NULL when
 *  out of memory. */
void *bond_rows_gather(const struct bond_rows *r, const void *a, size_t size);
/** The kept rows of @p a (as bond_rows_gather) in its place: when the rows
 *  are ascending they are moved within @p a and the block shrunk (the old
 *  and the new array never coexist: the distributed set-up's peak), else a
 *  gathered copy and @p a freed.  NULL when out of memory, @p a then
 *  untouched and still the caller's. */
void *bond_rows_take(const struct bond_rows *r, void *a, size_t size);
/** Free the row map's old offsets. */
void bond_rows_free(struct bond_rows *r);

/** Replace the list's arrays by new ones for @p n particles (taken over;
 *  the old ones and the reverse map are freed; the compact rest table
 *  stays: it holds every value a kept index names).  The struct keeps its
 *  address (distributed runs: localize and migration).  Exactly one of
 *  @p rest and @p rest_idx is set when the list has bonds. */
void bond_list_replace(struct bond_list *bl, size_t n, size_t *offset, int32_t *partner,
                       double *rest, uint16_t *rest_idx, uint8_t *state, uint8_t *type);

/** A new array (free it) of a[idx[0..n)], elements of @p size bytes; NULL
 *  when out of memory. */
void *array_gather(const void *a, size_t size, const size_t *idx, size_t n);

/** Build from reference positions: a bond for every pair closer than
 *  @p radius (cell list search).  type = 0 for all. */
int bond_list_build(struct bond_list **out, const struct particles *p, double radius,
                    struct spall_error *err);
/** bond_list_build with the rest lengths stored compact from the start
 *  (rest_idx and rest_tab as bond_list_compact_rest makes them, the doubles
 *  when there are more than 65 536 distinct lengths) and no type array: the
 *  set-up never holds the 8-byte lengths (peak memory, docs/performance.md
 *  "Set-up peak memory").  The same bonds, lengths and table. */
int bond_list_build_compact(struct bond_list **out, const struct particles *p, double radius,
                            struct spall_error *err);
/** Back to one double per half-bond (rest) from a compact list; nothing to
 *  do on a list that has its doubles. */
int bond_list_expand_rest(struct bond_list *bl, struct spall_error *err);
/** Free the rest lengths of every form (doubles, compact indices and their
 *  table): for a model that keeps them itself (peridynamics' tables). */
void bond_list_drop_rest(struct bond_list *bl);
/** Build bonds only for pairs whose reference distance lies in one of the
 *  shells [r_lo[s], r_hi[s]); type = s.  Used for lattice neighbour layers. */
int bond_list_build_shells(struct bond_list **out, const struct particles *p, int n_shells,
                           const double *r_lo, const double *r_hi, struct spall_error *err);
/** bond_list_build_shells with the rest lengths compact from the start, as
 *  bond_list_build_compact (types kept): for lists whose lengths never
 *  change. */
int bond_list_build_shells_compact(struct bond_list **out, const struct particles *p,
                                   int n_shells, const double *r_lo, const double *r_hi,
                                   struct spall_error *err);
void bond_list_destroy(struct bond_list **bl);

/** Slot of partner @p who in row @p j (rows are sorted), or SIZE_MAX. */
size_t bond_list_slot(const struct bond_list *bl, size_t j, int32_t who);
/** Build the reverse-slot index (needed by angular springs). */
int bond_list_build_reverse(struct bond_list *bl, struct spall_error *err);

/** Mark BROKEN|PRECUT every bond crossing the pre-crack (both halves);
 *  returns the number of bonds cut (each counted once). */
size_t bond_list_apply_precrack(struct bond_list *bl, const struct particles *p,
                                const struct precrack *c);

/** Number of bonds, each counted once (half-bonds / 2). */
size_t bond_list_count(const struct bond_list *bl);
/** Number of broken bonds, each counted once. */
size_t bond_list_count_broken(const struct bond_list *bl);

/** Bytes used by the list (for memory reports). */
size_t bond_list_bytes(const struct bond_list *bl);

#endif
