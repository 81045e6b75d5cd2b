/* cmd_timestep.c: the `timestep` deck command (a row of commands.def): reads its words and calls
 * the simulation's own settings (sim.h).
 */
#include <stdlib.h>
#include <string.h>
#include "deck.h"
#include "sim.h"

/* timestep DT [above_limit warn] | timestep auto [safety S] */
void cmd_timestep(YfSim *s, const YfArgs *a) {
  arg_count(a, 1, 3);
  s->dt_warn_only = s->y2d != NULL; /* each timestep line says it anew (a Y2D deck's own rule stays) */
  s->dt_resume = 0; /* the deck's own setting wins over the one a restart brought (read_restart) */
  if (!strcmp(a->w[0], "auto")) {
    s->dt_auto = 1;
    s->dt_pending = 1;
    s->dt_loc = a->loc; /* the line that auto's refusals name */
    /* each line says its factor anew: 'timestep auto' after 'timestep auto safety 0.2' is the
     * documented default 0.5, not the factor of the earlier line */
    s->dt_safety = 0.5;
    if (a->n > 1) {
      if (strcmp(a->w[1], "safety")) arg_error(a, 1, "expected 'safety S'");
      arg_count(a, 3, 3);
      s->dt_safety = arg_pos(a, 2, "safety");
      if (s->dt_safety > 1.0) arg_error(a, 2, "a safety factor above 1 exceeds the stable limit");
    }
  } else {
    if (a->n > 1) { /* the rule of Y2D decks, for a deck converted from one (y2d2deck.py) */
      arg_count(a, 3, 3);
      static const char *const kw[] = {"above_limit", NULL}, *const how[] = {"warn", NULL};
      arg_choice(a, 1, "keyword", kw);
      arg_choice(a, 2, "above_limit", how);
      s->dt_warn_only = 1;
    }
    s->dt_auto = 0;
    s->dt_pending = 0;
    s->dt = arg_pos(a, 0, "dt");
    s->dt_loc = a->loc;
  }
}
