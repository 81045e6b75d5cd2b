#!/usr/bin/env python3
"""y2d_compare.py: compare two directories of Y2D reference CSV files (shared/y2d/README.md 3).

    tools/y2d_compare.py REF_DIR RUN_DIR [--deck a|b|c|d1] [--du TOL --dv TOL --energy TOL]

REF_DIR holds the original program's files (corners_NNNNNNN.csv, summary.csv, broken.csv,
probes.csv), RUN_DIR the same files written by yfdem's `dump ID y2dref DIR ...`.  For every corner
table of REF_DIR the largest deviation is printed, relative to the max |u| (resp. |v|) over all
corners at that step (never element-wise: far-field values are round-off noise); the summary
energies relative to their maximum over the run; the broken joints as pairs and steps.  The
tolerances are those of README section 4.2 for the named deck (the deck is guessed from the
directory name when --deck is not given), or the ones given on the command line.  Exit status 0
when everything is within tolerance, 1 otherwise.  Standard library only.
"""
import argparse
import csv
import math
import os
import re
import sys

# README 4.2: (last step of the range, du, dv, broken rule) per deck; energy tolerance per deck.
TOL = {
    "a": {"steps": [(10**12, 1e-8, 1e-7)], "broken": "exact", "energy": 1e-8},
    "d1": {"steps": [(10**12, 1e-8, 1e-7)], "broken": "exact", "energy": 1e-8},
    "b": {"steps": [(5000, 1e-8, 1e-7), (10**12, 1e-8, 1e-5)], "broken": "pm1", "energy": 1e-8},
    "c": {"steps": [(1200, 1e-8, 1e-6), (3000, 1e-6, 1e-4), (10**12, 1e-2, None)],
          "broken": "pm1", "energy": None, "statistical_from": 9000},
}


def read_csv(path):
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    return rows[0], [r for r in rows[1:] if r]


def corners(path):
    head, rows = read_csv(path)
    out = {}
    for r in rows:
        out[(int(r[0]), int(r[1]))] = (int(r[2]), [float(x) for x in r[3:7]])
    return out


def rel_dev(ref, run, cols):
    """max |difference| / max |value| over all corners for the given columns (0,1: u; 2,3: v)."""
    vmax = 0.0
    dmax = 0.0
    where = None
    for key, (node, vals) in ref.items():
        if key not in run:
            return math.inf, key, 0.0
        other = run[key][1]
        for c in cols:
            vmax = max(vmax, abs(vals[c]))
            d = abs(vals[c] - other[c])
            if d > dmax:
                dmax, where = d, key
    return (dmax / vmax if vmax > 0 else dmax), where, vmax


def tolerances(deck, step):
    for last, du, dv in TOL[deck]["steps"]:
        if step <= last:
            return du, dv
    return None, None


def guess_deck(name):
    base = os.path.basename(os.path.normpath(name))
    m = re.match(r"(d1|a|b|c)_", base)
    return m.group(1) if m else None


def broken_rows(path):
    if not os.path.exists(path):
        return []
    _, rows = read_csv(path)
    return [(int(r[0]), int(r[1]), int(r[2]), int(r[3]), int(r[4])) for r in rows]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("ref")
    ap.add_argument("run")
    ap.add_argument("--deck", choices=sorted(TOL))
    ap.add_argument("--du", type=float)
    ap.add_argument("--dv", type=float)
    ap.add_argument("--energy", type=float)
    a = ap.parse_args()
    deck = a.deck or guess_deck(a.ref) or guess_deck(a.run) or "a"
    ok = True

    steps = sorted(int(m.group(1)) for f in os.listdir(a.ref) for m in [re.match(r"corners_(\d+)\.csv$", f)] if m)
    for st in steps:
        name = "corners_%07d.csv" % st
        rp = os.path.join(a.run, name)
        if not os.path.exists(rp):
            print("%s step %d: missing %s" % (deck, st, rp))
            ok = False
            continue
        ref, run = corners(os.path.join(a.ref, name)), corners(rp)
        du, wu, umax = rel_dev(ref, run, (0, 1))
        dv, wv, vmax = rel_dev(ref, run, (2, 3))
        badnode = sum(1 for k in ref if k in run and run[k][0] != ref[k][0])
        tu, tv = tolerances(deck, st)
        if a.du is not None:
            tu = a.du
        if a.dv is not None:
            tv = a.dv
        good = (tu is None or du <= tu) and (tv is None or dv <= tv) and badnode == 0
        ok &= good
        print("%s step %6d: du %.3g (at elem:corner %s, max|u| %.3g, tol %s)  dv %.3g (at %s, max|v| %.3g, tol %s)%s  %s"
              % (deck, st, du, "%d:%d" % wu if wu else "-", umax, tu, dv, "%d:%d" % wv if wv else "-", vmax, tv,
                 "  %d corners name other nodes" % badnode if badnode else "", "ok" if good else "FAIL"))

    # summary energies, relative to the run maxima
    sref, srun = os.path.join(a.ref, "summary.csv"), os.path.join(a.run, "summary.csv")
    if os.path.exists(sref) and os.path.exists(srun):
        _, r1 = read_csv(sref)
        _, r2 = read_csv(srun)
        m2 = {int(r[0]): r for r in r2}
        stat_from = TOL[deck].get("statistical_from")
        for col, name in ((2, "kinetic"), (3, "elastic")):
            emax = max(abs(float(r[col])) for r in r1) or 1.0
            worst, at = 0.0, None
            for r in r1:
                st = int(r[0])
                if st not in m2 or (stat_from and st > 3000):
                    continue
                d = abs(float(r[col]) - float(m2[st][col])) / emax
                if d > worst:
                    worst, at = d, st
            tol = a.energy if a.energy is not None else TOL[deck]["energy"]
            if stat_from:  # deck c: statistical comparison at the end of the run
                last = r1[-1]
                if int(last[0]) in m2:
                    d = abs(float(last[col]) - float(m2[int(last[0])][col])) / emax
                    good = d <= 1e-3
                    ok &= good
                    print("%s summary %s at step %s: %.3g of the run maximum (tol 1e-3) %s"
                          % (deck, name, last[0], d, "ok" if good else "FAIL"))
            good = tol is None or worst <= tol
            ok &= good
            print("%s summary %s: max deviation %.3g of the run maximum %.6g (at step %s, tol %s) %s"
                  % (deck, name, worst, emax, at, tol, "ok" if good else "FAIL"))
        missing = [int(r[0]) for r in r1 if int(r[0]) not in m2]
        if missing:
            ok = False
            print("%s summary: %d reference rows missing in the run (first step %d) FAIL" % (deck, len(missing), missing[0]))

    # broken joints
    b1 = broken_rows(os.path.join(a.ref, "broken.csv"))
    b2 = broken_rows(os.path.join(a.run, "broken.csv"))
    if b1 or b2:
        rule = TOL[deck]["broken"]
        stat_from = TOL[deck].get("statistical_from")
        p1 = {r[1:]: r[0] for r in b1}
        p2 = {r[1:]: r[0] for r in b2}
        if stat_from:
            good = abs(len(b1) - len(b2)) <= 5
            print("%s broken: %d reference, %d run (tol +-5) %s" % (deck, len(b1), len(b2), "ok" if good else "FAIL"))
            # before step 3000 the set must be identical
            e1 = {k for k, s in p1.items() if s <= 3000}
            e2 = {k for k, s in p2.items() if s <= 3000}
            good2 = e1 == e2
            print("%s broken up to step 3000: %d vs %d, %s" % (deck, len(e1), len(e2), "same set ok" if good2 else "FAIL"))
            ok &= good and good2
        else:
            only1 = sorted(set(p1) - set(p2))
            only2 = sorted(set(p2) - set(p1))
            late = [(k, p1[k], p2[k]) for k in p1 if k in p2 and abs(p1[k] - p2[k]) > (1 if rule == "pm1" else 0)]
            good = not only1 and not only2 and not late
            ok &= good
            print("%s broken: %d reference, %d run, %d only in reference, %d only in run, %d at another step %s"
                  % (deck, len(b1), len(b2), len(only1), len(only2), len(late), "ok" if good else "FAIL"))
            for k in only1[:5]:
                print("   only in reference: step %d elems %d %d nodes %d %d" % ((p1[k],) + k))
            for k in only2[:5]:
                print("   only in run: step %d elems %d %d nodes %d %d" % ((p2[k],) + k))
            for k, s1, s2 in late[:5]:
                print("   elems %d %d nodes %d %d: step %d in reference, %d in run" % (k + (s1, s2)))
    print("%s: %s" % (deck, "PASS" if ok else "FAIL"))
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
