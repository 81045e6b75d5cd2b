/* metrics.c: crack measurements of a run (see metrics.h): the `metrics` settings, a per-step
 * tracker (peak tensile stress, first fragment, a sampled time series) and the summary keys
 * (symmetry, midspan crack, crack length by region and orientation, fragments).
 *
 * State is module-static, like the region table: one simulation per process (tests run each
 * case in a forked child; sim_free calls metrics_reset).  The step hook allocates its work
 * arrays once, at the first step after the topology is final (joint insertion happens in
 * run_prepare), and grows the time-series buffer once per run, never inside a step.
 */
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "metrics.h"
#include "par.h"
#include "parfor.h"
#include "joint.h"
#include "region.h"
#include "run.h"
#include "summary.h"
#include "wfile.h"

#define MAX_REG YF_METRICS_REGIONS
#define MAX_REG_SHAPES YF_METRICS_REG_SHAPES

typedef struct {
  long step;
  double time;
  YfEnergy e;
  long broken, opened;
  double len[3], olen[3];
  int frags;
  double s1max;
} Sample;

typedef struct {
  char name[YF_NAME_MAX];
  int nr, r[MAX_REG_SHAPES]; /* region indices (union) */
} Reg;

/* Largest sigma1 of one block of triangles and the first triangle reaching the threshold. */
typedef struct {
  double best, above_val;
  int bt, above;
} PeakBlk;
#define MBLK 4096 /* triangles per block of the sigma1 scan */

static struct {
  int on;             /* any metrics command given */
  int body;           /* measured body, -1 = every fracturing body */
  int mirror_axis;    /* 0 none, 1 x = C, 2 y = C */
  double mirror_c;
  int nreg;
  Reg reg[MAX_REG];
  int midspan;        /* region index, -1 none */
  int peak;           /* track stresses */
  double threshold;   /* stress_first_above threshold [Pa], 0 = none */
  double until;       /* peak_stress only over times <= until [s] (INFINITY: the whole run) */
  char log_path[YF_METRICS_PATH_MAX];
  long every;
  /* tracked */
  double peak_val, peak_time;
  long peak_step;
  int peak_tri;
  int above_found;
  double above_val, above_time;
  long above_step;
  int above_tri;
  double first_frag_time;   /* < 0: not yet */
  long last_nbroken;
  /* work arrays (allocated once per topology) */
  int ntri_alloc, nnode_alloc, njoint_alloc;
  int *par, *first;
  unsigned char *intri;     /* triangle belongs to the measured body */
  PeakBlk *blk;             /* per block of MBLK triangles: the step's largest sigma1 (parallel) */
  long nrec_seen, norec_seen;
  double len_now[3], olen_now[3]; /* broken / opened crack length by mode so far [m] */
  double s1_step;           /* max sigma1 of the last step (for the log) */
  Sample *smp;
  long nsmp, capsmp;
  int adopted;              /* a continued run looked for the earlier run's log (adopt_log) */
  char *earlier;            /* rows of the earlier run's log this run continues (or NULL) */
} M = {.body = -1, .midspan = -1, .every = 100, .first_frag_time = -1, .until = INFINITY};

void metrics_reset(void) {
  free(M.par); free(M.first); free(M.intri); free(M.smp); free(M.blk); free(M.earlier);
  memset(&M, 0, sizeof M);
  M.body = -1;
  M.midspan = -1;
  M.every = 100;
  M.first_frag_time = -1;
  M.until = INFINITY;
}

void metrics_state_save(double d[METRICS_STATE_ND], long l[METRICS_STATE_NL]) {
  const double dd[METRICS_STATE_ND] = {M.peak_val, M.peak_time, M.above_val, M.above_time, M.first_frag_time};
  const long ll[METRICS_STATE_NL] = {M.peak_step, M.peak_tri, M.above_found, M.above_step, M.above_tri, M.last_nbroken};
  memcpy(d, dd, sizeof dd);
  memcpy(l, ll, sizeof ll);
}

void metrics_state_load(const double d[METRICS_STATE_ND], const long l[METRICS_STATE_NL]) {
  M.peak_val = d[0];
  M.peak_time = d[1];
  M.above_val = d[2];
  M.above_time = d[3];
  M.first_frag_time = d[4];
  M.peak_step = l[0];
  M.peak_tri = (int)l[1];
  M.above_found = (int)l[2];
  M.above_step = l[3];
  M.above_tri = (int)l[4];
  M.last_nbroken = l[5];
}

static const char log_head[] = "step,time,kinetic,strain,external_work,damping,joint_dissipated,contact,friction,"
                               "broken,crack_I,crack_II,crack_mixed,fragments,sigma1_max,opened,opened_I,opened_II,"
                               "opened_mixed\n";

/* A run continued by read_restart continues the log of the run it continues, as the dumps do
 * their series: the earlier log's rows of steps before the first one this run samples stay
 * (rows of later steps, written before an interrupt, are this run's to write again).  A log that
 * is missing or not one yfdem wrote starts afresh. */
static void adopt_log(const YfSim *s) {
  size_t len;
  char *t = yf_read_output(M.log_path, &len, "metrics log");
  if (!t) return;
  if (!strncmp(t, log_head, sizeof log_head - 1)) {
    size_t n = yf_rows_before(t + sizeof log_head - 1, s->step);
    M.earlier = yf_malloc(n + 1, "metrics log");
    memcpy(M.earlier, t + sizeof log_head - 1, n);
    M.earlier[n] = 0;
  }
  free(t);
}

/* ---- settings (the `metrics` command, deck/cmd_metrics.c) ---- */

void metrics_set_body(int b) { M.on = 1; M.body = b; }

void metrics_set_mirror(int axis, double c) {
  M.on = 1;
  M.mirror_axis = axis;
  M.mirror_c = c;
}

static int reg_slot(const char *name) {
  int i;
  for (i = 0; i < M.nreg; i++)
    if (!strcmp(M.reg[i].name, name)) break;
  return i;
}

int metrics_region_full(const char *name) { return reg_slot(name) == MAX_REG; }

void metrics_set_region(const char *name, const int *r, int nr) {
  M.on = 1;
  int i = reg_slot(name);
  YF_ASSERT(i < MAX_REG && nr <= MAX_REG_SHAPES);
  if (i == M.nreg) M.nreg++;
  Reg *g = &M.reg[i];
  snprintf(g->name, sizeof g->name, "%s", name);
  g->nr = nr;
  for (int k = 0; k < nr; k++) g->r[k] = r[k];
}

void metrics_set_midspan(int r) { M.on = 1; M.midspan = r; }
void metrics_set_peak(int on) { M.on = 1; M.peak = on; }
void metrics_set_threshold(double s) { M.threshold = s; }
void metrics_set_until(double t) { M.until = t; }

void metrics_set_log(const char *path, long every) {
  M.on = 1;
  snprintf(M.log_path, sizeof M.log_path, "%s", path);
  if (every > 0) M.every = every;
}

/* ---- helpers ---- */

static int uf_find(int *p, int i) {
  while (p[i] != i) {
    p[i] = p[p[i]];
    i = p[i];
  }
  return i;
}
static void uf_union(int *p, int a, int b) {
  a = uf_find(p, a);
  b = uf_find(p, b);
  if (a != b) {
    if (a < b) p[b] = a;
    else p[a] = b;
  }
}

static int tri_measured(const YfSim *s, int t) {
  const YfModel *m = &s->model;
  int b = m->tri.body[t];
  return M.body >= 0 ? b == M.body : m->body[b].fracture;
}

/* Allocate the work arrays for the current topology (outside the step proper: once). */
static int ensure_arrays(YfSim *s) {
  const YfModel *m = &s->model;
  if (M.par && M.ntri_alloc == m->tri.n && M.nnode_alloc == m->node.n) return 1;
  free(M.par); free(M.first); free(M.intri); free(M.blk);
  M.par = malloc((size_t)(m->tri.n + 1) * sizeof(int));
  M.first = malloc((size_t)(m->node.n + 1) * sizeof(int));
  M.intri = malloc((size_t)(m->tri.n + 1));
  M.blk = malloc(((size_t)m->tri.n / MBLK + 1) * sizeof(PeakBlk));
  if (!M.par || !M.first || !M.intri || !M.blk) {
    free(M.par); free(M.first); free(M.intri); free(M.blk);
    M.par = M.first = NULL;
    M.intri = NULL;
    M.blk = NULL;
    return 0;
  }
  M.ntri_alloc = m->tri.n;
  M.nnode_alloc = m->node.n;
  for (int t = 0; t < m->tri.n; t++) M.intri[t] = (unsigned char)tri_measured(s, t);
  return 1;
}

/* Connected pieces of the measured body (shared nodes and intact joints); roots in M.par. */
static int count_fragments(const YfSim *s) {
  const YfModel *m = &s->model;
  int nt = m->tri.n;
  for (int t = 0; t < nt; t++) M.par[t] = t;
  for (int i = 0; i < m->node.n; i++) M.first[i] = -1;
  for (int t = 0; t < nt; t++) {
    if (!M.intri[t]) continue;
    for (int c = 0; c < 3; c++) {
      int v = m->tri.v[3 * t + c];
      if (M.first[v] < 0) M.first[v] = t;
      else uf_union(M.par, M.first[v], t);
    }
  }
  const YfJoints *J = s->joints;
  if (J)
    for (int j = 0; j < J->n; j++)
      if (!J->state[j] && M.intri[J->tri[2 * j]] && M.intri[J->tri[2 * j + 1]])
        uf_union(M.par, J->tri[2 * j], J->tri[2 * j + 1]);
  int n = 0;
  for (int t = 0; t < nt; t++)
    if (M.intri[t] && M.par[t] == t) n++;
  return n;
}

static int mode_slot(int md) { return md == YF_JMODE_I ? 0 : md == YF_JMODE_II ? 1 : 2; }

/* Initial midpoint and direction class of joint j: 0 horizontal, 1 vertical, 2 inclined. */
static int joint_geom(const YfSim *s, int j, double *mx, double *my) {
  const YfNodes *nd = &s->model.node;
  const YfJoints *J = s->joints;
  int a = J->node[4 * j], b = J->node[4 * j + 1];
  double dx = nd->x0[b] - nd->x0[a], dy = nd->y0[b] - nd->y0[a];
  *mx = 0.5 * (nd->x0[a] + nd->x0[b]);
  *my = 0.5 * (nd->y0[a] + nd->y0[b]);
  double ang = atan2(fabs(dy), fabs(dx)) * 180.0 / M_PI; /* 0..90 degrees from the x axis */
  return ang <= 20.0 ? 0 : ang >= 70.0 ? 1 : 2;
}

static int joint_measured(const YfSim *s, int j) {
  const YfJoints *J = s->joints;
  return tri_measured(s, J->tri[2 * j]) || tri_measured(s, J->tri[2 * j + 1]);
}

/* ---- the step hook ---- */

static void sample(YfSim *s) {
  if (M.nsmp >= M.capsmp) return; /* sized at the run's start; never grows inside the loop */
  run_energies(s); /* MPI: a collective (every rank is here); each rank sums what it owns */
  Sample *q = &M.smp[M.nsmp++];
  q->step = s->step;
  q->time = s->time;
  q->e = s->energy;
  q->broken = s->joints ? s->joints->nbroken : 0;
  q->opened = s->joints ? s->joints->nopened : 0;
  memcpy(q->len, M.len_now, sizeof q->len);
  memcpy(q->olen, M.olen_now, sizeof q->olen);
  q->frags = count_fragments(s);
  q->s1max = M.s1_step;
}

void metrics_step(YfSim *s) {
  if (!M.on) return;
  const YfModel *m = &s->model;
  if (M.ntri_alloc != m->tri.n || !M.par) {
    if (!ensure_arrays(s)) return;
  }
  if (M.log_path[0] && M.capsmp - M.nsmp < (s->run_end_step - s->step) / M.every + 2) {
    /* once per run (the first step of a run): room for every sample of the run */
    long cap = M.nsmp + (s->run_end_step - s->step) / M.every + 4;
    Sample *p = realloc(M.smp, (size_t)cap * sizeof(Sample));
    if (p) {
      M.smp = p;
      M.capsmp = cap;
    }
  }
  if (s->restored && !M.adopted && M.log_path[0]) { /* the first step this run makes */
    M.adopted = 1;
    adopt_log(s);
  }
  /* crack length by mode so far (new records only) */
  const YfJoints *J = s->joints;
  if (J) {
    for (long i = M.nrec_seen; i < J->nrec; i++)
      if (joint_measured(s, J->rec[i].joint)) M.len_now[mode_slot(J->rec[i].mode)] += J->rec[i].length;
    M.nrec_seen = J->nrec;
    for (long i = M.norec_seen; i < J->nopened; i++)
      if (joint_measured(s, J->orec[i].joint)) M.olen_now[mode_slot(J->orec[i].mode)] += J->orec[i].length;
    M.norec_seen = J->nopened;
    if (M.first_frag_time < 0 && J->nbroken != M.last_nbroken) {
      M.last_nbroken = J->nbroken;
      if (count_fragments(s) > 1) M.first_frag_time = s->time;
    }
  }
  if (M.peak || M.log_path[0]) {
    /* the largest sigma1 (first triangle of equals) and the first triangle at the threshold, per
     * fixed block on all threads, the blocks combined in order: the serial scan's answer.  A
     * parallel region only from 4 blocks (16384 triangles): below, waking the team every step
     * costs more than the scan (on a busy machine up to a time slice: issue 24's fine beam spent
     * 99.8 s here on 2 threads and 0.85 s on 1).  MPI: each rank scans its own triangles (their
     * stresses are current there) and the ranks' answers are combined in rank order, which is
     * triangle order: the same answer, 24 B per rank instead of every stress. */
    const int nt = m->tri.n, nb = (nt + MBLK - 1) / MBLK;
    const int *tlo = par_tri_lo();
    const int e0 = tlo ? tlo[par_rank()] : 0, e1 = tlo ? tlo[par_rank() + 1] : nt;
    const int want_above = M.peak && M.threshold > 0 && !M.above_found;
    const double thr = M.threshold;
    const unsigned char *in = M.intri;
    const double *ts = m->tri.s;
    PeakBlk *pb = M.blk;
    YF_PARFOR_IF(nb >= 4, schedule(static), for (int b = 0; b < nb; b++) {
      PeakBlk r = {-INFINITY, 0.0, -1, -1};
      const int ta = b * MBLK > e0 ? b * MBLK : e0, t1 = (b + 1) * MBLK < e1 ? (b + 1) * MBLK : e1;
      for (int t = ta; t < t1; t++) {
        if (!in[t]) continue;
        const double *st = ts + 3 * t;
        double c = 0.5 * (st[0] + st[1]), rr = hypot(0.5 * (st[0] - st[1]), st[2]);
        double s1 = c + rr;
        if (s1 > r.best) {
          r.best = s1;
          r.bt = t;
        }
        if (want_above && r.above < 0 && s1 >= thr) {
          r.above = t;
          r.above_val = s1;
        }
      }
      pb[b] = r;
    });
    PeakBlk mine = {-INFINITY, 0.0, -1, -1};
    for (int b = 0; b < nb; b++) {
      if (pb[b].best > mine.best) {
        mine.best = pb[b].best;
        mine.bt = pb[b].bt;
      }
      if (mine.above < 0 && pb[b].above >= 0) {
        mine.above = pb[b].above;
        mine.above_val = pb[b].above_val;
      }
    }
    const PeakBlk *all = &mine;
    int nr = 1;
    if (tlo) {
      static int *rbs, nrbs; /* received sizes (grown once) */
      if (nrbs < par_size() + 1) {
        free(rbs);
        nrbs = par_size() + 1;
        rbs = yf_malloc((size_t)nrbs * sizeof(int), "peak stress");
      }
      all = par_concat(&mine, (int)sizeof mine, rbs);
      nr = par_size();
    }
    double best = -INFINITY;
    int bt = -1;
    for (int q = 0; q < nr; q++) {
      if (all[q].best > best) {
        best = all[q].best;
        bt = all[q].bt;
      }
      if (want_above && !M.above_found && all[q].above >= 0) {
        M.above_found = 1;
        M.above_val = all[q].above_val;
        M.above_time = s->time;
        M.above_step = s->step;
        M.above_tri = all[q].above;
      }
    }
    M.s1_step = best;
    if (M.peak && bt >= 0 && s->time <= M.until && (M.peak_step == 0 || best > M.peak_val)) {
      M.peak_val = best;
      M.peak_time = s->time;
      M.peak_step = s->step;
      M.peak_tri = bt;
    }
  }
  if (M.log_path[0] && s->step % M.every == 0) sample(s);
}

/* ---- summary ---- */

typedef struct {
  double x, y;
} Pt;
static int pt_cmp(const void *a, const void *b) {
  const Pt *p = a, *q = b;
  return p->x < q->x ? -1 : p->x > q->x ? 1 : p->y < q->y ? -1 : p->y > q->y ? 1 : 0;
}

/* Is (x, y) within tol of a point of the sorted array? */
static int pt_has(const Pt *p, int n, double x, double y, double tol) {
  int lo = 0, hi = n;
  while (lo < hi) {
    int mid = (lo + hi) / 2;
    if (p[mid].x < x - tol) lo = mid + 1;
    else hi = mid;
  }
  for (int i = lo; i < n && p[i].x <= x + tol; i++)
    if (fabs(p[i].y - y) <= tol) return 1;
  return 0;
}

static void tri_centroid0(const YfModel *m, int t, double *x, double *y) {
  const int *v = &m->tri.v[3 * t];
  *x = (m->node.x0[v[0]] + m->node.x0[v[1]] + m->node.x0[v[2]]) / 3.0;
  *y = (m->node.y0[v[0]] + m->node.y0[v[1]] + m->node.y0[v[2]]) / 3.0;
}

typedef struct {
  double area, x0, y0, x, y, vx, vy;
} Frag;
static int frag_cmp(const void *a, const void *b) {
  const Frag *p = a, *q = b;
  return p->area > q->area ? -1 : p->area < q->area ? 1 : 0;
}

/* Growing string for JSON arrays (summary time only). */
typedef struct {
  char *b;
  size_t n, cap;
} Str;
static void sput(Str *s, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static void sput(Str *s, const char *fmt, ...) {
  if (!s->b && s->cap == (size_t)-1) return;
  for (;;) {
    va_list ap;
    va_start(ap, fmt);
    size_t room = s->cap - s->n;
    int k = vsnprintf(s->b ? s->b + s->n : NULL, s->b ? room : 0, fmt, ap);
    va_end(ap);
    if (k < 0) return;
    if ((size_t)k < room && s->b) {
      s->n += (size_t)k;
      return;
    }
    size_t nc = (s->cap ? s->cap * 2 : 1024) + (size_t)k;
    char *p = realloc(s->b, nc);
    if (!p) {
      free(s->b);
      s->b = NULL;
      s->cap = (size_t)-1;
      return;
    }
    s->b = p;
    s->cap = nc;
  }
}

/* Mirror symmetry score over opened (which = 0) or broken (1) joints of the measured body: the
 * fraction whose mirror image (initial midpoints, tolerance 1e-3 of the shortest joint) is in the
 * same set.  -1 when the set is empty or memory is short. */
static double symmetry_score(const YfSim *s, int which) {
  const YfJoints *J = s->joints;
  Pt *p = malloc((size_t)(J->n + 1) * sizeof(Pt));
  if (!p) return -1;
  int nb = 0;
  double lmin = INFINITY;
  for (int j = 0; j < J->n; j++) {
    if (!(which ? J->state[j] : J->opened[j]) || !joint_measured(s, j)) continue;
    joint_geom(s, j, &p[nb].x, &p[nb].y);
    if (J->L0[j] < lmin) lmin = J->L0[j];
    nb++;
  }
  double score = -1;
  if (nb) {
    qsort(p, (size_t)nb, sizeof(Pt), pt_cmp);
    double tol = 1e-3 * lmin;
    int ok = 0;
    for (int i = 0; i < nb; i++) {
      double x = p[i].x, y = p[i].y;
      if (M.mirror_axis == 1) x = 2 * M.mirror_c - x;
      else y = 2 * M.mirror_c - y;
      ok += pt_has(p, nb, x, y, tol);
    }
    score = (double)ok / nb;
  }
  free(p);
  return score;
}

/* First mode I record (time order) of a measured joint whose initial midpoint is in region ri. */
static const YfBreak *first_mode_i_in(const YfSim *s, const YfBreak *rec, int n, int ri) {
  for (int i = 0; i < n; i++) {
    double x, y;
    joint_geom(s, rec[i].joint, &x, &y);
    if (rec[i].mode == YF_JMODE_I && joint_measured(s, rec[i].joint) && region_contains(ri, x, y)) return &rec[i];
  }
  return NULL;
}

static void put_event(const char *key, const YfBreak *e) {
  char buf[512];
  if (!e) {
    summary_add_raw(key, "null");
    return;
  }
  snprintf(buf, sizeof buf, "{\"step\": %ld, \"time\": %.17g, \"x\": %.17g, \"y\": %.17g}", e->step, e->time, e->x, e->y);
  summary_add_raw(key, buf);
}

/* Summary keys PFXcrack_length_by_region (by mode, orientation, count), PFXcrack_orientation and
 * PFXcrack_orientation_at_first_fragment from the records rec[0..n-1] (initial midpoints). */
static void region_lengths(const YfSim *s, const YfBreak *rec, int n, const char *pfx) {
  char buf[512], key[96];
  double rl[MAX_REG][8];
  memset(rl, 0, sizeof rl);
  double orient[3] = {0, 0, 0}, orient_ff[3] = {0, 0, 0};
  for (int i = 0; i < n; i++) {
    const YfBreak *b = &rec[i];
    if (!joint_measured(s, b->joint)) continue;
    double x, y;
    int o = joint_geom(s, b->joint, &x, &y);
    orient[o] += b->length;
    if (M.first_frag_time >= 0 && b->time <= M.first_frag_time) orient_ff[o] += b->length;
    for (int r = 0; r < M.nreg; r++) {
      int in = 0;
      for (int k = 0; k < M.reg[r].nr && !in; k++) in = region_contains(M.reg[r].r[k], x, y);
      if (!in) continue;
      rl[r][mode_slot(b->mode)] += b->length;
      rl[r][3] += b->length;
      rl[r][4 + (o == 2 ? 0 : o == 1 ? 1 : 2)] += b->length;
      rl[r][7] += 1;
    }
  }
  Str js = {0};
  sput(&js, "{");
  for (int r = 0; r < M.nreg; r++) {
    char nm[4 * sizeof M.reg[r].name + 8]; /* the deck's name as a JSON string: a Latin-1 byte or a quote in it made
                                           the summary unreadable (not UTF-8, or not JSON) */
    summary_json_string(nm, sizeof nm, M.reg[r].name);
    sput(&js,
         "%s%s: {\"I\": %.17g, \"II\": %.17g, \"mixed\": %.17g, \"total\": %.17g, \"inclined\": %.17g, "
         "\"vertical\": %.17g, \"horizontal\": %.17g, \"count\": %d}",
         r ? ", " : "", nm, rl[r][0], rl[r][1], rl[r][2], rl[r][3], rl[r][4], rl[r][5], rl[r][6], (int)rl[r][7]);
  }
  sput(&js, "}");
  snprintf(key, sizeof key, "%scrack_length_by_region", pfx);
  if (js.b) summary_add_raw(key, js.b);
  free(js.b);
  snprintf(key, sizeof key, "%scrack_orientation", pfx);
  snprintf(buf, sizeof buf, "{\"vertical\": %.17g, \"horizontal\": %.17g, \"inclined\": %.17g}", orient[1], orient[0],
           orient[2]);
  summary_add_raw(key, buf);
  snprintf(key, sizeof key, "%scrack_orientation_at_first_fragment", pfx);
  if (M.first_frag_time >= 0) {
    snprintf(buf, sizeof buf, "{\"vertical\": %.17g, \"horizontal\": %.17g, \"inclined\": %.17g}", orient_ff[1],
             orient_ff[0], orient_ff[2]);
    summary_add_raw(key, buf);
  } else {
    summary_add_raw(key, "null");
  }
  if (*pfx) { /* opened crack length by mode over the whole body (crack_length is joint.c's, broken) */
    double len[4] = {0, 0, 0, 0};
    for (int i = 0; i < n; i++)
      if (joint_measured(s, rec[i].joint)) len[mode_slot(rec[i].mode)] += rec[i].length;
    len[3] = len[0] + len[1] + len[2];
    snprintf(key, sizeof key, "%scrack_length", pfx);
    snprintf(buf, sizeof buf, "{\"I\": %.17g, \"II\": %.17g, \"mixed\": %.17g, \"total\": %.17g}", len[0], len[1], len[2],
             len[3]);
    summary_add_raw(key, buf);
  }
}

static void csv_num(char *buf, size_t n, double v) {
  if (isfinite(v)) snprintf(buf, n, "%.10g", v);
  else buf[0] = 0;
}

static void write_log(YfSim *s) {
  if (!yf_writer()) return;
  YfWFile w;
  if (yf_wfile_open(&w, M.log_path) != 0) { /* runs from the exit path too: there the other outputs are still written */
    yf_output_error("metrics log: cannot write '%s': %s", M.log_path, yf_strerror(errno));
    return;
  }
  FILE *f = w.f;
  fputs(log_head, f);
  if (M.earlier) fputs(M.earlier, f);
  for (long i = 0; i < M.nsmp; i++) {
    const Sample *q = &M.smp[i];
    /* a value that is not a number (sigma1_max with no fracturing body measured; an energy of
     * the step a run blew up at) is an empty field, never inf or nan */
    char v[11][32];
    const double d[11] = {q->time, q->e.kinetic, q->e.strain, q->e.external_work, q->e.damping, q->e.joint_dissipated,
                          q->e.contact, q->e.friction, q->len[0], q->len[1], q->len[2]};
    for (int k = 0; k < 11; k++) csv_num(v[k], sizeof v[k], d[k]);
    char s1[32], ol[3][32];
    csv_num(s1, sizeof s1, q->s1max);
    for (int k = 0; k < 3; k++) csv_num(ol[k], sizeof ol[k], q->olen[k]);
    fprintf(f, "%ld,%s,%s,%s,%s,%s,%s,%s,%s,%ld,%s,%s,%s,%d,%s,%ld,%s,%s,%s\n", q->step, v[0], v[1], v[2], v[3], v[4],
            v[5], v[6], v[7], q->broken, v[8], v[9], v[10], q->frags, s1, q->opened, ol[0], ol[1], ol[2]);
  }
  if (yf_wfile_close(&w, 0, 0) != 0) yf_output_error("metrics log: cannot write '%s': %s", M.log_path, yf_strerror(errno));
}

int metrics_flush_log(YfSim *s, char *err, size_t nerr) {
  (void)err, (void)nerr;
  if (M.on && M.log_path[0] && s->runs_begun) write_log(s);
  return 0;
}

void metrics_summary(YfSim *s) {
  if (!M.on) return;
  const YfModel *m = &s->model;
  if (!ensure_arrays(s)) return;
  const YfJoints *J = s->joints;
  char buf[512];

  /* symmetry about the mirror: over opened cracks (every joint past its peak, broken ones
   * included: `symmetry`) and over broken joints only (`symmetry_broken`) */
  if (M.mirror_axis) {
    double so = J ? symmetry_score(s, 0) : -1, sb = J ? symmetry_score(s, 1) : -1;
    if (so >= 0) summary_add_number("symmetry", so);
    else summary_add_raw("symmetry", "null");
    if (sb >= 0) summary_add_number("symmetry_broken", sb);
    else summary_add_raw("symmetry_broken", "null");
  }

  /* midspan crack: the first mode I crack inside the midspan region: opened (past the peak of
   * the law, the paper's fictitious crack: `midspan_crack_time`, `midspan_crack`) and broken
   * (`midspan_break`) */
  if (M.midspan >= 0) {
    int no = 0, nb = 0;
    const YfBreak *ro = J ? J->orec : NULL, *rb = J ? J->rec : NULL;
    if (J) {
      no = J->nopened;
      nb = J->nrec;
    }
    const YfBreak *ho = first_mode_i_in(s, ro, no, M.midspan), *hb = first_mode_i_in(s, rb, nb, M.midspan);
    if (ho) summary_add_number("midspan_crack_time", ho->time);
    else summary_add_raw("midspan_crack_time", "null");
    put_event("midspan_crack", ho);
    put_event("midspan_break", hb);
  }

  /* crack length by region, mode and orientation, for opened and for broken joints;
   * orientation overall and up to the first fragment */
  region_lengths(s, J ? J->orec : NULL, J ? J->nopened : 0, "opened_");
  region_lengths(s, J ? J->rec : NULL, J ? J->nrec : 0, "");
  if (M.first_frag_time >= 0) summary_add_number("first_fragment_time", M.first_frag_time);
  else summary_add_raw("first_fragment_time", "null");

  /* fragments of the measured body: area, initial and current centroid, mean velocity */
  {
    int nf = count_fragments(s);
    Frag *fr = calloc((size_t)(nf + 1), sizeof(Frag));
    int *id = malloc((size_t)(m->tri.n + 1) * sizeof(int));
    if (fr && id) {
      int k = 0;
      for (int t = 0; t < m->tri.n; t++) id[t] = -1;
      for (int t = 0; t < m->tri.n; t++)
        if (M.intri[t] && M.par[t] == t) id[t] = k++;
      for (int t = 0; t < m->tri.n; t++) {
        if (!M.intri[t]) continue;
        Frag *f = &fr[id[uf_find(M.par, t)]];
        double a = 0.5 * fabs(model_tri_d(m, t, 0)), x0, y0;
        tri_centroid0(m, t, &x0, &y0);
        const int *v = &m->tri.v[3 * t];
        double x = 0, y = 0, vx = 0, vy = 0;
        for (int c = 0; c < 3; c++) {
          x += m->node.x[v[c]] / 3;
          y += m->node.y[v[c]] / 3;
          vx += m->node.vx[v[c]] / 3;
          vy += m->node.vy[v[c]] / 3;
        }
        f->area += a;
        f->x0 += a * x0;
        f->y0 += a * y0;
        f->x += a * x;
        f->y += a * y;
        f->vx += a * vx;
        f->vy += a * vy;
      }
      for (int i = 0; i < nf; i++) {
        Frag *f = &fr[i];
        if (f->area > 0) {
          f->x0 /= f->area; f->y0 /= f->area; f->x /= f->area; f->y /= f->area; f->vx /= f->area; f->vy /= f->area;
        }
      }
      qsort(fr, (size_t)nf, sizeof(Frag), frag_cmp);
      Str js = {0};
      sput(&js, "{\"count\": %d, \"list\": [", nf);
      for (int i = 0; i < nf && i < 500; i++)
        sput(&js, "%s{\"area\": %.9g, \"x0\": %.9g, \"y0\": %.9g, \"x\": %.9g, \"y\": %.9g, \"vx\": %.9g, \"vy\": %.9g}",
             i ? ", " : "", fr[i].area, fr[i].x0, fr[i].y0, fr[i].x, fr[i].y, fr[i].vx, fr[i].vy);
      sput(&js, "]}");
      if (js.b) summary_add_raw("body_fragments", js.b);
      free(js.b);
    }
    free(fr);
    free(id);
  }

  if (M.peak) {
    if (M.peak_step > 0 && M.peak_tri >= 0 && M.peak_tri < m->tri.n) {
      double x, y;
      tri_centroid0(m, M.peak_tri, &x, &y);
      char until[40] = "null"; /* the window's end [s] (null: the whole run) */
      if (isfinite(M.until)) snprintf(until, sizeof until, "%.17g", M.until);
      snprintf(buf, sizeof buf,
               "{\"value\": %.17g, \"time\": %.17g, \"step\": %ld, \"x\": %.17g, \"y\": %.17g, \"tri\": %d, \"until\": %s}",
               M.peak_val, M.peak_time, M.peak_step, x, y, M.peak_tri, until);
      summary_add_raw("peak_stress", buf);
    } else {
      summary_add_raw("peak_stress", "null");
    }
    if (M.threshold > 0) {
      if (M.above_found && M.above_tri < m->tri.n) {
        double x, y;
        tri_centroid0(m, M.above_tri, &x, &y);
        snprintf(buf, sizeof buf,
                 "{\"threshold\": %.17g, \"value\": %.17g, \"time\": %.17g, \"step\": %ld, \"x\": %.17g, \"y\": %.17g, "
                 "\"tri\": %d}",
                 M.threshold, M.above_val, M.above_time, M.above_step, x, y, M.above_tri);
        summary_add_raw("stress_first_above", buf);
      } else {
        summary_add_raw("stress_first_above", "null");
      }
    }
  }
  if (M.log_path[0] && s->runs_begun) write_log(s); /* none for a deck that failed before its first run began */
}
