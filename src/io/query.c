/* query.c: what a deck expression can ask the simulation (see query.h).
 *
 * Thermo keywords: ke, strain, ext_work (loads and supports), gravity_work, ext (the two: the thermo
 * line's ExtWork), damping, joint_dissipated, friction, diss (the three), contact_energy, balance
 * (the energy check's residual, energy.c), broken, pairs, ntri, nnodes, dt_limit.  Group reductions, NAME_GROUP with GROUP a group or
 * body name: ux_G, uy_G (mean displacement [m]), vx_G, vy_G (mean velocity [m/s]), x_G, y_G
 * (mean position [m]), fx_G, fy_G (sum of nodal forces [N/m]), mass_G [kg/m].  Means are plain
 * averages over the group's nodes (copies of a node in a fracturing body count separately).
 */
#include <string.h>
#include "contact.h"
#include "energy.h"
#include "joint.h"
#include "query.h"
#include "run.h"

static int group_reduce(YfSim *s, const char *what, const char *g, double *val, char *err, size_t n) {
  YfModel *m = &s->model;
  int k = model_group(m, g, 0);
  if (k < 0) {
    snprintf(err, n, "'%s_%s': no group or body named '%s'", what, g, g);
    return -1;
  }
  uint64_t bit = (uint64_t)1 << k;
  const YfNodes *nd = &m->node;
  double sum = 0;
  long cnt = 0;
  for (int i = 0; i < nd->n; i++) {
    if (!(nd->gmask[i] & bit)) continue;
    cnt++;
    if (!strcmp(what, "ux")) sum += nd->x[i] - nd->x0[i];
    else if (!strcmp(what, "uy")) sum += nd->y[i] - nd->y0[i];
    else if (!strcmp(what, "vx")) sum += nd->vx[i];
    else if (!strcmp(what, "vy")) sum += nd->vy[i];
    else if (!strcmp(what, "x")) sum += nd->x[i];
    else if (!strcmp(what, "y")) sum += nd->y[i];
    else if (!strcmp(what, "fx")) sum += nd->fx[i];
    else if (!strcmp(what, "fy")) sum += nd->fy[i];
    else if (!strcmp(what, "mass")) sum += nd->m[i];
  }
  if (!cnt) {
    snprintf(err, n, "'%s_%s': group '%s' has no nodes", what, g, g);
    return -1;
  }
  int is_sum = !strcmp(what, "fx") || !strcmp(what, "fy") || !strcmp(what, "mass");
  *val = is_sum ? sum : sum / (double)cnt;
  return 1;
}

int sim_query(YfSim *s, const char *name, double *val, char *err, size_t errlen) {
  static const char *const red[] = {"ux", "uy", "vx", "vy", "x", "y", "fx", "fy", "mass", NULL};
  /* masses (so the kinetic energy) and the stable limit exist once a run has prepared the scene:
   * before, they read 0 silently ('timestep $(0.5*dt_limit)' became 0) */
  if (!s->model.prepared && (!strcmp(name, "ke") || !strcmp(name, "dt_limit") || !strncmp(name, "mass_", 5))) {
    snprintf(err, errlen, "'%s' is known once a run has prepared the scene (masses and the stable limit are computed "
             "then): put 'timestep auto' and 'run 0' before this line", name);
    return -1;
  }
  for (int i = 0; red[i]; i++) {
    size_t L = strlen(red[i]);
    if (!strncmp(name, red[i], L) && name[L] == '_' && name[L + 1]) return group_reduce(s, red[i], name + L + 1, val, err, errlen);
  }
  int energy = !strcmp(name, "ke") || !strcmp(name, "strain") || !strcmp(name, "gravity_work") ||
               !strcmp(name, "ext") || !strcmp(name, "balance");
  if (energy && s->model.prepared) run_energies_whole(s); /* (what reads a result reads a whole state) */
  if (!strcmp(name, "ke")) *val = s->energy.kinetic;
  else if (!strcmp(name, "strain")) *val = s->energy.strain;
  else if (!strcmp(name, "ext_work")) *val = s->energy.external_work;
  else if (!strcmp(name, "gravity_work")) *val = s->gravity_work;
  else if (!strcmp(name, "ext")) *val = energy_external(s);
  else if (!strcmp(name, "diss")) *val = s->energy.damping + s->energy.joint_dissipated + s->energy.friction;
  else if (!strcmp(name, "balance")) *val = energy_balance(s);
  else if (!strcmp(name, "damping")) *val = s->energy.damping;
  else if (!strcmp(name, "joint_dissipated")) *val = s->energy.joint_dissipated;
  else if (!strcmp(name, "contact_energy")) *val = s->energy.contact;
  else if (!strcmp(name, "friction")) *val = s->energy.friction;
  else if (!strcmp(name, "broken")) *val = (double)joints_broken(s);
  else if (!strcmp(name, "pairs")) *val = (double)contact_pairs(s);
  else if (!strcmp(name, "ntri")) *val = s->model.tri.n;
  else if (!strcmp(name, "nnodes")) *val = s->model.node.n;
  else if (!strcmp(name, "dt_limit")) *val = s->dt_limit;
  else if (!strcmp(name, "crack_length")) { /* broken joints' length so far [m] */
    double L = 0.0;
    for (int i = 0; s->joints && i < s->joints->nrec; i++) L += s->joints->rec[i].length;
    *val = L;
  }
  else return 0;
  return 1;
}
