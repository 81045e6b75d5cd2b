/* cmd_fix.c: the `fix` deck command (a row of commands.def): reads its words into a YfBcSpec
 * and adds it to the scene's fixes (bc_add, bc.h).
 */
#include <string.h>
#include "bc.h"
#include "deck.h"
#include "scene_args.h"

/* A component that may be NULL (left free). */
static void parse_component(const YfArgs *a, int i, const char *what, YfBcSpec *it, int c) {
  if (!strcmp(arg_word(a, i, what), "NULL")) { it->has[c] = 0; return; }
  it->has[c] = 1;
  it->a[c] = arg_num(a, i, what);
}

/* fix ID GROUP fixed x|y|xy
 * fix ID GROUP velocity VX|NULL VY|NULL [history H]
 * fix ID GROUP displacement UX|NULL UY|NULL [history H] */
void cmd_fix(YfSim *s, const YfArgs *a) {
  arg_count(a, 3, 7);
  static const char *const styles[] = {"fixed", "velocity", "displacement", NULL};
  int st = arg_choice(a, 2, "style", styles);
  int g = arg_group(s, a, 1);
  const char *id = arg_name(a, 0, "ID");
  if (bc_exists(s, id)) arg_error(a, 0, "ID '%s' is already used (by another fix or load); use unfix/unload first", id);
  YfBcSpec it = {.group = g, .hist = -1, .node_id = -1, .loc = a->loc};
  if (st == 0) {
    static const char *const dirs[] = {"x", "y", "xy", NULL};
    arg_count(a, 4, 4);
    int d = arg_choice(a, 3, "direction", dirs);
    it.kind = BC_FIXED;
    it.has[0] = d != 1;
    it.has[1] = d != 0;
  } else {
    arg_count(a, 5, 7);
    it.kind = st == 1 ? BC_VELOCITY : BC_DISPLACEMENT;
    parse_component(a, 3, st == 1 ? "vx" : "ux", &it, 0);
    parse_component(a, 4, st == 1 ? "vy" : "uy", &it, 1);
    if (!it.has[0] && !it.has[1]) arg_error(a, 3, "both components are NULL: nothing to prescribe");
    it.hist = arg_history(s, a, 5);
  }
  bc_add(s, id, &it);
}
