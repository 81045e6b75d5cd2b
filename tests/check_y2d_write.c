/* check_y2d_write.c: write_y2d, a native scene as a Y2D deck, read back by read_y2d.
 *
 * Round trip: the native run of a scene that uses only what Y2D expresses and the read_y2d run
 * of the deck write_y2d made of it are the same computation up to round-off (the operation order
 * of Y2D's BC-set update differs from the native update), so they break the same joints at the
 * same steps and end with the same energies to 1e-9 of the run's largest energy.  The runs are
 * short enough that the chaos of crushing has not yet amplified the round-off, and long enough that
 * joints break in every scene (docs/y2d_decks.md gives the growth with the run length; the
 * stable limit with joints and contact halved `timestep auto`, so the step counts doubled).  The seed decks' `-var y2d 1` variants are the scenes.
 * A scene with every kind of BC set (support, prescribed velocity with a ramp, point load with a
 * table, pressure, gravity; contact with Y2D's friction law) checks the BC sets and time tables the same way, and the features Y2D
 * lacks are refused with a message that names them.
 */
#include <check.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include "yftest.h"

static double json_num(const char *js, const char *key) {
  char k[64];
  snprintf(k, sizeof k, "\"%s\": ", key);
  const char *p = strstr(js, k);
  ck_assert_msg(p != NULL, "no %s in the summary", key);
  return strtod(p + strlen(k), NULL);
}

static const char *const ekeys[] = {"kinetic", "strain", "external_work", "damping", "joint_dissipated",
                                    "contact", "friction"};
#define NEK ((int)(sizeof ekeys / sizeof ekeys[0]))

/* Run NATIVE (deck text, extra args) in a temporary directory, then read_y2d of the deck it wrote
 * (EXPORTED, relative to that directory) in another; compare energies and (if BREAKS names the
 * native fracture log) the broken joints.  Returns the largest energy difference over the
 * largest energy. */
static double round_trip(const char *native, const char *extra, const char *exported, const char *breaks,
                         int *nbroken, char **native_dir) {
  char *err = NULL, *d1 = NULL, *d2 = NULL;
  char args[1024];
  setenv("OMP_NUM_THREADS", "1", 1); /* same bits on any threads; one is fastest on a busy machine */
  snprintf(args, sizeof args, "%s -summary native.json", extra);
  int code = yft_run_binary("native.deck", native, args, &err, &d1);
  ck_assert_msg(code == 0, "native run: exit %d: %s", code, err);
  free(err);
  char deck[1024];
  snprintf(deck, sizeof deck, "read_y2d %s/%s\nfracture_log y2d_breaks.csv\nrun\n", d1, exported);
  code = yft_run_binary("y2d.deck", deck, "-summary y2d.json", &err, &d2);
  ck_assert_msg(code == 0, "read_y2d run: exit %d: %s", code, err);
  free(err);
  char p1[1200], p2[1200];
  snprintf(p1, sizeof p1, "%s/native.json", d1);
  snprintf(p2, sizeof p2, "%s/y2d.json", d2);
  char *j1 = yft_slurp(p1, 0), *j2 = yft_slurp(p2, 0);
  ck_assert(j1 && j2);
  ck_assert_int_eq((long)json_num(j1, "steps"), (long)json_num(j2, "steps"));
  double emax = 0, worst = 0;
  for (int k = 0; k < NEK; k++) emax = fmax(emax, fabs(json_num(j1, ekeys[k])));
  for (int k = 0; k < NEK; k++) {
    double d = fabs(json_num(j1, ekeys[k]) - json_num(j2, ekeys[k])) / emax;
    printf("write_y2d round trip: %-16s native %.12e y2d %.12e (difference %.1e of the largest)\n", ekeys[k],
           json_num(j1, ekeys[k]), json_num(j2, ekeys[k]), d);
    worst = fmax(worst, d);
  }
  *nbroken = (int)json_num(j1, "joints_broken");
  ck_assert_int_eq(*nbroken, (int)json_num(j2, "joints_broken"));
  if (breaks) {
    /* the same joints (index) broken at the same steps, in the same order */
    snprintf(p1, sizeof p1, "%s/%s", d1, breaks);
    snprintf(p2, sizeof p2, "%s/y2d_breaks.csv", d2);
    FILE *a = fopen(p1, "r"), *b = fopen(p2, "r");
    ck_assert(a && b);
    char la[512], lb[512];
    int rows = 0;
    while (fgets(la, sizeof la, a)) {
      ck_assert_msg(fgets(lb, sizeof lb, b) != NULL, "the read_y2d run broke fewer joints");
      if (!rows++) continue; /* header */
      long sa = strtol(la, NULL, 10), sb = strtol(lb, NULL, 10);
      const char *ja = strrchr(la, ','), *jb = strrchr(lb, ',');
      ck_assert_msg(sa == sb && atoi(ja + 1) == atoi(jb + 1), "break %d: native step %ld joint %d, y2d step %ld joint %d",
                    rows - 1, sa, atoi(ja + 1), sb, atoi(jb + 1));
    }
    ck_assert_msg(fgets(lb, sizeof lb, b) == NULL, "the read_y2d run broke more joints");
    ck_assert_int_eq(rows - 1, *nbroken);
    fclose(a);
    fclose(b);
  }
  free(j1); free(j2); free(d2);
  if (native_dir) *native_dir = d1;
  else free(d1);
  return worst;
}

/* The value after KEY in a written .y deck: a scalar key's value, or the first value of a 1D array
 * ("KEY n" then the values). */
static double deck_value(const char *deck, const char *key, int array) {
  char k[80];
  snprintf(k, sizeof k, "%s ", key);
  const char *p = strstr(deck, k);
  ck_assert_msg(p != NULL, "no %s in the written deck", key);
  char *end;
  double v = strtod(p + strlen(k), &end);
  if (array) v = strtod(end, NULL);
  return v;
}

static char *seed_round_trip(const char *name, const char *vars, int min_broken) {
  char native[1200], cwd[512], extra[512], exported[64], breaks[64];
  ck_assert(getcwd(cwd, sizeof cwd));
  snprintf(native, sizeof native, "include %s/decks/%s.deck\n", cwd, name);
  snprintf(extra, sizeof extra, "-var y2d 1 -var every 1000000 %s", vars);
  snprintf(exported, sizeof exported, "%s.y", name);
  snprintf(breaks, sizeof breaks, "%s_breaks.csv", name);
  int nb = 0;
  char *dir = NULL;
  double worst = round_trip(native, extra, exported, breaks, &nb, &dir);
  printf("write_y2d round trip %s (%s): %d joints broken in both, energies agree to %.1e\n", name, vars, nb, worst);
  ck_assert_msg(nb >= min_broken, "%s: only %d joints broke (the round trip must cover fracture)", name, nb);
  ck_assert_msg(worst <= 1e-9, "%s: energies differ by %.2e of the largest", name, worst);
  char path[1200];
  snprintf(path, sizeof path, "%s/%s", dir, exported);
  free(dir);
  char *deck = yft_slurp(path, 0);
  ck_assert_msg(deck != NULL, "cannot read %s", path);
  return deck;
}

START_TEST(test_beam_round_trip) { free(seed_round_trip("beam", "-var nx 20 -var steps 1500", 4)); }
END_TEST

START_TEST(test_column_round_trip) { free(seed_round_trip("column", "-var nx 8 -var steps 1000", 40)); }
END_TEST

/* The beam's Mohr-Coulomb joints (-var mu) with Y2D's physics (-var y2d 1): the exported joint set
 * keeps them (Y2D's D1PJCO, D1PJFR; D1PJFS 0 makes the cohesion the shear strength), and the round
 * trip holds.  (Before, -var y2d 1 silently replaced them by fs = ft.) */
START_TEST(test_beam_mohr_coulomb_round_trip) {
  char *deck = seed_round_trip("beam", "-var nx 20 -var steps 1500 -var mu 0.6", 4);
  ck_assert_msg(deck_value(deck, "/YD/YDPJ/D1PJFR", 1) == 0.6 && deck_value(deck, "/YD/YDPJ/D1PJCO", 1) == 3.15e6 &&
                deck_value(deck, "/YD/YDPJ/D1PJFS", 1) == 0,
                "joint set: friction %g cohesion %g fs %g (expected 0.6, 3.15e6, 0)", deck_value(deck, "/YD/YDPJ/D1PJFR", 1),
                deck_value(deck, "/YD/YDPJ/D1PJCO", 1), deck_value(deck, "/YD/YDPJ/D1PJFS", 1));
  free(deck);
}
END_TEST

/* The column with platen friction (-var mu) in Y2D's physics (-var y2d 1): its materials take Y2D's
 * friction law, so the scene can be written (D1PEFR = mu for both) and read back.  (Before, write_y2d
 * refused it: the native Coulomb law is not Y2D's.) */
START_TEST(test_column_friction_round_trip) {
  char *deck = seed_round_trip("column", "-var nx 8 -var steps 1000 -var mu 0.5", 20);
  const char *p = strstr(deck, "/YD/YDPE/D1PEFR ");
  ck_assert(p != NULL);
  char *q;
  long n = strtol(p + strlen("/YD/YDPE/D1PEFR "), &q, 10);
  ck_assert_int_ge(n, 2);
  for (long i = 0; i < n; i++) ck_assert_msg(strtod(q, &q) == 0.5, "property %ld: friction is not 0.5", i);
  free(deck);
}
END_TEST

/* Y2D's coded output (FORMAT.md 7.2) divides every value by its DCSIZ scale and clips it to [-1, 1]:
 * with the default scales (1) every velocity above 1 m/s and every stress above 1 Pa saturates, and
 * Y2D's output could not be compared with yfdem's run.  The written deck sets the scales so that
 * coordinates (with room to move), the impact speed and stresses well past the strength fit, the
 * 4-digit coding (ICOUTP 4), the first file index (ICOUTI 0) and `every K` as ICOUTF. */
START_TEST(test_output_scales) {
  char cwd[512], native[1200];
  ck_assert(getcwd(cwd, sizeof cwd));
  snprintf(native, sizeof native, "include %s/decks/beam.deck\n", cwd);
  char *err = NULL, *dir = NULL;
  int code = yft_run_binary("native.deck", native, "-var y2d 1 -var nx 20 -var steps 10 -var every 5", &err, &dir);
  ck_assert_msg(code == 0, "exit %d: %s", code, err);
  char path[1200];
  snprintf(path, sizeof path, "%s/beam.y", dir);
  char *deck = yft_slurp(path, 0);
  ck_assert(deck != NULL);
  ck_assert_int_eq((long)deck_value(deck, "/YD/YDC/ICOUTF", 0), 5);
  ck_assert_int_eq((long)deck_value(deck, "/YD/YDC/ICOUTI", 0), 0);
  ck_assert_int_eq((long)deck_value(deck, "/YD/YDC/ICOUTP", 0), 4);
  double c = deck_value(deck, "/YD/YDC/DCSIZC", 0), v = deck_value(deck, "/YD/YDC/DCSIZV", 0),
         st = deck_value(deck, "/YD/YDC/DCSIZS", 0);
  /* the largest |coordinate| of D2NCI (beam 1.0 m long, impactor top at 0.15 m) */
  const char *p = strstr(deck, "/YD/YDN/D2NCI 21 2 ");
  ck_assert(p != NULL);
  char *q;
  long n = strtol(p + strlen("/YD/YDN/D2NCI 21 2 "), &q, 10);
  double cmax = 0;
  for (long i = 0; i < 2 * n; i++) cmax = fmax(cmax, fabs(strtod(q, &q)));
  printf("write_y2d output scales: DCSIZC %g (largest |coordinate| %g), DCSIZV %g, DCSIZS %g\n", c, cmax, v, st);
  ck_assert_msg(cmax == 1.0 && c >= 2 * cmax && c <= 4 * cmax, "DCSIZC %g for coordinates up to %g", c, cmax);
  ck_assert_msg(v >= 2 * 5.0 && v <= 100, "DCSIZV %g for an impact at 5 m/s", v);
  ck_assert_msg(st >= 100 * 3.15e6 && st <= 1e10, "DCSIZS %g for stresses past f_t = 3.15 MPa", st);
  free(deck);
  free(err);
  free(dir);
}
END_TEST

/* Every kind of BC set: held base, prescribed velocity ramped in, point load with a table history,
 * pressure on the top face, gravity; two bodies in contact, one fractured. */
static const char *bc_scene =
  "material rock elastic rho 2500 E 20e9 nu 0.2 plane_strain damping 0.2 pen_n 2e11 pen_t 2e10 friction 0.4 friction_law y2d\n"
  "material pad elastic rho 7800 E 200e9 nu 0.3 plane_stress pen_n 2e11\n"
  "mesh rect rock rock 0 0 0.2 0.1 8 4 pattern alt\n"
  "mesh rect pad pad 0.05 0.1 0.15 0.13 4 1\n"
  "jointprop j ft 2e6 fs 4e6 gf 50 pen 2e12 cohesion 1e6 friction 0.6 damage reversible tangent y2d\n"
  "fracture rock j\n"
  "region base box -1 -1 1 1e-9\n"
  "region left box -1 0.001 1e-9 1\n" /* not the base corner: yfdem counts the work of two fixes on one node twice */
  "region top box 0.049 0.129 0.151 1\n"
  "group base node region base\n"
  "group left node region left body rock\n"
  "group top node region top\n"
  "fix hold base fixed xy\n"
  "history rise ramp 0 2e-5\n"
  "fix push left velocity 0.5 NULL history rise\n"
  "history pulse table 0 0 1e-5 1 3e-5 0.2\n"
  "load tip point at 0.2 0.1 -2e4 -5e4 history pulse\n"
  "load press top pressure 3e6\n"
  "gravity 0 -9.81\n"
  "contact pair pad rock\n"
  "contact self rock\n"
  "timestep auto safety 0.4\n"
  "thermo 100\n"
  "write_y2d scene.y steps 2400\n"
  "fracture_log native_breaks.csv\n"
  "run 2400\n";

START_TEST(test_bc_sets_round_trip) {
  int nb = 0;
  double worst = round_trip(bc_scene, "", "scene.y", "native_breaks.csv", &nb, NULL);
  printf("write_y2d round trip of the BC-set scene: %d joints broken in both, energies agree to %.1e\n", nb, worst);
  ck_assert_msg(nb >= 5, "only %d joints broke (the round trip must cover fracture)", nb);
  ck_assert_msg(worst <= 1e-9, "energies differ by %.2e of the largest", worst);
}
END_TEST

/* Y2D moves no node of lumped mass <= 1e-10 in the deck's units (ALGORITHMS 7, 9), yfdem moves every node: a
 * scene in tonnes and millimetres with 0.5 mm cells has corner masses of 1e-10 t/mm, and write_y2d wrote it
 * silently; read back, those nodes stayed put and the energies differed by 27 % of the largest after 200 steps
 * (2026-11-29 sweep).  Now an error names the node, its mass and the units; with the light nodes held at rest
 * (Y2D and yfdem hold them alike) the scene is written and runs the same way. */
START_TEST(test_light_nodes_refused) {
  static const char *scene =
    "material c elastic rho 2.4e-9 E 30000 nu 0.2 plane_stress\n"
    "mesh rect A c 0 0 4 2 8 4\n"
    "velocity A set 1000 0\n"
    "region l box -1 -1 1e-9 10\n"
    "group l node region l\n"
    "fix f l fixed xy\n"
    "timestep auto safety 0.4\n"
    "write_y2d light.y steps 200\n"
    "run 200\n";
  char *err = NULL, *dir = NULL;
  int code = yft_run_binary("light.deck", scene, "", &err, &dir);
  ck_assert_msg(code == 1 && strstr(err, "light.deck:8: error:") && strstr(err, "1e-10") &&
                strstr(err, "Y2D never moves"), "exit %d: %s", code, err);
  char path[1200];
  snprintf(path, sizeof path, "%s/light.y", dir);
  ck_assert(!yft_exists(path));
  free(err);
  free(dir);
  /* the same scene with every node on the boundary held at rest (the light ones are two corners) and its
   * middle moving: written, and the same run */
  static const char *held =
    "material c elastic rho 2.4e-9 E 30000 nu 0.2 plane_stress\n"
    "mesh rect A c 0 0 4 2 8 4\n"
    "region c box 1 0.5 3 1.5\n"
    "group c node region c\n"
    "velocity c set 1000 0\n"
    "region in box 0.01 0.01 3.99 1.99 side out\n"
    "group l node region in\n"
    "fix f l fixed xy\n"
    "timestep auto safety 0.4\n"
    "write_y2d light.y steps 200\n"
    "run 200\n";
  int nb = 0;
  double worst = round_trip(held, "", "light.y", NULL, &nb, NULL);
  ck_assert_msg(worst <= 1e-11, "energies differ by %.2e of the largest", worst);
}
END_TEST

/* Features Y2D cannot express: an error that names them, at the right line. */
static const struct {
  const char *change, *with, *text;
} refusals[] = {
  {"damage reversible tangent y2d", "", "damage irreversible (Y2D's joints have no damage memory"},
  {"fracture rock j\n", "fracture rock j group rock\n", "limits fracture to a region or group of body 'rock'"},
  {"fix push left velocity 0.5 NULL history rise", "fix push left displacement 1e-4 NULL",
   "fix 'push' prescribes a displacement: Y2D has no displacement condition"},
  {"history pulse table 0 0 1e-5 1 3e-5 0.2", "history pulse sine 1e-4", "history 'pulse' is a sine"},
  {"gravity 0 -9.81", "gravity 0 -9.81\ndamping mass 10", "mass damping (damping mass 10)"},
  {"gravity 0 -9.81", "gravity 1 -9.81", "gravity has an x component"},
  {"friction 0.4 friction_law y2d", "friction 0.4", "material 'rock' has friction 0.4 with the coulomb friction law"},
  {"damage reversible tangent y2d", "damage reversible tangent y2d law linear", "its softening law is not Y2D's"},
  {"damage reversible tangent y2d", "damage reversible tangent y2d floor none", "floor none (Y2D's softening length"},
  {"damage reversible tangent y2d", "damage reversible tangent y2d weibull 10", "random strengths (weibull/normal)"},
  {"load press top pressure 3e6\n", "load press top pressure 3e6\nload side left pressure 1e6\n",
   "its conditions have different time histories (rise and none)"},
  {"region top box 0.049 0.129 0.151 1\n", "region top box 0.049 0.0 0.151 1\n", "the edge loads would act on"},
  {"write_y2d scene.y steps 2400\n", "run 1\nwrite_y2d scene.y steps 2400\n", "put it before the first run"},
  /* an auxetic material: yfdem runs it, Y2D refuses its negative D1PELA (FORMAT.md 6); it was written */
  {"material pad elastic rho 7800 E 200e9 nu 0.3", "material pad elastic rho 7800 E 200e9 nu -0.3",
   "Y2D refuses a negative D1PELA"},
};

START_TEST(test_refusals) {
  const char *p = strstr(bc_scene, refusals[_i].change);
  ck_assert(p != NULL);
  char deck[4096];
  snprintf(deck, sizeof deck, "%.*s%s%s", (int)(p - bc_scene), bc_scene, refusals[_i].with,
           p + strlen(refusals[_i].change));
  char *err = NULL, *dir = NULL;
  int code = yft_run_binary("bad.deck", deck, "", &err, &dir);
  ck_assert_msg(code == 1, "exit %d: %s", code, err);
  ck_assert_msg(strstr(err, "bad.deck:") && strstr(err, refusals[_i].text), "no '%s' in: %s", refusals[_i].text, err);
  /* and no deck is left behind */
  char path[1200];
  snprintf(path, sizeof path, "%s/scene.y", dir);
  ck_assert(!yft_exists(path));
  free(err);
  free(dir);
}
END_TEST

/* What write_y2d approximates is said in a warning, and the deck is written: the exact joint tangent
 * (Y2D's is e/(h + 1e-10 m)), 'contact joined skip', contact rules widened to all pairs, a traction of
 * fixed direction (Y2D's edge loads turn with the face).  A scene read by read_y2d is refused (run
 * that deck in Y2D). */
START_TEST(test_warnings) {
  char deck[4096];
  const char *p = strstr(bc_scene, "contact self rock\n");
  ck_assert(p != NULL);
  snprintf(deck, sizeof deck, "%.*scontact self rock\ncontact joined skip\ncontact search every\n%s", (int)(p - bc_scene), bc_scene,
           p + strlen("contact self rock\n"));
  char *q = strstr(deck, " tangent y2d");
  ck_assert(q != NULL);
  memmove(q, q + strlen(" tangent y2d"), strlen(q + strlen(" tangent y2d")) + 1);
  q = strstr(deck, "pressure 3e6");
  ck_assert(q != NULL);
  memmove(q + strlen("traction 0 -3e6"), q + strlen("pressure 3e6"), strlen(q + strlen("pressure 3e6")) + 1);
  memcpy(q, "traction 0 -3e6", strlen("traction 0 -3e6"));
  q = strstr(deck, "run 2400");
  ck_assert(q != NULL);
  strcpy(q, "run 1\n");
  char *err = NULL, *dir = NULL;
  int code = yft_run_binary("warn.deck", deck, "", &err, &dir);
  ck_assert_msg(code == 0, "exit %d: %s", code, err);
  static const char *const want[] = {"e/(h + 1e-10 m), this one as e/h", "'contact joined skip' has no Y2D equivalent",
                                     "contact rule(s) are widened to all pairs",
                                     "load 'press' is a traction of fixed direction (0, -3e+06) Pa; Y2D's edge loads",
                                     "'contact search every' has no Y2D equivalent"};
  for (int i = 0; i < 5; i++)
    ck_assert_msg(strstr(err, "warn.deck:") && strstr(err, want[i]), "no warning '%s' in: %s", want[i], err);
  char path[1200];
  snprintf(path, sizeof path, "%s/scene.y", dir);
  ck_assert(yft_exists(path));
  /* search every is written as the buffer, a search by travel (DIEZON 0 searched every step with
   * no buffer: fewer couples, another friction energy) */
  char *y = yft_slurp(path, 0);
  const char *dz = y ? strstr(y, "/YD/YDI/DIEZON ") : NULL;
  ck_assert_msg(dz && strtod(dz + 15, NULL) > 0, "DIEZON of search every: %.40s", dz ? dz : "(none)");
  free(y);
  free(err);
  free(dir);
  char cwd[512];
  ck_assert(getcwd(cwd, sizeof cwd));
  snprintf(deck, sizeof deck, "read_y2d %s/tests/y2d/tiny.y\nwrite_y2d again.y steps 10\n", cwd);
  code = yft_run_binary("again.deck", deck, "", &err, &dir);
  ck_assert_msg(code == 1 && strstr(err, "again.deck:2") && strstr(err, "this scene was read from a Y2D deck"), "exit %d: %s",
                code, err);
  free(err);
  free(dir);
}
END_TEST

Suite *y2d_write_suite(void) {
  Suite *s = suite_create("y2d_write");
  TCase *tc = tcase_create("round_trip");
  tcase_set_timeout(tc, 120);
  tcase_add_test(tc, test_beam_round_trip);
  tcase_add_test(tc, test_column_round_trip);
  tcase_add_test(tc, test_bc_sets_round_trip);
  tcase_add_test(tc, test_light_nodes_refused);
  tcase_add_test(tc, test_beam_mohr_coulomb_round_trip);
  tcase_add_test(tc, test_output_scales);
  tcase_add_test(tc, test_column_friction_round_trip);
  suite_add_tcase(s, tc);
  tc = tcase_create("refusals");
  tcase_add_loop_test(tc, test_refusals, 0, (int)(sizeof refusals / sizeof refusals[0]));
  tcase_add_test(tc, test_warnings);
  suite_add_tcase(s, tc);
  return s;
}
