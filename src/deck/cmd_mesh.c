/* cmd_mesh.c: the `mesh` deck command (a row of commands.def): `mesh rect` reads its words into a
 * YfRectSpec for the structured mesher (mesh_rect, model/mesh.c), `mesh gmsh` into the Gmsh
 * reader's options (gmsh_read, model/gmsh.c).
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "deck.h"
#include "mesh.h"
#include "scene_args.h"

/* mesh rect BODY MATERIAL X0 Y0 X1 Y1 NX NY [pattern right|left|alt|cross]
 * (the patterns and the numbering: mesh_rect, mesh.h) */
static void cmd_mesh_rect(YfModel *m, const YfArgs *a) {
  arg_count(a, 9, 11);
  YfRectSpec r = {.pattern = YF_PAT_RIGHT};
  r.body = arg_word(a, 1, "body name");
  r.mat = arg_material(m, a, 2);
  double x0 = arg_num(a, 3, "x0"), y0 = arg_num(a, 4, "y0");
  double x1 = arg_num(a, 5, "x1"), y1 = arg_num(a, 6, "y1");
  const double corner[4] = {x0, y0, x1, y1};
  for (int k = 0; k < 4; k++)
    if (!(fabs(corner[k]) <= YF_RANGE_MAX))
      arg_error(a, 3 + k, "coordinate %g is beyond +-%g m, the range the arithmetic holds (areas and "
                "energies multiply coordinates)", corner[k], YF_RANGE_MAX);
  if (!(x1 > x0)) arg_error(a, 5, "x1 must be greater than x0 = %g", x0);
  if (!(y1 > y0)) arg_error(a, 6, "y1 must be greater than y0 = %g", y0);
  r.x0 = x0, r.y0 = y0, r.x1 = x1, r.y1 = y1;
  r.nx = arg_int(a, 7, "nx", 1, 100000000);
  r.ny = arg_int(a, 8, "ny", 1, 100000000);
  /* cells whose corners doubles cannot tell apart (x0 = 1e20 with 8 km cells), or whose areas
   * underflow (a 1e-300 m box), gave zero-area triangles found only at the run, with no line */
  double dx = (x1 - x0) / (double)r.nx, dy = (y1 - y0) / (double)r.ny;
  double far = fmax(fmax(fabs(x0), fabs(x1)), fmax(fabs(y0), fabs(y1)));
  if (!(fmin(dx, dy) > 1e-12 * far))
    arg_error(a, 7, "cells of %g x %g m, %g m from the origin: too small for doubles (16 digits) to tell their "
              "corners apart; move the mesh nearer the origin or use fewer cells", dx, dy, far);
  if (!(dx * dy > 1e-280))
    arg_error(a, 7, "cells of %g x %g m: their areas underflow a double; use larger units", dx, dy);
  if (a->n > 9) {
    if (strcmp(a->w[9], "pattern") != 0) arg_error(a, 9, "expected the keyword 'pattern'");
    arg_count(a, 11, 11);
    r.pattern = arg_choice(a, 10, "pattern", mesh_patterns);
  }
  int b = mesh_rect(m, &r, &a->loc);
  if (b == -2) arg_error(a, 7, "%lld x %lld cells is too large a mesh", (long long)r.nx, (long long)r.ny);
  if (b == -1) arg_error(a, 7, "user ids would overflow");
}

/* mesh gmsh BODY FILE.msh [material PHYS=MAT ... | material MAT ...] [scale S] [shift DX DY]
 *
 * After `material`, words PHYS=MAT map a physical surface (by name or tag) to a material and a
 * bare word MAT sets the default material (used by surfaces with no mapping and no material of
 * their own name).  Without a bare default, the first mapping's material is the default. */
static void cmd_mesh_gmsh(YfModel *m, const YfArgs *a) {
  arg_count(a, 3, -1);
  const char *bname = arg_word(a, 1, "body name");
  const char *file = arg_word(a, 2, "mesh file");
  YfGmshOpts o;
  memset(&o, 0, sizeof o);
  o.body = bname;
  o.defmat = -1;
  o.scale = 1.0;
  o.from = a->loc;
  o.map = yf_calloc((size_t)a->n, sizeof *o.map, "material mappings");
  int first_map_mat = -1, seen_scale = 0, seen_shift = 0;
  for (int i = 3; i < a->n;) {
    if (!strcmp(a->w[i], "material")) {
      i++;
      if (i >= a->n || !strcmp(a->w[i], "scale") || !strcmp(a->w[i], "shift"))
        arg_error(a, i - 1, "expects PHYS=MAT mappings or a material name after it");
      for (; i < a->n && strcmp(a->w[i], "scale") != 0 && strcmp(a->w[i], "shift") != 0 &&
             strcmp(a->w[i], "material") != 0; i++) {
        char *eq = strchr(a->w[i], '=');
        char buf[512];
        if (!eq) {
          if (o.defmat >= 0) arg_error(a, i, "a second default material (the first was '%s')",
                                       m->mat[o.defmat].name);
          o.defmat = arg_material(m, a, i);
          continue;
        }
        if (eq == a->w[i] || eq[1] == '\0') arg_error(a, i, "expected PHYS=MAT");
        int mt = model_find_material(m, eq + 1);
        if (mt < 0)
          arg_error(a, i, "unknown material '%s' (known materials: %s)", eq + 1,
                    mesh_material_names(m, buf, sizeof buf));
        size_t plen = (size_t)(eq - a->w[i]);
        char *phys = yf_malloc(plen + 1, "physical name");
        memcpy(phys, a->w[i], plen);
        phys[plen] = '\0';
        for (int k = 0; k < o.nmap; k++)
          if (!strcmp(o.map[k].phys, phys)) arg_error(a, i, "physical group '%s' is mapped twice", phys);
        o.map[o.nmap].phys = phys;
        o.map[o.nmap].mat = mt;
        o.nmap++;
        if (first_map_mat < 0) first_map_mat = mt;
      }
    } else if (!strcmp(a->w[i], "scale")) {
      if (seen_scale) arg_error(a, i, "given twice");
      seen_scale = 1;
      if (i + 1 >= a->n) arg_error(a, i, "expects a factor after it");
      o.scale = arg_pos(a, i + 1, "scale");
      i += 2;
    } else if (!strcmp(a->w[i], "shift")) {
      /* after the scale, in metres: two bodies from one file (an impactor and its target) are
       * placed apart, as LAMMPS's displace_atoms moves a copy */
      if (seen_shift) arg_error(a, i, "given twice");
      seen_shift = 1;
      if (i + 2 >= a->n) arg_error(a, i, "expects DX DY [m] after it");
      o.dx = arg_coord(a, i + 1, "DX");
      o.dy = arg_coord(a, i + 2, "DY");
      i += 3;
    } else {
      arg_error(a, i, "unknown keyword (expected material, scale or shift)");
    }
  }
  if (o.defmat < 0) o.defmat = first_map_mat;
  char *path = deck_resolve_path(a, file);
  gmsh_read(m, path, &o);
  free(path);
  for (int k = 0; k < o.nmap; k++) free((char *)o.map[k].phys);
  free(o.map);
}

/* mesh rect ... | mesh gmsh ...  (see cmd_mesh_rect and cmd_mesh_gmsh for the grammar) */
void cmd_mesh(struct YfSim *sim, const YfArgs *a) {
  static const char *const kinds[] = {"rect", "gmsh", NULL};
  arg_count(a, 1, -1);
  int k = arg_choice(a, 0, "mesh style", kinds);
  if (k == 0) cmd_mesh_rect(&sim->model, a);
  else cmd_mesh_gmsh(&sim->model, a);
}
