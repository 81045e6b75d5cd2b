/* check_main.c: the one Check runner of `make check`.
 *
 * Every `Suite *NAME_suite(void)` of tests/check_*.c is listed in build/tests/suites.h (generated
 * by the Makefile) and added to one SRunner, which prints one closing summary line.
 * CK_RUN_SUITE=name runs one suite only.
 */
#include <check.h>
#include <stdlib.h>

#define YF_SUITE(name) Suite *name##_suite(void);
#include "suites.h"
#undef YF_SUITE

int main(void) {
  SRunner *sr = srunner_create(NULL);
#define YF_SUITE(name) srunner_add_suite(sr, name##_suite());
#include "suites.h"
#undef YF_SUITE
  srunner_set_fork_status(sr, CK_FORK);
  srunner_run_all(sr, CK_NORMAL);
  int failed = srunner_ntests_failed(sr);
  srunner_free(sr);
  return failed ? EXIT_FAILURE : EXIT_SUCCESS;
}
