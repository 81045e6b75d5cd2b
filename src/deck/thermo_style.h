/* thermo_style.h: what a deck asks to see of a run, LAMMPS style: custom thermo columns
 * (thermo_style custom, through the step's s->thermo_custom hook) and CSV records of chosen
 * quantities every N steps (record, like LAMMPS's fix print, an observer of the run loop).
 * The commands themselves are rows of commands.def (cmd_thermo_style, cmd_record). */
#ifndef YF_THERMO_STYLE_H
#define YF_THERMO_STYLE_H
#include "sim.h"

#endif
