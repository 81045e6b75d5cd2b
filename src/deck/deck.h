/* deck.h: the LAMMPS/YADE-style deck interpreter.
 *
 * deck.c owns reading deck text: lines, '#' comments, '&' continuation, quoted words, variables
 * (${name}, $x, $(expr)), include, label/jump loops, if/then/else, print.  It splits each command
 * into words, remembers where each came from (file and line) and dispatches through the command
 * table of commands.def.  Handlers receive a YfArgs and use the arg_* helpers below, which refuse
 * junk ("3.0x", missing words) with a FILE:LINE message naming the word at fault.
 */
#ifndef YF_DECK_H
#define YF_DECK_H
#include <stdio.h>
#include "err.h"
#include "strictnum.h" /* yf_parse_double, yf_parse_long: the deck's number rules */

struct YfSim;

typedef struct {
  const char *cmd; /* command name (word 0)                                */
  int n;           /* number of argument words after the command name      */
  char **w;        /* the argument words, substituted, quotes removed      */
  YfLoc loc;       /* file and line where the command starts               */
  const char *line;/* the command's text after substitution (for messages) */
} YfArgs;

typedef void (*YfCmdFn)(struct YfSim *sim, const YfArgs *a);

typedef struct {
  const char *name;
  YfCmdFn fn;
  const char *usage;   /* "fix ID GROUP fixed x|y|xy"                   */
  const char *help;    /* one sentence                                  */
  const char *example; /* a complete example line                       */
} YfCommand;

/* The table generated from commands.def, terminated by a {NULL} row. */
extern const YfCommand yf_commands[];
const YfCommand *deck_find_command(const char *name);
/* The command name nearest to a misspelt word (NULL: none close enough), for "did you mean". */
const char *deck_nearest_command(const char *word);

/* Interpreter. */
typedef struct YfDeck YfDeck;
YfDeck *deck_new(struct YfSim *sim);
void deck_free(YfDeck *d);
/* Define a variable before reading (the -var NAME VALUE option): a string value. */
void deck_set_var(YfDeck *d, const char *name, const char *value);
/* Run a whole deck from an open stream; fname is used in messages and for relative includes. */
void deck_run_stream(YfDeck *d, FILE *fp, const char *fname);
/* Run one deck file (path relative to cwd). I/O error if it cannot be opened. */
void deck_run_file(YfDeck *d, const char *path, const YfLoc *from);
/* Echo each command to stdout (the -echo option). */
void deck_set_echo(YfDeck *d, int on);
/* Directory of the deck currently being read ("." for stdin): handlers resolve relative
 * file names (mesh files, tables) against it.  Returns a malloc'd path joined with name,
 * or a copy of name when name is absolute.  An I/O error when the joined path does not exist
 * but name does from the working directory (where a LAMMPS user expects it). */
char *deck_resolve_path(const YfArgs *a, const char *name);
/* Evaluate an arithmetic expression with the current variables (used by 'variable' and $()). */
double deck_eval(YfDeck *d, const char *expr, const YfLoc *loc);
/* The same, its error message starting with what (e.g. "thermo_style column at step 50: "): an
 * expression evaluated during a run, whose failure the deck line alone does not place. */
double deck_eval_as(YfDeck *d, const char *expr, const YfLoc *loc, const char *what);

/* ---- argument helpers for command handlers (all exit with a deck error on bad input) ---- */
/* Require min <= a->n <= max (max < 0: unbounded); message shows the usage line. */
void arg_count(const YfArgs *a, int min, int max);
/* Strict number: whole word must be a finite number ("3.0x", "nan", "inf", "" are errors). */
double arg_num(const YfArgs *a, int i, const char *what);
/* arg_num of a point's coordinate [m], within +-YF_RANGE_MAX (where nodes lie). */
double arg_coord(const YfArgs *a, int i, const char *what);
/* Number that must be > 0 / >= 0. */
double arg_pos(const YfArgs *a, int i, const char *what);
double arg_nonneg(const YfArgs *a, int i, const char *what);
/* Strict integer (no fraction, no exponent overflow) in [lo, hi]. */
long arg_int(const YfArgs *a, int i, const char *what, long lo, long hi);
/* Word i must be one of choices (NULL-terminated); returns its index.  The message lists them. */
int arg_choice(const YfArgs *a, int i, const char *what, const char *const *choices);
/* Word i (exists, else usage error). */
const char *arg_word(const YfArgs *a, int i, const char *what);
/* arg_word for a name the scene keeps: refused when longer than YF_NAME_MAX - 1 characters */
const char *arg_name(const YfArgs *a, int i, const char *what);
/* Error naming word i: "FILE:LINE: error: CMD: WHAT 'word': message". */
void arg_error(const YfArgs *a, int i, const char *fmt, ...) __attribute__((noreturn, format(printf, 3, 4)));
/* An output the command will write, checked at its deck line (a missing folder is an error here,
 * not at the run after other outputs began): the path from fmt; what names it in the message
 * ("dump d", "restart every"). */
void arg_writable(const YfArgs *a, const char *what, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
/* Claim for owner ("record r1") the file prefix, or the numbered files prefix NNNNNN suffix, that
 * an output will write (output_claim); a file another output writes is an error at word i. */
/* Deck error at word i when path exists and is not a regular file (a directory, a device, a pipe):
 * for outputs written whole to PATH.tmp and renamed (restarts). */
void arg_regular(const YfArgs *a, int i, const char *path);
/* Deck error at word i when stem, the start of the names of files an output makes by adding its
 * endings (a dump's PREFIX or FILE.h5 without its extension, restart every's FILE), names no file:
 * it ends in '/' (or is only an extension), its last part is '.' or '..', or it is a directory.
 * made: the first file it would write, for the message. */
void arg_file_stem(const YfArgs *a, int i, const char *stem, const char *made);
void arg_claim(struct YfSim *s, const YfArgs *a, int i, const char *owner, const char *prefix, const char *suffix,
               int numbered);



#endif
