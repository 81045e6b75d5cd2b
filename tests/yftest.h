/* yftest.h: helpers for tests that run deck text in-process and look at the resulting arrays.
 *
 * Check runs each test in a forked child, so a deck that fails (and exits) only ends that test:
 * error tests use tcase_add_exit_test or yft_run_binary below.
 */
#ifndef YF_TEST_H
#define YF_TEST_H
#include "sim.h"

/* Run deck text in a fresh simulation (stdout silenced); returns the simulation (static). */
YfSim *yft_run(const char *deck_text);
/* Run a deck file (path relative to the repository root, where the tests run) in a fresh
 * simulation (stdout silenced), with the variables vars = {NAME, VALUE, ..., NULL} set as by
 * -var; returns the simulation (static). */
YfSim *yft_run_deck(const char *path, const char *const *vars);
/* Run the yfdem binary (path from $YFDEM, default ./yfdem) with the given deck text written to
 * a temporary file named NAME in a fresh temporary directory; returns the exit code, and the
 * captured stderr in err (caller frees).  *dir receives the temporary directory (caller frees). */
int yft_run_binary(const char *name, const char *deck_text, const char *extra_args, char **err, char **dir);
/* The yfdem binary's absolute path ($YFDEM, default ./yfdem). */
const char *yft_binary(void);
/* A fresh temporary directory (malloc'd path) holding deck NAME with deck_text. */
char *yft_deck_dir(const char *name, const char *deck_text);
/* Remove a directory yft_run_binary or yft_deck_dir made, and free its path. */
void yft_rm_dir(char *dir);
/* Write text to dir/name. */
void yft_put_file(const char *dir, const char *name, const char *text);
/* Run fn(arg) in a child process (its stdout silenced, its stderr captured into msg); returns
 * the child's exit code (0 when fn returns). */
int yft_child_run(void (*fn)(void *), void *arg, char *msg, size_t n);
/* Node nearest to (x, y) in the initial configuration. */
int yft_node_at(const YfSim *s, double x, double y);
/* The time [s] at which the velocity of node `probe` in component comp (0 x, 1 y), behind a step
 * front of unit velocity, first reaches 1/2 (interpolated between steps), stepping s until t_max;
 * -1 if it has not by then. */
double yft_front_arrival(YfSim *s, int probe, int comp, double t_max);
/* Whole file as a string (caller frees); NULL when it cannot be opened, or "" when
 * empty_if_missing is set. */
char *yft_slurp(const char *path, int empty_if_missing);
/* Whether a file exists. */
int yft_exists(const char *path);

#endif
