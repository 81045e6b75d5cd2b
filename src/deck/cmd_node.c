/* cmd_node.c: the `node` deck command (a row of commands.def): one inline node
 * (mesh_inline_node, model/mesh.c).
 */
#include <limits.h>
#include "deck.h"
#include "mesh.h"
#include "sim.h"

/* node ID X Y [BODY]
 * An inline node with user id ID at (X, Y) [m], in body BODY (default "inline"). */
void cmd_node(struct YfSim *sim, const YfArgs *a) {
  arg_count(a, 3, 4);
  long id = arg_int(a, 0, "node id", 0, INT_MAX);
  double x = arg_num(a, 1, "x"), y = arg_num(a, 2, "y");
  mesh_inline_node(&sim->model, id, x, y, a->n > 3 ? a->w[3] : "inline", &a->loc, "node");
}
