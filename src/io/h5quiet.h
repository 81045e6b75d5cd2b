/* h5quiet.h: HDF5 set up once for the io layer's writers and readers (dumps, restarts). */
#ifndef YF_H5QUIET_H
#define YF_H5QUIET_H

/* Silence HDF5's own error printing (once); yfdem reports HDF5 errors itself. */
void yf_h5_quiet(void);

#endif
