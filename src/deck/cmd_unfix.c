/* cmd_unfix.c: the `unfix` deck command (a row of commands.def): removes a fix (bc_remove). */
#include "bc.h"
#include "deck.h"

/* unfix ID */
void cmd_unfix(YfSim *s, const YfArgs *a) {
  arg_count(a, 1, 1);
  if (!bc_remove(s, a->w[0], 0)) arg_error(a, 0, "no fix with this ID");
}
