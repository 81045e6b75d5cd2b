/* mesh.c: putting nodes and triangles into the model, and mesh topology queries.
 *
 * Every mesh command creates one body and a group of the same name (model_add_body) holding its
 * nodes and triangles, so later commands can select "the beam" without a region.  Triangles are
 * always stored counter-clockwise: the structured mesher builds them so, the Gmsh reader flips
 * clockwise ones, and inline triangles (`triangle` commands) are refused when clockwise (a Y2D user must know that
 * the deck's orientation is wrong, because Y2D would compute negative areas from it).
 *
 * Inline nodes and triangles (`node`, `triangle`, `nodes FILE`, `triangles FILE`) are referred
 * to by user ids; the deck layer reads their words (deck/cmd_node.c ...) and this file keeps the
 * model right.  The id -> index maps live in a small static state tied to the model they were
 * built for, since one process runs one simulation (mesh_reset() forgets them for tests).
 *
 * Units: coordinates in m.
 */
#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "edgesort.h"
#include "memcap.h"
#include "mesh.h"

/* ------------------------------------------------------------------------------------------ */
/* small integer map                                                                           */

void idmap_init(YfIdMap *h) { memset(h, 0, sizeof *h); }

void idmap_free(YfIdMap *h) {
  free(h->key);
  free(h->val);
  memset(h, 0, sizeof *h);
}

static size_t idmap_slot(long long key, size_t cap) {
  unsigned long long z = (unsigned long long)key * 0x9E3779B97F4A7C15ull; /* Fibonacci hashing */
  return (size_t)(z ^ (z >> 29)) & (cap - 1);
}

static void idmap_grow(YfIdMap *h) {
  size_t cap = h->cap ? 2 * h->cap : 64;
  long long *key = yf_malloc(cap * sizeof *key, "id map");
  int *val = yf_malloc(cap * sizeof *val, "id map");
  for (size_t i = 0; i < cap; i++) val[i] = -1;
  for (size_t i = 0; i < h->cap; i++) {
    if (h->val[i] < 0) continue;
    size_t s = idmap_slot(h->key[i], cap);
    while (val[s] >= 0) s = (s + 1) & (cap - 1);
    key[s] = h->key[i];
    val[s] = h->val[i];
  }
  free(h->key);
  free(h->val);
  h->key = key;
  h->val = val;
  h->cap = cap;
}

int idmap_put(YfIdMap *h, long long key, int val) {
  YF_ASSERT(val >= 0);
  if (2 * (h->n + 1) > h->cap) idmap_grow(h); /* load factor <= 1/2 */
  size_t s = idmap_slot(key, h->cap);
  while (h->val[s] >= 0) {
    if (h->key[s] == key) return 0;
    s = (s + 1) & (h->cap - 1);
  }
  h->key[s] = key;
  h->val[s] = val;
  h->n++;
  return 1;
}

int idmap_get(const YfIdMap *h, long long key) {
  if (!h->cap) return -1;
  size_t s = idmap_slot(key, h->cap);
  while (h->val[s] >= 0) {
    if (h->key[s] == key) return h->val[s];
    s = (s + 1) & (h->cap - 1);
  }
  return -1;
}

/* ------------------------------------------------------------------------------------------ */
/* shared helpers                                                                              */

typedef const char *(*NameAt)(const YfModel *m, int i);
static const char *mat_name_at(const YfModel *m, int i) { return m->mat[i].name; }
static const char *body_name_at(const YfModel *m, int i) { return m->body[i].name; }
static const char *group_name_at(const YfModel *m, int i) { return m->group[i].name; }

static const char *name_list(const YfModel *m, int n, NameAt at, char *buf, size_t cap) {
  size_t k = 0;
  buf[0] = '\0';
  if (n == 0) {
    snprintf(buf, cap, "none defined");
    return buf;
  }
  for (int i = 0; i < n; i++) {
    const char *s = at(m, i);
    size_t need = strlen(s) + 2;
    if (k + need + 4 >= cap) {
      snprintf(buf + k, cap - k, "%s...", i ? ", " : "");
      break;
    }
    k += (size_t)snprintf(buf + k, cap - k, "%s%s", i ? ", " : "", s);
  }
  return buf;
}

const char *mesh_material_names(const YfModel *m, char *buf, size_t cap) {
  return name_list(m, m->nmat, mat_name_at, buf, cap);
}
const char *mesh_body_names(const YfModel *m, char *buf, size_t cap) {
  return name_list(m, m->nbody, body_name_at, buf, cap);
}
const char *mesh_group_names(const YfModel *m, char *buf, size_t cap) {
  return name_list(m, m->ngroup, group_name_at, buf, cap);
}

int mesh_group_or_die(YfModel *m, const char *name, const YfLoc *loc, const char *cmd) {
  if (strlen(name) >= YF_NAME_MAX)
    yf_deck_error(loc, "%s: group name '%s' is longer than %d characters", cmd, name, YF_NAME_MAX - 1);
  int g = model_group(m, name, 1);
  if (g < 0)
    yf_deck_error(loc, "%s: cannot create group '%s': all %d groups are in use", cmd, name,
                  YF_MAX_GROUPS);
  return g;
}

int mesh_new_body(YfModel *m, const char *name, int mat, const YfLoc *loc, const char *cmd) {
  char buf[512];
  if (strlen(name) >= YF_NAME_MAX)
    yf_deck_error(loc, "%s: body name '%s' is longer than %d characters", cmd, name, YF_NAME_MAX - 1);
  if (model_find_body(m, name) >= 0)
    yf_deck_error(loc, "%s: body '%s' already exists (bodies: %s)", cmd, name,
                  mesh_body_names(m, buf, sizeof buf));
  if (model_group(m, name, 0) >= 0)
    yf_deck_error(loc, "%s: '%s' is already a group name; a body needs a group of its own name",
                  cmd, name);
  if (m->ngroup >= YF_MAX_GROUPS)
    yf_deck_error(loc, "%s: cannot create body '%s': all %d groups are in use", cmd, name,
                  YF_MAX_GROUPS);
  int b = model_add_body(m, name, mat);
  YF_ASSERT(m->body[b].group >= 0);
  return b;
}

int mesh_next_node_id(const YfModel *m) {
  long mx = 0;
  for (int i = 0; i < m->node.n; i++)
    if (m->node.id[i] > mx) mx = m->node.id[i];
  if (mx >= INT_MAX) yf_deck_error(NULL, "node ids exhausted (largest id is %ld)", mx);
  return (int)mx + 1;
}

int mesh_next_tri_id(const YfModel *m) {
  long mx = 0;
  for (int i = 0; i < m->tri.n; i++)
    if (m->tri.id[i] > mx) mx = m->tri.id[i];
  if (mx >= INT_MAX) yf_deck_error(NULL, "triangle ids exhausted (largest id is %ld)", mx);
  return (int)mx + 1;
}

double mesh_longest_edge(const YfModel *m) {
  const double *X = m->node.x0, *Y = m->node.y0;
  double l2 = 0.0;
  for (int t = 0; t < m->tri.n; t++)
    for (int k = 0; k < 3; k++) {
      int a = m->tri.v[3 * t + k], b = m->tri.v[3 * t + (k + 1) % 3];
      double dx = X[b] - X[a], dy = Y[b] - Y[a], d = dx * dx + dy * dy;
      if (d > l2) l2 = d;
    }
  return sqrt(l2);
}

int mesh_node_root(const YfModel *m, int i) {
  /* parent chains are one step long in practice; the bound guards against a corrupt cycle */
  for (int k = 0; k < 64 && m->node.parent[i] != i; k++) i = m->node.parent[i];
  return i;
}

/* ------------------------------------------------------------------------------------------ */
/* mesh rect                                                                                   */


/* The structured mesher of `mesh rect` (mesh.h).
 *
 * NX x NY cells; right: each cell cut by its lower-left -> upper-right diagonal; left: by the
 * other one; alt: the two alternate like a chessboard (cell (i,j) is `right` when i+j is even);
 * cross: a centre node per cell and four triangles.  Corner nodes are numbered row by row from
 * the bottom (index j*(NX+1)+i), cross centres follow, also row by row; triangles go cell by
 * cell in the same order.  Ids continue after the largest existing ids. */
const char *const mesh_patterns[] = {"right", "left", "alt", "cross", NULL};

int mesh_rect(YfModel *m, const YfRectSpec *spec, const YfLoc *loc) {
  const char *const *pats = mesh_patterns;
  const int mat = spec->mat, pat = spec->pattern;
  const long nx = spec->nx, ny = spec->ny;
  const double x0 = spec->x0, y0 = spec->y0, x1 = spec->x1, y1 = spec->y1;
  {
    /* Volumetric locking: with one diagonal per cell the constant-strain triangles cannot deform
     * at constant volume in bending (each cell's pair has fewer free modes than constraints), so
     * near-incompressible plane strain is far too stiff: the cantilever of docs/VERIFICATION.md
     * deflects about half of Timoshenko's value at nu = 0.49, where the crossed mesh is within a
     * few per cent.  Warn, do not refuse: the pattern is right for compressible solids. */
    const YfMaterial *mt = &m->mat[mat];
    if ((pat == YF_PAT_RIGHT || pat == YF_PAT_LEFT) && mt->plane == YF_PLANE_STRAIN && mt->nu > 0.4)
      yf_warn(loc, "mesh rect: pattern %s with material '%s' in plane strain at nu = %g locks (constant-strain "
              "triangles in near-incompressible bending: about half the true deflection at nu = 0.49); use "
              "'pattern cross' (docs/VERIFICATION.md, volumetric locking)", pats[pat], mt->name, mt->nu);
  }
  long long nnode = (long long)(nx + 1) * (ny + 1) + (pat == YF_PAT_CROSS ? (long long)nx * ny : 0);
  long long ntri = (long long)nx * ny * (pat == YF_PAT_CROSS ? 4 : 2);
  if (nnode > INT_MAX / 4 || ntri > INT_MAX / 8) return -2;
  {
    char what[160]; /* before any allocation: a size beyond memory is a deck error, not a crash */
    snprintf(what, sizeof what, "mesh rect: %lld x %lld cells (%lld nodes, %lld triangles)", (long long)nx,
             (long long)ny, nnode, ntri);
    yf_mem_check(loc, (double)(m->node.n + nnode) * YF_BYTES_PER_NODE + (double)(m->tri.n + ntri) * YF_BYTES_PER_TRI,
                 what);
  }

  int b = mesh_new_body(m, spec->body, mat, loc, "mesh rect");
  uint64_t bit = (uint64_t)1 << m->body[b].group;
  int nid = mesh_next_node_id(m), tid = mesh_next_tri_id(m);
  if ((long long)nid + nnode > INT_MAX || (long long)tid + ntri > INT_MAX)
    return -1;

  model_reserve(m, (int)nnode, (int)ntri); /* counts known: exact sizes */
  /* Grid coordinates: the last row/column is placed exactly on x1/y1 so that regions and
   * supports selecting the edge x = x1 catch every node there. */
  int base = m->node.n;
  for (long j = 0; j <= ny; j++) {
    double y = j == ny ? y1 : y0 + (y1 - y0) * ((double)j / (double)ny);
    for (long i = 0; i <= nx; i++) {
      double x = i == nx ? x1 : x0 + (x1 - x0) * ((double)i / (double)nx);
      int k = model_add_node(m, x, y, nid++, b);
      m->node.gmask[k] |= bit;
    }
  }
  int cbase = m->node.n;
  if (pat == YF_PAT_CROSS)
    for (long j = 0; j < ny; j++)
      for (long i = 0; i < nx; i++) {
        double x = x0 + (x1 - x0) * (((double)i + 0.5) / (double)nx);
        double y = y0 + (y1 - y0) * (((double)j + 0.5) / (double)ny);
        int k = model_add_node(m, x, y, nid++, b);
        m->node.gmask[k] |= bit;
      }

  for (long j = 0; j < ny; j++)
    for (long i = 0; i < nx; i++) {
      /* cell corners counter-clockwise from the lower left */
      int p = base + (int)(j * (nx + 1) + i);
      int q = p + 1, r = p + 1 + (int)(nx + 1), s = p + (int)(nx + 1);
      int t[4][3], nt = 2;
      int use_right = pat == YF_PAT_RIGHT || (pat == YF_PAT_ALT && (i + j) % 2 == 0);
      if (pat == YF_PAT_CROSS) {
        int c = cbase + (int)(j * nx + i);
        int tt[4][3] = {{p, q, c}, {q, r, c}, {r, s, c}, {s, p, c}};
        memcpy(t, tt, sizeof tt);
        nt = 4;
      } else if (use_right) {
        int tt[2][3] = {{p, q, r}, {p, r, s}};
        memcpy(t, tt, sizeof tt);
      } else {
        int tt[2][3] = {{p, q, s}, {q, r, s}};
        memcpy(t, tt, sizeof tt);
      }
      for (int k = 0; k < nt; k++) {
        int e = model_add_tri(m, t[k][0], t[k][1], t[k][2], mat, tid++, b);
        m->tri.gmask[e] |= bit;
      }
    }
  return b;
}

/* ------------------------------------------------------------------------------------------ */
/* inline nodes and triangles                                                                  */

static struct {
  const YfModel *owner; /* the model the maps below describe */
  YfIdMap node, tri;    /* user id -> index of inline nodes / triangles */
  int *body;            /* flags per body index: 1 = made by inline commands */
  int nbody;
} inl;

void mesh_reset(void) {
  idmap_free(&inl.node);
  idmap_free(&inl.tri);
  free(inl.body);
  memset(&inl, 0, sizeof inl);
}

void mesh_renumbered(const YfModel *m, const int *tnew, const int *nnew) {
  if (inl.owner != m) return;
  /* the inline ids name the same nodes and triangles at their new indices (a 'triangle' after a
   * partitioned run took its corners from the old numbering: "clockwise", or other nodes) */
  for (size_t i = 0; i < inl.node.cap; i++)
    if (inl.node.val[i] >= 0) inl.node.val[i] = nnew[inl.node.val[i]];
  for (size_t i = 0; i < inl.tri.cap; i++)
    if (inl.tri.val[i] >= 0) inl.tri.val[i] = tnew[inl.tri.val[i]];
}

static void inline_bind(const YfModel *m) {
  /* a different model, or a new one at the same address (it has fewer bodies than we made) */
  if (inl.owner != m || m->nbody < inl.nbody) {
    mesh_reset();
    inl.owner = m;
  }
}

static int is_inline_body(int b) { return b >= 0 && b < inl.nbody && inl.body[b]; }

/* Body for inline input: created on first use (its material is set by its first triangle). */
static int inline_body(YfModel *m, const char *name, const YfLoc *loc, const char *cmd) {
  int b = model_find_body(m, name);
  if (b >= 0) {
    if (!is_inline_body(b))
      yf_deck_error(loc, "%s: body '%s' was made by a mesh command; inline nodes and triangles need "
                    "a body of their own", cmd, name);
    return b;
  }
  b = mesh_new_body(m, name, -1, loc, cmd);
  inl.body = yf_realloc(inl.body, (size_t)(b + 1) * sizeof *inl.body, "inline bodies");
  for (int k = inl.nbody; k <= b; k++) inl.body[k] = 0;
  inl.nbody = b + 1;
  inl.body[b] = 1;
  return b;
}

void mesh_inline_node(YfModel *m, long id, double x, double y, const char *bname,
                            const YfLoc *loc, const char *cmd) {
  if (!(fabs(x) <= YF_RANGE_MAX && fabs(y) <= YF_RANGE_MAX))
    yf_deck_error(loc, "%s: node %ld at (%g, %g) is beyond +-%g m, the range the arithmetic holds (areas "
                  "and energies multiply coordinates)", cmd, id, x, y, YF_RANGE_MAX);
  inline_bind(m);
  int b = inline_body(m, bname, loc, cmd);
  if (idmap_get(&inl.node, id) >= 0)
    yf_deck_error(loc, "%s: node id %ld is defined twice", cmd, id);
  int k = model_add_node(m, x, y, (int)id, b);
  m->node.gmask[k] |= (uint64_t)1 << m->body[b].group;
  idmap_put(&inl.node, id, k);
}

int mesh_tri_degenerate(double x0, double y0, double x1, double y1, double x2, double y2, double *d2) {
  double ax = x1 - x0, ay = y1 - y0, bx = x2 - x0, by = y2 - y0, cx = x2 - x1, cy = y2 - y1;
  double d = ax * by - bx * ay;
  double l2 = fmax(ax * ax + ay * ay, fmax(bx * bx + by * by, cx * cx + cy * cy));
  *d2 = d;
  return !(fabs(d) > 1e-12 * l2) || !(fabs(d) > 1e-280);
}

void mesh_inline_tri(YfModel *m, long id, const long nid[3], int mat, const char *bname,
                           const YfLoc *loc, const char *cmd) {
  inline_bind(m);
  int b = inline_body(m, bname, loc, cmd);
  if (idmap_get(&inl.tri, id) >= 0)
    yf_deck_error(loc, "%s: triangle id %ld is defined twice", cmd, id);
  int v[3];
  for (int k = 0; k < 3; k++) {
    v[k] = idmap_get(&inl.node, nid[k]);
    if (v[k] < 0)
      yf_deck_error(loc, "%s: triangle %ld: node %ld is not defined (define it with 'node %ld X Y' "
                    "before the triangle)", cmd, id, nid[k], nid[k]);
    if (m->node.body[v[k]] != b)
      yf_deck_error(loc, "%s: triangle %ld is in body '%s' but its node %ld is in body '%s'", cmd,
                    id, m->body[b].name, nid[k], m->body[m->node.body[v[k]]].name);
  }
  if (nid[0] == nid[1] || nid[1] == nid[2] || nid[0] == nid[2])
    yf_deck_error(loc, "%s: triangle %ld repeats a node (%ld %ld %ld)", cmd, id, nid[0], nid[1], nid[2]);
  const double *X = m->node.x0, *Y = m->node.y0;
  double d;
  if (mesh_tri_degenerate(X[v[0]], Y[v[0]], X[v[1]], Y[v[1]], X[v[2]], Y[v[2]], &d))
    yf_deck_error(loc, "%s: triangle %ld has zero area (nodes %ld %ld %ld are collinear, or the area %g m^2 is "
                  "below what doubles hold: use larger units)", cmd, id, nid[0], nid[1], nid[2], 0.5 * fabs(d));
  if (d < 0)
    yf_deck_error(loc, "%s: triangle %ld is clockwise; list its nodes counter-clockwise "
                  "(e.g. %ld %ld %ld)", cmd, id, nid[0], nid[2], nid[1]);
  int e = model_add_tri(m, v[0], v[1], v[2], mat, (int)id, b);
  m->tri.gmask[e] |= (uint64_t)1 << m->body[b].group;
  idmap_put(&inl.tri, id, e);
  if (m->body[b].mat < 0) m->body[b].mat = mat;
}



/* ------------------------------------------------------------------------------------------ */
/* topology queries                                                                            */

typedef YfEdgeRec EdgeRec; /* lo < hi: root node indices; t triangle, k local edge (corners k, k+1) */

static int bnd_cmp(const void *pa, const void *pb) {
  const EdgeRec *a = pa, *b = pb;
  if (a->t != b->t) return a->t < b->t ? -1 : 1;
  return a->k - b->k;
}

int mesh_boundary_edges(const YfModel *m, uint64_t groupbit, int **edges) {
  *edges = NULL;
  int nt = m->tri.n;
  if (nt == 0) return 0;
  EdgeRec *r = yf_malloc((size_t)nt * 3 * sizeof *r, "edge list");
  for (int t = 0; t < nt; t++)
    for (int k = 0; k < 3; k++) {
      int a = mesh_node_root(m, m->tri.v[3 * t + k]);
      int b = mesh_node_root(m, m->tri.v[3 * t + (k + 1) % 3]);
      EdgeRec *e = &r[3 * t + k];
      e->lo = a < b ? a : b;
      e->hi = a < b ? b : a;
      e->t = t;
      e->k = k;
    }
  yf_edges_sort(r, (long)nt * 3);
  int nb = 0;
  for (int i = 0; i < 3 * nt;) {
    int j = i + 1;
    while (j < 3 * nt && r[j].lo == r[i].lo && r[j].hi == r[i].hi) j++;
    if (j == i + 1) {
      int t = r[i].t, k = r[i].k;
      int a = m->tri.v[3 * t + k], b = m->tri.v[3 * t + (k + 1) % 3];
      if ((m->node.gmask[a] & groupbit) && (m->node.gmask[b] & groupbit)) r[nb++] = r[i];
    }
    i = j;
  }
  qsort(r, (size_t)nb, sizeof *r, bnd_cmp);
  if (nb > 0) {
    int *e = yf_malloc((size_t)nb * 2 * sizeof *e, "boundary edges");
    for (int i = 0; i < nb; i++) {
      e[2 * i] = m->tri.v[3 * r[i].t + r[i].k];
      e[2 * i + 1] = m->tri.v[3 * r[i].t + (r[i].k + 1) % 3];
    }
    *edges = e;
  }
  free(r);
  return nb;
}

double mesh_min_edge(const YfModel *m, int mat) {
  double h2 = INFINITY;
  const double *X = m->node.x0, *Y = m->node.y0;
  for (int t = 0; t < m->tri.n; t++) {
    if (mat >= 0 && m->tri.mat[t] != mat) continue;
    for (int k = 0; k < 3; k++) {
      int a = m->tri.v[3 * t + k], b = m->tri.v[3 * t + (k + 1) % 3];
      double dx = X[b] - X[a], dy = Y[b] - Y[a];
      double l2 = dx * dx + dy * dy;
      if (l2 < h2) h2 = l2;
    }
  }
  return isinf(h2) ? 0.0 : sqrt(h2);
}
