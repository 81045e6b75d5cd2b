/* commands.c: the command table, generated from commands_deck.def (interpreter commands) and
 * commands.def (scene and physics commands) by an X-macro, so dispatch, help and the README's
 * reference cannot disagree. */
#include <string.h>
#include "deck.h"
#include "commands.h"

const YfCommand yf_commands[] = {
#define YF_CMD(name, fn, usage, help, example) {#name, fn, usage, help, example},
#include "commands_deck.def"
#include "commands.def"
#undef YF_CMD
    {NULL, NULL, NULL, NULL, NULL}};

const YfCommand *deck_find_command(const char *name) {
  for (const YfCommand *c = yf_commands; c->name; c++)
    if (!strcmp(c->name, name)) return c;
  return NULL;
}

/* Markdown table cells: a '|' inside a cell must be escaped. */
static void cell(FILE *fp, const char *s, int code) {
  fputs(code ? " `" : " ", fp);
  for (; *s; s++) {
    if (*s == '|') fputs("\\|", fp);
    else fputc(*s, fp);
  }
  fputs(code ? "` |" : " |", fp);
}

void commands_print_reference(FILE *fp) {
  fprintf(fp, "| command | usage | what it does | example |\n|---|---|---|---|\n");
  for (const YfCommand *c = yf_commands; c->name; c++) {
    fputs("|", fp);
    cell(fp, c->name, 1);
    cell(fp, c->usage, 1);
    cell(fp, c->help, 0);
    cell(fp, c->example, 1);
    fputc('\n', fp);
  }
}
