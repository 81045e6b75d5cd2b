/* expr.h: the arithmetic/logical expression evaluator behind `variable NAME equal`, $(...) and
 * `if` conditions (private to deck.c; the public entry is deck_eval in deck.h).
 *
 * Grammar, lowest precedence first (C-like, except that '^' binds tighter than unary minus, as in
 * mathematics: -2^2 = -4, and '^' is right-associative: 2^3^2 = 2^9 = 512.  LAMMPS evaluates
 * both differently; we follow the mathematical convention and say so in the manual):
 *
 *   or    -> and ('||' and)*
 *   and   -> eq ('&&' eq)*                 (both '&&' and '||' short-circuit)
 *   eq    -> rel (('=='|'!=') rel)*
 *   rel   -> add (('<'|'<='|'>'|'>=') add)*
 *   add   -> mul (('+'|'-') mul)*
 *   mul   -> unary (('*'|'/'|'%') unary)*
 *   unary -> ('-'|'+'|'!') unary | power
 *   power -> primary ('^' unary)?
 *   primary -> NUMBER | NAME | NAME '(' or (',' or)* ')' | '(' or ')'
 *
 * Comparisons and logical operators give 1 or 0.  Names are resolved through a callback (the deck's
 * variables, step/time/dt); `v_name` is the LAMMPS spelling of the variable `name`; pi and PI are
 * constants; ln() is log(), the natural logarithm (LAMMPS's spelling; its log() is base 10).
 * Every intermediate result must be finite: division by zero, sqrt of a negative,
 * log of a non-positive number or an overflow is an error, reported with the character position.
 */
#ifndef YF_EXPR_H
#define YF_EXPR_H
#include <stddef.h>

/* The longest name an expression reads (127 characters, a buffer of 128 with its NUL): a variable
 * name must leave room for the "v_" of the LAMMPS spelling, so deck.c refuses longer ones where
 * they are defined (they worked in ${NAME} and failed only in $(v_NAME)). */
#define EXPR_NAME_MAX 128
#define EXPR_VAR_NAME_MAX (EXPR_NAME_MAX - 1 - 2)

typedef struct {
  char msg[512]; /* what went wrong, e.g. "missing ')'"             */
  int pos;       /* 0-based character offset in the expression text */
  int uses_log;  /* set on success too: the expression calls log(), which LAMMPS reads as base 10
                  * (here, as in C and Python, the natural one; ln() is that too) */
} ExprError;

/* Name lookup: return 1 and set *val if name is known, 0 if unknown, -1 on an error while
 * evaluating it (then write the reason into err).  name is as written: a LAMMPS-style v_X is
 * passed whole, so the lookup can tell "the variable X" from a bare X. */
typedef int (*ExprLookupFn)(void *ctx, const char *name, double *val, char *err, size_t errlen);

/* Evaluate s.  Returns 1 and sets *out on success; 0 and fills *e on failure. */
int expr_eval(const char *s, ExprLookupFn lookup, void *ctx, double *out, ExprError *e);
/* Syntax check only (names are not looked up, domain errors are not raised). */
int expr_check(const char *s, ExprError *e);

#endif
