/* joint_law.h: the cohesive joint element of Y2D as a pure kernel (ALGORITHMS.md 3), plus
 * yfdem's extra softening laws.
 *
 * A joint is four nodes on a shared edge of two triangles A and B.  joint_force() turns their
 * current positions and the joint's small state (current shear strength, optional damage memory)
 * into eight nodal force components; it allocates nothing, does no I/O and touches nothing but its
 * arguments, so joint.c can call it from any thread on any slice of joints.
 *
 * Laws (sigma/f_t = g(z) beyond the peak, z = (o - o_p)/o_t in pure mode I):
 *   YF_SOFT_MUNJIZA     Y2D's curve f(z) with o_t = 3 G/f_t: reproduces the book exactly when
 *                       y2d_floor = 1 and irreversible = 0.  It dissipates 3 I_f G beyond the peak,
 *                       I_f = YF_MUNJIZA_AREA, i.e. 1.15892 G (see joint_law.c); y2d_floor = 0 is
 *                       the Y-Geo rule o_t = 3 G/f_t without the 2 o_p floor.
 *   YF_SOFT_MUNJIZA_GF  the same curve with o_t = G/(f_t I_f): area beyond the peak exactly G.
 *   YF_SOFT_LINEAR      g = 1 - z, o_t = 2 G/f_t.
 *   YF_SOFT_BILINEAR    kink at (z1, s1); defaults z1 = 2/9, s1 = 1/3 (Petersson's concrete curve:
 *                       f_t/3 at 0.8 G/f_t, zero at 3.6 G/f_t); o_t = G/(f_t (z1 + s1)/2).
 *   YF_SOFT_TABLE       piecewise linear through user points (w_i, s_i), w rescaled to [0, 1];
 *                       o_t = G/(f_t area of the normalised table).
 * Every yfdem law (all but YF_SOFT_MUNJIZA) puts exactly G under the softening branch unless the
 * floor o_t >= 2 o_p (y2d_floor = 1, Y2D's guard against a softening branch shorter than the
 * pre-peak one) lengthens it.  Shear uses the same g with f_s, s_p, s_t in place of f_t, o_p, o_t.
 *
 * Units: SI, 2D per unit thickness: stresses Pa, openings m, forces N/m, energies J/m^2 per unit
 * joint length.
 */
#ifndef YF_JOINT_LAW_H
#define YF_JOINT_LAW_H
#include <math.h>
#include <stddef.h>
#include "yfvec.h"

enum { YF_SOFT_MUNJIZA = 0, YF_SOFT_MUNJIZA_GF, YF_SOFT_LINEAR, YF_SOFT_BILINEAR, YF_SOFT_TABLE,
       YF_SOFT_NLAW };

/* Failure mode reported by joint_force (at the most damaged sampling point). */
enum { YF_JMODE_NONE = 0, YF_JMODE_I, YF_JMODE_II, YF_JMODE_MIXED };

#define YF_JOINT_TAB_MAX 32 /* points of a tabulated softening curve */

/* Integral of Munjiza's f(z) over z = 0..1 (derived analytically in joint_law.c). */
#define YF_MUNJIZA_AREA 0.38630729474394262516

/* One joint property set.  Plain data: copy freely (the table lives inside). */
typedef struct {
  double ft, fs, gf, pen; /* tensile, shear strength [Pa], fracture energy [J/m^2], penalty [Pa] */
  double coh, phi;        /* Mohr-Coulomb cohesion [Pa] and friction coefficient; active if coh > 0 */
  int law;                /* YF_SOFT_*                                                          */
  int y2d_floor;          /* 1: o_t = max(2 o_p, law length) as Y2D; 0: the law's length alone   */
  int irreversible;       /* 0: Y2D, no damage memory; 1: damage never decreases, secant unloading */
  double bl_z, bl_s;      /* bilinear kink: fraction of o_t, fraction of f_t                      */
  int ntab;               /* tabulated law: set only through joint_prop_set_table()              */
  double tab_z[YF_JOINT_TAB_MAX]; /* normalised opening, 0 .. 1, strictly increasing          */
  double tab_s[YF_JOINT_TAB_MAX]; /* stress / f_t, 1 .. 0                                     */
  double tab_area;        /* integral of the normalised table                                    */
  double hreg;            /* [m] added to the joint length in its unit tangent e/(h + hreg): Y2D's
                             absolute 1e-10 (default, read_y2d); 0 for native decks, whose answers
                             must not depend on the unit of length (a 1e-5 m joint would be off by 1e-5) */
} YfJointProp;

/* What one evaluation saw (optional output of joint_force). */
typedef struct {
  double h;          /* current joint length [m]                                            */
  double open_mean;  /* mean normal opening (o_a + o_b)/2 [m], > 0 when A moves away from B     */
  double slip_mean;  /* mean slip (s_a + s_b)/2 [m], signed along e1                           */
  double zmax;       /* largest damage of the three sampling points after this call            */
  int mode;          /* YF_JMODE_* of the most damaged point: I if the normalised opening beyond
                        the peak is >= 9x the slip beyond the peak, II for the converse, else mixed;
                        NONE when zmax = 0                                                       */
} YfJointInfo;

/* Y2D-like defaults: Munjiza law, book floor, reversible, concrete of the seed paper
 * (f_t = f_s = 3.15 MPa, G = 300 J/m^2, p = 1e11 Pa), no Mohr-Coulomb, Petersson kink. */
void joint_prop_default(YfJointProp *p);
/* 1 if p is usable; else 0 and a one-line reason in why[0..n-1]. */
int joint_prop_check(const YfJointProp *p, char *why, size_t n);
/* Fill the tabulated law from n points (w_i opening in any unit, s_i stress/f_t): w_0 = 0, w
 * strictly increasing, s_0 = 1, s_{n-1} = 0, 0 <= s_i <= 1, 2 <= n <= YF_JOINT_TAB_MAX.  Sets law =
 * YF_SOFT_TABLE.  Returns 1, or 0 with a reason (p unchanged). */
int joint_prop_set_table(YfJointProp *p, int n, const double *w, const double *s, char *why,
                         size_t nwhy);
/* Shear strength a joint starts with (ALGORITHMS 3.2): fs, or coh if fs <= 0. [Pa] */
double joint_fs_init(const YfJointProp *p);

/* Normalised softening curve g(z) of the law, z in [0, 1]: g(0) = 1, g(1) = 0. */
double joint_soft(const YfJointProp *p, double z);
/* Integral of g over [0, 1]. */
double joint_soft_area(const YfJointProp *p);
/* Characteristic lengths for joint length h and shear strength fs [m]: peak opening o_p, softening
 * length o_t (stress 0 at o_p + o_t), and the same for slip.  Any pointer may be NULL. */
void joint_lengths(const YfJointProp *p, double h, double fs, double *op, double *ot, double *sp,
                   double *st);
/* Energy per unit joint length [J/m^2] dissipated by opening a joint of length h in pure mode I
 * until it fails: the quadratic pre-peak branch (2/3 f_t o_p) plus the softening area f_t o_t I_g.
 * joint_law_area_shear: the same in pure slip with the initial shear strength. */
double joint_law_area(const YfJointProp *p, double h);
double joint_law_area_shear(const YfJointProp *p, double h);

/* Forces of one joint (ALGORITHMS 3.1-3.7).
 * x[4], y[4]: current positions of nodes 0..3 [m] (0, 1 on triangle A: edge p->q in A's CCW order;
 *   3, 2: B's copies of p, q).  The joint length h must be > 0 (as in Y2D, o_p = 0 divides).
 *   As in Y2D the tangent is e/(h + 1e-10) and the normal its rotation, so both are shorter than
 *   1 by h/(h + 1e-10): measured o, s and the force vectors carry that factor.
 * fs_state: in/out current shear strength [Pa] (Mohr-Coulomb memory; start with joint_fs_init);
 *   NULL: use joint_fs_init(p) and keep nothing.
 * dmg: in/out, 3 doubles: largest damage reached at end a, middle, end b (start at 0); read and
 *   written only when p->irreversible (may be NULL otherwise).
 * f[8]: out, fx0, fy0, fx1, fy1, fx2, fy2, fx3, fy3 [N/m].
 * info: optional out.
 * Returns the number of failed sampling points (z >= 1); >= 2 means the joint is broken (3.7):
 * the caller still applies f of this call and drops the joint afterwards. */
int joint_force(const YfJointProp *p, const double x[4], const double y[4], double *fs_state,
                double *dmg, double f[8], YfJointInfo *info);

#define YF_JOINT_BROKEN(nfail) ((nfail) >= 2)

/* What joint_force derives from the property set alone (no geometry, no state): computed once
 * per set by joint_pre_init, so the step loop does not redo it for every joint. */
typedef struct {
  double ot;  /* softening length of f_t before the 2 o_p floor [m]                   */
  double fs0; /* initial shear strength joint_fs_init(p) [Pa]                            */
  double st0; /* softening length of fs0 before the floor [m] (used while fs = fs0)      */
} YfJointPre;
void joint_pre_init(const YfJointProp *p, YfJointPre *c);

/* The geometry of a joint (ALGORITHMS 3.1): all the law needs of the four positions. */
typedef struct {
  double h;            /* current length [m]                                          */
  double e1x, e1y;     /* tangent e/(h + hreg); the normal is (-e1y, e1x)             */
  double po[3], ps[3]; /* opening and slip at end a, middle, end b [m]                */
} YfJointGeom;

/* 3.1 in the document's order of operations (inline: the step loop computes the geometry of a
 * batch of joints first, a short loop whose square roots and divisions overlap; then the law). */
static inline void joint_geometry_inline(double hreg, const double x[4], const double y[4], YfJointGeom *g)
{
  double ex = ((x[1] + x[2]) - (x[0] + x[3])) / 2.0;
  double ey = ((y[1] + y[2]) - (y[0] + y[3])) / 2.0;
  double h = sqrt(ex * ex + ey * ey);
  double hr = h + hreg;
  if (!(hr > 0.0)) hr = 1.0; /* a collapsed joint (h = 0, native): no direction, no force */
  double e1x = ex / hr, e1y = ey / hr;
  double nx = -e1y, ny = e1x;
  double dax = x[0] - x[3], day = y[0] - y[3];
  double dbx = x[1] - x[2], dby = y[1] - y[2];
  double sa = dax * e1x + day * e1y, sb = dbx * e1x + dby * e1y;
  double oa = dax * nx + day * ny, ob = dbx * nx + dby * ny;
  g->h = h;
  g->e1x = e1x;
  g->e1y = e1y;
  g->po[0] = oa; g->po[1] = (oa + ob) / 2.0; g->po[2] = ob;
  g->ps[0] = sa; g->ps[1] = (sa + sb) / 2.0; g->ps[2] = sb;
}
void joint_geometry(double hreg, const double x[4], const double y[4], YfJointGeom *g);

/* ---- the common case, four joints at once ----
 * In a running scene nearly every joint is intact and before its peak at all three sampling
 * points (o <= o_p and |s| <= s_p: damage z = 0, g(z) = 1 for every law).  Then joint_force
 * reduces to the geometry, the pre-peak quadratics and the nodal weights, with no dependence on
 * the law, the floor, o_t, s_t or the damage memory.  joint_force_fast4 does exactly that for four
 * joints, one per lane, with each lane doing joint_force's IEEE operations in joint_force's order
 * (geometry of joint_geometry_inline, then law_core's z = 0 branch), so a lane it accepts has the
 * bits joint_force would give.  The caller may offer only joints for which joint_force would not
 * touch the state: no Mohr-Coulomb (coh == 0, so fs stays) and, if irreversible, all three
 * damage values 0 (then z = 0 >= D keeps them 0 and the secant branch is not taken). */
/* Lane l = joint l: x[c], y[c]: positions of nodes 0..3 (joint_force's x, y) [m]; hreg: the
 * property's hreg [m]; ft: tensile strength as joint_force sees it (p->ft, scaled) [Pa]; fs: the
 * current shear strength (*fs_state) [Pa]; pen: penalty [Pa].  (Pointers: a 32-byte vector passed
 * by value would change the ABI between a function's AVX and default builds.)
 * Forces f[c] (c as joint_force's f[8]) of the four lanes; returns the lanes it accepts as bits
 * (bit l set: f[.][l] is joint_force's, the joint stays undamaged, fs and damage unchanged, zmax
 * 0, no failure; clear: some sampling point is past its peak, or a value is NaN: the lane's f is
 * meaningless, use joint_force_geom). */
/* The geometry half of joint_force_fast4 (joint_geometry_inline per lane). */
typedef struct {
  yf_v4 h, e1x, e1y, po[3], ps[3];
} YfJointGeom4;

static inline __attribute__((always_inline)) void
joint_geometry4(const yf_v4 x[4], const yf_v4 y[4], const yf_v4 *hreg, YfJointGeom4 *g)
{
  const yf_v4 zero = {0.0, 0.0, 0.0, 0.0}, one = {1.0, 1.0, 1.0, 1.0};
  /* 3.1 geometry: joint_geometry_inline term by term */
  yf_v4 ex = ((x[1] + x[2]) - (x[0] + x[3])) / 2.0;
  yf_v4 ey = ((y[1] + y[2]) - (y[0] + y[3])) / 2.0;
  yf_v4 h = ex * ex + ey * ey;
  yf_sqrt4(&h);
  yf_v4 hr = h + *hreg;
  hr = YF_SEL4(hr > zero, hr, one);
  yf_v4 e1x = ex / hr, e1y = ey / hr;
  yf_v4 nx = -e1y, ny = e1x;
  yf_v4 dax = x[0] - x[3], day = y[0] - y[3];
  yf_v4 dbx = x[1] - x[2], dby = y[1] - y[2];
  yf_v4 sa = dax * e1x + day * e1y, sb = dbx * e1x + dby * e1y;
  yf_v4 oa = dax * nx + day * ny, ob = dbx * nx + dby * ny;
  g->h = h;
  g->e1x = e1x;
  g->e1y = e1y;
  g->po[0] = oa; g->po[1] = (oa + ob) / 2.0; g->po[2] = ob;
  g->ps[0] = sa; g->ps[1] = (sa + sb) / 2.0; g->ps[2] = sb;
}

/* The law half of joint_force_fast4 (law_core's z = 0 branch per lane); returns the accepted lanes. */
static inline __attribute__((always_inline)) int
joint_law4(const YfJointGeom4 *g, const yf_v4 *ft_, const yf_v4 *fs_, const yf_v4 *pen, yf_v4 f[8])
{
  const yf_v4 zero = {0.0, 0.0, 0.0, 0.0};
  const yf_v4 h = g->h, e1x = g->e1x, e1y = g->e1y, nx = -e1y, ny = e1x;
  /* 3.2 peak opening and slip, nodal weights h/6, h/3 (law_core's packed pairs, lane-wise) */
  const yf_v4 ft = *ft_, fs = *fs_;
  yf_v4 op = 2.0 * h * ft / *pen, sp = 2.0 * h * fs / *pen;
  yf_v4 w0 = h / 6.0, w1 = h / 3.0;
  yf_v4l ok = {-1, -1, -1, -1};
  yf_v4 qx[3], qy[3];
  for (int k = 0; k < 3; k++) {
    yf_v4 o = g->po[k], s = g->ps[k], as = YF_ABS4(s);
    ok &= (o <= op) & (as <= sp); /* z = 0 at this point (NaN: not accepted) */
    /* 3.4 with g = 1: ro = o/o_p, or the compression stress 2 o f_t/o_p; rs = |s|/s_p */
    yf_v4l neg = o < zero;
    yf_v4 ro = YF_SEL4(neg, 2.0 * o * ft, o) / op, rs = as / sp;
    yf_v4 sigma = YF_SEL4(neg, ro, (2.0 * ro - ro * ro) * ft);
    yf_v4 tau = (2.0 * rs - rs * rs) * fs;
    tau = YF_SEL4(s < zero, -tau, tau);
    qx[k] = tau * e1x + sigma * nx;
    qy[k] = tau * e1y + sigma * ny;
  }
  /* 3.6 nodal forces: A's nodes (0, 1) get -w q, B's (3, 2) +w q (w2 = w0) */
  f[0] = -w0 * qx[0] - w1 * qx[1];
  f[1] = -w0 * qy[0] - w1 * qy[1];
  f[2] = -w1 * qx[1] - w0 * qx[2];
  f[3] = -w1 * qy[1] - w0 * qy[2];
  f[4] = w1 * qx[1] + w0 * qx[2];
  f[5] = w1 * qy[1] + w0 * qy[2];
  f[6] = w0 * qx[0] + w1 * qx[1];
  f[7] = w0 * qy[0] + w1 * qy[1];
  return (int)((ok[0] & 1) | (ok[1] & 2) | (ok[2] & 4) | (ok[3] & 8));
}

static inline __attribute__((always_inline)) int
joint_force_fast4(const yf_v4 x[4], const yf_v4 y[4], const yf_v4 *hreg, const yf_v4 *ft, const yf_v4 *fs,
                  const yf_v4 *pen, yf_v4 f[8])
{
  YfJointGeom4 g;
  joint_geometry4(x, y, hreg, &g);
  return joint_law4(&g, ft, fs, pen, f);
}
/* joint_force in two halves: g = joint_geometry(p->hreg, x, y), c = joint_pre_init(p) (or of the
 * same property values); the same results, bit for bit. */
int joint_force_geom(const YfJointProp *p, const YfJointPre *c, const YfJointGeom *g, double *fs_state,
                     double *dmg, double f[8], YfJointInfo *info);

#endif
