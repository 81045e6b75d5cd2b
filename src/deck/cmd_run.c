/* cmd_run.c: the `run` deck command (a row of commands.def): reads its words and calls
 * run_steps (run.h).
 */
#include <stdlib.h>
#include <string.h>
#include "deck.h"
#include "run.h"

/* run N [upto] | run (to the last step of a Y2D deck read by read_y2d) */
void cmd_run(YfSim *s, const YfArgs *a) {
  arg_count(a, 0, 2);
  long n;
  if (a->n == 0) {
    if (s->last_step <= 0) arg_error(a, 0, "give the number of steps (run without N needs a read_y2d deck)");
    n = s->last_step - s->step;
    if (n < 0) n = 0;
  } else {
    n = arg_int(a, 0, "N", 0, 1000000000000000L); /* a .y deck's MCSTEP may pass 2^31 */
    if (a->n == 2) { /* upto: N is the step to reach (a deck continued from a restart) */
      static const char *const w[] = {"upto", NULL};
      arg_choice(a, 1, "run option", w);
      /* past the step to reach (as LAMMPS refuses it): a wrong restart file, or N meant as a count */
      if (n < s->step)
        arg_error(a, 0, "run %ld upto: the scene is at step %ld already, past it (is the restart the one meant? "
                  "'run N' without upto runs N more steps)", n, s->step);
      n -= s->step;
    }
  }
  /* the common deck mistakes, reported at the run line (run_steps has no deck place) */
  if (!s->model.tri.n) arg_error(a, -1, "the scene has no triangles (use mesh, triangle or read_y2d first)");
  if (!s->dt_auto && !(s->dt > 0)) arg_error(a, -1, "no time step set (use 'timestep DT' or 'timestep auto' before run)");
  run_steps(s, n);
}
