"""msh41.py: write a 2D triangle mesh as a Gmsh MSH 4.1 ASCII file (what `mesh gmsh` reads), for
the mesh generators in tools/ (gen_disc.py, gen_notched_plate.py).

write(path, xy, tris, curves, surface, fmt): xy the node coordinates [m] (node tag = index + 1),
tris the triangles (index triples), curves a list of (name, [(a, b), ...]) physical curves made of
2-node lines, surface the physical surface's name; fmt the coordinates' format (%.17g keeps every
bit).  One entity per physical group; all nodes in the surface's block.
"""


def write(path, xy, tris, curves, surface, fmt="%.17g"):
    nc = len(curves)

    def box(nodes):
        xs = [xy[q][0] for q in nodes]
        ys = [xy[q][1] for q in nodes]
        return "%.17g %.17g 0 %.17g %.17g 0" % (min(xs), min(ys), max(xs), max(ys))

    with open(path, "w") as f:
        w = f.write
        w("$MeshFormat\n4.1 0 8\n$EndMeshFormat\n")
        w("$PhysicalNames\n%d\n" % (nc + 1))
        for k, (name, _) in enumerate(curves):
            w('1 %d "%s"\n' % (k + 1, name))
        w('2 %d "%s"\n$EndPhysicalNames\n' % (nc + 1, surface))
        w("$Entities\n0 %d 1 0\n" % nc)
        for k, (_, lines) in enumerate(curves):
            w("%d %s 1 %d 0\n" % (k + 1, box([q for l in lines for q in l]), k + 1))
        w("1 %s 1 %d 0\n$EndEntities\n" % (box(range(len(xy))), nc + 1))
        nn = len(xy)
        w("$Nodes\n1 %d 1 %d\n2 1 0 %d\n" % (nn, nn, nn))
        w("".join("%d\n" % (q + 1) for q in range(nn)))
        w("".join((fmt + " " + fmt + " 0\n") % p for p in xy))
        w("$EndNodes\n")
        ne = sum(len(l) for _, l in curves) + len(tris)
        w("$Elements\n%d %d 1 %d\n" % (nc + 1, ne, ne))
        tag = 1
        for k, (_, lines) in enumerate(curves):
            w("1 %d 1 %d\n" % (k + 1, len(lines)))
            for a, b in lines:
                w("%d %d %d\n" % (tag, a + 1, b + 1))
                tag += 1
        w("2 1 2 %d\n" % len(tris))
        for t in tris:
            w("%d %d %d %d\n" % (tag, t[0] + 1, t[1] + 1, t[2] + 1))
            tag += 1
        w("$EndElements\n")
