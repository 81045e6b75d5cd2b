/* region.h: named geometric regions and the `group` command that builds node/triangle sets.
 *
 * A region is a shape in the plane (box, circle, polygon, or the outside of one).  Groups are
 * bits in node.gmask / tri.gmask (model.h); `group` fills them from regions, ids, bodies, the
 * nearest node to a point, or set operations on other groups.  Selections use the INITIAL
 * positions (x0, y0), so a deck line selects the same nodes whenever it runs.
 */
#ifndef YF_REGION_H
#define YF_REGION_H

struct YfSim;

/* Commands (rows for commands.def). */

/* Index of region `name`, or -1. */
int region_find(const char *name);
/* 1 when (x, y) [m] is in region r.  Points on the boundary (within 1e-9 of the region's size,
 * or of its coordinates' magnitude when larger) count as inside, for `side in` and `side out`
 * alike, so that nodes exactly on a box edge are caught. */
int region_contains(int r, double x, double y);
int region_count(void);
const char *region_name(int r);
/* Forget all regions (tests, a new simulation in the same process). */
void region_reset(void);

#endif
