/* report.h: what a deck asks to see of a run, LAMMPS style: custom thermo columns (thermo_style
 * custom) and CSV records of chosen quantities every N steps (record, like LAMMPS's fix print). */
#ifndef YF_REPORT_H
#define YF_REPORT_H
#include "sim.h"

/* The default thermo columns, in the order run.c prints them (their values: std[]). */
enum { YF_TH_STEP, YF_TH_TIME, YF_TH_KE, YF_TH_STRAIN, YF_TH_EXT, YF_TH_DISS, YF_TH_BALANCE, YF_TH_BROKEN,
       YF_TH_PAIRS, YF_TH_WALL, YF_TH_N };

/* 1 when thermo_style custom is in force (run.c then prints through the two functions below). */
int report_custom(void);
void report_thermo_header(YfSim *s);
void report_thermo_line(YfSim *s, const double *std);
/* A record line of every record due at this step (run start and every N steps); cheap when none. */
void report_step(YfSim *s, int force);
/* Close the record files (end of the program; also the error path). */
void report_close(void);
void report_reset(void);

#endif
