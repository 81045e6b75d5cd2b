/* check_physics.c: the elastic triangle, the time integration and the supports and loads,
 * checked against exact laws and textbook solutions (tolerances derived in each test). */
#include <check.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "bc.h"
#include "elem_tri.h"
#include "run.h"
#include "yftest.h"

static void quiet(void) { freopen("/dev/null", "w", stdout); }

#define MAT "material m elastic rho 1000 E 1e9 nu 0.25 plane_stress\n"

/* Deform every node by x = F X + c and evaluate the triangle forces. */
static void deform(YfSim *s, const double F[4], double cx, double cy) {
  YfNodes *n = &s->model.node;
  for (int i = 0; i < n->n; i++) {
    n->x[i] = F[0] * n->x0[i] + F[1] * n->y0[i] + cx;
    n->y[i] = F[2] * n->x0[i] + F[3] * n->y0[i] + cy;
  }
  YfTriPass p;
  tri_forces(&s->model, run_tri_mats(), 0, s->model.tri.n, &p);
  ck_assert_int_eq(p.bad, -1);
}

/* tri_forces runs four triangles per vector: each triangle must get exactly the bits of the
 * scalar code (the range's tail, or a range of one), with viscous (k > 0) and inviscid (k = 0)
 * materials mixed inside one vector and a distorted, moving mesh (so every term is non-trivial). */
START_TEST(test_tri_four_lanes_match_scalar) {
  quiet();
  YfSim *s = yft_run("material m elastic rho 1000 E 1e9 nu 0.25 plane_stress\n"
                     "material v elastic rho 2000 E 3e9 nu 0.3 plane_strain visc 1e3\n"
                     "mesh rect a m 0 0 1 0.5 5 3 pattern cross\nmesh rect b v 1 0 2 0.5 3 3 pattern alt\n"
                     "timestep auto\n");
  run_prepare(s);
  YfModel *m = &s->model;
  YfNodes *n = &m->node;
  const int nt = m->tri.n;
  /* mix the materials triangle by triangle so the lanes of one vector differ */
  for (int e = 0; e < nt; e++) m->tri.mat[e] = (e * 7 / 3) % 2;
  unsigned long r = 12345;
  for (int i = 0; i < n->n; i++) {
    double q[4];
    for (int c = 0; c < 4; c++) {
      r = r * 6364136223846793005UL + 1442695040888963407UL;
      q[c] = (double)(r >> 11) / 9007199254740992.0 - 0.5;
    }
    n->x[i] = n->x0[i] + 0.01 * q[0];
    n->y[i] = n->y0[i] + 0.01 * q[1];
    n->vx[i] = 3.0 * q[2];
    n->vy[i] = -2.0 * q[3];
  }
  const YfTriMat *tm = run_tri_mats();
  YfTriPass all, one;
  tri_forces(m, tm, 0, nt, &all);
  ck_assert_int_ge(nt, 8);
  double *s_all = malloc(3 * nt * sizeof(double)), *cf_all = malloc(6 * nt * sizeof(double));
  memcpy(s_all, m->tri.s, 3 * nt * sizeof(double));
  memcpy(cf_all, m->tri.cf, 6 * nt * sizeof(double));
  double power = 0.0;
  for (int e = 0; e < nt; e++) {
    memset(m->tri.s + 3 * e, 0xff, 3 * sizeof(double));
    memset(m->tri.cf + 6 * e, 0xff, 6 * sizeof(double));
    tri_forces(m, tm, e, e + 1, &one);
    ck_assert_int_eq(one.bad, -1);
    power += one.visc_power;
    ck_assert_msg(!memcmp(s_all + 3 * e, m->tri.s + 3 * e, 3 * sizeof(double)), "stress of triangle %d differs", e);
    ck_assert_msg(!memcmp(cf_all + 6 * e, m->tri.cf + 6 * e, 6 * sizeof(double)), "corner forces of triangle %d differ", e);
  }
  ck_assert_int_eq(all.bad, -1);
  ck_assert_msg(power > 0.0 && !memcmp(&power, &all.visc_power, sizeof power), "viscous power differs");
  /* an inverted triangle inside a vector is reported by its index, as the scalar loop does */
  int e = 4 * (nt / 8) + 1, *v = m->tri.v + 3 * e;
  double tx = n->x[v[1]], ty = n->y[v[1]];
  n->x[v[1]] = n->x[v[2]];
  n->y[v[1]] = n->y[v[2]];
  n->x[v[2]] = tx;
  n->y[v[2]] = ty;
  tri_forces(m, tm, 0, nt, &all);
  ck_assert_int_le(all.bad, e);
  ck_assert_int_ge(all.bad, 0);
  free(s_all);
  free(cf_all);
}
END_TEST

/* Patch test: a uniform deformation gives the same stress in every triangle, equal to the law
 * evaluated with that F, and zero net force on every interior node (to round-off). */
START_TEST(test_patch_uniform_strain) {
  quiet();
  YfSim *s = yft_run(MAT "mesh rect b m 0 0 1 0.5 6 3 pattern cross\ntimestep auto\n");
  run_prepare(s);
  const double F[4] = {1 + 1e-4, 2e-5, 3e-5, 1 - 5e-5};
  deform(s, F, 0.3, -0.2);
  double J = F[0] * F[3] - F[1] * F[2];
  double E11 = 0.5 * (F[0] * F[0] + F[1] * F[1] - 1), E22 = 0.5 * (F[2] * F[2] + F[3] * F[3] - 1);
  double E12 = 0.5 * (F[0] * F[2] + F[1] * F[3]);
  double mu = 1e9 / 2.5, lam = 1e9 * 0.25 / (1 - 0.0625);
  double T[3] = {2 * mu / J * E11 + 0.5 * lam * (J - 1 / J), 2 * mu / J * E22 + 0.5 * lam * (J - 1 / J), 2 * mu / J * E12};
  double scale = fabs(T[0]) + fabs(T[1]) + fabs(T[2]);
  for (int e = 0; e < s->model.tri.n; e++)
    for (int k = 0; k < 3; k++) ck_assert_double_eq_tol(s->model.tri.s[3 * e + k], T[k], 1e-9 * scale);
  /* interior nodes: sum of corner forces vanishes (uniform stress is in equilibrium) */
  int nn = s->model.node.n;
  double *fx = calloc(nn, sizeof(double)), *fy = calloc(nn, sizeof(double));
  for (int e = 0; e < s->model.tri.n; e++)
    for (int c = 0; c < 3; c++) {
      fx[s->model.tri.v[3 * e + c]] += s->model.tri.cf[6 * e + 2 * c];
      fy[s->model.tri.v[3 * e + c]] += s->model.tri.cf[6 * e + 2 * c + 1];
    }
  double fscale = scale * 0.5 / 6; /* stress x edge length */
  for (int i = 0; i < nn; i++) {
    double X = s->model.node.x0[i], Y = s->model.node.y0[i];
    if (X > 1e-9 && X < 1 - 1e-9 && Y > 1e-9 && Y < 0.5 - 1e-9) {
      ck_assert_double_le(fabs(fx[i]), 1e-9 * fscale);
      ck_assert_double_le(fabs(fy[i]), 1e-9 * fscale);
    }
  }
  free(fx);
  free(fy);
}
END_TEST

/* Small strain: the law is Hooke's law with the material's E, nu.  Uniaxial stress in plane
 * stress: eps_xx = s/E, eps_yy = -nu s/E gives sxx = s and syy = 0 up to O(eps) = 1e-6. */
START_TEST(test_uniaxial_stress_matches_E) {
  quiet();
  YfSim *s = yft_run(MAT "mesh rect b m 0 0 1 0.2 5 2 pattern alt\n");
  run_prepare(s);
  double eps = 1e-6, F[4] = {1 + eps, 0, 0, 1 - 0.25 * eps};
  deform(s, F, 0, 0);
  for (int e = 0; e < s->model.tri.n; e++) {
    ck_assert_double_eq_tol(s->model.tri.s[3 * e], 1e9 * eps, 1e9 * eps * 1e-5);
    ck_assert_double_le(fabs(s->model.tri.s[3 * e + 1]), 1e9 * eps * 1e-5);
  }
}
END_TEST

/* Plane strain: eps_yy = -nu/(1-nu) eps_xx gives syy = 0 and sxx = E/(1-nu^2) eps_xx. */
START_TEST(test_uniaxial_plane_strain) {
  quiet();
  YfSim *s = yft_run("material m elastic rho 1000 E 1e9 nu 0.3 plane_strain\nmesh rect b m 0 0 1 0.2 5 2\n");
  run_prepare(s);
  double eps = 1e-6, nu = 0.3, F[4] = {1 + eps, 0, 0, 1 - nu / (1 - nu) * eps};
  deform(s, F, 0, 0);
  double expect = 1e9 / (1 - nu * nu) * eps;
  for (int e = 0; e < s->model.tri.n; e++) {
    ck_assert_double_eq_tol(s->model.tri.s[3 * e], expect, expect * 1e-5);
    ck_assert_double_le(fabs(s->model.tri.s[3 * e + 1]), expect * 1e-5);
  }
}
END_TEST

/* Rigid motion (translation and a 60 degree rotation) gives no stress and no force: B = R R^T = I
 * to round-off, so |T| <= ~10 eps_machine E. */
START_TEST(test_rigid_rotation_zero_force) {
  quiet();
  YfSim *s = yft_run(MAT "mesh rect b m 0 0 1 0.5 4 2 pattern cross\n");
  run_prepare(s);
  double a = M_PI / 3, F[4] = {cos(a), -sin(a), sin(a), cos(a)};
  deform(s, F, 12.5, -3.0);
  for (int e = 0; e < s->model.tri.n; e++)
    for (int k = 0; k < 3; k++) ck_assert_double_le(fabs(s->model.tri.s[3 * e + k]), 1e9 * 1e-13);
  for (int k = 0; k < 6 * s->model.tri.n; k++) ck_assert_double_le(fabs(s->model.tri.cf[k]), 1e9 * 1e-13);
}
END_TEST

/* 1D wave: with nu = 0 the strip is a 1D bar, c = sqrt(E/rho) = 1000 m/s.  The left end is
 * driven at 1 m/s from t = 0; the half-amplitude point of the front reaches x = 0.5 m at
 * t = 0.5 ms.  Resolution: h = 2.5 mm (200 cells over the half length), dt = 0.5 limit. */
START_TEST(test_wave_arrival_time) {
  quiet();
  YfSim *s = yft_run("material m elastic rho 1000 E 1e9 nu 0 plane_stress\n"
                     "mesh rect bar m 0 0 1 0.01 400 4 pattern right\n"
                     "region left box -1 -1 1e-6 1\ngroup left node region left\n"
                     "fix push left velocity 1 NULL\ntimestep auto safety 0.5\nrun 0\n");
  double arrival = yft_front_arrival(s, yft_node_at(s, 0.5, 0.0), 0, 1e-3);
  ck_assert_double_gt(arrival, 0);
  ck_assert_double_eq_tol(arrival, 0.5e-3, 0.01 * 0.5e-3);
}
END_TEST

/* Free vibration without damping: kinetic + strain energy stays within 0.5 % of its initial
 * value over 10 000 steps (leapfrog is symplectic: the energy error oscillates, no drift). */
START_TEST(test_energy_conserved_free_vibration) {
  quiet();
  YfSim *s = yft_run(MAT "mesh rect beam m 0 0 0.5 0.05 20 2 pattern cross\n"
                     "region root box -1 -1 1e-6 1\ngroup root node region root\nfix clamp root fixed xy\n"
                     "velocity beam set 0 0\ntimestep auto safety 0.5\nrun 0\n");
  YfNodes *n = &s->model.node;
  for (int i = 0; i < n->n; i++) n->vy[i] = 0.5 * (n->x0[i] / 0.5) * (n->x0[i] / 0.5); /* m/s */
  run_energies(s);
  double e0 = s->energy.kinetic + s->energy.strain, emax = 0;
  for (int k = 0; k < 100; k++) {
    run_steps(s, 100);
    double e = s->energy.kinetic + s->energy.strain;
    double err = fabs(e - e0) / e0;
    if (err > emax) emax = err;
  }
  ck_assert_double_lt(emax, 0.005);
}
END_TEST

/* Cantilever (L = 1, h = 0.1, plane stress) with an end shear load P = 1000 N/m, damped to rest:
 * Timoshenko tip deflection P L^3 / (3 E I) + P L / (k G A), k = 5/6, within 2 %.  The crossed
 * mesh of 100 x 10 cells gives 0.9 % below (constant-strain triangles are slightly stiff in
 * bending; 60 x 6 cells give 2.2 %). */
START_TEST(test_cantilever_static_deflection) {
  quiet();
  YfSim *s = yft_run(MAT "mesh rect beam m 0 0 1 0.1 100 10 pattern cross\n"
                     "region root box -1 -1 1e-6 1\ngroup root node region root\nfix clamp root fixed xy\n"
                     "region tipr box 0.999999 -1 2 1\ngroup tip node region tipr\n"
                     "history rise ramp 0 0.01\nload P tip traction 0 -10000 history rise\n" /* 10 kPa x 0.1 m = 1000 N/m */
                     "damping mass 180\ntimestep auto safety 0.9\nrun 0\n");
  double E = 1e9, G = E / 2.5, I = 1e-3 / 12.0, A = 0.1, P = 1000;
  double expect = P / (3 * E * I) + P / (5.0 / 6.0 * G * A);
  double t_end = 0.08; /* ramp 0.01 s, then ~7/omega_1 of near-critical damping: residual < 0.1 % */
  run_steps(s, (long)(t_end / s->dt));
  double uy = 0;
  int cnt = 0;
  for (int i = 0; i < s->model.node.n; i++)
    if (s->model.node.x0[i] > 0.999999) { uy += s->model.node.y[i] - s->model.node.y0[i]; cnt++; }
  uy /= cnt;
  ck_assert_double_eq_tol(-uy, expect, 0.02 * expect);
}
END_TEST

/* A fixed node never moves, bit for bit, whatever the loads. */
START_TEST(test_fixed_nodes_never_move) {
  quiet();
  YfSim *s = yft_run(MAT "mesh rect b m 0 0 1 0.2 10 2\nregion l box -1 -1 1e-6 1\ngroup l node region l\n"
                     "fix hold l fixed xy\nload push b traction 3e5 -1e5\ngravity 0 -9.81\ntimestep auto\nrun 300\n");
  for (int i = 0; i < s->model.node.n; i++)
    if (s->model.node.x0[i] < 1e-6) {
      ck_assert(s->model.node.x[i] == s->model.node.x0[i]);
      ck_assert(s->model.node.y[i] == s->model.node.y0[i]);
    }
}
END_TEST

/* A prescribed displacement with a ramp history is met exactly at every step's end time. */
START_TEST(test_prescribed_displacement_exact) {
  quiet();
  YfSim *s = yft_run(MAT "mesh rect b m 0 0 1 0.2 10 2\nregion r box 0.999999 -1 2 1\ngroup r node region r\n"
                     "history ramp1 ramp 0 1e-4\nfix pull r displacement 1e-3 NULL history ramp1\n"
                     "timestep auto\nrun 57\n");
  double phi = s->time >= 1e-4 ? 1.0 : s->time / 1e-4;
  for (int i = 0; i < s->model.node.n; i++)
    if (s->model.node.x0[i] > 0.999999)
      ck_assert_double_eq_tol(s->model.node.x[i] - s->model.node.x0[i], 1e-3 * phi, 1e-15);
}
END_TEST

/* A pressure's resultant equals p times the loaded length, pointing into the body; a traction's
 * equals t times the length.  Exact up to round-off. */
START_TEST(test_pressure_resultant) {
  quiet();
  YfSim *s = yft_run(MAT "mesh rect b m 0 0 2 0.2 7 2 pattern cross\nregion top box -1 0.199999 3 1\n"
                     "group top node region top\nload p top pressure 1e5\nregion rs box 1.999999 -1 3 1\n"
                     "group rs node region rs\nload t rs traction 200 0\n");
  run_prepare(s);
  YfNodes *n = &s->model.node;
  for (int i = 0; i < n->n; i++) n->fx[i] = n->fy[i] = 0;
  bc_apply_loads(s);
  double sx = 0, sy = 0;
  for (int i = 0; i < n->n; i++) { sx += n->fx[i]; sy += n->fy[i]; }
  ck_assert_double_eq_tol(sy, -1e5 * 2.0, 1e-9 * 2e5);
  ck_assert_double_eq_tol(sx, 200 * 0.2, 1e-9 * 40);
}
END_TEST

/* A distributed load acts on every boundary edge with both ends in its group: a group made from a
 * band region across a block's top (two cells deep) holds the top face and the upper segments of
 * both sides, and a traction 1e5 Pa "on the top" of a 1 m block took 1.2e5 N/m, silently (the
 * support's reaction is 1.2e5).  The run says what each distributed load covers, once, when it
 * first acts: its edges, their length and its resultant at full amplitude, and the reaction it
 * leads to is that resultant. */
START_TEST(test_distributed_load_reported) {
  const char *deck = "material m elastic rho 2500 E 3e10 nu 0.2 plane_stress\nmesh rect b m 0 0 1 1 10 10\n"
                     "region band box -1 0.85 2 2\ngroup top node region band\n"
                     "region bot box -1 -1 2 1e-9\ngroup bot node region bot\nfix h bot fixed xy\n"
                     "history r ramp 0 0.005\nload t top traction 1e5 0 history r\nload p top pressure 2e5\n"
                     "unload p\ndamping mass 3000\ntimestep auto safety 0.9\nrun 0\nrun 3000\nrun 10\n"
                     "print \"R $(fx_bot)\"\n";
  char *err = NULL, *dir = NULL;
  int code = yft_run_binary("a.deck", deck, "-log log.txt", &err, &dir);
  ck_assert_msg(code == 0, "exit %d: %s", code, err);
  char path[512];
  snprintf(path, sizeof path, "%s/log.txt", dir);
  char *log = yft_slurp(path, 0);
  ck_assert_ptr_nonnull(log);
  /* 10 top edges + 1 at the top of each side: 12 edges, 1.2 m, 1.2e5 N/m; said once in three runs */
  const char *line = "load t: 12 boundary edges of group top, 1.2 m long; resultant (120000, 0) N/m at full amplitude\n";
  const char *at = strstr(log, line);
  ck_assert_msg(at && !strstr(at + 1, "load t:"), "%s", log);
  ck_assert_msg(!strstr(log, "load p:"), "an unloaded load reported: %s", log);
  const char *r = strstr(log, "\nR ");
  double R = 0;
  ck_assert_msg(r && sscanf(r, "\nR %lf", &R) == 1, "%s", log);
  ck_assert_double_eq_tol(R, 1.2e5, 1e-6 * 1.2e5);
  free(log);
  free(err);
  free(dir);
}
END_TEST

/* Gravity on a free body: after n steps v = g n dt exactly (uniform acceleration, no stress). */
START_TEST(test_gravity_free_fall) {
  quiet();
  YfSim *s = yft_run(MAT "mesh rect b m 0 0 1 0.2 4 2\ngravity 0 -9.81\ntimestep auto\nrun 100\n");
  for (int i = 0; i < s->model.node.n; i++) ck_assert_double_eq_tol(s->model.node.vy[i], -9.81 * s->time, 1e-9);
}
END_TEST

/* A free square (0.1 m, 4 x 4 crossed cells) spun at omega = 100 rad/s at safety 0.99 of the
 * stable limit for 1e5 steps (17.7 turns).  A rigid rotation stresses nothing (the law is
 * frame-indifferent); the body feels the centrifugal load, sigma = rho omega^2 a^2 = 2.5e4 Pa
 * (a = 0.05 m), a strain of 2.5e-5, and, started unstressed, breathes between 0 and twice that.
 * Bounds: the angular momentum about the centre is kept exactly by central differences under a
 * frame-indifferent force, so only round-off accumulates, at most 1e5 steps x 2.2e-16: 1e-10;
 * the energy error is (omega dt)^2 = 1.2e-6 for the rotation plus the breathing's energy (up to
 * four times the static sigma^2 / 2E x area: 1.4e-4 of the total) misread by (omega_b dt)^2 / 4,
 * omega_b dt about 0.35 for the 4-cell body's breathing: 4.4e-6 (measured 4.4e-6): bound 1e-5;
 * the radius of gyration within the breathing, twice the static strain: 5e-5 (measured 1.6e-5);
 * the centre of mass still (the forces sum to zero): 1e-12 m. */
START_TEST(test_spinning_body_keeps_energy_and_shape) {
  quiet();
  YfSim *s = yft_run(MAT "mesh rect b m -0.05 -0.05 0.05 0.05 4 4 pattern cross\nvelocity b set 0 0\n"
                         "timestep auto safety 0.99\nrun 0\n");
  YfNodes *n = &s->model.node;
  const double w = 100; /* rad/s */
  for (int i = 0; i < n->n; i++) {
    n->vx[i] = -w * n->y0[i];
    n->vy[i] = w * n->x0[i];
  }
  run_energies(s);
  double e0 = s->energy.kinetic + s->energy.strain, L0 = 0, r0 = 0;
  for (int i = 0; i < n->n; i++) {
    L0 += n->m[i] * (n->x[i] * n->vy[i] - n->y[i] * n->vx[i]);
    r0 += n->m[i] * (n->x0[i] * n->x0[i] + n->y0[i] * n->y0[i]);
  }
  double de = 0, dr = 0, dL = 0, dc = 0;
  for (int k = 0; k < 100; k++) {
    run_steps(s, 1000);
    run_energies(s);
    double M = 0, cx = 0, cy = 0, L = 0, r = 0;
    for (int i = 0; i < n->n; i++) {
      M += n->m[i];
      cx += n->m[i] * n->x[i];
      cy += n->m[i] * n->y[i];
    }
    cx /= M;
    cy /= M;
    /* positions are at step n, velocities at n + 1/2: take the momentum at the mid-step position */
    for (int i = 0; i < n->n; i++) {
      double x = n->x[i] + 0.5 * s->dt * n->vx[i] - cx, y = n->y[i] + 0.5 * s->dt * n->vy[i] - cy;
      L += n->m[i] * (x * n->vy[i] - y * n->vx[i]);
      r += n->m[i] * ((n->x[i] - cx) * (n->x[i] - cx) + (n->y[i] - cy) * (n->y[i] - cy));
    }
    de = fmax(de, fabs((s->energy.kinetic + s->energy.strain) / e0 - 1));
    dr = fmax(dr, fabs(sqrt(r / r0) - 1));
    dL = fmax(dL, fabs(L / L0 - 1));
    dc = fmax(dc, hypot(cx, cy));
  }
  fprintf(stderr, "spinning body: %.1f turns, energy %.2e, radius of gyration %.2e, angular momentum %.2e, centre %.2e m\n",
          w * s->time / (2 * M_PI), de, dr, dL, dc);
  ck_assert_double_lt(de, 1e-5);
  ck_assert_double_lt(dr, 5e-5);
  ck_assert_double_lt(dL, 1e-10);
  ck_assert_double_lt(dc, 1e-12);
}
END_TEST

Suite *physics_suite(void) {
  Suite *s = suite_create("physics");
  TCase *k = tcase_create("triangle");
  tcase_add_test(k, test_patch_uniform_strain);
  tcase_add_test(k, test_tri_four_lanes_match_scalar);
  tcase_add_test(k, test_uniaxial_stress_matches_E);
  tcase_add_test(k, test_uniaxial_plane_strain);
  tcase_add_test(k, test_rigid_rotation_zero_force);
  suite_add_tcase(s, k);
  TCase *d = tcase_create("dynamics");
  tcase_set_timeout(d, 120);
  tcase_add_test(d, test_wave_arrival_time);
  tcase_add_test(d, test_energy_conserved_free_vibration);
  tcase_add_test(d, test_cantilever_static_deflection);
  tcase_add_test(d, test_spinning_body_keeps_energy_and_shape);
  suite_add_tcase(s, d);
  TCase *b = tcase_create("directives");
  tcase_add_test(b, test_fixed_nodes_never_move);
  tcase_add_test(b, test_prescribed_displacement_exact);
  tcase_add_test(b, test_pressure_resultant);
  tcase_add_test(b, test_distributed_load_reported);
  tcase_add_test(b, test_gravity_free_fall);
  suite_add_tcase(s, b);
  return s;
}
