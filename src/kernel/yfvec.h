/* yfvec.h: small vector helpers of the hot loops (GCC vector extensions; each lane is an ordinary
 * IEEE operation, so results are the bits of the scalar code, and -ffp-contract=off keeps
 * multiplications and additions unfused).  Plain x86-64 runs them on SSE2; functions compiled
 * with __attribute__((target_clones("avx2", "default"))) get one AVX register per 4-wide vector
 * where the CPU has it. */
#ifndef YF_VEC_H
#define YF_VEC_H
#include <math.h>
#include <stdint.h>
#ifdef __SSE2__
#include <emmintrin.h>
#endif

typedef double yf_v2 __attribute__((vector_size(16)));
typedef double yf_v4 __attribute__((vector_size(32)));
typedef long long yf_v4l __attribute__((vector_size(32))); /* lane masks: 0 or -1 (all bits) */

/* Lanes of 4-wide vectors picked by constant indices (0-3: lanes of a, 4-7: lanes of b): moves
 * only, exact.  __builtin_shufflevector is clang's and GCC's (12 and later); GCC 11 and older
 * have only __builtin_shuffle. */
#if defined(__clang__) || (defined(__GNUC__) && __GNUC__ >= 12)
#define YF_SHUF4(a, b, i, j, k, l) __builtin_shufflevector((a), (b), i, j, k, l)
#else
#define YF_SHUF4(a, b, i, j, k, l) __builtin_shuffle((a), (b), (yf_v4l){i, j, k, l})
#endif

/* One copy of a hot function per instruction set, chosen once at start-up (GCC's target_clones).
 * Clang (the fuzzing build, tools/fuzz) gets the portable copy only: clang 14 does not link the
 * clones of a function defined in one file and called from another. */
#if defined(__clang__)
#define YF_CLONES
#else
#define YF_CLONES __attribute__((target_clones("avx2", "default")))
#endif

/* a / b and c / d as one packed division: half the divider work of two scalar divisions. */
static inline void yf_div2(double a, double b, double c, double d, double *ab, double *cd)
{
  yf_v2 q = (yf_v2){a, c} / (yf_v2){b, d};
  *ab = q[0];
  *cd = q[1];
}

/* Lanes of u where the mask m is set, else of w (a bit select: no arithmetic, exact).  Macros
 * rather than functions: a 32-byte vector passed or returned by value would change the ABI
 * between the AVX and the default build of one function (GCC's -Wpsabi). */
#define YF_SEL4(m, u, w) ((yf_v4)(((m) & (yf_v4l)(u)) | (~(m) & (yf_v4l)(w))))

/* |a| per lane: the sign bit cleared, as fabs. */
#define YF_ABS4(a) ((yf_v4)((yf_v4l)(a) & (yf_v4l){INT64_MAX, INT64_MAX, INT64_MAX, INT64_MAX}))

/* *a = sqrt(*a) per lane, correctly rounded (IEEE, as sqrt): two packed SSE2 square roots (GCC's
 * vector extensions have no square root operator); other targets take the lanes one by one. */
static inline __attribute__((always_inline)) void yf_sqrt4(yf_v4 *a)
{
#ifdef __SSE2__
  yf_v2 lo = {(*a)[0], (*a)[1]}, hi = {(*a)[2], (*a)[3]};
  lo = (yf_v2)_mm_sqrt_pd((__m128d)lo);
  hi = (yf_v2)_mm_sqrt_pd((__m128d)hi);
  *a = (yf_v4){lo[0], lo[1], hi[0], hi[1]};
#else
  *a = (yf_v4){sqrt((*a)[0]), sqrt((*a)[1]), sqrt((*a)[2]), sqrt((*a)[3])};
#endif
}

#endif
