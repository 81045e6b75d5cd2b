/* fuzz_y2d.c: libFuzzer target for the Y2D .y reader (src/y2d/y2d_read.c) and the scene it
 * builds (y2d_model.c) (tools/fuzz/README.md).
 *
 * Each input is written to in.y in the scratch directory and read by a deck `read_y2d in.y`,
 * then run for 2 steps: a reader that lets through what the step cannot take (a node index past
 * the nodes, a zero area, a NaN) shows there.  The exit hook (fuzz_common.h) brings a deck error
 * back here.  Its $YINCL files are looked up beside in.y: the scratch directory.
 * (make check replays the .y rows of tests/corpus/MANIFEST as `yfdem FILE.y`: the same reader.)
 */
#include "fuzz_common.h"

int LLVMFuzzerInitialize(int *argc, char ***argv) {
  (void)argc; (void)argv;
  fuzz_setup();
  return 0;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  static const char deck[] = "read_y2d in.y\nrun 2\n";
  if (size > 65536) return 0;
  fuzz_enter();
  if (fuzz_write_file("in.y", data, size)) fuzz_run_deck(deck, sizeof deck - 1, "fuzz_y2d.deck");
  fuzz_leave();
  return 0;
}
