/* region.h: named geometric regions and the selections the `group` command builds node/triangle
 * sets from.
 *
 * A region is a shape in the plane (box, circle, polygon, or the outside of one).  Groups are
 * bits in node.gmask / tri.gmask (model.h); `group` fills them from regions, ids, bodies, the
 * nearest node to a point, or set operations on other groups.  Selections use the INITIAL
 * positions (x0, y0), so a deck line selects the same nodes whenever it runs.
 */
#ifndef YF_REGION_H
#define YF_REGION_H
#include <stddef.h>
#include <stdint.h>
#include "model.h"

enum { YF_REG_BOX, YF_REG_CIRCLE, YF_REG_POLYGON };
/* Add region `name` (new, shorter than YF_NAME_MAX) of kind YF_REG_*, the outside of the shape
 * when out: box c = X0 Y0 X1 Y1 (X0 <= X1, Y0 <= Y1), circle c = XC YC R (R > 0), polygon c = nc
 * coordinates X1 Y1 X2 Y2 ... (nc even, >= 6).  The boundary tolerance scales with the shape and,
 * at most, with the nodes of m meshed so far.  Returns the region's index, or -1 (nothing added)
 * for a polygon of zero area. */
int region_add(const char *name, int kind, int out, const double *c, int nc, const YfModel *m);
/* Comma-separated region names for messages ("none defined" when none). */
const char *region_names(char *buf, size_t cap);

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

/* ---- group selections (the `group` command, deck/cmd_group.c) ----
 * Each sets ns[i] / ts[t] (one flag per node / triangle, initial positions) for the members it
 * selects; group_add then adds the flagged ones to group g (groups only grow). */
enum { YF_GROUP_UNION, YF_GROUP_SUBTRACT, YF_GROUP_INTERSECT };
/* Members of the groups of bit mask first (the first operand) and rest (the others): in any
 * (union), in first and none of rest (subtract), in all (intersect). */
void group_select_sets(const YfModel *m, int op, uint64_t first, uint64_t rest, unsigned char *ns,
                       unsigned char *ts);
/* Nodes in region r / triangles whose centroid is, of body b only when b >= 0. */
void group_select_region(const YfModel *m, int r, int b, int want_n, int want_t, unsigned char *ns,
                         unsigned char *ts);
/* Nodes / triangles with the user ids ids[0..nid-1]; hit[k] = 1 when ids[k] selected one. */
void group_select_ids(const YfModel *m, const long *ids, int nid, int want_n, int want_t, unsigned char *ns,
                      unsigned char *ts, unsigned char *hit);
void group_select_body(const YfModel *m, int b, int want_n, int want_t, unsigned char *ns, unsigned char *ts);
/* The node nearest (px, py) [m], with its copies (fracturing bodies); its index in *node (-1 when
 * the scene has no node); returns its distance from the point [m] (INFINITY without nodes). */
double group_select_nearest(const YfModel *m, double px, double py, unsigned char *ns, int *node);
/* count: nodes and triangles flagged, then the group's nodes and triangles as it now stands. */
void group_add(YfModel *m, int g, const unsigned char *ns, const unsigned char *ts, long count[4]);

#endif
