/* check_errors.c: what a user sees when a deck is wrong or a run fails: the FILE:LINE message,
 * the exit code that tells the kind apart, no partial output, and a summary that says why.
 * These run the real binary ($YFDEM) on small decks written to a temporary directory. */
#include <check.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>
#include "yftest.h"

#define MAT "material m elastic rho 1000 E 1e9 nu 0.25 plane_stress\n"
#define BAR MAT "mesh rect bar m 0 0 1 0.1 10 2\n"

static char *slurp(const char *path) { return yft_slurp(path, 0); }

/* Run deck text; assert exit code and that stderr contains each expected piece. */
static void expect_fail(const char *deck, int code, const char *piece1, const char *piece2) {
  char *err, *dir;
  int rc = yft_run_binary("bad.deck", deck, "-summary s.json", &err, &dir);
  ck_assert_msg(rc == code, "exit %d (expected %d), stderr:\n%s", rc, code, err);
  if (piece1) ck_assert_msg(strstr(err, piece1) != NULL, "stderr lacks '%s':\n%s", piece1, err);
  if (piece2) ck_assert_msg(strstr(err, piece2) != NULL, "stderr lacks '%s':\n%s", piece2, err);
  /* the summary says why; no dump file was created */
  char p[600];
  snprintf(p, sizeof p, "%s/s.json", dir);
  char *js = slurp(p);
  ck_assert_msg(js != NULL, "no summary written");
  const char *word = code == 1 ? "\"deck_error\"" : code == 2 ? "\"io_error\"" : "\"numerical_failure\"";
  ck_assert_msg(strstr(js, word) != NULL, "summary lacks status %s:\n%s", word, js);
  if (code != 3) { /* h5 dumps write out_NNNNNN.h5 and out.xmf */
    snprintf(p, sizeof p, "%s/out_000000.h5", dir);
    ck_assert_msg(!yft_exists(p), "a deck error left a partial output file");
    snprintf(p, sizeof p, "%s/out.xmf", dir);
    ck_assert_msg(!yft_exists(p), "a deck error left an output index");
  }
  free(js);
  free(err);
  free(dir);
}

/* A NUL byte (a binary file, a UTF-16 deck) is refused with the file, line and column, instead of
 * cutting the line short silently. */
START_TEST(test_nul_byte_in_deck) {
  char path[] = "/tmp/yf_nul_XXXXXX";
  ck_assert_ptr_nonnull(mkdtemp(path));
  char file[64];
  snprintf(file, sizeof file, "%s/nul.deck", path);
  FILE *f = fopen(file, "wb");
  static const char text[] = "material m elastic rho 1 E 1 nu 0.1\nmesh rect b m 0 0 1 1 2 2\0 pattern right\nrun 1\n";
  fwrite(text, 1, sizeof text - 1, f);
  fclose(f);
  char deck[128], *err = NULL, *dir = NULL;
  snprintf(deck, sizeof deck, "include %s\n", file);
  int rc = yft_run_binary("main.deck", deck, "", &err, &dir);
  ck_assert_msg(rc == 1, "exit %d, stderr:\n%s", rc, err);
  ck_assert_msg(strstr(err, "nul.deck:2: error: a NUL byte at column 26") != NULL, "stderr:\n%s", err);
  unlink(file);
  rmdir(path);
  free(err);
  free(dir);
}
END_TEST

START_TEST(test_unknown_command_suggests) {
  expect_fail(BAR "dump d h5 10 out.h5\nfxi hold bar fixed xy\nrun 10\n", 1, "bad.deck:4: error:", "did you mean 'fix'");
}
END_TEST

START_TEST(test_wrong_argument_count) {
  expect_fail(BAR "dump d h5 10 out.h5\ngravity 0\nrun 10\n", 1, "bad.deck:4: error:", "gravity GX GY");
}
END_TEST

START_TEST(test_non_numeric_number) {
  expect_fail(BAR "dump d h5 10 out.h5\ngravity 0 3.0x\nrun 10\n", 1, "bad.deck:4: error:", "3.0x");
}
END_TEST

START_TEST(test_unknown_group) {
  expect_fail(BAR "dump d h5 10 out.h5\nfix hold nosuch fixed xy\nrun 10\n", 1, "bad.deck:4: error:", "nosuch");
}
END_TEST

START_TEST(test_bad_choice_lists_valid) {
  expect_fail(BAR "fix hold bar fixed z\n", 1, "bad.deck:3: error:", "x, y, xy");
  /* a damage is a fraction: the error says the valid range */
  expect_fail(BAR "metrics opened_threshold 1.5\n", 1, "bad.deck:3: error:", "must lie in [0, 1]");
}
END_TEST

START_TEST(test_missing_include_is_io_error) {
  expect_fail(BAR "dump d h5 10 out.h5\ninclude nothere.deck\nrun 10\n", 2, "bad.deck:4: error:", "nothere.deck");
}
END_TEST

START_TEST(test_bad_mesh_file) {
  /* a .msh of the wrong version: deck error pointing into the mesh file */
  char *err, *dir;
  const char *deck = MAT "dump d h5 10 out.h5\nmesh gmsh b bad.msh material m\nrun 1\n";
  int rc = yft_run_binary("bad.deck", deck, "-summary s.json", &err, &dir);
  ck_assert_int_eq(rc, 2); /* bad.msh does not exist yet: an I/O error naming it */
  ck_assert_ptr_nonnull(strstr(err, "bad.msh"));
  char p[600];
  snprintf(p, sizeof p, "%s/bad.msh", dir);
  FILE *f = fopen(p, "w");
  fputs("$MeshFormat\n3.0 0 8\n$EndMeshFormat\n", f); /* 4.1 and 2.2 are read */
  fclose(f);
  free(err);
  char cmd[900];
  /* the binary under test ($YFDEM: build-asan/yfdem under make asan), relative to the test's directory */
  const char *bin = getenv("YFDEM") ? getenv("YFDEM") : "./yfdem";
  char cwd[512];
  ck_assert_ptr_nonnull(getcwd(cwd, sizeof cwd));
  snprintf(cmd, sizeof cmd, "cd %s && %s%s%s -in bad.deck -summary s.json >/dev/null 2>err.txt", dir, bin[0] == '/' ? "" : cwd,
           bin[0] == '/' ? "" : "/", bin);
  int st = system(cmd);
  ck_assert_int_eq(WEXITSTATUS(st), 1);
  snprintf(p, sizeof p, "%s/err.txt", dir);
  char *e2 = slurp(p);
  ck_assert_msg(strstr(e2, "bad.msh:2") != NULL, "message should point into the mesh file: %s", e2);
  snprintf(p, sizeof p, "%s/out_000000.h5", dir);
  ck_assert(!yft_exists(p));
  snprintf(p, sizeof p, "%s/out.xmf", dir);
  ck_assert(!yft_exists(p));
  free(e2);
  free(dir);
}
END_TEST

/* A time step above the stable limit is refused, naming the limit and what sets it. */
START_TEST(test_timestep_above_limit_refused) {
  expect_fail(BAR "timestep 1e-3\nrun 10\n", 1, "bad.deck:3: error: timestep", "stable limit");
  /* 'above_limit warn' (what a deck converted from Y2D says: Y2D never checks dt) warns and runs,
   * and the energy check stops the run it makes diverge; a later timestep line says it anew */
  char *err;
  int rc = yft_run_binary("w.deck", BAR "timestep 1e-3 above_limit warn\nrun 200\n", "-log none", &err, NULL);
  ck_assert_msg(rc == 3 && strstr(err, "w.deck:3: warning: the deck's time step 0.001 s is") &&
                strstr(err, "error: numerical failure"), "exit %d: %s", rc, err);
  free(err);
  expect_fail(BAR "timestep 1e-3 above_limit warn\ntimestep 1e-3\nrun 10\n", 1, "bad.deck:4: error: timestep", "stable limit");
  expect_fail(BAR "timestep 1e-3 above_limit stop\nrun 10\n", 1, "bad.deck:3: error: timestep: above_limit 'stop'", NULL);
}
END_TEST

/* Mass damping with alpha dt above 2 reverses the velocities every step instead of damping them
 * (a body kept 99.9 % of its kinetic energy at alpha = 1e12, exit 0): refused at the run, at the
 * damping line, with the most alpha the step allows; alpha dt = 2 itself runs. */
START_TEST(test_damping_above_two_over_dt_refused) {
  expect_fail(BAR "damping mass 1e12\ntimestep 1e-6\nrun 10\n", 1, "bad.deck:3: error: damping mass 1e+12: alpha dt = 1e+06 is above 2",
              "use at most alpha = 2/dt = 2e+06 1/s");
  YfSim *s = yft_run(BAR "damping mass 2e6\ntimestep 1e-6\nvelocity bar set 1 0\nrun 10\n");
  ck_assert_int_eq(s->step, 10);
  sim_free(s);
}
END_TEST

/* A record with a quantity no one knows is an error at the run, with no file made: it left a
 * header and half a row ("step,time,nosuchq\n0,0") behind. */
START_TEST(test_record_bad_quantity_no_file) {
  char *err, *dir;
  int rc = yft_run_binary("bad.deck", BAR "timestep auto\nrecord r1 1 r.csv ke nosuchq\nrun 5\n", NULL, &err, &dir);
  ck_assert_msg(rc == 1 && strstr(err, "bad.deck:4: error: record r1, at step 0: expression 'nosuchq': unknown variable"),
                "exit %d: %s", rc, err);
  char p[600];
  snprintf(p, sizeof p, "%s/r.csv", dir);
  ck_assert_msg(!yft_exists(p), "a half-written r.csv is left");
  free(err);
  free(dir);
}
END_TEST

/* A thermo column or a record quantity that fails during a run says at which step and for which
 * output: "e.deck:4: error: expression '1/(3-step)': division by zero" named the line that set it
 * up, and the step was left to guess from the last thermo line. */
START_TEST(test_run_expression_error_names_step) {
  char *err, *dir;
  int rc = yft_run_binary("bad.deck", BAR "timestep auto\nthermo 1\nthermo_style custom step \"1/(3-step)\"\nrun 5\n",
                          "-log none", &err, &dir);
  ck_assert_msg(rc == 1 && strstr(err, "bad.deck:5: error: thermo_style, at step 3: expression '1/(3-step)': division by "
                                       "zero"), "exit %d: %s", rc, err);
  free(err);
  free(dir);
  rc = yft_run_binary("bad.deck", BAR "timestep auto\nrecord rr 1 r.csv \"1/(2-step)\"\nrun 5\n", "-log none", &err, &dir);
  ck_assert_msg(rc == 1 && strstr(err, "bad.deck:4: error: record rr, at step 2: expression '1/(2-step)': division by zero"),
                "exit %d: %s", rc, err);
  free(err);
  free(dir);
}
END_TEST

/* An input that is a directory, or a device without end, is an I/O error (exit 2) at its line:
 * a directory read as an empty history, table or deck gave the wrong cause ("at least two points
 * needed", "MNODIM is required"), and /dev/zero grew until the kernel killed the process; an
 * output that is a directory is refused without a PATH.tmp left beside it. */
START_TEST(test_inputs_that_are_not_files) {
  static const struct {
    const char *line, *want;
  } cases[] = {
      {"history h file adir\n", "bad.deck:3: error: history: cannot open 'adir': Is a directory"},
      {"nodes adir\n", "bad.deck:3: error: nodes: cannot open"},
      {"jointprop j ft 1 fs 1 gf 1 pen 1 law table adir\n", "bad.deck:3: error: jointprop: cannot open softening table"},
      {"read_y2d adir\n", "bad.deck:3: error: cannot open Y2D deck 'adir': Is a directory"},
      {"include adir\n", "bad.deck:3: error: include: cannot open"},
      {"history h file /dev/zero\n", "bad.deck:3: error: history: cannot open '/dev/zero': File too large"},
      {"include /dev/zero\n", "bad.deck:3: error: include: cannot open '/dev/zero': File too large"},
      {"timestep 1e-6\nwrite_y2d adir steps 10\n", "bad.deck:4: error: write_y2d: cannot write 'adir': Is a directory"},
  };
  /* adir: a directory beside the deck */
  for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
    char deck[512], p[600], cmd[1600];
    snprintf(deck, sizeof deck, "%s%s", BAR, cases[k].line);
    char *d = yft_deck_dir("bad.deck", deck);
    snprintf(p, sizeof p, "%s/adir", d);
    ck_assert_int_eq(mkdir(p, 0755), 0);
    snprintf(cmd, sizeof cmd, "cd %s && %s -in bad.deck -log none >/dev/null 2>err.txt", d,
             yft_binary());
    int rc = system(cmd);
    snprintf(p, sizeof p, "%s/err.txt", d);
    char *e = slurp(p);
    ck_assert_msg(WIFEXITED(rc) && WEXITSTATUS(rc) == 2 && e && strstr(e, cases[k].want), "%s: exit %d: %s", cases[k].line,
                  WIFEXITED(rc) ? WEXITSTATUS(rc) : -1, e ? e : "");
    free(e);
    snprintf(p, sizeof p, "%s/adir.tmp", d);
    ck_assert_msg(!yft_exists(p), "%s: adir.tmp left", cases[k].line);
    snprintf(cmd, sizeof cmd, "rm -rf %s", d);
    if (system(cmd)) {}
    free(d);
  }
}
END_TEST

/* read_restart after a run of the deck is refused (it replaced the state reached and broke the
 * outputs' series: frames of the interrupted run dropped from the index, an off-cadence frame
 * listed); before the first run it continues the deck. */
START_TEST(test_read_restart_after_run_refused) {
  expect_fail(BAR "timestep auto\nrun 5\nread_restart x.restart\nrun 10 upto\n", 1,
              "bad.deck:5: error: read_restart: 'x.restart': read_restart after a run (or a read_restart) of this deck",
              "put it before the first run command");
  /* 'run 0' is a run: after it (and a body added) a restart was read over the new scene, and the
   * continuation differed from the uninterrupted run */
  expect_fail(BAR "timestep auto\nrun 0\nmesh rect c m 2 0 3 1 4 4\nread_restart x.restart\nrun 10 upto\n", 1,
              "bad.deck:6: error: read_restart: 'x.restart': read_restart after a run (or a read_restart) of this deck",
              NULL);
}
END_TEST

/* Out-of-range sizes at the line that gives them: cells doubles cannot tell apart (0.5 m cells at
 * 1e15 m) or whose areas underflow (a 1e-300 m box) gave zero-area triangles found only at the
 * run, with no line; a density so small every limit underflows was called "no triangles". */
START_TEST(test_sizes_beyond_doubles) {
  expect_fail(MAT "mesh rect b m 1e15 0 1000000000000001 1 2 2\nrun 1\n", 1,
              "bad.deck:2: error: mesh: '2': cells of 0.5 x 0.5 m, 1e+15 m from the origin: too small for doubles", NULL);
  expect_fail(MAT "mesh rect b m 0 0 1e-300 1e-300 2 2\nrun 1\n", 1,
              "bad.deck:2: error: mesh: '2': cells of 5e-301 x 5e-301 m: their areas underflow a double", NULL);
  /* rho 1e-300: omega_max 1e156 rad/s, though 3 lmax / rho overflows (the limit read as none,
   * so any explicit step ran: strain energy from nothing, "ok") */
  expect_fail("material m elastic rho 1e-300 E 1e9 nu 0.25 plane_stress\nmesh rect b m 0 0 1 1 2 2\ntimestep 1e-6\nrun 1\n", 1,
              "bad.deck:3: error: timestep 1e-06 s is above the stable limit 1.00569e-155 s (set by triangle 1", NULL);
  /* an inline triangle whose area underflows (1e-160 m legs) was found only at the run */
  expect_fail(MAT "node 1 0 0\nnode 2 1e-160 0\nnode 3 0 1e-160\ntriangle 1 1 2 3 m\ntimestep auto\nrun 1\n", 1,
              "bad.deck:5: error: triangle: triangle 1 has zero area (nodes 1 2 3 are collinear, or the area", NULL);
  /* E 1e307: omega_max itself overflows; auto gave dt = 0 and ran */
  expect_fail("material m elastic rho 1000 E 1e307 nu 0.25 plane_stress\nmesh rect b m 0 0 1 1 2 2\ntimestep auto\nrun 1\n", 1,
              "bad.deck:3: error: timestep auto: the stable limit 0 s (set by triangle 1 (material m)) is zero in doubles", NULL);
}
END_TEST

/* A run that goes wrong stops as a numerical failure naming the step and the element, keeps the
 * frames written before it, and exits 3. */
START_TEST(test_inverted_element_numerical_failure) {
  char *err, *dir;
  const char *deck = BAR "group tipn node nearest 1 0.1\nvelocity tipn set -3000 -3000\n"
                         "timestep auto\ndump d h5 1 out.h5\nrun 100\n";
  int rc = yft_run_binary("bad.deck", deck, "-summary s.json", &err, &dir);
  ck_assert_msg(rc == 3, "exit %d, stderr %s", rc, err);
  ck_assert_msg(strstr(err, "numerical failure at step") && strstr(err, "triangle") && strstr(err, "inverted"),
                "message: %s", err);
  char p[600];
  snprintf(p, sizeof p, "%s/out_000000.h5", dir);
  ck_assert_msg(yft_exists(p), "frames before the failure must be kept");
  snprintf(p, sizeof p, "%s/out.xmf", dir);
  char *x = slurp(p);
  ck_assert_ptr_nonnull(x);
  ck_assert_msg(strstr(x, "<Time") != NULL, "the XDMF index lists the frames written");
  free(x);
  free(err);
  free(dir);
  /* the summary's energies are the failing step's, whatever the thermo interval (they were the
   * last thermo step's, next to this step's external work) */
  char kin[2][64];
  for (int k = 0; k < 2; k++) {
    char d2[512]; /* a bar pulled at 1.9 x its stable step, no energy check: a triangle inverts at step 8 */
    snprintf(d2, sizeof d2, "material m elastic rho 1000 E 1e9 nu 0.25 plane_stress\nmesh rect b m 0 0 1 0.1 20 2\n"
             "region r box 0.99 -1 2 1\ngroup r node region r\nfix p r velocity 1 0\nenergy_check off\n"
             "timestep 6e-5\nthermo %d\nrun 20000\n", k ? 1 : 1000);
    rc = yft_run_binary("bad.deck", d2, "-summary s.json", &err, &dir);
    ck_assert_int_eq(rc, 3);
    snprintf(p, sizeof p, "%s/s.json", dir);
    char *js = slurp(p);
    const char *kp = strstr(js, "\"kinetic\": ");
    ck_assert_ptr_nonnull(kp);
    snprintf(kin[k], sizeof kin[k], "%.*s", (int)strcspn(kp + 11, ","), kp + 11);
    free(js);
    free(err);
    free(dir);
  }
  ck_assert_msg(!strcmp(kin[0], kin[1]), "kinetic energy at the failure: %s (thermo 1000), %s (thermo 1)", kin[0], kin[1]);
}
END_TEST

/* A state that overflows is the run's numerical failure (exit 3, its step) whatever output reads
 * it first: a record of 'strain' every step met the overflow before the step's own checks and
 * called it a deck error at the record line (exit 1, "expression 'strain': strain gives a
 * non-finite result"), the summary saying deck_error. */
START_TEST(test_record_reads_overflow_numerical_failure) {
  const char *deck = BAR "group tipn node nearest 1 0.1\nvelocity tipn set -3000 -3000\ntimestep auto\n"
                         "record rec 1 rec.csv step strain ke\nrun 100\n";
  expect_fail(deck, 3, "numerical failure at step 1:", "strain energy");
}
END_TEST

/* issue 20: nothing printed or written holds inf or nan.  A metrics log with no fracturing body
 * has no sigma1_max to give (it was -inf on every row): the field is empty.  A velocity so large
 * that the body leaves what doubles can resolve is named as such (it printed inf and -nan thermo
 * lines and blamed an inverted triangle). */
static int has_inf_nan(const char *t) {
  return strstr(t, "inf") || strstr(t, "nan") || strstr(t, "INF") || strstr(t, "NAN");
}
START_TEST(test_never_inf_nan) {
  char *err, *dir, p[600];
  int rc = yft_run_binary("m.deck", BAR "velocity bar set 1 0\ntimestep auto\nthermo 10\nmetrics log m.csv every 10\n"
                          "run 50\n", "-log run.log", &err, &dir);
  ck_assert_msg(rc == 0, "exit %d: %s", rc, err);
  snprintf(p, sizeof p, "%s/m.csv", dir);
  char *csv = slurp(p);
  ck_assert_ptr_nonnull(csv);
  ck_assert_msg(!has_inf_nan(csv), "metrics log holds inf or nan:\n%s", csv);
  /* row of step 10: sigma1_max (column 15) is empty, the energies are numbers */
  const char *row = strstr(csv, "\n10,");
  ck_assert_ptr_nonnull(row);
  int comma = 0;
  const char *q = row + 1;
  while (*q && comma < 14) comma += *q++ == ',';
  ck_assert_msg(*q == ',', "sigma1_max of a log with no fracturing body is not empty: %.200s", row + 1);
  free(csv);
  free(err);
  free(dir);
  rc = yft_run_binary("v.deck", BAR "velocity bar set 1e90 0\ntimestep auto\nthermo 1\nrun 50\n", "-log run.log", &err,
                      &dir);
  ck_assert_msg(rc == 3 && (strstr(err, "the range the arithmetic holds") || strstr(err, "overflows the range of a double")),
                "exit %d: %s", rc, err);
  ck_assert_msg(!has_inf_nan(err), "stderr holds inf or nan: %s", err);
  snprintf(p, sizeof p, "%s/run.log", dir);
  char *log = slurp(p);
  ck_assert_ptr_nonnull(log);
  ck_assert_msg(!has_inf_nan(log), "the -log holds inf or nan:\n%s", log);
  free(log);
  free(err);
  free(dir);
  /* Y2D decks with a contact penalty D1PEPE of 1e308 (it printed "is inf x the stable limit 0 s")
   * and a viscosity D1PEKS of 1e300 ("stable limit inf s"): both warn, run and stop as they blow up */
  char *y = slurp("tests/y2d/decks/a_elastic_block.y");
  ck_assert_ptr_nonnull(y);
  static const struct { const char *key, *val; } huge[] = {
      {"/YD/YDPE/D1PEPE 2\n", "1e308 1e308\n"}, {"/YD/YDPE/D1PEKS 2\n", "1e300 1e300\n"}};
  for (int k = 0; k < 2; k++) {
    char *at = strstr(y, huge[k].key);
    ck_assert_ptr_nonnull(at);
    at += strlen(huge[k].key);
    const char *eol = strchr(at, '\n') + 1;
    char *deck = malloc(strlen(y) + 64);
    sprintf(deck, "%.*s%s%s", (int)(at - y), y, huge[k].val, eol);
    rc = yft_run_binary("huge.y", deck, "-log none", &err, NULL);
    ck_assert_msg(rc == 3 && strstr(err, "warning: the Y2D deck's time step"), "%s: exit %d: %s", huge[k].val, rc, err);
    ck_assert_msg(!has_inf_nan(err), "%s: stderr holds inf or nan: %s", huge[k].val, err);
    free(err);
    free(deck);
  }
  free(y);
  /* names are not numbers: a folder 'inf' and a body 'inf' are printed as they are */
  char *d2 = yft_deck_dir("x.deck", "");
  char cmd[800];
  snprintf(cmd, sizeof cmd, "mkdir %s/inf", d2);
  ck_assert_int_eq(system(cmd), 0);
  yft_put_file(d2, "inf/nan.deck", MAT "mesh rect inf m 0 0 1 1 2 2\nfix f nothere fixed xy\n");
  snprintf(cmd, sizeof cmd, "cd %s && %s -in inf/nan.deck -log none 2> err.txt", d2, yft_binary());
  rc = system(cmd);
  snprintf(cmd, sizeof cmd, "%s/err.txt", d2);
  err = slurp(cmd);
  ck_assert_msg(strstr(err, "inf/nan.deck:3: error: fix: 'nothere': unknown group (defined groups: inf)"), "%s", err);
  free(err);
  free(d2);
}
END_TEST

/* A Gmsh mesh with duplicated, coincident nodes (two surfaces meshed without coherence) would run
 * as pieces that are not connected: warned, with the count and the first pair. */
START_TEST(test_gmsh_coincident_nodes_warned) {
  static const char msh[] =
      "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$PhysicalNames\n2\n2 1 \"soft\"\n2 2 \"hard\"\n$EndPhysicalNames\n"
      "$Entities\n0 0 2 0\n1 0 0 0 1 1 0 1 1 0\n2 0 0 0 1 1 0 1 2 0\n$EndEntities\n"
      "$Nodes\n2 6 1 6\n2 1 0 2\n1\n2\n0 0 0\n1 0 0\n2 2 0 4\n3\n4\n5\n6\n1 1 0\n0 1 0\n0.5 0.5 0\n0.5 0.5 0\n$EndNodes\n"
      "$Elements\n2 4 1 4\n2 1 2 2\n1 1 2 5\n2 3 5 4\n2 2 2 2\n3 2 3 6\n4 4 1 6\n$EndElements\n";
  char tmpl[] = "/tmp/yf_dup_XXXXXX";
  char *d = mkdtemp(tmpl);
  ck_assert_ptr_nonnull(d);
  char path[256];
  snprintf(path, sizeof path, "%s/dup.msh", d);
  FILE *f = fopen(path, "w");
  ck_assert_ptr_nonnull(f);
  fputs(msh, f);
  fclose(f);
  char deck[512], *err, *dir;
  snprintf(deck, sizeof deck, "material soft elastic rho 1000 E 1e9 nu 0.25 plane_stress\n"
           "material hard elastic rho 1000 E 1e9 nu 0.25 plane_stress\nmesh gmsh b %s\n", path);
  int rc = yft_run_binary("g.deck", deck, NULL, &err, &dir);
  ck_assert_msg(rc == 0, "exit %d: %s", rc, err);
  ck_assert_msg(strstr(err, "warning: mesh gmsh: 1 node of") && strstr(err, "nodes 5 and 6 at (0.5, 0.5)"), "%s", err);
  free(err);
  free(dir);
  unlink(path);
  rmdir(d);
}
END_TEST

/* The word under the caret of the first error in err ("" when there is none): the context line
 * above the caret line holds the deck line, both indented alike. */
static const char *caret_word(const char *err, char *buf, size_t n) {
  buf[0] = 0;
  const char *ctx = strchr(err, '\n');
  const char *car = ctx ? strchr(ctx + 1, '\n') : NULL;
  if (!car) return buf;
  ctx++, car++;
  size_t col = strcspn(car, "^\n");
  if (car[col] != '^' || col >= (size_t)(car - ctx)) return buf;
  size_t w = strcspn(ctx + col, " \n");
  snprintf(buf, n, "%.*s", (int)w, ctx + col);
  return buf;
}

/* material's elastic constants: lambda, mu is any pair of positive in-plane bulk modulus
 * (lambda > -mu), the range E > 0, nu in (-1, 0.5) covers ('lambda -0.5e9' was refused as
 * "give both lambda and mu": a negative lambda stood for "not given"), and each refusal points
 * at the word at fault (a conflict of E, nu and lambda, mu put the caret under 'rho'). */
START_TEST(test_material_constants) {
  static const char *const ok[] = {
      "material m elastic rho 1000 lambda -0.5e9 mu 1e9 plane_strain\n", /* E 1e9 nu -0.5 plane_strain */
      "material m elastic rho 1000 lambda -0.99e9 mu 1e9\n",              /* E 4e7 nu -0.98 plane_stress */
      "material m elastic rho 1000 lambda 0 mu 1e9\n",
      "material m elastic rho 1000 E 1e9 nu -0.2 plane_strain\n",
  };
  for (size_t k = 0; k < sizeof ok / sizeof ok[0]; k++) {
    char deck[512], *err;
    snprintf(deck, sizeof deck, "%smesh rect b m 0 0 1 1 2 2\ntimestep auto\nrun 2\n", ok[k]);
    int rc = yft_run_binary("ok.deck", deck, "-log none", &err, NULL);
    ck_assert_msg(rc == 0, "%s: exit %d: %s", ok[k], rc, err);
    free(err);
  }
  static const struct {
    const char *words, *want, *at;
  } bad[] = {
      {"lambda -1e9 mu 1e9", "'-1e9': lambda must be above -mu = -1e+09: the in-plane bulk modulus lambda + mu must be positive",
       "-1e9"},
      {"mu 1e9 lambda -2e9", "'-2e9': lambda must be above -mu = -1e+09", "-2e9"},
      {"lambda -0.6e9 mu 1e9 volfac 1", "'-0.6e9': lambda must be above -mu/2 with volfac 1 = -5e+08", "-0.6e9"},
      {"E 1e9 nu 0.3 plane_stress lambda 1 mu 1", "'lambda': give either E, nu or lambda, mu, not both", "lambda"},
      {"lambda 1 mu 1 nu 0.3 E 1e9 plane_stress", "'nu': give either E, nu or lambda, mu, not both", "nu"},
      {"lambda 1e9", "'lambda': missing 'mu'", "lambda"},
      {"mu 1e9", "'mu': missing 'lambda'", "mu"},
      {"nu 0.2 plane_strain", "'nu': missing 'E'", "nu"},
      {"E 1e9 nu 0.2 plane_strain visc 1 damping 0.1", "'damping': give either visc or damping, not both", "damping"},
  };
  for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++) {
    char deck[512], *err, want[300], w[64];
    snprintf(deck, sizeof deck, "material m elastic rho 1000 %s\n", bad[k].words);
    int rc = yft_run_binary("bad.deck", deck, "-log none", &err, NULL);
    snprintf(want, sizeof want, "bad.deck:1: error: material: %s", bad[k].want);
    ck_assert_msg(rc == 1 && strstr(err, want), "%s: exit %d, want '%s': %s", bad[k].words, rc, want, err);
    ck_assert_msg(!strcmp(caret_word(err, w, sizeof w), bad[k].at), "%s: caret under '%s', not '%s': %s", bad[k].words, w,
                  bad[k].at, err);
    free(err);
  }
}
END_TEST

/* A point load on a node no triangle meets (an inline node whose triangle was left out) went to
 * that massless node, which never moves: the force did nothing and the run ended ok.  Now it is a
 * deck error at the load's line; the same load on a triangle's node moves it (x 1 -> about 1 +
 * F t^2 / (2 m) after 10 steps, far above round-off). */
START_TEST(test_point_load_on_node_without_triangle) {
  static const char *const pre = "material m elastic rho 1000 E 1e9 nu 0.25 plane_stress\nnode 1 0 0\nnode 2 1 0\n"
                                 "node 3 1 1\nnode 4 2 2\ntriangle 1 1 2 3 m\n";
  char deck[1024];
  snprintf(deck, sizeof deck, "%sload p point node 4 1e6 0\ntimestep auto\ndump d h5 5 out.h5\nrun 10\n", pre);
  expect_fail(deck, 1, "bad.deck:7: error: load 'p': node 4 belongs to no triangle, so it has no mass and never moves",
              "'load p point at X Y' takes the nearest one");
  snprintf(deck, sizeof deck, "%sload p point node 2 1e6 0\ngroup g node id 2\ntimestep auto\nrun 10\n"
           "print \"moved $(ux_g > 1e-6)\"\n", pre);
  YfSim *sim = yft_run(deck);
  int k = yft_node_at(sim, 1.0, 0.0);
  ck_assert_double_gt(sim->model.node.x[k] - 1.0, 1e-6);
  sim_free(sim);
}
END_TEST

Suite *errors_suite(void) {
  Suite *s = suite_create("errors");
  TCase *t = tcase_create("deck");
  tcase_set_timeout(t, 60);
  tcase_add_test(t, test_unknown_command_suggests);
  tcase_add_test(t, test_nul_byte_in_deck);
  tcase_add_test(t, test_wrong_argument_count);
  tcase_add_test(t, test_non_numeric_number);
  tcase_add_test(t, test_unknown_group);
  tcase_add_test(t, test_bad_choice_lists_valid);
  tcase_add_test(t, test_missing_include_is_io_error);
  tcase_add_test(t, test_bad_mesh_file);
  tcase_add_test(t, test_timestep_above_limit_refused);
  tcase_add_test(t, test_damping_above_two_over_dt_refused);
  tcase_add_test(t, test_record_bad_quantity_no_file);
  tcase_add_test(t, test_run_expression_error_names_step);
  tcase_add_test(t, test_inputs_that_are_not_files);
  tcase_add_test(t, test_read_restart_after_run_refused);
  tcase_add_test(t, test_sizes_beyond_doubles);
  tcase_add_test(t, test_inverted_element_numerical_failure);
  tcase_add_test(t, test_never_inf_nan);
  tcase_add_test(t, test_record_reads_overflow_numerical_failure);
  tcase_add_test(t, test_gmsh_coincident_nodes_warned);
  tcase_add_test(t, test_material_constants);
  tcase_add_test(t, test_point_load_on_node_without_triangle);
  suite_add_tcase(s, t);
  return s;
}
