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
        out.update(label=c["label"], paper=c["paper"], other=c["other"])
        for k in failure_mode.CLASSES:
            out["t_" + k] = c[k]["time"] if c[k]["present"] else None
    print("failure_map: %-28s exit %d  %6.1f s  %s" % (tag, out["exit"], out.get("wall_s", 0), out.get("label")),
          flush=True)
    return out


COLS = ["kind", "tag", "L", "D", "a", "rho_i", "si", "nx", "pattern", "mu", "y2d", "span_depth", "mass_ratio",
        "T", "steps", "exit", "wall_s", "joints_broken", "first_break", "label", "paper", "other",
        "t_plug", "t_flexural", "t_cone", "t_supports"]


def write_csv(rows, path):
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=COLS, extrasaction="ignore")
        w.writeheader()
        for r in rows:
            w.writerow({k: ("" if r.get(k) is None else (("%.6g" % r[k]) if isinstance(r[k], float) else r[k]))
                        for k in COLS})


def read_csv(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


STYLE = {"plug": ("s", "tab:red"), "flexural": ("o", "tab:blue"), "cone": ("^", "tab:green"),
         "supports": ("v", "tab:orange"), "none": ("x", "0.5"), "other": ("d", "0.3")}


def plot(rows, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    grid = [r for r in rows if r["kind"] == "grid" and r.get("label")]
    oat = [r for r in rows if r["kind"].startswith("oat") and r.get("label")]
    fig, (ax, bx) = plt.subplots(1, 2, figsize=(11, 4.6), gridspec_kw={"width_ratios": [1.15, 1]})
    seen = set()
    for r in grid:
        x, y = float(r["span_depth"]), float(r["mass_ratio"])
        first = r["label"].split(">")[0]
        mk, col = STYLE.get(first, STYLE["other"])
        ax.scatter([x], [y], marker=mk, c=col, s=90, label=None if first in seen else "first: " + first,
                   edgecolors="k" if r["paper"] == "True" else "none", linewidths=2)
        seen.add(first)
        ax.annotate(r["label"].replace(">", ">\n"), (x, y), textcoords="offset points", xytext=(7, -4),
                    fontsize=6.5)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xticks([5, 7.5, 10, 13.3, 20])
    ax.set_xticklabels(["5", "7.5", "10", "13.3", "20"])
    ax.set_xlim(4, 32)
    ax.set_xlabel("span / depth  L / D")
    ax.set_ylabel("impactor / beam mass  rho_i a^2 / (rho L D)")
    ax.set_title("broken-crack sequence, v0 = 5 m/s, cells 1/40 m", fontsize=9)
    ax.legend(fontsize=7, loc="upper left")
    ax.grid(alpha=0.3, which="both")
    names = [r["kind"][4:] for r in oat]
    for i, r in enumerate(oat):
        for k in failure_mode.CLASSES:
            t = r.get("t_" + k)
            if t:
                mk, col = STYLE[k]
                bx.scatter([float(t) * 1e6], [i], marker=mk, c=col, s=60, label=k if i == 0 or k not in
                           [l.get_label() for l in bx.collections] else None)
        bx.annotate(r["label"], (5, i + 0.25), fontsize=6.5)
    bx.set_yticks(range(len(oat)))
    bx.set_yticklabels(names, fontsize=7.5)
    bx.set_xscale("log")
    bx.set_xlabel("time of the class's first break [us]")
    bx.set_title("one at a time around the default scene (L/D 10, mass 0.32)", fontsize=9)
    h, l = bx.get_legend_handles_labels()
    uniq = dict(zip(l, h))
    bx.legend(uniq.values(), uniq.keys(), fontsize=7, loc="lower right")
    bx.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    print("failure_map: wrote", path)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--workdir", default="sweep_runs/failure_map")
    ap.add_argument("--csv", required=True)
    ap.add_argument("--plot")
    ap.add_argument("--only", choices=["grid", "oat"])
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--replot", action="store_true", help="only redraw the plot from --csv")
    a = ap.parse_args(argv)
    if not a.replot:
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
