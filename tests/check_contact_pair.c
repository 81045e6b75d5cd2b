/* check_contact_pair.c: the contact kernels (contact_pair.c narrow phase, contact_search.c broad
 * phase) against hand-computed integrals, conservation laws and a brute-force search.
 *
 * Reference configuration "flat": target T = right triangle (0,0), (1,0), (0,1), so that
 * beta_0 = y, beta_1 = 1 - x - y, beta_2 = x and D = 1.  Contactor C = (2,d), (-1,d), (0.5,-5):
 * its edge 0 runs from x = 2 to x = -1 at height d, crossing T at barycentric depth d; its other
 * edges pass outside T.  Along that edge P = min(d, x, 1 - d - x) on 0 <= x <= 1 - d, so
 * int P dx = d - 2 d^2 (d < 1/3), and with s = (2 - x)/3, L = 3:
 *   F = 3 p_n int P ds = p_n (d - 2d^2),  F_b = F (3 + d)/6,  F_a = F (3 - d)/6,
 * forces on the contactor nodes (0, -3 F_a) and (0, -3 F_b).
 */
#include <check.h>
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#ifdef _OPENMP
#include <omp.h>
#endif

#include "contact_pair.h"
#include "contact_search.h"

static const double TX[3] = {0.0, 1.0, 0.0}, TY[3] = {0.0, 0.0, 1.0};
static const double Z3[3] = {0.0, 0.0, 0.0};

static void flat_contactor(double d, double x[3], double y[3])
{
  x[0] = 2.0; y[0] = d;
  x[1] = -1.0; y[1] = d;
  x[2] = 0.5; y[2] = -5.0;
}

static double sum_abs(const double *f, int n)
{
  double s = 0.0;
  for (int k = 0; k < n; k++) s += fabs(f[k]);
  return s;
}

/* ------------------------------------------------------------------ normal force */

START_TEST(test_flat_exact_integral)
{
  const double pn = 1e9, d = 0.1;
  double xc[3], yc[3], g[3] = {0, 0, 0}, ft[6] = {0}, fc[6] = {0}, dmin2 = DBL_MAX;
  flat_contactor(d, xc, yc);
  YfContactInfo info = {0};
  int n = contact_pair_dir(TX, TY, Z3, Z3, xc, yc, Z3, Z3, pn, 0.0, 0.0, YF_FRIC_Y2D, 1e-6, g, ft, fc, &dmin2, &info);
  ck_assert_int_eq(n, 1);
  double F = pn * (d - 2 * d * d), Fa = F * (3 - d) / 6, Fb = F * (3 + d) / 6;
  double tol = 1e-14 * 3 * F;
  ck_assert_double_eq_tol(fc[0], 0.0, tol);
  ck_assert_double_eq_tol(fc[1], -3 * Fa, tol);
  ck_assert_double_eq_tol(fc[2], 0.0, tol);
  ck_assert_double_eq_tol(fc[3], -3 * Fb, tol);
  ck_assert_double_eq_tol(fc[4], 0.0, tol);
  ck_assert_double_eq_tol(fc[5], 0.0, tol);
  ck_assert_int_eq(info.nedge, 1);
  ck_assert_double_eq_tol(info.fn, 3 * F, tol);
  /* Reaction with the barycentric weights of the contactor nodes: at (2,d) beta = (d, -1-d, 2),
   * at (-1,d) beta = (d, 2-d, -1); vertex v takes beta_(v+1). */
  double fay = -3 * Fa, fby = -3 * Fb;
  ck_assert_double_eq_tol(ft[1], -(fay * (-1 - d) + fby * (2 - d)), tol);
  ck_assert_double_eq_tol(ft[3], -(fay * 2 + fby * (-1)), tol);
  ck_assert_double_eq_tol(ft[5], -(fay * d + fby * d), tol);
  ck_assert_double_eq_tol(ft[0] + ft[2] + ft[4], 0.0, tol);
  /* Energy estimate: 1.5 p_n L sum h_k int P^2 ds over the three pieces (h = 1, 1, 1/sqrt 2). */
  double E = 1.5 * pn * 3 * (d * d * d / 9 + d * d * (1 - 3 * d) / 3 + d * d * d / (9 * sqrt(2.0)));
  ck_assert_double_eq_tol(info.energy, E, 1e-13 * E);
  /* The two other contactor edges are skipped; their start nodes (-1,d) and (0.5,-5) record
   * their distance to the target edge line of smallest beta: x = 0 (1) and y = 0 (25). */
  ck_assert_double_eq_tol(dmin2, 1.0, 1e-14);
}
END_TEST

START_TEST(test_flat_depth_sweep)
{
  /* F = p_n (d - 2 d^2) at every depth d < 1/4, hence also monotonic there. */
  const double pn = 3e10;
  double prev = 0.0;
  for (int i = 1; i <= 24; i++) {
    double d = 0.01 * i, xc[3], yc[3], g[3] = {0}, ft[6] = {0}, fc[6] = {0}, dmin2 = DBL_MAX;
    flat_contactor(d, xc, yc);
    contact_pair_dir(TX, TY, Z3, Z3, xc, yc, Z3, Z3, pn, 0.0, 0.0, YF_FRIC_Y2D, 1e-6, g, ft, fc, &dmin2, NULL);
    double fy = fc[1] + fc[3] + fc[5], expect = -3 * pn * (d - 2 * d * d);
    ck_assert_double_eq_tol(fy, expect, 1e-13 * fabs(expect));
    ck_assert(-fy > prev);
    prev = -fy;
  }
}
END_TEST

START_TEST(test_separated)
{
  /* Contactor edge 0.1 below the target: no force, no friction update.  In the direction C on
   * T, the start node (2,-0.1) records its distance to the line x + y = 1 (beta_1 = -0.9 is the
   * smallest, a quirk: the true distance is to the corner (1,0)): 0.81/2; the other start nodes
   * record 1 and 25. */
  double xc[3], yc[3], g[6] = {1, 2, 3, 4, 5, 6}, fa[6] = {0}, fb[6] = {0}, dmin2 = 0;
  flat_contactor(-0.1, xc, yc);
  int r = contact_pair_force(TX, TY, Z3, Z3, xc, yc, Z3, Z3, 1e9, 1e9, 0.5, YF_FRIC_Y2D, 1e-3, g, fa, fb, &dmin2, NULL);
  ck_assert_int_eq(r, 0);
  ck_assert(sum_abs(fa, 6) == 0.0 && sum_abs(fb, 6) == 0.0);
  for (int k = 0; k < 6; k++) ck_assert(g[k] == k + 1);
  /* The other direction (T's edges on C) records the gap itself: (0,0) and (1,0) are 0.1 from
   * C's top edge line. */
  ck_assert_double_eq_tol(dmin2, 0.01, 1e-15);
  dmin2 = DBL_MAX;
  ck_assert_int_eq(contact_pair_dir(TX, TY, Z3, Z3, xc, yc, Z3, Z3, 1e9, 1e9, 0.5, YF_FRIC_Y2D, 1e-3, g, fa, fb, &dmin2, NULL), 0);
  ck_assert_double_eq_tol(dmin2, 0.405, 1e-14);
}
END_TEST

/* ------------------------------------------------------------------ pair: conservation */

static void torque_and_momentum(const double xa[3], const double ya[3], const double xb[3],
                                const double yb[3], const double fa[6], const double fb[6],
                                double *px, double *py, double *tq, double *scale)
{
  *px = *py = *tq = *scale = 0.0;
  for (int v = 0; v < 3; v++) {
    *px += fa[2 * v] + fb[2 * v];
    *py += fa[2 * v + 1] + fb[2 * v + 1];
    *tq += xa[v] * fa[2 * v + 1] - ya[v] * fa[2 * v] + xb[v] * fb[2 * v + 1] - yb[v] * fb[2 * v];
    *scale += (fabs(xa[v]) + fabs(ya[v]) + 1) * (fabs(fa[2 * v]) + fabs(fa[2 * v + 1])) +
              (fabs(xb[v]) + fabs(yb[v]) + 1) * (fabs(fb[2 * v]) + fabs(fb[2 * v + 1]));
  }
}

START_TEST(test_conservation)
{
  /* Two overlapping general triangles moving relative to each other, with friction (some edges
   * sticking, some sliding over the steps).  Reactions act at the barycentric image of the
   * contactor node, which is the node itself, so both linear and angular momentum are conserved
   * (normal and tangential parts alike); the tolerance is round-off of the weights. */
  const double xa[3] = {0.0, 1.0, 0.3}, ya[3] = {0.0, 0.1, 0.9};
  const double xb[3] = {0.4, 1.2, 0.2}, yb[3] = {0.2, 0.5, 1.1};
  const double vxa[3] = {0.3, -0.2, 0.1}, vya[3] = {0.05, 0.4, -0.3};
  const double vxb[3] = {-1.0, 0.7, 0.2}, vyb[3] = {0.6, -0.1, 0.9};
  double g[6] = {0};
  for (int step = 0; step < 20; step++) {
    double fa[6] = {0}, fb[6] = {0}, dmin2;
    YfContactInfo info = {0};
    int r = contact_pair_force(xa, ya, vxa, vya, xb, yb, vxb, vyb, 1e10, 3e9, 0.4, YF_FRIC_Y2D, 1e-4, g, fa, fb,
                               &dmin2, &info);
    ck_assert_int_eq(r, 1);
    ck_assert(info.ft > 0.0 && info.fn > 0.0);
    double px, py, tq, sc;
    torque_and_momentum(xa, ya, xb, yb, fa, fb, &px, &py, &tq, &sc);
    ck_assert(fabs(px) <= 1e-14 * sc && fabs(py) <= 1e-14 * sc);
    ck_assert(fabs(tq) <= 1e-14 * sc);
  }
}
END_TEST

/* Apex-to-apex: A = (0,0),(2,0),(1,1) and B = A turned upside down, its apex delta into A. */
static void apex_pair(double delta, double xa[3], double ya[3], double xb[3], double yb[3])
{
  xa[0] = 0; ya[0] = 0; xa[1] = 2; ya[1] = 0; xa[2] = 1; ya[2] = 1;
  xb[0] = 2; yb[0] = 2 - delta; xb[1] = 0; yb[1] = 2 - delta; xb[2] = 1; yb[2] = 1 - delta;
}

START_TEST(test_monotonic_symmetric)
{
  double prev = 0.0;
  for (int i = 1; i <= 30; i++) {
    double delta = 0.01 * i, xa[3], ya[3], xb[3], yb[3], g[6] = {0}, fa[6] = {0}, fb[6] = {0}, dmin2;
    apex_pair(delta, xa, ya, xb, yb);
    int r = contact_pair_force(xa, ya, Z3, Z3, xb, yb, Z3, Z3, 1e9, 0, 0, YF_FRIC_Y2D, 1e-6, g, fa, fb, &dmin2, NULL);
    ck_assert_int_eq(r, 1);
    double fyb = fb[1] + fb[3] + fb[5];
    ck_assert(fyb > prev); /* B is pushed up, harder the deeper it goes */
    prev = fyb;
    /* Mirror x -> 2 - x maps A's corner 0 <-> 1 and B's 0 <-> 1, apexes onto themselves. */
    double tol = 1e-13 * fyb;
    ck_assert_double_eq_tol(fa[0], -fa[2], tol);
    ck_assert_double_eq_tol(fa[1], fa[3], tol);
    ck_assert_double_eq_tol(fa[4], 0.0, tol);
    ck_assert_double_eq_tol(fb[0], -fb[2], tol);
    ck_assert_double_eq_tol(fb[1], fb[3], tol);
    ck_assert_double_eq_tol(fb[4], 0.0, tol);
  }
  /* Apart by 0.01: nothing. */
  double xa[3], ya[3], xb[3], yb[3], g[6] = {0}, fa[6] = {0}, fb[6] = {0}, dmin2;
  apex_pair(-0.01, xa, ya, xb, yb);
  ck_assert_int_eq(contact_pair_force(xa, ya, Z3, Z3, xb, yb, Z3, Z3, 1e9, 1e9, 0.5, YF_FRIC_Y2D, 1e-6, g, fa, fb,
                                      &dmin2, NULL), 0);
  ck_assert(sum_abs(fa, 6) == 0.0 && sum_abs(fb, 6) == 0.0);
}
END_TEST

/* ------------------------------------------------------------------ friction */

START_TEST(test_friction_stick_then_slide)
{
  /* Flat configuration, contactor sliding at +0.5 m/s along x, target at rest:
   * w = (0 - 0.5) * (-3) = 1.5, so g_n = 1.5 n dt and F_t = p_t g_n until it reaches mu |F|,
   * then exactly mu |F| with g held at mu |F| / p_t.  The tangential force on the contactor
   * is F_t t_c = (-3 F_t, 0) in total. */
  const double pn = 1e3, pt = 1e3, mu = 0.3, dt = 1e-3, d = 0.1;
  const double F = pn * (d - 2 * d * d), cap = mu * F;
  double xc[3], yc[3], vx[3] = {0.5, 0.5, 0.5}, g[3] = {0};
  flat_contactor(d, xc, yc);
  int slid = 0;
  for (int n = 1; n <= 25; n++) {
    double ft[6] = {0}, fc[6] = {0}, dmin2 = DBL_MAX;
    YfContactInfo info = {0};
    contact_pair_dir(TX, TY, Z3, Z3, xc, yc, vx, Z3, pn, pt, mu, YF_FRIC_Y2D, dt, g, ft, fc, &dmin2, &info);
    double fx = fc[0] + fc[2] + fc[4];
    double Ft = pt * 1.5 * n * dt;
    if (Ft <= cap * (1 - 1e-12)) {
      ck_assert_double_eq_tol(fx, -3 * Ft, 1e-12 * cap);
      ck_assert_double_eq_tol(g[0], 1.5 * n * dt, 1e-12 * cap / pt);
      ck_assert(info.dissip == 0.0);
    } else if (Ft > cap * (1 + 1e-12)) {
      slid++;
      ck_assert_double_eq_tol(fx, -3 * cap, 1e-13 * cap);
      ck_assert_double_eq_tol(g[0], cap / pt, 1e-13 * cap / pt);
      /* Steady sliding: dissipation = mu x normal force (3F) x speed x dt. */
      if (Ft > cap + pt * 1.5 * dt) ck_assert_double_eq_tol(info.dissip, cap * 3 * 0.5 * dt, 1e-9 * cap * dt);
    }
    ck_assert(g[1] == 0.0 && g[2] == 0.0); /* the skipped edges keep their (zero) memory */
  }
  ck_assert_int_ge(slid, 8);

  /* Leaving contact: the edge is skipped and g keeps its value bit for bit. */
  double gkeep = g[0], ft[6] = {0}, fc[6] = {0}, dmin2 = DBL_MAX;
  flat_contactor(-0.1, xc, yc);
  ck_assert_int_eq(contact_pair_dir(TX, TY, Z3, Z3, xc, yc, vx, Z3, pn, pt, mu, YF_FRIC_Y2D, dt, g, ft, fc, &dmin2, NULL), 0);
  ck_assert(g[0] == gkeep);
  ck_assert(sum_abs(fc, 6) == 0.0);
}
END_TEST

START_TEST(test_friction_mu_zero)
{
  const double d = 0.1;
  double xc[3], yc[3], vx[3] = {0.5, 0.5, 0.5}, g[3] = {0};
  flat_contactor(d, xc, yc);
  for (int n = 0; n < 3; n++) {
    double ft[6] = {0}, fc[6] = {0}, dmin2 = DBL_MAX;
    contact_pair_dir(TX, TY, Z3, Z3, xc, yc, vx, Z3, 1e3, 1e3, 0.0, YF_FRIC_Y2D, 1e-3, g, ft, fc, &dmin2, NULL);
    ck_assert(fc[0] + fc[2] + fc[4] == 0.0); /* normal force is along y only */
    ck_assert(ft[0] + ft[2] + ft[4] == 0.0);
  }
}
END_TEST

START_TEST(test_friction_sbar_is_breakpoint_mean)
{
  /* Edge from (0.5,d) (inside T) to (-1,d): breakpoints s = 0, (0.5-d)/1.5 (kink beta_0 =
   * beta_2 at x = d) and 1/3 (exit through x = 0).  Target vertex 1 moves at (u, 0): the target
   * velocity at s is beta_2(x(s)) u = x(s) u.  Y2D samples it at the MEAN of the breakpoints,
   * s_bar, not at the centroid of P; g after one step = w dt with w = x(s_bar) u (-1.5). */
  const double d = 0.1, u = 2.0, dt = 1e-3;
  double xc[3] = {0.5, -1.0, -0.25}, yc[3] = {d, d, -5.0};
  double vxt[3] = {0.0, u, 0.0}, g[3] = {0}, ft[6] = {0}, fc[6] = {0}, dmin2 = DBL_MAX;
  contact_pair_dir(TX, TY, vxt, Z3, xc, yc, Z3, Z3, 1e3, 1e3, 0.5, YF_FRIC_Y2D, dt, g, ft, fc, &dmin2, NULL);
  double sbar = (0.0 + (0.5 - d) / 1.5 + 1.0 / 3.0) / 3.0, xs = 0.5 - 1.5 * sbar;
  ck_assert_double_eq_tol(g[0], xs * u * (-1.5) * dt, 1e-14);
  ck_assert(fabs(xs - 0.2) < 1e-14); /* (a centroid rule would give about 0.27) */
}
END_TEST

/* ------------------------------------------------------------------ broad phase */

static uint64_t rng_state;
static double urand(void)
{
  rng_state = rng_state * 6364136223846793005ULL + 1442695040888963407ULL;
  return (double)(rng_state >> 11) * (1.0 / 9007199254740992.0);
}

/* n random triangles (own nodes, CCW), sizes 0.3..1.5 (times s0), in a square of side L. */
static void random_tris(int n, double L, double s0, double *x, double *y, int *tv)
{
  for (int t = 0; t < n; t++) {
    double cx = L * urand(), cy = L * urand(), s = s0 * (0.3 + 1.2 * urand()), th = 6.283185307179586 * urand();
    for (int c = 0; c < 3; c++) {
      double a = th + c * 2.0943951023931957 + 0.5 * (urand() - 0.5), rr = s * (0.5 + 0.5 * urand());
      x[3 * t + c] = cx + rr * cos(a);
      y[3 * t + c] = cy + rr * sin(a);
      tv[3 * t + c] = 3 * t + c;
    }
  }
}

typedef struct {
  int n, cap;
  int *ij;
} IntPairs;

static void ip_push(IntPairs *p, int i, int j)
{
  if (p->n == p->cap) {
    p->cap = p->cap ? 2 * p->cap : 1024;
    p->ij = realloc(p->ij, (size_t)p->cap * 2 * sizeof(int));
  }
  p->ij[2 * p->n] = i;
  p->ij[2 * p->n + 1] = j;
  p->n++;
}

static int shares_node(const int *tv, int i, int j)
{
  for (int a = 0; a < 3; a++)
    for (int b = 0; b < 3; b++)
      if (tv[3 * i + a] == tv[3 * j + b]) return 1;
  return 0;
}

/* O(N^2) reference with the same filter semantics; items in order, tri[] increasing. */
static void brute(int n, const int *tri, const double *cx, const double *cy, const double *r, double buf,
                  const int *group, const uint64_t *mask, const int *tv, IntPairs *out)
{
  out->n = 0;
  for (int a = 0; a < n; a++)
    for (int b = a + 1; b < n; b++) {
      int i = tri[a], j = tri[b];
      double dx = cx[b] - cx[a], dy = cy[b] - cy[a], rr = (r[a] + buf) + r[b];
      if (!(dx * dx + dy * dy < rr * rr)) continue;
      if (group && group[i] == group[j]) continue;
      if (mask && !(mask[i] & mask[j])) continue;
      if (tv && shares_node(tv, i, j)) continue;
      ip_push(out, i, j);
    }
}

static void assert_same(const YfPairs *p, const IntPairs *q)
{
  ck_assert_int_eq(p->n, q->n);
  ck_assert(memcmp(p->ij, q->ij, (size_t)q->n * 2 * sizeof(int)) == 0);
}

START_TEST(test_search_equals_brute_force)
{
  enum { N = 2000 };
  double *x = malloc(3 * N * sizeof *x), *y = malloc(3 * N * sizeof *y);
  int *tv = malloc(3 * N * sizeof *tv), *tri = malloc(N * sizeof *tri);
  double *cx = malloc(N * sizeof *cx), *cy = malloc(N * sizeof *cy), *r = malloc(N * sizeof *r);
  rng_state = 12345;
  YfSearchWork w;
  contact_search_work_init(&w);
  YfPairs p;
  contact_pairs_init(&p);
  IntPairs q = {0};
  /* Sparse, dense and crowded scenes, with buffers from 0 to larger than a triangle. */
  const double Ls[3] = {80.0, 40.0, 12.0}, bufs[3] = {0.0, 0.05, 2.0};
  for (int sc = 0; sc < 3; sc++) {
    random_tris(N, Ls[sc], 1.0, x, y, tv);
    /* Items are a subset of the triangles (every other one plus some), tri[] increasing. */
    int n = 0;
    for (int t = 0; t < N; t++)
      if (t % 2 == 0 || t % 7 == 0) tri[n++] = t;
    contact_search_bounds(n, tri, tv, x, y, cx, cy, r);
    for (int b = 0; b < 3; b++) {
      brute(n, tri, cx, cy, r, bufs[b], NULL, NULL, NULL, &q);
      ck_assert_int_gt(q.n, 0);
      w.par_min = 1 << 30; /* serial */
      contact_search(&w, n, tri, cx, cy, r, bufs[b], NULL, &p);
      assert_same(&p, &q);
      w.par_min = 1;       /* threaded, with the runner's thread count */
      contact_search(&w, n, tri, cx, cy, r, bufs[b], NULL, &p);
      assert_same(&p, &q);
    }
  }
  free(q.ij);
  contact_pairs_free(&p);
  contact_search_work_free(&w);
  free(x); free(y); free(tv); free(tri); free(cx); free(cy); free(r);
}
END_TEST

static int keep_odd_sum(int i, int j, void *ctx)
{
  (void)ctx;
  return (i + j) % 2;
}

START_TEST(test_search_filters_and_threads)
{
  /* A structured mesh of shared-node triangles (nx x ny squares, two triangles each) with
   * bodies = column bands and random group masks. */
  enum { NX = 30, NY = 30, NT = 2 * NX * NY };
  double x[(NX + 1) * (NY + 1)], y[(NX + 1) * (NY + 1)];
  int tv[3 * NT], group[NT];
  uint64_t mask[NT];
  rng_state = 777;
  for (int j = 0; j <= NY; j++)
    for (int i = 0; i <= NX; i++) {
      x[j * (NX + 1) + i] = i + 0.2 * (urand() - 0.5);
      y[j * (NX + 1) + i] = j + 0.2 * (urand() - 0.5);
    }
  int t = 0;
  for (int j = 0; j < NY; j++)
    for (int i = 0; i < NX; i++) {
      int n0 = j * (NX + 1) + i, n1 = n0 + 1, n2 = n0 + NX + 2, n3 = n0 + NX + 1;
      tv[3 * t] = n0; tv[3 * t + 1] = n1; tv[3 * t + 2] = n2; group[t] = i / 5; mask[t] = 1ULL << (int)(4 * urand()); t++;
      tv[3 * t] = n0; tv[3 * t + 1] = n2; tv[3 * t + 2] = n3; group[t] = i / 5; mask[t] = 1ULL << (int)(4 * urand()); t++;
    }
  static double cx[NT], cy[NT], r[NT];
  contact_search_bounds(NT, NULL, tv, x, y, cx, cy, r);
  static int tri[NT];
  for (int k = 0; k < NT; k++) tri[k] = k;
  YfSearchWork w;
  contact_search_work_init(&w);
  YfPairs p, p1;
  contact_pairs_init(&p);
  contact_pairs_init(&p1);
  IntPairs q = {0};
  const double buf = 0.3;

  YfSearchFilter f = {0};
  f.group = group;
  contact_search(&w, NT, NULL, cx, cy, r, buf, &f, &p);
  brute(NT, tri, cx, cy, r, buf, group, NULL, NULL, &q);
  assert_same(&p, &q);

  f = (YfSearchFilter){0};
  f.mask = mask;
  contact_search(&w, NT, NULL, cx, cy, r, buf, &f, &p);
  brute(NT, tri, cx, cy, r, buf, NULL, mask, NULL, &q);
  assert_same(&p, &q);

  f = (YfSearchFilter){0};
  f.tri_v = tv;
  contact_search(&w, NT, NULL, cx, cy, r, buf, &f, &p);
  brute(NT, tri, cx, cy, r, buf, NULL, NULL, tv, &q);
  ck_assert_int_gt(q.n, 0);
  assert_same(&p, &q);

  /* The callback: keep pairs with i + j odd. */
  f = (YfSearchFilter){0};
  f.keep = keep_odd_sum;
  contact_search(&w, NT, NULL, cx, cy, r, buf, &f, &p);
  brute(NT, tri, cx, cy, r, buf, NULL, NULL, NULL, &q);
  int m = 0;
  for (int k = 0; k < q.n; k++)
    if ((q.ij[2 * k] + q.ij[2 * k + 1]) % 2) { q.ij[2 * m] = q.ij[2 * k]; q.ij[2 * m + 1] = q.ij[2 * k + 1]; m++; }
  q.n = m;
  assert_same(&p, &q);

  /* The lower-triangle range (MPI: a rank searches from its own triangles only): the couples of
   * brute force whose lower triangle is in [a, b), in the same order, on 1 and 2 threads, for
   * ranges that start and end anywhere (at the ends, one triangle, past the last); items given by a list
   * of triangle numbers with gaps (every other one), as the ranks' searches give them. */
  static int half[NT / 2];
  for (int k = 0; k < NT / 2; k++) half[k] = 2 * k + 1;
  static double hx[NT / 2], hy[NT / 2], hr[NT / 2];
  for (int k = 0; k < NT / 2; k++) { hx[k] = cx[half[k]]; hy[k] = cy[half[k]]; hr[k] = r[half[k]]; }
  const int ranges[][2] = {{0, NT}, {0, NT / 3}, {NT / 3, 2 * NT / 3}, {2 * NT / 3, NT}, {7, 8}, {8, 9}, {NT - 1, NT + 5}};
  int nthr0 = 1;
#ifdef _OPENMP
  nthr0 = omp_get_max_threads();
  w.par_min = 1;
#endif
  for (int g = 0; g < 2; g++)
    for (unsigned c = 0; c < sizeof ranges / sizeof ranges[0]; c++)
      for (int th = 1; th <= 2; th++) {
#ifdef _OPENMP
        omp_set_num_threads(th);
#endif
        const int n = g ? NT / 2 : NT, *items = g ? half : tri;
        f = (YfSearchFilter){0};
        f.lower_lo = ranges[c][0];
        f.lower_hi = ranges[c][1];
        if (g) contact_search(&w, n, half, hx, hy, hr, buf, &f, &p);
        else contact_search(&w, n, NULL, cx, cy, r, buf, &f, &p);
        brute(n, items, g ? hx : cx, g ? hy : cy, g ? hr : r, buf, NULL, NULL, NULL, &q);
        int kept = 0;
        for (int k = 0; k < q.n; k++)
          if (q.ij[2 * k] >= ranges[c][0] && q.ij[2 * k] < ranges[c][1]) {
            q.ij[2 * kept] = q.ij[2 * k]; q.ij[2 * kept + 1] = q.ij[2 * k + 1]; kept++;
          }
        q.n = kept;
        if (ranges[c][1] - ranges[c][0] > NT / 4) ck_assert_int_gt(q.n, 0);
        assert_same(&p, &q);
      }
#ifdef _OPENMP
  omp_set_num_threads(nthr0);
#endif

#ifdef _OPENMP
  /* Same list, bit for bit, with 1 and 2 threads (threaded path forced for this small N), and
   * equal to brute force with 2 threads. */
  int nthr = omp_get_max_threads();
  w.par_min = 1;
  omp_set_num_threads(1);
  contact_search(&w, NT, NULL, cx, cy, r, buf, NULL, &p1);
  omp_set_num_threads(2);
  contact_search(&w, NT, NULL, cx, cy, r, buf, NULL, &p);
  omp_set_num_threads(nthr);
  ck_assert_int_eq(p.n, p1.n);
  ck_assert(memcmp(p.ij, p1.ij, (size_t)p.n * 2 * sizeof(int)) == 0);
  brute(NT, tri, cx, cy, r, buf, NULL, NULL, NULL, &q);
  assert_same(&p, &q);
#endif
  free(q.ij);
  contact_pairs_free(&p);
  contact_pairs_free(&p1);
  contact_search_work_free(&w);
}
END_TEST

static double gval(int i, int j, int q) { return i * 1000.0 + j + 0.125 * q; }

START_TEST(test_search_merge_keeps_friction)
{
  enum { N = 1500 };
  static double x[3 * N], y[3 * N], cx[N], cy[N], r[N];
  static int tv[3 * N];
  rng_state = 99;
  random_tris(N, 35.0, 1.0, x, y, tv);
  YfSearchWork w;
  contact_search_work_init(&w);
  YfPairs old, fresh;
  contact_pairs_init(&old);
  contact_pairs_init(&fresh);
  contact_search_bounds(N, NULL, tv, x, y, cx, cy, r);
  contact_search(&w, N, NULL, cx, cy, r, 0.1, NULL, &old);
  contact_pairs_greserve(&old, old.n);
  old.ng = 0;
  for (int k = 0; k < old.n; k++) {
    old.gi[k] = -1;
    if (k % 5 == 4) continue; /* some couples never touched: no memory */
    double *g = contact_pairs_gslot(&old, k);
    for (int q = 0; q < YF_PAIR_NG; q++) g[q] = gval(old.ij[2 * k], old.ij[2 * k + 1], q);
  }
  /* Drop every third old couple (as the force routine would), then move everything. */
  unsigned char *keep = malloc(old.n > 0 ? old.n : 1);
  for (int k = 0; k < old.n; k++) keep[k] = (k % 3 != 0);
  int before = old.n;
  ck_assert_int_eq(contact_pairs_compact(&old, keep), before - (before + 2) / 3);
  for (int k = 0; k < 3 * N; k++) { x[k] += 0.6 * (urand() - 0.5); y[k] += 0.6 * (urand() - 0.5); }
  contact_search_bounds(N, NULL, tv, x, y, cx, cy, r);
  contact_search(&w, N, NULL, cx, cy, r, 0.1, NULL, &fresh);
  contact_search_merge(&old, &fresh);
  int carried = 0, fresh0 = 0, bad = 0;
  for (int k = 0; k < fresh.n; k++) {
    int i = fresh.ij[2 * k], j = fresh.ij[2 * k + 1], found = 0, had = 0;
    for (int a = 0; a < old.n; a++) /* linear scan: the test's own reference */
      if (old.ij[2 * a] == i && old.ij[2 * a + 1] == j) { found = 1; had = old.gi[a] >= 0; break; }
    for (int q = 0; q < YF_PAIR_NG; q++) {
      double want = found && had ? gval(i, j, q) : 0.0;
      double got = fresh.gi[k] >= 0 ? fresh.g[YF_PAIR_NG * fresh.gi[k] + q] : 0.0;
      bad += !(got == want);
    }
    carried += found;
    fresh0 += !found;
  }
  ck_assert_int_eq(bad, 0);
  ck_assert(carried > 0 && fresh0 > 0);
  free(keep);
  contact_pairs_free(&old);
  contact_pairs_free(&fresh);
  contact_search_work_free(&w);
}
END_TEST

/* The merge runs in fixed chunks of fresh couples on all threads: on lists of several chunks it
 * must give what one serial two-pointer merge gives (slots numbered in couple order, all-zero
 * memory not carried), bit for bit, on 1 and 2 threads. */
START_TEST(test_search_merge_chunks_match_serial)
{
  enum { NO = 300000, NF = 280000 };
  YfPairs old, fresh;
  contact_pairs_init(&old);
  contact_pairs_init(&fresh);
  contact_pairs_reserve(&old, NO);
  contact_pairs_reserve(&fresh, NF);
  rng_state = 4242;
  /* sorted keys (i, j): old steps through i with random partners; fresh keeps ~2/3 of old's
   * couples and adds new ones between them */
  int n = 0, i = 0, j = 1;
  while (n < NO) {
    if (urand() < 0.2) { i++; j = i + 1; }
    j += 1 + (int)(3 * urand());
    old.ij[2 * n] = i; old.ij[2 * n + 1] = j; n++;
  }
  old.n = NO;
  contact_pairs_greserve(&old, NO);
  old.ng = 0;
  for (int k = 0; k < NO; k++) {
    old.gi[k] = -1;
    double u = urand();
    if (u < 0.5) continue;                  /* never touched */
    double *g = contact_pairs_gslot(&old, k);
    if (u < 0.6) continue;                  /* touched, memory back to zero: not carried */
    for (int q = 0; q < YF_PAIR_NG; q++) g[q] = urand() - 0.5;
  }
  int a = 0, f = 0;
  while (f < NF && a < NO) {
    if (urand() < 0.66) { fresh.ij[2 * f] = old.ij[2 * a]; fresh.ij[2 * f + 1] = old.ij[2 * a + 1]; f++; }
    else if (urand() < 0.5 && (a + 1 == NO || old.ij[2 * a] != old.ij[2 * a + 2] || old.ij[2 * a + 1] + 1 < old.ij[2 * a + 3])) {
      fresh.ij[2 * f] = old.ij[2 * a]; fresh.ij[2 * f + 1] = old.ij[2 * a + 1] + 1; f++; /* a new key after a */
      if (a + 1 < NO && old.ij[2 * a] == old.ij[2 * a + 2] && old.ij[2 * a + 3] == old.ij[2 * a + 1] + 1) f--;
    }
    a++;
  }
  fresh.n = f;
  ck_assert_int_gt(fresh.n, 3 * 65536);
  for (int k = 1; k < fresh.n; k++) /* the merge's precondition: strictly sorted keys */
    ck_assert(fresh.ij[2 * k - 2] < fresh.ij[2 * k] ||
              (fresh.ij[2 * k - 2] == fresh.ij[2 * k] && fresh.ij[2 * k - 1] < fresh.ij[2 * k + 1]));
  /* the reference: one serial two-pointer pass */
  int *rgi = malloc((size_t)fresh.n * sizeof *rgi), rng = 0;
  double *rg = malloc((size_t)fresh.n * YF_PAIR_NG * sizeof *rg);
  for (int k = 0, p = 0; k < fresh.n; k++) {
    int fi = fresh.ij[2 * k], fj = fresh.ij[2 * k + 1];
    while (p < NO && (old.ij[2 * p] < fi || (old.ij[2 * p] == fi && old.ij[2 * p + 1] < fj))) p++;
    rgi[k] = -1;
    if (p < NO && old.ij[2 * p] == fi && old.ij[2 * p + 1] == fj && old.gi[p] >= 0) {
      const double *g = old.g + YF_PAIR_NG * (size_t)old.gi[p];
      int nz = 0;
      for (int q = 0; q < YF_PAIR_NG; q++) nz |= g[q] != 0.0;
      if (!nz) continue;
      rgi[k] = rng;
      memcpy(rg + YF_PAIR_NG * (size_t)rng, g, YF_PAIR_NG * sizeof *g);
      rng++;
    }
  }
  ck_assert_int_gt(rng, 1000);
  for (int t = 1; t <= 2; t++) {
    omp_set_num_threads(t);
    contact_search_merge(&old, &fresh);
    ck_assert_int_eq(fresh.ng, rng);
    int bad = 0;
    for (int k = 0; k < fresh.n; k++) {
      bad += fresh.gi[k] != rgi[k];
      if (rgi[k] >= 0 && fresh.gi[k] == rgi[k])
        bad += memcmp(fresh.g + YF_PAIR_NG * (size_t)rgi[k], rg + YF_PAIR_NG * (size_t)rgi[k], YF_PAIR_NG * sizeof(double)) != 0;
    }
    ck_assert_msg(bad == 0, "%d threads: %d couples differ from the serial merge", t, bad);
  }
  omp_set_num_threads(2);
  free(rgi);
  free(rg);
  contact_pairs_free(&old);
  contact_pairs_free(&fresh);
}
END_TEST

START_TEST(test_search_large_sampled)
{
  /* 2e5 triangles: the list is strictly sorted, every pair satisfies the distance test, and for
   * 300 sampled triangles the number of partners equals a brute-force count over all N. */
  enum { N = 200000 };
  double *x = malloc(3 * N * sizeof *x), *y = malloc(3 * N * sizeof *y);
  double *cx = malloc(N * sizeof *cx), *cy = malloc(N * sizeof *cy), *r = malloc(N * sizeof *r);
  int *tv = malloc(3 * N * sizeof *tv);
  rng_state = 2024;
  random_tris(N, 400.0, 1.0, x, y, tv);
  contact_search_bounds(N, NULL, tv, x, y, cx, cy, r);
  YfSearchWork w;
  contact_search_work_init(&w);
  YfPairs p;
  contact_pairs_init(&p);
  const double buf = 0.2;
  contact_search(&w, N, NULL, cx, cy, r, buf, NULL, &p);
  ck_assert_int_gt(p.n, N);
  /* (Failures are counted and asserted once: Check records every passing assertion.) */
  int *cnt = calloc(N, sizeof *cnt);
  long bad = 0;
  for (int k = 0; k < p.n; k++) {
    int i = p.ij[2 * k], j = p.ij[2 * k + 1];
    bad += !(i < j);
    if (k > 0) bad += !(i > p.ij[2 * k - 2] || (i == p.ij[2 * k - 2] && j > p.ij[2 * k - 1]));
    double dx = cx[j] - cx[i], dy = cy[j] - cy[i], rr = r[i] + buf + r[j];
    bad += !(dx * dx + dy * dy < rr * rr);
    cnt[i]++;
    cnt[j]++;
  }
  ck_assert_int_eq(bad, 0);
  for (int s = 0; s < 300; s++) {
    int a = (int)(urand() * N), c = 0;
    for (int b = 0; b < N; b++) {
      if (b == a) continue;
      int i = a < b ? a : b, j = a < b ? b : a;
      double dx = cx[j] - cx[i], dy = cy[j] - cy[i], rr = r[i] + buf + r[j];
      c += dx * dx + dy * dy < rr * rr;
    }
    ck_assert_int_eq(cnt[a], c);
  }
  free(cnt);
  contact_pairs_free(&p);
  contact_search_work_free(&w);
  free(x); free(y); free(tv); free(cx); free(cy); free(r);
}
END_TEST

START_TEST(test_trigger)
{
  /* 2 dt |v|max = 0.25 per step with buffer 1: search on the first step (initial travel 1e15),
   * then every 4th step. */
  YfSearchTrigger t;
  contact_trigger_init(&t, 1.0, 1e15);
  double vx[3] = {0.3, -1.0, 0.2}, vy[3] = {0.4, 0.0, 0.1};
  double v2 = contact_vmax2(3, NULL, vx, vy);
  ck_assert(v2 == 1.0);
  int idx[2] = {0, 2};
  ck_assert_double_eq_tol(contact_vmax2(2, idx, vx, vy), 0.25, 1e-16);
  int expect[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  for (int s = 0; s < 9; s++) ck_assert_int_eq(contact_trigger_step(&t, 0.125, v2), expect[s]);
}
END_TEST

static void random_couple(int mode, double xa[3], double ya[3], double xb[3], double yb[3]);

/* ------------------------------------------------------------------ random pairs */

START_TEST(test_random_pairs_conserve)
{
  /* Random overlapping pairs, plus mesh neighbours that share corners or whole edges (the
   * degenerate cases of an intact body: zero barycentric values, parallel lines): forces are
   * finite, linear and angular momentum are conserved to round-off, and a pair sharing an edge
   * exactly without overlap gets no force at all. */
  rng_state = 31337;
  int bad = 0, touching = 0;
  for (int it = 0; it < 3000; it++) {
    double xa[3], ya[3], xb[3], yb[3], vxa[3], vya[3], vxb[3], vyb[3];
    int mode = it % 3;
    for (int q = 0; q < 3; q++) {
      vxa[q] = urand() - 0.5; vya[q] = urand() - 0.5; vxb[q] = urand() - 0.5; vyb[q] = urand() - 0.5;
    }
    if (mode == 0) { /* two random CCW triangles near each other */
      random_couple(0, xa, ya, xb, yb);
    } else { /* the two triangles of a unit square cell (shared diagonal), perhaps nudged */
      double e = mode == 1 ? 0.0 : 0.02 * (urand() - 0.5);
      xa[0] = 0; ya[0] = 0; xa[1] = 1; ya[1] = 0; xa[2] = 1; ya[2] = 1;
      xb[0] = 0 + e; yb[0] = 0; xb[1] = 1; yb[1] = 1 + e; xb[2] = 0; yb[2] = 1;
    }
    double g[6] = {0}, fa[6] = {0}, fb[6] = {0}, d2;
    int r = 0;
    for (int step = 0; step < 3; step++) {
      for (int q = 0; q < 6; q++) fa[q] = fb[q] = 0.0;
      r = contact_pair_force(xa, ya, vxa, vya, xb, yb, vxb, vyb, 1e10, 1e9, 0.3, YF_FRIC_Y2D, 1e-4, g, fa, fb, &d2, NULL);
    }
    touching += r;
    double px, py, tq, sc;
    torque_and_momentum(xa, ya, xb, yb, fa, fb, &px, &py, &tq, &sc);
    if (!isfinite(sc) || fabs(px) > 1e-14 * sc || fabs(py) > 1e-14 * sc || fabs(tq) > 1e-14 * sc) bad++;
    if (mode == 1 && (r != 0 || sc != 0.0)) bad++;
  }
  ck_assert_int_eq(bad, 0);
  ck_assert_int_gt(touching, 1000);
}
END_TEST

/* Outcome s of the screen (0 busy, 1 keep, 2 drop) against the kernel's answer for the same couple
 * (return r, forces fa, fb, friction g, distance d2) at removal distance rem2: a quiet couple must
 * have no force and no friction change, and dropped exactly when d2 > rem2.  Counts into t. */
typedef struct { int busy, quiet, dropped, bad; } Tally;
static void tally_screen(int s, int r, const double fa[6], const double fb[6], const double g[6], double d2,
                         double rem2, Tally *t)
{
  if (s == 0) { t->busy++; return; }
  t->quiet++;
  double sum = 0;
  for (int c = 0; c < 6; c++) sum += fabs(fa[c]) + fabs(fb[c]) + fabs(g[c]);
  if (r != 0 || sum != 0.0) t->bad++;
  if ((s == 2) != (d2 > rem2)) t->bad++;
  t->dropped += s == 2;
}

/* The screen (contact_pair_quiet) must decide exactly as the kernel: on neighbours of a jointed
 * mesh (own nodes per triangle, corners coincident up to a random nudge of 1e-9..1e-1 of the
 * cell), a couple it calls quiet gets no force and no friction change from contact_pair_force,
 * and keep/drop agrees with the kernel's dmin2 against rem2, including rem2 within an ulp of
 * dmin2. */
START_TEST(test_screen_matches_kernel)
{
  rng_state = 7;
  enum { NC = 3, NT = 2 * NC * NC };
  Tally tl = {0, 0, 0, 0};
  for (int trial = 0; trial < 400; trial++) {
    double X[NT][3], Y[NT][3], V[NT][3] = {{0}};
    double nudge = pow(10.0, -9.0 + 8.0 * urand());
    for (int c = 0; c < NC * NC; c++) { /* cell (i, j) of side 1, two triangles "right" */
      double x0 = c % NC, y0 = c / NC;
      double tx[2][3] = {{x0, x0 + 1, x0 + 1}, {x0, x0 + 1, x0}}, ty[2][3] = {{y0, y0, y0 + 1}, {y0, y0 + 1, y0 + 1}};
      for (int h = 0; h < 2; h++)
        for (int q = 0; q < 3; q++) {
          X[2 * c + h][q] = tx[h][q] + nudge * (urand() - 0.5);
          Y[2 * c + h][q] = ty[h][q] + nudge * (urand() - 0.5);
        }
    }
    double rec[NT][YF_TRI_GEOM];
    for (int t = 0; t < NT; t++) contact_pair_geom(X[t], Y[t], rec[t]);
    for (int i = 0; i < NT; i++)
      for (int j = i + 1; j < NT; j++) {
        double g[6] = {0}, fa[6] = {0}, fb[6] = {0}, d2;
        int r = contact_pair_force(X[j], Y[j], V[j], V[j], X[i], Y[i], V[i], V[i], 1e10, 1e9, 0.3, YF_FRIC_Y2D, 1e-4, g, fa, fb,
                                   &d2, NULL);
        double rems[4] = {0.3, d2 < DBL_MAX ? d2 : 1.0, d2 < DBL_MAX ? nextafter(d2, 0.0) : 2.0,
                          d2 < DBL_MAX ? 4.0 * d2 : 3.0};
        for (int q = 0; q < 4; q++) tally_screen(contact_pair_quiet(rec[j], rec[i], rems[q]), r, fa, fb, g, d2, rems[q], &tl);
      }
  }
  ck_assert_int_eq(tl.bad, 0);
  ck_assert_int_gt(tl.quiet, 10000);
  ck_assert_int_gt(tl.busy, 1000);
  ck_assert_int_gt(tl.dropped, 1000);
}
END_TEST

/* The screen on couples of random shapes (slivers included, heights in a ratio up to ~1e3),
 * placed corner to corner, edge to edge or apart by about the removal distance, plus degenerate
 * (collapsed or inverted) triangles: the decision agrees with the kernel for removal distances
 * around the kernel's dmin2 (the "near" bound's margin of a factor 4 included), a degenerate
 * couple never needs the kernel, and the AVX2 and portable versions agree. */
static void random_tri(double x[3], double y[3], double cx, double cy, double s)
{
  double th = 6.283185307179586 * urand(), el = pow(10.0, -3.0 * urand()); /* elongation */
  double px[3] = {0.0, 1.0, urand()}, py[3] = {0.0, 0.0, el * (0.05 + urand())};
  for (int q = 0; q < 3; q++) {
    x[q] = cx + s * (cos(th) * px[q] - sin(th) * py[q]);
    y[q] = cy + s * (sin(th) * px[q] + cos(th) * py[q]);
  }
}

START_TEST(test_screen_shapes_and_degenerate)
{
  rng_state = 4242;
  int degen = 0, badany = 0;
  Tally tl = {0, 0, 0, 0};
  for (int it = 0; it < 60000; it++) {
    double X[2][3], Y[2][3], V[3] = {0, 0, 0};
    random_tri(X[0], Y[0], 0.0, 0.0, 1.0);
    int mode = it % 4;
    if (mode == 0) { /* B shares a corner of A (nudged) and points away */
      int c = (int)(3 * urand());
      random_tri(X[1], Y[1], X[0][c], Y[0][c], 0.3 + urand());
      double nud = pow(10.0, -10.0 + 9.0 * urand());
      X[1][0] = X[0][c] + nud * (urand() - 0.5); Y[1][0] = Y[0][c] + nud * (urand() - 0.5);
    } else if (mode == 1) { /* B is A's mirror over one of A's edges (an intact mesh's neighbour) */
      int e = (int)(3 * urand()), f = (e + 1) % 3, o = (e + 2) % 3;
      double ex = X[0][f] - X[0][e], ey = Y[0][f] - Y[0][e], t = urand();
      double nx = ey, ny = -ex, h = ((X[0][o] - X[0][e]) * nx + (Y[0][o] - Y[0][e]) * ny) / (nx * nx + ny * ny);
      double nud = pow(10.0, -10.0 + 9.0 * urand());
      X[1][0] = X[0][f] + nud * (urand() - 0.5); Y[1][0] = Y[0][f] + nud * (urand() - 0.5);
      X[1][1] = X[0][e] + nud * (urand() - 0.5); Y[1][1] = Y[0][e] + nud * (urand() - 0.5);
      X[1][2] = X[0][e] + t * ex - (0.2 + urand()) * h * nx; Y[1][2] = Y[0][e] + t * ey - (0.2 + urand()) * h * ny;
    } else { /* B anywhere near A */
      random_tri(X[1], Y[1], 2.0 * (urand() - 0.5), 2.0 * (urand() - 0.5), 0.2 + urand());
    }
    if (it % 97 == 0) { /* collapse B onto a line (D = 0 exactly) */
      X[1][2] = X[1][0]; Y[1][2] = Y[1][0];
      degen++;
    } else if (it % 89 == 0) { /* invert A (clockwise) */
      double t = X[0][1]; X[0][1] = X[0][2]; X[0][2] = t;
      t = Y[0][1]; Y[0][1] = Y[0][2]; Y[0][2] = t;
      degen++;
    }
    int isdeg = it % 97 == 0 || it % 89 == 0;
    int a = it & 1, b = 1 - a; /* either triangle as A */
    double rec[2][YF_TRI_GEOM];
    contact_pair_geom(X[0], Y[0], rec[0]);
    contact_pair_geom(X[1], Y[1], rec[1]);
    double g[6] = {0}, fa[6] = {0}, fb[6] = {0}, d2;
    int r = contact_pair_force(X[a], Y[a], V, V, X[b], Y[b], V, V, 1e10, 1e9, 0.3, YF_FRIC_Y2D, 1e-4, g, fa, fb, &d2, NULL);
    double base = d2 < DBL_MAX ? d2 : 1.0;
    double rems[8] = {0.1 * base, 0.3 * base, 0.6 * base, nextafter(base, 0.0), base, 1.7 * base, 3.5 * base,
                      4.5 * base};
    for (int q = 0; q < 8; q++) {
      int sv = contact_pair_quiet(rec[a], rec[b], rems[q]);
      if (contact_pair_quiet_any(rec[a], rec[b], rems[q]) != sv) badany++;
      if (isdeg && sv == 0) tl.bad++; /* a degenerate couple is settled without the kernel */
      tally_screen(sv, r, fa, fb, g, d2, rems[q], &tl);
    }
  }
  ck_assert_int_eq(tl.bad, 0);
  ck_assert_int_eq(badany, 0);
  ck_assert_int_gt(tl.quiet, 100000);
  ck_assert_int_gt(tl.busy, 10000);
  ck_assert_int_gt(tl.dropped, 50000);
  ck_assert_int_gt(degen, 1000);
}
END_TEST

/* ------------------------------------------------------------------ the kernel as it was */

/* contact_pair_dir as first written (plain scalar code, geometry from the corners), kept
 * verbatim as the reference of the optimised kernel: every force, friction memory, distance
 * and diagnostic must come out with the same bits.  Since 2026-11-29 its diagnostics book the
 * friction force's work at the point where it acts and its spring's energy (contact_pair.c). */
/* P(s) = min_k beta_k(s) at parameter s of the edge. */
static inline double ref_pmin3(const double al[3], const double dl[3], double s)
{
  double b0 = al[0] + s * dl[0], b1 = al[1] + s * dl[1], b2 = al[2] + s * dl[2];
  double p = b0;
  if (b1 < p) p = b1;
  if (b2 < p) p = b2;
  return p;
}

static int ref_dir(const double xt[3], const double yt[3], const double vxt[3], const double vyt[3],
                     const double xc[3], const double yc[3], const double vxc[3], const double vyc[3],
                     double pn, double pt, double mu, double dt, double g[3],
                     double ft[6], double fc[6], double *dmin2, YfContactInfo *info)
{
  /* 6.1: target normals (outward for CCW corners, length = edge length) and twice-area. */
  double D = (xt[1] - xt[0]) * (yt[2] - yt[0]) - (yt[1] - yt[0]) * (xt[2] - xt[0]);
  double Dc = (xc[1] - xc[0]) * (yc[2] - yc[0]) - (yc[1] - yc[0]) * (xc[2] - xc[0]);
  if (!(D > 0.0) || !(Dc > 0.0)) return 0; /* degenerate or inverted: the element check reports it */
  double mx[3], my[3];
  for (int k = 0; k < 3; k++) {
    int k1 = (k + 1) % 3;
    mx[k] = yt[k1] - yt[k];
    my[k] = -(xt[k1] - xt[k]);
  }
  /* beta_k of every contactor node: bn[i][k].  (Multiplying by 1/D instead of dividing by D
   * changes values by an ulp at most; it halves the cost of the common, far-apart couple.) */
  double invD = 1.0 / D;
  double bn[3][3];
  for (int i = 0; i < 3; i++)
    for (int k = 0; k < 3; k++)
      bn[i][k] = ((xt[k] - xc[i]) * mx[k] + (yt[k] - yc[i]) * my[k]) * invD;

  int nforce = 0;
  double hk[3] = {-1.0, -1.0, -1.0}; /* target heights over each edge [m], when first needed */
  double dmin = *dmin2; /* local: no store-to-load chain through the pointer */
  for (int e = 0; e < 3; e++) {
    int a = e, b = e < 2 ? e + 1 : 0;
    const double *al = bn[a], *ga = bn[b];
    double ncx = yc[b] - yc[a], ncy = -(xc[b] - xc[a]); /* contactor edge outward normal, |n_c| = L */

    /* 6.2: skip when both ends are outside one target edge (tested first: it is cheap and
     * settles most couples), or when the edge line does not separate the target's corners:
     * c_m = ((x_a - y_m) . n_c) / Dc is the contactor's barycentric function of this edge at
     * target corner m, positive on the contactor's inner side (compared as c_m Dc vs eps Dc). */
    int skip = (al[0] < YF_CONTACT_EPS && ga[0] < YF_CONTACT_EPS) || (al[1] < YF_CONTACT_EPS && ga[1] < YF_CONTACT_EPS) || (al[2] < YF_CONTACT_EPS && ga[2] < YF_CONTACT_EPS);
    if (!skip) {
      double ep = YF_CONTACT_EPS * Dc;
      int allpos = 1, allneg = 1;
      for (int m = 0; m < 3; m++) {
        double c = (xc[a] - xt[m]) * ncx + (yc[a] - yt[m]) * ncy;
        if (!(c > -ep)) allpos = 0;
        if (!(c < ep)) allneg = 0;
      }
      skip = allpos || allneg;
    }
    if (skip) {
      /* distance^2 of the start node to the line of the target edge with the smallest alpha:
       * alpha^2 / (|m_k|/D)^2, compared without dividing first. */
      int kmin = 0;
      if (al[1] < al[kmin]) kmin = 1;
      if (al[2] < al[kmin]) kmin = 2;
      double m2 = mx[kmin] * mx[kmin] + my[kmin] * my[kmin];
      double num = al[kmin] * al[kmin] * (D * D);
      if (num < dmin * m2) dmin = num / m2;
      continue;
    }

    /* 6.3: contact interval [s_min, s_max] of the edge inside the target. */
    double dl[3];
    double smin = 0.0, smax = 1.0;
    for (int k = 0; k < 3; k++) {
      dl[k] = ga[k] - al[k];
      if (al[k] < 0.0 && ga[k] > YF_CONTACT_EPS) {
        double s = al[k] / (al[k] - ga[k]);
        if (s > smin) smin = s;
      }
      if (al[k] > YF_CONTACT_EPS && ga[k] < 0.0) {
        double s = al[k] / (al[k] - ga[k]);
        if (s < smax) smax = s;
      }
    }
    if (smax <= smin) continue;

    /* Breakpoints: the ends and the kinks of min_k beta_k strictly inside (two lines cross and
     * the third is larger there), sorted. */
    double bs[5];
    int nb = 0;
    bs[nb++] = smin;
    bs[nb++] = smax;
    for (int i = 0; i < 2; i++)
      for (int j = i + 1; j < 3; j++) {
        double den = dl[i] - dl[j];
        if (den == 0.0) continue; /* parallel lines never cross */
        double s = (al[j] - al[i]) / den;
        if (!(s > smin && s < smax)) continue;
        int m = 3 - i - j;
        if (al[m] + s * dl[m] > al[i] + s * dl[i]) bs[nb++] = s;
      }
    for (int i = 1; i < nb; i++) { /* insertion sort of at most 5 values */
      double v = bs[i];
      int j = i - 1;
      while (j >= 0 && bs[j] > v) { bs[j + 1] = bs[j]; j--; }
      bs[j + 1] = v;
    }

    /* Exact integrals of the piecewise-linear P: int P ds and int P s ds. */
    double I0 = 0.0, I1 = 0.0, I2h = 0.0;
    double s1 = bs[0], p1 = ref_pmin3(al, dl, s1);
    for (int i = 1; i < nb; i++) {
      double s2 = bs[i], p2 = ref_pmin3(al, dl, s2), h = s2 - s1;
      I0 += 0.5 * h * (p1 + p2);
      I1 += h * (p1 * (2.0 * s1 + s2) + p2 * (s1 + 2.0 * s2)) / 6.0;
      if (info) { /* energy estimate: 3 int h_k P^2 ds with the active edge k of this piece */
        double sm = 0.5 * (s1 + s2);
        int k = 0;
        double bk = al[0] + sm * dl[0];
        for (int q = 1; q < 3; q++)
          if (al[q] + sm * dl[q] < bk) { bk = al[q] + sm * dl[q]; k = q; }
        if (!(hk[k] >= 0.0)) hk[k] = D / sqrt(mx[k] * mx[k] + my[k] * my[k]); /* once per edge */
        I2h += hk[k] * h * (p1 * p1 + p1 * p2 + p2 * p2);
      }
      s1 = s2;
      p1 = p2;
    }
    I2h /= 3.0;
    double F = 3.0 * pn * I0;
    double Fb = 3.0 * pn * I1;
    double Fa = F - Fb;
    double fax = -Fa * ncx, fay = -Fa * ncy;
    double fbx = -Fb * ncx, fby = -Fb * ncy;

    /* 6.4: friction on the edge. */
    double tcx = xc[b] - xc[a], tcy = yc[b] - yc[a]; /* unnormalised tangent */
    double Ft = 0.0, w = 0.0, slip = 0.0;
    {
      double sbar = 0.0;
      for (int i = 0; i < nb; i++) sbar += bs[i];
      sbar /= nb;
      double vtx = 0.0, vty = 0.0;
      for (int k = 0; k < 3; k++) {
        double bk = al[k] + sbar * dl[k];
        int v = (k + 2) % 3; /* beta_k belongs to target vertex k+2 */
        vtx += bk * vxt[v];
        vty += bk * vyt[v];
      }
      double vcx = (1.0 - sbar) * vxc[a] + sbar * vxc[b];
      double vcy = (1.0 - sbar) * vyc[a] + sbar * vyc[b];
      w = (vtx - vcx) * tcx + (vty - vcy) * tcy;
      g[e] += w * dt;
      Ft = pt * g[e];
      double cap = mu * fabs(F);
      if (fabs(Ft) > cap) {
        double gtrial = g[e];
        Ft = copysign(cap, Ft);
        g[e] = Ft / pt;
        slip = fabs(gtrial - g[e]);
      }
      if (F > 0.0) {
        double wa = Fa / F, wb = Fb / F;
        fax += Ft * wa * tcx;
        fay += Ft * wa * tcy;
        fbx += Ft * wb * tcx;
        fby += Ft * wb * tcy;
        /* the booking's slip rate: where the force acts, s = F_b / F */
        vtx = vty = 0.0;
        for (int k = 0; k < 3; k++) {
          double bk = al[k] + wb * dl[k];
          int v = (k + 2) % 3;
          vtx += bk * vxt[v];
          vty += bk * vyt[v];
        }
        vcx = (1.0 - wb) * vxc[a] + wb * vxc[b];
        vcy = (1.0 - wb) * vyc[a] + wb * vyc[b];
        w = (vtx - vcx) * tcx + (vty - vcy) * tcy;
      } else {
        Ft = 0.0; /* no normal force, nothing to share the tangential force with */
      }
      if (info && pt > 0.0) info->energy += 0.5 * Ft * Ft / pt; /* the spring's energy */
    }

    fc[2 * a] += fax;
    fc[2 * a + 1] += fay;
    fc[2 * b] += fbx;
    fc[2 * b + 1] += fby;
    /* 6.5: reaction; target vertex v carries beta_(v+1) (beta_k belongs to vertex k+2). */
    for (int v = 0; v < 3; v++) {
      int k = (v + 1) % 3;
      ft[2 * v] -= fax * al[k] + fbx * ga[k];
      ft[2 * v + 1] -= fay * al[k] + fby * ga[k];
    }
    nforce++;

    if (info) {
      double L = sqrt(ncx * ncx + ncy * ncy);
      info->nedge++;
      info->fn += fabs(F) * L;
      info->ft += fabs(Ft) * L;
      info->work_t += Ft * w * dt;
      info->dissip += fabs(Ft) * slip;
      info->energy += 1.5 * pn * L * I2h;
    }
  }
  *dmin2 = dmin;
  return nforce;
}

/* Random couples of every kind the kernel branches on (overlapping triangles, mesh neighbours
 * sharing an edge or a corner up to a nudge, slivers, one triangle inside the other, parallel
 * edges), random velocities and friction memories, a few steps each: contact_pair_force and
 * contact_pair_force_rec (AVX2 and portable) give exactly the reference's numbers. */
static void random_couple(int mode, double xa[3], double ya[3], double xb[3], double yb[3])
{
  if (mode == 0) { /* two random CCW triangles near each other */
    for (int q = 0; q < 3; q++) {
      double th = q * 2.0943951023931957 + 0.6 * (urand() - 0.5);
      xa[q] = 0.5 * cos(th) + 0.2 * urand(); ya[q] = 0.5 * sin(th) + 0.2 * urand();
      th = q * 2.0943951023931957 + 0.6 * (urand() - 0.5);
      xb[q] = 0.6 + 0.5 * cos(th) + 0.4 * (urand() - 0.5); yb[q] = 0.5 * sin(th) + 0.4 * (urand() - 0.5);
    }
  } else if (mode == 1) { /* the two triangles of a cell, nudged by 1e-12 .. 1e-1 */
    double e = pow(10.0, -12.0 + 11.0 * urand());
    xa[0] = 0; ya[0] = 0; xa[1] = 1; ya[1] = 0; xa[2] = 1; ya[2] = 1;
    xb[0] = 0; yb[0] = 0; xb[1] = 1; yb[1] = 1; xb[2] = 0; yb[2] = 1;
    for (int q = 0; q < 3; q++) {
      xb[q] += e * (urand() - 0.5); yb[q] += e * (urand() - 0.5);
      xa[q] += e * (urand() - 0.5); ya[q] += e * (urand() - 0.5);
    }
  } else if (mode == 2) { /* random shapes (slivers too) anywhere near each other */
    random_tri(xa, ya, 0.0, 0.0, 1.0);
    random_tri(xb, yb, 1.2 * (urand() - 0.5), 1.2 * (urand() - 0.5), 0.2 + urand());
  } else if (mode == 3) { /* B small, inside or across A */
    random_tri(xa, ya, 0.0, 0.0, 1.0);
    random_tri(xb, yb, 0.3 + 0.4 * urand(), 0.1 * urand(), 0.05 + 0.3 * urand());
  } else { /* corners on a grid: parallel edges, shared corners, exact zeros */
    for (int q = 0; q < 3; q++) {
      xa[q] = (double)(int)(4 * urand()) * 0.25; ya[q] = (double)(int)(4 * urand()) * 0.25;
      xb[q] = (double)(int)(4 * urand()) * 0.25; yb[q] = (double)(int)(4 * urand()) * 0.25;
    }
  }
}

static int same_bits(double a, double b) { return memcmp(&a, &b, sizeof a) == 0; }

START_TEST(test_kernel_matches_reference)
{
  rng_state = 2718;
  int bad = 0, forced = 0, sliding = 0;
  for (int it = 0; it < 200000; it++) {
    double xa[3], ya[3], xb[3], yb[3], vxa[3], vya[3], vxb[3], vyb[3];
    random_couple(it % 5, xa, ya, xb, yb);
    double vs = pow(10.0, -3.0 + 4.0 * urand());
    for (int q = 0; q < 3; q++) {
      vxa[q] = vs * (urand() - 0.5); vya[q] = vs * (urand() - 0.5);
      vxb[q] = vs * (urand() - 0.5); vyb[q] = vs * (urand() - 0.5);
    }
    double pn = 1e10, pt = urand() < 0.2 ? 0.0 : 1e9, mu = urand() < 0.2 ? 0.0 : 0.5 * urand(), dt = 1e-4;
    double g0[6];
    for (int q = 0; q < 6; q++) g0[q] = urand() < 0.5 ? 0.0 : 1e-5 * (urand() - 0.5);
    double gr[6], g1[6], g2[6];
    memcpy(gr, g0, sizeof g0); memcpy(g1, g0, sizeof g0); memcpy(g2, g0, sizeof g0);
    for (int step = 0; step < 2; step++) {
      double far[6] = {0}, fbr[6] = {0}, fa1[6] = {0}, fb1[6] = {0}, fa2[6] = {0}, fb2[6] = {0};
      double dr = DBL_MAX, d1, d2;
      YfContactInfo ir = {0}, i1 = ir, i2 = ir;
      int nr = ref_dir(xa, ya, vxa, vya, xb, yb, vxb, vyb, pn, pt, mu, dt, gr, far, fbr, &dr, &ir);
      nr += ref_dir(xb, yb, vxb, vyb, xa, ya, vxa, vya, pn, pt, mu, dt, gr + 3, fbr, far, &dr, &ir);
      int r1 = contact_pair_force(xa, ya, vxa, vya, xb, yb, vxb, vyb, pn, pt, mu, YF_FRIC_Y2D, dt, g1, fa1, fb1, &d1, &i1);
      double ra[YF_TRI_GEOM], rb[YF_TRI_GEOM];
      contact_pair_geom(xa, ya, ra);
      contact_pair_geom(xb, yb, rb);
      int r2 = (it & 1 ? contact_pair_force_rec : contact_pair_force_rec_any)(ra, vxa, vya, rb, vxb, vyb, pn, pt, mu, YF_FRIC_Y2D,
                                                                             dt, g2, fa2, fb2, &d2, step ? &i2 : NULL);
      if (!step) i2 = ir;
      if (r1 != (nr > 0) || r2 != (nr > 0) || !same_bits(d1, dr) || !same_bits(d2, dr)) bad++;
      for (int q = 0; q < 6; q++)
        if (!same_bits(fa1[q], far[q]) || !same_bits(fb1[q], fbr[q]) || !same_bits(g1[q], gr[q]) ||
            !same_bits(fa2[q], far[q]) || !same_bits(fb2[q], fbr[q]) || !same_bits(g2[q], gr[q]))
          bad++;
      const YfContactInfo *in[2] = {&i1, &i2};
      for (int q = 0; q < 2; q++)
        if (in[q]->nedge != ir.nedge || !same_bits(in[q]->fn, ir.fn) || !same_bits(in[q]->ft, ir.ft) ||
            !same_bits(in[q]->work_t, ir.work_t) || !same_bits(in[q]->dissip, ir.dissip) ||
            !(fabs(in[q]->energy - ir.energy) <= 1e-12 * fabs(ir.energy)))
          bad++;
      forced += ir.nedge;
      sliding += ir.dissip > 0.0;
    }
  }
  ck_assert_int_eq(bad, 0);
  ck_assert_int_gt(forced, 100000);
  ck_assert_int_gt(sliding, 10000);
}
END_TEST

Suite *contact_pair_suite(void)
{
  Suite *s = suite_create("contact_pair");
  TCase *tc = tcase_create("normal");
  tcase_add_test(tc, test_flat_exact_integral);
  tcase_add_test(tc, test_flat_depth_sweep);
  tcase_add_test(tc, test_separated);
  suite_add_tcase(s, tc);
  tc = tcase_create("pair");
  tcase_add_test(tc, test_conservation);
  tcase_add_test(tc, test_monotonic_symmetric);
  tcase_add_test(tc, test_random_pairs_conserve);
  tcase_add_test(tc, test_screen_matches_kernel);
  tcase_add_test(tc, test_screen_shapes_and_degenerate);
  tcase_add_test(tc, test_kernel_matches_reference);
  suite_add_tcase(s, tc);
  tc = tcase_create("friction");
  tcase_add_test(tc, test_friction_stick_then_slide);
  tcase_add_test(tc, test_friction_mu_zero);
  tcase_add_test(tc, test_friction_sbar_is_breakpoint_mean);
  suite_add_tcase(s, tc);
  tc = tcase_create("search");
  tcase_set_timeout(tc, 60);
  tcase_add_test(tc, test_search_equals_brute_force);
  tcase_add_test(tc, test_search_merge_chunks_match_serial);
  tcase_add_test(tc, test_search_filters_and_threads);
  tcase_add_test(tc, test_search_merge_keeps_friction);
  tcase_add_test(tc, test_search_large_sampled);
  tcase_add_test(tc, test_trigger);
  suite_add_tcase(s, tc);
  return s;
}
