/* par.h: the hooks by which a run is shared among MPI ranks (./yfdem_mpi, built by `make mpi`
 * with -DYF_MPI; the implementation is src/par/par_mpi.c, a layer above the step).  In ./yfdem every hook is an inline no-op and MPI is not
 * linked.
 *
 * The work of a step is divided by ownership (docs/SCALING.md):
 *   - every rank runs the whole deck and holds the whole scene (memory is not divided), but
 *     between readers only its own and its ghost nodes are current (the divided update below);
 *   - rank r owns the triangles of its METIS parts (a contiguous range of the partition order,
 *     whose borders move when contact makes the ranks' work uneven: par_balance)
 *     and the nodes their first triangle is r's (a contiguous range too); it computes its
 *     triangles' forces, the joint blocks and the contact couples whose lower triangle it owns;
 *   - the forces other ranks' nodes need go to their owners (slot halo, contact contributions);
 *     each owner sums its nodes' forces in the one-rank slot and couple order and updates its
 *     nodes (the divided update), or, where the update cannot be divided, every rank gets every
 *     node's force and updates every node: the same bits as one rank either way;
 *   - block sums that straddle ranks are summed from per-item results in order; joint events and
 *     dropped couples go to every rank, so records and lists stay the same everywhere;
 *   - what only owners hold (stresses, joint state, friction memory, node contact forces) is
 *     gathered when read (par_need_all: custom thermo, gathered frames, records, restarts; the
 *     energies are block sums on owners, run.c, and gather nothing);
 *   - only rank 0 prints and writes files (yf_writer), except h5 frames on 2 ranks or more, which
 *     every rank writes with parallel HDF5, each its own rows (io/output.c: no gather for
 *     them); an error stops every rank (par_mpi.c).
 */
#ifndef YF_PAR_H
#define YF_PAR_H
#include <stdio.h>
#include "model.h"
#include "elem_tri.h"
#include "stage_time.h"

#ifdef YF_MPI
struct YfSim;
void par_init(int *argc, char ***argv); /* MPI_Init, the writer rank, the error exit          */
/* A deck on stdin: rank 0 reads it, every rank runs it; an interrupt (*stop set by the signal
 * handler) while it is read ends every rank with "interrupted while reading the deck". */
FILE *par_stdin(FILE *in, const volatile int *stop);
/* From the signal handler (async-signal-safe): the ranks' standard output and error stop
 * blocking.  mpirun stops reading them at a Ctrl-C, and a rank blocked in a write would never
 * reach the step's interrupt check (nor write the restart) before mpirun kills the job. */
void par_interrupted(void);
int par_size(void);
/* Ownership of the element stage for the scene's triangles in nblk blocks of `block`. */
void par_prepare(struct YfSim *s, int nblk, int block);
void par_blocks(int *b0, int *b1);      /* the blocks this rank sums whole: [b0, b1)           */
/* After the element stage: this rank's triangles of blocks it shares with others, then every
 * rank gets every corner force (6 per triangle) and every block's (viscous power, first bad
 * triangle, its J). */
void par_share_elements(YfModel *m, const YfTriMat *tm, double *blk, int *blk_bad, double *blk_badJ,
                        double t_elem);
/* Every triangle's stress on every rank (a collective: every rank calls it at the same point; a
 * no-op when shared since the last element stage); par_need_all: that and what joints and
 * contact keep on owners (their forces, work, damage, friction memory, node contact forces),
 * for energies, frames and restarts. */
void par_need_stresses(YfModel *m);
void par_need_all(struct YfSim *s);
void par_run_end(struct YfSim *s); /* par_need_all at a run's end, its bytes apart in the report */
/* Halo mode: the nodes this rank sums the force of, [n0, n1) (unchanged when every rank sums
 * every node); then par_share_forces gives every rank every node's force from its owner. */
void par_nodes(int *n0, int *n1);
void par_share_forces(double *fx, double *fy);
/* Generic pieces for the stages that share work by ownership (contact.c):
 *   par_node_lo        node ranges lo[0..size] of the owners (NULL: every rank sums every node);
 *   par_owner_ranges   items sorted by a triangle tri[stride k] (couples, joint blocks), by that
 *                      triangle's owner: lo[0..size]; 0 when work is not shared (one rank);
 *   par_share_slots    the force slots other ranks' owned nodes need, to them (before the gather);
 *   par_concat         every rank's bytes, concatenated in rank order, to every rank (rbytes:
 *                      how many from each); the buffer lives until the next call;
 *   par_concat_writer  the same to the writer rank (rank 0) only: NULL on the others, whose
 *                      rbytes are left alone (what only the writer reads: a restart's couples);
 *   par_exchange       sbytes[r] bytes of send (grouped by rank) to rank r; returns what came,
 *                      grouped by sender, rbytes[r] from each;
 *   par_gather_ranges  an array whose elements lo[r]..lo[r+1]-1 rank r holds, whole on every rank. */
int par_rank(void);
void par_note_cross_hits(const int *ij, const int *hk, int nh); /* the run report's count */
void par_note_work(double secs); /* divided work of this rank (the report's imbalance) */
/* The CPU clock that par_note_work and par_share_elements are given differences of [s]: the
 * process's CPU time under MPI; 0 in ./yfdem, where nothing reads it (a system call per read:
 * two per step were 10 % of a 16-triangle scene's step). */
static inline double par_work_clock(void) { return yf_cpu_now(); }
void par_note_discs(long sent, long own); /* a contact search on ranks: discs sent, own discs */
const int *par_node_lo(void);
int par_owner_ranges(const int *tri, int stride, int n, int *lo);
void par_share_slots(YfModel *m);
const void *par_concat(const void *mine, int nbytes, int *rbytes);
const void *par_concat_writer(const void *mine, int nbytes, int *rbytes);
const void *par_exchange(const void *send, const int *sbytes, int *rbytes);
void par_gather_ranges(void *a, const int *lo, int elem_bytes);
int par_any(int flag);                  /* flag set on any rank (the same answer on all)       */
/* Parallel HDF5 frames (output.c): rank 0's value on every rank, and the triangle ranges of
 * the owners, tlo[0..size] (NULL on one rank). */
long par_bcast_long(long v);
const int *par_tri_lo(void);
void par_run_report(struct YfSim *s, long nsteps, double wall); /* ranks, imbalance, traffic */
void par_run_clock(void); /* the run's wall clock starts: its communication time counts from here */
/* Divided update (docs/SCALING.md section 1).  At each run's start par_run_begin decides whether
 * every rank updates only the nodes it owns (no mass damping, and no boundary-condition kind that
 * both replaces the update and shares nodes), plus the nodes the kinds share (YF_BC_SHARED: every
 * rank updates them, from forces their owners send); then, after each update, each rank receives
 * the positions and velocities of the ghost nodes it reads in the next step: its triangles'
 * corners, its joint blocks' nodes, the nodes the kinds read (YF_BC_READS), and the nodes of its
 * contact couples' triangles (par_contact_ghosts, at each search).  Other ranks' nodes are stale
 * between readers: par_need_all makes them whole.  The contact search runs on ranks by bounding
 * boxes (contact.c search_ranks) and reads no other rank's node.
 *   par_update_nodes   the nodes this rank updates: [n0, n1) and extra[0..nextra-1]
 *   par_node_split     for a sum over nblk fixed blocks of nodes: the blocks inside this rank's
 *                      nodes, [kb0, kb1), and a buffer for one value per node of its head and tail
 *                      pieces ([n0, kb0 block) and [kb1 block, n1), or all of [n0, n1) when kb1 <= kb0)
 *   par_node_block_sums  every block's sum on every rank: whole blocks from their rank, split
 *                      blocks summed from the pieces' values in node order (the one-rank bits) */
void par_run_begin(struct YfSim *s);
int par_divided(void);
int par_run_id(void);
int par_layout_id(void); /* changes when the triangle ranges do (a new scene, a re-cut) */
void par_update_nodes(int *n0, int *n1, const int **extra, int *nextra);
double *par_node_split(int nblk, int block, int *kb0, int *kb1);
void par_node_block_sums(double *blk);
/* The same for a sum over nblk fixed blocks of triangles over the triangle ranges (the strain
 * energy): par_tri_split gives the blocks inside this rank's triangles and the buffer of its
 * head and tail triangles' values; par_tri_block_sums every block's sum on every rank. */
double *par_tri_split(int nblk, int block, int *kb0, int *kb1);
void par_tri_block_sums(double *blk);
void par_ghost_exchange(YfNodes *n);
void par_contact_ghosts(YfNodes *n, const int *nodes, int nnodes);
double par_max(double v);
/* Re-balancing (docs/SCALING.md section 1): after a step whose contact stage searched, the ranks
 * weigh their work (triangles, nodes, joints, couples); when it is uneven the triangle ranges
 * move, and what changes owner goes to its new owner (a collective; the bits do not change).
 *   par_move_ranges  an array held by ranges lo_old made current on lo_new (what moves only). */
void par_balance(struct YfSim *s);
void par_move_ranges(void *a, const int *lo_old, const int *lo_new, int elem_bytes);
#else
static inline void par_init(int *argc, char ***argv) { (void)argc; (void)argv; }
static inline FILE *par_stdin(FILE *in, const volatile int *stop) { (void)stop; return in; }
static inline void par_interrupted(void) {}
static inline int par_size(void) { return 1; }
struct YfSim;
static inline void par_prepare(struct YfSim *s, int nblk, int block) { (void)s; (void)nblk; (void)block; }
static inline void par_blocks(int *b0, int *b1) { (void)b0; (void)b1; }
static inline void par_share_elements(YfModel *m, const YfTriMat *tm, double *blk, int *blk_bad,
                                      double *blk_badJ, double t_elem) {
  (void)m; (void)tm; (void)blk; (void)blk_bad; (void)blk_badJ; (void)t_elem;
}
static inline void par_need_stresses(YfModel *m) { (void)m; }
static inline void par_need_all(struct YfSim *s) { (void)s; }
static inline void par_run_end(struct YfSim *s) { (void)s; }
static inline void par_nodes(int *n0, int *n1) { (void)n0; (void)n1; }
static inline void par_share_forces(double *fx, double *fy) { (void)fx; (void)fy; }
static inline int par_rank(void) { return 0; }
static inline void par_note_cross_hits(const int *ij, const int *hk, int nh) { (void)ij; (void)hk; (void)nh; }
static inline void par_note_work(double secs) { (void)secs; }
static inline double par_work_clock(void) { return 0.0; }
static inline void par_note_discs(long sent, long own) { (void)sent; (void)own; }
static inline const int *par_node_lo(void) { return NULL; }
static inline int par_owner_ranges(const int *tri, int stride, int n, int *lo) { (void)tri; (void)stride; (void)n; (void)lo; return 0; }
static inline void par_share_slots(YfModel *m) { (void)m; }
static inline const void *par_concat(const void *mine, int nbytes, int *rbytes) { *rbytes = nbytes; return mine; }
static inline const void *par_concat_writer(const void *mine, int nbytes, int *rbytes) { *rbytes = nbytes; return mine; }
static inline const void *par_exchange(const void *send, const int *sbytes, int *rbytes) { *rbytes = *sbytes; return send; }
static inline void par_gather_ranges(void *a, const int *lo, int elem_bytes) { (void)a; (void)lo; (void)elem_bytes; }
static inline int par_any(int flag) { return flag; }
static inline long par_bcast_long(long v) { return v; }
static inline const int *par_tri_lo(void) { return NULL; }
#define par_run_report(s, nsteps, wall) ((void)0)
static inline void par_run_clock(void) {}
static inline void par_run_begin(struct YfSim *s) { (void)s; }
static inline int par_divided(void) { return 0; }
static inline int par_run_id(void) { return 0; }
static inline int par_layout_id(void) { return 0; }
static inline void par_update_nodes(int *n0, int *n1, const int **extra, int *nextra) {
  (void)n0; (void)n1; (void)extra; (void)nextra;
}
static inline double *par_node_split(int nblk, int block, int *kb0, int *kb1) {
  (void)nblk; (void)block; (void)kb0; (void)kb1; return NULL;
}
static inline void par_node_block_sums(double *blk) { (void)blk; }
static inline double *par_tri_split(int nblk, int block, int *kb0, int *kb1) {
  (void)nblk; (void)block; (void)kb0; (void)kb1; return NULL;
}
static inline void par_tri_block_sums(double *blk) { (void)blk; }
static inline void par_ghost_exchange(YfNodes *n) { (void)n; }
static inline void par_contact_ghosts(YfNodes *n, const int *nodes, int nnodes) { (void)n; (void)nodes; (void)nnodes; }
static inline double par_max(double v) { return v; }
static inline void par_balance(struct YfSim *s) { (void)s; }
static inline void par_move_ranges(void *a, const int *lo_old, const int *lo_new, int elem_bytes) {
  (void)a; (void)lo_old; (void)lo_new; (void)elem_bytes;
}
#endif

#endif
