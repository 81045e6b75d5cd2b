/* check_energy.c: the energy balance check (energy.c) on both sides, and the stable limit it
 * advises (issues 17 and 22).  Facts checked:
 *   - blow-ups stop with exit 3, the step, the energy that grew and its stage, the stable limit
 *     and what to change: Y2D's a_elastic_block at the steps issue 17 ran it at (0.99 and 1.3 x
 *     the limit yfdem printed then, 2.5 and 3.2 x today's), which ended `ok` with a balance 6-18
 *     times its input; the seed beam (nx 40) at the step of `timestep auto safety 0.7` of then,
 *     which booked 2257 J/m of damping out of 937.5 J/m given; the frames before the stop kept;
 *   - a healthy run is never stopped: a Y2D deck with joints inserted at step 0 (meshing code 3)
 *     whose bodies start overlapping (as rounded generator coordinates make them) releases that
 *     contact energy in its first steps; it is energy the scene was given, the run goes to its
 *     last step (issue 22: it was stopped at step 100) and its balance closes;
 *   - `timestep auto` at safety 1.0 is stable on an own scene with contact, joints and fragments;
 *   - negative dissipation stops a run; `energy_check warn` lets a run go on, with one warning;
 *   - what a deck does between runs is energy given, not energy from nowhere: a velocity set and a
 *     body added where it overlaps another (both were stopped with exit 3), and the check still
 *     stops a run that then blows up; so is a change made after read_restart;
 *   - a healthy run is never stopped (found by a sweep of new decks, 2026-11-28): a slab bouncing on
 *     its support under gravity with a period near the checks' interval; a bar held by a
 *     prescribed displacement under mass damping (the dissipation grew at rest); a Y2D deck at
 *     rest (the round-off floor was 0 for Y2D materials);
 *   - gravity's work is a deck quantity and a summary key (the loads' `ext_work` leaves it out).
 * Every case is small (a few hundred triangles, at most a few thousand steps).
 */
#include <check.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>
#include "bc.h"
#include "energy.h"
#include "joint.h"
#include "query.h"
#include "run.h"
#include "yftest.h"

/* The number a deck run by yft_run_binary in dir printed after "KEY " at the start of a line
 * (its log.yfdem). */
static double printed(const char *dir, const char *key) {
  char path[4096], pat[64];
  snprintf(path, sizeof path, "%s/log.yfdem", dir);
  snprintf(pat, sizeof pat, "\n%s ", key);
  char *log = yft_slurp(path, 0), *f = log ? strstr(log, pat) : NULL;
  ck_assert_msg(f, "no '%s' line in %s", key, path);
  double v = strtod(f + strlen(pat), NULL);
  free(log);
  return v;
}

/* Y2D's a_elastic_block with its DCSTEC replaced by dt and its MCSTEP by steps, in a temporary
 * file whose path is returned (caller frees). */
static char *y2d_variant(const char *src, double dt, long steps) {
  char *text = yft_slurp(src, 0);
  ck_assert_ptr_nonnull(text);
  char path[] = "/tmp/yfe_XXXXXX.y";
  int fd = mkstemps(path, 2);
  ck_assert_int_ge(fd, 0);
  FILE *f = fdopen(fd, "w");
  for (char *ln = strtok(text, "\n"); ln; ln = strtok(NULL, "\n")) {
    if (!strncmp(ln, "/YD/YDC/DCSTEC", 14) && dt > 0) fprintf(f, "/YD/YDC/DCSTEC %.17g\n", dt);
    else if (!strncmp(ln, "/YD/YDC/MCSTEP", 14) && steps > 0) fprintf(f, "/YD/YDC/MCSTEP %ld\n", steps);
    else fprintf(f, "%s\n", ln);
  }
  fclose(f);
  free(text);
  return strdup(path);
}

static void assert_blowup_message(const char *err) {
  ck_assert_ptr_nonnull(strstr(err, "numerical failure at step"));
  ck_assert_ptr_nonnull(strstr(err, "energy balance not closed"));
  ck_assert_ptr_nonnull(strstr(err, "appeared from nowhere"));
  ck_assert_ptr_nonnull(strstr(err, "grew most"));
  ck_assert_ptr_nonnull(strstr(err, "(stage"));
  ck_assert_ptr_nonnull(strstr(err, "stable limit"));
  ck_assert_ptr_nonnull(strstr(err, "energy_check warn"));
}

/* Issue 17: a_elastic_block.y at 0.99 and 1.3 x the limit printed before (4.714e-7 s) ended ok
 * with a balance 6-18 times its input.  Now: a warning at the start (the step is above the limit),
 * exit 3 within a few hundred steps, the message as above plus "DCSTEC", and the csv frames
 * written before the stop are kept. */
START_TEST(test_y2d_blowup_stops) {
  const double dts[2] = {4.6669e-7, 6.1283e-7};
  for (int k = 0; k < 2; k++) {
    char *y = y2d_variant("tests/y2d/decks/a_elastic_block.y", dts[k], 0);
    char deck[1024];
    snprintf(deck, sizeof deck, "read_y2d %s\ndump f csv 50 fr\nrun\n", y);
    char *err = NULL, *dir = NULL;
    int code = yft_run_binary("blow.deck", deck, "-summary s.json", &err, &dir);
    fprintf(stderr, "energy: a_elastic_block dt %g: exit %d: %s", dts[k], code, err);
    ck_assert_int_eq(code, 3);
    assert_blowup_message(err);
    ck_assert_ptr_nonnull(strstr(err, "x the stable limit"));
    ck_assert_ptr_nonnull(strstr(err, "DCSTEC"));
    long step = atol(strstr(err, "numerical failure at step") + strlen("numerical failure at step"));
    ck_assert_int_le(step, 1000);
    char path[1100];
    snprintf(path, sizeof path, "%s/fr_000001.csv", dir); /* the frame of step 50 */
    ck_assert(yft_exists(path));
    snprintf(path, sizeof path, "%s/s.json", dir);
    char *sum = yft_slurp(path, 0);
    ck_assert_ptr_nonnull(sum);
    ck_assert_ptr_nonnull(strstr(sum, "\"numerical_failure\""));
    free(sum);
    unlink(y);
    free(y);
    free(err);
    free(dir);
  }
}
END_TEST

/* decks/beam.deck (nx 40, fracture, contact) prepared, not run: its run line made `run 0`. */
static YfSim *beam40(void) {
  char *text = yft_slurp("decks/beam.deck", 0);
  ck_assert_ptr_nonnull(text);
  char *deck = malloc(strlen(text) + 256);
  char *r = strstr(text, "\nrun ${steps}");
  ck_assert_ptr_nonnull(r);
  *r = 0;
  sprintf(deck, "variable nx index 40\nvariable every index 100000\nvariable out index /tmp/yfe_beam\n%s\nrun 0\n", text);
  YfSim *s = yft_run(deck);
  free(text);
  free(deck);
  return s;
}

/* Issue 17's beam: `timestep auto safety 0.7` then gave dt = 6.30971e-7 s, which blew up while the
 * run reported ok.  The same dt (1.35 x today's limit, set through the API: a deck is refused
 * above the limit) stops with exit 3 and the message of a blow-up. */
static void beam_at_old_dt(void *arg) {
  (void)arg;
  YfSim *s = beam40();
  s->dt_safety = 6.30971e-7 / s->dt_limit;
  run_steps(s, 4000);
}

START_TEST(test_native_blowup_stops) {
  char msg[4096];
  int code = yft_child_run(beam_at_old_dt, NULL, msg, sizeof msg);
  fprintf(stderr, "energy: beam nx 40 at dt 6.31e-7: exit %d: %s", code, msg);
  ck_assert_int_eq(code, 3);
  assert_blowup_message(msg);
  ck_assert_ptr_nonnull(strstr(msg, "timestep auto"));
}
END_TEST

/* Issue 22's class: tests/y2d/joint_release.y (tools/gen_joint_release.py 5e-6 0.9): joints
 * inserted at step 0 in two stacked blocks under gravity, the upper one starting 5 um into the
 * lower; dt 0.9 x the printed limit.  Stopped at step 100 before ("energy growing without a
 * source": the overlap's contact energy was not counted as given).  Now it runs its 2000 steps:
 * the given energy includes the overlap's contact energy (about 15 J/m), no joint breaks, and the
 * balance closes within s^2 / (1 - s^2) = 0.3 of it (s = 0.9 / 1.19, the bisected stable step of
 * docs/STABILITY.md) and stays put after the release (the last 1000 steps move it by < 0.1%). */
START_TEST(test_joint_release_runs) {
  YfSim *s = yft_run("read_y2d tests/y2d/joint_release.y\nrun 1000\n");
  double r1 = energy_balance(s);
  run_steps(s, 1000);
  double r2 = energy_balance(s), given = energy_get_budget();
  fprintf(stderr, "energy: joint release: given %.4g J/m, balance %.4g then %.4g, %ld joints broken\n", given, r1, r2,
          joints_broken(s));
  ck_assert_int_eq(s->step, 2000);
  ck_assert_double_gt(given, 10.0);
  ck_assert_int_eq(joints_broken(s), 0);
  ck_assert_double_lt(fabs(r2), 0.3 * given);
  ck_assert_double_lt(fabs(r2 - r1), 1e-3 * given);
  sim_free(s);
}
END_TEST

/* An own scene with contact, joints and fragments at `timestep auto safety 1.0`: to the end,
 * fragments made, the balance closed (docs/STABILITY.md). */
#define FRAG_PLATE                                                                                                     \
  "material rock elastic rho 2600 E 30e9 nu 0.2 plane_strain damping 0.1 pen_n 3e11 pen_t 3e10 friction 0.5\n"      \
  "material steel elastic rho 7800 E 210e9 nu 0.3 plane_strain pen_n 3e11 pen_t 3e10 friction 0.3\n"                \
  "mesh rect plate rock 0 0 0.2 0.04 10 2 pattern cross\nmesh rect l steel 0.0 -0.02 0.02 0 1 1\n"                  \
  "mesh rect r steel 0.18 -0.02 0.2 0 1 1\nmesh rect hammer steel 0.09 0.04 0.11 0.06 1 1\n"                        \
  "jointprop cj ft 4e6 fs 8e6 gf 60 pen 3e11 law munjiza\nfracture plate cj\n"                                      \
  "region floor box -1 -1 1 -0.0199\ngroup floor node region floor\nfix base floor fixed xy\n"                      \
  "velocity hammer set 0 -20\ncontact pair hammer plate\ncontact pair plate l\ncontact pair plate r\n"              \
  "contact self plate\n"

START_TEST(test_auto_safety_one_stable) {
  YfSim *s = yft_run(FRAG_PLATE "timestep auto safety 1.0\nrun 1500\n");
  int frag[4096];
  ck_assert_int_le(s->model.tri.n, 4096);
  int nf = joints_fragments(s, frag);
  double r = energy_balance(s);
  fprintf(stderr, "energy: frag plate safety 1.0: %ld joints broken, %d fragments, balance %.4g of %.4g J/m\n",
          joints_broken(s), nf, r, energy_get_budget());
  ck_assert_int_eq(s->step, 1500);
  ck_assert_int_gt(joints_broken(s), 0);
  ck_assert_int_gt(nf, 4); /* the plate's fragments besides the steel bodies */
  ck_assert_double_lt(fabs(r), YF_EBAL_TOL * energy_get_budget());
  sim_free(s);
}
END_TEST

/* A dissipation that goes negative is not closed either. */
static void negative_friction(void *arg) {
  (void)arg;
  YfSim *s = yft_run(FRAG_PLATE "timestep auto\nrun 100\n");
  s->energy.friction = -0.5 * energy_get_budget();
  energy_check(s);
}

START_TEST(test_negative_dissipation_stops) {
  char msg[4096];
  int code = yft_child_run(negative_friction, NULL, msg, sizeof msg);
  fprintf(stderr, "energy: negative friction: exit %d: %s", code, msg);
  ck_assert_int_eq(code, 3);
  ck_assert_ptr_nonnull(strstr(msg, "negative friction dissipation (stage 'contact')"));
}
END_TEST

/* `energy_check warn` runs the blow-up of test_y2d_blowup_stops (300 steps of it) to its end with
 * one warning; `off` without; a native deck's timestep above the limit is then accepted with a
 * warning instead of refused. */
START_TEST(test_energy_check_switch) {
  char *y = y2d_variant("tests/y2d/decks/a_elastic_block.y", 4.6669e-7, 300);
  const char *modes[2] = {"warn", "off"};
  for (int k = 0; k < 2; k++) {
    char deck[1024];
    snprintf(deck, sizeof deck, "read_y2d %s\nenergy_check %s\nrun\n", y, modes[k]);
    char *err = NULL, *dir = NULL;
    int code = yft_run_binary("go.deck", deck, NULL, &err, &dir);
    fprintf(stderr, "energy: energy_check %s: exit %d: %s", modes[k], code, err);
    ck_assert_int_eq(code, 0);
    const char *w = strstr(err, "energy balance not closed");
    if (k == 0) {
      ck_assert_ptr_nonnull(w);
      ck_assert_ptr_null(strstr(w + 1, "energy balance not closed")); /* once */
    } else {
      ck_assert_ptr_null(w);
    }
    free(err);
    free(dir);
  }
  unlink(y);
  free(y);
  char *err = NULL, *dir = NULL;
  int code = yft_run_binary("dt.deck",
                            "material m elastic rho 1000 E 1e9 nu 0.25 plane_strain\nmesh rect b m 0 0 0.1 0.1 2 2\n"
                            "timestep auto\nrun 0\nenergy_check warn\ntimestep $(1.1*dt_limit)\nrun 10\n",
                            NULL, &err, &dir);
  ck_assert_int_eq(code, 0);
  ck_assert_ptr_nonnull(strstr(err, "dt.deck:6: warning"));
  free(err);
  free(dir);
}
END_TEST

/* Between runs a deck may give the scene energy: `velocity hammer set 0 -40` after 200 steps
 * (the hammer's kinetic energy goes to 2496 J/m), then a steel block added 0.1 mm into the
 * left support's side (its contact energy is released in the next run).  Before, the first was stopped
 * at step 300 with "energy appeared from nowhere", the second at the next check.  Now both run
 * to their end with the balance closed within the tolerance of the energy given, the energy given
 * grows by the kinetic energy the velocity set added, and a run that blows up after such a change
 * (a Y2D deck set moving, then at 2.5 x the stable limit) is still stopped. */
#define PHASE1 FRAG_PLATE "timestep auto\nrun 200\n"
#define ADD_OVERLAP "mesh rect lid steel -0.02 -0.02 0.0001 0 1 1\ncontact pair lid l\nrun 600\n"

static void between_runs_blowup(void *arg) {
  (void)arg;
  /* Y2D's a_elastic_block (a Y2D deck's step above the limit only warns): 100 steps, then
   * every node set moving down at twice its speed, and the step made 2.5 x the limit */
  YfSim *s = yft_run("read_y2d tests/y2d/decks/a_elastic_block.y\nrun 100\nregion every box -1e3 -1e3 1e3 1e3\n"
                     "group all node region every\nvelocity all set 0 -4\ntimestep $(2.5*dt_limit)\nrun 3000\n");
  sim_free(s);
}

START_TEST(test_changes_between_runs_are_given) {
  YfSim *s = yft_run(PHASE1);
  double k0 = s->energy.kinetic, given0 = energy_get_budget() + energy_external(s);
  ck_assert(bc_set_velocity(s, model_group(&s->model, "hammer", 0), 0.0, -40.0));
  run_steps(s, 600);
  double r1 = energy_balance(s), given1 = energy_get_budget() + energy_external(s);
  run_energies(s);
  fprintf(stderr, "energy: velocity set between runs: kinetic %.6g J/m before, given %.6g then %.6g J/m, balance %.4g\n",
          k0, given0, given1, r1);
  ck_assert_int_eq(s->step, 800);
  /* the hammer's nodes: 0.5 x 7800 kg/m^3 x (0.02 m)^2 x (40 m/s)^2 = 2496 J/m, less the hammer's
   * share of k0 (at most k0); the supports do no work (fixed) */
  ck_assert_double_gt(given1 - given0, 2496.0 - k0 - 1e-9 * 2496.0);
  ck_assert_double_lt(given1 - given0, 2496.0 + 1e-9 * 2496.0);
  ck_assert_double_lt(fabs(r1), YF_EBAL_TOL * given1);
  sim_free(s);
  s = yft_run(PHASE1 "velocity hammer set 0 -40\nrun 600\n" ADD_OVERLAP);
  double r2 = energy_balance(s), given2 = energy_get_budget() + energy_external(s);
  fprintf(stderr, "energy: body added overlapping between runs: given %.6g J/m, balance %.4g\n", given2, r2);
  ck_assert_int_eq(s->step, 1400);
  ck_assert_double_gt(given2, given1 + 1.0); /* the overlap's contact energy is given */
  ck_assert_double_lt(fabs(r2), YF_EBAL_TOL * given2);
  sim_free(s);
  char msg[4096];
  int code = yft_child_run(between_runs_blowup, NULL, msg, sizeof msg);
  fprintf(stderr, "energy: blow-up after a change between runs: exit %d: %s", code, msg);
  ck_assert_int_eq(code, 3);
  assert_blowup_message(msg);
}
END_TEST

/* A slab on a fixed floor under gravity bounces once about every 100 steps at safety 0.5 (the
 * checks' old interval): every check met the phase where gravity's work is small, measured a
 * healthy residual (3 % of the motion's energy) against it, saw it "grow" by aliasing and stopped
 * the run at step 300.  Now the checks fall at irregular steps (energy_check_due), which meet
 * every phase: at safety 0.5, 0.9 and 1.0 the run reaches its end with the balance a few per cent
 * of the motion's energy. */
START_TEST(test_bouncing_slab_not_stopped) {
  const double sf[3] = {0.5, 0.9, 1.0};
  for (int k = 0; k < 3; k++) {
    char deck[1024];
    snprintf(deck, sizeof deck, "material m elastic rho 1000 E 1e7 nu 0.25 plane_strain\nmesh rect base m 0 0 1 0.1 20 2\n"
             "region bl box -1 -1 2 1e-9\ngroup bot node region bl\nfix c bot fixed xy\ngravity 0 -9.81\n"
             "timestep auto safety %g\nrun 2000\n", sf[k]);
    YfSim *s = yft_run(deck);
    /* gravity's work in the static state: (rho g)^2 h^3 / (3 M) per metre of width, M the
     * P-wave modulus in plane strain; the sudden load's motion reaches twice that */
    double M = 1e7 * 0.75 / (1.25 * 0.5), rg = 1000 * 9.81, est = 2.0 * rg * rg * 0.1 * 0.1 * 0.1 / (3.0 * M) * 1.0;
    fprintf(stderr, "energy: bouncing slab safety %g: step %ld, balance %.4g J/m, energy scale %.4g J/m\n", sf[k], s->step,
            energy_balance(s), est);
    ck_assert_int_eq(s->step, 2000);
    /* 2.5-5.5 % of it: the half-step velocities' offset (docs/STABILITY.md), largest at s = 1 */
    ck_assert_double_lt(fabs(energy_balance(s)), 0.1 * est);
    sim_free(s);
  }
  int due = 0, at100 = 0;
  for (long st = 1; st <= 100000; st++)
    if (energy_check_due(st)) { due++; at100 += st % 100 == 0; }
  ck_assert_int_eq(due, 1000);    /* one in each 100 steps */
  ck_assert_int_lt(at100, 100);   /* not at a fixed phase */
}
END_TEST

/* A bar held at one end and pulled at the other by a prescribed displacement (ramped over 0.05
 * s), under mass damping: once at rest its dissipation must stay put.  Before, the damping was
 * booked on the pulled nodes at their free velocity (the reaction's), 0.085 J/m every 1000 steps,
 * and the run stopped with "more dissipated than given" at step 27300. */
START_TEST(test_damping_with_prescribed_displacement) {
  YfSim *s = yft_run("material m elastic rho 1000 E 1e7 nu 0.25 plane_stress\nmesh rect b m 0 0 1 0.1 20 2\n"
                     "region l box -1 -1 1e-9 1\ngroup l node region l\nregion r box 0.99999 -1 2 1\ngroup r node region r\n"
                     "fix c l fixed xy\nhistory up ramp 0 0.05\nfix p r displacement 0.002 NULL history up\n"
                     "damping mass 50\ntimestep auto safety 0.5\nrun 15000\n");
  double d1 = s->energy.damping, t1 = s->time;
  run_steps(s, 15000);
  double d2 = s->energy.damping, r = energy_balance(s), given = energy_get_budget() + energy_external(s);
  fprintf(stderr, "energy: damped pull: dissipated %.9g J/m at %.3g s, %.9g at %.3g s; balance %.3g of %.4g J/m\n", d1, t1,
          d2, s->time, r, given);
  ck_assert_double_gt(t1, 0.2); /* well after the ramp: at rest */
  ck_assert_double_lt(fabs(d2 - d1), 1e-6 * d1);
  ck_assert_double_lt(fabs(r), YF_EBAL_TOL * given);
  sim_free(s);
}
END_TEST

/* A velocity set after read_restart is energy given too: a restart of a moving bar continued
 * with the bar set moving otherwise runs to its end (it stopped with "300 J/m appeared from
 * nowhere") with the balance closed, and a restart continued unchanged gives the uninterrupted
 * run's balance to the bit. */
START_TEST(test_change_after_restart_is_given) {
  char tmpl[] = "/tmp/yfe_rs_XXXXXX";
  char *dir = mkdtemp(tmpl);
  ck_assert_ptr_nonnull(dir);
  char deck[2048];
  const char *scene = "material m elastic rho 1000 E 1e7 nu 0.25 plane_strain\nmesh rect b m 0 0 1 0.2 10 2\n"
                      "timestep auto\n";
  snprintf(deck, sizeof deck, "%svelocity b set 1 0\nrun 500\nwrite_restart %s/a.restart\nrun 500\n", scene, dir);
  YfSim *s = yft_run(deck);
  double r_whole = energy_balance(s);
  sim_free(s);
  snprintf(deck, sizeof deck, "%sread_restart %s/a.restart\nrun 1000 upto\n", scene, dir);
  s = yft_run(deck);
  double r_same = energy_balance(s);
  sim_free(s);
  snprintf(deck, sizeof deck, "%sread_restart %s/a.restart\nvelocity b set 0 2\nrun 1000 upto\n", scene, dir);
  s = yft_run(deck);
  double r = energy_balance(s), given = energy_get_budget() + energy_external(s);
  fprintf(stderr, "energy: restart: balance %.17g whole, %.17g restarted; %.4g of %.4g J/m after a velocity set\n", r_whole,
          r_same, r, given);
  ck_assert_int_eq(s->step, 1000);
  ck_assert(r_same == r_whole);
  ck_assert_double_gt(given, 0.99 * 400.0); /* 0.5 x 1000 x 0.2 m^2 x (2 m/s)^2 */
  ck_assert_double_lt(fabs(r), YF_EBAL_TOL * given);
  sim_free(s);
  char cmd[300];
  snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
  ck_assert_int_eq(system(cmd), 0);
}
END_TEST

/* A Y2D deck whose body holds still (supports, no gravity, no load): its energies are 0 and
 * round-off; the check's round-off floor (1e-16 E per unit area) was 0 for Y2D materials (no E),
 * and the run stopped with "2.9e-24 J/m appeared from nowhere". */
START_TEST(test_y2d_at_rest_runs) {
  char path[] = "/tmp/yfe_rest_XXXXXX.y";
  int fd = mkstemps(path, 2);
  ck_assert_int_ge(fd, 0);
  FILE *f = fdopen(fd, "w");
  fputs("/YD/YDC/MCSTEP 300 /YD/YDC/DCSTEC 1e-7\n/YD/YDE/MELEM 8 /YD/YDE/NELEM 8 /YD/YDE/MELNO 3 /YD/YDE/NELNO 3\n"
        "/YD/YDE/I1ELPR 8 0 0 0 0 0 0 0 0\n/YD/YDE/I2ELTO 21 3 8 0 1 4 0 4 3 1 2 5 1 5 4 3 4 7 3 7 6 4 5 8 4 8 7\n"
        "/YD/YDN/MNODIM 2 /YD/YDN/NNODIM 2 /YD/YDN/MNOPO 9 /YD/YDN/NNOPO 9\n"
        "/YD/YDN/D2NCI 21 2 9 0 0 0.05 0 0.1 0 0 0.05 0.05 0.05 0.1 0.05 0 0.1 0.05 0.1 0.1 0.1\n"
        "/YD/YDN/I1NOPR 9 1 1 1 0 0 0 0 0 0\n/YD/YDPE/MPROP 1 /YD/YDPE/NPROP 1 /YD/YDPE/I1PTYP 1 1\n"
        "/YD/YDPE/D1PERO 1 2400 /YD/YDPE/D1PELA 1 1e10 /YD/YDPE/D1PEMU 1 1e10 /YD/YDPE/D1PSEM 1 0\n"
        "/YD/YDPN/MPNSET 2 /YD/YDPN/NPNSET 2 /YD/YDPN/I1PNFX 2 1 3 /YD/YDPN/I1PNFY 2 1 3\n"
        "/YD/YDPN/D1PNAX 2 0 0 /YD/YDPN/D1PNAY 2 0 0\n$YDOIT\n$YSTOP\n", f);
  fclose(f);
  char deck[256];
  snprintf(deck, sizeof deck, "read_y2d %s\nrun\n", path);
  YfSim *s = yft_run(deck);
  ck_assert_int_eq(s->step, 300);
  ck_assert_double_lt(fabs(energy_balance(s)), 1e-12);
  sim_free(s);
  unlink(path);
}
END_TEST

/* Gravity's work: `gravity_work`, `ext` (loads and supports + gravity, the thermo line's ExtWork),
 * `diss` and `balance` are deck quantities, and the summary has `gravity_work` (energy.external_work
 * is the loads' and supports' only).  A free block falling from rest under g = 10 for t = 1 ms:
 * gravity's work is m g^2 t^2 / 2 = 10 kg/m x 100 x 1e-6 / 2 = 5e-4 J/m (to the leapfrog's dt/t). */
START_TEST(test_gravity_work_reported) {
  const char *deck = "material m elastic rho 1000 E 1e9 nu 0.25 plane_stress\nmesh rect b m 0 0 0.1 0.1 2 2\ngravity 0 -10\n"
                     "timestep 1e-6\nrun 1000\n";
  YfSim *s = yft_run(deck);
  double g = 0, ext = 0, ew = 0, bal = 0, diss = -1;
  char err[256];
  ck_assert_int_eq(sim_query(s, "gravity_work", &g, err, sizeof err), 1);
  ck_assert_int_eq(sim_query(s, "ext", &ext, err, sizeof err), 1);
  ck_assert_int_eq(sim_query(s, "ext_work", &ew, err, sizeof err), 1);
  ck_assert_int_eq(sim_query(s, "balance", &bal, err, sizeof err), 1);
  ck_assert_int_eq(sim_query(s, "diss", &diss, err, sizeof err), 1);
  fprintf(stderr, "energy: falling block: gravity_work %.9g, ext %.9g, ext_work %.3g, balance %.3g, diss %.3g\n", g, ext, ew, bal, diss);
  ck_assert_double_lt(fabs(g - 5e-4), 2e-3 * 5e-4);
  ck_assert(ext == g + ew);
  ck_assert_double_eq(ew, 0.0);
  ck_assert_double_eq(diss, 0.0);
  ck_assert_double_lt(fabs(bal), 2e-3 * 5e-4);
  sim_free(s);
  char *e = NULL, *dir = NULL;
  ck_assert_int_eq(yft_run_binary("fall.deck", deck, "-summary s.json", &e, &dir), 0);
  char p[600];
  snprintf(p, sizeof p, "%s/s.json", dir);
  char *j = yft_slurp(p, 0);
  ck_assert_ptr_nonnull(j);
  const char *q = strstr(j, "\"gravity_work\": ");
  ck_assert_ptr_nonnull(q);
  ck_assert_double_lt(fabs(strtod(q + strlen("\"gravity_work\": "), NULL) - g), 1e-12);
  free(j);
  free(e);
  free(dir);
}
END_TEST

/* Gravity changed between runs: the work done under the first stays booked.  The falling block
 * of 10 m/s^2 for 1000 steps, then 'gravity 0 0' or 'gravity 0 -20' and 500 more: at the second
 * run's start gravity_work is the first run's to the bit, and with g = 0 it stays there; with
 * -20 it grows by m 20 dy from then on (the balance closes).  Before, gravity_work was
 * sum m g (x - x0) with the new g alone: 0 after 'gravity 0 0' (5e-4 J/m lost from the summary,
 * 3.7e7 J/m in a user's scene), and twice the first run's work at once with -20. */
static double qe(YfSim *s, const char *name) {
  double v = NAN;
  char err[256] = "";
  ck_assert_msg(sim_query(s, name, &v, err, sizeof err) == 1, "%s: %s", name, err);
  return v;
}

START_TEST(test_gravity_changed_between_runs) {
  const char *g2[2] = {"0 0", "0 -20"};
  for (int k = 0; k < 2; k++) {
    char deck[1024];
    snprintf(deck, sizeof deck, "material m elastic rho 1000 E 1e9 nu 0.25 plane_stress\nmesh rect b m 0 0 0.1 0.1 2 2\n"
             "gravity 0 -10\ntimestep 1e-6\nrun 1000\ngravity %s\nrun 0\n", g2[k]);
    YfSim *s = yft_run(deck);
    double w1 = 5e-4; /* 0.5 m g^2 t^2 of 10 kg/m falling 1 ms */
    double w = qe(s, "gravity_work");
    ck_assert_msg(fabs(w - w1) < 2e-3 * w1, "gravity %s: gravity_work %g at the second run's start, not %g", g2[k], w, w1);
    run_steps(s, 500);
    double w2 = qe(s, "gravity_work"), bal = qe(s, "balance");
    fprintf(stderr, "energy: gravity 0 -10 then %s: gravity_work %.9g, then %.9g; balance %.3g\n", g2[k], w, w2, bal);
    if (k == 0) ck_assert(w2 == w);
    else ck_assert_msg(w2 > w + 1e-3, "gravity_work %g after the -20 run", w2); /* 10 kg/m x 20 x ~1.5e-5 m more */
    ck_assert_double_lt(fabs(bal), 2e-3 * w2);
    sim_free(s);
  }
}
END_TEST

/* A displacement fix added after a run, on nodes that have moved (a cantilever sagging under
 * gravity, then its tip held at its start): the nodes jump in the first step, a shock whose
 * energy no force did work for, and the energy check stopped the run as "still growing" with
 * advice about the time step.  The run's start says so; a fix given from the start, whose
 * history starts at 0, says nothing. */
START_TEST(test_displacement_jump_warned) {
  static const char *const base = "material m elastic rho 1000 E 1e9 nu 0.3 plane_stress\nmesh rect a m 0 0 1 0.1 20 4\n"
                                  "region l box -1 -1 1e-9 1\ngroup l node region l\nregion r box 0.999999 -1 2 1\n"
                                  "group r node region r\nfix cl l fixed xy\ntimestep auto safety 0.5\n";
  static const struct { const char *tail; int warn; } c[] = {
      {"gravity 0 -9.81\nrun 300\nfix pr r displacement 0 0\nenergy_check warn\nrun 10\n", 1},
      {"history h ramp 0 1e-3\nfix pr r displacement 1e-5 NULL history h\nrun 300\n", 0},
      /* the warning's advice: a velocity fix holds the sagged tip where it is, with no shock
       * (the energy check, left on, does not stop the run) */
      {"gravity 0 -9.81\nrun 300\nfix pr r velocity 0 0\nrun 10\n", 0}};
  for (int k = 0; k < 3; k++) {
    char deck[2048], *err, *dir;
    snprintf(deck, sizeof deck, "%s%s", base, c[k].tail);
    int rc = yft_run_binary("j.deck", deck, "-log none", &err, &dir);
    ck_assert_msg(rc == 0, "case %d: exit %d: %s", k, rc, err);
    ck_assert_msg(!strstr(err, "they jump there in the first step") == !c[k].warn, "case %d: %s", k, err);
    if (c[k].warn) {
      ck_assert_msg(strstr(err, "j.deck:11: warning: fix 'pr': at the run's start"), "%s", err);
      ck_assert_msg(strstr(err, "'unfix pr' then 'fix pr r velocity 0 0'"), "%s", err);
      ck_assert_msg(!strstr(err, "history that starts"), "%s", err); /* a history scales from the reference */
    }
    free(err);
    free(dir);
  }
}
END_TEST

/* A joint far weaker in tension than in shear (f_t 1 Pa, f_s 3 MPa: a weak bedding plane) books a
 * negative fracture dissipation while the balance itself closes: the irreversible law's secant
 * estimate of the stored energy exceeds the work its joints took in.  The stop said "reduce the
 * time step", which changes nothing: at 0.5 and 0.25 x the stable limit the dissipation at the
 * same time is -7.6e-4 and -6.0e-4 J/m (an integration error would at least halve) and the balance
 * closes to 1 % of the work.  The message now says what it
 * is and names the ways on; with 'damage reversible' the same bar runs to its end. */
START_TEST(test_joint_split_not_dt) {
  static const char *const scene =
      "material c elastic rho 2500 E 1e10 nu 0.2 plane_stress\nmesh rect bar c 0 0 0.1 0.02 20 4 pattern alt\n"
      "jointprop cj ft 1 fs 3e6 gf 100 pen 1e11 law munjiza_gf%s\nfracture bar cj\nregion l box -1 -1 1e-9 1\n"
      "region r box 0.099999 -1 1 1\ngroup l node region l\ngroup r node region r\nfix hold l fixed xy\n"
      "history pull ramp 0 1e-3\nfix pull r displacement 4e-4 NULL history pull\ntimestep %s\n"
      "energy_check %s tolerance 0.01\nrun %s\n";
  char deck[2048];
  double d[2];
  /* 0.5 and 0.25 x the stable limit (3.96e-7 s), to the same time 1.2e-3 s */
  const char *sf[2] = {"2e-7", "1e-7"}, *steps[2] = {"6000", "12000"};
  for (int k = 0; k < 2; k++) {
    snprintf(deck, sizeof deck, scene, "", sf[k], "warn", steps[k]);
    YfSim *s = yft_run(deck);
    d[k] = s->energy.joint_dissipated;
    double w = energy_external(s), r = energy_balance(s);
    fprintf(stderr, "energy: f_t 1 Pa, f_s 3 MPa, dt %s s: fracture dissipation %.4g J/m, balance %.3g of %.4g J/m\n",
            sf[k], d[k], r, w);
    ck_assert_double_lt(fabs(r), 0.01 * w);
    ck_assert_double_lt(d[k], -0.01 * w);
    sim_free(s);
  }
  /* an error of the time integration would shrink at least by half with dt (first order) */
  ck_assert_double_gt(fabs(d[1]), 0.5 * fabs(d[0]));
  for (int k = 0; k < 2; k++) {
    char *err, *dir;
    snprintf(deck, sizeof deck, scene, k ? " damage reversible" : "", sf[0], "stop", steps[0]);
    int rc = yft_run_binary("w.deck", deck, "-log none", &err, &dir);
    ck_assert_msg(rc == (k ? 0 : 3), "case %d: exit %d: %s", k, rc, err);
    if (!k) {
      ck_assert_msg(strstr(err, "the balance itself closes"), "%s", err);
      ck_assert_msg(strstr(err, "'damage reversible'"), "%s", err);
      ck_assert_msg(!strstr(err, "reduce it") && !strstr(err, "balance not closed"), "%s", err);
    }
    free(err);
    free(dir);
  }
}
END_TEST

/* Mohr-Coulomb joints (cohesion 1 MPa, friction 0.6) in a direct shear test under a 2 MPa pressure
 * ramp stopped at step 7275 (exit 3) with "energy split wrong", whose advice blamed f_t and f_s far
 * apart and sent users to 'damage reversible', which stops too (energy from nowhere).  The cause is
 * the law (ALGORITHMS 3.5): f_s = c - sigma mu scales the whole shear curve, so it derives from no
 * potential.  Physics first: a joint taken round a closed loop in (slip, opening) returns to its
 * state (damage 0) having done net work: 0 to rounding without friction, more than 5 % of the loop's
 * shear energy scale with mu 0.6, of opposite sign round the opposite loop.  So no state estimate
 * of the stored energy can make the split right, and the check now names the Mohr-Coulomb set. */
static double mc_loop_work(double mu, int dir) {
  YfJointProp p;
  joint_prop_default(&p);
  p.ft = 1e9;
  p.fs = 1e9;
  p.gf = 100;
  p.pen = 3e11;
  p.law = YF_SOFT_LINEAR;
  p.coh = 1e6;
  p.phi = mu;
  p.y2d_floor = 0;
  p.hreg = 0;
  const double h = 0.005, s1 = 0.8 * 2 * h * 1e6 / p.pen, o1 = -2e6 * h / p.pen;
  double c[5][2] = {{0, 0}, {s1, 0}, {s1, o1}, {0, o1}, {0, 0}};
  if (dir < 0) { c[1][0] = 0; c[1][1] = o1; c[3][0] = s1; c[3][1] = 0; }
  double fs = joint_fs_init(&p), dmg[3] = {0, 0, 0}, W = 0, fp[2] = {0, 0}, up[2] = {0, 0};
  const int n = 4000;
  for (int leg = 0; leg < 4; leg++)
    for (int i = 1; i <= n; i++) {
      double t = (double)i / n, ux = c[leg][0] + t * (c[leg + 1][0] - c[leg][0]),
             uy = c[leg][1] + t * (c[leg + 1][1] - c[leg][1]);
      double x[4] = {ux, h + ux, h, 0}, y[4] = {uy, uy, 0, 0}, f[8];
      joint_force(&p, x, y, &fs, dmg, f, NULL);
      double fa[2] = {f[0] + f[2], f[1] + f[3]}; /* the joint's force on side A (nodes 0, 1) */
      W += 0.5 * (fa[0] + fp[0]) * (ux - up[0]) + 0.5 * (fa[1] + fp[1]) * (uy - up[1]);
      fp[0] = fa[0]; fp[1] = fa[1]; up[0] = ux; up[1] = uy;
    }
  ck_assert(dmg[0] == 0 && dmg[1] == 0 && dmg[2] == 0);
  return W / (1e6 * s1 * h); /* per the loop's shear energy scale f_s s h */
}

START_TEST(test_mohr_coulomb_energy_named) {
  double w0 = mc_loop_work(0.0, 1), w1 = mc_loop_work(0.6, 1), w2 = mc_loop_work(0.6, -1);
  fprintf(stderr, "energy: joint loop work / f_s s h: mu 0 %.3g, mu 0.6 %.4g, reversed %.4g\n", w0, w1, w2);
  ck_assert_double_lt(fabs(w0), 1e-6);
  ck_assert_double_gt(w1, 0.05);
  ck_assert_double_lt(fabs(w1 + w2), 1e-6 * fabs(w1));
  static const char *const deck =
      "material m elastic rho 2500 E 3e10 nu 0.2 plane_strain\nmesh rect blk m 0 0 0.1 0.1 20 20 pattern right\n"
      "region band box -1 0.045 1 0.055\n"
      "jointprop j ft 1e9 fs 1e9 gf 100 pen 3e11 law linear cohesion 1e6 friction 0.6 floor none%s\n"
      "fracture blk j region band\nregion bot box -1 -1 1 1e-9\ngroup bot node region bot\n"
      "region top box -1 0.0999999 1 1\ngroup top node region top\nfix hold bot fixed xy\n"
      "history c ramp 0 0.002\nload p top pressure 2e6 history c\ndamping mass 3000\n"
      "timestep auto safety 0.5\nrun 10000\n";
  for (int k = 0; k < 2; k++) {
    char d[2048], *err, *dir;
    snprintf(d, sizeof d, deck, k ? " damage reversible" : "");
    int rc = yft_run_binary("mc.deck", d, "-log none", &err, &dir);
    ck_assert_msg(rc == 3, "case %d: exit %d: %s", k, rc, err);
    ck_assert_msg(strstr(err, "Mohr-Coulomb shear strength of jointprop j"), "%s", err);
    ck_assert_msg(!strstr(err, "f_t and f_s differ widely") && !strstr(err, "reduce it"), "%s", err);
    free(err);
    free(dir);
  }
}
END_TEST

/* A displacement fix given before the first run without a ramp (a pull of 1e-4 m from t = 0) makes
 * its nodes jump in the first step too, and the energy check stopped the run (exit 3) after a
 * warning whose advice was wrong for it: "a history cannot help", "add the fix before the run
 * that moves them" (it was).  Now the warning says the nodes are at their reference positions
 * and gives the ramp; following it, the run has no warning and ends ok with the bar's end force at
 * E A u / L of plane strain (E/(1-nu^2) with the lateral contraction free) within 0.5 %. */
START_TEST(test_displacement_without_ramp_advice) {
  static const char *const base = "material m elastic rho 2000 E 10e9 nu 0.3 plane_strain\nmesh rect bar m 0 0 1 0.2 20 4 pattern alt\n"
                                  "region l box -1 -1 1e-9 1\nregion r box 0.99999 -1 2 1\ngroup l node region l\n"
                                  "group r node region r\ngroup c node nearest 0 0\nfix lx l fixed x\nfix cy c fixed y\n";
  static const char *const tail = "damping mass 3000\ntimestep auto\nenergy_check warn\nrun 20000\nprint \"F $(fx_r)\"\n";
  char deck[2048], *err, *dir;
  snprintf(deck, sizeof deck, "%sfix pull r displacement 1e-4 NULL\n%s", base, tail);
  int rc = yft_run_binary("j.deck", deck, "-log none", &err, &dir);
  ck_assert_msg(rc == 0, "exit %d: %s", rc, err);
  ck_assert_msg(strstr(err, "j.deck:10: warning: fix 'pull': at the run's start (time 0 s) its nodes are at their "
                            "reference positions"), "%s", err);
  ck_assert_msg(strstr(err, "'history pull_ramp ramp 0 T1'") &&
                strstr(err, "'fix pull r displacement 0.0001 NULL history pull_ramp'"), "%s", err);
  ck_assert_msg(!strstr(err, "a history cannot help") && !strstr(err, "'unfix pull'"), "%s", err);
  free(err);
  free(dir);
  snprintf(deck, sizeof deck, "%shistory pull_ramp ramp 0 2e-3\nfix pull r displacement 0.0001 NULL history pull_ramp\n%s",
           base, tail);
  rc = yft_run_binary("j.deck", deck, NULL, &err, &dir);
  ck_assert_msg(rc == 0 && !strstr(err, "warning"), "exit %d: %s", rc, err);
  double F = -printed(dir, "F"), want = 10e9 / (1 - 0.3 * 0.3) * 1e-4 * 0.2;
  fprintf(stderr, "energy: bar pulled by a ramped displacement fix: end force %.6g, E' A u / L %.6g\n", F, want);
  ck_assert_double_lt(fabs(F / want - 1), 5e-3);
  free(err);
  free(dir);
}
END_TEST

/* Bounded swings that the checks saw as growth (the sweep of 2026-11-29).  A two-triangle 0.1 m
 * square (E 1e7, nu 0.25, rho 1000) whose corner (0.1, 0) is pulled by a prescribed displacement
 * of 1 mm ramped over 0.1 s and then held swings about that corner for ever.  Its exact stable step
 * is 2/omega_max of the three free nodes with lumped masses, 6.87368e-4 s (1.0807 x the printed
 * limit 6.36056e-4 s, which counts the held node as free; bisected: stable at 1.08, blown up at
 * 1.09).  At 0.84 and 0.92 x the printed limit (0.78 and 0.85 x the exact one) the residual swings
 * within -0.24 .. +0.50 of the energy given for 1e5 steps; the checks met rising phases at steps
 * 107, 183 and 322 (0.11, 0.18, 0.25 of it), and the run was stopped "still growing at every check"
 * at step 322 (0.92) and 473 (0.84).  A free square of 16 triangles (2 x 2 cells, crossed) whose
 * corner is set moving at 0.01 m/s, at safety 0.9: residual -0.16 .. +0.72 of its kinetic energy,
 * checks 0.21, 0.31, 0.47 then 0.29, 0.27 (above where the rise began: the offset's mean is
 * positive), stopped at step 322.  Now a run of highs must be held, and these come back down from
 * their last high: each run reaches its 1e5th step, the residual within the bound a stable step
 * can show, s^2 / (1 - s^2) of the energy given, s = dt / the exact limit (for the free square the
 * printed one, which is below the exact one: it runs bounded at 1.05 x it, residual <= 1.34). */
START_TEST(test_bounded_swing_not_stopped) {
  static const char *const pulled =
      "material m elastic rho 1000 E 1e7 nu 0.25 plane_stress\nmesh rect sq m 0 0 0.1 0.1 1 1\n"
      "group c node nearest 0.1 0\nhistory h ramp 0 0.1\nfix mv c displacement 0.001 0 history h\n"
      "timestep auto\nrun 0\ntimestep $(v_F*dt_limit)\nthermo 100000\nrun 100000\n"
      "print \"residual $(balance/ext_work)\"\nprint \"s $(dt/dt_limit)\"\n";
  static const char *const set =
      "material m elastic rho 1000 E 1e7 nu 0.25 plane_stress\nmesh rect sq m 0 0 0.1 0.1 2 2 pattern cross\n"
      "group c node nearest 0.1 0.1\nvelocity c set 0.01 0\ntimestep auto safety 0.9\nrun 0\n"
      "variable k0 equal $(ke)\nthermo 100000\nrun 100000\nprint \"residual $(balance/v_k0)\"\nprint \"s $(dt/dt_limit)\"\n";
  /* lim: the printed limit over the exact one */
  static const struct { const char *deck, *args; double lim; } c[3] = {
      {pulled, "-var F 0.84", 6.36056e-4 / 6.87368e-4}, {pulled, "-var F 0.92", 6.36056e-4 / 6.87368e-4}, {set, "", 1.0}};
  for (int k = 0; k < 3; k++) {
    char *err, *dir;
    int rc = yft_run_binary("sq.deck", c[k].deck, c[k].args, &err, &dir);
    ck_assert_msg(rc == 0, "case %d: exit %d: %s", k, rc, err);
    double r = printed(dir, "residual"), sr = printed(dir, "s") * c[k].lim;
    fprintf(stderr, "energy: bounded swing, case %d %s (s = %.3g): residual %.3g of the energy given after 1e5 steps\n",
            k, c[k].args, sr, r);
    ck_assert_double_lt(sr, 1.0);
    ck_assert_double_lt(fabs(r), sr * sr / (1.0 - sr * sr));
    free(err);
    free(dir);
  }
}
END_TEST

/* A jointed block over a held base, with contact between them and in the block (its 'contact
 * joined' line to follow). */
#define BLOCK_ON_BASE                                                                                      \
  "material c elastic rho 2400 E 30e9 nu 0.2 plane_stress pen_n 3e11 friction 0.3\n"                        \
  "mesh rect blk c 0 0 0.2 0.2 8 8 pattern alt\nmesh rect base c -0.2 -0.1 0.4 -0.0005 12 2\n"             \
  "jointprop j ft 1e6 fs 2e6 gf 10 pen 3e11 law bilinear\nfracture blk j\nregion bb box -1 -1 1 -0.099\n" \
  "group bb node region bb\nfix h bb fixed xy\ncontact self blk\ncontact pair blk base\n"

/* 'contact joined skip' lets a couple into the contact list only once its joint has failed, often
 * overlapping already (a joint in compression), and the penalty energy of that overlap comes from
 * nowhere: a jointed block hitting a base at 20 m/s showed 2.4e3 of its 1.92e4 J/m from nowhere at
 * the impact, at safety 0.5 and 0.1 alike, and was stopped with advice to reduce the time step,
 * which changes nothing.  The advice now names joined skip and says to keep joined couples; with
 * 'contact joined keep' the same scene runs to its end, its residual within 1 % of the energy given. */
START_TEST(test_joined_skip_advice) {
  /* the energy given is the block's kinetic energy, 0.5 x 2400 x 0.04 x 20^2 = 19200 J/m */
  static const char *const deck =
      BLOCK_ON_BASE "contact joined ${mode}\n"
      "velocity blk set 0 -20\ntimestep auto safety ${sf}\nrun $(round(800*0.5/v_sf))\nprint \"residual $(balance/19200)\"\n";
  char *err, *dir;
  /* safety 0.5: stopped at step 613 (13 to 37 % of the energy given, rising by a third a check);
   * safety 0.1 (a smaller step does not close it): slowly, 0.13 to 0.28 of it over 2000 steps, by
   * less than a quarter a check, and the run ended "ok" (exit 0) until 2026-11-29; now stopped by
   * the slow-growth windows (docs/STABILITY.md), at step 2421 */
  static const char *const skip[2] = {"-log none -var mode skip -var sf 0.5", "-log none -var mode skip -var sf 0.1"};
  for (int k = 0; k < 2; k++) {
    int rc = yft_run_binary("s.deck", deck, skip[k], &err, &dir);
    fprintf(stderr, "energy: jointed block on a base, %s: exit %d: %.120s\n", skip[k], rc, err);
    ck_assert_msg(rc == 3, "%s: exit %d: %s", skip[k], rc, err);
    ck_assert_msg(strstr(err, "energy balance not closed") && strstr(err, "still growing at every check") &&
                  strstr(err, "the scene's 'contact joined skip' lets a couple") && strstr(err, "use 'contact joined keep'"),
                  "%s", err);
    free(err);
    free(dir);
  }
  int rc = yft_run_binary("s.deck", deck, "-var mode keep -var sf 0.5", &err, &dir);
  ck_assert_msg(rc == 0, "joined keep: exit %d: %s", rc, err);
  double r = printed(dir, "residual");
  fprintf(stderr, "energy: jointed block on a base, joined keep: residual %.3g of the energy given\n", r);
  ck_assert_msg(fabs(r) < 1e-2, "joined keep: residual %g", r);
  free(err);
  free(dir);
}
END_TEST

/* The strain energy is the law's own potential (elem_tri.c tri_strain_potential), so a slow
 * stretch far beyond small strain keeps the balance closed.  Before, the energy was Y2D's secant
 * A_c/2 T:E, above the work of the law's stresses by 4/3 of the strain (relative, uniaxial): a
 * bar pulled to 4 % was stopped with exit 3.  Now: the bar (nu 0) pulled at 0.1 m/s to 15 %
 * strain runs to its end with the balance within 1e-3 of the work done; and a square stretched
 * uniformly by l = 1.15 along x holds the uniaxial energy of the law, (E/2)(l^2/2 - ln l - 1/2)
 * per unit area (nominal stress (E/2)(l - 1/l) integrated), to 1e-12. */
START_TEST(test_finite_strain_energy) {
  YfSim *s = yft_run("material m elastic rho 1000 E 1e7 nu 0 plane_stress\nmesh rect b m 0 0 1 0.1 10 2\n"
                     "region l box -1 -1 1e-9 1\ngroup l node region l\nregion r box 0.99999 -1 2 1\ngroup r node region r\n"
                     "fix c l fixed x\nfix p r velocity 0.1 NULL\ntimestep auto\nrun 8000\n");
  double r = energy_balance(s), w = energy_external(s), u = s->model.node.x[yft_node_at(s, 1.0, 0.0)] - 1.0;
  fprintf(stderr, "energy: bar pulled to strain %.3g: balance %.4g of %.4g J/m of work\n", u, r, w);
  ck_assert_int_eq(s->step, 8000);
  ck_assert_double_gt(u, 0.15);
  ck_assert_double_lt(fabs(r), 1e-3 * w);
  sim_free(s);
  s = yft_run("material m elastic rho 1000 E 1e7 nu 0 plane_stress\nmesh rect b m 0 0 1 1 4 4 pattern cross\n"
              "timestep auto\nrun 0\n");
  const double l = 1.15;
  for (int i = 0; i < s->model.node.n; i++) s->model.node.x[i] = l * s->model.node.x0[i];
  run_energies_whole(s);
  double want = 0.5e7 * (0.5 * l * l - log(l) - 0.5);
  fprintf(stderr, "energy: uniaxial stretch 1.15: %.17g J/m, law %.17g\n", s->energy.strain, want);
  ck_assert_double_lt(fabs(s->energy.strain - want), 1e-12 * want);
  sim_free(s);
}
END_TEST

/* A node component that two fixes prescribe (a clamped base and a pushed face share a corner
 * node; a clamp and a push of the whole body): the fix given last acts alone, its reaction is
 * booked once, and a warning names both.  Every fix used to act in turn and book its own
 * reaction: the block below stopped at step 322 with "78.6 J/m appeared from nowhere" (23 % of
 * the work given), and the bar with its clamp overridden ended "ok" with a balance of -2.8e5 J/m
 * for 1125 J/m of motion (a sweep of new decks, 2026-11-28). */
START_TEST(test_overlapping_fixes) {
  const char *block = "material m elastic rho 2500 E 1e9 nu 0.25 plane_strain\nmesh rect b m 0 0 0.1 0.1 10 10\n"
                      "region bot box -1 -1 1 1e-9\ngroup bot node region bot\nregion lf box -1 -1 1e-9 1\n"
                      "group left node region lf\nfix push left velocity 0.5 NULL\nfix base bot fixed xy\n"
                      "timestep auto\nrun 3000\n";
  YfSim *s = yft_run(block);
  const YfNodes *n = &s->model.node;
  int corner = -1;
  for (int i = 0; i < n->n; i++)
    if (n->x0[i] == 0.0 && n->y0[i] == 0.0) corner = i;
  ck_assert_int_ge(corner, 0);
  double r = energy_balance(s), given = energy_get_budget() + energy_external(s);
  fprintf(stderr, "energy: pushed block, clamped corner: step %ld, corner at %g %g, balance %.4g of %.4g J/m\n", s->step,
          n->x[corner], n->y[corner], r, given);
  ck_assert_int_eq(s->step, 3000);
  ck_assert(n->x[corner] == 0.0 && n->y[corner] == 0.0); /* the clamp, given last, holds it */
  /* 2e-4 of the work: the half-step offset of a pushed face (the same block without the corner
   * in the pushed group: 14.7 of 73051 J/m at 5000 steps) */
  ck_assert_double_lt(fabs(r), 1e-3 * given);
  sim_free(s);
  /* the clamp first, then the whole bar pushed: the push acts on the clamped nodes too */
  s = yft_run("material m elastic rho 2500 E 1e9 nu 0.25 plane_strain\nmesh rect b m 0 0 1 0.1 20 2\n"
              "region l box -1 -1 1e-9 1\ngroup l node region l\nfix c l fixed xy\nfix v b velocity 3 NULL\n"
              "timestep auto\nrun 4000\n");
  n = &s->model.node;
  double ke = s->energy.kinetic, ux = n->x[0] - n->x0[0];
  r = energy_balance(s);
  fprintf(stderr, "energy: clamped bar pushed: kinetic %.6g J/m, balance %.3g J/m, ux %.6g m at %.6g s\n", ke, r, ux, s->time);
  ck_assert_double_lt(fabs(ke - 0.5 * 2500 * 0.1 * 9.0) , 1e-9 * ke); /* rigid motion at 3 m/s */
  ck_assert_double_lt(fabs(r), 1e-9 * ke);
  ck_assert_double_lt(fabs(ux - 3.0 * s->time), 1e-9);
  sim_free(s);
  char *err, *dir;
  ck_assert_int_eq(yft_run_binary("b.deck", block, "-log none", &err, &dir), 0);
  ck_assert_msg(strstr(err, "b.deck:7: warning: fix 'push': 1 node of it (first: node ") &&
                strstr(err, "is also prescribed by the later fix 'base', which acts there"), "no warning:\n%s", err);
  free(err);
  free(dir);
}
END_TEST

/* Dissipation beyond the energy given, above the limit: shared deck b at DCSTEC 1.75e-7 s (1.58 x
 * the printed limit; 1e-7 is its own) stays bounded because the triangles' viscosity takes the
 * energy the step makes as it comes: 431 J/m dissipated of 337.5 given (74 at its own step), a
 * balance of +353 J/m, and it ended "ok".  Now it stops with exit 3 once the dissipation passes
 * the energy given; at its own step the deck runs (test_y2d_regress). */
START_TEST(test_dissipation_beyond_given_stops) {
  char *b = yft_slurp("tests/y2d/decks/b_beam_impact.y", 0);
  ck_assert_ptr_nonnull(b);
  char *dt = strstr(b, "/YD/YDC/DCSTEC "), *mc = strstr(b, "/YD/YDC/MCSTEP ");
  ck_assert(dt && mc && mc < dt);
  char *deck = malloc(strlen(b) + 64);
  int k = sprintf(deck, "%.*s/YD/YDC/MCSTEP 3000\n", (int)(mc - b), b);
  const char *after_mc = strchr(mc, '\n') + 1;
  k += sprintf(deck + k, "%.*s/YD/YDC/DCSTEC 1.75e-07\n", (int)(dt - after_mc), after_mc);
  strcpy(deck + k, strchr(dt, '\n') + 1);
  char *err;
  int rc = yft_run_binary("b175.y", deck, "-log none", &err, NULL);
  fprintf(stderr, "energy: deck b at 1.75e-7 s: exit %d: %.300s\n", rc, err);
  ck_assert_msg(rc == 3 && strstr(err, "more was dissipated than the scene was given"), "exit %d: %s", rc, err);
  free(err);
  free(deck);
  free(b);
}
END_TEST

/* Two 1 m squares placed 0.65 m into each other (a second body not moved off the first, as a
 * Gmsh file with two bodies gives them): the penalty's 4.3e7 J/m at step 0 throws them apart at
 * 2.6 km/s and the run stops at step 107.  The stop said "reduce it ('timestep auto safety 0.25')"
 * (2026-11-29 sweep), which does not help: it now says the bodies start overlapping, with that
 * energy and its share of the energy given, and where the run started.  The same when the second
 * body is added between runs: the overlap is at the second run's start, step 10.  Triangles are
 * named with their body when there are several (Gmsh bodies share their files' ids). */
START_TEST(test_start_overlap_named) {
  const char *b = "mesh rect b rock 0.35 0.35 1.35 1.35 10 10\ncontact pair a b\n";
  /* pen_n 1e11: a triangle inverts at step 19 first, and that message names the overlap too */
  const char *pen[3] = {"1e10", "1e10", "1e11"};
  for (int c = 0; c < 3; c++) {
    const int between = c == 1;
    char deck[1024], want[128];
    snprintf(deck, sizeof deck, "material rock elastic rho 2500 E 1e9 nu 0.2 pen_n %s plane_strain\n"
             "mesh rect a rock 0 0 1 1 10 10\n%s%stimestep auto\nrun 2000\n", pen[c],
             between ? "timestep auto\nrun 10\n" : "", b);
    char *err;
    int rc = yft_run_binary("overlap.deck", deck, "-log none", &err, NULL);
    fprintf(stderr, "energy: overlapping squares (pen_n %s, added %s): exit %d: %.200s\n", pen[c],
            between ? "after a run" : "at once", rc, err);
    snprintf(want, sizeof want, c < 2 ? "the bodies start overlapping: their contact penalty energy at step %d, "
                                      : "the bodies started overlapping (their contact penalty energy at step %d, ",
             between ? 10 : 0);
    ck_assert_msg(rc == 3 && strstr(err, want) && strstr(err, "% of the energy given") &&
                  (c < 2 || strstr(err, " of body a (material rock) inverted") || strstr(err, " of body b (material rock) inverted")),
                  "exit %d: %s", rc, err);
    free(err);
  }
}
END_TEST

/* The stop step of deck NAME run in a new directory (its stderr and directory returned, caller frees),
 * and the state_hash of its summary s.json into hash (17 bytes). */
static long stop_step(const char *name, const char *deck, char *hash, char **err, char **dir) {
  int rc = yft_run_binary(name, deck, "-log none -summary s.json", err, dir);
  ck_assert_msg(rc == 3, "%s: exit %d: %s", name, rc, *err);
  const char *f = strstr(*err, "numerical failure at step ");
  ck_assert_msg(f, "%s: %s", name, *err);
  char path[4096];
  snprintf(path, sizeof path, "%s/s.json", *dir);
  char *js = yft_slurp(path, 0), *h = js ? strstr(js, "\"state_hash\": \"") : NULL;
  ck_assert_msg(h, "%s: no state_hash in %s", name, path);
  snprintf(hash, 17, "%s", h + 15);
  free(js);
  return strtol(f + 26, NULL, 10);
}

/* The energy check's memory goes into the restart (format 3): a run continued from one is stopped
 * at the step, with the message, of the run it continues.  The jointed block of
 * test_joined_skip_advice at safety 0.1 grows slowly and is stopped by the slow-growth windows at
 * step 2421, in one run of 4000 steps and in runs of 1800 + 2200.  Its restarts at step 1800
 * (write_restart, between the runs) and 2000 (restart every, within the second run) started the
 * check afresh: both continued runs ended "ok" at step 4000 (exit 0), energy from nowhere and all;
 * so did one at step 1700 within the one run. */
START_TEST(test_restart_keeps_energy_check) {
  static const char *const scene = BLOCK_ON_BASE "contact joined skip\n";
  char deck[2048], h_one[17], h_two[17], h[17];
  char *err_one, *err_two, *err, *dir_one, *dir_two, *dir;
  snprintf(deck, sizeof deck, "%svelocity blk set 0 -20\ntimestep auto safety 0.1\nrestart every 1700 q\nrun 4000\n", scene);
  long s_one = stop_step("one.deck", deck, h_one, &err_one, &dir_one);
  snprintf(deck, sizeof deck, "%svelocity blk set 0 -20\ntimestep auto safety 0.1\nrestart every 1000 p\nrun 1800\n"
           "write_restart h.restart\nrun 2200\n", scene);
  long s_two = stop_step("two.deck", deck, h_two, &err_two, &dir_two);
  fprintf(stderr, "energy: slow growth stopped at step %ld in one run, %ld in two\n", s_one, s_two);
  ck_assert_int_eq(s_two, s_one);
  ck_assert_str_eq(h_two, h_one);
  ck_assert_int_lt(s_one, 4000);
  ck_assert_int_gt(s_one, 2000); /* after both restarts */
  /* q: within the one run at step 1700, where a check is due (energy_check_due) after the restart
   * is written: the continued run does that check first (without it the message said "since step
   * 1624", the check before, where the uninterrupted one says 1700) */
  static const char *const cont[3] = {"h.restart", "p", "q"};
  for (int k = 0; k < 3; k++) {
    const char *from = k < 2 ? dir_two : dir_one, *want_h = k < 2 ? h_two : h_one;
    const char *want_msg = strstr(k < 2 ? err_two : err_one, "numerical failure");
    snprintf(deck, sizeof deck, "%sread_restart %s/%s\nrun 4000 upto\n", scene, from, cont[k]);
    long sk = stop_step("cont.deck", deck, h, &err, &dir);
    fprintf(stderr, "energy: continued from %s: stopped at step %ld, state_hash %s (uninterrupted %s)\n", cont[k], sk,
            h, want_h);
    ck_assert_int_eq(sk, s_one);
    ck_assert_str_eq(h, want_h);
    ck_assert_str_eq(strstr(err, "numerical failure"), want_msg); /* the same cause, reference step and advice */
    free(err);
    yft_rm_dir(dir);
  }
  free(err_one); free(err_two);
  yft_rm_dir(dir_one);
  yft_rm_dir(dir_two);
}
END_TEST

Suite *energy_suite(void) {
  Suite *s = suite_create("energy");
  TCase *tc = tcase_create("energy");
  tcase_set_timeout(tc, 120);
  tcase_add_test(tc, test_y2d_blowup_stops);
  tcase_add_test(tc, test_native_blowup_stops);
  tcase_add_test(tc, test_joint_release_runs);
  tcase_add_test(tc, test_auto_safety_one_stable);
  tcase_add_test(tc, test_negative_dissipation_stops);
  tcase_add_test(tc, test_energy_check_switch);
  tcase_add_test(tc, test_changes_between_runs_are_given);
  tcase_add_test(tc, test_bouncing_slab_not_stopped);
  tcase_add_test(tc, test_damping_with_prescribed_displacement);
  tcase_add_test(tc, test_change_after_restart_is_given);
  tcase_add_test(tc, test_y2d_at_rest_runs);
  tcase_add_test(tc, test_gravity_work_reported);
  tcase_add_test(tc, test_finite_strain_energy);
  tcase_add_test(tc, test_gravity_changed_between_runs);
  tcase_add_test(tc, test_displacement_jump_warned);
  tcase_add_test(tc, test_joint_split_not_dt);
  tcase_add_test(tc, test_mohr_coulomb_energy_named);
  tcase_add_test(tc, test_displacement_without_ramp_advice);
  tcase_add_test(tc, test_joined_skip_advice);
  tcase_add_test(tc, test_bounded_swing_not_stopped);
  tcase_add_test(tc, test_overlapping_fixes);
  tcase_add_test(tc, test_dissipation_beyond_given_stops);
  tcase_add_test(tc, test_start_overlap_named);
  tcase_add_test(tc, test_restart_keeps_energy_check);
  suite_add_tcase(s, tc);
  return s;
}
