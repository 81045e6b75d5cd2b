/* energy.h: the energy balance of a run and the check that stops a run whose balance does not
 * close (energy.c).  run.c calls, in this order:
 *   energy_run_begin   at the start of every run command, after run_energies;
 *   energy_first_step  after the first step of a run (the contact energy of the start state);
 *   energy_check       about every 100 steps (energy_check_due) and at the end of the run;
 *   energy_run_end     at the end of the run, after its last check (what the next run starts from);
 *   energy_balance     for the thermo Balance column.
 */
#ifndef YF_ENERGY_H
#define YF_ENERGY_H
#include "sim.h"

/* Check modes of the energy_check command (YfSim.ebal_mode). */
enum { YF_EBAL_STOP = 0, YF_EBAL_WARN, YF_EBAL_OFF };

/* Default tolerance of the balance, as a fraction of the energy the scene was given. */
#define YF_EBAL_TOL 0.05
/* Recommended safety factor of `timestep auto` (docs/STABILITY.md: the study's smallest margin). */
#define YF_DT_SAFETY_RECOMMENDED 0.9

void energy_run_begin(YfSim *s, double e_floor);
void energy_first_step(YfSim *s);
void energy_run_end(const YfSim *s);
/* Whether an energy check is due after the step that made s->step = step (about every 100). */
int energy_check_due(long step);
/* Reads s->energy as run_energies (run.h) left it at this step. */
void energy_check(YfSim *s);
/* Work of loads, supports, prescribed motion and gravity so far [J/m]. */
double energy_external(const YfSim *s);
/* kinetic + stored + dissipated - given [J/m] (s->energy as last evaluated): ~0 when healthy. */
double energy_balance(const YfSim *s);
/* 1 when a deck's time step above the stable limit is accepted with a warning instead of refused
 * (Y2D decks, and native decks that said `energy_check warn|off`). */
int energy_dt_above_limit_ok(const YfSim *s);
/* The energy given at the start [J/m] (restart.c saves and restores it). */
double energy_get_budget(void);
void energy_set_budget(double e);
/* The check's memory (its highs, windows, streaks, reference terms) for a restart, so that a run
 * continued from one is stopped at the step the uninterrupted run is: ENERGY_STATE_ND doubles and
 * ENERGY_STATE_NL longs, in an order only energy.c knows (restart.c stores them as they are). */
enum { ENERGY_STATE_ND = 14, ENERGY_STATE_NL = 11 };
void energy_state_save(double d[ENERGY_STATE_ND], long l[ENERGY_STATE_NL]);
/* read_restart: the budget, and the state's energies as those a run ended with (s->energy as the
 * restart holds them; changes the deck makes before the next run are energy given).  d and l: the
 * check's memory energy_state_save gave (NULL: a restart of a format without it, the check starts
 * afresh); within a run (!s->restored_between) the next run goes on with it as the interrupted run
 * would have, streaks and the check due at the restart's step included. */
void energy_restored(const YfSim *s, double budget, const double *d, const long *l);
void energy_reset(void);
/* When most of the energy given is the contact energy of a start state (bodies that start
 * overlapping), a clause for a numerical failure's message naming it ("; the bodies started
 * overlapping: ..."), written into buf; "" otherwise.  Returns buf. */
const char *energy_overlap_note(const YfSim *s, char *buf, size_t n);

#endif
