/* check_layers.c: the layers of src/ point one way (README, Source layout).
 *
 * Each folder of src/ is a layer; a file may include headers of its own layer and of the layers
 * below it, as the table ALLOWED says, and main.c (src/ itself) anything.  The scan reads every
 * `#include "x"` of src/ and finds the folder that holds x; any upward include fails the test.
 * A second test builds a small tree with one upward include and checks that the scan finds it,
 * so the first test can fail.
 *
 * The include graph of modules (x.c and x.h are module x): Tarjan's strongly connected
 * components, the largest printed.  The bar is no cycle of more than three modules;
 * the test fails when the largest grows beyond MAX_CYCLE, today's.  A synthetic tree with a
 * three-module cycle checks that the scan sees cycles.
 */
#include <check.h>
#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* Layer folders, lowest first, and what each may include (its own folder and those listed). */
static const char *const ALLOWED[][2] = {
    {"base", "base"},
    {"model", "base model"},
    {"kernel", "base model kernel"},
    {"step", "base model kernel step"},
    {"par", "base model kernel step par"}, /* MPI ranks (make mpi): the implementation of step/par.h */
    {"y2d", "base model kernel step y2d"},
    {"io", "base model kernel step y2d io"},
    {"deck", "base model kernel step y2d io deck"},
};
enum { NLAYER = sizeof ALLOWED / sizeof ALLOWED[0] };

/* The largest include cycle allowed: today's (joint.c and contact.c include each other's
 * headers); issue #23 asked for at most 3. */
#define MAX_CYCLE 2

#define MAXF 512
typedef struct {
  char dir[32];   /* layer folder, "" for src/ itself */
  char name[64];  /* file name */
  char mod[64];   /* module: name without extension */
  int nin;
  char inc[48][64];
} SrcFile;

static int is_source(const char *n) {
  const char *d = strrchr(n, '.');
  return d && (!strcmp(d, ".c") || !strcmp(d, ".h") || !strcmp(d, ".def"));
}

static void read_includes(const char *path, SrcFile *f) {
  FILE *fp = fopen(path, "r");
  ck_assert_msg(fp != NULL, "cannot read %s", path);
  char line[512];
  while (fgets(line, sizeof line, fp)) {
    char h[64];
    if (sscanf(line, " # include \"%63[^\"]\"", h) == 1 && f->nin < 48) snprintf(f->inc[f->nin++], 64, "%s", h);
  }
  fclose(fp);
}

/* Every source file of root (a src/ tree): root itself, then each folder. */
static int scan_tree(const char *root, SrcFile *fs) {
  int n = 0;
  for (int l = -1; l < NLAYER; l++) {
    char dir[512];
    snprintf(dir, sizeof dir, "%s%s%s", root, l >= 0 ? "/" : "", l >= 0 ? ALLOWED[l][0] : "");
    DIR *d = opendir(dir);
    if (!d) continue;
    struct dirent *e;
    while ((e = readdir(d))) {
      if (!is_source(e->d_name) || n == MAXF) continue;
      SrcFile *f = &fs[n++];
      memset(f, 0, sizeof *f);
      snprintf(f->dir, sizeof f->dir, "%.31s", l >= 0 ? ALLOWED[l][0] : "");
      snprintf(f->name, sizeof f->name, "%.63s", e->d_name);
      snprintf(f->mod, sizeof f->mod, "%.63s", e->d_name);
      *strrchr(f->mod, '.') = 0;
      char path[1100];
      snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
      read_includes(path, f);
    }
    closedir(d);
  }
  return n;
}

static const SrcFile *find_file(const SrcFile *fs, int n, const char *name) {
  for (int i = 0; i < n; i++)
    if (!strcmp(fs[i].name, name)) return &fs[i];
  return NULL;
}

static int allowed(const char *from, const char *to) {
  if (!from[0]) return 1; /* main.c: the top */
  for (int l = 0; l < NLAYER; l++) {
    if (strcmp(ALLOWED[l][0], from)) continue;
    char list[256];
    snprintf(list, sizeof list, "%s", ALLOWED[l][1]);
    for (char *w = strtok(list, " "); w; w = strtok(NULL, " "))
      if (!strcmp(w, to)) return 1;
    return 0;
  }
  return 0; /* a folder that is not in the table */
}

/* Upward includes of the tree (written to rep). */
static int violations(const char *root, char *rep, size_t cap) {
  static SrcFile fs[MAXF];
  int n = scan_tree(root, fs), bad = 0;
  size_t k = 0;
  rep[0] = 0;
  for (int i = 0; i < n; i++)
    for (int j = 0; j < fs[i].nin; j++) {
      const SrcFile *h = find_file(fs, n, fs[i].inc[j]);
      if (!h || allowed(fs[i].dir, h->dir)) continue;
      char who[128];
      snprintf(who, sizeof who, "%.31s/%.63s", fs[i].dir, fs[i].name);
      bad++;
      int w = snprintf(rep + k, cap - k, "%s includes %s/%s (a layer above); ", who, h->dir, h->name);
      if (w > 0 && (size_t)w < cap - k) k += (size_t)w;
    }
  return bad;
}

START_TEST(test_layers_one_direction) {
  char rep[4096];
  int bad = violations("src", rep, sizeof rep);
  ck_assert_msg(bad == 0, "%d upward include(s): %s", bad, rep);
  printf("layers: %d folders, no upward include\n", NLAYER);
}
END_TEST

static void put(const char *path, const char *text) {
  FILE *f = fopen(path, "w");
  ck_assert_ptr_nonnull(f);
  fputs(text, f);
  fclose(f);
}

/* Write root/rel (rel = FOLDER/FILE; the folder is made when missing). */
static void tree_put(const char *root, const char *rel, const char *text) {
  char p[512];
  snprintf(p, sizeof p, "%s/%s", root, rel);
  *strrchr(p, '/') = 0;
  mkdir(p, 0700);
  snprintf(p, sizeof p, "%s/%s", root, rel);
  put(p, text);
}

static void tree_remove(const char *root) {
  char cmd[300];
  snprintf(cmd, sizeof cmd, "rm -rf %s", root);
  ck_assert_int_eq(system(cmd), 0);
}

/* The scan finds a kernel file that includes a step header, and accepts the reverse. */
START_TEST(test_layers_catch_upward_include) {
  char root[] = "/tmp/yf_layersXXXXXX";
  ck_assert_ptr_nonnull(mkdtemp(root));
  tree_put(root, "kernel/k.h", "#pragma once\n");
  tree_put(root, "step/s.h", "#include \"k.h\"\n");
  char rep[1024];
  ck_assert_int_eq(violations(root, rep, sizeof rep), 0);
  tree_put(root, "kernel/k.c", "#include \"k.h\"\n#include \"s.h\"\n");
  ck_assert_int_eq(violations(root, rep, sizeof rep), 1);
  ck_assert_msg(strstr(rep, "kernel/k.c includes step/s.h") != NULL, "report: %s", rep);
  tree_remove(root);
}
END_TEST

/* ---- include cycles: Tarjan's SCCs over modules ---- */
static int nmod;
static char mods[MAXF][64];
static unsigned char adj[MAXF][MAXF];
static int idx_[MAXF], low[MAXF], onst[MAXF], st[MAXF], sp, counter, largest, largest_at[MAXF], nlargest;

static int mod_index(const char *m) {
  for (int i = 0; i < nmod; i++)
    if (!strcmp(mods[i], m)) return i;
  snprintf(mods[nmod], 64, "%s", m);
  return nmod++;
}

static void strong(int v) {
  idx_[v] = low[v] = ++counter;
  st[sp++] = v;
  onst[v] = 1;
  for (int w = 0; w < nmod; w++) {
    if (!adj[v][w]) continue;
    if (!idx_[w]) {
      strong(w);
      if (low[w] < low[v]) low[v] = low[w];
    } else if (onst[w] && idx_[w] < low[v]) {
      low[v] = idx_[w];
    }
  }
  if (low[v] != idx_[v]) return;
  int comp[MAXF], nc = 0, w;
  do {
    w = st[--sp];
    onst[w] = 0;
    comp[nc++] = w;
  } while (w != v);
  if (nc > largest) {
    largest = nc;
    nlargest = nc;
    memcpy(largest_at, comp, (size_t)nc * sizeof(int));
  }
}

/* The largest strongly connected component of the module include graph of root (a src/ tree);
 * its modules' names, space-separated, in names. */
static int largest_cycle(const char *root, char *names, size_t cap) {
  static SrcFile fs[MAXF];
  int n = scan_tree(root, fs);
  nmod = 0;
  memset(adj, 0, sizeof adj);
  for (int i = 0; i < n; i++) mod_index(fs[i].mod);
  for (int i = 0; i < n; i++)
    for (int j = 0; j < fs[i].nin; j++) {
      const SrcFile *h = find_file(fs, n, fs[i].inc[j]);
      if (!h) continue;
      int a = mod_index(fs[i].mod), b = mod_index(h->mod);
      if (a != b) adj[a][b] = 1;
    }
  memset(idx_, 0, sizeof idx_);
  memset(onst, 0, sizeof onst);
  sp = counter = largest = nlargest = 0;
  for (int v = 0; v < nmod; v++)
    if (!idx_[v]) strong(v);
  names[0] = 0;
  for (int i = 0; i < nlargest; i++) {
    strncat(names, i ? " " : "", cap - strlen(names) - 1);
    strncat(names, mods[largest_at[i]], cap - strlen(names) - 1);
  }
  return largest;
}

START_TEST(test_no_long_include_cycle) {
  char names[1024];
  int big = largest_cycle("src", names, sizeof names);
  printf("include graph: %d modules, largest cycle %d module(s): %s\n", nmod, big, names);
  ck_assert_msg(big <= MAX_CYCLE, "an include cycle spans %d modules (at most %d): %s", big, MAX_CYCLE, names);
}
END_TEST

/* The cycle scan finds a cycle of three modules across two folders (a -> b -> c -> a), and none
 * once the include that closes it goes. */
START_TEST(test_layers_catch_cycle) {
  char root[] = "/tmp/yf_cyclesXXXXXX";
  ck_assert_ptr_nonnull(mkdtemp(root));
  static const char *const files[][2] = {
      {"step/a.h", "#include \"b.h\"\n"},
      {"step/b.h", "#pragma once\n"},
      {"step/b.c", "#include \"b.h\"\n#include \"c.h\"\n"},
      {"io/c.h", "#pragma once\n"},
      {"io/c.c", "#include \"c.h\"\n#include \"a.h\"\n"}, /* closes a -> b -> c -> a */
  };
  for (size_t k = 0; k < sizeof files / sizeof files[0]; k++) tree_put(root, files[k][0], files[k][1]);
  char names[1024];
  ck_assert_int_eq(largest_cycle(root, names, sizeof names), 3);
  tree_put(root, "io/c.c", "#include \"c.h\"\n");
  ck_assert_int_eq(largest_cycle(root, names, sizeof names), 1);
  tree_remove(root);
}
END_TEST

Suite *layers_suite(void) {
  Suite *s = suite_create("layers");
  TCase *t = tcase_create("includes");
  tcase_add_test(t, test_layers_one_direction);
  tcase_add_test(t, test_layers_catch_upward_include);
  tcase_add_test(t, test_no_long_include_cycle);
  tcase_add_test(t, test_layers_catch_cycle);
  suite_add_tcase(s, t);
  return s;
}
