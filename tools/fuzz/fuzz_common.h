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
#include <unistd.h>
#include "deck.h"
#include "err.h"
#include "run.h"
#include "sim.h"

static jmp_buf fuzz_back;
static void fuzz_exit_hook(int code) { longjmp(fuzz_back, code + 1); }

/* Into a scratch directory (the files a deck writes, and the files a reader target writes for
 * its reader, land there), a 256 MB scene cap (YFDEM_MEM_MAX: absurd sizes are clean deck errors,
 * not out-of-memory kills), the exit hook. */
static void fuzz_setup(void) {
  char tmpl[] = "/tmp/yffuzz_XXXXXX";
  if (mkdtemp(tmpl) && chdir(tmpl) == 0) {}
  setenv("YFDEM_MEM_MAX", "268435456", 0);
  yf_set_exit_hook(fuzz_exit_hook);
}

/* Run the n bytes of text as the deck fname in a fresh simulation; returns the exit code the
 * deck would have given yfdem (0: it ended normally). */
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
  d = deck_new(&s);
  int j = setjmp(fuzz_back);
  if (j == 0) deck_run_stream(d, fp, fname);
  else code = j - 1;
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

static int fuzz_has(const uint8_t *d, size_t n, const char *w) {
  size_t L = strlen(w);
  for (size_t i = 0; i + L <= n; i++)
    if (!memcmp(d + i, w, L)) return 1;
  return 0;
}
#endif
