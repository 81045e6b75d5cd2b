/* deck.c: the deck interpreter (interface in deck.h, builtin handlers declared in deck_cmds.h).
 *
 * A deck file is read whole into memory and cut into logical lines once: '#' comments are
 * stripped (outside quotes), lines ending in '&' are joined with the next, and """triple quotes"""
 * may span lines.  Each logical line keeps the number of its first physical line, so messages
 * point at the right place inside includes and continuations.  Keeping the text in memory is what
 * makes `jump SELF label` work on stdin too.
 *
 * Executing a line: substitute ${name}, $x and $(expr) (not inside single quotes), split into
 * words (quoted words keep spaces), look the command up in the table (commands.c) and call its
 * handler with a YfArgs.  Files being read form a stack of frames (include pushes one; jump moves
 * the position of the top one).  Loaded files stay in memory until deck_free; file names are
 * interned for the life of the program because handlers may keep a YfLoc for later messages.
 *
 * Variables follow LAMMPS: equal-style keeps its expression and evaluates it at each reference;
 * index/loop variables advance with `next`, and when exhausted are deleted and the next `jump` is
 * skipped; a variable given on the command line (-var) cannot be redefined by the deck, so decks
 * can state defaults.
 *
 * Error messages: "FILE:LINE: error: CMD: WHAT 'word': what is wrong", then the offending line
 * and a caret under the bad word (LAMMPS style).  The context lines are part of the message given
 * to yf_deck_error, so they follow the first line on stderr.
 */
#include <ctype.h>
#include <errno.h>
#include <limits.h>
#include <math.h>
#include <signal.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <unistd.h>
#include "deck.h"
#include "output.h"
#include "par.h"
#include "query.h"
#include "deck_cmds.h"
#include "expr.h"
#include "sim.h"

#define DECK_INCLUDE_MAX 32  /* nesting depth of include (recursive includes end here) */
#define DECK_EVAL_MAX 64     /* nesting depth of equal-style variables referring to each other */
#define DECK_EVAL_WORK 1000000 /* equal-style evaluations for one expression (a work bound)      */
#define DECK_LINE_MAX (16 << 20) /* bytes of a line after substitution                          */
#define DECK_NEST_MAX 64     /* nesting depth of commands run by `if` and of $(...) inside $(...):
                              * each level is a few stack frames, so a deck (or a variable that
                              * runs itself) cannot overflow the stack */

/* ------------------------------------------------------------------ storage */

typedef struct {
  char *text; /* logical line: comments stripped, continuations joined */
  int line;   /* first physical line (1-based)                        */
} DeckLine;

typedef struct DeckSource {
  const char *name; /* interned path as opened (used in messages)   */
  char *dir;        /* directory for relative paths ("." for stdin) */
  DeckLine *lines;
  int n;
  struct DeckSource *next;
} DeckSource;

typedef struct {
  DeckSource *src;
  int pos; /* index of the next line to run */
} DeckFrame;

enum { VAR_EQUAL, VAR_STRING, VAR_INDEX, VAR_LOOP };
static const char *const var_styles[] = {"equal", "string", "index", "loop", "delete", NULL};

typedef struct {
  char *name;
  int style;
  int cmdline;  /* set with -var: the deck cannot redefine it              */
  int used;     /* looked up or (re)defined by the deck                    */
  char *text;   /* equal: the expression; string: the text                 */
  char **vals;  /* index: the values                                       */
  int nvals, which;
  long cur, hi; /* loop: current and last value                            */
  int pad;      /* loop ... pad: digits the value is written with (0: as it is) */
  int shadow_warned; /* read bare where a built-in of its name exists: warned */
} DeckVar;

struct YfDeck {
  struct YfSim *sim;
  DeckVar *vars;
  int nvars, capvars;
  DeckFrame stack[DECK_INCLUDE_MAX + 1];
  int depth;
  DeckSource *sources;
  int echo, quit, jump_skip;
  char **defnames; /* names the deck's variable commands define, in order  */
  int ndef, capdef, vars_checked;
  int eval_depth;
  int eval_count;  /* equal-style evaluations of the current top-level expression */
  int exec_depth;  /* commands running inside other commands (if), see DECK_NEST_MAX */
  int subst_depth; /* $(...) being substituted inside $(...)                    */
  long ncmd;       /* commands run so far (an empty deck is worth a warning)     */
  int log_warned;   /* the note on log() (natural here, base 10 in LAMMPS) was given */
  char **gone;      /* variables a 'next' deleted when it ran past their last value...  */
  YfLoc *gone_at;   /* ...and where (named when one is used after that)               */
  int ngone;
  int unknown_bare; /* the expression being evaluated met a bare name that is nothing known
                     * (not one written v_NAME, not inside a variable's own expression) */
};

/* Interned file names: never freed (a YfLoc may outlive the deck). */
static const char *intern(const char *s) {
  static char **names;
  static int n, cap;
  for (int i = 0; i < n; i++)
    if (!strcmp(names[i], s)) return names[i];
  if (n == cap) {
    cap = cap ? 2 * cap : 16;
    names = yf_realloc(names, (size_t)cap * sizeof *names, "deck file names");
  }
  names[n] = yf_strdup(s);
  return names[n++];
}

/* Growable string. */
typedef struct {
  char *s;
  size_t n, cap;
} Buf;
static void buf_putn(Buf *b, const char *s, size_t n) {
  if (b->n + n + 1 > b->cap) {
    b->cap = (b->n + n + 1) * 2;
    b->s = yf_realloc(b->s, b->cap, "deck text");
  }
  memcpy(b->s + b->n, s, n);
  b->n += n;
  b->s[b->n] = 0;
}
static void buf_put(Buf *b, const char *s) { buf_putn(b, s, strlen(s)); }
static void buf_putc(Buf *b, char c) { buf_putn(b, &c, 1); }
static char *buf_take(Buf *b) {
  if (!b->s) return yf_strdup("");
  return b->s;
}

/* ------------------------------------------------------------------ messages */

/* s for a message: whole up to 80 characters, else its first 60 and "..." (a 40 KB expression
 * would push what is wrong with it out of the message). */
static const char *abbrev(const char *s, char *buf, size_t n) {
  if (strlen(s) <= 80) return s;
  snprintf(buf, n, "%.60s...", s);
  return buf;
}

/* The line being run, as written and as substituted, while they differ (exec_line): an error
 * shown on the substituted line also shows the written one, or which ${NAME} gave which word
 * was lost ('-var L ""' made 'mesh rect ... ${L} ...' one word short, and the message showed the
 * line without a trace of ${L}). */
static const char *cur_written, *cur_substituted;

/* Deck error with context: the message, then the line and a caret under column col (col < 0:
 * no caret; line NULL: no context), then the line as written when line is its substitution. */
static void fail_ctx(const YfLoc *loc, const char *line, int col, const char *fmt, ...)
    __attribute__((noreturn, format(printf, 4, 5)));
static void fail_ctx(const YfLoc *loc, const char *line, int col, const char *fmt, ...) {
  char msg[1200];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(msg, sizeof msg, fmt, ap);
  va_end(ap);
  if (!line) yf_deck_error(loc, "%s", msg);
  /* Show at most ~160 characters of the line, around the caret; tabs and newlines become
   * spaces so that the caret lines up. */
  int len = (int)strlen(line), from = 0, width = 160;
  if (col > len) col = len;
  if (len > width && col > width / 2) from = col - width / 2;
  if (from > 0 && len - from < width) from = len - width > 0 ? len - width : 0;
  if (from > col && col >= 0) from = col;
  /* the window starts and ends on whole UTF-8 characters (a cut one printed as a broken byte) */
  while (from > 0 && from < len && ((unsigned char)line[from] & 0xC0) == 0x80) from--;
  int to = from + width < len ? from + width : len;
  while (to < len && to > from && ((unsigned char)line[to] & 0xC0) == 0x80) to--;
  char ctx[400];
  int k = 0;
  ctx[k++] = ' ';
  ctx[k++] = ' ';
  if (from > 0) { memcpy(ctx + k, "...", 3); k += 3; }
  for (int i = from; i < to; i++) {
    char c = line[i];
    ctx[k++] = (c == '\t' || c == '\n' || c == '\r') ? ' ' : c;
  }
  if (to < len) { memcpy(ctx + k, "...", 3); k += 3; }
  ctx[k] = 0;
  char written[200] = "";
  if (line == cur_substituted && cur_written) {
    size_t wl = strlen(cur_written);
    snprintf(written, sizeof written, "\n  (as written: %.160s%s)", cur_written, wl > 160 ? "..." : "");
    for (char *q = written + 1; *q; q++)
      if (*q == '\t' || *q == '\n' || *q == '\r') *q = ' ';
  }
  if (col < 0) yf_deck_error(loc, "%s\n%s%s", msg, ctx, written);
  char caret[400];
  /* the caret under the character: one column per UTF-8 character, not per byte ('é' and '→'
   * before the fault put it 1 and 2 columns too far right) */
  int chars = 0;
  for (int i = from; i < col && i < len; i++) chars += ((unsigned char)line[i] & 0xC0) != 0x80;
  int c = 0, pad = 2 + (from > 0 ? 3 : 0) + chars;
  for (int i = 0; i < pad && c < (int)sizeof caret - 2; i++) caret[c++] = ' ';
  caret[c++] = '^';
  caret[c] = 0;
  yf_deck_error(loc, "%s\n%s\n%s%s", msg, ctx, caret, written);
}

/* ------------------------------------------------------------------ words */

/* Split line into words.  A word starting with ", ' or """ runs to the matching quote (which is
 * removed) and must be followed by white space.  Returns the number of words, or -1 with *errcol
 * set and *why describing the problem.  words/cols are malloc'd (free each word and the arrays). */
static int split_words(const char *line, char ***words, int **cols, int *errcol, const char **why) {
  int n = 0, cap = 8;
  char **w = yf_malloc((size_t)cap * sizeof *w, "deck words");
  int *c = yf_malloc((size_t)cap * sizeof *c, "deck words");
  const char *p = line;
  for (;;) {
    while (*p && isspace((unsigned char)*p)) p++;
    if (!*p) break;
    const char *start = p, *b, *e;
    if (!strncmp(p, "\"\"\"", 3)) {
      b = p + 3;
      e = strstr(b, "\"\"\"");
      if (!e) goto unmatched;
      p = e + 3;
    } else if (*p == '"' || *p == '\'') {
      b = p + 1;
      e = strchr(b, *p);
      if (!e) goto unmatched;
      p = e + 1;
    } else {
      b = p;
      while (*p && !isspace((unsigned char)*p)) p++;
      e = p;
    }
    if (*p && !isspace((unsigned char)*p)) {
      *errcol = (int)(p - line);
      *why = "a quoted word must be followed by a space";
      goto fail;
    }
    if (n == cap) {
      cap *= 2;
      w = yf_realloc(w, (size_t)cap * sizeof *w, "deck words");
      c = yf_realloc(c, (size_t)cap * sizeof *c, "deck words");
    }
    w[n] = yf_malloc((size_t)(e - b) + 1, "deck word");
    memcpy(w[n], b, (size_t)(e - b));
    w[n][e - b] = 0;
    c[n++] = (int)(start - line);
    continue;
  unmatched:
    *errcol = (int)(start - line);
    *why = "unmatched quote";
    goto fail;
  }
  *words = w;
  *cols = c;
  return n;
fail:
  for (int i = 0; i < n; i++) free(w[i]);
  free(w);
  free(c);
  return -1;
}

static void free_words(char **w, int *c, int n) {
  for (int i = 0; i < n; i++) free(w[i]);
  free(w);
  free(c);
}

/* ------------------------------------------------------------------ variables */

static DeckVar *var_find(YfDeck *d, const char *name) {
  for (int i = 0; i < d->nvars; i++)
    if (!strcmp(d->vars[i].name, name)) {
      d->vars[i].used = 1;
      return &d->vars[i];
    }
  return NULL;
}

/* Whether NAME appears as a whole word in a line of a deck source read so far (a use after the
 * first run: ${nx}, $x, v_nx in an expression, or a `variable nx` further on). */
static int named_in_sources(const YfDeck *d, const char *name) {
  size_t n = strlen(name);
  for (const DeckSource *s = d->sources; s; s = s->next)
    for (int i = 0; i < s->n; i++)
      for (const char *t = s->lines[i].text, *p = t; (p = strstr(p, name)) != NULL; p++) {
        int before = p > t && (isalnum((unsigned char)p[-1]) || p[-1] == '_') &&
                     !(p - t >= 2 && p[-2] == 'v' && p[-1] == '_' && (p - t == 2 || !isalnum((unsigned char)p[-3])));
        int after = isalnum((unsigned char)p[n]) || p[n] == '_';
        if (!before && !after) return 1;
      }
  return 0;
}

static DeckSource *source_load(YfDeck *d, const char *path, const YfLoc *from, const char *cmd);
static char *dir_of(const char *path);
static char *join_path(const char *dir, const char *name);

/* Load the files that the loaded ones name in 'include FILE' or 'jump FILE' (FILE without '$',
 * a readable regular file), and the files those name, so that their text is searched too: a -var
 * used only in a file included after the first run was warned about as unused. */
static void load_named_files(YfDeck *d) {
  for (int added = 1, round = 0; added && round < DECK_INCLUDE_MAX; round++) {
    added = 0;
    for (DeckSource *s = d->sources; s; s = s->next)
      for (int i = 0; i < s->n; i++) {
        const char *t = s->lines[i].text;
        if (strncmp(t, "include", 7) && strncmp(t, "jump", 4)) continue;
        char **w;
        int *cols, errcol;
        const char *why;
        int n = split_words(t, &w, &cols, &errcol, &why);
        if (n < 0) continue;
        if (n >= 2 && (!strcmp(w[0], "include") || !strcmp(w[0], "jump")) && !strchr(w[1], '$') &&
            strcmp(w[1], "SELF")) {
          char *dir = dir_of(s->name), *path = join_path(dir, w[1]);
          int known = 0;
          for (const DeckSource *k = d->sources; k && !known; k = k->next) known = !strcmp(k->name, path);
          struct stat st;
          if (!known && !stat(path, &st) && S_ISREG(st.st_mode) && !access(path, R_OK)) {
            source_load(d, path, NULL, NULL);
            added = 1;
          }
          free(dir);
          free(path);
        }
        free_words(w, cols, n);
      }
  }
}

/* A -var NAME that the deck neither defines nor uses is most likely a typo (-var nz for nx): warn
 * once, before the first run, naming the deck's own variables.  A name that the deck's text
 * holds as a word further on (used only after the first run, or in a file it includes) is not
 * warned about. */
static void check_cmdline_vars(YfDeck *d) {
  if (d->vars_checked) return;
  d->vars_checked = 1;
  int any = 0;
  for (int i = 0; i < d->nvars && !any; i++) any = d->vars[i].cmdline && !d->vars[i].used;
  if (any) load_named_files(d);
  size_t cap = 16;
  for (int i = 0; i < d->ndef; i++) cap += strlen(d->defnames[i]) + 2;
  char *list = yf_malloc(cap, "variable names");
  list[0] = 0;
  for (int i = 0; i < d->ndef; i++) {
    if (i) strcat(list, ", ");
    strcat(list, d->defnames[i]);
  }
  for (int i = 0; i < d->nvars; i++) {
    const DeckVar *v = &d->vars[i];
    if (!v->cmdline || v->used || named_in_sources(d, v->name)) continue;
    const char *near = d->ndef ? yf_nearest(v->name, (const char *const *)d->defnames, d->ndef) : NULL;
    char hint[YF_NAME_MAX + 32] = "";
    if (near) snprintf(hint, sizeof hint, "; did you mean '%s'?", near);
    yf_warn(NULL, "-var %s: the deck defines and uses no variable '%s' (its variables: %s)%s", v->name, v->name,
            list[0] ? list : "none", hint);
  }
  free(list);
}

static void var_clear(DeckVar *v) {
  free(v->name);
  free(v->text);
  for (int i = 0; i < v->nvals; i++) free(v->vals[i]);
  free(v->vals);
  memset(v, 0, sizeof *v);
}

static void var_delete(YfDeck *d, const char *name) {
  DeckVar *v = var_find(d, name);
  if (!v) return;
  int i = (int)(v - d->vars);
  var_clear(v);
  memmove(d->vars + i, d->vars + i + 1, (size_t)(d->nvars - i - 1) * sizeof *d->vars);
  d->nvars--;
}

static DeckVar *var_new(YfDeck *d, const char *name, int style) {
  var_delete(d, name);
  if (d->nvars == d->capvars) {
    d->capvars = d->capvars ? 2 * d->capvars : 16;
    d->vars = yf_realloc(d->vars, (size_t)d->capvars * sizeof *d->vars, "deck variables");
  }
  DeckVar *v = &d->vars[d->nvars++];
  memset(v, 0, sizeof *v);
  v->name = yf_strdup(name);
  v->style = style;
  return v;
}

/* What is wrong with s as a variable name, NULL when nothing.  The length is the one expressions
 * read as v_NAME (expr.h): a longer name worked in ${NAME} and failed in $(v_NAME). */
static const char *name_fault(const char *s) {
  static char why[96];
  const char *p = s;
  if (!isalpha((unsigned char)*p) && *p != '_') return "letters, digits and '_' only, not starting with a digit";
  for (p++; *p; p++)
    if (!isalnum((unsigned char)*p) && *p != '_') return "letters, digits and '_' only, not starting with a digit";
  if (p - s > EXPR_VAR_NAME_MAX) {
    snprintf(why, sizeof why, "%d characters: a variable name has at most %d (the longest an expression reads "
             "as v_NAME)", (int)(p - s), EXPR_VAR_NAME_MAX);
    return why;
  }
  return NULL;
}

static int lookup_cb(void *ctx, const char *name, double *val, char *err, size_t errlen);

/* The deck line running now (file NULL when none). */
static YfLoc here(const YfDeck *d) {
  YfLoc l = {0};
  if (d->depth > 0) {
    const DeckFrame *f = &d->stack[d->depth - 1];
    l.file = f->src->name;
    l.line = f->pos > 0 ? f->src->lines[f->pos - 1].line : 0;
  }
  return l;
}

/* LAMMPS's log() is base 10; here, as in C and Python, it is the natural one: a LAMMPS deck's
 * log(x) read 2.3 times its value, silently.  Said once, where it is first met. */
static void note_log(YfDeck *d, const ExprError *e, const YfLoc *loc) {
  if (!e->uses_log || d->log_warned) return;
  d->log_warned = 1;
  YfLoc l = loc ? *loc : here(d);
  yf_warn(l.file ? &l : NULL, "log() is the natural logarithm (as in C and Python; LAMMPS's log() is base 10): "
          "write ln() for the natural one, log10() for base 10, and this note goes");
}

/* What an unknown variable NAME could have been, for its message: " (did you mean 'nx'?)", else
 * the variables there are (" (variables: nx, ny)") or " (no variable is defined)".  bare: NAME
 * stands alone in an expression, where the simulation's names (step, ke, ...) are read too.
 * ("unknown variable 'nX'" alone left the user to find the deck's spelling of it.) */
static void unknown_hint(const YfDeck *d, const char *name, int bare, char *buf, size_t n) {
  static const char *const own[] = {"step", "time", "dt", "pi", NULL};
  const char *const *kw = sim_query_keywords();
  int nk = 0, nown = 0, k = 0;
  while (kw[nk]) nk++;
  while (own[nown]) nown++;
  const char **names = yf_malloc((size_t)(d->nvars + nk + nown + 1) * sizeof *names, "variable names");
  for (int i = 0; i < d->nvars; i++) names[k++] = d->vars[i].name;
  if (bare) {
    for (int i = 0; i < nown; i++) names[k++] = own[i];
    for (int i = 0; i < nk; i++) names[k++] = kw[i];
  }
  for (int i = 0; i < d->ngone; i++)
    if (!strcmp(d->gone[i], name)) { /* LAMMPS's rule, which surprises: say it */
      snprintf(buf, n, " (the 'next %s' at %s:%d deleted it when it ran past its last value, as LAMMPS does; "
               "keep a value for after the loop in another variable)", name, d->gone_at[i].file, d->gone_at[i].line);
      return;
    }
  /* one or two letters are near to any short name: no guess for them but a change of case (nX
   * for nx), the list says enough */
  const char *near = strlen(name) >= 3 ? yf_nearest(name, names, k) : NULL;
  for (int i = 0; i < k && !near; i++)
    if (!strcasecmp(name, names[i])) near = names[i];
  free(names);
  if (near) {
    snprintf(buf, n, " (did you mean '%s'?)", near);
    return;
  }
  if (!d->nvars) {
    snprintf(buf, n, " (no variable is defined)");
    return;
  }
  size_t len = (size_t)snprintf(buf, n, " (variables: ");
  for (int i = 0; i < d->nvars && len < n; i++) {
    if (len + strlen(d->vars[i].name) + 8 > n || i == 12) {
      len += (size_t)snprintf(buf + len, n - len, "...");
      break;
    }
    len += (size_t)snprintf(buf + len, n - len, "%s%s", i ? ", " : "", d->vars[i].name);
  }
  if (len < n) snprintf(buf + len, n - len, ")");
}

/* Evaluate expr; on failure write "expression 'expr': why" into err and return 0. */
static int eval_quiet(YfDeck *d, const char *expr, double *out, ExprError *e) {
  int ok = expr_eval(expr, lookup_cb, d, out, e);
  if (ok) note_log(d, e, NULL);
  return ok;
}

/* Numeric value of a variable: 1 ok, -1 error (err filled). */
static int var_number(YfDeck *d, DeckVar *v, double *val, char *err, size_t errlen) {
  if (v->style == VAR_EQUAL) {
    if (d->eval_depth >= DECK_EVAL_MAX) {
      snprintf(err, errlen, "variable '%s': equal-style variables nested deeper than %d "
                            "(does it refer to itself?)", v->name, DECK_EVAL_MAX);
      return -1;
    }
    /* a chain of variables each reading the one before twice is 2^depth evaluations: 60 such
     * lines spun for ever, deaf to a signal (checked between commands) */
    if (d->eval_depth == 0) d->eval_count = 0;
    if (++d->eval_count > DECK_EVAL_WORK) {
      snprintf(err, errlen, "variable '%s': more than %d evaluations of equal-style variables for one expression "
               "(variables that each read the one before more than once double the work at every level: store "
               "a value once with 'variable NAME equal $(EXPR)')", v->name, DECK_EVAL_WORK);
      return -1;
    }
    ExprError e;
    d->eval_depth++;
    int ok = eval_quiet(d, v->text, val, &e);
    d->eval_depth--;
    if (!ok) {
      /* report the innermost variable only: a chain of prefixes would be unreadable */
      if (!strncmp(e.msg, "variable '", 10)) snprintf(err, errlen, "%s", e.msg);
      else snprintf(err, errlen, "variable '%s' = '%s': %s", v->name, v->text, e.msg);
      return -1;
    }
    return 1;
  }
  if (v->style == VAR_LOOP) {
    *val = (double)v->cur;
    return 1;
  }
  const char *s = v->style == VAR_STRING ? v->text : v->vals[v->which];
  if (!yf_parse_double(s, val)) {
    snprintf(err, errlen, "variable '%s' has the non-numeric value '%s'", v->name, s);
    return -1;
  }
  return 1;
}

/* 1 when a bare name in an expression has a meaning of its own besides a variable's */
static int builtin_name(YfDeck *d, const char *name) {
  static const char *const own[] = {"step", "time", "dt", "pi", "PI", NULL};
  for (int i = 0; own[i]; i++)
    if (!strcmp(name, own[i])) return 1;
  return d->sim && sim_query_known(d->sim, name) != 0;
}

static int lookup_cb(void *ctx, const char *written, double *val, char *err, size_t errlen) {
  YfDeck *d = ctx;
  int prefixed = !strncmp(written, "v_", 2) && written[2]; /* v_X: the variable X (LAMMPS spelling) */
  const char *name = prefixed ? written + 2 : written;
  DeckVar *v = var_find(d, name);
  if (v && !prefixed && !v->shadow_warned && builtin_name(d, name)) {
    /* 'variable time equal 0.01' then $(time): the variable wins, silently (pi read 3) */
    v->shadow_warned = 1;
    YfLoc l = here(d);
    yf_warn(l.file ? &l : NULL, "'%s' in an expression reads your variable '%s', which hides the built-in '%s'; "
            "write v_%s to say you mean the variable, or rename the variable to read the built-in", name, name, name, name);
  }
  if (v) return var_number(d, v, val, err, errlen);
  if (d->sim) { /* simulation state */
    if (!strcmp(name, "step")) { *val = (double)d->sim->step; return 1; }
    if (!strcmp(name, "time")) { *val = d->sim->time; return 1; }
    if (!strcmp(name, "dt")) {
      /* before the run that computes it, 'timestep auto' has no dt yet: it read 0 ('run
       * $(round(T/dt))' failed as a division by zero) or the step of an earlier 'timestep DT' */
      if (d->sim->dt_pending) {
        snprintf(err, errlen, "'dt' under 'timestep auto' is known once a run has computed it (the safety factor "
                 "times the scene's stable limit): put 'run 0' after 'timestep auto' and before this line");
        return -1;
      }
      if (!(d->sim->dt > 0)) {
        snprintf(err, errlen, "'dt' is not known yet: no time step is set; give 'timestep DT', or 'timestep auto' and 'run 0', "
                 "before this line");
        return -1;
      }
      *val = d->sim->dt;
      return 1;
    }
    int q = sim_query(d->sim, name, val, err, errlen); /* thermo keywords, group averages */
    if (q) return q;
  }
  if (!prefixed && (!strcmp(name, "pi") || !strcmp(name, "PI"))) return 0; /* the evaluator's own */
  if (!prefixed && (!strcasecmp(name, "nan") || !strcasecmp(name, "inf") || !strcasecmp(name, "infinity"))) {
    /* a deck written by a script that computed a NaN: "unknown variable 'nan'" hid the cause */
    snprintf(err, errlen, "'%s' is not a finite number, and expressions hold finite numbers only (did the script "
             "that wrote this deck compute a %s?)", name, tolower((unsigned char)name[0]) == 'n' ? "NaN" : "division by zero or an overflow");
    return -1;
  }
  if (!prefixed && d->eval_depth == 0) d->unknown_bare = 1;
  char hint[300];
  unknown_hint(d, name, !prefixed, hint, sizeof hint);
  snprintf(err, errlen, "unknown variable '%s'%s", name, hint);
  return -1;
}

/* Evaluate or fail with "expression 'e': why" and the expression with a caret. */
static double eval_or_fail(YfDeck *d, const char *expr, const YfLoc *loc, const char *prefix) {
  double v;
  ExprError e;
  if (!eval_quiet(d, expr, &v, &e))
  {
    char ab[80];
    fail_ctx(loc, expr, e.pos, "%sexpression '%s': %s", prefix ? prefix : "", abbrev(expr, ab, sizeof ab), e.msg);
  }
  return v;
}

double deck_eval(YfDeck *d, const char *expr, const YfLoc *loc) { return eval_or_fail(d, expr, loc, NULL); }
double deck_eval_as(YfDeck *d, const char *expr, const YfLoc *loc, const char *what) {
  return eval_or_fail(d, expr, loc, what);
}

/* A number as ${NAME} and $(EXPR) write it: 15 significant digits, except that an integer up to
 * 2^53 (where doubles hold every integer) is written whole: %.15g wrote 2^50 as
 * 1.12589990684262e+15, another integer, and a count of 1e15 or more as "1e+15". */
static void fmt_number(char *buf, size_t n, double v) {
  if (v == floor(v) && fabs(v) <= 9007199254740992.0) snprintf(buf, n, "%.0f", v == 0.0 ? 0.0 : v);
  else snprintf(buf, n, "%.15g", v);
}

/* The text a ${name} reference stands for; NULL if the variable does not exist. */
static char *var_text(YfDeck *d, const char *name, const YfLoc *loc, const char *line, int col) {
  DeckVar *v = var_find(d, name);
  if (!v) return NULL;
  char buf[64];
  switch (v->style) {
  case VAR_EQUAL: {
    char err[600];
    double x;
    if (var_number(d, v, &x, err, sizeof err) < 0) fail_ctx(loc, line, col, "%s", err);
    fmt_number(buf, sizeof buf, x);
    return yf_strdup(buf);
  }
  case VAR_STRING: return yf_strdup(v->text);
  case VAR_INDEX: return yf_strdup(v->vals[v->which]);
  default: snprintf(buf, sizeof buf, "%0*ld", v->pad, v->cur); return yf_strdup(buf);
  }
}

/* A printf format for $(expr:%fmt): one conversion, nothing else.  Returns 1 for a floating
 * conversion (e f g), 2 for an integer one (d i: the value is rounded), 0 if invalid. */
static int valid_format(const char *f) {
  /* at most 5 flags and 2 digits each of width and precision: the widest result, %99.99f of
   * 1e308, then fits the 512 bytes substitute() formats into (a wider one was cut short, and
   * more flags overflowed the format copy that gains the 'l') */
  if (*f++ != '%') return 0;
  int n = 0;
  while (*f && strchr("-+ #0", *f)) f++, n++;
  if (n > 5) return 0;
  for (n = 0; isdigit((unsigned char)*f); f++) n++;
  if (n > 2) return 0;
  if (*f == '.') {
    f++;
    for (n = 0; isdigit((unsigned char)*f); f++) n++;
    if (n > 2) return 0;
  }
  if (f[0] && f[1]) return 0;
  if (*f && strchr("eEfFgG", *f)) return 1;
  if (*f == 'd' || *f == 'i') return 2;
  return 0;
}

/* Substitute ${name}, $x and $(expr[:%fmt]) outside single quotes.  Returns malloc'd text. */
static char *substitute(YfDeck *d, const char *in, const YfLoc *loc) {
  Buf b = {0};
  int in_s = 0, in_d = 0;
  for (const char *p = in; *p; p++) {
    /* string variables that each hold the one before four times grew to gigabytes, and the run
     * ended as "out of memory" with no line */
    if (b.n > DECK_LINE_MAX)
      fail_ctx(loc, in, (int)(p - in), "the line grows beyond %d MiB as its variables are substituted (variables "
               "that each hold the one before several times?)", DECK_LINE_MAX >> 20);
    if (*p == '\'' && !in_d) in_s = !in_s;
    else if (*p == '"' && !in_s) in_d = !in_d;
    if (*p != '$' || in_s) {
      buf_putc(&b, *p);
      continue;
    }
    int col = (int)(p - in);
    if (p[1] == '{') {
      const char *e = strchr(p + 2, '}');
      if (!e) fail_ctx(loc, in, col, "missing '}' after '${'");
      char name[256];
      size_t len = (size_t)(e - p - 2);
      if (len == 0) fail_ctx(loc, in, col, "empty variable name in '${}'");
      if (len >= sizeof name) fail_ctx(loc, in, col, "variable name too long");
      memcpy(name, p + 2, len);
      name[len] = 0;
      char *t = var_text(d, name, loc, in, col);
      if (!t) {
        char hint[300];
        unknown_hint(d, name, 0, hint, sizeof hint);
        fail_ctx(loc, in, col, "unknown variable '%s'%s", name, hint);
      }
      buf_put(&b, t);
      free(t);
      p = e;
    } else if (p[1] == '(') {
      int depth = 0;
      const char *e = p + 1;
      for (; *e; e++) {
        if (*e == '(') depth++;
        else if (*e == ')' && --depth == 0) break;
      }
      if (!*e) fail_ctx(loc, in, col, "missing ')' to close '$('");
      size_t len = (size_t)(e - p - 2);
      char *expr = yf_malloc(len + 1, "expression");
      memcpy(expr, p + 2, len);
      expr[len] = 0;
      if (strchr(expr, '$')) { /* $(v_a*${b}): references inside are substituted first */
        if (d->subst_depth >= DECK_NEST_MAX)
          fail_ctx(loc, in, col, "$(...) nested inside $(...) deeper than %d levels", DECK_NEST_MAX);
        d->subst_depth++;
        char *inner = substitute(d, expr, loc);
        d->subst_depth--;
        free(expr);
        expr = inner;
      }
      /* optional ":%fmt" at parenthesis depth 0 */
      const char *fmt = NULL;
      int kind = 1;
      char *colon = NULL;
      int dd = 0;
      for (char *q = expr; *q; q++) {
        if (*q == '(') dd++;
        else if (*q == ')') dd--;
        else if (*q == ':' && dd == 0 && q[1] == '%') colon = q;
      }
      if (colon) {
        *colon = 0;
        fmt = colon + 1;
        kind = valid_format(fmt);
        if (!kind)
          fail_ctx(loc, in, col + 2 + (int)(colon - expr) + 1,
                   "bad format '%s' in $(...) (expected one conversion like %%.3f, %%g, %%10.4e or %%d, width and "
                   "precision of at most 2 digits)", fmt);
      }
      double v;
      ExprError er;
      if (!eval_quiet(d, expr, &v, &er))
      {
        char ab[80];
        fail_ctx(loc, in, col + 2 + er.pos, "expression '%s': %s", abbrev(expr, ab, sizeof ab), er.msg);
      }
      char num[512];
      if (v == 0.0) v = 0.0;
      if (kind == 2) {
        if (fabs(v) > 9.0e18) fail_ctx(loc, in, col, "value %g of $(...) is too large for an integer format", v);
        /* the format was checked to be a single integer conversion; add the 'l' length */
        char lf[32];
        snprintf(lf, sizeof lf, "%.*sl%s", (int)strlen(fmt) - 1, fmt, fmt + strlen(fmt) - 1);
        snprintf(num, sizeof num, lf, (long)llround(v));
      } else if (colon)
        snprintf(num, sizeof num, fmt, v);
      else
        fmt_number(num, sizeof num, v);
      buf_put(&b, num);
      free(expr);
      p = e;
    } else if (isalpha((unsigned char)p[1]) || p[1] == '_') {
      char name[2] = {p[1], 0};
      char *t = var_text(d, name, loc, in, col);
      if (!t) fail_ctx(loc, in, col, "unknown variable '%s' (write ${name} for longer names)", name);
      buf_put(&b, t);
      free(t);
      p++;
    } else {
      buf_putc(&b, '$'); /* a lone '$' stays */
    }
  }
  return buf_take(&b);
}

/* ------------------------------------------------------------------ reading files */

/* Cut a whole deck text into logical lines (see the top of the file). */
static void parse_lines(DeckSource *s, const char *text, size_t len) {
  Buf cur = {0};
  int line = 1, start = 1, in_s = 0, in_d = 0, in_t = 0, cap = 0;
  for (size_t i = 0; i <= len; i++) {
    char c = i < len ? text[i] : '\n';
    /* a CR alone ends a line (classic Mac text); CRs before a LF (CRLF, or the CR CR LF of a
     * text converted twice) are one end with it: they are dropped below */
    if (c == '\r') {
      size_t k = i;
      while (k < len && text[k] == '\r') k++;
      if (k >= len || text[k] != '\n') c = '\n';
    }
    if (i == len && !cur.n && !in_t) break;
    if (i < len && c == 0) { /* a NUL would silently cut the line short: say where it is */
      YfLoc l = {s->name, line};
      size_t col = 1;
      for (size_t k = i; k > 0 && text[k - 1] != '\n'; k--) col++;
      yf_deck_error(&l, "a NUL byte at column %zu: a deck is plain text (is this a binary file, or a UTF-16 "
                        "text? save it as UTF-8 or ASCII)", col);
    }
    if (in_t) {
      if (i == len) in_t = 0; /* unterminated: the word splitter reports it */
      else if (!strncmp(text + i, "\"\"\"", 3) && i + 3 <= len) {
        buf_putn(&cur, "\"\"\"", 3);
        i += 2;
        in_t = 0;
        continue;
      } else {
        if (c == '\n') line++;
        if (c != '\r') buf_putc(&cur, c);
        continue;
      }
    }
    if (c == '\r') continue;
    if (c == '\n') {
      while (cur.n && isspace((unsigned char)cur.s[cur.n - 1])) cur.s[--cur.n] = 0;
      if (cur.n && cur.s[cur.n - 1] == '&' && i < len) { /* continuation */
        cur.s[--cur.n] = 0;
        buf_putc(&cur, ' ');
        line++;
        continue;
      }
      if (cur.n && cur.s[cur.n - 1] == '&') cur.s[--cur.n] = 0; /* '&' on the last line */
      const char *q = cur.s;
      while (q && *q && isspace((unsigned char)*q)) q++;
      if (q && *q) {
        if (s->n == cap) {
          cap = cap ? 2 * cap : 64;
          s->lines = yf_realloc(s->lines, (size_t)cap * sizeof *s->lines, "deck lines");
        }
        s->lines[s->n].text = yf_strdup(q);
        s->lines[s->n].line = start;
        s->n++;
      }
      cur.n = 0;
      if (cur.s) cur.s[0] = 0;
      in_s = in_d = 0;
      line++;
      start = line;
      continue;
    }
    if (!in_s && !in_d && !strncmp(text + i, "\"\"\"", 3) && i + 3 <= len) {
      buf_putn(&cur, "\"\"\"", 3);
      i += 2;
      in_t = 1;
      continue;
    }
    if (c == '\'' && !in_d) in_s = !in_s;
    else if (c == '"' && !in_s) in_d = !in_d;
    if (c == '#' && !in_s && !in_d) { /* comment to the end of the line */
      while (i + 1 < len && text[i + 1] != '\n' && text[i + 1] != '\r') i++;
      continue;
    }
    buf_putc(&cur, c);
  }
  free(cur.s);
}

static char *dir_of(const char *path) {
  if (!path || path[0] == '<') return yf_strdup(".");
  /* a deck read through a pipe ('-in <(python3 gen.py)' is /dev/fd/63, '-in /dev/stdin') found its
   * includes and meshes in /dev/fd or /dev: a pipe's deck, like stdin's, reads from the working
   * directory, and a file behind /dev/stdin from its own folder */
  struct stat st;
  if (!strncmp(path, "/dev/", 5) || !strncmp(path, "/proc/", 6)) {
    /* (MPI: rank 0's /dev/stdin is the file, the others' /dev/null: the working directory on
     * every rank, or the ranks would look for the deck's files in different places) */
    char *real = par_size() > 1 ? NULL : realpath(path, NULL);
    if (real && strncmp(real, "/dev/", 5) && strncmp(real, "/proc/", 6) && !stat(real, &st) && S_ISREG(st.st_mode)) {
      char *dir = dir_of(real);
      free(real);
      return dir;
    }
    free(real);
    return yf_strdup(".");
  }
  if (!stat(path, &st) && (S_ISFIFO(st.st_mode) || S_ISCHR(st.st_mode))) return yf_strdup(".");
  const char *slash = strrchr(path, '/');
  if (!slash) return yf_strdup(".");
  if (slash == path) return yf_strdup("/");
  size_t n = (size_t)(slash - path);
  char *dir = yf_malloc(n + 1, "path");
  memcpy(dir, path, n);
  dir[n] = 0;
  return dir;
}

static char *join_path(const char *dir, const char *name) {
  if (name[0] == '/' || !dir || !strcmp(dir, ".")) return yf_strdup(name);
  size_t n = strlen(dir) + strlen(name) + 2;
  char *p = yf_malloc(n, "path");
  snprintf(p, n, "%s%s%s", dir, dir[strlen(dir) - 1] == '/' ? "" : "/", name);
  return p;
}

/* Ctrl-C or SIGTERM (main sets sim->interrupted) while the deck is read or run outside `run`
 * (a `run` stops after its current step itself): stop with the files written so far closed. */
static void deck_interrupted(YfDeck *d, const YfLoc *loc) __attribute__((noreturn));
static void deck_interrupted(YfDeck *d, const YfLoc *loc) {
  int sig = d->sim ? d->sim->interrupted : 0;
  const char *name = sig == SIGTERM ? "SIGTERM" : "SIGINT";
  if (loc && loc->file && d->sim && d->sim->runs_begun > 0) {
    /* between runs (a loop of short runs spends its time there under mpirun, whose ranks wait on
     * their output once it stops reading): the state the last run left is kept, as a run's own
     * interrupt keeps its step's (the progress of a loop of 100-step runs was lost every time) */
    YfEvent iev = {.kind = YF_EV_INTERRUPT, .restart_path = ""};
    sim_notify(d->sim, &iev);
    if (iev.restart_path[0])
      yf_exit_with(YF_EXIT_INTERRUPT, "%s:%d: interrupted (%s) before this line ran, at step %ld: restart of that "
                   "state written to '%s', files written so far kept; to go on from it, run a deck of the commands "
                   "that build the scene, then 'read_restart %s' and the commands from this line on (without the "
                   "runs before it: read_restart comes before any run)", loc->file, loc->line, name, d->sim->step,
                   iev.restart_path, iev.restart_path);
  }
  if (loc && loc->file)
    yf_exit_with(YF_EXIT_INTERRUPT, "%s:%d: interrupted (%s) before this line ran, at step %ld: files written so far "
                 "are closed", loc->file, loc->line, name, d->sim ? d->sim->step : 0L);
  yf_exit_with(YF_EXIT_INTERRUPT, "interrupted (%s) while reading the deck: nothing was run", name);
}

static DeckSource *source_from_stream(YfDeck *d, FILE *fp, const char *name, const YfLoc *from) {
  Buf b = {0};
  char chunk[65536];
  size_t got;
  yf_interruptible(1); /* a deck on a terminal or a pipe may block here: let Ctrl-C end the read */
  while (!(d->sim && d->sim->interrupted) && (got = fread(chunk, 1, sizeof chunk, fp)) > 0) buf_putn(&b, chunk, got);
  int err = errno;
  yf_interruptible(0);
  if (d->sim && d->sim->interrupted) deck_interrupted(d, from);
  if (ferror(fp)) yf_io_error(from, "cannot read deck '%s': %s", name, strerror(err));
  DeckSource *s = yf_calloc(1, sizeof *s, "deck source");
  s->name = intern(name);
  s->dir = dir_of(name);
  size_t bom = b.s && b.n >= 3 ? yf_skip_bom(b.s) : 0; /* (b.s ends in a NUL: buf_putn) */
  parse_lines(s, b.s ? b.s : "", b.n - bom);
  free(b.s);
  s->next = d->sources;
  d->sources = s;
  return s;
}

/* A deck file, loaded once and kept (jump and repeated includes reuse it). */
static DeckSource *source_load(YfDeck *d, const char *path, const YfLoc *from, const char *cmd) {
  for (DeckSource *s = d->sources; s; s = s->next)
    if (!strcmp(s->name, path)) return s;
  /* MPI: a pipe or a device ('-in /dev/stdin', '-in <(...)', a FIFO) gives each rank other bytes
   * (mpirun's other ranks read /dev/null): they ran different decks and the job hung.  As a deck
   * on stdin, rank 0 reads it (its stat decides, for every rank) and sends it to all. */
  struct stat st;
  int shared = par_size() > 1 && (int)par_bcast_long(!stat(path, &st) && !S_ISREG(st.st_mode));
  FILE *fp = shared && par_rank() != 0 ? NULL : yf_open_input(path, "rb");
  if (!fp && !(shared && par_rank() != 0)) {
    if (cmd) yf_io_error(from, "%s: cannot open '%s': %s", cmd, path, strerror(errno));
    yf_io_error(from, "cannot open deck '%s': %s", path, strerror(errno));
  }
  static volatile int no_stop;
  FILE *in = shared ? par_stdin(fp, d->sim ? &d->sim->interrupted : &no_stop) : fp;
  DeckSource *s = source_from_stream(d, in, path, from);
  if (in != fp) fclose(in);
  if (fp) fclose(fp);
  return s;
}

/* ------------------------------------------------------------------ running */

static const char *const *command_names(int *n) {
  static const char **names;
  static int count = -1;
  if (count < 0) {
    int k = 0;
    while (yf_commands[k].name) k++;
    names = yf_malloc((size_t)(k + 1) * sizeof *names, "command names");
    for (int i = 0; i < k; i++) names[i] = yf_commands[i].name;
    count = k;
  }
  *n = count;
  return names;
}

const char *deck_nearest_command(const char *word) {
  int nn;
  const char *const *names = command_names(&nn);
  return yf_nearest(word, names, nn);
}

/* LAMMPS commands that a LAMMPS user writes in a deck and yfdem spells otherwise, does otherwise
 * or needs not: "unknown command 'log' (did you mean 'load'?)" led away from -log. */
static const char *lammps_command_hint(const char *w) {
  static const char *const hint[][2] = {
      {"log", "yfdem names its log on the command line: -log FILE (default log.yfdem) or -log none"},
      {"units", "yfdem works in SI units always (m, kg, s, N, Pa; loads and forces per metre of thickness): "
                "delete the line"},
      {"dimension", "yfdem is two-dimensional always (plane stress or plane strain, set by 'material'): delete the "
                    "line"},
      {"shell", "yfdem runs no shell commands from a deck: make folders before the run (an output whose folder is "
                "missing is an error at its line)"},
      {"clear", "yfdem builds one scene per deck: run one deck per case (-var NAME VALUE sets its parameters)"},
      {"python", "a deck runs no Python: write the deck from Python (a YADE-style script) and run it, or sweep "
                 "with tools/yfsweep.py"},
      {"write_dump", "frames are written by 'dump' during runs (and at the start of each, so 'run 0' writes one); "
                     "the state at once by write_restart or write_y2d"},
      {"thermo_modify", "thermo lines reach the screen and the log at once; choose their columns with "
                        "'thermo_style custom'"},
      {"reset_timestep", "the step count runs on from run to run; 'run N upto' runs until step N"},
      {"info", "print a variable with 'print \"${NAME}\"'; 'yfdem -h COMMAND' describes a command"},
      {"atom_style", "yfdem's bodies are triangle meshes, not atoms: 'mesh', 'read_y2d', 'nodes'/'triangles'"},
      {"read_data", "yfdem reads meshes: 'mesh gmsh BODY FILE.msh', 'read_y2d FILE.y', 'nodes'/'triangles'"},
      {"pair_style", "bodies interact through 'contact' (penalty and friction) and break through "
                     "'jointprop'/'fracture'"},
      {"minimize", "yfdem is explicit dynamics: reach a static state with 'damping' and a 'run'"},
  };
  for (size_t k = 0; k < sizeof hint / sizeof hint[0]; k++)
    if (!strcmp(w, hint[k][0])) return hint[k][1];
  return NULL;
}

/* Substitute, split and dispatch one logical line. */
static void exec_line(YfDeck *d, const char *text, const YfLoc *loc) {
  if (d->exec_depth >= DECK_NEST_MAX)
    fail_ctx(loc, text, -1, "commands nested deeper than %d levels (an 'if' runs an 'if' that runs an "
             "'if' ...; does a variable run itself?)", DECK_NEST_MAX);
  if (d->sim) {
    /* MPI: a signal to one rank stops every rank before the same line (a rank that stopped alone
     * left the others waiting in the next collective: a job that never ended) */
    int sig = (int)par_max((double)d->sim->interrupted);
    if (sig) {
      d->sim->interrupted = sig;
      deck_interrupted(d, loc);
    }
  }
  char *line = substitute(d, text, loc);
  const char *was_written = cur_written, *was_substituted = cur_substituted;
  int differs = strcmp(text, line) != 0;
  cur_written = differs ? text : NULL;
  cur_substituted = differs ? line : NULL;
  char **w;
  int *cols, errcol;
  const char *why;
  int n = split_words(line, &w, &cols, &errcol, &why);
  if (n < 0) fail_ctx(loc, line, errcol, "%s", why);
  if (n == 0) {
    free_words(w, cols, n);
    free(line);
    cur_written = was_written, cur_substituted = was_substituted;
    return;
  }
  if (d->echo) {
    if (d->sim) sim_printf(d->sim, "%s\n", line);
    else printf("%s\n", line);
  }
  if (d->sim && d->sim->log) { /* the log holds the input as read, as log.lammps does */
    fprintf(d->sim->log, "%s\n", line);
    fflush(d->sim->log);
  }
  const YfCommand *c = deck_find_command(w[0]);
  if (c && !strcmp(c->name, "run")) check_cmdline_vars(d);
  if (!c) {
    int nn;
    const char *const *names = command_names(&nn);
    const char *near = yf_nearest(w[0], names, nn);
    if (!strncmp(w[0], "/YD/", 4) || !strncmp(w[0], "/*", 2) || !strncmp(w[0], "$Y", 2))
      fail_ctx(loc, line, cols[0], "unknown command '%s': this looks like a Y2D .y deck, which yfdem reads as one "
               "when its name ends in .y (yfdem FILE.y), or inside a deck with 'read_y2d FILE'", w[0]);
    const char *lh = lammps_command_hint(w[0]);
    if (lh) fail_ctx(loc, line, cols[0], "unknown command '%s' (a LAMMPS command): %s", w[0], lh);
    if (near) fail_ctx(loc, line, cols[0], "unknown command '%s' (did you mean '%s'?)", w[0], near);
    fail_ctx(loc, line, cols[0], "unknown command '%s'", w[0]);
  }
  YfArgs a;
  a.cmd = c->name;
  a.n = n - 1;
  a.w = w + 1;
  a.loc = *loc;
  a.line = line;
  d->exec_depth++;
  d->ncmd++;
  c->fn(d->sim, &a);
  d->exec_depth--;
  free_words(w, cols, n);
  free(line);
  cur_written = was_written, cur_substituted = was_substituted;
}

/* Run the source from position pos on a new frame until its end, a quit, or an error. */
static void run_source(YfDeck *d, DeckSource *s, const YfLoc *from) {
  if (d->depth == 0) d->quit = 0;
  if (d->depth >= DECK_INCLUDE_MAX) {
    int self = 0;
    for (int i = 0; i < d->depth; i++) self |= d->stack[i].src == s;
    yf_deck_error(from, "include: nesting deeper than %d levels%s%s%s", DECK_INCLUDE_MAX,
                  self ? " ('" : "", self ? s->name : "", self ? "' includes itself, directly or through other files)" : "");
  }
  DeckFrame *f = &d->stack[d->depth++];
  f->src = s;
  f->pos = 0;
  while (!d->quit && f->pos < f->src->n) {
    DeckLine *l = &f->src->lines[f->pos++];
    YfLoc loc = {f->src->name, l->line};
    exec_line(d, l->text, &loc);
  }
  d->depth--;
}

YfDeck *deck_new(struct YfSim *sim) {
  YfDeck *d = yf_calloc(1, sizeof *d, "deck");
  cur_written = cur_substituted = NULL; /* (a harness that longjmps out of an error left them set) */
  d->sim = sim;
  if (sim) sim->deck = d;
  return d;
}

void deck_free(YfDeck *d) {
  if (!d) return;
  for (int i = 0; i < d->nvars; i++) var_clear(&d->vars[i]);
  free(d->vars);
  for (int i = 0; i < d->ndef; i++) free(d->defnames[i]);
  free(d->defnames);
  for (int i = 0; i < d->ngone; i++) free(d->gone[i]);
  free(d->gone);
  free(d->gone_at);
  DeckSource *s = d->sources;
  while (s) {
    DeckSource *nx = s->next;
    for (int i = 0; i < s->n; i++) free(s->lines[i].text);
    free(s->lines);
    free(s->dir);
    free(s);
    s = nx;
  }
  if (d->sim && d->sim->deck == d) d->sim->deck = NULL;
  free(d);
}

void deck_set_var(YfDeck *d, const char *name, const char *value) {
  const char *why = name_fault(name);
  if (why) yf_deck_error(NULL, "-var: bad variable name '%.60s%s' (%s)", name, strlen(name) > 60 ? "..." : "", why);
  /* '-var n 5 ... -var n 7' kept the last in silence, where LAMMPS keeps the first */
  for (int i = 0; i < d->nvars; i++)
    if (d->vars[i].cmdline && !strcmp(d->vars[i].name, name) && d->vars[i].nvals == 1 &&
        strcmp(d->vars[i].vals[0], value) != 0)
      yf_warn(NULL, "-var %s is given twice ('%.60s', then '%.60s'): the last is used (LAMMPS keeps the first)", name,
              d->vars[i].vals[0], value);
  DeckVar *v = var_new(d, name, VAR_INDEX);
  v->cmdline = 1;
  v->vals = yf_malloc(sizeof *v->vals, "variable values");
  v->vals[0] = yf_strdup(value);
  v->nvals = 1;
}

void deck_set_echo(YfDeck *d, int on) { d->echo = on != 0; }

/* A deck without a single command ran nothing and exited 0 in silence: an empty file on stdin
 * (a generator that failed, 'yfdem < /dev/null') looked like a run that went well. */
static void warn_if_empty(const YfDeck *d, const DeckSource *s) {
  if (d->ncmd || d->depth) return;
  YfLoc loc = {s->name, 1};
  yf_warn(&loc, "the deck holds no command (it is empty, or only comments and blank lines): nothing was done");
}

void deck_run_stream(YfDeck *d, FILE *fp, const char *fname) {
  DeckSource *s = source_from_stream(d, fp, fname ? fname : "<stdin>", NULL);
  run_source(d, s, NULL);
  warn_if_empty(d, s);
}

void deck_run_file(YfDeck *d, const char *path, const YfLoc *from) {
  DeckSource *s = source_load(d, path, from, NULL);
  run_source(d, s, from);
  warn_if_empty(d, s);
}

char *deck_resolve_path(const YfArgs *a, const char *name) {
  char *dir = dir_of(a->loc.file);
  char *p = join_path(dir, name);
  /* LAMMPS reads a deck's files from the working directory: 'yfdem -in cases/a.deck' with
   * 'include common.deck' beside the working directory's common.deck said only "cannot open
   * 'cases/common.deck'" (a mesh, a table, a history file the same) */
  struct stat st;
  if (strcmp(p, name) && stat(p, &st) != 0 && errno == ENOENT && stat(name, &st) == 0)
    yf_io_error(&a->loc, "%s: cannot open '%s': %s (a deck's files are found from its own folder, '%s'; the working "
                "directory has a '%s', which LAMMPS would read: give its path from the deck's folder, or an absolute "
                "one)", a->cmd, p, strerror(ENOENT), dir, name);
  free(dir);
  return p;
}

/* ------------------------------------------------------------------ argument helpers */

/* Column of argument word i in a->line (-1 if it cannot be found); i == a->n: end of line. */
static int arg_col(const YfArgs *a, int i) {
  if (!a->line) return -1;
  if (i >= a->n) return (int)strlen(a->line);
  char **w;
  int *cols, errcol, col = -1;
  const char *why;
  int n = split_words(a->line, &w, &cols, &errcol, &why);
  if (n < 0) return -1;
  if (i >= 0 && i + 1 < n && !strcmp(w[i + 1], a->w[i])) col = cols[i + 1];
  free_words(w, cols, n);
  if (col < 0 && i >= 0) {
    const char *q = strstr(a->line, a->w[i]);
    if (q) col = (int)(q - a->line);
  }
  return col;
}

/* Column of the first character inside word i (after an opening quote). */
static int arg_inner_col(const YfArgs *a, int i) {
  int col = arg_col(a, i);
  if (col < 0) return col;
  if (!strncmp(a->line + col, "\"\"\"", 3)) return col + 3;
  if (a->line[col] == '"' || a->line[col] == '\'') return col + 1;
  return col;
}

static void arg_fail(const YfArgs *a, int i, const char *what, const char *fmt, ...)
    __attribute__((noreturn, format(printf, 4, 5)));
static void arg_fail(const YfArgs *a, int i, const char *what, const char *fmt, ...) {
  char msg[900];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(msg, sizeof msg, fmt, ap);
  va_end(ap);
  if (i >= 0 && i < a->n)
    fail_ctx(&a->loc, a->line, arg_col(a, i), "%s: %s%s'%s': %s", a->cmd, what ? what : "", what ? " " : "",
             a->w[i], msg);
  fail_ctx(&a->loc, a->line, arg_col(a, i), "%s: %s", a->cmd, msg);
}

void arg_error(const YfArgs *a, int i, const char *fmt, ...) {
  char msg[900];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(msg, sizeof msg, fmt, ap);
  va_end(ap);
  arg_fail(a, i, NULL, "%s", msg);
}

static const char *usage_of(const char *cmd) {
  const YfCommand *c = deck_find_command(cmd);
  return c && c->usage ? c->usage : NULL;
}

void arg_count(const YfArgs *a, int min, int max) {
  if (a->n >= min && (max < 0 || a->n <= max)) return;
  const char *u = usage_of(a->cmd);
  char want[64];
  if (max < 0) snprintf(want, sizeof want, "at least %d", min);
  else if (min == max) snprintf(want, sizeof want, "%d", min);
  else snprintf(want, sizeof want, "%d to %d", min, max);
  int col = a->n > max && max >= 0 ? arg_col(a, max) : (int)strlen(a->line ? a->line : "");
  fail_ctx(&a->loc, a->line, col, "%s: expected %s argument%s, got %d%s%s", a->cmd, want,
           (min == 1 && max == 1) ? "" : "s", a->n, u ? "\n  usage: " : "", u ? u : "");
}

const char *arg_word(const YfArgs *a, int i, const char *what) {
  if (i < a->n) return a->w[i];
  const char *u = usage_of(a->cmd);
  fail_ctx(&a->loc, a->line, a->line ? (int)strlen(a->line) : -1, "%s: missing %s%s%s", a->cmd, what,
           u ? "\n  usage: " : "", u ? u : "");
}

/* A name the scene stores (material, history, fix, load, jointprop, dump, record, region, group):
 * one that does not fit YF_NAME_MAX was cut short silently and then not found by its full name. */
const char *arg_name(const YfArgs *a, int i, const char *what) {
  const char *w = arg_word(a, i, what);
  if (strlen(w) >= YF_NAME_MAX) arg_error(a, i, "%s longer than %d characters", what, YF_NAME_MAX - 1);
  return w;
}

/* A hint when someone writes an expression where a plain number is expected. */
static const char *num_hint(const char *w) {
  if (w[0] && strpbrk(w + 1, "+-*/^()") && !strpbrk(w, "eE")) return " (write an expression as $(...))"; /* w may be "" */
  if (strpbrk(w, "*/^()")) return " (write an expression as $(...))";
  return "";
}

double arg_num(const YfArgs *a, int i, const char *what) {
  const char *w = arg_word(a, i, what);
  double v;
  if (!yf_parse_double(w, &v)) arg_fail(a, i, what, "not a finite number%s", num_hint(w));
  if (v == 0.0) { /* 1e-400 became 0 ("E must be > 0" of a positive number; thermo 1e-400 ran as 0) */
    size_t m = strcspn(w, "eE");
    if (strcspn(w, "123456789") < m)
      arg_fail(a, i, what, "underflows to 0 in doubles (the smallest is 4.9e-324): use other units");
  }
  return v;
}

double arg_coord(const YfArgs *a, int i, const char *what) {
  double v = arg_num(a, i, what);
  /* a point's distances to the nodes are squared: beyond the nodes' own range they overflowed
   * ('group g node nearest 1e200 0' found no node) */
  if (!(fabs(v) <= YF_RANGE_MAX))
    arg_fail(a, i, what, "%g m is beyond +-%g m, the range the arithmetic holds (nodes lie within it)", v, YF_RANGE_MAX);
  return v;
}

double arg_pos(const YfArgs *a, int i, const char *what) {
  double v = arg_num(a, i, what);
  if (!(v > 0)) arg_fail(a, i, what, "must be > 0");
  return v;
}

double arg_nonneg(const YfArgs *a, int i, const char *what) {
  double v = arg_num(a, i, what);
  if (!(v >= 0)) arg_fail(a, i, what, "must be >= 0");
  return v;
}

long arg_int(const YfArgs *a, int i, const char *what, long lo, long hi) {
  const char *w = arg_word(a, i, what);
  long v;
  if (!yf_parse_long(w, &v)) {
    double x;
    if (yf_parse_double(w, &x)) {
      /* 'run $(v_T/dt)' gave 1234.56, and 'variable i loop 99999999999999999999' or a count that
       * prints as 1e+16 is an integer: both were "not an integer", with no way out said */
      if (x != floor(x))
        arg_fail(a, i, what, "not an integer (round an expression: $(round(EXPR)), or $(EXPR:%%d))");
      int below = x < (double)lo && lo != LONG_MIN, above = x > (double)hi && hi != LONG_MAX;
      if (below || above) v = below ? lo - 1 : hi + 1; /* outside the range: its message, below */
      else
        arg_fail(a, i, what, "an integer beyond those read exactly (at most %ld written in digits, 2^53 = "
                 "9007199254740992 with an exponent or a '.')", LONG_MAX);
    } else
      arg_fail(a, i, what, "not an integer%s", num_hint(w));
  }
  if (v < lo || v > hi) {
    if (hi == LONG_MAX) arg_fail(a, i, what, "must be >= %ld", lo);
    if (lo == LONG_MIN) arg_fail(a, i, what, "must be <= %ld", hi);
    arg_fail(a, i, what, "must be in [%ld, %ld]", lo, hi);
  }
  return v;
}

int arg_choice(const YfArgs *a, int i, const char *what, const char *const *choices) {
  const char *w = arg_word(a, i, what);
  int n = 0;
  for (; choices[n]; n++)
    if (!strcmp(choices[n], w)) return n;
  char list[600];
  size_t k = 0;
  list[0] = 0;
  for (int j = 0; j < n && k < sizeof list; j++)
    k += (size_t)snprintf(list + k, sizeof list - k, "%s%s", j ? ", " : "", choices[j]);
  const char *near = strlen(w) >= 3 ? yf_nearest(w, choices, n) : NULL; /* the list says enough for short words */
  if (near) arg_fail(a, i, what, "expected one of %s (did you mean '%s'?)", list, near);
  arg_fail(a, i, what, "expected one of %s", list);
}

/* ------------------------------------------------------------------ builtin commands */

static YfDeck *deck_of(struct YfSim *sim, const YfArgs *a) {
  if (!sim || !sim->deck) fail_ctx(&a->loc, NULL, -1, "%s: no deck interpreter attached to the simulation", a->cmd);
  return sim->deck;
}

static char *join_words(const YfArgs *a, int from) {
  Buf b = {0};
  for (int i = from; i < a->n; i++) {
    if (i > from) buf_putc(&b, ' ');
    buf_put(&b, a->w[i]);
  }
  return buf_take(&b);
}

/* variable NAME equal EXPR | string TEXT | index V1 V2 ... | loop N | loop N1 N2 | delete */
void deck_cmd_variable(struct YfSim *sim, const YfArgs *a) {
  YfDeck *d = deck_of(sim, a);
  arg_count(a, 2, -1);
  const char *name = a->w[0];
  const char *why = name_fault(name);
  if (why) arg_fail(a, 0, "name", "%s", why);
  int style = arg_choice(a, 1, "style", var_styles);
  DeckVar *old = var_find(d, name);
  int known = 0;
  for (int i = 0; i < d->ndef && !known; i++) known = !strcmp(d->defnames[i], name);
  if (!known) {
    if (d->ndef == d->capdef) {
      d->capdef = d->capdef ? 2 * d->capdef : 16;
      d->defnames = yf_realloc(d->defnames, (size_t)d->capdef * sizeof *d->defnames, "variable names");
    }
    d->defnames[d->ndef++] = yf_strdup(name);
  }
  if (style == 4) { /* delete */
    arg_count(a, 2, 2);
    var_delete(d, name);
    for (int i = 0; i < d->ngone; i++) /* deleted by the deck now, not by a 'next' */
      if (!strcmp(d->gone[i], name)) {
        free(d->gone[i]);
        d->gone[i] = d->gone[--d->ngone];
        d->gone_at[i] = d->gone_at[d->ngone];
        break;
      }
    return;
  }
  if (old && old->cmdline) return; /* -var wins: the deck gives defaults */
  int looping = style == VAR_INDEX || style == VAR_LOOP;
  if (old && looping && (old->style == VAR_INDEX || old->style == VAR_LOOP))
    return; /* LAMMPS: redefining an index/loop variable is ignored (loops re-read definitions) */
  if (old && old->style != style)
    arg_fail(a, 0, "variable", "already defined as %s-style, cannot redefine as %s-style "
             "(use 'variable %s delete' first)", var_styles[old->style], var_styles[style], name);
  /* loop N [N2] pad: LAMMPS's zero-padded values (out_01 ... out_10 sort as files); 'pad' was read
   * as the last value ("not an integer") */
  int pad = style == VAR_LOOP && a->n >= 4 && !strcmp(a->w[a->n - 1], "pad");
  arg_count(a, 3, style == VAR_LOOP ? 4 + pad : -1);
  if (style == VAR_EQUAL) {
    char *text = join_words(a, 2);
    ExprError e;
    char ab[80];
    if (!expr_check(text, &e)) /* caret inside the line when the expression is one word */
      fail_ctx(&a->loc, a->line, a->n == 3 ? arg_inner_col(a, 2) + e.pos : arg_col(a, 2),
               "variable: expression '%s': %s", abbrev(text, ab, sizeof ab), e.msg);
    note_log(d, &e, &a->loc);
    DeckVar *v = var_new(d, name, VAR_EQUAL);
    v->text = text;
  } else if (style == VAR_STRING) {
    char *text = join_words(a, 2);
    DeckVar *v = var_new(d, name, VAR_STRING);
    v->text = text;
  } else if (style == VAR_INDEX) {
    int nv = a->n - 2;
    char **vals = yf_malloc((size_t)nv * sizeof *vals, "variable values");
    for (int i = 0; i < nv; i++) vals[i] = yf_strdup(a->w[2 + i]);
    DeckVar *v = var_new(d, name, VAR_INDEX);
    v->vals = vals;
    v->nvals = nv;
  } else {
    long lo = 1, hi;
    if (a->n - pad == 3) hi = arg_int(a, 2, "count", 1, LONG_MAX);
    else {
      lo = arg_int(a, 2, "first value", LONG_MIN / 2, LONG_MAX / 2);
      hi = arg_int(a, 3, "last value", lo, LONG_MAX / 2);
    }
    DeckVar *v = var_new(d, name, VAR_LOOP);
    v->cur = lo;
    v->hi = hi;
    if (pad) { /* as many digits as the last value has (LAMMPS) */
      char digits[32];
      v->pad = snprintf(digits, sizeof digits, "%ld", hi);
    }
  }
}

/* next NAME [NAME ...] */
void deck_cmd_next(struct YfSim *sim, const YfArgs *a) {
  YfDeck *d = deck_of(sim, a);
  arg_count(a, 1, -1);
  int done = 0;
  for (int i = 0; i < a->n; i++) {
    DeckVar *v = var_find(d, a->w[i]);
    if (!v) {
      char hint[300];
      unknown_hint(d, a->w[i], 0, hint, sizeof hint);
      arg_fail(a, i, "variable", "no such variable%s", hint);
    }
    if (v->style != VAR_INDEX && v->style != VAR_LOOP)
      arg_fail(a, i, "variable", "is %s-style; next needs an index or loop variable", var_styles[v->style]);
  }
  for (int i = 0; i < a->n; i++) {
    DeckVar *v = var_find(d, a->w[i]);
    if (v->style == VAR_INDEX) done |= ++v->which >= v->nvals;
    else done |= ++v->cur > v->hi;
  }
  if (done) { /* LAMMPS: all listed variables are deleted and the next jump is skipped */
    for (int i = 0; i < a->n; i++) {
      var_delete(d, a->w[i]);
      int k = 0;
      while (k < d->ngone && strcmp(d->gone[k], a->w[i])) k++;
      if (k == d->ngone) {
        d->gone = yf_realloc(d->gone, (size_t)(k + 1) * sizeof *d->gone, "deck variables");
        d->gone_at = yf_realloc(d->gone_at, (size_t)(k + 1) * sizeof *d->gone_at, "deck variables");
        d->gone[k] = yf_strdup(a->w[i]);
        d->ngone++;
      }
      d->gone_at[k] = a->loc; /* (its file name is interned: it outlives the line) */
    }
    d->jump_skip = 1;
  }
}

/* Index of the line after `label NAME` in s, or -1.  label NULL: none is found, and the names of
 * the labels there are go into list (for the message of a label that is not there).  A label is
 * matched as written: like LAMMPS, which substitutes no variable in the lines it skips looking
 * for a label (a variable there may not be defined yet), `label l${i}` is not 'l2'; *dollar
 * (when not NULL) is set when a label there holds a '$', for the message. */
static int find_label(DeckSource *s, const char *label, Buf *list, int *dollar) {
  for (int i = 0; i < s->n; i++) {
    const char *t = s->lines[i].text;
    if (strncmp(t, "label", 5) || !isspace((unsigned char)t[5])) continue;
    char **w;
    int *cols, errcol;
    const char *why;
    int n = split_words(t, &w, &cols, &errcol, &why);
    if (n < 0) continue;
    int hit = n >= 2 && label && !strcmp(w[1], label);
    if (n >= 2 && dollar && strchr(w[1], '$')) *dollar = 1;
    if (n >= 2 && list && list->n < 200) {
      if (list->n) buf_put(list, ", ");
      buf_put(list, w[1]);
    }
    free_words(w, cols, n);
    if (hit) return i + 1;
  }
  return -1;
}

/* jump SELF|FILE [LABEL] */
void deck_cmd_jump(struct YfSim *sim, const YfArgs *a) {
  YfDeck *d = deck_of(sim, a);
  arg_count(a, 1, 2);
  if (d->jump_skip) { /* a `next` ran out of values: this jump ends the loop */
    d->jump_skip = 0;
    return;
  }
  if (d->depth == 0) arg_fail(a, 0, "file", "jump is only possible while reading a deck file");
  DeckFrame *f = &d->stack[d->depth - 1];
  DeckSource *s = f->src;
  if (strcmp(a->w[0], "SELF")) {
    char *path = deck_resolve_path(a, a->w[0]);
    if (strcmp(path, s->name)) s = source_load(d, path, &a->loc, "jump");
    free(path);
  }
  int pos = 0;
  if (a->n == 2) {
    pos = find_label(s, a->w[1], NULL, NULL);
    if (pos < 0) { /* what is there: a misspelt label was named alone */
      Buf list = {0};
      int dollar = 0;
      find_label(s, NULL, &list, &dollar);
      arg_fail(a, 1, "label", "no 'label %s' in %s (%s%s%s)%s", a->w[1], s->name, list.n ? "its labels: " : "it has no label",
               list.n ? list.s : "", list.n >= 200 ? ", ..." : "",
               dollar ? "; labels are matched as written: as in LAMMPS, no variable is substituted in the lines "
                        "skipped looking for a label, so a label holding '$' is not its value: give each label a "
                        "fixed name (label l1, label l2, ...) and jump to l${i}"
                      : "");
    }
  }
  f->src = s;
  f->pos = pos;
}

/* label NAME */
void deck_cmd_label(struct YfSim *sim, const YfArgs *a) { arg_count(a, 1, 1); }

/* include FILE */
void deck_cmd_include(struct YfSim *sim, const YfArgs *a) {
  YfDeck *d = deck_of(sim, a);
  arg_count(a, 1, 1);
  char *path = deck_resolve_path(a, a->w[0]);
  DeckSource *s = source_load(d, path, &a->loc, "include");
  free(path);
  run_source(d, s, &a->loc);
}

/* Where print's keywords begin: the first word (after the text's first) from which on the words
 * are pairs 'file F', 'append F', 'screen yes|no', 'universe yes|no' to the end of the line, as
 * LAMMPS reads them; a->n when there are none (the words are all text, as before: 'print the file
 * is ready' stays text, its 'is ready' is no pair). */
static int print_keywords_from(const YfArgs *a) {
  for (int i = 1; i + 1 < a->n; i++) {
    if ((a->n - i) % 2) continue;
    int ok = 1;
    for (int k = i; k < a->n && ok; k += 2) {
      const char *kw = a->w[k], *v = a->w[k + 1];
      if (!strcmp(kw, "file") || !strcmp(kw, "append")) ok = v[0] != 0;
      else if (!strcmp(kw, "screen") || !strcmp(kw, "universe")) ok = !strcmp(v, "yes") || !strcmp(v, "no");
      else ok = 0;
    }
    if (ok) return i;
  }
  return a->n;
}

/* print TEXT ... [file F | append F] [screen yes|no] [universe yes|no]
 * A LAMMPS deck's 'print "${E} $(uy_tip)" append results.txt screen no' printed its keywords on the
 * screen and wrote no file: the results of a sweep were lost.  As in LAMMPS, 'file' writes the
 * file anew at each print, 'append' adds a line to it, and 'screen no' keeps the text off the
 * screen and the log.  The file is relative to the working directory, as every output is. */
void deck_cmd_print(struct YfSim *sim, const YfArgs *a) {
  arg_count(a, 1, -1);
  int kw = print_keywords_from(a), screen = 1, fi = -1;
  for (int k = kw; k < a->n; k += 2) {
    if (!strcmp(a->w[k], "screen")) screen = !strcmp(a->w[k + 1], "yes");
    else if (!strcmp(a->w[k], "file") || !strcmp(a->w[k], "append")) {
      if (fi >= 0) arg_error(a, k, "a print writes one file, and '%s %s' names a second", a->w[fi], a->w[fi + 1]);
      fi = k;
    }
  }
  Buf b = {0};
  for (int i = 0; i < kw; i++) {
    if (i) buf_putc(&b, ' ');
    buf_put(&b, a->w[i]);
  }
  char *text = buf_take(&b);
  if (fi >= 0 && sim) { /* a dump or a log on the same file would interleave with it (every rank claims) */
    const char *by = output_claim(sim, "print", a->w[fi + 1], NULL, 0);
    if (by && strcmp(by, "print")) arg_error(a, fi + 1, "already written by %s", by);
  }
  if (fi >= 0 && yf_writer()) { /* (first: a file that cannot be written stops before the screen shows the line) */
    const char *path = a->w[fi + 1];
    FILE *fp = fopen(path, a->w[fi][0] == 'a' ? "a" : "w");
    if (!fp) yf_io_error(&a->loc, "print: cannot write '%s': %s", path, strerror(errno));
    int bad = fprintf(fp, "%s\n", text) < 0;
    int e = errno;
    if (fclose(fp) != 0 || bad)
      yf_io_error(&a->loc, "print: cannot write '%s': %s", path, strerror(bad ? e : errno));
  }
  if (screen) {
    if (sim) sim_printf(sim, "%s\n", text);
    else printf("%s\n", text);
  }
  free(text);
}

/* Truth of an if condition.  Besides numeric expressions, "WORD == WORD" and "WORD != WORD"
 * compare strings (LAMMPS allows "${mode} == fast"): when the expression fails only because a
 * bare word of it names nothing, and neither side is a number.  Any other failure is the deck's
 * error: a division by zero, a misspelt v_NAME or a misspelt name compared with a number
 * ("nbrokn == 0") were compared as text, silently false (or true with !=). */
static int condition(YfDeck *d, const YfArgs *a, int i) {
  const char *cond = a->w[i];
  double v, num;
  ExprError e;
  d->unknown_bare = 0;
  if (eval_quiet(d, cond, &v, &e)) return v != 0.0;
  char l[256], op[8], r[256], extra[2];
  if (d->unknown_bare && sscanf(cond, "%255s %7s %255s %1s", l, op, r, extra) == 3 &&
      (!strcmp(op, "==") || !strcmp(op, "!=")) && !yf_parse_double(l, &num) && !yf_parse_double(r, &num)) {
    int eq = !strcmp(l, r);
    return op[0] == '=' ? eq : !eq;
  }
  int col = arg_inner_col(a, i);
  fail_ctx(&a->loc, a->line, col < 0 ? -1 : col + e.pos, "if: condition '%s': %s", cond, e.msg);
}

/* if COND then CMD ... [elif COND [then] CMD ...] [else CMD ...]
 * Conditions are evaluated in order until one is true (later ones are not evaluated). */
void deck_cmd_if(struct YfSim *sim, const YfArgs *a) {
  YfDeck *d = deck_of(sim, a);
  arg_count(a, 2, -1);
  if (strcmp(a->w[1], "then"))
    arg_fail(a, 1, NULL, "expected 'then' after the condition%s",
             a->n > 2 && strchr("<>=!&|", a->w[1][0]) ? " (quote the condition: if \"a > b\" then ...)" : "");
  int i = 2, from = -1, to = -1;
  int start = i;
  while (i < a->n && strcmp(a->w[i], "elif") && strcmp(a->w[i], "else")) i++;
  /* a branch with no command did nothing without a word */
  if (i == start) arg_fail(a, i, NULL, "no command after 'then'");
  if (condition(d, a, 0)) from = start, to = i;
  while (i < a->n) {
    if (!strcmp(a->w[i], "else")) {
      for (int j = i + 1; j < a->n; j++)
        if (!strcmp(a->w[j], "elif") || !strcmp(a->w[j], "else"))
          arg_fail(a, j, NULL, "the 'else' branch must come last");
      if (i + 1 == a->n) arg_fail(a, a->n, NULL, "no command after 'else'");
      if (from < 0) from = i + 1, to = a->n;
      break;
    }
    /* elif COND [then] CMD ... */
    if (i + 1 >= a->n) arg_fail(a, a->n, NULL, "missing condition after 'elif'");
    int ci = i + 1;
    i += 2;
    if (i < a->n && !strcmp(a->w[i], "then")) i++;
    start = i;
    while (i < a->n && strcmp(a->w[i], "elif") && strcmp(a->w[i], "else")) i++;
    if (i == start) arg_fail(a, i, NULL, "no command after the 'elif' condition");
    if (from < 0 && condition(d, a, ci)) from = start, to = i;
  }
  /* each command is one (quoted) word: `if c then print big` would run `print` and `big` */
  for (int k = from; k >= 0 && k + 1 < to; k++) {
    char first[64];
    if (strpbrk(a->w[k], " \t") || !deck_find_command(a->w[k])) continue;
    if (sscanf(a->w[k + 1], "%63s", first) == 1 && deck_find_command(first)) continue;
    arg_fail(a, k, NULL, "each command of an if branch is one quoted word: write if COND then \"%s %s ...\" "
             "('%s' is not a command)", a->w[k], a->w[k + 1], a->w[k + 1]);
  }
  for (int k = from; k >= 0 && k < to && !d->quit; k++) exec_line(d, a->w[k], &a->loc);
}

/* echo on|off */
void deck_cmd_echo(struct YfSim *sim, const YfArgs *a) {
  static const char *const onoff[] = {"off", "on", NULL};
  YfDeck *d = deck_of(sim, a);
  arg_count(a, 1, 1);
  d->echo = arg_choice(a, 0, "setting", onoff);
}

/* quit */
void deck_cmd_quit(struct YfSim *sim, const YfArgs *a) {
  YfDeck *d = deck_of(sim, a);
  arg_count(a, 0, 0);
  d->quit = 1;
}

void arg_claim(struct YfSim *s, const YfArgs *a, int i, const char *owner, const char *prefix, const char *suffix,
               int numbered) {
  const char *by = output_claim(s, owner, prefix, suffix, numbered);
  if (!by) return;
  if (numbered) arg_error(a, i, "its files %sNNNNNN%s are already written by %s", prefix, suffix ? suffix : "", by);
  arg_error(a, i, "already written by %s", by);
}

void arg_regular(const YfArgs *a, int i, const char *path) {
  struct stat st;
  /* what is in the way on the disk is an I/O error (exit 2), as a folder in the way of every other
   * output is (it was a deck error, exit 1, and a folder at FILE.a of 'restart every' exit 2) */
  if (!stat(path, &st) && !S_ISREG(st.st_mode))
    yf_io_error(&a->loc, "%s: '%s': '%s' is not a regular file: a restart is written whole to a temporary file and "
                "renamed over it, which would replace it (write_restart onto a device replaced the device)", a->cmd,
                a->w[i], path);
}

/* The files were hidden or named by their endings alone: `dump d h5 10 .` wrote ._000000.h5 and
 * ..xmf, `dump d csv 10 /tmp/` /tmp/_000000.csv.  A folder of the stem's name is no reason: its
 * files go beside it (out_000000.h5 beside a y2dref dump's folder out/, the README's example;
 * refusing that made a deck fail on its second run). */
void arg_file_stem(const YfArgs *a, int i, const char *stem, const char *made) {
  const char *slash = strrchr(stem, '/'), *last = slash ? slash + 1 : stem;
  const char *word = a->w[i];
  size_t wl = strlen(word);
  char why[160];
  if (!*last && wl && word[wl - 1] == '/')
    snprintf(why, sizeof why, "it ends in '/'");
  else if (!*last)
    snprintf(why, sizeof why, "there is nothing before the extension");
  else if (!strcmp(last, ".") || !strcmp(last, ".."))
    snprintf(why, sizeof why, "'%s' is a directory", stem);
  else
    return;
  /* the suggestion: a name inside the folder meant */
  arg_error(a, i, "no file name: %s, and its files would be named like '%s'; give one, as in '%s%sout'", why, made,
            stem, *last ? "/" : "");
}

void arg_writable(const YfArgs *a, const char *what, const char *fmt, ...) {
  char path[4096];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(path, sizeof path, fmt, ap);
  va_end(ap);
  if (yf_can_create(path)) return;
  int e = errno;
  /* the file is written as PATH.tmp first: what is in the way may be that, not PATH (a folder
   * out.xmf.tmp was reported as "cannot write 'out.xmf': Is a directory", with no out.xmf there) */
  struct stat st;
  char tmp[4200];
  snprintf(tmp, sizeof tmp, "%s.tmp", path);
  if (lstat(path, &st) != 0 && lstat(tmp, &st) == 0)
    yf_io_error(&a->loc, "%s: cannot write '%s': '%s', where it is written before it is renamed, is in the way: %s",
                what, path, tmp, strerror(e));
  yf_io_error(&a->loc, "%s: cannot write '%s': %s", what, path, strerror(e));
}
