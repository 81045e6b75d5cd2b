/* fuzz_restart.c: libFuzzer target for read_restart (src/io/restart.c) (tools/fuzz/README.md).
 *
 * A restart is an HDF5 file; random bytes would fuzz libhdf5's parser (not instrumented here, and
 * not ours), so this target is structure-aware: at start it runs a small fracturing, contact
 * scene and writes its restart (the template), then each input is a list of edits of the
 * template's datasets, and the edited file is read by tests/corpus/reader_restart.deck, which
 * rebuilds the scene (reader_restart_scene.inc), reads in.restart and runs 2 steps: values read
 * without a check (an index past an array, a state no switch knows, a negative count, a NaN) show
 * there.  make check replays the .restart rows of tests/corpus/MANIFEST with the same deck.
 *
 * An input is a sequence of 12-byte edits: dataset (byte 0, modulo the template's datasets, in
 * the order H5Ovisit lists them), operation (byte 1), element (bytes 2-3, modulo the length) and
 * an 8-byte value (bytes 4-11):
 *   op 0: element = the value's bytes (as many as the element has: raw ints, doubles, flags);
 *   op 1: element = a special value (value byte 0 picks: NaN, +-inf, -1, 0, 1, 2, 3, 255, the
 *         dataset's length, INT_MAX, INT_MIN, LONG_MAX, 1e300, -1e300, 0.5), converted to its type;
 *   op 2: the dataset is deleted;
 *   op 3: the dataset is made again with (element) elements of its type, each the value's bytes.
 * Other ops: element = value byte 0 in every byte (0x00, 0xff...).
 */
#include <hdf5.h>
#include <math.h>
#include <limits.h>
#include "fuzz_common.h"
#include "h5quiet.h"

enum { NDS_MAX = 128 };
static char ds_name[NDS_MAX][64];
static int nds;
static uint8_t *tmpl;
static size_t ntmpl;
static char *deck;
static size_t ndeck;

static herr_t list_ds(hid_t o, const char *name, const H5O_info_t *info, void *op) {
  (void)o; (void)op;
  if (info->type == H5O_TYPE_DATASET && nds < NDS_MAX) snprintf(ds_name[nds++], sizeof ds_name[0], "/%s", name);
  return 0;
}

int LLVMFuzzerInitialize(int *argc, char ***argv) {
  (void)argc; (void)argv;
  fuzz_setup();
  size_t n;
  free(fuzz_corpus_file("reader_restart_scene.inc", &n));
  deck = fuzz_corpus_file("reader_restart.deck", &ndeck);
  static const char make[] = "include reader_restart_scene.inc\nrun 60\nwrite_restart t.restart\n";
  fuzz_enter();
  if (fuzz_run_deck(make, sizeof make - 1, "make_template.deck") != 0) {
    fprintf(stderr, "fuzz_restart: the template deck failed: %s\n", yf_last_message());
    exit(1);
  }
  char *t = yf_read_file("t.restart", &n, "template");
  if (!t) { perror("fuzz_restart: t.restart"); exit(1); }
  tmpl = (uint8_t *)t;
  ntmpl = n;
  yf_h5_quiet();
  hid_t f = H5Fopen("t.restart", H5F_ACC_RDONLY, H5P_DEFAULT);
  H5Ovisit2(f, H5_INDEX_NAME, H5_ITER_INC, list_ds, NULL, H5O_INFO_BASIC); /* HDF5 1.10 (Debian 12) */
  H5Fclose(f);
  fuzz_leave();
  fprintf(stderr, "fuzz_restart: template t.restart, %zu bytes, %d datasets\n", ntmpl, nds);
  return 0;
}

/* A special value of the element type (class c, size z) into out. */
static void special(int pick, H5T_class_t c, size_t z, long len, uint8_t *out) {
  static const double dv[] = {NAN, INFINITY, -INFINITY, -1, 0, 1, 2, 3, 255, 0 /*len*/, INT_MAX, INT_MIN,
                              9.2233720368547758e18, 1e300, -1e300, 0.5};
  enum { NV = sizeof dv / sizeof dv[0] };
  int k = pick % NV;
  double v = k == 9 ? (double)len : dv[k];
  long lv = k == 12 ? LONG_MAX : isfinite(v) && fabs(v) < 9e18 ? (long)v : (v > 0 ? LONG_MAX : LONG_MIN);
  memset(out, 0, 8);
  if (c == H5T_FLOAT) memcpy(out, &v, 8);
  else if (z == 8) memcpy(out, &lv, 8);
  else if (z == 4) { int iv = (int)lv; if (lv > INT_MAX) iv = INT_MAX; else if (lv < INT_MIN) iv = INT_MIN; memcpy(out, &iv, 4); }
  else out[0] = (uint8_t)lv;
}

static void edit(hid_t f, const uint8_t *e) {
  const char *name = ds_name[e[0] % nds];
  if (H5Lexists(f, name, H5P_DEFAULT) <= 0) return;
  int op = e[1];
  if (op == 2) { H5Ldelete(f, name, H5P_DEFAULT); return; }
  hid_t ds = H5Dopen2(f, name, H5P_DEFAULT);
  if (ds < 0) return;
  hid_t ft = H5Dget_type(ds), mt = H5Tget_native_type(ft, H5T_DIR_ASCEND);
  H5T_class_t c = H5Tget_class(mt);
  size_t z = H5Tget_size(mt);
  hid_t sp = H5Dget_space(ds);
  hsize_t dims[1] = {0};
  H5Sget_simple_extent_dims(sp, dims, NULL);
  H5Sclose(sp);
  long len = (long)dims[0];
  unsigned idx = (unsigned)e[2] | (unsigned)e[3] << 8;
  if (op == 3) { /* made again with idx elements */
    H5Dclose(ds);
    H5Ldelete(f, name, H5P_DEFAULT);
    hsize_t d1[1] = {idx % 4096};
    uint8_t *buf = calloc(d1[0] ? d1[0] : 1, z);
    for (hsize_t k = 0; k < d1[0]; k++) memcpy(buf + k * z, e + 4, z < 8 ? z : 8);
    hid_t s2 = H5Screate_simple(1, d1, NULL);
    hid_t d2 = H5Dcreate2(f, name, ft, s2, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    if (d2 >= 0) { if (d1[0]) H5Dwrite(d2, mt, H5S_ALL, H5S_ALL, H5P_DEFAULT, buf); H5Dclose(d2); }
    H5Sclose(s2);
    free(buf);
  } else if (len > 0 && z <= 8) {
    uint8_t *buf = malloc((size_t)len * z);
    if (H5Dread(ds, mt, H5S_ALL, H5S_ALL, H5P_DEFAULT, buf) >= 0) {
      uint8_t v[8];
      if (op == 0) memcpy(v, e + 4, 8);
      else if (op == 1) special(e[4], c, z, len, v);
      else memset(v, e[4], 8);
      memcpy(buf + (size_t)(idx % (unsigned long)len) * z, v, z);
      H5Dwrite(ds, mt, H5S_ALL, H5S_ALL, H5P_DEFAULT, buf);
      /* the edit is the fuzzer's, not damage: the value's checksum goes (a dataset without one is read
       * unchecked), so the reader's range checks are what the input meets, not the checksum's refusal */
      if (H5Aexists(ds, "fnv1a") > 0) H5Adelete(ds, "fnv1a");
    }
    free(buf);
    H5Dclose(ds);
  } else {
    H5Dclose(ds);
  }
  H5Tclose(mt);
  H5Tclose(ft);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  if (size > 12 * 64) return 0;
  fuzz_enter();
  yf_h5_quiet();
  hid_t f = fuzz_write_file("in.restart", tmpl, ntmpl) ? H5Fopen("in.restart", H5F_ACC_RDWR, H5P_DEFAULT) : -1;
  if (f >= 0) {
    for (size_t k = 0; k + 12 <= size; k += 12) edit(f, data + k);
    H5Fclose(f);
    fuzz_run_deck(deck, ndeck, "reader_restart.deck");
  }
  fuzz_leave();
  return 0;
}
