/* run.c: the explicit central-difference time loop and its stages.
 *
 * One step (ALGORITHMS.md 1, 7): forces at x_n and v_{n-1/2} (triangles write per-corner slots
 * in parallel; a node gather sums them in a fixed order, so 1 or N threads give the same bits),
 * external loads, then v_{n+1/2} = v_{n-1/2} + dt (f/m + g) with supports and prescribed motions,
 * x_{n+1} = x_n + dt v_{n+1/2}, t += dt.  Energies are evaluated at thermo lines; the energy
 * balance check (energy.c) stops a run whose balance does not close.
 * Nothing in the step allocates, does I/O (except output at its own stage) or touches strings.
 */
#include <float.h>
#include <math.h>
#include <omp.h>
#include <sys/resource.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>
#include "run.h"
#include "contact.h"
#include "elem_tri.h"
#include "err.h"
#include "joint.h"
#include "partition.h"
#include "energy.h"
#include "par.h"
#include "parfor.h"
#include "threads.h"

static int BLOCK = 2048; /* triangles per block of the force loop: fixed, so sums do not depend on threads */
/* Loops shorter than this run on one thread: a parallel region costs microseconds (much more on
 * a loaded machine) and results are the same bits either way. */
static int PAR_MIN = 16384;
/* Tests make small scenes run threaded (the bits must not change: check_parallel.c). */
void run_set_par_min(int par_min, int block) {
  PAR_MIN = par_min < 0 ? 0 : par_min;
  if (block > 0) BLOCK = block;
}

/* Run-time state derived from the model (rebuilt by run_prepare). */
static struct {
  YfTriMat *tm;
  int ntm;
  int nblk;
  double *blk;        /* per-block partial sums */
  int *blk_bad;
  double *blk_badJ;
  double *xo, *yo, *vxo, *vyo; /* positions and velocities before the update */
  int cap_nodes;
  double e_floor;     /* energy of a 1e-8 strain everywhere: below it, growth is round-off [J/m] */
  double t_wall0;
} R;

/* Build the node -> slot gather lists (CSR) of nodes n0..n1-1: triangle corners (slots
 * 0..3 ntri-1) then the extra slots (joints).  Each node's slots are in increasing slot order,
 * fixed for the whole run.  An MPI rank sums its own nodes' forces only: lists for those alone
 * (the whole scene's were 4 B per node and per slot: 48 MB at 1e6 with joints, on every rank). */
static void build_gather(YfModel *m, int n0, int n1) {
  int nr = n1 - n0, nt3 = 3 * m->tri.n, ns = nt3 + m->nxslot;
  free(m->gather_off);
  free(m->gather_slot);
  m->gather_off = yf_calloc((size_t)nr + 1, sizeof(int), "gather offsets");
  for (int k = 0; k < ns; k++) {
    int i = k < nt3 ? m->tri.v[k] : m->xslot_node[k - nt3];
    if (i >= n0 && i < n1) m->gather_off[i - n0 + 1]++;
  }
  for (int i = 0; i < nr; i++) m->gather_off[i + 1] += m->gather_off[i];
  m->gather_slot = yf_malloc((size_t)(m->gather_off[nr] > 0 ? m->gather_off[nr] : 1) * sizeof(int), "gather slots");
  int *fill = yf_calloc((size_t)nr + 1, sizeof(int), "gather fill");
  for (int k = 0; k < ns; k++) {
    int i = k < nt3 ? m->tri.v[k] : m->xslot_node[k - nt3];
    if (i >= n0 && i < n1) m->gather_slot[m->gather_off[i - n0] + fill[i - n0]++] = k;
  }
  free(fill);
  m->gather_n0 = n0;
  m->gather_n1 = n1;
}

/* The gather lists for the nodes this process sums now (again when a re-cut moves them). */
static void gather_for_ranks(YfModel *m) {
  int n0 = 0, n1 = m->node.n;
  par_nodes(&n0, &n1);
  if (!m->gather_off || m->gather_n0 != n0 || m->gather_n1 != n1) build_gather(m, n0, n1);
}

static void material_consts(YfSim *s) {
  YfModel *m = &s->model;
  free(R.tm);
  R.tm = yf_calloc((size_t)(m->nmat ? m->nmat : 1), sizeof(YfTriMat), "material constants");
  R.ntm = m->nmat;
  for (int i = 0; i < m->nmat; i++) {
    YfMaterial *mt = &m->mat[i];
    double k = mt->visc;
    if (mt->beta > 0) {
      /* Y practice: k = 2 h beta sqrt(E rho), h the smallest edge of this material's triangles */
      double h = INFINITY;
      for (int e = 0; e < m->tri.n; e++) {
        if (m->tri.mat[e] != i) continue;
        const int *v = m->tri.v + 3 * e;
        for (int c = 0; c < 3; c++) {
          int p = v[c], q = v[(c + 1) % 3];
          double L = hypot(m->node.x0[q] - m->node.x0[p], m->node.y0[q] - m->node.y0[p]);
          if (L < h) h = L;
        }
      }
      if (isfinite(h)) k = 2.0 * h * mt->beta * sqrt(mt->E * mt->rho);
    }
    R.tm[i].mu2 = 2.0 * mt->mu;
    R.tm[i].lamv = mt->volfac * mt->lambda;
    R.tm[i].k = k;
    R.tm[i].rho = mt->rho;
  }
}

double run_model_bytes(const YfSim *s) {
  const YfModel *m = &s->model;
  double nodes = (double)m->node.n * (9 * sizeof(double) + 4 * sizeof(int) + sizeof(uint64_t) + 1);
  double tris = (double)m->tri.n * (3 * sizeof(int) + 3 * sizeof(int) + sizeof(uint64_t) +
                                    (4 + 1 + 3 + 6) * sizeof(double) + 3 * sizeof(int));
  return nodes + tris + (double)(m->node.n + 1) * sizeof(int);
}

/* The stable time step: central differences are stable while dt <= 2/omega_max (reduced by the
 * viscous term).  Triangles alone: each triangle's exact omega_max (tri_omega_max).  A node that
 * also carries joints or can meet contact: Weyl's inequality bounds omega^2 of the whole by the
 * sum of the parts' bounds, omega_i^2 <= omega_T^2 + (P_i + K_i) / m_i, with omega_T the largest of
 * its triangles', P_i its joints' penalties and K_i its contact penalties (Gershgorin row sums,
 * joint.h, contact.h), all acting on the same node at once: an impactor pressing on a jointed
 * beam loads its top nodes through all three.  The viscous reduction uses the damping ratio the
 * triangle's viscosity gives that combined mode.  docs/STABILITY.md compares the result with the
 * bisected largest stable step of every deck. */
double run_stable_dt(YfSim *s, char *limiter, size_t n) {
  YfModel *m = &s->model;
  double best = INFINITY;
  int which = -1;
  /* every triangle's omega_max on all threads (a power iteration each: 1 s per 1e6 triangles at
   * setup), then the smallest limit, first of equals, in order: the serial loop's answer */
  const int nt = m->tri.n, nn = m->node.n;
  double *w = yf_malloc((size_t)(nt > 0 ? nt : 1) * sizeof *w, "stable time step");
  YF_PARFOR_IF(nt >= PAR_MIN, schedule(static), for (int e = 0; e < nt; e++) w[e] = tri_omega_max(m, R.tm, e););
  for (int e = 0; e < nt; e++) {
    double d = tri_dt_of_omega(w[e], R.tm + m->tri.mat[e]);
    if (d < best) { best = d; which = e; }
  }
  if (limiter) {
    if (which >= 0)
      model_tri_label(m, which, limiter, n);
    else if (nt > 0) /* rho 1e-300, or a 1e-160 m mesh: every limit underflows (it said "no triangles") */
      snprintf(limiter, n, "no triangle: every limit is beyond a double's range (density, moduli or size)");
    else
      snprintf(limiter, n, "nothing (no triangles)");
  }
  double *P = yf_calloc((size_t)nn + 1, sizeof(double), "stable time step");
  double *K = yf_calloc((size_t)nn + 1, sizeof(double), "stable time step");
  double *pof = yf_calloc((size_t)nn + 1, sizeof(double), "stable time step");
  int *jof = yf_malloc(((size_t)nn + 1) * sizeof(int), "stable time step");
  int *tof = yf_malloc(((size_t)nn + 1) * sizeof(int), "stable time step");
  int *tmax = yf_malloc(((size_t)nn + 1) * sizeof(int), "stable time step");
  for (int i = 0; i < nn; i++) jof[i] = tof[i] = tmax[i] = -1;
  int any = joints_node_penalty(s, P, jof);
  any |= contact_node_stiffness(s, K, tof, pof);
  if (any) {
    for (int e = 0; e < nt; e++)
      for (int c = 0; c < 3; c++) {
        int i = m->tri.v[3 * e + c];
        if (tmax[i] < 0 || w[e] > w[tmax[i]]) tmax[i] = e;
      }
    int bi = -1;
    for (int i = 0; i < nn; i++) {
      double mi = m->node.m[i];
      if (!(P[i] + K[i] > 0) || !(mi > 0) || tmax[i] < 0) continue;
      double wt = w[tmax[i]] > 0 ? w[tmax[i]] : 0.0, wt2 = wt * wt;
      double om = sqrt(wt2 + (P[i] + K[i]) / mi);
      const YfTriMat *mt = R.tm + m->tri.mat[tmax[i]];
      double M = 2.0 * mt->lamv + mt->mu2; /* lambda + 2 mu of the small-strain law */
      /* stiffness-proportional viscosity acts on the triangle's share of the mode only:
       * xi = xi_T omega_T / omega with xi_T = omega_T k / (2 (lambda + 2 mu)) */
      double xi = M > 0 ? wt2 * mt->k / (2.0 * M * om) : 0.0;
      double d = 2.0 / om * tri_visc_factor(xi);
      if (d < best) { best = d; bi = i; }
    }
    if (bi >= 0 && limiter) {
      char what[192];
      if (P[bi] >= K[bi]) joints_describe(s, jof[bi], what, sizeof what);
      else
      {
        char tl[160];
        snprintf(what, sizeof what, "contact penalty %.3g Pa at %s", pof[bi], model_tri_label(m, tof[bi], tl, sizeof tl));
      }
      snprintf(limiter, n, "%s", what);
    }
  }
  free(w); free(P); free(K); free(pof); free(jof); free(tof); free(tmax);
  return best;
}

/* Nodes whose state before the update the boundary-condition kinds need (0: none). */
static int bc_held(const YfSim *s) {
  int n = 0;
  for (int k = 0; k < s->nbc_kind; k++)
    if (s->bc_kind[k]->held) n += s->bc_kind[k]->held(s);
  return n;
}

void run_prepare(YfSim *s) {
  YfModel *m = &s->model;
  if (!m->tri.n) yf_deck_error(NULL, "run: the scene has no triangles (use mesh, triangle or read_y2d first)");
  if (!m->prepared) {
    joints_insert(s); /* fracturing bodies get their own nodes per triangle and joints */
    partition_apply(s); /* first run: METIS parts, nodes/triangles/joints renumbered part by part */
    material_consts(s);
    for (int i = 0; i < m->node.n; i++) m->node.m[i] = 0.0;
    int bad = tri_prepare(m, R.tm);
    if (bad >= 0) {
      char tl[160];
      yf_deck_error(NULL, "%s has non-positive area (%g m^2): its corners must be counter-clockwise and distinct",
                    model_tri_label(m, bad, tl, sizeof tl), 0.5 * m->tri.d0[bad]);
    }
    free(m->gather_off); /* a new scene: its gather lists are made for this rank's nodes below */
    free(m->gather_slot);
    m->gather_off = m->gather_slot = NULL;
    R.nblk = (m->tri.n + BLOCK - 1) / BLOCK;
    free(R.blk); free(R.blk_bad); free(R.blk_badJ);
    R.blk = yf_calloc((size_t)R.nblk, sizeof(double), "block sums");
    R.blk_bad = yf_calloc((size_t)R.nblk, sizeof(int), "block flags");
    R.blk_badJ = yf_calloc((size_t)R.nblk, sizeof(double), "block J");
    R.e_floor = 0;
    for (int e = 0; e < m->tri.n; e++) R.e_floor += 1e-16 * m->mat[m->tri.mat[e]].E * 0.5 * m->tri.d0[e];
    m->prepared = 1;
  }
  par_prepare(s, R.nblk, BLOCK); /* MPI: which triangles of the element stage this rank computes */
  gather_for_ranks(m);
  for (int k = 0; k < s->nbc_kind; k++)
    if (s->bc_kind[k]->prepare) s->bc_kind[k]->prepare(s);
  contact_prepare(s);
  /* positions and velocities before the update: read only by bc.c's supports and loads and by
   * the mass damping, so kept only when one of them is active (fix/load commands and damping may
   * come between runs: checked at every run) */
  if ((bc_held(s) > 0 || s->mass_damping > 0) && R.cap_nodes < m->node.n) {
    R.cap_nodes = m->node.n;
    R.xo = yf_realloc(R.xo, (size_t)R.cap_nodes * sizeof(double), "old positions");
    R.yo = yf_realloc(R.yo, (size_t)R.cap_nodes * sizeof(double), "old positions");
    R.vxo = yf_realloc(R.vxo, (size_t)R.cap_nodes * sizeof(double), "old velocities");
    R.vyo = yf_realloc(R.vyo, (size_t)R.cap_nodes * sizeof(double), "old velocities");
  }
}

/* Kinetic energy of nodes i0..i1-1 (g == NULL), or gravity's work on their displacements (g:
 * gx, gy), added in node order [J/m]. */
static double node_sum(const YfNodes *n, const double *g, int i0, int i1) {
  double sum = 0.0;
  if (g)
    for (int i = i0; i < i1; i++) sum += n->m[i] * (g[0] * (n->x[i] - n->x0[i]) + g[1] * (n->y[i] - n->y0[i]));
  else
    for (int i = i0; i < i1; i++) sum += 0.5 * n->m[i] * (n->vx[i] * n->vx[i] + n->vy[i] * n->vy[i]);
  return sum;
}

/* A sum over the nodes by fixed blocks bk (nbn of E_NBLK), blocks in order (dist: see energies). */
static double node_blocks(const YfNodes *n, const double *g, double *bk, int nbn, int dist);

/* Room for n doubles in *p (capacity *cap): the energies' block sums, grown when the scene does. */
static double *blocks(double **p, int *cap, int n) {
  if (n + 1 > *cap) {
    free(*p);
    *cap = n + 1;
    *p = yf_malloc((size_t)*cap * sizeof(double), "energy blocks");
  }
  return *p;
}

/* The energies as sums over fixed blocks (E_NBLK nodes, BLOCK triangles, the joints' blocks), each
 * added in item order and the blocks in block order: the same bits on any number of threads, and
 * on MPI ranks (dist), where each rank sums the blocks inside what it owns and the blocks it
 * shares are summed from per-item values in item order (par_node_split, par_tri_split; joints by
 * owned blocks), so nothing is gathered: the thermo lines, the energy check and the metrics
 * samples read no other rank's state.  Without dist every block is summed here (the state must
 * be whole: a writer alone, between runs). */
enum { E_NBLK = 4096 }; /* nodes per block (as the Y2D update's Y2D_UBLOCK: one node split serves both) */
static struct { double *ke, *st; int cke, cst; } E;
static int g_booked_zero(const YfSim *s) { return s->g_booked[0] == 0 && s->g_booked[1] == 0; }
static void energies(YfSim *s, int dist) {
  YfModel *m = &s->model;
  const YfNodes *n = &m->node;
  const int nbn = (n->n + E_NBLK - 1) / E_NBLK;
  double *bk = blocks(&E.ke, &E.cke, nbn);
  s->energy.kinetic = node_blocks(n, NULL, bk, nbn, dist);
  const double g[2] = {s->gx, s->gy};
  if (s->g_booked_set && (s->g_booked[0] != g[0] || s->g_booked[1] != g[1])) {
    /* gravity changed since its work was last booked (a deck's 'gravity' between runs): the
     * work done so far stays, and the new g's works from this state on (the work is a function
     * of the state for one g only; the summary lost 3.7e7 J/m at 'gravity 0 0' after a run) */
    double before = g_booked_zero(s) ? 0.0 : node_blocks(n, s->g_booked, bk, nbn, dist);
    double after = s->gx == 0 && s->gy == 0 ? 0.0 : node_blocks(n, g, bk, nbn, dist);
    s->gravity_base += before - after;
  }
  s->g_booked[0] = g[0];
  s->g_booked[1] = g[1];
  s->g_booked_set = 1;
  s->gravity_work = s->gravity_base + (s->gx == 0 && s->gy == 0 ? 0.0 : node_blocks(n, g, bk, nbn, dist));
  double strain = 0.0;
  if (R.tm) {
    const int nt = m->tri.n, nbt = (nt + BLOCK - 1) / BLOCK;
    double *bt = blocks(&E.st, &E.cst, nbt);
    int tb0 = 0, tb1 = nbt;
    double *tp = dist ? par_tri_split(nbt, BLOCK, &tb0, &tb1) : NULL;
    YF_PARFOR_IF(nt >= PAR_MIN, schedule(static),
                 for (int b = tb0; b < tb1; b++)
                   bt[b] = tri_strain_potential(m, R.tm, b * BLOCK, (b + 1) * BLOCK < nt ? (b + 1) * BLOCK : nt););
    if (tp) {
      const int *tlo = par_tri_lo(), e0 = tlo[par_rank()], e1 = tlo[par_rank() + 1];
      const int h1 = tb1 > tb0 ? tb0 * BLOCK : e1, t0 = tb1 > tb0 && tb1 * BLOCK < nt ? tb1 * BLOCK : e1;
      for (int e = e0; e < h1; e++) *tp++ = tri_strain_potential(m, R.tm, e, e + 1);
      for (int e = t0; e < e1; e++) *tp++ = tri_strain_potential(m, R.tm, e, e + 1);
      par_tri_block_sums(bt);
    }
    for (int b = 0; b < nbt; b++) strain += bt[b];
  }
  s->energy.strain = strain;
  s->joint_stored = joints_energy(s, dist); /* intact joints; sets energy.joint_dissipated */
  s->energy.strain += s->joint_stored;
}

static double node_blocks(const YfNodes *n, const double *g, double *bk, int nbn, int dist) {
  const int nn = n->n;
  int kb0 = 0, kb1 = nbn;
  double *piece = dist ? par_node_split(nbn, E_NBLK, &kb0, &kb1) : NULL;
  YF_PARFOR_IF(nn >= PAR_MIN, schedule(static),
               for (int b = kb0; b < kb1; b++)
                 bk[b] = node_sum(n, g, b * E_NBLK, (b + 1) * E_NBLK < nn ? (b + 1) * E_NBLK : nn););
  if (piece) {
    int n0 = 0, n1 = nn;
    par_update_nodes(&n0, &n1, NULL, NULL);
    const int h1 = kb1 > kb0 ? kb0 * E_NBLK : n1, t0 = kb1 > kb0 && kb1 * E_NBLK < nn ? kb1 * E_NBLK : n1;
    for (int i = n0; i < h1; i++) *piece++ = node_sum(n, g, i, i + 1);
    for (int i = t0; i < n1; i++) *piece++ = node_sum(n, g, i, i + 1);
    par_node_block_sums(bk);
  }
  double sum = 0.0;
  for (int b = 0; b < nbn; b++) sum += bk[b];
  return sum;
}

void run_energies(YfSim *s) { energies(s, 1); }
void run_energies_whole(YfSim *s) { energies(s, 0); }

static void thermo_header(YfSim *s) {
  if (s->thermo_custom) {
    s->thermo_custom(s, NULL);
    return;
  }
  sim_printf(s, "%10s %12s %13s %13s %13s %13s %13s %8s %9s %9s\n", "Step", "Time", "KinEng", "StrainEng", "ExtWork",
             "Dissipated", "Balance", "Broken", "Pairs", "Wall");
}

/* The first node of i0..i1-1 whose position or velocity is non-finite or beyond YF_RANGE_MAX, or -1. */
static int nodes_out_of_range(const YfNodes *n, int i0, int i1) {
  for (int i = i0; i < i1; i++)
    if (!(fabs(n->x[i]) <= YF_RANGE_MAX && fabs(n->y[i]) <= YF_RANGE_MAX && fabs(n->vx[i]) <= YF_RANGE_MAX &&
          fabs(n->vy[i]) <= YF_RANGE_MAX))
      return i;
  return -1;
}
static int node_out_of_range(const YfNodes *n) { return nodes_out_of_range(n, 0, n->n); }

/* Before a run: every position and velocity within the range the arithmetic holds (the commands
 * check what they set; this covers every other way in: .y decks, files, earlier runs). */
static void check_range(YfSim *s) {
  const YfNodes *n = &s->model.node;
  int i = node_out_of_range(n);
  if (i < 0) return;
  char a[4][32];
  const double v[4] = {n->x[i], n->y[i], n->vx[i], n->vy[i]};
  for (int k = 0; k < 4; k++) yf_fmt_g(a[k], sizeof a[k], v[k]);
  yf_deck_error(NULL, "run: node %d (body %s) at (%s, %s) m moving at (%s, %s) m/s: beyond +-%g, the range the "
                "arithmetic holds (areas and energies multiply coordinates and velocities)", n->id[i],
                s->model.body[n->body[i]].name, a[0], a[1], a[2], a[3], YF_RANGE_MAX);
}

void run_check_nodes(YfSim *s, int i0, int i1) {
  const YfNodes *n = &s->model.node;
  int i = nodes_out_of_range(n, i0, i1);
  if (i >= 0) {
    char a[4][32];
    const double w[4] = {n->x[i], n->y[i], n->vx[i], n->vy[i]};
    for (int k = 0; k < 4; k++) yf_fmt_g(a[k], sizeof a[k], w[k]);
    yf_numeric_error(s->step, "node %d (body %s) at (%s, %s) m moving at (%s, %s) m/s: beyond +-%g, the range "
                     "the arithmetic holds (time step %.6g s, stable limit %.6g s set by %s)", n->id[i],
                     s->model.body[n->body[i]].name, a[0], a[1], a[2], a[3], YF_RANGE_MAX, s->dt, s->dt_limit,
                     s->dt_limiter);
  }
}

/* A thermo value that is not finite: the run failed; say why instead of printing inf or nan. */
static void thermo_nonfinite(YfSim *s, const double *v, const char *const *names, int nv) {
  run_check_nodes(s, 0, s->model.node.n);
  for (int k = 0; k < nv; k++)
    if (!isfinite(v[k]))
      yf_numeric_error(s->step, "the %s overflows the range of a double (the masses, moduli or velocities "
                       "are too large for the arithmetic)", names[k]);
}

static void thermo_line(YfSim *s) {
  /* MPI: the energies are summed where the state is (a collective); a custom line's group
   * quantities and expressions read any node, so they have the whole state gathered first */
  if (s->thermo_custom) par_need_all(s);
  if (s->thermo_custom) run_check_nodes(s, 0, s->model.node.n); /* its expressions read the state */
  run_energies(s);
  double ext = energy_external(s);
  double diss = s->energy.damping + s->energy.joint_dissipated + s->energy.friction;
  double bal = energy_balance(s); /* energy now + dissipated - energy given; ~0 when healthy */
  static const char *const names[] = {"time", "kinetic energy", "strain energy", "external work",
                                      "dissipated energy", "energy balance"};
  const double v[6] = {s->time, s->energy.kinetic, s->energy.strain, ext, diss, bal};
  for (int k = 0; k < 6; k++)
    if (!isfinite(v[k])) {
      par_need_all(s); /* MPI: every rank is here (the same energies): the diagnosis reads every node */
      thermo_nonfinite(s, v, names, 6);
    }
  if (s->thermo_custom) {
    const double std[YF_TH_N] = {(double)s->step, s->time, s->energy.kinetic, s->energy.strain, ext, diss, bal,
                                 (double)joints_broken(s), (double)contact_pairs(s),
                                 s->wall_s + (yf_now() - R.t_wall0)};
    s->thermo_custom(s, std);
    return;
  }
  sim_printf(s, "%10ld %12.6e %13.6e %13.6e %13.6e %13.6e %13.6e %8ld %9ld %9.2f\n", s->step, s->time,
             s->energy.kinetic, s->energy.strain, ext, diss, bal, joints_broken(s), contact_pairs(s),
             s->wall_s + (yf_now() - R.t_wall0));
}

/* Where this run's wall time went, by stage, as LAMMPS prints its breakdown after a run (the
 * -summary JSON has the totals over all runs in stage_seconds).  "other" is the rest: thermo
 * lines, energy checks, the progress bar. */
static void timing_table(YfSim *s, const double *stage0, double wall) {
  sim_printf(s, "%-10s %10s %7s\n", "stage", "seconds", "%run");
  double sum = 0.0;
  for (int i = 0; i < YF_NSTAGE; i++) {
    double t = yf_stage_time[i] - stage0[i];
    sum += t;
    sim_printf(s, "%-10s %10.3f %7.1f\n", yf_stage_names[i], t, wall > 0 ? 100.0 * t / wall : 0.0);
  }
  double other = wall - sum > 0 ? wall - sum : 0.0;
  sim_printf(s, "%-10s %10.3f %7.1f\n", "other", other, wall > 0 ? 100.0 * other / wall : 0.0);
}

static void progress(YfSim *s, long done, long total, double t0) {
  static double last;
  double t = yf_now();
  if (t - last < 0.5 && done < total) return;
  last = t;
  double frac = total ? (double)done / (double)total : 1.0;
  double eta = frac > 0 ? (t - t0) * (1.0 - frac) / frac : 0;
  char bar[31];
  int k = (int)(frac * 30);
  for (int i = 0; i < 30; i++) bar[i] = i < k ? '#' : ' ';
  bar[30] = 0;
  fprintf(stderr, "\r[%s] %3.0f%% step %ld ETA %.0fs ", bar, 100 * frac, s->step, eta);
  if (done >= total) fprintf(stderr, "\r%60s\r", "");
  fflush(stderr);
}

/* The stages of one step, in order (the run loop below is this list).  Every loop over
 * elements or nodes is a static OpenMP loop whose iterations write only their own slots; sums
 * over blocks are added serially in block order. */

/* elements: constant-strain triangle forces into per-corner slots, viscous power per block */
static void stage_elements(YfSim *s) {
  YfModel *m = &s->model;
  const int nblk = R.nblk, nt = m->tri.n;
  const double c0 = par_work_clock();
  int b0 = 0, b1 = nblk;
  par_blocks(&b0, &b1); /* MPI: the blocks inside this rank's triangles; then every rank gets all results */
  YF_PARFOR_IF(nt >= PAR_MIN, schedule(static), for (int b = b0; b < b1; b++) {
    YfTriPass p;
    int e1 = (b + 1) * BLOCK < nt ? (b + 1) * BLOCK : nt;
    tri_forces(m, R.tm, b * BLOCK, e1, &p);
    R.blk[b] = p.visc_power;
    R.blk_bad[b] = p.bad;
    R.blk_badJ[b] = p.badJ;
  });
  par_share_elements(m, R.tm, R.blk, R.blk_bad, R.blk_badJ, par_work_clock() - c0);
  double power = 0;
  for (int b = 0; b < nblk; b++) {
    if (R.blk_bad[b] >= 0) {
      int e = R.blk_bad[b];
      par_need_all(s); /* MPI: every node, for the diagnosis (every rank is here: blk_bad is shared) */
      /* the summary's energies are the failing step's (they were the last thermo step's, next to
       * this step's external work) */
      run_energies_whole(s);
      if (node_out_of_range(&m->node) >= 0) { /* not an inversion: the motion left the arithmetic */
        static const char *const none[] = {""};
        thermo_nonfinite(s, NULL, none, 0);
      }
      char tl[160];
      model_tri_label(m, e, tl, sizeof tl);
      {
        /* corners so far from the origin that doubles cannot tell them apart (a body moved
         * 1e85 m by a huge velocity): the area is rounding, not an inversion */
        const int *v = m->tri.v + 3 * e;
        double far = 0;
        for (int k = 0; k < 3; k++) far = fmax(far, fmax(fabs(m->node.x[v[k]]), fabs(m->node.y[v[k]])));
        double size = sqrt(fabs(m->tri.d0[e]));
        if (far * DBL_EPSILON > 1e-3 * size)
          yf_numeric_error(s->step + 1, "%s, %.3g m across, is %.3g m from the origin: beyond "
                           "the range the arithmetic holds (doubles keep 16 digits, so its corners cannot be told "
                           "apart); are the velocities (or coordinates) far too large?", tl, size, far);
      }
      char ov[400];
      energy_overlap_note(s, ov, sizeof ov); /* bodies that start overlapping: the likelier cause */
      if (R.blk_badJ[b] <= 0)
        yf_numeric_error(s->step + 1, "%s inverted: J = %.6g (area ratio current/initial); "
                         "the time step (%.6g s, stable limit %.6g s of the undeformed mesh, set by %s) may be too "
                         "large for the mesh as compressed (its limit is lower: try a smaller 'timestep auto "
                         "safety'%s), or the body is crushed beyond what the law allows%s",
                         tl, R.blk_badJ[b], s->dt, s->dt_limit, s->dt_limiter,
                         /* a Y2D deck's step is its DCSTEC, which `yfdem DECK.y` has no timestep command for */
                         s->y2d ? ", or a smaller DCSTEC in the .y deck" : "", ov);
      /* a non-finite stress is an overflow of a growing instability: say what limits the step */
      yf_numeric_error(s->step + 1, "%s: stress is not finite (not a number, or beyond a double): the motion "
                       "blew up (time step %.6g s, stable limit %.6g s set by %s)%s", tl, s->dt, s->dt_limit,
                       s->dt_limiter, ov);
    }
    power += R.blk[b];
  }
  s->energy.damping += power * s->dt;
}

/* joints: cohesive joint forces into their extra slots (only with joints) */
static void stage_joints(YfSim *s) {
  if (s->model.nxslot) joints_forces(s);
}

/* gather: corner (and joint) forces into nodes in fixed slot order, then every boundary-condition
 * kind's external loads */
static void stage_gather(YfSim *s) {
  YfModel *m = &s->model;
  YfNodes *n = &m->node;
  const int nn = n->n, nt3 = 3 * m->tri.n;
  const int *slot = m->gather_slot;
  const double *cf = m->tri.cf, *xf = m->xslot_f;
  int n0 = 0, n1 = nn;
  par_share_slots(m); /* MPI: the slots other ranks wrote on this rank's nodes */
  par_nodes(&n0, &n1); /* MPI: the nodes this rank owns (their forces go to every rank after contact) */
  YF_ASSERT(m->gather_n0 == n0 && m->gather_n1 == n1);
  const int *off = m->gather_off; /* node i's list: off[i - n0] .. off[i - n0 + 1] - 1 */
  YF_PARFOR_IF(nn >= PAR_MIN, schedule(static), for (int i = n0; i < n1; i++) {
    double fx = 0, fy = 0;
    for (int k = off[i - n0]; k < off[i - n0 + 1]; k++) {
      int q = slot[k];
      const double *f = q < nt3 ? cf + 2 * q : xf + 2 * (q - nt3);
      fx += f[0];
      fy += f[1];
    }
    n->fx[i] = fx;
    n->fy[i] = fy;
  });
  for (int k = 0; k < s->nbc_kind; k++)
    if (s->bc_kind[k]->loads) s->bc_kind[k]->loads(s);
}

/* contact: detection when due, then pair forces added in pair order (timed inside) */
static void stage_contact(YfSim *s) { contact_step(s); }

/* update: v_{n+1/2}, then supports, then x_{n+1}.  With damping every node's old velocity is
 * read, and the old state is copied inside the update loops; without, only the supported and
 * loaded nodes' old state is (the kinds' save_old), one pass moves every node with its free velocity,
 * and the supported nodes are moved again after their velocities are imposed: the same
 * operations on every value as velocity update, supports, then position update. */
static void stage_update(YfSim *s) {
  YfNodes *n = &s->model.node;
  const int nn = n->n;
  const double dt = s->dt, gx = s->gx, gy = s->gy, alpha = s->mass_damping;
  par_share_forces(n->fx, n->fy); /* MPI: forces from their owners: the shared nodes', or every node's */
  double *x = n->x, *y = n->y, *vx = n->vx, *vy = n->vy;
  const double *fx = n->fx, *fy = n->fy, *ms = n->m;
  const int keep = alpha > 0, nbc = bc_held(s);
  double *xo = keep || nbc ? R.xo : NULL, *yo = keep || nbc ? R.yo : NULL;
  double *vxo = keep || nbc ? R.vxo : NULL, *vyo = keep || nbc ? R.vyo : NULL;
  if (nbc && !keep)
    for (int k = 0; k < s->nbc_kind; k++)
      if (s->bc_kind[k]->save_old) s->bc_kind[k]->save_old(s, xo, yo, vxo, vyo);
  const YfBcKind *integ = NULL; /* a boundary-condition kind that owns the velocity update */
  for (int k = 0; k < s->nbc_kind; k++)
    if (s->bc_kind[k]->integrate) integ = s->bc_kind[k];
  if (integ) {
    integ->integrate(s, nn >= PAR_MIN, keep ? vxo : NULL, keep ? vyo : NULL, !keep);
  } else if (alpha > 0) {
    /* central-difference mass damping: v+ = ((1 - a dt/2) v- + dt f/m) / (1 + a dt/2) */
    const double c1 = 1.0 - 0.5 * alpha * dt, c2 = 1.0 / (1.0 + 0.5 * alpha * dt);
    YF_PARFOR_IF(nn >= PAR_MIN, schedule(static), for (int i = 0; i < nn; i++) {
      vxo[i] = vx[i];
      vyo[i] = vy[i];
      if (!(ms[i] > 1e-300)) continue;
      vx[i] = (c1 * vx[i] + dt * (fx[i] / ms[i] + gx)) * c2;
      vy[i] = (c1 * vy[i] + dt * (fy[i] / ms[i] + gy)) * c2;
    });
  } else {
    /* MPI: this rank's nodes, then the shared nodes other ranks own (all nodes on one rank) */
    int u0 = 0, u1 = nn, nex = 0;
    const int *ex = NULL;
    par_update_nodes(&u0, &u1, &ex, &nex);
    YF_PARFOR_IF(u1 - u0 >= PAR_MIN, schedule(static), for (int i = u0; i < u1; i++) {
      if (ms[i] > 1e-300) {
        vx[i] += dt * (fx[i] / ms[i] + gx);
        vy[i] += dt * (fy[i] / ms[i] + gy);
      }
      x[i] += dt * vx[i];
      y[i] += dt * vy[i];
    });
    for (int k = 0; k < nex; k++) {
      const int i = ex[k];
      if (ms[i] > 1e-300) {
        vx[i] += dt * (fx[i] / ms[i] + gx);
        vy[i] += dt * (fy[i] / ms[i] + gy);
      }
      x[i] += dt * vx[i];
      y[i] += dt * vy[i];
    }
  }
  for (int k = 0; k < s->nbc_kind; k++)
    if (s->bc_kind[k]->constrain_velocities) s->bc_kind[k]->constrain_velocities(s, vxo, vyo);
  if (alpha > 0) {
    YF_PARFOR_IF(nn >= PAR_MIN, schedule(static), for (int i = 0; i < nn; i++) {
      xo[i] = x[i];
      yo[i] = y[i];
      x[i] += dt * vx[i];
      y[i] += dt * vy[i];
    });
  } else if (nbc) {
    for (int k = 0; k < s->nbc_kind; k++)
      if (s->bc_kind[k]->redo_positions) s->bc_kind[k]->redo_positions(s, xo, yo);
  }
  for (int k = 0; k < s->nbc_kind; k++)
    if (s->bc_kind[k]->constrain_positions) s->bc_kind[k]->constrain_positions(s, xo, yo, vxo, vyo);
  if (alpha > 0) {
    /* dissipated: alpha m |v_n|^2 dt with v_n the mean of the two half-step velocities, after
     * the supports and prescribed displacements, at the velocities the nodes moved with (a held
     * node dissipates nothing; the supports' reactions take the rest of the damping force, bc.c);
     * summed serially: same bits on any threads */
    double diss = 0;
    for (int i = 0; i < nn; i++) {
      double ax = 0.5 * (vx[i] + vxo[i]), ay = 0.5 * (vy[i] + vyo[i]);
      diss += ms[i] * (ax * ax + ay * ay);
    }
    s->energy.damping += alpha * diss * dt;
  }
  par_ghost_exchange(n); /* MPI: the ghosts' new positions and velocities from their owners */
  s->step++;
  s->time += dt;
}

/* One step = these stages in this order (as Box2D v3's solver stages or SWIFT's engine_step);
 * each adds its wall time to its timer (contact times detection and pair forces itself). */
typedef struct {
  void (*fn)(YfSim *s);
  int timer; /* YF_ST_*, -1: timed inside */
} YfStage;
static const YfStage STAGES[] = {
  {stage_elements, YF_ST_ELEMENTS},
  {stage_joints, YF_ST_JOINTS},
  {stage_gather, YF_ST_GATHER},
  {stage_contact, -1},
  {stage_update, YF_ST_UPDATE},
};

static void step_once(YfSim *s) {
  for (size_t k = 0; k < sizeof STAGES / sizeof STAGES[0]; k++) {
    double t0 = yf_now();
    STAGES[k].fn(s);
    if (STAGES[k].timer >= 0) yf_stage_time[STAGES[k].timer] += yf_now() - t0;
  }
}

void run_steps(YfSim *s, long nsteps) {
  run_prepare(s);
  check_range(s);
  contact_check_impact(s, NULL);
  char lim[96];
  double limit = run_stable_dt(s, lim, sizeof lim);
  if (s->dt_auto && !isfinite(limit))
    yf_deck_error(s->dt_loc.file ? &s->dt_loc : NULL, "timestep auto: nothing sets a stable limit (%s); give "
                  "the time step with 'timestep DT'", lim);
  s->dt_limit = limit;
  snprintf(s->dt_limiter, sizeof s->dt_limiter, "%s", lim);
  if (s->dt_auto) {
    s->dt = s->dt_safety * limit;
    s->dt_pending = 0;
    /* E 1e307: omega_max is beyond a double, the limit 0; a step of 0 s would run without moving */
    if (!(s->dt > 0))
      yf_deck_error(s->dt_loc.file ? &s->dt_loc : NULL, "timestep auto: the stable limit %.6g s (set by %s) is "
                    "zero in doubles: the scene's moduli, viscosity, density or sizes are beyond a double's range; use other units",
                    limit, lim);
    sim_printf(s, "timestep auto: dt = %.6g s = %.3g x stable limit %.6g s (set by %s)\n", s->dt, s->dt_safety, limit, lim);
  } else if (!(s->dt > 0)) {
    yf_deck_error(NULL, "run: no time step set (use 'timestep DT' or 'timestep auto')");
  } else if (s->dt > limit && !(limit > 0) && energy_dt_above_limit_ok(s)) {
    yf_warn(s->dt_loc.file ? &s->dt_loc : NULL,
            "the %s time step %.6g s is above every step doubles can tell stable: the stable limit (set by %s) is 0 "
            "in doubles (moduli, viscosity, penalties, density or sizes beyond a double's range); running it as asked: %s",
            s->y2d ? "Y2D deck's" : "deck's", s->dt, lim,
            s->ebal_mode == YF_EBAL_STOP ? "the energy check stops the run if it diverges"
            : s->ebal_mode == YF_EBAL_WARN ? "the energy check warns if it diverges (energy_check warn)"
                                           : "nothing checks whether it diverges (energy_check off)");
  } else if (s->dt > limit && energy_dt_above_limit_ok(s)) {
    /* Y2D never checks dt and its decks choose it by experience (ALGORITHMS.md 10); a native deck
     * that said energy_check warn|off takes stability over: warn only, the energy check (unless
     * off) stops the run if it diverges */
    yf_warn(s->dt_loc.file ? &s->dt_loc : NULL,
            "the %s time step %.6g s is %.3g x the stable limit %.6g s (set by %s); running it as asked: %s",
            s->y2d ? "Y2D deck's" : "deck's", s->dt, s->dt / limit, limit, lim,
            s->ebal_mode == YF_EBAL_STOP ? "the energy check stops the run if it diverges"
            : s->ebal_mode == YF_EBAL_WARN ? "the energy check warns if it diverges (energy_check warn)"
                                           : "nothing checks whether it diverges (energy_check off)");
  } else if (s->dt > limit) {
    yf_deck_error(s->dt_loc.file ? &s->dt_loc : NULL,
                  "timestep %.6g s is above the stable limit %.6g s (set by %s); use at most %.6g s or 'timestep auto'",
                  s->dt, limit, lim, limit);
  }
  /* time is a double: a step below its resolution at the current time leaves it where it is
   * ('timestep 1e-300' after a run: the time stood still and the run ended "ok"); a Y2D deck's time starts
   * at DCTIME, and tools/y2d2deck.py refuses DCTIME + DCSTEC == DCTIME with these words too */
  if (s->time + s->dt == s->time)
    yf_deck_error(s->dt_loc.file ? &s->dt_loc : NULL, "timestep %.6g s is below the resolution of the time %.6g s "
                  "(a double's): the time would not advance; use a step above %.3g s", s->dt, s->time,
                  nextafter(fabs(s->time), INFINITY) - fabs(s->time));
  /* the damped update v+ = ((1 - a dt/2) v- + dt f/m) / (1 + a dt/2) forgets v- at a dt = 2 and
   * beyond it reverses it every step: a body then keeps its speed, flipping sign, and more
   * damping damps less (a sweep of new decks: 99.9 % of the kinetic energy left at a = 1e12) */
  if (s->mass_damping * s->dt > 2.0)
    yf_deck_error(s->damping_loc.file ? &s->damping_loc : NULL,
                  "damping mass %g: alpha dt = %.4g is above 2 (dt = %.6g s): the update would reverse the "
                  "velocities every step instead of damping them; use at most alpha = 2/dt = %.6g 1/s, "
                  "which removes each step's velocity", s->mass_damping, s->mass_damping * s->dt, s->dt,
                  2.0 / s->dt);
  par_run_begin(s); /* MPI: whether each rank updates its own nodes only; the ghosts it reads */
  s->threads = threads_run_begin(); /* the most threads a step may use (threads.c chooses) */
  run_energies(s);
  energy_run_begin(s, R.e_floor);
  s->run_end_step = s->step + nsteps;
  if (!s->model.stress_restored) {
    /* stresses of the current state, so the run's first frame shows them (a restart's are those
     * of its step's element stage, as the uninterrupted run's frame of that step shows them) */
    YfTriPass p;
    tri_forces(&s->model, R.tm, 0, s->model.tri.n, &p);
  }
  s->model.stress_restored = 0;
  YfEvent ev = {.kind = YF_EV_RUN_BEGIN};
  s->runs_begun++; /* from here on the run's outputs exist (its first frames, then its logs) */
  sim_notify(s, &ev);
  double stage0[YF_NSTAGE];
  memcpy(stage0, yf_stage_time, sizeof stage0);
  par_run_clock(); /* MPI: the communication share is of this wall time */
  R.t_wall0 = yf_now();
  double t_start = R.t_wall0;
  thermo_header(s);
  thermo_line(s);
  int tty = s->progress && isatty(2) && yf_writer();
  long searches0 = contact_searches(s);
  s->in_run = 1; /* a restart written from here to the loop's end continues this run (restart.c) */
  for (long k = 0; k < nsteps; k++) {
    threads_step_begin();
    double ts = yf_now();
    step_once(s);
    if (k == 0) energy_first_step(s); /* the start state's contact energy belongs to the budget */
    if (contact_searches(s) != searches0) { /* speeds gained in the run (gravity, loads) can tunnel too */
      searches0 = contact_searches(s);
      contact_check_impact_run(s); /* (MPI: every rank, a collective when the update is divided) */
    }
    par_balance(s); /* MPI: after a contact search, move the ranks' borders if their work is uneven */
    gather_for_ranks(&s->model); /* (a re-cut moves the nodes whose forces this rank sums) */
    double t0 = yf_now();
    threads_after_step(t0 - ts); /* the next step's thread count (same bits on any) */
    ev.kind = YF_EV_STEP; /* frames, metrics samples and periodic restarts when due */
    sim_notify(s, &ev);
    yf_stage_time[YF_ST_OUTPUT] += yf_now() - t0;
    if (s->thermo_every > 0 && s->step % s->thermo_every == 0 && k + 1 < nsteps) thermo_line(s);
    if (energy_check_due(s->step)) {
      run_energies(s); /* the check reads the energies of this step (MPI: a collective, nothing gathered) */
      energy_check(s);
    }
    if (tty) progress(s, k + 1, nsteps, t_start);
    if (par_any(s->interrupted)) { /* MPI: every rank stops at the same step */
      s->interrupted = 1;
      /* finish cleanly: a restart of this step, its frame in every dump, files closed */
      YfEvent iev = {.kind = YF_EV_INTERRUPT, .restart_path = ""};
      sim_notify(s, &iev);
      const char *rp = iev.restart_path, *why = iev.why;
      s->wall_s += yf_now() - R.t_wall0;
      if (rp[0] && s->y2d_program) /* a .y deck has no run command: a native deck of three lines continues it */
        yf_exit_with(YF_EXIT_INTERRUPT, "interrupted at step %ld (time %.6g s): restart written to '%s', frames so far "
                     "kept; to continue, run a deck of the three lines 'read_y2d %s', 'read_restart %s' and "
                     "'run %ld upto'", s->step, s->time, rp, s->y2d_program, rp, s->run_end_step);
      if (rp[0])
        yf_exit_with(YF_EXIT_INTERRUPT, "interrupted at step %ld (time %.6g s): restart written to '%s', frames so far "
                     "kept; to continue, put 'read_restart %s' before the run command of the deck and make it "
                     "'run %ld upto'", s->step, s->time, rp, rp, s->run_end_step);
      yf_exit_with(YF_EXIT_INTERRUPT, "interrupted at step %ld (time %.6g s): frames written so far are kept, but no "
                   "restart could be written (%s)", s->step, s->time, why);
    }
  }
  s->in_run = 0;
  if (s->dt_resume) { /* a run continued from a restart written within it: the deck's timestep auto again */
    s->dt_auto = 1;
    s->dt_safety = s->dt_resume_safety;
    s->dt_resume = 0;
  }
  par_run_end(s); /* MPI: the last state whole on every rank, for what follows */
  run_energies(s);
  energy_check(s);
  energy_run_end(s);
  if (nsteps > 0) thermo_line(s); /* 'run 0' printed its start line twice (LAMMPS prints it once) */
  double wall = yf_now() - R.t_wall0;
  s->wall_s += wall;
  s->elem_steps += (double)s->model.tri.n * (double)nsteps;
  char how[160];
  const char *shared = threads_run_end(how, sizeof how);
  ev.kind = YF_EV_RUN_END;
  sim_notify(s, &ev);
  sim_printf(s, "run: %ld steps of %d triangles in %.3f s wall (%.3g element-steps/s on %d thread%s%s%s)\n", nsteps,
             s->model.tri.n, wall, wall > 0 ? (double)s->model.tri.n * (double)nsteps / wall : 0.0, s->threads,
             s->threads > 1 ? "s" : "", shared ? "; " : "", shared ? shared : "");
  timing_table(s, stage0, wall);
  par_run_report(s, nsteps, wall);
}

const YfTriMat *run_tri_mats(void) { return R.tm; }

void run_free(void) {
  free(E.ke); free(E.st);
  memset(&E, 0, sizeof E);
  free(R.tm); free(R.blk); free(R.blk_bad); free(R.blk_badJ);
  free(R.xo); free(R.yo); free(R.vxo); free(R.vyo);
  memset(&R, 0, sizeof R);
  energy_reset();
}
