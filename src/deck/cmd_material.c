/* cmd_material.c: the `material` deck command (a row of commands.def): reads its words into a
 * YfMaterial and adds it to the model (model_define_material, model/material.c, which maps E and
 * nu onto the Y2D triangle law).
 */
#include <math.h>
#include <stdio.h>
#include <string.h>
#include "deck.h"
#include "sim.h"

/* material NAME elastic rho R (E E nu NU [plane_stress|plane_strain] | lambda L mu M)
 *          [visc K | damping BETA] [volfac 0.5|1] [pen_n P] [pen_t P] [friction MU]
 *          [friction_law coulomb|y2d]
 * friction_law: coulomb (default) is the elastic-slip Coulomb law whose tangential stiffness is
 * the normal law's with pen_t for pen_n; y2d is Y2D's law (p_t L^2 times the slip, unit-dependent),
 * for comparison with Y2D runs (contact_pair.h). */
void cmd_material(YfSim *s, const YfArgs *a) {
  arg_count(a, 4, -1);
  const char *name = arg_name(a, 0, "name");
  static const char *const styles[] = {"elastic", NULL};
  arg_choice(a, 1, "material style", styles);
  int idx = model_find_material(&s->model, name);
  if (idx >= 0) arg_error(a, 0, "material already defined (each name once)");
  double rho = -1, E = -1, nu = -2, lam = -1, mu = -1, visc = 0, beta = 0, volfac = 0.5;
  double pn = 0, pt = -1, fr = 0;
  int plane = -1, given_lame = 0, given_e = 0, law = YF_FRIC_COULOMB;
  static const char *const keys[] = {"rho", "E", "nu", "plane_stress", "plane_strain", "lambda", "mu",
                                     "visc", "damping", "volfac", "pen_n", "pen_t", "friction",
                                     "friction_law", NULL};
  for (int i = 2; i < a->n;) {
    int k = arg_choice(a, i, "keyword", keys);
    if (k == 3 || k == 4) { plane = k == 3 ? YF_PLANE_STRESS : YF_PLANE_STRAIN; i++; continue; }
    if (i + 1 >= a->n) arg_error(a, i, "keyword needs a value");
    switch (k) {
    case 0: rho = arg_pos(a, i + 1, "rho"); break;
    case 1: E = arg_pos(a, i + 1, "E"); given_e = 1; break;
    case 2:
      nu = arg_num(a, i + 1, "nu");
      if (!(nu > -1.0 && nu < 0.5)) arg_error(a, i + 1, "Poisson's ratio must lie in (-1, 0.5)");
      given_e = 1;
      break;
    case 5: lam = arg_num(a, i + 1, "lambda"); given_lame = 1; break;
    case 6: mu = arg_pos(a, i + 1, "mu"); given_lame = 1; break;
    case 7: visc = arg_nonneg(a, i + 1, "visc"); break;
    case 8: beta = arg_nonneg(a, i + 1, "damping"); break;
    case 9:
      volfac = arg_pos(a, i + 1, "volfac");
      if (volfac != 0.5 && volfac != 1.0) arg_error(a, i + 1, "volfac must be 0.5 (book Y2D) or 1 (Y-Geo)");
      break;
    case 10: pn = arg_nonneg(a, i + 1, "pen_n"); break;
    case 11: pt = arg_nonneg(a, i + 1, "pen_t"); break;
    case 12: fr = arg_nonneg(a, i + 1, "friction"); break;
    case 13: {
      static const char *const laws[] = {"y2d", "coulomb", NULL}; /* index = YF_FRIC_* */
      law = arg_choice(a, i + 1, "friction law", laws);
      break;
    }
    }
    i += 2;
  }
  if (rho < 0) arg_error(a, 0, "missing 'rho R' (density, kg/m^3)");
  if (given_e && given_lame) arg_error(a, 2, "give either E, nu or lambda, mu, not both");
  if (!given_e && !given_lame) arg_error(a, 0, "missing elastic constants: 'E E nu NU plane_stress|plane_strain' or 'lambda L mu M'");
  if (visc > 0 && beta > 0) arg_error(a, 2, "give either visc or damping, not both");
  if (given_e) {
    if (E < 0) arg_error(a, 0, "missing 'E' (Young's modulus, Pa)");
    if (nu < -1) arg_error(a, 0, "missing 'nu' (Poisson's ratio)");
    if (plane < 0) arg_error(a, 0, "say plane_stress or plane_strain");
  } else if (lam < 0 || mu < 0) {
    arg_error(a, 0, "give both lambda and mu");
  }
  /* the Coulomb law's tangential spring is the normal one with pen_t: above pen_n it would
   * outrun the contact's stable time step (contact_stable_dt is the normal penalty's) */
  if (law == YF_FRIC_COULOMB && pt >= 0 && pt > pn)
    arg_error(a, 0, "pen_t %g is above pen_n %g: with the coulomb friction law the tangential stiffness is pen_t / pen_n "
              "of the normal one and must not exceed it (give pen_t <= pen_n, or friction_law y2d)", pt, pn);
  YfMaterial m = {.rho = rho, .volfac = volfac, .visc = visc, .beta = beta, .pen_n = pn,
                  .pen_t = pt < 0 ? pn : pt, .fric = fr, .fric_law = law};
  snprintf(m.name, sizeof m.name, "%s", name);
  if (given_e) {
    m.E = E;
    m.nu = nu;
    m.plane = plane;
  } else {
    m.plane = YF_PLANE_LAME;
    m.lambda = lam;
    m.mu = mu;
  }
  model_define_material(&s->model, &m);
}
