/* mesh.h: getting meshes into the model, and mesh topology queries.
 *
 * mesh.c owns what creates nodes and triangles: the structured rectangle mesher (`mesh rect`),
 * the Gmsh reader (`mesh gmsh`, gmsh.c) and the inline Y2D-style nodes and triangles (`node`,
 * `triangle`, `nodes FILE`, `triangles FILE`); the commands' words are read in deck/cmd_*.c.
 * Every mesh command makes one body and a group of the same name holding its nodes and triangles.  It also answers the
 * topology questions other modules ask at setup: the boundary edges of a group (loads) and the
 * smallest edge of a material (viscosity, time step).  Nothing here runs inside the step.
 */
#ifndef YF_MESH_H
#define YF_MESH_H
#include <stddef.h>
#include <stdint.h>
#include "err.h"
#include "model.h"

/* ---- the structured mesher (`mesh rect`) ---- */
enum { YF_PAT_RIGHT, YF_PAT_LEFT, YF_PAT_ALT, YF_PAT_CROSS };
extern const char *const mesh_patterns[]; /* names of YF_PAT_*, NULL-terminated */
typedef struct {
  const char *body;             /* new body (and group) name                               */
  int mat;                      /* material index                                          */
  double x0, y0, x1, y1;        /* corners [m], x1 > x0, y1 > y0, within +-YF_RANGE_MAX     */
  long nx, ny;                  /* cells; (nx+1)(ny+1) nodes fit in an int                 */
  int pattern;                  /* YF_PAT_*                                                */
} YfRectSpec;
/* Mesh the rectangle as a new body (errors and the warning on a locking pattern at loc);
 * returns the body index, or (nothing meshed) -2 when the mesh is too large for int indices,
 * -1 when the user ids would overflow an int. */
int mesh_rect(YfModel *m, const YfRectSpec *spec, const YfLoc *loc);

/* ---- inline nodes and triangles (`node`, `triangle`, `nodes`, `triangles`) ---- */
/* Add node user id `id` at (x, y) [m] / triangle `id` on inline node ids nid (counter-clockwise)
 * to inline body bname (made on first use); deck errors at loc name cmd: a coordinate out of
 * range, a repeated id, an unknown node, a node of another body, a clockwise or flat triangle. */
void mesh_inline_node(YfModel *m, long id, double x, double y, const char *bname, const YfLoc *loc,
                      const char *cmd);
/* Twice the signed area of the triangle (x0,y0) (x1,y1) (x2,y2) [m^2] in *d2; returns 1 when the
 * triangle is degenerate: its area is zero against its longest edge (collinear corners), or
 * below 1e-280 m^2, where the step's products underflow (1e-160 m corners). */
int mesh_tri_degenerate(double x0, double y0, double x1, double y1, double x2, double y2, double *d2);
void mesh_inline_tri(YfModel *m, long id, const long nid[3], int mat, const char *bname, const YfLoc *loc,
                     const char *cmd);

/* ---- topology queries (setup time) ---- */
/* Boundary edges: edges that belong to exactly one triangle when copies of a node (node.parent)
 * count as the same node, and whose two end nodes are both in the group ((gmask & groupbit) != 0).
 * *edges receives a malloc'd array of 2*count node indices (a, b), taken from the triangle that
 * owns the edge and ordered as in its counter-clockwise corner order, so that the outward unit
 * normal is (dy, -dx)/|d| with d = x[b] - x[a].  Edges come in triangle order.  Uses initial
 * positions only through the topology (no geometry).  Returns the count (*edges is NULL when 0). */
int mesh_boundary_edges(const YfModel *m, uint64_t groupbit, int **edges);
/* Smallest initial edge length [m] of the triangles of material mat (all triangles when mat < 0);
 * 0 when there is no such triangle. */
double mesh_min_edge(const YfModel *m, int mat);

/* ---- Gmsh MSH 4.1 ASCII reader (gmsh.c) ---- */
typedef struct {
  const char *phys; /* physical group name (or its tag as a number) */
  int mat;          /* material index                                */
  int used;         /* set by the reader when a surface matched it   */
} YfPhysMat;

typedef struct {
  const char *body;     /* body (and group) name to create                                   */
  int defmat;           /* material for surfaces without a mapping or same-named material; -1 */
  YfPhysMat *map;       /* PHYS=MAT mappings                                                  */
  int nmap;
  double scale;         /* coordinates are multiplied by this                                 */
  double dx, dy;        /* ... then moved by this [m] (a second body from the same file)        */
  YfLoc from;           /* the deck line of the mesh command (for messages)                   */
} YfGmshOpts;

/* Read path (already resolved) into m as a new body; returns the body index.  Malformed files
 * end the run with "FILE.msh:LINE: error: ..." (exit 1); an unreadable file with an I/O error
 * naming it at the deck line (exit 2). */
int gmsh_read(YfModel *m, const char *path, const YfGmshOpts *o);

/* ---- helpers shared by mesh.c, gmsh.c and region.c ---- */
/* Create body `name` with material mat (may be -1 until known) and its group; deck error at loc
 * when the name is too long, already a body or already a group, or the 64 groups are used up. */
int mesh_new_body(YfModel *m, const char *name, int mat, const YfLoc *loc, const char *cmd);
/* Create or find group `name` (deck error at loc when the table is full or the name too long). */
int mesh_group_or_die(YfModel *m, const char *name, const YfLoc *loc, const char *cmd);
/* Comma-separated lists of known names for error messages (truncated with "..." at cap). */
const char *mesh_material_names(const YfModel *m, char *buf, size_t cap);
const char *mesh_body_names(const YfModel *m, char *buf, size_t cap);
const char *mesh_group_names(const YfModel *m, char *buf, size_t cap);
/* Next free user ids: 1 + the largest node / triangle id so far (1 for an empty model). */
int mesh_next_node_id(const YfModel *m);
int mesh_next_tri_id(const YfModel *m);
/* Root of a node's copy chain (node.parent followed to its fixed point). */
int mesh_node_root(const YfModel *m, int i);
/* The longest triangle edge of the scene at the initial positions [m] (0 without triangles): how
 * far a point given by coordinates may lie from every node and still be on (or at) the mesh. */
double mesh_longest_edge(const YfModel *m);
/* The nodes and triangles of m were renumbered (old index i is now nnew[i], tnew[i]): the inline
 * id maps follow. */
void mesh_renumbered(const YfModel *m, const int *tnew, const int *nnew);
/* Forget the inline node/triangle id maps (a new simulation in the same process, tests). */
void mesh_reset(void);

/* A small integer map (open addressing) from user ids / file tags to indices. */
typedef struct {
  long long *key;
  int *val;
  size_t cap, n;
} YfIdMap;
void idmap_init(YfIdMap *h);
void idmap_free(YfIdMap *h);
/* Insert key -> val; returns 0 when the key was already present (value unchanged). */
int idmap_put(YfIdMap *h, long long key, int val);
/* Value for key, or -1. */
int idmap_get(const YfIdMap *h, long long key);

#endif
