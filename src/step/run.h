/* run.h: the explicit time loop. */
#ifndef YF_RUN_H
#define YF_RUN_H
#include "sim.h"
#include "elem_tri.h"
#include "stage_time.h" /* the stage timers, YF_ST_* */
/* Prepare the model (masses, reference inverses, gather lists, bc) for stepping.  Idempotent. */
void run_prepare(YfSim *s);
/* Advance n steps. */
void run_steps(YfSim *s, long n);
/* Current energies into s->energy (kinetic, strain; accumulated terms are kept).  MPI: a
 * collective (each rank sums what it owns); run_energies_whole sums everything on the calling
 * rank alone, from a whole state (a writer after par_need_all, a deck expression between runs). */
void run_energies(YfSim *s);
void run_energies_whole(YfSim *s);
/* A numerical failure (exit 3) naming the first node of i0..i1-1 whose position or velocity is not
 * finite or beyond YF_RANGE_MAX: the writers of frames and rows call it first, so no file holds
 * a non-finite number. */
void run_check_nodes(YfSim *s, int i0, int i1);
/* Stable time step of the prepared model and what limits it. */
double run_stable_dt(YfSim *s, char *limiter, size_t n);
/* Bytes held by the model's arrays (for the benchmark's bytes per element). */
double run_model_bytes(const YfSim *s);
/* Material constants of the prepared model, indexed by material (for tests and diagnostics). */
/* Material constants of the prepared model, indexed by material (tests, diagnostics). */
const YfTriMat *run_tri_mats(void);
/* Release the loop's work arrays (at exit). */
void run_free(void);
/* Loops of the step shorter than par_min run on one thread; block = triangles per block of the
 * force loop (default 16384 and 2048; tests lower them to run small scenes threaded). */
void run_set_par_min(int par_min, int block);

#endif
