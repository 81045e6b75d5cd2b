/* check_deck.c: the deck interpreter (deck.c) and the expression evaluator (expr.c).
 *
 * Decks are written to a fresh temporary directory.  Successful decks run in the test process and
 * their results are read back through deck_eval (numbers) or printed text; failing decks run in a
 * forked child with stdout/stderr captured to files, so each error test checks the exit code, the
 * FILE:LINE prefix, the message and the caret line exactly.  Only builtin commands are used (the
 * table in commands.c also holds physics commands, which are other modules' business).
 *
 * Operator convention under test: '^' binds tighter than unary minus and is right-associative
 * (-2^2 = -4, 2^3^2 = 512), the mathematical reading; LAMMPS reads both differently.
 */
#include <check.h>
#include <errno.h>
#include <ftw.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>
#include "deck.h"
#include "expr.h"
#include "sim.h"
#include "summary.h"
#include "yftest.h"

/* ------------------------------------------------------------------ helpers */

static char tdir[256]; /* per-test temporary directory */

static int rm_entry(const char *path, const struct stat *st, int flag, struct FTW *f) {
  return remove(path);
}
static void remove_tmpdir(void) {
  if (tdir[0]) nftw(tdir, rm_entry, 16, FTW_DEPTH | FTW_PHYS);
  tdir[0] = 0;
}

/* A fresh directory (the previous one of this test is removed; the teardown removes the last). */
static void make_tmpdir(void) {
  remove_tmpdir();
  snprintf(tdir, sizeof tdir, "/tmp/yf_check_deck_XXXXXX");
  ck_assert_ptr_nonnull(mkdtemp(tdir));
}

/* Write text to tdir/name (creating one level of sub-directory if name has one). */
static void write_file(const char *name, const char *text) {
  char path[512];
  const char *slash = strchr(name, '/');
  if (slash) {
    snprintf(path, sizeof path, "%s/%.*s", tdir, (int)(slash - name), name);
    mkdir(path, 0700);
  }
  snprintf(path, sizeof path, "%s/%s", tdir, name);
  FILE *fp = fopen(path, "w");
  ck_assert_ptr_nonnull(fp);
  fputs(text, fp);
  fclose(fp);
}

static char *read_all(const char *path) {
  FILE *fp = fopen(path, "rb");
  if (!fp) return strdup("");
  char *buf = calloc(1, 65536);
  size_t n = fread(buf, 1, 65535, fp);
  buf[n] = 0;
  fclose(fp);
  return buf;
}

/* Run a deck in the test process: the deck is written to tdir/main.deck and run by path. */
static YfSim g_sim;
static YfDeck *run_here(const char *text) {
  make_tmpdir();
  write_file("main.deck", text);
  memset(&g_sim, 0, sizeof g_sim);
  YfDeck *d = deck_new(&g_sim);
  char path[512];
  snprintf(path, sizeof path, "%s/main.deck", tdir);
  deck_run_file(d, path, NULL);
  return d;
}

static double val(YfDeck *d, const char *expr) { return deck_eval(d, expr, NULL); }

typedef struct {
  int code;   /* exit code of the child (or 128+signal) */
  char *out;  /* its stdout                             */
  char *err;  /* its stderr                             */
} Run;

/* Run tdir/e.deck (text) in a child whose working directory is tdir, so messages say "e.deck:N".
 * Extra files must have been written with write_file before.  var: optional -var NAME=VALUE. */
static Run run_child(const char *text, const char *var_name, const char *var_value) {
  write_file("e.deck", text);
  char out[512], err[512];
  snprintf(out, sizeof out, "%s/stdout.txt", tdir);
  snprintf(err, sizeof err, "%s/stderr.txt", tdir);
  fflush(NULL);
  pid_t pid = fork();
  ck_assert_int_ge(pid, 0);
  if (pid == 0) {
    if (chdir(tdir) || !freopen(out, "w", stdout) || !freopen(err, "w", stderr)) _exit(99);
    YfSim sim;
    sim_init(&sim);
    YfDeck *d = deck_new(&sim);
    if (var_name) deck_set_var(d, var_name, var_value);
    deck_run_file(d, "e.deck", NULL);
    deck_free(d);
    exit(0);
  }
  int st = 0;
  waitpid(pid, &st, 0);
  Run r;
  r.code = WIFEXITED(st) ? WEXITSTATUS(st) : 128 + WTERMSIG(st);
  r.out = read_all(out);
  r.err = read_all(err);
  return r;
}

static Run run_child_text(const char *text) {
  make_tmpdir();
  return run_child(text, NULL, NULL);
}

static void run_free(Run *r) {
  free(r->out);
  free(r->err);
}

/* Line k (0-based) of text, in a static buffer. */
static const char *line_of(const char *text, int k) {
  static char buf[1024];
  for (int i = 0; i < k && text; i++) {
    text = strchr(text, '\n');
    if (text) text++;
  }
  if (!text) return "";
  size_t n = strcspn(text, "\n");
  if (n >= sizeof buf) n = sizeof buf - 1;
  memcpy(buf, text, n);
  buf[n] = 0;
  return buf;
}

/* Assert an error run: exit code, first stderr line, and (if given) the context and caret lines. */
static void expect_error(const char *deck, int code, const char *first, const char *ctx, const char *caret) {
  Run r = run_child_text(deck);
  ck_assert_msg(r.code == code, "exit %d, expected %d; stderr:\n%s", r.code, code, r.err);
  ck_assert_str_eq(line_of(r.err, 0), first);
  if (ctx) ck_assert_str_eq(line_of(r.err, 1), ctx);
  if (caret) ck_assert_str_eq(line_of(r.err, 2), caret);
  run_free(&r);
}

/* ------------------------------------------------------------------ expressions */

static int no_names(void *ctx, const char *name, double *v, char *err, size_t n) { return 0; }

static double ev(const char *s) {
  double v = NAN;
  ExprError e;
  ck_assert_msg(expr_eval(s, no_names, NULL, &v, &e), "'%s' failed: %s", s, e.msg);
  return v;
}

START_TEST(expr_precedence) {
  /* exact in binary floating point */
  ck_assert_double_eq(ev("2^3^2"), 512.0); /* right-associative */
  ck_assert_double_eq(ev("-2^2"), -4.0);   /* '^' before unary minus */
  ck_assert_double_eq(ev("(-2)^2"), 4.0);
  ck_assert_double_eq(ev("2^-1"), 0.5);
  ck_assert_double_eq(ev("1+2*3"), 7.0);
  ck_assert_double_eq(ev("(1+2)*3"), 9.0);
  ck_assert_double_eq(ev("8/4/2"), 1.0); /* left-associative */
  ck_assert_double_eq(ev("10-4-3"), 3.0);
  ck_assert_double_eq(ev("7%3"), 1.0);
  ck_assert_double_eq(ev("10/4"), 2.5);
  ck_assert_double_eq(ev("1e3*2 + .5 + 1."), 2001.5);
  ck_assert_double_eq(ev("1 + 2 > 2"), 1.0); /* comparison below arithmetic */
  ck_assert_double_eq(ev("2 <= 1"), 0.0);
  ck_assert_double_eq(ev("3 >= 3 && 2 != 3"), 1.0);
  ck_assert_double_eq(ev("1 == 2 || 2 == 2"), 1.0);
  ck_assert_double_eq(ev("!0 + !5"), 1.0);
  ck_assert_double_eq(ev("0 || 0"), 0.0);
  ck_assert_double_eq(ev("1 < 2 == 1"), 1.0);   /* relational before equality */
  ck_assert_double_eq(ev("0 && 1/0"), 0.0);     /* short-circuit: 1/0 is not evaluated */
  ck_assert_double_eq(ev("1 || sqrt(-1)"), 1.0);
}
END_TEST

START_TEST(expr_functions) {
  ck_assert_double_eq(ev("sqrt(16)"), 4.0);
  ck_assert_double_eq(ev("max(1, 5, 3)"), 5.0);
  ck_assert_double_eq(ev("min(4,-2)"), -2.0);
  ck_assert_double_eq(ev("pow(2,10)"), 1024.0);
  ck_assert_double_eq(ev("abs(-3)"), 3.0);
  ck_assert_double_eq(ev("floor(-1.5)"), -2.0);
  ck_assert_double_eq(ev("ceil(1.2)"), 2.0);
  ck_assert_double_eq(ev("round(2.5)"), 3.0); /* half away from zero */
  ck_assert_double_eq(ev("round(-2.5)"), -3.0);
  ck_assert_double_eq(ev("log10(1000)"), 3.0);
  ck_assert_double_eq(ev("pi"), M_PI);
  ck_assert_double_eq(ev("PI"), M_PI);
  /* libm results: within a few ulp of the exact value */
  ck_assert_double_eq_tol(ev("atan2(1,1)"), M_PI / 4, 1e-15);
  ck_assert_double_eq_tol(ev("cos(pi)"), -1.0, 1e-15);
  ck_assert_double_eq_tol(ev("sin(pi/6)"), 0.5, 1e-15);
  ck_assert_double_eq_tol(ev("tan(pi/4)"), 1.0, 1e-15);
  ck_assert_double_eq_tol(ev("asin(1)"), M_PI / 2, 1e-15);
  ck_assert_double_eq_tol(ev("acos(0)"), M_PI / 2, 1e-15);
  ck_assert_double_eq_tol(ev("atan(1)*4"), M_PI, 1e-15);
  ck_assert_double_eq_tol(ev("log(exp(2))"), 2.0, 1e-15);
  ck_assert_double_eq_tol(ev("ln(exp(2))"), 2.0, 1e-15); /* LAMMPS's spelling of the natural log */
}
END_TEST

/* Each bad expression: the message and the character position it points at. */
START_TEST(expr_errors) {
  static const struct { const char *s, *msg; int pos; } t[] = {
      {"2*(3+", "missing ')'", 5},
      {"(1+2", "missing ')'", 4},
      {"1+2)", "unmatched ')'", 3},
      {"1/0", "division by zero", 1},
      {"5%0", "division by zero", 1},
      {"sqrt(-1)", "sqrt of negative number -1", 0},
      {"log(0)", "log of non-positive number 0", 0},
      {"log10(-2)", "log10 of non-positive number -2", 0},
      {"asin(2)", "asin of 2 (outside [-1, 1])", 0},
      {"exp(1000)", "exp gives a non-finite result", 0},
      {"10^400", "'^' gives a non-finite result", 2},
      {"(-8)^0.5", "negative base -8 to non-integer power 0.5", 4},
      {"1 + foo", "unknown variable 'foo'", 4},
      {"v_bar * 2", "unknown variable 'bar'", 0},
      {"hypot(3,4)", NULL, 0}, /* message lists the functions; checked by prefix below */
      {"atan2(1)", "atan2() takes 2 arguments, got 1", 0},
      {"max(1)", "max() takes at least 2 arguments, got 1", 0},
      {"2 3", "unexpected '3'", 2},
      {"", "empty expression", 0},
      {"1 +", "missing operand at the end", 3},
      {"3.0x", "unexpected 'x' after number", 3},
      {"1e", "bad exponent in number", 1},
      {"1 = 1", "'=' is not an operator (use '==' to compare)", 2},
      {"1 & 1", "'&' is not an operator (use '&&')", 2},
  };
  for (size_t i = 0; i < sizeof t / sizeof t[0]; i++) {
    ExprError e;
    double v;
    ck_assert_msg(!expr_eval(t[i].s, no_names, NULL, &v, &e), "'%s' should fail", t[i].s);
    if (t[i].msg) {
      ck_assert_msg(!strcmp(e.msg, t[i].msg), "'%s': got '%s', want '%s'", t[i].s, e.msg, t[i].msg);
      ck_assert_msg(e.pos == t[i].pos, "'%s': pos %d, want %d", t[i].s, e.pos, t[i].pos);
    } else {
      ck_assert_msg(!strncmp(e.msg, "unknown function 'hypot'", 24), "got '%s'", e.msg);
    }
  }
  /* syntax check only: names and domain are not checked */
  ExprError e;
  ck_assert(expr_check("v_later * 1/0", &e));
  ck_assert(!expr_check("2*(", &e));
}
END_TEST

/* ------------------------------------------------------------------ strict numbers, nearest */

START_TEST(strict_numbers) {
  static const struct { const char *s; int ok; double v; } t[] = {
      {"3", 1, 3.0},     {"-2.5e-3", 1, -2.5e-3}, {"+4.", 1, 4.0},   {".5", 1, 0.5},
      {"1E+2", 1, 100.0}, {"0", 1, 0.0},          {"1e-999", 1, 0.0}, /* underflow is fine */
      {"3.0x", 0, 0},    {"", 0, 0},              {"nan", 0, 0},     {"inf", 0, 0},
      {"-inf", 0, 0},    {"1e999", 0, 0},         {".", 0, 0},       {"e5", 0, 0},
      {"1e", 0, 0},      {" 1", 0, 0},            {"1 ", 0, 0},      {"0x10", 0, 0},
      {"--1", 0, 0},     {"1,5", 0, 0},           {"$(1)", 0, 0},    {"2*3", 0, 0},
  };
  for (size_t i = 0; i < sizeof t / sizeof t[0]; i++) {
    double v = -12345;
    int ok = yf_parse_double(t[i].s, &v);
    ck_assert_msg(ok == t[i].ok, "yf_parse_double('%s') = %d", t[i].s, ok);
    if (ok) ck_assert_msg(v == t[i].v, "yf_parse_double('%s') = %.17g", t[i].s, v);
  }
  static const struct { const char *s; int ok; long v; } L[] = {
      {"42", 1, 42},  {"-7", 1, -7},   {"+3", 1, 3},   {"1e6", 1, 1000000},
      {"2.0", 1, 2},  {"2.5", 0, 0},   {"1e-3", 0, 0}, {"", 0, 0},
      {"12a", 0, 0},  {"1e30", 0, 0},  {"99999999999999999999", 0, 0},
      {"9223372036854775807", 1, LONG_MAX},
  };
  for (size_t i = 0; i < sizeof L / sizeof L[0]; i++) {
    long v = -12345;
    int ok = yf_parse_long(L[i].s, &v);
    ck_assert_msg(ok == L[i].ok, "yf_parse_long('%s') = %d", L[i].s, ok);
    if (ok) ck_assert_msg(v == L[i].v, "yf_parse_long('%s') = %ld", L[i].s, v);
  }
}
END_TEST

START_TEST(nearest) {
  static const char *const names[] = {"fix", "run", "variable", "timestep", "label"};
  ck_assert_str_eq(yf_nearest("fxi", names, 5), "fix");
  ck_assert_str_eq(yf_nearest("varaible", names, 5), "variable");
  ck_assert_str_eq(yf_nearest("timstep", names, 5), "timestep");
  ck_assert_str_eq(yf_nearest("lable", names, 5), "label");
  ck_assert_ptr_null(yf_nearest("zzzzzz", names, 5)); /* distance 6 > max(2, 6/3) */
  ck_assert_ptr_null(yf_nearest("material", names, 5));
}
END_TEST

/* ------------------------------------------------------------------ variables and loops */

START_TEST(loop_sum) {
  YfDeck *d = run_here("variable s string 0\n"
                       "variable c string 0\n"
                       "variable i loop 10\n"
                       "label top\n"
                       "variable s string $(v_s + v_i)\n"
                       "variable c string $(v_c + 1)\n"
                       "next i\n"
                       "jump SELF top\n"
                       "variable after equal 1\n");
  ck_assert_double_eq(val(d, "v_s"), 55.0);   /* 1 + 2 + ... + 10 */
  ck_assert_double_eq(val(d, "c"), 10.0);     /* the body ran exactly 10 times */
  ck_assert_double_eq(val(d, "after"), 1.0);  /* the skipped jump fell through */
  deck_free(d);
  /* the jump's label is substituted (LAMMPS substitutes every line it runs): `jump SELF l${i}` picks one of
   * the fixed labels l2, l3 in turn; each adds its own weight, so s = 10 (l2) + 100 (l3) */
  d = run_here("variable s string 0\nvariable i index 2 3\nlabel top\njump SELF l${i}\n"
               "label l2\nvariable s string $(v_s + 10)\nnext i\njump SELF top\n"
               "label l3\nvariable s string $(v_s + 100)\nnext i\njump SELF top\n"
               "variable after equal 1\n");
  ck_assert_double_eq(val(d, "s"), 110.0);
  ck_assert_double_eq(val(d, "after"), 1.0);
  deck_free(d);
}
END_TEST

/* loop ... pad (LAMMPS): the values are written with the digits of the last one, so that files
 * named by them sort in order; expressions read the number ('pad' was read as the last value). */
START_TEST(loop_pad) {
  YfDeck *d = run_here("variable s string x\n"
                       "variable i loop 10 pad\n"
                       "label a\n"
                       "variable s string ${s}_${i}\n"
                       "next i\n"
                       "jump SELF a\n"
                       "variable j loop 98 100 pad\n"
                       "variable t string ${j}\n"
                       "variable u equal v_j+1\n");
  ck_assert_double_eq(val(d, "u"), 99.0); /* the number: 098 + 1 */
  deck_free(d);
  make_tmpdir();
  Run r = run_child("variable s string x\nvariable i loop 10 pad\nlabel a\nvariable s string ${s}_${i}\nnext i\n"
                    "jump SELF a\nvariable j loop 98 100 pad\nprint ${s}/${j}\n",
                    NULL, NULL);
  ck_assert_msg(r.code == 0, "exit %d: %s", r.code, r.err);
  ck_assert_str_eq(r.out, "x_01_02_03_04_05_06_07_08_09_10/098\n");
  run_free(&r);
}
END_TEST

/* Integers substitute whole up to 2^53: %.15g wrote 2^50 as 1.12589990684262e+15 (another
 * integer) and 1e15 as 1e+15; other numbers keep 15 digits.  Where an integer is asked for, a
 * fraction says how to round and an integer too large says so (both were "not an integer"). */
START_TEST(integers_substitute_whole) {
  make_tmpdir();
  Run r = run_child("variable n equal 2^50\nprint \"${n} $(1e15) $(-2^53) $(1/3) $(2^53*4) $(1e300) $(0.1*3)\"\n", NULL, NULL);
  ck_assert_msg(r.code == 0, "exit %d: %s", r.code, r.err);
  ck_assert_str_eq(r.out, "1125899906842624 1000000000000000 -9007199254740992 0.333333333333333 3.6028797018964e+16 "
                          "1e+300 0.3\n");
  run_free(&r);
  YfDeck *d = run_here("variable n equal 2^50+1\nvariable s string ${n}\n");
  ck_assert_double_eq(val(d, "s"), 1125899906842625.0); /* read back exactly */
  deck_free(d);
  expect_error("variable T equal 0.123456\nvariable i loop $(v_T*1e4)\n", 1,
               "e.deck:2: error: variable: count '1234.56': not an integer (round an expression: $(round(EXPR)), or "
               "$(EXPR:%d))", NULL, NULL);
  expect_error("variable i loop 99999999999999999999\n", 1,
               "e.deck:1: error: variable: count '99999999999999999999': an integer beyond those read exactly (at most "
               "9223372036854775807 written in digits, 2^53 = 9007199254740992 with an exponent or a '.')", NULL, NULL);
  expect_error("variable i loop 2 1e300\n", 1, "e.deck:1: error: variable: last value '1e300': must be in [2, 4611686018427387903]",
               NULL, NULL);
}
END_TEST

START_TEST(index_and_loop_ranges) {
  YfDeck *d = run_here("variable p string 1\n"
                       "variable n index 2 3 5\n"
                       "label a\n"
                       "variable p string $(v_p*v_n)\n"
                       "next n\n"
                       "jump SELF a\n"
                       "variable k loop 3 5\n"
                       "variable q string 0\n"
                       "label b\n"
                       "variable q string $(v_q+${k})\n"
                       "next k\n"
                       "jump SELF b\n"
                       /* two variables advanced together; ends when the shorter one runs out */
                       "variable x index 1 2 3\n"
                       "variable y loop 10 11\n"
                       "variable z string 0\n"
                       "label c\n"
                       "variable z string $(v_z + v_x*v_y)\n"
                       "next x y\n"
                       "jump SELF c\n"
                       /* an exhausted variable is deleted, so it can be defined again */
                       "variable n equal 99\n");
  ck_assert_double_eq(val(d, "p"), 30.0);            /* 2*3*5 */
  ck_assert_double_eq(val(d, "q"), 12.0);            /* 3+4+5 */
  ck_assert_double_eq(val(d, "z"), 1 * 10 + 2 * 11); /* y ends after 2 values */
  ck_assert_double_eq(val(d, "n"), 99.0);
  deck_free(d);
}
END_TEST

START_TEST(equal_is_lazy) {
  YfDeck *d = run_here("variable a equal 1\n"
                       "variable lazy equal v_a*2\n"
                       "variable now equal ${a}*2\n"
                       "variable a equal 5\n"
                       "variable s string 3.5\n"
                       "variable t equal v_s + 1\n");
  ck_assert_double_eq(val(d, "lazy"), 10.0); /* follows a */
  ck_assert_double_eq(val(d, "now"), 2.0);   /* ${a} was substituted at definition */
  ck_assert_double_eq(val(d, "t"), 4.5);     /* numeric string variables work in expressions */
  /* step, time, dt read the simulation */
  g_sim.step = 7;
  g_sim.time = 0.5;
  g_sim.dt = 1e-3;
  ck_assert_double_eq_tol(val(d, "step*dt + time"), 0.507, 1e-15);
  g_sim.time = 2.0;
  ck_assert_double_eq(val(d, "time"), 2.0);
  deck_free(d);
}
END_TEST

START_TEST(cmdline_var_wins) {
  make_tmpdir();
  write_file("main.deck", "variable n equal 3\nvariable m equal v_n*2\n");
  char path[512];
  snprintf(path, sizeof path, "%s/main.deck", tdir);
  YfSim sim;
  memset(&sim, 0, sizeof sim);
  YfDeck *d = deck_new(&sim);
  ck_assert_ptr_eq(sim.deck, d);
  deck_set_var(d, "n", "7");
  deck_run_file(d, path, NULL);
  ck_assert_double_eq(deck_eval(d, "m", NULL), 14.0); /* the deck's default 3 was ignored */
  deck_free(d);
  d = deck_new(&sim);
  deck_run_file(d, path, NULL);
  ck_assert_double_eq(deck_eval(d, "m", NULL), 6.0);
  deck_free(d);
}
END_TEST

START_TEST(if_branches) {
  static const struct { const char *x; double r; } t[] = {{"20", 1}, {"5", 2}, {"3", 3}, {"-1", 4}};
  for (int i = 0; i < 4; i++) {
    char deck[512];
    snprintf(deck, sizeof deck,
             "variable x equal %s\n"
             "if \"${x} > 10\" then \"variable r equal 1\" \"variable r2 equal 1\" &\n"
             "   elif \"v_x > 4\" \"variable r equal 2\" &\n"
             "   elif \"v_x >= 0 && v_x < 4\" then \"variable r equal 3\" &\n"
             "   else \"variable r equal 4\"\n",
             t[i].x);
    YfDeck *d = run_here(deck);
    ck_assert_double_eq(val(d, "r"), t[i].r);
    if (t[i].r == 1) ck_assert_double_eq(val(d, "r2"), 1.0); /* several commands in one branch */
    deck_free(d);
  }
  /* string comparison, jump from inside an if, and a false if without else */
  YfDeck *d = run_here("variable mode string fast\n"
                       "variable f equal 0\n"
                       "if \"${mode} == fast\" then \"variable f equal 1\"\n"
                       "if \"${mode} != fast\" then \"variable f equal 2\"\n"
                       "variable c string 0\n"
                       "label again\n"
                       "variable c string $(v_c+1)\n"
                       "if \"${c} < 4\" then \"jump SELF again\"\n");
  ck_assert_double_eq(val(d, "f"), 1.0);
  ck_assert_double_eq(val(d, "c"), 4.0);
  deck_free(d);
}
END_TEST

/* An if condition compares text only when a bare word of it names nothing and neither side is a
 * number ("${mode} == fast"); a division by zero, a misspelt v_NAME or a misspelt name compared
 * with a number was compared as text: silently false with ==, true with !=. */
START_TEST(if_condition_errors_are_not_strings) {
  YfDeck *d = run_here("variable mode string fast\n"
                       "variable f equal 0\n"
                       "if \"${mode} != slow\" then \"variable f equal 1\"\n"
                       "variable g equal 0\n"
                       "if \"a-b == a-b\" then \"variable g equal 1\"\n");
  ck_assert_double_eq(val(d, "f"), 1.0);
  ck_assert_double_eq(val(d, "g"), 1.0);
  deck_free(d);
  expect_error("variable nbroken equal 0\nif \"v_nbrokn == 0\" then \"print a\" else \"print b\"\n", 1,
               "e.deck:2: error: if: condition 'v_nbrokn == 0': unknown variable 'nbrokn' (did you mean 'nbroken'?)",
               NULL, NULL);
  expect_error("variable nbroken equal 0\nif \"nbrokn == 0\" then \"print a\"\n", 1,
               "e.deck:2: error: if: condition 'nbrokn == 0': unknown variable 'nbrokn' (did you mean 'nbroken'?)",
               NULL, NULL);
  expect_error("if \"1/0 == 1\" then \"print a\" else \"print b\"\n", 1,
               "e.deck:1: error: if: condition '1/0 == 1': division by zero", "  if \"1/0 == 1\" then \"print a\" else \"print b\"",
               "       ^");
  expect_error("if \"sqrt(-1) != 2\" then \"print a\"\n", 1,
               "e.deck:1: error: if: condition 'sqrt(-1) != 2': sqrt of negative number -1", NULL, NULL);
  /* a variable whose own expression fails is that variable's error, not a text */
  expect_error("variable r equal 1/v_z\nvariable z equal 0\nif \"v_r == x\" then \"print a\"\n", 1,
               "e.deck:3: error: if: condition 'v_r == x': variable 'r' = '1/v_z': division by zero", NULL, NULL);
}
END_TEST

START_TEST(include_relative) {
  make_tmpdir();
  write_file("sub/a.deck", "variable fromA equal 1\ninclude b.deck\nvariable afterB equal v_fromB+1\n");
  write_file("sub/b.deck", "variable fromB equal 41\n");
  write_file("main.deck", "include sub/a.deck\nvariable last equal v_afterB*2\n");
  YfSim sim;
  memset(&sim, 0, sizeof sim);
  YfDeck *d = deck_new(&sim);
  char path[512];
  snprintf(path, sizeof path, "%s/main.deck", tdir);
  deck_run_file(d, path, NULL); /* b.deck is found next to a.deck, not next to main.deck */
  ck_assert_double_eq(deck_eval(d, "last", NULL), 84.0);
  deck_free(d);

  /* deck_resolve_path joins with the directory of the command's deck */
  YfArgs a;
  memset(&a, 0, sizeof a);
  a.loc.file = "decks/sub/beam.deck";
  char *p = deck_resolve_path(&a, "mesh.msh");
  ck_assert_str_eq(p, "decks/sub/mesh.msh");
  free(p);
  p = deck_resolve_path(&a, "/abs/mesh.msh");
  ck_assert_str_eq(p, "/abs/mesh.msh");
  free(p);
  a.loc.file = "<stdin>";
  p = deck_resolve_path(&a, "mesh.msh");
  ck_assert_str_eq(p, "mesh.msh");
  free(p);
  a.loc.file = "beam.deck";
  p = deck_resolve_path(&a, "m.msh");
  ck_assert_str_eq(p, "m.msh");
  free(p);
}
END_TEST

START_TEST(quit_stops) {
  YfDeck *d = run_here("variable a equal 1\nif \"1\" then quit\nvariable a equal 2\n");
  ck_assert_double_eq(val(d, "a"), 1.0);
  deck_free(d);
}
END_TEST

/* ------------------------------------------------------------------ text: substitution, quotes */

START_TEST(substitution_and_quotes) {
  Run r = run_child_text("variable a equal 3\n"
                         "variable name string beam\n"
                         "print \"${name}: a=$a 2a=$(2*v_a) third=$(1/3:%.4f) n=$(7.6:%d)\" # comment\n"
                         "print 'single ${name} # not a comment'\n"
                         "print \"two  spaces\"   and   words\n"
                         "print \"long &\n"
                         "   line\" &\n"
                         "  end\n"
                         "print \"\"\"triple\n"
                         "quoted ${a}\"\"\"\n"
                         "print cost $5\n"
                         "print \"$(-0.0) ${a}${a}\"\n");
  ck_assert_msg(r.code == 0, "stderr: %s", r.err);
  ck_assert_str_eq(r.out, "beam: a=3 2a=6 third=0.3333 n=8\n"
                          "single ${name} # not a comment\n"
                          "two  spaces and words\n"
                          "long     line end\n"
                          "triple\nquoted 3\n"
                          "cost $5\n"
                          "0 33\n");
  run_free(&r);
}
END_TEST

START_TEST(echo_and_stdin) {
  make_tmpdir();
  Run r = run_child("echo on\nvariable v equal 2\nprint \"v=$v\"\necho off\nprint done\n", NULL, NULL);
  ck_assert_msg(r.code == 0, "stderr: %s", r.err);
  ck_assert_str_eq(r.out, "variable v equal 2\nprint \"v=2\"\nv=2\necho off\ndone\n");
  run_free(&r);
  /* a deck from a stream can jump backwards (it is read into memory first) */
  char text[] = "variable c string 0\nlabel l\nvariable c string $(v_c+1)\nif \"v_c < 3\" then \"jump SELF l\"\n";
  FILE *fp = fmemopen(text, strlen(text), "r");
  YfSim sim;
  memset(&sim, 0, sizeof sim);
  YfDeck *d = deck_new(&sim);
  deck_run_stream(d, fp, "<stdin>");
  fclose(fp);
  ck_assert_double_eq(deck_eval(d, "c", NULL), 3.0);
  deck_free(d);
}
END_TEST

/* ------------------------------------------------------------------ errors */

START_TEST(error_unknown_command) {
  expect_error("variable a equal 1\n"
               "\n"
               "varaible b equal 2\n",
               1, "e.deck:3: error: unknown command 'varaible' (did you mean 'variable'?)",
               "  varaible b equal 2", "  ^");
  expect_error("qwertyuiop\n", 1, "e.deck:1: error: unknown command 'qwertyuiop'", NULL, NULL);
  /* LAMMPS commands say what yfdem does instead: 'log' was "did you mean 'load'?" */
  expect_error("log log.case1.txt\n", 1,
               "e.deck:1: error: unknown command 'log' (a LAMMPS command): yfdem names its log on the command line: "
               "-log FILE (default log.yfdem) or -log none", NULL, NULL);
  expect_error("units si\n", 1,
               "e.deck:1: error: unknown command 'units' (a LAMMPS command): yfdem works in SI units always (m, kg, "
               "s, N, Pa; loads and forces per metre of thickness): delete the line", "  units si", "  ^");
  expect_error("shell mkdir out\n", 1,
               "e.deck:1: error: unknown command 'shell' (a LAMMPS command): yfdem runs no shell commands from a "
               "deck: make folders before the run (an output whose folder is missing is an error at its line)", NULL,
               NULL);
}
END_TEST

START_TEST(error_lines_after_continuation_and_include) {
  /* the command starts on line 2; the bad word is on line 3 */
  expect_error("# header\n"
               "echo &\n"
               "   maybe\n",
               1, "e.deck:2: error: echo: setting 'maybe': expected one of off, on", "  echo     maybe",
               "           ^");
  make_tmpdir();
  write_file("inc/x.deck", "variable ok equal 1\n\nvariable bad equal 2*(3+\n");
  Run r = run_child("variable a equal 1\ninclude inc/x.deck\n", NULL, NULL);
  ck_assert_int_eq(r.code, 1);
  ck_assert_str_eq(line_of(r.err, 0), "inc/x.deck:3: error: variable: expression '2*(3+': missing ')'");
  ck_assert_str_eq(line_of(r.err, 1), "  variable bad equal 2*(3+");
  ck_assert_str_eq(line_of(r.err, 2), "                          ^");
  run_free(&r);
}
END_TEST

START_TEST(error_expressions_and_variables) {
  expect_error("print \"x = $(2*(3+))\"\n", 1, "e.deck:1: error: expression '2*(3+)': expected a number, a name or '(' but found ')'",
               "  print \"x = $(2*(3+))\"", "                    ^");
  expect_error("variable a equal 1/(v_b-2)\nvariable b equal 2\nprint ${a}\n", 1,
               "e.deck:3: error: variable 'a' = '1/(v_b-2)': division by zero", "  print ${a}", "        ^");
  expect_error("print ${nope}\n", 1, "e.deck:1: error: unknown variable 'nope' (no variable is defined)", NULL, NULL);
  expect_error("print $q\n", 1, "e.deck:1: error: unknown variable 'q' (write ${name} for longer names)", NULL, NULL);
  expect_error("variable a equal v_b\nvariable b equal v_a+1\nprint ${a}\n", 1,
               "e.deck:3: error: variable 'a': equal-style variables nested deeper than 64 (does it refer to itself?)",
               NULL, NULL);
  expect_error("variable s string abc\nprint $(v_s+1)\n", 1,
               "e.deck:2: error: expression 'v_s+1': variable 's' has the non-numeric value 'abc'", NULL, NULL);
  expect_error("print \"unterminated\n", 1, "e.deck:1: error: unmatched quote", "  print \"unterminated", "        ^");
  expect_error("variable a equl 3\n", 1,
               "e.deck:1: error: variable: style 'equl': expected one of equal, string, index, loop, delete "
               "(did you mean 'equal'?)", NULL, NULL);
  expect_error("variable a index 1 2\nvariable a equal 3\n", 1,
               "e.deck:2: error: variable: variable 'a': already defined as index-style, cannot redefine as "
               "equal-style (use 'variable a delete' first)", NULL, NULL);
  expect_error("next i\n", 1, "e.deck:1: error: next: variable 'i': no such variable (no variable is defined)", NULL, NULL);
  expect_error("jump SELF nowhere\n", 1, "e.deck:1: error: jump: label 'nowhere': no 'label nowhere' in e.deck (it has no label)",
               NULL, NULL);
  /* the labels there are: a misspelt one was named alone */
  expect_error("label loop_a\nlabel done\njump SELF loopa\n", 1,
               "e.deck:3: error: jump: label 'loopa': no 'label loopa' in e.deck (its labels: loop_a, done)", NULL, NULL);
  /* `label l${i}`: LAMMPS substitutes the jump's label but no line it skips looking for the label (input.cpp
   * parse: "except if searching for a label"), so l${i} as written is not 'l2' and LAMMPS stops at the end of
   * the file; yfdem matches labels the same way, and now says why a label it lists is not the one named */
  expect_error("variable i loop 3\nlabel l${i}\nnext i\njump SELF l${i}\n", 1,
               "e.deck:4: error: jump: label 'l2': no 'label l2' in e.deck (its labels: l${i}); labels are matched as "
               "written: as in LAMMPS, no variable is substituted in the lines skipped looking for a label, so a label "
               "holding '$' is not its value: give each label a fixed name (label l1, label l2, ...) and jump to l${i}",
               NULL, NULL);
  expect_error("if \"v_q > 1\" then \"print x\"\n", 1, "e.deck:1: error: if: condition 'v_q > 1': unknown variable 'q' (no variable is defined)",
               "  if \"v_q > 1\" then \"print x\"", "      ^");
  expect_error("if 1 \"print x\"\n", 1, "e.deck:1: error: if: 'print x': expected 'then' after the condition", NULL,
               NULL);
  expect_error("label\n", 1, "e.deck:1: error: label: expected 1 argument, got 0", "  usage: label NAME", "  label");
  /* a branch with no command did nothing without a word */
  expect_error("if \"1\" then\n", 1, "e.deck:1: error: if: no command after 'then'", NULL, NULL);
  expect_error("if \"0\" then \"print a\" else\n", 1, "e.deck:1: error: if: no command after 'else'", NULL, NULL);
  expect_error("if \"0\" then \"print a\" elif \"1\" then\n", 1, "e.deck:1: error: if: no command after the 'elif' condition",
               NULL, NULL);
  expect_error("print $(1:%s)\n", 1,
               "e.deck:1: error: bad format '%s' in $(...) (expected one conversion like %.3f, %g, %10.4e or %d, "
               "width and precision of at most 2 digits)", NULL, NULL);
  /* a wider format was cut to a 128-byte buffer ('%300d' printed nothing of the value), and 30
   * flags overflowed the copy that gains the 'l' (a malformed printf format) */
  expect_error("print $(1:%300d)\n", 1, "e.deck:1: error: bad format '%300d' in $(...) (expected one conversion like %.3f, %g, %10.4e or %d, width and precision of at most 2 digits)", NULL, NULL);
  expect_error("print $(1:%.400f)\n", 1, "e.deck:1: error: bad format '%.400f' in $(...) (expected one conversion like %.3f, %g, %10.4e or %d, width and precision of at most 2 digits)", NULL, NULL);
  expect_error("print $(1:%000000000000000000000000000005d)\n", 1,
               "e.deck:1: error: bad format '%000000000000000000000000000005d' in $(...) (expected one conversion like %.3f, %g, %10.4e or %d, width and precision of at most 2 digits)", NULL, NULL);
  /* the widest allowed is whole: 1e300 has 301 digits, '.', then 99 */
  Run r = run_child("print \"<$(1e300:%99.99f)>\"\n", NULL, NULL);
  ck_assert_msg(r.code == 0, "stderr: %s", r.err);
  const char *a = strchr(r.out, '<'), *z = a ? strchr(a, '>') : NULL;
  ck_assert_msg(a && z && z - a - 1 == 301 + 1 + 99 && !strncmp(a + 1, "1000000000000000052504760255204420", 34), "%s", r.out);
  run_free(&r);
}
END_TEST

/* A name the scene keeps is refused at its line when it does not fit (47 characters): material,
 * history, fix and load names were cut short silently, then not found by their full name
 * ("unknown material" listing the cut name; a sweep of new decks, 2026-11-28). */
START_TEST(error_long_names) {
  make_tmpdir();
  char n48[49];
  memset(n48, 'N', 48);
  n48[48] = 0;
  static const char *const fmt[] = {
      "material %s elastic rho 1 E 1 nu 0.1 plane_strain\n", "history %s constant\n", "fix %s b fixed xy\n",
      "load %s point node 0 1 0\n", "jointprop %s ft 1 fs 1 gf 1 pen 1\n", "region %s box 0 0 1 1\n",
      "group %s node ids 0\n", "dump %s csv 1 out\n", "record %s 1 r.csv step\n"};
  const char *what[] = {"name", "name", "ID", "ID", "name", "region name", "group name", "dump id", "record id"};
  for (size_t k = 0; k < sizeof fmt / sizeof fmt[0]; k++) {
    char deck[256], want[160];
    int at = snprintf(deck, sizeof deck, "material m elastic rho 1 E 1 nu 0.1 plane_strain\nmesh rect b m 0 0 1 1 1 1\n");
    snprintf(deck + at, sizeof deck - (size_t)at, fmt[k], n48);
    Run r = run_child(deck, NULL, NULL);
    snprintf(want, sizeof want, "e.deck:3: error: %.*s: '%s': %s longer than 47 characters", (int)strcspn(fmt[k], " "),
             fmt[k], n48, what[k]);
    ck_assert_msg(r.code == 1 && strstr(r.err, want), "%s: exit %d: %s", deck, r.code, r.err);
    run_free(&r);
  }
}
END_TEST

/* A variable name is at most 125 characters, the longest an expression reads as v_NAME: a name of
 * 200 was accepted by `variable`, worked as ${NAME} and failed in $(NAME) and $(v_NAME) as "name
 * too long".  A name at the limit works in all three; one beyond is refused where it is defined
 * (the variable line, or -var) with the limit. */
START_TEST(error_long_variable_names) {
  make_tmpdir();
  char name[201], deck[1200], want[400];
  memset(name, 'v', 200);
  name[125] = 0;
  snprintf(deck, sizeof deck, "variable %s equal 7\nprint \"${%s} $(%s) $(v_%s)\"\n", name, name, name, name);
  Run r = run_child(deck, NULL, NULL);
  ck_assert_msg(r.code == 0 && !strcmp(r.out, "7 7 7\n"), "exit %d: out '%s' err %s", r.code, r.out, r.err);
  run_free(&r);
  static const int len[] = {126, 200};
  for (int k = 0; k < 2; k++) {
    memset(name, 'v', 200);
    name[len[k]] = 0;
    snprintf(deck, sizeof deck, "variable %s equal 7\nprint \"${%s}\"\n", name, name);
    r = run_child(deck, NULL, NULL);
    snprintf(want, sizeof want, "e.deck:1: error: variable: name '%s': %d characters: a variable name has at most 125 "
             "(the longest an expression reads as v_NAME)", name, len[k]);
    ck_assert_msg(r.code == 1 && !strcmp(line_of(r.err, 0), want), "exit %d: %s", r.code, r.err);
    ck_assert_str_eq(line_of(r.err, 2), "           ^");
    run_free(&r);
    r = run_child("print \"${x}\"\n", name, "3");
    ck_assert_msg(r.code == 1 && strstr(r.err, "-var: bad variable name") &&
                  strstr(r.err, "characters: a variable name has at most 125"), "exit %d: %s", r.code, r.err);
    run_free(&r);
  }
}
END_TEST

/* Two outputs never write one file: two records on one file interleaved their rows, a record on
 * a dump's index or a restart's file lost one of them, and dumps named out.h5 and ./out.h5 (or
 * c3.h5 and c3, or c2.h5 and c2_cracks.h5, whose index is c2.h5's crack index) listed each
 * other's frames (sweeps of new decks, 2026-11-28).  Each is refused at the second line; an
 * output turned off (record off, undump) gives its file back. */
START_TEST(error_outputs_share_a_file) {
  make_tmpdir();
  static const char *const pre = "material m elastic rho 1000 E 1e9 nu 0.25 plane_stress\nmesh rect b m 0 0 1 0.1 4 2\n";
  static const struct {
    const char *lines, *want;
  } cases[] = {
      {"record r1 1 r.csv ke\nrecord r2 5 r.csv strain\n", "e.deck:4: error: record: 'r.csv': already written by record 'r1'"},
      {"dump d h5 5 o.h5\nrecord r 1 o.xmf ke\n", "e.deck:4: error: record: 'o.xmf': already written by dump 'd'"},
      {"dump d h5 5 o.h5\nrecord r 1 o_000003.h5 ke\n", "e.deck:4: error: record: 'o_000003.h5': already written by dump 'd'"},
      {"dump d csv 5 x\nrecord r 1 x_frames.csv ke\n", "e.deck:4: error: record: 'x_frames.csv': already written by dump 'd'"},
      {"dump d1 h5 5 out.h5\ndump d2 h5 3 ./out.h5\n", "e.deck:4: error: dump: './out.h5': a file of it is already written by dump 'd1'"},
      {"dump d1 h5 5 c3.h5\ndump d2 h5 3 c3\n", "e.deck:4: error: dump: 'c3': a file of it is already written by dump 'd1'"},
      {"dump d1 h5 5 c2.h5\ndump d2 h5 3 c2_cracks.h5\n", "e.deck:4: error: dump: 'c2_cracks.h5': a file of it is already written by dump 'd1'"},
      {"fracture_log x.csv\nrecord r 10 x.csv ke\n", "e.deck:4: error: record: 'x.csv': already written by fracture_log"},
      {"fracture_log x.csv opened x.csv\n", "e.deck:3: error: fracture_log: 'x.csv': already written by fracture_log"},
      {"restart every 100 x.csv\nrecord r 10 x.csv.a ke\n", "e.deck:4: error: record: 'x.csv.a': already written by restart every"},
      {"metrics log m.csv\nrecord r 10 m.csv ke\n", "e.deck:4: error: record: 'm.csv': already written by metrics log"},
      /* a y2dref dump's files in its DIR: two such dumps on one DIR interleaved their rows */
      {"dump y1 y2dref ref summary 5\ndump y2 y2dref ./ref/ summary 2\n", "e.deck:4: error: dump: './ref/': a file it writes there is already written by dump 'y1'"},
      {"dump y1 y2dref . corners 3\nrecord r 1 corners_0000007.csv ke\n", "e.deck:4: error: record: 'corners_0000007.csv': already written by dump 'y1'"},
  };
  for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
    char deck[512];
    snprintf(deck, sizeof deck, "%s%s", pre, cases[k].lines);
    Run r = run_child(deck, NULL, NULL);
    ck_assert_msg(r.code == 1 && strstr(r.err, cases[k].want), "%s: exit %d: %s", cases[k].lines, r.code, r.err);
    run_free(&r);
  }
  /* turned off, its file is free again; a fracture_log replaced gives its file back too */
  char deck[512];
  snprintf(deck, sizeof deck, "%srecord r 1 a.csv ke\nrecord r off\nrecord q 1 a.csv ke\ndump d h5 5 o.h5\nundump d\n"
           "dump e h5 5 o.h5\nfracture_log f.csv\nfracture_log g.csv\nrecord z 1 f.csv ke\n"
           "dump y y2dref .\ndump h h5 5 o2.h5\nundump y\ndump y2 y2dref .\n", pre);
  Run r = run_child(deck, NULL, NULL);
  ck_assert_msg(r.code == 0, "exit %d: %s", r.code, r.err);
  run_free(&r);
}
END_TEST

/* A history file's rows are two numbers: a third column was dropped silently (the nodes,
 * triangles and table readers refuse one); a bad row names the file and its line. */
START_TEST(error_history_file_rows) {
  make_tmpdir();
  write_file("three.hist", "# t v\n0 0\n1 2 99\n");
  Run r = run_child("history h file three.hist\n", NULL, NULL);
  ck_assert_msg(r.code == 1 && strstr(r.err, "three.hist:3: error: history file: '99' after 't v'"), "exit %d: %s", r.code,
                r.err);
  run_free(&r);
  write_file("two.hist", "# t v\n0 0   # start\n1,2\n");
  r = run_child("history h file two.hist\n", NULL, NULL);
  ck_assert_msg(r.code == 0, "exit %d: %s", r.code, r.err);
  run_free(&r);
}
END_TEST

/* Masses, the kinetic energy and the stable limit exist once a run has prepared the scene: asked
 * for before, they read 0 silently ('timestep $(0.5*dt_limit)' then failed as "dt '0'"); now an
 * error says so, and after 'run 0' they are known. */
START_TEST(error_quantities_before_run) {
  make_tmpdir();
  static const char *const pre = "material m elastic rho 1000 E 1e9 nu 0.25 plane_stress\nmesh rect b m 0 0 1 1 2 2\n"
                                 "velocity b set 2 0\n";
  static const char *const q[] = {"ke", "dt_limit", "mass_b"};
  for (int k = 0; k < 3; k++) {
    char deck[512], want[160];
    snprintf(deck, sizeof deck, "%sprint \"$(%s)\"\n", pre, q[k]);
    snprintf(want, sizeof want, "e.deck:4: error: expression '%s': '%s' is known once a run has prepared the scene", q[k], q[k]);
    Run r = run_child(deck, NULL, NULL);
    ck_assert_msg(r.code == 1 && strstr(r.err, want), "%s: exit %d: %s", q[k], r.code, r.err);
    run_free(&r);
  }
  char deck[512];
  snprintf(deck, sizeof deck, "%stimestep auto\nrun 0\nprint \"ke $(ke) mass $(mass_b) ok $(dt_limit > 0)\"\n", pre);
  Run r = run_child(deck, NULL, NULL);
  ck_assert_msg(r.code == 0 && strstr(r.out, "ke 2000 mass 1000 ok 1"), "exit %d: %s%s", r.code, r.out, r.err);
  run_free(&r);
}
END_TEST

/* dt under 'timestep auto' is the safety factor times the stable limit, which a run computes: before
 * it, dt read 0 ('run $(round(T/dt))' failed as a division by zero) or the step of an earlier
 * 'timestep DT' (1e-5 printed, 1.42e-4 run); now an error says to put 'run 0' first.  And each
 * 'timestep auto' line says its factor anew: without 'safety' it is the documented default 0.5,
 * not the factor an earlier line gave (0.2 was kept). */
START_TEST(dt_known_when_run_computes_it) {
  make_tmpdir();
  static const char *const pre = "material m elastic rho 2000 E 1e8 nu 0.25 plane_stress\nmesh rect a m 0 0 1 0.2 10 2\n";
  char deck[768];
  snprintf(deck, sizeof deck, "%stimestep auto\nprint \"$(dt)\"\n", pre);
  Run r = run_child(deck, NULL, NULL);
  ck_assert_msg(r.code == 1 && strstr(r.err, "e.deck:4: error: expression 'dt': 'dt' under 'timestep auto' is known once a "
                                             "run has computed it"), "exit %d: %s", r.code, r.err);
  run_free(&r);
  snprintf(deck, sizeof deck, "%stimestep 1e-5\ntimestep auto\nprint \"$(dt)\"\n", pre);
  r = run_child(deck, NULL, NULL);
  ck_assert_msg(r.code == 1 && strstr(r.err, "e.deck:5: error: expression 'dt': 'dt' under 'timestep auto'"),
                "exit %d: %s", r.code, r.err);
  run_free(&r);
  snprintf(deck, sizeof deck, "%sprint \"$(dt)\"\n", pre);
  r = run_child(deck, NULL, NULL);
  ck_assert_msg(r.code == 1 && strstr(r.err, "e.deck:3: error: expression 'dt': 'dt' is not known yet: no time step is set"),
                "exit %d: %s", r.code, r.err);
  run_free(&r);
  /* the stable limit of this mesh is 2.84453e-4 s (triangle 5): dt is 0.5 of it after a bare
   * 'timestep auto', whatever factor an earlier line gave, and 0.2 of it when said */
  snprintf(deck, sizeof deck, "%stimestep auto safety 0.2\nrun 0\nprint \"r1 $(dt/dt_limit)\"\ntimestep auto\nrun 0\n"
           "print \"r2 $(dt/dt_limit)\"\ntimestep 1e-6\nprint \"r3 $(dt)\"\n", pre);
  r = run_child(deck, NULL, NULL);
  ck_assert_msg(r.code == 0 && strstr(r.out, "r1 0.2\n") && strstr(r.out, "r2 0.5\n") && strstr(r.out, "r3 1e-06\n"),
                "exit %d: %s%s", r.code, r.out, r.err);
  run_free(&r);
}
END_TEST

/* A Gmsh physical group named 'bottom-face' is a group a deck can fix and load, but 'fy_bottom-face'
 * in an expression reads as fy_bottom minus face, and the error said only "no group or body named
 * 'bottom'".  It now names the group and gives the alias; the alias reads the group's force. */
START_TEST(error_group_name_an_expression_cannot_hold) {
  make_tmpdir();
  char *msh = yft_slurp("decks/meshes/square4.msh", 0);
  ck_assert_ptr_nonnull(msh);
  char *q = strstr(msh, "\"base\"");
  ck_assert_ptr_nonnull(q);
  char text[8192];
  snprintf(text, sizeof text, "%.*s\"bottom-face\"%s", (int)(q - msh), msh, q + 6);
  write_file("sq.msh", text);
  free(msh);
  static const char *const pre = "material soft elastic rho 1000 E 1e9 nu 0.25 plane_stress\n"
                                 "material hard elastic rho 1000 E 2e9 nu 0.25 plane_stress\n"
                                 "mesh gmsh b sq.msh material soft=soft hard=hard\nfix a bottom-face fixed xy\n"
                                 "timestep auto\nrun 1\n";
  char deck[1024];
  snprintf(deck, sizeof deck, "%sprint \"$(fy_bottom-face)\"\n", pre);
  Run r = run_child(deck, NULL, NULL);
  ck_assert_msg(r.code == 1 && strstr(r.err, "e.deck:7: error: expression 'fy_bottom-face': 'fy_bottom': no group or "
                                             "body named 'bottom'; the group 'bottom-face' has a character") &&
                strstr(r.err, "('group bottom_face union \"bottom-face\"') and write fy_bottom_face"),
                "exit %d: %s", r.code, r.err);
  run_free(&r);
  snprintf(deck, sizeof deck, "%sgroup bottom_face union \"bottom-face\"\nprint \"n $(mass_bottom_face > 0)\"\n", pre);
  r = run_child(deck, NULL, NULL);
  ck_assert_msg(r.code == 0 && strstr(r.out, "n 1\n"), "exit %d: %s%s", r.code, r.out, r.err);
  run_free(&r);
}
END_TEST

/* A point load or a 'group nearest' whose point lies far off the mesh (a coordinate in mm on a
 * mesh in m) took the nearest node, 1000 m away, and the run ended ok with the force on a corner
 * the deck never meant.  Off the mesh by more than the scene's longest triangle edge is a deck
 * error at the word; a point within one element of the body (a corner given to rounding) still
 * takes its nearest node, and the load acts there: the held end's reaction is the load. */
START_TEST(error_point_off_the_mesh) {
  static const char *const bar = "material m elastic rho 2500 E 3e10 nu 0.2 plane_stress\n"
                                 "mesh rect b m 0 0 1 0.1 20 2\n"
                                 "region left box -1 -1 1e-9 1\ngroup left node region left\n"
                                 "fix c left fixed xy\ntimestep auto\n";
  char deck[2048];
  snprintf(deck, sizeof deck, "%sload tip point at 1000 100 0 -1000\nrun 10\n", bar);
  Run r = run_child_text(deck);
  ck_assert_msg(r.code == 1 && strstr(r.err, "e.deck:7: error: load 'tip': the point (1000, 100) is 1003.98 m from "
                                             "the nearest node (node 63 at (1, 0.1))") &&
                strstr(r.err, "longest triangle edge of the scene, 0.0707107 m"),
                "exit %d: %s", r.code, r.err);
  run_free(&r);
  snprintf(deck, sizeof deck, "%sgroup g node nearest -500 0.05\nrun 10\n", bar);
  r = run_child_text(deck);
  ck_assert_msg(r.code == 1 && strstr(r.err, "e.deck:7: error: group: '-500': the point (-500, 0.05) is 500 m from "
                                             "the nearest node"),
                "exit %d: %s", r.code, r.err);
  run_free(&r);
  /* within one element of the corner (1, 0.1): the nearest node, held in equilibrium by the clamp */
  snprintf(deck, sizeof deck, "%sload tip point at 1.02 0.12 0 -1000\ngroup g node nearest 1.02 0.12\n"
           "damping mass 180\nrun 40000\nprint \"R $(fy_left) g $(x_g-ux_g) $(y_g-uy_g)\"\n", bar);
  r = run_child_text(deck);
  ck_assert_msg(r.code == 0, "exit %d: %s", r.code, r.err);
  double R = 0, gx = 0, gy = 0;
  const char *o = strstr(r.out, "R ");
  ck_assert_msg(o && sscanf(o, "R %lf g %lf %lf", &R, &gx, &gy) == 3, "%s", r.out);
  /* damped for 40000 steps at alpha 180 (about 2 omega_1): the ringing left is exp(-alpha t / 2) ~ 1e-7 */
  ck_assert_msg(fabs(R + 1000) < 1e-3 && fabs(gx - 1) < 1e-12 && fabs(gy - 0.1) < 1e-12, "R %g at (%g, %g)", R, gx, gy);
  run_free(&r);
}
END_TEST

/* An unknown variable's message says what the deck could have meant: the variable of another case
 * or a near spelling, a thermo keyword for a bare name in an expression, else the variables there
 * are (the message named the unknown one only). */
START_TEST(error_unknown_variable_hints) {
  expect_error("variable nx equal 10\nvariable ny equal 2\nprint ${nX}\n", 1,
               "e.deck:3: error: unknown variable 'nX' (did you mean 'nx'?)", "  print ${nX}", "        ^");
  expect_error("variable length equal 2\nprint $(v_lenght/2)\n", 1,
               "e.deck:2: error: expression 'v_lenght/2': unknown variable 'lenght' (did you mean 'length'?)", NULL, NULL);
  expect_error("print $(2*kee)\n", 1, "e.deck:1: error: expression '2*kee': unknown variable 'kee' (did you mean 'ke'?)",
               "  print $(2*kee)", "            ^");
  expect_error("variable a equal 1\nvariable b index x y\nprint ${zzz}\n", 1,
               "e.deck:3: error: unknown variable 'zzz' (variables: a, b)", NULL, NULL);
  expect_error("variable count loop 2\nnext cuont\n", 1,
               "e.deck:2: error: next: variable 'cuont': no such variable (did you mean 'count'?)", NULL, NULL);
  /* v_NAME reads variables only: no thermo keyword is offered for it */
  expect_error("print $(v_kee)\n", 1, "e.deck:1: error: expression 'v_kee': unknown variable 'kee' (no variable is defined)",
               NULL, NULL);
  /* a NaN or an infinity a generating script wrote is named as such, not as an unknown variable */
  expect_error("variable E equal nan\nprint ${E}\n", 1,
               "e.deck:2: error: variable 'E' = 'nan': 'nan' is not a finite number, and expressions hold finite "
               "numbers only (did the script that wrote this deck compute a NaN?)", NULL, NULL);
  expect_error("print $(2*-inf)\n", 1,
               "e.deck:1: error: expression '2*-inf': 'inf' is not a finite number, and expressions hold finite numbers "
               "only (did the script that wrote this deck compute a division by zero or an overflow?)", NULL, NULL);
  /* a loop variable used after the 'next' that deleted it (LAMMPS's rule) says so and where */
  expect_error("variable i loop 2\nlabel l\nnext i\njump SELF l\nprint \"after: ${i}\"\n", 1,
               "e.deck:5: error: unknown variable 'i' (the 'next i' at e.deck:3 deleted it when it ran past its last "
               "value, as LAMMPS does; keep a value for after the loop in another variable)", NULL, NULL);
  expect_error("variable i loop 2\nlabel l\nnext i\njump SELF l\nvariable i equal 1\nvariable i delete\nprint $(v_i)\n", 1,
               "e.deck:7: error: expression 'v_i': unknown variable 'i' (no variable is defined)", NULL, NULL);
  /* pi stays the evaluator's own */
  YfDeck *d = run_here("variable r equal 2\n");
  ck_assert_double_eq_tol(val(d, "pi*v_r^2"), 4 * M_PI, 1e-15);
  deck_free(d);
}
END_TEST

/* print's LAMMPS keywords: a sweep's rows appended to a file, off the screen (they were printed as
 * text, "... append res.txt screen no", and no file was written). */
START_TEST(print_to_file) {
  make_tmpdir();
  Run r = run_child("variable E index 1e9 2e9 4e9\n"
                    "label l\n"
                    "print \"${E} $(1000/v_E)\" append res.txt screen no\n"
                    "print \"last ${E}\" file last.txt\n"
                    "next E\n"
                    "jump SELF l\n"
                    "print the file is ready\n"
                    "print one screen yes\n",
                    NULL, NULL);
  ck_assert_msg(r.code == 0, "exit %d: %s", r.code, r.err);
  /* 'file' writes anew, 'append' adds; the numbers as ${} and $() print them */
  char path[512];
  snprintf(path, sizeof path, "%s/res.txt", tdir);
  char *res = read_all(path);
  ck_assert_str_eq(res, "1e9 1e-06\n2e9 5e-07\n4e9 2.5e-07\n");
  free(res);
  snprintf(path, sizeof path, "%s/last.txt", tdir);
  char *last = read_all(path);
  ck_assert_str_eq(last, "last 4e9\n");
  free(last);
  /* screen no: not on the screen; words that are no keyword pairs stay text */
  ck_assert_str_eq(r.out, "last 1e9\nlast 2e9\nlast 4e9\nthe file is ready\none\n");
  run_free(&r);
  expect_error("print a file nodir/x.txt\n", 2, "e.deck:1: error: print: cannot write 'nodir/x.txt': No such file or directory",
               NULL, NULL);
  /* the file is claimed as outputs' files are: a dump's index on it would interleave */
  expect_error("print a file o.xmf\ndump d h5 5 o.h5\n", 1, "e.deck:2: error: dump: 'o.h5': a file of it is already written by print",
               NULL, NULL);
  expect_error("print a file f1 append f2\n", 1,
               "e.deck:1: error: print: 'append': a print writes one file, and 'file f1' names a second", NULL, NULL);
}
END_TEST

/* An error shown on a substituted line shows the line as written too: '-var x ""' made a line one
 * word short, and the message showed it with no trace of ${x}. */
START_TEST(error_shows_line_as_written) {
  make_tmpdir();
  Run r = run_child("variable n equal 3\nvariable i loop ${x}\n", "x", "");
  ck_assert_int_eq(r.code, 1);
  ck_assert_str_eq(line_of(r.err, 0), "e.deck:2: error: variable: expected 3 to 4 arguments, got 2");
  ck_assert_str_eq(line_of(r.err, 2), "  variable i loop ");
  ck_assert_str_eq(line_of(r.err, 4), "  (as written: variable i loop ${x})");
  run_free(&r);
  expect_error("variable n equal 3\nvariable i loop $(v_n-5)\n", 1, "e.deck:2: error: variable: count '-2': must be >= 1",
               "  variable i loop -2", "                  ^");
  r = run_child_text("variable n equal 3\nvariable i loop $(v_n-5)\n");
  ck_assert_str_eq(line_of(r.err, 3), "  (as written: variable i loop $(v_n-5))");
  run_free(&r);
  /* a line without substitution has no such line */
  r = run_child_text("variable i loop 0\n");
  ck_assert_int_eq(r.code, 1);
  ck_assert_ptr_null(strstr(r.err, "as written"));
  run_free(&r);
}
END_TEST

/* log() is natural here and base 10 in LAMMPS: the first log() of a deck says so, once, at its
 * line (a LAMMPS deck's log(x) read 2.3 times its value in silence); ln() and log10() say nothing. */
START_TEST(log_is_natural_noted) {
  make_tmpdir();
  Run r = run_child("variable a equal 1\nvariable b equal log(100)\nprint \"$(v_b) $(log(1))\"\n", NULL, NULL);
  ck_assert_msg(r.code == 0, "exit %d: %s", r.code, r.err);
  ck_assert_str_eq(r.out, "4.60517018598809 0\n");
  ck_assert_str_eq(r.err, "e.deck:2: warning: log() is the natural logarithm (as in C and Python; LAMMPS's log() is "
                          "base 10): write ln() for the natural one, log10() for base 10, and this note goes\n");
  run_free(&r);
  r = run_child_text("print \"$(ln(100)) $(log10(100))\"\n");
  ck_assert_msg(r.code == 0, "exit %d: %s", r.code, r.err);
  ck_assert_str_eq(r.out, "4.60517018598809 2\n");
  ck_assert_str_eq(r.err, "");
  run_free(&r);
}
END_TEST

/* Run the deck at path (relative to tdir, the child's working directory), its stdin from the file
 * stdin_from when given; the exit code, stdout in *out. */
static int run_path(const char *path, const char *stdin_from, char **out) {
  char o[600];
  snprintf(o, sizeof o, "%s/path_out.txt", tdir);
  fflush(NULL);
  pid_t pid = fork();
  ck_assert_int_ge(pid, 0);
  if (pid == 0) {
    if (chdir(tdir) || !freopen(o, "w", stdout) || (stdin_from && !freopen(stdin_from, "r", stdin))) _exit(99);
    YfSim sim;
    sim_init(&sim);
    YfDeck *d = deck_new(&sim);
    deck_run_file(d, path, NULL);
    deck_free(d);
    exit(0);
  }
  int st = 0;
  waitpid(pid, &st, 0);
  *out = read_all(o);
  return WIFEXITED(st) ? WEXITSTATUS(st) : 128 + WTERMSIG(st);
}

/* A deck read through a pipe or /dev/stdin finds its files as a deck on standard input does (the
 * working directory) or from the folder of the file behind /dev/stdin: '-in <(python3 gen.py)'
 * (/dev/fd/63) looked for its includes in /dev/fd. */
START_TEST(deck_through_a_pipe_finds_its_files) {
  make_tmpdir();
  write_file("parts/part.deck", "print \"part in parts\"\n");
  write_file("sub/main.deck", "include part.deck\n");
  write_file("sub/part.deck", "print \"part beside the deck\"\n");
  char *out;
  /* /dev/stdin from sub/main.deck: its includes from sub/, as with -in sub/main.deck */
  int code = run_path("/dev/stdin", "sub/main.deck", &out);
  ck_assert_msg(code == 0, "exit %d", code);
  ck_assert_str_eq(out, "part beside the deck\n");
  free(out);
  /* a FIFO in sub/ (as bash's <(...) is one): its includes from the working directory */
  char fifo[600];
  snprintf(fifo, sizeof fifo, "%s/sub/gen.fifo", tdir);
  ck_assert_int_eq(mkfifo(fifo, 0600), 0);
  pid_t w = fork();
  ck_assert_int_ge(w, 0);
  if (w == 0) {
    FILE *fp = fopen(fifo, "w");
    if (!fp) _exit(1);
    fputs("include parts/part.deck\n", fp);
    fclose(fp);
    _exit(0);
  }
  code = run_path("sub/gen.fifo", NULL, &out);
  waitpid(w, NULL, 0);
  ck_assert_msg(code == 0, "exit %d", code);
  ck_assert_str_eq(out, "part in parts\n");
  free(out);
}
END_TEST

/* Text beyond ASCII in a line: the caret stays under the character at fault (it counted bytes,
 * so 'é' and '→' before it put it 4 columns right), and a character an expression cannot read is
 * written whole, with its code and what to write for the ones word processors put in (its first
 * byte alone was printed, a broken character). */
START_TEST(error_unicode_lines) {
  expect_error("print \"h\xc3\xa9llo \xe2\x86\x92 w\xc3\xb6rld\" $(1/0)\n", 1, "e.deck:1: error: expression '1/0': division by zero",
               "  print \"h\xc3\xa9llo \xe2\x86\x92 w\xc3\xb6rld\" $(1/0)", "                           ^");
  expect_error("print $(2 \xc3\x97 3)\n", 1,
               "e.deck:1: error: expression '2 \xc3\x97 3': unexpected '\xc3\x97' (U+00D7, a multiplication sign: write *)", NULL,
               NULL);
  expect_error("variable E equal \xe2\x80\x9c" "1e9\xe2\x80\x9d\n", 1,
               "e.deck:1: error: variable: expression '\xe2\x80\x9c" "1e9\xe2\x80\x9d': expected a number, a name or '(' but found "
               "'\xe2\x80\x9c' (U+201C, a typographic quote: write \" or ')",
               NULL, "                   ^");
  expect_error("print $(2*\xe2\x88\x92" "3)\n", 1,
               "e.deck:1: error: expression '2*\xe2\x88\x92" "3': expected a number, a name or '(' but found '\xe2\x88\x92' "
               "(U+2212, a minus sign: write -)", NULL, NULL);
  expect_error("print $(2\xa0+1)\n", 1, "e.deck:1: error: expression '2\xa0+1': unexpected byte 0xA0 (not UTF-8 text) after number",
               NULL, NULL);
  /* look-alikes the Y2D reader named and the expressions did not (one table now, utf8name.h): a full-width
   * digit, a zero-width space, an overlong encoding of '-' (not UTF-8 text, was decoded as '-') */
  expect_error("print $(2*\xef\xbc\x93)\n", 1,
               "e.deck:1: error: expression '2*\xef\xbc\x93': expected a number, a name or '(' but found '\xef\xbc\x93' "
               "(U+FF13, a full-width digit: write 3)", NULL, NULL);
  expect_error("print $(2\xe2\x80\x8b)\n", 1,
               "e.deck:1: error: expression '2\xe2\x80\x8b': unexpected '\xe2\x80\x8b' (U+200B, a zero-width space: delete it) "
               "after number", NULL, NULL);
  expect_error("print $(2*\xc0\xad""3)\n", 1,
               "e.deck:1: error: expression '2*\xc0\xad""3': expected a number, a name or '(' but found byte 0xC0 (not UTF-8 "
               "text)", NULL, NULL);
}
END_TEST

START_TEST(error_includes) {
  expect_error("variable a equal 1\n\ninclude missing.deck\n", 2,
               "e.deck:3: error: include: cannot open 'missing.deck': No such file or directory", NULL, NULL);
  make_tmpdir();
  write_file("r1.deck", "include r2.deck\n");
  write_file("r2.deck", "include r1.deck\n");
  Run r = run_child("include r1.deck\n", NULL, NULL);
  ck_assert_int_eq(r.code, 1);
  ck_assert_msg(strstr(r.err, "error: include: nesting deeper than 32 levels ('r") &&
                    strstr(r.err, "includes itself, directly or through other files)"),
                "stderr: %s", r.err);
  run_free(&r);
  /* a file beside the working directory, not beside the deck (where LAMMPS would look): said so */
  make_tmpdir();
  write_file("common.deck", "variable c equal 1\n");
  write_file("rows.txt", "0 0\n1 1\n");
  write_file("cases/a.deck", "include common.deck\n");
  write_file("cases/h.deck", "history h file rows.txt\n");
  r = run_child("include cases/a.deck\n", NULL, NULL);
  ck_assert_int_eq(r.code, 2);
  ck_assert_str_eq(line_of(r.err, 0), "cases/a.deck:1: error: include: cannot open 'cases/common.deck': No such file or "
                                      "directory (a deck's files are found from its own folder, 'cases'; the working "
                                      "directory has a 'common.deck', which LAMMPS would read: give its path from the "
                                      "deck's folder, or an absolute one)");
  run_free(&r);
  r = run_child("include cases/h.deck\n", NULL, NULL);
  ck_assert_int_eq(r.code, 2);
  ck_assert_msg(strstr(line_of(r.err, 0), "cases/h.deck:1: error: history: cannot open 'cases/rows.txt': No such file or "
                                          "directory (a deck's files are found from its own folder, 'cases'"),
                "stderr: %s", r.err);
  run_free(&r);
}
END_TEST

/* The argument helpers, on a hand-made command (as a physics handler would call them). */
static YfArgs fake_args(const char *cmd, const char *line, int n, char **w) {
  YfArgs a;
  a.cmd = cmd;
  a.n = n;
  a.w = w;
  a.loc.file = "beam.deck";
  a.loc.line = 14;
  a.line = line;
  return a;
}

/* Run fn in a child and return its stderr (first line in *first) and exit code. */
static int helper_child(void (*fn)(void), char **err) {
  make_tmpdir();
  char path[512];
  snprintf(path, sizeof path, "%s/stderr.txt", tdir);
  fflush(NULL);
  pid_t pid = fork();
  if (pid == 0) {
    if (!freopen(path, "w", stderr)) _exit(99);
    fn();
    exit(0);
  }
  int st = 0;
  waitpid(pid, &st, 0);
  *err = read_all(path);
  return WIFEXITED(st) ? WEXITSTATUS(st) : 128 + WTERMSIG(st);
}

static char *w_fix[] = {"base", "bottom", "fixed", "z"};
static void call_choice(void) {
  static const char *const dirs[] = {"x", "y", "xy", NULL};
  YfArgs a = fake_args("fix", "fix base bottom fixed z", 4, w_fix);
  arg_choice(&a, 3, "direction", dirs);
}
static char *w_num[] = {"3.0x"};
static void call_num(void) {
  YfArgs a = fake_args("timestep", "timestep 3.0x", 1, w_num);
  arg_num(&a, 0, "dt");
}
static char *w_expr[] = {"2*E"};
static void call_num_expr(void) {
  YfArgs a = fake_args("timestep", "timestep 2*E", 1, w_expr);
  arg_num(&a, 0, "dt");
}
static char *w_int[] = {"0"};
static void call_int_range(void) {
  YfArgs a = fake_args("run", "run 0", 1, w_int);
  arg_int(&a, 0, "steps", 1, 100);
}
static char *w_neg[] = {"-1e-3"};
static void call_pos(void) {
  YfArgs a = fake_args("timestep", "timestep -1e-3", 1, w_neg);
  arg_pos(&a, 0, "dt");
}
static void call_word_missing(void) {
  YfArgs a = fake_args("fix", "fix base", 1, w_fix);
  arg_word(&a, 1, "group");
}
static void call_arg_error(void) {
  YfArgs a = fake_args("fix", "fix base bottom fixed z", 4, w_fix);
  arg_error(&a, 1, "no such group");
}

START_TEST(arg_helpers) {
  /* successful conversions */
  char *ok[] = {"2.5e-3", "1e6", "xy", "0"};
  YfArgs a = fake_args("t", "t 2.5e-3 1e6 xy 0", 4, ok);
  static const char *const dirs[] = {"x", "y", "xy", NULL};
  ck_assert_double_eq(arg_num(&a, 0, "v"), 2.5e-3);
  ck_assert_int_eq(arg_int(&a, 1, "n", 0, LONG_MAX), 1000000);
  ck_assert_int_eq(arg_choice(&a, 2, "dir", dirs), 2);
  ck_assert_double_eq(arg_nonneg(&a, 3, "v"), 0.0);
  ck_assert_str_eq(arg_word(&a, 2, "w"), "xy");
  arg_count(&a, 4, 4);
  arg_count(&a, 1, -1);

  static const struct { void (*fn)(void); const char *l0, *l1, *l2; } t[] = {
      {call_choice, "beam.deck:14: error: fix: direction 'z': expected one of x, y, xy", "  fix base bottom fixed z",
       "                        ^"},
      {call_num, "beam.deck:14: error: timestep: dt '3.0x': not a finite number", "  timestep 3.0x", "           ^"},
      {call_num_expr, "beam.deck:14: error: timestep: dt '2*E': not a finite number (write an expression as $(...))",
       NULL, NULL},
      {call_int_range, "beam.deck:14: error: run: steps '0': must be in [1, 100]", NULL, NULL},
      {call_pos, "beam.deck:14: error: timestep: dt '-1e-3': must be > 0", NULL, NULL},
      {call_word_missing, "beam.deck:14: error: fix: missing group", NULL, NULL},
      {call_arg_error, "beam.deck:14: error: fix: 'bottom': no such group", "  fix base bottom fixed z",
       "           ^"},
  };
  for (size_t i = 0; i < sizeof t / sizeof t[0]; i++) {
    char *err;
    int code = helper_child(t[i].fn, &err);
    ck_assert_msg(code == 1, "case %zu: exit %d, stderr %s", i, code, err);
    ck_assert_str_eq(line_of(err, 0), t[i].l0);
    if (t[i].l1) ck_assert_str_eq(line_of(err, 1), t[i].l1);
    if (t[i].l2) ck_assert_str_eq(line_of(err, 2), t[i].l2);
    free(err);
  }
}
END_TEST

/* Exit codes through Check's own fork mode (decks from memory streams: nothing to clean up). */
static void run_text_stream(const char *text) {
  static char buf[256];
  snprintf(buf, sizeof buf, "%s", text);
  FILE *fp = fmemopen(buf, strlen(buf), "r");
  YfSim sim;
  memset(&sim, 0, sizeof sim);
  YfDeck *d = deck_new(&sim);
  if (!freopen("/dev/null", "w", stderr)) return;
  deck_run_stream(d, fp, "<stdin>");
}

START_TEST(exit_deck_error) { run_text_stream("variable a equal 1\nfxi 1\n"); }
END_TEST

START_TEST(exit_missing_include) { run_text_stream("include /nonexistent/yf_no_such_file.deck\n"); }
END_TEST

/* Line endings: a deck and every table it reads (history, nodes, triangles, a Gmsh mesh) give the
 * same scene with LF, CRLF and CR-alone (classic Mac) ends.  A CR alone was dropped, so the deck
 * became one line of run-together words ("plane_stressmesh"), and a table one long row. */
static void write_eol(const char *path, const char *text, const char *eol) {
  FILE *f = fopen(path, "w");
  ck_assert_ptr_nonnull(f);
  for (const char *c = text; *c; c++)
    if (*c == '\n') fputs(eol, f);
    else fputc(*c, f);
  fclose(f);
}

START_TEST(line_endings_any) {
  static const char *eols[] = {"\n", "\r\n", "\r", "\r\r\n"}; /* the last: a text converted twice */
  const char *deck = "# a block of inline triangles and a Gmsh body\n"
                     "material m elastic rho 1000 E 1e9 nu 0.25 plane_stress\n"
                     "nodes n.txt blk\ntriangles t.txt blk\n"
                     "mesh gmsh g m.msh material m\n"
                     "history h file h.txt\n"
                     "load push point at 3 1 0 -100 history h\n"
                     "timestep auto\nrun 20\n";
  char *msh = yft_slurp("decks/meshes/square4.msh", 0);
  ck_assert_ptr_nonnull(msh);
  uint64_t hash[4];
  int nt[4];
  for (int k = 0; k < 4; k++) {
    char tmpl[] = "/tmp/yft_eol_XXXXXX", p[512];
    char *dir = mkdtemp(tmpl);
    ck_assert_ptr_nonnull(dir);
    snprintf(p, sizeof p, "%s/n.txt", dir);
    write_eol(p, "# id x y\n1 2 0\n2 3 0\n3 3 1\n4 2 1\n", eols[k]);
    snprintf(p, sizeof p, "%s/t.txt", dir);
    write_eol(p, "1 1 2 3 m\n2 1 3 4 m\n", eols[k]);
    snprintf(p, sizeof p, "%s/h.txt", dir);
    write_eol(p, "0 0\n1e-4 1 # ramp\n1 1\n", eols[k]);
    snprintf(p, sizeof p, "%s/m.msh", dir);
    write_eol(p, msh, eols[k]);
    snprintf(p, sizeof p, "%s/e.deck", dir);
    write_eol(p, deck, eols[k]);
    YfSim *s = yft_run_deck(p, NULL);
    hash[k] = sim_state_hash(s);
    nt[k] = s->model.tri.n;
    ck_assert_msg(s->step == 20, "ending %d: %ld steps", k, s->step);
    char cmd[600];
    snprintf(cmd, sizeof cmd, "rm -rf %s", dir);
    ck_assert_int_eq(system(cmd), 0);
  }
  free(msh);
  /* a .y deck's messages name the line in any of them (a CR alone counted no line: 'line 1') */
  char *y = yft_slurp("tests/y2d/decks/a_elastic_block.y", 0);
  ck_assert_ptr_nonnull(y);
  char *at = strstr(y, "/YD/YDC/DCSTEC ");
  ck_assert_ptr_nonnull(at);
  memcpy(at + 15, "abc    ", 7);
  int line = 1;
  for (const char *c = y; c < at; c++) line += *c == '\n';
  for (int k = 0; k < 4; k++) {
    make_tmpdir();
    char p[600], want[64];
    snprintf(p, sizeof p, "%s/bad.y", tdir);
    write_eol(p, y, eols[k]);
    Run r = run_child("read_y2d bad.y\n", NULL, NULL);
    snprintf(want, sizeof want, "bad.y:%d: error: /YD/YDC/DCSTEC: 'abc", line);
    ck_assert_msg(r.code == 1 && strstr(r.err, want), "ending %d: exit %d: %s", k, r.code, r.err);
    run_free(&r);
  }
  free(y);
  ck_assert_int_eq(nt[0], 2 + 4);
  for (int k = 1; k < 4; k++) {
    ck_assert_int_eq(nt[k], nt[0]);
    ck_assert_msg(hash[k] == hash[0], "ending %d: state hash %016llx, LF %016llx", k, (unsigned long long)hash[k],
                  (unsigned long long)hash[0]);
  }
}
END_TEST

/* A variable named as a built-in (time, pi, ke, ux_G...) hides it from bare expressions: the
 * deck says so once, at the first line that reads it bare; v_NAME says the variable is meant and
 * is quiet.  'variable pi equal 3' made $(2*pi) read 6 without a word. */
START_TEST(variable_hiding_builtin_warned) {
  make_tmpdir();
  Run r = run_child("variable pi equal 3\nvariable tm equal 2\nprint \"$(v_pi) $(v_tm) $(tm)\"\n"
                    "print \"$(2*pi)\"\nprint \"$(pi)\"\n", NULL, NULL);
  ck_assert_msg(r.code == 0 && strstr(r.out, "3 2 2\n6\n3\n"), "exit %d: %s%s", r.code, r.out, r.err);
  const char *w = "e.deck:4: warning: 'pi' in an expression reads your variable 'pi', which hides the built-in 'pi'";
  const char *at = strstr(r.err, w);
  ck_assert_msg(at && !strstr(at + strlen(w), "warning"), "one warning at line 4 expected: %s", r.err);
  run_free(&r);
  r = run_child("variable ux_b equal 7\nmaterial m elastic rho 1000 E 1e9 nu 0.25 plane_stress\n"
                "mesh rect b m 0 0 1 1 2 2\nprint \"$(ux_b)\"\n", NULL, NULL);
  ck_assert_msg(r.code == 0 && strstr(r.err, "e.deck:4: warning: 'ux_b' in an expression reads your variable"),
                "exit %d: %s", r.code, r.err);
  run_free(&r);
  /* x_c of a centre point, with no group or body c: hides nothing, quiet */
  r = run_child("variable x_c equal 0.5\nvariable fx_total equal 2\nmaterial m elastic rho 1000 E 1e9 nu 0.25 plane_stress\n"
                "mesh rect b m 0 0 1 1 2 2\nprint \"$(x_c*fx_total)\"\n", NULL, NULL);
  ck_assert_msg(r.code == 0 && strstr(r.out, "1\n") && !strstr(r.err, "warning"), "exit %d: %s%s", r.code, r.out, r.err);
  run_free(&r);
}
END_TEST

/* fx_G, fy_G include gravity's m g: internal forces of a free body sum to zero, so the sum over
 * the body is its weight at any step (it read 0; a support group's sum missed its own nodes'
 * weight, 359.7 of a hanging block's 392.4 N/m). */
START_TEST(group_force_includes_gravity) {
  make_tmpdir();
  Run r = run_child("material m elastic rho 1000 E 1e9 nu 0.25 plane_stress\nmesh rect b m 0 0 1 0.2 5 2\n"
                    "gravity 0 -9.81\ntimestep auto\nrun 20\n"
                    "print \"W $(fy_b / (-9.81 * mass_b)) $(fx_b)\"\n", NULL, NULL);
  ck_assert_msg(r.code == 0, "exit %d: %s", r.code, r.err);
  const char *w = strstr(r.out, "W ");
  ck_assert_ptr_nonnull(w);
  double ratio = 1, fx = 1;
  ck_assert_int_eq(sscanf(w, "W %lf %lf", &ratio, &fx), 2);
  ck_assert_msg(fabs(ratio - 1.0) < 1e-9 && fabs(fx) < 1e-6, "fy_b / weight %.17g, fx_b %g", ratio, fx);
  run_free(&r);
}
END_TEST

Suite *deck_suite(void) {
  Suite *s = suite_create("deck");
  TCase *tc = tcase_create("expressions");
  tcase_add_checked_fixture(tc, NULL, remove_tmpdir);
  tcase_add_test(tc, expr_precedence);
  tcase_add_test(tc, expr_functions);
  tcase_add_test(tc, expr_errors);
  tcase_add_test(tc, strict_numbers);
  tcase_add_test(tc, nearest);
  suite_add_tcase(s, tc);

  tc = tcase_create("interpreter");
  tcase_add_checked_fixture(tc, NULL, remove_tmpdir);
  tcase_add_test(tc, loop_sum);
  tcase_add_test(tc, index_and_loop_ranges);
  tcase_add_test(tc, loop_pad);
  tcase_add_test(tc, integers_substitute_whole);
  tcase_add_test(tc, equal_is_lazy);
  tcase_add_test(tc, cmdline_var_wins);
  tcase_add_test(tc, if_branches);
  tcase_add_test(tc, if_condition_errors_are_not_strings);
  tcase_add_test(tc, include_relative);
  tcase_add_test(tc, deck_through_a_pipe_finds_its_files);
  tcase_add_test(tc, quit_stops);
  tcase_add_test(tc, substitution_and_quotes);
  tcase_add_test(tc, echo_and_stdin);
  suite_add_tcase(s, tc);

  tc = tcase_create("errors");
  tcase_add_checked_fixture(tc, NULL, remove_tmpdir);
  tcase_add_test(tc, error_unknown_command);
  tcase_add_test(tc, error_lines_after_continuation_and_include);
  tcase_add_test(tc, error_expressions_and_variables);
  tcase_add_test(tc, error_unknown_variable_hints);
  tcase_add_test(tc, print_to_file);
  tcase_add_test(tc, error_includes);
  tcase_add_test(tc, error_shows_line_as_written);
  tcase_add_test(tc, error_unicode_lines);
  tcase_add_test(tc, log_is_natural_noted);
  tcase_add_test(tc, error_long_names);
  tcase_add_test(tc, error_long_variable_names);
  tcase_add_test(tc, error_outputs_share_a_file);
  tcase_add_test(tc, error_history_file_rows);
  tcase_add_test(tc, error_quantities_before_run);
  tcase_add_test(tc, dt_known_when_run_computes_it);
  tcase_add_test(tc, error_group_name_an_expression_cannot_hold);
  tcase_add_test(tc, arg_helpers);
  tcase_add_test(tc, line_endings_any);
  tcase_add_test(tc, variable_hiding_builtin_warned);
  tcase_add_test(tc, group_force_includes_gravity);
  tcase_add_test(tc, error_point_off_the_mesh);
  tcase_add_exit_test(tc, exit_deck_error, 1);
  tcase_add_exit_test(tc, exit_missing_include, 2);
  suite_add_tcase(s, tc);
  return s;
}
