/* bc.c: what holds and drives the scene from outside: fixed supports, prescribed velocities and
 * displacements, point and edge loads, initial velocities, each with an optional time history.
 *
 * Every item is a row of one table (YfBcItem) whose kind says how it acts; adding a kind means
 * one parse branch in deck/cmd_fix.c or cmd_load.c and one case in the apply functions.  Items are resolved
 * to node lists (and boundary edges for distributed loads) at the start of each run, through the
 * group masks, so nodes created by joint insertion (copies of a shared node) are included.
 *
 * Order inside a step (run.c): loads are added to the nodal forces before the update; fixed and
 * prescribed-velocity components override the velocity after the free update; prescribed
 * displacements set the position after it moves.  On a node component that several fixes
 * prescribe, the one given last acts alone (bc_prepare finds it once a run and warns): the others
 * skip it, so its reaction is booked once, from the free velocity to the one imposed.  The work
 * of loads and of constraint reactions is accumulated so that the energy balance (kinetic +
 * strain = external work - dissipation) can be checked.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "bc.h"
#include "err.h"
#include "mesh.h"

typedef struct {
  char id[YF_NAME_MAX];
  YfBcSpec sp;        /* as the deck command gave it                              */
  /* resolved at bc_prepare: */
  int nn, *nodes;     /* nodes acted on                                           */
  unsigned char *acts; /* fixes: per node of the list, bit c set when this fix prescribes its
                          component c (the last fix given that prescribes it acts there)    */
  int ne, *edges;     /* boundary edges (2 node indices each), CCW                */
  double *lf;         /* loads: force applied to each node this step (2 per node)  */
} YfBcItem;

typedef struct YfBc {
  int n;
  YfBcItem *item;
  int *owner;           /* at bc_prepare only (whole scene, 8 B per node, freed after): per
                           node component, the fix that prescribes it (the last given), -1 none */
  unsigned char *warned; /* per item: its overlap with a later fix (bit 0), a jump at a run's
                            start (bit 1), a distributed load's edges (bit 2), its empty group
                            (bit 3) were reported                                         */
  int warned_n;
} YfBc;

static YfBc *bc_get(YfSim *s) {
  if (!s->bc) s->bc = yf_calloc(1, sizeof(YfBc), "bc");
  return s->bc;
}

int bc_count(const YfSim *s) { return s->bc ? s->bc->n : 0; }

int bc_exists(const YfSim *s, const char *id) {
  for (int i = 0; i < bc_count(s); i++)
    if (!strcmp(s->bc->item[i].id, id)) return 1;
  return 0;
}

void bc_add(YfSim *s, const char *id, const YfBcSpec *spec) {
  YfBc *b = bc_get(s);
  b->item = yf_realloc(b->item, (size_t)(b->n + 1) * sizeof *b->item, "bc items");
  YfBcItem *it = &b->item[b->n++];
  memset(it, 0, sizeof *it);
  snprintf(it->id, sizeof it->id, "%s", id);
  it->sp = *spec;
}

int bc_remove(YfSim *s, const char *id, int load) {
  YfBc *b = bc_get(s);
  for (int i = 0; i < b->n; i++) {
    YfBcItem *it = &b->item[i];
    int isload = it->sp.kind >= BC_POINT;
    if (!strcmp(it->id, id) && isload == load) {
      free(it->nodes); free(it->acts); free(it->edges); free(it->lf);
      memmove(it, it + 1, (size_t)(b->n - i - 1) * sizeof *it);
      if (i < b->warned_n) {
        memmove(b->warned + i, b->warned + i + 1, (size_t)(b->warned_n - i - 1));
        b->warned_n--;
      }
      b->n--;
      return 1;
    }
  }
  return 0;
}

int bc_set_velocity(YfSim *s, int group, double vx, double vy) {
  YfNodes *n = &s->model.node;
  uint64_t bit = (uint64_t)1 << group;
  int cnt = 0;
  for (int i = 0; i < n->n; i++)
    if (n->gmask[i] & bit) { n->vx[i] = vx; n->vy[i] = vy; cnt++; }
  return cnt;
}

/* ---------------- resolution and application ---------------- */

/* warned: the item's bits of YfBc.warned; bit 3 says its empty group was reported (once per item:
 * a deck of several runs said it again at every run) */
static void resolve_nodes(YfSim *s, YfBcItem *it, unsigned char *warned) {
  YfNodes *n = &s->model.node;
  free(it->nodes);
  free(it->acts);
  it->nodes = NULL;
  it->acts = NULL;
  it->nn = 0;
  if (it->sp.kind == BC_POINT) {
    /* The target node and all its copies (joint insertion) share the load equally. */
    int target = -1;
    if (it->sp.node_id >= 0) {
      for (int i = 0; i < n->n && target < 0; i++)
        if (n->id[i] == it->sp.node_id) target = i;
    } else {
      double best = INFINITY;
      for (int i = 0; i < n->n; i++) {
        if (n->m[i] <= 0) continue;
        double d = (n->x0[i] - it->sp.px) * (n->x0[i] - it->sp.px) + (n->y0[i] - it->sp.py) * (n->y0[i] - it->sp.py);
        if (d < best) { best = d; target = i; }
      }
    }
    if (target < 0) yf_deck_error(&it->sp.loc, "load '%s': no node to apply it to", it->id);
    if (it->sp.node_id < 0) {
      /* 'point at X Y' far off the mesh (mm typed on a mesh in m) loaded a node 1000 m away and the
       * run ended ok; within one element of the body it is a point given to rounding.  Checked here,
       * at the run, since a mesh given after the load command may be the one it points at. */
      double d = sqrt((n->x0[target] - it->sp.px) * (n->x0[target] - it->sp.px) +
                      (n->y0[target] - it->sp.py) * (n->y0[target] - it->sp.py));
      double reach = mesh_longest_edge(&s->model);
      if (d > reach)
        yf_deck_error(&it->sp.loc, "load '%s': the point (%g, %g) is %g m from the nearest node (node %ld at (%g, %g)), "
                      "farther than the longest triangle edge of the scene, %g m: it lies off the mesh (a coordinate "
                      "in other units?); give a point on the body or within one element of it", it->id, it->sp.px,
                      it->sp.py, d, (long)n->id[target], n->x0[target], n->y0[target], reach);
    }
    int p = n->parent[target];
    for (int i = 0; i < n->n; i++)
      if (n->parent[i] == p && n->m[i] > 0) it->nn++;
    /* a node no triangle meets (an inline 'node' whose triangle was left out) has no mass and is
     * never moved: the force went to it and did nothing, and the run ended ok */
    if (!it->nn)
      yf_deck_error(&it->sp.loc, "load '%s': node %ld belongs to no triangle, so it has no mass and never moves: a "
                    "force on it does nothing; load a node of a triangle ('load %s point at X Y' takes the nearest one)",
                    it->id, (long)n->id[target], it->id);
    it->nodes = yf_malloc((size_t)it->nn * sizeof(int), "load nodes");
    int k = 0;
    for (int i = 0; i < n->n && k < it->nn; i++)
      if (n->parent[i] == p && n->m[i] > 0) it->nodes[k++] = i;
  } else if (it->sp.kind == BC_TRACTION || it->sp.kind == BC_PRESSURE) {
    free(it->edges);
    it->edges = NULL;
    it->ne = mesh_boundary_edges(&s->model, (uint64_t)1 << it->sp.group, &it->edges);
    if (!it->ne && !(*warned & 8))
      yf_warn(&it->sp.loc, "load '%s': group '%s' has no boundary edge (both end nodes must be in the group)",
              it->id, s->model.group[it->sp.group].name);
    /* nodes touched: the edge ends, each edge contributing to its own two nodes */
    it->nn = 2 * it->ne;
    it->nodes = yf_malloc((size_t)(it->nn ? it->nn : 1) * sizeof(int), "load nodes");
    if (it->nn) memcpy(it->nodes, it->edges, (size_t)it->nn * sizeof(int)); /* edges NULL when none */
  } else {
    uint64_t bit = (uint64_t)1 << it->sp.group;
    for (int i = 0; i < n->n; i++) it->nn += (n->gmask[i] & bit) != 0;
    it->nodes = yf_malloc((size_t)(it->nn ? it->nn : 1) * sizeof(int), "fix nodes");
    int k = 0;
    for (int i = 0; i < n->n; i++)
      if (n->gmask[i] & bit) it->nodes[k++] = i;
    if (!it->nn && !(*warned & 8))
      yf_warn(&it->sp.loc, "fix '%s': group '%s' has no nodes", it->id, s->model.group[it->sp.group].name);
  }
  if (!it->nn) *warned |= 8;
  free(it->lf);
  it->lf = yf_calloc((size_t)(it->nn ? it->nn : 1) * 2, sizeof(double), "load forces");
}

/* A node component prescribed by two fixes: the later one acts.  Say so once per earlier fix
 * (a clamped base and a pushed face that share a corner node are common; the corner then moves
 * with the push).  Every fix used to act in turn and book its own reaction, so the supports'
 * work was wrong by m (t1 - v)(t1 - t2) / 2 dt a step and a healthy run was stopped. */
static void warn_overridden(YfSim *s, YfBc *b) {
  const YfNodes *n = &s->model.node;
  for (int i = 0; i < b->n; i++) {
    const YfBcItem *it = &b->item[i];
    if (it->sp.kind > BC_DISPLACEMENT || b->warned[i] & 1) continue;
    int cnt = 0, by = -1, first = -1;
    for (int k = 0; k < it->nn; k++)
      for (int c = 0; c < 2; c++) {
        int o = b->owner[2 * it->nodes[k] + c];
        if (!it->sp.has[c] || o == i || o < 0) continue;
        if (!cnt) { by = o; first = it->nodes[k]; }
        cnt++;
        break;
      }
    if (!cnt) continue;
    b->warned[i] |= 1;
    yf_warn(&it->sp.loc, "fix '%s': %d node%s of it (first: node %ld at %g %g) %s also prescribed by the later "
            "fix '%s'%s, which acts there (on a node component in several fixes, the one given last acts)",
            it->id, cnt, cnt == 1 ? "" : "s", (long)n->id[first], n->x0[first], n->y0[first],
            cnt == 1 ? "is" : "are", b->item[by].id, cnt > 1 ? " or another" : "");
  }
}

/* A displacement fix whose nodes are not where it puts them at the run's start (one added after a
 * run, when the body has moved or sagged, or one whose full displacement applies from the start,
 * without a ramp) moves them there in the first step: a shock whose
 * strain energy no force did work for, which the energy check then stops as energy from nowhere
 * ("still growing"), with advice about the time step.  Say so at the start, once per fix. */
static double factor(const YfSim *s, int hist, double t);
static void warn_jumps(YfSim *s, YfBc *b) {
  const YfNodes *n = &s->model.node;
  double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
  for (int j = 0; j < n->n; j++) {
    lo[0] = fmin(lo[0], n->x0[j]); hi[0] = fmax(hi[0], n->x0[j]);
    lo[1] = fmin(lo[1], n->y0[j]); hi[1] = fmax(hi[1], n->y0[j]);
  }
  double size = n->n ? fmax(hi[0] - lo[0], hi[1] - lo[1]) : 0.0;
  for (int i = 0; i < b->n; i++) {
    const YfBcItem *it = &b->item[i];
    if (it->sp.kind != BC_DISPLACEMENT || b->warned[i] & 2) continue;
    double ph = factor(s, it->sp.hist, s->time), gap = 0.0, moved = 0.0;
    int at = -1;
    for (int k = 0; k < it->nn; k++) {
      int j = it->nodes[k];
      const double x[2] = {n->x[j], n->y[j]}, x0[2] = {n->x0[j], n->y0[j]};
      for (int c = 0; c < 2; c++) {
        if (!(it->acts[k] >> c & 1)) continue;
        double d = fabs(x0[c] + it->sp.a[c] * ph - x[c]);
        if (d > gap) { gap = d; at = j; }
        moved = fmax(moved, fabs(x[c] - x0[c]));
      }
    }
    /* round-off of positions is 1e-16 of the scene; 1e-9 of it is a jump */
    if (at < 0 || !(gap > 1e-9 * size)) continue;
    b->warned[i] |= 2;
    if (!(moved > 1e-9 * size)) {
      /* the nodes are where the mesh put them and the fix asks for its full displacement at once
       * (a pull given without a ramp, the common slip): a history that is 0 at this time is the
       * cure, the advice for sagged nodes below is not */
      char u[2][32];
      for (int c = 0; c < 2; c++) {
        if (it->sp.has[c]) snprintf(u[c], sizeof u[c], "%.6g", it->sp.a[c]);
        else snprintf(u[c], sizeof u[c], "NULL");
      }
      yf_warn(&it->sp.loc, "fix '%s': at the run's start (time %.6g s) its nodes are at their reference positions and "
              "it puts them up to %.3g m away (node %ld) at once: they jump there in the first step, a shock the energy "
              "balance cannot count as work (the energy check may stop the run); give the fix a history that starts "
              "at 0 then, e.g. 'history %s_ramp ramp %.6g T1' (T1 a few periods of the body later) and 'fix %s %s "
              "displacement %s %s history %s_ramp'", it->id, s->time, gap, (long)n->id[at], it->id, s->time, it->id,
              s->model.group[it->sp.group].name, u[0], u[1], it->id);
      continue;
    }
    yf_warn(&it->sp.loc, "fix '%s': at the run's start (time %.6g s) its nodes are up to %.3g m from where it puts "
            "them (node %ld): they jump there in the first step, a shock the energy balance cannot count as work "
            "(the energy check may stop the run); a history cannot help (it scales the displacement from the "
            "reference position); to hold them where they are, use 'unfix %s' then 'fix %s %s velocity %s %s', or "
            "add the fix before the run that moves them", it->id, s->time, gap, (long)n->id[at], it->id, it->id,
            s->model.group[it->sp.group].name, it->sp.has[0] ? "0" : "NULL", it->sp.has[1] ? "0" : "NULL");
  }
}

/* What a distributed load covers, said once when it first acts (as 'group' says its counts): every
 * boundary edge with both ends in the group takes it, so a group from a band region across a
 * block's top held the sides' upper segments too, and a traction "on the top" of a 1 m block took
 * 1.2 m of edges, which nothing showed.  The resultant is at full amplitude on the current edges. */
static void report_edges(YfSim *s, YfBc *b) {
  const YfNodes *n = &s->model.node;
  for (int i = 0; i < b->n; i++) {
    YfBcItem *it = &b->item[i];
    if ((it->sp.kind != BC_TRACTION && it->sp.kind != BC_PRESSURE) || !it->ne || b->warned[i] & 4) continue;
    double len = 0.0, rx = 0.0, ry = 0.0;
    for (int e = 0; e < it->ne; e++) {
      int j = it->edges[2 * e], k = it->edges[2 * e + 1];
      double dx = n->x[k] - n->x[j], dy = n->y[k] - n->y[j], L = sqrt(dx * dx + dy * dy);
      len += L;
      if (it->sp.kind == BC_TRACTION) {
        rx += it->sp.a[0] * L;
        ry += it->sp.a[1] * L;
      } else { /* as bc_apply_loads: inward, p times the outward normal (dy, -dx) reversed */
        rx -= it->sp.a[0] * dy;
        ry += it->sp.a[0] * dx;
      }
    }
    /* a closed or symmetric boundary sums to round-off: print it as the zero it is */
    double big = fabs(it->sp.kind == BC_TRACTION ? fmax(fabs(it->sp.a[0]), fabs(it->sp.a[1])) : it->sp.a[0]) * len;
    if (fabs(rx) < 1e-12 * big) rx = 0.0;
    if (fabs(ry) < 1e-12 * big) ry = 0.0;
    sim_printf(s, "load %s: %d boundary edge%s of group %s, %.6g m long; resultant (%.6g, %.6g) N/m at full amplitude\n",
               it->id, it->ne, it->ne == 1 ? "" : "s", s->model.group[it->sp.group].name, len, rx + 0.0, ry + 0.0);
    b->warned[i] |= 4;
  }
}

void bc_prepare(YfSim *s) {
  YfBc *b = bc_get(s);
  int nn = s->model.node.n, nfix = 0;
  if (b->warned_n < b->n) {
    b->warned = yf_realloc(b->warned, (size_t)b->n, "fix warnings");
    memset(b->warned + b->warned_n, 0, (size_t)(b->n - b->warned_n));
    b->warned_n = b->n;
  }
  for (int i = 0; i < b->n; i++) {
    resolve_nodes(s, &b->item[i], &b->warned[i]);
    nfix += b->item[i].sp.kind <= BC_DISPLACEMENT;
  }
  /* which fix acts on each node component: a whole-scene table for this set-up only (a run keeps
   * each fix's own bits, the size of its list, not 8 B per node of the scene) */
  if (nfix) {
    b->owner = yf_malloc((size_t)(nn ? nn : 1) * 2 * sizeof(int), "fix owners");
    for (int j = 0; j < 2 * nn; j++) b->owner[j] = -1;
    for (int i = 0; i < b->n; i++) {
      const YfBcItem *it = &b->item[i];
      if (it->sp.kind <= BC_DISPLACEMENT)
        for (int k = 0; k < it->nn; k++)
          for (int c = 0; c < 2; c++)
            if (it->sp.has[c]) b->owner[2 * it->nodes[k] + c] = i;
    }
    for (int i = 0; i < b->n; i++) {
      YfBcItem *it = &b->item[i];
      if (it->sp.kind > BC_DISPLACEMENT) continue;
      it->acts = yf_calloc((size_t)(it->nn ? it->nn : 1), 1, "fix components");
      for (int k = 0; k < it->nn; k++)
        for (int c = 0; c < 2; c++)
          if (it->sp.has[c] && b->owner[2 * it->nodes[k] + c] == i) it->acts[k] |= (unsigned char)(1 << c);
    }
    warn_overridden(s, b);
    free(b->owner);
    b->owner = NULL;
  }
  warn_jumps(s, b);
  report_edges(s, b);
}

const YfBcSpec *bc_spec(const YfSim *s, int i, const char **id) {
  const YfBcItem *it = &s->bc->item[i];
  *id = it->id;
  return &it->sp;
}

/* MPI: every node of a fix or load is shared (par.h): the supports' and loads' work is summed
 * over them in list order, so every rank keeps them whole (lists resolved by bc_prepare). */
static void bc_mark_nodes(YfSim *s, unsigned char *mark) {
  const YfBc *b = s->bc;
  for (int i = 0; b && i < b->n; i++)
    for (int k = 0; k < b->item[i].nn; k++) mark[b->item[i].nodes[k]] |= YF_BC_SHARED;
}

static double factor(const YfSim *s, int hist, double t) {
  return hist < 0 ? 1.0 : history_value(&s->hist[hist], t);
}

void bc_apply_loads(YfSim *s) {
  if (!s->bc) return;
  YfNodes *n = &s->model.node;
  for (int i = 0; i < s->bc->n; i++) {
    YfBcItem *it = &s->bc->item[i];
    if (it->sp.kind < BC_POINT) continue;
    double ph = factor(s, it->sp.hist, s->time);
    if (it->sp.kind == BC_POINT) {
      double fx = it->sp.a[0] * ph / it->nn, fy = it->sp.a[1] * ph / it->nn;
      for (int k = 0; k < it->nn; k++) {
        it->lf[2 * k] = fx;
        it->lf[2 * k + 1] = fy;
      }
    } else {
      for (int e = 0; e < it->ne; e++) {
        int j = it->edges[2 * e], k = it->edges[2 * e + 1];
        double dx = n->x[k] - n->x[j], dy = n->y[k] - n->y[j];
        double fx, fy;
        if (it->sp.kind == BC_TRACTION) {
          double L = sqrt(dx * dx + dy * dy);
          fx = 0.5 * it->sp.a[0] * ph * L;
          fy = 0.5 * it->sp.a[1] * ph * L;
        } else {
          /* outward normal (dy, -dx) has the edge length; pressure pushes inwards */
          fx = -0.5 * it->sp.a[0] * ph * dy;
          fy = 0.5 * it->sp.a[0] * ph * dx;
        }
        it->lf[4 * e] = fx; it->lf[4 * e + 1] = fy;
        it->lf[4 * e + 2] = fx; it->lf[4 * e + 3] = fy;
      }
    }
    for (int k = 0; k < it->nn; k++) {
      n->fx[it->nodes[k]] += it->lf[2 * k];
      n->fy[it->nodes[k]] += it->lf[2 * k + 1];
    }
    /* the load's own overflow (an amplitude near a double's range times its history) is named
     * here, not later as a node gone out of range */
    if (it->nn && !(isfinite(it->lf[0]) && isfinite(it->lf[1])))
      yf_numeric_error(s->step + 1, "load '%s': its force is beyond the range of a double at time %.6g s (amplitude "
                       "%.6g x history factor %.6g)", it->id, s->time, fmax(fabs(it->sp.a[0]), fabs(it->sp.a[1])), ph);
  }
}

void bc_save_old(YfSim *s, double *x_old, double *y_old, double *vx_old, double *vy_old) {
  if (!s->bc) return;
  const YfNodes *n = &s->model.node;
  for (int i = 0; i < s->bc->n; i++) {
    const YfBcItem *it = &s->bc->item[i];
    for (int k = 0; k < it->nn; k++) {
      int j = it->nodes[k];
      x_old[j] = n->x[j];
      y_old[j] = n->y[j];
      vx_old[j] = n->vx[j];
      vy_old[j] = n->vy[j];
    }
  }
}

void bc_redo_positions(YfSim *s, const double *x_old, const double *y_old) {
  if (!s->bc) return;
  YfNodes *n = &s->model.node;
  const double dt = s->dt;
  for (int i = 0; i < s->bc->n; i++) {
    const YfBcItem *it = &s->bc->item[i];
    if (it->sp.kind != BC_FIXED && it->sp.kind != BC_VELOCITY) continue;
    for (int k = 0; k < it->nn; k++) {
      int j = it->nodes[k];
      n->x[j] = x_old[j] + dt * n->vx[j];
      n->y[j] = y_old[j] + dt * n->vy[j];
    }
  }
}

/* The reaction [N/m] that changes a node's free velocity by dv [m/s] in a step. */
static double react(const YfSim *s, double m, double dv) {
  double R = m * dv / s->dt;
  return s->mass_damping > 0 ? R * (1.0 + 0.5 * s->mass_damping * s->dt) : R;
}

void bc_constrain_velocities(YfSim *s, const double *vx_old, const double *vy_old) {
  if (!s->bc) return;
  YfNodes *n = &s->model.node;
  for (int i = 0; i < s->bc->n; i++) {
    YfBcItem *it = &s->bc->item[i];
    if (it->sp.kind != BC_FIXED && it->sp.kind != BC_VELOCITY) continue;
    double ph = it->sp.kind == BC_VELOCITY ? factor(s, it->sp.hist, s->time) : 0.0;
    for (int k = 0; k < it->nn; k++) {
      int j = it->nodes[k];
      if (n->m[j] <= 0) continue;
      double *v[2] = {&n->vx[j], &n->vy[j]};
      for (int c = 0; c < 2; c++) {
        if (!(it->acts[k] >> c & 1)) continue;
        double target = it->sp.kind == BC_VELOCITY ? it->sp.a[c] * ph : 0.0;
        /* reaction R = m (v_target - v_free)/dt acting over the step at the mean velocity of the
         * two half steps (the central-difference energy measure); with mass damping the free
         * velocity felt the damping force at its own mean, and the node's dissipation is booked
         * at the imposed one (run.c): the reaction takes the difference, a factor 1 + alpha dt/2 */
        double R = react(s, n->m[j], target - *v[c]);
        double vo = c ? vy_old[j] : vx_old[j];
        s->energy.external_work += R * 0.5 * (target + vo) * s->dt;
        *v[c] = target;
      }
    }
  }
}

void bc_constrain_positions(YfSim *s, const double *x_old, const double *y_old, const double *vx_old,
                            const double *vy_old) {
  YfNodes *n = &s->model.node;
  double t1 = s->time + s->dt;
  if (s->bc) {
    for (int i = 0; i < s->bc->n; i++) {
      YfBcItem *it = &s->bc->item[i];
      if (it->sp.kind != BC_DISPLACEMENT) continue;
      double ph = factor(s, it->sp.hist, t1);
      for (int k = 0; k < it->nn; k++) {
        int j = it->nodes[k];
        if (n->m[j] <= 0) continue;
        double *x[2] = {&n->x[j], &n->y[j]}, *v[2] = {&n->vx[j], &n->vy[j]};
        const double x0[2] = {n->x0[j], n->y0[j]}, xo[2] = {x_old[j], y_old[j]};
        for (int c = 0; c < 2; c++) {
          if (!(it->acts[k] >> c & 1)) continue;
          double target = x0[c] + it->sp.a[c] * ph;
          double vnew = (target - xo[c]) / s->dt;
          double R = react(s, n->m[j], vnew - *v[c]);
          double vo = c ? vy_old[j] : vx_old[j];
          s->energy.external_work += R * 0.5 * (vnew + vo) * s->dt;
          *v[c] = vnew;
          *x[c] = target;
        }
      }
    }
    /* work of the loads of this step at the mean velocity of the two half steps */
    for (int i = 0; i < s->bc->n; i++) {
      YfBcItem *it = &s->bc->item[i];
      if (it->sp.kind < BC_POINT) continue;
      for (int k = 0; k < it->nn; k++) {
        int j = it->nodes[k];
        s->energy.external_work += 0.5 * s->dt * (it->lf[2 * k] * (n->vx[j] + vx_old[j]) + it->lf[2 * k + 1] * (n->vy[j] + vy_old[j]));
      }
    }
  }
}

void bc_free(YfSim *s) {
  if (!s->bc) return;
  for (int i = 0; i < s->bc->n; i++) {
    free(s->bc->item[i].nodes);
    free(s->bc->item[i].acts);
    free(s->bc->item[i].edges);
    free(s->bc->item[i].lf);
  }
  free(s->bc->item);
  free(s->bc->warned);
  free(s->bc);
  s->bc = NULL;
}

const YfBcKind bc_kind_native = {.name = "fix/load", .loads = bc_apply_loads, .prepare = bc_prepare,
                                 .held = bc_count, .save_old = bc_save_old,
                                 .constrain_velocities = bc_constrain_velocities,
                                 .redo_positions = bc_redo_positions,
                                 .constrain_positions = bc_constrain_positions, .mark_nodes = bc_mark_nodes,
                                 .free = bc_free};
