/* contact.h: contact between triangles in the scene: which triangles take part, when the broad
 * phase runs (Y2D's buffer travel rule), the candidate pairs with their friction memory, and the
 * contact force stage.  The pair kernel is contact_pair.c, the broad phase contact_search.c.
 *
 * Contract with run.c:
 *   contact_prepare(s)  in run_prepare after joints_insert and masses: participation and pairs
 *                       filters from the deck's contact commands; nothing when contact is off.
 *   contact_step(s)     each step after the joint forces and the gather: detection if due, then
 *                       the screen and the pair forces (parallel over fixed blocks of couples,
 *                       touching couples into a compact list in couple order), then added into
 *                       node.fx/fy in pair order (deterministic).  Accumulates contact energy
 *                       and frictional dissipation into s->energy.
 *   contact_node_stiffness  the contact penalty's share of the stable time step (below).
 *
 * Deck commands (one row `contact` in commands.def):
 *   contact pair G1 G2      triangles of group (or body) G1 against those of G2
 *   contact self G          triangles of G against each other (fragments of a fracturing body, a
 *                           body folding onto itself)
 *   contact off             no contact (forget every rule and pair)
 *   contact KEY VALUE ...   options, several per line:
 *     buffer D|auto         Y2D's DIEZON [m]: the pair list stays valid until the nodes have
 *                           travelled D/2 relative to each other; auto (default) = 0.3 x the
 *                           smallest edge of the participating triangles (the reference decks)
 *     joined keep|skip      pairs of triangles still joined by an intact joint: keep (default,
 *                           Y2D evaluates them; they give no force while they coincide) or skip
 *                           (cheaper; a joint that breaks triggers a search at the next step)
 *     surface boundary|all  which triangles take part: boundary (default, Y2D's IWFAST: at least
 *                           one node on a free boundary of the node topology, so every triangle
 *                           of a fracturing body) or all
 *     search travel|every   travel (default): search when the travel counter reaches the
 *                           buffer (ALGORITHMS.md 5); every: search at every step (checks)
 * Up to 64 pair/self rules; penalties and friction of a pair come from the two materials:
 * p_n = min(pen_n), p_t = min(pen_t), mu = min(friction), as Y2D does.  A material without
 * pen_n in a contact rule is a deck error at the contact command (or at run when the triangles
 * come later).  Without a contact command there is no contact work at all.
 *
 * Pairs: a couple (i, j), i < j triangle indices, is found when the discs around the centroids
 * overlap by less than the buffer (contact_search.h) and passes the filters: the rules (i in
 * one side and j in the other), no shared node (a body that cannot break never touches its own
 * neighbours; Y2D mode keeps them), and optionally the joined filter.  Y2D's buffer rule: the
 * travel counter grows by 2 dt sqrt(max |v|^2) over the participating nodes each step, the first
 * step always searches; couples are dropped at a search when |c_i - c_j| > r_i + r_j + buffer,
 * and by the force stage when neither direction touched and the smallest node-to-edge-line
 * distance exceeds 2 buffer.  The friction memory g of a couple that persists across a search
 * is carried over.  Known deviation: Y2D reuses freed couple slots without clearing their
 * friction memory (a new couple can inherit a stale g); here every new couple starts at g = 0.
 */
#ifndef YF_CONTACT_H
#define YF_CONTACT_H
#include <stddef.h>
#include "sim.h"

void contact_prepare(YfSim *s);
void contact_step(YfSim *s);
/* Warn (at loc) when participating bodies can press harder than the contact penalty can push
 * back: rho v^2 > pen_n, v the spread of the participating nodes' velocities (the most two can
 * close at), rho the densest and pen_n the lowest of the participating materials'.  Penalty contact stops a
 * body within a triangle's depth only below that (kinetic energy per volume rho v^2 / 2 against
 * the penalty's p / 2 at full depth); above it a block at 500 m/s passed through a fixed wall
 * four cells thick, "ok".  The run checks again after each contact search (speeds a run gains, a
 * body falling under gravity), with contact_check_impact_run. */
void contact_check_impact(YfSim *s, const YfLoc *loc);
/* The same within a run, after a search: on MPI ranks with the divided update, every rank calls it
 * (a collective) and the ranks' velocities are agreed. */
void contact_check_impact_run(YfSim *s);
/* The contact penalty's part of the stable time step (run_stable_dt combines it with the
 * triangles and joints at every node).  For every participating triangle e that can touch a
 * triangle of another body, or its own body's under a self rule (a fracturing body's fragments, a
 * body that folds onto itself), the stiffest
 * contact it can meet is a flat penetration of one of its edges: force per node
 * k = 1.5 p L_e / h_e (ALGORITHMS 6.3 with P = delta / h), L_e its longest edge, h_e = 2 A_e / L_e
 * its smallest height, p = min(its pen_n, the largest pen_n it can meet).  Each corner i of e gets
 * 2 k added to K[i] [Pa]: the Gershgorin row sum of the node pressed against an equal target node
 * (alone, a node of mass m is then stable for dt <= sqrt(2 m / k), the two-mass bound).  tof[i],
 * pof[i]: the triangle giving node i's largest share and its penalty (for the message), where
 * tof[i] < 0 on entry or a larger share is found.  Self-contact of a body that cannot break
 * counts too: it acts only when the body folds onto itself, but then at the full penalty (left
 * out, a U closing on itself blew up at the default safety).  Returns 0 without contact. */
int contact_node_stiffness(YfSim *s, double *K, int *tof, double *pof);
/* Live couples in the list (Y2D's ncouples). */
long contact_pairs(const YfSim *s);
/* The couple list's entries (dead ones too, until a compaction) this rank holds, and the whole
 * list's (MPI: each rank holds its own couples; both equal on one rank). */
void contact_held(const YfSim *s, long *mine, long *whole);
void contact_free(YfSim *s);
/* MPI: each node's contact force lives on its owner; this makes it whole on every rank for a
 * reader (a collective: every rank calls it at the same point; par_need_all does). */
void contact_par_gather(YfSim *s);
/* MPI: each couple, with its friction memory, lives on the rank that evaluates it (docs/SCALING.md
 * section 1); this gathers the whole list for contact_state_save (a collective: every rank calls
 * it, after par_need_all, before a restart is written; a no-op on one rank). */
void contact_par_whole(YfSim *s);
/* MPI, re-balancing (par_balance): each rank's range of the one-rank list (size + 1 ints; NULL
 * unless the list is laid out by ranks); this rank's couples counted by the block of g triangles
 * of their lower triangle (added into cnt); and, once the triangle ranges changed, each couple
 * with its state and friction memory to the new owner of its lower triangle and the node contact
 * forces to their nodes' new owners (nold: the node ranges before; a collective). */
const int *contact_rank_lo(const YfSim *s);
void contact_count_by_block(const YfSim *s, int g, int *cnt);
void contact_rehome(YfSim *s, const int *nold);

/* ---- what the deck's contact command sets (deck/cmd_contact.c) ---- */
#define YF_CONTACT_MAX_RULES 64
/* A rule between groups g1 and g2 (g1 == g2: self); the same pair again is no new rule;
 * -1 when there are already YF_CONTACT_MAX_RULES rules. */
int contact_add_rule(YfSim *s, int g1, int g2, const YfLoc *loc);
/* contact off: no contact from now on (contact energy 0). */
void contact_off(YfSim *s);
/* Options: buffer [m] (value < 0: auto = 0.3 x smallest edge), joined (0 keep, 1 skip),
 * surface (0 boundary, 1 all), search (0 travel, 1 every step). */
enum { YF_CONTACT_BUFFER, YF_CONTACT_JOINED, YF_CONTACT_SURFACE, YF_CONTACT_SEARCH };
void contact_set_option(YfSim *s, int key, double value);

/* ---- API for read_y2d (y2d_model.c) and tests ---- */
/* Y2D contact (MICOUP > 0): every participating triangle against every other (one rule over the
 * whole scene, including triangles of the same body and couples that share a node, as Y2D
 * evaluates them), buffer = DIEZON [m] (>= 0; 0 searches every step), joined keep, search
 * travel.  Penalties come from the materials' pen_n, pen_t, friction (zero penalties are
 * allowed here, as in Y2D: such couples give no force).  Participation is every triangle until
 * contact_set_participation says otherwise. */
void contact_enable_all(YfSim *s, double buffer);
/* Which triangles take part (IWFAST > 0: triangles with a node whose I1NOBF is 1; the copies
 * made by joint meshing are flagged).  tri_flag[t] != 0 for triangle index t = 0..n-1
 * (copied; triangles added later do not take part); NULL = every triangle (IWFAST = 0). */
void contact_set_participation(YfSim *s, const unsigned char *tri_flag, int n);
/* The first setup's travel counter starts at d [m] (>= 0) instead of searching at the first step
 * (Y2D's DIEDI without joint meshing): the first search is made when the travel reaches the
 * buffer.  Later setups search at their first step, as by default. */
void contact_set_first_travel(YfSim *s, double d);
/* Keep couples of triangles that share a node (1, Y2D) or drop them (0, native default). */
void contact_set_keep_shared(YfSim *s, int keep);
/* Fewer pairs than this: the force stage runs on one thread (default 2048); also lowers the
 * search's own threshold when smaller.  Tests set 0 to force the parallel paths. */
void contact_set_par_min(YfSim *s, int n);
/* The triangles were renumbered (partition.c): tnew[old] = new for old < n.  Moves the
 * participation flags of the API with their triangles and makes the next prepare start over
 * (couples hold triangle indices: the renumbering happens before the first search only). */
void contact_renumber_tris(YfSim *s, const int *tnew, int n);

/* ---- export (write_y2d, y2d_write.c) ---- */
typedef struct {
  int nrule;         /* contact rules (0: contact off)                                   */
  int all_pairs;     /* 1: one rule already takes every pair of triangles (Y2D's contact)  */
  int surface_all, joined_skip, search_every; /* the deck's contact options               */
  double buffer;     /* buffer in use [m] (after contact_prepare)                          */
} YfContactExport;
/* The contact settings of the scene; returns 0 when contact is off. */
int contact_export(const YfSim *s, YfContactExport *e);

/* ---- diagnostics (output, tests) ---- */
/* Contact force of the last evaluated step per node (2 per node, fx fy) [N/m], zeros before the
 * first step evaluated since contact_prepare, NULL when contact is off or not prepared.  h5 dumps
 * write it as the node field `fc`, in every frame (ParaView's reader lists a field only if every
 * frame has it: the frame at the start of the first run, before any contact step, has zeros). */
const double *contact_node_forces(const YfSim *s);
/* Searches made so far. */
long contact_searches(const YfSim *s);
/* Triangles taking part (after contact_prepare). */
int contact_participants(const YfSim *s);
/* Buffer in use [m] (after contact_prepare). */
double contact_buffer(const YfSim *s);

/* ---- restart (restart.c) ---- */
/* The dynamic contact state: what the next step needs besides the deck's settings. */
typedef struct {
  int n;                 /* couples in the list (live and dead)                    */
  int *ij;               /* 2 per couple: triangle indices i < j                   */
  double *g;             /* YF_PAIR_NG per couple (contact_search.h): friction memory,
                            the 6 sliding values then the 6 forces of the last step
                            (save: a copy the contact state owns until the next save) */
  unsigned char *alive;  /* per couple: 0 = dropped since the last search          */
  int nlive, ndead;
  double travel;         /* travel counter of the search trigger [m]               */
  long nsearch, broken_seen;
  int force_search;
  int nn;                /* nodes of fcn                                           */
  double *fcn;           /* 2 per node: contact force of the last step [N/m]       */
  int fcn_valid;
  double spring;         /* energy held by the Coulomb springs after the last step [J/m] */
  int has_spring;        /* 0: not known (an older restart): load computes it from g      */
} YfContactState;
/* 1 when contact is on and prepared (there is a state to save), 0 otherwise. */
int contact_has_state(const YfSim *s);
/* Pointers into the live state (no copy; valid until the next step; under MPI, after
 * contact_par_whole).  Returns 0 when contact is off or not prepared (nothing to save), 1
 * otherwise. */
int contact_state_save(const YfSim *s, YfContactState *st);
/* Copy a saved state into a prepared contact (after contact_prepare for the same scene):
 * couple list, friction memory, node contact forces, counters.  Returns 0,
 * or -1 when contact is off here. */
int contact_state_load(YfSim *s, const YfContactState *st);

#endif
