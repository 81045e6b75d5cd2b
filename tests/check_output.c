/* check_output.c: dumps (HDF5 + XDMF, CSV), the summary JSON and the state hash.
 *
 * Facts checked: arrays read back from the .h5 are bit-identical to the model's at the frame's
 * step, frames land exactly every N steps plus at the run start, the .xmf lists exactly the
 * frames written and refers to them by a relative path, a writer killed by SIGKILL in the middle
 * of its stream leaves every frame its .xmf lists readable and exact, the summary has the
 * standard keys in order and never contains NaN, and the state hash sees a single flipped bit.
 */
#include <check.h>
#include <errno.h>
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>
#include <hdf5.h>
#include "output.h"
#include "summary.h"
#include "model.h"
#include "sim.h"
#include "err.h"
#include "yftest.h"

/* ---------------------------------------------------------------- fixtures */

static char tmpdir[64];

static void mk_tmpdir(void) {
  snprintf(tmpdir, sizeof tmpdir, "/tmp/yf_check_output_XXXXXX");
  ck_assert_ptr_nonnull(mkdtemp(tmpdir));
}

static void rm_tmpdir(void) {
  char cmd[128];
  snprintf(cmd, sizeof cmd, "rm -rf '%s'", tmpdir);
  if (system(cmd) != 0) fprintf(stderr, "could not remove %s\n", tmpdir);
}

/* A strip of nx x 1 cells, 2 triangles each: (nx+1)*2 nodes, 2 nx triangles. */
static void build(YfSim *s, int nx) {
  memset(s, 0, sizeof *s);
  model_init(&s->model);
  YfModel *m = &s->model;
  for (int i = 0; i <= nx; i++) {
    model_add_node(m, 0.1 * i, 0.0, 100 + 2 * i, 0);
    model_add_node(m, 0.1 * i, 0.1, 101 + 2 * i, 0);
  }
  for (int i = 0; i < nx; i++) {
    int a = 2 * i, b = 2 * i + 2, c = 2 * i + 3, d = 2 * i + 1;
    model_add_tri(m, a, b, c, i % 2, 10 * i, 0);
    model_add_tri(m, a, c, d, (i + 1) % 2, 10 * i + 5, 1);
  }
}

/* A state that is an exact function of the step (non-round values, both signs). */
static void set_state(YfSim *s, long step) {
  YfModel *m = &s->model;
  for (int i = 0; i < m->node.n; i++) {
    m->node.x[i] = m->node.x0[i] + 1e-3 * (double)step / 3.0 * (i + 1);
    m->node.y[i] = m->node.y0[i] - 1e-4 * (double)step / 7.0;
    m->node.vx[i] = 0.1 * step + i / 3.0;
    m->node.vy[i] = -0.2 * step - i / 9.0;
    m->node.fx[i] = 1e3 * step / 11.0 + i;
    m->node.fy[i] = -1e3 * i / 13.0;
  }
  for (int e = 0; e < m->tri.n; e++) {
    m->tri.s[3 * e] = 1e6 * (step + 1) / 3.0 + e;
    m->tri.s[3 * e + 1] = -2e6 * e / 7.0;
    m->tri.s[3 * e + 2] = 5e5 * step / 9.0 - e;
  }
  s->step = step;
  s->time = step * 1.25e-6;
}

static void free_sim(YfSim *s) {
  output_free(s);
  model_free(&s->model);
}

static int file_exists(const char *p) {
  struct stat st;
  return stat(p, &st) == 0;
}

static char *slurp(const char *path) {
  FILE *f = fopen(path, "rb");
  ck_assert_msg(f != NULL, "cannot open %s", path);
  fseek(f, 0, SEEK_END);
  long n = ftell(f);
  fseek(f, 0, SEEK_SET);
  char *b = malloc((size_t)n + 1);
  ck_assert_int_eq(fread(b, 1, (size_t)n, f), (size_t)n);
  b[n] = 0;
  fclose(f);
  return b;
}

static int count_str(const char *hay, const char *needle) {
  int k = 0;
  for (const char *p = strstr(hay, needle); p; p = strstr(p + 1, needle)) k++;
  return k;
}

/* Read a whole dataset of doubles/ints into a malloc'd buffer; returns element count or -1. */
static long h5_read(hid_t f, const char *path, hid_t type, void **out) {
  hid_t ds = H5Dopen2(f, path, H5P_DEFAULT);
  if (ds < 0) return -1;
  hid_t sp = H5Dget_space(ds);
  hssize_t n = H5Sget_simple_extent_npoints(sp);
  *out = malloc((size_t)(n > 0 ? n : 1) * 8);
  herr_t st = H5Dread(ds, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, *out);
  H5Sclose(sp);
  H5Dclose(ds);
  return st < 0 ? -1 : (long)n;
}

/* Compare frame k of file f with the state set_state(step) of a model built like s.
 * Returns 0 when every array is bit-identical. */
static int check_frame(hid_t f, YfSim *s, long k, long step) {
  set_state(s, step);
  const YfModel *m = &s->model;
  int n = m->node.n, nt = m->tri.n, bad = 0;
  char p[128];
  void *buf;
  double *b;
  snprintf(p, sizeof p, "/frames/%06ld/time", k);
  if (h5_read(f, p, H5T_NATIVE_DOUBLE, &buf) != 1) return 1;
  bad |= ((double *)buf)[0] != s->time;
  free(buf);
  snprintf(p, sizeof p, "/frames/%06ld/step", k);
  if (h5_read(f, p, H5T_NATIVE_LLONG, &buf) != 1) return 1;
  bad |= ((long long *)buf)[0] != step;
  free(buf);
  static const char *const vec[] = {"x", "u", "v", "f"};
  for (int q = 0; q < 4; q++) {
    snprintf(p, sizeof p, "/frames/%06ld/%s", k, vec[q]);
    if (h5_read(f, p, H5T_NATIVE_DOUBLE, &buf) != 2L * n) return 1;
    b = buf;
    for (int i = 0; i < n; i++) {
      double ex[4][2] = {{m->node.x[i], m->node.y[i]},
                         {m->node.x[i] - m->node.x0[i], m->node.y[i] - m->node.y0[i]},
                         {m->node.vx[i], m->node.vy[i]},
                         {m->node.fx[i], m->node.fy[i]}};
      bad |= memcmp(&b[2 * i], ex[q], sizeof ex[q]) != 0;
    }
    free(buf);
  }
  snprintf(p, sizeof p, "/frames/%06ld/stress", k);
  if (h5_read(f, p, H5T_NATIVE_DOUBLE, &buf) != 3L * nt) return 1;
  bad |= memcmp(buf, m->tri.s, sizeof(double) * 3 * (size_t)nt) != 0;
  free(buf);
  return bad;
}

/* ---------------------------------------------------------------- h5 + xmf */

/* Period 2 over 4 steps: frames at steps 0 (run start), 2, 4; arrays exact; derived stresses
 * match the closed forms; the .xmf lists the 3 frames with relative HDF paths. */
static void roundtrip(int compress) {
  mk_tmpdir();
  YfSim s;
  build(&s, 6);
  char h5[128], xmf[128];
  snprintf(h5, sizeof h5, "%s/out.h5", tmpdir);
  snprintf(xmf, sizeof xmf, "%s/out.xmf", tmpdir);
  ck_assert_int_eq(output_add_dump(&s, "d1", YF_DUMP_H5, 2, h5, YF_FIELD_ALL, compress), 0);
  ck_assert_msg(!file_exists(h5), "file must not exist before the first frame");
  set_state(&s, 0);
  output_run_begin(&s);
  for (long st = 1; st <= 4; st++) {
    set_state(&s, st);
    output_step(&s);
    ck_assert_int_eq(output_frames(&s, "d1"), 1 + st / 2);
  }
  output_run_end(&s);
  output_close_all(&s);

  hid_t f = H5Fopen(h5, H5F_ACC_RDONLY, H5P_DEFAULT);
  ck_assert_int_ge(f, 0);
  for (long k = 0; k < 3; k++) ck_assert_msg(check_frame(f, &s, k, 2 * k) == 0, "frame %ld differs", k);
  ck_assert_int_lt(H5Lexists(f, "/frames/000003", H5P_DEFAULT), 1);
  void *buf;
  ck_assert_int_eq(h5_read(f, "/mesh/triangles", H5T_NATIVE_INT, &buf), 3L * s.model.tri.n);
  ck_assert_int_eq(memcmp(buf, s.model.tri.v, sizeof(int) * 3 * (size_t)s.model.tri.n), 0);
  free(buf);
  ck_assert_int_eq(h5_read(f, "/mesh/material", H5T_NATIVE_INT, &buf), s.model.tri.n);
  ck_assert_int_eq(memcmp(buf, s.model.tri.mat, sizeof(int) * (size_t)s.model.tri.n), 0);
  free(buf);
  /* von Mises and sigma1 of frame 1 (step 2) against their closed forms */
  set_state(&s, 2);
  double *vm, *s1;
  ck_assert_int_eq(h5_read(f, "/frames/000001/vonmises", H5T_NATIVE_DOUBLE, (void **)&vm), s.model.tri.n);
  ck_assert_int_eq(h5_read(f, "/frames/000001/sigma1", H5T_NATIVE_DOUBLE, (void **)&s1), s.model.tri.n);
  for (int e = 0; e < s.model.tri.n; e++) {
    double a = s.model.tri.s[3 * e], c = s.model.tri.s[3 * e + 1], t = s.model.tri.s[3 * e + 2];
    /* principal stresses from the eigenvalues of the 2x2 tensor; von Mises from them */
    double p1 = 0.5 * (a + c) + hypot(0.5 * (a - c), t), p2 = 0.5 * (a + c) - hypot(0.5 * (a - c), t);
    double vmx = sqrt(p1 * p1 - p1 * p2 + p2 * p2);
    double scale = fabs(a) + fabs(c) + fabs(t);
    ck_assert_double_eq_tol(s1[e], p1, 1e-14 * scale);
    ck_assert_double_eq_tol(vm[e], vmx, 1e-14 * scale);
  }
  free(vm);
  free(s1);
  H5Fclose(f);

  char *x = slurp(xmf);
  ck_assert_ptr_nonnull(strstr(x, "<Xdmf Version=\"3.0\""));
  ck_assert_ptr_nonnull(strstr(x, "CollectionType=\"Temporal\""));
  ck_assert_int_eq(count_str(x, "GridType=\"Uniform\""), 3);
  ck_assert_int_eq(count_str(x, "TopologyType=\"Triangle\""), 3);
  ck_assert_int_eq(count_str(x, "GeometryType=\"XY\""), 3);
  /* relative references only: every HDF item starts with the bare file name */
  ck_assert_int_eq(count_str(x, "Format=\"HDF\">"), count_str(x, "Format=\"HDF\">out.h5:/"));
  ck_assert_ptr_null(strstr(x, tmpdir));
  ck_assert_ptr_nonnull(strstr(x, ">out.h5:/frames/000002/x<"));
  ck_assert_ptr_nonnull(strstr(x, ">out.h5:/mesh/triangles<"));
  ck_assert_ptr_nonnull(strstr(x, "Center=\"Cell\""));
  ck_assert_ptr_nonnull(strstr(x, "Center=\"Node\""));
  /* the three times, in order, read back exactly */
  const char *p = x;
  for (long k = 0; k < 3; k++) {
    p = strstr(p, "<Time Value=\"");
    ck_assert_ptr_nonnull(p);
    p += strlen("<Time Value=\"");
    set_state(&s, 2 * k);
    ck_assert(strtod(p, NULL) == s.time);
  }
  ck_assert_ptr_null(strstr(p, "<Time Value=\""));
  free(x);
  char tmpx[160];
  snprintf(tmpx, sizeof tmpx, "%s.tmp", xmf);
  ck_assert(!file_exists(tmpx));
  free_sim(&s);
  rm_tmpdir();
}

START_TEST(test_h5_roundtrip) { roundtrip(0); }
END_TEST

START_TEST(test_h5_roundtrip_compressed) { roundtrip(1); }
END_TEST

/* A second run continues the same file (also after output_close_all); a topology change starts
 * /mesh_0001; undump closes. */
START_TEST(test_h5_runs_and_topology) {
  mk_tmpdir();
  YfSim s;
  build(&s, 3);
  char h5[128], xmf[128];
  snprintf(h5, sizeof h5, "%s/t.h5", tmpdir);
  snprintf(xmf, sizeof xmf, "%s/t.xmf", tmpdir);
  output_add_dump(&s, "a", YF_DUMP_H5, 10, h5, YF_FIELD_U | YF_FIELD_MATERIAL, 0);
  set_state(&s, 0);
  output_run_begin(&s);               /* frame 0, step 0 */
  for (long st = 1; st <= 5; st++) { set_state(&s, st); output_step(&s); }
  output_run_end(&s);
  ck_assert_int_eq(output_frames(&s, "a"), 1);
  output_close_all(&s);               /* closed between runs: the next frame reopens, appends */
  output_run_begin(&s);               /* second run starts at step 5: frame 1 */
  output_topology_changed(&s);
  for (long st = 6; st <= 10; st++) { set_state(&s, st); output_step(&s); } /* frame 2 at 10 */
  ck_assert_int_eq(output_frames(&s, "a"), 3);
  output_run_begin(&s);               /* a run starting where a frame was just written: none */
  ck_assert_int_eq(output_frames(&s, "a"), 3);
  ck_assert_int_eq(output_remove_dump(&s, "a"), 0);
  ck_assert_int_eq(output_frames(&s, "a"), -1);
  ck_assert_int_eq(output_remove_dump(&s, "a"), -1);
  hid_t f = H5Fopen(h5, H5F_ACC_RDONLY, H5P_DEFAULT);
  ck_assert_int_ge(f, 0);
  ck_assert_int_gt(H5Lexists(f, "/frames/000002/u", H5P_DEFAULT), 0);
  ck_assert_int_lt(H5Lexists(f, "/frames/000002/v", H5P_DEFAULT), 1); /* not asked for */
  ck_assert_int_gt(H5Lexists(f, "/mesh_0001", H5P_DEFAULT), 0);
  for (int k = 0; k < 3; k++) {
    static const long long want[3] = {0, 5, 10};
    char p[64];
    void *buf;
    snprintf(p, sizeof p, "/frames/%06d/step", k);
    ck_assert_int_eq(h5_read(f, p, H5T_NATIVE_LLONG, &buf), 1);
    ck_assert_int_eq(((long long *)buf)[0], want[k]);
    free(buf);
  }
  H5Fclose(f);
  char *x = slurp(xmf);
  ck_assert_int_eq(count_str(x, "GridType=\"Uniform\""), 3);
  /* frames 0 and 1 (written before the change) use /mesh, frame 2 the new /mesh_0001 */
  ck_assert_int_eq(count_str(x, ">t.h5:/mesh/triangles<"), 2);
  ck_assert_int_eq(count_str(x, ">t.h5:/mesh_0001/triangles<"), 1);
  ck_assert_int_eq(count_str(x, "Name=\"material\""), 3);
  ck_assert_int_eq(count_str(x, "Name=\"stress\""), 0);
  free(x);
  free_sim(&s);
  rm_tmpdir();
}
END_TEST

/* CSV: one file per frame with exact values, and an index of frames. */
START_TEST(test_csv) {
  mk_tmpdir();
  YfSim s;
  build(&s, 2);
  char pre[128], p[160];
  snprintf(pre, sizeof pre, "%s/nodes", tmpdir);
  output_add_dump(&s, "c", YF_DUMP_CSV, 3, pre, 0, 0);
  set_state(&s, 0);
  output_run_begin(&s);
  for (long st = 1; st <= 3; st++) { set_state(&s, st); output_step(&s); }
  output_close_all(&s);
  snprintf(p, sizeof p, "%s_000001.csv", pre);
  FILE *f = fopen(p, "r");
  ck_assert_ptr_nonnull(f);
  char line[512];
  ck_assert_ptr_nonnull(fgets(line, sizeof line, f));
  ck_assert_str_eq(line, "id,x,y,ux,uy,vx,vy\n");
  int n = 0;
  while (fgets(line, sizeof line, f)) {
    int id;
    double v[6];
    ck_assert_int_eq(sscanf(line, "%d,%lf,%lf,%lf,%lf,%lf,%lf", &id, v, v + 1, v + 2, v + 3, v + 4, v + 5), 7);
    const YfNodes *nd = &s.model.node;
    ck_assert_int_eq(id, nd->id[n]);
    ck_assert(v[0] == nd->x[n] && v[1] == nd->y[n] && v[4] == nd->vx[n] && v[5] == nd->vy[n]);
    ck_assert(v[2] == nd->x[n] - nd->x0[n] && v[3] == nd->y[n] - nd->y0[n]);
    n++;
  }
  fclose(f);
  ck_assert_int_eq(n, s.model.node.n);
  snprintf(p, sizeof p, "%s_frames.csv", pre);
  char *ix = slurp(p);
  char want[256];
  set_state(&s, 3);
  snprintf(want, sizeof want, "frame,step,time,file\n0,0,0,nodes_000000.csv\n1,3,%.17g,nodes_000001.csv\n", s.time);
  ck_assert_str_eq(ix, want);
  free(ix);
  free_sim(&s);
  rm_tmpdir();
}
END_TEST

/* ---------------------------------------------------------------- deck commands */

/* Through the interpreter: periods, fields, csv, undump, and no frame twice at a run boundary. */
START_TEST(test_deck_dump) {
  mk_tmpdir();
  char cwd[1024];
  ck_assert_ptr_nonnull(getcwd(cwd, sizeof cwd));
  ck_assert_int_eq(chdir(tmpdir), 0);
  YfSim *s = yft_run("material m elastic rho 1000 E 1e9 nu 0.25 plane_stress\n"
                     "mesh rect bar m 0 0 1 0.1 10 2\n"
                     "velocity bar set 0.1 0.05\n"
                     "timestep auto\n"
                     "dump a h5 5 a.h5 fields v stress\n"
                     "dump c csv 10 n\n"
                     "run 10\n"
                     "undump a\n"
                     "run 5\n");
  ck_assert_int_eq(s->step, 15);
  ck_assert_int_eq(output_frames(s, "a"), -1);
  ck_assert_int_eq(output_frames(s, "c"), 2); /* steps 0 and 10; the second run starts at 10 */
  ck_assert(yft_exists("n_000001.csv") && !yft_exists("n_000002.csv"));
  hid_t f = H5Fopen("a.h5", H5F_ACC_RDONLY, H5P_DEFAULT);
  ck_assert_int_ge(f, 0);
  ck_assert_int_gt(H5Lexists(f, "/frames/000002/v", H5P_DEFAULT), 0);
  ck_assert_int_gt(H5Lexists(f, "/frames/000002/stress", H5P_DEFAULT), 0);
  ck_assert_int_lt(H5Lexists(f, "/frames/000002/u", H5P_DEFAULT), 1);
  ck_assert_int_lt(H5Lexists(f, "/frames/000003", H5P_DEFAULT), 1);
  void *buf;
  ck_assert_int_eq(h5_read(f, "/frames/000002/step", H5T_NATIVE_LLONG, &buf), 1);
  ck_assert_int_eq(((long long *)buf)[0], 10);
  free(buf);
  ck_assert_int_eq(h5_read(f, "/frames/000002/time", H5T_NATIVE_DOUBLE, &buf), 1);
  ck_assert_double_eq_tol(((double *)buf)[0], 10 * s->dt, 1e-12 * s->dt);
  free(buf);
  H5Fclose(f);
  char *x = slurp("a.xmf");
  ck_assert_int_eq(count_str(x, "GridType=\"Uniform\""), 3);
  ck_assert_int_eq(count_str(x, "Name=\"u\""), 0);
  free(x);
  ck_assert_int_eq(chdir(cwd), 0);
  rm_tmpdir();
}
END_TEST

/* A wrong field name is a deck error naming the word and the valid fields; nothing is written. */
START_TEST(test_deck_dump_errors) {
  static const char *const bad[][2] = {
      {"dump d h5 10 out.h5 fields u speed\n", "speed"},
      {"dump d h5 0 out.h5\n", "N (steps between frames)"},
      {"dump d h5 10 out.h5 fast\n", "expected fields or compress"},
      {"dump d h5 10 a:b.h5\n", "may not contain ':'"},
      {"dump d h5 10 out.h5\ndump d csv 10 n\n", "undump it first"},
      {"undump nosuch\n", "no such dump"}};
  for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
    char deck[512], *err, *dir;
    snprintf(deck, sizeof deck, "material m elastic rho 1000 E 1e9 nu 0.25 plane_stress\n"
                                "mesh rect bar m 0 0 1 0.1 10 2\ntimestep auto\n%srun 10\n", bad[i][0]);
    int rc = yft_run_binary("bad.deck", deck, NULL, &err, &dir);
    ck_assert_msg(rc == YF_EXIT_DECK, "exit %d for %s", rc, bad[i][0]);
    ck_assert_msg(strstr(err, i == 4 ? "bad.deck:5: error:" : "bad.deck:4: error:") && strstr(err, bad[i][1]),
                  "stderr: %s", err);
    if (i == 0) ck_assert_msg(strstr(err, "vonmises") != NULL, "valid fields not listed: %s", err);
    char p[600];
    snprintf(p, sizeof p, "%s/out.h5", dir);
    ck_assert(!yft_exists(p));
    snprintf(p, sizeof p, "rm -rf '%s'", dir);
    ck_assert_int_eq(system(p), 0);
    free(err);
    free(dir);
  }
}
END_TEST

/* ---------------------------------------------------------------- I/O errors */

static YfSim *cleanup_sim;
static void close_on_error(int code, const char *msg) {
  (void)code;
  (void)msg;
  output_close_all(cleanup_sim);
}

/* A dump that cannot create its file ends the run with exit code 2 and a message naming the
 * file and the system's reason; the cleanup path closes the other dump, whose frame stays. */
START_TEST(test_io_error) {
  mk_tmpdir();
  char good[128], bad[128];
  snprintf(good, sizeof good, "%s/good.h5", tmpdir);
  snprintf(bad, sizeof bad, "%s/no_such_dir/bad.h5", tmpdir);
  int pfd[2];
  ck_assert_int_eq(pipe(pfd), 0);
  pid_t pid = fork();
  if (pid == 0) {
    dup2(pfd[1], 2);
    close(pfd[0]);
    static YfSim s;
    build(&s, 2);
    cleanup_sim = &s;
    yf_set_cleanup(close_on_error);
    output_add_dump(&s, "good", YF_DUMP_H5, 1, good, YF_FIELD_ALL, 0);
    output_add_dump(&s, "bad", YF_DUMP_H5, 1, bad, YF_FIELD_ALL, 0);
    set_state(&s, 0);
    output_run_begin(&s);
    _exit(0);
  }
  close(pfd[1]);
  char msg[2048] = "";
  size_t k = 0;
  ssize_t r;
  while (k + 1 < sizeof msg && (r = read(pfd[0], msg + k, sizeof msg - 1 - k)) > 0) k += (size_t)r;
  msg[k] = 0;
  close(pfd[0]);
  int status;
  waitpid(pid, &status, 0);
  ck_assert(WIFEXITED(status));
  ck_assert_int_eq(WEXITSTATUS(status), YF_EXIT_IO);
  ck_assert_msg(strstr(msg, "dump bad") && strstr(msg, bad) && strstr(msg, "No such file"), "message: %s", msg);
  YfSim s;
  build(&s, 2);
  hid_t f = H5Fopen(good, H5F_ACC_RDONLY, H5P_DEFAULT);
  ck_assert_int_ge(f, 0);
  ck_assert_int_eq(check_frame(f, &s, 0, 0), 0);
  H5Fclose(f);
  model_free(&s.model);
  rm_tmpdir();
}
END_TEST

/* ---------------------------------------------------------------- kill test */

/* Fork a writer (period 1, 800 nodes) that reports through a pipe once frame 1 is flushed and
 * indexed, SIGKILL it after delay_us microseconds, then check that the .xmf lists >= 2 frames and
 * that every listed frame reads back exactly.  Returns the number of listed frames, -1 - k
 * when frame k is unreadable or wrong, or -1000 when the file does not open at all. */
static long kill_trial(const char *dir, useconds_t delay_us) {
  char h5[160], xmf[160];
  snprintf(h5, sizeof h5, "%s/k.h5", dir);
  snprintf(xmf, sizeof xmf, "%s/k.xmf", dir);
  int pfd[2];
  ck_assert_int_eq(pipe(pfd), 0);
  pid_t pid = fork();
  ck_assert_int_ge(pid, 0);
  if (pid == 0) {
    close(pfd[0]);
    YfSim s;
    build(&s, 399);
    output_add_dump(&s, "k", YF_DUMP_H5, 1, h5, YF_FIELD_ALL, 0);
    set_state(&s, 0);
    output_run_begin(&s);
    for (long st = 1; st < 100000; st++) {
      set_state(&s, st);
      output_step(&s);
      if (st == 1 && write(pfd[1], "x", 1) != 1) _exit(3);
    }
    _exit(0);
  }
  close(pfd[1]);
  char c;
  ck_assert_int_eq(read(pfd[0], &c, 1), 1);
  if (delay_us) usleep(delay_us);
  kill(pid, SIGKILL);
  int status;
  waitpid(pid, &status, 0);
  close(pfd[0]);
  ck_assert(WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL);

  char *x = slurp(xmf);
  long listed = count_str(x, "GridType=\"Uniform\"");
  free(x);
  ck_assert_int_ge(listed, 2);
  YfSim s;
  build(&s, 399);
  long result = listed;
  hid_t f = H5Fopen(h5, H5F_ACC_RDONLY, H5P_DEFAULT);
  if (f < 0) result = -1000;
  for (long k = 0; f >= 0 && k < listed; k++)
    if (check_frame(f, &s, k, k) != 0) {
      result = -1 - k;
      break;
    }
  if (f >= 0) H5Fclose(f);
  model_free(&s.model);
  return result;
}

START_TEST(test_kill_midway) {
  mk_tmpdir();
  H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
  /* Kill right away (the writer is inside frame 2) and a little later (some frames on). */
  static const useconds_t delay[] = {0, 300, 3000};
  for (size_t i = 0; i < sizeof delay / sizeof delay[0]; i++) {
    long r = kill_trial(tmpdir, delay[i]);
    ck_assert_msg(r != -1000, "killed writer (delay %u us): the .h5 does not open", (unsigned)delay[i]);
    ck_assert_msg(r >= 2, "killed writer (delay %u us): frame %ld listed in the .xmf is unreadable",
                  (unsigned)delay[i], -1 - r);
  }
  rm_tmpdir();
}
END_TEST

/* ---------------------------------------------------------------- summary + hash */

static void summary_sim(YfSim *s) {
  build(s, 2);
  set_state(s, 7);
  s->time = 8.75e-6;
  s->energy = (YfEnergy){1.5, 2.25, 4.0, 0.125, 0.0, 1e-300, 0.1};
  s->wall_s = 2.0;
  s->elem_steps = 3e6;
  s->threads = 2;
}

START_TEST(test_summary_keys) {
  mk_tmpdir();
  YfSim s;
  summary_sim(&s);
  summary_clear_extras();
  summary_set_counts(12, 3, 5);
  summary_add_number("peak_force", 1.0);
  summary_add_raw("probe", "[1, 2]");
  summary_add_number("peak_force", 0.1); /* replaces */
  char path[128];
  snprintf(path, sizeof path, "%s/s.json", tmpdir);
  ck_assert_int_eq(summary_write(&s, path, YF_EXIT_OK, ""), YF_EXIT_OK);
  char *j = slurp(path);
  static const char *const keys[] = {
      "\"version\": \"", "\"status\": \"ok\"", "\"reason\": \"\"", "\"steps\": 7,", "\"time\": 8.75e-06,",
      "\"nodes\": 6,", "\"elements\": 4,", "\"joints\": 12,", "\"joints_broken\": 3,",
      "\"contact_pairs\": 5,", "\"energy\": {\"kinetic\": 1.5, \"strain\": 2.25, \"external_work\": 4, "
      "\"damping\": 0.125, \"joint_dissipated\": 0, \"contact\": 1e-300, \"friction\": 0.1}",
      "\"wall_s\": 2,", "\"element_steps_per_s\": 1500000,", "\"threads\": 2,", "\"state_hash\": \"",
      "\"peak_force\": 0.1,", "\"probe\": [1, 2]\n}"};
  const char *p = j;
  for (size_t i = 0; i < sizeof keys / sizeof keys[0]; i++) {
    const char *q = strstr(p, keys[i]);
    ck_assert_msg(q != NULL, "missing or out of order: %s\n%s", keys[i], j);
    p = q + strlen(keys[i]);
  }
  char hash[48];
  snprintf(hash, sizeof hash, "\"state_hash\": \"%016llx\"", (unsigned long long)sim_state_hash(&s));
  ck_assert_ptr_nonnull(strstr(j, hash));
  ck_assert_int_eq(count_str(j, "peak_force"), 1);
  free(j);
  char tmp[160];
  snprintf(tmp, sizeof tmp, "%s.tmp", path);
  ck_assert(!file_exists(tmp));
  summary_clear_extras();
  summary_set_counts(0, 0, 0);
  free_sim(&s);
  rm_tmpdir();
}
END_TEST

START_TEST(test_summary_nonfinite) {
  mk_tmpdir();
  YfSim s;
  summary_sim(&s);
  summary_clear_extras();
  s.energy.strain = NAN;
  char path[128];
  snprintf(path, sizeof path, "%s/s.json", tmpdir);
  ck_assert_int_eq(summary_write(&s, path, YF_EXIT_OK, ""), YF_EXIT_NUMERIC);
  char *j = slurp(path);
  ck_assert_ptr_nonnull(strstr(j, "\"status\": \"numerical_failure\""));
  ck_assert_ptr_nonnull(strstr(j, "\"strain\": null"));
  ck_assert_ptr_nonnull(strstr(j, "energy.strain"));
  ck_assert_ptr_null(strstr(j, "nan"));
  free(j);
  /* an error status is kept; an infinite extra number is null too */
  s.energy.strain = 1.0;
  summary_add_number("x_inf", INFINITY);
  ck_assert_int_eq(summary_write(&s, path, YF_EXIT_IO, "disk full"), YF_EXIT_IO);
  j = slurp(path);
  ck_assert_ptr_nonnull(strstr(j, "\"status\": \"io_error\""));
  ck_assert_ptr_nonnull(strstr(j, "\"reason\": \"disk full\""));
  ck_assert_ptr_nonnull(strstr(j, "\"x_inf\": null"));
  ck_assert_ptr_null(strstr(j, "inf,"));
  free(j);
  summary_clear_extras();
  free_sim(&s);
  rm_tmpdir();
}
END_TEST

START_TEST(test_summary_escaping) {
  char out[256];
  summary_json_string(out, sizeof out, "deck.y:3: error: bad \"word\"\n\tback\\slash \x01 caf\xc3\xa9 \xff");
  ck_assert_str_eq(out, "\"deck.y:3: error: bad \\\"word\\\"\\n\\tback\\\\slash \\u0001 caf\xc3\xa9 \\ufffd\"");
  /* truncation keeps a closed string and never splits an escape */
  summary_json_string(out, 8, "ab\"cdefgh");
  ck_assert_str_eq(out, "\"ab\\\"c\"");
  summary_json_string(out, 6, "ab\"cdefgh");
  ck_assert_str_eq(out, "\"ab\"");
  mk_tmpdir();
  YfSim s;
  summary_sim(&s);
  summary_clear_extras();
  char path[128];
  snprintf(path, sizeof path, "%s/s.json", tmpdir);
  ck_assert_int_eq(summary_write(&s, path, YF_EXIT_DECK, "a.deck:1: error: \"x\"\nnext"), YF_EXIT_DECK);
  char *j = slurp(path);
  ck_assert_ptr_nonnull(strstr(j, "\"status\": \"deck_error\""));
  ck_assert_ptr_nonnull(strstr(j, "\"reason\": \"a.deck:1: error: \\\"x\\\"\\nnext\""));
  free(j);
  free_sim(&s);
  rm_tmpdir();
}
END_TEST

START_TEST(test_state_hash) {
  YfSim s;
  build(&s, 3);
  set_state(&s, 5);
  uint64_t h0 = sim_state_hash(&s);
  ck_assert(sim_state_hash(&s) == h0);
  /* forces, stresses, time are not state in the hash */
  s.model.node.fx[2] += 1.0;
  s.model.tri.s[0] = -7.0;
  s.time = 99.0;
  ck_assert(sim_state_hash(&s) == h0);
  /* one bit of one velocity */
  for (int bit = 0; bit < 64; bit += 21) {
    uint64_t u;
    memcpy(&u, &s.model.node.vy[4], 8);
    u ^= (uint64_t)1 << bit;
    memcpy(&s.model.node.vy[4], &u, 8);
    ck_assert_msg(sim_state_hash(&s) != h0, "bit %d of vy[4] not seen", bit);
    u ^= (uint64_t)1 << bit;
    memcpy(&s.model.node.vy[4], &u, 8);
    ck_assert(sim_state_hash(&s) == h0);
  }
  /* swapping two nodes' x changes it (order matters) */
  double t = s.model.node.x[0];
  s.model.node.x[0] = s.model.node.x[1];
  s.model.node.x[1] = t;
  ck_assert(sim_state_hash(&s) != h0);
  /* FNV-1a 64 of no bytes is the offset basis */
  s.model.node.n = 0;
  ck_assert(sim_state_hash(&s) == 0xcbf29ce484222325ull);
  model_free(&s.model);
}
END_TEST

Suite *output_suite(void) {
  Suite *su = suite_create("output");
  TCase *tc = tcase_create("h5");
  tcase_set_timeout(tc, 30);
  tcase_add_test(tc, test_h5_roundtrip);
  tcase_add_test(tc, test_h5_roundtrip_compressed);
  tcase_add_test(tc, test_h5_runs_and_topology);
  tcase_add_test(tc, test_csv);
  tcase_add_test(tc, test_deck_dump);
  tcase_add_test(tc, test_deck_dump_errors);
  tcase_add_test(tc, test_io_error);
  tcase_add_test(tc, test_kill_midway);
  suite_add_tcase(su, tc);
  tc = tcase_create("summary");
  tcase_add_test(tc, test_summary_keys);
  tcase_add_test(tc, test_summary_nonfinite);
  tcase_add_test(tc, test_summary_escaping);
  tcase_add_test(tc, test_state_hash);
  suite_add_tcase(su, tc);
  return su;
}
