/* fuzz_deck.c: libFuzzer target for the deck interpreter (tools/fuzz/README.md).
 *
 * Each input is run as a deck through deck_run_stream in a fresh simulation (fuzz_common.h:
 * the exit hook longjmps back here on a deck error).
 *
 * Not fuzzed: `run` (the time loop is not the parser, and a random `run 2000000000` only burns
 * time) and `jump` (a deck may loop forever by design).  Inputs holding those words are
 * skipped.  YFDEM_MEM_MAX caps the scene size (the resource check refuses bigger ones) so that
 * `mesh rect ... 100000 1000` is a clean deck error and not an out-of-memory kill.
 */
#include "fuzz_common.h"

int LLVMFuzzerInitialize(int *argc, char ***argv) {
  (void)argc; (void)argv;
  fuzz_setup();
  return 0;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  if (size > 65536 || fuzz_has(data, size, "run") || fuzz_has(data, size, "jump")) return 0;
  fuzz_enter();
  fuzz_run_deck((const char *)data, size, "fuzz.deck");
  fuzz_leave();
  return 0;
}
