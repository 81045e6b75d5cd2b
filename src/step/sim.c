/* sim.c: the simulation object, time histories, and the small global commands
 * (history, gravity, damping, thermo, timestep).
 */
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include "metrics.h"
#include "sim.h"
#include "deck.h"
#include "err.h"
#include "mesh.h"
#include "bc.h"
#include "contact.h"
#include "joint.h"
#include "output.h"
#include "y2d_model.h"
#include "region.h"
#include "restart.h"

void sim_init(YfSim *s) {
  memset(s, 0, sizeof *s);
  model_init(&s->model);
  s->dt_safety = 0.5;
  s->thermo_every = 0;
  s->threads = 1;
}

void sim_printf(YfSim *s, const char *fmt, ...) {
  if (!yf_writer()) return;
  va_list ap;
  va_start(ap, fmt);
  vfprintf(stdout, fmt, ap);
  va_end(ap);
  if (s && s->log) {
    va_start(ap, fmt);
    vfprintf(s->log, fmt, ap);
    va_end(ap);
  }
}

int sim_find_history(const YfSim *s, const char *name) {
  for (int i = 0; i < s->nhist; i++)
    if (!strcmp(s->hist[i].name, name)) return i;
  return -1;
}

double history_value(const YfHistory *h, double t) {
  switch (h->kind) {
  case YF_HIST_RAMP:
    if (t <= h->t0) return 0.0;
    if (t >= h->t1) return 1.0;
    return (t - h->t0) / (h->t1 - h->t0);
  case YF_HIST_SINE: return sin(2.0 * M_PI * t / h->t0);
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
    return h->v[lo] + w * (h->v[hi] - h->v[lo]);
  }
  default: return 1.0;
  }
}

/* history NAME constant
 * history NAME ramp T0 T1            (0 before T0, linear to 1 at T1, then 1)
 * history NAME sine PERIOD           (sin(2 pi t / PERIOD))
 * history NAME table T1 V1 T2 V2 ... (piecewise linear; end values held outside)
 * history NAME file FILE             (two columns t v, '#' comments) */
void cmd_history(YfSim *s, const YfArgs *a) {
  arg_count(a, 2, -1);
  static const char *const kinds[] = {"constant", "ramp", "table", "sine", "file", NULL};
  const char *name = arg_word(a, 0, "name");
  int k = arg_choice(a, 1, "history style", kinds);
  if (sim_find_history(s, name) >= 0) arg_error(a, 0, "history already defined");
  YfHistory h;
  memset(&h, 0, sizeof h);
  snprintf(h.name, sizeof h.name, "%s", name);
  if (k == 0) { arg_count(a, 2, 2); h.kind = YF_HIST_CONSTANT; }
  else if (k == 1) {
    arg_count(a, 4, 4);
    h.kind = YF_HIST_RAMP;
    h.t0 = arg_num(a, 2, "t0");
    h.t1 = arg_num(a, 3, "t1");
    if (!(h.t1 > h.t0)) arg_error(a, 3, "ramp end must be after its start");
  } else if (k == 3) {
    arg_count(a, 3, 3);
    h.kind = YF_HIST_SINE;
    h.t0 = arg_pos(a, 2, "period");
  } else if (k == 2) {
    if ((a->n - 2) < 4 || (a->n - 2) % 2) arg_error(a, a->n - 1, "a table needs pairs 't v', at least two of them");
    h.kind = YF_HIST_TABLE;
    h.npts = (a->n - 2) / 2;
    h.t = yf_malloc((size_t)h.npts * sizeof(double), "history");
    h.v = yf_malloc((size_t)h.npts * sizeof(double), "history");
    for (int i = 0; i < h.npts; i++) {
      h.t[i] = arg_num(a, 2 + 2 * i, "t");
      h.v[i] = arg_num(a, 3 + 2 * i, "value");
      if (i && !(h.t[i] > h.t[i - 1])) { free(h.t); free(h.v); arg_error(a, 2 + 2 * i, "table times must increase"); }
    }
  } else {
    arg_count(a, 3, 3);
    char *path = deck_resolve_path(a, a->w[2]);
    FILE *fp = fopen(path, "r");
    if (!fp) { YfLoc l = a->loc; free(path); yf_io_error(&l, "history: cannot open '%s'", a->w[2]); }
    h.kind = YF_HIST_TABLE;
    char line[512];
    int cap = 0, ln = 0;
    while (fgets(line, sizeof line, fp)) {
      ln++;
      char *c = strchr(line, '#');
      if (c) *c = 0;
      char *t1 = strtok(line, " \t\r\n,"), *t2 = t1 ? strtok(NULL, " \t\r\n,") : NULL;
      if (!t1) continue;
      double tv, vv;
      if (!t2 || !yf_parse_double(t1, &tv) || !yf_parse_double(t2, &vv)) {
        YfLoc l = {path, ln};
        fclose(fp);
        yf_deck_error(&l, "history file: expected two numbers 't v'");
      }
      if (h.npts == cap) {
        cap = cap ? 2 * cap : 16;
        h.t = yf_realloc(h.t, (size_t)cap * sizeof(double), "history");
        h.v = yf_realloc(h.v, (size_t)cap * sizeof(double), "history");
      }
      if (h.npts && !(tv > h.t[h.npts - 1])) { YfLoc l = {path, ln}; fclose(fp); yf_deck_error(&l, "history file: times must increase"); }
      h.t[h.npts] = tv;
      h.v[h.npts++] = vv;
    }
    fclose(fp);
    if (h.npts < 2) { YfLoc l = {path, ln}; yf_deck_error(&l, "history file: at least two points needed"); }
    free(path);
  }
  s->hist = yf_realloc(s->hist, (size_t)(s->nhist + 1) * sizeof *s->hist, "histories");
  s->hist[s->nhist++] = h;
}

/* gravity GX GY   [m/s^2] */
void cmd_gravity(YfSim *s, const YfArgs *a) {
  arg_count(a, 2, 2);
  s->gx = arg_num(a, 0, "gx");
  s->gy = arg_num(a, 1, "gy");
}

/* damping mass ALPHA   (force -ALPHA m v on every node [1/s]; 0 switches it off) */
void cmd_damping(YfSim *s, const YfArgs *a) {
  arg_count(a, 2, 2);
  static const char *const kinds[] = {"mass", NULL};
  arg_choice(a, 0, "damping style", kinds);
  s->mass_damping = arg_nonneg(a, 1, "alpha");
}

/* thermo N   (a thermo line every N steps; 0: start and end of each run only) */
void cmd_thermo(YfSim *s, const YfArgs *a) {
  arg_count(a, 1, 1);
  s->thermo_every = arg_int(a, 0, "N", 0, 2000000000L);
}

/* timestep DT | timestep auto [safety S] */
void cmd_timestep(YfSim *s, const YfArgs *a) {
  arg_count(a, 1, 3);
  if (!strcmp(a->w[0], "auto")) {
    s->dt_auto = 1;
    if (a->n > 1) {
      if (strcmp(a->w[1], "safety")) arg_error(a, 1, "expected 'safety S'");
      arg_count(a, 3, 3);
      s->dt_safety = arg_pos(a, 2, "safety");
      if (s->dt_safety > 1.0) arg_error(a, 2, "a safety factor above 1 exceeds the stable limit");
    }
  } else {
    arg_count(a, 1, 1);
    s->dt_auto = 0;
    s->dt = arg_pos(a, 0, "dt");
    s->dt_loc = a->loc;
  }
}

void sim_free(YfSim *s) {
  restart_free(s);
  joints_free(s);
  contact_free(s);
  y2d_model_free(s);
  bc_free(s);
  output_free(s);
  for (int i = 0; i < s->nhist; i++) { free(s->hist[i].t); free(s->hist[i].v); }
  free(s->hist);
  model_free(&s->model);
  region_reset();
  metrics_reset();
  mesh_reset();
}
