/* cmd_load.c: the `load` deck command (a row of commands.def): reads its words into a YfBcSpec
 * and adds it to the scene's loads (bc_add, bc.h).
 */
#include <string.h>
#include "bc.h"
#include "deck.h"
#include "scene_args.h"

/* load ID point node NODEID FX FY [history H]
 * load ID point at X Y FX FY [history H]
 * load ID GROUP traction TX TY [history H]     (on the group's boundary edges, [Pa] = N/m per m)
 * load ID GROUP pressure P [history H]          (positive pushes into the body [Pa]) */
void cmd_load(YfSim *s, const YfArgs *a) {
  arg_count(a, 3, 9);
  const char *id = arg_name(a, 0, "ID");
  YfBcSpec it = {.hist = -1, .node_id = -1, .loc = a->loc};
  if (!strcmp(a->w[1], "point")) {
    static const char *const how[] = {"node", "at", NULL};
    int h = arg_choice(a, 2, "point location", how);
    if (bc_exists(s, id)) arg_error(a, 0, "ID '%s' is already used (by another fix or load); use unfix/unload first", id);
    it.kind = BC_POINT;
    int i = 3;
    if (h == 0) {
      it.node_id = (int)arg_int(a, 3, "node id", 0, 2147483647L);
      i = 4;
    } else {
      it.px = arg_coord(a, 3, "x");
      it.py = arg_coord(a, 4, "y");
      i = 5;
    }
    it.has[0] = it.has[1] = 1;
    it.a[0] = arg_num(a, i, "fx");
    it.a[1] = arg_num(a, i + 1, "fy");
    it.hist = arg_history(s, a, i + 2);
    if (h == 0) {
      /* Gmsh bodies keep their files' tags as ids, so two may share this one: the load went to
       * whichever came first in memory (and a partition renumbers memory); refuse the guess */
      const YfModel *m = &s->model;
      int first = -1;
      for (int k = 0; k < m->node.n; k++) {
        if (m->node.id[k] != it.node_id) continue;
        if (first < 0) first = k;
        else if (m->node.body[k] != m->node.body[first]) /* copies of one node (joints) share its id */
          arg_error(a, 3, "node id %d is that of a node of body '%s' and of one of body '%s' (a Gmsh mesh keeps its "
                    "file's tags as ids): say which with 'load %s point at X Y' (the nearest node)", it.node_id,
                    m->body[m->node.body[first]].name, m->body[m->node.body[k]].name, id);
      }
      if (first < 0) arg_error(a, 3, "no node has this id");
    }
    bc_add(s, id, &it);
    return;
  }
  static const char *const styles[] = {"traction", "pressure", NULL};
  int g = arg_group(s, a, 1);
  int st = arg_choice(a, 2, "load style", styles);
  if (bc_exists(s, id)) arg_error(a, 0, "ID '%s' is already used (by another fix or load); use unfix/unload first", id);
  it.group = g;
  if (st == 0) {
    it.kind = BC_TRACTION;
    it.a[0] = arg_num(a, 3, "tx");
    it.a[1] = arg_num(a, 4, "ty");
    it.hist = arg_history(s, a, 5);
  } else {
    it.kind = BC_PRESSURE;
    it.a[0] = arg_num(a, 3, "p");
    it.hist = arg_history(s, a, 4);
  }
  bc_add(s, id, &it);
}
