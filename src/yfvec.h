/* yfvec.h: small vector helpers of the hot loops (GCC vector extensions; each lane is an ordinary
 * IEEE operation, so results are the bits of the scalar code, and -ffp-contract=off keeps
 * multiplications and additions unfused).  Plain x86-64 runs them on SSE2. */
#ifndef YF_VEC_H
#define YF_VEC_H

typedef double yf_v2 __attribute__((vector_size(16)));

/* a / b and c / d as one packed division: half the divider work of two scalar divisions. */
static inline void yf_div2(double a, double b, double c, double d, double *ab, double *cd)
{
  yf_v2 q = (yf_v2){a, c} / (yf_v2){b, d};
  *ab = q[0];
  *cd = q[1];
}

#endif
