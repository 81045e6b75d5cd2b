/* output.h: state dumps for post-processing (HDF5 + XDMF 3 for ParaView, CSV for scripts).
 *
 * output.c owns everything written per frame: up to YF_MAX_DUMPS dumps, each with its own files,
 * period and field list.  The step loop only calls output_step() after every completed step;
 * when no dump is due that costs one integer compare (YfOutput.next_due).
 *
 * Crash safety by construction: an h5 dump (FILE.h5) writes each frame k to its own file
 * FILE_NNNNNN.h5 (via NAME.tmp, close, rename) and never modifies a written file; only then is
 * the index FILE.xmf replaced atomically (FILE.xmf.tmp + rename) by one that lists the frame.  A
 * run killed at any moment leaves an .xmf that lists only complete frames (not fsync'ed: a power
 * cut is not covered; see output.c).  Files are created at the first frame (the start of the
 * first run after the dump command), so a deck error before `run` leaves no file.
 */
#ifndef YF_OUTPUT_H
#define YF_OUTPUT_H
#include <stddef.h>
#include "sim.h"

#define YF_MAX_DUMPS 8

/* Dump styles; y2dref (y2d/y2dref.c: Y2D reference CSV files) is written every step and
 * y2dref_frame decides what is due. */
enum { YF_DUMP_H5 = 0, YF_DUMP_CSV = 1, YF_DUMP_Y2DREF = 2 };

/* Fields of an h5 dump (bit mask).  Geometry (current x, y) is always written. */
enum {
  YF_FIELD_U = 1 << 0,        /* displacement x - x0 (node, 2 comps) [m]          */
  YF_FIELD_V = 1 << 1,        /* velocity (node, 2 comps) [m/s]                   */
  YF_FIELD_F = 1 << 2,        /* total nodal force (node, 2 comps) [N/m]          */
  YF_FIELD_STRESS = 1 << 3,   /* Cauchy stress sxx, syy, sxy (cell, 3 comps) [Pa] */
  YF_FIELD_VONMISES = 1 << 4, /* von Mises of the in-plane stress (cell) [Pa]     */
  YF_FIELD_SIGMA1 = 1 << 5,   /* max principal in-plane stress (cell) [Pa]        */
  YF_FIELD_MATERIAL = 1 << 6, /* material index (cell)                            */
  YF_FIELD_BODY = 1 << 7,     /* body index (cell)                                */
  YF_FIELD_FC = 1 << 8,       /* contact force (node, 2 comps) [N/m]; written only
                                 while contact is on (contact_node_forces)       */
  YF_FIELD_ALL = (1 << 9) - 1
};

struct YfDump;

struct YfClaim;

struct YfOutput {
  long next_due;   /* smallest step at which any dump is due (LONG_MAX: none) */
  int ndump;
  struct YfDump *dump[YF_MAX_DUMPS];
  int nclaim;      /* the files outputs write, by owner (output_claim)        */
  struct YfClaim *claim;
  int npast;       /* dumps undumped in this process: style, fields and clean */
  int *past_style; /* path, so that a dump again on the same file continues  */
  unsigned *past_fields; /* their series instead of writing over its frames   */
  int *past_fc;    /* ... and whether that series had the contact force fc   */
  char **past;
};

/* The files the outputs write, so that two outputs never write one file (two records on one
 * file interleaved their rows; a record on a dump's index, or dumps named out.h5 and ./out.h5,
 * lost one of the two).  Every command that names an output claims its files here, in one
 * place: dumps, records, fracture_log, metrics log, restart every, -log, -summary.  A claim is
 * PREFIX exactly, or PREFIX, `numbered` digits, SUFFIX (numbered frames: 6 digits for a dump's,
 * 7 for a y2dref dump's corners files); paths are compared
 * absolute, with '.', '..' and repeated '/' resolved (links are not followed).  Returns the
 * owner of a claim the new one meets (nothing is recorded then), or NULL when it is recorded. */
const char *output_claim(YfSim *s, const char *owner, const char *prefix, const char *suffix, int numbered);
/* The fields of the earlier dump whose series dump k continues (it was undumped, and k names its
 * file again), or 0 when k starts its own series. */
unsigned output_dump_earlier_fields(const YfSim *s, int k);
/* Write every index that lags its frames (a long series rewrites its index only now and then):
 * restart_write calls it, so every frame before a restart's step is listed and a continuation
 * after SIGKILL has no hole before its restart (it numbered its frames after the last listed one
 * and overwrote frames already written).  0, or -1 with the message in err. */
int output_flush_indexes(YfSim *s, char *err, size_t nerr);
/* Forget every claim of owner (undump, record ID off, a fracture_log or restart replaced). */
void output_release(YfSim *s, const char *owner);

/* Deck commands (their words: deck/cmd_dump.c, cmd_undump.c).
 *   dump ID h5 N FILE.h5 [fields F1 F2 ...] [compress]
 *   dump ID csv N PREFIX
 *   dump ID y2dref DIR ...
 *   undump ID                                                                     */

/* Field names of an h5 dump: index k is YF_FIELD_* bit k, then "x" (geometry, always written). */
extern const char *const output_field_names[];
struct YfY2dRef;
/* Programmatic form of `dump` (used by cmd_dump and tests).  Returns the dump's slot; checks
 * nothing about the deck (the handler does), but refuses a full table or a duplicate id with -1. */
int output_add_dump(YfSim *s, const char *id, int style, long every, const char *path,
                    unsigned fields, int compress);
/* A y2dref dump (every step) writing r, which it then owns; the slot or -1 as output_add_dump. */
int output_add_y2dref(YfSim *s, const char *id, struct YfY2dRef *r);
/* The dumps as they stand: count, slot of id (-1: none), id and path of slot k, and the file
 * names an h5 dump writes (FILE_NNNNNN.EXT frames, the XDMF index). */
int output_ndump(const YfSim *s);
int output_find_dump(const YfSim *s, const char *id);
const char *output_dump_id(const YfSim *s, int k);
const char *output_dump_path(const YfSim *s, int k);
void output_dump_files(const YfSim *s, int k, const char **stem, const char **ext, const char **xmf);
/* The length of an h5 dump's stem in its FILE: FILE without a .h5, .hdf5 or .hdf extension (the
 * whole of FILE when it has none: the frames then get ".h5"). */
size_t output_h5_stem_len(const char *path);
/* Close and forget dump id; returns 0, or -1 when there is no such dump. */
int output_remove_dump(YfSim *s, const char *id);

/* Step-loop hooks (run.c). */
void output_run_begin(YfSim *s); /* start of each run: a frame of the current state per dump  */
void output_step(YfSim *s);      /* after each completed step: frames that are due            */
void output_run_end(YfSim *s);   /* end of each run                                          */
/* Write one frame of every dump now (whether due or not; skipped if this step is written). */
void output_write_all(YfSim *s);
/* Topology changed (triangles or node count).  Kept for callers; nothing to do, since every h5
 * frame file carries the mesh of its own step. */
void output_topology_changed(YfSim *s);
/* Close what is open (csv indexes; a frame file a failure left half-written is removed).
 * Frames written so far stay readable.  Safe from the error cleanup path and more than once;
 * never exits. */
void output_close_all(YfSim *s);
/* output_close_all + free everything (sim_free). */
void output_free(YfSim *s);

/* Frames written so far by dump id (-1 if no such dump); for tests and messages. */
long output_frames(const YfSim *s, const char *id);
/* Times the .xmf index of h5 dump id was rewritten (-1 if no such dump); for tests. */
long output_index_writes(const YfSim *s, const char *id);
/* The index rewrite policy (see output.c, xmf_write): indexes up to small_bytes are rewritten
 * at every frame, larger ones when gap x their last rewrite time has passed.  Defaults 1 MiB
 * and 20; for tests. */
void output_set_index_policy(size_t small_bytes, double gap);
/* ./yfdem_mpi: 1 when h5 dumps are written by every rank with parallel HDF5 (YFDEM_H5_MPIIO=1|0,
 * unset: the measured default, docs/SCALING.md), 0 when gathered to rank 0; ./yfdem: 0. */
int output_mpio(void);
int output_dump_mpio(const YfSim *s, int k); /* dump k is written so */

#endif
