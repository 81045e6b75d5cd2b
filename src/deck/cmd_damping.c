/* cmd_damping.c: the `damping` deck command (a row of commands.def): reads its words and calls
 * the simulation's own settings (sim.h).
 */
#include <stdlib.h>
#include <string.h>
#include "deck.h"
#include "sim.h"

/* damping mass ALPHA   (force -ALPHA m v on every node [1/s]; 0 switches it off) */
void cmd_damping(YfSim *s, const YfArgs *a) {
  arg_count(a, 2, 2);
  static const char *const kinds[] = {"mass", NULL};
  arg_choice(a, 0, "damping style", kinds);
  s->mass_damping = arg_nonneg(a, 1, "alpha");
  s->damping_loc = a->loc;
}
