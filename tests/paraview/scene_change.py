# scene_change.py: a body added between two runs shows in the frame of the second run's first step.
# Run by tests/paraview/run under pvpython.
#
#   pvpython scene_change.py SERIES.xmf BAR_TRIANGLES BLOCK_TRIANGLES V0
#
# The deck (tests/paraview/run) runs a bar for exactly one frame interval, adds a block moving at
# -V0 m/s in y and runs again.  The frame of the step where the runs meet was written when the
# first run ended there, before the block existed, and yfdem kept it (the second run's own frame
# of that step was skipped as a duplicate), so ParaView showed no block at that time and the block
# appeared a whole frame interval into its flight, while the thermo line of that step counted its
# kinetic energy.  Checked with ParaView's default reader: 3 frames at distinct times, and the
# middle one holds bar and block (cells), the block's velocity -V0 (points) and body 0..1 (cells);
# and, as the README says, the legacy "XDMF Reader" reads the same frames (v with 3 components).
import sys

from paraview.simple import OpenDataFile, XDMFReader
from pvcheck import check, finish, times_of

xmf, ntri_bar, ntri_block, v0 = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), float(sys.argv[4])
r = OpenDataFile(xmf)
times = times_of(r)
check(len(times) == 3 and len(set(times)) == 3, 'three frames at distinct times: %s' % times)
if len(times) == 3:
    r.UpdatePipeline(times[1])
    nc = r.GetDataInformation().GetNumberOfCells()
    check(nc == ntri_bar + ntri_block, 'frame of the second run\'s first step (t = %.6g s): %d cells, the bar\'s %d '
          'and the added block\'s %d' % (times[1], nc, ntri_bar, ntri_block))
    vy = r.PointData['v'].GetRange(1) if 'v' in r.PointData.keys() else (0.0, 0.0)
    # the block's nodes move at exactly -V0 (set by the deck), the bar's at a few mm/s
    check(vy[0] == -v0, 'its velocity v_y spans %g..%g m/s: the block at -%g m/s' % (vy[0], vy[1], v0))
    body = r.CellData['body'].GetRange() if 'body' in r.CellData.keys() else (0.0, 0.0)
    check(tuple(body) == (0.0, 1.0), 'its body field spans %g..%g (bar 0, block 1)' % tuple(body))
legacy = XDMFReader(FileNames=[xmf])
legacy.PointArrayStatus = ['v']
lt = times_of(legacy)
check(lt == times, 'the legacy XDMF Reader has the same frames: %s' % lt)
if len(lt) == 3:
    legacy.UpdatePipeline(lt[1])
    nc = legacy.GetDataInformation().GetNumberOfCells()
    have = 'v' in legacy.PointData.keys()
    ncomp = legacy.PointData['v'].GetNumberOfComponents() if have else 0
    vy = legacy.PointData['v'].GetRange(1) if have else (0.0, 0.0)
    check(nc == ntri_bar + ntri_block and ncomp == 3 and vy[0] == -v0,
          'legacy reader, t = %.6g s: %d cells, v with %d components, v_y from %g m/s' % (lt[1], nc, ncomp, vy[0]))
finish('paraview scene change')
