/* y2d_read.h: reading Munjiza Y2D input decks (.y files) into plain arrays.
 *
 * y2d_read() owns the Y2D token language of /work/shared/y2d/FORMAT.md (keys /YD/<GROUP>/<NAME>,
 * comments, $YDOIT/$YSTOP/$YINCL, 1D/2D/3D array syntaxes) and turns a deck into a YfY2d: one
 * field per Y2D key, arrays allocated at the deck's capacities (M... keys) and filled with
 * FORMAT.md's defaults, then overwritten by what the deck gives.  It does not build a YfModel:
 * the lead's read_y2d command turns a YfY2d into nodes, triangles, materials, joints and BC sets.
 *
 * Differences from the book-Y anchor, all on the side of refusing bad input early:
 *  - every problem is a deck error "FILE:LINE: error: /YD/GROUP/KEY: ..." (exit 1), never the
 *    anchor's silent "orderly" stop or a crash; FILE:LINE is the .y (or included) file's line;
 *  - an integer key given a real literal ("4e3") is an error instead of the anchor's misreading;
 *  - a count larger than the capacity, too few values, non-numeric values, arrays read before
 *    their capacity key, keys of the Y-Geo derivative, and the unchecked traps of FORMAT.md
 *    section 6 are reported (errors or warnings, see y2d_read.c);
 *  - $YINCL name is tried relative to the working directory (as the anchor) and, if not found
 *    there, relative to the directory of the file that contains the $YINCL;
 *  - one input section only: keys after $YDOIT are reported as unsupported.
 *
 * Layout of the arrays (all 0-based, as in Y2D):
 *   1D key of capacity M:            a[i],            i < M
 *   2D key, dim 1 (small) x dim 2:   a[i2*M1 + i1],   i.e. one row of M1 values per element/node
 *   D3PNFAC [2][MPNSET][MPNFACT]:    a[(c*MPNSET + s)*MPNFACT + p], c = 0 times, 1 factors
 * Integer arrays are int, integer scalars long, reals double.  Units are whatever the deck uses;
 * the reference decks are SI (m, kg, s, Pa), 2D per unit thickness.
 */
#ifndef YF_Y2D_READ_H
#define YF_Y2D_READ_H
#include "err.h"

/* Every key the reader knows, group by group in the order FORMAT.md lists them (which is the
 * order names are tried under the anchor's prefix rule: the first matching name wins).
 * Y2D_<group>_<NAME>; groups C=YDC, E=YDE, N=YDN, I=YDI, PE=YDPE, PJ=YDPJ, PM=YDPM, PN=YDPN,
 * O=YDO, B=YDB, S=YDS. */
enum {
  /* /YD/YDC/ */
  Y2D_C_MCSTEP, Y2D_C_NCSTEP, Y2D_C_DCSTEC, Y2D_C_DCTIME, Y2D_C_DCGRAY, Y2D_C_DCGRAX, Y2D_C_DCGRAZ,
  Y2D_C_DCSIZC, Y2D_C_DCSIZF, Y2D_C_DCSIZS, Y2D_C_DCSIZV, Y2D_C_ICOUTF, Y2D_C_ICOUTI, Y2D_C_ICOUTP,
  Y2D_C_ICOUTT, Y2D_C_ICSHTF, Y2D_C_IWFAST, Y2D_C_DCURELX, Y2D_C_INITER,
  /* /YD/YDE/ */
  Y2D_E_MELEM, Y2D_E_NELEM, Y2D_E_MELST, Y2D_E_NELST, Y2D_E_MELNO, Y2D_E_NELNO, Y2D_E_I2ELTO,
  Y2D_E_I1ELPR, Y2D_E_D2ELST, Y2D_E_I1ELCF, Y2D_E_I1ELBE, Y2D_E_D3TCS, Y2D_E_D1EMCT,
  /* /YD/YDN/ */
  Y2D_N_MNODIM, Y2D_N_NNODIM, Y2D_N_MNOPO, Y2D_N_NNOPO, Y2D_N_D2NCI, Y2D_N_D2NCC, Y2D_N_D2NVC,
  Y2D_N_I1NOPR, Y2D_N_I1NOBF, Y2D_N_D1NMCT, Y2D_N_D2NFC, Y2D_N_D2NFT,
  /* /YD/YDI/ */
  Y2D_I_MICOUP, Y2D_I_MISTATE, Y2D_I_DIEZON, Y2D_I_DIEDI, Y2D_I_IIECFF, Y2D_I_NICOUP, Y2D_I_D1IESL,
  Y2D_I_I1IECN, Y2D_I_I1IECT, Y2D_I_D2SLDIS,
  /* /YD/YDPE/ */
  Y2D_PE_MPROP, Y2D_PE_NPROP, Y2D_PE_I1PTYP, Y2D_PE_D1PERO, Y2D_PE_D1PELA, Y2D_PE_D1PEMU,
  Y2D_PE_D1PEKS, Y2D_PE_D1PEPE, Y2D_PE_D1PEPT, Y2D_PE_D1PEFR, Y2D_PE_D1PSEM, Y2D_PE_I1PSDE,
  Y2D_PE_I1PEFR, Y2D_PE_I1PEMB, Y2D_PE_I1PEJP, Y2D_PE_D1PECA, Y2D_PE_D1PECL, Y2D_PE_D1PERA,
  Y2D_PE_D1PEVI, Y2D_PE_I1PECN, Y2D_PE_I1PECP, Y2D_PE_I1PECT, Y2D_PE_I1PEMN, Y2D_PE_I1PNIB,
  /* /YD/YDPJ/ */
  Y2D_PJ_MPJSET, Y2D_PJ_NPJSET, Y2D_PJ_I1PTYP, Y2D_PJ_D1PJFT, Y2D_PJ_D1PJFS, Y2D_PJ_D1PJGF,
  Y2D_PJ_D1PJPE, Y2D_PJ_D1PJCO, Y2D_PJ_D1PJFR, Y2D_PJ_I1PSDE, Y2D_PJ_NINTPT,
  /* /YD/YDPM/ */
  Y2D_PM_MPMCOM, Y2D_PM_MPMCOL, Y2D_PM_I2PMSET, Y2D_PM_MPMROW, Y2D_PM_I2PMIJ, Y2D_PM_IAUTBN,
  /* /YD/YDPN/ */
  Y2D_PN_MPNSET, Y2D_PN_NPNSET, Y2D_PN_I1PNFX, Y2D_PN_I1PNFY, Y2D_PN_D1PNAX, Y2D_PN_D1PNAY,
  Y2D_PN_D1PNAP, Y2D_PN_D1PNAT, Y2D_PN_D1PNXX, Y2D_PN_D1PNXY, Y2D_PN_D1PNYX, Y2D_PN_D1PNYY,
  Y2D_PN_D1PNXZ, Y2D_PN_D1PNYZ, Y2D_PN_D1PNZX, Y2D_PN_D1PNZY, Y2D_PN_D1PNZZ, Y2D_PN_I1PNFZ,
  Y2D_PN_D1PNAZ, Y2D_PN_MPNFACT, Y2D_PN_NPNFACT, Y2D_PN_D3PNFAC, Y2D_PN_D1PNAF,
  /* /YD/YDO/ */
  Y2D_O_MOHYS, Y2D_O_NOHYS, Y2D_O_DOHYP, Y2D_O_I1OHYT, Y2D_O_D1OHYX, Y2D_O_D1OHYY, Y2D_O_D1OHYC,
  Y2D_O_D1OHYF, Y2D_O_D1OHYS, Y2D_O_D1OHYT,
  /* /YD/YDB/ boreholes (accepted, ignored) */
  Y2D_B_MBORH, Y2D_B_NBORH, Y2D_B_MBDIM, Y2D_B_NBDIM, Y2D_B_NBPAF, Y2D_B_D2BCA, Y2D_B_D2BCB,
  Y2D_B_D1BRAD, Y2D_B_D1BPAF, Y2D_B_D1BPTS, Y2D_B_D1BPTE, Y2D_B_D1BVDT, Y2D_B_D1BPRS,
  Y2D_B_DBLMAX, Y2D_B_DBBUF,
  /* /YD/YDS/ sources (accepted, ignored) */
  Y2D_S_MSOUR, Y2D_S_NSOUR, Y2D_S_MSDIM, Y2D_S_NSDIM, Y2D_S_NSPAF, Y2D_S_NSSAF, Y2D_S_D2SCS,
  Y2D_S_D1SPAF, Y2D_S_D1SSAF, Y2D_S_D1SPTS, Y2D_S_D1SPTE, Y2D_S_D1SVPR, Y2D_S_D1SPRS,
  Y2D_S_D1SSIR, Y2D_S_DSBUF,
  Y2D_NKEYS
};

/* Full name of a key, e.g. "/YD/YDC/MCSTEP" (for messages that name a key). */
const char *y2d_key_name(int key);

/* A run of lines holding values of one array key (see YfY2d.vline). */
typedef struct { int key, file, line, nlines; long m, per; } YfValueLines;

typedef struct {
  /* ---- bookkeeping ---- */
  char **files;            /* names of the deck and of included files (owned; YfLoc.file points here) */
  int nfiles;
  unsigned char given[Y2D_NKEYS]; /* 1 if the key was read                                 */
  YfLoc where[Y2D_NKEYS];  /* FILE:LINE of the (last) reading of each key                  */
  long nread[Y2D_NKEYS];   /* arrays: entries read along the long dimension (1D: n; 2D: n2;
                              D3PNFAC: table points n3); scalars: 1                        */
  int has_ydoit;           /* 1: the deck ends its (only) section with $YDOIT              */
  int ystop;               /* 1: reading stopped at a $YSTOP before any $YDOIT              */
  YfLoc end;               /* where reading stopped ($YDOIT, $YSTOP or end of file)        */
  /* Where the values of arrays are, for messages about one value (a negative density on the
   * line after its key): runs of lines of one key (value ordinals m, m+1... from file:line on,
   * per values a line over nlines lines, the last possibly longer); a few per key. */
  YfValueLines *vline;
  long nvline, capvline;
  unsigned char *prop_used; /* [nprop]: 1 if an element uses property p (set by the checks)     */
  unsigned char *pjset_used; /* [npjset]: 1 if an I2PMIJ row of used properties names set j, with
                                meshing (set by the checks; NULL without I2PMSET)               */

  /* ---- /YD/YDC/ control ---- */
  long mcstep;             /* MCSTEP: total steps (loop runs while step < MCSTEP)           */
  long ncstep;             /* NCSTEP: initial step counter                                  */
  double dcstec;           /* DCSTEC: time step [s]                                         */
  double dctime;           /* DCTIME: initial time [s]                                      */
  double dcgray;           /* DCGRAY: gravity along y [m/s^2] (signed)                      */
  double dcgrax, dcgraz;   /* DCGRAX, DCGRAZ: 3D only, ignored in 2D (warning if non-zero)  */
  double dcsizc, dcsizf, dcsizs, dcsizv; /* DCSIZC/F/S/V: coded-output scales (default 1)   */
  long icoutf;             /* ICOUTF: output every ICOUTF steps (<= 0 -> 10, as the anchor) */
  long icouti, icoutp, icoutt; /* ICOUTI (0), ICOUTP digits (4), ICOUTT (0)                 */
  long icshtf;             /* ICSHTF: progress line every ICSHTF steps (100)                */
  long iwfast;             /* IWFAST: 0 all triangles in contact, >0 only flagged ones (1)  */
  double dcurelx;          /* DCURELX: 3D relaxation (1), unused                            */
  long initer;             /* INITER: 3D (2), unused                                        */

  /* ---- /YD/YDE/ elements ---- */
  long melem, nelem;       /* MELEM capacity, NELEM input triangles                         */
  long melst, nelst;       /* MELST, NELST: element state rows                              */
  long melno, nelno;       /* MELNO (row stride of i2elto), NELNO (3)                       */
  int *i2elto;             /* I2ELTO [melem][melno]: node numbers, CCW; default -1           */
  int *i1elpr;             /* I1ELPR [melem]: element property 0..NPROP-1; default -1         */
  double *d2elst;          /* D2ELST [melem][melst]: state (damage); default 0               */

  /* ---- /YD/YDN/ nodes ---- */
  long mnodim, nnodim;     /* MNODIM, NNODIM: 2 (checked)                                   */
  long mnopo, nnopo;       /* MNOPO capacity, NNOPO input nodes                             */
  double *d2nci;           /* D2NCI [mnopo][2]: initial (reference) coordinates [m]; required */
  double *d2ncc;           /* D2NCC [mnopo][2]: current coordinates [m]; copy of D2NCI if absent */
  double *d2nvc;           /* D2NVC [mnopo][2]: initial velocity [m/s]; default 0            */
  int *i1nopr;             /* I1NOPR [mnopo]: BC set of each node 0..NPNSET-1; default -1    */
  int *i1nobf;             /* I1NOBF [mnopo]: boundary flag (1 = free surface); default 0    */

  /* ---- /YD/YDI/ interaction ---- */
  long micoup;             /* MICOUP: couple capacity; 0 = no contact                       */
  long mistate;            /* MISTATE: sliding rows (>= 6 with contact, checked)            */
  double diezon;           /* DIEZON: buffer zone [m]                                        */
  double diedi;            /* DIEDI: travel since last search [m] (1e15)                     */
  long iiecff, nicoup;     /* IIECFF (-2), NICOUP (0): restart data, stored only             */

  /* ---- /YD/YDPE/ element properties, arrays [mprop] ---- */
  long mprop, nprop;       /* MPROP, NPROP                                                  */
  int *pe_i1ptyp;          /* I1PTYP: 1 elastic, 2 rigid, 4 softening triangle; default -1   */
  double *d1pero;          /* D1PERO: density [kg/m^3]                                       */
  double *d1pela;          /* D1PELA: Lame lambda [Pa] (the anchor's law uses lambda/2)      */
  double *d1pemu;          /* D1PEMU: Lame mu [Pa]                                           */
  double *d1peks;          /* D1PEKS: viscous coefficient [Pa s]                              */
  double *d1pepe;          /* D1PEPE: normal contact penalty [Pa]                             */
  double *d1pept;          /* D1PEPT: tangential contact penalty [Pa]                         */
  double *d1pefr;          /* D1PEFR: Coulomb friction coefficient [-]                        */
  double *d1psem;          /* D1PSEM: max stretch of softening triangles [-]                  */
  int *pe_i1psde;          /* I1PSDE: state row of D2ELST (0)                                 */
  int *i1pefr;             /* I1PEFR: >0 softening triangles may fracture (-1)                */
  int *i1pemb;             /* I1PEMB: refinement boundary option (0)                          */
  int *i1pejp;             /* I1PEJP: joint set of softening triangles (-1)                   */

  /* ---- /YD/YDPJ/ joint property sets, arrays [mpjset] ---- */
  long mpjset, npjset;     /* MPJSET, NPJSET                                                */
  int *pj_i1ptyp;          /* I1PTYP: 3 = YTE2JOINTS; default -1                              */
  double *d1pjft;          /* D1PJFT: tensile strength f_t [Pa]                               */
  double *d1pjfs;          /* D1PJFS: shear strength f_s [Pa] (<= 0: cohesion used)           */
  double *d1pjgf;          /* D1PJGF: fracture energy G_f [J/m^2]                             */
  double *d1pjpe;          /* D1PJPE: joint penalty p [Pa]                                    */
  double *d1pjco;          /* D1PJCO: cohesion c [Pa] (0)                                     */
  double *d1pjfr;          /* D1PJFR: internal friction coefficient [-] (0)                   */
  int *pj_i1psde;          /* I1PSDE: state row (unused in 2D); default 0                     */
  long nintpt;             /* NINTPT: 3D joints (7)                                           */

  /* ---- /YD/YDPM/ meshing ---- */
  long mpmcom;             /* MPMCOM: number of meshing rows                                 */
  long mpmcol;             /* MPMCOL: columns per row (2 + max properties in a row)          */
  int *i2pmset;            /* I2PMSET [mpmcom][mpmcol]: k, code, p1..pk; default 0            */
  long mpmrow;             /* MPMROW: rows of I2PMIJ                                          */
  int *i2pmij;             /* I2PMIJ [mpmrow][3]: p_i, p_j, joint set; default 0              */
  long iautbn;             /* IAUTBN: 3D only                                                 */

  /* ---- /YD/YDPN/ boundary-condition sets, arrays [mpnset] ---- */
  long mpnset, npnset;     /* MPNSET, NPNSET                                                */
  int *i1pnfx, *i1pnfy;    /* I1PNFX/Y: 1 force, 2 acceleration, 3 velocity, else frozen (-1) */
  double *d1pnax, *d1pnay; /* D1PNAX/Y: amplitude [N/m | m/s^2 | m/s] in local x/y (1.0)     */
  double *d1pnap;          /* D1PNAP: edge pressure [N/m per m of edge = Pa] (0)              */
  double *d1pnat;          /* D1PNAT: edge shear traction [Pa] (0)                            */
  double *d1pnxx, *d1pnxy; /* D1PNXX, D1PNXY: local x axis (1, 0)                             */
  double *d1pnyx, *d1pnyy; /* D1PNYX, D1PNYY: local y axis (0, 1)                             */
  long mpnfact, npnfact;   /* MPNFACT, NPNFACT: points per time-factor table                 */
  double *d3pnfac;         /* D3PNFAC [2][mpnset][mpnfact]: times [s] then factors [-]; default 0.
                              Use y2d_fac_time()/y2d_fac_value() below.                       */
  int tables_on;           /* 1 if D3PNFAC given, NPNFACT > 0 and time 0 of set 0 != -1       */

  /* ---- /YD/YDO/ history output, arrays [mohys] ---- */
  long mohys, nohys;       /* MOHYS, NOHYS                                                    */
  double dohyp;            /* DOHYP: change threshold (0.05)                                  */
  int *i1ohyt;             /* I1OHYT: field code (1 sxx, 2 sxy, 3 syy, 7 |v|, 8 vx, 9 vy, 15 Ek,
                              18 Fx, 19 Fy); default 0                                        */
  double *d1ohyx, *d1ohyy; /* D1OHYX/Y: sampling point [m] (0)                                */
  double *d1ohyc, *d1ohyf; /* D1OHYC/F: time and value scales (default 1: not documented)      */
  double *d1ohys, *d1ohyt; /* D1OHYS/T: state (0)                                             */
  char *tok_scratch;       /* the reader's token buffer while it reads (freed by y2d_free too: a
                              deck error's exit hook, in the fuzzers and tests, leaves the reader) */
} YfY2d;

/* Read a .y deck.  path is opened as given (relative to the working directory); from is the
 * place of the command that asked for it (for the I/O error if it cannot be opened; may be NULL).
 * Exits through yf_deck_error (1) or yf_io_error (2) on any problem; warnings go to stderr.
 * On return every array of a key whose capacity is > 0 is allocated and holds defaults where the
 * deck gave nothing; D2NCC is a copy of D2NCI when not given.  Returns 0. */
int y2d_read(const char *path, YfY2d *out, const YfLoc *from);
/* The same, read as the Y2D program reads it (yfdem DECK.y): a deck that stops at $YSTOP before
 * any $YDOIT, or ends without one, computes nothing in Y2D (FORMAT.md 1.2): then returns 1 after
 * a warning, without checking the keys (a $YSTOP before the data is a quiet end), else 0. */
int y2d_read_program(const char *path, YfY2d *out, const YfLoc *from);
void y2d_free(YfY2d *y);
/* FILE:LINE of value m (in reading order; for 1D arrays entry m) of array key `key`, while the
 * deck's value lines are kept (until y2d_free_arrays). */
YfLoc y2d_value_loc(const YfY2d *y, int key, long m);
/* Free the arrays and the value lines only (set to NULL); scalars, given/where and the file names (which YfLoc
 * places of messages point at) stay valid until y2d_free. */
void y2d_free_arrays(YfY2d *y);
/* 1 if the file name ends in ".y". */
int y2d_is_y_file(const char *path);

/* Time table of BC set s: point p's time [s] and factor [-]. */
static inline double y2d_fac_time(const YfY2d *y, long s, long p) {
  return y->d3pnfac[(0 * y->mpnset + s) * y->mpnfact + p];
}
static inline double y2d_fac_value(const YfY2d *y, long s, long p) {
  return y->d3pnfac[(1 * y->mpnset + s) * y->mpnfact + p];
}

#endif
