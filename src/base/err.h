/* err.h: how yfdem fails.
 *
 * Every failure ends the run through one of the functions below, which print one clear message,
 * record the status for the -summary JSON, run the registered cleanup (close output files, remove
 * half-written ones, write the summary) and exit with a code that tells the kinds apart.
 * Handlers validate user input themselves and call yf_deck_error(); YF_ASSERT is for programmer
 * errors only, never for user input.
 */
#ifndef YF_ERR_H
#define YF_ERR_H
#include <stdarg.h>
#include <stdio.h>
#include <stddef.h>

enum {
  YF_EXIT_OK = 0,
  YF_EXIT_DECK = 1,      /* bad deck: unknown command, bad argument, missing group...     */
  YF_EXIT_IO = 2,        /* cannot read a mesh/include file, cannot write output          */
  YF_EXIT_NUMERIC = 3,   /* NaN, inverted element, unstable time step, energy blow-up     */
  YF_EXIT_INTERRUPT = 130, /* SIGINT / SIGTERM (128 + SIGINT, what shells report for Ctrl-C) */
  YF_EXIT_INTERNAL = 70  /* failed internal assertion (a bug in yfdem)                     */
};

/* Status words used in the summary JSON ("status" key) of the codes above. */
const char *yf_status_word(int code);

/* A place in a deck: file name and 1-based line. file may be "<stdin>". */
typedef struct {
  const char *file;
  int line;
} YfLoc;

/* Cleanup hook run once before exit on any error (set by main). */
typedef void (*YfCleanupFn)(int code, const char *message);
/* The log file that warnings are copied to (NULL: none). */
void yf_set_log(FILE *fp);
void yf_set_cleanup(YfCleanupFn fn);
/* Called instead of exit(code) after the cleanup when set (tools/fuzz: the harness longjmps back
 * to the next input); it must not return.  NULL: exit. */
void yf_set_exit_hook(void (*hook)(int code));
/* Whether this process prints messages and writes output files: 1 always in ./yfdem; under MPI
 * (src/par) only rank 0 is the writer, the other ranks run the same deck silently. */
int yf_writer(void);
void yf_set_writer(int on);

/* "FILE:LINE: error: message" then exit(YF_EXIT_DECK). loc may be NULL (message has no place). */
void yf_deck_error(const YfLoc *loc, const char *fmt, ...) __attribute__((noreturn, format(printf, 2, 3)));
/* I/O failure (file cannot be opened, read, or written). loc may be NULL. */
void yf_io_error(const YfLoc *loc, const char *fmt, ...) __attribute__((noreturn, format(printf, 2, 3)));
/* Numerical failure during a run: "error: numerical failure at step N: ..." */
void yf_numeric_error(long step, const char *fmt, ...) __attribute__((noreturn, format(printf, 2, 3)));
/* Generic exit with a given code and message (used for interrupts). */
void yf_exit_with(int code, const char *fmt, ...) __attribute__((noreturn, format(printf, 2, 3)));
/* An output that cannot be written: like yf_io_error, except on the way out (inside the cleanup,
 * when the files are closed and the logs and the summary written), where it prints the error,
 * returns so that the other outputs are still written, and the run then exits with
 * YF_EXIT_IO (a successful run: with this message as the summary's reason). */
void yf_output_error(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
/* code, or YF_EXIT_IO when it is YF_EXIT_OK and an output failed on the way out. */
int yf_exit_code(int code);
/* The end of a run that did not fail: the cleanup (once), then the exit code to return. */
int yf_finish(int code);
/* Warning on stderr (and the log), run continues. */
void yf_warn(const YfLoc *loc, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

/* SIGINT and SIGTERM: handler (main's) installed with SA_RESTART, so that a signal never turns a
 * write into a short write (an I/O error).  yf_interruptible(1) reinstalls it without SA_RESTART
 * around a read that may block forever (a deck on a terminal or a pipe), so that the signal ends
 * the read (EINTR) and the reader can stop; yf_interruptible(0) puts SA_RESTART back. */
void yf_catch_signals(void (*handler)(int sig));
void yf_interruptible(int on);
/* Around a library call that installs its own signal handlers (METIS): on = 1 blocks SIGINT and
 * SIGTERM in this thread and keeps the SIGINT, SIGTERM and SIGABRT handlers; on = 0 restores them
 * exactly and unblocks (a signal sent meanwhile then reaches the handler). */
void yf_signals_guard(int on);
/* 1 once the exit path (files closed, summary written) has begun: a signal then changes nothing. */
int yf_exiting(void);

/* v as "%.6g", or "inf", "-inf", "nan" spelled out as what they mean ("beyond the range of a
 * double", "not a number"): messages never print inf or nan. */
const char *yf_fmt_g(char *buf, size_t n, double v);
/* The temporary file being written now (PATH.tmp, renamed over PATH when whole), NULL when none:
 * a second Ctrl-C, which stops at once, removes it (yf_tmp_drop, async-signal-safe) instead of
 * leaving a half-written .tmp beside the outputs.  Writes are one at a time: one slot. */
void yf_tmp_live(const char *path);
void yf_tmp_drop(void);

/* Last error message (for the summary's "reason"); "" when none. */
const char *yf_last_message(void);

void yf_assert_fail(const char *expr, const char *file, int line) __attribute__((noreturn));
#define YF_ASSERT(c) ((c) ? (void)0 : yf_assert_fail(#c, __FILE__, __LINE__))

/* Checked allocation: on failure a clear I/O-class error naming what was being allocated. */
void *yf_malloc(size_t n, const char *what);
void *yf_calloc(size_t n, size_t size, const char *what);
void *yf_realloc(void *p, size_t n, const char *what);
char *yf_strdup(const char *s);
/* The whole of file path, NUL-terminated, its length (without the NUL) in *len; NULL with errno
 * set if it cannot be opened or read.  what names it for an allocation failure.  A UTF-8
 * byte-order mark at its start is left out. */
char *yf_read_file(const char *path, size_t *len, const char *what);
/* fopen of an input file for reading: a directory is refused (EISDIR); a pipe or a device is read
 * up to 256 MiB into an unnamed file returned in its place (beyond: EFBIG); NULL with errno. */
FILE *yf_open_input(const char *path, const char *mode);
/* getline that also ends a line at a CR alone (classic Mac text; CRLF stays one end, its CR kept
 * for the caller's tokenizer): a CR-only table read as one long row.  Returns the length or -1. */
long yf_getline(char **line, size_t *cap, FILE *fp);
/* Of CSV rows that each begin with a step ("STEP,..."), text from its start: the length of the
 * leading rows whose step is below step (a log continued after a restart keeps these, and writes
 * the rest again). */
size_t yf_rows_before(const char *text, long step);
/* A UTF-8 byte-order mark (EF BB BF, which some Windows editors put at the start of a text) at
 * the start of the NUL-terminated s is removed; returns the bytes removed (0 or 3).  Every text
 * reader skips it (yf_read_file does), so that 'material' is not read as '\xef\xbb\xbfmaterial'. */
size_t yf_skip_bom(char *s);
/* 1 if path can be written as outputs are (PATH.tmp created, then renamed): checked when an
 * output is asked for, so that a missing folder is a clear error before the run, not after it;
 * 0 with errno set if not.  Nothing is left behind.  Always 1 on a rank that writes no files
 * (MPI ranks other than 0). */
int yf_can_create(const char *path);

/* The name of names[0..n-1] nearest to word by edit distance, NULL when none is close
 * (for "did you mean" in messages). */
const char *yf_nearest(const char *word, const char *const *names, int n);

#endif
