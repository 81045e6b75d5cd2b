/* cmd_write_y2d.c: the `write_y2d` deck command (a row of commands.def): reads its words and calls
 * y2d_write (y2d_write.h).
 */
#include <string.h>
#include "deck.h"
#include "output.h"
#include "y2d_write.h"

/* write_y2d FILE steps N [every K] */
void cmd_write_y2d(YfSim *s, const YfArgs *a) {
  arg_count(a, 3, 5);
  const char *path = arg_word(a, 0, "file");
  const char *by = output_claim(s, "write_y2d", path, NULL, 0); /* it wrote over a dump's index without a word */
  if (by && strcmp(by, "write_y2d")) arg_error(a, 0, "already written by %s", by); /* its own again: a new version */
  static const char *const kw[] = {"steps", NULL}, *const kw_every[] = {"every", NULL};
  arg_choice(a, 1, "keyword", kw);
  long steps = arg_int(a, 2, "steps", 1, 2000000000L);
  long every = 0; /* Y2D's output interval ICOUTF; 0: the thermo interval */
  if (a->n > 3) {
    arg_choice(a, 3, "keyword", kw_every);
    every = arg_int(a, 4, "output interval K (steps)", 1, 2000000000L);
  }
  y2d_write(s, path, steps, every, &a->loc);
}
