/* check_habits.c: what a LAMMPS user expects of the program around the physics: a log file by
 * default (input lines, thermo, messages), a line per group, custom thermo columns and record
 * files, a timing table per run, a warning for a -var the deck never uses, "did you mean" in -h,
 * no output file from a deck that fails before its first run, and no system call in the step.
 * The real binary ($YFDEM) runs small decks in a temporary directory (yft_run_binary); its
 * stdout is read back from the log. */
#include <check.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>
#include "yftest.h"

#define BAR "variable nx index 10\n" \
            "material m elastic rho 1000 E 1e9 nu 0.25 plane_stress\n" \
            "mesh rect bar m 0 0 1 0.1 ${nx} 2\n" \
            "region l box -1 -1 1e-9 1\n" \
            "group left node region l\n" \
            "fix hold left fixed xy\n" \
            "velocity bar set 0 -0.1\n" \
            "timestep auto\n"

static char *file_in(const char *dir, const char *name) {
  char p[600];
  snprintf(p, sizeof p, "%s/%s", dir, name);
  return yft_slurp(p, 0);
}

static int count_lines(const char *s) {
  int n = 0;
  for (; s && *s; s++) n += *s == '\n';
  return n;
}

/* log.yfdem holds the input as read (after substitution), the group line, the custom thermo
 * header and lines, the timing table; record writes its rows at the run start and every N steps. */
START_TEST(test_log_thermo_record) {
  char *err, *dir;
  int rc = yft_run_binary("a.deck", BAR "thermo 10\nthermo_style custom step time ke broken uy_left \"ke+strain\"\n"
                          "record r 5 rec.csv ke vy_bar\nrun 20\n", "", &err, &dir);
  ck_assert_msg(rc == 0, "exit %d:\n%s", rc, err);
  char *log = file_in(dir, "log.yfdem");
  ck_assert_msg(log != NULL, "no log.yfdem");
  ck_assert_msg(strstr(log, "mesh rect bar m 0 0 1 0.1 10 2\n") != NULL, "input line (substituted) not in the log:\n%s", log);
  ck_assert_msg(strstr(log, "group left: 3 nodes, 0 triangles\n") != NULL, "no group line:\n%s", log);
  ck_assert_msg(strstr(log, "      Step          Time        KinEng        Broken       uy_left     ke+strain\n") != NULL,
                "custom thermo header:\n%s", log);
  ck_assert_msg(strstr(log, "\n        20 ") != NULL, "thermo line of step 20:\n%s", log);
  ck_assert_msg(strstr(log, "stage         seconds    %run\nelements ") != NULL, "timing table:\n%s", log);
  ck_assert_msg(strstr(log, "\nother ") != NULL, "timing table's other row:\n%s", log);
  char *rec = file_in(dir, "rec.csv");
  ck_assert_msg(rec != NULL, "no rec.csv");
  ck_assert_msg(!strncmp(rec, "step,time,ke,vy_bar\n0,0,", 24), "rec.csv:\n%s", rec);
  ck_assert_int_eq(count_lines(rec), 1 + 5); /* header, steps 0 5 10 15 20 */
  /* the start: every node at -0.1 m/s, ke = 1/2 (rho L H) v^2 = 1/2 100 kg/m 0.01 = 0.5 J/m */
  long st;
  double t, ke, vy;
  ck_assert_int_eq(sscanf(strchr(rec, '\n') + 1, "%ld,%lf,%lf,%lf", &st, &t, &ke, &vy), 4);
  ck_assert_msg(st == 0 && t == 0 && fabs(ke - 0.5) < 1e-12 && fabs(vy + 0.1) < 1e-12, "row 0: %ld %g %.17g %.17g", st,
                t, ke, vy);
  free(rec);
  free(log);
  free(err);
  free(dir);
}
END_TEST

/* -log none: no log file; -log FILE: that file. */
START_TEST(test_log_none_and_named) {
  char *err, *dir;
  int rc = yft_run_binary("a.deck", BAR "run 2\n", "-log none", &err, &dir);
  ck_assert_int_eq(rc, 0);
  char p[600];
  snprintf(p, sizeof p, "%s/log.yfdem", dir);
  ck_assert(!yft_exists(p));
  free(err);
  free(dir);
  rc = yft_run_binary("a.deck", BAR "run 2\n", "-log my.log", &err, &dir);
  ck_assert_int_eq(rc, 0);
  char *log = file_in(dir, "my.log");
  ck_assert_msg(log && strstr(log, "run 2\n"), "my.log:\n%s", log ? log : "(none)");
  free(log);
  free(err);
  free(dir);
}
END_TEST

/* -var for a name the deck never defines nor uses: a warning that names the deck's variables. */
START_TEST(test_var_unused_warns) {
  char *err, *dir;
  int rc = yft_run_binary("a.deck", BAR "run 1\n", "-var nz 20 -var nx 4", &err, &dir);
  ck_assert_int_eq(rc, 0);
  ck_assert_msg(strstr(err, "warning: -var nz: the deck defines and uses no variable 'nz' (its variables: nx); "
                            "did you mean 'nx'?") != NULL, "stderr:\n%s", err);
  ck_assert_msg(strstr(err, "-var nx") == NULL, "a used -var warned:\n%s", err);
  char *log = file_in(dir, "log.yfdem");
  ck_assert_msg(log && strstr(log, "-var nz"), "the warning is not in the log");
  ck_assert_msg(strstr(log, "mesh rect bar m 0 0 1 0.1 4 2\n") != NULL, "-var nx not applied:\n%s", log);
  free(log);
  free(err);
  free(dir);
  /* names the deck uses only after its first run (a second run's length, an expression's v_name)
   * are used: no warning, and the values arrive; a typo beside them is still warned about */
  rc = yft_run_binary("a.deck", BAR "run 1\nrun ${more}\nprint \"twice $(v_extra*2)\"\n",
                      "-var nx 4 -var more 3 -var extra 1.5 -var mroe 3", &err, &dir);
  ck_assert_int_eq(rc, 0);
  ck_assert_msg(strstr(err, "-var more") == NULL && strstr(err, "-var extra") == NULL,
                "a -var used after the first run warned:\n%s", err);
  ck_assert_msg(strstr(err, "warning: -var mroe:") != NULL, "the typo was not warned about:\n%s", err);
  log = file_in(dir, "log.yfdem");
  ck_assert_msg(log && strstr(log, "run 3\n") && strstr(log, "twice 3"), "late -var values not applied:\n%s", log);
  free(log);
  free(err);
  free(dir);
  /* a name used only in a file included after the first run (and in one that file includes) is
   * used: it was warned about as unused, though the include read it */
  dir = yft_deck_dir("a.deck", BAR "run 1\ninclude post/report.deck\n");
  char sub[700];
  snprintf(sub, sizeof sub, "%s/post", dir);
  ck_assert_int_eq(mkdir(sub, 0700), 0);
  yft_put_file(dir, "post/report.deck", "print \"scale ${scale}\"\ninclude more.deck\n");
  yft_put_file(dir, "post/more.deck", "print \"depth $(v_depth*2)\"\n");
  char cmd[2048];
  snprintf(cmd, sizeof cmd, "cd %s && %s -in a.deck -var scale 3 -var depth 2 -var sclae 1 > out.txt 2> err.txt", dir,
           yft_binary());
  ck_assert_int_eq(system(cmd), 0);
  err = file_in(dir, "err.txt");
  ck_assert_msg(strstr(err, "-var scale:") == NULL && strstr(err, "-var depth:") == NULL,
                "a -var used in an included file warned:\n%s", err);
  ck_assert_msg(strstr(err, "warning: -var sclae:") != NULL, "the typo was not warned about:\n%s", err);
  char *out = file_in(dir, "out.txt");
  ck_assert_msg(strstr(out, "scale 3\n") && strstr(out, "depth 4\n"), "stdout:\n%s", out);
  free(out);
  free(err);
  free(dir);
}
END_TEST

/* Thermo lines and messages reach stdout and the log as they are printed, also when stdout is a
 * file (nohup, a batch queue: the C library would hold them in its buffer until exit): a deck
 * that runs, prints, then starts a run far too long to finish (no thermo lines) has its lines in
 * both files while it is still running; SIGTERM then stops it (exit 130). */
START_TEST(test_flushed_while_running) {
  char *dir = yft_deck_dir("a.deck", BAR "thermo 5\nrun 10\nprint \"after the run\"\nthermo 0\nrun 1000000000\n");
  char cmd[2048];
  snprintf(cmd, sizeof cmd, "cd %s && exec %s -in a.deck > out.txt 2> err.txt", dir, yft_binary());
  pid_t pid = fork();
  ck_assert(pid >= 0);
  if (pid == 0) {
    execl("/bin/sh", "sh", "-c", cmd, (char *)NULL);
    _exit(127);
  }
  char *out = NULL, *log = NULL;
  int seen = 0;
  for (int i = 0; i < 400 && !seen; i++) { /* up to 20 s */
    struct timespec ts = {0, 50000000};
    nanosleep(&ts, NULL);
    free(out);
    free(log);
    out = file_in(dir, "out.txt");
    log = file_in(dir, "log.yfdem");
    seen = out && log && strstr(out, "after the run\n") && strstr(log, "after the run\n");
  }
  kill(pid, SIGTERM);
  int st = 0;
  for (int i = 0; i < 200 && waitpid(pid, &st, WNOHANG) == 0; i++) { /* up to 10 s, then SIGKILL */
    struct timespec ts = {0, 50000000};
    nanosleep(&ts, NULL);
    if (i == 199) {
      kill(pid, SIGKILL);
      waitpid(pid, &st, 0);
    }
  }
  ck_assert_msg(seen, "while running, stdout holds:\n%s\nand log.yfdem:\n%s", out ? out : "(none)", log ? log : "(none)");
  ck_assert_msg(strstr(out, "\n        10 ") && strstr(out, "run: 10 steps"), "thermo lines not in stdout:\n%s", out);
  ck_assert_msg(WIFEXITED(st) && WEXITSTATUS(st) == 130, "SIGTERM: status %d", st);
  free(out);
  free(log);
  snprintf(cmd, sizeof cmd, "rm -rf %s", dir);
  if (system(cmd)) {}
  free(dir);
}
END_TEST

/* yfdem -h with a misspelt command suggests the nearest one, as the deck does. */
START_TEST(test_help_suggests) {
  const char *bin = getenv("YFDEM") ? getenv("YFDEM") : "./yfdem";
  char cmd[1200];
  snprintf(cmd, sizeof cmd, "%s -h contcat 2>&1 >/dev/null | grep -q \"no deck command 'contcat' (did you mean 'contact'?)\"", bin);
  int st = system(cmd);
  ck_assert_msg(WIFEXITED(st) && WEXITSTATUS(st) == 0, "yfdem -h contcat did not suggest contact");
}
END_TEST

/* A deck that fails before its first run leaves no output behind (fracture_log, metrics log,
 * record, dumps): neither when a command before `run` is at fault, nor when `run` itself refuses
 * to start (a time step above the stable limit) or write_restart cannot write, after the scene
 * was prepared (joints inserted).  Until issue 19 the last two left header-only CSVs.  Only the
 * log (log.yfdem, which says why) remains. */
START_TEST(test_no_files_before_run) {
  static const char *const tail[][2] = {
      {"bogus 1\nrun 10\n", "1"},
      {"timestep 1\nrun 10\n", "1"},                     /* refused by run, before step 0 */
      {"write_restart no_dir/r.restart\nrun 10\n", "2"}, /* prepares the scene, then fails */
  };
  for (size_t c = 0; c < sizeof tail / sizeof *tail; c++) {
    char deck[4096], *err, *dir;
    snprintf(deck, sizeof deck, "%s", BAR "jointprop j ft 1e6 fs 1e6 gf 10 pen 1e11\nfracture bar j\n"
             "fracture_log b.csv opened o.csv\nmetrics body bar\nmetrics log m.csv every 5\n"
             "record r 5 rec.csv ke\ndump d h5 5 d.h5\ndump c csv 5 c\n");
    snprintf(deck + strlen(deck), sizeof deck - strlen(deck), "%s", tail[c][0]);
    int rc = yft_run_binary("a.deck", deck, "", &err, &dir);
    ck_assert_msg(rc == atoi(tail[c][1]), "case %zu: exit %d:\n%s", c, rc, err);
    static const char *const f[] = {"b.csv", "o.csv", "m.csv", "rec.csv", "d.xmf", "d_000000.h5", "d_cracks.xmf",
                                    "c_frames.csv", "c_000000.csv"};
    for (size_t i = 0; i < sizeof f / sizeof *f; i++) {
      char p[600];
      snprintf(p, sizeof p, "%s/%s", dir, f[i]);
      ck_assert_msg(!yft_exists(p), "case %zu (%s): %s left behind by a deck that failed before run", c, tail[c][0],
                    f[i]);
    }
    char p[600];
    snprintf(p, sizeof p, "%s/log.yfdem", dir);
    ck_assert_msg(yft_exists(p), "case %zu: no log.yfdem", c);
    free(err);
    free(dir);
  }
}
END_TEST

/* README, Files: what a deck reads is relative to the deck's directory, what yfdem writes is
 * relative to the working directory (as LAMMPS).  A deck in sub/ run from its parent with every
 * kind of output: each file lands in the working directory and none in sub/ (the y2dref dump's
 * folder was made beside the deck until 2026-11-28). */
START_TEST(test_outputs_in_working_dir) {
  char tmpl[] = "/tmp/yft_cwd_XXXXXX", cwd[1024], cmd[4096], p[1200];
  char *dir = mkdtemp(tmpl);
  ck_assert_ptr_nonnull(dir);
  ck_assert_ptr_nonnull(getcwd(cwd, sizeof cwd));
  snprintf(p, sizeof p, "%s/sub", dir);
  ck_assert_int_eq(mkdir(p, 0755), 0);
  snprintf(p, sizeof p, "%s/sub/a.deck", dir);
  FILE *f = fopen(p, "w");
  ck_assert_ptr_nonnull(f);
  fputs(BAR "jointprop j ft 1e6 fs 1e6 gf 10 pen 1e11 damage reversible\nfracture bar j\nfracture_log b.csv opened o.csv\n"
        "metrics body bar\nmetrics log m.csv every 5\nrecord r 5 rec.csv ke\ndump d h5 5 d.h5\ndump c csv 5 c\n"
        "dump y y2dref yref corners 0,10\nrestart every 5 rs.restart\ntimestep auto\nwrite_y2d x.y steps 10\n"
        "run 10\nwrite_restart w.restart\n", f);
  fclose(f);
  const char *bin = getenv("YFDEM") ? getenv("YFDEM") : "./yfdem";
  snprintf(cmd, sizeof cmd, "cd %s && OMP_NUM_THREADS=1 %s%s%s -in sub/a.deck -summary s.json >/dev/null 2>err.txt", dir,
           bin[0] == '/' ? "" : cwd, bin[0] == '/' ? "" : "/", bin);
  ck_assert_int_eq(system(cmd), 0);
  static const char *const out[] = {"b.csv", "o.csv", "m.csv", "rec.csv", "d.xmf", "d_000002.h5", "c_frames.csv",
                                    "c_000002.csv", "yref/corners_0000010.csv", "yref/broken.csv", "rs.restart.a",
                                    "w.restart", "x.y", "s.json", "log.yfdem"};
  for (size_t i = 0; i < sizeof out / sizeof *out; i++) {
    snprintf(p, sizeof p, "%s/%s", dir, out[i]);
    ck_assert_msg(yft_exists(p), "%s not written in the working directory", out[i]);
    snprintf(p, sizeof p, "%s/sub/%s", dir, out[i]);
    ck_assert_msg(!yft_exists(p), "%s written beside the deck (sub/), not in the working directory", out[i]);
  }
  snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
  ck_assert_int_eq(system(cmd), 0);
}
END_TEST

/* Files written whole (the -summary JSON, fracture_log, metrics log) go through a symbolic link
 * and into a pipe or a device as a shell user means them: -summary /dev/stdout (a link to
 * /proc/self/fd/1) used to replace the link by a regular file, printing nothing, and as root a
 * device (/dev/full) became a regular file and its "no space" was never seen. */
START_TEST(test_whole_files_through_links_and_devices) {
  char *dir = yft_deck_dir("a.deck", BAR "jointprop j ft 1e6 fs 1e6 gf 10 pen 1e11\nfracture bar j\nfracture_log breaks.csv\n"
                                         "run 5\n");
  char p[600], cmd[4096];
  const char *bin = yft_binary();
  /* a link to a file elsewhere; the JSON to a pipe; the fracture log through a link */
  snprintf(cmd, sizeof cmd,
           "cd %s && mkdir real && ln -s real/s.json s.json && ln -s real/b.csv breaks.csv && "
           "%s -in a.deck -summary s.json -log none >/dev/null 2>err1.txt && "
           "%s -in a.deck -summary /dev/stdout -log none 2>err2.txt | grep -c state_hash > piped.txt",
           dir, bin, bin);
  ck_assert_int_eq(system(cmd), 0);
  struct stat st;
  snprintf(p, sizeof p, "%s/s.json", dir);
  ck_assert(lstat(p, &st) == 0 && S_ISLNK(st.st_mode));
  snprintf(p, sizeof p, "%s/breaks.csv", dir);
  ck_assert(lstat(p, &st) == 0 && S_ISLNK(st.st_mode));
  char *j = file_in(dir, "real/s.json"), *b = file_in(dir, "real/b.csv"), *pi = file_in(dir, "piped.txt");
  ck_assert_msg(j && strstr(j, "\"status\": \"ok\""), "the link's target: %s", j ? j : "(none)");
  ck_assert_msg(b && !strncmp(b, "step,time,x,y", 13), "the fracture log's target: %s", b ? b : "(none)");
  ck_assert_msg(pi && atoi(pi) == 1, "the JSON did not reach the pipe: %s", pi ? pi : "(none)");
  free(j);
  free(b);
  free(pi);
  /* a full device (a node of its own, as root: never the machine's /dev/full): an I/O error,
   * exit 2, the device left a device */
  snprintf(p, sizeof p, "%s/full", dir);
  if (mknod(p, S_IFCHR | 0666, makedev(1, 7)) == 0) {
    snprintf(cmd, sizeof cmd, "cd %s && %s -in a.deck -summary full -log none >/dev/null 2>err3.txt", dir, bin);
    int rc = system(cmd);
    char *e = file_in(dir, "err3.txt");
    ck_assert_msg(WIFEXITED(rc) && WEXITSTATUS(rc) == 2 && e && strstr(e, "No space left on device"), "exit %d: %s", rc,
                  e ? e : "");
    free(e);
    ck_assert(lstat(p, &st) == 0 && S_ISCHR(st.st_mode));
  }
  snprintf(cmd, sizeof cmd, "rm -rf %s", dir);
  if (system(cmd)) {}
  free(dir);
}
END_TEST

/* -summary on the log's file (the default log.yfdem): refused before anything runs, exit 1. */
START_TEST(test_summary_on_the_log_refused) {
  char *err, *dir;
  int rc = yft_run_binary("a.deck", BAR "run 2\n", "-summary log.yfdem", &err, &dir);
  ck_assert_msg(rc == 1 && strstr(err, "yfdem: -summary 'log.yfdem': already written by the log (-log)"), "exit %d: %s", rc,
                err);
  free(err);
  free(dir);
  /* an option where a file name belongs ('-log -in deck' made a log named '-in') */
  rc = yft_run_binary("a.deck", BAR "run 2\n", "-log -summary s.json", &err, &dir);
  ck_assert_msg(rc == 1 && strstr(err, "yfdem: -log '-summary': expected a file name after -log, not an option"),
                "exit %d: %s", rc, err);
  free(err);
  free(dir);
  /* two decks: 'yfdem a.y -in b.deck' ran b.deck alone and never looked at a.y (nor said it was missing) */
  const char *second[] = {"-in other.deck", "other.y"};
  for (int k = 0; k < 2; k++) {
    rc = yft_run_binary("a.deck", BAR "run 2\n", second[k], &err, &dir);
    ck_assert_msg(rc == 1 && strstr(err, "the deck is already") && strstr(err, "give one deck"), "%s: exit %d: %s",
                  second[k], rc, err);
    free(err);
    free(dir);
  }
}
END_TEST

/* LAMMPS reads '-var n 10 20' as an index of two values; yfdem's -var takes one, and the second
 * value was taken for a deck: "the deck is already 'a.deck'", or under '< deck' "cannot open deck
 * '20'", neither of which says what went wrong.  Now the message names -var and the remedy, with
 * exit 1 (2 when no deck was given, as for a missing deck file); a deck file after a -var still
 * runs. */
START_TEST(test_var_takes_one_value) {
  char *err, *dir;
  int rc = yft_run_binary("a.deck", BAR "run 2\nprint \"nx ${nx}\"\n", "-var nx 10 20", &err, &dir);
  ck_assert_msg(rc == 1 && strstr(err, "yfdem: '20': -var takes one value ('-var nx 10' was read)") &&
                strstr(err, "'variable nx index 10 20 ...'"), "exit %d: %s", rc, err);
  free(err);
  free(dir);
  dir = yft_deck_dir("a.deck", BAR "run 2\nprint \"nx ${nx}\"\n");
  char cmd[4096];
  snprintf(cmd, sizeof cmd, "cd %s && %s -var nx 12 20 < a.deck > out.txt 2> err.txt; echo $? > rc.txt; "
           "%s -var nx 12 a.deck > out2.txt 2>&1", dir, yft_binary(), yft_binary());
  ck_assert_int_eq(system(cmd), 0);
  char p[4200];
  snprintf(p, sizeof p, "%s/err.txt", dir);
  char *e = yft_slurp(p, 0);
  snprintf(p, sizeof p, "%s/rc.txt", dir);
  char *c = yft_slurp(p, 0);
  ck_assert_msg(atoi(c) == 2 && strstr(e, "'20': no such deck file; if it is a second value, -var takes one value"),
                "exit %s: %s", c, e);
  snprintf(p, sizeof p, "%s/out2.txt", dir);
  char *o = yft_slurp(p, 0);
  ck_assert_msg(strstr(o, "nx 12\n"), "%s", o);
  free(e);
  free(c);
  free(o);
  free(dir);
}
END_TEST

/* LAMMPS's spellings on yfdem's command line: '-echo screen' made 'screen' the deck ("the deck is
 * already"), '-v', '-sc none', '-pk omp 2' were "unknown or incomplete option" with no way on, and
 * an option cut short ('-var n' at the end) did not say what it lacked; '-log ""' was an I/O error
 * (exit 2, -summary's a command-line one), '-in -' "cannot open deck '-'" and '-reference sectons'
 * printed the table, its typo unseen. Each now names the word at fault and yfdem's way, exit 1,
 * before anything runs. */
START_TEST(test_lammps_options_hinted) {
  static const struct {
    const char *args, *msg;
  } cases[] = {
      {"-echo screen", "yfdem: -echo 'screen': -echo takes no value (LAMMPS's -echo screen|log|both|none)"},
      {"-echo none", "yfdem: -echo 'none': -echo takes no value"},
      {"-v nx 4", "yfdem: unknown option '-v': yfdem sets a variable with -var NAME VALUE"},
      {"-sc none", "yfdem: unknown option '-sc': yfdem has no -screen: send the screen elsewhere with > FILE"},
      {"-pk omp 2", "yfdem: unknown option '-pk': yfdem sets its OpenMP threads with -threads N"},
      {"-x", "yfdem: unknown or incomplete option '-x': the options are -in FILE, -var NAME VALUE,"},
      {"-var nx", "yfdem: -var expects NAME VALUE after it, and the command line ends before"},
      {"-threads", "yfdem: -threads expects N|auto after it"},
      {"-log ''", "yfdem: -log '': an empty file name (give -log FILE, or -log none"},
      {"-in -", "yfdem: -in '-': yfdem reads standard input when no deck is given: yfdem < FILE"},
      {"-reference sectons", "yfdem: -reference 'sectons': expected 'sections' (a section per command) or nothing"},
  };
  for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
    char *err, *dir;
    int rc = yft_run_binary("a.deck", BAR "run 2\nprint \"done\"\n", cases[k].args, &err, &dir);
    ck_assert_msg(rc == 1 && strstr(err, cases[k].msg), "'%s': exit %d: %s", cases[k].args, rc, err);
    char *log = file_in(dir, "log.yfdem"); /* refused before the deck was read */
    ck_assert_msg(!log, "'%s' ran the deck", cases[k].args);
    free(err);
    free(dir);
  }
}
END_TEST

/* '-var nx 4 ... -var nx 6' (a sweep script that appends its value to a base command line) kept
 * the last value in silence, where LAMMPS keeps the first: it still keeps the last, and says so. */
START_TEST(test_var_given_twice_warned) {
  char *err, *dir;
  int rc = yft_run_binary("a.deck", BAR "run 0\nprint \"nx ${nx}\"\n", "-var nx 4 -var nx 6", &err, &dir);
  char *out = file_in(dir, "log.yfdem");
  ck_assert_msg(rc == 0 && strstr(err, "warning: -var nx is given twice ('4', then '6'): the last is used") && out &&
                strstr(out, "nx 6\n"), "exit %d: %s", rc, err);
  free(out);
  free(err);
  free(dir);
}
END_TEST

/* A deck without a command ('yfdem < /dev/null', an empty or comment-only file a generator left)
 * ran nothing and exited 0 in silence, as a run that went well; it still exits 0 but warns.  And
 * 'yfdem' alone at a terminal waited for a deck without a word: it now says what it waits for
 * (run under script(1), which gives it a terminal). */
START_TEST(test_empty_deck_and_terminal_stdin) {
  char *dir = yft_deck_dir("c.deck", "# a deck to come\n\n");
  yft_put_file(dir, "e.deck", "");
  char cmd[4096];
  snprintf(cmd, sizeof cmd, "cd %s && %s -log none -in c.deck 2> err1.txt; echo $? > rc1.txt; "
           "%s -log none < e.deck 2> err2.txt; echo $? > rc2.txt; "
           "printf 'print \"from the terminal\"\\n\\004' | timeout 60 script -qec '%s -log none' /dev/null > tty.txt 2>&1; "
           "echo $? > rc3.txt",
           dir, yft_binary(), yft_binary(), yft_binary());
  ck_assert_int_eq(system(cmd), 0);
  const char *want[2] = {"c.deck:1: warning: the deck holds no command (it is empty, or only comments and blank "
                         "lines): nothing was done",
                         "<stdin>:1: warning: the deck holds no command"};
  for (int k = 0; k < 2; k++) {
    char name[32];
    snprintf(name, sizeof name, "err%d.txt", k + 1);
    char *e = file_in(dir, name);
    snprintf(name, sizeof name, "rc%d.txt", k + 1);
    char *c = file_in(dir, name);
    ck_assert_msg(e && c && atoi(c) == 0 && strstr(e, want[k]), "exit %s: %s", c, e);
    free(e);
    free(c);
  }
  char *t = file_in(dir, "tty.txt"), *c = file_in(dir, "rc3.txt");
  ck_assert_msg(t && c && atoi(c) == 0 &&
                strstr(t, "yfdem: reading the deck from the terminal: type commands, end with Ctrl-D") &&
                strstr(t, "from the terminal"), "exit %s: %s", c, t);
  free(t);
  free(c);
  free(dir);
}
END_TEST

/* 'run 0' (the LAMMPS idiom for setting up and reading quantities) printed the thermo line of step 0
 * twice, once as the run's start and once as its end; LAMMPS prints it once, and so does yfdem
 * now, while 'run 5' with thermo 5 still prints steps 0 and 5. */
START_TEST(test_run_zero_prints_one_line) {
  char *err, *dir;
  int rc = yft_run_binary("z.deck", BAR "thermo 5\nthermo_style custom step ke\nrun 0\nrun 5\n", NULL, &err, &dir);
  ck_assert_msg(rc == 0, "exit %d: %s", rc, err);
  char p[4096];
  snprintf(p, sizeof p, "%s/log.yfdem", dir);
  char *log = yft_slurp(p, 0);
  int zeros = 0, fives = 0;
  for (const char *q = log; q && *q; q = strchr(q, '\n') ? strchr(q, '\n') + 1 : NULL) {
    long step;
    char rest[8];
    if (sscanf(q, " %ld %7s", &step, rest) == 2 && rest[0] != '\0') {
      if (step == 0 && strncmp(q, "run", 3)) zeros++;
      if (step == 5) fives++;
    }
  }
  /* step 0: once for run 0, once as run 5's start; step 5: run 5's end */
  ck_assert_msg(zeros == 2 && fives == 1, "step-0 lines %d, step-5 lines %d:\n%s", zeros, fives, log);
  free(log);
  free(err);
  free(dir);
}
END_TEST

/* Standard output that cannot be written: 'yfdem deck | head -1' was killed by SIGPIPE (exit 141)
 * with no summary, and stdout on a full disk ran on to "ok" with every thermo line lost.  Both
 * are an output error now: exit 2, the summary written with status io_error. */
START_TEST(test_stdout_unwritable) {
  char *dir = yft_deck_dir("p.deck", BAR "thermo 1\nrun 3000\n");
  /* (no standard output at all, '>&-' as a daemon runs, asks for none: the run goes on, exit 0) */
  const char *how[3] = {"| head -1 >/dev/null", ">/dev/full", ">&-"};
  for (int k = 0; k < 3; k++) {
    char cmd[4096];
    snprintf(cmd, sizeof cmd, "cd %s && rm -f s.json && bash -c 'OMP_NUM_THREADS=1 %s -in p.deck -log none -summary s.json "
             "2>err.txt %s; echo ${PIPESTATUS[0]} > rc.txt'", dir, yft_binary(), how[k]);
    ck_assert_int_eq(system(cmd), 0);
    char *rc = file_in(dir, "rc.txt"), *j = file_in(dir, "s.json"), *e = file_in(dir, "err.txt");
    ck_assert_msg(rc && atoi(rc) == (k < 2 ? 2 : 0) && e && !strstr(e, "cannot write to standard output") == (k == 2),
                  "%s: exit %s: %s", how[k], rc ? rc : "?", e ? e : "");
    ck_assert_msg(j && strstr(j, k < 2 ? "\"status\": \"io_error\"" : "\"status\": \"ok\""), "%s: summary %s", how[k],
                  j ? j : "missing");
    free(rc); free(j); free(e);
  }
  char cmd[600];
  snprintf(cmd, sizeof cmd, "rm -rf %s", dir);
  if (system(cmd)) {}
  free(dir);
}
END_TEST

/* Run the binary on an existing deck dir with extra args; stderr in *err. */
static int run_in_dir(const char *dir, const char *deck, const char *args, char **err) {
  char cmd[4096];
  snprintf(cmd, sizeof cmd, "cd %s && OMP_NUM_THREADS=1 %s -in %s %s >/dev/null 2>stderr.txt", dir, yft_binary(), deck, args);
  int st = system(cmd);
  *err = file_in(dir, "stderr.txt");
  return WIFEXITED(st) ? WEXITSTATUS(st) : 128;
}

/* Outputs that wrote over files they do not own: -log or -summary naming the deck itself (the
 * deck emptied before it was read, or overwritten by the JSON), write_restart over the log,
 * write_y2d over a dump's index, write_restart onto a fifo (renamed over it), an empty or a
 * too long -summary (ignored, or cut short and written elsewhere).  Each is refused at once,
 * with nothing lost; write_restart twice to one file writes it twice. */
START_TEST(test_outputs_never_overwrite_inputs) {
  char *err, *dir;
  int rc = yft_run_binary("a.deck", BAR "run 2\n", "-log a.deck", &err, &dir);
  ck_assert_msg(rc == 1 && strstr(err, "yfdem: -log 'a.deck': that is the deck being read (-in)"), "exit %d: %s", rc, err);
  char *deck = file_in(dir, "a.deck");
  ck_assert_msg(strstr(deck, "run 2"), "the deck was damaged: '%s'", deck);
  free(deck);
  free(err);
  rc = run_in_dir(dir, "a.deck", "-summary ./a.deck", &err);
  ck_assert_msg(rc == 1 && strstr(err, "yfdem: -summary './a.deck': that is the deck being read (-in)"), "exit %d: %s", rc, err);
  free(err);
  /* the deck through a link, or on stdin: the same file */
  char cmd0[700];
  snprintf(cmd0, sizeof cmd0, "ln -s a.deck %s/link.deck", dir);
  ck_assert_int_eq(system(cmd0), 0);
  rc = run_in_dir(dir, "link.deck", "-log a.deck", &err);
  ck_assert_msg(rc == 1 && strstr(err, "yfdem: -log 'a.deck': that is the deck being read (-in)"), "exit %d: %s", rc, err);
  free(err);
  snprintf(cmd0, sizeof cmd0, "cd %s && %s -log a.deck < a.deck >/dev/null 2>stderr.txt", dir, yft_binary());
  rc = system(cmd0);
  err = file_in(dir, "stderr.txt");
  ck_assert_msg(WIFEXITED(rc) && WEXITSTATUS(rc) == 1 && strstr(err, "that is the deck being read (stdin)"), "%s", err);
  free(err);
  deck = file_in(dir, "a.deck");
  ck_assert_msg(strstr(deck, "run 2"), "the deck was damaged: '%s'", deck);
  free(deck);
  rc = run_in_dir(dir, "a.deck", "-summary ''", &err);
  ck_assert_msg(rc == 1 && strstr(err, "an empty file name"), "exit %d: %s", rc, err);
  free(err);
  char longp[1200];
  memset(longp, 'x', 1100);
  longp[1100] = 0;
  char args[1300];
  snprintf(args, sizeof args, "-summary %s", longp);
  rc = run_in_dir(dir, "a.deck", args, &err);
  ck_assert_msg(rc == 1 && strstr(err, "a path longer than 1023 characters"), "exit %d: %s", rc, err);
  free(err);
  free(dir);
  /* a FIFO in the way of a restart is an I/O error (exit 2), as a folder in the way of any output */
  static const struct { const char *lines, *want; int code; } cases[] = {
      {"run 2\nwrite_restart log.yfdem\n", "b.deck:10: error: write_restart: 'log.yfdem': already written by the log (-log)", 1},
      {"dump d h5 1 wy.h5\nrun 2\nwrite_y2d wy.xmf steps 10\n", "b.deck:11: error: write_y2d: 'wy.xmf': already written by dump 'd'", 1},
      {"run 2\nwrite_restart ff\n", "b.deck:10: error: write_restart: 'ff': 'ff' is not a regular file", 2},
      {"run 2\nwrite_restart dd\n", "b.deck:10: error: write_restart: 'dd': 'dd' is not a regular file", 2},
      {"restart every 2 dd\nrun 2\n", "b.deck:9: error: restart: 'dd': 'dd.b' is not a regular file", 2},
  };
  for (int k = 0; k < 5; k++) {
    char text[1024];
    snprintf(text, sizeof text, "%s%s", BAR, cases[k].lines);
    char *d2 = yft_deck_dir("b.deck", text), cmd[700];
    snprintf(cmd, sizeof cmd, "mkfifo %s/ff && mkdir %s/dd %s/dd.b", d2, d2, d2);
    ck_assert_int_eq(system(cmd), 0);
    rc = run_in_dir(d2, "b.deck", "", &err);
    ck_assert_msg(rc == cases[k].code && strstr(err, cases[k].want), "case %d: exit %d: %s", k, rc, err);
    char *log = file_in(d2, "log.yfdem");
    ck_assert_msg(strstr(log, "material m elastic"), "case %d: the log is not the log: %.80s", k, log);
    struct stat st;
    snprintf(cmd, sizeof cmd, "%s/ff", d2);
    ck_assert(stat(cmd, &st) == 0 && S_ISFIFO(st.st_mode));
    free(log);
    free(err);
    snprintf(cmd, sizeof cmd, "rm -rf %s", d2);
    if (system(cmd)) {}
    free(d2);
  }
  rc = yft_run_binary("c.deck", BAR "run 2\nwrite_restart r.h5\nrun 2\nwrite_restart r.h5\n", "", &err, &dir);
  ck_assert_msg(rc == 0, "write_restart twice: exit %d: %s", rc, err);
  free(err);
  free(dir);
}
END_TEST

/* Runaway decks end with a deck error at their line, quickly: 60 equal-style variables that each
 * read the one before twice (2^59 evaluations: it spun for ever, deaf to SIGTERM), string
 * variables that each hold the one before four times (gigabytes, then "out of memory" with no
 * line), a Weibull modulus whose scale overflows (GSL aborted, exit 134), a point at 1e200 m (the
 * squared distances overflowed: no node), a number that underflows to 0 ('E 1e-400': "must be >
 * 0"; thermo 1e-400 ran as 0). */
START_TEST(test_runaway_decks_stop_at_their_line) {
  char chain[8192] = "variable v0 equal 1\n";
  for (int k = 1; k < 60; k++) {
    char l[64];
    snprintf(l, sizeof l, "variable v%d equal v_v%d+v_v%d\n", k, k - 1, k - 1);
    strcat(chain, l);
  }
  strcat(chain, "print \"$(v_v59)\"\n");
  char strs[4096] = "variable s0 string abcdefghijklmnopqrstuvwxyz0123456789\n";
  for (int k = 1; k < 20; k++) {
    char l[96];
    snprintf(l, sizeof l, "variable s%d string ${s%d}${s%d}${s%d}${s%d}\n", k, k - 1, k - 1, k - 1, k - 1);
    strcat(strs, l);
  }
  static char weib[512];
  snprintf(weib, sizeof weib, "%s", BAR "jointprop cj ft 3e6 fs 3e6 gf 100 pen 1e11 law munjiza_gf weibull 0.005 seed 7\n");
  const struct { const char *deck, *want; } cases[] = {
      {chain, "more than 1000000 evaluations of equal-style variables"},
      {strs, "the line grows beyond 16 MiB as its variables are substituted"},
      {weib, "a.deck:9: error: jointprop: '0.005': a Weibull modulus below 0.01"},
      {BAR "group g node nearest 1e200 0\n", "a.deck:9: error: group: x '1e200': 1e+200 m is beyond +-1e+100 m"},
      {BAR "load L point at 0 1e200 1 0\n", "a.deck:9: error: load: y '1e200': 1e+200 m is beyond +-1e+100 m"},
      {"material m elastic rho 1000 E 1e-400 nu 0.25 plane_stress\n", "a.deck:1: error: material: E '1e-400': underflows to 0"},
      {BAR "thermo 1e-400\n", "a.deck:9: error: thermo"},
  };
  for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
    char *err;
    time_t t0 = time(NULL);
    int rc = yft_run_binary("a.deck", cases[k].deck, "-log none", &err, NULL);
    ck_assert_msg(rc == 1 && strstr(err, cases[k].want), "case %zu: exit %d: %.600s", k, rc, err);
    ck_assert_msg(time(NULL) - t0 < 60, "case %zu took %ld s", k, (long)(time(NULL) - t0));
    free(err);
  }
}
END_TEST

/* A record row is written whole or not at all: a quantity that fails at step 1 (1/(step-1)) left
 * "1,1.89e-05" with no value and no newline. */
START_TEST(test_record_row_whole) {
  char *err, *dir;
  int rc = yft_run_binary("a.deck", BAR "record r 1 rr.csv \"1/(step-1)\"\nrun 2\n", "-log none", &err, &dir);
  ck_assert_msg(rc == 1, "exit %d: %s", rc, err);
  char *csv = file_in(dir, "rr.csv");
  size_t n = strlen(csv);
  ck_assert_msg(n > 0 && csv[n - 1] == '\n' && !strstr(csv, "\n1,"), "rr.csv: '%s'", csv);
  free(csv);
  free(err);
  free(dir);
}
END_TEST

/* Every -summary key is there when nothing ran (null where unknown): model_bytes_per_element and
 * dt_limit were left out, so scripts that index them failed. */
START_TEST(test_summary_keys_without_run) {
  char *err, *dir;
  int rc = yft_run_binary("a.deck", "material m elastic rho 1000 E 1e9 nu 0.25 plane_stress\n", "-summary s.json", &err, &dir);
  ck_assert_msg(rc == 0, "exit %d: %s", rc, err);
  char *js = file_in(dir, "s.json");
  ck_assert_msg(strstr(js, "\"model_bytes_per_element\": null") && strstr(js, "\"dt_limit\": null"), "%s", js);
  free(js);
  free(err);
  free(dir);
}
END_TEST

/* The metrics log is written with each restart, so that after a SIGKILL it holds the rows the
 * continuation keeps (it was written only at the end: lost, and the continued log silently began
 * at the restart's step). */
START_TEST(test_metrics_log_survives_kill) {
  char *dir = yft_deck_dir("k.deck", BAR "metrics log met.csv every 10\nrun 50\nwrite_restart r.h5\nrun 100000000\n");
  char cmd[1200];
  snprintf(cmd, sizeof cmd, "cd %s && (OMP_NUM_THREADS=1 %s -in k.deck -log none >/dev/null 2>&1 & p=$!; "
           "for i in $(seq 600); do [ -f r.h5 ] && break; sleep 0.1; done; sleep 0.5; kill -9 $p; wait $p; true)",
           dir, yft_binary());
  ck_assert_int_eq(system(cmd), 0);
  char *met = file_in(dir, "met.csv");
  ck_assert_msg(strstr(met, "\n10,") && strstr(met, "\n50,"), "met.csv after SIGKILL: %.600s", met);
  free(met);
  snprintf(cmd, sizeof cmd, "rm -rf %s", dir);
  if (system(cmd)) {}
  free(dir);
}
END_TEST

/* A second Ctrl-C stops at once; the file being written then is removed, not left half done as
 * PATH.tmp beside the outputs (a restart's rs.a.tmp was left on the first of 20 tries). */
START_TEST(test_second_interrupt_leaves_no_tmp) {
  char *dir = yft_deck_dir("d.deck", "material m elastic rho 1000 E 1e9 nu 0.25 plane_stress\n"
                                     "mesh rect b m 0 0 1 0.1 40 4\nvelocity b set 0 1\ntimestep auto\n"
                                     "dump d h5 1 long.h5\nrestart every 50 rs\nrun 2000000000\n");
  char cmd[1500];
  snprintf(cmd, sizeof cmd, "cd %s && for t in 1 2 3 4 5 6; do rm -f *.tmp; OMP_NUM_THREADS=1 %s -in d.deck -log none "
           ">/dev/null 2>&1 & p=$!; sleep 1.$t; kill -INT $p; sleep 0.00$t; kill -INT $p 2>/dev/null; wait $p; "
           "ls | grep -q '[.]tmp$' && exit 1; done; exit 0", dir, yft_binary());
  int st = system(cmd);
  ck_assert_msg(WIFEXITED(st) && WEXITSTATUS(st) == 0, "a .tmp file was left behind after a second SIGINT");
  snprintf(cmd, sizeof cmd, "rm -rf %s", dir);
  if (system(cmd)) {}
  free(dir);
}
END_TEST

/* Occurrences of needle in hay. */
static int occurrences(const char *hay, const char *needle) {
  int n = 0;
  for (const char *p = hay; (p = strstr(p, needle)); p += strlen(needle)) n++;
  return n;
}

/* A fix and a load on a group that selects nothing: said once each, at the first run, however many
 * runs the deck makes (each of 3 runs said both again: 2026-11-29 MPI sweep). */
START_TEST(test_empty_group_warned_once) {
  char *err = NULL;
  int code = yft_run_binary("eg.deck",
                            "material m elastic rho 1000 E 1e7 nu 0.25 plane_strain\n"
                            "mesh rect a m 0 0 0.1 0.05 4 2\nregion far box 5 5 6 6\ngroup g node region far\n"
                            "fix f g velocity 0 0\nload q g traction 0 1\ntimestep 1e-6\nrun 5\nrun 5\nrun 5\n",
                            "-log none", &err, NULL);
  ck_assert_msg(code == 0 && occurrences(err, "fix 'f': group 'g' has no nodes") == 1 &&
                occurrences(err, "load 'q': group 'g' has no boundary edge") == 1, "exit %d:\n%s", code, err);
  free(err);
}
END_TEST

/* System calls that `strace -f -c` counts for the deck of dir run for `steps` steps with the
 * options opt (-threads 1, or the default governed choice between one thread and two). */
/* (ASAN_OPTIONS: under `make asan` LeakSanitizer refuses to run under ptrace and fails the binary;
 * the leaks of these runs are checked by the other tests.) */
static long syscalls_of_run(const char *dir, long steps, const char *opt) {
  char cmd[1400], out[600];
  snprintf(out, sizeof out, "%s/strace_%ld.txt", dir, steps);
  snprintf(cmd, sizeof cmd, "cd %s && OMP_NUM_THREADS=2 ASAN_OPTIONS=detect_leaks=0 strace -f -c -o %s %s %s -log none -var steps %ld a.deck "
           ">/dev/null 2>&1", dir, out, yft_binary(), opt, steps);
  if (system(cmd) != 0) return -1;
  char *t = yft_slurp(out, 0);
  ck_assert_ptr_nonnull(t);
  const char *tot = strstr(t, " total");
  ck_assert_ptr_nonnull(tot);
  const char *ln = tot;
  while (ln > t && ln[-1] != '\n') ln--;
  double pct = 0, sec = 0;
  long upc = 0, calls = -1;
  ck_assert_int_eq(sscanf(ln, "%lf %lf %ld %ld", &pct, &sec, &upc, &calls), 4);
  free(t);
  return calls;
}

/* The step does no I/O and allocates nothing (README, Source layout), so a run's system calls do
 * not grow with its steps.  A 20-triangle bar with a support and gravity, 200 and 2200 steps, on
 * one thread and by default (two threads allowed): the 2000 more steps may add a few calls (none
 * are expected), not one per step.  An OpenMP loop whose `if` is false still built a libgomp team
 * of one thread at each entry (a futex call each) and the element stage read the process's CPU
 * clock twice (a system call each): 5 calls per step, 10 000 more here, and 80 % of a 16-triangle
 * scene's step (parfor.h); by default the thread governor read it twice more per step, although
 * no loop of such a scene runs on the team (threads.c). */
START_TEST(test_step_makes_no_system_calls) {
  char *dir = yft_deck_dir("a.deck", BAR "gravity 0 -9.81\nthermo 0\nvariable steps index 10\nrun ${steps}\n");
  if (system("strace -V >/dev/null 2>&1") != 0) {
    fprintf(stderr, "strace is not installed (tools/install-deps --test): the step's system calls are not counted\n");
  } else {
    static const char *const opts[] = {"-threads 1", ""};
    for (int k = 0; k < 2; k++) {
      long a = syscalls_of_run(dir, 200, opts[k]), b = syscalls_of_run(dir, 2200, opts[k]);
      fprintf(stderr, "system calls (%s): %ld for 200 steps, %ld for 2200 steps\n", k ? "default" : opts[k], a, b);
      ck_assert_int_gt(a, 0);
      ck_assert_msg(b - a < 100, "%s: 2000 more steps made %ld more system calls (the step should make none)",
                    k ? "default" : opts[k], b - a);
    }
  }
  char cmd[700];
  snprintf(cmd, sizeof cmd, "rm -rf %s", dir);
  if (system(cmd)) {}
  free(dir);
}
END_TEST

Suite *habits_suite(void) {
  Suite *s = suite_create("habits");
  TCase *t = tcase_create("lammps");
  tcase_set_timeout(t, 60);
  tcase_add_test(t, test_log_thermo_record);
  tcase_add_test(t, test_log_none_and_named);
  tcase_add_test(t, test_var_unused_warns);
  tcase_add_test(t, test_help_suggests);
  tcase_add_test(t, test_flushed_while_running);
  tcase_add_test(t, test_no_files_before_run);
  tcase_add_test(t, test_outputs_in_working_dir);
  tcase_add_test(t, test_whole_files_through_links_and_devices);
  tcase_add_test(t, test_summary_on_the_log_refused);
  tcase_add_test(t, test_var_takes_one_value);
  tcase_add_test(t, test_run_zero_prints_one_line);
  tcase_add_test(t, test_stdout_unwritable);
  tcase_add_test(t, test_outputs_never_overwrite_inputs);
  tcase_add_test(t, test_runaway_decks_stop_at_their_line);
  tcase_add_test(t, test_record_row_whole);
  tcase_add_test(t, test_summary_keys_without_run);
  tcase_add_test(t, test_metrics_log_survives_kill);
  tcase_add_test(t, test_second_interrupt_leaves_no_tmp);
  tcase_add_test(t, test_lammps_options_hinted);
  tcase_add_test(t, test_empty_deck_and_terminal_stdin);
  tcase_add_test(t, test_var_given_twice_warned);
  tcase_add_test(t, test_empty_group_warned_once);
  tcase_add_test(t, test_step_makes_no_system_calls);
  suite_add_tcase(s, t);
  return s;
}
