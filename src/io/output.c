/* output.c: frames of the state for post-processing (see output.h for the contract).
 *
 * h5 dumps.  `dump ID h5 N FILE.h5` writes frame k to its own HDF5 file STEM_NNNNNN.h5 (STEM is
 * FILE without its .h5/.hdf5/.hdf extension, NNNNNN the frame index k, zero-padded to 6 digits,
 * the extension kept; .h5 when FILE has none) and an XDMF 3 index STEM.xmf that lists the frames
 * (ParaView: File > Open STEM.xmf), plus STEM_cracks.xmf for the cracks of a scene with joints.  Each frame file is self-contained:
 *
 *   /mesh/{triangles (ntri x 3 int), material, body, tri_id (ntri int),
 *          node_id (n int), x0 (n x 2)}                   the topology at this frame
 *   /time, /step (scalars), /x, /u, /v, /f (n x 2), /stress (ntri x 3: sxx syy sxy) and its
 *   parts /stress_xx, /stress_yy, /stress_xy, /vonmises, /sigma1 (ntri),
 *   /fc (n x 2): contact force per node, only while contact is on
 *   /cracks/{segments, xy, state, mode, damage}: the crack series (see xmf_add_frame)
 *
 * Why one file per frame: crash safety by construction.  A file is never modified once written.
 * A frame goes to NAME.tmp, is closed (H5Fclose: every byte handed to the OS), renamed to NAME
 * (atomic), and only then is the .xmf replaced atomically (STEM.xmf.tmp + rename) by an index
 * that lists it (at once, or for a long series of frequent frames a little later: xmf_write).
 * A run killed at any moment therefore leaves an .xmf that lists only complete,
 * never-again-touched files; at worst a stale NAME.tmp of the frame in progress.  The earlier
 * design (one file, a group per frame, H5Fflush) updated shared metadata (group header,
 * superblock) in place with multi-page writes, which SIGKILL can tear, losing earlier frames.
 * It also makes topology changes (fracture inserting nodes) free: each file has its own /mesh.
 * The cost is one file create/close per frame and the mesh arrays once per frame (~30 % of a
 * frame's bytes): for 1e5 triangles ~7 ms with 5e4 nodes, ~17-20 ms with the 3e5 nodes of a
 * fully jointed mesh (31 MB), measured on a loaded 2-core machine (README, Output).
 *
 * Durability: nothing is fsync'ed.  rename after close is enough against a killed process (the
 * kernel has the data); after a power cut or OS crash the most recent frames and the index may
 * be lost or, on file systems that reorder metadata and data, the .xmf may name a frame whose
 * data did not reach the disk.  Guarding against that would need an fsync of each frame file
 * and of the directory before the index names it (tens of ms per frame on a loaded disk).
 *
 * A new run (a new process) with the same dump starts again at frame 0 and rewrites the index
 * from scratch (a run continued by read_restart continues the series instead: dump_adopt);
 * frame files of an earlier, longer run beyond the new count stay on disk but are not listed
 * (delete STEM_*.h5 yourself if they are in the way).
 *
 * Datasets are contiguous and uncompressed by default: a frame is then one write per array.
 * `compress` switches to gzip (level 1, with shuffle) in chunks: half the size, ~20x the time.
 *
 * ./yfdem_mpi on 2 ranks or more (or YFDEM_H5_MPIIO=1) writes h5 frames with parallel HDF5: every
 * rank opens the frame file (MPI-IO) and writes, collectively, the rows of the triangles, nodes
 * and joints it owns (h5_put_rows), so what only owners hold is never gathered; rank 0 alone
 * renames the file and writes the indexes.  The datasets are those one writer writes, bit for
 * bit (the files differ in layout only).  YFDEM_H5_MPIIO=0: rank 0 writes, after a gather.
 *
 * csv dumps.  PREFIX_NNNNNN.csv (node id, x, y, ux, uy, vx, vy) per frame plus PREFIX_frames.csv
 * (frame, step, time, file) for scripts.  The index grows by whole rows (YfRows, wfile.h), as a
 * record's file: on a full disk it ends at its last complete row (through stdio it ended mid-row,
 * the unwritten tail of a failed fflush, 2026-11-28).
 *
 * The XDMF <Grid> text of every frame is kept in memory and the whole index is rewritten per
 * frame (about 2 kB per frame), so the index stays a plain, self-contained file.
 */
#include <ctype.h>
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include <hdf5.h>
#ifdef YF_MPI
#include <mpi.h> /* parallel HDF5 (H5Pset_fapl_mpio): ./yfdem_mpi only */
#endif
#include "output.h"
#include "wfile.h"
#include "h5quiet.h"
#include "par.h"
#include "report.h"
#include "restart.h"
#include "contact.h"
#include "joint.h"
#include "err.h"
#include "y2dref.h"
#include "run.h"
#include "summary.h" /* sim_state_hash: did the deck change the scene between runs? */

/* A growing text: the <Grid> elements of an index. */
typedef struct {
  char *s;
  size_t len, cap;
} YfText;

typedef struct YfDump {
  char id[YF_NAME_MAX];
  int style;          /* YF_DUMP_H5 | YF_DUMP_CSV                                       */
  long every;         /* steps between frames                                          */
  unsigned fields;    /* YF_FIELD_* (h5)                                               */
  int compress;       /* gzip chunks (h5)                                              */
  char *path;         /* h5 file as given (FILE.h5), or csv prefix                      */
  char *stem, *ext;   /* h5: FILE without its extension, and the extension (".h5")      */
  char *xmf, *xmf_tmp;/* STEM.xmf and STEM.xmf.tmp                                      */
  char *cur, *cur_tmp;/* h5: the frame file being written (STEM_NNNNNN.h5) and its .tmp */
  size_t curcap;      /* bytes allocated for cur and cur_tmp                           */
  hid_t file;         /* the frame file while it is being written, else < 0            */
  int mpio;           /* h5 frames written by every rank into one file (parallel HDF5)  */
  int created;        /* csv index created in this process (a later open appends)      */
  long nframe;        /* frames written (including those of a continued series)        */
  int adopted;        /* a continued run looked for the earlier run's series (dump_adopt) */
  int again;          /* on the file of a dump undumped earlier in this process: continues its
                         series as a restarted run does (it wrote over its frames from 0) */
  unsigned again_fields; /* that dump's fields                                         */
  int had_fc, fc_asked; /* a frame had the contact force / the deck's fields named fc    */
  long first;         /* number of this process's first frame (> 0: a continued series) */
  long last_step;     /* step of the last frame (LONG_MIN: none)                       */
  uint64_t end_key;   /* sim_state_hash when a run ended on the step of its last frame   */
  long end_step;      /* ... that step (LONG_MIN: none)                                 */
  int rewrite;        /* the frame being written replaces the last one (frame_retract)  */
  YfText grids;       /* XDMF <Grid> elements of the frames so far (STEM.xmf)          */
  YfText cgrids;      /* the crack series' <Grid> elements (STEM_cracks.xmf)           */
  char *cxmf, *cxmf_tmp; /* STEM_cracks.xmf and its .tmp                               */
  int xmf_pending;    /* frames listed in grids but not yet in the .xmf (see xmf_write)  */
  double xmf_done, xmf_cost; /* when the last index rewrite ended, and what it took [s]  */
  long xmf_writes;    /* index rewrites so far                                         */
  double *buf;        /* scratch for interleaved / derived arrays                      */
  size_t bufcap;
  YfRows csv_index;   /* PREFIX_frames.csv (fd -1: not open)                            */
  struct YfY2dRef *y2d; /* y2dref style                                                */
} YfDump;

const char *const output_field_names[] = {"u", "v", "f", "stress", "vonmises", "sigma1",
                                          "material", "body", "fc", "x", NULL};

/* ---------------------------------------------------------------- small helpers */

static char *str_printf(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
static char *str_printf(const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  int n = vsnprintf(NULL, 0, fmt, ap);
  va_end(ap);
  char *p = yf_malloc((size_t)n + 1, "string");
  va_start(ap, fmt);
  vsnprintf(p, (size_t)n + 1, fmt, ap);
  va_end(ap);
  return p;
}

static void grids_printf(YfText *t, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static void grids_printf(YfText *t, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  int n = vsnprintf(NULL, 0, fmt, ap);
  va_end(ap);
  if (t->len + (size_t)n + 1 > t->cap) {
    size_t cap = t->cap ? t->cap : 4096;
    while (cap < t->len + (size_t)n + 1) cap *= 2;
    t->s = yf_realloc(t->s, cap, "XDMF index text");
    t->cap = cap;
  }
  va_start(ap, fmt);
  vsnprintf(t->s + t->len, (size_t)n + 1, fmt, ap);
  va_end(ap);
  t->len += (size_t)n;
}

static double *scratch(YfDump *d, size_t n) {
  if (n > d->bufcap) {
    d->buf = yf_realloc(d->buf, n * sizeof *d->buf, "dump buffer");
    d->bufcap = n;
  }
  return d->buf;
}

/* The most specific message on HDF5's error stack (it names errno for system failures). */
static herr_t h5_walk_cb(unsigned n, const H5E_error2_t *e, void *data) {
  if (n == 0 && e->desc) snprintf((char *)data, 512, "%s", e->desc);
  return 0;
}
static const char *h5_message(void) {
  static char msg[512], out[512];
  msg[0] = 0;
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_UPWARD, h5_walk_cb, msg);
  /* a system failure: "... errno = 28, error message = 'No space left on device', buf = 0x..."
   * (addresses and sizes of HDF5's internals): keep the system's words and the errno */
  const char *en = strstr(msg, "errno = "), *em = strstr(msg, "error message = '");
  if (en && em) {
    em += 17;
    const char *q = strchr(em, '\'');
    snprintf(out, sizeof out, "%.*s (errno %d)", q ? (int)(q - em) : 200, em, atoi(en + 8));
    return out;
  }
  return msg[0] ? msg : "HDF5 error";
}

/* A frame that cannot be written: its unfinished NAME.tmp is removed (the frames before it,
 * renamed and indexed, stay), then the I/O error. */
static void h5_fail(YfDump *d, const char *what) __attribute__((noreturn));
static void h5_fail(YfDump *d, const char *what) {
  const char *why = h5_message();
  /* a parallel file's close is a collective: the other ranks may never reach it, so the
   * handle is dropped (the error ends every rank: par_mpi.c) */
  if (d->file >= 0 && !d->mpio) H5Fclose(d->file);
  d->file = -1;
  if (d->cur_tmp) unlink(d->cur_tmp);
  yf_io_error(NULL, "dump %s: cannot write '%s' (%s): %s", d->id, d->cur, what, why);
}

static YfDump *find_dump(const struct YfOutput *o, const char *id, int *slot) {
  if (!o) return NULL;
  for (int i = 0; i < o->ndump; i++)
    if (strcmp(o->dump[i]->id, id) == 0) {
      if (slot) *slot = i;
      return o->dump[i];
    }
  return NULL;
}

/* next_due = the smallest multiple of some dump's period after the current step. */
static void update_next_due(YfSim *s) {
  struct YfOutput *o = s->out;
  if (!o) return;
  long next = LONG_MAX;
  for (int i = 0; i < o->ndump; i++) {
    long e = o->dump[i]->every;
    long k = (s->step / e + 1) * e;
    if (k < next) next = k;
  }
  o->next_due = next;
}

/* ---------------------------------------------------------------- HDF5 */

/* Which rows of a dataset this process writes, [r0, r1) of dims[0].  One writer (./yfdem, or
 * rank 0 of the gather path) writes every row.  Parallel HDF5 (output_mpio): each rank writes the
 * rows of what it owns, so what only owners hold (stresses, node contact forces, joints' damage)
 * is never gathered: triangles by their owner (par_tri_lo), nodes by theirs (par_node_lo),
 * joints and their cracks by the rank of their block (joints_par_rows); replicated arrays follow
 * the same ranges (the write is divided too); scalars are rank 0's. */
enum { ROWS_ONE, ROWS_TRI, ROWS_NODE, ROWS_JOINT, ROWS_CRACK, ROWS_CRACK2, ROWS_N };
static struct {
  int on;              /* this frame is written by every rank                       */
  hsize_t lo[ROWS_N][2];
  hid_t dxpl;          /* collective transfers                                      */
} W = {.dxpl = H5P_DEFAULT};

/* rank r's share of n rows: lo[r]..lo[r+1]-1 when given, else an even split */
static void rows_of(hsize_t *out, const int *lo, long n) {
  int r = par_rank(), S = par_size();
  out[0] = lo ? (hsize_t)lo[r] : (hsize_t)((long long)n * r / S);
  out[1] = lo ? (hsize_t)lo[r + 1] : (hsize_t)((long long)n * (r + 1) / S);
}

/* Create dataset `name` under loc and write its rows `rows` (ROWS_*) of data (memory type = file
 * type; data holds every row, at its row's place). */
static void h5_put_rows(YfDump *d, hid_t loc, const char *name, hid_t type, int rank,
                        const hsize_t *dims, const void *data, int rows) {
  hid_t space = rank ? H5Screate_simple(rank, dims, NULL) : H5Screate(H5S_SCALAR);
  if (space < 0) h5_fail(d, name);
  hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
  /* no modification times in the file: the same run writes the same bytes (a continued run's
   * frames are byte for byte the uninterrupted run's, and can be compared with cmp) */
  H5Pset_obj_track_times(dcpl, 0);
  H5Pset_fill_time(dcpl, H5D_FILL_TIME_NEVER); /* every byte is written right away */
  if (d->compress && rank > 0 && dims[0] > 0) {
    hsize_t chunk[2] = {dims[0] < 65536 ? dims[0] : 65536, rank > 1 ? dims[1] : 1};
    H5Pset_chunk(dcpl, rank, chunk);
    H5Pset_shuffle(dcpl);
    H5Pset_deflate(dcpl, 1); /* level 1: ~2x smaller than raw, 1.5x faster than level 4 */
  }
  hid_t ds = H5Dcreate2(loc, name, type, space, H5P_DEFAULT, dcpl, H5P_DEFAULT);
  if (ds < 0) h5_fail(d, name); /* before any other call: each API call clears the error stack */
  H5Pclose(dcpl);
  static const double none = 0.0; /* HDF5 wants a non-NULL buffer even for 0 elements */
  herr_t st = 0;
  if (W.on && rank > 0 && dims[0] == 0) {
    /* nothing to write (no crack yet): parallel HDF5 refuses a write to storage never allocated */
  } else if (!W.on) {
    st = H5Dwrite(ds, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data ? data : &none);
  } else {
    /* every rank takes part in the collective write, with its rows (maybe none); the memory
     * has the dataset's shape, so the same selection picks this rank's rows in both */
    int whole = rows == ROWS_ONE || rank == 0; /* scalars and small arrays: rank 0 writes them */
    hsize_t r0 = W.lo[rows][0], r1 = W.lo[rows][1];
    if (whole ? par_rank() != 0 : r1 <= r0) {
      H5Sselect_none(space);
    } else if (!whole) {
      hsize_t start[2] = {r0, 0}, count[2] = {r1 - r0, rank > 1 ? dims[1] : 1};
      H5Sselect_hyperslab(space, H5S_SELECT_SET, start, NULL, count, NULL);
    }
    st = H5Dwrite(ds, type, space, space, W.dxpl, data ? data : &none);
  }
  if (st < 0) h5_fail(d, name);
  H5Dclose(ds);
  H5Sclose(space);
}

static void h5_put(YfDump *d, hid_t loc, const char *name, hid_t type, int rank,
                   const hsize_t *dims, const void *data) {
  h5_put_rows(d, loc, name, type, rank, dims, data, ROWS_ONE);
}

/* Create the frame file (as NAME.tmp; h5_frame renames it when it is complete). */
static void h5_open(YfDump *d) {
  yf_h5_quiet();
  hid_t fapl = H5Pcreate(H5P_FILE_ACCESS);
  H5Pset_fclose_degree(fapl, H5F_CLOSE_STRONG); /* closing after an error also closes its objects */
#ifdef YF_MPI
  if (d->mpio) {
    H5Pset_fapl_mpio(fapl, MPI_COMM_WORLD, MPI_INFO_NULL); /* one file, every rank writes */
    H5Pset_coll_metadata_write(fapl, 1); /* the headers go out in one collective write */
    if (W.dxpl == H5P_DEFAULT) {
      W.dxpl = H5Pcreate(H5P_DATASET_XFER);
      H5Pset_dxpl_mpio(W.dxpl, H5FD_MPIO_COLLECTIVE);
    }
  }
#endif
  /* Default (earliest) file format: the widest range of readers, ParaView's bundled HDF5 too. */
  if (yf_writer()) yf_tmp_live(d->cur_tmp); /* a second Ctrl-C removes it */
  d->file = H5Fcreate(d->cur_tmp, H5F_ACC_TRUNC, H5P_DEFAULT, fapl);
  if (d->file < 0) h5_fail(d, "create file"); /* before any other call: it clears the error stack */
  H5Pclose(fapl);
}

/* Error path (output_close_all): close a frame file left open by a failure and remove it; the
 * frames already renamed and indexed are untouched. */
static void h5_close(YfDump *d) {
  if (d->file < 0) return;
  if (!d->mpio) H5Fclose(d->file); /* a parallel file's close would wait for every rank (h5_fail) */
  d->file = -1;
  if (d->cur_tmp) unlink(d->cur_tmp);
  yf_tmp_live(NULL);
}

/* Write the current topology to /mesh of the frame file. */
static void h5_mesh(YfSim *s, YfDump *d) {
  const YfModel *m = &s->model;
  int n = m->node.n, nt = m->tri.n;
  hid_t g = H5Gcreate2(d->file, "mesh", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  if (g < 0) h5_fail(d, "mesh");
  hsize_t dt[2] = {(hsize_t)nt, 3}, d1[1] = {(hsize_t)nt}, dn[1] = {(hsize_t)n};
  hsize_t dn2[2] = {(hsize_t)n, 2};
  h5_put_rows(d, g, "triangles", H5T_NATIVE_INT, 2, dt, m->tri.v, ROWS_TRI);
  h5_put_rows(d, g, "material", H5T_NATIVE_INT, 1, d1, m->tri.mat, ROWS_TRI);
  h5_put_rows(d, g, "body", H5T_NATIVE_INT, 1, d1, m->tri.body, ROWS_TRI);
  h5_put_rows(d, g, "tri_id", H5T_NATIVE_INT, 1, d1, m->tri.id, ROWS_TRI);
  h5_put_rows(d, g, "node_id", H5T_NATIVE_INT, 1, dn, m->node.id, ROWS_NODE);
  double *b = scratch(d, 2 * (size_t)n);
  for (int i = (int)W.lo[ROWS_NODE][0]; i < (int)W.lo[ROWS_NODE][1]; i++) {
    b[2 * i] = m->node.x0[i];
    b[2 * i + 1] = m->node.y0[i];
  }
  h5_put_rows(d, g, "x0", H5T_NATIVE_DOUBLE, 2, dn2, b, ROWS_NODE);
  H5Gclose(g);
}

/* XML-safe copy of a file name (the .xmf refers to the .h5 by name). */
static void xml_escape(char *out, size_t cap, const char *s) {
  size_t k = 0;
  for (; *s && k + 7 < cap; s++) {
    const char *r = NULL;
    switch (*s) {
    case '&': r = "&amp;"; break;
    case '<': r = "&lt;"; break;
    case '>': r = "&gt;"; break;
    case '"': r = "&quot;"; break;
    case '\'': r = "&apos;"; break;
    }
    if (r) {
      size_t l = strlen(r);
      memcpy(out + k, r, l);
      k += l;
    } else {
      out[k++] = *s;
    }
  }
  out[k] = 0;
}

static const char *const stress_parts[3] = {"stress_xx", "stress_yy", "stress_xy"};

static void xmf_item(YfText *t, const char *fname, const char *dims, int is_int, const char *path) {
  grids_printf(t, "          <DataItem Dimensions=\"%s\" NumberType=\"%s\" Precision=\"%d\" "
                  "Format=\"HDF\">%s:%s</DataItem>\n",
               dims, is_int ? "Int" : "Float", is_int ? 4 : 8, fname, path);
}

static void xmf_attr(YfText *t, const char *fname, const char *name, const char *type,
                     const char *center, const char *dims, int is_int, const char *path) {
  grids_printf(t, "        <Attribute Name=\"%s\" AttributeType=\"%s\" Center=\"%s\">\n", name,
               type, center);
  xmf_item(t, fname, dims, is_int, path);
  grids_printf(t, "        </Attribute>\n");
}

/* Append the <Grid> of the frame just written (file d->cur; the .xmf sits in the same
 * directory and names it without the directory, so the pair can be moved together).
 *
 * Why two indexes: ParaView's default XDMF reader (Xdmf3ReaderS, 5.11) merges the grids of a
 * spatial collection into one dataset and keeps only the arrays that every grid has, so frames
 * that held the triangles and the crack segments together drew every field flat grey (and the
 * legacy reader showed frame 0 only).  The triangles are therefore one temporal series of
 * uniform grids (STEM.xmf) and the cracks another (STEM_cracks.xmf, every frame of a scene with
 * joints), each of which colours in any reader.  A frame before the first crack opens lists one
 * zero-length segment with state, mode and damage 0 at the first node (`at`), written inline: the
 * reader crashes (SIGFPE) on a grid without cells, and the frame file's /cracks stays empty.
 * The stress tensor is listed as three named scalars (/stress_xx, /stress_yy, /stress_xy): XDMF's
 * vector would name the parts of /stress X, Y, Z and give a meaningless magnitude, its symmetric
 * tensor is the 3-D Tensor6, and the same parts read as hyperslabs of /stress are skipped by
 * Xdmf3ReaderS ("unrecognized array type"). */
static void xmf_add_frame(YfDump *d, double time, long step, int n, int nt, int with_fc, int ncrack,
                          const double *at) {
  /* a file name is at most 255 bytes, each escaped to at most 6 (1024 cut 230 '&' short) */
  char fname[6 * 256 + 8], p[32], dn2[48], dt3[48], dt1[48];
  const char *base = strrchr(d->cur, '/');
  xml_escape(fname, sizeof fname, base ? base + 1 : d->cur);
  snprintf(dn2, sizeof dn2, "%d 2", n);
  snprintf(dt3, sizeof dt3, "%d 3", nt);
  snprintf(dt1, sizeof dt1, "%d", nt);
  YfText *t = &d->grids;
  grids_printf(t, "      <Grid Name=\"frame_%06ld\" GridType=\"Uniform\">\n", d->nframe);
  grids_printf(t, "        <Time Value=\"%.17g\"/>\n", time);
  grids_printf(t, "        <Information Name=\"step\" Value=\"%ld\"/>\n", step);
  grids_printf(t, "        <Topology TopologyType=\"Triangle\" NumberOfElements=\"%d\" "
                  "NodesPerElement=\"3\">\n", nt);
  xmf_item(t, fname, dt3, 1, "/mesh/triangles");
  grids_printf(t, "        </Topology>\n        <Geometry GeometryType=\"XY\">\n");
  xmf_item(t, fname, dn2, 0, "/x");
  grids_printf(t, "        </Geometry>\n");
  static const struct { unsigned bit; const char *name, *type, *center; int dims; } attrs[] = {
      {YF_FIELD_U, "u", "Vector", "Node", 2},         {YF_FIELD_V, "v", "Vector", "Node", 2},
      {YF_FIELD_F, "f", "Vector", "Node", 2},         {YF_FIELD_VONMISES, "vonmises", "Scalar", "Cell", 1},
      {YF_FIELD_SIGMA1, "sigma1", "Scalar", "Cell", 1}};
  for (size_t i = 0; i < sizeof attrs / sizeof attrs[0]; i++) {
    if (!(d->fields & attrs[i].bit)) continue;
    snprintf(p, sizeof p, "/%s", attrs[i].name);
    xmf_attr(t, fname, attrs[i].name, attrs[i].type, attrs[i].center, attrs[i].dims == 2 ? dn2 : dt1, 0, p);
  }
  for (int c = 0; c < 3 && (d->fields & YF_FIELD_STRESS); c++) {
    snprintf(p, sizeof p, "/%s", stress_parts[c]);
    xmf_attr(t, fname, stress_parts[c], "Scalar", "Cell", dt1, 0, p);
  }
  if (with_fc) xmf_attr(t, fname, "fc", "Vector", "Node", dn2, 0, "/fc");
  if (d->fields & YF_FIELD_MATERIAL) xmf_attr(t, fname, "material", "Scalar", "Cell", dt1, 1, "/mesh/material");
  if (d->fields & YF_FIELD_BODY) xmf_attr(t, fname, "body", "Scalar", "Cell", dt1, 1, "/mesh/body");
  grids_printf(t, "      </Grid>\n");
  if (ncrack < 0) return;
  char dc2[48], dc1[48], dp2[48];
  snprintf(dc2, sizeof dc2, "%d 2", ncrack);
  snprintf(dc1, sizeof dc1, "%d", ncrack);
  snprintf(dp2, sizeof dp2, "%d 2", 2 * ncrack);
  t = &d->cgrids;
  grids_printf(t, "      <Grid Name=\"cracks_%06ld\" GridType=\"Uniform\">\n", d->nframe);
  grids_printf(t, "        <Time Value=\"%.17g\"/>\n", time);
  grids_printf(t, "        <Information Name=\"step\" Value=\"%ld\"/>\n", step);
  if (ncrack == 0) {
    grids_printf(t, "        <Topology TopologyType=\"Polyline\" NumberOfElements=\"1\" NodesPerElement=\"2\">\n"
                    "          <DataItem Dimensions=\"1 2\" NumberType=\"Int\" Format=\"XML\">0 1</DataItem>\n"
                    "        </Topology>\n        <Geometry GeometryType=\"XY\">\n"
                    "          <DataItem Dimensions=\"2 2\" NumberType=\"Float\" Precision=\"8\" Format=\"XML\">"
                    "%.17g %.17g %.17g %.17g</DataItem>\n        </Geometry>\n", at[0], at[1], at[0], at[1]);
    static const char *const cn[3] = {"crack_state", "crack_mode", "damage"};
    for (int c = 0; c < 3; c++)
      grids_printf(t, "        <Attribute Name=\"%s\" AttributeType=\"Scalar\" Center=\"Cell\">\n"
                      "          <DataItem Dimensions=\"1\" NumberType=\"%s\" Format=\"XML\">0</DataItem>\n"
                      "        </Attribute>\n", cn[c], c < 2 ? "Int" : "Float");
    grids_printf(t, "      </Grid>\n");
    return;
  }
  grids_printf(t, "        <Topology TopologyType=\"Polyline\" NumberOfElements=\"%d\" NodesPerElement=\"2\">\n",
               ncrack);
  xmf_item(t, fname, dc2, 1, "/cracks/segments");
  grids_printf(t, "        </Topology>\n        <Geometry GeometryType=\"XY\">\n");
  xmf_item(t, fname, dp2, 0, "/cracks/xy");
  grids_printf(t, "        </Geometry>\n");
  xmf_attr(t, fname, "crack_state", "Scalar", "Cell", dc1, 1, "/cracks/state");
  xmf_attr(t, fname, "crack_mode", "Scalar", "Cell", dc1, 1, "/cracks/mode");
  xmf_attr(t, fname, "damage", "Scalar", "Cell", dc1, 0, "/cracks/damage");
  grids_printf(t, "      </Grid>\n");
}

/* Replace STEM.xmf atomically: a reader (or a killed run) sees the old or the new index.  Not
 * fsync'ed: the frame files it names are not either (see the file comment, Durability).
 *
 * Why fallocate: ext4 (auto_da_alloc, on by default) starts writeback of a file's delayed-
 * allocation blocks when a rename replaces another file, so that the replacement survives a
 * crash; that made each index rename cost ~2 ms on this project's machines, more than the frame
 * itself (1e4 triangles).  Blocks reserved with fallocate before the write are not delayed, so
 * the rename finds nothing to flush (index: 9 ms -> 1.5 ms per 50 frames, measured).  Where
 * fallocate is not supported it is simply skipped. */
static int index_try(YfDump *d, const char *path, const char *tmp, const char *suffix, const YfText *t,
                     char *msg, size_t nmsg) {
  char name[YF_NAME_MAX * 6 + 1];
  xml_escape(name, sizeof name, d->id);
  char head[YF_NAME_MAX * 6 + 256];
  static const char tail[] = "    </Grid>\n  </Domain>\n</Xdmf>\n";
  int hl = snprintf(head, sizeof head,
                    "<?xml version=\"1.0\" ?>\n<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n"
                    "<Xdmf Version=\"3.0\">\n  <Domain>\n"
                    "    <Grid Name=\"%s%s\" GridType=\"Collection\" CollectionType=\"Temporal\">\n",
                    name, suffix);
  const char *part[3] = {head, t->s ? t->s : "", tail};
  size_t plen[3] = {(size_t)hl, t->len, sizeof tail - 1};
  yf_tmp_live(tmp); /* a second Ctrl-C removes it: live before open creates it (no window) */
  int fd = open(tmp, O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
  if (fd < 0) {
    yf_tmp_live(NULL);
    snprintf(msg, nmsg, "dump %s: cannot create '%s': %s", d->id, tmp, yf_strerror(errno));
    return -1;
  }
#ifdef __linux__
  (void)fallocate(fd, 0, 0, (off_t)(plen[0] + plen[1] + plen[2])); /* an optimisation only */
#endif
  int err = 0;
  for (int i = 0; i < 3 && !err; i++)
    for (size_t done = 0; done < plen[i] && !err;) {
      ssize_t w = write(fd, part[i] + done, plen[i] - done);
      if (w > 0) done += (size_t)w;
      else if (w < 0 && errno == EINTR) continue;
      else err = w < 0 ? errno : EIO;
    }
  if (close(fd) != 0 && !err) err = errno;
  if (err) {
    unlink(tmp);
    yf_tmp_live(NULL);
    snprintf(msg, nmsg, "dump %s: cannot write '%s': %s", d->id, tmp, strerror(err));
    return -1;
  }
  int rc = rename(tmp, path);
  yf_tmp_live(NULL);
  if (rc != 0) { /* (a directory or an immutable file in the way): no NAME.tmp left behind */
    int e = errno;
    unlink(tmp);
    snprintf(msg, nmsg, "dump %s: cannot rename '%s' to '%s': %s", d->id, tmp, path, yf_strerror(e));
    return -1;
  }
  return 0;
}

/* Both indexes of a dump: the crack series first, so that a run killed in between leaves a mesh
 * index that lists no frame the crack index lacks. */
static int xmf_try(YfDump *d, char *msg, size_t nmsg) {
  if (d->cgrids.len && index_try(d, d->cxmf, d->cxmf_tmp, " cracks", &d->cgrids, msg, nmsg)) return -1;
  if (index_try(d, d->xmf, d->xmf_tmp, "", &d->grids, msg, nmsg)) return -1;
  d->xmf_pending = 0;
  d->xmf_writes++;
  return 0;
}

/* The index after a frame.  Rewriting it costs in proportion to the frames it lists (about
 * 2.2 KB each), so with frequent frames and a long series that cost would grow without bound
 * (4000 frames of a 2000-triangle bar: 10.8 s of index for 0.14 s of run).  An index of up to
 * XMF_SMALL bytes (about 450 frames, under a millisecond to write) is rewritten at every frame;
 * a larger one only when the time since its last rewrite is at least XMF_GAP times what that
 * rewrite took, so at most about 1/XMF_GAP of the run goes to it and it lags the newest frames
 * by a fraction of a second (20 rewrites' time: 0.3 s at 1e4 frames).  The end of a run, an
 * interrupt, an error and the exit write it (xmf_flush): a run that ends in any of these ways
 * lists every frame; SIGKILL may leave the newest frames of a long series unlisted. */
static double xmf_gap = 20.0;              /* XMF_GAP */
static size_t xmf_small = (size_t)1 << 20; /* XMF_SMALL [bytes] */
void output_set_index_policy(size_t small_bytes, double gap) {
  xmf_small = small_bytes;
  xmf_gap = gap;
}
static void xmf_write(YfDump *d) {
  double t0 = yf_now();
  if (d->grids.len + d->cgrids.len > xmf_small && d->xmf_cost > 0.0 && t0 - d->xmf_done < xmf_gap * d->xmf_cost) {
    d->xmf_pending = 1;
    return;
  }
  char msg[3 * PATH_MAX];
  if (xmf_try(d, msg, sizeof msg)) yf_io_error(NULL, "%s", msg);
  d->xmf_done = yf_now();
  d->xmf_cost = d->xmf_done - t0;
}

/* Write the index if frames are waiting for it.  On the way out (output_close_all) a failure is
 * reported and the exit code made 2, after another error that error keeps its message and
 * code (yf_output_error). */
static void xmf_flush(YfDump *d) {
  if (!d->xmf_pending) return;
  char msg[3 * PATH_MAX];
  if (!xmf_try(d, msg, sizeof msg)) return;
  d->xmf_pending = 0; /* reported once */
  yf_output_error("%s", msg);
}

/* Cracks of a fracturing scene: every joint past its peak (opened: softening, still cohesive) or
 * broken, as a 2-point segment from the middle of its end a node pair to the middle of its end b
 * pair (current positions), with state (1 opened, 2 broken), mode (1 I, 2 II, 3 mixed: YF_JMODE_*) and the
 * largest damage z of the last evaluation; plus the damage of every joint (/joint_damage).
 * Returns the number of crack segments: 0 (empty datasets) before the first crack opens, -1 in a
 * scene without joints (no /cracks group). */
static int h5_cracks(YfSim *s, YfDump *d) {
  const YfJoints *j = s->joints;
  if (!j || j->n == 0) return -1;
  const YfNodes *nd = &s->model.node;
  hsize_t dj[1] = {(hsize_t)j->n};
  h5_put_rows(d, d->file, "joint_damage", H5T_NATIVE_DOUBLE, 1, dj, j->z, ROWS_JOINT);
  /* the crack rows of this rank's joints (state and openings are on every rank, damage on the
   * joint's owner): cracks c0..c1-1 */
  int nc = 0, c0 = 0, c1 = 0;
  for (int k = 0; k < j->n; k++) {
    if (k == (int)W.lo[ROWS_JOINT][0]) c0 = nc;
    if (k == (int)W.lo[ROWS_JOINT][1]) c1 = nc;
    nc += j->state[k] == 2 || (j->opened && j->opened[k]);
  }
  if ((int)W.lo[ROWS_JOINT][1] >= j->n) c1 = nc;
  if ((int)W.lo[ROWS_JOINT][0] >= j->n) c0 = nc;
  W.lo[ROWS_CRACK][0] = (hsize_t)c0;
  W.lo[ROWS_CRACK][1] = (hsize_t)c1;
  W.lo[ROWS_CRACK2][0] = 2 * (hsize_t)c0;
  W.lo[ROWS_CRACK2][1] = 2 * (hsize_t)c1;
  double *xy = yf_malloc((size_t)nc * 4 * sizeof(double), "crack output");
  double *dmg = yf_malloc((size_t)nc * sizeof(double), "crack output");
  int *iv = yf_malloc((size_t)nc * 4 * sizeof(int), "crack output"); /* segments (2), state, mode */
  int *state = iv + 2 * nc, *mode = iv + 3 * nc, c = 0;
  for (int k = 0; k < j->n; k++) {
    int broken = j->state[k] == 2, opened = j->opened && j->opened[k];
    if (!broken && !opened) continue;
    const int *q = j->node + 4 * k;
    xy[4 * c] = 0.5 * (nd->x[q[0]] + nd->x[q[3]]);
    xy[4 * c + 1] = 0.5 * (nd->y[q[0]] + nd->y[q[3]]);
    xy[4 * c + 2] = 0.5 * (nd->x[q[1]] + nd->x[q[2]]);
    xy[4 * c + 3] = 0.5 * (nd->y[q[1]] + nd->y[q[2]]);
    iv[2 * c] = 2 * c;
    iv[2 * c + 1] = 2 * c + 1;
    state[c] = broken ? 2 : 1;
    mode[c] = broken ? j->mode[k] : (j->opened[k] & 0x7f);
    dmg[c] = broken ? 1.0 : j->z[k];
    c++;
  }
  hid_t g = H5Gcreate2(d->file, "cracks", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  if (g < 0) h5_fail(d, "cracks");
  hsize_t d2[2] = {(hsize_t)nc, 2}, dp[2] = {(hsize_t)(2 * nc), 2}, d1[1] = {(hsize_t)nc};
  h5_put_rows(d, g, "segments", H5T_NATIVE_INT, 2, d2, iv, ROWS_CRACK);
  h5_put_rows(d, g, "xy", H5T_NATIVE_DOUBLE, 2, dp, xy, ROWS_CRACK2);
  h5_put_rows(d, g, "state", H5T_NATIVE_INT, 1, d1, state, ROWS_CRACK);
  h5_put_rows(d, g, "mode", H5T_NATIVE_INT, 1, d1, mode, ROWS_CRACK);
  h5_put_rows(d, g, "damage", H5T_NATIVE_DOUBLE, 1, d1, dmg, ROWS_CRACK);
  H5Gclose(g);
  free(xy);
  free(dmg);
  free(iv);
  return nc;
}

/* This frame's rows per process (see h5_put_rows): all of them for one writer. */
static void frame_rows(YfSim *s, YfDump *d) {
  const YfModel *m = &s->model;
  long nj = s->joints ? s->joints->n : 0;
  W.on = d->mpio;
  memset(W.lo, 0, sizeof W.lo);
  if (!W.on) {
    W.lo[ROWS_TRI][1] = (hsize_t)m->tri.n;
    W.lo[ROWS_NODE][1] = (hsize_t)m->node.n;
    W.lo[ROWS_JOINT][1] = (hsize_t)nj;
    return;
  }
  rows_of(W.lo[ROWS_TRI], par_tri_lo(), m->tri.n);
  rows_of(W.lo[ROWS_NODE], par_node_lo(), m->node.n);
  int *jl = yf_malloc(((size_t)par_size() + 1) * sizeof(int), "joint rows");
  rows_of(W.lo[ROWS_JOINT], joints_par_rows(s, jl) ? jl : NULL, nj);
  free(jl);
}

static void h5_frame(YfSim *s, YfDump *d) {
  const YfModel *m = &s->model;
  const YfNodes *nd = &m->node;
  int n = nd->n, nt = m->tri.n;
  frame_rows(s, d);
  if (d->mpio) run_check_nodes(s, (int)W.lo[ROWS_NODE][0], (int)W.lo[ROWS_NODE][1]); /* the rows this rank writes */
  /* parallel: every rank opens the file rank 0 names (rank 0 alone adopted an earlier series) */
  if (d->mpio) d->nframe = par_bcast_long(d->nframe);
  snprintf(d->cur, d->curcap, "%s_%06ld%s", d->stem, d->nframe, d->ext);
  snprintf(d->cur_tmp, d->curcap, "%s.tmp", d->cur);
  h5_open(d);
  h5_mesh(s, d);
  hid_t g = d->file; /* the frame's arrays are at the root */
  long long step = s->step;
  h5_put(d, g, "time", H5T_NATIVE_DOUBLE, 0, NULL, &s->time);
  h5_put(d, g, "step", H5T_NATIVE_LLONG, 0, NULL, &step);

  hsize_t dn2[2] = {(hsize_t)n, 2}, dt3[2] = {(hsize_t)nt, 3}, dt1[1] = {(hsize_t)nt};
  size_t need = 2 * (size_t)n > (size_t)nt ? 2 * (size_t)n : (size_t)nt;
  double *b = scratch(d, need);
  /* this process's rows: nodes n0..n1-1, triangles e0..e1-1 */
  const int n0 = (int)W.lo[ROWS_NODE][0], n1 = (int)W.lo[ROWS_NODE][1];
  const int e0 = (int)W.lo[ROWS_TRI][0], e1 = (int)W.lo[ROWS_TRI][1];
  for (int i = n0; i < n1; i++) {
    b[2 * i] = nd->x[i];
    b[2 * i + 1] = nd->y[i];
  }
  h5_put_rows(d, g, "x", H5T_NATIVE_DOUBLE, 2, dn2, b, ROWS_NODE);
  if (d->fields & YF_FIELD_U) {
    for (int i = n0; i < n1; i++) {
      b[2 * i] = nd->x[i] - nd->x0[i];
      b[2 * i + 1] = nd->y[i] - nd->y0[i];
    }
    h5_put_rows(d, g, "u", H5T_NATIVE_DOUBLE, 2, dn2, b, ROWS_NODE);
  }
  if (d->fields & YF_FIELD_V) {
    for (int i = n0; i < n1; i++) {
      b[2 * i] = nd->vx[i];
      b[2 * i + 1] = nd->vy[i];
    }
    h5_put_rows(d, g, "v", H5T_NATIVE_DOUBLE, 2, dn2, b, ROWS_NODE);
  }
  if (d->fields & YF_FIELD_F) {
    for (int i = n0; i < n1; i++) {
      b[2 * i] = nd->fx[i];
      b[2 * i + 1] = nd->fy[i];
    }
    h5_put_rows(d, g, "f", H5T_NATIVE_DOUBLE, 2, dn2, b, ROWS_NODE);
  }
  const double *sg = m->tri.s; /* sxx, syy, sxy per triangle, already the file layout */
  if (d->fields & YF_FIELD_STRESS) {
    h5_put_rows(d, g, "stress", H5T_NATIVE_DOUBLE, 2, dt3, sg, ROWS_TRI);
    for (int c = 0; c < 3; c++) { /* the parts by name, for ParaView (see xmf_add_frame) */
      for (int e = e0; e < e1; e++) b[e] = sg[3 * e + c];
      h5_put_rows(d, g, stress_parts[c], H5T_NATIVE_DOUBLE, 1, dt1, b, ROWS_TRI);
    }
  }
  if (d->fields & YF_FIELD_VONMISES) {
    /* In-plane von Mises (szz taken as 0): sqrt(sxx^2 - sxx syy + syy^2 + 3 sxy^2). */
    for (int e = e0; e < e1; e++) {
      double a = sg[3 * e], c = sg[3 * e + 1], t = sg[3 * e + 2];
      b[e] = sqrt(a * a - a * c + c * c + 3.0 * t * t);
    }
    h5_put_rows(d, g, "vonmises", H5T_NATIVE_DOUBLE, 1, dt1, b, ROWS_TRI);
  }
  if (d->fields & YF_FIELD_SIGMA1) {
    for (int e = e0; e < e1; e++) {
      double a = sg[3 * e], c = sg[3 * e + 1], t = sg[3 * e + 2];
      double h = 0.5 * (a - c);
      b[e] = 0.5 * (a + c) + sqrt(h * h + t * t);
    }
    h5_put_rows(d, g, "sigma1", H5T_NATIVE_DOUBLE, 1, dt1, b, ROWS_TRI);
  }
  /* contact force per node: while contact is on (else the field would be all zeros), and zeros
   * once a frame of the series had it, or when the deck's `fields` asked for it: ParaView colours
   * a series only by a field every frame has (contact off after a run dropped fc from the rest,
   * and 'fields fc' without contact wrote nothing) */
  const double *fc = (d->fields & YF_FIELD_FC) ? contact_node_forces(s) : NULL;
  if (!fc && (d->fields & YF_FIELD_FC) && (d->had_fc || d->fc_asked)) {
    double *z = scratch(d, 2 * (size_t)n);
    memset(z, 0, 2 * (size_t)n * sizeof *z);
    fc = z;
  }
  if (fc && !d->had_fc && d->nframe > 0) /* contact given after the series began (it is not known before) */
    yf_warn(NULL, "dump %s: the contact force fc begins at frame %ld (step %ld): the frames before have none, and "
            "ParaView colours the series by fc only from here; 'dump ... fields ... fc' writes it (zeros) from the "
            "first frame", d->id, d->nframe, s->step);
  if (fc) d->had_fc = 1;
  if (fc) h5_put_rows(d, g, "fc", H5T_NATIVE_DOUBLE, 2, dn2, fc, ROWS_NODE);
  int ncrack = h5_cracks(s, d);
  /* Complete and closed, then renamed, then indexed: the .xmf never names a partial file. */
  /* Parallel: a rank whose part failed leaves at once (h5_fail: a collective after a failed one
   * could wait forever), and the job ends with its message (par_mpi.c); that every rank's part
   * reached the file rests on the MPI-IO layer reporting a failed write, which OpenMPI's ROMIO
   * does and its default ompio did not (par_init). */
  herr_t st = H5Fclose(d->file);
  d->file = -1;
  W.on = 0;
  if (st < 0) {
    unlink(d->cur_tmp);
    h5_fail(d, "close");
  }
  if (!yf_writer()) return; /* parallel: rank 0 renames and indexes */
  /* A frame file of an earlier run with this name is listed by no index any more (this run's
   * index was rewritten at its first frame), so it is removed first: ext4 flushes a file that
   * replaces another by rename (see xmf_write), ~3 ms per frame when a deck is run again in the
   * same directory.  The first frame of this process (0, or the first after the frames of a
   * continued series) keeps the atomic replace: the earlier run's index still lists it. */
  if (d->nframe > d->first) unlink(d->cur);
  if (rename(d->cur_tmp, d->cur) != 0) { /* (a directory or an immutable file in the way) */
    int e = errno;
    unlink(d->cur_tmp); /* no NAME.tmp left behind (README) */
    yf_io_error(NULL, "dump %s: cannot rename '%s' to '%s': %s", d->id, d->cur_tmp, d->cur, yf_strerror(e));
  }
  yf_tmp_live(NULL);
  const double at[2] = {n ? nd->x[0] : 0.0, n ? nd->y[0] : 0.0};
  xmf_add_frame(d, s->time, s->step, n, nt, fc != NULL, ncrack, at);
  xmf_write(d);
}

/* ---------------------------------------------------------------- CSV */

static void csv_frame(YfSim *s, YfDump *d) {
  const YfNodes *nd = &s->model.node;
  char *path = str_printf("%s_%06ld.csv", d->path, d->nframe);
  if (d->csv_index.fd < 0) {
    char *ip = str_printf("%s_frames.csv", d->path);
    if (yf_rows_open(&d->csv_index, ip, d->created) != 0)
      yf_io_error(NULL, "dump %s: cannot create '%s': %s", d->id, ip, yf_strerror(errno));
    if (!d->created) {
      yf_rows_printf(&d->csv_index, "frame,step,time,file\n");
      if (yf_rows_end(&d->csv_index) != 0) {
        /* not even its header: no index rather than an empty one */
        int e = errno;
        if (d->csv_index.end >= 0) unlink(ip);
        errno = e;
        yf_io_error(NULL, "dump %s: cannot write '%s': %s", d->id, ip, yf_strerror(errno));
      }
    }
    d->created = 1;
    free(ip);
  }
  /* whole or not at all (PATH.tmp renamed, wfile.h), as h5 frames: on a full disk a frame cut
   * mid-row was left under its own name */
  YfWFile w;
  if (yf_wfile_open(&w, path) != 0) yf_io_error(NULL, "dump %s: cannot create '%s': %s", d->id, path, yf_strerror(errno));
  FILE *f = w.f;
  fprintf(f, "id,x,y,ux,uy,vx,vy\n");
  for (int i = 0; i < nd->n; i++)
    fprintf(f, "%d,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n", nd->id[i], nd->x[i], nd->y[i],
            nd->x[i] - nd->x0[i], nd->y[i] - nd->y0[i], nd->vx[i], nd->vy[i]);
  if (yf_wfile_close(&w, 0, 0) != 0) yf_io_error(NULL, "dump %s: cannot write '%s': %s", d->id, path, yf_strerror(errno));
  const char *base = strrchr(path, '/');
  /* whole or not at all: on a full disk the index ends at the row before */
  char *field = yf_csv_field(base ? base + 1 : path); /* a PREFIX with a comma: still one field */
  /* a frame written again (frame_retract) keeps its row: the same frame, step, time and file */
  if (!d->rewrite) yf_rows_printf(&d->csv_index, "%ld,%ld,%.17g,%s\n", d->nframe, s->step, s->time, field);
  free(field);
  if (!d->rewrite && yf_rows_end(&d->csv_index) != 0)
    yf_io_error(NULL, "dump %s: cannot write '%s_frames.csv': %s", d->id, d->path, yf_strerror(errno));
  free(path);
}

/* ---------------------------------------------------------------- continuing after a restart */

/* A run continued from a restart (read_restart) continues each dump's series instead of starting
 * it again at frame 0, which would overwrite the frames of the run it continues: at the dump's
 * first frame, the index the earlier run left (STEM.xmf or PREFIX_frames.csv) keeps its frames of
 * steps before the current one, numbered 0, 1, ... in order, and the new frames follow.  Frames of
 * the earlier run at or after this step (written before it was stopped) leave the index; their
 * files are overwritten as the new frames reach their numbers.  An index that is missing, or not
 * one yfdem wrote, starts a new series.  A restart written between runs (s->restored_between)
 * keeps the frame of its own step too: the earlier run wrote it as the uninterrupted deck did
 * (due on its last step, or at its next run's start), and an interrupt between runs writes none. */

/* The first step whose frames a continued run writes again (a dump on the file of one undumped
 * is a new dump: it writes its own frame of this step). */
static long adopt_before(const YfSim *s, const YfDump *d) { return s->restored_between && !d->again ? s->step + 1 : s->step; }

/* An index (STEM.xmf, grids named frame_K, or STEM_cracks.xmf, cracks_K): the frames of the earlier
 * run with step < before become this series' first frames, copied to out; *last: the step of the
 * last one (LONG_MIN: none). */
static long index_adopt(const char *path, const char *frame_tag, long before, YfText *out, long *last) {
  size_t len;
  char *t = yf_read_output(path, &len, "index text");
  if (!t) return 0;
  static const char open_tag[] = "CollectionType=\"Temporal\">\n", close_tag[] = "    </Grid>\n  </Domain>",
                    step_tag[] = "<Information Name=\"step\" Value=\"";
  const size_t ftl = strlen(frame_tag);
  char *a = strstr(t, open_tag), *z = NULL;
  for (char *q = a; q && (q = strstr(q, close_tag)); q++) z = q;
  long kept = 0;
  if (a && z && z > a) {
    a += sizeof open_tag - 1;
    /* a frame runs from the first line that names frame_K to the first line naming another K */
    char *keep_end = a, *p = a;
    long cur = -1;
    while (p < z) {
      char *g = strstr(p, frame_tag);
      char *next = g && g < z ? g : z;
      long k = next < z ? strtol(next + ftl, NULL, 10) : -1;
      if (next < z && k == cur) { /* the Uniform grid of a Collection frame: same frame */
        p = next + 1;
        continue;
      }
      if (cur >= 0) { /* frame cur runs from keep_end to the start of next's line */
        char *end = next;
        while (end > keep_end && end[-1] != '\n') end--;
        char *st = strstr(keep_end, step_tag);
        long step = st && st < end ? strtol(st + sizeof step_tag - 1, NULL, 10) : LONG_MAX;
        if (cur != kept || step >= before) break;
        kept++;
        keep_end = end;
        if (last) *last = step;
      }
      if (next >= z) break;
      cur = k;
      p = next + 1;
    }
    if (kept) grids_printf(out, "%.*s", (int)(keep_end - a), a);
  }
  free(t);
  return kept;
}

/* The fields of the last frame adopted from an earlier run's index (the Attribute names of
 * d->grids' last Grid), against this dump's: a run continued by read_restart whose dump asks for
 * other fields gives a series ParaView colours only by the fields every frame has (as a dump on
 * the file of one undumped: cmd_dump warns of that), so it is said; an earlier fc stays in the
 * series (zeros while contact is off). */
static void adopted_fields(YfDump *d) {
  const char *last = NULL, *t = d->grids.s;
  for (const char *q = t; (q = strstr(q, "<Grid Name=\"frame_")); q++) last = q;
  if (!last) return;
  unsigned had = 0;
  static const char tag[] = "<Attribute Name=\"";
  for (const char *q = last; (q = strstr(q, tag)); q++) {
    const char *nm = q + sizeof tag - 1, *e = strchr(nm, '"');
    if (!e) break;
    size_t l = (size_t)(e - nm);
    for (int k = 0; output_field_names[k] && k < 9; k++) {
      size_t kl = strlen(output_field_names[k]);
      /* the stress is written as stress_xx, stress_yy, stress_xy */
      if ((l == kl || (k == 3 && l == kl + 3)) && !strncmp(nm, output_field_names[k], kl)) had |= 1u << k;
    }
  }
  if (had & YF_FIELD_FC) d->had_fc = 1;
  unsigned want = d->fields & (YF_FIELD_ALL & ~(unsigned)YF_FIELD_FC);
  if ((had & ~(unsigned)YF_FIELD_FC) != want)
    yf_warn(NULL, "dump %s: it continues the series in %s, whose frames hold other fields than this dump's; ParaView "
            "colours a series only by the fields every frame has: give this dump the earlier fields, or write "
            "to another file", d->id, d->xmf);
}

/* The mesh index and, when the earlier run wrote one, the crack index: a crack index that does
 * not match the mesh index frame for frame is started again. */
static long h5_adopt(YfDump *d, long before, long *last) {
  long kept = index_adopt(d->xmf, "<Grid Name=\"frame_", before, &d->grids, last);
  if (kept && index_adopt(d->cxmf, "<Grid Name=\"cracks_", before, &d->cgrids, NULL) != kept) d->cgrids.len = 0;
  if (kept) adopted_fields(d);
  /* The index is rewritten now with the frames kept, as csv_adopt rewrites its own: a continued
   * run that writes no frame (it ends before the next is due) left listed the earlier run's frames
   * from the restart step on (an interrupt's own, or those past its last restart).  Rank 0 alone
   * writes indexes (h5_frame). */
  if (kept && yf_writer()) xmf_write(d);
  return kept;
}

/* PREFIX_frames.csv: its rows of frames with step < before stay, and the index is rewritten. */
static long csv_adopt(YfDump *d, long before, long *last) {
  char *ip = str_printf("%s_frames.csv", d->path);
  size_t len;
  char *t = yf_read_output(ip, &len, "index text");
  long kept = 0;
  char *keep_end = NULL;
  static const char head[] = "frame,step,time,file\n";
  if (t && !strncmp(t, head, sizeof head - 1)) {
    char *p = t + sizeof head - 1;
    for (char *nl; (nl = strchr(p, '\n')); p = nl + 1) {
      char *e;
      long k = strtol(p, &e, 10), step = *e == ',' ? strtol(e + 1, NULL, 10) : LONG_MAX;
      if (k != kept || step >= before) break;
      kept++;
      keep_end = nl + 1;
      *last = step;
    }
  }
  if (kept) {
    /* the kept rows go in whole (PATH.tmp renamed, wfile.h): a full disk leaves the earlier index,
     * not one cut short; the new rows are appended (csv_frame) */
    YfWFile w;
    if (yf_wfile_open(&w, ip) != 0) yf_io_error(NULL, "dump %s: cannot create '%s': %s", d->id, ip, yf_strerror(errno));
    fwrite(t, 1, (size_t)(keep_end - t), w.f);
    if (yf_wfile_close(&w, 0, 0) != 0) yf_io_error(NULL, "dump %s: cannot write '%s': %s", d->id, ip, yf_strerror(errno));
    if (yf_rows_open(&d->csv_index, ip, 1) != 0)
      yf_io_error(NULL, "dump %s: cannot create '%s': %s", d->id, ip, yf_strerror(errno));
    d->created = 1;
  }
  free(t);
  free(ip);
  return kept;
}

/* Returns the step of the last frame kept (LONG_MIN: none). */
static long dump_adopt(YfSim *s, YfDump *d) {
  const long before = adopt_before(s, d);
  const char *upto = before > s->step ? "up to" : "before";
  if (d->style == YF_DUMP_Y2DREF) { /* its growing tables, as the series of the other styles */
    if (!y2dref_continue(s, d->y2d, before)) return LONG_MIN;
    sim_printf(s, "dump %s: continuing the tables of the earlier run in %s: their rows %s step %ld kept\n",
               d->id, d->path, upto, s->step);
    return before - 1; /* (its frames are every step's: the earlier run wrote the last one kept) */
  }
  long last = LONG_MIN;
  long kept = d->style == YF_DUMP_H5 ? h5_adopt(d, before, &last) : d->style == YF_DUMP_CSV ? csv_adopt(d, before, &last) : 0;
  if (!kept) return LONG_MIN;
  d->nframe = d->first = kept;
  sim_printf(s, "dump %s: continuing the series of the earlier %s: its %ld frame%s %s step %ld kept, "
             "the next is frame %ld\n", d->id, d->again ? "dump on this file" : "run", kept, kept == 1 ? "" : "s",
             upto, s->step, kept);
  return last;
}

/* ---------------------------------------------------------------- frames */

/* The first frame of a dump in a run continued by read_restart, or of a dump on the file of one
 * undumped earlier: the series it continues is adopted (once, at the step it begins). */
static int continuing(const YfSim *s, const YfDump *d) {
  return (s->restored || d->again) && !d->adopted && d->nframe == 0 && d->last_step == LONG_MIN;
}

static void write_frame(YfSim *s, YfDump *d) {
  /* MPI: every rank is here, in the same order (a collective).  A parallel h5 frame is written
   * by every rank from what it owns; otherwise what owners hold is gathered for rank 0. */
  if (!d->mpio) par_need_all(s);
  /* no frame holds a non-finite number: the failure is said now (a NaN load wrote and listed the
   * frame of its step before the next step's element check stopped the run) */
  if (!d->mpio) run_check_nodes(s, 0, s->model.node.n);
  if (!yf_writer() && !d->mpio) { /* an MPI rank other than 0: the same bookkeeping, no file */
    d->nframe++;
    d->last_step = s->step;
    d->rewrite = 0;
    return;
  }
  if (continuing(s, d)) {
    d->adopted = 1;
    dump_adopt(s, d);
  }
  if (d->style == YF_DUMP_Y2DREF) y2dref_frame(s, d->y2d);
  else if (d->style == YF_DUMP_H5) h5_frame(s, d);
  else csv_frame(s, d);
  d->nframe++;
  d->last_step = s->step;
  d->rewrite = 0;
}

/* The last frame's entries leave the indexes' text (its file is written again under its number):
 * the frame of the step a run ended on, when the deck changed the scene before the next run.  A
 * csv index keeps its row, which names the same frame (csv_frame). */
static void frame_retract(YfDump *d) {
  static const char *const tag[2] = {"      <Grid Name=\"frame_", "      <Grid Name=\"cracks_"};
  YfText *t[2] = {&d->grids, &d->cgrids};
  const int had_cracks = d->cgrids.len > 0;
  for (int k = 0; k < 2; k++) {
    if (!t[k]->len) continue; /* (an MPI rank other than 0 keeps no index text) */
    const char *last = NULL;
    for (const char *q = t[k]->s; (q = strstr(q, tag[k])); q++) last = q;
    if (last) t[k]->len = (size_t)(last - t[k]->s), t[k]->s[t[k]->len] = 0;
  }
  d->nframe--;
  d->rewrite = 1;
  /* The indexes leave the frame before its file is replaced (rank 0 writes them): a run killed
   * in between lists no frame whose file differs from its entry (README: every frame an index
   * lists is complete).  An index left with no frame lists none for that moment. */
  if (d->style != YF_DUMP_H5 || !yf_writer()) return;
  char msg[3 * PATH_MAX];
  if ((had_cracks && !d->cgrids.len && index_try(d, d->cxmf, d->cxmf_tmp, " cracks", &d->cgrids, msg, sizeof msg)) ||
      xmf_try(d, msg, sizeof msg))
    yf_io_error(NULL, "%s", msg);
}

/* A run begins on the step of the dump's last frame (written when the run before ended there, or
 * kept from the series a restart continues): the frame stays unless the deck changed the scene
 * since (a body added, a `velocity ... set`), in which case it is written again, so that the frame
 * of the run's first step shows the state the run starts from, as it does when no frame was due
 * on it (the thermo line of that step is the new state's).  h5 and csv (a
 * y2dref dump's tables take their rows for good: it runs a Y2D deck's single run). */
static int scene_changed(const YfSim *s, const YfDump *d, int restored) {
  if (d->style == YF_DUMP_Y2DREF || d->last_step != s->step) return 0;
  if (restored) return restart_scene_changed(s);
  return d->end_step == s->step && sim_state_hash(s) != d->end_key;
}

void output_run_begin(YfSim *s) {
  struct YfOutput *o = s->out;
  if (!o) return;
  for (int i = 0; i < o->ndump; i++) {
    YfDump *d = o->dump[i];
    if (d->last_step == s->step) {
      if (scene_changed(s, d, 0)) {
        frame_retract(d);
        write_frame(s, d);
      }
      continue;
    }
    /* A restart written between runs: the uninterrupted deck's next run began with a frame unless
     * the dump had one of this step already (due on the last step of the run before), and the
     * earlier run's index then holds it (an interrupt between runs writes none).  The series is
     * adopted with that frame, and the run writes one only if there was none (the stresses are
     * recomputed for it, as the uninterrupted deck's were: restart.c). */
    if (continuing(s, d) && !d->again && s->restored_between) {
      d->adopted = 1;
      long at = LONG_MIN;
      if (yf_writer() || d->mpio) at = dump_adopt(s, d);
      /* MPI: rank 0 alone read a gathered dump's index; every rank writes the frame or none */
      at = par_bcast_long(at);
      if (at == s->step) {
        d->last_step = s->step;
        if (!scene_changed(s, d, 1)) continue;
        frame_retract(d);
      }
      write_frame(s, d);
      continue;
    }
    /* A run continued from a restart written within a run writes the frames the uninterrupted run
     * wrote: none at a step no dump is due on (an interrupt at step 997 with frames every 500), but
     * its series is adopted now, at the step it continues from (frames of the earlier run from this
     * step on, such as the interrupt's own, leave the index). */
    if (continuing(s, d) && !d->again && s->step % d->every != 0) { /* (a dump again is new: it writes) */
      d->adopted = 1;
      /* MPI: the writer alone adopts, as in write_frame (a csv index is rewritten: the other ranks
       * truncated it while rank 0 read it, and the series began again at frame 0) */
      if (yf_writer() || d->mpio) dump_adopt(s, d);
      continue;
    }
    write_frame(s, d);
  }
  update_next_due(s);
}

void output_step(YfSim *s) {
  struct YfOutput *o = s->out;
  if (!o || s->step < o->next_due) return;
  for (int i = 0; i < o->ndump; i++) {
    YfDump *d = o->dump[i];
    if (s->step % d->every == 0 && d->last_step != s->step) write_frame(s, d);
  }
  update_next_due(s);
}

void output_run_end(YfSim *s) {
  /* Every frame is closed as it is written; an index whose rewrite was put off (xmf_write) is
   * written now (csv indexes stay open for the next run; output_close_all closes them). */
  struct YfOutput *o = s->out;
  if (!o) return;
  for (int i = 0; i < o->ndump; i++) {
    YfDump *d = o->dump[i];
    xmf_flush(d);
    /* the state the run ended in, for the next run's start (scene_changed); at a run's end the
     * state is whole on every rank (par_run_end), so every rank decides alike (after an interrupt
     * no run follows) */
    if (d->style != YF_DUMP_Y2DREF && d->last_step == s->step) {
      d->end_key = sim_state_hash(s);
      d->end_step = s->step;
    }
  }
}

void output_write_all(YfSim *s) {
  struct YfOutput *o = s->out;
  if (!o) return;
  for (int i = 0; i < o->ndump; i++)
    if (o->dump[i]->last_step != s->step) write_frame(s, o->dump[i]);
  update_next_due(s);
}

void output_topology_changed(YfSim *s) {
  /* Nothing to do: every frame file carries the topology of its own step. */
  (void)s;
}

static void dump_close(YfDump *d) {
  if (d->style == YF_DUMP_H5) {
    h5_close(d);
    xmf_flush(d);
  }
  if (d->style == YF_DUMP_Y2DREF) y2dref_close(d->y2d);
  if (d->csv_index.fd >= 0) {
    int bad = yf_rows_close(&d->csv_index) != 0;
    if (bad) yf_output_error("dump %s: cannot write '%s_frames.csv': %s", d->id, d->path, strerror(errno ? errno : EIO));
  }
}

static void dump_free(YfDump *d) {
  dump_close(d);
  free(d->path);
  free(d->xmf);
  free(d->xmf_tmp);
  free(d->stem);
  free(d->ext);
  free(d->cur);
  free(d->cur_tmp);
  free(d->grids.s);
  free(d->cgrids.s);
  free(d->cxmf);
  free(d->cxmf_tmp);
  free(d->buf);
  y2dref_free(d->y2d);
  free(d);
}

int output_flush_indexes(YfSim *s, char *err, size_t nerr) {
  struct YfOutput *o = s->out;
  for (int i = 0; o && i < o->ndump; i++) {
    YfDump *d = o->dump[i];
    if (!d->xmf_pending) continue;
    if (xmf_try(d, err, nerr)) return -1;
    d->xmf_pending = 0;
    d->xmf_done = yf_now();
  }
  return 0;
}

void output_close_all(YfSim *s) {
  struct YfOutput *o = s->out;
  if (!o) return;
  for (int i = 0; i < o->ndump; i++) dump_close(o->dump[i]);
}

struct YfClaim {
  char *owner, *prefix, *suffix; /* prefix absolute and clean; suffix "" unless numbered */
  int numbered;
};

void output_free(YfSim *s) {
  struct YfOutput *o = s->out;
  if (!o) return;
  for (int i = 0; i < o->ndump; i++) dump_free(o->dump[i]);
  while (o->nclaim) output_release(s, o->claim[0].owner);
  free(o->claim);
  for (int i = 0; i < o->npast; i++) free(o->past[i]);
  free(o->past);
  free(o->past_style);
  free(o->past_fields);
  free(o->past_fc);
  free(o);
  s->out = NULL;
}

/* ---------------------------------------------------------------- claims */

static struct YfOutput *out_get(YfSim *s) {
  if (!s->out) {
    s->out = yf_calloc(1, sizeof *s->out, "output");
    s->out->next_due = LONG_MAX;
    io_attach(s); /* whatever made it (write_restart too), the observer frees it with the simulation */
  }
  return s->out;
}

/* path made absolute (relative to the working directory) with '.', '..' and '//' resolved, in
 * text only: "out.h5", "./out.h5" and "/work/x/../x/out.h5" are one name. */
static char *clean_path(const char *path) {
  char cwd[4096] = "";
  if (path[0] != '/' && !getcwd(cwd, sizeof cwd)) cwd[0] = 0;
  char *in = str_printf("%s/%s", cwd, path);
  /* the folder as the file system resolves it, when it exists: 'link/out.h5' with link -> . is
   * out.h5 (two dumps wrote the same frames through a link to their folder).  The file itself is
   * not resolved: /dev/stdout and /dev/stderr are two outputs though both may reach a terminal. */
  char *slash = strrchr(in, '/'), real[PATH_MAX];
  if (slash && slash > in) {
    *slash = 0;
    if (realpath(in, real)) {
      char *r = str_printf("%s/%s", real, slash + 1);
      free(in);
      in = r;
    } else {
      *slash = '/';
    }
  }
  char *out = yf_malloc(strlen(in) + 2, "path");
  size_t n = 0;
  for (char *p = in; *p;) {
    while (*p == '/') p++;
    char *e = p;
    while (*e && *e != '/') e++;
    size_t len = (size_t)(e - p);
    if (len == 0 || (len == 1 && p[0] == '.')) {
    } else if (len == 2 && p[0] == '.' && p[1] == '.') {
      while (n > 0 && out[n - 1] != '/') n--;
      if (n > 0) n--;
    } else {
      out[n++] = '/';
      memcpy(out + n, p, len);
      n += len;
    }
    p = e;
  }
  if (!n) out[n++] = '/';
  out[n] = 0;
  free(in);
  return out;
}

/* Whether the numbered claim a (prefix, a->numbered digits, suffix) names file f. */
static int numbered_names(const struct YfClaim *a, const char *f) {
  size_t lp = strlen(a->prefix), ls = strlen(a->suffix), lf = strlen(f), nd = (size_t)a->numbered;
  if (lf != lp + nd + ls || strncmp(f, a->prefix, lp) || strcmp(f + lp + nd, a->suffix)) return 0;
  for (size_t i = lp; i < lp + nd; i++)
    if (!isdigit((unsigned char)f[i])) return 0;
  return 1;
}

static int claims_meet(const struct YfClaim *a, const struct YfClaim *b) {
  if (a->numbered && b->numbered)
    return a->numbered == b->numbered && !strcmp(a->prefix, b->prefix) && !strcmp(a->suffix, b->suffix);
  if (a->numbered) return numbered_names(a, b->prefix);
  if (b->numbered) return numbered_names(b, a->prefix);
  return !strcmp(a->prefix, b->prefix);
}

const char *output_claim(YfSim *s, const char *owner, const char *prefix, const char *suffix, int numbered) {
  struct YfOutput *o = out_get(s);
  struct YfClaim c = {NULL, clean_path(prefix), yf_strdup(numbered && suffix ? suffix : ""), numbered};
  for (int i = 0; i < o->nclaim; i++)
    if (claims_meet(&o->claim[i], &c)) {
      free(c.prefix);
      free(c.suffix);
      return o->claim[i].owner;
    }
  c.owner = yf_strdup(owner);
  o->claim = yf_realloc(o->claim, (size_t)(o->nclaim + 1) * sizeof *o->claim, "output claims");
  o->claim[o->nclaim++] = c;
  return NULL;
}

void output_release(YfSim *s, const char *owner) {
  struct YfOutput *o = s->out;
  if (!o) return;
  char *own = yf_strdup(owner); /* owner may be a claim's own string */
  int k = 0;
  for (int i = 0; i < o->nclaim; i++) {
    if (!strcmp(o->claim[i].owner, own)) {
      free(o->claim[i].owner);
      free(o->claim[i].prefix);
      free(o->claim[i].suffix);
    } else {
      o->claim[k++] = o->claim[i];
    }
  }
  o->nclaim = k;
  free(own);
}

long output_frames(const YfSim *s, const char *id) {
  const YfDump *d = find_dump(s->out, id, NULL);
  return d ? d->nframe : -1;
}

long output_index_writes(const YfSim *s, const char *id) {
  const YfDump *d = find_dump(s->out, id, NULL);
  return d ? d->xmf_writes : -1;
}

/* ---------------------------------------------------------------- commands */

/* ./yfdem_mpi: h5 frames by parallel HDF5 (every rank writes its rows into the one file) or by a
 * gather to rank 0, which writes them alone.  YFDEM_H5_MPIIO=1 or 0 chooses; unset, the faster
 * of the two in docs/SCALING.md's measurement (section 6, PERF.md's problem at 1e6, 400 MB
 * frames, minima of 10-11 runs on a shared machine): parallel HDF5 on 2 ranks or more (0.44
 * against 0.51 s per frame gathered: a small margin, but it also keeps every frame from passing
 * through one rank when ranks are many), the one writer on one rank (0.36 s; MPI-IO 0.42 s).  The datasets are the same either way (names,
 * shapes, values: tests/check_mpi.c), so the .xmf and ParaView see one series.  Compressed dumps
 * take the gather: filtered parallel writes need every rank in each chunk's write, not tried.
 * ./yfdem has one writer. */
int output_mpio(void) {
#ifdef YF_MPI
  const char *e = getenv("YFDEM_H5_MPIIO");
  if (!e || !*e) return par_size() > 1;
  if (strcmp(e, "0") && strcmp(e, "1"))
    yf_exit_with(YF_EXIT_DECK, "error: YFDEM_H5_MPIIO='%s': expected 1 (parallel HDF5) or 0 (gather to rank 0)", e);
  return e[0] == '1';
#else
  return 0;
#endif
}

int output_add_dump(YfSim *s, const char *id, int style, long every, const char *path,
                    unsigned fields, int compress) {
  io_attach(s); /* dumps observe the run loop (report.c) */
  restart_before_write(output_flush_indexes); /* a restart lists every frame before its step */
  struct YfOutput *o = out_get(s);
  if (o->ndump >= YF_MAX_DUMPS || find_dump(o, id, NULL) || every < 1) return -1;
  YfDump *d = yf_calloc(1, sizeof *d, "dump");
  snprintf(d->id, sizeof d->id, "%s", id);
  d->style = style;
  d->every = every;
  d->fields = fields & YF_FIELD_ALL;
  d->compress = compress;
  d->path = yf_strdup(path);
  d->file = -1;
  d->csv_index.fd = -1;
  d->last_step = LONG_MIN;
  d->end_step = LONG_MIN;
  d->mpio = style == YF_DUMP_H5 && !compress && output_mpio();
  d->fc_asked = (fields & YF_FIELD_ALL) != YF_FIELD_ALL && (fields & YF_FIELD_FC);
  if (style == YF_DUMP_H5) {
    size_t l = output_h5_stem_len(path);
    d->stem = str_printf("%.*s", (int)l, path);
    d->ext = yf_strdup(path[l] ? path + l : ".h5");
    d->xmf = str_printf("%s.xmf", d->stem);
    d->xmf_tmp = str_printf("%s.tmp", d->xmf);
    d->cxmf = str_printf("%s_cracks.xmf", d->stem);
    d->cxmf_tmp = str_printf("%s.tmp", d->cxmf);
    /* frame names are formatted in place per frame: room for a 20-digit index and ".tmp" */
    d->curcap = l + strlen(d->ext) + 32;
    d->cur = yf_malloc(d->curcap, "dump file name");
    d->cur_tmp = yf_malloc(d->curcap, "dump file name");
    d->cur[0] = d->cur_tmp[0] = 0;
  }
  char *cp = clean_path(path);
  for (int i = 0; i < o->npast; i++)
    if (o->past_style[i] == style && !strcmp(o->past[i], cp)) {
      d->again = 1;
      d->again_fields = o->past_fields[i];
      d->had_fc = o->past_fc[i]; /* fc stays in the series (zeros after contact off) */
    }
  free(cp);
  o->dump[o->ndump++] = d;
  update_next_due(s);
  return o->ndump - 1;
}

unsigned output_dump_earlier_fields(const YfSim *s, int k) {
  const YfDump *d = s->out && k >= 0 && k < s->out->ndump ? s->out->dump[k] : NULL;
  return d && d->again ? d->again_fields : 0;
}

int output_remove_dump(YfSim *s, const char *id) {
  struct YfOutput *o = s->out;
  int slot;
  YfDump *d = find_dump(o, id, &slot);
  if (!d) return -1;
  char owner[YF_NAME_MAX + 16];
  snprintf(owner, sizeof owner, "dump '%s'", d->id);
  output_release(s, owner);
  if (d->nframe > 0 && d->style != YF_DUMP_Y2DREF) {
    o->past = yf_realloc(o->past, (size_t)(o->npast + 1) * sizeof *o->past, "undumped files");
    o->past_style = yf_realloc(o->past_style, (size_t)(o->npast + 1) * sizeof *o->past_style, "undumped files");
    o->past_fields = yf_realloc(o->past_fields, (size_t)(o->npast + 1) * sizeof *o->past_fields, "undumped files");
    o->past_fc = yf_realloc(o->past_fc, (size_t)(o->npast + 1) * sizeof *o->past_fc, "undumped files");
    o->past_fc[o->npast] = d->had_fc;
    o->past_style[o->npast] = d->style;
    o->past_fields[o->npast] = d->fields;
    o->past[o->npast++] = clean_path(d->path);
  }
  dump_free(d);
  for (int i = slot; i + 1 < o->ndump; i++) o->dump[i] = o->dump[i + 1];
  o->ndump--;
  update_next_due(s);
  return 0;
}

int output_add_y2dref(YfSim *s, const char *id, struct YfY2dRef *r) {
  int k = output_add_dump(s, id, YF_DUMP_Y2DREF, 1, y2dref_dir(r), 0, 0);
  if (k >= 0) s->out->dump[k]->y2d = r;
  return k;
}

int output_ndump(const YfSim *s) { return s->out ? s->out->ndump : 0; }
int output_dump_mpio(const YfSim *s, int k) { return s->out->dump[k]->mpio; }
const char *output_dump_id(const YfSim *s, int k) { return s->out->dump[k]->id; }
const char *output_dump_path(const YfSim *s, int k) { return s->out->dump[k]->path; }
int output_find_dump(const YfSim *s, const char *id) {
  int slot;
  return find_dump(s->out, id, &slot) ? slot : -1;
}

size_t output_h5_stem_len(const char *path) {
  const char *base = strrchr(path, '/');
  const char *dot = strrchr(base ? base + 1 : path, '.');
  size_t l = strlen(path);
  if (dot && (strcmp(dot, ".h5") == 0 || strcmp(dot, ".hdf5") == 0 || strcmp(dot, ".hdf") == 0)) l -= strlen(dot);
  return l;
}

void output_dump_files(const YfSim *s, int k, const char **stem, const char **ext, const char **xmf) {
  const YfDump *d = s->out->dump[k];
  *stem = d->stem;
  *ext = d->ext;
  *xmf = d->xmf;
}
