/* energy.c: the energy balance of a run, and the check that stops a run whose balance does not
 * close (issues 17 and 22).
 *
 * This module owns the energy the scene was given and the balance residual
 *
 *   r = kinetic + strain + joint stored + contact          (stored now)
 *     + damping + fracture + friction                      (dissipated so far)
 *     - (energy at the start of the first run + work of loads, supports and gravity)   [J/m]
 *
 * The start energy counts everything the scene holds at step 0: kinetic, strain, joint and the
 * contact penalty energy of bodies that overlap in the input (a generated deck's rounded
 * coordinates): that energy is real and is released in the first steps (issue 22).  A stable
 * central-difference run closes r to its time-integration error, which is bounded: energy put at
 * once into modes the step barely resolves (an overlap at the start, an impact) is measured, with
 * half-step velocities, off the conserved discrete energy by up to s^2 / (1 - s^2) of it, s =
 * omega dt / 2 <= dt / dt_limit, and that offset then stays (docs/STABILITY.md).  An unstable
 * mode creates energy that grows exponentially, whether it stays as motion or is booked as
 * damping, fracture or friction.  With tol = ebal_tol (default YF_EBAL_TOL) x the energy given
 * + the energy of a 1e-8 strain everywhere (round-off), a run stops (exit 3) when
 *   - r > tol and r exceeds the largest offset a stable step can show, max(1, s^2 / (1 - s^2))
 *     times the energy given (the energy given alone above the limit), or
 *   - r > tol and r rose to a new high, by tol/10 and by a quarter, at each of GROWING checks in
 *     a row (energy from nowhere, wherever it went: a bounded offset stops setting new highs), and
 *     stayed at the last of those highs (less tol/10) or above at the HELD checks after (a
 *     bounded swing comes back down, energy from nowhere stays), or
 *   - r rose slowly: its range over WINDOW checks, as a fraction of the energy given, lay wholly
 *     above that of the window before at WINDOWS windows in a row, or
 *   - r > tol and more was dissipated (damping, fracture, friction) than the largest offset a
 *     stable step can show, and than the energy given: above the limit that is the energy given
 *     alone, and a step whose energy from nowhere the viscosity took as it came ended "ok" with a
 *     balance of the whole energy given (a Y2D deck at 1.6 x its limit), or
 *   - a dissipation is negative.
 * Dissipation beyond what the scene was given is energy from nowhere too: it is part of r.  The
 * message names the step, the energy that grew most since the last closed check and the stage
 * that owns it, and what to change.
 * What a deck does between two runs is energy given too: a `velocity set`, a body added, gravity
 * changed; a read_restart counts as a run that ended at its step.  So a later run takes the
 * residual of the state it starts from as the one the last run ended with (the budget moves by
 * the difference: nothing, bit for bit, when the deck changed nothing), and when the scene's
 * nodes or triangles changed, the contact energy of its first step is taken as given as at step
 * 0 (a body added where it overlaps another).
 * `energy_check warn|off` (the one deck switch) lets a run go on against that advice.
 */
#include <math.h>
#include <stdio.h>
#include <string.h>
#include "energy.h"
#include "contact.h"
#include "joint.h"
#include "par.h"

enum { T_KIN, T_STRAIN, T_JOINT, T_CONTACT, T_DAMP, T_FRACT, T_FRIC, NT };
static const char *const term_name[NT] = {
    "kinetic energy (stage 'update')",           "strain energy of the triangles (stage 'elements')",
    "energy stored in the joints (stage 'joints')", "contact penalty energy (stage 'contact')",
    "damping dissipation (stages 'elements' and 'update')", "fracture dissipation (stage 'joints')",
    "friction dissipation (stage 'contact')"};

static struct {
  double budget;     /* energy held at step 0 [J/m] */
  int budget_set;
  int contact_pending; /* the first step's contact energy (that of the start state) is still to add */
  double contact_base; /* ... less this much: the contact energy booked before it (0 at step 0) */
  int have_end;      /* a run of this process ended with the residual r_end, on nn_end nodes, nt_end triangles */
  double r_end;
  int nn_end, nt_end;
  double floor;      /* energy of a 1e-8 strain everywhere [J/m] */
  double last[NT];   /* the terms at the last closed check */
  long last_step;
  double r_max;      /* the largest residual of the checks so far */
  int streak;        /* consecutive checks above the tolerance with the residual still growing */
  double hold;       /* after GROWING new highs: the last of them less tol/10, which growth keeps above */
  int held;          /* ... checks since then at which the residual stayed above it (0: none pending) */
  long win;          /* 1 + the window of WINDOW checks the residual's range below is of (0: none yet) */
  double wmin, wmax; /* the residual's lowest and highest at the checks of that window ... */
  int wn;            /* ... at wn checks */
  double pmax;       /* the highest of the window before it, at pn checks (0: none) */
  int pn;
  int wgrow;         /* consecutive windows that lay wholly above the one before, above the tolerance */
  int warned;        /* warn mode: one warning per run */
  double overlap;    /* contact energy of a start state taken as given (bodies that start overlapping) [J/m] */
  long overlap_step; /* ... at the first step of the run that started at this step */
  long check_step;   /* the step of the last check (-1: none) */
  int resume;        /* read_restart of a restart written within a run: the next run goes on with the
                      * check's memory of that run instead of starting its own */
} E;

/* Checks in a row (100 steps apart) at which a residual above the tolerance must reach a new high,
 * by a tenth of the tolerance each, and then checks at which it must stay at the last of those
 * highs (less a tenth of the tolerance), before the run is stopped (below the hard bound).
 * Energy from nowhere stays in the balance (nothing takes it back); the half-step measure's
 * offset of a stable step is an oscillation, which checks at irregular steps meet at any phase:
 * three of them can rise in a row (a two-triangle square with a pulled corner, 0.85 x its exact
 * limit: residual 0.11, 0.18, 0.25 of the energy given at steps 107, 183, 322, then 0.22 and
 * -0.08, in a band -0.24..0.50 for 1e5 steps), but they come back down from a high.  Not to
 * where they began: the offset's mean is positive (a free square of 16 triangles set moving at
 * 0.9 x its limit: 0.21, 0.31, 0.47, then 0.29, 0.27, 0.40, in a band -0.16..0.72). */
#define GROWING 3
#define HELD 2
/* Slow growth (by less than a quarter a check, which never sets GROWING highs in a row): the
 * residual's range over WINDOW checks, as a fraction of the energy given, lies wholly above that of
 * the window before, by a tenth of the tolerance, WINDOWS times in a row.  WINDOW irregular checks
 * sample a bounded oscillation's band, its low phases too, so its windows overlap (the band is a
 * fraction of the energy given: a load that ramps up widens it, and the fraction stays); energy
 * made a little at every step lifts the whole range ('contact joined skip' at safety 0.1: 0.16-0.20,
 * 0.22-0.26 after 0.13-0.15 of the energy given). */
#define WINDOW 6
#define WINDOWS 2

void energy_reset(void) { memset(&E, 0, sizeof E); }
double energy_get_budget(void) { return E.budget; }
void energy_set_budget(double e) {
  E.budget = e;
  E.budget_set = 1;
  E.contact_pending = 0;
  E.have_end = 0;
}

/* The check's memory, in the order energy_restored reads it back. */
void energy_state_save(double d[ENERGY_STATE_ND], long l[ENERGY_STATE_NL]) {
  int k = 0;
  d[k++] = E.contact_base;
  for (int i = 0; i < NT; i++) d[k++] = E.last[i];
  d[k++] = E.r_max; d[k++] = E.hold; d[k++] = E.wmin; d[k++] = E.wmax; d[k++] = E.pmax; d[k++] = E.overlap;
  YF_ASSERT(k == ENERGY_STATE_ND);
  k = 0;
  l[k++] = E.contact_pending; l[k++] = E.last_step; l[k++] = E.streak; l[k++] = E.held; l[k++] = E.win;
  l[k++] = E.wn; l[k++] = E.pn; l[k++] = E.wgrow; l[k++] = E.warned; l[k++] = E.overlap_step; l[k++] = E.check_step;
  YF_ASSERT(k == ENERGY_STATE_NL);
}

/* A restart's state: its budget, and the residual it was written with (its energies were those of
 * its step), as if a run had ended there: a deck that changes the scene after read_restart gives
 * energy as between two runs.  With the check's memory (d, l) the residual's highs and windows go
 * on as in the uninterrupted deck (until format 3 they started afresh: a slow growth that spanned
 * a restart was stopped up to WINDOWS + 1 windows later, or not at all). */
void energy_restored(const YfSim *s, double budget, const double *d, const long *l) {
  energy_set_budget(budget);
  energy_run_end(s);
  E.resume = 0;
  if (!d || !l) {
    E.r_max = E.r_end;
    E.win = 0;
    E.wgrow = 0;
    E.pn = 0;
    E.check_step = -1;
    return;
  }
  int k = 0;
  E.contact_base = d[k++];
  for (int i = 0; i < NT; i++) E.last[i] = d[k++];
  E.r_max = d[k++]; E.hold = d[k++]; E.wmin = d[k++]; E.wmax = d[k++]; E.pmax = d[k++]; E.overlap = d[k++];
  k = 0;
  E.contact_pending = (int)l[k++]; E.last_step = l[k++]; E.streak = (int)l[k++]; E.held = (int)l[k++];
  E.win = l[k++]; E.wn = (int)l[k++]; E.pn = (int)l[k++]; E.wgrow = (int)l[k++]; E.warned = (int)l[k++];
  E.overlap_step = l[k++]; E.check_step = l[k++];
  E.resume = !s->restored_between;
}

/* Gravity's work is a function of the state: sum m g . (x - x0). */
/* (gravity's work: summed with the kinetic energy by run_energies, per block of nodes) */
double energy_external(const YfSim *s) { return s->energy.external_work + s->gravity_work; }

double energy_balance(const YfSim *s) {
  const YfEnergy *e = &s->energy;
  double diss = e->damping + e->joint_dissipated + e->friction;
  return e->kinetic + e->strain + e->contact + diss - energy_external(s) - E.budget;
}

int energy_dt_above_limit_ok(const YfSim *s) { return s->dt_warn_only || s->ebal_mode != YF_EBAL_STOP; }

static void terms(const YfSim *s, double *t) {
  const YfEnergy *e = &s->energy;
  t[T_KIN] = e->kinetic;
  t[T_STRAIN] = e->strain - s->joint_stored;
  t[T_JOINT] = s->joint_stored;
  t[T_CONTACT] = e->contact;
  t[T_DAMP] = e->damping;
  t[T_FRACT] = e->joint_dissipated;
  t[T_FRIC] = e->friction;
}

void energy_run_begin(YfSim *s, double e_floor) {
  E.floor = e_floor;
  if (s->step == 0 || !E.budget_set) {
    E.budget = s->energy.kinetic + s->energy.strain;
    E.budget_set = 1;
    E.contact_pending = s->step == 0;
    E.contact_base = 0.0;
  } else if (E.have_end) {
    /* the deck's changes since the last run (velocities set, gravity changed, bodies added):
     * energy given now, so the residual goes on from where that run left it */
    double r = energy_balance(s);
    if (isfinite(r) && isfinite(E.r_end)) E.budget += r - E.r_end;
    E.contact_pending = s->model.node.n != E.nn_end || s->model.tri.n != E.nt_end;
    E.contact_base = s->energy.contact;
  }
  if (E.resume) {
    /* a restart written within a run: the uninterrupted run went on from here with its streaks,
     * its reference terms and its warning; a periodic restart is written before its step's check */
    E.resume = 0;
    if (energy_check_due(s->step) && E.check_step != s->step) energy_check(s);
    return;
  }
  terms(s, E.last);
  E.last_step = s->step;
  /* the residual's highest so far is the scene's, not the run's (the residual goes on across
   * runs): a deck that runs in slices of 100 steps met a new "high" at every slice's first check */
  if (!E.have_end || s->step == 0) {
    E.r_max = energy_balance(s);
    E.win = 0;
    E.wgrow = 0;
    E.pn = 0;
  }
  E.streak = 0;
  E.held = 0;
  E.warned = 0;
}

/* After the first step s->energy.contact is the penalty energy at the positions of step 0. */
void energy_first_step(YfSim *s) {
  if (!E.contact_pending) return;
  E.contact_pending = 0;
  double c = s->energy.contact - E.contact_base;
  if (isfinite(c) && c > 0) {
    E.budget += c;
    E.overlap = c;
    E.overlap_step = s->step - 1;
  }
}

/* The checks' steps: one in each hundred, the c-th at step 100 c + j with j in -32..31 from a hash
 * of c, a function of the step alone (a restart checks where the uninterrupted run did).  At a fixed
 * interval a motion whose period divides it (a slab bouncing once every 100 steps) showed every
 * check the same phase. */
int energy_check_due(long step) {
  long c = (step + 50) / 100;
  if (c < 1) return 0;
  unsigned long h = ((unsigned long)c * 2654435761ul) & 0xfffffffful;
  return step == 100 * c + (long)(h >> 26) - 32;
}

void energy_run_end(const YfSim *s) {
  E.r_end = energy_balance(s);
  E.nn_end = s->model.node.n;
  E.nt_end = s->model.tri.n;
  E.have_end = 1;
}

/* What to change: the time step against the limit, and the switch. */
/* Most of the energy given is a start state's contact energy: bodies that start overlapping. */
static int overlap_dominates(const YfSim *s) { return E.overlap > 0.5 * (E.budget + fabs(energy_external(s))); }

const char *energy_overlap_note(const YfSim *s, char *buf, size_t n) {
  if (n) buf[0] = 0;
  if (overlap_dominates(s))
    snprintf(buf, n, "; the bodies started overlapping (their contact penalty energy at step %ld, %.6g J/m, is %.0f %% "
             "of the energy given, and the penalty throws them apart with it): check the bodies' positions and start "
             "them touching, not overlapping", E.overlap_step, E.overlap,
             100.0 * E.overlap / (E.budget + fabs(energy_external(s))));
  return buf;
}

static void advice(const YfSim *s, char *buf, size_t n) {
  double ratio = s->dt_limit > 0 && isfinite(s->dt_limit) ? s->dt / s->dt_limit : 0.0;
  YfContactExport ce;
  int skip = contact_export(s, &ce) && ce.joined_skip && s->joints && s->joints->n > 0;
  int k;
  const double scale = E.budget + fabs(energy_external(s));
  if (ratio > 1.0)
    k = snprintf(buf, n, "the time step %.6g s is %.3g x the stable limit %.6g s (set by %s): use at most %.6g s%s",
                 s->dt, ratio, s->dt_limit, s->dt_limiter, YF_DT_SAFETY_RECOMMENDED * s->dt_limit,
                 s->y2d ? " (DCSTEC of the .y deck)" : " ('timestep auto')");
  else if (overlap_dominates(s))
    /* two 1 m squares placed 0.65 m into each other (a second Gmsh body not moved off the first):
     * 4.3e7 J/m of penalty energy at once, released at 2.6 km/s, stopped at step 107 with the
     * time-step advice, which does not help: the start state is the cause */
    k = snprintf(buf, n, "the bodies start overlapping: their contact penalty energy at step %ld, %.6g J/m, is %.0f %% "
                 "of the energy given, and the penalty throws them apart with it; check the bodies' positions (a mesh "
                 "placed into another, a body not moved off its neighbour) and start them touching, not overlapping; "
                 "the time step %.6g s is %.3g x the stable limit %.6g s (set by %s)", E.overlap_step, E.overlap,
                 100.0 * E.overlap / scale, s->dt, ratio, s->dt_limit, s->dt_limiter);
  else if (ratio > 0 && skip)
    /* a block with joints hitting a base at 20 m/s: 13 % of the impact energy from nowhere at
     * safety 0.5 and at 0.1 alike, none with joined keep; the time step advice sent users astray */
    k = snprintf(buf, n, "the scene's 'contact joined skip' lets a couple of triangles into the contact list only once "
                 "their joint has failed, often already overlapping (a joint in compression), and the penalty energy of "
                 "that overlap comes from nowhere whatever the time step: use 'contact joined keep' (the default, Y2D's) "
                 "for this scene; the time step %.6g s is %.3g x the stable limit %.6g s (set by %s)", s->dt, ratio,
                 s->dt_limit, s->dt_limiter);
  else if (ratio > 0)
    k = snprintf(buf, n, "the time step %.6g s is %.3g x the stable limit %.6g s (set by %s): reduce it "
                 "('timestep auto safety %.2g' or less%s), and check the scene for bodies that start overlapping "
                 "or loads that do work the balance cannot see", s->dt, ratio, s->dt_limit, s->dt_limiter,
                 ratio < 0.6 ? 0.5 * ratio : 0.5, s->y2d ? ", or DCSTEC of the .y deck" : "");
  else
    k = snprintf(buf, n, "reduce the time step (%.6g s)", s->dt);
  if (k > 0 && (size_t)k < n)
    snprintf(buf + k, n - (size_t)k, "; to run on against this advice put 'energy_check warn' (or off) before run");
}

/* The name of a joint set of the scene with a Mohr-Coulomb shear strength (cohesion and friction
 * > 0), or NULL.  That law (ALGORITHMS 3.5, Y2D's) scales a joint's whole shear curve, its pre-peak
 * part and its secant unloading too, by f_s = c - sigma mu: the shear force at a fixed slip grows
 * with the compression although no work is done, so it derives from no potential.  A joint taken
 * round a closed loop (slip 0.8 s_p, press to 2 MPa, slip back, release; mu 0.6) comes back to
 * its state having given 1.55e-5 J/m more than it took (12 % of its shear energy), the opposite
 * loop takes it back: the joints make energy, and in a dynamic scene a vibration can feed on it and
 * grow (a direct shear test under 2 MPa: kinetic energy 2e-5 to 10 J/m in 0.4 ms before any shear,
 * with dt halved too).  No stored-energy estimate that is a function of the state can book this
 * as a dissipation >= 0, so the check names the cause rather than the split or the time step. */
static const char *mohr_coulomb_set(const YfSim *s) {
  const YfJoints *J = s->joints;
  if (!J || J->n <= 0) return NULL;
  for (int i = 0; i < J->nset; i++)
    if (J->set[i].p.coh > 0.0 && J->set[i].p.phi > 0.0) return J->set[i].name;
  return NULL;
}

/* This check's residual r against the ones before (tol: the tolerance, scale: the energy given
 * [J/m]): 1 when it has grown as energy from nowhere does, fast (GROWING new highs, then held HELD
 * checks) or slowly (its range over WINDOW checks above that of the window before, WINDOWS times
 * in a row). */
static int grown(double r, double tol, double scale, long step) {
  /* a new high of the residual, by a tenth of tol and by a quarter of the last high: the
   * half-step measure of a stable motion swings within a bound (above tol when the step is near
   * the limit) and checks at irregular steps meet its phases in any order, so small new highs come
   * and go; an unstable mode's energy grows by a factor at every check */
  int higher = r > E.r_max + fmax(0.1 * tol, 0.25 * fabs(E.r_max));
  int fast = 0, slow = 0;
  if (E.streak >= GROWING) { /* the highs are to be held: a bounded swing comes back down */
    if (r >= E.hold) fast = ++E.held >= HELD;
    else E.streak = E.held = 0;
  } else if (r > tol && higher) {
    E.streak++;
    E.hold = r - 0.1 * tol;
  } else {
    E.streak = 0;
  }
  long w = (step + 50) / 100 / WINDOW + 1;
  double q = r / (scale + E.floor), tq = tol / (scale + E.floor); /* fractions of the energy given */
  if (!(scale + E.floor > 0)) q = tq = 0.0;
  if (w != E.win) { /* the window E.win is complete; a window begun part way (a run from a restart)
                     * has sampled too few phases to compare */
    if (E.win > 0) {
      int full = E.wn >= WINDOW / 2 && E.pn >= WINDOW / 2;
      E.wgrow = full && E.wmin > tq && E.wmin > E.pmax + 0.1 * tq ? E.wgrow + 1 : 0;
      E.pmax = E.wmax;
      E.pn = E.wn;
    }
    E.win = w;
    E.wmin = E.wmax = q;
    E.wn = 1;
  } else {
    E.wmin = fmin(E.wmin, q);
    E.wmax = fmax(E.wmax, q);
    E.wn++;
  }
  slow = E.wgrow >= WINDOWS;
  return fast || slow;
}

void energy_check(YfSim *s) {
  E.check_step = s->step;
  if (s->ebal_mode == YF_EBAL_OFF) return;
  double t[NT];
  terms(s, t);
  double ext = energy_external(s);
  double given = E.budget + ext, scale = E.budget + fabs(ext);
  double diss = t[T_DAMP] + t[T_FRACT] + t[T_FRIC];
  double r = energy_balance(s);
  double tol = s->ebal_tol * scale + E.floor;
  /* the largest offset a stable step can show: s^2 / (1 - s^2) of the energy, s = dt / dt_limit;
   * at least the energy given (s <= 0.7), and that alone above the limit (no bound there) */
  double sr = s->dt_limit > 0 ? s->dt / s->dt_limit : 2.0;
  double hard = scale * (sr < 1.0 ? fmax(1.0, sr * sr / (1.0 - sr * sr)) : 1.0) + tol;
  int finite = isfinite(r) && isfinite(ext);
  for (int i = 0; i < NT; i++) finite = finite && isfinite(t[i]);
  int growing = finite && grown(r, tol, scale, s->step);
  char what[640];
  what[0] = 0;
  int grew = -1;
  if (!finite) {
    snprintf(what, sizeof what, "the energies are not finite (the motion blew up)");
  } else if (r > tol && (r > hard || diss > fmax(hard, given + tol) || growing)) {
    double best = -INFINITY;
    for (int i = 0; i < NT; i++)
      if (t[i] - E.last[i] > best) { best = t[i] - E.last[i]; grew = i; }
    snprintf(what, sizeof what, "energy balance not closed: %.6g J/m appeared from nowhere (kinetic %.6g + stored "
             "%.6g + dissipated %.6g - given %.6g J/m), %s; since step %ld the %s grew most (+%.6g J/m)", r,
             t[T_KIN], t[T_STRAIN] + t[T_JOINT] + t[T_CONTACT], diss, given,
             diss > fmax(hard, given + tol) ? (r > hard ? "more than a stable step can show, and more was dissipated than given"
                                                        : "more was dissipated than the scene was given")
             : r > hard ? "more than a stable step can show" : "still growing at every check",
             E.last_step, term_name[grew], best);
  } else {
    for (int i = T_DAMP; i < NT && grew < 0; i++)
      if (t[i] < -tol) grew = i;
    if (grew >= 0)
      snprintf(what, sizeof what, "%s: negative %s of %.6g J/m (tolerance %.6g J/m)",
               grew == T_FRACT && fabs(r) <= tol ? "energy split wrong" : "energy balance not closed",
               term_name[grew], t[grew], tol);
  }
  if (!what[0]) {
    if (r > E.r_max) E.r_max = r;
    if (E.streak == 0 && E.wgrow == 0) { /* the reference of "grew most": the last check that was closed or steady */
      memcpy(E.last, t, sizeof t);
      E.last_step = s->step;
    }
    return;
  }
  char adv[640];
  const char *mc = mohr_coulomb_set(s);
  if (mc && (t[T_FRACT] < -tol || t[T_JOINT] < -tol))
    snprintf(adv, sizeof adv, "the joints gave back more work than they took in: the Mohr-Coulomb shear strength of "
             "jointprop %s (cohesion C friction MU, Y2D's rule) scales a joint's whole shear curve with its normal "
             "stress, so a joint that slips and is then pressed harder returns more than it stored, and a vibration "
             "can feed on it; neither a smaller time step nor 'damage reversible' changes this (friction 0 does); "
             "to run on put 'energy_check warn' (or off) before run", mc);
  else if (grew == T_FRACT && fabs(r) <= tol)
    /* The balance itself is closed: the motion conserved energy, and only the split of the joints'
     * work into stored and dissipated is off.  Their stored energy is the secant estimate of the
     * irreversible law; unloading inside its damage envelope across mixed modes (toward the origin
     * along rays) is not a potential, and when f_t and f_s differ by orders of magnitude the estimate
     * exceeds the work the joints took in.  This does not go with the time step (a bar pulled apart
     * with f_t 1 Pa, f_s 3 MPa: -6.9e-4, -4.4e-4, -5.8e-4, -5.8e-4 J/m of 0.016 at safety 0.5, 0.25,
     * 0.1, 0.05), so the time-step advice would mislead. */
    snprintf(adv, sizeof adv, "the balance itself closes (residual %.3g J/m): the joints' secant estimate of their stored "
             "energy exceeds the work they took in, which the irreversible law's unloading across mixed modes "
             "does when f_t and f_s differ widely, whatever the time step; 'damage reversible' (Y2D's law) books "
             "none of this, or put 'energy_check warn' (or off) before run to go on", r);
  else
    advice(s, adv, sizeof adv);
  /* MPI: every rank is here (the energies are every rank's), so the failed run's summary can
   * hash the whole state */
  if (s->ebal_mode == YF_EBAL_STOP) par_need_all(s);
  if (s->ebal_mode == YF_EBAL_STOP) yf_numeric_error(s->step, "%s; %s", what, adv);
  if (!E.warned) yf_warn(NULL, "step %ld: %s; the run goes on ('energy_check warn')", s->step, what);
  E.warned = 1;
}
