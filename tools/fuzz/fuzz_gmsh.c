/* fuzz_gmsh.c: libFuzzer target for the Gmsh reader (src/model/gmsh.c: MSH 2.2 and 4.1, ASCII and
 * binary) (tools/fuzz/README.md).
 *
 * Each input is written to in.msh in the scratch directory and read by tests/corpus/reader_gmsh.deck,
 * the deck make check replays the .msh rows of tests/corpus/MANIFEST with: `mesh gmsh` as a body
 * with a default material, made fracturing with contact, then run for 2 steps: a reader that lets
 * through what the step cannot take (a degenerate or inverted triangle, a coordinate of 1e300)
 * shows there.  The exit hook (fuzz_common.h) brings a deck error back here.
 */
#include "fuzz_common.h"

static char *deck;
static size_t ndeck;

int LLVMFuzzerInitialize(int *argc, char ***argv) {
  (void)argc; (void)argv;
  fuzz_setup();
  deck = fuzz_corpus_file("reader_gmsh.deck", &ndeck);
  return 0;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  if (size > 65536) return 0;
  fuzz_enter();
  if (fuzz_write_file("in.msh", data, size)) fuzz_run_deck(deck, ndeck, "reader_gmsh.deck");
  fuzz_leave();
  return 0;
}
