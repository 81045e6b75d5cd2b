#!/usr/bin/env python3
"""Convert a Y2D input deck (.y) into an equivalent, readable yfdem deck.

usage: y2d2deck.py [--allow-differences] DECK.y OUT
  writes OUT.deck plus OUT.nodes (rows "id x y") and OUT.tris (rows "id n1 n2 n3 material"): the
  Y2D nodes and elements in input order, ids = the Y2D indices (0-based), one body 'y2d', so the
  converted deck sums forces in the order `yfdem DECK.y` does and results compare by id.  OUT.deck
  names its files in quotes ('...', or "..." when the name holds a single quote), so OUT may hold
  spaces, '#' and '$'; an OUT with both a single quote and a '$' or '"' cannot be quoted: exit 1.

Exit status: 0 the converted deck runs the physics of `yfdem DECK.y`; 1 error (a key Y2D does not
read, a value that is not a number, or not an integer where Y2D reads one, a density, bulk modulus
or joint strength, energy or penalty of a property or joint set in use that is not positive (and a shear
modulus D1PEMU of 0, which yfdem DECK.y runs as Y2D does and no native material takes), no
time step or one below the resolution of the start time DCTIME (DCTIME + DCSTEC == DCTIME), MISTATE < 6 with contact, an element property out of range, NELNO other than 3, a 3D
deck, a clockwise triangle, a zero BC axis, a D2NCC short of NNOPO or with a triangle inverted or flat,
a joint set out of range or not of type 3, a property
type other than 1, 2, 4, a negative property value, a count above its capacity (NNOPO > MNOPO) or an
array longer than its capacity, a node coordinate or velocity beyond +-1e100, as yfdem's reader
refuses them (its words, its FILE:LINE); a file: no OUT.deck written); 2 bad usage; 3 the deck is written
but does not run the same physics: each difference is a line "warning: DECK: ..." on stderr and a
"DIFFERS:" note at the top of OUT.deck (stdout: "wrote OUT.deck (N differences of physics, W
warnings, M notes)").  --allow-differences accepts them: exit 0, the warnings stay.  Notes of exact
translations (written in OUT.deck only) do not count.  A warning of the same physics told differently
(NCSTEP > 0: step numbers; "nothing is computed" for a .y with no key and no $YDOIT, whose OUT.deck
computes nothing and says so, as yfdem DECK.y warns and exits 0) is a line "warning: FILE:LINE: ..."
and a "WARNING:" note in OUT.deck, exit 0.

The converted deck runs the physics of `yfdem DECK.y` (tests/convert/run compares the final
energies, broken joints and contact pairs of the four shared decks and of the small decks in
tests/convert/decks: within 1e-11 of the energy scale, not bitwise, since the native velocity update
is not Y2D's BC-set update).

What is translated (native syntax = the SYNTAX dict below, one place to adapt):
  DCSTEC                     -> timestep DT above_limit warn (a step above yfdem's
                                limit warns, as for `yfdem DECK.y`; the energy check still stops a divergence)
  MCSTEP - NCSTEP            -> run N (a native deck counts its steps from 0 and no command sets the
                                counter: NCSTEP > 0 is a warning, exit 0: the same physics, step
                                numbers lower by NCSTEP than those of `yfdem DECK.y`)
  DCTIME (start time)        -> no native start time: every time table is shifted by -DCTIME (the
                                native time is the Y2D time - DCTIME; thermo/summary times too)
  ICSHTF / ICOUTF            -> thermo N (ICSHTF <= 0: thermo 0) / dump ID h5 N FILE
  DCGRAY                     -> gravity 0 G  (Y2D applies it to BC kinds 1 and 2 only; the nodes of
                                the other kinds are held or driven by a fix, which overrides it)
  /YD/YDPE/ property p       -> material p<p> elastic rho R lambda L mu M visc K volfac 0.5
                                pen_n PE pen_t PT friction FR friction_law y2d  (Y2D's law uses
                                lambda/2: volfac 0.5; Y2D's contact friction, not the native Coulomb)
  joint set j (/YD/YDPJ/)    -> jointprop j<j> ft [fs] gf pen law munjiza [cohesion C friction MU]
                                damage reversible floor y2d tangent y2d  (Y2D's law: no damage
                                memory, 2 o_p floor, unit tangent e/(h + 1e-10 m)); fs left out when
                                D1PJFS <= 0 < D1PJCO (both then start from the cohesion)
  meshing row r of code 3    -> group row<r> tri id ... (the triangles of its properties) and
                                fracture y2d j<s> group row<r>, s = the I2PMIJ set of its properties
  MICOUP > 0                 -> group contact_tris tri id ... (every triangle, or with IWFAST > 0
                                those with a corner flagged in I1NOBF and those of jointed rows),
                                contact self contact_tris, contact buffer DIEZON joined keep
                                surface all search travel shared keep; nothing when no triangle
                                takes part; triangles of a property with D1PEPE 0 (no force with
                                anyone: Y2D's pair penalty is the smaller D1PEPE) take part with
                                pen_n 0.0, their couples kept (and counted) as Y2D keeps them
  D2NVC                      -> velocity GROUP set VX VY, one group per distinct initial velocity
  BC sets (/YD/YDPN/, global frame only):
    kind 3 (velocity) amp 0 in x and y        -> fix ID GROUP fixed xy   (x or y alone likewise)
    kind 3 amp v                              -> fix ID GROUP velocity VX|NULL VY|NULL [history H]
    other kinds (-1, 0, ...: frozen velocity) -> fixed when the nodes' initial velocity is 0 there,
                                                 else fix ID bc<s>_z<k> velocity V.. per distinct
                                                 initial velocity
    kind 1 (force) amp F != 0                 -> load ID point node N FX FY [history H] per node, F
                                                 times the node's copies c (joint insertion: Y2D
                                                 gives each copy F, `load point` shares F among them)
    kind 2 (acceleration) amp A != 0          -> the same point load with A m, m = the node's lumped
                                                 mass rho A0/3 summed over its triangles (exact when
                                                 its copies have equal masses, else a difference)
    D1PNAP (edge pressure) != 0               -> load ID GROUP pressure P [history H], one per
                                                 (pressure, table) class: GROUP = its set, or the
                                                 union of its sets (group pr<k> union bc<a> bc<b>);
                                                 a D1PNAP or D1PNAT that never exceeds 1e-10 times
                                                 its table loads nothing in Y2D: left out
    kind 1 amp 0                              -> nothing (free)
  D3PNFAC time table of set s  -> history bc<s> table T1 V1 T2 V2 ... with Y2D's factor at every
                                time: 1.0 before the first and after the last time (points of value
                                1.0 one ulp outside), zero-length intervals (a padded table) dropped,
                                a jump at a repeated time one ulp wide
Differences (warnings, exit 3): BC sets with a rotated local frame and conditions of different kinds
in its two directions (one kind in both, force, acceleration or velocity, is that kind in global x and
y with the amplitude turned, R A; frozen in both is the same in any frame), kind 2 on copies of different masses, D1PNAT edge shear
(the native traction keeps its direction), edge pressure on an outer edge between sets of different
pressures or tables (Y2D: linear variation; written as the mean of the two when a group can hold
that edge alone: the same resultant), edge pressure on interior edges of jointed triangles (Y2D
pushes each triangle's copy: not written), an edge between a meshed row and a triangle outside it
(Y2D: separate bodies; `fracture` joins them), refinement codes 1/2/4, a meshing row whose
property pairs use different joint sets, rigid (type 2) and softening (type 4) triangles, time
tables with decreasing times, /YD/YDN/D2NCC (current coordinates) other than D2NCI at a node of a
triangle (`yfdem DECK.y` starts the nodes there, pre-strained; a native node has one position, its
reference: written at D2NCI, the largest difference named).  Not translated, no effect on the
physics: history output /YD/YDO/ (a note), DCSIZ scales (output scales of the book Y), nodes used
by no triangle (massless, a note), joint friction without cohesion (Y2D ignores it too, a note).
Native decks hold at most 64 groups and bodies: a .y with very many BC sets or distinct velocities
gives a deck yfdem refuses.

The .y file is parsed here with the Y2D token rules as yfdem's reader applies them (comments of at
most 100 tokens after '/*', the terminator its own token beginning with '*/', none inside a value
list; $YINCL relative to the working directory or the including file's directory; $YDOIT and $YSTOP
honoured at any include depth, after $YDOIT only comments and $YSTOP, in the including files too;
1D/2D/3D array codes, names compared over the known name's length: /YD/YDC/MCSTEPS is MCSTEP).
A key or group Y2D does not read is refused with FILE:LINE and the nearest key, or as a key or
group of the Y-Geo derivative, as yfdem names them (exit 1, nothing written), and so are a comment inside a value list and one longer than 100 tokens.  Every
other refusal of yfdem's reader (src/y2d/y2d_read.c) is the converter's too, in its words at its FILE:LINE:
the .y is first read by `read_y2d` (reads and checks, computes nothing) of the yfdem in $YFDEM, else the
one built beside tools/, else the first on PATH; without a yfdem, only the checks above are made (a
"note:" line on stderr says so and what to build); a $YFDEM that names no executable file: exit 2.
"""
import argparse
import difflib
import functools
import math
import os
import re
import shutil
import subprocess
import sys

# ---------------------------------------------------------------------------------------------
# Native deck syntax (being finalised by the lead): edit here only.  None = not available, the
# converter writes a comment instead.  Entries with a leading '#' are written commented out.
SYNTAX = {
    'header':    '# converted from {src} by tools/y2d2deck.py',
    'nodes':     'nodes {file} {body}',
    'triangles': 'triangles {file} {body}',
    'material':  'material {name} elastic rho {rho!r} lambda {lam!r} mu {mu!r} visc {visc!r} '
                 'volfac 0.5 pen_n {pen_n!r} pen_t {pen_t!r} friction {fric!r} friction_law y2d',
    'timestep':  'timestep {dt!r} above_limit warn',   # as `yfdem DECK.y`: Y2D never checks dt
    'gravity':   'gravity 0 {gy!r}',
    'group_ids': 'group {name} node id {ids}',
    'velocity':  'velocity {group} set {vx!r} {vy!r}',
    'fix_fixed': 'fix {id} {group} fixed {dirs}',
    'fix_vel':   'fix {id} {group} velocity {vx} {vy}{hist}',
    'load_point': 'load {id} point node {node} {fx!r} {fy!r}{hist}',
    'load_pressure': 'load {id} {group} pressure {p!r}{hist}',
    'history':   'history {name} table {pairs}',
    'hist_opt':  ' history {name}',
    'jointprop': 'jointprop {name} ft {ft!r}{fs} gf {gf!r} pen {pen!r} law munjiza{mc} '
                 'damage reversible floor y2d tangent y2d',
    'jointprop_fs': ' fs {fs!r}',                           # left out when D1PJFS <= 0 < D1PJCO
    'mohr_coulomb': ' cohesion {co!r} friction {fr!r}',   # written when D1PJCO > 0
    'group_tris': 'group {name} tri id {ids}',
    'group_union': 'group {name} union {groups}',
    'fracture':  'fracture {body} {jp} group {group}',
    'contact_self': 'contact self {group}',
    'contact':   'contact buffer {buffer!r} joined keep surface all search travel shared keep',
    'thermo':    'thermo {n}',
    'dump':      'dump d1 h5 {n} {file}',
    'run':       'run {n}',
    'continue':  ' &',     # line continuation of the native deck
}
LINE_MAX = 100
# ---------------------------------------------------------------------------------------------


class DeckError(Exception):
    pass


CONTROL = {}  # deck path -> the control word that ended its reading ($YDOIT or $YSTOP)


COMMENT_MAX = 100  # tokens after a comment's opener, its terminator included (src/y2d/y2d_read.c)
INCL_MAX = 10      # include files nested deeper than 9: refused


class _Src:
    """The token stream of a .y deck and the files it includes, read as yfdem's reader reads it: a
    stack of files, the next token taken from the innermost, a file's end returning to the file that
    included it (so a comment, $YDOIT or $YSTOP count wherever they stand)."""

    def __init__(self, path):
        self.stack = []
        self.last = ('', path, 1)   # the last token read: where yfdem's reader says the deck ends
        self.push(path)

    def push(self, path):
        if len(self.stack) >= INCL_MAX:
            raise DeckError('%s: $YINCL nested deeper than %d' % (path, INCL_MAX - 1))
        # bytes, as the C reader reads them: a UTF-8 byte-order mark skipped, lines ended by LF, CR LF
        # or a CR alone, tokens split at ASCII white space only; any other byte kept in its token (the
        # text was decoded as UTF-8: a comment in Latin-1, 'densit\xe9', stopped the converter with
        # "'utf-8' codec can't decode byte 0xe9", and a BOM made the first token '\ufeff/*')
        with open(path, 'rb') as f:
            data = f.read()
        if data.startswith(b'\xef\xbb\xbf'):
            data = data[3:]
        raw = [(t.decode('utf-8', 'surrogateescape'), path, ln) for ln, line in enumerate(data.splitlines(), 1)
               for t in line.split()]
        self.stack.append([raw, 0])

    def next(self):
        while self.stack:
            raw, i = self.stack[-1]
            if i < len(raw):
                self.stack[-1][1] += 1
                self.last = raw[i]
                return raw[i]
            self.stack.pop()
        return None

    def skip_comment(self, opener):
        """Skip the comment opened by token opener (t, file, line): it ends at the first token that
        begins with '*/', at most COMMENT_MAX tokens after the opener (yfdem's reader)."""
        t, f, ln = opener
        for n in range(1, COMMENT_MAX + 1):
            u = self.next()
            if u is None:
                raise DeckError("%s:%d: unterminated comment '%s': no token beginning with '*/' before the end "
                                "of the input" % (f, ln, t[:70]))
            if u[0].startswith('*/'):
                return
        raise DeckError("%s:%d: comment '%s' longer than %d tokens (the anchor stops with \"too long comment\"; "
                        "yfdem refuses it)" % (f, ln, t[:70], COMMENT_MAX))


def tokens(path):
    """(token, file, line) with $YINCL expanded (Y2D rules, as src/y2d/y2d_read.c reads them); a
    comment becomes one token '/*' (a value list that meets it is refused, as by yfdem).  $YDOIT or
    $YSTOP ends the reading at any include depth; after $YDOIT only comments and $YSTOP may follow,
    in the including files too (a second input section: refused, as by yfdem).  CONTROL[path] says
    which of the two ended the reading."""
    src = _Src(path)
    out = []
    CONTROL[path] = {'ydoit': False, 'ystop': False}
    while True:
        tok = src.next()
        if tok is None:
            break
        t, f, ln = tok
        if t.startswith('/*'):
            src.skip_comment(tok)
            out.append(('/*', f, ln))
        elif t == '$YINCL':
            nxt = src.next()
            if nxt is None or nxt[0].startswith('/YD/') or nxt[0].startswith('$Y'):
                raise DeckError('%s:%d: $YINCL without a file name' % (f, ln))
            name = nxt[0]
            cand = name
            if not os.path.exists(name) and not name.startswith('/'):
                cand = os.path.join(os.path.dirname(f), name)
            if not os.path.exists(cand):
                raise DeckError('%s:%d: $YINCL %s: cannot open it relative to the working directory nor as %s'
                                % (f, ln, name, cand))
            src.push(cand)
        elif t == '$YSTOP':
            CONTROL[path]['ystop'] = True
            break
        elif t == '$YDOIT':
            CONTROL[path]['ydoit'] = True
            while True:
                u = src.next()
                if u is None or u[0] == '$YSTOP':
                    break
                if u[0].startswith('/*'):
                    src.skip_comment(u)
                    continue
                raise DeckError("%s:%d: '%s' after $YDOIT (at %s:%d): multiple input sections (continuing a run "
                                "with changed keys) are not supported, as by yfdem" % (u[1], u[2], u[0], f, ln))
            break
        else:
            out.append(tok)
    CONTROL[path]['end'] = src.last[1:]
    return out


class Keys(dict):
    """The keys read, looked up by Y2D's prefix rule: a name in the deck matches a known name when it
    begins with it (compared over the known name's length, FORMAT.md 1), so /YD/YDC/MCSTEPS is MCSTEP;
    the key read last wins, as in Y2D."""

    def __init__(self):
        dict.__init__(self)
        self.order = []
        self.where = {}   # name -> (file, line) of the key and [(file, line)] of its values in order
        self.warnings = []   # what yfdem's reader warns of while reading (FILE:LINE: text)

    def at(self, key, idx, default):
        """(file, line) of value idx of 1D array key, else of the key, else default."""
        hit = self._find(key)
        if hit is None or hit not in self.where:
            return default
        kpos, vpos = self.where[hit]
        return vpos[idx] if 0 <= idx < len(vpos) else kpos

    def key_at(self, key, default):
        """(file, line) of key, else default."""
        hit = self._find(key)
        return self.where[hit][0] if hit is not None and hit in self.where else default

    def __setitem__(self, key, value):
        if dict.__contains__(self, key):
            self.order.remove(key)
        self.order.append(key)
        dict.__setitem__(self, key, value)

    def _find(self, key):
        grp, name = key.split('/', 1)
        hit = None
        for k in self.order:
            g, n = k.split('/', 1)
            if g == grp and n.startswith(name):
                hit = k
        return hit

    def __contains__(self, key):
        return self._find(key) is not None

    def __getitem__(self, key):
        hit = self._find(key)
        if hit is None:
            raise KeyError(key)
        return dict.__getitem__(self, hit)

    def get(self, key, default=None):
        hit = self._find(key)
        return default if hit is None else dict.__getitem__(self, hit)


# The keys Y2D reads, by group (FORMAT.md; the same table as src/y2d/y2d_read.c's keydefs, which
# tests/convert/run compares with this one).  A name in a deck matches a key when it begins with the
# key's first MATCH characters (the whole key unless 'KEY:MATCH').  Any other key is refused, as
# yfdem and Y2D refuse it: a converter that skipped it silently dropped what the deck meant.
KNOWN = {
    'YDC': 'MCSTEP NCSTEP DCSTEC DCTIME DCGRAY DCGRAX DCGRAZ DCSIZC DCSIZF DCSIZS DCSIZV ICOUTF ICOUTI '
           'ICOUTP ICOUTT ICSHTF IWFAST DCURELX INITER',
    'YDE': 'MELEM NELEM MELST NELST MELNO NELNO I2ELTO I1ELPR D2ELST I1ELCF I1ELBE D3TCS D1EMCT',
    'YDN': 'MNODIM:5 NNODIM:5 MNOPO NNOPO D2NCI D2NCC D2NVC I1NOPR I1NOBF D1NMCT D2NFC D2NFT',
    'YDI': 'MICOUP MISTATE DIEZON DIEDI IIECFF NICOUP D1IESL I1IECN I1IECT D2SLDIS',
    'YDPE': 'MPROP NPROP I1PTYP D1PERO D1PELA D1PEMU D1PEKS D1PEPE D1PEPT D1PEFR D1PSEM I1PSDE I1PEFR '
            'I1PEMB I1PEJP D1PECA D1PECL D1PERA D1PEVI I1PECN I1PECP I1PECT I1PEMN I1PNIB',
    'YDPJ': 'MPJSET NPJSET I1PTYP D1PJFT D1PJFS D1PJGF D1PJPE D1PJCO D1PJFR I1PSDE NINTPT',
    'YDPM': 'MPMCOM MPMCOL I2PMSET MPMROW I2PMIJ IAUTBN',
    'YDPN': 'MPNSET NPNSET I1PNFX I1PNFY D1PNAX D1PNAY D1PNAP D1PNAT D1PNXX D1PNXY D1PNYX D1PNYY D1PNXZ '
            'D1PNYZ D1PNZX D1PNZY D1PNZZ I1PNFZ D1PNAZ MPNFACT NPNFACT D3PNFAC D1PNAF',
    'YDO': 'MOHYS NOHYS DOHYP I1OHYT D1OHYX D1OHYY D1OHYC D1OHYF D1OHYS D1OHYT',
    'YDB': 'MBORH NBORH MBDIM NBDIM NBPAF D2BCA D2BCB D1BRAD D1BPAF D1BPTS D1BPTE D1BVDT D1BPRS DBLMAX DBBUF',
    'YDS': 'MSOUR NSOUR MSDIM NSDIM NSPAF NSSAF D2SCS D1SPAF D1SSAF D1SPTS D1SPTE D1SVPR D1SPRS D1SSIR DSBUF',
}
KNOWN = {g: [(k.split(':')[0], int(k.split(':')[1]) if ':' in k else len(k)) for k in v.split()]
         for g, v in KNOWN.items()}

# Keys and groups of the Y-Geo derivative (FORMAT.md 9; the same lists as src/y2d/y2d_read.c's ygeo_keys
# and ygeo_groups, which tests/convert/run compares with these): refused by name, as yfdem refuses them,
# so that a Y-Geo deck is not told 'unknown key ... did you mean' a Y2D key of another meaning.
YGEO_KEYS = {
    'YDC': 'ICOUTRF ICOUTNF ICRESF IUSEECZM',
    'YDN': 'I1NOWE',
    'YDPE': 'MPEROW D2PEINT D1PEEM D1PENU I1PEXC I1USAN D1PEEX D1PEEY D1PEMX D1PEMY D1PEG D1PHI D1DPC '
            'D1SIG_T D1F0 D1H1 D1H2 D1HC D1CK D1CC D1BK D1CKP D1NK D1URU D1UC D1RE D1CHI D1NP D1N2 D1NN '
            'I1USE_EXT_SUBLOADING I1USE_KINHARD I1PSUP',
    'YDPJ': 'D1PJGS IUSEHY D1USAF D1PJAL D1PJCR D1PJFD D1PJTR D1PJGR D1PJSR',
}
YGEO_KEYS = {g: v.split() for g, v in YGEO_KEYS.items()}
YGEO_GROUPS = ['YDP', 'YDFN', 'YDIS', 'YDHF', 'YDSM', 'YDR', 'YDSB', 'YDPS']
# Keys that pre-processors of other Y derivatives write (src/y2d/y2d_read.c's other_keys): Y2D stops on them
OTHER_KEYS = {'YDC': 'ISAVE ICSAVF DCSIZD DCSIZA DCRMPT DCGRST ICFMTY ICIATY'.split(), 'YDE': 'I1ELTY I2ELJP'.split()}

# The capacity of each dimension of an array key (src/y2d/y2d_read.c keydefs' cap[], which tests/convert/run
# compares with this table): the capacity key, or a fixed size; None (or a key not listed) is not checked.
# An array of more entries than its capacity is refused at its key's line, as yfdem refuses it (Y2D writes
# past its arrays): the converter wrote such decks and exited 0 (2026-11-29).
_ONE = {'YDPE': 'YDPE/MPROP', 'YDPJ': 'YDPJ/MPJSET', 'YDPN': 'YDPN/MPNSET', 'YDO': 'YDO/MOHYS'}
CAPS = {g + '/' + k: [c] for g, c in _ONE.items() for k, _ in KNOWN[g] if k[:2] in ('D1', 'I1')}
CAPS.update({k: ['YDE/MELEM'] for k in ('YDE/I1ELPR', 'YDE/I1ELCF', 'YDE/I1ELBE', 'YDE/D1EMCT')})
CAPS.update({k: ['YDN/MNOPO'] for k in ('YDN/I1NOPR', 'YDN/I1NOBF', 'YDN/D1NMCT')})
CAPS.update({k: ['YDN/MNODIM', 'YDN/MNOPO'] for k in ('YDN/D2NCI', 'YDN/D2NCC', 'YDN/D2NVC', 'YDN/D2NFC', 'YDN/D2NFT')})
CAPS.update({k: ['YDI/MICOUP'] for k in ('YDI/D1IESL', 'YDI/I1IECN', 'YDI/I1IECT')})
CAPS.update({'YDE/I2ELTO': ['YDE/MELNO', 'YDE/MELEM'], 'YDE/D2ELST': ['YDE/MELST', 'YDE/MELEM'],
             'YDI/D2SLDIS': ['YDI/MISTATE', 'YDI/MICOUP'], 'YDPM/I2PMSET': ['YDPM/MPMCOL', 'YDPM/MPMCOM'],
             'YDPM/I2PMIJ': [3, 'YDPM/MPMROW'], 'YDPN/D3PNFAC': [2, 'YDPN/MPNSET', 'YDPN/MPNFACT']})
# Count keys and their capacities (src/y2d/y2d_read.c check_deck's pairs): a count above its capacity is
# refused at the count's line, in the reader's words
CAP_PAIRS = [('YDE/MELEM', 'YDE/NELEM'), ('YDE/MELNO', 'YDE/NELNO'), ('YDN/MNOPO', 'YDN/NNOPO'),
             ('YDPE/MPROP', 'YDPE/NPROP'), ('YDPN/MPNSET', 'YDPN/NPNSET'), ('YDPJ/MPJSET', 'YDPJ/NPJSET'),
             ('YDE/MELST', 'YDE/NELST'), ('YDPN/MPNFACT', 'YDPN/NPNFACT'), ('YDO/MOHYS', 'YDO/NOHYS')]
# Node coordinates and velocities beyond this are refused at their value's line (YF_RANGE_MAX, F_RANGE keys)
RANGE_MAX, RANGE_KEYS = 1e100, {'YDN/D2NCI': 'm', 'YDN/D2NCC': 'm', 'YDN/D2NVC': 'm/s'}


def check_key(t, f, ln, grp, name):
    """Refuse a group or key Y2D does not read, with the file, the line and the nearest name."""
    if grp in YGEO_GROUPS:
        raise DeckError('%s:%d: %s: Y-Geo group /YD/%s/, not in Y2D' % (f, ln, t, grp))
    if grp not in KNOWN:
        near = difflib.get_close_matches(grp, KNOWN, 1)
        raise DeckError('%s:%d: %s: unknown group /YD/%s/%s (groups: %s)' % (
            f, ln, t, grp, ' (did you mean /YD/%s/?)' % near[0] if near else '', ' '.join(KNOWN)))
    keys = KNOWN[grp]
    if any(len(name) >= m and name[:m] == k[:m] for k, m in keys):
        return
    if name in YGEO_KEYS.get(grp, []):
        raise DeckError('%s:%d: %s: Y-Geo key, not in Y2D' % (f, ln, t))
    if name in OTHER_KEYS.get(grp, []):
        raise DeckError('%s:%d: %s: not a Y2D key (written for other Y derivatives; Y2D stops on it too)' % (f, ln, t))
    near = difflib.get_close_matches(name, [k for k, _ in keys], 1)
    raise DeckError('%s:%d: %s: unknown key in /YD/%s/ (%s)' % (
        f, ln, t, grp, 'did you mean %s?' % near[0] if near else 'keys: ' + ' '.join(k for k, _ in keys)))


def number(t):
    """A token as yfdem's C reader takes it (src/y2d/y2d_read.c): an integer is [+-]digits, a real
    any finite C double strtod reads whole (hexadecimal 0x1.8p-3 included) that begins with a digit,
    a sign or a point; None when it is neither."""
    if re.fullmatch(r'[+-]?[0-9]+', t):
        return int(t)
    if not t or t[0] not in '0123456789+-.' or '_' in t:
        return None
    try:
        v = float.fromhex(t) if re.fullmatch(r'[+-]?0[xX].*', t) else float(t)
    except ValueError:
        return None
    return v if math.isfinite(v) else None


def check_caps(keys, key, canon, caps, counts, last):
    """Refuse counts of array key key = (token, file, line) above their capacities (caps, CAPS), at the
    key's line in yfdem's reader's words; over capacity in a list that holds no value (another size 0):
    read as empty, a warning, as yfdem and Y2D read it."""
    t, f, ln = key
    empty = any(c == 0 for c in counts)
    for n in counts:
        if n < 0:   # at the last size's line, as the reader (its position after reading the sizes)
            raise DeckError('%s:%d: /YD/%s: negative size %d' % (last[1], last[2], canon, n))
    for d, (n, c) in enumerate(zip(counts, caps)):
        if c is None:
            continue
        cap, by = (c, 'its fixed size') if isinstance(c, int) else (int(keys.get(c, 0)), '/YD/' + c)
        if n > cap:
            nm = ('n%d = ' % (d + 1)) if len(counts) > 1 else 'n = '
            if empty:
                keys.warnings.append('%s:%d: /YD/%s: %s%d exceeds the capacity %d given by %s, but the array holds '
                                     'no values (another size is 0): read as an empty array, as Y2D does'
                                     % (f, ln, canon, nm, n, cap, by))
            else:
                raise DeckError('%s:%d: /YD/%s: %s%d entries exceed the capacity %d given by %s%s' % (
                    f, ln, canon, nm, n, cap, by, ' (set it before this key)' if cap == 0 else ''))


def parse(path):
    """dict NAME -> value (scalars) or (dims, flat list in C order [d1][d2][d3])."""
    toks = tokens(path)
    keys, i = Keys(), 0

    def num(j, key=None, want=-1, got=0, what='value', integer=False):
        """The number at token j, of key key = (token, file, line): want values of which got are read
        (want < 0: a single item, what it is).  A comment there is refused, as by yfdem; so is, where
        an integer is read (integer=True: counts, codes, sizes, and the values of the keys whose name
        begins with M, N or I, Y2D's integer keys), a token that is not digits only: Y2D's %ld reads
        3000 of '3000.0' and stops at the stray '.0' (yfdem refuses it; the converter ran 3000 steps)."""
        if j >= len(toks) or toks[j][0] == '/*':
            where = 'the end of the input' if j >= len(toks) else \
                "'/*' at %s:%d (comments cannot appear inside a value list)" % toks[j][1:]
            kt, kf, kln = key if key else (toks[j - 1] if j else ('', path, 0))
            if j >= len(toks) and not key:
                raise DeckError('%s: unexpected end of the deck' % path)
            if want < 0:
                raise DeckError('%s:%d: %s: missing %s before %s' % (kf, kln, kt, what, where))
            raise DeckError('%s:%d: %s: expected %d %s, found %d before %s' % (kf, kln, kt, want, what, got, where))
        t, f, ln = toks[j]
        v = number(t)
        kname = key[0] if key else toks[j - 1][0] if j else ''
        if v is None:
            fortran = re.sub('[dD]', 'e', t, count=1) != t and number(re.sub('[dD]', 'e', t, count=1)) is not None
            raise DeckError('%s:%d: %s: %r is not a number%s' % (
                f, ln, kname, t, " (a Fortran 'd' exponent: Y2D reads C reals (%le) and stops at the 'd'; write it "
                "with 'e', e.g. 1.5e5 for 1.5d5)" if fortran else ''))
        if integer and not isinstance(v, int):
            raise DeckError("%s:%d: %s: '%s' is not an integer (the anchor would misread it; an integer is digits "
                            "only: 3000, not 3000.0 or 3e3)" % (f, ln, kname, t))
        if integer and not -2 ** 63 <= v < 2 ** 63:
            raise DeckError("%s:%d: %s: '%s' is beyond the range of an integer" % (f, ln, kname, t))
        return v

    while i < len(toks):
        t, f, ln = toks[i]
        if t == '/*':
            i += 1
            continue
        if not t.startswith('/YD/'):
            raise DeckError('%s:%d: unexpected token %r' % (f, ln, t))
        name = t.split('/')[3] if t.count('/') >= 3 else ''
        grp = t.split('/')[2]
        check_key(t, f, ln, grp, name)
        # the key's own name (MCSTEPS is MCSTEP), for its capacities and range
        canon = grp + '/' + next(k for k, m in KNOWN[grp] if len(name) >= m and name[:m] == k[:m])
        # stored under it: a name shorter than the key that Y2D's rule still matches (MNODI, compared over
        # 5 characters) was stored as written and never found ('D2NCI read before its capacity MNODIM',
        # a deck yfdem reads, 2026-11-29)
        full = canon
        caps = CAPS.get(canon, [])
        for c in caps:
            if isinstance(c, str) and c not in keys:
                raise DeckError('%s:%d: /YD/%s: read before its capacity /YD/%s; give /YD/%s first (FORMAT.md 2.1)'
                                % (f, ln, canon, c, c))
        isint = name[:1] in ('M', 'N', 'I')   # Y2D's integer keys (src/y2d/y2d_read.c keydefs)
        if len(name) >= 2 and name[1] in '123' and name[0] in 'DI':
            nd = int(name[1])
            if nd == 1:
                n = num(i + 1, toks[i], what='count', integer=True)
                check_caps(keys, toks[i], canon, caps, [n], toks[i + 1])
                vals = [num(i + 2 + k, toks[i], n, k, 'values', isint) for k in range(n)]
                keys[full] = ((n,), vals)
                keys.where[full] = ((f, ln), [toks[i + 2 + k][1:] for k in range(n)])
                i += 2 + n
                continue
            code = str(num(i + 1, toks[i], what='code', integer=True))
            dims = [num(i + 2 + d, toks[i], what='dimension %d' % (d + 1), integer=True) for d in range(nd)]
            check_caps(keys, toks[i], canon, caps, dims, toks[i + 1 + nd])
            tot = 1
            for d in dims:
                tot *= d
            flat = [num(i + 2 + nd + k, toks[i], tot, k, 'values', isint) for k in range(tot)]
            order = [0, 1] if (nd == 2 and code == '12') else [1, 0] if nd == 2 else \
                [int(c) - 1 for c in code]
            arr = [0] * tot
            strides = [1] * nd
            for d in range(nd - 2, -1, -1):
                strides[d] = strides[d + 1] * dims[d + 1]
            for m, v in enumerate(flat):
                rem, idx = m, [0] * nd
                for q in range(nd - 1, -1, -1):
                    d = order[q]
                    idx[d] = rem % dims[d]
                    rem //= dims[d]
                arr[sum(idx[d] * strides[d] for d in range(nd))] = v
                # at its own line, in the words of yfdem's reader (a coordinate that large makes its
                # triangles' areas round to 0: refused later as 'not counter-clockwise', far from the cause)
                if canon in RANGE_KEYS and not abs(v) <= RANGE_MAX:
                    vt, vf, vln = toks[i + 2 + nd + m]
                    raise DeckError('%s:%d: /YD/%s: node %d, %s component: %s is beyond +-%g %s, the range the '
                                    'arithmetic holds (areas and energies multiply coordinates and velocities); give '
                                    'it in units that keep it within' % (vf, vln, canon, idx[1], 'xyz'[idx[0]]
                                                                         if idx[0] < 3 else '?', vt, RANGE_MAX,
                                                                         RANGE_KEYS[canon]))
            keys[full] = (tuple(dims), arr)
            keys.where[full] = ((f, ln), [])
            i += 2 + nd + tot
        else:
            keys[full] = num(i + 1, toks[i], integer=isint)
            keys.where[full] = ((f, ln), [toks[i + 1][1:]])
            i += 2
    return keys


def validate(K, path):
    """Refuse, as yfdem's reader does (its words, the value's FILE:LINE), the values of the properties and
    joint sets in use that a native material or jointprop cannot take: the converter wrote them and exited 0,
    and the converted deck was refused when run, in the native command's words.  Properties no element
    uses and joint sets no I2PMIJ row of properties in use names are never evaluated (left out)."""
    g = lambda k, d=0: K.get(k, d)
    end = (path, 0)
    ne, nprop = g('YDE/NELEM'), g('YDPE/NPROP')
    # counts above their capacities, first, as yfdem's reader checks them (the converter took NNOPO > MNOPO
    # and refused the deck later for a symptom, or wrote it, 2026-11-29)
    for m, n in CAP_PAIRS:
        if int(g(n)) > int(g(m)):
            raise DeckError('%s:%d: /YD/%s = %d exceeds its capacity /YD/%s = %d' % (K.key_at(n, end) + (n, g(n), m, g(m))))
    # the checks of yfdem's reader that a converted deck would otherwise hide (it ran them, exit 0)
    if g('YDC/MCSTEP') > g('YDC/NCSTEP') and not float(g('YDC/DCSTEC', 0)) > 0:
        raise DeckError('%s:%d: /YD/YDC/DCSTEC (the time step) is required and must be > 0 when /YD/YDC/MCSTEP > '
                        '/YD/YDC/NCSTEP' % K.at('YDC/DCSTEC', 0, K.at('YDC/MCSTEP', 0, end)))
    # `yfdem DECK.y` starts its time at DCTIME, and its run refuses a step below the resolution of that time
    # (src/step/run.c, the same words at DCSTEC's line): the time would stand still.  The converted deck starts at
    # t = 0 and ran it (DCTIME 1e300, time tables shifted by -1e300), exit 0.  The rule is run.c's test, in the
    # same doubles: DCTIME + DCSTEC == DCTIME (a DCSTEC of 0 is no step at all: refused above, or none is taken)
    t0, dt = float(g('YDC/DCTIME', 0.0)), float(g('YDC/DCSTEC', 0.0))
    if dt > 0 and t0 + dt == t0:
        raise DeckError('%s:%d: timestep %.6g s is below the resolution of the time %.6g s (a double\'s): the time '
                        'would not advance; use a step above %.3g s' % (
                            K.at('YDC/DCSTEC', 0, end) + (dt, t0, math.nextafter(abs(t0), math.inf) - abs(t0))))
    if g('YDI/MICOUP') > 0 and g('YDI/MISTATE') < 6:
        raise DeckError('%s:%d: /YD/YDI/MISTATE = %d with /YD/YDI/MICOUP = %d: contact needs MISTATE >= 6 (sliding '
                        'state per couple and edge; the anchor crashes otherwise)' % (
                            K.at('YDI/MISTATE', 0, K.at('YDI/MICOUP', 0, end)) + (g('YDI/MISTATE'), g('YDI/MICOUP'))))
    for e, p in enumerate(arr1(K, 'YDE/I1ELPR', ne, -1)):
        if not 0 <= p < nprop:
            raise DeckError('%s:%d: /YD/YDE/I1ELPR: element %d: property %d outside 0..NPROP-1 = 0..%d'
                            % (K.at('YDE/I1ELPR', e, end) + (e, p, nprop - 1)))
    if g('YDE/NELNO') != 3:
        raise DeckError('%s:%d: /YD/YDE/NELNO = %d: input elements must be 3-node triangles (NELNO 3)'
                        % (K.at('YDE/NELNO', 0, end) + (g('YDE/NELNO'),)))
    nnod, mnod = K.get('YDN/NNODIM'), g('YDN/MNODIM')   # MNODIM 3 is a capacity when NNODIM is 2 (C++ writers)
    if (nnod is not None and nnod != 2) or mnod < 2 or (mnod > 2 and nnod != 2):
        raise DeckError('%s:%d: /YD/YDN/MNODIM = %d, /YD/YDN/NNODIM = %d: yfdem reads 2D decks only (NNODIM must be 2, '
                        'and MNODIM, a capacity, at least 2)' % (K.at('YDN/NNODIM', 0, K.at('YDN/MNODIM', 0, end)) +
                                                                 (g('YDN/MNODIM'), g('YDN/NNODIM'))))
    nn = g('YDN/NNOPO')
    xy = get2(K, 'YDN/D2NCI') if 'YDN/D2NCI' in K else []
    if len(xy) >= nn:
        cw = []
        for e, v in enumerate(get2(K, 'YDE/I2ELTO')[:ne] if 'YDE/I2ELTO' in K else []):
            if all(0 <= n < nn for n in v[:3]):
                a, b, c = (xy[n] for n in v[:3])
                area2 = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
                if not area2 > 0:
                    cw.append((e, area2 / 2))
        if cw:
            raise DeckError('%s:%d: /YD/YDE/I2ELTO: %d element(s) not counter-clockwise, first element %d (signed area '
                            '%g from D2NCI); Y2D needs counter-clockwise triangles (FORMAT.md 5.1)'
                            % (K.at('YDE/I2ELTO', 0, end) + (len(cw),) + cw[0]))
    if 'YDN/D2NCC' in K:   # a pre-strained start: every node, every triangle counter-clockwise there too
        xc = get2(K, 'YDN/D2NCC')
        if len(xc) < nn:
            raise DeckError('%s:%d: /YD/YDN/D2NCC gives %d nodes, NNOPO = %d: the others would start at (0, 0), the '
                            "array's default (give every node, or leave D2NCC out: it is then D2NCI)"
                            % (K.key_at('YDN/D2NCC', end) + (len(xc), nn)))
        for e, v in enumerate(get2(K, 'YDE/I2ELTO')[:ne] if 'YDE/I2ELTO' in K else []):
            if all(0 <= n < nn for n in v[:3]):
                a, b, c = (xc[n] for n in v[:3])
                area2 = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
                if not area2 > 0:
                    raise DeckError('%s:%d: /YD/YDN/D2NCC: element %d (nodes %d %d %d) has the signed area %g in the '
                                    'current coordinates: %s at the start' % (K.key_at('YDN/D2NCC', end) + (
                                        e, v[0], v[1], v[2], area2 / 2, 'inverted' if area2 < 0 else 'flat')))
    nset = g('YDPN/NPNSET')
    ax = [arr1(K, 'YDPN/' + k, nset, d) for k, d in (('D1PNXX', 1.0), ('D1PNXY', 0.0), ('D1PNYX', 0.0), ('D1PNYY', 1.0))]
    for s in range(nset):
        xx, xy_, yx, yy = (float(a[s]) for a in ax)
        if math.hypot(xx, xy_) == 0 or math.hypot(yx, yy) == 0:
            raise DeckError('%s:%d: BC set %d: local axis %s is zero (D1PNXX/XY = %g %g, D1PNYX/YY = %g %g)'
                            % (K.key_at('YDPN/D1PNXX', end) + (s, 'x' if math.hypot(xx, xy_) == 0 else 'y', xx, xy_,
                                                                  yx, yy)))
    in_use = set(arr1(K, 'YDE/I1ELPR', ne, -1))
    ptyp = arr1(K, 'YDPE/I1PTYP', nprop, -1)
    for p in sorted(x for x in in_use if 0 <= x < nprop):
        if ptyp[p] not in (1, 2, 4):
            raise DeckError('%s:%d: /YD/YDPE/I1PTYP: property %d has type %d (valid: 1 elastic, 2 rigid, 4 softening '
                            'triangle)' % (K.at('YDPE/I1PTYP', p, end) + (p, ptyp[p])))
    for k in ('D1PEFR', 'D1PEKS', 'D1PEMU', 'D1PERO', 'D1PEPE', 'D1PEPT'):
        for p, v in enumerate(arr1(K, 'YDPE/' + k, nprop, 0.0)):
            if float(v) < 0:
                raise DeckError('%s:%d: /YD/YDPE/%s: property %d has the negative value %g'
                                % (K.at('YDPE/' + k, p, end) + (k, p, v)))
    ptyp, rho = arr1(K, 'YDPE/I1PTYP', nprop, -1), arr1(K, 'YDPE/D1PERO', nprop, 0)
    lam, mu = arr1(K, 'YDPE/D1PELA', nprop, 0), arr1(K, 'YDPE/D1PEMU', nprop, 0)
    for p in sorted(x for x in in_use if 0 <= x < nprop and ptyp[x] == 1):
        if not float(rho[p]) > 0:
            raise DeckError('%s:%d: /YD/YDPE/D1PERO: property %d (elastic) has density %g; it must be > 0'
                            % (K.at('YDPE/D1PERO', p, end) + (p, rho[p])))
        if not float(mu[p]) > 0:   # Y2D and yfdem DECK.y take 0 (only a negative mu is refused): no native material
            raise DeckError('%s:%d: /YD/YDPE/D1PEMU: property %d has mu %g: Y2D and yfdem DECK.y run it (a triangle '
                            'without shear stiffness), but a native material needs mu > 0: no deck written (run the '
                            '.y with yfdem DECK.y)' % (K.at('YDPE/D1PEMU', p, end) + (p, float(mu[p]))))
        if not float(lam[p]) + float(mu[p]) > 0:   # volfac 0.5: the in-plane bulk modulus is lambda + mu
            raise DeckError('%s:%d: /YD/YDPE/D1PELA: property %d has lambda %g and mu (/YD/YDPE/D1PEMU) %g: the '
                            'in-plane bulk modulus lambda + mu = %g must be positive' %
                            (K.at('YDPE/D1PELA', p, end) + (p, lam[p], mu[p], float(lam[p]) + float(mu[p]))))
    if 'YDPM/I2PMSET' not in K or not g('YDPJ/NPJSET'):
        return
    npj = g('YDPJ/NPJSET')
    for q, m in enumerate(get2(K, 'YDPM/I2PMIJ') if 'YDPM/I2PMIJ' in K else []):
        if not 0 <= m[2] < npj:
            raise DeckError('%s:%d: /YD/YDPM/I2PMIJ: row %d: joint set %d outside 0..NPJSET-1 = 0..%d'
                            % (K.at('YDPM/I2PMIJ', 0, end) + (q, m[2], npj - 1)))
    live = {m[2] for m in (get2(K, 'YDPM/I2PMIJ') if 'YDPM/I2PMIJ' in K else []) if m[0] in in_use and m[1] in in_use}
    jtyp = arr1(K, 'YDPJ/I1PTYP', npj, -1)
    for j in sorted(x for x in live if 0 <= x < npj):
        if jtyp[j] != 3:
            raise DeckError('%s:%d: /YD/YDPJ/I1PTYP: joint set %d has type %d; 2D joint sets must be 3 (YTE2JOINTS)'
                            % (K.at('YDPJ/I1PTYP', j, end) + (j, jtyp[j])))
    vals = {k: arr1(K, 'YDPJ/' + k, npj, 0.0) for k in ('D1PJFT', 'D1PJGF', 'D1PJPE', 'D1PJFS', 'D1PJCO')}
    for j in sorted(x for x in live if 0 <= x < npj):
        for k in ('D1PJFT', 'D1PJGF', 'D1PJPE'):
            if not float(vals[k][j]) > 0:
                raise DeckError('%s:%d: /YD/YDPJ/%s: joint set %d has %g; it must be > 0'
                                % (K.at('YDPJ/' + k, j, end) + (k, j, vals[k][j])))
        if not float(vals['D1PJFS'][j]) > 0 and not float(vals['D1PJCO'][j]) > 0:
            raise DeckError('%s:%d: /YD/YDPJ/D1PJFS: joint set %d has shear strength %g and cohesion /YD/YDPJ/D1PJCO '
                            '%g: one must be > 0' % (K.at('YDPJ/D1PJFS', j, end) + (j, vals['D1PJFS'][j],
                                                                                    vals['D1PJCO'][j])))


def arr1(K, key, n, default):
    dims, vals = K.get(key, ((0,), []))
    return [vals[k] if k < len(vals) else default for k in range(n)]


# Rows of 2D arrays padded to the width the code reads, with the reader's default: a deck may give fewer
# values along dimension 1 than it holds (D2NVC 21 1 N: x velocities only; I2PMIJ 21 2 N: the set column
# left at 0), which Y2D and yfdem read with the rest at the default; the converter indexed past the row
# ('list index out of range', 2026-11-29).  I2PMSET rows are padded to MPMCOL.
ROW_PAD = {'YDN/D2NCI': (2, 0.0), 'YDN/D2NCC': (2, 0.0), 'YDN/D2NVC': (2, 0.0), 'YDE/I2ELTO': (3, -1),
           'YDPM/I2PMIJ': (3, 0), 'YDPM/I2PMSET': ('YDPM/MPMCOL', 0)}


def get2(K, key):
    """2D array as rows over dimension 2: list of lists (dim-1 values, padded as ROW_PAD says)."""
    (n1, n2), flat = K[key]
    width, default = ROW_PAD.get(key, (n1, 0))
    width = max(n1, int(K.get(width, 0)) if isinstance(width, str) else width)
    return [[flat[a * n2 + b] for a in range(n1)] + [default] * (width - n1) for b in range(n2)]


def wrap(head, items):
    """head + items, split with the native continuation over lines of LINE_MAX characters."""
    lines, cur = [], head
    for it in items:
        if len(cur) + 1 + len(it) > LINE_MAX:
            lines.append(cur + SYNTAX['continue'])
            cur = '   ' + it
        else:
            cur += ' ' + it
    lines.append(cur)
    return '\n'.join(lines)


def native_table(tab, shift):
    """Y2D's time factor of one set as a native `history table`: (pairs, exact).  pairs is None when
    the factor is 1.0 at every time.  Y2D (ALGORITHMS 7, src/y2d/y2d_model.c set_factor) interpolates
    in the first interval [t_i, t_i+1] with t_i+1 > t_i that holds t, and uses 1.0 outside every
    interval; a native table holds its end values and needs increasing times.  So intervals of zero
    length (a table padded by repeating its last point) are dropped, a jump at a repeated time gets a
    point one ulp later, and a point of value 1.0 one ulp before the first time and one after the
    last: the same factor at every double time.  Times are shifted by -shift (DCTIME).  exact is
    False when times decrease and an interval that increases is dropped where the intervals before it do
    not hold it: Y2D takes it first there.  Times that fall back into what the table already holds (a
    table padded with the default points (0, 0) under a larger NPNFACT) change nothing: exact."""
    pts = [(float(t) - shift, float(v)) for t, v in tab]
    exact = True
    out = []
    for (ta, va), (tb, vb) in zip(pts, pts[1:]):
        if not tb > ta:
            continue
        if out and ta < out[-1][0]:
            exact = exact and out[0][0] <= ta and tb <= out[-1][0]
            continue
        if not out:
            out.append((ta, va))
        elif va != out[-1][1]:
            # a jump at ta: Y2D's factor at ta is the earlier interval's end, just after it this one's
            up = math.nextafter(ta, math.inf)
            if up < tb:
                out.append((up, va))
        out.append((tb, vb))
    if not out:
        return None, exact
    if out[0][1] != 1.0:
        out.insert(0, (math.nextafter(out[0][0], -math.inf), 1.0))
    if out[-1][1] != 1.0:
        out.append((math.nextafter(out[-1][0], math.inf), 1.0))
    if all(v == 1.0 for _, v in out):
        return None, exact
    return out, exact


def below_edge_threshold(value, table):
    """True when an edge load value (D1PNAP or D1PNAT of a set) times its time factor (table: the set's
    native history pairs, None for 1.0; outside a table the factor is 1.0) never exceeds 1e-10 in
    magnitude: Y2D applies an edge load only where both end nodes' values exceed 1e-10 (ALGORITHMS 2.5,
    9; yfdem's reader the same), so such a set loads no edge, not even one shared with a loaded set.  The
    converter wrote a set of D1PNAP 1e-15 next to one of 1e6 as a linearly varying pressure, loaded with
    the mean, and exited 3 (2026-11-29)."""
    peak = max([1.0] + [abs(v) for _, v in table]) if table else 1.0
    return abs(float(value)) * peak <= 1e-10


def pressure_loads(L, note, diff, ne, elto, meshed, nopr, nset, ap, hist_of, ids_of_node):
    """Y2D's edge pressure (ALGORITHMS 2.5): every triangle edge whose two end nodes are in sets with
    D1PNAP != 0, with the consistent load of a pressure varying linearly from p_j to p_k.  The native
    `load GROUP pressure P` loads, with a constant P, the outer boundary edges whose two nodes are in
    GROUP.  Exact: an outer edge whose two nodes are in sets of the same pressure and time table (the
    sets of one (P, table) class go into one group), and an interior edge between two unjointed
    triangles (Y2D's two loads cancel).  Not expressible: an outer edge between sets of different
    pressures (a linear variation; written, when its own group can hold it alone, as two halves of
    the pressures: the same resultant, not the same distribution) and an interior edge of jointed
    triangles (Y2D pushes each triangle's copy: it opens the joints; not written)."""
    loaded = lambda n: 0 <= nopr[n] < nset and nopr[n] in hist_of and float(ap[nopr[n]]) != 0.0
    cls = {}
    for s in sorted(hist_of):
        if float(ap[s]) != 0.0:
            cls.setdefault((float(ap[s]), hist_of[s]), []).append(s)
    if not cls:
        return
    key_of = {s: key for key, ss in cls.items() for s in ss}
    tris_of = {}
    for e in range(ne):
        for j in range(3):
            a, b = elto[e][j], elto[e][(j + 1) % 3]
            tris_of.setdefault(frozenset((a, b)), []).append(e)
    outer = [k for k, es in tris_of.items() if len(es) == 1]
    same, mixed, inner = {}, {}, []
    for e in range(ne):
        for j in range(3):
            a, b = elto[e][j], elto[e][(j + 1) % 3]
            if not (loaded(a) and loaded(b)):
                continue
            others = [o for o in tris_of[frozenset((a, b))] if o != e]
            if others:
                if meshed[e] or any(meshed[o] for o in others):
                    inner.append((min(e, *others), a, b))
                continue
            ka, kb = key_of[nopr[a]], key_of[nopr[b]]
            if ka == kb:
                same[ka] = same.get(ka, 0) + 1
            else:
                mixed.setdefault(tuple(sorted((ka, kb), key=repr)), []).append((a, b))
    L.append('# edge pressure (D1PNAP): one load per (pressure, time table), on the outer edges whose two '
             'nodes carry it')
    gname = {}
    for k, (key, ss) in enumerate(cls.items()):
        if len(ss) == 1:
            gname[key] = 'bc%d' % ss[0]
        else:
            gname[key] = 'pr%d' % k
            if key in same:
                L.append(SYNTAX['group_union'].format(name=gname[key], groups=' '.join('bc%d' % s for s in ss)))
                note('BC sets %s: the same pressure and time table, loaded as one group (edges between them '
                     'included)' % ' '.join(map(str, ss)))
        if key in same:
            hist = SYNTAX['hist_opt'].format(name='bc%d' % ss[0]) if key[1] else ''
            L.append(SYNTAX['load_pressure'].format(id='%s_p' % gname[key], group=gname[key], p=key[0], hist=hist))
    outer_set = set(outer)
    for k, ((ka, kb), edges) in enumerate(mixed.items()):
        nodes = {n for ed in edges for n in ed}
        hit = {o for o in outer_set if o <= nodes}
        what = '%d outer edge(s) between BC sets of pressures %r and %r (first: nodes %d %d) carry a linearly ' \
               'varying pressure' % (len(edges), ka[0], kb[0], edges[0][0], edges[0][1])
        if hit != {frozenset(ed) for ed in edges}:
            diff(what + ': not translated (unloaded)')
            continue
        name = 'prm%d' % k
        L.append(wrap(SYNTAX['group_ids'].format(name=name, ids='').rstrip(),
                      [str(i) for n in sorted(nodes) for i in ids_of_node[n]]))
        for h, key in (('a', ka), ('b', kb)):
            hist = SYNTAX['hist_opt'].format(name='bc%d' % cls[key][0]) if key[1] else ''
            L.append(SYNTAX['load_pressure'].format(id='%s_%s' % (name, h), group=name, p=key[0] / 2, hist=hist))
        diff(what + ': written as the mean pressure (p_j + p_k)/2 (the same resultant, not the same '
             'distribution: each end node is off by n (p_j - p_k)/12)')
    inner = sorted({(e, frozenset((a, b))): (e, a, b) for e, a, b in inner}.values())
    if inner:
        diff('%d interior edge(s) of jointed triangles (first: element %d, nodes %d %d) have both end nodes in '
             'pressure sets: Y2D loads them (it pushes the triangles\' own copies apart), the native pressure '
             'loads the outer boundary only: not translated' % (len(inner), inner[0][0], inner[0][1], inner[0][2]))
    L.append('')


def deck_word(name):
    """name as one word of the native deck (README, The deck): in single quotes, where a space, '#'
    (a comment outside quotes) and '$' (substitution outside single quotes) are plain characters; in
    double quotes when it holds a single quote ('#' is plain there too, '$' is not).  A name with a
    single quote and a '$' or a double quote, or with a line break, cannot be written: DeckError."""
    if '\n' in name or '\r' in name:
        raise DeckError('%r: a file name with a line break cannot be written in a native deck' % name)
    if "'" not in name:
        return "'%s'" % name
    if '"' not in name and '$' not in name:
        return '"%s"' % name
    raise DeckError("%r: a file name holding a single quote and a '$' or '\"' cannot be quoted in a native deck "
                    "(a '$' is substituted inside double quotes, a single-quoted word ends at the next '); "
                    "choose another OUT" % name)


WARN = 'warn'   # a note kind: the same physics, but something the user sees differently (exit 0, on stderr)


def nothing_computed(src, out, ctl):
    """A .y with no key and no $YDOIT (empty, or comments only): yfdem DECK.y warns that nothing is computed
    and exits 0, as Y2D reads it and stops.  The converted deck computes nothing too, and says so: in its
    header, and when run (a print); no .nodes / .tris (there is no scene).  The converter refused it, exit 1
    ('/YD/YDE/NELNO = 0', 2026-11-29)."""
    f, ln = ctl.get('end', (src, 1))
    why = ('%s:%d: nothing is computed: the deck has no $YDOIT before %s, and Y2D reads it and stops without '
           'computing; put $YDOIT before $YSTOP to run it' % (f, ln, 'its $YSTOP' if ctl.get('ystop') else 'its end'))
    L = [SYNTAX['header'].format(src=src),
         '# NOTES: WARNING = the same physics, told differently', '#   WARNING: ' + why,
         '# the .y has no keys: no scene, no run; this deck computes nothing, as yfdem DECK.y',
         # single quotes: no $ substitution in the native deck
         "print 'nothing is computed: %s has no keys and no $YDOIT (converted by tools/y2d2deck.py)'"
         % os.path.basename(src).replace("'", "")]
    with open(out + '.deck', 'w') as fh:
        fh.write('\n'.join(L) + '\n')
    return out + '.deck', [(why, WARN)]


class NoYfdem(Exception):
    """$YFDEM names no executable file: bad usage (exit 2), said before anything is read or written."""


def find_yfdem():
    """yfdem's binary for reader_check: $YFDEM, else the one built beside tools/ (the repository's root),
    else the first on PATH; None when there is none (a note on stderr says where it looked and what to
    build).  A $YFDEM that names no executable file is refused (NoYfdem): the converter used another
    yfdem, or none, without a word (2026-11-29)."""
    return _find_yfdem(os.environ.get('YFDEM'), os.environ.get('PATH'))


@functools.lru_cache(maxsize=None)
def _find_yfdem(given, path):
    """find_yfdem for one $YFDEM and $PATH: looked up (and the note written) once per run."""
    here = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    if given:
        if os.path.isfile(given) and os.access(given, os.X_OK):
            return given
        raise NoYfdem('YFDEM=%s: %s; build yfdem with `make -j2 yfdem` in %s, or unset YFDEM (then %s, '
                      'else the yfdem on PATH)' % (given, 'not an executable file' if os.path.exists(given)
                                                   else 'no such file', here, os.path.join(here, 'yfdem')))
    for cand in (os.path.join(here, 'yfdem'), shutil.which('yfdem')):
        if cand and os.path.isfile(cand) and os.access(cand, os.X_OK):
            return cand
    sys.stderr.write('note: no yfdem found (YFDEM unset, no %s, none on PATH): the .y is checked by the converter '
                     'alone, not by yfdem\'s reader; build it with `make -j2 yfdem` in %s\n'
                     % (os.path.join(here, 'yfdem'), here))
    return None


def reader_check(src):
    """Refuse the .y as yfdem's own reader refuses it: `read_y2d SRC` (reads, checks and builds the scene,
    computes nothing) in the yfdem found by find_yfdem, from the working directory (where `yfdem SRC` would
    look for SRC and its $YINCL files).  Its error 'FILE:LINE: error: TEXT' (exit 1, or 2 for a file it
    cannot read) becomes DeckError('FILE:LINE: TEXT'), in its words.  The checks of validate() mirror a
    part of the reader's; this one is all of them: the converter wrote decks the reader refuses (a negative
    DIEZON or MCSTEP, BC axes that are not orthogonal, a meshing code digit 5, NPJSET 0 with meshing: the
    joints dropped) or stopped with a Python message ('list index out of range'), 2026-11-29.  Without a
    yfdem (or with a name a native deck cannot quote), validate() alone checks."""
    exe = find_yfdem()
    if not exe:
        return
    try:
        word = deck_word(src)
    except DeckError:
        return
    env = dict(os.environ, OMP_NUM_THREADS='1')
    p = subprocess.run([exe, '-log', os.devnull], input=('read_y2d %s\n' % word).encode(), stdout=subprocess.DEVNULL,
                       stderr=subprocess.PIPE, env=env)
    if p.returncode not in (1, 2):   # read (0), or a failure that is not the reader's refusal: validate() checks
        return
    lines = p.stderr.decode(errors='replace').splitlines()
    for k, line in enumerate(lines):
        m = re.match(r'^(.*?:\d+): error: (.*)$', line) or re.match(r'^()error: (.*)$', line)
        if m:
            # '<stdin>:1' is the one-line deck piped to yfdem here, not the user's: the .y is named instead
            # ("error: <stdin>:1: cannot open Y2D deck 'x.y'", 2026-11-29)
            own = m.group(1) and not m.group(1).startswith('<stdin>:')
            head = ('%s: ' % m.group(1)) if own else ('%s: ' % src)
            raise DeckError('\n'.join([head + m.group(2)] + lines[k + 1:]))
    raise DeckError('%s: refused by yfdem\'s reader (exit %d): %s' % (src, p.returncode, ' '.join(lines)[-300:]))


def convert(src, out):
    base = os.path.basename(out)
    for name in (base + '.nodes', base + '.tris', base + '.h5'):
        deck_word(name)   # refused before anything is written
    try:
        K = parse(src)
    except Exception:
        reader_check(src)   # the reader's words where it refuses the deck too
        raise
    ctl = CONTROL.get(src, {})
    if not ctl.get('ydoit') and not K.order:
        return nothing_computed(src, out, ctl)
    reader_check(src)
    validate(K, src)
    g = lambda k, d=0: K.get(k, d)
    ne, nn, nprop = g('YDE/NELEM'), g('YDN/NNOPO'), g('YDPE/NPROP')
    elto = get2(K, 'YDE/I2ELTO')
    elpr = arr1(K, 'YDE/I1ELPR', ne, -1)
    xy = get2(K, 'YDN/D2NCI')
    vel = get2(K, 'YDN/D2NVC') if 'YDN/D2NVC' in K else [[0.0, 0.0]] * nn
    vel = [vel[n] if n < len(vel) else [0.0, 0.0] for n in range(nn)]
    L = [SYNTAX['header'].format(src=src), '']
    # notes: (text, changes the physics).  diff(): the converted deck does not run the physics of
    # `yfdem DECK.y` (a warning, counted, exit 3 unless accepted); note(): an exact translation
    # worth a word (listed in OUT.deck only)
    notes = [(w, WARN) for w in K.warnings]
    note = lambda text: notes.append((text, False))
    diff = lambda text: notes.append((text, True))
    warn = lambda text: notes.append((text, WARN))

    # ---- materials
    pe = lambda name, d: arr1(K, 'YDPE/' + name, nprop, d)
    ptyp, rho, lam, mu = pe('I1PTYP', -1), pe('D1PERO', 0), pe('D1PELA', 0), pe('D1PEMU', 0)
    ks, pen_n, pen_t, fric = pe('D1PEKS', 0), pe('D1PEPE', 0), pe('D1PEPT', 0), pe('D1PEFR', 0)
    L.append('# materials: Y2D element properties (Lame constants as given)')
    in_use = set(elpr[:ne])
    for p in range(nprop):
        if p not in in_use:
            # Y2D evaluates a property through its elements only: a spare one (NPROP above those in
            # use, often left at type -1 and density 0, which a native material refuses) has no effect
            note('property %d is used by no element: not written (no effect in Y2D)' % p)
            continue
        if ptyp[p] != 1:
            diff('property %d has type %d (%s): written as elastic' %
                         (p, ptyp[p], {2: 'rigid', 4: 'softening'}.get(ptyp[p], '?')))
        L.append(SYNTAX['material'].format(name='p%d' % p, rho=float(rho[p]), lam=float(lam[p]),
                                           mu=float(mu[p]), visc=float(ks[p]), pen_n=float(pen_n[p]),
                                           pen_t=float(pen_t[p]), fric=float(fric[p])))
    L.append('')

    # ---- mesh: one body, nodes and triangles in input order (the order of `yfdem FILE.y`, so
    # sums over nodes and triangles run in the same order and the results are the same bits)
    rows = get2(K, 'YDPM/I2PMSET') if 'YDPM/I2PMSET' in K else []
    used = sorted({n for e in range(ne) for n in elto[e][:3]})
    ids_of_node = {n: [] for n in range(nn)}
    for n in used:
        ids_of_node[n].append(n)
    body = 'y2d'
    with open('%s.nodes' % out, 'w') as f:
        for n in used:
            f.write('%d %r %r\n' % (n, float(xy[n][0]), float(xy[n][1])))
    with open('%s.tris' % out, 'w') as f:
        for e in range(ne):
            v = elto[e]
            f.write('%d %d %d %d p%d\n' % (e, v[0], v[1], v[2], elpr[e]))
    L.append('# mesh: the Y2D nodes and elements in input order, ids = Y2D indices (0-based)')
    L.append(SYNTAX['nodes'].format(file=deck_word('%s.nodes' % base), body=body))
    L.append(SYNTAX['triangles'].format(file=deck_word('%s.tris' % base), body=body))
    # D2NCC: the nodes' current coordinates (yfdem DECK.y starts each node there, with D2NCI as its
    # reference: a pre-strained body).  A native node has one position, its reference: not expressible
    if 'YDN/D2NCC' in K:
        xc = get2(K, 'YDN/D2NCC')
        worst, wn = 0.0, -1
        for n in used:
            d = max(abs(float(xc[n][c]) - float(xy[n][c])) for c in (0, 1)) if n < len(xc) else 0.0
            if d > worst:
                worst, wn = d, n
        if wn >= 0:
            moved = sum(1 for n in used if n < len(xc) and (float(xc[n][0]), float(xc[n][1])) !=
                        (float(xy[n][0]), float(xy[n][1])))
            diff('/YD/YDN/D2NCC (current coordinates) differs from D2NCI (reference) at %d node(s), by up to %r m '
                 '(node %d): yfdem DECK.y starts them there, pre-strained; a native deck has no current position '
                 'apart from the reference one: written at D2NCI, unstrained' % (moved, worst, wn))
    unused = [n for n in range(nn) if not ids_of_node[n]]
    if unused:
        note('%d node(s) used by no triangle were dropped (first: %d; massless, Y2D never moves them)'
             % (len(unused), unused[0]))
    L.append('')

    # ---- joints: each meshing row of code 3 gets joints on the edges of its triangles, with the
    # joint set I2PMIJ gives its property pair
    meshed = [False] * ne
    row_of = {}       # meshed element -> its meshing row
    if 'YDPJ/NPJSET' in K and rows:
        npj = g('YDPJ/NPJSET')
        pj = lambda name: arr1(K, 'YDPJ/' + name, npj, 0.0)
        ft, fs, gf, pen, co, fr = (pj(n) for n in ('D1PJFT', 'D1PJFS', 'D1PJGF', 'D1PJPE', 'D1PJCO', 'D1PJFR'))
        pair_set = {}
        for m in get2(K, 'YDPM/I2PMIJ') if 'YDPM/I2PMIJ' in K else []:
            pair_set[(m[0], m[1])] = m[2]
            pair_set[(m[1], m[0])] = m[2]
        L.append('# joints (Y2D meshing code 3): Munjiza\'s law with Y2D\'s floor, no damage memory')
        # the sets an I2PMIJ row of two properties in use names: the others (spare sets, often left at
        # f_t 0, which a native jointprop refuses) are never evaluated, as yfdem's reader has it
        live_sets = {m[2] for m in (get2(K, 'YDPM/I2PMIJ') if 'YDPM/I2PMIJ' in K else [])
                     if m[0] in in_use and m[1] in in_use}
        for j in range(npj):
            if j not in live_sets:
                note('joint set %d is named by no I2PMIJ row of properties in use: not written (no effect)' % j)
                continue
            mc = SYNTAX['mohr_coulomb'].format(co=float(co[j]), fr=float(fr[j])) if float(co[j]) > 0 else ''
            if float(co[j]) <= 0 and float(fr[j]) != 0:
                note('joint set %d: friction %g without cohesion (D1PJCO = 0): Y2D ignores it too' % (j, fr[j]))
            # D1PJFS <= 0 with cohesion: Y2D starts from the cohesion as shear strength, as the native
            # jointprop does without fs (fs must be > 0 there)
            fsw = '' if float(fs[j]) <= 0 and float(co[j]) > 0 else SYNTAX['jointprop_fs'].format(fs=float(fs[j]))
            L.append(SYNTAX['jointprop'].format(name='j%d' % j, ft=float(ft[j]), fs=fsw, gf=float(gf[j]),
                                                pen=float(pen[j]), mc=mc))
        for r, row in enumerate(rows):
            k, code = row[0], row[1]
            props = list(row[2:2 + k])
            if k <= 0 or '3' not in str(code):
                continue
            if any(c in str(code) for c in '124'):
                diff('meshing row %d: code %d has refinement/detach digits (1, 2, 4) that are '
                             'not translated' % (r, code))
            # the set of each pair of the row's properties in use (ALGORITHMS 4.1): its I2PMIJ row, or
            # without one the creating triangle's own (P, P) row, either of the two; properties no
            # element uses join nothing (a row that lists one, with two diagonal rows of one set, was
            # refused as 'joint sets [0]' with None among them)
            live = [q for q in props if q in in_use]
            sets = set()
            for a in live:
                for b in live:
                    s = pair_set.get((a, b))
                    sets |= {s} if s is not None else {pair_set.get((a, a)), pair_set.get((b, b))}
            if len(sets) > 1 or None in sets:
                diff('meshing row %d: its property pairs use joint sets %s; written with the set of '
                             'its first property' % (r, sorted(x for x in sets if x is not None)))
            tris = [e for e in range(ne) if elpr[e] in props]
            if not tris:
                note('meshing row %d: no element has its properties %s: nothing to joint' % (r, props))
                continue
            jset = pair_set.get((live[0], live[0]), 0)
            for e in tris:
                meshed[e] = True
                row_of[e] = r
            L.append(wrap(SYNTAX['group_tris'].format(name='row%d' % r, ids='').rstrip(), [str(e) for e in tris]))
            L.append(SYNTAX['fracture'].format(body=body, jp='j%d' % jset, group='row%d' % r))
        L.append('')
        # Y2D joins only the triangles of one row: an edge between a row and a triangle outside it
        # (unmeshed, or of another row) separates the two (its joint is neutralised, ALGORITHMS 4.1);
        # `fracture` puts a joint on every internal edge with a side in its zone
        sides = {}
        for e in range(ne):
            for j in range(3):
                sides.setdefault(frozenset((elto[e][j], elto[e][(j + 1) % 3])), []).append(e)
        apart = [(es[0], es[1]) for es in sides.values() if len(es) == 2 and row_of.get(es[0]) != row_of.get(es[1])]
        if apart:
            diff('%d edge(s) between a meshed row and a triangle outside it (first: elements %d, %d): Y2D leaves '
                 'them unjoined (separate bodies), the native fracture joins them by joints' % (len(apart), *apart[0]))

    # ---- contact: every participating triangle against every other, couples sharing a node kept
    # (Y2D's MICOUP); with IWFAST > 0 only triangles with a corner flagged in I1NOBF take part, and
    # the triangles of jointed rows (their new nodes are flagged)
    if g('YDI/MICOUP') > 0:
        nobf = arr1(K, 'YDN/I1NOBF', nn, 0)
        iwfast = g('YDC/IWFAST', 1)
        part = [e for e in range(ne) if iwfast == 0 or meshed[e] or any(nobf[v] == 1 for v in elto[e][:3])]
        # Y2D's pair penalty is the smaller D1PEPE of the two properties (ALGORITHMS 6): a triangle of a property
        # with D1PEPE 0 gets no contact force from any couple, but its couples exist (Y2D's search is geometric,
        # ALGORITHMS 5) and are counted, as yfdem DECK.y counts them.  Kept in contact: its material's 'pen_n 0.0',
        # written out, is one a native contact rule takes (the converter left such triangles out, and its deck
        # had fewer contact couples than yfdem DECK.y, 2026-11-29).
        nopen = sorted({elpr[e] for e in part if not float(pen_n[elpr[e]]) > 0})
        if nopen:
            note('propert%s %s: D1PEPE 0, so no couple with %s triangles carries a contact force in Y2D (the pair '
                 'penalty is the smaller D1PEPE): in contact with pen_n 0, the couples kept as Y2D keeps them' % (
                     'y' if len(nopen) == 1 else 'ies', ' '.join(map(str, nopen)), 'its' if len(nopen) == 1 else 'their'))
        L.append('# contact (Y2D MICOUP %d, buffer DIEZON, IWFAST %d: %d of %d triangles take part)'
                 % (g('YDI/MICOUP'), iwfast, len(part), ne))
        if part:
            L.append(wrap(SYNTAX['group_tris'].format(name='contact_tris', ids='').rstrip(), [str(e) for e in part]))
            L.append(SYNTAX['contact_self'].format(group='contact_tris'))
            L.append(SYNTAX['contact'].format(buffer=float(g('YDI/DIEZON', 0.0))))
        else:
            note('MICOUP > 0 but no triangle takes part in contact (IWFAST %d, no I1NOBF flag, no joints): '
                 'no contact written' % iwfast)
        L.append('')

    # ---- initial velocities
    groups_v = {}
    for n in range(nn):
        v = (float(vel[n][0]), float(vel[n][1]))
        if v != (0.0, 0.0) and ids_of_node[n]:
            groups_v.setdefault(v, []).extend(ids_of_node[n])
    if groups_v:
        L.append('# initial velocities (D2NVC)')
        for k, (v, ids) in enumerate(sorted(groups_v.items(), key=lambda kv: min(kv[1]))):
            L.append(wrap(SYNTAX['group_ids'].format(name='v%d' % k, ids='').rstrip(), [str(i) for i in ids]))
            L.append(SYNTAX['velocity'].format(group='v%d' % k, vx=v[0], vy=v[1]))
        L.append('')

    # ---- the nodes after joint insertion: a meshed triangle gets its own copy of each corner, the
    # node itself stays while an unmeshed triangle uses it.  Y2D treats every copy as a node of the
    # set (full point force, its own lumped mass rho A0/3); the native `load point` shares one force
    # among the copies.  masses[n]: the lumped mass of each copy of n (Y2D: rho d0/6 per corner).
    rho_e = [float(rho[p]) if 0 <= p < nprop else 0.0 for p in elpr]
    copies = {n: [] for n in used}
    own = {}
    for e in range(ne):
        a, b, c = elto[e][:3]
        d0 = (float(xy[b][0]) - float(xy[a][0])) * (float(xy[c][1]) - float(xy[a][1])) - \
             (float(xy[c][0]) - float(xy[a][0])) * (float(xy[b][1]) - float(xy[a][1]))
        for v in (a, b, c):
            if meshed[e]:
                copies[v].append(rho_e[e] * d0 / 6.0)
            else:
                own[v] = own.get(v, 0.0) + rho_e[e] * d0 / 6.0
    for v, m in own.items():
        copies[v].append(m)

    # ---- gravity and BC sets
    if float(g('YDC/DCGRAY', 0.0)) != 0.0:
        L.append(SYNTAX['gravity'].format(gy=float(g('YDC/DCGRAY'))))
        note('gravity acts on every node; Y2D lets it act on BC kinds 1 and 2 only, the others are held '
             'or driven by a fix, which overrides it')
    nset = g('YDPN/NPNSET')
    pn = lambda name, d: arr1(K, 'YDPN/' + name, nset, d)
    fx, fy, ax, ay = pn('I1PNFX', -1), pn('I1PNFY', -1), pn('D1PNAX', 1.0), pn('D1PNAY', 1.0)
    ap, at = pn('D1PNAP', 0.0), pn('D1PNAT', 0.0)
    xx, xy_, yx, yy = pn('D1PNXX', 1.0), pn('D1PNXY', 0.0), pn('D1PNYX', 0.0), pn('D1PNYY', 1.0)
    nopr = arr1(K, 'YDN/I1NOPR', nn, -1)
    npts = g('YDPN/NPNFACT', 0)
    t0 = float(g('YDC/DCTIME', 0.0))
    if t0 != 0.0:
        note('DCTIME %r: the native run starts at t = 0, so every time table is shifted by -%r (native '
             'time = Y2D time - DCTIME; thermo and summary times are the native ones)' % (t0, t0))
    tables = {}
    if 'YDPN/D3PNFAC' in K and npts > 0:
        (d1, d2, d3), flat = K['YDPN/D3PNFAC']
        # entries not given keep the default 0, as Y2D and yfdem read them (NPNFACT above the points given,
        # sets beyond those given, no factor row): the converter indexed past the list, 2026-11-29
        fac = lambda i, s, p: flat[(i * d2 + s) * d3 + p] if i < d1 and s < d2 and p < d3 else 0.0
        if flat and flat[0] != -1:
            for s in range(min(d2, nset)):
                tables[s] = [(fac(0, s, p), fac(1, s, p)) for p in range(npts)]
    L.append('# boundary conditions: one group per Y2D BC set (node ids)')
    hist_of = {}      # set -> native table (tuple of (t, v)), None = factor 1.0 throughout
    for s in range(nset):
        ids = [i for n in range(nn) if nopr[n] == s for i in ids_of_node[n]]
        nodes_s = [n for n in range(nn) if nopr[n] == s and ids_of_node[n]]
        if not ids:
            continue
        gname = 'bc%d' % s
        hist = ''
        hist_of[s] = None
        if s in tables:
            tab, exact = native_table(tables[s], t0)
            if not exact:
                diff('BC set %d: its time table has decreasing times; written with the intervals that '
                     'increase' % s)
            if tab:
                L.append(wrap(SYNTAX['history'].format(name=gname, pairs='').rstrip(),
                              ['%r %r' % (t, v) for t, v in tab]))
                hist = SYNTAX['hist_opt'].format(name=gname)
                hist_of[s] = tuple(tab)
        L.append(wrap(SYNTAX['group_ids'].format(name=gname, ids='').rstrip(), [str(i) for i in ids]))
        kinds, amps = (fx[s], fy[s]), (float(ax[s]), float(ay[s]))
        frozen = [k not in (1, 2, 3) for k in kinds]
        # held in both directions, free in both, or frozen in both: the same in any frame
        any_frame = (not hist and amps == (0.0, 0.0) and tuple(kinds) in ((3, 3), (1, 1))) or all(frozen)
        if (xx[s], xy_[s], yx[s], yy[s]) != (1, 0, 0, 1) and not any_frame:
            if kinds[0] == kinds[1] and kinds[0] in (1, 2, 3):
                # the same kind in both local directions: Y2D's v = R u with u updated by that kind (ALGORITHMS 7)
                # is the same kind in global x and y with the amplitude R A (force, acceleration or velocity; the
                # edge loads and gravity act through R R^-1 = 1); the converter dropped such a set (2026-11-29)
                ex, ey = (float(xx[s]), float(xy_[s])), (float(yx[s]), float(yy[s]))
                amps = (ex[0] * amps[0] + ey[0] * amps[1], ex[1] * amps[0] + ey[1] * amps[1])
                note('BC set %d: kinds %d/%d in the local frame x = (%g, %g), y = (%g, %g): the same kind in global '
                     'x and y, amplitudes turned into it (%r, %r)' % (s, kinds[0], kinds[1], ex[0], ex[1], ey[0],
                                                                        ey[1], amps[0], amps[1]))
            else:
                L.append('# NOT TRANSLATED: BC set %d uses the local frame x = (%g, %g), y = (%g, %g): kinds %d/%d, '
                         'amplitudes %g/%g' % (s, xx[s], xy_[s], yx[s], yy[s], fx[s], fy[s], ax[s], ay[s]))
                diff('BC set %d (a rotated local frame, kinds %d/%d: a condition of another kind in each local '
                     'direction) not translated: its nodes are free' % (s, kinds[0], kinds[1]))
                continue
        fixed = ''.join(d for d, k, a in zip('xy', kinds, amps) if k == 3 and a == 0 and not hist)
        # kinds other than 1, 2, 3 freeze the velocity at its initial value (forces ignored): held
        # when it is 0, else a prescribed velocity, one fix per distinct initial velocity
        if any(frozen):
            vfro = {}
            for n in nodes_s:
                vfro.setdefault(tuple(float(vel[n][d]) if frozen[d] else None for d in (0, 1)), []).extend(ids_of_node[n])
            if all(v in (0.0, None) for key in vfro for v in key):
                fixed += ''.join(d for d, f in zip('xy', frozen) if f)
            else:
                for k, (key, fids) in enumerate(sorted(vfro.items(), key=lambda kv: min(kv[1]))):
                    zname = '%s_z%d' % (gname, k)
                    L.append(wrap(SYNTAX['group_ids'].format(name=zname, ids='').rstrip(), [str(i) for i in fids]))
                    L.append(SYNTAX['fix_vel'].format(id=zname, group=zname, hist='',
                                                      vx='NULL' if key[0] is None else repr(key[0]),
                                                      vy='NULL' if key[1] is None else repr(key[1])))
                note('BC set %d: kinds %d/%d freeze the initial velocity: a prescribed velocity per distinct '
                     'initial velocity' % (s, kinds[0], kinds[1]))
        fixed = ''.join(sorted(set(fixed)))
        if fixed:
            L.append(SYNTAX['fix_fixed'].format(id='%s_fix' % gname, group=gname, dirs=fixed))
        vparts = [('%r' % a) if (k == 3 and (a != 0 or hist)) else 'NULL' for k, a in zip(kinds, amps)]
        if vparts != ['NULL', 'NULL']:
            L.append(SYNTAX['fix_vel'].format(id='%s_vel' % gname, group=gname, vx=vparts[0], vy=vparts[1], hist=hist))
        # kind 1: the force A on every copy of the node; kind 2: the acceleration A, a force m A on a
        # copy of mass m.  `load point` gives each of the node's c copies 1/c of the force: write c A
        # (kind 1) and A times the copies' total mass (kind 2, exact when the copies' masses are equal)
        for n in nodes_s:
            cm = copies[n]
            f = [0.0, 0.0]
            for d in (0, 1):
                if kinds[d] == 1:
                    f[d] = amps[d] * len(cm) if len(cm) > 1 else amps[d]
                elif kinds[d] == 2:
                    f[d] = amps[d] * sum(cm)
            if f == [0.0, 0.0]:
                continue
            if 2 in kinds and max(cm) - min(cm) > 1e-12 * max(abs(x) for x in cm):
                diff('BC set %d: node %d: kind 2 (acceleration) on %d copies of different masses (%g..%g): '
                     'written as the force A m shared equally, not A m per copy' % (s, n, len(cm), min(cm), max(cm)))
            L.append(SYNTAX['load_point'].format(id='%s_f%d' % (gname, n), node=ids_of_node[n][0],
                                                 fx=f[0], fy=f[1], hist=hist))
        if 2 in kinds:
            note('BC set %d: kind 2 (acceleration) written as point forces A m (m: the lumped node mass '
                 'rho A0/3 summed over the node\'s triangles)' % s)
        if any(k == 1 and a != 0 for k, a in zip(kinds, amps)) and any(len(copies[n]) > 1 for n in nodes_s):
            note('BC set %d: a point force on a node with c copies (joint insertion) is written as c F: '
                 '`load point` shares it, Y2D gives every copy F' % s)
        if float(at[s]) != 0.0 and below_edge_threshold(at[s], hist_of[s]):
            note('BC set %d: edge shear D1PNAT %r, times its time factor, never exceeds 1e-10: Y2D loads no edge '
                 'with it (ALGORITHMS 2.5, 9); left out' % (s, float(at[s])))
        elif float(at[s]) != 0.0:
            L.append('# NOT TRANSLATED: BC set %d: edge shear traction D1PNAT = %r' % (s, float(at[s])))
            diff('BC set %d: edge shear traction D1PNAT %r not translated (the native traction has a fixed '
                 'direction, Y2D\'s follows the edge)' % (s, float(at[s])))
    L.append('')
    for s_ in hist_of:
        if float(ap[s_]) != 0.0 and below_edge_threshold(ap[s_], hist_of[s_]):
            note('BC set %d: edge pressure D1PNAP %r, times its time factor, never exceeds 1e-10: Y2D loads no '
                 'edge with it (ALGORITHMS 2.5, 9), nor an edge between it and another pressure set; left out'
                 % (s_, float(ap[s_])))
            ap[s_] = 0.0
    pressure_loads(L, note, diff, ne, elto, meshed, nopr, nset, ap, hist_of, ids_of_node)

    # ---- nodes Y2D never moves: a BC set outside 0..NPNSET-1 (FORMAT.md 6), or a lumped mass of
    # 1e-10 or less (ALGORITHMS 7, 9: tonnes and millimetres with fine cells).  Held in place
    # natively: the same while they stand still; Y2D keeps a velocity they start with (in its
    # kinetic energy and viscous term), a fix sets it to 0
    still, partly = [], []
    for n in used:
        light = [m <= 1e-10 for m in copies.get(n, [])]
        if not (0 <= nopr[n] < nset) or (light and all(light)):
            still.append(n)
        elif any(light):
            partly.append(n)
    if still:
        L.append('# nodes Y2D never moves (a BC set outside 0..NPNSET-1, or mass <= 1e-10)')
        L.append(wrap(SYNTAX['group_ids'].format(name='still', ids='').rstrip(), [str(n) for n in still]))
        L.append(SYNTAX['fix_fixed'].format(id='still_fix', group='still', dirs='xy'))
        L.append('')
        note('%d node(s) Y2D never moves (first: %d) are held by a fix' % (len(still), still[0]))
        moving = [n for n in still if (float(vel[n][0]), float(vel[n][1])) != (0.0, 0.0)]
        if moving:
            diff('%d node(s) Y2D never moves start with a velocity (first: node %d): Y2D keeps it in its kinetic '
                 'energy and viscous term, the native fix sets it to 0' % (len(moving), moving[0]))
    if partly:
        diff('%d node(s) have copies of mass <= 1e-10 beside heavier ones (first: node %d): Y2D moves only the '
             'heavier copies, the native deck moves them all' % (len(partly), partly[0]))
    diedi = float(g('YDI/DIEDI', 1e15))
    if g('YDI/MICOUP') > 0 and not any(meshed) and diedi < float(g('YDI/DIEZON', 0.0)):
        diff('DIEDI %r below DIEZON: Y2D makes its first contact search only once the bodies have moved '
             'DIEZON - DIEDI; the native deck searches at the first step' % diedi)
    if not CONTROL.get(src, {}).get('ydoit'):
        diff('the deck has no $YDOIT before %s: Y2D (and yfdem DECK.y) compute nothing; the converted deck runs'
             % ('its $YSTOP' if CONTROL.get(src, {}).get('ystop') else 'its end'))

    # ---- run control
    dt = float(g('YDC/DCSTEC', 0.0))
    ncstep = int(g('YDC/NCSTEP', 0))
    nsteps = int(g('YDC/MCSTEP', 0)) - ncstep
    if ncstep:
        # yfdem DECK.y starts its step counter at NCSTEP (src/y2d/y2d_model.c); a native deck has no command
        # that sets it (only read_restart restores a step; 'run N upto' needs the counter there already)
        kf, kl = K.key_at('YDC/NCSTEP', (src, 0))
        warn('%s:%d: /YD/YDC/NCSTEP %d: the converted deck counts its steps from 0, yfdem DECK.y from %d (no native '
             'command sets the step counter): its step numbers (summary, thermo lines, dump frames) are those of '
             'yfdem DECK.y less %d, and its thermo lines and dumps every N steps fall at its own multiples of N; '
             'the physics is the same' % (kf, kl, ncstep, ncstep, ncstep))
    # MCSTEP <= NCSTEP with DCSTEC 0 (validate allows it): Y2D and yfdem DECK.y compute nothing, and
    # a native run, even of 0 steps, needs a time step: the converted deck builds the scene only
    idle = nsteps <= 0 and not dt > 0
    if idle:
        note('/YD/YDC/MCSTEP <= /YD/YDC/NCSTEP and DCSTEC 0: Y2D computes nothing; the converted deck builds the '
             'scene and has no timestep or run')
    else:
        L.append(SYNTAX['timestep'].format(dt=dt))
    icshtf = int(g('YDC/ICSHTF', 100))
    if not 0 < icshtf <= 2000000000:
        note('ICSHTF %d: no progress lines in Y2D; written as thermo 0 (start and end only)' % icshtf)
    L.append(SYNTAX['thermo'].format(n=icshtf if 0 < icshtf <= 2000000000 else 0))
    icoutf = int(g('YDC/ICOUTF', 10))
    if icoutf <= 0:
        # Y2D's rule (FORMAT.md 3.1, yfdem's reader too): ICOUTF <= 0 is 10, frames every 10 steps (the
        # converted deck had none, 2026-11-29)
        note('ICOUTF %d: Y2D writes a frame every 10 steps (ICOUTF <= 0 is 10): dump every 10' % icoutf)
        icoutf = 10
    if icoutf <= nsteps:
        L.append(SYNTAX['dump'].format(n=icoutf, file=deck_word(base + '.h5')))
    if not idle:
        L.append(SYNTAX['run'].format(n=max(nsteps, 0)))
    if 'YDO/NOHYS' in K:
        note('history output /YD/YDO/ not translated (output only)')
    head = ['# NOTES: DIFFERS = the converted deck does not run the physics of the .y there; WARNING = the same '
            'physics, told differently; note = an exact translation'] + \
        ['#   %s %s' % ('DIFFERS:' if d is True else 'WARNING:' if d == WARN else 'note:', t) for t, d in notes] \
        if notes else []
    with open(out + '.deck', 'w') as f:
        f.write('\n'.join(L[:1] + head + L[1:]) + '\n')
    return out + '.deck', notes


EXIT_ERROR, EXIT_DIFFERS = 1, 3


def main():
    ap = argparse.ArgumentParser(
        description='Y2D .y deck -> yfdem deck (see the docstring).  Exit status: 0 the converted deck runs '
                    'the physics of `yfdem DECK.y`; 1 error (no OUT.deck written); 2 bad usage; %d written, but '
                    'the deck does not run the same physics (each difference is a warning on stderr and a '
                    'DIFFERS note in OUT.deck); 0 for that too with --allow-differences.' % EXIT_DIFFERS)
    ap.add_argument('deck')
    ap.add_argument('out', help='output base name: OUT.deck, OUT.nodes, OUT.tris')
    ap.add_argument('--allow-differences', action='store_true',
                    help='exit 0 although the converted deck does not run the same physics (the warnings stay)')
    a = ap.parse_args()
    try:
        find_yfdem()
    except NoYfdem as e:
        sys.stderr.write('error: %s\n' % e)
        sys.exit(2)
    try:
        path, notes = convert(a.deck, a.out)
    except (DeckError, OSError, KeyError, IndexError, ValueError) as e:
        msg = str(e) if not isinstance(e, KeyError) else 'required key %s missing' % e
        if isinstance(e, OSError) and e.filename:
            # the file and the system's reason, not Python's "[Errno 2] ...: 'OUT.nodes'" after the deck's name
            # (a missing output folder was reported as an error of the .y, 2026-11-29)
            sys.stderr.write('error: cannot %s %s: %s\n' % ('read' if os.path.abspath(e.filename) == os.path.abspath(
                a.deck) else 'write', e.filename, e.strerror or msg))
            sys.exit(EXIT_ERROR)
        # a DeckError names its file and line first (an included file's, maybe): no second name
        sys.stderr.write('error: %s\n' % msg if isinstance(e, DeckError) else 'error: %s: %s\n' % (a.deck, msg))
        sys.exit(EXIT_ERROR)
    ndiff = sum(1 for _, d in notes if d is True)
    nwarn = sum(1 for _, d in notes if d == WARN)
    for t, d in notes:
        if d is True:
            sys.stderr.write('warning: %s: %s\n' % (a.deck, t))
        elif d == WARN:   # the text names its FILE:LINE, as yfdem's reader's warnings do
            sys.stderr.write('warning: %s\n' % t)
    nnote = len(notes) - ndiff - nwarn
    print('wrote %s (%d difference%s of physics, %d warning%s, %d note%s)' % (
        path, ndiff, '' if ndiff == 1 else 's', nwarn, '' if nwarn == 1 else 's', nnote, '' if nnote == 1 else 's'))
    if ndiff and not a.allow_differences:
        sys.stderr.write('%s: the converted deck does not run the physics of %s (%d difference%s above; '
                         '--allow-differences accepts them)\n' % (path, a.deck, ndiff, '' if ndiff == 1 else 's'))
        sys.exit(EXIT_DIFFERS)


if __name__ == '__main__':
    main()
