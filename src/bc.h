/* bc.h: supports, prescribed motions, loads and time histories (the directives Y2D lacked). */
#ifndef YF_BC_H
#define YF_BC_H
#include "sim.h"

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
/* Per-node flags: bit 0 x is prescribed, bit 1 y is prescribed (used by contact/energy). */
const unsigned char *bc_node_flags(const YfSim *s);
/* Time-step limit implied by anything in bc (none today): INFINITY. */
void bc_free(YfSim *s);
int bc_count(const YfSim *s);

#endif
