/* cmd_unload.c: the `unload` deck command (a row of commands.def): removes a load (bc_remove). */
#include "bc.h"
#include "deck.h"

/* unload ID */
void cmd_unload(YfSim *s, const YfArgs *a) {
  arg_count(a, 1, 1);
  if (!bc_remove(s, a->w[0], 1)) arg_error(a, 0, "no load with this ID");
}
