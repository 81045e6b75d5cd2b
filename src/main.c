/* main.c: the yfdem program: command-line options, the deck, the exit code.
 *
 *   yfdem < beam.deck
 *   yfdem -in beam.deck -var n 40 -log run.log -summary run.json
 *   yfdem old_model.y            (a Y2D input deck, run to its own last step)
 */
#include <errno.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "bc.h"
#include "commands.h"
#include "deck.h"
#include "err.h"
#include "output.h"
#include "report.h"
#include "run.h"
#include "sim.h"
#include "summary.h"
#include "y2d_model.h"
#include "par.h"

#ifndef YF_VERSION
#define YF_VERSION "0.1.0"
#endif

static YfSim g_sim;
static YfDeck *g_deck;

static void usage(FILE *fp) {
  fprintf(fp,
          "yfdem %s: combined finite-discrete element method (Munjiza's FDEM, Y2D-compatible)\n\n"
          "usage: yfdem [options] [< deck]\n"
          "       yfdem [options] FILE.y           run a Y2D input deck\n"
          "options:\n"
          "  -in FILE          read the deck from FILE (default: standard input)\n"
          "  -var NAME VALUE   define variable NAME (repeatable; the deck's own definition is then ignored)\n"
          "  -log FILE|none    copy the input lines, thermo lines and messages to FILE (default log.yfdem)\n"
          "  -echo             print each command before running it\n"
          "  -summary FILE     write a JSON summary at the end (also after an error)\n"
          "  -h [COMMAND]      this help, or the usage of one deck command\n"
          "  -reference [sections]  print the deck reference (markdown table, or a section per command)\n"
          "  -version          print the version\n"
          "exit codes: 0 ok, 1 deck error, 2 I/O error, 3 numerical failure, 4 interrupted, 70 internal error\n\n"
          "deck commands:\n",
          YF_VERSION);
  for (const YfCommand *c = yf_commands; c->name; c++) fprintf(fp, "  %-10s %s\n", c->name, c->help);
}

static void finish(int code, const char *message) {
  output_close_all(&g_sim);
  run_summary_update(&g_sim);
  if (g_sim.summary_path[0]) summary_write(&g_sim, g_sim.summary_path, code, message);
  if (g_sim.log) {
    if (message && *message) fprintf(g_sim.log, "%s\n", message);
    yf_set_log(NULL);
    fclose(g_sim.log);
    g_sim.log = NULL;
  }
}

static void on_signal(int sig) {
  (void)sig;
  g_sim.interrupted = 1;
}

int main(int argc, char **argv) {
  par_init(&argc, &argv); /* ./yfdem_mpi: MPI ranks (a no-op in ./yfdem) */
  sim_init(&g_sim);
  g_sim.progress = 1;
  yf_set_cleanup(finish);
  g_deck = deck_new(&g_sim);
  io_attach(&g_sim); /* dumps, metrics and restarts (and the interrupt restart) observe the run loop */
  const char *in = NULL, *log_path = "log.yfdem"; /* as LAMMPS writes log.lammps */
  int echo = 0;
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
        printf("%s\n  %s\n  example: %s\n", c->usage, c->help, c->example);
        return 0;
      }
      usage(stdout);
      return 0;
    } else if (!strcmp(o, "-reference")) {
      if (i + 1 < argc && !strcmp(argv[i + 1], "sections")) commands_print_sections(stdout);
      else commands_print_reference(stdout);
      return 0;
    } else if (!strcmp(o, "-version") || !strcmp(o, "--version")) {
      printf("yfdem %s\n", YF_VERSION);
      return 0;
    } else if (!strcmp(o, "-in") && i + 1 < argc) {
      in = argv[++i];
    } else if (!strcmp(o, "-var") && i + 2 < argc) {
      deck_set_var(g_deck, argv[i + 1], argv[i + 2]);
      i += 2;
    } else if (!strcmp(o, "-log") && i + 1 < argc) {
      log_path = argv[++i];
    } else if (!strcmp(o, "-echo")) {
      echo = 1;
    } else if (!strcmp(o, "-summary") && i + 1 < argc) {
      snprintf(g_sim.summary_path, sizeof g_sim.summary_path, "%s", argv[++i]);
    } else if (o[0] != '-' && !in) {
      in = o;
    } else {
      fprintf(stderr, "yfdem: unknown or incomplete option '%s' (try yfdem -h)\n", o);
      return YF_EXIT_DECK;
    }
  }
  if (strcmp(log_path, "none") != 0 && yf_writer()) { /* MPI: rank 0 writes the log */
    g_sim.log = fopen(log_path, "w");
    if (!g_sim.log)
      yf_io_error(NULL, "cannot open log file '%s': %s (give another with -log FILE, or -log none)", log_path,
                  strerror(errno));
    yf_set_log(g_sim.log);
  }
  deck_set_echo(g_deck, echo);
  signal(SIGINT, on_signal);
  signal(SIGTERM, on_signal);
  if (in) {
    size_t L = strlen(in);
    if (L > 2 && !strcmp(in + L - 2, ".y")) {
      /* A Y2D deck: read it and run to its own last step (read_y2d + run). */
      y2d_run_file(&g_sim, in);
    } else {
      deck_run_file(g_deck, in, NULL);
    }
  } else {
    deck_run_stream(g_deck, par_stdin(stdin), "<stdin>");
  }
  finish(YF_EXIT_OK, "");
  deck_free(g_deck);
  run_free();
  sim_free(&g_sim);
  return 0;
}
