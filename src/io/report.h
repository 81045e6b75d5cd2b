/* report.h: what the io layer does for a run: the observer of the run loop's events (dumps,
 * metrics, restarts) and the summary keys of the loop and of fracture.
 *
 * io_attach() registers the observer (sim.h) once: main calls it (frames, metrics and the
 * interrupt restart of every run), and so do the commands that create io state (dump, metrics,
 * restart, read_restart), for a simulation driven without main (tests).
 */
#ifndef YF_REPORT_H
#define YF_REPORT_H
#include "sim.h"

void io_attach(YfSim *s);

/* Fill the summary's counts and the loop's extra keys (also on the error path). */
void run_summary_update(YfSim *s);

/* At the end of a run: summary keys (crack_length, fragments, first_break...), fracture_log. */
void joints_summary(YfSim *s);

#endif
