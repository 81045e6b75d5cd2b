/* cmd_nodes.c: the `nodes` deck command (a row of commands.def): inline nodes from a file, one
 * row each (mesh_inline_node, model/mesh.c).
 */
#include "deck.h"
#include "mesh.h"
#include "scene_args.h"

static void node_row(YfModel *m, char **w, const YfLoc *loc, const char *bname) {
  long id = row_long(w[0], loc, "node id");
  double x = row_num(w[1], loc, "x"), y = row_num(w[2], loc, "y");
  mesh_inline_node(m, id, x, y, bname, loc, "nodes");
}

/* nodes FILE [BODY]
 * Inline nodes from a text file, one "ID X Y" row per node (relative paths: the deck's dir). */
void cmd_nodes(struct YfSim *sim, const YfArgs *a) {
  deck_read_rows(&sim->model, a, 3, node_row, "id x y");
}
