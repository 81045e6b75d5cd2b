/* summary.c: the -summary JSON and the state hash (see summary.h).
 *
 * The summary is what scripts and CI read after a run, so it is written on every exit path
 * (main's cleanup calls summary_write with the exit code) and must always be valid JSON: strings
 * are escaped, non-finite numbers become null, and the file is replaced atomically so a reader
 * never sees half of it.  Numbers are printed with the fewest digits that read back to the same
 * double.  Extra keys live in a small static list because the modules that add them (joints,
 * contact, benchmarks) have no other channel to main.
 */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include "summary.h"
#include "wfile.h"
#include "err.h"

#ifndef YF_VERSION
#define YF_VERSION "0.1.0"
#endif

static long cnt_joints, cnt_broken, cnt_pairs;

typedef struct {
  char *key;
  char *json; /* NULL: number in val */
  double val;
} YfExtra;
static YfExtra *extras;
static int nextra, capextra;

static const char *const std_keys[] = {
    "version", "status", "reason", "steps", "time", "nodes", "elements", "joints",
    "joints_broken", "contact_pairs", "energy", "wall_s", "element_steps_per_s", "threads",
    "state_hash", NULL};

void summary_set_counts(long joints, long joints_broken, long contact_pairs) {
  cnt_joints = joints;
  cnt_broken = joints_broken;
  cnt_pairs = contact_pairs;
}

static YfExtra *extra_slot(const char *key) {
  for (int i = 0; std_keys[i]; i++) YF_ASSERT(strcmp(std_keys[i], key) != 0);
  for (int i = 0; i < nextra; i++)
    if (strcmp(extras[i].key, key) == 0) {
      free(extras[i].json);
      extras[i].json = NULL;
      return &extras[i];
    }
  if (nextra == capextra) {
    capextra = capextra ? 2 * capextra : 16;
    extras = yf_realloc(extras, (size_t)capextra * sizeof *extras, "summary keys");
  }
  YfExtra *e = &extras[nextra++];
  e->key = yf_strdup(key);
  e->json = NULL;
  return e;
}

void summary_add_number(const char *key, double v) { extra_slot(key)->val = v; }

void summary_add_raw(const char *key, const char *json_text) {
  extra_slot(key)->json = yf_strdup(json_text);
}

void summary_clear_extras(void) {
  for (int i = 0; i < nextra; i++) {
    free(extras[i].key);
    free(extras[i].json);
  }
  free(extras);
  extras = NULL;
  nextra = capextra = 0;
}

uint64_t sim_state_hash(const YfSim *s) {
  const YfNodes *n = &s->model.node;
  uint64_t h = 0xcbf29ce484222325ull; /* FNV-1a 64 offset basis */
  for (int i = 0; i < n->n; i++) {
    const double v[4] = {n->x[i], n->y[i], n->vx[i], n->vy[i]};
    const unsigned char *b = (const unsigned char *)v;
    for (size_t k = 0; k < sizeof v; k++) {
      h ^= b[k];
      h *= 0x100000001b3ull; /* FNV 64 prime */
    }
  }
  return h;
}

/* Length of the valid UTF-8 sequence at s (1..4), or 0 when the bytes are not valid UTF-8. */
static int utf8_len(const unsigned char *s) {
  unsigned c = s[0];
  int n;
  unsigned min;
  if (c < 0x80) return 1;
  if (c >= 0xc2 && c <= 0xdf) n = 2, min = 0x80;
  else if (c >= 0xe0 && c <= 0xef) n = 3, min = 0x800;
  else if (c >= 0xf0 && c <= 0xf4) n = 4, min = 0x10000;
  else return 0;
  unsigned cp = c & (0x3fu >> (n - 1));
  for (int k = 1; k < n; k++) {
    if ((s[k] & 0xc0) != 0x80) return 0;
    cp = (cp << 6) | (s[k] & 0x3f);
  }
  if (cp < min || cp > 0x10ffff || (cp >= 0xd800 && cp <= 0xdfff)) return 0;
  return n;
}

void summary_json_string(char *out, size_t cap, const char *str) {
  const unsigned char *s = (const unsigned char *)(str ? str : "");
  size_t k = 0;
  if (cap < 3) {
    if (cap) out[0] = 0;
    return;
  }
  out[k++] = '"';
  while (*s) {
    char tmp[8];
    const char *r = tmp;
    size_t len;
    int adv = 1;
    switch (*s) {
    case '"': r = "\\\""; break;
    case '\\': r = "\\\\"; break;
    case '\n': r = "\\n"; break;
    case '\r': r = "\\r"; break;
    case '\t': r = "\\t"; break;
    case '\b': r = "\\b"; break;
    case '\f': r = "\\f"; break;
    default:
      if (*s < 0x20 || *s == 0x7f) {
        snprintf(tmp, sizeof tmp, "\\u%04x", *s);
      } else {
        int n = utf8_len(s);
        if (n == 0) {
          r = "\\ufffd";
        } else {
          memcpy(tmp, s, (size_t)n);
          tmp[n] = 0;
          adv = n;
        }
      }
    }
    len = strlen(r);
    if (k + len + 2 > cap) break; /* keep room for the closing quote and NUL */
    memcpy(out + k, r, len);
    k += len;
    s += adv;
  }
  out[k++] = '"';
  out[k] = 0;
}

/* Shortest %.Ng that reads back as the same double; "null" (and *bad set) when non-finite. */
static void fmt_num(char *buf, size_t cap, double v, int *bad) {
  if (!isfinite(v)) {
    snprintf(buf, cap, "null");
    *bad = 1;
    return;
  }
  for (int p = 15; p <= 17; p++) {
    snprintf(buf, cap, "%.*g", p, v);
    if (strtod(buf, NULL) == v) break;
  }
}

int summary_write(const YfSim *s, const char *path, int status_code, const char *reason) {
  if (!yf_writer()) return 0;
  if (!reason) reason = yf_last_message();
  const YfEnergy *en = &s->energy;
  double eps = s->wall_s > 0 ? s->elem_steps / s->wall_s : 0.0;
  struct { const char *key; double v; } nums[] = {
      {"time", s->time},
      {"energy.kinetic", en->kinetic},
      {"energy.strain", en->strain},
      {"energy.external_work", en->external_work},
      {"energy.damping", en->damping},
      {"energy.joint_dissipated", en->joint_dissipated},
      {"energy.contact", en->contact},
      {"energy.friction", en->friction},
      {"wall_s", s->wall_s},
      {"element_steps_per_s", eps}};
  enum { NNUM = sizeof nums / sizeof nums[0] };
  char num[NNUM][40];
  const char *first_bad = NULL;
  for (int i = 0; i < NNUM; i++) {
    int bad = 0;
    fmt_num(num[i], sizeof num[i], nums[i].v, &bad);
    if (bad && !first_bad) first_bad = nums[i].key;
  }
  char (*xnum)[40] = nextra ? yf_calloc((size_t)nextra, sizeof *xnum, "summary") : NULL;
  for (int i = 0; i < nextra; i++) {
    int bad = 0;
    if (!extras[i].json) fmt_num(xnum[i], sizeof xnum[i], extras[i].val, &bad);
    if (bad && !first_bad) first_bad = extras[i].key;
  }

  int code = status_code;
  char why[2200];
  if (first_bad && code == YF_EXIT_OK) {
    code = YF_EXIT_NUMERIC;
    snprintf(why, sizeof why, "non-finite value of summary key '%s'", first_bad);
    reason = why;
  }
  char rs[8192], ver[128], hash[24];
  summary_json_string(rs, sizeof rs, reason);
  summary_json_string(ver, sizeof ver, YF_VERSION);
  snprintf(hash, sizeof hash, "%016llx", (unsigned long long)sim_state_hash(s));

  YfWFile w;
  if (yf_wfile_open(&w, path) != 0) {
    int e = errno;
    free(xnum);
    errno = e;
    return -1;
  }
  FILE *f = w.f;
  fprintf(f, "{\n");
  fprintf(f, "  \"version\": %s,\n", ver);
  fprintf(f, "  \"status\": \"%s\",\n", yf_status_word(code));
  fprintf(f, "  \"reason\": %s,\n", rs);
  fprintf(f, "  \"steps\": %ld,\n", s->step);
  fprintf(f, "  \"time\": %s,\n", num[0]);
  fprintf(f, "  \"nodes\": %d,\n", s->model.node.n);
  fprintf(f, "  \"elements\": %d,\n", s->model.tri.n);
  fprintf(f, "  \"joints\": %ld,\n", cnt_joints);
  fprintf(f, "  \"joints_broken\": %ld,\n", cnt_broken);
  fprintf(f, "  \"contact_pairs\": %ld,\n", cnt_pairs);
  fprintf(f, "  \"energy\": {\"kinetic\": %s, \"strain\": %s, \"external_work\": %s, "
             "\"damping\": %s, \"joint_dissipated\": %s, \"contact\": %s, \"friction\": %s},\n",
          num[1], num[2], num[3], num[4], num[5], num[6], num[7]);
  fprintf(f, "  \"wall_s\": %s,\n", num[8]);
  fprintf(f, "  \"element_steps_per_s\": %s,\n", num[9]);
  fprintf(f, "  \"threads\": %d,\n", s->threads);
  fprintf(f, "  \"state_hash\": \"%s\"", hash);
  for (int i = 0; i < nextra; i++) {
    char key[512];
    summary_json_string(key, sizeof key, extras[i].key);
    fprintf(f, ",\n  %s: %s", key, extras[i].json ? extras[i].json : xnum[i]);
  }
  fprintf(f, "\n}\n");
  free(xnum);
  if (yf_wfile_close(&w, 0, 1) != 0) return -1;
  return code;
}
