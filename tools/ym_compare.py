#!/usr/bin/env python3
"""ym_compare.py: compare Y2D's own output of a .y deck (its coded .ym files) with yfdem's run of the
same deck: is what yfdem computes what Y2D computes?  (Issue 21, question 1.)

    tools/ym_compare.py DECK.y Y2D_OUT/*.ym [--run DIR | --yfdem PATH --workdir DIR] [--offset K]
                        [--du TOL] [--dv TOL] [--quanta Q]

What Y2D writes (shared/y2d/FORMAT.md 7.2): every ICOUTF steps (and at step 0) a file
<deck><index>.ym, first line CODED, then one record per element in element order: triangles
(positions of the 3 corners, mean velocity, stress, damage), broken joints (the 4 node positions)
and intact joints whose mean opening exceeds 10 % of the softening length.  Values are divided by
the deck's DCSIZC (coordinates), DCSIZV (velocities), DCSIZS (stresses), clipped to [-1, 1] and
coded with ICOUTP = d digits in base 90: a decoded value lies within one quantum
Q = 2 scale / (90^d - 1) (3e-8 of the scale for d = 4) of the true one.  `write_y2d` sets the scales
so that nothing clips (docs/y2d_decks.md); decks with the default scales (1) clip every velocity
above 1 m/s and every stress above 1 Pa (reported as saturated, and left out).

What it is compared with: yfdem's `dump ID y2dref DIR corners S1,S2,...` of `read_y2d DECK.y`
(elements, corners and nodes by the deck's own indices; README "Running Y2D decks").  Without --run
the tool makes that run itself (yfdem from --yfdem, default ./yfdem, in --workdir, default a
temporary directory) at the steps of the given .ym files.  File index i holds the state after
S = (i - ICOUTI) ICOUTF completed steps (positions x_S, velocities v_{S-1/2}: the output comes
after the force evaluation of the loop's iteration S, ALGORITHMS.md 1; --offset K adds K to S):

  * triangles: the first NELEM records are the deck's triangles 0..NELEM-1 (joints are appended
    after them, FORMAT.md 5.2); corner c's position against the node's D2NCI + (ux, uy) of yfdem's
    corners table; the mean velocity against the mean of the 3 corners' (vx, vy).  Deviations are
    printed relative to the largest |displacement| (|mean velocity|) at that step, and the check is
    |difference| <= Q_quanta x Q + TOL x that largest value (--quanta, default 2; --du default 1e-6,
    --dv default 1e-5: README of shared/y2d 4.2, with room for the quantisation).
  * broken joints: Y2D's broken-joint records against yfdem's broken.csv rows with step <= S + 1
    (the iteration that writes the file has already evaluated the joints of yfdem's step S + 1, which
    uses positions x_S); each matched by the midpoint of its 4 nodes to the midpoint of the shared
    edge of elemA and elemB in yfdem's corners table (within 10 Q + 1e-3 of the smallest edge).
    Records whose node pairs coincide exactly (node 3 = node 0, node 2 = node 1: how Y2D neutralises
    the joints of outer boundary edges, ALGORITHMS.md 4.1) are left out and counted, in case a build
    writes those with the broken ones.
  * stresses are not compared: the book's output routine re-evaluates them with its own volumetric
    factor (ALGORITHMS.md 2.3); intact opened joints are counted only.

Exit status 0 when every file agrees, 1 otherwise (2 on a usage or input error).  Standard library
only; the deck is read with tools/y2d2deck.py's parser and the .ym files with tools/y2d_coded.py.
"""
import argparse
import csv
import math
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import y2d2deck  # noqa: E402
import y2d_coded  # noqa: E402


class CompareError(Exception):
    pass


def deck_info(path):
    K = y2d2deck.parse(path)
    nelem = int(K.get('YDE/NELEM', 0))
    tops = y2d2deck.get2(K, 'YDE/I2ELTO')[:nelem]
    xy = y2d2deck.get2(K, 'YDN/D2NCI')
    hmin = math.inf
    for t in tops:
        for c in range(3):
            a, b = xy[t[c]], xy[t[(c + 1) % 3]]
            hmin = min(hmin, math.hypot(b[0] - a[0], b[1] - a[1]))
    icoutf = int(K.get('YDC/ICOUTF', 10))
    return {
        'nelem': nelem, 'tops': tops, 'xy': xy, 'hmin': hmin,
        'icoutf': icoutf if icoutf > 0 else 10,       # Y2D's rule for ICOUTF <= 0
        'icouti': int(K.get('YDC/ICOUTI', 0)),
        'icoutp': int(K.get('YDC/ICOUTP', 4)),
        'mcstep': int(K.get('YDC/MCSTEP', 0)),
        'sc': {'c': float(K.get('YDC/DCSIZC', 1.0)), 'v': float(K.get('YDC/DCSIZV', 1.0)),
               's': float(K.get('YDC/DCSIZS', 1.0))},
    }


def run_yfdem(yfdem, deck, steps, workdir):
    """read_y2d DECK with a y2dref dump at the given steps; returns the dump directory."""
    out = os.path.join(workdir, 'yfdem_y2dref')
    last = max(steps)
    text = ('read_y2d %s\ndump ref y2dref %s corners %s\nrun %d\n'
            % (os.path.abspath(deck), out, ','.join(str(s) for s in sorted(set(steps))), max(last, 1)))
    dk = os.path.join(workdir, 'ym_compare.deck')
    with open(dk, 'w') as f:
        f.write(text)
    print('ym_compare: running %s -in %s (read_y2d %s, %d steps, corner tables at %d steps)'
          % (yfdem, dk, deck, max(last, 1), len(set(steps))))
    r = subprocess.run([yfdem, '-in', dk], cwd=workdir, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                       universal_newlines=True)
    if r.returncode != 0:
        raise CompareError('yfdem failed (exit %d):\n%s' % (r.returncode, r.stdout[-2000:]))
    return out


def read_corners(path):
    """{(elem, corner): (node, ux, uy, vx, vy)}"""
    out = {}
    with open(path, newline='') as f:
        for r in csv.DictReader(f):
            out[(int(r['elem']), int(r['corner']))] = (int(r['node']), float(r['ux']), float(r['uy']),
                                                       float(r['vx']), float(r['vy']))
    return out


def read_broken(path):
    if not os.path.exists(path):
        return []
    with open(path, newline='') as f:
        return [tuple(int(r[k]) for k in ('step', 'elemA', 'elemB', 'nodeP', 'nodeQ')) for r in csv.DictReader(f)]


def compare_file(ym, step, D, run, a):
    """Print the comparison of one .ym file with yfdem's state after `step` steps; True if it agrees."""
    d = D['icoutp']
    top = 90 ** d - 1
    sc = D['sc']
    qc, qv = 2.0 * sc['c'] / top, 2.0 * sc['v'] / top
    sat_lim = 1.0 - 2.0 / top
    rows = y2d_coded.read_ym(ym, sc)
    tris = [r for r in rows if r['kind'] == 'tri']
    bj_all = [r for r in rows if r['kind'] == 'broken_joint']
    # a record whose node pairs coincide exactly (slots 3 = 0 and 2 = 1) is not a crack: Y2D neutralises
    # the joints of outer boundary edges by pointing slots 2, 3 at slots 1, 0 (ALGORITHMS.md 4.1); in case
    # a build writes them with the broken ones, they are left out (and counted)
    def degenerate(r):
        return r['x0'] == r['x3'] and r['y0'] == r['y3'] and r['x1'] == r['x2'] and r['y1'] == r['y2']
    bj = [r for r in bj_all if not degenerate(r)]
    ndeg = len(bj_all) - len(bj)
    oj = [r for r in rows if r['kind'] == 'intact_joint']
    name = os.path.basename(ym)
    if len(tris) < D['nelem']:
        print('%s (step %d): %d triangle records, the deck has %d triangles FAIL' % (name, step, len(tris), D['nelem']))
        return False
    cpath = os.path.join(run, 'corners_%07d.csv' % step)
    if not os.path.exists(cpath):
        print('%s (step %d): yfdem has no %s (run with corner tables at this step) FAIL' % (name, step, cpath))
        return False
    C = read_corners(cpath)
    umax = vmax = 0.0
    du = dv = 0.0
    wu = wv = None
    sat = 0
    okc = True
    tol_u_abs = tol_v_abs = 0.0
    diffs = []
    for e in range(D['nelem']):
        r = tris[e]
        mvx = mvy = 0.0
        for c in range(3):
            if (e, c) not in C:
                raise CompareError('%s: no corner %d of element %d' % (cpath, c, e))
            node, ux, uy, vx, vy = C[(e, c)]
            if node != D['tops'][e][c]:
                raise CompareError('%s: element %d corner %d is node %d in yfdem, %d in the deck'
                                   % (cpath, e, c, node, D['tops'][e][c]))
            umax = max(umax, abs(ux), abs(uy))
            mvx += vx / 3.0
            mvy += vy / 3.0
            x0, y0 = D['xy'][node]
            for comp, ref, val in (('x', x0 + ux, r['x%d' % c]), ('y', y0 + uy, r['y%d' % c])):
                if abs(val) >= sat_lim * sc['c']:
                    sat += 1
                    continue
                diffs.append(('u', abs(val - ref), e, c))
        vmax = max(vmax, abs(mvx), abs(mvy))
        for ref, val in ((mvx, r['vx']), (mvy, r['vy'])):
            if abs(val) >= sat_lim * sc['v']:
                sat += 1
                continue
            diffs.append(('v', abs(val - ref), e, -1))
    tol_u_abs = a.quanta * qc + a.du * umax
    tol_v_abs = a.quanta * qv + a.dv * vmax
    for kind, dd, e, c in diffs:
        if kind == 'u' and dd > du:
            du, wu = dd, (e, c)
        if kind == 'v' and dd > dv:
            dv, wv = dd, e
    okc = du <= tol_u_abs and dv <= tol_v_abs
    print('%s (step %d): positions max |diff| %.3g m = %.3g of max|u| %.3g (quantum %.2g m, %s, tol %.3g m)%s'
          % (name, step, du, du / umax if umax else 0.0, umax, qc, 'at elem:corner %d:%d' % wu if wu else '-',
             tol_u_abs, '' if du <= tol_u_abs else ' FAIL'))
    print('%s (step %d): mean velocities max |diff| %.3g m/s = %.3g of max|v| %.3g (quantum %.2g m/s, %s, tol %.3g)%s'
          % (name, step, dv, dv / vmax if vmax else 0.0, vmax, qv, 'at elem %d' % wv if wv is not None else '-',
             tol_v_abs, '' if dv <= tol_v_abs else ' FAIL'))
    if sat:
        print('%s (step %d): %d values saturated at their DCSIZ scale (left out): raise DCSIZC/DCSIZV in the deck'
              % (name, step, sat))

    # broken joints
    B = read_broken(os.path.join(run, 'broken.csv'))
    upto_s = sum(1 for b in B if b[0] <= step)
    exp = [b for b in B if b[0] <= step + 1]

    def edge_mid(b):
        pts = []
        for e in (b[1], b[2]):
            for c in range(3):
                node, ux, uy, _, _ = C[(e, c)]
                if node in (b[3], b[4]):
                    x0, y0 = D['xy'][node]
                    pts.append((x0 + ux, y0 + uy))
        if len(pts) != 4:
            raise CompareError('broken joint %s: elements %d, %d do not share nodes %d, %d' % (b, b[1], b[2], b[3], b[4]))
        return (sum(p[0] for p in pts) / 4.0, sum(p[1] for p in pts) / 4.0)

    ym_mid = [(sum(r['x%d' % k] for k in range(4)) / 4.0, sum(r['y%d' % k] for k in range(4)) / 4.0) for r in bj]
    yf_mid = [edge_mid(b) for b in exp]
    tolj = 10.0 * qc + 1e-3 * D['hmin']
    used = [False] * len(ym_mid)
    only_yf = []
    for b, m in zip(exp, yf_mid):
        best, bi = math.inf, -1
        for i, p in enumerate(ym_mid):
            if not used[i]:
                dd = math.hypot(p[0] - m[0], p[1] - m[1])
                if dd < best:
                    best, bi = dd, i
        if bi >= 0 and best <= tolj:
            used[bi] = True
        else:
            only_yf.append((b, m))
    only_ym = [p for i, p in enumerate(ym_mid) if not used[i]]
    okb = not only_yf and not only_ym
    print('%s (step %d): broken joints: Y2D %d, yfdem %d (%d by step %d, %d by step %d), %d only in Y2D, %d only in '
          'yfdem; %d intact opened joints written by Y2D%s%s'
          % (name, step, len(bj), len(exp), upto_s, step, len(exp), step + 1, len(only_ym), len(only_yf), len(oj),
             '; %d records with coinciding node pairs (boundary joints) left out' % ndeg if ndeg else '',
             '' if okb else ' FAIL'))
    for b, m in only_yf[:5]:
        print('   only in yfdem: step %d elems %d %d nodes %d %d at (%.6g, %.6g)' % (b + m))
    for p in only_ym[:5]:
        print('   only in Y2D: broken joint at (%.6g, %.6g)' % p)
    return okc and okb


def main():
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0], epilog='see the module docstring')
    ap.add_argument('deck', help='the .y deck Y2D ran (e.g. beam.y from decks/beam.deck -var y2d 1)')
    ap.add_argument('ym', nargs='+', help="Y2D's coded output files <deck><index>.ym")
    ap.add_argument('--run', help="a directory with yfdem's y2dref dump of the deck (corners at the .ym steps, "
                    'broken.csv); default: make that run')
    ap.add_argument('--yfdem', default=os.environ.get('YFDEM', './yfdem'), help='yfdem binary (default $YFDEM or ./yfdem)')
    ap.add_argument('--workdir', help='where to make the run (default: a temporary directory, removed after)')
    ap.add_argument('--offset', type=int, default=0, help='add K to the step of every file (default 0)')
    ap.add_argument('--du', type=float, default=1e-6, help='position tolerance relative to max|u| (default 1e-6)')
    ap.add_argument('--dv', type=float, default=1e-5, help='velocity tolerance relative to max|v| (default 1e-5)')
    ap.add_argument('--quanta', type=float, default=2.0, help='allowance in coding quanta (default 2)')
    a = ap.parse_args()
    try:
        D = deck_info(a.deck)
        files = sorted(a.ym, key=y2d_coded.file_index)
        steps = [(y2d_coded.file_index(p) - D['icouti']) * D['icoutf'] + a.offset for p in files]
        if any(s < 0 for s in steps):
            raise CompareError('a file index below ICOUTI %d (or --offset) gives a negative step' % D['icouti'])
        print('ym_compare: %s: %d triangles, ICOUTF %d, ICOUTI %d, ICOUTP %d, DCSIZC %g, DCSIZV %g; %d files, steps %s'
              % (a.deck, D['nelem'], D['icoutf'], D['icouti'], D['icoutp'], D['sc']['c'], D['sc']['v'], len(files),
                 ', '.join(str(s) for s in steps[:8]) + (' ...' if len(steps) > 8 else '')))
        tmp = None
        run = a.run
        if not run:
            wd = a.workdir
            if not wd:
                wd = tmp = tempfile.mkdtemp(prefix='ym_compare_')
            os.makedirs(wd, exist_ok=True)
            run = run_yfdem(os.path.abspath(a.yfdem), a.deck, steps, wd)
        ok = True
        try:
            for p, s in zip(files, steps):
                ok &= compare_file(p, s, D, run, a)
        finally:
            if tmp:
                import shutil
                shutil.rmtree(tmp, ignore_errors=True)
    except (CompareError, y2d_coded.CodedError, y2d2deck.DeckError, OSError, KeyError, ValueError) as e:
        sys.stderr.write('ym_compare: error: %s\n' % e)
        return 2
    print('ym_compare: %s' % ('PASS: Y2D and yfdem agree on every file' if ok else 'FAIL'))
    return 0 if ok else 1


if __name__ == '__main__':
    sys.exit(main())
