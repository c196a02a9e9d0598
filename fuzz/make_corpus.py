#!/usr/bin/env python3
"""Writes the fuzz targets' seed corpora (fuzz/corpus/NAME/) from the shipped files, made small
so that libFuzzer mutates them quickly: every format's real shape, nothing invented by hand
except the teleoperation packets (built here byte by byte, as docs/formats.md lays them out)
and the HTTP requests. Deterministic; run it again after a format changes:

    python3 fuzz/make_corpus.py

Inputs a fuzzing run found useful, and every input that once crashed a target, are added to the
corpus by hand (named found_*/crash_*) and are kept by this script.
"""
import glob
import hashlib
import hmac
import json
import os
import shutil
import struct
import zlib

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
CORPUS = os.path.join(ROOT, "fuzz", "corpus")


def read(path, mode="r"):
    with open(os.path.join(ROOT, path), mode) as f:
        return f.read()


def put(target, name, data):
    folder = os.path.join(CORPUS, target)
    os.makedirs(folder, exist_ok=True)
    with open(os.path.join(folder, name), "wb") as f:
        f.write(data.encode() if isinstance(data, str) else data)


def reset(target):
    """Removes the generated seeds of `target`, keeping the found_* and crash_* inputs."""
    folder = os.path.join(CORPUS, target)
    for path in glob.glob(os.path.join(folder, "*")):
        if not os.path.basename(path).startswith(("found_", "crash_")):
            os.remove(path)


def short_log(path, keep_every=40):
    """A demonstration log with its header, every keep_every-th row and every row with an event."""
    lines = read(path).splitlines()
    header = [l for l in lines if l.startswith("#")]
    table = [l for l in lines if not l.startswith("#")]
    columns, rows = table[0], table[1:]
    event = columns.split(",").index("event")
    kept = [r for i, r in enumerate(rows)
            if i % keep_every == 0 or r.split(",")[event] not in ("", "0") or i == len(rows) - 1]
    return "\n".join(header + [columns] + kept) + "\n"


def demo_logs():
    reset("demo_log")
    demos = sorted(glob.glob(os.path.join(ROOT, "learning_data", "demos", "*.csv")))
    for path in demos[:1] + demos[-1:]:
        put("demo_log", os.path.basename(path), short_log(os.path.relpath(path, ROOT)))
    put("demo_log", "empty.csv", "")


def json_files():
    reset("scene")
    put("scene", "scene.json", read("models/scene.json"))
    scene = json.loads(read("models/scene.json"))
    scene["object"] = "objects/mug.json"
    put("scene", "scene_mug.json", json.dumps(scene, indent=1))
    # paths that must be refused, not cut or read: a NUL inside, and an endless device.
    scene["object"] = "objects/pan.json\u0000.stl"
    put("scene", "scene_nul_object.json", json.dumps(scene, indent=1))
    scene["object"] = "/dev/zero"
    put("scene", "scene_device_object.json", json.dumps(scene, indent=1))
    reset("object")
    for path in sorted(glob.glob(os.path.join(ROOT, "models", "objects", "*.json"))):
        put("object", os.path.basename(path), read(os.path.relpath(path, ROOT)))
    mesh = json.loads(read("models/objects/pan_mesh.json"))
    mesh["parts"][0]["file"] = "meshes/pan_body.stl\u0000.obj"
    put("object", "pan_mesh_nul_file.json", json.dumps(mesh, indent=1))
    reset("operator")
    put("operator", "pan.json", read("learning_data/demos/operator.json"))
    for path in sorted(glob.glob(os.path.join(ROOT, "learning_data", "objects", "*", "demos",
                                              "operator.json"))):
        name = path.split(os.sep)[-3]
        put("operator", name + ".json", read(os.path.relpath(path, ROOT)))
    reset("calibration")
    put("calibration", "calibration.json", read("examples/teleop_calibration.json"))


def placements():
    """The placements of a library over placements as (x, y, theta) doubles, a query last: the
    shape of the shipped grid (3 x 3 positions, 20..100 deg), and a line up to roundoff."""
    reset("placements")
    triples = [(x, y, t * 3.141592653589793 / 180) for x in (-0.30, -0.25, -0.20)
               for y in (0.80, 0.85, 0.90) for t in range(20, 101, 10)]
    query = [(-0.26, 0.855, 0.9)]
    put("placements", "grid.bin", b"".join(struct.pack("<3d", *p) for p in triples + query))
    line = [(-0.25 + (i % 3 - 1) * 1e-16, y, t * 3.141592653589793 / 180)
            for i, (y, t) in enumerate((y, t) for y in (0.80, 0.85, 0.90) for t in (20, 60, 100))]
    put("placements", "line_up_to_roundoff.bin",
        b"".join(struct.pack("<3d", *p) for p in line + query))


def library():
    """The shipped library cut to two entries, their scores and every 4th waypoint."""
    reset("library")
    lib = json.loads(read("learning_data/library.json"))
    lib["entries"] = lib["entries"][:2]
    files = {e["file"] for e in lib["entries"]}
    lib["scores"] = [s for s in lib["scores"] if s["file"] in files]
    for e in lib["entries"]:
        w = e["motion"]["waypoints"]
        e["motion"]["waypoints"] = w[::4] + ([w[-1]] if (len(w) - 1) % 4 else [])
    put("library", "two_entries.json", json.dumps(lib, indent=1))
    lib["entries"] = []
    put("library", "no_entries.json", json.dumps(lib, indent=1))


def trajectories():
    reset("trajectory")
    t = json.loads(read("examples/grasp_60deg.json"))
    t["samples"] = t["samples"][::10] + [t["samples"][-1]]
    t["waypoints"] = [w for w in t["waypoints"] if w["t"] <= t["samples"][-1]["t"]]
    put("trajectory", "trajectory.json", json.dumps(t, indent=1))
    grasp = {"format": "graspsynth-grasp/1", "trajectory": t}
    put("trajectory", "grasp.json", json.dumps(grasp, indent=1))


def meshes():
    reset("mesh")
    put("mesh", "pan_body.stl", b"\x00" + read("models/objects/meshes/pan_body.stl", "rb"))
    put("mesh", "pan_handle.obj", b"\x01" + read("models/objects/meshes/pan_handle.obj", "rb"))
    tetra = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1)]
    faces = [(0, 2, 1), (0, 1, 3), (0, 3, 2), (1, 2, 3)]
    ascii_stl = "solid t\n"
    for f in faces:
        ascii_stl += " facet normal 0 0 0\n  outer loop\n"
        for v in f:
            ascii_stl += "   vertex %g %g %g\n" % tetra[v]
        ascii_stl += "  endloop\n endfacet\n"
    put("mesh", "tetra_ascii.stl", b"\x00" + (ascii_stl + "endsolid t\n").encode())
    obj = "".join("v %g %g %g\n" % v for v in tetra)
    obj += "".join("f %d/1 %d/1 %d/1\n" % tuple(i + 1 for i in f) for f in faces)
    put("mesh", "tetra.obj", b"\x01" + obj.encode())


def urdf():
    reset("urdf")
    put("urdf", "pa10_gifu3.urdf", read("models/pa10_gifu3.urdf"))


def robot_files():
    reset("robot_file")
    for name in ("pa10_gifu3", "iiwa14_allegro"):
        robot = json.loads(read("models/%s.robot.json" % name))
        put("robot_file", name + ".robot.json", json.dumps(robot, indent=1))
        # the arm part only, the smallest file the reader takes
        arm_only = {k: robot[k] for k in ("format", "name", "urdf", "arm")}
        put("robot_file", name + "_arm.robot.json", json.dumps(arm_only, indent=1))
    arm_only["arm"]["flange_link"] = "A6_link"
    put("robot_file", "iiwa_six_joints.robot.json", json.dumps(arm_only, indent=1))


KEY = b"\x24" * 32  # fuzz/gstp_fuzz.cpp's key


def packet(kind, seq, payload, authenticated):
    head = b"GSTP" + struct.pack("<HHIId", 2 if authenticated else 1, kind, seq, len(payload), 1.5)
    body = head + payload
    body += struct.pack("<I", zlib.crc32(body) & 0xFFFFFFFF)
    if authenticated:
        body += hmac.new(KEY, body, hashlib.sha256).digest()
    return body


def gstp():
    reset("gstp")
    fingers = [0.1 * i for i in range(16)]
    command = struct.pack("<7dBBH16d", 0.1, -0.2, 0.3, 1, 0, 0, 0, 1, 1, 0, *fingers)
    glove = struct.pack("<7dBBH16d", 0, 0, 0, 1, 0, 0, 0, 0, 2, 0, *([0.5] * 14 + [0, 0]))
    state = struct.pack("<7d16d3d4ddII", *([0.2] * 7), *([0.1] * 16), -0.25, 0.85, 0.025,
                        1, 0, 0, 0, 60.0, 3, 2)
    # the first byte: even, the receiver has no key; odd, it has fuzz/gstp_fuzz.cpp's.
    for auth in (False, True):
        prefix = b"\x01" if auth else b"\x00"
        tag = "v2" if auth else "v1"
        put("gstp", "command_%s.bin" % tag, prefix + packet(1, 7, command, auth))
        put("gstp", "glove_%s.bin" % tag, prefix + packet(1, 8, glove, auth))
        put("gstp", "state_%s.bin" % tag, prefix + packet(2, 9, state, auth))
        put("gstp", "end_%s.bin" % tag, prefix + packet(3, 10, b"", auth))


def http():
    reset("http")
    put("http", "get.txt", "GET /frame HTTP/1.1\r\nHost: 127.0.0.1:8765\r\nConnection: keep-alive\r\n\r\n")
    put("http", "head.txt", "HEAD /index.html?x=1 HTTP/1.0\r\n\r\n")
    put("http", "lf.txt", "GET / HTTP/1.1\nHost: a\n\n")
    put("http", "body.txt", "POST /scene.json HTTP/1.1\r\nContent-Length: 4\r\n\r\nabcd")


def text():
    reset("text")
    put("text", "orientations.txt", "20,30:100:10,65.5")
    put("text", "numbers.txt", "0.1 0.2, -0.3 1e-3 0 0 0")
    put("text", "camera.txt", "1.2,-0.4,0.9,-0.25,0.85,0.1")
    put("text", "key.txt", "# key\n" + "0123456789abcdef" * 4 + "\n")


def main():
    demo_logs()
    json_files()
    placements()
    library()
    trajectories()
    meshes()
    urdf()
    robot_files()
    gstp()
    http()
    text()
    total = sum(os.path.getsize(p) for p in glob.glob(os.path.join(CORPUS, "*", "*")))
    print("fuzz/corpus: %d files, %d kB" % (len(glob.glob(os.path.join(CORPUS, "*", "*"))),
                                           total // 1024))


if __name__ == "__main__":
    main()
