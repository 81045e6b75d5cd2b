/* cmd_velocity.c: the `velocity` deck command (a row of commands.def): sets the velocity of a
 * group's nodes now (bc_set_velocity, bc.h).
 */
#include <math.h>
#include "bc.h"
#include "deck.h"
#include "scene_args.h"

/* velocity GROUP set VX VY    (initial velocity of the group's nodes, now) */
void cmd_velocity(YfSim *s, const YfArgs *a) {
  arg_count(a, 4, 4);
  static const char *const styles[] = {"set", NULL};
  int g = arg_group(s, a, 0);
  arg_choice(a, 1, "style", styles);
  double vx = arg_num(a, 2, "vx"), vy = arg_num(a, 3, "vy");
  for (int k = 2; k < 4; k++)
    if (!(fabs(k == 2 ? vx : vy) <= YF_RANGE_MAX))
      arg_error(a, k, "velocity %g is beyond +-%g m/s, the range the arithmetic holds (kinetic energy "
                "is mass times velocity squared)", k == 2 ? vx : vy, YF_RANGE_MAX);
  if (!bc_set_velocity(s, g, vx, vy)) yf_warn(&a->loc, "velocity: group '%s' has no nodes", a->w[0]);
}
