/* commands.c: the command table, generated from commands_deck.def (interpreter commands) and
 * commands.def (scene and physics commands) by an X-macro, so dispatch, help and the README's
 * reference cannot disagree. */
#include <ctype.h>
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

/* Does text name command c as a word (not inside a longer name: "fix" is not in "unfix")? */
static int names_word(const char *text, const char *c) {
  size_t L = strlen(c);
  for (const char *p = text; (p = strstr(p, c)) != NULL; p++) {
    int before = p == text || !(isalnum((unsigned char)p[-1]) || p[-1] == '_');
    int after = !(isalnum((unsigned char)p[L]) || p[L] == '_');
    if (before && after) return 1;
  }
  return 0;
}

/* One section per command: usage, what it does (arguments, units and defaults are in its help
 * text), an example, and the related commands: those it names in its usage or help, and those
 * that name it. */
void commands_print_sections(FILE *fp) {
  fprintf(fp, "# yfdem deck reference\n\nGenerated from the command table (src/commands_deck.def, "
              "src/commands.def) by `tools/update-reference`; `yfdem -h COMMAND` prints one entry.\n");
  for (const YfCommand *c = yf_commands; c->name; c++) {
    fprintf(fp, "\n## %s\n\n```\n%s\n```\n\n%s\n\nExample:\n\n```\n%s\n```\n", c->name, c->usage, c->help,
            c->example);
    int n = 0;
    for (const YfCommand *o = yf_commands; o->name; o++) {
      if (o == c) continue;
      int rel = names_word(c->help, o->name) || names_word(o->help, c->name) || names_word(o->usage, c->name);
      if (!rel) continue;
      fprintf(fp, "%s[`%s`](#%s)", n++ ? ", " : "\nRelated: ", o->name, o->name);
    }
    if (n) fputc('\n', fp);
  }
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
