/* restart.c: exact restart files (HDF5) and the interrupt restart (see restart.h for the
 * semantics).
 *
 * This module owns the restart file layout, the periodic restart schedule (YfRestart in
 * YfSim.restart) and the check that a restart fits the scene the deck rebuilt.  It reads and
 * writes the other modules' state through their public structs (model.h, joint.h) and the
 * contact accessors (contact_state_save/load), so the step loop knows nothing about it except
 * restart_step() (one compare per step) and restart_on_interrupt().
 *
 * Layout (HDF5 1.8 format, one dataset per array, no compression; a restart must be exact, not
 * small):
 *   /meta/{version, nnode, ntri, njoint, topo_hash, mat_hash, jset_hash, part_ntri, part_n, complete}
 *          (part_ntri: the triangles the partition renumbered at the first run, -1 when it renumbered
 *          none; optional, for the message when a scene grew after it; part_n: the parts of that
 *          partition, 1 when none; optional, for the message when the reading deck splits the
 *          mesh otherwise)
 *   /sim/{step, time, dt, last_step, energy (7), elem_steps, wall_s, e_budget, gravity_base (3),
 *         between_runs, dt_auto, dt_safety}   (the last three optional: absent, within a run)
 *   /nodes/{x, y, x0, y0, vx, vy, fx, fy, m}                      (nnode each, [m], [m/s], [N/m], [kg/m])
 *   /tris/s (3 ntri: sxx, syy, sxy [Pa])  the stresses of the step's element stage: a frame due on
 *            the restart's step is written again by the continued run, and must be the live one's
 *            (they cannot be recomputed: they belong to the positions at the start of that step)
 *   /joints/{k, fs, dmg(3), w, z, f(8), state, mode, pend, nbroken, diss_broken, dt_prev,
 *            rec_step, rec_d(4: time x y length), rec_i(4: mode triA triB joint), rng_SET}
 *   /contact/{ij(2), g(6), gprev(6), spring, alive, nlive, ndead, travel, nsearch, broken_seen,
 *             force_search, fcn(2 nnode), fcn_valid}                 (only when contact is on)
 *            gprev: each couple's spring forces of the last step and spring: the energy the
 *            Coulomb springs held then (the friction booking, contact.c); a file without them
 *            (written before they were kept) reads as no history: zero forces, and the
 *            springs' energy computed from g at the file's positions
 *   /energy/{d (ENERGY_STATE_ND), l (ENERGY_STATE_NL)}   the energy check's memory (energy.c: its
 *            highs, windows and streaks); version 3 on, required there
 * /meta/complete is written last; a file without it is refused.
 */
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>
#include <gsl/gsl_rng.h>
#include <hdf5.h>
#include "restart.h"
#include "h5quiet.h"
#include "par.h"
#include "contact.h"
#include "contact_search.h" /* YF_PAIR_NG: the friction memory per couple */
#include "err.h"
#include "joint.h"
#include "run.h"
#include "energy.h"
#include "metrics.h"
#include "summary.h" /* sim_state_hash */

/* 2: the Coulomb friction law's memory is s = F_t / sqrt(k_t) (contact_pair.h), no longer F_t.
 * A version 1 file is read when none of its Coulomb couples holds friction memory (the rest of
 * the layout is the same); otherwise it is refused (F_t cannot be turned into s without the
 * contact interval of the step it was written at).
 * 3: /energy holds the energy check's memory (energy.h energy_state_save), so a continued run is
 * stopped where the uninterrupted one is.  Versions 1 and 2 are read with the check starting
 * afresh at the restart's step, and read_restart says so. */
#define RESTART_VERSION 3
/* the most steps a run takes (cmd_run.c): a restart's step and last step lie in [0, this] */
#define RESTART_STEP_MAX 1000000000000000L

typedef struct YfRestart {
  long every;      /* steps between periodic restarts (0: none)            */
  char *base;      /* FILE of `restart every N FILE`                        */
  int next;        /* 0: FILE.a is written next, 1: FILE.b                   */
  char *last;      /* last restart file written (for messages)              */
  uint64_t read_key; /* sim_state_hash of the state read_restart restored (output.c: a scene
                        changed after it rewrites the frame of its step)            */
  char *reading;   /* the file read_restart is reading: held here, not only on its stack, so that
                      an error's exit hook (the fuzzers, the tests) leaves nothing unreachable */
} YfRestart;

static YfRestart *rget(YfSim *s) {
  if (!s->restart) s->restart = yf_calloc(1, sizeof(YfRestart), "restart settings");
  return s->restart;
}

int restart_scene_changed(const YfSim *s) {
  return s->restored && s->restart && sim_state_hash(s) != s->restart->read_key;
}

void restart_free(YfSim *s) {
  YfRestart *r = s->restart;
  if (!r) return;
  free(r->base);
  free(r->last);
  free(r->reading);
  free(r);
  s->restart = NULL;
}

/* ---------------------------------------------------------------- scene fingerprint */

static void fnv(uint64_t *h, const void *p, size_t n) {
  const unsigned char *b = p;
  for (size_t k = 0; k < n; k++) {
    *h ^= b[k];
    *h *= 0x100000001b3ull;
  }
}

/* What the deck must rebuild identically: counts, triangle corners and materials, initial
 * positions, joint nodes and property sets. */
static uint64_t topo_hash(const YfSim *s) {
  const YfModel *m = &s->model;
  uint64_t h = 0xcbf29ce484222325ull;
  fnv(&h, &m->node.n, sizeof m->node.n);
  fnv(&h, &m->tri.n, sizeof m->tri.n);
  fnv(&h, m->tri.v, (size_t)m->tri.n * 3 * sizeof(int));
  fnv(&h, m->tri.mat, (size_t)m->tri.n * sizeof(int));
  fnv(&h, m->node.x0, (size_t)m->node.n * sizeof(double));
  fnv(&h, m->node.y0, (size_t)m->node.n * sizeof(double));
  const YfJoints *J = s->joints;
  if (J && J->n) {
    fnv(&h, J->node, (size_t)J->n * 4 * sizeof(int));
    fnv(&h, J->prop, (size_t)J->n * sizeof(int));
  }
  return h;
}

/* The properties of material k and of joint set k, each a hash: the topology hash has their
 * indices only, so a deck that rebuilt the scene with another E, density, penalty, strength or
 * fracture energy continued the restart silently, with a run no uninterrupted one gives.  Field by
 * field (no struct padding); names are left out (renaming is harmless). */
static void fnv_d(uint64_t *h, double v) { fnv(h, &v, sizeof v); }
static void fnv_i(uint64_t *h, int v) { fnv(h, &v, sizeof v); }
static uint64_t mat_hash(const YfMaterial *mt) {
  uint64_t h = 0xcbf29ce484222325ull;
  fnv_d(&h, mt->rho); fnv_d(&h, mt->E); fnv_d(&h, mt->nu); fnv_i(&h, mt->plane); fnv_d(&h, mt->lambda);
  fnv_d(&h, mt->mu); fnv_d(&h, mt->volfac); fnv_d(&h, mt->visc); fnv_d(&h, mt->beta); fnv_d(&h, mt->pen_n);
  fnv_d(&h, mt->pen_t); fnv_d(&h, mt->fric); fnv_i(&h, mt->fric_law); fnv_i(&h, mt->rigid);
  return h;
}
/* (the heterogeneity's seed and scatter are left out: the restart holds each joint's factors) */
static uint64_t jset_hash(const YfJointProp *p) {
  uint64_t h = 0xcbf29ce484222325ull;
  fnv_d(&h, p->ft); fnv_d(&h, p->fs); fnv_d(&h, p->gf); fnv_d(&h, p->pen); fnv_d(&h, p->coh); fnv_d(&h, p->phi);
  fnv_i(&h, p->law); fnv_i(&h, p->y2d_floor); fnv_i(&h, p->irreversible); fnv_d(&h, p->bl_z); fnv_d(&h, p->bl_s);
  fnv_i(&h, p->ntab);
  for (int k = 0; k < p->ntab && k < YF_JOINT_TAB_MAX; k++) { fnv_d(&h, p->tab_z[k]); fnv_d(&h, p->tab_s[k]); }
  fnv_d(&h, p->hreg);
  return h;
}

/* ---------------------------------------------------------------- HDF5 helpers */


typedef struct {
  hid_t file;
  int bad;          /* a write failed                          */
  char what[128];   /* the first dataset that failed            */
} W;

/* FNV-1a of n values of sz bytes (1, 4 or 8) taken least significant byte first, the same on a
 * machine of either byte order: the checksum of a dataset's values (attribute CHECKSUM). */
#define CHECKSUM "fnv1a"
static uint64_t values_hash(const void *data, size_t n, size_t sz) {
  uint64_t h = 0xcbf29ce484222325ull;
  const unsigned char *p = data;
  for (size_t k = 0; k < n; k++, p += sz) {
    uint64_t v = 0;
    if (sz == 8) memcpy(&v, p, 8);
    else if (sz == 4) { uint32_t u; memcpy(&u, p, 4); v = u; }
    else v = *p;
    for (size_t b = 0; b < sz; b++) {
      h ^= (v >> (8 * b)) & 0xffu;
      h *= 0x100000001b3ull;
    }
  }
  return h;
}

/* Each dataset carries the checksum of its values (from format 3): a restart damaged after it was
 * written (a block of a copy zeroed, a bit flipped) read as a valid one and continued a state no
 * run reached. */
static void put(W *w, hid_t g, const char *name, hid_t type, size_t n, const void *data) {
  if (w->bad) return;
  hsize_t dims[1] = {(hsize_t)n};
  hid_t sp = H5Screate_simple(1, dims, NULL);
  hid_t ds = sp >= 0 ? H5Dcreate2(g, name, type, sp, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT) : -1;
  static const double none[1] = {0};
  const uint64_t sum = values_hash(data, n && data ? n : 0, H5Tget_size(type));
  hid_t asp = ds >= 0 ? H5Screate(H5S_SCALAR) : -1;
  hid_t at = asp >= 0 ? H5Acreate2(ds, CHECKSUM, H5T_NATIVE_UINT64, asp, H5P_DEFAULT, H5P_DEFAULT) : -1;
  if (ds < 0 || H5Dwrite(ds, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, n && data ? data : (const void *)none) < 0 ||
      at < 0 || H5Awrite(at, H5T_NATIVE_UINT64, &sum) < 0) {
    w->bad = 1;
    snprintf(w->what, sizeof w->what, "%s", name);
  }
  if (at >= 0) H5Aclose(at);
  if (asp >= 0) H5Sclose(asp);
  if (ds >= 0) H5Dclose(ds);
  if (sp >= 0) H5Sclose(sp);
}
static void put_d(W *w, hid_t g, const char *name, double v) { put(w, g, name, H5T_NATIVE_DOUBLE, 1, &v); }
static void put_l(W *w, hid_t g, const char *name, long v) { put(w, g, name, H5T_NATIVE_LONG, 1, &v); }

static hid_t group(W *w, const char *name) {
  hid_t g = w->bad ? -1 : H5Gcreate2(w->file, name, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  if (g < 0 && !w->bad) {
    w->bad = 1;
    snprintf(w->what, sizeof w->what, "%s", name);
  }
  return g;
}
static void gclose(hid_t g) {
  if (g >= 0) H5Gclose(g);
}
/* A module's saved state (metrics, the energy check): its doubles as d and its integers as l in group name. */
static void put_state(W *w, const char *name, const double *d, size_t nd, const long *l, size_t nl) {
  hid_t g = group(w, name);
  put(w, g, "d", H5T_NATIVE_DOUBLE, nd, d);
  put(w, g, "l", H5T_NATIVE_LONG, nl, l);
  gclose(g);
}

/* Reading: every failure is fatal (an I/O error naming the file and the dataset). */
typedef struct {
  hid_t file;
  const char *path;
  const YfLoc *loc;
} R;

/* The file and whatever of it is still open (the group and dataset being read): H5Fclose alone
 * leaves the file open while an object of it is, so a process that goes on after the error (the
 * fuzz target, tools/fuzz; a library caller) found the stale file in HDF5's cache when it opened
 * a file of that name again (a SEGV in libhdf5). */
static void close_file_all(hid_t f) {
  const unsigned kinds = H5F_OBJ_DATASET | H5F_OBJ_GROUP | H5F_OBJ_DATATYPE | H5F_OBJ_ATTR | H5F_OBJ_LOCAL;
  ssize_t n = H5Fget_obj_count(f, kinds);
  if (n > 0) {
    hid_t *ids = yf_malloc((size_t)n * sizeof *ids, "HDF5 handles");
    n = H5Fget_obj_ids(f, kinds, (size_t)n, ids);
    for (ssize_t k = 0; k < n; k++) {
      if (H5Iget_type(ids[k]) == H5I_ATTR) H5Aclose(ids[k]);
      else H5Oclose(ids[k]);
    }
    free(ids);
  }
  H5Fclose(f);
}

static void rfail(const R *r, const char *what) __attribute__((noreturn));
static void rfail(const R *r, const char *what) {
  hid_t f = r->file;
  if (f >= 0) close_file_all(f);
  yf_io_error(r->loc, "read_restart: '%s' is not a usable yfdem restart (%s)", r->path, what);
}

/* Length of a 1-D dataset, -1 when absent. */
static long dlen(hid_t g, const char *name) {
  if (H5Lexists(g, name, H5P_DEFAULT) <= 0) return -1;
  hid_t ds = H5Dopen2(g, name, H5P_DEFAULT);
  if (ds < 0) return -1;
  hid_t sp = H5Dget_space(ds);
  hsize_t dims[1] = {0};
  long n = (sp >= 0 && H5Sget_simple_extent_ndims(sp) == 1 && H5Sget_simple_extent_dims(sp, dims, NULL) == 1) ? (long)dims[0] : -1;
  if (sp >= 0) H5Sclose(sp);
  H5Dclose(ds);
  return n;
}

static void get(const R *r, hid_t g, const char *name, hid_t type, size_t n, void *data) {
  char what[160];
  long have = dlen(g, name);
  if (have != (long)n) {
    snprintf(what, sizeof what, "dataset %s: %ld values, expected %zu", name, have, n);
    rfail(r, what);
  }
  if (!n) return;
  hid_t ds = H5Dopen2(g, name, H5P_DEFAULT);
  herr_t e = ds >= 0 ? H5Dread(ds, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data) : -1;
  /* the checksum written with the values (absent before format 3) */
  uint64_t sum = 0;
  int has = e >= 0 && H5Aexists(ds, CHECKSUM) > 0, bad_sum = 0;
  if (has) {
    hid_t at = H5Aopen(ds, CHECKSUM, H5P_DEFAULT);
    bad_sum = at < 0 || H5Aread(at, H5T_NATIVE_UINT64, &sum) < 0 || sum != values_hash(data, n, H5Tget_size(type));
    if (at >= 0) H5Aclose(at);
  }
  if (ds >= 0) H5Dclose(ds);
  if (e < 0) {
    snprintf(what, sizeof what, "cannot read dataset %s", name);
    rfail(r, what);
  }
  if (bad_sum) {
    snprintf(what, sizeof what, "dataset %s does not match the checksum written with it: the file was damaged after "
             "it was written", name);
    rfail(r, what);
  }
}
static double get_d(const R *r, hid_t g, const char *name) {
  double v;
  get(r, g, name, H5T_NATIVE_DOUBLE, 1, &v);
  return v;
}
static long get_l(const R *r, hid_t g, const char *name) {
  long v;
  get(r, g, name, H5T_NATIVE_LONG, 1, &v);
  return v;
}
static hid_t ropen(const R *r, const char *name) {
  hid_t g = H5Gopen2(r->file, name, H5P_DEFAULT);
  if (g < 0) {
    char what[96];
    snprintf(what, sizeof what, "no group /%s", name);
    rfail(r, what);
  }
  return g;
}

/* ---------------------------------------------------------------- write */

/* The opened-crack record (joint.h): flags and events, datasets opened, orec_step, orec_d
 * (time x y length), orec_i (mode triA triB joint). */
static void put_opened(W *w, hid_t g, const YfJoints *J) {
  size_t nr = (size_t)J->nopened;
  put(w, g, "opened", H5T_NATIVE_UCHAR, (size_t)J->n, J->opened);
  long *rs = yf_malloc((nr ? nr : 1) * sizeof(long), "restart buffer");
  double *rd = yf_malloc((nr ? nr : 1) * 4 * sizeof(double), "restart buffer");
  int *ri = yf_malloc((nr ? nr : 1) * 4 * sizeof(int), "restart buffer");
  for (size_t k = 0; k < nr; k++) {
    const YfBreak *b = &J->orec[k];
    rs[k] = b->step;
    rd[4 * k] = b->time; rd[4 * k + 1] = b->x; rd[4 * k + 2] = b->y; rd[4 * k + 3] = b->length;
    ri[4 * k] = b->mode; ri[4 * k + 1] = b->triA; ri[4 * k + 2] = b->triB; ri[4 * k + 3] = b->joint;
  }
  put(w, g, "orec_step", H5T_NATIVE_LONG, nr, rs);
  put(w, g, "orec_d", H5T_NATIVE_DOUBLE, 4 * nr, rd);
  put(w, g, "orec_i", H5T_NATIVE_INT, 4 * nr, ri);
  free(rs); free(rd); free(ri);
}

static void write_all(W *w, YfSim *s) {
  YfModel *m = &s->model;
  const YfNodes *N = &m->node;
  size_t nn = (size_t)N->n;
  hid_t g = group(w, "meta");
  put_l(w, g, "version", RESTART_VERSION);
  put_l(w, g, "nnode", N->n);
  put_l(w, g, "ntri", m->tri.n);
  put_l(w, g, "njoint", s->joints ? s->joints->n : 0);
  uint64_t th = topo_hash(s);
  put(w, g, "topo_hash", H5T_NATIVE_UINT64, 1, &th);
  put_l(w, g, "part_ntri", m->tri_new ? m->ntri_new : -1);
  put_l(w, g, "part_n", m->npart);
  {
    uint64_t *mh = yf_malloc((size_t)(m->nmat > 0 ? m->nmat : 1) * sizeof *mh, "restart material hashes");
    for (int k = 0; k < m->nmat; k++) mh[k] = mat_hash(&m->mat[k]);
    if (m->nmat > 0) put(w, g, "mat_hash", H5T_NATIVE_UINT64, (size_t)m->nmat, mh);
    free(mh);
    const YfJoints *J = s->joints;
    if (J && J->nset > 0) {
      uint64_t *jh = yf_malloc((size_t)J->nset * sizeof *jh, "restart joint set hashes");
      for (int k = 0; k < J->nset; k++) jh[k] = jset_hash(&J->set[k].p);
      put(w, g, "jset_hash", H5T_NATIVE_UINT64, (size_t)J->nset, jh);
      free(jh);
    }
  }
  gclose(g);

  g = group(w, "sim");
  put_l(w, g, "step", s->step);
  put_d(w, g, "time", s->time);
  put_d(w, g, "dt", s->dt);
  put_l(w, g, "last_step", s->last_step);
  const YfEnergy *e = &s->energy;
  double en[7] = {e->kinetic, e->strain, e->external_work, e->damping, e->joint_dissipated, e->contact, e->friction};
  put(w, g, "energy", H5T_NATIVE_DOUBLE, 7, en);
  put_d(w, g, "elem_steps", s->elem_steps);
  put_d(w, g, "wall_s", s->wall_s);
  put_d(w, g, "e_budget", energy_get_budget());
  /* gravity's work before the gravity changed, and the gravity booked since (run.c energies) */
  const double gb[3] = {s->gravity_base, s->g_booked[0], s->g_booked[1]};
  put(w, g, "gravity_base", H5T_NATIVE_DOUBLE, 3, gb);
  /* written outside a run (write_restart, an interrupt between runs): the continued deck's next
   * run starts as the uninterrupted deck's did (its first frame and record row, the stresses
   * recomputed, and under timestep auto its dt recomputed), so the deck's time step setting of
   * this moment goes along.  Optional datasets: a restart without them continues within a run,
   * as every restart did before, and an older yfdem reads this one as such */
  put_l(w, g, "between_runs", !s->in_run);
  /* the deck's setting, also within a run continued from a restart (which runs with auto off) */
  put_l(w, g, "dt_auto", s->dt_resume ? 1 : s->dt_auto);
  put_d(w, g, "dt_safety", s->dt_resume ? s->dt_resume_safety : s->dt_safety);
  gclose(g);

  g = group(w, "nodes");
  put(w, g, "x", H5T_NATIVE_DOUBLE, nn, N->x);
  put(w, g, "y", H5T_NATIVE_DOUBLE, nn, N->y);
  put(w, g, "x0", H5T_NATIVE_DOUBLE, nn, N->x0);
  put(w, g, "y0", H5T_NATIVE_DOUBLE, nn, N->y0);
  put(w, g, "vx", H5T_NATIVE_DOUBLE, nn, N->vx);
  put(w, g, "vy", H5T_NATIVE_DOUBLE, nn, N->vy);
  put(w, g, "fx", H5T_NATIVE_DOUBLE, nn, N->fx);
  put(w, g, "fy", H5T_NATIVE_DOUBLE, nn, N->fy);
  put(w, g, "m", H5T_NATIVE_DOUBLE, nn, N->m);
  gclose(g);

  g = group(w, "tris");
  put(w, g, "s", H5T_NATIVE_DOUBLE, 3 * (size_t)m->tri.n, m->tri.s);
  gclose(g);

  const YfJoints *J = s->joints;
  if (J && J->n) {
    size_t nj = (size_t)J->n;
    g = group(w, "joints");
    put(w, g, "k", H5T_NATIVE_DOUBLE, nj, J->k);
    put(w, g, "fs", H5T_NATIVE_DOUBLE, nj, J->fs);
    put(w, g, "dmg", H5T_NATIVE_DOUBLE, 3 * nj, J->dmg);
    put(w, g, "w", H5T_NATIVE_DOUBLE, nj, J->w);
    put(w, g, "z", H5T_NATIVE_DOUBLE, nj, J->z);
    put(w, g, "f", H5T_NATIVE_DOUBLE, 8 * nj, J->f);
    put(w, g, "state", H5T_NATIVE_UCHAR, nj, J->state);
    put(w, g, "mode", H5T_NATIVE_UCHAR, nj, J->mode);
    put(w, g, "pend", H5T_NATIVE_INT, (size_t)J->npend, J->pend);
    put_l(w, g, "nbroken", J->nbroken);
    put_d(w, g, "diss_broken", J->diss_broken);
    put_d(w, g, "dt_prev", J->dt_prev);
    size_t nr = (size_t)J->nrec;
    long *rs = yf_malloc((nr ? nr : 1) * sizeof(long), "restart buffer");
    double *rd = yf_malloc((nr ? nr : 1) * 4 * sizeof(double), "restart buffer");
    int *ri = yf_malloc((nr ? nr : 1) * 4 * sizeof(int), "restart buffer");
    for (size_t k = 0; k < nr; k++) {
      const YfBreak *b = &J->rec[k];
      rs[k] = b->step;
      rd[4 * k] = b->time; rd[4 * k + 1] = b->x; rd[4 * k + 2] = b->y; rd[4 * k + 3] = b->length;
      ri[4 * k] = b->mode; ri[4 * k + 1] = b->triA; ri[4 * k + 2] = b->triB; ri[4 * k + 3] = b->joint;
    }
    put(w, g, "rec_step", H5T_NATIVE_LONG, nr, rs);
    put(w, g, "rec_d", H5T_NATIVE_DOUBLE, 4 * nr, rd);
    put(w, g, "rec_i", H5T_NATIVE_INT, 4 * nr, ri);
    free(rs); free(rd); free(ri);
    put_opened(w, g, J);
    /* generator state of each joint set (joints added later in the deck would draw from it) */
    for (int i = 0; i < J->nset; i++) {
      const gsl_rng *rng = J->set[i].rng;
      if (!rng) continue;
      char name[32];
      snprintf(name, sizeof name, "rng_%d", i);
      put(w, g, name, H5T_NATIVE_UCHAR, gsl_rng_size(rng), gsl_rng_state(rng));
    }
    gclose(g);
  }

  /* the metrics' events before this step (an optional group: restarts without it read) */
  double md[METRICS_STATE_ND];
  long ml[METRICS_STATE_NL];
  metrics_state_save(md, ml);
  put_state(w, "metrics", md, METRICS_STATE_ND, ml, METRICS_STATE_NL);

  /* the energy check's memory (format 3) */
  double ed[ENERGY_STATE_ND];
  long el[ENERGY_STATE_NL];
  energy_state_save(ed, el);
  put_state(w, "energy", ed, ENERGY_STATE_ND, el, ENERGY_STATE_NL);

  YfContactState cs;
  if (contact_state_save(s, &cs)) {
    size_t np = (size_t)cs.n;
    g = group(w, "contact");
    put(w, g, "ij", H5T_NATIVE_INT, 2 * np, cs.ij);
    /* the memory's two halves as two datasets: g as before, gprev added (older readers skip it) */
    double *gh = yf_malloc((6 * np + 1) * sizeof(double), "restart buffer");
    for (int h = 0; h < 2; h++) {
      for (size_t k = 0; k < np; k++) memcpy(gh + 6 * k, cs.g + YF_PAIR_NG * k + 6 * h, 6 * sizeof(double));
      put(w, g, h ? "gprev" : "g", H5T_NATIVE_DOUBLE, 6 * np, gh);
    }
    free(gh);
    put_d(w, g, "spring", cs.spring);
    put(w, g, "alive", H5T_NATIVE_UCHAR, np, cs.alive);
    put_l(w, g, "nlive", cs.nlive);
    put_l(w, g, "ndead", cs.ndead);
    put_d(w, g, "travel", cs.travel);
    put_l(w, g, "nsearch", cs.nsearch);
    put_l(w, g, "broken_seen", cs.broken_seen);
    put_l(w, g, "force_search", cs.force_search);
    put(w, g, "fcn", H5T_NATIVE_DOUBLE, cs.fcn ? 2 * (size_t)cs.nn : 0, cs.fcn);
    put_l(w, g, "fcn_valid", cs.fcn_valid);
    gclose(g);
  }
  g = w->bad ? -1 : H5Gopen2(w->file, "meta", H5P_DEFAULT);
  put_l(w, g, "complete", 1); /* last: a file without it is refused */
  gclose(g);
}

enum { BEFORE_MAX = 4 };
static int (*before_write[BEFORE_MAX])(YfSim *s, char *err, size_t nerr);
void restart_before_write(int (*fn)(YfSim *s, char *err, size_t nerr)) {
  for (int i = 0; i < BEFORE_MAX; i++) {
    if (before_write[i] == fn) return;
    if (!before_write[i]) {
      before_write[i] = fn;
      return;
    }
  }
  YF_ASSERT(!"too many restart_before_write hooks");
}

int restart_write(YfSim *s, const char *path, char *err, size_t nerr) {
  if (err && nerr) err[0] = 0;
  if (!s->model.prepared) {
    if (err) snprintf(err, nerr, "the model is not prepared yet (write_restart needs a run or read_restart first)");
    return -1;
  }
  par_need_all(s); /* MPI: every rank is here; rank 0 needs what owners hold (stresses, joints) */
  contact_par_whole(s); /* MPI: and the couples with their friction memory */
  if (!yf_writer()) return 0; /* under MPI rank 0 writes the (replicated) state */
  char ferr[3 * 4096];
  for (int i = 0; i < BEFORE_MAX && before_write[i]; i++)
    if (before_write[i](s, ferr, sizeof ferr) != 0) {
      if (err) snprintf(err, nerr, "%s", ferr);
      return -1;
    }
  yf_h5_quiet();
  size_t L = strlen(path);
  char *tmp = yf_malloc(L + 8, "restart path");
  snprintf(tmp, L + 8, "%s.tmp", path);
  hid_t fapl = H5Pcreate(H5P_FILE_ACCESS);
  H5Pset_libver_bounds(fapl, H5F_LIBVER_V18, H5F_LIBVER_V18);
  yf_tmp_live(tmp); /* a second Ctrl-C removes it */
  W w = {H5Fcreate(tmp, H5F_ACC_TRUNC, H5P_DEFAULT, fapl), 0, ""};
  H5Pclose(fapl);
  if (w.file < 0) {
    yf_tmp_live(NULL);
    if (err) snprintf(err, nerr, "cannot create '%s' (%s)", tmp, errno ? strerror(errno) : "HDF5 error");
    unlink(tmp); /* a full disk may leave it empty */
    free(tmp);
    return -1;
  }
  write_all(&w, s);
  if (H5Fclose(w.file) < 0 && !w.bad) {
    w.bad = 1;
    snprintf(w.what, sizeof w.what, "closing the file");
  }
  if (!w.bad) {
    /* the data must be on disk before the name points at it */
    int fd = open(tmp, O_RDONLY);
    if (fd < 0 || fsync(fd) != 0) {
      w.bad = 1;
      snprintf(w.what, sizeof w.what, "fsync: %s", strerror(errno));
    }
    if (fd >= 0) close(fd);
  }
  if (!w.bad && rename(tmp, path) != 0) {
    w.bad = 1;
    snprintf(w.what, sizeof w.what, "rename to '%s': %s", path, strerror(errno));
  }
  yf_tmp_live(NULL);
  if (w.bad) {
    if (err) snprintf(err, nerr, "cannot write restart '%s' (%s)", path, w.what);
    unlink(tmp);
    free(tmp);
    return -1;
  }
  free(tmp);
  YfRestart *r = rget(s);
  free(r->last);
  r->last = yf_strdup(path);
  return 0;
}

/* ---------------------------------------------------------------- read */

static int exists(const char *p) {
  struct stat st;
  return stat(p, &st) == 0;
}

/* Step of a complete restart file, -1 when it is not one. */
static long peek_step(const char *path) {
  yf_h5_quiet();
  hid_t f = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
  if (f < 0) return -1;
  long step = -1, one = 0;
  if (H5Lexists(f, "meta", H5P_DEFAULT) > 0 && H5Lexists(f, "sim", H5P_DEFAULT) > 0) {
    hid_t m = H5Gopen2(f, "meta", H5P_DEFAULT), g = H5Gopen2(f, "sim", H5P_DEFAULT);
    if (m >= 0 && g >= 0 && dlen(m, "complete") == 1 && dlen(g, "step") == 1) {
      hid_t d1 = H5Dopen2(m, "complete", H5P_DEFAULT), d2 = H5Dopen2(g, "step", H5P_DEFAULT);
      if (d1 >= 0 && d2 >= 0 && H5Dread(d1, H5T_NATIVE_LONG, H5S_ALL, H5S_ALL, H5P_DEFAULT, &one) >= 0 && one == 1 &&
          H5Dread(d2, H5T_NATIVE_LONG, H5S_ALL, H5S_ALL, H5P_DEFAULT, &step) < 0)
        step = -1;
      if (d1 >= 0) H5Dclose(d1);
      if (d2 >= 0) H5Dclose(d2);
    }
    if (m >= 0) H5Gclose(m);
    if (g >= 0) H5Gclose(g);
  }
  H5Fclose(f);
  return step;
}

/* FILE itself, or the newer complete one of FILE.a / FILE.b (malloc'd); NULL when none. */
char *restart_pick_file(const char *path) {
  if (exists(path)) return yf_strdup(path);
  size_t L = strlen(path) + 3;
  char *a = yf_malloc(L, "restart path"), *b = yf_malloc(L, "restart path");
  snprintf(a, L, "%s.a", path);
  snprintf(b, L, "%s.b", path);
  long sa = exists(a) ? peek_step(a) : -1, sb = exists(b) ? peek_step(b) : -1;
  if (sa < 0 && sb < 0) {
    free(a); free(b);
    return NULL;
  }
  if (sa >= sb) { free(b); return a; }
  free(a);
  return b;
}

static void mismatch(const YfLoc *loc, const char *path, const char *what, long file, long here) __attribute__((noreturn));
static void mismatch(const YfLoc *loc, const char *path, const char *what, long file, long here) {
  yf_deck_error(loc, "read_restart: '%s' was written for a different scene: %s %ld in the file, %ld here "
                "(the deck must rebuild the same scene: the same mesh, fracture and contact commands, in the same order)",
                path, what, file, here);
}

/* A break or opened-crack record read from a restart: its indices name a triangle and a joint of
 * the scene (the fracture log prints the triangles' ids: an index past them was read out of
 * bounds), its mode one of the failure modes, its numbers finite. */
static int record_ok(const YfBreak *b, int ntri, int njoint, long step) {
  return b->mode >= YF_JMODE_I && b->mode <= YF_JMODE_MIXED && b->triA >= 0 && b->triA < ntri && b->triB >= 0 &&
         b->triB < ntri && b->joint >= 0 && b->joint < njoint && b->step >= 0 && b->step <= step + 1 &&
         isfinite(b->time) && isfinite(b->x) && isfinite(b->y) && isfinite(b->length);
}

void restart_read(YfSim *s, const char *path_in, const YfLoc *loc) {
  YfModel *m = &s->model;
  if (!m->tri.n)
    yf_deck_error(loc, "read_restart: the scene has no triangles: the deck must rebuild the scene (mesh, fracture, "
                  "contact commands) before read_restart");
  char *path = restart_pick_file(path_in);
  if (!path)
    yf_io_error(loc, "read_restart: no restart '%s' (nor %s.a / %s.b): %s", path_in, path_in, path_in, strerror(ENOENT));
  free(rget(s)->reading);
  rget(s)->reading = path;
  yf_h5_quiet();
  R r = {H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT), path, loc};
  if (r.file < 0) rfail(&r, "not an HDF5 file, or unreadable");
  hid_t g = ropen(&r, "meta");
  if (dlen(g, "complete") != 1 || get_l(&r, g, "complete") != 1) rfail(&r, "incomplete file: the writer was stopped");
  long ver = get_l(&r, g, "version");
  if (ver < 1 || ver > RESTART_VERSION) {
    char what[96];
    snprintf(what, sizeof what, "format version %ld, this yfdem reads %d", ver, RESTART_VERSION);
    rfail(&r, what);
  }
  long f_nn = get_l(&r, g, "nnode"), f_nt = get_l(&r, g, "ntri"), f_nj = get_l(&r, g, "njoint");
  uint64_t f_th;
  get(&r, g, "topo_hash", H5T_NATIVE_UINT64, 1, &f_th);
  long f_part = H5Lexists(g, "part_ntri", H5P_DEFAULT) > 0 ? get_l(&r, g, "part_ntri") : -1;
  long f_npart = H5Lexists(g, "part_n", H5P_DEFAULT) > 0 ? get_l(&r, g, "part_n") : 0;
  /* the properties' hashes (absent from restarts of before 2026-11-29: not checked then) */
  long f_nmat = dlen(g, "mat_hash"), f_nset = dlen(g, "jset_hash");
  uint64_t *f_mh = NULL, *f_jh = NULL;
  if (f_nmat > 0) {
    f_mh = yf_malloc((size_t)f_nmat * sizeof *f_mh, "restart material hashes");
    get(&r, g, "mat_hash", H5T_NATIVE_UINT64, (size_t)f_nmat, f_mh);
  }
  if (f_nset > 0) {
    f_jh = yf_malloc((size_t)f_nset * sizeof *f_jh, "restart joint set hashes");
    get(&r, g, "jset_hash", H5T_NATIVE_UINT64, (size_t)f_nset, f_jh);
  }
  H5Gclose(g);

  /* the scene as `run` would prepare it (joints inserted, masses, contact setup) */
  run_prepare(s);
  long nj = s->joints ? s->joints->n : 0;
  if (f_nt != m->tri.n) { H5Fclose(r.file); mismatch(loc, path, "triangles", f_nt, m->tri.n); }
  if (f_nn != m->node.n) { H5Fclose(r.file); mismatch(loc, path, "nodes", f_nn, m->node.n); }
  if (f_nj != nj) { H5Fclose(r.file); mismatch(loc, path, "joints", f_nj, nj); }
  if (f_th != topo_hash(s)) {
    H5Fclose(r.file);
    free(f_mh);
    free(f_jh);
    if (f_part >= 0 && f_part < f_nt)
      /* The partition renumbers the scene once, at the first run; triangles added after it follow
       * in the order they were made.  A deck that makes them all before read_restart has them
       * renumbered together, in another order, so the scene cannot be matched; without a
       * renumbering (partition none: every triangle in the order made) both decks agree. */
      yf_deck_error(loc, "read_restart: '%s' was written for a scene that grew after the partition of its first run "
                    "(%ld of its %ld triangles were renumbered then, the rest were added between runs): a deck that "
                    "makes them all before read_restart renumbers them together, in another order, so it cannot "
                    "continue it; give 'partition none' in the deck that writes the restart and in the one that "
                    "reads it", path, f_part, f_nt);
    if (f_npart >= 1 && f_npart != m->npart) {
      /* The same scene split otherwise (a `partition` line added, removed or changed between the
       * two decks) numbers its triangles and nodes in another order: said as such, since the deck
       * did rebuild the scene. */
      char want[64];
      if (f_npart == 1) snprintf(want, sizeof want, "partition none");
      else snprintf(want, sizeof want, "partition metis parts %ld", f_npart);
      yf_deck_error(loc, "read_restart: '%s' was written by a run whose mesh was split into %ld part%s (%s), and "
                    "this deck splits it into %d (%s): the triangles and nodes are numbered in another order, so "
                    "the restart cannot be matched; give this deck the partition of the one that wrote it ('%s' "
                    "before its first run)", path, f_npart, f_npart == 1 ? "" : "s",
                    f_npart == 1 ? "not renumbered" : "METIS", m->npart, m->npart == 1 ? "not renumbered" : "METIS",
                    want);
    }
    yf_deck_error(loc, "read_restart: '%s' was written for a different scene: same counts, but the triangle corners, "
                  "materials, initial positions or joints differ (the deck must rebuild the same scene)", path);
  }
  /* the properties of every material a triangle uses and every joint set a joint uses */
  for (int t = 0; f_mh && t < m->tri.n; t++) {
    int k = m->tri.mat[t];
    if (k < f_nmat && f_mh[k] == mat_hash(&m->mat[k])) continue;
    char name[YF_NAME_MAX];
    snprintf(name, sizeof name, "%s", m->mat[k].name);
    free(f_mh);
    free(f_jh);
    H5Fclose(r.file);
    yf_deck_error(loc, "read_restart: '%s' was written with other properties of material '%s' (density, moduli, "
                  "plane, damping, contact penalties or friction): the deck must rebuild the same scene, the same "
                  "material commands included", path, name);
  }
  for (int j = 0; f_jh && s->joints && j < s->joints->n; j++) {
    int k = s->joints->prop[j];
    if (k < f_nset && f_jh[k] == jset_hash(&s->joints->set[k].p)) continue;
    char name[YF_NAME_MAX];
    snprintf(name, sizeof name, "%s", s->joints->set[k].name);
    free(f_mh);
    free(f_jh);
    H5Fclose(r.file);
    yf_deck_error(loc, "read_restart: '%s' was written with other properties of jointprop '%s' (strengths, fracture "
                  "energy, penalty, law or damage memory): the deck must rebuild the same scene, the same jointprop "
                  "commands included", path, name);
  }
  free(f_mh);
  free(f_jh);
  int c_here = contact_has_state(s);
  int c_file = H5Lexists(r.file, "contact", H5P_DEFAULT) > 0;
  if (c_here != c_file) {
    H5Fclose(r.file);
    yf_deck_error(loc, "read_restart: '%s' %s contact state but contact is %s in this deck (give the same contact "
                  "commands before read_restart)", path, c_file ? "holds" : "has no", c_here ? "on" : "off");
  }

  /* read everything into place; sizes are checked per dataset */
  YfNodes *N = &m->node;
  size_t nn = (size_t)N->n;
  g = ropen(&r, "sim");
  long step = get_l(&r, g, "step");
  double time = get_d(&r, g, "time"), dt = get_d(&r, g, "dt");
  long last_step = get_l(&r, g, "last_step");
  double en[7];
  get(&r, g, "energy", H5T_NATIVE_DOUBLE, 7, en);
  double elem_steps = get_d(&r, g, "elem_steps"), wall_s = get_d(&r, g, "wall_s"), budget = get_d(&r, g, "e_budget");
  double gb[3] = {0.0, 0.0, 0.0}; /* restarts before 2026-11-28 have none: no gravity changed */
  int has_gb = H5Lexists(g, "gravity_base", H5P_DEFAULT) > 0;
  if (has_gb) get(&r, g, "gravity_base", H5T_NATIVE_DOUBLE, 3, gb);
  /* restarts before 2026-11-29 have no between_runs: they continue within a run */
  long between = H5Lexists(g, "between_runs", H5P_DEFAULT) > 0 ? get_l(&r, g, "between_runs") : 0;
  /* the deck's time step setting (optional like between_runs): within a run it comes back when the
   * continued run ends (s->dt_resume) */
  const int has_auto = H5Lexists(g, "dt_auto", H5P_DEFAULT) > 0;
  long f_auto = has_auto ? get_l(&r, g, "dt_auto") : 0;
  double f_safety = has_auto ? get_d(&r, g, "dt_safety") : 0.5;
  H5Gclose(g);
  if (!(isfinite(gb[0]) && isfinite(gb[1]) && isfinite(gb[2]))) rfail(&r, "gravity_base out of range");
  if (between != 0 && between != 1) rfail(&r, "sim/between_runs is neither 0 nor 1");
  if (has_auto && (f_auto < 0 || f_auto > 1 || !(f_safety > 0 && f_safety <= 1.0))) rfail(&r, "sim/dt_auto or dt_safety out of range");
  /* dt 0: a restart written before the first run of a deck with timestep auto (no step set yet) */
  if (step < 0 || !(dt > 0 || (between && f_auto && dt == 0.0)) || time != time)
    rfail(&r, "step, time or dt out of range");
  /* a run goes on from these (step + N, time + dt...: a step of 2^63 - 1 overflowed) and the
   * summary and thermo print them: the steps a run may take (cmd_run.c), finite numbers */
  if (step > RESTART_STEP_MAX || last_step < 0 || last_step > RESTART_STEP_MAX || !isfinite(time) || !isfinite(dt))
    rfail(&r, "sim/step, last_step, time or dt out of range");
  for (int k = 0; k < 7; k++)
    if (!isfinite(en[k])) rfail(&r, "sim/energy: not a finite number");
  if (!(elem_steps >= 0 && isfinite(elem_steps)) || !(wall_s >= 0 && isfinite(wall_s)))
    rfail(&r, "sim/elem_steps or wall_s out of range");

  g = ropen(&r, "nodes");
  get(&r, g, "x", H5T_NATIVE_DOUBLE, nn, N->x);
  get(&r, g, "y", H5T_NATIVE_DOUBLE, nn, N->y);
  get(&r, g, "x0", H5T_NATIVE_DOUBLE, nn, N->x0);
  get(&r, g, "y0", H5T_NATIVE_DOUBLE, nn, N->y0);
  get(&r, g, "vx", H5T_NATIVE_DOUBLE, nn, N->vx);
  get(&r, g, "vy", H5T_NATIVE_DOUBLE, nn, N->vy);
  get(&r, g, "fx", H5T_NATIVE_DOUBLE, nn, N->fx);
  get(&r, g, "fy", H5T_NATIVE_DOUBLE, nn, N->fy);
  /* the masses run_prepare made from this scene (the fingerprint above proved it the file's): the
   * file's must be the same bits; a zero mass was taken and froze its node, a NaN one was too */
  double *m_here = yf_malloc((size_t)(nn ? nn : 1) * sizeof(double), "restart buffer");
  memcpy(m_here, N->m, (size_t)nn * sizeof(double));
  get(&r, g, "m", H5T_NATIVE_DOUBLE, nn, N->m);
  int bad_m = memcmp(m_here, N->m, (size_t)nn * sizeof(double)) != 0;
  free(m_here);
  if (bad_m) rfail(&r, "nodes/m: the masses are not those of the scene the deck built");
  {
    const double *a[] = {N->x, N->y, N->vx, N->vy, N->fx, N->fy};
    for (size_t q = 0; q < sizeof a / sizeof a[0]; q++)
      for (size_t i = 0; i < nn; i++)
        if (!isfinite(a[q][i])) rfail(&r, "nodes/x, y, vx, vy, fx or fy: not a finite number");
  }
  H5Gclose(g);
  /* stresses (absent in restarts written before they were stored: the first frame then shows the
   * stresses the deck's own preparation left) */
  if (H5Lexists(r.file, "tris", H5P_DEFAULT) > 0) {
    g = ropen(&r, "tris");
    if (dlen(g, "s") != 3 * (long)m->tri.n) rfail(&r, "tris/s: not 3 stresses per triangle");
    get(&r, g, "s", H5T_NATIVE_DOUBLE, 3 * (size_t)m->tri.n, m->tri.s);
    H5Gclose(g);
    /* between runs the uninterrupted deck's next run recomputed them for its first frame (run.c):
     * so does the continued one */
    m->stress_restored = !between;
  }

  YfJoints *J = s->joints;
  if (J && J->n) {
    size_t n = (size_t)J->n;
    g = ropen(&r, "joints");
    get(&r, g, "k", H5T_NATIVE_DOUBLE, n, J->k);
    get(&r, g, "fs", H5T_NATIVE_DOUBLE, n, J->fs);
    get(&r, g, "dmg", H5T_NATIVE_DOUBLE, 3 * n, J->dmg);
    get(&r, g, "w", H5T_NATIVE_DOUBLE, n, J->w);
    get(&r, g, "z", H5T_NATIVE_DOUBLE, n, J->z);
    get(&r, g, "f", H5T_NATIVE_DOUBLE, 8 * n, J->f);
    get(&r, g, "state", H5T_NATIVE_UCHAR, n, J->state);
    get(&r, g, "mode", H5T_NATIVE_UCHAR, n, J->mode);
    long np = dlen(g, "pend");
    if (np < 0 || np > J->n) rfail(&r, "joints/pend out of range");
    get(&r, g, "pend", H5T_NATIVE_INT, (size_t)np, J->pend);
    J->npend = (int)np;
    for (int q = 0; q < J->npend; q++)
      if (J->pend[q] < 0 || J->pend[q] >= J->n) rfail(&r, "joints/pend: joint index out of range");
    J->nbroken = (int)get_l(&r, g, "nbroken");
    J->diss_broken = get_d(&r, g, "diss_broken");
    J->dt_prev = get_d(&r, g, "dt_prev");
    long nr = dlen(g, "rec_step");
    if (nr < 0 || nr > INT_MAX / 2) rfail(&r, "joints/rec_step missing");
    long *rs = yf_malloc((size_t)(nr ? nr : 1) * sizeof(long), "restart buffer");
    double *rd = yf_malloc((size_t)(nr ? nr : 1) * 4 * sizeof(double), "restart buffer");
    int *ri = yf_malloc((size_t)(nr ? nr : 1) * 4 * sizeof(int), "restart buffer");
    get(&r, g, "rec_step", H5T_NATIVE_LONG, (size_t)nr, rs);
    get(&r, g, "rec_d", H5T_NATIVE_DOUBLE, 4 * (size_t)nr, rd);
    get(&r, g, "rec_i", H5T_NATIVE_INT, 4 * (size_t)nr, ri);
    if (J->caprec < nr) {
      J->caprec = (int)nr;
      J->rec = yf_realloc(J->rec, (size_t)J->caprec * sizeof *J->rec, "break record");
    }
    J->nrec = (int)nr;
    for (long k = 0; k < nr; k++)
      J->rec[k] = (YfBreak){rs[k], rd[4 * k], rd[4 * k + 1], rd[4 * k + 2], rd[4 * k + 3],
                            ri[4 * k], ri[4 * k + 1], ri[4 * k + 2], ri[4 * k + 3]};
    free(rs); free(rd); free(ri);
    for (long k = 0; k < nr; k++)
      if (!record_ok(&J->rec[k], m->tri.n, J->n, step)) rfail(&r, "joints/rec_*: a break record out of range");
    if (J->nbroken < 0 || J->nbroken > J->n) rfail(&r, "joints/nbroken out of range");
    for (size_t j = 0; j < n; j++)
      if (J->state[j] > 2 || J->mode[j] > YF_JMODE_MIXED) rfail(&r, "joints/state or mode: a value no joint takes");
    if (!isfinite(J->diss_broken) || !(J->dt_prev >= 0 && isfinite(J->dt_prev)))
      rfail(&r, "joints/diss_broken or dt_prev out of range");
    /* opened cracks (absent in restarts written before they were recorded: none then) */
    if (dlen(g, "opened") >= 0) {
      get(&r, g, "opened", H5T_NATIVE_UCHAR, n, J->opened);
      long no = dlen(g, "orec_step");
      if (no < 0 || no > J->n) rfail(&r, "joints/orec_step out of range");
      rs = yf_malloc((size_t)(no ? no : 1) * sizeof(long), "restart buffer");
      rd = yf_malloc((size_t)(no ? no : 1) * 4 * sizeof(double), "restart buffer");
      ri = yf_malloc((size_t)(no ? no : 1) * 4 * sizeof(int), "restart buffer");
      get(&r, g, "orec_step", H5T_NATIVE_LONG, (size_t)no, rs);
      get(&r, g, "orec_d", H5T_NATIVE_DOUBLE, 4 * (size_t)no, rd);
      get(&r, g, "orec_i", H5T_NATIVE_INT, 4 * (size_t)no, ri);
      if (J->caporec < no) {
        J->caporec = (int)no;
        J->orec = yf_realloc(J->orec, (size_t)J->caporec * sizeof *J->orec, "opened record");
      }
      J->nopened = (int)no;
      for (long k = 0; k < no; k++)
        J->orec[k] = (YfBreak){rs[k], rd[4 * k], rd[4 * k + 1], rd[4 * k + 2], rd[4 * k + 3],
                               ri[4 * k], ri[4 * k + 1], ri[4 * k + 2], ri[4 * k + 3]};
      free(rs); free(rd); free(ri);
      for (long k = 0; k < no; k++)
        if (!record_ok(&J->orec[k], m->tri.n, J->n, step)) rfail(&r, "joints/orec_*: an opened-crack record out of range");
    }
    for (int i = 0; i < J->nset; i++) {
      char name[32];
      snprintf(name, sizeof name, "rng_%d", i);
      long nb = dlen(g, name);
      if (nb < 0) continue;
      if (!J->set[i].rng) {
        J->set[i].rng = gsl_rng_alloc(gsl_rng_mt19937);
        gsl_rng_set(J->set[i].rng, J->set[i].seed);
      }
      if ((size_t)nb != gsl_rng_size(J->set[i].rng)) rfail(&r, "joints: random generator state of another size");
      get(&r, g, name, H5T_NATIVE_UCHAR, (size_t)nb, gsl_rng_state(J->set[i].rng));
    }
    H5Gclose(g);
  }

  if (c_file) {
    g = ropen(&r, "contact");
    YfContactState st;
    memset(&st, 0, sizeof st);
    long np = dlen(g, "alive");
    if (np < 0 || np > INT_MAX / 12) rfail(&r, "contact/alive missing");
    st.n = (int)np;
    st.ij = yf_malloc((size_t)(np ? np : 1) * 2 * sizeof(int), "restart buffer");
    st.g = yf_calloc((size_t)(np ? np : 1) * YF_PAIR_NG, sizeof(double), "restart buffer");
    double *gh = yf_malloc((size_t)(np ? np : 1) * 6 * sizeof(double), "restart buffer");
    st.alive = yf_malloc((size_t)(np ? np : 1), "restart buffer");
    st.fcn = yf_malloc((nn ? nn : 1) * 2 * sizeof(double), "restart buffer");
    get(&r, g, "ij", H5T_NATIVE_INT, 2 * (size_t)np, st.ij);
    get(&r, g, "g", H5T_NATIVE_DOUBLE, 6 * (size_t)np, gh);
    for (long k = 0; k < np; k++) memcpy(st.g + YF_PAIR_NG * k, gh + 6 * k, 6 * sizeof(double));
    /* the forces of the last step: a file without them (older) has no history, zeros */
    if (dlen(g, "gprev") == 6 * np) {
      get(&r, g, "gprev", H5T_NATIVE_DOUBLE, 6 * (size_t)np, gh);
      for (long k = 0; k < np; k++) memcpy(st.g + YF_PAIR_NG * k + 6, gh + 6 * k, 6 * sizeof(double));
    }
    free(gh);
    /* the springs' energy of the last step: without it (older) contact_state_load computes it */
    st.has_spring = dlen(g, "spring") == 1;
    if (st.has_spring) st.spring = get_d(&r, g, "spring");
    get(&r, g, "alive", H5T_NATIVE_UCHAR, (size_t)np, st.alive);
    for (long k = 0; k < 2 * np; k++)
      if (st.ij[k] < 0 || st.ij[k] >= m->tri.n) rfail(&r, "contact/ij: triangle index out of range");
    if (ver == 1) /* the old form of the Coulomb memory (F_t): refused where it is not zero */
      for (long k = 0; k < np; k++) {
        int ma = m->tri.mat[st.ij[2 * k]], mb = m->tri.mat[st.ij[2 * k + 1]];
        if (m->mat[ma].fric_law == YF_FRIC_Y2D || m->mat[mb].fric_law == YF_FRIC_Y2D) continue;
        for (int c = 0; c < 6; c++)
          if (st.g[YF_PAIR_NG * k + c] != 0.0)
            rfail(&r, "format version 1 holds the coulomb friction law's memory as F_t (this yfdem keeps "
                      "F_t / sqrt(k_t)): rerun from the deck, or with the yfdem that wrote it");
      }
    st.nlive = (int)get_l(&r, g, "nlive");
    st.ndead = (int)get_l(&r, g, "ndead");
    st.travel = get_d(&r, g, "travel");
    st.nsearch = get_l(&r, g, "nsearch");
    st.broken_seen = get_l(&r, g, "broken_seen");
    st.force_search = (int)get_l(&r, g, "force_search");
    long nf = dlen(g, "fcn");
    if (nf == 2 * (long)nn) {
      get(&r, g, "fcn", H5T_NATIVE_DOUBLE, 2 * nn, st.fcn);
      st.nn = (int)nn;
    } else {
      free(st.fcn);
      st.fcn = NULL;
    }
    st.fcn_valid = st.fcn ? (int)get_l(&r, g, "fcn_valid") : 0;
    /* the distance moved since the last search decides the next one (a NaN never reaches the
     * buffer: no search again, contacts missed in silence); the springs' energy is booked */
    if (!(st.travel >= 0 && isfinite(st.travel)) || (st.has_spring && !isfinite(st.spring))) {
      free(st.ij); free(st.g); free(st.alive); free(st.fcn);
      rfail(&r, "contact/travel or spring out of range");
    }
    H5Gclose(g);
    contact_state_load(s, &st);
    free(st.ij); free(st.g); free(st.alive); free(st.fcn);
  }
  if (H5Lexists(r.file, "metrics", H5P_DEFAULT) > 0) {
    double md[METRICS_STATE_ND];
    long ml[METRICS_STATE_NL];
    g = ropen(&r, "metrics");
    get(&r, g, "d", H5T_NATIVE_DOUBLE, METRICS_STATE_ND, md);
    get(&r, g, "l", H5T_NATIVE_LONG, METRICS_STATE_NL, ml);
    H5Gclose(g);
    metrics_state_load(md, ml);
  }
  double ed[ENERGY_STATE_ND];
  long el[ENERGY_STATE_NL];
  if (ver >= 3) {
    g = ropen(&r, "energy");
    get(&r, g, "d", H5T_NATIVE_DOUBLE, ENERGY_STATE_ND, ed);
    get(&r, g, "l", H5T_NATIVE_LONG, ENERGY_STATE_NL, el);
    H5Gclose(g);
  }
  H5Fclose(r.file);

  s->step = step;
  s->time = time;
  s->dt = dt;
  s->restored = 1;
  s->restored_between = (int)between;
  rget(s)->read_key = sim_state_hash(s);
  /* within a run the uninterrupted run kept the dt of its start; between runs its next run took
   * the time step setting of that moment (timestep auto computes dt anew from the state reached:
   * broken joints no longer limit it).  A later `timestep` overrides either. */
  s->dt_auto = between ? (int)f_auto : 0;
  if (between) s->dt_safety = f_safety;
  /* within a run under timestep auto: the uninterrupted deck's next run recomputed its dt (a
   * joint that limited it may have broken), so the continued one does once this run ends (until
   * 2026-11-29 auto stayed off for the rest of the deck: another state) */
  s->dt_resume = !between && f_auto;
  s->dt_resume_safety = f_safety;
  s->dt_pending = 0; /* dt is the restart's, as the deck read it at that point */
  s->dt_loc.file = NULL;
  s->last_step = last_step;
  YfEnergy *e = &s->energy;
  e->kinetic = en[0]; e->strain = en[1]; e->external_work = en[2]; e->damping = en[3];
  e->joint_dissipated = en[4]; e->contact = en[5]; e->friction = en[6];
  s->elem_steps = elem_steps;
  s->wall_s = wall_s;
  s->gravity_base = gb[0];
  s->g_booked[0] = gb[1];
  s->g_booked[1] = gb[2];
  s->g_booked_set = has_gb; /* a gravity given before read_restart other than the booked one is a change */
  /* the energies of this state (the file holds those last evaluated), as the residual the deck's
   * changes before the next run are measured from (energy.c) */
  run_energies_whole(s);
  energy_restored(s, budget, ver >= 3 ? ed : NULL, ver >= 3 ? el : NULL);
  if (ver < 3)
    yf_warn(loc, "read_restart: '%s' is of format version %ld, which holds no memory of the energy check: the "
            "check starts afresh at step %ld (a growth of the energy balance that began before it is seen later "
            "than in the uninterrupted run)", path, ver, step);
  sim_printf(s, "read_restart: %s: step %ld, time %.6g s, dt %.6g s, %d nodes, %d triangles, %ld joints (%ld broken)%s\n",
             path, step, time, dt, m->node.n, m->tri.n, nj, s->joints ? (long)s->joints->nbroken : 0L,
             c_file ? ", contact couples restored" : "");
  s->restart->reading = NULL;
  free(path);
}

/* ---------------------------------------------------------------- schedule, interrupt, commands */

/* Next file of `restart every` (alternating), malloc'd. */
static char *next_periodic(YfRestart *r) {
  size_t L = strlen(r->base) + 3;
  char *p = yf_malloc(L, "restart path");
  snprintf(p, L, "%s.%c", r->base, r->next ? 'b' : 'a');
  r->next = !r->next;
  return p;
}

void restart_step(YfSim *s) {
  YfRestart *r = s->restart;
  if (!r || r->every <= 0 || s->step % r->every) return;
  char *p = next_periodic(r);
  char err[1024];
  if (restart_write(s, p, err, sizeof err)) yf_io_error(NULL, "restart every %ld: %s", r->every, err);
  free(p);
}

const char *restart_on_interrupt(YfSim *s, char *err, size_t nerr) {
  static char name[1024];
  YfRestart *r = rget(s);
  name[0] = 0;
  if (r->base) {
    char *p = next_periodic(r);
    if (!restart_write(s, p, err, nerr)) snprintf(name, sizeof name, "%s", r->base);
    free(p);
  } else if (!restart_write(s, YF_RESTART_DEFAULT, err, nerr)) {
    snprintf(name, sizeof name, "%s", YF_RESTART_DEFAULT);
  }
  return name;
}

void restart_every(YfSim *s, long every, const char *base) {
  YfRestart *r = rget(s);
  free(r->base);
  r->base = NULL;
  r->every = every;
  if (every <= 0) {
    r->every = 0;
    return;
  }
  r->base = yf_strdup(base);
  r->next = 0;
}
