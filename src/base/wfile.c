/* wfile.c: files written whole at once, renamed into place unless special (see wfile.h). */
#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>
#include "err.h"
#include "wfile.h"

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
    w->f = fopen(path, "w");
    return w->f ? 0 : -1;
  }
  size_t n = strlen(path);
  w->tmp = yf_malloc(n + 5, "path");
  memcpy(w->tmp, path, n);
  memcpy(w->tmp + n, ".tmp", 5);
  w->f = fopen(w->tmp, "w");
  if (w->f) yf_tmp_live(w->tmp);
  if (!w->f) {
    int e = errno;
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
