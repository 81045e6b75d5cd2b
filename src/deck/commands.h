/* commands.h: the generated command table (commands.c). */
#ifndef YF_COMMANDS_H
#define YF_COMMANDS_H
#include <stdio.h>
/* Markdown table of every command (the README's deck reference is checked against it). */
void commands_print_reference(FILE *fp);
#endif
