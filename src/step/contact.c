/* contact.c: contact in the scene (see contact.h for the commands, the Y2D rules it follows and
 * the API read_y2d uses).
 *
 * This module owns the contact state of a simulation (YfContact): the rules of the deck, which
 * triangles take part and in which rule sides (two 64-bit masks per triangle), the couple list
 * with its (sparse) friction memory, the per-step triangle records of the screen and the forces
 * of the couples that touch.  The kernels are contact_search.c (broad phase) and contact_pair.c
 * (Y2D's potential contact and the screen).
 *
 * One step (contact_step):
 *   detection   travel += 2 dt max|v| over participating nodes; when due (or at the first step,
 *               or when the setup changed, or a joint broke in `joined skip` mode) a search over
 *               the participating triangles' discs gives a fresh sorted couple list; friction
 *               memory of persisting couples is merged in.
 *   records     each participating triangle's corners, edge normals and twice-area, once.
 *   screen      every live couple (A = larger index, as Y2D sums it): when every contactor edge
 *               of both directions has both ends outside one target edge line (98 % of the
 *               couples of a fracturing body), the couple gives no force and only its distance
 *               decides whether it stays; the others are marked (parallel over fixed blocks).
 *   kernel      the marked couples run the full kernel and write their 12 forces into a compact
 *               list in couple order (offsets from per-block counts: no atomics); a couple that
 *               touched in neither direction and is farther than 2 buffer is dropped (Y2D).
 *   scatter     each node's contact force is the sum of its couples' forces in couple order,
 *               added to node.fx/fy, so 1 or N threads give the same bits (one thread adds
 *               them during the kernel pass instead, in the same order: no list).  Energy: penalty
 *               energy (kernel estimate) of this step and accumulated frictional dissipation,
 *               summed per block in order.
 * Dropped couples stay in the list as dead entries until a search, or until a quarter of the
 * list is dead, when the list is compacted.  Memory per couple: 8 B indices, 4 B friction slot,
 * 1 B state; 96 B of friction memory only for couples that have touched (the six springs' s and
 * their forces of the last step, YF_PAIR_NG).
 * Friction energy (the Coulomb law): what its springs do not store is dissipated.  Each touching
 * couple gives the centred work of its springs' forces (YfContactInfo.work_c, the work the
 * integrator books into the motion) and the energy they hold after the step; the dissipation of
 * a step is the work less the change of the springs' total energy (espring: that of the last
 * step), so a spring that lets go (apart, screened, dropped, forgotten) is dissipated too, and
 * the balance sees the springs' work, not their energy estimate.  Y2D's law is booked the same
 * way (its spring 0.5 F_t^2 / p_t, its force's work where the force acts: contact_pair.c).
 *
 * Units: SI, 2D per unit thickness: forces N/m, penalties Pa, energies J/m.
 */
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "contact.h"
#include "contact_pair.h"
#include "contact_search.h"
#include "err.h"
#include "joint.h"
#include "par.h"
#include "parfor.h"
#include "stage_time.h"

#define MAX_RULES YF_CONTACT_MAX_RULES
#define PAIR_BLK 1024      /* couples per block of the force loop: fixed, so sums do not depend on threads */
#define PAR_MIN_DEF 2048   /* fewer couples than this: one thread (a parallel region costs microseconds) */
#define BUFFER_FRAC 0.3    /* auto buffer = 0.3 x smallest edge (Y2D reference decks' DIEZON)  */

typedef struct {
  int ga, gb;   /* group indices of the two sides (-1: every triangle)  */
  int native;   /* 1: from a deck command (pen_n required), 0: Y2D API    */
  YfLoc loc;    /* where it was given (file name owned)                   */
} Rule;

typedef struct {
  double pmax;  /* largest pen_n among the side's participating triangles [Pa] */
  int any;      /* the side holds a participating triangle                    */
} Side;

typedef struct YfContact {
  /* settings from the deck / API */
  int nrule;
  Rule rule[MAX_RULES];
  int buffer_auto;
  double buffer_set;     /* [m] when not auto                                   */
  int joined_skip, surface_all, search_every, keep_shared;
  unsigned char *uflag;  /* participation flags of the API (NULL: none given)   */
  int nuflag;
  int par_min;
  int dirty;             /* settings changed since the last prepare             */

  /* prepared for the current topology */
  int prep_ntri, prep_nn;
  double buffer;         /* [m]                                                 */
  int nitem, *item;      /* participating triangles, increasing                 */
  uint64_t *ma, *mb;     /* rule sides per triangle                             */
  int npn, *pnode;       /* nodes of participating triangles, increasing        */
  double *cx, *cy, *cr;  /* per item: centroid and radius [m] (MPI, search by boxes: per item of
                            the rank's own, from its first, search_ranks)     */
  int cap_bounds;        /* room in cx, cy, cr                                   */
  int nmat;
  double *mpn, *mpt, *mmu; /* per material: pen_n, pen_t [Pa], friction         */
  int impact_warned;       /* contact_check_impact said it once                    */
  double first_travel;     /* >= 0: the next setup's travel counter, no forced search */
  int *mlaw;               /* per material: friction law YF_FRIC_* (contact_pair.h) */
  int joined_on;         /* joined skip mode with joints                                        */
  int *jpart, *jidx;     /* joined skip: 3 per triangle jlo..jhi-1 (the lower triangles a search
                            keeps couples of: every triangle on one process, a rank's own on
                            ranks), partner triangle and joint (-1 none)                        */
  int jlo, jhi;
  const unsigned char *jstate;

  /* couples */
  YfPairs pairs, fresh;
  unsigned char *alive;  /* per couple: 0 dropped, 1 live (the screen marks 2: needs the kernel) */
  int cap_alive;
  int nlive, ndead;
  double *tg;            /* per triangle: the screen's record of this step (YF_TRI_GEOM) */
  int cap_tg;
  double *blk_e, *blk_d, *blk_s; /* per block: contact energy, friction dissipation, spring energy */
  double espring;        /* energy held by the Coulomb springs after the last step [J/m]      */
  int *blk_rm, *blk_busy, *blk_off, *blk_need, *blk_goff, cap_blk;
  /* forces of the couples that touched this step, in couple order: couple hk[h], 12 numbers
   * hf[12 h ..] (A's corners, then B's) [N/m]; room for cap_hit */
  int *hk, cap_hit, max_busy;
  /* nodes that received contact force at the last step (fcn nonzero only there) */
  unsigned char *tmark;  /* per node: 1 when fcn holds a contact force of the last step */
  /* MPI (halo mode): the owned nodes whose tmark is set, ntl of them (cap_tl), listed during run
   * tl_run (par_run_id); ntl < 0: not known (after a restart is read or a one-process step) */
  int *tlist, ntl, cap_tl, tl_run;
  double *hf;
  double *fcn;           /* per node: contact force of the last step [N/m]      */
  double *gdense;        /* restart: the friction memory, YF_PAIR_NG per couple (copy) */
  int cap_nodes;
  int fcn_valid;
  int tmarked;           /* 0: no tmark is set (the one-thread path then skips its passes over every node) */

  YfSearchWork work;
  YfSearchTrigger trig;
  long nsearch;
  long broken_seen;
  int force_search;
  int ghost_run;         /* MPI: par_run_id() when this rank's contact ghosts were set       */
  int lay_id;            /* MPI: par_layout_id() of the triangle ranges the list is laid by  */
  /* MPI (halo mode): the couple list holds this rank's couples only, the one-rank list's range
   * DS.lo[rank] .. DS.lo[rank + 1] - 1 (friction slots numbered on this rank); nlive and ndead
   * still count the whole list.  wij, walive, gdense: the whole list gathered for a restart
   * on the writer rank (contact_par_whole), wn couples (0 elsewhere), current while wfresh. */
  int local;
  int *wij, wn, wfresh;
  unsigned char *walive;
} YfContact;


/* ---------------------------------------------------------------- state */

static YfContact *get(YfSim *s) {
  if (!s->contact) {
    YfContact *C = yf_calloc(1, sizeof *C, "contact state");
    C->buffer_auto = 1;
    C->par_min = PAR_MIN_DEF;
    C->first_travel = -1.0;
    contact_pairs_init(&C->pairs);
    contact_pairs_init(&C->fresh);
    contact_search_work_init(&C->work);
    s->contact = C;
  }
  return s->contact;
}

static void free_prepared(YfContact *C) {
  free(C->item); free(C->ma); free(C->mb); free(C->pnode);
  free(C->cx); free(C->cy); free(C->cr);
  free(C->mpn); free(C->mpt); free(C->mmu); free(C->mlaw);
  free(C->jpart); free(C->jidx);
  C->item = C->pnode = C->jpart = C->jidx = NULL;
  C->joined_on = 0;
  C->ma = C->mb = NULL;
  C->cx = C->cy = C->cr = C->mpn = C->mpt = C->mmu = NULL;
  C->mlaw = NULL;
  C->nitem = C->npn = C->nmat = 0;
  C->prep_ntri = C->prep_nn = -1;
}

void contact_free(YfSim *s) {
  YfContact *C = s->contact;
  if (!C) return;
  free_prepared(C);
  for (int r = 0; r < C->nrule; r++) free((char *)C->rule[r].loc.file);
  free(C->uflag);
  contact_pairs_free(&C->pairs);
  contact_pairs_free(&C->fresh);
  free(C->alive); free(C->tg);
  free(C->blk_e); free(C->blk_d); free(C->blk_s); free(C->blk_rm); free(C->blk_busy); free(C->blk_off);
  free(C->blk_need); free(C->blk_goff); free(C->gdense); free(C->wij); free(C->walive);
  free(C->hk); free(C->hf);
  free(C->tmark); free(C->fcn); free(C->tlist);
  contact_search_work_free(&C->work);
  free(C);
  s->contact = NULL;
}

/* The contact share of a node's row sum, in units of one edge's flat-penetration stiffness: 2 for
 * a node pressed against one equal node (the two-mass bound), x3 for the neighbours a node of a
 * fracturing body or a body's corner is pressed into at once (docs/STABILITY.md: with 2 the
 * jointed scenes in contact were unstable at 0.75-0.78 of the limit). */
#define CONTACT_ROW 6.0

static int active(const YfContact *C) { return C && C->nrule > 0; }

static Rule *add_rule(YfContact *C, int ga, int gb, int native, const YfLoc *loc) {
  for (int r = 0; r < C->nrule; r++) {
    Rule *q = &C->rule[r];
    if ((q->ga == ga && q->gb == gb) || (q->ga == gb && q->gb == ga)) return q; /* same rule again */
  }
  if (C->nrule >= MAX_RULES) {
    yf_deck_error(loc, "contact: at most %d contact rules", MAX_RULES);
  }
  Rule *q = &C->rule[C->nrule++];
  q->ga = ga;
  q->gb = gb;
  q->native = native;
  q->loc.file = loc && loc->file ? yf_strdup(loc->file) : NULL;
  q->loc.line = loc ? loc->line : 0;
  C->dirty = 1;
  return q;
}

/* ---------------------------------------------------------------- API */

void contact_enable_all(YfSim *s, double buffer) {
  YfContact *C = get(s);
  YF_ASSERT(buffer >= 0.0);
  add_rule(C, -1, -1, 0, NULL);
  C->buffer_auto = 0;
  C->buffer_set = buffer;
  C->keep_shared = 1;
  C->joined_skip = 0;
  C->search_every = 0;
  C->dirty = 1;
}

void contact_set_first_travel(YfSim *s, double d) {
  YF_ASSERT(d >= 0.0);
  get(s)->first_travel = d;
}

void contact_set_participation(YfSim *s, const unsigned char *tri_flag, int n) {
  YfContact *C = get(s);
  free(C->uflag);
  C->uflag = NULL;
  C->nuflag = 0;
  C->surface_all = 1;
  if (tri_flag) {
    C->uflag = yf_malloc((size_t)(n > 0 ? n : 1), "contact participation");
    memcpy(C->uflag, tri_flag, (size_t)n);
    C->nuflag = n;
  }
  C->dirty = 1;
}

void contact_set_keep_shared(YfSim *s, int keep) {
  YfContact *C = get(s);
  C->keep_shared = keep != 0;
  C->dirty = 1;
}

void contact_set_par_min(YfSim *s, int n) {
  YfContact *C = get(s);
  C->par_min = n < 0 ? 0 : n;
  if (C->work.par_min > C->par_min) C->work.par_min = C->par_min;
}

void contact_renumber_tris(YfSim *s, const int *tnew, int n) {
  YfContact *C = s->contact;
  if (!C) return;
  if (C->uflag) {
    unsigned char *u = yf_calloc((size_t)(n > C->nuflag ? n : C->nuflag) + 1, 1, "contact participation");
    for (int t = 0; t < n && t < C->nuflag; t++) u[tnew[t]] = C->uflag[t];
    for (int t = n; t < C->nuflag; t++) u[t] = C->uflag[t];
    free(C->uflag);
    C->uflag = u;
  }
  YF_ASSERT(C->pairs.n == 0); /* before the first search: no couple holds an index yet */
  C->dirty = 1;
}

const double *contact_node_forces(const YfSim *s) {
  const YfContact *C = s->contact;
  return active(C) && C->fcn ? C->fcn : NULL; /* zeros until the first contact step (contact_prepare) */
}

long contact_searches(const YfSim *s) { return s->contact ? s->contact->nsearch : 0; }
int contact_participants(const YfSim *s) { return active(s->contact) ? s->contact->nitem : 0; }
double contact_buffer(const YfSim *s) { return active(s->contact) ? s->contact->buffer : 0.0; }
long contact_pairs(const YfSim *s) { return active(s->contact) ? s->contact->nlive : 0; }
static int ntotal(const YfContact *C);
void contact_held(const YfSim *s, long *mine, long *whole) {
  const YfContact *C = s->contact;
  *mine = active(C) ? C->pairs.n : 0;
  *whole = active(C) ? ntotal(C) : 0;
}

int contact_export(const YfSim *s, YfContactExport *e) {
  const YfContact *C = s->contact;
  memset(e, 0, sizeof *e);
  if (!active(C)) return 0;
  const YfModel *m = &s->model;
  e->nrule = C->nrule;
  e->surface_all = C->surface_all;
  e->joined_skip = C->joined_skip;
  e->search_every = C->search_every;
  e->buffer = C->buffer;
  /* all pairs: a rule whose two sides hold every triangle (Y2D's only contact rule) */
  for (int r = 0; r < C->nrule && !e->all_pairs; r++) {
    int ok = 1;
    for (int t = 0; t < m->tri.n && ok; t++) {
      uint64_t g = m->tri.gmask[t];
      ok = (C->rule[r].ga < 0 || (g >> C->rule[r].ga & 1)) && (C->rule[r].gb < 0 || (g >> C->rule[r].gb & 1));
    }
    e->all_pairs = ok;
  }
  return 1;
}

/* ---------------------------------------------------------------- what the deck sets */

int contact_add_rule(YfSim *s, int g1, int g2, const YfLoc *loc) {
  YfContact *C = get(s);
  for (int r = 0; r < C->nrule; r++) {
    const Rule *q = &C->rule[r];
    if ((q->ga == g1 && q->gb == g2) || (q->ga == g2 && q->gb == g1)) return 0; /* same rule again */
  }
  if (C->nrule >= MAX_RULES) return -1;
  add_rule(C, g1, g2, 1, loc);
  return 0;
}

void contact_off(YfSim *s) {
  contact_free(s);
  s->energy.contact = 0.0;
}

void contact_set_option(YfSim *s, int key, double value) {
  YfContact *C = get(s);
  switch (key) {
  case YF_CONTACT_BUFFER:
    C->buffer_auto = value < 0;
    if (value >= 0) C->buffer_set = value;
    break;
  case YF_CONTACT_JOINED: C->joined_skip = (int)value; break;
  case YF_CONTACT_SURFACE: C->surface_all = (int)value; break;
  case YF_CONTACT_SEARCH: C->search_every = (int)value; break;
  }
  C->dirty = 1;
}

/* ---------------------------------------------------------------- setup */

/* Nodes on a free boundary of the node topology: an edge used by one triangle only. */
static unsigned char *boundary_nodes(const YfModel *m) {
  int nn = m->node.n, nt = m->tri.n;
  const int *v = m->tri.v;
  int *off = yf_calloc((size_t)nn + 1, sizeof(int), "contact topology");
  int *lst = yf_malloc((size_t)(3 * nt > 0 ? 3 * nt : 1) * sizeof(int), "contact topology");
  for (int k = 0; k < 3 * nt; k++) off[v[k] + 1]++;
  for (int i = 0; i < nn; i++) off[i + 1] += off[i];
  int *fill = yf_calloc((size_t)nn + 1, sizeof(int), "contact topology");
  for (int k = 0; k < 3 * nt; k++) lst[off[v[k]] + fill[v[k]]++] = k / 3;
  free(fill);
  unsigned char *bn = yf_calloc((size_t)nn + 1, 1, "contact boundary nodes");
  for (int t = 0; t < nt; t++)
    for (int c = 0; c < 3; c++) {
      int p = v[3 * t + c], q = v[3 * t + (c + 1) % 3], shared = 0;
      for (int u = off[p]; u < off[p + 1] && !shared; u++) {
        int o = lst[u];
        if (o == t) continue;
        shared = v[3 * o] == q || v[3 * o + 1] == q || v[3 * o + 2] == q;
      }
      if (!shared) bn[p] = bn[q] = 1;
    }
  free(off);
  free(lst);
  return bn;
}

static int joined_keep(int i, int j, void *ctx) { /* i: the lower triangle, in jlo..jhi-1 */
  const YfContact *C = ctx;
  const size_t q = 3 * (size_t)(i - C->jlo);
  for (int k = 0; k < 3; k++)
    if (C->jpart[q + k] == j && C->jstate[C->jidx[q + k]] == 0) return 0;
  return 1;
}

/* The joined partners of triangles lo..hi-1 (joined_keep; again when a re-cut moves a rank's). */
static void joined_build(const YfSim *s, YfContact *C, int lo, int hi) {
  const YfJoints *J = s->joints;
  const size_t n3 = 3 * (size_t)(hi > lo ? hi - lo : 1);
  free(C->jpart); free(C->jidx);
  C->jpart = yf_malloc(n3 * sizeof(int), "contact joined");
  C->jidx = yf_malloc(n3 * sizeof(int), "contact joined");
  for (size_t k = 0; k < n3; k++) C->jpart[k] = C->jidx[k] = -1;
  for (int j = 0; j < J->n; j++)
    for (int side = 0; side < 2; side++) {
      int t = J->tri[2 * j + side], o = J->tri[2 * j + 1 - side];
      if (t < lo || t >= hi) continue;
      int *p = C->jpart + 3 * (size_t)(t - lo);
      for (int k = 0; k < 3; k++)
        if (p[k] < 0) {
          p[k] = o;
          C->jidx[3 * (size_t)(t - lo) + k] = j;
          break;
        }
    }
  C->jlo = lo;
  C->jhi = hi;
}

/* The contact penalty's share of the nodes' stiffness for the stable time step (contact.h). */
int contact_node_stiffness(YfSim *s, double *K, int *tof, double *pof) {
  const YfContact *C = s->contact;
  if (!active(C) || !C->ma) return 0;
  const YfModel *m = &s->model;
  Side A[MAX_RULES], B[MAX_RULES];
  for (int r = 0; r < C->nrule; r++) A[r] = B[r] = (Side){0.0, 0};
  for (int k = 0; k < C->nitem; k++) {
    int t = C->item[k];
    double p = C->mpn[m->tri.mat[t]];
    for (int r = 0; r < C->nrule; r++)
      for (int side = 0; side < 2; side++) {
        uint64_t mk = side ? C->mb[t] : C->ma[t];
        if (!(mk >> r & 1)) continue;
        Side *q = side ? &B[r] : &A[r];
        if (p > q->pmax) q->pmax = p;
        q->any = 1;
      }
  }
  unsigned char *jointed = yf_calloc((size_t)m->tri.n + 1, 1, "contact jointed");
  const YfJoints *J = s->joints;
  for (int j = 0; J && j < J->n; j++) jointed[J->tri[2 * j]] = jointed[J->tri[2 * j + 1]] = 1;
  int any = 0;
  double *kmax = yf_calloc((size_t)m->node.n + 1, sizeof(double), "contact stiffness");
  for (int k = 0; k < C->nitem; k++) {
    int t = C->item[k], b = m->tri.body[t];
    int meets = jointed[t] || m->body[b].fracture;
    double pm = 0.0;
    for (int r = 0; r < C->nrule; r++) {
      /* a rule whose other side holds any triangle: another body's, or this body's own (contact
       * self of a body that folds onto itself: a U whose arms close met its own contact penalty at
       * 9 x the limit of its triangles, which alone set the step) */
      if (C->ma[t] >> r & 1) {
        if (B[r].pmax > pm) pm = B[r].pmax;
        if (B[r].any) meets = 1;
      }
      if (C->mb[t] >> r & 1) {
        if (A[r].pmax > pm) pm = A[r].pmax;
        if (A[r].any) meets = 1;
      }
    }
    double p = C->mpn[m->tri.mat[t]];
    if (pm < p) p = pm;
    if (!meets || !(p > 0)) continue;
    const int *v = m->tri.v + 3 * t;
    double L2 = 0;
    for (int c = 0; c < 3; c++) {
      double dx = m->node.x0[v[(c + 1) % 3]] - m->node.x0[v[c]], dy = m->node.y0[v[(c + 1) % 3]] - m->node.y0[v[c]];
      if (dx * dx + dy * dy > L2) L2 = dx * dx + dy * dy;
    }
    double area = 0.5 * m->tri.d0[t];
    if (!(area > 0)) continue;
    /* 1.5 p L / h with h = 2 A / L, times CONTACT_ROW (contact.h) */
    double kn = CONTACT_ROW * 0.75 * p * L2 / area;
    for (int c = 0; c < 3; c++) {
      int i = v[c];
      if (kn > kmax[i]) { kmax[i] = kn; tof[i] = t; pof[i] = p; }
      K[i] += kn;
    }
    any = 1;
  }
  free(jointed);
  free(kmax);
  return any;
}

static int first_at_least(const int *v, int n, int x);
/* ranks: in a run whose update is divided (MPI), where a rank's velocities are current for its own
 * nodes only: each rank takes the spread over its own participating nodes and the ranks' extremes
 * are agreed (a collective every rank calls at the same search; minima and maxima are exact, so
 * the warning and its numbers are one rank's).  Without it the warning of speeds gained in a run
 * was never given on MPI ranks (a sweep of new decks, 2026-11-29). */
static void check_impact(YfSim *s, const YfLoc *loc, int ranks) {
  YfContact *C = s->contact;
  if (!active(C) || !C->nitem || C->impact_warned) return;
  const YfModel *m = &s->model;
  /* the most two participating nodes can close at: the spread of their velocities (a body, or
   * two, moving as one closes at nothing) */
  double vx0 = INFINITY, vx1 = -INFINITY, vy0 = INFINITY, vy1 = -INFINITY, rho = 0.0, pen = INFINITY;
  int tw = -1;
  for (int k = 0; k < C->nitem; k++) {
    const int t = C->item[k], *v = m->tri.v + 3 * t;
    if (!ranks)
      for (int c = 0; c < 3; c++) {
        vx0 = fmin(vx0, m->node.vx[v[c]]), vx1 = fmax(vx1, m->node.vx[v[c]]);
        vy0 = fmin(vy0, m->node.vy[v[c]]), vy1 = fmax(vy1, m->node.vy[v[c]]);
      }
    const double r = m->mat[m->tri.mat[t]].rho;
    if (r > rho) rho = r, tw = t;
    pen = fmin(pen, C->mpn[m->tri.mat[t]]);
  }
  if (ranks) { /* the participating nodes (C->pnode: the items' corners, increasing) this rank owns */
    int n0 = 0, n1 = m->node.n;
    par_update_nodes(&n0, &n1, NULL, NULL);
    const int a = first_at_least(C->pnode, C->npn, n0), b = first_at_least(C->pnode, C->npn, n1);
    for (int q = a; q < b; q++) {
      const int i = C->pnode[q];
      vx0 = fmin(vx0, m->node.vx[i]), vx1 = fmax(vx1, m->node.vx[i]);
      vy0 = fmin(vy0, m->node.vy[i]), vy1 = fmax(vy1, m->node.vy[i]);
    }
    vx0 = -par_max(-vx0), vx1 = par_max(vx1), vy0 = -par_max(-vy0), vy1 = par_max(vy1);
  }
  const double vrel = hypot(vx1 - vx0, vy1 - vy0), worst = rho * vrel * vrel;
  if (tw < 0 || !(worst > pen) || !(pen > 0)) return;
  C->impact_warned = 1;
  char when[64] = "";
  if (s->run_end_step > 0 && s->step > 0) snprintf(when, sizeof when, " (at step %ld)", s->step);
  yf_warn(loc ? loc : &C->rule[0].loc,
          "contact%s: an impact can press up to rho v^2 = %.3g Pa (material %s, bodies closing at up to %.3g m/s), above "
          "the contact penalty pen_n = %.3g Pa: the penalty cannot stop such a body within a triangle's depth, and it "
          "can pass through another (tunnelling); give pen_n above rho v^2 (it lowers the stable step), or 'contact "
          "surface all'", when, worst, m->mat[m->tri.mat[tw]].name, vrel, pen);
}

void contact_check_impact(YfSim *s, const YfLoc *loc) { check_impact(s, loc, 0); }

void contact_check_impact_run(YfSim *s) { check_impact(s, NULL, par_divided()); }

/* Room for the discs (centroid, radius) of n items in C->cx, cy, cr; they exist once prepared
 * (contact_has_state).  Ranks searching by bounding boxes hold their own items' only, which
 * change at a re-cut: a margin keeps a rank from allocating again at every search. */
static void bounds_room(YfContact *C, int n) {
  if (C->cap_bounds >= n) return;
  int cap = par_size() == 1 ? n : n + n / 8 + 256;
  free(C->cx); free(C->cy); free(C->cr);
  C->cx = yf_malloc((size_t)(cap + 1) * sizeof(double), "contact bounds");
  C->cy = yf_malloc((size_t)(cap + 1) * sizeof(double), "contact bounds");
  C->cr = yf_malloc((size_t)(cap + 1) * sizeof(double), "contact bounds");
  C->cap_bounds = cap;
}

/* Room for n triangle records of the screen (YF_TRI_GEOM doubles each; their contents are made
 * again at every step).  MPI ranks keep those of their couples' triangles only, which change at
 * a search: a margin keeps a rank from allocating again at every search. */
static void tg_room(YfContact *C, int n) {
  if (C->cap_tg >= n) return;
  int cap = par_size() == 1 ? n : n + n / 4 + 256;
  free(C->tg);
  C->tg = yf_malloc((size_t)(cap > 0 ? cap : 1) * YF_TRI_GEOM * sizeof(double), "contact triangle records");
  C->cap_tg = cap;
}

void contact_prepare(YfSim *s) {
  YfContact *C = s->contact;
  if (!active(C)) return;
  YfModel *m = &s->model;
  int nt = m->tri.n, nn = m->node.n;
  if (!C->dirty && C->prep_ntri == nt && C->prep_nn == nn && C->nmat == m->nmat) return;
  free_prepared(C);

  /* rule sides per triangle */
  C->ma = yf_calloc((size_t)nt + 1, sizeof(uint64_t), "contact masks");
  C->mb = yf_calloc((size_t)nt + 1, sizeof(uint64_t), "contact masks");
  for (int r = 0; r < C->nrule; r++) {
    const Rule *q = &C->rule[r];
    uint64_t bit = (uint64_t)1 << r;
    for (int t = 0; t < nt; t++) {
      uint64_t g = m->tri.gmask[t];
      if (q->ga < 0 || (g >> q->ga & 1)) C->ma[t] |= bit;
      if (q->gb < 0 || (g >> q->gb & 1)) C->mb[t] |= bit;
    }
  }

  /* participation */
  unsigned char *bn = (!C->surface_all && !C->uflag) ? boundary_nodes(m) : NULL;
  C->item = yf_malloc((size_t)(nt > 0 ? nt : 1) * sizeof(int), "contact items");
  C->nitem = 0;
  for (int t = 0; t < nt; t++) {
    if (!(C->ma[t] | C->mb[t])) continue;
    int in;
    if (C->uflag) in = t < C->nuflag && C->uflag[t];
    else if (bn) in = bn[m->tri.v[3 * t]] || bn[m->tri.v[3 * t + 1]] || bn[m->tri.v[3 * t + 2]];
    else in = 1;
    if (in) C->item[C->nitem++] = t;
    else C->ma[t] = C->mb[t] = 0; /* not a candidate of any couple */
  }
  free(bn);

  /* materials: penalties and friction; a deck rule needs pen_n */
  C->nmat = m->nmat;
  C->mpn = yf_malloc((size_t)(m->nmat + 1) * sizeof(double), "contact materials");
  C->mpt = yf_malloc((size_t)(m->nmat + 1) * sizeof(double), "contact materials");
  C->mmu = yf_malloc((size_t)(m->nmat + 1) * sizeof(double), "contact materials");
  C->mlaw = yf_malloc((size_t)(m->nmat + 1) * sizeof(int), "contact materials");
  for (int i = 0; i < m->nmat; i++) {
    C->mpn[i] = m->mat[i].pen_n;
    C->mpt[i] = m->mat[i].pen_t;
    C->mmu[i] = m->mat[i].fric;
    C->mlaw[i] = m->mat[i].fric_law;
  }
  for (int k = 0; k < C->nitem; k++) {
    int t = C->item[k];
    const YfMaterial *mt = &m->mat[m->tri.mat[t]];
    if (mt->pen_n > 0 || mt->pen_n_given) continue; /* pen_n 0 written out: no force, meant */
    for (int r = 0; r < C->nrule; r++)
      if (C->rule[r].native && ((C->ma[t] | C->mb[t]) >> r & 1))
        yf_deck_error(C->rule[r].loc.file ? &C->rule[r].loc : NULL,
                      "contact: material '%s' (triangle %d) has no normal contact penalty: add 'pen_n P' [Pa] "
                      "(typically 1-10 x E) to its material command", mt->name, m->tri.id[t]);
  }

  /* participating nodes (increasing) and the auto buffer */
  unsigned char *mark = yf_calloc((size_t)nn + 1, 1, "contact nodes");
  double hmin = INFINITY;
  for (int k = 0; k < C->nitem; k++) {
    const int *v = m->tri.v + 3 * C->item[k];
    for (int c = 0; c < 3; c++) {
      mark[v[c]] = 1;
      int p = v[c], q = v[(c + 1) % 3];
      double L = hypot(m->node.x0[q] - m->node.x0[p], m->node.y0[q] - m->node.y0[p]);
      if (L < hmin) hmin = L;
    }
  }
  C->npn = 0;
  for (int i = 0; i < nn; i++) C->npn += mark[i];
  C->pnode = yf_malloc((size_t)(C->npn > 0 ? C->npn : 1) * sizeof(int), "contact nodes");
  C->npn = 0;
  for (int i = 0; i < nn; i++)
    if (mark[i]) C->pnode[C->npn++] = i;
  free(mark);
  C->buffer = C->buffer_auto ? (isfinite(hmin) ? BUFFER_FRAC * hmin : 0.0) : C->buffer_set;

  /* joined couples (skip mode) */
  if (C->joined_skip && s->joints && s->joints->n) {
    /* one process: every triangle's partners, made here; MPI: at the search, for the lower
     * triangles it keeps couples of */
    C->joined_on = 1;
    if (par_size() == 1) joined_build(s, C, 0, nt);
    C->jstate = s->joints->state;
    C->broken_seen = joints_broken(s);
  }

  /* one process: a disc for every item, made here (no allocation in the step); MPI: at the
   * first search, for every item (replicated update) or the rank's own (search_ranks) */
  C->cap_bounds = -1;
  bounds_room(C, par_size() == 1 ? C->nitem : 0);
  if (C->cap_nodes < nn) {
    C->tmark = yf_realloc(C->tmark, (size_t)nn, "contact gather");
    C->fcn = yf_realloc(C->fcn, (size_t)2 * nn * sizeof(double), "contact node forces");
    C->cap_nodes = nn;
  }
  memset(C->tmark, 0, (size_t)nn);
  C->ntl = -1;
  memset(C->fcn, 0, (size_t)2 * nn * sizeof(double));
  C->fcn_valid = 0;
  /* the triangle records (128 B per triangle) are sized at the first step that has a couple
   * (contact_step: a step that searched, which allocates anyway): a rule between bodies that never
   * come near holds none (two 400-triangle bodies: heap peak 357 -> 255 KB); MPI: also when it is
   * known whether a rank keeps the records of its couples' triangles only */

  /* the first step after a (re)setup searches; couples of the old list that still pass keep
   * their friction memory through the merge (triangle indices do not change) */
  contact_trigger_init(&C->trig, C->buffer, C->first_travel >= 0 ? C->first_travel : 1e15);
  C->force_search = !(C->first_travel >= 0);
  C->first_travel = -1.0;
  C->prep_ntri = nt;
  C->prep_nn = nn;
  C->dirty = 0;
  sim_printf(s, "contact: %d rule%s, %d of %d triangles take part, buffer %.4g m%s\n", C->nrule,
             C->nrule > 1 ? "s" : "", C->nitem, nt, C->buffer, C->joined_skip ? ", joined couples skipped" : "");
}


/* ---------------------------------------------------------------- detection */

/* Room for the per-couple arrays of n couples, and for the blocks of a list of ntot (MPI: the
 * one-rank list, whose blocks every rank sums). */
static void couple_arrays(YfContact *C, int n, int ntot) {
  if (C->cap_alive < n || !C->alive) { /* (MPI: a rank may hold no couple; the array exists) */
    C->cap_alive = n + n / 4 + 64;
    C->alive = yf_realloc(C->alive, (size_t)C->cap_alive, "contact couples");
  }
  int nblk = (ntot + PAIR_BLK - 1) / PAIR_BLK;
  if (C->cap_blk < nblk + 1) {
    C->cap_blk = nblk + nblk / 4 + 16;
    C->blk_e = yf_realloc(C->blk_e, (size_t)C->cap_blk * sizeof(double), "contact blocks");
    C->blk_d = yf_realloc(C->blk_d, (size_t)C->cap_blk * sizeof(double), "contact blocks");
    C->blk_s = yf_realloc(C->blk_s, (size_t)C->cap_blk * sizeof(double), "contact blocks");
    C->blk_rm = yf_realloc(C->blk_rm, (size_t)C->cap_blk * sizeof(int), "contact blocks");
    C->blk_busy = yf_realloc(C->blk_busy, (size_t)C->cap_blk * sizeof(int), "contact blocks");
    C->blk_off = yf_realloc(C->blk_off, (size_t)(C->cap_blk + 1) * sizeof(int), "contact blocks");
    C->blk_need = yf_realloc(C->blk_need, (size_t)C->cap_blk * sizeof(int), "contact blocks");
    C->blk_goff = yf_realloc(C->blk_goff, (size_t)(C->cap_blk + 1) * sizeof(int), "contact blocks");
  }
}

/* Room for the forces of n touching couples.  Made at each search for twice the most couples
 * that have needed the kernel in one step so far (at least 1/16 of the list), so a step grows
 * it only when contact spreads past that (rarely, geometrically). */
static void hit_room(YfContact *C, int n) {
  if (C->cap_hit >= n) return;
  C->cap_hit = n + n / 2 + 64;
  free(C->hk);
  free(C->hf);
  C->hk = yf_malloc((size_t)C->cap_hit * sizeof(int), "contact hits");
  C->hf = yf_malloc((size_t)C->cap_hit * 12 * sizeof(double), "contact hits");
}

/* The first k in [0, n] with v[k] >= x (v increasing). */
static int first_at_least(const int *v, int n, int x) {
  int a = 0, b = n;
  while (a < b) {
    int c = a + (b - a) / 2;
    if (v[c] < x) a = c + 1;
    else b = c;
  }
  return a;
}

static void search_ranks(YfSim *s, YfContact *C, const YfSearchFilter *f);
static int set_ranges(int n);
static void search(YfSim *s, YfContact *C) {
  const YfModel *m = &s->model;
  /* couples dropped since the last search are forgotten (their friction memory too) */
  if (C->ndead) contact_pairs_compact(&C->pairs, C->alive);
  YfSearchFilter f = {0};
  f.mask = C->ma;
  f.mask2 = C->mb;
  f.tri_v = C->keep_shared ? NULL : m->tri.v;
  /* MPI, couples laid out by ranks: a rank finds only the couples whose lower triangle it owns
   * (it evaluates those), the others' partners serving as upper triangles only */
  const int *tlo = par_tri_lo();
  if (tlo && (C->local || par_divided())) {
    f.lower_lo = tlo[par_rank()];
    f.lower_hi = tlo[par_rank() + 1];
  }
  if (C->joined_on) {
    const int lo = f.lower_hi > f.lower_lo ? f.lower_lo : 0, hi = f.lower_hi > f.lower_lo ? f.lower_hi : m->tri.n;
    if (!C->jpart || C->jlo != lo || C->jhi != hi) joined_build(s, C, lo, hi);
    f.keep = joined_keep;
    f.ctx = C;
  }
  if (par_divided()) { /* MPI: each rank its own triangles against its neighbours' (below) */
    search_ranks(s, C, &f);
  } else {
    bounds_room(C, C->nitem);
    contact_search_bounds(C->nitem, C->item, m->tri.v, m->node.x, m->node.y, C->cx, C->cy, C->cr);
    contact_search(&C->work, C->nitem, C->item, C->cx, C->cy, C->cr, C->buffer, &f, &C->fresh);
  }
  contact_search_merge(&C->pairs, &C->fresh);
  YfPairs tmp = C->pairs;
  C->pairs = C->fresh;
  C->fresh = tmp;
  int n = C->pairs.n, ntot = C->local ? set_ranges(n) : n;
  couple_arrays(C, n, ntot);
  memset(C->alive, 1, (size_t)n);
  C->nlive = ntot;
  C->ndead = 0;
  int want = 2 * C->max_busy, floor16 = n / 16;
  hit_room(C, want > floor16 ? want : floor16);
  /* friction memory slots: room for the couples that have touched and as many again */
  contact_pairs_greserve(&C->pairs, 2 * C->pairs.ng + n / 64 + 256);
  C->nsearch++;
}

/* ---------------------------------------------------------------- the step */

/* What pass 2 of contact_step reads and where it puts the forces: the hit list (hf, hk: several
 * threads) or the node sums directly (fcn, tmark: one thread, blocks in order). */
typedef struct {
  const int *ij, *tv, *tmat;
  int *gi;
  unsigned char *alive;
  const double *vx, *vy, *tg;
  const int *tmap; /* MPI, divided update: a triangle's record in tg (NULL: tg by triangle) */
  double *gmem;
  const double *mpn, *mpt, *mmu;
  const int *mlaw;
  double dt, rem2;
  int np;
  double *hf;
  int *hk;
  double *fcn;
  unsigned char *tmark;
} KernelPass;

/* The kernel on the marked couples of block b, in couple order: friction slots numbered from the
 * block's offset, energy and dissipation summed per block, couples dropped as Y2D drops them. */
/* The kernel on the marked couples ka..kb-1, hits numbered from h, new friction slots from slot;
 * contact energy, friction dissipation before the springs' release and spring energy summed in
 * couple order into sum[0..NSUM-1] (and, when ed is not NULL, each touching couple's NSUM values
 * written to ed in order: the pieces of a block shared by two ranks).  A couple's
 * dissipation is its centred work less its springs' energy now (the caller adds that of the last
 * step, espring), whatever the law. */
enum { NSUM = 3 };
static void kernel_run(const KernelPass *P, int ka, int kb, int h, int slot, double *sum, int *rmo, double *ed) {
  double e = 0.0, d = 0.0, sp = 0.0;
  int rm = 0;
  const int *ij = P->ij, *tv = P->tv, *tmat = P->tmat;
  int *gi = P->gi;
  unsigned char *alive = P->alive;
  const double *vx = P->vx, *vy = P->vy, *tg = P->tg;
  double *gmem = P->gmem;
  for (int k = ka; k < kb; k++) {
    if (alive[k] != 2) continue;
    alive[k] = 1;
    int ti = ij[2 * k], tj = ij[2 * k + 1];
    const int *va = tv + 3 * tj, *vb = tv + 3 * ti;
    double vxa[3], vya[3], vxb[3], vyb[3];
    for (int c = 0; c < 3; c++) {
      vxa[c] = vx[va[c]]; vya[c] = vy[va[c]];
      vxb[c] = vx[vb[c]]; vyb[c] = vy[vb[c]];
    }
    int ma = tmat[tj], mb = tmat[ti];
    double pn = P->mpn[ma] < P->mpn[mb] ? P->mpn[ma] : P->mpn[mb];
    double pt = P->mpt[ma] < P->mpt[mb] ? P->mpt[ma] : P->mpt[mb];
    double mu = P->mmu[ma] < P->mmu[mb] ? P->mmu[ma] : P->mmu[mb];
    int law = P->mlaw[ma] < P->mlaw[mb] ? P->mlaw[ma] : P->mlaw[mb]; /* Y2D's if either is a Y2D material */
    double loc[12];
    double *fa = P->hf ? P->hf + 12 * (size_t)h : loc, *fb = fa + 6;
    for (int c = 0; c < 12; c++) fa[c] = 0.0;
    YfContactInfo info = {0, 0, 0, 0, 0, 0, NULL, 0, 0};
    double d2;
    if (gi[k] < 0) { /* first contact of the couple: a zeroed slot, numbered in couple order */
      gi[k] = slot++;
      memset(gmem + YF_PAIR_NG * (size_t)gi[k], 0, YF_PAIR_NG * sizeof *gmem);
    }
    double *gk = gmem + YF_PAIR_NG * (size_t)gi[k];
    info.gprev = gk + 6;
    const int *tm = P->tmap;
    int hit = contact_pair_force_rec(tg + (size_t)YF_TRI_GEOM * (tm ? tm[tj] : tj), vxa, vya,
                                     tg + (size_t)YF_TRI_GEOM * (tm ? tm[ti] : ti), vxb,
                                     vyb, pn, pt, mu, law, P->dt, gk, fa, fb, &d2, &info);
    double dc = info.work_c - info.spring;
    e += info.energy;
    d += dc;
    sp += info.spring;
    if (ed) {
      *ed++ = info.energy;
      *ed++ = dc;
      *ed++ = info.spring;
    }
    if (P->hf) {
      P->hk[h] = k;
    } else { /* one thread: the scatter's additions, here (A's corners, then B's) */
      for (int c = 0; c < 6; c++) {
        int i = c < 3 ? va[c] : vb[c - 3];
        P->tmark[i] = 1;
        P->fcn[2 * i] += fa[2 * c];
        P->fcn[2 * i + 1] += fa[2 * c + 1];
      }
    }
    h++;
    if (!hit && d2 > P->rem2) { alive[k] = 0; rm++; }
  }
  sum[0] = e;
  sum[1] = d;
  sum[2] = sp;
  *rmo = rm;
}

static void kernel_block(YfContact *C, const KernelPass *P, int b) {
  int h = C->blk_off[b], rm = 0;
  if (h == C->blk_off[b + 1]) { C->blk_e[b] = C->blk_d[b] = C->blk_s[b] = 0.0; return; }
  int k1 = (b + 1) * PAIR_BLK < P->np ? (b + 1) * PAIR_BLK : P->np;
  double q[NSUM];
  kernel_run(P, b * PAIR_BLK, k1, h, C->blk_goff[b], q, &rm, NULL);
  C->blk_e[b] = q[0];
  C->blk_d[b] = q[1];
  C->blk_s[b] = q[2];
  C->blk_rm[b] += rm;
}

/* dropped couples (removed: of the whole list, every rank's): compact once a quarter of the list
 * is dead (MPI: of the one-rank list, so that every rank compacts its own couples at the step one
 * rank would, and the blocks of the energy sums hold the same couples) */
static void contact_compact(YfContact *C, int removed) {
  C->nlive -= removed;
  C->ndead += removed;
  if (C->ndead > 0 && 4 * (long)C->ndead > ntotal(C)) {
    contact_pairs_compact(&C->pairs, C->alive);
    memset(C->alive, 1, (size_t)C->pairs.n);
    C->ndead = 0;
    if (C->local) set_ranges(C->pairs.n);
  }
}

/* ---------------------------------------------------------------- the kernel on MPI ranks
 *
 * Couple k of the one-rank list belongs to the rank owning its lower triangle ij[2k]: the list
 * is sorted by it, so each rank's couples are one range of it, DS.lo[r] .. DS.lo[r + 1] - 1, in
 * rank order.  Each rank holds its own range only (C->local): its search keeps the couples whose
 * lower triangle it owns, merges them with its old ones (a couple's friction memory stays on its
 * owner, and goes with the couple when its lower triangle changes rank: a re-cut, or a scene
 * changed between runs, contact_rehome and lay_out), and the ranks' counts give
 * the ranges (4 B per rank, at each search and compaction).  Each rank screens and runs the kernel
 * on its couples only, numbering the friction slots of first contacts itself, then:
 *   - the per-block energy and dissipation (blocks of PAIR_BLK couples of the one-rank list) of
 *     blocks inside one rank's range come from that rank; a block two ranks share is summed from
 *     its touching couples' values in couple order (the owners send them): every block sum has
 *     the one-rank bits;
 *   - each rank's count of dropped couples goes to every rank, so the live and dead counts of the
 *     whole list, and with them the step at which each rank compacts its own, are one rank's;
 *   - each hit's forces on nodes another rank owns go to that rank (node, fx, fy), in couple
 *     order; the owner of a node adds its couples' contributions rank by rank, i.e. in couple
 *     order: the one-rank scatter's additions.
 * Only owned nodes get their contact force here (fcn of the other nodes is stale until
 * contact_par_gather).  The whole list is gathered only for a restart (contact_par_whole). */
typedef struct { double i, fx, fy; } Contrib; /* a hit's force on a node another rank owns */

static struct {
  void *ed, *send, *sum, *hof, *box, *cbx;
  size_t ced, csend, csum, chof, cbox, ccbx;
  int *lo, *rb, *sb;
  int nlo;
  unsigned char *tmk;    /* divided update: per triangle, scratch mark (all 0 between uses)  */
  int ntmk;
  int *rtri, nrtri, crtri; /* the triangles this rank's couples read (increasing)           */
  int *tloc;             /* per triangle: its place in rtri (only those of rtri are current) */
  int *rnode;            /* their corners                                                   */
  int *uitem, cu;        /* search on ranks: the triangles searched and their discs          */
  int *cst, ncst;        /* search on ranks: this rank's chunks' first items                 */
  double *ucx, *ucy, *ucr;
} DS;

static void ds_room(void **p, size_t *cap, size_t need) {
  if (need <= *cap) return;
  *cap = need + need / 2 + 1024;
  free(*p);
  *p = yf_malloc(*cap, "contact exchange");
}

/* A piece of block b inside couples [r0, r1): ka..kb-1; whole when it is the block. */
static int piece(int b, int r0, int r1, int np, int *ka, int *kb) {
  *ka = b * PAIR_BLK > r0 ? b * PAIR_BLK : r0;
  *kb = (b + 1) * PAIR_BLK < r1 ? (b + 1) * PAIR_BLK : r1;
  return *ka == b * PAIR_BLK && (*kb == (b + 1) * PAIR_BLK || *kb == np);
}

/* The corners of this rank's hits, in couple order (A's corners, then B's): mode 0 counts the
 * bytes for each owner of a node another rank owns (sb), 1 writes those contributions grouped by
 * owner (fl: next place per owner), 2 adds the contributions on owned nodes into fcn. */
typedef struct {
  const YfContact *C;
  const int *ij, *tv;
  int n0, n1, S;
  const int *nlo;
  int *sb, *fl;
  Contrib *cs;
  double *fcn;
  unsigned char *tmark;
  int *tl, *ntl; /* mode 2: the owned nodes marked, in the order first marked */
} HitWalk;

static void walk_hits(const HitWalk *w, int nh, int mode) {
  for (int h = 0; h < nh; h++) {
    int k = w->C->hk[h];
    const int *vv[2] = {w->tv + 3 * w->ij[2 * k + 1], w->tv + 3 * w->ij[2 * k]};
    const double *f = w->C->hf + 12 * (size_t)h;
    for (int c = 0; c < 6; c++) {
      int i = vv[c / 3][c % 3], own = i >= w->n0 && i < w->n1;
      if (mode == 2) {
        if (!own) continue;
        if (!w->tmark[i]) { w->tmark[i] = 1; w->tl[(*w->ntl)++] = i; }
        w->fcn[2 * i] += f[2 * c];
        w->fcn[2 * i + 1] += f[2 * c + 1];
        continue;
      }
      if (own) continue;
      int a = 0, z = w->S; /* owner: nlo[a] <= i < nlo[a + 1] */
      while (z - a > 1) {
        int m = (a + z) / 2;
        if (w->nlo[m] <= i) a = m;
        else z = m;
      }
      if (mode == 0) w->sb[a] += (int)sizeof(Contrib);
      else w->cs[w->fl[a]++] = (Contrib){(double)i, f[2 * c], f[2 * c + 1]};
    }
  }
}

/* MPI, divided update (par.h): the participating triangles of this rank's couples (both sides),
 * whose records its screen and kernel read, and their corners as this rank's contact ghosts; at
 * each search and at the start of each run. */
static void contact_ghosts(YfSim *s, YfContact *C) {
  const YfModel *m = &s->model;
  const int nt = m->tri.n, np = C->pairs.n, *ij = C->pairs.ij;
  if (DS.ntmk < nt) {
    free(DS.tmk); free(DS.tloc);
    DS.tmk = yf_calloc((size_t)nt, 1, "contact ghosts");
    DS.tloc = yf_malloc((size_t)nt * sizeof(int), "contact ghosts");
    DS.ntmk = nt;
  }
  YF_ASSERT(C->local); /* the divided update runs in halo mode: this rank's couples only */
  int nmk = 0;
  for (int k = 0; k < 2 * np; k++)
    if (!DS.tmk[ij[k]]) DS.tmk[ij[k]] = 1, nmk++;
  /* the triangles of this rank's couples, not every item (a margin: they change at each search) */
  if (DS.crtri < nmk + 1) {
    free(DS.rtri); free(DS.rnode);
    DS.crtri = nmk + nmk / 8 + 256;
    DS.rtri = yf_malloc((size_t)DS.crtri * sizeof(int), "contact ghosts");
    DS.rnode = yf_malloc(3 * (size_t)DS.crtri * sizeof(int), "contact ghosts");
  }
  int n = 0;
  for (int q = 0; q < C->nitem; q++) {
    int t = C->item[q];
    if (!DS.tmk[t]) continue;
    DS.tmk[t] = 0;
    DS.tloc[t] = n;
    DS.rtri[n] = t;
    for (int c = 0; c < 3; c++) DS.rnode[3 * n + c] = m->tri.v[3 * t + c];
    n++;
  }
  DS.nrtri = n;
  C->ghost_run = par_run_id();
  par_contact_ghosts(&s->model.node, DS.rnode, 3 * n);
}

/* MPI, divided update: the search on ranks, by bounding boxes.  Each rank computes the discs of
 * its own participating triangles (their corners are its own nodes or ghosts, current) and the
 * boxes that hold them, one per chunk of its triangles (below); the boxes go to every rank; each
 * rank sends a rank the discs of its triangles whose disc, grown by the buffer, reaches into one
 * of that rank's boxes (a couple's partner always does: |c_i - c_j| < r_i + r_j + buffer puts
 * c_j within r_j + buffer of i's disc, which lies in its chunk's box); then each rank searches
 * its own triangles with those it received and keeps the couples whose lower triangle it owns:
 * the ranks' lists, concatenated in rank order, are the one-rank list (sorted by lower triangle;
 * the search's test is made from the lower triangle's side on the same numbers), but no rank
 * receives the others'.  Boxes are made again at each search, so the exchange follows fragments
 * however far they fly.  No rank reads another rank's nodes.
 *
 * Chunks, not one box per rank: a rank's METIS parts are a contiguous range of part numbers,
 * which need not be one compact region, so one box per rank can hold most of another rank's
 * triangles (the beam deck at 1e6 on 2 ranks: rank 1 sent 401 717 of its 488 370 discs, and
 * each rank searched 0.9e6 discs for 0.5e6 of its own).  The partition numbers triangles part by
 * part, so a chunk of consecutive ones is a compact piece of the mesh with a tight box. */
typedef struct { double t, cx, cy, r; } Disc;
enum { CHUNK_MIN = 512, CHUNKS_MAX = 256, FAR_CUTS = 512 }; /* triangles per chunk, at least (but at a cut);
                                                              * chunks per rank by count, at most; far cuts */

/* How far disc k (of C->cx..) reaches beyond its radius: the buffer, with a margin for rounding. */
static double disc_pad(const YfContact *C, int k) {
  return (C->cr[k] + C->buffer) * (1.0 + 1e-6) + 1e-12 * (fabs(C->cx[k]) + fabs(C->cy[k]));
}

/* Box b (xmin, ymin, xmax, ymax) made empty; grown to hold the box (xmin, ymin, xmax, ymax). */
static void box_empty(double *b) {
  b[0] = b[1] = DBL_MAX;
  b[2] = b[3] = -DBL_MAX;
}
static void box_grow(double *b, double xmin, double ymin, double xmax, double ymax) {
  b[0] = fmin(b[0], xmin);
  b[1] = fmin(b[1], ymin);
  b[2] = fmax(b[2], xmax);
  b[3] = fmax(b[3], ymax);
}

/* Box a (xmin, ymin, xmax, ymax) grown by p overlaps box b (strictly). */
static int box_meets(const double *a, double p, const double *b) {
  return a[0] - p < b[2] && a[2] + p > b[0] && a[1] - p < b[3] && a[3] + p > b[1];
}

static void ds_ranks(void);
static void search_ranks(YfSim *s, YfContact *C, const YfSearchFilter *f) {
  const YfModel *m = &s->model;
  const int S = par_size(), me = par_rank(), *tlo = par_tri_lo();
  const int qa = first_at_least(C->item, C->nitem, tlo[me]), qb = first_at_least(C->item, C->nitem, tlo[me + 1]);
  const double buf = C->buffer;
  bounds_room(C, qb - qa); /* the discs of this rank's items only: C->cx[q - qa] is item q's */
  contact_search_bounds(qb - qa, C->item + qa, m->tri.v, m->node.x, m->node.y, C->cx, C->cy, C->cr);
  /* this rank's chunks: its items qa.. in order, cut every `per` items, at METIS part borders
   * (two parts need not be near each other) and where a disc lies beyond its chunk's box by more
   * than two of its diameters (a part's order can jump, a fragment can fly: at most FAR_CUTS such
   * cuts, so the count of boxes stays bounded).  cs[c]: chunk c's first item; mine: the boxes
   * (xmin, ymin, xmax, ymax); mpad[c]: chunk c's largest pad. */
  const int nown = qb - qa, per = nown / CHUNKS_MAX + 1 > CHUNK_MIN ? nown / CHUNKS_MAX + 1 : CHUNK_MIN;
  const int *pt = m->npart > 1 ? m->part_tri : NULL;
  const int cap = nown / per + 2 + (pt ? m->npart : 0) + FAR_CUTS;
  if (DS.ncst < cap + 1) {
    free(DS.cst);
    DS.ncst = cap + 1;
    DS.cst = yf_malloc((size_t)DS.ncst * sizeof(int), "contact search on ranks");
  }
  ds_room(&DS.cbx, &DS.ccbx, 5 * ((size_t)cap + 1) * sizeof(double));
  int *cs = DS.cst, nch = 0, nfar = 0, p = 0;
  double *mine = DS.cbx, *mpad = mine + 4 * ((size_t)cap + 1), *bc = NULL;
  for (int q = qa, k = 0; q < qb; q++, k++) {
    const double x = C->cx[q - qa], y = C->cy[q - qa], r = C->cr[q - qa], g = 4.0 * r;
    int cut = q == qa || k == per;
    while (pt && p < m->npart && C->item[q] >= pt[p + 1]) p++, cut = 1;
    if (!cut && nfar < FAR_CUTS && (x < bc[0] - g || x > bc[2] + g || y < bc[1] - g || y > bc[3] + g)) cut = 1, nfar++;
    if (cut) {
      YF_ASSERT(nch < cap);
      cs[nch] = q;
      bc = mine + 4 * nch;
      box_empty(bc);
      mpad[nch++] = 0.0;
      k = 0;
    }
    box_grow(bc, x - r, y - r, x + r, y + r);
    mpad[nch - 1] = fmax(mpad[nch - 1], disc_pad(C, q - qa));
  }
  cs[nch] = qb;
  ds_ranks();
  int *rb = DS.rb, *sb = DS.sb;
  const double *boxes = par_concat(mine, 4 * nch * (int)sizeof(double), rb);
  /* every rank's boxes (from bo[r] on), each rank's hull, and a list of one rank's boxes */
  int nbox = 0;
  for (int r = 0; r < S; r++) nbox += rb[r] / (4 * (int)sizeof(double));
  ds_room(&DS.box, &DS.cbox, (4 * (size_t)nbox + 4 * (size_t)S) * sizeof(double) + ((size_t)S + 1 + nbox) * sizeof(int));
  double *bx = DS.box, *hull = bx + 4 * (size_t)nbox;
  int *bo = (int *)(hull + 4 * (size_t)S), *near = bo + S + 1;
  memcpy(bx, boxes, 4 * (size_t)nbox * sizeof(double));
  bo[0] = 0;
  for (int r = 0; r < S; r++) {
    bo[r + 1] = bo[r] + rb[r] / (4 * (int)sizeof(double));
    double *h = hull + 4 * r;
    box_empty(h);
    for (int b = bo[r]; b < bo[r + 1]; b++) box_grow(h, bx[4 * b], bx[4 * b + 1], bx[4 * b + 2], bx[4 * b + 3]);
  }
  /* the discs each rank needs from this one, rank by rank in triangle order: pass 0 counts,
   * pass 1 writes.  A chunk grown by its largest pad holds every grown disc of it, so a rank
   * whose boxes it misses needs none of them. */
  size_t nsend = 0;
  Disc *o = NULL;
  for (int pass = 0; pass < 2; pass++) {
    if (pass) {
      ds_room(&DS.send, &DS.csend, (nsend + 1) * sizeof(Disc));
      o = DS.send;
    }
    for (int r = 0; r < S; r++) {
      sb[r] = 0;
      for (int c = 0; c < nch && r != me; c++) {
        if (!box_meets(mine + 4 * c, mpad[c], hull + 4 * r)) continue;
        int nn = 0;
        for (int b = bo[r]; b < bo[r + 1]; b++)
          if (box_meets(mine + 4 * c, mpad[c], bx + 4 * b)) near[nn++] = b;
        for (int k = cs[c]; nn && k < cs[c + 1]; k++) {
          const double pad = disc_pad(C, k - qa), d[4] = {C->cx[k - qa], C->cy[k - qa], C->cx[k - qa], C->cy[k - qa]};
          int hit = 0;
          for (int z = 0; z < nn && !hit; z++) hit = box_meets(d, pad, bx + 4 * near[z]);
          if (!hit) continue;
          sb[r] += (int)sizeof(Disc);
          if (pass) *o++ = (Disc){C->item[k], C->cx[k - qa], C->cy[k - qa], C->cr[k - qa]};
          else nsend++;
        }
      }
    }
  }
  par_note_discs((long)nsend, (long)nown);
  const Disc *in = par_exchange(DS.send, sb, rb);
  /* the discs to search, by triangle: those of lower ranks, this rank's, those of higher ranks */
  size_t nin = 0;
  for (int r = 0; r < S; r++) nin += (size_t)rb[r] / sizeof(Disc);
  const int nu = (int)nin + (qb - qa);
  if (DS.cu < nu + 1) {
    free(DS.uitem); free(DS.ucx); free(DS.ucy); free(DS.ucr);
    DS.cu = nu + nu / 2 + 1024;
    DS.uitem = yf_malloc((size_t)DS.cu * sizeof(int), "contact search on ranks");
    DS.ucx = yf_malloc((size_t)DS.cu * sizeof(double), "contact search on ranks");
    DS.ucy = yf_malloc((size_t)DS.cu * sizeof(double), "contact search on ranks");
    DS.ucr = yf_malloc((size_t)DS.cu * sizeof(double), "contact search on ranks");
  }
  int u = 0;
  for (int r = 0; r < S; r++) {
    if (r == me) {
      for (int k = qa; k < qb; k++, u++) {
        DS.uitem[u] = C->item[k];
        DS.ucx[u] = C->cx[k - qa]; DS.ucy[u] = C->cy[k - qa]; DS.ucr[u] = C->cr[k - qa];
      }
      continue;
    }
    for (size_t t = 0; t < (size_t)rb[r] / sizeof(Disc); t++, u++, in++) {
      DS.uitem[u] = (int)in->t;
      DS.ucx[u] = in->cx; DS.ucy[u] = in->cy; DS.ucr[u] = in->r;
    }
  }
  contact_search(&C->work, nu, DS.uitem, DS.ucx, DS.ucy, DS.ucr, buf, f, &C->fresh);
}

/* MPI: the ranks' ranges of the one-rank list (DS.lo) from their counts (n: this rank's); a
 * collective.  Returns the length of the whole list. */
static int set_ranges(int n) {
  const int S = par_size();
  ds_ranks();
  const int *c = par_concat(&n, (int)sizeof n, DS.rb);
  DS.lo[0] = 0;
  for (int r = 0; r < S; r++) DS.lo[r + 1] = DS.lo[r] + c[r];
  return DS.lo[S];
}

/* The length of the whole (one-rank) list. */
static int ntotal(const YfContact *C) { return C->local ? DS.lo[par_size()] : C->pairs.n; }

/* MPI: rank r's scratch counts (DS.rb, DS.sb) and ranges (DS.lo), room for par_size() ranks. */
static void ds_ranks(void) {
  const int S = par_size();
  if (DS.nlo < S + 1) {
    free(DS.lo); free(DS.rb); free(DS.sb);
    DS.lo = yf_malloc(((size_t)S + 1) * sizeof(int), "contact ranges");
    DS.rb = yf_malloc(((size_t)S + 1) * sizeof(int), "contact ranges");
    DS.sb = yf_malloc(((size_t)S + 1) * sizeof(int), "contact ranges");
    DS.nlo = S + 1;
  }
}

/* Lay the couples of the list by ranks (C->local) when this run is in halo mode (2 ranks or
 * more).  A list is whole on every rank after a restart is read (every rank then keeps its range,
 * a collective).  Once laid out it follows the triangle ranges: when they change (a re-cut, or a
 * scene changed between runs: triangles added move the cut) each couple goes to its lower
 * triangle's new owner, and when a changed scene leaves halo mode (its node order no longer
 * follows the ranks) the list is made whole on every rank again, friction memory and all. */
static void gather_whole(YfContact *C, int everyone);
static void install(YfContact *C, int n, const int *ij, const double *g, const unsigned char *alive);
static void rehome_couples(YfContact *C);
static void lay_out(YfContact *C) {
  const int want = par_node_lo() != NULL;
  if (!want && C->local) {
    gather_whole(C, 1);
    install(C, C->wn, C->wij, C->gdense, C->walive);
    C->local = 0;
    C->wfresh = 0;
    return;
  }
  if (want && C->local && C->lay_id != par_layout_id()) rehome_couples(C);
  if (want == C->local) return;
  /* the whole list is the same on every rank: each keeps its range (friction slots stay) */
  ds_ranks();
  par_owner_ranges(C->pairs.ij, 2, C->pairs.n, DS.lo);
  const int a = DS.lo[par_rank()], n = DS.lo[par_rank() + 1] - a, ntot = C->pairs.n;
  if (n > 0) { /* (an empty list may have no arrays yet) */
    memmove(C->pairs.ij, C->pairs.ij + 2 * (size_t)a, (size_t)n * 2 * sizeof(int));
    memmove(C->pairs.gi, C->pairs.gi + a, (size_t)n * sizeof(int));
    memmove(C->alive, C->alive + a, (size_t)n);
  }
  C->pairs.n = n;
  couple_arrays(C, n, ntot);
  C->local = 1;
  C->lay_id = par_layout_id();
}

/* The kernel stage on MPI ranks (above), after the screen of this rank's couples (which marked
 * its drops 3).  P's couple arrays hold this rank's couples, the one-rank list's k0 .. k1 - 1
 * (P->np: the length of that list); *ng: this rank's friction slots in use, updated.  Returns
 * the couples dropped this step by the screens and kernels of all ranks. */
static int kernel_ranks(YfSim *s, YfContact *C, KernelPass *P, int nbusy, int *ng) {
  const int S = par_size(), me = par_rank();
  int *lo = DS.lo, *rb = DS.rb, *sb = DS.sb;
  const int *nlo = par_node_lo();
  const int np = P->np, k0 = lo[me], k1 = lo[me + 1], n0 = nlo[me], n1 = nlo[me + 1];
  int *gi = P->gi;
  unsigned char *alive = P->alive; /* alive[k - k0]: couple k of the one-rank list */
  /* 0. the screen's drops (3) become 0, and first contacts get zeroed friction slots, numbered
   * on this rank in couple order (a couple's memory never leaves it, so no other rank needs the
   * numbers).  The screen counted both per block (blk_rm, blk_need), so only the blocks that
   * hold one are read: a pass over all 4.5e6 couples of a rank cost 2-3 ms a step at 1e6. */
  const int b0 = k0 / PAIR_BLK, b1 = k1 > k0 ? (k1 - 1) / PAIR_BLK + 1 : b0, nq = b1 - b0;
  int nneed = 0, nsd = 0;
  for (int b = b0; b < b1; b++) {
    nneed += C->blk_need[b];
    nsd += C->blk_rm[b];
  }
  int slot = *ng;
  contact_pairs_greserve(&C->pairs, slot + nneed);
  P->gmem = C->pairs.g;
  for (int b = b0; b < b1; b++) {
    if (!C->blk_need[b] && !C->blk_rm[b]) continue;
    int xa, xb;
    (void)piece(b, k0, k1, np, &xa, &xb);
    for (int k = xa - k0; k < xb - k0; k++)
      if (alive[k] == 3) alive[k] = 0;
      else if (alive[k] == 2 && gi[k] < 0) {
        gi[k] = slot++;
        memset(P->gmem + YF_PAIR_NG * (size_t)gi[k], 0, YF_PAIR_NG * sizeof(double));
      }
  }
  *ng = slot;
  /* this rank's pieces: hits numbered from 0 in couple order */
  ds_room(&DS.sum, &DS.csum, (size_t)(NSUM * nq + 4) * sizeof(double));
  double *qsum = DS.sum; /* e, d, s per piece */
  int nh = 0, ned = 0;
  ds_room(&DS.hof, &DS.chof, (size_t)(3 * nq + 3) * sizeof(int));
  int *hoff = DS.hof, *eoff = hoff + nq + 1;
  for (int q = 0; q < nq; q++) {
    int xa, xb, whole = piece(b0 + q, k0, k1, np, &xa, &xb), c = 0;
    if (whole) c = C->blk_busy[b0 + q];
    else
      for (int k = xa; k < xb; k++) c += alive[k - k0] == 2;
    hoff[q] = nh;
    eoff[q] = ned;
    nh += c;
    if (!whole) ned += c;
  }
  hit_room(C, nh > nbusy ? nh : nbusy);
  P->hf = C->hf;
  P->hk = C->hk;
  ds_room(&DS.ed, &DS.ced, (size_t)(NSUM * ned + NSUM * nq + 2) * sizeof(double));
  double *ed = DS.ed;
  const double tk = yf_cpu_now();
  #pragma omp parallel for schedule(dynamic, 1) if (YF_WANT_TEAM(nh >= C->par_min / 32 && nq > 1))
  for (int q = 0; q < nq; q++) {
    int xa, xb, rm = 0, whole = piece(b0 + q, k0, k1, np, &xa, &xb);
    kernel_run(P, xa - k0, xb - k0, hoff[q], 0, &qsum[NSUM * q], &rm, whole ? NULL : ed + NSUM * eoff[q]);
  }
  par_note_work(yf_cpu_now() - tk);

  /* 1. to every rank: the whole blocks' sums, the split pieces' pairs, then how many couples this
   * rank dropped (screen and kernel) */
  int nwhole = 0;
  for (int q = 0; q < nq; q++) {
    int xa, xb;
    nwhole += piece(b0 + q, k0, k1, np, &xa, &xb);
  }
  int ndrop = nsd;
  for (int h = 0; h < nh; h++) ndrop += !alive[C->hk[h]];
  size_t nsend = (size_t)(NSUM * nwhole + NSUM * ned + nq + 3) * sizeof(double);
  ds_room(&DS.send, &DS.csend, nsend + 16);
  double *o = DS.send;
  for (int q = 0; q < nq; q++) {
    int xa, xb;
    if (piece(b0 + q, k0, k1, np, &xa, &xb))
      for (int v = 0; v < NSUM; v++) *o++ = qsum[NSUM * q + v];
  }
  for (int q = 0; q < nq; q++) { /* split pieces: how many touching couples, then their pairs */
    int xa, xb;
    if (piece(b0 + q, k0, k1, np, &xa, &xb)) continue;
    int c = q + 1 < nq ? eoff[q + 1] - eoff[q] : ned - eoff[q];
    *o++ = c;
    memcpy(o, ed + NSUM * eoff[q], (size_t)(NSUM * c) * sizeof(double));
    o += NSUM * c;
  }
  *o++ = ndrop;
  const char *all = par_concat(DS.send, (int)((char *)o - (char *)DS.send), rb);
  int removed = 0;
  for (int r = 0; r < S; r++, all += rb[r - 1]) {
    const double *a = (const double *)all;
    removed += (int)a[rb[r] / (int)sizeof(double) - 1];
    if (lo[r + 1] <= lo[r]) continue;
    int rb0 = lo[r] / PAIR_BLK, rb1 = (lo[r + 1] - 1) / PAIR_BLK + 1, xa, xb;
    for (int b = rb0; b < rb1; b++)
      if (piece(b, lo[r], lo[r + 1], np, &xa, &xb)) { C->blk_e[b] = a[0]; C->blk_d[b] = a[1]; C->blk_s[b] = a[2]; a += NSUM; }
    for (int b = rb0; b < rb1; b++) {
      if (piece(b, lo[r], lo[r + 1], np, &xa, &xb)) continue;
      /* a split block: its touching couples in couple order, rank after rank */
      const int first = xa == b * PAIR_BLK;
      double e = first ? 0.0 : C->blk_e[b], d = first ? 0.0 : C->blk_d[b], sp = first ? 0.0 : C->blk_s[b];
      int c = (int)*a++;
      for (int t = 0; t < c; t++, a += NSUM) { e += a[0]; d += a[1]; sp += a[2]; }
      C->blk_e[b] = e;
      C->blk_d[b] = d;
      C->blk_s[b] = sp;
    }
  }

  /* 2. hits on other ranks' nodes to their owners, in couple order */
  const int *ij = P->ij, *tv = P->tv;
  for (int r = 0; r < S; r++) sb[r] = 0;
  /* grouped by owner: count, then fill */
  int fill[64], *fl = S <= 64 ? fill : yf_calloc((size_t)S, sizeof(int), "contact exchange");
  HitWalk w = {C, ij, tv, n0, n1, S, nlo, sb, fl, NULL, NULL, NULL, NULL, NULL};
  walk_hits(&w, nh, 0);
  size_t ncon = 0;
  for (int r = 0; r < S; r++) { fl[r] = (int)ncon; ncon += (size_t)sb[r] / sizeof(Contrib); }
  ds_room(&DS.send, &DS.csend, (ncon + 1) * sizeof(Contrib));
  Contrib *cs = DS.send;
  w.cs = cs;
  walk_hits(&w, nh, 1);
  if (fl != fill) free(fl);
  const char *in = par_exchange(cs, sb, rb);
  par_note_cross_hits(ij, C->hk, nh);

  /* 3. the owned nodes' contact forces: every rank's contributions in rank (= couple) order.
   * The nodes marked are listed (tlist), so that only they are cleared at the next step and
   * added now: a pass over a rank's 1.5e6 owned nodes cost 1 ms a step at 1e6.  Each node's sum
   * and its addition to fx are what the pass made, so the bits do not change. */
  YfNodes *nd = &s->model.node;
  double *fcn = C->fcn;
  unsigned char *tmark = C->tmark;
  if (C->cap_tl < n1 - n0) { /* rarely grows: once per run's node range */
    C->cap_tl = n1 - n0;
    C->tlist = yf_realloc(C->tlist, (size_t)C->cap_tl * sizeof(int), "contact node list");
  }
  if (C->ntl < 0 || C->tl_run != par_run_id()) { /* not known: every owned node */
    for (int i = n0; i < n1; i++)
      if (tmark[i]) { fcn[2 * i] = fcn[2 * i + 1] = 0.0; tmark[i] = 0; }
  } else {
    for (int t = 0; t < C->ntl; t++) {
      int i = C->tlist[t];
      fcn[2 * i] = fcn[2 * i + 1] = 0.0;
      tmark[i] = 0;
    }
  }
  C->ntl = 0;
  C->tl_run = par_run_id();
  w.fcn = fcn;
  w.tmark = tmark;
  w.tl = C->tlist;
  w.ntl = &C->ntl;
  for (int r = 0; r < S; r++) {
    if (r == me) {
      walk_hits(&w, nh, 2);
      continue;
    }
    const Contrib *cr = (const Contrib *)in;
    for (int t = 0; t < rb[r] / (int)sizeof(Contrib); t++) {
      int i = (int)cr[t].i;
      if (!tmark[i]) { tmark[i] = 1; C->tlist[C->ntl++] = i; }
      fcn[2 * i] += cr[t].fx;
      fcn[2 * i + 1] += cr[t].fy;
    }
    in += rb[r];
  }
  for (int t = 0; t < C->ntl; t++) {
    int i = C->tlist[t];
    nd->fx[i] += fcn[2 * i];
    nd->fy[i] += fcn[2 * i + 1];
  }
  return removed;
}

/* MPI: the node contact forces whole on every rank, for a reader (frames, restarts, the end of a
 * run).  Every rank calls it at the same point.  (The couples and their friction memory stay
 * with their owners: contact_par_whole gathers them for a restart.) */
void contact_par_gather(YfSim *s) {
  YfContact *C = s->contact;
  if (!active(C) || !C->fcn_valid || par_size() <= 1) return;
  const int *nlo = par_node_lo();
  if (!nlo) return;
  par_gather_ranges(C->fcn, nlo, 2 * (int)sizeof(double));
}

/* MPI: the whole couple list, its states and its friction memory (YF_PAIR_NG per couple, zeros
 * where a couple has none, as contact_state_save gives it) into wij, walive, gdense on the writer
 * rank (rank 0, the one that writes the restart), from the ranks' ranges in rank order: 9 B per
 * couple and 96 B per couple with memory, sent to that rank only.  A collective; a no-op unless the list is
 * laid out by ranks. */
void contact_par_whole(YfSim *s) {
  YfContact *C = s->contact;
  if (!active(C) || !C->local) return;
  gather_whole(C, 0);
}

/* The whole list into wij, walive, gdense (wn couples) on the writer rank, or on every rank
 * (everyone: par_concat). */
static void gather_whole(YfContact *C, int everyone) {
  const int S = par_size(), n = C->pairs.n, ntot = DS.lo[S], w = everyone || yf_writer();
  const void *(*cat)(const void *, int, int *) = everyone ? par_concat : par_concat_writer;
  int *rb = DS.rb;
  free(C->wij); free(C->walive); free(C->gdense);
  C->wij = NULL; C->walive = NULL; C->gdense = NULL;
  C->wn = w ? ntot : 0;
  if (w) {
    C->wij = yf_malloc((size_t)(ntot + 1) * 2 * sizeof(int), "restart couples");
    C->walive = yf_malloc((size_t)ntot + 1, "restart couples");
    C->gdense = yf_calloc((size_t)(ntot + 1) * YF_PAIR_NG, sizeof(double), "restart friction memory");
  }
  const void *all = cat(C->pairs.ij, (int)((size_t)n * 2 * sizeof(int)), rb);
  if (all && ntot) memcpy(C->wij, all, (size_t)ntot * 2 * sizeof(int));
  /* per couple: its state, + 4 when it has friction memory; then the memories in couple order */
  unsigned char *st = yf_malloc((size_t)n + 1, "restart couples");
  int nm = 0;
  for (int k = 0; k < n; k++) {
    st[k] = (unsigned char)(C->alive[k] | (C->pairs.gi[k] >= 0 ? 4 : 0));
    nm += C->pairs.gi[k] >= 0;
  }
  all = cat(st, n, rb);
  if (all && ntot) memcpy(C->walive, all, (size_t)ntot);
  free(st);
  double *g = yf_malloc((size_t)(YF_PAIR_NG * nm + 1) * sizeof(double), "restart friction memory"), *o = g;
  for (int k = 0; k < n; k++)
    if (C->pairs.gi[k] >= 0) {
      memcpy(o, C->pairs.g + YF_PAIR_NG * (size_t)C->pairs.gi[k], YF_PAIR_NG * sizeof(double));
      o += YF_PAIR_NG;
    }
  const double *a = cat(g, YF_PAIR_NG * nm * (int)sizeof(double), rb);
  for (int k = 0; a && k < ntot; k++)
    if (C->walive[k] & 4) {
      memcpy(C->gdense + YF_PAIR_NG * (size_t)k, a, YF_PAIR_NG * sizeof(double));
      a += YF_PAIR_NG;
      C->walive[k] &= 3;
    }
  free(g);
  C->wfresh = 1;
}

void contact_step(YfSim *s) {
  YfContact *C = s->contact;
  if (!active(C)) return;
  double t0 = yf_now();
  YfModel *m = &s->model;
  YfNodes *nd = &m->node;
  const double dt = s->dt;
  lay_out(C); /* MPI: each rank its own couples (after a restart is read, say) */
  C->wfresh = 0;

  /* detection (ALGORITHMS 5): travel of the previous half step's velocities (MPI, divided
   * update: of this rank's nodes, then the largest of all ranks: a maximum is exact) */
  double vmax2;
  if (par_divided()) {
    int n0 = 0, n1 = nd->n;
    par_update_nodes(&n0, &n1, NULL, NULL);
    const int a = first_at_least(C->pnode, C->npn, n0), b = first_at_least(C->pnode, C->npn, n1);
    vmax2 = par_max(contact_vmax2(b - a, C->pnode + a, nd->vx, nd->vy));
  } else {
    vmax2 = contact_vmax2(C->npn, C->pnode, nd->vx, nd->vy);
  }
  int due = contact_trigger_step(&C->trig, dt, vmax2);
  if (C->joined_on) {
    long nb = joints_broken(s);
    if (nb != C->broken_seen) { due = 1; C->broken_seen = nb; } /* newly free faces must see each other now */
  }
  int searched = 0;
  if (due || C->force_search || C->search_every) {
    if (!due) C->trig.travel = 0.0;
    search(s, C);
    C->force_search = 0;
    searched = 1;
  }
  if (!searched && C->nsearch == 0) { /* a first search delayed by Y2D's DIEDI: no couples yet */
    yf_stage_time[YF_ST_DETECT] += yf_now() - t0;
    return;
  }
  /* MPI, divided update: the triangles this rank's couples read, their corners as ghosts */
  const int *item = C->item, *tmap = NULL;
  int nitem = C->nitem;
  if (par_divided()) {
    if (searched || C->ghost_run != par_run_id()) contact_ghosts(s, C);
    item = DS.rtri;
    nitem = DS.nrtri;
    tmap = DS.tloc; /* the records of these triangles only, in this order */
  }
  if (C->pairs.n > 0) tg_room(C, tmap ? nitem : m->tri.n); /* rarely grows: see contact_prepare */
  double t1 = yf_now();
  yf_stage_time[YF_ST_DETECT] += t1 - t0;

  /* the screen's triangle records of this step (participating triangles only; MPI, divided
   * update: those of this rank's couples).  Only the screen and the kernel of this step read
   * them: with no couple (bodies that are not near each other, a 'contact pair' that never
   * meets) none are made (2000 steps of two 1e4-triangle bodies 4 m apart: 6 % of the step). */
  const int *tv = m->tri.v, *tmat = m->tri.mat;
  const double *x = nd->x, *y = nd->y, *vx = nd->vx, *vy = nd->vy;
  double *tg = C->tg;
  YF_PARFOR_IF(nitem >= C->par_min, schedule(static), for (int q = 0; q < (C->pairs.n > 0 ? nitem : 0); q++) {
    const int t = item[q], *v = tv + 3 * t;
    double xs[3] = {x[v[0]], x[v[1]], x[v[2]]}, ys[3] = {y[v[0]], y[v[1]], y[v[2]]};
    contact_pair_geom(xs, ys, tg + (size_t)YF_TRI_GEOM * (tmap ? q : t));
  });

  /* pass 1, the screen: couples whose edges all miss give no force (only their distance decides
   * whether they stay); the others are marked 2 and counted per fixed block */
  /* MPI: this rank's couples, the one-rank list's s0 .. s1 - 1, in ij[2 (k - s0)] etc.; the
   * blocks are the one-rank list's */
  const int np = C->pairs.n, dist = par_size() > 1 && C->local, s0 = dist ? DS.lo[par_rank()] : 0, s1 = s0 + np;
  const int ntot = ntotal(C), nblk = (ntot + PAIR_BLK - 1) / PAIR_BLK;
  const int *ij = C->pairs.ij;
  int *gi = C->pairs.gi;
  unsigned char *alive = C->alive;
  const double rem2 = 4.0 * C->buffer * C->buffer;
  const int *mlaw = C->mlaw;
  int coul = 0; /* a Coulomb material: only then can a quiet couple hold a spring to let go */
  for (int i = 0; i < C->nmat; i++) coul |= mlaw[i] != YF_FRIC_Y2D;
  double *gmem = C->pairs.g;
  /* MPI: this rank screens its own couples only (kernel_ranks), marking its drops 3 */
  const unsigned char dropped = dist ? 3 : 0;
  const double cs0 = dist ? yf_cpu_now() : 0.0;
  YF_PARFOR_IF(np >= C->par_min && nblk > 1, schedule(static), for (int b = 0; b < nblk; b++) {
    int k1 = (b + 1) * PAIR_BLK < s1 ? (b + 1) * PAIR_BLK : s1, rm = 0, busy = 0, need = 0;
    for (int k = (b * PAIR_BLK > s0 ? b * PAIR_BLK : s0) - s0; k < k1 - s0; k++) {
      if (!alive[k]) continue;
      const int ta = ij[2 * k + 1], tb = ij[2 * k];
      const double *ra = tg + (size_t)YF_TRI_GEOM * (tmap ? tmap[ta] : ta), *rb = tg + (size_t)YF_TRI_GEOM * (tmap ? tmap[tb] : tb);
      int q = contact_pair_quiet(ra, rb, rem2);
      if (q == 0) { alive[k] = 2; busy++; need += gi[k] < 0; }
      else if (q == 2) { alive[k] = dropped; rm++; }
      else if (coul && gi[k] >= 0 && mlaw[tmat[ij[2 * k]]] != YF_FRIC_Y2D && mlaw[tmat[ij[2 * k + 1]]] != YF_FRIC_Y2D)
        memset(gmem + YF_PAIR_NG * (size_t)gi[k], 0, YF_PAIR_NG * sizeof *gmem); /* apart: the Coulomb springs let go */
    }
    C->blk_rm[b] = rm;
    C->blk_busy[b] = busy;
    C->blk_need[b] = need;
  });
  if (dist) par_note_work(yf_cpu_now() - cs0); /* the screen of this rank's couples */
  int nbusy = 0, ng = C->pairs.ng;
  for (int b = 0; b < nblk; b++) {
    C->blk_off[b] = nbusy;
    nbusy += C->blk_busy[b];
    C->blk_goff[b] = ng;
    ng += C->blk_need[b];
  }
  C->blk_off[nblk] = nbusy;
  if (nbusy > C->max_busy) C->max_busy = nbusy;
  contact_pairs_greserve(&C->pairs, ng); /* rarely grows: reserved at each search */

  /* pass 2: the kernel on the marked couples (A = the larger index, Y2D's order).  On several
   * threads each couple writes its 12 forces into its place of the hit list, in couple order
   * (no atomics), and the scatter below sums them per node in couple order.  On one thread the
   * blocks run in order anyway, so each couple's forces go straight into the node sums, in the
   * scatter's order: the same additions in the same order, the same bits, without the list
   * (100 B per touching couple written and read back; PERF.md at 1e4: 43 000 of them). */
  int nthr = 1;
#ifdef _OPENMP
  nthr = omp_get_max_threads();
#endif
  const int serial = !YF_WANT_TEAM(nbusy >= C->par_min / 32 && nblk > 1) || nthr == 1;
  KernelPass P = {ij, tv, tmat, gi, alive, vx, vy, tg, tmap, C->pairs.g, C->mpn, C->mpt, C->mmu, C->mlaw, dt, rem2, ntot,
                  NULL, NULL, NULL, NULL};
  double *fx = nd->fx, *fy = nd->fy, *fcn = C->fcn;
  unsigned char *tmark = C->tmark;
  const int nn = nd->n;
  if (dist) ng = C->pairs.ng; /* kernel_ranks numbers this rank's first contacts itself */
  const int kdrop = dist ? kernel_ranks(s, C, &P, nbusy, &ng) : -1; /* MPI: each rank its couples (above) */
  if (kdrop >= 0) C->tmarked = 1;
  if (!dist) C->ntl = -1; /* the paths below mark nodes without listing them */
  if (kdrop < 0 && serial) {
    /* the passes over every node find nothing when no node was marked and no couple touches */
    const int marks = C->tmarked || nbusy > 0;
    if (marks)
      for (int i = 0; i < nn; i++)
        if (tmark[i]) { fcn[2 * i] = fcn[2 * i + 1] = 0.0; tmark[i] = 0; }
    P.fcn = fcn;
    P.tmark = tmark;
    for (int b = 0; b < nblk; b++) kernel_block(C, &P, b);
    if (marks)
      for (int i = 0; i < nn; i++)
        if (tmark[i]) { fx[i] += fcn[2 * i]; fy[i] += fcn[2 * i + 1]; }
    C->tmarked = nbusy > 0;
  } else if (kdrop < 0) {
    C->tmarked = 1;
    hit_room(C, nbusy); /* rarely grows: see hit_room */
    P.hf = C->hf;
    P.hk = C->hk;
    #pragma omp parallel for schedule(dynamic, 1)
    for (int b = 0; b < nblk; b++) kernel_block(C, &P, b);
  }
  double esum = 0.0, dsum = 0.0, ssum = 0.0;
  int removed = 0;
  for (int b = 0; b < nblk; b++) {
    esum += C->blk_e[b];
    dsum += C->blk_d[b];
    ssum += C->blk_s[b];
    removed += C->blk_rm[b];
  }
  if (dist) removed = kdrop; /* blk_rm counted this rank's screen only */
  s->energy.contact = esum;
  /* the springs' work less the change of their energy (the couples gave work - energy now) */
  s->energy.friction += dsum + C->espring;
  C->espring = ssum;
  C->pairs.ng = ng;

  /* scatter in couple order: each node's contact force is the sum of its couples'
   * contributions in couple order (A's corners before B's), then added to node.fx.  Thread t
   * owns the nodes of one contiguous range and reads every record, so each node's sum has the
   * same order (and bits) on any thread count. */
  const int *hk = C->hk;
  const double *hf = C->hf;
  if (!serial && kdrop < 0)
  #pragma omp parallel if (nbusy >= C->par_min / 8 && nn >= C->par_min)
  {
    int nth = 1, me = 0;
#ifdef _OPENMP
    nth = omp_get_num_threads();
    me = omp_get_thread_num();
#endif
    const int n0 = (int)((long)nn * me / nth), n1 = (int)((long)nn * (me + 1) / nth);
    for (int i = n0; i < n1; i++)
      if (tmark[i]) { fcn[2 * i] = fcn[2 * i + 1] = 0.0; tmark[i] = 0; }
    for (int h = 0; h < nbusy; h++) {
      int k = hk[h];
      const int *vv[2] = {tv + 3 * ij[2 * k + 1], tv + 3 * ij[2 * k]};
      const double *f = hf + 12 * (size_t)h;
      for (int c = 0; c < 6; c++) {
        int i = vv[c / 3][c % 3];
        if (i < n0 || i >= n1) continue;
        tmark[i] = 1;
        fcn[2 * i] += f[2 * c];
        fcn[2 * i + 1] += f[2 * c + 1];
      }
    }
    for (int i = n0; i < n1; i++)
      if (tmark[i]) { fx[i] += fcn[2 * i]; fy[i] += fcn[2 * i + 1]; }
  }
  C->fcn_valid = 1;

  contact_compact(C, removed);
  yf_stage_time[YF_ST_CONTACT] += yf_now() - t1;
}

/* ---------------------------------------------------------------- restart accessors (restart.c) */

/* MPI: each rank's range of the one-rank couple list (size + 1; NULL unless laid out by ranks). */
const int *contact_rank_lo(const YfSim *s) {
  const YfContact *C = s->contact;
  return active(C) && C->local ? DS.lo : NULL;
}

void contact_count_by_block(const YfSim *s, int g, int *cnt) {
  const YfContact *C = s->contact;
  if (!active(C)) return;
  for (int k = 0; k < C->pairs.n; k++) cnt[C->pairs.ij[2 * k] / g]++;
}

/* A couple on its way to the new owner of its lower triangle (112 B). */
typedef struct { int i, j, st, pad; double g[YF_PAIR_NG]; } Moved;

void contact_rehome(YfSim *s, const int *nold) {
  YfContact *C = s->contact;
  if (!active(C) || !C->local) return;
  const int me = par_rank(), *nlo = par_node_lo();
  if (!nlo) return; /* (one rank) */
  /* the node contact forces of the last step, for a reader before the next one; an owned node is
   * marked when it holds one, so that the next step clears it before adding (the list of marked
   * nodes is not known: the next step passes over every owned node) */
  if (C->fcn_valid) par_move_ranges(C->fcn, nold, nlo, 2 * (int)sizeof(double));
  for (int i = nlo[me]; i < nlo[me + 1]; i++) C->tmark[i] = C->fcn[2 * i] != 0.0 || C->fcn[2 * i + 1] != 0.0;
  C->ntl = -1;
  C->tmarked = 1;
  rehome_couples(C);
}

/* MPI: this rank's couples to the owners of their lower triangles by the current ranges, with
 * their states and friction memory, after the ranges changed (a re-cut, or a new scene between
 * runs whose triangle count moved the cut): the one-rank list and its order are unchanged, only
 * where its pieces live.  A collective. */
static void rehome_couples(YfContact *C) {
  const int S = par_size(), me = par_rank(), n = C->pairs.n;
  C->wfresh = 0;
  C->lay_id = par_layout_id();
  /* this rank's couples by their new owner: the list is sorted by lower triangle, so each new
   * owner's are one range of it, d[r]..d[r+1]-1 */
  ds_ranks();
  int *d = yf_malloc(((size_t)S + 1) * sizeof(int), "contact re-cut"), *sb = DS.sb, *rb = DS.rb;
  par_owner_ranges(C->pairs.ij, 2, n, d);
  for (int r = 0; r < S; r++) sb[r] = r == me ? 0 : (d[r + 1] - d[r]) * (int)sizeof(Moved);
  ds_room(&DS.send, &DS.csend, (size_t)(n - (d[me + 1] - d[me]) + 1) * sizeof(Moved));
  Moved *o = DS.send;
  for (int k = 0; k < n; k++) {
    if (k >= d[me] && k < d[me + 1]) continue;
    const int gi = C->pairs.gi[k];
    Moved mv = {C->pairs.ij[2 * k], C->pairs.ij[2 * k + 1], C->alive[k] | (gi >= 0 ? 4 : 0), 0, {0}};
    if (gi >= 0) memcpy(mv.g, C->pairs.g + YF_PAIR_NG * (size_t)gi, sizeof mv.g);
    *o++ = mv;
  }
  const Moved *in = par_exchange(DS.send, sb, rb);
  /* the new list, in place: what ranks before this one sent, the couples it keeps (moved up or
   * down as a block, their friction slots kept), what ranks after it sent (rank order is
   * triangle order); the sent couples' slots stay unused until the next search's merge, as a
   * dropped couple's do */
  int nlow = 0, nhigh = 0, nmem = 0;
  for (int r = 0; r < S; r++) {
    if (r < me) nlow += rb[r] / (int)sizeof(Moved);
    if (r > me) nhigh += rb[r] / (int)sizeof(Moved);
  }
  for (int t = 0; t < nlow + nhigh; t++) nmem += (in[t].st & 4) != 0;
  const int k0 = d[me], nk = d[me + 1] - d[me], nnew = nlow + nk + nhigh, ntot = DS.lo[S];
  YfPairs *p = &C->pairs;
  contact_pairs_reserve(p, nnew);
  contact_pairs_greserve(p, p->ng + nmem);
  couple_arrays(C, nnew, ntot);
  if (nk && k0 != nlow) {
    memmove(p->ij + 2 * (size_t)nlow, p->ij + 2 * (size_t)k0, (size_t)nk * 2 * sizeof(int));
    memmove(p->gi + nlow, p->gi + k0, (size_t)nk * sizeof(int));
    memmove(C->alive + nlow, C->alive + k0, (size_t)nk);
  }
  for (int t = 0; t < nlow + nhigh; t++) {
    const int w = t < nlow ? t : nk + t;
    p->ij[2 * w] = in[t].i;
    p->ij[2 * w + 1] = in[t].j;
    p->gi[w] = -1;
    if (in[t].st & 4) {
      p->gi[w] = p->ng++;
      memcpy(p->g + YF_PAIR_NG * (size_t)p->gi[w], in[t].g, YF_PAIR_NG * sizeof(double));
    }
    C->alive[w] = (unsigned char)(in[t].st & 3);
  }
  p->n = nnew;
  set_ranges(nnew);
  free(d);
}

int contact_has_state(const YfSim *s) { return active(s->contact) && s->contact->cx; }

int contact_state_save(const YfSim *s, YfContactState *st) {
  YfContact *C = s->contact; /* keeps the dense copy of the friction memory */
  memset(st, 0, sizeof *st);
  if (!contact_has_state(s)) return 0; /* not prepared */
  if (C->local) { /* MPI: the whole list, gathered by contact_par_whole at this step */
    YF_ASSERT(C->wfresh);
    st->n = C->wn;
    st->ij = C->wij;
    st->g = C->gdense;
    st->alive = C->walive;
  } else {
    st->n = C->pairs.n;
    st->ij = C->pairs.ij;
    /* the friction memory as YF_PAIR_NG values per couple (zeros where a couple has no slot) */
    free(C->gdense);
    C->gdense = yf_calloc((size_t)(st->n > 0 ? st->n : 1) * YF_PAIR_NG, sizeof(double), "restart friction memory");
    for (int k = 0; k < st->n; k++)
      if (C->pairs.gi[k] >= 0)
        memcpy(C->gdense + YF_PAIR_NG * (size_t)k, C->pairs.g + YF_PAIR_NG * (size_t)C->pairs.gi[k],
               YF_PAIR_NG * sizeof(double));
    st->g = C->gdense;
    st->alive = C->alive;
  }
  st->nlive = C->nlive;
  st->ndead = C->ndead;
  st->travel = C->trig.travel;
  st->nsearch = C->nsearch;
  st->broken_seen = C->broken_seen;
  st->force_search = C->force_search;
  st->nn = C->prep_nn;
  st->fcn = C->fcn;
  st->fcn_valid = C->fcn_valid;
  st->spring = C->espring;
  st->has_spring = 1;
  return 1;
}

/* A whole couple list (n couples ij, friction memory g YF_PAIR_NG per couple with zeros for none,
 * states alive) into C: friction slots in couple order for the couples whose memory is not zero. */
static void install(YfContact *C, int n, const int *ij, const double *g, const unsigned char *alive) {
  contact_pairs_reserve(&C->pairs, n);
  C->pairs.n = n;
  C->pairs.ng = 0;
  if (n) {
    memcpy(C->pairs.ij, ij, (size_t)n * 2 * sizeof(int));
    int used = 0;
    for (int k = 0; k < n; k++) {
      C->pairs.gi[k] = -!contact_gmem_zero(g + YF_PAIR_NG * (size_t)k);
      used -= C->pairs.gi[k];
    }
    contact_pairs_greserve(&C->pairs, 2 * used + n / 64 + 256);
    for (int k = 0; k < n; k++) { /* gi -1 marks the couples with memory, 0 the others */
      int has = C->pairs.gi[k] < 0;
      C->pairs.gi[k] = -1;
      if (has) memcpy(contact_pairs_gslot(&C->pairs, k), g + YF_PAIR_NG * (size_t)k, YF_PAIR_NG * sizeof(double));
    }
  }
  couple_arrays(C, n, n);
  if (n) memcpy(C->alive, alive, (size_t)n);
}

/* The energy the Coulomb springs of the installed list hold, sum 0.5 s^2 L over the contactor
 * edges (contact_pair.c, coulomb_edge) at the current positions: for a restart written before
 * the springs' energy was kept, whose own step's edge lengths are gone (an approximation of
 * the energy the next step's dissipation is measured from, by the edges' strain in one step). */
static double spring_energy(const YfSim *s, const YfContact *C) {
  const YfModel *m = &s->model;
  const double *x = m->node.x, *y = m->node.y;
  double e = 0.0;
  for (int k = 0; k < C->pairs.n; k++) {
    if (C->pairs.gi[k] < 0) continue;
    const int t[2] = {C->pairs.ij[2 * k], C->pairs.ij[2 * k + 1]}; /* contactor of direction 0, 1 */
    if (C->mlaw[m->tri.mat[t[0]]] == YF_FRIC_Y2D || C->mlaw[m->tri.mat[t[1]]] == YF_FRIC_Y2D) continue;
    const double *g = C->pairs.g + YF_PAIR_NG * (size_t)C->pairs.gi[k];
    for (int d = 0; d < 2; d++) {
      const int *v = m->tri.v + 3 * t[d];
      for (int c = 0; c < 3; c++) {
        int a = v[c], b = v[(c + 1) % 3];
        e += 0.5 * g[3 * d + c] * g[3 * d + c] * hypot(x[b] - x[a], y[b] - y[a]);
      }
    }
  }
  return e;
}

int contact_state_load(YfSim *s, const YfContactState *st) {
  YfContact *C = s->contact;
  if (!active(C) || !C->cx) return -1;
  install(C, st->n, st->ij, st->g, st->alive);
  C->local = 0; /* whole on every rank: each keeps its range at the next step (lay_out) */
  C->wfresh = 0;
  C->nlive = st->nlive;
  C->ndead = st->ndead;
  C->trig.travel = st->travel;
  C->nsearch = st->nsearch;
  C->broken_seen = st->broken_seen;
  C->force_search = st->force_search;
  /* the nodes that carry contact force of the last step (zeroed before the next scatter) */
  if (st->fcn && st->nn == C->prep_nn) {
    memcpy(C->fcn, st->fcn, (size_t)2 * st->nn * sizeof(double));
    for (int i = 0; i < st->nn; i++) C->tmark[i] = C->fcn[2 * i] != 0.0 || C->fcn[2 * i + 1] != 0.0;
    C->ntl = -1;
    C->tmarked = 1;
  }
  C->fcn_valid = st->fcn_valid;
  C->espring = st->has_spring ? st->spring : spring_energy(s, C);
  return 0;
}
