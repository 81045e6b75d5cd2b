/* cmd_fracture.c: the `fracture` deck command (a row of commands.def): names a body, a joint set
 * and an optional region or group, and adds the fracture zone (joints_add_fracture, joint.h).
 */
#include "deck.h"
#include "joint.h"
#include "mesh.h"
#include "region.h"

/* fracture BODY JOINTPROP [region R | group G] */
void cmd_fracture(YfSim *s, const YfArgs *a) {
  arg_count(a, 2, 4);
  YfModel *m = &s->model;
  if (s->step > 0 || m->prepared)
    arg_error(a, 0, "fracture must come before the first run (the mesh is split once, when the run starts)");
  int b = model_find_body(m, a->w[0]);
  if (b < 0) {
    char list[1024];
    arg_error(a, 0, "unknown body (bodies: %s)", mesh_body_names(m, list, sizeof list));
  }
  int js = joints_find_set(s, arg_word(a, 1, "jointprop"));
  if (js < 0) arg_error(a, 1, "unknown jointprop (define it first with: jointprop NAME ft FT fs FS gf GF pen P ...)");
  int region = -1, group = -1;
  if (a->n > 2) {
    static const char *const how[] = {"region", "group", NULL};
    int h = arg_choice(a, 2, "selection", how);
    const char *nm = arg_word(a, 3, h ? "group" : "region");
    if (h == 0) {
      region = region_find(nm);
      if (region < 0) arg_error(a, 3, "unknown region (define it with: region NAME box|circle|polygon ...)");
    } else {
      group = model_group(m, nm, 0);
      if (group < 0) {
        char list[1024];
        arg_error(a, 3, "unknown group (groups: %s)", mesh_group_names(m, list, sizeof list));
      }
    }
  }
  joints_add_fracture(s, b, js, region, group, &a->loc);
}
