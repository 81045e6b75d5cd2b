/* contact_pair.h: the narrow phase of triangle-to-triangle contact (ALGORITHMS.md 6).
 *
 * Munjiza's potential contact, as in Y2D: every edge of a contactor triangle that crosses a
 * target triangle is pushed out along its own outward normal by the integral of the target's
 * potential phi = 3 min_k beta_k over the part of the edge inside the target; a penalty
 * "spring" g per edge adds Coulomb friction; the reaction goes to the target's corners with the
 * barycentric weights of the contactor nodes, so momentum and angular momentum are conserved
 * (to round-off).  A couple (A, B) is evaluated in both directions: B as contactor on target A,
 * then A on B.  To mirror Y2D's summation order exactly, pass A = the triangle with the larger
 * index and B = the smaller one (Y2D evaluates the couple list's target, the smaller element,
 * first as contactor); any other convention changes results by round-off only.
 *
 * These are pure functions on plain numbers: no model, no allocation, no I/O.  Units: SI, 2D per
 * unit thickness.  Forces [N/m]; penalties [Pa]; the sliding memory g is Y2D's (m^2: a relative
 * tangential velocity dotted with the unnormalised edge vector, times dt) or, with the Coulomb
 * law, s = F_t / sqrt(k_t), the edge's tangential force over the square root of its stiffness
 * (0.5 s^2 L is the spring's energy [J/m]; see the laws below).
 */
#ifndef YF_CONTACT_PAIR_H
#define YF_CONTACT_PAIR_H
#include "model.h" /* YF_FRIC_*: the friction law is a material property */

#define YF_CONTACT_EPS 1e-10 /* barycentric tolerance of Y2D (dimensionless) */
/* Friction laws of a couple (the `law` argument of the kernels): YF_FRIC_Y2D or YF_FRIC_COULOMB,
 * a material's property (model.h):
 *   YF_FRIC_Y2D      Y2D's (ALGORITHMS 6.4): g += w dt with w the relative velocity dotted with
 *                    the unnormalised edge vector (g in m^2), F_t = p_t g capped at mu |F|; the
 *                    tangential force is p_t L^2 times the slip, so it depends on the unit of
 *                    length; g is kept while the edge is apart.  read_y2d decks.
 *   YF_FRIC_COULOMB  elastic-slip Coulomb: a tangential spring spread over the edge's contact
 *                    interval, stiffness k_t = 3 p_t (s_max - s_min) / h per metre of slip (the
 *                    normal law's with p_t for p_n; h = the target's height over its edge nearest
 *                    the interval's midpoint s_m), acting at s_m and fed by the slip rate there;
 *                    g is s = F_t / sqrt(k_t) (the spring's energy, 0.5 s^2 per unit L, is
 *                    kept when k_t follows a change of the interval), F_t = s sqrt(k_t) updated
 *                    F_t += k_t (w / L) dt and return-mapped onto |F_t| <= mu |F|; an edge that
 *                    is apart releases it (g = 0).  Unit-independent: k_t / k_n = p_t / p_n.
 *                    Native decks. */

#define YF_TRI_GEOM 16 /* doubles per triangle record: x[3] y[3] mx[3] my[3] D 1/D H2 (1 spare) */

/* Optional diagnostics of a kernel call, ADDED to (the caller zeroes them). */
typedef struct {
  int nedge;     /* contactor edges that produced a force (s_min < s_max)                    */
  double fn;     /* sum over those edges of the normal force magnitude F L [N/m]              */
  double ft;     /* sum over those edges of the tangential force magnitude |F_t| L [N/m]       */
  double work_t; /* work of the tangential forces against the relative motion, sum F_t w dt
                    [J/m]; > 0 when friction takes energy from the motion (stick + slip)      */
  double dissip; /* frictional dissipation of this step: |F_t| |g_trial - g| on sliding edges
                    [J/m] (0 while sticking); a diagnostic (booked: work_c - spring)       */
  double energy; /* estimate of the normal penalty energy: sum over edges of
                    1.5 p_n L int h_k P(s)^2 ds, h_k = height of the target over the edge that
                    gives the minimum (exact for a flat penetration of one edge), plus the
                    friction springs' energy (spring below) [J/m]                             */
  /* The friction booking (contact.c), both laws: what the springs do not store is dissipated, i.e.
   * the centred work of their forces less the change of their energy.  The integrator moves a
   * node by (v_(n-1/2) + v_(n+1/2)) dt / 2 under the force of step n, so the work it books into
   * the kinetic energy is, summed by parts over the steps, sum_n (F_(n-1) + F_n) / 2 w_n dt
   * (w_n at the velocities v_(n-1/2) this kernel reads): each edge needs its force of the last
   * step, kept in gprev.  Booking F_n w_n dt instead (work_t) misses half the change of F
   * times the slip rate: a spring whose cap shrinks releases energy nobody books, and the
   * balance of an oblique impact lost 9 % of the energy given. */
  double *gprev; /* in/out, optional (NULL: none): F_t of each contactor edge at the last call,
                    as g (3 per direction, contact_pair_force: 6); 0 where an edge is apart.
                    Read for work_c only: the forces do not depend on it                       */
  double work_c; /* centred work of the friction springs' forces, sum 0.5 (F_t,prev + F_t) w dt,
                    F_t,prev from gprev (0 without it) [J/m]                                    */
  double spring; /* energy the springs hold after this call: Coulomb 0.5 s^2 L, Y2D 0.5 F_t^2 / p_t [J/m] */
} YfContactInfo;

/* One direction: contactor triangle C acting on target triangle T (ALGORITHMS 6.1-6.5).
 *   xt,yt,vxt,vyt: target corners (CCW) and velocities; xc,yc,vxc,vyc: the contactor's.
 *   pn, pt [Pa], mu: normal and tangential penalties and friction coefficient of the pair;
 *   law: YF_FRIC_Y2D or YF_FRIC_COULOMB (above).
 *   dt [s]: time step (friction memory increment).
 *   g[3]: in/out sliding memory of the contactor's edges (edge e from corner e to e+1); an edge
 *         not in contact keeps its value (Y2D law) or is zeroed (Coulomb law).
 *   ft[6], fc[6]: forces ADDED to the target's / contactor's corners (fx0, fy0, fx1, ...) [N/m].
 *   dmin2: in/out, lowered to the squared distance [m^2] recorded by each skipped edge (its
 *          start node to the target edge line with the smallest barycentric value).
 *   info: optional (NULL), added to.
 * Returns the number of contactor edges that produced a force (0..3).  Triangles with
 * non-positive area are ignored (return 0) instead of producing NaN. */
int contact_pair_dir(const double xt[3], const double yt[3], const double vxt[3], const double vyt[3],
                     const double xc[3], const double yc[3], const double vxc[3], const double vyc[3],
                     double pn, double pt, double mu, int law, double dt, double g[3],
                     double ft[6], double fc[6], double *dmin2, YfContactInfo *info);

/* One couple (A, B): B as contactor on target A (g[0..2]), then A on B (g[3..5]).
 *   g[6]: sliding memory of the couple, index = dir*3 + contactor edge (dir 0 = B on A).
 *   fa[6], fb[6]: forces ADDED to A's and B's corners [N/m].
 *   dmin2: out (set, not lowered): smallest squared node-to-edge-line distance [m^2] of the
 *          skipped edges of both directions, DBL_MAX if none; used for couple removal
 *          (ALGORITHMS 5: remove when the return is 0 and dmin2 > (2 buffer)^2).
 * Returns 1 if any edge of either direction produced a force, else 0.  An edge that passes the
 * skip tests but whose contact interval is empty counts as neither (it records no distance). */
int contact_pair_force(const double xa[3], const double ya[3], const double vxa[3], const double vya[3],
                       const double xb[3], const double yb[3], const double vxb[3], const double vyb[3],
                       double pn, double pt, double mu, int law, double dt, double g[6],
                       double fa[6], double fb[6], double *dmin2, YfContactInfo *info);

/* contact_pair_force on the couple's triangle records (contact_pair_geom of this step's corner
 * positions) instead of the corners: the same numbers, without recomputing the geometry. */
int contact_pair_force_rec(const double ra[YF_TRI_GEOM], const double vxa[3], const double vya[3],
                           const double rb[YF_TRI_GEOM], const double vxb[3], const double vyb[3],
                           double pn, double pt, double mu, int law, double dt, double g[6],
                           double fa[6], double fb[6], double *dmin2, YfContactInfo *info);
/* The portable version (what contact_pair_force_rec runs without AVX2), for the tests. */
int contact_pair_force_rec_any(const double ra[YF_TRI_GEOM], const double vxa[3], const double vya[3],
                               const double rb[YF_TRI_GEOM], const double vxb[3], const double vyb[3],
                               double pn, double pt, double mu, int law, double dt, double g[6],
                               double fa[6], double fb[6], double *dmin2, YfContactInfo *info);

/* ---- the screen: a couple whose edges all miss (the common case) without the full kernel ----
 * Most couples of a fracturing body are neighbours whose edges only meet at corners: every
 * contactor edge has both ends outside one target edge line (6.2), in both directions, so the
 * couple gives no force and only its removal distance matters.  The screen decides that from a
 * per-triangle record computed once per step, with the kernel's own arithmetic term by term, so
 * a couple it passes gets exactly what contact_pair_force would give (same dmin2 bits). */
/* The record of a triangle with corners x, y (CCW) [m]: corners, target edge normals m_k (6.1,
 * length = edge length), twice the area D [m^2], 1/D (NaN when D <= 0: the degenerate mark the
 * screen relies on) and H2 = D^2 / min_k |m_k|^2, the largest squared height [m^2]. */
void contact_pair_geom(const double x[3], const double y[3], double rec[YF_TRI_GEOM]);
/* The screen of couple (A, B) (records ra, rb; A as in contact_pair_force) against the removal
 * distance rem2 = (2 buffer)^2 [m^2].  Returns
 *   0  some edge is not skipped by the "both ends outside one target edge" test: the couple
 *      needs contact_pair_force;
 *   1  every edge of both directions is skipped (or a triangle is degenerate): no force, no
 *      change of friction memory, and contact_pair_force's dmin2 would be <= rem2 (keep);
 *   2  the same, with dmin2 > rem2 (Y2D drops the couple).
 * Decisions 1 and 2 are exactly contact_pair_force's (same arithmetic; "keep" is also decided
 * early by a bound: some edge's distance is at most a quarter of rem2, to a few ulps). */
int contact_pair_quiet(const double ra[YF_TRI_GEOM], const double rb[YF_TRI_GEOM], double rem2);
/* The portable version (plain x86-64 vectors) that contact_pair_quiet runs on a CPU without
 * AVX2; exposed so that the tests check both. */
int contact_pair_quiet_any(const double ra[YF_TRI_GEOM], const double rb[YF_TRI_GEOM], double rem2);

#endif
