/* query.h: simulation quantities that deck expressions can read (LAMMPS thermo keywords and
 * group reductions), e.g.  print "tip deflection $(uy_tip) m"  or  if "${broken} > 0" then ... */
#ifndef YF_QUERY_H
#define YF_QUERY_H
#include <stddef.h>
#include "sim.h"

/* 1 and *val when name is a known quantity, 0 when unknown, -1 on error (message in err). */
int sim_query(YfSim *s, const char *name, double *val, char *err, size_t errlen);

/* 1 when name is a keyword sim_query answers (ke, dt_limit, ...), 2 a group reduction of a group
 * or body that exists (ux_G, ...), else 0: the deck warns when a variable of that name hides it
 * from bare expressions. */
int sim_query_known(YfSim *s, const char *name);

/* The keywords sim_query answers (ke, strain, ..., dt_limit), NULL-terminated: what an unknown
 * name in an expression may have been meant as. */
const char *const *sim_query_keywords(void);

#endif
