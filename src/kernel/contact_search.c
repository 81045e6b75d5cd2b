/* contact_search.c: linear-time broad phase for triangle contact (ALGORITHMS.md 5).
 *
 * Munjiza's NBS idea without its quirks: centroids are binned into a uniform grid whose cell is
 * at least the largest possible couple distance 2 r_max + buffer, so every partner of a
 * triangle lies in the 3x3 cells around its own.  Binning is a stable counting sort (items keep
 * their order inside a cell), then each item i scans its 3x3 cells for partners j > i.  Items are
 * split into one contiguous range per thread; every range yields its pairs already sorted by
 * (i, j), and the ranges are concatenated in order, so the list is identical for 1 or N threads.
 * Y2D's own search truncates cell coordinates toward zero (a double-width cell on each axis) and
 * stores couples in linked lists; the SET of couples, which is all the forces depend on, is the
 * same: { (i, j) : |c_i - c_j| < r_i + r_j + buffer }.
 *
 * The workspace grows with N and is reused, so a search in steady state allocates nothing.
 * Cell count is capped near 4 N (a wide empty scene gets larger cells, never a huge array).
 */
#include "contact_search.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "err.h"
#include "parfor.h"

#ifdef _OPENMP
#include <omp.h>
#endif

/* Below this many items a search runs on one thread: waking a team costs more than it saves
 * (and on a loaded machine a descheduled worker can stall a barrier for a time slice). */
#define YF_SEARCH_PAR_MIN 20000
#define YF_SEARCH_MAX_THREADS 1024

struct YfPairBuf {
  int n, cap;
  int *ij;
};

/* ---------------------------------------------------------------- pair lists */

void contact_pairs_init(YfPairs *p) { memset(p, 0, sizeof *p); }

void contact_pairs_free(YfPairs *p)
{
  free(p->ij);
  free(p->gi);
  free(p->g);
  memset(p, 0, sizeof *p);
}

void contact_pairs_reserve(YfPairs *p, int n)
{
  if (n <= p->cap) return;
  int cap = p->cap > 0 ? p->cap : 1024;
  while (cap < n) cap = cap > (1 << 29) ? n : 2 * cap;
  p->ij = yf_realloc(p->ij, (size_t)cap * 2 * sizeof *p->ij, "contact couples");
  p->gi = yf_realloc(p->gi, (size_t)cap * sizeof *p->gi, "contact couples");
  p->cap = cap;
}

void contact_pairs_greserve(YfPairs *p, int n)
{
  if (n <= p->gcap) return;
  int cap = p->gcap > 0 ? p->gcap : 256;
  while (cap < n) cap = cap > (1 << 28) ? n : 2 * cap;
  p->g = yf_realloc(p->g, (size_t)cap * YF_PAIR_NG * sizeof *p->g, "contact friction memory");
  p->gcap = cap;
}

double *contact_pairs_gslot(YfPairs *p, int k)
{
  if (p->gi[k] < 0) {
    YF_ASSERT(p->ng < p->gcap);
    p->gi[k] = p->ng++;
    memset(p->g + YF_PAIR_NG * (size_t)p->gi[k], 0, YF_PAIR_NG * sizeof *p->g);
  }
  return p->g + YF_PAIR_NG * (size_t)p->gi[k];
}

int contact_pairs_compact(YfPairs *p, const unsigned char *keep)
{
  int m = 0;
  for (int k = 0; k < p->n; k++) {
    if (!keep[k]) continue;
    if (m != k) {
      p->ij[2 * m] = p->ij[2 * k];
      p->ij[2 * m + 1] = p->ij[2 * k + 1];
      p->gi[m] = p->gi[k]; /* the slot of a dropped pair stays unused until the next merge */
    }
    m++;
  }
  p->n = m;
  return m;
}

/* ---------------------------------------------------------------- workspace */

void contact_search_work_init(YfSearchWork *w)
{
  memset(w, 0, sizeof *w);
  w->par_min = YF_SEARCH_PAR_MIN;
}

void contact_search_work_free(YfSearchWork *w)
{
  free(w->cell);
  free(w->start);
  free(w->sid);
  free(w->sx);
  free(w->sy);
  free(w->sr);
  free(w->stri);
  for (int t = 0; t < w->nthr_cap; t++) free(w->buf[t].ij);
  free(w->buf);
  contact_search_work_init(w);
}

static void work_grow(YfSearchWork *w, int n, int ncells, int nthr)
{
  if (n > w->cap_items) {
    int cap = n + n / 4 + 16;
    w->cell = yf_realloc(w->cell, (size_t)cap * sizeof *w->cell, "contact search");
    w->sid = yf_realloc(w->sid, (size_t)cap * sizeof *w->sid, "contact search");
    w->stri = yf_realloc(w->stri, (size_t)cap * sizeof *w->stri, "contact search");
    w->sx = yf_realloc(w->sx, (size_t)cap * sizeof *w->sx, "contact search");
    w->sy = yf_realloc(w->sy, (size_t)cap * sizeof *w->sy, "contact search");
    w->sr = yf_realloc(w->sr, (size_t)cap * sizeof *w->sr, "contact search");
    w->cap_items = cap;
  }
  if (ncells + 1 > w->cap_cells) {
    int cap = ncells + 1 + ncells / 4 + 16;
    w->start = yf_realloc(w->start, (size_t)cap * sizeof *w->start, "contact search grid");
    w->cap_cells = cap;
  }
  if (nthr > w->nthr_cap) {
    w->buf = yf_realloc(w->buf, (size_t)nthr * sizeof *w->buf, "contact search");
    for (int t = w->nthr_cap; t < nthr; t++) w->buf[t] = (struct YfPairBuf){0, 0, NULL};
    w->nthr_cap = nthr;
  }
}

static inline void buf_push(struct YfPairBuf *b, int i, int j)
{
  if (b->n == b->cap) {
    b->cap = b->cap ? 2 * b->cap : 4096;
    b->ij = yf_realloc(b->ij, (size_t)b->cap * 2 * sizeof *b->ij, "contact search pairs");
  }
  b->ij[2 * b->n] = i;
  b->ij[2 * b->n + 1] = j;
  b->n++;
}

static int cmp_int(const void *a, const void *b)
{
  int x = *(const int *)a, y = *(const int *)b;
  return (x > y) - (x < y);
}

/* Sort the partners j of one i (pairs [from, b->n) of the buffer): a few sorted runs, usually
 * short, so insertion sort; a sort routine for the rare crowded case. */
static void sort_partners(struct YfPairBuf *b, int from)
{
  int m = b->n - from;
  if (m < 2) return;
  int *ij = b->ij + 2 * from;
  if (m > 48) {
    /* i is the same for all: sort the j's through a stride-2 copy in place. */
    int *tmp = malloc((size_t)m * sizeof *tmp);
    if (tmp) {
      for (int k = 0; k < m; k++) tmp[k] = ij[2 * k + 1];
      qsort(tmp, (size_t)m, sizeof *tmp, cmp_int);
      for (int k = 0; k < m; k++) ij[2 * k + 1] = tmp[k];
      free(tmp);
      return;
    }
  }
  for (int k = 1; k < m; k++) {
    int v = ij[2 * k + 1], q = k - 1;
    while (q >= 0 && ij[2 * q + 1] > v) {
      ij[2 * (q + 1) + 1] = ij[2 * q + 1];
      q--;
    }
    ij[2 * (q + 1) + 1] = v;
  }
}

static inline int filter_keep(const YfSearchFilter *f, int i, int j)
{
  if (f->group && f->group[i] == f->group[j]) return 0;
  if (f->mask) {
    const uint64_t *m2 = f->mask2 ? f->mask2 : f->mask;
    if (!(f->mask[i] & m2[j]) && !(f->mask[j] & m2[i])) return 0;
  }
  if (f->tri_v) {
    const int *a = f->tri_v + 3 * (size_t)i, *b = f->tri_v + 3 * (size_t)j;
    for (int p = 0; p < 3; p++)
      if (a[p] == b[0] || a[p] == b[1] || a[p] == b[2]) return 0;
  }
  if (f->keep && !f->keep(i, j, f->ctx)) return 0;
  return 1;
}

/* ---------------------------------------------------------------- search */

/* The first item whose triangle (tri NULL: the item itself) is >= x; tri increasing. */
static int first_item_at_least(int n, const int *tri, int x)
{
  int a = 0, b = n;
  while (a < b) {
    int c = a + (b - a) / 2;
    if ((tri ? tri[c] : c) < x) a = c + 1;
    else b = c;
  }
  return a;
}

void contact_search_bounds(int n, const int *tri, const int *tri_v, const double *x, const double *y,
                           double *cx, double *cy, double *r)
{
#pragma omp parallel for schedule(static) if (YF_WANT_TEAM(n >= YF_SEARCH_PAR_MIN))
  for (int k = 0; k < n; k++) {
    const int *v = tri_v + 3 * (size_t)(tri ? tri[k] : k);
    double x0 = x[v[0]], x1 = x[v[1]], x2 = x[v[2]];
    double y0 = y[v[0]], y1 = y[v[1]], y2 = y[v[2]];
    double mx = (x0 + x1 + x2) / 3.0, my = (y0 + y1 + y2) / 3.0;
    double d0 = (x0 - mx) * (x0 - mx) + (y0 - my) * (y0 - my);
    double d1 = (x1 - mx) * (x1 - mx) + (y1 - my) * (y1 - my);
    double d2 = (x2 - mx) * (x2 - mx) + (y2 - my) * (y2 - my);
    double d = d0 > d1 ? d0 : d1;
    if (d2 > d) d = d2;
    cx[k] = mx;
    cy[k] = my;
    r[k] = sqrt(d);
  }
}

void contact_search(YfSearchWork *w, int n, const int *tri, const double *cx, const double *cy,
                    const double *r, double buffer, const YfSearchFilter *f, YfPairs *out)
{
  out->n = 0;
  w->tested = 0;
  if (n < 2) return;

  /* Extent of the centroids and the largest radius. */
  double xmin = cx[0], xmax = cx[0], ymin = cy[0], ymax = cy[0], rmax = r[0];
  for (int k = 1; k < n; k++) {
    if (cx[k] < xmin) xmin = cx[k];
    if (cx[k] > xmax) xmax = cx[k];
    if (cy[k] < ymin) ymin = cy[k];
    if (cy[k] > ymax) ymax = cy[k];
    if (r[k] > rmax) rmax = r[k];
  }
  YF_ASSERT(isfinite(xmin) && isfinite(xmax) && isfinite(ymin) && isfinite(ymax) && isfinite(rmax));
  if (tri)
    for (int k = 1; k < n; k++) YF_ASSERT(tri[k] > tri[k - 1]);
  /* Any couple has |dc| < r_i + r_j + buffer <= 2 r_max + buffer.  The relative margin 1e-6
   * keeps rounding of (x - xmin)/h from ever putting two partners two cells apart. */
  double h = (2.0 * rmax + buffer) * (1.0 + 1e-6);
  if (!(h > 0.0)) return; /* r = 0 and buffer <= 0: nothing can be closer than 0 */
  double limit = 4.0 * n + 1024.0;
  double ex = xmax - xmin, ey = ymax - ymin;
  while ((floor(ex / h) + 1.0) * (floor(ey / h) + 1.0) > limit) h *= 1.25;
  int nx = (int)(ex / h) + 1, ny = (int)(ey / h) + 1;
  int ncells = nx * ny;

  int maxthr = 1;
#ifdef _OPENMP
  maxthr = omp_get_max_threads();
#endif
  work_grow(w, n, ncells, maxthr);
  w->nx = nx;
  w->ny = ny;
  w->h = h;

  /* Stable counting sort of items by cell. */
  int *start = w->start, *cell = w->cell;
  memset(start, 0, (size_t)(ncells + 1) * sizeof *start);
#pragma omp parallel for schedule(static) if (YF_WANT_TEAM(n >= YF_SEARCH_PAR_MIN))
  for (int k = 0; k < n; k++) {
    int ix = (int)((cx[k] - xmin) / h), iy = (int)((cy[k] - ymin) / h);
    if (ix >= nx) ix = nx - 1;
    if (iy >= ny) iy = ny - 1;
    cell[k] = iy * nx + ix;
  }
  for (int k = 0; k < n; k++) start[cell[k] + 1]++;
  for (int c = 0; c < ncells; c++) start[c + 1] += start[c];
  for (int k = 0; k < n; k++) { /* scatter, then shift start back below */
    int p = start[cell[k]]++;
    w->sid[p] = k;
    w->sx[p] = cx[k];
    w->sy[p] = cy[k];
    w->sr[p] = r[k];
    w->stri[p] = tri ? tri[k] : k;
  }
  for (int c = ncells; c > 0; c--) start[c] = start[c - 1];
  start[0] = 0;

  const double *sx = w->sx, *sy = w->sy, *sr = w->sr;
  const int *stri = w->stri;
  long tested = 0;
  int nthr_used = 1;
  /* the items searched from: those whose triangle may be a couple's lower one (all by default) */
  int klo = 0, khi = n;
  if (f && f->lower_hi > f->lower_lo) {
    klo = first_item_at_least(n, tri, f->lower_lo);
    khi = first_item_at_least(n, tri, f->lower_hi);
  }

#pragma omp parallel reduction(+ : tested) if (YF_WANT_TEAM(n >= w->par_min))
  {
    int t = 0, nt = 1;
#ifdef _OPENMP
    t = omp_get_thread_num();
    nt = omp_get_num_threads();
#endif
#pragma omp single
    nthr_used = nt;
    /* A private copy of this thread's buffer header: the headers of all threads share a cache
     * line, and bumping a shared line's counter per pair would serialise the threads. */
    struct YfPairBuf bl = w->buf[t], *b = &bl;
    b->n = 0;
    int lo = klo + (int)((long)(khi - klo) * t / nt), hi = klo + (int)((long)(khi - klo) * (t + 1) / nt);
    for (int k = lo; k < hi; k++) {
      int ti = tri ? tri[k] : k;
      double xi = cx[k], yi = cy[k], ri = r[k] + buffer;
      int c = cell[k], ix = c % nx, iy = c / nx;
      int from = b->n;
      int y0 = iy > 0 ? iy - 1 : 0, y1 = iy + 1 < ny ? iy + 1 : ny - 1;
      int x0 = ix > 0 ? ix - 1 : 0, x1 = ix + 1 < nx ? ix + 1 : nx - 1;
      for (int yy = y0; yy <= y1; yy++) {
        /* the cells x0..x1 of a row are contiguous in the sorted slots */
        int p0 = start[yy * nx + x0], p1 = start[yy * nx + x1 + 1];
        for (int p = p0; p < p1; p++) {
          int tj = stri[p];
          if (tj <= ti) continue;
          double dx = sx[p] - xi, dy = sy[p] - yi, rr = ri + sr[p];
          tested++;
          if (dx * dx + dy * dy < rr * rr && (!f || filter_keep(f, ti, tj))) buf_push(b, ti, tj);
        }
      }
      sort_partners(b, from);
    }
    w->buf[t] = bl;
  }

  /* Concatenate the per-thread lists in thread (= item range) order, each thread copying its
   * own (a fresh list's first touch of its pages is most of this copy's cost at 1e6 couples). */
  int total = 0, off[YF_SEARCH_MAX_THREADS + 1];
  YF_ASSERT(nthr_used <= YF_SEARCH_MAX_THREADS);
  for (int t = 0; t < nthr_used; t++) {
    off[t] = total;
    total += w->buf[t].n;
  }
  contact_pairs_reserve(out, total);
#pragma omp parallel for schedule(static, 1) num_threads(nthr_used) if (YF_WANT_TEAM(nthr_used > 1))
  for (int t = 0; t < nthr_used; t++)
    if (w->buf[t].n) /* an empty list may have no array (memcpy of NULL: undefined, UBSan) */
      memcpy(out->ij + 2 * (size_t)off[t], w->buf[t].ij, (size_t)w->buf[t].n * 2 * sizeof *out->ij);
  out->n = total;
  w->tested = tested;
}

/* Is old couple a before key (i, j) in the list order? */
static inline int pair_before(const int *ij, int a, int i, int j)
{
  return ij[2 * a] < i || (ij[2 * a] == i && ij[2 * a + 1] < j);
}

/* The first couple of old not before (i, j) (binary search: the list is sorted). */
static int lower_bound(const YfPairs *old, int i, int j)
{
  int lo = 0, hi = old->n;
  while (lo < hi) {
    int mid = lo + (hi - lo) / 2;
    if (pair_before(old->ij, mid, i, j)) lo = mid + 1;
    else hi = mid;
  }
  return lo;
}

/* Fixed chunks of fresh couples, each finding its start in old by binary search.  Pass 1 marks
 * every fresh couple with the old slot of its memory (or -1) and counts per chunk; pass 2 numbers
 * the slots in couple order from the chunk counts and copies the memory, so the result is the
 * serial merge's on any thread count. */
#define MERGE_CHUNK 65536

static int merge_mark(const YfPairs *old, YfPairs *fresh, int k0, int k1)
{
  int a = lower_bound(old, fresh->ij[2 * k0], fresh->ij[2 * k0 + 1]), used = 0;
  for (int k = k0; k < k1; k++) {
    int i = fresh->ij[2 * k], j = fresh->ij[2 * k + 1];
    while (a < old->n && pair_before(old->ij, a, i, j)) a++;
    fresh->gi[k] = -1;
    if (a < old->n && old->ij[2 * a] == i && old->ij[2 * a + 1] == j && old->gi[a] >= 0) {
      if (contact_gmem_zero(old->g + YF_PAIR_NG * (size_t)old->gi[a])) continue;
      fresh->gi[k] = old->gi[a];
      used++;
    }
  }
  return used;
}

static void merge_copy(const YfPairs *old, YfPairs *fresh, int k0, int k1, int slot)
{
  for (int k = k0; k < k1; k++) {
    if (fresh->gi[k] < 0) continue;
    const double *g = old->g + YF_PAIR_NG * (size_t)fresh->gi[k];
    fresh->gi[k] = slot++;
    memcpy(fresh->g + YF_PAIR_NG * (size_t)fresh->gi[k], g, YF_PAIR_NG * sizeof *g);
  }
}

void contact_search_merge(const YfPairs *old, YfPairs *fresh)
{
  fresh->ng = 0;
  contact_pairs_greserve(fresh, old->ng);
  const int n = fresh->n, nch = (n + MERGE_CHUNK - 1) / MERGE_CHUNK;
  if (n == 0) return;
  if (old->ng == 0) { /* nothing to carry over */
    for (int k = 0; k < n; k++) fresh->gi[k] = -1;
    return;
  }
  int *cnt = yf_malloc((size_t)(nch + 1) * sizeof *cnt, "contact merge"); /* once per search */
#pragma omp parallel for schedule(static) if (YF_WANT_TEAM(nch > 1))
  for (int c = 0; c < nch; c++) {
    int k1 = (c + 1) * MERGE_CHUNK < n ? (c + 1) * MERGE_CHUNK : n;
    cnt[c] = merge_mark(old, fresh, c * MERGE_CHUNK, k1);
  }
  int total = 0;
  for (int c = 0; c < nch; c++) {
    int u = cnt[c];
    cnt[c] = total;
    total += u;
  }
#pragma omp parallel for schedule(static) if (YF_WANT_TEAM(nch > 1))
  for (int c = 0; c < nch; c++) {
    int k1 = (c + 1) * MERGE_CHUNK < n ? (c + 1) * MERGE_CHUNK : n;
    merge_copy(old, fresh, c * MERGE_CHUNK, k1, cnt[c]);
  }
  fresh->ng = total;
  free(cnt);
}

/* ---------------------------------------------------------------- travel trigger */

void contact_trigger_init(YfSearchTrigger *t, double buffer, double travel0)
{
  t->buffer = buffer;
  t->travel = travel0;
}

int contact_trigger_step(YfSearchTrigger *t, double dt, double vmax2)
{
  t->travel += 2.0 * dt * sqrt(vmax2);
  if (t->travel >= t->buffer) {
    t->travel = 0.0;
    return 1;
  }
  return 0;
}

double contact_vmax2(int n, const int *nodes, const double *vx, const double *vy)
{
  double vm = 0.0;
  YF_PARFOR_IF(n >= YF_SEARCH_PAR_MIN, schedule(static) reduction(max : vm), for (int k = 0; k < n; k++) {
    int i = nodes ? nodes[k] : k;
    double v2 = vx[i] * vx[i] + vy[i] * vy[i];
    if (v2 > vm) vm = v2;
  });
  return vm;
}
