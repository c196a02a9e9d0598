#!/usr/bin/env python3
"""Test of experiments/tune_operator.py: a short search on one strategy of the shipped operator
writes a config that graspsynth reads, with the strategy's grip inside the searched bounds and
the other strategies untouched; the same seed gives the same file; a strategy that does not
exist is refused by name. Exit status 0 pass, 1 fail."""

import argparse
import json
import os
import subprocess
import sys
import tempfile


def fail(message):
    print("FAIL: " + message)
    sys.exit(1)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--graspsynth", required=True)
    parser.add_argument("--script", required=True)
    parser.add_argument("--config", required=True)
    args = parser.parse_args()
    sys.path.insert(0, os.path.dirname(args.script))
    import tune_operator  # the PARAMETERS and the conversions under test

    with tempfile.TemporaryDirectory() as work:
        def tune(out, strategies="100:0"):
            return subprocess.run(
                [sys.executable, args.script, "--config", args.config, "--out", out,
                 "--strategies", strategies, "--iterations", "3", "--perturb", "2",
                 "--seed", "5", "--graspsynth", args.graspsynth],
                capture_output=True, text=True)

        first, second = os.path.join(work, "a.json"), os.path.join(work, "b.json")
        for out in (first, second):
            run = tune(out)
            if run.returncode != 0:
                fail("tune_operator.py exited %d: %s" % (run.returncode, run.stderr))
        if "100:0: done" not in run.stderr:
            fail("no progress line for the strategy: " + run.stderr)
        with open(first) as f:
            text = f.read()
        with open(second) as f:
            if f.read() != text:
                fail("the same seed gave different files")
        tuned, shipped = json.loads(text), json.load(open(args.config))
        # graspsynth reads it and makes a trial with it.
        demos = os.path.join(work, "demos")
        gen = subprocess.run([args.graspsynth, "demos", "generate", "--operator", first, "--out",
                              demos, "--trials-per-orientation", "1", "--quiet"],
                             capture_output=True, text=True)
        if gen.returncode != 0:
            fail("graspsynth did not read the tuned config: " + gen.stderr)
        # the tuned strategy's grip is whole and within the bounds; the rest is as shipped.
        for plan, old in zip(tuned["plans"], shipped["plans"]):
            for k, (strategy, before) in enumerate(zip(plan["strategies"], old["strategies"])):
                if plan["theta_deg"] == 100.0 and k == 0:
                    grip = strategy["grasp"]
                    values = tune_operator.style_to_values(grip)
                    for (name, low, high, _), v in zip(tune_operator.PARAMETERS, values):
                        if not low - 1e-9 <= v <= high + 1e-9:
                            fail("%s = %g is outside [%g, %g]" % (name, v, low, high))
                    if tune_operator.style_to_values(tune_operator.values_to_style(values)) != values:
                        fail("a grip does not survive values_to_style(style_to_values())")
                    for key in ("d", "eta_deg", "weight"):
                        if strategy[key] != before[key]:
                            fail("the wrist position %s changed" % key)
                elif strategy != before:
                    fail("strategy %d at %g deg changed" % (k, plan["theta_deg"]))
        # a strategy that does not exist.
        bad = tune(os.path.join(work, "c.json"), "55:0")
        if bad.returncode == 0 or "55:0" not in bad.stderr + bad.stdout:
            fail("a missing strategy was not refused by name: %r" % (bad.stderr + bad.stdout))
    print("PASS")


if __name__ == "__main__":
    main()
