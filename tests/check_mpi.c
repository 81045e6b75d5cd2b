/* check_mpi.c: ./yfdem_mpi on 1-4 MPI ranks (oversubscribed on 2 cores) against ./yfdem.
 *
 *   - the determinism matrix: the shortened column deck, the beam deck, the 4 shared Y2D decks
 *     and PERF.md's problem at 1e4 triangles run on 1, 2, 3 and 4 ranks x 1 and 2 threads; the
 *     summary's state_hash, energies (the viscous dissipation sums the element blocks that
 *     straddle ranks), broken joints, contact couples, stress peak and the beam's last frame
 *     of stresses (shared among ranks for metrics and frames) equal ./yfdem's to the last bit;
 *   - frames written with parallel HDF5 (every rank its rows) and gathered to rank 0, on 2 and 3
 *     ranks: every dataset and both indexes as ./yfdem's;
 *   - every output a user reads (record rows, metrics log, fracture logs, CSV frames, thermo and
 *     print lines) of a deck with most of the commands, on 3 ranks, as ./yfdem's byte for byte;
 *   - a restart written on 2 ranks and read on 3 continues bitwise (the uninterrupted run's hash);
 *   - SIGTERM to one rank stops every rank at the same step with one restart, which continues
 *     bitwise, and exit 130 (interrupted);
 *   - a deck error ends every rank with exit 1 and one message; a failure injected on rank 1
 *     only (YFDEM_MPI_FAIL_RANK) ends every rank with exit 3 within seconds, never a hang.
 *
 * Skipped, with a message, when mpirun or ./yfdem_mpi is absent (`make check` builds it when
 * mpicc is installed: tools/install-deps --test installs OpenMPI).  Runs are short (tens to a
 * few hundred steps): the bits diverge at the first wrong addition, and a wrong exchange is
 * visible in the hash within a step or two.
 */
#include <check.h>
#include <glob.h>
#include <hdf5.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>
#include "yftest.h"

static char ROOT[PATH_MAX], MPIBIN[PATH_MAX], SERBIN[PATH_MAX];

/* The binaries and mpirun; 0 (and a message) when the MPI tests cannot run. */
static int mpi_ready(void) {
  if (!getcwd(ROOT, sizeof ROOT)) return 0;
  const char *m = getenv("YFDEM_MPI"), *s = getenv("YFDEM");
  if (!realpath(m ? m : "./yfdem_mpi", MPIBIN) || access(MPIBIN, X_OK) != 0 ||
      system("command -v mpirun >/dev/null 2>&1") != 0) {
    fprintf(stderr, "check_mpi: SKIPPED: mpirun or ./yfdem_mpi not found (tools/install-deps --mpi; make mpi)\n");
    return 0;
  }
  ck_assert_msg(realpath(s ? s : "./yfdem", SERBIN) != NULL, "no ./yfdem");
  return 1;
}

/* A fresh working directory (outputs of the decks land there). */
static char *workdir(void) {
  char *d = strdup("/tmp/yf_mpi_XXXXXX");
  ck_assert_ptr_nonnull(mkdtemp(d));
  return d;
}

/* The end of a test: its working directory goes (only after a pass: a failure keeps it). */
static void drop_dir(char *d) {
  char cmd[64];
  snprintf(cmd, sizeof cmd, "rm -rf %s", d);
  ck_assert_int_eq(system(cmd), 0);
  free(d);
}

/* Run in dir: ./yfdem (ranks 0) or mpirun -np ranks ./yfdem_mpi, with args; threads > 0: exactly
 * that many OpenMP threads on every step (-threads), threads < 0: the thread governor's choice of
 * 1 or -threads on each step (docs/THREADS.md).  stderr to dir/err.txt, stdout to dir/out.txt.
 * Returns the exit code; *secs the wall time. */
static int run_in(const char *dir, int ranks, int threads, const char *args, double *secs) {
  char cmd[4 * PATH_MAX + 1024], th[32] = "";
  /* YFDEM_MPI_POISON=1: after each step a rank sets NaN into every node it neither owns nor reads
   * as a ghost (the divided update, par.h), so a reader that forgot to gather shows in the bits */
  const char *env = "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMP_WAIT_POLICY=passive "
                    "YFDEM_MPI_POISON=1";
  if (threads > 0) snprintf(th, sizeof th, "-threads %d", threads);
  threads = abs(threads);
  if (ranks > 0)
    snprintf(cmd, sizeof cmd, "cd %s && %s OMP_NUM_THREADS=%d timeout 300 mpirun -q --oversubscribe --mca "
             "mpi_yield_when_idle 1 -np %d %s %s %s >out.txt 2>err.txt", dir, env, threads, ranks, MPIBIN, th, args);
  else
    snprintf(cmd, sizeof cmd, "cd %s && OMP_NUM_THREADS=%d %s %s %s >out.txt 2>err.txt", dir, threads, SERBIN, th,
             args);
  struct timespec t0, t1;
  clock_gettime(CLOCK_MONOTONIC, &t0);
  int st = system(cmd);
  clock_gettime(CLOCK_MONOTONIC, &t1);
  if (secs) *secs = (double)(t1.tv_sec - t0.tv_sec) + 1e-9 * (double)(t1.tv_nsec - t0.tv_nsec);
  return WIFEXITED(st) ? WEXITSTATUS(st) : 128;
}

/* The summary lines that must be bitwise equal on any ranks x threads. */
static char *key_lines(const char *path) {
  static const char *const keys[] = {"\"steps\"", "\"state_hash\"", "\"energy\"", "\"joints_broken\"",
                                     "\"contact_pairs\"", "\"peak_stress\"", "\"first_break\"", NULL};
  char *txt = yft_slurp(path, 0);
  ck_assert_msg(txt != NULL, "no summary %s", path);
  size_t cap = strlen(txt) + 1, n = 0;
  char *out = calloc(cap, 1);
  for (char *line = strtok(txt, "\n"); line; line = strtok(NULL, "\n")) {
    const char *k = line + strspn(line, " ");
    for (int i = 0; keys[i]; i++)
      if (!strncmp(k, keys[i], strlen(keys[i]))) {
        n += (size_t)snprintf(out + n, cap - n, "%s\n", k);
        break;
      }
  }
  free(txt);
  return out;
}

/* Run args (which write -summary m.json) on `ranks` ranks x 1 thread in dir: exit 0 and the
 * summary's key lines equal ref (./yfdem's); what names the case in a failure. */
static void ranks_match(const char *dir, int ranks, const char *args, const char *ref, const char *what) {
  char path[PATH_MAX + 32];
  ck_assert_msg(run_in(dir, ranks, 1, args, NULL) == 0, "%s, %d ranks: failed", what, ranks);
  snprintf(path, sizeof path, "%s/m.json", dir);
  char *got = key_lines(path);
  ck_assert_msg(!strcmp(ref, got), "%s, %d ranks differ from ./yfdem:\n%s--- vs ./yfdem:\n%s", what, ranks, got, ref);
  free(got);
}

static void write_file(const char *dir, const char *name, const char *text) {
  char p[PATH_MAX + 64];
  snprintf(p, sizeof p, "%s/%s", dir, name);
  FILE *f = fopen(p, "w");
  ck_assert_ptr_nonnull(f);
  fputs(text, f);
  fclose(f);
}

/* /stress of a frame file (every triangle: the ranks' shares gathered for the writer); NULL if
 * the file has none.  *n: doubles read. */
static double *frame_stress(const char *dir, const char *frame, long *n) {
  char p[PATH_MAX + 64];
  snprintf(p, sizeof p, "%s/%s", dir, frame);
  *n = 0;
  hid_t f = H5Fopen(p, H5F_ACC_RDONLY, H5P_DEFAULT);
  if (f < 0) return NULL;
  hid_t ds = H5Dopen2(f, "/stress", H5P_DEFAULT);
  double *buf = NULL;
  if (ds >= 0) {
    hid_t sp = H5Dget_space(ds);
    *n = (long)H5Sget_simple_extent_npoints(sp);
    buf = malloc((size_t)(*n > 0 ? *n : 1) * sizeof(double));
    if (H5Dread(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, buf) < 0) *n = -1;
    H5Sclose(sp);
    H5Dclose(ds);
  }
  H5Fclose(f);
  return buf;
}

/* The matrix for one case: ./yfdem on 1 thread, then 1-4 ranks x 1-2 threads; frame (or NULL):
 * an HDF5 frame whose stresses must be bitwise ./yfdem's too. */
static void matrix_gov(const char *name, const char *dir, const char *args, const char *frame, int team);
static void matrix(const char *name, const char *dir, const char *args, const char *frame) {
  matrix_gov(name, dir, args, frame, 1);
}
/* team 0: no loop of the scene is large enough to ask for the team, so the governor times no
 * step and never switches (threads.c: nothing to choose; it used to read the CPU clock twice a
 * step to switch between counts that computed alike) */
static void matrix_gov(const char *name, const char *dir, const char *args, const char *frame, int team) {
  char sargs[2 * PATH_MAX + 64], path[PATH_MAX + 32], line[256];
  snprintf(sargs, sizeof sargs, "%s -summary ref.json", args);
  ck_assert_msg(run_in(dir, 0, 1, sargs, NULL) == 0, "%s: ./yfdem failed", name);
  snprintf(path, sizeof path, "%s/ref.json", dir);
  char *ref = key_lines(path);
  ck_assert_msg(strstr(ref, "state_hash") != NULL, "%s: no state_hash", name);
  long nref = 0, ngot = 0;
  double *sref = frame ? frame_stress(dir, frame, &nref) : NULL;
  ck_assert_msg(!frame || (sref && nref > 0), "%s: no stresses in ./yfdem's %s", name, frame);
  int k = snprintf(line, sizeof line, "check_mpi: %-16s", name);
  for (int ranks = 1; ranks <= 4; ranks++)
    for (int i = 0; i < 3; i++) { /* exactly 1 and 2 threads, and on 2 ranks the governor (-2) */
      const int th = (const int[]){1, 2, -2}[i];
      if (th < 0 && ranks != 2) break;
      double secs;
      snprintf(sargs, sizeof sargs, "%s -summary m.json", args);
      int rc = run_in(dir, ranks, th, sargs, &secs);
      ck_assert_msg(rc == 0, "%s: %d ranks x %d threads: exit %d", name, ranks, th, rc);
      snprintf(path, sizeof path, "%s/m.json", dir);
      char *got = key_lines(path);
      ck_assert_msg(!strcmp(ref, got), "%s: %d ranks x %d threads differ from ./yfdem:\n%s--- vs ./yfdem:\n%s", name,
                    ranks, th, got, ref);
      free(got);
      unlink(path);
      if (frame) {
        double *sg = frame_stress(dir, frame, &ngot);
        ck_assert_msg(sg && ngot == nref && !memcmp(sg, sref, (size_t)nref * sizeof(double)),
                      "%s: %d ranks x %d threads: the stresses of %s differ from ./yfdem's", name, ranks, th, frame);
        free(sg);
        char fp[PATH_MAX + 64];
        snprintf(fp, sizeof fp, "%s/%s", dir, frame);
        unlink(fp);
      }
      if (th < 0 && team) { /* the run line says how the governor shared the steps: both counts ran */
        snprintf(path, sizeof path, "%s/out.txt", dir);
        char *out = yft_slurp(path, 0);
        /* "run: ... on 2 threads; auto: N steps on 2, M on 1)" (not "timestep auto: dt = ...") */
        const char *a = out ? strstr(out, "; auto: ") : NULL, *b = a ? strstr(a, " on 2, ") : NULL;
        long on2 = a ? strtol(a + 8, NULL, 10) : 0, on1 = b ? strtol(b + 7, NULL, 10) : 0;
        ck_assert_msg(on2 > 0 && on1 > 0, "%s: 2 ranks x auto: the governor did not switch (%.60s)", name,
                      a ? a : "no 'auto:' on the run line");
        free(out);
      }
      k += snprintf(line + k, sizeof line - (size_t)k, th > 0 ? " %dx%d ok" : " %dxauto ok", ranks, th);
    }
  fprintf(stderr, "%s (state_hash, energies, joints, couples, stresses as ./yfdem)\n", line);
  free(ref);
  free(sref);
}

START_TEST(matrix_column) {
  if (!mpi_ready()) return;
  char *d = workdir(), a[2 * PATH_MAX];
  snprintf(a, sizeof a, "-in %s/decks/column.deck -var steps 120", ROOT);
  matrix("column", d, a, NULL);
  drop_dir(d);
}
END_TEST

START_TEST(matrix_beam) {
  if (!mpi_ready()) return;
  char *d = workdir(), a[2 * PATH_MAX];
  snprintf(a, sizeof a, "-in %s/decks/beam.deck -var steps 300 -var every 100", ROOT);
  matrix("beam", d, a, "beam_000003.h5"); /* frames at steps 0, 100, 200, 300 */
  drop_dir(d);
}
END_TEST

static const char *const Y2D[] = {"a_elastic_block", "b_beam_impact", "c_column_impact", "d1_cantilever_bc"};

START_TEST(matrix_y2d) {
  if (!mpi_ready()) return;
  char *d = workdir(), deck[PATH_MAX + 128];
  snprintf(deck, sizeof deck, "read_y2d %s/tests/y2d/decks/%s.y\nrun 150\n", ROOT, Y2D[_i]);
  write_file(d, "y.deck", deck);
  /* a (736 triangles) and d1 are too small for any loop to ask for the team (parfor.h) */
  matrix_gov(Y2D[_i], d, "-in y.deck", NULL, _i == 1 || _i == 2);
  drop_dir(d);
}
END_TEST

/* PERF.md's problem at 1e4 triangles (5 element blocks: blocks inside ranks and blocks split
 * between them), generated by tools/gen_perf_deck.py. */
static char *perf_dir(int steps) {
  char *d = workdir(), cmd[2 * PATH_MAX];
  snprintf(cmd, sizeof cmd, "python3 %s/tools/gen_perf_deck.py 94 %s/perf.y --steps %d >/dev/null", ROOT, d, steps);
  ck_assert_msg(system(cmd) == 0, "cannot generate the PERF.md deck");
  return d;
}

START_TEST(matrix_perf_1e4) {
  if (!mpi_ready()) return;
  char *d = perf_dir(40);
  write_file(d, "p.deck", "read_y2d perf.y\nrun 40\n");
  matrix("y2d_perf 1e4", d, "-in p.deck", NULL);
  drop_dir(d);
}
END_TEST

static long report_count(const char *dir, const char *what);
static int count_in(const char *dir, const char *name, const char *needle);

/* A number the ranks' report gives just before `what` ("N WHAT"), or -1. */
static double report_before(const char *dir, const char *what) {
  char p[PATH_MAX + 64];
  snprintf(p, sizeof p, "%s/out.txt", dir);
  char *t = yft_slurp(p, 1);
  const char *q = strstr(t, what);
  double v = -1;
  if (q && q > t + 1) {
    q--; /* the space before WHAT, then back to the start of the number */
    while (q > t && q[-1] != ' ') q--;
    v = strtod(q, NULL);
  }
  free(t);
  return v;
}

/* The couple list by ranks (contact.c): each rank holds its own couples only, so on 2 ranks the
 * entries the two hold add up to the whole list's, and each holds some (a replicated list: each
 * holds all of them).  From the report's "contact couples held per rank A..B of N". */
static void couples_divided(const char *dir, const char *what) {
  char p[PATH_MAX + 64];
  snprintf(p, sizeof p, "%s/out.txt", dir);
  char *t = yft_slurp(p, 1);
  const char *q = strstr(t, "contact couples held per rank ");
  long a = -1, b = -1, n = -1;
  ck_assert_msg(q && sscanf(q, "contact couples held per rank %ld..%ld of %ld", &a, &b, &n) == 3,
                "%s: the report does not say which couples each rank holds", what);
  free(t);
  ck_assert_msg(n > 1000 && a > 0 && a + b == n, "%s: ranks hold %ld and %ld couples of the list's %ld: not each "
                "its own", what, a, b, n);
}

/* The divided update (par.h): on PERF.md's problem at 1e4 (every triangle fracturing: 3 nodes
 * per triangle, 29 682 nodes) on 2 ranks each rank updates its own nodes and receives only its
 * ghosts' state (32 B per ghost node per step) and, at a contact search, the discs that reach its
 * box and its neighbours' couple counts (4 B per rank).  The replicated update it replaces sends
 * every node's force every step (16 B per node, and per rank beyond the first).  So the divided
 * update must save at least half of what that allgather alone sends, with ./yfdem's bits;
 * YFDEM_MPI_DIVIDE=0 (the replicated update) must send at least that; a mass-damped deck says why
 * it replicates; a value other than 0 or 1 is refused.  Each way, and under mass damping, each
 * rank holds its own couples only (couples_divided). */
START_TEST(divided_update) {
  if (!mpi_ready()) return;
  char *d = perf_dir(40);
  write_file(d, "p.deck", "read_y2d perf.y\nrun 40\n");
  ck_assert_int_eq(run_in(d, 0, 1, "-in p.deck -summary ref.json", NULL), 0);
  char path[PATH_MAX + 32];
  snprintf(path, sizeof path, "%s/ref.json", d);
  char *ref = key_lines(path);
  double nodes = 0, bytes[2] = {0, 0};
  {
    char *t = yft_slurp(path, 1);
    const char *q = strstr(t, "\"nodes\":");
    ck_assert(q != NULL);
    nodes = strtod(q + 8, NULL);
    free(t);
  }
  const double allgather = 16.0 * nodes; /* 2 ranks: each sends its half of every node's force */
  for (int div = 1; div >= 0; div--) {
    setenv("YFDEM_MPI_DIVIDE", div ? "1" : "0", 1);
    int rc = run_in(d, 2, 1, "-in p.deck -summary m.json", NULL);
    unsetenv("YFDEM_MPI_DIVIDE");
    ck_assert_int_eq(rc, 0);
    snprintf(path, sizeof path, "%s/m.json", d);
    char *got = key_lines(path);
    ck_assert_msg(!strcmp(ref, got), "YFDEM_MPI_DIVIDE=%d: differs from ./yfdem:\n%s--- vs ./yfdem:\n%s", div, got, ref);
    free(got);
    bytes[div] = report_before(d, "bytes sent per step");
    ck_assert_msg(report_count(d, div ? "; update divided (" : "; update replicated (YFDEM_MPI_DIVIDE=0") != -1,
                  "YFDEM_MPI_DIVIDE=%d: the report does not say how the update ran", div);
    couples_divided(d, div ? "divided update" : "replicated update");
  }
  /* the divided update still sends the ghosts' state, the discs at a search and what readers
   * gather at the run's start and end: it must save at least half the allgather */
  ck_assert_msg(bytes[1] > 0 && bytes[0] - bytes[1] >= 0.5 * allgather,
                "divided update: %.4g bytes per step against %.4g replicated: saves less than half the force "
                "allgather's %.4g", bytes[1], bytes[0], allgather);
  ck_assert_msg(bytes[0] >= allgather, "replicated update: %.4g bytes per step, below the allgather's %.4g", bytes[0],
                allgather);
  /* a value that is neither 0 nor 1 is refused, once, with exit 1 (a deck error), not taken for one */
  setenv("YFDEM_MPI_DIVIDE", "yes", 1);
  int rc = run_in(d, 2, 1, "-in p.deck", NULL);
  unsetenv("YFDEM_MPI_DIVIDE");
  ck_assert_msg(rc == 1 && count_in(d, "err.txt", "YFDEM_MPI_DIVIDE='yes'") >= 1,
                "YFDEM_MPI_DIVIDE=yes: exit %d, message %d times", rc, count_in(d, "err.txt", "YFDEM_MPI_DIVIDE='yes'"));
  fprintf(stderr, "check_mpi: divided update on 2 ranks: %.3g bytes per step against %.3g replicated (force "
          "allgather alone %.3g), ./yfdem's bits both ways\n", bytes[1], bytes[0], allgather);
  free(ref);
  /* mass damping sums over every node every step: replicated, said, the same bits */
  write_file(d, "pd.deck", "read_y2d perf.y\ndamping mass 2000\nrun 40\n");
  {
    ck_assert_int_eq(run_in(d, 0, 1, "-in pd.deck -summary ref.json", NULL), 0);
    snprintf(path, sizeof path, "%s/ref.json", d);
    ref = key_lines(path);
    ck_assert_int_eq(run_in(d, 2, 1, "-in pd.deck -summary m.json", NULL), 0);
    snprintf(path, sizeof path, "%s/m.json", d);
    char *got = key_lines(path);
    ck_assert_msg(!strcmp(ref, got), "mass damping: differs from ./yfdem:\n%s--- vs ./yfdem:\n%s", got, ref);
    ck_assert_msg(report_count(d, "; update replicated (mass damping") != -1, "mass damping: the report does not "
                  "say the update is replicated for it");
    couples_divided(d, "mass damping");
    free(got);
    free(ref);
  }
  drop_dir(d);
}
END_TEST

/* Every dataset of frame file b equals a's: the same objects (names), and for each dataset the
 * same type, shape and bytes.  Returns NULL, or what differs (a static message). */
typedef struct {
  hid_t other;
  long nobj;
  char why[PATH_MAX + 256];
} FrameCmp;

static herr_t frame_cmp_one(hid_t loc, const char *name, const H5O_info_t *info, void *data) {
  FrameCmp *c = data;
  c->nobj++;
  if (c->why[0] || info->type != H5O_TYPE_DATASET) return 0;
  hid_t da = H5Dopen2(loc, name, H5P_DEFAULT), db = H5Dopen2(c->other, name, H5P_DEFAULT);
  if (db < 0) {
    snprintf(c->why, sizeof c->why, "%s missing", name);
  } else {
    hid_t ta = H5Dget_type(da), tb = H5Dget_type(db), sa = H5Dget_space(da), sb = H5Dget_space(db);
    hsize_t na[4] = {0}, nb[4] = {0};
    int ra = H5Sget_simple_extent_dims(sa, na, NULL), rb = H5Sget_simple_extent_dims(sb, nb, NULL);
    if (H5Tequal(ta, tb) <= 0 || ra != rb || memcmp(na, nb, sizeof na)) {
      snprintf(c->why, sizeof c->why, "%s: type or shape differs", name);
    } else {
      size_t bytes = (size_t)H5Sget_simple_extent_npoints(sa) * H5Tget_size(ta);
      char *ba = malloc(bytes + 1), *bb = malloc(bytes + 1);
      hid_t mt = H5Tget_native_type(ta, H5T_DIR_DEFAULT);
      if (bytes && (H5Dread(da, mt, H5S_ALL, H5S_ALL, H5P_DEFAULT, ba) < 0 ||
                    H5Dread(db, mt, H5S_ALL, H5S_ALL, H5P_DEFAULT, bb) < 0))
        snprintf(c->why, sizeof c->why, "%s: cannot read", name);
      else if (bytes && memcmp(ba, bb, bytes)) {
        size_t k = 0;
        while (ba[k] == bb[k]) k++;
        snprintf(c->why, sizeof c->why, "%s: values differ (first at byte %zu of %zu)", name, k, bytes);
      }
      H5Tclose(mt);
      free(ba);
      free(bb);
    }
    H5Tclose(ta); H5Tclose(tb); H5Sclose(sa); H5Sclose(sb);
    H5Dclose(db);
  }
  H5Dclose(da);
  return 0;
}

static herr_t frame_count(hid_t loc, const char *name, const H5O_info_t *info, void *data) {
  (void)loc; (void)name; (void)info;
  ++*(long *)data;
  return 0;
}

static const char *frame_diff(const char *pa, const char *pb) {
  static FrameCmp c;
  memset(&c, 0, sizeof c);
  hid_t fa = H5Fopen(pa, H5F_ACC_RDONLY, H5P_DEFAULT), fb = H5Fopen(pb, H5F_ACC_RDONLY, H5P_DEFAULT);
  if (fa < 0 || fb < 0) {
    snprintf(c.why, sizeof c.why, "cannot open %s", fa < 0 ? pa : pb);
  } else {
    c.other = fb;
    long nb = 0;
    H5Ovisit(fa, H5_INDEX_NAME, H5_ITER_INC, frame_cmp_one, &c);
    H5Ovisit(fb, H5_INDEX_NAME, H5_ITER_INC, frame_count, &nb);
    if (!c.why[0] && nb != c.nobj) snprintf(c.why, sizeof c.why, "%ld objects against %ld", nb, c.nobj);
  }
  if (fa >= 0) H5Fclose(fa);
  if (fb >= 0) H5Fclose(fb);
  return c.why[0] ? c.why : NULL;
}

/* Frames of ./yfdem_mpi written by every rank with parallel HDF5 (YFDEM_H5_MPIIO=1: each rank
 * writes the rows of its triangles, nodes and joints, nothing gathered) and by a gather to rank
 * 0 (=0), on 2 and 3 ranks, against ./yfdem's: PERF.md's problem at 1e4 (contact forces, cracks
 * opened and broken by step 40), frames at steps 0, 20 and 40; every dataset's bytes and the two
 * .xmf indexes equal.  A rank whose rows are not written leaves the file's bytes there
 * unwritten (no fill), which the comparison sees. */
START_TEST(frames_parallel_h5) {
  if (!mpi_ready()) return;
  char *d = perf_dir(40);
  write_file(d, "p.deck", "read_y2d perf.y\ndump d h5 20 fr/p.h5\nrun 40\n");
  char cmd[PATH_MAX + 64], pa[PATH_MAX + 64], pb[PATH_MAX + 64];
  snprintf(cmd, sizeof cmd, "mkdir %s/fr", d);
  ck_assert_int_eq(system(cmd), 0);
  ck_assert_msg(run_in(d, 0, 1, "-in p.deck", NULL) == 0, "./yfdem failed");
  snprintf(cmd, sizeof cmd, "mv %s/fr %s/ref", d, d);
  ck_assert_int_eq(system(cmd), 0);
  static const char *const files[] = {"p_000000.h5", "p_000001.h5", "p_000002.h5", "p.xmf", "p_cracks.xmf"};
  for (int ranks = 2; ranks <= 3; ranks++)
    for (int mpio = 1; mpio >= 0; mpio--) {
      snprintf(cmd, sizeof cmd, "rm -rf %s/fr && mkdir %s/fr", d, d);
      ck_assert_int_eq(system(cmd), 0);
      setenv("YFDEM_H5_MPIIO", mpio ? "1" : "0", 1);
      int rc = run_in(d, ranks, 1, "-in p.deck", NULL);
      unsetenv("YFDEM_H5_MPIIO");
      ck_assert_msg(rc == 0, "%d ranks, YFDEM_H5_MPIIO=%d: exit %d", ranks, mpio, rc);
      snprintf(pa, sizeof pa, "%s/out.txt", d);
      char *out = yft_slurp(pa, 0);
      ck_assert_msg(out && !strstr(out, "parallel HDF5") == !mpio, "%d ranks, YFDEM_H5_MPIIO=%d: the dump line does "
                    "not say how it is written", ranks, mpio);
      free(out);
      for (size_t i = 0; i < sizeof files / sizeof files[0]; i++) {
        snprintf(pa, sizeof pa, "%s/ref/%s", d, files[i]);
        snprintf(pb, sizeof pb, "%s/fr/%s", d, files[i]);
        if (strstr(files[i], ".xmf")) { /* the index names the frames, which have the same names */
          char *ta = yft_slurp(pa, 0), *tb = yft_slurp(pb, 0);
          ck_assert_msg(ta && tb && !strcmp(ta, tb), "%d ranks, YFDEM_H5_MPIIO=%d: %s differs from ./yfdem's", ranks,
                        mpio, files[i]);
          free(ta);
          free(tb);
          continue;
        }
        const char *why = frame_diff(pa, pb);
        ck_assert_msg(!why, "%d ranks, YFDEM_H5_MPIIO=%d: %s differs from ./yfdem's: %s", ranks, mpio, files[i], why);
      }
    }
  fprintf(stderr, "check_mpi: frames by parallel HDF5 and by the gather, 2 and 3 ranks: every dataset as ./yfdem's\n");
  drop_dir(d);
}
END_TEST

/* Two fracturing blocks of 128 triangles each (one METIS part: the partition order is the mesh
 * order, so on 2 ranks rank 0 owns block a and rank 1 block b; on 3 and 4 ranks the rank borders
 * cut the blocks); a flies at 50 m/s into b, shatters against it and breaks joints everywhere.
 * On 1-4 ranks: the summary's bits equal ./yfdem's; the ranks' own counts show couples of two
 * ranks' triangles touching (a body, then its fragments, crossing into another rank's region)
 * and joints broken across rank borders; momentum (no support, no gravity: every force pair is
 * internal) stays a's initial m v to 1e-12 (equal-area triangles with their own nodes: equal
 * node masses, so each block's momentum is its mass times its nodes' mean velocity). */
static const char CROSS_DECK[] =
    "material c elastic rho 2340 E 26e9 nu 0.18 plane_stress pen_n 1e11 pen_t 1e10 friction 0.3\n"
    "jointprop j ft 2e5 fs 2e5 gf 1 pen 1e11\n"
    "mesh rect a c 0 0 0.02 0.02 8 8 pattern right\n"
    "mesh rect b c 0.0205 0 0.0405 0.02 8 8 pattern right\n"
    "fracture a j\nfracture b j\nvelocity a set 50 0\n"
    "contact self a\ncontact self b\ncontact pair a b\n"
    "timestep auto safety 0.5\nthermo 0\nrecord r 50 rec.csv vx_a vx_b ux_b fx_a ke broken\nrun 600\n"
    "print \"momentum $(mass_a) $(vx_a) $(mass_b) $(vx_b)\"\n";

/* The momentum line of dir/out.txt: |p - p0| / p0 with p0 = m_a 50 m/s. */
static double momentum_error(const char *dir) {
  char p[PATH_MAX + 64];
  snprintf(p, sizeof p, "%s/out.txt", dir);
  char *t = yft_slurp(p, 1);
  const char *q = strstr(t, "momentum ");
  double ma = 0, va = 0, mb = 0, vb = 0;
  ck_assert_msg(q && sscanf(q, "momentum %lf %lf %lf %lf", &ma, &va, &mb, &vb) == 4, "no momentum line in:\n%s", t);
  free(t);
  ck_assert(ma > 0 && mb > 0);
  return fabs(ma * va + mb * vb - ma * 50.0) / (ma * 50.0);
}

/* A count the ranks' report gives after `what` ("...; WHAT N"), or -1. */
static long report_count(const char *dir, const char *what) {
  char p[PATH_MAX + 64];
  snprintf(p, sizeof p, "%s/out.txt", dir);
  char *t = yft_slurp(p, 1);
  const char *q = strstr(t, what);
  long n = q ? strtol(q + strlen(what), NULL, 10) : -1;
  free(t);
  return n;
}

/* Every output a user reads, not the state alone: a fracturing slab hit by a steel block, on a
 * steel foot, pushed at one end by a velocity fix with a history, under gravity, a traction with
 * a sine history and a point load, with contact, friction, Weibull-scattered joints, two runs with
 * an `if` on a result between them that removes the point load and the fix.  On 3 ranks (poisoned:
 * a reader that forgot to gather would see NaN) every file equals ./yfdem's byte for byte: the
 * record rows (expressions of group quantities), the metrics log, both fracture logs, the CSV
 * frames and their index; and so do the thermo lines (custom, with a group quantity; wall time
 * aside) and the `print` lines of results between and after the runs. */
static const char *OUTPUTS_DECK =
    "history rise ramp 0 2e-5\n"
    "history wob sine 1e-4\n"
    "material c elastic rho 2400 E 30e9 nu 0.2 plane_stress damping 0.05 pen_n 3e11 pen_t 3e10 friction 0.4\n"
    "material s elastic rho 7800 E 200e9 nu 0.3 plane_stress pen_n 3e11 pen_t 3e10 friction 0.3\n"
    "mesh rect slab c 0 0 0.6 0.1 180 30 pattern alt\n"
    "mesh rect ball s 0.27 0.10002 0.33 0.16002 8 8\n"
    "mesh rect foot s 0.0 -0.03 0.6 0 40 2\n"
    "jointprop cj ft 2e6 fs 6e6 gf 30 pen 3e11 weibull 6 seed 5\n"
    "region mid box 0.2 -1 0.4 1\n"
    "fracture slab cj region mid\n"
    "region base box -1 -1 2 -0.0299\n"
    "group base node region base\n"
    "fix hold base fixed xy\n"
    "region lend box -1 -1 1e-9 1\n"
    "group lend node region lend body slab\n"
    "fix pushl lend velocity 0.2 NULL history rise\n"
    "region rtop box 0.55 0.0999 0.61 0.11\n"
    "group rtop node region rtop body slab\n"
    "load rl rtop traction 0 -2e5 history wob\n"
    "load pt point at 0.45 0.1 0 -500\n"
    "gravity 0 -9.81\n"
    "velocity ball set 0.5 -25\n"
    "contact pair ball slab\n"
    "contact pair slab foot\n"
    "contact self slab\n"
    "metrics body slab\n"
    "metrics region mid mid\n"
    "metrics log m.csv every 50\n"
    "fracture_log br.csv opened op.csv\n"
    "record r 25 r.csv ke strain broken pairs uy_ball \"ke+strain\"\n"
    "timestep auto safety 0.5\n"
    "thermo_style custom step ke strain broken pairs vy_ball\n"
    "thermo 100\n"
    "dump d csv 100 fr\n"
    "run 300\n"
    "print \"after 1: broken $(broken) vy_ball $(vy_ball)\"\n"
    "if \"$(broken) > 0\" then \"unload pt\" \"unfix pushl\"\n"
    "run 200\n"
    "print \"end: broken $(broken) vy_ball $(vy_ball) ux_slab $(ux_slab) crack $(crack_length)\"\n"
;
static const char *const OUTPUT_FILES[] = {"r.csv", "m.csv", "br.csv", "op.csv", "fr_frames.csv", "fr_000000.csv",
                                           "fr_000003.csv", "fr_000005.csv", NULL};

/* out.txt of a run without what differs between ./yfdem and ./yfdem_mpi by design: timings, the
 * mpi: report, the parallel frame note (only lines printed by rank 0, in order). */
static char *printed(const char *dir) {
  char p[PATH_MAX + 64];
  snprintf(p, sizeof p, "%s/out.txt", dir);
  char *t = yft_slurp(p, 0), *o = calloc(strlen(t ? t : "") + 1, 1);
  size_t n = 0;
  for (char *line = t ? strtok(t, "\n") : NULL; line; line = strtok(NULL, "\n")) {
    static const char *const skip[] = {"run:", "stage", "elements", "joints ", "detection", "contact ", "gather",
                                       "update", "output", "other", "mpi:", NULL};
    int drop = 0;
    for (int i = 0; skip[i] && !drop; i++) drop = !strncmp(line, skip[i], strlen(skip[i]));
    if (!drop) n += (size_t)sprintf(o + n, "%s\n", line);
  }
  free(t);
  return o;
}

START_TEST(outputs_equal) {
  if (!mpi_ready()) return;
  char *a = workdir(), *b = workdir();
  write_file(a, "o.deck", OUTPUTS_DECK);
  write_file(b, "o.deck", OUTPUTS_DECK);
  ck_assert_int_eq(run_in(a, 0, 2, "-in o.deck -summary s.json", NULL), 0);
  ck_assert_int_eq(run_in(b, 3, 1, "-in o.deck -summary s.json", NULL), 0);
  char pa[PATH_MAX + 64], pb[PATH_MAX + 64];
  snprintf(pa, sizeof pa, "%s/s.json", a);
  snprintf(pb, sizeof pb, "%s/s.json", b);
  char *ka = key_lines(pa), *kb = key_lines(pb);
  ck_assert_msg(!strcmp(ka, kb), "3 ranks:\n%s--- vs ./yfdem:\n%s", kb, ka);
  free(ka); free(kb);
  int nfiles = 0;
  for (int i = 0; OUTPUT_FILES[i]; i++) {
    snprintf(pa, sizeof pa, "%s/%s", a, OUTPUT_FILES[i]);
    snprintf(pb, sizeof pb, "%s/%s", b, OUTPUT_FILES[i]);
    char *fa = yft_slurp(pa, 0), *fb = yft_slurp(pb, 0);
    ck_assert_msg(fa && strchr(fa, '\n') != strrchr(fa, '\n'), "./yfdem wrote no rows to %s", OUTPUT_FILES[i]);
    ck_assert_msg(fb && !strcmp(fa, fb), "%s on 3 ranks differs from ./yfdem's", OUTPUT_FILES[i]);
    free(fa); free(fb);
    nfiles++;
  }
  char *oa = printed(a), *ob = printed(b);
  /* the deck's prints, after the runs' thermo lines: the physics happened (joints broke, the if
   * took its branch) */
  ck_assert_msg(strstr(oa, "after 1: broken ") && !strstr(oa, "after 1: broken 0 ") && strstr(oa, "end: broken "),
                "./yfdem printed:\n%s", oa);
  ck_assert_msg(!strcmp(oa, ob), "what 3 ranks printed differs from ./yfdem:\n%s--- vs ./yfdem:\n%s", ob, oa);
  free(oa); free(ob);
  fprintf(stderr, "check_mpi: outputs_equal: %d files and the printed lines on 3 ranks as ./yfdem\n", nfiles);
  drop_dir(a);
  drop_dir(b);
}
END_TEST

START_TEST(bodies_cross_ranks) {
  if (!mpi_ready()) return;
  char *d = workdir(), path[PATH_MAX + 32];
  write_file(d, "cross.deck", CROSS_DECK);
  ck_assert_int_eq(run_in(d, 0, 1, "-in cross.deck -summary ref.json", NULL), 0);
  ck_assert_msg(momentum_error(d) <= 1e-12, "./yfdem: momentum off by %g", momentum_error(d));
  snprintf(path, sizeof path, "%s/ref.json", d);
  char *ref = key_lines(path);
  snprintf(path, sizeof path, "%s/rec.csv", d);
  char *rec = yft_slurp(path, 1);
  long jx_most = 0;
  for (int ranks = 2; ranks <= 4; ranks++) {
    int th = ranks == 2 ? 2 : 1;
    ck_assert_int_eq(run_in(d, ranks, th, "-in cross.deck -summary m.json", NULL), 0);
    snprintf(path, sizeof path, "%s/m.json", d);
    char *got = key_lines(path);
    ck_assert_msg(!strcmp(ref, got), "%d ranks x %d threads differ from ./yfdem:\n%s--- vs ./yfdem:\n%s", ranks, th,
                  got, ref);
    free(got);
    /* the record rows read node means and forces of both blocks: gathered, written by rank 0 */
    snprintf(path, sizeof path, "%s/rec.csv", d);
    char *rg = yft_slurp(path, 1);
    ck_assert_msg(!strcmp(rec, rg), "%d ranks: rec.csv differs from ./yfdem's:\n%s--- vs ./yfdem:\n%s", ranks, rg, rec);
    free(rg);
    double pe = momentum_error(d);
    ck_assert_msg(pe <= 1e-12, "%d ranks: momentum off by %g", ranks, pe);
    long hits = report_count(d, "contact hits between two ranks' triangles ");
    long jx = report_count(d, "joints broken across rank borders ");
    ck_assert_msg(hits > 0, "%d ranks: no contact between two ranks' triangles (%ld)", ranks, hits);
    if (ranks == 2) ck_assert_msg(hits > 0 && jx == 0, "2 ranks: the blocks are one rank each (%ld joints across)", jx);
    jx_most = jx > jx_most ? jx : jx_most;
    fprintf(stderr, "check_mpi: two blocks colliding on %d ranks x %d threads: ./yfdem's bits, momentum to %.1e, "
            "%ld couple hits between ranks, %ld joints broken across rank borders\n", ranks, th, pe, hits, jx);
  }
  ck_assert_msg(jx_most > 0, "no joint broke across a rank border on 3 or 4 ranks");
  free(ref);
  free(rec);
  drop_dir(d);
}
END_TEST

/* The contact search on ranks by bounding boxes (contact.c search_ranks): two blocks on two ranks
 * 1.5 mm apart, less than two triangles' disc radii (1.86 mm each) plus the buffer (0.75 mm) but
 * more than the discs reach (1.03 mm beyond each face): the couples across the gap exist only
 * through the buffer, so a rank must receive the other's discs that reach its box within the
 * buffer.  The couple count and every other key equal ./yfdem's on 2 and 3 ranks (seen to fail,
 * 8 couples against 16, with the buffer left out of the reach). */
static const char GAP_DECK[] =
    "material c elastic rho 2340 E 26e9 nu 0.18 plane_stress pen_n 1e11 pen_t 1e10 friction 0.3\n"
    "mesh rect a c 0 0 0.02 0.02 8 8 pattern right\n"
    "mesh rect b c 0.0215 0 0.0415 0.02 8 8 pattern right\n"
    "velocity a set 1 0\ncontact pair a b\ntimestep auto safety 0.5\nthermo 0\nrun 20\n";

START_TEST(search_by_boxes) {
  if (!mpi_ready()) return;
  char *d = workdir(), path[PATH_MAX + 32];
  write_file(d, "gap.deck", GAP_DECK);
  ck_assert_int_eq(run_in(d, 0, 1, "-in gap.deck -summary ref.json", NULL), 0);
  snprintf(path, sizeof path, "%s/ref.json", d);
  char *ref = key_lines(path);
  const char *cp = strstr(ref, "\"contact_pairs\":");
  ck_assert_msg(cp && strtol(cp + 16, NULL, 10) > 0, "./yfdem: no couple across the gap:\n%s", ref);
  for (int ranks = 2; ranks <= 3; ranks++) ranks_match(d, ranks, "-in gap.deck -summary m.json", ref, "gap");
  fprintf(stderr, "check_mpi: couples across a gap within the search buffer found on 2 and 3 ranks as ./yfdem "
          "(%.30s)\n", cp);
  free(ref);
  drop_dir(d);
}
END_TEST

/* The search on ranks sends only what is near another rank's triangles (contact.c search_ranks:
 * one box per chunk of a rank's triangles, a chunk never spanning two METIS parts).  The beam
 * deck at nx 200 (16 112 triangles, every one fracturing and in contact, 4 METIS parts): its
 * rank borders are cuts across its depth of 20 cells, and a disc reaches r_i + r_j + buffer,
 * about 1.5 cells; with a chunk's box a few rows of a part, a rank needs the other's triangles
 * within ~3 cells of a border: 3 cells x 20 deep x 4 triangles x 2 sides = 480 discs a border,
 * and 2 ranks' parts meet at up to 3 borders, so at most 1 611 (10 %) per search.  One box per
 * rank (before 2026-11-28) sent 9 792 (61 %): a rank's parts need not be one region, and the
 * box of two far parts held the whole beam.  The bits stay ./yfdem's on 2 and 3 ranks. */
START_TEST(search_sends_near_only) {
  if (!mpi_ready()) return;
  char *d = workdir(), a[2 * PATH_MAX], path[PATH_MAX + 32];
  snprintf(a, sizeof a, "-in %s/decks/beam.deck -var nx 200 -var steps 200 -var out b -summary ref.json", ROOT);
  ck_assert_int_eq(run_in(d, 0, 1, a, NULL), 0);
  snprintf(path, sizeof path, "%s/ref.json", d);
  char *ref = key_lines(path);
  for (int ranks = 2; ranks <= 3; ranks++) {
    snprintf(a, sizeof a, "-in %s/decks/beam.deck -var nx 200 -var steps 200 -var out b -summary m.json", ROOT);
    ck_assert_int_eq(run_in(d, ranks, 1, a, NULL), 0);
    snprintf(path, sizeof path, "%s/m.json", d);
    char *got = key_lines(path);
    ck_assert_msg(!strcmp(ref, got), "%d ranks differ from ./yfdem:\n%s--- vs ./yfdem:\n%s", ranks, got, ref);
    free(got);
    snprintf(path, sizeof path, "%s/out.txt", d);
    char *t = yft_slurp(path, 1);
    const char *q = strstr(t, "contact search discs sent ");
    double sent = -1, own = -1;
    long nsearch = 0;
    ck_assert_msg(q && sscanf(q, "contact search discs sent %lf per search of %lf (all ranks, %ld searches", &sent,
                              &own, &nsearch) == 3, "%d ranks: the report does not count the discs sent", ranks);
    free(t);
    ck_assert_msg(own == 16112 && nsearch > 0, "%d ranks: %g discs searched (not the beam's 16 112), %ld searches",
                  ranks, own, nsearch);
    if (ranks == 2)
      ck_assert_msg(sent > 0 && sent <= 0.10 * own, "2 ranks: %g discs sent per search of %g: more than the 10 %% near "
                    "the rank borders", sent, own);
    fprintf(stderr, "check_mpi: beam nx 200 on %d ranks: ./yfdem's bits, %.0f discs sent per search of %.0f (%ld "
            "searches)\n", ranks, sent, own, nsearch);
  }
  free(ref);
  drop_dir(d);
}
END_TEST

/* The state_hash line of dir/cont.json, checked equal to dir/full.json's (the uninterrupted
 * run); what names the case in a failure.  Returns the line (static). */
static const char *same_hash_as_full(const char *dir, const char *what) {
  static char line[64];
  char path[PATH_MAX + 32];
  snprintf(path, sizeof path, "%s/full.json", dir);
  char *a = key_lines(path);
  snprintf(path, sizeof path, "%s/cont.json", dir);
  char *b = key_lines(path);
  const char *ha = strstr(a, "\"state_hash\""), *hb = strstr(b, "\"state_hash\"");
  ck_assert_msg(ha && hb && !strncmp(ha, hb, 32), "%s differs:\n%s--- uninterrupted:\n%s", what, b, a);
  const char *sa = strstr(a, "\"steps\""), *sb = strstr(b, "\"steps\"");
  ck_assert_msg(sa && sb && !strncmp(sa, sb, strcspn(sa, "\n")), "%s: not the same step:\n%s--- uninterrupted:\n%s",
                what, b, a);
  snprintf(line, sizeof line, "%.32s", hb);
  free(a);
  free(b);
  return line;
}

/* Written on 2 ranks at step 40, read on 3, continued to 80: the uninterrupted run's bits. */
START_TEST(restart_2_to_3) {
  if (!mpi_ready()) return;
  char *d = perf_dir(80);
  write_file(d, "full.deck", "read_y2d perf.y\nrun 80\n");
  write_file(d, "first.deck", "read_y2d perf.y\nrun 40\nwrite_restart half.restart\n");
  write_file(d, "second.deck", "read_y2d perf.y\nread_restart half.restart\nrun 80 upto\n");
  ck_assert_int_eq(run_in(d, 0, 1, "-in full.deck -summary full.json", NULL), 0);
  ck_assert_int_eq(run_in(d, 2, 1, "-in first.deck", NULL), 0);
  ck_assert_int_eq(run_in(d, 3, 1, "-in second.deck -summary cont.json", NULL), 0);
  fprintf(stderr, "check_mpi: restart written on 2 ranks, read on 3: %s as the uninterrupted run\n",
          same_hash_as_full(d, "restart 2 -> 3 ranks"));
  drop_dir(d);
}
END_TEST

/* Re-balancing (par_mpi.c par_balance): a fracturing block in self-contact (every triangle in
 * couples with its neighbours: 3 nodes, 1.5 joints and about 9 couples per triangle) beside a
 * steel plate of as many triangles that takes no part in contact (1 node per 2 triangles).  METIS
 * gives each body whole parts, so the first cut on 2 ranks puts the block on one rank and the
 * plate on the other: by the fixed weights (13 ns a triangle, 6 a node, 16 a joint, 11 a couple)
 * the block's rank carries 1.8 x the mean.  After the first search the border moves into the
 * block: its couples are shared (each rank holds at least half as many as the other, against
 * 0 and all of them with YFDEM_MPI_BALANCE=0), the weight imbalance after the cut is within the
 * granularity of a block of 256 triangles (about 3 % here), the bits and the h5 frames (every
 * rank writes its rows by the new ranges) are ./yfdem's on 2 and 3 ranks, and a restart written
 * after the re-cut on 2 ranks and read on 3 continues bitwise. */
static const char REBAL_DECK[] =
    "material c elastic rho 2340 E 26e9 nu 0.18 plane_stress pen_n 1e11 pen_t 1e10 friction 0.3\n"
    "material s elastic rho 7800 E 210e9 nu 0.3 plane_stress\n"
    "jointprop cj ft 3e6 fs 3e6 gf 100 pen 1e11 law munjiza\n"
    "mesh rect rubble c 0 0 0.064 0.032 64 32 pattern cross\n"
    "mesh rect plate s 0.1 0 0.164 0.032 64 32 pattern cross\n"
    "fracture rubble cj\ncontact self rubble\nvelocity rubble set 0.5 -2\nvelocity plate set 0 1\n"
    "timestep auto safety 0.5\nthermo 0\n";

static void held_couples(const char *dir, long *a, long *b) {
  char p[PATH_MAX + 64];
  snprintf(p, sizeof p, "%s/out.txt", dir);
  char *t = yft_slurp(p, 1);
  const char *q = strstr(t, "contact couples held per rank ");
  long n = 0;
  ck_assert_msg(q && sscanf(q, "contact couples held per rank %ld..%ld of %ld", a, b, &n) == 3,
                "the report does not say which couples each rank holds");
  free(t);
}

START_TEST(rebalance_contact_work) {
  if (!mpi_ready()) return;
  char *d = workdir(), path[PATH_MAX + 32], deck[sizeof REBAL_DECK + 128];
  snprintf(deck, sizeof deck, "%sdump d h5 20 ${out}.h5\nrun 100\n", REBAL_DECK);
  write_file(d, "full.deck", deck);
  snprintf(deck, sizeof deck, "%srun 50\nwrite_restart half.restart\n", REBAL_DECK);
  write_file(d, "first.deck", deck);
  snprintf(deck, sizeof deck, "%sread_restart half.restart\nrun 100 upto\n", REBAL_DECK);
  write_file(d, "second.deck", deck);
  ck_assert_int_eq(run_in(d, 0, 1, "-in full.deck -var out ref -summary full.json", NULL), 0);
  snprintf(path, sizeof path, "%s/full.json", d);
  char *ref = key_lines(path);
  long a = -1, b = -1;
  setenv("YFDEM_MPI_BALANCE", "0", 1);
  int rc = run_in(d, 2, 1, "-in full.deck -var out m -summary m.json", NULL);
  unsetenv("YFDEM_MPI_BALANCE");
  ck_assert_int_eq(rc, 0);
  held_couples(d, &a, &b);
  ck_assert_msg(a == 0 && b > 10000, "YFDEM_MPI_BALANCE=0: ranks hold %ld..%ld couples: the scene is not one-sided", a,
                b);
  ck_assert_msg(count_in(d, "out.txt", "not re-balanced (YFDEM_MPI_BALANCE=0") == 1,
                "YFDEM_MPI_BALANCE=0: the report does not say the borders stayed");
  for (int ranks = 2; ranks <= 3; ranks++) {
    ranks_match(d, ranks, "-in full.deck -var out m -summary m.json", ref, "re-balanced");
    for (int k = 0; k <= 5; k++) { /* every rank's rows of the frames after the re-cut, by the new ranges */
      char pa[PATH_MAX + 64], pb[PATH_MAX + 64];
      snprintf(pa, sizeof pa, "%s/ref_%06d.h5", d, k);
      snprintf(pb, sizeof pb, "%s/m_%06d.h5", d, k);
      const char *why = frame_diff(pa, pb);
      ck_assert_msg(why == NULL, "%d ranks: frame %d differs from ./yfdem's: %s", ranks, k, why);
    }
    held_couples(d, &a, &b);
    snprintf(path, sizeof path, "%s/out.txt", d);
    char *t = yft_slurp(path, 1);
    const char *q = strstr(t, "re-balanced ");
    int n = 0;
    double w0 = 0, w1 = 0;
    ck_assert_msg(q && sscanf(q, "re-balanced %d time%*[s ](weight imbalance %lf -> %lf", &n, &w0, &w1) == 3,
                  "%d ranks: the report does not say the borders moved (%.80s)", ranks, q ? q : "no 're-balanced'");
    free(t);
    ck_assert_msg(n >= 1 && w0 > 1.5 && w1 < 1.05, "%d ranks: re-balanced %d times, weight imbalance %.3f -> %.3f",
                  ranks, n, w0, w1);
    ck_assert_msg(a > 0 && 2 * a >= b, "%d ranks: couples held per rank %ld..%ld after the re-cut", ranks, a, b);
    fprintf(stderr, "check_mpi: re-balanced on %d ranks: weight imbalance %.3f -> %.3f, couples held per rank "
            "%ld..%ld (all on one rank without), ./yfdem's bits and h5 frames\n", ranks, w0, w1, a, b);
  }
  free(ref);
  ck_assert_int_eq(run_in(d, 2, 1, "-in first.deck", NULL), 0);
  ck_assert_msg(count_in(d, "out.txt", "re-balanced 1 time") == 1, "2 ranks, first half: not re-balanced");
  ck_assert_int_eq(run_in(d, 3, 1, "-in second.deck -summary cont.json", NULL), 0);
  fprintf(stderr, "check_mpi: restart written after a re-cut on 2 ranks, read on 3: %s as the uninterrupted run\n",
          same_hash_as_full(d, "re-balanced restart 2 -> 3 ranks"));
  /* a value that is neither 0 nor 1 is refused (a deck error, exit 1), not taken for one */
  setenv("YFDEM_MPI_BALANCE", "yes", 1);
  rc = run_in(d, 2, 1, "-in full.deck -var out m", NULL);
  unsetenv("YFDEM_MPI_BALANCE");
  ck_assert_msg(rc == 1 && count_in(d, "err.txt", "YFDEM_MPI_BALANCE='yes'") >= 1,
                "YFDEM_MPI_BALANCE=yes: exit %d, message %d times", rc, count_in(d, "err.txt", "YFDEM_MPI_BALANCE='yes'"));
  drop_dir(d);
}
END_TEST


/* What a rank holds for its own range only (docs/SCALING.md section 1: the force gather's lists
 * for its nodes, the joined partners of its lower triangles under 'contact joined skip', its
 * items' discs, its couples' triangles) is made again when a re-cut moves the range, and a
 * restart read on another rank count makes it for the new ranges.  The one-sided rubble deck with
 * joined couples skipped (a couple of an intact joint is left out by its lower triangle's partner
 * list), a search at every step (so that searches follow the re-cut: the deck searches once by
 * travel) and a fixed plate edge (each fix's own acting bits): re-balanced on 2 and 3 ranks, the
 * bits and the couple count are ./yfdem's (partners kept for the first cut's range let in 5000
 * joined couples after the re-cut, with the same state hash); written after the re-cut on 2 ranks
 * and read on 3 and on 1, the run continues bitwise. */
START_TEST(range_buffers_follow_recut) {
  if (!mpi_ready()) return;
  static const char more[] = "contact joined skip search every\nregion pe box 0.163 -1 1 1\ngroup pe node region pe\nfix pe pe fixed x\n";
  char *d = workdir(), path[PATH_MAX + 32], deck[sizeof REBAL_DECK + sizeof more + 128];
  snprintf(deck, sizeof deck, "%s%srun 100\n", REBAL_DECK, more);
  write_file(d, "full.deck", deck);
  snprintf(deck, sizeof deck, "%s%srun 50\nwrite_restart half.restart\n", REBAL_DECK, more);
  write_file(d, "first.deck", deck);
  snprintf(deck, sizeof deck, "%s%sread_restart half.restart\nrun 100 upto\n", REBAL_DECK, more);
  write_file(d, "second.deck", deck);
  ck_assert_int_eq(run_in(d, 0, 1, "-in full.deck -summary full.json", NULL), 0);
  snprintf(path, sizeof path, "%s/full.json", d);
  char *ref = key_lines(path);
  for (int ranks = 2; ranks <= 3; ranks++) {
    ranks_match(d, ranks, "-in full.deck -summary m.json", ref, "joined skip, a fix, re-balanced");
    ck_assert_msg(count_in(d, "out.txt", "not re-balanced") == 0 && count_in(d, "out.txt", "re-balanced ") == 1,
                  "%d ranks: the borders did not move: the test does not test a re-cut", ranks);
  }
  free(ref);
  ck_assert_int_eq(run_in(d, 2, 1, "-in first.deck", NULL), 0);
  ck_assert_msg(count_in(d, "out.txt", "re-balanced 1 time") == 1, "2 ranks, first half: not re-balanced");
  for (int ranks = 3; ranks >= 1; ranks -= 2) {
    ck_assert_int_eq(run_in(d, ranks, 1, "-in second.deck -summary cont.json", NULL), 0);
    fprintf(stderr, "check_mpi: joined skip and a fix, re-cut on 2 ranks, restart read on %d: %s as ./yfdem's run\n",
            ranks, same_hash_as_full(d, "joined skip, restart after a re-cut"));
  }
  drop_dir(d);
}
END_TEST
/* Re-balancing an unpartitioned mesh (below 8192 triangles; found by a sweep of new decks,
 * 2026-11-29): a concrete block with a fracturing zone hit by a steel block, 1600 triangles
 * each.  On 2 ranks the first cut falls between the bodies, where the node order follows the
 * ranks by chance, so the update is divided; the couples all sit on one rank, and the re-cut
 * moved the border to a block of triangles inside a body, where nodes numbered by the mesh (and
 * the fracture's new nodes) no longer follow the triangles' ranks: halo mode ended in the middle
 * of a divided run and the contact stage's assertion stopped it (exit 70).  A cut may now take
 * only a border that keeps the node order (par_mpi.c, P.bok): exit 0 and ./yfdem's bits on 2
 * and 3 ranks, the update still divided on 2. */
static const char UNPART_DECK[] =
    "material c elastic rho 2400 E 30e9 nu 0.2 plane_stress pen_n 3e11 pen_t 3e10 friction 0.4\n"
    "material s elastic rho 7800 E 200e9 nu 0.3 plane_stress pen_n 3e11 pen_t 3e10 friction 0.3\n"
    "jointprop cj ft 1e6 fs 3e6 gf 5 pen 3e11\n"
    "mesh rect a c 0 0 0.1 0.05 40 20 pattern alt\nmesh rect b s 0.1002 0 0.2 0.05 40 20 pattern right\n"
    "region z box 0.08 -1 0.1 1\nfracture a cj region z\ncontact self a\ncontact pair a b\n"
    "velocity a set 20 0\nvelocity b set -20 0\ntimestep auto\nthermo 0\nrun 50\n";

START_TEST(rebalance_unpartitioned) {
  if (!mpi_ready()) return;
  char *d = workdir(), path[PATH_MAX + 32];
  write_file(d, "u.deck", UNPART_DECK);
  ck_assert_int_eq(run_in(d, 0, 1, "-in u.deck -summary ref.json", NULL), 0);
  snprintf(path, sizeof path, "%s/ref.json", d);
  char *ref = key_lines(path);
  for (int ranks = 2; ranks <= 3; ranks++) {
    ranks_match(d, ranks, "-in u.deck -summary m.json", ref, "unpartitioned, re-balanced");
    if (ranks == 2)
      ck_assert_msg(count_in(d, "out.txt", "update divided") == 1, "2 ranks: the update is not divided: the case "
                    "this test is for (a divided run on an unpartitioned mesh) is gone");
  }
  fprintf(stderr, "check_mpi: an unpartitioned mesh's divided run on 2 and 3 ranks: ./yfdem's bits, no cut that "
          "leaves halo mode\n");
  free(ref);
  drop_dir(d);
}
END_TEST

/* The mpi: line's communication share is a share of the run's wall time, so at most 100 %.  It
 * counted the exchanges before the run's clock started (the divided update's ghost lists, the
 * first frames) and the gathers of the deck's prints between runs, and divided the slowest rank's
 * by rank 0's wall: 155-260 % on runs of 2 steps on 2 ranks (a sweep of new decks, 2026-11-29).
 * Each rank's time in exchanges now counts from its run's start, over its own wall. */
START_TEST(report_share_of_wall) {
  if (!mpi_ready()) return;
  char *d = workdir(), path[PATH_MAX + 32];
  write_file(d, "c.deck", "material c elastic rho 2340 E 26e9 nu 0.18 plane_stress pen_n 1e11\n"
             "mesh rect a c 0 0 1 0.5 120 60\ntimestep auto\nthermo 0\nrun 2\nprint \"ux $(ux_a)\"\nrun 2\n");
  ck_assert_int_eq(run_in(d, 2, 1, "-in c.deck", NULL), 0);
  snprintf(path, sizeof path, "%s/out.txt", d);
  char *t = yft_slurp(path, 1);
  int n = 0;
  for (const char *q = strstr(t, "communication "); q; q = strstr(q + 1, "communication ")) {
    double share = -1;
    if (sscanf(q, "communication %lf %% of wall", &share) != 1) continue;
    ck_assert_msg(share >= 0 && share <= 100.0, "run %d: communication %.1f %% of wall", n + 1, share);
    n++;
  }
  ck_assert_msg(n == 2, "%d communication shares reported for 2 runs", n);
  free(t);
  drop_dir(d);
}
END_TEST

/* Why the update is replicated, in the mpi: line: a mesh of 10 000 triangles left unpartitioned by
 * 'partition none' was said to be "an unpartitioned mesh below 8192 triangles" (a sweep of new
 * decks, 2026-11-29).  The reason names both ways a mesh stays unpartitioned; the bits stay
 * ./yfdem's. */
START_TEST(replicated_reason) {
  if (!mpi_ready()) return;
  char *d = workdir(), path[PATH_MAX + 32];
  write_file(d, "n.deck", "material m elastic rho 2000 E 1e9 nu 0.25 plane_stress\nmesh rect b m 0 0 2 1 100 25 pattern cross\n"
             "partition none\nvelocity b set 1 0\ntimestep auto\nthermo 0\nrun 2\n");
  ck_assert_int_eq(run_in(d, 0, 1, "-in n.deck -summary ref.json", NULL), 0);
  snprintf(path, sizeof path, "%s/ref.json", d);
  char *ref = key_lines(path);
  ranks_match(d, 2, "-in n.deck -summary m.json", ref, "partition none");
  ck_assert_msg(count_in(d, "out.txt", "update replicated (the node order does not follow the triangles' ranks: a "
                         "mesh left unpartitioned (below 8192 triangles, or 'partition none')") == 1,
                "the mpi: line does not give 'partition none' as the reason the update is replicated");
  free(ref);
  drop_dir(d);
}
END_TEST

/* The tunnelling warning for speeds a run gains (contact_check_impact_run): a block falling under
 * 5e7 m/s^2 onto a held base reaches 420 m/s at step 19, where rho v^2 = 4.24e8 Pa passes the
 * penalty 3e8 Pa.  ./yfdem warned; on MPI ranks the check was made on one process only, so no
 * rank warned (a sweep of new decks, 2026-11-29).  On 2 and 3 ranks, the update divided and
 * replicated (mass damping), stderr is ./yfdem's, warning and numbers alike, and so are the bits. */
START_TEST(impact_warning_in_run) {
  if (!mpi_ready()) return;
  char *d = workdir(), path[PATH_MAX + 32];
  static const char *const extra[] = {"", "damping mass 10\n"};
  for (int k = 0; k < 2; k++) {
    char deck[1024];
    snprintf(deck, sizeof deck, "material c elastic rho 2400 E 30e9 nu 0.2 plane_stress pen_n 3e8\n"
             "mesh rect base c 0 0 0.2 0.02 40 4\nmesh rect blk c 0.05 0.03 0.1 0.05 10 4\n"
             "region bot box -1 -1 1 1e-9\ngroup bot node region bot\nfix h bot fixed xy\ncontact pair base blk\n"
             "gravity 0 -5e7\n%stimestep auto\nthermo 0\nrun 200\n", extra[k]);
    write_file(d, "fall.deck", deck);
    ck_assert_int_eq(run_in(d, 0, 1, "-in fall.deck -summary ref.json", NULL), 0);
    snprintf(path, sizeof path, "%s/err.txt", d);
    char *eref = yft_slurp(path, 1);
    ck_assert_msg(strstr(eref, "warning: contact (at step 19): an impact can press up to rho v^2 = 4.24e+08 Pa") != NULL,
                  "./yfdem does not warn of the impact it gains:\n%s", eref);
    snprintf(path, sizeof path, "%s/ref.json", d);
    char *ref = key_lines(path);
    for (int ranks = 2; ranks <= 3; ranks++) {
      ranks_match(d, ranks, "-in fall.deck -summary m.json", ref, k ? "falling block, damped" : "falling block");
      ck_assert_msg(count_in(d, "out.txt", k ? "update replicated" : "update divided") == 1,
                    "%d ranks: not the update this case is for (%s)", ranks, k ? "replicated" : "divided");
      snprintf(path, sizeof path, "%s/err.txt", d);
      char *e = yft_slurp(path, 1);
      ck_assert_msg(!strcmp(e, eref), "%d ranks%s: stderr\n%s--- ./yfdem's:\n%s", ranks, k ? ", damped" : "", e, eref);
      free(e);
    }
    free(eref);
    free(ref);
  }
  fprintf(stderr, "check_mpi: the tunnelling warning of a run's gained speed on 2 and 3 ranks as ./yfdem's\n");
  drop_dir(d);
}
END_TEST

/* Scenes that change between runs (found by a sweep of new decks, 2026-11-28):
 *   - a body added after a run moves the first cut (the triangle count changed): a couple whose
 *     lower triangle changed owner must keep its friction memory (it was zeroed: the block slid
 *     on with another friction energy on 2 ranks);
 *   - a body added on 4 ranks whose cut falls inside a cell leaves halo mode (node order no
 *     longer follows the ranks): the couple list must be made whole again (an assertion ended
 *     the run, exit 70);
 *   - a node with no triangle added after a run (a point-loaded node): its force must be summed
 *     anew each step (it added up: fx 3 after 3 steps of a unit load on 2 ranks);
 *   - an error after a record row was begun: the file keeps what ./yfdem's exit keeps (MPI_Abort
 *     dropped rank 0's buffers: an empty file);
 *   - write_y2d: every rank wrote and renamed the one file (a rank then failed, exit 2).
 * Each: ./yfdem's exit code, state_hash, printed results and files, on 2 to 4 ranks. */
static const char *const CHANGE_DECKS[][2] = {
    {"fric_add.deck",
     "material c elastic rho 2340 E 26e9 nu 0.18 plane_stress pen_n 1e11 pen_t 1e10 friction 0.5\n"
     "mesh rect base c 0 0 0.1 0.01 20 2\nmesh rect blk c 0.02 0.01 0.05 0.02 6 2 pattern left\n"
     "region bot box -1 -1 1 1e-9\ngroup bot node region bot\nfix hold bot fixed xy\nvelocity blk set 2 0\n"
     "gravity 0 -9.81e3\ncontact pair base blk\ntimestep auto\nrun 500\nprint \"r1 $(vx_blk) $(friction)\"\n"
     "mesh rect far c 5 5 5.01 5.01 1 1\nrun 500\nprint \"r2 $(vx_blk) $(friction)\"\n"},
    {"halo_off.deck",
     "material c elastic rho 2340 E 26e9 nu 0.18 plane_stress pen_n 1e11\nmesh rect a c 0 0 0.02 0.02 4 4\n"
     "partition metis parts 2\ncontact self a\ntimestep auto\nrun 10\nmesh rect b c 1 1 1.01 1.01 1 6\nrun 10\n"},
    {"stray_node.deck",
     "material m elastic rho 2000 E 1e9 nu 0.25 plane_stress\nmesh rect b m 0 0 1 1 2 2\ntimestep auto\nrun 1\n"
     "node 99 5 5\ngroup s node id 99\nload p point node 99 1 0\nrun 3\nprint \"fx_s $(fx_s)\"\n"},
    {"record_err.deck",
     "material m elastic rho 2000 E 1e9 nu 0.25 plane_stress\nmesh rect b m 0 0 1 1 4 4\nvelocity b set 1 0\n"
     "timestep auto\nrecord r 10 r.csv ke \"sqrt(vx_b-1.5)\"\nrun 20\n"},
    {"write_y2d.deck",
     "material c elastic rho 2340 E 26e9 nu 0.18 plane_stress pen_n 1e11\nmesh rect a c 0 0 0.02 0.02 6 6\n"
     "velocity a set 1 0\ntimestep auto\nwrite_y2d g.y steps 50\nrun 10\n"},
};

/* The lines of dir/out.txt that a deck prints itself ("r1 ...", "fx_s ..."): the results read. */
static char *print_lines(const char *dir) {
  char p[PATH_MAX + 64];
  snprintf(p, sizeof p, "%s/out.txt", dir);
  char *t = yft_slurp(p, 1), *out = calloc(strlen(t) + 1, 1);
  size_t n = 0;
  for (char *line = strtok(t, "\n"); line; line = strtok(NULL, "\n"))
    if (!strncmp(line, "r1 ", 3) || !strncmp(line, "r2 ", 3) || !strncmp(line, "fx_s ", 5))
      n += (size_t)sprintf(out + n, "%s\n", line);
  free(t);
  return out;
}

START_TEST(scene_changes_between_runs) {
  if (!mpi_ready()) return;
  char *d = workdir(), args[256], path[PATH_MAX + 64];
  const int nd = (int)(sizeof CHANGE_DECKS / sizeof CHANGE_DECKS[0]);
  for (int k = 0; k < nd; k++) {
    const char *name = CHANGE_DECKS[k][0];
    write_file(d, name, CHANGE_DECKS[k][1]);
    snprintf(args, sizeof args, "-in %s -summary ref.json", name);
    const int rc0 = run_in(d, 0, 1, args, NULL);
    snprintf(path, sizeof path, "%s/ref.json", d);
    char *ref = key_lines(path), *pref = print_lines(d);
    snprintf(path, sizeof path, "%s/r.csv", d);
    char *cref = yft_slurp(path, 1);
    unlink(path);
    for (int ranks = 2; ranks <= 4; ranks++) {
      snprintf(args, sizeof args, "-in %s -summary m.json", name);
      const int rc = run_in(d, ranks, 1, args, NULL);
      ck_assert_msg(rc == rc0, "%s, %d ranks: exit %d, ./yfdem %d", name, ranks, rc, rc0);
      snprintf(path, sizeof path, "%s/m.json", d);
      char *got = key_lines(path), *pgot = print_lines(d);
      ck_assert_msg(!strcmp(ref, got), "%s, %d ranks differ from ./yfdem:\n%s--- vs ./yfdem:\n%s", name, ranks, got, ref);
      ck_assert_msg(!strcmp(pref, pgot), "%s, %d ranks print:\n%s--- ./yfdem:\n%s", name, ranks, pgot, pref);
      snprintf(path, sizeof path, "%s/r.csv", d);
      char *cgot = yft_slurp(path, 1);
      ck_assert_msg(!strcmp(cref, cgot), "%s, %d ranks: r.csv is '%s', ./yfdem's '%s'", name, ranks, cgot, cref);
      unlink(path);
      free(got); free(pgot); free(cgot);
    }
    fprintf(stderr, "check_mpi: %s (exit %d) on 2-4 ranks: ./yfdem's state_hash%s\n", name, rc0,
            *pref ? ", printed results" : *cref ? ", record file" : "");
    free(ref); free(pref); free(cref);
  }
  drop_dir(d);
}
END_TEST

/* The energies are sums over fixed blocks on the ranks that own them (run.c energies), so the
 * default thermo line, the energy check and a metrics sample gather no node, triangle or joint
 * state (before 2026-11-28 each gathered every node's position, velocity and force, every
 * stress and every joint's owner state: at 1e6 a metrics sample spent 0.03 s gathering).  On
 * PERF.md's problem at 1e4 (29 682 nodes, every triangle fracturing) on 2 ranks, a thermo line
 * and a metrics sample every 10 steps over 200 steps may add their block sums (a few doubles per
 * block of 4096 nodes or 2048 triangles and per 256 joints: 4.7 kB a sample here) but less than
 * one double per node per line: under 8 B x nodes / 10 a step (one gather of the node state
 * alone is 48 B a node).  The metrics log and the summary equal ./yfdem's.  The end of the run's
 * gather, which makes the state whole for what follows, is reported apart from the steps' bytes. */
START_TEST(readers_gather_nothing) {
  if (!mpi_ready()) return;
  char *d = perf_dir(200), path[PATH_MAX + 32];
  write_file(d, "quiet.deck", "read_y2d perf.y\nthermo 0\nrun 200\n");
  write_file(d, "busy.deck", "read_y2d perf.y\nthermo 10\nmetrics log m.csv every 10\nrun 200\n");
  ck_assert_int_eq(run_in(d, 0, 1, "-in busy.deck -summary ref.json", NULL), 0);
  snprintf(path, sizeof path, "%s/ref.json", d);
  char *ref = key_lines(path);
  snprintf(path, sizeof path, "%s/m.csv", d);
  char *mref = yft_slurp(path, 0);
  double bytes[2] = {0, 0}, nodes = 0;
  {
    snprintf(path, sizeof path, "%s/ref.json", d);
    char *t = yft_slurp(path, 1);
    const char *q = strstr(t, "\"nodes\":");
    ck_assert(q != NULL);
    nodes = strtod(q + 8, NULL);
    free(t);
  }
  for (int busy = 0; busy <= 1; busy++) {
    ck_assert_int_eq(run_in(d, 2, 1, busy ? "-in busy.deck -summary m.json" : "-in quiet.deck", NULL), 0);
    bytes[busy] = report_before(d, "bytes sent per step");
    /* the run's end gather (every node's state, stresses, joints: at least 48 B a node) is
     * reported apart, not spread over the steps */
    const double end = report_before(d, "more at the run's end");
    ck_assert_msg(end >= 48.0 * nodes, "the run's end gather: %.4g bytes reported, less than the node state's %.4g",
                  end, 48.0 * nodes);
    if (!busy) continue;
    snprintf(path, sizeof path, "%s/m.json", d);
    char *got = key_lines(path);
    ck_assert_msg(!strcmp(ref, got), "2 ranks differ from ./yfdem:\n%s--- vs ./yfdem:\n%s", got, ref);
    snprintf(path, sizeof path, "%s/m.csv", d);
    char *mgot = yft_slurp(path, 0);
    ck_assert_msg(mref && mgot && !strcmp(mref, mgot), "2 ranks: the metrics log differs from ./yfdem's");
    free(got); free(mgot);
  }
  const double extra = bytes[1] - bytes[0], bound = 8.0 * nodes / 10.0;
  ck_assert_msg(bytes[0] > 0 && extra < bound, "a thermo line and a metrics sample every 10 steps add %.4g bytes a step "
                "(%.4g against %.4g): at least a double per node per line (bound %.4g)", extra, bytes[1], bytes[0], bound);
  fprintf(stderr, "check_mpi: thermo and metrics every 10 steps on 2 ranks add %.4g bytes a step (bound %.4g: no state "
          "gathered), metrics log and summary as ./yfdem\n", extra, bound);
  free(ref); free(mref);
  drop_dir(d);
}
END_TEST

/* How many times needle occurs in the file dir/name. */
static int count_in(const char *dir, const char *name, const char *needle) {
  char p[PATH_MAX + 64];
  snprintf(p, sizeof p, "%s/%s", dir, name);
  char *t = yft_slurp(p, 1);
  int n = 0;
  for (const char *q = t; (q = strstr(q, needle)); q++) n++;
  free(t);
  return n;
}

/* A deck error met by every rank: exit 1, the message once. */
START_TEST(error_all_ranks) {
  if (!mpi_ready()) return;
  char *d = workdir();
  write_file(d, "bad.deck", "material m elastic rho 1 E 1 nu 0.2 plane_stress\nbogus_command 1\n");
  double secs;
  int rc = run_in(d, 3, 1, "-in bad.deck", &secs);
  ck_assert_int_eq(rc, 1);
  ck_assert_int_eq(count_in(d, "err.txt", "bad.deck:2:"), 1); /* one message, not one per rank */
  ck_assert_msg(secs < 60, "took %.1f s", secs);
  drop_dir(d);
}
END_TEST

/* An output whose folder is missing, on 3 ranks: only rank 0 writes files, so only it checks (at
 * the deck line, before the run); the job ends with exit 2 and the message once, within seconds,
 * though the other ranks went on to the run. */
START_TEST(output_error_ranks) {
  if (!mpi_ready()) return;
  char *d = workdir();
  write_file(d, "o.deck", "material m elastic rho 2700 E 30e9 nu 0.25 plane_stress\nmesh rect b m 0 0 1 1 4 4\n"
             "timestep auto\ndump d h5 10 no_dir/k.h5\nrun 20\n");
  double secs;
  int rc = run_in(d, 3, 1, "-in o.deck", &secs);
  ck_assert_msg(rc == 2, "exit %d", rc);
  ck_assert_int_eq(count_in(d, "err.txt", "o.deck:4: error: dump d: cannot write 'no_dir/k_000000.h5'"), 1);
  ck_assert_msg(secs < 60, "took %.1f s", secs);
  drop_dir(d);
}
END_TEST

/* A numerical failure on rank 1 only (injected at its 5th element stage): every rank ends,
 * mpirun exits 3 (numerical failure), the message once, within seconds. */
START_TEST(error_one_rank) {
  if (!mpi_ready()) return;
  char *d = perf_dir(100);
  write_file(d, "p.deck", "read_y2d perf.y\nrun 100\n");
  double secs;
  setenv("YFDEM_MPI_FAIL_RANK", "1", 1);
  int rc = run_in(d, 3, 1, "-in p.deck", &secs);
  unsetenv("YFDEM_MPI_FAIL_RANK");
  ck_assert_int_eq(rc, 3);
  ck_assert_int_eq(count_in(d, "err.txt", "injected failure"), 1);
  ck_assert_msg(secs < 60, "took %.1f s", secs);
  fprintf(stderr, "check_mpi: a failure on rank 1 of 3 ended every rank with exit 3 in %.1f s\n", secs);
  drop_dir(d);
}
END_TEST

/* A full disk under parallel h5 frames (3 ranks; a tmpfs of a few sizes in a mount namespace of
 * its own): exit 2 with the cause, no NAME.tmp left, and every frame file on disk opens and
 * reads.  With OpenMPI's default MPI-IO (ompio) the collective write printed its own error and
 * returned success, so rank 0 renamed an incomplete frame into the series and failed later on
 * the index (a sweep of new decks, 2026-11-28); par_init now asks for ROMIO, which returns the
 * error. */
START_TEST(full_disk_parallel_frames) {
  if (!mpi_ready()) return;
  char *d = workdir(), cmd[4 * PATH_MAX + 1024], path[PATH_MAX + 64];
  write_file(d, "f.deck", "material m elastic rho 2000 E 1e9 nu 0.25 plane_stress\nmesh rect plate m 0 0 1.0 0.2 20 4\n"
             "partition metis parts 4\njointprop cj ft 1e5 fs 1e5 gf 1 pen 1e10 law linear\nfracture plate cj\n"
             "region left box -1 -1 1e-9 1\ngroup left node region left\nfix clamp left fixed xy\n"
             "velocity plate set 0 -5\ntimestep auto\ndump d h5 20 fr.h5\nrun 300\n");
  snprintf(cmd, sizeof cmd, "unshare -rm sh -c 'mkdir -p %s/t0 && mount -t tmpfs -o size=64k tmpfs %s/t0' 2>/dev/null", d, d);
  if (system(cmd) != 0) {
    fprintf(stderr, "check_mpi: full_disk_parallel_frames: no mount namespace here: not run\n");
    drop_dir(d);
    return;
  }
  static const int kb[] = {150, 200, 260, 400};
  for (int i = 0; i < 4; i++) {
    snprintf(cmd, sizeof cmd,
             "cd %s && mkdir -p o%d && unshare -rm sh -c 'mkdir -p t && mount -t tmpfs -o size=%dk tmpfs t && cd t && "
             "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMP_NUM_THREADS=1 timeout 120 mpirun -q "
             "--oversubscribe -np 3 %s -threads 1 -in ../f.deck -summary ../o%d/s.json >/dev/null 2>../o%d/err.txt; "
             "echo $? > ../o%d/code; cp -a . ../o%d/'",
             d, kb[i], kb[i], MPIBIN, kb[i], kb[i], kb[i], kb[i]);
    ck_assert_int_eq(system(cmd), 0);
    snprintf(path, sizeof path, "%s/o%d/code", d, kb[i]);
    char *c = yft_slurp(path, 1);
    int code = atoi(c);
    free(c);
    snprintf(path, sizeof path, "%s/o%d/err.txt", d, kb[i]);
    char *e = yft_slurp(path, 1);
    fprintf(stderr, "check_mpi: full disk of %d KB, parallel frames on 3 ranks: exit %d\n", kb[i], code);
    ck_assert_msg(code == 2, "%d KB: exit %d: %s", kb[i], code, e);
    ck_assert_msg(strstr(e, "MPI_ERR_IO") || strstr(e, "No space left"), "%d KB: %s", kb[i], e);
    /* the summary says io_error; when the disk filled in one rank's part only, that rank ends
     * the job alone (a collective after a failed one could wait forever): its message, no summary */
    snprintf(path, sizeof path, "%s/o%d/s.json", d, kb[i]);
    char *j = yft_slurp(path, 1);
    if (j[0]) ck_assert_msg(strstr(j, "\"status\": \"io_error\""), "%d KB: summary: %s", kb[i], j);
    else ck_assert_msg(strstr(e, "rank ") == e, "%d KB: no summary, and not one rank's failure: %s", kb[i], e);
    free(j);
    free(e);
    snprintf(cmd, sizeof cmd, "ls %s/o%d | grep -q '\\.tmp$'", d, kb[i]);
    ck_assert_msg(system(cmd) != 0, "%d KB: a NAME.tmp is left", kb[i]);
    /* every frame file on disk (listed, or renamed just before the index write failed) is whole */
    snprintf(path, sizeof path, "%s/o%d/fr_0*.h5", d, kb[i]);
    glob_t g;
    int nf = glob(path, 0, NULL, &g) == 0 ? (int)g.gl_pathc : 0;
    for (int k = 0; k < nf; k++) {
      const char *name = g.gl_pathv[k];
      hid_t f = H5Fopen(name, H5F_ACC_RDONLY, H5P_DEFAULT);
      ck_assert_msg(f >= 0, "%d KB: %s does not open", kb[i], name);
      hid_t ds = H5Dopen2(f, "/x", H5P_DEFAULT);
      ck_assert_msg(ds >= 0, "%d KB: %s has no /x", kb[i], name);
      static double buf[2 * 2000];
      hid_t sp = H5Dget_space(ds);
      hsize_t dims[2];
      H5Sget_simple_extent_dims(sp, dims, NULL);
      ck_assert_msg(dims[0] <= 2000 && H5Dread(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, buf) >= 0,
                    "%d KB: %s: /x does not read", kb[i], name);
      H5Sclose(sp);
      H5Dclose(ds);
      H5Fclose(f);
    }
    if (nf) globfree(&g);
    ck_assert_msg(nf >= 1, "%d KB: no frame at all", kb[i]);
  }
  drop_dir(d);
}
END_TEST

/* mpirun on 2 ranks over deck NAME in dir d (summary s.json), with Ctrl-C to mpirun itself 3 s
 * after the run's thermo header is out (not before: on a loaded machine the ranks may take
 * seconds to reach the run, and an interrupt before any run leaves nothing to restart); T = 10 s
 * (odls_base_sigkill_timeout) for the ranks to write the restart.  Returns system()'s status,
 * after asserting that mpirun ended before its timeout. */
static int ctrl_c_mpirun(const char *d, const char *name) {
  char cmd[4 * PATH_MAX];
  snprintf(cmd, sizeof cmd, "cd %s && OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMP_NUM_THREADS=1 "
           "timeout 120 mpirun -q --oversubscribe --mca odls_base_sigkill_timeout 10 -np 2 %s -threads 1 -in %s "
           "-summary s.json >out.txt 2>err.txt & "
           "pid=$!; for i in $(seq 120); do grep -q Step out.txt 2>/dev/null && break; sleep 0.5; done; sleep 3; "
           "kill -INT $(pgrep -P $pid -x mpirun); wait $pid", d, MPIBIN, name);
  int st = system(cmd);
  ck_assert_msg(WIFEXITED(st) && WEXITSTATUS(st) != 124, "mpirun did not end (timeout)");
  return st;
}

/* The interrupt's restart and the summary "interrupted" in dir d (err.txt in the message). */
static void assert_interrupt_kept(const char *d) {
  char path[PATH_MAX + 32];
  snprintf(path, sizeof path, "%s/err.txt", d);
  char *e = yft_slurp(path, 1);
  snprintf(path, sizeof path, "%s/yfdem_interrupt.restart", d);
  ck_assert_msg(yft_exists(path), "no restart written at the interrupt: %s", e);
  free(e);
  snprintf(path, sizeof path, "%s/s.json", d);
  char *j = yft_slurp(path, 1);
  ck_assert_msg(strstr(j, "\"status\": \"interrupted\""), "summary: %s", j);
  free(j);
}

/* Ctrl-C to mpirun itself while rank 0 prints a thermo line every 10 steps.  OpenMPI 4.1's mpirun,
 * on SIGINT, stops reading the ranks' output and sends them SIGCONT at once, SIGTERM after
 * odls_base_sigkill_timeout seconds (T, 1 s by default) and SIGKILL after 2T (strace, 2026-11-28):
 * the ranks have T seconds to write the restart; T = 10 here, for the sanitizer build.  Rank 0
 * used to block in a write to its full output pipe, never reached the step's interrupt check,
 * and was killed with no restart and no summary (8 of 8 tries, a sweep of new decks); now the
 * signal makes the ranks' stdout and stderr non-blocking, and the run stops with a restart and
 * the summary "interrupted".  The SIGINT goes to mpirun itself, as a terminal's Ctrl-C does:
 * `timeout` passes a signal on to its child and again to its process group, and mpirun, when
 * it sees the two apart, takes the second for a second Ctrl-C and kills the job at once (CI,
 * 2026-11-28: no restart). */
START_TEST(interrupt_mpirun_chatty) {
  if (!mpi_ready()) return;
  char *d = workdir();
  write_file(d, "chatty.deck", "material m elastic rho 2000 E 1e9 nu 0.25 plane_stress\nmesh rect plate m 0 0 1.0 0.2 20 4\n"
             "region left box -1 -1 1e-9 1\ngroup left node region left\nfix clamp left fixed xy\ngravity 0 -9.81\n"
             "timestep auto\nthermo 10\nrun 100000000\n");
  int st = ctrl_c_mpirun(d, "chatty.deck");
  fprintf(stderr, "check_mpi: Ctrl-C to mpirun with a thermo line every 10 steps: mpirun exit %d\n",
          WIFEXITED(st) ? WEXITSTATUS(st) : -1);
  assert_interrupt_kept(d);
  drop_dir(d);
}
END_TEST

/* `mpirun ... | head` on a METIS-partitioned mesh (a sweep, 2026-11-29): when head ends, mpirun
 * stops reading the ranks' output and sends them SIGTERM; rank 0, blocked writing a thermo line,
 * got EINTR and ended the job with "cannot write to standard output: Interrupted system call"
 * (MPI_Abort, exit 2) and no restart, 3 of 3 tries.  METIS (GKlib) had put our SIGTERM handler
 * back one-shot and without SA_RESTART after the partition (strace); below 8192 triangles with no
 * `partition` line, METIS never ran and the same pipe gave the interrupt's restart.  The ranks now
 * stop at one step with the restart and the summary "interrupted", as on Ctrl-C.  (mpirun itself
 * may then crash in its SIGPIPE abort, exit 139, either way: OpenMPI 4.1's, README.) */
START_TEST(head_after_partition) {
  if (!mpi_ready()) return;
  char *d = workdir(), cmd[4 * PATH_MAX];
  write_file(d, "head.deck", "material m elastic rho 2000 E 1e9 nu 0.25 plane_stress\nmesh rect plate m 0 0 1.0 0.2 40 8\n"
             "partition metis parts 2\nregion left box -1 -1 1e-9 1\ngroup left node region left\nfix clamp left fixed xy\n"
             "gravity 0 -9.81\ntimestep auto\nthermo 1\nrun 100000000\n");
  /* (the subshell keeps the shell's "Segmentation fault" of mpirun off the test's output) */
  snprintf(cmd, sizeof cmd, "cd %s && (OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMP_NUM_THREADS=1 "
           "timeout 120 mpirun -q --oversubscribe --mca odls_base_sigkill_timeout 5 -np 2 %s -threads 1 -in head.deck "
           "-summary s.json 2>err.txt | head -n 3 >/dev/null) 2>/dev/null", d, MPIBIN);
  if (system(cmd)) {}
  ck_assert_int_eq(count_in(d, "err.txt", "cannot write to standard output"), 0);
  assert_interrupt_kept(d);
  ck_assert_int_eq(count_in(d, "err.txt", "restart written to"), 1);
  drop_dir(d);
}
END_TEST

/* A deck through a pipe or a device ('-in /dev/stdin < deck', a FIFO) on 2 ranks: mpirun gives
 * stdin to rank 0 only, so each rank read other bytes (rank 1 an empty deck from /dev/null) and
 * the job hung with no output.  Rank 0 now reads such a deck and sends it to every rank, as a deck
 * on stdin: the run ends with the serial run's bits, its loop and its include done. */
START_TEST(deck_through_a_pipe_on_ranks) {
  if (!mpi_ready()) return;
  char *d = workdir();
  write_file(d, "main.deck", "material m elastic rho 2000 E 1e9 nu 0.25 plane_stress\nmesh rect b m 0 0 1 1 4 4\n"
                             "velocity b set 1 0\ntimestep auto\nvariable i loop 3\nlabel l\nrun 10\n"
                             "print \"i=${i} step=$(step)\"\nnext i\njump SELF l\ninclude part.deck\n");
  write_file(d, "part.deck", "run 5\nprint \"part ran\"\n");
  ck_assert_int_eq(run_in(d, 0, 1, "-in main.deck -summary s0.json", NULL), 0);
  int rc = run_in(d, 2, 1, "-in /dev/stdin -summary s1.json < main.deck", NULL);
  ck_assert_msg(rc == 0, "mpirun exit %d (124: it hung)", rc);
  ck_assert_int_eq(count_in(d, "out.txt", "i=3 step=30"), 1);
  ck_assert_int_eq(count_in(d, "out.txt", "part ran"), 1);
  char path[PATH_MAX + 64];
  snprintf(path, sizeof path, "%s/s0.json", d);
  char *ref = key_lines(path);
  snprintf(path, sizeof path, "%s/s1.json", d);
  char *got = key_lines(path);
  ck_assert_str_eq(got, ref);
  free(ref);
  free(got);
  drop_dir(d);
}
END_TEST

/* Ctrl-C to mpirun where a deck spends its time between runs, and while a deck on stdin is still
 * arriving (a sweep of new decks, 2026-11-28):
 * - a loop of 100-step runs with a print after each: rank 0 waits on its output pipe, which
 *   mpirun has stopped reading, so the interrupt was met before a deck line, outside any run,
 *   and the job ended with no restart (every try); the state the last run left is now written;
 * - a deck piped in slowly: mpirun closes rank 0's stdin at the Ctrl-C, which read as the deck's
 *   end, and the part read so far ran to "ok"; now nothing runs ("interrupted while reading the
 *   deck", as ./yfdem says). */
START_TEST(interrupt_mpirun_outside_runs) {
  if (!mpi_ready()) return;
  char *d = workdir(), cmd[4 * PATH_MAX], path[PATH_MAX + 32];
  write_file(d, "loop.deck", "material m elastic rho 2000 E 1e9 nu 0.25 plane_stress\nmesh rect b m 0 0 1 1 20 20\n"
             "velocity b set 1 0\ntimestep auto\nvariable i loop 100000\nlabel top\nrun 100\nprint \"i=${i} ke=$(ke)\"\n"
             "next i\njump SELF top\n");
  ctrl_c_mpirun(d, "loop.deck");
  assert_interrupt_kept(d);
  char *j;
  write_file(d, "part1.deck", "material m elastic rho 2000 E 1e9 nu 0.25 plane_stress\nmesh rect b m 0 0 1 1 4 4\n"
             "timestep auto\nprint \"part 1 ran\"\nrun 10\n");
  write_file(d, "part2.deck", "print \"part 2 ran\"\nrun 10\n");
  /* (the pipeline's mpirun is a child of this shell's subshell: find it by the working directory) */
  /* the Ctrl-C goes once a rank of this test runs (a loaded machine may take seconds to start
   * them: a Ctrl-C before, which mpirun takes for its own, failed this test once), and long
   * before the deck's second half comes */
  snprintf(cmd, sizeof cmd, "cd %s && rm -f s.json && ( (cat part1.deck; sleep 12; cat part2.deck) | OMPI_ALLOW_RUN_AS_ROOT=1 "
           "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMP_NUM_THREADS=1 timeout 120 mpirun -q --oversubscribe -np 2 %s -threads 1 "
           "-summary s.json >out2.txt 2>err2.txt & for i in $(seq 120); do r=; for p in $(pgrep -x \"$(basename %s | cut "
           "-c1-15)\"); do [ \"$(readlink /proc/$p/cwd)\" = \"$(pwd -P)\" ] && r=$p; done; [ -n \"$r\" ] && break; "
           "sleep 0.25; done; sleep 2; for p in $(pgrep -x mpirun); do "
           "[ \"$(readlink /proc/$p/cwd)\" = \"$(pwd -P)\" ] && kill -INT $p; done; wait )", d, MPIBIN, MPIBIN);
  ck_assert_int_eq(system(cmd), 0);
  ck_assert_int_eq(count_in(d, "out2.txt", "part 1 ran"), 0);
  snprintf(path, sizeof path, "%s/s.json", d);
  j = yft_slurp(path, 1);
  ck_assert_msg(strstr(j, "\"status\": \"interrupted\""), "summary after Ctrl-C while the deck arrived: %s", j);
  free(j);
  drop_dir(d);
}
END_TEST

/* The command line is every rank's: an error in it, -h or -version, came once per rank. */
START_TEST(command_line_once) {
  if (!mpi_ready()) return;
  char *d = workdir(), cmd[4 * PATH_MAX];
  snprintf(cmd, sizeof cmd, "cd %s && OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 timeout 60 mpirun -q "
           "--oversubscribe -np 3 %s -threads 0 >out.txt 2>err.txt; OMPI_ALLOW_RUN_AS_ROOT=1 "
           "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 timeout 60 mpirun -q --oversubscribe -np 3 %s -version >>out.txt 2>>err.txt",
           d, MPIBIN, MPIBIN);
  if (system(cmd)) {}
  ck_assert_int_eq(count_in(d, "err.txt", "-threads '0': expected a whole number"), 1);
  ck_assert_int_eq(count_in(d, "out.txt", "yfdem "), 1);
  drop_dir(d);
}
END_TEST

/* SIGTERM to one rank only (a signal reaching the ranks at different steps): the flag is
 * OR-reduced every step, so every rank stops at the same step, rank 0 writes the restart and says
 * so once, and mpirun exits 4; the restart continued on 3 ranks gives the bits of an
 * uninterrupted ./yfdem run to the same step.  Without the reduction the signalled rank leaves
 * alone and the others wait for it (the 300 s timeout, exit 124).  The signalled rank is one of
 * this test's own (by the binary's name and the working directory: other runs may share the machine), signalled
 * 6 s after it appears (a loaded machine may take seconds to start the ranks). */
START_TEST(interrupt_all_ranks) {
  if (!mpi_ready()) return;
  char *d = perf_dir(100000), cmd[4 * PATH_MAX], path[PATH_MAX + 32];
  write_file(d, "long.deck", "read_y2d perf.y\nrun 100000\n");
  snprintf(cmd, sizeof cmd, "cd %s && OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMP_WAIT_POLICY=passive "
           "OMP_NUM_THREADS=1 timeout 300 mpirun -q --oversubscribe --mca mpi_yield_when_idle 1 -np 2 %s -in long.deck "
           ">out.txt 2>err.txt & pid=$!; q=; for i in $(seq 240); do for p in $(pgrep -x \"$(basename %s | cut -c1-15)\"); do "
           "[ \"$(readlink /proc/$p/cwd)\" = \"%s\" ] && q=$p; done; [ -n \"$q\" ] && break; sleep 0.5; done; "
           "sleep 6; kill -TERM $q; wait $pid", d, MPIBIN, MPIBIN, d);
  int st = system(cmd);
  ck_assert_msg(WIFEXITED(st) && WEXITSTATUS(st) == YF_EXIT_INTERRUPT, "exit %d, not 130 (interrupted)", WIFEXITED(st) ? WEXITSTATUS(st) : -1);
  snprintf(path, sizeof path, "%s/err.txt", d);
  char *err = yft_slurp(path, 1);
  long k = -1;
  const char *at = strstr(err, "interrupted at step ");
  ck_assert_msg(at && sscanf(at, "interrupted at step %ld", &k) == 1 && k > 0, "no interrupt message: %s", err);
  ck_assert_int_eq(count_in(d, "err.txt", "interrupted at step"), 1);
  free(err);
  char deck[256];
  snprintf(deck, sizeof deck, "read_y2d perf.y\nread_restart yfdem_interrupt.restart\nrun %ld upto\n", k + 10);
  write_file(d, "cont.deck", deck);
  snprintf(deck, sizeof deck, "read_y2d perf.y\nrun %ld\n", k + 10);
  write_file(d, "full.deck", deck);
  ck_assert_int_eq(run_in(d, 3, 1, "-in cont.deck -summary cont.json", NULL), 0);
  ck_assert_int_eq(run_in(d, 0, 1, "-in full.deck -summary full.json", NULL), 0);
  char what[96];
  snprintf(what, sizeof what, "interrupt at step %ld, continued on 3 ranks", k);
  fprintf(stderr, "check_mpi: SIGTERM to one rank stopped both at step %ld; continued on 3 ranks to step %ld: %s as ./yfdem\n",
          k, k + 10, same_hash_as_full(d, what));
  drop_dir(d);
}
END_TEST

/* A signal to one rank outside a run stops every rank: in a deck's endless label/jump loop, and
 * while rank 0 still reads a deck from a pipe held open.  The signalled rank stopped alone and the
 * others waited in their next collective, so the job never ended (killed by timeout, exit 124). */
START_TEST(interrupt_outside_run) {
  if (!mpi_ready()) return;
  char *d = workdir(), cmd[4 * PATH_MAX];
  write_file(d, "loop.deck", "material m elastic rho 1000 E 1e9 nu 0.25 plane_stress\nmesh rect b m 0 0 1 0.1 10 2\n"
                             "variable i equal 0\nlabel L\nvariable j equal $(v_i+1)\njump SELF L\n");
  static const char *const how[] = {"-in loop.deck", "< <(cat loop.deck; sleep 100)"};
  for (int k = 0; k < 2; k++) {
    /* the last rank to start (rank 2, as mpirun starts them in order): not the one reading stdin */
    snprintf(cmd, sizeof cmd, "cd %s || exit 9; OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMP_WAIT_POLICY=passive "
             "OMP_NUM_THREADS=1 timeout 90 mpirun -q --oversubscribe -np 3 %s -log none %s >out.txt 2>err.txt & pid=$!; "
             "q=; for i in $(seq 120); do n=0; for p in $(pgrep -x \"$(basename %s | cut -c1-15)\" | sort -n); do "
             "[ \"$(readlink /proc/$p/cwd)\" = \"%s\" ] && q=$p && n=$((n+1)); done; [ $n -ge 3 ] && break; sleep 0.5; done; "
             "sleep 3; t0=$(date +%%s); kill -TERM $q; wait $pid; rc=$?; echo $(( $(date +%%s) - t0 )) > secs.txt; exit $rc",
             d, MPIBIN, how[k], MPIBIN, d);
    char *bash = malloc(strlen(cmd) + 64);
    sprintf(bash, "bash -c '%s'", cmd); /* < <(...) is bash's (cmd holds no single quote) */
    int st = system(bash);
    free(bash);
    char path[PATH_MAX + 32];
    snprintf(path, sizeof path, "%s/secs.txt", d);
    char *secs = yft_slurp(path, 1);
    ck_assert_msg(WIFEXITED(st) && WEXITSTATUS(st) == YF_EXIT_INTERRUPT, "%s: exit %d (124: the job never ended), %s s",
                  how[k], WIFEXITED(st) ? WEXITSTATUS(st) : -1, secs);
    ck_assert_msg(secs[0] && atoi(secs) <= 30, "%s: '%s' s after the signal", how[k], secs);
    fprintf(stderr, "check_mpi: SIGTERM to one of 3 ranks outside a run (%s): every rank ended, exit 130, %d s\n",
            k ? "deck on a pipe" : "deck loop", atoi(secs));
    free(secs);
  }
  drop_dir(d);
}
END_TEST

Suite *mpi_suite(void) {
  Suite *s = suite_create("mpi");
  /* decks that reach the ranks through a pipe (CK_RUN_CASE=pipe runs it alone) */
  TCase *tp = tcase_create("pipe");
  tcase_set_timeout(tp, 900);
  tcase_add_test(tp, deck_through_a_pipe_on_ranks);
  suite_add_tcase(s, tp);
  TCase *tr = tcase_create("ranges"); /* what a rank sizes to its range, made again for a new one */
  tcase_set_timeout(tr, 900);
  tcase_add_test(tr, range_buffers_follow_recut);
  suite_add_tcase(s, tr);
  /* a run's output piped into head (CK_RUN_CASE=head) */
  TCase *th = tcase_create("head");
  tcase_set_timeout(th, 300);
  tcase_add_test(th, head_after_partition);
  suite_add_tcase(s, th);
  TCase *t = tcase_create("mpi");
  tcase_set_timeout(t, 900);
  tcase_add_test(t, matrix_column);
  tcase_add_test(t, matrix_beam);
  tcase_add_loop_test(t, matrix_y2d, 0, 4);
  tcase_add_test(t, matrix_perf_1e4);
  tcase_add_test(t, divided_update);
  tcase_add_test(t, frames_parallel_h5);
  tcase_add_test(t, outputs_equal);
  tcase_add_test(t, bodies_cross_ranks);
  tcase_add_test(t, search_by_boxes);
  tcase_add_test(t, search_sends_near_only);
  tcase_add_test(t, restart_2_to_3);
  tcase_add_test(t, rebalance_contact_work);
  tcase_add_test(t, rebalance_unpartitioned);
  tcase_add_test(t, report_share_of_wall);
  tcase_add_test(t, replicated_reason);
  tcase_add_test(t, impact_warning_in_run);
  tcase_add_test(t, scene_changes_between_runs);
  tcase_add_test(t, readers_gather_nothing);
  tcase_add_test(t, error_all_ranks);
  tcase_add_test(t, error_one_rank);
  tcase_add_test(t, output_error_ranks);
  tcase_add_test(t, interrupt_all_ranks);
  tcase_add_test(t, interrupt_mpirun_chatty);
  tcase_add_test(t, interrupt_mpirun_outside_runs);
  tcase_add_test(t, command_line_once);
  tcase_add_test(t, interrupt_outside_run);
  tcase_add_test(t, full_disk_parallel_frames);
  suite_add_tcase(s, t);
  return s;
}
