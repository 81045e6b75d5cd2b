/* gmsh.c: reader of Gmsh MSH 4.1 and 2.2 meshes, ASCII or binary, and MSH 2.0 and 2.1 ASCII (the
 * `mesh gmsh` command's parser).
 *
 * The file is read whole into memory and walked token by token, keeping the line of each token
 * so that every complaint names FILE.msh:LINE (and the deck line of the mesh command).  Sections
 * used: $MeshFormat (4.1, 2.2, 2.1 or 2.0), $PhysicalNames, $Entities (which entity belongs to
 * which physical groups), $PartitionedEntities (the same for the partition entities that hold the
 * elements of a mesh partitioned in Gmsh; its partitions are ignored), $Nodes (with or without
 * parametric coordinates) and $Elements; any other section is skipped.
 *
 * What becomes what:
 *   - 3-node triangles (type 2) in surfaces become triangles, turned counter-clockwise when the
 *     file has them clockwise; their material comes from the surface's physical group (see
 *     gmsh_read in mesh.h and cmd_mesh_gmsh in deck/cmd_mesh.c);
 *   - every physical group (point, curve, surface) becomes a node group named after it (a
 *     surface also a triangle group), so boundary curves carry loads and supports; unnamed
 *     groups are called phys_<tag> (phys_<tag>_<curve|surface|point> when tags of two
 *     dimensions coincide).  A name already used by a group of an earlier mesh adds to that
 *     group; a name equal to a body's name is refused (it would corrupt the body's group);
 *   - 2-node lines (type 1) and points (type 15) only matter in physical curves and points;
 *     elements of entities without physical groups in dimensions 0 and 1 are skipped;
 *   - only nodes that are triangle corners enter the model (a node without a triangle would
 *     have no mass); z is dropped, after checking that every node has the first one's.  Node
 *     and element tags become the user ids.
 * Each element must sit on one line (as Gmsh writes them), which lets the reader check the
 * number of node tags of every element.
 *
 * MSH 2.2 has no $Entities: each element line carries its physical tag (0: none) and elementary
 * tag, and an element in several physical groups is written once per group, each copy with its
 * own tag.  The reader makes an entity of each (dimension, elementary tag, physical tags) the
 * elements show and merges the copies of a triangle (same corners), so that the rest is the 4.1
 * path and the same mesh in either version gives the same scene (same nodes in the same order,
 * triangles, materials, groups); only the ids of triangles with copies differ (the first copy's
 * tag).  Elements of physical tag 0 are those of 4.1 entities without physical groups.  The
 * nodes are in $Nodes, or in $ParametricNodes (each node's entity and u, or u v, after x y z).
 * Binary 2.2 keeps the ASCII layout around the data of $Nodes (tag and x y z of each node) and
 * $Elements (blocks of one element type); the data is read in the byte order the header's integer
 * 1 tells, and complaints about it name the line of the section's count.  MSH 2.0 and 2.1 (early
 * Gmsh 2 releases) are 2.2 but for an element's tags after the second (its partition), which are
 * skipped; their binary form is refused.
 *
 * Binary 4.1 has the ASCII values of 4.1 in binary ($PhysicalNames stays ASCII): counts and node
 * and element tags as 8-byte size_t, entity tags, dimensions, element types and physical tags as
 * 4-byte ints, coordinates as doubles, in the header's byte order.  Its sections are read by the
 * ASCII code through rd_size/rd_int/rd_double; an element's node tags are as many as its type has
 * (ASCII: the words on its line), and complaints name the byte as well as the line.
 */
#include <ctype.h>
#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "memcap.h"
#include "mesh.h"
#include "strictnum.h"

typedef struct {
  const char *fname;
  const YfLoc *from;
  char *buf;
  size_t len, pos;
  int line;            /* line of the read position (1-based)  */
  int tokline;         /* line of the last token               */
  char tok[256];
  const char *section; /* for messages                         */
  int bin, swap;       /* binary file; its data in the other byte order */
  int b41;             /* binary MSH 4.1: the rd_* readers take binary values */
  int inbin;           /* in a binary MSH 4.1 section's data: messages give the byte */
  size_t binat;        /* where the last binary value starts (0-based byte offset) */
} Msh;

typedef struct {
  int dim;
  long tag;
  int off, nphys; /* physical tags in the pool */
  int ntri;       /* triangles read in this entity (surfaces) */
  int mat;        /* resolved material (surfaces with triangles) */
  uint64_t bits;  /* group bits of its physical groups */
  int next;       /* MSH 2.2: the next entity of the same dimension and elementary tag, or -1 */
  long el;        /* MSH 2.2: its first element's tag (for messages) */
} Ent;

typedef struct {
  int dim;
  long tag;
  char name[128];
} PhysName;

typedef struct {
  int dim;
  long tag;
  char name[160];
  int group;
} Phys;

static void msh_fail(const Msh *r, int line, const char *fmt, ...)
    __attribute__((noreturn, format(printf, 3, 4)));
static void msh_fail(const Msh *r, int line, const char *fmt, ...) {
  char msg[1024];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(msg, sizeof msg, fmt, ap);
  va_end(ap);
  /* a line of binary data means little (its newline bytes are data): the byte is where to look */
  if (r->inbin) {
    size_t k = strlen(msg);
    snprintf(msg + k, sizeof msg - k, " (binary data at byte %zu)", r->binat);
  }
  YfLoc loc = {r->fname, line};
  if (r->from && r->from->file)
    yf_deck_error(&loc, "%s%s%s (read by mesh gmsh at %s:%d)", r->section ? r->section : "",
                  r->section ? ": " : "", msg, r->from->file, r->from->line);
  yf_deck_error(&loc, "%s%s%s", r->section ? r->section : "", r->section ? ": " : "", msg);
}

/* Next whitespace-separated token into r->tok; 0 at end of file. */
static int msh_next(Msh *r) {
  while (r->pos < r->len) {
    char c = r->buf[r->pos];
    if (c == '\n') r->line++;
    else if (!isspace((unsigned char)c)) break;
    r->pos++;
  }
  r->tokline = r->line;
  if (r->pos >= r->len) {
    r->tok[0] = '\0';
    return 0;
  }
  size_t k = 0;
  while (r->pos < r->len && !isspace((unsigned char)r->buf[r->pos])) {
    if (k + 1 >= sizeof r->tok) msh_fail(r, r->line, "a word longer than %zu characters", sizeof r->tok - 1);
    r->tok[k++] = r->buf[r->pos++];
  }
  r->tok[k] = '\0';
  return 1;
}

/* 1 when only blanks remain on the current line. */
static int msh_eol(Msh *r) {
  while (r->pos < r->len && (r->buf[r->pos] == ' ' || r->buf[r->pos] == '\t' || r->buf[r->pos] == '\r'))
    r->pos++;
  return r->pos >= r->len || r->buf[r->pos] == '\n';
}

/* A data token: refuses end of file and section markers (both mean the counts are wrong). */
static void msh_need(Msh *r, const char *what) {
  if (!msh_next(r))
    msh_fail(r, r->line, "unexpected end of file while reading %s (truncated file?)", what);
  if (r->tok[0] == '$')
    msh_fail(r, r->tokline, "found '%s' while reading %s: the section holds less data than its "
             "counts declare", r->tok, what);
  /* no file ends on data (an $End marker follows): a word that runs into the end was cut, and
   * read as it stands it gave wrong complaints ("node tag 1 is defined twice" for a cut "12") */
  if (r->pos >= r->len)
    msh_fail(r, r->tokline, "unexpected end of file in '%s' while reading %s (truncated file?)", r->tok, what);
}

static long msh_long(Msh *r, const char *what) {
  msh_need(r, what);
  char *end;
  errno = 0;
  long v = strtol(r->tok, &end, 10);
  if (end == r->tok || *end != '\0' || errno == ERANGE)
    msh_fail(r, r->tokline, "expected an integer for %s, found '%s'", what, r->tok);
  return v;
}

/* A real of the file, by the deck's rules (strictnum.h): strtod also took hex ("0x1p-1"), "inf"
 * and "nan" in a node's coordinates, numbers the deck refuses. */
static double msh_double(Msh *r, const char *what) {
  msh_need(r, what);
  double v;
  if (!yf_parse_double(r->tok, &v))
    msh_fail(r, r->tokline, "expected a number for %s, found '%s' (a finite decimal number: digits, an optional "
             "'.' and exponent, as in the deck)", what, r->tok);
  return v;
}

/* A physical tag, its sign dropped (in $Entities it gives an orientation), in 0..INT_MAX: labs of
 * the smallest long is undefined. */
static long rd_int(Msh *r, const char *what);
static long msh_phys(Msh *r, const char *what) {
  long t = rd_int(r, what);
  if (t < -INT_MAX || t > INT_MAX) msh_fail(r, r->tokline, "%s %ld is not in -%d..%d", what, t, INT_MAX, INT_MAX);
  return labs(t);
}

static void msh_expect(Msh *r, const char *word, const char *why) {
  if (!msh_next(r))
    msh_fail(r, r->line, "unexpected end of file: %s is missing (truncated file?)", word);
  if (strcmp(r->tok, word) != 0 && r->pos >= r->len && !strncmp(word, r->tok, strlen(r->tok)))
    msh_fail(r, r->tokline, "unexpected end of file in '%s': %s is cut short (truncated file?)", r->tok, word);
  if (strcmp(r->tok, word) != 0)
    msh_fail(r, r->tokline, "expected %s, found '%s'%s", word, r->tok, why);
}

/* Skip an unused section up to its $End marker. */
static void msh_skip_section(Msh *r) {
  char end[300];
  int line0 = r->tokline;
  snprintf(end, sizeof end, "$End%s", r->tok + 1);
  size_t n = strlen(end);
  /* the marker as a word, found by a plain search: read as words, the binary data of a section
   * (a $NodeData in a binary file) held runs of bytes longer than a word may be ("a word longer
   * than 255 characters") */
  const char *lim = r->buf + r->len;
  for (const char *p = r->buf + r->pos; (p = memmem(p, (size_t)(lim - p), end, n)); p++) {
    if (p > r->buf && !isspace((unsigned char)p[-1])) continue;
    if (p + n < lim && !isspace((unsigned char)p[n])) continue;
    for (const char *q = r->buf + r->pos; (q = memchr(q, '\n', (size_t)(p - q))); q++) r->line++;
    r->pos = (size_t)(p + n - r->buf);
    r->tokline = r->line;
    return;
  }
  msh_fail(r, line0, "section $%s is not closed by %s (truncated file?)", end + 4, end);
}

static const char *elem_name(long type) {
  switch (type) {
  case 1: return "2-node line";
  case 2: return "3-node triangle";
  case 3: return "4-node quadrangle";
  case 4: return "4-node tetrahedron";
  case 5: return "8-node hexahedron";
  case 6: return "6-node prism";
  case 7: return "5-node pyramid";
  case 8: return "3-node line";
  case 9: return "6-node triangle";
  case 10: return "9-node quadrangle";
  case 11: return "10-node tetrahedron";
  case 15: return "1-node point";
  case 16: return "8-node quadrangle";
  case 21: return "10-node triangle";
  default: return "unknown type";
  }
}

static const char *const dim_word[4] = {"point", "curve", "surface", "volume"};

static void unsupported(Msh *r, int line, long type, int dim, long etag) {
  msh_fail(r, line, "element type %ld (%s) in %s %ld is not supported: yfdem reads 3-node triangles "
           "(type 2) in surfaces, 2-node lines (type 1) in physical curves and points (type 15) in "
           "physical points; mesh 2D with Mesh.ElementOrder = 1 and without recombination",
           type, elem_name(type), dim_word[dim], etag);
}

/* Binary MSH 2.2: after an ASCII count, the rest of its line, then the binary data. */
static void bin_begin(Msh *r, const char *what) {
  if (!msh_eol(r))
    msh_fail(r, r->line, "expected the end of the line before the binary data of %s, found '%c'", what, r->buf[r->pos]);
  if (r->pos >= r->len) msh_fail(r, r->line, "unexpected end of file before the binary data of %s (truncated file?)", what);
  r->pos++;
  r->line++;
}

/* The next n bytes of binary data (newline bytes in them still count as lines, as an editor
 * shows them); refused when the file ends first. */
static const unsigned char *bin_bytes(Msh *r, size_t n, const char *what) {
  if (r->len - r->pos < n)
    msh_fail(r, r->line, "unexpected end of file in the binary data of %s (truncated file?)", what);
  const unsigned char *p = (const unsigned char *)r->buf + r->pos;
  for (const char *q = r->buf + r->pos; (q = memchr(q, '\n', (size_t)(r->buf + r->pos + n - q))); q++) r->line++;
  r->pos += n;
  return p;
}

static void bin_swap(unsigned char *b, int n) {
  for (int i = 0; i < n / 2; i++) {
    unsigned char t = b[i];
    b[i] = b[n - 1 - i];
    b[n - 1 - i] = t;
  }
}

static long bin_int(const Msh *r, const unsigned char *p) {
  unsigned char b[4];
  memcpy(b, p, 4);
  if (r->swap) bin_swap(b, 4);
  int32_t v;
  memcpy(&v, b, 4);
  return v;
}

static double bin_double(const Msh *r, const unsigned char *p) {
  unsigned char b[8];
  memcpy(b, p, 8);
  if (r->swap) bin_swap(b, 8);
  double v;
  memcpy(&v, b, 8);
  return v;
}

/* The values of MSH 4.1 sections, ASCII or binary (r->b41).  Binary MSH 4.1 writes counts and
 * node and element tags as size_t (the header's data size: 8 bytes), entity tags, dimensions,
 * types and physical tags as 4-byte ints, and reals as 8-byte doubles, all in the byte order of
 * the header's integer 1; ASCII writes them all as words.  One reader serves both. */
static const unsigned char *rd_bin(Msh *r, size_t n) {
  r->binat = r->pos;
  r->tokline = r->line;
  return bin_bytes(r, n, r->section ? r->section : "the file");
}

/* A count or a node or element tag (binary: size_t). */
static long rd_size(Msh *r, const char *what) {
  if (!r->b41) return msh_long(r, what);
  unsigned char b[8];
  memcpy(b, rd_bin(r, 8), 8);
  if (r->swap) bin_swap(b, 8);
  uint64_t v;
  memcpy(&v, b, 8);
  if (v > LONG_MAX) /* a negative count written as a signed integer reads as one beyond 2^63: said so */
    msh_fail(r, r->tokline, "%s is %llu, beyond %ld (read as a signed integer: %lld)", what, (unsigned long long)v,
             LONG_MAX, (long long)v);
  return (long)v;
}

/* An entity tag, dimension, element type, flag or physical tag (binary: int). */
static long rd_int(Msh *r, const char *what) {
  if (!r->b41) return msh_long(r, what);
  return bin_int(r, rd_bin(r, 4));
}

/* A coordinate (binary: double, refused unless finite as the deck refuses "inf" and "nan"). */
static double rd_double(Msh *r, const char *what) {
  if (!r->b41) return msh_double(r, what);
  double v = bin_double(r, rd_bin(r, 8));
  if (!isfinite(v)) msh_fail(r, r->tokline, "%s is not a finite number", what);
  return v;
}

/* The header of a MSH 4.1 $Nodes or $Elements section (what: "node" or "element"): the number of
 * blocks, the number of nodes or elements, the smallest and the largest tag.  A count out of range is
 * refused naming it and, in a binary file, its own bytes (the header's first byte was named for any).
 * Returns the total; *nblk the number of blocks, *hline the header's line, *at_ntot where the total's
 * bytes are, for the complaints about it once the blocks are read (r->binat is left there). */
static long rd_header41(Msh *r, const char *what, long *nblk, int *hline, size_t *at_ntot) {
  char total[48], lo[48], hi[48];
  snprintf(total, sizeof total, "the number of %ss", what);
  snprintf(lo, sizeof lo, "the smallest %s tag", what);
  snprintf(hi, sizeof hi, "the largest %s tag", what);
  *nblk = rd_size(r, "the number of entity blocks");
  *hline = r->tokline;
  const size_t at_nblk = r->binat;
  const long ntot = rd_size(r, total);
  *at_ntot = r->binat;
  rd_size(r, lo);
  rd_size(r, hi);
  const int blocks = *nblk < 0; /* the field at fault: ASCII counts can be negative, binary ones too large */
  r->binat = blocks ? at_nblk : *at_ntot;
  if (blocks || ntot < 0 || ntot > INT_MAX / 4) {
    char why[48] = "negative";
    if (!blocks && ntot > 0) snprintf(why, sizeof why, "above %d", INT_MAX / 4);
    msh_fail(r, *hline, "bad counts in the %s header (%ld blocks, %ld %ss): %s, %ld, is %s", r->section, *nblk, ntot,
             what, blocks ? "the number of entity blocks" : total, blocks ? *nblk : ntot, why);
  }
  r->binat = *at_ntot;
  return ntot;
}

/* Into the binary data of a MSH 4.1 section (r->section), after its name's line. */
static void rd_begin(Msh *r) {
  if (!r->b41) return;
  bin_begin(r, r->section);
  r->inbin = 1;
  r->binat = r->pos;
}

/* Out of it, at the newline Gmsh writes before the end marker. */
static void rd_end(Msh *r) {
  r->inbin = 0;
}

/* Nodes of a Gmsh element type (a binary element block does not say it), or -1. */
static int elem_nodes(long type) {
  static const signed char n[32] = {-1, 2, 3, 4, 4, 8, 6, 5, 3, 6, 9, 10, 27, 18, 14, 1,
                                    8, 20, 15, 13, 9, 10, 12, 15, 15, 21, 4, 5, 6, 20, 35, 56};
  return type >= 0 && type < 32 ? n[type] : -1;
}

static char *slurp(const char *path, const YfLoc *from, size_t *len) {
  char *buf = yf_read_file(path, len, "mesh file");
  if (!buf) yf_io_error(from, "mesh gmsh: cannot open '%s': %s", path, strerror(errno));
  /* a binary file is left as it is: its CR bytes are data */
  char ver[16];
  int ft;
  if (sscanf(buf, " $MeshFormat %15s %d", ver, &ft) == 2 && ft == 1) return buf;
  /* a CR alone ends a line (classic Mac text), as in every text yfdem reads; CRLF is left */
  for (size_t i = 0; i < *len; i++)
    if (buf[i] == '\r') { /* CRs before a LF (CRLF, CR CR LF) stay blanks */
      size_t k = i;
      while (k < *len && buf[k] == '\r') k++;
      if (k >= *len || buf[k] != '\n') buf[i] = '\n';
    }
  return buf;
}

/* Coincident nodes: order by (x, y). */
static int by_xy(const void *a, const void *b, void *ctx) {
  const double *const *c = ctx;
  long i = *(const long *)a, j = *(const long *)b;
  if (c[0][i] != c[0][j]) return c[0][i] < c[0][j] ? -1 : 1;
  if (c[1][i] != c[1][j]) return c[1][i] < c[1][j] ? -1 : 1;
  return i < j ? -1 : i > j;
}

/* Triangle corners that share a position with another one (a mesh written without "Coherence",
 * or two surfaces meshed apart): they are not connected, so the body would fall apart along
 * them in silence.  Warn with the count and the first pair (Gmsh tags). */
static void warn_coincident(const char *path, const YfLoc *from, const double *nx, const double *ny,
                            const long *ntag, const int *used, long nn) {
  long *ix = yf_malloc((size_t)(nn ? nn : 1) * sizeof *ix, "mesh nodes"), k = 0;
  for (long i = 0; i < nn; i++)
    if (used[i]) ix[k++] = i;
  const double *c[2] = {nx, ny};
  qsort_r(ix, (size_t)k, sizeof *ix, by_xy, c);
  long dup = 0, a = -1, b = -1;
  for (long i = 1; i < k; i++)
    if (nx[ix[i]] == nx[ix[i - 1]] && ny[ix[i]] == ny[ix[i - 1]]) {
      if (!dup++) a = ix[i - 1], b = ix[i];
    }
  if (dup)
    yf_warn(from, "mesh gmsh: %ld node%s of '%s' coincide%s with another node (first: nodes %ld and %ld at "
            "(%g, %g)): the triangles on either side are not connected there (duplicated nodes: use "
            "Coherence Mesh in Gmsh, or Geometry.AutoCoherence, if they should be one)", dup, dup == 1 ? "" : "s",
            path, dup == 1 ? "s" : "", ntag[a], ntag[b], nx[a], ny[a]);
  free(ix);
}

/* Flatness of the nodes read so far.  The mesh must lie in a plane z = constant (a section drawn
 * at z = 5 is as 2D as one at z = 0: its z is dropped); the first node's z is the plane's. */
typedef struct {
  double zmax, ext, zref, zat;
  int zline;
  long zntag;
} Flat;

/* Room for ntot nodes, once the memory they need is known to be there. */
static void nodes_alloc(Msh *r, int hline, long ntot, long **ntag, double **nx, double **ny, int **used) {
  /* binary: the least a node takes in the file, a size_t (4.1) or int (2.2) tag and 3 doubles.  A
   * count beyond what the rest of the file holds (a flipped byte of the count, a cut file) is
   * refused before its memory is taken (ASCII: the data read says where it ends) */
  size_t per = r->b41 ? 32 : 28, left = r->len - r->pos;
  if (r->bin && (double)ntot * (double)per > (double)left)
    msh_fail(r, hline, "%ld nodes take at least %.0f bytes, more than the %zu left in the file: a wrong count, or "
             "(truncated file?)", ntot, (double)ntot * (double)per, left);
  if ((double)ntot * (25.0 + YF_BYTES_PER_NODE) > yf_mem_cap()) /* before allocating */
    msh_fail(r, hline, "%ld nodes need about %.3g GB of memory, more than the %.3g GB available", ntot,
             (double)ntot * (25.0 + YF_BYTES_PER_NODE) / 1e9, yf_mem_cap() / 1e9);
  *ntag = yf_malloc((size_t)(ntot ? ntot : 1) * sizeof **ntag, "mesh nodes");
  *nx = yf_malloc((size_t)(ntot ? ntot : 1) * sizeof **nx, "mesh nodes");
  *ny = yf_malloc((size_t)(ntot ? ntot : 1) * sizeof **ny, "mesh nodes");
  *used = yf_calloc((size_t)(ntot ? ntot : 1), sizeof **used, "mesh nodes");
}

/* Node i (tag) at x y z (file line cline): scaled into nx, ny, z into f. */
static void node_put(Msh *r, double scale, Flat *f, long i, long tag, double *nx, double *ny, double x, double y,
                     double z, int cline) {
  nx[i] = x * scale;
  ny[i] = y * scale;
  if (!(fabs(nx[i]) <= YF_RANGE_MAX && fabs(ny[i]) <= YF_RANGE_MAX))
    msh_fail(r, cline, "node %ld at (%g, %g) m is beyond +-%g m, the range the arithmetic holds "
             "(areas and energies multiply coordinates)", tag, nx[i], ny[i], YF_RANGE_MAX);
  f->ext = fmax(f->ext, fmax(fabs(x), fabs(y)));
  if (i == 0) f->zref = z;
  if (fabs(z - f->zref) > f->zmax) {
    f->zmax = fabs(z - f->zref);
    f->zat = z;
    f->zline = cline;
    f->zntag = tag;
  }
}

/* x y z of node i (tag), then `extra` parametric coordinates. */
static void node_xyz(Msh *r, double scale, Flat *f, long i, long tag, double *nx, double *ny, int extra) {
  double x = rd_double(r, "a node x");
  int cline = r->tokline;
  double y = rd_double(r, "a node y");
  double z = rd_double(r, "a node z");
  for (int k = 0; k < extra; k++) rd_double(r, "a parametric coordinate");
  node_put(r, scale, f, i, tag, nx, ny, x, y, z, cline);
}

static void nodes_flat(Msh *r, const Flat *f, long tag0) {
  if (f->zmax > 1e-9 * fmax(f->ext, fabs(f->zref)))
    msh_fail(r, f->zline, "node %ld has z = %g where node %ld has z = %g: yfdem is 2D and needs a flat mesh, in "
             "one plane z = constant (such as z = 0)", f->zntag, f->zat, tag0, f->zref);
}

/* Node tag k of element tag (of type, on file line line) from the word just read; want: how many
 * its line must hold. */
static void elem_tag_word(Msh *r, long line, long tag, int type, int want, int k, long *nt) {
  if (k >= want) msh_fail(r, line, "element %ld (%s) has more than %d node tags on its line", tag, elem_name(type), want);
  char *end;
  errno = 0;
  nt[k] = strtol(r->tok, &end, 10);
  if (end == r->tok || *end != '\0' || errno == ERANGE)
    msh_fail(r, line, "expected an integer node tag in element %ld, found '%s'", tag, r->tok);
}

/* The want corners of element tag as node indices (v), from its k node tags nt. */
static void elem_corners(Msh *r, long line, const YfIdMap *nmap, const long *nt, int k, int want, long tag,
                         int type, int *v) {
  if (k < want)
    msh_fail(r, line, "element %ld (%s) has %d node tags on its line, expected %d", tag, elem_name(type), k, want);
  for (int j = 0; j < want; j++) {
    v[j] = idmap_get(nmap, nt[j]);
    if (v[j] < 0) msh_fail(r, line, "node %ld of element %ld is not defined in $Nodes", nt[j], tag);
  }
}

/* A point or line element's nodes as (entity, node) pairs, for its physical groups. */
static void pair_add(int **pair, long *npair, long *cappair, int ei, const int *v, int want) {
  if (*npair + want > *cappair) {
    *cappair = *cappair ? 2 * *cappair : 256;
    *pair = yf_realloc(*pair, (size_t)*cappair * 2 * sizeof **pair, "group nodes");
  }
  for (int j = 0; j < want; j++) {
    (*pair)[2 * *npair] = ei;
    (*pair)[2 * *npair + 1] = v[j];
    (*npair)++;
  }
}

/* A triangle's tag and area checked (positions nx, ny after scale), its corners v made
 * counter-clockwise. */
static void tri_checked(Msh *r, long line, long tag, const long *nt, const double *nx, const double *ny, int *v) {
  if (tag <= 0 || tag > INT_MAX) msh_fail(r, line, "element tag %ld is not in 1..%d", tag, INT_MAX);
  double d;
  if (mesh_tri_degenerate(nx[v[0]], ny[v[0]], nx[v[1]], ny[v[1]], nx[v[2]], ny[v[2]], &d))
    msh_fail(r, line, "triangle %ld has zero area (nodes %ld %ld %ld; area %g m^2 after scale)", tag, nt[0], nt[1],
             nt[2], 0.5 * fabs(d));
  if (d < 0) { /* clockwise in the file: swap two corners */
    int t = v[1];
    v[1] = v[2];
    v[2] = t;
  }
}

/* What to do with an element of dimension edim and type in entity etag (physical: the entity is in
 * a physical group): 1 a triangle, 2 its nodes join the groups, 0 skipped (points and curves in
 * no group); *want: node tags per element.  3D and higher-order elements are refused. */
static int elem_keep(Msh *r, long line, int edim, long type, long etag, int physical, int *want) {
  if (edim == 3) msh_fail(r, line, "3D elements (%s) in volume %ld: yfdem is 2D (mesh with gmsh -2)", elem_name(type), etag);
  if (edim == 2) {
    if (type != 2) unsupported(r, line, type, 2, etag);
    *want = 3;
    return 1;
  }
  if (!physical) {
    *want = 0;
    return 0;
  }
  if (edim == 1) {
    if (type != 1) unsupported(r, line, type, 1, etag);
    *want = 2;
    return 2;
  }
  if (type != 15) unsupported(r, line, type, 0, etag);
  *want = 1;
  return 2;
}

static int ent_find(const YfIdMap *emap, int dim, long tag) {
  return idmap_get(emap, (long long)tag * 4 + dim);
}

/* Dimension of a Gmsh element type (MSH 2.2 element lines do not say it), or -1 for a type
 * yfdem does not know. */
static int elem_dim(long type) {
  switch (type) {
  case 15: return 0;
  case 1: case 8: case 26: case 27: case 28: return 1;
  case 2: case 3: case 9: case 10: case 16: case 20: case 21: case 22: case 23: case 24: case 25: return 2;
  case 4: case 5: case 6: case 7: case 11: case 12: case 13: case 14: case 17: case 18: case 19: case 29:
  case 30: case 31: return 3;
  default: return -1;
  }
}

/* MSH 2.2 has no $Entities: an entity here is what the elements tell, one per dimension,
 * elementary tag and set of physical tags (phys[0..np)), so that the rest of the reader treats
 * it as a 4.1 entity with those physical groups.  Found or made; `el` is the element asking. */
static int ent22(Ent **ent, int *nent, int *capent, long **pool, int *npool, int *cappool, YfIdMap *emap,
                 int dim, long etag, const long *phys, int np, long el) {
  long long key = (long long)etag * 4 + dim;
  int e = idmap_get(emap, key), last = -1;
  for (; e >= 0; last = e, e = (*ent)[e].next) {
    const Ent *q = &(*ent)[e];
    if (q->nphys == np && (!np || !memcmp(*pool + q->off, phys, (size_t)np * sizeof *phys))) return e;
  }
  if (*nent == *capent) {
    *capent = *capent ? 2 * *capent : 64;
    *ent = yf_realloc(*ent, (size_t)*capent * sizeof **ent, "entities");
  }
  if (*npool + np > *cappool) {
    while (*npool + np > *cappool) *cappool = *cappool ? 2 * *cappool : 256;
    *pool = yf_realloc(*pool, (size_t)*cappool * sizeof **pool, "physical tags");
  }
  e = (*nent)++;
  Ent *q = &(*ent)[e];
  memset(q, 0, sizeof *q);
  q->dim = dim;
  q->tag = etag;
  q->off = *npool;
  q->nphys = np;
  q->mat = -1;
  q->next = -1;
  q->el = el;
  if (np) memcpy(*pool + *npool, phys, (size_t)np * sizeof *phys); /* phys may be NULL when np is 0 */
  *npool += np;
  if (last >= 0) (*ent)[last].next = e;
  else idmap_put(emap, key, e);
  return e;
}

/* Triangles of a MSH 2.2 file by their corners (sorted), then by their order in the file. */
static int by_corners(const void *a, const void *b, void *ctx) {
  const int *c = ctx;
  long i = *(const long *)a, j = *(const long *)b;
  for (int k = 0; k < 3; k++)
    if (c[3 * i + k] != c[3 * j + k]) return c[3 * i + k] < c[3 * j + k] ? -1 : 1;
  return i < j ? -1 : i > j;
}

int gmsh_read(YfModel *m, const char *path, const YfGmshOpts *o) {
  Msh rd = {0}, *r = &rd;
  r->fname = path;
  r->from = &o->from;
  r->line = 1;
  r->buf = slurp(path, &o->from, &r->len);

  int nent = 0, capent = 0, npool = 0, cappool = 0;
  Ent *ent = NULL;
  long *pool = NULL;
  YfIdMap emap, pmap; /* entities of $Entities and of $PartitionedEntities, by tag * 4 + dim */
  idmap_init(&emap);
  idmap_init(&pmap);
  int npn = 0;
  PhysName *pn = NULL;

  /* nodes of the file (local index = order in $Nodes) */
  long nn = 0;
  long *ntag = NULL;
  double *nx = NULL, *ny = NULL;
  int *used = NULL;
  YfIdMap nmap;
  idmap_init(&nmap);

  /* triangles, and (entity, node) pairs of physical points and curves */
  long ntri = 0, captri = 0;
  int *tv = NULL, *tent = NULL;
  long *ttag = NULL;
  long npair = 0, cappair = 0;
  int *pair = NULL; /* 2 per pair: entity, local node */

  int have_fmt = 0, have_ent = 0, have_pent = 0, have_nodes = 0, have_elems = 0;
  int msh2 = 0; /* MSH 2.2: other $Nodes and $Elements layouts, no $Entities */
  long nphys22 = 0; /* MSH 2.2: elements in a physical group */

  while (msh_next(r)) {
    r->section = NULL;
    if (!have_fmt && strcmp(r->tok, "$MeshFormat") != 0)
      msh_fail(r, r->tokline, "not a Gmsh mesh: the file must start with $MeshFormat (found '%s')", r->tok);
    if (r->tok[0] != '$')
      msh_fail(r, r->tokline, "expected a section name such as $Nodes, found '%s'", r->tok);

    if (!strcmp(r->tok, "$MeshFormat")) {
      if (have_fmt) msh_fail(r, r->tokline, "a second $MeshFormat section");
      r->section = "$MeshFormat";
      msh_need(r, "the version");
      char ver[sizeof r->tok];
      memcpy(ver, r->tok, sizeof ver);
      int vline = r->tokline;
      double v;
      /* MSH 2.0 and 2.1 (early Gmsh 2 releases) write $Nodes and $Elements as 2.2 does; only the tags
       * after an element's first two (physical, elementary) differ, its partition where 2.2 has
       * the number of partitions and their list, and the reader skips them */
      int v2old = yf_parse_double(ver, &v) && (fabs(v - 2.0) <= 1e-9 || fabs(v - 2.1) <= 1e-9);
      if (!yf_parse_double(ver, &v) || (fabs(v - 4.1) > 1e-9 && fabs(v - 2.2) > 1e-9 && !v2old))
        msh_fail(r, vline, "MSH version %s is not supported: yfdem reads MSH 4.1 and 2.2 (ASCII or binary) and "
                 "2.0 and 2.1 (ASCII); save with gmsh -format msh41, or Mesh.MshFileVersion = 4.1", ver);
      msh2 = v < 3;
      long ft = msh_long(r, "the file type");
      if (ft == 1 && v2old)
        msh_fail(r, r->tokline, "binary MSH %s files are not supported: save as MSH 4.1 or 2.2 (binary or not), or "
                 "as ASCII (Mesh.Binary = 0)", ver);
      if (ft != 0 && ft != 1) msh_fail(r, r->tokline, "file type %ld is neither 0 (ASCII) nor 1 (binary)", ft);
      long ds = msh_long(r, "the data size");
      r->bin = ft == 1;
      r->b41 = r->bin && !msh2;
      if (r->bin) {
        /* the size of a real, then the integer 1 written in binary, which tells the byte order */
        if (ds != 8)
          msh_fail(r, r->tokline, "data size %ld: yfdem reads binary files of 8-byte reals and (MSH 4.1) 8-byte "
                   "size_t (as Gmsh writes them)", ds);
        bin_begin(r, "$MeshFormat");
        const unsigned char *one = bin_bytes(r, 4, "$MeshFormat");
        long v1 = bin_int(r, one);
        if (v1 != 1) {
          r->swap = 1;
          if (bin_int(r, one) != 1)
            msh_fail(r, r->line, "the binary integer after the version line is %ld, not 1 in either byte order", v1);
        }
      }
      /* an ASCII mesh has no NUL bytes; a binary one mislabelled as ASCII would be misread (and
       * said "expected $EndMeshFormat, found ''" at its binary integer 1) */
      const char *nul = r->bin ? NULL : memchr(r->buf, '\0', r->len);
      if (nul) {
        int line = 1;
        for (const char *p = r->buf; p < nul; p++) line += *p == '\n';
        msh_fail(r, line, "the file contains binary data although $MeshFormat says ASCII");
      }
      msh_expect(r, "$EndMeshFormat", "");
      have_fmt = 1;

    } else if (!strcmp(r->tok, "$PhysicalNames")) {
      r->section = "$PhysicalNames";
      long n = msh_long(r, "the number of physical names");
      if (n < 0 || n > 1000000) msh_fail(r, r->tokline, "bad number of physical names %ld", n);
      pn = yf_realloc(pn, (size_t)(npn + n) * sizeof *pn, "physical names");
      for (long i = 0; i < n; i++) {
        PhysName *p = &pn[npn];
        long dim = msh_long(r, "the dimension of a physical name");
        if (dim < 0 || dim > 3) msh_fail(r, r->tokline, "physical name dimension %ld is not 0..3", dim);
        p->dim = (int)dim;
        p->tag = msh_long(r, "the tag of a physical name");
        /* the name is a quoted string on the same line, spaces allowed */
        if (msh_eol(r))
          msh_fail(r, r->line, r->pos >= r->len ? "unexpected end of file: physical group %ld has no name (truncated "
                   "file?)" : "physical group %ld has no name", p->tag);
        if (r->buf[r->pos] != '"')
          msh_fail(r, r->line, "the name of physical group %ld must be in double quotes", p->tag);
        size_t k = 0, q = r->pos + 1;
        while (q < r->len && r->buf[q] != '"' && r->buf[q] != '\n') {
          if (k + 1 >= sizeof p->name) msh_fail(r, r->line, "physical name longer than %zu characters", sizeof p->name - 1);
          p->name[k++] = r->buf[q++];
        }
        if (q >= r->len) msh_fail(r, r->line, "unexpected end of file in the name of physical group %ld (truncated file?)", p->tag);
        if (r->buf[q] != '"') msh_fail(r, r->line, "unterminated physical name");
        p->name[k] = '\0';
        r->pos = q + 1;
        if (k == 0) msh_fail(r, r->line, "physical group %ld has an empty name", p->tag);
        for (int j = 0; j < npn; j++)
          if (pn[j].dim == p->dim && pn[j].tag == p->tag)
            msh_fail(r, r->line, "physical %s %ld is named twice", dim_word[p->dim], p->tag);
        npn++;
      }
      msh_expect(r, "$EndPhysicalNames", " (more names than the count declares?)");

    } else if (!msh2 && (!strcmp(r->tok, "$Entities") || !strcmp(r->tok, "$PartitionedEntities"))) {
      /* a mesh partitioned in Gmsh keeps its elements in partition entities, listed in
       * $PartitionedEntities with the physical tags of their parents: elements refer to those */
      int part = !strcmp(r->tok, "$PartitionedEntities");
      if (part ? have_pent : have_ent) msh_fail(r, r->tokline, "a second %s section", r->tok);
      /* after the elements it came too late to give them their physical groups, and the surfaces
       * those elements had defined made it say "surface 1 is defined twice" */
      if (have_elems)
        msh_fail(r, r->tokline, "%s comes after $Elements: it must come before (as Gmsh writes it), since the "
                 "element blocks name its entities", r->tok);
      r->section = part ? "$PartitionedEntities" : "$Entities";
      YfIdMap *map = part ? &pmap : &emap;
      rd_begin(r);
      if (part) {
        long npart = rd_size(r, "the number of partitions");
        if (npart < 0) msh_fail(r, r->tokline, "bad number of partitions %ld", npart);
        long nghost = rd_size(r, "the number of ghost entities");
        if (nghost < 0 || nghost > 100000000) msh_fail(r, r->tokline, "bad number of ghost entities %ld", nghost);
        for (long k = 0; k < 2 * nghost; k++) rd_int(r, k % 2 ? "a ghost entity's partition" : "a ghost entity tag");
      }
      long cnt[4];
      for (int d = 0; d < 4; d++) {
        cnt[d] = rd_size(r, "the number of entities");
        if (cnt[d] < 0 || cnt[d] > 100000000) msh_fail(r, r->tokline, "bad entity count %ld", cnt[d]);
      }
      for (int d = 0; d < 4; d++)
        for (long i = 0; i < cnt[d]; i++) {
          char what[64];
          snprintf(what, sizeof what, "a %s entity", dim_word[d]);
          long tag = rd_int(r, what);
          int line = r->tokline;
          if (part) { /* parent dimension and tag, the partitions it belongs to */
            rd_int(r, "the parent's dimension");
            rd_int(r, "the parent's tag");
            long np = rd_size(r, "the number of partitions of an entity");
            if (np < 0 || np > 100000000) msh_fail(r, r->tokline, "bad number of partitions %ld", np);
            for (long k = 0; k < np; k++) rd_int(r, "a partition tag");
          }
          for (int k = 0; k < (d == 0 ? 3 : 6); k++) rd_double(r, d == 0 ? "a point coordinate" : "a bounding box");
          long np = rd_size(r, "the number of physical tags");
          if (np < 0 || np > 100000) msh_fail(r, r->tokline, "bad number of physical tags %ld", np);
          if (nent == capent) {
            capent = capent ? 2 * capent : 64;
            ent = yf_realloc(ent, (size_t)capent * sizeof *ent, "entities");
          }
          if (npool + np > cappool) {
            while (npool + np > cappool) cappool = cappool ? 2 * cappool : 256;
            pool = yf_realloc(pool, (size_t)cappool * sizeof *pool, "physical tags");
          }
          Ent *e = &ent[nent];
          memset(e, 0, sizeof *e);
          e->dim = d;
          e->tag = tag;
          e->off = npool;
          e->nphys = (int)np;
          e->mat = -1;
          for (long k = 0; k < np; k++) pool[npool++] = msh_phys(r, "a physical tag");
          if (d > 0) {
            long nb = rd_size(r, "the number of bounding entities");
            if (nb < 0 || nb > 100000000) msh_fail(r, r->tokline, "bad number of bounding entities %ld", nb);
            for (long k = 0; k < nb; k++) rd_int(r, "a bounding entity tag");
          }
          if (!idmap_put(map, (long long)tag * 4 + d, nent))
            msh_fail(r, line, "%s %ld is defined twice", dim_word[d], tag);
          nent++;
        }
      rd_end(r);
      msh_expect(r, part ? "$EndPartitionedEntities" : "$EndEntities", " (more entities than the counts declare?)");
      if (part) have_pent = 1;
      else have_ent = 1;

    } else if ((!strcmp(r->tok, "$Nodes") || !strcmp(r->tok, "$ParametricNodes")) && msh2) {
      /* MSH 2.2: the count, then one "tag x y z" line per node; $ParametricNodes (Gmsh's
       * Mesh.SaveParametric) adds the node's entity, "dim tag", and its u (curves) or u v
       * (surfaces) */
      int par = !strcmp(r->tok, "$ParametricNodes");
      if (have_nodes) msh_fail(r, r->tokline, "a second %s section", par ? "$Nodes or $ParametricNodes" : "$Nodes");
      r->section = par ? "$ParametricNodes" : "$Nodes";
      if (par && r->bin)
        msh_fail(r, r->tokline, "binary $ParametricNodes are not supported: save without Mesh.SaveParametric, or as ASCII");
      long ntot = msh_long(r, "the number of nodes");
      int hline = r->tokline;
      if (ntot < 0 || ntot > INT_MAX / 4) msh_fail(r, hline, "bad number of nodes %ld", ntot);
      nodes_alloc(r, hline, ntot, &ntag, &nx, &ny, &used);
      Flat f = {0};
      if (r->bin) bin_begin(r, "$Nodes");
      for (; nn < ntot; nn++) {
        if (r->bin) { /* int tag, 3 doubles; messages name the line of the count */
          const unsigned char *p = bin_bytes(r, 28, "$Nodes");
          long t = bin_int(r, p);
          double c[3];
          for (int k = 0; k < 3; k++) c[k] = bin_double(r, p + 4 + 8 * k);
          if (t <= 0 || t > INT_MAX) msh_fail(r, hline, "node %ld of the binary data: tag %ld is not in 1..%d", nn + 1, t, INT_MAX);
          if (!idmap_put(&nmap, t, (int)nn)) msh_fail(r, hline, "node tag %ld is defined twice (binary data)", t);
          if (!isfinite(c[0]) || !isfinite(c[1]) || !isfinite(c[2]))
            msh_fail(r, hline, "node %ld has a coordinate that is not a finite number (%g, %g, %g) (binary data)", t,
                     c[0], c[1], c[2]);
          ntag[nn] = t;
          node_put(r, o->scale, &f, nn, t, nx, ny, c[0], c[1], c[2], hline);
          continue;
        }
        long t = msh_long(r, "a node tag");
        if (t <= 0 || t > INT_MAX) msh_fail(r, r->tokline, "node tag %ld is not in 1..%d", t, INT_MAX);
        if (!idmap_put(&nmap, t, (int)nn)) msh_fail(r, r->tokline, "node tag %ld is defined twice", t);
        ntag[nn] = t;
        node_xyz(r, o->scale, &f, nn, t, nx, ny, 0);
        if (par && !msh_eol(r)) {
          int line = r->line;
          long dim = msh_long(r, "the dimension of a node's entity");
          if (dim < 0 || dim > 3) msh_fail(r, line, "node %ld: entity dimension %ld is not 0..3", t, dim);
          msh_long(r, "the tag of a node's entity");
          for (long k = 0; k < (dim == 1 || dim == 2 ? dim : 0); k++) msh_double(r, "a parametric coordinate");
        }
        if (!msh_eol(r)) {
          int line = r->line;
          msh_next(r);
          msh_fail(r, line, "node %ld: '%s' after its %s on its line", t, r->tok,
                   par ? "coordinates, entity and parametric coordinates" : "x y z");
        }
      }
      msh_expect(r, par ? "$EndParametricNodes" : "$EndNodes", " (more nodes than the count declares?)");
      nodes_flat(r, &f, nn ? ntag[0] : 0);
      have_nodes = 1;

    } else if (!strcmp(r->tok, "$Nodes")) {
      if (have_nodes) msh_fail(r, r->tokline, "a second $Nodes section");
      r->section = "$Nodes";
      rd_begin(r);
      long nblk;
      int hline;
      size_t at_ntot;
      long ntot = rd_header41(r, "node", &nblk, &hline, &at_ntot);
      nodes_alloc(r, hline, ntot, &ntag, &nx, &ny, &used);
      Flat f = {0};
      for (long b = 0; b < nblk; b++) {
        long edim = rd_int(r, "the entity dimension of a node block");
        int bline = r->tokline;
        if (edim < 0 || edim > 3) msh_fail(r, bline, "entity dimension %ld is not 0..3", edim);
        rd_int(r, "the entity tag of a node block");
        long par = rd_int(r, "the parametric flag");
        if (par != 0 && par != 1) msh_fail(r, r->tokline, "parametric flag %ld is neither 0 nor 1", par);
        long nin = rd_size(r, "the number of nodes in a block");
        if (nin < 0 || nin > ntot - nn)
          msh_fail(r, r->tokline, "node block %ld declares %ld nodes, more than the %ld left of the "
                   "header's total %ld", b + 1, nin, ntot - nn, ntot);
        for (long i = 0; i < nin; i++) {
          long t = rd_size(r, "a node tag");
          if (t <= 0 || t > INT_MAX) msh_fail(r, r->tokline, "node tag %ld is not in 1..%d", t, INT_MAX);
          if (!idmap_put(&nmap, t, (int)(nn + i))) msh_fail(r, r->tokline, "node tag %ld is defined twice", t);
          ntag[nn + i] = t;
        }
        int extra = par ? (int)edim : 0; /* parametric u (curves), u v (surfaces) */
        for (long i = 0; i < nin; i++) node_xyz(r, o->scale, &f, nn + i, ntag[nn + i], nx, ny, extra);
        nn += nin;
      }
      r->binat = at_ntot;
      if (nn != ntot)
        msh_fail(r, hline, "the blocks hold %ld nodes but the header declares %ld", nn, ntot);
      rd_end(r);
      msh_expect(r, "$EndNodes", " (the header's block count does not match the data?)");
      nodes_flat(r, &f, nn ? ntag[0] : 0);
      have_nodes = 1;

    } else if (!strcmp(r->tok, "$Elements") && msh2) {
      /* MSH 2.2: the count, then one line per element: tag, type, the number of tags, the tags,
       * the node tags.  The first tag is the physical group (0: none), the second the elementary
       * entity; partitions follow in a partitioned mesh.  An element in several physical groups
       * is written once per group, each copy with an element tag of its own. */
      if (have_elems) msh_fail(r, r->tokline, "a second $Elements section");
      r->section = "$Elements";
      if (!have_nodes) msh_fail(r, r->tokline, "$Elements comes before $Nodes");
      long ntot = msh_long(r, "the number of elements");
      int hline = r->tokline;
      if (ntot < 0 || ntot > INT_MAX / 4) msh_fail(r, r->tokline, "bad number of elements %ld", ntot);
      /* binary: blocks of elements of one type and tag count, each a header (type, count, tags)
       * and the elements (tag, tags, node tags); messages name the line of the count */
      long bleft = 0, btype = 0, bntg = 0;
      if (r->bin) bin_begin(r, "$Elements");
      /* triangles as read, copies included: corners (counter-clockwise), tag, elementary tag, physical tag */
      long nraw = 0, capraw = 0;
      int *rv = NULL;
      long *rtag = NULL, *retag = NULL, *rphys = NULL;
      for (long i = 0; i < ntot; i++) {
        long tag, type, phys = 0, etag = 0, nt[3];
        int line, k = 0;
        if (r->bin) {
          if (!bleft) {
            const unsigned char *p = bin_bytes(r, 12, "$Elements");
            btype = bin_int(r, p), bleft = bin_int(r, p + 4), bntg = bin_int(r, p + 8);
            if (elem_nodes(btype) < 0)
              msh_fail(r, hline, "an element block of type %ld, no Gmsh element type yfdem knows (binary data, element %ld "
                       "of %ld): yfdem reads 3-node triangles (type 2), 2-node lines (type 1) and points (type 15)",
                       btype, i + 1, ntot);
            if (bleft <= 0 || bleft > ntot - i || bntg < 0 || bntg > 1000)
              msh_fail(r, hline, "an element block of %ld elements with %ld tags each, after %ld of the %ld elements "
                       "(binary data): the counts are wrong", bleft, bntg, i, ntot);
          }
          int nv = elem_nodes(btype);
          const unsigned char *p = bin_bytes(r, (size_t)(1 + bntg + nv) * 4, "$Elements");
          tag = bin_int(r, p);
          type = btype;
          if (bntg > 0) phys = labs(bin_int(r, p + 4));
          if (bntg > 1) etag = bin_int(r, p + 8);
          for (k = 0; k < nv && k < 3; k++) nt[k] = bin_int(r, p + 4 * (1 + bntg + k));
          if (nv > 3) k = nv;
          bleft--;
          line = hline;
        } else {
          tag = msh_long(r, "an element tag");
          line = r->tokline;
          type = msh_long(r, "the element type");
          long ntg = msh_long(r, "the number of tags of an element");
          if (ntg < 0 || ntg > 1000)
            msh_fail(r, r->tokline, "element %ld has %ld tags, expected 0 to 1000 (Gmsh writes 2: the physical "
                     "group and the elementary entity)", tag, ntg);
          for (long q = 0; q < ntg; q++) {
            if (q == 0) phys = msh_phys(r, "the physical tag of an element");
            else if (q == 1) etag = msh_long(r, "the elementary tag of an element");
            else msh_long(r, "a partition tag of an element");
          }
        }
        nphys22 += phys != 0;
        int edim = elem_dim(type);
        if (edim < 0)
          msh_fail(r, line, "element %ld has type %ld, no Gmsh element type yfdem knows: yfdem reads 3-node "
                   "triangles (type 2), 2-node lines (type 1) and points (type 15)", tag, type);
        int want; /* node tags per element; keep as 4.1 keeps (points and curves in no group skipped) */
        const int keep = elem_keep(r, line, edim, type, etag, phys != 0, &want);
        while (!r->bin && !msh_eol(r)) {
          msh_next(r);
          if (!keep) continue;
          elem_tag_word(r, line, tag, type, want, k, nt);
          k++;
        }
        if (!r->bin && r->pos >= r->len)
          msh_fail(r, r->line, "unexpected end of file in element %ld, %ld of %ld elements (truncated file?)",
                   tag, i + 1, ntot);
        if (!keep) continue;
        int v[3];
        elem_corners(r, line, &nmap, nt, k, want, tag, type, v);
        if (keep == 2) {
          int ei = ent22(&ent, &nent, &capent, &pool, &npool, &cappool, &emap, edim, etag, &phys, 1, tag);
          pair_add(&pair, &npair, &cappair, ei, v, want);
          continue;
        }
        tri_checked(r, line, tag, nt, nx, ny, v);
        if (nraw == capraw) {
          capraw = capraw ? 2 * capraw : 1024;
          rv = yf_realloc(rv, (size_t)capraw * 3 * sizeof *rv, "mesh triangles");
          rtag = yf_realloc(rtag, (size_t)capraw * sizeof *rtag, "mesh triangles");
          retag = yf_realloc(retag, (size_t)capraw * sizeof *retag, "mesh triangles");
          rphys = yf_realloc(rphys, (size_t)capraw * sizeof *rphys, "mesh triangles");
        }
        memcpy(rv + 3 * nraw, v, sizeof v);
        rtag[nraw] = tag;
        retag[nraw] = etag;
        rphys[nraw] = phys;
        nraw++;
      }
      msh_expect(r, "$EndElements", " (more elements than the count declares?)");

      /* The copies of a triangle (one per physical group) share their corners: sort by corners
       * to find them, keep the first copy (its tag and place), in all the copies' groups.  The
       * triangle's entity is the one of its elementary tag and that set of physical groups. */
      int *key = yf_malloc((size_t)(nraw ? 3 * nraw : 1) * sizeof *key, "mesh triangles");
      long *ord = yf_malloc((size_t)(nraw ? nraw : 1) * sizeof *ord, "mesh triangles");
      long *run = yf_malloc((size_t)(nraw ? nraw : 1) * sizeof *run, "mesh triangles");
      for (long t = 0; t < nraw; t++) {
        int a = rv[3 * t], b = rv[3 * t + 1], c = rv[3 * t + 2], s;
        if (a > b) s = a, a = b, b = s;
        if (b > c) s = b, b = c, c = s;
        if (a > b) s = a, a = b, b = s;
        key[3 * t] = a, key[3 * t + 1] = b, key[3 * t + 2] = c;
        ord[t] = t;
      }
      qsort_r(ord, (size_t)nraw, sizeof *ord, by_corners, key);
      /* run[t]: for the first copy, where its copies start in ord; -1 for the later copies */
      for (long j = 0; j < nraw; j++) {
        long j0 = j;
        while (j + 1 < nraw && !memcmp(key + 3 * ord[j + 1], key + 3 * ord[j0], 3 * sizeof *key)) run[ord[++j]] = -1;
        run[ord[j0]] = j0;
      }
      long *phl = NULL;
      int capphl = 0;
      for (long t = 0; t < nraw; t++) {
        if (run[t] < 0) continue;
        int np = 0;
        for (long j = run[t]; j < nraw && !memcmp(key + 3 * ord[j], key + 3 * t, 3 * sizeof *key); j++) {
          long p = rphys[ord[j]];
          int seen = !p;
          for (int q = 0; q < np && !seen; q++) seen = phl[q] == p;
          if (seen) continue;
          if (np == capphl) {
            capphl = capphl ? 2 * capphl : 8;
            phl = yf_realloc(phl, (size_t)capphl * sizeof *phl, "physical tags");
          }
          phl[np++] = p;
        }
        int ei = ent22(&ent, &nent, &capent, &pool, &npool, &cappool, &emap, 2, retag[t], phl, np, rtag[t]);
        if (ntri == captri) {
          captri = captri ? 2 * captri : 1024;
          tv = yf_realloc(tv, (size_t)captri * 3 * sizeof *tv, "mesh triangles");
          tent = yf_realloc(tent, (size_t)captri * sizeof *tent, "mesh triangles");
          ttag = yf_realloc(ttag, (size_t)captri * sizeof *ttag, "mesh triangles");
        }
        memcpy(tv + 3 * ntri, rv + 3 * t, 3 * sizeof *tv);
        tent[ntri] = ei;
        ttag[ntri] = rtag[t];
        ntri++;
        ent[ei].ntri++;
        for (int j = 0; j < 3; j++) used[rv[3 * t + j]] = 1;
      }
      free(phl);
      free(run);
      free(ord);
      free(key);
      free(rv);
      free(rtag);
      free(retag);
      free(rphys);
      have_elems = 1;

    } else if (!strcmp(r->tok, "$Elements")) {
      if (have_elems) msh_fail(r, r->tokline, "a second $Elements section");
      r->section = "$Elements";
      if (!have_nodes) msh_fail(r, r->tokline, "$Elements comes before $Nodes");
      rd_begin(r);
      long nblk;
      int hline;
      size_t at_ntot;
      long ntot = rd_header41(r, "element", &nblk, &hline, &at_ntot);
      long ne = 0;
      for (long b = 0; b < nblk; b++) {
        long edim = rd_int(r, "the entity dimension of an element block");
        int bline = r->tokline;
        if (edim < 0 || edim > 3) msh_fail(r, bline, "entity dimension %ld is not 0..3", edim);
        /* binary: where the block's entity tag and type are, for the complaints about them below (read
         * on, the last value read was the block's count, and they named its bytes) */
        long etag = rd_int(r, "the entity tag of an element block");
        size_t at_etag = r->binat;
        long type = rd_int(r, "the element type");
        size_t at_type = r->binat;
        long nin = rd_size(r, "the number of elements in a block");
        if (nin < 0 || nin > ntot - ne)
          msh_fail(r, r->tokline, "element block %ld declares %ld elements, more than the %ld left of "
                   "the header's total %ld", b + 1, nin, ntot - ne, ntot);
        int ei = -1;
        r->binat = at_etag; /* the entity's complaints name its tag's bytes, the type's its own */
        if (have_pent) {
          ei = ent_find(&pmap, (int)edim, etag);
          if (ei < 0) msh_fail(r, bline, "the entity tag of an element block is %ld: %s %ld, which $PartitionedEntities "
                               "does not define", etag, dim_word[edim], etag);
        } else if (have_ent) {
          ei = ent_find(&emap, (int)edim, etag);
          if (ei < 0) msh_fail(r, bline, "the entity tag of an element block is %ld: %s %ld, which $Entities does not "
                               "define", etag, dim_word[edim], etag);
        }
        int physical = ei >= 0 && ent[ei].nphys > 0;
        int want; /* node tags per element */
        r->binat = at_type;
        const int keep = elem_keep(r, bline, edim, type, etag, physical, &want); /* 1 triangles, 2 group nodes, 0 skip */
        if (ei < 0 && keep == 1) {
          /* no $Entities: remember the surface so triangles still know where they came from */
          ei = ent_find(&emap, 2, etag);
          if (ei < 0) {
            if (nent == capent) {
              capent = capent ? 2 * capent : 64;
              ent = yf_realloc(ent, (size_t)capent * sizeof *ent, "entities");
            }
            memset(&ent[nent], 0, sizeof ent[nent]);
            ent[nent].dim = 2;
            ent[nent].tag = etag;
            ent[nent].mat = -1;
            ei = nent++;
            idmap_put(&emap, (long long)etag * 4 + 2, ei);
          }
        }
        /* binary: the node tags of an element are as many as its type has (ASCII: its line's words) */
        const int nv = elem_nodes(type);
        if (r->b41 && nv < 0)
          msh_fail(r, bline, "element type %ld in %s %ld is no Gmsh element type yfdem knows, so its binary data "
                   "cannot be read past: yfdem reads 3-node triangles (type 2), 2-node lines (type 1) and points "
                   "(type 15)", type, dim_word[edim], etag);
        for (long i = 0; i < nin; i++) {
          long tag = rd_size(r, "an element tag");
          int line = r->tokline;
          long nt[3];
          int k = 0;
          for (int j = 0; r->b41 && j < nv; j++) {
            long w = rd_size(r, "a node tag of an element");
            if (keep && k < 3) nt[k++] = w; /* nv is want for the types kept */
          }
          while (!r->b41 && !msh_eol(r)) {
            msh_next(r);
            if (!keep) continue;
            elem_tag_word(r, line, tag, type, want, k, nt);
            k++;
          }
          /* a file cut inside an element's line said "has 0 node tags", not that it was cut */
          if (!r->b41 && r->pos >= r->len)
            msh_fail(r, r->line, "unexpected end of file in element %ld, %ld of %ld elements into its block "
                     "(truncated file?)", tag, i + 1, nin);
          if (!keep) continue;
          int v[3];
          elem_corners(r, line, &nmap, nt, k, want, tag, type, v);
          if (keep == 2) {
            pair_add(&pair, &npair, &cappair, ei, v, want);
            continue;
          }
          tri_checked(r, line, tag, nt, nx, ny, v);
          if (ntri == captri) {
            captri = captri ? 2 * captri : 1024;
            tv = yf_realloc(tv, (size_t)captri * 3 * sizeof *tv, "mesh triangles");
            tent = yf_realloc(tent, (size_t)captri * sizeof *tent, "mesh triangles");
            ttag = yf_realloc(ttag, (size_t)captri * sizeof *ttag, "mesh triangles");
          }
          memcpy(tv + 3 * ntri, v, sizeof v);
          tent[ntri] = ei;
          ttag[ntri] = tag;
          ntri++;
          ent[ei].ntri++;
          for (int j = 0; j < 3; j++) used[v[j]] = 1;
        }
        ne += nin;
      }
      r->binat = at_ntot;
      if (ne != ntot)
        msh_fail(r, hline, "the blocks hold %ld elements but the header declares %ld", ne, ntot);
      rd_end(r);
      msh_expect(r, "$EndElements", " (the header's block count does not match the data?)");
      have_elems = 1;

    } else if (!strncmp(r->tok, "$End", 4)) {
      msh_fail(r, r->tokline, "unexpected %s", r->tok);
    } else {
      msh_skip_section(r);
    }
  }
  r->section = NULL;
  if (!have_fmt) msh_fail(r, r->line, "not a Gmsh mesh: the file is empty");
  if (!have_nodes) msh_fail(r, r->line, "no $Nodes section (truncated file?)");
  if (!have_elems) msh_fail(r, r->line, "no $Elements section (truncated file?)");
  /* Gmsh's Mesh.SaveAll writes every element of a 2.2 file with physical tag 0, the names kept:
   * without a word the groups the user named were missing, or "no physical surface 'rock'" */
  if (msh2 && npn > 0 && !nphys22)
    yf_warn(&o->from, "mesh gmsh: '%s' names %d physical group%s in $PhysicalNames but no element is in one "
            "(physical tag 0 throughout, as Gmsh's Mesh.SaveAll writes MSH 2.2), so none becomes a group: save "
            "without Mesh.SaveAll, or as MSH 4.1", path, npn, npn == 1 ? "" : "s");
  if (ntri == 0)
    msh_fail(r, r->line, "no 3-node triangles in the file (mesh in 2D with gmsh -2)");

  /* ---- physical groups: names and group indices ---- */
  int nph = 0;
  Phys *ph = NULL;
  for (int e = 0; e < nent; e++) {
    if (ent[e].dim > 2) continue;
    for (int k = 0; k < ent[e].nphys; k++) {
      long tag = pool[ent[e].off + k];
      int j;
      for (j = 0; j < nph; j++)
        if (ph[j].dim == ent[e].dim && ph[j].tag == tag) break;
      if (j < nph) continue;
      ph = yf_realloc(ph, (size_t)(nph + 1) * sizeof *ph, "physical groups");
      ph[nph].dim = ent[e].dim;
      ph[nph].tag = tag;
      ph[nph].name[0] = '\0';
      ph[nph].group = -1;
      for (int q = 0; q < npn; q++)
        if (pn[q].dim == ent[e].dim && pn[q].tag == tag) snprintf(ph[nph].name, sizeof ph[nph].name, "%s", pn[q].name);
      nph++;
    }
  }
  /* unnamed: phys_<tag>, with the dimension added when another unnamed group shares the tag
   * (Gmsh numbers physical curves and surfaces independently, so tag 1 is often both).  Which
   * share is settled before any is named: naming as it went, the first of two got the dimension
   * (phys_9_curve) and the second, finding the first named, did not (phys_9, not phys_9_surface) */
  int *shared = yf_calloc((size_t)(nph ? nph : 1), sizeof *shared, "physical groups");
  for (int j = 0; j < nph; j++)
    for (int q = 0; q < nph && !ph[j].name[0]; q++)
      if (q != j && ph[q].tag == ph[j].tag && !ph[q].name[0]) shared[j] = 1;
  for (int j = 0; j < nph; j++) {
    if (ph[j].name[0]) continue;
    if (shared[j]) snprintf(ph[j].name, sizeof ph[j].name, "phys_%ld_%s", ph[j].tag, dim_word[ph[j].dim]);
    else snprintf(ph[j].name, sizeof ph[j].name, "phys_%ld", ph[j].tag);
  }
  free(shared);

  /* ---- materials of the surfaces ---- */
  char buf[512];
  for (int k = 0; k < o->nmap; k++) {
    int found = 0;
    for (int j = 0; j < nph; j++) {
      char tagword[32];
      snprintf(tagword, sizeof tagword, "%ld", ph[j].tag);
      if (ph[j].dim == 2 && (!strcmp(ph[j].name, o->map[k].phys) || !strcmp(tagword, o->map[k].phys)))
        found = 1;
    }
    if (!found) {
      size_t q = 0;
      buf[0] = '\0';
      for (int j = 0; j < nph && q + 60 < sizeof buf; j++)
        if (ph[j].dim == 2) q += (size_t)snprintf(buf + q, sizeof buf - q, "%s%s", q ? ", " : "", ph[j].name);
      yf_deck_error(&o->from, "mesh gmsh: '%s' has no physical surface '%s' (physical surfaces: %s)",
                    path, o->map[k].phys, q ? buf : "none");
    }
  }
  int first_mat = -1;
  for (int e = 0; e < nent; e++) {
    if (ent[e].dim != 2 || ent[e].ntri == 0) continue;
    int mat = -1;
    const char *phname = NULL;
    for (int k = 0; k < ent[e].nphys && mat < 0; k++) {
      long tag = pool[ent[e].off + k];
      const Phys *p = NULL;
      for (int j = 0; j < nph; j++)
        if (ph[j].dim == 2 && ph[j].tag == tag) p = &ph[j];
      if (!phname) phname = p->name;
      char tagword[32];
      snprintf(tagword, sizeof tagword, "%ld", tag);
      for (int q = 0; q < o->nmap && mat < 0; q++)
        if (!strcmp(o->map[q].phys, p->name) || !strcmp(o->map[q].phys, tagword)) mat = o->map[q].mat;
      if (mat < 0) mat = model_find_material(m, p->name);
    }
    if (mat < 0) mat = o->defmat;
    if (mat < 0) {
      if (phname)
        yf_deck_error(&o->from, "mesh gmsh: no material for physical surface '%s' of '%s': define a "
                      "material of that name or add 'material %s=MAT' (known materials: %s)", phname,
                      path, phname, mesh_material_names(m, buf, sizeof buf));
      if (msh2)
        yf_deck_error(&o->from, "mesh gmsh: triangle %ld (elementary surface %ld) of '%s' is in no physical group "
                      "(physical tag 0): give a default material with 'material MAT' (known materials: %s)",
                      ent[e].el, ent[e].tag, path, mesh_material_names(m, buf, sizeof buf));
      yf_deck_error(&o->from, "mesh gmsh: surface %ld of '%s' is in no physical group: give a default "
                    "material with 'material MAT' (known materials: %s)", ent[e].tag, path,
                    mesh_material_names(m, buf, sizeof buf));
    }
    ent[e].mat = mat;
    if (first_mat < 0) first_mat = mat;
  }

  /* ---- into the model ---- */
  /* every physical group becomes a group: say so when they do not fit, rather than naming the
   * first group that did not ("cannot create group 'edge63'"), a name the deck never gave */
  int fresh = model_group(m, o->body, 0) < 0; /* the body's own group */
  for (int j = 0; j < nph; j++) {
    int dup = 0;
    for (int q = 0; q < j; q++) dup |= !strcmp(ph[q].name, ph[j].name);
    fresh += !dup && model_group(m, ph[j].name, 0) < 0;
  }
  if (m->ngroup + fresh > YF_MAX_GROUPS)
    yf_deck_error(&o->from, "mesh gmsh: '%s' has %d physical groups: with the body's they need %d new groups, and %d "
                  "of the %d groups yfdem holds are free (every body and group counts): merge physical groups in "
                  "Gmsh (one physical surface per material, one physical curve per loaded or held boundary)",
                  path, nph, fresh, YF_MAX_GROUPS - m->ngroup, YF_MAX_GROUPS);
  int b = mesh_new_body(m, o->body, o->defmat >= 0 ? o->defmat : first_mat, &o->from, "mesh gmsh");
  uint64_t bbit = (uint64_t)1 << m->body[b].group;
  for (int j = 0; j < nph; j++) {
    if (model_find_body(m, ph[j].name) >= 0)
      yf_deck_error(&o->from, "mesh gmsh: physical %s '%s' of '%s' has the name of a body; rename "
                    "the body or the physical group", dim_word[ph[j].dim], ph[j].name, path);
    ph[j].group = mesh_group_or_die(m, ph[j].name, &o->from, "mesh gmsh");
  }
  for (int e = 0; e < nent; e++)
    for (int k = 0; k < ent[e].nphys && ent[e].dim <= 2; k++)
      for (int j = 0; j < nph; j++)
        if (ph[j].dim == ent[e].dim && ph[j].tag == pool[ent[e].off + k])
          ent[e].bits |= (uint64_t)1 << ph[j].group;

  warn_coincident(path, &o->from, nx, ny, ntag, used, nn);
  int *l2m = yf_malloc((size_t)(nn ? nn : 1) * sizeof *l2m, "mesh nodes");
  for (long i = 0; i < nn; i++) {
    l2m[i] = -1;
    if (!used[i]) continue;
    l2m[i] = model_add_node(m, nx[i] + o->dx, ny[i] + o->dy, (int)ntag[i], b);
    m->node.gmask[l2m[i]] |= bbit;
  }
  for (long t = 0; t < ntri; t++) {
    const Ent *e = &ent[tent[t]];
    int v0 = l2m[tv[3 * t]], v1 = l2m[tv[3 * t + 1]], v2 = l2m[tv[3 * t + 2]];
    int k = model_add_tri(m, v0, v1, v2, e->mat, (int)ttag[t], b);
    m->tri.gmask[k] |= bbit | e->bits;
    m->node.gmask[v0] |= e->bits;
    m->node.gmask[v1] |= e->bits;
    m->node.gmask[v2] |= e->bits;
  }
  /* node groups of physical points and curves; nodes that are no triangle corner were dropped */
  long dropped = 0;
  uint64_t dropbits = 0;
  for (long p = 0; p < npair; p++) {
    const Ent *e = &ent[pair[2 * p]];
    int k = l2m[pair[2 * p + 1]];
    if (k < 0) {
      dropped++;
      dropbits |= e->bits;
      continue;
    }
    m->node.gmask[k] |= e->bits;
  }
  if (dropped) {
    size_t q = 0;
    buf[0] = '\0';
    for (int j = 0; j < nph && q + 60 < sizeof buf; j++)
      if (dropbits & ((uint64_t)1 << ph[j].group))
        q += (size_t)snprintf(buf + q, sizeof buf - q, "%s%s", q ? ", " : "", ph[j].name);
    yf_warn(&o->from, "mesh gmsh: %ld node references of physical group(s) %s in '%s' are not "
            "triangle corners and were left out", dropped, buf, path);
  }

  free(l2m);
  free(ph);
  free(pair);
  free(tv);
  free(tent);
  free(ttag);
  free(ntag);
  free(nx);
  free(ny);
  free(used);
  idmap_free(&nmap);
  idmap_free(&emap);
  idmap_free(&pmap);
  free(pn);
  free(pool);
  free(ent);
  free(r->buf);
  return b;
}
