/* parfor.h: a loop that enters OpenMP only when it runs on a team of two threads or more.
 *
 * `#pragma omp parallel for if (c)` with c false is not a plain loop: libgomp (GCC 12) still
 * builds a team of one thread for it at every entry, with a memalign, a free and a futex system
 * call, about a microsecond each time; so does a true c when the team is one thread (-threads 1).
 * The step has three to eight such loops, so a small scene (a verification deck, a sweep of
 * 100-1000 triangles, below the sizes that put a loop on the team) spent more on them than on its
 * triangles: 16 triangles took 5.7 us per step, 60 % of it in libgomp and the kernel
 * (docs/PERFORMANCE.md, "What a scene costs").  YF_PARFOR_IF runs the loop plainly unless COND
 * holds and more than one thread may run, and as `omp parallel for CLAUSES` otherwise.  Every loop
 * given to it writes only its own slots (or reduces by max, which is exact), so both ways give
 * the same bits.
 *
 *   YF_PARFOR_IF(n >= PAR_MIN, schedule(static), for (int i = 0; i < n; i++) a[i] = f(i););
 */
#ifndef YF_PARFOR_H
#define YF_PARFOR_H

#ifdef _OPENMP
#include <omp.h>
#define YF_TEAM_OF_MANY() (omp_get_max_threads() > 1)
#else
#define YF_TEAM_OF_MANY() 0
#endif

/* Loops whose condition held, counted by YF_PARFOR_IF and YF_WANT_TEAM (a region outside the
 * macro): a step that counted none ran on one thread whatever the team, so the thread governor
 * (step/threads.c) does not time it, and saves the two reads of the CPU clock it would cost.
 * Counted by the main thread, outside parallel regions. */
extern unsigned long yf_team_wanted;
#define YF_WANT_TEAM(cond) ((cond) ? (yf_team_wanted++, 1) : 0)

#define YF_PRAGMA_(x) _Pragma(#x)
#define YF_PARFOR_IF(cond, clauses, ...)     \
  do {                                       \
    if (YF_WANT_TEAM(cond) && YF_TEAM_OF_MANY()) { \
      YF_PRAGMA_(omp parallel for clauses)   \
      __VA_ARGS__                            \
    } else {                                 \
      __VA_ARGS__                            \
    }                                        \
  } while (0)

#endif
