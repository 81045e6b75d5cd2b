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
  double rho = -1, E = -1, nu = -2, lam = 0, mu = -1, visc = 0, beta = 0, volfac = 0.5;
  double pn = 0, pt = -1, fr = 0;
  int pn_given = 0;
  int plane = -1, law = YF_FRIC_COULOMB;
  /* the word of each keyword given, 0 when absent: messages point at the word at fault (any
   * number is a valid lambda, so no value can stand for "not given") */
  int at_e = 0, at_nu = 0, at_lam = 0, at_mu = 0, at_visc = 0, at_beta = 0;
  static const char *const keys[] = {"rho", "E", "nu", "plane_stress", "plane_strain", "lambda", "mu",
                                     "visc", "damping", "volfac", "pen_n", "pen_t", "friction",
                                     "friction_law", NULL};
  for (int i = 2; i < a->n;) {
    int k = arg_choice(a, i, "keyword", keys);
    if (k == 3 || k == 4) { plane = k == 3 ? YF_PLANE_STRESS : YF_PLANE_STRAIN; i++; continue; }
    if (i + 1 >= a->n) arg_error(a, i, "keyword needs a value");
    switch (k) {
    case 0: rho = arg_pos(a, i + 1, "rho"); break;
    case 1: E = arg_pos(a, i + 1, "E"); at_e = at_e ? at_e : i; break;
    case 2:
      nu = arg_num(a, i + 1, "nu");
      if (!(nu > -1.0 && nu < 0.5)) arg_error(a, i + 1, "Poisson's ratio must lie in (-1, 0.5)");
      at_nu = at_nu ? at_nu : i;
      break;
    case 5: lam = arg_num(a, i + 1, "lambda"); at_lam = at_lam ? at_lam : i; break;
    case 6: mu = arg_pos(a, i + 1, "mu"); at_mu = at_mu ? at_mu : i; break;
    case 7: visc = arg_nonneg(a, i + 1, "visc"); at_visc = at_visc ? at_visc : i; break;
    case 8: beta = arg_nonneg(a, i + 1, "damping"); at_beta = at_beta ? at_beta : i; break;
    case 9:
      volfac = arg_pos(a, i + 1, "volfac");
      if (volfac != 0.5 && volfac != 1.0) arg_error(a, i + 1, "volfac must be 0.5 (book Y2D) or 1 (Y-Geo)");
      break;
    case 10: pn = arg_nonneg(a, i + 1, "pen_n"), pn_given = 1; break;
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
  /* the first word of each way of giving the constants */
  int at_en = at_e && (!at_nu || at_e < at_nu) ? at_e : at_nu;
  int at_lm = at_lam && (!at_mu || at_lam < at_mu) ? at_lam : at_mu;
  int given_e = at_en > 0;
  if (at_en && at_lm) /* the later of the two: the first word that contradicts the other way */
    arg_error(a, at_en > at_lm ? at_en : at_lm, "give either E, nu or lambda, mu, not both");
  if (!at_en && !at_lm) arg_error(a, 0, "missing elastic constants: 'E E nu NU plane_stress|plane_strain' or 'lambda L mu M'");
  if (visc > 0 && beta > 0)
    arg_error(a, at_visc > at_beta ? at_visc : at_beta, "give either visc or damping, not both");
  if (given_e) {
    if (!at_e) arg_error(a, at_nu, "missing 'E' (Young's modulus, Pa) beside nu");
    if (!at_nu) arg_error(a, at_e, "missing 'nu' (Poisson's ratio) beside E");
    if (plane < 0) arg_error(a, 0, "say plane_stress or plane_strain");
  } else {
    if (!at_mu) arg_error(a, at_lam, "missing 'mu' (Lame's shear modulus, Pa) beside lambda");
    if (!at_lam) arg_error(a, at_mu, "missing 'lambda' (Lame's first constant, Pa) beside mu");
    /* the law's in-plane bulk modulus is 2 volfac lambda + mu (material.c): at or below 0 a
     * triangle has no stiffness against a change of area, or a negative one.  Above it every pair
     * is the 2D law of some E > 0 and nu in (-1, 0.5), plane_stress (lambda in (-mu, 2 mu)) or
     * plane_strain (lambda > -2/3 mu), the range 'E E nu NU' accepts. */
    double lmin = -mu / (2.0 * volfac);
    if (!(lam > lmin))
      arg_error(a, at_lam + 1, "lambda must be above %s = %g: the in-plane bulk modulus %s must be positive "
                "(every E > 0 with nu in (-1, 0.5) gives such a pair)", volfac == 1.0 ? "-mu/2 with volfac 1" : "-mu", lmin,
                volfac == 1.0 ? "2 lambda + mu" : "lambda + mu");
  }
  /* the Coulomb law's tangential spring is the normal one with pen_t: above pen_n it would
   * outrun the contact's stable time step (contact_stable_dt is the normal penalty's) */
  if (law == YF_FRIC_COULOMB && pt >= 0 && pt > pn)
    arg_error(a, 0, "pen_t %g is above pen_n %g: with the coulomb friction law the tangential stiffness is pen_t / pen_n "
              "of the normal one and must not exceed it (give pen_t <= pen_n, or friction_law y2d)", pt, pn);
  YfMaterial m = {.rho = rho, .volfac = volfac, .visc = visc, .beta = beta, .pen_n = pn, .pen_n_given = pn_given,
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
