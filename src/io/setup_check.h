/**
 * @file setup_check.h
 * @brief Checks of a deck's set-up before anything is built or written
 *        (issue 24 item 1): material constants outside the range of real
 *        solids, the usual sign of a unit slip (g/cm^3, GPa, MPa).
 */
#ifndef SPALL_SETUP_CHECK_H
#define SPALL_SETUP_CHECK_H

struct deck;
struct spall_error;

/** Refuse (SPALL_ERR_INPUT, message "FILE:LINE:COL: ...", err->key the key
 *  path "materials.NAME.KEY") a material density, elastic modulus or
 *  strength outside the range of real solids, naming the likely unit slip.
 *  SPALL_OK when the deck has nothing suspicious. */
int setup_check_units(const struct deck *d, struct spall_error *err);

#endif
