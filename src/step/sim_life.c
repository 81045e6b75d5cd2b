/* sim_life.c: the start and the end of a simulation's life (sim_init, sim_free; declared in
 * sim.h): the modules that keep state in YfSim are set up and freed here, so that sim.c, which
 * they all include, includes none of them.
 */
#include <stdlib.h>
#include <string.h>
#include "sim.h"
#include "bc.h"
#include "contact.h"
#include "joint.h"
#include "mesh.h"
#include "region.h"
#include "energy.h"

void sim_init(YfSim *s) {
  memset(s, 0, sizeof *s);
  model_init(&s->model);
  s->dt_safety = 0.5;
  s->ebal_tol = YF_EBAL_TOL;
  s->thermo_every = 0;
  s->threads = 1;
  sim_add_bc_kind(s, &bc_kind_native);
}

void sim_free(YfSim *s) {
  YfEvent ev = {.kind = YF_EV_FREE};
  sim_notify(s, &ev); /* restarts, dumps, metrics */
  joints_free(s);
  contact_free(s);
  for (int i = 0; i < s->nbc_kind; i++)
    if (s->bc_kind[i]->free) s->bc_kind[i]->free(s);
  for (int i = 0; i < s->nhist; i++) { free(s->hist[i].t); free(s->hist[i].v); }
  free(s->hist);
  model_free(&s->model);
  region_reset();
  mesh_reset();
  memset(s, 0, sizeof *s); /* a second sim_free (or one of a never-initialised, zeroed YfSim) frees nothing */
}
