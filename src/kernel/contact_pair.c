/* contact_pair.c: forces between two triangles from Munjiza's contact potential, as in Y2D
 * (ALGORITHMS.md 6.1-6.5, quirks included, so that couples give Y2D's numbers to round-off).
 *
 * Per direction (contactor C on target T):
 *   6.1  beta_k(P) = ((y_k - P) . m_k) / D, m_k the outward normal of target edge k (length =
 *        edge length), D twice the target's area; beta_k belongs to target vertex k+2 (mod 3).
 *   6.2  a contactor edge a->b is skipped when its line does not separate the target's corners
 *        or when both ends are outside one target edge (tolerance 1e-10); a skipped edge records
 *        the squared distance of its start node to the target edge line of smallest beta.
 *   6.3  along x(s) = x_a + s (x_b - x_a), P(s) = min_k beta_k(s) is piecewise linear between
 *        the breakpoints (interval ends and kinks); F = 3 p_n int P, F_b = 3 p_n int P s,
 *        F_a = F - F_b; the contactor gets -(F_a, F_b) n_c with n_c of length L.
 *   6.4  friction: g += w dt with w = (v_T(s_bar) - v_C(s_bar)) . (x_b - x_a) and s_bar the MEAN
 *        OF THE BREAKPOINTS (Y2D's choice, not the centroid of P); F_t = p_t g capped at mu |F|.
 *   6.5  the target's corners get minus the contactor's nodal forces, weighted by the
 *        barycentric coordinates of the contactor nodes (extrapolated when outside).
 * The arithmetic follows the equations term by term, except that beta is scaled by 1/D and the
 * separation test by D_c instead of dividing (an ulp apart; the far-apart couple, the common
 * case, costs half as much).  Checked against the book-Y reference of deck (a) (contact, no
 * friction): displacements agree to 7e-11 of the largest at steps 1000-4000 and the couple count
 * matches at every output.  The summation order of forces on shared nodes is the caller's.
 *
 * Speed without changing a bit: each triangle's geometry (corners, normals, D, 1/D) is computed
 * once per step into a record (contact_pair_geom) that both the screen (contact_pair_quiet: does
 * the couple need the kernel at all?) and the kernel read; per couple only the barycentric
 * values are computed, three lanes at a time.  Vector lanes do exactly the scalar operations of
 * the equations (no FMA, same operand order), and every division whose quotient is used has the
 * same operands as in the plain formulas, so the results are those of the scalar code
 * (tests/check_contact_pair.c keeps that code as the reference and compares bits).  The screen
 * and the kernel come in an AVX2 version and a portable one, chosen once at load time.
 */
#include "contact_pair.h"

#include <float.h>
#include <math.h>

#include "yfvec.h"

#define EPS YF_CONTACT_EPS

/* ---------------------------------------------------------------- the triangle record */

void contact_pair_geom(const double x[3], const double y[3], double rec[YF_TRI_GEOM])
{
  double q[3];
#pragma GCC unroll 3
  for (int k = 0; k < 3; k++) {
    int k1 = (k + 1) % 3;
    rec[k] = x[k];
    rec[3 + k] = y[k];
    rec[6 + k] = y[k1] - y[k];    /* mx, as contact_pair_dir */
    rec[9 + k] = -(x[k1] - x[k]); /* my */
    q[k] = rec[6 + k] * rec[6 + k] + rec[9 + k] * rec[9 + k]; /* |m_k|^2 as the kernel's m2 */
  }
  double D = (x[1] - x[0]) * (y[2] - y[0]) - (y[1] - y[0]) * (x[2] - x[0]);
  rec[12] = D;
  /* NaN for a degenerate triangle: its betas as a target are NaN, so no edge of the couple is
   * skipped and the screen looks at D only on that (rare) path */
  rec[13] = D > 0.0 ? 1.0 / D : NAN;
  double qmin = q[0];
  if (q[1] < qmin) qmin = q[1];
  if (q[2] < qmin) qmin = q[2];
  rec[14] = (D * D) / qmin; /* the largest squared height D^2 / |m_k|^2 [m^2] (bounds distances) */
  rec[15] = 0.0;
}

/* 4-wide vectors of three corners or edges (GCC vector extensions: two SSE2 halves on plain
 * x86-64, one AVX register in the AVX2 versions); every lane does the scalar arithmetic term by
 * term, so the bits are the same. */
typedef double v4d __attribute__((vector_size(32)));
typedef long long v4l __attribute__((vector_size(32)));

/* lanes of u where the mask m is set, else of w */
#define BLEND(m, u, w) ((v4d)(((m) & (v4l)(u)) | (~(m) & (v4l)(w))))

/* The sign bits of the 4 lanes of a comparison mask: one instruction with AVX, four extractions
 * without (the two versions of the screen and of the kernel pass the one their target has). */
typedef int (*Mask4)(const v4l *);
__attribute__((target("avx2"), always_inline)) static inline int mask4_avx2(const v4l *m)
{
  return __builtin_ia32_movmskpd256((v4d)*m);
}
__attribute__((always_inline)) static inline int mask4_any(const v4l *m)
{
  const v4l v = *m;
  return (int)((v[0] & 1) | (v[1] & 2) | (v[2] & 4) | (v[3] & 8));
}

/* *v = corners p[0..2] in lanes 0..2 and p[0] again in lane 3 (reads p[3], unused): lane 3
 * repeats corner 0 bit for bit, so the screen's lane masks need no trimming */
__attribute__((always_inline)) static inline void corners(const double *p, v4d *v)
{
  __builtin_memcpy(v, p, sizeof *v);
  *v = YF_SHUF4(*v, *v, 0, 1, 2, 0);
}

/* ---------------------------------------------------------------- the kernel */

/* P(s) = min_k beta_k(s) at parameter s of the edge. */
static inline double pmin3(const double al[3], const double dl[3], double s)
{
  double b0 = al[0] + s * dl[0], b1 = al[1] + s * dl[1], b2 = al[2] + s * dl[2];
  double p = b0;
  if (b1 < p) p = b1;
  if (b2 < p) p = b2;
  return p;
}

/* The relative tangential velocity at s of a contactor edge a-b on a target, times the edge length
 * (w = (v_T(s) - v_C(s)) . (x_b - x_a) [m^2/s]; al, dl: the target's barycentrics at a and their
 * change along the edge). */
static inline double slip_rate(const double al[3], const double dl[3], const double vxt[3], const double vyt[3],
                               double vxa, double vya, double vxb, double vyb, double tcx, double tcy, double s)
{
  double vtx = 0.0, vty = 0.0;
#pragma GCC unroll 3
  for (int k = 0; k < 3; k++) {
    double bk = al[k] + s * dl[k];
    int v = (k + 2) % 3; /* beta_k belongs to target vertex k+2 */
    vtx += bk * vxt[v];
    vty += bk * vyt[v];
  }
  double vcx = (1.0 - s) * vxa + s * vxb, vcy = (1.0 - s) * vya + s * vyb;
  return (vtx - vcx) * tcx + (vty - vcy) * tcy;
}

/* The elastic-slip Coulomb law on one contactor edge (YF_FRIC_COULOMB, contact_pair.h).
 * Returns F_t, in F's units (times the edge vector it is the force on the contactor [N/m]).
 * The tangential spring spreads evenly over the contact interval [s_min, s_max] (stiffness 3 p_t / h
 * per unit contact length: the normal law's 3 p_n / h with p_t for p_n, h the target's height over
 * its edge nearest to the interval's midpoint s_m), so its force acts at s_m, on the contactor
 * with the weights (1 - s_m, s_m) (the caller) and on the target with the barycentric coordinates
 * of that point, and the slip rate w is taken at the same point: F_t w dt is then exactly the work
 * of the forces the spring applies.  (At the normal force's centroid F_b / F instead, which moves
 * as the pressure shifts, the spring does work on a rocking block: a block held by mu = 1e4 rocked
 * itself loose.)
 *
 * The memory *g is not F_t but s = F_t / sqrt(k_t), whose square is twice the spring's energy
 * per unit L (0.5 F_t^2 / k_t = 0.5 s^2).  k_t follows the contact interval, which changes
 * every step as the bodies move; with F_t kept across such a change (an incremental F_t), a
 * shrinking interval raised the stored 0.5 F_t^2 / k_t without work: energy from nowhere, which
 * stopped a block held well inside the cone (docs/VERIFICATION.md).  Keeping s instead keeps the
 * spring's energy across the change, and the increment F_t += k_t w dt / L adds exactly the
 * work F_t w dt to it (to first order in dt), so the spring neither makes nor loses energy of
 * its own; a change of interval that is undone (the ringing of a block at rest) gives back the
 * same F_t.  A trial force above mu |F| is returned onto the cone; the excess is slip (*slip =
 * the slip distance times L [m^2], for the dissipation |F_t| slip). */
static inline double coulomb_edge(const double al[3], const double dl[3], const double vxt[3], const double vyt[3],
                                  double vxa, double vya, double vxb, double vyb, double tcx, double tcy,
                                  double smin, double smax, const v4d Q, double D, double pt, double cap,
                                  double dt, double *g, double *w, double *slip, YfContactInfo *info)
{
  const double sm = 0.5 * (smin + smax);
  double vtx = 0.0, vty = 0.0, bmin = INFINITY;
  int kmin = 0;
  for (int k = 0; k < 3; k++) {
    double bk = al[k] + sm * dl[k];
    int v = (k + 2) % 3; /* beta_k belongs to target vertex k+2 */
    vtx += bk * vxt[v];
    vty += bk * vyt[v];
    if (bk < bmin) { bmin = bk; kmin = k; }
  }
  double vcx = (1.0 - sm) * vxa + sm * vxb, vcy = (1.0 - sm) * vya + sm * vyb;
  double L = sqrt(tcx * tcx + tcy * tcy);
  *w = (vtx - vcx) * tcx + (vty - vcy) * tcy;              /* relative velocity times L [m^2/s] */
  double kt = 3.0 * pt * (smax - smin) * sqrt(Q[kmin]) / D; /* F_t per metre of slip [Pa/m]   */
  double sk = sqrt(kt);
  double Ft = *g * sk + kt * (*w * dt / L);
  if (fabs(Ft) > cap) {
    *slip = (fabs(Ft) - cap) / kt * L;
    Ft = copysign(cap, Ft);
  }
  *g = sk > 0.0 ? Ft / sk : 0.0; /* pen_t 0: no spring */
  if (info) { /* the spring's energy 0.5 F_t^2 / k_t L [J/m] */
    double es = 0.5 * *g * *g * L;
    info->energy += es;
    info->spring += es;
  }
  return Ft;
}

/* One direction on the triangle records (contact_pair_geom): contactor c on target t.  The
 * record holds the target's normals, D and 1/D and the contactor's D (the separation test's
 * scale), so only the betas are computed here.  Vectors hold the three target edges (or
 * corners) k in lanes 0..2, loaded straight from the record (lane 3 is the record's next value,
 * never used); every lane does the scalar arithmetic of the equations, so the bits are those of
 * plain scalar code. */
__attribute__((always_inline)) static inline int pair_dir(const double *t, const double *c, const double vxt[3],
                                                         const double vyt[3], const double vxc[3], const double vyc[3],
                                                         double pn, double pt, double mu, int law, double dt, double g[3],
                                                         double *gp, double ft[6], double fc[6], double *dmin2,
                                                         YfContactInfo *info, Mask4 mask)
{
  /* 6.1: target normals (outward for CCW corners, length = edge length) and twice-area. */
  const double D = t[12], Dc = c[12];
  if (!(D > 0.0) || !(Dc > 0.0)) return 0; /* degenerate or inverted: the element check reports it */
  const double *xc = c, *yc = c + 3;
  v4d XT, YT, MX, MY;
  __builtin_memcpy(&XT, t, sizeof XT);
  __builtin_memcpy(&YT, t + 3, sizeof YT);
  __builtin_memcpy(&MX, t + 6, sizeof MX);
  __builtin_memcpy(&MY, t + 9, sizeof MY);
  /* beta_k of every contactor node i, bn[i][k], with 1/D from the record.  (Multiplying by 1/D
   * instead of dividing by D changes values by an ulp at most; it halves the cost of the
   * common, far-apart couple.) */
  double bn[3][4];
  {
    const v4d iD = {t[13], t[13], t[13], t[13]};
#pragma GCC unroll 3
    for (int i = 0; i < 3; i++) {
      v4d b = ((XT - xc[i]) * MX + (YT - yc[i]) * MY) * iD;
      __builtin_memcpy(bn[i], &b, sizeof b);
    }
  }

  /* |m_k|^2 (the squared edge lengths [m^2]) and, at the first edge in contact, the heights
   * D / |m_k| [m] of the energy estimate, lane by lane as the scalar formulas */
  const v4d Q = MX * MX + MY * MY;
  double hk[4];
  int have_hk = 0;
  int nforce = 0;
  double dmin = *dmin2; /* local: no store-to-load chain through the pointer */
  for (int e = 0; e < 3; e++) {
    const int a = e, b = e < 2 ? e + 1 : 0;
    const double *al = bn[a], *ga = bn[b];
    double ncx = yc[b] - yc[a], ncy = -(xc[b] - xc[a]); /* contactor edge outward normal, |n_c| = L */

    /* 6.2: skip when both ends are outside one target edge (tested first: it is cheap and
     * settles most couples), or when the edge line does not separate the target's corners:
     * c_m = ((x_a - y_m) . n_c) / Dc is the contactor's barycentric function of this edge at
     * target corner m, positive on the contactor's inner side (compared as c_m Dc vs eps Dc). */
    v4d AL, GA;
    __builtin_memcpy(&AL, al, sizeof AL);
    __builtin_memcpy(&GA, ga, sizeof GA);
    v4l out = (AL < EPS) & (GA < EPS);
    int skip = (mask(&out) & 7) != 0;
    if (!skip) {
      double ep = EPS * Dc;
      v4d cm = (xc[a] - XT) * ncx + (yc[a] - YT) * ncy;
      v4l pos = cm > -ep, neg = cm < ep;
      skip = (mask(&pos) & 7) == 7 || (mask(&neg) & 7) == 7;
    }
    if (skip) {
      /* distance^2 of the start node to the line of the target edge with the smallest alpha:
       * alpha^2 / (|m_k|/D)^2, compared without dividing first. */
      double amin = al[0], m2 = Q[0];
      if (al[1] < amin) { amin = al[1]; m2 = Q[1]; }
      if (al[2] < amin) { amin = al[2]; m2 = Q[2]; }
      double num = amin * amin * (D * D);
      if (num < dmin * m2) dmin = num / m2;
      if (law != YF_FRIC_Y2D) g[e] = 0.0; /* apart: the tangential spring lets go (Y2D's keeps it) */
      if (gp) gp[e] = 0.0;                /* and applies no force: the booking's last force */
      continue;
    }

    /* 6.3: contact interval [s_min, s_max] of the edge inside the target. */
    double dl[3];
    double smin = 0.0, smax = 1.0;
#pragma GCC unroll 3
    for (int k = 0; k < 3; k++) {
      dl[k] = ga[k] - al[k];
      if (al[k] < 0.0 && ga[k] > EPS) {
        double s = al[k] / (al[k] - ga[k]);
        if (s > smin) smin = s;
      }
      if (al[k] > EPS && ga[k] < 0.0) {
        double s = al[k] / (al[k] - ga[k]);
        if (s < smax) smax = s;
      }
    }
    if (smax <= smin) {
      if (law != YF_FRIC_Y2D) g[e] = 0.0;
      if (gp) gp[e] = 0.0;
      continue;
    }

    /* Breakpoints, sorted: s_min, the kinks of min_k beta_k strictly inside (two lines cross
     * and the third is larger there), s_max.  Only the kinks need sorting. */
    double bs[5];
    int nb = 1;
    bs[0] = smin;
#pragma GCC unroll 2
    for (int i = 0; i < 2; i++)
#pragma GCC unroll 2
      for (int j = i + 1; j < 3; j++) {
        double den = dl[i] - dl[j];
        if (den == 0.0) continue; /* parallel lines never cross */
        double s = (al[j] - al[i]) / den;
        if (!(s > smin && s < smax)) continue;
        int m = 3 - i - j;
        if (al[m] + s * dl[m] > al[i] + s * dl[i]) bs[nb++] = s;
      }
    for (int i = 2; i < nb; i++) { /* insertion sort of at most 3 kinks, all above bs[0] */
      double v = bs[i];
      int j = i - 1;
      while (bs[j] > v) { bs[j + 1] = bs[j]; j--; }
      bs[j + 1] = v;
    }
    bs[nb++] = smax;

    /* Exact integrals of the piecewise-linear P: int P ds and int P s ds. */
    double I0 = 0.0, I1 = 0.0, I2h = 0.0;
    if (info && !have_hk) {
#pragma GCC unroll 3
      for (int k = 0; k < 3; k++) hk[k] = D / sqrt(Q[k]);
      have_hk = 1;
    }
    double s1 = bs[0], p1 = pmin3(al, dl, s1);
    for (int i = 1; i < nb; i++) {
      double s2 = bs[i], p2 = pmin3(al, dl, s2), h = s2 - s1;
      I0 += 0.5 * h * (p1 + p2);
      I1 += h * (p1 * (2.0 * s1 + s2) + p2 * (s1 + 2.0 * s2)) / 6.0;
      if (info) { /* energy estimate: 3 int h_k P^2 ds with the active edge k of this piece */
        double sm = 0.5 * (s1 + s2);
        int k = 0;
        double bk = al[0] + sm * dl[0];
#pragma GCC unroll 2
        for (int q = 1; q < 3; q++)
          if (al[q] + sm * dl[q] < bk) { bk = al[q] + sm * dl[q]; k = q; }
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
    double Ft = 0.0, w = 0.0, slip = 0.0, fp = 0.0; /* fp: the edge's F_t of the last call (booking) */
    if (law == YF_FRIC_Y2D) {
      double sbar = 0.0;
      for (int i = 0; i < nb; i++) sbar += bs[i];
      sbar /= nb;
      w = slip_rate(al, dl, vxt, vyt, vxc[a], vyc[a], vxc[b], vyc[b], tcx, tcy, sbar);
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
        double wa, wb; /* Fa / F and Fb / F in one packed division */
        yf_div2(Fa, F, Fb, F, &wa, &wb);
        fax += Ft * wa * tcx;
        fay += Ft * wa * tcy;
        fbx += Ft * wb * tcx;
        fby += Ft * wb * tcy;
        if (info) w = slip_rate(al, dl, vxt, vyt, vxc[a], vyc[a], vxc[b], vyc[b], tcx, tcy, wb);
      } else {
        Ft = 0.0; /* no normal force, nothing to share the tangential force with */
      }
      /* Booking (not the force): the force acts at the ends with the normal force's weights, i.e. at
       * s = F_b / F, where the memory above took the slip rate at the mean breakpoint: the work of
       * the force is F_t w(F_b / F) dt (w linear in s), and the spring's energy 0.5 F_t^2 / p_t
       * (g += w dt, F_t = p_t g).  Booking |F_t| slip instead left the difference out of the
       * balance: a block sliding to a stop on Y2D's law lost 8 % of its energy from the books. */
      if (gp) {
        fp = gp[e];
        gp[e] = Ft;
      }
      if (info && pt > 0.0) {
        double es = 0.5 * Ft * Ft / pt;
        info->energy += es;
        info->spring += es;
      }
    } else if (F > 0.0) { /* the Coulomb law; its spring acts at the interval's midpoint s_m */
      Ft = coulomb_edge(al, dl, vxt, vyt, vxc[a], vyc[a], vxc[b], vyc[b], tcx, tcy, smin, smax, Q, D, pt,
                        mu * F, dt, &g[e], &w, &slip, info);
      if (gp) {
        fp = gp[e];
        gp[e] = Ft;
      }
      double sm = 0.5 * (smin + smax);
      fax += Ft * (1.0 - sm) * tcx;
      fay += Ft * (1.0 - sm) * tcy;
      fbx += Ft * sm * tcx;
      fby += Ft * sm * tcy;
    } else {
      g[e] = 0.0; /* touching without force: the spring holds nothing */
      if (gp) gp[e] = 0.0;
    }

    fc[2 * a] += fax;
    fc[2 * a + 1] += fay;
    fc[2 * b] += fbx;
    fc[2 * b + 1] += fby;
    /* 6.5: reaction; target vertex v carries beta_(v+1) (beta_k belongs to vertex k+2). */
    {
      /* ft[2v + c] -= f_a,c al[v+1] + f_b,c ga[v+1] for vertices v = 0, 1 (one vector) and 2 */
      const v4d FA = {fax, fay, fax, fay}, FB = {fbx, fby, fbx, fby};
      v4d f01;
      __builtin_memcpy(&f01, ft, sizeof f01);
      f01 -= FA * YF_SHUF4(AL, AL, 1, 1, 2, 2) + FB * YF_SHUF4(GA, GA, 1, 1, 2, 2);
      __builtin_memcpy(ft, &f01, sizeof f01);
      ft[4] -= fax * al[0] + fbx * ga[0];
      ft[5] -= fay * al[0] + fby * ga[0];
    }
    nforce++;

    if (info) {
      double L = sqrt(ncx * ncx + ncy * ncy);
      info->nedge++;
      info->fn += fabs(F) * L;
      info->ft += fabs(Ft) * L;
      info->work_t += Ft * w * dt;
      info->work_c += 0.5 * (fp + Ft) * w * dt;
      info->dissip += fabs(Ft) * slip;
      info->energy += 1.5 * pn * L * I2h;
    }
  }
  *dmin2 = dmin;
  return nforce;
}

int contact_pair_dir(const double xt[3], const double yt[3], const double vxt[3], const double vyt[3],
                     const double xc[3], const double yc[3], const double vxc[3], const double vyc[3],
                     double pn, double pt, double mu, int law, double dt, double g[3],
                     double ft[6], double fc[6], double *dmin2, YfContactInfo *info)
{
  double rt[YF_TRI_GEOM], rc[YF_TRI_GEOM];
  contact_pair_geom(xt, yt, rt);
  contact_pair_geom(xc, yc, rc);
  return pair_dir(rt, rc, vxt, vyt, vxc, vyc, pn, pt, mu, law, dt, g, info ? info->gprev : NULL, ft, fc, dmin2, info,
                  mask4_any);
}

/* both directions of a couple (contact_pair_force_rec) with the given lane-mask function */
__attribute__((always_inline)) static inline int pair_force(const double *ra, const double *vxa, const double *vya,
                                                           const double *rb, const double *vxb, const double *vyb,
                                                           double pn, double pt, double mu, int law, double dt, double g[6],
                                                           double fa[6], double fb[6], double *dmin2,
                                                           YfContactInfo *info, Mask4 mask)
{
  double d2 = DBL_MAX;
  double *gp = info ? info->gprev : NULL;
  int n = pair_dir(ra, rb, vxa, vya, vxb, vyb, pn, pt, mu, law, dt, g, gp, fa, fb, &d2, info, mask);
  n += pair_dir(rb, ra, vxb, vyb, vxa, vya, pn, pt, mu, law, dt, g + 3, gp ? gp + 3 : NULL, fb, fa, &d2, info, mask);
  if (dmin2) *dmin2 = d2;
  return n > 0;
}

__attribute__((target("avx2"))) static int force_rec_avx2(const double *ra, const double *vxa, const double *vya,
                                                          const double *rb, const double *vxb, const double *vyb,
                                                          double pn, double pt, double mu, int law, double dt, double g[6],
                                                          double fa[6], double fb[6], double *dmin2,
                                                          YfContactInfo *info)
{
  /* Y2D's law as a constant: its own copy of the kernel, without the Coulomb branches */
  if (law == YF_FRIC_Y2D)
    return pair_force(ra, vxa, vya, rb, vxb, vyb, pn, pt, mu, YF_FRIC_Y2D, dt, g, fa, fb, dmin2, info, mask4_avx2);
  return pair_force(ra, vxa, vya, rb, vxb, vyb, pn, pt, mu, law, dt, g, fa, fb, dmin2, info, mask4_avx2);
}

int contact_pair_force_rec_any(const double ra[YF_TRI_GEOM], const double vxa[3], const double vya[3],
                               const double rb[YF_TRI_GEOM], const double vxb[3], const double vyb[3],
                               double pn, double pt, double mu, int law, double dt, double g[6],
                               double fa[6], double fb[6], double *dmin2, YfContactInfo *info)
{
  return pair_force(ra, vxa, vya, rb, vxb, vyb, pn, pt, mu, law, dt, g, fa, fb, dmin2, info, mask4_any);
}

/* contact_pair_force_rec resolves to the AVX2 version once, where the CPU has it */
typedef int (*ForceRecFn)(const double *, const double *, const double *, const double *, const double *,
                          const double *, double, double, double, int, double, double *, double *, double *, double *,
                          YfContactInfo *);
/* Resolvers run while the dynamic linker relocates the program, before sanitizer runtimes are
 * set up: they must not be instrumented (an ASan build would fault on its first shadow check). */
#define YF_RESOLVER __attribute__((no_sanitize("address", "undefined")))
YF_RESOLVER static ForceRecFn resolve_force_rec(void)
{
  __builtin_cpu_init();
  return __builtin_cpu_supports("avx2") ? force_rec_avx2 : contact_pair_force_rec_any;
}
int contact_pair_force_rec(const double ra[YF_TRI_GEOM], const double vxa[3], const double vya[3],
                           const double rb[YF_TRI_GEOM], const double vxb[3], const double vyb[3],
                           double pn, double pt, double mu, int law, double dt, double g[6],
                           double fa[6], double fb[6], double *dmin2, YfContactInfo *info)
  __attribute__((ifunc("resolve_force_rec")));

int contact_pair_force(const double xa[3], const double ya[3], const double vxa[3], const double vya[3],
                       const double xb[3], const double yb[3], const double vxb[3], const double vyb[3],
                       double pn, double pt, double mu, int law, double dt, double g[6],
                       double fa[6], double fb[6], double *dmin2, YfContactInfo *info)
{
  double ra[YF_TRI_GEOM], rb[YF_TRI_GEOM];
  contact_pair_geom(xa, ya, ra);
  contact_pair_geom(xb, yb, rb);
  return contact_pair_force_rec(ra, vxa, vya, rb, vxb, vyb, pn, pt, mu, law, dt, g, fa, fb, dmin2, info);
}

/* ---------------------------------------------------------------- the screen */

/* One direction, contactor record c on target record t: b[k] = beta_k of the contactor corners
 * (lanes; contact_pair_dir's bn[i][k] term by term), and whether every contactor edge (i, i+1)
 * has both ends outside one target edge. */
__attribute__((always_inline)) static inline int screen_dir(const double *t, const double *c, v4d b[3], Mask4 mask)
{
  const v4d iD = {t[13], t[13], t[13], t[13]};
  v4d XC, YC;
  corners(c, &XC);
  corners(c + 3, &YC);
  v4l both = {0, 0, 0, 0};
#pragma GCC unroll 3
  for (int k = 0; k < 3; k++) {
    v4d bk = ((t[k] - XC) * t[6 + k] + (t[3 + k] - YC) * t[9 + k]) * iD;
    b[k] = bk;
    v4l o = bk < EPS;                                    /* corner i outside edge k */
    both |= o & YF_SHUF4(o, o, 1, 2, 0, 1); /* ... and corner i+1 too   */
  }
  return mask(&both) == 15;
}

/* 1 if some start corner e (lane) of one direction has a = min_k beta_k with a^2 H2 < c, where
 * H2 >= D^2 / |m_kmin|^2: then the kernel's distance of that edge, a^2 D^2 / |m_kmin|^2, is below
 * c too (to a few ulps).  With c = rem2 / 4 that settles the couple as kept: the kernel's
 * distance sequence passes that edge and ends at most a few ulps above it, far below rem2. */
__attribute__((always_inline)) static inline int screen_near(const double *t, const v4d b[3], double c, Mask4 mask)
{
  v4d a = b[0];
  a = BLEND(b[1] < a, b[1], a);
  a = BLEND(b[2] < a, b[2], a);
  v4l near = a * a * t[14] < c;
  return mask(&near) != 0;
}

/* contact_pair_dir's skip path for the three edges of one direction, exactly: lowers *dmin. */
__attribute__((always_inline)) static inline void screen_dmin(const double *t, const v4d b[3], double *dmin)
{
  const double D = t[12];
  double d = *dmin;
  for (int e = 0; e < 3; e++) {
    double al0 = b[0][e], al1 = b[1][e], al2 = b[2][e];
    int kmin = 0;
    double a = al0;
    if (al1 < a) { kmin = 1; a = al1; }
    if (al2 < a) { kmin = 2; a = al2; }
    double m2 = t[6 + kmin] * t[6 + kmin] + t[9 + kmin] * t[9 + kmin];
    double num = a * a * (D * D);
    if (num < d * m2) d = num / m2;
  }
  *dmin = d;
}

/* The rare couple that no edge settles as near (Y2D drops most of them): the kernel's distance
 * sequence of both directions, exactly.  Out of line, so that the common path keeps the betas in
 * registers; it recomputes them (same arithmetic, same bits). */
__attribute__((noinline)) static int quiet_far(const double *ra, const double *rb, double rem2)
{
  v4d b1[3], b2[3];
  screen_dir(ra, rb, b1, mask4_any);
  screen_dir(rb, ra, b2, mask4_any);
  double d = DBL_MAX;
  screen_dmin(ra, b1, &d);
  screen_dmin(rb, b2, &d);
  return d > rem2 ? 2 : 1;
}

__attribute__((always_inline)) static inline int quiet(const double *ra, const double *rb, double rem2, Mask4 mask)
{
  v4d b1[3], b2[3];
  /* a degenerate triangle (NaN 1/D) fails here as a target, so the quiet path never checks D */
  if (!screen_dir(ra, rb, b1, mask) || !screen_dir(rb, ra, b2, mask)) {
    if (!(ra[12] > 0.0) || !(rb[12] > 0.0)) /* the kernel ignores degenerate triangles: d2 = DBL_MAX */
      return DBL_MAX > rem2 ? 2 : 1;
    return 0;
  }
  /* the bound needs rem2 / 4 exact and far from underflow (else the exact path decides) */
  const double c = rem2 >= 0x1p-900 ? 0.25 * rem2 : 0.0;
  if (screen_near(ra, b1, c, mask) || screen_near(rb, b2, c, mask)) return 1;
  return quiet_far(ra, rb, rem2);
}

__attribute__((target("avx2"))) static int quiet_avx2(const double *ra, const double *rb, double rem2)
{
  return quiet(ra, rb, rem2, mask4_avx2);
}
int contact_pair_quiet_any(const double ra[YF_TRI_GEOM], const double rb[YF_TRI_GEOM], double rem2)
{
  return quiet(ra, rb, rem2, mask4_any);
}

/* contact_pair_quiet resolves to the AVX2 version once, where the CPU has it (as target_clones) */
typedef int (*QuietFn)(const double *, const double *, double);
YF_RESOLVER static QuietFn resolve_quiet(void)
{
  __builtin_cpu_init();
  return __builtin_cpu_supports("avx2") ? quiet_avx2 : contact_pair_quiet_any;
}
int contact_pair_quiet(const double ra[YF_TRI_GEOM], const double rb[YF_TRI_GEOM], double rem2)
  __attribute__((ifunc("resolve_quiet")));
