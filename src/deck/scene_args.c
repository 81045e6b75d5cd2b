/* scene_args.c: group and history words of the command handlers (scene_args.h). */
#include <string.h>
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
