/* region.c: named regions (box, circle, polygon, inside or outside) and the selections of groups
 * (the words of `region` and `group` are read in deck/cmd_region.c, cmd_group.c).
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
  case YF_REG_BOX: {
    double dx = fmin(x - g->p[0], g->p[2] - x), dy = fmin(y - g->p[1], g->p[3] - y);
    if (dx < -g->tol || dy < -g->tol) return -1;
    return dx > g->tol && dy > g->tol ? 1 : 0;
  }
  case YF_REG_CIRCLE: {
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

int region_add(const char *name, int kind, int out, const double *c, int nc, const YfModel *m) {
  Region g;
  memset(&g, 0, sizeof g);
  snprintf(g.name, sizeof g.name, "%s", name);
  g.kind = kind;
  g.out = out;
  double size, mag = 0;
  if (kind == YF_REG_BOX) {
    for (int k = 0; k < 4; k++) g.p[k] = c[k];
    size = fmax(g.p[2] - g.p[0], g.p[3] - g.p[1]);
    for (int k = 0; k < 4; k++) mag = fmax(mag, fabs(g.p[k]));
  } else if (kind == YF_REG_CIRCLE) {
    for (int k = 0; k < 3; k++) g.p[k] = c[k];
    size = g.p[2];
    mag = fmax(fabs(g.p[0]), fabs(g.p[1]));
  } else {
    g.np = nc / 2;
    g.poly = yf_malloc((size_t)nc * sizeof *g.poly, "polygon");
    double bb[4] = {INFINITY, INFINITY, -INFINITY, -INFINITY};
    for (int k = 0; k < nc; k++) {
      g.poly[k] = c[k];
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
      return -1;
    }
  }
  /* relative to the region's size; the magnitude term covers rounding of coordinates far
   * from the origin (a region small compared with its distance to 0) */
  g.tol = 1e-9 * size + 1e-13 * mag;
  /* A region much larger than the scene (the half-plane idiom `box -1e30 -1e30 X 1e30`) must not
   * get a tolerance larger than the scene itself: cap it by the same rule applied to the nodes
   * meshed so far (mesher rounding scales with the scene, not with the region). */
  const YfNodes *nd = &m->node;
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
  reg[nreg] = g;
  return nreg++;
}

/* ------------------------------------------------------------------------------------------ */
/* group                                                                                       */

const char *region_names(char *buf, size_t cap) {
  size_t k = 0;
  buf[0] = '\0';
  if (!nreg) return "none defined";
  for (int i = 0; i < nreg && k + YF_NAME_MAX + 8 < cap; i++)
    k += (size_t)snprintf(buf + k, cap - k, "%s%s", i ? ", " : "", reg[i].name);
  return buf;
}

void group_select_sets(const YfModel *m, int op, uint64_t first, uint64_t rest, unsigned char *ns,
                       unsigned char *ts) {
  for (int k = 0; k < 2; k++) {
    const uint64_t *gm = k ? m->tri.gmask : m->node.gmask;
    unsigned char *sel = k ? ts : ns;
    int n = k ? m->tri.n : m->node.n;
    for (int i = 0; i < n; i++) {
      uint64_t g = gm[i];
      if (op == YF_GROUP_UNION) sel[i] = (g & (first | rest)) != 0;
      else if (op == YF_GROUP_SUBTRACT) sel[i] = (g & first) && !(g & rest);
      else sel[i] = (g & (first | rest)) == (first | rest);
    }
  }
}

void group_select_region(const YfModel *m, int r, int b, int want_n, int want_t, unsigned char *ns,
                         unsigned char *ts) {
  const double *X = m->node.x0, *Y = m->node.y0;
  if (want_n)
    for (int i = 0; i < m->node.n; i++)
      ns[i] = (b < 0 || m->node.body[i] == b) && region_contains(r, X[i], Y[i]);
  if (want_t)
    for (int t = 0; t < m->tri.n; t++) {
      if (b >= 0 && m->tri.body[t] != b) continue;
      const int *v = m->tri.v + 3 * t;
      double cx = (X[v[0]] + X[v[1]] + X[v[2]]) / 3.0, cy = (Y[v[0]] + Y[v[1]] + Y[v[2]]) / 3.0;
      ts[t] = (unsigned char)region_contains(r, cx, cy);
    }
}

void group_select_ids(const YfModel *m, const long *ids, int nid, int want_n, int want_t, unsigned char *ns,
                      unsigned char *ts, unsigned char *hit) {
  YfIdMap want;
  idmap_init(&want);
  unsigned char *hit_n = yf_calloc((size_t)nid, 1, "group ids");
  unsigned char *hit_t = yf_calloc((size_t)nid, 1, "group ids");
  for (int k = 0; k < nid; k++) idmap_put(&want, ids[k], k); /* a repeated id keeps its first position */
  if (want_n)
    for (int i = 0; i < m->node.n; i++) {
      int k = idmap_get(&want, m->node.id[i]);
      if (k >= 0) ns[i] = hit_n[k] = 1;
    }
  if (want_t)
    for (int t = 0; t < m->tri.n; t++) {
      int k = idmap_get(&want, m->tri.id[t]);
      if (k >= 0) ts[t] = hit_t[k] = 1;
    }
  for (int k = 0; k < nid; k++) {
    int pos = idmap_get(&want, ids[k]);
    hit[k] = hit_n[pos] || hit_t[pos];
  }
  free(hit_n);
  free(hit_t);
  idmap_free(&want);
}

void group_select_body(const YfModel *m, int b, int want_n, int want_t, unsigned char *ns, unsigned char *ts) {
  if (want_n)
    for (int i = 0; i < m->node.n; i++) ns[i] = m->node.body[i] == b;
  if (want_t)
    for (int t = 0; t < m->tri.n; t++) ts[t] = m->tri.body[t] == b;
}

double group_select_nearest(const YfModel *m, double px, double py, unsigned char *ns, int *node) {
  const double *X = m->node.x0, *Y = m->node.y0;
  int nn = m->node.n, best = -1;
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
  *node = best;
  return sqrt(bd);
}

void group_add(YfModel *m, int g, const unsigned char *ns, const unsigned char *ts, long count[4]) {
  uint64_t bit = (uint64_t)1 << g;
  int nn = m->node.n, nt = m->tri.n;
  long cn = 0, ct = 0;
  for (int i = 0; i < nn; i++)
    if (ns[i]) m->node.gmask[i] |= bit, cn++;
  for (int t = 0; t < nt; t++)
    if (ts[t]) m->tri.gmask[t] |= bit, ct++;
  /* the group as it now stands (groups only grow) */
  long gn = 0, gt = 0;
  for (int i = 0; i < nn; i++) gn += (m->node.gmask[i] & bit) != 0;
  for (int t = 0; t < nt; t++) gt += (m->tri.gmask[t] & bit) != 0;
  count[0] = cn, count[1] = ct, count[2] = gn, count[3] = gt;
}
