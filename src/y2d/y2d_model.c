/* y2d_model.c: a Y2D input deck as a yfdem scene (read_y2d), and Y2D's boundary-condition sets
 * inside the step.
 *
 * This module owns the translation of a YfY2d (y2d_read.c: plain arrays, Y2D defaults) into the
 * model: nodes keep their input numbers as ids, triangles their input element index (in input
 * order, so input element e is triangle tri0 + e), each element property becomes one material and
 * one body, joint meshing rows (code 3) insert joints through joint.c, MICOUP > 0 switches on
 * contact through contact.c.  It also owns the two Y2D stages run.c calls when s->y2d is set:
 *
 *  - y2d_apply_loads: the exact consistent edge loads of ALGORITHMS 2.5 (linearly varying pressure
 *    and shear traction over every triangle edge whose two nodes carry loaded sets; Y2D's quirk of
 *    loading interior edges too is kept), at positions x_n and time factors of t_n;
 *  - y2d_update_velocities: ALGORITHMS 7 per node of mass > 1e-10: gravity m g_y added in global
 *    y, force and velocity into the set's local frame, per local direction kind 1 force, 2
 *    acceleration, 3 prescribed velocity, anything else frozen, back to global.
 *
 * Time tables follow Y2D: piecewise linear, factor 1.0 outside a table's time range (not the end
 * value), all tables off when the first time of set 0 is -1 (y2d_read sets tables_on).
 *
 * The work done on the nodes by loads, prescribed motions and frozen directions is accumulated
 * into s->energy.external_work (reaction R = m dv/dt - f_internal - m g, at the mean of the two
 * half-step velocities), so the energy balance and the run's energy check stay meaningful.
 * Units: whatever the deck uses (reference decks SI, 2D per unit thickness).
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "y2d_model.h"

#include "par.h"
#include "parfor.h"
#include "yfvec.h"
#include "y2d_read.h"
#include "contact.h"
#include "err.h"
#include "joint.h"
#include "run.h"
#include "partition.h"

/* r->set of a deck node whose BC set is outside 0..NPNSET-1: Y2D never moves it (-1: a node of
 * native commands, no set) */
#define Y2D_FROZEN (-2)

static YfY2d *deck_of(const YfY2dRun *r) { return (YfY2d *)r->deck; }

/* ------------------------------------------------------------------ index maps */

int y2d_tri_of_elem(const YfSim *s, long e) {
  if (e < 0) return -1;
  if (s->y2d) return e < s->y2d->ntri ? partition_tri(&s->model, s->y2d->tri0 + (int)e) : -1; /* through the renumbering */
  for (int t = 0; t < s->model.tri.n; t++)
    if (s->model.tri.id[t] == e) return t;
  return -1;
}

/* Nodes keep their input number as id, and joint insertion gives copies the id of the original
 * (joint.h), so the id is the input number even after nodes are renumbered. */
int y2d_input_node(const YfSim *s, int i) { return s->model.node.id[i]; }

/* ------------------------------------------------------------------ time factors */

/* Factor of set b at time t: linear in the table; 1.0 outside its range or without tables. */
static double set_factor(const YfY2dRun *r, int b, double t) {
  if (!r->tables_on || r->npts < 1) return 1.0;
  const double *tt = r->tt + (size_t)b * r->npts, *tf = r->tf + (size_t)b * r->npts;
  for (int i = 0; i + 1 < r->npts; i++) {
    if (t >= tt[i] && t <= tt[i + 1] && tt[i + 1] > tt[i])
      return tf[i] + (tf[i + 1] - tf[i]) * (t - tt[i]) / (tt[i + 1] - tt[i]);
  }
  return 1.0;
}

/* ------------------------------------------------------------------ per-node resolution */

/* Sets of nodes and the list of loaded edges for the current topology (after joint insertion the
 * triangles use copies; a copy inherits the set of the node it was copied from). */
static void resolve(YfSim *s, YfY2dRun *r) {
  YfModel *m = &s->model;
  const YfNodes *n = &m->node;
  r->nn = n->n;
  free(r->set);
  free(r->lf);
  free(r->le);
  r->lf = NULL;
  r->le = NULL;
  r->set = yf_malloc((size_t)(n->n + 1) * sizeof(int), "y2d node sets");
  r->nublk = (n->n + Y2D_UBLOCK - 1) / Y2D_UBLOCK;
  free(r->ublk);
  r->ublk = yf_calloc((size_t)r->nublk + 1, sizeof(double), "y2d update blocks");
  /* a node of the deck (or a copy of one: copies keep group masks and ids) has the set of its
   * input node; nodes added by native commands have none */
  for (int i = 0; i < n->n; i++) {
    int in = n->id[i];
    int mine = (n->gmask[i] & r->gbit) && in >= 0 && in < r->nnode;
    r->set[i] = mine ? r->setof[in] : -1;
    if (mine && (r->set[i] < 0 || r->set[i] >= r->nset)) r->set[i] = Y2D_FROZEN; /* never moved (FORMAT.md 6) */
  }
  /* triangle edges whose two end nodes both carry a pressure or both a shear traction (counted,
   * then listed: scenes without edge loads keep no per-node load array) */
  for (int pass = 0; pass < 2; pass++) {
    r->nle = 0;
    for (int e = 0; e < r->ntri; e++) {
      int t = partition_tri(m, r->tri0 + e);
      const int *v = m->tri.v + 3 * t;
      for (int j = 0; j < 3; j++) {
        int a = r->set[v[j]], b = r->set[v[(j + 1) % 3]];
        if (a < 0 || b < 0) continue;
        if ((r->ap[a] != 0 && r->ap[b] != 0) || (r->at[a] != 0 && r->at[b] != 0)) {
          if (pass) {
            r->le[2 * r->nle] = t;
            r->le[2 * r->nle + 1] = j;
          }
          r->nle++;
        }
      }
    }
    if (!pass) {
      if (!r->nle) break;
      r->le = yf_malloc((size_t)(2 * r->nle) * sizeof(int), "y2d loaded edges");
      r->lf = yf_calloc((size_t)(2 * n->n + 2), sizeof(double), "y2d edge loads");
    }
  }
}

/* ------------------------------------------------------------------ step stages */

void y2d_apply_loads(YfSim *s) {
  YfY2dRun *r = s->y2d;
  if (!r) return;
  YfNodes *n = &s->model.node;
  if (r->nn != n->n) resolve(s, r);
  for (int b = 0; b < r->nset; b++) r->phi[b] = set_factor(r, b, s->time);
  if (!r->nle) return;
  const int *tv = s->model.tri.v;
  /* clear last step's loads on the loaded nodes */
  for (int k = 0; k < r->nle; k++) {
    const int *v = tv + 3 * r->le[2 * k];
    int j = r->le[2 * k + 1];
    int a = v[j], b = v[(j + 1) % 3];
    r->lf[2 * a] = r->lf[2 * a + 1] = r->lf[2 * b] = r->lf[2 * b + 1] = 0.0;
  }
  const double *x = n->x, *y = n->y;
  for (int k = 0; k < r->nle; k++) {
    const int *v = tv + 3 * r->le[2 * k];
    int jj = r->le[2 * k + 1];
    int j = v[jj], kk = v[(jj + 1) % 3];
    int sj = r->set[j], sk = r->set[kk];
    double nx = y[kk] - y[j], ny = x[j] - x[kk]; /* outward normal, length L */
    double tx = x[kk] - x[j], ty = y[kk] - y[j]; /* CCW tangent, length L */
    double fjx = 0, fjy = 0, fkx = 0, fky = 0;
    double pj = r->ap[sj] * r->phi[sj], pk = r->ap[sk] * r->phi[sk];
    if (fabs(pj) > 1e-10 && fabs(pk) > 1e-10) {
      double wj = pj / 3.0 + pk / 6.0, wk = pj / 6.0 + pk / 3.0;
      fjx -= nx * wj; fjy -= ny * wj;
      fkx -= nx * wk; fky -= ny * wk;
    }
    double qj = r->at[sj] * r->phi[sj], qk = r->at[sk] * r->phi[sk];
    if (fabs(qj) > 1e-10 && fabs(qk) > 1e-10) {
      double wj = qj / 3.0 + qk / 6.0, wk = qj / 6.0 + qk / 3.0;
      fjx += tx * wj; fjy += ty * wj;
      fkx += tx * wk; fky += ty * wk;
    }
    n->fx[j] += fjx; n->fy[j] += fjy;
    n->fx[kk] += fkx; n->fy[kk] += fky;
    r->lf[2 * j] += fjx; r->lf[2 * j + 1] += fjy;
    r->lf[2 * kk] += fkx; r->lf[2 * kk + 1] += fky;
  }
}

/* Nodes i0..i1-1 of the velocity update; returns the external work of this range [J/m].
 * Velocities follow ALGORITHMS 7 operation by operation (same bits as a serial loop whatever the
 * range).  The work of node i is dt R.(v0 + v1)/2 with R = m (v1 - v0)/dt - f_int - m g, written
 * multiplied through by dt so that no division is needed. */
/* Y2D's update of one node i that has a BC set (b >= 0) and mass above 1e-10; returns its
 * external work increment (see update_range). */
static inline double update_one(const YfY2dRun *r, YfNodes *n, double dt, int i, double *vxo, double *vyo) {
  const int b = r->set[i];
  const double m = n->m[i], gy = r->gy, vx0 = n->vx[i], vy0 = n->vy[i], *lf = r->lf;
  const double *R = r->R + 4 * b, *Ri = r->Ri + 4 * b;
  double gfx = n->fx[i], gfy = n->fy[i] + m * gy; /* gravity as a force in global y */
  double u0 = Ri[0] * vx0 + Ri[1] * vy0, u1 = Ri[2] * vx0 + Ri[3] * vy0;
  double q0 = Ri[0] * gfx + Ri[1] * gfy, q1 = Ri[2] * gfx + Ri[3] * gfy;
  /* per local direction: kind 1 force u += dt (A + q)/m, 2 acceleration u += dt (A + q/m),
   * 3 prescribed velocity u = A, anything else frozen (velocity kept, forces ignored); the two
   * directions' divisions by m as one pair */
  const int k0 = r->kind[2 * b], k1 = r->kind[2 * b + 1];
  const double A0 = r->acur[2 * b], A1 = r->acur[2 * b + 1];
  double d0, d1;
  yf_div2(k0 == Y2D_KIND_FORCE ? dt * (A0 + q0) : q0, m, k1 == Y2D_KIND_FORCE ? dt * (A1 + q1) : q1, m, &d0, &d1);
  u0 = k0 == Y2D_KIND_FORCE ? u0 + d0 : k0 == Y2D_KIND_ACCEL ? u0 + dt * (A0 + d0) : k0 == Y2D_KIND_VELOCITY ? A0 : u0;
  u1 = k1 == Y2D_KIND_FORCE ? u1 + d1 : k1 == Y2D_KIND_ACCEL ? u1 + dt * (A1 + d1) : k1 == Y2D_KIND_VELOCITY ? A1 : u1;
  double vx1 = R[0] * u0 + R[1] * u1, vy1 = R[2] * u0 + R[3] * u1;
  if (vxo) { /* the step's old velocities, for bc.c's supports (fused: no extra pass) */
    vxo[i] = vx0;
    vyo[i] = vy0;
  }
  n->vx[i] = vx1;
  n->vy[i] = vy1;
  /* work of everything that is not an internal force: loads, supports, prescribed motion
   * (gravity's work is counted by run.c from positions) */
  double lfx = lf ? lf[2 * i] : 0.0, lfy = lf ? lf[2 * i + 1] : 0.0; /* no edge loads: none */
  double rxdt = m * (vx1 - vx0) - dt * (n->fx[i] - lfx);
  double rydt = m * (vy1 - vy0) - dt * (n->fy[i] - lfy) - dt * m * gy;
  return 0.5 * (rxdt * (vx1 + vx0) + rydt * (vy1 + vy0));
}

/* update_one for nodes i..i+3 of one BC set b at once, one node per lane of a 4-wide vector (an
 * AVX register where the CPU has it): every lane does update_one's operations in their order (the
 * set's kinds choose the same branch in every lane), so each node gets the bits of the scalar
 * code (tests/check_y2d_regress.c compares them).  Their work increments go to w[0..3], added in
 * node order by the caller.  Nodes of one set are usually consecutive (a body's nodes). */
typedef double v4d __attribute__((vector_size(32)));

static inline __attribute__((always_inline)) void update_four(const YfY2dRun *r, YfNodes *n, double dt, int i, int b,
                                                               double *vxo, double *vyo, double w[4]) {
  const double *R = r->R + 4 * b, *Ri = r->Ri + 4 * b, *lf = r->lf, gy = r->gy;
  const int k0 = r->kind[2 * b], k1 = r->kind[2 * b + 1];
  const double A0 = r->acur[2 * b], A1 = r->acur[2 * b + 1];
#define LD(a) (v4d){a[i], a[i + 1], a[i + 2], a[i + 3]}
  const v4d m = LD(n->m), vx0 = LD(n->vx), vy0 = LD(n->vy), fx = LD(n->fx), fy = LD(n->fy);
#undef LD
  v4d gfx = fx, gfy = fy + m * gy;
  v4d u0 = Ri[0] * vx0 + Ri[1] * vy0, u1 = Ri[2] * vx0 + Ri[3] * vy0;
  v4d q0 = Ri[0] * gfx + Ri[1] * gfy, q1 = Ri[2] * gfx + Ri[3] * gfy;
  v4d d0 = (k0 == Y2D_KIND_FORCE ? dt * (A0 + q0) : q0) / m;
  v4d d1 = (k1 == Y2D_KIND_FORCE ? dt * (A1 + q1) : q1) / m;
  v4d A0v = {A0, A0, A0, A0}, A1v = {A1, A1, A1, A1};
  u0 = k0 == Y2D_KIND_FORCE ? u0 + d0 : k0 == Y2D_KIND_ACCEL ? u0 + dt * (A0 + d0) : k0 == Y2D_KIND_VELOCITY ? A0v : u0;
  u1 = k1 == Y2D_KIND_FORCE ? u1 + d1 : k1 == Y2D_KIND_ACCEL ? u1 + dt * (A1 + d1) : k1 == Y2D_KIND_VELOCITY ? A1v : u1;
  v4d vx1 = R[0] * u0 + R[1] * u1, vy1 = R[2] * u0 + R[3] * u1;
  v4d lfx = {0, 0, 0, 0}, lfy = lfx;
  if (lf) {
    lfx = (v4d){lf[2 * i], lf[2 * i + 2], lf[2 * i + 4], lf[2 * i + 6]};
    lfy = (v4d){lf[2 * i + 1], lf[2 * i + 3], lf[2 * i + 5], lf[2 * i + 7]};
  }
  v4d rxdt = m * (vx1 - vx0) - dt * (fx - lfx);
  v4d rydt = m * (vy1 - vy0) - dt * (fy - lfy) - dt * m * gy;
  v4d wk = 0.5 * (rxdt * (vx1 + vx0) + rydt * (vy1 + vy0));
  if (vxo) {
    for (int l = 0; l < 4; l++) {
      vxo[i + l] = vx0[l];
      vyo[i + l] = vy0[l];
    }
  }
  for (int l = 0; l < 4; l++) {
    n->vx[i + l] = vx1[l];
    n->vy[i + l] = vy1[l];
    w[l] = wk[l];
  }
}

/* Any node i: the generic update for nodes added by native commands after read_y2d (no set),
 * nothing for Y2D's massless nodes, else update_one with its work added to *work. */
static inline void update_node(const YfY2dRun *r, YfNodes *n, const YfSim *s, int i, double *vxo, double *vyo,
                               double *work) {
  const int b = r->set[i];
  const double m = n->m[i];
  if (b >= 0 && m > 1e-10) {
    *work += update_one(r, n, s->dt, i, vxo, vyo);
    return;
  }
  if (vxo) {
    vxo[i] = n->vx[i];
    vyo[i] = n->vy[i];
  }
  if (b == -1 && m > 1e-300) { /* a native node; Y2D_FROZEN keeps its velocity and place */
    double ax, ay;
    yf_div2(n->fx[i], m, n->fy[i], m, &ax, &ay);
    n->vx[i] = n->vx[i] + s->dt * (ax + s->gx);
    n->vy[i] = n->vy[i] + s->dt * (ay + s->gy);
  }
  /* b >= 0 with mass <= 1e-10: Y2D does not move nodes without mass */
}

static int scalar_only; /* tests: every node through update_node (the reference of update_four) */
void y2d_update_scalar_only(int on) { scalar_only = on; }

/* ALGORITHMS 7 on nodes [i0, i1); returns the external work of the step there (summed in node
 * order).  Groups of four ordinary nodes of one set go through update_four, the others one by one. */
YF_CLONES
static double update_range(const YfY2dRun *r, YfNodes *n, const YfSim *s, int i0, int i1, double *vxo,
                           double *vyo, int move) {
  const int *set = r->set;
  const double *ms = n->m;
  double work = 0.0;
  int i = scalar_only ? i1 : i0;
  if (scalar_only)
    for (int j = i0; j < i1; j++) update_node(r, n, s, j, vxo, vyo, &work);
  for (; i + 4 <= i1; i += 4) {
    const int b = set[i];
    if (b >= 0 && set[i + 1] == b && set[i + 2] == b && set[i + 3] == b && ms[i] > 1e-10 && ms[i + 1] > 1e-10 &&
        ms[i + 2] > 1e-10 && ms[i + 3] > 1e-10) {
      double w[4];
      update_four(r, n, s->dt, i, b, vxo, vyo, w);
      work += w[0];
      work += w[1];
      work += w[2];
      work += w[3];
    } else {
      for (int j = i; j < i + 4; j++) update_node(r, n, s, j, vxo, vyo, &work);
    }
  }
  for (; i < i1; i++) update_node(r, n, s, i, vxo, vyo, &work);
  if (move) { /* run.c's x += dt v of these nodes while they are in cache (same operations) */
    const double dt = s->dt, *vx = n->vx, *vy = n->vy;
    double *x = n->x, *y = n->y;
    for (int j = i0; j < i1; j++) {
      /* Y2D moves no node of mass <= 1e-10 (ALGORITHMS 7, 9), nor one of a set out of range */
      if (set[j] == Y2D_FROZEN || (set[j] >= 0 && !(ms[j] > 1e-10))) continue;
      x[j] += dt * vx[j];
      y[j] += dt * vy[j];
    }
  }
  return work;
}

void y2d_update_velocities(YfSim *s, int par, double *vxo, double *vyo, int move) {
  YfY2dRun *r = s->y2d;
  if (!r) return;
  YfNodes *n = &s->model.node;
  if (r->nn != n->n) resolve(s, r);
  /* amplitudes of this step (the same product as per node, once per set) */
  for (int b = 0; b < r->nset; b++) {
    r->acur[2 * b] = r->amp[2 * b] * r->phi[b];
    r->acur[2 * b + 1] = r->amp[2 * b + 1] * r->phi[b];
  }
  const int nn = n->n, nb = r->nublk;
  /* MPI (par.h): this rank's nodes only; the blocks inside them whole, and one work value per
   * node of the blocks it shares with another rank, summed in node order by par_node_block_sums */
  int kb0 = 0, kb1 = nb, n0 = 0, n1 = nn;
  double *piece = par_node_split(nb, Y2D_UBLOCK, &kb0, &kb1);
  /* work summed per fixed block of nodes, blocks added in order: the same bits on any threads */
  YF_PARFOR_IF(par, schedule(static), for (int k = kb0; k < kb1; k++) {
    int i1 = (k + 1) * Y2D_UBLOCK < nn ? (k + 1) * Y2D_UBLOCK : nn;
    r->ublk[k] = update_range(r, n, s, k * Y2D_UBLOCK, i1, vxo, vyo, move);
  });
  if (piece) {
    par_update_nodes(&n0, &n1, NULL, NULL);
    const int h1 = kb1 > kb0 ? kb0 * Y2D_UBLOCK : n1, t0 = kb1 > kb0 && kb1 * Y2D_UBLOCK < nn ? kb1 * Y2D_UBLOCK : n1;
    for (int i = n0; i < h1; i++) *piece++ = update_range(r, n, s, i, i + 1, vxo, vyo, move);
    for (int i = t0; i < n1; i++) *piece++ = update_range(r, n, s, i, i + 1, vxo, vyo, move);
    par_node_block_sums(r->ublk);
  }
  double work = 0.0;
  for (int k = 0; k < nb; k++) work += r->ublk[k];
  s->energy.external_work += work;
}

/* ------------------------------------------------------------------ building the scene */

/* Joint set of row (P, Q) of I2PMIJ (either order; P == Q: the diagonal row), -1 if none. */
static int pmij_set(const YfY2d *y, int p, int q) {
  for (long k = 0; k < y->mpmrow; k++) {
    const int *w = &y->i2pmij[3 * k];
    if ((w[0] == p && w[1] == q) || (w[0] == q && w[1] == p)) return w[2];
  }
  return -1;
}

static int row_has(const YfY2d *y, long row, int p) {
  const int *w = &y->i2pmset[row * y->mpmcol];
  for (int i = 0; i < w[0] && i + 2 < y->mpmcol; i++)
    if (w[2 + i] == p) return 1;
  return 0;
}

static void unsupported_checks(const YfY2d *y) {
  for (long p = 0; p < y->nprop; p++) {
    int ty = y->pe_i1ptyp[p];
    if (ty == 2 || ty == 4) {
      YfLoc l = y->given[Y2D_PE_I1PTYP] ? y->where[Y2D_PE_I1PTYP] : y->end;
      int used = 0;
      for (long e = 0; e < y->nelem; e++) used |= y->i1elpr[e] == p;
      if (used)
        yf_deck_error(&l, "%s: property %ld has type %d (%s): not supported yet by read_y2d "
                      "(supported: 1 elastic triangle)", y2d_key_name(Y2D_PE_I1PTYP), p, ty,
                      ty == 2 ? "rigid triangle" : "softening triangle");
    }
  }
  if (y->given[Y2D_PM_I2PMSET]) {
    YfLoc l = y->where[Y2D_PM_I2PMSET];
    for (long row = 0; row < y->mpmcom; row++) {
      const int *w = &y->i2pmset[row * y->mpmcol];
      if (w[0] <= 0) continue;
      if (w[1] != 3)
        yf_deck_error(&l, "%s: row %ld has meshing code %d: not supported yet by read_y2d "
                      "(supported: 3 = insert joints; refinement 1, 2 and detaching 4 are not)",
                      y2d_key_name(Y2D_PM_I2PMSET), row, w[1]);
    }
  }
}

/* Joint insertion callback: the yfdem joint set for the edge shared by triangles A < B of one
 * meshing row (ALGORITHMS 4.1 step 2): row (P, P) of I2PMIJ when both have property P, else a row
 * holding both properties (either order), else the creating triangle's (A's) row (P_A, P_A);
 * triangles outside the row (other rows, unmeshed properties) are not joined (-1). */
typedef struct {
  const YfY2d *y;
  const int *jmap;  /* Y2D joint set -> yfdem joint set */
  long row;
  int tri0, ntri;
} PairCtx;

static int prop_of_pair(void *ctx, int A, int B) {
  const PairCtx *c = ctx;
  int ea = A - c->tri0, eb = B - c->tri0;
  if (ea < 0 || eb < 0 || ea >= c->ntri || eb >= c->ntri) return -1;
  const YfY2d *y = c->y;
  int pa = y->i1elpr[ea], pb = y->i1elpr[eb];
  if (!row_has(y, c->row, pa) || !row_has(y, c->row, pb)) return -1;
  int js = pmij_set(y, pa, pb);
  if (js < 0) js = pmij_set(y, pa, pa);
  return js < 0 || js >= y->npjset ? -1 : c->jmap[js];
}

/* Joint sets (Munjiza law with Y2D's 2 o_p floor, no damage memory, Mohr-Coulomb from D1PJCO and
 * D1PJFR) and joint insertion for every meshing row of code 3, row by row as Y2D meshes them.
 * Marks the meshed triangles in meshed[] (their new nodes are boundary-flagged for contact). */
static void y2d_setup_joints(YfSim *s, YfY2dRun *r, const YfY2d *y, unsigned char *meshed) {
  if (!y->given[Y2D_PM_I2PMSET]) return;
  int any = 0;
  for (long row = 0; row < y->mpmcom; row++) any |= y->i2pmset[row * y->mpmcol] > 0;
  if (!any) return;
  int *jmap = yf_malloc((size_t)(y->npjset + 1) * sizeof(int), "y2d joint sets");
  YfLoc jl = y->given[Y2D_PJ_D1PJFT] ? y->where[Y2D_PJ_D1PJFT] : y->end;
  for (long j = 0; j < y->npjset; j++) {
    if (!y->pjset_used || !y->pjset_used[j]) { /* a spare set: never evaluated (y2d_read.c) */
      jmap[j] = -1;
      continue;
    }
    YfJointProp p;
    joint_prop_default(&p);
    p.ft = y->d1pjft[j];
    p.fs = y->d1pjfs[j];
    p.gf = y->d1pjgf[j];
    p.pen = y->d1pjpe[j];
    p.coh = y->d1pjco[j];
    p.phi = y->d1pjfr[j];
    p.law = YF_SOFT_MUNJIZA;
    p.y2d_floor = 1;
    p.irreversible = 0;
    char name[YF_NAME_MAX];
    snprintf(name, sizeof name, "y2d_j%ld", j);
    jmap[j] = joints_add_set(s, name, &p, YF_HET_NONE, 0.0, 1, &jl);
  }
  YfModel *m = &s->model;
  unsigned char *zone = yf_calloc((size_t)m->tri.n + 1, 1, "y2d meshing zone");
  for (long row = 0; row < y->mpmcom; row++) {
    if (y->i2pmset[row * y->mpmcol] <= 0) continue;
    int nz = 0;
    for (int t = 0; t < m->tri.n; t++) {
      int e = t - r->tri0;
      zone[t] = (unsigned char)(e >= 0 && e < r->ntri && row_has(y, row, y->i1elpr[e]));
      if (zone[t]) meshed[e] = 1;
      nz += zone[t];
    }
    if (!nz) continue;
    PairCtx c = {y, jmap, row, r->tri0, r->ntri};
    joints_insert_zone(s, zone, prop_of_pair, &c);
  }
  free(zone);
  free(jmap);
}

/* Contact as Y2D has it (FORMAT.md 5.3, ALGORITHMS.md 5): MICOUP > 0 switches it on between every
 * pair of participating triangles (same body and neighbours sharing nodes included), buffer
 * DIEZON; with IWFAST > 0 only triangles with a corner whose input node has I1NOBF = 1 take part,
 * and joint meshing flags all the new nodes of the meshed triangles. */
static void y2d_setup_contact(YfSim *s, YfY2dRun *r, const YfY2d *y, const unsigned char *meshed) {
  if (y->micoup <= 0) return;
  YfModel *m = &s->model;
  unsigned char *flag = yf_calloc((size_t)m->tri.n + 1, 1, "contact participation");
  for (int e = 0; e < r->ntri; e++) {
    int in = y->iwfast == 0 || meshed[e];
    for (int c = 0; c < 3 && !in; c++) in = y->i1nobf[y->i2elto[(long)e * y->melno + c]] == 1;
    flag[r->tri0 + e] = (unsigned char)in;
  }
  contact_enable_all(s, y->diezon);
  contact_set_participation(s, flag, m->tri.n);
  free(flag);
  /* the travel counter starts at DIEDI (1e15: the first step searches), or at 2 DIEZON after
   * joint meshing (ALGORITHMS 5): a deck with DIEDI below DIEZON and no meshing first searches
   * once its bodies have moved DIEZON */
  int any_meshed = 0;
  for (int e = 0; e < r->ntri && !any_meshed; e++) any_meshed = meshed[e];
  if (!any_meshed && y->diedi < y->diezon) contact_set_first_travel(s, y->diedi);
}

/* The run being built by load (NULL otherwise): reachable from y2d_model_free, which sim_free calls
 * once the bc kind is registered, so that a deck error in the middle of reading (which ends yfdem;
 * the fuzz targets and library callers go on) leaves its arrays (sized by the deck's capacities)
 * freed, not unreachable. */
static YfY2dRun *loading;

static void y2drun_free(YfY2dRun *r) {
  if (r->deck) {
    y2d_free(deck_of(r));
    free(r->deck);
  }
  free(r->path);
  free(r->kind); free(r->amp); free(r->ap); free(r->at); free(r->R); free(r->Ri);
  free(r->tt); free(r->tf); free(r->phi); free(r->set); free(r->le); free(r->lf);
  free(r->acur); free(r->ublk); free(r->setof);
  free(r);
}

static int load(YfSim *s, const char *path, double volfac, const YfLoc *from, int program) {
  if (s->y2d) yf_deck_error(from, "read_y2d: a Y2D deck (%s) was already read; one per simulation", s->y2d->path);
  YfY2d *y = yf_calloc(1, sizeof *y, "y2d deck");
  YfY2dRun *r = yf_calloc(1, sizeof *r, "y2d run");
  r->deck = y;
  loading = r;
  sim_add_bc_kind(s, &y2d_bc_kind); /* its free hook frees `loading` after an error (sim_free) */
  if (program ? y2d_read_program(path, y, from) : y2d_read(path, y, from)) { /* nothing to compute */
    loading = NULL;
    y2drun_free(r);
    return 0;
  }
  unsupported_checks(y);
  /* the law's in-plane bulk modulus 2 volfac lambda + mu must be positive, as for a native material
   * (cmd_material.c): lambda itself may be negative (a negative Poisson's ratio).  Checked before
   * anything is allocated here, so that the error leaves nothing unreachable. */
  for (long p = 0; p < y->nprop; p++) {
    const double la = y->d1pela[p], mu = y->d1pemu[p];
    if (y->prop_used[p] && y->pe_i1ptyp[p] == 1 && !(2.0 * volfac * la + mu > 0)) {
      YfLoc l = y2d_value_loc(y, Y2D_PE_D1PELA, p);
      yf_deck_error(&l, "%s: property %ld has lambda %g and mu (%s) %g: the in-plane bulk modulus %s = %g must be "
                    "positive (lambda above %g; every E > 0 with nu in (-1, 0.5) gives such a pair)",
                    y2d_key_name(Y2D_PE_D1PELA), p, la, y2d_key_name(Y2D_PE_D1PEMU), mu,
                    volfac == 1.0 ? "2 lambda + mu" : "lambda + mu", 2.0 * volfac * la + mu,
                    mu > 0 ? -mu / (2.0 * volfac) : 0.0);
    }
  }

  YfModel *m = &s->model;
  r->path = yf_strdup(path);
  r->volfac = volfac;
  r->gy = y->dcgray;

  /* materials and bodies: one per element property */
  int np = (int)y->nprop;
  int *pmat = yf_malloc((size_t)(np + 1) * sizeof(int), "y2d materials");
  int *pbody = yf_malloc((size_t)(np + 1) * sizeof(int), "y2d bodies");
  for (int p = 0; p < np; p++) {
    char name[YF_NAME_MAX];
    snprintf(name, sizeof name, "y2d_p%d", p);
    if (model_find_material(m, name) >= 0) yf_deck_error(from, "read_y2d: material '%s' already exists", name);
    int k = model_add_material(m, name);
    YfMaterial *mt = &m->mat[k];
    mt->rho = y->d1pero[p];
    mt->plane = YF_PLANE_LAME;
    mt->lambda = y->d1pela[p];
    mt->mu = y->d1pemu[p];
    mt->volfac = volfac;

    mt->visc = y->d1peks[p];
    mt->pen_n = y->d1pepe[p];
    mt->pen_n_given = 1; /* D1PEPE 0 is Y2D's own value (couples without force): a native contact rule takes it */
    mt->pen_t = y->d1pept[p];
    mt->fric = y->d1pefr[p];
    model_lame_moduli(mt); /* E, nu: the energy check's round-off floor is 1e-16 E per unit area */
    pmat[p] = k;
    pbody[p] = model_add_body(m, name, k);
  }

  /* nodes: input numbering kept as ids; body and groups of the elements that use them */
  int nn = (int)y->nnopo, ne = (int)y->nelem;
  int *nbody = yf_malloc((size_t)(nn + 1) * sizeof(int), "y2d node bodies");
  for (int i = 0; i < nn; i++) nbody[i] = -1;
  for (int e = 0; e < ne; e++)
    for (int c = 0; c < 3; c++) {
      int v = y->i2elto[(long)e * y->melno + c];
      if (nbody[v] < 0) nbody[v] = pbody[y->i1elpr[e]];
    }
  /* group "y2d": every node and triangle of the deck (identifies them after joint insertion) */
  int g = model_group(m, "y2d", 1);
  if (g < 0) yf_deck_error(from, "read_y2d: no room for group 'y2d' (at most %d groups)", YF_MAX_GROUPS);
  r->gbit = (uint64_t)1 << g;
  model_reserve(m, nn, ne); /* counts known: exact sizes */
  r->node0 = m->node.n;
  r->nnode = nn;
  for (int i = 0; i < nn; i++) {
    int k = model_add_node(m, y->d2nci[2 * i], y->d2nci[2 * i + 1], i, nbody[i] >= 0 ? nbody[i] : 0);
    m->node.x[k] = y->d2ncc[2 * i];
    m->node.y[k] = y->d2ncc[2 * i + 1];
    m->node.vx[k] = y->d2nvc[2 * i];
    m->node.vy[k] = y->d2nvc[2 * i + 1];
    m->node.gmask[k] |= r->gbit;
  }
  r->tri0 = m->tri.n;
  r->ntri = ne;
  for (int e = 0; e < ne; e++) {
    const int *v = &y->i2elto[(long)e * y->melno];
    int p = y->i1elpr[e];
    int t = model_add_tri(m, r->node0 + v[0], r->node0 + v[1], r->node0 + v[2], pmat[p], e, pbody[p]);
    m->tri.gmask[t] |= r->gbit;
    for (int c = 0; c < 3; c++) m->node.gmask[r->node0 + v[c]] |= m->tri.gmask[m->tri.n - 1];
  }
  free(nbody);
  /* the node states are in the scene: their MNOPO-wide arrays go before joint insertion, the
   * set-up's peak (216 MB of 1.37 GB at 1e6 triangles); the rest of the deck goes at the end */
  double **states[] = {&y->d2nci, &y->d2ncc, &y->d2nvc, &y->d2elst};
  for (size_t k = 0; k < sizeof states / sizeof states[0]; k++) {
    free(*states[k]);
    *states[k] = NULL;
  }

  /* control */
  s->dt = y->dcstec;
  s->dt_auto = 0;
  s->dt_loc = y->given[Y2D_C_DCSTEC] ? y->where[Y2D_C_DCSTEC] : y->end;
  s->time = y->dctime;
  s->step = y->ncstep;
  s->last_step = y->mcstep;
  s->gx = 0.0;
  s->gy = y->dcgray;

  /* BC sets */
  int ns = (int)y->npnset;
  r->nset = ns;
  r->kind = yf_malloc((size_t)(2 * ns + 2) * sizeof(int), "y2d kinds");
  r->amp = yf_malloc((size_t)(2 * ns + 2) * sizeof(double), "y2d amplitudes");
  r->ap = yf_malloc((size_t)(ns + 1) * sizeof(double), "y2d pressures");
  r->at = yf_malloc((size_t)(ns + 1) * sizeof(double), "y2d tractions");
  r->R = yf_malloc((size_t)(4 * ns + 4) * sizeof(double), "y2d frames");
  r->Ri = yf_malloc((size_t)(4 * ns + 4) * sizeof(double), "y2d frames");
  r->phi = yf_malloc((size_t)(ns + 1) * sizeof(double), "y2d factors");
  r->acur = yf_calloc((size_t)(2 * ns + 2), sizeof(double), "y2d amplitudes");
  for (int b = 0; b < ns; b++) {
    r->kind[2 * b] = y->i1pnfx[b];
    r->kind[2 * b + 1] = y->i1pnfy[b];
    r->amp[2 * b] = y->d1pnax[b];
    r->amp[2 * b + 1] = y->d1pnay[b];
    r->ap[b] = y->d1pnap[b];
    r->at[b] = y->d1pnat[b];
    /* R = [ex ey]: columns are the local axes in global components */
    double a = y->d1pnxx[b], c = y->d1pnxy[b], bb = y->d1pnyx[b], d = y->d1pnyy[b];
    double *R = r->R + 4 * b, *Ri = r->Ri + 4 * b;
    R[0] = a; R[1] = bb; R[2] = c; R[3] = d;
    double det = a * d - bb * c;
    Ri[0] = d / det; Ri[1] = -bb / det; Ri[2] = -c / det; Ri[3] = a / det;
    r->phi[b] = 1.0;
  }
  r->tables_on = y->tables_on;
  r->npts = y->tables_on ? (int)y->npnfact : 0;
  if (r->npts > 0) {
    r->tt = yf_malloc((size_t)ns * r->npts * sizeof(double), "y2d tables");
    r->tf = yf_malloc((size_t)ns * r->npts * sizeof(double), "y2d tables");
    for (int b = 0; b < ns; b++)
      for (int p = 0; p < r->npts; p++) {
        r->tt[b * r->npts + p] = y2d_fac_time(y, b, p);
        r->tf[b * r->npts + p] = y2d_fac_value(y, b, p);
      }
  }
  s->y2d = r; /* the run loop applies the BC sets through y2d_bc_kind */
  loading = NULL;
  s->dt_warn_only = 1;              /* Y2D decks choose dt by experience: warn only */

  /* joints (meshing code 3) and contact */
  unsigned char *meshed = yf_calloc((size_t)ne + 1, 1, "y2d meshed elements");
  y2d_setup_joints(s, r, y, meshed);
  r->contact_on = y->micoup > 0;
  r->micoup = y->micoup;
  r->micoup_loc = y->given[Y2D_I_MICOUP] ? y->where[Y2D_I_MICOUP] : y->end;
  y2d_setup_contact(s, r, y, meshed);
  free(meshed);
  free(pmat);
  free(pbody);
  /* the BC set of each input node is all resolve() needs of the deck later (copies made by
   * joint insertion, partition renumbering) */
  r->setof = yf_malloc((size_t)(nn + 1) * sizeof(int), "y2d input node sets");
  for (int i = 0; i < nn; i++) r->setof[i] = y->i1nopr[i];
  resolve(s, r);
  /* The scene now holds everything: the deck's capacity-sized arrays (MNOPO, MELEM... wide, a
   * third of the peak memory at 1e5 triangles while they lived until the first run's set-up)
   * go before the run builds its own. */
  y2d_free_arrays(y);
  return 1;
}

void y2d_model_free(YfSim *s) {
  if (loading && loading != s->y2d) y2drun_free(loading);
  loading = NULL;
  if (!s->y2d) return;
  y2drun_free(s->y2d);
  s->y2d = NULL;
}

static void y2d_renumbered(YfSim *s) {
  if (s->y2d) s->y2d->nn = -1; /* node sets and loaded edges are resolved again */
}

/* Y2D stores its contact couples in a list of fixed capacity MICOUP and stops when a search
 * finds more ("Ycd: to small meicoc", FORMAT.md 3.4, 6).  yfdem's list grows, so such a deck runs
 * here where Y2D would have stopped: say so once, with the step and the count, so that a user
 * comparing with Y2D, or keeping the deck runnable by it, knows.  The count is the whole list's
 * on every rank (contact.c), so every rank decides alike and rank 0 prints. */
static void y2d_check_couples(YfSim *s, YfY2dRun *r) {
  if (r->micoup <= 0 || r->micoup_warned) return;
  long n = contact_pairs(s);
  if (n <= r->micoup) return;
  r->micoup_warned = 1;
  yf_warn(r->micoup_loc.file ? &r->micoup_loc : NULL,
          "step %ld: the contact list holds %ld couples, more than /YD/YDI/MICOUP = %ld: Y2D stops here "
          "(\"Ycd: to small meicoc\"); yfdem's list grows and the run goes on (give MICOUP >= %ld, "
          "20-25 per triangle, to keep the deck runnable by Y2D)", s->step, n, r->micoup, n);
}

static void y2d_loads(YfSim *s) {
  if (!s->y2d) return;
  y2d_check_couples(s, s->y2d);
  y2d_apply_loads(s); /* edge pressure and shear traction */
}

/* Y2D's BC sets as a boundary-condition kind (sim.h): edge loads at the gather stage, and the
 * BC-set velocity update (kinds, local frames, time factors), which without damping moves the
 * nodes too, block by block while they are in cache. */
/* MPI: the ends of loaded edges are read by every rank (y2d_apply_loads computes every edge);
 * the update itself is node by node, divided by owner (y2d_update_velocities). */
static void y2d_mark_nodes(YfSim *s, unsigned char *mark) {
  YfY2dRun *r = s->y2d;
  if (!r) return;
  if (r->nn != s->model.node.n) resolve(s, r);
  const int *tv = s->model.tri.v;
  for (int k = 0; k < r->nle; k++) {
    const int *v = tv + 3 * r->le[2 * k];
    int jj = r->le[2 * k + 1];
    mark[v[jj]] |= YF_BC_READS;
    mark[v[(jj + 1) % 3]] |= YF_BC_READS;
  }
}

/* With native mass damping the run loop moves every node after the update (run.c, old positions
 * in xo, yo): a Y2D node of mass <= 1e-10 goes back, as Y2D moves none (ALGORITHMS 7, 9: a deck in
 * tonnes and millimetres with fine cells has such nodes everywhere).  Without damping the update
 * itself leaves them (update_range). */
static void y2d_hold_massless(YfSim *s, const double *xo, const double *yo, const double *vxo, const double *vyo) {
  YfY2dRun *r = s->y2d;
  if (!r || !xo || !(s->mass_damping > 0)) return;
  YfNodes *n = &s->model.node;
  for (int i = 0; i < n->n && i < r->nn; i++)
    if (r->set[i] == Y2D_FROZEN || (r->set[i] >= 0 && !(n->m[i] > 1e-10))) {
      n->x[i] = xo[i];
      n->y[i] = yo[i];
    }
  (void)vxo, (void)vyo;
}

const YfBcKind y2d_bc_kind = {.name = "y2d", .loads = y2d_loads, .integrate = y2d_update_velocities,
                              .constrain_positions = y2d_hold_massless, .mark_nodes = y2d_mark_nodes,
                              .renumbered = y2d_renumbered,
                              .free = y2d_model_free};

int y2d_nprop(const YfSim *s) { return s->y2d && s->y2d->deck ? (int)deck_of(s->y2d)->nprop : 0; }

void y2d_load(YfSim *s, const char *path, double volfac, const YfLoc *from) { load(s, path, volfac, from, 0); }

void y2d_run_file(YfSim *s, const char *path) {
  if (!load(s, path, 0.5, NULL, 1)) return; /* $YSTOP before any $YDOIT: Y2D computes nothing */
  s->y2d_program = s->y2d->path;
  /* Y2D prints a progress line every ICSHTF steps (FORMAT.md 1.5): the thermo line takes its place,
   * so a batch run's log shows the run going, as Y2D's does (only `yfdem DECK.y`: a native deck
   * that reads a .y keeps its own thermo) */
  const YfY2d *y = deck_of(s->y2d);
  const long every = y->icshtf;
  if (every > 0) s->thermo_every = every;
  long n = s->last_step - s->step;
  /* Y2D writes an animation frame every ICOUTF steps (the reader made <= 0 into 10); `yfdem DECK.y` writes
   * none: said where Y2D would write one after step 0, with the two ways to frames (a native deck that
   * reads the .y keeps its own dumps: not said there) */
  if (y->icoutf > 0 && y->icoutf <= n) {
    YfLoc l = y->given[Y2D_C_ICOUTF] ? y->where[Y2D_C_ICOUTF] : y->end;
    yf_warn(&l, "/YD/YDC/ICOUTF = %ld: Y2D writes an animation frame every %ld steps; `yfdem %s` writes no frames "
            "(its results: the thermo lines and -summary FILE). For frames ParaView opens: tools/y2d2deck.py %s OUT "
            "(OUT.deck dumps every %ld steps), or a deck: read_y2d %s, dump d1 h5 %ld out.h5, run", y->icoutf, y->icoutf,
            path, path, y->icoutf, path, y->icoutf);
  }
  /* MCSTEP <= NCSTEP: Y2D computes no step, and a deck that gives it no time step (DCSTEC 0) is
   * not wrong for that (the reader warned at $YDOIT); a step-0 run would need one, so there is
   * none, as after a $YSTOP before any $YDOIT */
  if (n <= 0 && !(s->dt > 0)) return;
  run_steps(s, n > 0 ? n : 0);
}
