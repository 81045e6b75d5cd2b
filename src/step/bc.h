/* bc.h: supports, prescribed motions, loads and time histories (the directives Y2D lacked). */
#ifndef YF_BC_H
#define YF_BC_H
#include "sim.h"

/* Native fixes and loads as a boundary-condition kind (sim.h): prepare, loads, the supports
 * around the update, free.  The run loop reaches the functions below only through it. */
extern const YfBcKind bc_kind_native;

/* One fix or load as a deck command describes it (deck/cmd_fix.c, cmd_load.c). */
enum { BC_FIXED, BC_VELOCITY, BC_DISPLACEMENT, BC_POINT, BC_TRACTION, BC_PRESSURE };
typedef struct {
  int kind;           /* BC_*                                                       */
  int group;          /* group index (fixes, edge loads)                            */
  int has[2];         /* component given (x, y); NULL in the deck leaves it free     */
  double a[2];        /* amplitude: velocity [m/s], displacement [m], force [N/m], traction [Pa], pressure [Pa] */
  int hist;           /* history index or -1 (factor 1)                             */
  int node_id;        /* point load: user node id, or -1 when given by position     */
  double px, py;      /* point load: position for 'at'                              */
  YfLoc loc;          /* where it was defined (messages at resolution)              */
} YfBcSpec;
/* 1 when a fix or load has this ID. */
int bc_exists(const YfSim *s, const char *id);
/* Add a fix or load (the ID must be new). */
void bc_add(YfSim *s, const char *id, const YfBcSpec *spec);
/* Remove the fix (load = 0) or load (load = 1) with this ID; 0 when there is none. */
int bc_remove(YfSim *s, const char *id, int load);
/* Set the velocity [m/s] of a group's nodes now; returns how many nodes it set. */
int bc_set_velocity(YfSim *s, int group, double vx, double vy);

/* Resolve groups to node lists and edges (at the start of each run, after any re-meshing). */
void bc_prepare(YfSim *s);
/* Add external loads of the current step (time s->time) into node.fx/fy; remembers them for
 * the work they do during the update. */
void bc_apply_loads(YfSim *s);
/* After the free velocity update (v_{n+1/2} from forces) and before positions move: impose
 * fixed and prescribed velocities; after positions move: impose prescribed displacements.
 * Both accumulate the work of the constraint reactions and loads into s->energy. */
void bc_constrain_velocities(YfSim *s, const double *vx_old, const double *vy_old);
void bc_constrain_positions(YfSim *s, const double *x_old, const double *y_old, const double *vx_old,
                            const double *vy_old);
/* Without damping only the supported and loaded nodes need their state before the update: copy
 * x, y, vx, vy of those nodes into the node-indexed arrays (other entries are left alone).  After
 * the update has moved every node with its free velocity and bc_constrain_velocities has changed
 * some, bc_redo_positions moves the fixed / prescribed-velocity nodes again from their old
 * positions, as x_old + dt v (the operation of the plain position update). */
void bc_save_old(YfSim *s, double *x_old, double *y_old, double *vx_old, double *vy_old);
void bc_redo_positions(YfSim *s, const double *x_old, const double *y_old);
/* Time-step limit implied by anything in bc (none today): INFINITY. */
void bc_free(YfSim *s);
/* One fix or load as the deck gave it (write_y2d, y2d_write.c); i = 0..bc_count-1, in deck
 * order (later items override earlier ones on a node component); *id receives its ID. */
const YfBcSpec *bc_spec(const YfSim *s, int i, const char **id);
int bc_count(const YfSim *s);

#endif
