/* strictnum.h: the strict number rules of every text yfdem reads: the deck's words and its row
 * files (deck layer), and the Gmsh .msh files (model/gmsh.c), so that a number one of them takes
 * the others take too.  A number is decimal: an optional sign, digits with an optional '.', an
 * optional exponent, nothing after it; strtod's hex ("0x1p-1"), "inf", "nan" and a value beyond
 * a double are refused.  The callers say where and why in their own messages. */
#ifndef YF_STRICTNUM_H
#define YF_STRICTNUM_H

/* Returns 1 and sets *out (out may be NULL) when the whole of s is such a finite number, 0 if not
 * (an underflow to 0 or a subnormal is accepted: the deck's arg_num refuses its own). */
int yf_parse_double(const char *s, double *out);
/* The same for an integer: digits (the whole long range), or a number whose value is an exact
 * integer within 2^53 ("1e6", "2.0"). */
int yf_parse_long(const char *s, long *out);

#endif
