/* model.c: growing and querying the scene arrays (see model.h).
 *
 * Arrays grow geometrically while a deck builds the scene, or to the exact size when the builder
 * knows the count (model_reserve: meshing, read_y2d, joint insertion), so that a large scene does
 * not carry up to twice its size in capacity; nothing here runs inside the step.
 */
#include <stdio.h>
#include <string.h>
#include <stdlib.h>
#include "model.h"
#include "err.h"

void model_init(YfModel *m) { memset(m, 0, sizeof *m); }

void model_free(YfModel *m) {
  YfNodes *n = &m->node;
  free(n->x); free(n->y); free(n->x0); free(n->y0); free(n->vx); free(n->vy);
  free(n->fx); free(n->fy); free(n->m); free(n->id); free(n->parent); free(n->body); free(n->gmask);
  YfTris *t = &m->tri;
  free(t->v); free(t->mat); free(t->body); free(t->id); free(t->gmask);
  free(t->xinv); free(t->d0); free(t->s); free(t->cf);
  free(m->mat); free(m->body);
  free(m->gather_off); free(m->gather_slot);
  free(m->part_tri); free(m->tri_new);
  memset(m, 0, sizeof *m);
}

#define GROW(p, cap, k) p = yf_realloc(p, (size_t)(cap) * (k) * sizeof *(p), #p)

/* exact: capacity = want (model_reserve); else doubling (one node or triangle at a time) */
static void nodes_reserve(YfNodes *n, int want, int exact) {
  if (want <= n->cap) return;
  int cap = n->cap ? n->cap : 64;
  while (cap < want) cap *= 2;
  if (exact) cap = want;
  GROW(n->x, cap, 1); GROW(n->y, cap, 1); GROW(n->x0, cap, 1); GROW(n->y0, cap, 1);
  GROW(n->vx, cap, 1); GROW(n->vy, cap, 1); GROW(n->fx, cap, 1); GROW(n->fy, cap, 1);
  GROW(n->m, cap, 1); GROW(n->id, cap, 1); GROW(n->parent, cap, 1); GROW(n->body, cap, 1);
  GROW(n->gmask, cap, 1);
  n->cap = cap;
}

static void tris_reserve(YfTris *t, int want, int exact) {
  if (want <= t->cap) return;
  int cap = t->cap ? t->cap : 64;
  while (cap < want) cap *= 2;
  if (exact) cap = want;
  GROW(t->v, cap, 3); GROW(t->mat, cap, 1); GROW(t->body, cap, 1); GROW(t->id, cap, 1);
  GROW(t->gmask, cap, 1); GROW(t->xinv, cap, 4); GROW(t->d0, cap, 1); GROW(t->s, cap, 3);
  GROW(t->cf, cap, 6);
  t->cap = cap;
}

void model_reserve(YfModel *m, int nodes, int tris) {
  if (nodes > 0) nodes_reserve(&m->node, m->node.n + nodes, 1);
  if (tris > 0) tris_reserve(&m->tri, m->tri.n + tris, 1);
}

int model_add_node(YfModel *m, double x, double y, int id, int body) {
  YfNodes *n = &m->node;
  nodes_reserve(n, n->n + 1, 0);
  int i = n->n++;
  n->x[i] = n->x0[i] = x;
  n->y[i] = n->y0[i] = y;
  n->vx[i] = n->vy[i] = n->fx[i] = n->fy[i] = n->m[i] = 0.0;
  n->id[i] = id;
  n->parent[i] = i;
  n->body[i] = body;
  n->gmask[i] = (body >= 0 && body < m->nbody && m->body[body].group >= 0)
                    ? (uint64_t)1 << m->body[body].group : 0;
  m->prepared = 0;
  return i;
}

int model_add_tri(YfModel *m, int n0, int n1, int n2, int mat, int id, int body) {
  YfTris *t = &m->tri;
  tris_reserve(t, t->n + 1, 0);
  int e = t->n++;
  t->v[3 * e] = n0; t->v[3 * e + 1] = n1; t->v[3 * e + 2] = n2;
  t->mat[e] = mat;
  t->id[e] = id;
  t->body[e] = body;
  t->gmask[e] = (body >= 0 && body < m->nbody && m->body[body].group >= 0)
                    ? (uint64_t)1 << m->body[body].group : 0;
  for (int k = 0; k < 3; k++) t->s[3 * e + k] = 0.0;
  for (int k = 0; k < 6; k++) t->cf[6 * e + k] = 0.0;
  m->prepared = 0;
  return e;
}

int model_add_material(YfModel *m, const char *name) {
  m->mat = yf_realloc(m->mat, (size_t)(m->nmat + 1) * sizeof *m->mat, "materials");
  YfMaterial *mt = &m->mat[m->nmat];
  memset(mt, 0, sizeof *mt);
  snprintf(mt->name, sizeof mt->name, "%s", name);
  mt->volfac = 0.5;
  mt->jset = -1;
  return m->nmat++;
}

int model_find_material(const YfModel *m, const char *name) {
  for (int i = 0; i < m->nmat; i++)
    if (!strcmp(m->mat[i].name, name)) return i;
  return -1;
}

int model_add_body(YfModel *m, const char *name, int mat) {
  m->body = yf_realloc(m->body, (size_t)(m->nbody + 1) * sizeof *m->body, "bodies");
  YfBody *b = &m->body[m->nbody];
  memset(b, 0, sizeof *b);
  snprintf(b->name, sizeof b->name, "%s", name);
  b->mat = mat;
  b->group = model_group(m, name, 1);
  return m->nbody++;
}

int model_find_body(const YfModel *m, const char *name) {
  for (int i = 0; i < m->nbody; i++)
    if (!strcmp(m->body[i].name, name)) return i;
  return -1;
}

int model_group(YfModel *m, const char *name, int create) {
  for (int i = 0; i < m->ngroup; i++)
    if (!strcmp(m->group[i].name, name)) return i;
  if (!create || m->ngroup >= YF_MAX_GROUPS) return -1;
  snprintf(m->group[m->ngroup].name, YF_NAME_MAX, "%s", name);
  return m->ngroup++;
}

double model_tri_d(const YfModel *m, int t, int cur) {
  const int *v = m->tri.v + 3 * t;
  const double *X = cur ? m->node.x : m->node.x0, *Y = cur ? m->node.y : m->node.y0;
  return (X[v[1]] - X[v[0]]) * (Y[v[2]] - Y[v[0]]) - (X[v[2]] - X[v[0]]) * (Y[v[1]] - Y[v[0]]);
}

const char *model_tri_label(const YfModel *m, int e, char *buf, size_t n) {
  const char *mat = m->mat[m->tri.mat[e]].name;
  const int b = m->tri.body ? m->tri.body[e] : -1;
  if (m->nbody > 1 && b >= 0 && strcmp(m->body[b].name, mat) != 0)
    snprintf(buf, n, "triangle %d of body %s (material %s)", m->tri.id[e], m->body[b].name, mat);
  else
    snprintf(buf, n, "triangle %d (material %s)", m->tri.id[e], mat);
  return buf;
}
