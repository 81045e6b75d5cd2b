/* deck_cmds.h: handlers of the interpreter's builtin commands (rows in commands_deck.def).
 *
 * They live in deck.c because they drive the interpreter itself (variables, loops, includes);
 * commands.c includes this header before expanding commands_deck.def.
 */
#ifndef YF_DECK_CMDS_H
#define YF_DECK_CMDS_H
#include "deck.h"

void deck_cmd_variable(struct YfSim *sim, const YfArgs *a);
void deck_cmd_next(struct YfSim *sim, const YfArgs *a);
void deck_cmd_jump(struct YfSim *sim, const YfArgs *a);
void deck_cmd_label(struct YfSim *sim, const YfArgs *a);
void deck_cmd_include(struct YfSim *sim, const YfArgs *a);
void deck_cmd_print(struct YfSim *sim, const YfArgs *a);
void deck_cmd_if(struct YfSim *sim, const YfArgs *a);
void deck_cmd_echo(struct YfSim *sim, const YfArgs *a);
void deck_cmd_quit(struct YfSim *sim, const YfArgs *a);

#endif
