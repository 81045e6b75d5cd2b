/* cmd_partition.c: the `partition` deck command (a row of commands.def): reads its words and calls
 * the partition settings of the model (partition.h).
 */
#include <stdlib.h>
#include <string.h>
#include "deck.h"
#include "partition.h"

/* partition metis|none [parts N] */
void cmd_partition(YfSim *s, const YfArgs *a) {
  arg_count(a, 1, 3);
  static const char *const methods[] = {"metis", "none", NULL};
  int k = arg_choice(a, 0, "partition method", methods);
  YfModel *m = &s->model;
  m->part_method = k == 0 ? PART_METIS : PART_NONE;
  m->part_req = 0;
  if (a->n > 1) {
    static const char *const kw[] = {"parts", NULL};
    arg_choice(a, 1, "partition option", kw);
    if (a->n < 3) arg_error(a, 1, "parts needs a number");
    if (k == 1) arg_error(a, 1, "'partition none' takes no parts");
    m->part_req = (int)arg_int(a, 2, "number of parts", 1, 1000000);
  }
  if (m->part_done)
    yf_warn(&a->loc, "partition: the mesh was already renumbered at the first run; this setting has no effect");
}
