#!/usr/bin/env python3
"""Writes the meshes of the shipped objects (models/objects/meshes/) from their dimensions.

Run it from anywhere: python3 models/objects/make_meshes.py. Each mesh is closed, with its
triangles counter-clockwise seen from outside, in metres in its part frame (the frame the
object file places with "position" and "rpy_deg"). The same dimensions give the same bytes.

  pan_body.stl    the pan's body, a cylinder of radius 0.08 m and height 0.05 m, as a
                  64-sided prism (binary STL)
  pan_handle.obj  the pan's handle, a 0.30 x 0.024 x 0.024 m bar (OBJ)
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


if __name__ == "__main__":
    main()
