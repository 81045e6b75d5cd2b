/* check_y2d_read.c: the Y2D (.y) deck reader.
 *
 * Three layers: (1) the four reference decks of /work/shared/y2d (copied to tests/y2d/decks)
 * give the counts of the README table and the values written in them (exact: the reader must
 * not change a digit); (2) the array syntaxes (codes 12/21, 3D permutations), defaults, the
 * prefix rule and $YINCL relative to the deck; (3) malformed decks in tests/y2d_bad each end
 * the process with the documented exit code and a "FILE:LINE: error:" message naming the key.
 * Error cases run y2d_read in a forked child with stderr captured in a file.
 */
#include <check.h>
#include <malloc.h>
#include <setjmp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>
#include "contact.h"
#include "err.h"
#include "run.h"
#include "summary.h"
#include "y2d_model.h"
#include "y2d_read.h"
#include "yftest.h"

#define DECKS "tests/y2d/decks/"
#define BAD "tests/y2d_bad/"

/* ------------------------------------------------------------------ reference decks */

static const struct {
  const char *file;
  long tris, nodes, steps;
  double dt;
} refs[] = {
  {DECKS "a_elastic_block.y", 736, 440, 4000, 2.5e-7},
  {DECKS "b_beam_impact.y", 1080, 628, 15000, 1.0e-7},
  {DECKS "c_column_impact.y", 952, 541, 9000, 6.0e-8},
  {DECKS "d1_cantilever_bc.y", 720, 427, 16000, 2.5e-7},
};

START_TEST(test_reference_counts) {
  YfY2d y;
  y2d_read(refs[_i].file, &y, NULL);
  ck_assert_int_eq(y.nelem, refs[_i].tris);
  ck_assert_int_eq(y.nnopo, refs[_i].nodes);
  ck_assert_int_eq(y.mcstep, refs[_i].steps);
  ck_assert(y.dcstec == refs[_i].dt); /* the literal in the deck, read exactly */
  ck_assert_int_eq(y.has_ydoit, 1);
  ck_assert_int_eq(y.mnodim, 2);
  /* every input node has a valid BC set and every triangle a property (checked on read) */
  for (long n = 0; n < y.nnopo; n++) ck_assert(y.i1nopr[n] >= 0 && y.i1nopr[n] < y.npnset);
  /* D2NCC is given in these decks and equals D2NCI (no pre-strain) */
  ck_assert_int_eq(y.given[Y2D_N_D2NCC], 1);
  for (long i = 0; i < 2 * y.nnopo; i++) ck_assert(y.d2ncc[i] == y.d2nci[i]);
  y2d_free(&y);
}
END_TEST

START_TEST(test_beam_values) {
  YfY2d y;
  y2d_read(DECKS "b_beam_impact.y", &y, NULL);
  ck_assert_int_eq(y.nprop, 3);
  ck_assert(y.d1pero[0] == 2340 && y.d1pero[1] == 30000);
  ck_assert(y.d1pela[0] == 4836709384.042993);
  ck_assert(y.d1pemu[1] == 80769230769.23077);
  ck_assert(y.d1pepe[2] == 1e11);
  ck_assert_int_eq(y.npjset, 2);
  ck_assert(y.d1pjft[0] == 3.15e6 && y.d1pjgf[0] == 300 && y.d1pjgf[1] == 3e12);
  /* meshing rows: [k, code, p] = [1 3 0], [1 3 1]; I2PMIJ [0 0 0], [1 1 1] */
  ck_assert_int_eq(y.mpmcom, 2);
  ck_assert_int_eq(y.mpmcol, 3);
  const int set[6] = {1, 3, 0, 1, 3, 1}, ij[6] = {0, 0, 0, 1, 1, 1};
  for (int i = 0; i < 6; i++) ck_assert_int_eq(y.i2pmset[i], set[i]);
  for (int i = 0; i < 6; i++) ck_assert_int_eq(y.i2pmij[i], ij[i]);
  /* BC sets: 0 free (force 0), 1 fixed (velocity 0) */
  ck_assert_int_eq(y.i1pnfx[0], 1);
  ck_assert_int_eq(y.i1pnfx[1], 3);
  ck_assert(y.d1pnay[1] == 0.0);
  ck_assert_int_eq(y.micoup, 27000);
  ck_assert_int_eq(y.mistate, 6);
  ck_assert(y.diezon == 0.0014999999999999846);
  /* the where[] of a key is its line in the .y file */
  ck_assert_int_eq(y.where[Y2D_I_MICOUP].line, 3113);
  ck_assert_int_eq(y.where[Y2D_PM_I2PMSET].line, 3160);
  ck_assert_str_eq(y.where[Y2D_PM_I2PMSET].file, DECKS "b_beam_impact.y");
  y2d_free(&y);
}
END_TEST

START_TEST(test_cantilever_bc_tables) {
  YfY2d y;
  y2d_read(DECKS "d1_cantilever_bc.y", &y, NULL);
  /* topology: first two triangles as written (21 ordering: one row per element) */
  const int t01[6] = {0, 1, 62, 0, 62, 61};
  for (int k = 0; k < 3; k++) {
    ck_assert_int_eq(y.i2elto[0 * y.melno + k], t01[k]);
    ck_assert_int_eq(y.i2elto[1 * y.melno + k], t01[3 + k]);
  }
  ck_assert(y.d2nci[2 * 1] == 0.0050000000000000001 && y.d2nci[2 * 1 + 1] == 0.0);
  ck_assert_int_eq(y.npnset, 5);
  ck_assert(y.i1pnfy[2] == 1 && y.d1pnay[2] == -20000); /* tip point load */
  ck_assert(y.d1pnap[3] == 2e6);                        /* pressure patch  */
  ck_assert(y.i1pnfy[4] == 3 && y.d1pnay[4] == 0.5);    /* velocity pulse  */
  /* D3PNFAC 123 2 5 4: all times set by set, then all factors */
  ck_assert_int_eq(y.npnfact, 4);
  ck_assert_int_eq(y.tables_on, 1);
  const double t2[4] = {0.0, 0.00050000000000000001, 0.00059999999999999995, 0.040000000000000001};
  const double f2[4] = {0, 1, 1, 1};
  const double t3[4] = {0.0, 0.00020000000000000001, 0.00040000000000000002, 0.040000000000000001};
  const double f3[4] = {0, 1, 0, 0};
  const double t4[4] = {0.0, 5e-05, 0.0001, 0.040000000000000001};
  for (int p = 0; p < 4; p++) {
    ck_assert(y2d_fac_time(&y, 2, p) == t2[p] && y2d_fac_value(&y, 2, p) == f2[p]);
    ck_assert(y2d_fac_time(&y, 3, p) == t3[p] && y2d_fac_value(&y, 3, p) == f3[p]);
    ck_assert(y2d_fac_time(&y, 4, p) == t4[p] && y2d_fac_value(&y, 4, p) == f3[p]);
    ck_assert(y2d_fac_value(&y, 0, p) == 1.0);
  }
  y2d_free(&y);
}
END_TEST

/* ------------------------------------------------------------------ syntax and defaults */

/* The tiny deck of tests/y2d/tiny.y with line 11 (I2ELTO) and the keys before $YDOIT
 * replaceable, written to a temporary file. */
static const char *tiny_head =
  "/* tiny deck */\n/YD/YDC/MCSTEP 10\n/YD/YDC/DCSTEC 1e-6\n/YD/YDE/MELEM 2\n/YD/YDE/NELEM 2\n"
  "/YD/YDE/MELST 1\n/YD/YDE/NELST 1\n/YD/YDE/MELNO 3\n/YD/YDE/NELNO 3\n/YD/YDE/I1ELPR 2 0 0\n";
static const char *tiny_tail =
  "/YD/YDN/MNODIM 2\n/YD/YDN/NNODIM 2\n/YD/YDN/MNOPO 4\n/YD/YDN/NNOPO 4\n"
  "/YD/YDN/D2NCI 21 2 4 0 0 1 0 1 1 0 1\n/YD/YDN/I1NOPR 4 0 0 0 0\n/YD/YDN/I1NOBF 4 1 1 1 1\n"
  "/YD/YDI/MICOUP 10\n/YD/YDI/MISTATE 6\n/YD/YDPE/MPROP 1\n/YD/YDPE/NPROP 1\n"
  "/YD/YDPE/I1PTYP 1 1\n/YD/YDPE/D1PERO 1 2000\n/YD/YDPE/D1PELA 1 1e9\n/YD/YDPE/D1PEMU 1 1e9\n"
  "/YD/YDPE/D1PEPE 1 1e10\n/YD/YDPE/D1PEPT 1 1e9\n/YD/YDPN/MPNSET 2\n/YD/YDPN/NPNSET 2\n"
  "/YD/YDPN/I1PNFX 2 1 3\n/YD/YDPN/I1PNFY 2 1 3\n/YD/YDPN/D1PNAX 2 0 0\n/YD/YDPN/D1PNAY 2 0 0\n";

static void write_tiny(char *path, const char *elto, const char *extra) {
  strcpy(path, "/tmp/y2d_testXXXXXX.y");
  int fd = mkstemps(path, 2);
  ck_assert(fd >= 0);
  FILE *f = fdopen(fd, "w");
  fprintf(f, "%s%s\n%s%s\n$YDOIT\n$YSTOP\n", tiny_head, elto, tiny_tail, extra);
  fclose(f);
}

START_TEST(test_array_orders) {
  char path[64];
  /* code 12: dimension 1 (node slot) outermost: slot 0 of both elements, then slot 1, slot 2;
   * D3PNFAC 321: table point outermost, then set, then time/factor */
  write_tiny(path, "/YD/YDE/I2ELTO 12 3 2  0 0  1 2  2 3",
             "/YD/YDPN/MPNFACT 2\n/YD/YDPN/NPNFACT 2\n"
             "/YD/YDPN/D3PNFAC 321 2 2 2  0 0.5  0 0.25  1 1.5  2 2.5\n");
  YfY2d y;
  y2d_read(path, &y, NULL);
  unlink(path);
  const int t[6] = {0, 1, 2, 0, 2, 3};
  for (int i = 0; i < 6; i++) ck_assert_int_eq(y.i2elto[i], t[i]);
  /* value order (p, s, c): p0 s0: t=0 f=0.5; p0 s1: t=0 f=0.25; p1 s0: t=1 f=1.5; p1 s1: 2, 2.5 */
  ck_assert(y2d_fac_time(&y, 0, 0) == 0 && y2d_fac_value(&y, 0, 0) == 0.5);
  ck_assert(y2d_fac_time(&y, 1, 0) == 0 && y2d_fac_value(&y, 1, 0) == 0.25);
  ck_assert(y2d_fac_time(&y, 0, 1) == 1 && y2d_fac_value(&y, 0, 1) == 1.5);
  ck_assert(y2d_fac_time(&y, 1, 1) == 2 && y2d_fac_value(&y, 1, 1) == 2.5);
  y2d_free(&y);
}
END_TEST

START_TEST(test_defaults_and_prefix) {
  char path[64];
  /* MCSTEPXYZ is MCSTEP under the anchor's prefix rule; MNODIMX is MNODIM (5 characters) */
  write_tiny(path, "/YD/YDE/I2ELTO 21 3 2 0 1 2 0 2 3", "/YD/YDC/MCSTEPXYZ 77\n");
  YfY2d y;
  y2d_read(path, &y, NULL);
  unlink(path);
  ck_assert_int_eq(y.mcstep, 77);
  ck_assert_int_eq(y.where[Y2D_C_MCSTEP].line, 35);
  /* FORMAT.md defaults of keys the deck does not give */
  ck_assert_int_eq(y.icoutf, 10);
  ck_assert_int_eq(y.icoutp, 4);
  ck_assert_int_eq(y.icshtf, 100);
  ck_assert_int_eq(y.iwfast, 1);
  ck_assert_int_eq(y.iiecff, -2);
  ck_assert(y.diedi == 1e15 && y.dcsizc == 1 && y.dcsizv == 1 && y.dohyp == 0.05);
  ck_assert(y.d1pnxx[1] == 1 && y.d1pnxy[1] == 0 && y.d1pnyx[1] == 0 && y.d1pnyy[1] == 1);
  ck_assert(y.d1pnap[0] == 0 && y.d1pnat[1] == 0);
  ck_assert(y.d1peks[0] == 0 && y.d1pefr[0] == 0);
  ck_assert_int_eq(y.i1pefr[0], -1);
  ck_assert_int_eq(y.given[Y2D_PE_D1PEKS], 0);
  ck_assert_int_eq(y.given[Y2D_PE_D1PEPT], 1);
  /* D2NCC not given: copy of D2NCI; D2NVC zero */
  ck_assert_int_eq(y.given[Y2D_N_D2NCC], 0);
  for (int i = 0; i < 8; i++) ck_assert(y.d2ncc[i] == y.d2nci[i] && y.d2nvc[i] == 0);
  ck_assert(y.d2nci[2 * 2] == 1 && y.d2nci[2 * 2 + 1] == 1);
  y2d_free(&y);
  ck_assert_int_eq(y2d_is_y_file("a/b/beam.y"), 1);
  ck_assert_int_eq(y2d_is_y_file("beam.deck"), 0);
  ck_assert_int_eq(y2d_is_y_file("beam.yh0"), 0);
}
END_TEST

START_TEST(test_include_relative_to_deck) {
  /* tiny_incl.y says "$YINCL tiny_part.inc"; the test runs from the repo root, so the file is
   * found only relative to the deck's directory */
  YfY2d a, b;
  y2d_read("tests/y2d/tiny.y", &a, NULL);
  y2d_read("tests/y2d/tiny_incl.y", &b, NULL);
  ck_assert_int_eq(a.nprop, b.nprop);
  ck_assert(a.d1pero[0] == b.d1pero[0] && a.d1pept[0] == b.d1pept[0]);
  ck_assert_str_eq(b.where[Y2D_PE_D1PERO].file, "tests/y2d/tiny_part.inc");
  ck_assert_int_eq(b.where[Y2D_PE_D1PERO].line, 4);
  ck_assert_int_eq(b.where[Y2D_PN_MPNSET].line, 22); /* back in the including file */
  y2d_free(&a);
  y2d_free(&b);
}
END_TEST

/* ------------------------------------------------------------------ errors */

/* Run y2d_read(path) in a child; return its exit status, stderr in msg. */
static int run_child(const char *path, char *msg, size_t cap) {
  char tmp[] = "/tmp/y2d_errXXXXXX";
  int fd = mkstemp(tmp);
  ck_assert(fd >= 0);
  fflush(stderr);
  pid_t pid = fork();
  ck_assert(pid >= 0);
  if (pid == 0) {
    dup2(fd, 2);
    YfY2d y;
    y2d_read(path, &y, NULL);
    _exit(0);
  }
  int st = 0;
  waitpid(pid, &st, 0);
  FILE *f = fdopen(fd, "r");
  rewind(f);
  size_t n = fread(msg, 1, cap - 1, f);
  msg[n] = 0;
  fclose(f);
  unlink(tmp);
  return WIFEXITED(st) ? WEXITSTATUS(st) : 128 + WTERMSIG(st);
}

static const struct {
  const char *file;
  int code, line;
  const char *text; /* must appear after "FILE:LINE: error: " */
} bad[] = {
  {"unknown_key.y", 1, 2, "/YD/YDC/MCSTPE: unknown key in /YD/YDC/ (did you mean MCSTEP?)"},
  {"unknown_group.y", 1, 3, "unknown group /YD/YDX/ (did you mean /YD/YDC/?)"},
  {"ygeo_key.y", 1, 25, "/YD/YDPE/D1PEEM: Y-Geo key, not in Y2D"},
  {"ygeo_group.y", 1, 35, "/YD/YDFN/MFNSET: Y-Geo group"},
  {"short_array.y", 1, 10, "/YD/YDE/I1ELPR: expected 2 values, found 1 before '/YD/YDE/I2ELTO'"},
  {"real_for_int.y", 1, 2, "/YD/YDC/MCSTEP: '4e3' is not an integer"},
  /* a decimal comma said as such, with the number to write (2026-11-29 sweep: only "not a number") */
  {"decimal_comma.y", 1, 4, "/YD/YDC/DCGRAY: '-9,81' is not a number (a decimal comma: Y2D reads C reals (%le) with a "
                            "decimal point and stops at the ','; write -9.81)"},
  {"array_before_cap.y", 1, 4, "/YD/YDE/I1ELPR: read before its capacity /YD/YDE/MELEM"},
  /* a set given out of range freezes its node (FORMAT.md 6, test_frozen_set); one not given is a mistake */
  {"set_list_short.y", 1, 18, "/YD/YDN/I1NOPR: node 3 has no BC set (not given: the list is shorter than NNOPO = 4"},
  {"missing_required.y", 1, 34, "/YD/YDN/D2NCI is required"},
  {"unterminated_comment.y", 1, 35, "unterminated comment"},
  {"comment_too_long.y", 1, 1, "longer than 100 tokens"},
  {"missing_include.y", 2, 5, "$YINCL no_such_file.inc: cannot open"},
  {"non_numeric.y", 1, 25, "/YD/YDPE/D1PERO: '2e3x' is not a number"},
  {"count_over_capacity.y", 1, 10, "/YD/YDE/I1ELPR: n = 3 entries exceed the capacity 2 given by /YD/YDE/MELEM"},
  {"stray_value.y", 1, 10, "unexpected value '0'"},
  {"mistate_small.y", 1, 20, "/YD/YDI/MISTATE = 3 with /YD/YDI/MICOUP = 10"},
  {"pept_missing.y", 1, 34, "/YD/YDPE/D1PEPT (tangential contact penalty) is required"},
  {"two_sections.y", 1, 36, "'/YD/YDC/MCSTEP' after $YDOIT"},
  {"clockwise.y", 1, 11, "not counter-clockwise, first element 1"},
  {"negative_size.y", 1, 4, "/YD/YDE/MELEM: negative value -2"},
  {"no_bc_set.y", 1, 30, "/YD/YDPN/NPNSET = 0 must be >= 1"},
  {"other_derivative.y", 1, 4, "/YD/YDC/ICSAVF: not a Y2D key (restart save frequency"},
  {"ygeo_ydp_group.y", 1, 21, "/YD/YDP/MPROP: Y-Geo group /YD/YDP/"},
  {"nnodim3.y", 1, 13, "/YD/YDN/NNODIM = 3: yfdem reads 2D decks only"},
  /* a NUL in MCSTEP's value ran 1 step silently (the token was cut at it) until 2026-11-28 */
  {"nul_byte.y", 1, 2, "a NUL byte in a token: a .y deck is plain text"},
};

START_TEST(test_bad_decks) {
  char path[256], msg[4096], want[512];
  snprintf(path, sizeof path, BAD "%s", bad[_i].file);
  int code = run_child(path, msg, sizeof msg);
  ck_assert_msg(code == bad[_i].code, "%s: exit %d, expected %d; stderr: %s", path, code,
                bad[_i].code, msg);
  snprintf(want, sizeof want, "%s:%d: error: ", path, bad[_i].line);
  const char *p = strstr(msg, want);
  ck_assert_msg(p != NULL, "%s: no '%s' in: %s", path, want, msg);
  ck_assert_msg(strstr(p, bad[_i].text) != NULL, "%s: no '%s' in: %s", path, bad[_i].text, msg);
}
END_TEST

START_TEST(test_missing_deck) {
  char msg[1024];
  int code = run_child("tests/y2d_bad/does_not_exist.y", msg, sizeof msg);
  ck_assert_int_eq(code, 2);
  ck_assert_ptr_nonnull(strstr(msg, "cannot open Y2D deck 'tests/y2d_bad/does_not_exist.y'"));
}
END_TEST

/* A Y2D deck under another name (no extension, or on standard input) is read as a native deck:
 * its first word is refused with a hint to name it .y or read it with read_y2d (it was "unknown
 * command '/ *' (did you mean 'if'?)"); FILE.Y runs as FILE.y does. */
START_TEST(test_y2d_deck_misnamed) {
  char *text = yft_slurp("tests/y2d/decks/a_elastic_block.y", 0);
  ck_assert_ptr_nonnull(text);
  char *err = NULL, *dir = NULL;
  int code = yft_run_binary("model", text, NULL, &err, &dir);
  fprintf(stderr, "y2d_read: a .y deck named 'model': exit %d: %s", code, err);
  ck_assert_int_eq(code, 1);
  ck_assert_ptr_nonnull(strstr(err, "model:1: error: unknown command '/*': this looks like a Y2D .y deck"));
  ck_assert_ptr_nonnull(strstr(err, "read_y2d FILE"));
  free(err);
  free(dir);
  /* MCSTEP 4000 -> 20: the same deck, short */
  char *m = strstr(text, "/YD/YDC/MCSTEP 4000");
  ck_assert_ptr_nonnull(m);
  memcpy(m, "/YD/YDC/MCSTEP   20", 19);
  code = yft_run_binary("MODEL.Y", text, "-summary s.json", &err, &dir);
  ck_assert_msg(code == 0, "MODEL.Y: exit %d: %s", code, err);
  char p[600];
  snprintf(p, sizeof p, "%s/s.json", dir);
  char *j = yft_slurp(p, 0);
  ck_assert_ptr_nonnull(strstr(j, "\"steps\": 20,"));
  free(j);
  free(err);
  free(dir);
  free(text);
}
END_TEST

/* MICOUP is Y2D's couple capacity: a search that finds more stops Y2D ("Ycd: to small meicoc").
 * yfdem's list grows, so the beam with MICOUP 3 runs; it warns once, at the deck's MICOUP line,
 * with the step and the count (it ran silently, 2026-11-28), and the run is the one of the
 * deck's own MICOUP (the capacity changes nothing else). */
static char *beam_with_micoup(const char *micoup, int *code, char **err) {
  char *text = yft_slurp("tests/y2d/decks/b_beam_impact.y", 0);
  ck_assert_ptr_nonnull(text);
  char *m = strstr(text, "/YD/YDC/MCSTEP 15000");
  ck_assert_ptr_nonnull(m);
  memcpy(m, "/YD/YDC/MCSTEP    40", 20);
  m = strstr(text, "/YD/YDI/MICOUP 27000");
  ck_assert_ptr_nonnull(m);
  memcpy(m + 15, micoup, 5);
  char *dir = NULL;
  *code = yft_run_binary("beam.y", text, "-summary s.json", err, &dir);
  char p[600];
  snprintf(p, sizeof p, "%s/s.json", dir);
  char *j = yft_slurp(p, 0);
  free(dir);
  free(text);
  return j;
}

START_TEST(test_couple_capacity_warned) {
  int code;
  char *err;
  char *small = beam_with_micoup("3    ", &code, &err);
  fprintf(stderr, "y2d_read: the beam with MICOUP 3: %s", err);
  ck_assert_int_eq(code, 0);
  int line = 0;
  char *text = yft_slurp("tests/y2d/decks/b_beam_impact.y", 0);
  for (char *p = text; p < strstr(text, "/YD/YDI/MICOUP"); p++) line += *p == '\n';
  free(text);
  char want[64];
  snprintf(want, sizeof want, "beam.y:%d: warning: step ", line + 1);
  ck_assert_msg(strstr(err, want) && strstr(err, "couples, more than /YD/YDI/MICOUP = 3: Y2D stops here"),
                "no capacity warning at the MICOUP line:\n%s", err);
  int warnings = 0;
  for (const char *p = err; (p = strstr(p, "to small meicoc")) != NULL; p++) warnings++;
  ck_assert_int_eq(warnings, 1);
  free(err);
  char *big = beam_with_micoup("27000", &code, &err);
  ck_assert_int_eq(code, 0);
  ck_assert_msg(!strstr(err, "meicoc"), "a capacity warning with MICOUP 27000:\n%s", err);
  const char *h1 = strstr(small, "\"state_hash\""), *h2 = strstr(big, "\"state_hash\"");
  ck_assert_msg(h1 && h2 && !strncmp(h1, h2, 40), "MICOUP changed the run:\n%s\n%s", small, big);
  free(err);
  free(small);
  free(big);
}
END_TEST

/* Y2D moves no node of mass <= 1e-10 (ALGORITHMS 7, 9): in tonnes and millimetres with 0.1 mm
 * cells every node is such a node, and with an initial velocity of 1000 mm/s none moves in Y2D,
 * its velocity kept.  yfdem moved them all (ux 1e-4 mm after 100 steps), with native mass damping
 * too. */
START_TEST(test_massless_nodes_stay) {
  static const char *const decks[] = {"read_y2d tests/y2d/lowmass.y\nrun\n",
                                      "read_y2d tests/y2d/lowmass.y\ndamping mass 10\nrun\n"};
  for (int k = 0; k < 2; k++) {
    YfSim *s = yft_run(decks[k]);
    ck_assert_int_eq(s->step, 100);
    const YfNodes *n = &s->model.node;
    ck_assert_int_gt(n->n, 0);
    for (int i = 0; i < n->n; i++) {
      ck_assert_msg(n->m[i] > 0 && n->m[i] < 1e-10, "node %d mass %g", i, n->m[i]);
      ck_assert_msg(n->x[i] == n->x0[i] && n->y[i] == n->y0[i], "deck %d: node %d moved by (%g, %g)", k, i,
                    n->x[i] - n->x0[i], n->y[i] - n->y0[i]);
      ck_assert_msg(n->vx[i] == 1000.0, "deck %d: node %d vx %g, its initial 1000 kept in Y2D", k, i, n->vx[i]);
    }
  }
}
END_TEST

/* `yfdem DECK.y` computes nothing when the deck stops at $YSTOP before any $YDOIT, as Y2D
 * (FORMAT.md 1.2): a $YDOIT commented out ran all its steps, and a $YSTOP before the data was
 * the error "MNODIM is required".  A key commented out on purpose is quiet; one after a '*' '/'
 * glued to a word (the comment did not end there) is warned. */
START_TEST(test_ystop_and_comments_as_y2d) {
  char *tiny = yft_slurp("tests/y2d/tiny.y", 0);
  ck_assert_ptr_nonnull(tiny);
  char *at = strstr(tiny, "$YDOIT");
  ck_assert_ptr_nonnull(at);
  size_t n = strlen(tiny);
  char *nodoit = malloc(n + 64), *first = malloc(n + 64), *glued = malloc(n + 64);
  sprintf(nodoit, "%.*s/* $YDOIT */\n$YSTOP\n", (int)(at - tiny), tiny);
  sprintf(first, "/* a deck that ends at once */\n$YSTOP\n%s", tiny);
  sprintf(glued, "/* note*/\n/YD/YDC/MCSTEP 7\n*/\n%s", tiny);
  char *dir = yft_deck_dir("nodoit.y", nodoit);
  yft_put_file(dir, "first.y", first);
  yft_put_file(dir, "glued.y", glued);
  static const char *const files[] = {"nodoit.y", "first.y"};
  for (int k = 0; k < 2; k++) {
    char cmd[1200], ep[700];
    snprintf(ep, sizeof ep, "%s/err.txt", dir);
    snprintf(cmd, sizeof cmd, "cd %s && %s -log none -summary s.json %s > /dev/null 2> err.txt", dir, yft_binary(), files[k]);
    int st = system(cmd);
    char *err = yft_slurp(ep, 1);
    snprintf(ep, sizeof ep, "%s/s.json", dir);
    char *js = yft_slurp(ep, 1);
    ck_assert_msg(WIFEXITED(st) && WEXITSTATUS(st) == 0, "%s: exit %d: %s", files[k], WEXITSTATUS(st), err);
    ck_assert_msg(strstr(err, "warning: nothing is computed: the deck has no $YDOIT before its $YSTOP"), "%s: %s",
                  files[k], err);
    ck_assert_msg(!strstr(err, "inside the comment"), "%s: %s", files[k], err);
    ck_assert_msg(strstr(js, "\"steps\": 0,"), "%s: %s", files[k], js);
    free(err);
    free(js);
  }
  char cmd[1200], ep[700];
  snprintf(cmd, sizeof cmd, "cd %s && %s -log none glued.y > /dev/null 2> err.txt", dir, yft_binary());
  ck_assert_int_ne(system(cmd), -1);
  snprintf(ep, sizeof ep, "%s/err.txt", dir);
  char *err = yft_slurp(ep, 1);
  ck_assert_msg(strstr(err, "warning: '/YD/YDC/MCSTEP' is inside the comment opened at glued.y:"), "%s", err);
  free(err);
  free(dir);
  free(nodoit);
  free(first);
  free(glued);
  free(tiny);
}
END_TEST

/* Shared deck a's text (free it), with *at at the first occurrence of key in it. */
static char *deck_a_at(const char *key, char **at) {
  char *a = yft_slurp(DECKS "a_elastic_block.y", 0);
  ck_assert_ptr_nonnull(a);
  *at = strstr(a, key);
  ck_assert_msg(*at != NULL, "deck a has no %s", key);
  return a;
}

/* DIEDI: the travel counter starts there without joint meshing (ALGORITHMS 5), so with DIEDI 0
 * the first search waits until the bodies have moved DIEZON (1.5 mm: a travel of 2 dt |v|_max = 1 um a step
 * for deck a's block at 2 m/s, step 1500).  yfdem read DIEDI and searched at the first step whatever it was. */
START_TEST(test_diedi_delays_first_search) {
  char *dz, *a = deck_a_at("/YD/YDI/DIEZON", &dz);
  char *deck = malloc(strlen(a) + 64);
  sprintf(deck, "%.*s/YD/YDI/DIEDI 0\n%s", (int)(dz - a), a, dz);
  char *dir = yft_deck_dir("a0.y", deck);
  long searches[2];
  for (int k = 0; k < 2; k++) {
    char nd[800];
    snprintf(nd, sizeof nd, "read_y2d %s/%s\nrun 100\n", k ? dir : "tests/y2d/decks", k ? "a0.y" : "a_elastic_block.y");
    YfSim *s = yft_run(nd);
    ck_assert_int_eq(s->step, 100);
    searches[k] = contact_searches(s);
  }
  ck_assert_msg(searches[0] >= 1 && searches[1] == 0, "searches in 100 steps: DIEDI default %ld, DIEDI 0 %ld",
                searches[0], searches[1]);
  free(dir);
  free(deck);
  free(a);
}
END_TEST

/* A BC set index outside 0..NPNSET-1 freezes its node, as Y2D never moves it (FORMAT.md 6): it
 * was refused as an error.  The deck a's block with its corner node 0 given set 7 runs, warns
 * once, and that node stays put while the block flies. */
START_TEST(test_frozen_set) {
  char *at, *a = deck_a_at("/YD/YDN/I1NOPR ", &at);
  char *v = strchr(at, '\n') + 1; /* the first value on the next line */
  while (*v == ' ') v++;
  ck_assert(*v == '0' || *v == '1');
  char *deck = strdup(a);
  deck[v - a] = '7';
  /* node 0 at rest: frozen, said once; given a velocity, the warning says Y2D keeps it */
  char *err, *vel = strstr(deck, "/YD/YDN/D2NVC 21 2 440\n0.0 0.0");
  ck_assert_ptr_nonnull(vel);
  for (int k = 0; k < 2; k++) {
    if (k) memcpy(vel + strlen("/YD/YDN/D2NVC 21 2 440\n"), "1.0 0.0", 7);
    int rc = yft_run_binary("fz.y", deck, "-log none", &err, NULL);
    ck_assert_msg(k || rc == 0, "exit %d: %s", rc, err); /* with a velocity the energy check may stop it */
    ck_assert_msg(strstr(err, "frozen, as Y2D never moves such a node") &&
                  !strstr(err, "one has an initial velocity") == !k, "%s", err);
    free(err);
  }
  memcpy(vel + strlen("/YD/YDN/D2NVC 21 2 440\n"), "0.0 0.0", 7);
  char *dir = yft_deck_dir("f.y", deck);
  char nd[700];
  snprintf(nd, sizeof nd, "read_y2d %s/f.y\nrun 200\n", dir);
  YfSim *s = yft_run(nd);
  ck_assert_int_eq(s->step, 200);
  const YfNodes *n = &s->model.node;
  int found = 0;
  for (int i = 0; i < n->n; i++)
    if (n->id[i] == 0) {
      found++;
      ck_assert_msg(n->x[i] == n->x0[i] && n->y[i] == n->y0[i], "node 0 moved by (%g, %g)", n->x[i] - n->x0[i],
                    n->y[i] - n->y0[i]);
    }
  ck_assert_int_ge(found, 1);
  free(dir);
  free(deck);
  free(a);
}
END_TEST

/* A property that no element uses is never evaluated by Y2D (its loop runs over each property's
 * elements), so a deck with NPROP above the properties in use runs there whatever the spare ones
 * hold.  yfdem refused it ("property 2 has type -1", or "density 0" for a placeholder of type 1).
 * Deck a with NPROP 4, properties 2 and 3 left at their defaults (type -1, density 0): the binary
 * runs it (exit 0, one warning at NPROP's line), and read_y2d of it ends 200 steps in the state of
 * deck a itself (the spare properties change nothing). */
START_TEST(test_spare_properties) {
  char *at, *a = deck_a_at("/YD/YDPE/MPROP 2\n/YD/YDPE/NPROP 2\n", &at);
  char *deck = strdup(a);
  memcpy(deck + (at - a), "/YD/YDPE/MPROP 4\n/YD/YDPE/NPROP 4\n", strlen("/YD/YDPE/MPROP 4\n/YD/YDPE/NPROP 4\n"));
  int line = 1;
  for (const char *c = a; c < at; c++) line += *c == '\n';
  char *err, *dir;
  int rc = yft_run_binary("spare.y", deck, "-log none", &err, &dir);
  char want[128];
  snprintf(want, sizeof want, "spare.y:%d: warning: /YD/YDPE/NPROP = 4: 2 properties (first: property 2, type -1)",
           line + 1);
  ck_assert_msg(rc == 0 && strstr(err, want), "exit %d, no '%s' in: %s", rc, want, err);
  free(err);
  char nd[700];
  snprintf(nd, sizeof nd, "read_y2d %s/spare.y\nrun 200\n", dir);
  uint64_t h1 = sim_state_hash(yft_run(nd));
  uint64_t h0 = sim_state_hash(yft_run("read_y2d " DECKS "a_elastic_block.y\nrun 200\n"));
  ck_assert_msg(h1 == h0, "spare properties changed the state: %016llx vs %016llx", (unsigned long long)h1,
                (unsigned long long)h0);
  free(dir);
  free(deck);
  free(a);
}
END_TEST

/* Joint sets as Y2D evaluates them: a set that no I2PMIJ row of properties in use names is never
 * evaluated (spare sets left at their defaults: type -1, f_t 0 ... ran in Y2D, yfdem refused them
 * as "jointprop 'y2d_j2': tensile strength ft must be > 0" at D1PJFT's line); a set in use with a
 * value the joint law divides by at 0 is refused in the deck's words at that value's line (it was
 * the native jointprop's words at D1PJFT's line whatever the value).  Deck b (300 steps) with
 * NPJSET 3: one warning at NPJSET's line, and deck b's own state; deck b with G_f 0 in set 1 (the
 * impactor's joints): the error at the line of that value. */
START_TEST(test_spare_joint_sets) {
  char *b = yft_slurp(DECKS "b_beam_impact.y", 0);
  ck_assert_ptr_nonnull(b);
  char *m = strstr(b, "/YD/YDC/MCSTEP 15000\n"), *js = strstr(b, "/YD/YDPJ/MPJSET 2\n/YD/YDPJ/NPJSET 2\n");
  char *gf = strstr(b, "/YD/YDPJ/D1PJGF 2\n300 3000000000000.0\n");
  ck_assert(m && js && gf);
  memcpy(m, "/YD/YDC/MCSTEP   300", 20); /* the same length: the lines stay where they are */
  int line = 1;
  for (const char *c = b; c < js; c++) line += *c == '\n';
  char *deck = strdup(b);
  memcpy(deck + (js - b), "/YD/YDPJ/MPJSET 3\n/YD/YDPJ/NPJSET 3\n", 36);
  char *err, *dir, want[200];
  int rc = yft_run_binary("spare_j.y", deck, "-log none", &err, &dir);
  snprintf(want, sizeof want, "spare_j.y:%d: warning: /YD/YDPJ/NPJSET = 3: 1 joint set (first: set 2) named by no",
           line + 1);
  ck_assert_msg(rc == 0 && strstr(err, want), "exit %d, no '%s' in: %s", rc, want, err);
  free(err);
  char nd[700];
  snprintf(nd, sizeof nd, "read_y2d %s/spare_j.y\nrun\n", dir);
  YfSim *s1 = yft_run(nd);
  ck_assert_int_eq(s1->step, 300);
  uint64_t h1 = sim_state_hash(s1);
  free(dir);
  dir = yft_deck_dir("b300.y", b);
  snprintf(nd, sizeof nd, "read_y2d %s/b300.y\nrun\n", dir);
  uint64_t h0 = sim_state_hash(yft_run(nd));
  ck_assert_msg(h1 == h0, "a spare joint set changed the state: %016llx vs %016llx", (unsigned long long)h1,
                (unsigned long long)h0);
  free(dir);
  /* G_f 0 in set 1, which the impactor's joints use */
  strcpy(deck, b);
  memcpy(deck + (gf - b) + strlen("/YD/YDPJ/D1PJGF 2\n300 "), "0.0000000000000", 15);
  line = 2;
  for (const char *c = b; c < gf; c++) line += *c == '\n';
  rc = yft_run_binary("gf0.y", deck, "-log none", &err, &dir);
  snprintf(want, sizeof want, "gf0.y:%d: error: /YD/YDPJ/D1PJGF: joint set 1 has 0; it must be > 0", line);
  ck_assert_msg(rc == 1 && strstr(err, want), "exit %d, no '%s' in: %s", rc, want, err);
  free(err);
  free(dir);
  free(deck);
  free(b);
}
END_TEST

/* A message about one value of an array names the line that value is on.  The lines were noted
 * one entry per line (100 MB for a generated deck at 1e6 triangles); they are now runs of lines
 * of equal width, so lines of other widths must still come out right: deck a's I1NOPR (440
 * values) is rewritten with lines of 20, 20, 7, 3, 20, 1 values..., and the frozen-set warning
 * (value_loc of the first frozen node) must name the line of the node set to 7, whether it is a
 * line's first value, its last, or inside a run of lines of one width. */
START_TEST(test_value_lines) {
  static const int width[] = {20, 20, 7, 3, 20, 1, 1, 1, 5, 20, 20, 20};
  static const long at[] = {0, 19, 20, 39, 40, 46, 47, 49, 50, 69, 70, 71, 72, 77, 100, 300, 439};
  char *key, *a = deck_a_at("/YD/YDN/I1NOPR 440\n", &key);
  char *vals = key + strlen("/YD/YDN/I1NOPR 440\n"), *end = strstr(vals, "/YD/");
  ck_assert_ptr_nonnull(end);
  int line0 = 1; /* the line of the first value */
  for (const char *c = a; c < vals; c++) line0 += *c == '\n';
  char *ms = strstr(a, "/YD/YDC/MCSTEP 4000\n");
  ck_assert_ptr_nonnull(ms);
  for (size_t t = 0; t < sizeof at / sizeof at[0]; t++) {
    /* the deck: 1 step, and I1NOPR's values (those of deck a) laid out by width[] */
    size_t cap = strlen(a) + 4096, n = 0;
    char *deck = malloc(cap);
    n += (size_t)snprintf(deck + n, cap - n, "%.*s/YD/YDC/MCSTEP 1\n%.*s", (int)(ms - a), a,
                          (int)(vals - ms - strlen("/YD/YDC/MCSTEP 4000\n")), ms + strlen("/YD/YDC/MCSTEP 4000\n"));
    const char *v = vals;
    long k = 0, want = -1;
    int line = line0, w = 0, col = 0;
    while (k < 440) {
      char *e;
      long x = strtol(v, &e, 10);
      ck_assert(e > v);
      v = e;
      if (k == at[t]) {
        x = 7;
        want = line;
      }
      n += (size_t)snprintf(deck + n, cap - n, "%s%ld", col ? " " : "", x);
      k++;
      if (++col == width[w % (int)(sizeof width / sizeof width[0])] || k == 440) {
        n += (size_t)snprintf(deck + n, cap - n, "\n");
        line++, w++, col = 0;
      }
    }
    n += (size_t)snprintf(deck + n, cap - n, "%s", end);
    char *err, needle[64];
    int rc = yft_run_binary("vl.y", deck, "-log none", &err, NULL);
    ck_assert_msg(rc == 0, "exit %d: %s", rc, err);
    snprintf(needle, sizeof needle, "vl.y:%ld: warning: ", want);
    char *wl = strstr(err, needle);
    ck_assert_msg(wl && strstr(wl, "frozen, as Y2D never moves such a node"), "node %ld on line %ld: %s", at[t], want, err);
    free(err);
    free(deck);
  }
  free(a);
}
END_TEST

/* The memory cap counts all the arrays of a .y deck, not each alone: with YFDEM_MEM_MAX=1e9, deck a
 * with MPROP 15e6 (13 property arrays of at most 120 MB, 1.26 GB in all) or MNOPO 20e6 (5 node
 * arrays of at most 320 MB, 1.12 GB) is refused at the capacity's line, before anything is
 * allocated.  Each array passed the per-array check, and MPROP 2147483648 was an OOM kill. */
START_TEST(test_capacity_memory_total) {
  static const struct {
    const char *key, *value, *want;
  } c[] = {{"/YD/YDPE/MPROP 2\n", "/YD/YDPE/MPROP 15000000\n", "/YD/YDPE/MPROP = 15000000 (it sizes 13 arrays"},
           {"/YD/YDN/MNOPO 3384\n", "/YD/YDN/MNOPO 20000000\n", "/YD/YDN/MNOPO = 20000000 (it sizes 5 arrays"}};
  setenv("YFDEM_MEM_MAX", "1e9", 1);
  for (size_t k = 0; k < sizeof c / sizeof c[0]; k++) {
    char *at, *a = deck_a_at(c[k].key, &at);
    int line = 1;
    for (const char *p = a; p < at; p++) line += *p == '\n';
    char *deck = malloc(strlen(a) + 64), *err, want[200];
    sprintf(deck, "%.*s%s%s", (int)(at - a), a, c[k].value, at + strlen(c[k].key));
    int rc = yft_run_binary("cap.y", deck, "-log none", &err, NULL);
    snprintf(want, sizeof want, "cap.y:%d: error: %s", line, c[k].want);
    ck_assert_msg(rc == 1 && strstr(err, want) && strstr(err, "more than the 1 GB available (YFDEM_MEM_MAX)"),
                  "%s: exit %d, want '%s': %s", c[k].value, rc, want, err);
    free(err);
    free(deck);
    free(a);
  }
  /* The key that tips the sum over need not be the one to change: MELEM 200000000 (line 14 of deck a)
   * sizes nothing until MELST (line 16) does, with it, D2ELST.  The error, at MELST's line, said
   * "MELST = 1 ... use a smaller size" alone (2026-11-29 sweep); it now names the largest array's
   * capacities with their values and lines. */
  {
    char *at, *a = deck_a_at("/YD/YDE/MELEM 3680\n", &at);
    int line = 1;
    for (const char *p = a; p < at; p++) line += *p == '\n';
    char *deck = malloc(strlen(a) + 64), *err, want[200];
    sprintf(deck, "%.*s/YD/YDE/MELEM 200000000\n%s", (int)(at - a), a, at + strlen("/YD/YDE/MELEM 3680\n"));
    int rc = yft_run_binary("cap.y", deck, "-log none", &err, NULL);
    snprintf(want, sizeof want, "the largest array, /YD/YDE/D2ELST, is sized by /YD/YDE/MELST = 1 (line %d), "
             "/YD/YDE/MELEM = 200000000 (line %d)", line + 2, line);
    ck_assert_msg(rc == 1 && strstr(err, want), "exit %d, want '%s': %s", rc, want, err);
    free(err);
    free(deck);
    free(a);
  }
  unsetenv("YFDEM_MEM_MAX");
}
END_TEST

/* A Y2D deck whose DCSTEC is far above the stable limit inverts a triangle: exit 3, and the advice names
 * the deck's own time step key.  It said only "try a smaller 'timestep auto safety'", a native command
 * that `yfdem DECK.y` has no place for (2026-11-29 sweep): tiny.y with DCSTEC 1 s (1.2e4 x the limit)
 * and node 2 moving down at 3 m/s, which crosses the unit triangle in its second step. */
START_TEST(test_inverted_names_dcstec) {
  char *text = yft_slurp("tests/y2d/tiny.y", 0);
  ck_assert_ptr_nonnull(text);
  char deck[4096];
  const char *dt = strstr(text, "/YD/YDC/DCSTEC 1e-6\n"), *pr = strstr(text, "/YD/YDN/I1NOPR");
  ck_assert(dt && pr && dt < pr);
  snprintf(deck, sizeof deck, "%.*s/YD/YDC/DCSTEC 1.0\n%.*s/YD/YDN/D2NVC 21 2 4 0 0 0 0 0 -3 0 0\n%s", (int)(dt - text), text,
           (int)(pr - dt - strlen("/YD/YDC/DCSTEC 1e-6\n")), dt + strlen("/YD/YDC/DCSTEC 1e-6\n"), pr);
  free(text);
  char *err = NULL;
  int code = yft_run_binary("inv.y", deck, "-log none", &err, NULL);
  ck_assert_msg(code == 3 && strstr(err, "numerical failure at step 2: triangle 0") && strstr(err, "inverted") &&
                strstr(err, "DCSTEC"), "exit %d: %s", code, err);
  free(err);
}
END_TEST

/* MCSTEP <= NCSTEP: Y2D computes no step, so a DCSTEC of 0 is no error there; `yfdem DECK.y` warned
 * "no time step will be computed" and then stopped with "run: no time step set (use 'timestep DT' ...)",
 * exit 1, no file:line and a native command's advice (2026-11-29 sweep).  Now it warns, computes
 * nothing and ends ok with 0 steps, as with a DCSTEC given. */
START_TEST(test_no_steps_no_dcstec) {
  char *text = yft_slurp("tests/y2d/tiny.y", 0);
  ck_assert_ptr_nonnull(text);
  const char *mc = strstr(text, "/YD/YDC/MCSTEP 10\n"), *dt = strstr(text, "/YD/YDC/DCSTEC 1e-6\n");
  ck_assert(mc && dt && mc < dt);
  const size_t lm = strlen("/YD/YDC/MCSTEP 10\n"), ld = strlen("/YD/YDC/DCSTEC 1e-6\n");
  char deck[4096];
  snprintf(deck, sizeof deck, "%.*s/YD/YDC/MCSTEP 0\n%.*s/YD/YDC/DCSTEC 0\n%s", (int)(mc - text), text,
           (int)(dt - mc - lm), mc + lm, dt + ld);
  free(text);
  char *err = NULL, *dir = NULL;
  int code = yft_run_binary("idle.y", deck, "-log none -summary s.json", &err, &dir);
  ck_assert_msg(code == 0 && strstr(err, "no time step will be computed") && !strstr(err, "error"), "exit %d: %s",
                code, err);
  char path[600];
  snprintf(path, sizeof path, "%s/s.json", dir);
  char *js = yft_slurp(path, 0);
  ck_assert_msg(js && strstr(js, "\"status\": \"ok\"") && strstr(js, "\"steps\": 0,"), "%s", js ? js : "no summary");
  free(js);
  free(err);
  free(dir);
}
END_TEST

/* A native contact rule over the triangles of a Y2D property of D1PEPE 0: the penalty is the deck's own
 * (Y2D's couples without force), so the rule takes them; it was refused with "add 'pen_n P' to its
 * material command", a command the .y has no place for (2026-11-29). */
START_TEST(test_zero_dcpepe_native_contact) {
  char *text = yft_slurp("tests/y2d/tiny.y", 0);
  ck_assert_ptr_nonnull(text);
  const char *pe = strstr(text, "/YD/YDPE/D1PEPE 1 1e10\n");
  ck_assert_ptr_nonnull(pe);
  char y[4096], deck[1024];
  snprintf(y, sizeof y, "%.*s/YD/YDPE/D1PEPE 1 0\n%s", (int)(pe - text), text, pe + strlen("/YD/YDPE/D1PEPE 1 1e10\n"));
  free(text);
  char *dir = yft_deck_dir("pe0.y", y);
  snprintf(deck, sizeof deck, "read_y2d %s/pe0.y\ncontact self y2d\nrun 2\n", dir);
  char *err = NULL;
  int code = yft_run_binary("pe0.deck", deck, "-log none", &err, NULL);
  ck_assert_msg(code == 0 && !strstr(err, "pen_n"), "exit %d: %s", code, err);
  free(err);
  free(dir);
}
END_TEST

/* IWFAST below 0: yfdem takes only flagged triangles into contact, as for IWFAST > 0 (y2d_model.c: all of them
 * with IWFAST 0 only), but the warning about boundary nodes left unflagged was given for IWFAST > 0 only: tiny.y
 * with IWFAST -1 and no I1NOBF flag ran without contact and without a word (2026-11-29 sweep).  The count is of
 * nodes: tiny.y's square has 4, all on its boundary; the warning said "8 boundary node(s)", each node counted once
 * per boundary edge it ends (2026-11-29 sweep-y2d4). */
START_TEST(test_iwfast_negative_warned) {
  char *text = yft_slurp("tests/y2d/tiny.y", 0);
  ck_assert_ptr_nonnull(text);
  char *f = strstr(text, "/YD/YDN/I1NOBF 4 1 1 1 1");
  ck_assert_ptr_nonnull(f);
  memcpy(f, "/YD/YDN/I1NOBF 4 0 0 0 0", strlen("/YD/YDN/I1NOBF 4 0 0 0 0"));
  char deck[4096];
  snprintf(deck, sizeof deck, "/YD/YDC/IWFAST -1\n%s", text);
  free(text);
  char *err = NULL;
  int code = yft_run_binary("neg.y", deck, "-log none", &err, NULL);
  ck_assert_msg(code == 0 && strstr(err, ": 4 boundary node(s) of unjointed bodies have /YD/YDN/I1NOBF != 1") &&
                strstr(err, "IWFAST = -1"), "exit %d: %s", code, err);
  free(err);
}
END_TEST

/* `yfdem NAME` on tests/y2d/tiny.y with its text `from` replaced by `to`: the exit code; its stderr in *err
 * (caller frees). */
static int tiny_with(const char *name, const char *from, const char *to, char **err) {
  char *text = yft_slurp("tests/y2d/tiny.y", 0);
  ck_assert_ptr_nonnull(text);
  const char *at = strstr(text, from);
  ck_assert_msg(at != NULL, "tiny.y has no '%s'", from);
  char deck[4096];
  snprintf(deck, sizeof deck, "%.*s%s%s", (int)(at - text), text, to, at + strlen(from));
  free(text);
  *err = NULL;
  return yft_run_binary(name, deck, "-log none", err, NULL);
}

/* Characters that look like ASCII but are not, as decks copied from a word processor, a PDF or a web page hold
 * them: a no-break space (U+00A0) between a key and its value or inside a list, a minus sign (U+2212), a
 * full-width digit.  The messages quoted the token, which looked right: "'200 ' is not a number", "'0 0' is not
 * a number", "'-9.81' is not a number", "unexpected token ' /YD/YDC/MCSTEP'", and for a key glued to its value
 * by a no-break space "/YD/YDC/MCSTEP 200 read as /YD/YDC/MCSTEP" then "missing its value" (2026-11-29
 * sweep-y2d4).  Each message now names the character, its code point and where it is in the token. */
START_TEST(test_non_ascii_named) {
  static const struct {
    const char *from, *to, *want1, *want2;
    int line;
  } v[] = {
      {"/YD/YDC/MCSTEP 10\n", "/YD/YDC/MCSTEP 10\xc2\xa0\n", "U+00A0 (a no-break space) at byte 3", "is not a number", 2},
      {"/YD/YDE/I1ELPR 2 0 0", "/YD/YDE/I1ELPR 2 0\xc2\xa0""0", "U+00A0 (a no-break space) at byte 2", "is not a number", 10},
      {"/YD/YDC/MCSTEP 10\n", "/YD/YDC/MCSTEP\xc2\xa0""10\n", "U+00A0 (a no-break space) at byte 15", "read as /YD/YDC/MCSTEP", 2},
      {"/YD/YDC/MCSTEP 10\n", "\xc2\xa0/YD/YDC/MCSTEP 10\n", "U+00A0 (a no-break space) at byte 1", "unexpected token", 2},
      {"/YD/YDPE/D1PERO 1 2000", "/YD/YDPE/D1PERO 1 \xe2\x88\x92""2000", "U+2212 (a minus sign, not the ASCII '-') at byte 1",
       "is not a number", 24},
      {"/YD/YDPE/D1PERO 1 2000", "/YD/YDPE/D1PERO 1 \xef\xbc\x92""000", "U+FF12 (a full-width digit) at byte 1",
       "is not a number", 24},
      {"/YD/YDPE/D1PERO 1 2000", "/YD/YDPE/D1PERO 1 2000\xe9", "the byte 0xe9 (not ASCII, not UTF-8) at byte 5",
       "is not a number", 24},
      /* look-alikes the deck's expressions named and this reader did not (one table now, utf8name.h) */
      {"/YD/YDPE/D1PERO 1 2000", "/YD/YDPE/D1PERO 1 2\xc3\x97""1000", "U+00D7 (a multiplication sign, not the ASCII '*') at byte 2",
       "is not a number", 24},
      {"/YD/YDPE/D1PERO 1 2000", "/YD/YDPE/D1PERO 1 2000\xc2\xb2", "U+00B2 (a superscript) at byte 5", "is not a number", 24},
  };
  for (size_t i = 0; i < sizeof v / sizeof v[0]; i++) {
    char *err, want[64];
    int code = tiny_with("na.y", v[i].from, v[i].to, &err);
    snprintf(want, sizeof want, "na.y:%d: ", v[i].line);
    ck_assert_msg(strstr(err, want) && strstr(err, v[i].want1) && strstr(err, v[i].want2) &&
                      strstr(err, "retype it in ASCII"), "case %zu: exit %d: %s", i, code, err);
    free(err);
  }
}
END_TEST

/* A negative D1PELA (a material of negative Poisson's ratio) is run by yfdem (the native material takes it,
 * write_y2d writes it), but Y2D's consistency check refuses it and computes nothing (FORMAT.md 6: "no negative
 * D1PEFR, D1PEKS, D1PELA, ..."): `yfdem DECK.y` ran tiny.y with D1PELA -2e8 without a word, a deck Y2D itself
 * does not run (2026-11-29 sweep-y2d4).  Now a warning at D1PELA's line says so; D1PELA 1e9 and -0 do not warn. */
static char *lambda_run(const char *lambda, int *code) {
  char to[64], *err;
  snprintf(to, sizeof to, "/YD/YDPE/D1PELA 1 %s\n", lambda);
  *code = tiny_with("lam.y", "/YD/YDPE/D1PELA 1 1e9\n", to, &err);
  return err;
}

START_TEST(test_negative_lambda_warned) {
  int code;
  char *err = lambda_run("-2e8", &code);
  ck_assert_msg(code == 0 && strstr(err, "lam.y:25: warning: /YD/YDPE/D1PELA: property 0 has the negative value -2e+08") &&
                strstr(err, "Y2D refuses"), "exit %d: %s", code, err);
  free(err);
  const char *fine[] = {"1e9", "-0"};
  for (int i = 0; i < 2; i++) {
    err = lambda_run(fine[i], &code);
    ck_assert_msg(code == 0 && !strstr(err, "D1PELA"), "D1PELA %s: exit %d: %s", fine[i], code, err);
    free(err);
  }
}
END_TEST

/* Y2D writes an animation frame every ICOUTF steps (FORMAT.md 1.5, 7; ICOUTF <= 0 is 10); `yfdem DECK.y` writes
 * none, and said nothing: a Y2D user's `yfdem beam.y` with ICOUTF 100 ended with no file to open (2026-11-29
 * sweep-y2d4).  Now a warning at ICOUTF's line says so and how to get frames (the converter, or read_y2d with a
 * dump), whenever Y2D would write a frame after step 0: tiny.y (10 steps) with ICOUTF 5 and 0 (= 10) warns,
 * with ICOUTF 11 (above the run) it does not, and a native deck that reads it (its own dumps) does not. */
static int icoutf_warned(const char *icoutf, int native) {
  char *text = yft_slurp("tests/y2d/tiny.y", 0);
  ck_assert_ptr_nonnull(text);
  char deck[4096];
  snprintf(deck, sizeof deck, "/YD/YDC/ICOUTF %s\n%s", icoutf, text);
  free(text);
  char *err = NULL, *dir = NULL;
  int code;
  if (native) {
    char *d = yft_deck_dir("t.y", deck), cmd[8192];
    yft_put_file(d, "t.deck", "read_y2d t.y\nrun\n");
    snprintf(cmd, sizeof cmd, "cd '%s' && '%s' -in t.deck -log none >/dev/null 2>err.txt", d, yft_binary());
    code = WEXITSTATUS(system(cmd));
    char path[4200];
    snprintf(path, sizeof path, "%s/err.txt", d);
    err = yft_slurp(path, 1);
    free(d);
  } else {
    code = yft_run_binary("t.y", deck, "-log none", &err, &dir);
    free(dir);
  }
  ck_assert_msg(code == 0, "ICOUTF %s: exit %d: %s", icoutf, code, err);
  int warned = strstr(err, "t.y:1: warning: /YD/YDC/ICOUTF = ") && strstr(err, "writes no frames") &&
               strstr(err, "tools/y2d2deck.py") && strstr(err, "read_y2d");
  free(err);
  return warned;
}

START_TEST(test_icoutf_frames_warned) {
  ck_assert_msg(icoutf_warned("5", 0), "ICOUTF 5 of 10 steps: no warning");
  ck_assert_msg(icoutf_warned("0", 0), "ICOUTF 0 (= 10) of 10 steps: no warning");
  ck_assert_msg(!icoutf_warned("11", 0), "ICOUTF 11 of 10 steps: warned");
  ck_assert_msg(!icoutf_warned("5", 1), "read_y2d in a native deck: warned");
}
END_TEST

/* Y2D prints a progress line every ICSHTF steps (FORMAT.md 1.5); `yfdem DECK.y` printed the thermo
 * line at the run's start and end only, so a long batch run's log showed nothing until it ended
 * (2026-11-29 sweep).  Now the thermo line comes every ICSHTF steps: tiny.y run for 10 steps with
 * ICSHTF 4 logs steps 0, 4, 8 and 10; ICSHTF 0 (no progress lines) logs 0 and 10. */
static int thermo_steps(const char *log, long *steps, int max) {
  int n = 0;
  const char *p = strstr(log, "      Step ");
  while (p && (p = strchr(p, '\n')) && n < max) {
    p++;
    long st;
    double t;
    if (sscanf(p, "%ld %lf", &st, &t) != 2) break;
    steps[n++] = st;
  }
  return n;
}

START_TEST(test_progress_every_icshtf) {
  char *text = yft_slurp("tests/y2d/tiny.y", 0);
  ck_assert_ptr_nonnull(text);
  const long every[2] = {4, 0}, want[2][4] = {{0, 4, 8, 10}, {0, 10, -1, -1}};
  const int nwant[2] = {4, 2};
  for (int c = 0; c < 2; c++) {
    char *deck = malloc(strlen(text) + 128);
    sprintf(deck, "/YD/YDC/ICSHTF %ld\n/YD/YDC/MCSTEP 10\n%s", every[c], text);
    char *err = NULL, *dir = NULL, path[1200];
    int code = yft_run_binary("progress.y", deck, "-log run.log", &err, &dir);
    ck_assert_msg(code == 0, "exit %d: %s", code, err);
    snprintf(path, sizeof path, "%s/run.log", dir);
    char *log = yft_slurp(path, 0);
    ck_assert_ptr_nonnull(log);
    long steps[16];
    int n = thermo_steps(log, steps, 16);
    ck_assert_msg(n == nwant[c], "ICSHTF %ld: %d thermo lines:\n%s", every[c], n, log);
    for (int k = 0; k < n; k++) ck_assert_int_eq(steps[k], want[c][k]);
    free(log);
    free(err);
    free(dir);
    free(deck);
  }
  free(text);
}
END_TEST


/* A deck error in the middle of a .y (yfdem exits there; the reader fuzz target, tools/fuzz,
 * longjmps back through err.c's exit hook and goes on) leaves nothing allocated once the
 * simulation is freed: the arrays read so far, sized by the deck's capacities, were unreachable
 * (a NaN coordinate after MNOPO 2e6: 32 MB per read, gigabytes in a fuzzing run).  8 reads; the
 * heap may keep what the error path owns (a token buffer, the open FILE: < 10 KB a read), far
 * below one array of 2e6 nodes (32 MB). */
static jmp_buf y2d_back;
static void y2d_back_hook(int code) { longjmp(y2d_back, code + 1); }
START_TEST(test_error_frees_capacity) {
  char *t = yft_slurp("tests/corpus/y_nan.y", 0), *at = strstr(t, "MNOPO 4");
  ck_assert_ptr_nonnull(at);
  char text[4096];
  snprintf(text, sizeof text, "%.*sMNOPO 2000000%s", (int)(at - t), t, at + strlen("MNOPO 4"));
  free(t);
  char *dir = yft_deck_dir("y2d_err_free", "");
  yft_put_file(dir, "big_nan.y", text);
  char path[512];
  snprintf(path, sizeof path, "%s/big_nan.y", dir);
  yf_set_exit_hook(y2d_back_hook);
  size_t base = 0, used = 0;
  for (int it = 0; it < 8; it++) {
    static YfSim s; /* static: the longjmp must not leave it in a dead frame */
    static volatile int code;
    code = 0;
    sim_init(&s);
    s.progress = 0;
    int j = setjmp(y2d_back);
    if (j == 0) y2d_load(&s, path, 0.5, NULL);
    else code = j - 1;
    run_free();
    sim_free(&s);
    ck_assert_int_eq(code, YF_EXIT_DECK);
    struct mallinfo2 mi = mallinfo2();
    used = mi.uordblks + mi.hblkhd;
    if (it == 0) base = used;
  }
  yf_set_exit_hook(NULL);
  ck_assert_msg(used < base + 1000000, "8 failed reads of a .y with MNOPO 2e6 left %.1f MB more allocated than the first",
                ((double)used - (double)base) / 1e6);
  free(dir);
}
END_TEST

Suite *y2d_read_suite(void) {
  Suite *s = suite_create("y2d_read");
  TCase *tc = tcase_create("reference_decks");
  tcase_add_loop_test(tc, test_reference_counts, 0, (int)(sizeof refs / sizeof refs[0]));
  tcase_add_test(tc, test_beam_values);
  tcase_add_test(tc, test_cantilever_bc_tables);
  suite_add_tcase(s, tc);
  tc = tcase_create("syntax");
  tcase_add_test(tc, test_array_orders);
  tcase_add_test(tc, test_defaults_and_prefix);
  tcase_add_test(tc, test_include_relative_to_deck);
  tcase_add_test(tc, test_y2d_deck_misnamed);
  tcase_add_test(tc, test_couple_capacity_warned);
  tcase_add_test(tc, test_massless_nodes_stay);
  tcase_add_test(tc, test_ystop_and_comments_as_y2d);
  tcase_add_test(tc, test_diedi_delays_first_search);
  tcase_add_test(tc, test_frozen_set);
  tcase_add_test(tc, test_iwfast_negative_warned);
  tcase_add_test(tc, test_progress_every_icshtf);
  tcase_add_test(tc, test_icoutf_frames_warned);
  tcase_add_test(tc, test_negative_lambda_warned);
  tcase_add_test(tc, test_non_ascii_named);
  tcase_add_test(tc, test_spare_properties);
  tcase_add_test(tc, test_spare_joint_sets);
  tcase_add_test(tc, test_value_lines);
  tcase_add_test(tc, test_capacity_memory_total);
  suite_add_tcase(s, tc);
  tc = tcase_create("errors");
  tcase_add_loop_test(tc, test_bad_decks, 0, (int)(sizeof bad / sizeof bad[0]));
  tcase_add_test(tc, test_missing_deck);
  tcase_add_test(tc, test_error_frees_capacity);
  tcase_add_test(tc, test_inverted_names_dcstec);
  tcase_add_test(tc, test_no_steps_no_dcstec);
  tcase_add_test(tc, test_zero_dcpepe_native_contact);
  suite_add_tcase(s, tc);
  return s;
}
