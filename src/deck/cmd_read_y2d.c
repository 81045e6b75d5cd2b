/* cmd_read_y2d.c: the `read_y2d` deck command (a row of commands.def): reads its words and calls
 * y2d_load (y2d_model.h).
 */
#include <stdlib.h>
#include <string.h>
#include "deck.h"
#include "y2d_model.h"
#include "joint.h"

/* read_y2d FILE [volfac 0.5|1] */
void cmd_read_y2d(YfSim *s, const YfArgs *a) {
  arg_count(a, 1, 3);
  const char *f = arg_word(a, 0, "file");
  double vf = 0.5;
  if (a->n > 1) {
    if (strcmp(a->w[1], "volfac")) arg_error(a, 1, "unknown keyword (expected 'volfac 0.5|1')");
    if (a->n < 3) arg_error(a, 1, "expected a value after it: 0.5 (book Y2D) or 1 (Y-Geo family decks)");
    vf = arg_num(a, 2, "volfac");
    if (vf != 0.5 && vf != 1.0)
      arg_error(a, 2, "must be 0.5 (book Y2D: (lambda/2)(J - 1/J)) or 1 (Y-Geo and other Y2D copies: lambda (J - 1/J))");
  }
  if (s->y2d) arg_error(a, 0, "a Y2D deck (%s) was already read; one read_y2d per simulation", s->y2d->path);
  char *path = deck_resolve_path(a, f);
  y2d_load(s, path, vf, &a->loc);
  YfY2dRun *r = s->y2d;
  sim_printf(s, "read_y2d: %s: %d nodes, %d triangles, %d properties, %d BC sets, dt %.6g s, last step %ld%s%s\n",
             path, r->nnode, r->ntri, y2d_nprop(s), r->nset, s->dt, s->last_step,
             joints_count(s) ? ", joints" : "", r->contact_on ? ", contact" : "");
  free(path);
}
