/* memcap.h: refuse a scene that cannot fit in memory before allocating it.
 *
 * Readers that learn a size from their input (mesh rect NX NY, a .msh $Nodes header, a .y
 * deck's capacities such as MNOPO) estimate the bytes the scene will need and call
 * yf_mem_check first, so an absurd count is a clear deck error (exit 1) naming the input and
 * the numbers, not a crash, an out-of-memory kill or minutes of swapping.
 *
 * The cap is the machine's physical memory (sysconf), or YFDEM_MEM_MAX bytes when that
 * variable is set (tests and the fuzzer use a small cap).
 */
#ifndef YF_MEMCAP_H
#define YF_MEMCAP_H
#include "err.h"

/* Bytes per node and per triangle of a prepared scene including the step's work arrays, the
 * gather lists and, for a fracturing body, its node copies and joints (an upper estimate). */
#define YF_BYTES_PER_NODE 200.0
#define YF_BYTES_PER_TRI 600.0

/* Memory cap [bytes]. */
double yf_mem_cap(void);
/* Deck error at loc (may be NULL) when bytes exceed the cap: "WHAT needs about X GB, more
 * than the Y GB of memory ...". */
void yf_mem_check(const YfLoc *loc, double bytes, const char *what);

#endif
