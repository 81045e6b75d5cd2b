/* region.c: named regions (box, circle, polygon, inside or outside) and the `group` command.
 *
 * Regions are a small static table: a deck defines a handful, and each is tested once per node
 * or triangle when a group is built, never inside the step.  Containment is decided with a
 * tolerance so that nodes placed exactly on a region's edge (the usual way to pick a support or
 * a loaded side) are inside whatever rounding the mesher did.
 *
 * Groups are bits of node.gmask / tri.gmask (model.h).  `group` only ever adds members (like
 * LAMMPS's group command), so a set operation writes into a new group and never removes from
 * its operands.  Triangles are selected by the centroid of their initial corners.
 */
#include <float.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "mesh.h"
#include "region.h"
#include "deck.h"
#include "sim.h"

enum { REG_BOX, REG_CIRCLE, REG_POLYGON };

typedef struct {
  char name[YF_NAME_MAX];
  int kind;
  int out;      /* side out: the complement (boundary kept)       */
  double p[4];  /* box x0 y0 x1 y1 | circle xc yc r               */
  double *poly; /* polygon vertices x, y (np of them)             */
  int np;
  double tol;   /* boundary tolerance [m]                          */
} Region;

static Region *reg;
static int nreg;

void region_reset(void) {
  for (int i = 0; i < nreg; i++) free(reg[i].poly);
  free(reg);
  reg = NULL;
  nreg = 0;
}

int region_find(const char *name) {
  for (int i = 0; i < nreg; i++)
    if (!strcmp(reg[i].name, name)) return i;
  return -1;
}

int region_count(void) { return nreg; }
const char *region_name(int r) { return r >= 0 && r < nreg ? reg[r].name : NULL; }

/* Distance from (x, y) to the segment a-b. */
static double seg_dist(double x, double y, double ax, double ay, double bx, double by) {
  double dx = bx - ax, dy = by - ay;
  double l2 = dx * dx + dy * dy;
  double s = l2 > 0 ? ((x - ax) * dx + (y - ay) * dy) / l2 : 0.0;
  s = s < 0 ? 0 : s > 1 ? 1 : s;
  return hypot(x - (ax + s * dx), y - (ay + s * dy));
}

/* 1 strictly inside, 0 on the boundary (within tol), -1 outside. */
static int classify(const Region *g, double x, double y) {
  switch (g->kind) {
  case REG_BOX: {
    double dx = fmin(x - g->p[0], g->p[2] - x), dy = fmin(y - g->p[1], g->p[3] - y);
    if (dx < -g->tol || dy < -g->tol) return -1;
    return dx > g->tol && dy > g->tol ? 1 : 0;
  }
  case REG_CIRCLE: {
    double d = hypot(x - g->p[0], y - g->p[1]) - g->p[2];
    return d > g->tol ? -1 : d < -g->tol ? 1 : 0;
  }
  default: {
    const double *v = g->poly;
    int n = g->np, odd = 0;
    for (int i = 0, j = n - 1; i < n; j = i++) {
      double xi = v[2 * i], yi = v[2 * i + 1], xj = v[2 * j], yj = v[2 * j + 1];
      if (seg_dist(x, y, xi, yi, xj, yj) <= g->tol) return 0;
      /* crossing number (even-odd rule) with a ray towards +x */
      if ((yi > y) != (yj > y) && x < xj + (y - yj) * (xi - xj) / (yi - yj)) odd = !odd;
    }
    return odd ? 1 : -1;
  }
  }
}

int region_contains(int r, double x, double y) {
  YF_ASSERT(r >= 0 && r < nreg);
  int c = classify(&reg[r], x, y);
  return reg[r].out ? c <= 0 : c >= 0;
}

/* region NAME box X0 Y0 X1 Y1 [side in|out]
 * region NAME circle XC YC R [side in|out]
 * region NAME polygon X1 Y1 X2 Y2 X3 Y3 ... [side in|out]
 * Coordinates in m.  A box may be flat (X0 = X1 or Y0 = Y1) to pick the nodes on a line. */
void cmd_region(struct YfSim *sim, const YfArgs *a) {
  static const char *const kinds[] = {"box", "circle", "polygon", NULL};
  static const char *const sides[] = {"in", "out", NULL};
  (void)sim;
  arg_count(a, 2, -1);
  const char *name = arg_word(a, 0, "region name");
  if (strlen(name) >= YF_NAME_MAX) arg_error(a, 0, "name longer than %d characters", YF_NAME_MAX - 1);
  if (region_find(name) >= 0) arg_error(a, 0, "region already exists");
  int kind = arg_choice(a, 1, "region style", kinds);
  int n = a->n, out = 0;
  if (n >= 4 && !strcmp(a->w[n - 2], "side")) {
    out = arg_choice(a, n - 1, "side", sides);
    n -= 2;
  }
  Region g;
  memset(&g, 0, sizeof g);
  snprintf(g.name, sizeof g.name, "%s", name);
  g.kind = kind;
  g.out = out;
  double size, mag = 0;
  if (kind == REG_BOX) {
    if (n != 6) arg_error(a, n < 6 ? n - 1 : 6, "box expects X0 Y0 X1 Y1 [side in|out]");
    for (int k = 0; k < 4; k++) g.p[k] = arg_num(a, 2 + k, k % 2 ? "y" : "x");
    if (g.p[2] < g.p[0]) arg_error(a, 4, "X1 must not be less than X0 = %g", g.p[0]);
    if (g.p[3] < g.p[1]) arg_error(a, 5, "Y1 must not be less than Y0 = %g", g.p[1]);
    size = fmax(g.p[2] - g.p[0], g.p[3] - g.p[1]);
    for (int k = 0; k < 4; k++) mag = fmax(mag, fabs(g.p[k]));
  } else if (kind == REG_CIRCLE) {
    if (n != 5) arg_error(a, n < 5 ? n - 1 : 5, "circle expects XC YC R [side in|out]");
    g.p[0] = arg_num(a, 2, "xc");
    g.p[1] = arg_num(a, 3, "yc");
    g.p[2] = arg_pos(a, 4, "radius");
    size = g.p[2];
    mag = fmax(fabs(g.p[0]), fabs(g.p[1]));
  } else {
    int nc = n - 2;
    if (nc < 6) arg_error(a, n - 1, "a polygon needs at least 3 points (X1 Y1 X2 Y2 X3 Y3 ...)");
    if (nc % 2) arg_error(a, n - 1, "polygon coordinates come in X Y pairs (odd count %d)", nc);
    g.np = nc / 2;
    g.poly = yf_malloc((size_t)nc * sizeof *g.poly, "polygon");
    double bb[4] = {INFINITY, INFINITY, -INFINITY, -INFINITY};
    for (int k = 0; k < nc; k++) {
      g.poly[k] = arg_num(a, 2 + k, k % 2 ? "y" : "x");
      bb[k % 2] = fmin(bb[k % 2], g.poly[k]);
      bb[2 + k % 2] = fmax(bb[2 + k % 2], g.poly[k]);
      mag = fmax(mag, fabs(g.poly[k]));
    }
    size = hypot(bb[2] - bb[0], bb[3] - bb[1]);
    double area2 = 0;
    for (int i = 0, j = g.np - 1; i < g.np; j = i++)
      area2 += g.poly[2 * j] * g.poly[2 * i + 1] - g.poly[2 * i] * g.poly[2 * j + 1];
    if (!(fabs(area2) > 1e-12 * size * size)) {
      free(g.poly);
      arg_error(a, 2, "the polygon has zero area");
    }
  }
  /* relative to the region's size; the magnitude term covers rounding of coordinates far
   * from the origin (a region small compared with its distance to 0) */
  g.tol = 1e-9 * size + 1e-13 * mag;
  /* A region much larger than the scene (the half-plane idiom `box -1e30 -1e30 X 1e30`) must not
   * get a tolerance larger than the scene itself: cap it by the same rule applied to the nodes
   * meshed so far (mesher rounding scales with the scene, not with the region). */
  const YfNodes *nd = &sim->model.node;
  if (nd->n > 0) {
    double bb[4] = {INFINITY, INFINITY, -INFINITY, -INFINITY}, nmag = 0;
    for (int i = 0; i < nd->n; i++) {
      bb[0] = fmin(bb[0], nd->x0[i]); bb[1] = fmin(bb[1], nd->y0[i]);
      bb[2] = fmax(bb[2], nd->x0[i]); bb[3] = fmax(bb[3], nd->y0[i]);
      nmag = fmax(nmag, fmax(fabs(nd->x0[i]), fabs(nd->y0[i])));
    }
    double cap = 1e-9 * fmax(bb[2] - bb[0], bb[3] - bb[1]) + 1e-13 * nmag;
    if (cap > 0 && g.tol > cap) g.tol = cap;
  }
  reg = yf_realloc(reg, (size_t)(nreg + 1) * sizeof *reg, "regions");
  reg[nreg++] = g;
}

/* ------------------------------------------------------------------------------------------ */
/* group                                                                                       */

static const char *region_list(char *buf, size_t cap) {
  size_t k = 0;
  buf[0] = '\0';
  if (!nreg) return "none defined";
  for (int i = 0; i < nreg && k + YF_NAME_MAX + 8 < cap; i++)
    k += (size_t)snprintf(buf + k, cap - k, "%s%s", i ? ", " : "", reg[i].name);
  return buf;
}

static int body_or_die(const YfModel *m, const YfArgs *a, int i) {
  char buf[512];
  int b = model_find_body(m, a->w[i]);
  if (b < 0) arg_error(a, i, "unknown body (bodies: %s)", mesh_body_names(m, buf, sizeof buf));
  return b;
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
void cmd_group(struct YfSim *sim, const YfArgs *a) {
  static const char *const styles[] = {"node", "tri", "both", "union", "subtract", "intersect", NULL};
  static const char *const sels[] = {"region", "id", "body", "nearest", NULL};
  enum { S_NODE, S_TRI, S_BOTH, S_UNION, S_SUBTRACT, S_INTERSECT };
  enum { BY_REGION, BY_ID, BY_BODY, BY_NEAREST };
  YfModel *m = &sim->model;
  arg_count(a, 3, -1);
  const char *name = arg_word(a, 0, "group name");
  if (strlen(name) >= YF_NAME_MAX) arg_error(a, 0, "name longer than %d characters", YF_NAME_MAX - 1);
  if (model_find_body(m, name) >= 0)
    arg_error(a, 0, "is the group of body '%s', which holds exactly that body; choose another name", name);
  int style = arg_choice(a, 1, "group style", styles);
  int nn = m->node.n, nt = m->tri.n;
  unsigned char *ns = yf_calloc((size_t)(nn ? nn : 1), 1, "group selection");
  unsigned char *ts = yf_calloc((size_t)(nt ? nt : 1), 1, "group selection");
  const double *X = m->node.x0, *Y = m->node.y0;

  if (style >= S_UNION) {
    arg_count(a, style == S_UNION ? 3 : 4, -1);
    uint64_t first = 0, rest = 0;
    for (int i = 2; i < a->n; i++) {
      uint64_t bit = (uint64_t)1 << group_or_die(m, a, i);
      if (i == 2) first = bit;
      else rest |= bit;
    }
    for (int k = 0; k < 2; k++) {
      const uint64_t *gm = k ? m->tri.gmask : m->node.gmask;
      unsigned char *sel = k ? ts : ns;
      int n = k ? nt : nn;
      for (int i = 0; i < n; i++) {
        uint64_t g = gm[i];
        if (style == S_UNION) sel[i] = (g & (first | rest)) != 0;
        else if (style == S_SUBTRACT) sel[i] = (g & first) && !(g & rest);
        else sel[i] = (g & (first | rest)) == (first | rest);
      }
    }
  } else {
    int want_n = style != S_TRI, want_t = style != S_NODE;
    int by = arg_choice(a, 2, "selection", sels);
    if (by == BY_REGION) {
      arg_count(a, 4, 6);
      int r = region_find(a->w[3]);
      if (r < 0) {
        char buf[1024];
        arg_error(a, 3, "unknown region (regions: %s)", region_list(buf, sizeof buf));
      }
      int b = -1;
      if (a->n > 4) {
        if (strcmp(a->w[4], "body") != 0) arg_error(a, 4, "expected 'body B'");
        arg_count(a, 6, 6);
        b = body_or_die(m, a, 5);
      }
      if (want_n)
        for (int i = 0; i < nn; i++)
          ns[i] = (b < 0 || m->node.body[i] == b) && region_contains(r, X[i], Y[i]);
      if (want_t)
        for (int t = 0; t < nt; t++) {
          if (b >= 0 && m->tri.body[t] != b) continue;
          const int *v = m->tri.v + 3 * t;
          double cx = (X[v[0]] + X[v[1]] + X[v[2]]) / 3.0, cy = (Y[v[0]] + Y[v[1]] + Y[v[2]]) / 3.0;
          ts[t] = (unsigned char)region_contains(r, cx, cy);
        }
    } else if (by == BY_ID) {
      arg_count(a, 4, -1);
      YfIdMap want;
      idmap_init(&want);
      int nid = a->n - 3;
      unsigned char *hit_n = yf_calloc((size_t)nid, 1, "group ids");
      unsigned char *hit_t = yf_calloc((size_t)nid, 1, "group ids");
      for (int k = 0; k < nid; k++) {
        long id = arg_int(a, 3 + k, "id", LONG_MIN, LONG_MAX);
        idmap_put(&want, id, k); /* a repeated id keeps its first position */
      }
      if (want_n)
        for (int i = 0; i < nn; i++) {
          int k = idmap_get(&want, m->node.id[i]);
          if (k >= 0) ns[i] = hit_n[k] = 1;
        }
      if (want_t)
        for (int t = 0; t < nt; t++) {
          int k = idmap_get(&want, m->tri.id[t]);
          if (k >= 0) ts[t] = hit_t[k] = 1;
        }
      /* an id that selects nothing is a typo; with `both` it must name a node or a triangle */
      for (int k = 0; k < nid; k++) {
        int pos = idmap_get(&want, arg_int(a, 3 + k, "id", LONG_MIN, LONG_MAX));
        if (hit_n[pos] || hit_t[pos]) continue;
        arg_error(a, 3 + k, "no %s has this id", style == S_NODE ? "node" : style == S_TRI ? "triangle"
                                                                      : "node or triangle");
      }
      free(hit_n);
      free(hit_t);
      idmap_free(&want);
    } else if (by == BY_BODY) {
      arg_count(a, 4, 4);
      int b = body_or_die(m, a, 3);
      if (want_n)
        for (int i = 0; i < nn; i++) ns[i] = m->node.body[i] == b;
      if (want_t)
        for (int t = 0; t < nt; t++) ts[t] = m->tri.body[t] == b;
    } else {
      if (style != S_NODE) arg_error(a, 1, "'nearest' selects a node: use 'group NAME node nearest X Y'");
      arg_count(a, 5, 5);
      double px = arg_num(a, 3, "x"), py = arg_num(a, 4, "y");
      int best = -1;
      double bd = INFINITY;
      for (int i = 0; i < nn; i++) {
        double d = (X[i] - px) * (X[i] - px) + (Y[i] - py) * (Y[i] - py);
        if (d < bd) bd = d, best = i;
      }
      if (best >= 0) {
        /* copies of the node (fracturing bodies) belong with it */
        int root = mesh_node_root(m, best);
        for (int i = 0; i < nn; i++) ns[i] = mesh_node_root(m, i) == root;
      }
    }
  }

  int g = mesh_group_or_die(m, name, &a->loc, "group");
  uint64_t bit = (uint64_t)1 << g;
  long cn = 0, ct = 0;
  for (int i = 0; i < nn; i++)
    if (ns[i]) m->node.gmask[i] |= bit, cn++;
  for (int t = 0; t < nt; t++)
    if (ts[t]) m->tri.gmask[t] |= bit, ct++;
  if (cn == 0 && ct == 0) yf_warn(&a->loc, "group %s: the selection is empty", name);
  /* the group as it now stands (groups only grow), as LAMMPS reports its atoms */
  long gn = 0, gt = 0;
  for (int i = 0; i < nn; i++) gn += (m->node.gmask[i] & bit) != 0;
  for (int t = 0; t < nt; t++) gt += (m->tri.gmask[t] & bit) != 0;
  sim_printf(sim, "group %s: %ld node%s, %ld triangle%s\n", name, gn, gn == 1 ? "" : "s", gt, gt == 1 ? "" : "s");
  free(ns);
  free(ts);
}
