#!/usr/bin/env python3
"""failure_map: the beam's failure-mode map (docs/FAILURE_MAP.md): runs decks/beam.deck over a
design of its scene variables with yfsweep, names each run's broken-crack pattern with
failure_mode.classify, and writes a CSV and the map's figure.

Design (the full factorial of the issue's seven axes is hundreds of runs; the machine is shared):
  grid  span/depth x impactor-to-beam mass ratio, the two axes the impact literature names as the
        switch between a global (flexural) and a local (punching) response: (L, D) in
        (1.0, 0.2) (1.5, 0.2) (1.0, 0.1) (2.0, 0.15) (2.0, 0.1) m, i.e. L/D 5, 7.5, 10, 13.3, 20,
        and mass ratio m_i / m_b = rho_i a^2 / (2340 L D) in 0.1, 0.3, 1, 3 (impactor side a fixed
        at 0.05 m; the density carries the mass per metre of thickness);
  oat   one-at-a-time around the default scene (L 1, D 0.1, rho_i 30000: mass ratio 0.32): impactor
        side 0.1 m at the same mass; inner supports at 0.10 or 0.25 m from the ends; Y2D's right
        triangles; cells of 1/60 and 1/80 m; Mohr-Coulomb joints (friction 0.6); reversible joints
        (-var y2d 1).
Every run: cells of 1/nx m (nx 40: 4 cells through a 0.1 m depth), no frames, and the physical time
T = clamp(0.75 T1, 1.5 ms, 4 ms), T1 the fundamental period of the inner span Ls = L - 2 si as a
clamped-clamped Euler beam (omega = 22.37 / Ls^2 sqrt(E D^2 / (12 rho))): long enough for the
global bending response's first peak (T1/4) and for the reversed moment over the supports.  The
step count is T / dt with dt from a one-step probe of the same scene.

  nice -n 19 tools/failure_map.py --workdir /tmp/fmap --csv docs/sweep/failure_map.csv \\
      --plot docs/sweep/failure_map.png [--only grid|oat] [--jobs 2]

Runs use OMP_NUM_THREADS=1 (yfsweep threads=1); --jobs runs that many at once.

--scene column: the column's map (decks/column.deck, failure_mode.classify_column): the grid of the
issue's three axes, aspect H/W 1, 2, 3 (W 0.15 m, H 0.15, 0.30, 0.45 m) x impactor width a/W 1/3,
2/3, 1 (a 0.05, 0.10, 0.15 m; square, density 30000) x platen friction mu 0 (smooth: roller base,
frictionless impactor) and 0.5 (Coulomb 0.5 on the impactor and on a fixed steel platen under the
base), 18 runs on cells of W/12 (nx 12; --nx N for another mesh), each the deck's 1.39 ms (1000 nx steps),
no frames.  --only search: six runs near the full-width impactor with friction (COLUMN_SEARCH).

  nice -n 19 tools/failure_map.py --scene column --jobs 1 --workdir /tmp/cmap \\
      --csv docs/sweep/column_map.csv --plot docs/img/column_map.png
"""
import argparse
import concurrent.futures as cf
import csv
import json
import math
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import yfsweep  # noqa: E402
import failure_mode  # noqa: E402

DECK = os.path.join(os.path.dirname(HERE), "decks", "beam.deck")
RHO_C, E_C = 2340.0, 26e9
BASE = {"nx": 40, "L": 1.0, "D": 0.1, "a": 0.05, "rho_i": 30000, "si": 0.15}
GEOMS = [(1.0, 0.2), (1.5, 0.2), (1.0, 0.1), (2.0, 0.15), (2.0, 0.1)]
# L/D 10 at D 0.2 (the grid's L/D 10 is D 0.1): separates depth from slenderness, at the two lightest
EXTRA = [(2.0, 0.2, 0.1), (2.0, 0.2, 0.3)]
RATIOS = [0.1, 0.3, 1.0, 3.0]
OAT = [("a 0.1 (same mass)", {"a": 0.1, "rho_i": 7500}),
       ("inner supports 0.10", {"si": 0.10}),
       ("inner supports 0.25", {"si": 0.25}),
       ("pattern right", {"pattern": "right"}),
       ("cells 1/60 m", {"nx": 60}),
       ("cells 1/80 m", {"nx": 80}),
       ("Mohr-Coulomb mu 0.6", {"mu": 0.6}),
       ("reversible (y2d 1)", {"y2d": 1}),
       ("default", {})]
# search: around the grid's only cone (L 1, D 0.2, mass ratio 0.1: rho_i 18720), the axes that could
# delay the shear at the impactor's edges (Mohr-Coulomb friction, a wider or lighter impactor) or
# raise the hogging moment over the inner supports (si 0.25), and the mesh
DEEP = dict(BASE, D=0.2, rho_i=18720)
SEARCH = [("mu 0.6", dict(DEEP, mu=0.6)),
          ("mu 1.0", dict(DEEP, mu=1.0)),
          ("mass ratio 0.05", dict(DEEP, rho_i=9360)),
          ("a 0.1 (same mass)", dict(DEEP, a=0.1, rho_i=4680)),
          ("inner supports 0.25", dict(DEEP, si=0.25)),
          ("mu 0.6, si 0.25", dict(DEEP, mu=0.6, si=0.25)),
          ("mass ratio 0.3, mu 0.6", dict(DEEP, rho_i=56160, mu=0.6)),
          ("L 1.5, mu 0.6", dict(DEEP, L=1.5, rho_i=28080, mu=0.6)),
          ("reversible (y2d 1)", dict(DEEP, y2d=1)),
          ("cells 1/60 m", dict(DEEP, nx=60))]


COLUMN_DECK = os.path.join(os.path.dirname(HERE), "decks", "column.deck")
COLUMN_HW = [1, 2, 3]
COLUMN_AW = [(1, 3), (2, 3), (3, 3)]
COLUMN_MU = [0, 0.5]
COLUMN_NX = 12


# search: between the grid's points that come nearest (the full-width impactor with friction breaks
# the inclined pair before the corners): lighter and heavier friction, a slight overhang
COLUMN_SEARCH = [(hw, a, mu) for hw in (1, 2) for a, mu in ((0.15, 0.2), (0.15, 1.0), (0.12, 0.5))]


def column_design(nx=COLUMN_NX, only=None):
    runs = []
    if only == "search":
        for hw, a, mu in COLUMN_SEARCH:
            p = {"nx": nx, "W": 0.15, "H": round(0.15 * hw, 6), "a": a, "mu": mu}
            runs.append(("search", "search_HW%g_a%g_mu%g" % (hw, a, mu), p))
        return runs
    for hw in COLUMN_HW:
        for n, d in COLUMN_AW:
            for mu in COLUMN_MU:
                p = {"nx": nx, "W": 0.15, "H": round(0.15 * hw, 6), "a": round(0.15 * n / d, 6), "mu": mu}
                runs.append(("column", "HW%g_aW%d-%d_mu%g" % (hw, n, d, mu), p))
    return runs


COLUMN_COLS = ["kind", "tag", "W", "H", "a", "mu", "nx", "steps", "exit", "wall_s", "joints_broken", "first_break",
               "first_fragment", "label", "paper", "n_longitudinal", "x_longitudinal", "inclined_shape", "other",
               "t_longitudinal", "t_inclined", "t_shoulders"]


def column_classes(rd):
    """The COLUMN_COLS entries that failure_mode.classify_column gives for run directory rd."""
    c = failure_mode.classify_run(rd)
    out = dict(label=c["label"], paper=c["paper"], other=c["other"],
               n_longitudinal=c["longitudinal"]["count"] if c["longitudinal"]["present"] else 0,
               x_longitudinal=" ".join("%.4g" % x for x in c["longitudinal"].get("x", [])),
               inclined_shape=c["inclined"].get("shape", ""))
    for k in failure_mode.COLUMN_CLASSES:
        out["t_" + k] = c[k]["time"] if c[k]["present"] else None
    return out


def one_column(kind, tag, p, workdir):
    rd = os.path.join(workdir, tag)
    row = yfsweep.run_case(COLUMN_DECK, dict(p, every=10 ** 9), rd, threads=1)
    out = dict(p, kind=kind, tag=tag, exit=row["exit"], wall_s=row["wall_s"], steps=round(1000 * p["nx"]),
               joints_broken=row.get("joints_broken"), first_break=row.get("first_break.time"),
               first_fragment=row.get("first_fragment_time"))
    if row["exit"] == 0:
        out.update(column_classes(rd))
    print("failure_map: %-22s exit %d  %6.1f s  %s" % (tag, out["exit"], out.get("wall_s", 0), out.get("label")),
          flush=True)
    return out


COLUMN_STYLE = {"longitudinal": ("o", "tab:blue"), "inclined": ("^", "tab:green"), "shoulders": ("s", "tab:red")}


def plot_column(rows, path):
    """One panel per platen friction: a/W on x, H/W on y; at each scene the three classes' first
    breaks as a small time line (marker per class, left to right in time order), the label below."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    mus = sorted({float(r["mu"]) for r in rows})
    fig, axs = plt.subplots(1, len(mus), figsize=(5.6 * len(mus), 6.2), squeeze=False)
    for ax, mu in zip(axs[0], mus):
        for r in rows:
            if float(r["mu"]) != mu or not r.get("label"):
                continue
            x0, y0 = float(r["a"]) / float(r["W"]), float(r["H"]) / float(r["W"])
            ts = sorted((float(r["t_" + k]), k) for k in failure_mode.COLUMN_CLASSES if r.get("t_" + k))
            for j, (t, k) in enumerate(ts):
                mk, col = COLUMN_STYLE[k]
                ax.scatter([x0 - 0.1 + 0.1 * j], [y0], marker=mk, c=col, s=120, zorder=3,
                           edgecolors="k" if r["paper"] == "True" else "w", linewidths=1.5)
                ax.annotate("%.0f" % (t * 1e6), (x0 - 0.1 + 0.1 * j, y0 + 0.13), fontsize=7, ha="center")
            txt = r["label"].replace("longitudinal", "long").replace("shoulders", "shoul").replace("inclined", "incl")
            if r.get("n_longitudinal") and r["n_longitudinal"] != "0":
                txt += "\n%s long." % r["n_longitudinal"]
            if r.get("inclined_shape"):
                txt += " incl. " + r["inclined_shape"].replace("lambda", "Λ")
            ax.annotate(txt, (x0, y0 - 0.22), fontsize=7, ha="center", va="top")
        ax.set_xlim(0.1, 1.25)
        ax.set_ylim(0.4, 3.45)
        ax.set_xticks([1 / 3, 2 / 3, 1])
        ax.set_xticklabels(["1/3", "2/3", "1"])
        ax.set_yticks([1, 2, 3])
        ax.set_xlabel("impactor width / column width  a / W")
        ax.set_ylabel("height / width  H / W   (W 0.15 m)")
        ax.set_title("platen friction %g%s" % (mu, " (smooth: the paper's)" if mu == 0 else ""), fontsize=9)
        ax.grid(alpha=0.3)
    hs = [axs[0][0].scatter([], [], marker=mk, c=col, s=60, label=k + " (first break, us)")
          for k, (mk, col) in COLUMN_STYLE.items()]
    fig.legend(handles=hs, fontsize=8, loc="lower center", ncol=3, frameon=False)
    axs[0][0].annotate("decks/column.deck", (2 / 3, 2 - 0.55), fontsize=7, ha="center", color="0.4")
    nx = rows[0]["nx"] if rows else "?"
    fig.suptitle("column hit at 10 m/s: broken-crack classes in time order (first break left; black edge: the "
                 "paper's order), cells W/%s, 1.39 ms" % nx, fontsize=10)
    fig.tight_layout(rect=(0, 0.05, 1, 1))
    fig.savefig(path, dpi=100)
    print("failure_map: wrote", path)


def plot_column_cracks(rows, workdir, path, tmax=400e-6):
    """The broken joints of every run of the column map (from WORKDIR/TAG/column_breaks.csv) at their
    positions at the break, coloured by the time of the break (capped at tmax), one panel per run:
    rows H/W, columns a/W and friction."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    hws = sorted({float(r["H"]) / float(r["W"]) for r in rows})
    cols = sorted({(float(r["mu"]), float(r["a"])) for r in rows})
    fig, axs = plt.subplots(len(hws), len(cols), figsize=(2.1 * len(cols), 1.0 + 2.6 * len(hws)), squeeze=False,
                            sharex=True, sharey="row")
    sc = None
    for r in rows:
        i = hws.index(float(r["H"]) / float(r["W"]))
        j = cols.index((float(r["mu"]), float(r["a"])))
        ax = axs[i][j]
        W, H, a = float(r["W"]), float(r["H"]), float(r["a"])
        ax.plot([0, W, W, 0, 0], [0, 0, H, H, 0], "-", c="0.7", lw=0.8)
        ax.plot([(W - a) / 2, (W + a) / 2], [H, H], "-", c="k", lw=3)
        b = failure_mode.read_breaks(os.path.join(workdir, r["tag"], "column_breaks.csv"))
        for mode, mk in (("I", "o"), ("II", "x"), ("mixed", "^")):
            q = [x for x in b if x["mode"] == mode]
            sc = ax.scatter([x["x"] for x in q], [x["y"] for x in q], c=[min(tmax, x["time"]) * 1e6 for x in q],
                            marker=mk, s=6, cmap="viridis", vmin=0, vmax=tmax * 1e6, linewidths=0.8)
        ax.set_aspect("equal")
        ax.set_title("H/W %g, a/W %.2g, mu %g\n%s" % (hws[i], a / W, float(r["mu"]),
                                                       r["label"].replace("longitudinal", "long")
                                                       .replace("shoulders", "shoul").replace("inclined", "incl")),
                     fontsize=7)
        ax.tick_params(labelsize=6)
    fig.colorbar(sc, ax=axs, shrink=0.5, label="time of break [us] (o mode I, x mode II, ^ mixed)")
    fig.savefig(path, dpi=90)
    print("failure_map: wrote", path)


def mass_ratio(p):
    return p["rho_i"] * p["a"] ** 2 / (RHO_C * p["L"] * p["D"])


def sim_time(p):
    ls = p["L"] - 2 * p["si"]
    omega = 22.37 / ls ** 2 * math.sqrt(E_C * p["D"] ** 2 / (12 * RHO_C))
    return min(4e-3, max(1.5e-3, 0.75 * 2 * math.pi / omega))


def design(only=None):
    runs = []
    if only in (None, "grid"):
        for L, D in GEOMS:
            for mr in RATIOS:
                p = dict(BASE, L=L, D=D)
                p["rho_i"] = round(mr * RHO_C * L * D / p["a"] ** 2)
                runs.append(("grid", "L%g_D%g_mr%g" % (L, D, mr), p))
    if only in (None, "extra"):
        for L, D, mr in EXTRA:
            p = dict(BASE, L=L, D=D)
            p["rho_i"] = round(mr * RHO_C * L * D / p["a"] ** 2)
            runs.append(("grid", "L%g_D%g_mr%g" % (L, D, mr), p))
    if only in (None, "search"):
        for name, p in SEARCH:
            runs.append(("search:" + name, "search_" + name.replace(" ", "").replace(",", "_").replace("(", "")
                         .replace(")", ""), p))
    if only in (None, "oat"):
        for name, ch in OAT:
            runs.append(("oat:" + name, "oat_" + name.split()[0] + "_" + str(list(ch.values())[0] if ch else "base"),
                         dict(BASE, **ch)))
    return runs


def one(kind, tag, p, workdir):
    rd = os.path.join(workdir, tag)
    probe = yfsweep.run_case(DECK, dict(p, steps=1, every=10 ** 9), rd, threads=1)
    if probe["exit"] != 0:
        return dict(p, kind=kind, tag=tag, exit=probe["exit"])
    T = sim_time(p)
    steps = int(math.ceil(T / probe["dt"]))
    row = yfsweep.run_case(DECK, dict(p, steps=steps, every=steps + 1), rd, threads=1)
    out = dict(p, kind=kind, tag=tag, exit=row["exit"], wall_s=row["wall_s"], steps=steps, T=T,
               mass_ratio=mass_ratio(p), span_depth=p["L"] / p["D"],
               joints_broken=row.get("joints_broken"), first_break=row.get("first_break.time"))
    if row["exit"] == 0:
        c = failure_mode.classify_run(rd)
        out.update(label=c["label"], paper=c["paper"], other=c["other"], flexural_first=c["flexural_first"])
        for k in failure_mode.CLASSES:
            out["t_" + k] = c[k]["time"] if c[k]["present"] else None
    print("failure_map: %-28s exit %d  %6.1f s  %s" % (tag, out["exit"], out.get("wall_s", 0), out.get("label")),
          flush=True)
    return out


COLS = ["kind", "tag", "L", "D", "a", "rho_i", "si", "nx", "pattern", "mu", "y2d", "span_depth", "mass_ratio",
        "T", "steps", "exit", "wall_s", "joints_broken", "first_break", "label", "paper", "flexural_first",
        "other", "t_plug", "t_edge", "t_flexural", "t_cone", "t_supports"]


def write_csv(rows, path, cols=None):
    cols = cols or COLS
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=cols, extrasaction="ignore")
        w.writeheader()
        for r in rows:
            w.writerow({k: ("" if r.get(k) is None else (("%.6g" % r[k]) if isinstance(r[k], float) else r[k]))
                        for k in cols})


def read_csv(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


STYLE = {"plug": ("s", "tab:red"), "edge": ("D", "tab:purple"), "flexural": ("o", "tab:blue"),
         "cone": ("^", "tab:green"), "supports": ("v", "tab:orange")}
FIXED_COLORS = {"plug": "tab:red", "plug>flexural": "tab:orange", "plug>flexural>cone": "tab:olive",
                "edge>flexural>cone": "tab:green", "none": "0.6"}
LABEL_COLORS = ["tab:red", "tab:orange", "tab:green", "tab:purple", "tab:blue", "tab:brown", "tab:pink", "tab:olive"]


def plot(rows, path):
    """Left: the grid, one marker per run coloured by its broken-crack sequence (a black ring: the
    paper's sequence).  Right: the one-at-a-time and search runs, each class's first break on a
    time line, the sequence written beside it."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    grid = [r for r in rows if r["kind"] == "grid" and r.get("label")]
    oat = [r for r in rows if r["kind"].startswith(("oat", "search")) and r.get("label")]
    labels = []
    for r in rows:
        if r.get("label") and r["label"] not in labels and r["label"] != "none":
            labels.append(r["label"])
    color = dict(zip(labels, [c for c in LABEL_COLORS if c not in FIXED_COLORS.values()] * 4))
    color.update(FIXED_COLORS)
    color["none"] = "0.6"
    fig, (ax, bx) = plt.subplots(1, 2, figsize=(12, 5.2), gridspec_kw={"width_ratios": [1, 1.25]})
    seen, taken = set(), set()
    marks = {"0.1": "o", "0.15": "s", "0.2": "^"}
    for r in grid:
        x, y = float(r["span_depth"]), float(r["mass_ratio"])
        while (round(x, 2), y) in taken:  # two depths at one L/D: side by side
            x *= 1.08
        taken.add((round(x, 2), y))
        ax.scatter([x], [y], marker=marks.get("%g" % float(r["D"]), "D"), c=color[r["label"]], s=150, zorder=3,
                   label=None if r["label"] in seen else r["label"],
                   edgecolors="k" if r["paper"] == "True" else "w", linewidths=2)
        seen.add(r["label"])
    for d, mk in marks.items():
        ax.scatter([], [], marker=mk, c="w", edgecolors="k", s=60, label="D %s m" % d)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ticks = sorted({round(float(r["span_depth"]), 1) for r in grid})
    ax.set_xticks(ticks)
    ax.set_xticklabels(["%g" % t for t in ticks])
    ax.minorticks_off()
    ratios = sorted({float(r["mass_ratio"]) for r in grid})
    ax.set_yticks(ratios)
    ax.set_yticklabels(["%g" % t for t in ratios])
    ax.set_xlim(4, 25)
    ax.set_ylim(0.06, 5)
    ax.set_xlabel("span / depth  L / D   (L 1-2 m, D 0.1-0.2 m)")
    ax.set_ylabel("impactor / beam mass  rho_i a^2 / (2340 L D)")
    ax.set_title("broken-crack sequence (first break first), v0 5 m/s, a 0.05 m, cells 1/40 m", fontsize=9)
    ax.legend(fontsize=8, loc="upper center", bbox_to_anchor=(0.5, -0.13), ncol=3, frameon=False)
    ax.grid(alpha=0.3)
    tmax = 0.0
    for i, r in enumerate(oat):
        ts = [(k, float(r["t_" + k]) * 1e6) for k in failure_mode.CLASSES if r.get("t_" + k)]
        if ts:
            bx.plot([t for _, t in ts], [i] * len(ts), "-", c="0.8", zorder=1)
        for k, t in ts:
            mk, col = STYLE[k]
            bx.scatter([t], [i], marker=mk, c=col, s=50, zorder=3, label=k)
            tmax = max(tmax, t)
    for i, r in enumerate(oat):
        bx.annotate(r["label"], (1.02, i), xycoords=("axes fraction", "data"), fontsize=7, va="center")
    bx.set_yticks(range(len(oat)))
    bx.set_yticklabels([r["kind"].replace("oat:", "").replace("search:", "deep: ") for r in oat], fontsize=7)
    bx.set_xlim(0, tmax * 1.05 + 1)
    bx.set_xlabel("time of the class's first break [us]")
    bx.set_title("one at a time: the default scene (L/D 10, mass 0.32);\n"
                 "deep: L 1, D 0.2, mass 0.1 (the grid's edge>flexural>cone)", fontsize=9)
    h, lab = bx.get_legend_handles_labels()
    uniq = dict(zip(lab, h))
    bx.legend(uniq.values(), uniq.keys(), fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.13), ncol=5,
              frameon=False)
    bx.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    print("failure_map: wrote", path)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--workdir", default="sweep_runs/failure_map")
    ap.add_argument("--csv", required=True)
    ap.add_argument("--plot")
    ap.add_argument("--only", choices=["grid", "extra", "oat", "search"],
                    help="beam: one block; column: search runs only the search block (default: the grid)")
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--replot", action="store_true", help="only redraw the plot from --csv")
    ap.add_argument("--reclassify", action="store_true",
                    help="classify again the runs of --csv from their directories under --workdir (no runs)")
    ap.add_argument("--scene", choices=["beam", "column"], default="beam")
    ap.add_argument("--cracks", help="column: PNG of every run's broken joints (needs --workdir's runs)")
    ap.add_argument("--nx", type=int, default=COLUMN_NX, help="column: cells across (default %d)" % COLUMN_NX)
    a = ap.parse_args(argv)
    if a.scene == "column":
        if a.reclassify:
            rows = read_csv(a.csv)
            for r in rows:
                if r["exit"] == "0":
                    r.update({k: v for k, v in column_classes(os.path.join(a.workdir, r["tag"])).items()})
            write_csv(rows, a.csv, COLUMN_COLS)
            print("failure_map: reclassified", a.csv)
        elif not a.replot:
            with cf.ThreadPoolExecutor(a.jobs) as ex:
                rows = list(ex.map(lambda r: one_column(r[0], r[1], r[2], a.workdir), column_design(a.nx, a.only)))
            write_csv(rows, a.csv, COLUMN_COLS)
            print("failure_map: wrote", a.csv)
        if a.plot:
            plot_column(read_csv(a.csv), a.plot)
        if a.cracks:
            plot_column_cracks(read_csv(a.csv), a.workdir, a.cracks)
        return 0
    if a.reclassify:
        rows = read_csv(a.csv)
        for r in rows:
            if r["exit"] == "0":
                c = failure_mode.classify_run(os.path.join(a.workdir, r["tag"]))
                r.update(label=c["label"], paper=c["paper"], other=c["other"], flexural_first=c["flexural_first"])
                for k in failure_mode.CLASSES:
                    r["t_" + k] = c[k]["time"] if c[k]["present"] else None
        write_csv(rows, a.csv)
        print("failure_map: reclassified", a.csv)
    elif not a.replot:
        runs = design(a.only)
        with cf.ThreadPoolExecutor(a.jobs) as ex:
            rows = list(ex.map(lambda r: one(r[0], r[1], r[2], a.workdir), runs))
        write_csv(rows, a.csv)
        print("failure_map: wrote", a.csv)
    if a.plot:
        plot(read_csv(a.csv), a.plot)
    return 0


if __name__ == "__main__":
    sys.exit(main())
