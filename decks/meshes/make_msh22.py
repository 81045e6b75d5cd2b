"""make_msh22.py: the MSH 2.2 test meshes of yfdem's Gmsh reader, written by Gmsh itself (the
`gmsh` Python module, pip install gmsh) from two_squares.msh, so that each 2.2 file holds the
same mesh as a 4.1 file and the two must give the same scene (tests/check_mesh.c).

  two_squares_22.msh   two_squares.msh saved as MSH 2.2
  two_squares_22p.msh  the same with Mesh.SaveParametric ($ParametricNodes)
  overlap.msh          two_squares.msh with physical groups that overlap (a surface in two
  overlap_22.msh       and three physical surfaces, curves in two physical curves, unnamed
  overlap_22b.msh      groups of the same tag in two dimensions), as MSH 4.1, as MSH 2.2 and
                       as binary MSH 2.2: 2.2 writes an element once per physical group it is in.
  two_squares_b.msh    two_squares.msh and overlap.msh saved as binary MSH 4.1 (Mesh.Binary = 1,
  overlap_b.msh        as gmsh -bin writes them)
  two_squares_part.msh two_squares.msh partitioned in 3 ($PartitionedEntities), as MSH 4.1 and
  two_squares_partb.msh as binary MSH 4.1
  two_squares_paramb.msh two_squares_param.msh saved as binary MSH 4.1 (Mesh.SaveParametric)
  periodic.msh         a unit square meshed with its right side periodic to its left ($Periodic,
  periodic_b.msh       which yfdem skips), as MSH 4.1 and as binary MSH 4.1 (from periodic.msh)

Run from decks/meshes: python3 make_msh22.py
"""
import gmsh

gmsh.initialize()
gmsh.option.setNumber("General.Terminal", 0)
gmsh.open("two_squares.msh")
gmsh.option.setNumber("Mesh.Binary", 1)
gmsh.write("two_squares_b.msh")
gmsh.option.setNumber("Mesh.Binary", 0)
gmsh.option.setNumber("Mesh.MshFileVersion", 2.2)
gmsh.write("two_squares_22.msh")
gmsh.option.setNumber("Mesh.SaveParametric", 1)
gmsh.write("two_squares_22p.msh")
gmsh.option.setNumber("Mesh.SaveParametric", 0)
gmsh.model.addPhysicalGroup(2, [1, 2], name="whole")
gmsh.model.addPhysicalGroup(2, [2], tag=9)
gmsh.model.addPhysicalGroup(1, [1, 3], tag=9)
gmsh.model.addPhysicalGroup(1, [1], name="half")
gmsh.model.addPhysicalGroup(0, [1, 6], name="pins")
for version, binary, name in ((4.1, 0, "overlap.msh"), (2.2, 0, "overlap_22.msh"), (2.2, 1, "overlap_22b.msh")):
    gmsh.option.setNumber("Mesh.MshFileVersion", version)
    gmsh.option.setNumber("Mesh.Binary", binary)
    gmsh.write(name)
gmsh.option.setNumber("Mesh.MshFileVersion", 4.1)
gmsh.option.setNumber("Mesh.Binary", 1)
gmsh.write("overlap_b.msh")
gmsh.clear()
gmsh.open("two_squares.msh")
gmsh.model.mesh.partition(3)
for binary, name in ((0, "two_squares_part.msh"), (1, "two_squares_partb.msh")):
    gmsh.option.setNumber("Mesh.Binary", binary)
    gmsh.write(name)
gmsh.clear()
gmsh.open("two_squares_param.msh")
gmsh.option.setNumber("Mesh.SaveParametric", 1)
gmsh.write("two_squares_paramb.msh")
gmsh.option.setNumber("Mesh.SaveParametric", 0)
gmsh.clear()
gmsh.model.add("periodic")
pts = [gmsh.model.geo.addPoint(x, y, 0, 0.3) for x, y in ((0, 0), (1, 0), (1, 1), (0, 1))]
lines = [gmsh.model.geo.addLine(pts[i], pts[(i + 1) % 4]) for i in range(4)]
sq = gmsh.model.geo.addPlaneSurface([gmsh.model.geo.addCurveLoop(lines)])
gmsh.model.geo.synchronize()
# the right side (line 2) is the left one (line 4) moved by x + 1
gmsh.model.mesh.setPeriodic(1, [lines[1]], [lines[3]], [1, 0, 0, 1, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1])
gmsh.model.addPhysicalGroup(2, [sq], name="rock")
gmsh.model.addPhysicalGroup(1, [lines[0]], name="bottom")
gmsh.model.mesh.generate(2)
gmsh.option.setNumber("Mesh.Binary", 0)
gmsh.write("periodic.msh")
# Gmsh places the periodic side's nodes anew from the other side when it reads a file: both files
# are written from the mesh read back, so that they hold the same bits
gmsh.clear()
gmsh.open("periodic.msh")
for binary, name in ((0, "periodic.msh"), (1, "periodic_b.msh")):
    gmsh.option.setNumber("Mesh.Binary", binary)
    gmsh.write(name)
gmsh.finalize()
