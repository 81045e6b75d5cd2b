/* fuzz_common.h: what every libFuzzer target of tools/fuzz shares (tools/fuzz/README.md).
 *
 * yfdem exits on a deck or file error; here err.c's exit hook (yf_set_exit_hook) longjmps back to
 * the harness instead, so one process runs millions of inputs and the error paths are fuzzed too.
 * fuzz_run_deck runs a deck text in a fresh simulation and frees everything after it (also after
 * an error), so ASan sees use-after-free and double frees across the error path.
 * Included by one .c per target (each its own binary): the statics are per target.
 */
#ifndef YF_FUZZ_COMMON_H
#define YF_FUZZ_COMMON_H
#include <setjmp.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <fcntl.h>
#include <unistd.h>
#include "deck.h"
#include "err.h"
#include "output.h"
#include "report.h"
#include "run.h"
#include "sim.h"
#include "summary.h"

static jmp_buf fuzz_back;
static void fuzz_exit_hook(int code) { longjmp(fuzz_back, code + 1); }

/* A scratch directory ($TMPDIR or /tmp) for the files a deck writes and the files a reader target
 * writes for its reader; every input runs in it (fuzz_enter .. fuzz_leave), the harness's own working directory
 * is left as it was between inputs, so that libFuzzer finds the inputs named on its command line
 * (build-fuzz/crash-...) relative to it.  A 256 MB scene cap (YFDEM_MEM_MAX: absurd sizes are
 * clean deck errors, not out-of-memory kills) and the exit hook. */
static char fuzz_dir[256];
static int fuzz_home = -1;
static void fuzz_setup(void) {
  const char *tmp = getenv("TMPDIR");
  snprintf(fuzz_dir, sizeof fuzz_dir, "%s/yffuzz_XXXXXX", tmp && tmp[0] && strlen(tmp) < 200 ? tmp : "/tmp");
  if (!mkdtemp(fuzz_dir)) { perror("fuzz: mkdtemp"); exit(1); }
  setenv("YFDEM_MEM_MAX", "268435456", 0);
  yf_set_exit_hook(fuzz_exit_hook);
}

/* A reader stopped by an error (longjmp) leaves its file open, which yfdem's exit would have
 * closed: fuzz_leave closes the descriptors of files in the scratch directory (only those:
 * libFuzzer keeps descriptors of its own, its output among them). */
static void fuzz_close_scratch_fds(void) {
  size_t L = strlen(fuzz_dir);
  for (int fd = 3; fd < 1024; fd++) {
    char link[64], to[512];
    snprintf(link, sizeof link, "/proc/self/fd/%d", fd);
    ssize_t n = readlink(link, to, sizeof to - 1);
    if (n <= 0) continue;
    to[n] = 0;
    if (!strncmp(to, fuzz_dir, L) && to[L] == '/') close(fd);
  }
}
static void fuzz_enter(void) {
  if (fuzz_home < 0) fuzz_home = open(".", O_RDONLY | O_DIRECTORY);
  if (chdir(fuzz_dir) != 0) { perror("fuzz: chdir"); exit(1); }
}
static void fuzz_leave(void) {
  if (fchdir(fuzz_home) != 0) { perror("fuzz: fchdir"); exit(1); }
  fuzz_close_scratch_fds();
}

/* What yfdem's exit path does (main.c's finish): the outputs closed (the fracture log, the records
 * and the frames written out), the summary written: they read what the deck and its files left,
 * so they are fuzzed too. */
static YfSim *fuzz_sim;
static void fuzz_cleanup(int code, const char *message) {
  output_close_all(fuzz_sim);
  run_summary_update(fuzz_sim);
  summary_write(fuzz_sim, "summary.json", code, message);
}

/* Run the n bytes of text as the deck fname in a fresh simulation observed by the outputs (as
 * main.c's io_attach), then the exit path; returns the exit code the deck would have given yfdem
 * (0: it ended normally). */
static int fuzz_run_deck(const char *text, size_t n, const char *fname) {
  char *buf = malloc(n + 1);
  memcpy(buf, text, n);
  buf[n] = 0;
  FILE *fp = fmemopen(buf, n ? n : 1, "r");
  if (!fp) { free(buf); return 0; }
  static YfSim s; /* static: the longjmp must not leave it in a dead stack frame */
  static YfDeck *d;
  static volatile int code;
  code = 0;
  sim_init(&s);
  s.progress = 0;
  fuzz_sim = &s;
  io_attach(&s);
  yf_set_cleanup(fuzz_cleanup);
  d = deck_new(&s);
  int j = setjmp(fuzz_back);
  if (j == 0) {
    deck_run_stream(d, fp, fname);
    code = yf_finish(0);
  } else {
    code = j - 1;
  }
  fclose(fp);
  free(buf);
  deck_free(d);
  run_free();
  sim_free(&s);
  return code;
}

/* The n bytes of data into the file path (in the scratch directory); 0 when it cannot be written. */
static int fuzz_write_file(const char *path, const uint8_t *data, size_t n) {
  FILE *f = fopen(path, "wb");
  if (!f) return 0;
  int ok = fwrite(data, 1, n, f) == n;
  return fclose(f) == 0 && ok;
}

/* The text of tests/corpus/NAME (the harness runs from the repository's root: tools/fuzz/run),
 * copied into the scratch directory; its length in *n.  Exits when it is missing. */
static char *fuzz_corpus_file(const char *name, size_t *n) {
  char path[256];
  snprintf(path, sizeof path, "tests/corpus/%s", name);
  char *t = yf_read_file(path, n, "fuzz input");
  if (!t) { fprintf(stderr, "fuzz: cannot read %s (run from the repository's root)\n", path); exit(1); }
  fuzz_enter();
  if (!fuzz_write_file(name, (const uint8_t *)t, *n)) { perror("fuzz: scratch"); exit(1); }
  fuzz_leave();
  return t;
}

static int fuzz_has(const uint8_t *d, size_t n, const char *w) {
  size_t L = strlen(w);
  for (size_t i = 0; i + L <= n; i++)
    if (!memcmp(d + i, w, L)) return 1;
  return 0;
}
#endif
