/* cmd_group.c: the `group` deck command (a row of commands.def): reads the selection's words and
 * adds what the model's selections (group_select_*, model/region.c) pick to the group.
 */
#include <limits.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include "deck.h"
#include "mesh.h"
#include "region.h"
#include "sim.h"

static int body_or_die(const YfModel *m, const YfArgs *a, int i) {
  char buf[512];
  int b = model_find_body(m, a->w[i]);
  if (b < 0) arg_error(a, i, "unknown body (bodies: %s)", mesh_body_names(m, buf, sizeof buf));
  return b;
}

/* Gmsh meshes keep their files' tags as ids, so two such bodies (or one and an earlier mesh) share
 * ids, and `group G node id 1` took node 1 of every body without a word.  Warn at the first id
 * that selected nodes or triangles of two bodies, with the way to keep one body's. */
static void warn_shared_ids(const YfModel *m, const YfArgs *a, const char *name, const unsigned char *ns,
                            const unsigned char *ts) {
  for (int kind = 0; kind < 2; kind++) {
    const unsigned char *sel = kind ? ts : ns;
    int n = kind ? m->tri.n : m->node.n;
    const int *id = kind ? m->tri.id : m->node.id, *body = kind ? m->tri.body : m->node.body;
    YfIdMap first; /* id -> index of the first selected entity with it */
    idmap_init(&first);
    for (int i = 0; i < n; i++) {
      if (!sel[i]) continue;
      int j = idmap_get(&first, id[i]);
      if (j < 0) {
        idmap_put(&first, id[i], i);
        continue;
      }
      if (body[j] == body[i]) continue;
      yf_warn(&a->loc, "group %s: %s id %d is that of a %s of body '%s' and of one of body '%s' (a Gmsh mesh keeps "
              "its file's tags as ids): all are selected; to keep one body's, 'group %s_%s intersect %s %s'",
              name, kind ? "triangle" : "node", id[i], kind ? "triangle" : "node", m->body[body[j]].name,
              m->body[body[i]].name, name, m->body[body[j]].name, name, m->body[body[j]].name);
      idmap_free(&first);
      return;
    }
    idmap_free(&first);
  }
}

static int group_or_die(YfModel *m, const YfArgs *a, int i) {
  char buf[1024];
  int g = model_group(m, a->w[i], 0);
  if (g < 0) arg_error(a, i, "unknown group (groups: %s)", mesh_group_names(m, buf, sizeof buf));
  return g;
}

/* group NAME node|tri|both region R [body B]
 * group NAME node|tri|both id I1 I2 ...
 * group NAME node|tri|both body B
 * group NAME node nearest X Y
 * group NAME union G1 G2 ...
 * group NAME subtract G1 G2 ...     (members of G1 that are in none of G2 ...)
 * group NAME intersect G1 G2 ...
 * Adds the selected nodes and/or triangles to group NAME (created when new).  Selection uses
 * initial positions; a triangle is in a region when its centroid is.  An empty selection is a
 * warning, an unknown group, body or region an error. */
void cmd_group(YfSim *sim, const YfArgs *a) {
  static const char *const styles[] = {"node", "tri", "both", "union", "subtract", "intersect", NULL};
  static const char *const sels[] = {"region", "id", "body", "nearest", NULL};
  enum { S_NODE, S_TRI, S_BOTH, S_UNION, S_SUBTRACT, S_INTERSECT };
  enum { BY_REGION, BY_ID, BY_BODY, BY_NEAREST };
  YfModel *m = &sim->model;
  arg_count(a, 3, -1);
  const char *name = arg_name(a, 0, "group name");
  if (model_find_body(m, name) >= 0)
    arg_error(a, 0, "is the group of body '%s', which holds exactly that body; choose another name", name);
  int style = arg_choice(a, 1, "group style", styles);
  int nn = m->node.n, nt = m->tri.n;
  unsigned char *ns = yf_calloc((size_t)(nn ? nn : 1), 1, "group selection");
  unsigned char *ts = yf_calloc((size_t)(nt ? nt : 1), 1, "group selection");

  if (style >= S_UNION) {
    arg_count(a, style == S_UNION ? 3 : 4, -1);
    uint64_t first = 0, rest = 0;
    for (int i = 2; i < a->n; i++) {
      uint64_t bit = (uint64_t)1 << group_or_die(m, a, i);
      if (i == 2) first = bit;
      else rest |= bit;
    }
    group_select_sets(m, YF_GROUP_UNION + style - S_UNION, first, rest, ns, ts);
  } else {
    int want_n = style != S_TRI, want_t = style != S_NODE;
    int by = arg_choice(a, 2, "selection", sels);
    if (by == BY_REGION) {
      arg_count(a, 4, 6);
      int r = region_find(a->w[3]);
      if (r < 0) {
        char buf[1024];
        arg_error(a, 3, "unknown region (regions: %s)", region_names(buf, sizeof buf));
      }
      int b = -1;
      if (a->n > 4) {
        if (strcmp(a->w[4], "body") != 0) arg_error(a, 4, "expected 'body B'");
        arg_count(a, 6, 6);
        b = body_or_die(m, a, 5);
      }
      group_select_region(m, r, b, want_n, want_t, ns, ts);
    } else if (by == BY_ID) {
      arg_count(a, 4, -1);
      int nid = a->n - 3;
      long *ids = yf_malloc((size_t)nid * sizeof *ids, "group ids");
      unsigned char *hit = yf_calloc((size_t)nid, 1, "group ids");
      for (int k = 0; k < nid; k++) ids[k] = arg_int(a, 3 + k, "id", LONG_MIN, LONG_MAX);
      group_select_ids(m, ids, nid, want_n, want_t, ns, ts, hit);
      /* an id that selects nothing is a typo; with `both` it must name a node or a triangle */
      for (int k = 0; k < nid; k++) {
        if (hit[k]) continue;
        arg_error(a, 3 + k, "no %s has this id", style == S_NODE ? "node" : style == S_TRI ? "triangle"
                                                                      : "node or triangle");
      }
      free(hit);
      free(ids);
      warn_shared_ids(m, a, name, ns, ts);
    } else if (by == BY_BODY) {
      arg_count(a, 4, 4);
      group_select_body(m, body_or_die(m, a, 3), want_n, want_t, ns, ts);
    } else {
      if (style != S_NODE) arg_error(a, 1, "'nearest' selects a node: use 'group NAME node nearest X Y'");
      arg_count(a, 5, 5);
      double px = arg_coord(a, 3, "x"), py = arg_coord(a, 4, "y");
      int nd;
      double d = group_select_nearest(m, px, py, ns, &nd), reach = mesh_longest_edge(m);
      /* a point far off the mesh (mm typed on a mesh in m) took a node 1000 m away, silently;
       * within one element of the body it is a point given to rounding (no triangles yet: no
       * measure of the mesh, so no check) */
      if (nd >= 0 && reach > 0 && d > reach)
        arg_error(a, fabs(px - m->node.x0[nd]) >= fabs(py - m->node.y0[nd]) ? 3 : 4,
                  "the point (%g, %g) is %g m from the nearest node (node %ld at (%g, %g)), farther than the longest "
                  "triangle edge of the scene, %g m: it lies off the mesh (a coordinate in other units?); give a point "
                  "on the body or within one element of it", px, py, d, (long)m->node.id[nd], m->node.x0[nd],
                  m->node.y0[nd], reach);
    }
  }

  int g = mesh_group_or_die(m, name, &a->loc, "group");
  long c[4];
  group_add(m, g, ns, ts, c);
  if (c[0] == 0 && c[1] == 0) yf_warn(&a->loc, "group %s: the selection is empty", name);
  /* the group as it now stands (groups only grow), as LAMMPS reports its atoms */
  sim_printf(sim, "group %s: %ld node%s, %ld triangle%s\n", name, c[2], c[2] == 1 ? "" : "s", c[3],
             c[3] == 1 ? "" : "s");
  free(ns);
  free(ts);
}
