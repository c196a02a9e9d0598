#!/usr/bin/env python3
"""Writes a synthetic operator (graspsynth-operator/1) for an object with a grip axis.

The pan's operator (learning_data/demos/operator.json) was calibrated to the paper's Table I;
another object has no such table, so its operator is planned from the object's geometry: at
every orientation the hand closes on the grip axis (the object file's "handle": a handle's bar,
or a line through the body) --grip-radius from the object centre, crossing it squarely, with
the wrist on one side of it (the grip's reach, hook_reach, from the axis). Everything else -
the motion and the variability - is the pan operator's top-level settings (its per-strategy
grips are not copied). One strategy per orientation; the reach enters the grasp region at the
wrist's own polar angle.

The grip (--grip):
  hook   the pan operator's hook: palm down, the fingers curled around the far side of the
         bar and under it (a handle);
  pinch  models/README.md's pinch: the fingertips press the far face and the thumb tip the near
         face, contact normals horizontal, only friction against the weight (an object held by
         its body); reach 0.103 m and depth 0.086 m put a 24 mm bar between the pads.
--hook-reach and --wrist-above-handle move the axis in the hand (a thicker object: a longer
reach, so that the thumb tip still meets its near face).

    experiments/make_operator.py --object saucepan --grip-radius 0.15 --side right \\
        --out learning_data/objects/saucepan/demos/operator.json

Then `graspsynth demos generate --object NAME --operator OUT --out DIR` makes the trials and
labels them in physics (learning_data/README.md, "Other objects").
"""

import argparse
import json
import math
import os
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--object", required=True, help="shipped object name (models/objects/NAME.json)")
    p.add_argument("--grip-radius", type=float, required=True,
                   help="where the hand closes on the grip axis: distance from the object centre "
                   "along it, m")
    p.add_argument("--side", choices=["left", "right"], required=True,
                   help="the wrist's side of the grip axis, seen along it from the object centre")
    p.add_argument("--side-at", action="append", default=[], metavar="THETA=SIDE",
                   help="the side at one orientation instead of --side's, e.g. 20=left "
                   "(repeatable)")
    p.add_argument("--grip", choices=["hook", "pinch"], default="hook",
                   help="the hand's grip (see above; default: hook)")
    p.add_argument("--hook-reach", type=float,
                   help="the axis along z_H from the wrist, m (default: the grip's)")
    p.add_argument("--wrist-above-handle", type=float,
                   help="the axis along x_H (below the palm) from the wrist, m (default: the "
                   "grip's)")
    p.add_argument("--orientations", default="20:100:10", help="FROM:TO:STEP, deg")
    p.add_argument("--trials", type=int, default=10, help="trials per orientation")
    p.add_argument("--scene", default=os.path.join(ROOT, "models", "scene.json"))
    p.add_argument("--base", default=os.path.join(ROOT, "learning_data", "demos", "operator.json"),
                   help="operator whose top-level settings are kept (default: the pan's)")
    p.add_argument("--out", required=True)
    a = p.parse_args()

    with open(os.path.join(ROOT, "models", "objects", a.object + ".json")) as f:
        obj = json.load(f)
    handle = obj.get("handle")
    if handle is None:
        sys.exit("make_operator.py: object '%s' has no grip axis ('handle')" % a.object)
    if not handle["start_radius"] <= a.grip_radius <= handle["end_radius"]:
        sys.exit("make_operator.py: --grip-radius %g is off the grip axis (%g to %g m)" %
                 (a.grip_radius, handle["start_radius"], handle["end_radius"]))
    with open(a.scene) as f:
        scene = json.load(f)
    with open(a.base) as f:
        op = json.load(f)

    if a.grip == "pinch":
        # models/README.md's pinch (HandFk.ThumbAndFingertipsPinchABar) with the spread of
        # motion/scripted_grasp.cpp's shapes.
        op["hook_reach"] = 0.103
        op["wrist_above_handle"] = 0.086
        op["open_hand_deg"] = [90, 0, 15, 0, -20, 0, 0, 0, 0, 0, 20, 0, 0, 20, 0, 0]
        op["closed_hand_deg"] = [90, 0, 30, 10, -20, 70, 17.5, 0, 70, 17.5, 20, 70, 17.5,
                                 20, 20, 10]
    if a.hook_reach is not None:
        op["hook_reach"] = a.hook_reach
    if a.wrist_above_handle is not None:
        op["wrist_above_handle"] = a.wrist_above_handle

    lo, hi, step = (float(x) for x in a.orientations.split(":"))
    sides = {}
    for item in a.side_at:
        theta, _, name = item.partition("=")
        if name not in ("left", "right"):
            sys.exit("make_operator.py: --side-at %s: expected THETA=left or THETA=right" % item)
        sides[float(theta)] = name
    reach = op["hook_reach"]
    direction = handle.get("direction_deg", 0.0)
    plans = []
    theta = lo
    while theta <= hi + 1e-9:
        side = 1.0 if sides.get(theta, a.side) == "left" else -1.0
        phi = math.radians(theta + scene["object_yaw_offset_deg"] + direction)
        h = (math.cos(phi), math.sin(phi))  # along the handle
        n = (-h[1], h[0])  # its left
        w = (a.grip_radius * h[0] + side * reach * n[0], a.grip_radius * h[1] + side * reach * n[1])
        eta = math.degrees(math.atan2(w[1], w[0]))
        plans.append({"theta_deg": theta, "pregrasp_eta_deg": eta, "trials": a.trials,
                      "strategies": [{"weight": 1.0, "d": math.hypot(*w),
                                      "eta_deg": eta}]})
        theta += step
    op["comment"] = (
        "The synthetic operator of the object '%s' (learning_data/README.md, 'Other objects'), "
        "written by experiments/make_operator.py --object %s --grip-radius %g --side %s%s" %
        (a.object, a.object, a.grip_radius, a.side,
         "".join(" --side-at " + item for item in a.side_at)))
    if a.grip == "hook" and a.hook_reach is None and a.wrist_above_handle is None:
        op["comment"] += (": the hook %g m out along the handle, the wrist on its %s; the motion, "
                          "variability and grip are the pan operator's." % (a.grip_radius, a.side))
    else:
        op["comment"] += (" --grip %s%s%s: the %s %g m out along the grip axis, the wrist on its "
                          "%s%s, the axis %g m along z_H and %g m along x_H from the wrist; the "
                          "motion and variability are the pan operator's." %
                          (a.grip, "" if a.hook_reach is None else " --hook-reach %g" % a.hook_reach,
                           "" if a.wrist_above_handle is None
                           else " --wrist-above-handle %g" % a.wrist_above_handle,
                           a.grip, a.grip_radius, a.side,
                           " (%s)" % ", ".join(a.side_at) if a.side_at else "", op["hook_reach"],
                           op["wrist_above_handle"]))
    op["plans"] = plans
    tmp = a.out + ".tmp"
    with open(tmp, "w") as f:
        json.dump(op, f, indent=2)
        f.write("\n")
    os.replace(tmp, a.out)
    print("wrote", a.out)


if __name__ == "__main__":
    main()
