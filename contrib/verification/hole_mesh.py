#!/usr/bin/env python3
"""Writes a gmsh (2.2, ASCII) mesh of a quarter of a plane-strain slab with a
circular hole at the origin, for the hole problems of the study (Kirsch,
Salencon) run from a parameter file through 'Mesh file'.

The same mesh as tests/deformable/hole_mesh.h: x >= 0, y >= 0,
0 <= z <= thickness, hole radius a, outer boundary a circle of radius R or
the square [0, R]^2; n_theta equal sectors and n_r rings spaced
geometrically along each ray (zones about as deep as they are wide), one
layer of hexahedra. With --kind tet each hexahedron is split into 24
tetrahedra (a point at the centre of every face and of the cell; symmetric,
no preferred diagonal); with --kind hex the hexahedra are written as they
are (for elements that take bricks).

Usage: hole_mesh.py --sectors 8 --outer 40 --square --kind tet out.msh
Prints n_r, the ring ratio and the thickness (m) on one line.
"""

import argparse
import math
import sys


def ring_count(a, R, n_theta):
    """Rings as deep as the sectors are wide at the wall, out to R."""
    dtheta = 0.5 * math.pi / n_theta
    return max(1, int(round(math.log(R / a) / math.log(1.0 + dtheta))))


def build(a, R, n_theta, square, kind):
    dtheta = 0.5 * math.pi / n_theta
    n_r = ring_count(a, R, n_theta)
    thickness = 2.0 * a * dtheta
    nodes = []  # (x, y, z)

    def outer(theta):
        return R / max(math.cos(theta), math.sin(theta)) if square else R

    plane = []
    for j in range(n_theta + 1):
        theta = 0.5 * math.pi * j / n_theta
        for i in range(n_r + 1):
            r = a * (outer(theta) / a) ** (i / n_r)
            # Exact zeros on the symmetry planes, so that regions find them.
            plane.append((0.0 if j == n_theta else r * math.cos(theta),
                          0.0 if j == 0 else r * math.sin(theta)))
    for z in (0.0, thickness):
        nodes.extend((x, y, z) for x, y in plane)
    n_plane = len(plane)

    def pid(i, j, layer):
        return layer * n_plane + j * (n_r + 1) + i

    hexes = []
    for j in range(n_theta):
        for i in range(n_r):
            bottom = [pid(i, j, 0), pid(i + 1, j, 0), pid(i + 1, j + 1, 0), pid(i, j + 1, 0)]
            hexes.append(bottom + [n + n_plane for n in bottom])
    if kind == "hex":
        return nodes, [(5, h) for h in hexes], n_r, thickness

    face_centre = {}

    def centre_of(corners):
        key = tuple(sorted(corners))
        if key not in face_centre:
            face_centre[key] = len(nodes)
            nodes.append(tuple(sum(nodes[c][d] for c in corners) / len(corners)
                               for d in range(3)))
        return face_centre[key]

    def volume(t):
        p = [nodes[k] for k in t]
        u = [p[1][d] - p[0][d] for d in range(3)]
        v = [p[2][d] - p[0][d] for d in range(3)]
        w = [p[3][d] - p[0][d] for d in range(3)]
        return (u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) +
                u[2] * (v[0] * w[1] - v[1] * w[0])) / 6.0

    faces = [(0, 1, 2, 3), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (3, 0, 4, 7)]
    tets = []
    for h in hexes:
        cell = len(nodes)
        nodes.append(tuple(sum(nodes[c][d] for c in h) / 8.0 for d in range(3)))
        for f in faces:
            corners = [h[k] for k in f]
            fc = centre_of(corners)
            for k in range(4):
                t = [fc, corners[k], corners[(k + 1) % 4], cell]
                if volume(t) < 0.0:
                    t[1], t[2] = t[2], t[1]
                tets.append((4, t))
    return nodes, tets, n_r, thickness


def write_msh(path, nodes, elements):
    with open(path, "w") as out:
        out.write("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n%d\n" % len(nodes))
        for k, (x, y, z) in enumerate(nodes):
            out.write("%d %.17g %.17g %.17g\n" % (k + 1, x, y, z))
        out.write("$EndNodes\n$Elements\n%d\n" % len(elements))
        for k, (gmsh_type, conn) in enumerate(elements):
            out.write("%d %d 2 1 1 %s\n" % (k + 1, gmsh_type, " ".join(str(c + 1) for c in conn)))
        out.write("$EndElements\n")


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("output")
    parser.add_argument("--sectors", type=int, default=8, help="sectors in the quarter")
    parser.add_argument("--radius", type=float, default=1.0, help="hole radius a (m)")
    parser.add_argument("--outer", type=float, default=20.0, help="outer radius or half-width (m)")
    parser.add_argument("--square", action="store_true", help="outer boundary a square")
    parser.add_argument("--kind", choices=["tet", "hex"], default="tet")
    args = parser.parse_args(argv)
    nodes, elements, n_r, thickness = build(args.radius, args.outer, args.sectors, args.square,
                                            args.kind)
    write_msh(args.output, nodes, elements)
    print("rings %d ring_ratio %.17g thickness %.17g cells %d nodes %d" %
          (n_r, (args.outer / args.radius) ** (1.0 / n_r), thickness, len(elements), len(nodes)))


if __name__ == "__main__":
    main(sys.argv[1:])
