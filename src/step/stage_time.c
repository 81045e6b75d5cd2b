/* stage_time.c: the stage timers and the clock they read (stage_time.h). */
#include <time.h>
#include "stage_time.h"

const char *const yf_stage_names[YF_NSTAGE] = {"elements", "joints", "detection", "contact", "gather", "update", "output"};
double yf_stage_time[YF_NSTAGE];

double yf_now(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

double yf_cpu_now(void) {
  struct timespec ts;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}
