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
gmsh.finalize()
