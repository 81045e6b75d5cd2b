/* fuzz_deck.c: libFuzzer target for the deck interpreter (tools/fuzz/README.md).
 *
 * Each input is run as a deck through deck_run_stream in a fresh simulation.  A deck error
 * calls exit() in yfdem; here err.c's exit hook longjmps back to this harness instead, so one
 * process runs millions of inputs.  Everything is freed after each input (also after an
 * error), so ASan sees use-after-free and double frees across the error path too.
 *
 * Not fuzzed: `run` (the time loop is not the parser, and a random `run 2000000000` only burns
 * time) and `jump` (a deck may loop forever by design).  Inputs holding those words are
 * skipped.  YFDEM_MEM_MAX caps the scene size (the resource check refuses bigger ones) so that
 * `mesh rect ... 100000 1000` is a clean deck error and not an out-of-memory kill.
 */
#include <setjmp.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include "deck.h"
#include "err.h"
#include "mesh.h"
#include "region.h"
#include "run.h"
#include "sim.h"

static jmp_buf back;
static void on_exit_hook(int code) { longjmp(back, code + 1); }

int LLVMFuzzerInitialize(int *argc, char ***argv) {
  (void)argc; (void)argv;
  char tmpl[] = "/tmp/yffuzz_XXXXXX";
  if (mkdtemp(tmpl) && chdir(tmpl) == 0) {} /* files a deck writes land in a scratch directory */
  setenv("YFDEM_MEM_MAX", "268435456", 0);  /* 256 MB per scene */
  yf_set_exit_hook(on_exit_hook);
  return 0;
}

static int has(const uint8_t *d, size_t n, const char *w) {
  size_t L = strlen(w);
  for (size_t i = 0; i + L <= n; i++)
    if (!memcmp(d + i, w, L)) return 1;
  return 0;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  if (size > 65536 || has(data, size, "run") || has(data, size, "jump")) return 0;
  char *buf = malloc(size + 1);
  memcpy(buf, data, size);
  buf[size] = 0;
  FILE *fp = fmemopen(buf, size ? size : 1, "r");
  if (!fp) { free(buf); return 0; }
  static YfSim s; /* static: the longjmp must not leave it in a dead stack frame */
  static YfDeck *d;
  sim_init(&s);
  s.progress = 0;
  d = deck_new(&s);
  if (setjmp(back) == 0) deck_run_stream(d, fp, "fuzz.deck");
  fclose(fp);
  free(buf);
  deck_free(d);
  run_free();
  sim_free(&s);
  return 0;
}
