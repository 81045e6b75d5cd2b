/* parfor.c: the count of loops that asked for the team (parfor.h). */
#include "parfor.h"

unsigned long yf_team_wanted;
