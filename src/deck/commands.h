/* commands.h: the generated command table (commands.c). */
#ifndef YF_COMMANDS_H
#define YF_COMMANDS_H
#include <stdio.h>
#include "deck.h"

/* The handler of every command of the table: deck/cmd_WORD.c for the scene and physics commands,
 * deck.c for the interpreter's own (tests call some directly). */
#define YF_CMD(name, fn, usage, help, example) void fn(struct YfSim *, const YfArgs *);
#include "commands_deck.def"
#include "commands.def"
#undef YF_CMD
/* Markdown table of every command (the README's deck reference is checked against it). */
void commands_print_reference(FILE *fp);
/* The full reference, a markdown section per command (docs/reference.md). */
void commands_print_sections(FILE *fp);
/* The arguments of command NAME (command_args.def): one 'WORDS: meaning' line each; NULL for a
 * name without a row.  yf_command_args lists the rows (NULL-terminated), for the tests. */
const char *commands_args(const char *name);
typedef struct { const char *name, *args; } YfCommandArgs;
extern const YfCommandArgs yf_command_args[];
/* `yfdem -h COMMAND`: usage, what it does, its arguments, an example. */
void commands_print_help(FILE *fp, const YfCommand *c);
#endif
