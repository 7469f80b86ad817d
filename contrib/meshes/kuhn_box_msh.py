#!/usr/bin/env python3
"""Writes a gmsh 2.2 ASCII mesh of linear tetrahedra filling a box:
nx x ny x nz cubes, each split into the six tetrahedra around its main
diagonal (Kuhn's split, conforming across faces), so that a box region
whose faces lie on the cubes' faces holds exactly its volume of zones.

  kuhn_box_msh.py LX LY LZ NX NY NZ > file.msh

Used for tests/parallel/body_excavation_01 (6 2 5 12 4 10)."""
import sys

lx, ly, lz = (float(a) for a in sys.argv[1:4])
nx, ny, nz = (int(a) for a in sys.argv[4:7])


def node(i, j, k):
    return 1 + i + (nx + 1) * (j + (ny + 1) * k)


out = sys.stdout
out.write("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n")
out.write(f"{(nx + 1) * (ny + 1) * (nz + 1)}\n")
for k in range(nz + 1):
    for j in range(ny + 1):
        for i in range(nx + 1):
            out.write(f"{node(i, j, k)} {lx * i / nx:.17g} {ly * j / ny:.17g} {lz * k / nz:.17g}\n")
out.write("$EndNodes\n$Elements\n")
# The six paths from corner (0,0,0) to (1,1,1) along the axes.
paths = [(0, 1, 2), (0, 2, 1), (1, 0, 2), (1, 2, 0), (2, 0, 1), (2, 1, 0)]
out.write(f"{6 * nx * ny * nz}\n")
e = 0
for k in range(nz):
    for j in range(ny):
        for i in range(nx):
            for path in paths:
                c = [i, j, k]
                corners = [node(*c)]
                for axis in path:
                    c[axis] += 1
                    corners.append(node(*c))
                e += 1
                out.write(f"{e} 4 2 1 1 " + " ".join(str(n) for n in corners) + "\n")
out.write("$EndElements\n")
