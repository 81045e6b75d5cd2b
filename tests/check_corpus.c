/* check_corpus.c: every malformed input of tests/corpus (MANIFEST) through the real binary.
 *
 * Each row names an input (a deck, a Y2D .y deck, a Gmsh .msh mesh or a .restart file), the exit
 * code it must give (1 deck error, 2 I/O error) and a piece of the message, which always starts
 * with the FILE:LINE of the fault.  A .msh row is copied to in.msh and read by reader_gmsh.deck, a
 * .restart row to in.restart and read by reader_restart.deck: the decks the reader fuzz targets
 * run their inputs with (tools/fuzz), so that what they found stays fixed.
 * The inputs cover truncated lines, wrong types, huge numbers, NaN and inf, negative counts,
 * missing files, recursive includes, binary garbage, absurd sizes (mesh rect, .msh $Nodes,
 * .y capacities: refused before allocation) and what the fuzzers found (fuzz_*).  Besides
 * the expected message: no crash (signal), no internal error, no sanitizer report.
 * YFDEM_MEM_MAX=4e9 makes the memory refusals independent of the machine.
 */
#include <check.h>
#include "yftest.h"
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>
#include "err.h"

static char *slurp(const char *path) { return yft_slurp(path, 1); }

START_TEST(test_corpus) {
  char dir[] = "/tmp/yfcorpus_XXXXXX";
  ck_assert_ptr_nonnull(mkdtemp(dir));
  char cmd[4096], cwd[1024];
  ck_assert_ptr_nonnull(getcwd(cwd, sizeof cwd));
  const char *bin = getenv("YFDEM") ? getenv("YFDEM") : "./yfdem";
  char abs[1200];
  snprintf(abs, sizeof abs, "%s%s%s", bin[0] == '/' ? "" : cwd, bin[0] == '/' ? "" : "/", bin);
  snprintf(cmd, sizeof cmd, "cp -r tests/corpus/. %s/", dir);
  ck_assert_int_eq(system(cmd), 0);
  char man[1100];
  snprintf(man, sizeof man, "%s/MANIFEST", dir);
  FILE *f = fopen(man, "r");
  ck_assert_ptr_nonnull(f);
  char line[2048];
  int rows = 0, bad = 0;
  while (fgets(line, sizeof line, f)) {
    if (line[0] == '#' || line[0] == '\n') continue;
    line[strcspn(line, "\n")] = 0;
    char *name = strtok(line, "\t"), *code_s = strtok(NULL, "\t"), *piece = strtok(NULL, "\t");
    ck_assert_msg(name && code_s && piece, "bad MANIFEST row %d", rows + 1);
    int want = atoi(code_s);
    const char *ext = strrchr(name, '.') ? strrchr(name, '.') : "";
    char run[1400];
    if (!strcmp(ext, ".y")) /* a Y2D deck is run as such */
      snprintf(run, sizeof run, "%s %s", abs, name);
    else if (!strcmp(ext, ".msh") || !strcmp(ext, ".restart")) /* a file read by its reader's deck */
      snprintf(run, sizeof run, "cp %s in%s && %s -in reader_%s.deck", name, ext, abs, ext[1] == 'm' ? "gmsh" : "restart");
    else
      snprintf(run, sizeof run, "%s -in %s", abs, name);
    snprintf(cmd, sizeof cmd, "cd %s && YFDEM_MEM_MAX=4e9 OMP_NUM_THREADS=1 timeout 120 sh -c '%s' >/dev/null 2>err.txt",
             dir, run);
    int st = system(cmd);
    int code = WIFEXITED(st) ? WEXITSTATUS(st) : 128;
    char ep[1100];
    snprintf(ep, sizeof ep, "%s/err.txt", dir);
    char *err = slurp(ep);
    int ok = code == want && strstr(err, piece) && !strstr(err, "internal error") && !strstr(err, "Sanitizer") &&
             !strstr(err, "runtime error");
    if (!ok) {
      bad++;
      fprintf(stderr, "corpus %s: exit %d (want %d), expected '%s', got:\n%s\n", name, code, want, piece, err);
    }
    free(err);
    rows++;
  }
  fclose(f);
  snprintf(cmd, sizeof cmd, "rm -rf %s", dir);
  if (system(cmd)) {}
  ck_assert_int_ge(rows, 50);
  ck_assert_msg(bad == 0, "%d of %d corpus inputs gave another exit code or message (see above)", bad, rows);
}
END_TEST

Suite *corpus_suite(void) {
  Suite *s = suite_create("corpus");
  TCase *tc = tcase_create("corpus");
  tcase_set_timeout(tc, 600);
  tcase_add_test(tc, test_corpus);
  suite_add_tcase(s, tc);
  return s;
}
