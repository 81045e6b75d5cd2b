#!/usr/bin/env python3
"""Read Y2D's coded "space saving" animation files (.ym) and convert them to CSV or HDF5+XDMF.

The format (FORMAT.md 7.2 of the Y2D anchor notes): first line `CODED`, then one line per element
record.  Each record is a list of integers written in base 90 with the alphabet

    0123456789-=qwertyuiop[]^asdfghjkl;zxcvbnm,./~!@#$%&*()_+QWERTYUIOP{}|ASDFGHJKL:ZXCVBNM<>?

(digit value = position).  Character 1 = digits per value d (= ICOUTP), character 2 = record
length m (number of values including these two), then m-2 values of d characters each, least
significant digit first.  Value 3 is the element type code (an integer); the other values are
reals r in [-1, 1] stored as k = floor((r+1)/2 (90^d - 1)) and decoded as r = 2k/(90^d - 1) - 1,
then multiplied by their DCSIZ scale:

    m = 15 triangle:      x0 x1 x2 y0 y1 y2 (*DCSIZC), vx vy (*DCSIZV), sxx syy sxy (*DCSIZS), damage
    m = 12 broken joint:  x0..x3 y0..y3 (*DCSIZC), state
    m = 14 intact joint:  x0..x3 y0..y3 (*DCSIZC), 1, opening1/o_t, opening2/s_t  (written only when
                          the mean opening exceeds 10 % of the softening length)

The values were clipped to [-1, 1] after division by the scale, so a quantity beyond its scale
saturates at +-scale.  The resolution is 2/(90^d - 1) of the scale (3e-8 for d = 4).

usage:
  y2d_coded.py csv  FILE.ym... [-o OUTDIR] [--deck DECK.y | --sizc C --sizv V --sizs S]
      one CSV per .ym (OUTDIR/<name>.csv), one row per record:
      record,kind,type,x0,x1,x2,x3,y0,y1,y2,y3,vx,vy,sxx,syy,sxy,damage,state,flag,open1,open2
      (kind = tri | broken_joint | intact_joint | other; empty cells where not applicable;
      triangles leave x3, y3 empty).  Standard library only.
  y2d_coded.py hdf5 FILE.ym... -o OUT [--deck DECK.y | scales] [--joints quads|lines] [--dt T]
      OUT.h5 + OUT.xdmf (XDMF 3, a temporal collection, one step per .ym in the order of the index
      in the file name <deck><index>.ym): per step a grid "triangles" (cell data sxx, syy, sxy,
      damage, velocity) and a grid "joints" (intact and broken joints, cell data broken, state,
      open1, open2) drawn as quadrilaterals (nodes 0,1,2,3) or as their mid-lines (--joints lines:
      from the middle of nodes 3-0 to the middle of nodes 1-2).  Step time = index * T (--dt,
      default 1: the index).  Needs numpy and h5py (tools/install-deps --python).  Open OUT.xdmf
      in ParaView (Xdmf3 reader).
  y2d_coded.py --selftest
      checks the decoder on FORMAT.md's worked example (`2510/{{l` -> 1, 0.49994, -0.25003) and an
      encode/decode round trip, then exits 0 (or 1 on failure).

Scales: --deck reads DCSIZC, DCSIZV, DCSIZS from a .y deck (default 1 when not given, as Y2D);
explicit --sizc/--sizv/--sizs override the deck.
"""
import argparse
import csv
import math
import os
import re
import sys

ALPHABET = ("0123456789-=qwertyuiop[]^asdfghjkl;zxcvbnm,./~!@#$%&*()_+"
            "QWERTYUIOP{}|ASDFGHJKL:ZXCVBNM<>?")
DIGIT = {c: i for i, c in enumerate(ALPHABET)}
BASE = 90

KIND_BY_LEN = {15: 'tri', 12: 'broken_joint', 14: 'intact_joint'}
CSV_COLS = ['record', 'kind', 'type', 'x0', 'x1', 'x2', 'x3', 'y0', 'y1', 'y2', 'y3', 'vx', 'vy',
            'sxx', 'syy', 'sxy', 'damage', 'state', 'flag', 'open1', 'open2']


class CodedError(Exception):
    pass


def decode_ints(line):
    """Integers of one coded line: [type, k1, k2, ...] and d (digits per value)."""
    line = line.strip()
    if len(line) < 2:
        raise CodedError('record shorter than 2 characters')
    try:
        d = DIGIT[line[0]]
        m = DIGIT[line[1]]
        vals = []
        for i in range(m - 2):
            chunk = line[2 + i * d: 2 + (i + 1) * d]
            if len(chunk) != d:
                raise CodedError('record of %d values (m = %d, d = %d) needs %d characters, has %d'
                                 % (m - 2, m, d, 2 + (m - 2) * d, len(line)))
            k = 0
            for j, c in enumerate(chunk):     # least significant digit first
                k += DIGIT[c] * BASE ** j
            vals.append(k)
    except KeyError as e:
        raise CodedError('character %s is not in the base-90 alphabet' % e)
    if d <= 0:
        raise CodedError('digits per value d = 0')
    if len(line) != 2 + (m - 2) * d:
        raise CodedError('record has %d characters, expected %d (m = %d, d = %d)'
                         % (len(line), 2 + (m - 2) * d, m, d))
    return vals, d, m


def decode_record(line):
    """(m, type, reals in [-1, 1]) of one coded line."""
    vals, d, m = decode_ints(line)
    top = BASE ** d - 1
    reals = [2.0 * k / top - 1.0 for k in vals[1:]]
    return m, (vals[0] if vals else None), reals


def encode_record(etype, reals, d=4):
    """Inverse of decode_record (for tests): type and reals in [-1, 1]."""
    top = BASE ** d - 1
    ints = [etype] + [int(math.floor((min(1.0, max(-1.0, r)) + 1.0) / 2.0 * top)) for r in reals]
    m = len(ints) + 2
    out = [ALPHABET[d], ALPHABET[m]]
    for k in ints:
        for _ in range(d):
            out.append(ALPHABET[k % BASE])
            k //= BASE
    return ''.join(out)


def scaled(m, etype, r, sc):
    """Dict of physical values of one record (keys of CSV_COLS)."""
    c, v, s = sc['c'], sc['v'], sc['s']
    row = {'kind': KIND_BY_LEN.get(m, 'other'), 'type': etype}
    if m == 15:
        for i in range(3):
            row['x%d' % i] = r[i] * c
            row['y%d' % i] = r[3 + i] * c
        row.update(vx=r[6] * v, vy=r[7] * v, sxx=r[8] * s, syy=r[9] * s, sxy=r[10] * s,
                   damage=r[11])
    elif m in (12, 14):
        for i in range(4):
            row['x%d' % i] = r[i] * c
            row['y%d' % i] = r[4 + i] * c
        if m == 12:
            row['state'] = r[8]
        else:
            row.update(flag=r[8], open1=r[9], open2=r[10])
    return row


def read_ym(path, sc):
    rows = []
    with open(path) as f:
        first = f.readline().strip()
        if first != 'CODED':
            raise CodedError('%s:1: first line is %r, expected CODED' % (path, first[:20]))
        for ln, line in enumerate(f, start=2):
            if not line.strip():
                continue
            try:
                m, etype, r = decode_record(line)
            except CodedError as e:
                raise CodedError('%s:%d: %s' % (path, ln, e))
            if m in KIND_BY_LEN and len(r) != m - 3:
                raise CodedError('%s:%d: bad record length' % (path, ln))
            row = scaled(m, etype, r, sc)
            row['record'] = len(rows)
            rows.append(row)
    return rows


def deck_scales(path):
    """DCSIZC/F/S/V of a .y deck (1 when absent), by the deck's own token rules."""
    sc = {'DCSIZC': 1.0, 'DCSIZF': 1.0, 'DCSIZS': 1.0, 'DCSIZV': 1.0}
    toks = open(path).read().split()
    i = 0
    while i < len(toks):
        t = toks[i]
        if t.startswith('/*'):
            i += 1
            while i < len(toks) and not toks[i].startswith('*/'):
                i += 1
        elif t.startswith('/YD/YDC/DCSIZ') and len(t) >= 14 and t[13] in 'CFSV':
            key = t[8:14]
            if i + 1 < len(toks):
                sc[key] = float(toks[i + 1])
                i += 1
        i += 1
    return sc


def get_scales(a):
    sc = {'c': 1.0, 'v': 1.0, 's': 1.0}
    if a.deck:
        d = deck_scales(a.deck)
        sc = {'c': d['DCSIZC'], 'v': d['DCSIZV'], 's': d['DCSIZS']}
    for k in 'cvs':
        v = getattr(a, 'siz' + k)
        if v is not None:
            sc[k] = v
    return sc


def file_index(path):
    m = re.search(r'(\d+)\.ym$', os.path.basename(path))
    return int(m.group(1)) if m else 0


def to_csv(a):
    sc = get_scales(a)
    os.makedirs(a.o, exist_ok=True)
    for p in a.files:
        rows = read_ym(p, sc)
        out = os.path.join(a.o, os.path.splitext(os.path.basename(p))[0] + '.csv')
        with open(out, 'w', newline='') as f:
            w = csv.DictWriter(f, fieldnames=CSV_COLS, restval='')
            w.writeheader()
            for r in rows:
                w.writerow({k: (repr(v) if isinstance(v, float) else v) for k, v in r.items()})
        print('%s: %d records -> %s' % (p, len(rows), out))


def to_hdf5(a):
    try:
        import numpy as np
        import h5py
    except ImportError as e:
        sys.stderr.write('error: HDF5 output needs numpy and h5py (%s); install them with '
                         '`tools/install-deps --python`, or use the csv mode (standard library '
                         'only)\n' % e)
        sys.exit(2)
    sc = get_scales(a)
    files = sorted(a.files, key=file_index)
    base = a.o[:-3] if a.o.endswith('.h5') else a.o
    h5name = base + '.h5'
    h5rel = os.path.basename(h5name)
    xdmf = ['<?xml version="1.0" ?>', '<Xdmf Version="3.0">', '<Domain>',
            '<Grid Name="y2d" GridType="Collection" CollectionType="Temporal">']

    def item(path, shape, dtype):
        nt = 'Int' if dtype == 'i' else 'Float'
        prec = 4 if dtype == 'i' else 8
        return ('<DataItem Dimensions="%s" NumberType="%s" Precision="%d" Format="HDF">%s:%s'
                '</DataItem>' % (' '.join(str(s) for s in shape), nt, prec, h5rel, path))

    with h5py.File(h5name, 'w') as h:
        for si, p in enumerate(files):
            rows = read_ym(p, sc)
            tris = [r for r in rows if r['kind'] == 'tri']
            jts = [r for r in rows if r['kind'] in ('intact_joint', 'broken_joint')]
            g = h.create_group('step_%06d' % si)
            g.attrs['source'] = p
            t = file_index(p) * a.dt
            xdmf.append('<Grid Name="step_%d" GridType="Collection" CollectionType="Spatial">' % si)
            xdmf.append('<Time Value="%r"/>' % t)
            # triangles: own 3 nodes each (coded output has no shared node numbering)
            nt = len(tris)
            xy = np.zeros((3 * nt, 2))
            for i, r in enumerate(tris):
                for k in range(3):
                    xy[3 * i + k] = (r['x%d' % k], r['y%d' % k])
            g['tri/xy'] = xy
            g['tri/conn'] = np.arange(3 * nt, dtype=np.int32).reshape(nt, 3)
            for key in ('sxx', 'syy', 'sxy', 'damage', 'type'):
                g['tri/' + key] = np.array([r[key] for r in tris], dtype=float if key != 'type' else np.int32)
            vel = np.zeros((nt, 3))
            for i, r in enumerate(tris):
                vel[i, 0], vel[i, 1] = r['vx'], r['vy']
            g['tri/velocity'] = vel
            pre = 'step_%06d/tri/' % si
            if nt:
                xdmf.append('<Grid Name="triangles"><Topology TopologyType="Triangle" NumberOfElements="%d">%s</Topology>'
                        % (nt, item(pre + 'conn', (nt, 3), 'i')))
                xdmf.append('<Geometry GeometryType="XY">%s</Geometry>' % item(pre + 'xy', (3 * nt, 2), 'f'))
                for key in ('sxx', 'syy', 'sxy', 'damage'):
                    xdmf.append('<Attribute Name="%s" AttributeType="Scalar" Center="Cell">%s</Attribute>'
                                % (key, item(pre + key, (nt,), 'f')))
                xdmf.append('<Attribute Name="velocity" AttributeType="Vector" Center="Cell">%s</Attribute>'
                            % item(pre + 'velocity', (nt, 3), 'f'))
                xdmf.append('</Grid>')
            # joints
            nj = len(jts)
            if a.joints == 'quads':
                jxy = np.zeros((4 * nj, 2))
                for i, r in enumerate(jts):
                    for k in range(4):
                        jxy[4 * i + k] = (r['x%d' % k], r['y%d' % k])
                conn = np.arange(4 * nj, dtype=np.int32).reshape(nj, 4)
                topo, npc = 'Quadrilateral', 4
            else:
                jxy = np.zeros((2 * nj, 2))
                for i, r in enumerate(jts):
                    jxy[2 * i] = ((r['x3'] + r['x0']) / 2, (r['y3'] + r['y0']) / 2)
                    jxy[2 * i + 1] = ((r['x1'] + r['x2']) / 2, (r['y1'] + r['y2']) / 2)
                conn = np.arange(2 * nj, dtype=np.int32).reshape(nj, 2)
                topo, npc = 'Polyline" NodesPerElement="2', 2
            g['joint/xy'] = jxy
            g['joint/conn'] = conn
            g['joint/broken'] = np.array([1 if r['kind'] == 'broken_joint' else 0 for r in jts], dtype=np.int32)
            g['joint/state'] = np.array([r.get('state', 0.0) for r in jts], dtype=float)
            g['joint/open1'] = np.array([r.get('open1', 0.0) for r in jts], dtype=float)
            g['joint/open2'] = np.array([r.get('open2', 0.0) for r in jts], dtype=float)
            if nj:
                pre = 'step_%06d/joint/' % si
                xdmf.append('<Grid Name="joints"><Topology TopologyType="%s" NumberOfElements="%d">%s</Topology>'
                            % (topo, nj, item(pre + 'conn', (nj, npc), 'i')))
                xdmf.append('<Geometry GeometryType="XY">%s</Geometry>' % item(pre + 'xy', jxy.shape, 'f'))
                xdmf.append('<Attribute Name="broken" AttributeType="Scalar" Center="Cell">%s</Attribute>'
                            % item(pre + 'broken', (nj,), 'i'))
                for key in ('state', 'open1', 'open2'):
                    xdmf.append('<Attribute Name="%s" AttributeType="Scalar" Center="Cell">%s</Attribute>'
                                % (key, item(pre + key, (nj,), 'f')))
                xdmf.append('</Grid>')
            xdmf.append('</Grid>')
            print('%s: %d triangles, %d joints' % (p, nt, nj))
    xdmf += ['</Grid>', '</Domain>', '</Xdmf>']
    with open(base + '.xdmf', 'w') as f:
        f.write('\n'.join(xdmf) + '\n')
    print('wrote %s and %s' % (h5name, base + '.xdmf'))


def selftest():
    ok = True
    if len(ALPHABET) != 90 or len(set(ALPHABET)) != 90:
        print('FAIL: alphabet has %d characters, %d distinct' % (len(ALPHABET), len(set(ALPHABET))))
        ok = False
    m, t, r = decode_record('2510/{{l')
    want = (5, 1, [0.49994, -0.25003])
    if m != 5 or t != 1 or any(abs(a - b) > 5e-6 for a, b in zip(r, want[2])):
        print('FAIL: 2510/{{l decoded as m=%d type=%s reals=%s, expected 5, 1, [0.49994, -0.25003]'
              % (m, t, r))
        ok = False
    else:
        print('ok: 2510/{{l -> type %d, %.5f, %.5f (FORMAT.md 7.2 worked example)' % (t, r[0], r[1]))
    if encode_record(1, [0.5, -0.25], d=2) != '2510/{{l':
        print('FAIL: encoding 1, 0.5, -0.25 with d = 2 gives %s' % encode_record(1, [0.5, -0.25], d=2))
        ok = False
    # round trip of a triangle record with d = 4: error below one quantum 2/(90^4-1)
    vals = [0.1, -0.2, 0.3, 0.4, -0.5, 0.6, 0.01, -0.02, 0.7, -0.8, 0.9, 0.0]
    m, t, r = decode_record(encode_record(1, vals, d=4))
    q = 2.0 / (BASE ** 4 - 1)
    err = max(abs(a - b) for a, b in zip(vals, r))
    if m != 15 or t != 1 or err > q:
        print('FAIL: d=4 round trip error %g > quantum %g' % (err, q))
        ok = False
    else:
        print('ok: d = 4 triangle record round trip, max error %.2g <= quantum %.2g' % (err, q))
    row = scaled(m, t, r, {'c': 2.0, 'v': 10.0, 's': 1e6})
    if abs(row['x1'] - 2.0 * vals[1]) > 2 * q or abs(row['sxx'] - 1e6 * vals[8]) > 1e6 * q:
        print('FAIL: scaling')
        ok = False
    print('selftest %s' % ('passed' if ok else 'FAILED'))
    return ok


def main():
    if '--selftest' in sys.argv[1:]:
        sys.exit(0 if selftest() else 1)
    ap = argparse.ArgumentParser(description='Y2D coded .ym files to CSV or HDF5+XDMF',
                                 epilog='see the module docstring for the record layouts')
    ap.add_argument('mode', choices=['csv', 'hdf5'])
    ap.add_argument('files', nargs='+')
    ap.add_argument('-o', default=None, help='csv: output directory (default .); hdf5: output base name')
    ap.add_argument('--deck', help='read DCSIZC/DCSIZV/DCSIZS from this .y deck')
    ap.add_argument('--sizc', type=float)
    ap.add_argument('--sizv', type=float)
    ap.add_argument('--sizs', type=float)
    ap.add_argument('--joints', choices=['quads', 'lines'], default='quads')
    ap.add_argument('--dt', type=float, default=1.0, help='time per file index (hdf5)')
    a = ap.parse_args()
    try:
        if a.mode == 'csv':
            a.o = a.o or '.'
            to_csv(a)
        else:
            if not a.o:
                ap.error('hdf5 mode needs -o OUT (writes OUT.h5 and OUT.xdmf)')
            to_hdf5(a)
    except (CodedError, OSError, ValueError) as e:
        sys.stderr.write('error: %s\n' % e)
        sys.exit(1)


if __name__ == '__main__':
    main()
