/**
 * @file setup_check.c
 * @brief Unit-slip refusals for material constants (issue 24 item 1).
 *
 * Why: a density in g/cm^3 (1.1 for epoxy) or a modulus in GPa (3.26) is a
 * valid positive number, so the deck reader accepts it, and the run goes on
 * with a stable step off by orders of magnitude.  The bounds below enclose
 * every real solid by a wide margin (densities from foams, ~10 kg/m^3, to
 * osmium, 22 590 kg/m^3; moduli from soft gels, ~1 kPa, to diamond,
 * 1.2e12 Pa), so only slips trip them.
 */
#include "io/setup_check.h"

#include "core/options.h"
#include "spall/error.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

struct range {
    const char *key;
    double lo, hi;
    const char *unit;
    const char *slip; /* the likely slip when the value is below lo */
};

static const struct range ranges[] = {
    {"density", 10.0, 3.0e4, "kg/m^3", "a density in g/cm^3 (multiply by 1000)"},
    {"youngs_modulus", 1.0e3, 2.0e12, "Pa", "a modulus in GPa or MPa (multiply by 1e9 or 1e6)"},
    {"bulk_modulus", 1.0e3, 2.0e12, "Pa", "a modulus in GPa or MPa (multiply by 1e9 or 1e6)"},
    {"shear_modulus", 1.0e2, 2.0e12, "Pa", "a modulus in GPa or MPa (multiply by 1e9 or 1e6)"},
    {"tensile_strength", 1.0e2, 1.0e11, "Pa", "a strength in MPa (multiply by 1e6)"},
    {"yield_stress", 1.0e2, 1.0e11, "Pa", "a strength in MPa (multiply by 1e6)"},
};

int setup_check_units(const struct deck *d, struct spall_error *err)
{
    const struct deck_node *mats = d && d->root ? deck_peek(d->root, "materials") : NULL;
    if (!mats || mats->kind != DECK_MAPPING)
        return SPALL_OK; /* the deck builder reports a missing section */
    for (size_t m = 0; m < mats->n; m++) {
        const struct deck_node *mat = mats->items[m];
        if (mat->kind != DECK_MAPPING)
            continue;
        for (size_t r = 0; r < sizeof ranges / sizeof ranges[0]; r++) {
            const struct deck_node *v = deck_peek(mat, ranges[r].key);
            if (!v || v->kind != DECK_SCALAR)
                continue;
            char *end = NULL;
            double x = strtod(v->scalar, &end);
            if (end == v->scalar || *end || !(x > 0.0))
                continue; /* not a positive number: the typed getters refuse it */
            if (x >= ranges[r].lo && x <= ranges[r].hi)
                continue;
            int rc = deck_error(err, v,
                       "material '%s': %s = %g %s is outside the range of real solids "
                       "[%g, %g] %s; likely cause: %s (spall takes SI units)",
                       mats->keys[m], ranges[r].key, x, ranges[r].unit, ranges[r].lo,
                       ranges[r].hi, ranges[r].unit,
                       x < ranges[r].lo ? ranges[r].slip : "a value in the wrong unit");
            if (!err)
                return rc;
            char key[SPALL_ERROR_KEY_LEN];
            if ((size_t)snprintf(key, sizeof key, "materials.%s.%s", mats->keys[m],
                                 ranges[r].key) < sizeof key)
                memcpy(err->key, key, sizeof key);
            return rc;
        }
    }
    return SPALL_OK;
}
