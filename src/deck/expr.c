/* expr.c: recursive-descent evaluator for deck expressions (grammar and conventions in expr.h).
 *
 * The parser evaluates while it reads (no syntax tree): deck expressions are short and evaluated
 * rarely (once per reference, never inside a time step), so simplicity wins.  Short-circuit
 * operators and the syntax-only check parse their operand in "skip" mode, in which names are not
 * looked up and domain errors are not raised, so `x != 0 && 1/x > 2` is safe.  Errors unwind with
 * longjmp to expr_eval, which reports the message and the character position.
 */
#include <ctype.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "expr.h"
#include "utf8name.h"

#define EXPR_MAX_ARGS 16
/* Nesting of parentheses, function calls, unary signs and '^' exponents: each level is a few
 * stack frames of this recursive parser, so an absurd nesting (a 40 KB line of '(' or '-') would
 * overflow the stack.  The count is shared by expressions evaluated inside others (equal-style
 * variables referring to each other), so the total stays bounded too. */
#define EXPR_DEPTH_MAX 256
static int expr_depth; /* levels open across every expression being evaluated now */

typedef struct {
  const char *s;  /* whole expression        */
  const char *p;  /* read position           */
  int skip;       /* > 0: evaluate nothing that can fail (short-circuit, syntax check) */
  int open;       /* parentheses opened and not yet closed (for "missing ')'") */
  int depth0;     /* expr_depth when this expression started (restored on an error) */
  ExprLookupFn lookup;
  void *ctx;
  ExprError *e;
  jmp_buf jb;
} Parser;

static void fail_at(Parser *P, const char *at, const char *fmt, ...) __attribute__((noreturn, format(printf, 3, 4)));
static void fail_at(Parser *P, const char *at, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(P->e->msg, sizeof P->e->msg, fmt, ap);
  va_end(ap);
  P->e->pos = (int)(at - P->s);
  longjmp(P->jb, 1);
}

static void skip_ws(Parser *P) {
  while (*P->p && isspace((unsigned char)*P->p)) P->p++;
}

/* Describe the token at p for messages: "'x'" or "end of expression".  A character beyond ASCII
 * is written whole (its first byte alone printed a broken character), with its code and, for
 * the ones a word processor puts in place of ASCII ones (utf8name.h's table), what to write instead. */
static void describe(const char *p, char *buf, size_t n) {
  if (!*p) {
    snprintf(buf, n, "end of expression");
    return;
  }
  unsigned cp;
  int len = yf_utf8_decode(p, &cp);
  if (len == 1) {
    snprintf(buf, n, "'%c'", *p);
    return;
  }
  if (!len) {
    snprintf(buf, n, "byte 0x%02X (not UTF-8 text)", cp);
    return;
  }
  YfLookalike l;
  char use[64] = "expressions are ASCII";
  if (yf_lookalike(cp, &l)) snprintf(use, sizeof use, *l.ascii ? "%s: write %s" : "%s: delete it", l.name, l.ascii);
  snprintf(buf, n, "'%.*s' (U+%04X, %s)", len, p, cp, use);
}

/* A result must be finite unless we are skipping. */
static double chk(Parser *P, const char *at, double v, const char *what) {
  if (!P->skip && !isfinite(v)) fail_at(P, at, "%s gives a non-finite result", what);
  return v;
}

static double parse_or(Parser *P);
static double parse_unary(Parser *P);

static double parse_number(Parser *P) {
  const char *q = P->p;
  while (isdigit((unsigned char)*q)) q++;
  if (*q == '.') {
    q++;
    while (isdigit((unsigned char)*q)) q++;
  }
  if (q == P->p + 1 && *P->p == '.') fail_at(P, P->p, "'.' is not a number");
  if (*q == 'e' || *q == 'E') {
    const char *r = q + 1;
    if (*r == '+' || *r == '-') r++;
    if (!isdigit((unsigned char)*r)) fail_at(P, q, "bad exponent in number");
    while (isdigit((unsigned char)*r)) r++;
    q = r;
  }
  if (isalpha((unsigned char)*q) || *q == '_') fail_at(P, q, "unexpected '%c' after number", *q);
  if ((unsigned char)*q >= 0x80) {
    char d[160];
    describe(q, d, sizeof d);
    fail_at(P, q, "unexpected %s after number", d);
  }
  char buf[128];
  size_t len = (size_t)(q - P->p);
  if (len >= sizeof buf) fail_at(P, P->p, "number too long");
  memcpy(buf, P->p, len);
  buf[len] = 0;
  double v = strtod(buf, NULL);
  if (!isfinite(v)) fail_at(P, P->p, "number '%s' overflows", buf);
  P->p = q;
  return v;
}

static double call_function(Parser *P, const char *name, const char *at, double *x, int n) {
  /* name, arity (-2: two or more), implementation selected below */
  static const struct { const char *name; int nargs; } fns[] = {
      {"sqrt", 1}, {"sin", 1},   {"cos", 1},  {"tan", 1},   {"asin", 1}, {"acos", 1},
      {"atan", 1}, {"atan2", 2}, {"exp", 1},  {"log", 1},   {"log10", 1}, {"ln", 1}, {"abs", 1},
      {"floor", 1}, {"ceil", 1}, {"round", 1}, {"min", -2}, {"max", -2}, {"pow", 2}, {NULL, 0}};
  int k;
  for (k = 0; fns[k].name; k++)
    if (!strcmp(fns[k].name, name)) break;
  if (!fns[k].name)
    fail_at(P, at, "unknown function '%s' (functions: sqrt sin cos tan asin acos atan atan2 exp log "
                   "log10 ln abs floor ceil round min max pow)", name);
  if (fns[k].nargs == -2 && n < 2) fail_at(P, at, "%s() takes at least 2 arguments, got %d", name, n);
  if (fns[k].nargs > 0 && n != fns[k].nargs)
    fail_at(P, at, "%s() takes %d argument%s, got %d", name, fns[k].nargs, fns[k].nargs > 1 ? "s" : "", n);
  if (!strcmp(name, "log")) P->e->uses_log = 1; /* (in a syntax check too: a variable's definition) */
  if (P->skip) return 0.0;
  double a = x[0], r = 0.0;
  if (!strcmp(name, "sqrt")) {
    if (a < 0) fail_at(P, at, "sqrt of negative number %.15g", a);
    r = sqrt(a);
  } else if (!strcmp(name, "sin")) r = sin(a);
  else if (!strcmp(name, "cos")) r = cos(a);
  else if (!strcmp(name, "tan")) r = tan(a);
  else if (!strcmp(name, "asin") || !strcmp(name, "acos")) {
    if (a < -1 || a > 1) fail_at(P, at, "%s of %.15g (outside [-1, 1])", name, a);
    r = name[1] == 's' ? asin(a) : acos(a);
  } else if (!strcmp(name, "atan")) r = atan(a);
  else if (!strcmp(name, "atan2")) r = atan2(a, x[1]);
  else if (!strcmp(name, "exp")) r = exp(a);
  else if (!strcmp(name, "log") || !strcmp(name, "log10") || !strcmp(name, "ln")) {
    if (a <= 0) fail_at(P, at, "%s of non-positive number %.15g", name, a);
    r = !strcmp(name, "log10") ? log10(a) : log(a);
  } else if (!strcmp(name, "abs")) r = fabs(a);
  else if (!strcmp(name, "floor")) r = floor(a);
  else if (!strcmp(name, "ceil")) r = ceil(a);
  else if (!strcmp(name, "round")) r = round(a);
  else if (!strcmp(name, "min") || !strcmp(name, "max")) {
    r = a;
    for (int i = 1; i < n; i++) r = name[1] == 'i' ? fmin(r, x[i]) : fmax(r, x[i]);
  } else if (!strcmp(name, "pow")) {
    if (a < 0 && x[1] != floor(x[1])) fail_at(P, at, "pow of negative base %.15g with non-integer exponent", a);
    if (a == 0 && x[1] < 0) fail_at(P, at, "pow: division by zero (0 to a negative power)");
    r = pow(a, x[1]);
  }
  return chk(P, at, r, name);
}

static double parse_name(Parser *P) {
  const char *at = P->p;
  char name[EXPR_NAME_MAX];
  size_t len = 0;
  while (isalnum((unsigned char)*P->p) || *P->p == '_') {
    if (len + 1 >= sizeof name) fail_at(P, at, "name longer than %d characters", EXPR_NAME_MAX - 1);
    name[len++] = *P->p++;
  }
  name[len] = 0;
  skip_ws(P);
  if (*P->p == '(') { /* function call */
    P->p++;
    P->open++;
    double x[EXPR_MAX_ARGS];
    int n = 0;
    skip_ws(P);
    if (*P->p != ')') {
      for (;;) {
        if (n == EXPR_MAX_ARGS) fail_at(P, P->p, "too many arguments to %s()", name);
        x[n++] = parse_or(P);
        skip_ws(P);
        if (*P->p == ',') { P->p++; continue; }
        if (*P->p == ')') break;
        if (!*P->p) fail_at(P, P->p, "missing ')' after the arguments of %s()", name);
        fail_at(P, P->p, "missing ')' after the arguments of %s() (found '%c')", name, *P->p);
      }
    }
    P->p++; /* ')' */
    P->open--;
    return call_function(P, name, at, x, n);
  }
  const char *var = name;
  if (!strncmp(name, "v_", 2) && name[2]) var = name + 2; /* LAMMPS spelling */
  if (P->skip) return 0.0;
  double v = 0.0;
  char err[sizeof P->e->msg - 64];
  err[0] = 0;
  int r = P->lookup ? P->lookup(P->ctx, name, &v, err, sizeof err) : 0; /* as written: v_X or X */
  if (r > 0) return chk(P, at, v, var);
  if (r < 0) fail_at(P, at, "%s", err);
  if (var == name && (!strcmp(name, "pi") || !strcmp(name, "PI"))) return M_PI;
  fail_at(P, at, "unknown variable '%s'", var);
}

/* primary -> NUMBER | NAME | NAME '(' args ')' | '(' or ')' */
static double parse_primary(Parser *P) {
  skip_ws(P);
  const char *at = P->p;
  if (isdigit((unsigned char)*P->p) || *P->p == '.') return parse_number(P);
  if (isalpha((unsigned char)*P->p) || *P->p == '_') return parse_name(P);
  if (*P->p == '(') {
    P->p++;
    P->open++;
    double v = parse_or(P);
    P->open--;
    skip_ws(P);
    if (*P->p != ')') {
      if (*P->p) fail_at(P, P->p, "missing ')' (found '%c')", *P->p);
      fail_at(P, P->p, "missing ')'");
    }
    P->p++;
    return v;
  }
  if (!*at && P->open > 0) fail_at(P, at, "missing ')'");
  if (!*at) fail_at(P, at, "missing operand at the end");
  char d[160];
  describe(at, d, sizeof d);
  fail_at(P, at, "expected a number, a name or '(' but found %s", d);
}

/* power -> primary ('^' unary)?   right-associative, exponent may carry a sign: 2^-1 */
static double parse_power(Parser *P) {
  double a = parse_primary(P);
  skip_ws(P);
  if (*P->p == '^') {
    const char *at = P->p++;
    double b = parse_unary(P);
    if (P->skip) return 0.0;
    if (a < 0 && b != floor(b)) fail_at(P, at, "negative base %.15g to non-integer power %.15g", a, b);
    if (a == 0 && b < 0) fail_at(P, at, "division by zero (0 to a negative power)");
    return chk(P, at, pow(a, b), "'^'");
  }
  return a;
}

/* unary -> ('-'|'+'|'!') unary | power.  Every recursion of the grammar passes here, so this is
 * where the nesting is counted. */
static double parse_unary_in(Parser *P) {
  skip_ws(P);
  if (*P->p == '-') { P->p++; return -parse_unary(P); }
  if (*P->p == '+') { P->p++; return parse_unary(P); }
  if (*P->p == '!' && P->p[1] != '=') { P->p++; return parse_unary(P) == 0.0 ? 1.0 : 0.0; }
  return parse_power(P);
}
static double parse_unary(Parser *P) {
  if (expr_depth >= EXPR_DEPTH_MAX)
    fail_at(P, P->p, "nested deeper than %d levels (parentheses, function calls, signs, '^'; "
                     "variables evaluated inside count too)", EXPR_DEPTH_MAX);
  expr_depth++;
  double v = parse_unary_in(P);
  expr_depth--;
  return v;
}

/* mul -> unary (('*'|'/'|'%') unary)* */
static double parse_mul(Parser *P) {
  double a = parse_unary(P);
  for (;;) {
    skip_ws(P);
    char op = *P->p;
    if (op != '*' && op != '/' && op != '%') return a;
    const char *at = P->p++;
    double b = parse_unary(P);
    if (P->skip) continue;
    if (op == '*') a = chk(P, at, a * b, "'*'");
    else {
      if (b == 0.0) fail_at(P, at, "division by zero");
      a = chk(P, at, op == '/' ? a / b : fmod(a, b), op == '/' ? "'/'" : "'%'");
    }
  }
}

/* add -> mul (('+'|'-') mul)* */
static double parse_add(Parser *P) {
  double a = parse_mul(P);
  for (;;) {
    skip_ws(P);
    char op = *P->p;
    if (op != '+' && op != '-') return a;
    const char *at = P->p++;
    double b = parse_mul(P);
    a = chk(P, at, op == '+' ? a + b : a - b, op == '+' ? "'+'" : "'-'");
  }
}

/* rel -> add (('<'|'<='|'>'|'>=') add)* */
static double parse_rel(Parser *P) {
  double a = parse_add(P);
  for (;;) {
    skip_ws(P);
    char op = *P->p;
    if (op != '<' && op != '>') return a;
    int eq = P->p[1] == '=';
    P->p += eq ? 2 : 1;
    double b = parse_add(P);
    if (op == '<') a = eq ? a <= b : a < b;
    else a = eq ? a >= b : a > b;
  }
}

/* eq -> rel (('=='|'!=') rel)* */
static double parse_eq(Parser *P) {
  double a = parse_rel(P);
  for (;;) {
    skip_ws(P);
    if ((P->p[0] != '=' && P->p[0] != '!') || P->p[1] != '=') {
      if (P->p[0] == '=' ) fail_at(P, P->p, "'=' is not an operator (use '==' to compare)");
      return a;
    }
    int ne = P->p[0] == '!';
    P->p += 2;
    double b = parse_rel(P);
    a = ne ? a != b : a == b;
  }
}

/* and -> eq ('&&' eq)* */
static double parse_and(Parser *P) {
  double a = parse_eq(P);
  for (;;) {
    skip_ws(P);
    if (P->p[0] != '&' || P->p[1] != '&') {
      if (P->p[0] == '&') fail_at(P, P->p, "'&' is not an operator (use '&&')");
      return a;
    }
    P->p += 2;
    int shortcut = a == 0.0;
    P->skip += shortcut;
    double b = parse_eq(P);
    P->skip -= shortcut;
    a = (a != 0.0 && b != 0.0) ? 1.0 : 0.0;
  }
}

/* or -> and ('||' and)* */
static double parse_or(Parser *P) {
  double a = parse_and(P);
  for (;;) {
    skip_ws(P);
    if (P->p[0] != '|' || P->p[1] != '|') {
      if (P->p[0] == '|') fail_at(P, P->p, "'|' is not an operator (use '||')");
      return a;
    }
    P->p += 2;
    int shortcut = a != 0.0;
    P->skip += shortcut;
    double b = parse_and(P);
    P->skip -= shortcut;
    a = (a != 0.0 || b != 0.0) ? 1.0 : 0.0;
  }
}

static int run(const char *s, ExprLookupFn lookup, void *ctx, int skip, double *out, ExprError *e) {
  Parser P;
  memset(&P, 0, sizeof P);
  P.s = P.p = s;
  P.skip = skip;
  P.lookup = lookup;
  P.ctx = ctx;
  P.e = e;
  e->msg[0] = 0;
  e->pos = 0;
  e->uses_log = 0;
  P.depth0 = expr_depth;
  if (setjmp(P.jb)) {
    expr_depth = P.depth0; /* the levels the longjmp skipped */
    return 0;
  }
  skip_ws(&P);
  if (!*P.p) fail_at(&P, P.p, "empty expression");
  double v = parse_or(&P);
  skip_ws(&P);
  if (*P.p) {
    if (*P.p == ')') fail_at(&P, P.p, "unmatched ')'");
    char d[160];
    describe(P.p, d, sizeof d);
    fail_at(&P, P.p, "unexpected %s", d);
  }
  if (out) *out = v == 0.0 ? 0.0 : v; /* no "-0" in printed results */
  return 1;
}

int expr_eval(const char *s, ExprLookupFn lookup, void *ctx, double *out, ExprError *e) {
  return run(s, lookup, ctx, 0, out, e);
}

int expr_check(const char *s, ExprError *e) { return run(s, NULL, NULL, 1, NULL, e); }
