/* y2d_write.c: a native scene as a Y2D input deck (the write_y2d command, deck/cmd_write_y2d.c) (see y2d_write.h and
 * docs/y2d_decks.md for the mapping).
 *
 * This module owns the translation from the scene (model, joints, contact, bc, histories) to the
 * keys of FORMAT.md.  It reads the scene before the first run: the mesh is captured as the deck
 * built it (before `fracture` splits it: Y2D inserts the joints itself), then run_prepare
 * resolves what the scene derives (joint insertion, masses, `damping BETA`, the auto contact
 * buffer, `timestep auto`), exactly as the first run would, so the numbers written are the ones
 * the native run uses.  Reals are written with 17 significant digits: read back, they are the
 * same doubles.
 *
 * Mapping (units SI, per unit thickness, as both programs use them):
 *  - element property = (body, material) in the order triangles first use them;
 *    D1PELA = 2 volfac lambda (yfdem's law has volfac lambda (J - 1/J), Y2D's (lambda/2)(J -
 *    1/J)), D1PEMU = mu, so a material given by E, nu is the same material in Y2D;
 *  - a body fractured whole = one meshing row of code 3 listing its properties; I2PMIJ gives each
 *    of them (and each pair of them) the body's joint set;
 *  - node BC sets: per node component kind 3 (velocity) with amplitude 0 for `fix fixed`, v for
 *    `fix velocity`, kind 1 (force) with the point load shared by the node's copies, else free
 *    (kind 1, 0); `load pressure` / `traction` as D1PNAP / D1PNAT (straight faces); one time table
 *    per set from the history of its amplitudes.
 */
#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "bc.h"
#include "contact.h"
#include "err.h"
#include "joint.h"
#include "mesh.h"
#include "par.h"
#include "run.h"
#include "y2d_model.h"
#include "y2d_write.h"
#include "wfile.h"

/* One node's boundary condition as a Y2D BC set: kind per direction (1 force, 3 velocity),
 * amplitude, edge pressure and shear [Pa], history of the amplitudes (-1: factor 1). */
typedef struct {
  int k[2];
  double a[2];
  double ap, at;
  int hist;
} NodeBc;

static int same_bc(const NodeBc *p, const NodeBc *q) {
  return p->k[0] == q->k[0] && p->k[1] == q->k[1] && p->a[0] == q->a[0] && p->a[1] == q->a[1] &&
         p->ap == q->ap && p->at == q->at && p->hist == q->hist;
}

/* ------------------------------------------------------------------ output helpers */

static void put_d(FILE *f, const char *key, long n, const double *v, int stride) {
  fprintf(f, "%s %ld\n", key, n);
  for (long i = 0; i < n; i++) fprintf(f, "%.17g%s", v[i * stride], (i + 1) % 6 == 0 || i + 1 == n ? "\n" : " ");
}

static void put_i(FILE *f, const char *key, long n, const int *v) {
  fprintf(f, "%s %ld\n", key, n);
  for (long i = 0; i < n; i++) fprintf(f, "%d%s", v[i], (i + 1) % 20 == 0 || i + 1 == n ? "\n" : " ");
}

/* 2D array "KEY 21 n1 n2" of n2 rows of n1 doubles. */
static void put_d2(FILE *f, const char *key, long n2, const double *a, const double *b) {
  fprintf(f, "%s 21 2 %ld\n", key, n2);
  for (long i = 0; i < n2; i++) fprintf(f, "%.17g %.17g\n", a[i], b[i]);
}

/* ------------------------------------------------------------------ time tables */

/* Knots of history h over [0, tfar] (its value is linear between them, held outside). */
static int hist_knots(const YfSim *s, int h, double tfar, double *t, int cap, const YfLoc *loc) {
  int n = 0;
  t[n++] = 0.0;
  if (h >= 0) {
    const YfHistory *H = &s->hist[h];
    if (H->kind == YF_HIST_SINE)
      yf_deck_error(loc, "history '%s' is a sine: Y2D's time tables are piecewise linear (give it as a table)", H->name);
    if (H->kind == YF_HIST_RAMP) {
      if (H->t0 > 0 && H->t0 < tfar) t[n++] = H->t0;
      if (H->t1 > 0 && H->t1 < tfar) t[n++] = H->t1;
    } else if (H->kind == YF_HIST_TABLE) {
      for (int i = 0; i < H->npts && n + 1 < cap; i++)
        if (H->t[i] > t[n - 1] && H->t[i] < tfar) t[n++] = H->t[i];
    }
  }
  t[n++] = tfar;
  return n;
}

/* Largest |factor| of history h (-1: none, factor 1); sine histories are refused elsewhere. */
static double hist_max(const YfSim *s, int h) {
  if (h < 0) return 1.0;
  const YfHistory *H = &s->hist[h];
  if (H->kind != YF_HIST_TABLE) return 1.0;
  double v = 0.0;
  for (int i = 0; i < H->npts; i++) v = fmax(v, fabs(H->v[i]));
  return v;
}

/* An output scale: x rounded up to two significant digits (a round number in the deck). */
static double round_up2(double x) {
  if (!(x > 0) || !isfinite(x)) return 1.0;
  double p = pow(10.0, floor(log10(x)) - 1.0);
  return ceil(x / p * (1.0 - 1e-12)) * p;
}

/* ------------------------------------------------------------------ the command */

void y2d_write(YfSim *s, const char *path, long steps, long every, const YfLoc *loc) {
  YfModel *m = &s->model;
  if (s->y2d) yf_deck_error(loc, "this scene was read from a Y2D deck (%s): run that deck in Y2D", s->y2d->path);
  if (m->prepared || s->step > 0)
    yf_deck_error(loc, "write_y2d exports the scene as the deck set it up: put it before the first run (Y2D "
              "inserts the joints and starts at step 0)");
  if (!m->tri.n) yf_deck_error(loc, "the scene has no triangles");
  if (s->gx != 0)
    yf_deck_error(loc, "gravity has an x component (%g m/s^2): Y2D's 2D gravity acts along y only (DCGRAY)", s->gx);
  if (s->mass_damping > 0)
    yf_deck_error(loc, "mass damping (damping mass %g): Y2D has no mass-proportional damping (only the material's "
              "viscous term, material damping BETA or visc K)", s->mass_damping);

  /* ---- the mesh as the deck built it (before fracture splits it) ---- */
  const int nn = m->node.n, nt = m->tri.n, nb = m->nbody;
  double *nx0 = yf_malloc(6 * (size_t)nn * sizeof(double), "write_y2d nodes");
  double *ny0 = nx0 + nn, *nx = ny0 + nn, *ny = nx + nn, *nvx = ny + nn, *nvy = nvx + nn;
  uint64_t *ngm = yf_malloc((size_t)nn * sizeof(uint64_t), "write_y2d nodes");
  for (int i = 0; i < nn; i++) {
    nx0[i] = m->node.x0[i]; ny0[i] = m->node.y0[i];
    nx[i] = m->node.x[i]; ny[i] = m->node.y[i];
    nvx[i] = m->node.vx[i]; nvy[i] = m->node.vy[i];
    ngm[i] = m->node.gmask[i];
  }
  int *tv = yf_malloc((size_t)(3 * nt) * sizeof(int), "write_y2d triangles");
  int *tprop = yf_malloc((size_t)nt * sizeof(int), "write_y2d triangles");
  int *pbody = yf_malloc((size_t)nt * sizeof(int), "write_y2d properties");
  int *pmat = yf_malloc((size_t)nt * sizeof(int), "write_y2d properties");
  int np = 0;
  memcpy(tv, m->tri.v, (size_t)(3 * nt) * sizeof(int));
  for (int t = 0; t < nt; t++) {
    int p = 0;
    while (p < np && !(pbody[p] == m->tri.body[t] && pmat[p] == m->tri.mat[t])) p++;
    if (p == np) { pbody[np] = m->tri.body[t]; pmat[np] = m->tri.mat[t]; np++; }
    tprop[t] = p;
  }
  /* friction: Y2D has only its own law (tangential force p_t L^2 times the slip, kernel/contact_pair.h);
   * the elastic-slip Coulomb law, the native default, is another law.  With friction 0 both put no
   * tangential force, so only a frictional Coulomb material is refused. */
  for (int p = 0; p < np; p++) {
    const YfMaterial *mt = &m->mat[pmat[p]];
    if (mt->fric_law == YF_FRIC_COULOMB && mt->fric > 0)
      yf_deck_error(loc, "write_y2d: material '%s' has friction %g with the coulomb friction law (the native default): "
                    "Y2D has only its own friction law (give the material 'friction_law y2d', or friction 0)",
                    mt->name, mt->fric);
    /* Y2D checks its properties after $YDOIT and computes nothing with a negative D1PELA (FORMAT.md 6):
     * an auxetic material (nu < 0) is one yfdem runs and Y2D refuses */
    if (mt->lambda < 0)
      yf_deck_error(loc, "write_y2d: material '%s' has Lame lambda %g Pa < 0 (nu %g): Y2D refuses a negative D1PELA "
                    "and computes nothing (FORMAT.md 6); give it nu >= 0 to write it for Y2D", mt->name, mt->lambda,
                    mt->nu);
  }
  /* fracture: whole bodies only, with joint sets Y2D has */
  int *bset = yf_malloc((size_t)(nb + 1) * sizeof(int), "write_y2d bodies");
  int nj = s->joints ? s->joints->nset : 0;
  int *jmap = yf_malloc((size_t)(nj + 1) * sizeof(int), "write_y2d joint sets"), njs = 0;
  int *jsrc = yf_malloc((size_t)(nj + 1) * sizeof(int), "write_y2d joint sets");
  for (int j = 0; j < nj; j++) jmap[j] = -1;
  int nrow = 0, maxk = 0;
  for (int b = 0; b < nb; b++) {
    const YfLoc *part;
    bset[b] = joints_body_set(s, b, &part);
    if (part)
      yf_deck_error(part, "write_y2d: this fracture command limits fracture to a region or group of body '%s': "
                    "Y2D meshes whole element properties (fracture the whole body, or make the zone its own body)",
                    m->body[b].name);
    if (bset[b] < 0) continue;
    const YfJointSet *js = &s->joints->set[bset[b]];
    const char *why = js->p.law != YF_SOFT_MUNJIZA ? "its softening law is not Y2D's (law munjiza)"
                      : !js->p.y2d_floor ? "floor none (Y2D's softening length has the 2 o_p floor: floor y2d)"
                      : js->p.irreversible ? "damage irreversible (Y2D's joints have no damage memory: damage reversible)"
                      : js->het != YF_HET_NONE ? "random strengths (weibull/normal): Y2D's joint sets are homogeneous"
                      : NULL;
    if (why) yf_deck_error(loc, "jointprop '%s' of body '%s' cannot be written for Y2D: %s", js->name, m->body[b].name, why);
    if (js->p.hreg != 1e-10)
      yf_warn(loc, "write_y2d: jointprop '%s': Y2D's joints take the unit tangent as e/(h + 1e-10 m), this one as "
              "e/h (a relative change of 1e-10 m / h in the joint forces); 'tangent y2d' gives Y2D's", js->name);
    if (jmap[bset[b]] < 0) { jsrc[njs] = bset[b]; jmap[bset[b]] = njs++; }
    int k = 0;
    for (int p = 0; p < np; p++) k += pbody[p] == b;
    if (k > maxk) maxk = k;
    nrow++;
  }
  /* triangles per node: in fractured bodies (zone) and others, for copies and the buffer sizes */
  int *zuse = yf_calloc((size_t)nn + 1, sizeof(int), "write_y2d nodes"), *ouse = yf_calloc((size_t)nn + 1, sizeof(int), "write_y2d nodes");
  int nzone = 0;
  for (int t = 0; t < nt; t++) {
    int z = bset[m->tri.body[t]] >= 0;
    nzone += z;
    for (int c = 0; c < 3; c++) (z ? zuse : ouse)[tv[3 * t + c]]++;
  }
  /* free-surface nodes of the deck's topology (contact participation of unjointed bodies) */
  int *bedge = NULL;
  int nbe = mesh_boundary_edges(m, ~(uint64_t)0, &bedge);
  int *nobf = yf_calloc((size_t)nn + 1, sizeof(int), "write_y2d nodes");
  for (int e = 0; e < 2 * nbe; e++) nobf[bedge[e]] = 1;
  free(bedge);

  /* ---- boundary conditions per node ---- */
  NodeBc *nbc = yf_malloc((size_t)(nn + 1) * sizeof(NodeBc), "write_y2d node sets");
  int *chist = yf_malloc(2 * (size_t)(nn + 1) * sizeof(int), "write_y2d node sets"); /* per component */
  int *ehist = yf_malloc((size_t)(nn + 1) * sizeof(int), "write_y2d node sets");   /* edge loads      */
  for (int i = 0; i < nn; i++) {
    nbc[i] = (NodeBc){{1, 1}, {0, 0}, 0, 0, -1};
    chist[2 * i] = chist[2 * i + 1] = ehist[i] = -1;
  }
  int nbci = bc_count(s);
  long nedge = 0; /* boundary edges yfdem's edge loads act on */
  for (int q = 0; q < nbci; q++) {
    const char *bc_id;
    const YfBcSpec it = *bc_spec(s, q, &bc_id);
    if (it.kind == BC_DISPLACEMENT)
      yf_deck_error(&it.loc, "write_y2d: fix '%s' prescribes a displacement: Y2D has no displacement condition "
                    "(prescribe the velocity instead)", bc_id);
    if (it.kind == BC_FIXED || it.kind == BC_VELOCITY) {
      uint64_t bit = (uint64_t)1 << it.group;
      for (int i = 0; i < nn; i++)
        if (ngm[i] & bit)
          for (int c = 0; c < 2; c++)
            if (it.has[c]) {
              nbc[i].k[c] = 3;
              nbc[i].a[c] = it.kind == BC_FIXED ? 0.0 : it.a[c];
              chist[2 * i + c] = it.kind == BC_FIXED ? -1 : it.hist;
            }
    } else if (it.kind == BC_POINT) {
      int tgt = -1;
      double best = INFINITY;
      for (int i = 0; i < nn; i++) {
        if (it.node_id >= 0) {
          if (m->node.id[i] == it.node_id) { tgt = i; break; }
          continue;
        }
        if (!zuse[i] && !ouse[i]) continue; /* the native load picks a node with mass */
        double d = (nx0[i] - it.px) * (nx0[i] - it.px) + (ny0[i] - it.py) * (ny0[i] - it.py);
        if (d < best) { best = d; tgt = i; }
      }
      if (tgt < 0) yf_deck_error(&it.loc, "write_y2d: load '%s' has no node to act on", bc_id);
      /* Y2D gives every copy of a node its set: the load is shared by the copies, as yfdem does */
      int copies = zuse[tgt] + (ouse[tgt] > 0);
      if (copies < 1) copies = 1;
      for (int c = 0; c < 2; c++) {
        if (nbc[tgt].k[c] == 3 || it.a[c] == 0) continue; /* a held direction ignores forces (both programs) */
        if (nbc[tgt].a[c] != 0 && chist[2 * tgt + c] != it.hist)
          yf_deck_error(&it.loc, "write_y2d: load '%s' and another load act on node %d with different histories: "
                        "a Y2D BC set has one time table", bc_id, m->node.id[tgt]);
        nbc[tgt].a[c] += it.a[c] / copies;
        chist[2 * tgt + c] = it.hist;
      }
    } else { /* traction, pressure: Y2D's edge pressure and shear, constant along straight faces */
      if (it.kind == BC_TRACTION)
        yf_warn(loc, "write_y2d: load '%s' is a traction of fixed direction (%g, %g) Pa; Y2D's edge loads (D1PNAP, "
                "D1PNAT) are a pressure and a shear that turn with the face: written as those of the undeformed face, "
                "the same load while the face turns little", bc_id, it.a[0], it.a[1]);
      int *ed = NULL;
      int ne = mesh_boundary_edges(m, (uint64_t)1 << it.group, &ed);
      nedge += ne;
      for (int e = 0; e < ne; e++) {
        int j = ed[2 * e], k = ed[2 * e + 1];
        double dx = nx0[k] - nx0[j], dy = ny0[k] - ny0[j], L = hypot(dx, dy);
        double p = it.a[0], sh = 0.0;
        if (it.kind == BC_TRACTION) { /* t = -p n + q t: n outward (dy, -dx)/L, t CCW (dx, dy)/L */
          p = -(it.a[0] * dy - it.a[1] * dx) / L;
          sh = (it.a[0] * dx + it.a[1] * dy) / L;
        }
        for (int w = 0; w < 2; w++) {
          int i = w ? k : j;
          int first = nbc[i].ap == 0 && nbc[i].at == 0;
          if (!first && (fabs(nbc[i].ap - p) > 1e-12 * (fabs(p) + fabs(sh)) ||
                         fabs(nbc[i].at - sh) > 1e-12 * (fabs(p) + fabs(sh)) || ehist[i] != it.hist))
            yf_deck_error(&it.loc, "write_y2d: load '%s' changes direction along its boundary, or meets another edge "
                          "load, at node %d: Y2D's edge loads are one normal pressure and one shear per node set "
                          "(straight faces)", bc_id, m->node.id[i]);
          nbc[i].ap = p;
          nbc[i].at = sh;
          ehist[i] = it.hist;
        }
      }
      free(ed);
    }
  }
  /* one history per node */
  for (int i = 0; i < nn; i++) {
    int h = -2;
    const int cand[3] = {nbc[i].a[0] != 0 ? chist[2 * i] : -2, nbc[i].a[1] != 0 ? chist[2 * i + 1] : -2,
                         nbc[i].ap != 0 || nbc[i].at != 0 ? ehist[i] : -2};
    for (int c = 0; c < 3; c++) {
      if (cand[c] == -2) continue;
      if (h != -2 && h != cand[c])
        yf_deck_error(loc, "node %d: its conditions have different time histories (%s and %s): a Y2D BC set has one "
                  "time table", m->node.id[i], h >= 0 ? s->hist[h].name : "none",
                  cand[c] >= 0 ? s->hist[cand[c]].name : "none");
      h = cand[c];
    }
    nbc[i].hist = h < 0 ? -1 : h;
  }
  /* Y2D moves no node of lumped mass <= 1e-10 in the deck's units (ALGORITHMS 7, 9), yfdem moves every node: a
   * scene in tonnes and millimetres with fine cells has such nodes, and Y2D would leave them where they are.
   * Masses as both programs lump them, rho A0 / 3 per triangle corner: summed over a node's triangles, or, in
   * a fractured body, one triangle's for each of its copies.  A node held in both directions and at rest
   * stays put in both programs: not refused (with an initial velocity Y2D would keep it in its kinetic
   * energy, yfdem's fix zeroes it). */
#define HELD_AT_REST(i) (nbc[i].k[0] == 3 && nbc[i].a[0] == 0 && nbc[i].k[1] == 3 && nbc[i].a[1] == 0 && nvx[i] == 0 && \
                         nvy[i] == 0)
  {
    long nlight = 0;
    int first = -1;
    double mfirst = 0.0;
    double *msum = yf_calloc((size_t)nn + 1, sizeof(double), "write_y2d masses");
    for (int t = 0; t < nt; t++) {
      const int *v = tv + 3 * t;
      double a0 = 0.5 * fabs((nx0[v[1]] - nx0[v[0]]) * (ny0[v[2]] - ny0[v[0]]) -
                             (ny0[v[1]] - ny0[v[0]]) * (nx0[v[2]] - nx0[v[0]]));
      double mc = m->mat[pmat[tprop[t]]].rho * a0 / 3.0;
      for (int c = 0; c < 3; c++) {
        if (bset[m->tri.body[t]] < 0) {
          msum[v[c]] += mc;
        } else if (mc <= 1e-10 && !HELD_AT_REST(v[c])) {
          if (first < 0) first = v[c], mfirst = mc;
          nlight++;
        }
      }
    }
    for (int i = 0; i < nn; i++)
      if (ouse[i] && msum[i] <= 1e-10 && !HELD_AT_REST(i)) {
        if (first < 0) first = i, mfirst = msum[i];
        nlight++;
      }
    free(msum);
    if (nlight)
      yf_deck_error(loc, "write_y2d: %ld node%s (first: node %d, lumped mass %g) ha%s a mass at or below Y2D's threshold "
                    "1e-10 in the deck's units: Y2D never moves such a node (ALGORITHMS.md 7, 9), yfdem does; write the "
                    "scene in units that make the masses larger (kg and m rather than tonnes and mm), use coarser "
                    "cells, or hold those nodes at rest (fix ... fixed xy)", nlight, nlight == 1 ? " (or copy)" : "s (or copies)",
                    m->node.id[first], mfirst, nlight == 1 ? "s" : "ve");
  }
#undef HELD_AT_REST
  /* Y2D loads every triangle edge whose two nodes carry an edge load: no more than yfdem's */
  long ny2d = 0;
  for (int t = 0; t < nt; t++)
    for (int c = 0; c < 3; c++) {
      int j = tv[3 * t + c], k = tv[3 * t + (c + 1) % 3];
      ny2d += (nbc[j].ap != 0 && nbc[k].ap != 0) || (nbc[j].at != 0 && nbc[k].at != 0);
    }
  if (ny2d > nedge)
    yf_deck_error(loc, "the edge loads would act on %ld triangle edges in Y2D but on %ld in yfdem: Y2D loads every "
              "edge whose two nodes carry loaded sets (inner edges and faces between two loaded faces included)",
              ny2d, nedge);
  /* sets: 0 free, then in node order */
  int nset = 1, capset = 16;
  NodeBc *sets = yf_malloc((size_t)capset * sizeof(NodeBc), "write_y2d sets");
  sets[0] = (NodeBc){{1, 1}, {0, 0}, 0, 0, -1};
  int *nset_of = yf_malloc((size_t)(nn + 1) * sizeof(int), "write_y2d sets");
  for (int i = 0; i < nn; i++) {
    int b = 0;
    while (b < nset && !same_bc(&sets[b], &nbc[i])) b++;
    if (b == nset) {
      if (nset == capset) sets = yf_realloc(sets, (size_t)(capset *= 2) * sizeof(NodeBc), "write_y2d sets");
      sets[nset++] = nbc[i];
    }
    nset_of[i] = b;
  }

  /* ---- scales of Y2D's coded output (FORMAT.md 7.2): each value is divided by its scale and clipped
   * to [-1, 1], then stored to 2/(90^4 - 1) = 3e-8 of the scale.  The defaults (1) clip every velocity
   * above 1 m/s and every stress above 1 Pa.  Coordinates: twice the largest |coordinate| (room for
   * the scene to move by its own size); velocities: four times the largest initial or prescribed speed
   * (1 m/s when there is none); stresses: 1 % of the stiffest material's 2 mu + 2 volfac lambda (a
   * strain of 1 %: concrete breaks near 1e-4). ---- */
  double cmax = 0.0, vmax = 0.0, smax = 0.0;
  for (int i = 0; i < nn; i++) {
    cmax = fmax(cmax, fmax(fmax(fabs(nx0[i]), fabs(ny0[i])), fmax(fabs(nx[i]), fabs(ny[i]))));
    vmax = fmax(vmax, hypot(nvx[i], nvy[i]));
    for (int c = 0; c < 2; c++)
      if (nbc[i].k[c] == 3) vmax = fmax(vmax, fabs(nbc[i].a[c]) * hist_max(s, chist[2 * i + c]));
  }
  for (int p = 0; p < np; p++) {
    const YfMaterial *mt = &m->mat[pmat[p]];
    smax = fmax(smax, 0.01 * (2.0 * mt->mu + 2.0 * mt->volfac * mt->lambda));
  }
  const double sizc = round_up2(2.0 * cmax), sizv = round_up2(vmax > 0 ? 4.0 * vmax : 1.0), sizs = round_up2(smax);

  /* ---- what the scene derives: as the first run does it ---- */
  run_prepare(s);
  double dt = s->dt;
  if (s->dt_auto) {
    char lim[96];
    dt = s->dt_safety * run_stable_dt(s, lim, sizeof lim);
  }
  if (!(dt > 0)) yf_deck_error(loc, "no time step is set (timestep DT or timestep auto)");
  const YfTriMat *tm = run_tri_mats();
  YfContactExport ce;
  int con = contact_export(s, &ce);
  if (con && !ce.all_pairs)
    yf_warn(loc, "write_y2d: Y2D's contact acts between every pair of participating triangles; the scene's %d "
            "contact rule(s) are widened to all pairs (pairs no rule takes, such as two triangles of one unjointed "
            "body, are evaluated too)", ce.nrule);
  if (con && ce.search_every) /* DIEZON 0 searched every step with no buffer: fewer couples, other friction */
    yf_warn(loc, "write_y2d: 'contact search every' has no Y2D equivalent: Y2D searches when the travel reaches "
            "DIEZON and keeps the couples within DIEZON; written DIEZON = the buffer %g m (a search by travel: "
            "couples and their friction memory can differ; 'contact ... search travel' runs the same in both)", ce.buffer);
  if (con && ce.joined_skip)
    yf_warn(loc, "write_y2d: 'contact joined skip' has no Y2D equivalent: Y2D evaluates couples of joined "
            "triangles too (joined keep)");

  /* ---- time tables ---- */
  int tables = 0;
  for (int b = 0; b < nset; b++) tables |= sets[b].hist >= 0;
  int npts = 0, capk = 4;
  for (int h = 0; h < s->nhist; h++)
    if (s->hist[h].kind == YF_HIST_TABLE && s->hist[h].npts + 4 > capk) capk = s->hist[h].npts + 4;
  double *knot = NULL;
  double tfar = 0;
  if (tables) {
    double tlast = 0;
    for (int h = 0; h < s->nhist; h++)
      if (s->hist[h].kind == YF_HIST_TABLE) tlast = fmax(tlast, s->hist[h].t[s->hist[h].npts - 1]);
      else if (s->hist[h].kind == YF_HIST_RAMP) tlast = fmax(tlast, s->hist[h].t1);
    /* beyond the run and every table: Y2D's factor is 1.0 outside a table, yfdem's the end value */
    tfar = 2.0 * (s->time + (double)steps * dt + tlast) + 1.0;
    knot = yf_malloc((size_t)(nset * capk) * sizeof(double), "write_y2d tables");
    int *kn = yf_malloc((size_t)nset * sizeof(int), "write_y2d tables");
    for (int b = 0; b < nset; b++) {
      kn[b] = hist_knots(s, sets[b].hist, tfar, knot + (size_t)b * capk, capk, loc);
      if (kn[b] > npts) npts = kn[b];
    }
    for (int b = 0; b < nset; b++) /* all sets share the number of points: repeat the last one */
      for (int p = kn[b]; p < npts; p++) knot[(size_t)b * capk + p] = knot[(size_t)b * capk + kn[b] - 1];
    free(kn);
  }

  /* ---- write ---- */
  /* MPI: rank 0 writes the file (whole, wfile.h: PATH.tmp renamed into place); the others
   * format it into /dev/null (the same path, so the same errors), then every rank waits for the
   * file (a deck may read it next) */
  const int w = yf_writer();
  YfWFile wf;
  if (yf_wfile_open(&wf, w ? path : "/dev/null") != 0)
    yf_io_error(loc, "write_y2d: cannot write '%s': %s", path, yf_strerror(errno));
  FILE *f = wf.f;
  fprintf(f, "/* written by yfdem write_y2d from %s line %d */\n", loc && loc->file ? loc->file : "?", loc ? loc->line : 0);
  fprintf(f, "/* %d nodes, %d triangles, %d element properties, %d BC sets%s */\n", nn, nt, np, nset,
          nrow ? ", joints inserted by Y2D at step 0" : "");
  long melem = nt + 3L * nzone + 1, mnopo = nn + 3L * nzone + 1;
  fprintf(f, "/YD/YDC/MCSTEP %ld\n/YD/YDC/NCSTEP 0\n/YD/YDC/DCSTEC %.17g\n/YD/YDC/DCTIME %.17g\n", steps, dt, s->time);
  long icoutf = every > 0 ? every : s->thermo_every > 0 ? s->thermo_every : (steps >= 10 ? steps / 10 : 1);
  fprintf(f, "/YD/YDC/DCGRAY %.17g\n/YD/YDC/ICOUTF %ld\n/YD/YDC/ICSHTF %ld\n", s->gy, icoutf,
          steps >= 10 ? steps / 10 : 1);
  /* the coded output <deck><index>.ym: index i holds the state after i ICOUTF steps */
  fprintf(f, "/YD/YDC/ICOUTI 0\n/YD/YDC/ICOUTP 4\n/YD/YDC/DCSIZC %.17g\n/YD/YDC/DCSIZV %.17g\n"
          "/YD/YDC/DCSIZS %.17g\n", sizc, sizv, sizs);
  fprintf(f, "/YD/YDC/IWFAST %d\n", con && ce.surface_all ? 0 : 1);
  fprintf(f, "/YD/YDE/MELEM %ld\n/YD/YDE/NELEM %d\n/YD/YDE/MELST 1\n/YD/YDE/NELST 1\n/YD/YDE/MELNO 4\n"
          "/YD/YDE/NELNO 3\n", melem, nt);
  put_i(f, "/YD/YDE/I1ELPR", nt, tprop);
  fprintf(f, "/YD/YDE/I2ELTO 21 3 %d\n", nt);
  for (int t = 0; t < nt; t++) fprintf(f, "%d %d %d\n", tv[3 * t], tv[3 * t + 1], tv[3 * t + 2]);
  fprintf(f, "/YD/YDN/MNODIM 2\n/YD/YDN/NNODIM 2\n/YD/YDN/MNOPO %ld\n/YD/YDN/NNOPO %d\n", mnopo, nn);
  put_d2(f, "/YD/YDN/D2NCI", nn, nx0, ny0);
  put_d2(f, "/YD/YDN/D2NCC", nn, nx, ny);
  put_d2(f, "/YD/YDN/D2NVC", nn, nvx, nvy);
  put_i(f, "/YD/YDN/I1NOPR", nn, nset_of);
  put_i(f, "/YD/YDN/I1NOBF", nn, nobf);
  if (con)
    fprintf(f, "/YD/YDI/MICOUP %ld\n/YD/YDI/MISTATE 6\n/YD/YDI/DIEZON %.17g\n", 25L * melem + 1000,
            ce.buffer);
  else
    fprintf(f, "/YD/YDI/MICOUP 0\n");
  /* element properties */
  double *col = yf_malloc((size_t)(np + nset + njs + 1) * sizeof(double), "write_y2d columns");
  int *icol = yf_malloc((size_t)(np + 1) * sizeof(int), "write_y2d columns");
  fprintf(f, "/YD/YDPE/MPROP %d\n/YD/YDPE/NPROP %d\n", np, np);
  for (int p = 0; p < np; p++) icol[p] = 1;
  put_i(f, "/YD/YDPE/I1PTYP", np, icol);
#define PCOL(KEY, EXPR)                                  \
  do {                                                   \
    for (int p = 0; p < np; p++) {                       \
      const YfMaterial *mt = &m->mat[pmat[p]];           \
      (void)mt;                                          \
      col[p] = (EXPR);                                   \
    }                                                    \
    put_d(f, "/YD/YDPE/" KEY, np, col, 1);               \
  } while (0)
  PCOL("D1PERO", mt->rho);
  PCOL("D1PELA", 2.0 * mt->volfac * mt->lambda); /* Y2D's (lambda/2)(J - 1/J) = yfdem's volfac lambda (J - 1/J) */
  PCOL("D1PEMU", mt->mu);
  PCOL("D1PEKS", tm[pmat[p]].k);
  PCOL("D1PEPE", mt->pen_n);
  PCOL("D1PEPT", mt->pen_t);
  PCOL("D1PEFR", mt->fric);
  PCOL("D1PSEM", 0.0);
#undef PCOL
  /* joints */
  if (nrow) {
    fprintf(f, "/YD/YDPJ/MPJSET %d\n/YD/YDPJ/NPJSET %d\n", njs, njs);
    int *ityp = yf_malloc((size_t)njs * sizeof(int), "write_y2d joint sets");
    for (int j = 0; j < njs; j++) ityp[j] = 3;
    put_i(f, "/YD/YDPJ/I1PTYP", njs, ityp);
    free(ityp);
#define JCOL(KEY, FIELD)                                                         \
  do {                                                                           \
    for (int j = 0; j < njs; j++) col[j] = s->joints->set[jsrc[j]].p.FIELD;      \
    put_d(f, "/YD/YDPJ/" KEY, njs, col, 1);                                      \
  } while (0)
    JCOL("D1PJFT", ft);
    JCOL("D1PJFS", fs);
    JCOL("D1PJGF", gf);
    JCOL("D1PJPE", pen);
    JCOL("D1PJCO", coh);
    JCOL("D1PJFR", phi);
#undef JCOL
    int mcol = 2 + maxk, nij = 0;
    fprintf(f, "/YD/YDPM/MPMCOM %d\n/YD/YDPM/MPMCOL %d\n/YD/YDPM/I2PMSET 21 %d %d\n", nrow, mcol, mcol, nrow);
    for (int b = 0; b < nb; b++) {
      if (bset[b] < 0) continue;
      int k = 0;
      for (int p = 0; p < np; p++) k += pbody[p] == b;
      fprintf(f, "%d 3", k);
      for (int p = 0; p < np; p++)
        if (pbody[p] == b) fprintf(f, " %d", p);
      for (int c = k; c < maxk; c++) fprintf(f, " 0");
      fprintf(f, "\n");
      nij += k * (k + 1) / 2;
    }
    fprintf(f, "/YD/YDPM/MPMROW %d\n/YD/YDPM/I2PMIJ 21 3 %d\n", nij, nij);
    for (int p = 0; p < np; p++)
      for (int q = p; q < np; q++)
        if (pbody[p] == pbody[q] && bset[pbody[p]] >= 0) fprintf(f, "%d %d %d\n", p, q, jmap[bset[pbody[p]]]);
  }
  /* BC sets */
  fprintf(f, "/YD/YDPN/MPNSET %d\n/YD/YDPN/NPNSET %d\n", nset, nset);
  int *ik = yf_malloc((size_t)nset * sizeof(int), "write_y2d sets");
  for (int c = 0; c < 2; c++) {
    for (int b = 0; b < nset; b++) ik[b] = sets[b].k[c];
    put_i(f, c ? "/YD/YDPN/I1PNFY" : "/YD/YDPN/I1PNFX", nset, ik);
  }
  double *sc = yf_malloc((size_t)nset * sizeof(double), "write_y2d sets");
  for (int c = 0; c < 4; c++) {
    for (int b = 0; b < nset; b++) sc[b] = c < 2 ? sets[b].a[c] : c == 2 ? sets[b].ap : sets[b].at;
    static const char *const keys[] = {"/YD/YDPN/D1PNAX", "/YD/YDPN/D1PNAY", "/YD/YDPN/D1PNAP", "/YD/YDPN/D1PNAT"};
    put_d(f, keys[c], nset, sc, 1);
  }
  if (tables) {
    fprintf(f, "/YD/YDPN/MPNFACT %d\n/YD/YDPN/NPNFACT %d\n/YD/YDPN/D3PNFAC 123 2 %d %d\n", npts, npts, nset, npts);
    for (int b = 0; b < nset; b++)
      for (int p = 0; p < npts; p++)
        fprintf(f, "%.17g%s", knot[(size_t)b * capk + p], p + 1 == npts ? "\n" : " ");
    for (int b = 0; b < nset; b++)
      for (int p = 0; p < npts; p++) {
        int h = sets[b].hist;
        double v = h < 0 ? 1.0 : history_value(&s->hist[h], knot[(size_t)b * capk + p]);
        fprintf(f, "%.17g%s", v, p + 1 == npts ? "\n" : " ");
      }
  }
  fprintf(f, "$YDOIT\n$YSTOP\n");
  if (yf_wfile_close(&wf, 0, 0) != 0) yf_io_error(loc, "write_y2d: cannot write '%s': %s", path, yf_strerror(errno));
  (void)par_any(0); /* MPI: the file is whole before any rank goes on */
  sim_printf(s, "write_y2d: %s: %d nodes, %d triangles, %d properties, %d BC sets, %d joint set(s), dt %.6g s, %ld steps, "
             "output every %ld steps\n", path, nn, nt, np, nset, njs, dt, steps, icoutf);
  free(ik); free(sc); free(col); free(icol); free(knot);
  free(nx0); free(ngm); free(tv); free(tprop); free(pbody); free(pmat); free(bset); free(jmap); free(jsrc);
  free(zuse); free(ouse); free(nobf); free(nbc); free(chist); free(ehist); free(sets); free(nset_of);
}
