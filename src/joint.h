/* joint.h: fracture in the scene: joint insertion (Y2D meshing code 3), the joint force stage,
 * breakage records and crack/fragment statistics.  The per-joint law is joint_law.c.
 *
 * Contract with run.c:
 *   joints_insert(s)   once, in run_prepare before masses are computed: gives every triangle of a
 *                      fracturing body (or of a fracture region) its own nodes (copies keep
 *                      node.parent = the shared node, group masks, velocity, ids) and creates a
 *                      4-node joint on each internal edge.  Non-fracturing bodies are untouched.
 *   joints_forces(s)   each step after the triangle forces: evaluates every intact joint at x_n
 *                      (parallel over joints), writes 8 forces per joint into jf (zero for broken
 *                      ones), marks new breaks and records them (step, time, position, mode) in
 *                      joint index order, so the record does not depend on the thread count.
 *   The gather adds jf into nodes through the model's extra slots (model.xslot_*), so joint
 *   forces enter the node sums in a fixed order.
 */
#ifndef YF_JOINT_H
#define YF_JOINT_H
#include "sim.h"

void joints_insert(YfSim *s);
void joints_forces(YfSim *s);
/* Stable time step limit of the joints' penalty [s] (INFINITY without joints); *what names it. */
double joints_stable_dt(YfSim *s, char *what, size_t n);
/* Counts for the summary and thermo. */
long joints_count(const YfSim *s);
long joints_broken(const YfSim *s);
/* At the end of a run: summary keys (crack_length, fragments, first_break...). */
void joints_summary(YfSim *s);
void joints_free(YfSim *s);

#endif
