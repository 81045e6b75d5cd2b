/* check_support.c: shared helpers of the test suites (yftest.h); defines no suite. */
#include <check.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>
#include "deck.h"
#include "run.h"
#include "yftest.h"

static YfSim t_sim;
/* the last in-process run's deck and simulation, freed by the next run (sim_free leaves the deck,
 * and a second sim_free is harmless), so a test that runs several decks leaks nothing */
static YfDeck *t_deck;

static YfDeck *new_deck(void) {
  deck_free(t_deck);
  sim_free(&t_sim); /* what the last in-process run left, when its test did not free it */
  sim_init(&t_sim);
  t_sim.progress = 0;
  return t_deck = deck_new(&t_sim);
}

YfSim *yft_run(const char *deck_text) {
  YfDeck *d = new_deck();
  FILE *fp = fmemopen((void *)deck_text, strlen(deck_text), "r");
  fflush(stdout);
  int saved = dup(1);
  FILE *devnull = fopen("/dev/null", "w");
  dup2(fileno(devnull), 1);
  deck_run_stream(d, fp, "test.deck");
  fflush(stdout);
  dup2(saved, 1);
  close(saved);
  fclose(devnull);
  fclose(fp);
  return &t_sim;
}

YfSim *yft_run_deck(const char *path, const char *const *vars) {
  YfDeck *d = new_deck();
  for (int i = 0; vars && vars[i]; i += 2) deck_set_var(d, vars[i], vars[i + 1]);
  fflush(stdout);
  int saved = dup(1);
  FILE *devnull = fopen("/dev/null", "w");
  dup2(fileno(devnull), 1);
  deck_run_file(d, path, NULL);
  fflush(stdout);
  dup2(saved, 1);
  close(saved);
  fclose(devnull);
  return &t_sim;
}

char *yft_slurp(const char *path, int empty_if_missing) {
  FILE *f = fopen(path, "rb");
  if (!f) return empty_if_missing ? calloc(1, 1) : NULL;
  fseek(f, 0, SEEK_END);
  long n = ftell(f);
  fseek(f, 0, SEEK_SET);
  char *b = calloc(1, (size_t)(n > 0 ? n : 0) + 1);
  if (n > 0 && fread(b, 1, (size_t)n, f) != (size_t)n) b[0] = 0;
  fclose(f);
  return b;
}

int yft_exists(const char *path) {
  struct stat st;
  return stat(path, &st) == 0;
}

const char *yft_binary(void) {
  static char abs[1024];
  const char *bin = getenv("YFDEM") ? getenv("YFDEM") : "./yfdem";
  if (bin[0] == '/' || !getcwd(abs, sizeof abs - strlen(bin) - 2)) return bin;
  strcat(abs, "/");
  strcat(abs, bin);
  return abs;
}

void yft_put_file(const char *dir, const char *name, const char *text) {
  char path[1024];
  snprintf(path, sizeof path, "%s/%s", dir, name);
  FILE *fp = fopen(path, "w");
  ck_assert_ptr_nonnull(fp);
  fputs(text, fp);
  fclose(fp);
}

char *yft_deck_dir(const char *name, const char *deck_text) {
  char tmpl[] = "/tmp/yft_XXXXXX";
  char *dir = mkdtemp(tmpl);
  ck_assert_ptr_nonnull(dir);
  yft_put_file(dir, name, deck_text);
  return strdup(dir);
}

void yft_rm_dir(char *dir) {
  if (!dir) return;
  ck_assert_msg(!strncmp(dir, "/tmp/yft_", 9) && !strchr(dir, '\''), "not a test directory: %s", dir);
  char cmd[600];
  snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
  ck_assert_int_eq(system(cmd), 0);
  free(dir);
}

int yft_run_binary(const char *name, const char *deck_text, const char *extra_args, char **err, char **dirout) {
  char *dir = yft_deck_dir(name, deck_text);
  char errpath[512], cmd[4096];
  snprintf(errpath, sizeof errpath, "%s/stderr.txt", dir);
  const char *bin = yft_binary();
  snprintf(cmd, sizeof cmd, "cd %s && OMP_NUM_THREADS=${OMP_NUM_THREADS:-1} %s -in %s %s >/dev/null 2>%s", dir, bin,
           name, extra_args ? extra_args : "", errpath);
  int st = system(cmd);
  int code = WIFEXITED(st) ? WEXITSTATUS(st) : 128;
  if (err) {
    FILE *fe = fopen(errpath, "r");
    char *buf = calloc(1, 65536);
    if (fe) {
      size_t k = fread(buf, 1, 65535, fe);
      buf[k] = 0;
      fclose(fe);
    }
    *err = buf;
  }
  if (dirout) *dirout = dir;
  else free(dir);
  return code;
}

int yft_node_at(const YfSim *s, double x, double y) {
  int best = -1;
  double bd = INFINITY;
  for (int i = 0; i < s->model.node.n; i++) {
    double d = hypot(s->model.node.x0[i] - x, s->model.node.y0[i] - y);
    if (d < bd) { bd = d; best = i; }
  }
  return best;
}

double yft_front_arrival(YfSim *s, int probe, int comp, double t_max) {
  const double *v = comp ? s->model.node.vy : s->model.node.vx;
  double tprev = s->time, vprev = v[probe];
  while (s->time < t_max) {
    run_steps(s, 1);
    /* velocities live at half steps: v_{n+1/2} belongs to t - dt/2 */
    double vn = v[probe], t = s->time - 0.5 * s->dt;
    if (vn >= 0.5) return tprev + (0.5 - vprev) / (vn - vprev) * (t - tprev);
    tprev = t;
    vprev = vn;
  }
  return -1;
}


int yft_child_run(void (*fn)(void *), void *arg, char *msg, size_t n) {
  char path[] = "/tmp/yfx_XXXXXX";
  int fd = mkstemp(path);
  ck_assert_int_ge(fd, 0);
  fflush(stdout);
  fflush(stderr);
  pid_t pid = fork();
  ck_assert_int_ge(pid, 0);
  if (pid == 0) {
    dup2(fd, 2);
    (void)!freopen("/dev/null", "w", stdout);
    fn(arg);
    fflush(NULL);
    _exit(0);
  }
  int st = 0;
  waitpid(pid, &st, 0);
  ssize_t k = pread(fd, msg, n - 1, 0);
  msg[k > 0 ? k : 0] = 0;
  close(fd);
  unlink(path);
  return WIFEXITED(st) ? WEXITSTATUS(st) : 128;
}
