/* thermo_style.c: custom thermo output and record files (thermo_style.h), the deck's side: the
 * step prints the thermo line through s->thermo_custom when it is set, and record rows are written
 * by an observer of the run loop's events (run start, steps), so the step calls no deck code.
 *
 * thermo_style custom K1 K2 ... replaces the columns of the thermo line (the default line is
 * unchanged for decks that do not ask).  A keyword is one of the default columns (step, time, ke,
 * strain, ext, diss, balance, broken, pairs, wall; also by their header names KinEng, ...) or any
 * deck expression: a thermo or group quantity (vy_impactor, uy_tip, broken, pairs, damping, ...),
 * a variable v_NAME, or arithmetic on them ("ke+strain").  Expressions are evaluated by the deck
 * (deck_eval) when the line is printed, so a mistake is reported at the first thermo line with the
 * thermo_style line's place.
 *
 * record ID N FILE K1 K2 ... writes "step,time,K1,K2,..." rows to FILE every N steps of a run and
 * at its start, each row handed to the file as it is written, so a plot can follow a long run; the
 * file is created at its first row (a deck that fails before run leaves none).  It is always whole:
 * its header (and the rows a continued run keeps) go in as FILE.tmp renamed over FILE, and a row
 * that does not fit (a full disk) is cut off again (YfRows, wfile.h), so the file ends at its last
 * complete row (one cut mid-number was left at its end, 2026-11-28).  Keywords as for thermo_style (the default
 * columns other than step and time need a thermo line's energies: use ke, strain, ... which the
 * queries compute).  Nothing here runs inside the step loop's numerics: rows are due at most once
 * per step, and the step checks a single integer when none is.
 */
#include <errno.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include "par.h"
#include "thermo_style.h"
#include "deck.h"
#include "run.h"
#include "output.h"
#include "err.h"
#include "wfile.h"

#define REPORT_MAX_WORDS 32
#define REPORT_MAX_RECORDS 8

typedef struct {
  int n;
  char *w[REPORT_MAX_WORDS];
  YfLoc loc; /* the command's place, for errors in its expressions */
  char file[YF_NAME_MAX * 8];
} Words;

typedef struct {
  char id[YF_NAME_MAX];
  long every;
  Words q;
  char *path; /* the CSV file, in the working directory as dumps are */
  YfRows out; /* fd -1 until its first row */
  long last_step;
  int adopted; /* a run continued by read_restart took up this file's earlier rows (adopt) */
} Record;

static struct {
  int custom;
  Words th;
  Record rec[REPORT_MAX_RECORDS];
  int nrec;
  long next_due; /* smallest step at which a record is due (LONG_MAX: none) */
} P = {.next_due = LONG_MAX};

static const char *const std_names[YF_TH_N] = {"step", "time", "ke", "strain", "ext", "diss", "balance",
                                               "broken", "pairs", "wall"};
static const char *const std_heads[YF_TH_N] = {"Step", "Time", "KinEng", "StrainEng", "ExtWork",
                                               "Dissipated", "Balance", "Broken", "Pairs", "Wall"};

static int std_index(const char *w) {
  for (int i = 0; i < YF_TH_N; i++)
    if (!strcasecmp(w, std_names[i]) || !strcasecmp(w, std_heads[i])) return i;
  return -1;
}

static void words_free(Words *q) {
  for (int i = 0; i < q->n; i++) free(q->w[i]);
  q->n = 0;
}

static void words_take(Words *q, const YfArgs *a, int from) {
  words_free(q);
  if (a->n - from > REPORT_MAX_WORDS) arg_error(a, from + REPORT_MAX_WORDS, "at most %d quantities", REPORT_MAX_WORDS);
  for (int i = from; i < a->n; i++) q->w[q->n++] = yf_strdup(a->w[i]);
  q->loc = a->loc;
  snprintf(q->file, sizeof q->file, "%s", a->loc.file ? a->loc.file : "");
  q->loc.file = q->file;
}

static double value(YfSim *s, const Words *q, int i, const double *std, const char *owner) {
  int k = std_index(q->w[i]);
  if (k >= 0 && std) return std[k];
  if (k == YF_TH_STEP) return (double)s->step;
  if (k == YF_TH_TIME) return s->time;
  if (!s->deck) yf_deck_error(&q->loc, "quantity '%s': no deck to evaluate it", q->w[i]);
  /* a column that fails mid-run (1/(1-step/50) at step 50) named the deck line only: say when */
  char what[YF_NAME_MAX + 64];
  snprintf(what, sizeof what, "%s, at step %ld: ", owner, s->step);
  return deck_eval_as(s->deck, q->w[i], &q->loc, what);
}

/* thermo_style default | thermo_style custom K1 K2 ... */
static void custom_thermo(YfSim *s, const double *std);
static void record_observer(YfSim *s, YfEvent *ev);

void cmd_thermo_style(YfSim *s, const YfArgs *a) {
  static const char *const styles[] = {"default", "custom", NULL};
  arg_count(a, 1, -1);
  int st = arg_choice(a, 0, "thermo style", styles);
  if (st == 0) {
    arg_count(a, 1, 1);
    P.custom = 0;
    words_free(&P.th);
    s->thermo_custom = NULL;
    return;
  }
  if (a->n < 2) arg_error(a, 0, "give the quantities, e.g. 'thermo_style custom step time ke broken vy_impactor'");
  words_take(&P.th, a, 1);
  P.custom = 1;
  s->thermo_custom = custom_thermo;
  sim_observe(s, record_observer); /* its FREE event clears this module's state */
}

static void thermo_header(YfSim *s) {
  char line[REPORT_MAX_WORDS * 40] = "";
  size_t k = 0;
  for (int i = 0; i < P.th.n && k < sizeof line; i++) {
    int j = std_index(P.th.w[i]);
    k += (size_t)snprintf(line + k, sizeof line - k, i ? " %13.13s" : "%10.10s", j >= 0 ? std_heads[j] : P.th.w[i]);
  }
  sim_printf(s, "%s\n", line);
}

static void thermo_line(YfSim *s, const double *std) {
  char line[REPORT_MAX_WORDS * 40] = "";
  size_t k = 0;
  for (int i = 0; i < P.th.n && k < sizeof line; i++) {
    double v = value(s, &P.th, i, std, "thermo_style");
    int j = std_index(P.th.w[i]);
    if (j == YF_TH_STEP || j == YF_TH_BROKEN || j == YF_TH_PAIRS)
      k += (size_t)snprintf(line + k, sizeof line - k, i ? " %13ld" : "%10ld", (long)v);
    else
      k += (size_t)snprintf(line + k, sizeof line - k, i ? " %13.6e" : "%10.4e", v == 0.0 ? 0.0 : v);
  }
  sim_printf(s, "%s\n", line);
}

/* The step's hook (sim.h): std NULL for the header, else the default columns' values. */
static void custom_thermo(YfSim *s, const double *std) {
  if (std) thermo_line(s, std);
  else thermo_header(s);
}

static void update_due(const YfSim *s) {
  P.next_due = LONG_MAX;
  for (int i = 0; i < P.nrec; i++) {
    long k = (s->step / P.rec[i].every + 1) * P.rec[i].every;
    if (k < P.next_due) P.next_due = k;
  }
}

/* record ID N FILE K1 K2 ... | record ID off */
void cmd_record(YfSim *s, const YfArgs *a) {
  arg_count(a, 2, -1);
  const char *id = arg_name(a, 0, "record id");
  int slot = -1;
  for (int i = 0; i < P.nrec; i++)
    if (!strcmp(P.rec[i].id, id)) slot = i;
  if (a->n == 2 && !strcmp(a->w[1], "off")) {
    if (slot < 0) arg_error(a, 0, "no such record");
    char owner[YF_NAME_MAX + 16];
    snprintf(owner, sizeof owner, "record '%s'", id);
    output_release(s, owner);
    Record *r = &P.rec[slot];
    if (r->out.fd >= 0) yf_rows_close(&r->out);
    words_free(&r->q);
    free(r->path);
    P.rec[slot] = P.rec[--P.nrec];
    update_due(s);
    return;
  }
  arg_count(a, 4, -1);
  if (slot >= 0) arg_error(a, 0, "a record with this id exists ('record %s off' first)", id);
  if (P.nrec >= REPORT_MAX_RECORDS) arg_error(a, 0, "at most %d records at a time", REPORT_MAX_RECORDS);
  long every = arg_int(a, 1, "N (steps between rows)", 1, LONG_MAX / 4);
  const char *file = arg_word(a, 2, "file");
  if (!file[0]) arg_error(a, 2, "empty file name");
  /* a missing folder: now, at this line (the file itself is created at its first row) */
  if (!yf_can_create(file)) yf_io_error(&a->loc, "record %s: cannot write '%s': %s", id, file, yf_strerror(errno));
  char owner[YF_NAME_MAX + 16];
  snprintf(owner, sizeof owner, "record '%s'", id);
  arg_claim(s, a, 2, owner, file, NULL, 0);
  Record *r = &P.rec[P.nrec];
  memset(r, 0, sizeof *r);
  r->out.fd = -1;
  snprintf(r->id, sizeof r->id, "%s", id);
  r->every = every;
  r->last_step = LONG_MIN;
  words_take(&r->q, a, 3);
  r->path = yf_strdup(file);
  P.nrec++;
  sim_observe(s, record_observer);
  sim_printf(s, "record %s: every %ld steps to %s (step, time, %d quantit%s)\n", id, every, file, r->q.n,
             r->q.n == 1 ? "y" : "ies");
  update_due(s);
}

/* The file created with its header line and, when a run continued by read_restart adopts it,
 * the earlier run's rows kept (keep: NULL or text after the header). */
/* The file's header line, "step,time,K1,K2,...\n" (allocated). */
static char *record_head(const Record *r) {
  size_t n = sizeof "step,time\n";
  for (int i = 0; i < r->q.n; i++) n += 3 + 2 * strlen(r->q.w[i]); /* quoted, its quotes doubled */
  char *h = yf_malloc(n, "record header"), *o = h + sprintf(h, "step,time");
  for (int i = 0; i < r->q.n; i++) {
    char *f = yf_csv_field(r->q.w[i]); /* an expression with a comma is one column */
    o += sprintf(o, ",%s", f);
    free(f);
  }
  strcpy(o, "\n");
  return h;
}

static void record_open(Record *r, const char *keep) {
  struct stat st;
  if (lstat(r->path, &st) == 0 && !S_ISREG(st.st_mode) && !S_ISDIR(st.st_mode)) {
    /* a FIFO, a device, a link such as /dev/stdout: opened once, header and rows through the one
     * descriptor (written whole, then opened again to append, a FIFO's reader saw the end of its
     * input after the header and the rows found no reader) */
    if (yf_rows_open(&r->out, r->path, 0) != 0)
      yf_io_error(&r->q.loc, "record %s: cannot create '%s': %s", r->id, r->path, yf_strerror(errno));
    char *h = record_head(r);
    yf_rows_printf(&r->out, "%s%s", h, keep ? keep : "");
    free(h);
    if (yf_rows_end(&r->out) != 0)
      yf_io_error(&r->q.loc, "record %s: cannot write '%s': %s", r->id, r->path, yf_strerror(errno));
    return;
  }
  /* whole or not at all: a full disk leaves the earlier file (and its rows a continued run keeps)
   * rather than a header cut short */
  YfWFile w;
  if (yf_wfile_open(&w, r->path) != 0)
    yf_io_error(&r->q.loc, "record %s: cannot create '%s': %s", r->id, r->path, yf_strerror(errno));
  char *h = record_head(r);
  fputs(h, w.f);
  free(h);
  if (keep) fputs(keep, w.f);
  if (yf_wfile_close(&w, 0, 0) != 0)
    yf_io_error(&r->q.loc, "record %s: cannot write '%s': %s", r->id, r->path, yf_strerror(errno));
  if (yf_rows_open(&r->out, r->path, 1) != 0)
    yf_io_error(&r->q.loc, "record %s: cannot create '%s': %s", r->id, r->path, yf_strerror(errno));
}

/* A run continued by read_restart continues each record's file as the dumps continue their
 * series (output.c): the earlier run's rows of steps before the one this run continues from stay,
 * and rows of later steps (written before an interrupt) are this run's to write again.  A file
 * that is missing, or whose header is not this record's, starts afresh at the first row.  Rows of
 * steps before `before` are kept; returns 1 if one of them is of step before - 1. */
static int adopt(Record *r, long before) {
  r->adopted = 1;
  size_t len;
  char *t = yf_read_output(r->path, &len, "record file");
  if (!t) return 0;
  char *h = record_head(r);
  size_t hl = strlen(h);
  int at = 0;
  if (!strncmp(t, h, hl)) {
    char *keep = t + hl;
    size_t n = yf_rows_before(keep, before);
    at = n > yf_rows_before(keep, before - 1);
    keep[n] = 0;
    record_open(r, keep);
  }
  free(h);
  free(t);
  return at;
}

static void record_row(YfSim *s, Record *r) {
  char owner[YF_NAME_MAX + 16];
  snprintf(owner, sizeof owner, "record %s", r->id);
  if (r->out.fd < 0) {
    /* every quantity evaluates before the file is made: a mistake in one ('nosuchq') left a
     * header and half a row behind */
    for (int i = 0; i < r->q.n; i++) (void)value(s, &r->q, i, NULL, owner);
    record_open(r, NULL);
  }
  /* the row's values first, then the row: a quantity failing mid-run (1/(step-1) at step 1) left
   * a row cut after its time */
  double vals[REPORT_MAX_WORDS];
  for (int i = 0; i < r->q.n; i++) vals[i] = value(s, &r->q, i, NULL, owner);
  yf_rows_printf(&r->out, "%ld,%.17g", s->step, s->time);
  for (int i = 0; i < r->q.n; i++) yf_rows_printf(&r->out, ",%.17g", vals[i] == 0.0 ? 0.0 : vals[i]);
  yf_rows_printf(&r->out, "\n");
  /* whole or not at all: on a full disk the file ends at the row before */
  if (yf_rows_end(&r->out) != 0)
    yf_io_error(&r->q.loc, "record %s: cannot write '%s': %s", r->id, r->path, yf_strerror(errno));
  r->last_step = s->step;
}

static void record_step(YfSim *s, int force) {
  if (!force && s->step < P.next_due) return;
  if (force && s->restored) /* the first run after read_restart: the earlier rows taken up */
    for (int i = 0; i < P.nrec; i++) {
      Record *r = &P.rec[i];
      if (r->adopted || r->last_step != LONG_MIN) continue;
      if (s->restored_between) {
        /* a restart written between runs: the earlier run's row of this step stays (due on its
         * last step, or its next run's start row), and the uninterrupted deck's next run began
         * with a row unless it had that one (as the dumps' first frames, output.c) */
        long at = yf_writer() ? adopt(r, s->step + 1) : 0;
        r->adopted = 1;
        if (par_bcast_long(at)) r->last_step = s->step; /* MPI: rank 0 read the file; all or none write */
        continue;
      }
      if (yf_writer()) adopt(r, s->step);
      else r->adopted = 1;
      /* the uninterrupted run went through this step in one run: no row here unless one was
       * due (a continued run's dumps write no frame either, output.c) */
      if (s->step % r->every != 0) r->last_step = s->step;
    }
  int due = 0;
  for (int i = 0; i < P.nrec; i++) due |= P.rec[i].last_step != s->step && (force || s->step % P.rec[i].every == 0);
  if (due) par_need_all(s); /* MPI: the rows read any node (every rank is here); rank 0 writes them */
  /* a state gone non-finite is the run's numerical failure, named by its node (a row of 'ke' was a
   * deck error "ke gives a non-finite result", exit 1) */
  if (due) run_check_nodes(s, 0, s->model.node.n);
  for (int i = 0; i < P.nrec; i++) {
    Record *r = &P.rec[i];
    if (r->last_step != s->step && (force || s->step % r->every == 0)) {
      if (yf_writer()) record_row(s, r);
      else r->last_step = s->step;
    }
  }
  update_due(s);
}

static void record_close(void) {
  for (int i = 0; i < P.nrec; i++)
    if (P.rec[i].out.fd >= 0) yf_rows_close(&P.rec[i].out);
}

static void reset(void) {
  record_close();
  for (int i = 0; i < P.nrec; i++) {
    free(P.rec[i].path);
    words_free(&P.rec[i].q);
  }
  P.nrec = 0;
  P.custom = 0;
  words_free(&P.th);
  P.next_due = LONG_MAX;
}

/* The run loop's events: rows at the start of a run and at the steps due; all state goes when the
 * simulation is freed. */
static void record_observer(YfSim *s, YfEvent *ev) {
  if (ev->kind == YF_EV_RUN_BEGIN) record_step(s, 1);
  else if (ev->kind == YF_EV_STEP) record_step(s, 0);
  else if (ev->kind == YF_EV_FREE) reset();
}
