/* check_docs.c: the README's deck reference is the command table (commands.def), word for word,
 * so the documentation cannot drift from what the program accepts. */
#include <check.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include "commands.h"
#include "deck.h"
#include "yftest.h"

START_TEST(test_readme_reference_matches_table) {
  FILE *f = fopen("README.md", "r");
  ck_assert_msg(f != NULL, "README.md not found (run the tests from the repository root)");
  static char buf[1 << 20];
  size_t n = fread(buf, 1, sizeof buf - 1, f);
  buf[n] = 0;
  fclose(f);
  const char *b = strstr(buf, "<!-- deck-reference:begin -->\n"), *e = strstr(buf, "<!-- deck-reference:end -->");
  ck_assert_msg(b && e && e > b, "README.md lacks the deck-reference markers");
  b += strlen("<!-- deck-reference:begin -->\n");
  char *gen = NULL;
  size_t glen = 0;
  FILE *m = open_memstream(&gen, &glen);
  commands_print_reference(m);
  fclose(m);
  size_t rlen = (size_t)(e - b);
  ck_assert_msg(rlen == glen && !memcmp(b, gen, glen),
                "README.md's deck reference differs from the command table: run tools/update-reference");
  /* and every command appears with its name */
  for (const YfCommand *c = yf_commands; c->name; c++) {
    char key[80];
    snprintf(key, sizeof key, "| `%s` |", c->name);
    ck_assert_msg(strstr(b, key) != NULL, "command %s missing from README", c->name);
  }
  free(gen);
}
END_TEST

/* docs/reference.md, a section per command, is the command table too. */
START_TEST(test_reference_sections_match_table) {
  char *doc = yft_slurp("docs/reference.md", 0);
  ck_assert_msg(doc != NULL, "docs/reference.md not found (run the tests from the repository root)");
  char *gen = NULL;
  size_t glen = 0;
  FILE *m = open_memstream(&gen, &glen);
  commands_print_sections(m);
  fclose(m);
  ck_assert_msg(strlen(doc) == glen && !memcmp(doc, gen, glen),
                "docs/reference.md differs from the command table: run tools/update-reference");
  for (const YfCommand *c = yf_commands; c->name; c++) {
    char key[80];
    snprintf(key, sizeof key, "\n## %s\n", c->name);
    ck_assert_msg(strstr(doc, key) != NULL, "command %s has no section", c->name);
  }
  ck_assert_msg(strstr(doc, "Related: [`fix`](#fix)") != NULL || strstr(doc, "[`fix`](#fix)") != NULL,
                "no related-command links");
  free(gen);
  free(doc);
}
END_TEST

static int word_char(char c) { return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_'; }

/* Is w (n chars) a whole word of text[0..len)? */
static int has_word(const char *text, size_t len, const char *w, size_t n) {
  for (size_t i = 0; i + n <= len; i++)
    if (!strncmp(text + i, w, n) && (i == 0 || !word_char(text[i - 1])) && (i + n == len || !word_char(text[i + n])))
      return 1;
  return 0;
}

/* Every command has its arguments (command_args.def), and every placeholder of its usage (an
 * upper-case word: NAME, FILE, X0, ...) is explained by a line of them (among the words before
 * the line's first ": "); no row names a command that does not exist.  The sections of
 * docs/reference.md print them with units and defaults (issue 19). */
START_TEST(test_every_command_has_its_arguments) {
  char missing[4096] = "";
  size_t k = 0;
  for (const YfCommand *c = yf_commands; c->name; c++) {
    const char *args = commands_args(c->name);
    if (!args || !args[0]) {
      k += (size_t)snprintf(missing + k, sizeof missing - k, "%s: no arguments row; ", c->name);
      continue;
    }
    const char *u = c->usage;
    for (size_t i = 0; u[i] && k < sizeof missing - 200; i++) {
      if (!(u[i] >= 'A' && u[i] <= 'Z') || (i > 0 && (word_char(u[i - 1]) || u[i - 1] == '$'))) continue;
      size_t n = 0;
      while ((u[i + n] >= 'A' && u[i + n] <= 'Z') || (u[i + n] >= '0' && u[i + n] <= '9') || u[i + n] == '_') n++;
      if (word_char(u[i + n])) { i += n - 1; continue; } /* part of a longer word (n >= 1; the loop adds 1) */
      int found = 0;
      for (const char *p = args; *p && !found;) { /* the words part of each line */
        const char *e = strchr(p, '\n'), *end = e ? e : p + strlen(p), *colon = strstr(p, ": ");
        size_t len = colon && colon < end ? (size_t)(colon - p) : 0;
        found = has_word(p, len, u + i, n);
        p = e ? e + 1 : end;
      }
      if (!found) k += (size_t)snprintf(missing + k, sizeof missing - k, "%s: %.*s unexplained; ", c->name, (int)n, u + i);
      i += n - 1; /* the loop's i++ lands on the character after the word: never past the NUL */
    }
  }
  for (const YfCommandArgs *r = yf_command_args; r->name; r++) {
    int n = 0;
    for (const YfCommandArgs *q = yf_command_args; q->name; q++) n += !strcmp(q->name, r->name);
    if (!deck_find_command(r->name) || n != 1)
      k += (size_t)snprintf(missing + k, sizeof missing - k, "%s: %s; ", r->name, n != 1 ? "two rows" : "no such command");
  }
  ck_assert_msg(k == 0, "command_args.def: %s", missing);
  /* and the reference's sections carry them */
  char *doc = yft_slurp("docs/reference.md", 0);
  ck_assert_ptr_nonnull(doc);
  ck_assert_msg(strstr(doc, "\n## material\n") && strstr(doc, "Arguments:\n\n- `NAME`: the material's name") &&
                strstr(doc, "- `rho R`: density [kg/m^3]; required\n"), "docs/reference.md lacks the arguments");
  free(doc);
}
END_TEST

/* decks/sweep.deck does what its comments say: three bars of 10, 20 and 40 cells along built by a
 * loop, one dump showing all three (sweep.xmf), and each bar's end reaction printed next to
 * E A u / L = 2e4 N/m, a little above it (the clamps' lateral restraint) and closer on finer meshes.
 * Measured: 20096, 20064, 20052 N/m. */
/* The reference said of `region ... side out` that "its boundary counts as inside", so not as the
 * outside; the selection keeps the boundary on either side (a box side out selects the box's own
 * edges: 24 of a 5 x 5 grid's 25 nodes for the corner box [0, 0.5]^2, only its centre node left
 * out).  The reference now says what the selection does. */
START_TEST(test_region_side_out_documented) {
  const char *args = commands_args("region");
  ck_assert_ptr_nonnull(args);
  const char *side = strstr(args, "side in|out:");
  ck_assert_ptr_nonnull(side);
  ck_assert_msg(strstr(side, "selected on either side") && !strstr(side, "counts as inside"), "%s", side);
  YfSim *s = yft_run("material m elastic rho 1000 E 1e9 nu 0.25 plane_stress\nmesh rect b m 0 0 1 1 4 4\n"
                     "region r box 0 0 0.5 0.5 side out\ngroup g node region r\n");
  int g = model_group(&s->model, "g", 0), cnt = 0;
  for (int i = 0; i < s->model.node.n; i++) cnt += (s->model.node.gmask[i] >> g) & 1;
  ck_assert_int_eq(cnt, 24);
  sim_free(s);
}
END_TEST

/* The usage of dump listed the fields without fc, which the parser accepts (and README's ParaView
 * section uses: 'fields ... fc'): every field a dump writes is in the usage's list. */
START_TEST(test_dump_usage_lists_every_field) {
  const char *usage = NULL;
  for (const YfCommand *c = yf_commands; c->name; c++)
    if (!strcmp(c->name, "dump")) usage = c->usage;
  ck_assert_ptr_nonnull(usage);
  const char *b = strstr(usage, "[fields "), *e = b ? strchr(b, ']') : NULL;
  ck_assert_msg(b && e, "%s", usage);
  static const char *const fields[] = {"u", "v", "f", "stress", "vonmises", "sigma1", "material", "body", "fc"};
  for (size_t k = 0; k < sizeof fields / sizeof fields[0]; k++) {
    int found = 0;
    for (const char *p = b + 8; p < e && !found; p++) {
      size_t n = strlen(fields[k]);
      found = !strncmp(p, fields[k], n) && p[-1] == ' ' && (p[n] == ' ' || p[n] == ']');
    }
    ck_assert_msg(found, "dump usage lacks field '%s': %.*s", fields[k], (int)(e - b + 1), b);
  }
}
END_TEST

START_TEST(test_sweep_deck_does_what_it_says) {
  char cwd[900], deck[1024], *err, *dir;
  ck_assert_ptr_nonnull(getcwd(cwd, sizeof cwd));
  snprintf(deck, sizeof deck, "include %s/decks/sweep.deck\n", cwd);
  int rc = yft_run_binary("s.deck", deck, "", &err, &dir);
  ck_assert_msg(rc == 0, "exit %d:\n%s", rc, err);
  char p[1200];
  snprintf(p, sizeof p, "%s/log.yfdem", dir);
  char *log = yft_slurp(p, 0);
  ck_assert_ptr_nonnull(log);
  double r[4] = {0, 0, 0, 0};
  for (int k = 1; k <= 3; k++) {
    char head[80];
    snprintf(head, sizeof head, "\nbar %d (%d cells along): end reaction ", k, 10 << (k - 1));
    const char *q = strstr(log, head);
    ck_assert_msg(q != NULL, "no line '%s' in the log:\n%s", head + 1, log);
    double ref;
    ck_assert_int_eq(sscanf(q + strlen(head), "%lf N/m, E A u / L = %lf N/m", &r[k], &ref), 2);
    ck_assert_msg(ref == 2e4, "bar %d: E A u / L printed as %g", k, ref);
    ck_assert_msg(r[k] > 2e4 && r[k] < 1.01 * 2e4, "bar %d: end reaction %.9g N/m, not within 1 %% above 2e4", k, r[k]);
    if (k > 1) ck_assert_msg(r[k] < r[k - 1], "bar %d: %.9g N/m not closer to 2e4 than bar %d's %.9g", k, r[k], k - 1, r[k - 1]);
  }
  snprintf(p, sizeof p, "%s/sweep.xmf", dir);
  char *xmf = yft_slurp(p, 0);
  ck_assert_msg(xmf != NULL, "no sweep.xmf");
  int nframe = 0;
  for (const char *q = xmf; (q = strstr(q, "<Grid Name=\"frame_")) != NULL; q++) nframe++;
  ck_assert_int_eq(nframe, 5); /* steps 0, 500, ..., 2000 */
  /* the three bars in one mesh: 2 x (10 x 2 + 20 x 4 + 40 x 8) triangles (pattern alt) */
  ck_assert_msg(strstr(xmf, "NumberOfElements=\"840\"") != NULL, "the frames do not hold the three bars");
  free(xmf);
  free(log);
  free(err);
  free(dir);
}
END_TEST

Suite *docs_suite(void) {
  Suite *s = suite_create("docs");
  TCase *t = tcase_create("readme");
  tcase_add_test(t, test_readme_reference_matches_table);
  tcase_add_test(t, test_reference_sections_match_table);
  tcase_add_test(t, test_every_command_has_its_arguments);
  tcase_add_test(t, test_sweep_deck_does_what_it_says);
  tcase_add_test(t, test_region_side_out_documented);
  tcase_add_test(t, test_dump_usage_lists_every_field);
  suite_add_tcase(s, t);
  return s;
}
