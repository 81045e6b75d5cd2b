/* joint.c: fracture in the scene (see joint.h).  This first version holds no joints: no deck
 * command creates fracturing bodies yet; the fracture issue fills it in. */
#include <math.h>
#include <stdio.h>
#include "joint.h"

void joints_insert(YfSim *s) { (void)s; }
void joints_forces(YfSim *s) { (void)s; }
double joints_stable_dt(YfSim *s, char *what, size_t n) {
  (void)s;
  if (what && n) what[0] = 0;
  return INFINITY;
}
long joints_count(const YfSim *s) { (void)s; return 0; }
long joints_broken(const YfSim *s) { (void)s; return 0; }
void joints_summary(YfSim *s) { (void)s; }
void joints_free(YfSim *s) { (void)s; }
