/* check_docs.c: the README's deck reference is the command table (commands.def), word for word,
 * so the documentation cannot drift from what the program accepts. */
#include <check.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
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

Suite *docs_suite(void) {
  Suite *s = suite_create("docs");
  TCase *t = tcase_create("readme");
  tcase_add_test(t, test_readme_reference_matches_table);
  tcase_add_test(t, test_reference_sections_match_table);
  suite_add_tcase(s, t);
  return s;
}
