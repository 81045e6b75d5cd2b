/* partition.c: the METIS partition of the triangles' dual graph and the
 * renumbering of nodes, triangles and joints that makes each part contiguous (see partition.h).
 *
 * Why: the step's loops run over triangles, joints and nodes in index order, split into
 * contiguous ranges per thread (static schedules over fixed blocks).  After the renumbering a
 * thread's range of triangles is a few compact pieces of the mesh whose nodes are a matching
 * range of the node arrays, so the force gather of a node reads corner forces its own thread
 * wrote (ownership by contiguity), and the working set of a block fits in cache.  The order does
 * not depend on the thread count, so the fixed-order sums give the same bits on any threads.
 *
 * The graph: one vertex per triangle; an edge between two triangles sharing an edge (two node
 * indices) or joined by a joint (fracturing bodies have own nodes per triangle: the joints are
 * their only connection).  METIS_PartGraphKway with a fixed seed (deterministic).
 */
#include <metis.h>
#include <stdlib.h>
#include <string.h>

#include "partition.h"
#include "mesh.h"
#include "contact.h"
#include "err.h"
#include "joint.h"


/* Permute an array of n records of `size` bytes: new record i = old record perm[i]. */
static void permute(void *arr, size_t size, int n, const int *perm, void *tmp) {
  if (!arr || n <= 0) return;
  char *a = arr, *t = tmp;
  for (int i = 0; i < n; i++) memcpy(t + (size_t)i * size, a + (size_t)perm[i] * size, size);
  memcpy(a, t, (size_t)n * size);
}

/* Dual graph (CSR, METIS idx_t) of the triangles: shared edges and joints. */
static void dual_graph(const YfSim *s, idx_t **xadj_out, idx_t **adj_out) {
  const YfModel *m = &s->model;
  int nt = m->tri.n, nn = m->node.n;
  const int *v = m->tri.v;
  /* node -> triangles */
  int *off = yf_calloc((size_t)nn + 2, sizeof(int), "partition graph");
  int *lst = yf_malloc((size_t)3 * nt * sizeof(int), "partition graph");
  for (int k = 0; k < 3 * nt; k++) off[v[k] + 1]++;
  for (int i = 0; i < nn; i++) off[i + 1] += off[i];
  int *fill = yf_calloc((size_t)nn + 1, sizeof(int), "partition graph");
  for (int k = 0; k < 3 * nt; k++) lst[off[v[k]] + fill[v[k]]++] = k / 3;
  free(fill);
  /* up to 3 neighbours by shared edges and 3 by joints per triangle */
  int *nb = yf_malloc((size_t)6 * nt * sizeof(int), "partition graph");
  int *cnt = yf_calloc((size_t)nt + 1, sizeof(int), "partition graph");
  for (int t = 0; t < nt; t++)
    for (int c = 0; c < 3; c++) {
      int p = v[3 * t + c], q = v[3 * t + (c + 1) % 3];
      for (int u = off[p]; u < off[p + 1]; u++) {
        int o = lst[u];
        if (o == t) continue;
        if (v[3 * o] == q || v[3 * o + 1] == q || v[3 * o + 2] == q) {
          int dup = 0;
          for (int z = 0; z < cnt[t]; z++) dup |= nb[6 * t + z] == o;
          if (!dup && cnt[t] < 3) nb[6 * t + cnt[t]++] = o;
          break;
        }
      }
    }
  free(off);
  free(lst);
  const YfJoints *J = s->joints;
  for (int j = 0; J && j < J->n; j++)
    for (int side = 0; side < 2; side++) {
      int t = J->tri[2 * j + side], o = J->tri[2 * j + 1 - side];
      int dup = 0;
      for (int z = 0; z < cnt[t]; z++) dup |= nb[6 * t + z] == o;
      if (!dup && cnt[t] < 6) nb[6 * t + cnt[t]++] = o;
    }
  idx_t *xadj = yf_malloc(((size_t)nt + 1) * sizeof(idx_t), "partition graph");
  xadj[0] = 0;
  for (int t = 0; t < nt; t++) xadj[t + 1] = xadj[t] + cnt[t];
  idx_t *adj = yf_malloc(((size_t)xadj[nt] + 1) * sizeof(idx_t), "partition graph");
  for (int t = 0; t < nt; t++)
    for (int z = 0; z < cnt[t]; z++) adj[xadj[t] + z] = nb[6 * t + z];
  free(nb);
  free(cnt);
  *xadj_out = xadj;
  *adj_out = adj;
}

static int cmp_key(const void *pa, const void *pb) {
  const int *a = pa, *b = pb;
  if (a[0] != b[0]) return a[0] < b[0] ? -1 : 1;
  return (a[1] > b[1]) - (a[1] < b[1]);
}

/* Renumber joints after tri/node renumbering: node and corner slots, triangles, then the joint
 * order itself (by the smaller renumbered triangle, old order among equals). */
static void renumber_joints(YfSim *s, const int *tnew, const int *nnew) {
  YfJoints *J = s->joints;
  if (!J || !J->n) return;
  int nj = J->n;
  for (int k = 0; k < 4 * nj; k++) {
    J->node[k] = nnew[J->node[k]];
    int t = J->corner[k] / 3, c = J->corner[k] % 3;
    J->corner[k] = 3 * tnew[t] + c;
  }
  for (int k = 0; k < 2 * nj; k++) J->tri[k] = tnew[J->tri[k]];
  for (int r = 0; r < J->nrec; r++) {
    J->rec[r].triA = tnew[J->rec[r].triA];
    J->rec[r].triB = tnew[J->rec[r].triB];
  }
  for (int r = 0; r < J->nopened; r++) {
    J->orec[r].triA = tnew[J->orec[r].triA];
    J->orec[r].triB = tnew[J->orec[r].triB];
  }
  int *key = yf_malloc((size_t)2 * nj * sizeof(int), "partition joints");
  for (int j = 0; j < nj; j++) {
    int a = J->tri[2 * j], b = J->tri[2 * j + 1];
    key[2 * j] = a < b ? a : b;
    key[2 * j + 1] = j;
  }
  qsort(key, (size_t)nj, 2 * sizeof(int), cmp_key);
  int *perm = yf_malloc((size_t)nj * sizeof(int), "partition joints");
  int *jnew = yf_malloc((size_t)nj * sizeof(int), "partition joints");
  for (int j = 0; j < nj; j++) {
    perm[j] = key[2 * j + 1];
    jnew[perm[j]] = j;
  }
  free(key);
  void *tmp = yf_malloc((size_t)nj * 8 * sizeof(double), "partition joints");
  permute(J->corner, 4 * sizeof(int), nj, perm, tmp);
  permute(J->node, 4 * sizeof(int), nj, perm, tmp);
  permute(J->tri, 2 * sizeof(int), nj, perm, tmp);
  permute(J->prop, sizeof(int), nj, perm, tmp);
  permute(J->k, sizeof(double), nj, perm, tmp);
  permute(J->fs, sizeof(double), nj, perm, tmp);
  permute(J->dmg, 3 * sizeof(double), nj, perm, tmp);
  permute(J->w, sizeof(double), nj, perm, tmp);
  permute(J->z, sizeof(double), nj, perm, tmp);
  permute(J->L0, sizeof(double), nj, perm, tmp);
  permute(J->state, 1, nj, perm, tmp);
  permute(J->mode, 1, nj, perm, tmp);
  permute(J->opened, 1, nj, perm, tmp);
  permute(J->f, 8 * sizeof(double), nj, perm, tmp);
  for (int k = 0; k < J->npend; k++) J->pend[k] = jnew[J->pend[k]];
  for (int r = 0; r < J->nrec; r++) J->rec[r].joint = jnew[J->rec[r].joint];
  for (int r = 0; r < J->nopened; r++) J->orec[r].joint = jnew[J->orec[r].joint];
  free(tmp);
  free(perm);
  free(jnew);
}

void partition_apply(YfSim *s) {
  YfModel *m = &s->model;
  int nt = m->tri.n, nn = m->node.n;
  if (m->part_done) {
    /* triangles made after the renumbering follow the last part */
    if (m->npart >= 1 && m->part_tri && m->part_tri[m->npart] != nt) m->part_tri[m->npart] = nt;
    return;
  }
  m->part_done = 1;
  int nparts = m->part_req;
  if (m->part_method == PART_NONE) nparts = 1;
  else if (nparts <= 0) nparts = m->part_method == PART_METIS || nt >= 2 * YF_PART_TRIS ? (nt + YF_PART_TRIS - 1) / YF_PART_TRIS : 1;
  if (nparts > nt) nparts = nt > 0 ? nt : 1;
  free(m->part_tri);
  m->part_tri = yf_malloc(((size_t)nparts + 1) * sizeof(int), "partition");
  m->npart = nparts;
  if (nparts <= 1) {
    m->npart = 1;
    m->part_tri[0] = 0;
    m->part_tri[1] = nt;
    if (m->part_method == PART_NONE) sim_printf(s, "partition: none (%d triangles in index order)\n", nt);
    return;
  }

  idx_t *xadj, *adj;
  dual_graph(s, &xadj, &adj);
  idx_t nv = nt, ncon = 1, np = nparts, cut = 0;
  idx_t *part = yf_malloc((size_t)nt * sizeof(idx_t), "partition");
  idx_t opt[METIS_NOPTIONS];
  METIS_SetDefaultOptions(opt);
  opt[METIS_OPTION_SEED] = 1;    /* deterministic: the same mesh gives the same parts */
  opt[METIS_OPTION_NUMBERING] = 0;
  yf_signals_guard(1); /* METIS leaves SIGTERM one-shot and non-restarting (err.h) */
  int rc = METIS_PartGraphKway(&nv, &ncon, xadj, adj, NULL, NULL, NULL, &np, NULL, NULL, opt, &cut, part);
  yf_signals_guard(0);
  free(xadj);
  free(adj);
  if (rc != METIS_OK) {
    /* METIS refuses only on memory or input errors: run unpartitioned rather than stop */
    yf_warn(NULL, "partition: METIS failed (code %d); running with the mesh in its own order", rc);
    free(part);
    m->npart = 1;
    m->part_tri[0] = 0;
    m->part_tri[1] = nt;
    return;
  }

  /* triangles: by part, old order inside a part (counting sort: stable) */
  int *pt = m->part_tri;
  memset(pt, 0, ((size_t)nparts + 1) * sizeof(int));
  for (int t = 0; t < nt; t++) pt[part[t] + 1]++;
  for (int p = 0; p < nparts; p++) pt[p + 1] += pt[p];
  int *fillp = yf_malloc((size_t)nparts * sizeof(int), "partition");
  memcpy(fillp, pt, (size_t)nparts * sizeof(int));
  int *tperm = yf_malloc((size_t)nt * sizeof(int), "partition"); /* new -> old */
  int *tnew = yf_malloc((size_t)nt * sizeof(int), "partition");  /* old -> new */
  for (int t = 0; t < nt; t++) {
    int i = fillp[part[t]]++;
    tperm[i] = t;
    tnew[t] = i;
  }
  free(fillp);
  int largest = 0;
  for (int p = 0; p < nparts; p++)
    if (pt[p + 1] - pt[p] > largest) largest = pt[p + 1] - pt[p];
  free(part);

  /* nodes: in the order the renumbered triangles meet them, then the others */
  int *nnew = yf_malloc((size_t)(nn > 0 ? nn : 1) * sizeof(int), "partition");
  int *nperm = yf_malloc((size_t)(nn > 0 ? nn : 1) * sizeof(int), "partition");
  for (int i = 0; i < nn; i++) nnew[i] = -1;
  int k = 0;
  for (int i = 0; i < nt; i++)
    for (int c = 0; c < 3; c++) {
      int q = m->tri.v[3 * tperm[i] + c];
      if (nnew[q] < 0) { nnew[q] = k; nperm[k++] = q; }
    }
  for (int i = 0; i < nn; i++)
    if (nnew[i] < 0) { nnew[i] = k; nperm[k++] = i; }

  size_t big = (size_t)(nt > nn ? nt : nn) + 1;
  void *tmp = yf_malloc(big * 6 * sizeof(double), "partition");
  YfNodes *N = &m->node;
  double *dn[] = {N->x, N->y, N->x0, N->y0, N->vx, N->vy, N->fx, N->fy, N->m};
  for (int a = 0; a < 9; a++) permute(dn[a], sizeof(double), nn, nperm, tmp);
  permute(N->id, sizeof(int), nn, nperm, tmp);
  permute(N->body, sizeof(int), nn, nperm, tmp);
  permute(N->gmask, sizeof(uint64_t), nn, nperm, tmp);
  permute(N->parent, sizeof(int), nn, nperm, tmp);
  for (int i = 0; i < nn; i++) N->parent[i] = nnew[N->parent[i]];

  YfTris *T = &m->tri;
  permute(T->v, 3 * sizeof(int), nt, tperm, tmp);
  for (int i = 0; i < 3 * nt; i++) T->v[i] = nnew[T->v[i]];
  permute(T->mat, sizeof(int), nt, tperm, tmp);
  permute(T->body, sizeof(int), nt, tperm, tmp);
  permute(T->id, sizeof(int), nt, tperm, tmp);
  permute(T->gmask, sizeof(uint64_t), nt, tperm, tmp);
  permute(T->xinv, 4 * sizeof(double), nt, tperm, tmp);
  permute(T->d0, sizeof(double), nt, tperm, tmp);
  permute(T->s, 3 * sizeof(double), nt, tperm, tmp);
  permute(T->cf, 6 * sizeof(double), nt, tperm, tmp);
  free(tmp);

  renumber_joints(s, tnew, nnew);
  contact_renumber_tris(s, tnew, nt);
  mesh_renumbered(m, tnew, nnew);
  for (int i = 0; i < s->nbc_kind; i++) /* node sets and loaded edges are resolved again */
    if (s->bc_kind[i]->renumbered) s->bc_kind[i]->renumbered(s);

  free(m->tri_new);
  m->tri_new = tnew;
  m->ntri_new = nt;
  m->prepared = 0;
  free(tperm);
  free(nperm);
  free(nnew);
  sim_printf(s, "partition: metis, %d parts of %d triangles, edge cut %ld, balance %.3f (largest part / mean)\n",
             nparts, nt, (long)cut, (double)largest * nparts / nt);
}
