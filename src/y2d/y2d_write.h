/* y2d_write.h: export of a native scene as a Y2D input deck (write_y2d FILE steps N [every K]).
 *
 * The inverse of read_y2d (y2d_model.c) for the part of a scene that Y2D can express, in the
 * format of /work/shared/y2d/FORMAT.md: the mesh before joint insertion with meshing rows of
 * code 3 (Y2D inserts the joints at its step 0 as yfdem's `fracture` does), one element property
 * per (body, material), joint sets, contact, fixed supports and prescribed velocities, point and
 * edge loads with their time tables as BC sets, initial velocities, gravity, dt, step count and
 * output interval.  What Y2D cannot express is a deck error naming the feature, or a warning
 * that says how it was approximated.  docs/y2d_decks.md documents the mapping.
 */
#ifndef YF_Y2D_WRITE_H
#define YF_Y2D_WRITE_H
#include "err.h"
#include "sim.h"

/* Write the scene (before its first run) to path as a Y2D deck that runs `steps` steps and writes
 * its animation output every `every` steps (ICOUTF; 0: the thermo interval, else steps/10), with
 * output scales DCSIZC/V/S that hold the scene's coordinates, velocities and stresses unclipped;
 * loc is the command's place for messages.  Deck errors name what Y2D cannot express. */
void y2d_write(YfSim *s, const char *path, long steps, long every, const YfLoc *loc);

#endif
