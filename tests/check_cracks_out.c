/* check_cracks_out.c: h5 dumps of a fracturing scene carry its cracks, so ParaView shows them:
 * every broken or opened joint is a segment of the frame's /cracks polyline grid, listed in a
 * crack series of its own (STEM_cracks.xmf) beside the triangles' (STEM.xmf), whose frames are
 * single uniform grids (ParaView's default reader drops the fields of mixed collections). */
#include <check.h>
#include <hdf5.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "joint.h"
#include "yftest.h"

/* A bar of joints pulled by a prescribed displacement until cracks open and break
 * (12000 steps, mass-damped): `pre` goes after the fracture line, `post` before the run. */
static void pulled_bar_deck(char *deck, size_t n, const char *pre, const char *post) {
  snprintf(deck, n,
           "material c elastic rho 2500 E 1e10 nu 0.2 plane_stress\n"
           "mesh rect bar c 0 0 0.1 0.02 20 4 pattern alt\n"
           "jointprop cj ft 3e6 fs 3e6 gf 100 pen 1e11 law munjiza_gf\n"
           "fracture bar cj\n%s"
           "region l box -1 -1 1e-9 1\nregion r box 0.099999 -1 1 1\n"
           "group l node region l\ngroup r node region r\nfix hold l fixed xy\n"
           "history pull ramp 0 1e-3\nfix pull r displacement 4e-4 NULL history pull\n"
           "damping mass 3000\ntimestep auto\n%srun 12000\n", pre, post);
}

START_TEST(test_cracks_in_frames) {
  freopen("/dev/null", "w", stdout);
  char dir[] = "/tmp/yf_cracks_XXXXXX";
  ck_assert_ptr_nonnull(mkdtemp(dir));
  char deck[2048], extra[256];
  snprintf(extra, sizeof extra, "dump d h5 12000 %s/bar.h5\n", dir);
  pulled_bar_deck(deck, sizeof deck, "", extra);
  YfSim *s = yft_run(deck);
  const YfJoints *j = s->joints;
  ck_assert_int_gt(j->nbroken, 0);
  int expect = 0;
  for (int k = 0; k < j->n; k++) expect += j->state[k] == 2 || (j->opened && j->opened[k]);
  char p[256];
  snprintf(p, sizeof p, "%s/bar_000001.h5", dir); /* frame 0 at step 0, frame 1 at the end */
  H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
  hid_t f = H5Fopen(p, H5F_ACC_RDONLY, H5P_DEFAULT);
  ck_assert_msg(f >= 0, "cannot open %s", p);
  hid_t ds = H5Dopen2(f, "/cracks/state", H5P_DEFAULT);
  ck_assert(ds >= 0);
  hid_t sp = H5Dget_space(ds);
  hssize_t nc = H5Sget_simple_extent_npoints(sp);
  ck_assert_int_eq(nc, expect);
  int *st = malloc(sizeof(int) * (size_t)nc);
  H5Dread(ds, H5T_NATIVE_INT, H5S_ALL, H5S_ALL, H5P_DEFAULT, st);
  int nb = 0;
  for (hssize_t k = 0; k < nc; k++) nb += st[k] == 2;
  ck_assert_int_eq(nb, j->nbroken); /* every broken joint is drawn as broken */
  free(st);
  H5Sclose(sp);
  H5Dclose(ds);
  H5Fclose(f);
  snprintf(p, sizeof p, "%s/bar.xmf", dir);
  FILE *x = fopen(p, "r");
  ck_assert_ptr_nonnull(x);
  char *buf = calloc(1, 1 << 20);
  size_t k = fread(buf, 1, (1 << 20) - 1, x);
  buf[k] = 0;
  fclose(x);
  ck_assert_ptr_null(strstr(buf, "Polyline"));
  ck_assert_ptr_null(strstr(buf, "CollectionType=\"Spatial\""));
  ck_assert_ptr_nonnull(strstr(buf, "Name=\"stress_xy\""));
  free(buf);
  snprintf(p, sizeof p, "%s/bar_cracks.xmf", dir);
  char *cx = yft_slurp(p, 0);
  ck_assert_ptr_nonnull(cx);
  ck_assert_ptr_nonnull(strstr(cx, "TopologyType=\"Polyline\""));
  ck_assert_ptr_nonnull(strstr(cx, "bar_000001.h5:/cracks/xy"));
  ck_assert_ptr_null(strstr(cx, "CollectionType=\"Spatial\""));
  free(cx);
  char cmd[300];
  snprintf(cmd, sizeof cmd, "rm -rf %s", dir);
  if (system(cmd)) {}
}
END_TEST

/* metrics opened_threshold Z: a joint counts as an opened crack once its damage reaches Z, not at
 * the first damage past the law's peak.  On the pulled bar, every intact joint whose damage is
 * at least Z is opened, no opened intact joint has less, and joints damaged below Z (which the
 * default would count) are not opened. */
START_TEST(test_opened_threshold) {
  const double Z = 0.5;
  char deck[2048], extra[64];
  snprintf(extra, sizeof extra, "metrics opened_threshold %g\n", Z);
  pulled_bar_deck(deck, sizeof deck, extra, "");
  YfSim *s = yft_run(deck);
  const YfJoints *j = s->joints;
  int below = 0, flagged = 0;
  for (int k = 0; k < j->n; k++) {
    flagged += j->opened[k] != 0;
    if (j->state[k]) continue; /* broken joints keep the flag they had when they broke */
    if (j->z[k] >= Z) ck_assert_msg(j->opened[k], "joint %d: damage %g >= %g but not opened", k, j->z[k], Z);
    else ck_assert_msg(!j->opened[k], "joint %d: damage %g < %g but opened", k, j->z[k], Z);
    below += j->z[k] > 0.0 && j->z[k] < Z;
  }
  ck_assert_int_eq(flagged, j->nopened);
  ck_assert_msg(below > 0, "no joint damaged below %g: the threshold is not exercised", Z);
  ck_assert_int_gt(j->nopened, 0);
}
END_TEST

Suite *cracks_out_suite(void) {
  Suite *s = suite_create("cracks_out");
  TCase *t = tcase_create("h5");
  tcase_set_timeout(t, 120);
  tcase_add_test(t, test_cracks_in_frames);
  tcase_add_test(t, test_opened_threshold);
  suite_add_tcase(s, t);
  return s;
}
