/* model.h: the scene as plain arrays (structure of arrays).
 *
 * The hot loops of a step touch only numbers: positions, velocities, forces and masses of nodes;
 * corner node indices, reference inverses and stresses of triangles; joint node quadruples and
 * their state.  Bookkeeping (user ids, group masks, bodies, names) sits in separate arrays the
 * step never reads.  Every array is indexed by a dense 0-based index so that a partition (a
 * thread now, an MPI rank later) can own a contiguous range of nodes, triangles and joints.
 *
 * Fracturing bodies follow Y2D: each triangle owns its three nodes and a 4-node joint sits on
 * every internal edge (joint.c).  Bodies that cannot break keep shared nodes and have no joints.
 * node.parent[] remembers the shared node a copy came from, so topology (boundary edges, groups,
 * output by original id) survives the split.
 *
 * Units: SI throughout, 2D per unit thickness (forces N/m, masses kg/m, energies J/m).
 */
#ifndef YF_MODEL_H
#define YF_MODEL_H
#include <stdint.h>
#include <stddef.h>

#define YF_NAME_MAX 48
/* The largest |coordinate| [m] and |velocity| [m/s] accepted: areas, stiffnesses and energies
 * multiply two of them (and a modulus or a density), which must stay far inside the range of a
 * double (1.8e308); 1e100 leaves that room and is beyond any physical scene.  Beyond it the
 * arithmetic overflows (areas of zero or inf, energies of inf), so it is refused by name. */
#define YF_RANGE_MAX 1e100
#define YF_MAX_GROUPS 64 /* group membership is a 64-bit mask per node and per triangle */

enum { YF_PLANE_STRESS = 0, YF_PLANE_STRAIN = 1, YF_PLANE_LAME = 2 };
/* Contact friction laws (kernel/contact_pair.h has their equations): Y2D's, and the elastic-slip
 * Coulomb law of native decks. */
enum { YF_FRIC_Y2D = 0, YF_FRIC_COULOMB = 1 };

/* A material: the triangle law T = (2 mu / J) E + k D + volfac lambda (J - 1/J) I
 * (Munjiza / Y2D, ALGORITHMS.md 2.2).  Native decks give E, nu and plane_stress|plane_strain;
 * material.c maps them to (lambda, mu) with volfac = 1/2 so that the small-strain response is
 * exactly Hooke's law (J - 1/J ~ 2 tr eps).  read_y2d keeps the deck's Lame constants and the
 * book's volfac = 1/2 (or 1 for Y-Geo decks). */
typedef struct {
  char name[YF_NAME_MAX];
  double rho;      /* density [kg/m^3]                                        */
  double E, nu;    /* Young's modulus [Pa], Poisson's ratio (0 when Lame-given) */
  int plane;       /* YF_PLANE_*                                               */
  double lambda;   /* Lame lambda used in the law [Pa]                          */
  double mu;       /* shear modulus [Pa]                                        */
  double volfac;   /* factor of the volumetric term (0.5 book Y2D, 1 Y-Geo)     */
  double visc;     /* viscous coefficient k [Pa s]                              */
  double beta;     /* if > 0: visc = 2 h beta sqrt(E rho), h = smallest edge of the material */
  /* contact (contact.c): penalties [Pa] and Coulomb friction coefficient      */
  double pen_n, pen_t, fric;
  int pen_n_given; /* 1: the deck wrote pen_n, so a pen_n of 0 is meant (a Y2D property of D1PEPE 0, whose
                      couples exist and carry no force); 0: a contact rule refuses pen_n 0 as forgotten */
  int fric_law;    /* YF_FRIC_* (contact_pair.h): 0 = Y2D's (read_y2d, zeroed default),
                      native `material` commands set the Coulomb law unless told y2d */
  int rigid;       /* reserved for Y2D type 2 triangles                          */
  int jset;        /* joint property set for fracture (joint.c), -1 = unbreakable */
} YfMaterial;

typedef struct {
  int n, cap;
  double *x, *y;   /* current position [m]                                     */
  double *x0, *y0; /* initial (reference) position [m]                         */
  double *vx, *vy; /* velocity [m/s] at the half step n-1/2 (after update: n+1/2) */
  double *fx, *fy; /* total nodal force of the current step [N/m]              */
  double *m;       /* lumped mass [kg/m]                                       */
  int *id;         /* user/input id (deck node id, Gmsh tag, Y2D index)        */
  int *parent;     /* shared node this one was copied from (== own index if none) */
  int *body;       /* body index                                               */
  uint64_t *gmask; /* group membership bits                                    */
} YfNodes;

typedef struct {
  int n, cap;
  int *v;          /* 3 node indices per triangle, counter-clockwise           */
  int *mat;        /* material index                                           */
  int *body;       /* body index                                               */
  int *id;         /* user/input id                                            */
  uint64_t *gmask; /* group membership bits                                    */
  /* derived at setup (model_prepare): */
  double *xinv;    /* 4 per triangle: inverse of the initial edge matrix X_e, row-major */
  double *d0;      /* twice the initial area [m^2]                             */
  /* written by the force stage: */
  double *s;       /* 3 per triangle: Cauchy stress sxx, syy, sxy [Pa]          */
  double *cf;      /* 6 per triangle: force on corners 0,1,2 (fx, fy) [N/m]     */
} YfTris;

/* A body: a connected piece of the scene made by one mesh command. */
typedef struct {
  char name[YF_NAME_MAX];
  int mat;         /* default material                                          */
  int fracture;    /* 1: own nodes per triangle + joints (joint.c)              */
  int group;       /* group index of the group named after the body             */
} YfBody;

typedef struct {
  char name[YF_NAME_MAX];
} YfGroup;

typedef struct {
  YfNodes node;
  YfTris tri;
  int nmat, nbody, ngroup;
  YfMaterial *mat;
  YfBody *body;
  YfGroup group[YF_MAX_GROUPS];
  /* node -> force slot gather (CSR), built by run_prepare for the nodes whose force this process
   * sums, gather_n0 .. gather_n1-1 (every node on one process; an MPI rank's own range): the force
   * of node i is the sum of slot[gather_slot[k]] for k in gather_off[i - gather_n0] ..
   * gather_off[i - gather_n0 + 1] - 1, in that fixed order, so any thread count gives the same
   * bits.  Slots 0..3*ntri-1 are triangle corners (tri.cf). */
  int *gather_off, *gather_slot;
  int gather_n0, gather_n1;
  /* Extra force slots beyond the triangle corners (joints register 4 per joint): slot
   * 3*ntri + k adds (xslot_f[2k], xslot_f[2k+1]) to node xslot_node[k]. */
  int nxslot;
  const int *xslot_node;
  double *xslot_f;
  int prepared;    /* model_prepare done for the current topology               */
  int stress_restored; /* tri.s was read from a restart: it holds the stresses of the restart's
                        * step (element stage), which the next run's first frame must show */
  /* partition (partition.c): set by the deck's `partition`, applied once at the first run.
   * Triangles of part p are part_tri[p]..part_tri[p+1]-1, and nodes are numbered in the order
   * their triangles are met, so each part's data is contiguous.  tri_new maps a triangle index of
   * before the renumbering (the order the deck made them in) to its current index (NULL: none). */
  int part_method;   /* 0 auto, 1 metis, 2 none                                      */
  int part_req;      /* parts asked for (0: default)                                  */
  int part_done;     /* the renumbering has been applied (it is never redone)        */
  int npart;         /* parts of the current order (1 when not partitioned)           */
  int *part_tri;     /* npart + 1 triangle offsets                                    */
  int *tri_new;      /* old triangle index -> current index, ntri_new entries          */
  int ntri_new;
} YfModel;

void model_init(YfModel *m);
void model_free(YfModel *m);
/* Room for exactly `nodes` more nodes and `tris` more triangles (no-op where there is room):
 * builders that know their counts call it first. */
void model_reserve(YfModel *m, int nodes, int tris);
/* Append a node / triangle; return its index.  Grows arrays geometrically. */
int model_add_node(YfModel *m, double x, double y, int id, int body);
int model_add_tri(YfModel *m, int n0, int n1, int n2, int mat, int id, int body);
/* A triangle as messages name it: "triangle ID (material M)", or "triangle ID of body B (material
 * M)" when the scene has several bodies and B is not M's name (Gmsh bodies keep their file's
 * element tags, so two bodies share ids).  Written into buf (n bytes); returns buf. */
const char *model_tri_label(const YfModel *m, int e, char *buf, size_t n);
int model_add_material(YfModel *m, const char *name); /* zeroed, jset = -1, volfac 0.5 */
int model_find_material(const YfModel *m, const char *name);  /* -1 if none */
/* Add material given->name from the constants a deck gives (material.c): rho, volfac, visc,
 * beta, pen_n, pen_t, fric, fric_law, and either E, nu with plane YF_PLANE_STRESS|STRAIN or
 * lambda, mu with plane YF_PLANE_LAME; derives the other pair (the rest of *given is copied,
 * jset excepted).  The name must be new.  Returns the material's index. */
void model_lame_moduli(YfMaterial *mt);
int model_define_material(YfModel *m, const YfMaterial *given);
int model_add_body(YfModel *m, const char *name, int mat);
int model_find_body(const YfModel *m, const char *name);
/* Group index by name, creating it when create != 0 (returns -1 when full or absent). */
int model_group(YfModel *m, const char *name, int create);
/* Twice the signed area of triangle t with current (cur=1) or initial positions. */
double model_tri_d(const YfModel *m, int t, int cur);

#endif
