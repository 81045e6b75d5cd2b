/* cmd_fracture_log.c: the `fracture_log` deck command (a row of commands.def): the CSV files of
 * the break and opened-crack records (joints_set_logs, joint.h; written by io/report.c).
 */
#include <errno.h>
#include <string.h>
#include "deck.h"
#include "output.h"
#include "joint.h"

/* fracture_log FILE [opened FILE2]: the break record as CSV, and optionally the opened-crack
 * record (joints first past their peak) in the same columns, rewritten at the end of every run. */
void cmd_fracture_log(YfSim *s, const YfArgs *a) {
  arg_count(a, 1, 3);
  if (a->n == 2) arg_error(a, 1, "expected 'opened FILE2' after FILE");
  const YfJoints *J = s->joints; /* only for the sizes of the paths */
  /* outputs, like dumps: relative to the working directory */
  if (strlen(a->w[0]) >= sizeof J->log_path) arg_error(a, 0, "path too long");
  const char *opened = NULL;
  if (a->n == 3) {
    static const char *const kw[] = {"opened", NULL};
    arg_choice(a, 1, "option", kw);
    if (strlen(a->w[2]) >= sizeof J->open_log_path) arg_error(a, 2, "path too long");
    opened = a->w[2];
  }
  for (int i = 0; i < a->n; i += 2) /* a missing folder: now, not after the run */
    if (!yf_can_create(a->w[i])) yf_io_error(&a->loc, "fracture_log: cannot write '%s': %s", a->w[i], strerror(errno));
  output_release(s, "fracture_log"); /* a later fracture_log replaces the earlier */
  for (int i = 0; i < a->n; i += 2) arg_claim(s, a, i, "fracture_log", a->w[i], NULL, 0);
  joints_set_logs(s, a->w[0], opened);
}
