/* scene_args.h: argument words that name things of the scene (groups, histories), shared by the
 * command handlers of the deck layer; each gives the deck's own message on a bad word. */
#ifndef YF_SCENE_ARGS_H
#define YF_SCENE_ARGS_H
#include "deck.h"
#include "sim.h"

/* Word i names a group: its index, or an error listing the defined groups. */
int arg_group(YfSim *s, const YfArgs *a, int i);
/* Optional trailing "history NAME" from word i: the history index, -1 when absent. */
int arg_history(YfSim *s, const YfArgs *a, int i);

#endif
