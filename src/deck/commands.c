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

const YfCommandArgs yf_command_args[] = {
#define YF_ARGS(name, args) {#name, args},
#include "command_args.def"
#undef YF_ARGS
    {NULL, NULL}};

const char *commands_args(const char *name) {
  for (const YfCommandArgs *r = yf_command_args; r->name; r++)
    if (!strcmp(r->name, name)) return r->args;
  return NULL;
}

/* Each line of an args text, split at its first ": " (words, meaning), to fn. */
static void each_arg(const char *args, FILE *fp, void (*fn)(FILE *, const char *, int, const char *, int)) {
  for (const char *p = args; p && *p;) {
    const char *e = strchr(p, '\n');
    int n = e ? (int)(e - p) : (int)strlen(p);
    const char *colon = strstr(p, ": ");
    if (colon && colon < p + n) fn(fp, p, (int)(colon - p), colon + 2, n - (int)(colon + 2 - p));
    else fn(fp, p, 0, p, n);
    p += n + (e ? 1 : 0);
  }
}

static void arg_markdown(FILE *fp, const char *w, int nw, const char *t, int nt) {
  if (nw && w[0] == '(') fprintf(fp, "- %.*s: %.*s\n", nw, w, nt, t);
  else if (nw) fprintf(fp, "- `%.*s`: %.*s\n", nw, w, nt, t);
  else fprintf(fp, "- %.*s\n", nt, t);
}

static void arg_text(FILE *fp, const char *w, int nw, const char *t, int nt) {
  if (nw) fprintf(fp, "    %.*s: %.*s\n", nw, w, nt, t);
  else fprintf(fp, "    %.*s\n", nt, t);
}

void commands_print_help(FILE *fp, const YfCommand *c) {
  fprintf(fp, "%s\n  %s\n", c->usage, c->help);
  const char *args = commands_args(c->name);
  if (args) {
    fprintf(fp, "  arguments:\n");
    each_arg(args, fp, arg_text);
  }
  fprintf(fp, "  example: %s\n", c->example);
}

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

/* One section per command: usage, what it does, its arguments with units and defaults
 * (command_args.def), an example, and the related commands: those it names in its usage or help,
 * and those that name it. */
void commands_print_sections(FILE *fp) {
  fprintf(fp, "# yfdem deck reference\n\nGenerated from the command table (src/deck/commands_deck.def, "
              "src/deck/commands.def, src/deck/command_args.def) by `tools/update-reference`; `yfdem -h COMMAND` "
              "prints one entry.\n");
  for (const YfCommand *c = yf_commands; c->name; c++) {
    fprintf(fp, "\n## %s\n\n```\n%s\n```\n\n%s\n", c->name, c->usage, c->help);
    const char *args = commands_args(c->name);
    if (args) {
      fprintf(fp, "\nArguments:\n\n");
      each_arg(args, fp, arg_markdown);
    }
    fprintf(fp, "\nExample:\n\n```\n%s\n```\n", c->example);
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
