/* cmd_history.c: the `history` deck command (a row of commands.def): reads its words and calls
 * the simulation's own settings (sim.h).
 */
#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include "deck.h"
#include "sim.h"

/* history NAME constant
 * history NAME ramp T0 T1            (0 before T0, linear to 1 at T1, then 1)
 * history NAME sine PERIOD           (sin(2 pi t / PERIOD))
 * history NAME table T1 V1 T2 V2 ... (piecewise linear; end values held outside)
 * history NAME file FILE             (two columns t v, '#' comments) */
void cmd_history(YfSim *s, const YfArgs *a) {
  arg_count(a, 2, -1);
  static const char *const kinds[] = {"constant", "ramp", "table", "sine", "file", NULL};
  const char *name = arg_name(a, 0, "name");
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
    FILE *fp = yf_open_input(path, "r");
    if (!fp) { YfLoc l = a->loc; free(path); yf_io_error(&l, "history: cannot open '%s': %s", a->w[2], strerror(errno)); }
    h.kind = YF_HIST_TABLE;
    char *line = NULL; /* whole lines, however long: a long comment must not split a line in two */
    size_t lcap = 0;
    int cap = 0, ln = 0;
    while (yf_getline(&line, &lcap, fp) >= 0) {
      ln++;
      if (ln == 1) yf_skip_bom(line);
      char *c = strchr(line, '#');
      if (c) *c = 0;
      char *t1 = strtok(line, " \t\r\n,"), *t2 = t1 ? strtok(NULL, " \t\r\n,") : NULL;
      if (!t1) continue;
      char *t3 = t2 ? strtok(NULL, " \t\r\n,") : NULL; /* a third column was dropped silently */
      double tv, vv;
      if (!t2 || t3 || !yf_parse_double(t1, &tv) || !yf_parse_double(t2, &vv)) {
        YfLoc l = {path, ln};
        char extra[64];
        snprintf(extra, sizeof extra, "%s", t3 ? t3 : "");
        fclose(fp);
        free(line);
        if (extra[0]) yf_deck_error(&l, "history file: '%s' after 't v' (two numbers a row; comments start with '#')", extra);
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
    free(line);
    if (h.npts < 2) { YfLoc l = {path, ln}; yf_deck_error(&l, "history file: at least two points needed"); }
    free(path);
  }
  s->hist = yf_realloc(s->hist, (size_t)(s->nhist + 1) * sizeof *s->hist, "histories");
  s->hist[s->nhist++] = h;
}
