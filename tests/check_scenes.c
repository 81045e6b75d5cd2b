/* check_scenes.c: the seed paper's two scenes (decks/beam.deck, decks/column.deck) run by the
 * yfdem binary on coarse meshes, judged on the crack measurements of metrics.c read back from
 * the -summary JSON; and the metrics command's deck errors.
 *
 * What is asserted is what the runs show (see README, "The seed paper's scenes"): perfectly
 * mirrored crack patterns on the mirror-symmetric `cross` meshes, the beam's first break at the
 * impactor's edge (local crushing: with ft = fs = 3.15 MPa the contact stress rho c v ~ 39 MPa
 * of a 5 m/s impact shears the concrete under the impactor corners long before the beam bends),
 * the column's longitudinal cracks before its first fragment and fragments thrown outwards from
 * the shoulders.  The paper's bending cracks (midspan bottom, inclined pair, tops over the
 * supports) do not appear in these runs: the impactor punches a plug first.
 */
#include <check.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "yftest.h"

static char *slurp(const char *path) {
  FILE *f = fopen(path, "rb");
  if (!f) return NULL;
  fseek(f, 0, SEEK_END);
  long n = ftell(f);
  fseek(f, 0, SEEK_SET);
  char *b = calloc(1, (size_t)n + 1);
  if (fread(b, 1, (size_t)n, f) != (size_t)n) b[0] = 0;
  fclose(f);
  return b;
}

/* The number after "key": (searching from p); NAN when absent or null. */
static double jnum(const char *p, const char *key) {
  char k[128];
  snprintf(k, sizeof k, "\"%s\":", key);
  const char *q = p ? strstr(p, k) : NULL;
  if (!q) return NAN;
  q += strlen(k);
  while (*q == ' ') q++;
  if (!strncmp(q, "null", 4)) return NAN;
  return strtod(q, NULL);
}

/* Run deck FILE (repo-relative) with extra -var options; returns the summary text. */
static char *run_scene(const char *deck, const char *vars) {
  char *text = slurp(deck);
  ck_assert_msg(text != NULL, "cannot read %s", deck);
  char args[512], *err = NULL, *dir = NULL;
  snprintf(args, sizeof args, "%s -summary s.json", vars);
  int rc = yft_run_binary("scene.deck", text, args, &err, &dir);
  ck_assert_msg(rc == 0, "%s failed (exit %d): %s", deck, rc, err);
  char path[600];
  snprintf(path, sizeof path, "%s/s.json", dir);
  char *js = slurp(path);
  ck_assert_ptr_nonnull(js);
  free(text);
  free(err);
  free(dir);
  return js;
}

START_TEST(beam_coarse) {
  /* nx 40: 4 cells through the depth, h = 0.025 m; 2000 steps = 0.45 ms (the plug forms by 0.2 ms) */
  char *js = run_scene("decks/beam.deck", "-var nx 40 -var steps 2000");
  double sym = jnum(js, "symmetry");
  ck_assert_msg(sym >= 0.9, "beam symmetry %g < 0.9", sym);
  const char *fb = strstr(js, "\"first_break\":");
  ck_assert_ptr_nonnull(fb);
  double x = jnum(fb, "x"), y = jnum(fb, "y"), h = 0.025;
  /* first break at an impactor corner (x = 0.5 +- 0.025), in the top cell row */
  ck_assert_msg(fabs(fabs(x - 0.5) - 0.025) <= 1.5 * h && y >= 0.1 - h, "first break at (%g, %g)", x, y);
  ck_assert(jnum(js, "joints_broken") >= 2);
  free(js);
}
END_TEST

START_TEST(column_coarse) {
  char *js = run_scene("decks/column.deck", "-var nx 12 -var steps 4000");
  double sym = jnum(js, "symmetry");
  ck_assert_msg(sym >= 0.8, "column symmetry %g < 0.8", sym);
  double tff = jnum(js, "first_fragment_time");
  ck_assert_msg(tff > 0, "the column never broke into pieces");
  const char *o = strstr(js, "\"crack_orientation_at_first_fragment\":");
  ck_assert_ptr_nonnull(o);
  ck_assert_msg(jnum(o, "vertical") > 0, "no longitudinal (vertical) crack before the first fragment");
  /* fragments from the shoulders: small pieces that started in the top third, outside the
   * impactor's footprint (x < 0.025 or x > 0.125 +- a cell), moving outwards */
  const char *l = strstr(js, "\"body_fragments\":");
  ck_assert_ptr_nonnull(l);
  int out_l = 0, out_r = 0;
  for (const char *p = strstr(l, "{\"area\""); p; p = strstr(p + 1, "{\"area\"")) {
    double x0 = jnum(p, "x0"), y0 = jnum(p, "y0"), vx = jnum(p, "vx"), area = jnum(p, "area");
    if (area > 0.1 * 0.15 * 0.3 || y0 < 0.2) continue;
    if (x0 < 0.0375 && vx < -1.0) out_l++;
    if (x0 > 0.1125 && vx > 1.0) out_r++;
  }
  ck_assert_msg(out_l > 0 && out_r > 0, "fragments leaving the shoulders: left %d right %d", out_l, out_r);
  free(js);
}
END_TEST

START_TEST(metrics_errors) {
  char *err = NULL;
  int rc = yft_run_binary("m.deck", "metrics mirror z 0.5\n", "", &err, NULL);
  ck_assert_int_eq(rc, 1);
  ck_assert_msg(strstr(err, "m.deck:1") && strstr(err, "'z'") && strstr(err, "x, y"), "%s", err);
  free(err);
  rc = yft_run_binary("m.deck", "metrics region mid nowhere\n", "", &err, NULL);
  ck_assert_int_eq(rc, 1);
  ck_assert_msg(strstr(err, "nowhere"), "%s", err);
  free(err);
  rc = yft_run_binary("m.deck", "metrics peek_stress on\n", "", &err, NULL);
  ck_assert_int_eq(rc, 1);
  ck_assert_msg(strstr(err, "peak_stress"), "%s", err);
  free(err);
}
END_TEST

Suite *scenes_suite(void) {
  Suite *s = suite_create("scenes");
  TCase *tc = tcase_create("scenes");
  tcase_set_timeout(tc, 600);
  tcase_add_test(tc, beam_coarse);
  tcase_add_test(tc, column_coarse);
  tcase_add_test(tc, metrics_errors);
  suite_add_tcase(s, tc);
  return s;
}
