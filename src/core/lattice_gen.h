/**
 * @file lattice_gen.h
 * @brief Lattice generators that fill a geometry with particle sites.
 *
 * 1D chain (along x), 2D triangular (rows along x rotated by `angle`) and
 * square, 3D simple cubic and FCC.  `spacing` is the nearest-neighbour
 * distance r0 for every kind (for FCC the cubic cell edge is sqrt(2) r0).
 * Sites are generated on the lattice anchored at `origin`, kept when inside
 * the region, and appended in a deterministic order (row-major), which keeps
 * neighbours close in memory.
 */
#ifndef SPALL_LATTICE_GEN_H
#define SPALL_LATTICE_GEN_H

#include <stddef.h>
#include <stdint.h>

struct geom;
struct particles;
struct spall_error;

/** LATTICE_TRIPLE_HONEYCOMB has the sites of the triangular lattice; its
 *  bonds fall into three honeycomb families by the sublattices they join
 *  (Ostoja-Starzewski's alpha-beta-gamma model, see lattice_sublattice). */
enum lattice_kind {
    LATTICE_CHAIN,
    LATTICE_TRIANGULAR,
    LATTICE_SQUARE,
    LATTICE_SC,
    LATTICE_FCC,
    LATTICE_TRIPLE_HONEYCOMB,
    LATTICE_RINGS, /**< 2D concentric rings around the origin (core/lattice_polar.h) */
    LATTICE_SHELLS /**< 3D concentric spherical shells around the origin */
};

/** Refuse to enumerate more candidate sites than this (a typo in a spacing):
 *  1000 x SPALL_MAX_PARTICLES_DEFAULT.  Measured (2026-12-02, Release, one thread):
 *  1.85e9 candidates of a thin 2D frame in 3.7 s, so <= ~20 s here (4e10
 *  before: ~80 s of set-up, a hang to the user). */
#define LATTICE_MAX_CANDIDATES 1.0e10

struct lattice_spec {
    enum lattice_kind kind;
    double spacing;    /**< nearest-neighbour distance r0 [m] */
    double origin[3];  /**< a lattice site sits here [m] */
    double angle;      /**< 2D: rotation of the lattice about z [rad] */
};

/** Parse "chain", "triangular", "square", "sc", "fcc", "triple_honeycomb",
 *  "rings", "shells";
 *  returns -1 if unknown. */
int lattice_kind_from_name(const char *name);
const char *lattice_kind_name(enum lattice_kind kind);
/** NULL-terminated names of every lattice kind, in the order of enum
 *  lattice_kind (the deck's lattice.type values). */
const char *const *lattice_kind_names(void);
/** Spatial dimension of a lattice kind (1, 2 or 3). */
int lattice_kind_dim(enum lattice_kind kind);

/** Append every lattice site inside @p region to @p p with material @p material.
 *  Fails with SPALL_ERR_INPUT if the region is unbounded, or contains no site
 *  ("geometry 'name' contains no lattice site": the caller adds the name). */
int lattice_fill(struct particles *p, const struct lattice_spec *spec, const struct geom *region,
                 int32_t material, size_t *n_added, struct spall_error *err);

/** Distributed set-up (core/parallel/setup_dist.h): one rank's share of a
 *  fill.  The outer index layers of the generation (the last lattice
 *  axis: k in 3D, rows j in 2D) are split into @p size contiguous blocks
 *  balanced by site count; a rank generates its block plus @p halo metres
 *  of whole layers on either side, in the serial generation order, so the
 *  serial index of its first site is gid_first and its sites keep the
 *  serial order. */
struct lattice_window {
    int rank, size;    /**< in: this rank, of how many */
    double halo;       /**< in: halo depth [m] on either side of the block */
    size_t n_prior;    /**< in: particles of the earlier fills in the serial
                            set-up (their windows hold fewer): the limit */
    int64_t gid_first; /**< out: index of the first site appended among the
                            region's sites (the serial index less n_prior) */
    size_t n_below;    /**< out: halo sites before the rank's own block */
    size_t n_own;      /**< out: sites of the rank's own block */
    size_t n_total;    /**< out: sites of the whole region */
};

/** Split @p n_layers layers of cnt[l] sites into @p size contiguous blocks
 *  balanced by count: rank r holds layers [first[r], first[r+1]) (@p first
 *  has size + 1 entries; first[0] = 0, first[size] = n_layers). */
void lattice_split_layers(const size_t *cnt, size_t n_layers, int size, size_t *first);

/** lattice_fill restricted to one rank's window (above); every rank counts
 *  the whole region (positions only, nothing stored), so the particle
 *  limit and "contains no lattice site" are decided on the whole body, the
 *  same on every rank.  Not for rings and shells (SPALL_ERR_INTERNAL). */
int lattice_fill_window(struct particles *p, const struct lattice_spec *spec,
                        const struct geom *region, int32_t material, struct lattice_window *w,
                        struct spall_error *err);

/** Append one site at @p pos (for the fill implementations): refused once
 *  the run holds @p limit particles (run.max_particles). */
int lattice_append_site(struct particles *p, const double pos[3], int32_t material, double limit,
                        double spacing, struct spall_error *err);

/** Distance of the k-th neighbour shell (k = 1 nearest, 2 second...). */
double lattice_shell_distance(const struct lattice_spec *spec, int shell);
/** Number of neighbours in shell k of a bulk site. */
int lattice_shell_count(enum lattice_kind kind, int shell);

/** Sublattice (0, 1 or 2) of the site nearest to @p pos on a triangular or
 *  triple-honeycomb lattice: the three interpenetrating triangular
 *  sublattices of spacing sqrt3 r0, numbered so that the step +r0 along the
 *  lattice's x axis goes from sublattice c to c+1 (mod 3).  Nearest
 *  neighbours are always on different sublattices; the bonds joining
 *  sublattices a and b form one honeycomb lattice, and the three of them
 *  (family 3 - a - b) make the "triple honeycomb".  -1 for other kinds. */
int lattice_sublattice(const struct lattice_spec *spec, const double pos[2]);

/** Volume per site [m^3].  2D kinds need the plate thickness t (> 0);
 *  1D needs the cross-section area passed as thickness_or_area.  For rings
 *  and shells the nominal dx^2 t or dx^3 (sites differ: see below). */
double lattice_site_volume(const struct lattice_spec *spec, double thickness_or_area);
/** Volume of the site at @p pos: lattice_site_volume, except on rings and
 *  shells, whose sites own their layer's share (lattice_polar_site_volume). */
double lattice_site_volume_at(const struct lattice_spec *spec, const double pos[3],
                              double thickness_or_area);

#endif
