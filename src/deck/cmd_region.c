/* cmd_region.c: the `region` deck command (a row of commands.def): reads a shape's words and adds
 * the region (region_add, model/region.c).
 */
#include <stdlib.h>
#include <string.h>
#include "deck.h"
#include "region.h"
#include "sim.h"

/* region NAME box X0 Y0 X1 Y1 [side in|out]
 * region NAME circle XC YC R [side in|out]
 * region NAME polygon X1 Y1 X2 Y2 X3 Y3 ... [side in|out]
 * Coordinates in m.  A box may be flat (X0 = X1 or Y0 = Y1) to pick the nodes on a line. */
void cmd_region(YfSim *sim, const YfArgs *a) {
  static const char *const kinds[] = {"box", "circle", "polygon", NULL}; /* index = YF_REG_* */
  static const char *const sides[] = {"in", "out", NULL};
  arg_count(a, 2, -1);
  const char *name = arg_name(a, 0, "region name");
  if (region_find(name) >= 0) arg_error(a, 0, "region already exists");
  int kind = arg_choice(a, 1, "region style", kinds);
  int n = a->n, out = 0;
  if (n >= 4 && !strcmp(a->w[n - 2], "side")) {
    out = arg_choice(a, n - 1, "side", sides);
    n -= 2;
  }
  double p[4];
  if (kind == YF_REG_BOX) {
    if (n != 6) arg_error(a, n < 6 ? n - 1 : 6, "box expects X0 Y0 X1 Y1 [side in|out]");
    for (int k = 0; k < 4; k++) p[k] = arg_num(a, 2 + k, k % 2 ? "y" : "x");
    if (p[2] < p[0]) arg_error(a, 4, "X1 must not be less than X0 = %g", p[0]);
    if (p[3] < p[1]) arg_error(a, 5, "Y1 must not be less than Y0 = %g", p[1]);
    region_add(name, kind, out, p, 4, &sim->model);
  } else if (kind == YF_REG_CIRCLE) {
    if (n != 5) arg_error(a, n < 5 ? n - 1 : 5, "circle expects XC YC R [side in|out]");
    p[0] = arg_num(a, 2, "xc");
    p[1] = arg_num(a, 3, "yc");
    p[2] = arg_pos(a, 4, "radius");
    region_add(name, kind, out, p, 3, &sim->model);
  } else {
    int nc = n - 2;
    if (nc < 6) arg_error(a, n - 1, "a polygon needs at least 3 points (X1 Y1 X2 Y2 X3 Y3 ...)");
    if (nc % 2) arg_error(a, n - 1, "polygon coordinates come in X Y pairs (odd count %d)", nc);
    double *c = yf_malloc((size_t)nc * sizeof *c, "polygon");
    for (int k = 0; k < nc; k++) c[k] = arg_num(a, 2 + k, k % 2 ? "y" : "x");
    int r = region_add(name, kind, out, c, nc, &sim->model);
    free(c);
    if (r < 0) arg_error(a, 2, "the polygon has zero area");
  }
}
