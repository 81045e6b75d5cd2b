/* h5quiet.c: HDF5 opened once with its error printing off (h5quiet.h): HDF5 prints its error
 * stack by default, and yfdem reports errors itself (dumps and restarts). */
#include <hdf5.h>
#include "h5quiet.h"

void yf_h5_quiet(void) {
  static int done;
  if (!done) {
    H5open();
    H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
    done = 1;
  }
}
