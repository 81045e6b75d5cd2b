/* wfile.c: files written whole at once, renamed into place unless special, and files that grow by
 * whole rows (see wfile.h). */
#include <errno.h>
#include <fcntl.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>
#include "err.h"
#include "wfile.h"

/* open for writing without waiting: a FIFO that no process reads makes a plain open wait for
 * a reader for ever, deaf to Ctrl-C (a record or log named on a FIFO hung the run at its first
 * row, 2026-11-29); O_NONBLOCK fails it at once with ENXIO instead (yf_strerror says why), and
 * is cleared after the open so that writes wait for a slow reader as they would on a pipe.  On
 * a regular file, a terminal or /dev/null it changes nothing. */
static int open_w(const char *path, int flags) {
  /* the file yfdem's own standard output or error goes to (/dev/stdout, 2>&1, a shell's
   * '> out.txt'): written through a copy of that descriptor, sharing its offset.  Opened anew it
   * was truncated under the stream's position (the lines printed before became a run of NUL bytes
   * and grep took out.txt for binary), or, opened to append, its rows were written over by the
   * lines printed after them. */
  struct stat st, so;
  if (stat(path, &st) == 0)
    for (int k = 1; k <= 2; k++)
      if (fstat(k, &so) == 0 && so.st_dev == st.st_dev && so.st_ino == st.st_ino) {
        fflush(k == 1 ? stdout : stderr);
        return fcntl(k, F_DUPFD_CLOEXEC, 3);
      }
  int fd = open(path, O_WRONLY | O_CLOEXEC | O_NONBLOCK | flags, 0666);
  if (fd < 0) return -1;
  int fl = fcntl(fd, F_GETFL);
  if (fl != -1) fcntl(fd, F_SETFL, fl & ~O_NONBLOCK);
  return fd;
}

FILE *yf_fopen_w(const char *path) {
  int fd = open_w(path, O_CREAT | O_TRUNC);
  if (fd < 0) return NULL;
  FILE *f = fdopen(fd, "w");
  if (!f) {
    int e = errno;
    close(fd);
    errno = e;
  }
  return f;
}

char *yf_csv_field(const char *s) {
  size_t n = strlen(s), q = 0;
  int quote = strpbrk(s, ",\"\r\n") != NULL;
  for (const char *c = s; *c; c++) q += *c == '"';
  char *out = yf_malloc(n + q + 3, "CSV field"), *o = out;
  if (quote) *o++ = '"';
  for (const char *c = s; *c; c++) {
    if (*c == '"') *o++ = '"';
    *o++ = *c;
  }
  if (quote) *o++ = '"';
  *o = 0;
  return out;
}

char *yf_read_output(const char *path, size_t *len, const char *what) {
  struct stat st;
  if (stat(path, &st) != 0 || !S_ISREG(st.st_mode)) return NULL;
  return yf_read_file(path, len, what);
}

const char *yf_strerror(int e) {
  return e == ENXIO ? "no process reads this FIFO (start its reader first, or name a file)" : strerror(e);
}

int yf_wfile_open(YfWFile *w, const char *path) {
  struct stat st;
  w->path = path;
  w->tmp = NULL;
  /* lstat: a symbolic link is written through (/dev/stdout -> /proc/self/fd/1 -> the file the
   * shell redirected to: renaming over the link replaced it and the shell's file stayed empty) */
  if (lstat(path, &st) == 0 && !S_ISREG(st.st_mode)) {
    if (S_ISDIR(st.st_mode) || (stat(path, &st) == 0 && S_ISDIR(st.st_mode))) {
      errno = EISDIR;
      return -1;
    }
    w->f = yf_fopen_w(path);
    return w->f ? 0 : -1;
  }
  size_t n = strlen(path);
  w->tmp = yf_malloc(n + 5, "path");
  memcpy(w->tmp, path, n);
  memcpy(w->tmp + n, ".tmp", 5);
  /* live before it exists: a second Ctrl-C between fopen's creating it and a later registration
   * left it behind (habits:test_second_interrupt_leaves_no_tmp, under load) */
  yf_tmp_live(w->tmp);
  w->f = fopen(w->tmp, "w");
  if (!w->f) {
    int e = errno;
    yf_tmp_live(NULL);
    free(w->tmp);
    w->tmp = NULL;
    errno = e;
    return -1;
  }
  return 0;
}

int yf_wfile_close(YfWFile *w, int bad, int sync) {
  int e = bad ? (errno ? errno : EIO) : 0;
  if (!bad && (ferror(w->f) || fflush(w->f) != 0)) bad = 1, e = errno ? errno : EIO;
  /* fsync of a terminal or a pipe fails with EINVAL: only files are synced */
  if (!bad && sync && w->tmp && fsync(fileno(w->f)) != 0) bad = 1, e = errno;
  if (fclose(w->f) != 0 && !bad) bad = 1, e = errno;
  w->f = NULL;
  if (!bad && w->tmp && rename(w->tmp, w->path) != 0) bad = 1, e = errno;
  if (bad && w->tmp) remove(w->tmp);
  if (w->tmp) yf_tmp_live(NULL);
  free(w->tmp);
  w->tmp = NULL;
  if (bad) errno = e;
  return bad ? -1 : 0;
}

int yf_rows_open(YfRows *r, const char *path, int append) {
  r->end = -1;
  r->fd = open_w(path, O_CREAT | (append ? O_APPEND : O_TRUNC));
  if (r->fd < 0) return -1;
  struct stat st;
  /* only a regular file can be cut back; its rows start where it ends now.  Not the file of
   * standard output (open_w): the lines printed between the rows would be cut with a row. */
  struct stat so;
  int shared = 0;
  for (int k = 1; k <= 2; k++)
    shared |= fstat(k, &so) == 0 && fstat(r->fd, &st) == 0 && so.st_dev == st.st_dev && so.st_ino == st.st_ino;
  if (!shared && fstat(r->fd, &st) == 0 && S_ISREG(st.st_mode)) r->end = (long long)st.st_size;
  return 0;
}

void yf_rows_printf(YfRows *r, const char *fmt, ...) {
  for (;;) {
    va_list ap;
    va_start(ap, fmt);
    int n = vsnprintf(r->row ? r->row + r->len : NULL, r->row ? r->cap - r->len : 0, fmt, ap);
    va_end(ap);
    if (n < 0) return;
    if (r->row && r->len + (size_t)n < r->cap) {
      r->len += (size_t)n;
      return;
    }
    size_t cap = r->cap ? r->cap : 256;
    while (cap <= r->len + (size_t)n) cap *= 2;
    r->row = yf_realloc(r->row, cap, "output row");
    r->cap = cap;
  }
}

int yf_rows_end(YfRows *r) {
  size_t done = 0;
  int e = 0;
  while (done < r->len) {
    ssize_t k = write(r->fd, r->row + done, r->len - done);
    if (k < 0 && errno == EINTR) continue;
    if (k <= 0) {
      e = k < 0 ? errno : EIO;
      break;
    }
    done += (size_t)k;
  }
  if (!e && r->end >= 0) r->end += (long long)r->len;
  r->len = 0;
  if (!e) return 0;
  /* the part that went in is taken out again: the file ends at its last complete row */
  if (done && r->end >= 0 && ftruncate(r->fd, (off_t)r->end) == 0) lseek(r->fd, (off_t)r->end, SEEK_SET);
  errno = e;
  return -1;
}

int yf_rows_close(YfRows *r) {
  int rc = 0;
  if (r->fd >= 0 && close(r->fd) != 0) rc = -1;
  r->fd = -1;
  int e = errno;
  free(r->row);
  r->row = NULL;
  r->len = r->cap = 0;
  errno = e;
  return rc;
}
