/* stage_time.h: the wall-clock timers of a step's stages (the benchmark's breakdown).
 *
 * The run loop (run.c) times most stages itself; contact.c times detection and pair forces
 * inside its stage.  Both reach the timers here, so contact needs nothing of the run loop.
 */
#ifndef YF_STAGE_TIME_H
#define YF_STAGE_TIME_H

/* Stages of a step, timed separately for the benchmark's breakdown. */
enum { YF_ST_ELEMENTS, YF_ST_JOINTS, YF_ST_DETECT, YF_ST_CONTACT, YF_ST_GATHER, YF_ST_UPDATE, YF_ST_OUTPUT, YF_NSTAGE };
extern const char *const yf_stage_names[YF_NSTAGE];
extern double yf_stage_time[YF_NSTAGE]; /* seconds accumulated over all runs */

/* Monotonic wall clock [s] (stage timers). */
double yf_now(void);
/* CPU seconds of the process, all threads (MPI: the work a rank did, whatever the machine's load). */
double yf_cpu_now(void);

#endif
