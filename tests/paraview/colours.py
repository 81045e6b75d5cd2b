# colours.py: does a real ParaView show what yfdem wrote?  Run by tests/paraview/run under pvpython.
#
#   pvpython colours.py MESH.xmf CRACKS.xmf OUT.png [PICTURE.png]
#
# Opens both indexes with the reader ParaView picks by default (OpenDataFile; Xdmf3ReaderS in
# ParaView 5.11), checks that every frame carries every field the index declares, then colours the
# mesh by sigma1 on the last frame (map over -f_t..f_t), with the cracks coloured by crack_state on
# top, renders OUT.png and checks that the image holds the colour map's range of colours: pixels
# are matched to 32 samples of the map (within 12 of 255 per channel), and at least 8 samples, one
# from each end quarter, must each colour 20 pixels or more.  A field drawn flat grey matches one
# sample at most (the map's grey middle).  Prints one line per check and "N passed, M failed".
import os
import re
import sys

from paraview.simple import (ColorBy, GetActiveViewOrCreate, GetAnimationScene, GetColorTransferFunction,
                             OpenDataFile, Render, SaveScreenshot, Show)

from pvcheck import check, finish, times_of

mesh_xmf, crack_xmf, png = sys.argv[1:4]


def declared(xmf):
    """Names of the Attributes the index declares, per centre."""
    text = open(xmf).read()
    cells = set(re.findall(r'<Attribute Name="([^"]+)" AttributeType="[^"]+" Center="Cell"', text))
    nodes = set(re.findall(r'<Attribute Name="([^"]+)" AttributeType="[^"]+" Center="Node"', text))
    return cells, nodes


def every_frame(reader, xmf, label):
    """Every frame has every declared field, with the size of its grid."""
    cells, nodes = declared(xmf)
    times = times_of(reader)
    missing = []
    for t in times:
        reader.UpdatePipeline(t)
        have_c, have_n = set(reader.CellData.keys()), set(reader.PointData.keys())
        ncell = reader.GetDataInformation().GetNumberOfCells()
        for name in sorted(cells - have_c if ncell else set()):
            missing.append('%s t=%g: cell field %s' % (label, t, name))
        for name in sorted(nodes - have_n):
            missing.append('%s t=%g: node field %s' % (label, t, name))
    check(not missing, '%s: %d frames, every one with its fields %s%s' %
          (label, len(times), sorted(cells | nodes), ('; missing: ' + ', '.join(missing[:6])) if missing else ''))
    return times


mesh = OpenDataFile(mesh_xmf)
check(mesh is not None and mesh.GetXMLName() == 'Xdmf3ReaderS',
      'default reader for %s: %s' % (mesh_xmf, mesh.GetXMLName() if mesh else None))
times = every_frame(mesh, mesh_xmf, 'mesh')
cracks = OpenDataFile(crack_xmf) if os.path.exists(crack_xmf) else None
check(cracks is not None, 'crack series %s' % crack_xmf)
if cracks:
    ctimes = every_frame(cracks, crack_xmf, 'cracks')
    check(ctimes == times, 'the crack series has the frames of the mesh series')

scene = GetAnimationScene()
scene.UpdateAnimationUsingDataTimeSteps()
view = GetActiveViewOrCreate('RenderView')
view.ViewSize = [1000, 260]
view.OrientationAxesVisibility = 0
md = Show(mesh, view)
cd = Show(cracks, view) if cracks else None
scene.AnimationTime = times[-1]
mesh.UpdatePipeline(times[-1])
if cracks:
    cracks.UpdatePipeline(times[-1])
ColorBy(md, ('CELLS', 'sigma1'))
lut = GetColorTransferFunction('sigma1')
lo, hi = mesh.CellData['sigma1'].GetRange() if 'sigma1' in mesh.CellData.keys() else (0.0, 0.0)
# The map spans -FT..FT, the concrete's tensile strength (decks/beam.deck): blue in compression,
# red where joints may open.  The data range itself is set by a few triangles under the impactor
# (tens of MPa) and would paint the whole beam one blue.
ft = 3.15e6
check(lo < 0 < ft < hi, 'sigma1 on the last frame spans %g to %g Pa (compression and tension past f_t)' % (lo, hi))
lut.RescaleTransferFunction(-ft, ft)
md.Ambient, md.Diffuse = 1.0, 0.0  # unlit: a cell shows exactly its colour-map colour
if cd:
    ColorBy(cd, ('CELLS', 'crack_state'))
    cd.RescaleTransferFunctionToDataRange(False, True)
    cd.LineWidth = 2.0
Render(view)  # the first render resets the camera: set it after
view.CameraParallelProjection = 1
view.CameraFocalPoint = [0.5, 0.07, 0.0]
view.CameraPosition = [0.5, 0.07, 5.0]
view.CameraViewUp = [0.0, 1.0, 0.0]
view.CameraParallelScale = 0.14  # the beam's 1 m across the 1000 x 260 picture
Render(view)
SaveScreenshot(png, view, ImageResolution=[1000, 260])  # counted: no colour bar in it

ctf = lut.GetClientSideObject()
nbin = 32
samples = []
for k in range(nbin):
    rgb = [0.0, 0.0, 0.0]
    ctf.GetColor(-ft + 2 * ft * (k + 0.5) / nbin, rgb)
    samples.append(tuple(int(round(255 * c)) for c in rgb))

from PIL import Image  # noqa: E402  (Debian's python3-pil, a dependency of paraview)
img = Image.open(png).convert('RGB')
count = [0] * nbin
for n, c in img.getcolors(1 << 24):
    best, bd = -1, 13
    for k, s in enumerate(samples):
        d = max(abs(c[0] - s[0]), abs(c[1] - s[1]), abs(c[2] - s[2]))
        if d < bd:
            best, bd = k, d
    if best >= 0:
        count[best] += n
used = [k for k in range(nbin) if count[k] >= 20]
check(len(used) >= 8 and min(used) < nbin // 4 and max(used) >= nbin - nbin // 4,
      'sigma1 on the last frame (t = %g s) over -%g..%g Pa: %d of %d colour-map samples in the image '
      '(pixels per sample: %s)' % (times[-1], ft, ft, len(used), nbin, count))
if len(sys.argv) > 4:  # the README's picture: the same view with the colour bar
    md.SetScalarBarVisibility(view, True)
    Render(view)
    SaveScreenshot(sys.argv[4], view, ImageResolution=[1000, 260])
finish('paraview')
