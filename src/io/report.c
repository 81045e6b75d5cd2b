/* report.c: the io layer's side of a run: the observer that turns the run loop's event records
 * into frames, metrics samples and restart files, and the summary keys of the loop (counts,
 * memory, stage times) and of fracture (first break, crack length, fragments) with the
 * fracture_log CSVs.  The step calls none of this: it hands events on (sim_notify), and the
 * exit path calls run_summary_update.
 */
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include "report.h"
#include "contact.h"
#include "err.h"
#include "joint.h"
#include "metrics.h"
#include "output.h"
#include "restart.h"
#include "run.h"
#include "summary.h"
#include "wfile.h"

/* The order within each event is the order the run loop used to call them in. */
static void io_observer(YfSim *s, YfEvent *ev) {
  switch (ev->kind) {
  case YF_EV_RUN_BEGIN: output_run_begin(s); break;
  case YF_EV_STEP:
    output_step(s);
    metrics_step(s);
    restart_step(s); /* periodic restart file when due */
    break;
  case YF_EV_TOPOLOGY:
    if (s->out) output_topology_changed(s);
    break;
  case YF_EV_INTERRUPT:
    /* finish cleanly: a restart of this step, its frame in every dump, files closed.  Between
     * runs (deck.c) no frame: the uninterrupted deck's next run writes its own of this step after
     * the commands before it, and a continued run, which cannot tell an interrupt's frame from
     * that one, writes it (output.c) */
    ev->restart_path = restart_on_interrupt(s, ev->why, sizeof ev->why);
    if (s->in_run) output_write_all(s);
    output_run_end(s);
    break;
  case YF_EV_RUN_END: output_run_end(s); break;
  case YF_EV_FREE:
    restart_free(s);
    output_free(s);
    metrics_reset();
    break;
  }
}

void io_attach(YfSim *s) { sim_observe(s, io_observer); }

/* Summary keys owned by the loop: counts, cost of the model, where the time went.  Runs from
 * the exit path too, so it must not fail. */
void run_summary_update(YfSim *s) {
  summary_set_counts(joints_count(s), joints_broken(s), contact_pairs(s));
  /* every key is always there (scripts index them): null when there is no scene or no limit */
  if (s->model.tri.n > 0) summary_add_number("model_bytes_per_element", run_model_bytes(s) / s->model.tri.n);
  else summary_add_raw("model_bytes_per_element", "null");
  struct rusage ru;
  if (!getrusage(RUSAGE_SELF, &ru)) summary_add_number("peak_rss_mb", ru.ru_maxrss / 1024.0);
  char buf[512];
  int k = snprintf(buf, sizeof buf, "{");
  for (int i = 0; i < YF_NSTAGE && k > 0 && (size_t)k < sizeof buf; i++)
    k += snprintf(buf + k, sizeof buf - (size_t)k, "%s\"%s\": %.6g", i ? ", " : "", yf_stage_names[i], yf_stage_time[i]);
  if (k > 0 && (size_t)k < sizeof buf - 2) {
    snprintf(buf + k, sizeof buf - (size_t)k, "}");
    summary_add_raw("stage_seconds", buf);
  }
  summary_add_number("gravity_work", s->gravity_work); /* not in energy.external_work (loads, supports) */
  summary_add_number("dt", s->dt);
  if (isfinite(s->dt_limit) && s->dt_limit > 0) summary_add_number("dt_limit", s->dt_limit);
  else summary_add_raw("dt_limit", "null");
  joints_summary(s);
  metrics_summary(s);
}

static int dbl_desc(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return x < y ? 1 : x > y ? -1 : 0;
}

static const char *mode_name(int md) { return md == YF_JMODE_I ? "I" : md == YF_JMODE_II ? "II" : "mixed"; }

static void write_log(YfSim *s, const char *path, const YfBreak *rec, int nrec) {
  if (!yf_writer()) return;
  YfWFile w;
  if (yf_wfile_open(&w, path) != 0) { /* runs from the exit path too: there the other outputs are still written */
    yf_output_error("fracture_log: cannot write '%s': %s", path, yf_strerror(errno));
    return;
  }
  FILE *f = w.f;
  fprintf(f, "step,time,x,y,mode,triA,triB,length,joint\n");
  for (int i = 0; i < nrec; i++) {
    const YfBreak *b = &rec[i];
    fprintf(f, "%ld,%.17g,%.17g,%.17g,%s,%d,%d,%.17g,%d\n", b->step, b->time, b->x, b->y, mode_name(b->mode),
            s->model.tri.id[b->triA], s->model.tri.id[b->triB], b->length, b->joint);
  }
  if (yf_wfile_close(&w, 0, 0) != 0) yf_output_error("fracture_log: cannot write '%s': %s", path, yf_strerror(errno));
}

void joints_summary(YfSim *s) {
  YfJoints *J = s->joints;
  summary_set_counts(joints_count(s), joints_broken(s), contact_pairs(s));
  if (!J || !J->n) return;
  char buf[1024];
  if (J->nrec) {
    const YfBreak *b = &J->rec[0];
    snprintf(buf, sizeof buf, "{\"step\": %ld, \"time\": %.17g, \"x\": %.17g, \"y\": %.17g, \"mode\": \"%s\"}", b->step,
             b->time, b->x, b->y, mode_name(b->mode));
    summary_add_raw("first_break", buf);
  } else {
    summary_add_raw("first_break", "null");
  }
  if (J->nopened) { /* the first joint past its peak (an opened, still cohesive crack) */
    const YfBreak *b = &J->orec[0];
    snprintf(buf, sizeof buf, "{\"step\": %ld, \"time\": %.17g, \"x\": %.17g, \"y\": %.17g, \"mode\": \"%s\"}", b->step,
             b->time, b->x, b->y, mode_name(b->mode));
    summary_add_raw("first_crack", buf);
  } else {
    summary_add_raw("first_crack", "null");
  }
  summary_add_number("joints_opened", J->nopened);
  double len[4] = {0, 0, 0, 0};
  for (int i = 0; i < J->nrec; i++) len[J->rec[i].mode == YF_JMODE_I ? 0 : J->rec[i].mode == YF_JMODE_II ? 1 : 2] += J->rec[i].length;
  len[3] = len[0] + len[1] + len[2];
  snprintf(buf, sizeof buf, "{\"I\": %.17g, \"II\": %.17g, \"mixed\": %.17g, \"total\": %.17g}", len[0], len[1], len[2], len[3]);
  summary_add_raw("crack_length", buf);
  const YfModel *m = &s->model;
  int *fr = yf_malloc((size_t)m->tri.n * sizeof(int), "fragments");
  int nf = joints_fragments(s, fr);
  summary_add_number("fragments", nf);
  double *area = yf_calloc((size_t)(nf > 0 ? nf : 1), sizeof(double), "fragments");
  for (int t = 0; t < m->tri.n; t++) area[fr[t]] += 0.5 * fabs(model_tri_d(m, t, 0));
  qsort(area, (size_t)nf, sizeof(double), dbl_desc);
  int k = 0;
  k += snprintf(buf + k, sizeof buf - (size_t)k, "[");
  for (int i = 0; i < nf && i < 10; i++) k += snprintf(buf + k, sizeof buf - (size_t)k, "%s%.17g", i ? ", " : "", area[i]);
  snprintf(buf + k, sizeof buf - (size_t)k, "]");
  summary_add_raw("fragment_sizes", buf);
  free(fr);
  free(area);
  /* not for a deck that failed before its first run began (a command before it, or run's own
   * checks, or write_restart, after the scene was prepared): no run, no file, not even a header */
  if (J->log_path[0] && s->runs_begun) write_log(s, J->log_path, J->rec, J->nrec);
  if (J->open_log_path[0] && s->runs_begun) write_log(s, J->open_log_path, J->orec, J->nopened);
}

