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

void tri_forces(YfModel *m, const YfTriMat *tm, int e0, int e1, YfTriPass *out) {
  const double *x = m->node.x, *y = m->node.y, *vx = m->node.vx, *vy = m->node.vy;
  YfTris *t = &m->tri;
  int bad = -1;
  double badJ = 0.0, power = 0.0;
  for (int e = e0; e < e1; e++) {
    const int *v = t->v + 3 * e;
    const YfTriMat *mt = tm + t->mat[e];
    double T[3], dd = 0.0;
    double J = tri_stress(x, y, vx, vy, v, t->xinv + 4 * e, t->d0[e], mt, T, &dd);
    if (!(J > 0.0) || !isfinite(T[0] + T[1] + T[2])) {
      if (bad < 0) { bad = e; badJ = J; }
    }
    power += mt->k * dd;
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
  out->bad = bad;
  out->badJ = badJ;
  out->visc_power = power;
}

double tri_strain_energy(const YfModel *m, const YfTriMat *tm, int e0, int e1) {
  const double *x = m->node.x, *y = m->node.y;
  const YfTris *t = &m->tri;
  double sum = 0.0;
  for (int e = e0; e < e1; e++) {
    const int *v = t->v + 3 * e;
    const double *xi = t->xinv + 4 * e;
    double x1 = x[v[1]] - x[v[0]], x2 = x[v[2]] - x[v[0]];
    double y1 = y[v[1]] - y[v[0]], y2 = y[v[2]] - y[v[0]];
    double F11 = x1 * xi[0] + x2 * xi[2], F12 = x1 * xi[1] + x2 * xi[3];
    double F21 = y1 * xi[0] + y2 * xi[2], F22 = y1 * xi[1] + y2 * xi[3];
    double dc = x1 * y2 - x2 * y1, J = dc / t->d0[e];
    double E11 = 0.5 * (F11 * F11 + F12 * F12 - 1.0), E22 = 0.5 * (F21 * F21 + F22 * F22 - 1.0);
    double E12 = 0.5 * (F11 * F21 + F12 * F22);
    const YfTriMat *mt = tm + t->mat[e];
    double a = mt->mu2 / J, vol = mt->lamv * (J - 1.0 / J);
    double TE = (a * E11 + vol) * E11 + (a * E22 + vol) * E22 + 2.0 * a * E12 * E12;
    sum += 0.25 * dc * TE; /* A_c/2 T:E with A_c = dc/2 */
  }
  return sum;
}

double tri_stable_dt(const YfModel *m, const YfTriMat *tm, int e) {
  /* Linearised element: K_e = A B^T C B, M_e = (rho A / 3) I.  The non-zero eigenvalues of
   * B^T C B are those of the 3x3 product C G with G = B B^T, so omega_max^2 = 3 lmax(C G)/rho. */
  const int *v = m->tri.v + 3 * e;
  const double *X = m->node.x0, *Y = m->node.y0;
  double A2 = m->tri.d0[e];
  if (!(A2 > 0)) return 0.0;
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
  if (!(w > 0)) return INFINITY;
  /* Viscous term: damping ratio of the highest mode xi = w k / (2 (lam + 2 mu)); central
   * differences are stable for dt <= (2/w)(sqrt(1 + xi^2) - xi). */
  double xi = w * mt->k / (2.0 * (lam + 2.0 * mu));
  return 2.0 / w * (sqrt(1.0 + xi * xi) - xi);
}
