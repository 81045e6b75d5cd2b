/* threads.c: the thread count of each step, so that threads never lose (issue 24, docs/THREADS.md).
 *
 * Every loop of the step is static or works on fixed blocks, so any thread count gives the same
 * bits (check_parallel.c), and the count may change between two steps.  On an idle machine two
 * threads run the large scenes about 1.8x faster than one; on a machine with other work, each
 * of the step's parallel regions ends in a barrier that waits for the slowest thread, and a
 * descheduled thread makes every barrier cost up to a time slice: two threads then run several
 * times slower than one.  Which case holds is known only by timing it, and it changes while a run
 * goes on (a build starts, ParaView opens).  So the governor times the steps: it starts on one
 * thread, then every so often runs a few steps on the other count and keeps the faster (the
 * median of a window of steps, so that a step with a contact search or a stray interruption does
 * not decide).  A probe that is clearly losing stops after two steps; while the choice holds the
 * probes get rarer (x4 each time, up to every 1600 steps), so a run on a busy machine pays a few
 * percent for them.  `-threads N` fixes the count (no probes), as LAMMPS's `-pk omp N`.
 *
 * Owns: the fixed/automatic setting, the governor's state of the current run.
 */
#include "threads.h"

#include <stdio.h>
#ifdef _OPENMP
#include <omp.h>
#endif

static int g_fixed;               /* 0: automatic; n: exactly n threads */
static long g_first = 100, g_max = 1600; /* probe intervals [steps] */
static YfGov G;
static int g_omp_max;             /* the OpenMP maximum when the run began (restored at its end) */

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
  double a[YF_GOV_WINDOW];
  for (int i = 0; i < n; i++) { /* insertion sort: n <= 5 */
    double x = v[i];
    int j = i;
    for (; j > 0 && a[j - 1] > x; j--) a[j] = a[j - 1];
    a[j] = x;
  }
  return n % 2 ? a[n / 2] : 0.5 * (a[n / 2 - 1] + a[n / 2]);
}

void gov_init(YfGov *g, int cap) {
  *g = (YfGov){0};
  g->cap = cap > 1 ? cap : 1;
  g->cur = g->best = 1; /* one thread first: on a busy machine the cheap guess */
  g->interval0 = g_first;
  g->interval_max = g_max;
  g->interval = g->interval0;
  g->left = 1; /* the first step warms caches and pages: not timed */
}

/* Does the probed count win?  The team must beat one thread by 5 %: on an idle machine two
 * threads are far ahead, and a near tie goes to one thread, which leaves the cores to others. */
static int probe_wins(const YfGov *g, double tprobe, double tcur) {
  return g->cur > 1 ? tprobe < 0.95 * tcur : 0.95 * tprobe < tcur;
}

int gov_step(YfGov *g, double seconds) {
  if (g->cap <= 1) return 1;
  g->steps_at[g->cur > 1]++;
  switch (g->phase) {
  case 0: /* untimed step */
    if (--g->left > 0) break;
    g->phase = 1;
    g->n = 0;
    g->left = YF_GOV_WINDOW;
    break;
  case 1: /* the chosen count: keep the window's last times, probe when due */
    g->t[g->n % YF_GOV_WINDOW] = seconds;
    g->n++;
    --g->left;
    if (g->n < YF_GOV_WINDOW) break;
    if (g->tref <= 0) g->tref = median(g->t, YF_GOV_WINDOW);
    /* the team's steps got slower (a competitor came): probe one thread now.  One thread's
     * own slowdowns (noise of a busy machine, a costlier scene) wait for the next probe. */
    if (g->left > 0 && (g->cur == 1 || median(g->t, YF_GOV_WINDOW) <= 1.5 * g->tref)) break;
    g->phase = 2;
    g->cur = g->best > 1 ? 1 : g->cap;
    g->n = -1; /* the switch's first step (a team waking up): see below */
    break;
  case 2: { /* the other count */
    const double tc = median(g->t, YF_GOV_WINDOW);
    int done = 0, win = 0;
    if (g->n < 0) /* the switch's step (a team waking up) is not in the median, but 3x slower
                   * on its own it has lost already */
      done = seconds > 3.0 * tc;
    else
      g->probe[g->n] = seconds;
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
      for (int i = 0; i < YF_GOV_WINDOW; i++) g->t[i] = g->probe[i];
    } else {
      g->interval = 4 * g->interval < g->interval_max ? 4 * g->interval : g->interval_max;
    }
    g->tref = median(g->t, YF_GOV_WINDOW); /* the kept count's times, whichever won */
    g->cur = g->best;
    g->phase = 1;
    g->n = 0;
    g->left = g->interval;
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
  omp_use(G.cur);
  return G.cap;
}

void threads_last_run(long *on1, long *onmore) {
  *on1 = G.steps_at[0];
  *onmore = G.steps_at[1];
}

int threads_after_step(double seconds) {
  if (G.cap <= 1) return omp_max();
  int was = G.cur, n = gov_step(&G, seconds);
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
