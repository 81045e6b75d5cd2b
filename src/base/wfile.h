/* wfile.h: a file written whole at once (the summary, the fracture log, the metrics log).
 *
 * A regular file (or a new one) is written as PATH.tmp and renamed over PATH when complete, so a
 * reader never sees half of it and a failed write leaves the old file.  Anything else that exists
 * under PATH (a symbolic link such as /dev/stdout, a terminal, a device, a FIFO) is written
 * directly, through the link: a rename would replace the link or the special file itself (as root, /dev/stdout or /dev/full became a regular file
 * and the output went nowhere, 2026-11-28). */
#ifndef YF_WFILE_H
#define YF_WFILE_H
#include <stdio.h>

typedef struct {
  FILE *f;
  char *tmp; /* PATH.tmp, or NULL when PATH is written directly */
  const char *path;
} YfWFile;

/* Open for writing; 0, or -1 with errno set (nothing to close). */
int yf_wfile_open(YfWFile *w, const char *path);
/* Flush (and fsync when sync), close and rename; bad: the caller saw a write fail.  0, or -1
 * with errno set (the .tmp removed). */
int yf_wfile_close(YfWFile *w, int bad, int sync);
#endif
