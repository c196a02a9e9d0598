#!/usr/bin/env python3
"""The browser viewer in a real headless browser.

Starts `graspsynth view` three times and has Debian's chromium take a screenshot of the page
(WebGL on SwiftShader) at the end of each replay: a small generated trajectory played as joint
commands (--joints-only: the arm holding the hand above the pan's handle); a synthesized grasp
at 60 deg played as simulated (the viewer runs its nominal trial: the pan lifted); and the trial
record of a grasp that fails (the line principle at 65 deg, written with --force: the pan
dropped). It decodes each PNG (zlib only) and checks that the robot and the pan are drawn where
the scene's camera puts them: the pixels of the arm's blue and the hand's teal, and those of the
pan's orange (viewer/viewer.js), must cover the silhouettes predicted from /scene.json's shapes
and camera and /frame's poses (intersection over union >= MIN_OVERLAP), and the image must not
be blank. For the physics replays the pan must be where the trial record has it at the end
(lifted at least 5 cm, or below that for the failure), the outcome banner in its colour (green
success, red FAILED with the outcome) and the contact dots drawn. SIGTERM must stop graspsynth
cleanly each time.

Exit status: 0 pass, 1 fail, 77 skip (chromium is not installed; scripts/setup.sh installs it).

    viewer_screenshot_test.py --graspsynth build/apps/graspsynth [--output shot.png]
        [--output-lift lift.png] [--output-drop drop.png] [--size 800x600] [--camera E,T]
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
# hue ranges of the physics replay's marks (viewer/index.html, viewer/viewer.js): the outcome
# banner's green and red, the contact dots' magenta.
MARKS = {"success": (115, 135), "failure": (0, 6), "contact": (290, 310)}
# least overlap (intersection over union) of the drawn and the predicted silhouettes.
MIN_OVERLAP = 0.85
# a lifted pan: its centre this far above its rest height (DESIGN.md's success threshold), m.
LIFT = 0.05


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
    """'arm', 'hand', 'object', a mark of MARKS or None by hue, for saturated, not too dark
    pixels."""
    h, s, v = colorsys.rgb_to_hsv(*(c / 255.0 for c in rgb))
    if s < 0.35 or v < 0.25:
        return None
    hue = h * 360.0
    for name, (lo, hi) in list(HUES.items()) + list(MARKS.items()):
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


def run_graspsynth(graspsynth, args, allowed=(0,)):
    """Runs `graspsynth ARGS`; fails unless its exit status is in `allowed`."""
    done = subprocess.run([graspsynth] + args, stdout=subprocess.PIPE, stderr=subprocess.STDOUT)
    if done.returncode not in allowed:
        fail(f"graspsynth {' '.join(args)} exited {done.returncode}:\n"
             f"{done.stdout.decode(errors='replace')[-3000:]}")
    return done.stdout.decode(errors="replace")


def screenshot(chromium, graspsynth, view_args, work, name, output, size):
    """Serves `graspsynth view VIEW_ARGS`, has chromium take a screenshot once the replay has
    ended; returns (png path, /scene.json, the last /frame). SIGTERM must stop the viewer."""
    view_err = open(os.path.join(work, f"{name}.err"), "w+")
    view = subprocess.Popen([graspsynth, "view"] + view_args +
                            ["--port", "0", "--speed", "100", "--hold", "60", "--exit-after", "90"],
                            stdout=subprocess.DEVNULL, stderr=view_err)
    try:
        url = None
        deadline = time.time() + 60
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

        shot = os.path.join(work, f"{name}.png")
        env = dict(os.environ, HOME=work)
        started = time.time()
        flags = [f for f in CHROMIUM_FLAGS if not f.startswith("--window-size")]
        browser = subprocess.run(
            [chromium] + flags +
            [f"--window-size={size[0]},{size[1]}",
             f"--user-data-dir={os.path.join(work, 'profile_' + name)}", f"--screenshot={shot}",
             url],
            env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, timeout=90)
        print(f"{name}: chromium took {time.time() - started:.1f} s")
        if not os.path.exists(shot):
            fail(f"chromium wrote no screenshot (status {browser.returncode}):\n"
                 f"{browser.stdout.decode(errors='replace')[-3000:]}")
        if output:
            shutil.copyfile(shot, output)
            print(f"screenshot: {output}")

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
    if "replay done" not in frame["text"]:
        fail(f"{name}: the screenshot's frame is not the replay's end: {frame['text']!r}")
    return shot, scene, frame


def check_drawing(name, shot, scene, frame, size):
    """The robot and the pan drawn where the frame's poses put them; the pixel counts by hue."""
    width, height, rows = read_png(shot)
    if (width, height) != size:
        fail(f"{name}: screenshot is {width}x{height}, not {size[0]}x{size[1]}")
    colours = set()
    found = {name: [] for name in list(HUES) + list(MARKS)}
    for y, row in enumerate(rows):
        for x, rgb in enumerate(row):
            colours.add(rgb)
            kind = classify(rgb)
            if kind:
                found[kind].append((x, y))
    print(f"{name}: {len(colours)} colours; pixels: " +
          ", ".join(f"{kind} {len(p)}" for kind, p in found.items()))
    if len(colours) < 100:
        fail(f"{name}: the screenshot is (nearly) blank: {len(colours)} colours")

    # the silhouettes the scene and the frame predict (links in the order of
    # viewer/viewer_scene.hpp, the camera of the scene) must match the pixels of the
    # robot's and the pan's colours: a wrong pose, axis or camera moves or turns them.
    links = frame["links"]
    if len(links) != len(scene["links"]):
        fail(f"{name}: the frame has {len(links)} links, the scene {len(scene['links'])}")
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
    # a pan in the hand is partly hidden by the fingers, and the contact dots are drawn over
    # both: the pan is compared outside the robot's predicted silhouette, and both outside the
    # dots (with their antialiased rims).
    dots = {(x + dx, y + dy) for x, y in found["contact"] for dx in (-1, 0, 1) for dy in (-1, 0, 1)}
    hidden = {"robot": dots, "object": dots | predicted["robot"]}
    for part in predicted:
        predicted[part] -= hidden[part]
        observed[part] -= hidden[part]
        overlap = len(predicted[part] & observed[part]) / len(predicted[part] | observed[part])
        print(f"{name}: {part}: {len(predicted[part])} pixels predicted, "
              f"{len(observed[part])} drawn, overlap (IoU) {overlap:.2f}")
        if overlap < MIN_OVERLAP:
            fail(f"{name}: {part}: the drawn pixels overlap the predicted silhouette by "
                 f"{overlap:.2f} (< {MIN_OVERLAP})")
    for part in HUES:
        if len(found[part]) < 100:
            fail(f"{name}: {part}: only {len(found[part])} pixels of its colour")
    return found


def check_physics(name, found, frame, record, lifted):
    """A physics replay's end: the pan where the simulation put it (lifted, or at the table),
    the outcome in the frame and its banner (green or red) on the page, the contacts drawn."""
    rest_z = record["frames"][0]["object_position"][2]
    end_z = frame["object"][2]
    print(f"{name}: pan centre {1000 * (end_z - rest_z):.1f} mm above its rest height at the end "
          f"(record: {1000 * (record['frames'][-1]['object_position'][2] - rest_z):.1f} mm); "
          f"outcome {frame.get('outcome')}")
    outcome = frame.get("outcome")
    if outcome is None:
        fail(f"{name}: the replay's last frame shows no outcome")
    if outcome["success"] != record["success"] or outcome["success"] != lifted:
        fail(f"{name}: outcome {outcome} but the trial record says success = {record['success']}")
    if abs(end_z - record["frames"][-1]["object_position"][2]) > 0.005:
        fail(f"{name}: the viewer's pan is at z = {end_z:.4f} m, the trial record's at "
             f"{record['frames'][-1]['object_position'][2]:.4f} m")
    if lifted and not end_z > rest_z + LIFT:
        fail(f"{name}: the pan is not lifted: {1000 * (end_z - rest_z):.1f} mm above its rest")
    if not lifted:
        if not end_z < rest_z + LIFT:
            fail(f"{name}: the failed replay's pan is {1000 * (end_z - rest_z):.1f} mm up")
        if not outcome["text"].startswith("FAILED (" + record["outcome"] + ")"):
            fail(f"{name}: the banner says {outcome['text']!r}")
    banner = "success" if lifted else "failure"
    other = "failure" if lifted else "success"
    if len(found[banner]) < 1000 or len(found[other]) > 50:
        fail(f"{name}: the {banner} banner is not shown: {len(found[banner])} pixels of its "
             f"colour, {len(found[other])} of the other's")
    if frame.get("contacts") and len(found["contact"]) < 4:
        fail(f"{name}: {len(frame['contacts'])} contacts in the frame, "
             f"{len(found['contact'])} pixels of the contact dots")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--graspsynth", required=True)
    parser.add_argument("--output", help="keep the joint replay's screenshot here")
    parser.add_argument("--output-lift", help="keep the lifting replay's screenshot here")
    parser.add_argument("--output-drop", help="keep the failed replay's screenshot here")
    parser.add_argument("--size", default=f"{WIDTH}x{HEIGHT}", help="window size, WxH")
    parser.add_argument("--camera", help="view's --camera for the physics replays (EX,EY,EZ,TX,TY,TZ)")
    args = parser.parse_args()
    camera = ["--camera", args.camera] if args.camera else []
    size = tuple(int(v) for v in args.size.split("x"))

    chromium = find_chromium()
    if chromium is None:
        print("SKIP: chromium is not installed (scripts/setup.sh installs it)")
        return SKIP

    work = tempfile.mkdtemp(prefix="graspsynth_viewer_")
    try:
        # 1. joint commands alone (--joints-only): the arm above the handle, the pan at rest.
        trajectory = os.path.join(work, "grasp.json")
        with open(trajectory, "w") as f:
            json.dump({"format": "graspsynth-trajectory/1", "theta_deg": 60.0,
                       "samples": [{"t": 0.0, "arm": ARM, "hand": HAND_OPEN},
                                   {"t": 0.5, "arm": ARM, "hand": HAND_CLOSING}]}, f)
        shot, scene, frame = screenshot(chromium, args.graspsynth,
                                        ["--trajectory", trajectory, "--joints-only"], work,
                                        "joints", args.output, size)
        check_drawing("joints", shot, scene, frame, size)
        if "outcome" in frame or "contacts" in frame:
            fail("a replay of joint commands shows an outcome or contacts")

        # 2. physics: a grasp synthesized for 60 deg, which lifts the pan; the viewer runs its
        # nominal trial itself from the grasp file.
        lift = os.path.join(work, "lift.json")
        run_graspsynth(args.graspsynth, ["synthesize", "--theta", "60", "--perturb", "0",
                                         "--out", lift])
        lift_record = os.path.join(work, "lift_trial.json")
        run_graspsynth(args.graspsynth, ["simulate", lift, "--trial-record", lift_record])
        shot, scene, frame = screenshot(chromium, args.graspsynth, ["--trajectory", lift] + camera, work,
                                        "lift", args.output_lift, size)
        found = check_drawing("lift", shot, scene, frame, size)
        with open(lift_record) as f:
            record = json.load(f)
        record["success"] = record["outcome"] == "success"
        check_physics("lift", found, frame, record, lifted=True)

        # 3. physics, a failure: the study's line-principle grasp at 65 deg (its nominal trial
        # drops the pan: experiments/results/study_report.md), written with --force, simulated
        # into a trial record that the viewer plays.
        drop = os.path.join(work, "drop.json")
        run_graspsynth(args.graspsynth, ["synthesize", "--theta", "65", "--method", "line",
                                         "--perturb", "0", "--force", "--out", drop], (0, 1))
        drop_record = os.path.join(work, "drop_trial.json")
        run_graspsynth(args.graspsynth, ["simulate", drop, "--trial-record", drop_record], (1,))
        shot, scene, frame = screenshot(chromium, args.graspsynth, ["--trial", drop_record] + camera, work,
                                        "drop", args.output_drop, size)
        found = check_drawing("drop", shot, scene, frame, size)
        with open(drop_record) as f:
            record = json.load(f)
        record["success"] = record["outcome"] == "success"
        check_physics("drop", found, frame, record, lifted=False)
        print("PASS")
        return 0
    finally:
        shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    sys.exit(main())
