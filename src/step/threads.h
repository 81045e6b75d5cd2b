/* threads.h: how many threads the step uses (docs/THREADS.md).  See threads.c. */
#ifndef YF_THREADS_H
#define YF_THREADS_H

/* The governor: a state machine fed with the wall and CPU time of each step, answering the thread
 * count of the next step.  Plain data so that tests can drive it with made-up times. */
#define YF_GOV_WINDOW 5  /* steps per timed window (the median is compared) */
#define YF_GOV_ULOW 0.85 /* a team step whose threads ran less than this share of its wall time
                          * was descheduled (one competitor on 2 cores: 2/3) */
typedef struct {
  int cap;          /* the most threads (OMP_NUM_THREADS or the cores); 1: nothing to choose */
  int cur, best;    /* threads of the next step; the count chosen by the last comparison */
  int phase;        /* 0 skip the first step (cold caches), 1 timing cur, 2 probing the other count */
  long left;        /* steps left in this phase (phase 1: before the next probe) */
  long interval;    /* steps between probes: doubles while the choice holds, resets when it flips */
  long interval0, interval_max;
  int n;            /* times in the window */
  int m;            /* the current count's times the probe compares with (n of phase 1, <= window) */
  double t[YF_GOV_WINDOW];      /* the current count's last step times [s] (a ring) */
  double u[YF_GOV_WINDOW];      /* their utilisation: CPU time / (threads x wall time) */
  double probe[YF_GOV_WINDOW];  /* the probed count's step times [s] */
  double probe_u[YF_GOV_WINDOW];
  double tref;                  /* the chosen count's median when chosen [s] */
  double uref;                  /* the team's median utilisation when chosen (1 until measured) */
  long steps_at[2];             /* steps run on 1 thread, on cap threads (the run line's report) */
  int switches;
} YfGov;

void gov_init(YfGov *g, int cap);
/* the step just taken took `seconds` of wall time and `cpu` seconds of the process's CPU time
 * (all its threads): returns the thread count of the next step */
int gov_step(YfGov *g, double seconds, double cpu);

/* The step's thread setting: n >= 1 runs exactly n threads (the -threads option), 0 lets the
 * governor choose between 1 and the OpenMP maximum every so often (the default). */
void threads_set(int n);
int threads_fixed(void);
/* Probe intervals of the governor (tests make it switch every few steps). */
void threads_set_probe(long first, long max);
/* Around a run: begin sets the first step's count and returns the cap; end restores the
 * OpenMP maximum and says how the steps were shared (for the run line; NULL if not governed). */
int threads_run_begin(void);
void threads_step_begin(void); /* before each step: the CPU clock, when the governor needs it */
int threads_after_step(double seconds);
const char *threads_run_end(char *buf, int n);
/* the last run's steps on 1 thread and on more (tests) */
void threads_last_run(long *on1, long *onmore);

#endif
