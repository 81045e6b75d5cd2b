/* check_output.c: dumps (HDF5 + XDMF, CSV), the summary JSON and the state hash.
 *
 * Facts checked: arrays read back from each frame file STEM_NNNNNN.h5 are bit-identical to the
 * model's at the frame's step, frames land exactly every N steps plus at the run start, each
 * file carries the topology of its own frame, the .xmf lists exactly the frames written and
 * refers to each frame's file by its bare name, a writer killed by SIGKILL at random moments
 * leaves every frame its .xmf lists readable and exact, the summary has the standard keys in
 * order and never contains NaN, the state hash sees a single flipped bit, and on a full disk a
 * y2dref dump's files, a record's file and a csv dump's index are left whole (to their last
 * complete row).
 */
#include <check.h>
#include <dirent.h>
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
  char *b = yft_slurp(path, 0);
  ck_assert_msg(b != NULL, "cannot open %s", path);
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

/* The file of frame k of an h5 dump whose FILE is STEM.h5. */
static void frame_path(char *out, size_t n, const char *stem, long k) {
  snprintf(out, n, "%s_%06ld.h5", stem, k);
}

/* Compare the open frame file f with the state set_state(step) of a model built like s.
 * Returns 0 when every array is bit-identical. */
static int check_frame(hid_t f, YfSim *s, long step) {
  set_state(s, step);
  const YfModel *m = &s->model;
  int n = m->node.n, nt = m->tri.n, bad = 0;
  void *buf;
  double *b;
  if (h5_read(f, "/time", H5T_NATIVE_DOUBLE, &buf) != 1) return 1;
  bad |= ((double *)buf)[0] != s->time;
  free(buf);
  if (h5_read(f, "/step", H5T_NATIVE_LLONG, &buf) != 1) return 1;
  bad |= ((long long *)buf)[0] != step;
  free(buf);
  static const char *const vec[] = {"/x", "/u", "/v", "/f"};
  for (int q = 0; q < 4; q++) {
    if (h5_read(f, vec[q], H5T_NATIVE_DOUBLE, &buf) != 2L * n) return 1;
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
  if (h5_read(f, "/stress", H5T_NATIVE_DOUBLE, &buf) != 3L * nt) return 1;
  bad |= memcmp(buf, m->tri.s, sizeof(double) * 3 * (size_t)nt) != 0;
  free(buf);
  static const char *const part[3] = {"/stress_xx", "/stress_yy", "/stress_xy"};
  for (int c = 0; c < 3; c++) { /* the named parts ParaView shows: the same numbers */
    if (h5_read(f, part[c], H5T_NATIVE_DOUBLE, &buf) != nt) return 1;
    for (int e = 0; e < nt; e++) bad |= ((double *)buf)[e] != m->tri.s[3 * e + c];
    free(buf);
  }
  if (h5_read(f, "/mesh/triangles", H5T_NATIVE_INT, &buf) != 3L * nt) return 1;
  bad |= memcmp(buf, m->tri.v, sizeof(int) * 3 * (size_t)nt) != 0;
  free(buf);
  return bad;
}

/* check_frame on frame k of dump STEM; 0 ok, 1 wrong, 2 the file does not open. */
static int check_frame_file(const char *stem, YfSim *s, long k, long step) {
  char p[256];
  frame_path(p, sizeof p, stem, k);
  hid_t f = H5Fopen(p, H5F_ACC_RDONLY, H5P_DEFAULT);
  if (f < 0) return 2;
  int r = check_frame(f, s, step);
  H5Fclose(f);
  return r;
}

/* ---------------------------------------------------------------- h5 + xmf */

/* Period 2 over 4 steps: frames at steps 0 (run start), 2, 4; arrays exact; derived stresses
 * match the closed forms; the .xmf lists the 3 frames with relative HDF paths. */
static void roundtrip(int compress) {
  mk_tmpdir();
  YfSim s;
  build(&s, 6);
  char h5[128], xmf[128], stem[128], p0[160];
  snprintf(h5, sizeof h5, "%s/out.h5", tmpdir);
  snprintf(stem, sizeof stem, "%s/out", tmpdir);
  snprintf(xmf, sizeof xmf, "%s/out.xmf", tmpdir);
  frame_path(p0, sizeof p0, stem, 0);
  ck_assert_int_eq(output_add_dump(&s, "d1", YF_DUMP_H5, 2, h5, YF_FIELD_ALL, compress), 0);
  ck_assert_msg(!file_exists(p0) && !file_exists(xmf), "no file before the first frame");
  set_state(&s, 0);
  output_run_begin(&s);
  for (long st = 1; st <= 4; st++) {
    set_state(&s, st);
    output_step(&s);
    ck_assert_int_eq(output_frames(&s, "d1"), 1 + st / 2);
  }
  output_run_end(&s);
  output_close_all(&s);

  ck_assert_msg(!file_exists(h5), "FILE.h5 itself is not written, only STEM_NNNNNN.h5");
  for (long k = 0; k < 3; k++) {
    ck_assert_msg(check_frame_file(stem, &s, k, 2 * k) == 0, "frame %ld differs", k);
    char p[200];
    frame_path(p, sizeof p, stem, k);
    strcat(p, ".tmp");
    ck_assert_msg(!file_exists(p), "%s left behind", p);
  }
  frame_path(p0, sizeof p0, stem, 3);
  ck_assert(!file_exists(p0));
  frame_path(p0, sizeof p0, stem, 1);
  hid_t f = H5Fopen(p0, H5F_ACC_RDONLY, H5P_DEFAULT);
  ck_assert_int_ge(f, 0);
  void *buf = NULL;
  ck_assert_int_eq(h5_read(f, "/mesh/triangles", H5T_NATIVE_INT, &buf), 3L * s.model.tri.n);
  ck_assert_int_eq(memcmp(buf, s.model.tri.v, sizeof(int) * 3 * (size_t)s.model.tri.n), 0);
  free(buf);
  ck_assert_int_eq(h5_read(f, "/mesh/material", H5T_NATIVE_INT, &buf), s.model.tri.n);
  ck_assert_int_eq(memcmp(buf, s.model.tri.mat, sizeof(int) * (size_t)s.model.tri.n), 0);
  free(buf);
  /* von Mises and sigma1 of frame 1 (step 2) against their closed forms */
  set_state(&s, 2);
  double *vm, *s1;
  ck_assert_int_eq(h5_read(f, "/vonmises", H5T_NATIVE_DOUBLE, (void **)&vm), s.model.tri.n);
  ck_assert_int_eq(h5_read(f, "/sigma1", H5T_NATIVE_DOUBLE, (void **)&s1), s.model.tri.n);
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
  /* relative references only: every HDF item starts with the bare name of its frame's file */
  ck_assert_int_eq(count_str(x, "Format=\"HDF\">"), count_str(x, "Format=\"HDF\">out_00000"));
  ck_assert_ptr_null(strstr(x, tmpdir));
  for (int k = 0; k < 3; k++) {
    char w[64];
    snprintf(w, sizeof w, ">out_%06d.h5:/x<", k);
    ck_assert_int_eq(count_str(x, w), 1);
    snprintf(w, sizeof w, ">out_%06d.h5:/mesh/triangles<", k);
    ck_assert_int_eq(count_str(x, w), 1);
    /* x, u v f vonmises sigma1, stress as 3 named parts, triangles, material, body */
    snprintf(w, sizeof w, ">out_%06d.h5:/", k);
    ck_assert_int_eq(count_str(x, w), 12);
    snprintf(w, sizeof w, ">out_%06d.h5:/stress_xy<", k);
    ck_assert_int_eq(count_str(x, w), 1);
  }
  ck_assert_ptr_null(strstr(x, ".tmp"));
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

/* A second run continues the frame numbering (also after output_close_all); a frame after a
 * topology change carries the new mesh in its own file while earlier files keep the old one;
 * undump closes; a new dump with the same file (a rerun) starts again at frame 0 and its index
 * lists only its own frames. */
START_TEST(test_h5_runs_and_topology) {
  mk_tmpdir();
  YfSim s;
  build(&s, 3);
  char h5[128], xmf[128], stem[128], p[200];
  snprintf(h5, sizeof h5, "%s/t.h5", tmpdir);
  snprintf(stem, sizeof stem, "%s/t", tmpdir);
  snprintf(xmf, sizeof xmf, "%s/t.xmf", tmpdir);
  output_add_dump(&s, "a", YF_DUMP_H5, 10, h5, YF_FIELD_U | YF_FIELD_MATERIAL, 0);
  set_state(&s, 0);
  output_run_begin(&s);               /* frame 0, step 0 */
  for (long st = 1; st <= 5; st++) { set_state(&s, st); output_step(&s); }
  output_run_end(&s);
  ck_assert_int_eq(output_frames(&s, "a"), 1);
  output_close_all(&s);               /* closed between runs: the next frame goes on */
  output_run_begin(&s);               /* second run starts at step 5: frame 1 */
  /* a new node and triangle (what fracture does to the node count) */
  int nn = model_add_node(&s.model, 0.35, 0.05, 999, 0);
  model_add_tri(&s.model, 6, nn, 7, 1, 77, 0);
  output_topology_changed(&s);
  for (long st = 6; st <= 10; st++) { set_state(&s, st); output_step(&s); } /* frame 2 at 10 */
  ck_assert_int_eq(output_frames(&s, "a"), 3);
  output_run_begin(&s);               /* a run starting where a frame was just written: none */
  ck_assert_int_eq(output_frames(&s, "a"), 3);
  ck_assert_int_eq(output_remove_dump(&s, "a"), 0);
  ck_assert_int_eq(output_frames(&s, "a"), -1);
  ck_assert_int_eq(output_remove_dump(&s, "a"), -1);
  static const long long want[3] = {0, 5, 10};
  for (int k = 0; k < 3; k++) {
    frame_path(p, sizeof p, stem, k);
    hid_t f = H5Fopen(p, H5F_ACC_RDONLY, H5P_DEFAULT);
    ck_assert_int_ge(f, 0);
    void *buf;
    ck_assert_int_eq(h5_read(f, "/step", H5T_NATIVE_LLONG, &buf), 1);
    ck_assert_int_eq(((long long *)buf)[0], want[k]);
    free(buf);
    ck_assert_int_gt(H5Lexists(f, "/u", H5P_DEFAULT), 0);
    ck_assert_int_lt(H5Lexists(f, "/v", H5P_DEFAULT), 1); /* not asked for */
    /* frames 0 and 1 were written before the change: 6 triangles, 8 nodes; frame 2: 7, 9 */
    int nt = k < 2 ? 6 : 7, n = k < 2 ? 8 : 9;
    ck_assert_int_eq(h5_read(f, "/mesh/triangles", H5T_NATIVE_INT, &buf), 3L * nt);
    ck_assert_int_eq(memcmp(buf, s.model.tri.v, sizeof(int) * 3 * (size_t)nt), 0);
    free(buf);
    ck_assert_int_eq(h5_read(f, "/mesh/node_id", H5T_NATIVE_INT, &buf), n);
    ck_assert_int_eq(((int *)buf)[n - 1], k < 2 ? 107 : 999);
    free(buf);
    ck_assert_int_eq(h5_read(f, "/u", H5T_NATIVE_DOUBLE, &buf), 2L * n);
    free(buf);
    H5Fclose(f);
  }
  char *x = slurp(xmf);
  ck_assert_int_eq(count_str(x, "GridType=\"Uniform\""), 3);
  ck_assert_int_eq(count_str(x, "NumberOfElements=\"6\""), 2);
  ck_assert_int_eq(count_str(x, "NumberOfElements=\"7\""), 1);
  ck_assert_int_eq(count_str(x, ">t_000002.h5:/mesh/triangles<"), 1);
  ck_assert_int_eq(count_str(x, "Dimensions=\"9 2\""), 2); /* x and u of frame 2 */
  ck_assert_int_eq(count_str(x, "Name=\"material\""), 3);
  ck_assert_int_eq(count_str(x, "Name=\"stress\""), 0);
  free(x);
  free_sim(&s);

  /* Rerun (a fresh process's view): two frames; frame 2 of the longer run stays on disk, unlisted. */
  build(&s, 3);
  output_add_dump(&s, "a", YF_DUMP_H5, 10, h5, YF_FIELD_U, 0);
  set_state(&s, 100);
  output_run_begin(&s);
  for (long st = 101; st <= 110; st++) { set_state(&s, st); output_step(&s); }
  ck_assert_int_eq(output_frames(&s, "a"), 2);
  x = slurp(xmf);
  ck_assert_int_eq(count_str(x, "GridType=\"Uniform\""), 2);
  ck_assert_ptr_null(strstr(x, "t_000002.h5"));
  ck_assert_ptr_nonnull(strstr(x, "<Information Name=\"step\" Value=\"110\"/>"));
  free(x);
  frame_path(p, sizeof p, stem, 2);
  ck_assert(file_exists(p));
  hid_t f = H5Fopen(h5, H5F_ACC_RDONLY, H5P_DEFAULT); /* never FILE.h5 itself */
  ck_assert_int_lt(f, 0);
  frame_path(p, sizeof p, stem, 1);
  f = H5Fopen(p, H5F_ACC_RDONLY, H5P_DEFAULT);
  ck_assert_int_ge(f, 0);
  void *buf;
  ck_assert_int_eq(h5_read(f, "/step", H5T_NATIVE_LLONG, &buf), 1);
  ck_assert_int_eq(((long long *)buf)[0], 110);
  free(buf);
  H5Fclose(f);
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
  ck_assert(!yft_exists("a.h5") && !yft_exists("a_000003.h5"));
  hid_t f = H5Fopen("a_000002.h5", H5F_ACC_RDONLY, H5P_DEFAULT);
  ck_assert_int_ge(f, 0);
  ck_assert_int_gt(H5Lexists(f, "/v", H5P_DEFAULT), 0);
  ck_assert_int_gt(H5Lexists(f, "/stress", H5P_DEFAULT), 0);
  ck_assert_int_lt(H5Lexists(f, "/u", H5P_DEFAULT), 1);
  void *buf;
  ck_assert_int_eq(h5_read(f, "/step", H5T_NATIVE_LLONG, &buf), 1);
  ck_assert_int_eq(((long long *)buf)[0], 10);
  free(buf);
  ck_assert_int_eq(h5_read(f, "/time", H5T_NATIVE_DOUBLE, &buf), 1);
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

/* A long series of frequent frames: the index is not rewritten at every frame (its cost grows
 * with the frames it lists), yet when the run ends it lists every frame, the last one included.
 * The policy is set so that every rewrite after the first is put off (any index is "large", the
 * gap is never reached): the index is written at the first frame and at the end of the run. */
START_TEST(test_long_series_index) {
  mk_tmpdir();
  char cwd[1024];
  ck_assert_ptr_nonnull(getcwd(cwd, sizeof cwd));
  ck_assert_int_eq(chdir(tmpdir), 0);
  output_set_index_policy(0, 1e300);
  YfSim *s = yft_run("material m elastic rho 1000 E 1e9 nu 0.25 plane_stress\n"
                     "mesh rect bar m 0 0 1 0.1 4 1\n"
                     "velocity bar set 0.1 0.05\n"
                     "timestep auto\n"
                     "dump a h5 1 a.h5 fields u\n"
                     "run 2000\n");
  output_set_index_policy((size_t)1 << 20, 20.0);
  ck_assert_int_eq(output_frames(s, "a"), 2001);
  ck_assert_int_eq(output_index_writes(s, "a"), 2);
  char *x = slurp("a.xmf");
  ck_assert_int_eq(count_str(x, "GridType=\"Uniform\""), 2001);
  const char *last = strstr(x, "Name=\"frame_002000\"");
  ck_assert_ptr_nonnull(last);
  ck_assert_ptr_nonnull(strstr(last, "<Information Name=\"step\" Value=\"2000\"/>"));
  free(x);
  sim_free(s);
  /* a restart writes the index first, so every frame before its step is listed: after a SIGKILL
   * the continuation numbered its frames after the last listed one and left a hole (a sweep of
   * new decks, 2026-11-28); here: the first frame, the restart at step 500, the end */
  output_set_index_policy(0, 1e300);
  s = yft_run("material m elastic rho 1000 E 1e9 nu 0.25 plane_stress\nmesh rect bar m 0 0 1 0.1 4 1\n"
              "velocity bar set 0.1 0.05\ntimestep auto\ndump a h5 1 a.h5 fields u\nrestart every 500 rr\nrun 700\n");
  output_set_index_policy((size_t)1 << 20, 20.0);
  ck_assert_int_eq(output_index_writes(s, "a"), 3);
  sim_free(s);
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
    snprintf(p, sizeof p, "%s/out_000000.h5", dir);
    ck_assert(!yft_exists(p));
    snprintf(p, sizeof p, "%s/out.xmf", dir);
    ck_assert(!yft_exists(p));
    snprintf(p, sizeof p, "rm -rf '%s'", dir);
    ck_assert_int_eq(system(p), 0);
    free(err);
    free(dir);
  }
}
END_TEST

/* The entries of directory path other than those listed (NULL-ended), as "a b " ("" when none). */
static void other_entries(const char *path, const char *const *keep, char *out, size_t n) {
  out[0] = 0;
  DIR *d = opendir(path);
  ck_assert_ptr_nonnull(d);
  for (struct dirent *e; (e = readdir(d));) {
    int k = !strcmp(e->d_name, ".") || !strcmp(e->d_name, "..");
    for (int i = 0; keep[i] && !k; i++) k = !strcmp(e->d_name, keep[i]);
    if (!k) snprintf(out + strlen(out), n - strlen(out), "%s ", e->d_name);
  }
  closedir(d);
}

/* A file prefix that names no file is refused at its line, nothing written: `dump d h5 10 .` wrote
 * ._000000.h5 and ..xmf (hidden), `dump d csv 10 /tmp/` /tmp/_000000.csv, and `restart every 5 .`
 * wrote ..a and ..b.  A name inside the folder works, and so does a stem that is a folder's name
 * (sub.h5 beside sub/: the README's y2dref folder 'out' beside an h5 dump 'out.h5' was refused
 * on the deck's second run, once the first had made the folder). */
START_TEST(test_dump_prefix_names_a_file) {
  static const struct {
    const char *line, *want;
  } bad[] = {
      {"dump d h5 10 .", "dump: '.': no file name: '.' is a directory, and its files would be named like '._000000.h5'; "
                         "give one, as in './out'"},
      {"dump d h5 10 sub/", "dump: 'sub/': no file name: it ends in '/', and its files would be named like "
                            "'sub/_000000.h5'; give one, as in 'sub/out'"},
      {"dump d h5 10 sub/.h5", "dump: 'sub/.h5': no file name: there is nothing before the extension"},
      {"dump d csv 10 .", "dump: '.': no file name: '.' is a directory, and its files would be named like '._000000.csv'"},
      {"dump d csv 10 sub/", "dump: 'sub/': no file name: it ends in '/'"},
      {"restart every 5 .", "restart: '.': no file name: '.' is a directory, and its files would be named like '..a'"},
      {"restart every 5 sub/", "restart: 'sub/': no file name: it ends in '/', and its files would be named like 'sub/.a'"},
  };
  static const char *const keep[] = {"bad.deck", "err.txt", "sub", NULL}, *const none[] = {NULL};
  const size_t nbad = sizeof bad / sizeof bad[0];
  for (size_t k = 0; k < nbad + 2; k++) {
    int ok = k >= nbad; /* last two: a name in sub, and sub.h5 beside sub, work */
    char deck[512], p[700], cmd[1600], left[400];
    snprintf(deck, sizeof deck, "material m elastic rho 1000 E 1e9 nu 0.25 plane_stress\nmesh rect bar m 0 0 1 0.1 4 2\n"
             "timestep auto\n%s\nrun 10\n", !ok ? bad[k].line : k == nbad ? "dump d h5 10 sub/out.h5" : "dump d h5 10 sub.h5");
    char *dir = yft_deck_dir("bad.deck", deck);
    snprintf(p, sizeof p, "%s/sub", dir);
    ck_assert_int_eq(mkdir(p, 0755), 0);
    snprintf(cmd, sizeof cmd, "cd %s && %s -in bad.deck -log none >/dev/null 2>err.txt", dir, yft_binary());
    int st = system(cmd), rc = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
    snprintf(p, sizeof p, "%s/err.txt", dir);
    char *err = yft_slurp(p, 1), want[400];
    if (ok) {
      snprintf(p, sizeof p, "%s/%s", dir, k == nbad ? "sub/out.xmf" : "sub.xmf");
      ck_assert_msg(rc == 0 && yft_exists(p), "%s: exit %d: %s", p, rc, err);
    } else {
      snprintf(want, sizeof want, "bad.deck:4: error: %s", bad[k].want);
      ck_assert_msg(rc == YF_EXIT_DECK && strstr(err, want), "%s: exit %d, want '%s': %s", bad[k].line, rc, want, err);
      other_entries(dir, keep, left, sizeof left);
      ck_assert_msg(!left[0], "%s: left %s", bad[k].line, left);
      snprintf(p, sizeof p, "%s/sub", dir);
      other_entries(p, none, left, sizeof left);
      ck_assert_msg(!left[0], "%s: left in sub: %s", bad[k].line, left);
    }
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    ck_assert_int_eq(system(cmd), 0);
    free(err);
    free(dir);
  }
}
END_TEST

/* Two outputs on one file through a link to a folder: 'link/out.h5' with link -> . is out.h5,
 * and sub/../out.h5 through a linked sub is where the link points.  They were told apart by their
 * text, and both dumps wrote the same frames and index, each over the other's. */
START_TEST(test_claims_through_links) {
  static const struct { const char *setup, *lines, *want; } cases[] = {
      {"ln -s . here", "dump a h5 1 here/out.h5\ndump b h5 1 out.h5", "dump: 'out.h5': a file of it is already written by dump 'a'"},
      {"mkdir sub && ln -s sub l", "dump a csv 1 l/c\nrecord b 1 sub/c_frames.csv step ke",
       "record: 'sub/c_frames.csv': already written by dump 'a'"},
      {"mkdir -p sub/x && ln -s sub/x l", "dump a h5 1 l/../out.h5\ndump b h5 1 sub/out.h5",
       "dump: 'sub/out.h5': a file of it is already written by dump 'a'"},
  };
  for (size_t k = 0; k < sizeof cases / sizeof *cases; k++) {
    char deck[512], cmd[1600], p[600];
    snprintf(deck, sizeof deck, "material m elastic rho 1000 E 1e9 nu 0.25 plane_stress\nmesh rect bar m 0 0 1 0.1 4 2\n"
             "timestep auto\n%s\nrun 2\n", cases[k].lines);
    char *dir = yft_deck_dir("f.deck", deck);
    snprintf(cmd, sizeof cmd, "cd %s && %s && %s f.deck >/dev/null 2>err.txt", dir, cases[k].setup, yft_binary());
    int st = system(cmd), rc = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
    snprintf(p, sizeof p, "%s/err.txt", dir);
    char *err = yft_slurp(p, 1), want[400];
    snprintf(want, sizeof want, "f.deck:5: error: %s", cases[k].want);
    ck_assert_msg(rc == YF_EXIT_DECK && strstr(err, want), "%s: exit %d, want '%s': %s", cases[k].lines, rc, want, err);
    free(err);
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    ck_assert_int_eq(system(cmd), 0);
    free(dir);
  }
}
END_TEST

/* A record of an expression with a comma, and a csv dump whose PREFIX has one: each is one CSV
 * field, quoted (RFC 4180).  The header 'step,time,max(ke,strain)' had one column more than its
 * rows, and a row of the index PREFIX_frames.csv one field more than its header, so a CSV reader
 * (pandas, Python's csv) paired values with the wrong names. */
START_TEST(test_csv_fields_with_commas) {
  char *err, *dir;
  int rc = yft_run_binary("f.deck", "material m elastic rho 1000 E 1e9 nu 0.25 plane_stress\n"
                          "mesh rect bar m 0 0 1 0.1 4 2\ntimestep auto\nvelocity bar set 1 0\n"
                          "dump c csv 1 \"a,b\"\nrecord r 1 r.csv \"max(ke,strain)\" ke\nrun 1\n", "", &err, &dir);
  ck_assert_msg(rc == 0, "exit %d: %s", rc, err);
  char p[600];
  snprintf(p, sizeof p, "%s/r.csv", dir);
  char *r = yft_slurp(p, 1);
  /* 1000 kg/m^3 x 0.1 m^2 at 1 m/s: ke = 50 J/m */
  ck_assert_msg(!strncmp(r, "step,time,\"max(ke,strain)\",ke\n0,0,50,50\n", 39), "r.csv:\n%s", r);
  snprintf(p, sizeof p, "%s/a,b_frames.csv", dir);
  char *ix = yft_slurp(p, 1);
  ck_assert_msg(!strncmp(ix, "frame,step,time,file\n0,0,0,\"a,b_000000.csv\"\n", 44), "a,b_frames.csv:\n%s", ix);
  free(r);
  free(ix);
  free(err);
  char cmd[700];
  snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
  ck_assert_int_eq(system(cmd), 0);
  free(dir);
}
END_TEST

/* An h5 dump's file name goes into its XDMF index, XML, which holds UTF-8 text only: a Latin-1
 * name ('\xe9t\xe9.h5') made an index that is not well-formed, and ParaView's reader aborted on
 * it.  It is refused at its line (nothing written); a UTF-8 name with spaces, accents and XML's
 * special characters is written, escaped, into the index. */
START_TEST(test_h5_name_not_utf8) {
  static const char head[] = "material m elastic rho 1000 E 1e9 nu 0.25 plane_stress\nmesh rect bar m 0 0 1 0.1 4 2\n"
                             "timestep auto\n";
  char deck[512], *err, *dir;
  snprintf(deck, sizeof deck, "%sdump d h5 1 \xe9t\xe9.h5\nrun 1\n", head);
  int rc = yft_run_binary("f.deck", deck, "-log none", &err, &dir);
  ck_assert_msg(rc == YF_EXIT_DECK && strstr(err, "f.deck:4: error: dump: ") &&
                strstr(err, "the file name is not UTF-8 text (byte 1 of it is 0xe9)"), "exit %d: %s", rc, err);
  static const char *const keep[] = {"f.deck", "stderr.txt", NULL};
  char left[400];
  other_entries(dir, keep, left, sizeof left);
  ck_assert_msg(!left[0], "left %s", left);
  free(err);
  char cmd[700];
  snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
  ck_assert_int_eq(system(cmd), 0);
  free(dir);
  /* the dump's id names the series in the index: the same */
  snprintf(deck, sizeof deck, "%sdump \xe9 h5 1 out.h5\nrun 1\n", head);
  rc = yft_run_binary("f.deck", deck, "-log none", &err, &dir);
  ck_assert_msg(rc == YF_EXIT_DECK && strstr(err, "f.deck:4: error: dump: ") &&
                strstr(err, "the dump id is not UTF-8 text (byte 1 of it is 0xe9)"), "exit %d: %s", rc, err);
  free(err);
  snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
  ck_assert_int_eq(system(cmd), 0);
  free(dir);
  snprintf(deck, sizeof deck, "%sdump d h5 1 \"r\xc3\xa9s ultats&<x>.h5\"\nrun 1\n", head);
  rc = yft_run_binary("f.deck", deck, "-log none", &err, &dir);
  ck_assert_msg(rc == 0, "exit %d: %s", rc, err);
  char p[700];
  snprintf(p, sizeof p, "%s/r\xc3\xa9s ultats&<x>.xmf", dir);
  char *x = yft_slurp(p, 1);
  ck_assert_msg(strstr(x, ">r\xc3\xa9s ultats&amp;&lt;x&gt;_000001.h5:/x</DataItem>"), "index:\n%.600s", x);
  free(x);
  free(err);
  snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
  ck_assert_int_eq(system(cmd), 0);
  free(dir);
}
END_TEST

/* ---------------------------------------------------------------- I/O errors */

static YfSim *cleanup_sim;
static void close_on_error(int code, const char *msg) {
  (void)code;
  (void)msg;
  output_close_all(cleanup_sim);
}

/* A dump that cannot create its frame file ends the run with exit code 2 and a message naming
 * the file and the system's reason; the other dump's frame, written before, stays. */
START_TEST(test_io_error) {
  mk_tmpdir();
  char good[128], bad[128], bad0[160], goodstem[128];
  snprintf(good, sizeof good, "%s/good.h5", tmpdir);
  snprintf(goodstem, sizeof goodstem, "%s/good", tmpdir);
  snprintf(bad, sizeof bad, "%s/no_such_dir/bad.h5", tmpdir);
  snprintf(bad0, sizeof bad0, "%s/no_such_dir/bad_000000.h5", tmpdir);
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
  ck_assert_msg(strstr(msg, "dump bad") && strstr(msg, bad0) && strstr(msg, "No such file"), "message: %s", msg);
  YfSim s;
  build(&s, 2);
  ck_assert_int_eq(check_frame_file(goodstem, &s, 0, 0), 0);
  char p[200];
  snprintf(p, sizeof p, "%s/good.xmf", tmpdir);
  char *x = slurp(p);
  ck_assert_int_eq(count_str(x, ">good_000000.h5:/x<"), 1);
  free(x);
  model_free(&s.model);
  rm_tmpdir();
}
END_TEST

/* ---------------------------------------------------------------- kill test */

/* Fork a writer (period 1, 800 nodes, 798 triangles) into the fresh directory dir that reports
 * through a pipe once frame 1 is indexed, SIGKILL it after delay_us microseconds, then check
 * that the .xmf is a complete document listing >= 2 frames, frame k in k.xmf names k_NNNNNN.h5
 * and every listed frame's file opens and reads back exactly.  Returns the number of listed
 * frames, or -1 - k when frame k is unreadable or wrong (-1000 - k: its file does not open). */
static long kill_trial(const char *dir, useconds_t delay_us) {
  char h5[160], xmf[160], stem[160];
  snprintf(h5, sizeof h5, "%s/k.h5", dir);
  snprintf(stem, sizeof stem, "%s/k", dir);
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
  size_t xl = strlen(x);
  static const char end[] = "  </Domain>\n</Xdmf>\n";
  ck_assert_msg(xl > strlen(end) && strcmp(x + xl - strlen(end), end) == 0, "the .xmf is not a complete document");
  ck_assert_int_ge(listed, 2);
  ck_assert_ptr_null(strstr(x, ".tmp"));
  char w[64];
  for (long k = 0; k < listed; k++) {
    snprintf(w, sizeof w, ">k_%06ld.h5:/x<", k);
    ck_assert_msg(strstr(x, w) != NULL, "frame %ld is not indexed by its own file", k);
  }
  snprintf(w, sizeof w, "k_%06ld.h5", listed);
  ck_assert_ptr_null(strstr(x, w));
  free(x);
  YfSim s;
  build(&s, 399);
  long result = listed;
  for (long k = 0; k < listed; k++) {
    int r = check_frame_file(stem, &s, k, k);
    if (r != 0) {
      result = r == 2 ? -1000 - k : -1 - k;
      break;
    }
  }
  model_free(&s.model);
  return result;
}

/* 20 kills at pseudo-random delays in [0, 5) ms after frame 1 (a fixed sequence, so a failure
 * repeats with the same delay), each in a fresh directory. */
START_TEST(test_kill_midway) {
  H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
  unsigned long long rng = 0x9e3779b97f4a7c15ull;
  long total = 0;
  for (int i = 0; i < 20; i++) {
    rng = rng * 6364136223846793005ull + 1442695040888963407ull; /* LCG (Knuth MMIX) */
    useconds_t delay = i == 0 ? 0 : (useconds_t)((rng >> 33) % 5000);
    mk_tmpdir();
    long r = kill_trial(tmpdir, delay);
    ck_assert_msg(r > -1000, "trial %d (delay %u us): frame %ld listed in the .xmf has no file",
                  i, (unsigned)delay, -1000 - r);
    ck_assert_msg(r >= 2, "trial %d (delay %u us): frame %ld listed in the .xmf is unreadable or wrong",
                  i, (unsigned)delay, -1 - r);
    total += r;
    rm_tmpdir();
  }
  ck_assert_int_ge(total, 40);
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

/* A metrics region named with a Latin-1 byte: its name is a key inside the summary's
 * crack_length_by_region, written as it was, so the summary was not UTF-8 (Python's json.load
 * failed on it); it is escaped as every summary string is (U+FFFD for the byte). */
START_TEST(test_summary_region_name_escaped) {
  char *err, *dir;
  int rc = yft_run_binary("f.deck", "material m elastic rho 1000 E 1e9 nu 0.25 plane_stress\nmesh rect bar m 0 0 1 0.1 4 2\n"
                          "jointprop cj ft 1e5 fs 1e5 gf 1 pen 1e10 law munjiza\nfracture bar cj\n"
                          "region r box -1 -1 2 2\nmetrics body bar\nmetrics region z\xe9 r\ntimestep auto\nrun 1\n",
                          "-summary s.json -log none", &err, &dir);
  ck_assert_msg(rc == 0, "exit %d: %s", rc, err);
  char p[600];
  snprintf(p, sizeof p, "%s/s.json", dir);
  char *j = slurp(p);
  ck_assert_msg(!strchr(j, '\xe9') && strstr(j, "\"crack_length_by_region\": {\"z\\ufffd\": {\"I\": 0"), "summary:\n%s", j);
  free(j);
  free(err);
  char cmd[700];
  snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
  ck_assert_int_eq(system(cmd), 0);
  free(dir);
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

/* undump, then dump again on the same file: the new dump continues the series (frames before its
 * first step kept, numbered on), as a run continued from a restart does.  It began again at frame
 * 0 and wrote over the earlier frames, and the index listed only the new ones. */
START_TEST(test_dump_again_continues_series) {
  const char *deck = "material m elastic rho 1000 E 1e9 nu 0.25 plane_stress\nmesh rect b m 0 0 1 0.2 10 2\n"
                     "velocity b set 1 0\ntimestep 1e-5\ndump d h5 10 out.h5\ndump c csv 10 fr\nrun 30\n"
                     "undump d\nundump c\nrun 15\ndump d h5 10 ./out.h5 fields u\ndump c csv 10 fr\nrun 30\n";
  char *err, *dir;
  int rc = yft_run_binary("again.deck", deck, "-log none", &err, &dir);
  ck_assert_msg(rc == 0, "exit %d: %s", rc, err);
  /* its fields differ from the earlier dump's: one series, two field sets (said, at the line) */
  ck_assert_msg(strstr(err, "again.deck:11: warning: dump d: it continues the series of the dump undumped on ./out.h5, "
                            "whose frames hold other fields"), "%s", err);
  char p[600];
  snprintf(p, sizeof p, "%s/out.xmf", dir);
  char *x = yft_slurp(p, 1);
  snprintf(p, sizeof p, "%s/fr_frames.csv", dir);
  char *c = yft_slurp(p, 1);
  /* the steps the index lists, in order: 0 10 20 30 from the first dump, 45 (the new dump's
   * first, at its run's start) 50 60 70 from the second */
  static const long want[] = {0, 10, 20, 30, 45, 50, 60, 70};
  const char *q = x;
  for (int k = 0; k < 8; k++) {
    char name[64];
    snprintf(name, sizeof name, "Name=\"frame_%06d\"", k);
    q = strstr(q, name);
    ck_assert_msg(q, "out.xmf lacks frame %d: %s", k, x);
    const char *st = strstr(q, "<Information Name=\"step\" Value=\"");
    ck_assert_ptr_nonnull(st);
    ck_assert_int_eq(strtol(st + strlen("<Information Name=\"step\" Value=\""), NULL, 10), want[k]);
    char row[64];
    snprintf(row, sizeof row, "\n%d,%ld,", k, want[k]);
    ck_assert_msg(strstr(c, row), "fr_frames.csv lacks row %s: %s", row + 1, c);
  }
  ck_assert_ptr_null(strstr(x, "frame_000008"));
  /* the first dump's frame 0 is still its own (all fields), the new frames have only u */
  snprintf(p, sizeof p, "%s/out_000000.h5", dir);
  hid_t f = H5Fopen(p, H5F_ACC_RDONLY, H5P_DEFAULT);
  ck_assert_int_ge(f, 0);
  ck_assert_int_gt(H5Lexists(f, "/v", H5P_DEFAULT), 0);
  H5Fclose(f);
  snprintf(p, sizeof p, "%s/out_000004.h5", dir);
  f = H5Fopen(p, H5F_ACC_RDONLY, H5P_DEFAULT);
  ck_assert_int_ge(f, 0);
  ck_assert_int_eq(H5Lexists(f, "/v", H5P_DEFAULT), 0);
  H5Fclose(f);
  free(x);
  free(c);
  free(err);
  free(dir);
}
END_TEST

/* A frame file name whose escaped form passes 1023 bytes (230 '&', each "&amp;" in the index) is
 * listed whole: the index named a file cut short, which did not exist. */
START_TEST(test_index_long_escaped_name) {
  char name[256], deck[1024];
  memset(name, '&', 230);
  strcpy(name + 230, ".h5");
  snprintf(deck, sizeof deck, "material m elastic rho 1000 E 1e9 nu 0.25 plane_stress\nmesh rect b m 0 0 1 0.2 4 2\n"
           "timestep auto\ndump d h5 1 '%s'\nrun 1\n", name);
  char *err, *dir;
  int rc = yft_run_binary("n.deck", deck, "-log none", &err, &dir);
  ck_assert_msg(rc == 0, "exit %d: %s", rc, err);
  char p[1200], want[1300];
  memset(name + 230, 0, 1);
  snprintf(p, sizeof p, "%s/%s.xmf", dir, name);
  char *x = yft_slurp(p, 1);
  size_t k = 0;
  for (int i = 0; i < 230; i++) k += (size_t)snprintf(want + k, sizeof want - k, "&amp;");
  snprintf(want + k, sizeof want - k, "_000001.h5:/");
  ck_assert_msg(strstr(x, want) != NULL, "the index does not name frame 1 whole: %.300s", x);
  snprintf(p, sizeof p, "%s/%s_000001.h5", dir, name);
  ck_assert(yft_exists(p));
  free(x);
  free(err);
  free(dir);
}
END_TEST

/* The contact force field fc stays in a series once a frame had it (contact off after a run
 * dropped it from the later frames, so ParaView could not colour the series by it), and 'fields
 * fc' without contact writes zeros (it wrote no field at all). */
START_TEST(test_fc_in_every_frame_after) {
  static const char *const base = "material m elastic rho 1000 E 1e9 nu 0.25 plane_stress pen_n 1e10\n"
                                  "mesh rect a m 0 0 1 0.2 4 2\nmesh rect b m 0 0.25 1 0.45 4 2\n"
                                  "timestep auto\n";
  char deck[1024], *err, *dir, p[700];
  snprintf(deck, sizeof deck, "%sdump d h5 5 o.h5\ncontact pair a b\nrun 10\ncontact off\nrun 10\n", base);
  int rc = yft_run_binary("fc.deck", deck, "-log none", &err, &dir);
  ck_assert_msg(rc == 0, "exit %d: %s", rc, err);
  snprintf(p, sizeof p, "%s/o.xmf", dir);
  char *x = yft_slurp(p, 1);
  int frames = 0, fcs = 0;
  for (const char *q = x; (q = strstr(q, "<Grid Name=\"frame_")); q++) frames++;
  for (const char *q = x; (q = strstr(q, "Name=\"fc\"")); q++) fcs++;
  ck_assert_msg(frames == 5 && fcs == 5, "%d frames, %d with fc", frames, fcs);
  free(x);
  free(err);
  free(dir);
  /* undump, contact off, dump again on the file: the continued series keeps fc (zeros) */
  snprintf(deck, sizeof deck, "%sdump d h5 5 o.h5\ncontact pair a b\nrun 10\ncontact off\nundump d\n"
           "dump d h5 5 o.h5\nrun 10\n", base);
  rc = yft_run_binary("fc4.deck", deck, "-log none", &err, &dir);
  ck_assert_msg(rc == 0, "exit %d: %s", rc, err);
  snprintf(p, sizeof p, "%s/o.xmf", dir);
  x = yft_slurp(p, 1);
  frames = fcs = 0;
  for (const char *q = x; (q = strstr(q, "<Grid Name=\"frame_")); q++) frames++;
  for (const char *q = x; (q = strstr(q, "Name=\"fc\"")); q++) fcs++;
  ck_assert_msg(frames == 5 && fcs == 5, "dump again: %d frames, %d with fc", frames, fcs);
  free(x);
  free(err);
  free(dir);
  /* contact given after the series began: the frames before lack fc (said once) */
  snprintf(deck, sizeof deck, "%sdump d h5 5 o.h5\nrun 10\ncontact pair a b\nrun 10\n", base);
  rc = yft_run_binary("fc3.deck", deck, "-log none", &err, &dir);
  ck_assert_msg(rc == 0 && strstr(err, "warning: dump d: the contact force fc begins at frame 3 (step 15)"), "exit %d: %s",
                rc, err);
  free(err);
  free(dir);
  snprintf(deck, sizeof deck, "%sdump d h5 5 o.h5 fields u fc\nrun 10\n", base);
  rc = yft_run_binary("fc2.deck", deck, "-log none", &err, &dir);
  ck_assert_msg(rc == 0, "exit %d: %s", rc, err);
  snprintf(p, sizeof p, "%s/o.xmf", dir);
  x = yft_slurp(p, 1);
  ck_assert_msg(strstr(x, "Name=\"fc\""), "fields fc without contact: no fc in %.300s", x);
  free(x);
  free(err);
  free(dir);
}
END_TEST

/* ---------------------------------------------------------------- full disk, files whole */

/* Deck text d.deck in tmpdir run at each of nkb sizes of disk: a tmpfs of KB kilobytes in a mount
 * namespace of its own (`unshare -rm`, as check_restart.c's test_full_disk), else a file size
 * limit (RLIMIT_FSIZE in 512-byte blocks, SIGXFSZ ignored: writes fail with EFBIG).  Each run's
 * files, its exit code (code) and its stderr (err.txt) land in tmpdir/oKB. */
static void run_small_disks(const char *deck, const int *kb, int nkb) {
  char cmd[2048];
  yft_put_file(tmpdir, "d.deck", deck);
  snprintf(cmd, sizeof cmd, "unshare -rm sh -c 'mkdir -p %s/t && mount -t tmpfs -o size=64k tmpfs %s/t' 2>/dev/null",
           tmpdir, tmpdir);
  int tmpfs = system(cmd) == 0;
  for (int i = 0; i < nkb; i++) {
    char out[128];
    snprintf(out, sizeof out, "%s/o%d", tmpdir, kb[i]);
    ck_assert_int_eq(mkdir(out, 0755), 0);
    if (tmpfs)
      snprintf(cmd, sizeof cmd,
               "cd %s && unshare -rm sh -c 'mkdir -p t && mount -t tmpfs -o size=%dk tmpfs t && cd t && "
               "OMP_NUM_THREADS=1 %s -in ../d.deck >/dev/null 2>../o%d/err.txt; echo $? > ../o%d/code; cp -a . ../o%d/'",
               tmpdir, kb[i], yft_binary(), kb[i], kb[i], kb[i]);
    else
      snprintf(cmd, sizeof cmd,
               "cd %s && sh -c 'ulimit -f %d; trap \"\" XFSZ; OMP_NUM_THREADS=1 exec %s -in ../d.deck >/dev/null "
               "2>err.txt'; echo $? > code",
               out, 2 * kb[i], yft_binary());
    ck_assert_int_eq(system(cmd), 0);
  }
}

/* The exit code and stderr of the run at KB kilobytes (run_small_disks); *err: caller frees. */
static int small_disk_result(int kb, char **err) {
  char path[256];
  snprintf(path, sizeof path, "%s/o%d/code", tmpdir, kb);
  char *c = slurp(path);
  int code = atoi(c);
  free(c);
  snprintf(path, sizeof path, "%s/o%d/err.txt", tmpdir, kb);
  *err = slurp(path);
  return code;
}

/* A y2dref dump on a full disk: exit 2 with the cause, and every file it leaves is whole: each
 * corner table its header and a row for each corner of the 40 triangles, each of summary.csv,
 * probes.csv and broken.csv its header and whole rows, no NAME.tmp.  A corner table cut at 4096
 * bytes mid-row was left under its own name, and the tables of rows ended mid-row or empty (their
 * headers still in stdio's buffer) (a tester's full disk, 2026-11-28). */
START_TEST(test_y2dref_full_disk) {
  mk_tmpdir();
  static const int kb[] = {12, 16, 20, 24, 28, 36, 44, 60};
  const int n = (int)(sizeof kb / sizeof *kb);
  run_small_disks("material m elastic rho 1000 E 1e9 nu 0.25 plane_stress\nmesh rect b m 0 0 1 0.2 10 2\n"
                  "velocity b set 1 0\ntimestep auto\nthermo 1000\n"
                  "dump r y2dref ref corners 1,2,3,4,5,6,7,8,9,10,11,12,13,14,15,16,17,18,19,20 summary 1 probes 1 1:0 3:2\n"
                  "run 20\n",
                  kb, n);
  for (int i = 0; i < n; i++) {
    char *e, cmd[1024];
    int code = small_disk_result(kb[i], &e);
    ck_assert_msg(code == YF_EXIT_IO, "%d KB: exit %d: %s", kb[i], code, e);
    ck_assert_msg(strstr(e, "error: dump y2dref: cannot write 'ref/") &&
                  (strstr(e, "No space left on device") || strstr(e, "File too large")), "%d KB: %s", kb[i], e);
    free(e);
    snprintf(cmd, sizeof cmd, "ls -R %s/o%d | grep -q '\\.tmp$'", tmpdir, kb[i]);
    ck_assert_msg(system(cmd) != 0, "%d KB: a NAME.tmp is left", kb[i]);
    snprintf(cmd, sizeof cmd,
             "cd %s/o%d/ref 2>/dev/null || exit 0; for f in *.csv; do [ -e \"$f\" ] || continue; "
             "[ -s \"$f\" ] && [ \"$(tail -c 1 \"$f\" | od -An -c | tr -d ' ')\" = '\\n' ] || { echo \"$f\"; exit 1; }; "
             "case \"$f\" in corners_*) [ \"$(wc -l < \"$f\")\" = 121 ] || { echo \"$f\"; exit 1; };; "
             "summary.csv) head -n 1 \"$f\" | grep -q '^step,time,kinetic' || { echo \"$f\"; exit 1; };; "
             "probes.csv) head -n 1 \"$f\" | grep -q '^step,time,ux_1_0' || { echo \"$f\"; exit 1; };; esac; done",
             tmpdir, kb[i]);
    ck_assert_msg(system(cmd) == 0, "%d KB: a file of the y2dref dump is not whole", kb[i]);
  }
  rm_tmpdir();
}
END_TEST

/* A record on a full disk: exit 2 with the cause, and the file ends at its last complete row
 * (each row as many columns as the header, the last ended by its newline): a row cut mid-number
 * was left at its end (a tester's full disk, 2026-11-28). */
START_TEST(test_record_full_disk) {
  mk_tmpdir();
  static const int kb[] = {8, 12, 16, 20, 24};
  const int n = (int)(sizeof kb / sizeof *kb);
  run_small_disks("material m elastic rho 1000 E 1e9 nu 0.25 plane_stress\nmesh rect b m 0 0 1 0.2 10 2\n"
                  "velocity b set 1 0\ntimestep auto\nthermo 100000\nrecord q 1 r.csv ke strain\nrun 2000\n",
                  kb, n);
  for (int i = 0; i < n; i++) {
    char *e, cmd[1024];
    int code = small_disk_result(kb[i], &e);
    ck_assert_msg(code == YF_EXIT_IO, "%d KB: exit %d: %s", kb[i], code, e);
    ck_assert_msg(strstr(e, "record q: cannot write 'r.csv'") &&
                  (strstr(e, "No space left on device") || strstr(e, "File too large")), "%d KB: %s", kb[i], e);
    free(e);
    snprintf(cmd, sizeof cmd,
             "cd %s/o%d && [ -s r.csv ] && [ \"$(tail -c 1 r.csv | od -An -c | tr -d ' ')\" = '\\n' ] && "
             "head -n 1 r.csv | grep -qx 'step,time,ke,strain' && awk -F, 'NF != 4 { exit 1 }' r.csv",
             tmpdir, kb[i]);
    ck_assert_msg(system(cmd) == 0, "%d KB: r.csv does not end at a complete row", kb[i]);
  }
  rm_tmpdir();
}
END_TEST

/* A csv dump on a full disk: exit 2 with the cause, and its index PREFIX_frames.csv ends at its
 * last complete row (its header, then rows of 4 fields, the last ended by its newline), as a
 * record's file.  Written through stdio, the index ended mid-row when the disk filled while its
 * row went in (the unwritten tail of the failed fflush).  The index row is long (a long prefix) and
 * the disk sizes span more than a page of index rows, so at some sizes the index is what fills
 * the disk, not a frame: that is asserted, or the test would prove nothing. */
START_TEST(test_csv_index_full_disk) {
  mk_tmpdir();
  static int kb[25];
  const int n = (int)(sizeof kb / sizeof *kb);
  for (int i = 0; i < n; i++) kb[i] = 64 + 4 * i;
  char prefix[201], deck[1024];
  memset(prefix, 'c', 200);
  prefix[200] = 0;
  snprintf(deck, sizeof deck, "material m elastic rho 1000 E 1e9 nu 0.25 plane_stress\nmesh rect b m 0 0 1 0.2 2 1\n"
           "velocity b set 1 0\ntimestep auto\nthermo 100000\ndump c csv 1 %s\nrun 2000\n", prefix);
  run_small_disks(deck, kb, n);
  int index_full = 0;
  for (int i = 0; i < n; i++) {
    char *e, cmd[1024];
    int code = small_disk_result(kb[i], &e);
    ck_assert_msg(code == YF_EXIT_IO, "%d KB: exit %d: %.200s", kb[i], code, e);
    ck_assert_msg(strstr(e, "error: dump c: cannot write '") &&
                  (strstr(e, "No space left on device") || strstr(e, "File too large")), "%d KB: %.200s", kb[i], e);
    index_full += strstr(e, "_frames.csv': ") != NULL;
    free(e);
    snprintf(cmd, sizeof cmd,
             "cd %s/o%d && f=%s_frames.csv && [ -s $f ] && [ \"$(tail -c 1 $f | od -An -c | tr -d ' ')\" = '\\n' ] && "
             "head -n 1 $f | grep -qx 'frame,step,time,file' && awk -F, 'NF != 4 { exit 1 }' $f",
             tmpdir, kb[i], prefix);
    ck_assert_msg(system(cmd) == 0, "%d KB: PREFIX_frames.csv does not end at a complete row", kb[i]);
  }
  ck_assert_msg(index_full > 0, "no disk size filled up on the index");
  rm_tmpdir();
}
END_TEST

/* A frame or an index that cannot be renamed into place (a directory there; an immutable file
 * does the same): exit 2 naming it, and no NAME.tmp left beside the frames (README: "no
 * half-written NAME.tmp is left"); it was, complete but under its .tmp name.  The index lists only
 * frames that are there.  A folder named as the crack index is refused at the dump's line, as one
 * named as the index is (it failed the first frame, that frame's file left unlisted). */
START_TEST(test_rename_refused_no_tmp_left) {
  static const char *const in_way[] = {"out_000002.h5", "out_cracks.xmf"};
  for (int k = 0; k < 2; k++) {
    char *dir = yft_deck_dir("f.deck", "material m elastic rho 1000 E 1e9 nu 0.25 plane_stress\n"
                                       "mesh rect bar m 0 0 1 0.1 4 2\njointprop cj ft 1e5 fs 1e5 gf 1 pen 1e10 law munjiza\n"
                                       "fracture bar cj\ntimestep auto\ndump a h5 1 out.h5\nrun 4\n");
    char cmd[2048], p[600];
    snprintf(cmd, sizeof cmd, "cd %s && mkdir %s && %s f.deck >/dev/null 2>err.txt", dir, in_way[k], yft_binary());
    int st = system(cmd), code = WIFEXITED(st) ? WEXITSTATUS(st) : 128;
    snprintf(p, sizeof p, "%s/err.txt", dir);
    char *e = yft_slurp(p, 1), want[128];
    snprintf(want, sizeof want, "%s'%s': Is a directory", k ? "f.deck:6: error: dump a: cannot write " : "to ", in_way[k]);
    ck_assert_msg(code == YF_EXIT_IO && strstr(e, want), "%s in the way: exit %d: %s", in_way[k], code, e);
    free(e);
    snprintf(cmd, sizeof cmd, "cd %s && ls | grep '\\.tmp$'", dir);
    ck_assert_msg(system(cmd) != 0, "%s in the way: a .tmp file was left", in_way[k]);
    /* every frame out.xmf lists is there */
    snprintf(cmd, sizeof cmd, "cd %s && [ ! -e out.xmf ] || for f in $(grep -o 'out_[0-9]*\\.h5' out.xmf | sort -u); do "
             "[ -f $f ] || exit 1; done", dir);
    ck_assert_msg(system(cmd) == 0, "%s in the way: out.xmf lists a frame that is not there", in_way[k]);
    snprintf(cmd, sizeof cmd, "chmod -R u+w %s; rm -rf %s", dir, dir);
    if (system(cmd)) {}
    free(dir);
  }
}
END_TEST

/* A y2dref dump whose table is a folder in its folder (yd/probes.csv/): exit 2 at the dump's line
 * naming the table.  It was found at the run's first step, without the line, after the other
 * outputs began (summary.csv was checked at the line, but named the folder: "cannot write in
 * directory 'yd'"). */
START_TEST(test_y2dref_table_in_way) {
  static const char *const table[] = {"summary.csv", "probes.csv", "broken.csv"};
  for (int k = 0; k < 3; k++) {
    char *dir = yft_deck_dir("f.deck", "material m elastic rho 1000 E 1e9 nu 0.25 plane_stress\n"
                                       "mesh rect bar m 0 0 1 0.1 4 2\ntimestep auto\n"
                                       "dump y y2dref yd summary 1 probes 1 1:0\nrun 2\n");
    char cmd[1600], p[600];
    snprintf(cmd, sizeof cmd, "cd %s && mkdir -p yd/%s && %s f.deck >/dev/null 2>err.txt", dir, table[k], yft_binary());
    int st = system(cmd), rc = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
    snprintf(p, sizeof p, "%s/err.txt", dir);
    char *err = yft_slurp(p, 1), want[200];
    snprintf(want, sizeof want, "f.deck:4: error: dump y: cannot write 'yd/%s': Is a directory", table[k]);
    ck_assert_msg(rc == YF_EXIT_IO && strstr(err, want), "%s: exit %d: %s", table[k], rc, err);
    free(err);
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    ck_assert_int_eq(system(cmd), 0);
    free(dir);
  }
}
END_TEST

/* A folder where a frame or the index is written before its rename (out.xmf.tmp/): the error at
 * the dump's line names it; it said "cannot write 'out.xmf': Is a directory" with no out.xmf
 * there. */
START_TEST(test_tmp_in_way_named) {
  static const char *const tmp[] = {"out.xmf.tmp", "out_000000.h5.tmp", "r.a.tmp"};
  for (int k = 0; k < 3; k++) {
    char *dir = yft_deck_dir("f.deck", "material m elastic rho 1000 E 1e9 nu 0.25 plane_stress\n"
                                       "mesh rect bar m 0 0 1 0.1 4 2\ntimestep auto\n"
                                       "dump d h5 1 out.h5\nrestart every 2 r\nrun 2\n");
    char cmd[1600], p[600];
    snprintf(cmd, sizeof cmd, "cd %s && mkdir %s && %s f.deck >/dev/null 2>err.txt", dir, tmp[k], yft_binary());
    int st = system(cmd), rc = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
    snprintf(p, sizeof p, "%s/err.txt", dir);
    char *err = yft_slurp(p, 1), want[200];
    snprintf(want, sizeof want, "'%s', where it is written before it is renamed, is in the way: Is a directory", tmp[k]);
    ck_assert_msg(rc == YF_EXIT_IO && strstr(err, want), "%s: exit %d: %s", tmp[k], rc, err);
    free(err);
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    ck_assert_int_eq(system(cmd), 0);
    free(dir);
  }
}
END_TEST

/* A run continued by read_restart takes up its outputs' earlier rows by reading them: a record on
 * /dev/stdout piped to another program ('yfdem c.deck | tee') was read too, which waited for ever
 * for a writer (yfdem itself), hanging the run at its start.  Only a regular file is taken up. */
START_TEST(test_continued_run_output_on_pipe) {
  static const char head[] = "material m elastic rho 1000 E 1e9 nu 0.25 plane_stress\nmesh rect bar m 0 0 1 0.1 4 2\n"
                             "timestep auto\nvelocity bar set 1 0\nrecord r 1 /dev/stdout step ke\n";
  char deck[512];
  snprintf(deck, sizeof deck, "%srun 5\nwrite_restart r.h5\n", head);
  char *dir = yft_deck_dir("a.deck", deck);
  snprintf(deck, sizeof deck, "%sread_restart r.h5\nrun 8 upto\n", head);
  yft_put_file(dir, "c.deck", deck);
  char cmd[2048], p[600];
  snprintf(cmd, sizeof cmd, "cd %s && %s a.deck >/dev/null 2>&1 && { timeout -s KILL 20 %s c.deck 2>err.txt; "
           "echo $? > code; } | cat > out.txt", dir, yft_binary(), yft_binary());
  ck_assert_int_eq(system(cmd), 0);
  snprintf(p, sizeof p, "%s/code", dir);
  char *code = yft_slurp(p, 1);
  snprintf(p, sizeof p, "%s/out.txt", dir);
  char *out = yft_slurp(p, 1);
  /* 1000 kg/m^3 x 0.1 m^2 at 1 m/s: ke = 50 J/m */
  ck_assert_msg(atoi(code) == 0 && strstr(out, "step,time,step,ke\n") && strstr(out, "\n8,"),
                "exit %s (137: killed waiting), stdout:\n%s", code, out);
  free(code);
  free(out);
  snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
  ck_assert_int_eq(system(cmd), 0);
  free(dir);
}
END_TEST

/* An output named on a FIFO that no process reads: exit 2 at once, naming the file and why.  It
 * waited for a reader for ever at the output's first write (a record's first row, the log at the
 * start), deaf to Ctrl-C and SIGTERM, since a plain open of a FIFO blocks until a reader opens it.
 * With a reader the rows still stream through it (the reader gets the record's rows whole). */
START_TEST(test_fifo_without_reader) {
  static const struct { const char *setup, *lines, *args, *file; } cases[] = {
      {"mkfifo r.csv", "record r 1 r.csv step ke\n", "", "r.csv"},
      {"mkfifo c_frames.csv", "dump c csv 1 c\n", "", "c_frames.csv"},
      {"mkfifo b.csv", "fracture_log b.csv\n", "", "b.csv"},
      {"mkfifo m.csv", "metrics body bar\nmetrics log m.csv\n", "", "m.csv"},
      {"mkdir yd && mkfifo yd/summary.csv", "dump y y2dref yd summary 1\n", "", "yd/summary.csv"},
      {"mkfifo lg", "", "-log lg", "lg"},
      {"mkfifo s.json", "", "-summary s.json", "s.json"},
  };
  for (size_t k = 0; k < sizeof cases / sizeof *cases; k++) {
    char deck[1024];
    snprintf(deck, sizeof deck, "material m elastic rho 1000 E 1e9 nu 0.25 plane_stress\nmesh rect bar m 0 0 1 0.1 4 2\n"
             "jointprop cj ft 1e5 fs 1e5 gf 1 pen 1e10 law munjiza\nfracture bar cj\ntimestep auto\n%srun 4\n",
             cases[k].lines);
    char *dir = yft_deck_dir("f.deck", deck), cmd[2048];
    /* KILL after 20 s: a process stuck in open() would outlive the test */
    snprintf(cmd, sizeof cmd, "cd %s && %s && timeout -s KILL 20 %s %s f.deck >/dev/null 2>err.txt", dir,
             cases[k].setup, yft_binary(), cases[k].args);
    int st = system(cmd), code = WIFEXITED(st) ? WEXITSTATUS(st) : 128;
    char p[600];
    snprintf(p, sizeof p, "%s/err.txt", dir);
    char *e = yft_slurp(p, 1);
    char want[128];
    snprintf(want, sizeof want, "'%s': no process reads this FIFO", cases[k].file);
    ck_assert_msg(code == YF_EXIT_IO && strstr(e, want), "%s: exit %d (137: killed waiting): %s", cases[k].file, code, e);
    free(e);
    snprintf(cmd, sizeof cmd, "rm -rf %s", dir);
    if (system(cmd)) {}
    free(dir);
  }
  /* with its reader: the record's rows go through whole */
  char *dir = yft_deck_dir("f.deck", "material m elastic rho 1000 E 1e9 nu 0.25 plane_stress\n"
                                     "mesh rect bar m 0 0 1 0.1 4 2\ntimestep auto\nrecord r 1 r.csv step ke\nrun 4\n");
  char cmd[2048];
  snprintf(cmd, sizeof cmd, "cd %s && mkfifo r.csv && { cat r.csv > got.txt & } && sleep 0.2 && "
           "timeout -s KILL 20 %s f.deck >/dev/null 2>err.txt; rc=$?; wait; exit $rc", dir, yft_binary());
  int st = system(cmd);
  char p[600];
  snprintf(p, sizeof p, "%s/err.txt", dir);
  char *e = yft_slurp(p, 1);
  ck_assert_msg(WIFEXITED(st) && WEXITSTATUS(st) == 0, "with a reader: status %d: %s", st, e);
  free(e);
  snprintf(p, sizeof p, "%s/got.txt", dir);
  char *got = yft_slurp(p, 1);
  ck_assert_msg(!strncmp(got, "step,time,step,ke\n0,0,0,0\n", 26) && strstr(got, "\n4,"), "the reader got: %s", got);
  free(got);
  snprintf(cmd, sizeof cmd, "rm -rf %s", dir);
  if (system(cmd)) {}
  free(dir);
}
END_TEST

/* An output sent to yfdem's own standard output (/dev/stdout, with 'yfdem ... > out.txt') is
 * appended to what was printed: it was opened with truncation, which cut out.txt to zero under
 * the stream's position: the lines printed before the output's first write were lost or became a
 * run of NUL bytes (grep took out.txt for a binary file). */
START_TEST(test_output_to_own_stdout) {
  static const struct { const char *line, *args, *want; } cases[] = {
      {"record r 1 /dev/stdout step ke\n", "", "step,time,step,ke\n0,0,0,0\n"},
      {"", "-summary /dev/stdout", "\"status\": \"ok\""},
      {"", "-log /dev/stdout", "run 2\n"},
  };
  for (size_t k = 0; k < sizeof cases / sizeof *cases; k++) {
    char deck[512];
    snprintf(deck, sizeof deck, "material m elastic rho 1000 E 1e9 nu 0.25 plane_stress\nmesh rect bar m 0 0 1 0.1 4 2\n"
             "timestep auto\n%srun 2\n", cases[k].line);
    char *dir = yft_deck_dir("f.deck", deck), cmd[2048], p[600];
    snprintf(cmd, sizeof cmd, "cd %s && %s %s f.deck >out.txt 2>&1", dir, yft_binary(), cases[k].args);
    int st = system(cmd);
    snprintf(p, sizeof p, "%s/out.txt", dir);
    size_t n = 0;
    FILE *f = fopen(p, "rb");
    ck_assert_ptr_nonnull(f);
    char *text = calloc(1, 1 << 20);
    n = fread(text, 1, (1 << 20) - 1, f);
    fclose(f);
    ck_assert_msg(WIFEXITED(st) && WEXITSTATUS(st) == 0, "case %zu: status %d: %s", k, st, text);
    ck_assert_msg(strlen(text) == n, "case %zu: a NUL byte at %zu of %zu in out.txt", k, strlen(text), n);
    ck_assert_msg(strstr(text, "timestep auto: dt =") && strstr(text, cases[k].want),
                  "case %zu: out.txt lacks the lines printed before, or the output:\n%s", k, text);
    free(text);
    snprintf(cmd, sizeof cmd, "rm -rf %s", dir);
    if (system(cmd)) {}
    free(dir);
  }
}
END_TEST

/* The log on a full disk: exit 2 with the cause when it fills, and a summary (elsewhere) that says
 * io_error with that reason.  The run went on to its end, its summary said "ok" next to exit 2,
 * and the message gave a stale errno ("No such file or directory"). */
START_TEST(test_log_full_disk) {
  mk_tmpdir();
  yft_put_file(tmpdir, "d.deck", "material m elastic rho 1000 E 1e9 nu 0.25 plane_stress\nmesh rect b m 0 0 1 0.2 4 2\n"
                                 "timestep auto\nthermo 1\nrun 20000\n");
  char cmd[2048];
  snprintf(cmd, sizeof cmd, "unshare -rm sh -c 'mkdir -p %s/t && mount -t tmpfs -o size=64k tmpfs %s/t' 2>/dev/null",
           tmpdir, tmpdir);
  if (system(cmd) != 0) { /* no mount namespace here: nothing to fill */
    rm_tmpdir();
    return;
  }
  snprintf(cmd, sizeof cmd,
           "cd %s && unshare -rm sh -c 'mkdir -p t && mount -t tmpfs -o size=16k tmpfs t && "
           "OMP_NUM_THREADS=1 %s -in d.deck -log t/log.txt -summary s.json >/dev/null 2>err.txt; echo $? > code'",
           tmpdir, yft_binary());
  ck_assert_int_eq(system(cmd), 0);
  char p[300];
  snprintf(p, sizeof p, "%s/code", tmpdir);
  char *c = slurp(p), *e, *js;
  snprintf(p, sizeof p, "%s/err.txt", tmpdir);
  e = slurp(p);
  snprintf(p, sizeof p, "%s/s.json", tmpdir);
  js = slurp(p);
  ck_assert_msg(atoi(c) == YF_EXIT_IO && strstr(e, "-log: cannot write 't/log.txt': No space left on device"),
                "exit %s: %s", c, e);
  ck_assert_msg(js && strstr(js, "\"status\": \"io_error\"") && strstr(js, "No space left on device"), "summary: %s", js);
  /* it stopped when the log filled (16 KB hold about 130 thermo lines), not at the run's end */
  const char *st = strstr(js, "\"steps\": ");
  ck_assert_msg(st && atol(st + 9) < 20000, "summary: %s", js);
  free(c);
  free(e);
  free(js);
  rm_tmpdir();
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
  tcase_add_test(tc, test_long_series_index);
  tcase_add_test(tc, test_dump_again_continues_series);
  tcase_add_test(tc, test_index_long_escaped_name);
  tcase_add_test(tc, test_fc_in_every_frame_after);
  tcase_add_test(tc, test_deck_dump_errors);
  tcase_add_test(tc, test_dump_prefix_names_a_file);
  tcase_add_test(tc, test_claims_through_links);
  tcase_add_test(tc, test_csv_fields_with_commas);
  tcase_add_test(tc, test_h5_name_not_utf8);
  tcase_add_test(tc, test_io_error);
  tcase_add_test(tc, test_kill_midway);
  suite_add_tcase(su, tc);
  tc = tcase_create("full disk");
  tcase_set_timeout(tc, 120);
  tcase_add_test(tc, test_y2dref_full_disk);
  tcase_add_test(tc, test_record_full_disk);
  tcase_add_test(tc, test_csv_index_full_disk);
  tcase_add_test(tc, test_log_full_disk);
  suite_add_tcase(su, tc);
  tc = tcase_create("summary");
  tcase_set_timeout(tc, 120); /* (the FIFO and pipe cases kill a yfdem stuck waiting after 20 s) */
  tcase_add_test(tc, test_summary_keys);
  tcase_add_test(tc, test_summary_nonfinite);
  tcase_add_test(tc, test_summary_escaping);
  tcase_add_test(tc, test_summary_region_name_escaped);
  tcase_add_test(tc, test_state_hash);
  tcase_add_test(tc, test_fifo_without_reader);
  tcase_add_test(tc, test_rename_refused_no_tmp_left);
  tcase_add_test(tc, test_y2dref_table_in_way);
  tcase_add_test(tc, test_tmp_in_way_named);
  tcase_add_test(tc, test_output_to_own_stdout);
  tcase_add_test(tc, test_continued_run_output_on_pipe);
  suite_add_tcase(su, tc);
  return su;
}
