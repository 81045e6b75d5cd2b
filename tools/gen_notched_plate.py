#!/usr/bin/env python3
"""gen_notched_plate.py: a rectangular plate with straight edge notches (slits), as a Gmsh MSH 4.1
ASCII file, for the dynamic fracture benchmarks of decks/verify/ (Ha & Bobaru's branching plate,
Kalthoff-Winkler's double-notched plate).

The plate [X0, X1] x [Y0, Y1] is meshed with NX x NY square cells, each crossed (four triangles
around a centre node, as `mesh rect ... pattern cross`).  A notch is a horizontal slit along a
row of cell edges, from the plate's left edge (x = X0) to x = XN at height YN (both on the grid):
the nodes on it, except its tip, are doubled, the cells above using one copy and the cells below
the other, so the slit has zero width and opens freely.  Physical groups: surface "glass"; curves
"top", "bottom", "left", "right" (the plate's sides) and, for Kalthoff-Winkler's impact,
"impact" (the left edge between the notches, with --impact).

    tools/gen_notched_plate.py --box -0.05 -0.02 0.05 0.02 --cells 200 80 --notch 0 0 plate.msh
    tools/gen_notched_plate.py --box 0 -0.1 0.1 0.1 --cells 50 100 --notch 0.05 0.025 \\
        --notch 0.05 -0.025 --impact kw.msh
Standard library only.
"""
import argparse
import os
import random
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import msh41  # noqa: E402


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("out")
    ap.add_argument("--box", type=float, nargs=4, metavar=("X0", "Y0", "X1", "Y1"), required=True)
    ap.add_argument("--cells", type=int, nargs=2, metavar=("NX", "NY"), required=True)
    ap.add_argument("--notch", type=float, nargs=2, action="append", default=[], metavar=("XN", "YN"),
                    help="a slit from the left edge to x = XN at height YN (repeatable)")
    ap.add_argument("--impact", action="store_true", help="group 'impact': the left edge between the notches")
    ap.add_argument("--jitter", type=float, default=0.0,
                    help="move each interior node by up to JITTER cells in x and y (seeded, default 0)")
    ap.add_argument("--seed", type=int, default=1, help="seed of the jitter (default 1)")
    o = ap.parse_args()
    x0, y0, x1, y1 = o.box
    nx, ny = o.cells
    dx, dy = (x1 - x0) / nx, (y1 - y0) / ny
    # grid nodes (i, j) and cell centres
    xy = []
    gid = {}
    for j in range(ny + 1):
        for i in range(nx + 1):
            gid[(i, j)] = len(xy)
            xy.append((x0 + i * dx, y0 + j * dy))
    notches = []
    for xn, yn in o.notch:
        jn = round((yn - y0) / dy)
        inn = round((xn - x0) / dx)
        if abs(y0 + jn * dy - yn) > 1e-9 * (y1 - y0) or abs(x0 + inn * dx - xn) > 1e-9 * (x1 - x0):
            sys.exit("gen_notched_plate: notch (%g, %g) is not on the grid" % (xn, yn))
        if not (0 < jn < ny and 0 < inn < nx):
            sys.exit("gen_notched_plate: notch (%g, %g) is outside the plate" % (xn, yn))
        notches.append((inn, jn))
    # the lower copies of the slit nodes (tip excluded)
    low = {}
    for inn, jn in notches:
        for i in range(0, inn):
            low[(i, jn)] = len(xy)
            xy.append(xy[gid[(i, jn)]])

    def node(i, j, below):
        """grid node (i, j) as seen from a cell above (below = 0) or below (1) the row j"""
        if below and (i, j) in low:
            return low[(i, j)]
        return gid[(i, j)]

    tris = []
    centre = {}
    for j in range(ny):
        for i in range(nx):
            c = len(xy)
            centre[(i, j)] = c
            xy.append((x0 + (i + 0.5) * dx, y0 + (j + 0.5) * dy))
            # the cell's bottom row j sees its nodes from above, its top row j + 1 from below
            a = node(i, j, 0)
            b = node(i + 1, j, 0)
            d = node(i + 1, j + 1, 1)
            e = node(i, j + 1, 1)
            tris += [(a, b, c), (b, d, c), (d, e, c), (e, a, c)]
    eps = 1e-9 * max(x1 - x0, y1 - y0)
    if o.jitter > 0:
        # interior nodes only: not on the plate's sides, not on a slit (its copies must coincide)
        # and not a slit's tip; the same draws for the same seed
        rng = random.Random(o.seed)
        fixed = set(low) | {(inn, jn) for inn, jn in notches}
        for (i, j), q in sorted(gid.items(), key=lambda kv: kv[1]):
            if 0 < i < nx and 0 < j < ny and (i, j) not in fixed:
                xy[q] = (xy[q][0] + o.jitter * dx * rng.uniform(-1, 1), xy[q][1] + o.jitter * dy * rng.uniform(-1, 1))
        # cell centres: the mean of the cell's four corners (keeps the four triangles valid)
        for j in range(ny):
            for i in range(nx):
                c = centre[(i, j)]
                cs = [xy[gid[(i, j)]], xy[gid[(i + 1, j)]], xy[gid[(i + 1, j + 1)]], xy[gid[(i, j + 1)]]]
                xy[c] = (sum(p[0] for p in cs) / 4, sum(p[1] for p in cs) / 4)
    groups = {
        "top": [gid[(i, ny)] for i in range(nx + 1)],
        "bottom": [gid[(i, 0)] for i in range(nx + 1)],
        "left": [node(0, j, b) for j in range(ny + 1) for b in (0, 1) if b == 0 or (0, j) in low],
        "right": [gid[(nx, j)] for j in range(ny + 1)],
    }
    if o.impact:
        if len(notches) != 2:
            sys.exit("gen_notched_plate: --impact needs two notches")
        ja, jb = sorted(jn for _, jn in notches)
        # between the slits: the upper copy of the lower slit's mouth up to the lower copy of the upper one
        groups["impact"] = [node(0, j, 0 if j == ja else 1) for j in range(ja, jb + 1)]
    # each group as a chain of 2-node lines between consecutive nodes (sorted along the side); a
    # pair of slit copies at the same point is joined by no line
    curves = []
    for nm, g in groups.items():
        key = (lambda q: (xy[q][0], q)) if nm in ("top", "bottom") else (lambda q: (xy[q][1], q))
        s = sorted(set(g), key=key)
        curves.append((nm, [(s[i], s[i + 1]) for i in range(len(s) - 1)
                            if abs(xy[s[i]][0] - xy[s[i + 1]][0]) + abs(xy[s[i]][1] - xy[s[i + 1]][1]) > eps]))
    msh41.write(o.out, xy, tris, curves, "glass", "%.12g")
    print("gen_notched_plate: %s: %d nodes, %d triangles, %d notch(es)" % (o.out, len(xy), len(tris), len(notches)))


if __name__ == "__main__":
    main()
