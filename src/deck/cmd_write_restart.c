/* cmd_write_restart.c: the `write_restart` deck command (a row of commands.def): prepares the
 * scene as `run` would and writes a restart now (restart_write, io/restart.c).
 */
#include <string.h>
#include "deck.h"
#include "output.h"
#include "report.h"
#include "restart.h"
#include "run.h"

/* write_restart FILE */
void cmd_write_restart(YfSim *s, const YfArgs *a) {
  arg_count(a, 1, 1);
  if (!s->model.tri.n) arg_error(a, 0, "the scene has no triangles: nothing to write");
  run_prepare(s); /* a restart before the first run holds the prepared initial state */
  io_attach(s);   /* the restart and output state it makes are freed with the simulation (report.c) */
  const char *p = arg_word(a, 0, "FILE"); /* an output: relative to the working directory */
  /* "" wrote a whole restart to '.tmp' and failed to rename it (exit 2): a deck error, as for the
   * other outputs' names */
  if (!p[0]) arg_error(a, 0, "empty file name");
  arg_regular(a, 0, p);
  const char *by = output_claim(s, "write_restart", p, NULL, 0); /* it wrote over the log, a dump's index... */
  if (by && strcmp(by, "write_restart")) arg_error(a, 0, "already written by %s", by); /* its own again: a new version */
  char err[1024];
  if (restart_write(s, p, err, sizeof err)) yf_io_error(&a->loc, "write_restart: %s", err);
  sim_printf(s, "write_restart: %s at step %ld\n", p, s->step);
}
