#!/usr/bin/env python3
"""stability_study.py: is yfdem's printed stable limit a real bound?  (issue 17)

For each scene, bisect the largest time step dt_max at which the run stays stable, and put it
beside the stable limit dt_lim that yfdem prints (`timestep auto` uses safety x dt_lim).
"Stable" = the run reaches its last step with its energy balance closed at every check (every
100 steps): kinetic + stored + dissipated - given within 5 % of the energy given (energy.c), and
no numerical failure.  An unstable step creates energy without bound, so the verdict does not
hang on that tolerance: the unstable runs of the table miss it by factors of 10 to 1e6 within a
few hundred steps (the residual column shows the first one above dt_max).

dt is set as a factor F of dt_lim: F x dt_lim through `energy_check warn` + `timestep $(F*dt_lim)`
on native decks (a step above the limit is then accepted with a warning), DCSTEC on Y2D decks
(which only warn).  The search: F = 1, then x1.25 up (or x0.8 down) until the verdict changes,
then 4 bisections (F within 1.5 %).  Output: a Markdown table on stdout (docs/STABILITY.md).

  tools/stability_study.py [--yfdem ./yfdem] [--y2d ../shared/y2d/decks] [--scenes a,b,...] [-j 2]
"""
import argparse
import concurrent.futures
import json
import os
import re
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)

# An own scene with contact, joints and fragments: a fracturing plate on two steel supports hit
# at 20 m/s by a steel block, fragments in self-contact.
FRAG_DECK = """
material rock elastic rho 2600 E 30e9 nu 0.2 plane_strain damping 0.1 pen_n 3e11 pen_t 3e10 friction 0.5
material steel elastic rho 7800 E 210e9 nu 0.3 plane_strain pen_n 3e11 pen_t 3e10 friction 0.3
mesh rect plate rock 0 0 0.2 0.04 10 2 pattern cross
mesh rect l steel 0.0 -0.02 0.02 0 1 1
mesh rect r steel 0.18 -0.02 0.2 0 1 1
mesh rect hammer steel 0.09 0.04 0.11 0.06 1 1
jointprop cj ft 4e6 fs 8e6 gf 60 pen 3e11 law munjiza
fracture plate cj
region floor box -1 -1 1 -0.0199
group floor node region floor
fix base floor fixed xy
velocity hammer set 0 -20
contact pair hammer plate
contact pair plate l
contact pair plate r
contact self plate
timestep auto
run 1500
"""

# name: (kind, source, steps, -var pairs or generator args, what it has)
SCENES = {
    "beam": ("native", "decks/beam.deck", None, ["nx", "40", "steps", "4000", "every", "100000"],
             "impact, contact, joints, fragments"),
    "blocks_impact": ("native", "decks/blocks_impact.deck", None, [], "impact, contact, friction"),
    "column": ("native", "decks/column.deck", None, ["steps", "4000"], "impact, contact, joints"),
    "fracture_bar": ("native", "decks/fracture_bar.deck", None, [], "joints, mass damping"),
    "wave_bar": ("native", "decks/wave_bar.deck", None, [], "triangles only"),
    "cantilever": ("native", "decks/cantilever.deck", None, [], "triangles only"),
    "gmsh_body": ("native", "decks/gmsh_body.deck", None, [], "triangles only"),
    "frag_plate": ("inline", FRAG_DECK, None, [], "own: impact, contact, joints, fragments"),
    "a_elastic_block": ("y2d", "a_elastic_block.y", 4000, None, "Y2D: impact, contact"),
    "b_beam_impact": ("y2d", "b_beam_impact.y", 4000, None, "Y2D: impact, contact, joints"),
    "c_column_impact": ("y2d", "c_column_impact.y", 4000, None, "Y2D: impact, contact, joints"),
    "d1_cantilever_bc": ("y2d", "d1_cantilever_bc.y", 4000, None, "Y2D: loads, supports"),
    "joint_settle": ("gen", "0", None, None, "own Y2D: joint insertion, contact, gravity"),
    "joint_release": ("gen", "5e-6", None, None, "own Y2D: joint insertion, 5 um start overlap"),
}


def run(cmd, cwd):
    p = subprocess.run(cmd, cwd=cwd, capture_output=True, text=True,
                       env=dict(os.environ, OMP_NUM_THREADS="1"))
    return p.returncode, p.stdout, p.stderr


def native_deck(text, factor):
    """The deck with its timestep line replaced by F x the stable limit (energy_check warn)."""
    lines, done = [], False
    for ln in text.splitlines():
        if re.match(r"\s*timestep\b", ln) and not done:
            lines += ["energy_check warn", "timestep auto", "run 0", "timestep $(%r*dt_limit)" % factor]
            done = True
        else:
            lines.append(ln)
    return "\n".join(lines) + "\n"


def y2d_deck(text, factor, dt_lim, steps):
    text = re.sub(r"^/YD/YDC/DCSTEC .*$", "/YD/YDC/DCSTEC %r" % (factor * dt_lim), text, flags=re.M)
    if steps:
        text = re.sub(r"^/YD/YDC/MCSTEP .*$", "/YD/YDC/MCSTEP %d" % steps, text, flags=re.M)
    return text


def trial(args, name, factor, dt_lim=None):
    """Run scene `name` at F = factor: (stable, dt_lim, dt, residual/given, message)."""
    kind, src, steps, extra, _ = SCENES[name]
    with tempfile.TemporaryDirectory() as tmp:
        summ = os.path.join(tmp, "s.json")
        if kind in ("native", "inline"):
            if kind == "native":
                text = open(os.path.join(ROOT, src)).read()
                for inc in ("meshes",):
                    if os.path.isdir(os.path.join(ROOT, "decks", inc)):
                        os.symlink(os.path.join(ROOT, "decks", inc), os.path.join(tmp, inc))
            else:
                text = src
            with open(os.path.join(tmp, "d.deck"), "w") as f:
                f.write(native_deck(text, factor))
            cmd = [args.yfdem, "-in", "d.deck", "-summary", summ]
            for i in range(0, len(extra), 2):
                cmd += ["-var", extra[i], extra[i + 1]]
        else:
            if kind == "gen":
                text = subprocess.run([sys.executable, os.path.join(HERE, "gen_joint_release.py"), src, "1.0"],
                                      capture_output=True, text=True, check=True).stdout
            else:
                text = open(os.path.join(args.y2d, src)).read()
            if dt_lim is None:  # one step to read the limit
                with open(os.path.join(tmp, "d.y"), "w") as f:
                    f.write(y2d_deck(text, 1e-12, 1.0, 1))
                run([args.yfdem, "d.y", "-summary", summ], tmp)
                dt_lim = json.load(open(summ))["dt_limit"]
            with open(os.path.join(tmp, "d.y"), "w") as f:
                f.write(y2d_deck(text, factor, dt_lim, steps))
            cmd = [args.yfdem, "d.y", "-summary", summ]
        code, out, err = run(cmd, tmp)
        try:
            s = json.load(open(summ))
        except (OSError, ValueError):
            return False, dt_lim, None, None, "no summary: exit %d %s" % (code, err[-300:])
        lim = s.get("dt_limit", dt_lim)
        m = re.search(r"energy balance not closed: ([-0-9.e+]+) J/m appeared.*?given ([-0-9.e+]+) J/m", err)
        resid = float(m.group(1)) / max(float(m.group(2)), 1e-300) if m else None
        bad = code != 0 or "energy balance not closed" in err
        msg = err.strip().splitlines()[-1][:160] if bad and err.strip() else ""
        return not bad, lim, s.get("dt"), resid, msg


def study(args, name):
    ok1, lim, _, r1, _ = trial(args, name, 1.0)
    verdict = {1.0: (ok1, r1)}
    lo = hi = None
    f = 1.0
    if ok1:
        lo = 1.0
        while hi is None and f < 8:
            f *= 1.25
            ok, _, _, r, _ = trial(args, name, f, lim)
            verdict[f] = (ok, r)
            if ok: lo = f
            else: hi = f
    else:
        hi = 1.0
        while lo is None and f > 0.05:
            f *= 0.8
            ok, _, _, r, _ = trial(args, name, f, lim)
            verdict[f] = (ok, r)
            if ok: lo = f
            else: hi = f
    for _ in range(4 if lo and hi else 0):
        mid = 0.5 * (lo + hi)
        ok, _, _, r, _ = trial(args, name, mid, lim)
        verdict[mid] = (ok, r)
        if ok: lo = mid
        else: hi = mid
    return name, lim, lo, hi, verdict


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--yfdem", default=os.path.join(ROOT, "yfdem"))
    ap.add_argument("--y2d", default=os.path.join(ROOT, "..", "..", "shared", "y2d", "decks"))
    ap.add_argument("--scenes", default=",".join(SCENES))
    ap.add_argument("-j", type=int, default=2)
    args = ap.parse_args()
    args.yfdem = os.path.abspath(args.yfdem)
    if not os.path.isdir(args.y2d):
        args.y2d = "/work/shared/y2d/decks"
    names = args.scenes.split(",")
    with concurrent.futures.ThreadPoolExecutor(args.j) as ex:
        res = list(ex.map(lambda n: study(args, n), names))
    print("| scene | what it has | printed limit dt_lim [s] | largest stable dt_max [s] | dt_max / dt_lim | "
          "first unstable F: residual / given |")
    print("|---|---|---|---|---|---|")
    for name, lim, lo, hi, verdict in res:
        r = verdict.get(hi, (None, None))[1] if hi else None
        print("| %s | %s | %.4g | %s | %s | %s |" % (
            name, SCENES[name][4], lim, "%.4g" % (lo * lim) if lo else "< %.3g" % (0.05 * lim),
            ("%.2f-%.2f" % (lo, hi) if hi else "> %.2f" % lo) if lo else "< 0.05",
            ("F %.2f: %.3g" % (hi, r) if r is not None else "F %.2f: stopped" % hi) if hi else "-"))
        sys.stdout.flush()


if __name__ == "__main__":
    main()
