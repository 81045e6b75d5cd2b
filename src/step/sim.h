/* sim.h: a whole simulation = the model + what acts on it + how it is run and written.
 *
 * YfSim is what every command handler receives.  The step loop (run.c) reads it; the modules
 * that add physics (bc.c for supports and loads, joint.c for fracture, contact.c for contact)
 * keep their own state structs inside it and are called at fixed stages of the step.
 */
#ifndef YF_SIM_H
#define YF_SIM_H
#include <stdio.h>
#include "model.h"
#include "err.h"

/* Energies [J/m], accumulated or evaluated as stated. */
typedef struct {
  double kinetic;        /* sum m |v|^2 / 2 with half-step velocities (Y2D's definition) */
  double strain;         /* sum A_c/2 T:E without the viscous part                       */
  double external_work;  /* work of loads, gravity and prescribed motions, accumulated  */
  double damping;        /* dissipated by viscous and mass damping, accumulated         */
  double joint_dissipated;/* fracture (joint.c)                                           */
  double contact;        /* contact potential energy (contact.c)                         */
  double friction;       /* dissipated by friction (contact.c)                           */
} YfEnergy;

/* Time history: a factor phi(t) multiplying an amplitude. */
enum { YF_HIST_CONSTANT = 0, YF_HIST_RAMP, YF_HIST_TABLE, YF_HIST_SINE };
typedef struct {
  char name[YF_NAME_MAX];
  int kind;
  double t0, t1;        /* ramp: 0 before t0, linear to 1 at t1, 1 after; sine: period t0 */
  int npts;             /* table: points, interpolated linearly, end values held outside  */
  double *t, *v;
} YfHistory;

struct YfBc;      /* bc.c      */
struct YfOutput;  /* output.c  */
struct YfJoints;  /* joint.c   */
struct YfContact; /* contact.c */
struct YfY2dRun;  /* y2d_model.c: Y2D boundary-condition sets of a read_y2d scene */
struct YfRestart; /* restart.c: periodic restart files and the interrupt restart */
struct YfDeck;
struct YfSim;

/* Boundary-condition kinds: what adds external nodal forces at the gather stage or replaces the
 * free velocity update.  Native fixes and loads (bc.c) are one kind, registered by sim_init;
 * Y2D's BC sets (y2d_model.c) another, registered by the layer that reads a .y deck.  The run
 * loop calls every registered kind in registration order and knows none of them by name.
 * Any member may be NULL. */
typedef struct YfBcKind {
  const char *name;
  void (*loads)(struct YfSim *s);          /* gather stage: add external forces to node.f [N/m] */
  /* update stage: v_{n+1/2} of every node instead of the free update (at most one kind); par:
   * threaded; vxo, vyo: old velocities to keep (mass damping) or NULL; move: also x_{n+1} */
  void (*integrate)(struct YfSim *s, int par, double *vxo, double *vyo, int move);
  /* supports and prescribed motions around the update (native fixes, bc.c): prepare resolves
   * groups at the start of each run; held > 0 when the kind needs the old state of its nodes,
   * which save_old copies (without damping); constrain_velocities after the velocity update,
   * redo_positions after the free position update (without damping), constrain_positions last */
  void (*prepare)(struct YfSim *s);
  int (*held)(const struct YfSim *s);
  void (*save_old)(struct YfSim *s, double *xo, double *yo, double *vxo, double *vyo);
  void (*constrain_velocities)(struct YfSim *s, const double *vxo, const double *vyo);
  void (*redo_positions)(struct YfSim *s, const double *xo, const double *yo);
  void (*constrain_positions)(struct YfSim *s, const double *xo, const double *yo, const double *vxo,
                              const double *vyo);
  /* MPI (par.h): the nodes the kind acts on beyond the node-by-node update, marked in mark[]
   * (one per node): YF_BC_READS, its loads read their current state (every rank computes them);
   * YF_BC_SHARED, it also imposes their motion or sums work over them (every rank keeps them
   * whole and updates them).  NULL: none. */
  void (*mark_nodes)(struct YfSim *s, unsigned char *mark);
  void (*renumbered)(struct YfSim *s);     /* nodes and triangles renumbered (partition.c) */
  void (*free)(struct YfSim *s);
} YfBcKind;
#define YF_MAX_BC_KINDS 4
enum { YF_BC_READS = 1, YF_BC_SHARED = 2 };

/* Observers: what the step tells the layers above it (dumps, metrics, restarts) at fixed points
 * of the run loop, as event records.  The step never calls output; the front end registers the
 * observers (io_attach), and they are called in registration order. */
enum {
  YF_EV_RUN_BEGIN,  /* a run starts: the current state is a frame                            */
  YF_EV_STEP,       /* a step is done: frames, metrics samples and restarts that are due      */
  YF_EV_TOPOLOGY,   /* joints were inserted: nodes, triangles or slots changed                */
  YF_EV_INTERRUPT,  /* SIGINT/SIGTERM: write what is needed to continue, the run then stops   */
  YF_EV_RUN_END,    /* a run ended                                                             */
  YF_EV_FREE        /* the simulation is freed                                                 */
};
typedef struct YfEvent {
  int kind;                 /* YF_EV_*                                                        */
  const char *restart_path; /* INTERRUPT: the restart written ("" none), set by the observer  */
  char why[512];            /* INTERRUPT: why no restart could be written                     */
} YfEvent;
typedef void (*YfObserverFn)(struct YfSim *s, YfEvent *ev);

/* The default thermo columns, in the order the step prints them; a custom thermo line (the deck's
 * thermo_style custom) is printed by s->thermo_custom from their values (std NULL: the header). */
enum { YF_TH_STEP, YF_TH_TIME, YF_TH_KE, YF_TH_STRAIN, YF_TH_EXT, YF_TH_DISS, YF_TH_BALANCE, YF_TH_BROKEN,
       YF_TH_PAIRS, YF_TH_WALL, YF_TH_N };
typedef void (*YfThermoFn)(struct YfSim *s, const double *std);
#define YF_MAX_OBSERVERS 4

typedef struct YfSim {
  YfModel model;
  struct YfDeck *deck;

  /* time stepping */
  long step;            /* completed steps                                                  */
  double time;          /* [s]                                                              */
  double dt;            /* [s]; 0 until set                                                 */
  int dt_auto;          /* 1: dt = safety * stable limit, recomputed at each run            */
  double dt_safety;     /* safety factor of auto (default 0.5)                              */
  int dt_resume;        /* 1 after read_restart of a restart written within a run under timestep
                         * auto: that run goes on with the restart's dt (auto off), and auto comes
                         * back, with dt_resume_safety, when it ends, as the uninterrupted deck's
                         * next run recomputed its dt; a timestep command clears it             */
  double dt_resume_safety;
  int dt_pending;       /* 1: 'timestep auto' given and no run has computed its dt yet, so dt
                         * holds an older step (or 0) that the next run will not take        */
  double dt_limit;      /* last computed stable limit [s] and what limits it                */
  char dt_limiter[96];
  YfLoc dt_loc;         /* where the time step was set (for the 'above the limit' error)    */
  double gx, gy;        /* gravity [m/s^2]                                                  */
  double mass_damping;  /* alpha [1/s]: force -alpha m v (dynamic relaxation), 0 = off      */
  YfLoc damping_loc;    /* where it was set (for the 'alpha dt above 2' error)              */
  int ebal_mode;        /* energy_check: YF_EBAL_STOP (default), _WARN or _OFF (energy.h)    */
  double ebal_tol;      /* its tolerance, a fraction of the energy given (YF_EBAL_TOL)      */

  int nhist;
  YfHistory *hist;

  struct YfBc *bc;
  struct YfOutput *out;
  struct YfJoints *joints;
  struct YfContact *contact;
  struct YfY2dRun *y2d;   /* non-NULL after read_y2d (owned by y2d_model.c; the step never
                             reads it: Y2D's BC sets are a boundary-condition kind)          */
  const char *y2d_program; /* the .y deck run as `yfdem DECK.y` (NULL: a native deck runs): an
                             interrupt's advice is a native deck that continues it            */
  int dt_warn_only;       /* 1: a time step above the stable limit is a warning (Y2D decks
                             choose it by experience, ALGORITHMS.md 10), 0: an error          */
  const YfBcKind *bc_kind[YF_MAX_BC_KINDS];
  int nbc_kind;
  YfObserverFn observer[YF_MAX_OBSERVERS];
  int nobserver;
  long last_step;         /* `run` without N runs to this step (Y2D's MCSTEP), 0 = none   */
  struct YfRestart *restart; /* restart.c (NULL until a restart command)                  */
  int restored;           /* 1 after read_restart: a dump's first frame continues its series */
  int restored_between;   /* 1 when that restart was written between runs (write_restart, an
                             interrupt outside a run): the next run starts as the uninterrupted
                             deck's next run started, first frame and record row included      */

  YfEnergy energy;
  double joint_stored;  /* intact joints' stored energy [J/m], part of energy.strain (run_energies) */
  double gravity_work;  /* work of gravity on the nodes' displacements [J/m] (run_energies)      */
  double gravity_base;  /* ... of the gravities before a change between runs [J/m]: gravity_work is
                           this + sum m g . (x - x0) for the g of g_booked                          */
  double g_booked[2];   /* the gravity gravity_work was last computed with [m/s^2]                */
  int g_booked_set;     /* g_booked holds one (0: the next evaluation takes the current g)       */
  long thermo_every;    /* thermo line every N steps (0: only at start and end of a run)    */
  YfThermoFn thermo_custom; /* NULL: the default thermo line                               */
  double wall_s;        /* wall time spent in runs [s]                                      */
  double elem_steps;    /* triangles x steps done (for element_steps_per_s)                 */
  int threads;

  volatile int interrupted; /* set by SIGINT/SIGTERM; the run stops after the current step */
  long run_end_step;    /* last step of the current run command                            */
  int in_run;           /* 1 while a run command's steps are under way: a restart written then
                           continues within that run, one written otherwise begins a run     */
  int runs_begun;       /* run commands past their checks (RUN_BEGIN sent): the logs are
                           written only after one, so a deck that fails first leaves no file */

  /* options */
  char summary_path[1024];
  FILE *log;            /* -log FILE (also gets every message), NULL if none                */
  const char *log_name; /* its name, for the message when it cannot be written               */
  int log_failed;       /* errno of the log's failed write (said once; nothing more goes in) */
  int progress;         /* progress bar on stderr when it is a terminal                     */
} YfSim;

void sim_init(YfSim *s);
/* Register a boundary-condition kind / an observer (a second registration is ignored). */
void sim_add_bc_kind(YfSim *s, const YfBcKind *k);
void sim_observe(YfSim *s, YfObserverFn fn);
/* Hand an event record to every observer. */
void sim_notify(YfSim *s, YfEvent *ev);
/* Free everything the simulation holds and zero it (a second call frees nothing). */
void sim_free(YfSim *s);
int sim_find_history(const YfSim *s, const char *name);
double history_value(const YfHistory *h, double t);

/* Print to stdout and the log. */
void sim_printf(YfSim *s, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

#endif
