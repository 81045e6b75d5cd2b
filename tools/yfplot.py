#!/usr/bin/env python3
"""yfplot: pictures of yfdem runs (the seed paper's figures, from yfdem's own output).

Reads the HDF5 frames of a `dump ID h5 N FILE.h5` (one file per frame, STEM_NNNNNN.h5), the
`fracture_log FILE opened FILE2` CSVs (one row per broken joint, and one per joint that passed the
peak of its law = an opened, still cohesive crack: step, time, x, y, mode, triA, triB, ...; triA and
triB are triangle ids, mapped through the frame's /mesh/tri_id) and the `metrics log` CSV (energies
and crack growth in time).  A crack is drawn as the edge that its two triangles shared, at the
frame's current positions, so no crack data is needed in the frames themselves.  Fragments are the
pieces connected through shared nodes and joints not yet broken at the frame's time.

  yfplot.py cracks STEM --breaks breaks.csv [--opened opened.csv] --times 2e-4,1e-3 -o out.png
             [--min-damage Z] [--layout column|row]
      deformed mesh at the frames nearest to the given times [s], fragments coloured, cracks by
      mode (I red, II blue, mixed green): opened thin, broken bold  -- the paper's figures 6 and 9;
      --min-damage draws only opened cracks of damage >= Z (the frame's /joint_damage), --layout
      puts the panels side by side (row) instead of stacked
  yfplot.py stress STEM --time T [--body N] -o out.png
      max principal stress contours [MPa] at the frame nearest to T (figure 7 with the elastic
      variant); the title says which run it is: elastic (no joints) or fracturing (joints, broken)
  yfplot.py history LOG.csv -o out.png
      energies (kinetic, strain, external work, damping, joint dissipation, contact) and crack
      length by mode against time

Needs numpy, h5py, matplotlib: `tools/install-deps --python` creates .venv with them; run as
`.venv/bin/python tools/yfplot.py ...`.
"""
import argparse
import csv
import glob
import os
import sys

try:
    import numpy as np
    import h5py
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.collections import LineCollection, PolyCollection
except ImportError as e:  # pragma: no cover
    sys.exit("yfplot: %s: run `tools/install-deps --python` and use .venv/bin/python" % e)

MODE_COLOR = {"I": "#d62728", "II": "#1f77b4", "mixed": "#2ca02c"}


def listed_frames(xmf):
    """The frame files the index STEM.xmf lists, in its order (None when it cannot be read).  A
    rerun leaves the frames of an earlier, longer run on disk, unlisted (README, Output): picked up
    by a glob, they were drawn as frames of this run."""
    import xml.etree.ElementTree as ET
    try:
        root = ET.parse(xmf).getroot()
    except (OSError, ET.ParseError):
        return None
    out = []
    for g in root.iter("Grid"):
        item = g.find("Geometry/DataItem")
        if g.get("GridType") == "Uniform" and item is not None and item.text and ":/" in item.text:
            out.append(os.path.join(os.path.dirname(xmf), item.text.strip().rsplit(":/", 1)[0]))
    return out


def frames(stem):
    """Frame files of a dump stem: those its index STEM.xmf lists, else the STEM_NNNNNN.h5 there."""
    stem = stem[:-3] if stem.endswith(".h5") else stem
    fs = listed_frames(stem + ".xmf") if os.path.exists(stem + ".xmf") else None
    if fs is None:
        fs = sorted(glob.glob(stem + "_[0-9][0-9][0-9][0-9][0-9][0-9].h5"))
    if not fs:
        sys.exit("yfplot: no frames %s_NNNNNN.h5 (write them with `dump ID h5 N %s.h5`)" % (stem, stem))
    return fs


def read_frame(path):
    with h5py.File(path, "r") as f:
        d = {k: f[k][()] for k in ("time", "step", "x")}
        d["tri"] = f["mesh/triangles"][()]
        d["x0"] = f["mesh/x0"][()]
        d["body"] = f["mesh/body"][()] if "mesh/body" in f else np.zeros(len(d["tri"]), int)
        if "mesh/tri_id" in f:
            d["tri_id"] = f["mesh/tri_id"][()]
        for k in ("sigma1", "stress", "u", "joint_damage"):
            if k in f:
                d[k] = f[k][()]
        if "cracks/state" in f:  # 1 opened, 2 broken (a scene with joints only)
            d["crack_state"] = f["cracks/state"][()]
    return d


def nearest_frame(stem, t):
    """The frame nearest to t [s]; an error when no frame is within half a frame interval of t."""
    fs = frames(stem)
    times = []
    for p in fs:
        with h5py.File(p, "r") as f:
            times.append(float(f["time"][()]))
    times = np.array(times)
    i = int(np.argmin(np.abs(times - t)))
    gap = np.max(np.diff(times)) if len(times) > 1 else 0.0
    if abs(times[i] - t) > 0.5 * gap * (1 + 1e-9) or (len(times) == 1 and times[0] != t):
        sys.exit("yfplot: no frame at t = %g s: the %d frames of %s cover %g to %g s (every %g s); "
                 "choose --times within that range, or dump more often" % (t, len(times), stem, times[0], times[-1],
                                                                          gap))
    return read_frame(fs[i])


def read_breaks(path):
    if not path:
        return []
    if not os.path.exists(path):
        sys.exit("yfplot: no file %s" % path)
    with open(path) as f:
        return [dict(r, time=float(r["time"]), triA=int(r["triA"]), triB=int(r["triB"])) for r in csv.DictReader(f)]


def tri_index(fr):
    """Map triangle id (CSV triA/triB) -> triangle index in the frame."""
    ids = fr.get("tri_id")
    if ids is None:
        return lambda i: i
    m = {int(v): k for k, v in enumerate(ids)}
    return lambda i: m[i]


def shared_edge(fr, a, b):
    """Node indices (in a) of the edge that triangles a and b (indices) shared initially."""
    tri, x0 = fr["tri"], fr["x0"]
    pb = [tuple(np.round(x0[n], 9)) for n in tri[b]]
    nodes = [n for n in tri[a] if tuple(np.round(x0[n], 9)) in pb]
    return nodes if len(nodes) == 2 else None


def fragments(fr, broken_pairs):
    """Fragment label per triangle: union through shared nodes and unbroken shared edges."""
    tri, x0 = fr["tri"], fr["x0"]
    nt = len(tri)
    par = np.arange(nt)

    def find(i):
        while par[i] != i:
            par[i] = par[par[i]]
            i = par[i]
        return i

    def union(a, b):
        a, b = find(a), find(b)
        if a != b:
            par[max(a, b)] = min(a, b)

    first = {}
    edges = {}
    key = np.round(x0, 9)
    for t in range(nt):
        for c in range(3):
            n = tri[t][c]
            if n in first:
                union(first[n], t)
            else:
                first[n] = t
            m = tri[t][(c + 1) % 3]
            e = tuple(sorted((tuple(key[n]), tuple(key[m]))))
            edges.setdefault(e, []).append(t)
    for ts in edges.values():
        if len(ts) == 2 and (min(ts), max(ts)) not in broken_pairs and fr["body"][ts[0]] == fr["body"][ts[1]]:
            union(ts[0], ts[1])
    lab = np.array([find(t) for t in range(nt)])
    _, lab = np.unique(lab, return_inverse=True)
    return lab


def draw_cracks(ax, fr, breaks, t, lw=1.6, what="broken", skip=()):
    segs = {m: [] for m in MODE_COLOR}
    ix = tri_index(fr)
    for b in breaks:
        if b["time"] > t or (b["triA"], b["triB"]) in skip:
            continue
        e = shared_edge(fr, ix(b["triA"]), ix(b["triB"]))
        if e:
            segs.setdefault(b["mode"], []).append(fr["x"][e])
    for m, s in segs.items():
        if s:
            ax.add_collection(LineCollection(s, colors=MODE_COLOR.get(m, "k"), linewidths=lw,
                                             alpha=1.0 if what == "broken" else 0.8,
                                             label="%s, mode %s" % (what, m)))


LEGEND_IN = 0.55  # [inch] under the panels for the legend (up to 2 rows of 3 entries), added to the figure


def panels(n, a):
    """n panels stacked (--layout column) or side by side (row), as a flat list; the figure is
    LEGEND_IN taller than the panels, so the legend never covers an axis label."""
    if a.layout == "row":
        fig, axs = plt.subplots(1, n, figsize=(a.width * n, a.height + LEGEND_IN), squeeze=False)
        return fig, list(axs[0, :])
    fig, axs = plt.subplots(n, 1, figsize=(a.width, a.height * n + LEGEND_IN), squeeze=False)
    return fig, list(axs[:, 0])


def cmd_cracks(a):
    breaks = read_breaks(a.breaks)
    opened = read_breaks(a.opened)
    times = [float(v) for v in a.times.split(",")]
    n = len(times)
    fig, axl = panels(n, a)
    cmap = plt.get_cmap("tab20")
    for ax, t in zip(axl, times):
        fr = nearest_frame(a.stem, t)
        shown = opened
        if a.min_damage is not None:  # opened cracks whose damage at this frame reaches Z
            if "joint_damage" not in fr:
                sys.exit("yfplot: --min-damage needs /joint_damage in the frames (a fracturing scene's h5 dump)")
            z = fr["joint_damage"]
            shown = [b for b in opened
                     if 0 <= int(b.get("joint", -1)) < len(z) and z[int(b["joint"])] >= a.min_damage]
        tf = float(fr["time"])
        ix = tri_index(fr)
        pairs = {(min(ix(b["triA"]), ix(b["triB"])), max(ix(b["triA"]), ix(b["triB"]))) for b in breaks
                 if b["time"] <= tf}
        lab = fragments(fr, pairs)
        sizes = np.bincount(lab)
        big = np.argmax(sizes)
        colors = []
        for t_, l in enumerate(lab):
            if fr["body"][t_] != a.body:
                colors.append("#555555")
            elif sizes[l] == sizes.max() or l == big:
                colors.append("#d9d9d9")
            else:
                colors.append(cmap(l % 20))
        polys = fr["x"][fr["tri"]]
        ax.add_collection(PolyCollection(polys, facecolors=colors, edgecolors="#9a9a9a", linewidths=0.15))
        done = {(b["triA"], b["triB"]) for b in breaks if b["time"] <= tf}
        draw_cracks(ax, fr, shown, tf, lw=0.7, what="opened", skip=done)
        draw_cracks(ax, fr, breaks, tf)
        nb = len(done)
        # opened: past the peak and not broken at this frame (a broken joint opened first: counted
        # once, as broken), as drawn and as the frame's /cracks/state 1 that ParaView shows
        no = sum(1 for b in shown if b["time"] <= tf and (b["triA"], b["triB"]) not in done)
        nfr = len(np.unique(lab[fr["body"] == a.body]))
        # side by side, the panels are narrow: the counts go on a second line of the title
        pieces = "%d piece%s of the body" % (nfr, "" if nfr == 1 else "s")
        if a.layout == "row":
            ax.set_title("t = %.3g ms\n%s%d broken joints\n%s" %
                         (tf * 1e3, "%d opened, " % no if a.opened else "", nb, pieces), fontsize=10)
        else:
            ax.set_title("t = %.3g ms: %s%d broken joints, %s" %
                         (tf * 1e3, "%d opened, " % no if a.opened else "", nb, pieces), fontsize=10)
        ax.set_aspect("equal")
        ax.autoscale_view()
        if a.xlim:
            ax.set_xlim(*[float(v) for v in a.xlim.split(",")])
        if a.ylim:
            ax.set_ylim(*[float(v) for v in a.ylim.split(",")])
        ax.set_xlabel("x [m]")
        ax.set_ylabel("y [m]")
    h, l = axl[0].get_legend_handles_labels()
    for ax in axl[1:]:
        hh, ll = ax.get_legend_handles_labels()
        for x, y in zip(hh, ll):
            if y not in l:
                h.append(x)
                l.append(y)
    if h:
        fig.legend(h, l, loc="lower center", ncol=3, fontsize=9)
    if a.title:
        fig.suptitle(a.title)
    # the legend's own strip under the panels (LEGEND_IN of the figure's height)
    fig.tight_layout(rect=(0, LEGEND_IN / fig.get_size_inches()[1], 1, 0.97 if a.title else 1))
    # equal-aspect panels are resized when drawn, after tight_layout: a short row of them could
    # push the titles past the top edge; the saved picture grows to hold them instead
    fig.savefig(a.o, dpi=a.dpi, bbox_inches="tight", pad_inches=0.1)
    print("yfplot: wrote", a.o)


def run_kind(fr):
    """What the frame's run is, from the frame itself: a scene with joints (a frame holds
    /joint_damage then) fractures; one without is elastic."""
    if "joint_damage" not in fr:
        return "elastic run (no joints)"
    nb = int(np.sum(fr["crack_state"] == 2)) if "crack_state" in fr else 0
    return "fracturing run (%d joints, %d broken)" % (len(fr["joint_damage"]), nb)


def cmd_stress(a):
    fr = nearest_frame(a.stem, a.time)
    if "sigma1" not in fr:
        sys.exit("yfplot: frame has no sigma1 (dump ... fields sigma1)")
    sel = fr["body"] == a.body
    fig, ax = plt.subplots(figsize=(a.width, a.height))
    import matplotlib.tri as mtri
    tr = mtri.Triangulation(fr["x"][:, 0], fr["x"][:, 1], fr["tri"][sel])
    s1 = fr["sigma1"][sel] / 1e6
    lim = a.vmax if a.vmax else max(abs(s1.min()), abs(s1.max()))
    pc = ax.tripcolor(tr, facecolors=s1, cmap="RdBu_r", vmin=-lim, vmax=lim)
    fig.colorbar(pc, ax=ax, label="sigma1 [MPa]", shrink=0.8)
    if a.mark:
        x, y = [float(v) for v in a.mark.split(",")]
        ax.plot([x], [y], "k*", ms=12, label="crack of the fracturing run")
        ax.legend(loc="upper right", fontsize=8)
    ax.set_aspect("equal")
    ax.set_title(a.title or "%s: max principal stress at t = %.3g ms" % (run_kind(fr), float(fr["time"]) * 1e3))
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    fig.tight_layout()
    fig.savefig(a.o, dpi=a.dpi)
    print("yfplot: wrote", a.o)


def cmd_history(a):
    with open(a.log) as f:
        rows = list(csv.DictReader(f))
    if not rows:
        sys.exit("yfplot: %s has no rows" % a.log)
    col = {k: np.array([float(r[k]) for r in rows]) for k in rows[0]}
    t = col["time"] * 1e3
    has_open = "opened_I" in col
    fig, axs = plt.subplots(3 if has_open else 2, 1, figsize=(a.width, a.height * (3 if has_open else 2)), sharex=True)
    ax1, ax2 = axs[0], axs[-1]
    for k, lab in (("kinetic", "kinetic"), ("strain", "strain (incl. joints)"), ("external_work", "external work"),
                   ("damping", "damping"), ("joint_dissipated", "joint dissipation"), ("contact", "contact")):
        if np.any(col[k] != 0):
            ax1.plot(t, col[k], label=lab)
    ax1.set_ylabel("energy [J/m]")
    ax1.legend(fontsize=7, ncol=2)
    ax1.grid(alpha=0.3)
    if has_open:  # opened (past the peak, still cohesive) cracks: a panel of their own
        for k, m in (("opened_I", "I"), ("opened_II", "II"), ("opened_mixed", "mixed")):
            if np.any(col[k] != 0):
                axs[1].plot(t, col[k], color=MODE_COLOR[m], label="opened, mode " + m)
        axs[1].set_ylabel("opened length [m]")
        axs[1].legend(fontsize=7)
        axs[1].grid(alpha=0.3)
    for k, m in (("crack_I", "I"), ("crack_II", "II"), ("crack_mixed", "mixed")):
        if np.any(col[k] != 0):
            ax2.plot(t, col[k], color=MODE_COLOR[m], lw=2, label="broken, mode " + m)
    ax2.set_ylabel("broken length [m]")
    ax2.set_xlabel("time [ms]")
    ax3 = ax2.twinx()
    ax3.step(t, col["fragments"], color="#7f7f7f", where="post", lw=0.8, label="pieces")
    ax3.set_ylabel("pieces of the body", color="#7f7f7f")
    ax2.legend(fontsize=7, loc="center right")
    ax2.grid(alpha=0.3)
    if a.title:
        fig.suptitle(a.title)
    fig.tight_layout()
    fig.savefig(a.o, dpi=a.dpi)
    print("yfplot: wrote", a.o)


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    sub = p.add_subparsers(dest="cmd", required=True)
    c = sub.add_parser("cracks", help="crack pattern and fragments at chosen times")
    c.add_argument("stem", help="dump stem: the FILE of `dump ID h5 N FILE.h5` (frames STEM_NNNNNN.h5)")
    c.add_argument("--breaks", required=True, help="broken-joint CSV (fracture_log FILE)")
    c.add_argument("--opened", help="opened-crack CSV (fracture_log ... opened FILE2)")
    c.add_argument("--times", required=True, help="comma-separated times [s], one panel each (nearest frame)")
    c.add_argument("--min-damage", type=float, metavar="Z",
                   help="draw only the opened cracks whose damage at the frame is at least Z (0..1; default: all)")
    c.add_argument("--layout", choices=("column", "row"), default="column",
                   help="panels stacked (column, default) or side by side (row)")
    c.add_argument("--body", type=int, default=0, help="index of the cracking body (default 0)")
    c.add_argument("--xlim", help="XMIN,XMAX [m]")
    c.add_argument("--ylim", help="YMIN,YMAX [m]")
    c.add_argument("--title", help="title over the figure")
    c.add_argument("--width", type=float, default=9, help="panel width [inch] (default 9)")
    c.add_argument("--height", type=float, default=2.2, help="panel height [inch] (default 2.2)")
    c.set_defaults(fn=cmd_cracks)
    s = sub.add_parser("stress", help="max principal stress contours")
    s.add_argument("stem", help="dump stem (frames STEM_NNNNNN.h5 with the sigma1 field)")
    s.add_argument("--time", type=float, required=True, help="time [s] (nearest frame)")
    s.add_argument("--body", type=int, default=0, help="index of the body drawn (default 0)")
    s.add_argument("--vmax", type=float, help="colour range -VMAX..VMAX [MPa] (default: the data's)")
    s.add_argument("--mark", help="X,Y [m] of a point to mark (first crack)")
    s.add_argument("--title", help="title over the figure")
    s.add_argument("--width", type=float, default=9, help="figure width [inch] (default 9)")
    s.add_argument("--height", type=float, default=2.6, help="figure height [inch] (default 2.6)")
    s.set_defaults(fn=cmd_stress)
    h = sub.add_parser("history", help="energies and crack growth in time (metrics log CSV)")
    h.add_argument("log", help="the CSV of `metrics log FILE`")
    h.add_argument("--title", help="title over the figure")
    h.add_argument("--width", type=float, default=7, help="panel width [inch] (default 7)")
    h.add_argument("--height", type=float, default=2.6, help="panel height [inch] (default 2.6)")
    h.set_defaults(fn=cmd_history)
    for q in (c, s, h):
        q.add_argument("-o", required=True, help="output PNG file")
        q.add_argument("--dpi", type=int, default=110, help="resolution [dots per inch] (default 110)")
    a = p.parse_args(argv)
    a.fn(a)


if __name__ == "__main__":
    main()
