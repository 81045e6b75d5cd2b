/* cmd_gravity.c: the `gravity` deck command (a row of commands.def): reads its words and calls
 * the simulation's own settings (sim.h).
 */
#include <stdlib.h>
#include <string.h>
#include "deck.h"
#include "sim.h"

/* gravity GX GY   [m/s^2] */
void cmd_gravity(YfSim *s, const YfArgs *a) {
  arg_count(a, 2, 2);
  s->gx = arg_num(a, 0, "gx");
  s->gy = arg_num(a, 1, "gy");
}
