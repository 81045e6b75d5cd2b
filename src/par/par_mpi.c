/* par_mpi.c: MPI ranks for ./yfdem_mpi (see par.h for what is shared and what is replicated).
 *
 * Owns: the rank and size, triangle and node ownership (ranges per rank), the slot halo, the
 * element stage's and the node sums' block ranges, the divided update (which nodes a rank
 * updates, its ghost lists and their exchange, the shared nodes of fixes and loads), the
 * exchanges (node forces, block results, stresses, node state for readers, and the generic
 * concat / exchange / range gather that contact.c and joint.c use), the traffic, time and
 * cross-rank counters of the run report, the deck read from stdin, and the error exit.
 *
 * Errors.  Every rank runs the same deck on the same data, so a deck error or a numerical
 * failure is met by every rank at the same place (block results are shared before they are
 * checked).  Rank 0 prints it, runs the cleanup (summary, closed dumps) and calls MPI_Abort with
 * the exit code, which ends every rank and makes mpirun exit with that code.  An error met by
 * one rank only (a file rank 0 cannot write) takes the same path.  A rank other than 0 that fails
 * alone waits 2 s (rank 0, if it fails too, ends the job first and prints the message once),
 * then prints its message and aborts.  Nothing waits on a rank that has failed, so no hang.
 */
#include <fcntl.h>
#include <math.h>
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

/* Blocks of a fixed-order sum over items held in ranges per rank (triangles, nodes): rank r sums
 * blocks b0[r]..b1[r]-1 whole (inside its range) and gives one value per item (`per` doubles) of
 * the blocks it shares with another rank, its head and tail pieces.  A split block is summed by
 * the rank holding its first item (its tail block): the ranks after it send it their heads
 * (split_to_starters), and it adds its own items' values, then theirs, in item order: the
 * additions of the one-rank loop.  Then each rank gives every rank the sums of the blocks whose
 * first item it holds, b0[r]..s1[r]-1 (one range per rank, in rank order). */
typedef struct {
  int n, nblk, block, per;
  int *b0, *b1, *s1;        /* size + 1; b1 < s1: the rank's last block is split (its tail block) */
  int npiece;               /* this rank's items of split blocks: its head, then its tail       */
  double *piece;            /* per * npiece, in item order                                      */
  int *scnt, *sdsp, *rcnt, *rdsp; /* doubles of heads sent to / received from each rank        */
  int nhead, ntail;         /* this rank's head and tail items                                  */
  double *tail;             /* per * items of this rank's tail block, in item order             */
} Split;

static struct {
  int rank, size;
  int nt, nblk, block;
  int *tlo;                 /* size + 1: rank r owns triangles tlo[r]..tlo[r+1]-1 (its parts)  */
  Split st;                 /* the element stage's blocks over the triangle ranges (3 per piece:
                               kdd, bad, J)                                                     */
  Split sn;                 /* a node sum's blocks over the node ranges (par_node_split)        */
  Split se;                 /* a triangle sum's blocks over the triangle ranges (par_tri_split) */
  double *erec;             /* the element stage's block records: power, bad, badJ per block    */
  int *cnt, *dsp;           /* scratch counts and displacements of an allgatherv              */
  double bytes;             /* bytes this rank sent in collectives of the current run's steps  */
  double bytes_end;         /* and in its end gather (par_run_end)                              */
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
  int launched;             /* started by mpirun (its pipes are the ranks' stdout and stderr)   */
  int *nlo;                 /* size + 1                                                        */
  int *scnt, *sdsp, *rcnt, *rdsp; /* slot halo: doubles to / from each rank                     */
  int *sslot, *rslot;       /* corner slot of each halo value sent / received, grouped by rank */
  double *sbuf, *rbuf;
  int *xs, *xr, *xsd, *xrd; /* par_concat / par_exchange: counts and displacements (bytes)     */
  char *xbuf;               /* their receive buffer                                            */
  size_t xcap;
  /* Divided update (par.h): this run's nodes, per node what is kept current here */
  int div;                  /* 1: each rank updates its own nodes and the shared ones           */
  int run_id;               /* par_run_begin calls so far (contact.c rebuilds its ghosts on change) */
  unsigned char *nmark;     /* per node: YF_BC_* of the kinds, | GHOST when this rank receives it */
  int nshared, *shared;     /* YF_BC_SHARED nodes, increasing; owners' slices bcnt/bdsp (doubles) */
  int nextra, *extra;       /* the shared nodes other ranks own (this rank updates them too)   */
  int *bcnt, *bdsp;
  double *bbuf;
  int nsneed, *sneed, csneed; /* ghosts of the triangles, joint blocks and loads (fixed per run)  */
  int ncneed, *cneed, ccneed; /* ghosts of the contact couples (par_contact_ghosts)            */
  int ngh, *gh, cgh;        /* all ghosts, increasing: what this rank receives                 */
  int *gcnt, *gdsp;         /* ghosts per owner (doubles: 4 per node), received               */
  int *ocnt, *odsp, *oidx, coidx; /* nodes this rank sends to each rank, and their indices     */
  double *gsend, *grecv;
  int cgsend, cgrecv;
  int nodes_fresh;          /* every node's state current on this rank (since the last update) */
  int poison;               /* tests (YFDEM_MPI_POISON): NaN into what is neither owned nor read */
  const char *why;          /* why this run's update is replicated ("" when divided)           */
  int ngh_max;              /* most ghost nodes this rank received in a step (this run)        */
  long cross_hits;          /* contact hits of couples whose triangles two ranks own (this rank) */
  long disc_sent, disc_own, nsearch; /* contact searches on ranks: discs this rank sent (to every
                             * other rank, counted once per rank), its own discs, searches */
  double hbytes;            /* of bytes: what went to one rank only (slot halo, contact hits)  */
  /* Re-balancing (par_balance): each triangle's fixed cost, per block of bal_g triangles too */
  unsigned char *tw;        /* per triangle: W_TRI + W_NODE per node it numbers + W_JOINT per
                               joint it is the lower triangle of (units of about 1 ns a step)  */
  long *bw;                 /* per block: the sum of tw                                         */
  int *bc;                  /* per block: contact couples whose lower triangle is in it         */
  unsigned char *bok;       /* per border before block b (0..bal_nb): a cut there keeps halo mode */
  int tw_nt, tw_nn, tw_nj, bal_g, bal_nb;
  int bal;                  /* 1: re-balance (YFDEM_MPI_BALANCE, default 1)                    */
  long bal_search;          /* contact searches when the ranks' weights were last looked at     */
  int nrecut;               /* re-cuts in this run                                              */
  int bal_stuck;            /* this run wanted a re-cut that no border keeping halo mode allowed */
  double bal_from, bal_to;  /* the first re-cut's weight imbalance before, the last's after     */
  double t_recut;           /* wall seconds of this run's re-cuts                              */
  int lay_id;               /* changes with the triangle ranges (par_prepare, a re-cut)         */
  void *sc[4];              /* the layout's scratch: owner, seen, trank, jrank (scratch_release) */
  size_t sc_cap[4];
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
  fflush(NULL); /* what ./yfdem's exit() would keep: a record's last rows, say (MPI_Abort drops buffers) */
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
  /* Parallel h5 frames through OpenMPI's ROMIO, not its default ompio: on a full disk ompio's
   * collective write printed its own error and returned success, so an incomplete frame was
   * renamed into the series; ROMIO returns MPI_ERR_IO to every rank (a sweep of new decks,
   * 2026-11-28).  A user's own OMPI_MCA_io wins. */
  setenv("OMPI_MCA_io", "romio321", 0);
  P.launched = getenv("OMPI_COMM_WORLD_SIZE") != NULL || getenv("PMIX_RANK") != NULL;
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

static volatile sig_atomic_t got_cont;
static void on_cont(int sig) { (void)sig; got_cont = 1; }

FILE *par_stdin(FILE *in, const volatile int *stop) {
  /* mpirun gives stdin to rank 0 only: it reads the deck and sends it to every rank */
  long n = 0;
  char *buf = NULL;
  if (P.rank == 0) {
    /* Ctrl-C to mpirun closes rank 0's stdin, which read as the deck's end: the part read so far
     * ran and ended "ok" (a sweep of new decks).  mpirun sends its ranks SIGCONT at once on a
     * Ctrl-C (SIGTERM only a second later): seen while the deck is read, or just after its end,
     * it is that interrupt. */
    struct sigaction sa, old;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_cont;
    sigemptyset(&sa.sa_mask);
    if (P.launched) sigaction(SIGCONT, &sa, &old);
    size_t cap = 1 << 16, k;
    buf = yf_malloc(cap, "deck from stdin");
    yf_interruptible(1); /* a pipe or a terminal may block here: a signal ends the read (EINTR) */
    while (!*stop && !got_cont && (k = fread(buf + n, 1, cap - (size_t)n, in)) > 0) {
      n += (long)k;
      if ((size_t)n == cap) buf = yf_realloc(buf, cap *= 2, "deck from stdin");
    }
    yf_interruptible(0);
    for (int w = 0; P.launched && w < 50 && !*stop && !got_cont; w++) usleep(2000); /* 0.1 s for the SIGCONT */
    if (P.launched) sigaction(SIGCONT, &old, NULL);
    if (*stop || got_cont) n = -1;
  }
  /* the other ranks wait for the deck without blocking, so that a signal to one of them ends the
   * job while rank 0 still reads a pipe held open (it waited in MPI_Bcast, and the job never
   * ended) */
  MPI_Request req;
  MPI_Ibcast(&n, 1, MPI_LONG, 0, MPI_COMM_WORLD, &req);
  for (int done = 0;;) {
    MPI_Test(&req, &done, MPI_STATUS_IGNORE);
    if (done) break;
    if (*stop) { /* alone (rank 0 still reads): no agreed exit to make, so abort the job */
      fprintf(stderr, "interrupted while waiting for the deck (rank %d): nothing was run\n", P.rank);
      fflush(stderr);
      MPI_Abort(MPI_COMM_WORLD, YF_EXIT_INTERRUPT);
    }
    usleep(2000);
  }
  if (n < 0) yf_exit_with(YF_EXIT_INTERRUPT, "interrupted while reading the deck: nothing was run");
  if (P.rank != 0) buf = yf_malloc((size_t)n + 1, "deck from stdin");
  MPI_Bcast(buf, (int)n, MPI_CHAR, 0, MPI_COMM_WORLD);
  FILE *f = fmemopen(buf, (size_t)n, "r"); /* buf lives as long as the program */
  if (!f) yf_io_error(NULL, "cannot read the deck from standard input");
  return f;
}

void par_interrupted(void) {
  /* only under mpirun, whose pipes these are: a singleton's stdout may be the user's terminal,
   * shared with the shell, which must not be left non-blocking */
  if (!P.launched) return;
  for (int fd = 1; fd <= 2; fd++) {
    int fl = fcntl(fd, F_GETFL);
    if (fl >= 0) fcntl(fd, F_SETFL, fl | O_NONBLOCK);
  }
}

/* Whole-scene scratch of a layout (4 B per node or triangle each: 34 MB a rank at 1e6), held
 * only while the ranges are made (par_prepare, a re-cut's weights and layout): a run reads none. */
static void *scratch(int k, size_t bytes) {
  if (bytes > P.sc_cap[k]) {
    free(P.sc[k]);
    P.sc[k] = yf_malloc(bytes, "rank layout");
    P.sc_cap[k] = bytes;
  }
  return P.sc[k];
}

static void scratch_release(void) {
  for (int k = 0; k < 4; k++) {
    free(P.sc[k]);
    P.sc[k] = NULL;
    P.sc_cap[k] = 0;
  }
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
    jrank = scratch(3, (size_t)nj * sizeof(int));
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
  free(fs); free(fr);
}

/* What a halo design would exchange (docs/SCALING.md): the nodes rank r reads but does not own.
 * A node belongs to the rank of the first triangle that meets it (nodes are numbered in that
 * order); rank r reads the nodes of its triangles and of the joints whose first triangle it owns. */
static void count_ghosts(const YfSim *s) {
  const YfModel *m = &s->model;
  int nn = m->node.n, nt = m->tri.n;
  int *owner = scratch(0, (size_t)(nn > 0 ? nn : 1) * sizeof(int));
  int *seen = scratch(1, (size_t)(nn > 0 ? nn : 1) * sizeof(int));
  int *trank = scratch(2, (size_t)(nt > 0 ? nt : 1) * sizeof(int));
  for (int i = 0; i < nn; i++) owner[i] = seen[i] = -1;
  for (int r = 0; r < P.size; r++)
    for (int e = P.tlo[r]; e < P.tlo[r + 1]; e++) {
      trank[e] = r;
      for (int c = 0; c < 3; c++)
        if (owner[m->tri.v[3 * e + c]] < 0) owner[m->tri.v[3 * e + c]] = r;
    }
  int *ghosts = yf_calloc((size_t)P.size, sizeof(int), "ghost count");
  const YfJoints *J = s->joints;
  const int nj = J ? J->n : 0;
  for (int r = 0, j = 0; r < P.size; r++) { /* seen[q] == r: q already counted for rank r */
    for (int e = P.tlo[r]; e < P.tlo[r + 1]; e++)
      for (int c = 0; c < 3; c++) {
        int q = m->tri.v[3 * e + c];
        if (owner[q] != r && seen[q] != r) seen[q] = r, ghosts[r]++;
      }
    /* rank r's joints: sorted by their lower triangle, so the next ones in joint order */
    for (; j < nj; j++) {
      int ta = J->tri[2 * j], tb = J->tri[2 * j + 1];
      if (trank[ta < tb ? ta : tb] != r) break;
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
  free(ghosts);
}

/* The blocks of n items (nblk of `block`) over the ranges lo[0..size]: which each rank sums
 * whole, and its pieces. */
static void split_build(Split *sp, const int *lo, int n, int nblk, int block, int per) {
  const int S = P.size;
  free(sp->b0); free(sp->b1); free(sp->s1); free(sp->piece);
  free(sp->scnt); free(sp->sdsp); free(sp->rcnt); free(sp->rdsp); free(sp->tail);
  size_t n1 = (size_t)S + 1;
  sp->b0 = yf_malloc(n1 * sizeof(int), "rank ranges");
  sp->b1 = yf_malloc(n1 * sizeof(int), "rank ranges");
  sp->s1 = yf_malloc(n1 * sizeof(int), "rank ranges");
  sp->scnt = yf_calloc(n1, sizeof(int), "rank ranges");
  sp->sdsp = yf_calloc(n1, sizeof(int), "rank ranges");
  sp->rcnt = yf_calloc(n1, sizeof(int), "rank ranges");
  sp->rdsp = yf_calloc(n1, sizeof(int), "rank ranges");
  sp->n = n;
  sp->nblk = nblk;
  sp->block = block;
  sp->per = per;
  sp->npiece = 0;
  for (int r = 0; r < S; r++) {
    int e0 = lo[r], e1 = lo[r + 1];
    int b0 = (e0 + block - 1) / block, b1 = e1 == n ? nblk : e1 / block;
    if (b1 < b0) b1 = b0;
    sp->b0[r] = b0;
    sp->b1[r] = b1;
    int s1 = e1 == n ? nblk : (e1 + block - 1) / block;
    sp->s1[r] = s1 > b1 ? s1 : b1;
    int full = b1 > b0 ? (b1 * block < n ? b1 * block : n) - b0 * block : 0;
    if (r == P.rank) sp->npiece = e1 - e0 - full;
  }
  sp->piece = yf_malloc((size_t)per * (size_t)(sp->npiece > 0 ? sp->npiece : 1) * sizeof(double), "split blocks");
  /* heads: rank r's items before its first whole block go to the rank holding that block's first
   * item (a lower rank); this rank's tail block gathers its own tail, then the heads of the ranks
   * after it in rank order, i.e. item order */
  const int me = P.rank;
  sp->nhead = sp->ntail = 0;
  int nrecv = 0;
  for (int r = 0; r < S; r++) {
    int e0 = lo[r], e1 = lo[r + 1], h1 = sp->b0[r] * block < e1 ? sp->b0[r] * block : e1, nh = h1 - e0;
    if (nh <= 0) continue;
    int first = e0 / block * block, q = 0; /* the starter: lo[q] <= first < lo[q + 1] */
    while (q + 1 < S && lo[q + 1] <= first) q++;
    if (r == me) {
      sp->nhead = nh;
      sp->scnt[q] = per * nh;
    }
    if (q == me) {
      sp->rcnt[r] = per * nh;
      nrecv += nh;
    }
  }
  if (sp->s1[me] > sp->b1[me]) {
    int t0 = sp->b1[me] * block > lo[me] ? sp->b1[me] * block : lo[me];
    sp->ntail = lo[me + 1] - t0;
  }
  for (int r = 0, d = per * sp->ntail; r < S; r++) {
    sp->rdsp[r] = d;
    d += sp->rcnt[r];
  }
  sp->tail = yf_malloc((size_t)per * (size_t)(sp->ntail + nrecv + 1) * sizeof(double), "split blocks");
}

/* This rank's tail block's items in item order into sp->tail (its own tail, then the heads the
 * ranks after it send), its head to the rank that sums its block; returns the items of sp->tail
 * (0: this rank has no tail block).  A collective. */
static int split_to_starters(Split *sp) {
  const int me = P.rank, per = sp->per;
  const double *mine = sp->piece;
  memcpy(sp->tail, mine + (size_t)per * sp->nhead, (size_t)per * sp->ntail * sizeof(double));
  P.bytes += (double)per * sp->nhead * sizeof(double);
  MPI_Alltoallv(mine, sp->scnt, sp->sdsp, MPI_DOUBLE, sp->tail, sp->rcnt, sp->rdsp, MPI_DOUBLE, MPI_COMM_WORLD);
  if (sp->s1[me] <= sp->b1[me]) return 0;
  int b = sp->b1[me], i1 = (b + 1) * sp->block < sp->n ? (b + 1) * sp->block : sp->n;
  return i1 - b * sp->block;
}

/* Every rank's records of the blocks whose first item it holds (b0[r]..s1[r]-1, `per` doubles
 * each, in rec), to every rank. */
static void allgatherv(void *a, MPI_Datatype type, int size);
static void split_share_sums(const Split *sp, double *rec, int per) {
  for (int r = 0; r < P.size; r++) {
    P.cnt[r] = per * (sp->s1[r] - sp->b0[r]);
    P.dsp[r] = per * sp->b0[r];
  }
  allgatherv(rec, MPI_DOUBLE, sizeof(double));
}

/* What follows from the triangle ranges P.tlo: the element stage's split blocks, the node ranges
 * and the slot halo (count_ghosts); the node sums' blocks again at their first use. */
static void layout(YfSim *s) {
  split_build(&P.st, P.tlo, s->model.tri.n, P.nblk, P.block, 3);
  P.sn.n = -1;
  P.se.n = -1;
  count_ghosts(s);
  scratch_release();
}

static void tri_weights(const YfSim *s);
void par_prepare(YfSim *s, int nblk, int block) {
  const YfModel *m = &s->model;
  int nt = m->tri.n, S = P.size;
  /* the same scene: the same triangles and nodes (a node added after a run, with no triangle,
   * changes the node ranges, and with them whose force each rank sums) */
  if (P.tlo && P.nt == nt && P.nn == m->node.n && P.nblk == nblk && P.block == block) return;
  P.lay_id++; /* contact.c moves its couples to their new owners at its next step */
  free(P.tlo); free(P.cnt); free(P.dsp);
  size_t n1 = (size_t)S + 1;
  P.tlo = yf_malloc(n1 * sizeof(int), "rank ranges");
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
   * block split between ranks are evaluated one by one by their owners, and the rank holding its
   * first triangle sums the block's per-triangle results in triangle order: the same additions as
   * the one-rank loop. */
  free(P.erec);
  P.erec = yf_malloc(3 * ((size_t)nblk + 1) * sizeof(double), "block records");
  layout(s);
  /* the re-cut's weights now, while the run's buffers (the contact couples) are not yet made:
   * their whole-scene scratch (4 B per node) at the first weighing set a rank's peak at 1e6 */
  if (S > 1 && nt >= 4 * 256 * S) tri_weights(s);
}

void par_blocks(int *b0, int *b1) {
  *b0 = P.st.b0[P.rank];
  *b1 = P.st.b1[P.rank];
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

void par_share_elements(YfModel *m, const YfTriMat *tm, double *blk, int *blk_bad, double *blk_badJ, double t_elem) {
  double c0 = yf_cpu_now();
  int r = P.rank, B = P.block, nt = P.nt;
  const Split *sp = &P.st;
  P.stress_fresh = P.state_fresh = 0;
  /* this rank's head and tail pieces (triangles of blocks it shares with others) */
  double *out = sp->piece;
  int e0 = P.tlo[r], e1 = P.tlo[r + 1];
  if (sp->b1[r] > sp->b0[r]) {
    for (int e = e0; e < sp->b0[r] * B; e++, out += 3) piece_one(m, tm, e, out);
    for (int e = sp->b1[r] * B < nt ? sp->b1[r] * B : nt; e < e1; e++, out += 3) piece_one(m, tm, e, out);
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
  /* the records of the blocks whose first triangle this rank holds: its whole blocks, then its
   * tail block summed from its triangles' and the next ranks' results in triangle order (a
   * triangle index is exact in a double) */
  double *rec = P.erec;
  for (int b = sp->b0[r]; b < sp->b1[r]; b++) {
    rec[3 * b] = blk[b];
    rec[3 * b + 1] = blk_bad[b];
    rec[3 * b + 2] = blk_badJ[b];
  }
  const int ni = split_to_starters(&P.st);
  if (ni) {
    const int b = sp->b1[r];
    const double *pc = sp->tail;
    double power = 0.0, bad = -1, badJ = 0.0;
    for (int k = 0; k < ni; k++, pc += 3) {
      if (bad < 0 && pc[1] != 0.0) {
        bad = b * B + k;
        badJ = pc[2];
      }
      power += pc[0];
    }
    rec[3 * b] = power;
    rec[3 * b + 1] = bad;
    rec[3 * b + 2] = badJ;
  }
  split_share_sums(sp, rec, 3);
  for (int b = 0; b < P.nblk; b++) {
    blk[b] = rec[3 * b];
    blk_bad[b] = (int)rec[3 * b + 1];
    blk_badJ[b] = rec[3 * b + 2];
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
  if (P.div) { /* the shared nodes' forces only, from their owners */
    const int k0 = P.bdsp[P.rank] / 2;
    for (int k = k0; k < k0 + P.bcnt[P.rank] / 2; k++) {
      P.bbuf[2 * k] = fx[P.shared[k]];
      P.bbuf[2 * k + 1] = fy[P.shared[k]];
    }
    memcpy(P.cnt, P.bcnt, (size_t)P.size * sizeof(int));
    memcpy(P.dsp, P.bdsp, (size_t)P.size * sizeof(int));
    allgatherv(P.bbuf, MPI_DOUBLE, sizeof(double));
    for (int k = 0; k < P.nshared; k++) {
      fx[P.shared[k]] = P.bbuf[2 * k];
      fy[P.shared[k]] = P.bbuf[2 * k + 1];
    }
    P.t_comm += yf_now() - t0;
    return;
  }
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

/* Divided update: every node's state from its owner. */
#define NODE_STATE(n) {(n)->x, (n)->y, (n)->vx, (n)->vy, (n)->fx, (n)->fy} /* what owners keep current */
static void gather_nodes(YfNodes *n) {
  if (!P.div || P.nodes_fresh) return;
  double *a[6] = NODE_STATE(n);
  for (int k = 0; k < 6; k++) par_gather_ranges(a[k], P.nlo, (int)sizeof(double));
  P.nodes_fresh = 1;
}

/* The end of a run: the state whole on every rank for what follows (deck expressions, the next
 * run's start), its bytes kept apart from the run's per-step traffic in the report. */
void par_run_end(YfSim *s) {
  const double b0 = P.bytes;
  par_need_all(s);
  P.bytes_end = P.bytes - b0;
  P.bytes = b0;
}

void par_need_all(YfSim *s) {
  if (P.size <= 1) return;
  par_need_stresses(&s->model);
  gather_nodes(&s->model.node);
  if (P.state_fresh) return;
  contact_par_gather(s); /* friction memory, node contact forces */
  joints_par_gather(s);  /* joints' forces, work, damage */
  P.state_fresh = 1;
}

/* ---------------------------------------------------------------- the divided update */

static int owner_of(int i) { /* nlo[a] <= i < nlo[a + 1] */
  int a = 0, z = P.size;
  while (z - a > 1) {
    int c = (a + z) / 2;
    if (P.nlo[c] <= i) a = c;
    else z = c;
  }
  return a;
}

enum { GHOST = 8, LISTED = 16 }; /* nmark bits above the kinds' YF_BC_*: this rank receives the node;
                                  * in the list being made (divide) */

/* Room for n items of `size` bytes in *p (capacity *cap, grown by half again, never shrunk): the
 * ghost lists change at each contact search; they allocate only when they outgrow their room. */
static void room(void **p, int *cap, int n, size_t size) {
  if (n <= *cap) return;
  *cap = n + n / 2 + 256;
  free(*p);
  *p = yf_malloc((size_t)*cap * size, "ghost lists");
}

/* The ghosts from the fixed and the contact lists: what this rank asks of each owner, and (an
 * exchange of node indices) what it sends to each rank. */
static void build_requests(void) {
  const int S = P.size, me = P.rank, n0 = P.nlo[me], n1 = P.nlo[me + 1];
  for (int k = 0; k < P.ngh; k++) P.nmark[P.gh[k]] &= (unsigned char)~GHOST;
  int cap = P.nsneed + P.ncneed;
  room((void **)&P.gh, &P.cgh, cap, sizeof(int));
  P.ngh = 0;
  const int *lists[2] = {P.sneed, P.cneed}, nl[2] = {P.nsneed, P.ncneed};
  for (int l = 0; l < 2; l++)
    for (int k = 0; k < nl[l]; k++) {
      int i = lists[l][k];
      if (i >= n0 && i < n1) continue;
      if (P.nmark[i] & (GHOST | YF_BC_SHARED)) continue;
      P.nmark[i] |= GHOST;
      P.gh[P.ngh++] = i;
    }
  /* increasing, so grouped by owner in rank order (node ranges are contiguous) */
  int nn = P.nn, w = 0;
  for (int i = 0; i < nn && w < P.ngh; i++)
    if (P.nmark[i] & GHOST) P.gh[w++] = i;
  for (int r = 0; r <= S; r++) P.gcnt[r] = 0;
  for (int k = 0; k < P.ngh; k++) P.gcnt[owner_of(P.gh[k])]++;
  MPI_Alltoall(P.gcnt, 1, MPI_INT, P.ocnt, 1, MPI_INT, MPI_COMM_WORLD);
  P.gdsp[0] = P.odsp[0] = 0;
  for (int r = 0; r < S; r++) {
    P.gdsp[r + 1] = P.gdsp[r] + P.gcnt[r];
    P.odsp[r + 1] = P.odsp[r] + P.ocnt[r];
  }
  room((void **)&P.oidx, &P.coidx, P.odsp[S] + 1, sizeof(int));
  MPI_Alltoallv(P.gh, P.gcnt, P.gdsp, MPI_INT, P.oidx, P.ocnt, P.odsp, MPI_INT, MPI_COMM_WORLD);
  P.bytes += (double)P.ngh * sizeof(int);
  /* from here on in doubles: 4 per node (x, y, vx, vy) */
  for (int r = 0; r <= S; r++) {
    P.gcnt[r] *= 4; P.gdsp[r] *= 4; P.ocnt[r] *= 4; P.odsp[r] *= 4;
  }
  if (P.ngh > P.ngh_max) P.ngh_max = P.ngh;
  room((void **)&P.gsend, &P.cgsend, P.odsp[S] + 1, sizeof(double));
  room((void **)&P.grecv, &P.cgrecv, P.gdsp[S] + 1, sizeof(double));
}

void par_ghost_exchange(YfNodes *n) {
  if (!P.div) return;
  double t0 = yf_now();
  const int no = P.odsp[P.size] / 4;
  for (int k = 0; k < no; k++) {
    int i = P.oidx[k];
    double *o = P.gsend + 4 * (size_t)k;
    o[0] = n->x[i]; o[1] = n->y[i]; o[2] = n->vx[i]; o[3] = n->vy[i];
  }
  P.bytes += (double)P.odsp[P.size] * sizeof(double);
  P.hbytes += (double)P.odsp[P.size] * sizeof(double);
  MPI_Alltoallv(P.gsend, P.ocnt, P.odsp, MPI_DOUBLE, P.grecv, P.gcnt, P.gdsp, MPI_DOUBLE, MPI_COMM_WORLD);
  for (int k = 0; k < P.ngh; k++) {
    int i = P.gh[k];
    const double *a = P.grecv + 4 * (size_t)k;
    n->x[i] = a[0]; n->y[i] = a[1]; n->vx[i] = a[2]; n->vy[i] = a[3];
  }
  P.nodes_fresh = 0;
  P.state_fresh = 0;
  if (P.poison) { /* tests: what this rank neither owns, shares nor reads must never be read */
    const double nan = NAN;
    const int n0 = P.nlo[P.rank], n1 = P.nlo[P.rank + 1];
    for (int i = 0; i < P.nn; i++) {
      if ((i >= n0 && i < n1) || (P.nmark[i] & YF_BC_SHARED)) continue;
      n->fx[i] = n->fy[i] = nan;
      if (!(P.nmark[i] & GHOST)) n->x[i] = n->y[i] = n->vx[i] = n->vy[i] = nan;
    }
  }
  P.t_comm += yf_now() - t0;
}

void par_contact_ghosts(YfNodes *n, const int *nodes, int nnodes) {
  if (!P.div) return;
  double t0 = yf_now();
  /* the other ranks' nodes only (most of the couples' corners are this rank's own) */
  const int n0 = P.nlo[P.rank], n1 = P.nlo[P.rank + 1];
  int nf = 0;
  for (int k = 0; k < nnodes; k++) nf += nodes[k] < n0 || nodes[k] >= n1;
  room((void **)&P.cneed, &P.ccneed, nf + 1, sizeof(int));
  P.ncneed = 0;
  for (int k = 0; k < nnodes; k++)
    if (nodes[k] < n0 || nodes[k] >= n1) P.cneed[P.ncneed++] = nodes[k];
  build_requests();
  P.t_comm += yf_now() - t0;
  int fresh = P.nodes_fresh;
  par_ghost_exchange(n); /* the new ghosts' state now: this step's couples read them */
  P.nodes_fresh = fresh;
}

static void divide(YfSim *s);
void par_run_begin(YfSim *s) {
  P.run_id++;
  P.div = 0;
  P.why = "";
  if (P.size <= 1) return;
  const YfModel *m = &s->model;
  const int nn = m->node.n;
  if (!P.halo || nn != P.nn) { /* node ranges of another scene, or not one range per rank */
    P.why = "the node order does not follow the triangles' ranks: a mesh left unpartitioned (below 8192 triangles, "
            "or 'partition none') (every corner force goes to every rank)";
    return;
  }
  free(P.nmark);
  P.nmark = yf_calloc((size_t)(nn > 0 ? nn : 1), 1, "node marks");
  P.ngh = 0; /* no ghost marked yet */
  int integ = 0;
  for (int k = 0; k < s->nbc_kind; k++) {
    if (s->bc_kind[k]->mark_nodes) s->bc_kind[k]->mark_nodes(s, P.nmark);
    integ |= s->bc_kind[k]->integrate != NULL;
  }
  int nsh = 0;
  for (int i = 0; i < nn; i++) nsh += (P.nmark[i] & YF_BC_SHARED) != 0;
  /* the update is divided unless mass damping sums over every node every step, or a kind that
   * replaces the update would have to update shared nodes it does not own */
  P.div = !(s->mass_damping > 0) && !(integ && nsh);
  P.why = s->mass_damping > 0 ? "mass damping sums over every node" : integ && nsh ? "a Y2D deck with native fixes or loads" : "";
  /* tests and benchmarks: YFDEM_MPI_DIVIDE=0 keeps the replicated update; YFDEM_MPI_POISON=1
   * writes NaN into what a rank neither owns nor reads (par_ghost_exchange) */
  const char *e = getenv("YFDEM_MPI_DIVIDE"), *po = getenv("YFDEM_MPI_POISON");
  if (e && *e && strcmp(e, "0") && strcmp(e, "1"))
    yf_exit_with(YF_EXIT_DECK, "error: YFDEM_MPI_DIVIDE='%s': expected 1 (divide the update where it can be, the "
                 "default) or 0 (every rank updates every node)", e);
  if (po && *po && strcmp(po, "0") && strcmp(po, "1"))
    yf_exit_with(YF_EXIT_DECK, "error: YFDEM_MPI_POISON='%s': expected 1 (tests: NaN into the nodes a rank neither "
                 "owns nor reads) or 0 (off, the default)", po);
  if (e && *e == '0' && P.div) {
    P.div = 0;
    P.why = "YFDEM_MPI_DIVIDE=0";
  }
  P.poison = po && *po == '1';
  const char *b = getenv("YFDEM_MPI_BALANCE");
  if (b && *b && strcmp(b, "0") && strcmp(b, "1"))
    yf_exit_with(YF_EXIT_DECK, "error: YFDEM_MPI_BALANCE='%s': expected 1 (move the ranks' borders when the contact "
                 "work is uneven, the default) or 0 (keep the first cut)", b);
  P.bal = !(b && *b == '0');
  P.bal_search = -1;
  P.nrecut = 0;
  P.bal_stuck = 0;
  P.t_recut = 0.0;
  if (!P.div) return;
  divide(s);
  /* the state is whole now (the run starts from a replicated state) */
  P.nodes_fresh = 1;
}

/* The divided update's lists for the current ranges (a run's start, a re-cut): the shared nodes
 * and each owner's slice of them, the fixed ghosts and what this rank asks of each owner.  The
 * contact ghosts are set again at the next contact stage (par_run_id changes). */
static void divide(YfSim *s) {
  const YfModel *m = &s->model;
  const int nn = m->node.n, S = P.size, me = P.rank;
  int nsh = 0;
  for (int i = 0; i < nn; i++) nsh += (P.nmark[i] & YF_BC_SHARED) != 0;
  /* the shared nodes and each owner's slice of them */
  free(P.shared); free(P.bcnt); free(P.bdsp); free(P.bbuf);
  P.shared = yf_malloc((size_t)(nsh > 0 ? nsh : 1) * sizeof(int), "shared nodes");
  P.bcnt = yf_calloc((size_t)S + 1, sizeof(int), "shared nodes");
  P.bdsp = yf_calloc((size_t)S + 1, sizeof(int), "shared nodes");
  P.bbuf = yf_malloc(2 * (size_t)(nsh > 0 ? nsh : 1) * sizeof(double), "shared nodes");
  P.nshared = 0;
  for (int i = 0; i < nn; i++)
    if (P.nmark[i] & YF_BC_SHARED) {
      P.shared[P.nshared++] = i;
      P.bcnt[owner_of(i)] += 2;
    }
  for (int r = 0; r < S; r++) P.bdsp[r + 1] = P.bdsp[r] + P.bcnt[r];
  free(P.extra);
  P.extra = yf_malloc((size_t)(nsh > 0 ? nsh : 1) * sizeof(int), "shared nodes");
  P.nextra = 0;
  for (int q = 0; q < P.nshared; q++)
    if (P.shared[q] < P.nlo[me] || P.shared[q] >= P.nlo[me + 1]) P.extra[P.nextra++] = P.shared[q];
  /* the fixed ghosts: corners of this rank's triangles, nodes of its joint blocks (a block goes
   * with the owner of its first joint's lower triangle), nodes the kinds read; listed are only
   * the nodes this rank receives (not its own, not shared), each once: a corner is met by
   * up to 6 triangles and a joint's node by 2 joints, and the list of every corner and joint node
   * of a rank was 3 ints a triangle and 4 a joint (with the ghost array sized from it, 56 MB a
   * rank at 1e6 on 2 ranks) where its ghosts are a few thousand; LISTED marks what is in it
   * (cleared below) */
  const int own0 = P.nlo[me], own1 = P.nlo[me + 1];
  int ns = 0;
  room((void **)&P.sneed, &P.csneed, 1024, sizeof(int));
  int *sn = P.sneed, cap = P.csneed;
#define PUSH(i) do { const int i_ = (i); \
                     if ((i_ >= own0 && i_ < own1) || (P.nmark[i_] & (LISTED | YF_BC_SHARED))) break; \
                     P.nmark[i_] |= LISTED; \
                     if (ns == cap) sn = yf_realloc(sn, (size_t)(cap *= 2) * sizeof(int), "ghost nodes"); \
                     sn[ns++] = i_; } while (0)
  for (int e2 = 3 * P.tlo[me]; e2 < 3 * P.tlo[me + 1]; e2++) PUSH(m->tri.v[e2]);
  const YfJoints *J = s->joints;
  if (J && J->n) {
    const int nb = (J->n + YF_JBLOCK - 1) / YF_JBLOCK;
    for (int b = 0; b < nb; b++) {
      int a = J->tri[2 * b * YF_JBLOCK], c = J->tri[2 * b * YF_JBLOCK + 1], t = a < c ? a : c;
      if (t < P.tlo[me] || t >= P.tlo[me + 1]) continue;
      for (int j = b * YF_JBLOCK; j < J->n && j < (b + 1) * YF_JBLOCK; j++)
        for (int c4 = 0; c4 < 4; c4++) PUSH(J->node[4 * j + c4]);
    }
  }
  for (int i = 0; i < nn; i++)
    if (P.nmark[i] & YF_BC_READS) PUSH(i);
#undef PUSH
  for (int k = 0; k < ns; k++) P.nmark[sn[k]] &= (unsigned char)~LISTED;
  P.sneed = sn; /* (kept between calls, as the other ghost lists) */
  P.csneed = cap;
  P.nsneed = ns;
  P.ncneed = 0;
  if (!P.gcnt) {
    size_t n1 = (size_t)S + 1;
    P.gcnt = yf_calloc(n1, sizeof(int), "ghost nodes");
    P.gdsp = yf_calloc(n1, sizeof(int), "ghost nodes");
    P.ocnt = yf_calloc(n1, sizeof(int), "ghost nodes");
    P.odsp = yf_calloc(n1, sizeof(int), "ghost nodes");
  }
  build_requests(); /* (clears the marks of the ghosts it had) */
}

int par_divided(void) { return P.div; }
int par_layout_id(void) { return P.lay_id; }
int par_run_id(void) { return P.run_id; }

void par_update_nodes(int *n0, int *n1, const int **extra, int *nextra) {
  if (!P.div) return;
  *n0 = P.nlo[P.rank];
  *n1 = P.nlo[P.rank + 1];
  if (extra) { /* the shared nodes of other owners: every rank updates them (their forces came first) */
    *extra = P.extra;
    *nextra = P.nextra;
  }
}

double *par_node_split(int nblk, int block, int *kb0, int *kb1) {
  if (!P.div) return NULL;
  if (P.sn.n != P.nn || P.sn.nblk != nblk || P.sn.block != block) split_build(&P.sn, P.nlo, P.nn, nblk, block, 1);
  *kb0 = P.sn.b0[P.rank];
  *kb1 = P.sn.b1[P.rank];
  return P.sn.piece;
}

/* Every block's sum on every rank: this rank's tail block summed from its items' values and the
 * next ranks' heads in item order, then the blocks whose first item each rank holds. */
static void split_sums(Split *sp, double *blk) {
  double t0 = yf_now();
  const int ni = split_to_starters(sp);
  if (ni) {
    double sum = 0.0;
    for (int k = 0; k < ni; k++) sum += sp->tail[k];
    blk[sp->b1[P.rank]] = sum;
  }
  split_share_sums(sp, blk, 1);
  P.t_comm += yf_now() - t0;
}

void par_node_block_sums(double *blk) {
  if (P.div) split_sums(&P.sn, blk);
}

double *par_tri_split(int nblk, int block, int *kb0, int *kb1) {
  if (!P.div) return NULL;
  if (P.se.n != P.nt || P.se.nblk != nblk || P.se.block != block) split_build(&P.se, P.tlo, P.nt, nblk, block, 1);
  *kb0 = P.se.b0[P.rank];
  *kb1 = P.se.b1[P.rank];
  return P.se.piece;
}

void par_tri_block_sums(double *blk) {
  if (P.div) split_sums(&P.se, blk);
}

double par_max(double v) {
  if (P.size <= 1) return v;
  double t0 = yf_now(), all = v;
  MPI_Allreduce(&v, &all, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
  P.t_comm += yf_now() - t0;
  return all;
}

int par_rank(void) { return P.rank; }

void par_note_work(double secs) { P.t_elem += secs; }

void par_note_discs(long sent, long own) {
  P.disc_sent += sent;
  P.disc_own += own;
  P.nsearch++;
}

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

const void *par_concat_writer(const void *mine, int nbytes, int *rbytes) {
  double t0 = yf_now();
  xroom(0);
  MPI_Gather(&nbytes, 1, MPI_INT, P.xr, 1, MPI_INT, 0, MPI_COMM_WORLD);
  size_t tot = 0;
  if (P.rank == 0)
    for (int r = 0; r < P.size; r++) {
      P.xrd[r] = (int)tot;
      tot += (size_t)P.xr[r];
    }
  xroom(tot);
  if (P.rank) P.bytes += (double)nbytes;
  MPI_Gatherv(mine, nbytes, MPI_BYTE, P.xbuf, P.xr, P.xrd, MPI_BYTE, 0, MPI_COMM_WORLD);
  P.t_comm += yf_now() - t0;
  if (P.rank) return NULL;
  memcpy(rbytes, P.xr, (size_t)P.size * sizeof(int));
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

/* An array held by ranges lo_old (rank r: items lo_old[r]..lo_old[r+1]-1 current) made current
 * on the ranges lo_new: each item whose owner changes goes from its old owner to its new one, and
 * nothing else moves (a collective). */
void par_move_ranges(void *a, const int *lo_old, const int *lo_new, int elem_bytes) {
  const int S = P.size, me = P.rank;
  xroom(0);
  size_t tot = 0;
  for (int r = 0; r < S; r++) {
    int s0 = lo_old[me] > lo_new[r] ? lo_old[me] : lo_new[r], s1 = lo_old[me + 1] < lo_new[r + 1] ? lo_old[me + 1] : lo_new[r + 1];
    int g0 = lo_old[r] > lo_new[me] ? lo_old[r] : lo_new[me], g1 = lo_old[r + 1] < lo_new[me + 1] ? lo_old[r + 1] : lo_new[me + 1];
    P.xs[r] = r != me && s1 > s0 ? (s1 - s0) * elem_bytes : 0;
    P.xsd[r] = P.xs[r] ? s0 * elem_bytes : 0;
    P.xr[r] = r != me && g1 > g0 ? (g1 - g0) * elem_bytes : 0;
    P.xrd[r] = (int)tot;
    tot += (size_t)P.xr[r];
  }
  xroom(tot);
  double t0 = yf_now();
  for (int r = 0; r < S; r++) P.bytes += P.xs[r];
  MPI_Alltoallv(a, P.xs, P.xsd, MPI_BYTE, P.xbuf, P.xr, P.xrd, MPI_BYTE, MPI_COMM_WORLD);
  for (int r = 0; r < S; r++) {
    int g0 = lo_old[r] > lo_new[me] ? lo_old[r] : lo_new[me];
    if (P.xr[r]) memcpy((char *)a + (size_t)g0 * elem_bytes, P.xbuf + P.xrd[r], (size_t)P.xr[r]);
  }
  P.t_comm += yf_now() - t0;
}

/* ---------------------------------------------------------------- re-balancing
 *
 * Triangles keep their rank as fragments fly (Lagrangian ownership), and the first cut balances
 * triangles, not work.  What makes a rank slower is mostly its contact couples (a couple is
 * evaluated by the owner of its lower triangle, and couples per triangle vary across a scene: the
 * beam deck at 1e6 on 2 ranks holds 4.60e6 and 4.37e6).  After each contact search the ranks
 * weigh their work: a fixed cost per triangle, per node it numbers and per joint it is the lower
 * triangle of, and a cost per couple (W_*, measured from ./yfdem's stage table: the beam deck at
 * 1e6, one thread: elements and the screen's records 13 ns a triangle, gather and update 6 ns a
 * node, joints 16 ns a joint, contact 11 ns a couple).  When the heaviest rank is more than
 * BAL_TOL above the mean and a cut by weight would save, over the steps left in the run, twice
 * what the re-cut costs, the borders move: every rank computes the same new ranges from the same integer counts (the cut is at a
 * block of bal_g triangles), the state of the items that change owner goes to their new owners
 * (nodes, stresses, joints, couples with their friction memory and contact forces), and the
 * ranges, halos and ghost lists are made again.  The one-rank order of every sum is the same for
 * any ranges, so a re-cut changes no bit; only where the work is done. */
enum { W_TRI = 13, W_NODE = 6, W_JOINT = 16, W_COUPLE = 11 }; /* ns of a step, one thread */
#define BAL_TOL 0.01
#define RECUT_NS 17.0

/* Each triangle's fixed weight and its blocks' sums, for this scene (again when it changes). */
static void tri_weights(const YfSim *s) {
  const YfModel *m = &s->model;
  const YfJoints *J = s->joints;
  const int nt = m->tri.n, nn = m->node.n, nj = J ? J->n : 0;
  if (P.tw && P.tw_nt == nt && P.tw_nn == nn && P.tw_nj == nj) return;
  free(P.tw); free(P.bw); free(P.bc); free(P.bok);
  P.tw = yf_malloc((size_t)(nt > 0 ? nt : 1), "rank weights");
  unsigned char *seen = scratch(1, (size_t)(nn > 0 ? nn : 1));
  memset(seen, 0, (size_t)nn);
  for (int e = 0; e < nt; e++) {
    int w = W_TRI;
    for (int c = 0; c < 3; c++) {
      int i = m->tri.v[3 * e + c];
      if (!seen[i]) seen[i] = 1, w += W_NODE;
    }
    P.tw[e] = (unsigned char)w;
  }
  for (int j = 0; j < nj; j++) {
    int a = J->tri[2 * j], b = J->tri[2 * j + 1], t = a < b ? a : b;
    P.tw[t] = (unsigned char)(P.tw[t] + W_JOINT <= 255 ? P.tw[t] + W_JOINT : 255);
  }
  /* blocks: at most 1024 per rank, of 256 triangles at least */
  P.bal_g = nt / (1024 * P.size) > 256 ? nt / (1024 * P.size) : 256;
  P.bal_nb = (nt + P.bal_g - 1) / P.bal_g;
  P.bw = yf_calloc((size_t)P.bal_nb + 1, sizeof(long), "rank weights");
  P.bc = yf_calloc((size_t)P.bal_nb + 1, sizeof(int), "rank weights");
  for (int e = 0; e < nt; e++) P.bw[e / P.bal_g] += P.tw[e];
  /* The borders a cut may take.  The divided update needs halo mode (build_halo): each node's
   * owner, the rank of the first triangle that meets it, non-decreasing in node order.  A
   * partitioned mesh numbers its nodes so, and every border keeps it; an unpartitioned one (below
   * 8192 triangles) may keep it at its first cut by chance (bodies one after another) and not at
   * a border inside a body: a cut there left halo mode in the middle of a divided run (the contact
   * stage's assertion, exit 70).  A border at triangle t keeps it when the nodes first met by
   * triangles before t are the first nodes: the p nodes whose first triangle is below t are
   * nodes 0 .. p-1 exactly when the largest first triangle of nodes 0 .. p-1 is below t.  A node
   * no triangle meets goes with the node before it (build_halo), so it takes that node's. */
  {
    const int G = P.bal_g, nb = P.bal_nb;
    int *first = scratch(0, (size_t)(nn > 0 ? nn : 1) * sizeof(int));
    for (int i = 0; i < nn; i++) first[i] = -1;
    for (int e = 0; e < nt; e++)
      for (int c = 0; c < 3; c++)
        if (first[m->tri.v[3 * e + c]] < 0) first[m->tri.v[3 * e + c]] = e;
    int *below = yf_calloc((size_t)nb + 2, sizeof(int), "rank weights"); /* nodes first met before border b */
    for (int i = 0, prev = 0; i < nn; i++) {
      if (first[i] < 0) first[i] = prev;
      prev = first[i];
      below[first[i] / G + 1]++;
    }
    for (int b = 1; b <= nb; b++) below[b] += below[b - 1];
    P.bok = yf_malloc((size_t)nb + 1, "rank weights");
    int most = -1; /* the largest first triangle of nodes 0 .. i-1 */
    for (int b = 0, i = 0; b <= nb; b++) {
      for (; i < below[b]; i++) most = first[i] > most ? first[i] : most;
      P.bok[b] = most < b * G;
    }
    free(below);
  }
  scratch_release();
  P.tw_nt = nt;
  P.tw_nn = nn;
  P.tw_nj = nj;
}

/* A rank's fixed weight: its triangles' tw. */
static long range_weight(int e0, int e1) {
  long w = 0;
  for (int e = e0; e < e1; e++) w += P.tw[e];
  return w;
}

static void recut(YfSim *s, const int *tnew);
void par_balance(YfSim *s) {
  if (P.size <= 1 || !P.div || !P.bal) return;
  const long ns = contact_searches(s);
  if (ns == P.bal_search) return; /* the couples have not changed since the last look */
  P.bal_search = ns;
  const int *clo = contact_rank_lo(s); /* every rank's couples: ranges of the one-rank list */
  const int S = P.size, nt = s->model.tri.n;
  if (!clo || nt < 4 * 256 * S) return;
  double t0 = yf_now();
  tri_weights(s);
  long wmax = 0, wsum = 0;
  for (int r = 0; r < S; r++) {
    long w = range_weight(P.tlo[r], P.tlo[r + 1]) + (long)W_COUPLE * (clo[r + 1] - clo[r]);
    wmax = w > wmax ? w : wmax;
    wsum += w;
  }
  const double mean = (double)wsum / S;
  P.t_recut += yf_now() - t0;
  if ((double)wmax <= mean * (1.0 + BAL_TOL)) return;
  /* every rank's couples per block, summed (integers: every rank gets the same counts) */
  const int G = P.bal_g, nb = P.bal_nb;
  memset(P.bc, 0, (size_t)nb * sizeof(int));
  contact_count_by_block(s, G, P.bc);
  MPI_Allreduce(MPI_IN_PLACE, P.bc, nb, MPI_INT, MPI_SUM, MPI_COMM_WORLD);
  P.bytes += (double)nb * sizeof(int);
  /* the new cut: rank r starts at the block border whose weight before it is nearest r/S of the
   * whole, at least one block after rank r-1's */
  long tot = 0;
  for (int b = 0; b < nb; b++) tot += P.bw[b] + (long)W_COUPLE * P.bc[b];
  int *tnew = yf_malloc(((size_t)S + 1) * sizeof(int), "rank weights");
  long pre = 0, nmax = 0, last = 0;
  tnew[0] = 0;
  for (int r = 1, b = 0; r < S; r++) {
    const double want = (double)tot * r / S;
    const int bmin = tnew[r - 1] / G + 1, bmax = nb - (S - r); /* a block at least for each rank */
    for (; b < bmin; b++) pre += P.bw[b] + (long)W_COUPLE * P.bc[b];
    for (; b < bmax; b++) {
      const long wb = P.bw[b] + (long)W_COUPLE * P.bc[b];
      /* the border before block b is the nearer one that keeps halo mode (P.bok) */
      if (P.bok[b] && (double)pre + 0.5 * (double)wb > want) break;
      pre += wb;
    }
    if (!P.bok[b]) { /* no border left that keeps halo mode: the cut stays */
      P.bal_stuck = 1;
      free(tnew);
      P.t_recut += yf_now() - t0;
      return;
    }
    tnew[r] = b * G;
    nmax = pre - last > nmax ? pre - last : nmax;
    last = pre;
  }
  tnew[S] = nt;
  nmax = tot - last > nmax ? tot - last : nmax;
  /* worth the move when what it saves over the rest of the run (in the weights' units, about a
   * ns of a step) is at least twice what a re-cut costs: RECUT_NS per triangle, node and joint
   * (passes over all of them: the node ranges, the slot halo, the ghost lists; 0.093 s for the
   * beam deck at 1e6, 5.5e6 of them, on 2 ranks) */
  const YfJoints *J = s->joints;
  const double left = (double)(s->run_end_step - s->step);
  const double cost = RECUT_NS * ((double)nt + s->model.node.n + (J ? J->n : 0));
  if ((double)(wmax - nmax) * left < 2.0 * cost) {
    free(tnew);
    P.t_recut += yf_now() - t0;
    return;
  }
  if (!P.nrecut) P.bal_from = (double)wmax / mean;
  P.bal_to = (double)nmax / mean;
  recut(s, tnew);
  free(tnew);
  P.nrecut++;
  P.t_recut += yf_now() - t0;
}

/* The ranges become tnew; the state of what changes owner goes to its new owner. */
static void recut(YfSim *s, const int *tnew) {
  YfModel *m = &s->model;
  const int S = P.size;
  size_t n1 = (size_t)S + 1;
  int *told = yf_malloc(n1 * sizeof(int), "re-cut"), *nold = yf_malloc(n1 * sizeof(int), "re-cut");
  int *jold = yf_malloc(n1 * sizeof(int), "re-cut");
  memcpy(told, P.tlo, n1 * sizeof(int));
  memcpy(nold, P.nlo, n1 * sizeof(int));
  const int joints = joints_par_rows(s, jold);
  memcpy(P.tlo, tnew, n1 * sizeof(int));
  P.lay_id++;
  layout(s); /* the new node ranges, split blocks and slot halo */
  if (!P.nodes_fresh) {
    double *a[6] = NODE_STATE(&m->node);
    for (int k = 0; k < 6; k++) par_move_ranges(a[k], nold, P.nlo, (int)sizeof(double));
  }
  if (!P.stress_fresh) par_move_ranges(m->tri.s, told, P.tlo, 3 * (int)sizeof(double));
  if (joints) joints_par_move(s, jold);
  contact_rehome(s, nold);
  const int nf = P.nodes_fresh, sf = P.state_fresh;
  P.run_id++; /* contact.c sets its ghosts and its list of forced nodes again */
  divide(s);
  if (!nf) par_ghost_exchange(&m->node); /* the new ghosts' state: the next step reads it */
  P.nodes_fresh = nf;
  P.state_fresh = sf;
  free(told); free(nold); free(jold);
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

/* The report's communication share is of the run's wall time, which starts after the run's set-up
 * (the first run's partition, a restart's list cut to ranks, the divided update's ghost lists, the
 * first frames) and after the gathers of the deck's prints between runs: counted, they made the
 * share above 100 % on short runs (a sweep of new decks: 112-154 % on 2-4 ranks). */
void par_run_clock(void) { P.t_comm = 0.0; }

/* After a run: what each rank computed and sent, as measured on every rank. */
void par_run_report(YfSim *s, long nsteps, double wall) {
  long held = 0, whole = 0;
  contact_held(s, &held, &whole);
  /* each rank's communication share of its own run wall time: the ranks' clocks start apart */
  double mine[7] = {P.t_elem, wall > 0 ? P.t_comm / wall : 0.0, P.bytes, P.hbytes, P.ngh_max, (double)held, P.bytes_end}, *all = NULL;
  if (P.rank == 0) all = yf_malloc(7 * (size_t)P.size * sizeof(double), "rank report");
  MPI_Gather(mine, 7, MPI_DOUBLE, all, 7, MPI_DOUBLE, 0, MPI_COMM_WORLD);
  long cross = 0;
  MPI_Reduce(&P.cross_hits, &cross, 1, MPI_LONG, MPI_SUM, 0, MPI_COMM_WORLD);
  P.cross_hits = 0;
  long dmine[2] = {P.disc_sent, P.disc_own}, disc[2] = {0, 0};
  MPI_Reduce(dmine, disc, 2, MPI_LONG, MPI_SUM, 0, MPI_COMM_WORLD);
  const long nsearch = P.nsearch; /* the same on every rank: every rank searches at the same step */
  P.disc_sent = P.disc_own = P.nsearch = 0;
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
    double emax = 0, esum = 0, cmax = 0, bsum = 0, hmax = 0, gmin = 1e300, gmax = 0, cpmin = 1e300, cpmax = 0, bend = 0;
    int tmin = P.nt, tmax = 0;
    for (int r = 0; r < P.size; r++) {
      const double *a = all + 7 * r;
      bend += a[6];
      emax = a[0] > emax ? a[0] : emax;
      esum += a[0];
      cmax = a[1] > cmax ? a[1] : cmax;
      bsum += a[2];
      hmax = a[3] > hmax ? a[3] : hmax;
      gmin = a[4] < gmin ? a[4] : gmin;
      gmax = a[4] > gmax ? a[4] : gmax;
      cpmin = a[5] < cpmin ? a[5] : cpmin;
      cpmax = a[5] > cpmax ? a[5] : cpmax;
      int nt = P.tlo[r + 1] - P.tlo[r];
      tmin = nt < tmin ? nt : tmin;
      tmax = nt > tmax ? nt : tmax;
    }
    double emean = esum / P.size;
    char upd[512], bal[256];
    if (P.nrecut)
      snprintf(bal, sizeof bal, "re-balanced %d time%s (weight imbalance %.3f -> %.3f, %.3f s)", P.nrecut,
               P.nrecut > 1 ? "s" : "", P.bal_from, P.bal_to, P.t_recut);
    else
      snprintf(bal, sizeof bal, "not re-balanced (%s; %.3f s weighing)", P.size <= 1 ? "one rank" : !P.div ? "the update is replicated" :
               !P.bal ? "YFDEM_MPI_BALANCE=0" : P.bal_stuck ? "the node order of an unpartitioned mesh allows no "
               "border nearer an equal share; 'partition metis' numbers it for any cut" : "the ranks' work within 1 % of the mean, or a re-cut would cost more than it saves", P.t_recut);
    if (P.size <= 1)
      snprintf(upd, sizeof upd, "update on one rank");
    else if (P.div)
      snprintf(upd, sizeof upd, "update divided (each rank updates its own nodes and receives its ghosts' positions "
               "and velocities: %.0f..%.0f nodes per rank, from triangles' corners, joints, loaded edges and contact "
               "couples; %d shared nodes of fixes and loads updated on every rank)", gmin, gmax, P.nshared);
    else
      snprintf(upd, sizeof upd, "update replicated (%s: every rank receives every node's force and updates every "
               "node)", P.why && *P.why ? P.why : "not prepared");
    sim_printf(s, "mpi: %d ranks x %d threads; triangles per rank %d..%d; work imbalance %.3f "
               "(CPU of elements, joints and contact: slowest / mean rank; mean %.4g s); %.4g bytes sent per step (border "
               "halo %.4g from the busiest rank; %.4g more at the run's end, to make the state whole); communication %.1f %% of wall (slowest rank); "
               "ghost nodes per rank %d..%d; contact hits between two ranks' triangles %ld; contact couples held "
               "per rank %.0f..%.0f of %ld; contact search discs sent %.0f per search of %.0f (all ranks, %ld searches); "
               "joints broken across rank borders %ld (all runs so far); %s; %s\n",
               P.size, s->threads, tmin, tmax, emean > 0 ? emax / emean : 1.0, emean, bsum / (double)nsteps,
               hmax / (double)nsteps, bend,
               100.0 * cmax, P.ghost_min, P.ghost_max, cross, cpmin, cpmax, whole,
               nsearch ? (double)disc[0] / (double)nsearch : 0.0, nsearch ? (double)disc[1] / (double)nsearch : 0.0,
               nsearch, jcross, upd, bal);
  }
  P.ngh_max = 0;
  free(all);
  P.t_elem = P.t_comm = P.bytes = P.hbytes = P.bytes_end = 0;
}
