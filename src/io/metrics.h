/* metrics.h: quantitative crack measurements of a run (the seed paper's questions, answered in
 * numbers instead of pictures).
 *
 * metrics.c owns the settings of the `metrics` deck command (its words: deck/cmd_metrics.c), a
 * cheap per-step hook that tracks what can only be
 * seen during the run (peak tensile stress, the moment the body first falls apart, a time series
 * of energies and crack growth), and the end-of-run keys it adds to the -summary JSON:
 *   symmetry                 fraction of broken joints whose mirror image is broken too (null:
 *                            no broken joint or no `metrics mirror`)
 *   midspan_crack_time       first mode I break inside the `metrics midspan` region (or null)
 *   midspan_crack            {step, time, x, y} of that break (or null)
 *   crack_length_by_region   {NAME: {I, II, mixed, total, inclined, vertical, horizontal, count}}
 *   crack_orientation        {vertical, horizontal, inclined} lengths over the whole body [m]
 *   crack_orientation_at_first_fragment   the same, counting breaks up to first_fragment_time
 *   first_fragment_time      when the measured body first became two pieces (or null)
 *   body_fragments           {count, list: [{area, x0, y0, x, y, vx, vy}, ...] largest first}
 *   peak_stress              {value, time, step, x, y, tri}: the largest max principal stress
 *                            of the body's triangles over the run [Pa] (x, y: initial centroid)
 *   stress_first_above       {threshold, value, time, step, x, y, tri}: the first triangle whose
 *                            max principal stress reached the threshold (or null)
 * Positions of cracks are the joints' midpoints in the initial configuration, so a crack is
 * matched to its mirror image however far the pieces have moved.  Orientation: a joint within
 * 20 degrees of the x axis is horizontal, within 20 degrees of the y axis vertical, else inclined.
 *
 * Deck command (one keyword per line, rows in commands.def):
 *   metrics body BODY                   measure this body (default: every fracturing body)
 *   metrics mirror x|y C                symmetry about the line x = C (or y = C) [m]
 *   metrics region NAME R1 [R2 ...]     crack length inside the union of regions R1, R2, ...
 *   metrics midspan R                   region of the midspan crack (midspan_crack_time)
 *   metrics peak_stress on|off [threshold S]   track the max principal stress (each step)
 *   metrics log FILE [every N]          CSV time series (step, time, energies, broken, crack
 *                                       length by mode, fragments, sigma1_max), default N = 100
 */
#ifndef YF_METRICS_H
#define YF_METRICS_H
#include "sim.h"

/* Settings, one per keyword of the command (any of them turns the measurements on). */
#define YF_METRICS_REGIONS 16     /* metrics regions */
#define YF_METRICS_REG_SHAPES 8   /* regions in the union of one metrics region */
#define YF_METRICS_PATH_MAX 1024  /* bytes of the log's path, with its terminating 0 */
void metrics_set_body(int b);                   /* body index, -1: every fracturing body */
void metrics_set_mirror(int axis, double c);   /* 1: the line x = c [m], 2: y = c */
/* 1 when region name is new and the table of metrics regions is full. */
int metrics_region_full(const char *name);
/* (Re)define metrics region name as the union of the nr (<= YF_METRICS_REG_SHAPES) regions r. */
void metrics_set_region(const char *name, const int *r, int nr);
void metrics_set_midspan(int r);                /* region index */
void metrics_set_peak(int on);                  /* track the max principal stress */
void metrics_set_threshold(double s);           /* stress_first_above threshold [Pa] */
void metrics_set_until(double t);               /* peak_stress over times <= t [s] */
void metrics_set_log(const char *path, long every); /* every <= 0: keep the period (default 100) */
/* The log so far, written whole now (a restart is about to be written: after a SIGKILL the log
 * then holds every row the continuation keeps; it was written only at the end, and was lost). */
int metrics_flush_log(YfSim *s, char *err, size_t nerr);

/* After every completed step (run.c); a few compares when nothing is due. */
void metrics_step(YfSim *s);
/* Summary keys and the log file (run_summary_update); never exits. */
void metrics_summary(YfSim *s);
/* Forget everything (sim_free). */
void metrics_reset(void);
/* What a restart carries of the metrics (restart.c): the events before it that the summary reports
 * (peak_stress, stress_first_above, first_fragment_time) and the broken-joint count they were
 * last checked at.  A continued run reported the first step after the restart instead. */
enum { METRICS_STATE_ND = 5, METRICS_STATE_NL = 6 };
void metrics_state_save(double d[METRICS_STATE_ND], long l[METRICS_STATE_NL]);
void metrics_state_load(const double d[METRICS_STATE_ND], const long l[METRICS_STATE_NL]);

#endif
