/* y2d_read.c: the Y2D (.y) deck reader (see y2d_read.h and /work/shared/y2d/FORMAT.md).
 *
 * The reader is table-driven: keydefs[] holds one row per Y2D key (group, name, type, where it
 * is stored in YfY2d, which capacity keys size its dimensions, default, flags).  The token loop
 * reproduces the anchor's lexical rules (whitespace tokens, prefix-matched names, comments whose
 * terminator must be its own token, $YDOIT/$YSTOP/$YINCL) but refuses everything the anchor
 * would misread or silently drop.  After the token stream ends, check_deck() turns the anchor's
 * Yck checks and the unchecked traps of FORMAT.md section 6 into errors or warnings; it runs
 * once, so the per-step code of the engine never has to validate Y2D input again.
 *
 * Choices where FORMAT.md leaves room (documented here so that messages can be trusted):
 *  - a comment may hold at most 100 tokens after its opening token, the terminator included;
 *  - $YINCL name: tried as given (relative to the working directory, as the anchor), then
 *    relative to the directory of the file holding the $YINCL; nesting depth < 10 files;
 *  - a 2D array code other than 12 is read as 21 (the anchor's rule) with a warning unless 21;
 *    a 3D code must be a permutation of 123;
 *  - keys after $YDOIT (other than $YSTOP and comments) are an error: one section only;
 *  - the last token of a file without a trailing newline is read (the anchor loses it), with
 *    a warning.
 */
#include <ctype.h>
#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdio_ext.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include "edgesort.h"
#include "err.h"
#include "memcap.h"
#include "model.h"
#include "y2d_read.h"
#include "utf8name.h"

/* ------------------------------------------------------------------ key table */

enum { KI, KR, KI1, KR1, KI2, KR2, KR3 };
enum {
  F_SIZE = 1,     /* integer that must be >= 0 (capacities, counts, steps)                  */
  F_NONNEG = 2,   /* real that must be >= 0 (the anchor: "illegitimate parameter")           */
  F_RESTART = 4,  /* restart/scratch data: parsed, dropped, warning                          */
  F_3D = 8,       /* 3D only: parsed, dropped (if not stored), warning                        */
  F_UNUSED = 16,  /* read and unused by the anchor: parsed, dropped, no warning              */
  F_BORE = 32,    /* boreholes and sources: parsed, dropped, one warning                     */
  F_RANGE = 64    /* node coordinates and velocities: within +-YF_RANGE_MAX, checked as read   */
};
#define NOFF ((size_t)-1)
#define CAPF(n) (-(100 + (n))) /* a fixed dimension size n                                   */
#define NOCAP (-1)             /* dimension size not checked                                   */

typedef struct {
  const char *group; /* "YDC"                                              */
  const char *name;  /* "MCSTEP"                                           */
  const char *full;  /* "/YD/YDC/MCSTEP"                                   */
  int match;         /* characters compared by the prefix rule (0: whole name) */
  int type;
  size_t off;        /* offsetof the field in YfY2d (long/double or int* / double*), NOFF: dropped */
  int cap[3];        /* dimension sizes: key id, CAPF(n) or NOCAP          */
  double def;        /* default value (scalars and every array entry)      */
  int flags;
  int after;         /* key that must be read earlier (-1 none); arrays also need their cap keys */
} KeyDef;

#define OFF(f) offsetof(YfY2d, f)
#define K(G, GS, NM, MATCH, T, OF, C1, C2, C3, DEF, FL, AFTER)                                     \
  [Y2D_##G##_##NM] = {GS, #NM, "/YD/" GS "/" #NM, MATCH, T, OF, {C1, C2, C3}, DEF, FL, AFTER}
#define KC(NM, T, OF, DEF, FL) K(C, "YDC", NM, 0, T, OF, NOCAP, NOCAP, NOCAP, DEF, FL, -1)
#define KE(NM, T, OF, C1, C2, DEF, FL) K(E, "YDE", NM, 0, T, OF, C1, C2, NOCAP, DEF, FL, Y2D_E_MELEM)
#define KN(NM, T, OF, C1, C2, DEF, FL) K(N, "YDN", NM, 0, T, OF, C1, C2, NOCAP, DEF, FL, -1)
#define KI_(NM, T, OF, C1, C2, DEF, FL) K(I, "YDI", NM, 0, T, OF, C1, C2, NOCAP, DEF, FL, -1)
#define KPE(NM, T, OF, DEF, FL) K(PE, "YDPE", NM, 0, T, OF, Y2D_PE_MPROP, NOCAP, NOCAP, DEF, FL, -1)
#define KPJ(NM, T, OF, DEF, FL) K(PJ, "YDPJ", NM, 0, T, OF, Y2D_PJ_MPJSET, NOCAP, NOCAP, DEF, FL, -1)
#define KPN(NM, T, OF, DEF, FL) K(PN, "YDPN", NM, 0, T, OF, Y2D_PN_MPNSET, NOCAP, NOCAP, DEF, FL, -1)
#define KO(NM, T, OF, DEF, FL) K(O, "YDO", NM, 0, T, OF, Y2D_O_MOHYS, NOCAP, NOCAP, DEF, FL, -1)
#define KB(NM, T) K(B, "YDB", NM, 0, T, NOFF, NOCAP, NOCAP, NOCAP, 0, F_BORE, -1)
#define KS(NM, T) K(S, "YDS", NM, 0, T, NOFF, NOCAP, NOCAP, NOCAP, 0, F_BORE, -1)

static const KeyDef keydefs[Y2D_NKEYS] = {
  KC(MCSTEP, KI, OFF(mcstep), 0, F_SIZE),
  KC(NCSTEP, KI, OFF(ncstep), 0, F_SIZE),
  KC(DCSTEC, KR, OFF(dcstec), 0, F_NONNEG),
  KC(DCTIME, KR, OFF(dctime), 0, 0),
  KC(DCGRAY, KR, OFF(dcgray), 0, 0),
  KC(DCGRAX, KR, OFF(dcgrax), 0, 0),
  KC(DCGRAZ, KR, OFF(dcgraz), 0, 0),
  KC(DCSIZC, KR, OFF(dcsizc), 1, F_NONNEG),
  KC(DCSIZF, KR, OFF(dcsizf), 1, F_NONNEG),
  KC(DCSIZS, KR, OFF(dcsizs), 1, F_NONNEG),
  KC(DCSIZV, KR, OFF(dcsizv), 1, F_NONNEG),
  KC(ICOUTF, KI, OFF(icoutf), 10, 0),
  KC(ICOUTI, KI, OFF(icouti), 0, 0),
  KC(ICOUTP, KI, OFF(icoutp), 4, 0),
  KC(ICOUTT, KI, OFF(icoutt), 0, 0),
  KC(ICSHTF, KI, OFF(icshtf), 100, 0),
  KC(IWFAST, KI, OFF(iwfast), 1, 0),
  KC(DCURELX, KR, OFF(dcurelx), 1, 0),
  KC(INITER, KI, OFF(initer), 2, 0),

  K(E, "YDE", MELEM, 0, KI, OFF(melem), NOCAP, NOCAP, NOCAP, 0, F_SIZE, -1),
  K(E, "YDE", NELEM, 0, KI, OFF(nelem), NOCAP, NOCAP, NOCAP, 0, F_SIZE, -1),
  KE(MELST, KI, OFF(melst), NOCAP, NOCAP, 0, F_SIZE),
  K(E, "YDE", NELST, 0, KI, OFF(nelst), NOCAP, NOCAP, NOCAP, 0, F_SIZE, -1),
  K(E, "YDE", MELNO, 0, KI, OFF(melno), NOCAP, NOCAP, NOCAP, 0, F_SIZE, -1),
  K(E, "YDE", NELNO, 0, KI, OFF(nelno), NOCAP, NOCAP, NOCAP, 0, F_SIZE, -1),
  KE(I2ELTO, KI2, OFF(i2elto), Y2D_E_MELNO, Y2D_E_MELEM, -1, 0),
  KE(I1ELPR, KI1, OFF(i1elpr), Y2D_E_MELEM, NOCAP, -1, 0),
  KE(D2ELST, KR2, OFF(d2elst), Y2D_E_MELST, Y2D_E_MELEM, 0, 0),
  KE(I1ELCF, KI1, NOFF, Y2D_E_MELEM, NOCAP, -1, F_RESTART),
  KE(I1ELBE, KI1, NOFF, Y2D_E_MELEM, NOCAP, 0, F_RESTART),
  KE(D3TCS, KR3, NOFF, NOCAP, NOCAP, 0, F_RESTART),
  KE(D1EMCT, KR1, NOFF, Y2D_E_MELEM, NOCAP, 0, F_RESTART),

  /* MNODIM/NNODIM: the anchor compares their first 5 characters only */
  K(N, "YDN", MNODIM, 5, KI, OFF(mnodim), NOCAP, NOCAP, NOCAP, 0, F_SIZE, -1),
  K(N, "YDN", NNODIM, 5, KI, OFF(nnodim), NOCAP, NOCAP, NOCAP, 0, F_SIZE, -1),
  K(N, "YDN", MNOPO, 0, KI, OFF(mnopo), NOCAP, NOCAP, NOCAP, 0, F_SIZE, Y2D_N_MNODIM),
  KN(NNOPO, KI, OFF(nnopo), NOCAP, NOCAP, 0, F_SIZE),
  KN(D2NCI, KR2, OFF(d2nci), Y2D_N_MNODIM, Y2D_N_MNOPO, 0, F_RANGE),
  KN(D2NCC, KR2, OFF(d2ncc), Y2D_N_MNODIM, Y2D_N_MNOPO, 0, F_RANGE),
  KN(D2NVC, KR2, OFF(d2nvc), Y2D_N_MNODIM, Y2D_N_MNOPO, 0, F_RANGE),
  KN(I1NOPR, KI1, OFF(i1nopr), Y2D_N_MNOPO, NOCAP, -1, 0),
  KN(I1NOBF, KI1, OFF(i1nobf), Y2D_N_MNOPO, NOCAP, 0, 0),
  KN(D1NMCT, KR1, NOFF, Y2D_N_MNOPO, NOCAP, 0, F_RESTART),
  KN(D2NFC, KR2, NOFF, Y2D_N_MNODIM, Y2D_N_MNOPO, 0, F_RESTART),
  KN(D2NFT, KR2, NOFF, Y2D_N_MNODIM, Y2D_N_MNOPO, 0, F_RESTART),

  KI_(MICOUP, KI, OFF(micoup), NOCAP, NOCAP, 0, F_SIZE),
  K(I, "YDI", MISTATE, 0, KI, OFF(mistate), NOCAP, NOCAP, NOCAP, 0, F_SIZE, Y2D_I_MICOUP),
  KI_(DIEZON, KR, OFF(diezon), NOCAP, NOCAP, 0, F_NONNEG),
  KI_(DIEDI, KR, OFF(diedi), NOCAP, NOCAP, 1e15, 0),
  KI_(IIECFF, KI, OFF(iiecff), NOCAP, NOCAP, -2, 0),
  KI_(NICOUP, KI, OFF(nicoup), NOCAP, NOCAP, 0, F_SIZE),
  KI_(D1IESL, KR1, NOFF, Y2D_I_MICOUP, NOCAP, 0, F_RESTART),
  KI_(I1IECN, KI1, NOFF, Y2D_I_MICOUP, NOCAP, 0, F_RESTART),
  KI_(I1IECT, KI1, NOFF, Y2D_I_MICOUP, NOCAP, 0, F_RESTART),
  KI_(D2SLDIS, KR2, NOFF, Y2D_I_MISTATE, Y2D_I_MICOUP, 0, F_RESTART),

  K(PE, "YDPE", MPROP, 0, KI, OFF(mprop), NOCAP, NOCAP, NOCAP, 0, F_SIZE, -1),
  K(PE, "YDPE", NPROP, 0, KI, OFF(nprop), NOCAP, NOCAP, NOCAP, 0, F_SIZE, -1),
  KPE(I1PTYP, KI1, OFF(pe_i1ptyp), -1, 0),
  KPE(D1PERO, KR1, OFF(d1pero), 0, 0),
  KPE(D1PELA, KR1, OFF(d1pela), 0, 0),
  KPE(D1PEMU, KR1, OFF(d1pemu), 0, 0),
  KPE(D1PEKS, KR1, OFF(d1peks), 0, 0),
  KPE(D1PEPE, KR1, OFF(d1pepe), 0, 0),
  KPE(D1PEPT, KR1, OFF(d1pept), 0, 0),
  KPE(D1PEFR, KR1, OFF(d1pefr), 0, 0),
  KPE(D1PSEM, KR1, OFF(d1psem), 0, 0),
  KPE(I1PSDE, KI1, OFF(pe_i1psde), 0, 0),
  KPE(I1PEFR, KI1, OFF(i1pefr), -1, 0),
  KPE(I1PEMB, KI1, OFF(i1pemb), 0, 0),
  KPE(I1PEJP, KI1, OFF(i1pejp), -1, 0),
  KPE(D1PECA, KR1, NOFF, 0, F_UNUSED),
  KPE(D1PECL, KR1, NOFF, 0, F_UNUSED),
  KPE(D1PERA, KR1, NOFF, 0, F_UNUSED),
  KPE(D1PEVI, KR1, NOFF, 0, F_UNUSED),
  KPE(I1PECN, KI1, NOFF, 0, F_UNUSED),
  KPE(I1PECP, KI1, NOFF, 0, F_UNUSED),
  KPE(I1PECT, KI1, NOFF, 0, F_UNUSED),
  KPE(I1PEMN, KI1, NOFF, 0, F_UNUSED),
  KPE(I1PNIB, KI1, NOFF, 0, F_UNUSED),

  K(PJ, "YDPJ", MPJSET, 0, KI, OFF(mpjset), NOCAP, NOCAP, NOCAP, 0, F_SIZE, -1),
  K(PJ, "YDPJ", NPJSET, 0, KI, OFF(npjset), NOCAP, NOCAP, NOCAP, 0, F_SIZE, -1),
  KPJ(I1PTYP, KI1, OFF(pj_i1ptyp), -1, 0),
  KPJ(D1PJFT, KR1, OFF(d1pjft), 0, 0),
  KPJ(D1PJFS, KR1, OFF(d1pjfs), 0, 0),
  KPJ(D1PJGF, KR1, OFF(d1pjgf), 0, 0),
  KPJ(D1PJPE, KR1, OFF(d1pjpe), 0, 0),
  KPJ(D1PJCO, KR1, OFF(d1pjco), 0, 0),
  KPJ(D1PJFR, KR1, OFF(d1pjfr), 0, 0),
  KPJ(I1PSDE, KI1, OFF(pj_i1psde), 0, 0),
  K(PJ, "YDPJ", NINTPT, 0, KI, OFF(nintpt), NOCAP, NOCAP, NOCAP, 7, F_3D, -1),

  K(PM, "YDPM", MPMCOM, 0, KI, OFF(mpmcom), NOCAP, NOCAP, NOCAP, 0, F_SIZE, -1),
  K(PM, "YDPM", MPMCOL, 0, KI, OFF(mpmcol), NOCAP, NOCAP, NOCAP, 0, F_SIZE, -1),
  K(PM, "YDPM", I2PMSET, 0, KI2, OFF(i2pmset), Y2D_PM_MPMCOL, Y2D_PM_MPMCOM, NOCAP, 0, 0, -1),
  K(PM, "YDPM", MPMROW, 0, KI, OFF(mpmrow), NOCAP, NOCAP, NOCAP, 0, F_SIZE, -1),
  K(PM, "YDPM", I2PMIJ, 0, KI2, OFF(i2pmij), CAPF(3), Y2D_PM_MPMROW, NOCAP, 0, 0, -1),
  K(PM, "YDPM", IAUTBN, 0, KI, OFF(iautbn), NOCAP, NOCAP, NOCAP, 0, F_3D, -1),

  K(PN, "YDPN", MPNSET, 0, KI, OFF(mpnset), NOCAP, NOCAP, NOCAP, 0, F_SIZE, -1),
  K(PN, "YDPN", NPNSET, 0, KI, OFF(npnset), NOCAP, NOCAP, NOCAP, 0, F_SIZE, -1),
  KPN(I1PNFX, KI1, OFF(i1pnfx), -1, 0),
  KPN(I1PNFY, KI1, OFF(i1pnfy), -1, 0),
  KPN(D1PNAX, KR1, OFF(d1pnax), 1, 0),
  KPN(D1PNAY, KR1, OFF(d1pnay), 1, 0),
  KPN(D1PNAP, KR1, OFF(d1pnap), 0, 0),
  KPN(D1PNAT, KR1, OFF(d1pnat), 0, 0),
  KPN(D1PNXX, KR1, OFF(d1pnxx), 1, 0),
  KPN(D1PNXY, KR1, OFF(d1pnxy), 0, 0),
  KPN(D1PNYX, KR1, OFF(d1pnyx), 0, 0),
  KPN(D1PNYY, KR1, OFF(d1pnyy), 1, 0),
  KPN(D1PNXZ, KR1, NOFF, 0, F_3D),
  KPN(D1PNYZ, KR1, NOFF, 0, F_3D),
  KPN(D1PNZX, KR1, NOFF, 0, F_3D),
  KPN(D1PNZY, KR1, NOFF, 0, F_3D),
  KPN(D1PNZZ, KR1, NOFF, 1, F_3D),
  KPN(I1PNFZ, KI1, NOFF, -1, F_3D),
  KPN(D1PNAZ, KR1, NOFF, 1, F_3D),
  K(PN, "YDPN", MPNFACT, 0, KI, OFF(mpnfact), NOCAP, NOCAP, NOCAP, 0, F_SIZE, -1),
  K(PN, "YDPN", NPNFACT, 0, KI, OFF(npnfact), NOCAP, NOCAP, NOCAP, 0, F_SIZE, -1),
  K(PN, "YDPN", D3PNFAC, 0, KR3, OFF(d3pnfac), CAPF(2), Y2D_PN_MPNSET, Y2D_PN_MPNFACT, 0, 0, -1),
  KPN(D1PNAF, KR1, NOFF, 1, F_UNUSED),

  K(O, "YDO", MOHYS, 0, KI, OFF(mohys), NOCAP, NOCAP, NOCAP, 0, F_SIZE, -1),
  K(O, "YDO", NOHYS, 0, KI, OFF(nohys), NOCAP, NOCAP, NOCAP, 0, F_SIZE, -1),
  K(O, "YDO", DOHYP, 0, KR, OFF(dohyp), NOCAP, NOCAP, NOCAP, 0.05, 0, -1),
  KO(I1OHYT, KI1, OFF(i1ohyt), 0, 0),
  KO(D1OHYX, KR1, OFF(d1ohyx), 0, 0),
  KO(D1OHYY, KR1, OFF(d1ohyy), 0, 0),
  KO(D1OHYC, KR1, OFF(d1ohyc), 1, 0),
  KO(D1OHYF, KR1, OFF(d1ohyf), 1, 0),
  KO(D1OHYS, KR1, OFF(d1ohys), 0, 0),
  KO(D1OHYT, KR1, OFF(d1ohyt), 0, 0),

  KB(MBORH, KI), KB(NBORH, KI), KB(MBDIM, KI), KB(NBDIM, KI), KB(NBPAF, KI), KB(D2BCA, KR2),
  KB(D2BCB, KR2), KB(D1BRAD, KR1), KB(D1BPAF, KR1), KB(D1BPTS, KR1), KB(D1BPTE, KR1),
  KB(D1BVDT, KR1), KB(D1BPRS, KR1), KB(DBLMAX, KR), KB(DBBUF, KR),
  KS(MSOUR, KI), KS(NSOUR, KI), KS(MSDIM, KI), KS(NSDIM, KI), KS(NSPAF, KI), KS(NSSAF, KI),
  KS(D2SCS, KR2), KS(D1SPAF, KR1), KS(D1SSAF, KR1), KS(D1SPTS, KR1), KS(D1SPTE, KR1),
  KS(D1SVPR, KR1), KS(D1SPRS, KR1), KS(D1SSIR, KR1), KS(DSBUF, KR),
};

const char *y2d_key_name(int key) {
  return key >= 0 && key < Y2D_NKEYS ? keydefs[key].full : "?";
}

/* Groups of the anchor in the order its dispatcher knows them. */
static const char *const groups[] = {"YDC", "YDE", "YDN", "YDI", "YDPE", "YDPJ",
                                     "YDPM", "YDPN", "YDO", "YDB", "YDS"};
#define NGROUPS ((int)(sizeof groups / sizeof groups[0]))

/* Keys of the Y-Geo derivative (FORMAT.md 9): refused by name so that a Y-Geo deck fails with a
 * message saying what it is rather than "unknown key".  The note says what Y2D uses instead. */
typedef struct {
  const char *group, *name, *note;
} YgeoKey;
static const YgeoKey ygeo_keys[] = {
  {"YDC", "ICOUTRF", "output after a number of fractures"},
  {"YDC", "ICOUTNF", "output after a number of fractures"},
  {"YDC", "ICRESF", "restart output"},
  {"YDC", "IUSEECZM", "alternative cohesive model"},
  {"YDN", "I1NOWE", "hydro-fracture wetting flags"},
  {"YDPE", "MPEROW", "size of the contact pair table; Y2D gives D1PEPE, D1PEPT, D1PEFR per property"},
  {"YDPE", "D2PEINT", "contact pair table; Y2D gives D1PEPE, D1PEPT, D1PEFR per property"},
  {"YDPE", "D1PEEM", "Young's modulus of types 5/6; Y2D takes Lame constants D1PELA, D1PEMU"},
  {"YDPE", "D1PENU", "Poisson's ratio of types 5/6; Y2D takes Lame constants D1PELA, D1PEMU"},
  {"YDPE", "I1PEXC", "excavation flag"},
  {"YDPE", "I1USAN", "transversely isotropic elasticity"},
  {"YDPE", "D1PEEX", "transversely isotropic elasticity"},
  {"YDPE", "D1PEEY", "transversely isotropic elasticity"},
  {"YDPE", "D1PEMX", "transversely isotropic elasticity"},
  {"YDPE", "D1PEMY", "transversely isotropic elasticity"},
  {"YDPE", "D1PEG", "transversely isotropic elasticity"},
  {"YDPE", "D1PHI", "plasticity/damage"}, {"YDPE", "D1DPC", "plasticity/damage"},
  {"YDPE", "D1SIG_T", "plasticity/damage"}, {"YDPE", "D1F0", "plasticity/damage"},
  {"YDPE", "D1H1", "plasticity/damage"}, {"YDPE", "D1H2", "plasticity/damage"},
  {"YDPE", "D1HC", "plasticity/damage"}, {"YDPE", "D1CK", "plasticity/damage"},
  {"YDPE", "D1CC", "plasticity/damage"}, {"YDPE", "D1BK", "plasticity/damage"},
  {"YDPE", "D1CKP", "plasticity/damage"}, {"YDPE", "D1NK", "plasticity/damage"},
  {"YDPE", "D1URU", "plasticity/damage"}, {"YDPE", "D1UC", "plasticity/damage"},
  {"YDPE", "D1RE", "plasticity/damage"}, {"YDPE", "D1CHI", "plasticity/damage"},
  {"YDPE", "D1NP", "plasticity/damage"}, {"YDPE", "D1N2", "plasticity/damage"},
  {"YDPE", "D1NN", "plasticity/damage"}, {"YDPE", "I1USE_EXT_SUBLOADING", "plasticity/damage"},
  {"YDPE", "I1USE_KINHARD", "plasticity/damage"}, {"YDPE", "I1PSUP", "plasticity/damage"},
  {"YDPJ", "D1PJGS", "mode-II fracture energy; Y2D uses D1PJGF for both modes"},
  {"YDPJ", "IUSEHY", "hysteretic joint law"},
  {"YDPJ", "D1USAF", "anisotropic joint strength"}, {"YDPJ", "D1PJAL", "anisotropic joint strength"},
  {"YDPJ", "D1PJCR", "anisotropic joint strength"}, {"YDPJ", "D1PJFD", "anisotropic joint strength"},
  {"YDPJ", "D1PJTR", "anisotropic joint strength"}, {"YDPJ", "D1PJGR", "anisotropic joint strength"},
  {"YDPJ", "D1PJSR", "anisotropic joint strength"},
};
/* Keys that public pre-processors of other Y derivatives write (a C++ writer and GiD templates
 * for Y-Geo-family programs with restart, hydraulic and rough-joint options): the anchor stops on
 * them ("unknown name"), so yfdem names them instead of suggesting a near Y2D key. */
static const YgeoKey other_keys[] = {
  {"YDC", "ISAVE", "restart saving"},
  {"YDC", "ICSAVF", "restart save frequency"},
  {"YDC", "DCSIZD", "displacement output scale"},
  {"YDC", "DCSIZA", "joint aperture output scale"},
  {"YDC", "DCRMPT", "load ramping stage"},
  {"YDC", "DCGRST", "gravity settling stage"},
  {"YDC", "ICFMTY", "joint friction model (Coulomb, Barton-Bandis)"},
  {"YDC", "ICIATY", "joint roughness input type"},
  {"YDE", "I1ELTY", "element types"},
  {"YDE", "I2ELJP", "joint properties per element"},
};
static const struct {
  const char *group, *note;
} ygeo_groups[] = {
  {"YDP", "the single property group of Y-Geo-family decks; Y2D splits it into /YD/YDPE/, "
          "/YD/YDPN/ and /YD/YDPJ/"},
  {"YDFN", "discrete fracture network"}, {"YDIS", "initial in-situ stress"},
  {"YDHF", "hydraulic fracturing"},      {"YDSM", "seismic monitoring"},
  {"YDR", "reinforcement"},              {"YDSB", "reinforcement"},
  {"YDPS", "reinforcement bars"},
};

/* ------------------------------------------------------------------ tokens */

#define MAX_DEPTH 10      /* the anchor: include nesting depth < 10                      */
#define MAX_COMMENT 100   /* the anchor: "too long comment" beyond 100 tokens             */

typedef struct {
  FILE *fp;
  int file; /* index into y->files */
  int line;
} Src;

typedef struct {
  YfY2d *y;
  Src src[MAX_DEPTH];
  int depth;           /* number of open files                                          */
  char *tok;           /* current token                                                 */
  size_t tokcap;
  YfLoc loc;           /* where the current token starts                                */
  int glued_warned;
  int last_key;        /* last key read (for stray-token hints)                          */
  int program;         /* read as `yfdem DECK.y` reads it (y2d_read_program)             */
  long last_n;         /* entries it read along its long dimension                       */
  int bore_warned;
} Rd;

static int add_file(YfY2d *y, const char *name) {
  y->files = yf_realloc(y->files, (size_t)(y->nfiles + 1) * sizeof *y->files, "y2d file names");
  y->files[y->nfiles] = yf_strdup(name);
  return y->nfiles++;
}

static void push_file(Rd *r, FILE *fp, const char *name) {
  unsigned char bom[3]; /* a UTF-8 byte-order mark is skipped (the files are regular files) */
  if (fread(bom, 1, 3, fp) != 3 || bom[0] != 0xef || bom[1] != 0xbb || bom[2] != 0xbf) rewind(fp);
  /* One thread reads the stream, so stdio's per-character lock is only cost: under MPI the
   * library's own threads make glibc take it on every getc (10x the time of the read itself at
   * 1e6 triangles, 2026-11-28), where a one-thread ./yfdem skips it. */
  __fsetlocking(fp, FSETLOCKING_BYCALLER);
  Src *s = &r->src[r->depth++];
  s->fp = fp;
  s->file = add_file(r->y, name);
  s->line = 1;
}

/* 1 when c ends a line: a LF, or a CR alone (classic Mac text; the CR of a CRLF is not counted,
 * its LF is), so that messages name the right line whatever the file's line ends. */
static int ends_line(FILE *fp, int c) {
  if (c == '\n') return 1;
  if (c != '\r') return 0;
  int d = getc(fp);
  if (d != EOF) ungetc(d, fp);
  return d != '\n' && d != '\r'; /* CR CR LF: the last CR's LF counts, once */
}

/* Next whitespace-separated token, or NULL at the end of the outermost file.  The end of an
 * included file returns transparently to the including one (as the anchor). */
static const char *next_tok(Rd *r) {
  while (r->depth > 0) {
    Src *s = &r->src[r->depth - 1];
    int c;
    while ((c = getc(s->fp)) != EOF && isspace(c))
      if (ends_line(s->fp, c)) s->line++;
    if (c == EOF) {
      fclose(s->fp);
      r->depth--;
      continue;
    }
    size_t n = 0;
    r->loc.file = r->y->files[s->file];
    r->loc.line = s->line;
    do {
      if (c == 0) /* a NUL would cut the token short, silently (as the native reader, deck.c) */
        yf_deck_error(&r->loc, "a NUL byte in a token: a .y deck is plain text (is this a binary file, or a UTF-16 "
                      "text? save it as UTF-8 or ASCII)");
      if (n + 2 > r->tokcap) {
        r->tokcap = r->tokcap ? 2 * r->tokcap : 256;
        r->tok = yf_realloc(r->tok, r->tokcap, "y2d token");
        r->y->tok_scratch = r->tok;
      }
      r->tok[n++] = (char)c;
    } while ((c = getc(s->fp)) != EOF && !isspace(c));
    r->tok[n] = 0;
    if (ends_line(s->fp, c)) s->line++;
    if (c == EOF && !r->glued_warned) {
      r->glued_warned = 1;
      yf_warn(&r->loc, "'%s' ends the file without a trailing newline: the anchor loses this "
              "last token (yfdem reads it); end the file with a newline", r->tok);
    }
    return r->tok;
  }
  return NULL;
}

static int is_key_like(const char *t) {
  return !strncmp(t, "/YD/", 4) || !strncmp(t, "$Y", 2) || !strncmp(t, "/*", 2);
}

/* Strict integer: optional sign and digits only. */
static int parse_int_tok(const char *t, long *v) {
  const char *p = t;
  if (*p == '+' || *p == '-') p++;
  if (!isdigit((unsigned char)*p)) return 0;
  while (isdigit((unsigned char)*p)) p++;
  if (*p) return 0;
  errno = 0;
  *v = strtol(t, NULL, 10);
  return errno == 0;
}

/* Strict real: the whole token is a finite C double (%le syntax). */
static int parse_real_tok(const char *t, double *v) {
  char *end;
  errno = 0;
  *v = strtod(t, &end);
  if (end == t || *end || !isfinite(*v)) return 0;
  /* strtod also takes "inf", "nan", hex: isfinite and the first character limit that */
  return isdigit((unsigned char)t[0]) || t[0] == '-' || t[0] == '+' || t[0] == '.';
}

/* ------------------------------------------------------------------ value reading */

/* What stopped a value list: for "too few values" messages. */
static void short_list(Rd *r, int key, const YfLoc *kloc, const char *what, long want, long got,
                       const char *stop) {
  char where[600];
  /* want < 0: a single item (a scalar's value, an array's count or code) is missing */
  if (!stop)
    snprintf(where, sizeof where, "the end of the input");
  else
    snprintf(where, sizeof where, "'%.200s' at %s:%d%s", stop, r->loc.file, r->loc.line,
             !strncmp(stop, "/*", 2) ? " (comments cannot appear inside a value list)" : "");
  if (want < 0) yf_deck_error(kloc, "%s: missing %s before %s", keydefs[key].full, what, where);
  yf_deck_error(kloc, "%s: expected %ld %s, found %ld before %s", keydefs[key].full, want, what,
                got, where);
}

/* The first non-ASCII character of token t, named, for the messages that quote t: "" when t is ASCII.
 * Decks copied from a word processor, a PDF or a web page hold look-alikes (a no-break space between a
 * key and its value, a minus sign U+2212, full-width digits) that the quoted token hides: "'200 ' is not a
 * number".  Y2D splits tokens at ASCII white space only and reads keys and numbers in ASCII.  The names
 * come from utf8name.h's table, which the deck's expressions name from too. */
static const char *non_ascii_note(const char *t) {
  static char note[256]; /* the reader is one thread; the message is printed before the next call */
  const unsigned char *u = (const unsigned char *)t;
  size_t i = 0;
  while (u[i] && u[i] < 0x80) i++;
  if (!u[i]) return "";
  unsigned cp;
  YfLookalike l;
  char what[96];
  if (!yf_utf8_decode(t + i, &cp))
    snprintf(what, sizeof what, "the byte 0x%02x (not ASCII, not UTF-8)", cp);
  else if (!yf_lookalike(cp, &l))
    snprintf(what, sizeof what, "U+%04X (not ASCII)", cp);
  else if (strlen(l.ascii) == 1 && ispunct((unsigned char)l.ascii[0])) /* a sign's look-alike: name the sign */
    snprintf(what, sizeof what, "U+%04X (%s, not the ASCII '%s')", cp, l.name, l.ascii);
  else
    snprintf(what, sizeof what, "U+%04X (%s)", cp, l.name);
  snprintf(note, sizeof note, "it holds %s at byte %zu: Y2D splits tokens at ASCII white space only and reads keys "
           "and numbers in ASCII; retype it in ASCII", what, i + 1);
  return note;
}

/* Why token t is not a number, and what is: for the messages of read_int and read_real.  The
 * forms users bring from other programs get their own words: a Fortran 'd' exponent (1.d5, which
 * Y2D's %le reads as 1. followed by a stray token 'd5'), a value beyond a double (1e400), words. */
static const char *not_number_why(const char *t) {
  if (*non_ascii_note(t)) return non_ascii_note(t);
  char buf[64];
  size_t n = strlen(t);
  if (n < sizeof buf) {
    memcpy(buf, t, n + 1);
    char *d = strpbrk(buf, "dD");
    if (d) {
      *d = 'e';
      double v;
      if (parse_real_tok(buf, &v))
        return "a Fortran 'd' exponent: Y2D reads C reals (%le) and stops at the 'd'; write it with 'e', "
               "e.g. 1.5e5 for 1.5d5";
    }
  }
  /* a decimal comma (a European locale's output): Y2D's %le reads up to the ',' and the rest is a stray token */
  if (n < sizeof buf && strchr(t, ',') && strchr(t, ',') == strrchr(t, ',')) {
    memcpy(buf, t, n + 1);
    *strchr(buf, ',') = '.';
    double v;
    if (parse_real_tok(buf, &v)) {
      static char why[160]; /* the reader is one thread; the message is printed before the next call */
      snprintf(why, sizeof why, "a decimal comma: Y2D reads C reals (%%le) with a decimal point and stops at the ','; "
               "write %s", buf);
      return why;
    }
  }
  char *end;
  errno = 0;
  double v = strtod(t, &end);
  if (end != t && !*end && (isdigit((unsigned char)t[0]) || t[0] == '-' || t[0] == '+' || t[0] == '.') &&
      (!isfinite(v) || errno == ERANGE) && fabs(v) > 1.0)
    return "beyond the range of a double (+-1.8e308)";
  return "a real is written like 2000, -0.5, 1e5 or 1.0E+05";
}

/* Read one integer of key `key`; `what` names it in messages ("count", "value 3 of 720"). */
static long read_int(Rd *r, int key, const YfLoc *kloc, const char *what, long want, long got) {
  const char *t = next_tok(r);
  if (!t || is_key_like(t)) short_list(r, key, kloc, what, want, got, t);
  long v;
  double d;
  if (!parse_int_tok(t, &v)) {
    const char *p = t + (*t == '+' || *t == '-');
    if (*p && strspn(p, "0123456789") == strlen(p)) /* digits only: too many of them */
      yf_deck_error(&r->loc, "%s: '%s' is beyond the range of an integer (%ld to %ld)", keydefs[key].full, t,
                    LONG_MIN, LONG_MAX);
    if (parse_real_tok(t, &d))
      yf_deck_error(&r->loc, "%s: '%s' is not an integer (the anchor would misread it; an integer is digits "
                    "only: 3000, not 3000.0 or 3e3)", keydefs[key].full, t);
    yf_deck_error(&r->loc, "%s: '%s' is not a number (%s)", keydefs[key].full, t,
                  *non_ascii_note(t) ? non_ascii_note(t) : "an integer is wanted here, digits only: e.g. 3000");
  }
  return v;
}

static double read_real(Rd *r, int key, const YfLoc *kloc, const char *what, long want, long got) {
  const char *t = next_tok(r);
  if (!t || is_key_like(t)) short_list(r, key, kloc, what, want, got, t);
  double v;
  if (!parse_real_tok(t, &v))
    yf_deck_error(&r->loc, "%s: '%s' is not a number (%s)", keydefs[key].full, t, not_number_why(t));
  return v;
}

/* Value of an integer scalar key (capacities). */
static long scalar_long(const YfY2d *y, int key) {
  return *(const long *)((const char *)y + keydefs[key].off);
}

/* Size of dimension d of array key k: -1 if not checked. */
static long dim_cap(const YfY2d *y, int k, int d) {
  int c = keydefs[k].cap[d];
  if (c == NOCAP) return -1;
  if (c <= -100) return -c - 100;
  return scalar_long(y, c);
}

static int ndims(int type) {
  return type == KI1 || type == KR1 ? 1 : type == KI2 || type == KR2 ? 2 : type == KR3 ? 3 : 0;
}
static int is_int_type(int type) { return type == KI || type == KI1 || type == KI2; }

/* Bytes of array key k at the capacities read so far (0 for a key that is not stored). */
static double array_bytes(const YfY2d *y, int k) {
  const KeyDef *kd = &keydefs[k];
  if (kd->off == NOFF || !ndims(kd->type)) return 0.0;
  double bytes = is_int_type(kd->type) ? (double)sizeof(int) : (double)sizeof(double);
  for (int d = 0; d < ndims(kd->type); d++) {
    long c = dim_cap(y, k, d);
    bytes *= c > 0 ? (double)c : 0.0;
  }
  return bytes;
}

/* Capacity key k (MNOPO, MPROP...) has just been given: refuse it at its line when all the
 * arrays of the deck, at the capacities given so far, need more memory than the cap.  The sum
 * matters, not each array: MPROP 2147483648 sizes 13 arrays that each fit in 32 GB and together
 * need 180 GB, and every array is allocated at its capacity (those never given at the end).
 * Checked here, once per capacity, so that alloc_array never meets a size that overflows. */
static void check_capacity_memory(const YfY2d *y, int k, const YfLoc *kloc) {
  double total = 0.0, bmax = 0.0;
  int nsized = 0, nall = 0, amax = -1;
  for (int a = 0; a < Y2D_NKEYS; a++) {
    double b = array_bytes(y, a);
    if (!(b > 0)) continue;
    total += b;
    nall++;
    if (b > bmax) { bmax = b; amax = a; }
    for (int d = 0; d < 3; d++)
      if (keydefs[a].cap[d] == k) {
        nsized++;
        break;
      }
  }
  if (!nsized || !(total > yf_mem_cap())) return;
  /* The key read last tips the sum over, but the capacity to change is often an earlier one (MELEM
   * 4000000000, then MELST 1: the error named MELST alone): name the largest array's capacities,
   * each with its value and line. */
  char big[400] = "";
  if (amax >= 0) {
    int o = snprintf(big, sizeof big, "; the largest array, %s, is sized by", keydefs[amax].full);
    for (int d = 0; d < ndims(keydefs[amax].type) && o > 0 && (size_t)o < sizeof big; d++) {
      int c = keydefs[amax].cap[d];
      if (c < 0) continue; /* a fixed size */
      o += snprintf(big + o, sizeof big - (size_t)o, "%s %s = %ld (line %d)", d ? "," : "", keydefs[c].full,
                    scalar_long(y, c), c == k ? kloc->line : y->where[c].line);
    }
  }
  char what[640];
  snprintf(what, sizeof what, "%s = %ld (it sizes %d array%s; with the arrays sized by the capacities before it, "
           "%d in all%s)", keydefs[k].full, scalar_long(y, k), nsized, nsized == 1 ? "" : "s", nall, big);
  yf_mem_check(kloc, total, what);
}

/* (Re)allocate the storage of array key k at its capacity, filled with the default.  Its size
 * fits: check_capacity_memory refused every capacity that would make all arrays too big. */
static void alloc_array(YfY2d *y, int k) {
  const KeyDef *kd = &keydefs[k];
  if (kd->off == NOFF) return;
  long n = 1;
  for (int d = 0; d < ndims(kd->type); d++) {
    long c = dim_cap(y, k, d);
    n *= c > 0 ? c : 0;
  }
  void **pp = (void **)((char *)y + kd->off);
  free(*pp);
  if (is_int_type(kd->type)) {
    int *a = yf_malloc((size_t)(n ? n : 1) * sizeof *a, kd->full);
    for (long i = 0; i < n; i++) a[i] = (int)kd->def;
    *pp = a;
  } else {
    double *a = yf_malloc((size_t)(n ? n : 1) * sizeof *a, kd->full);
    for (long i = 0; i < n; i++) a[i] = kd->def;
    *pp = a;
  }
}

static const char *dimname(int k, int d) {
  int c = keydefs[k].cap[d];
  return c >= 0 ? keydefs[c].full : "its fixed size";
}

/* KEY n v1..vn | KEY code n1 n2 values | KEY code n1 n2 n3 values (FORMAT.md 1.3). */
/* Before value m of array key k is read: note its line (peeks at the next token's line: blank
 * space and newlines before it are skipped).  Lines that follow each other with the same number
 * of values make one run (a generated deck's 4 million lines of coordinates: one entry, where an
 * entry per line took 100 MB at 1e6 triangles). */
static void note_value_line(Rd *r, int k, long m) {
  YfY2d *y = r->y;
  if (r->depth <= 0) return;
  Src *s = &r->src[r->depth - 1];
  int c;
  while ((c = getc(s->fp)) != EOF && isspace(c))
    if (ends_line(s->fp, c)) s->line++;
  if (c != EOF) ungetc(c, s->fp);
  if (y->nvline) {
    YfValueLines *e = &y->vline[y->nvline - 1];
    if (e->key == k && e->file == s->file) {
      long on_last = m - (e->m + e->per * (e->nlines - 1)); /* values before m on its last line */
      if (s->line == e->line + e->nlines - 1) { /* one more on the run's last line (which may be longer) */
        if (e->nlines == 1) e->per = on_last + 1;
        return;
      }
      if (s->line == e->line + e->nlines && on_last == e->per) { /* the next line, the last exactly full */
        e->nlines++;
        return;
      }
    }
  }
  if (y->nvline == y->capvline) {
    y->capvline = y->capvline ? 2 * y->capvline : 64;
    y->vline = yf_realloc(y->vline, (size_t)y->capvline * sizeof *y->vline, "y2d value lines");
  }
  y->vline[y->nvline++] = (YfValueLines){.key = k, .file = s->file, .line = s->line, .nlines = 1, .m = m, .per = 1};
}

static void read_array(Rd *r, int k, const YfLoc *kloc) {
  YfY2d *y = r->y;
  const KeyDef *kd = &keydefs[k];
  int nd = ndims(kd->type);
  /* capacity keys (FORMAT.md 2.1) must come first */
  for (int d = 0; d < nd; d++) {
    int c = kd->cap[d];
    if (c >= 0 && !y->given[c])
      yf_deck_error(kloc, "%s: read before its capacity %s; give %s first (FORMAT.md 2.1)",
                    kd->full, keydefs[c].full, keydefs[c].full);
  }
  if (kd->after >= 0 && !y->given[kd->after])
    yf_deck_error(kloc, "%s: read before %s; give %s first (FORMAT.md 2.1)", kd->full,
                  keydefs[kd->after].full, keydefs[kd->after].full);
  int order[3] = {0, 1, 2};
  long cnt[3] = {1, 1, 1};
  if (nd == 1) {
    cnt[0] = read_int(r, k, kloc, "the count n", -1, 0);
  } else {
    long code = read_int(r, k, kloc, "the array code", -1, 0);
    YfLoc cloc = r->loc;
    if (nd == 2) {
      if (code == 12) order[0] = 0, order[1] = 1;
      else {
        order[0] = 1, order[1] = 0;
        if (code != 21)
          yf_warn(&cloc, "%s: array code %ld read as 21 (long index outermost), as the anchor "
                  "does; write 12 or 21", kd->full, code);
      }
    } else {
      char s[32];
      snprintf(s, sizeof s, "%ld", code);
      if (strlen(s) != 3 || !strchr(s, '1') || !strchr(s, '2') || !strchr(s, '3'))
        yf_deck_error(&cloc, "%s: array code '%s' is not a permutation of 123 (valid: 123 132 "
                      "213 231 312 321)", kd->full, s);
      for (int d = 0; d < 3; d++) order[d] = s[d] - '1';
    }
    for (int d = 0; d < nd; d++) {
      char w[32];
      snprintf(w, sizeof w, "the size n%d", d + 1);
      cnt[d] = read_int(r, k, kloc, w, -1, d);
    }
  }
  int empty = cnt[0] == 0 || cnt[1] == 0 || cnt[2] == 0;
  for (int d = 0; d < nd; d++) {
    if (cnt[d] < 0) yf_deck_error(&r->loc, "%s: negative size %ld", kd->full, cnt[d]);
    long c = dim_cap(y, k, d);
    if (c >= 0 && cnt[d] > c) {
      const char *nm = nd > 1 ? (d == 0 ? "n1 = " : d == 1 ? "n2 = " : "n3 = ") : "n = ";
      /* "D2ELST 21 529 0" (a C++ generator): no value is read, so the anchor writes nothing
       * past the capacity and accepts it; only a list that holds values can overflow */
      if (empty)
        yf_warn(kloc, "%s: %s%ld exceeds the capacity %ld given by %s, but the array holds no "
                "values (another size is 0): read as an empty array, as Y2D does", kd->full, nm,
                cnt[d], c, dimname(k, d));
      else
        yf_deck_error(kloc, "%s: %s%ld entries exceed the capacity %ld given by %s%s", kd->full,
                      nm, cnt[d], c, dimname(k, d), c == 0 ? " (set it before this key)" : "");
    }
  }
  alloc_array(y, k);
  long total = empty ? 0 : cnt[0] * cnt[1] * cnt[2]; /* each <= its capacity: no overflow */
  long cap1 = nd >= 2 ? dim_cap(y, k, 0) : 0, cap2 = nd == 3 ? dim_cap(y, k, 1) : 0;
  long cap3 = nd == 3 ? dim_cap(y, k, 2) : 0;
  void *base = kd->off == NOFF ? NULL : *(void **)((char *)y + kd->off);
  long idx[3] = {0, 0, 0};
  char what[64];
  for (long m = 0; m < total; m++) {
    note_value_line(r, k, m);
    /* idx of the m-th value: the innermost loop is order[nd-1] */
    long rem = m;
    for (int q = nd - 1; q >= 0; q--) {
      int d = order[q];
      idx[d] = rem % cnt[d];
      rem /= cnt[d];
    }
    snprintf(what, sizeof what, "values");
    long off = nd == 1 ? idx[0] : nd == 2 ? idx[1] * cap1 + idx[0]
                                          : (idx[0] * cap2 + idx[1]) * cap3 + idx[2];
    if (is_int_type(kd->type)) {
      long v = read_int(r, k, kloc, what, total, m);
      if (v < INT_MIN || v > INT_MAX)
        yf_deck_error(&r->loc, "%s: %ld is out of range", kd->full, v);
      if (base) ((int *)base)[off] = (int)v;
    } else {
      double v = read_real(r, k, kloc, what, total, m);
      /* at its own line: the run's check of every node (run.c) would only name the node, without
       * the deck's FILE:LINE, and a coordinate that large first makes its triangles' areas round
       * to 0 (then refused as "not counter-clockwise") */
      if ((kd->flags & F_RANGE) && !(fabs(v) <= YF_RANGE_MAX))
        yf_deck_error(&r->loc, "%s: node %ld, %c component: %s is beyond +-%g %s, the range the arithmetic holds "
                      "(areas and energies multiply coordinates and velocities); give it in units that keep "
                      "it within", kd->full, idx[1], idx[0] == 0 ? 'x' : idx[0] == 1 ? 'y' : 'z', r->tok,
                      YF_RANGE_MAX, k == Y2D_N_D2NVC ? "m/s" : "m");
      if (base) ((double *)base)[off] = v;
    }
  }
  y->nread[k] = nd == 1 ? cnt[0] : nd == 2 ? cnt[1] : cnt[2];
  r->last_n = total;
}

/* A capacity key re-given with another value after arrays were sized by it. */
static void check_cap_change(Rd *r, int k, long oldv, long newv, const YfLoc *kloc) {
  if (!r->y->given[k] || oldv == newv) return;
  for (int a = 0; a < Y2D_NKEYS; a++) {
    if (!r->y->given[a] || !ndims(keydefs[a].type)) continue;
    for (int d = 0; d < 3; d++)
      if (keydefs[a].cap[d] == k)
        yf_deck_error(kloc, "%s: changed from %ld to %ld after %s (read at %s:%d) was sized by "
                      "it; give each capacity once, before its arrays", keydefs[k].full, oldv,
                      newv, keydefs[a].full, r->y->where[a].file, r->y->where[a].line);
  }
}

static void read_key(Rd *r, int k, const YfLoc *kloc) {
  YfY2d *y = r->y;
  const KeyDef *kd = &keydefs[k];
  r->last_n = 1;
  if (kd->type == KI || kd->type == KR) {
    if (kd->after >= 0 && !y->given[kd->after])
      yf_warn(kloc, "%s read before %s: the anchor requires %s first (FORMAT.md 2.1); yfdem "
              "accepts this order", kd->full, keydefs[kd->after].full, keydefs[kd->after].full);
    if (kd->type == KI) {
      long v = read_int(r, k, kloc, "its value", -1, 0);
      if ((kd->flags & F_SIZE) && v < 0)
        yf_deck_error(&r->loc, "%s: negative value %ld (a size or count must be >= 0)",
                      kd->full, v);
      if (kd->off != NOFF) {
        long *p = (long *)((char *)y + kd->off);
        check_cap_change(r, k, *p, v, kloc);
        *p = v;
        check_capacity_memory(y, k, kloc);
      }
    } else {
      double v = read_real(r, k, kloc, "its value", -1, 0);
      if ((kd->flags & F_NONNEG) && v < 0)
        yf_deck_error(&r->loc, "%s: negative value %g (the anchor: \"illegitimate parameter "
                      "definition\")", kd->full, v);
      if (kd->off != NOFF) *(double *)((char *)y + kd->off) = v;
    }
    y->nread[k] = 1;
  } else {
    read_array(r, k, kloc);
  }
  if ((kd->flags & F_RESTART) && !y->given[k] && r->last_n > 0) /* "D1NMCT 0": nothing given */
    yf_warn(kloc, "%s: restart/scratch data, ignored (yfdem computes it)", kd->full);
  if ((kd->flags & F_3D) && !y->given[k])
    yf_warn(kloc, "%s: 3D-only key, ignored in 2D", kd->full);
  if ((kd->flags & F_BORE) && !r->bore_warned) {
    r->bore_warned = 1;
    yf_warn(kloc, "%s: boreholes and sources (/YD/YDB/, /YD/YDS/) are accepted and ignored "
            "(they have no effect in the anchor either)", kd->full);
  }
  y->given[k] = 1;
  y->where[k] = *kloc;
  r->last_key = k;
}

/* ------------------------------------------------------------------ keys and control tokens */

static int group_index(const char *g, size_t len) {
  for (int i = 0; i < NGROUPS; i++)
    if (strlen(groups[i]) == len && !strncmp(groups[i], g, len)) return i;
  return -1;
}

/* "/YD/<GROUP>/<NAME>": dispatch by the anchor's rules, or fail with a clear message. */
static void do_key(Rd *r, const char *tok) {
  YfLoc kloc = r->loc;
  char t[256];
  snprintf(t, sizeof t, "%s", tok);
  const char *g = t + 4;
  const char *slash = strchr(g, '/');
  size_t glen = slash ? (size_t)(slash - g) : strlen(g);
  const char *name = slash ? slash + 1 : "";
  int gi = group_index(g, glen);
  if (gi < 0) {
    for (size_t i = 0; i < sizeof ygeo_groups / sizeof ygeo_groups[0]; i++)
      if (strlen(ygeo_groups[i].group) == glen && !strncmp(ygeo_groups[i].group, g, glen))
        yf_deck_error(&kloc, "%s: Y-Geo group /YD/%s/ (%s), not in Y2D", t, ygeo_groups[i].group,
                      ygeo_groups[i].note);
    char gname[64];
    snprintf(gname, sizeof gname, "%.*s", (int)(glen < 60 ? glen : 60), g);
    const char *near = yf_nearest(gname, (const char *const *)groups, NGROUPS);
    yf_deck_error(&kloc, "%s: unknown group /YD/%s/%s%s%s (groups: YDC YDE YDN YDI YDPE YDPJ "
                  "YDPM YDPN YDO YDB YDS)", t, gname, near ? " (did you mean /YD/" : "",
                  near ? near : "", near ? "/?)" : "");
  }
  /* anchor rule: compare the known name over its own length; first match wins */
  for (int k = 0; k < Y2D_NKEYS; k++) {
    const KeyDef *kd = &keydefs[k];
    if (strcmp(kd->group, groups[gi])) continue;
    size_t ml = kd->match ? (size_t)kd->match : strlen(kd->name);
    if (!strncmp(name, kd->name, ml)) {
      if (strcmp(name, kd->name) && strlen(name) != ml)
        yf_warn(&kloc, "%s read as %s (the anchor compares only the first %zu characters)%s%s", t,
                kd->full, ml, *non_ascii_note(t) ? "; " : "", non_ascii_note(t));
      read_key(r, k, &kloc);
      return;
    }
  }
  for (size_t i = 0; i < sizeof ygeo_keys / sizeof ygeo_keys[0]; i++)
    if (!strcmp(ygeo_keys[i].group, groups[gi]) && !strcmp(ygeo_keys[i].name, name))
      yf_deck_error(&kloc, "%s: Y-Geo key, not in Y2D (%s)", t, ygeo_keys[i].note);
  for (size_t i = 0; i < sizeof other_keys / sizeof other_keys[0]; i++)
    if (!strcmp(other_keys[i].group, groups[gi]) && !strcmp(other_keys[i].name, name))
      yf_deck_error(&kloc, "%s: not a Y2D key (%s: written for other Y derivatives; Y2D stops on "
                    "it too)", t, other_keys[i].note);
  const char *names[64];
  int nn = 0;
  for (int k = 0; k < Y2D_NKEYS && nn < 64; k++)
    if (!strcmp(keydefs[k].group, groups[gi])) names[nn++] = keydefs[k].name;
  const char *near = name[0] ? yf_nearest(name, names, nn) : NULL;
  if (*non_ascii_note(t))
    yf_deck_error(&kloc, "%s: unknown key in /YD/%s/ (%s)", t, groups[gi], non_ascii_note(t));
  if (near)
    yf_deck_error(&kloc, "%s: unknown key in /YD/%s/ (did you mean %s?)", t, groups[gi], near);
  char list[1024];
  size_t p = 0;
  list[0] = 0;
  for (int i = 0; i < nn && p + 16 < sizeof list; i++)
    p += (size_t)snprintf(list + p, sizeof list - p, "%s%s", i ? " " : "", names[i]);
  yf_deck_error(&kloc, "%s: unknown key in /YD/%s/ (keys: %s)", t, groups[gi], list);
}

/* Skip a comment whose opening token has just been read (FORMAT.md 1.1). */
static void skip_comment(Rd *r) {
  YfLoc open = r->loc;
  char opener[80];
  snprintf(opener, sizeof opener, "%.70s", r->tok);
  int glued = strlen(r->tok) > 2 && strstr(r->tok + 2, "*/") != NULL;
  char swallowed[128] = "";
  YfLoc sw_loc = open;
  for (int n = 1;; n++) {
    const char *t = next_tok(r);
    if (!t)
      yf_deck_error(&open, "unterminated comment '%s': no token beginning with '*/' before the "
                    "end of the input%s", opener,
                    glued ? " (a '*/' glued to a word does not close a comment: the terminator "
                            "must be its own token)" : "");
    if (!strncmp(t, "*/", 2)) break;
    if (strstr(t, "*/")) glued = 1;
    /* a key or control word after a terminator glued to a word: the comment meant to end there; one
     * inside a comment that no glued terminator precedes is commented out on purpose (quiet) */
    if (glued && !swallowed[0] && (!strncmp(t, "/YD/", 4) || !strncmp(t, "$Y", 2))) {
      snprintf(swallowed, sizeof swallowed, "%.100s", t);
      sw_loc = r->loc;
    }
    if (n >= MAX_COMMENT)
      yf_deck_error(&open, "comment '%s' longer than %d tokens (the anchor stops with \"too long "
                    "comment\")%s", opener, MAX_COMMENT,
                    glued ? "; note: a '*/' glued to a word does not close a comment, the "
                            "terminator must be its own token" : "");
  }
  if (swallowed[0])
    yf_warn(&sw_loc, "'%s' is inside the comment opened at %s:%d and is ignored (is a '*/' "
            "glued to a word? the terminator must be its own token)", swallowed, open.file,
            open.line);
}

static char *dir_of(const char *path) {
  const char *s = strrchr(path, '/');
  if (!s) return yf_strdup(".");
  size_t n = (size_t)(s - path);
  char *d = yf_malloc(n + 2, "path");
  memcpy(d, path, n ? n : 1);
  d[n ? n : 1] = 0;
  if (!n) d[0] = '/';
  return d;
}

static void do_include(Rd *r) {
  YfLoc iloc = r->loc;
  const char *including = r->depth > 0 ? r->y->files[r->src[r->depth - 1].file] : ".";
  const char *t = next_tok(r);
  if (!t || is_key_like(t))
    yf_deck_error(&iloc, "$YINCL: expected a file name%s%s", t ? " before " : " before the end",
                  t ? t : "");
  char *name = yf_strdup(t);
  if (r->depth >= MAX_DEPTH)
    yf_deck_error(&iloc, "$YINCL %s: include files nested deeper than %d", name, MAX_DEPTH - 1);
  FILE *fp = yf_open_input(name, "r");
  char *used = yf_strdup(name);
  if (!fp && name[0] != '/') {
    int e1 = errno;
    char *dir = dir_of(including);
    size_t n = strlen(dir) + strlen(name) + 2;
    char *alt = yf_malloc(n, "path");
    snprintf(alt, n, "%s/%s", dir, name);
    free(dir); /* before the error below, which exits */
    fp = yf_open_input(alt, "r");
    if (!fp)
      yf_io_error(&iloc, "$YINCL %s: cannot open it relative to the working directory (%s) nor "
                  "as %s (%s)", name, strerror(e1), alt, strerror(errno));
    free(used);
    used = alt;
  } else if (!fp) {
    yf_io_error(&iloc, "$YINCL %s: cannot open: %s", name, strerror(errno));
  }
  push_file(r, fp, used);
  free(used);
  free(name);
}

/* After $YDOIT: only comments and $YSTOP may follow (one input section). */
static void after_ydoit(Rd *r) {
  YfLoc dl = r->loc;
  const char *t;
  while ((t = next_tok(r))) {
    if (!strncmp(t, "/*", 2)) {
      skip_comment(r);
      continue;
    }
    if (!strcmp(t, "$YSTOP")) return;
    yf_deck_error(&r->loc, "'%s' after $YDOIT (at %s:%d): multiple input sections (continuing a "
                  "run with changed keys) are not supported by yfdem; end the deck with $YDOIT "
                  "and $YSTOP", t, dl.file, dl.line);
  }
  yf_warn(&dl, "the deck ends after $YDOIT without $YSTOP (the anchor crashes at exit); end it "
          "with $YSTOP and a newline");
}

static void read_tokens(Rd *r) {
  YfY2d *y = r->y;
  const char *t;
  while ((t = next_tok(r))) {
    if (!strncmp(t, "/*", 2)) {
      skip_comment(r);
    } else if (!strcmp(t, "$YDOIT")) {
      y->has_ydoit = 1;
      y->end = r->loc;
      after_ydoit(r);
      return;
    } else if (!strcmp(t, "$YSTOP")) {
      y->end = r->loc;
      y->ystop = 1;
      if (!r->program)
        yf_warn(&r->loc, "$YSTOP before any $YDOIT: Y2D would stop here without computing (read_y2d takes the "
                "scene as read)");
      return;
    } else if (!strcmp(t, "$YINCL")) {
      do_include(r);
    } else if (!strncmp(t, "$Y", 2)) {
      yf_deck_error(&r->loc, "unknown control token '%s' (valid: $YDOIT $YSTOP $YINCL)", t);
    } else if (!strncmp(t, "/YD/", 4)) {
      do_key(r, t);
    } else {
      double v;
      int prev = r->last_key;
      if (prev >= 0 && ndims(keydefs[prev].type) && parse_real_tok(t, &v))
        yf_deck_error(&r->loc, "unexpected value '%s': expected a key /YD/<GROUP>/<NAME> (is "
                      "the count of %s at %s:%d too small? it read %ld values)", t,
                      keydefs[prev].full, y->where[prev].file, y->where[prev].line, r->last_n);
      if (prev >= 0 && parse_real_tok(t, &v))
        yf_deck_error(&r->loc, "unexpected value '%s': expected a key /YD/<GROUP>/<NAME> (%s at "
                      "%s:%d takes one value)", t, keydefs[prev].full, y->where[prev].file,
                      y->where[prev].line);
      if (!strncasecmp(t, "/YD/", 4) || !strncasecmp(t, "$Y", 2)) /* Y2D compares keys case by case */
        yf_deck_error(&r->loc, "unexpected token '%s': keys and control words are upper case (/YD/YDC/MCSTEP, "
                      "$YDOIT), as Y2D reads them", t);
      if (*non_ascii_note(t)) yf_deck_error(&r->loc, "unexpected token '%s': %s", t, non_ascii_note(t));
      yf_deck_error(&r->loc, "unexpected token '%s': expected a key /YD/<GROUP>/<NAME>, a "
                    "comment '/* ... */' or $YDOIT, $YSTOP, $YINCL", t);
    }
  }
  /* end of input without $YDOIT/$YSTOP */
  y->end = r->loc;
  if (!r->program)
    yf_warn(&y->end, "the deck ends without $YDOIT: Y2D would not compute anything (read_y2d takes the scene "
            "as read); end it with $YDOIT and $YSTOP");
}

/* ------------------------------------------------------------------ checks after reading */

static YfLoc loc_of(const YfY2d *y, int k) { return y->given[k] ? y->where[k] : y->end; }

/* FILE:LINE of value m (in reading order) of array key k: the line it is on (the key's own line
 * when unknown). */
static YfLoc value_loc(const YfY2d *y, int k, long m) {
  YfLoc l = loc_of(y, k);
  for (long i = 0; i < y->nvline; i++) {
    const YfValueLines *e = &y->vline[i];
    if (e->key == k && e->m <= m) {
      long d = (m - e->m) / e->per;
      l.file = y->files[e->file];
      l.line = e->line + (int)(d < e->nlines - 1 ? d : e->nlines - 1);
    }
  }
  return l;
}


static void require(const YfY2d *y, int k, const char *why) {
  if (!y->given[k])
    yf_deck_error(&y->end, "%s is required (%s) but was not given before %s", keydefs[k].full,
                  why, y->has_ydoit ? "$YDOIT" : "the end of the deck");
}

/* An edge (lo < hi node indices) of element t, local edge k (edgesort.h). */
typedef YfEdgeRec Edge;

/* Sorted list of the edges of the triangles with sel[e] != 0 (sel NULL: all). */
static Edge *edge_list(const YfY2d *y, const unsigned char *sel, long *ne) {
  Edge *ed = yf_malloc((size_t)(3 * y->nelem + 1) * sizeof *ed, "y2d edges");
  long n = 0;
  for (long e = 0; e < y->nelem; e++) {
    if (sel && !sel[e]) continue;
    const int *v = &y->i2elto[e * y->melno];
    for (int k = 0; k < 3; k++) {
      int a = v[k], b = v[(k + 1) % 3];
      ed[n].lo = a < b ? a : b;
      ed[n].hi = a < b ? b : a;
      ed[n].t = (int)e;
      ed[n].k = k;
      n++;
    }
  }
  yf_edges_sort(ed, n);
  *ne = n;
  return ed;
}

static int row_has_prop(const YfY2d *y, long row, int p) {
  const int *s = &y->i2pmset[row * y->mpmcol];
  for (int i = 0; i < s[0] && i + 2 < y->mpmcol; i++)
    if (s[2 + i] == p) return 1;
  return 0;
}

static void check_meshing(YfY2d *y) {
  YfLoc ml = loc_of(y, Y2D_PM_I2PMSET);
  if (y->mpmrow <= 0)
    yf_deck_error(&ml, "%s is given, so %s must be > 0 (rows of %s)", keydefs[Y2D_PM_I2PMSET].full,
                  keydefs[Y2D_PM_MPMROW].full, keydefs[Y2D_PM_I2PMIJ].full);
  require(y, Y2D_PM_I2PMIJ, "joint sets between meshed properties, needed with I2PMSET");
  if (y->mpjset <= 0 || y->npjset <= 0)
    yf_deck_error(&ml, "%s is given, so a joint database is required: %s and %s must be > 0",
                  keydefs[Y2D_PM_I2PMSET].full, keydefs[Y2D_PJ_MPJSET].full,
                  keydefs[Y2D_PJ_NPJSET].full);
  static const int jreq[] = {Y2D_PJ_D1PJFS, Y2D_PJ_D1PJFT, Y2D_PJ_D1PJGF, Y2D_PJ_D1PJPE,
                             Y2D_PJ_I1PTYP};
  for (size_t i = 0; i < sizeof jreq / sizeof jreq[0]; i++)
    require(y, jreq[i], "joint property, needed with meshing");
  int joints = 0;
  long need_nodes = y->nnopo, need_elems = y->nelem;
  unsigned char *sel = yf_calloc((size_t)y->nelem + 1, 1, "y2d selection");
  for (long row = 0; row < y->mpmcom; row++) {
    const int *s = &y->i2pmset[row * y->mpmcol];
    int k = s[0], code = s[1];
    if (k == 0) continue;
    if (k < 0 || k > y->mpmcol - 2)
      yf_deck_error(&ml, "%s: row %ld lists %d properties, but %s = %ld allows at most %ld",
                    keydefs[Y2D_PM_I2PMSET].full, row, k, keydefs[Y2D_PM_MPMCOL].full, y->mpmcol,
                    y->mpmcol - 2);
    if (code <= 0)
      yf_deck_error(&ml, "%s: row %ld: meshing code %d must be positive (digits 1 split in 4, 2 "
                    "split in 6, 3 joints, 4 detach)", keydefs[Y2D_PM_I2PMSET].full, row, code);
    for (int c = code; c > 0; c /= 10)
      if (c % 10 < 1 || c % 10 > 4)
        yf_deck_error(&ml, "%s: row %ld: meshing code %d has digit %d (valid digits: 1 split in 4, "
                      "2 split in 6, 3 joints, 4 detach)", keydefs[Y2D_PM_I2PMSET].full, row, code,
                      c % 10);
    for (int i = 0; i < k; i++) {
      int p = s[2 + i];
      if (p < 0 || p >= y->nprop)
        yf_deck_error(&ml, "%s: row %ld: property %d outside 0..NPROP-1 = 0..%ld",
                      keydefs[Y2D_PM_I2PMSET].full, row, p, y->nprop - 1);
      /* a property no element uses is not meshed: its type is not checked */
      if (y->prop_used[p] && y->pe_i1ptyp[p] != 1 && y->pe_i1ptyp[p] != 2)
        yf_deck_error(&ml, "%s: row %ld: property %d has type %d; only types 1 and 2 may be meshed",
                      keydefs[Y2D_PM_I2PMSET].full, row, p, y->pe_i1ptyp[p]);
    }
    /* size estimate: triangles T, distinct edges E of the row's triangles */
    long T = 0;
    for (long e = 0; e < y->nelem; e++) {
      sel[e] = (unsigned char)row_has_prop(y, row, y->i1elpr[e]);
      T += sel[e];
    }
    long n3, E = 0;
    Edge *ed = edge_list(y, sel, &n3);
    for (long i = 0; i < n3; i++)
      if (i == 0 || ed[i].lo != ed[i - 1].lo || ed[i].hi != ed[i - 1].hi) E++;
    free(ed);
    for (int c = code; c > 0; c /= 10) {
      switch (c % 10) {
      case 1: need_nodes += E; need_elems += 3 * T; E = 2 * E + 3 * T; T *= 4; break;
      case 2: need_nodes += E + T; need_elems += 5 * T; E = 2 * E + 6 * T; T *= 6; break;
      case 3: joints = 1; need_nodes += 3 * T; need_elems += E; E = 3 * T; break;
      case 4: need_nodes += 3 * T; E = 3 * T; break;
      }
    }
    if (code % 10 == 3 || code / 10 % 10 == 3 || joints)
      for (int i = 0; i < k; i++) {
        int p = s[2 + i], found = 0;
        for (long q = 0; q < y->mpmrow; q++)
          if (y->i2pmij[q * 3] == p && y->i2pmij[q * 3 + 1] == p) found = 1;
        /* Y2D looks the row up for the triangles it meshes: a property no element uses needs none */
        if (!found && y->prop_used[p])
          yf_deck_error(&ml, "meshing row %ld joints property %d, but %s has no row '%d %d set' "
                        "(one is needed for every meshed property)", row, p,
                        keydefs[Y2D_PM_I2PMIJ].full, p, p);
      }
  }
  free(sel);
  YfLoc jl = loc_of(y, Y2D_PM_I2PMIJ);
  for (long q = 0; q < y->mpmrow; q++) {
    const int *m = &y->i2pmij[q * 3];
    for (int i = 0; i < 2; i++)
      if (m[i] < 0 || m[i] >= y->nprop)
        yf_deck_error(&jl, "%s: row %ld: property %d outside 0..NPROP-1 = 0..%ld",
                      keydefs[Y2D_PM_I2PMIJ].full, q, m[i], y->nprop - 1);
    if (m[2] < 0 || m[2] >= y->npjset)
      yf_deck_error(&jl, "%s: row %ld: joint set %d outside 0..NPJSET-1 = 0..%ld",
                    keydefs[Y2D_PM_I2PMIJ].full, q, m[2], y->npjset - 1);
  }
  if (joints) {
    if (y->melst < 1)
      yf_warn(&ml, "joint meshing with %s = 0: the anchor crashes (it needs MELST >= 1); "
              "yfdem does not need it", keydefs[Y2D_E_MELST].full);
    if (y->melno < 4)
      yf_warn(&ml, "joint meshing with %s = %ld: the anchor needs 4 (4-node joints); yfdem "
              "does not need it", keydefs[Y2D_E_MELNO].full, y->melno);
  }
  if (y->melem < need_elems)
    yf_warn(&ml, "%s = %ld is smaller than the about %ld elements after meshing (the anchor "
            "stops with \"MELEM too small\"); yfdem allocates what it needs",
            keydefs[Y2D_E_MELEM].full, y->melem, need_elems);
  if (y->mnopo < need_nodes)
    yf_warn(&ml, "%s = %ld is smaller than the about %ld nodes after meshing (the anchor "
            "stops with \"MNOPO too small\"); yfdem allocates what it needs",
            keydefs[Y2D_N_MNOPO].full, y->mnopo, need_nodes);
  /* The joint sets that can act: named by an I2PMIJ row of two properties in use (the rows Y2D looks
   * up for the edges it joints).  Those are checked here, in the deck's words and at the value's
   * line (the joint law divides by f_t, f_s or the cohesion, G_f and the penalty: Y2D's joints turn to
   * NaN without them); a spare set (NPJSET above the sets in use, left at its defaults) is never
   * evaluated by Y2D: one warning, and read_y2d does not build it. */
  unsigned char *su = y->pjset_used = yf_calloc((size_t)y->npjset + 1, 1, "y2d used joint sets");
  for (long q = 0; q < y->mpmrow; q++) {
    const int *m = &y->i2pmij[q * 3];
    if (y->prop_used[m[0]] && y->prop_used[m[1]]) su[m[2]] = 1;
  }
  long nspare = 0, spare0 = -1;
  for (long j = 0; j < y->npjset; j++) {
    if (!su[j]) {
      if (!nspare++) spare0 = j;
      continue;
    }
    YfLoc tl = value_loc(y, Y2D_PJ_I1PTYP, j);
    if (y->pj_i1ptyp[j] != 3)
      yf_deck_error(&tl, "%s: joint set %ld has type %d; 2D joint sets must be 3 (YTE2JOINTS)",
                    keydefs[Y2D_PJ_I1PTYP].full, j, y->pj_i1ptyp[j]);
    static const struct {
      int key;
      const char *what;
    } pos[] = {{Y2D_PJ_D1PJFT, "tensile strength f_t [Pa]: the peak opening 2 h f_t / p and the softening length "
                               "3 G_f / f_t divide by it"},
               {Y2D_PJ_D1PJGF, "fracture energy G_f [J/m^2]: the softening length is 3 G_f / f_t"},
               {Y2D_PJ_D1PJPE, "joint penalty p [Pa]: the peak openings 2 h f_t / p and 2 h f_s / p divide by it"}};
    for (size_t i = 0; i < sizeof pos / sizeof pos[0]; i++) {
      const double v = (*(double **)((char *)y + keydefs[pos[i].key].off))[j];
      if (!(v > 0)) {
        YfLoc l = value_loc(y, pos[i].key, j);
        yf_deck_error(&l, "%s: joint set %ld has %g%s; it must be > 0 (the %s)", keydefs[pos[i].key].full, j, v,
                      j >= y->nread[pos[i].key] ? " (not given: the default)" : "", pos[i].what);
      }
    }
    if (!(y->d1pjfs[j] > 0) && !(y->d1pjco[j] > 0)) {
      YfLoc l = value_loc(y, Y2D_PJ_D1PJFS, j);
      yf_deck_error(&l, "%s: joint set %ld has shear strength %g and cohesion %s %g: one must be > 0 (with "
                    "D1PJFS <= 0 Y2D starts from the cohesion; the shear softening length 3 G_f / f_s divides "
                    "by it)", keydefs[Y2D_PJ_D1PJFS].full, j, y->d1pjfs[j], keydefs[Y2D_PJ_D1PJCO].full,
                    y->d1pjco[j]);
    }
  }
  if (nspare) {
    YfLoc l = loc_of(y, Y2D_PJ_NPJSET);
    yf_warn(&l, "%s = %ld: %ld joint set%s (first: set %ld) named by no %s row of two properties in use: not "
            "checked, and without effect", keydefs[Y2D_PJ_NPJSET].full, y->npjset, nspare, nspare == 1 ? "" : "s",
            spare0, keydefs[Y2D_PM_I2PMIJ].full);
  }
}

/* Meshing code 0: Y2D reads it as "no meshing for this property" (a MATLAB generator writes
 * every row as `1 0 p`).  The row is dropped (its count set to 0) after a warning, so that its
 * properties stay unmeshed bodies everywhere downstream. */
static void drop_code0_rows(YfY2d *y) {
  char rows[160] = "";
  size_t n = 0;
  long nrow = 0;
  for (long row = 0; row < y->mpmcom; row++) {
    int *s = &y->i2pmset[row * y->mpmcol];
    if (s[0] <= 0 || s[1] != 0) continue;
    if (n + 24 < sizeof rows)
      n += (size_t)snprintf(rows + n, sizeof rows - n, "%s%ld", nrow ? " " : "", row);
    else if (!strstr(rows, "..."))
      n += (size_t)snprintf(rows + n, sizeof rows - n, " ...");
    nrow++;
    s[0] = 0;
  }
  if (!nrow) return;
  YfLoc ml = loc_of(y, Y2D_PM_I2PMSET);
  yf_warn(&ml, "%s: meshing code 0 in %ld row(s) (%s): read as \"no meshing for these "
          "properties\", as Y2D does: no joints are inserted, their triangles stay unjointed",
          keydefs[Y2D_PM_I2PMSET].full, nrow, rows);
}

YfLoc y2d_value_loc(const YfY2d *y, int key, long m) { return value_loc(y, key, m); }

static void check_nonneg(const YfY2d *y, int k, const double *a, long n, const char *what) {
  for (long i = 0; i < n; i++)
    if (a[i] < 0) {
      YfLoc l = value_loc(y, k, i); /* 1D arrays: value i is the i-th read */
      yf_deck_error(&l, "%s: %s %ld has the negative value %g", keydefs[k].full, what, i, a[i]);
    }
}

static void check_deck(YfY2d *y) {
  YfLoc end = y->end;
  /* ---- sizes (Yck) ---- */
  require(y, Y2D_N_MNODIM, "space dimension, 2");
  if (y->mnodim != 2 || (y->given[Y2D_N_NNODIM] && y->nnodim != 2)) {
    YfLoc l = loc_of(y, y->given[Y2D_N_NNODIM] && y->nnodim != 2 ? Y2D_N_NNODIM : Y2D_N_MNODIM);
    yf_deck_error(&l, "%s = %ld, %s = %ld: yfdem reads 2D decks only (NNODIM must be 2, and "
                  "MNODIM, a capacity, at least 2)", keydefs[Y2D_N_MNODIM].full, y->mnodim,
                  keydefs[Y2D_N_NNODIM].full, y->nnodim);
  }
  static const struct {
    int m, n;
    long min;
  } pairs[] = {{Y2D_E_MELEM, Y2D_E_NELEM, 1}, {Y2D_E_MELNO, Y2D_E_NELNO, 1},
               {Y2D_N_MNOPO, Y2D_N_NNOPO, 1}, {Y2D_PE_MPROP, Y2D_PE_NPROP, 1},
               {Y2D_PN_MPNSET, Y2D_PN_NPNSET, 1}, {Y2D_PJ_MPJSET, Y2D_PJ_NPJSET, 0},
               {Y2D_E_MELST, Y2D_E_NELST, 0}, {Y2D_PN_MPNFACT, Y2D_PN_NPNFACT, 0},
               {Y2D_O_MOHYS, Y2D_O_NOHYS, 0}};
  for (size_t i = 0; i < sizeof pairs / sizeof pairs[0]; i++) {
    long m = scalar_long(y, pairs[i].m), n = scalar_long(y, pairs[i].n);
    if (pairs[i].min > 0) {
      require(y, pairs[i].m, "a capacity");
      require(y, pairs[i].n, "a count");
      if (n < pairs[i].min) {
        YfLoc l = loc_of(y, pairs[i].n);
        yf_deck_error(&l, "%s = %ld must be >= %ld%s", keydefs[pairs[i].n].full, n, pairs[i].min,
                      pairs[i].n == Y2D_PN_NPNSET ? " (every node needs a boundary-condition set; "
                      "without one the anchor crashes)" : "");
      }
    }
    if (n > m) {
      YfLoc l = loc_of(y, pairs[i].n);
      yf_deck_error(&l, "%s = %ld exceeds its capacity %s = %ld", keydefs[pairs[i].n].full, n,
                    keydefs[pairs[i].m].full, m);
    }
  }
  if (y->nelno != 3) {
    YfLoc l = loc_of(y, Y2D_E_NELNO);
    yf_deck_error(&l, "%s = %ld: input elements must be 3-node triangles (NELNO 3)",
                  keydefs[Y2D_E_NELNO].full, y->nelno);
  }
  if (y->melno < 3) {
    YfLoc l = loc_of(y, Y2D_E_MELNO);
    yf_deck_error(&l, "%s = %ld: must be >= NELNO = 3", keydefs[Y2D_E_MELNO].full, y->melno);
  }
  require(y, Y2D_E_I2ELTO, "element topology");
  require(y, Y2D_E_I1ELPR, "element properties");
  require(y, Y2D_N_D2NCI, "initial node coordinates");
  require(y, Y2D_N_I1NOPR, "boundary-condition set of each node");
  require(y, Y2D_PE_I1PTYP, "element property type");
  require(y, Y2D_PE_D1PERO, "density");
  require(y, Y2D_PE_D1PELA, "Lame lambda");
  require(y, Y2D_PE_D1PEMU, "Lame mu");
  if (y->mcstep > y->ncstep && y->dcstec <= 0)
    yf_deck_error(&end, "%s (the time step) is required and must be > 0 when %s > %s",
                  keydefs[Y2D_C_DCSTEC].full, keydefs[Y2D_C_MCSTEP].full,
                  keydefs[Y2D_C_NCSTEP].full);
  if (y->mcstep <= y->ncstep)
    yf_warn(&end, "%s = %ld <= %s = %ld: no time step will be computed",
            keydefs[Y2D_C_MCSTEP].full, y->mcstep, keydefs[Y2D_C_NCSTEP].full, y->ncstep);

  /* ---- elements ---- */
  YfLoc tl = loc_of(y, Y2D_E_I2ELTO), pl = loc_of(y, Y2D_E_I1ELPR);
  if (y->nread[Y2D_E_I2ELTO] < y->nelem)
    yf_deck_error(&tl, "%s gives %ld elements, NELEM = %ld", keydefs[Y2D_E_I2ELTO].full,
                  y->nread[Y2D_E_I2ELTO], y->nelem);
  if (y->nread[Y2D_E_I1ELPR] < y->nelem)
    yf_deck_error(&pl, "%s gives %ld values, NELEM = %ld", keydefs[Y2D_E_I1ELPR].full,
                  y->nread[Y2D_E_I1ELPR], y->nelem);
  if (y->nread[Y2D_N_D2NCI] < y->nnopo) {
    YfLoc l = loc_of(y, Y2D_N_D2NCI);
    yf_deck_error(&l, "%s gives %ld nodes, NNOPO = %ld", keydefs[Y2D_N_D2NCI].full,
                  y->nread[Y2D_N_D2NCI], y->nnopo);
  }
  long nbad = 0, first_bad = -1;
  double first_area = 0;
  for (long e = 0; e < y->nelem; e++) {
    const int *v = &y->i2elto[e * y->melno];
    for (int k = 0; k < 3; k++)
      if (v[k] < 0 || v[k] >= y->nnopo)
        yf_deck_error(&tl, "%s: element %ld: node %d (slot %d) outside 0..NNOPO-1 = 0..%ld",
                      keydefs[Y2D_E_I2ELTO].full, e, v[k], k, y->nnopo - 1);
    if (v[0] == v[1] || v[1] == v[2] || v[0] == v[2])
      yf_deck_error(&tl, "%s: element %ld repeats a node (%d %d %d)", keydefs[Y2D_E_I2ELTO].full,
                    e, v[0], v[1], v[2]);
    int p = y->i1elpr[e];
    if (p < 0 || p >= y->nprop)
      yf_deck_error(&pl, "%s: element %ld: property %d outside 0..NPROP-1 = 0..%ld",
                    keydefs[Y2D_E_I1ELPR].full, e, p, y->nprop - 1);
    const double *a = &y->d2nci[2 * v[0]], *b = &y->d2nci[2 * v[1]], *c = &y->d2nci[2 * v[2]];
    double area2 = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
    if (!(area2 > 0)) {
      if (!nbad) first_bad = e, first_area = area2 / 2;
      nbad++;
    }
  }
  if (nbad)
    yf_deck_error(&tl, "%s: %ld element(s) not counter-clockwise, first element %ld (signed "
                  "area %g from D2NCI); Y2D needs counter-clockwise triangles (FORMAT.md 5.1)",
                  keydefs[Y2D_E_I2ELTO].full, nbad, first_bad, first_area);
  /* D2NCC, the current coordinates (a pre-strained start): every node given, and every triangle of
   * positive area there too.  A shorter list leaves the other nodes at (0, 0), the array's default,
   * and a triangle inverted or flat at the start has J <= 0: the run failed at step 0 with "the
   * strain energy overflows the range of a double", without the deck's place. */
  if (y->given[Y2D_N_D2NCC]) {
    YfLoc cl = loc_of(y, Y2D_N_D2NCC);
    if (y->nread[Y2D_N_D2NCC] < y->nnopo)
      yf_deck_error(&cl, "%s gives %ld nodes, NNOPO = %ld: the others would start at (0, 0), the array's default "
                    "(give every node, or leave D2NCC out: it is then D2NCI)", keydefs[Y2D_N_D2NCC].full,
                    y->nread[Y2D_N_D2NCC], y->nnopo);
    for (long e = 0; e < y->nelem; e++) {
      const int *v = &y->i2elto[e * y->melno];
      const double *a = &y->d2ncc[2 * v[0]], *b = &y->d2ncc[2 * v[1]], *c = &y->d2ncc[2 * v[2]];
      double area2 = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
      if (!(area2 > 0))
        yf_deck_error(&cl, "%s: element %ld (nodes %d %d %d) has the signed area %g in the current coordinates: "
                      "%s at the start (its area from D2NCI is positive); a pre-strained start needs every "
                      "triangle counter-clockwise", keydefs[Y2D_N_D2NCC].full, e, v[0], v[1], v[2], area2 / 2,
                      area2 < 0 ? "inverted" : "flat");
    }
  }

  /* ---- element properties ---- */
  /* A property no element uses is never evaluated by Y2D (its force loop runs over the elements of
   * each property): a deck with NPROP above the properties in use, the spare ones left at their
   * defaults (type -1, density 0), runs in Y2D.  Its type and density are not checked (one warning),
   * as read_y2d only refuses rigid and softening triangles that are used. */
  /* kept in y (freed with its arrays): an error below exits with it reachable */
  unsigned char *used = y->prop_used = yf_calloc((size_t)y->nprop + 1, 1, "y2d used properties");
  for (long e = 0; e < y->nelem; e++) used[y->i1elpr[e]] = 1; /* each in 0..NPROP-1 (checked above) */
  long nunused = 0, unused0 = -1;
  for (long p = 0; p < y->nprop; p++)
    if (!used[p] && !nunused++) unused0 = p;
  if (nunused) {
    YfLoc l = loc_of(y, Y2D_PE_NPROP);
    yf_warn(&l, "%s = %ld: %ld propert%s (first: property %ld, type %d) used by no element: not checked, and "
            "without effect (Y2D evaluates properties through their elements)", keydefs[Y2D_PE_NPROP].full,
            y->nprop, nunused, nunused == 1 ? "y" : "ies", unused0, y->pe_i1ptyp[unused0]);
  }
  for (long p = 0; p < y->nprop; p++) {
    int t = y->pe_i1ptyp[p];
    YfLoc tyl = value_loc(y, Y2D_PE_I1PTYP, p);
    if (!used[p]) continue;
    if (t == 3)
      yf_deck_error(&tyl, "%s: property %ld has type 3 (YTE2JOINTS), a joint type: it belongs in "
                    "/YD/YDPJ/I1PTYP; triangles are 1 (elastic), 2 (rigid) or 4 (softening)",
                    keydefs[Y2D_PE_I1PTYP].full, p);
    if (t == 11 || t == 13 || t == 21 || t == 23)
      yf_deck_error(&tyl, "%s: property %ld has the 3D type %d; 2D types are 1, 2, 4",
                    keydefs[Y2D_PE_I1PTYP].full, p, t);
    if (t != 1 && t != 2 && t != 4)
      yf_deck_error(&tyl, "%s: property %ld has type %d (valid: 1 elastic, 2 rigid, 4 softening "
                    "triangle)", keydefs[Y2D_PE_I1PTYP].full, p, t);
    if (t == 4)
      yf_warn(&tyl, "%s: property %ld is a softening triangle (type 4, legacy)",
              keydefs[Y2D_PE_I1PTYP].full, p);
    if (t == 1 && !(y->d1pero[p] > 0)) {
      YfLoc l = value_loc(y, Y2D_PE_D1PERO, p);
      yf_deck_error(&l, "%s: property %ld (elastic) has density %g; it must be > 0",
                    keydefs[Y2D_PE_D1PERO].full, p, y->d1pero[p]);
    }
  }
  check_nonneg(y, Y2D_PE_D1PEFR, y->d1pefr, y->nprop, "property");
  check_nonneg(y, Y2D_PE_D1PEKS, y->d1peks, y->nprop, "property");
  /* D1PELA may be negative (a material of negative Poisson's ratio, from another writer): the
   * bulk modulus it must keep positive depends on read_y2d's volfac, checked there (y2d_model.c).  Y2D's
   * own check refuses it (FORMAT.md 6): said, once, at the first such value */
  for (long p = 0; p < y->nprop; p++)
    if (y->d1pela[p] < 0) {
      YfLoc l = value_loc(y, Y2D_PE_D1PELA, p);
      yf_warn(&l, "%s: property %ld has the negative value %g: yfdem runs it (negative Poisson's ratio), but Y2D "
              "refuses a negative D1PELA in its check after $YDOIT (Yck) and computes nothing", keydefs[Y2D_PE_D1PELA].full,
              p, y->d1pela[p]);
      break;
    }
  check_nonneg(y, Y2D_PE_D1PEMU, y->d1pemu, y->nprop, "property");
  check_nonneg(y, Y2D_PE_D1PERO, y->d1pero, y->nprop, "property");
  check_nonneg(y, Y2D_PE_D1PEPE, y->d1pepe, y->nprop, "property");
  check_nonneg(y, Y2D_PE_D1PEPT, y->d1pept, y->nprop, "property");

  /* ---- contact ---- */
  if (y->micoup > 0) {
    if (y->mistate < 6) {
      YfLoc l = loc_of(y, Y2D_I_MISTATE);
      yf_deck_error(&l, "%s = %ld with %s = %ld: contact needs MISTATE >= 6 (sliding state per "
                    "couple and edge; the anchor crashes otherwise)", keydefs[Y2D_I_MISTATE].full,
                    y->mistate, keydefs[Y2D_I_MICOUP].full, y->micoup);
    }
    if (!y->given[Y2D_PE_D1PEPT])
      yf_deck_error(&end, "%s (tangential contact penalty) is required when %s = %ld > 0 (the "
                    "anchor crashes without it)", keydefs[Y2D_PE_D1PEPT].full,
                    keydefs[Y2D_I_MICOUP].full, y->micoup);
    if (!y->given[Y2D_PE_D1PEPE])
      yf_warn(&end, "%s (normal contact penalty) not given: 0 for every property (no contact "
              "force)", keydefs[Y2D_PE_D1PEPE].full);
  }

  /* ---- joints and meshing ---- */
  check_nonneg(y, Y2D_PJ_D1PJFT, y->d1pjft, y->npjset, "joint set");
  check_nonneg(y, Y2D_PJ_D1PJGF, y->d1pjgf, y->npjset, "joint set");
  check_nonneg(y, Y2D_PJ_D1PJPE, y->d1pjpe, y->npjset, "joint set");
  check_nonneg(y, Y2D_PJ_D1PJCO, y->d1pjco, y->npjset, "joint set");
  check_nonneg(y, Y2D_PJ_D1PJFR, y->d1pjfr, y->npjset, "joint set");
  int meshed_any = 0;
  if (y->given[Y2D_PM_I2PMSET]) {
    drop_code0_rows(y);
    check_meshing(y);
    meshed_any = 1;
  }

  /* ---- boundary-condition sets ---- */
  for (long s = 0; s < y->npnset; s++) {
    double xx = y->d1pnxx[s], xy = y->d1pnxy[s], yx = y->d1pnyx[s], yy = y->d1pnyy[s];
    double lx = hypot(xx, xy), ly = hypot(yx, yy);
    YfLoc l = loc_of(y, Y2D_PN_D1PNXX);
    if (lx == 0 || ly == 0)
      yf_deck_error(&l, "BC set %ld: local axis %s is zero (D1PNXX/XY = %g %g, D1PNYX/YY = %g %g)",
                    s, lx == 0 ? "x" : "y", xx, xy, yx, yy);
    if (fabs(xx * yx + xy * yy) > 1e-6 * lx * ly)
      yf_deck_error(&l, "BC set %ld: local axes not orthogonal (x = (%g, %g), y = (%g, %g))", s, xx,
                    xy, yx, yy);
    const int kinds[2] = {y->i1pnfx[s], y->i1pnfy[s]};
    const int kk[2] = {Y2D_PN_I1PNFX, Y2D_PN_I1PNFY}, ak[2] = {Y2D_PN_D1PNAX, Y2D_PN_D1PNAY};
    for (int d = 0; d < 2; d++) {
      YfLoc kl = loc_of(y, kk[d]);
      if (kinds[d] < 1 || kinds[d] > 3)
        yf_warn(&kl, "BC set %ld: %s = %d%s: the velocity in local %c of its nodes stays at its "
                "initial value and forces are ignored (1 force, 2 acceleration, 3 velocity)", s,
                keydefs[kk[d]].name, kinds[d], s >= y->nread[kk[d]] ? " (default)" : "", "xy"[d]);
      if (kinds[d] == 1 && s >= y->nread[ak[d]])
        yf_warn(&kl, "BC set %ld: force kind in local %c but %s left at its default 1.0: a force "
                "of 1 unit acts on every node of the set", s, "xy"[d], keydefs[ak[d]].name);
    }
  }
  /* a set outside 0..NPNSET-1 given in the list freezes its node (FORMAT.md 6: Y2D never moves
   * it), an idiom: warned once; one the list leaves out (shorter than NNOPO) is a mistake */
  long nfrozen = 0, n0 = -1, nmoving = 0; /* nmoving: 1 + the first frozen node with a velocity */
  for (long n = 0; n < y->nnopo; n++) {
    int s = y->i1nopr[n];
    if (s >= 0 && s < y->npnset) continue;
    if (n >= y->nread[Y2D_N_I1NOPR]) {
      YfLoc nl = value_loc(y, Y2D_N_I1NOPR, n);
      yf_deck_error(&nl, "%s: node %ld has no BC set (not given: the list is shorter than NNOPO = %ld; the "
                    "anchor would never move this node)", keydefs[Y2D_N_I1NOPR].full, n, y->nnopo);
    }
    if (!nfrozen++) n0 = n;
    if (nmoving == 0 && (y->d2nvc[2 * n] != 0.0 || y->d2nvc[2 * n + 1] != 0.0)) nmoving = n + 1;
  }
  if (nfrozen) {
    YfLoc nl = value_loc(y, Y2D_N_I1NOPR, n0);
    yf_warn(&nl, "%s: %ld node%s (first: node %ld, set %d) %s a BC set outside 0..NPNSET-1 = 0..%ld: frozen, as "
            "Y2D never moves such a node%s", keydefs[Y2D_N_I1NOPR].full, nfrozen, nfrozen == 1 ? "" : "s", n0,
            y->i1nopr[n0], nfrozen == 1 ? "has" : "have", y->npnset - 1,
            nmoving ? "; one has an initial velocity (D2NVC), which Y2D keeps in the kinetic energy and the viscous term "
                      "while the node stays put: the energy balance books that as energy from nowhere and may stop the "
                      "run (give it velocity 0, or 'energy_check warn' in a deck that reads this one)" : "");
  }

  /* ---- time tables ---- */
  if (y->given[Y2D_PN_D3PNFAC] && y->npnfact > 0) {
    YfLoc fl = loc_of(y, Y2D_PN_D3PNFAC);
    if (y2d_fac_time(y, 0, 0) == -1) {
      y->tables_on = 0;
      yf_warn(&fl, "%s: the first time of set 0 is -1: all time tables are switched off",
              keydefs[Y2D_PN_D3PNFAC].full);
    } else {
      y->tables_on = 1;
      double tend = y->dctime + (double)(y->mcstep - y->ncstep) * y->dcstec;
      for (long s = 0; s < y->npnset && s < y->mpnset; s++) {
        for (long p = 1; p < y->npnfact; p++)
          if (y2d_fac_time(y, s, p) < y2d_fac_time(y, s, p - 1))
            yf_warn(&fl, "%s: set %ld: times decrease at point %ld (%g after %g)",
                    keydefs[Y2D_PN_D3PNFAC].full, s, p, y2d_fac_time(y, s, p),
                    y2d_fac_time(y, s, p - 1));
        double last = y2d_fac_time(y, s, y->npnfact - 1);
        if (last < tend && y2d_fac_value(y, s, y->npnfact - 1) != 1.0)
          yf_warn(&fl, "%s: set %ld: the table ends at t = %g before the end of the run (t = %g); "
                  "after it the factor is 1.0, not the last value (Y2D rule)",
                  keydefs[Y2D_PN_D3PNFAC].full, s, last, tend);
      }
    }
  } else if (y->given[Y2D_PN_D3PNFAC]) {
    YfLoc fl = loc_of(y, Y2D_PN_D3PNFAC);
    yf_warn(&fl, "%s given but %s = 0: no time tables", keydefs[Y2D_PN_D3PNFAC].full,
            keydefs[Y2D_PN_NPNFACT].full);
  }

  /* ---- contact participation (FORMAT.md 5.3): the model (y2d_model.c) takes every triangle with IWFAST 0
   * only, so any other value, below 0 too, leaves unflagged boundaries out of contact ---- */
  if (y->micoup > 0 && y->iwfast != 0) {
    unsigned char *sel = yf_calloc((size_t)y->nelem + 1, 1, "y2d selection");
    for (long e = 0; e < y->nelem; e++) {
      int meshed = 0;
      if (meshed_any)
        for (long row = 0; row < y->mpmcom; row++)
          if (row_has_prop(y, row, y->i1elpr[e])) meshed = 1;
      sel[e] = (unsigned char)!meshed;
    }
    long ne, nflag = 0, first = -1;
    Edge *ed = edge_list(y, sel, &ne);
    /* a node ends two boundary edges (or more): counted once, where it is first met */
    unsigned char *seen = yf_calloc((size_t)y->nnopo + 1, 1, "y2d boundary nodes");
    for (long i = 0; i < ne; i++) {
      int single = (i == 0 || ed[i].lo != ed[i - 1].lo || ed[i].hi != ed[i - 1].hi) &&
                   (i + 1 == ne || ed[i].lo != ed[i + 1].lo || ed[i].hi != ed[i + 1].hi);
      if (!single) continue;
      for (int q = 0; q < 2; q++) {
        int n = q ? ed[i].hi : ed[i].lo;
        if (y->i1nobf[n] != 1 && !seen[n]) {
          seen[n] = 1;
          if (first < 0) first = n;
          nflag++;
        }
      }
    }
    free(seen);
    free(ed);
    free(sel);
    if (nflag) {
      YfLoc l = loc_of(y, Y2D_N_I1NOBF);
      yf_warn(&l, "%ld boundary node(s) of unjointed bodies have %s != 1 (first: node %ld): with "
              "IWFAST = %ld (not 0) their triangles take no part in contact, as in Y2D with IWFAST > 0", nflag,
              keydefs[Y2D_N_I1NOBF].full, first, y->iwfast);
    }
  }

  /* ---- misc ---- */
  if (y->nohys > 0) {
    YfLoc l = loc_of(y, Y2D_O_NOHYS);
    yf_warn(&l, "%s = %ld history variables: read, but yfdem does not write Y2D's history files "
            "(<deck>h<i>); sample with a dump instead (dump ID y2dref DIR ... probes K E:C, or "
            "csv)", keydefs[Y2D_O_NOHYS].full, y->nohys);
  }
  if (y->dcgrax != 0 || y->dcgraz != 0) {
    YfLoc l = loc_of(y, y->dcgrax != 0 ? Y2D_C_DCGRAX : Y2D_C_DCGRAZ);
    yf_warn(&l, "DCGRAX/DCGRAZ are used only in 3D: ignored (2D gravity is DCGRAY)");
  }
  if (y->icoutf <= 0) y->icoutf = 10; /* the anchor's rule */
}

/* MNODIM is a capacity (rows of the node arrays), NNODIM the dimension in use: generators (a GiD
 * template, a C++ writer) write MNODIM 3 with NNODIM 2 and Y2D runs such a deck in 2D.  yfdem
 * keeps x, y only: the node arrays are repacked from MNODIM rows to 2 (the layout of
 * y2d_read.h) and MNODIM becomes 2, after a warning that names what was dropped. */
static void narrow_node_dim(YfY2d *y) {
  long md = y->mnodim;
  if (md <= 2 || !y->given[Y2D_N_NNODIM] || y->nnodim != 2) return; /* check_deck refuses */
  static const int keys[] = {Y2D_N_D2NCI, Y2D_N_D2NCC, Y2D_N_D2NVC};
  long nz = 0;
  for (size_t q = 0; q < sizeof keys / sizeof keys[0]; q++) {
    double *a = *(double **)((char *)y + keydefs[keys[q]].off);
    for (long i = 0; i < y->mnopo; i++) {
      for (long d = 2; d < md; d++) nz += a[i * md + d] != 0;
      a[2 * i] = a[i * md];
      a[2 * i + 1] = a[i * md + 1];
    }
  }
  YfLoc l = loc_of(y, Y2D_N_MNODIM);
  yf_warn(&l, "%s = %ld with %s = 2: MNODIM is a capacity, the deck is 2D; only x and y of the "
          "node arrays are kept%s", keydefs[Y2D_N_MNODIM].full, md, keydefs[Y2D_N_NNODIM].full,
          nz ? " (non-zero third components were given and are ignored, as in 2D Y2D)" : "");
  y->mnodim = 2;
}

/* ------------------------------------------------------------------ public */

int y2d_is_y_file(const char *path) {
  size_t n = path ? strlen(path) : 0;
  return n > 2 && !strcmp(path + n - 2, ".y");
}

static int read_deck(const char *path, YfY2d *out, const YfLoc *from, int program);
int y2d_read(const char *path, YfY2d *out, const YfLoc *from) { return read_deck(path, out, from, 0); }
int y2d_read_program(const char *path, YfY2d *out, const YfLoc *from) { return read_deck(path, out, from, 1); }

static int read_deck(const char *path, YfY2d *out, const YfLoc *from, int program) {
  memset(out, 0, sizeof *out);
  for (int k = 0; k < Y2D_NKEYS; k++) {
    const KeyDef *kd = &keydefs[k];
    if (kd->off == NOFF) continue;
    if (kd->type == KI) *(long *)((char *)out + kd->off) = (long)kd->def;
    else if (kd->type == KR) *(double *)((char *)out + kd->off) = kd->def;
  }
  FILE *fp = yf_open_input(path, "r");
  if (!fp) yf_io_error(from, "cannot open Y2D deck '%s': %s", path, strerror(errno));
  Rd r;
  memset(&r, 0, sizeof r);
  r.y = out;
  r.program = program;
  r.last_key = -1;
  push_file(&r, fp, path);
  r.loc.file = out->files[0];
  r.loc.line = 1;
  read_tokens(&r);
  while (r.depth > 0) fclose(r.src[--r.depth].fp);
  free(r.tok);
  out->tok_scratch = NULL;
  if (program && !out->has_ydoit) {
    yf_warn(&out->end, "nothing is computed: the deck has no $YDOIT before %s, and Y2D reads it and stops "
            "without computing; put $YDOIT before $YSTOP to run it", out->ystop ? "its $YSTOP" : "its end");
    return 1;
  }
  /* arrays never given: allocate at capacity with their defaults */
  for (int k = 0; k < Y2D_NKEYS; k++) {
    const KeyDef *kd = &keydefs[k];
    if (kd->off == NOFF || !ndims(kd->type)) continue;
    if (!*(void **)((char *)out + kd->off)) alloc_array(out, k);
  }
  narrow_node_dim(out);
  if (!out->given[Y2D_N_D2NCC])
    memcpy(out->d2ncc, out->d2nci, (size_t)(out->mnopo * (out->mnodim > 0 ? out->mnodim : 0)) *
                                       sizeof(double));
  check_deck(out);
  return 0;
}

void y2d_free_arrays(YfY2d *y) {
  if (!y) return;
  for (int k = 0; k < Y2D_NKEYS; k++) {
    const KeyDef *kd = &keydefs[k];
    if (kd->off == NOFF || !ndims(kd->type)) continue;
    void **pp = (void **)((char *)y + kd->off);
    free(*pp);
    *pp = NULL;
  }
  free(y->prop_used);
  y->prop_used = NULL;
  free(y->pjset_used);
  y->pjset_used = NULL;
  free(y->vline); /* only the checks after reading place values on their lines */
  y->vline = NULL;
  y->nvline = y->capvline = 0;
}

void y2d_free(YfY2d *y) {
  if (!y) return;
  y2d_free_arrays(y);
  free(y->tok_scratch);
  y->tok_scratch = NULL;
  for (int i = 0; i < y->nfiles; i++) free(y->files[i]);
  free(y->files);
  y->files = NULL;
  y->nfiles = 0;
}
