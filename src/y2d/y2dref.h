/* y2dref.h: the `y2dref` dump style: yfdem results in the neutral CSV format of the Y2D reference
 * outputs (shared/y2d/README.md section 3), so that yfdem and Y2D can be compared file for file.
 *
 *   dump ID y2dref DIR [corners S1,S2,...] [summary K] [probes K E:C E:C ...]
 *
 * writes into DIR (created if missing):
 *   corners_NNNNNNN.csv  at the listed steps: elem,corner,node,ux,uy,vx,vy per triangle corner;
 *   summary.csv          every K steps (K, 2K, ...): step,time,kinetic,elastic,px,py,nbroken,ncouples;
 *   broken.csv           every joint failure: step,elemA,elemB,nodeP,nodeQ (A < B, P < Q);
 *   probes.csv           every K steps: step,time, then ux,uy,vx,vy of each element:corner.
 * Indices are those of the input deck (element = input triangle index = triangle id, node = input
 * node number = id of the node or of the node it was copied from).  Numbers are written with 17
 * significant digits (%.16e), so they read back to the same doubles.
 */
#ifndef YF_Y2DREF_H
#define YF_Y2DREF_H
#include "sim.h"

struct YfY2dRef;

/* The names of the files in DIR (what the deck claims for the dump, cmd_dump.c): corners files are
 * Y2DREF_CORNERS, 7 digits of the step, ".csv". */
#define Y2DREF_SUMMARY "summary.csv"
#define Y2DREF_PROBES "probes.csv"
#define Y2DREF_BROKEN "broken.csv"
#define Y2DREF_CORNERS "corners_"

/* A dump into directory dir (the words of `dump ID y2dref` are read in deck/cmd_dump.c), then
 * its corner-table steps, summary and probe periods and probes (input element, corner 0..2);
 * the adders return how many there are now. */
struct YfY2dRef *y2dref_new(const char *dir);
int y2dref_add_corner_step(struct YfY2dRef *r, long step);
void y2dref_set_summary(struct YfY2dRef *r, long every);
void y2dref_set_probe_every(struct YfY2dRef *r, long every);
int y2dref_add_probe(struct YfY2dRef *r, long elem, long corner);
int y2dref_nprobe(const struct YfY2dRef *r);
int y2dref_ncorner_steps(const struct YfY2dRef *r);
/* Whether directory dir can be made (as the first frame makes it) or, when it is there, written in:
 * 0 yes, 1 it cannot be made (a file on its path, no permission), 2 it is there but cannot be
 * written in, 3, 4, 5: its summary, probes or broken table is there and cannot be written (a
 * folder of that name); errno set when not 0.  Checked at the dump's deck line, so that the deck's line
 * names the fault before the run and before any other output is written.  Nothing is left behind. */
int y2dref_dir_check(const char *dir);
/* Directory written by the dump. */
const char *y2dref_dir(const struct YfY2dRef *r);
/* After each completed step (and at the start of a run): write what is due at s->step. */
void y2dref_frame(YfSim *s, struct YfY2dRef *r);
/* At the first frame of a run continued by read_restart (before y2dref_frame): the files are
 * opened taking up the tables the earlier run left in DIR (summary, probes, broken), each keeping
 * its rows of steps before `before` (s->step for a restart written within a run, s->step + 1 for
 * one written between runs, whose step the earlier run wrote in full), so that the continued
 * tables equal the uninterrupted run's; a table that is missing, or has another header, is begun
 * afresh.  Corner tables are files of their own step, written again when due.  Returns how many
 * tables were taken up. */
int y2dref_continue(YfSim *s, struct YfY2dRef *r, long before);
/* Flush and close the files (frames written so far stay complete); safe to call twice. */
void y2dref_close(struct YfY2dRef *r);
void y2dref_free(struct YfY2dRef *r);

#endif
