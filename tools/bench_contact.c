/* bench_contact.c: throughput of the contact kernels (contact_search.c, contact_pair.c).
 *
 * Scene: an NX x NY block of squares (edge h = 1 cm), two triangles per square, every triangle
 * with its own nodes (as a fully jointed Y2D body), nodes jittered by +-1 % of h (argument 2:
 * the jitter range as a fraction of h, default 0.02) so that neighbours overlap a little;
 * buffer = 0.2 h.  With jitter 0 the triangles touch exactly along shared edges, as an intact
 * jointed Y2D body at step 0.  For 1e4, 1e5 and 1e6 triangles it prints the
 * broad-phase time (search + friction-memory merge) and the narrow-phase time over all
 * candidate couples, with the thread count of OMP_NUM_THREADS for the search (the narrow-phase
 * loop here is serial: it measures the kernel, timed in process CPU time).
 *
 *   gcc -std=c11 -D_GNU_SOURCE -fopenmp -ffp-contract=off -O2 -Isrc/base -Isrc/kernel \
 *       tools/bench_contact.c src/kernel/contact_search.c src/kernel/contact_pair.c src/base/err.c \
 *       -lm -o bench_contact
 *   OMP_NUM_THREADS=1 ./bench_contact [max_triangles [jitter]]
 */
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "contact_pair.h"
#include "contact_search.h"

static double now(void)
{
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return t.tv_sec + 1e-9 * t.tv_nsec;
}
/* CPU time of this process: the serial narrow-phase loop is timed with it, so that other load on
 * a shared machine does not count. */
static double cpu(void)
{
  struct timespec t;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return t.tv_sec + 1e-9 * t.tv_nsec;
}

static uint64_t rs = 42;
static double urand(void)
{
  rs = rs * 6364136223846793005ULL + 1442695040888963407ULL;
  return (double)(rs >> 11) * (1.0 / 9007199254740992.0);
}

static void run(int ntri_target, double jitter)
{
  const double h = 0.01, buffer = 0.2 * h;
  int nx = (int)sqrt(ntri_target / 2.0), ny = ntri_target / (2 * nx);
  int nt = 2 * nx * ny, nn = 3 * nt;
  double *x = malloc(nn * sizeof *x), *y = malloc(nn * sizeof *y);
  double *vx = calloc(nn, sizeof *vx), *vy = calloc(nn, sizeof *vy);
  double *fx = calloc(nn, sizeof *fx), *fy = calloc(nn, sizeof *fy);
  int *tv = malloc(3 * (size_t)nt * sizeof *tv);
  double *cx = malloc(nt * sizeof *cx), *cy = malloc(nt * sizeof *cy), *r = malloc(nt * sizeof *r);
  int t = 0;
  for (int j = 0; j < ny; j++)
    for (int i = 0; i < nx; i++) {
      double X[4] = {i * h, (i + 1) * h, (i + 1) * h, i * h}, Y[4] = {j * h, j * h, (j + 1) * h, (j + 1) * h};
      const int c[2][3] = {{0, 1, 2}, {0, 2, 3}};
      for (int k = 0; k < 2; k++, t++)
        for (int q = 0; q < 3; q++) {
          int n = 3 * t + q;
          x[n] = X[c[k][q]] + jitter * h * (urand() - 0.5);
          y[n] = Y[c[k][q]] + jitter * h * (urand() - 0.5);
          vx[n] = 0.1 * (urand() - 0.5);
          vy[n] = 0.1 * (urand() - 0.5);
          tv[3 * t + q] = n;
        }
    }

  YfSearchWork w;
  contact_search_work_init(&w);
  YfPairs old, p;
  contact_pairs_init(&old);
  contact_pairs_init(&p);
  /* warm-up: grows the workspace and both lists */
  contact_search_bounds(nt, NULL, tv, x, y, cx, cy, r);
  contact_search(&w, nt, NULL, cx, cy, r, buffer, NULL, &old);
  for (int k = 0; k < old.n; k++) old.gi[k] = -1; /* no friction memory yet */
  contact_search(&w, nt, NULL, cx, cy, r, buffer, NULL, &p);

  int reps = nt >= 1000000 ? 3 : nt >= 100000 ? 10 : 50;
  double tb = 0, ts = 0, tm = 0;
  for (int k = 0; k < reps; k++) {
    double t0 = now();
    contact_search_bounds(nt, NULL, tv, x, y, cx, cy, r);
    double t1 = now();
    contact_search(&w, nt, NULL, cx, cy, r, buffer, NULL, &p);
    double t2 = now();
    contact_search_merge(&old, &p);
    double t3 = now();
    tb += (t1 - t0) / reps;
    ts += (t2 - t1) / reps;
    tm += (t3 - t2) / reps;
  }

  /* Narrow phase over all couples, serial, forces gathered into the node arrays. */
  int nreps = nt >= 1000000 ? 1 : nt >= 100000 ? 3 : 20;
  long touching = 0;
  YfContactInfo info = {0};
  double *gm = calloc((size_t)p.n * 6 + 1, sizeof *gm); /* friction memory, 6 per couple */
  double t0 = cpu();
  for (int k = 0; k < nreps; k++) {
    for (int c = 0; c < p.n; c++) {
      int a = p.ij[2 * c + 1], b = p.ij[2 * c]; /* A = larger index, as Y2D */
      const int *va = tv + 3 * (size_t)a, *vb = tv + 3 * (size_t)b;
      double xa[3], ya[3], vxa[3], vya[3], xb[3], yb[3], vxb[3], vyb[3], fa[6] = {0}, fb[6] = {0}, d2;
      for (int q = 0; q < 3; q++) {
        xa[q] = x[va[q]]; ya[q] = y[va[q]]; vxa[q] = vx[va[q]]; vya[q] = vy[va[q]];
        xb[q] = x[vb[q]]; yb[q] = y[vb[q]]; vxb[q] = vx[vb[q]]; vyb[q] = vy[vb[q]];
      }
      touching += contact_pair_force(xa, ya, vxa, vya, xb, yb, vxb, vyb, 1e10, 1e10, 0.5, YF_FRIC_Y2D, 1e-7,
                                     gm + 6 * (size_t)c, fa, fb, &d2, k == 0 ? &info : NULL);
      for (int q = 0; q < 3; q++) {
        fx[va[q]] += fa[2 * q]; fy[va[q]] += fa[2 * q + 1];
        fx[vb[q]] += fb[2 * q]; fy[vb[q]] += fb[2 * q + 1];
      }
    }
  }
  double tn = (cpu() - t0) / nreps;
  printf("%8d tris %9d couples (%.1f/tri, %.1f tested/tri, %2d%% touching) | bounds %7.2f ms, search "
         "%7.2f ms = %5.2f M tris/s = %5.1f M couples/s, merge %7.2f ms | narrow (cpu) %8.2f ms = "
         "%5.2f M couples/s\n",
         nt, p.n, (double)p.n / nt, (double)w.tested / nt, (int)(100.0 * touching / nreps / p.n), tb * 1e3,
         ts * 1e3, nt / ts * 1e-6, p.n / ts * 1e-6, tm * 1e3, tn * 1e3, p.n / tn * 1e-6);
  free(gm);
  contact_pairs_free(&old);
  contact_pairs_free(&p);
  contact_search_work_free(&w);
  free(x); free(y); free(vx); free(vy); free(fx); free(fy); free(tv); free(cx); free(cy); free(r);
}

int main(int argc, char **argv)
{
  int nmax = argc > 1 ? atoi(argv[1]) : 1000000;
  double jitter = argc > 2 ? atof(argv[2]) : 0.02;
  for (int n = 10000; n <= nmax; n *= 10) run(n, jitter);
  return 0;
}
