#!/usr/bin/env python3
"""Writes the meshes of the shipped objects (models/objects/meshes/) from their dimensions.

Run it from anywhere: python3 models/objects/make_meshes.py. Each mesh is closed, with its
triangles counter-clockwise seen from outside, in metres in its part frame (the frame the
object file places with "position" and "rpy_deg"). The same dimensions give the same bytes.

  pan_body.stl    the pan's body, a cylinder of radius 0.08 m and height 0.05 m, as a
                  64-sided prism (binary STL)
  pan_handle.obj  the pan's handle, a 0.30 x 0.024 x 0.024 m bar (OBJ)
  mug_body.stl    the mug's body, a cup: outer radius 0.040 m, height 0.090 m, a 4.5 mm wall
                  and a 6 mm bottom, as a 48-sided solid of revolution (binary STL)
  mug_handle.obj  the mug's vertical loop handle in the x-z plane: a 10 x 12 mm band (10 mm in
                  the loop's plane, 12 mm thick along y) swept along a half ellipse from the
                  wall (x = 0.0385 m, inside it, at z = +-0.028 m) out to x = 0.0725 m (OBJ)
"""

import math
import os
import struct

HERE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "meshes")


def prism(sides, radius, height):
    """A closed prism about z, centred at the origin: (vertices, triangles)."""
    v = []
    for k in range(sides):
        a = 2.0 * math.pi * k / sides
        x, y = radius * math.cos(a), radius * math.sin(a)
        v += [(x, y, -0.5 * height), (x, y, 0.5 * height)]
    bottom, top = len(v), len(v) + 1
    v += [(0.0, 0.0, -0.5 * height), (0.0, 0.0, 0.5 * height)]
    t = []
    for k in range(sides):
        b0, t0 = 2 * k, 2 * k + 1
        b1 = 2 * ((k + 1) % sides)
        t1 = b1 + 1
        t += [(b0, b1, t1), (b0, t1, t0), (bottom, b1, b0), (top, t0, t1)]
    return v, t


def box(sx, sy, sz):
    """A closed box centred at the origin: (vertices, triangles)."""
    v = [((sx if i & 1 else -sx) / 2, (sy if i & 2 else -sy) / 2, (sz if i & 4 else -sz) / 2)
         for i in range(8)]
    quads = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]
    t = []
    for a, b, c, d in quads:
        t += [(a, b, c), (a, c, d)]
    return v, t


def revolved(sides, profile):
    """A closed solid of revolution about z from its half profile [(r, z), ...], which runs
    from a point on the axis round the solid's cross-section back to the axis:
    (vertices, triangles)."""
    v, rings = [], []
    for r, z in profile:
        if r == 0.0:
            v.append((0.0, 0.0, z))
            rings.append([len(v) - 1] * sides)
        else:
            rings.append([])
            for k in range(sides):
                a = 2.0 * math.pi * k / sides
                rings[-1].append(len(v))
                v.append((r * math.cos(a), r * math.sin(a), z))
    t = []
    for a, b in zip(rings, rings[1:]):
        for k in range(sides):
            k1 = (k + 1) % sides
            if a[k] != a[k1]:
                t.append((a[k], a[k1], b[k1]))
            if b[k] != b[k1]:
                t.append((a[k], b[k1], b[k]))
    return oriented(v, t)


def swept(path, width, thickness):
    """A closed tube of rectangular section (width in the x-z plane across the path,
    thickness along y) swept along a path in the x-z plane [(x, z), ...], capped at both ends:
    (vertices, triangles)."""
    v = []
    n = len(path)
    for i, (x, z) in enumerate(path):
        x0, z0 = path[max(i - 1, 0)]
        x1, z1 = path[min(i + 1, n - 1)]
        tx, tz = x1 - x0, z1 - z0
        length = math.hypot(tx, tz)
        nx, nz = tz / length, -tx / length  # across the path, in the x-z plane
        for s1, s2 in ((1, 1), (1, -1), (-1, -1), (-1, 1)):
            v.append((x + s1 * 0.5 * width * nx, s2 * 0.5 * thickness, z + s1 * 0.5 * width * nz))
    t = []
    for i in range(n - 1):
        for c in range(4):
            a, b = 4 * i + c, 4 * i + (c + 1) % 4
            t += [(a, b, b + 4), (a, b + 4, a + 4)]
    last = 4 * (n - 1)
    t += [(0, 2, 1), (0, 3, 2), (last, last + 1, last + 2), (last, last + 2, last + 3)]
    return oriented(v, t)


def oriented(v, t):
    """The triangles turned outward: the signed volume positive."""
    volume = 0.0
    for a, b, c in t:
        p, q, r = v[a], v[b], v[c]
        volume += (p[0] * (q[1] * r[2] - q[2] * r[1]) - p[1] * (q[0] * r[2] - q[2] * r[0]) +
                   p[2] * (q[0] * r[1] - q[1] * r[0])) / 6.0
    return v, t if volume > 0.0 else [(a, c, b) for a, b, c in t]


def normal(p, q, r):
    u = [q[i] - p[i] for i in range(3)]
    w = [r[i] - p[i] for i in range(3)]
    n = (u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0])
    length = math.sqrt(sum(c * c for c in n))
    return tuple(c / length for c in n)


def write_stl(path, vertices, triangles):
    data = bytearray(b"graspsynth make_meshes.py".ljust(80, b" "))
    data += struct.pack("<I", len(triangles))
    for tri in triangles:
        p, q, r = (vertices[i] for i in tri)
        data += struct.pack("<12fH", *normal(p, q, r), *p, *q, *r, 0)
    write(path, bytes(data))


def write_obj(path, vertices, triangles):
    lines = ["# graspsynth make_meshes.py"]
    lines += ["v %.9g %.9g %.9g" % p for p in vertices]
    lines += ["f %d %d %d" % tuple(i + 1 for i in tri) for tri in triangles]
    write(path, ("\n".join(lines) + "\n").encode())


def write(path, data):
    tmp = path + ".tmp"
    with open(tmp, "wb") as f:
        f.write(data)
    os.replace(tmp, path)
    print("wrote", os.path.relpath(path))


def main():
    os.makedirs(HERE, exist_ok=True)
    write_stl(os.path.join(HERE, "pan_body.stl"), *prism(64, 0.08, 0.05))
    write_obj(os.path.join(HERE, "pan_handle.obj"), *box(0.30, 0.024, 0.024))
    # the mug (models/README.md, "The mug"): O at the body's centre.
    radius, inner, height, bottom = 0.040, 0.0355, 0.090, 0.006
    write_stl(os.path.join(HERE, "mug_body.stl"),
              *revolved(48, [(0.0, -height / 2), (radius, -height / 2), (radius, height / 2),
                             (inner, height / 2), (inner, -height / 2 + bottom),
                             (0.0, -height / 2 + bottom)]))
    loop = [(0.0385 + 0.034 * math.cos(a), 0.028 * math.sin(a))
            for a in (math.pi / 2 - math.pi * k / 24 for k in range(25))]
    write_obj(os.path.join(HERE, "mug_handle.obj"), *swept(loop, 0.010, 0.012))


if __name__ == "__main__":
    main()
