/* material.c: a material's elastic constants mapped onto the Y2D triangle law (model.h).
 *
 * Native decks give E and nu with plane_stress or plane_strain; the law's volumetric term is
 * volfac * lambda * (J - 1/J) ~ 2 volfac lambda tr(eps), so with the book's volfac = 1/2 the
 * stored lambda is the true Lame lambda and the small-strain response is exactly Hooke's law.
 * With `volfac 1` (Y-Geo family) the stored lambda is halved so the bulk modulus stays the one
 * E and nu mean.  Materials given by lambda and mu (as Y2D decks do) keep them as given.  The
 * `material` command's words are read in deck/cmd_material.c.
 */
#include "model.h"

/* In-plane Young's modulus and Poisson's ratio of the law at small strain, of a material given by
 * lambda, mu and volfac (element damping's beta and the energy check's round-off floor read E). */
void model_lame_moduli(YfMaterial *mt) {
  const double le = 2.0 * mt->volfac * mt->lambda, mu = mt->mu;
  mt->E = 4.0 * mu * (le + mu) / (le + 2.0 * mu); /* 2D uniaxial-stress modulus */
  mt->nu = le / (le + 2.0 * mu);
}

int model_define_material(YfModel *m, const YfMaterial *given) {
  YfMaterial mt = *given;
  const double volfac = given->volfac;
  if (given->plane != YF_PLANE_LAME) {
    const double E = given->E, nu = given->nu;
    mt.mu = E / (2.0 * (1.0 + nu));
    double l = given->plane == YF_PLANE_STRESS ? E * nu / (1.0 - nu * nu) : E * nu / ((1.0 + nu) * (1.0 - 2.0 * nu));
    mt.lambda = l * 0.5 / volfac; /* 2 volfac lambda_stored = lambda_true */
  } else {
    model_lame_moduli(&mt);
  }
  int idx = model_add_material(m, given->name);
  mt.jset = m->mat[idx].jset; /* no joint property set yet */
  m->mat[idx] = mt;
  return idx;
}
