/* strictnum.c: the strict number rules of every text yfdem reads (see strictnum.h). */
#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "strictnum.h"

int yf_parse_double(const char *s, double *out) {
  if (!s) return 0;
  const char *p = s;
  if (*p == '+' || *p == '-') p++;
  int digits = 0;
  while (isdigit((unsigned char)*p)) p++, digits++;
  if (*p == '.') {
    p++;
    while (isdigit((unsigned char)*p)) p++, digits++;
  }
  if (!digits) return 0; /* "", ".", "nan", "inf", "e5" */
  if (*p == 'e' || *p == 'E') {
    p++;
    if (*p == '+' || *p == '-') p++;
    if (!isdigit((unsigned char)*p)) return 0;
    while (isdigit((unsigned char)*p)) p++;
  }
  if (*p) return 0; /* trailing junk: "3.0x", "1 " */
  errno = 0;
  double v = strtod(s, NULL);
  if (!isfinite(v)) return 0; /* overflow: "1e999" (underflow to 0 or a subnormal is accepted) */
  if (out) *out = v;
  return 1;
}

int yf_parse_long(const char *s, long *out) {
  if (!s) return 0;
  const char *p = s;
  if (*p == '+' || *p == '-') p++;
  if (!*p) return 0;
  while (isdigit((unsigned char)*p)) p++;
  if (!*p) { /* plain integer: full long range */
    errno = 0;
    long v = strtol(s, NULL, 10);
    if (errno == ERANGE) return 0;
    if (out) *out = v;
    return 1;
  }
  /* "1e6", "2.0": a number whose value is an exact integer (within 2^53, where doubles are exact) */
  double d;
  if (!yf_parse_double(s, &d)) return 0;
  if (d != floor(d) || fabs(d) > 9007199254740992.0) return 0;
  if (d == 0.0 && strcspn(s, "123456789") < strcspn(s, "eE")) return 0; /* 1e-400: not 0 */
  if (out) *out = (long)d;
  return 1;
}
