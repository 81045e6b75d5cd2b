/* threads.c: the thread count of each step, so that threads never lose (issue 24, docs/THREADS.md).
 *
 * Every loop of the step is static or works on fixed blocks, so any thread count gives the same
 * bits (check_parallel.c), and the count may change between two steps.  On an idle machine two
 * threads run the large scenes about 1.8x faster than one; on a machine with other work, each
 * of the step's parallel regions ends in a barrier that waits for the slowest thread, and a
 * descheduled thread makes every barrier cost up to a time slice: two threads then run several
 * times slower than one.  Which case holds is known only by timing it, and it changes while a run
 * goes on (a build starts, ParaView opens).  So the governor times the steps: it starts on the
 * team, and runs a few steps on the other count when the team's threads are descheduled (the
 * process's CPU time per step is well under threads x wall time) or every so often, and keeps
 * the faster (the median of a window of steps, so that a step with a contact search or a stray
 * interruption does not decide).  A probe that is clearly losing stops after two steps; while the
 * choice holds the probes get rarer (x4 each time, up to every 1600 steps; 3x rarer still for a
 * team that has its cores), so a run on a busy machine pays a few percent for them and one on an
 * idle machine next to nothing.  `-threads N` fixes the count (no probes), as LAMMPS's
 * `-pk omp N`.
 *
 * Owns: the fixed/automatic setting, the governor's state of the current run.
 */
#include "threads.h"

#include <stdio.h>

#include "parfor.h"
#include "stage_time.h"
#ifdef _OPENMP
#include <omp.h>
#endif

static int g_fixed;               /* 0: automatic; n: exactly n threads */
static long g_first = 100, g_max = 1600; /* probe intervals [steps] */
static YfGov G;
static int g_omp_max;             /* the OpenMP maximum when the run began (restored at its end) */
static double g_cpu0;             /* the process's CPU clock when the step began [s] */
static unsigned long g_want0;     /* yf_team_wanted when the step began (parfor.h) */
static int g_clocked;             /* this step's CPU clock was read at its start */
static int g_wanted_last;         /* the last step asked for the team */

static int omp_max(void) {
#ifdef _OPENMP
  return omp_get_max_threads();
#else
  return 1;
#endif
}

static void omp_use(int n) {
#ifdef _OPENMP
  omp_set_num_threads(n);
#else
  (void)n;
#endif
}

static double median(const double *v, int n) {
  double a[YF_GOV_WINDOW] = {0};
  n = n < 1 ? 1 : n > YF_GOV_WINDOW ? YF_GOV_WINDOW : n; /* 1 to 5 times (a probe from 2 on) */
  for (int i = 0; i < n; i++) { /* insertion sort: n <= 5 */
    double x = v[i];
    int j = i;
    for (; j > 0 && a[j - 1] > x; j--) a[j] = a[j - 1];
    a[j] = x;
  }
  return n % 2 ? a[n / 2] : 0.5 * (a[n / 2 - 1] + a[n / 2]);
}

/* The share of its wall time the step's threads ran: the process's CPU time over threads x wall.
 * A team whose threads have their cores runs them all the time (waiting threads spin, and spinning
 * is CPU time too); with one competitor on 2 cores it gets 2/3 of it. */
static double utilisation(const YfGov *g, double seconds, double cpu) {
  return seconds > 0 ? cpu / ((double)g->cur * seconds) : 1.0;
}

void gov_init(YfGov *g, int cap) {
  *g = (YfGov){0};
  g->cap = cap > 1 ? cap : 1;
  /* the team first: on an idle machine it is the faster, and on a busy one its steps show their
   * descheduling (utilisation) within two steps, when one thread is probed */
  g->cur = g->best = g->cap;
  g->interval0 = g_first;
  g->interval_max = g_max;
  g->interval = g->interval0;
  g->uref = 1.0;
  g->left = 1; /* the first step warms caches and pages (and searches contact): not timed */
}

/* Steps before the next probe.  A team whose threads had their cores when it was chosen probes
 * one thread 3x more rarely: on an idle machine the probe is all the governor costs (PERF.md's
 * 1e5 problem, 150 steps: 9 steps on one thread made the run 10 % slower than -threads 2), and a
 * competitor that arrives shows in the utilisation at once. */
static long next_probe(const YfGov *g) {
  return g->best > 1 && g->uref >= YF_GOV_ULOW ? 3 * g->interval : g->interval;
}

/* Does the probed count win?  The team must beat one thread by 5 %: on an idle machine two
 * threads are far ahead, and a near tie goes to one thread, which leaves the cores to others. */
static int probe_wins(const YfGov *g, double tprobe, double tcur) {
  return g->cur > 1 ? tprobe < 0.95 * tcur : 0.95 * tprobe < tcur;
}

int gov_step(YfGov *g, double seconds, double cpu) {
  if (g->cap <= 1) return 1;
  g->steps_at[g->cur > 1]++;
  switch (g->phase) {
  case 0: /* untimed step */
    if (--g->left > 0) break;
    g->phase = 1;
    g->n = 0;
    g->left = next_probe(g);
    break;
  case 1: { /* the chosen count: keep the window's last times, probe when due */
    const double u = utilisation(g, seconds, cpu);
    const double uprev = g->n > 0 ? g->u[(g->n - 1) % YF_GOV_WINDOW] : 1.0;
    g->t[g->n % YF_GOV_WINDOW] = seconds;
    g->u[g->n % YF_GOV_WINDOW] = u;
    g->n++;
    --g->left;
    g->m = g->n < YF_GOV_WINDOW ? g->n : YF_GOV_WINDOW;
    /* two team steps in a row descheduled (below 0.85, and 0.1 below the team's share when it
     * was chosen on a busy machine): a competitor came, or the run began beside one; probe one
     * thread now, with the times there are */
    const double ulow = g->uref - 0.1 < YF_GOV_ULOW ? g->uref - 0.1 : YF_GOV_ULOW;
    if (g->cur > 1 && g->n >= 2 && u < ulow && uprev < ulow) { /* compare with these two only */
      const double t1 = g->t[(g->n - 2) % YF_GOV_WINDOW];
      g->t[0] = t1;
      g->t[1] = seconds;
      g->u[0] = uprev;
      g->u[1] = u;
      g->m = 2;
    } else {
      if (g->n < YF_GOV_WINDOW) break;
      if (g->tref <= 0) {
        g->tref = median(g->t, YF_GOV_WINDOW);
        if (g->cur > 1) g->uref = median(g->u, YF_GOV_WINDOW);
      }
      /* the team's steps got slower (a competitor came): probe one thread now.  One thread's
       * own slowdowns (noise of a busy machine, a costlier scene) wait for the next probe. */
      if (g->left > 0 && (g->cur == 1 || median(g->t, YF_GOV_WINDOW) <= 1.5 * g->tref)) break;
    }
    g->phase = 2;
    g->cur = g->best > 1 ? 1 : g->cap;
    g->n = -1; /* the switch's first step (a team waking up): see below */
    break;
  }
  case 2: { /* the other count */
    const double tc = median(g->t, g->m);
    int done = 0, win = 0;
    if (g->n < 0) { /* the switch's step (a team waking up) is not in the median, but 3x slower
                     * on its own it has lost already */
      done = seconds > 3.0 * tc;
    } else {
      g->probe[g->n] = seconds;
      g->probe_u[g->n] = utilisation(g, seconds, cpu);
    }
    g->n++;
    if (g->n == YF_GOV_WINDOW) {
      done = 1;
      win = probe_wins(g, median(g->probe, g->n), tc);
    } else if (!done && g->n >= 1) { /* clearly losing: its first step 3x the median, or its
                                      * fastest of two or more 30 % behind */
      double fast = g->probe[0];
      for (int i = 1; i < g->n; i++) fast = g->probe[i] < fast ? g->probe[i] : fast;
      done = fast > (g->n == 1 ? 3.0 : 1.3) * tc;
    }
    if (!done) break;
    if (win) {
      g->best = g->cur;
      g->switches++;
      g->interval = g->interval0;
      for (int i = 0; i < YF_GOV_WINDOW; i++) {
        g->t[i] = g->probe[i];
        g->u[i] = g->probe_u[i];
      }
      g->m = YF_GOV_WINDOW;
    } else {
      g->interval = 4 * g->interval < g->interval_max ? 4 * g->interval : g->interval_max;
    }
    /* the kept count's times, whichever won; a team kept while descheduled probes again when
     * its share drops further, or its steps get 1.5x slower */
    g->tref = median(g->t, g->m);
    if (g->best > 1) g->uref = median(g->u, g->m);
    g->cur = g->best;
    g->phase = 1;
    g->n = 0;
    g->left = next_probe(g);
    break;
  }
  }
  return g->cur;
}

void threads_set(int n) { g_fixed = n > 0 ? n : 0; }
int threads_fixed(void) { return g_fixed; }

void threads_set_probe(long first, long max) {
  g_first = first > 0 ? first : 1;
  g_max = max > g_first ? max : g_first;
}

int threads_run_begin(void) {
  g_omp_max = omp_max();
  if (g_fixed) {
    omp_use(g_fixed);
    gov_init(&G, 1);
    return g_fixed;
  }
  gov_init(&G, g_omp_max);
  g_wanted_last = 1; /* the first step is clocked */
  omp_use(G.cur);
  return G.cap;
}

void threads_last_run(long *on1, long *onmore) {
  *on1 = G.steps_at[0];
  *onmore = G.steps_at[1];
}

/* Only the steps in which a loop asked for the team (parfor.h's count) are timed: a step whose
 * loops are all below their thresholds (a scene of a few thousand triangles) runs on one thread
 * whatever the team, so there is nothing to choose, and its two reads of the CPU clock (system
 * calls) were two thirds of a 16-triangle scene's step by default (1.2 -> 3.5 s for 3e5 steps).
 * A step is clocked when the step before it asked for the team; one that asks without being
 * clocked (the first to) is not timed. */

/* one CPU clock read per step (a system call, under a microsecond), only when governed */
void threads_step_begin(void) {
  if (G.cap <= 1) return;
  g_want0 = yf_team_wanted;
  g_clocked = g_wanted_last;
  if (g_clocked) g_cpu0 = yf_cpu_now();
}

int threads_after_step(double seconds) {
  if (G.cap <= 1) return omp_max();
  g_wanted_last = yf_team_wanted != g_want0;
  if (!g_wanted_last) { /* every loop ran as a plain loop: the step was on one thread, whatever the team */
    G.steps_at[0]++;
    return G.cur;
  }
  if (!g_clocked) {
    G.steps_at[G.cur > 1]++; /* the run line's report counts it on the current count */
    return G.cur;
  }
  int was = G.cur, n = gov_step(&G, seconds, yf_cpu_now() - g_cpu0);
  if (n != was) omp_use(n);
  return n;
}

const char *threads_run_end(char *buf, int n) {
  omp_use(g_fixed ? g_fixed : g_omp_max);
  long tot = G.steps_at[0] + G.steps_at[1];
  if (G.cap <= 1 || tot == 0) return NULL;
  snprintf(buf, (size_t)n, "auto: %ld steps on %d, %ld on 1", G.steps_at[1], G.cap, G.steps_at[0]);
  return buf;
}
