/* wfile.h: a file written whole at once (the summary, the fracture log, the metrics log), and a
 * file that grows by whole rows (YfRows: the record files, the y2dref dump's summary, probes and
 * broken tables).
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

/* fopen(path, "w") that never waits: a FIFO with no reader fails at once with ENXIO. */
FILE *yf_fopen_w(const char *path);
/* s as one CSV field (allocated): as it is, or in double quotes (its quotes doubled, RFC 4180)
 * when it holds a comma, a quote or a line break ('max(ke,strain)' was two header columns over
 * one value, a file 'a,b_000000.csv' two fields of the csv dump's index). */
char *yf_csv_field(const char *s);
/* The text of an output written earlier, for a continued run to take up (yf_read_file), or NULL
 * when PATH is not a regular file: a FIFO, a terminal or /dev/stdout (a pipe) has nothing to take
 * up, and reading it waited for ever for a writer (a continued run's record on /dev/stdout piped
 * to tee hung at the run's start). */
char *yf_read_output(const char *path, size_t *len, const char *what);
/* strerror, with ENXIO (from the opens here: a FIFO that no process reads) said as such. */
const char *yf_strerror(int e);

/* Open for writing; 0, or -1 with errno set (nothing to close). */
int yf_wfile_open(YfWFile *w, const char *path);
/* Flush (and fsync when sync), close and rename; bad: the caller saw a write fail.  0, or -1
 * with errno set (the .tmp removed). */
int yf_wfile_close(YfWFile *w, int bad, int sync);

/* A CSV file that grows by whole rows.  A row is gathered in memory (yf_rows_printf) and handed to
 * the file in one go (yf_rows_end); a row that does not go in whole (a full disk) is cut off again
 * (ftruncate to the length before it), so the file always ends at its last complete row.  stdio's
 * buffer is not used: after a failed fflush it keeps the unwritten tail and writes it again at
 * fclose, after the cut.  On a pipe or a terminal nothing can be cut (as stdio). */
typedef struct {
  int fd;        /* -1: not open                                                   */
  long long end; /* the file's length after its last complete row (-1: not a file) */
  char *row;     /* the row being gathered                                         */
  size_t len, cap;
} YfRows;

/* Open PATH for rows: append (its rows kept) or truncate.  0, or -1 with errno set.  r starts
 * zeroed or closed; a row gathered before the open (a header) is kept for the first yf_rows_end. */
int yf_rows_open(YfRows *r, const char *path, int append);
/* Add text to the row being gathered (a row may be several calls, a line or several lines). */
void yf_rows_printf(YfRows *r, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
/* Write the gathered row whole: 0, or -1 with errno set and the file cut back to its last
 * complete row.  The row is emptied either way. */
int yf_rows_end(YfRows *r);
/* Close (a gathered row not ended is dropped); 0, or -1 with errno set. */
int yf_rows_close(YfRows *r);
#endif
