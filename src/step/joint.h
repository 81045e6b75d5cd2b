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
 *   joints_energy(s, dist)  from run_energies: returns the elastic energy stored in intact joints
 *                      [J/m], summed per block (MPI, dist: each rank its own blocks, a collective)
 *                      (added to energy.strain) and sets energy.joint_dissipated, both for the
 *                      current positions.
 *                      Joints first past their peak (damage > 0) are recorded the same way
 *                      (opened cracks: joints_opened), at one compare per joint per step.
 *   The summary keys of fracture and the fracture_log CSV(s) are written by the io layer
 *   (report.c: joints_summary) from the records below.
 *   The gather adds jf into nodes through the model's extra slots (model.xslot_*), so joint
 *   forces enter the node sums in a fixed order.
 *
 * Deck commands (rows in commands.def):
 *   jointprop NAME ft FT fs FS gf GF pen P [law munjiza|munjiza_gf|linear|bilinear [kink Z S]|
 *             table FILE] [cohesion C friction MU] [damage reversible|irreversible]
 *             [floor y2d|none] [weibull M | normal CV] [seed S] [tangent exact|y2d]
 *   fracture BODY JOINTPROP [region R | group G]
 *   fracture_log FILE [opened FILE2]
 * Native defaults: law munjiza (Y2D's curve and constants), damage irreversible, floor y2d,
 * homogeneous, seed 1.
 *
 * Energy bookkeeping.  Each joint integrates the work its tractions do on the relative
 * displacements (trapezoid rule over every step, w[j]).  An intact joint stores: with reversible
 * damage (Y2D: unloading retraces the curve) all of w[j]; with irreversible damage the energy
 * recoverable by secant unloading to the origin, or the exact pre-peak potential while no
 * sampling point is damaged.  Dissipated = sum of w over broken joints + sum over intact joints of
 * (w - stored).
 */
#ifndef YF_JOINT_H
#define YF_JOINT_H
#include "sim.h"
#include "joint_law.h"

/* One recorded break. */
typedef struct {
  long step;       /* the step whose force evaluation failed it (1-based, Y2D's broken.csv) */
  double time;     /* time of the positions it used [s]                                     */
  double x, y;     /* midpoint of the joint at that time [m]                                 */
  double length;   /* initial joint length [m]                                               */
  int mode;        /* YF_JMODE_I, _II, _MIXED                                                */
  int triA, triB;  /* triangle indices (A < B: A created it)                                 */
  int joint;       /* joint index                                                            */
} YfBreak;

/* A joint property set (jointprop) with its heterogeneity. */
enum { YF_HET_NONE = 0, YF_HET_WEIBULL, YF_HET_NORMAL };
typedef struct {
  char name[YF_NAME_MAX];
  YfJointProp p;
  YfJointPre pre;      /* joint_pre_init(p): for joints of heterogeneity factor 1        */
  int het;             /* YF_HET_*                                         */
  double het_par;      /* Weibull modulus M or normal coefficient of variation */
  unsigned long seed;  /* GSL mt19937 seed                                   */
  void *rng;           /* gsl_rng *, created at the first insertion          */
} YfJointSet;

/* All joints of the scene (structure of arrays, index = joint number in creation order). */
typedef struct YfJoints {
  int nset;
  YfJointSet *set;
  int nspec;
  struct YfFracSpec *spec;
  int n, cap;
  int *corner;          /* 4 per joint: triangle corner slots 3*t + c of nodes 0..3          */
  int *node;            /* 4 per joint: node indices (= tri.v[corner]); the model's xslot_node */
  int *tri;             /* 2 per joint: A, B                                                  */
  int *prop;            /* joint set index                                                    */
  double *k;            /* heterogeneity factor of ft, fs, cohesion and gf (1 if none)        */
  double *fs;           /* current shear strength [Pa] (Mohr-Coulomb memory)                  */
  double *dmg;          /* 3 per joint: largest damage at end a, middle, end b (irreversible)  */
  double *w;            /* work done on the joint so far [J/m]                                */
  double *z;            /* largest damage of the last evaluation (0..1)                       */
  double *L0;           /* initial length [m]                                                 */
  unsigned char *state; /* 0 intact, 1 failed at the last evaluation, 2 broken                */
  unsigned char *mode;  /* failure mode (YF_JMODE_*) once failed                              */
  double *f;            /* 8 per joint: forces on nodes 0..3 [N/m]; the model's xslot_f        */
  int nbroken;
  int npend, *pend;     /* joints failed at the last evaluation (finalised at the next one)   */
  double diss_broken;   /* work of broken joints [J/m]                                        */
  double dt_prev;       /* time step of the last evaluation (0 before the first) [s]          */
  int nblk, *blk_nbreak;
  int nrec, caprec;
  YfBreak *rec;
  char log_path[1024];
  /* Opened cracks (the fictitious crack of the cohesive model): a joint "opens" at the first
   * evaluation that leaves damage z > 0 at a sampling point (opening beyond o_p or slip beyond
   * s_p: past the peak of the law, softening but still transmitting stress), and z >= open_z.  opened[j]: 0 never,
   * else the mode at that moment (YF_JMODE_*), | 0x80 until recorded.  The records (same layout
   * as breaks; length = initial length) are appended in joint order per step, like breaks. */
  unsigned char *opened;
  double open_z;        /* damage z a joint must reach to count as opened (metrics opened_threshold;
                           0: any z > 0, the law's peak), in [0, 1]                               */
  int *blk_nopen;
  int nopened, caporec;
  YfBreak *orec;
  char open_log_path[1024]; /* fracture_log ... opened FILE */
} YfJoints;

#define YF_JBLOCK 256 /* joints per block of the force loop (and per MPI ownership unit) */
void joints_insert(YfSim *s);
void joints_forces(YfSim *s);
/* MPI: each joint block is evaluated by the rank owning its first joint's lower triangle, which
 * alone holds the blocks' forces, work and damage; this makes them whole on every rank for a
 * reader (energies, frames, restarts; a collective: par_need_stresses calls it). */
void joints_par_gather(YfSim *s);
/* MPI: the joints whose damage (z) and forces are current on rank r, lo[r]..lo[r+1]-1 (lo: size
 * + 1 ints); 0 when every rank holds every joint's (one rank, or work not divided). */
int joints_par_rows(const YfSim *s, int *lo);
/* MPI, after the triangle ranges changed (par_balance): the blocks' forces, work and damage to
 * their new owners from the ranges lo_old (joints_par_rows before the change; a collective). */
void joints_par_move(YfSim *s, const int *lo_old);
/* The joints' part of the stable time step (run_stable_dt combines it with the triangles and
 * contact at every node): each intact joint adds its penalty [Pa] to P[i] of its 4 nodes (the
 * Gershgorin row sum of its stiffness); jof[i] (if < 0 on entry): a joint of node i, for the
 * message.  Returns 0 without intact joints.  joints_describe names joint j. */
int joints_node_penalty(const YfSim *s, double *P, int *jof);
void joints_describe(const YfSim *s, int j, char *what, size_t n);
/* Counts for the summary and thermo. */
long joints_count(const YfSim *s);
long joints_broken(const YfSim *s);
/* Stored elastic energy of intact joints [J/m]; sets s->energy.joint_dissipated (see above). */
double joints_energy(YfSim *s, int dist);
void joints_free(YfSim *s);

/* ---- what the deck's commands call (deck/cmd_jointprop.c, cmd_fracture.c, cmd_fracture_log.c) ---- */
/* A fracture zone: the triangles of body (or of those in region or group; -1 none) get joints
 * of set at the first run; a later zone overrides the set of its triangles. */
void joints_add_fracture(YfSim *s, int body, int set, int region, int group, const YfLoc *loc);
/* CSV files of the break record and (opened != NULL) of the opened-crack record. */
void joints_set_logs(YfSim *s, const char *breaks, const char *opened);
/* The damage z in [0, 1] an opened crack must reach (0, the default: any z > 0).  Joints already
 * marked opened stay opened. */
void joints_set_open_threshold(YfSim *s, double z);

/* ---- reusable pieces (Y2D reader, tests) ---- */
/* Add a joint property set; returns its index (deck error at loc when the name is taken or the
 * set is invalid; loc may be NULL). */
int joints_add_set(YfSim *s, const char *name, const YfJointProp *p, int het, double het_par,
                   unsigned long seed, const YfLoc *loc);
int joints_find_set(const YfSim *s, const char *name);
/* write_y2d: the joint set of body b when a fracture command takes the whole body (-1: none);
 * *partial is the place of a fracture command of b limited to a region or group (NULL: none). */
int joints_body_set(const YfSim *s, int body, const YfLoc **partial);
/* Split the triangles with tri_in_zone[t] != 0 and insert joints (ALGORITHMS.md 4.1 order):
 * triangles are scanned in element order and their edges in local order 0->1, 1->2, 2->0; an
 * edge shared by two triangles (the same two node indices in opposite order) with at least one
 * side in the zone is offered to prop_of_pair(ctx, A, B), A < B; a result >= 0 (a joint set
 * index) creates a joint numbered in creation order (by A, then A's local edge), slots 0, 1 = A's
 * nodes of the edge start p and end q in A's CCW order, slots 3, 2 = B's nodes of p, q.  Outer
 * boundary edges and refused pairs get no joint.  Every zone triangle gets its own three nodes:
 * each original node is reused by the first zone triangle (element order) that uses it when no
 * non-zone triangle uses it (no orphan zero-mass nodes); other copies keep id, body, gmask,
 * velocity, x0/x and node.parent = the original's index.  Nodes are renumbered: nodes not used by
 * zone triangles keep their relative order; the zone triangles of each body follow in element
 * order, three contiguous nodes each, at the place of the body's lowest zone node.  The nodes of
 * a zone triangle after the call are tri.v[3t..3t+2], in its original corner order.  May be
 * called again (later zones); earlier joints follow their triangle corners.  Registers the
 * joints as the model's extra force slots.  Returns the number of joints created. */
int joints_insert_zone(YfSim *s, const unsigned char *tri_in_zone,
                       int (*prop_of_pair)(void *ctx, int triA, int triB), void *ctx);
/* Break records so far (in detection order). */
const YfBreak *joints_breaks(const YfSim *s, int *n);
/* Opened-crack records so far (first evaluation past the peak of each joint, in detection order). */
const YfBreak *joints_opened(const YfSim *s, int *n);
/* Fragments: connected groups of triangles through shared nodes and unbroken joints.  Writes the
 * fragment index of each triangle into frag (may be NULL) and returns the count. */
int joints_fragments(const YfSim *s, int *frag);
/* Joint loops shorter than this run on one thread (default 4096; tests set 0 to force threads). */
void joints_set_par_min(int n);

#endif
