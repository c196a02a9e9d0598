#!/usr/bin/env python3
"""Writes a synthetic operator (graspsynth-operator/1) for an object with a handle.

The pan's operator (learning_data/demos/operator.json) was calibrated to the paper's Table I;
another object has no such table, so its operator is planned from the object's geometry: at
every orientation the hand hooks the handle --grip-radius from the object centre, crossing it
squarely, with the wrist on one side of it (the hook's reach, hook_reach, from the handle's
axis). Everything else - the motion, the variability, the grip - is the pan operator's
top-level settings (its per-strategy grips are not copied). One strategy per orientation; the
reach enters the grasp region at the wrist's own polar angle.

    experiments/make_operator.py --object saucepan --grip-radius 0.15 --side right \\
        --out learning_data/objects/saucepan/demos/operator.json

Then `graspsynth demos generate --object NAME --config OUT --out DIR` makes the trials and
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
                   help="where the hand closes on the handle: distance from the object centre, m")
    p.add_argument("--side", choices=["left", "right"], required=True,
                   help="the wrist's side of the handle, seen along it from the object centre")
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
        sys.exit("make_operator.py: object '%s' has no handle" % a.object)
    if not handle["start_radius"] <= a.grip_radius <= handle["end_radius"]:
        sys.exit("make_operator.py: --grip-radius %g is off the handle (%g to %g m)" %
                 (a.grip_radius, handle["start_radius"], handle["end_radius"]))
    with open(a.scene) as f:
        scene = json.load(f)
    with open(a.base) as f:
        op = json.load(f)

    lo, hi, step = (float(x) for x in a.orientations.split(":"))
    side = 1.0 if a.side == "left" else -1.0
    reach = op["hook_reach"]
    plans = []
    theta = lo
    while theta <= hi + 1e-9:
        phi = math.radians(theta + scene["object_yaw_offset_deg"])
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
        "written by experiments/make_operator.py --object %s --grip-radius %g --side %s: the hook "
        "%g m out along the handle, the wrist on its %s; the motion, variability and grip are "
        "the pan operator's." % (a.object, a.object, a.grip_radius, a.side, a.grip_radius, a.side))
    op["plans"] = plans
    tmp = a.out + ".tmp"
    with open(tmp, "w") as f:
        json.dump(op, f, indent=2)
        f.write("\n")
    os.replace(tmp, a.out)
    print("wrote", a.out)


if __name__ == "__main__":
    main()
