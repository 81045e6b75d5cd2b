/* edgesort.c: sorting triangle edge records by (lo, hi, t, k) (edgesort.h).
 *
 * Joint insertion, boundary queries and Y2D's meshing sort 3 records per triangle; with qsort
 * that was about 0.7 s of a 1e6-triangle setup.  Here a stable counting sort by lo puts each
 * node's edges together (a handful per node), and each such run is then sorted by (hi, t, k):
 * by insertion when short, by qsort when a node has many edges (a fan), so no input is
 * quadratic.  The keys are unique, so the result is exactly qsort's. */
#include "edgesort.h"

#include <stdlib.h>
#include <string.h>

#include "err.h"

static int rec_cmp(const void *pa, const void *pb)
{
  const YfEdgeRec *a = pa, *b = pb;
  if (a->lo != b->lo) return a->lo < b->lo ? -1 : 1;
  if (a->hi != b->hi) return a->hi < b->hi ? -1 : 1;
  if (a->t != b->t) return a->t < b->t ? -1 : 1;
  return (a->k > b->k) - (a->k < b->k);
}

#define RUN_INSERTION_MAX 32

void yf_edges_sort(YfEdgeRec *e, long n)
{
  if (n < 2) return;
  int maxlo = 0;
  for (long i = 0; i < n; i++) {
    if (e[i].lo < 0) { /* not a node index: the general sort */
      qsort(e, (size_t)n, sizeof *e, rec_cmp);
      return;
    }
    if (e[i].lo > maxlo) maxlo = e[i].lo;
  }
  long *start = yf_calloc((size_t)maxlo + 2, sizeof *start, "edge sort");
  YfEdgeRec *tmp = yf_malloc((size_t)n * sizeof *tmp, "edge sort");
  for (long i = 0; i < n; i++) start[e[i].lo + 1]++;
  for (long v = 0; v <= maxlo; v++) start[v + 1] += start[v];
  for (long i = 0; i < n; i++) tmp[start[e[i].lo]++] = e[i]; /* stable; start[v] ends at run v's end */
  long r0 = 0;
  for (long v = 0; v <= maxlo; v++) {
    long r1 = start[v], m = r1 - r0;
    YfEdgeRec *run = tmp + r0;
    if (m > RUN_INSERTION_MAX) {
      qsort(run, (size_t)m, sizeof *run, rec_cmp);
    } else {
      for (long i = 1; i < m; i++) {
        YfEdgeRec x = run[i];
        long j = i - 1;
        while (j >= 0 && rec_cmp(&run[j], &x) > 0) {
          run[j + 1] = run[j];
          j--;
        }
        run[j + 1] = x;
      }
    }
    r0 = r1;
  }
  memcpy(e, tmp, (size_t)n * sizeof *e);
  free(tmp);
  free(start);
}
