/* partition.h: METIS partition of the mesh and the renumbering that makes each part contiguous.
 *
 * Deck command (row in commands.def; deck/cmd_partition.c sets model.part_method, part_req):
 *   partition metis|none [parts N]
 * Default (no command, or `partition metis` without parts): METIS with one part per
 * YF_PART_TRIS triangles when the scene has at least 2 x YF_PART_TRIS triangles, none below.
 * The number of parts depends on the mesh only, never on the thread count, so the order of every
 * array, and with it every fixed-order sum, is the same on any number of threads.
 *
 * partition_apply(s) is called by run_prepare once, at the first run, after joint insertion and
 * before masses, gather lists, supports and contact are prepared.  It renumbers triangles (by
 * part, original order inside a part), nodes (in the order the renumbered triangles meet them;
 * nodes of no triangle last, in their old order), and joints (by their renumbered triangle A),
 * and updates everything that holds indices: tri.v, node.parent, the joints' node/corner/tri
 * slots, the contact participation flags (contact_renumber_tris) and the Y2D element map
 * (model.tri_new, used by y2d_tri_of_elem).  Ids, group masks and bodies travel with the arrays.
 * Later runs keep the order (a later mesh appends its triangles after the last part).
 */
#ifndef YF_PARTITION_H
#define YF_PARTITION_H
#include "sim.h"

/* model.part_method */
enum { PART_AUTO = 0, PART_METIS = 1, PART_NONE = 2 };

#define YF_PART_TRIS 4096 /* default: triangles per part (a part's data fits in L2) */

void partition_apply(YfSim *s);
/* Current index of a triangle given its index before the renumbering (identity when none). */
static inline int partition_tri(const YfModel *m, int t) {
  return m->tri_new && t >= 0 && t < m->ntri_new ? m->tri_new[t] : t;
}

#endif
