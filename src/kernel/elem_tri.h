/* elem_tri.h: constant-strain triangle kernels (Munjiza / Y2D law, ALGORITHMS.md 2). */
#ifndef YF_ELEM_TRI_H
#define YF_ELEM_TRI_H
#include "model.h"

/* Per-material constants the kernel reads (gathered once per run by tri_prepare). */
typedef struct {
  double mu2;   /* 2 mu [Pa]                        */
  double lamv;  /* volfac * lambda [Pa]             */
  double k;     /* viscous coefficient [Pa s]       */
  double rho;   /* [kg/m^3]                         */
} YfTriMat;

/* Result of a force pass over a range of triangles. */
typedef struct {
  int bad;          /* first triangle (lowest index) with J <= 0 or a non-finite stress, or -1 */
  double badJ;      /* its J                                                                  */
  double visc_power;/* sum of A_c k D:D [W/m]: rate of viscous dissipation                    */
} YfTriPass;

/* Reference inverses, twice-areas and lumped masses (adds rho d0/6 to each corner node's m).
 * Returns the first triangle with non-positive initial area, or -1. */
int tri_prepare(YfModel *m, const YfTriMat *tm);
/* Stress and corner forces of triangles [e0, e1) at the current x, v: writes tri.s and tri.cf. */
void tri_forces(YfModel *m, const YfTriMat *tm, int e0, int e1, YfTriPass *out);
/* Y2D's strain energy diagnostic of triangles [e0, e1): sum A_c/2 T:E without the viscous part
 * [J/m] (the y2dref dump's "elastic", shared/y2d/README.md); a secant measure, above the law's
 * energy by 4/3 of the strain (relative) in uniaxial stretch. */
double tri_strain_energy(const YfModel *m, const YfTriMat *tm, int e0, int e1);
/* The law's own strain energy of triangles [e0, e1) [J/m]: the stress T = (2 mu / J) E +
 * lamv (J - 1/J) I, E = (F F^T - I)/2, is the derivative of the potential per reference area
 *   W = mu/2 (|F|^2 - 2) - mu ln J + lamv (J^2/2 - ln J - 1/2)
 * (a compressible neo-Hookean solid), so the work the elements' forces do is its change at any
 * strain: the energy balance uses it (energy.c).  Equal to tri_strain_energy to second order. */
double tri_strain_potential(const YfModel *m, const YfTriMat *tm, int e0, int e1);
/* Stable time step of triangle e with lumped masses: 2/omega_max of the linearised element
 * (an upper bound of the mesh's highest frequency, Irons' element-by-element theorem), reduced
 * for the viscous term.  Uses initial positions. [s] */
double tri_stable_dt(const YfModel *m, const YfTriMat *tm, int e);
/* Its two halves: the linearised element's highest angular frequency omega_max [rad/s] (-1 for a
 * degenerate triangle; it depends on rho, lambda and mu, not on the viscosity), the costly part,
 * and the stable step for that omega with material mt's viscosity [s]. */
double tri_omega_max(const YfModel *m, const YfTriMat *tm, int e);
double tri_dt_of_omega(double w, const YfTriMat *mt);
/* sqrt(1 + xi^2) - xi: the viscous reduction of the stable step at damping ratio xi (finite and
 * positive for any finite xi). */
double tri_visc_factor(double xi);

#endif
