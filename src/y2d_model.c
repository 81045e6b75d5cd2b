/* y2d_model.c: turning a Y2D input deck (y2d_read.c) into the yfdem scene.  (In progress: the
 * Y2D compatibility issue fills it in; until then a .y deck is refused with a clear message.) */
#include "y2d_model.h"
#include "err.h"
void y2d_apply_loads(YfSim *s) { (void)s; }
void y2d_update_velocities(YfSim *s) { (void)s; }
void y2d_run_file(YfSim *s, const char *path) {
  (void)s;
  yf_deck_error(NULL, "%s: running Y2D decks is not available in this build yet", path);
}
void y2d_model_free(YfSim *s) { (void)s; }
