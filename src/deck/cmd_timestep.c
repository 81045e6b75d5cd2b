/* cmd_timestep.c: the `timestep` deck command (a row of commands.def): reads its words and calls
 * the simulation's own settings (sim.h).
 */
#include <stdlib.h>
#include <string.h>
#include "deck.h"
#include "sim.h"

/* timestep DT | timestep auto [safety S] */
void cmd_timestep(YfSim *s, const YfArgs *a) {
  arg_count(a, 1, 3);
  if (!strcmp(a->w[0], "auto")) {
    s->dt_auto = 1;
    s->dt_loc = a->loc; /* the line that auto's refusals name */
    if (a->n > 1) {
      if (strcmp(a->w[1], "safety")) arg_error(a, 1, "expected 'safety S'");
      arg_count(a, 3, 3);
      s->dt_safety = arg_pos(a, 2, "safety");
      if (s->dt_safety > 1.0) arg_error(a, 2, "a safety factor above 1 exceeds the stable limit");
    }
  } else {
    arg_count(a, 1, 1);
    s->dt_auto = 0;
    s->dt = arg_pos(a, 0, "dt");
    s->dt_loc = a->loc;
  }
}
