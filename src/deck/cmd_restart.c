/* cmd_restart.c: the `restart` deck command (a row of commands.def): periodic restarts on or off
 * (restart_every, io/restart.c).
 */
#include <limits.h>
#include <stdlib.h>
#include <string.h>
#include "deck.h"
#include "output.h"
#include "report.h"
#include "restart.h"

/* restart every N FILE | restart off */
void cmd_restart(YfSim *s, const YfArgs *a) {
  io_attach(s); /* its state observes the run loop (report.c) */
  arg_count(a, 1, 3);
  static const char *const w[] = {"every", "off", NULL};
  int k = arg_choice(a, 0, "restart keyword", w);
  if (k == 1) {
    arg_count(a, 1, 1);
    output_release(s, "restart every");
    restart_every(s, 0, NULL);
    return;
  }
  arg_count(a, 3, 3);
  long every = arg_int(a, 1, "N (steps)", 1, LONG_MAX);
  const char *base = arg_word(a, 2, "FILE"); /* an output: relative to the working directory */
  if (!base[0]) arg_error(a, 2, "empty file name");
  char *made = yf_malloc(strlen(base) + 3, "path");
  sprintf(made, "%s.a", base);
  arg_file_stem(a, 2, base, made); /* FILE.a and FILE.b: "." made the hidden ..a and ..b */
  free(made);
  /* a missing folder: now, at this line, not at the first restart step after frames were written */
  arg_writable(a, "restart every", "%s.a", base);
  output_release(s, "restart every"); /* a later one replaces the earlier */
  char *ab = yf_malloc(strlen(base) + 3, "path");
  for (int i = 0; i < 2; i++) {
    sprintf(ab, "%s.%c", base, 'a' + i);
    arg_regular(a, 2, ab);
    const char *by = output_claim(s, "restart every", ab, NULL, 0);
    if (by) {
      free(ab);
      output_release(s, "restart every");
      arg_error(a, 2, "'%s.%c' is already written by %s", base, 'a' + i, by);
    }
  }
  free(ab);
  restart_every(s, every, base);
}
