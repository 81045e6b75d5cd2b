/* cmd_energy_check.c: the energy_check command (the check itself is step/energy.c). */
#include "deck.h"
#include "energy.h"

/* energy_check stop|warn|off [tolerance F] */
void cmd_energy_check(YfSim *s, const YfArgs *a) {
  arg_count(a, 1, 3);
  static const char *const modes[] = {"stop", "warn", "off", NULL};
  s->ebal_mode = arg_choice(a, 0, "energy check mode", modes);
  if (a->n > 1) {
    static const char *const w[] = {"tolerance", NULL};
    arg_choice(a, 1, "energy check option", w);
    arg_count(a, 3, 3);
    s->ebal_tol = arg_pos(a, 2, "tolerance");
  }
}
