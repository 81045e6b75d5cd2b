/* check_contact.c: contact in the scene (contact.c) checked against the physics it must obey:
 * momentum and energy of an elastic impact, Coulomb's law on an incline, the penalty's resting
 * penetration and its long-time stability, no missed couple for a fast body, action = reaction
 * in a dense pack, bitwise-identical results for 1 and 2 threads, and the deck interface. */
#include <check.h>
#include <hdf5.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "contact.h"
#include "energy.h"
#include "joint.h"
#include "run.h"
#include "threads.h"
#include "summary.h"
#include "y2d_model.h"
#include "y2d_read.h"
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

static Impact impact(const char *pen, double mu) {
  char deck[1024];
  snprintf(deck, sizeof deck,
           "material m elastic rho 1000 E 1e8 nu 0.25 plane_strain pen_n %s friction %g\n"
           "mesh rect a m 0 0 0.1 0.05 8 4\nmesh rect b m 0.101 0 0.201 0.05 8 4\n"
           "velocity a set 3 0\nvelocity b set -1 0\ncontact pair a b\ntimestep auto\nrun 0\n", pen, mu);
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
  Impact r = impact("1e9", 0.3);
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
 * the initial (elastic restitution through the penalty).  Frictionless: at a penalty E / 333 the
 * blocks overlap by millimetres, and the top and bottom edges that enter the other block rub
 * along the approach; with friction 0.3 the Coulomb law (whose tangential stiffness is the
 * normal one's) takes 3.5 % of the energy there (rigid K / K0 0.965), where Y2D's law, with its
 * p_t L^2 spring 1e-4 of that, hardly engaged. */
START_TEST(test_headon_kinetic_restitution) {
  quiet();
  Impact r = impact("3e5", 0.0);
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
 * elastic compliance of the tangential springs and of the block: over 40 ms (frictionless it
 * would slide 2.7 mm) the displacement stays below a micrometre (the "to the
 * micrometre"; Y2D's law rings at 2.6e-5 m).  Not asserted: it is not quite still.  The sudden
 * tangential load overshoots the cone (T/N up to 0.73 > 0.5) and the undamped ringing then
 * ratchets the block on by about 4e-8 m per 20 ms, accelerating (3.6e-7, 4.1e-7, ... 8.2e-7 m
 * over eight 20 ms windows): docs/VERIFICATION.md, sliding block near the cone. */
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
  ck_assert_double_le(max1, 1e-6);
  ck_assert_double_le(max2, 1e-6);
  ck_assert_double_le(max2, 0.02 * free_d);
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

/* ------------------------------------------------------------------ fast body, no missed couple */

/* A 20 mm square (2 x 2 cells) 2 mm above a fixed plate 4 mm thick, falling at 40 m/s and spinning
 * at 2000 rad/s (corner speed 68 m/s), frictionless.  The buffer (auto: 0.3 x 4 mm) is crossed
 * many times between searches.  The same scene searching at every step must give bitwise the
 * same state: a couple missing from the reused list would change the forces.  The body must
 * bounce off the plate, not pass it. */
static uint64_t fast_body(const char *mode, long *nsearch, double *vy_end, double *ymin) {
  char deck[1024];
  snprintf(deck, sizeof deck,
           "material m elastic rho 1000 E 1e9 nu 0.25 plane_strain pen_n 1e10\n"
           "mesh rect plate m 0 0 0.2 0.004 50 1\nfix hold plate fixed xy\n"
           "mesh rect bullet m 0.09 0.006 0.11 0.026 2 2\ncontact pair bullet plate\ncontact search %s\n"
           "timestep auto\nrun 0\n", mode);
  YfSim *s = yft_run(deck);
  YfNodes *n = &s->model.node;
  int gb = model_group(&s->model, "bullet", 0);
  for (int i = 0; i < n->n; i++)
    if (n->gmask[i] >> gb & 1) {
      double rx = n->x[i] - 0.1, ry = n->y[i] - 0.016, w = 2000;
      n->vx[i] = -w * ry;
      n->vy[i] = -40 + w * rx;
    }
  *ymin = INFINITY;
  for (int k = 0; k < 30; k++) {
    run_steps(s, 50);
    Stat b = gstat(s, "bullet");
    if (b.ymin < *ymin) *ymin = b.ymin;
  }
  *vy_end = gstat(s, "bullet").py / gstat(s, "bullet").m;
  *nsearch = contact_searches(s);
  return sim_state_hash(s);
}

START_TEST(test_fast_body_no_missed_couple) {
  quiet();
  long ns_t, ns_e;
  double vy_t, vy_e, ymin_t, ymin_e;
  uint64_t h_t = fast_body("travel", &ns_t, &vy_t, &ymin_t);
  uint64_t h_e = fast_body("every", &ns_e, &vy_e, &ymin_e);
  fprintf(stderr, "fast body: searches %ld (travel) vs %ld (every step), lowest point %.4g m, final vy %.3g m/s, "
          "hashes %016llx %016llx\n", ns_t, ns_e, ymin_t, vy_t, (unsigned long long)h_t, (unsigned long long)h_e);
  ck_assert_msg(h_t == h_e, "reusing the couple list changed the result");
  ck_assert_int_lt(10 * ns_t, ns_e); /* the list was really reused */
  ck_assert_double_gt(ymin_t, 0.004 - 0.001); /* stopped at the plate's surface (4 mm), overlap < 1 mm */
  ck_assert_double_gt(vy_t, 10.0);            /* and bounced */
}
END_TEST

/* ------------------------------------------------------------------ dense pack of fragments */

/* A 12 x 12-cell fracturing block with weak joints on a fixed floor, struck by a heavy hammer at
 * 20 m/s, friction 0.5: fragments, joined neighbours pressed together, sliding.  Every couple's
 * forces are equal and opposite (the reaction is spread with weights that sum to 1), so the sum
 * of all contact forces over the nodes vanishes to round-off: below 1e-12 of the largest nodal
 * contact force (round-off of ~1e4 terms of 1e-16 each), at every sampled step. */
static YfSim *pack_scene(void) {
  return yft_run("material m elastic rho 2000 E 1e9 nu 0.2 plane_strain pen_n 1e10 pen_t 1e10 friction 0.5 damping 0.1\n"
                 "material steel elastic rho 20000 E 2e10 nu 0.3 plane_strain pen_n 1e10 pen_t 1e10 friction 0.3\n"
                 "jointprop j ft 2e5 fs 2e5 gf 5 pen 1e10\n"
                 "mesh rect pack m 0 0 0.06 0.06 12 12 pattern alt\nfracture pack j\n"
                 "mesh rect floor m -0.01 -0.01 0.07 0 16 2\nfix hold floor fixed xy\n"
                 "mesh rect hammer steel 0.02 0.0605 0.04 0.0705 4 2\nvelocity hammer set 0 -20\n"
                 "contact self pack\ncontact pair pack floor\ncontact pair hammer pack\n"
                 "gravity 0 -9.81\ntimestep auto\nrun 0\n");
}

START_TEST(test_pack_forces_sum_to_zero) {
  quiet();
  YfSim *s = pack_scene();
  double worst = 0, fmax_all = 0;
  long maxpairs = 0;
  for (int k = 0; k < 30; k++) {
    run_steps(s, 40);
    const double *f = contact_node_forces(s);
    ck_assert_ptr_nonnull(f);
    double sx = 0, sy = 0, fmax = 0;
    for (int i = 0; i < s->model.node.n; i++) {
      sx += f[2 * i];
      sy += f[2 * i + 1];
      double a = hypot(f[2 * i], f[2 * i + 1]);
      if (a > fmax) fmax = a;
    }
    if (fmax > 0 && hypot(sx, sy) / fmax > worst) worst = hypot(sx, sy) / fmax;
    if (fmax > fmax_all) fmax_all = fmax;
    if (contact_pairs(s) > maxpairs) maxpairs = contact_pairs(s);
  }
  fprintf(stderr, "pack: |sum f| / max|f| <= %.3g, max nodal contact force %.3g N/m, %ld couples, %ld joints broken\n",
          worst, fmax_all, maxpairs, joints_broken(s));
  ck_assert_double_gt(fmax_all, 0);
  ck_assert_int_gt(joints_broken(s), 0);
  ck_assert_double_le(worst, 1e-12);
}
END_TEST

/* The same scene with every parallel threshold at 0 (forced team work in the search, the couple
 * blocks and the joints): 1 and 2 threads must give the same state hash after 600 steps. */
START_TEST(test_threads_bitwise) {
  quiet();
  uint64_t h[2];
  for (int t = 0; t < 2; t++) {
    threads_set(t + 1); /* exactly, on every step */
    YfSim *s = pack_scene();
    contact_set_par_min(s, 0);
    joints_set_par_min(0);
    run_steps(s, 600);
    ck_assert_int_gt(contact_pairs(s), 1024); /* several couple blocks */
    h[t] = sim_state_hash(s);
    fprintf(stderr, "threads %d: hash %016llx, %ld couples, %ld searches\n", t + 1, (unsigned long long)h[t],
            contact_pairs(s), contact_searches(s));
  }
  joints_set_par_min(4096);
  threads_set(0);
  ck_assert_msg(h[0] == h[1], "1 and 2 threads differ");
}
END_TEST

/* ------------------------------------------------------------------ contact that comes later */

/* Two blocks 0.2 m apart closing at 4 m/s (8 x 4 cells each, h = 12.5 mm, buffer 3.75 mm):
 * for the first ~9000 steps no couple exists, so the step makes no triangle records and skips
 * its passes over the nodes (contact.c: a scene pays for contact only while couples exist); then
 * the search finds the couples and the blocks collide.  The same scene with a 1 m buffer has
 * every couple of the two blocks' boundary triangles from step 0 and so runs every pass at every step.  Couples that
 * do not touch give no force, and touching ones are summed in couple order in both, so the two
 * runs must end in the same bits, with no contact force left on a node once the blocks are apart;
 * and the skipped run's impact must conserve momentum (1e-10 of
 * sum m|v|, as head-on above) and exchange it (the blocks of equal mass swap velocities in a
 * rigid bounce: b must leave faster than 1 m/s; it leaves at 2.997 m/s, a's 3 m/s). */
static uint64_t far_impact(const char *buffer, long *pairs0, double *dP, double *vb) {
  char deck[1024];
  snprintf(deck, sizeof deck,
           "material m elastic rho 1000 E 1e8 nu 0.25 plane_strain pen_n 3e5\n"
           "mesh rect a m 0 0 0.1 0.05 8 4\nmesh rect b m 0.3 0 0.4 0.05 8 4\n"
           "velocity a set 3 0\nvelocity b set -1 0\ncontact pair a b\ncontact buffer %s\ntimestep 2e-6\nrun 0\n",
           buffer);
  YfSim *s = yft_run(deck);
  Stat a0 = gstat(s, "a"), b0 = gstat(s, "b");
  const double P0 = a0.px + b0.px, scale = fabs(a0.px) + fabs(b0.px);
  run_steps(s, 1000); /* 8 mm closer: 0.192 m apart */
  *pairs0 = contact_pairs(s);
  *dP = 0;
  for (int k = 0; k < 60; k++) {
    run_steps(s, 500);
    Stat a = gstat(s, "a"), b = gstat(s, "b");
    if (fabs(a.px + b.px - P0) > *dP) *dP = fabs(a.px + b.px - P0);
  }
  *dP /= scale;
  *vb = gstat(s, "b").px / gstat(s, "b").m;
  /* apart again: no node holds a contact force (the dump's fc field) */
  const double *fc = contact_node_forces(s);
  for (int i = 0; i < s->model.node.n; i++)
    ck_assert_msg(fc[2 * i] == 0.0 && fc[2 * i + 1] == 0.0, "node %d keeps a contact force after the impact", i);
  return sim_state_hash(s);
}

START_TEST(test_far_contact_skips_then_meets) {
  quiet();
  long p_far, p_all;
  double dP_far, dP_all, vb_far, vb_all;
  uint64_t h_far = far_impact("auto", &p_far, &dP_far, &vb_far);
  uint64_t h_all = far_impact("1", &p_all, &dP_all, &vb_all);
  fprintf(stderr, "far contact: couples before meeting %ld (buffer 1 m: %ld), b's velocity after %.4f m/s, dP %.3g; "
          "hashes %016llx %016llx\n", p_far, p_all, vb_far, dP_far, (unsigned long long)h_far, (unsigned long long)h_all);
  ck_assert_int_eq(p_far, 0);
  ck_assert_int_eq(p_all, 40 * 40); /* every couple of the blocks' 40 + 40 boundary triangles */
  ck_assert_double_gt(vb_far, 1.0);
  ck_assert_double_le(dP_far, 1e-10);
  ck_assert_msg(h_far == h_all, "the run without couples until they meet differs from the one with every couple");

  /* contact that stops from one step to the next: blocks overlapping by 20 um push each other
   * for a step, then fly apart at 2 x 100 m/s (0.4 mm a step of 2 us): at the next step no couple
   * touches, and the node contact forces of the step before must not stay (the one-thread path
   * skips its passes over the nodes only when no node holds one) */
  YfSim *s = yft_run("material m elastic rho 1000 E 1e8 nu 0.25 plane_strain pen_n 3e5\n"
                     "mesh rect a m 0 0 0.1 0.05 8 4\nmesh rect b m 0.09998 0 0.19998 0.05 8 4\n"
                     "contact pair a b\ntimestep 2e-6\nenergy_check off\nrun 1\n");
  const double *fc = contact_node_forces(s);
  double f1 = 0;
  for (int i = 0; i < s->model.node.n; i++) f1 += fabs(fc[2 * i]);
  ck_assert_double_gt(f1, 0.0);
  const int ga = model_group(&s->model, "a", 0);
  for (int i = 0; i < s->model.node.n; i++) s->model.node.vx[i] = (s->model.node.gmask[i] >> ga & 1) ? -100.0 : 100.0;
  run_steps(s, 2);
  fc = contact_node_forces(s);
  for (int i = 0; i < s->model.node.n; i++)
    ck_assert_msg(fc[2 * i] == 0.0 && fc[2 * i + 1] == 0.0, "node %d keeps the contact force of a step before", i);
}
END_TEST

/* ------------------------------------------------------------------ Y2D reference deck (a) */

/* Reference deck (a) (elastic block falling on a base, contact, no friction) with contact switched
 * on through the API read_y2d uses (every triangle with a boundary-flagged node, DIEZON, couples
 * sharing a node kept): displacements at step 1000 (mid-impact) within 1e-8 of the largest, the
 * tolerance of shared/y2d/README.md 4.2. */
START_TEST(test_y2d_deck_a_api) {
  quiet();
  YfSim *s = yft_run("print loading\n");
  y2d_load(s, "tests/y2d/decks/a_elastic_block.y", 0.5, NULL);
  /* the scene has dropped the deck's arrays once built from them: the flags come from a copy */
  YfY2d yd = {0}, *y = &yd;
  y2d_read("tests/y2d/decks/a_elastic_block.y", y, NULL);
  YfModel *m = &s->model;
  unsigned char *flag = calloc((size_t)m->tri.n + 1, 1);
  for (int e = 0; e < s->y2d->ntri; e++) {
    int in = y->iwfast == 0;
    for (int c = 0; c < 3; c++) in |= y->i1nobf[y->i2elto[(long)e * y->melno + c]] == 1;
    flag[s->y2d->tri0 + e] = (unsigned char)in;
  }
  contact_enable_all(s, y->diezon);
  contact_set_participation(s, flag, m->tri.n);
  free(flag);
  y2d_free(y);
  run_steps(s, 1000);
  FILE *f = fopen("tests/y2d/ref/a_elastic_block/corners_0001000.csv", "r");
  ck_assert_ptr_nonnull(f);
  char line[512];
  ck_assert_ptr_nonnull(fgets(line, sizeof line, f));
  double umax = 0, dev = 0;
  int rows = 0;
  int e, c, nd;
  double ux, uy, vx, vy;
  while (fscanf(f, "%d,%d,%d,%lf,%lf,%lf,%lf", &e, &c, &nd, &ux, &uy, &vx, &vy) == 7) {
    int i = m->tri.v[3 * (s->y2d->tri0 + e) + c];
    double dx = m->node.x[i] - m->node.x0[i] - ux, dy = m->node.y[i] - m->node.y0[i] - uy;
    if (hypot(ux, uy) > umax) umax = hypot(ux, uy);
    if (hypot(dx, dy) > dev) dev = hypot(dx, dy);
    rows++;
  }
  fclose(f);
  fprintf(stderr, "y2d deck a via the API: step 1000 deviation %.3g of max |u| %.3g (%d corners), %ld couples\n",
          dev / umax, umax, rows, contact_pairs(s));
  ck_assert_int_eq(rows, 3 * 736);
  ck_assert_double_le(dev, 1e-8 * umax);
}
END_TEST

/* ------------------------------------------------------------------ deck interface */

static const char *TWO = "material m elastic rho 1000 E 1e8 nu 0.25 plane_strain pen_n 1e9\n"
                         "mesh rect a m 0 0 0.1 0.05 8 4\nmesh rect b m 0.102 0 0.202 0.05 8 4\n";

/* Participation: with `surface boundary` a triangle takes part when one of its nodes is on a free
 * boundary: for an nx x ny grid every triangle of the border cells, 2 (nx ny - (nx-2)(ny-2)) = 40
 * of 64 per block; `surface all` takes all.  No contact command: no contact state at all;
 * `contact off` forgets everything. */
START_TEST(test_participation_and_off) {
  quiet();
  char deck[1024];
  snprintf(deck, sizeof deck, "%scontact pair a b\ntimestep auto\nrun 1\n", TWO);
  YfSim *s = yft_run(deck);
  ck_assert_int_eq(contact_participants(s), 80);
  ck_assert_double_eq_tol(contact_buffer(s), 0.3 * 0.0125, 1e-15);
  snprintf(deck, sizeof deck, "%scontact pair a b\ncontact surface all buffer 0.002\ntimestep auto\nrun 1\n", TWO);
  s = yft_run(deck);
  ck_assert_int_eq(contact_participants(s), 128);
  ck_assert_double_eq(contact_buffer(s), 0.002);
  ck_assert_int_gt(contact_pairs(s), 0);
  snprintf(deck, sizeof deck, "%stimestep auto\nrun 1\n", TWO);
  s = yft_run(deck);
  ck_assert_ptr_null(s->contact);
  ck_assert_int_eq(contact_pairs(s), 0);
  snprintf(deck, sizeof deck, "%scontact pair a b\ntimestep auto\nrun 1\ncontact off\nrun 1\n", TWO);
  s = yft_run(deck);
  ck_assert_ptr_null(s->contact);
  ck_assert_double_eq(s->energy.contact, 0.0);
}
END_TEST

/* A material of pen_n 0 written out (the converted Y2D deck of a property of D1PEPE 0): Y2D forms its couples by
 * geometry alone (ALGORITHMS 5) and presses them with p_n = 0 (6: the smaller D1PEPE), so they exist and carry no
 * force.  A contact rule refused the material (the converter then left its triangles out, and its deck counted
 * fewer couples than yfdem DECK.y); a pen_n not written at all is still refused as forgotten (test_deck_errors).
 * The blocks pass through each other untouched: no other force acts, so each keeps its momentum exactly. */
START_TEST(test_zero_penalty_written_keeps_couples) {
  quiet();
  YfSim *s = yft_run("material m elastic rho 1000 E 1e8 nu 0.25 plane_strain pen_n 0 friction 0.3\n"
                     "mesh rect a m 0 0 0.1 0.05 8 4\nmesh rect b m 0.101 0 0.201 0.05 8 4\n"
                     "velocity a set 3 0\nvelocity b set -1 0\ncontact pair a b\ntimestep 1e-6\nrun 0\n");
  Stat a0 = gstat(s, "a"), b0 = gstat(s, "b");
  long most = 0;
  for (int k = 0; k < 40; k++) { /* 10 ms at 4 m/s closing: 40 mm, past the 1 mm gap by 39 mm */
    run_steps(s, 250);
    if (contact_pairs(s) > most) most = contact_pairs(s);
  }
  Stat a = gstat(s, "a"), b = gstat(s, "b");
  ck_assert_msg(most > 0, "no contact couple formed");
  ck_assert_msg(a.xmax > b.xmin + 0.03, "the blocks did not overlap: a ends at %g, b starts at %g", a.xmax, b.xmin);
  ck_assert_double_eq_tol(a.px, a0.px, 1e-12 * fabs(a0.px));
  ck_assert_double_eq_tol(b.px, b0.px, 1e-12 * fabs(b0.px));
  ck_assert_double_eq(s->energy.contact, 0.0);
}
END_TEST

/* HDF5 dumps carry the contact force per node (field fc) while contact is on: it is in every
 * frame, with the node count's rows, zero in frame 0 (before the first contact evaluation; until
 * 2026-11-28 frame 0 had no fc, so ParaView's reader did not offer it) and nonzero during the
 * impact. */
START_TEST(test_dump_contact_force_field) {
  quiet();
  char deck[2048], path[] = "/tmp/yfct_XXXXXX";
  ck_assert_ptr_nonnull(mkdtemp(path));
  snprintf(deck, sizeof deck, "%svelocity a set 2 0\ncontact pair a b\ntimestep auto\ndump d h5 200 %s/c.h5 fields u fc\nrun 1600\n",
           TWO, path);
  YfSim *s = yft_run(deck);
  sim_free(s);
  double fmax = 0;
  /* the blocks meet at 1 ms (step about 840); frame 0 precedes the first contact evaluation */
  for (int fr = 0; fr <= 8; fr++) {
    char file[256];
    snprintf(file, sizeof file, "%s/c_%06d.h5", path, fr); /* one file per frame */
    hid_t f = H5Fopen(file, H5F_ACC_RDONLY, H5P_DEFAULT);
    ck_assert_int_ge(f, 0);
    const char *name = "/fc";
    ck_assert_int_gt(H5Lexists(f, name, H5P_DEFAULT), 0);
    hid_t d = H5Dopen2(f, name, H5P_DEFAULT);
    hid_t sp = H5Dget_space(d);
    hsize_t dims[2];
    H5Sget_simple_extent_dims(sp, dims, NULL);
    ck_assert_int_eq((int)dims[0], 90); /* 2 blocks x 9 x 5 nodes */
    double buf[180];
    H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, buf);
    for (int i = 0; i < 180; i++) fmax = fmax > fabs(buf[i]) ? fmax : fabs(buf[i]);
    if (fr == 0) ck_assert_double_eq(fmax, 0.0);
    H5Sclose(sp);
    H5Dclose(d);
    H5Fclose(f);
  }
  ck_assert_double_gt(fmax, 0);
}
END_TEST

/* Joined couples: in a fracturing body every joint's two triangles are a couple at distance 0
 * (never dropped); `joined skip` leaves out exactly those while the joints are intact. */
START_TEST(test_joined_skip_counts) {
  quiet();
  long np[2], nj = 0;
  for (int k = 0; k < 2; k++) {
    char deck[1024];
    snprintf(deck, sizeof deck,
             "material m elastic rho 1000 E 1e8 nu 0.25 plane_strain pen_n 1e9\n"
             "jointprop j ft 1e6 fs 1e6 gf 10 pen 1e9\nmesh rect p m 0 0 0.06 0.04 6 4\nfracture p j\n"
             "contact self p\ncontact joined %s\ntimestep auto\nrun 1\n", k ? "skip" : "keep");
    YfSim *s = yft_run(deck);
    np[k] = contact_pairs(s);
    nj = joints_count(s);
    ck_assert_int_eq(joints_broken(s), 0);
  }
  ck_assert_int_eq(nj, 3 * 6 * 4 - 6 - 4); /* internal edges of a 6 x 4 right-diagonal grid */
  ck_assert_int_eq(np[0] - np[1], nj);
}
END_TEST

/* Deck errors: a material without pen_n in a contact rule, a group that does not exist, a bad
 * option value; each names the place and the word. */
START_TEST(test_deck_errors) {
  struct { const char *deck, *want1, *want2; } cases[] = {
      {"material m elastic rho 1000 E 1e8 nu 0.25 plane_strain\nmesh rect a m 0 0 1 1 2 2\n"
       "mesh rect b m 2 0 3 1 2 2\ncontact pair a b\n", "bad.deck:4", "pen_n"},
      {"material m elastic rho 1000 E 1e8 nu 0.25 plane_strain pen_n 1e9\nmesh rect a m 0 0 1 1 2 2\n"
       "contact pair a nope\n", "nope", "defined: a"},
      {"material m elastic rho 1000 E 1e8 nu 0.25 plane_strain pen_n 1e9\nmesh rect a m 0 0 1 1 2 2\n"
       "contact buffer -1\n", "bad.deck:3", "-1"},
      {"material m elastic rho 1000 E 1e8 nu 0.25 plane_strain pen_n 1e9\nmesh rect a m 0 0 1 1 2 2\n"
       "contact joined maybe\n", "maybe", "skip"},
  };
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
    char *err = NULL, *dir = NULL;
    int rc = yft_run_binary("bad.deck", cases[i].deck, NULL, &err, &dir);
    ck_assert_msg(rc == 1, "case %zu: exit %d (%s)", i, rc, err ? err : "");
    ck_assert_msg(strstr(err, cases[i].want1) && strstr(err, cases[i].want2), "case %zu: %s", i, err);
    free(err);
    free(dir);
  }
}
END_TEST

/* Self-contact of a body that does not fracture (a U whose arms close, contact self U): its
 * contact penalty is part of the stable step.  Only other bodies' and fracturing bodies' rules
 * counted, so the triangles alone set the step (9 x the contact's limit) and the arms' impact
 * blew up at the default safety, or ended "ok" with 18 % of the energy from nowhere at 0.3. */
START_TEST(test_self_contact_sets_the_step) {
  quiet();
  static const char *const base = "material m elastic rho 1000 E 1e7 nu 0.3 plane_strain pen_n 1e8\n"
                                  "mesh rect u m 0 0 1 0.2 10 2\n";
  char deck[512];
  snprintf(deck, sizeof deck, "%stimestep auto\nrun 0\n", base);
  double alone = yft_run(deck)->dt_limit;
  snprintf(deck, sizeof deck, "%scontact self u\ntimestep auto\nrun 0\n", base);
  YfSim *s = yft_run(deck);
  ck_assert_msg(strstr(s->dt_limiter, "contact penalty") != NULL, "limiter: %s", s->dt_limiter);
  ck_assert_double_lt(s->dt_limit, 0.5 * alone);
}
END_TEST

/* An impact that presses harder than the penalty can push back (rho v^2 > pen_n) is warned at
 * the run: a block at 500 m/s passed through a fixed wall four cells thick and the run ended
 * "ok".  At 50 m/s (rho (2 v)^2 = 1e7 Pa, a tenth of pen_n) nothing is said. */
START_TEST(test_impact_above_penalty_warned) {
  static const char *const fmt = "material m elastic rho 1000 E 1e7 nu 0.3 plane_strain pen_n 1e8\n"
                                 "mesh rect wall m 1 -0.5 1.2 0.5 4 20\nmesh rect p m 0 -0.1 0.2 0.1 4 4\n"
                                 "fix w wall fixed xy\nvelocity p set %s 0\ncontact pair p wall\n"
                                 "timestep auto\nrun 1\n";
  static const char *const v[] = {"500", "50"};
  for (int k = 0; k < 2; k++) {
    char deck[600], *err;
    snprintf(deck, sizeof deck, fmt, v[k]);
    int rc = yft_run_binary("imp.deck", deck, "-log none", &err, NULL);
    ck_assert_msg(rc == 0, "exit %d: %s", rc, err);
    const char *w = strstr(err, "imp.deck:6: warning: contact: an impact can press up to rho v^2 = 2.5e+08 Pa");
    if (k == 0) ck_assert_msg(w != NULL, "v %s: no warning: %s", v[k], err);
    else ck_assert_msg(!strstr(err, "an impact can press"), "v %s: %s", v[k], err);
    free(err);
  }
  /* bodies moving as one close at nothing: a block and its neighbour both at 1000 m/s, quiet */
  char *err;
  int rc = yft_run_binary("one.deck", "material m elastic rho 1000 E 1e7 nu 0.3 plane_strain pen_n 1e8\n"
                          "mesh rect a m 0 0 0.2 0.2 4 4\nmesh rect b m 0.25 0 0.45 0.2 4 4\nvelocity a set 1000 0\n"
                          "velocity b set 1000 0\ncontact pair a b\ncontact self a\ntimestep auto\nrun 1\n", "-log none", &err, NULL);
  ck_assert_msg(rc == 0 && !strstr(err, "an impact can press"), "exit %d: %s", rc, err);
  free(err);
  /* a speed the run gives (gravity 5e5 m/s^2 drives a block at rest into a wall at 316 m/s,
   * rho v^2 2.5e8 Pa): it passed through with no word, the check being made at the run's start;
   * it is made again after each search.  At 1e3 m/s^2 (14 m/s) nothing is said. */
  static const char *const g[] = {"5e5", "1e3"};
  for (int k = 0; k < 2; k++) {
    char deck[600];
    snprintf(deck, sizeof deck, "material m elastic rho 2500 E 1e9 nu 0.25 plane_strain pen_n 1e8\n"
             "mesh rect a m 0 0 0.1 0.1 4 4\nmesh rect w m 0.2 -0.2 0.3 0.3 4 20\nfix hw w fixed xy\n"
             "contact pair a w\ngravity %s 0\ntimestep auto\nrun 3000\n", g[k]);
    rc = yft_run_binary("grav.deck", deck, "-log none", &err, NULL);
    ck_assert_msg(rc == 0 || (k == 0 && rc == 3), "gravity %s: exit %d: %s", g[k], rc, err); /* (the energy check may stop the pass) */
    ck_assert_msg((strstr(err, "grav.deck:5: warning: contact (at step ") == NULL) == k, "gravity %s: %s", g[k], err);
    free(err);
  }
}
END_TEST

/* ------------------------------------------------------------------ friction energy */

/* The energy balance of a scene with the elastic-slip Coulomb law at a tangential stiffness of a
 * tenth of the normal one, where the springs' cap moves fastest against their stiffness.  The
 * dissipation is what the springs do not store: their centred work less the change of their
 * energy (contact.c).  The old booking, |F_t| times the slip, missed the energy a spring releases
 * when its cap shrinks (the normal force falling as a body leaves) and, to first order in dt, the
 * work of the force's change along the slip. */

/* A 0.1 m square block (4 x 4 cells, rho 2500, E 1e9) thrown at (8, -6) m/s onto a fixed base,
 * pen_n 10 E, pen_t 0.1 pen_n, friction mu, no damping, for 20 ms (it bounces off spinning,
 * about 28 % of the 1250 J/m given dissipated by friction), at auto step `safety`.  Returns the
 * balance residual over the energy given and sets *fric to the friction dissipation [J/m]. */
static double oblique_impact(double safety, double mu, double *fric) {
  char deck[1024];
  snprintf(deck, sizeof deck,
           "material rock elastic rho 2500 E 1e9 nu 0.25 plane_strain pen_n 1e10 pen_t 1e9 friction %g\n"
           "mesh rect base rock -0.3 -0.05 0.5 0 16 2\nmesh rect blk rock 0 0.001 0.1 0.101 4 4\n"
           "fix hold base fixed xy\nvelocity blk set 8 -6\ncontact pair blk base\n"
           "timestep auto safety %g\nrun 0\nrun $(0.02/dt:%%d)\n",
           mu, safety);
  YfSim *s = yft_run(deck);
  double given = energy_get_budget(), r = energy_balance(s) / given;
  *fric = s->energy.friction;
  fprintf(stderr, "oblique impact: safety %g mu %g: balance %.4g J/m of %.6g given (%+.4f %%), friction %.6g J/m\n",
          safety, mu, energy_balance(s), given, 100 * r, *fric);
  return r;
}

/* Measured (balance over the energy given at safety 0.7, 0.5, 0.35, 0.25, 0.125, 0.0625): the
 * old booking -12.4, -9.1, -6.4, -4.9, -2.5, -1.25 % (first order in dt, the friction 203, 243,
 * 272, 292, 319, 333 J/m); the new one -0.32, -0.11, +0.07, +0.007, +0.014, +0.007 %, of which
 * the same scene without friction shows -0.13, +0.001, +0.08, +0.015, +0.015, +0.005 % (the
 * time integration's own offset of the half-step kinetic energy): what friction adds is -0.11,
 * -0.007, -0.0007 % at 0.5, 0.25, 0.125, the friction 356, 353, 350, 349 J/m.  So: within
 * 0.25 % at 0.5 and 0.05 % at 0.25 (2x and 7x the measured; the old booking is 36x and 100x
 * beyond), and the friction within 1.5 % of the finer step's (old: 17 % apart). */
START_TEST(test_oblique_impact_friction_balance) {
  quiet();
  double f1, f2;
  double r1 = oblique_impact(0.5, 0.5, &f1), r2 = oblique_impact(0.25, 0.5, &f2);
  ck_assert_double_lt(fabs(r1), 0.0025);
  ck_assert_double_lt(fabs(r2), 0.0005);
  ck_assert_double_gt(f2, 0.2 * 1250); /* friction did act (28 % of the energy given) */
  ck_assert_double_lt(fabs(f1 - f2), 0.015 * f2);
}
END_TEST

/* The sliding block of decks/verify (0.2 x 0.1 m, 4 x 2 cells, rho 2500, E 1e9) on 40 degrees
 * at a friction angle of 20, pen_n 10 E, pen_t 0.1 pen_n, no damping, 50 ms at auto safety 0.5,
 * with the friction law `law`: the undamped block rings, its edges lift off and touch again, every
 * spring's energy released at each lift-off.  Returns the balance residual [J/m] and sets *w to
 * the gravity work and *fric to the friction dissipation [J/m]. */
static double sliding_block(const char *law, double *w, double *fric) {
  quiet();
  double th = 40 * M_PI / 180, mu = tan(20 * M_PI / 180);
  char deck[1024];
  snprintf(deck, sizeof deck,
           "material rock elastic rho 2500 E 1e9 nu 0.25 plane_strain pen_n 1e10 pen_t 1e9 friction %.17g "
           "friction_law %s\n"
           "mesh rect base rock -0.05 -0.05 0.55 0 12 2\nmesh rect blk rock 0 0 0.2 0.1 4 2\n"
           "fix hold base fixed xy\ncontact pair blk base\ntimestep auto safety 0.5\n"
           "gravity %.17g %.17g\nrun 0\nrun $(0.05/dt:%%d)\n",
           mu, law, 9.81 * sin(th), -9.81 * cos(th));
  YfSim *s = yft_run(deck);
  double r = energy_balance(s);
  *w = energy_external(s);
  *fric = s->energy.friction;
  fprintf(stderr, "sliding block, %s law: balance %.4g J/m of gravity work %.6g J/m (%+.4f %%), friction %.6g J/m\n",
          law, r, *w, 100 * r / *w, *fric);
  return r;
}

/* The Coulomb law.  Measured over the gravity work (1.41 J/m), at safety 0.5, 0.25, 0.125 (the
 * verify deck's gravity, rounded by its expressions): the old booking -0.87, -0.43, -0.15 %, the
 * new one -0.039, -0.003, -0.0015 %; this run -0.71 % and -0.037 %.  Within 0.2 % (5x). */
START_TEST(test_sliding_block_friction_balance) {
  double w, fric, r = sliding_block("coulomb", &w, &fric);
  ck_assert_double_gt(w, 1.0);
  ck_assert_double_gt(fric, 0.3 * w); /* it slid: friction took a good part */
  ck_assert_double_lt(fabs(r), 0.002 * w);
}
END_TEST

/* Y2D's law (friction_law y2d, every .y deck's) is booked as the Coulomb law is: the centred work
 * of its force where the force acts (the contactor edge's ends with the normal force's weights,
 * s = F_b / F; its memory takes the slip rate at the breakpoints' mean) less the change of its
 * spring's energy 0.5 F_t^2 / p_t.  Booked as |F_t| slip, this block's balance was -2.9 % of the
 * gravity work (2.24 J/m) at safety 0.5 and -1.5 % at 0.25; now -0.028 % and -0.006 %.  Within
 * 0.2 % (7x), as the Coulomb law's. */
START_TEST(test_sliding_block_y2d_law_balance) {
  double w, fric, r = sliding_block("y2d", &w, &fric);
  ck_assert_double_gt(w, 1.0);
  ck_assert_double_gt(fric, 0.05 * w); /* friction did act */
  ck_assert_double_lt(fabs(r), 0.002 * w);
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
  tcase_add_test(t, test_fast_body_no_missed_couple);
  tcase_add_test(t, test_pack_forces_sum_to_zero);
  tcase_add_test(t, test_threads_bitwise);
  tcase_add_test(t, test_far_contact_skips_then_meets);
  tcase_add_test(t, test_y2d_deck_a_api);
  tcase_add_test(t, test_participation_and_off);
  tcase_add_test(t, test_joined_skip_counts);
  tcase_add_test(t, test_dump_contact_force_field);
  tcase_add_test(t, test_deck_errors);
  tcase_add_test(t, test_zero_penalty_written_keeps_couples);
  tcase_add_test(t, test_self_contact_sets_the_step);
  tcase_add_test(t, test_impact_above_penalty_warned);
  tcase_add_test(t, test_oblique_impact_friction_balance);
  tcase_add_test(t, test_sliding_block_friction_balance);
  tcase_add_test(t, test_sliding_block_y2d_law_balance);
  suite_add_tcase(s, t);
  return s;
}
