#!/usr/bin/env python3
"""crack_tip.py: crack-tip history, speed and branching from a yfdem break log (`fracture_log`
CSV: step,time,x,y,mode,triA,triB,length,joint), for the dynamic fracture decks of decks/verify/.

The crack is followed from the point --from X Y (a notch tip) as the broken joints connected to
it (two breaks are connected when their midpoints are within --link metres, default 1.6 cell
diagonals: pass about 2.2 x the cell size).  Its tip at time t is the connected break farthest
from the start; the tip speed is the slope of that distance over --window seconds.  The crack has
branched at the first time two connected breaks both lie at least --sep metres from the line
of the crack before the fork, on opposite sides (default: the crack runs along +x from the
start and branches to +y and -y): the script reports that time, the place (where the two
branches leave the main crack: the last break of the main crack before them), and the angle of
each branch (the line from the fork to the branch's farthest break against the main direction).

    tools/crack_tip.py branching_breaks.csv --from 0 0 --link 0.0011 --rayleigh 3100
"""
import argparse
import csv
import math


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("log")
    ap.add_argument("--from", dest="start", type=float, nargs=2, default=(0.0, 0.0), metavar=("X", "Y"))
    ap.add_argument("--dir", type=float, nargs=2, default=(1.0, 0.0), metavar=("DX", "DY"),
                    help="direction of the main crack before the fork (default +x)")
    ap.add_argument("--link", type=float, default=0.0011, help="largest distance between connected breaks [m]")
    ap.add_argument("--sep", type=float, default=0.002, help="distance off the main line that counts as a branch [m]")
    ap.add_argument("--window", type=float, default=4e-6, help="time window of the speed [s]")
    ap.add_argument("--rayleigh", type=float, default=None, help="Rayleigh wave speed [m/s], to compare")
    o = ap.parse_args()
    rows = [(float(r["time"]), float(r["x"]), float(r["y"])) for r in csv.DictReader(open(o.log))]
    rows.sort()
    sx, sy = o.start
    dx, dy = o.dir
    dn = math.hypot(dx, dy)
    dx, dy = dx / dn, dy / dn
    # connected growth in time order: a break joins the crack when it is within `link` of the start
    # or of a break already in it
    crack = []
    pending = list(rows)
    changed = True
    while changed:
        changed = False
        rest = []
        for r in pending:
            if math.hypot(r[1] - sx, r[2] - sy) <= o.link or any(
                    math.hypot(r[1] - c[1], r[2] - c[2]) <= o.link for c in crack):
                crack.append(r)
                changed = True
            else:
                rest.append(r)
        pending = rest
    crack.sort()
    if not crack:
        print("crack_tip: no broken joint is connected to the start point")
        return
    # tip distance in time
    tip, best = [], -1.0
    for t, x, y in crack:
        d = math.hypot(x - sx, y - sy)
        if d > best:
            best = d
            tip.append((t, d, x, y))
    print("crack_tip: %d breaks connected to (%g, %g) of %d; first at %.2f us, last at %.2f us" %
          (len(crack), sx, sy, len(rows), crack[0][0] * 1e6, crack[-1][0] * 1e6))
    vmax = 0.0
    print("  time [us]  tip distance [mm]  speed over the window [m/s]")
    k0 = 0
    for k in range(len(tip)):
        while tip[k][0] - tip[k0][0] > o.window:
            k0 += 1
        v = (tip[k][1] - tip[k0][1]) / (tip[k][0] - tip[k0][0]) if tip[k][0] > tip[k0][0] else 0.0
        if tip[k][0] - tip[0][0] >= o.window:
            vmax = max(vmax, v)
        if k % max(1, len(tip) // 12) == 0 or k == len(tip) - 1:
            print("  %8.2f  %8.2f  %8.0f" % (tip[k][0] * 1e6, tip[k][1] * 1e3, v))
    mean = (tip[-1][1] - tip[0][1]) / (tip[-1][0] - tip[0][0]) if tip[-1][0] > tip[0][0] else 0.0
    print("crack_tip: mean tip speed %.0f m/s, largest over %.1f us %.0f m/s%s" %
          (mean, o.window * 1e6, vmax,
           "" if o.rayleigh is None else " (Rayleigh %.0f m/s: %s)" % (o.rayleigh, "below" if vmax < o.rayleigh else "ABOVE")))
    t_, d_, tx, ty = tip[-1]
    print("crack_tip: the tip at (%.2f, %.2f) mm, %.1f mm from the start, at %.1f degrees to the main direction" %
          (tx * 1e3, ty * 1e3, d_ * 1e3, math.degrees(math.atan2((tx - sx) * -dy + (ty - sy) * dx, (tx - sx) * dx + (ty - sy) * dy))))
    # branching: signed distance from the main line
    off = lambda r: -(r[1] - sx) * dy + (r[2] - sy) * dx
    along = lambda r: (r[1] - sx) * dx + (r[2] - sy) * dy
    up = [r for r in crack if off(r) >= o.sep]
    dn_ = [r for r in crack if off(r) <= -o.sep]
    if not up or not dn_:
        print("crack_tip: no branching (no connected breaks %.1f mm off the main line on both sides)" % (o.sep * 1e3))
        return
    tb = max(up[0][0], dn_[0][0])
    main_line = [r for r in crack if abs(off(r)) < 0.5 * o.sep and r[0] <= tb]
    first_off = min(up[0], dn_[0], key=lambda r: along(r))
    fork = max((r for r in main_line if along(r) <= along(first_off)), key=along, default=crack[0])
    print("crack_tip: branched by %.2f us (first break %.1f mm above the line at %.2f us, below at %.2f us); "
          "fork at (%.2f, %.2f) mm" % (tb * 1e6, o.sep * 1e3, up[0][0] * 1e6, dn_[0][0] * 1e6,
                                        fork[1] * 1e3, fork[2] * 1e3))
    for name, br in (("upper", up), ("lower", dn_)):
        far = max(br, key=lambda r: math.hypot(r[1] - fork[1], r[2] - fork[2]))
        ang = math.degrees(math.atan2(abs(-(far[1] - fork[1]) * dy + (far[2] - fork[2]) * dx),
                                      (far[1] - fork[1]) * dx + (far[2] - fork[2]) * dy))
        print("  %s branch: to (%.2f, %.2f) mm, %.1f degrees off the main direction" %
              (name, far[1] * 1e3, far[2] * 1e3, ang))


if __name__ == "__main__":
    main()
