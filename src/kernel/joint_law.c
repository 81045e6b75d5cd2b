/* joint_law.c: cohesive joint kernel (Y2D's YTE2JOINTS, ALGORITHMS.md 3) and the softening laws.
 *
 * This module owns the constitutive side of fracture: geometry of one 4-node joint, its damage
 * variable, normal and shear stresses, the Mohr-Coulomb strength update and the consistent nodal
 * forces.  joint.c owns the arrays of joints, the loop, breakage bookkeeping and energy totals.
 * Everything here is a pure function of plain numbers so the step loop can run it on any thread.
 *
 * Reproducing Y2D (law YF_SOFT_MUNJIZA, y2d_floor = 1, irreversible = 0) means keeping its quirks:
 * the 1e-10 in the unit tangent (but not in o_p or the weights), the damage recomputed from the
 * current opening every step (unloading retraces the curve), the shear strength replaced by the
 * Mohr-Coulomb value at each sampling point before that point's tau, o_p/s_p/s_t taken from the
 * strength at the start of the call, and the sampling order end a, middle, end b.  Formulas are
 * written in the document's order of operations so round-off stays close to the book's.
 *
 * Energy of the laws.  With z = (o - o_p)/o_t beyond the peak, the softening branch stores
 * f_t o_t I_g per unit joint length, I_g = integral of g over [0, 1]; the pre-peak branch
 * sigma = (2 r - r^2) f_t, r = o/o_p, adds 2/3 f_t o_p.  For Munjiza's curve
 *   f(z) = (1 - K e^{lambda z}) (a (1 - z) + b (1 - z)^c),
 *   K = (a + b - 1)/(a + b) = 1.43/2.43, lambda = (a + c b)/((a + b)(1 - a - b)) = -3.28930329...
 * the integral is, with J_n = int_0^1 e^{lambda z} (1 - z)^n dz,
 *   I_f = a/2 + b/(c + 1) - K (a J_1 + b J_6),
 *   J_0 = (e^lambda - 1)/lambda,  J_n = (n J_{n-1} - 1)/lambda  (integration by parts),
 * which evaluates (40 digits) to I_f = 0.3863072947439426...  Y2D sets o_t = 3 G/f_t, so its
 * softening branch dissipates 3 I_f G = 1.158921884231828 G, about 16% more than G (plus the
 * pre-peak part, and more again when the 2 o_p floor is active).  tests/check_joint_law.c checks
 * YF_MUNJIZA_AREA against GSL adaptive quadrature.
 *
 * Irreversible variant (not in Y2D).  Each sampling point keeps D, the largest z reached.  When the
 * current z >= D the point is on its damage envelope and the stresses are exactly the reversible
 * ones (D := z).  When z < D the point is inside the envelope: we follow the ray from the origin
 * through the current (o, |s|) out to the envelope z = D, at (lambda o, lambda |s|), lambda >= 1,
 * evaluate the reversible stresses there with damage D, and divide them by lambda.  This is secant
 * unloading towards the origin: linear along every ray, continuous with the loading branch on the
 * envelope, and in pure mode I it is sigma = g(D) f_t o / (o_p + D o_t).  Compression (o < 0) keeps
 * the undamaged penalty sigma = o p/h as in Y2D.
 */
#include "joint_law.h"
#include "yfvec.h"

#include <float.h>
#include <math.h>
#include <stdio.h>

#include <gsl/gsl_interp.h>

/* Munjiza's softening curve, written as in ALGORITHMS 3.3.  Most sampling points of a scene are
 * undamaged (z = 0, f = 1): they skip exp entirely, and (1 - z)^6 is three multiplications instead
 * of pow (both agree with the formula to an ulp; the Y2D regressions check 1e-8). */
static double soft_munjiza(double z)
{
  const double a = 0.63, b = 1.8;
  if (z == 0.0) return 1.0;
  double u = 1.0 - z, u2 = u * u, u6 = u2 * u2 * u2; /* c = 6 */
  return (1.0 - ((a + b - 1.0) / (a + b)) * exp(z * (a + 6.0 * b) / ((a + b) * (1.0 - a - b)))) *
         (a * u + b * u6);
}

/* Piecewise linear through (tab_z, tab_s); same arithmetic as gsl_interp_linear, but with the
 * index search alone so that the property set stays plain copyable data (no gsl_interp object to
 * allocate or free) and evaluation is read-only. */
static double soft_table(const YfJointProp *p, double z)
{
  if (z <= 0.0) return p->tab_s[0];
  if (z >= 1.0) return p->tab_s[p->ntab - 1];
  size_t i = gsl_interp_bsearch(p->tab_z, z, 0, (size_t)p->ntab - 1);
  double x_lo = p->tab_z[i], x_hi = p->tab_z[i + 1];
  double y_lo = p->tab_s[i], y_hi = p->tab_s[i + 1];
  double dx = x_hi - x_lo;
  return dx > 0.0 ? y_lo + (z - x_lo) / dx * (y_hi - y_lo) : y_lo;
}

double joint_soft(const YfJointProp *p, double z)
{
  switch (p->law) {
  case YF_SOFT_MUNJIZA:
  case YF_SOFT_MUNJIZA_GF:
    return soft_munjiza(z);
  case YF_SOFT_LINEAR:
    return 1.0 - z;
  case YF_SOFT_BILINEAR:
    if (z <= p->bl_z) return 1.0 - (1.0 - p->bl_s) * (z / p->bl_z);
    return p->bl_s * (1.0 - z) / (1.0 - p->bl_z);
  case YF_SOFT_TABLE:
    return soft_table(p, z);
  default:
    return 0.0;
  }
}

double joint_soft_area(const YfJointProp *p)
{
  switch (p->law) {
  case YF_SOFT_MUNJIZA:
  case YF_SOFT_MUNJIZA_GF:
    return YF_MUNJIZA_AREA;
  case YF_SOFT_LINEAR:
    return 0.5;
  case YF_SOFT_BILINEAR: /* trapezoid (0,1)-(z1,s1) plus triangle (z1,s1)-(1,0) */
    return 0.5 * (p->bl_z + p->bl_s);
  case YF_SOFT_TABLE:
    return p->tab_area;
  default:
    return 0.0;
  }
}

/* Softening length for strength fstr [Pa] before the floor: Y2D's 3 G/f for Munjiza's law, the
 * length that puts exactly G under the curve for the others. */
static double soft_length(const YfJointProp *p, double fstr)
{
  if (p->law == YF_SOFT_MUNJIZA) return 3.0 * p->gf / fstr;
  return p->gf / (fstr * joint_soft_area(p));
}

void joint_lengths(const YfJointProp *p, double h, double fs, double *op, double *ot, double *sp,
                   double *st)
{
  double o_p = 2.0 * h * p->ft / p->pen;
  double s_p = 2.0 * h * fs / p->pen;
  double o_t = soft_length(p, p->ft), s_t = soft_length(p, fs);
  if (p->y2d_floor) {
    o_t = fmax(2.0 * o_p, o_t);
    s_t = fmax(2.0 * s_p, s_t);
  }
  if (op) *op = o_p;
  if (ot) *ot = o_t;
  if (sp) *sp = s_p;
  if (st) *st = s_t;
}

double joint_fs_init(const YfJointProp *p) { return p->fs > 0.0 ? p->fs : p->coh; }

double joint_law_area(const YfJointProp *p, double h)
{
  double op, ot;
  joint_lengths(p, h, joint_fs_init(p), &op, &ot, NULL, NULL);
  return p->ft * op * (2.0 / 3.0) + p->ft * ot * joint_soft_area(p);
}

double joint_law_area_shear(const YfJointProp *p, double h)
{
  double fs = joint_fs_init(p), sp, st;
  joint_lengths(p, h, fs, NULL, NULL, &sp, &st);
  return fs * sp * (2.0 / 3.0) + fs * st * joint_soft_area(p);
}

void joint_prop_default(YfJointProp *p)
{
  *p = (YfJointProp){0};
  p->ft = 3.15e6;
  p->fs = 3.15e6;
  p->gf = 300.0;
  p->pen = 1e11;
  p->coh = 0.0;
  p->phi = 0.0;
  p->law = YF_SOFT_MUNJIZA;
  p->y2d_floor = 1;
  p->irreversible = 0;
  p->bl_z = 2.0 / 9.0; /* Petersson: kink at 0.8 G/f_t of a critical opening 3.6 G/f_t */
  p->bl_s = 1.0 / 3.0; /* ... where the stress is f_t/3 */
  p->ntab = 0;
  p->tab_area = 0.0;
  p->hreg = 1e-10; /* Y2D's regularisation of the unit tangent */
}

/* Validate table points; shared by joint_prop_set_table and joint_prop_check. */
static int table_check(int n, const double *w, const double *s, char *why, size_t nwhy)
{
  if (n < 2 || n > YF_JOINT_TAB_MAX) {
    snprintf(why, nwhy, "softening table needs 2 to %d points (got %d)", YF_JOINT_TAB_MAX, n);
    return 0;
  }
  if (w[0] != 0.0) {
    snprintf(why, nwhy, "softening table must start at opening 0 (got %g)", w[0]);
    return 0;
  }
  if (s[0] != 1.0 || s[n - 1] != 0.0) {
    snprintf(why, nwhy, "softening table stress must go from 1 to 0 (got %g .. %g)", s[0],
             s[n - 1]);
    return 0;
  }
  for (int i = 0; i < n; i++) {
    if (!isfinite(w[i]) || !isfinite(s[i]) || s[i] < 0.0 || s[i] > 1.0) {
      snprintf(why, nwhy, "softening table point %d (%g, %g): stress/ft must be in [0, 1]", i,
               w[i], s[i]);
      return 0;
    }
    if (i > 0 && !(w[i] > w[i - 1])) {
      snprintf(why, nwhy, "softening table openings must increase strictly (point %d: %g after %g)",
               i, w[i], w[i - 1]);
      return 0;
    }
  }
  return 1;
}

int joint_prop_set_table(YfJointProp *p, int n, const double *w, const double *s, char *why,
                         size_t nwhy)
{
  if (!table_check(n, w, s, why, nwhy)) return 0;
  double wc = w[n - 1], area = 0.0;
  for (int i = 0; i < n; i++) {
    p->tab_z[i] = w[i] / wc; /* last one is exactly 1 */
    p->tab_s[i] = s[i];
  }
  for (int i = 0; i + 1 < n; i++)
    area += 0.5 * (p->tab_z[i + 1] - p->tab_z[i]) * (p->tab_s[i] + p->tab_s[i + 1]);
  p->ntab = n;
  p->tab_area = area;
  p->law = YF_SOFT_TABLE;
  return 1;
}

int joint_prop_check(const YfJointProp *p, char *why, size_t n)
{
#define BAD(...) do { snprintf(why, n, __VA_ARGS__); return 0; } while (0)
  if (!(p->ft > 0.0) || !isfinite(p->ft)) BAD("tensile strength ft must be > 0 Pa (got %g)", p->ft);
  if (!(p->gf > 0.0) || !isfinite(p->gf)) BAD("fracture energy Gf must be > 0 J/m^2 (got %g)", p->gf);
  if (!(p->pen > 0.0) || !isfinite(p->pen)) BAD("joint penalty must be > 0 Pa (got %g)", p->pen);
  if (!isfinite(p->fs)) BAD("shear strength fs must be finite (got %g)", p->fs);
  if (!(p->coh >= 0.0) || !isfinite(p->coh)) BAD("cohesion must be >= 0 Pa (got %g)", p->coh);
  if (!(p->phi >= 0.0) || !isfinite(p->phi)) BAD("friction coefficient must be >= 0 (got %g)", p->phi);
  if (!(p->fs > 0.0) && !(p->coh > 0.0))
    BAD("shear strength fs (got %g) or cohesion (got %g) must be > 0 Pa", p->fs, p->coh);
  if (p->law < 0 || p->law >= YF_SOFT_NLAW)
    BAD("unknown softening law %d (expected munjiza munjiza_gf linear bilinear table)", p->law);
  if (p->y2d_floor != 0 && p->y2d_floor != 1) BAD("y2d_floor must be 0 or 1 (got %d)", p->y2d_floor);
  if (p->irreversible != 0 && p->irreversible != 1)
    BAD("irreversible must be 0 or 1 (got %d)", p->irreversible);
  if (p->law == YF_SOFT_BILINEAR) {
    if (!(p->bl_z > 0.0 && p->bl_z < 1.0))
      BAD("bilinear kink opening fraction must be in (0, 1) (got %g)", p->bl_z);
    if (!(p->bl_s > 0.0 && p->bl_s < 1.0))
      BAD("bilinear kink stress fraction must be in (0, 1) (got %g)", p->bl_s);
  }
  if (p->law == YF_SOFT_TABLE) {
    if (!table_check(p->ntab, p->tab_z, p->tab_s, why, n)) return 0;
    if (p->tab_z[p->ntab - 1] != 1.0 || !(p->tab_area > 0.0))
      BAD("softening table not normalised (set it with joint_prop_set_table)");
  }
  return 1;
#undef BAD
}

/* Per-call constants of one joint. */
typedef struct {
  double ft, op, ot, sp, st, coh, phi;
} JointLens;

/* Damage of a sampling point (ALGORITHMS 3.3), not yet clamped. */
static double point_z(const JointLens *L, double o, double as)
{
  if (o > L->op && as > L->sp) {
    double zo = (o - L->op) / L->ot, zs = (as - L->sp) / L->st;
    return sqrt(zo * zo + zs * zs);
  }
  if (o > L->op) return (o - L->op) / L->ot;
  if (as > L->sp) return (as - L->sp) / L->st;
  return 0.0;
}

/* Normal stress of the reversible law for opening o >= 0 and softening value fz (3.4). */
static double sigma_tension(const JointLens *L, double o, double fz)
{
  if (o <= L->op) {
    double r = o / L->op;
    return (2.0 * r - r * r) * fz * L->ft;
  }
  return fz * L->ft;
}

/* Shear stress magnitude of the reversible law for slip magnitude as >= 0 (3.4). */
static double tau_mag(const JointLens *L, double as, double fz, double fs)
{
  if (as > L->sp) return fz * fs;
  double r = as / L->sp;
  return (2.0 * r - r * r) * fz * fs;
}

/* Scale lambda >= 1 at which the ray (lambda o, lambda as) reaches the envelope z = D (D > 0).
 * Returns 0 when the ray never gets there (o <= 0 and as == 0). */
static double envelope_ray(const JointLens *L, double o, double as, double D)
{
  double lx = o > 0.0 ? (L->op + D * L->ot) / o : INFINITY;
  double ly = as > 0.0 ? (L->sp + D * L->st) / as : INFINITY;
  if (!isfinite(lx) && !isfinite(ly)) return 0.0;
  /* the first component to reach D alone; if the other one is still inactive there, done */
  if (lx <= ly) {
    if (!(lx * as > L->sp)) return lx;
  } else {
    if (!(ly * o > L->op)) return ly;
  }
  /* both active: ((l o - o_p)/o_t)^2 + ((l as - s_p)/s_t)^2 = D^2, larger root (z^2 - D^2 grows) */
  double io = 1.0 / L->ot, is = 1.0 / L->st;
  double A = o * o * io * io + as * as * is * is;
  double B = -2.0 * (o * L->op * io * io + as * L->sp * is * is);
  double C = L->op * L->op * io * io + L->sp * L->sp * is * is - D * D;
  double disc = B * B - 4.0 * A * C;
  return (-B + sqrt(disc > 0.0 ? disc : 0.0)) / (2.0 * A);
}

void joint_pre_init(const YfJointProp *p, YfJointPre *c)
{
  c->ot = soft_length(p, p->ft);
  c->fs0 = joint_fs_init(p);
  c->st0 = soft_length(p, c->fs0);
}

void joint_geometry(double hreg, const double x[4], const double y[4], YfJointGeom *g)
{
  joint_geometry_inline(hreg, x, y, g);
}

/* The law of one joint from its geometry (ALGORITHMS 3.2-3.7).  ot: the softening length of f_t
 * before the floor; st0: the one of the shear strength fs0 (used when the joint's current strength
 * is fs0, i.e. always without Mohr-Coulomb).  Operations are those of the document in its order;
 * what is skipped is only what cannot change a bit: g(0) = 1 for every law (no call for an
 * undamaged point), the mode of the info is worked out for the most damaged point alone, and
 * lengths that do not depend on the joint's geometry come precomputed. */
static inline int law_core(const YfJointProp *p, double ot, double fs0, double st0, const YfJointGeom *g,
                           double *fs_state, double *dmg, double f[8], YfJointInfo *info)
{
  const double h = g->h, e1x = g->e1x, e1y = g->e1y, nx = -e1y, ny = e1x;
  const double *po = g->po, *ps = g->ps;

  /* 3.2 strengths: lengths from the shear strength at the start of the call (as joint_lengths) */
  double fs = fs_state ? *fs_state : joint_fs_init(p);
  JointLens L = {.ft = p->ft, .coh = p->coh, .phi = p->phi};
  yf_div2(2.0 * h * p->ft, p->pen, 2.0 * h * fs, p->pen, &L.op, &L.sp);
  L.ot = ot;
  L.st = fs == fs0 ? st0 : soft_length(p, fs);
  if (p->y2d_floor) { /* fmax of two positive lengths */
    double o2 = 2.0 * L.op, s2 = 2.0 * L.sp;
    if (o2 > L.ot) L.ot = o2;
    if (s2 > L.st) L.st = s2;
  }

  double w[3];
  yf_div2(h, 6.0, h, 3.0, &w[0], &w[1]);
  w[2] = w[0];
  double qx[3], qy[3];
  int nfail = 0, kmax = -1;
  double zmax = 0.0, lmax = 1.0;

  for (int k = 0; k < 3; k++) {
    double o = po[k], s = ps[k], as = fabs(s);
    /* 3.3 damage */
    double z = point_z(&L, o, as);
    if (z >= 1.0) z = 1.0;
    double lam = 1.0; /* ray scale of the irreversible unloading branch (1: on the envelope) */
    if (p->irreversible) {
      double D = dmg[k];
      if (z >= D) {
        dmg[k] = z;
      } else {
        z = D;
        lam = envelope_ray(&L, o, as, D);
      }
    }
    if (z >= 1.0) nfail++;
    double fz = z == 0.0 ? 1.0 : joint_soft(p, z); /* g(0) = 1 exactly for every law */

    double sigma, tau;
    if (lam == 1.0) {
      /* on the envelope (always in Y2D's reversible law): the two quotients of 3.4, packed.
       * ro: o/o_p for 0 <= o <= o_p, or the compression stress 2 o f_t/o_p (penalty o p/h) */
      double ro, rs;
      yf_div2(o < 0.0 ? 2.0 * o * L.ft : o, L.op, as, L.sp, &ro, &rs);
      if (o < 0.0)
        sigma = ro;
      else if (o <= L.op)
        sigma = (2.0 * ro - ro * ro) * fz * L.ft;
      else
        sigma = fz * L.ft;
      /* 3.5 Mohr-Coulomb: replace f_s before this point's tau; kept for the next points/calls */
      if (L.coh > 0.0) fs = sigma > 0.0 ? L.coh : L.coh - sigma * L.phi;
      tau = as > L.sp ? fz * fs : (2.0 * rs - rs * rs) * fz * fs;
    } else {
      /* 3.4 normal stress (compression: undamaged penalty o p/h) */
      if (o < 0.0)
        sigma = 2.0 * o * L.ft / L.op;
      else if (lam > 0.0)
        sigma = sigma_tension(&L, lam * o, fz) / lam;
      else
        sigma = 0.0;
      if (L.coh > 0.0) fs = sigma > 0.0 ? L.coh : L.coh - sigma * L.phi;
      /* 3.4 shear stress on the secant branch */
      if (lam > 0.0 && as > 0.0)
        tau = tau_mag(&L, lam * as, fz, fs) / lam;
      else
        tau = 0.0;
    }
    if (s < 0.0) tau = -tau;

    qx[k] = tau * e1x + sigma * nx;
    qy[k] = tau * e1y + sigma * ny;

    if (z > zmax) { /* the most damaged point (first of equals) and its ray scale */
      zmax = z;
      kmax = k;
      lmax = lam;
    }
  }
  if (fs_state) *fs_state = fs;

  /* 3.6 nodal forces: A's nodes (0, 1) get -w q, B's (3, 2) +w q */
  f[0] = -w[0] * qx[0] - w[1] * qx[1];
  f[1] = -w[0] * qy[0] - w[1] * qy[1];
  f[2] = -w[1] * qx[1] - w[2] * qx[2];
  f[3] = -w[1] * qy[1] - w[2] * qy[2];
  f[4] = w[1] * qx[1] + w[2] * qx[2];
  f[5] = w[1] * qy[1] + w[2] * qy[2];
  f[6] = w[0] * qx[0] + w[1] * qx[1];
  f[7] = w[0] * qy[0] + w[1] * qy[1];

  if (info) {
    info->h = h;
    info->open_mean = po[1];
    info->slip_mean = ps[1];
    info->zmax = zmax;
    info->mode = YF_JMODE_NONE;
    if (kmax >= 0) {
      /* normalised distances beyond the peaks, on the envelope */
      double sc = lmax > 0.0 ? lmax : 1.0;
      double ol = sc * po[kmax], sl = sc * fabs(ps[kmax]);
      double a = ol > L.op ? (ol - L.op) / L.ot : 0.0;
      double b = sl > L.sp ? (sl - L.sp) / L.st : 0.0;
      if (b <= a / 9.0 && a > 0.0)
        info->mode = YF_JMODE_I;
      else if (a <= b / 9.0 && b > 0.0)
        info->mode = YF_JMODE_II;
      else
        info->mode = YF_JMODE_MIXED;
    }
  }
  return nfail;
}

int joint_force(const YfJointProp *p, const double x[4], const double y[4], double *fs_state,
                double *dmg, double f[8], YfJointInfo *info)
{
  YfJointPre c;
  YfJointGeom g;
  joint_pre_init(p, &c);
  joint_geometry_inline(p->hreg, x, y, &g);
  return law_core(p, c.ot, c.fs0, c.st0, &g, fs_state, dmg, f, info);
}

int joint_force_geom(const YfJointProp *p, const YfJointPre *c, const YfJointGeom *g, double *fs_state,
                     double *dmg, double f[8], YfJointInfo *info)
{
  return law_core(p, c->ot, c->fs0, c->st0, g, fs_state, dmg, f, info);
}
