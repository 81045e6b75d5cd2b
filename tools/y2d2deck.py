#!/usr/bin/env python3
"""Convert a Y2D input deck (.y) into an equivalent, readable yfdem deck.

usage: y2d2deck.py DECK.y OUT [--body-per-component]
  writes OUT.deck plus, per body B, OUT_B.nodes (rows "id x y") and OUT_B.tris (rows
  "id n1 n2 n3 material"); ids are the Y2D node and element indices (0-based), so results can be
  compared with Y2D outputs by id.  A node shared by two bodies is written once per body; the
  second copy gets a new id (NNOPO + k), listed in a comment.

What is translated (assumed native syntax = the SYNTAX dict below, one place to adapt):
  DCSTEC                     -> timestep DT
  MCSTEP - NCSTEP            -> run N
  ICSHTF / ICOUTF            -> thermo N / dump ID h5 N FILE
  DCGRAY                     -> gravity 0 G  (note: Y2D applies gravity to BC kinds 1 and 2 only)
  /YD/YDPE/ property p       -> material p<p> elastic rho R lambda L mu M visc K volfac 0.5
                                pen_n PE pen_t PT friction FR  (Y2D's law uses lambda/2: volfac 0.5)
  bodies                     -> one body per /YD/YDPM/ meshing row (its properties, jointed) and one
                                body "solid" for the triangles of properties not meshed
                                (--body-per-component: one body per connected piece instead)
  D2NVC                      -> velocity GROUP set VX VY, one group per distinct initial velocity
  BC sets (/YD/YDPN/, global frame only):
    kind 3 (velocity) amp 0 in x and y        -> fix ID GROUP fixed xy   (x or y alone likewise)
    kind 3 amp v                              -> fix ID GROUP velocity VX|NULL VY|NULL [history H]
    kind 1 (force) amp F != 0                 -> load ID point node N FX FY [history H] per node
    D1PNAP (edge pressure) != 0               -> load ID GROUP pressure P [history H]
    kind 1 amp 0                              -> nothing (free)
  D3PNFAC time table of set s  -> history bc<s> table T1 V1 T2 V2 ...
  joints (meshing code 3)      -> fracture ... (see SYNTAX['fracture']; written as a comment while
                                  the native command is not final)
Not translated (listed as comments in OUT.deck): BC sets with a rotated local frame, kind 2
(acceleration) conditions, frozen directions (kind not 1/2/3) with non-zero initial velocity,
D1PNAT edge shear, refinement codes 1/2/4, rigid (type 2) and softening (type 4) triangles,
history output /YD/YDO/, IWFAST boundary flags, DCSIZ scales.  Differences of semantics the
converted deck keeps as notes: Y2D time factors are 1.0 outside a table's time range (native
histories hold their end values); Y2D's edge pressure acts on edges whose two nodes are in sets
with non-zero D1PNAP.

The .y file is parsed here with the Y2D token rules (comments, $YINCL relative to the working
directory or the deck's directory, 1D/2D/3D array codes); run `yfdem` on the .y file itself (the
C reader, src/y2d/y2d_read.c) for full validation with FILE:LINE messages.
"""
import argparse
import os
import sys

# ---------------------------------------------------------------------------------------------
# Native deck syntax (being finalised by the lead): edit here only.  None = not available, the
# converter writes a comment instead.  Entries with a leading '#' are written commented out.
SYNTAX = {
    'header':    '# converted from {src} by tools/y2d2deck.py',
    'nodes':     'nodes {file} {body}',
    'triangles': 'triangles {file} {body}',
    'material':  'material {name} elastic rho {rho!r} lambda {lam!r} mu {mu!r} visc {visc!r} '
                 'volfac 0.5 pen_n {pen_n!r} pen_t {pen_t!r} friction {fric!r}',
    'timestep':  'timestep {dt!r}',
    'gravity':   'gravity 0 {gy!r}',
    'group_ids': 'group {name} node id {ids}',
    'velocity':  'velocity {group} set {vx!r} {vy!r}',
    'fix_fixed': 'fix {id} {group} fixed {dirs}',
    'fix_vel':   'fix {id} {group} velocity {vx} {vy}{hist}',
    'load_point': 'load {id} point node {node} {fx!r} {fy!r}{hist}',
    'load_pressure': 'load {id} {group} pressure {p!r}{hist}',
    'history':   'history {name} table {pairs}',
    'hist_opt':  ' history {name}',
    'fracture':  '# fracture {body} {mat_i} {mat_j} ft {ft!r} fs {fs!r} gf {gf!r} pen {pen!r} '
                 'cohesion {co!r} friction {fr!r}',
    'contact':   '# contact buffer {buffer!r}',
    'thermo':    'thermo {n}',
    'dump':      'dump d1 h5 {n} {file}',
    'run':       'run {n}',
    'continue':  ' &',     # line continuation of the native deck
}
LINE_MAX = 100
# ---------------------------------------------------------------------------------------------


class DeckError(Exception):
    pass


def tokens(path, depth=0):
    """(token, file, line) with comments removed and $YINCL expanded (Y2D rules)."""
    if depth >= 10:
        raise DeckError('%s: $YINCL nested deeper than 9' % path)
    out = []
    with open(path) as f:
        raw = [(t, ln) for ln, line in enumerate(f, 1) for t in line.split()]
    i = 0
    while i < len(raw):
        t, ln = raw[i]
        if t.startswith('/*'):
            i += 1
            while i < len(raw) and not raw[i][0].startswith('*/'):
                i += 1
            if i >= len(raw):
                raise DeckError('%s:%d: unterminated comment' % (path, ln))
        elif t == '$YINCL':
            if i + 1 >= len(raw):
                raise DeckError('%s:%d: $YINCL without a file name' % (path, ln))
            name = raw[i + 1][0]
            cand = name if os.path.exists(name) else os.path.join(os.path.dirname(path), name)
            out += tokens(cand, depth + 1)
            i += 1
        elif t in ('$YDOIT', '$YSTOP'):
            break
        else:
            out.append((t, path, ln))
        i += 1
    return out


def parse(path):
    """dict NAME -> value (scalars) or (dims, flat list in C order [d1][d2][d3])."""
    toks = tokens(path)
    keys, i = {}, 0

    def num(j):
        if j >= len(toks):
            raise DeckError('%s: unexpected end of the deck' % path)
        t, f, ln = toks[j]
        try:
            return float(t) if any(c in t for c in '.eE') else int(t)
        except ValueError:
            raise DeckError('%s:%d: %r is not a number' % (f, ln, t))

    while i < len(toks):
        t, f, ln = toks[i]
        if not t.startswith('/YD/'):
            raise DeckError('%s:%d: unexpected token %r' % (f, ln, t))
        name = t.split('/')[3] if t.count('/') >= 3 else ''
        grp = t.split('/')[2]
        full = grp + '/' + name
        if len(name) >= 2 and name[1] in '123' and name[0] in 'DI':
            nd = int(name[1])
            if nd == 1:
                n = num(i + 1)
                vals = [num(i + 2 + k) for k in range(n)]
                keys[full] = ((n,), vals)
                i += 2 + n
                continue
            code = str(num(i + 1))
            dims = [num(i + 2 + d) for d in range(nd)]
            tot = 1
            for d in dims:
                tot *= d
            flat = [num(i + 2 + nd + k) for k in range(tot)]
            order = [0, 1] if (nd == 2 and code == '12') else [1, 0] if nd == 2 else \
                [int(c) - 1 for c in code]
            arr = [0] * tot
            strides = [1] * nd
            for d in range(nd - 2, -1, -1):
                strides[d] = strides[d + 1] * dims[d + 1]
            for m, v in enumerate(flat):
                rem, idx = m, [0] * nd
                for q in range(nd - 1, -1, -1):
                    d = order[q]
                    idx[d] = rem % dims[d]
                    rem //= dims[d]
                arr[sum(idx[d] * strides[d] for d in range(nd))] = v
            keys[full] = (tuple(dims), arr)
            i += 2 + nd + tot
        else:
            keys[full] = num(i + 1)
            i += 2
    return keys


def arr1(K, key, n, default):
    dims, vals = K.get(key, ((0,), []))
    return [vals[k] if k < len(vals) else default for k in range(n)]


def get2(K, key):
    """2D array as rows over dimension 2: list of lists (dim-1 values)."""
    (n1, n2), flat = K[key]
    return [[flat[a * n2 + b] for a in range(n1)] for b in range(n2)]


def wrap(head, items):
    """head + items, split with the native continuation over lines of LINE_MAX characters."""
    lines, cur = [], head
    for it in items:
        if len(cur) + 1 + len(it) > LINE_MAX:
            lines.append(cur + SYNTAX['continue'])
            cur = '   ' + it
        else:
            cur += ' ' + it
    lines.append(cur)
    return '\n'.join(lines)


def convert(src, out, per_component=False):
    K = parse(src)
    g = lambda k, d=0: K.get(k, d)
    ne, nn, nprop = g('YDE/NELEM'), g('YDN/NNOPO'), g('YDPE/NPROP')
    elto = get2(K, 'YDE/I2ELTO')
    elpr = arr1(K, 'YDE/I1ELPR', ne, -1)
    xy = get2(K, 'YDN/D2NCI')
    vel = get2(K, 'YDN/D2NVC') if 'YDN/D2NVC' in K else [[0.0, 0.0]] * nn
    vel = [vel[n] if n < len(vel) else [0.0, 0.0] for n in range(nn)]
    notes, L = [], [SYNTAX['header'].format(src=src), '']

    # ---- materials
    pe = lambda name, d: arr1(K, 'YDPE/' + name, nprop, d)
    ptyp, rho, lam, mu = pe('I1PTYP', -1), pe('D1PERO', 0), pe('D1PELA', 0), pe('D1PEMU', 0)
    ks, pen_n, pen_t, fric = pe('D1PEKS', 0), pe('D1PEPE', 0), pe('D1PEPT', 0), pe('D1PEFR', 0)
    L.append('# materials: Y2D element properties (Lame constants as given)')
    for p in range(nprop):
        if ptyp[p] != 1:
            notes.append('property %d has type %d (%s): written as elastic' %
                         (p, ptyp[p], {2: 'rigid', 4: 'softening'}.get(ptyp[p], '?')))
        L.append(SYNTAX['material'].format(name='p%d' % p, rho=float(rho[p]), lam=float(lam[p]),
                                           mu=float(mu[p]), visc=float(ks[p]), pen_n=float(pen_n[p]),
                                           pen_t=float(pen_t[p]), fric=float(fric[p])))
    L.append('')

    # ---- bodies
    body_of_prop = {}
    rows = get2(K, 'YDPM/I2PMSET') if 'YDPM/I2PMSET' in K else []
    codes = {}
    for r, row in enumerate(rows):
        k, code = row[0], row[1]
        for p in row[2:2 + k]:
            body_of_prop[p] = 'b%d' % r
        codes['b%d' % r] = code
        if any(c in str(code) for c in '124'):
            notes.append('meshing row %d: code %d has refinement/detach digits (1, 2, 4) that are '
                         'not translated' % (r, code))
    tri_body = [body_of_prop.get(elpr[e], 'solid') for e in range(ne)]
    if per_component:   # split 'solid' into connected pieces (shared nodes)
        parent = list(range(nn))

        def find(a):
            while parent[a] != a:
                parent[a] = parent[parent[a]]
                a = parent[a]
            return a
        for e in range(ne):
            if tri_body[e] == 'solid':
                for k in (1, 2):
                    parent[find(elto[e][0])] = find(elto[e][k])
        comp = {}
        for e in range(ne):
            if tri_body[e] == 'solid':
                tri_body[e] = comp.setdefault(find(elto[e][0]), 'solid%d' % len(comp))
    bodies = sorted(set(tri_body), key=lambda b: min(e for e in range(ne) if tri_body[e] == b))
    owner, dup, next_id = {}, {}, nn
    ids_of_node = {n: [] for n in range(nn)}
    base = os.path.basename(out)
    L.append('# mesh: one body per Y2D meshing row (jointed) or unjointed piece; ids = Y2D indices')
    for b in bodies:
        tris = [e for e in range(ne) if tri_body[e] == b]
        nodes = sorted({n for e in tris for n in elto[e][:3]})
        idmap = {}
        for n in nodes:
            if n not in owner:
                owner[n] = b
                idmap[n] = n
            else:
                idmap[n] = next_id
                dup[next_id] = n
                next_id += 1
            ids_of_node[n].append(idmap[n])
        with open('%s_%s.nodes' % (out, b), 'w') as f:
            for n in nodes:
                f.write('%d %r %r\n' % (idmap[n], float(xy[n][0]), float(xy[n][1])))
        with open('%s_%s.tris' % (out, b), 'w') as f:
            for e in tris:
                v = elto[e]
                f.write('%d %d %d %d p%d\n' % (e, idmap[v[0]], idmap[v[1]], idmap[v[2]], elpr[e]))
        L.append(SYNTAX['nodes'].format(file='%s_%s.nodes' % (base, b), body=b))
        L.append(SYNTAX['triangles'].format(file='%s_%s.tris' % (base, b), body=b))
    if dup:
        L.append('# nodes shared by two bodies, written again with a new id: ' +
                 ' '.join('%d=%d' % (i, n) for i, n in sorted(dup.items())))
    unused = [n for n in range(nn) if not ids_of_node[n]]
    if unused:
        notes.append('%d node(s) used by no triangle were dropped (first: %d)' % (len(unused), unused[0]))
    L.append('')

    # ---- joints
    if 'YDPJ/NPJSET' in K and rows:
        npj = g('YDPJ/NPJSET')
        pj = lambda name: arr1(K, 'YDPJ/' + name, npj, 0.0)
        ft, fs, gf, pen, co, fr = (pj(n) for n in ('D1PJFT', 'D1PJFS', 'D1PJGF', 'D1PJPE', 'D1PJCO', 'D1PJFR'))
        L.append('# joints (Y2D meshing code 3): cohesive joints on every edge between triangles of a body')
        for m in get2(K, 'YDPM/I2PMIJ'):
            pi, pjj, s = m
            b = body_of_prop.get(pi)
            if b is None or '3' not in str(codes.get(b, '')):
                continue
            L.append(SYNTAX['fracture'].format(body=b, mat_i='p%d' % pi, mat_j='p%d' % pjj,
                                               ft=float(ft[s]), fs=float(fs[s]), gf=float(gf[s]),
                                               pen=float(pen[s]), co=float(co[s]), fr=float(fr[s])))
        L.append('')

    # ---- contact
    if g('YDI/MICOUP') > 0:
        L.append(SYNTAX['contact'].format(buffer=float(g('YDI/DIEZON', 0.0))))
        if g('YDC/IWFAST', 1) > 0:
            notes.append('IWFAST > 0: Y2D lets only triangles with a flagged node (I1NOBF) take part '
                         'in contact; not translated')
        L.append('')

    # ---- initial velocities
    groups_v = {}
    for n in range(nn):
        v = (float(vel[n][0]), float(vel[n][1]))
        if v != (0.0, 0.0) and ids_of_node[n]:
            groups_v.setdefault(v, []).extend(ids_of_node[n])
    if groups_v:
        L.append('# initial velocities (D2NVC)')
        for k, (v, ids) in enumerate(sorted(groups_v.items(), key=lambda kv: min(kv[1]))):
            L.append(wrap(SYNTAX['group_ids'].format(name='v%d' % k, ids='').rstrip(), [str(i) for i in ids]))
            L.append(SYNTAX['velocity'].format(group='v%d' % k, vx=v[0], vy=v[1]))
        L.append('')

    # ---- gravity and BC sets
    if float(g('YDC/DCGRAY', 0.0)) != 0.0:
        L.append(SYNTAX['gravity'].format(gy=float(g('YDC/DCGRAY'))))
        notes.append('gravity: Y2D applies it to nodes of BC kinds 1 and 2 only')
    nset = g('YDPN/NPNSET')
    pn = lambda name, d: arr1(K, 'YDPN/' + name, nset, d)
    fx, fy, ax, ay = pn('I1PNFX', -1), pn('I1PNFY', -1), pn('D1PNAX', 1.0), pn('D1PNAY', 1.0)
    ap, at = pn('D1PNAP', 0.0), pn('D1PNAT', 0.0)
    xx, xy_, yx, yy = pn('D1PNXX', 1.0), pn('D1PNXY', 0.0), pn('D1PNYX', 0.0), pn('D1PNYY', 1.0)
    nopr = arr1(K, 'YDN/I1NOPR', nn, -1)
    npts = g('YDPN/NPNFACT', 0)
    tables = {}
    if 'YDPN/D3PNFAC' in K and npts > 0:
        (d1, d2, d3), flat = K['YDPN/D3PNFAC']
        if flat and flat[0] != -1:
            for s in range(min(d2, nset)):
                tables[s] = [(flat[(0 * d2 + s) * d3 + p], flat[(1 * d2 + s) * d3 + p]) for p in range(npts)]
    L.append('# boundary conditions: one group per Y2D BC set (node ids)')
    for s in range(nset):
        ids = [i for n in range(nn) if nopr[n] == s for i in ids_of_node[n]]
        nodes_s = [n for n in range(nn) if nopr[n] == s and ids_of_node[n]]
        if not ids:
            continue
        gname = 'bc%d' % s
        hist = ''
        if s in tables:
            tab = tables[s]
            if any(v != 1.0 for t, v in tab):
                L.append(SYNTAX['history'].format(name=gname, pairs=' '.join('%r %r' % (float(t), float(v)) for t, v in tab)))
                hist = SYNTAX['hist_opt'].format(name=gname)
                t_end = float(g('YDC/DCTIME', 0.0)) + (int(g('YDC/MCSTEP', 0)) - int(g('YDC/NCSTEP', 0))) * float(g('YDC/DCSTEC', 0.0))
                if float(tab[-1][1]) != 1.0 and float(tab[-1][0]) < t_end:
                    notes.append('BC set %d: after its table ends (t = %g) Y2D uses the factor 1.0, the '
                                 'native history holds %g' % (s, tab[-1][0], tab[-1][1]))
        L.append(wrap(SYNTAX['group_ids'].format(name=gname, ids='').rstrip(), [str(i) for i in ids]))
        if (xx[s], xy_[s], yx[s], yy[s]) != (1, 0, 0, 1) and (xx[s], xy_[s], yx[s], yy[s]) != (1.0, 0.0, 0.0, 1.0):
            L.append('# NOT TRANSLATED: BC set %d uses the local frame x = (%g, %g), y = (%g, %g): kinds %d/%d, '
                     'amplitudes %g/%g' % (s, xx[s], xy_[s], yx[s], yy[s], fx[s], fy[s], ax[s], ay[s]))
            continue
        kinds, amps = (fx[s], fy[s]), (ax[s], ay[s])
        fixed = ''.join(d for d, k, a in zip('xy', kinds, amps) if k == 3 and a == 0 and not hist)
        for d, k in zip((0, 1), kinds):
            if k not in (1, 2, 3):
                if all(float(vel[n][d]) == 0.0 for n in nodes_s):
                    fixed += 'xy'[d]
                else:
                    L.append('# NOT TRANSLATED: BC set %d: %s kind %d freezes the initial velocity' % (s, 'xy'[d], k))
            if k == 2:
                L.append('# NOT TRANSLATED: BC set %d: %s kind 2 (acceleration %g)' % (s, 'xy'[d], amps[d]))
        fixed = ''.join(sorted(set(fixed)))
        if fixed:
            L.append(SYNTAX['fix_fixed'].format(id='%s_fix' % gname, group=gname, dirs=fixed))
        vparts = [('%r' % float(a)) if (k == 3 and (a != 0 or hist)) else 'NULL' for k, a in zip(kinds, amps)]
        if vparts != ['NULL', 'NULL']:
            L.append(SYNTAX['fix_vel'].format(id='%s_vel' % gname, group=gname, vx=vparts[0], vy=vparts[1], hist=hist))
        fpart = [float(a) if k == 1 else 0.0 for k, a in zip(kinds, amps)]
        if fpart != [0.0, 0.0]:
            for n in nodes_s:
                L.append(SYNTAX['load_point'].format(id='%s_f%d' % (gname, n), node=ids_of_node[n][0],
                                                     fx=fpart[0], fy=fpart[1], hist=hist))
        if float(ap[s]) != 0.0:
            L.append(SYNTAX['load_pressure'].format(id='%s_p' % gname, group=gname, p=float(ap[s]), hist=hist))
            notes.append('BC set %d: Y2D pressure acts on edges whose two nodes have non-zero D1PNAP, '
                         'positive into the body; check the native sign convention' % s)
        if float(at[s]) != 0.0:
            L.append('# NOT TRANSLATED: BC set %d: edge shear traction D1PNAT = %g' % (s, at[s]))
    L.append('')

    # ---- run control
    dt = float(g('YDC/DCSTEC', 0.0))
    nsteps = int(g('YDC/MCSTEP', 0)) - int(g('YDC/NCSTEP', 0))
    L.append(SYNTAX['timestep'].format(dt=dt))
    L.append(SYNTAX['thermo'].format(n=int(g('YDC/ICSHTF', 100))))
    icoutf = int(g('YDC/ICOUTF', 10))
    if 0 < icoutf <= nsteps:
        L.append(SYNTAX['dump'].format(n=icoutf, file=base + '.h5'))
    L.append(SYNTAX['run'].format(n=max(nsteps, 0)))
    if 'YDO/NOHYS' in K:
        notes.append('history output /YD/YDO/ not translated')
    head = ['# NOTES (not translated or different semantics):'] + ['#   ' + n for n in notes]
    with open(out + '.deck', 'w') as f:
        f.write('\n'.join(L[:1] + head + L[1:]) + '\n')
    return out + '.deck', len(bodies), notes


def main():
    ap = argparse.ArgumentParser(description='Y2D .y deck -> yfdem deck (see the docstring)')
    ap.add_argument('deck')
    ap.add_argument('out', help='output base name: OUT.deck, OUT_<body>.nodes/.tris')
    ap.add_argument('--body-per-component', action='store_true')
    a = ap.parse_args()
    try:
        path, nb, notes = convert(a.deck, a.out, a.body_per_component)
    except (DeckError, OSError, KeyError, IndexError, ValueError) as e:
        sys.stderr.write('error: %s: %s\n' % (a.deck, e if not isinstance(e, KeyError) else
                                              'required key %s missing' % e))
        sys.exit(1)
    print('wrote %s (%d bodies, %d notes)' % (path, nb, len(notes)))


if __name__ == '__main__':
    main()
