/**
 * @file deck_contact.c
 * @brief `contact:` — particle-particle contact between bodies and between
 *        unbonded particles (core/contact_particles.h):
 *
 *   contact: {distance: 2.0e-4, stiffness: 3.26e7, exponent: 1}
 *
 * Every key is checked; errors name file:line:column.
 */
#include "io/deck_contact.h"

#include "core/contact_particles.h"
#include "core/sim.h"
#include "io/deck.h"
#include "spall/error.h"

#include <math.h>
#include <stdio.h>

int deck_parse_contact(struct sim *s, const struct deck_node *root, struct spall_error *err)
{
    static const char *const keys[] = {"distance", "stiffness", "exponent", NULL};
    const struct deck_node *n = deck_get(root, "contact");
    if (!n)
        return SPALL_OK;
    struct particle_contact_params prm = {0.0, 0.0, 1.0};
    int rc;
    if ((rc = deck_expect_map(n, "a contact mapping (distance, stiffness, exponent)", err)) ||
        (rc = deck_double_pos(n, "distance", true, &prm.distance, err)) ||
        (rc = deck_double_pos(n, "stiffness", true, &prm.stiffness, err)) ||
        (rc = deck_double(n, "exponent", false, 1.0, 2.0, &prm.exponent, err)) ||
        (rc = deck_check_unused(n, "contact", keys, err)))
        return rc;
    particle_contact_destroy(&s->pcontact);
    if ((rc = particle_contact_create(&s->pcontact, &prm, err))) {
        char msg[SPALL_ERROR_MSG_LEN];
        snprintf(msg, sizeof msg, "%s", err->msg);
        deck_error(err, n, "%s", msg);
        err->code = rc;
        return rc;
    }
    return SPALL_OK;
}
