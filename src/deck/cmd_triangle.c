/* cmd_triangle.c: the `triangle` deck command (a row of commands.def): one inline triangle
 * (mesh_inline_tri, model/mesh.c).
 */
#include <limits.h>
#include "deck.h"
#include "mesh.h"
#include "scene_args.h"

/* triangle ID N1 N2 N3 MATERIAL [BODY]
 * An inline triangle on inline nodes N1 N2 N3 (user ids, counter-clockwise), in body BODY
 * (default "inline"); the nodes must be in the same body. */
void cmd_triangle(struct YfSim *sim, const YfArgs *a) {
  arg_count(a, 5, 6);
  long id = arg_int(a, 0, "triangle id", 0, INT_MAX);
  long n[3];
  for (int k = 0; k < 3; k++) n[k] = arg_int(a, 1 + k, "node id", 0, INT_MAX);
  int mat = arg_material(&sim->model, a, 4);
  mesh_inline_tri(&sim->model, id, n, mat, a->n > 5 ? a->w[5] : "inline", &a->loc, "triangle");
}
