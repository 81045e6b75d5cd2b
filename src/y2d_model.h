/* y2d_model.h: a Y2D input deck (y2d_read.c) as a yfdem scene, and the Y2D boundary-condition
 * sets in the step (ALGORITHMS.md 7, 2.5).
 *
 * Contract with run.c (active only when sim->y2d != NULL, i.e. after read_y2d):
 *   y2d_apply_loads(s)        after the gather: edge pressures and shear tractions of the sets.
 *   y2d_update_velocities(s)  replaces the generic velocity update for every node: v_{n+1/2}
 *                             from forces, gravity and each set's kinds in its local frame.
 *                             Native fixes and loads given after read_y2d still act on top.
 */
#ifndef YF_Y2D_MODEL_H
#define YF_Y2D_MODEL_H
#include "sim.h"

void y2d_apply_loads(YfSim *s);
void y2d_update_velocities(YfSim *s);
/* `yfdem FILE.y`: read_y2d FILE.y then run to MCSTEP. */
void y2d_run_file(YfSim *s, const char *path);
void y2d_model_free(YfSim *s);

#endif
