/* contact_search.h: broad phase of triangle contact (ALGORITHMS.md 5): which couples to evaluate.
 *
 * Each participating triangle is a disc (centroid c, radius r = largest centroid-to-corner
 * distance).  A couple (i, j) is a candidate when |c_i - c_j| < r_i + r_j + buffer (Y2D's DIEZON),
 * so the list stays valid until some node has travelled buffer/2 (the travel trigger below).
 * The search bins centroids into a uniform grid by counting sort and compares each triangle with
 * the 3x3 cells around it: O(N) time, no hashing, no allocation once the workspace has grown.
 * The output is sorted by (i, j) with i < j (triangle indices), the same for any thread count,
 * which lets contact_search_merge carry the friction memory of persisting couples over by a
 * linear merge of keys.
 */
#ifndef YF_CONTACT_SEARCH_H
#define YF_CONTACT_SEARCH_H
#include <stdint.h>

/* A couple list: pairs (ij[2k], ij[2k+1]) with ij[2k] < ij[2k+1], sorted lexicographically, and
 * the friction memory of each couple, YF_PAIR_NG values: the 6 sliding values (contact_pair.h:
 * index dir*3 + contactor edge), then the 6 tangential forces of the last step in the same order
 * (YfContactInfo.gprev: the Coulomb law's energy booking only; zeros for Y2D's law).  Kept
 * sparse: few couples ever touch (1-2 % of a fracturing body's neighbour couples), so a couple
 * has a slot in the pool g only from its first contact on; without one its values are 0. */
#define YF_PAIR_NG 12
/* 1 when a slot's YF_PAIR_NG values are all zero (the couple holds no memory) */
static inline int contact_gmem_zero(const double *g)
{
  int z = 1;
  for (int c = 0; c < YF_PAIR_NG; c++) z &= g[c] == 0.0;
  return z;
}
typedef struct {
  int n, cap;
  int *ij;   /* 2 per pair: triangle indices                             */
  int *gi;   /* per pair: slot in g, -1 = none (friction memory all zero)  */
  int ng, gcap;
  double *g; /* YF_PAIR_NG per slot: friction memory (above)              */
} YfPairs;

void contact_pairs_init(YfPairs *p);
void contact_pairs_free(YfPairs *p);
/* Make room for n pairs (keeps content; grows geometrically, never shrinks). */
void contact_pairs_reserve(YfPairs *p, int n);
/* Room for n slots of friction memory (keeps content; grows geometrically). */
void contact_pairs_greserve(YfPairs *p, int n);
/* The friction memory of pair k, YF_PAIR_NG values (a zeroed slot is taken when it has none; room must have
 * been reserved). */
double *contact_pairs_gslot(YfPairs *p, int k);
/* Keep only pairs k with keep[k] != 0, in order (e.g. couples removed by the force routine).
 * Returns the new count. */
int contact_pairs_compact(YfPairs *p, const unsigned char *keep);

/* Which candidate pairs to drop.  Every array is indexed by TRIANGLE index (as model.tri.*);
 * NULL disables that test.  All tests must pass for a pair to be kept. */
typedef struct {
  const int *group;       /* drop pairs with group[i] == group[j] (e.g. tri.body)              */
  const uint64_t *mask;   /* keep only if (mask[i] & mask2[j]) || (mask[j] & mask2[i]) ...       */
  const uint64_t *mask2;  /* ... with mask2 = mask when NULL (then: share a bit)                  */
  const int *tri_v;       /* 3 node indices per triangle: drop pairs that share a node           */
  int (*keep)(int i, int j, void *ctx); /* last word (i < j); called from several threads      */
  void *ctx;
  /* lower_hi > lower_lo: only couples whose lower triangle i is in [lower_lo, lower_hi).  Items
   * outside that range are still binned (they can be the upper partner j) but not searched from,
   * so a rank that evaluates the couples of its own triangles (MPI: the owner of the lower one)
   * pays neither the time nor the buffers of its neighbours' couples.  0, 0: no restriction. */
  int lower_lo, lower_hi;
} YfSearchFilter;

/* Reusable workspace (binning arrays and per-thread pair buffers). */
typedef struct YfSearchWork {
  int cap_items, cap_cells, nthr_cap;
  int *cell;            /* cell of each item                                         */
  int *start;           /* cap_cells + 1: first sorted slot of each cell              */
  int *sid;             /* item of each sorted slot                                   */
  double *sx, *sy, *sr; /* centroid and radius per sorted slot (locality)             */
  int *stri;            /* triangle index per sorted slot                             */
  struct YfPairBuf *buf;/* one per thread                                             */
  int par_min;          /* fewer items than this: one thread (set by init; tests lower it) */
  /* statistics of the last search */
  int nx, ny;           /* grid size                                                  */
  double h;             /* cell size [m]                                              */
  long tested;          /* candidate distance tests made                              */
} YfSearchWork;

void contact_search_work_init(YfSearchWork *w);
void contact_search_work_free(YfSearchWork *w);

/* Centroids and radii of triangles tri[0..n-1] (tri NULL: 0..n-1) from node positions
 * x, y [m] and corner nodes tri_v (3 per triangle index).  r = max |corner - centroid|. */
void contact_search_bounds(int n, const int *tri, const int *tri_v, const double *x, const double *y,
                           double *cx, double *cy, double *r);

/* All couples of items 0..n-1 with |c_i - c_j| < r_i + r_j + buffer that pass the filter (may be
 * NULL).  Item k is triangle tri[k] (tri NULL: k); tri must be strictly increasing.  cx, cy, r
 * are per item.  Writes out->n and out->ij (sorted, i < j); out->g is left for
 * contact_search_merge.  OpenMP-parallel; same output for any thread count. */
void contact_search(YfSearchWork *w, int n, const int *tri, const double *cx, const double *cy,
                    const double *r, double buffer, const YfSearchFilter *f, YfPairs *out);

/* Fill fresh's friction memory: a pair also present in old gets a copy of its six values (in a
 * slot of fresh's pool, in pair order, only when they are not all zero), new pairs none (zeros).
 * Both lists must be sorted (as contact_search makes them).  O(old->n + fresh->n). */
void contact_search_merge(const YfPairs *old, YfPairs *fresh);

/* Travel trigger (ALGORITHMS 5): travel += 2 dt sqrt(vmax2) each step; a search is due when
 * travel >= buffer, and travel restarts at 0. */
typedef struct {
  double travel; /* [m] */
  double buffer; /* [m] */
} YfSearchTrigger;

/* travel0: 1e15 (Y2D: the first step always searches) or 2 buffer after meshing. */
void contact_trigger_init(YfSearchTrigger *t, double buffer, double travel0);
/* Account for one step; returns 1 when a search is due now (and resets the travel). */
int contact_trigger_step(YfSearchTrigger *t, double dt, double vmax2);
/* max |v|^2 [m^2/s^2] over nodes[0..n-1] (nodes NULL: 0..n-1). */
double contact_vmax2(int n, const int *nodes, const double *vx, const double *vy);

#endif
