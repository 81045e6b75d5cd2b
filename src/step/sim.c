/* sim.c: the simulation object, time histories, and the two registration lists of the run
 * loop: boundary-condition kinds and observers (sim.h).  The commands that set its fields
 * (history, gravity, damping, thermo, timestep) are in deck/cmd_*.c.
 */
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include "sim.h"
#include "err.h"


void sim_add_bc_kind(YfSim *s, const YfBcKind *k) {
  for (int i = 0; i < s->nbc_kind; i++)
    if (s->bc_kind[i] == k) return;
  YF_ASSERT(s->nbc_kind < YF_MAX_BC_KINDS);
  s->bc_kind[s->nbc_kind++] = k;
}

void sim_observe(YfSim *s, YfObserverFn fn) {
  for (int i = 0; i < s->nobserver; i++)
    if (s->observer[i] == fn) return;
  YF_ASSERT(s->nobserver < YF_MAX_OBSERVERS);
  s->observer[s->nobserver++] = fn;
}

void sim_notify(YfSim *s, YfEvent *ev) {
  for (int i = 0; i < s->nobserver; i++) s->observer[i](s, ev);
}

void sim_printf(YfSim *s, const char *fmt, ...) {
  if (!yf_writer()) return;
  static int stdout_lost; /* standard output failed once: the exit that follows prints nothing more there */
  va_list ap;
  if (!stdout_lost) {
    va_start(ap, fmt);
    vfprintf(stdout, fmt, ap);
    va_end(ap);
    /* thermo lines and messages reach the screen and the log at once, also when stdout is a file
     * or a pipe (nohup, a batch queue), where the C library would hold them in a 4 KB buffer */
    if (fflush(stdout) != 0 || ferror(stdout)) {
      /* 'yfdem ... | head' (SIGPIPE is ignored: yf_catch_signals) or a full disk: an output
       * that cannot be written stops the run with exit 2 and its summary (it was killed by
       * SIGPIPE with no summary, or ran on to "ok" printing into nothing) */
      int e = errno;
      stdout_lost = 1;
      clearerr(stdout);
      /* EAGAIN: an MPI rank's output made non-blocking by an interrupt (par_interrupted: mpirun has
       * stopped reading it); what it would print is dropped and the interrupt ends the run.
       * EBADF: no standard output at all ('>&-', a daemon): none was asked for; the log and the
       * summary hold the run (this ran to exit 0 before, and still does). */
      if (e != EAGAIN && e != EWOULDBLOCK && e != EBADF)
        yf_output_error("cannot write to standard output: %s (its reader has ended, or its disk is full)", strerror(e));
    }
  }
  if (s && s->log && !s->log_failed) {
    va_start(ap, fmt);
    vfprintf(s->log, fmt, ap);
    va_end(ap);
    /* a log that cannot be written (a full disk) ends the run with exit 2 as any output does: it
     * ran on to the end and a summary saying "ok", with the error (and a stale errno) at the exit */
    if (fflush(s->log) != 0 || ferror(s->log)) {
      s->log_failed = errno ? errno : EIO;
      yf_output_error("-log: cannot write '%s': %s", s->log_name ? s->log_name : "log.yfdem", strerror(s->log_failed));
    }
  }
}

int sim_find_history(const YfSim *s, const char *name) {
  for (int i = 0; i < s->nhist; i++)
    if (!strcmp(s->hist[i].name, name)) return i;
  return -1;
}

double history_value(const YfHistory *h, double t) {
  switch (h->kind) {
  case YF_HIST_RAMP: {
    if (t <= h->t0) return 0.0;
    if (t >= h->t1) return 1.0;
    double f = (t - h->t0) / (h->t1 - h->t0);
    /* a span beyond a double (ramp -1e308 1e308) made the factor 0: halves keep it, and the
     * bits of every finite span */
    return isfinite(h->t1 - h->t0) ? f : (0.5 * t - 0.5 * h->t0) / (0.5 * h->t1 - 0.5 * h->t0);
  }
  case YF_HIST_SINE: {
    double ph = 2.0 * M_PI * t / h->t0;
    /* a period so short that 2 pi t / T overflows (sine 4.9e-324) gave sin(inf), a NaN load:
     * the phase of t within its period instead (the same bits wherever the first is finite) */
    return sin(isfinite(ph) ? ph : 2.0 * M_PI * (fmod(t, h->t0) / h->t0));
  }
  case YF_HIST_TABLE: {
    /* piecewise linear, end values held outside the table (unlike Y2D's factor 1: say so in docs) */
    if (t <= h->t[0]) return h->v[0];
    if (t >= h->t[h->npts - 1]) return h->v[h->npts - 1];
    int lo = 0, hi = h->npts - 1;
    while (hi - lo > 1) {
      int mid = (lo + hi) / 2;
      if (h->t[mid] <= t) lo = mid; else hi = mid;
    }
    double w = (t - h->t[lo]) / (h->t[hi] - h->t[lo]);
    if (!isfinite(h->t[hi] - h->t[lo])) w = (0.5 * t - 0.5 * h->t[lo]) / (0.5 * h->t[hi] - 0.5 * h->t[lo]);
    double v = h->v[lo] + w * (h->v[hi] - h->v[lo]);
    /* values of opposite sign near the range of a double: their difference overflows */
    return isfinite(v) ? v : (1.0 - w) * h->v[lo] + w * h->v[hi];
  }
  default: return 1.0;
  }
}
