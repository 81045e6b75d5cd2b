/* check_mesh.c: meshes and sets (mesh.c, gmsh.c, region.c) through the C API.
 *
 * Handlers are called with YfArgs built by hand from a command line, on a fresh model per test.
 * Geometric facts are exact or to round-off: the triangles of a mesh tile their domain, so the
 * areas add up to the domain's area (1e-12 relative), every interior edge is shared by exactly two
 * triangles, and the boundary edges add up to the perimeter with outward normals (dy, -dx).
 * Failures run in a forked child whose stderr is captured, and each checks the exit code, the
 * FILE:LINE of the offending .msh / data line and the message.
 *
 * The Gmsh tests use decks/meshes/two_squares.msh (made by gmsh 4.8 from two_squares.geo),
 * its parametric twin, and square4.msh (hand-written: a unit square cut into 4 triangles
 * around its centre, two physical surfaces, a physical curve, one triangle clockwise).
 * Paths are taken relative to the working directory (the repository root under `make check`).
 */
#include <check.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "deck.h"
#include "edgesort.h"
#include "commands.h"
#include "mesh.h"
#include "model.h"
#include "query.h"
#include "region.h"
#include "sim.h"
#include "summary.h"
#include "yftest.h"

/* ------------------------------------------------------------------ helpers */

static YfSim *new_sim(void) {
  YfSim *s = calloc(1, sizeof *s);
  model_init(&s->model);
  mesh_reset();
  region_reset();
  return s;
}

static void free_sim(YfSim *s) {
  mesh_reset();
  region_reset();
  model_free(&s->model);
  free(s);
}

/* Split line into words (no quoting needed by these tests) and call fn as the deck would. */
static void run(YfSim *s, YfCmdFn fn, const char *cmd, const char *line) {
  static char buf[8192], full[8300];
  static char *w[512];
  snprintf(buf, sizeof buf, "%s", line);
  snprintf(full, sizeof full, "%s %s", cmd, line);
  int n = 0;
  for (char *t = strtok(buf, " \t"); t; t = strtok(NULL, " \t")) w[n++] = t;
  YfArgs a = {.cmd = cmd, .n = n, .w = w, .loc = {"test.deck", 7}, .line = full};
  fn(s, &a);
}

/* Run a command in a child; return its exit status and captured stderr (static buffer). */
static int run_child(YfSim *s, YfCmdFn fn, const char *cmd, const char *line, char **err) {
  static char out[8192];
  int p[2];
  ck_assert_int_eq(pipe(p), 0);
  fflush(stdout);
  fflush(stderr);
  pid_t pid = fork();
  ck_assert_int_ge(pid, 0);
  if (pid == 0) {
    close(p[0]);
    dup2(p[1], 2);
    run(s, fn, cmd, line);
    fflush(stderr);
    _exit(0);
  }
  close(p[1]);
  size_t n = 0;
  ssize_t k;
  while ((k = read(p[0], out + n, sizeof out - 1 - n)) > 0) n += (size_t)k;
  out[n] = '\0';
  close(p[0]);
  int st;
  waitpid(pid, &st, 0);
  *err = out;
  return WIFEXITED(st) ? WEXITSTATUS(st) : 128 + WTERMSIG(st);
}

#define EXPECT_FAIL(s, fn, cmd, line, code, ...)                                                   \
  do {                                                                                             \
    char *err_;                                                                                    \
    int rc_ = run_child(s, fn, cmd, line, &err_);                                                  \
    ck_assert_msg(rc_ == (code), "'%s %s': exit %d, expected %d; stderr: %s", cmd, line, rc_,      \
                  code, err_);                                                                     \
    const char *want_[] = {__VA_ARGS__, NULL};                                                     \
    for (int i_ = 0; want_[i_]; i_++)                                                              \
      ck_assert_msg(strstr(err_, want_[i_]), "'%s %s': stderr lacks \"%s\": %s", cmd, line,        \
                    want_[i_], err_);                                                              \
  } while (0)

static char tmpdir[256];
static const char *tmp_path(const char *name) {
  static char p[512];
  if (!tmpdir[0]) {
    snprintf(tmpdir, sizeof tmpdir, "/tmp/yf_check_mesh_XXXXXX");
    ck_assert_ptr_nonnull(mkdtemp(tmpdir));
  }
  snprintf(p, sizeof p, "%s/%s", tmpdir, name);
  return p;
}

static const char *write_tmp(const char *name, const char *text) {
  const char *p = tmp_path(name);
  FILE *fp = fopen(p, "w");
  ck_assert_ptr_nonnull(fp);
  fputs(text, fp);
  fclose(fp);
  return p;
}

/* Absolute path of a file of the repository (tests run from its root). */
static const char *repo_path(const char *rel) {
  static char p[1024];
  char cwd[700];
  ck_assert_ptr_nonnull(getcwd(cwd, sizeof cwd));
  snprintf(p, sizeof p, "%s/%s", cwd, rel);
  ck_assert_msg(access(p, R_OK) == 0, "missing test file %s (run from the repository root)", p);
  return p;
}

static double tri_area(const YfModel *m, int t) { return 0.5 * model_tri_d(m, t, 0); }

static double total_area(const YfModel *m, int body) {
  double a = 0;
  for (int t = 0; t < m->tri.n; t++)
    if (body < 0 || m->tri.body[t] == body) a += tri_area(m, t);
  return a;
}

static void assert_all_ccw(const YfModel *m) {
  for (int t = 0; t < m->tri.n; t++) ck_assert_msg(model_tri_d(m, t, 0) > 0, "triangle %d is not CCW", t);
}

/* Number of triangles sharing each edge: returns how many edges have 1, 2 and more uses. */
static void edge_use(const YfModel *m, int *n1, int *n2, int *nmore) {
  int ne = 3 * m->tri.n;
  long long *key = malloc((size_t)ne * sizeof *key);
  for (int t = 0; t < m->tri.n; t++)
    for (int k = 0; k < 3; k++) {
      long long a = m->tri.v[3 * t + k], b = m->tri.v[3 * t + (k + 1) % 3];
      key[3 * t + k] = a < b ? a * 100000000LL + b : b * 100000000LL + a;
    }
  *n1 = *n2 = *nmore = 0;
  for (int i = 0; i < ne; i++) {
    int c = 0, first = 1;
    for (int j = 0; j < ne; j++)
      if (key[j] == key[i]) {
        c++;
        if (j < i) first = 0;
      }
    if (!first) continue;
    if (c == 1) (*n1)++;
    else if (c == 2) (*n2)++;
    else (*nmore)++;
  }
  free(key);
}

static int count_nodes(const YfModel *m, int g) {
  int c = 0;
  for (int i = 0; i < m->node.n; i++) c += (m->node.gmask[i] >> g) & 1;
  return c;
}
static int count_tris(const YfModel *m, int g) {
  int c = 0;
  for (int t = 0; t < m->tri.n; t++) c += (m->tri.gmask[t] >> g) & 1;
  return c;
}

/* Sum of boundary edge lengths of group g; checks each normal (dy, -dx) points away from c. */
static double boundary_length(const YfModel *m, int g, double cx, double cy, int *count) {
  int *e;
  int n = mesh_boundary_edges(m, (uint64_t)1 << g, &e);
  double L = 0;
  for (int i = 0; i < n; i++) {
    int a = e[2 * i], b = e[2 * i + 1];
    double dx = m->node.x0[b] - m->node.x0[a], dy = m->node.y0[b] - m->node.y0[a];
    double mx = 0.5 * (m->node.x0[a] + m->node.x0[b]) - cx, my = 0.5 * (m->node.y0[a] + m->node.y0[b]) - cy;
    ck_assert_msg(dy * mx - dx * my > 0, "edge %d-%d: normal points inwards", a, b);
    L += hypot(dx, dy);
  }
  free(e);
  *count = n;
  return L;
}

/* ------------------------------------------------------------------ mesh rect */

START_TEST(test_rect_patterns) {
  static const char *pats[] = {"right", "left", "alt", "cross"};
  const int nx = 3, ny = 2;
  const double x0 = 0.5, y0 = -1.0, x1 = 2.0, y1 = 0.5, A = 1.5 * 1.5;
  for (int p = 0; p < 4; p++) {
    YfSim *s = new_sim();
    YfModel *m = &s->model;
    model_add_material(m, "steel");
    char line[256];
    snprintf(line, sizeof line, "rect plate steel %g %g %g %g %d %d pattern %s", x0, y0, x1, y1, nx, ny, pats[p]);
    run(s, cmd_mesh, "mesh", line);
    int cross = p == 3;
    ck_assert_int_eq(m->node.n, (nx + 1) * (ny + 1) + (cross ? nx * ny : 0));
    ck_assert_int_eq(m->tri.n, (cross ? 4 : 2) * nx * ny);
    assert_all_ccw(m);
    ck_assert_double_eq_tol(total_area(m, -1), A, 1e-12 * A);
    /* Euler: E = V + F - 1 for a disc; boundary edges = 2 (nx + ny) */
    int n1, n2, nmore;
    edge_use(m, &n1, &n2, &nmore);
    ck_assert_int_eq(nmore, 0);
    ck_assert_int_eq(n1, 2 * (nx + ny));
    ck_assert_int_eq(n1 + n2, m->node.n + m->tri.n - 1);
    /* row-by-row numbering with exact edges */
    for (int j = 0; j <= ny; j++)
      for (int i = 0; i <= nx; i++) {
        int k = j * (nx + 1) + i;
        ck_assert_double_eq_tol(m->node.x0[k], x0 + (x1 - x0) * i / nx, 1e-15);
        ck_assert_double_eq_tol(m->node.y0[k], y0 + (y1 - y0) * j / ny, 1e-15);
        ck_assert_int_eq(m->node.id[k], k + 1);
      }
    ck_assert(m->node.x0[nx] == x1 && m->node.y0[(nx + 1) * (ny + 1) - 1] == y1);
    if (cross) { /* centre of cell (1, 1) */
      int c = (nx + 1) * (ny + 1) + 1 * nx + 1;
      ck_assert_double_eq_tol(m->node.x0[c], x0 + 1.5 * 0.5, 1e-15);
      ck_assert_double_eq_tol(m->node.y0[c], y0 + 1.5 * 0.75, 1e-15);
    }
    /* body, material, group named after the body holding everything */
    ck_assert_int_eq(m->nbody, 1);
    int g = model_group(m, "plate", 0);
    ck_assert_int_ge(g, 0);
    ck_assert_int_eq(count_nodes(m, g), m->node.n);
    ck_assert_int_eq(count_tris(m, g), m->tri.n);
    for (int t = 0; t < m->tri.n; t++) ck_assert_int_eq(m->tri.mat[t], 0);
    /* boundary of the whole body = perimeter, normals outward */
    int nb;
    double L = boundary_length(m, g, 0.5 * (x0 + x1), 0.5 * (y0 + y1), &nb);
    ck_assert_int_eq(nb, 2 * (nx + ny));
    ck_assert_double_eq_tol(L, 6.0, 1e-12 * 6.0);
    free_sim(s);
  }
}
END_TEST

/* The diagonals of the patterns: which corner pairs of the first two cells are edges. */
static int has_edge(const YfModel *m, int a, int b) {
  for (int t = 0; t < m->tri.n; t++)
    for (int k = 0; k < 3; k++) {
      int p = m->tri.v[3 * t + k], q = m->tri.v[3 * t + (k + 1) % 3];
      if ((p == a && q == b) || (p == b && q == a)) return 1;
    }
  return 0;
}

START_TEST(test_rect_diagonals) {
  static const char *pats[] = {"right", "left", "alt"};
  /* cell (0,0): corners 0, 1, 5, 4 (nx = 3 -> row length 4); cell (1,0): 1, 2, 6, 5 */
  static const int want[3][4] = {{1, 0, 1, 0}, {0, 1, 0, 1}, {1, 0, 0, 1}};
  for (int p = 0; p < 3; p++) {
    YfSim *s = new_sim();
    model_add_material(&s->model, "steel");
    char line[128];
    snprintf(line, sizeof line, "rect b steel 0 0 3 1 3 1 pattern %s", pats[p]);
    run(s, cmd_mesh, "mesh", line);
    const YfModel *m = &s->model;
    ck_assert_int_eq(has_edge(m, 0, 5), want[p][0]); /* cell 0, lower-left to upper-right */
    ck_assert_int_eq(has_edge(m, 1, 4), want[p][1]); /* cell 0, the other diagonal */
    ck_assert_int_eq(has_edge(m, 1, 6), want[p][2]);
    ck_assert_int_eq(has_edge(m, 2, 5), want[p][3]);
    free_sim(s);
  }
}
END_TEST

START_TEST(test_rect_two_bodies_ids_min_edge) {
  YfSim *s = new_sim();
  YfModel *m = &s->model;
  model_add_material(m, "steel");
  model_add_material(m, "rock");
  run(s, cmd_mesh, "mesh", "rect a steel 0 0 1 1 2 4");           /* cells 0.5 x 0.25 */
  run(s, cmd_mesh, "mesh", "rect b rock 2 0 3 1 4 4 pattern cross"); /* 0.25 x 0.25, centres */
  ck_assert_int_eq(m->nbody, 2);
  ck_assert_int_eq(m->node.n, 15 + 25 + 16);
  /* ids continue after the first body */
  ck_assert_int_eq(m->node.id[15], 16);
  ck_assert_int_eq(m->tri.id[16], 17);
  ck_assert_int_eq(m->tri.mat[m->tri.n - 1], 1);
  ck_assert_double_eq_tol(mesh_min_edge(m, 0), 0.25, 1e-15);
  ck_assert_double_eq_tol(mesh_min_edge(m, 1), 0.125 * sqrt(2.0), 1e-15);
  ck_assert_double_eq_tol(mesh_min_edge(m, -1), 0.125 * sqrt(2.0), 1e-15);
  ck_assert(mesh_min_edge(m, 5) == 0.0);
  /* boundary of body b only */
  int nb;
  double L = boundary_length(m, model_group(m, "b", 0), 2.5, 0.5, &nb);
  ck_assert_int_eq(nb, 16);
  ck_assert_double_eq_tol(L, 4.0, 1e-12);
  free_sim(s);
}
END_TEST

START_TEST(test_rect_errors) {
  YfSim *s = new_sim();
  model_add_material(&s->model, "steel");
  model_add_material(&s->model, "rock");
  EXPECT_FAIL(s, cmd_mesh, "mesh", "rect a stel 0 0 1 1 2 2", 1, "test.deck:7", "unknown material",
              "steel, rock");
  EXPECT_FAIL(s, cmd_mesh, "mesh", "rect a steel 1 0 1 1 2 2", 1, "x1 must be greater");
  EXPECT_FAIL(s, cmd_mesh, "mesh", "rect a steel 0 0 1 1 0 2", 1, "test.deck:7");
  EXPECT_FAIL(s, cmd_mesh, "mesh", "rect a steel 0 0 1 1 2 2 pattern diag", 1, "diag");
  run(s, cmd_mesh, "mesh", "rect a steel 0 0 1 1 2 2");
  EXPECT_FAIL(s, cmd_mesh, "mesh", "rect a steel 0 0 1 1 2 2", 1, "body 'a' already exists");
  free_sim(s);
}
END_TEST

/* ------------------------------------------------------------------ gmsh */

static int group_of(const YfModel *m, const char *name) {
  int g = model_group((YfModel *)m, name, 0);
  ck_assert_msg(g >= 0, "no group %s", name);
  return g;
}

static void check_two_squares(const YfModel *m, double sc, int rock, int steel) {
  /* 31 nodes in the file, all triangle corners; the .msh has 44 triangles */
  ck_assert_int_eq(m->node.n, 31);
  ck_assert_int_eq(m->tri.n, 44);
  assert_all_ccw(m);
  ck_assert_double_eq_tol(total_area(m, -1), sc * sc, 1e-12 * sc * sc);
  int gr = group_of(m, "rock"), gs = group_of(m, "steel");
  double ar = 0, as = 0;
  for (int t = 0; t < m->tri.n; t++) {
    const int *v = m->tri.v + 3 * t;
    double cx = (m->node.x0[v[0]] + m->node.x0[v[1]] + m->node.x0[v[2]]) / 3;
    int in_r = (m->tri.gmask[t] >> gr) & 1, in_s = (m->tri.gmask[t] >> gs) & 1;
    ck_assert_int_eq(in_r + in_s, 1);
    ck_assert_int_eq(in_r, cx < 0.5 * sc);
    ck_assert_int_eq(m->tri.mat[t], in_r ? rock : steel);
    if (in_r) ar += tri_area(m, t);
    else as += tri_area(m, t);
  }
  ck_assert_double_eq_tol(ar, 0.5 * sc * sc, 1e-12);
  ck_assert_double_eq_tol(as, 0.5 * sc * sc, 1e-12);
  /* physical curves and point: nodes on y = 0 (9: lc = 0.25 on two halves), on x = 1, corner */
  int gb = group_of(m, "bottom"), gx = group_of(m, "right"), gc = group_of(m, "corner");
  int nbot = 0, nright = 0;
  for (int i = 0; i < m->node.n; i++) {
    int onb = fabs(m->node.y0[i]) < 1e-12, onr = fabs(m->node.x0[i] - sc) < 1e-12;
    nbot += onb;
    nright += onr;
    ck_assert_int_eq((int)((m->node.gmask[i] >> gb) & 1), onb);
    ck_assert_int_eq((int)((m->node.gmask[i] >> gx) & 1), onr);
    ck_assert_int_eq((int)((m->node.gmask[i] >> gc) & 1),
                     fabs(m->node.x0[i]) < 1e-12 && fabs(m->node.y0[i] - sc) < 1e-12);
  }
  ck_assert_int_eq(nbot, 5);
  ck_assert_int_eq(nright, 5);
  ck_assert_int_eq(count_tris(m, gb), 0);
  int nb;
  ck_assert_double_eq_tol(boundary_length(m, gb, 0.5 * sc, 0.5 * sc, &nb), sc, 1e-12);
  ck_assert_int_eq(nb, 4);
  ck_assert_double_eq_tol(boundary_length(m, group_of(m, "sq"), 0.5 * sc, 0.5 * sc, &nb), 4 * sc, 1e-12);
  /* node ids are the Gmsh tags: tag 1 is point 1 at the origin */
  ck_assert_int_eq(m->node.id[0], 1);
  ck_assert(m->node.x0[0] == 0.0 && m->node.y0[0] == 0.0);
}

START_TEST(test_gmsh_two_squares) {
  YfSim *s = new_sim();
  YfModel *m = &s->model;
  int rock = model_add_material(m, "rock"), steel = model_add_material(m, "steel");
  char line[1200];
  snprintf(line, sizeof line, "gmsh sq %s", repo_path("decks/meshes/two_squares.msh"));
  run(s, cmd_mesh, "mesh", line);
  check_two_squares(m, 1.0, rock, steel);
  ck_assert_int_eq(m->body[0].mat, rock);
  free_sim(s);
}
END_TEST

START_TEST(test_gmsh_parametric_scale_mapping) {
  YfSim *s = new_sim();
  YfModel *m = &s->model;
  model_add_material(m, "rock");
  int granite = model_add_material(m, "granite"), steel = model_add_material(m, "steel");
  char line[1200];
  snprintf(line, sizeof line, "gmsh sq %s material rock=granite scale 2",
           repo_path("decks/meshes/two_squares_param.msh"));
  run(s, cmd_mesh, "mesh", line);
  check_two_squares(m, 2.0, granite, steel);
  free_sim(s);
  /* a bare default material applies where no name matches; by tag number works too */
  s = new_sim();
  m = &s->model;
  int soft = model_add_material(m, "soft"), hardm = model_add_material(m, "hardm");
  snprintf(line, sizeof line, "gmsh sq %s material soft 2=hardm", repo_path("decks/meshes/two_squares.msh"));
  run(s, cmd_mesh, "mesh", line);
  check_two_squares(m, 1.0, soft, hardm);
  free_sim(s);
}
END_TEST

/* The scene of square4.msh (or of the same mesh partitioned): 5 nodes, 4 triangles covering the
 * unit square, tags up to 3 soft and above hard, the curve 'base' on y = 0 of length 1. */
static void check_square4(YfModel *m, int soft, int hard) {
  ck_assert_int_eq(m->node.n, 5);
  ck_assert_int_eq(m->tri.n, 4);
  assert_all_ccw(m); /* triangle 3 is clockwise in the file */
  ck_assert_double_eq_tol(total_area(m, -1), 1.0, 1e-15);
  int gs = group_of(m, "soft"), gh = group_of(m, "hard"), gb = group_of(m, "base");
  for (int t = 0; t < 4; t++) {
    int tag = m->tri.id[t];
    ck_assert_int_eq(m->tri.mat[t], tag <= 3 ? soft : hard);
    ck_assert_int_eq((int)((m->tri.gmask[t] >> gs) & 1), tag <= 3);
    ck_assert_int_eq((int)((m->tri.gmask[t] >> gh) & 1), tag > 3);
  }
  ck_assert_int_eq(count_nodes(m, gs), 5);
  ck_assert_int_eq(count_nodes(m, gh), 5);
  ck_assert_int_eq(count_nodes(m, gb), 2);
  int nb;
  ck_assert_double_eq_tol(boundary_length(m, gb, 0.5, 0.5, &nb), 1.0, 1e-15);
  ck_assert_int_eq(nb, 1);
}

START_TEST(test_gmsh_hand_written) {
  YfSim *s = new_sim();
  YfModel *m = &s->model;
  int soft = model_add_material(m, "soft"), hard = model_add_material(m, "hard");
  char line[1200];
  snprintf(line, sizeof line, "gmsh sq %s", repo_path("decks/meshes/square4.msh"));
  run(s, cmd_mesh, "mesh", line);
  check_square4(m, soft, hard);
  free_sim(s);
}
END_TEST

/* square4.msh, kept here to derive malformed variants from (line numbers below refer to it) */
static const char *SQ4 =
    "$MeshFormat\n"                 /* 1 */
    "4.1 0 8\n"                     /* 2 */
    "$EndMeshFormat\n"              /* 3 */
    "$PhysicalNames\n"              /* 4 */
    "3\n"                           /* 5 */
    "1 10 \"base\"\n"               /* 6 */
    "2 1 \"soft\"\n"                /* 7 */
    "2 2 \"hard\"\n"                /* 8 */
    "$EndPhysicalNames\n"           /* 9 */
    "$Entities\n"                   /* 10 */
    "0 1 2 0\n"                     /* 11 */
    "1 0 0 0 1 0 0 1 10 0\n"        /* 12 */
    "1 0 0 0 1 1 0 1 1 0\n"         /* 13 */
    "2 0 0 0 1 1 0 1 2 0\n"         /* 14 */
    "$EndEntities\n"                /* 15 */
    "$Nodes\n"                      /* 16 */
    "2 5 1 5\n"                     /* 17 */
    "1 1 0 2\n"                     /* 18 */
    "1\n"                           /* 19 */
    "2\n"                           /* 20 */
    "0 0 0\n"                       /* 21 */
    "1 0 0\n"                       /* 22 */
    "2 1 0 3\n"                     /* 23 */
    "3\n"                           /* 24 */
    "4\n"                           /* 25 */
    "5\n"                           /* 26 */
    "1 1 0\n"                       /* 27 */
    "0 1 0\n"                       /* 28 */
    "0.5 0.5 0\n"                   /* 29 */
    "$EndNodes\n"                   /* 30 */
    "$Elements\n"                   /* 31 */
    "3 5 1 5\n"                     /* 32 */
    "1 1 1 1\n"                     /* 33 */
    "1 1 2\n"                       /* 34 */
    "2 1 2 2\n"                     /* 35 */
    "2 1 2 5\n"                     /* 36 */
    "3 3 5 4\n"                     /* 37 */
    "2 2 2 2\n"                     /* 38 */
    "4 2 3 5\n"                     /* 39 */
    "5 4 1 5\n"                     /* 40 */
    "$EndElements\n";               /* 41 */

/* SQ4 with the first occurrence of `from` replaced by `to` (or cut after it when to is NULL). */
static const char *variant(const char *name, const char *from, const char *to) {
  static char buf[4096];
  const char *p = strstr(SQ4, from);
  ck_assert_ptr_nonnull(p);
  size_t k = (size_t)(p - SQ4);
  if (to) snprintf(buf, sizeof buf, "%.*s%s%s", (int)k, SQ4, to, p + strlen(from));
  else snprintf(buf, sizeof buf, "%.*s", (int)(k + strlen(from)), SQ4);
  return write_tmp(name, buf);
}

START_TEST(test_gmsh_same_as_file) {
  /* the string above is the committed file */
  FILE *fp = fopen(repo_path("decks/meshes/square4.msh"), "r");
  char buf[4096];
  size_t n = fread(buf, 1, sizeof buf - 1, fp);
  buf[n] = '\0';
  fclose(fp);
  ck_assert_str_eq(buf, SQ4);
}
END_TEST

static void bad_msh(const char *name, const char *from, const char *to, int line, const char *msg) {
  YfSim *s = new_sim();
  model_add_material(&s->model, "soft");
  model_add_material(&s->model, "hard");
  const char *path = variant(name, from, to);
  char cmd[1024], where[700];
  snprintf(cmd, sizeof cmd, "gmsh sq %s", path);
  snprintf(where, sizeof where, "%s:%d: error:", path, line);
  EXPECT_FAIL(s, cmd_mesh, "mesh", cmd, 1, where, msg, "mesh gmsh at test.deck:7");
  free_sim(s);
}

START_TEST(test_gmsh_malformed) {
  bad_msh("v30.msh", "4.1 0 8", "3.0 0 8", 2, "MSH version 3.0 is not supported");
  /* an ASCII file that says binary: its "$End" is no binary integer 1 (binary 4.1 was refused) */
  bad_msh("bin.msh", "4.1 0 8", "4.1 1 8", 3, "the binary integer after the version line is");
  bad_msh("trunc.msh", "4 2 3 5\n", NULL, 40, "unexpected end of file");
  bad_msh("trunc2.msh", "1 0 0\n", NULL, 23, "unexpected end of file");
  /* cut inside a physical name: it said "unterminated physical name", or "has no name" */
  bad_msh("trunc4.msh", "2 2 \"ha", NULL, 8, "unexpected end of file in the name of physical group 2 (truncated file?)");
  bad_msh("trunc5.msh", "2 2 ", NULL, 8, "unexpected end of file: physical group 2 has no name (truncated file?)");
  /* cut inside a number or an $End marker: the cut word was read as it stood ("expected a number,
   * found '-'", "node tag 1 is defined twice" for a cut "12", "expected $EndNodes, found '$EndNod'") */
  bad_msh("trunc6.msh", "0.5 0.", NULL, 29, "unexpected end of file in '0.' while reading a node y (truncated file?)");
  bad_msh("trunc7.msh", "$EndNod", NULL, 30, "unexpected end of file in '$EndNod': $EndNodes is cut short (truncated file?)");
  /* cut inside an element's line: it said "element 4 (3-node triangle) has 2 node tags" */
  bad_msh("trunc3.msh", "4 2 3", NULL, 39, "unexpected end of file in element 4, 1 of 2 elements into its block "
          "(truncated file?)");
  bad_msh("num.msh", "0.5 0.5 0\n", "0.5 0.5x 0\n", 29, "expected a number for a node y, found '0.5x'");
  /* the deck's number rules (strictnum.h): strtod read hex coordinates the deck refuses */
  bad_msh("hex.msh", "0.5 0.5 0\n", "0x1p-1 0.5 0\n", 29,
          "expected a number for a node x, found '0x1p-1' (a finite decimal number: digits, an optional '.' and exponent");
  bad_msh("hexz.msh", "0.5 0.5 0\n", "0.5 0.5 0X0P0\n", 29, "expected a number for a node z, found '0X0P0'");
  bad_msh("inf.msh", "0.5 0.5 0\n", "0.5 infinity 0\n", 29, "expected a number for a node y, found 'infinity'");
  bad_msh("tag.msh", "5 4 1 5\n", "5 4 1 9\n", 40, "node 9 of element 5 is not defined in $Nodes");
  bad_msh("count.msh", "2 5 1 5\n", "2 6 1 5\n", 17, "the blocks hold 5 nodes but the header declares 6");
  bad_msh("count2.msh", "3 5 1 5\n", "3 4 1 5\n", 38, "element block 3 declares 2 elements");
  bad_msh("count3.msh", "2 1 0 3\n", "2 1 0 4\n", 23, "node block 2 declares 4 nodes, more than the 3 left");
  bad_msh("short.msh", "0.5 0.5 0\n$EndNodes", "$EndNodes", 29, "found '$EndNodes' while reading a node x");
  bad_msh("dup.msh", "4\n5\n", "4\n4\n", 26, "node tag 4 is defined twice");
  bad_msh("nodes.msh", "4 2 3 5\n", "4 2 3\n", 39, "element 4 (3-node triangle) has 2 node tags");
  bad_msh("zero.msh", "0.5 0.5 0\n", "0.5 0 0\n", 36, "triangle 2 has zero area");
  bad_msh("quad.msh", "2 2 2 2\n4 2 3 5\n5 4 1 5\n", "2 2 3 1\n4 2 3 5 1\n", 38,
          "element type 3 (4-node quadrangle) in surface 2 is not supported");
  bad_msh("z.msh", "0.5 0.5 0\n", "0.5 0.5 0.1\n", 29, "needs a flat mesh, in one plane z = constant");
  bad_msh("ent.msh", "2 2 2 2\n", "2 7 2 2\n", 38, "surface 7, which $Entities does not define");
  bad_msh("phys.msh", "2 0 0 0 1 1 0 1 2 0\n", "2 0 0 0 1 1 0 1 -9223372036854775808 0\n", 14,
          "a physical tag -9223372036854775808 is not in -2147483647..2147483647");
  bad_msh("start.msh", "$MeshFormat\n", "$Mesh\n", 1, "must start with $MeshFormat");
  /* an unknown section never closed: it said "section Nodez is not closed", without its '$' */
  bad_msh("nodez.msh", "$Nodes", "$Nodez", 16, "section $Nodez is not closed by $EndNodez (truncated file?)");
}
END_TEST

/* base (SQ4 for sq4_with) with each sub[k][0] replaced by sub[k][1] (first occurrence, in turn); a
 * static buffer. */
static char *text_with(const char *base, const char *const (*sub)[2], size_t n) {
  static char txt[4096];
  snprintf(txt, sizeof txt, "%s", base);
  for (size_t k = 0; k < n; k++) {
    char *p = strstr(txt, sub[k][0]);
    ck_assert_ptr_nonnull(p);
    char rest[4096];
    snprintf(rest, sizeof rest, "%s", p + strlen(sub[k][0]));
    snprintf(p, sizeof txt - (size_t)(p - txt), "%s%s", sub[k][1], rest);
  }
  return txt;
}

static char *sq4_with(const char *const (*sub)[2], size_t n) { return text_with(SQ4, sub, n); }

/* A flat mesh in the plane z = 5 (a section of a 3D model drawn where it lies) is as 2D as one at
 * z = 0: its scene is square4's.  It was refused ("node 1 has z = 5 ... needs the plane z = 0"). A
 * mesh that is not flat is still refused, naming a node off the first node's plane. */
START_TEST(test_gmsh_flat_plane_off_zero) {
  static const char *const sub[][2] = {{"0 0 0\n1 0 0\n", "0 0 5\n1 0 5\n"},
                                       {"1 1 0\n0 1 0\n0.5 0.5 0\n", "1 1 5\n0 1 5\n0.5 0.5 5.0000000000000001\n"}};
  char *txt = sq4_with(sub, 2);
  YfSim *s = new_sim();
  YfModel *m = &s->model;
  int soft = model_add_material(m, "soft"), hard = model_add_material(m, "hard");
  char cmd[1200];
  snprintf(cmd, sizeof cmd, "gmsh sq %s", write_tmp("z5.msh", txt));
  run(s, cmd_mesh, "mesh", cmd);
  check_square4(m, soft, hard);
  free_sim(s);
  bad_msh("z5tilt.msh", "0.5 0.5 0\n", "0.5 0.5 0.1\n", 29, "node 5 has z = 0.1 where node 1 has z = 0: yfdem is 2D "
          "and needs a flat mesh, in one plane z = constant");
}
END_TEST

/* Every physical group becomes a group and yfdem holds 64: a file with more (here the base curve in
 * 70 unnamed physical groups) was refused naming the first group that did not fit ("cannot create
 * group 'phys_73'"), a name the deck never gave; the error now counts them and says what to do. */
START_TEST(test_gmsh_too_many_groups) {
  char ents[600];
  int k = snprintf(ents, sizeof ents, "1 0 0 0 1 0 0 70");
  for (int t = 10; t < 80; t++) k += snprintf(ents + k, sizeof ents - (size_t)k, " %d", t);
  snprintf(ents + k, sizeof ents - (size_t)k, " 0\n");
  const char *const sub[][2] = {{"1 0 0 0 1 0 0 1 10 0\n", ents}};
  char *txt = sq4_with(sub, 1);
  YfSim *s = new_sim();
  model_add_material(&s->model, "soft");
  model_add_material(&s->model, "hard");
  char cmd[1200];
  snprintf(cmd, sizeof cmd, "gmsh sq %s", write_tmp("many.msh", txt));
  EXPECT_FAIL(s, cmd_mesh, "mesh", cmd, 1, "test.deck:7: error: mesh gmsh:", "many.msh' has 72 physical groups: with the "
              "body's they need 73 new groups, and 64 of the 64 groups yfdem holds are free", "merge physical groups in Gmsh");
  free_sim(s);
}
END_TEST

/* $Entities after $Elements came too late to give the elements their physical groups, and said
 * "surface 1 is defined twice" (the element blocks had made it); now it names the order. */
START_TEST(test_gmsh_entities_after_elements) {
  static const char *const ents = "$Entities\n0 1 2 0\n1 0 0 0 1 0 0 1 10 0\n1 0 0 0 1 1 0 1 1 0\n"
                                  "2 0 0 0 1 1 0 1 2 0\n$EndEntities\n";
  char moved[300];
  snprintf(moved, sizeof moved, "$EndElements\n%s", ents);
  const char *const sub[][2] = {{ents, ""}, {"$EndElements\n", moved}};
  char *txt = sq4_with(sub, 2);
  YfSim *s = new_sim();
  model_add_material(&s->model, "soft");
  model_add_material(&s->model, "hard");
  char cmd[1200];
  snprintf(cmd, sizeof cmd, "gmsh sq %s", write_tmp("entlast.msh", txt));
  EXPECT_FAIL(s, cmd_mesh, "mesh", cmd, 1, "entlast.msh:36: error: $Entities comes after $Elements: it must "
              "come before (as Gmsh writes it)");
  free_sim(s);
}
END_TEST

/* square4.msh as Gmsh writes it once partitioned (Mesh > Partition, or gmsh -part 2): the nodes
 * and elements sit in partition entities, which $PartitionedEntities lists with their parents'
 * physical tags (and ghost entities, here one); the scene is that of the unpartitioned file.
 * Before, the reader looked the element blocks up in $Entities and refused the file. */
START_TEST(test_gmsh_partitioned) {
  static const char *const sub[][2] = {
      {"$EndEntities\n", "$EndEntities\n$PartitionedEntities\n2\n1\n5 1\n0 1 2 0\n"
                         "3 1 1 1 1 0 0 0 1 0 0 1 10 0\n"
                         "3 2 1 1 1 0 0 0 1 1 0 1 1 0\n"
                         "4 2 2 1 2 0 0 0 1 1 0 1 2 0\n$EndPartitionedEntities\n"},
      {"1 1 0 2\n", "1 3 0 2\n"}, {"2 1 0 3\n", "2 3 0 3\n"},
      {"1 1 1 1\n", "1 3 1 1\n"}, {"2 1 2 2\n", "2 3 2 2\n"}, {"2 2 2 2\n", "2 4 2 2\n"}};
  char *txt = sq4_with(sub, sizeof sub / sizeof sub[0]);
  YfSim *s = new_sim();
  YfModel *m = &s->model;
  int soft = model_add_material(m, "soft"), hard = model_add_material(m, "hard");
  char cmd[1200];
  snprintf(cmd, sizeof cmd, "gmsh sq %s", write_tmp("part.msh", txt));
  run(s, cmd_mesh, "mesh", cmd);
  check_square4(m, soft, hard);
  free_sim(s);
  /* an element block in an entity $PartitionedEntities lacks names that section */
  char *p = strstr(txt, "2 4 2 2\n");
  p[2] = '7';
  s = new_sim();
  model_add_material(&s->model, "soft");
  model_add_material(&s->model, "hard");
  snprintf(cmd, sizeof cmd, "gmsh sq %s", write_tmp("part7.msh", txt));
  EXPECT_FAIL(s, cmd_mesh, "mesh", cmd, 1, "part7.msh:47: error:",
              "surface 7, which $PartitionedEntities does not define");
  free_sim(s);
}
END_TEST

/* Two Gmsh bodies keep their files' tags as ids, so they share ids: 'group G node id 5' takes the
 * node of each and said nothing.  It still takes both (the ids are the user's), with a warning
 * naming the two bodies and how to keep one; 'load ID point node 5', which loads one node, is
 * refused. */
START_TEST(test_gmsh_shared_ids_warned) {
  YfSim *s = new_sim();
  YfModel *m = &s->model;
  model_add_material(m, "soft");
  model_add_material(m, "hard");
  char cmd[1200];
  snprintf(cmd, sizeof cmd, "gmsh one %s", repo_path("decks/meshes/square4.msh"));
  run(s, cmd_mesh, "mesh", cmd);
  snprintf(cmd, sizeof cmd, "gmsh two %s scale 2", repo_path("decks/meshes/square4.msh"));
  run(s, cmd_mesh, "mesh", cmd);
  EXPECT_FAIL(s, cmd_group, "group", "c node id 5", 0, "test.deck:7: warning: group c: node id 5 is that of a node "
              "of body 'one' and of one of body 'two'", "'group c_one intersect c one'");
  EXPECT_FAIL(s, cmd_group, "group", "t tri id 4", 0, "warning: group t: triangle id 4 is that of a triangle of body 'one'");
  run(s, cmd_group, "group", "c node id 5");
  ck_assert_int_eq(count_nodes(m, group_of(m, "c")), 2); /* the centres (0.5, 0.5) and (1, 1) */
  run(s, cmd_group, "group", "c_one intersect c one");
  ck_assert_int_eq(count_nodes(m, group_of(m, "c_one")), 1);
  /* a point load on such an id went to whichever node came first in memory: refused */
  EXPECT_FAIL(s, cmd_load, "load", "p point node 5 1 0", 1, "test.deck:7: error: load: '5': node id 5 is that of a node "
              "of body 'one' and of one of body 'two'", "'load p point at X Y'");
  free_sim(s);
  /* ids of one body only: no warning */
  s = new_sim();
  model_add_material(&s->model, "soft");
  model_add_material(&s->model, "hard");
  snprintf(cmd, sizeof cmd, "gmsh one %s", repo_path("decks/meshes/square4.msh"));
  run(s, cmd_mesh, "mesh", cmd);
  char *err;
  ck_assert_int_eq(run_child(s, cmd_group, "group", "c node id 5 4", &err), 0);
  ck_assert_msg(!strstr(err, "warning"), "%s", err);
  free_sim(s);
}
END_TEST

/* One file, two bodies: `shift DX DY` [m] moves the second after its scale, so an impactor and its
 * target can come from one mesh (without it the copies lay on each other and a run with contact
 * between them blew up at its start).  Every node of 'two' is at 2 x its twin's position plus
 * (3, -1); a shift given twice, with one number, or not a number is an error at its word. */
START_TEST(test_gmsh_shift) {
  YfSim *s = new_sim();
  YfModel *m = &s->model;
  model_add_material(m, "soft");
  model_add_material(m, "hard");
  char cmd[1200];
  snprintf(cmd, sizeof cmd, "gmsh one %s", repo_path("decks/meshes/square4.msh"));
  run(s, cmd_mesh, "mesh", cmd);
  const int n1 = m->node.n;
  snprintf(cmd, sizeof cmd, "gmsh two %s shift 3 -1 scale 2", repo_path("decks/meshes/square4.msh"));
  run(s, cmd_mesh, "mesh", cmd);
  ck_assert_int_eq(m->node.n, 2 * n1);
  for (int i = 0; i < n1; i++) {
    ck_assert_int_eq(m->node.id[n1 + i], m->node.id[i]);
    ck_assert_double_eq(m->node.x[n1 + i], 2.0 * m->node.x[i] + 3.0);
    ck_assert_double_eq(m->node.y[n1 + i], 2.0 * m->node.y[i] - 1.0);
    ck_assert_double_eq(m->node.x0[n1 + i], m->node.x[n1 + i]);
  }
  snprintf(cmd, sizeof cmd, "gmsh three %s shift 1 1 shift 2 2", repo_path("decks/meshes/square4.msh"));
  EXPECT_FAIL(s, cmd_mesh, "mesh", cmd, 1, "'shift': given twice", NULL);
  snprintf(cmd, sizeof cmd, "gmsh three %s shift 1", repo_path("decks/meshes/square4.msh"));
  EXPECT_FAIL(s, cmd_mesh, "mesh", cmd, 1, "'shift': expects DX DY [m] after it", NULL);
  snprintf(cmd, sizeof cmd, "gmsh three %s shift 1 up", repo_path("decks/meshes/square4.msh"));
  EXPECT_FAIL(s, cmd_mesh, "mesh", cmd, 1, "'up'", NULL);
  free_sim(s);
}
END_TEST

START_TEST(test_gmsh_deck_errors) {
  YfSim *s = new_sim();
  model_add_material(&s->model, "soft");
  char cmd[1200];
  /* unreadable file: I/O error at the deck line, naming the file */
  EXPECT_FAIL(s, cmd_mesh, "mesh", "gmsh sq /nonexistent/nothere.msh", 2, "test.deck:7",
              "/nonexistent/nothere.msh");
  /* no material for 'hard' (no same-named material, no default) */
  snprintf(cmd, sizeof cmd, "gmsh sq %s", repo_path("decks/meshes/square4.msh"));
  EXPECT_FAIL(s, cmd_mesh, "mesh", cmd, 1, "test.deck:7", "no material for physical surface 'hard'");
  /* a mapping naming a physical group the file does not have */
  snprintf(cmd, sizeof cmd, "gmsh sq %s material hrad=soft", repo_path("decks/meshes/square4.msh"));
  EXPECT_FAIL(s, cmd_mesh, "mesh", cmd, 1, "no physical surface 'hrad'", "soft, hard");
  snprintf(cmd, sizeof cmd, "gmsh sq %s material hard=steel", repo_path("decks/meshes/square4.msh"));
  EXPECT_FAIL(s, cmd_mesh, "mesh", cmd, 1, "unknown material 'steel'");
  snprintf(cmd, sizeof cmd, "gmsh soft %s material hard=soft", repo_path("decks/meshes/square4.msh"));
  EXPECT_FAIL(s, cmd_mesh, "mesh", cmd, 1, "has the name of a body");
  free_sim(s);
}
END_TEST

START_TEST(test_gmsh_no_entities_unnamed) {
  /* no $PhysicalNames, no $Entities: every triangle gets the default material, and line
   * elements (even 3-node ones, type 8) are skipped since they are in no physical group */
  static const char *txt =
      "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n"
      "$Comments\nanything $Nodes here is skipped\n$EndComments\n"
      "$Nodes\n1 4 1 4\n2 1 0 4\n1\n2\n3\n4\n0 0 0\n2 0 0\n2 1 0\n0 1 0\n$EndNodes\n"
      "$Elements\n3 4 1 4\n2 1 2 2\n1 1 3 2\n2 1 3 4\n"
      "1 5 1 1\n3 1 2\n1 6 8 1\n4 2 3 9\n$EndElements\n"; /* lines outside physical groups */
  YfSim *s = new_sim();
  YfModel *m = &s->model;
  model_add_material(m, "a");
  int b = model_add_material(m, "b");
  char cmd[600];
  snprintf(cmd, sizeof cmd, "gmsh blk %s material b", write_tmp("plain.msh", txt));
  run(s, cmd_mesh, "mesh", cmd);
  ck_assert_int_eq(m->tri.n, 2);
  assert_all_ccw(m); /* 1 3 2 is clockwise */
  ck_assert_double_eq_tol(total_area(m, -1), 2.0, 1e-15);
  ck_assert_int_eq(m->tri.mat[0], b);
  ck_assert_int_eq(m->tri.mat[1], b);
  ck_assert_int_eq(m->ngroup, 1);
  free_sim(s);
  /* without a default the error names the surface */
  s = new_sim();
  model_add_material(&s->model, "a");
  EXPECT_FAIL(s, cmd_mesh, "mesh", cmd, 1, "unknown material");
  snprintf(cmd, sizeof cmd, "gmsh blk %s", tmp_path("plain.msh"));
  EXPECT_FAIL(s, cmd_mesh, "mesh", cmd, 1, "surface 1 of", "in no physical group");
  free_sim(s);
}
END_TEST

/* Unnamed physical groups of one tag in two dimensions are named phys_<tag>_<dimension>, both of
 * them: the first named took the dimension and the second, finding the first named, did not (a
 * physical curve 1 made phys_1_curve, and surface 1, phys_1). */
START_TEST(test_gmsh_unnamed_shared_tag) {
  static const char *const sub[][2] = {{"3\n1 10 \"base\"\n2 1 \"soft\"\n", "1\n"}, {"1 0 0 0 1 0 0 1 10 0\n", "1 0 0 0 1 0 0 1 1 0\n"}};
  char *txt = sq4_with(sub, 2);
  YfSim *s = new_sim();
  YfModel *m = &s->model;
  model_add_material(m, "soft");
  model_add_material(m, "hard");
  char cmd[1200];
  snprintf(cmd, sizeof cmd, "gmsh sq %s material soft", write_tmp("unnamed.msh", txt));
  run(s, cmd_mesh, "mesh", cmd);
  ck_assert_int_eq(count_nodes(m, group_of(m, "phys_1_curve")), 2);
  ck_assert_int_eq(count_tris(m, group_of(m, "phys_1_surface")), 2);
  ck_assert_int_eq(count_tris(m, group_of(m, "hard")), 2);
  ck_assert_int_eq(m->ngroup, 4);
  free_sim(s);
}
END_TEST

/* ------------------------------------------------------------------ gmsh MSH 2.2 */

/* A body read from FILE (absolute) by 'mesh gmsh sq FILE ARGS', with materials soft, hard, rock
 * and steel (indices 0..3). */
static YfSim *gmsh_scene(const char *file, const char *args) {
  YfSim *s = new_sim();
  model_add_material(&s->model, "soft");
  model_add_material(&s->model, "hard");
  model_add_material(&s->model, "rock");
  model_add_material(&s->model, "steel");
  char cmd[1400];
  snprintf(cmd, sizeof cmd, "gmsh sq %s %s", file, args);
  run(s, cmd_mesh, "mesh", cmd);
  return s;
}

/* The scenes two files of one mesh must give alike: the same nodes (ids = file tags, places, in
 * the same order), triangles (corners, materials, and ids unless tri_ids is 0: a 2.2 file
 * numbers the copies of an element in several physical groups, so its tags are not 4.1's), area,
 * and groups of the same names with the same members. */
static void same_scene(const YfModel *a, const YfModel *b, int tri_ids) {
  ck_assert_int_eq(a->node.n, b->node.n);
  ck_assert_int_eq(a->tri.n, b->tri.n);
  for (int i = 0; i < a->node.n; i++) {
    ck_assert_int_eq(a->node.id[i], b->node.id[i]);
    ck_assert_msg(a->node.x0[i] == b->node.x0[i] && a->node.y0[i] == b->node.y0[i], "node %d at (%.17g, %.17g) and "
                  "(%.17g, %.17g)", a->node.id[i], a->node.x0[i], a->node.y0[i], b->node.x0[i], b->node.y0[i]);
  }
  for (int t = 0; t < a->tri.n; t++) {
    for (int k = 0; k < 3; k++) ck_assert_int_eq(a->tri.v[3 * t + k], b->tri.v[3 * t + k]);
    ck_assert_int_eq(a->tri.mat[t], b->tri.mat[t]);
    if (tri_ids) ck_assert_int_eq(a->tri.id[t], b->tri.id[t]);
  }
  ck_assert(total_area(a, -1) == total_area(b, -1));
  ck_assert_int_eq(a->ngroup, b->ngroup);
  for (int g = 0; g < a->ngroup; g++) {
    int h = model_group((YfModel *)b, a->group[g].name, 0);
    ck_assert_msg(h >= 0, "group %s is missing", a->group[g].name);
    for (int i = 0; i < a->node.n; i++)
      ck_assert_msg((a->node.gmask[i] >> g & 1) == (b->node.gmask[i] >> h & 1), "group %s, node %d",
                    a->group[g].name, a->node.id[i]);
    for (int t = 0; t < a->tri.n; t++)
      ck_assert_msg((a->tri.gmask[t] >> g & 1) == (b->tri.gmask[t] >> h & 1), "group %s, triangle %d",
                    a->group[g].name, t);
  }
}

/* state_hash after a short run of deck text with FILE for %s */
static uint64_t run_hash(const char *deck_fmt, const char *file, double *ux) {
  char deck[4096], err[256] = "";
  snprintf(deck, sizeof deck, deck_fmt, file);
  YfSim *s = yft_run(deck);
  uint64_t h = sim_state_hash(s);
  ck_assert_msg(sim_query(s, "ux_right", ux, err, sizeof err) == 1, "%s", err);
  sim_free(s);
  return h;
}

/* overlap.msh's scene pushed on its tag-9 curve, its half fixed, for 300 steps (%s: the file) */
static const char *const OVERLAP_DECK = "material granite elastic rho 2700 E 50e9 nu 0.25 plane_strain damping 0.1\n"
                                        "material steel elastic rho 7800 E 200e9 nu 0.3 plane_strain damping 0.1\n"
                                        "mesh gmsh block %s material whole=granite 9=steel scale 0.1\n"
                                        "fix base half fixed xy\nfix pin pins fixed y\nload push phys_9_curve pressure 1e6\n"
                                        "timestep auto\nrun 300\n";

/* The deck (its %s the mesh file) run on the files a and b (names for the message) gives the same
 * state_hash, and the pushed side (query ux_right) moved inwards, by the same amount. */
static void same_run(const char *deck, const char *a, const char *b, const char *what) {
  double uxa, uxb;
  uint64_t ha = run_hash(deck, repo_path(a), &uxa);
  uint64_t hb = run_hash(deck, repo_path(b), &uxb);
  ck_assert_msg(ha == hb, "state_hash %016llx and %016llx (%s)", (unsigned long long)ha, (unsigned long long)hb, what);
  ck_assert(uxa < 0 && uxb == uxa);
}

/* two_squares.msh saved by Gmsh as MSH 2.2 (decks/meshes/make_msh22.py) gives the 4.1 file's
 * scene, and the same bits after a run; the 2.2 file was refused ("MSH version 2.2 is not
 * supported"). */
START_TEST(test_gmsh_msh22_same_scene) {
  YfSim *a = gmsh_scene(repo_path("decks/meshes/two_squares.msh"), "");
  YfSim *b = gmsh_scene(repo_path("decks/meshes/two_squares_22.msh"), "");
  check_two_squares(&b->model, 1.0, 2, 3);
  same_scene(&a->model, &b->model, 1);
  free_sim(a);
  free_sim(b);
  static const char *deck = "material granite elastic rho 2700 E 50e9 nu 0.25 plane_strain damping 0.1\n"
                            "material steel elastic rho 7800 E 200e9 nu 0.3 plane_strain damping 0.1\n"
                            "mesh gmsh block %s material rock=granite steel=steel scale 0.1\n"
                            "fix base bottom fixed xy\nload push right pressure 1e6\ntimestep auto\nrun 300\n";
  same_run(deck, "decks/meshes/two_squares.msh", "decks/meshes/two_squares_22.msh", "4.1 and 2.2");
}
END_TEST

/* Physical groups that overlap: MSH 2.2 writes an element once per physical group it is in, each
 * copy with its own tag (surface 2's 22 triangles three times, in steel, whole and 9).  The copies
 * are one triangle, in each of their groups: 44 triangles, as the 4.1 file of the same mesh gives,
 * not 110 (overlapping triangles, each in one group).  Unnamed groups of one tag in two dimensions
 * get the same names (phys_9_curve, phys_9_surface), points and curves in two groups are in both. */
START_TEST(test_gmsh_msh22_overlapping_groups) {
  YfSim *a = gmsh_scene(repo_path("decks/meshes/overlap.msh"), "");
  /* unnamed groups of tag 9 in two dimensions: both names say the dimension (the surface was
   * named phys_9, the curve, named first, having taken phys_9_curve) */
  ck_assert_int_eq(count_tris(&a->model, group_of(&a->model, "phys_9_surface")), 22);
  ck_assert_int_eq(count_nodes(&a->model, group_of(&a->model, "phys_9_curve")), 8);
  YfSim *b = gmsh_scene(repo_path("decks/meshes/overlap_22.msh"), "");
  YfModel *m = &b->model;
  check_two_squares(m, 1.0, 2, 3);
  same_scene(&a->model, m, 0);
  int gw = group_of(m, "whole"), g9 = group_of(m, "phys_9_surface"), gc = group_of(m, "phys_9_curve");
  ck_assert_int_eq(count_tris(m, gw), 44);
  ck_assert_int_eq(count_tris(m, g9), 22);
  ck_assert_int_eq(count_nodes(m, gc), 8); /* curves 1 and 3: the bottom's left half (3 nodes), the right side (5) */
  ck_assert_int_eq(count_nodes(m, group_of(m, "half")), 3);
  /* points 1 and 6, but only 6 has a point element in two_squares.msh: Gmsh writes that one */
  ck_assert_int_eq(count_nodes(m, group_of(m, "pins")), 1);
  /* a triangle keeps its first copy's tag; the tags of its later copies are no ids */
  run(b, cmd_group, "group", "t1 tri id 19");
  ck_assert_int_eq(count_tris(m, group_of(m, "t1")), 1);
  EXPECT_FAIL(b, cmd_group, "group", "t2 tri id 20", 1, "no triangle has this id");
  free_sim(a);
  free_sim(b);
  /* the material of a triangle in several physical surfaces: that of the first of them that has
   * one, in the file's order, as in 4.1 (surface 2 is in steel, whole, 9: here whole's) */
  const char *f[2] = {repo_path("decks/meshes/overlap.msh"), NULL};
  f[0] = strdup(f[0]);
  f[1] = strdup(repo_path("decks/meshes/overlap_22.msh"));
  YfSim *ab[2];
  for (int k = 0; k < 2; k++) {
    ab[k] = new_sim();
    model_add_material(&ab[k]->model, "soft");
    model_add_material(&ab[k]->model, "hard");
    char cmd[1400];
    snprintf(cmd, sizeof cmd, "gmsh sq %s material 9=hard whole=soft", f[k]);
    run(ab[k], cmd_mesh, "mesh", cmd);
    free((void *)f[k]);
  }
  same_scene(&ab[0]->model, &ab[1]->model, 0);
  for (int t = 0; t < 44; t++) ck_assert_int_eq(ab[1]->model.tri.mat[t], 0);
  free_sim(ab[0]);
  free_sim(ab[1]);
  same_run(OVERLAP_DECK, "decks/meshes/overlap.msh", "decks/meshes/overlap_22.msh", "4.1 and 2.2");
}
END_TEST

/* square4.msh written as MSH 2.2 by hand (line numbers below refer to it) */
static const char *SQ22 =
    "$MeshFormat\n"                 /* 1 */
    "2.2 0 8\n"                     /* 2 */
    "$EndMeshFormat\n"              /* 3 */
    "$PhysicalNames\n"              /* 4 */
    "3\n"                           /* 5 */
    "1 10 \"base\"\n"               /* 6 */
    "2 1 \"soft\"\n"                /* 7 */
    "2 2 \"hard\"\n"                /* 8 */
    "$EndPhysicalNames\n"           /* 9 */
    "$Nodes\n"                      /* 10 */
    "5\n"                           /* 11 */
    "1 0 0 0\n"                     /* 12 */
    "2 1 0 0\n"                     /* 13 */
    "3 1 1 0\n"                     /* 14 */
    "4 0 1 0\n"                     /* 15 */
    "5 0.5 0.5 0\n"                 /* 16 */
    "$EndNodes\n"                   /* 17 */
    "$Elements\n"                   /* 18 */
    "5\n"                           /* 19 */
    "1 1 2 10 1 1 2\n"              /* 20 */
    "2 2 2 1 1 1 2 5\n"             /* 21 */
    "3 2 2 1 1 3 5 4\n"             /* 22 */
    "4 2 2 2 2 2 3 5\n"             /* 23 */
    "5 2 2 2 2 4 1 5\n"             /* 24 */
    "$EndElements\n";               /* 25 */

/* SQ22 with the first occurrence of `from` replaced by `to` (or cut after it when to is NULL). */
static const char *variant22(const char *name, const char *from, const char *to) {
  static char buf[4096];
  const char *p = strstr(SQ22, from);
  ck_assert_ptr_nonnull(p);
  size_t k = (size_t)(p - SQ22);
  if (to) snprintf(buf, sizeof buf, "%.*s%s%s", (int)k, SQ22, to, p + strlen(from));
  else snprintf(buf, sizeof buf, "%.*s", (int)(k + strlen(from)), SQ22);
  return write_tmp(name, buf);
}

static void bad_msh22(const char *name, const char *from, const char *to, int line, const char *msg) {
  YfSim *s = new_sim();
  model_add_material(&s->model, "soft");
  model_add_material(&s->model, "hard");
  const char *path = variant22(name, from, to);
  char cmd[1024], where[700];
  snprintf(cmd, sizeof cmd, "gmsh sq %s", path);
  snprintf(where, sizeof where, "%s:%d: error:", path, line);
  EXPECT_FAIL(s, cmd_mesh, "mesh", cmd, 1, where, msg, "mesh gmsh at test.deck:7");
  free_sim(s);
}

/* The hand-written 2.2 square gives square4.msh's scene; copies of a triangle in another physical
 * group need not follow it nor share its orientation; elements with physical tag 0, or no tags,
 * are those of entities in no physical group in 4.1: points and lines skipped (even of types yfdem
 * does not read), triangles taken, with the default material. */
START_TEST(test_gmsh_msh22_hand_written) {
  YfSim *a = gmsh_scene(repo_path("decks/meshes/square4.msh"), "");
  YfSim *b = gmsh_scene(variant22("sq22.msh", "$", "$"), ""); /* SQ22 as it is */
  check_square4(&b->model, 0, 1);
  same_scene(&a->model, &b->model, 1);
  free_sim(b);
  /* triangle 3 again, later, turned, in physical surface 7 too; and a copy with physical tag 0 */
  char buf[4096];
  snprintf(buf, sizeof buf, "%s", SQ22);
  char *e = strstr(buf, "$EndElements");
  snprintf(e, sizeof buf - (size_t)(e - buf), "6 2 2 7 1 5 4 3\n7 2 2 0 1 4 3 5\n$EndElements\n");
  buf[strstr(buf, "$Elements\n5") - buf + 10] = '7';
  b = gmsh_scene(write_tmp("copy22.msh", buf), "");
  YfModel *m = &b->model;
  check_square4(m, 0, 1);
  int g7 = group_of(m, "phys_7");
  ck_assert_int_eq(count_tris(m, g7), 1);
  for (int t = 0; t < 4; t++) ck_assert_int_eq((int)(m->tri.gmask[t] >> g7 & 1), m->tri.id[t] == 3);
  free_sim(b);
  /* physical tag 0 (Gmsh's Mesh.SaveAll in 2.2), or no tags at all */
  static const char *const none[][2] = {{"1 1 2 10 1 1 2\n", "1 1 2 0 1 1 2\n"}, {"2 2 2 1 1", "2 2 2 0 1"},
                                        {"3 2 2 1 1", "3 2 0"}, {"4 2 2 2 2", "4 2 2 0 2"},
                                        {"5 2 2 2 2", "5 2 2 0 2"}};
  snprintf(buf, sizeof buf, "%s", SQ22);
  for (size_t k = 0; k < sizeof none / sizeof none[0]; k++) {
    char *p = strstr(buf, none[k][0]), rest[4096];
    ck_assert_ptr_nonnull(p);
    snprintf(rest, sizeof rest, "%s", p + strlen(none[k][0]));
    snprintf(p, sizeof buf - (size_t)(p - buf), "%s%s", none[k][1], rest);
  }
  /* and a 3-node line (type 8) in no physical group, skipped as 4.1 skips it */
  e = strstr(buf, "$EndElements");
  snprintf(e, sizeof buf - (size_t)(e - buf), "6 8 2 0 3 1 2 5\n$EndElements\n");
  buf[strstr(buf, "$Elements\n5") - buf + 10] = '6';
  const char *plain = write_tmp("plain22.msh", buf);
  b = gmsh_scene(plain, "material hard");
  m = &b->model;
  ck_assert_int_eq(m->tri.n, 4);
  assert_all_ccw(m);
  ck_assert_double_eq_tol(total_area(m, -1), 1.0, 1e-15);
  for (int t = 0; t < 4; t++) ck_assert_int_eq(m->tri.mat[t], 1);
  ck_assert_int_eq(m->ngroup, 1); /* the body's: no group of a physical tag 0 */
  char cmd[1200];
  /* the names of $PhysicalNames with no element in a group: Gmsh's SaveAll; said, no longer silent */
  snprintf(cmd, sizeof cmd, "gmsh sq3 %s material hard", plain);
  EXPECT_FAIL(b, cmd_mesh, "mesh", cmd, 0, "test.deck:7: warning: mesh gmsh:", "names 3 physical groups in $PhysicalNames "
              "but no element is in one (physical tag 0 throughout, as Gmsh's Mesh.SaveAll writes MSH 2.2)");
  snprintf(cmd, sizeof cmd, "gmsh sq2 %s", plain);
  EXPECT_FAIL(b, cmd_mesh, "mesh", cmd, 1, "test.deck:7: error: mesh gmsh: triangle 2 (elementary surface 1) of",
              "is in no physical group (physical tag 0): give a default material with 'material MAT'");
  free_sim(b);
  free_sim(a);
}
END_TEST

START_TEST(test_gmsh_msh22_malformed) {
  /* cut anywhere: the file says where and that it looks cut */
  bad_msh22("t1.msh", "3 2 2 1 1 3 5", NULL, 22, "unexpected end of file in element 3, 3 of 5 elements (truncated file?)");
  bad_msh22("t2.msh", "3 1 1 0\n", NULL, 15, "unexpected end of file while reading a node tag (truncated file?)");
  bad_msh22("t3.msh", "$Elements\n5", NULL, 19, "unexpected end of file in '5' while reading the number of elements "
            "(truncated file?)");
  bad_msh22("t4.msh", "5 2 2 2 2 4 1 5\n", NULL, 25, "unexpected end of file: $EndElements is missing (truncated file?)");
  bad_msh22("t5.msh", "4 2 2 2", NULL, 23, "unexpected end of file in '2' while reading the physical tag of an element "
            "(truncated file?)");
  bad_msh22("t6.msh", "5 0.5 0.", NULL, 16, "unexpected end of file in '0.' while reading a node y (truncated file?)");
  /* counts that do not match the data */
  bad_msh22("c1.msh", "$Elements\n5\n", "$Elements\n6\n", 25, "found '$EndElements' while reading an element tag: the "
            "section holds less data than its counts declare");
  bad_msh22("c2.msh", "$Elements\n5\n", "$Elements\n4\n", 24, "expected $EndElements, found '5' (more elements than the "
            "count declares?)");
  bad_msh22("c3.msh", "$Nodes\n5\n", "$Nodes\n6\n", 17, "found '$EndNodes' while reading a node tag");
  bad_msh22("c4.msh", "$Nodes\n5\n", "$Nodes\n4\n", 16, "expected $EndNodes, found '5' (more nodes than the count declares?)");
  bad_msh22("c5.msh", "$Nodes\n5\n", "$Nodes\n-5\n", 11, "bad number of nodes -5");
  bad_msh22("c7.msh", "4 2 2 2 2 2 3 5\n", "4 2 2 -9223372036854775808 2 2 3 5\n", 23, "the physical tag of an element "
            "-9223372036854775808 is not in -2147483647..2147483647");
  bad_msh22("c6.msh", "4 2 2 2 2 2 3 5\n", "4 2 -1 2 2 2 3 5\n", 23, "element 4 has -1 tags, expected 0 to 1000");
  /* element types yfdem does not read */
  bad_msh22("e1.msh", "4 2 2 2 2 2 3 5\n", "4 99 2 2 2 2 3 5\n", 23, "element 4 has type 99, no Gmsh element type yfdem "
            "knows: yfdem reads 3-node triangles (type 2), 2-node lines (type 1) and points (type 15)");
  bad_msh22("e2.msh", "4 2 2 2 2 2 3 5\n", "4 3 2 2 2 2 3 5 1\n", 23, "element type 3 (4-node quadrangle) in surface 2 "
            "is not supported: yfdem reads 3-node triangles");
  bad_msh22("e3.msh", "4 2 2 2 2 2 3 5\n", "4 9 2 2 2 2 3 5 1 1 1\n", 23, "element type 9 (6-node triangle) in surface 2 "
            "is not supported");
  bad_msh22("e4.msh", "4 2 2 2 2 2 3 5\n", "4 4 2 2 2 2 3 5 1\n", 23, "3D elements (4-node tetrahedron) in volume 2: "
            "yfdem is 2D");
  bad_msh22("e5.msh", "1 1 2 10 1 1 2\n", "1 8 2 10 1 1 2 5\n", 20, "element type 8 (3-node line) in curve 1 is not supported");
  /* node references and node tags on an element's line */
  bad_msh22("n1.msh", "5 2 2 2 2 4 1 5\n", "5 2 2 2 2 4 1 9\n", 24, "node 9 of element 5 is not defined in $Nodes");
  bad_msh22("n2.msh", "1 1 2 10 1 1 2\n", "1 1 2 10 1 1 7\n", 20, "node 7 of element 1 is not defined in $Nodes");
  bad_msh22("n3.msh", "4 2 2 2 2 2 3 5\n", "4 2 2 2 2 2 3\n", 23, "element 4 (3-node triangle) has 2 node tags on its "
            "line, expected 3");
  bad_msh22("n4.msh", "4 2 2 2 2 2 3 5\n", "4 2 2 2 2 2 3 5 1\n", 23, "element 4 (3-node triangle) has more than 3 node tags");
  bad_msh22("n5.msh", "4 2 2 2 2 2 3 5\n", "4 2 2 2 2 2 3 x\n", 23, "expected an integer node tag in element 4, found 'x'");
  /* nodes: the same rules as in 4.1 */
  bad_msh22("d1.msh", "4 0 1 0\n", "3 0 1 0\n", 15, "node tag 3 is defined twice");
  bad_msh22("d2.msh", "5 0.5 0.5 0\n", "5 0x1p-1 0.5 0\n", 16, "expected a number for a node x, found '0x1p-1'");
  bad_msh22("d3.msh", "5 0.5 0.5 0\n", "5 0.5 0.5 0.1\n", 16, "node 5 has z = 0.1 where node 1 has z = 0: yfdem is 2D");
  bad_msh22("d4.msh", "5 0.5 0.5 0\n", "5 0.5 0 0\n", 21, "triangle 2 has zero area");
  bad_msh22("d5.msh", "4 0 1 0\n", "0 0 1 0\n", 15, "node tag 0 is not in 1..");
  bad_msh22("d6.msh", "$Nodes", "$Nodez", 10, "section $Nodez is not closed by $EndNodez");
  /* versions */
  bad_msh22("v1.msh", "2.2 0 8", "3.0 0 8", 2, "MSH version 3.0 is not supported: yfdem reads MSH 4.1 and 2.2 (ASCII or binary) and "
            "2.0 and 2.1 (ASCII); save with gmsh -format msh41");
  bad_msh22("v2.msh", "2.2 0 8", "2.2 2 8", 2, "file type 2 is neither 0 (ASCII) nor 1 (binary)");
}
END_TEST

/* $ParametricNodes (Mesh.SaveParametric in 2.2: each node's entity and its u, or u v, follow x y z)
 * gives the scene of $Nodes; it was skipped as an unknown section ("$Elements comes before
 * $Nodes"). Node lines hold what their section says, no more. */
START_TEST(test_gmsh_msh22_parametric) {
  YfSim *a = gmsh_scene(repo_path("decks/meshes/two_squares_param.msh"), "");
  YfSim *b = gmsh_scene(repo_path("decks/meshes/two_squares_22p.msh"), "");
  check_two_squares(&b->model, 1.0, 2, 3);
  same_scene(&a->model, &b->model, 1);
  free_sim(a);
  free_sim(b);
  static const char *par = "$ParametricNodes\n5\n1 0 0 0 0 1\n2 1 0 0 0 2\n3 1 1 0 1 2 0.5\n4 0 1 0\n"
                           "5 0.5 0.5 0 2 1 0.5 0.5\n$EndParametricNodes\n";
  const char *nodes = "$Nodes\n5\n1 0 0 0\n2 1 0 0\n3 1 1 0\n4 0 1 0\n5 0.5 0.5 0\n$EndNodes\n";
  b = gmsh_scene(variant22("par22.msh", nodes, par), "");
  check_square4(&b->model, 0, 1);
  free_sim(b);
  char bad[400];
  snprintf(bad, sizeof bad, "%s", par);
  *strstr(bad, " 0.5\n$End") = '\0';
  strcat(bad, "\n$EndParametricNodes\n");
  bad_msh22("par1.msh", nodes, bad, 17, "found '$EndParametricNodes' while reading a parametric coordinate");
  snprintf(bad, sizeof bad, "%s", par);
  bad[strstr(bad, "5 0.5 0.5 0 2") - bad + 12] = '5';
  bad_msh22("par2.msh", nodes, bad, 16, "$ParametricNodes: node 5: entity dimension 5 is not 0..3");
  bad_msh22("par3.msh", "5 0.5 0.5 0\n", "5 0.5 0.5 0 7\n", 16, "$Nodes: node 5: '7' after its x y z on its line");
  bad_msh22("par4.msh", "$EndNodes\n", "$EndNodes\n$ParametricNodes\n0\n$EndParametricNodes\n", 18,
            "a second $Nodes or $ParametricNodes section");
}
END_TEST

/* SQ22 as binary MSH 2.2 (the ASCII header and names, the node and element data in binary; swap:
 * in the other byte order than this machine's), into buf; its length.  off[] receives the offsets
 * of: 0 the integer 1 of the header, 1 node 5's x, 2 the second element block's header, 3 the last
 * node tag of element 5.  Line numbers: the header's integer on 3, the node count on 12, the element
 * count on 16 (after the data of physical tag 10, a newline byte). */
/* Binary data into buf at n (swap: in the other byte order): a string, a value, an int, a size_t,
 * a double. */
#define PUT_S(str) (memcpy(buf + n, str, strlen(str)), n += strlen(str))
#define PUT_B(v)                                                                                   \
  do {                                                                                             \
    unsigned char b_[8];                                                                           \
    memcpy(b_, &(v), sizeof(v));                                                                   \
    for (size_t i_ = 0; i_ < sizeof(v); i_++) buf[n + i_] = (char)b_[swap ? sizeof(v) - 1 - i_ : i_]; \
    n += sizeof(v);                                                                                \
  } while (0)
#define PUT_I(x) do { int32_t v_ = (x); PUT_B(v_); } while (0)
#define PUT_Z(x) do { uint64_t v_ = (x); PUT_B(v_); } while (0)
#define PUT_D(x) do { double v_ = (x); PUT_B(v_); } while (0)

static size_t sq22_bin(char *buf, int swap, size_t off[4]) {
  size_t n = 0;
  PUT_S("$MeshFormat\n2.2 1 8\n");
  off[0] = n;
  PUT_I(1);
  PUT_S("\n$EndMeshFormat\n$PhysicalNames\n3\n1 10 \"base\"\n2 1 \"soft\"\n2 2 \"hard\"\n$EndPhysicalNames\n$Nodes\n5\n");
  static const double xy[5][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}, {0.5, 0.5}};
  for (int i = 0; i < 5; i++) {
    PUT_I(i + 1);
    if (i == 4) off[1] = n;
    for (int k = 0; k < 3; k++) {
      double c = k < 2 ? xy[i][k] : 0.0;
      PUT_B(c);
    }
  }
  PUT_S("\n$EndNodes\n$Elements\n5\n");
  static const int line[] = {1, 1, 2, 1, 10, 1, 1, 2};
  for (int k = 0; k < 8; k++) PUT_I(line[k]);
  off[2] = n;
  static const int tri[] = {2, 4, 2, 2, 1, 1, 1, 2, 5, 3, 1, 1, 3, 5, 4, 4, 2, 2, 2, 3, 5, 5, 2, 2, 4, 1, 5};
  for (int k = 0; k < 27; k++) {
    if (k == 26) off[3] = n;
    PUT_I(tri[k]);
  }
  PUT_S("\n$EndElements\n");
  return n;
}

static const char *write_bin(const char *name, const char *buf, size_t n) {
  const char *p = tmp_path(name);
  FILE *fp = fopen(p, "wb");
  ck_assert_ptr_nonnull(fp);
  ck_assert_uint_eq(fwrite(buf, 1, n, fp), n);
  fclose(fp);
  return p;
}

/* A binary file (buf, n) that must fail: exit 1 at line, with msg, and `also` unless NULL. */
static void bad_bin_also(const char *name, const char *buf, size_t n, int line, const char *msg, const char *also) {
  YfSim *s = new_sim();
  model_add_material(&s->model, "soft");
  model_add_material(&s->model, "hard");
  const char *path = write_bin(name, buf, n);
  char cmd[1024], where[700];
  snprintf(cmd, sizeof cmd, "gmsh sq %s", path);
  snprintf(where, sizeof where, "%s:%d: error:", path, line);
  EXPECT_FAIL(s, cmd_mesh, "mesh", cmd, 1, where, msg, "mesh gmsh at test.deck:7", also);
  free_sim(s);
}

static void bad_bin(const char *name, const char *buf, size_t n, int line, const char *msg) {
  bad_bin_also(name, buf, n, line, msg, NULL);
}

/* Every cut of a file (n bytes in buf) at offsets from k0 by step: exit 1, the file named, and the
 * message says it looks cut. */
static void cuts_fail(const char *buf, size_t n, size_t k0, size_t step) {
  for (size_t k = k0; k + 1 < n; k += step) {
    YfSim *s = new_sim();
    model_add_material(&s->model, "soft");
    model_add_material(&s->model, "hard");
    model_add_material(&s->model, "rock");
    model_add_material(&s->model, "steel");
    char cmd[1024], *err;
    snprintf(cmd, sizeof cmd, "gmsh sq %s", write_bin("cut.msh", buf, k));
    int rc = run_child(s, cmd_mesh, "mesh", cmd, &err);
    ck_assert_msg(rc == 1 && strstr(err, "cut.msh:") && strstr(err, "(truncated file?)"),
                  "cut after %zu of %zu bytes: exit %d: %s", k, n, rc, err);
    free_sim(s);
  }
}

/* Binary MSH 2.2 (Mesh.Binary = 1), which was refused ("binary .msh files are not supported"): the
 * binary file Gmsh writes of a mesh gives the scene and the bits of its ASCII files; a binary file
 * in either byte order is read; a binary file cut anywhere says it looks cut, and wrong binary
 * data is named (messages give the line of the section's count). */
START_TEST(test_gmsh_msh22_binary) {
  YfSim *a = gmsh_scene(repo_path("decks/meshes/overlap.msh"), "");
  YfSim *b = gmsh_scene(repo_path("decks/meshes/overlap_22b.msh"), "");
  YfSim *c = gmsh_scene(repo_path("decks/meshes/overlap_22.msh"), "");
  check_two_squares(&b->model, 1.0, 2, 3);
  same_scene(&a->model, &b->model, 0);
  same_scene(&c->model, &b->model, 1);
  free_sim(a);
  free_sim(b);
  free_sim(c);
  same_run(OVERLAP_DECK, "decks/meshes/overlap.msh", "decks/meshes/overlap_22b.msh", "4.1 and binary 2.2");

  /* both byte orders give square4's scene */
  static char buf[2048];
  size_t off[4];
  a = gmsh_scene(repo_path("decks/meshes/square4.msh"), "");
  for (int swap = 0; swap < 2; swap++) {
    size_t n = sq22_bin(buf, swap, off);
    b = gmsh_scene(write_bin("sqb.msh", buf, n), "");
    check_square4(&b->model, 0, 1);
    same_scene(&a->model, &b->model, 1);
    free_sim(b);
  }
  free_sim(a);

  /* a section yfdem skips, with binary data (a $NodeData of meshio's): a run of 400 bytes without a
   * blank was "a word longer than 255 characters"; an end marker inside a word is no end */
  {
    size_t n = sq22_bin(buf, 0, off);
    char *e = memmem(buf, n, "$Elements\n", 10);
    ck_assert_ptr_nonnull(e);
    static char sec[1024];
    size_t k = (size_t)snprintf(sec, sizeof sec, "$NodeData\n1\n\"u\"\n1\n0\n3\n0\n1\n5\n");
    memset(sec + k, 0x41, 400);
    memcpy(sec + k + 200, "$EndNodeData", 12);
    k += 400;
    k += (size_t)snprintf(sec + k, sizeof sec - k, "\n$EndNodeData\n");
    static char big[4096];
    size_t h = (size_t)(e - buf);
    memcpy(big, buf, h);
    memcpy(big + h, sec, k);
    memcpy(big + h + k, e, n - h);
    YfSim *s = gmsh_scene(write_bin("sqbd.msh", big, n + k), "");
    check_square4(&s->model, 0, 1);
    free_sim(s);
  }

  /* cut at any byte: exit 1, and the message says the file looks cut (the whole file less its
   * last newline is whole) */
  size_t n = sq22_bin(buf, 0, off);
  b = gmsh_scene(write_bin("sqb.msh", buf, n - 1), "");
  ck_assert_int_eq(b->model.tri.n, 4);
  free_sim(b);
  cuts_fail(buf, n, strlen("$MeshFormat"), 1);

  /* wrong binary data */
  char bad[2048];
  memcpy(bad, buf, n);
  int32_t two = 2;
  memcpy(bad + off[0], &two, 4);
  bad_bin("b1.msh", bad, n, 3, "the binary integer after the version line is 2, not 1 in either byte order");
  memcpy(bad, buf, n);
  bad[strlen("$MeshFormat\n2.2 1 ")] = '4';
  bad_bin("b2.msh", bad, n, 2, "data size 4: yfdem reads binary files of 8-byte reals");
  memcpy(bad, buf, n);
  double nan_ = NAN;
  memcpy(bad + off[1], &nan_, 8);
  bad_bin("b3.msh", bad, n, 12, "node 5 has a coordinate that is not a finite number");
  memcpy(bad, buf, n);
  int32_t nine = 9;
  memcpy(bad + off[3], &nine, 4);
  bad_bin("b4.msh", bad, n, 16, "node 9 of element 5 is not defined in $Nodes");
  memcpy(bad, buf, n);
  int32_t t99 = 99;
  memcpy(bad + off[2], &t99, 4);
  bad_bin("b5.msh", bad, n, 16, "an element block of type 99, no Gmsh element type yfdem knows (binary data, element 2 of 5)");
  memcpy(bad, buf, n);
  int32_t five = 5;
  memcpy(bad + off[2] + 4, &five, 4);
  bad_bin("b6.msh", bad, n, 16, "an element block of 5 elements with 2 tags each, after 1 of the 5 elements (binary data): "
          "the counts are wrong");
  memcpy(bad, buf, n);
  int32_t zero = 0;
  memcpy(bad + off[1] - 4, &zero, 4);
  bad_bin("b7.msh", bad, n, 12, "node 5 of the binary data: tag 0 is not in 1..");
  /* binary data in a file that says ASCII */
  memcpy(bad, buf, n);
  bad[strlen("$MeshFormat\n2.2 ")] = '0';
  bad_bin("b8.msh", bad, n, 3, "the file contains binary data although $MeshFormat says ASCII");
}
END_TEST

/* square4.msh as binary MSH 4.1, as Gmsh writes it (size_t counts and node and element tags, int
 * entity tags, types and physical tags, double coordinates; swap: in the other byte order than
 * this machine's), into buf; its length.  off[] receives the offsets of: 0 the header's integer 1,
 * 1 the number of points in $Entities, 2 curve 1's number of physical tags, 3 node 5's tag, 4 node
 * 5's x, 5 the second element block's header, 6 the first element block's type, 7 the last node
 * tag of element 5, 8 surface 1's physical tag. */
static size_t sq41_bin(char *buf, int swap, size_t off[9]) {
  size_t n = 0;
  memset(off, 0, 9 * sizeof *off);
  PUT_S("$MeshFormat\n4.1 1 8\n");
  off[0] = n;
  PUT_I(1);
  PUT_S("\n$EndMeshFormat\n$PhysicalNames\n3\n1 10 \"base\"\n2 1 \"soft\"\n2 2 \"hard\"\n$EndPhysicalNames\n$Entities\n");
  off[1] = n;
  PUT_Z(0);
  PUT_Z(1);
  PUT_Z(2);
  PUT_Z(0);
  static const double box[2][6] = {{0, 0, 0, 1, 0, 0}, {0, 0, 0, 1, 1, 0}};
  PUT_I(1); /* curve 1 in physical curve 10, no bounding points */
  for (int k = 0; k < 6; k++) PUT_D(box[0][k]);
  off[2] = n;
  PUT_Z(1);
  PUT_I(10);
  PUT_Z(0);
  for (int e = 1; e <= 2; e++) { /* surface e in physical surface e */
    PUT_I(e);
    for (int k = 0; k < 6; k++) PUT_D(box[1][k]);
    PUT_Z(1);
    if (e == 1) off[8] = n;
    PUT_I(e);
    PUT_Z(0);
  }
  PUT_S("\n$EndEntities\n$Nodes\n");
  static const long nhead[] = {2, 5, 1, 5};
  for (int k = 0; k < 4; k++) PUT_Z(nhead[k]);
  static const double xy[5][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}, {0.5, 0.5}};
  for (int b = 0; b < 2; b++) { /* curve 1: nodes 1 2; surface 1: nodes 3 4 5 */
    int i0 = b ? 2 : 0, i1 = b ? 5 : 2;
    PUT_I(b + 1);
    PUT_I(1);
    PUT_I(0);
    PUT_Z(i1 - i0);
    for (int i = i0; i < i1; i++) {
      if (i == 4) off[3] = n;
      PUT_Z(i + 1);
    }
    for (int i = i0; i < i1; i++) {
      if (i == 4) off[4] = n;
      for (int k = 0; k < 3; k++) PUT_D(k < 2 ? xy[i][k] : 0.0);
    }
  }
  PUT_S("\n$EndNodes\n$Elements\n");
  static const long ehead[] = {3, 5, 1, 5};
  for (int k = 0; k < 4; k++) PUT_Z(ehead[k]);
  /* blocks: dimension, entity, type, count, then each element's tag and node tags */
  static const long blk[3][4] = {{1, 1, 1, 1}, {2, 1, 2, 2}, {2, 2, 2, 2}};
  static const long el[5][4] = {{1, 1, 2, 0}, {2, 1, 2, 5}, {3, 3, 5, 4}, {4, 2, 3, 5}, {5, 4, 1, 5}};
  for (int b = 0, e = 0; b < 3; b++) {
    if (b == 1) off[5] = n;
    PUT_I(blk[b][0]);
    PUT_I(blk[b][1]);
    if (b == 0) off[6] = n;
    PUT_I(blk[b][2]);
    PUT_Z(blk[b][3]);
    for (int i = 0; i < blk[b][3]; i++, e++)
      for (int k = 0; k < (b ? 4 : 3); k++) {
        if (e == 4 && k == 3) off[7] = n;
        PUT_Z(el[e][k]);
      }
  }
  PUT_S("\n$EndElements\n");
  return n;
}
#undef PUT_S
#undef PUT_B
#undef PUT_I
#undef PUT_Z
#undef PUT_D

/* A binary MSH 4.1 file (buf, n) that must fail: exit 1 at the line of byte `at` (its newline
 * bytes counted, as an editor shows them), naming that byte, with msg. */
static void bad_bin41(const char *name, const char *buf, size_t n, size_t at, const char *msg) {
  int line = 1;
  for (size_t k = 0; k < at; k++) line += buf[k] == '\n';
  char byte[64];
  snprintf(byte, sizeof byte, "(binary data at byte %zu)", at);
  bad_bin_also(name, buf, n, line, msg, byte);
}

/* Binary MSH 4.1 (gmsh -bin, Mesh.Binary = 1), which was refused ("binary MSH 4.1 files are not
 * supported"): the binary file Gmsh writes of a mesh, partitioned or not, gives the scene of its
 * ASCII file (nodes, order, triangles, materials, groups) and the same state_hash after a run. */
START_TEST(test_gmsh_msh41_binary_same_scene) {
  /* two_squares (the partitioned files order nodes by partition), parametric nodes, a skipped
   * $Periodic section */
  static const char *pairs[][2] = {{"two_squares.msh", "two_squares_b.msh"},
                                   {"overlap.msh", "overlap_b.msh"},
                                   {"two_squares_param.msh", "two_squares_paramb.msh"},
                                   {"two_squares_part.msh", "two_squares_partb.msh"},
                                   {"periodic.msh", "periodic_b.msh"}};
  for (int k = 0; k < 5; k++) {
    char f[2][600];
    snprintf(f[0], sizeof f[0], "decks/meshes/%s", pairs[k][0]);
    snprintf(f[1], sizeof f[1], "decks/meshes/%s", pairs[k][1]);
    YfSim *a = gmsh_scene(repo_path(f[0]), "material rock");
    YfSim *b = gmsh_scene(repo_path(f[1]), "material rock");
    if (k < 3) check_two_squares(&b->model, 1.0, 2, 3);
    if (k == 4) { /* the unit square, its bottom side a group */
      ck_assert_double_eq_tol(total_area(&b->model, -1), 1.0, 1e-12);
      int nb;
      ck_assert_double_eq_tol(boundary_length(&b->model, group_of(&b->model, "bottom"), 0.5, 0.5, &nb), 1.0, 1e-12);
    }
    same_scene(&a->model, &b->model, 1);
    free_sim(a);
    free_sim(b);
  }
  same_run(OVERLAP_DECK, "decks/meshes/overlap.msh", "decks/meshes/overlap_b.msh", "4.1 and binary 4.1");
}
END_TEST

/* Binary MSH 4.1 written by hand: either byte order gives square4's scene, as does the file with a
 * skipped section of binary data; a file cut at any byte, or with wrong binary data, is named
 * (exit 1, the file, its line and byte, what is wrong), never misread. */
START_TEST(test_gmsh_msh41_binary_hand_written) {
  static char buf[4096];
  size_t off[9];
  YfSim *a = gmsh_scene(repo_path("decks/meshes/square4.msh"), "");
  for (int swap = 0; swap < 2; swap++) {
    size_t n = sq41_bin(buf, swap, off);
    YfSim *b = gmsh_scene(write_bin("sq41b.msh", buf, n), "");
    check_square4(&b->model, 0, 1);
    same_scene(&a->model, &b->model, 1);
    free_sim(b);
  }
  /* a section yfdem skips, of binary data with newline bytes and an end marker inside a word */
  size_t n = sq41_bin(buf, 0, off);
  {
    static char big[8192];
    char *e = memmem(buf, n, "$Nodes\n", 7);
    ck_assert_ptr_nonnull(e);
    size_t h = (size_t)(e - buf), k = 0;
    memcpy(big, buf, h);
    k = h + (size_t)snprintf(big + h, sizeof big - h, "$Periodic\n");
    for (int i = 0; i < 300; i++) big[k++] = (char)(i % 7 ? i : '\n');
    memcpy(big + k, "x$EndPeriodic\n", 14);
    k += 14;
    k += (size_t)snprintf(big + k, sizeof big - k, "\n$EndPeriodic\n");
    memcpy(big + k, e, n - h);
    YfSim *b = gmsh_scene(write_bin("sq41p.msh", big, k + n - h), "");
    check_square4(&b->model, 0, 1);
    same_scene(&a->model, &b->model, 1);
    free_sim(b);
  }
  free_sim(a);

  /* cut at any byte (the whole file less its last newline is whole) */
  YfSim *b = gmsh_scene(write_bin("sq41b.msh", buf, n - 1), "");
  ck_assert_int_eq(b->model.tri.n, 4);
  free_sim(b);
  cuts_fail(buf, n, strlen("$MeshFormat"), 1);

  /* wrong binary data */
  char bad[4096];
#define PATCH(o, v) do { __typeof__(v) v_ = (v); memcpy(bad, buf, n); memcpy(bad + (o), &v_, sizeof v_); } while (0)
  PATCH(off[0], (int32_t)2);
  bad_bin("c1.msh", bad, n, 3, "the binary integer after the version line is 2, not 1 in either byte order");
  memcpy(bad, buf, n);
  bad[strlen("$MeshFormat\n4.1 1 ")] = '4';
  bad_bin("c2.msh", bad, n, 2, "data size 4: yfdem reads binary files of 8-byte reals and (MSH 4.1) 8-byte size_t");
  memcpy(bad, buf, n);
  bad[strlen("$MeshFormat\n4.1 ")] = '0';
  bad_bin("c3.msh", bad, n, 3, "the file contains binary data although $MeshFormat says ASCII");
  PATCH(off[1], (uint64_t)1 << 63);
  bad_bin41("c4.msh", bad, n, off[1], "$Entities: the number of entities is 9223372036854775808, beyond");
  PATCH(off[1], (uint64_t)200000000);
  bad_bin41("c5.msh", bad, n, off[1], "$Entities: bad entity count 200000000");
  PATCH(off[8], (int32_t)-2147483647 - 1);
  bad_bin41("c6.msh", bad, n, off[8], "$Entities: a physical tag -2147483648 is not in");
  PATCH(off[3], (uint64_t)0);
  bad_bin41("c7.msh", bad, n, off[3], "$Nodes: node tag 0 is not in 1..");
  PATCH(off[3], (uint64_t)4);
  bad_bin41("c8.msh", bad, n, off[3], "$Nodes: node tag 4 is defined twice");
  /* a count the rest of the file cannot hold is refused before its memory is taken, naming the count's bytes
   * (not the header's first, the number of blocks: 2026-11-29) */
  size_t cnt = (size_t)((char *)memmem(buf, n, "$Nodes\n", 7) - buf) + 7 + 8; /* the number of nodes */
  PATCH(cnt, (uint64_t)100000000);
  bad_bin41("c7b.msh", bad, n, cnt, "$Nodes: 100000000 nodes take at least 3200000000 bytes, more than the");
  /* a corrupt field of a block header is named with its own bytes (a field after the first named the block's
   * first byte, or the header's): a node block's entity dimension 7, parametric flag 2; the $Elements header's
   * element count above what yfdem takes, and -1 (a size_t: 2^64 - 1); an element block's count -1 */
  PATCH(cnt + 24, (int32_t)7);
  bad_bin41("c7c.msh", bad, n, cnt + 24, "$Nodes: entity dimension 7 is not 0..3");
  PATCH(cnt + 32, (int32_t)2);
  bad_bin41("c7d.msh", bad, n, cnt + 32, "$Nodes: parametric flag 2 is neither 0 nor 1");
  size_t ecnt = (size_t)((char *)memmem(buf, n, "$Elements\n", 10) - buf) + 10 + 8; /* the number of elements */
  PATCH(ecnt, (uint64_t)600000000);
  bad_bin41("c7e.msh", bad, n, ecnt, "$Elements: bad counts in the $Elements header (3 blocks, 600000000 elements): the "
            "number of elements, 600000000, is above 536870911");
  PATCH(ecnt, (uint64_t)-1);
  bad_bin41("c7f.msh", bad, n, ecnt, "$Elements: the number of elements is 18446744073709551615, beyond "
            "9223372036854775807 (read as a signed integer: -1)");
  PATCH(off[5] + 12, (uint64_t)-1);
  bad_bin41("c7g.msh", bad, n, off[5] + 12, "$Elements: the number of elements in a block is 18446744073709551615, "
            "beyond 9223372036854775807 (read as a signed integer: -1)");
  PATCH(off[4], (double)NAN);
  bad_bin41("c9.msh", bad, n, off[4], "$Nodes: a node x is not a finite number");
  PATCH(off[4] + 8, (double)INFINITY);
  bad_bin41("c10.msh", bad, n, off[4] + 8, "$Nodes: a node y is not a finite number");
  PATCH(off[7], (uint64_t)9);
  bad_bin41("c11.msh", bad, n, off[7], "$Elements: node 9 of element 5 is not defined in $Nodes");
  PATCH(off[5], (int32_t)7);
  bad_bin41("c12.msh", bad, n, off[5], "$Elements: entity dimension 7 is not 0..3");
  /* the entity tag and the type, each at its own bytes (both named the block's count, after them, until 2026-11-29) */
  PATCH(off[5] + 4, (int32_t)7);
  bad_bin41("c13.msh", bad, n, off[5] + 4, "$Elements: the entity tag of an element block is 7: surface 7, which $Entities "
            "does not define");
  PATCH(off[5] + 8, (int32_t)3);
  bad_bin41("c14.msh", bad, n, off[5] + 8, "$Elements: element type 3 (4-node quadrangle) in surface 1 is not supported");
  PATCH(off[5] + 12, (uint64_t)5);
  bad_bin41("c15.msh", bad, n, off[5] + 12, "$Elements: element block 2 declares 5 elements, more than the 4 left");
  /* an element type of unknown size, in a curve of no physical group (its elements are skipped,
   * but their data cannot be): curve 1 without its physical tag */
  size_t m = off[2];
  memcpy(bad, buf, m);
  memset(bad + m, 0, 8);
  memcpy(bad + m + 8, buf + off[2] + 12, n - off[2] - 12);
  int32_t t99 = 99;
  memcpy(bad + off[6] - 4, &t99, 4);
  bad_bin41("c16.msh", bad, n - 4, off[6] - 4, "$Elements: element type 99 in curve 1 is no Gmsh element type yfdem "
            "knows, so its binary data cannot be read past");
#undef PATCH
}
END_TEST

/* Gmsh's own binary files cut at many bytes (every 7th): exit 1, the file named, said to look cut. */
START_TEST(test_gmsh_msh41_binary_cut) {
  static char buf[8192];
  FILE *fp = fopen(repo_path("decks/meshes/two_squares_partb.msh"), "rb");
  ck_assert_ptr_nonnull(fp);
  size_t n = fread(buf, 1, sizeof buf, fp);
  fclose(fp);
  ck_assert(n > 1000 && n < sizeof buf);
  cuts_fail(buf, n, strlen("$MeshFormat"), 7);
}
END_TEST

/* MSH 2.0 and 2.1 (early Gmsh 2 releases) lay out $Nodes and $Elements as 2.2 does; an element's tags
 * after the physical and elementary ones are its partition (2.2: the number of partitions and
 * their list), which the reader skips.  They were refused ("MSH version 2.1 is not supported");
 * they give 2.2's scene.  Binary 2.0 and 2.1 stay refused. */
START_TEST(test_gmsh_msh20_21) {
  YfSim *a = gmsh_scene(variant22("sq22.msh", "$", "$"), "");
  static const char *const v20[][2] = {{"2.2 0 8", "2.0 0 8"}, {"3 2 2 1 1 3 5 4\n", "3 2 3 1 1 1 3 5 4\n"}};
  YfSim *b = gmsh_scene(write_tmp("sq20.msh", text_with(SQ22, v20, 2)), "");
  check_square4(&b->model, 0, 1);
  same_scene(&a->model, &b->model, 1);
  free_sim(b);
  b = gmsh_scene(variant22("sq21.msh", "2.2 0 8", "2.1 0 8"), "");
  same_scene(&a->model, &b->model, 1);
  free_sim(b);
  free_sim(a);
  static char txt[4096];
  FILE *fp = fopen(repo_path("decks/meshes/two_squares_22.msh"), "r");
  ck_assert_ptr_nonnull(fp);
  txt[fread(txt, 1, sizeof txt - 1, fp)] = '\0';
  fclose(fp);
  char *v = strstr(txt, "2.2 0 8");
  ck_assert_ptr_nonnull(v);
  v[2] = '1';
  a = gmsh_scene(repo_path("decks/meshes/two_squares_22.msh"), "");
  b = gmsh_scene(write_tmp("ts21.msh", txt), "");
  check_two_squares(&b->model, 1.0, 2, 3);
  same_scene(&a->model, &b->model, 1);
  free_sim(a);
  free_sim(b);
  bad_msh22("v21b.msh", "2.2 0 8", "2.1 1 8", 2, "binary MSH 2.1 files are not supported: save as MSH 4.1 or 2.2");
  bad_msh22("v23.msh", "2.2 0 8", "2.3 0 8", 2, "MSH version 2.3 is not supported");
}
END_TEST

/* ------------------------------------------------------------------ inline node / triangle */

START_TEST(test_inline_commands) {
  YfSim *s = new_sim();
  YfModel *m = &s->model;
  model_add_material(m, "rock");
  run(s, cmd_node, "node", "10 0 0");
  run(s, cmd_node, "node", "11 2 0");
  run(s, cmd_node, "node", "12 2 1");
  run(s, cmd_node, "node", "13 0 1");
  run(s, cmd_triangle, "triangle", "1 10 11 12 rock");
  run(s, cmd_triangle, "triangle", "2 10 12 13 rock");
  ck_assert_int_eq(m->nbody, 1);
  ck_assert_str_eq(m->body[0].name, "inline");
  ck_assert_int_eq(m->body[0].mat, 0);
  ck_assert_double_eq_tol(total_area(m, -1), 2.0, 1e-15);
  ck_assert_int_eq(m->tri.v[3], 0);
  ck_assert_int_eq(m->tri.v[4], 2);
  ck_assert_int_eq(count_tris(m, group_of(m, "inline")), 2);
  EXPECT_FAIL(s, cmd_node, "node", "11 5 5", 1, "test.deck:7", "node id 11 is defined twice");
  EXPECT_FAIL(s, cmd_triangle, "triangle", "3 10 11 99 rock", 1, "node 99 is not defined");
  EXPECT_FAIL(s, cmd_triangle, "triangle", "3 10 12 11 rock", 1, "triangle 3 is clockwise", "10 11 12");
  EXPECT_FAIL(s, cmd_triangle, "triangle", "1 10 11 13 rock", 1, "triangle id 1 is defined twice");
  EXPECT_FAIL(s, cmd_triangle, "triangle", "3 10 11 13 gneiss", 1, "unknown material", "rock");
  EXPECT_FAIL(s, cmd_node, "node", "14 0 1x", 1, "test.deck:7");
  /* a second inline body; its triangles may not use the first body's nodes */
  run(s, cmd_node, "node", "20 5 0 other");
  run(s, cmd_node, "node", "21 6 0 other");
  EXPECT_FAIL(s, cmd_triangle, "triangle", "7 20 21 13 rock other", 1, "its node 13 is in body 'inline'");
  free_sim(s);
}
END_TEST

START_TEST(test_inline_files) {
  YfSim *s = new_sim();
  YfModel *m = &s->model;
  model_add_material(m, "rock");
  char np[600], tp[600], cmd[700];
  snprintf(np, sizeof np, "%s", write_tmp("n.txt", "# id x y\n1 0 0\n2 1 0  # comment\n\n3 1 1\n4 0 1\n"));
  snprintf(tp, sizeof tp, "%s", write_tmp("t.txt", "1 1 2 3 rock\n2 1 3 4 rock\n"));
  snprintf(cmd, sizeof cmd, "%s blk", np);
  run(s, cmd_nodes, "nodes", cmd);
  snprintf(cmd, sizeof cmd, "%s blk", tp);
  run(s, cmd_triangles, "triangles", cmd);
  ck_assert_int_eq(m->node.n, 4);
  ck_assert_int_eq(m->tri.n, 2);
  ck_assert_str_eq(m->body[0].name, "blk");
  ck_assert_double_eq_tol(total_area(m, -1), 1.0, 1e-15);
  free_sim(s);

  s = new_sim();
  model_add_material(&s->model, "rock");
  run(s, cmd_nodes, "nodes", np);
  char where[800];
  snprintf(cmd, sizeof cmd, "%s", write_tmp("t2.txt", "1 1 2 3 rock\n2 1 4 3 rock\n"));
  snprintf(where, sizeof where, "%s:2: error:", cmd);
  EXPECT_FAIL(s, cmd_triangles, "triangles", cmd, 1, where, "clockwise");
  snprintf(cmd, sizeof cmd, "%s", write_tmp("t3.txt", "1 1 2 3 rock\n\n2 1 3 rock\n"));
  snprintf(where, sizeof where, "%s:3: error:", cmd);
  EXPECT_FAIL(s, cmd_triangles, "triangles", cmd, 1, where, "expected 5 columns");
  snprintf(cmd, sizeof cmd, "%s", write_tmp("n2.txt", "7 0 0\n8 1 zero\n"));
  snprintf(where, sizeof where, "%s:2: error:", cmd);
  EXPECT_FAIL(s, cmd_nodes, "nodes", cmd, 1, where, "'zero' is not a number");
  EXPECT_FAIL(s, cmd_nodes, "nodes", "/nonexistent/n.txt", 2, "test.deck:7", "/nonexistent/n.txt");
  free_sim(s);
}
END_TEST

/* A fracturing body owns one node set per triangle; copies point at their shared node through
 * node.parent.  The diagonal of a split square is still interior, and each boundary edge is
 * given by the copies its own triangle uses. */
START_TEST(test_boundary_edges_with_copies) {
  YfSim *s = new_sim();
  YfModel *m = &s->model;
  model_add_material(m, "rock");
  run(s, cmd_mesh, "mesh", "rect sq rock 0 0 1 1 1 1"); /* triangles (0,1,3) and (0,3,2) */
  int g = group_of(m, "sq");
  /* give triangle 1 its own copies of its three corners */
  for (int k = 0; k < 3; k++) {
    int v = m->tri.v[3 + k];
    int c = model_add_node(m, m->node.x0[v], m->node.y0[v], m->node.id[v], 0);
    m->node.parent[c] = v;
    m->node.gmask[c] = m->node.gmask[v];
    m->tri.v[3 + k] = c;
  }
  int *e, n = mesh_boundary_edges(m, (uint64_t)1 << g, &e);
  ck_assert_int_eq(n, 4);
  double L = 0;
  for (int i = 0; i < n; i++) {
    int a = e[2 * i], b = e[2 * i + 1];
    L += hypot(m->node.x0[b] - m->node.x0[a], m->node.y0[b] - m->node.y0[a]);
    /* edges of triangle 1 (the upper-left one, edges on y = 1 and x = 0) use its copies */
    int upper_left = m->node.y0[a] + m->node.y0[b] == 2.0 || m->node.x0[a] + m->node.x0[b] == 0.0;
    ck_assert_int_eq(a >= 4 && b >= 4, upper_left);
  }
  ck_assert_double_eq_tol(L, 4.0, 1e-15);
  free(e);
  /* without parents the split diagonal would count as two boundary edges */
  for (int k = 4; k < 7; k++) m->node.parent[k] = k;
  n = mesh_boundary_edges(m, (uint64_t)1 << g, &e);
  ck_assert_int_eq(n, 6);
  free(e);
  free_sim(s);
}
END_TEST

/* ------------------------------------------------------------------ regions */

START_TEST(test_region_box_circle_polygon) {
  YfSim *s = new_sim();
  run(s, cmd_region, "region", "b box 0 0 2 1");
  run(s, cmd_region, "region", "c circle 1 1 0.5");
  run(s, cmd_region, "region", "L polygon 0 0 2 0 2 1 1 1 1 2 0 2");
  run(s, cmd_region, "region", "o box 0 0 2 1 side out");
  run(s, cmd_region, "region", "line box 0 1 2 1");
  int b = region_find("b"), c = region_find("c"), L = region_find("L"), o = region_find("o");
  int ln = region_find("line");
  ck_assert_int_eq(region_find("nothere"), -1);
  ck_assert_int_eq(region_count(), 5);
  /* box: interior, edges and corners inside; 1e-6 outside is outside, 1e-10 (round-off) inside */
  ck_assert(region_contains(b, 1, 0.5));
  ck_assert(region_contains(b, 2, 1) && region_contains(b, 0, 0) && region_contains(b, 2, 0.3));
  ck_assert(region_contains(b, 2 + 1e-10, 0.5) && region_contains(b, 1, -1e-10));
  ck_assert(!region_contains(b, 2 + 1e-6, 0.5) && !region_contains(b, 1, -1e-6));
  /* side out: the complement, boundary included */
  ck_assert(!region_contains(o, 1, 0.5));
  ck_assert(region_contains(o, 2, 0.5) && region_contains(o, 3, 0.5));
  /* a flat box selects a line */
  ck_assert(region_contains(ln, 0.7, 1.0) && !region_contains(ln, 0.7, 1.0 - 1e-6));
  /* circle */
  ck_assert(region_contains(c, 1, 1) && region_contains(c, 1.5, 1) && region_contains(c, 1, 0.5));
  ck_assert(region_contains(c, 1 + 0.5 / sqrt(2.0), 1 + 0.5 / sqrt(2.0)));
  ck_assert(!region_contains(c, 1.36, 1.36));
  /* L-shaped (concave) polygon: the notch is outside, its edges inside */
  ck_assert(region_contains(L, 0.5, 1.5) && region_contains(L, 1.5, 0.5));
  ck_assert(!region_contains(L, 1.5, 1.5));
  ck_assert(region_contains(L, 1.5, 1.0) && region_contains(L, 1.0, 1.5) && region_contains(L, 1, 1));
  ck_assert(region_contains(L, 0, 1.3) && region_contains(L, 2, 0));
  ck_assert(!region_contains(L, -1e-6, 1.0) && !region_contains(L, 1.0 + 1e-6, 1.5));
  EXPECT_FAIL(s, cmd_region, "region", "p polygon 0 0 1 0", 1, "at least 3 points");
  EXPECT_FAIL(s, cmd_region, "region", "p polygon 0 0 1 0 1 1 2", 1, "X Y pairs");
  EXPECT_FAIL(s, cmd_region, "region", "b box 0 0 1 1", 1, "region already exists");
  EXPECT_FAIL(s, cmd_region, "region", "p box 0 0 -1 1", 1, "X1 must not be less than X0");
  EXPECT_FAIL(s, cmd_region, "region", "p circle 0 0 0", 1, "test.deck:7");
  EXPECT_FAIL(s, cmd_region, "region", "p sphere 0 0 1", 1, "sphere");
  free_sim(s);
}
END_TEST

/* ------------------------------------------------------------------ groups */

START_TEST(test_groups) {
  YfSim *s = new_sim();
  YfModel *m = &s->model;
  model_add_material(m, "steel");
  run(s, cmd_mesh, "mesh", "rect plate steel 0 0 1 1 4 4");  /* node (i,j) = 5 j + i, h = 0.25 */
  run(s, cmd_mesh, "mesh", "rect other steel 2 0 3 1 1 1");
  run(s, cmd_region, "region", "left box 0 0 0 1");
  run(s, cmd_region, "region", "bottom box -1 0 5 0");
  run(s, cmd_region, "region", "lowhalf box 0 0 1 0.5");
  run(s, cmd_group, "group", "left node region left");
  run(s, cmd_group, "group", "bot node region bottom body plate");
  run(s, cmd_group, "group", "allbot node region bottom");
  run(s, cmd_group, "group", "low both region lowhalf");
  int gl = group_of(m, "left"), gb = group_of(m, "bot"), gab = group_of(m, "allbot"), glo = group_of(m, "low");
  ck_assert_int_eq(count_nodes(m, gl), 5);
  ck_assert_int_eq(count_tris(m, gl), 0);
  ck_assert_int_eq(count_nodes(m, gb), 5);
  ck_assert_int_eq(count_nodes(m, gab), 7);
  ck_assert_int_eq(count_nodes(m, glo), 15); /* rows j = 0, 1, 2 */
  ck_assert_int_eq(count_tris(m, glo), 16);  /* centroids of the lower two rows of cells */
  /* boundary edges of the left side: 4 edges of length 0.25, outward normal (-1, 0) */
  int *e, n = mesh_boundary_edges(m, (uint64_t)1 << gl, &e);
  ck_assert_int_eq(n, 4);
  for (int i = 0; i < n; i++) {
    double dx = m->node.x0[e[2 * i + 1]] - m->node.x0[e[2 * i]];
    double dy = m->node.y0[e[2 * i + 1]] - m->node.y0[e[2 * i]];
    ck_assert_double_eq_tol(dy / 0.25, -1.0, 1e-12); /* normal (dy, -dx) = (-1, 0) */
    ck_assert(dx == 0.0);
  }
  free(e);
  /* set operations */
  run(s, cmd_group, "group", "u union left bot");
  run(s, cmd_group, "group", "x intersect left bot");
  run(s, cmd_group, "group", "d subtract bot left");
  run(s, cmd_group, "group", "d2 subtract low left bot");
  ck_assert_int_eq(count_nodes(m, group_of(m, "u")), 9);
  ck_assert_int_eq(count_nodes(m, group_of(m, "x")), 1);
  ck_assert_int_eq(count_nodes(m, group_of(m, "d")), 4);
  ck_assert_int_eq(count_nodes(m, group_of(m, "d2")), 15 - 3 - 4);
  ck_assert_int_eq(count_tris(m, group_of(m, "d2")), 16);
  ck_assert_int_eq(count_tris(m, group_of(m, "x")), 0);
  /* ids, nearest, body */
  run(s, cmd_group, "group", "ids node id 1 25 26");
  int gi = group_of(m, "ids");
  ck_assert_int_eq(count_nodes(m, gi), 3);
  ck_assert(m->node.gmask[0] >> gi & 1 && m->node.gmask[24] >> gi & 1 && m->node.gmask[25] >> gi & 1);
  run(s, cmd_group, "group", "t3 tri id 3");
  ck_assert_int_eq(count_tris(m, group_of(m, "t3")), 1);
  ck_assert(m->tri.gmask[2] >> group_of(m, "t3") & 1);
  run(s, cmd_group, "group", "tip node nearest 0.74 0.26");
  int gt = group_of(m, "tip");
  ck_assert_int_eq(count_nodes(m, gt), 1);
  ck_assert(m->node.gmask[5 + 3] >> gt & 1);
  run(s, cmd_group, "group", "ob both body other");
  ck_assert_int_eq(count_nodes(m, group_of(m, "ob")), 4);
  ck_assert_int_eq(count_tris(m, group_of(m, "ob")), 2);
  /* a group only grows: adding to an existing group */
  run(s, cmd_group, "group", "left node id 3");
  ck_assert_int_eq(count_nodes(m, gl), 6);
  /* errors and the empty warning */
  EXPECT_FAIL(s, cmd_group, "group", "z union left nothere", 1, "test.deck:7", "unknown group",
              "plate, other, left");
  EXPECT_FAIL(s, cmd_group, "group", "z node region nowhere", 1, "unknown region", "left, bottom, lowhalf");
  EXPECT_FAIL(s, cmd_group, "group", "z both body rock", 1, "unknown body", "plate, other");
  EXPECT_FAIL(s, cmd_group, "group", "z node id 1 999", 1, "no node has this id");
  EXPECT_FAIL(s, cmd_group, "group", "z both id 1 99", 1, "no node or triangle has this id");
  /* nodes have ids 1..29, triangles 1..34: 30 names a triangle only */
  run(s, cmd_group, "group", "nt both id 26 30");
  ck_assert_int_eq(count_nodes(m, group_of(m, "nt")), 1);
  ck_assert_int_eq(count_tris(m, group_of(m, "nt")), 2);
  EXPECT_FAIL(s, cmd_group, "group", "z tri nearest 0 0", 1, "selects a node");
  EXPECT_FAIL(s, cmd_group, "group", "plate node id 1", 1, "group of body");
  run(s, cmd_region, "region", "far circle 10 10 1");
  EXPECT_FAIL(s, cmd_group, "group", "empty node region far", 0, "test.deck:7: warning:", "empty");
  free_sim(s);
}
END_TEST

/* The edge sort (a counting sort by lo, then each node's run) must give qsort's order with the
 * (lo, hi, t, k) comparator: on a real mesh's edges (shared edges: equal (lo, hi)), on random
 * records with long runs (a fan: more than the insertion-sort limit), and with a negative lo
 * (the general path). */
static int edge_rec_cmp(const void *pa, const void *pb) {
  const YfEdgeRec *a = pa, *b = pb;
  if (a->lo != b->lo) return a->lo < b->lo ? -1 : 1;
  if (a->hi != b->hi) return a->hi < b->hi ? -1 : 1;
  if (a->t != b->t) return a->t < b->t ? -1 : 1;
  return (a->k > b->k) - (a->k < b->k);
}

START_TEST(test_edge_sort_matches_qsort) {
  enum { N = 30000 };
  YfEdgeRec *a = malloc(N * sizeof *a), *b = malloc(N * sizeof *b);
  unsigned long long rng = 12345;
#define RND() (rng = rng * 6364136223846793005ull + 1442695040888963407ull, (int)(rng >> 33))
  for (int trial = 0; trial < 4; trial++) {
    long n = 0;
    if (trial == 0) { /* the edges of a structured mesh, 3 per triangle, in generation order */
      const int nx = 60, ny = 40;
      for (int t = 0; t < 2 * nx * ny; t++) {
        int c = t / 2, i = c % nx, j = c / nx, n0 = j * (nx + 1) + i, v[3];
        if (t % 2 == 0) { v[0] = n0; v[1] = n0 + 1; v[2] = n0 + nx + 2; }
        else { v[0] = n0; v[1] = n0 + nx + 2; v[2] = n0 + nx + 1; }
        for (int k = 0; k < 3; k++) {
          int p = v[k], q = v[(k + 1) % 3];
          a[n++] = (YfEdgeRec){p < q ? p : q, p < q ? q : p, t, k};
        }
      }
    } else {
      for (; n < N; n++) {
        int lo = trial == 1 ? RND() % 5000 : RND() % 40; /* trial 2: runs of ~750 (qsort path) */
        a[n] = (YfEdgeRec){lo, lo + RND() % 7, RND() % 9000, RND() % 3};
        if (trial == 3 && n % 1000 == 7) a[n].lo = -1 - RND() % 3; /* not a node index */
      }
    }
    memcpy(b, a, (size_t)n * sizeof *a);
    qsort(b, (size_t)n, sizeof *b, edge_rec_cmp);
    yf_edges_sort(a, n);
    ck_assert_msg(memcmp(a, b, (size_t)n * sizeof *a) == 0, "trial %d: the order differs from qsort's", trial);
  }
#undef RND
  free(a);
  free(b);
}
END_TEST

/* An inline triangle added after a partitioned run names its nodes by the ids they were given:
 * the partition renumbered the nodes and the id map kept the old indices ('triangle 4 2 6 5'
 * read as clockwise, or took other nodes).  The same scene with 1 part and with 2 moves alike. */
START_TEST(test_inline_after_partition) {
  double ke[2], ux[2];
  for (int p = 0; p < 2; p++) {
    char deck[1024];
    snprintf(deck, sizeof deck, "material m elastic rho 2000 E 1e9 nu 0.25 plane_stress\nnode 1 0 0\nnode 2 1 0\n"
             "node 3 2 0\nnode 4 0 1\nnode 5 1 1\nnode 6 2 1\ntriangle 1 1 2 5 m\ntriangle 2 1 5 4 m\n"
             "triangle 3 2 3 6 m\npartition metis parts %d\ntimestep 1e-6\nrun 0\ntriangle 4 2 6 5 m\n"
             "group tip node nearest 2 1\nvelocity tip set 1 0\nrun 200\n", p + 1);
    YfSim *s = yft_run(deck);
    char err[256] = "";
    ck_assert_msg(sim_query(s, "ke", &ke[p], err, sizeof err) == 1 && sim_query(s, "ux_tip", &ux[p], err, sizeof err) == 1,
                  "%s", err);
    sim_free(s);
  }
  ck_assert_msg(fabs(ke[1] - ke[0]) <= 1e-12 * ke[0] && fabs(ux[1] - ux[0]) <= 1e-12 * fabs(ux[0]),
                "parts 1: ke %.17g ux %.17g; parts 2: ke %.17g ux %.17g", ke[0], ux[0], ke[1], ux[1]);
}
END_TEST

Suite *mesh_suite(void) {
  Suite *s = suite_create("mesh");
  TCase *tc = tcase_create("rect");
  tcase_add_test(tc, test_rect_patterns);
  tcase_add_test(tc, test_edge_sort_matches_qsort);
  tcase_add_test(tc, test_rect_diagonals);
  tcase_add_test(tc, test_rect_two_bodies_ids_min_edge);
  tcase_add_test(tc, test_rect_errors);
  tcase_add_test(tc, test_boundary_edges_with_copies);
  suite_add_tcase(s, tc);
  tc = tcase_create("gmsh");
  tcase_add_test(tc, test_gmsh_two_squares);
  tcase_add_test(tc, test_gmsh_parametric_scale_mapping);
  tcase_add_test(tc, test_gmsh_hand_written);
  tcase_add_test(tc, test_gmsh_same_as_file);
  tcase_add_test(tc, test_gmsh_malformed);
  tcase_add_test(tc, test_gmsh_partitioned);
  tcase_add_test(tc, test_gmsh_shared_ids_warned);
  tcase_add_test(tc, test_gmsh_shift);
  tcase_add_test(tc, test_gmsh_flat_plane_off_zero);
  tcase_add_test(tc, test_gmsh_too_many_groups);
  tcase_add_test(tc, test_gmsh_entities_after_elements);
  tcase_add_test(tc, test_gmsh_deck_errors);
  tcase_add_test(tc, test_gmsh_no_entities_unnamed);
  tcase_add_test(tc, test_gmsh_unnamed_shared_tag);
  tcase_add_test(tc, test_gmsh_msh22_same_scene);
  tcase_add_test(tc, test_gmsh_msh22_overlapping_groups);
  tcase_add_test(tc, test_gmsh_msh22_parametric);
  tcase_add_test(tc, test_gmsh_msh22_hand_written);
  tcase_add_test(tc, test_gmsh_msh22_malformed);
  tcase_add_test(tc, test_gmsh_msh22_binary);
  tcase_set_timeout(tc, 30); /* the binary test reads its file cut at each of ~450 bytes, in a child each */
  suite_add_tcase(s, tc);
  tc = tcase_create("gmsh_bin41");
  tcase_add_test(tc, test_gmsh_msh41_binary_same_scene);
  tcase_add_test(tc, test_gmsh_msh41_binary_hand_written);
  tcase_add_test(tc, test_gmsh_msh41_binary_cut);
  tcase_add_test(tc, test_gmsh_msh20_21);
  tcase_set_timeout(tc, 60); /* the files are read cut at ~1700 bytes in all, in a child each */
  suite_add_tcase(s, tc);
  tc = tcase_create("inline");
  tcase_add_test(tc, test_inline_commands);
  tcase_add_test(tc, test_inline_files);
  tcase_add_test(tc, test_inline_after_partition);
  suite_add_tcase(s, tc);
  tc = tcase_create("sets");
  tcase_add_test(tc, test_region_box_circle_polygon);
  tcase_add_test(tc, test_groups);
  suite_add_tcase(s, tc);
  return s;
}
