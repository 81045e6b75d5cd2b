/* contact.h: contact between triangles in the scene: which triangles take part, when the broad
 * phase runs (Y2D's buffer travel rule), the candidate pairs with their friction memory, and the
 * contact force stage.  The pair kernel is contact_pair.c, the broad phase contact_search.c.
 *
 * Contract with run.c:
 *   contact_prepare(s)  in run_prepare after joints_insert and masses: participation and pairs
 *                       filters from the deck's contact commands; nothing when contact is off.
 *   contact_step(s)     each step after the joint forces and the gather: detection if due, then
 *                       pair forces (parallel over pairs into per-pair slots), then added into
 *                       node.fx/fy in pair order (deterministic).  Accumulates contact energy
 *                       and frictional dissipation into s->energy.
 */
#ifndef YF_CONTACT_H
#define YF_CONTACT_H
#include "sim.h"

void contact_prepare(YfSim *s);
void contact_step(YfSim *s);
double contact_stable_dt(YfSim *s, char *what, size_t n);
long contact_pairs(const YfSim *s);
void contact_free(YfSim *s);

#endif
