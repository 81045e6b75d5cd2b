/* joint.c: fracture in the scene (see joint.h): joint sets and fracture zones (set by the deck's
 * jointprop / fracture / fracture_log commands, deck/cmd_*.c), the splitting of fracturing triangles into their own nodes with a 4-node joint on each internal
 * edge (Y2D meshing code 3, ALGORITHMS.md 4.1), the per-step joint force stage with breakage
 * (3.7), the energy bookkeeping of the joints, the joints' stable time step, and the break records
 * and fragments that the summary (io/report.c) reports.
 *
 * Determinism: the force loop writes only per-joint data; breaks are collected per fixed block of
 * joints and recorded serially in joint order; every sum over joints is serial.  So 1 or N
 * threads give the same bits, and a scene without fracture has no joints and pays nothing.
 *
 * Speed: in a running scene nearly every joint is intact and before its peak, and then its forces
 * need no law, no damage memory and no state update.  The force stage takes such joints four at a
 * time (joint_force_fast4 of joint_law.h: one joint per lane of a 4-wide vector, each lane doing
 * joint_force's IEEE operations in its order, so the bits are the scalar law's); a joint past its
 * peak, with damage memory already damaged, or with Mohr-Coulomb takes the scalar law.
 *
 * Units: SI, 2D per unit thickness (forces N/m, energies J/m, fracture energy J/m^2).
 */
#include <errno.h>
#include <math.h>
#include <omp.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <gsl/gsl_randist.h>
#include <gsl/gsl_rng.h>
#include <gsl/gsl_sf_gamma.h>
#include "joint.h"
#include "par.h"
#include "parfor.h"
#include "contact.h"
#include "edgesort.h"
#include "elem_tri.h"
#include "err.h"
#include "mesh.h"
#include "region.h"
#include "stage_time.h"

#define JBLOCK YF_JBLOCK /* break collection granularity */
#define PF_GROUPS 4
static int par_min = 4096;
void joints_set_par_min(int n) { par_min = n < 0 ? 0 : n; }

/* A `fracture` command: which triangles of which body get joints of which set. */
typedef struct YfFracSpec {
  int body, set, region, group;
  int applied;
  YfLoc loc;
} YfFracSpec;

static YfJoints *jget(YfSim *s) {
  if (!s->joints) s->joints = yf_calloc(1, sizeof(YfJoints), "joints");
  return s->joints;
}

int joints_find_set(const YfSim *s, const char *name) {
  const YfJoints *J = s->joints;
  if (!J) return -1;
  for (int i = 0; i < J->nset; i++)
    if (!strcmp(J->set[i].name, name)) return i;
  return -1;
}

int joints_add_set(YfSim *s, const char *name, const YfJointProp *p, int het, double het_par,
                   unsigned long seed, const YfLoc *loc) {
  YfJoints *J = jget(s);
  if (joints_find_set(s, name) >= 0) yf_deck_error(loc, "jointprop '%s' is already defined", name);
  if (strlen(name) >= YF_NAME_MAX) yf_deck_error(loc, "jointprop name '%s' is too long (max %d)", name, YF_NAME_MAX - 1);
  char why[256];
  if (!joint_prop_check(p, why, sizeof why)) yf_deck_error(loc, "jointprop '%s': %s", name, why);
  J->set = yf_realloc(J->set, (size_t)(J->nset + 1) * sizeof *J->set, "joint sets");
  YfJointSet *js = &J->set[J->nset];
  memset(js, 0, sizeof *js);
  snprintf(js->name, sizeof js->name, "%s", name);
  js->p = *p;
  joint_pre_init(&js->p, &js->pre);
  js->het = het;
  js->het_par = het_par;
  js->seed = seed;
  return J->nset++;
}

/* A fracture zone (deck/cmd_fracture.c): the triangles of body (or of those in region or group,
 * -1 none) get joints of set at the first run. */
void joints_add_fracture(YfSim *s, int body, int set, int region, int group, const YfLoc *loc) {
  YfFracSpec sp = {.body = body, .set = set, .region = region, .group = group, .loc = *loc};
  YfJoints *J = jget(s);
  J->spec = yf_realloc(J->spec, (size_t)(J->nspec + 1) * sizeof *J->spec, "fracture specs");
  J->spec[J->nspec++] = sp;
  s->model.body[body].fracture = 1;
}

int joints_body_set(const YfSim *s, int body, const YfLoc **partial) {
  const YfJoints *J = s->joints;
  int set = -1;
  *partial = NULL;
  for (int q = 0; J && q < J->nspec; q++) {
    const YfFracSpec *sp = &J->spec[q];
    if (sp->body != body) continue;
    if (sp->region >= 0 || sp->group >= 0) *partial = &sp->loc;
    else set = sp->set;
  }
  return set;
}

void joints_set_logs(YfSim *s, const char *breaks, const char *opened) {
  YfJoints *J = jget(s);
  snprintf(J->log_path, sizeof J->log_path, "%s", breaks);
  J->open_log_path[0] = 0;
  if (opened) snprintf(J->open_log_path, sizeof J->open_log_path, "%s", opened);
}

void joints_set_open_threshold(YfSim *s, double z) { jget(s)->open_z = z; }

/* ---------------- insertion ---------------- */

typedef YfEdgeRec Edge;

typedef struct {
  int A, kA, B, kB, set;
} NewJoint;

static int nj_cmp(const void *pa, const void *pb) {
  const NewJoint *a = pa, *b = pb;
  if (a->A != b->A) return a->A < b->A ? -1 : 1;
  return a->kA - b->kA;
}

/* Exact capacity: joints come in one batch per insertion, whose size is known. */
static void joints_reserve(YfJoints *J, int want) {
  if (want <= J->cap) return;
  int cap = want;
#define JG(p, k) J->p = yf_realloc(J->p, (size_t)cap * (k) * sizeof *J->p, "joint " #p)
  JG(corner, 4); JG(node, 4); JG(tri, 2); JG(prop, 1); JG(k, 1); JG(fs, 1); JG(dmg, 3); JG(w, 1);
  JG(z, 1); JG(L0, 1); JG(state, 1); JG(mode, 1); JG(f, 8); JG(pend, 1); JG(opened, 1);
#undef JG
  J->cap = cap;
}

/* Renumber nodes so that each zone triangle owns three contiguous nodes (see joint.h). */
static void split_nodes(YfModel *m, const unsigned char *zone) {
  const int nn = m->node.n, nt = m->tri.n;
  YfNodes *N = &m->node;
  int *usez = yf_calloc((size_t)nn, sizeof(int), "split"), *usen = yf_calloc((size_t)nn, sizeof(int), "split");
  int nzt = 0;
  for (int t = 0; t < nt; t++) {
    if (zone[t]) nzt++;
    for (int c = 0; c < 3; c++) (zone[t] ? usez : usen)[m->tri.v[3 * t + c]]++;
  }
  /* anchor of each body: lowest node index used by its zone triangles */
  int nb = m->nbody > 0 ? m->nbody : 1;
  int *anchor = yf_malloc((size_t)nb * sizeof(int), "split");
  for (int b = 0; b < nb; b++) anchor[b] = nn;
  for (int t = 0; t < nt; t++)
    if (zone[t]) {
      int b = m->tri.body[t] >= 0 && m->tri.body[t] < nb ? m->tri.body[t] : 0;
      for (int c = 0; c < 3; c++)
        if (m->tri.v[3 * t + c] < anchor[b]) anchor[b] = m->tri.v[3 * t + c];
    }
  /* new order: src[new] = old node */
  int nkeep = 0;
  for (int i = 0; i < nn; i++) nkeep += usez[i] == 0 || usen[i] > 0;
  int nnew = nkeep + 3 * nzt;
  int *src = yf_malloc((size_t)(nnew > 0 ? nnew : 1) * sizeof(int), "split");
  int *rep = yf_malloc((size_t)(nn > 0 ? nn : 1) * sizeof(int), "split");
  int *tv = yf_malloc((size_t)nt * 3 * sizeof(int), "split");
  for (int i = 0; i < nn; i++) rep[i] = -1;
  int k = 0;
  for (int i = 0; i <= nn; i++) {
    for (int b = 0; b < nb; b++) {
      if (anchor[b] != i) continue;
      for (int t = 0; t < nt; t++) {
        int tb = m->tri.body[t] >= 0 && m->tri.body[t] < nb ? m->tri.body[t] : 0;
        if (!zone[t] || tb != b) continue;
        for (int c = 0; c < 3; c++) {
          int o = m->tri.v[3 * t + c];
          tv[3 * t + c] = k;
          if (rep[o] < 0 && usen[o] == 0) rep[o] = k; /* first zone use reuses the node */
          src[k++] = o;
        }
      }
    }
    if (i < nn && (usez[i] == 0 || usen[i] > 0)) {
      rep[i] = k;
      src[k++] = i;
    }
  }
  YF_ASSERT(k == nnew);
  for (int t = 0; t < nt; t++)
    if (!zone[t])
      for (int c = 0; c < 3; c++) tv[3 * t + c] = rep[m->tri.v[3 * t + c]];
  /* copy the old arrays, grow the model, write permuted */
  size_t dsz = (size_t)(nn > 0 ? nn : 1) * sizeof(double), isz = (size_t)(nn > 0 ? nn : 1) * sizeof(int);
  double *old[10];
  double *cur[10] = {N->x, N->y, N->x0, N->y0, N->vx, N->vy, N->fx, N->fy, N->m, NULL};
  for (int a = 0; a < 9; a++) {
    old[a] = yf_malloc(dsz, "split");
    memcpy(old[a], cur[a], (size_t)nn * sizeof(double));
  }
  int *oid = yf_malloc(isz, "split"), *opar = yf_malloc(isz, "split"), *obody = yf_malloc(isz, "split");
  uint64_t *ogm = yf_malloc((size_t)(nn > 0 ? nn : 1) * sizeof(uint64_t), "split");
  memcpy(oid, N->id, (size_t)nn * sizeof(int));
  memcpy(opar, N->parent, (size_t)nn * sizeof(int));
  memcpy(obody, N->body, (size_t)nn * sizeof(int));
  memcpy(ogm, N->gmask, (size_t)nn * sizeof(uint64_t));
  model_reserve(m, nnew - N->n, 0); /* exact: the split's node count is known */
  while (N->n < nnew) model_add_node(m, 0, 0, 0, -1);
  N->n = nnew;
  double *dst[9] = {N->x, N->y, N->x0, N->y0, N->vx, N->vy, N->fx, N->fy, N->m};
  for (int a = 0; a < 9; a++)
    for (int i = 0; i < nnew; i++) dst[a][i] = old[a][src[i]];
  /* root of an old node (copy chains from earlier calls), then its representative */
  for (int i = 0; i < nnew; i++) {
    int o = src[i], r = o;
    for (int it = 0; it < 64 && opar[r] != r; it++) r = opar[r];
    N->id[i] = oid[o];
    N->body[i] = obody[o];
    N->gmask[i] = ogm[o];
    N->parent[i] = rep[r] >= 0 ? rep[r] : i;
  }
  memcpy(m->tri.v, tv, (size_t)nt * 3 * sizeof(int));
  for (int a = 0; a < 9; a++) free(old[a]);
  free(oid); free(opar); free(obody); free(ogm);
  free(src); free(rep); free(tv); free(usez); free(usen); free(anchor);
}

/* Point the model's extra slots at the joint arrays (after any change of n or the arrays). */
static void register_slots(YfSim *s) {
  YfJoints *J = s->joints;
  YfModel *m = &s->model;
  m->nxslot = J && J->n ? 4 * J->n : 0;
  m->xslot_node = J && J->n ? J->node : NULL;
  m->xslot_f = J && J->n ? J->f : NULL;
}

int joints_insert_zone(YfSim *s, const unsigned char *tri_in_zone,
                       int (*prop_of_pair)(void *ctx, int triA, int triB), void *ctx) {
  YfModel *m = &s->model;
  YfJoints *J = jget(s);
  const int nt = m->tri.n;
  int any = 0;
  for (int t = 0; t < nt && !any; t++) any = tri_in_zone[t] != 0;
  if (!any) return 0;
  /* 1. candidate joints on shared edges (by node index, before the split) */
  Edge *E = yf_malloc((size_t)nt * 3 * sizeof *E, "edges");
  for (int t = 0; t < nt; t++)
    for (int c = 0; c < 3; c++) {
      int a = m->tri.v[3 * t + c], b = m->tri.v[3 * t + (c + 1) % 3];
      E[3 * t + c] = (Edge){a < b ? a : b, a < b ? b : a, t, c};
    }
  yf_edges_sort(E, (long)nt * 3);
  NewJoint *nj = yf_malloc(((size_t)nt * 3 / 2 + 1) * sizeof *nj, "joints");
  int nnj = 0;
  for (int i = 0; i < 3 * nt;) {
    int j = i + 1;
    while (j < 3 * nt && E[j].lo == E[i].lo && E[j].hi == E[i].hi) j++;
    if (j == i + 2) { /* exactly two triangles: internal edge (more would be non-manifold) */
      const Edge *ea = &E[i], *eb = &E[i + 1]; /* ea->t < eb->t */
      int A = ea->t, B = eb->t;
      int pa = m->tri.v[3 * A + ea->k], pb = m->tri.v[3 * B + eb->k];
      if (A != B && pa != pb && (tri_in_zone[A] || tri_in_zone[B])) { /* opposite orientation */
        int set = prop_of_pair(ctx, A, B);
        if (set >= 0) {
          if (set >= J->nset) yf_deck_error(NULL, "internal: joint set %d out of range", set);
          nj[nnj++] = (NewJoint){A, ea->k, B, eb->k, set};
        }
      }
    }
    i = j;
  }
  free(E);
  qsort(nj, (size_t)nnj, sizeof *nj, nj_cmp);
  /* 2. split the zone triangles' nodes */
  split_nodes(m, tri_in_zone);
  /* 3. append the joints in creation order */
  int j0 = J->n;
  joints_reserve(J, J->n + nnj);
  for (int q = 0; q < nnj; q++) {
    int j = J->n++;
    const NewJoint *w = &nj[q];
    int *cn = J->corner + 4 * j;
    cn[0] = 3 * w->A + w->kA;             /* p in A */
    cn[1] = 3 * w->A + (w->kA + 1) % 3;   /* q in A */
    cn[2] = 3 * w->B + w->kB;             /* B's edge starts at q */
    cn[3] = 3 * w->B + (w->kB + 1) % 3;   /* ... and ends at p    */
    J->tri[2 * j] = w->A;
    J->tri[2 * j + 1] = w->B;
    J->prop[j] = w->set;
    J->k[j] = 1.0;
    J->w[j] = J->z[j] = 0.0;
    J->dmg[3 * j] = J->dmg[3 * j + 1] = J->dmg[3 * j + 2] = 0.0;
    J->state[j] = 0;
    J->mode[j] = YF_JMODE_NONE;
    J->opened[j] = 0;
    for (int c = 0; c < 8; c++) J->f[8 * j + c] = 0.0;
  }
  free(nj);
  /* 4. node indices of every joint from its corners (earlier joints follow the renumbering) */
  for (int j = 0; j < J->n; j++)
    for (int c = 0; c < 4; c++) J->node[4 * j + c] = m->tri.v[J->corner[4 * j + c]];
  /* 5. heterogeneity in joint index order, one generator per set; initial lengths */
  for (int j = j0; j < J->n; j++) {
    YfJointSet *js = &J->set[J->prop[j]];
    if (js->het != YF_HET_NONE) {
      if (!js->rng) {
        js->rng = gsl_rng_alloc(gsl_rng_mt19937);
        gsl_rng_set(js->rng, js->seed);
      }
      double f;
      if (js->het == YF_HET_WEIBULL) {
        f = gsl_ran_weibull(js->rng, 1.0 / gsl_sf_gamma(1.0 + 1.0 / js->het_par), js->het_par);
      } else {
        do f = 1.0 + js->het_par * gsl_ran_gaussian(js->rng, 1.0); while (!(f > 0.0));
      }
      J->k[j] = f;
    }
    YfJointProp p = js->p;
    p.coh *= J->k[j];
    p.fs *= J->k[j];
    J->fs[j] = joint_fs_init(&p);
    const int *nd = J->node + 4 * j;
    J->L0[j] = hypot(m->node.x0[nd[1]] - m->node.x0[nd[0]], m->node.y0[nd[1]] - m->node.y0[nd[0]]);
  }
  J->nblk = (J->n + JBLOCK - 1) / JBLOCK;
  J->blk_nbreak = yf_realloc(J->blk_nbreak, (size_t)(J->nblk > 0 ? J->nblk : 1) * sizeof(int), "joint blocks");
  J->blk_nopen = yf_realloc(J->blk_nopen, (size_t)(J->nblk > 0 ? J->nblk : 1) * sizeof(int), "joint blocks");
  register_slots(s);
  m->prepared = 0;
  YfEvent ev = {.kind = YF_EV_TOPOLOGY};
  sim_notify(s, &ev);
  return J->n - j0;
}

/* Native pair rule: same body; the joint takes the set of the later fracture command among
 * the two sides (tspec = spec index per triangle, -1 outside every zone). */
typedef struct {
  const YfModel *m;
  const int *tspec;
  const YfFracSpec *spec;
} NativeCtx;

static int native_pair(void *ctx, int A, int B) {
  const NativeCtx *c = ctx;
  if (c->m->tri.body[A] != c->m->tri.body[B]) return -1;
  int sp = c->tspec[A] > c->tspec[B] ? c->tspec[A] : c->tspec[B];
  return sp >= 0 ? c->spec[sp].set : -1;
}

/* Y2D's floor of the softening length, 2 o_p (o_p = 2 h f_t / pen), is on by default; where it is
 * longer than the length that puts G_f under a law's curve (coarse cells, a low penalty or a small
 * G_f), the joints of a law the README says puts exactly G_f under it dissipate more, and nothing
 * said so (G_f 0.1 and 0.01 gave the same bits).  Said once per joint set, for the joints j0.. just
 * made: how many, and the largest factor on the softening length. */
static void warn_floor(YfSim *s, int j0) {
  YfJoints *J = s->joints;
  const YfNodes *n = &s->model.node;
  for (int q = 0; q < J->nset; q++) {
    const YfJointProp *p = &J->set[q].p;
    if (!p->y2d_floor || p->law == YF_SOFT_MUNJIZA) continue; /* (Munjiza's law is Y2D's, floor and all) */
    YfJointProp nf = *p;
    nf.y2d_floor = 0;
    int cnt = 0, tot = 0;
    double worst = 1.0;
    for (int j = j0; j < J->n; j++) {
      if (J->prop[j] != q) continue;
      const int *v = J->node + 4 * j;
      double ex = ((n->x0[v[1]] + n->x0[v[2]]) - (n->x0[v[0]] + n->x0[v[3]])) / 2.0;
      double ey = ((n->y0[v[1]] + n->y0[v[2]]) - (n->y0[v[0]] + n->y0[v[3]])) / 2.0;
      double h = sqrt(ex * ex + ey * ey), on, off;
      joint_lengths(p, h, p->fs, NULL, &on, NULL, NULL);
      joint_lengths(&nf, h, p->fs, NULL, &off, NULL, NULL);
      tot++;
      if (on > off) {
        cnt++;
        if (on / off > worst) worst = on / off;
      }
    }
    if (cnt)
      yf_warn(NULL, "jointprop %s: Y2D's floor of the softening length, 2 o_p = 4 h f_t / pen (floor y2d, the "
              "default), is longer than the one that puts G_f under the law's curve on %d of its %d joints, by up to "
              "%.3g x: they dissipate more than G_f; 'floor none' gives G_f exactly", J->set[q].name, cnt, tot, worst);
  }
}

void joints_insert(YfSim *s) {
  YfJoints *J = s->joints;
  if (!J || !J->nspec) return;
  YfModel *m = &s->model;
  const int nt = m->tri.n;
  int *tspec = yf_malloc((size_t)(nt > 0 ? nt : 1) * sizeof(int), "fracture zone");
  unsigned char *zone = yf_calloc((size_t)(nt > 0 ? nt : 1), 1, "fracture zone");
  for (int t = 0; t < nt; t++) tspec[t] = -1;
  int pending = 0;
  for (int q = 0; q < J->nspec; q++) {
    YfFracSpec *sp = &J->spec[q];
    if (sp->applied) continue;
    pending = 1;
    sp->applied = 1;
    int cnt = 0;
    uint64_t gb = sp->group >= 0 ? (uint64_t)1 << sp->group : 0;
    for (int t = 0; t < nt; t++) {
      if (m->tri.body[t] != sp->body) continue;
      const int *v = m->tri.v + 3 * t;
      if (sp->region >= 0) {
        double cx = (m->node.x0[v[0]] + m->node.x0[v[1]] + m->node.x0[v[2]]) / 3.0;
        double cy = (m->node.y0[v[0]] + m->node.y0[v[1]] + m->node.y0[v[2]]) / 3.0;
        if (!region_contains(sp->region, cx, cy)) continue;
      } else if (sp->group >= 0) {
        int in = (m->tri.gmask[t] & gb) || ((m->node.gmask[v[0]] & gb) && (m->node.gmask[v[1]] & gb) &&
                                            (m->node.gmask[v[2]] & gb));
        if (!in) continue;
      }
      tspec[t] = q;
      zone[t] = 1;
      cnt++;
    }
    if (!cnt) yf_warn(&sp->loc, "fracture: no triangle of body '%s' is in the selection (no joints)", m->body[sp->body].name);
  }
  if (pending) {
    NativeCtx c = {m, tspec, J->spec};
    int j0 = J->n;
    int made = joints_insert_zone(s, zone, native_pair, &c);
    sim_printf(s, "fracture: %d joints inserted (%d in total), %d nodes\n", made, J->n, m->node.n);
    warn_floor(s, j0);
  }
  free(tspec);
  free(zone);
}

/* ---------------- the force stage ---------------- */

/* Work increment of a joint over the last step: -(f_old + f_new)/2 . dx, dx = dt v of each node
 * (the step moved every node by dt v_{n+1/2}); v: vx, vy of its nodes 0..3. */
static inline double work_inc_v(const double *v, const double *fo, const double *fn, double dt) {
  double w = 0;
  for (int c = 0; c < 4; c++)
    w -= 0.5 * ((fo[2 * c] + fn[2 * c]) * v[2 * c] + (fo[2 * c + 1] + fn[2 * c + 1]) * v[2 * c + 1]);
  return w * dt;
}

/* The same with the velocities read from the nodes nd[0..3]. */
static inline double work_inc(const YfNodes *N, const int *nd, const double *fo, const double *fn, double dt) {
  double v[8];
  for (int c = 0; c < 4; c++) {
    v[2 * c] = N->vx[nd[c]];
    v[2 * c + 1] = N->vy[nd[c]];
  }
  return work_inc_v(v, fo, fn, dt);
}

/* Scaled property of joint j (heterogeneity factor on the strengths and the fracture energy). */
static inline void scaled_prop(const YfJoints *J, int j, YfJointProp *lp, int *cur) {
  if (*cur != J->prop[j]) {
    *lp = J->set[J->prop[j]].p;
    *cur = J->prop[j];
  }
  const YfJointProp *b = &J->set[J->prop[j]].p;
  double k = J->k[j];
  lp->ft = b->ft * k;
  lp->fs = b->fs * k;
  lp->coh = b->coh * k;
  lp->gf = b->gf * k;
}

/* The general path of one intact joint: joint_force_geom with the (scaled) property set, the
 * work increment, and the opened / failed marks.  x, y, v: its nodes' positions and velocities. */
static void joint_general(YfJoints *J, int j, const double x[4], const double y[4], const double v[8],
                          double dtp, YfJointProp *lp, int *cur, int *nbreak, int *nopen) {
  scaled_prop(J, j, lp, cur);
  YfJointGeom g;
  joint_geometry_inline(lp->hreg, x, y, &g);
  double f[8];
  YfJointInfo info;
  /* factor 1 (every joint of a homogeneous set): the set's precomputed lengths apply */
  YfJointPre pre;
  const YfJointPre *pc = &J->set[J->prop[j]].pre;
  if (J->k[j] != 1.0) {
    joint_pre_init(lp, &pre);
    pc = &pre;
  }
  int nfail = joint_force_geom(lp, pc, &g, J->fs + j, J->dmg + 3 * j, f, &info);
  double *fj = J->f + 8 * j;
  J->w[j] += work_inc_v(v, fj, f, dtp);
  memcpy(fj, f, sizeof f);
  J->z[j] = info.zmax;
  /* first time past the peak (and past the user's damage threshold): an opened crack */
  if (info.zmax > 0.0 && info.zmax >= J->open_z && !J->opened[j]) {
    J->opened[j] = (unsigned char)(0x80 | (info.mode != YF_JMODE_NONE ? info.mode : YF_JMODE_MIXED));
    (*nopen)++;
  }
  if (YF_JOINT_BROKEN(nfail)) {
    J->state[j] = 1;
    J->mode[j] = (unsigned char)(info.mode != YF_JMODE_NONE ? info.mode : YF_JMODE_MIXED);
    (*nbreak)++;
  }
}

/* The lines of J->f of four joints (four components each, from component c0) as four vectors,
 * one per component, lane l = joint l; and back.  A 4x4 transpose: moves only, exact. */
static inline void rows_to_lanes(const double *r0, const double *r1, const double *r2, const double *r3,
                                 yf_v4 out[4]) {
  yf_v4 a, b, c, d;
  memcpy(&a, r0, sizeof a);
  memcpy(&b, r1, sizeof b);
  memcpy(&c, r2, sizeof c);
  memcpy(&d, r3, sizeof d);
  yf_v4 t0 = YF_SHUF4(a, b, 0, 4, 2, 6), t1 = YF_SHUF4(a, b, 1, 5, 3, 7);
  yf_v4 t2 = YF_SHUF4(c, d, 0, 4, 2, 6), t3 = YF_SHUF4(c, d, 1, 5, 3, 7);
  out[0] = YF_SHUF4(t0, t2, 0, 1, 4, 5);
  out[1] = YF_SHUF4(t1, t3, 0, 1, 4, 5);
  out[2] = YF_SHUF4(t0, t2, 2, 3, 6, 7);
  out[3] = YF_SHUF4(t1, t3, 2, 3, 6, 7);
}

static inline void lanes_to_rows(const yf_v4 in[4], int mask, double *r0, double *r1, double *r2, double *r3) {
  yf_v4 t0 = YF_SHUF4(in[0], in[1], 0, 4, 2, 6), t1 = YF_SHUF4(in[0], in[1], 1, 5, 3, 7);
  yf_v4 t2 = YF_SHUF4(in[2], in[3], 0, 4, 2, 6), t3 = YF_SHUF4(in[2], in[3], 1, 5, 3, 7);
  yf_v4 a = YF_SHUF4(t0, t2, 0, 1, 4, 5), b = YF_SHUF4(t1, t3, 0, 1, 4, 5);
  yf_v4 c = YF_SHUF4(t0, t2, 2, 3, 6, 7), d = YF_SHUF4(t1, t3, 2, 3, 6, 7);
  if (mask & 1) memcpy(r0, &a, sizeof a);
  if (mask & 2) memcpy(r1, &b, sizeof b);
  if (mask & 4) memcpy(r2, &c, sizeof c);
  if (mask & 8) memcpy(r3, &d, sizeof d);
}

/* Whether joint j may be offered to joint_force_fast4: intact, no Mohr-Coulomb (its shear
 * strength never changes), and reversible or not damaged yet (joint_force leaves its state as it
 * is while every point stays before its peak). */
static inline int fast_ok(const YfJoints *J, int j) {
  if (J->state[j]) return 0;
  const YfJointProp *p = &J->set[J->prop[j]].p;
  if (p->coh > 0.0) return 0;
  if (!p->irreversible) return 1;
  const double *d = J->dmg + 3 * j;
  return d[0] == 0.0 && d[1] == 0.0 && d[2] == 0.0;
}

/* The general path for joint j, reading its nodes. */
static void joint_general_n(YfJoints *J, const YfNodes *N, int j, double dtp, YfJointProp *lp, int *cur,
                            int *nbreak, int *nopen) {
  const int *nd = J->node + 4 * j;
  double x[4], y[4], v[8];
  for (int c = 0; c < 4; c++) {
    x[c] = N->x[nd[c]];
    y[c] = N->y[nd[c]];
    v[2 * c] = N->vx[nd[c]];
    v[2 * c + 1] = N->vy[nd[c]];
  }
  joint_general(J, j, x, y, v, dtp, lp, cur, nbreak, nopen);
}

/* Joints jb0 .. jb1-1 (one block), four consecutive joints at a time: the ones fast_ok accepts go
 * through joint_force_fast4 together (their per-joint arrays are one vector load each), and the
 * lanes it declines (a point past its peak) and the others take joint_general.  Each joint's
 * results depend on that joint alone, so the order in which they are done does not matter.
 * A batch of NGRP groups of four goes through the geometry first, then the law and the work: two
 * short loops whose square roots and divisions (the latency of a group) overlap from group to
 * group, where one long loop would leave them in sequence. */
#define NGRP 8
YF_CLONES
static void joints_block(YfJoints *J, const YfNodes *N, int jb0, int jb1, double dtp, int *nbreak_out,
                         int *nopen_out) {
  YfJointProp lp;
  int cur = -1, nbreak = 0, nopen = 0;
  int j = jb0;
  struct {
    YfJointGeom4 g;
    yf_v4 ft, fs, pen, vx[4], vy[4];
  } B[NGRP];
  int elig[NGRP];
  while (j + 4 <= jb1) {
    int ng = (jb1 - j) / 4 < NGRP ? (jb1 - j) / 4 : NGRP;
    for (int q = 0; q < ng; q++) {
      const int jq = j + 4 * q;
      if (jq + 4 * PF_GROUPS + 4 <= jb1) { /* the lines a later group will need (node gathers are not streams) */
        const int *np = J->node + 4 * (jq + 4 * PF_GROUPS);
        for (int l = 0; l < 4; l++) {
          int a = np[4 * l], b = np[4 * l + 3];
          __builtin_prefetch(N->x + a); __builtin_prefetch(N->y + a); __builtin_prefetch(N->vx + a); __builtin_prefetch(N->vy + a);
          __builtin_prefetch(N->x + b); __builtin_prefetch(N->y + b); __builtin_prefetch(N->vx + b); __builtin_prefetch(N->vy + b);
        }
        __builtin_prefetch(J->f + 8 * (jq + 4 * PF_GROUPS), 1);
        __builtin_prefetch(J->f + 8 * (jq + 4 * PF_GROUPS) + 16, 1);
      }
      /* the common case first: four intact joints of one reversible set without Mohr-Coulomb */
      const int *pr = J->prop + jq;
      uint32_t st4;
      memcpy(&st4, J->state + jq, sizeof st4);
      const YfJointProp *p0 = &J->set[pr[0]].p;
      int e;
      if (!st4 && pr[1] == pr[0] && pr[2] == pr[0] && pr[3] == pr[0] && !p0->irreversible && !(p0->coh > 0.0))
        e = 15;
      else
        e = fast_ok(J, jq) | fast_ok(J, jq + 1) << 1 | fast_ok(J, jq + 2) << 2 | fast_ok(J, jq + 3) << 3;
      elig[q] = e;
      if (!e) continue;
      const int *nd = J->node + 4 * jq; /* nd[4 l + c]: node c of lane l */
      const YfJointProp *p1 = &J->set[pr[1]].p, *p2 = &J->set[pr[2]].p, *p3 = &J->set[pr[3]].p;
      const yf_v4 hreg = {p0->hreg, p1->hreg, p2->hreg, p3->hreg}, ft = {p0->ft, p1->ft, p2->ft, p3->ft};
      B[q].pen = (yf_v4){p0->pen, p1->pen, p2->pen, p3->pen};
      yf_v4 k, x[4], y[4];
      memcpy(&k, J->k + jq, sizeof k);
      B[q].ft = ft * k; /* as scaled_prop */
      memcpy(&B[q].fs, J->fs + jq, sizeof B[q].fs);
      for (int c = 0; c < 4; c++) {
        int n0 = nd[c], n1 = nd[4 + c], n2 = nd[8 + c], n3 = nd[12 + c];
        /* through plain arrays: GCC 12 at -O3 takes the vector literals, in the clone without
         * AVX, for partial writes of x[c] and warns (-Wmaybe-uninitialized); same code */
        const double xl[4] = {N->x[n0], N->x[n1], N->x[n2], N->x[n3]}, yl[4] = {N->y[n0], N->y[n1], N->y[n2], N->y[n3]};
        memcpy(&x[c], xl, sizeof xl);
        memcpy(&y[c], yl, sizeof yl);
        B[q].vx[c] = (yf_v4){N->vx[n0], N->vx[n1], N->vx[n2], N->vx[n3]};
        B[q].vy[c] = (yf_v4){N->vy[n0], N->vy[n1], N->vy[n2], N->vy[n3]};
      }
      joint_geometry4(x, y, &hreg, &B[q].g);
    }
    for (int q = 0; q < ng; q++) {
      const int jq = j + 4 * q;
      int done = 0;
      if (elig[q]) {
        yf_v4 f[8];
        done = joint_law4(&B[q].g, &B[q].ft, &B[q].fs, &B[q].pen, f) & elig[q];
        if (done) {
          double *fj = J->f + 8 * jq;
          yf_v4 fo[8];
          rows_to_lanes(fj, fj + 8, fj + 16, fj + 24, fo);
          rows_to_lanes(fj + 4, fj + 12, fj + 20, fj + 28, fo + 4);
          /* work_inc_v lane by lane (v: vx, vy of node c) */
          yf_v4 w = {0.0, 0.0, 0.0, 0.0};
          for (int c = 0; c < 4; c++)
            w -= 0.5 * ((fo[2 * c] + f[2 * c]) * B[q].vx[c] + (fo[2 * c + 1] + f[2 * c + 1]) * B[q].vy[c]);
          w = w * dtp;
          lanes_to_rows(f, done, fj, fj + 8, fj + 16, fj + 24);
          lanes_to_rows(f + 4, done, fj + 4, fj + 12, fj + 20, fj + 28);
          if (done == 15) {
            yf_v4 wj;
            const yf_v4 zero = {0.0, 0.0, 0.0, 0.0};
            memcpy(&wj, J->w + jq, sizeof wj);
            wj = wj + w;
            memcpy(J->w + jq, &wj, sizeof wj);
            memcpy(J->z + jq, &zero, sizeof zero);
          } else {
            for (int l = 0; l < 4; l++)
              if (done >> l & 1) {
                J->w[jq + l] += w[l];
                J->z[jq + l] = 0.0;
              }
          }
        }
      }
      if (done != 15)
        for (int l = 0; l < 4; l++)
          if (!(done >> l & 1) && !J->state[jq + l]) joint_general_n(J, N, jq + l, dtp, &lp, &cur, &nbreak, &nopen);
    }
    j += 4 * ng;
  }
  for (; j < jb1; j++)
    if (!J->state[j]) joint_general_n(J, N, j, dtp, &lp, &cur, &nbreak, &nopen);
  *nbreak_out = nbreak;
  *nopen_out = nopen;
}

/* ---- MPI ranks: block b is evaluated by the rank owning its first joint's lower triangle
 * (joints are sorted by it, so each rank's blocks are one range, in rank order).  The pending
 * (failed) joints, break and opening marks are replicated on every rank; forces, work, damage and
 * shear strength are current on the owner (joints_par_gather makes them whole for a reader). */
static int *J_lo, J_nlo, J_dirty;
static double *J_ev, *J_mxy, *J_rmxy; /* events; the records' coordinate sums (J_rmxy: next one) */
static size_t J_cev, J_cmxy;

/* The exchange buffer J_ev with room for n doubles. */
static double *J_ev_room(size_t n) {
  if (J_cev < n) {
    J_cev = n + 1024;
    free(J_ev);
    J_ev = yf_malloc(J_cev * sizeof(double), "joint events");
  }
  return J_ev;
}

/* The sums of a joint's 4 nodes' coordinates (its record's midpoint is a quarter of them). */
static void node_sums(const YfNodes *N, const int *nd, double *mx, double *my) {
  double sx = 0, sy = 0;
  for (int c = 0; c < 4; c++) {
    sx += N->x[nd[c]];
    sy += N->y[nd[c]];
  }
  *mx = sx;
  *my = sy;
}

static int mine_blocks(const YfJoints *J, int *b0, int *b1) {
  const int S = par_size();
  if (S <= 1) return 0;
  if (J_nlo < S + 1) {
    free(J_lo);
    J_lo = yf_malloc(((size_t)S + 1) * sizeof(int), "joint ranges");
    J_nlo = S + 1;
  }
  /* the first joint of each block: its lower triangle is J->tri[2 JBLOCK b] or the other one */
  int nb = J->nblk;
  int *key = yf_malloc((size_t)(nb + 1) * sizeof(int), "joint ranges");
  for (int b = 0; b < nb; b++) {
    int a = J->tri[2 * b * JBLOCK], c = J->tri[2 * b * JBLOCK + 1];
    key[b] = a < c ? a : c;
  }
  int dist = par_owner_ranges(key, 1, nb, J_lo);
  free(key);
  if (!dist) return 0;
  *b0 = J_lo[par_rank()];
  *b1 = J_lo[par_rank() + 1];
  return 1;
}

/* After this rank's blocks: every rank learns the pending joints' final work (their dissipation is
 * added in joint order), the joints opened and the joints failed, so every rank records them as
 * one rank does. */
static void share_events(YfJoints *J, const YfNodes *N, int b0, int b1) {
  const int nj = J->n;
  size_t n = 0;
  for (int q = 0; q < J->npend; q++) n += J->pend[q] / JBLOCK >= b0 && J->pend[q] / JBLOCK < b1;
  for (int b = b0; b < b1; b++) n += (size_t)J->blk_nbreak[b] + (size_t)J->blk_nopen[b];
  J_ev_room(5 * n + 5);
  /* (joint, kind, value, mx, my): 0 work of a pending joint, 1 opened, 2 failed; mx, my: the sums
   * of its 4 nodes' coordinates for the records, from the owner (other ranks may not hold them
   * current: the divided update) */
  double *o = J_ev;
  for (int q = 0; q < J->npend; q++) {
    int j = J->pend[q];
    if (j / JBLOCK >= b0 && j / JBLOCK < b1) { *o++ = j; *o++ = 0; *o++ = J->w[j]; *o++ = 0; *o++ = 0; }
  }
  for (int b = b0; b < b1; b++) {
    if (!J->blk_nbreak[b] && !J->blk_nopen[b]) continue;
    int j1 = (b + 1) * JBLOCK < nj ? (b + 1) * JBLOCK : nj;
    for (int j = b * JBLOCK; j < j1; j++) {
      double mx = 0, my = 0;
      if ((J->opened[j] & 0x80) || J->state[j] == 1) node_sums(N, J->node + 4 * j, &mx, &my);
      if (J->opened[j] & 0x80) { *o++ = j; *o++ = 1; *o++ = J->opened[j]; *o++ = mx; *o++ = my; }
      if (J->state[j] == 1) { *o++ = j; *o++ = 2; *o++ = J->mode[j]; *o++ = mx; *o++ = my; }
    }
  }
  for (int b = 0; b < J->nblk; b++)
    if (b < b0 || b >= b1) J->blk_nbreak[b] = J->blk_nopen[b] = 0;
  int S = par_size();
  int *rb = yf_malloc(((size_t)S + 1) * sizeof(int), "joint events");
  const double *a = par_concat(J_ev, (int)((o - J_ev) * (long)sizeof(double)), rb);
  size_t tot = 0;
  for (int r = 0; r < S; r++) tot += (size_t)rb[r] / sizeof(double);
  free(rb);
  size_t nmxy = 0, no = 0;
  for (size_t t = 0; t < tot; t += 5) {
    nmxy += (int)a[t + 1] != 0;
    no += (int)a[t + 1] == 1;
  }
  if (J_cmxy < 2 * nmxy + 2) {
    J_cmxy = 2 * nmxy + 2 + 256;
    free(J_mxy);
    J_mxy = yf_malloc(J_cmxy * sizeof(double), "joint events");
  }
  /* the records' coordinates in the records' order: the opened joints in joint order, then the
   * failed ones (rank order = joint order) */
  double *om = J_mxy, *fm = J_mxy + 2 * no;
  J_rmxy = J_mxy;
  for (size_t t = 0; t < tot; t += 5) {
    int j = (int)a[t], kind = (int)a[t + 1], b = j / JBLOCK;
    if (kind == 0) {
      J->w[j] = a[t + 2];
      J->diss_broken += a[t + 2];
    } else if (kind == 1) {
      J->opened[j] = (unsigned char)a[t + 2];
      if (b < b0 || b >= b1) J->blk_nopen[b]++;
      *om++ = a[t + 3];
      *om++ = a[t + 4];
    } else {
      J->state[j] = 1;
      J->mode[j] = (unsigned char)a[t + 2];
      if (b < b0 || b >= b1) J->blk_nbreak[b]++;
      *fm++ = a[t + 3];
      *fm++ = a[t + 4];
    }
  }
}

int joints_par_rows(const YfSim *s, int *lo) {
  const YfJoints *J = s->joints;
  int b0, b1;
  if (!J || !J->n || !mine_blocks(J, &b0, &b1)) return 0;
  for (int r = 0; r <= par_size(); r++) lo[r] = J_lo[r] * JBLOCK < J->n ? J_lo[r] * JBLOCK : J->n;
  return 1;
}

/* What only a block's owner keeps current: forces, damage, work, opening, shear force. */
enum { J_OWNED = 5 };
static void owned_arrays(YfJoints *J, void **a, int *bytes) {
  void *arr[J_OWNED] = {J->f, J->dmg, J->w, J->z, J->fs};
  const int by[J_OWNED] = {8 * sizeof(double), 3 * sizeof(double), sizeof(double), sizeof(double), sizeof(double)};
  memcpy(a, arr, sizeof arr);
  memcpy(bytes, by, sizeof by);
}

void joints_par_gather(YfSim *s) {
  YfJoints *J = s->joints;
  if (!J || !J->n || !J_dirty || par_size() <= 1) return;
  int *lo = yf_malloc(((size_t)par_size() + 1) * sizeof(int), "joint gather");
  if (joints_par_rows(s, lo)) {
    J_dirty = 0;
    void *a[J_OWNED];
    int by[J_OWNED];
    owned_arrays(J, a, by);
    for (int k = 0; k < J_OWNED; k++) par_gather_ranges(a[k], lo, by[k]);
  }
  free(lo);
}

void joints_par_move(YfSim *s, const int *lo_old) {
  YfJoints *J = s->joints;
  if (!J || !J->n || !J_dirty || par_size() <= 1) return; /* (whole on every rank: nothing to move) */
  int *lo = yf_malloc(((size_t)par_size() + 1) * sizeof(int), "joint ranges");
  if (joints_par_rows(s, lo)) {
    void *a[J_OWNED];
    int by[J_OWNED];
    owned_arrays(J, a, by);
    for (int k = 0; k < J_OWNED; k++) par_move_ranges(a[k], lo_old, lo, by[k]);
  }
  free(lo);
}

void joints_forces(YfSim *s) {
  YfJoints *J = s->joints;
  if (!J || !J->n) return;
  const YfNodes *N = &s->model.node;
  const double dtp = J->dt_prev;
  static const double zero8[8] = {0, 0, 0, 0, 0, 0, 0, 0};
  /* joints that failed at the last evaluation: their forces acted over the last step; close
   * their work and drop them */
  const int nj = J->n, nblk = J->nblk;
  int b0 = 0, b1 = nblk, dist = mine_blocks(J, &b0, &b1); /* MPI: this rank's blocks */
  for (int q = 0; q < J->npend; q++) {
    int j = J->pend[q];
    if (j / JBLOCK >= b0 && j / JBLOCK < b1) {
      J->w[j] += work_inc(N, J->node + 4 * j, J->f + 8 * j, J->f + 8 * j, dtp) ;
      if (!dist) J->diss_broken += J->w[j];
    }
    J->state[j] = 2;
    memcpy(J->f + 8 * j, zero8, sizeof zero8);
  }
  /* dynamic: a block of intact joints costs a fraction of one past its peak (scalar law, softening
   * curve), and the damaged ones cluster where the scene breaks; results are per joint and per
   * block, so the schedule cannot change a bit */
  const double t0 = dist ? par_work_clock() : 0.0;
  YF_PARFOR_IF(nj >= par_min, schedule(dynamic, 8), for (int b = b0; b < b1; b++) {
    int jb1 = (b + 1) * JBLOCK < nj ? (b + 1) * JBLOCK : nj;
    joints_block(J, N, b * JBLOCK, jb1, dtp, &J->blk_nbreak[b], &J->blk_nopen[b]);
  });
  if (dist) par_note_work(par_work_clock() - t0);
  if (dist) share_events(J, N, b0, b1);
  J->npend = 0;
  J_dirty = 1;
  /* record the newly opened joints in joint order (before the breaks of the same step) */
  for (int b = 0; b < nblk; b++) {
    if (!J->blk_nopen[b]) continue;
    int j1 = (b + 1) * JBLOCK < nj ? (b + 1) * JBLOCK : nj;
    for (int j = b * JBLOCK; j < j1; j++) {
      if (!(J->opened[j] & 0x80)) continue;
      J->opened[j] &= 0x7f;
      if (J->nopened == J->caporec) {
        J->caporec = J->caporec ? 2 * J->caporec : 256;
        J->orec = yf_realloc(J->orec, (size_t)J->caporec * sizeof *J->orec, "opened record");
      }
      double mx, my;
      if (dist) { mx = *J_rmxy++; my = *J_rmxy++; } /* MPI: from the owner (share_events) */
      else node_sums(N, J->node + 4 * j, &mx, &my);
      J->orec[J->nopened++] = (YfBreak){s->step + 1, s->time, 0.25 * mx, 0.25 * my, J->L0[j], J->opened[j],
                                         J->tri[2 * j], J->tri[2 * j + 1], j};
    }
  }
  /* record the new breaks in joint order */
  for (int b = 0; b < nblk; b++) {
    if (!J->blk_nbreak[b]) continue;
    int j1 = (b + 1) * JBLOCK < nj ? (b + 1) * JBLOCK : nj;
    for (int j = b * JBLOCK; j < j1; j++) {
      if (J->state[j] != 1) continue;
      J->pend[J->npend++] = j;
      J->nbroken++;
      if (J->nrec == J->caprec) {
        J->caprec = J->caprec ? 2 * J->caprec : 256;
        J->rec = yf_realloc(J->rec, (size_t)J->caprec * sizeof *J->rec, "break record");
      }
      double mx, my;
      if (dist) { mx = *J_rmxy++; my = *J_rmxy++; }
      else node_sums(N, J->node + 4 * j, &mx, &my);
      J->rec[J->nrec++] = (YfBreak){s->step + 1, s->time, 0.25 * mx, 0.25 * my, J->L0[j], J->mode[j],
                                     J->tri[2 * j], J->tri[2 * j + 1], j};
    }
  }
  J->dt_prev = s->dt;
}

/* ---------------- energy ---------------- */

/* Energy stored in joint j at positions x, y after an evaluation that left dmg3 and returned f:
 * the exact pre-peak potential while undamaged, else the secant energy -1/2 (f0 . d_a + f1 . d_b)
 * (= 1/2 Simpson integral of q . d, exact for secant unloading). */
static double stored_irrev(const YfJointProp *p, const double *x, const double *y, const double *f,
                           const double *dmg3, double fs) {
  double dax = x[0] - x[3], day = y[0] - y[3], dbx = x[1] - x[2], dby = y[1] - y[2];
  if (dmg3[0] > 0 || dmg3[1] > 0 || dmg3[2] > 0)
    return -0.5 * (f[0] * dax + f[1] * day + f[2] * dbx + f[3] * dby);
  double ex = ((x[1] + x[2]) - (x[0] + x[3])) / 2.0, ey = ((y[1] + y[2]) - (y[0] + y[3])) / 2.0;
  double h = sqrt(ex * ex + ey * ey);
  double hr = h + p->hreg > 0.0 ? h + p->hreg : 1.0; /* as joint_force */
  double e1x = ex / hr, e1y = ey / hr, nx = -e1y, ny = e1x;
  double op, sp;
  joint_lengths(p, h, fs, &op, NULL, &sp, NULL);
  double oa = dax * nx + day * ny, ob = dbx * nx + dby * ny, sa = dax * e1x + day * e1y, sb = dbx * e1x + dby * e1y;
  double po[3] = {oa, 0.5 * (oa + ob), ob}, ps[3] = {sa, 0.5 * (sa + sb), sb}, wt[3] = {h / 6, 2 * h / 3, h / 6};
  double e = 0;
  for (int k = 0; k < 3; k++) {
    double o = po[k], r = fabs(ps[k]) / sp, en;
    if (o < 0) en = o * o * p->ft / op; /* penalty o p/h, integrated */
    else {
      double ro = o / op;
      en = p->ft * op * (ro * ro - ro * ro * ro / 3.0);
    }
    en += fs * sp * (r * r - r * r * r / 3.0);
    e += wt[k] * en;
  }
  return e;
}

/* Stored and dissipated energy of the intact joints of block b (joint order) into e[0], e[1]. */
static void block_energy(YfJoints *J, const YfNodes *N, int b, double *e) {
  YfJointProp lp;
  int cur = -1;
  double stored = 0.0, diss = 0.0;
  const int j1 = (b + 1) * JBLOCK < J->n ? (b + 1) * JBLOCK : J->n;
  for (int j = b * JBLOCK; j < j1; j++) {
    if (J->state[j]) continue;
    scaled_prop(J, j, &lp, &cur);
    const int *nd = J->node + 4 * j;
    double x[4], y[4], f[8], fs = J->fs[j], dmg[3] = {J->dmg[3 * j], J->dmg[3 * j + 1], J->dmg[3 * j + 2]};
    for (int c = 0; c < 4; c++) {
      x[c] = N->x[nd[c]];
      y[c] = N->y[nd[c]];
    }
    joint_force(&lp, x, y, &fs, dmg, f, NULL);
    /* work up to the current positions (the last step is not yet in w) */
    double W = J->w[j] + work_inc(N, nd, J->f + 8 * j, f, J->dt_prev);
    double en = lp.irreversible ? stored_irrev(&lp, x, y, f, dmg, fs) : W;
    stored += en;
    diss += W - en;
  }
  e[0] = stored;
  e[1] = diss;
}

/* Per block of joints (stored, dissipated), and the pending joints' final work in pend order. */
static double *JE, *JP;
static int JE_cap, JP_cap;

double joints_energy(YfSim *s, int dist) {
  YfJoints *J = s->joints;
  if (!J || !J->n) return 0.0;
  const YfNodes *N = &s->model.node;
  const int nb = J->nblk, np = J->npend;
  if (JE_cap < 2 * nb + 2) {
    free(JE);
    JE_cap = 2 * nb + 2;
    JE = yf_malloc((size_t)JE_cap * sizeof(double), "joint energies");
  }
  if (JP_cap < np + 1) {
    free(JP);
    JP_cap = np + 1;
    JP = yf_malloc((size_t)JP_cap * sizeof(double), "joint energies");
  }
  /* blocks in parallel, each in joint order; MPI (dist): this rank's blocks, whose joints' forces,
   * work and damage it alone holds current, then every block's pair from its owner */
  int b0 = 0, b1 = nb;
  const int mine = dist && mine_blocks(J, &b0, &b1);
  YF_PARFOR_IF(J->n >= par_min, schedule(dynamic, 8), for (int b = b0; b < b1; b++) block_energy(J, N, b, JE + 2 * b););
  for (int q = 0; q < np; q++) {
    const int j = J->pend[q];
    JP[q] = !mine || (j / JBLOCK >= b0 && j / JBLOCK < b1) ? J->w[j] + work_inc(N, J->node + 4 * j, J->f + 8 * j, J->f + 8 * j, J->dt_prev) : 0.0;
  }
  if (mine) {
    par_gather_ranges(JE, J_lo, 2 * (int)sizeof(double));
    /* the pending joints' work from their owners: (q, value) pairs, every rank's */
    double *o = J_ev_room(2 * (size_t)np + 2), *w = o;
    for (int q = 0; q < np; q++)
      if (J->pend[q] / JBLOCK >= b0 && J->pend[q] / JBLOCK < b1) { *w++ = q; *w++ = JP[q]; }
    int *rb = yf_malloc(((size_t)par_size() + 1) * sizeof(int), "joint energies");
    const double *a = par_concat(o, (int)((w - o) * (long)sizeof(double)), rb);
    size_t tot = 0;
    for (int r = 0; r < par_size(); r++) tot += (size_t)rb[r] / sizeof(double);
    free(rb);
    for (size_t t = 0; t < tot; t += 2) JP[(int)a[t]] = a[t + 1];
  }
  double stored = 0.0, diss = J->diss_broken;
  for (int q = 0; q < np; q++) diss += JP[q];
  for (int b = 0; b < nb; b++) {
    stored += JE[2 * b];
    diss += JE[2 * b + 1];
  }
  s->energy.joint_dissipated = diss;
  return stored;
}

/* ---------------- stable time step ---------------- */

/* Row sums of the joint stiffness in units of p: 1 pre-peak (below); x1.25 because past the peak
 * opening and slip are coupled (f(z) depends on both, ALGORITHMS 3.3-3.4) and the joint's tangent
 * then exceeds p/h in some direction: docs/STABILITY.md measured fracture_bar unstable at 0.96 of
 * the limit without this margin. */
#define JOINT_ROW 1.25

int joints_node_penalty(const YfSim *s, double *P, int *jof) {
  const YfJoints *J = s->joints;
  if (!J || !J->n) return 0;
  /* A joint is, pre-peak, an isotropic interface of stiffness p/h per length; its consistent 4x4
   * stiffness (per direction) has absolute row sums p h (1/3 + 1/6 + 1/3 + 1/6)/h = p for every
   * node, whatever h: Gershgorin bounds the joints' part of omega^2 by P_i / m_i (JOINT_ROW). */
  int any = 0;
  for (int j = 0; j < J->n; j++) {
    if (J->state[j]) continue;
    double pj = JOINT_ROW * J->set[J->prop[j]].p.pen;
    for (int c = 0; c < 4; c++) {
      int i = J->node[4 * j + c];
      P[i] += pj;
      if (jof[i] < 0) jof[i] = j;
    }
    any = 1;
  }
  return any;
}

void joints_describe(const YfSim *s, int j, char *what, size_t n) {
  const YfJoints *J = s->joints;
  snprintf(what, n, "joint %d (jointprop %s, triangles %d/%d)", j, J->set[J->prop[j]].name,
           s->model.tri.id[J->tri[2 * j]], s->model.tri.id[J->tri[2 * j + 1]]);
}

/* ---------------- statistics ---------------- */

long joints_count(const YfSim *s) { return s->joints ? s->joints->n : 0; }
long joints_broken(const YfSim *s) { return s->joints ? s->joints->nbroken : 0; }

const YfBreak *joints_opened(const YfSim *s, int *n) {
  *n = s->joints ? s->joints->nopened : 0;
  return s->joints ? s->joints->orec : NULL;
}

const YfBreak *joints_breaks(const YfSim *s, int *n) {
  *n = s->joints ? s->joints->nrec : 0;
  return s->joints ? s->joints->rec : NULL;
}

static int uf_find(int *par, int i) {
  while (par[i] != i) {
    par[i] = par[par[i]];
    i = par[i];
  }
  return i;
}
static void uf_union(int *par, int a, int b) {
  a = uf_find(par, a);
  b = uf_find(par, b);
  if (a != b) {
    if (a < b) par[b] = a;
    else par[a] = b;
  }
}

int joints_fragments(const YfSim *s, int *frag) {
  const YfModel *m = &s->model;
  const int nt = m->tri.n, nn = m->node.n;
  if (!nt) return 0;
  int *par = yf_malloc((size_t)nt * sizeof(int), "fragments");
  int *first = yf_malloc((size_t)(nn > 0 ? nn : 1) * sizeof(int), "fragments");
  for (int t = 0; t < nt; t++) par[t] = t;
  for (int i = 0; i < nn; i++) first[i] = -1;
  for (int t = 0; t < nt; t++)
    for (int c = 0; c < 3; c++) {
      int v = m->tri.v[3 * t + c];
      if (first[v] < 0) first[v] = t;
      else uf_union(par, first[v], t);
    }
  const YfJoints *J = s->joints;
  if (J)
    for (int j = 0; j < J->n; j++)
      if (!J->state[j]) uf_union(par, J->tri[2 * j], J->tri[2 * j + 1]);
  int nf = 0;
  int *id = yf_malloc((size_t)nt * sizeof(int), "fragments");
  for (int t = 0; t < nt; t++) id[t] = -1;
  for (int t = 0; t < nt; t++) {
    int r = uf_find(par, t);
    if (id[r] < 0) id[r] = nf++;
    if (frag) frag[t] = id[r];
  }
  free(id);
  free(par);
  free(first);
  return nf;
}

void joints_free(YfSim *s) {
  YfJoints *J = s->joints;
  if (!J) return;
  for (int i = 0; i < J->nset; i++)
    if (J->set[i].rng) gsl_rng_free(J->set[i].rng);
  free(J->set); free(J->spec);
  free(J->corner); free(J->node); free(J->tri); free(J->prop); free(J->k); free(J->fs); free(J->dmg);
  free(J->w); free(J->z); free(J->L0); free(J->state); free(J->mode); free(J->f); free(J->pend);
  free(J->blk_nbreak); free(J->rec); free(J->opened); free(J->blk_nopen); free(J->orec);
  free(J);
  s->joints = NULL;
  s->model.nxslot = 0;
  s->model.xslot_node = NULL;
  s->model.xslot_f = NULL;
}
