/* err.c: the single exit path for failures (see err.h).
 *
 * Messages go to stderr (and to the log through the cleanup hook, which main installs).  The last
 * message is kept for the summary JSON.  The cleanup hook runs at most once, so a failure inside
 * cleanup cannot loop.
 */
#include <ctype.h>
#include <pthread.h>
#include <errno.h>
#include <limits.h>
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <unistd.h>
#include <sys/stat.h>
#include <string.h>
#include <strings.h>
#include "err.h"

static char last_msg[2048];
static YfCleanupFn cleanup_fn;
static int in_cleanup;
static int cleanup_code;  /* the code the cleanup runs for                            */
static int pending_io;    /* an output failed during the cleanup: the exit code is 2   */
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

static void (*sig_handler)(int);

static void install(int restart) {
  if (!sig_handler) return;
  struct sigaction sa;
  memset(&sa, 0, sizeof sa);
  sa.sa_handler = sig_handler;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = restart ? SA_RESTART : 0;
  sigaction(SIGINT, &sa, NULL);
  sigaction(SIGTERM, &sa, NULL);
}
void yf_catch_signals(void (*handler)(int sig)) {
  sig_handler = handler;
  install(1);
  /* a closed pipe on stdout ('yfdem deck | head') is a write error sim_printf reports (exit 2,
   * with the summary), not a signal that kills the run before it can write anything */
  signal(SIGPIPE, SIG_IGN);
}
void yf_interruptible(int on) { install(!on); }

/* METIS (GKlib's gk_sigtrap/gk_siguntrap, built with strict C: signal() is SysV's there) traps
 * SIGTERM and SIGABRT during a call and puts the old handlers back one-shot (SA_RESETHAND), with
 * no SA_RESTART and without SA_SIGINFO: after a partition the next SIGTERM (mpirun's on Ctrl-C)
 * broke a blocked write to stdout (EINTR: exit 2 where an interrupt ends with a restart, exit
 * 130), a second one killed the run, and OpenMPI's SIGABRT handler got no siginfo.  The guard
 * blocks SIGINT and SIGTERM in this thread, keeps the handlers and restores them exactly
 * afterwards; a signal that came in meanwhile is then delivered to our handler. */
static struct sigaction guard_old[3];
static sigset_t guard_mask;
static const int guard_sig[3] = {SIGINT, SIGTERM, SIGABRT};
void yf_signals_guard(int on) {
  if (on) {
    sigset_t block;
    sigemptyset(&block);
    sigaddset(&block, SIGINT);
    sigaddset(&block, SIGTERM);
    pthread_sigmask(SIG_BLOCK, &block, &guard_mask);
    for (int k = 0; k < 3; k++) sigaction(guard_sig[k], NULL, &guard_old[k]);
  } else {
    for (int k = 0; k < 3; k++) sigaction(guard_sig[k], &guard_old[k], NULL);
    pthread_sigmask(SIG_SETMASK, &guard_mask, NULL);
  }
}

void yf_set_cleanup(YfCleanupFn fn) { cleanup_fn = fn; }
void yf_set_exit_hook(void (*hook)(int code)) { exit_hook = hook; }
const char *yf_last_message(void) { return last_msg; }
int yf_writer(void) { return writer; }
void yf_set_writer(int on) { writer = on; }

/* Run the cleanup once (output files closed, logs and the summary written); an output that fails
 * there (yf_output_error) turns a successful exit into YF_EXIT_IO.  Returns the exit code. */
static volatile sig_atomic_t exiting; /* the exit path has begun (read by signal handlers) */
int yf_exiting(void) { return exiting; }

static int cleanup(int code) {
  exiting = 1;
  if (cleanup_fn && !in_cleanup) {
    in_cleanup = 1;
    cleanup_code = code;
    cleanup_fn(code, last_msg);
  }
  in_cleanup = 0;
  return yf_exit_code(code);
}

int yf_exit_code(int code) { return code == YF_EXIT_OK && pending_io ? YF_EXIT_IO : code; }

int yf_finish(int code) {
  if (code != YF_EXIT_OK) {
    fprintf(stderr, "%s\n", last_msg);
    fflush(stderr);
  }
  return cleanup(code);
}

static void finish(int code) __attribute__((noreturn));
static void finish(int code) {
  if (writer) {
    fprintf(stderr, "%s\n", last_msg);
    fflush(stderr);
  }
  code = cleanup(code);
  if (exit_hook) exit_hook(code); /* the fuzz harness longjmps out instead of exiting */
  exit(code);
}

/* The net under "never print inf or nan": in a composed message's first line (later lines echo
 * the deck line under a caret, which must stay as typed), a word inf or nan that printf made of a
 * non-finite number, outside quotes (a name or a word quoted from the deck stays), is spelled
 * out.  Each site should say better what a non-finite value means; this catches the ones
 * that do not (D1PEKS 1e300 printed "stable limit inf s"). */
static void spell_nonfinite(char *msg, size_t cap) {
  /* printf's words only: inf and nan in lower case, a word of their own (not 'inf/run.deck',
   * 'nan-test', 'Infinity' or 'NaN', which are names) */
  static const struct { const char *word, *say; } w[] = {
      {"inf", "beyond the range of a double"}, {"nan", "not a number"}, {NULL, NULL}};
  int quoted = 0;
  for (size_t i = 0; msg[i] && msg[i] != '\n'; i++) {
    if (msg[i] == '\'' || msg[i] == '"') { quoted = !quoted; continue; }
    if (quoted || (i > 0 && !strchr(" (=[", msg[i - 1]) && !(msg[i - 1] == '-' && (i < 2 || msg[i - 2] == ' '))))
      continue;
    if (i >= 2 && msg[i - 1] == ' ' && (msg[i - 2] == ',' || msg[i - 2] == ':')) continue; /* a list of names */
    for (int k = 0; w[k].word; k++) {
      size_t L = strlen(w[k].word);
      if (strncmp(msg + i, w[k].word, L)) continue; /* (stops at the end: msg[i + L] is then inside) */
      char next = msg[i + L];
      if (!(next == 0 || next == '\n' || strchr(" ),];x", next))) continue;
      size_t S = strlen(w[k].say), rest = strlen(msg + i + L);
      if (i + S + rest + 1 > cap) return; /* no room: leave the rest as it is */
      memmove(msg + i + S, msg + i + L, rest + 1);
      memcpy(msg + i, w[k].say, S);
      i += S - 1;
      break;
    }
  }
}

void yf_output_error(const char *fmt, ...) {
  char msg[2048];
  int k = snprintf(msg, sizeof msg, "error: ");
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(msg + k, sizeof msg - (size_t)k, fmt, ap);
  va_end(ap);
  spell_nonfinite(msg, sizeof msg);
  if (!in_cleanup) {
    snprintf(last_msg, sizeof last_msg, "%s", msg);
    finish(YF_EXIT_IO);
  }
  /* on the way out: say it, keep going (the other files and the summary), exit 2 at the end;
   * after another error that error keeps its message and its code */
  fprintf(stderr, "%s\n", msg);
  fflush(stderr);
  if (cleanup_code == YF_EXIT_OK && !pending_io) snprintf(last_msg, sizeof last_msg, "%s", msg);
  pending_io = 1;
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
  spell_nonfinite(last_msg, sizeof last_msg);
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
  spell_nonfinite(last_msg, sizeof last_msg);
  finish(YF_EXIT_NUMERIC);
}

void yf_exit_with(int code, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(last_msg, sizeof last_msg, fmt, ap);
  va_end(ap);
  spell_nonfinite(last_msg, sizeof last_msg);
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
  spell_nonfinite(buf, sizeof buf);
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

/* Input read from something other than a file (a pipe, a device) stops here: /dev/zero grew
 * until the kernel killed the process (a sweep of bad input, 2026-11-28). */
#define YF_READ_STREAM_MAX ((size_t)256 << 20)

FILE *yf_open_input(const char *path, const char *mode) {
  FILE *f = fopen(path, mode);
  if (!f) return NULL;
  struct stat st;
  if (fstat(fileno(f), &st) != 0 || S_ISREG(st.st_mode)) return f;
  if (S_ISDIR(st.st_mode)) { /* fopen opens a directory, and reading it fails without a word */
    fclose(f);
    errno = EISDIR;
    return NULL;
  }
  /* a pipe or a device: its bytes, up to the limit, into an unnamed file the caller reads */
  FILE *t = tmpfile();
  char buf[65536];
  size_t n = 0, r;
  while (t && (r = fread(buf, 1, sizeof buf, f)) > 0 && (n += r) <= YF_READ_STREAM_MAX)
    if (fwrite(buf, 1, r, t) != r) break;
  int err = !t ? errno : n > YF_READ_STREAM_MAX ? EFBIG : ferror(f) || ferror(t) ? (errno ? errno : EIO) : 0;
  fclose(f);
  if (err) {
    if (t) fclose(t);
    errno = err;
    return NULL;
  }
  rewind(t);
  return t;
}

char *yf_read_file(const char *path, size_t *len, const char *what) {
  FILE *f = yf_open_input(path, "rb");
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
  if (n >= 3 && !memcmp(t, "\xef\xbb\xbf", 3)) { /* a UTF-8 byte-order mark (the rest may hold NULs) */
    memmove(t, t + 3, n - 2);
    n -= 3;
  }
  *len = n;
  return t;
}

size_t yf_rows_before(const char *text, long step) {
  const char *end = text;
  for (const char *p = text, *nl; (nl = strchr(p, '\n')); p = nl + 1) {
    char *e;
    long k = strtol(p, &e, 10);
    if (e == p || *e != ',' || k >= step) break;
    end = nl + 1;
  }
  return (size_t)(end - text);
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

size_t yf_skip_bom(char *s) {
  if ((unsigned char)s[0] != 0xef || (unsigned char)s[1] != 0xbb || (unsigned char)s[2] != 0xbf) return 0;
  memmove(s, s + 3, strlen(s + 3) + 1);
  return 3;
}

/* The one file being written as NAME.tmp (yf_tmp_live), for a second Ctrl-C to remove. */
static char tmp_path[4096];
static volatile sig_atomic_t tmp_set;

int yf_can_create(const char *path) {
  /* MPI: only the writer (rank 0) writes files, so only it checks (the probe's PATH.tmp is the
   * name the real write uses: other ranks must not create or remove it) */
  if (!writer) return 1;
  /* a link, a device, a pipe is written through as it is (wfile.h): probe it, never PATH.tmp
   * beside it (/dev/stdout.tmp) */
  struct stat st;
  if (lstat(path, &st) == 0 && !S_ISREG(st.st_mode)) {
    if (S_ISDIR(st.st_mode) || (stat(path, &st) == 0 && S_ISDIR(st.st_mode))) {
      errno = EISDIR;
      return 0;
    }
    if (stat(path, &st) == 0) return access(path, W_OK) == 0;
  }
  size_t n = strlen(path) + 5;
  char *tmp = yf_malloc(n, "path");
  snprintf(tmp, n, "%s.tmp", path);
  /* a second Ctrl-C during the probe removes it too (unless a file being written holds the one
   * slot: the probe is then not in a file's write) */
  int mine = !tmp_set;
  if (mine) yf_tmp_live(tmp);
  FILE *f = fopen(tmp, "w");
  int ok = f != NULL, err = errno;
  if (f) {
    fclose(f);
    remove(tmp);
  }
  if (mine) yf_tmp_live(NULL);
  free(tmp);
  errno = err;
  return ok;
}

const char *yf_fmt_g(char *buf, size_t n, double v) {
  if (isnan(v)) snprintf(buf, n, "not a number");
  else if (isinf(v)) snprintf(buf, n, "%sbeyond the range of a double", v < 0 ? "-" : "");
  else snprintf(buf, n, "%.6g", v);
  return buf;
}

long yf_getline(char **line, size_t *cap, FILE *fp) {
  size_t n = 0;
  int c;
  while ((c = getc(fp)) != EOF) {
    if (n + 2 >= *cap) {
      size_t nc = *cap ? 2 * *cap : 256;
      *line = yf_realloc(*line, nc, "input line");
      *cap = nc;
    }
    (*line)[n++] = (char)c;
    if (c == '\n') break;
    if (c == '\r') { /* CRs before a LF are one end with it (CRLF, CR CR LF) */
      int d;
      while ((d = getc(fp)) == '\r') {}
      if (d == '\n') (*line)[n++] = '\n';
      else if (d != EOF) ungetc(d, fp);
      break;
    }
  }
  if (!n) return -1;
  (*line)[n] = 0;
  return (long)n;
}


void yf_tmp_live(const char *path) {
  tmp_set = 0;
  if (!path || strlen(path) >= sizeof tmp_path) return;
  memcpy(tmp_path, path, strlen(path) + 1);
  tmp_set = 1;
}

void yf_tmp_drop(void) {
  if (tmp_set) unlink(tmp_path);
  tmp_set = 0;
}
