/* output.c: frames of the state for post-processing (see output.h for the contract).
 *
 * h5 dumps.  One HDF5 file per dump, laid out for XDMF 3 (ParaView: File > Open FILE.xmf):
 *
 *   /mesh/{triangles (ntri x 3 int), material, body, tri_id (ntri int),
 *          node_id (n int), x0 (n x 2)}             topology, written at the first frame
 *   /mesh_NNNN/...                                  a later topology (output_topology_changed)
 *   /frames/NNNNNN/{time, step (scalars), x, u, v, f (n x 2), stress (ntri x 3: sxx syy sxy),
 *                   vonmises, sigma1 (ntri)}        one group per frame, frame index NNNNNN
 *                  fc (n x 2): contact force per node, only in frames written while contact is on
 *
 * Datasets are contiguous and uncompressed by default: a frame is then one write per array,
 * which keeps a 1e5-triangle frame well under the cost of ten steps.  `compress` switches to
 * gzip (level 1, with shuffle) in chunks: half the size, ~20x the time of a raw frame.
 *
 * Why per-frame groups and not extendible datasets: a frame never changes what earlier frames
 * occupy in the file (fresh datasets at the end of the file; no chunk index or dataspace of an
 * old array is rewritten), so the only metadata shared between frames is the /frames group's
 * list of links.  /frames is a "compact" group whose object header is pre-sized for FRAMES_EST
 * links (H5Pset_est_link_info): adding a frame fills a slot of that one header in place, and the
 * header reaches the file in one write at the next flush, so there is no moment at which an
 * earlier frame's link is missing.  (With the classic symbol-table groups, or once the header
 * overflows, HDF5 splits or moves group metadata across several writes and a kill between them
 * can lose earlier frames: we measured this by crashing the writer at every write.)
 * After each frame: H5Fflush (everything of the frame reaches the OS), then the .xmf is replaced
 * atomically (tmp + fsync + rename).  The .xmf therefore never names a frame that is not fully
 * in the file; the kill test in tests/check_output.c SIGKILLs a writer mid-stream and reads back.
 * The file format is pinned to HDF5 1.8 (H5F_LIBVER_V18): new enough for compact groups, and its
 * superblock has no "open for writing" flag, which with the 1.10 format would make a killed
 * file refuse to open (in ParaView too) until `h5clear -s`.
 *
 * csv dumps.  PREFIX_NNNNNN.csv (node id, x, y, ux, uy, vx, vy) per frame plus PREFIX_frames.csv
 * (frame, step, time, file) for scripts.
 *
 * The XDMF <Grid> text of every frame is kept in memory and the whole index is rewritten per
 * frame (a few hundred bytes per frame), so the index stays a plain, self-contained file.
 */
#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include <hdf5.h>
#include "output.h"
#include "contact.h"
#include "err.h"
#include "y2dref.h"

/* The y2dref style (y2dref.c: Y2D reference CSV files) is written every step; y2dref_frame decides
 * what is due. */
enum { YF_DUMP_Y2DREF = 2 };

typedef struct YfDump {
  char id[YF_NAME_MAX];
  int style;          /* YF_DUMP_H5 | YF_DUMP_CSV                                       */
  long every;         /* steps between frames                                          */
  unsigned fields;    /* YF_FIELD_* (h5)                                               */
  int compress;       /* gzip chunks (h5)                                              */
  char *path;         /* h5 file, or csv prefix                                        */
  char *xmf, *xmf_tmp;/* FILE.xmf and FILE.xmf.tmp                                     */
  char *h5name;       /* file name without directory, as the .xmf refers to it         */
  hid_t file, frames; /* open handles (h5), < 0 when closed                             */
  int created;        /* file created in this process (a later open appends)           */
  long nframe;        /* frames written                                                */
  long last_step;     /* step of the last frame (LONG_MIN: none)                       */
  int topo;           /* mesh group index of the current topology (-1: none yet)       */
  int topo_pending;   /* output_topology_changed since the last frame                  */
  int topo_n, topo_nt;/* node and triangle counts of the current mesh group            */
  char *grids;        /* XDMF <Grid> elements of the frames so far                     */
  size_t glen, gcap;
  double *buf;        /* scratch for interleaved / derived arrays                      */
  size_t bufcap;
  FILE *csv_index;    /* PREFIX_frames.csv                                             */
  struct YfY2dRef *y2d; /* y2dref style                                                */
} YfDump;

static const char *const field_names[] = {"u", "v", "f", "stress", "vonmises", "sigma1",
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

static void grids_printf(YfDump *d, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static void grids_printf(YfDump *d, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  int n = vsnprintf(NULL, 0, fmt, ap);
  va_end(ap);
  if (d->glen + (size_t)n + 1 > d->gcap) {
    size_t cap = d->gcap ? d->gcap : 4096;
    while (cap < d->glen + (size_t)n + 1) cap *= 2;
    d->grids = yf_realloc(d->grids, cap, "XDMF index text");
    d->gcap = cap;
  }
  va_start(ap, fmt);
  vsnprintf(d->grids + d->glen, (size_t)n + 1, fmt, ap);
  va_end(ap);
  d->glen += (size_t)n;
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
  static char msg[512];
  msg[0] = 0;
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_UPWARD, h5_walk_cb, msg);
  return msg[0] ? msg : "HDF5 error";
}

static void h5_fail(const YfDump *d, const char *what) __attribute__((noreturn));
static void h5_fail(const YfDump *d, const char *what) {
  yf_io_error(NULL, "dump %s: cannot write '%s' (%s): %s", d->id, d->path, what, h5_message());
}

/* HDF5 prints its error stack by default; yfdem reports errors itself. */
static void h5_quiet(void) {
  static int done;
  if (!done) {
    H5open();
    H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
    done = 1;
  }
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

/* Create dataset `name` under loc and write data (memory type = file type). */
static void h5_put(YfDump *d, hid_t loc, const char *name, hid_t type, int rank,
                   const hsize_t *dims, const void *data) {
  hid_t space = rank ? H5Screate_simple(rank, dims, NULL) : H5Screate(H5S_SCALAR);
  if (space < 0) h5_fail(d, name);
  hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
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
  if (H5Dwrite(ds, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data ? data : &none) < 0) h5_fail(d, name);
  H5Dclose(ds);
  H5Sclose(space);
}

/* Frames that /frames holds in its pre-sized object header (see the file comment). */
#define FRAMES_EST 8192

static void h5_open(YfDump *d) {
  h5_quiet();
  /* 1.8 file format: link messages in object headers (needed for the pre-sized /frames), and a
   * version-2 superblock, which has no "open for writing" flag that would lock a killed file. */
  hid_t fapl = H5Pcreate(H5P_FILE_ACCESS);
  H5Pset_libver_bounds(fapl, H5F_LIBVER_V18, H5F_LIBVER_V18);
  H5Pset_fclose_degree(fapl, H5F_CLOSE_STRONG); /* closing after an error also closes its objects */
  if (!d->created) {
    hid_t fcpl = H5Pcreate(H5P_FILE_CREATE);
    H5Pset_est_link_info(fcpl, 16, 9); /* root: frames, mesh, mesh_NNNN... */
    d->file = H5Fcreate(d->path, H5F_ACC_TRUNC, fcpl, fapl);
    if (d->file < 0) h5_fail(d, "create file");
    H5Pclose(fcpl);
    H5Pclose(fapl);
    d->created = 1;
    hid_t gcpl = H5Pcreate(H5P_GROUP_CREATE);
    H5Pset_link_phase_change(gcpl, 65535, 65534);
    H5Pset_est_link_info(gcpl, FRAMES_EST, 6);
    d->frames = H5Gcreate2(d->file, "frames", H5P_DEFAULT, gcpl, H5P_DEFAULT);
    if (d->frames < 0) h5_fail(d, "create /frames");
    H5Pclose(gcpl);
  } else { /* reopened after output_close_all / between runs: append */
    d->file = H5Fopen(d->path, H5F_ACC_RDWR, fapl);
    if (d->file < 0) h5_fail(d, "reopen file");
    H5Pclose(fapl);
    d->frames = H5Gopen2(d->file, "frames", H5P_DEFAULT);
    if (d->frames < 0) h5_fail(d, "open /frames");
  }
}

static void h5_close(YfDump *d) {
  if (d->frames >= 0) H5Gclose(d->frames);
  if (d->file >= 0) H5Fclose(d->file);
  d->frames = d->file = -1;
}

static void mesh_name(char *buf, size_t n, int topo) {
  if (topo == 0) snprintf(buf, n, "mesh");
  else snprintf(buf, n, "mesh_%04d", topo);
}

/* Write the current topology as a new mesh group. */
static void h5_mesh(YfSim *s, YfDump *d) {
  const YfModel *m = &s->model;
  int n = m->node.n, nt = m->tri.n;
  char name[32];
  d->topo++;
  mesh_name(name, sizeof name, d->topo);
  hid_t g = H5Gcreate2(d->file, name, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  if (g < 0) h5_fail(d, name);
  hsize_t dt[2] = {(hsize_t)nt, 3}, d1[1] = {(hsize_t)nt}, dn[1] = {(hsize_t)n};
  hsize_t dn2[2] = {(hsize_t)n, 2};
  h5_put(d, g, "triangles", H5T_NATIVE_INT, 2, dt, m->tri.v);
  h5_put(d, g, "material", H5T_NATIVE_INT, 1, d1, m->tri.mat);
  h5_put(d, g, "body", H5T_NATIVE_INT, 1, d1, m->tri.body);
  h5_put(d, g, "tri_id", H5T_NATIVE_INT, 1, d1, m->tri.id);
  h5_put(d, g, "node_id", H5T_NATIVE_INT, 1, dn, m->node.id);
  double *b = scratch(d, 2 * (size_t)n);
  for (int i = 0; i < n; i++) {
    b[2 * i] = m->node.x0[i];
    b[2 * i + 1] = m->node.y0[i];
  }
  h5_put(d, g, "x0", H5T_NATIVE_DOUBLE, 2, dn2, b);
  H5Gclose(g);
  d->topo_pending = 0;
  d->topo_n = n;
  d->topo_nt = nt;
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

static void xmf_item(YfDump *d, const char *fname, const char *dims, int is_int, const char *path) {
  grids_printf(d, "          <DataItem Dimensions=\"%s\" NumberType=\"%s\" Precision=\"%d\" "
                  "Format=\"HDF\">%s:%s</DataItem>\n",
               dims, is_int ? "Int" : "Float", is_int ? 4 : 8, fname, path);
}

static void xmf_attr(YfDump *d, const char *fname, const char *name, const char *type,
                     const char *center, const char *dims, int is_int, const char *path) {
  grids_printf(d, "        <Attribute Name=\"%s\" AttributeType=\"%s\" Center=\"%s\">\n", name,
               type, center);
  xmf_item(d, fname, dims, is_int, path);
  grids_printf(d, "        </Attribute>\n");
}

/* Append the <Grid> of the frame just written. */
static void xmf_add_frame(YfDump *d, const char *frame, double time, long step, int n, int nt, int with_fc) {
  char fname[1024], mesh[32], p[128], dn2[48], dt3[48], dt1[48];
  xml_escape(fname, sizeof fname, d->h5name);
  mesh_name(mesh, sizeof mesh, d->topo);
  snprintf(dn2, sizeof dn2, "%d 2", n);
  snprintf(dt3, sizeof dt3, "%d 3", nt);
  snprintf(dt1, sizeof dt1, "%d", nt);
  grids_printf(d, "      <Grid Name=\"frame_%s\" GridType=\"Uniform\">\n", frame);
  grids_printf(d, "        <Time Value=\"%.17g\"/>\n", time);
  grids_printf(d, "        <Information Name=\"step\" Value=\"%ld\"/>\n", step);
  grids_printf(d, "        <Topology TopologyType=\"Triangle\" NumberOfElements=\"%d\" "
                  "NodesPerElement=\"3\">\n", nt);
  snprintf(p, sizeof p, "/%s/triangles", mesh);
  xmf_item(d, fname, dt3, 1, p);
  grids_printf(d, "        </Topology>\n        <Geometry GeometryType=\"XY\">\n");
  snprintf(p, sizeof p, "/frames/%s/x", frame);
  xmf_item(d, fname, dn2, 0, p);
  grids_printf(d, "        </Geometry>\n");
  static const struct { unsigned bit; const char *name, *type, *center; int dims; } attrs[] = {
      {YF_FIELD_U, "u", "Vector", "Node", 2},         {YF_FIELD_V, "v", "Vector", "Node", 2},
      {YF_FIELD_F, "f", "Vector", "Node", 2},         {YF_FIELD_STRESS, "stress", "Vector", "Cell", 3},
      {YF_FIELD_VONMISES, "vonmises", "Scalar", "Cell", 1},
      {YF_FIELD_SIGMA1, "sigma1", "Scalar", "Cell", 1}};
  for (size_t i = 0; i < sizeof attrs / sizeof attrs[0]; i++) {
    if (!(d->fields & attrs[i].bit)) continue;
    snprintf(p, sizeof p, "/frames/%s/%s", frame, attrs[i].name);
    xmf_attr(d, fname, attrs[i].name, attrs[i].type, attrs[i].center,
             attrs[i].dims == 2 ? dn2 : attrs[i].dims == 3 ? dt3 : dt1, 0, p);
  }
  if (with_fc) {
    snprintf(p, sizeof p, "/frames/%s/fc", frame);
    xmf_attr(d, fname, "fc", "Vector", "Node", dn2, 0, p);
  }
  if (d->fields & YF_FIELD_MATERIAL) {
    snprintf(p, sizeof p, "/%s/material", mesh);
    xmf_attr(d, fname, "material", "Scalar", "Cell", dt1, 1, p);
  }
  if (d->fields & YF_FIELD_BODY) {
    snprintf(p, sizeof p, "/%s/body", mesh);
    xmf_attr(d, fname, "body", "Scalar", "Cell", dt1, 1, p);
  }
  grids_printf(d, "      </Grid>\n");
}

/* Replace FILE.xmf atomically: a reader (or a killed run) sees the old or the new index. */
static void xmf_write(YfDump *d) {
  FILE *f = fopen(d->xmf_tmp, "w");
  if (!f) yf_io_error(NULL, "dump %s: cannot create '%s': %s", d->id, d->xmf_tmp, strerror(errno));
  char name[YF_NAME_MAX * 6 + 1];
  xml_escape(name, sizeof name, d->id);
  fprintf(f, "<?xml version=\"1.0\" ?>\n<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n"
             "<Xdmf Version=\"3.0\">\n  <Domain>\n"
             "    <Grid Name=\"%s\" GridType=\"Collection\" CollectionType=\"Temporal\">\n", name);
  if (d->glen) fwrite(d->grids, 1, d->glen, f);
  fputs("    </Grid>\n  </Domain>\n</Xdmf>\n", f);
  int bad = ferror(f) || fflush(f) != 0 || fsync(fileno(f)) != 0;
  int err = errno;
  if (fclose(f) != 0 && !bad) {
    bad = 1;
    err = errno;
  }
  if (bad) yf_io_error(NULL, "dump %s: cannot write '%s': %s", d->id, d->xmf_tmp, strerror(err));
  if (rename(d->xmf_tmp, d->xmf) != 0)
    yf_io_error(NULL, "dump %s: cannot rename '%s' to '%s': %s", d->id, d->xmf_tmp, d->xmf,
                strerror(errno));
}

static void h5_frame(YfSim *s, YfDump *d) {
  const YfModel *m = &s->model;
  const YfNodes *nd = &m->node;
  int n = nd->n, nt = m->tri.n;
  if (d->file < 0) h5_open(d);
  if (d->topo < 0 || d->topo_pending || n != d->topo_n || nt != d->topo_nt) h5_mesh(s, d);

  char frame[32];
  snprintf(frame, sizeof frame, "%06ld", d->nframe);
  hid_t g = H5Gcreate2(d->frames, frame, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  if (g < 0) h5_fail(d, "create frame group");
  long long step = s->step;
  h5_put(d, g, "time", H5T_NATIVE_DOUBLE, 0, NULL, &s->time);
  h5_put(d, g, "step", H5T_NATIVE_LLONG, 0, NULL, &step);

  hsize_t dn2[2] = {(hsize_t)n, 2}, dt3[2] = {(hsize_t)nt, 3}, dt1[1] = {(hsize_t)nt};
  size_t need = 2 * (size_t)n > (size_t)nt ? 2 * (size_t)n : (size_t)nt;
  double *b = scratch(d, need);
  for (int i = 0; i < n; i++) {
    b[2 * i] = nd->x[i];
    b[2 * i + 1] = nd->y[i];
  }
  h5_put(d, g, "x", H5T_NATIVE_DOUBLE, 2, dn2, b);
  if (d->fields & YF_FIELD_U) {
    for (int i = 0; i < n; i++) {
      b[2 * i] = nd->x[i] - nd->x0[i];
      b[2 * i + 1] = nd->y[i] - nd->y0[i];
    }
    h5_put(d, g, "u", H5T_NATIVE_DOUBLE, 2, dn2, b);
  }
  if (d->fields & YF_FIELD_V) {
    for (int i = 0; i < n; i++) {
      b[2 * i] = nd->vx[i];
      b[2 * i + 1] = nd->vy[i];
    }
    h5_put(d, g, "v", H5T_NATIVE_DOUBLE, 2, dn2, b);
  }
  if (d->fields & YF_FIELD_F) {
    for (int i = 0; i < n; i++) {
      b[2 * i] = nd->fx[i];
      b[2 * i + 1] = nd->fy[i];
    }
    h5_put(d, g, "f", H5T_NATIVE_DOUBLE, 2, dn2, b);
  }
  const double *sg = m->tri.s; /* sxx, syy, sxy per triangle, already the file layout */
  if (d->fields & YF_FIELD_STRESS) h5_put(d, g, "stress", H5T_NATIVE_DOUBLE, 2, dt3, sg);
  if (d->fields & YF_FIELD_VONMISES) {
    /* In-plane von Mises (szz taken as 0): sqrt(sxx^2 - sxx syy + syy^2 + 3 sxy^2). */
    for (int e = 0; e < nt; e++) {
      double a = sg[3 * e], c = sg[3 * e + 1], t = sg[3 * e + 2];
      b[e] = sqrt(a * a - a * c + c * c + 3.0 * t * t);
    }
    h5_put(d, g, "vonmises", H5T_NATIVE_DOUBLE, 1, dt1, b);
  }
  if (d->fields & YF_FIELD_SIGMA1) {
    for (int e = 0; e < nt; e++) {
      double a = sg[3 * e], c = sg[3 * e + 1], t = sg[3 * e + 2];
      double h = 0.5 * (a - c);
      b[e] = 0.5 * (a + c) + sqrt(h * h + t * t);
    }
    h5_put(d, g, "sigma1", H5T_NATIVE_DOUBLE, 1, dt1, b);
  }
  /* contact force per node: only while contact is on (else the field would be all zeros) */
  const double *fc = (d->fields & YF_FIELD_FC) ? contact_node_forces(s) : NULL;
  if (fc) h5_put(d, g, "fc", H5T_NATIVE_DOUBLE, 2, dn2, fc);
  if (H5Gclose(g) < 0) h5_fail(d, "close frame group");
  /* The frame must be complete in the file before the index names it. */
  if (H5Fflush(d->file, H5F_SCOPE_GLOBAL) < 0) h5_fail(d, "flush");
  xmf_add_frame(d, frame, s->time, s->step, n, nt, fc != NULL);
  xmf_write(d);
}

/* ---------------------------------------------------------------- CSV */

static void csv_frame(YfSim *s, YfDump *d) {
  const YfNodes *nd = &s->model.node;
  char *path = str_printf("%s_%06ld.csv", d->path, d->nframe);
  if (!d->csv_index) {
    char *ip = str_printf("%s_frames.csv", d->path);
    d->csv_index = fopen(ip, d->created ? "a" : "w");
    if (!d->csv_index) yf_io_error(NULL, "dump %s: cannot create '%s': %s", d->id, ip, strerror(errno));
    if (!d->created) fprintf(d->csv_index, "frame,step,time,file\n");
    d->created = 1;
    free(ip);
  }
  FILE *f = fopen(path, "w");
  if (!f) yf_io_error(NULL, "dump %s: cannot create '%s': %s", d->id, path, strerror(errno));
  fprintf(f, "id,x,y,ux,uy,vx,vy\n");
  for (int i = 0; i < nd->n; i++)
    fprintf(f, "%d,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n", nd->id[i], nd->x[i], nd->y[i],
            nd->x[i] - nd->x0[i], nd->y[i] - nd->y0[i], nd->vx[i], nd->vy[i]);
  int bad = ferror(f);
  if (fclose(f) != 0 || bad) yf_io_error(NULL, "dump %s: cannot write '%s': %s", d->id, path, strerror(errno));
  const char *base = strrchr(path, '/');
  fprintf(d->csv_index, "%ld,%ld,%.17g,%s\n", d->nframe, s->step, s->time, base ? base + 1 : path);
  if (fflush(d->csv_index) != 0)
    yf_io_error(NULL, "dump %s: cannot write '%s_frames.csv': %s", d->id, d->path, strerror(errno));
  free(path);
}

/* ---------------------------------------------------------------- frames */

static void write_frame(YfSim *s, YfDump *d) {
  if (d->style == YF_DUMP_Y2DREF) y2dref_frame(s, d->y2d);
  else if (d->style == YF_DUMP_H5) h5_frame(s, d);
  else csv_frame(s, d);
  d->nframe++;
  d->last_step = s->step;
}

void output_run_begin(YfSim *s) {
  struct YfOutput *o = s->out;
  if (!o) return;
  for (int i = 0; i < o->ndump; i++)
    if (o->dump[i]->last_step != s->step) write_frame(s, o->dump[i]);
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
  /* Every frame is flushed and indexed as it is written; nothing is pending here.  Files stay
   * open for the next run (output_close_all closes them at exit). */
  (void)s;
}

void output_write_all(YfSim *s) {
  struct YfOutput *o = s->out;
  if (!o) return;
  for (int i = 0; i < o->ndump; i++)
    if (o->dump[i]->last_step != s->step) write_frame(s, o->dump[i]);
  update_next_due(s);
}

void output_topology_changed(YfSim *s) {
  struct YfOutput *o = s->out;
  if (!o) return;
  for (int i = 0; i < o->ndump; i++) o->dump[i]->topo_pending = 1;
}

static void dump_close(YfDump *d) {
  if (d->style == YF_DUMP_H5) h5_close(d);
  if (d->style == YF_DUMP_Y2DREF) y2dref_close(d->y2d);
  if (d->csv_index) {
    fclose(d->csv_index);
    d->csv_index = NULL;
  }
}

static void dump_free(YfDump *d) {
  dump_close(d);
  free(d->path);
  free(d->xmf);
  free(d->xmf_tmp);
  free(d->h5name);
  free(d->grids);
  free(d->buf);
  y2dref_free(d->y2d);
  free(d);
}

void output_close_all(YfSim *s) {
  struct YfOutput *o = s->out;
  if (!o) return;
  for (int i = 0; i < o->ndump; i++) dump_close(o->dump[i]);
}

void output_free(YfSim *s) {
  struct YfOutput *o = s->out;
  if (!o) return;
  for (int i = 0; i < o->ndump; i++) dump_free(o->dump[i]);
  free(o);
  s->out = NULL;
}

long output_frames(const YfSim *s, const char *id) {
  const YfDump *d = find_dump(s->out, id, NULL);
  return d ? d->nframe : -1;
}

/* ---------------------------------------------------------------- commands */

int output_add_dump(YfSim *s, const char *id, int style, long every, const char *path,
                    unsigned fields, int compress) {
  if (!s->out) {
    s->out = yf_calloc(1, sizeof *s->out, "output");
    s->out->next_due = LONG_MAX;
  }
  struct YfOutput *o = s->out;
  if (o->ndump >= YF_MAX_DUMPS || find_dump(o, id, NULL) || every < 1) return -1;
  YfDump *d = yf_calloc(1, sizeof *d, "dump");
  snprintf(d->id, sizeof d->id, "%s", id);
  d->style = style;
  d->every = every;
  d->fields = fields & YF_FIELD_ALL;
  d->compress = compress;
  d->path = yf_strdup(path);
  d->file = d->frames = -1;
  d->last_step = LONG_MIN;
  d->topo = -1;
  if (style == YF_DUMP_H5) {
    const char *base = strrchr(path, '/');
    d->h5name = yf_strdup(base ? base + 1 : path);
    size_t l = strlen(path);
    const char *dot = strrchr(d->h5name, '.');
    if (dot && (strcmp(dot, ".h5") == 0 || strcmp(dot, ".hdf5") == 0 || strcmp(dot, ".hdf") == 0))
      l -= strlen(dot);
    d->xmf = str_printf("%.*s.xmf", (int)l, path);
    d->xmf_tmp = str_printf("%s.tmp", d->xmf);
  }
  o->dump[o->ndump++] = d;
  update_next_due(s);
  return o->ndump - 1;
}

int output_remove_dump(YfSim *s, const char *id) {
  struct YfOutput *o = s->out;
  int slot;
  YfDump *d = find_dump(o, id, &slot);
  if (!d) return -1;
  dump_free(d);
  for (int i = slot; i + 1 < o->ndump; i++) o->dump[i] = o->dump[i + 1];
  o->ndump--;
  update_next_due(s);
  return 0;
}

/* dump ID h5 N FILE.h5 [fields F1 F2 ...] [compress]
 * dump ID csv N PREFIX */
void cmd_dump(YfSim *s, const YfArgs *a) {
  static const char *const styles[] = {"h5", "csv", "y2dref", NULL};
  arg_count(a, 2, -1);
  const char *id = arg_word(a, 0, "dump id");
  if (strlen(id) >= YF_NAME_MAX) arg_error(a, 0, "id too long (at most %d characters)", YF_NAME_MAX - 1);
  int style = arg_choice(a, 1, "style", styles);
  if (style == YF_DUMP_Y2DREF) { /* dump ID y2dref DIR [corners S,...] [summary K] [probes K E:C ...] */
    if (find_dump(s->out, id, NULL)) arg_error(a, 0, "a dump with this id exists (undump it first)");
    if (s->out && s->out->ndump >= YF_MAX_DUMPS) arg_error(a, 0, "at most %d dumps at a time", YF_MAX_DUMPS);
    struct YfY2dRef *r = y2dref_parse(s, a);
    int k = output_add_dump(s, id, style, 1, y2dref_dir(r), 0, 0);
    s->out->dump[k]->y2d = r;
    sim_printf(s, "dump %s: Y2D reference CSV files in %s\n", id, y2dref_dir(r));
    return;
  }
  arg_count(a, 4, -1);
  long every = arg_int(a, 2, "N (steps between frames)", 1, LONG_MAX / 4);
  const char *path = arg_word(a, 3, style == YF_DUMP_H5 ? "file" : "file prefix");
  unsigned fields = YF_FIELD_ALL;
  int compress = 0;
  for (int i = 4; i < a->n;) {
    if (style == YF_DUMP_H5 && strcmp(a->w[i], "fields") == 0) {
      int first = ++i;
      fields = 0;
      for (; i < a->n && strcmp(a->w[i], "compress") != 0; i++) {
        int k = arg_choice(a, i, "field", field_names);
        if (k < 9) fields |= 1u << k; /* "x" (geometry) is always written */
      }
      if (i == first) arg_error(a, first - 1, "expected field names after it (u v f stress vonmises sigma1 material body fc)");
    } else if (style == YF_DUMP_H5 && strcmp(a->w[i], "compress") == 0) {
      compress = 1;
      i++;
    } else if (style == YF_DUMP_H5) {
      arg_error(a, i, "unknown keyword (expected fields or compress)");
    } else {
      arg_error(a, i, "unexpected word (a csv dump takes no keywords)");
    }
  }
  if (!path[0]) arg_error(a, 3, "empty file name");
  const char *base = strrchr(path, '/');
  if (style == YF_DUMP_H5 && strchr(base ? base + 1 : path, ':'))
    arg_error(a, 3, "the file name may not contain ':' (XDMF uses it to separate file and dataset)");
  struct YfOutput *o = s->out;
  if (find_dump(o, id, NULL)) arg_error(a, 0, "a dump with this id exists (undump it first)");
  if (o && o->ndump >= YF_MAX_DUMPS) arg_error(a, 0, "at most %d dumps at a time", YF_MAX_DUMPS);
  for (int i = 0; o && i < o->ndump; i++)
    if (strcmp(o->dump[i]->path, path) == 0)
      arg_error(a, 3, "already written by dump '%s'", o->dump[i]->id);
  output_add_dump(s, id, style, every, path, fields, compress);
  if (style == YF_DUMP_H5)
    sim_printf(s, "dump %s: every %ld steps to %s (index %s)\n", id, every, path, s->out->dump[s->out->ndump - 1]->xmf);
  else
    sim_printf(s, "dump %s: every %ld steps to %s_NNNNNN.csv\n", id, every, path);
}

/* undump ID */
void cmd_undump(YfSim *s, const YfArgs *a) {
  arg_count(a, 1, 1);
  const char *id = arg_word(a, 0, "dump id");
  if (output_remove_dump(s, id) == 0) return;
  struct YfOutput *o = s->out;
  char have[YF_MAX_DUMPS * (YF_NAME_MAX + 1) + 8] = "";
  for (int i = 0; o && i < o->ndump; i++) {
    strcat(have, i ? " " : "");
    strcat(have, o->dump[i]->id);
  }
  arg_error(a, 0, "no such dump (defined: %s)", have[0] ? have : "none");
}
