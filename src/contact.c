/* contact.c: contact in the scene (see contact.h).  This first version has no contact: no deck
 * command enables it yet; the contact issue fills it in. */
#include <math.h>
#include <stdio.h>
#include "contact.h"

void contact_prepare(YfSim *s) { (void)s; }
void contact_step(YfSim *s) { (void)s; }
double contact_stable_dt(YfSim *s, char *what, size_t n) {
  (void)s;
  if (what && n) what[0] = 0;
  return INFINITY;
}
long contact_pairs(const YfSim *s) { (void)s; return 0; }
void contact_free(YfSim *s) { (void)s; }
