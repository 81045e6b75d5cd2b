/* elem_tri.c: the constant-strain triangle of Munjiza's FDEM, as Y2D computes it.
 *
 * ALGORITHMS.md 2: F = x_e X_e^-1 from initial and current edge matrices, L = v_e x_e^-1,
 * D = (L + L^T)/2, E = (F F^T - I)/2, Cauchy stress T = (2 mu/J) E + k D + volfac lambda (J - 1/J) I,
 * nodal force f_i = T n_i / 2 with n_i the outward normal (length = edge length) of the edge
 * opposite node i.  The kernels write per-triangle corner forces (tri.cf) instead of adding into
 * nodes, so that any number of threads can run them; run.c gathers them into nodes in a fixed
 * order (bitwise-identical results for any thread count).
 */
#include <math.h>
#include <stddef.h>
#include "elem_tri.h"
#include "yfvec.h"

int tri_prepare(YfModel *m, const YfTriMat *tm) {
  YfTris *t = &m->tri;
  const double *X = m->node.x0, *Y = m->node.y0;
  int bad = -1;
  for (int e = 0; e < t->n; e++) {
    const int *v = t->v + 3 * e;
    double a = X[v[1]] - X[v[0]], b = X[v[2]] - X[v[0]];
    double c = Y[v[1]] - Y[v[0]], d = Y[v[2]] - Y[v[0]];
    double det = a * d - b * c; /* X_e = [[a b],[c d]] */
    t->d0[e] = det;
    if (!(det > 0.0)) {
      if (bad < 0) bad = e;
      det = 1.0;
    }
    double *xi = t->xinv + 4 * e;
    xi[0] = d / det; xi[1] = -b / det; xi[2] = -c / det; xi[3] = a / det;
    double mc = tm[t->mat[e]].rho * t->d0[e] / 6.0;
    m->node.m[v[0]] += mc;
    m->node.m[v[1]] += mc;
    m->node.m[v[2]] += mc;
  }
  return bad;
}

/* Cauchy stress T (sxx, syy, sxy) of one triangle; returns J.  *dd = A_c D:D. */
static inline double tri_stress(const double *x, const double *y, const double *vx, const double *vy,
                                const int *v, const double *xi, double d0, const YfTriMat *mt,
                                double T[3], double *dd) {
  double x1 = x[v[1]] - x[v[0]], x2 = x[v[2]] - x[v[0]];
  double y1 = y[v[1]] - y[v[0]], y2 = y[v[2]] - y[v[0]];
  /* F = x_e X_e^-1, x_e = [[x1 x2],[y1 y2]] */
  double F11 = x1 * xi[0] + x2 * xi[2], F12 = x1 * xi[1] + x2 * xi[3];
  double F21 = y1 * xi[0] + y2 * xi[2], F22 = y1 * xi[1] + y2 * xi[3];
  double dc = x1 * y2 - x2 * y1;
  double idc = 1.0 / dc; /* one division per triangle: J = dc/d0, 1/J = d0/dc */
  double J = dc / d0;
  /* E = (F F^T - I)/2 */
  double E11 = 0.5 * (F11 * F11 + F12 * F12 - 1.0);
  double E22 = 0.5 * (F21 * F21 + F22 * F22 - 1.0);
  double E12 = 0.5 * (F11 * F21 + F12 * F22);
  double iJ = d0 * idc;
  double a = mt->mu2 * iJ;
  double vol = mt->lamv * (J - iJ);
  double s11 = a * E11 + vol, s22 = a * E22 + vol, s12 = a * E12;
  double D11 = 0, D22 = 0, D12 = 0;
  if (mt->k != 0.0) {
    /* L = v_e x_e^-1; x_e^-1 = [[y2 -x2],[-y1 x1]] / dc */
    double u1 = vx[v[1]] - vx[v[0]], u2 = vx[v[2]] - vx[v[0]];
    double w1 = vy[v[1]] - vy[v[0]], w2 = vy[v[2]] - vy[v[0]];
    double L11 = (u1 * y2 - u2 * y1) * idc, L12 = (-u1 * x2 + u2 * x1) * idc;
    double L21 = (w1 * y2 - w2 * y1) * idc, L22 = (-w1 * x2 + w2 * x1) * idc;
    D11 = L11; D22 = L22; D12 = 0.5 * (L12 + L21);
    s11 += mt->k * D11; s22 += mt->k * D22; s12 += mt->k * D12;
  }
  if (dd) *dd = (D11 * D11 + D22 * D22 + 2.0 * D12 * D12) * 0.5 * dc;
  T[0] = s11; T[1] = s22; T[2] = s12;
  return J;
}

/* One triangle, scalar: the reference arithmetic of the kernel (the tail of a range and any range
 * of fewer than 4 triangles). */
static inline void tri_one(const double *x, const double *y, const double *vx, const double *vy, YfTris *t,
                           const YfTriMat *tm, int e, double *J, double *kdd) {
  const int *v = t->v + 3 * e;
  const YfTriMat *mt = tm + t->mat[e];
  double T[3], dd = 0.0;
  *J = tri_stress(x, y, vx, vy, v, t->xinv + 4 * e, t->d0[e], mt, T, &dd);
  *kdd = mt->k * dd;
  double *s = t->s + 3 * e;
  s[0] = T[0]; s[1] = T[1]; s[2] = T[2];
  double *cf = t->cf + 6 * e;
  for (int i = 0; i < 3; i++) {
    int j = v[(i + 1) % 3], k = v[(i + 2) % 3];
    double nx = y[k] - y[j], ny = x[j] - x[k];
    cf[2 * i] = 0.5 * (T[0] * nx + T[2] * ny);
    cf[2 * i + 1] = 0.5 * (T[2] * nx + T[1] * ny);
  }
}

/* Four triangles e..e+3 at once, one per lane of a 4-wide vector (GCC vector extensions: one AVX
 * register where the CPU has it, two SSE2 halves otherwise).  Every lane does tri_stress's and
 * tri_one's operations in their order (no FMA: -ffp-contract=off), so each triangle gets the bits
 * of the scalar code; lanes whose material has k = 0 keep D = 0 and the stress without k D, as
 * the scalar branch does.  tests/check_physics.c compares the two triangle by triangle. */
typedef double v4d __attribute__((vector_size(32)));
typedef long long v4l __attribute__((vector_size(32)));
#define LANES(expr) {expr(0), expr(1), expr(2), expr(3)}
#define BLEND(msk, u, w) ((v4d)(((msk) & (v4l)(u)) | (~(msk) & (v4l)(w))))

static inline __attribute__((always_inline)) void tri_four(const double *x, const double *y, const double *vx, const double *vy, YfTris *t,
                            const YfTriMat *tm, int e, double J[4], double kdd[4]) {
  const int *v = t->v + 3 * e;
  const YfTriMat *m0 = tm + t->mat[e], *m1 = tm + t->mat[e + 1], *m2 = tm + t->mat[e + 2], *m3 = tm + t->mat[e + 3];
  const double *xi = t->xinv + 4 * e, *d0p = t->d0 + e;
#define N(a, c, l) a[v[3 * (l) + (c)]]
#define X0(l) N(x, 0, l)
#define X1(l) N(x, 1, l)
#define X2(l) N(x, 2, l)
#define Y0(l) N(y, 0, l)
#define Y1(l) N(y, 1, l)
#define Y2(l) N(y, 2, l)
  const v4d ax0 = LANES(X0), ax1 = LANES(X1), ax2 = LANES(X2);
  const v4d ay0 = LANES(Y0), ay1 = LANES(Y1), ay2 = LANES(Y2);
#define XI(c) (v4d){xi[c], xi[4 + (c)], xi[8 + (c)], xi[12 + (c)]}
  const v4d xi0 = XI(0), xi1 = XI(1), xi2 = XI(2), xi3 = XI(3);
  const v4d d0 = {d0p[0], d0p[1], d0p[2], d0p[3]};
  const v4d mu2 = {m0->mu2, m1->mu2, m2->mu2, m3->mu2}, lamv = {m0->lamv, m1->lamv, m2->lamv, m3->lamv};
  const v4d kv = {m0->k, m1->k, m2->k, m3->k};
  /* tri_stress */
  v4d x1 = ax1 - ax0, x2 = ax2 - ax0, y1 = ay1 - ay0, y2 = ay2 - ay0;
  v4d F11 = x1 * xi0 + x2 * xi2, F12 = x1 * xi1 + x2 * xi3;
  v4d F21 = y1 * xi0 + y2 * xi2, F22 = y1 * xi1 + y2 * xi3;
  v4d dc = x1 * y2 - x2 * y1;
  v4d idc = 1.0 / dc;
  v4d Jv = dc / d0;
  v4d E11 = 0.5 * (F11 * F11 + F12 * F12 - 1.0);
  v4d E22 = 0.5 * (F21 * F21 + F22 * F22 - 1.0);
  v4d E12 = 0.5 * (F11 * F21 + F12 * F22);
  v4d iJ = d0 * idc;
  v4d a = mu2 * iJ;
  v4d vol = lamv * (Jv - iJ);
  v4d s11 = a * E11 + vol, s22 = a * E22 + vol, s12 = a * E12;
  v4d D11 = {0, 0, 0, 0}, D22 = D11, D12 = D11;
  v4l visc = kv != 0.0;
  if (visc[0] | visc[1] | visc[2] | visc[3]) {
#define U(c, l) N(vx, c, l)
#define W(c, l) N(vy, c, l)
#define U0(l) U(0, l)
#define U1(l) U(1, l)
#define U2(l) U(2, l)
#define W0(l) W(0, l)
#define W1(l) W(1, l)
#define W2(l) W(2, l)
    const v4d au0 = LANES(U0), au1 = LANES(U1), au2 = LANES(U2), aw0 = LANES(W0), aw1 = LANES(W1), aw2 = LANES(W2);
    v4d u1 = au1 - au0, u2 = au2 - au0, w1 = aw1 - aw0, w2 = aw2 - aw0;
    v4d L11 = (u1 * y2 - u2 * y1) * idc, L12 = (-u1 * x2 + u2 * x1) * idc;
    v4d L21 = (w1 * y2 - w2 * y1) * idc, L22 = (-w1 * x2 + w2 * x1) * idc;
    D11 = BLEND(visc, L11, D11);
    D22 = BLEND(visc, L22, D22);
    D12 = BLEND(visc, 0.5 * (L12 + L21), D12);
    s11 = BLEND(visc, s11 + kv * D11, s11);
    s22 = BLEND(visc, s22 + kv * D22, s22);
    s12 = BLEND(visc, s12 + kv * D12, s12);
  }
  v4d dd = (D11 * D11 + D22 * D22 + 2.0 * D12 * D12) * 0.5 * dc;
  v4d kd = kv * dd;
  /* corner forces: corner i gets half the stress times the normal of the opposite edge (j, k) */
  v4d fx0 = 0.5 * (s11 * (ay2 - ay1) + s12 * (ax1 - ax2)), fy0 = 0.5 * (s12 * (ay2 - ay1) + s22 * (ax1 - ax2));
  v4d fx1 = 0.5 * (s11 * (ay0 - ay2) + s12 * (ax2 - ax0)), fy1 = 0.5 * (s12 * (ay0 - ay2) + s22 * (ax2 - ax0));
  v4d fx2 = 0.5 * (s11 * (ay1 - ay0) + s12 * (ax0 - ax1)), fy2 = 0.5 * (s12 * (ay1 - ay0) + s22 * (ax0 - ax1));
  for (int l = 0; l < 4; l++) {
    double *s = t->s + 3 * (e + l), *cf = t->cf + 6 * (e + l);
    s[0] = s11[l]; s[1] = s22[l]; s[2] = s12[l];
    cf[0] = fx0[l]; cf[1] = fy0[l]; cf[2] = fx1[l]; cf[3] = fy1[l]; cf[4] = fx2[l]; cf[5] = fy2[l];
    J[l] = Jv[l];
    kdd[l] = kd[l];
  }
}

YF_CLONES
void tri_forces(YfModel *m, const YfTriMat *tm, int e0, int e1, YfTriPass *out) {
  const double *x = m->node.x, *y = m->node.y, *vx = m->node.vx, *vy = m->node.vy;
  YfTris *t = &m->tri;
  int bad = -1;
  double badJ = 0.0, power = 0.0;
  const double *s = t->s;
  int e = e0;
  for (; e + 4 <= e1; e += 4) {
    double J[4], kdd[4];
    tri_four(x, y, vx, vy, t, tm, e, J, kdd);
    for (int l = 0; l < 4; l++) { /* in triangle order, as the scalar loop */
      const double *T = s + 3 * (e + l);
      if (!(J[l] > 0.0) || !isfinite(T[0] + T[1] + T[2])) {
        if (bad < 0) { bad = e + l; badJ = J[l]; }
      }
      power += kdd[l];
    }
  }
  for (; e < e1; e++) {
    double J, kdd;
    tri_one(x, y, vx, vy, t, tm, e, &J, &kdd);
    const double *T = s + 3 * e;
    if (!(J > 0.0) || !isfinite(T[0] + T[1] + T[2])) {
      if (bad < 0) { bad = e; badJ = J; }
    }
    power += kdd;
  }
  out->bad = bad;
  out->badJ = badJ;
  out->visc_power = power;
}

/* Triangle e's deformation gradient F = (F11 F12; F21 F22) at the current positions, and twice
 * its current area dc. */
static inline void tri_gradient(const YfModel *m, int e, double F[4], double *dc) {
  const double *x = m->node.x, *y = m->node.y;
  const int *v = m->tri.v + 3 * e;
  const double *xi = m->tri.xinv + 4 * e;
  double x1 = x[v[1]] - x[v[0]], x2 = x[v[2]] - x[v[0]];
  double y1 = y[v[1]] - y[v[0]], y2 = y[v[2]] - y[v[0]];
  F[0] = x1 * xi[0] + x2 * xi[2];
  F[1] = x1 * xi[1] + x2 * xi[3];
  F[2] = y1 * xi[0] + y2 * xi[2];
  F[3] = y1 * xi[1] + y2 * xi[3];
  *dc = x1 * y2 - x2 * y1;
}

double tri_strain_energy(const YfModel *m, const YfTriMat *tm, int e0, int e1) {
  const YfTris *t = &m->tri;
  double sum = 0.0;
  for (int e = e0; e < e1; e++) {
    double F[4], dc;
    tri_gradient(m, e, F, &dc);
    const double F11 = F[0], F12 = F[1], F21 = F[2], F22 = F[3], J = dc / t->d0[e];
    double E11 = 0.5 * (F11 * F11 + F12 * F12 - 1.0), E22 = 0.5 * (F21 * F21 + F22 * F22 - 1.0);
    double E12 = 0.5 * (F11 * F21 + F12 * F22);
    const YfTriMat *mt = tm + t->mat[e];
    double a = mt->mu2 / J, vol = mt->lamv * (J - 1.0 / J);
    double TE = (a * E11 + vol) * E11 + (a * E22 + vol) * E22 + 2.0 * a * E12 * E12;
    sum += 0.25 * dc * TE; /* A_c/2 T:E with A_c = dc/2 */
  }
  return sum;
}

/* j - log(1 + j) >= 0 without cancellation: its series below |j| = 0.05 (terms to j^16, below
 * 1e-17 of the first), log1p above. */
static double j_minus_log1p(double j) {
  if (fabs(j) >= 0.05) return j - log1p(j);
  double s = 0.0;
  for (int k = 16; k >= 2; k--) s = (k & 1 ? -1.0 : 1.0) / k + j * s;
  return j * j * s;
}

double tri_strain_potential(const YfModel *m, const YfTriMat *tm, int e0, int e1) {
  const YfTris *t = &m->tri;
  double sum = 0.0;
  for (int e = e0; e < e1; e++) {
    double F[4], dc;
    tri_gradient(m, e, F, &dc);
    const double F11 = F[0], F12 = F[1], F21 = F[2], F22 = F[3], j = (dc - t->d0[e]) / t->d0[e]; /* J - 1 */
    const YfTriMat *mt = tm + t->mat[e];
    double mu = 0.5 * mt->mu2, lv = mt->lamv;
    /* mu/2 (|F|^2 - 2) - mu ln J = mu/2 ((F11 - F22)^2 + (F12 + F21)^2) + mu (J - 1 - ln J) */
    double dev = (F11 - F22) * (F11 - F22) + (F12 + F21) * (F12 + F21);
    double w = 0.5 * mu * dev + (mu + lv) * j_minus_log1p(j) + 0.5 * lv * j * j;
    sum += 0.5 * t->d0[e] * w; /* per reference area A0 = d0/2 */
  }
  return sum;
}

double tri_omega_max(const YfModel *m, const YfTriMat *tm, int e) {
  /* Linearised element: K_e = A B^T C B, M_e = (rho A / 3) I.  The non-zero eigenvalues of
   * B^T C B are those of the 3x3 product C G with G = B B^T, so omega_max^2 = 3 lmax(C G)/rho. */
  const int *v = m->tri.v + 3 * e;
  const double *X = m->node.x0, *Y = m->node.y0;
  double A2 = m->tri.d0[e];
  if (!(A2 > 0)) return -1.0;
  double b[3], c[3];
  for (int i = 0; i < 3; i++) {
    int j = v[(i + 1) % 3], k = v[(i + 2) % 3];
    b[i] = (Y[j] - Y[k]) / A2;
    c[i] = (X[k] - X[j]) / A2;
  }
  /* B rows: [b0 0 b1 0 b2 0], [0 c0 0 c1 0 c2], [c0 b0 c1 b1 c2 b2] */
  double G[3][3];
  double bb = b[0] * b[0] + b[1] * b[1] + b[2] * b[2], cc = c[0] * c[0] + c[1] * c[1] + c[2] * c[2];
  double bc = b[0] * c[0] + b[1] * c[1] + b[2] * c[2];
  G[0][0] = bb; G[0][1] = 0; G[0][2] = bc;
  G[1][0] = 0; G[1][1] = cc; G[1][2] = bc;
  G[2][0] = bc; G[2][1] = bc; G[2][2] = bb + cc;
  const YfTriMat *mt = tm + m->tri.mat[e];
  double mu = 0.5 * mt->mu2, lam = 2.0 * mt->lamv; /* small-strain Lame of the law */
  double C[3][3] = {{lam + 2 * mu, lam, 0}, {lam, lam + 2 * mu, 0}, {0, 0, mu}};
  double P[3][3];
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) P[i][j] = C[i][0] * G[0][j] + C[i][1] * G[1][j] + C[i][2] * G[2][j];
  /* Largest eigenvalue of P (similar to a symmetric PSD matrix): power iteration, then a
   * Gershgorin-free safety: use the Rayleigh-type estimate converged to 1e-12. */
  double q[3] = {1, 0.7, 0.3}, lmax = 0;
  for (int it = 0; it < 200; it++) {
    double r[3];
    for (int i = 0; i < 3; i++) r[i] = P[i][0] * q[0] + P[i][1] * q[1] + P[i][2] * q[2];
    double nr = fabs(r[0]) + fabs(r[1]) + fabs(r[2]);
    if (nr == 0) break;
    double lnew = nr / (fabs(q[0]) + fabs(q[1]) + fabs(q[2]));
    for (int i = 0; i < 3; i++) q[i] = r[i] / nr;
    if (fabs(lnew - lmax) <= 1e-13 * lnew) { lmax = lnew; break; }
    lmax = lnew;
  }
  double w = sqrt(3.0 * lmax / mt->rho);
  /* rho 1e-300: the quotient overflows though omega does not (1e156 rad/s); the split form is
   * used only then, so every finite limit keeps its bits */
  if (!isfinite(w) && isfinite(lmax)) w = sqrt(3.0 * lmax) / sqrt(mt->rho);
  return w;
}

double tri_dt_of_omega(double w, const YfTriMat *mt) {
  if (w < 0) return 0.0; /* degenerate triangle */
  if (isnan(w) || isinf(w)) return 0.0; /* beyond a double: no step is stable enough */
  if (!(w > 0)) return INFINITY;
  double mu = 0.5 * mt->mu2, lam = 2.0 * mt->lamv; /* small-strain Lame of the law */
  /* Viscous term: damping ratio of the highest mode xi = w k / (2 (lam + 2 mu)); central
   * differences are stable for dt <= (2/w)(sqrt(1 + xi^2) - xi). */
  double xi = w * mt->k / (2.0 * (lam + 2.0 * mu));
  return 2.0 / w * tri_visc_factor(xi);
}

double tri_visc_factor(double xi) {
  double r = sqrt(1.0 + xi * xi) - xi;
  /* xi above 1e154 (D1PEKS 1e300): xi^2 overflows and the difference is inf - inf; the same
   * number as 1 / (sqrt(1 + xi^2) + xi), used only then, so every finite limit keeps its bits */
  if (!(r > 0) || !isfinite(r)) r = isfinite(xi) ? 1.0 / (hypot(1.0, xi) + xi) : 0.0;
  return r;
}

double tri_stable_dt(const YfModel *m, const YfTriMat *tm, int e) {
  return tri_dt_of_omega(tri_omega_max(m, tm, e), tm + m->tri.mat[e]);
}
