/* memcap.c: the memory cap of scene sizes read from input (see memcap.h). */
#include <stdlib.h>
#include <unistd.h>
#include "memcap.h"

double yf_mem_cap(void) {
  const char *e = getenv("YFDEM_MEM_MAX");
  if (e && *e) {
    char *end;
    double v = strtod(e, &end);
    if (end != e && v > 0) return v;
  }
  long pages = sysconf(_SC_PHYS_PAGES), psz = sysconf(_SC_PAGESIZE);
  if (pages > 0 && psz > 0) return (double)pages * (double)psz;
  return 64e9; /* unknown: a generous fixed cap */
}

void yf_mem_check(const YfLoc *loc, double bytes, const char *what) {
  double cap = yf_mem_cap();
  if (!(bytes > cap)) return; /* also refuses NaN */
  yf_deck_error(loc, "%s needs about %.3g GB of memory, more than the %.3g GB available%s; use a smaller size",
                what, bytes / 1e9, cap / 1e9, getenv("YFDEM_MEM_MAX") ? " (YFDEM_MEM_MAX)" : "");
}
