#!/usr/bin/env python3
"""study.py: the speed-against-accuracy trade of yfdem, measured (issue 8).

Runs small scenes over a grid of element size, time-step safety factor, penalty (as a multiple
of E) and contact's `joined keep|skip`, and for each run records the cost (wall time and
element-steps from the -summary JSON) and the error against a reference:

  wave        a bar pushed at one end: wave speed (= arrival time) from the rate of external
              work, rho c v^2 H, against c = sqrt(E/rho)                      [analytical]
  cantilever  decks/cantilever.deck: tip deflection against Timoshenko beam theory
                                                                               [analytical]
  joint       a notched bar pulled until one crack crosses it: energy dissipated by fracture
              against G_f x height, and the elastic stiffness before it against E [analytical]
  incline     a block sliding down a 30 degree incline (mu = 0.2): acceleration against
              g (sin 30 - mu cos 30)                                           [analytical]
  beam        a small notched beam hit by an impactor: first-break time, crack length,
              fragments, fracture energy, against the finest `joined keep` run  [finest run]

Output: OUT/study.csv (one row per run and measured quantity) and OUT/study_SCENE.png (error
against cost, the Pareto front marked).  The default grid takes a few minutes on 2 cores;
--quick runs a CI-size subset (about half a minute).

  tools/study.py [--quick] [--out docs/study] [--yfdem ./yfdem] [--scenes wave,joint,...]

Needs only the Python standard library to run and write the CSV; the plots need matplotlib
(`tools/install-deps --python` creates .venv with it; run as `.venv/bin/python tools/study.py`).
"""
import argparse
import csv
import json
import math
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)

# ---------------------------------------------------------------------------------- scenes
# Each deck prints one line "RESULT key value key value ..." read back by the study.

WAVE = """
variable n index 40
variable s index 0.5
variable L equal 0.2
variable H equal 0.01
variable c equal sqrt(1e9/1000)
material m elastic rho 1000 E 1e9 nu 0 plane_stress
mesh rect bar m 0 0 ${L} ${H} ${n} $(max(1,round(v_n/20))) pattern right
region l box -1 -1 1e-9 1
group l node region l
fix push l velocity 1.0 NULL
timestep auto safety ${s}
run 0
run $(round(0.3*v_L/v_c/dt))
variable w1 string $(ext_work)
variable t1 string $(time)
run $(round(0.4*v_L/v_c/dt))
print "RESULT c $((ext_work-v_w1)/(time-v_t1)/(1000*v_H)) c_ref ${c}"
"""

JOINT = """
variable nx index 20
variable pen index 10
variable L equal 0.1
variable H equal 0.02
material c elastic rho 2500 E 1e10 nu 0.2 plane_stress
mesh rect bar c 0 0 ${L} ${H} ${nx} $(max(1,round(v_nx/5))) pattern alt
jointprop cj ft 3e6 fs 3e6 gf 100 pen $(v_pen*1e10) law munjiza_gf
jointprop weak ft 2.7e6 fs 2.7e6 gf 100 pen $(v_pen*1e10) law munjiza_gf
region notch box $(0.5*v_L-0.5*v_L/v_nx) -1 $(0.5*v_L+0.5*v_L/v_nx) 1
fracture bar cj
fracture bar weak region notch
region left box -1 -1 1e-9 1
region right box $(v_L*0.99999) -1 1 1
group left node region left
group right node region right
fix hold left fixed xy
history pull ramp 0 4e-3
fix pull right displacement 4e-4 NULL history pull
damping mass 3000
timestep auto
run 0
run $(round(2e-4/dt))
variable k string $(-fx_right/(ux_right*1e10*v_H/v_L))
run $(round(4.3e-3/dt))
print "RESULT gf $(joint_dissipated/v_H) gf_ref 100 stiffness ${k} stiffness_ref 1"
"""

INCLINE = """
variable n index 4
variable pen index 10
variable s index 0.5
variable th equal 30*pi/180
material m elastic rho 1000 E 1e8 nu 0.25 plane_strain pen_n $(v_pen*1e8) pen_t $(v_pen*1e8) friction 0.2
mesh rect base m 0 -0.02 0.4 0 $(8*v_n) 2
mesh rect blk m 0.05 0 0.1 0.05 ${n} ${n}
fix hold base fixed xy
contact pair blk base
timestep auto safety ${s}
gravity 0 $(-9.81*cos(v_th))
damping mass 3e4
run 0
run $(round(0.03/dt))
damping mass 0
gravity $(9.81*sin(v_th)) $(-9.81*cos(v_th))
run $(round(0.005/dt))
variable v1 string $(vx_blk)
variable t1 string $(time)
run $(round(0.02/dt))
print "RESULT a $((vx_blk-v_v1)/(time-v_t1)) a_ref $(9.81*(sin(v_th)-0.2*cos(v_th)))"
"""

BEAM = """
variable nx index 40
variable joined index keep
variable s index 0.5
variable L equal 0.4
variable H equal 0.1
material con elastic rho 2400 E 3e10 nu 0.2 plane_stress pen_n 3e11 pen_t 3e11 friction 0.3
material st elastic rho 7800 E 2e11 nu 0.3 plane_stress pen_n 3e11 pen_t 3e11 friction 0.3
mesh rect beam con 0 0 ${L} ${H} ${nx} $(round(v_nx/4)) pattern alt
mesh rect imp st $(0.5*v_L-0.02) ${H} $(0.5*v_L+0.02) $(v_H+0.04) 2 2
jointprop cj ft 3e6 fs 9e6 gf 100 pen 3e11 law munjiza_gf
fracture beam cj
region sl box -1 -1 0.02 1e-9
region sr box $(v_L-0.02) -1 1 1e-9
group sl node region sl
group sr node region sr
fix a sl fixed xy
fix b sr fixed y
contact pair imp beam
contact self beam
contact joined ${joined}
velocity imp set 0 -5
timestep auto safety ${s}
run 0
run $(round(2e-4/dt))
print "RESULT broken $(broken) jd $(joint_dissipated)"
"""


def cantilever_deck():
    with open(os.path.join(ROOT, "decks", "cantilever.deck")) as f:
        text = f.read()
    # no dump: the study measures cost, not output
    text = "\n".join(l for l in text.splitlines() if not l.startswith("dump "))
    return text + '\nprint "RESULT u $(-uy_tip) u_ref $(v_P/(3*1e9*0.1^3/12) + v_P/(5/6*0.4e9*0.1))"\n'


def grid(quick):
    """(scene, deck text, {var: value}) for every run."""
    runs = []
    ns = [20, 40] if quick else [20, 40, 80]
    ss = [0.5, 0.9] if quick else [0.25, 0.5, 0.9]
    for n in ns:
        for s in ss:
            runs.append(("wave", WAVE, {"n": n, "s": s}))
    for nx in ([20] if quick else [20, 40, 60]):
        runs.append(("cantilever", cantilever_deck(), {"nx": nx}))
    for nx in ([10, 20] if quick else [10, 20, 40]):
        for pen in ([1, 10] if quick else [1, 10, 100]):
            if nx * pen <= 2000:  # 40 cells at 100 E would take minutes alone
                runs.append(("joint", JOINT, {"nx": nx, "pen": pen}))
    for n in ([2, 4] if quick else [2, 4, 8]):
        for pen in ([1, 10] if quick else [1, 10, 100]):
            for s in ([0.5] if quick else [0.5, 0.9]):
                runs.append(("incline", INCLINE, {"n": n, "pen": pen, "s": s}))
    for nx in ([12, 16] if quick else [12, 16, 24, 32]):
        for joined in ("keep", "skip"):
            runs.append(("beam", BEAM, {"nx": nx, "joined": joined}))
    return runs


def run_one(yfdem, scene, deck, var, tmp):
    path = os.path.join(tmp, scene + ".deck")
    with open(path, "w") as f:
        f.write(deck)
    summ = os.path.join(tmp, "summary.json")
    cmd = [yfdem, "-in", path, "-summary", summ]
    for k, v in var.items():
        cmd += ["-var", k, str(v)]
    p = subprocess.run(cmd, cwd=tmp, capture_output=True, text=True)
    res = {}
    for line in p.stdout.splitlines():
        if line.startswith("RESULT "):
            w = line.split()[1:]
            res = {w[i]: float(w[i + 1]) for i in range(0, len(w) - 1, 2)}
    try:
        with open(summ) as f:
            js = json.load(f)
    except (OSError, ValueError):
        js = {}
    if p.returncode != 0 or not res:
        sys.stderr.write("study: %s %s failed (exit %d): %s\n" % (scene, var, p.returncode, p.stderr.strip()[:300]))
    return p.returncode, res, js


def rows_for(scene, var, code, res, js):
    """One CSV row per measured quantity with an analytical reference ('beam' later)."""
    base = {
        "scene": scene,
        "h": "", "safety": var.get("s", ""), "pen_over_E": var.get("pen", ""),
        "joined": var.get("joined", ""), "exit": code,
        "wall_s": js.get("wall_s", ""),
        "element_steps": (js.get("elements", 0) or 0) * (js.get("steps", 0) or 0),
        "steps": js.get("steps", ""), "dt": js.get("dt", ""), "dt_limit": js.get("dt_limit", ""),
        "first_break": "", "crack_length": js.get("crack_length", ""), "fragments": js.get("fragments", ""),
    }
    if isinstance(base["crack_length"], dict):
        base["crack_length"] = base["crack_length"].get("total", "")
    fb = js.get("first_break")
    if isinstance(fb, dict):
        base["first_break"] = fb.get("time", "")
    sizes = {"wave": lambda v: 0.2 / v["n"], "cantilever": lambda v: 1.0 / v["nx"],
             "joint": lambda v: 0.1 / v["nx"], "incline": lambda v: 0.05 / v["n"], "beam": lambda v: 0.4 / v["nx"]}
    base["h"] = sizes[scene](var)
    out = []
    pairs = [(k, k + "_ref") for k in res if k + "_ref" in res]
    if scene == "beam":
        pairs = [(k, None) for k in ("broken", "jd")]
    for q, r in pairs:
        row = dict(base)
        row["quantity"] = q
        row["value"] = res.get(q, "")
        row["reference"] = res.get(r, "") if r else ""
        if r and q in res and res[r] != 0:
            row["rel_error"] = abs(res[q] / res[r] - 1.0)
        else:
            row["rel_error"] = ""
        out.append(row)
    if scene == "beam":
        for q in ("first_break", "crack_length", "fragments"):
            row = dict(base)
            row["quantity"] = q
            row["value"] = base[q]
            row["reference"] = ""
            row["rel_error"] = ""
            out.append(row)
    return out


def beam_reference(rows):
    """Errors of the beam runs against the finest `joined keep` run."""
    beam = [r for r in rows if r["scene"] == "beam" and r["exit"] == 0]
    if not beam:
        return
    hmin = min(r["h"] for r in beam if r["joined"] == "keep")
    ref = {r["quantity"]: r["value"] for r in beam if r["joined"] == "keep" and r["h"] == hmin}
    for r in beam:
        v, rv = r["value"], ref.get(r["quantity"])
        r["reference"] = rv if rv is not None else ""
        try:
            r["rel_error"] = abs(float(v) / float(rv) - 1.0)
        except (TypeError, ValueError, ZeroDivisionError):
            r["rel_error"] = ""


FIELDS = ["scene", "h", "safety", "pen_over_E", "joined", "quantity", "value", "reference", "rel_error",
          "wall_s", "element_steps", "steps", "dt", "dt_limit", "first_break", "crack_length", "fragments", "exit"]


def pareto(points):
    """Indices of the points not dominated in (cost, error), both to be small."""
    idx = sorted(range(len(points)), key=lambda i: (points[i][0], points[i][1]))
    front, best = [], math.inf
    for i in idx:
        if points[i][1] < best:
            front.append(i)
            best = points[i][1]
    return front


def plot(rows, out):
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        sys.stderr.write("study: matplotlib is missing, CSV written but no plots: run tools/install-deps --python, "
                         "then .venv/bin/python tools/study.py\n")
        return
    for scene in sorted({r["scene"] for r in rows}):
        sr = [r for r in rows if r["scene"] == scene and r["rel_error"] != "" and r["element_steps"]]
        qs = sorted({r["quantity"] for r in sr})
        if not qs:
            continue
        fig, axes = plt.subplots(1, len(qs), figsize=(4.2 * len(qs), 3.6), squeeze=False)
        for ax, q in zip(axes[0], qs):
            pr = [r for r in sr if r["quantity"] == q]
            pts = [(float(r["element_steps"]), max(float(r["rel_error"]), 1e-9)) for r in pr]
            labels = [label(r) for r in pr]
            for (x, y), lab in zip(pts, labels):
                ax.loglog(x, y, "o", color="0.6", ms=4)
                ax.annotate(lab, (x, y), fontsize=6, xytext=(2, 2), textcoords="offset points")
            fr = pareto(pts)
            ax.loglog([pts[i][0] for i in fr], [pts[i][1] for i in fr], "r-o", ms=5, label="Pareto front")
            ax.set_xlabel("cost [element-steps]")
            ax.set_ylabel("relative error of %s" % q)
            ax.set_title("%s: %s" % (scene, q), fontsize=9)
            ax.legend(fontsize=7)
        fig.tight_layout()
        fig.savefig(os.path.join(out, "study_%s.png" % scene), dpi=90)
        plt.close(fig)


def label(r):
    parts = ["h=%.3g" % r["h"]]
    if r["safety"] != "":
        parts.append("s=%s" % r["safety"])
    if r["pen_over_E"] != "":
        parts.append("p=%sE" % r["pen_over_E"])
    if r["joined"]:
        parts.append(r["joined"])
    return " ".join(parts)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--quick", action="store_true", help="CI-size grid (about half a minute)")
    ap.add_argument("--out", default=os.path.join(ROOT, "docs", "study"))
    ap.add_argument("--yfdem", default=os.path.join(ROOT, "yfdem"))
    ap.add_argument("--scenes", default="wave,cantilever,joint,incline,beam")
    a = ap.parse_args()
    if not os.access(a.yfdem, os.X_OK):
        sys.exit("study: %s not found or not executable: run `make` first" % a.yfdem)
    want = set(a.scenes.split(","))
    os.makedirs(a.out, exist_ok=True)
    rows = []
    runs = [r for r in grid(a.quick) if r[0] in want]
    with tempfile.TemporaryDirectory() as tmp:
        for k, (scene, deck, var) in enumerate(runs):
            code, res, js = run_one(a.yfdem, scene, deck, var, tmp)
            new = rows_for(scene, var, code, res, js)
            rows += new
            errs = ", ".join("%s %.3g" % (r["quantity"], r["rel_error"]) for r in new if r["rel_error"] != "")
            print("[%d/%d] %-10s %-40s %6.2f s  %s" % (k + 1, len(runs), scene, var, float(js.get("wall_s", 0) or 0),
                                                      errs), flush=True)
    beam_reference(rows)
    path = os.path.join(a.out, "study.csv")
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=FIELDS)
        w.writeheader()
        for r in rows:
            w.writerow({k: r.get(k, "") for k in FIELDS})
    print("study: %d runs, %d rows -> %s" % (len(runs), len(rows), path))
    plot(rows, a.out)


if __name__ == "__main__":
    main()
