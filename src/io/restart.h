/* restart.h: exact restarts (HDF5) and what happens on SIGINT/SIGTERM.
 *
 * Semantics (LAMMPS-like, adapted to a deck that builds its scene from commands):
 *   The deck that continues a run rebuilds the same scene (the same material, mesh, fracture,
 *   contact, fix, load and history commands, in the same order), then `read_restart FILE`
 *   (before `run`) prepares the model exactly as `run` would (joint insertion, masses, contact
 *   setup) and overwrites the whole dynamic state with the file's: positions, initial
 *   positions, half-step velocities, forces, masses, step, time, dt, energy accumulators, joint
 *   state (broken flags, pending breaks, damage per sampling point, shear strength memory,
 *   heterogeneity factors, random generator state, work, joint forces, break records), contact
 *   state (couple list, friction memory, live flags, couple forces, travel counter, search
 *   count), the energy-check budget and the check's memory (its highs, windows and streaks: a
 *   continued run is stopped where the uninterrupted one is).  Every dataset carries the checksum
 *   of its values: a file damaged after it was written is refused (I/O error).  Histories are
 *   functions of time and need nothing.
 *   A scene that does not match (node, triangle, joint counts or the topology hash over the
 *   triangle corners, initial positions and joint nodes) is refused with a deck error.
 *   The time step is restored.  A restart written during a run (restart every, an interrupt in
 *   a run) switches `timestep auto` off (the uninterrupted run used the dt computed at the start
 *   of its `run`); one written between runs (write_restart, an interrupt outside a run: the file's
 *   /sim/between_runs) takes the time step setting of that moment, and the next run starts as the
 *   uninterrupted deck's next run did (dt computed anew under auto, stresses recomputed, a first
 *   frame and record row where that deck wrote them: output.c, thermo_style.c).  A `timestep`
 *   command after read_restart overrides either.  Output files are not part of a restart: dumps given by the deck write new
 *   files (name them differently if the old ones must be kept).  `run N upto` runs to step N.
 *   Continuing gives bitwise the same state (state_hash) as the uninterrupted run.
 *
 * Files are written to FILE.tmp, flushed, fsync'ed and renamed, so FILE is always either the
 * previous complete restart or the new complete one.  `restart every N FILE` alternates
 * FILE.a and FILE.b, so even a storage that loses the rename leaves the other one;
 * `read_restart FILE` reads FILE if it exists, else the newer valid of FILE.a / FILE.b.
 *
 * SIGINT/SIGTERM (main.c sets s->interrupted): the step in progress is finished, a restart is
 * written (to the next `restart every` file, or yfdem_interrupt.restart), every dump writes a
 * frame of that step (in a run only: between runs the continued deck's next run writes it),
 * files are closed, and yfdem exits with YF_EXIT_INTERRUPT saying how to continue.
 */
#ifndef YF_RESTART_H
#define YF_RESTART_H
#include <stddef.h>
#include "sim.h"

#define YF_RESTART_DEFAULT "yfdem_interrupt.restart"


/* Write a restart of the current state to path (atomically).  Returns 0, or -1 with a message
 * in err. Needs a prepared model (after a run or read_restart). */
int restart_write(YfSim *s, const char *path, char *err, size_t nerr);
/* What restart_write calls first (output.c registers the writing of the dumps' lagging indexes,
 * so that every frame before a restart's step is listed; restart.c knows nothing of the dumps):
 * 0, or -1 with the message in err, which stops the write. */
void restart_before_write(int (*fn)(YfSim *s, char *err, size_t nerr));
/* Read a restart into a scene built by the deck (see above); errors exit (deck / I/O). */
void restart_read(YfSim *s, const char *path, const YfLoc *loc);
/* 1 when the nodes' positions or velocities (or their number) differ from those read_restart
 * restored: the deck changed the scene after it (a body added, a velocity set). */
int restart_scene_changed(const YfSim *s);
/* The file read_restart PATH reads (PATH, else the newer valid of PATH.a / PATH.b; malloc'd), or
 * NULL when there is none. */
char *restart_pick_file(const char *path);
/* `restart every N FILE`: a restart every `every` steps, to base.a and base.b in turn; every <= 0
 * (`restart off`): none. */
void restart_every(YfSim *s, long every, const char *base);
/* Step loop hook: writes the periodic restart when due (cheap when not). */
void restart_step(YfSim *s);
/* Interrupt: write the restart; returns the name to give to read_restart ("" on failure, with
 * the reason in err). */
const char *restart_on_interrupt(YfSim *s, char *err, size_t nerr);
void restart_free(YfSim *s);

#endif
