#!/usr/bin/env python3
"""failure_mode: name the broken-crack pattern of a beam or column impact run (decks/beam.deck, decks/column.deck and their sweeps).

The seed paper (Yuan, Xu & Yang 2011) reports, for its beam hit at midspan: first a tensile crack at
the bottom of midspan, then an inclined pair (an inverted V, like a punching cone), then cracks from
the top face near the end supports.  decks/beam.deck on its default scene breaks instead as a
vertical punched plug.  This tool reads a run's broken joints (the `fracture_log` CSV: step, time,
x, y, mode, ..., length) and the scene's geometry, and reports which of four classes of *broken*
cracks appear and when each first broke (opened joints are not used: the paper's cracks are
through cracks, and on these scenes almost every joint near the impact opens).

Geometry (all in m): beam length L, depth D, impactor side a (half-width b = a/2) centred at
xc = L/2, cell size h, inner supports' centres si from each end.  s = |x - xc|.  A joint's y is
its midpoint at the break.  The classes and the regions they use:

  plug      near-vertical shear cracks down the impactor's edges: on EACH side, broken joints with
            -h <= s - b <= max(h, D/8) (one cell, or a 7-degree slope over the depth, outwards)
            cover >= 3/4 of the depth (union of [y - len/2, y + len/2]).
            Time: the first break in the two edge bands.  When the edge bands hold breaks but
            do not make a plug, the class `edge` (shear under the impactor's edges) is
            reported instead, with the same time.
  flexural  a mode I break at the bottom of midspan (s <= b + D/2, y <= max(D/4,
            0.55 h)) with no earlier break just above it (|dx| <= 1.5 h, dy <= 2 h): a crack that starts at the
            bottom face, not the lower end of a shear crack come down from the impactor (the
            plug's cracks break top first).  Time: the first such break.  `flexural_first` says whether it is the
            beam's first break (ties in the same step allowed): the paper's first observation.
  cone      an inclined pair: on EACH flank (b + max(h, D/8) < s <= b + 2 D) the broken joints cover
            >= D/3 of the depth, spread >= max(D/4, h) horizontally, and move away from
            midspan downwards (least-squares ds/dy < 0: the inverted V, a punching cone's
            trace).  Time: the later of the two flanks' first breaks (the pair is complete).
  supports  cracks from the top face over the end spans: broken joints with
            y >= D - max(D/4, 0.55 h) and x <= si + D or x >= L - si - D.  Time: the first one.

Breaks outside every class region are counted as `other`.  The `sequence` is the present classes
ordered by their time; `paper` is true when flexural (first), cone and supports are all present in
that order (t_flexural < t_cone < t_supports).  `label` is the sequence joined with '>' ("none" when
nothing broke).

The column (decks/column.deck; `--scene column`, or found from the run's column_breaks.csv).  The
paper sees, for its column hit axially: longitudinal cracks (two in the middle, three in the lower
part) and two inclined cracks near the top sides first, then crushing at the shoulders under the
impactor's edges, then fragments.  Geometry: column width W, height H, impactor side a (b = a/2)
centred at xc = W/2, the overhang o = W/2 - b, cell size h = W/nx.  The zones are disjoint:

  shoulders  S: within o + h of a side and y >= H - max(o, h) - h (the column's top corners beside
             and under the impactor's edges).  Time: the first break in S ("crushing").
  longitudinal  in the lower half (y <= H/2): a crack along a vertical mesh line x0 = i h, made of
             the broken joints within 0.3 h of it (the line's edges, spanning their length in y, and
             the cross pattern's diagonals beside it, spanning len / sqrt 2), whose
             union in y has a contiguous piece >= max(3 h, H/10).  `count` is the number of such
             cracks (the paper: three; cracked lines side by side are one crack), `x` their
             positions (the mean of their lines).  Time: the first break of those pieces.
  inclined   in the upper half outside S (y > H/2): on EACH side of the axis, a chain of broken
             diagonals on one 45-degree mesh line (x - y or x + y a multiple of h, within 0.2 h),
             consecutive ones at most 0.6 h apart in y, spanning >= max(2 h, W/5) in y.  `shape`: a
             Lambda (the chain moves away from the axis downwards: the wedge under a punch) or a V
             (towards the axis downwards: the cone under a platen), or both.  Time: the later of the
             two sides' first chain breaks (the pair complete).

The inclined test uses the `pattern cross` lattice (its diagonals are the only inclined joints, all
at 45 degrees): positions at the break are the initial ones to well within 0.1 h (the column's
strain before its joints break is about 1e-3: the top moves down about 0.1 h at nx 12; the other family is 0.5 h off).  `paper` is true when longitudinal (>= 2 cracks) and
inclined both break before the shoulders, and the shoulders break.

  tools/failure_mode.py RUNDIR                  (a yfsweep run directory: run.deck + *_breaks.csv)
  tools/failure_mode.py --breaks beam_breaks.csv --set L=1.0 --set D=0.1 --set nx=40 [--json]
  tools/failure_mode.py --scene column --breaks column_breaks.csv --set nx=12 --set H=0.3

Geometry comes from the run's deck (`variable NAME index VALUE` lines: L, D, a, nx, si; h = 1/nx;
for the column W, H, a, nx; h = W/nx) with the deck's defaults for names it lacks; --set
NAME=VALUE overrides.
"""
import argparse
import csv
import glob
import json
import os
import re
import sys

DEFAULTS = {"L": 1.0, "D": 0.1, "a": 0.05, "nx": 60.0, "si": 0.15, "so": 0.05}
CLASSES = ("plug", "edge", "flexural", "cone", "supports")
COLUMN_DEFAULTS = {"W": 0.15, "H": 0.30, "a": 0.10, "nx": 16.0, "mu": 0.0}
COLUMN_CLASSES = ("longitudinal", "inclined", "shoulders")
VAR_RE = re.compile(r"^\s*variable\s+(\S+)\s+index\s+(\S+)")


def deck_geometry(path, over=None, column=False):
    """Geometry dict from a deck's `variable NAME index VALUE` lines, beam.deck's (column.deck's when
    column) defaults otherwise."""
    g = dict(COLUMN_DEFAULTS if column else DEFAULTS)
    if path:
        with open(path) as f:
            for ln in f:
                m = VAR_RE.match(ln)
                if m and m.group(1) in g:
                    try:
                        g[m.group(1)] = float(m.group(2))
                    except ValueError:
                        pass
    for k, v in (over or {}).items():
        g[k] = float(v)
    g["h"] = (g["W"] if column else 1.0) / g["nx"]
    return g


def read_breaks(path):
    """Rows of a fracture_log CSV as dicts of floats (mode kept as text)."""
    out = []
    with open(path, newline="") as f:
        for r in csv.DictReader(f):
            out.append({"time": float(r["time"]), "step": int(r["step"]), "x": float(r["x"]),
                        "y": float(r["y"]), "mode": r["mode"], "len": float(r["length"])})
    return out


def _coverage(rows, D):
    """Length of the union of the joints' y spans [y - len/2, y + len/2] clipped to [0, D]."""
    iv = sorted((max(0.0, r["y"] - r["len"] / 2), min(D, r["y"] + r["len"] / 2)) for r in rows)
    tot, cur_a, cur_b = 0.0, None, None
    for a, b in iv:
        if cur_b is None or a > cur_b + 1e-12:
            if cur_b is not None:
                tot += cur_b - cur_a
            cur_a, cur_b = a, b
        else:
            cur_b = max(cur_b, b)
    if cur_b is not None:
        tot += cur_b - cur_a
    return tot


def classify(breaks, g):
    """breaks: read_breaks rows; g: deck_geometry.  Returns {class: {present, time, count}, sequence,
    label, paper, other, first_break}."""
    L, D, h, si = g["L"], g["D"], g["h"], g["si"]
    b, xc = g["a"] / 2, g["L"] / 2
    zone = max(D / 4, 0.55 * h)
    res = {c: {"present": False, "time": None, "count": 0} for c in CLASSES}
    used = set()
    first = min((r["time"] for r in breaks), default=None)

    # plug: the two edge bands, each covering 3/4 of the depth
    wout = max(h, D / 8)
    sides = [[r for r in breaks if -h <= abs(r["x"] - xc) - b <= wout and (r["x"] - xc) * sgn > 0]
             for sgn in (-1, 1)]
    band = sides[0] + sides[1]
    if band:
        full = all(_coverage(sd, D) >= 0.75 * D for sd in sides)
        res["plug" if full else "edge"].update(present=True, time=min(r["time"] for r in band), count=len(band))
        used.update(id(r) for r in band)

    # flexural: mode I at the bottom of midspan, started there
    bot = [r for r in breaks if abs(r["x"] - xc) <= b + D / 2 and r["y"] <= zone and r["mode"] == "I"
           and not any(abs(q["x"] - r["x"]) <= 1.5 * h and r["y"] < q["y"] <= r["y"] + 2 * h and q["time"] < r["time"]
                       for q in breaks)]
    res["flexural_first"] = False
    if bot:
        t = min(r["time"] for r in bot)
        res["flexural"].update(time=t, count=len(bot), present=True)
        res["flexural_first"] = t <= first
        used.update(id(r) for r in bot)

    # cone: both flanks, upper and lower halves, widening downwards
    flank_ok, flank_t, nfl = [], [], 0
    for sgn in (-1, 1):
        fl = [r for r in breaks if b + wout < (r["x"] - xc) * sgn <= b + 2 * D]
        nfl += len(fl)
        used.update(id(r) for r in fl)
        ok = False
        if len(fl) >= 2:
            ss = [abs(r["x"] - xc) for r in fl]
            ys = [r["y"] for r in fl]
            my, ms = sum(ys) / len(ys), sum(ss) / len(ss)
            syy = sum((y - my) ** 2 for y in ys)
            sys_ = sum((y - my) * (s_ - ms) for y, s_ in zip(ys, ss))
            ok = (_coverage(fl, D) >= D / 3 and max(ss) - min(ss) >= max(D / 4, h) and syy > 0 and sys_ / syy < 0)
        flank_ok.append(ok)
        flank_t.append(min((r["time"] for r in fl), default=None))
    if nfl:
        res["cone"]["count"] = nfl
        res["cone"]["present"] = all(flank_ok)
        if all(t is not None for t in flank_t):
            res["cone"]["time"] = max(flank_t)

    # supports: top face over the end spans
    sup = [r for r in breaks if r["y"] >= D - zone and (r["x"] <= si + D or r["x"] >= L - si - D)]
    if sup:
        res["supports"].update(present=True, time=min(r["time"] for r in sup), count=len(sup))
        used.update(id(r) for r in sup)

    seq = sorted((c for c in CLASSES if res[c]["present"]), key=lambda c: (res[c]["time"], CLASSES.index(c)))
    tf, tc, ts = (res[c]["time"] if res[c]["present"] else None for c in ("flexural", "cone", "supports"))
    res["sequence"] = seq
    res["label"] = ">".join(seq) if seq else ("none" if not breaks else "other")
    res["paper"] = None not in (tf, tc, ts) and res["flexural_first"] and tf < tc < ts
    res["other"] = sum(1 for r in breaks if id(r) not in used)
    res["broken"] = len(breaks)
    res["first_break"] = first
    return res


def _runs(ys, gap):
    """Contiguous pieces of sorted intervals (lo, hi, row): [(lo, hi, rows)], joined across gaps <= gap."""
    out = []
    for lo, hi, r in sorted(ys, key=lambda t: t[0]):
        if out and lo <= out[-1][1] + gap:
            out[-1][1] = max(out[-1][1], hi)
            out[-1][2].append(r)
        else:
            out.append([lo, hi, [r]])
    return out


def classify_column(breaks, g):
    """breaks: read_breaks rows of a column run; g: deck_geometry(column=True).  Returns {class:
    {present, time, count, ...}, sequence, label, paper, other, broken, first_break}."""
    W, H, h = g["W"], g["H"], g["h"]
    xc, o = W / 2, max(0.0, (W - g["a"]) / 2)
    res = {c: {"present": False, "time": None, "count": 0} for c in COLUMN_CLASSES}
    first = min((r["time"] for r in breaks), default=None)

    def in_s(r):
        return W / 2 - abs(r["x"] - xc) <= o + h and r["y"] >= H - max(o, h) - h

    sh = [r for r in breaks if in_s(r)]
    lower = [r for r in breaks if not in_s(r) and r["y"] <= H / 2]
    upper = [r for r in breaks if not in_s(r) and r["y"] > H / 2]
    if sh:
        res["shoulders"].update(present=True, time=min(r["time"] for r in sh), count=len(sh))

    # longitudinal: pieces along vertical mesh lines in the lower half
    lines = {}
    for r in lower:
        i = round(r["x"] / h)
        dx = abs(r["x"] - i * h)
        if 0 < i < round(W / h) and dx <= 0.3 * h:
            half = (r["len"] if dx < 0.125 * h else r["len"] / 2 ** 0.5) / 2
            lines.setdefault(i, []).append((r["y"] - half, r["y"] + half, r))
    need = max(3 * h, H / 10)
    cracked, tl, used = [], [], set(id(r) for r in sh)
    for i, ys in sorted(lines.items()):
        pieces = [p for p in _runs(ys, 0.1 * h) if p[1] - p[0] >= need - 1e-9]
        used.update(id(r) for p in pieces for r in p[2])
        if pieces:
            cracked.append(i)
            tl.append(min(r["time"] for p in pieces for r in p[2]))
    # lines side by side are one crack zigzagging between them: a crack per run of adjacent lines
    groups = []
    for i in cracked:
        if groups and i == groups[-1][-1] + 1:
            groups[-1].append(i)
        else:
            groups.append([i])
    if groups:
        res["longitudinal"].update(present=True, time=min(tl), count=len(groups),
                                   x=[h * sum(gr) / len(gr) for gr in groups])

    # inclined: a 45-degree diagonal chain on each side of the axis in the upper half
    need = max(2 * h, W / 5)
    side_t, shapes = [], set()
    for sgn in (-1, 1):
        rows = [r for r in upper if (r["x"] - xc) * sgn > 0.3 * h]
        best = None
        for fam, f in (("/", lambda r: r["x"] - r["y"]), ("\\", lambda r: r["x"] + r["y"])):
            groups = {}
            for r in rows:
                k = f(r) / h
                if abs(k - round(k)) <= 0.2 and not (abs(r["x"] / h - round(r["x"] / h)) < 0.1):
                    groups.setdefault(round(k), []).append((r["y"], r["y"], r))
            for ys in groups.values():
                for lo, hi, rs in _runs(ys, 0.6 * h):
                    if hi - lo + h / 2 >= need - 1e-9:
                        used.update(id(r) for r in rs)
                        t = min(r["time"] for r in rs)
                        # left side ("/": x falls as y falls) and right side ("\\") move away downwards
                        shapes.add("lambda" if (fam == "/") == (sgn < 0) else "V")
                        best = t if best is None else min(best, t)
        side_t.append(best)
    res["inclined"]["count"] = sum(1 for r in upper if id(r) in used)
    if all(t is not None for t in side_t):
        res["inclined"].update(present=True, time=max(side_t), shape="+".join(sorted(shapes)))

    seq = sorted((c for c in COLUMN_CLASSES if res[c]["present"]),
                 key=lambda c: (res[c]["time"], COLUMN_CLASSES.index(c)))
    tl_, ti, ts = (res[c]["time"] if res[c]["present"] else None for c in COLUMN_CLASSES)
    res["sequence"] = seq
    res["label"] = ">".join(seq) if seq else ("none" if not breaks else "other")
    res["paper"] = None not in (tl_, ti, ts) and res["longitudinal"]["count"] >= 2 and tl_ < ts and ti < ts
    res["other"] = sum(1 for r in breaks if id(r) not in used)
    res["broken"] = len(breaks)
    res["first_break"] = first
    return res


def is_column(rundir_or_csv):
    """A column run: its break log is column_breaks.csv (decks/column.deck's fracture_log)."""
    return os.path.basename(rundir_or_csv).startswith("column") or \
        bool(glob.glob(os.path.join(rundir_or_csv, "column_breaks.csv")))


def classify_run(rundir, over=None):
    """Classify a yfsweep run directory (run.deck and one *_breaks.csv): beam or column by the log's name."""
    deck = os.path.join(rundir, "run.deck")
    found = sorted(glob.glob(os.path.join(rundir, "*_breaks.csv")))
    if not found:
        raise FileNotFoundError("%s: no *_breaks.csv (the deck needs fracture_log)" % rundir)
    col = os.path.basename(found[0]).startswith("column")
    g = deck_geometry(deck if os.path.exists(deck) else None, over, column=col)
    return (classify_column if col else classify)(read_breaks(found[0]), g)


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("rundir", nargs="?", help="a yfsweep run directory")
    p.add_argument("--breaks", help="fracture_log CSV (instead of RUNDIR)")
    p.add_argument("--deck", help="deck whose `variable ... index` lines give the geometry")
    p.add_argument("--set", action="append", default=[],
                   help="NAME=VALUE geometry override (beam: L, D, a, nx, si; column: W, H, a, nx)")
    p.add_argument("--scene", choices=["beam", "column"],
                   help="which classes (default: column when the log or run holds column_breaks.csv)")
    p.add_argument("--json", action="store_true", help="print the whole result as JSON")
    a = p.parse_args(argv)
    col = a.scene == "column" if a.scene else is_column(a.breaks or a.rundir or "")
    names = COLUMN_DEFAULTS if col else DEFAULTS
    over = {}
    for it in a.set:
        k, _, v = it.partition("=")
        if k not in names or not v:
            sys.exit("failure_mode: --set NAME=VALUE with NAME one of %s, got '%s'" % (", ".join(names), it))
        over[k] = v
    try:
        if a.breaks:
            res = (classify_column if col else classify)(read_breaks(a.breaks), deck_geometry(a.deck, over, col))
        elif a.rundir:
            res = classify_run(a.rundir, over)
        else:
            sys.exit("failure_mode: give RUNDIR or --breaks CSV")
    except (OSError, KeyError, ValueError) as e:
        sys.exit("failure_mode: %s" % e)
    if a.json:
        print(json.dumps(res, indent=1))
    else:
        times = ", ".join("%s %.1f us" % (c, res[c]["time"] * 1e6) for c in res["sequence"])
        if col and res["longitudinal"]["present"]:
            times += "; %d longitudinal" % res["longitudinal"]["count"]
        if col and res["inclined"]["present"]:
            times += "; inclined " + res["inclined"]["shape"]
        print("%s%s (%d broken, %d other)%s" % (res["label"], " [" + times + "]" if times else "",
                                               res["broken"], res["other"], "  paper's sequence" if res["paper"] else ""))
    return 0


if __name__ == "__main__":
    sys.exit(main())
