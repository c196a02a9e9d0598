#!/usr/bin/env python3
"""Synthesize grasps over the pan's orientations, check each in physics, and plot the result.

From the shipped grasp library (one demonstration per 10 deg from 20 to 100 deg), a grasp is
synthesized for every orientation by the paper's method (blend of the two nearest
demonstrations, then refinement) and validated in the ODE simulation: a nominal grasp-and-lift
trial and perturbed replays. Two Python threads share the work: the synthesis and the
simulation release the GIL.

The figure (a PNG) has two panels: the robustness of every grasp over the orientation
(filled: passed the physics gate), and the grasp wrist positions relative to the object centre,
the demonstrations' means with the wrist line fitted to them (the paper's Fig. 8) beside the
synthesized grasps'.

    PYTHONPATH=build/python /usr/bin/python3 examples/python/synthesize_and_plot.py --out grasps.png
"""

import argparse
import concurrent.futures
import sys

import matplotlib

matplotlib.use("Agg")  # files only, no display needed
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import graspsynth  # noqa: E402


def orientations(text):
    values = []
    for part in text.split(","):
        if ":" in part:
            start, stop, step = (float(v) for v in part.split(":"))
            values.extend(np.arange(start, stop + step / 2, step))
        else:
            values.append(float(part))
    return values


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--out", default="grasps.png", help="PNG file to write")
    parser.add_argument("--orientations", default="20:100:5",
                        help="object orientations, deg: FROM:TO:STEP or a comma list")
    parser.add_argument("--perturb", type=int, default=10,
                        help="perturbed replays of each grasp's physics gate")
    parser.add_argument("--threads", type=int, default=2, help="Python threads")
    args = parser.parse_args()

    library = graspsynth.GraspLibrary()
    synthesizer = graspsynth.Synthesizer(library)
    thetas = orientations(args.orientations)

    def synthesize(theta):
        # one gate thread per grasp: the Python threads share the cores.
        return synthesizer.synthesize(theta, perturb=args.perturb, threads=1)

    with concurrent.futures.ThreadPoolExecutor(args.threads) as pool:
        grasps = list(pool.map(synthesize, thetas))

    scene = graspsynth.default_scene()
    lifted = 0
    rows = []
    for theta, grasp in zip(thetas, grasps):
        if not grasp.ok:
            print(f"{theta:6.1f} deg: no grasp ({grasp.message})")
            continue
        # the same trajectory once more in physics, as `graspsynth simulate` would play it.
        trial = graspsynth.simulate(grasp)
        lifted += trial.success
        wrist = grasp.motion["position"][-1] - scene.object_pose(theta)[:3, 3]
        rows.append((theta, grasp.robustness or 0.0, grasp.passed, wrist[0], wrist[1]))
        print(f"{theta:6.1f} deg: {grasp.method_used.label:8s} robustness {grasp.robustness or 0:.2f}"
              f"  gate {'passed' if grasp.passed else 'failed'}  trial {trial.outcome.label}")
    print(f"{lifted} of {len(thetas)} synthesized grasps lifted the pan")

    analysis = graspsynth.analyze_demonstrations()
    means = np.array([[o["grasp"]["x"], o["grasp"]["y"]] for o in analysis["orientations"]])
    line = analysis["wrist_line"]

    data = np.array(rows, dtype=float).reshape(-1, 5)
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(11, 4.5))
    passed = data[:, 2] > 0
    ax1.plot(data[:, 0], data[:, 1], color="0.6", zorder=1)
    ax1.scatter(data[passed, 0], data[passed, 1], color="tab:green", label="passed the gate",
                zorder=2)
    ax1.scatter(data[~passed, 0], data[~passed, 1], facecolors="none", edgecolors="tab:red",
                label="failed the gate", zorder=2)
    ax1.set(xlabel="object orientation (deg)", ylabel="robustness (perturbed replays)",
            ylim=(-0.05, 1.05), title="Synthesized grasps in physics")
    ax1.legend(loc="lower left")

    point, direction = np.array(line["point"]), np.array(line["direction"])
    ends = point + np.outer([-0.25, 0.25], direction)
    ax2.plot(ends[:, 0], ends[:, 1], "k--", lw=1,
             label=f"wrist line (rms {line['rms_m'] * 1e3:.1f} mm)")
    ax2.scatter(means[:, 0], means[:, 1], marker="s", color="tab:blue",
                label="demonstrations (mean)")
    ax2.scatter(data[:, 3], data[:, 4], marker=".", color="tab:orange", label="synthesized")
    ax2.set(xlabel="x from the object centre (m)", ylabel="y from the object centre (m)",
            title="Grasp wrist positions", aspect="equal")
    ax2.legend(loc="best", fontsize="small")
    fig.tight_layout()
    fig.savefig(args.out, dpi=120)
    print(f"wrote {args.out}")
    return 0 if lifted == len(thetas) else 1


if __name__ == "__main__":
    sys.exit(main())
