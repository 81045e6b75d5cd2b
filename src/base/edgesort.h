/* edgesort.h: the sort of triangle edge records that every topology query starts with (shared
 * edges become joints, single edges are the boundary, Y2D's meshing codes).  See edgesort.c. */
#ifndef YF_EDGESORT_H
#define YF_EDGESORT_H

/* One edge of a triangle: node indices lo < hi (lo == hi for a degenerate triangle), the
 * triangle t and its local edge k (corners k, k+1). */
typedef struct {
  int lo, hi, t, k;
} YfEdgeRec;

/* Sort by (lo, hi, t, k) ascending: the order qsort gives with that comparator (the keys are
 * unique), in O(n + largest lo) instead of O(n log n). */
void yf_edges_sort(YfEdgeRec *e, long n);

#endif
