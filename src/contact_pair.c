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
 */
#include "contact_pair.h"

#include <float.h>
#include <math.h>

#define EPS YF_CONTACT_EPS

/* P(s) = min_k beta_k(s) at parameter s of the edge. */
static inline double pmin3(const double al[3], const double dl[3], double s)
{
  double b0 = al[0] + s * dl[0], b1 = al[1] + s * dl[1], b2 = al[2] + s * dl[2];
  double p = b0;
  if (b1 < p) p = b1;
  if (b2 < p) p = b2;
  return p;
}

int contact_pair_dir(const double xt[3], const double yt[3], const double vxt[3], const double vyt[3],
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
    int skip = (al[0] < EPS && ga[0] < EPS) || (al[1] < EPS && ga[1] < EPS) || (al[2] < EPS && ga[2] < EPS);
    if (!skip) {
      double ep = EPS * Dc;
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
      if (al[k] < 0.0 && ga[k] > EPS) {
        double s = al[k] / (al[k] - ga[k]);
        if (s > smin) smin = s;
      }
      if (al[k] > EPS && ga[k] < 0.0) {
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
    double s1 = bs[0], p1 = pmin3(al, dl, s1);
    for (int i = 1; i < nb; i++) {
      double s2 = bs[i], p2 = pmin3(al, dl, s2), h = s2 - s1;
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
      } else {
        Ft = 0.0; /* no normal force, nothing to share the tangential force with */
      }
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

int contact_pair_force(const double xa[3], const double ya[3], const double vxa[3], const double vya[3],
                       const double xb[3], const double yb[3], const double vxb[3], const double vyb[3],
                       double pn, double pt, double mu, double dt, double g[6],
                       double fa[6], double fb[6], double *dmin2, YfContactInfo *info)
{
  double d2 = DBL_MAX;
  int n = contact_pair_dir(xa, ya, vxa, vya, xb, yb, vxb, vyb, pn, pt, mu, dt, g, fa, fb, &d2, info);
  n += contact_pair_dir(xb, yb, vxb, vyb, xa, ya, vxa, vya, pn, pt, mu, dt, g + 3, fb, fa, &d2, info);
  if (dmin2) *dmin2 = d2;
  return n > 0;
}

/* ---------------------------------------------------------------- the screen */

void contact_pair_geom(const double x[3], const double y[3], double rec[YF_TRI_GEOM])
{
  for (int k = 0; k < 3; k++) {
    int k1 = (k + 1) % 3;
    rec[k] = x[k];
    rec[3 + k] = y[k];
    rec[6 + k] = y[k1] - y[k];    /* mx, as contact_pair_dir */
    rec[9 + k] = -(x[k1] - x[k]); /* my */
  }
  double D = (x[1] - x[0]) * (y[2] - y[0]) - (y[1] - y[0]) * (x[2] - x[0]);
  rec[12] = D;
  rec[13] = 1.0 / D;
  rec[14] = rec[15] = 0.0;
}

/* The screen works on the three contactor corners at once, one per lane of a 4-wide vector
 * (GCC vector extensions: two SSE2 halves on plain x86-64, one AVX register where the CPU has
 * it); every lane does contact_pair_dir's arithmetic term by term, so the bits are the same. */
typedef double v4d __attribute__((vector_size(32)));
typedef long long v4l __attribute__((vector_size(32)));

/* beta_k of the contactor corners (lanes) for target edge k (as contact_pair_dir's bn[.][k]) */
#define BETA(t, k, XC, YC) ((((t)[k] - (XC)) * (t)[6 + (k)] + ((t)[3 + (k)] - (YC)) * (t)[9 + (k)]) * (t)[13])
/* lanes of u where the mask m is set, else of w */
#define BLEND(m, u, w) ((v4d)(((m) & (v4l)(u)) | (~(m) & (v4l)(w))))

typedef struct {
  v4d b[3]; /* b[k]: beta_k of contactor corner (lane) i */
} Betas;

/* One direction, contactor record c on target record t: the betas, and whether every contactor
 * edge (i, i+1) has both ends outside one target edge. */
static inline int screen_dir(const double *t, const double *c, Betas *B)
{
  const v4d XC = {c[0], c[1], c[2], c[0]}, YC = {c[3], c[4], c[5], c[3]};
  const v4l rot = {1, 2, 0, 3};
  v4l any = {0, 0, 0, 0};
  for (int k = 0; k < 3; k++) {
    v4d bk = BETA(t, k, XC, YC);
    B->b[k] = bk;
    v4l o = bk < EPS;                     /* corner i outside edge k */
    any |= o & __builtin_shuffle(o, rot); /* ... and corner i+1 too  */
  }
  return any[0] && any[1] && any[2];
}

/* For each start corner e (lane) of one direction: the smallest beta and the squared length of
 * its target edge, chosen as contact_pair_dir chooses kmin; 1 if for some corner
 * num = beta^2 D^2 < c m2.  With c = rem2 / 4 that settles the couple as kept: the kernel's
 * distance sequence passes that edge and ends at most a few ulps above num / m2 < rem2 / 4. */
static inline int screen_near(const double *t, const Betas *B, double c)
{
  const double D = t[12];
  const double q0 = t[6] * t[6] + t[9] * t[9], q1 = t[7] * t[7] + t[10] * t[10], q2 = t[8] * t[8] + t[11] * t[11];
  v4d a = B->b[0], m2 = {q0, q0, q0, q0};
  v4l s1 = B->b[1] < a;
  a = BLEND(s1, B->b[1], a);
  m2 = BLEND(s1, ((v4d){q1, q1, q1, q1}), m2);
  v4l s2 = B->b[2] < a;
  a = BLEND(s2, B->b[2], a);
  m2 = BLEND(s2, ((v4d){q2, q2, q2, q2}), m2);
  v4l near = a * a * (D * D) < c * m2;
  return near[0] || near[1] || near[2];
}

/* contact_pair_dir's skip path for the three edges of one direction, exactly: lowers *dmin. */
static inline void screen_dmin(const double *t, const Betas *B, double *dmin)
{
  const double D = t[12];
  double d = *dmin;
  for (int e = 0; e < 3; e++) {
    double al0 = B->b[0][e], al1 = B->b[1][e], al2 = B->b[2][e];
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

__attribute__((target_clones("avx2", "default")))
int contact_pair_quiet(const double ra[YF_TRI_GEOM], const double rb[YF_TRI_GEOM], double rem2)
{
  if (!(ra[12] > 0.0) || !(rb[12] > 0.0)) /* the kernel ignores degenerate triangles: d2 = DBL_MAX */
    return DBL_MAX > rem2 ? 2 : 1;
  Betas b1, b2;
  if (!screen_dir(ra, rb, &b1)) return 0; /* B as contactor on target A */
  if (!screen_dir(rb, ra, &b2)) return 0; /* A on B */
  const double c = 0.25 * rem2;
  if (screen_near(ra, &b1, c) || screen_near(rb, &b2, c)) return 1;
  double d = DBL_MAX;
  screen_dmin(ra, &b1, &d);
  screen_dmin(rb, &b2, &d);
  return d > rem2 ? 2 : 1;
}
