/* check_y2d_wild.c: idioms of public Y2D deck generators that the original Y2D accepts.
 *
 * Each deck of tests/y2d_wild/ carries the idioms of one family of generators (see
 * docs/y2d_decks.md for the generators studied) and has a plain twin that says the same thing
 * in the form yfdem always read.  A test asserts two facts:
 *  - the reader says what it assumed, as "FILE:LINE: warning: ..." at the line of the idiom;
 *  - the idiom means what Y2D makes of it: the deck and its twin, run through read_y2d to their
 *    MCSTEP, end in bitwise the same state (sim_state_hash: positions, velocities, joints,
 *    energies), so nothing was lost or misread.
 * Before this suite, matlab_code0.y (meshing code 0) and cpp_mnodim3.y (MNODIM 3, D2ELST with
 * n1 > MELST and no values) were refused with an error.
 */
#include <check.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include "summary.h"
#include "y2d_read.h"
#include "yftest.h"

#define WILD "tests/y2d_wild/"

/* Read a deck with stderr captured; return the captured text (caller frees). */
static char *read_warnings(const char *path, YfY2d *y) {
  char tmp[] = "/tmp/y2d_wildXXXXXX";
  int fd = mkstemp(tmp);
  ck_assert(fd >= 0);
  fflush(stderr);
  int saved = dup(2);
  dup2(fd, 2);
  y2d_read(path, y, NULL);
  fflush(stderr);
  dup2(saved, 2);
  close(saved);
  close(fd);
  char *text = yft_slurp(tmp, 1);
  unlink(tmp);
  return text;
}

/* Run `read_y2d PATH` + `run` (to its MCSTEP); return the state hash, and the steps done. */
static uint64_t run_hash(const char *path, long *steps) {
  char deck[512];
  snprintf(deck, sizeof deck, "read_y2d %s\nrun\n", path);
  YfSim *s = yft_run(deck);
  *steps = s->step;
  return sim_state_hash(s);
}

static const struct {
  const char *deck, *twin;
  long steps;         /* the decks' MCSTEP                                    */
  int nwarn;          /* expected warnings (FILE:LINE and text); 0: none      */
  int line[3];
  const char *text[3];
} twins[] = {
  /* MATLAB printY: every meshing row "1 0 p" */
  {"matlab_code0.y", "matlab_nomesh.y", 300, 3, {204, 98, 134},
   {"/YD/YDPM/I2PMSET: meshing code 0 in 2 row(s) (0 1): read as \"no meshing",
    "/YD/YDE/I1ELBE: restart/scratch data, ignored",
    "/YD/YDO/NOHYS = 1 history variables: read, but yfdem does not write"}},
  /* C++ writers: MNODIM 3 with NNODIM 2; D2ELST 21 NELEM 0 */
  {"cpp_mnodim3.y", "cpp_plain.y", 400, 3, {53, 20, 21},
   {"/YD/YDN/MNODIM = 3 with /YD/YDN/NNODIM = 2: MNODIM is a capacity",
    "/YD/YDE/D2ELST: n1 = 16 exceeds the capacity 1 given by /YD/YDE/MELST, but the array holds "
    "no values",
    "/YD/YDE/I1ELCF: restart/scratch data, ignored"}},
  /* comment styles of a Qt exporter, Y's own writer, MATLAB; a D3PNFAC in code 231 */
  {"styles.y", "styles_plain.y", 400, 0, {0}, {NULL}},
  /* no newline after the last token */
  {"no_newline.y", "styles_plain.y", 400, 1, {129},
   {"'$YSTOP' ends the file without a trailing newline"}},
};

START_TEST(test_idiom_twin) {
  char path[256], twin[256], want[512];
  snprintf(path, sizeof path, WILD "%s", twins[_i].deck);
  snprintf(twin, sizeof twin, WILD "%s", twins[_i].twin);
  YfY2d y;
  char *err = read_warnings(path, &y);
  y2d_free(&y);
  int nwarn = 0;
  for (const char *p = err; (p = strstr(p, ": warning: ")); p++) nwarn++;
  ck_assert_msg(nwarn == twins[_i].nwarn, "%s: %d warnings, expected %d: %s", path, nwarn,
                twins[_i].nwarn, err);
  for (int w = 0; w < twins[_i].nwarn; w++) {
    snprintf(want, sizeof want, "%s:%d: warning: %s", path, twins[_i].line[w], twins[_i].text[w]);
    ck_assert_msg(strstr(err, want) != NULL, "no '%s' in: %s", want, err);
  }
  free(err);
  /* and the twin reads without the idiom's warning (the first): the idiom is the difference */
  err = read_warnings(twin, &y);
  y2d_free(&y);
  if (twins[_i].nwarn)
    ck_assert_msg(!strstr(err, twins[_i].text[0]), "%s: %s", twin, err);
  free(err);
  long n1, n2;
  uint64_t h1 = run_hash(path, &n1);
  uint64_t h2 = run_hash(twin, &n2);
  ck_assert_int_eq(n1, twins[_i].steps);
  ck_assert_int_eq(n2, twins[_i].steps);
  ck_assert_msg(h1 == h2, "%s and %s end in different states (%016llx, %016llx)", path, twin,
                (unsigned long long)h1, (unsigned long long)h2);
}
END_TEST

/* MNODIM 3 with coordinates given as 3 rows (x y z): x and y are kept exactly, z is dropped
 * with a warning that says so. */
START_TEST(test_mnodim3_three_rows) {
  char path[] = "/tmp/y2d_mnodimXXXXXX.y";
  int fd = mkstemps(path, 2);
  ck_assert(fd >= 0);
  FILE *f = fdopen(fd, "w");
  char *base = yft_slurp("tests/y2d/tiny.y", 0);
  ck_assert_ptr_nonnull(base);
  const char *from = strstr(base, "/YD/YDN/MNODIM 2"), *to = strstr(base, "/YD/YDN/I1NOPR");
  ck_assert(from && to);
  fprintf(f, "%.*s/YD/YDN/MNODIM 3\n/YD/YDN/NNODIM 2\n/YD/YDN/MNOPO 4\n/YD/YDN/NNOPO 4\n"
          "/YD/YDN/D2NCI 21 3 4  0 0 0.5  1 0 0  1.25 1 0  0 1 0\n%s",
          (int)(from - base), base, to);
  fclose(f);
  free(base);
  YfY2d y;
  char *err = read_warnings(path, &y);
  unlink(path);
  ck_assert_int_eq(y.mnodim, 2);
  const double want[8] = {0, 0, 1, 0, 1.25, 1, 0, 1};
  for (int i = 0; i < 8; i++) ck_assert(y.d2nci[i] == want[i] && y.d2ncc[i] == want[i]);
  ck_assert_msg(strstr(err, ":12: warning: /YD/YDN/MNODIM = 3") &&
                strstr(err, "non-zero third components were given and are ignored"), "%s", err);
  free(err);
  y2d_free(&y);
}
END_TEST

Suite *y2d_wild_suite(void) {
  Suite *s = suite_create("y2d_wild");
  TCase *tc = tcase_create("idioms");
  tcase_add_loop_test(tc, test_idiom_twin, 0, (int)(sizeof twins / sizeof twins[0]));
  tcase_add_test(tc, test_mnodim3_three_rows);
  suite_add_tcase(s, tc);
  return s;
}
