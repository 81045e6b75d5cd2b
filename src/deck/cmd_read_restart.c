/* cmd_read_restart.c: the `read_restart` deck command (a row of commands.def): finds the file
 * (the working directory first, then beside the deck) and continues from it (restart_read,
 * io/restart.c).
 */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "deck.h"
#include "report.h"
#include "restart.h"

/* read_restart FILE */
void cmd_read_restart(YfSim *s, const YfArgs *a) {
  io_attach(s); /* its state observes the run loop (report.c) */
  arg_count(a, 1, 1);
  /* Restarts are written relative to the working directory (write_restart, restart every, an
   * interrupt), so that is where FILE is looked for first; a deck run from elsewhere may keep
   * its restart beside itself, so the deck's directory is the second place. */
  const char *w = arg_word(a, 0, "FILE");
  if (!w[0]) arg_error(a, 0, "empty file name"); /* ("" was looked for as '' and '.a' / '.b': exit 2) */
  /* a restart continues a deck from its start: after a run (or a restart read) it would replace
   * the state reached and the series the outputs began (frames of the earlier run were dropped
   * from the index and an off-cadence frame listed; a sweep of new decks, 2026-11-28) */
  /* ('run 0' counts: after it and a body added, a restart was read over the new scene, and the
   * continuation differed from the uninterrupted run) */
  if (s->step > 0 || s->model.prepared || s->runs_begun > 0 || s->restored)
    arg_error(a, 0, "read_restart after a run (or a read_restart) of this deck: put it before the first run "
                    "command, which then continues with 'run N upto'");
  char *here = restart_pick_file(w), *p = NULL, *there = NULL;
  if (!here) {
    p = deck_resolve_path(a, w);
    there = restart_pick_file(p);
  }
  if (!here && !there) {
    YfLoc l = a->loc;
    char msg[2200];
    snprintf(msg, sizeof msg, "no restart '%s' (nor %s.a / %s.b) in the working directory, nor '%s' beside the deck",
             w, w, w, p);
    free(p);
    yf_io_error(&l, "read_restart: %s: %s", msg, strerror(ENOENT));
  }
  restart_read(s, here ? w : p, &a->loc);
  free(here);
  free(there);
  free(p);
}
