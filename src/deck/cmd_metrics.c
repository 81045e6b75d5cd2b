/* cmd_metrics.c: the `metrics` deck command (a row of commands.def): one keyword per line, each
 * a setting of the crack measurements (metrics_set_*, io/metrics.c).
 */
#include <errno.h>
#include <string.h>
#include "deck.h"
#include "output.h"
#include "joint.h"
#include "metrics.h"
#include "restart.h"
#include "region.h"
#include "report.h"

/* Word w names a region: its index (else a deck error). */
static int region_word(const YfArgs *a, int w) {
  int ri = region_find(a->w[w]);
  if (ri < 0) arg_error(a, w, "no region named '%s' (define it with `region` first)", a->w[w]);
  return ri;
}

void cmd_metrics(YfSim *s, const YfArgs *a) {
  io_attach(s); /* its state observes the run loop (report.c) */
  static const char *const kw[] = {"body", "mirror", "region", "midspan", "peak_stress", "log", "opened_threshold", NULL};
  arg_count(a, 1, -1);
  int k = arg_choice(a, 0, "keyword", kw);
  switch (k) {
  case 0: {
    arg_count(a, 2, 2);
    int b = model_find_body(&s->model, a->w[1]);
    if (b < 0) arg_error(a, 1, "no body named '%s'", a->w[1]);
    metrics_set_body(b);
    break;
  }
  case 1: {
    static const char *const ax[] = {"x", "y", NULL};
    arg_count(a, 3, 3);
    int axis = 1 + arg_choice(a, 1, "axis", ax);
    metrics_set_mirror(axis, arg_num(a, 2, "C"));
    break;
  }
  case 2: {
    arg_count(a, 3, 2 + YF_METRICS_REG_SHAPES);
    const char *name = arg_name(a, 1, "region name");
    if (metrics_region_full(name)) arg_error(a, 1, "at most %d metrics regions", YF_METRICS_REGIONS);
    int r[YF_METRICS_REG_SHAPES], nr = 0;
    for (int w = 2; w < a->n; w++) r[nr++] = region_word(a, w);
    metrics_set_region(name, r, nr);
    break;
  }
  case 3: {
    arg_count(a, 2, 2);
    metrics_set_midspan(region_word(a, 1));
    break;
  }
  case 4: {
    static const char *const oo[] = {"on", "off", NULL};
    arg_count(a, 2, 6);
    metrics_set_peak(arg_choice(a, 1, "switch", oo) == 0);
    for (int w = 2; w < a->n; w += 2) {
      static const char *const th[] = {"threshold", "until", NULL};
      int o = arg_choice(a, w, "option", th);
      if (w + 1 >= a->n) arg_error(a, w, "'%s' needs a value", a->w[w]);
      if (o == 0) metrics_set_threshold(arg_pos(a, w + 1, "threshold S [Pa]"));
      else metrics_set_until(arg_pos(a, w + 1, "until T [s]"));
    }
    break;
  }
  case 5: {
    arg_count(a, 2, 4);
    if (strlen(a->w[1]) >= YF_METRICS_PATH_MAX) arg_error(a, 1, "path too long");
    if (!yf_can_create(a->w[1])) yf_io_error(&a->loc, "metrics log: cannot write '%s': %s", a->w[1], strerror(errno));
    output_release(s, "metrics log"); /* a later metrics log replaces the earlier */
    arg_claim(s, a, 1, "metrics log", a->w[1], NULL, 0);
    metrics_set_log(a->w[1], 0);
    restart_before_write(metrics_flush_log); /* a restart's log holds the rows before it */
    if (a->n > 2) {
      static const char *const ev[] = {"every", NULL};
      arg_choice(a, 2, "option", ev);
      metrics_set_log(a->w[1], arg_int(a, 3, "N", 1, 1000000000L));
    }
    break;
  }
  case 6: { /* opened cracks: only joints whose damage reaches Z (the records, counts and frames) */
    arg_count(a, 2, 2);
    double z = arg_nonneg(a, 1, "damage Z");
    if (z > 1.0) arg_error(a, 1, "damage Z must lie in [0, 1] (0: every joint past its peak; 1: fully damaged)");
    joints_set_open_threshold(s, z);
    break;
  }
  }
}
