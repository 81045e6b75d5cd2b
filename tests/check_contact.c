/* check_contact.c: contact in the scene (contact.c) checked against the physics it must obey:
 * momentum and energy of an elastic impact, Coulomb's law on an incline, the penalty's resting
 * penetration and its long-time stability, no missed couple for a fast body, action = reaction
 * in a dense pack, bitwise-identical results for 1 and 2 threads, and the deck interface. */
#include <check.h>
#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "contact.h"
#include "joint.h"
#include "run.h"
#include "summary.h"
#include "yftest.h"

static void quiet(void) { (void)!freopen("/dev/null", "w", stdout); }

/* Mass-weighted state of the nodes of group g. */
typedef struct {
  double m, px, py, x, y, ke;
  double xmin, xmax, ymin, ymax;
} Stat;

static Stat gstat(YfSim *s, const char *g) {
  YfModel *md = &s->model;
  int gi = model_group(md, g, 0);
  ck_assert_int_ge(gi, 0);
  Stat r = {0, 0, 0, 0, 0, 0, INFINITY, -INFINITY, INFINITY, -INFINITY};
  const YfNodes *n = &md->node;
  for (int i = 0; i < n->n; i++) {
    if (!(n->gmask[i] >> gi & 1) || !(n->m[i] > 0)) continue;
    r.m += n->m[i];
    r.px += n->m[i] * n->vx[i];
    r.py += n->m[i] * n->vy[i];
    r.x += n->m[i] * n->x[i];
    r.y += n->m[i] * n->y[i];
    r.ke += 0.5 * n->m[i] * (n->vx[i] * n->vx[i] + n->vy[i] * n->vy[i]);
    if (n->x[i] < r.xmin) r.xmin = n->x[i];
    if (n->x[i] > r.xmax) r.xmax = n->x[i];
    if (n->y[i] < r.ymin) r.ymin = n->y[i];
    if (n->y[i] > r.ymax) r.ymax = n->y[i];
  }
  r.x /= r.m;
  r.y /= r.m;
  return r;
}

/* ------------------------------------------------------------------ head-on impact */

/* Two elastic blocks 0.1 x 0.05 m (8 x 4 cells, h = 12.5 mm), E = 1e8 Pa, nu = 0.25, rho = 1000,
 * at +3 and -1 m/s, no damping; friction 0.3 (it must not act head-on).  Returns the largest
 * momentum error over the impact relative to sum m|v|, the smallest K + strain after separation
 * and the rigid-body kinetic energy after separation, both over the initial kinetic energy, and
 * the largest |K + strain + contact - K0| / K0 during the impact (the thermo's Balance). */
typedef struct {
  double dP, emech, krigid, bal;
  long sep;
  char limiter[96];
} Impact;

static Impact impact(const char *pen) {
  char deck[1024];
  snprintf(deck, sizeof deck,
           "material m elastic rho 1000 E 1e8 nu 0.25 plane_strain pen_n %s friction 0.3\n"
           "mesh rect a m 0 0 0.1 0.05 8 4\nmesh rect b m 0.101 0 0.201 0.05 8 4\n"
           "velocity a set 3 0\nvelocity b set -1 0\ncontact pair a b\ntimestep auto\nrun 0\n", pen);
  YfSim *s = yft_run(deck);
  Impact r = {0, INFINITY, 0, 0, -1, ""};
  snprintf(r.limiter, sizeof r.limiter, "%s", s->dt_limiter);
  Stat a0 = gstat(s, "a"), b0 = gstat(s, "b");
  double P0 = a0.px + b0.px, scale = fabs(a0.px) + fabs(b0.px), K0 = a0.ke + b0.ke;
  int touched = 0;
  for (int k = 0; k < 2000 && r.sep < 0; k++) {
    run_steps(s, 5);
    Stat a = gstat(s, "a"), b = gstat(s, "b");
    if (fabs(a.px + b.px - P0) > r.dP) r.dP = fabs(a.px + b.px - P0);
    run_energies(s);
    double bal = fabs(s->energy.kinetic + s->energy.strain + s->energy.contact - K0);
    if (bal > r.bal) r.bal = bal;
    if (a.xmax > b.xmin) touched = 1;
    if (touched && b.xmin > a.xmax + 1e-4 && s->energy.contact == 0.0) r.sep = s->step;
  }
  ck_assert_msg(r.sep > 0, "blocks did not touch and separate");
  for (int k = 0; k < 100; k++) { /* free flight: vibration exchanges K and strain energy */
    run_steps(s, 10);
    run_energies(s);
    Stat a = gstat(s, "a"), b = gstat(s, "b");
    if (fabs(a.px + b.px - P0) > r.dP) r.dP = fabs(a.px + b.px - P0);
    if (s->energy.kinetic + s->energy.strain < r.emech) r.emech = s->energy.kinetic + s->energy.strain;
  }
  Stat a = gstat(s, "a"), b = gstat(s, "b");
  r.krigid = (0.5 * a.px * a.px / a.m + 0.5 * b.px * b.px / b.m) / K0;
  r.emech /= K0;
  r.dP /= scale;
  r.bal /= K0;
  return r;
}

/* Penalty 10 x E (as the Y2D decks): the contact is stiffer than the blocks, so the impact leaves
 * elastic vibration in them (about 17% of the energy here, a property of the 2D blocks, not a
 * loss).  Momentum: contact forces are equal and opposite couple by couple, so the total can
 * only change by round-off: 1e-10 relative.  Energy: nothing is lost at the contact, kinetic +
 * strain after separation >= 98% of the initial kinetic energy, and the Balance (K + strain +
 * contact energy) stays within 5% during the impact (the contact energy is the kernel's estimate,
 * exact for the flat penetration of one edge, not at the blocks' corners).  The contact penalty sets the time step. */
START_TEST(test_headon_stiff) {
  quiet();
  Impact r = impact("1e9");
  fprintf(stderr, "headon stiff: dP %.3g, (K+S)/K0 after %.5f, rigid K/K0 %.4f, balance %.4f, separated at %ld, dt by %s\n",
          r.dP, r.emech, r.krigid, r.bal, r.sep, r.limiter);
  ck_assert_double_le(r.dP, 1e-10);
  ck_assert_double_ge(r.emech, 0.98);
  ck_assert_double_le(r.emech, 1.02);
  ck_assert_double_le(r.bal, 0.05);
  ck_assert_msg(strstr(r.limiter, "contact penalty") != NULL, "limiter: %s", r.limiter);
}
END_TEST

/* Penalty 3e5 Pa: contact stiffness 6 p / h x 0.05 m = 7.2e6 N/m^2 per metre of thickness, so
 * the contact lasts pi sqrt(m_red / k) = 1.9 ms, 6 x the blocks' wave transit (0.29 ms): the
 * blocks bounce as rigid bodies and the rigid-body kinetic energy after separation is >= 98% of
 * the initial (elastic restitution through the penalty). */
START_TEST(test_headon_kinetic_restitution) {
  quiet();
  Impact r = impact("3e5");
  fprintf(stderr, "headon soft: dP %.3g, (K+S)/K0 after %.5f, rigid K/K0 %.4f, balance %.4f\n", r.dP, r.emech,
          r.krigid, r.bal);
  ck_assert_double_le(r.dP, 1e-10);
  ck_assert_double_ge(r.krigid, 0.98);
  ck_assert_double_le(r.krigid, 1.0 + 1e-3);
}
END_TEST

/* ------------------------------------------------------------------ incline with friction */

/* A 0.05 x 0.05 m block (4 x 4 cells) on a fixed base 0.4 m long; the slope is a tilted gravity
 * vector.  First the block settles under the normal component with mass damping; then damping is
 * switched off and the tangential component applied. */
static YfSim *incline_scene(double slope_deg, double mu) {
  char deck[2048];
  double g = 9.81, th = slope_deg * M_PI / 180.0;
  snprintf(deck, sizeof deck,
           "material m elastic rho 1000 E 1e8 nu 0.25 plane_strain pen_n 1e9 pen_t 1e9 friction %g\n"
           "mesh rect base m 0 -0.02 0.4 0 32 2\nmesh rect blk m 0.05 0 0.1 0.05 4 4\n"
           "fix hold base fixed xy\ncontact pair blk base\ntimestep auto\n"
           "gravity 0 %.17g\ndamping mass 3e4\nrun 3000\n",
           mu, -g * cos(th));
  YfSim *s = yft_run(deck);
  s->mass_damping = 0.0;
  s->gx = g * sin(th);
  return s;
}

/* tan(phi) = 0.5 > tan(20 deg) = 0.364: Coulomb says the block stays.  It can only move by the
 * elastic compliance of the tangential penalty and of the block, i.e. ring around a fixed offset:
 * over 40 ms (frictionless it would slide 2.7 mm) the displacement stays below 2% of the
 * frictionless slide, and its largest value in the second 20 ms is not larger than in the first
 * (no creep; 5% allowance for the ringing's phase). */
START_TEST(test_incline_sticks) {
  quiet();
  YfSim *s = incline_scene(20.0, 0.5);
  Stat b0 = gstat(s, "blk");
  double t0 = s->time, T = 0.04, max1 = 0, max2 = 0;
  long n = (long)(T / s->dt), chunk = 100;
  for (long k = 0; k < n; k += chunk) {
    run_steps(s, chunk);
    double u = fabs(gstat(s, "blk").x - b0.x);
    if (s->time - t0 < 0.5 * T) { if (u > max1) max1 = u; }
    else if (u > max2) max2 = u;
  }
  double free_d = 0.5 * 9.81 * sin(20 * M_PI / 180) * (s->time - t0) * (s->time - t0);
  fprintf(stderr, "incline stick: max offset %.3g m then %.3g m (frictionless slide %.3g m)\n", max1, max2, free_d);
  ck_assert_double_le(max2, 0.02 * free_d);
  ck_assert_double_le(max2, 1.05 * max1);
}
END_TEST

/* tan(phi) = 0.2 < tan(30 deg): the block slides with a = g (sin 30 - 0.2 cos 30) = 3.206 m/s^2;
 * measured from the mean velocity over 20 ms of sliding, within 2%. */
START_TEST(test_incline_slides) {
  quiet();
  double th = 30 * M_PI / 180;
  YfSim *s = incline_scene(30.0, 0.2);
  run_steps(s, (long)(0.005 / s->dt)); /* the tangential spring loads up, then slides */
  Stat b1 = gstat(s, "blk");
  double t1 = s->time;
  run_steps(s, (long)(0.02 / s->dt));
  Stat b2 = gstat(s, "blk");
  double acc = (b2.px / b2.m - b1.px / b1.m) / (s->time - t1);
  double expect = 9.81 * (sin(th) - 0.2 * cos(th));
  fprintf(stderr, "incline slide: a %.6f m/s^2, expected %.6f (%.4f%%), slid %.3g m\n", acc, expect,
          100 * (acc / expect - 1), b2.x - b1.x);
  ck_assert_double_eq_tol(acc, expect, 0.02 * expect);
}
END_TEST

/* ------------------------------------------------------------------ resting block */

/* Block 0.05 x 0.05 m (2 x 2 cells, h = 25 mm) on a base 0.1 x 0.025 m (4 x 1 cells) whose
 * bottom is held, gravity 9.81.  Penalty p = 1e9 Pa.  A flat overlap delta of an edge gives a
 * pressure 3 p delta / h from each direction (ALGORITHMS 6.3 with P = delta / h: block edges in
 * base triangles and base edges in block triangles), so the weight rho g H = 490.5 Pa is carried
 * at delta = rho g H / (3 p (1/h_block + 1/h_base)) = 2.04e-9 m.  The mean overlap under the
 * block must be within 30% of that (the pressure under a flat punch is not uniform).  Then,
 * after settling with mass damping, 1e5 undamped steps: the total energy K + strain + contact -
 * work of gravity may not drift by more than 1% of the contact energy stored at rest
 * (W delta / 2), and the kinetic energy of the last 10^4 steps stays below that of the first. */
START_TEST(test_resting_penetration_no_jitter) {
  quiet();
  YfSim *s = yft_run("material m elastic rho 1000 E 1e8 nu 0.25 plane_strain pen_n 1e9 friction 0.3\n"
                     "mesh rect base m 0 -0.025 0.1 0 4 1\nmesh rect blk m 0.025 0 0.075 0.05 2 2\n"
                     "region bot box -1 -1 1 -0.0249\ngroup bot node region bot\nfix hold bot fixed xy\n"
                     "contact pair blk base\ntimestep auto\ngravity 0 -9.81\ndamping mass 2e4\nrun 20000\n");
  /* overlap: mean height of the base's top nodes under the block minus the block's bottom nodes */
  YfNodes *n = &s->model.node;
  int gb = model_group(&s->model, "blk", 0), gs = model_group(&s->model, "base", 0);
  double ytop = 0, ybot = 0;
  int ct = 0, cb = 0;
  for (int i = 0; i < n->n; i++) {
    if (fabs(n->y0[i]) > 1e-12 || n->x0[i] < 0.025 - 1e-9 || n->x0[i] > 0.075 + 1e-9) continue;
    if (n->gmask[i] >> gs & 1) { ytop += n->y[i]; ct++; }
    if (n->gmask[i] >> gb & 1) { ybot += n->y[i]; cb++; }
  }
  ck_assert_int_eq(ct, 3);
  ck_assert_int_eq(cb, 3);
  double delta = ytop / ct - ybot / cb, expect = 1000 * 9.81 * 0.05 / (3e9 * (1 / 0.025 + 1 / 0.025));
  double W = 1000 * 9.81 * 0.05 * 0.05, Ec = 0.5 * W * expect;
  s->mass_damping = 0.0;
  run_energies(s);
  double e0 = s->energy.kinetic + s->energy.strain + s->energy.contact, k_first = 0, k_last = 0, drift = 0;
  double g0 = 0;
  for (int i = 0; i < n->n; i++) g0 += n->m[i] * -9.81 * (n->y[i] - n->y0[i]);
  for (int k = 0; k < 100; k++) {
    run_steps(s, 1000);
    run_energies(s);
    double gw = 0;
    for (int i = 0; i < n->n; i++) gw += n->m[i] * -9.81 * (n->y[i] - n->y0[i]);
    double e = s->energy.kinetic + s->energy.strain + s->energy.contact - (gw - g0);
    if (fabs(e - e0) > drift) drift = fabs(e - e0);
    if (k < 10 && s->energy.kinetic > k_first) k_first = s->energy.kinetic;
    if (k >= 90 && s->energy.kinetic > k_last) k_last = s->energy.kinetic;
  }
  fprintf(stderr, "resting: overlap %.4g m, predicted %.4g m (ratio %.3f); energy drift %.3g of Ec %.3g; "
          "K first %.3g last %.3g\n", delta, expect, delta / expect, drift / Ec, Ec, k_first, k_last);
  ck_assert_double_eq_tol(delta, expect, 0.3 * expect);
  ck_assert_double_le(drift, 0.01 * Ec);
  ck_assert_double_le(k_last, k_first + 1e-6 * Ec);
}
END_TEST

Suite *contact_suite(void) {
  Suite *s = suite_create("contact");
  TCase *t = tcase_create("physics");
  tcase_set_timeout(t, 120);
  tcase_add_test(t, test_headon_stiff);
  tcase_add_test(t, test_headon_kinetic_restitution);
  tcase_add_test(t, test_incline_sticks);
  tcase_add_test(t, test_incline_slides);
  tcase_add_test(t, test_resting_penetration_no_jitter);
  suite_add_tcase(s, t);
  return s;
}
