/* scene_args.c: group, history and material words of the command handlers, and the row tables
 * of `nodes` and `triangles` (scene_args.h). */
#include <errno.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "mesh.h"
#include "scene_args.h"

int arg_group(YfSim *s, const YfArgs *a, int i) {
  const char *g = arg_word(a, i, "group");
  int k = model_group(&s->model, g, 0);
  if (k < 0) {
    char list[1024] = "";
    for (int j = 0; j < s->model.ngroup; j++) {
      strncat(list, j ? ", " : "", sizeof list - strlen(list) - 1);
      strncat(list, s->model.group[j].name, sizeof list - strlen(list) - 1);
    }
    arg_error(a, i, "unknown group (defined groups: %s)", s->model.ngroup ? list : "none yet");
  }
  return k;
}

int arg_history(YfSim *s, const YfArgs *a, int i) {
  if (i >= a->n) return -1;
  if (strcmp(a->w[i], "history")) arg_error(a, i, "unexpected word (expected 'history NAME' or nothing)");
  const char *h = arg_word(a, i + 1, "history name");
  int k = sim_find_history(s, h);
  if (k < 0) arg_error(a, i + 1, "unknown history (define it first with: history NAME constant|ramp|table|sine ...)");
  if (i + 2 < a->n) arg_error(a, i + 2, "unexpected word after the history name");
  return k;
}

int arg_material(const YfModel *m, const YfArgs *a, int i) {
  char buf[512];
  int mt = model_find_material(m, a->w[i]);
  if (mt < 0) {
    if (m->nmat == 0)
      arg_error(a, i, "unknown material (no material is defined yet: define it with 'material' first)");
    arg_error(a, i, "unknown material (known materials: %s)", mesh_material_names(m, buf, sizeof buf));
  }
  return mt;
}

void deck_read_rows(YfModel *m, const YfArgs *a, int want, YfRowFn fn, const char *layout) {
  arg_count(a, 1, 2);
  const char *bname = a->n > 1 ? a->w[1] : "inline";
  char *path = deck_resolve_path(a, arg_word(a, 0, "file"));
  FILE *fp = yf_open_input(path, "r");
  if (!fp) yf_io_error(&a->loc, "%s: cannot open '%s': %s", a->cmd, path, strerror(errno));
  char *line = NULL;
  size_t cap = 0;
  YfLoc loc = {path, 0};
  int rows = 0;
  while (yf_getline(&line, &cap, fp) >= 0) {
    loc.line++;
    if (loc.line == 1) yf_skip_bom(line);
    char *hash = strchr(line, '#');
    if (hash) *hash = '\0';
    char *w[8];
    int n = 0;
    for (char *s = strtok(line, " \t\r\n"); s; s = strtok(NULL, " \t\r\n")) {
      if (n == want) {
        n++;
        break;
      }
      w[n++] = s;
    }
    if (n == 0) continue;
    if (n != want)
      yf_deck_error(&loc, "%s: expected %d columns (%s), found %s%d", a->cmd, want, layout,
                    n > want ? "more than " : "", n > want ? want : n);
    fn(m, w, &loc, bname);
    rows++;
  }
  if (ferror(fp)) yf_io_error(&a->loc, "%s: error reading '%s'", a->cmd, path);
  fclose(fp);
  free(line);
  if (rows == 0) yf_warn(&a->loc, "%s: '%s' has no rows", a->cmd, path);
  free(path);
}

long row_long(char *s, const YfLoc *loc, const char *what) {
  long v;
  if (!yf_parse_long(s, &v) || v < 0 || v > INT_MAX)
    yf_deck_error(loc, "%s '%s' is not an integer in 0..%d", what, s, INT_MAX);
  return v;
}

double row_num(char *s, const YfLoc *loc, const char *what) {
  double v;
  if (!yf_parse_double(s, &v)) yf_deck_error(loc, "%s '%s' is not a number", what, s);
  return v;
}
