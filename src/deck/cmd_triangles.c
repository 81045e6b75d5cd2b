/* cmd_triangles.c: the `triangles` deck command (a row of commands.def): inline triangles from a
 * file, one row each (mesh_inline_tri, model/mesh.c).
 */
#include "deck.h"
#include "mesh.h"
#include "scene_args.h"

static void tri_row(YfModel *m, char **w, const YfLoc *loc, const char *bname) {
  char buf[512];
  long id = row_long(w[0], loc, "triangle id");
  long n[3];
  for (int k = 0; k < 3; k++) n[k] = row_long(w[1 + k], loc, "node id");
  int mat = model_find_material(m, w[4]);
  if (mat < 0)
    yf_deck_error(loc, "triangles: unknown material '%s' (known materials: %s)", w[4],
                  mesh_material_names(m, buf, sizeof buf));
  mesh_inline_tri(m, id, n, mat, bname, loc, "triangles");
}

/* triangles FILE [BODY]
 * Inline triangles from a text file, one "ID N1 N2 N3 MATERIAL" row per triangle. */
void cmd_triangles(struct YfSim *sim, const YfArgs *a) {
  deck_read_rows(&sim->model, a, 5, tri_row, "id n1 n2 n3 material");
}
