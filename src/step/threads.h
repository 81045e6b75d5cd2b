/* threads.h: how many threads the step uses (docs/THREADS.md).  See threads.c. */
#ifndef YF_THREADS_H
#define YF_THREADS_H

/* The governor: a state machine fed with the wall time of each step, answering the thread count
 * of the next step.  Plain data so that tests can drive it with made-up times. */
#define YF_GOV_WINDOW 5 /* steps per timed window (the median is compared) */
typedef struct {
  int cap;          /* the most threads (OMP_NUM_THREADS or the cores); 1: nothing to choose */
  int cur, best;    /* threads of the next step; the count chosen by the last comparison */
  int phase;        /* 0 skip the first step (cold caches), 1 timing cur, 2 probing the other count */
  long left;        /* steps left in this phase (phase 1: before the next probe) */
  long interval;    /* steps between probes: doubles while the choice holds, resets when it flips */
  long interval0, interval_max;
  int n;            /* times in the window */
  double t[YF_GOV_WINDOW];      /* the current count's last step times [s] (a ring) */
  double probe[YF_GOV_WINDOW];  /* the probed count's step times [s] */
  double tref;                  /* the chosen count's median when chosen [s] */
  long steps_at[2];             /* steps run on 1 thread, on cap threads (the run line's report) */
  int switches;
} YfGov;

void gov_init(YfGov *g, int cap);
/* the step just taken took `seconds`: returns the thread count of the next step */
int gov_step(YfGov *g, double seconds);

/* The step's thread setting: n >= 1 runs exactly n threads (the -threads option), 0 lets the
 * governor choose between 1 and the OpenMP maximum every so often (the default). */
void threads_set(int n);
int threads_fixed(void);
/* Probe intervals of the governor (tests make it switch every few steps). */
void threads_set_probe(long first, long max);
/* Around a run: begin sets the first step's count and returns the cap; end restores the
 * OpenMP maximum and says how the steps were shared (for the run line; NULL if not governed). */
int threads_run_begin(void);
int threads_after_step(double seconds);
const char *threads_run_end(char *buf, int n);
/* the last run's steps on 1 thread and on more (tests) */
void threads_last_run(long *on1, long *onmore);

#endif
