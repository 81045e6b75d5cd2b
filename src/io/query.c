/* query.c: what a deck expression can ask the simulation (see query.h).
 *
 * Thermo keywords: ke, strain, ext_work (loads and supports), gravity_work, ext (the two: the thermo
 * line's ExtWork), damping, joint_dissipated, friction, diss (the three), contact_energy, balance
 * (the energy check's residual, energy.c), broken, pairs, ntri, nnodes, dt_limit.  Group reductions, NAME_GROUP with GROUP a group or
 * body name: ux_G, uy_G (mean displacement [m]), vx_G, vy_G (mean velocity [m/s]), x_G, y_G
 * (mean position [m]), fx_G, fy_G (sum of nodal forces with gravity's m g [N/m]: on held nodes
 * at rest, minus the supports' reaction), mass_G [kg/m].  Means are plain
 * averages over the group's nodes (copies of a node in a fracturing body count separately).
 */
#include <math.h>
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
    /* a Gmsh physical group named 'bottom-face' is a group the deck can fix and load, but in an
     * expression 'fy_bottom-face' reads as fy_bottom minus face: say so and give the alias */
    size_t L = strlen(g);
    for (int q = 0; q < m->ngroup; q++) {
      const char *nm = m->group[q].name;
      char c = nm[L];
      if (strncmp(nm, g, L) || !c || (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
          c == '_')
        continue;
      char alias[YF_NAME_MAX];
      size_t j = 0;
      for (; nm[j] && j + 1 < sizeof alias; j++) {
        char a = nm[j];
        alias[j] = (a >= 'a' && a <= 'z') || (a >= 'A' && a <= 'Z') || (a >= '0' && a <= '9') ? a : '_';
      }
      alias[j] = 0;
      snprintf(err, n, "'%s_%s': no group or body named '%s'; the group '%s' has a character an expression name "
               "cannot hold: give it another name first ('group %s union \"%s\"') and write %s_%s", what, g, g, nm,
               alias, nm, what, alias);
      return -1;
    }
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
    /* gravity is the body force of the update, not in f: added, so that a support's sum is its
     * reaction (LAMMPS's fix gravity adds to f too); a hanging block's top nodes read 359.7 of
     * its 392.4 N/m weight */
    else if (!strcmp(what, "fx")) sum += nd->fx[i] + nd->m[i] * s->gx;
    else if (!strcmp(what, "fy")) sum += nd->fy[i] + nd->m[i] * s->gy;
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

/* The keywords sim_query answers besides the group reductions, in the order of its switch. */
enum { Q_KE, Q_STRAIN, Q_EXT_WORK, Q_GRAVITY_WORK, Q_EXT, Q_DISS, Q_BALANCE, Q_DAMPING, Q_JOINT_DISSIPATED,
       Q_CONTACT_ENERGY, Q_FRICTION, Q_BROKEN, Q_PAIRS, Q_NTRI, Q_NNODES, Q_DT_LIMIT, Q_CRACK_LENGTH };
static const char *const keywords[] = {"ke", "strain", "ext_work", "gravity_work", "ext", "diss", "balance",
                                       "damping", "joint_dissipated", "contact_energy", "friction", "broken",
                                       "pairs", "ntri", "nnodes", "dt_limit", "crack_length", NULL};
static const char *const red[] = {"ux", "uy", "vx", "vy", "x", "y", "fx", "fy", "mass", NULL};

const char *const *sim_query_keywords(void) { return keywords; }

static int keyword(const char *name) {
  for (int i = 0; keywords[i]; i++)
    if (!strcmp(name, keywords[i])) return i;
  return -1;
}

/* the reduction of NAME_GROUP (its index in red), or -1 */
static int reduction(const char *name) {
  for (int i = 0; red[i]; i++) {
    size_t L = strlen(red[i]);
    if (!strncmp(name, red[i], L) && name[L] == '_' && name[L + 1]) return i;
  }
  return -1;
}

int sim_query_known(YfSim *s, const char *name) {
  if (keyword(name) >= 0) return 1;
  int r = reduction(name);
  /* x_c is a reduction only when a group or body c exists (a centre's x_c is a common name) */
  return r >= 0 && model_group(&s->model, name + strlen(red[r]) + 1, 0) >= 0 ? 2 : 0;
}

/* A quantity of the state that is not finite: the state overflowed, the run's numerical failure
 * (exit 3, its step), not the deck's (a record of 'strain' every step reads the overflow before
 * the step's own checks and was a deck error at the record's line).  A node beyond the range is
 * named first, as a thermo line does. */
static int nonfinite(YfSim *s, const char *name) {
  run_check_nodes(s, 0, s->model.node.n);
  const char *what = !strcmp(name, "strain") ? " (the strain energy)" : !strcmp(name, "ke") ? " (the kinetic energy)" : "";
  yf_numeric_error(s->step, "'%s'%s is not finite: the state overflows the range of a double (the masses, moduli or "
                   "velocities are too large for the arithmetic)", name, what);
}

static int query(YfSim *s, const char *name, double *val, char *err, size_t errlen);

int sim_query(YfSim *s, const char *name, double *val, char *err, size_t errlen) {
  int r = query(s, name, val, err, errlen);
  if (r == 1 && !isfinite(*val) && s->model.prepared) return nonfinite(s, name);
  return r;
}

static int query(YfSim *s, const char *name, double *val, char *err, size_t errlen) {
  /* masses (so the kinetic energy) and the stable limit exist once a run has prepared the scene:
   * before, they read 0 silently ('timestep $(0.5*dt_limit)' became 0) */
  if (!s->model.prepared && (!strcmp(name, "ke") || !strcmp(name, "dt_limit") || !strncmp(name, "mass_", 5))) {
    snprintf(err, errlen, "'%s' is known once a run has prepared the scene (masses and the stable limit are computed "
             "then): put 'timestep auto' and 'run 0' before this line", name);
    return -1;
  }
  int r = reduction(name);
  if (r >= 0) return group_reduce(s, red[r], name + strlen(red[r]) + 1, val, err, errlen);
  int k = keyword(name);
  if (k < 0) return 0;
  if ((k == Q_KE || k == Q_STRAIN || k == Q_GRAVITY_WORK || k == Q_EXT || k == Q_BALANCE) && s->model.prepared)
    run_energies_whole(s); /* (what reads a result reads a whole state) */
  switch (k) {
  case Q_KE: *val = s->energy.kinetic; break;
  case Q_STRAIN: *val = s->energy.strain; break;
  case Q_EXT_WORK: *val = s->energy.external_work; break;
  case Q_GRAVITY_WORK: *val = s->gravity_work; break;
  case Q_EXT: *val = energy_external(s); break;
  case Q_DISS: *val = s->energy.damping + s->energy.joint_dissipated + s->energy.friction; break;
  case Q_BALANCE: *val = energy_balance(s); break;
  case Q_DAMPING: *val = s->energy.damping; break;
  case Q_JOINT_DISSIPATED: *val = s->energy.joint_dissipated; break;
  case Q_CONTACT_ENERGY: *val = s->energy.contact; break;
  case Q_FRICTION: *val = s->energy.friction; break;
  case Q_BROKEN: *val = (double)joints_broken(s); break;
  case Q_PAIRS: *val = (double)contact_pairs(s); break;
  case Q_NTRI: *val = s->model.tri.n; break;
  case Q_NNODES: *val = s->model.node.n; break;
  case Q_DT_LIMIT: *val = s->dt_limit; break;
  default: { /* Q_CRACK_LENGTH: broken joints' length so far [m] */
    double L = 0.0;
    for (int i = 0; s->joints && i < s->joints->nrec; i++) L += s->joints->rec[i].length;
    *val = L;
  }
  }
  return 1;
}
