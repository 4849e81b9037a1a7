#!/usr/bin/env python3
"""Writes the small damaged meshes of this directory, each made the way files of one origin come
damaged (the real files were checked by scripts/repair-samples.sh; these are our own, so the tests
carry no third-party data). Re-run to regenerate: python3 make_damaged.py"""
import math

def write_off(name, header_comment, points, faces):
    with open(name, "w") as f:
        f.write("OFF\n# " + header_comment + "\n")
        f.write(f"{len(points)} {len(faces)} 0\n")
        for p in points:
            f.write(" ".join(repr(float(c)) for c in p) + "\n")
        for face in faces:
            f.write(f"{len(face)} " + " ".join(map(str, face)) + "\n")

# A unit cube of 6 quads, as hand-written and viewer files (geomview's unitcube.off, CGAL's
# cube-shuffled.off) list it: two quads wound clockwise.
cube = [(x, y, z) for z in (0, 1) for y in (0, 1) for x in (0, 1)]
quads = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]
quads[1] = quads[1][::-1]
quads[3] = quads[3][::-1]
write_off("quad-cube-mixed-winding.off", "unit cube, 6 quads, 2 wound clockwise", cube, quads)

# Two tetrahedra touching at one corner (a bow-tie vertex, as in geomview's hook.off and cam.off):
# the corner is non-manifold. Volumes 1/6 and 8/6.
tet_a = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1)]
tet_b = [(0, 0, 0), (-2, 0, 0), (0, -2, 0), (0, 0, -2)]
points = tet_a + tet_b[1:]
faces = [(0, 2, 1), (0, 1, 3), (0, 3, 2), (1, 2, 3),      # outward for tet_a
         (0, 4, 5), (0, 6, 4), (0, 5, 6), (4, 6, 5)]      # outward for tet_b (mirrored)
write_off("tetrahedra-sharing-a-corner.off", "two tetrahedra sharing vertex 0", points, faces)

# A UV sphere as OBJ exporters write it with texture coordinates: the seam meridian repeated (its
# vertices carry u = 0 and u = 1), one pole vertex per pole triangle, v/vt/vn face corners.
rings, segments = 8, 12
with open("uv-sphere-seams.obj", "w") as f:
    f.write("# UV sphere, seam meridian and poles repeated as a textured OBJ export writes them\n")
    index = {}
    count = 0
    def vertex(i, j):
        """Writes the vertex at ring i, meridian j (u = j / segments): the copies an exporter makes
        for the seam (j = segments) and the poles repeat the coordinates of the original exactly."""
        global count
        theta, phi = math.pi * i / rings, 2 * math.pi * (j % segments) / segments
        if i in (0, rings):
            p = (0.0, 0.0, 1.0 if i == 0 else -1.0)
        else:
            p = (math.sin(theta) * math.cos(phi), math.sin(theta) * math.sin(phi), math.cos(theta))
        count += 1
        f.write("v {:.17g} {:.17g} {:.17g}\n".format(*p))
        f.write("vt {:.6f} {:.6f}\n".format(j / segments, 1 - i / rings))
        f.write("vn {:.17g} {:.17g} {:.17g}\n".format(*p))
        return count
    for i in range(1, rings):
        for j in range(segments + 1):       # j = segments repeats j = 0: the seam
            index[i, j] = vertex(i, j)
    for j in range(segments):                # a pole copy per triangle
        index[0, j] = vertex(0, j + 0.5)
        index[rings, j] = vertex(rings, j + 0.5)
    def corner(k):
        return f"{k}/{k}/{k}"
    for j in range(segments):
        f.write("f {} {} {}\n".format(corner(index[0, j]), corner(index[1, j]), corner(index[1, j + 1])))
        f.write("f {} {} {}\n".format(corner(index[rings, j]), corner(index[rings - 1, j + 1]),
                                      corner(index[rings - 1, j])))
    for i in range(1, rings - 1):
        for j in range(segments):
            a, b, c, d = index[i, j], index[i + 1, j], index[i + 1, j + 1], index[i, j + 1]
            f.write("f {} {} {} {}\n".format(*map(corner, (a, b, c, d))))

# A range-scan patch as scanner software writes ASCII PLY (colour and confidence per vertex): a
# height field on a 10 x 10 grid, two scan passes stitched along row 5 (that row's vertices
# written twice, each pass using its own copy), a face whose corners are collinear (a cap), and a
# missing face (a hole).
n = 10
grid = [(0.1 * x, 0.1 * y, 0.02 * math.sin(x) * math.cos(y)) for y in range(n) for x in range(n)]
copies = [grid[5 * n + x] for x in range(n)]            # row 5 again, for the second pass
points = grid + copies
def at(x, y, second_pass):
    return n * n + x if (y == 5 and second_pass) else y * n + x
faces = []
for y in range(n - 1):
    for x in range(n - 1):
        if (x, y) == (3, 7):
            continue                                     # the hole
        second = y >= 5
        a, b, c, d = at(x, y, second), at(x + 1, y, second), at(x + 1, y + 1, second), at(x, y + 1, second)
        faces += [(a, b, c), (a, c, d)]
# The cap: a triangle on the boundary edge (1,0)-(2,0) and a point on that edge (collinear corners).
points.append(((0.1 + 0.2) / 2, 0.0, (grid[1][2] + grid[2][2]) / 2))
mid = len(points) - 1
faces.append((1, mid, 2))
with open("scan-patch.ply", "w") as f:
    f.write("ply\nformat ascii 1.0\ncomment range-scan patch: two passes stitched along a row\n")
    f.write(f"element vertex {len(points)}\nproperty float x\nproperty float y\nproperty float z\n")
    f.write("property uchar red\nproperty uchar green\nproperty uchar blue\nproperty float confidence\n")
    f.write(f"element face {len(faces)}\nproperty list uchar int vertex_indices\nend_header\n")
    for p in points:
        f.write("{:.9g} {:.9g} {:.9g} 200 180 160 0.9\n".format(*p))
    for face in faces:
        f.write("3 {} {} {}\n".format(*face))
