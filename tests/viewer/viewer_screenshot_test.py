#!/usr/bin/env python3
"""The browser viewer in a real headless browser.

Starts `graspsynth view` on a small generated trajectory (the arm holding the hand above the
pan's handle), has Debian's chromium take a screenshot of the page (WebGL on SwiftShader),
decodes the PNG (zlib only) and checks that the robot and the pan are drawn where the scene's
camera puts them: the pixels of the arm's blue and the hand's teal, and those of the pan's orange
(viewer/viewer.js), must cover the silhouettes predicted from /scene.json's shapes and camera and
/frame's link poses (intersection over union >= MIN_OVERLAP), and the image must not be blank.
Then SIGTERM must stop graspsynth cleanly.

Exit status: 0 pass, 1 fail, 77 skip (chromium is not installed; scripts/setup.sh installs it).

    viewer_screenshot_test.py --graspsynth build/apps/graspsynth [--output shot.png]
"""

import argparse
import colorsys
import json
import math
import os
import shutil
import signal
import struct
import subprocess
import sys
import tempfile
import time
import urllib.error
import urllib.request
import zlib

SKIP = 77
WIDTH, HEIGHT = 800, 600

# the arm at a pre-grasp above the handle at theta = 60 deg: `graspsynth ik --branch 1,1,1` of
# the wrist 8 cm above the Table I grasp of `graspsynth run`, arm angle 0.
ARM = [1.9572818780320826, 0.8324773213285145, 0.0, 1.9241556706877925, -1.76296224149854,
       1.4935677146794129, -0.3775127214907898]
HAND_OPEN = [1.5, 0, 0, 0] + [0, 0, 0] * 4
HAND_CLOSING = [1.5, 0, 0.5, 0.2] + [0, 0.9, 0.4] * 4

CHROMIUM_FLAGS = [
    "--headless", "--no-sandbox", "--disable-gpu", "--enable-unsafe-swiftshader", "--disable-quic",
    "--no-first-run", "--disable-background-networking", "--disable-component-update",
    "--disable-sync", "--hide-scrollbars", f"--window-size={WIDTH},{HEIGHT}",
    "--virtual-time-budget=4000",
]

# hue ranges (degrees) of the colours of viewer/viewer.js under its lights.
HUES = {"arm": (200, 235), "hand": (155, 190), "object": (12, 40)}
# least overlap (intersection over union) of the drawn and the predicted silhouettes.
MIN_OVERLAP = 0.85


def fail(message):
    print(f"FAIL: {message}", file=sys.stderr)
    sys.exit(1)


def find_chromium():
    for name in (os.environ.get("GRASPSYNTH_CHROMIUM"), "chromium", "chromium-browser"):
        if name and shutil.which(name):
            return shutil.which(name)
    return None


def read_png(path):
    """(width, height, rows of RGB tuples) of an 8-bit RGB or RGBA PNG, without libraries."""
    with open(path, "rb") as f:
        data = f.read()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        fail(f"{path} is not a PNG")
    pos, idat, header = 8, b"", None
    while pos < len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        chunk = data[pos + 8:pos + 8 + length]
        pos += 12 + length
        if kind == b"IHDR":
            header = struct.unpack(">IIBBBBB", chunk)
        elif kind == b"IDAT":
            idat += chunk
        elif kind == b"IEND":
            break
    width, height, depth, colour, _, _, interlace = header
    if depth != 8 or colour not in (2, 6) or interlace != 0:
        fail(f"unexpected PNG layout: depth {depth}, colour type {colour}, interlace {interlace}")
    channels = 3 if colour == 2 else 4
    raw = zlib.decompress(idat)
    stride = width * channels
    rows, previous = [], bytearray(stride)
    for y in range(height):
        start = y * (stride + 1)
        kind, line = raw[start], bytearray(raw[start + 1:start + 1 + stride])
        for i in range(stride):
            left = line[i - channels] if i >= channels else 0
            up = previous[i]
            corner = previous[i - channels] if i >= channels else 0
            if kind == 1:
                line[i] = (line[i] + left) & 0xFF
            elif kind == 2:
                line[i] = (line[i] + up) & 0xFF
            elif kind == 3:
                line[i] = (line[i] + (left + up) // 2) & 0xFF
            elif kind == 4:
                p = left + up - corner
                pa, pb, pc = abs(p - left), abs(p - up), abs(p - corner)
                predictor = left if pa <= pb and pa <= pc else (up if pb <= pc else corner)
                line[i] = (line[i] + predictor) & 0xFF
        rows.append([tuple(line[x * channels:x * channels + 3]) for x in range(width)])
        previous = line
    return width, height, rows


def classify(rgb):
    """'arm', 'hand', 'object' or None by hue, for saturated, not too dark pixels."""
    h, s, v = colorsys.rgb_to_hsv(*(c / 255.0 for c in rgb))
    if s < 0.35 or v < 0.25:
        return None
    hue = h * 360.0
    for name, (lo, hi) in HUES.items():
        if lo <= hue <= hi:
            return name
    return None


def project(camera, point, width, height):
    """Pixel (x, y) of world point under the page's camera (three.js PerspectiveCamera, z up)."""
    eye, target = camera["eye"], camera["target"]
    forward = [t - e for t, e in zip(target, eye)]
    norm = math.sqrt(sum(c * c for c in forward))
    forward = [c / norm for c in forward]
    right = [forward[1], -forward[0], 0.0]  # forward x z_up
    norm = math.sqrt(sum(c * c for c in right))
    right = [c / norm for c in right]
    up = [right[1] * forward[2] - right[2] * forward[1], right[2] * forward[0] - right[0] * forward[2],
          right[0] * forward[1] - right[1] * forward[0]]
    d = [p - e for p, e in zip(point, eye)]
    depth = sum(a * b for a, b in zip(d, forward))
    half = math.tan(math.radians(camera["fov_deg"]) / 2)
    x_ndc = sum(a * b for a, b in zip(d, right)) / depth / (half * width / height)
    y_ndc = sum(a * b for a, b in zip(d, up)) / depth / half
    return (width / 2 * (1 + x_ndc), height / 2 * (1 - y_ndc))


def rotate(q, v):
    """v turned by the unit quaternion q = (w, x, y, z)."""
    w, x, y, z = q
    tx, ty, tz = 2 * (y * v[2] - z * v[1]), 2 * (z * v[0] - x * v[2]), 2 * (x * v[1] - y * v[0])
    return [v[0] + w * tx + y * tz - z * ty, v[1] + w * ty + z * tx - x * tz,
            v[2] + w * tz + x * ty - y * tx]


def apply_pose(pose, point):
    """X * p for a pose [x, y, z, qw, qx, qy, qz]."""
    turned = rotate(pose[3:], point)
    return [turned[i] + pose[i] for i in range(3)]


def inside_points(shape):
    """Points filling a shape (a grid of about 1 cm, finer for thin shapes), in its frame."""
    if shape["kind"] == "box":
        half = [c / 2 for c in shape["size"]]
    else:
        r = shape["radius"]
        length = shape.get("length", 0.0)
        cap = r if shape["kind"] in ("capsule", "sphere") else 0.0
        half = [r, r, length / 2 + cap]
    step = min([0.01] + [h / 2 for h in half if h > 0])

    def ticks(h):
        n = max(1, int(math.ceil(2 * h / step)))
        return [-h + 2 * h * (i + 0.5) / n for i in range(n)]

    points = []
    for x in ticks(half[0]):
        for y in ticks(half[1]):
            for z in ticks(half[2]):
                kind = shape["kind"]
                if kind == "box":
                    inside = True
                elif kind == "cylinder":
                    inside = x * x + y * y <= r * r
                elif kind == "sphere":
                    inside = x * x + y * y + z * z <= r * r
                else:  # capsule: within r of the straight part
                    dz = max(0.0, abs(z) - length / 2)
                    inside = x * x + y * y + dz * dz <= r * r
                if inside:
                    points.append([x, y, z])
    return points

def fetch(url):
    with urllib.request.urlopen(url, timeout=5) as reply:
        return json.loads(reply.read())


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--graspsynth", required=True)
    parser.add_argument("--output", help="keep the screenshot here")
    args = parser.parse_args()

    chromium = find_chromium()
    if chromium is None:
        print("SKIP: chromium is not installed (scripts/setup.sh installs it)")
        return SKIP

    work = tempfile.mkdtemp(prefix="graspsynth_viewer_")
    try:
        trajectory = os.path.join(work, "grasp.json")
        with open(trajectory, "w") as f:
            json.dump({"format": "graspsynth-trajectory/1", "theta_deg": 60.0,
                       "samples": [{"t": 0.0, "arm": ARM, "hand": HAND_OPEN},
                                   {"t": 0.5, "arm": ARM, "hand": HAND_CLOSING}]}, f)
        view_err = open(os.path.join(work, "view.err"), "w+")
        view = subprocess.Popen([args.graspsynth, "view", "--trajectory", trajectory, "--port", "0",
                                 "--speed", "100", "--hold", "60", "--exit-after", "90"],
                                stdout=subprocess.DEVNULL, stderr=view_err)
        try:
            url = None
            deadline = time.time() + 30
            while url is None and time.time() < deadline and view.poll() is None:
                time.sleep(0.05)
                view_err.seek(0)
                for line in view_err.read().splitlines():
                    if "open http://" in line:
                        url = line.split("open ", 1)[1].split()[0]
            if url is None:
                view_err.seek(0)
                fail(f"graspsynth view printed no URL:\n{view_err.read()}")

            try:
                urllib.request.urlopen(url + "three.module.js", timeout=5).close()
            except urllib.error.HTTPError as error:
                fail(f"{url}three.module.js: {error.read().decode(errors='replace')}")

            shot = os.path.join(work, "shot.png")
            env = dict(os.environ, HOME=work)
            started = time.time()
            browser = subprocess.run(
                [chromium] + CHROMIUM_FLAGS +
                [f"--user-data-dir={os.path.join(work, 'profile')}", f"--screenshot={shot}", url],
                env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, timeout=90)
            print(f"chromium took {time.time() - started:.1f} s")
            if not os.path.exists(shot):
                fail(f"chromium wrote no screenshot (status {browser.returncode}):\n"
                     f"{browser.stdout.decode(errors='replace')[-3000:]}")
            if args.output:
                shutil.copyfile(shot, args.output)
                print(f"screenshot: {args.output}")

            scene = fetch(url + "scene.json")
            frame = fetch(url + "frame")
        finally:
            view.send_signal(signal.SIGTERM)
            try:
                status = view.wait(timeout=20)
            except subprocess.TimeoutExpired:
                view.kill()
                status = "killed after SIGTERM was ignored"
        view_err.seek(0)
        view_log = view_err.read()
        if status != 0 or "stopped by a signal" not in view_log:
            fail(f"graspsynth view did not stop cleanly on SIGTERM (status {status}):\n{view_log}")

        width, height, rows = read_png(shot)
        if (width, height) != (WIDTH, HEIGHT):
            fail(f"screenshot is {width}x{height}, not {WIDTH}x{HEIGHT}")
        colours = set()
        found = {name: [] for name in HUES}
        for y, row in enumerate(rows):
            for x, rgb in enumerate(row):
                colours.add(rgb)
                name = classify(rgb)
                if name:
                    found[name].append((x, y))
        print(f"{len(colours)} colours; pixels: " +
              ", ".join(f"{name} {len(p)}" for name, p in found.items()))
        if len(colours) < 100:
            fail(f"the screenshot is (nearly) blank: {len(colours)} colours")

        # the silhouettes the scene and the frame predict (links in the order of
        # viewer/viewer_scene.hpp, the camera of the scene) must match the pixels of the
        # robot's and the pan's colours: a wrong pose, axis or camera moves or turns them.
        links = frame["links"]
        if len(links) != len(scene["links"]):
            fail(f"the frame has {len(links)} links, the scene {len(scene['links'])}")
        predicted = {"robot": set(), "object": set()}
        bodies = list(zip(scene["links"], links)) + [(scene["object"], frame["object"])]
        for body, pose in bodies:
            target = predicted["object" if body["group"] == "object" else "robot"]
            for shape in body["shapes"]:
                for point in inside_points(shape):
                    world = apply_pose(pose, apply_pose(shape["pose"], point))
                    x, y = project(scene["camera"], world, width, height)
                    target.update((round(x) + dx, round(y) + dy) for dx in (-1, 0, 1)
                                  for dy in (-1, 0, 1) if 0 <= round(x) + dx < width
                                  and 0 <= round(y) + dy < height)
        observed = {"robot": set(found["arm"]) | set(found["hand"]), "object": set(found["object"])}
        for name in predicted:
            overlap = len(predicted[name] & observed[name]) / len(predicted[name] | observed[name])
            print(f"{name}: {len(predicted[name])} pixels predicted, {len(observed[name])} drawn, "
                  f"overlap (IoU) {overlap:.2f}")
            if overlap < MIN_OVERLAP:
                fail(f"{name}: the drawn pixels overlap the predicted silhouette by {overlap:.2f} "
                     f"(< {MIN_OVERLAP})")
        for name in HUES:
            if len(found[name]) < 100:
                fail(f"{name}: only {len(found[name])} pixels of its colour")
        print("PASS")
        return 0
    finally:
        shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    sys.exit(main())
