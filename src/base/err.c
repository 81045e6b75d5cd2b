/* err.c: the single exit path for failures (see err.h).
 *
 * Messages go to stderr (and to the log through the cleanup hook, which main installs).  The last
 * message is kept for the summary JSON.  The cleanup hook runs at most once, so a failure inside
 * cleanup cannot loop.
 */
#include <errno.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "err.h"

static char last_msg[2048];
static YfCleanupFn cleanup_fn;
static int in_cleanup;
static void (*exit_hook)(int code);
static int writer = 1;
static FILE *log_fp; /* the run's log (main: log.yfdem or -log FILE): warnings are copied to it */

void yf_set_log(FILE *fp) { log_fp = fp; }

const char *yf_status_word(int code) {
  switch (code) {
  case YF_EXIT_OK: return "ok";
  case YF_EXIT_DECK: return "deck_error";
  case YF_EXIT_IO: return "io_error";
  case YF_EXIT_NUMERIC: return "numerical_failure";
  case YF_EXIT_INTERRUPT: return "interrupted";
  default: return "internal_error";
  }
}

void yf_set_cleanup(YfCleanupFn fn) { cleanup_fn = fn; }
void yf_set_exit_hook(void (*hook)(int code)) { exit_hook = hook; }
const char *yf_last_message(void) { return last_msg; }
int yf_writer(void) { return writer; }
void yf_set_writer(int on) { writer = on; }

static void finish(int code) __attribute__((noreturn));
static void finish(int code) {
  if (writer) {
    fprintf(stderr, "%s\n", last_msg);
    fflush(stderr);
  }
  if (cleanup_fn && !in_cleanup) {
    in_cleanup = 1;
    cleanup_fn(code, last_msg);
  }
  in_cleanup = 0;
  if (exit_hook) exit_hook(code); /* the fuzz harness longjmps out instead of exiting */
  exit(code);
}

/* Compose "FILE:LINE: error: " + message into last_msg. */
static void compose(const YfLoc *loc, const char *kind, const char *fmt, va_list ap) {
  int k = 0;
  if (loc && loc->file)
    k = snprintf(last_msg, sizeof last_msg, "%s:%d: %s: ", loc->file, loc->line, kind);
  else
    k = snprintf(last_msg, sizeof last_msg, "%s: ", kind);
  if (k < 0) k = 0;
  if ((size_t)k < sizeof last_msg) vsnprintf(last_msg + k, sizeof last_msg - (size_t)k, fmt, ap);
}

void yf_deck_error(const YfLoc *loc, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  compose(loc, "error", fmt, ap);
  va_end(ap);
  finish(YF_EXIT_DECK);
}

void yf_io_error(const YfLoc *loc, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  compose(loc, "error", fmt, ap);
  va_end(ap);
  finish(YF_EXIT_IO);
}

void yf_numeric_error(long step, const char *fmt, ...) {
  int k = snprintf(last_msg, sizeof last_msg, "error: numerical failure at step %ld: ", step);
  va_list ap;
  va_start(ap, fmt);
  if (k > 0 && (size_t)k < sizeof last_msg) vsnprintf(last_msg + k, sizeof last_msg - (size_t)k, fmt, ap);
  va_end(ap);
  finish(YF_EXIT_NUMERIC);
}

void yf_exit_with(int code, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(last_msg, sizeof last_msg, fmt, ap);
  va_end(ap);
  finish(code);
}

void yf_warn(const YfLoc *loc, const char *fmt, ...) {
  char buf[2048];
  int k = 0;
  if (loc && loc->file) k = snprintf(buf, sizeof buf, "%s:%d: warning: ", loc->file, loc->line);
  else k = snprintf(buf, sizeof buf, "warning: ");
  va_list ap;
  va_start(ap, fmt);
  if (k > 0 && (size_t)k < sizeof buf) vsnprintf(buf + k, sizeof buf - (size_t)k, fmt, ap);
  va_end(ap);
  if (writer) {
    fprintf(stderr, "%s\n", buf);
    fflush(stderr);
  }
  if (log_fp) {
    fprintf(log_fp, "%s\n", buf);
    fflush(log_fp);
  }
}

void yf_assert_fail(const char *expr, const char *file, int line) {
  snprintf(last_msg, sizeof last_msg, "internal error: assertion '%s' failed at %s:%d (a bug in yfdem)",
           expr, file, line);
  finish(YF_EXIT_INTERNAL);
}

static void oom(size_t n, const char *what) __attribute__((noreturn));
static void oom(size_t n, const char *what) {
  snprintf(last_msg, sizeof last_msg, "error: out of memory allocating %zu bytes for %s", n, what);
  finish(YF_EXIT_IO);
}

void *yf_malloc(size_t n, const char *what) {
  void *p = malloc(n ? n : 1);
  if (!p) oom(n, what);
  return p;
}
void *yf_calloc(size_t n, size_t size, const char *what) {
  void *p = calloc(n ? n : 1, size ? size : 1);
  if (!p) oom(n * size, what);
  return p;
}
void *yf_realloc(void *p, size_t n, const char *what) {
  void *q = realloc(p, n ? n : 1);
  if (!q) oom(n, what);
  return q;
}
char *yf_strdup(const char *s) {
  size_t n = strlen(s) + 1;
  char *p = yf_malloc(n, "string");
  memcpy(p, s, n);
  return p;
}

char *yf_read_file(const char *path, size_t *len, const char *what) {
  FILE *f = fopen(path, "rb");
  if (!f) return NULL;
  size_t cap = 1 << 16, n = 0;
  char *t = yf_malloc(cap, what);
  for (size_t r; (r = fread(t + n, 1, cap - n - 1, f)) > 0;) {
    n += r;
    if (n + 1 == cap) t = yf_realloc(t, cap *= 2, what);
  }
  int bad = ferror(f), err = errno;
  fclose(f);
  if (bad) {
    free(t);
    errno = err ? err : EIO;
    return NULL;
  }
  t[n] = 0;
  *len = n;
  return t;
}

/* Edit distance, for "did you mean" in messages (the deck and the .y reader). */

static int levenshtein(const char *a, const char *b) {
  int la = (int)strlen(a), lb = (int)strlen(b);
  if (la > 255 || lb > 255) return INT_MAX;
  int row[256];
  for (int j = 0; j <= lb; j++) row[j] = j;
  for (int i = 1; i <= la; i++) {
    int diag = row[0];
    row[0] = i;
    for (int j = 1; j <= lb; j++) {
      int up = row[j];
      int best = diag + (a[i - 1] != b[j - 1]);
      if (up + 1 < best) best = up + 1;
      if (row[j - 1] + 1 < best) best = row[j - 1] + 1;
      row[j] = best;
      diag = up;
    }
  }
  return row[lb];
}

const char *yf_nearest(const char *word, const char *const *names, int n) {
  int len = (int)strlen(word);
  int limit = len / 3 > 2 ? len / 3 : 2;
  const char *best = NULL;
  int bestd = INT_MAX;
  for (int i = 0; i < n; i++) {
    if (!names[i]) continue;
    int d = levenshtein(word, names[i]);
    if (d < bestd) bestd = d, best = names[i];
  }
  return bestd <= limit ? best : NULL;
}
