/* y2dref.c: the `y2dref` dump (see y2dref.h): the neutral CSV files of the Y2D reference outputs.
 *
 * The dump is registered in output.c with a period of one step; y2dref_frame decides what is due
 * (a corner table at a listed step, a summary or probe row every K steps, new joint failures) and
 * costs a few integer compares on the other steps.  Every file is left whole, also on a full disk:
 * a corner table is written as NAME.tmp and renamed (wfile.h), and summary, probe and broken rows
 * go into their files a row at a time, a row that does not fit cut off again (YfRows, wfile.h), so
 * an interrupted or failed run leaves complete rows (a corner table cut at 4096 bytes mid-row, and
 * tables ended mid-row, were left behind, 2026-11-28).  A run continued by read_restart continues
 * the tables as the other dumps continue their series (y2dref_continue), so its folder equals the
 * uninterrupted run's (the tables began afresh at the restart step, their earlier rows lost,
 * 2026-11-28).  Energies follow README section 3: kinetic = sum m |v|^2 / 2 with the half-step
 * velocities, elastic = sum A_c/2 T:E of the triangle law without the viscous part
 * (run_energies).  Units: SI (J/m, kg m/s per m).
 */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <unistd.h>
#include "y2dref.h"
#include "contact.h"
#include "err.h"
#include "joint.h"
#include "elem_tri.h"
#include "run.h"
#include "y2d_model.h"
#include "partition.h"
#include "wfile.h"

typedef struct YfY2dRef {
  char *dir;
  long *csteps;   /* corner-table steps, as given */
  int ncsteps;
  long sum_every, probe_every;
  int nprobe;
  long *probe;    /* 2 per probe: input element, corner */
  YfRows fsum, fprobe, fbroken; /* fd -1: not open */
  int opened;          /* files open                                              */
  int created;         /* files created by this dump (a reopen appends)            */
  long cont_step;      /* while y2dref_continue opens the files: rows of steps before it are
                          the earlier run's to keep (else -1)                      */
  long nbroken_written;
} YfY2dRef;

const char *y2dref_dir(const YfY2dRef *r) { return r->dir; }

YfY2dRef *y2dref_new(const char *dir) {
  YfY2dRef *r = yf_calloc(1, sizeof *r, "y2dref dump");
  r->dir = yf_strdup(dir);
  r->fsum.fd = r->fprobe.fd = r->fbroken.fd = -1;
  r->cont_step = -1;
  return r;
}

int y2dref_add_corner_step(YfY2dRef *r, long step) {
  r->csteps = yf_realloc(r->csteps, (size_t)(r->ncsteps + 1) * sizeof(long), "y2dref steps");
  r->csteps[r->ncsteps++] = step;
  return r->ncsteps;
}

void y2dref_set_summary(YfY2dRef *r, long every) { r->sum_every = every; }
void y2dref_set_probe_every(YfY2dRef *r, long every) { r->probe_every = every; }

int y2dref_add_probe(YfY2dRef *r, long elem, long corner) {
  r->probe = yf_realloc(r->probe, (size_t)(2 * r->nprobe + 2) * sizeof(long), "y2dref probes");
  r->probe[2 * r->nprobe] = elem;
  r->probe[2 * r->nprobe + 1] = corner;
  return ++r->nprobe;
}
int y2dref_nprobe(const YfY2dRef *r) { return r->nprobe; }
int y2dref_ncorner_steps(const YfY2dRef *r) { return r->ncsteps; }

/* A row (or rows) gathered in w goes into file NAME of the dump whole, or the run ends (exit 2). */
static void check_write(YfRows *w, const YfY2dRef *r, const char *name) {
  if (yf_rows_end(w) != 0) yf_io_error(NULL, "dump y2dref: cannot write '%s/%s': %s", r->dir, name, yf_strerror(errno));
}

/* In a run continued by read_restart (r->cont_step >= 0), the table the earlier run left at PATH,
 * when it begins with this table's header (gathered in w), is taken up: its rows of steps before
 * r->cont_step stay, the later ones (written before an interrupt, past the restart) go, and the
 * rows this run writes follow.  The kept part goes in as PATH.tmp renamed over PATH (wfile.h), so a
 * full disk leaves the earlier table, not a cut one.  1 if taken up; 0 if the table is missing or
 * another (its header differs: other probes), to be begun afresh. */
static int adopt_csv(YfY2dRef *r, YfRows *w, const char *path) {
  size_t len;
  char *t = r->cont_step >= 0 ? yf_read_output(path, &len, "y2dref table") : NULL;
  if (!t) return 0;
  if (len < w->len || memcmp(t, w->row, w->len) != 0) {
    free(t);
    return 0;
  }
  char *keep = t + w->len;
  keep[yf_rows_before(keep, r->cont_step)] = 0;
  YfWFile f;
  if (yf_wfile_open(&f, path) != 0) yf_io_error(NULL, "dump y2dref: cannot create '%s': %s", path, yf_strerror(errno));
  fwrite(w->row, 1, w->len, f.f);
  fputs(keep, f.f);
  free(t);
  if (yf_wfile_close(&f, 0, 0) != 0) yf_io_error(NULL, "dump y2dref: cannot write '%s': %s", path, yf_strerror(errno));
  if (yf_rows_open(w, path, 1) != 0) yf_io_error(NULL, "dump y2dref: cannot create '%s': %s", path, yf_strerror(errno));
  w->len = 0; /* the header is there */
  return 1;
}

/* Create (first time, with its header gathered in w by the caller: w->row) or reopen for
 * appending (after y2dref_close) a CSV file; 1 if it took up the earlier run's table (adopt_csv). */
static int open_csv(YfY2dRef *r, YfRows *w, const char *name) {
  char path[4096];
  snprintf(path, sizeof path, "%s/%s", r->dir, name);
  if (!r->created && adopt_csv(r, w, path)) return 1;
  if (yf_rows_open(w, path, r->created) != 0)
    yf_io_error(NULL, "dump y2dref: cannot create '%s': %s", path, yf_strerror(errno));
  if (r->created) { /* reopened: its header is there */
    w->len = 0;
    return 0;
  }
  if (yf_rows_end(w) != 0) {
    /* not even its header: no file rather than an empty one */
    int e = errno;
    if (w->end >= 0) unlink(path);
    errno = e;
    yf_io_error(NULL, "dump y2dref: cannot write '%s': %s", path, yf_strerror(errno));
  }
  return 0;
}

static void mkdir_p(const char *dir) {
  char *p = yf_strdup(dir);
  for (char *q = p + 1; *q; q++) {
    if (*q != '/') continue;
    *q = 0;
    mkdir(p, 0777);
    *q = '/';
  }
  if (mkdir(p, 0777) != 0 && errno != EEXIST) yf_io_error(NULL, "dump y2dref: cannot create directory '%s': %s", p, yf_strerror(errno));
  free(p);
}

int y2dref_dir_check(const char *dir) {
  if (!yf_writer()) return 0; /* MPI: rank 0 alone makes the folder and writes the files */
  char *p = yf_strdup(dir);
  size_t n = strlen(p);
  int rc = 0, missing = 0;
  /* each folder on the way, as mkdir_p makes them: one that is there must be a folder; the first
   * one missing is made and removed again (the only sure test that it can be made, also as root or
   * on a read-only disk), and nothing is left behind by a deck that then fails */
  for (size_t i = 1; i <= n && !rc && !missing; i++) {
    if ((p[i] != '/' && p[i] != 0) || p[i - 1] == '/') continue;
    char c = p[i];
    p[i] = 0;
    struct stat st;
    if (stat(p, &st) == 0) {
      if (!S_ISDIR(st.st_mode)) errno = ENOTDIR, rc = 1;
    } else if (errno != ENOENT) {
      rc = 1;
    } else if (mkdir(p, 0777) != 0) {
      rc = 1;
    } else {
      rmdir(p);
      missing = 1;
    }
    p[i] = c;
  }
  if (!rc && !missing) { /* there already: its files can be written in it */
    static const char *const tables[] = {Y2DREF_SUMMARY, Y2DREF_PROBES, Y2DREF_BROKEN};
    for (int k = 0; k < 3 && !rc; k++) { /* (a folder named probes.csv failed the run's first step) */
      char f[4096];
      struct stat st;
      snprintf(f, sizeof f, "%s/%s", dir, tables[k]);
      if (!yf_can_create(f)) rc = lstat(f, &st) == 0 ? 3 + k : 2;
    }
  }
  int e = errno;
  free(p);
  errno = e;
  return rc;
}

/* The files opened (created, reopened or, in a continued run, taken up); how many tables were
 * taken up from an earlier run. */
static int open_files(YfSim *s, YfY2dRef *r) {
  int adopted = 0;
  mkdir_p(r->dir);
  if (r->sum_every) {
    yf_rows_printf(&r->fsum, "step,time,kinetic,elastic,px,py,nbroken,ncouples\n");
    adopted += open_csv(r, &r->fsum, Y2DREF_SUMMARY);
  }
  if (r->probe_every) {
    yf_rows_printf(&r->fprobe, "step,time");
    for (int k = 0; k < r->nprobe; k++) {
      long e = r->probe[2 * k], c = r->probe[2 * k + 1];
      yf_rows_printf(&r->fprobe, ",ux_%ld_%ld,uy_%ld_%ld,vx_%ld_%ld,vy_%ld_%ld", e, c, e, c, e, c, e, c);
    }
    yf_rows_printf(&r->fprobe, "\n");
    adopted += open_csv(r, &r->fprobe, Y2DREF_PROBES);
  }
  yf_rows_printf(&r->fbroken, "step,elemA,elemB,nodeP,nodeQ\n");
  if (open_csv(r, &r->fbroken, Y2DREF_BROKEN)) {
    /* its rows of failures before the restart step are there: the failures the restart holds
     * from that step on are this run's to write (else every failure it holds is written, as by a
     * dump begun after joints broke) */
    adopted++;
    int nb = 0;
    const YfBreak *b = joints_breaks(s, &nb);
    r->nbroken_written = 0;
    while (r->nbroken_written < nb && b[r->nbroken_written].step < r->cont_step) r->nbroken_written++;
  }
  r->opened = 1;
  r->created = 1;
  return adopted;
}

int y2dref_continue(YfSim *s, YfY2dRef *r, long before) {
  if (r->opened || r->created) return 0;
  r->cont_step = before;
  int n = open_files(s, r);
  r->cont_step = -1;
  return n;
}

static void write_corners(YfSim *s, YfY2dRef *r) {
  char path[4096];
  snprintf(path, sizeof path, "%s/" Y2DREF_CORNERS "%07ld.csv", r->dir, s->step);
  /* whole or not at all (PATH.tmp renamed, wfile.h), as the csv dump's frames */
  YfWFile w;
  if (yf_wfile_open(&w, path) != 0) yf_io_error(NULL, "dump y2dref: cannot create '%s': %s", path, yf_strerror(errno));
  FILE *f = w.f;
  fputs("elem,corner,node,ux,uy,vx,vy\n", f);
  const YfNodes *n = &s->model.node;
  const YfTris *t = &s->model.tri;
  /* rows in input element order (the partition may have renumbered the triangles) */
  int e0 = s->y2d ? s->y2d->tri0 : 0, e1 = s->y2d ? s->y2d->tri0 + s->y2d->ntri : t->n;
  for (int eo = e0; eo < e1; eo++)
    for (int c = 0; c < 3; c++) {
      int e = partition_tri(&s->model, eo);
      int i = t->v[3 * e + c];
      fprintf(f, "%d,%d,%d,%.16e,%.16e,%.16e,%.16e\n", t->id[e], c, y2d_input_node(s, i), n->x[i] - n->x0[i],
              n->y[i] - n->y0[i], n->vx[i], n->vy[i]);
    }
  if (yf_wfile_close(&w, 0, 0) != 0) yf_io_error(NULL, "dump y2dref: cannot write '%s': %s", path, yf_strerror(errno));
}

static void write_summary(YfSim *s, YfY2dRef *r) {
  /* README 3: kinetic = sum m |v|^2 / 2; elastic = triangles only (A_c/2 T:E, no viscous part,
   * no joint energy, which run_energies adds to energy.strain) */
  run_energies_whole(s); /* MPI: on the writer alone, from the state gathered for the frame */
  const YfTriMat *tm = run_tri_mats();
  double elastic = tm ? tri_strain_energy(&s->model, tm, 0, s->model.tri.n) : 0.0;
  const YfNodes *n = &s->model.node;
  double px = 0, py = 0;
  for (int i = 0; i < n->n; i++) {
    px += n->m[i] * n->vx[i];
    py += n->m[i] * n->vy[i];
  }
  yf_rows_printf(&r->fsum, "%ld,%.16e,%.16e,%.16e,%.16e,%.16e,%ld,%ld\n", s->step, s->time, s->energy.kinetic,
          elastic, px, py, joints_broken(s), contact_pairs(s));
  check_write(&r->fsum, r, Y2DREF_SUMMARY);
}

static void write_probes(YfSim *s, YfY2dRef *r) {
  const YfNodes *n = &s->model.node;
  yf_rows_printf(&r->fprobe, "%ld,%.16e", s->step, s->time);
  for (int k = 0; k < r->nprobe; k++) {
    int t = y2d_tri_of_elem(s, r->probe[2 * k]);
    int i = s->model.tri.v[3 * t + r->probe[2 * k + 1]];
    yf_rows_printf(&r->fprobe, ",%.16e,%.16e,%.16e,%.16e", n->x[i] - n->x0[i], n->y[i] - n->y0[i], n->vx[i], n->vy[i]);
  }
  yf_rows_printf(&r->fprobe, "\n");
  check_write(&r->fprobe, r, Y2DREF_PROBES);
}

/* New joint failures since the last frame, in the order joint.c recorded them. */
static void write_breaks(YfSim *s, YfY2dRef *r) {
  int nb = 0;
  const YfBreak *b = joints_breaks(s, &nb);
  if (nb <= r->nbroken_written) return;
  const YfJoints *J = s->joints;
  for (long k = r->nbroken_written; k < nb; k++) {
    int ea = s->model.tri.id[b[k].triA], eb = s->model.tri.id[b[k].triB];
    /* the shared edge: slots 0, 1 are A's copies of its start and end nodes */
    int p = y2d_input_node(s, J->node[4 * b[k].joint]), q = y2d_input_node(s, J->node[4 * b[k].joint + 1]);
    yf_rows_printf(&r->fbroken, "%ld,%d,%d,%d,%d\n", b[k].step, ea < eb ? ea : eb, ea < eb ? eb : ea, p < q ? p : q,
            p < q ? q : p);
  }
  r->nbroken_written = nb;
  check_write(&r->fbroken, r, Y2DREF_BROKEN); /* this frame's failures go in together */
}

void y2dref_frame(YfSim *s, YfY2dRef *r) {
  if (!r->opened) open_files(s, r);
  write_breaks(s, r);
  for (int k = 0; k < r->ncsteps; k++)
    if (r->csteps[k] == s->step) {
      write_corners(s, r);
      break;
    }
  if (s->step > 0 && r->sum_every && s->step % r->sum_every == 0) write_summary(s, r);
  if (s->step > 0 && r->probe_every && s->step % r->probe_every == 0) write_probes(s, r);
}

void y2dref_close(YfY2dRef *r) {
  if (!r) return;
  YfRows *f[3] = {&r->fsum, &r->fprobe, &r->fbroken};
  for (int k = 0; k < 3; k++)
    if (f[k]->fd >= 0 && yf_rows_close(f[k]) != 0)
      yf_output_error("dump y2dref: cannot write a file of '%s': %s", r->dir, strerror(errno ? errno : EIO));
  r->opened = 0;
}

void y2dref_free(YfY2dRef *r) {
  if (!r) return;
  y2dref_close(r);
  free(r->fsum.row); /* a header gathered for a file that never opened */
  free(r->fprobe.row);
  free(r->fbroken.row);
  free(r->dir);
  free(r->csteps);
  free(r->probe);
  free(r);
}
