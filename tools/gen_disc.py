#!/usr/bin/env python3
"""gen_disc.py: a disc mesh for the Brazilian test, written as a Gmsh MSH 4.1 ASCII file.

A disc of diameter D [m] meshed by concentric rings (ring k of n at radius k D / (2 n) holds 6 k
nodes; consecutive rings are stitched by merging their nodes in angle order), so the triangles
are nearly equilateral with edge about D / (2 n) everywhere.  Every ring has a node on the loaded
(vertical) diameter, so a line of edges runs along it: the path of the central split the test is
about (with --no-seam the rings start at angle 0, and a vertical crack can only zig-zag through
edges at +-30 degrees, whose normal stress at the centre, sigma_y = -3 sigma_x, is zero).  With
--flat ALPHA (degrees) the disc is flattened: nodes above y = R cos(ALPHA) or below -R cos(ALPHA)
are moved onto those lines, two flat loading faces of width 2 R sin(ALPHA) (the flattened
Brazilian disc, Wang et al. 2004, IJRMMS 41: 245; 2 ALPHA is the loading angle).  Only the outer
ring is moved when the cap height R (1 - cos ALPHA) is under half a ring spacing, which the
script checks.  The outer nodes nearest to the faces' (or arcs') ends are first moved onto them,
so the loaded width is exactly 2 R sin(ALPHA).

Physical groups: surface "rock"; curves "top" and "bottom" (the flat faces, or, without --flat,
the outer nodes within ALPHA of the vertical: the loading arcs).  Standard library only (no Gmsh
needed); `mesh gmsh` reads the result.

    tools/gen_disc.py --rings 25 --flat 10 decks/verify/meshes/disc_r25.msh
"""
import argparse
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import msh41  # noqa: E402


def rings(n, R, phase):
    """Node coordinates ring by ring: [[(x, y)], ...], ring 0 the centre; every ring has a node at
    angle `phase` (and phase + 60, 120, ... degrees: the six radial seams of edges)."""
    out = [[(0.0, 0.0)]]
    for k in range(1, n + 1):
        r = k * R / n
        m = 6 * k
        out.append([(r * math.cos(phase + 2 * math.pi * j / m), r * math.sin(phase + 2 * math.pi * j / m))
                    for j in range(m)])
    return out


def stitch(a, b, phase):
    """Triangles (index triples into a + b offsets handled by the caller) between an inner ring a and
    an outer ring b, both listed by increasing angle from angle 0: advance on the ring whose next
    node has the smaller angle (the Delaunay-like merge of two sorted angle lists)."""
    na, nb = len(a), len(b)
    ang = lambda p: (math.atan2(p[1], p[0]) - phase) % (2 * math.pi)
    tris = []
    i = j = 0
    while i < na or j < nb:
        ta = ang(a[(i + 1) % na]) if i + 1 < na else 2 * math.pi
        tb = ang(b[(j + 1) % nb]) if j + 1 < nb else 2 * math.pi
        if i < na and (j >= nb or ta <= tb):
            tris.append(("a", i % na, "a", (i + 1) % na, "b", j % nb))
            i += 1
        else:
            tris.append(("a", i % na, "b", j % nb, "b", (j + 1) % nb))
            j += 1
    return tris


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("out")
    ap.add_argument("--diameter", type=float, default=0.05, help="disc diameter [m] (default 0.05)")
    ap.add_argument("--rings", type=int, default=25, help="rings from centre to rim (edge ~ D / (2 rings))")
    ap.add_argument("--flat", type=float, default=None, help="flatten to loading faces of half-angle ALPHA [deg]")
    ap.add_argument("--no-seam", dest="seam", action="store_false",
                    help="rings start at angle 0 (no line of edges on the loaded diameter)")
    ap.add_argument("--arc", type=float, default=10.0, help="without --flat: half-angle of the loading arcs [deg]")
    o = ap.parse_args()
    R = 0.5 * o.diameter
    n = o.rings
    # seams on the loaded (vertical) diameter unless --no-seam: the hexagonal rings elsewhere offer
    # a vertical crack only zig-zags of edges at +-30 degrees, which carry no tension at the centre
    # of the disc (sigma_y = -3 sigma_x there: sigma_n = 0.75 sigma_x - 0.25 * 3 sigma_x = 0)
    phase = math.pi / 2 if o.seam else 0.0
    rg = rings(n, R, phase)
    # the outer nodes nearest to 90 +- ALPHA and 270 +- ALPHA go exactly there (a shift of at most
    # half the outer spacing), so the faces or arcs span exactly 2 ALPHA
    al = math.radians(o.flat if o.flat is not None else o.arc)
    outer = rg[n]
    for target in (math.pi / 2 - al, math.pi / 2 + al, 1.5 * math.pi - al, 1.5 * math.pi + al):
        d = lambda p: abs((math.atan2(p[1], p[0]) - target + math.pi) % (2 * math.pi) - math.pi)
        j = min(range(len(outer)), key=lambda q: d(outer[q]))
        outer[j] = (R * math.cos(target), R * math.sin(target))
    base = [0]
    for r in rg[:-1]:
        base.append(base[-1] + len(r))
    xy = [p for r in rg for p in r]
    top, bot = [], []
    if o.flat is not None:
        al = math.radians(o.flat)
        yf = R * math.cos(al)
        if R * (1 - math.cos(al)) > 0.5 * R / n:
            sys.exit("gen_disc: the cap R (1 - cos ALPHA) is more than half a ring spacing: use fewer rings")
        for q, (x, y) in enumerate(xy):
            if abs(y) > yf * (1 - 1e-12):
                xy[q] = (x, math.copysign(yf, y))
                (top if y > 0 else bot).append(q)
    else:
        al = math.radians(o.arc)
        for j, (x, y) in enumerate(rg[n]):
            th = math.atan2(y, x)
            if abs(th - math.pi / 2) <= al + 1e-12:
                top.append(base[n] + j)
            if abs(th + math.pi / 2) <= al + 1e-12:
                bot.append(base[n] + j)
    tris = []
    for j in range(6):
        tris.append((0, base[1] + j, base[1] + (j + 1) % 6))
    for k in range(2, n + 1):
        for t in stitch(rg[k - 1], rg[k], phase):
            idx = [(base[k - 1] if w == "a" else base[k]) + i for w, i in zip(t[0::2], t[1::2])]
            tris.append(tuple(idx))
    # counter-clockwise, and no degenerate triangle
    good = []
    for t in tris:
        (x0, y0), (x1, y1), (x2, y2) = (xy[i] for i in t)
        d = (x1 - x0) * (y2 - y0) - (y1 - y0) * (x2 - x0)
        if d < 0:
            t = (t[0], t[2], t[1])
            d = -d
        if d <= 1e-6 * (R / n) ** 2:
            sys.exit("gen_disc: a degenerate triangle; use fewer rings or a smaller ALPHA")
        good.append(t)
    # the faces as chains of line elements, sorted along x
    lines = []
    for nodes in (top, bot):
        s = sorted(nodes, key=lambda q: xy[q][0])
        lines.append([(s[i], s[i + 1]) for i in range(len(s) - 1)])
    msh41.write(o.out, xy, good, [("top", lines[0]), ("bottom", lines[1])], "rock")
    nn = len(xy)
    print("gen_disc: %s: %d nodes, %d triangles, %d + %d face nodes" % (o.out, nn, len(good), len(top), len(bot)))


if __name__ == "__main__":
    main()
