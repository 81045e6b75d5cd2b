#!/usr/bin/env python3
"""yfsweep: write yfdem decks from parameters and run parameter sweeps.

A sweep takes a template deck whose parameters are `variable NAME index VALUE` lines (the seed
paper's decks/beam.deck and decks/column.deck are written that way: nx, v0, ft, steps, ...), runs
every combination of the values given, one run per directory, and collects each run's -summary
JSON into one CSV row (nested keys flattened with dots: first_crack.time) plus a plot.

  tools/yfsweep.py decks/beam.deck --param nx=20,30,40 --set steps=2000 \\
      --keys first_crack.time,midspan_crack_time,first_break.time,symmetry,joints_opened,joints_broken \\
      --csv docs/sweep/beam_nx.csv --plot docs/sweep/beam_nx.png

Each run directory (--workdir, default sweep_runs/) holds the generated deck RUN.deck (the template
with the swept and --set values written into its `variable ... index` lines, so the deck alone
reproduces the run), its summary, log and outputs.  The values are also passed as `-var NAME
VALUE` (index variables: the command line wins), which is what `yfdem` itself documents.

As a module:
    import yfsweep
    text = yfsweep.write_deck("decks/beam.deck", {"nx": 40, "steps": 2000})
    row = yfsweep.run_case("decks/beam.deck", {"nx": 40}, "runs/nx40")
    rows = yfsweep.sweep("decks/beam.deck", {"nx": [20, 40]}, fixed={"steps": 2000})

The plot (matplotlib, from tools/install-deps --python; skipped with a message when missing) puts
the first swept parameter on x and one panel per key.
"""
import argparse
import csv
import itertools
import json
import os
import re
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
VAR_RE = re.compile(r"^(\s*variable\s+)(\S+)(\s+index\s+)(\S+)(.*)$")


def write_deck(template, params, path=None):
    """Deck text of TEMPLATE with `variable NAME index V` set from params (NAME -> value).
    Every parameter must be an index variable of the template.  Written to path if given."""
    with open(template) as f:
        lines = f.read().split("\n")
    seen = set()
    for i, ln in enumerate(lines):
        m = VAR_RE.match(ln)
        if m and m.group(2) in params:
            lines[i] = "%s%s%s%s%s" % (m.group(1), m.group(2), m.group(3), params[m.group(2)], m.group(5))
            seen.add(m.group(2))
    missing = set(params) - seen
    if missing:
        raise ValueError("%s has no `variable NAME index` line for: %s" % (template, ", ".join(sorted(missing))))
    text = "\n".join(lines)
    if path:
        with open(path, "w") as f:
            f.write(text)
    return text


def flatten(d, pre=""):
    """Nested summary dict -> {dotted.key: scalar}; lists are skipped (fragment lists etc.)."""
    out = {}
    for k, v in d.items():
        key = pre + k
        if isinstance(v, dict):
            out.update(flatten(v, key + "."))
        elif not isinstance(v, list):
            out[key] = v
    return out


def run_case(template, params, rundir, yfdem=None, threads=2):
    """Write RUN.deck into rundir, run it, return the flattened summary plus params, wall time
    and exit code."""
    os.makedirs(rundir, exist_ok=True)
    deck = os.path.join(rundir, "run.deck")
    write_deck(template, params, deck)
    exe = yfdem or os.environ.get("YFDEM") or os.path.join(ROOT, "yfdem")
    cmd = [os.path.abspath(exe), "-in", "run.deck", "-summary", "summary.json"]
    for k, v in params.items():
        cmd += ["-var", k, str(v)]
    env = dict(os.environ, OMP_NUM_THREADS=str(threads))
    t0 = time.time()
    with open(os.path.join(rundir, "log.txt"), "w") as log:
        rc = subprocess.call(cmd, cwd=rundir, stdout=log, stderr=subprocess.STDOUT, env=env)
    row = dict(params)
    row["exit"] = rc
    row["wall_s"] = round(time.time() - t0, 3)
    sp = os.path.join(rundir, "summary.json")
    if rc == 0 and os.path.exists(sp):
        with open(sp) as f:
            row.update(flatten(json.load(f)))
    return row


def sweep(template, grid, fixed=None, workdir="sweep_runs", yfdem=None, threads=2, quiet=False):
    """Run every combination of grid (NAME -> list of values) with fixed values added; returns rows."""
    names = list(grid)
    rows = []
    for combo in itertools.product(*(grid[n] for n in names)):
        params = dict(fixed or {})
        params.update(zip(names, combo))
        tag = "_".join("%s%s" % (n, v) for n, v in zip(names, combo)) or "run"
        row = run_case(template, params, os.path.join(workdir, tag), yfdem, threads)
        rows.append(row)
        if not quiet:
            print("yfsweep: %s exit %d, %.1f s" % (tag, row["exit"], row["wall_s"]), flush=True)
    return rows


def write_csv(rows, path, keys=None, params=None):
    """CSV of rows: the params columns, exit, wall_s, then keys (every column when keys is None)."""
    if not rows:
        return
    if keys:
        cols = list(params or []) + ["exit", "wall_s"] + list(keys)
    else:
        cols = []
        for r in rows:
            cols += [k for k in r if k not in cols]
    os.makedirs(os.path.dirname(os.path.abspath(path)), exist_ok=True)
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=cols, extrasaction="ignore")
        w.writeheader()
        for r in rows:
            w.writerow({k: ("" if r.get(k) is None else r.get(k)) for k in cols})


def plot(rows, xkey, keys, path, title=None):
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("yfsweep: no matplotlib (tools/install-deps --python; use .venv/bin/python): no plot")
        return
    n = len(keys)
    fig, axs = plt.subplots(n, 1, figsize=(5.5, 1.7 * n + 0.6), sharex=True, squeeze=False)
    xs = [float(r[xkey]) for r in rows]
    for ax, k in zip(axs[:, 0], keys):
        ys = [float(r[k]) if isinstance(r.get(k), (int, float)) else float("nan") for r in rows]
        scale, unit = 1.0, ""
        if k.endswith("time") and any(y == y for y in ys):
            scale, unit = 1e6, " [us]"
        ax.plot(xs, [y * scale for y in ys], "o-", ms=4)
        ax.set_ylabel(k + unit, fontsize=8)
        ax.grid(alpha=0.3)
        ax.tick_params(labelsize=8)
    axs[-1, 0].set_xlabel(xkey)
    if title:
        fig.suptitle(title, fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    print("yfsweep: wrote", path)


def parse_kv(items, lists):
    out = {}
    for it in items or []:
        if "=" not in it:
            sys.exit("yfsweep: expected NAME=VALUE%s, got '%s'" % (",VALUE..." if lists else "", it))
        k, v = it.split("=", 1)
        out[k] = v.split(",") if lists else v
    return out


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("deck", help="template deck with `variable NAME index VALUE` parameters")
    p.add_argument("--param", action="append", help="NAME=V1,V2,... swept (repeat: all combinations)")
    p.add_argument("--set", action="append", help="NAME=VALUE fixed for every run")
    p.add_argument("--keys", default="first_crack.time,first_break.time,symmetry,joints_opened,joints_broken",
                   help="summary keys (dotted) for the CSV's last columns and the plot")
    p.add_argument("--csv", required=True)
    p.add_argument("--plot")
    p.add_argument("--title")
    p.add_argument("--workdir", default="sweep_runs")
    p.add_argument("--threads", type=int, default=2)
    p.add_argument("--yfdem")
    a = p.parse_args(argv)
    grid, fixed = parse_kv(a.param, True), parse_kv(a.set, False)
    if not grid:
        sys.exit("yfsweep: give at least one --param NAME=V1,V2")
    try:
        write_deck(a.deck, dict(fixed, **{k: v[0] for k, v in grid.items()}))
    except (OSError, ValueError) as e:
        sys.exit("yfsweep: %s" % e)
    keys = [k for k in a.keys.split(",") if k]
    rows = sweep(a.deck, grid, fixed, a.workdir, a.yfdem, a.threads)
    write_csv(rows, a.csv, keys, list(grid) + list(fixed))
    print("yfsweep: wrote", a.csv)
    if a.plot:
        plot(rows, list(grid)[0], keys, a.plot, a.title)
    return 0 if all(r["exit"] == 0 for r in rows) else 1


if __name__ == "__main__":
    sys.exit(main())
