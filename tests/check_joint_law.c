/* check_joint_law.c: the cohesive joint kernel (src/kernel/joint_law.c, ALGORITHMS.md 3).
 *
 * Each test drives one joint through prescribed node positions and checks a physical or exact
 * fact: dissipated energy of quasi-static mode I and mode II failure against joint_law_area, peak
 * stresses, the compression penalty, the mixed-mode damage formula, the weights and order of the
 * three sampling points, objectivity and equilibrium, the 2-of-3 failure rule, Mohr-Coulomb, and
 * the reversible (Y2D) versus irreversible (secant unloading) damage.
 *
 * Geometry used throughout: B's nodes 3, 2 sit at P - d_a/2, Q - d_b/2 and A's nodes 0, 1 at
 * P + d_a/2, Q + d_b/2, with d = o n + s e1.  The symmetric split keeps the joint axis exactly Q - P
 * for any d, so the kernel measures o and s times c = h/(h + 1e-10) (Y2D's regularised tangent).
 */
#include <check.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>
#include <gsl/gsl_interp.h>

#include "joint_law.h"

#define H0 0.005  /* joint length [m] (seed paper mesh size) */
#define TH 0.7    /* joint direction [rad] */
#define PX 0.31   /* end p of the edge [m] */
#define PY -0.17

static const double cfac = H0 / (H0 + 1e-10); /* measured / prescribed relative displacement */

/* Place the joint with relative displacements (o, s) at end a and end b. */
static void place(double oa, double sa, double ob, double sb, double x[4], double y[4])
{
  double ex = cos(TH), ey = sin(TH), nx = -ey, ny = ex;
  double qx = PX + H0 * ex, qy = PY + H0 * ey;
  double dax = oa * nx + sa * ex, day = oa * ny + sa * ey;
  double dbx = ob * nx + sb * ex, dby = ob * ny + sb * ey;
  x[0] = PX + dax / 2; y[0] = PY + day / 2;
  x[3] = PX - dax / 2; y[3] = PY - day / 2;
  x[1] = qx + dbx / 2; y[1] = qy + dby / 2;
  x[2] = qx - dbx / 2; y[2] = qy - dby / 2;
}

/* Mean traction (tau, sigma) of a uniformly loaded joint: the force on A is -h q, and q = tau e1 +
 * sigma n is built from Y2D's e1 and n, whose length is c, not 1. */
static void traction(const double f[8], double h, double *tau, double *sigma)
{
  double ex = cos(TH), ey = sin(TH), nx = -ey, ny = ex;
  double fx = -(f[0] + f[2]) / (h * cfac), fy = -(f[1] + f[3]) / (h * cfac);
  *tau = fx * ex + fy * ey;
  *sigma = fx * nx + fy * ny;
}

static double rel(double a, double b) { return fabs(a - b) / fmax(fabs(b), 1e-300); }

/* Relative tolerance of a stress read from a relative displacement u [m]: node coordinates of
 * ~0.4 m carry ~4e-17 m of round-off each, so u itself is known to ~4e-16/|u| relative. */
static double rtol_u(double u) { return 1e-12 + 4e-16 / fabs(u); }

static void prop_law(YfJointProp *p, int law)
{
  joint_prop_default(p);
  p->law = law;
  if (law == YF_SOFT_TABLE) {
    /* a Hordijk-like curve given in millimetres, to exercise the rescaling */
    const double w[] = {0.0, 0.02, 0.06, 0.15, 0.3, 0.6, 1.2};
    const double s[] = {1.0, 0.70, 0.45, 0.25, 0.12, 0.04, 0.0};
    char why[160];
    ck_assert_msg(joint_prop_set_table(p, 7, w, s, why, sizeof why), "%s", why);
  }
}

static const int all_laws[] = {YF_SOFT_MUNJIZA, YF_SOFT_MUNJIZA_GF, YF_SOFT_LINEAR,
                               YF_SOFT_BILINEAR, YF_SOFT_TABLE};
static const char *law_word[] = {"munjiza", "munjiza_gf", "linear", "bilinear", "table"};

/* ---------------------------------------------------------------- softening curves */

static double g_of(double z, void *par) { return joint_soft((const YfJointProp *)par, z); }

static double munjiza_unclamped(double z, void *par)
{
  (void)par;
  const double a = 0.63, b = 1.8, c = 6.0;
  return (1.0 - ((a + b - 1.0) / (a + b)) * exp(z * (a + c * b) / ((a + b) * (1.0 - a - b)))) *
         (a * (1.0 - z) + b * pow(1.0 - z, c));
}

START_TEST(test_soft_ends_and_area)
{
  /* report quadrature failures through the status instead of abort(); restored at the end */
  gsl_error_handler_t *old_handler = gsl_set_error_handler_off();
  gsl_integration_workspace *ws = gsl_integration_workspace_alloc(1000);
  for (size_t i = 0; i < sizeof all_laws / sizeof *all_laws; i++) {
    YfJointProp p;
    prop_law(&p, all_laws[i]);
    ck_assert_msg(fabs(joint_soft(&p, 0.0) - 1.0) < 1e-12, "%s: g(0) = %.17g", law_word[i],
                  joint_soft(&p, 0.0));
    ck_assert_msg(fabs(joint_soft(&p, 1.0)) < 1e-12, "%s: g(1) = %.17g", law_word[i],
                  joint_soft(&p, 1.0));
    /* softening: never increases, stays in [0, 1] */
    double prev = joint_soft(&p, 0.0);
    for (int k = 1; k <= 1000; k++) {
      double g = joint_soft(&p, k / 1000.0);
      ck_assert_msg(g <= prev + 1e-15 && g >= -1e-15, "%s: g not softening at z=%g", law_word[i],
                    k / 1000.0);
      prev = g;
    }
    /* the stated area is the integral of the curve (break points given to QAG) */
    gsl_function F = {g_of, &p};
    double res = 0.0, err = 0.0;
    if (all_laws[i] == YF_SOFT_TABLE || all_laws[i] == YF_SOFT_BILINEAR) {
      double pts[YF_JOINT_TAB_MAX];
      size_t np = 0;
      if (all_laws[i] == YF_SOFT_TABLE)
        for (int k = 0; k < p.ntab; k++) pts[np++] = p.tab_z[k];
      else {
        pts[np++] = 0.0; pts[np++] = p.bl_z; pts[np++] = 1.0;
      }
      ck_assert_int_eq(gsl_integration_qagp(&F, pts, np, 0.0, 1e-12, 1000, ws, &res, &err), 0);
    } else {
      ck_assert_int_eq(
          gsl_integration_qag(&F, 0.0, 1.0, 0.0, 1e-12, 1000, GSL_INTEG_GAUSS61, ws, &res, &err), 0);
    }
    ck_assert_msg(rel(joint_soft_area(&p), res) < 1e-12, "%s: area %.17g vs quadrature %.17g",
                  law_word[i], joint_soft_area(&p), res);
  }
  /* Munjiza's constant against the analytic recursion of joint_law.c's header comment */
  const double a = 0.63, b = 1.8, c = 6.0;
  double K = (a + b - 1.0) / (a + b), lam = (a + c * b) / ((a + b) * (1.0 - a - b));
  double J[7];
  J[0] = (exp(lam) - 1.0) / lam;
  for (int n = 1; n <= 6; n++) J[n] = (n * J[n - 1] - 1.0) / lam;
  double If = a / 2 + b / (c + 1) - K * (a * J[1] + b * J[6]);
  ck_assert_msg(rel(YF_MUNJIZA_AREA, If) < 1e-14, "I_f %.17g vs analytic %.17g", YF_MUNJIZA_AREA, If);
  gsl_function F = {munjiza_unclamped, NULL};
  double res, err;
  ck_assert_int_eq(
      gsl_integration_qag(&F, 0.0, 1.0, 0.0, 1e-13, 1000, GSL_INTEG_GAUSS61, ws, &res, &err), 0);
  ck_assert_msg(rel(YF_MUNJIZA_AREA, res) < 1e-13, "I_f %.17g vs QAG %.17g", YF_MUNJIZA_AREA, res);
  gsl_integration_workspace_free(ws);
  gsl_set_error_handler(old_handler);
}
END_TEST

START_TEST(test_table_matches_gsl_linear)
{
  YfJointProp p;
  prop_law(&p, YF_SOFT_TABLE);
  gsl_interp *it = gsl_interp_alloc(gsl_interp_linear, (size_t)p.ntab);
  gsl_interp_init(it, p.tab_z, p.tab_s, (size_t)p.ntab);
  for (int k = 0; k <= 997; k++) {
    double z = k / 997.0;
    double want = gsl_interp_eval(it, p.tab_z, p.tab_s, z, NULL);
    ck_assert_msg(fabs(joint_soft(&p, z) - want) <= 1e-15, "z=%g: %.17g vs gsl %.17g", z,
                  joint_soft(&p, z), want);
  }
  gsl_interp_free(it);
  /* the rescaled curve puts exactly Gf under the softening branch */
  double op, ot;
  joint_lengths(&p, H0, p.fs, &op, &ot, NULL, NULL);
  ck_assert(rel(p.ft * ot * joint_soft_area(&p), p.gf) < 1e-13);
}
END_TEST

/* ---------------------------------------------------------------- quasi-static failure */

/* Open (shear = 0) or slip (shear = 1) a joint from 0 to 1.03 times the failure value in small
 * steps, integrating the work of the forces by the trapezoid rule.  Returns work per unit joint
 * length [J/m^2]; *peak is the largest traction met, *ufail the first prescribed displacement at
 * which all three points had failed. */
static double pull(const YfJointProp *p, int shear, double *peak, double *ufail)
{
  double fs = joint_fs_init(p), op, ot, sp, st;
  joint_lengths(p, H0, fs, &op, &ot, &sp, &st);
  double u_pk = shear ? sp : op, u_c = shear ? sp + st : op + ot;
  double x[4], y[4], f[8], xo[4], yo[4], fo[8] = {0};
  double work = 0.0, fsv = fs;
  int npre = 400, npost = 40000;
  place(0, 0, 0, 0, xo, yo);
  *peak = 0.0;
  *ufail = -1.0;
  for (int k = 1; k <= npre + npost; k++) {
    double u = k <= npre ? u_pk * k / npre / cfac
                         : (u_pk + (1.03 * u_c - u_pk) * (k - npre) / npost) / cfac;
    if (shear) place(0, u, 0, u, x, y);
    else place(u, 0, u, 0, x, y);
    int nf = joint_force(p, x, y, &fsv, NULL, f, NULL);
    for (int i = 0; i < 4; i++)
      work -= 0.5 * ((f[2 * i] + fo[2 * i]) * (x[i] - xo[i]) +
                     (f[2 * i + 1] + fo[2 * i + 1]) * (y[i] - yo[i]));
    double tau, sigma;
    traction(f, H0, &tau, &sigma);
    *peak = fmax(*peak, shear ? tau : sigma);
    if (nf == 3 && *ufail < 0) *ufail = u * cfac;
    ck_assert_msg(nf == 0 || nf == 3, "uniform loading: all points fail together (nf=%d)", nf);
    memcpy(xo, x, sizeof x);
    memcpy(yo, y, sizeof y);
    memcpy(fo, f, sizeof f);
  }
  return work / H0;
}

START_TEST(test_mode_I_energy)
{
  /* _i: the law; the y2d floor is inactive with the seed concrete (3G/ft = 907 o_p) */
  YfJointProp p;
  prop_law(&p, all_laws[_i]);
  double op, ot, peak, ufail;
  joint_lengths(&p, H0, p.fs, &op, &ot, NULL, NULL);
  double W = pull(&p, 0, &peak, &ufail);
  double A = joint_law_area(&p, H0);
  /* trapezoid error with 40000 steps is ~3e-9 (curvature of g is O(1) in z); the kink at o_p is a
   * grid point */
  ck_assert_msg(rel(W, A) < 1e-5, "%s: work %.10g J/m^2 vs joint_law_area %.10g", law_word[_i], W, A);
  double soft = (W - p.ft * op * 2.0 / 3.0) / p.gf;
  if (all_laws[_i] == YF_SOFT_MUNJIZA)
    ck_assert_msg(rel(soft, 3.0 * YF_MUNJIZA_AREA) < 1e-5, "Munjiza: softening work %.8g Gf", soft);
  else
    ck_assert_msg(rel(soft, 1.0) < 1e-5, "%s: softening work %.8g Gf (want 1)", law_word[_i], soft);
  ck_assert_msg(rel(peak, p.ft) < 1e-12, "%s: peak %.17g vs ft", law_word[_i], peak);
  /* failure at o_p + o_t, within one step */
  ck_assert_msg(fabs(ufail - (op + ot)) <= 1.03 * (op + ot) / 40000 * 1.0001, "%s: fails at %g, want %g",
                law_word[_i], ufail, op + ot);
}
END_TEST

START_TEST(test_mode_II_energy)
{
  YfJointProp p;
  prop_law(&p, all_laws[_i]);
  p.fs = 0.63 * p.ft; /* distinct from ft so a mix-up shows */
  double sp, st, peak, ufail;
  joint_lengths(&p, H0, p.fs, NULL, NULL, &sp, &st);
  double W = pull(&p, 1, &peak, &ufail);
  double A = joint_law_area_shear(&p, H0);
  ck_assert_msg(rel(W, A) < 1e-5, "%s: shear work %.10g vs %.10g", law_word[_i], W, A);
  double soft = (W - p.fs * sp * 2.0 / 3.0) / p.gf;
  double want = all_laws[_i] == YF_SOFT_MUNJIZA ? 3.0 * YF_MUNJIZA_AREA : 1.0;
  ck_assert_msg(rel(soft, want) < 1e-5, "%s: shear softening work %.8g Gf", law_word[_i], soft);
  ck_assert_msg(rel(peak, p.fs) < 1e-12, "%s: shear peak %.17g vs fs %.17g", law_word[_i], peak, p.fs);
  /* negative slip: tau changes sign, same magnitude */
  double x[4], y[4], f[8], tau, sigma, fsv = p.fs;
  place(0, -1.5 * sp, 0, -1.5 * sp, x, y);
  joint_force(&p, x, y, &fsv, NULL, f, NULL);
  traction(f, H0, &tau, &sigma);
  double z = (1.5 * sp * cfac - sp) / st;
  ck_assert(rel(tau, -joint_soft(&p, z) * p.fs) < 1e-9);
  ck_assert(fabs(sigma) < 1e-9 * p.fs);
}
END_TEST

START_TEST(test_floor_active)
{
  /* small Gf: 3G/ft < 2 o_p, so Y2D uses o_t = 2 o_p; the work follows */
  YfJointProp p;
  joint_prop_default(&p);
  p.gf = 0.1;
  double op, ot, peak, ufail;
  joint_lengths(&p, H0, p.fs, &op, &ot, NULL, NULL);
  ck_assert(rel(ot, 2.0 * op) < 1e-15);
  double W = pull(&p, 0, &peak, &ufail);
  double want = p.ft * op * (2.0 / 3.0 + 2.0 * YF_MUNJIZA_AREA);
  ck_assert(rel(joint_law_area(&p, H0), want) < 1e-14);
  ck_assert_msg(rel(W, want) < 1e-5, "work %.10g vs %.10g", W, want);
  /* Y-Geo rule (no floor): o_t = 3G/ft */
  p.y2d_floor = 0;
  joint_lengths(&p, H0, p.fs, &op, &ot, NULL, NULL);
  ck_assert(rel(ot, 3.0 * p.gf / p.ft) < 1e-15);
  W = pull(&p, 0, &peak, &ufail);
  ck_assert_msg(rel(W, joint_law_area(&p, H0)) < 1e-5, "work %.10g vs %.10g", W,
                joint_law_area(&p, H0));
}
END_TEST

/* ---------------------------------------------------------------- exact point values */

START_TEST(test_compression_penalty)
{
  YfJointProp p;
  prop_law(&p, all_laws[_i]);
  p.irreversible = 1;
  double op, x[4], y[4], f[8], dmg[3] = {0, 0, 0}, tau, sigma, fsv = p.fs;
  joint_lengths(&p, H0, p.fs, &op, NULL, NULL, NULL);
  for (double o = -0.1 * op; o > -1e4 * op; o *= 3.0) {
    place(o, 0, o, 0, x, y);
    YfJointInfo info;
    int nf = joint_force(&p, x, y, &fsv, dmg, f, &info);
    traction(f, H0, &tau, &sigma);
    ck_assert_int_eq(nf, 0);
    ck_assert(info.zmax == 0.0 && info.mode == YF_JMODE_NONE);
    ck_assert(dmg[0] == 0.0 && dmg[1] == 0.0 && dmg[2] == 0.0);
    ck_assert_msg(rel(sigma, o * cfac * p.pen / H0) < rtol_u(o), "sigma %.17g vs o p/h %.17g", sigma,
                  o * cfac * p.pen / H0);
    /* zero slip up to round-off: |tau| <= 2 fs |ds|/s_p */
    ck_assert(fabs(tau) <= 2.0 * p.fs * 4e-16 / (2.0 * H0 * p.fs / p.pen));
  }
}
END_TEST

START_TEST(test_mixed_mode_point)
{
  YfJointProp p;
  joint_prop_default(&p);
  p.fs = 2.2e6;
  double op, ot, sp, st, x[4], y[4], f[8], tau, sigma, fsv = p.fs;
  joint_lengths(&p, H0, p.fs, &op, &ot, &sp, &st);
  double o = op + 0.3 * ot, s = -(sp + 0.4 * st); /* both beyond their peaks */
  place(o / cfac, s / cfac, o / cfac, s / cfac, x, y);
  YfJointInfo info;
  int nf = joint_force(&p, x, y, &fsv, NULL, f, &info);
  traction(f, H0, &tau, &sigma);
  double z = sqrt(0.3 * 0.3 + 0.4 * 0.4); /* 0.5 */
  double fz = 1.0;
  {
    const double a = 0.63, b = 1.8, c = 6.0;
    fz = (1 - (a + b - 1) / (a + b) * exp(z * (a + c * b) / ((a + b) * (1 - a - b)))) *
         (a * (1 - z) + b * pow(1 - z, c));
  }
  ck_assert_int_eq(nf, 0);
  ck_assert_msg(rel(info.zmax, z) < 1e-9, "z %.17g want %.17g", info.zmax, z);
  ck_assert_msg(rel(sigma, fz * p.ft) < 1e-9, "sigma %.17g want %.17g", sigma, fz * p.ft);
  ck_assert_msg(rel(tau, -fz * p.fs) < 1e-9, "tau %.17g want %.17g", tau, -fz * p.fs);
  ck_assert_int_eq(info.mode, YF_JMODE_MIXED);
  ck_assert(rel(info.open_mean, o) < 1e-12 && rel(info.slip_mean, s) < 1e-12);
  /* pre-peak in both: z = 0, sigma and tau follow 2r - r^2 */
  place(0.5 * op / cfac, 0.25 * sp / cfac, 0.5 * op / cfac, 0.25 * sp / cfac, x, y);
  joint_force(&p, x, y, &fsv, NULL, f, &info);
  traction(f, H0, &tau, &sigma);
  ck_assert(info.zmax == 0.0);
  ck_assert(rel(sigma, 0.75 * p.ft) < 1e-9 && rel(tau, (0.5 - 0.0625) * p.fs) < 1e-9);
  /* pure modes are reported as such */
  place(2 * op, 0, 2 * op, 0, x, y);
  joint_force(&p, x, y, &fsv, NULL, f, &info);
  ck_assert_int_eq(info.mode, YF_JMODE_I);
  place(0, 2 * sp, 0, 2 * sp, x, y);
  joint_force(&p, x, y, &fsv, NULL, f, &info);
  ck_assert_int_eq(info.mode, YF_JMODE_II);
}
END_TEST

/* Y2D point values recomputed by hand for a non-uniform joint: weights h/6, h/3, h/6, order a,
 * middle, b, and the 2-of-3 failure rule. */
static void hand_forces(const YfJointProp *p, const double o[3], double fexp[8])
{
  double op, ot, sg[3];
  joint_lengths(p, H0, p->fs, &op, &ot, NULL, NULL);
  for (int k = 0; k < 3; k++) {
    double z = o[k] > op ? fmin(1.0, (o[k] - op) / ot) : 0.0;
    double g = joint_soft(p, z), r = o[k] / op;
    sg[k] = o[k] < 0 ? o[k] * p->pen / H0 : o[k] <= op ? (2 * r - r * r) * g * p->ft : g * p->ft;
  }
  double nx = -sin(TH) * cfac, ny = cos(TH) * cfac; /* Y2D's n has length c */
  double fa = H0 / 6 * sg[0], fm = H0 / 3 * sg[1], fb = H0 / 6 * sg[2];
  fexp[0] = -(fa + fm) * nx; fexp[1] = -(fa + fm) * ny;
  fexp[2] = -(fm + fb) * nx; fexp[3] = -(fm + fb) * ny;
  fexp[4] = (fm + fb) * nx;  fexp[5] = (fm + fb) * ny;
  fexp[6] = (fa + fm) * nx;  fexp[7] = (fa + fm) * ny;
}

START_TEST(test_three_points_and_failure_rule)
{
  YfJointProp p;
  joint_prop_default(&p);
  double op, ot, x[4], y[4], f[8], fe[8], fsv = p.fs;
  joint_lengths(&p, H0, p.fs, &op, &ot, NULL, NULL);
  double oc = op + ot;
  /* end a pre-peak, middle softening, end b failed: one failed point, not broken */
  double o1[3] = {0.5 * op, 0, 1.5 * oc};
  o1[1] = 0.5 * (o1[0] + o1[2]);
  place(o1[0] / cfac, 0, o1[2] / cfac, 0, x, y);
  int nf = joint_force(&p, x, y, &fsv, NULL, f, NULL);
  ck_assert_int_eq(nf, 1);
  ck_assert(!YF_JOINT_BROKEN(nf));
  hand_forces(&p, o1, fe);
  double fmaxv = 0;
  for (int i = 0; i < 8; i++) fmaxv = fmax(fmaxv, fabs(fe[i]));
  for (int i = 0; i < 8; i++)
    ck_assert_msg(fabs(f[i] - fe[i]) < 1e-9 * fmaxv, "f[%d] %.17g vs hand %.17g", i, f[i], fe[i]);
  /* end a compressed, middle and end b failed: broken */
  double o2[3] = {-0.4 * oc, 0, 2.5 * oc};
  o2[1] = 0.5 * (o2[0] + o2[2]);
  place(o2[0] / cfac, 0, o2[2] / cfac, 0, x, y);
  nf = joint_force(&p, x, y, &fsv, NULL, f, NULL);
  ck_assert_int_eq(nf, 2);
  ck_assert(YF_JOINT_BROKEN(nf));
  hand_forces(&p, o2, fe);
  fmaxv = 0;
  for (int i = 0; i < 8; i++) fmaxv = fmax(fmaxv, fabs(fe[i]));
  for (int i = 0; i < 8; i++)
    ck_assert_msg(fabs(f[i] - fe[i]) < 1e-9 * fmaxv, "f[%d] %.17g vs hand %.17g", i, f[i], fe[i]);
  /* only the middle point: a joint opened at its centre cannot be, but the mirror image of the
   * first case (end a failed) also counts one */
  place(1.5 * oc / cfac, 0, 0.5 * op / cfac, 0, x, y);
  ck_assert_int_eq(joint_force(&p, x, y, &fsv, NULL, f, NULL), 1);
}
END_TEST

/* ---------------------------------------------------------------- invariance, equilibrium */

static void rigid(double c, double s, double tx, double ty, double x[4], double y[4])
{
  for (int i = 0; i < 4; i++) {
    double xi = x[i], yi = y[i];
    x[i] = c * xi - s * yi + tx;
    y[i] = s * xi + c * yi + ty;
  }
}

START_TEST(test_rigid_motion)
{
  YfJointProp p;
  joint_prop_default(&p);
  double op, ot, x[4], y[4], f[8], g[8], fsv = p.fs;
  joint_lengths(&p, H0, p.fs, &op, &ot, NULL, NULL);
  /* closed joint moved rigidly: no force at all */
  for (int k = 0; k < 12; k++) {
    double a = 0.55 * k;
    place(0, 0, 0, 0, x, y);
    rigid(cos(a), sin(a), 1.7 * k - 3.0, -0.9 * k, x, y);
    int nf = joint_force(&p, x, y, &fsv, NULL, f, NULL);
    ck_assert_int_eq(nf, 0);
    for (int i = 0; i < 8; i++) ck_assert_msg(f[i] == 0.0, "f[%d] = %g N/m", i, f[i]);
  }
  /* a loaded joint moved rigidly: the same forces, rotated (objectivity) */
  place(0.7 * op, 0.4 * op, op + 0.2 * ot, -0.3 * op, x, y);
  joint_force(&p, x, y, &fsv, NULL, f, NULL);
  double fmaxv = 0;
  for (int i = 0; i < 8; i++) fmaxv = fmax(fmaxv, fabs(f[i]));
  for (int k = 1; k < 8; k++) {
    double a = 0.9 * k, c = cos(a), s = sin(a);
    double xr[4], yr[4];
    memcpy(xr, x, sizeof x);
    memcpy(yr, y, sizeof y);
    rigid(c, s, 0.2 * k, -0.1 * k, xr, yr);
    joint_force(&p, xr, yr, &fsv, NULL, g, NULL);
    for (int i = 0; i < 4; i++) {
      double wx = c * f[2 * i] - s * f[2 * i + 1], wy = s * f[2 * i] + c * f[2 * i + 1];
      /* positions of ~1 m carry 1e-16 m of round-off against openings of 1e-7 m */
      ck_assert_msg(fabs(g[2 * i] - wx) < 1e-7 * fmaxv && fabs(g[2 * i + 1] - wy) < 1e-7 * fmaxv,
                    "rotation %d node %d: (%g, %g) vs (%g, %g)", k, i, g[2 * i], g[2 * i + 1], wx, wy);
    }
  }
}
END_TEST

START_TEST(test_equilibrium_random)
{
  unsigned seed = 12345u;
  double x[4], y[4], f[8];
  for (int trial = 0; trial < 2000; trial++) {
    YfJointProp p;
    prop_law(&p, all_laws[trial % 5]);
    p.irreversible = trial % 2;
    if (trial % 3 == 0) { p.coh = 2e6; p.phi = 0.5; }
    double op, ot, fsv = joint_fs_init(&p), dmg[3] = {0, 0, 0};
    joint_lengths(&p, H0, p.fs, &op, &ot, NULL, NULL);
    double sc = 1.5 * (op + ot);
    place(0, 0, 0, 0, x, y);
    for (int i = 0; i < 4; i++) {
      x[i] += sc * (2.0 * rand_r(&seed) / RAND_MAX - 1.0);
      y[i] += sc * (2.0 * rand_r(&seed) / RAND_MAX - 1.0);
    }
    joint_force(&p, x, y, &fsv, dmg, f, NULL);
    double sx = 0, sy = 0, m = 0;
    for (int i = 0; i < 4; i++) {
      sx += f[2 * i];
      sy += f[2 * i + 1];
      m = fmax(m, fmax(fabs(f[2 * i]), fabs(f[2 * i + 1])));
    }
    ck_assert_msg(fabs(sx) <= 4e-16 * m && fabs(sy) <= 4e-16 * m, "trial %d: sum (%g, %g), max %g",
                  trial, sx, sy, m);
  }
}
END_TEST

/* ---------------------------------------------------------------- damage memory */

START_TEST(test_reversible_retraces)
{
  YfJointProp p;
  joint_prop_default(&p);
  double op, ot, x[4], y[4], f[8], f0[8], fsv = p.fs, tau, sigma;
  joint_lengths(&p, H0, p.fs, &op, &ot, NULL, NULL);
  place(0.6 * op, 0, 0.6 * op, 0, x, y);
  joint_force(&p, x, y, &fsv, NULL, f0, NULL);
  place(op + 0.5 * ot, 0, op + 0.5 * ot, 0, x, y); /* damage 0.5 */
  joint_force(&p, x, y, &fsv, NULL, f, NULL);
  place(0.6 * op, 0, 0.6 * op, 0, x, y);           /* back: the virgin curve again */
  joint_force(&p, x, y, &fsv, NULL, f, NULL);
  for (int i = 0; i < 8; i++) ck_assert(f[i] == f0[i]);
  traction(f, H0, &tau, &sigma);
  double r = 0.6 * cfac;
  ck_assert(rel(sigma, (2 * r - r * r) * p.ft) < rtol_u(0.6 * op));
}
END_TEST

START_TEST(test_irreversible_secant)
{
  YfJointProp p;
  prop_law(&p, all_laws[_i]);
  p.irreversible = 1;
  double op, ot, sp, st, x[4], y[4], f[8], fsv = p.fs, tau, sigma, dmg[3] = {0, 0, 0};
  joint_lengths(&p, H0, p.fs, &op, &ot, &sp, &st);
  /* load to D = 0.5 in pure mode I */
  double oenv = op + 0.5 * ot;
  place(oenv / cfac, 0, oenv / cfac, 0, x, y);
  joint_force(&p, x, y, &fsv, dmg, f, NULL);
  for (int k = 0; k < 3; k++) ck_assert(rel(dmg[k], 0.5) < 1e-9);
  double D = dmg[0], gD = joint_soft(&p, D);
  /* unload: straight towards the origin, damage kept */
  for (double t = 0.9; t > 0.0; t -= 0.2) {
    place(t * oenv / cfac, 0, t * oenv / cfac, 0, x, y);
    YfJointInfo info;
    int nf = joint_force(&p, x, y, &fsv, dmg, f, &info);
    traction(f, H0, &tau, &sigma);
    ck_assert_int_eq(nf, 0);
    ck_assert(dmg[0] == D && dmg[1] == D && dmg[2] == D && info.zmax == D);
    ck_assert_msg(rel(sigma, gD * p.ft * t) < 1e-9, "t=%g sigma %.17g want %.17g", t, sigma,
                  gD * p.ft * t);
  }
  /* reload to the envelope: back on the softening curve */
  place(oenv / cfac, 0, oenv / cfac, 0, x, y);
  joint_force(&p, x, y, &fsv, dmg, f, NULL);
  traction(f, H0, &tau, &sigma);
  ck_assert(rel(sigma, gD * p.ft) < 1e-9);

  /* mixed mode: after loading to (o, s), every point of the ray t (o, s) carries t q */
  double dm[3] = {0, 0, 0}, qt, qs, q1t, q1s;
  double o = op + 0.25 * ot, s = sp + 0.35 * st;
  place(o, s, o, s, x, y);
  joint_force(&p, x, y, &fsv, dm, f, NULL);
  traction(f, H0, &q1t, &q1s);
  double Dm = dm[1];
  for (double t = 0.95; t > 0.0; t -= 0.15) {
    place(t * o, t * s, t * o, t * s, x, y);
    joint_force(&p, x, y, &fsv, dm, f, NULL);
    traction(f, H0, &qt, &qs);
    ck_assert(dm[1] == Dm);
    ck_assert_msg(rel(qs, t * q1s) < 1e-9 && rel(qt, t * q1t) < 1e-9,
                  "t=%g: (tau, sigma) = (%g, %g) want (%g, %g)", t, qt, qs, t * q1t, t * q1s);
  }
  /* continuity at the envelope: just inside differs from on by O(1e-9) */
  place(o * (1 - 1e-9), s * (1 - 1e-9), o * (1 - 1e-9), s * (1 - 1e-9), x, y);
  joint_force(&p, x, y, &fsv, dm, f, NULL);
  traction(f, H0, &qt, &qs);
  ck_assert(rel(qs, q1s) < 1e-7 && rel(qt, q1t) < 1e-7);
  /* slip-dominated damage, opening below o_p: secant still exact along the ray */
  double dn[3] = {0, 0, 0};
  o = 0.4 * op;
  s = sp + 0.6 * st;
  place(o, s, o, s, x, y);
  joint_force(&p, x, y, &fsv, dn, f, NULL);
  traction(f, H0, &q1t, &q1s);
  place(0.5 * o, 0.5 * s, 0.5 * o, 0.5 * s, x, y);
  joint_force(&p, x, y, &fsv, dn, f, NULL);
  traction(f, H0, &qt, &qs);
  ck_assert(rel(qs, 0.5 * q1s) < 1e-9 && rel(qt, 0.5 * q1t) < 1e-9);
}
END_TEST

START_TEST(test_irreversible_monotone_walk)
{
  YfJointProp p;
  prop_law(&p, all_laws[_i]);
  p.irreversible = 1;
  double op, ot, x[4], y[4], f[8], fsv = p.fs, dmg[3] = {0, 0, 0}, old[3];
  joint_lengths(&p, H0, p.fs, &op, &ot, NULL, NULL);
  unsigned seed = 777u + (unsigned)_i;
  double oa = 0, ob = 0, sa = 0, sb = 0, step = 0.05 * (op + ot);
  int broke = 0;
  for (int k = 0; k < 3000; k++) {
    oa += step * (2.0 * rand_r(&seed) / RAND_MAX - 1.0);
    ob += step * (2.0 * rand_r(&seed) / RAND_MAX - 1.0);
    sa += step * (2.0 * rand_r(&seed) / RAND_MAX - 1.0);
    sb += step * (2.0 * rand_r(&seed) / RAND_MAX - 1.0);
    place(oa, sa, ob, sb, x, y);
    memcpy(old, dmg, sizeof old);
    int nf = joint_force(&p, x, y, &fsv, dmg, f, NULL);
    int n1 = 0;
    for (int i = 0; i < 3; i++) {
      ck_assert_msg(dmg[i] >= old[i] && dmg[i] <= 1.0, "step %d point %d: %g after %g", k, i,
                    dmg[i], old[i]);
      n1 += dmg[i] >= 1.0;
    }
    ck_assert_int_eq(nf, n1); /* a failed point stays failed */
    broke |= nf >= 2;
  }
  ck_assert_msg(broke, "the walk should reach failure (range of the walk ~ 2.7 critical openings)");
}
END_TEST

/* ---------------------------------------------------------------- Mohr-Coulomb */

START_TEST(test_mohr_coulomb)
{
  YfJointProp p;
  joint_prop_default(&p);
  p.fs = 0.0; /* strength from cohesion */
  p.coh = 1.5e6;
  p.phi = 0.6;
  double fsv = joint_fs_init(&p);
  ck_assert(fsv == p.coh);
  double op, ot, sp, st, x[4], y[4], f[8], tau, sigma;
  joint_lengths(&p, H0, fsv, &op, &ot, &sp, &st);
  /* compression (sigma = -6 ft) with a slip of 2 s_p: beyond the peak of the cohesion alone */
  double o = -3.0 * op, s = 2.0 * sp;
  place(o / cfac, s / cfac, o / cfac, s / cfac, x, y);
  joint_force(&p, x, y, &fsv, NULL, f, NULL);
  traction(f, H0, &tau, &sigma);
  double sig = o * p.pen / H0, fsn = p.coh - sig * p.phi;
  ck_assert(rel(sigma, sig) < rtol_u(o));
  ck_assert_msg(rel(fsv, fsn) < rtol_u(o), "fs %.17g want %.17g", fsv, fsn);
  /* tau of this call: z from the old lengths (cohesion), magnitude from the new strength */
  double z = (s - sp) / st;
  ck_assert_msg(rel(tau, joint_soft(&p, z) * fsn) < rtol_u(s), "tau %.17g want %.17g", tau,
                joint_soft(&p, z) * fsn);
  /* the next call takes s_p from the stored strength (8.6 times larger): now pre-peak */
  double sp2;
  joint_lengths(&p, H0, fsv, NULL, NULL, &sp2, NULL);
  ck_assert(s < sp2);
  joint_force(&p, x, y, &fsv, NULL, f, NULL);
  traction(f, H0, &tau, &sigma);
  double r = s / sp2;
  ck_assert_msg(rel(tau, (2 * r - r * r) * fsn) < rtol_u(s), "tau %.17g want %.17g", tau,
                (2 * r - r * r) * fsn);
  /* tension: back to the cohesion */
  place(0.5 * op, 0, 0.5 * op, 0, x, y);
  joint_force(&p, x, y, &fsv, NULL, f, NULL);
  ck_assert(fsv == p.coh);
  /* without cohesion the strength never changes */
  joint_prop_default(&p);
  fsv = p.fs;
  place(o, s, o, s, x, y);
  joint_force(&p, x, y, &fsv, NULL, f, NULL);
  ck_assert(fsv == p.fs);
}
END_TEST

/* ---------------------------------------------------------------- property checks */

START_TEST(test_prop_check)
{
  char why[200];
  YfJointProp p;
  for (size_t i = 0; i < sizeof all_laws / sizeof *all_laws; i++) {
    prop_law(&p, all_laws[i]);
    ck_assert_msg(joint_prop_check(&p, why, sizeof why), "%s: %s", law_word[i], why);
  }
  joint_prop_default(&p);
  p.ft = -1;
  ck_assert(!joint_prop_check(&p, why, sizeof why) && strstr(why, "ft"));
  joint_prop_default(&p);
  p.gf = 0;
  ck_assert(!joint_prop_check(&p, why, sizeof why) && strstr(why, "Gf"));
  joint_prop_default(&p);
  p.fs = 0;
  ck_assert(!joint_prop_check(&p, why, sizeof why) && strstr(why, "cohesion"));
  p.coh = 1e6;
  ck_assert(joint_prop_check(&p, why, sizeof why));
  joint_prop_default(&p);
  p.law = 17;
  ck_assert(!joint_prop_check(&p, why, sizeof why) && strstr(why, "bilinear"));
  joint_prop_default(&p);
  p.law = YF_SOFT_BILINEAR;
  p.bl_z = 1.0;
  ck_assert(!joint_prop_check(&p, why, sizeof why) && strstr(why, "kink"));
  joint_prop_default(&p);
  p.law = YF_SOFT_TABLE; /* no table given */
  ck_assert(!joint_prop_check(&p, why, sizeof why) && strstr(why, "table"));
  const double w[] = {0, 1, 0.5, 2}, s[] = {1, 0.5, 0.2, 0};
  ck_assert(!joint_prop_set_table(&p, 4, w, s, why, sizeof why) && strstr(why, "increase"));
  const double w2[] = {0, 1, 2}, s2[] = {1, 0.5, 0.1};
  ck_assert(!joint_prop_set_table(&p, 3, w2, s2, why, sizeof why) && strstr(why, "1 to 0"));
  ck_assert(p.ntab == 0);
}
END_TEST

/* ---------------------------------------------------------------- four joints at once */

/* Uniform in [a, b). */
static double urand(unsigned *seed, double a, double b) { return a + (b - a) * (rand_r(seed) / (RAND_MAX + 1.0)); }

/* A relative displacement for one end: around the peak t (> 0) so that the measured value falls
 * on either side of it by an ulp or so, well inside, in compression, past the peak, or zero. */
static double near_peak(unsigned *seed, double t, double cf)
{
  switch (rand_r(seed) % 6) {
  case 0: return t / cf * (1.0 + urand(seed, -3e-15, 3e-15));
  case 1: return t / cf;
  case 2: return urand(seed, -1.0, 1.0) * t;
  case 3: return urand(seed, 1.0, 1.5) * t;
  case 4: return -urand(seed, 0.0, 3.0) * t;
  default: return 0.0;
  }
}

/* A strength t such that 2 h t/pen rounds to target exactly (NAN if no t within 400 ulps). */
static double tune_strength(double h, double pen, double target)
{
  double t = target * pen / (2.0 * h);
  for (int i = 0; i < 400; i++) {
    double v = 2.0 * h * t / pen;
    if (v == target) return t;
    t = nextafter(t, v < target ? INFINITY : -INFINITY);
  }
  return NAN;
}

/* An axis-aligned joint (h = 2^-7, hreg = 0) whose measured opening o and slip s are exact
 * multiples of 2^-57 (every sum of the geometry is exact), with f_t and the shear strength tuned
 * so that the peaks o_p, s_p are o or its neighbour below or above (likewise s): the accept test
 * o <= o_p, |s| <= s_p is then exercised to the last ulp.  Returns 0 if no tuning was found. */
static int exact_lane(unsigned *seed, YfJointProp *q, double *fsv, double x[4], double y[4])
{
  const double h = 0x1p-7;
  q->hreg = 0.0;
  double o = ldexp(floor(ldexp(urand(seed, 0.5, 1.5) * 2.0 * h * q->ft / q->pen, 57)), -57);
  double s = ldexp(floor(ldexp(urand(seed, 0.5, 1.5) * 2.0 * h * *fsv / q->pen, 57)), -57);
  double to = rand_r(seed) % 3 == 0 ? o : nextafter(o, rand_r(seed) % 2 ? INFINITY : -INFINITY);
  double ts = rand_r(seed) % 3 == 0 ? s : nextafter(s, rand_r(seed) % 2 ? INFINITY : -INFINITY);
  double ft = tune_strength(h, q->pen, to), fs = tune_strength(h, q->pen, ts);
  if (isnan(ft) || isnan(fs)) return 0;
  q->ft = ft;
  *fsv = fs;
  if (rand_r(seed) % 2) s = -s;
  x[0] = s; x[3] = 0.0; x[1] = h + s; x[2] = h;
  y[0] = o; y[3] = 0.0; y[1] = o; y[2] = 0.0;
  return 1;
}

/* joint_force_fast4 against joint_force, bit for bit, on random joints of every law, damage
 * model, floor and hreg, with scaled strengths and shear strengths off their initial value;
 * openings and slips straddle the peaks (exact_lane: by one ulp), so lanes of one call mix
 * accepted and declined joints.  An accepted lane must be exactly joint_force's forces with no change of state; every
 * finite lane joint_force leaves undamaged must be accepted. */
START_TEST(test_fast4_bitwise)
{
  unsigned seed = 2024u;
  int nacc = 0, nrej = 0, nmixed = 0, nexact = 0;
  for (int trial = 0; trial < 20000; trial++) {
    YfJointProp p[4];
    double xs[4][4], ys[4][4], fsv[4];
    int isnan_lane[4] = {0, 0, 0, 0};
    for (int l = 0; l < 4; l++) {
      YfJointProp *q = &p[l];
      prop_law(q, all_laws[rand_r(&seed) % 5]);
      q->irreversible = rand_r(&seed) % 2;
      q->y2d_floor = rand_r(&seed) % 2;
      q->hreg = rand_r(&seed) % 3 ? 1e-10 : 0.0;
      double k = rand_r(&seed) % 2 ? 1.0 : urand(&seed, 0.3, 2.0); /* heterogeneity factor */
      q->ft *= k;
      q->fs *= k * (rand_r(&seed) % 4 ? 1.0 : urand(&seed, 0.2, 3.0));
      q->gf *= k;
      q->pen *= rand_r(&seed) % 2 ? 1.0 : urand(&seed, 0.1, 10.0);
      fsv[l] = rand_r(&seed) % 4 ? joint_fs_init(q) : urand(&seed, 0.5, 2.0) * q->fs;
      double h = urand(&seed, 1e-4, 2e-2), th = urand(&seed, -M_PI, M_PI);
      double cf = h / (h + q->hreg), op = 2.0 * h * q->ft / q->pen, sp = 2.0 * h * fsv[l] / q->pen;
      double ex = cos(th), ey = sin(th), nx = -ey, ny = ex, px = urand(&seed, -1, 1), py = urand(&seed, -1, 1);
      double oa = near_peak(&seed, op, cf), ob = near_peak(&seed, op, cf);
      double sa = near_peak(&seed, sp, cf), sb = near_peak(&seed, sp, cf);
      if (rand_r(&seed) % 3 == 0) ob = oa; /* the middle point at the peak too */
      if (rand_r(&seed) % 3 == 0) sb = sa;
      double dax = oa * nx + sa * ex, day = oa * ny + sa * ey, dbx = ob * nx + sb * ex, dby = ob * ny + sb * ey;
      double qx = px + h * ex, qy = py + h * ey;
      xs[l][0] = px + dax / 2; ys[l][0] = py + day / 2;
      xs[l][3] = px - dax / 2; ys[l][3] = py - day / 2;
      xs[l][1] = qx + dbx / 2; ys[l][1] = qy + dby / 2;
      xs[l][2] = qx - dbx / 2; ys[l][2] = qy - dby / 2;
      if (rand_r(&seed) % 2 && exact_lane(&seed, q, &fsv[l], xs[l], ys[l])) {
        nexact++;
        continue;
      }
      if (trial % 101 == 7 && l == 1) { /* a collapsed native joint: h = 0, hreg = 0 */
        q->hreg = 0.0;
        for (int c = 0; c < 4; c++) { xs[l][c] = px; ys[l][c] = py; }
      }
      if (trial % 103 == 5 && l == 2) { xs[l][rand_r(&seed) % 4] = NAN; isnan_lane[l] = 1; }
    }
    yf_v4 x[4], y[4], f[8];
    yf_v4 hreg = {p[0].hreg, p[1].hreg, p[2].hreg, p[3].hreg}, ft = {p[0].ft, p[1].ft, p[2].ft, p[3].ft};
    yf_v4 fs = {fsv[0], fsv[1], fsv[2], fsv[3]}, pen = {p[0].pen, p[1].pen, p[2].pen, p[3].pen};
    for (int c = 0; c < 4; c++) {
      x[c] = (yf_v4){xs[0][c], xs[1][c], xs[2][c], xs[3][c]};
      y[c] = (yf_v4){ys[0][c], ys[1][c], ys[2][c], ys[3][c]};
    }
    int acc = joint_force_fast4(x, y, &hreg, &ft, &fs, &pen, f);
    ck_assert_int_eq(acc & ~15, 0);
    int na = __builtin_popcount((unsigned)acc);
    if (na > 0 && na < 4) nmixed++;
    for (int l = 0; l < 4; l++) {
      double fr[8], fsr = fsv[l], dmg[3] = {0.0, 0.0, 0.0}, fl[8];
      YfJointInfo info;
      int nfail = joint_force(&p[l], xs[l], ys[l], &fsr, dmg, fr, &info);
      for (int c = 0; c < 8; c++) fl[c] = f[c][l];
      if (acc >> l & 1) {
        nacc++;
        ck_assert_msg(!isnan_lane[l], "trial %d lane %d: a NaN position accepted", trial, l);
        ck_assert_msg(!memcmp(fl, fr, sizeof fr), "trial %d lane %d: forces differ (%.17g vs %.17g ...)", trial, l,
                      fl[0], fr[0]);
        ck_assert(!memcmp(&fsr, &fsv[l], sizeof fsr));
        const double z3[3] = {0.0, 0.0, 0.0};
        ck_assert(!memcmp(dmg, z3, sizeof z3));
        ck_assert(info.zmax == 0.0 && nfail == 0 && info.mode == YF_JMODE_NONE);
      } else {
        nrej++;
        ck_assert_msg(isnan_lane[l] || info.zmax > 0.0, "trial %d lane %d: undamaged joint declined", trial, l);
      }
    }
  }
  ck_assert_int_gt(nacc, 10000);
  ck_assert_int_gt(nrej, 10000);
  ck_assert_int_gt(nmixed, 5000);
  ck_assert_int_gt(nexact, 10000);
}
END_TEST

Suite *joint_law_suite(void)
{
  Suite *s = suite_create("joint_law");
  TCase *tc;
  const int nl = (int)(sizeof all_laws / sizeof *all_laws);

  tc = tcase_create("softening curves");
  tcase_add_test(tc, test_soft_ends_and_area);
  tcase_add_test(tc, test_table_matches_gsl_linear);
  suite_add_tcase(s, tc);

  tc = tcase_create("quasi-static failure energy");
  tcase_set_timeout(tc, 30);
  tcase_add_loop_test(tc, test_mode_I_energy, 0, nl);
  tcase_add_loop_test(tc, test_mode_II_energy, 0, nl);
  tcase_add_test(tc, test_floor_active);
  suite_add_tcase(s, tc);

  tc = tcase_create("point values");
  tcase_add_loop_test(tc, test_compression_penalty, 0, nl);
  tcase_add_test(tc, test_mixed_mode_point);
  tcase_add_test(tc, test_three_points_and_failure_rule);
  suite_add_tcase(s, tc);

  tc = tcase_create("invariance and equilibrium");
  tcase_add_test(tc, test_rigid_motion);
  tcase_add_test(tc, test_equilibrium_random);
  suite_add_tcase(s, tc);

  tc = tcase_create("damage memory");
  tcase_add_test(tc, test_reversible_retraces);
  tcase_add_loop_test(tc, test_irreversible_secant, 0, nl);
  tcase_add_loop_test(tc, test_irreversible_monotone_walk, 0, nl);
  suite_add_tcase(s, tc);

  tc = tcase_create("Mohr-Coulomb");
  tcase_add_test(tc, test_mohr_coulomb);
  suite_add_tcase(s, tc);

  tc = tcase_create("four joints at once");
  tcase_add_test(tc, test_fast4_bitwise);
  suite_add_tcase(s, tc);

  tc = tcase_create("property checks");
  tcase_add_test(tc, test_prop_check);
  suite_add_tcase(s, tc);
  return s;
}
