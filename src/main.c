/* main.c: the yfdem program: command-line options, the deck, the exit code.
 *
 *   yfdem < beam.deck
 *   yfdem -in beam.deck -var n 40 -log run.log -summary run.json
 *   yfdem old_model.y            (a Y2D input deck, run to its own last step)
 */
#include <errno.h>
#include <fcntl.h>
#include <hdf5.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>
#include "bc.h"
#include "commands.h"
#include "deck.h"
#include "err.h"
#include "output.h"
#include "report.h"
#include "run.h"
#include "sim.h"
#include "wfile.h"
#include "summary.h"
#include "threads.h"
#include "y2d_model.h"
#include "par.h"

#ifndef YF_VERSION
#define YF_VERSION "0.1.0"
#endif

static YfSim g_sim;
static YfDeck *g_deck;
static const char *g_log_path;

static void usage(FILE *fp) {
  fprintf(fp,
          "yfdem %s: combined finite-discrete element method (Munjiza's FDEM, Y2D-compatible)\n\n"
          "usage: yfdem [options] [-in] DECK       run a deck\n"
          "       yfdem [options] < DECK           the same, the deck read from standard input\n"
          "       yfdem [options] FILE.y           run a Y2D input deck\n"
          "options:\n"
          "  -in FILE          read the deck from FILE (default: standard input)\n"
          "  -var NAME VALUE   define variable NAME (repeatable; the deck's own definition is then ignored)\n"
          "  -log FILE|none    copy the input lines, thermo lines and messages to FILE (default log.yfdem)\n"
          "  -echo             print each command before running it\n"
          "  -summary FILE     write a JSON summary at the end (also after an error)\n"
          "  -threads N|auto   N: run every step on exactly N threads; auto (the default): one thread or\n"
          "                    OMP_NUM_THREADS (default: the cores), whichever the step's timing finds faster\n"
          "  -h [COMMAND]      this help, or the usage of one deck command\n"
          "  -reference [sections]  print the deck reference (markdown table, or a section per command)\n"
          "  -version          print the version\n"
          "exit codes: 0 ok, 1 deck error, 2 I/O error, 3 numerical failure, 130 interrupted (Ctrl-C,\n"
          "SIGTERM), 70 internal error\n\n"
          "deck commands:\n",
          YF_VERSION);
  for (const YfCommand *c = yf_commands; c->name; c++) fprintf(fp, "  %-10s %s\n", c->name, c->help);
}

/* The cleanup of every exit (err.c runs it once): files closed, logs and the summary written.
 * An output that fails here (yf_output_error) makes a successful run exit 2 with that message. */
static void finish(int code, const char *message) {
  output_close_all(&g_sim);
  run_summary_update(&g_sim);
  /* the log's state before the summary's: a log that failed makes the summary say io_error */
  if (g_sim.log && !g_sim.log_failed && (fflush(g_sim.log) != 0 || ferror(g_sim.log))) {
    g_sim.log_failed = errno ? errno : EIO;
    yf_output_error("-log: cannot write '%s': %s", g_log_path, strerror(g_sim.log_failed));
  }
  code = yf_exit_code(code);
  message = yf_last_message();
  if (g_sim.summary_path[0] && summary_write(&g_sim, g_sim.summary_path, code, message) < 0)
    yf_output_error("-summary: cannot write '%s': %s", g_sim.summary_path, yf_strerror(errno));
  if (g_sim.log) {
    message = yf_last_message();
    if (message && *message && !g_sim.log_failed) fprintf(g_sim.log, "%s\n", message);
    yf_set_log(NULL);
    int bad = ferror(g_sim.log) || fflush(g_sim.log) != 0, e = errno;
    if (fclose(g_sim.log) != 0 && !bad) bad = 1, e = errno;
    g_sim.log = NULL;
    if (bad && !g_sim.log_failed) yf_output_error("-log: cannot write '%s': %s", g_log_path, strerror(e ? e : EIO));
  }
}

/* SIGINT/SIGTERM: the deck interpreter (before each command) and the run (after each step) see
 * the flag and stop cleanly: files closed, a restart in a run, the summary says "interrupted".
 * A second signal before that is done stops at once (only async-signal-safe calls here). */
static void on_signal(int sig) {
  if (yf_exiting()) return; /* the run already ends (mpirun's SIGTERM to the ranks after one left) */
  par_interrupted();
  if (g_sim.interrupted) {
    static const char m[] = "yfdem: interrupted again: stopping at once (the summary is not written)\n";
    if (write(2, m, sizeof m - 1) < 0) {}
    yf_tmp_drop(); /* the file being written, half done (a restart's .tmp was left behind) */
    _exit(YF_EXIT_INTERRUPT);
  }
  g_sim.interrupted = sig;
}

/* Whether w is one of the command-line options (a value that is one was an option forgotten). */
static int is_option(const char *w) {
  static const char *const opts[] = {"-in", "-var", "-log", "-summary", "-threads", "-echo", "-h", "-help", "--help",
                                     "-version", "--version", NULL};
  for (int k = 0; opts[k]; k++)
    if (!strcmp(w, opts[k])) return 1;
  return 0;
}

/* LAMMPS's options that yfdem spells otherwise or lacks: a LAMMPS user's '-i deck', '-v n 10',
 * '-sc none' or '-pk omp 2' was "unknown or incomplete option" with no way forward. */
static const char *lammps_hint(const char *w) {
  static const char *const hint[][2] = {
      {"-i", "yfdem reads the deck with -in FILE"},
      {"-v", "yfdem sets a variable with -var NAME VALUE"},
      {"-l", "yfdem names the log with -log FILE|none"},
      {"-e", "yfdem's -echo takes no value: it prints each command on the screen and in the log"},
      {"-sc", "yfdem has no -screen: send the screen elsewhere with > FILE (or > /dev/null)"},
      {"-screen", "yfdem has no -screen: send the screen elsewhere with > FILE (or > /dev/null)"},
      {"-pk", "yfdem sets its OpenMP threads with -threads N"},
      {"-sf", "yfdem's steps are OpenMP ones already: set their threads with -threads N"},
      {"-k", "yfdem sets its OpenMP threads with -threads N"},
      {"-nc", "yfdem writes no citation file"},
      {"-nocite", "yfdem writes no citation file"},
      {"--in", "yfdem's options take one dash: -in FILE"},
      {"--var", "yfdem's options take one dash: -var NAME VALUE"},
      {"--log", "yfdem's options take one dash: -log FILE|none"},
      {"--summary", "yfdem's options take one dash: -summary FILE"},
      {"--threads", "yfdem's options take one dash: -threads N|auto"},
      {"--echo", "yfdem's options take one dash: -echo"},
  };
  for (size_t k = 0; k < sizeof hint / sizeof hint[0]; k++)
    if (!strcmp(w, hint[k][0])) return hint[k][1];
  return NULL;
}

/* An output option on a file another output writes, or on the deck itself. */
static int refuse_claim(const char *opt, const char *path, const char *by) {
  int input = !strncmp(by, "the deck being read", 19);
  fprintf(stderr, "yfdem: %s '%s': %s%s\n", opt, path, input ? "that is " : "already written by ", by);
  return YF_EXIT_DECK;
}

int main(int argc, char **argv) {
  par_init(&argc, &argv); /* ./yfdem_mpi: MPI ranks (a no-op in ./yfdem) */
  /* HDF5's own exit handler closes every file still open, also one whose H5Fclose failed (a full
   * disk), and crashes there; yfdem closes its files itself (output_close_all, restart.c). */
  H5dont_atexit();
  sim_init(&g_sim);
  g_sim.progress = 1;
  yf_set_cleanup(finish);
  g_deck = deck_new(&g_sim);
  io_attach(&g_sim); /* dumps, metrics and restarts (and the interrupt restart) observe the run loop */
  const char *in = NULL, *log_path = "log.yfdem"; /* as LAMMPS writes log.lammps */
  int echo = 0;
  /* MPI: every rank reads the same command line; rank 0 alone prints its help or what is wrong
   * with it (an error came once per rank, -h 3 times over on 3 ranks) */
  int saved_fd[2] = {-1, -1};
  if (!yf_writer()) {
    fflush(stdout);
    fflush(stderr);
    int dn = open("/dev/null", O_WRONLY);
    for (int k = 0; k < 2 && dn >= 0; k++) {
      saved_fd[k] = dup(k + 1);
      dup2(dn, k + 1);
    }
    if (dn >= 0) close(dn);
  }
  int var_end = -2; /* index of the last -var's VALUE: a word right after it may be a second value */
  for (int i = 1; i < argc; i++) {
    const char *o = argv[i];
    if (!strcmp(o, "-h") || !strcmp(o, "-help") || !strcmp(o, "--help")) {
      if (i + 1 < argc) {
        const YfCommand *c = deck_find_command(argv[i + 1]);
        if (!c) {
          const char *near = deck_nearest_command(argv[i + 1]);
          if (near) fprintf(stderr, "yfdem: no deck command '%s' (did you mean '%s'?)\n", argv[i + 1], near);
          else fprintf(stderr, "yfdem: no deck command '%s' (yfdem -h lists them)\n", argv[i + 1]);
          return YF_EXIT_DECK;
        }
        commands_print_help(stdout, c);
        return 0;
      }
      usage(stdout);
      return 0;
    } else if (!strcmp(o, "-reference")) {
      /* '-reference sectons' printed the table, the typo unseen */
      if (i + 1 < argc && strcmp(argv[i + 1], "sections") != 0 && !is_option(argv[i + 1])) {
        fprintf(stderr, "yfdem: -reference '%s': expected 'sections' (a section per command) or nothing (the "
                "markdown table)\n", argv[i + 1]);
        return YF_EXIT_DECK;
      }
      if (i + 1 < argc && !strcmp(argv[i + 1], "sections")) commands_print_sections(stdout);
      else commands_print_reference(stdout);
      return 0;
    } else if (!strcmp(o, "-version") || !strcmp(o, "--version")) {
      printf("yfdem %s\n", YF_VERSION);
      return 0;
    } else if (!strcmp(o, "-in") && i + 1 < argc && !strcmp(argv[i + 1], "-") && access("-", F_OK) != 0) {
      /* 'cat deck | yfdem -in -' was "cannot open deck '-'" */
      fprintf(stderr, "yfdem: -in '-': yfdem reads standard input when no deck is given: yfdem < FILE, or "
              "... | yfdem\n");
      return YF_EXIT_DECK;
    } else if (!strcmp(o, "-in") && i + 1 < argc) {
      if (in) { /* 'yfdem a.y -in b.deck' ran b.deck alone, a.y not even looked at */
        fprintf(stderr, "yfdem: -in '%s': the deck is already '%s'; give one deck (a native deck can read_y2d a .y "
                "deck, or include another)\n", argv[i + 1], in);
        return YF_EXIT_DECK;
      }
      in = argv[++i];
    } else if (!strcmp(o, "-var") && i + 2 < argc) {
      deck_set_var(g_deck, argv[i + 1], argv[i + 2]);
      i += 2;
      var_end = i;
    } else if ((!strcmp(o, "-log") || !strcmp(o, "-summary")) && i + 1 < argc && is_option(argv[i + 1])) {
      /* '-log -in deck' made a log file named '-in' and read the deck from stdin */
      fprintf(stderr, "yfdem: %s '%s': expected a file name after %s, not an option\n", o, argv[i + 1], o);
      return YF_EXIT_DECK;
    } else if (!strcmp(o, "-log") && i + 1 < argc) {
      /* an empty name was an I/O error (exit 2, "cannot open log file ''"), where -summary's is a
       * command-line error (exit 1) */
      if (!argv[i + 1][0]) {
        fprintf(stderr, "yfdem: -log '': an empty file name (give -log FILE, or -log none for no log)\n");
        return YF_EXIT_DECK;
      }
      log_path = argv[++i];
    } else if (!strcmp(o, "-echo")) {
      echo = 1;
      /* LAMMPS's '-echo screen|log|both|none' takes a value, yfdem's none: the value became the
       * deck ("the deck is already 'screen'", or a deck named 'none' that cannot be opened) */
      static const char *const lmp_echo[] = {"screen", "log", "both", "none", NULL};
      for (int k = 0; i + 1 < argc && lmp_echo[k]; k++)
        if (!strcmp(argv[i + 1], lmp_echo[k]) && access(argv[i + 1], F_OK) != 0) {
          fprintf(stderr, "yfdem: -echo '%s': -echo takes no value (LAMMPS's -echo screen|log|both|none); "
                  "-echo alone prints each command on the screen and in the log, without it none is printed\n",
                  argv[i + 1]);
          return YF_EXIT_DECK;
        }
    } else if (!strcmp(o, "-summary") && i + 1 < argc) {
      /* an empty name was ignored, a long one cut short: the summary went nowhere, or elsewhere */
      if (!argv[i + 1][0] || strlen(argv[i + 1]) >= sizeof g_sim.summary_path) {
        fprintf(stderr, "yfdem: -summary '%.60s%s': %s\n", argv[i + 1], strlen(argv[i + 1]) > 60 ? "..." : "",
                argv[i + 1][0] ? "a path longer than 1023 characters" : "an empty file name");
        return YF_EXIT_DECK;
      }
      snprintf(g_sim.summary_path, sizeof g_sim.summary_path, "%s", argv[++i]);
      if (!yf_can_create(g_sim.summary_path)) { /* now, not after the run */
        g_sim.summary_path[0] = 0;
        yf_io_error(NULL, "-summary: cannot write '%s': %s", argv[i], yf_strerror(errno));
      }
    } else if (!strcmp(o, "-threads") && i + 1 < argc) {
      const char *v = argv[++i];
      char *end;
      long n = strtol(v, &end, 10);
      if (!strcmp(v, "auto")) {
        threads_set(0);
      } else if (end == v || *end || n < 1 || n > 4096) {
        fprintf(stderr, "yfdem: -threads '%s': expected a whole number of threads from 1 to 4096, or auto\n", v);
        return YF_EXIT_DECK;
      } else {
        threads_set((int)n);
      }
    } else if (o[0] != '-') {
      /* LAMMPS reads '-var n 10 20 30' as an index of three values; here -var takes one, and the
       * second value became the deck ("the deck is already", or "cannot open '20'" under '< deck') */
      if (i == var_end + 1 && (in || access(o, F_OK) != 0)) {
        fprintf(stderr, "yfdem: '%s': %s-var takes one value ('-var %s %s' was read); for several values of an "
                "index variable, list them in the deck ('variable %s index %s %s ...') or run yfdem once per value\n", o,
                in ? "" : "no such deck file; if it is a second value, ", argv[i - 2], argv[i - 1], argv[i - 2],
                argv[i - 1], o);
        return in ? YF_EXIT_DECK : YF_EXIT_IO;
      }
      if (in) {
        fprintf(stderr, "yfdem: '%s': the deck is already '%s'; give one deck (a native deck can read_y2d a .y "
                "deck, or include another)\n", o, in);
        return YF_EXIT_DECK;
      }
      in = o;
    } else {
      const char *h = lammps_hint(o);
      static const char *const need[][2] = {{"-in", "FILE"}, {"-var", "NAME VALUE"}, {"-log", "FILE|none"},
                                            {"-summary", "FILE"}, {"-threads", "N|auto"}};
      for (size_t k = 0; k < sizeof need / sizeof need[0]; k++)
        if (!strcmp(o, need[k][0])) {
          fprintf(stderr, "yfdem: %s expects %s after it, and the command line ends before\n", o, need[k][1]);
          return YF_EXIT_DECK;
        }
      if (h) fprintf(stderr, "yfdem: unknown option '%s': %s (yfdem -h lists the options)\n", o, h);
      else
        fprintf(stderr, "yfdem: unknown or incomplete option '%s': the options are -in FILE, -var NAME VALUE, "
                "-log FILE|none, -echo, -summary FILE, -threads N|auto, -h [COMMAND], -reference, -version "
                "(yfdem -h)\n", o);
      return YF_EXIT_DECK;
    }
  }
  for (int k = 0; k < 2; k++)
    if (saved_fd[k] >= 0) {
      dup2(saved_fd[k], k + 1);
      close(saved_fd[k]);
    }
  /* the deck read is no output's ('-log my.deck' emptied the deck before it was read): by name,
   * and by the file itself (a link to it, or the file on stdin); the log and the summary are
   * outputs like the deck's: no deck output may write them */
  if (in) output_claim(&g_sim, "the deck being read (-in)", in, NULL, 0);
  struct stat dst;
  int have_deck = in ? stat(in, &dst) == 0 : fstat(0, &dst) == 0 && S_ISREG(dst.st_mode);
  const char *outs[2] = {strcmp(log_path, "none") ? log_path : NULL, g_sim.summary_path[0] ? g_sim.summary_path : NULL};
  for (int k = 0; k < 2 && have_deck; k++) {
    struct stat ost;
    if (outs[k] && stat(outs[k], &ost) == 0 && ost.st_dev == dst.st_dev && ost.st_ino == dst.st_ino)
      return refuse_claim(k ? "-summary" : "-log", outs[k], in ? "the deck being read (-in)" : "the deck being read (stdin)");
  }
  if (strcmp(log_path, "none") != 0) {
    const char *by = output_claim(&g_sim, "the log (-log)", log_path, NULL, 0);
    if (by) {
      return refuse_claim("-log", log_path, by);
    }
  }
  if (g_sim.summary_path[0]) {
    const char *by = output_claim(&g_sim, "the summary (-summary)", g_sim.summary_path, NULL, 0);
    if (by) {
      return refuse_claim("-summary", g_sim.summary_path, by);
    }
  }
  if (strcmp(log_path, "none") != 0 && yf_writer()) { /* MPI: rank 0 writes the log */
    g_log_path = log_path;
    g_sim.log_name = log_path;
    g_sim.log = yf_fopen_w(log_path); /* a FIFO with no reader: an error, not a wait (wfile.h) */
    if (!g_sim.log)
      yf_io_error(NULL, "cannot open log file '%s': %s (give another with -log FILE, or -log none)", log_path,
                  yf_strerror(errno));
    yf_set_log(g_sim.log);
  }
  deck_set_echo(g_deck, echo);
  yf_catch_signals(on_signal);
  if (in) {
    size_t L = strlen(in);
    if (L > 2 && (!strcmp(in + L - 2, ".y") || !strcmp(in + L - 2, ".Y"))) {
      /* A Y2D deck: read it and run to its own last step (read_y2d + run). */
      y2d_run_file(&g_sim, in);
    } else {
      deck_run_file(g_deck, in, NULL);
    }
  } else {
    /* 'yfdem' alone waited for a deck on the terminal without a word: say what it waits for */
    if (isatty(0) && yf_writer())
      fprintf(stderr, "yfdem: reading the deck from the terminal: type commands, end with Ctrl-D "
              "(yfdem -in FILE or yfdem < FILE reads a file; yfdem -h lists the options)\n");
    deck_run_stream(g_deck, par_stdin(stdin, &g_sim.interrupted), "<stdin>");
  }
  int code = yf_finish(YF_EXIT_OK);
  deck_free(g_deck);
  run_free();
  sim_free(&g_sim);
  if (code == YF_EXIT_OK) H5close(); /* not after a failed H5Fclose: it would close that file again */
  return code;
}
