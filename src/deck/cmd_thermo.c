/* cmd_thermo.c: the `thermo` deck command (a row of commands.def): reads its words and calls
 * the simulation's own settings (sim.h).
 */
#include <stdlib.h>
#include <string.h>
#include "deck.h"
#include "sim.h"

/* thermo N   (a thermo line every N steps; 0: start and end of each run only) */
void cmd_thermo(YfSim *s, const YfArgs *a) {
  arg_count(a, 1, 1);
  s->thermo_every = arg_int(a, 0, "N", 0, 2000000000L);
}
