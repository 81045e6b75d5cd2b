/* cmd_undump.c: the `undump` deck command (a row of commands.def): stops a dump
 * (output_remove_dump, io/output.c).
 */
#include <string.h>
#include "deck.h"
#include "output.h"

/* undump ID */
void cmd_undump(YfSim *s, const YfArgs *a) {
  arg_count(a, 1, 1);
  const char *id = arg_word(a, 0, "dump id");
  if (output_remove_dump(s, id) == 0) return;
  char have[YF_MAX_DUMPS * (YF_NAME_MAX + 1) + 8] = "";
  for (int i = 0; i < output_ndump(s); i++) {
    strcat(have, i ? " " : "");
    strcat(have, output_dump_id(s, i));
  }
  arg_error(a, 0, "no such dump (defined: %s)", have[0] ? have : "none");
}
