/* par_mpi.c: MPI ranks for ./yfdem_mpi (see par.h for what is shared and what is replicated).
 *
 * Owns: the rank and size, triangle and node ownership (ranges per rank), the slot halo, the
 * element stage's block ranges, the exchanges (node forces, block results, stresses, and the
 * generic concat / exchange / range gather that contact.c and joint.c use), the traffic, time
 * and cross-rank counters of the run report, the deck read from stdin, and the error exit.
 *
 * Errors.  Every rank runs the same deck on the same data, so a deck error or a numerical
 * failure is met by every rank at the same place (block results are shared before they are
 * checked).  Rank 0 prints it, runs the cleanup (summary, closed dumps) and calls MPI_Abort with
 * the exit code, which ends every rank and makes mpirun exit with that code.  An error met by
 * one rank only (a file rank 0 cannot write) takes the same path.  A rank other than 0 that fails
 * alone waits 2 s (rank 0, if it fails too, ends the job first and prints the message once),
 * then prints its message and aborts.  Nothing waits on a rank that has failed, so no hang.
 */
#include <mpi.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include "par.h"
#include "err.h"
#include "elem_tri.h"
#include "contact.h"
#include "joint.h"
#include "run.h"
#include "sim.h"

static struct {
  int rank, size;
  int nt, nblk, block;
  int *tlo;                 /* size + 1: rank r owns triangles tlo[r]..tlo[r+1]-1 (its parts)  */
  int *fb0, *fb1;           /* rank r sums blocks fb0[r]..fb1[r]-1 whole (inside its triangles) */
  int *pcnt, *pdsp;         /* triangles of split blocks per rank (its head and tail pieces)    */
  int npiece;               /* triangles of split blocks, all ranks                            */
  double *piece;            /* 3 per split-block triangle, in triangle order: kdd, bad, J      */
  int *cnt, *dsp;           /* scratch counts and displacements of an allgatherv              */
  double bytes;             /* bytes this rank sent in collectives of the current run          */
  double t_comm, t_elem;    /* wall seconds in exchanges / CPU seconds of divided work (elements,
                               joints, contact screen and kernel): CPU, so a loaded machine's
                               descheduling does not show as imbalance */
  int ghost_min, ghost_max; /* ghost nodes a rank would read in a halo design (measured)       */
  int fail_rank;            /* tests: this rank fails alone at its 5th element stage (-1: none) */
  long nelem;               /* element stages done by this process                             */
  int stress_fresh;         /* every rank's stresses shared since the last element stage        */
  int state_fresh;          /* joints' and contact's owner state too (par_need_all)            */
  /* Node ownership (halo mode): rank r owns nodes nlo[r]..nlo[r+1]-1, the nodes whose first
   * triangle (in the partition order, which numbers nodes as its triangles meet them) is r's.
   * Only the owner sums a node's force; the corner slots another rank's triangles write on it
   * come in the slot halo; then every rank gets every node's force (forces of owned ranges). */
  int halo;                 /* 1: node ranges are contiguous (always after the partition)      */
  int nn;                   /* nodes when prepared                                             */
  int *nlo;                 /* size + 1                                                        */
  int *scnt, *sdsp, *rcnt, *rdsp; /* slot halo: doubles to / from each rank                     */
  int *sslot, *rslot;       /* corner slot of each halo value sent / received, grouped by rank */
  double *sbuf, *rbuf;
  int *xs, *xr, *xsd, *xrd; /* par_concat / par_exchange: counts and displacements (bytes)     */
  char *xbuf;               /* their receive buffer                                            */
  size_t xcap;
  long cross_hits;          /* contact hits of couples whose triangles two ranks own (this rank) */
  double hbytes;            /* of bytes: what went to one rank only (slot halo, contact hits)  */
} P;

static void on_exit_code(int code) {
  /* an interrupt is agreed by every rank at the same step (par_any in the run loop): a
   * collective, clean end (atexit finalizes) */
  if (P.size <= 1 || code == YF_EXIT_INTERRUPT) exit(code);
  if (P.rank != 0) {
    /* if rank 0 met the same error it ends the job first, with one message: mpirun's SIGTERM
     * must then end this rank at once (not set the run's interrupt flag) */
    signal(SIGTERM, SIG_DFL);
    signal(SIGINT, SIG_DFL);
    sleep(2);
    fprintf(stderr, "rank %d: %s\n", P.rank, yf_last_message());
    fflush(stderr);
  }
  MPI_Abort(MPI_COMM_WORLD, code);
  exit(code);
}

static void finalize_at_exit(void) {
  int fin = 0;
  MPI_Finalized(&fin);
  if (!fin) MPI_Finalize();
}

void par_init(int *argc, char ***argv) {
  int got = 0;
  /* OpenMP threads inside a rank; only the main thread calls MPI */
  MPI_Init_thread(argc, argv, MPI_THREAD_FUNNELED, &got);
  MPI_Comm_rank(MPI_COMM_WORLD, &P.rank);
  MPI_Comm_size(MPI_COMM_WORLD, &P.size);
  yf_set_writer(P.rank == 0);
  /* fault injection for tests/check_mpi.c: a failure met by one rank only */
  const char *f = getenv("YFDEM_MPI_FAIL_RANK");
  P.fail_rank = f && *f ? atoi(f) : -1;
  yf_set_exit_hook(on_exit_code);
  atexit(finalize_at_exit);
}

int par_size(void) { return P.size; }

FILE *par_stdin(FILE *in) {
  /* mpirun gives stdin to rank 0 only: it reads the deck and sends it to every rank */
  long n = 0;
  char *buf = NULL;
  if (P.rank == 0) {
    size_t cap = 1 << 16, k;
    buf = yf_malloc(cap, "deck from stdin");
    while ((k = fread(buf + n, 1, cap - (size_t)n, in)) > 0) {
      n += (long)k;
      if ((size_t)n == cap) buf = yf_realloc(buf, cap *= 2, "deck from stdin");
    }
  }
  MPI_Bcast(&n, 1, MPI_LONG, 0, MPI_COMM_WORLD);
  if (P.rank != 0) buf = yf_malloc((size_t)n + 1, "deck from stdin");
  MPI_Bcast(buf, (int)n, MPI_CHAR, 0, MPI_COMM_WORLD);
  FILE *f = fmemopen(buf, (size_t)n, "r"); /* buf lives as long as the program */
  if (!f) yf_io_error(NULL, "cannot read the deck from standard input");
  return f;
}

/* Node ranges and the slot halo from owner[] (node -> rank, -1: no triangle) and trank[]
 * (triangle -> rank).  Nodes no triangle meets go with the node before them.  Halo mode needs
 * owner non-decreasing in node order (the partition numbers nodes so); otherwise the run keeps
 * the replicated gather (every corner force to every rank). */
static void build_halo(const YfSim *s, int *owner, const int *trank) {
  const YfModel *m = &s->model;
  int nn = m->node.n, nt = m->tri.n, S = P.size;
  free(P.nlo); free(P.scnt); free(P.sdsp); free(P.rcnt); free(P.rdsp);
  free(P.sslot); free(P.rslot); free(P.sbuf); free(P.rbuf);
  P.nlo = yf_calloc((size_t)S + 1, sizeof(int), "node ranges");
  P.scnt = yf_calloc((size_t)S + 1, sizeof(int), "slot halo");
  P.sdsp = yf_calloc((size_t)S + 1, sizeof(int), "slot halo");
  P.rcnt = yf_calloc((size_t)S + 1, sizeof(int), "slot halo");
  P.rdsp = yf_calloc((size_t)S + 1, sizeof(int), "slot halo");
  P.nn = nn;
  P.halo = 1;
  for (int i = 0, prev = 0; i < nn; i++) {
    if (owner[i] < 0) owner[i] = prev;
    if (owner[i] < prev) P.halo = 0;
    prev = owner[i];
  }
  for (int r = 0, i = 0; r <= S; r++) {
    while (i < nn && owner[i] < r) i++;
    P.nlo[r] = i;
  }
  P.nlo[S] = nn;
  /* the force slots rank q writes on rank r's nodes (q != r), in slot order: corners of q's
   * triangles, then the joint slots of q's joint blocks (a block goes with the owner of its first
   * joint's lower triangle: joints are sorted by it) */
  int me = P.rank, ns = 0, nr = 0, nt3 = 3 * nt, nsl = nt3 + m->nxslot;
  const YfJoints *J = s->joints;
  int *jrank = NULL;
  if (m->nxslot) {
    int nj = J->n, nb = (nj + YF_JBLOCK - 1) / YF_JBLOCK;
    jrank = yf_malloc((size_t)nj * sizeof(int), "slot halo");
    for (int b = 0; b < nb; b++) {
      int a = J->tri[2 * b * YF_JBLOCK], c = J->tri[2 * b * YF_JBLOCK + 1];
      for (int j = b * YF_JBLOCK; j < nj && j < (b + 1) * YF_JBLOCK; j++) jrank[j] = trank[a < c ? a : c];
    }
  }
#define SLOT_RANKS(k, q, r) int q = (k) < nt3 ? trank[(k) / 3] : jrank[((k) - nt3) / 4]; \
  int r = owner[(k) < nt3 ? m->tri.v[k] : m->xslot_node[(k) - nt3]]
  for (int k = 0; k < nsl; k++) {
    SLOT_RANKS(k, q, r);
    if (q == r) continue;
    if (q == me) P.scnt[r] += 2, ns++;
    if (r == me) P.rcnt[q] += 2, nr++;
  }
  for (int r = 0; r < S; r++) {
    P.sdsp[r + 1] = P.sdsp[r] + P.scnt[r];
    P.rdsp[r + 1] = P.rdsp[r] + P.rcnt[r];
  }
  P.sslot = yf_malloc((size_t)(ns + 1) * sizeof(int), "slot halo");
  P.rslot = yf_malloc((size_t)(nr + 1) * sizeof(int), "slot halo");
  P.sbuf = yf_malloc((size_t)(2 * ns + 1) * sizeof(double), "slot halo");
  P.rbuf = yf_malloc((size_t)(2 * nr + 1) * sizeof(double), "slot halo");
  int *fs = yf_calloc((size_t)S + 1, sizeof(int), "slot halo"), *fr = yf_calloc((size_t)S + 1, sizeof(int), "slot halo");
  for (int k = 0; k < nsl; k++) {
    SLOT_RANKS(k, q, r);
    if (q == r) continue;
    if (q == me) P.sslot[P.sdsp[r] / 2 + fs[r]++] = k;
    if (r == me) P.rslot[P.rdsp[q] / 2 + fr[q]++] = k;
  }
#undef SLOT_RANKS
  free(fs); free(fr); free(jrank);
}

/* What a halo design would exchange (docs/SCALING.md): the nodes rank r reads but does not own.
 * A node belongs to the rank of the first triangle that meets it (nodes are numbered in that
 * order); rank r reads the nodes of its triangles and of the joints whose first triangle it owns. */
static void count_ghosts(const YfSim *s) {
  const YfModel *m = &s->model;
  int nn = m->node.n, nt = m->tri.n;
  int *owner = yf_malloc((size_t)(nn > 0 ? nn : 1) * sizeof(int), "ghost count");
  int *seen = yf_malloc((size_t)(nn > 0 ? nn : 1) * sizeof(int), "ghost count");
  int *trank = yf_malloc((size_t)(nt > 0 ? nt : 1) * sizeof(int), "ghost count");
  for (int i = 0; i < nn; i++) owner[i] = seen[i] = -1;
  for (int r = 0; r < P.size; r++)
    for (int e = P.tlo[r]; e < P.tlo[r + 1]; e++) {
      trank[e] = r;
      for (int c = 0; c < 3; c++)
        if (owner[m->tri.v[3 * e + c]] < 0) owner[m->tri.v[3 * e + c]] = r;
    }
  int *ghosts = yf_calloc((size_t)P.size, sizeof(int), "ghost count");
  const YfJoints *J = s->joints;
  for (int r = 0; r < P.size; r++) { /* seen[q] == r: q already counted for rank r */
    for (int e = P.tlo[r]; e < P.tlo[r + 1]; e++)
      for (int c = 0; c < 3; c++) {
        int q = m->tri.v[3 * e + c];
        if (owner[q] != r && seen[q] != r) seen[q] = r, ghosts[r]++;
      }
    for (int j = 0; J && j < J->n; j++) {
      int ta = J->tri[2 * j], tb = J->tri[2 * j + 1];
      if (trank[ta < tb ? ta : tb] != r) continue;
      for (int c = 0; c < 4; c++) {
        int q = J->node[4 * j + c];
        if (owner[q] != r && seen[q] != r) seen[q] = r, ghosts[r]++;
      }
    }
  }
  P.ghost_min = nn;
  P.ghost_max = 0;
  for (int r = 0; r < P.size; r++) {
    P.ghost_min = ghosts[r] < P.ghost_min ? ghosts[r] : P.ghost_min;
    P.ghost_max = ghosts[r] > P.ghost_max ? ghosts[r] : P.ghost_max;
  }
  build_halo(s, owner, trank);
  free(owner); free(seen); free(trank); free(ghosts);
}

void par_prepare(YfSim *s, int nblk, int block) {
  const YfModel *m = &s->model;
  int nt = m->tri.n, S = P.size;
  if (P.tlo && P.nt == nt && P.nblk == nblk && P.block == block) return; /* the same scene */
  free(P.tlo); free(P.fb0); free(P.fb1); free(P.pcnt); free(P.pdsp); free(P.cnt); free(P.dsp); free(P.piece);
  size_t n1 = (size_t)S + 1;
  P.tlo = yf_malloc(n1 * sizeof(int), "rank ranges");
  P.fb0 = yf_malloc(n1 * sizeof(int), "rank ranges");
  P.fb1 = yf_malloc(n1 * sizeof(int), "rank ranges");
  P.pcnt = yf_malloc(n1 * sizeof(int), "rank ranges");
  P.pdsp = yf_malloc(n1 * sizeof(int), "rank ranges");
  P.cnt = yf_malloc(n1 * sizeof(int), "rank ranges");
  P.dsp = yf_malloc(n1 * sizeof(int), "rank ranges");
  P.nt = nt;
  P.nblk = nblk;
  P.block = block;
  /* rank r owns the triangles of METIS parts r*np/S .. (r+1)*np/S - 1 (contiguous after the
   * renumbering) when the part count is a multiple of the rank count; otherwise (a part is
   * 4096 triangles: 3 parts at 1e4) triangles r*nt/S .. of the partition order, a compact
   * piece of the mesh all the same, and balanced.  It depends on the mesh and the rank count
   * only, and the bits on neither. */
  int by_part = m->part_tri && m->npart >= S && m->npart % S == 0;
  for (int r = 0; r <= S; r++)
    P.tlo[r] = by_part ? m->part_tri[(long)r * m->npart / S] : (int)((long)r * nt / S);
  P.tlo[0] = 0;
  P.tlo[S] = nt;
  /* A block inside one rank's triangles is summed there, as on one rank.  The triangles of a
   * block split between ranks are evaluated one by one by their owners, and every rank sums the
   * block's per-triangle results in triangle order: the same additions as the one-rank loop. */
  P.npiece = 0;
  for (int r = 0; r < S; r++) {
    int e0 = P.tlo[r], e1 = P.tlo[r + 1];
    int b0 = (e0 + block - 1) / block, b1 = e1 == nt ? nblk : e1 / block;
    if (b1 < b0) b1 = b0;
    P.fb0[r] = b0;
    P.fb1[r] = b1;
    int full = b1 > b0 ? (b1 * block < nt ? b1 * block : nt) - b0 * block : 0;
    P.pcnt[r] = e1 - e0 - full;
    P.pdsp[r] = P.npiece;
    P.npiece += P.pcnt[r];
  }
  P.piece = yf_malloc(3 * (size_t)(P.npiece > 0 ? P.npiece : 1) * sizeof(double), "split blocks");
  count_ghosts(s);
}

void par_blocks(int *b0, int *b1) {
  *b0 = P.fb0[P.rank];
  *b1 = P.fb1[P.rank];
}

/* One triangle of a split block: its corner forces and stress, and (kdd, bad, J) packed. */
static void piece_one(YfModel *m, const YfTriMat *tm, int e, double *out) {
  YfTriPass p;
  tri_forces(m, tm, e, e + 1, &p);
  out[0] = p.visc_power;
  out[1] = p.bad >= 0 ? 1.0 : 0.0;
  out[2] = p.badJ;
}

static void allgatherv(void *a, MPI_Datatype type, int size) {
  P.bytes += (double)P.cnt[P.rank] * size * (P.size - 1);
  MPI_Allgatherv(MPI_IN_PLACE, 0, MPI_DATATYPE_NULL, a, P.cnt, P.dsp, type, MPI_COMM_WORLD);
}

/* Every rank's triangles' records of `per` doubles, to every rank. */
static void share_tris(double *a, int per) {
  for (int r = 0; r < P.size; r++) {
    P.cnt[r] = per * (P.tlo[r + 1] - P.tlo[r]);
    P.dsp[r] = per * P.tlo[r];
  }
  allgatherv(a, MPI_DOUBLE, sizeof(double));
}

static void share_blocks(void *a, MPI_Datatype type, int size) {
  for (int r = 0; r < P.size; r++) {
    P.cnt[r] = P.fb1[r] - P.fb0[r];
    P.dsp[r] = P.fb0[r];
  }
  allgatherv(a, type, size);
}

void par_share_elements(YfModel *m, const YfTriMat *tm, double *blk, int *blk_bad, double *blk_badJ, double t_elem) {
  double c0 = yf_cpu_now();
  int r = P.rank, B = P.block, nt = P.nt;
  P.stress_fresh = P.state_fresh = 0;
  /* this rank's head and tail pieces (triangles of blocks it shares with other ranks) */
  double *out = P.piece + 3 * (size_t)P.pdsp[r];
  int e0 = P.tlo[r], e1 = P.tlo[r + 1];
  if (P.fb1[r] > P.fb0[r]) {
    for (int e = e0; e < P.fb0[r] * B; e++, out += 3) piece_one(m, tm, e, out);
    for (int e = P.fb1[r] * B < nt ? P.fb1[r] * B : nt; e < e1; e++, out += 3) piece_one(m, tm, e, out);
  } else {
    for (int e = e0; e < e1; e++, out += 3) piece_one(m, tm, e, out);
  }
  double t1 = yf_now();
  P.t_elem += t_elem + (yf_cpu_now() - c0);
  if (++P.nelem == 5 && P.rank == P.fail_rank)
    yf_exit_with(YF_EXIT_NUMERIC, "error: injected failure on rank %d (YFDEM_MPI_FAIL_RANK) at its element stage %ld",
                 P.rank, P.nelem);
  if (P.size <= 1) return;
  if (!P.halo) share_tris(m->tri.cf, 6); /* every corner force to every rank */
  share_blocks(blk, MPI_DOUBLE, sizeof(double));
  share_blocks(blk_bad, MPI_INT, sizeof(int));
  share_blocks(blk_badJ, MPI_DOUBLE, sizeof(double));
  for (int q = 0; q < P.size; q++) {
    P.cnt[q] = 3 * P.pcnt[q];
    P.dsp[q] = 3 * P.pdsp[q];
  }
  allgatherv(P.piece, MPI_DOUBLE, sizeof(double));
  /* the split blocks, in order: their triangles are consecutive in P.piece */
  const double *pc = P.piece;
  for (int b = 0, k = 0; b < P.nblk && k < P.npiece; b++) {
    int whole = 0;
    for (int q = 0; q < P.size && !whole; q++) whole = b >= P.fb0[q] && b < P.fb1[q];
    if (whole) continue;
    int t1b = (b + 1) * B < nt ? (b + 1) * B : nt;
    double power = 0.0;
    int bad = -1;
    double badJ = 0.0;
    for (int e = b * B; e < t1b; e++, k++, pc += 3) {
      if (bad < 0 && pc[1] != 0.0) {
        bad = e;
        badJ = pc[2];
      }
      power += pc[0];
    }
    blk[b] = power;
    blk_bad[b] = bad;
    blk_badJ[b] = badJ;
  }
  P.t_comm += yf_now() - t1;
}

/* Halo: the force slots (corners, joint slots) other ranks' nodes need, to their owners: border
 * nodes shared by triangles of two ranks, and the far side of joints across a rank border. */
void par_share_slots(YfModel *m) {
  if (P.size <= 1 || !P.halo) return;
  double t0 = yf_now();
  const int nt3 = 3 * m->tri.n;
  double *cf = m->tri.cf, *xf = m->xslot_f;
  for (int k = 0; k < P.sdsp[P.size] / 2; k++) {
    int q = P.sslot[k];
    const double *f = q < nt3 ? cf + 2 * (size_t)q : xf + 2 * (size_t)(q - nt3);
    P.sbuf[2 * k] = f[0];
    P.sbuf[2 * k + 1] = f[1];
  }
  P.bytes += (double)P.sdsp[P.size] * sizeof(double);
  P.hbytes += (double)P.sdsp[P.size] * sizeof(double);
  MPI_Alltoallv(P.sbuf, P.scnt, P.sdsp, MPI_DOUBLE, P.rbuf, P.rcnt, P.rdsp, MPI_DOUBLE, MPI_COMM_WORLD);
  for (int k = 0; k < P.rdsp[P.size] / 2; k++) {
    int q = P.rslot[k];
    double *f = q < nt3 ? cf + 2 * (size_t)q : xf + 2 * (size_t)(q - nt3);
    f[0] = P.rbuf[2 * k];
    f[1] = P.rbuf[2 * k + 1];
  }
  P.t_comm += yf_now() - t0;
}

void par_nodes(int *n0, int *n1) {
  if (P.size <= 1 || !P.halo) return;
  *n0 = P.nlo[P.rank];
  *n1 = P.nlo[P.rank + 1];
}

void par_share_forces(double *fx, double *fy) {
  if (P.size <= 1 || !P.halo) return;
  double t0 = yf_now();
  for (int r = 0; r < P.size; r++) {
    P.cnt[r] = P.nlo[r + 1] - P.nlo[r];
    P.dsp[r] = P.nlo[r];
  }
  allgatherv(fx, MPI_DOUBLE, sizeof(double));
  allgatherv(fy, MPI_DOUBLE, sizeof(double));
  P.t_comm += yf_now() - t0;
}

void par_need_stresses(YfModel *m) {
  if (P.size <= 1 || P.stress_fresh) return;
  double t0 = yf_now();
  share_tris(m->tri.s, 3);
  P.t_comm += yf_now() - t0;
  P.stress_fresh = 1;
}

void par_need_all(YfSim *s) {
  if (P.size <= 1) return;
  par_need_stresses(&s->model);
  if (P.state_fresh) return;
  contact_par_gather(s); /* friction memory, node contact forces */
  joints_par_gather(s);  /* joints' forces, work, damage */
  P.state_fresh = 1;
}

int par_rank(void) { return P.rank; }

void par_note_work(double secs) { P.t_elem += secs; }

void par_note_cross_hits(const int *ij, const int *hk, int nh) {
  const int t1 = P.tlo[P.rank + 1]; /* couple k is this rank's: ij[2k+1] beyond its triangles is another's */
  for (int h = 0; h < nh; h++) P.cross_hits += ij[2 * hk[h] + 1] >= t1;
}
const int *par_node_lo(void) { return P.size > 1 && P.halo ? P.nlo : NULL; }

/* Items sorted by a triangle tri[stride k] (couples by their lower triangle, joint blocks by
 * their first joint's lower triangle) go with that triangle's owner: lo[r] = the first item whose
 * triangle is at or after rank r's first. */
int par_owner_ranges(const int *tri, int stride, int n, int *lo) {
  if (P.size <= 1 || !P.halo) return 0;
  for (int r = 0; r <= P.size; r++) {
    int a = 0, b = n; /* first k in [0, n] with tri[stride k] >= tlo[r] */
    while (a < b) {
      int c = a + (b - a) / 2;
      if (tri[(size_t)stride * c] < P.tlo[r]) a = c + 1;
      else b = c;
    }
    lo[r] = r == P.size ? n : a;
  }
  return 1;
}

static void xroom(size_t need) {
  if (!P.xs) {
    size_t n1 = (size_t)P.size + 1;
    P.xs = yf_calloc(n1, sizeof(int), "rank exchange");
    P.xr = yf_calloc(n1, sizeof(int), "rank exchange");
    P.xsd = yf_calloc(n1, sizeof(int), "rank exchange");
    P.xrd = yf_calloc(n1, sizeof(int), "rank exchange");
  }
  if (need > P.xcap) {
    P.xcap = need + need / 2 + 4096;
    free(P.xbuf);
    P.xbuf = yf_malloc(P.xcap, "rank exchange");
  }
}

const void *par_concat(const void *mine, int nbytes, int *rbytes) {
  double t0 = yf_now();
  xroom(0);
  MPI_Allgather(&nbytes, 1, MPI_INT, rbytes, 1, MPI_INT, MPI_COMM_WORLD);
  size_t tot = 0;
  for (int r = 0; r < P.size; r++) {
    P.xrd[r] = (int)tot;
    tot += (size_t)rbytes[r];
  }
  xroom(tot);
  P.bytes += (double)nbytes * (P.size - 1);
  MPI_Allgatherv(mine, nbytes, MPI_BYTE, P.xbuf, rbytes, P.xrd, MPI_BYTE, MPI_COMM_WORLD);
  P.t_comm += yf_now() - t0;
  return P.xbuf;
}

const void *par_exchange(const void *send, const int *sbytes, int *rbytes) {
  double t0 = yf_now();
  xroom(0);
  MPI_Alltoall(sbytes, 1, MPI_INT, rbytes, 1, MPI_INT, MPI_COMM_WORLD);
  size_t tot = 0;
  int st = 0;
  for (int r = 0; r < P.size; r++) {
    P.xsd[r] = st;
    st += sbytes[r];
    P.xrd[r] = (int)tot;
    tot += (size_t)rbytes[r];
  }
  xroom(tot);
  P.bytes += (double)(st - sbytes[P.rank]);
  P.hbytes += (double)(st - sbytes[P.rank]);
  MPI_Alltoallv(send, sbytes, P.xsd, MPI_BYTE, P.xbuf, rbytes, P.xrd, MPI_BYTE, MPI_COMM_WORLD);
  P.t_comm += yf_now() - t0;
  return P.xbuf;
}

void par_gather_ranges(void *a, const int *lo, int elem_bytes) {
  double t0 = yf_now();
  for (int r = 0; r < P.size; r++) {
    P.cnt[r] = (lo[r + 1] - lo[r]) * elem_bytes;
    P.dsp[r] = lo[r] * elem_bytes;
  }
  allgatherv(a, MPI_BYTE, 1);
  P.t_comm += yf_now() - t0;
}

int par_any(int flag) {
  if (P.size <= 1) return flag;
  int any = 0;
  double t0 = yf_now();
  MPI_Allreduce(&flag, &any, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
  P.t_comm += yf_now() - t0;
  return any;
}

long par_bcast_long(long v) {
  if (P.size > 1) MPI_Bcast(&v, 1, MPI_LONG, 0, MPI_COMM_WORLD);
  return v;
}

const int *par_tri_lo(void) { return P.size > 1 ? P.tlo : NULL; }

/* After a run: what each rank computed and sent, as measured on every rank. */
void par_run_report(YfSim *s, long nsteps, double wall) {
  double mine[4] = {P.t_elem, P.t_comm, P.bytes, P.hbytes}, *all = NULL;
  if (P.rank == 0) all = yf_malloc(4 * (size_t)P.size * sizeof(double), "rank report");
  MPI_Gather(mine, 4, MPI_DOUBLE, all, 4, MPI_DOUBLE, 0, MPI_COMM_WORLD);
  long cross = 0;
  MPI_Reduce(&P.cross_hits, &cross, 1, MPI_LONG, MPI_SUM, 0, MPI_COMM_WORLD);
  P.cross_hits = 0;
  /* breaks of joints whose two triangles two ranks own (the records are on every rank) */
  long jcross = 0;
  int nrec = 0;
  const YfBreak *rec = joints_breaks(s, &nrec);
  for (int i = 0; i < nrec && P.tlo; i++) {
    int a = rec[i].triA, b = rec[i].triB, ra = 0, rb = 0;
    while (ra < P.size - 1 && a >= P.tlo[ra + 1]) ra++;
    while (rb < P.size - 1 && b >= P.tlo[rb + 1]) rb++;
    jcross += ra != rb;
  }
  if (P.rank == 0 && nsteps > 0) {
    double emax = 0, esum = 0, cmax = 0, bsum = 0, hmax = 0;
    int tmin = P.nt, tmax = 0;
    for (int r = 0; r < P.size; r++) {
      emax = all[4 * r] > emax ? all[4 * r] : emax;
      esum += all[4 * r];
      cmax = all[4 * r + 1] > cmax ? all[4 * r + 1] : cmax;
      bsum += all[4 * r + 2];
      hmax = all[4 * r + 3] > hmax ? all[4 * r + 3] : hmax;
      int nt = P.tlo[r + 1] - P.tlo[r];
      tmin = nt < tmin ? nt : tmin;
      tmax = nt > tmax ? nt : tmax;
    }
    double emean = esum / P.size;
    sim_printf(s, "mpi: %d ranks x %d threads; triangles per rank %d..%d; work imbalance %.3f "
               "(CPU of elements, joints and contact: slowest / mean rank; mean %.4g s); %.4g bytes sent per step (border "
               "halo %.4g from the busiest rank); communication %.1f %% of wall (slowest rank); "
               "ghost nodes per rank %d..%d; contact hits between two ranks' triangles %ld; joints broken "
               "across rank borders %ld (all runs so far)\n",
               P.size, s->threads, tmin, tmax, emean > 0 ? emax / emean : 1.0, emean, bsum / (double)nsteps,
               hmax / (double)nsteps,
               wall > 0 ? 100.0 * cmax / wall : 0.0, P.ghost_min, P.ghost_max, cross, jcross);
  }
  free(all);
  P.t_elem = P.t_comm = P.bytes = P.hbytes = 0;
}
