/* fuzz_gmsh.c: libFuzzer target for the Gmsh reader (src/model/gmsh.c: MSH 2.2 and 4.1, ASCII and
 * binary) (tools/fuzz/README.md).
 *
 * Each input is written to in.msh in the scratch directory and read by `mesh gmsh` as a body
 * with a default material (every physical surface gets it), made fracturing with contact, then
 * run for 2 steps: a reader that lets through what the step cannot take (a degenerate or
 * inverted triangle, a node shared oddly, a coordinate of 1e300) shows there.  The exit hook
 * (fuzz_common.h) brings a deck error back here.
 */
#include "fuzz_common.h"

int LLVMFuzzerInitialize(int *argc, char ***argv) {
  (void)argc; (void)argv;
  fuzz_setup();
  return 0;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  if (size > 65536 || !fuzz_write_file("in.msh", data, size)) return 0;
  static const char deck[] =
      "material m elastic rho 2700 E 50e9 nu 0.25 plane_strain damping 0.1 pen_n 1e11 pen_t 1e10 friction 0.3\n"
      "mesh gmsh b in.msh material m\n"
      "jointprop j ft 2e6 fs 4e6 gf 20 pen 1e11\n"
      "fracture b j\n"
      "contact self b\n"
      "timestep auto\n"
      "run 2\n";
  fuzz_run_deck(deck, sizeof deck - 1, "fuzz_gmsh.deck");
  return 0;
}
