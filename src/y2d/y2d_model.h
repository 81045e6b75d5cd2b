/* y2d_model.h: a Y2D input deck (y2d_read.c) as a yfdem scene, and the Y2D boundary-condition
 * sets in the step (ALGORITHMS.md 7, 2.5).
 *
 * read_y2d builds nodes (ids = input node numbers), triangles (ids = input element indices, in
 * input order), one material per Y2D element property (the deck's Lame constants, the book's
 * volumetric factor 1/2 unless `volfac 1`), joints from the meshing rows (ALGORITHMS 4.1, code 3)
 * and contact (MICOUP > 0), and keeps the BC sets in a YfY2dRun (s->y2d).
 *
 * Contract with run.c (active only when sim->y2d != NULL, i.e. after read_y2d):
 *   y2d_apply_loads(s)        after the gather: edge pressures and shear tractions of the sets.
 *   y2d_update_velocities(s, par, vxo, vyo, move) replaces the generic velocity update for every node:
 *                             v_{n+1/2} from forces, gravity and each set's kinds in its local frame.
 *                             Native fixes and loads given after read_y2d still act on top.  move = 1
 *                             (only when nothing acts between the two, i.e. no native supports and
 *                             no damping) also does run.c's x += dt v, block by block in cache.
 */
#ifndef YF_Y2D_MODEL_H
#define YF_Y2D_MODEL_H
#include "sim.h"

/* Y2D BC kinds of a local direction (FORMAT.md 3.8); anything else freezes the velocity. */
enum { Y2D_KIND_FORCE = 1, Y2D_KIND_ACCEL = 2, Y2D_KIND_VELOCITY = 3 };

/* The state of a read_y2d scene (plain arrays; built once by read_y2d, node arrays resolved again
 * when joint insertion adds nodes). */
typedef struct YfY2dRun {
  char *path;          /* the .y file                                                        */
  void *deck;          /* the YfY2d as read (owned; YfLoc file names of messages point here);
                          its arrays are freed once the scene is built from them             */
  double volfac;       /* factor of the volumetric term: 0.5 book Y2D, 1 Y-Geo family          */
  int tri0, ntri;      /* triangles tri0 .. tri0+ntri-1 are the input elements 0..ntri-1       */
  int node0, nnode;    /* at read: nodes node0 .. node0+nnode-1 are the input nodes 0..nnode-1
                          (joint insertion renumbers nodes: use ids and gbit afterwards)        */
  uint64_t gbit;       /* group mask bit of group "y2d" (all nodes and triangles of the deck)  */
  double gy;           /* DCGRAY [m/s^2]                                                      */
  /* BC sets (arrays [nset]) */
  int nset;
  int *kind;           /* 2 per set: local x, local y                                         */
  double *amp;         /* 2 per set: amplitude [N/m | m/s^2 | m/s]                             */
  double *ap, *at;     /* edge pressure and shear traction [Pa]                               */
  double *R, *Ri;      /* 4 per set: local frame [ex ey] (row-major 2x2) and its inverse        */
  int tables_on, npts; /* time tables: on/off, points per table                               */
  double *tt, *tf;     /* [nset][npts]: times [s], factors [-]                                 */
  double *phi;         /* [nset]: time factor at the current step's t_n                        */
  double *acur;        /* [2 nset]: amp * phi of the current step                              */
  /* per node (resolved for the current node count) */
  int nn;              /* node count the arrays below were built for                           */
  int *setof;          /* [nnode]: BC set of each input node (the deck's I1NOPR), -1 none       */
  int *set;            /* BC set of each node (copies inherit their parent's), -1 none         */
  int nublk;           /* blocks of Y2D_UBLOCK nodes of the velocity update                    */
  double *ublk;        /* [nublk]: external work of each block of the last update [J/m]        */
  /* loaded triangle edges: triangle, local edge j (edge from corner j to j+1) */
  int nle;
  int *le;
  double *lf;          /* per node: edge load of this step (2 per node) [N/m], for the work    */
  int contact_on;      /* MICOUP > 0                                                           */
  long micoup;         /* MICOUP: Y2D's couple capacity (overflow stops Y2D, FORMAT.md 3.4, 6)       */
  YfLoc micoup_loc;    /* where the deck gave it                                               */
  int micoup_warned;   /* the couple list outgrew it once (warned)                              */
} YfY2dRun;

extern const YfBcKind y2d_bc_kind;
void y2d_apply_loads(YfSim *s);
/* Nodes per block of the velocity update: fixed, so the work sum does not depend on threads. */
#define Y2D_UBLOCK 4096
/* par: run the node blocks on threads; vxo, vyo (or NULL): receive the velocities before the
 * update (bc.c's supports need them). */
void y2d_update_velocities(YfSim *s, int par, double *vxo, double *vyo, int move);
/* Tests: 1 sends every node through the scalar update (the reference of the 4-wide one). */
void y2d_update_scalar_only(int on);
/* `yfdem FILE.y`: read_y2d FILE.y then run to MCSTEP. */
void y2d_run_file(YfSim *s, const char *path);
/* Build the scene of a .y deck into s (programmatic form of read_y2d; from: where it was asked,
 * for messages, may be NULL).  volfac: 0.5 (book Y2D) or 1 (Y-Geo family decks). */
void y2d_load(YfSim *s, const char *path, double volfac, const YfLoc *from);
void y2d_model_free(YfSim *s);
/* Deck command: read_y2d FILE [volfac 0.5|1] */
/* Properties (materials) of the deck read. */
int y2d_nprop(const YfSim *s);

/* Index maps of a read_y2d scene: triangle index of input element e (-1 if none), input node
 * number of node i (its id: copies made by joint insertion keep the original's id). */
int y2d_tri_of_elem(const YfSim *s, long e);
int y2d_input_node(const YfSim *s, int i);

#endif
