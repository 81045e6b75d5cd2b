/* scene_args.h: argument words that name things of the scene (groups, histories, materials) and
 * the row files of inline meshes, shared by the
 * command handlers of the deck layer; each gives the deck's own message on a bad word. */
#ifndef YF_SCENE_ARGS_H
#define YF_SCENE_ARGS_H
#include "deck.h"
#include "sim.h"

/* Word i names a group: its index, or an error listing the defined groups. */
int arg_group(YfSim *s, const YfArgs *a, int i);
/* Optional trailing "history NAME" from word i: the history index, -1 when absent. */
int arg_history(YfSim *s, const YfArgs *a, int i);
/* Word i names a material: its index, or an error listing the defined materials. */
int arg_material(const YfModel *m, const YfArgs *a, int i);

/* `nodes FILE [BODY]`, `triangles FILE [BODY]`: read the whitespace-separated table FILE
 * (relative to the deck) with `want` columns per row ('#' starts a comment) and hand each row to
 * fn with the row's FILE:LINE and the body name (default "inline"); layout names the columns in
 * messages.  row_long and row_num read one cell (an id in 0..INT_MAX, a number) or stop at loc. */
typedef void (*YfRowFn)(YfModel *m, char **w, const YfLoc *loc, const char *bname);
void deck_read_rows(YfModel *m, const YfArgs *a, int want, YfRowFn fn, const char *layout);
long row_long(char *s, const YfLoc *loc, const char *what);
double row_num(char *s, const YfLoc *loc, const char *what);

#endif
