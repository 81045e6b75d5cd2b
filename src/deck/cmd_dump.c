/* cmd_dump.c: the `dump` deck command (a row of commands.def): reads a dump's words and adds it
 * (output_add_dump, io/output.c; the y2dref style's words into a YfY2dRef, y2d/y2dref.c).
 */
#include <errno.h>
#include <limits.h>
#include <stdlib.h>
#include <string.h>
#include "deck.h"
#include "output.h"
#include "utf8name.h"
#include "y2d_model.h"
#include "y2dref.h"

/* "S1,S2,..." -> corner-table steps of r; *n: how many r has (all corners keywords so far) */
static void parse_steps(const YfArgs *a, int i, struct YfY2dRef *r, int *n) {
  const char *w = arg_word(a, i, "corner steps");
  char *buf = yf_strdup(w), *save = NULL;
  for (char *t = strtok_r(buf, ",", &save); t; t = strtok_r(NULL, ",", &save)) {
    long v;
    if (!yf_parse_long(t, &v) || v < 0) {
      free(buf);
      arg_error(a, i, "expected a comma-separated list of step numbers >= 0 (e.g. 500,2000,4000)");
    }
    *n = y2dref_add_corner_step(r, v);
  }
  free(buf);
  if (!*n) arg_error(a, i, "expected at least one step");
}

/* dump ID y2dref DIR [corners S1,S2,...] [summary K] [probes K E:C E:C ...]  (y2dref.h) */
static struct YfY2dRef *parse_y2dref(YfSim *s, const YfArgs *a) {
  arg_count(a, 3, -1);
  const char *d = arg_word(a, 2, "directory");
  if (!d[0]) arg_error(a, 2, "empty directory name");
  /* relative to the working directory, as every file yfdem writes (README, Files) */
  struct YfY2dRef *r = y2dref_new(d);
  int ncs = 0, nprobe = 0;
  for (int i = 3; i < a->n;) {
    const char *k = a->w[i];
    if (!strcmp(k, "corners")) {
      parse_steps(a, i + 1, r, &ncs);
      i += 2;
    } else if (!strcmp(k, "summary")) {
      y2dref_set_summary(r, arg_int(a, i + 1, "summary period K (steps)", 1, 1000000000L));
      i += 2;
    } else if (!strcmp(k, "probes")) {
      y2dref_set_probe_every(r, arg_int(a, i + 1, "probe period K (steps)", 1, 1000000000L));
      i += 2;
      for (; i < a->n && strchr(a->w[i], ':'); i++) {
        long e, c;
        char *w = yf_strdup(a->w[i]), *colon = strchr(w, ':');
        *colon = 0;
        int ok = yf_parse_long(w, &e) && yf_parse_long(colon + 1, &c) && e >= 0 && c >= 0 && c <= 2;
        free(w);
        if (!ok) arg_error(a, i, "expected ELEMENT:CORNER (input element index, corner 0, 1 or 2)");
        if (y2d_tri_of_elem(s, e) < 0) arg_error(a, i, "no triangle with input index %ld in the scene", e);
        nprobe = y2dref_add_probe(r, e, c);
      }
      if (!nprobe) arg_error(a, i - 1, "expected probes ELEMENT:CORNER after the period");
    } else {
      arg_error(a, i, "unknown keyword (expected corners S1,S2,..., summary K or probes K E:C ...)");
    }
  }
  return r;
}

/* Offset of the first byte of s that XML 1.0 text cannot hold (UTF-8 that is malformed, overlong,
 * a surrogate or beyond U+10FFFF; a control character other than tab), or -1 when there is none.
 * A Latin-1 name ('\xe9t\xe9.h5') went into the index as it was: not well-formed XML. */
static long not_xml_text(const char *s) {
  for (long i = 0; s[i];) {
    unsigned cp;
    int n = yf_utf8_decode(s + i, &cp);
    if (!n || (cp < 0x20 && cp != '\t') || cp == 0xFFFE || cp == 0xFFFF) return i;
    i += n;
  }
  return -1;
}

/* The files a dump writes, claimed for it (output_claim): frames STEM_NNNNNN EXT, the index
 * (index, or NULL) and STEM SIDE (its crack index, or a csv dump's index).  A file another
 * output writes: the dump is taken back and the line refused. */
static void claim_files(YfSim *s, const YfArgs *a, const char *id, const char *owner, const char *stem, const char *ext,
                        const char *index, const char *side) {
  char *fr = yf_malloc(strlen(stem) + 2, "path"), *sd = yf_malloc(strlen(stem) + strlen(side) + 1, "path");
  sprintf(fr, "%s_", stem);
  sprintf(sd, "%s%s", stem, side);
  const char *by = output_claim(s, owner, fr, ext, 6);
  if (!by && index) by = output_claim(s, owner, index, NULL, 0);
  if (!by) by = output_claim(s, owner, sd, NULL, 0);
  free(fr);
  free(sd);
  if (by) {
    output_remove_dump(s, id);
    arg_error(a, 3, "a file of it is already written by %s", by);
  }
}

/* dump ID h5 N FILE.h5 [fields F1 F2 ...] [compress]
 * dump ID csv N PREFIX
 * dump ID y2dref DIR ... */
void cmd_dump(YfSim *s, const YfArgs *a) {
  static const char *const styles[] = {"h5", "csv", "y2dref", NULL}; /* index = YF_DUMP_* */
  arg_count(a, 2, -1);
  const char *id = arg_name(a, 0, "dump id");
  int style = arg_choice(a, 1, "style", styles);
  if (style == YF_DUMP_Y2DREF) {
    if (output_find_dump(s, id) >= 0) arg_error(a, 0, "a dump with this id exists (undump it first)");
    if (output_ndump(s) >= YF_MAX_DUMPS) arg_error(a, 0, "at most %d dumps at a time", YF_MAX_DUMPS);
    struct YfY2dRef *r = parse_y2dref(s, a);
    output_add_y2dref(s, id, r);
    char owner[YF_NAME_MAX + 16];
    snprintf(owner, sizeof owner, "dump '%s'", id);
    /* the files it writes in DIR: two y2dref dumps on one DIR interleaved their rows */
    static const char *const files[] = {Y2DREF_SUMMARY, Y2DREF_PROBES, Y2DREF_BROKEN, Y2DREF_CORNERS, NULL};
    const char *by = NULL;
    for (int i = 0; files[i] && !by; i++) {
      char f[4096];
      snprintf(f, sizeof f, "%s/%s", y2dref_dir(r), files[i]);
      by = files[i + 1] ? output_claim(s, owner, f, NULL, 0) : output_claim(s, owner, f, ".csv", 7);
    }
    if (by) {
      output_remove_dump(s, id);
      arg_error(a, 2, "a file it writes there is already written by %s", by);
    }
    /* a folder that cannot be made: now, at this line, as the h5 and csv dumps' (arg_writable),
     * not at the run's first frame after the other outputs began */
    int bad = y2dref_dir_check(y2dref_dir(r));
    if (bad) {
      int e = errno;
      output_remove_dump(s, id); /* r goes with it: the folder's name from the deck's word */
      if (bad >= 3) /* a table in the way: named, not the folder */
        yf_io_error(&a->loc, "dump %s: cannot write '%s/%s': %s", id, a->w[2], files[bad - 3], strerror(e));
      yf_io_error(&a->loc, "dump %s: cannot %s '%s': %s", id, bad == 1 ? "create directory" : "write in directory",
                  a->w[2], strerror(e));
    }
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
        int k = arg_choice(a, i, "field", output_field_names);
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
  /* the names of its files are the stem and their endings: the stem must name a file */
  size_t sl = style == YF_DUMP_H5 ? output_h5_stem_len(path) : strlen(path);
  char *fstem = yf_malloc(sl + 1, "path"), *made = yf_malloc(sl + 32, "path");
  snprintf(fstem, sl + 1, "%s", path);
  snprintf(made, sl + 32, "%s_000000%s", fstem, style == YF_DUMP_CSV ? ".csv" : path[sl] ? path + sl : ".h5");
  arg_file_stem(a, 3, fstem, made);
  free(fstem);
  free(made);
  const char *base = strrchr(path, '/');
  if (style == YF_DUMP_H5 && strchr(base ? base + 1 : path, ':'))
    arg_error(a, 3, "the file name may not contain ':' (XDMF uses it to separate file and dataset)");
  long badid = style == YF_DUMP_H5 ? not_xml_text(id) : -1; /* the index's series is named by it */
  if (badid >= 0)
    arg_error(a, 0, "the dump id is not UTF-8 text (byte %ld of it is 0x%02x): the XDMF index names its series by it, "
              "in XML, which holds UTF-8 text only; give an ASCII id", badid + 1, (unsigned char)id[badid]);
  long bad = style == YF_DUMP_H5 ? not_xml_text(base ? base + 1 : path) : -1;
  if (bad >= 0)
    arg_error(a, 3, "the file name is not UTF-8 text (byte %ld of it is 0x%02x): the XDMF index names its frame files in "
              "XML, which holds UTF-8 text only (ParaView's reader aborted on such an index); rename it, e.g. in "
              "ASCII", bad + 1, (unsigned char)(base ? base + 1 : path)[bad]);
  if (output_find_dump(s, id) >= 0) arg_error(a, 0, "a dump with this id exists (undump it first)");
  if (output_ndump(s) >= YF_MAX_DUMPS) arg_error(a, 0, "at most %d dumps at a time", YF_MAX_DUMPS);
  int k = output_add_dump(s, id, style, every, path, fields, compress);
  char owner[YF_NAME_MAX + 16];
  snprintf(owner, sizeof owner, "dump '%s'", id);
  if (style == YF_DUMP_H5) {
    const char *stem, *ext, *xmf;
    output_dump_files(s, k, &stem, &ext, &xmf);
    /* its frames, its index and its crack index (STEM_cracks.xmf): no other output's */
    claim_files(s, a, id, owner, stem, ext, xmf, "_cracks.xmf");
    unsigned before = output_dump_earlier_fields(s, k);
    if (before && before != (fields & YF_FIELD_ALL))
      yf_warn(&a->loc, "dump %s: it continues the series of the dump undumped on %s, whose frames hold other fields; "
              "ParaView colours a series only by the fields every frame has: write these to another file", id, a->w[3]);
    /* a missing folder: now, at this line, not at the run after the other outputs began */
    char what[256];
    snprintf(what, sizeof what, "dump %s", id);
    arg_writable(a, what, "%s_000000%s", stem, ext);
    arg_writable(a, what, "%s", xmf);
    arg_writable(a, what, "%s_cracks.xmf", stem); /* (a folder of that name failed the first frame) */
    sim_printf(s, "dump %s: every %ld steps to %s_NNNNNN%s (index %s)%s\n", id, every, stem, ext, xmf,
               output_dump_mpio(s, k) ? "; every rank writes its rows (parallel HDF5; YFDEM_H5_MPIIO=0: gathered to rank 0)" : "");
  } else {
    claim_files(s, a, id, owner, path, ".csv", NULL, "_frames.csv");
    char what[256];
    snprintf(what, sizeof what, "dump %s", id);
    arg_writable(a, what, "%s_frames.csv", path);
    sim_printf(s, "dump %s: every %ld steps to %s_NNNNNN.csv\n", id, every, path);
  }
}
