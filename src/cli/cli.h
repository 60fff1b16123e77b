/** @file cli.h @brief Sub-commands of the `spall` program. */
#ifndef SPALL_CLI_H
#define SPALL_CLI_H

int cli_run(int argc, char **argv);
int cli_validate(int argc, char **argv);
int cli_bench(int argc, char **argv);
int cli_calibrate(int argc, char **argv);
/** `spall penetrate`: analytical penetration models (src/cli/cmd_penetrate.c). */
int cli_penetrate(int argc, char **argv);
/** `spall calibrate macroparticle` (cmd_calibrate_macro.c). */
int cli_calibrate_macroparticle(int argc, char **argv);
/** `spall calibrate peridynamics ...` (src/cli/cmd_calibrate_pd.c). */
int cli_calibrate_peridynamics(int argc, char **argv);
/** `spall calibrate DECK.yaml` and `spall calibrate sph ...`
 *  (cmd_calibrate_deck.c): the constants and time step of the simulation as
 *  `spall run` builds it. */
int cli_calibrate_deck(const char *path);
int cli_calibrate_sph(int argc, char **argv);
int cli_render(int argc, char **argv);

/** Map a libspall status to the process exit status: bad input 2,
 *  unstable run 3, I/O 4, anything else 1. */
int cli_exit_status(int code);

#endif
