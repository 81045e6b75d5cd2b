/* y2d_model.c: turning a Y2D input deck (y2d_read.c) into the yfdem scene.  (In progress.) */
#include "sim.h"
#include "err.h"
void y2d_run_file(YfSim *s, const char *path) {
  (void)s;
  yf_deck_error(NULL, "%s: running Y2D decks is not available in this build yet", path);
}
