#!/usr/bin/env python3
"""The cost of the analytic IK called from Python on a batch, per target, against the C++
benchmark of the same solve (BM_AnalyticIkOneBranch: one branch at the target's arm angle, with
the nearest 2 pi-equivalent to the target's own configuration).

    PYTHONPATH=build/python /usr/bin/python3 benchmarks/python/ik_batch.py \
        --cxx build/benchmarks/ik_benchmark

Targets: FK of uniformly random in-limit configurations (seed 20261125), configurations within
0.05 rad of S2 = 0, E1 = 0 or W1 = 0 redrawn: the C++ benchmark's recipe (numpy's generator,
so not the same numbers). The batch call is
graspsynth.ik(X (N, 4, 4), psi (N,), branch (N, 3), q_near (N, 7)); its time is the median of
--repeats calls. Prints both figures and their ratio (the issue's goal: within 20%)."""

import argparse
import json
import statistics
import subprocess
import sys
import time

import numpy as np

import graspsynth


def targets(n, seed):
    robot = graspsynth.default_robot()
    rng = np.random.default_rng(seed)
    q = rng.uniform(robot.joint_lower, robot.joint_upper, size=(n, 7))
    near_singular = (np.abs(q[:, [1, 3, 5]]) < 0.05).any(axis=1)
    while near_singular.any():
        q[near_singular] = rng.uniform(robot.joint_lower, robot.joint_upper,
                                       size=(near_singular.sum(), 7))
        near_singular = (np.abs(q[:, [1, 3, 5]]) < 0.05).any(axis=1)
    return q


def cxx_time_us(binary):
    out = subprocess.run([binary, "--benchmark_filter=^BM_AnalyticIkOneBranch",
                          "--benchmark_repetitions=5", "--benchmark_format=json"],
                         capture_output=True, text=True, check=True).stdout
    runs = json.loads(out)["benchmarks"]
    median = next(r for r in runs if r.get("aggregate_name") == "median")
    scale = {"ns": 1e-3, "us": 1.0, "ms": 1e3}[median["time_unit"]]
    return median["cpu_time"] * scale


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--batch", type=int, default=10_000)
    parser.add_argument("--repeats", type=int, default=21)
    parser.add_argument("--cxx", help="build/benchmarks/ik_benchmark, to compare with")
    args = parser.parse_args()

    q = targets(args.batch, 20261125)
    X = graspsynth.fk(q)
    psi = graspsynth.arm_angle(q)
    branch = graspsynth.branch_of(q).astype(np.float64)
    solutions, status = graspsynth.ik(X, psi, branch=branch, q_near=q)
    solved = np.mean((status == graspsynth.IkStatus.OK)
                     & np.all(np.abs(graspsynth.fk(solutions) - X) < 1e-5, axis=(1, 2)))

    times = []
    for _ in range(args.repeats):
        start = time.process_time()
        graspsynth.ik(X, psi, branch=branch, q_near=q)
        times.append(time.process_time() - start)
    per_target_us = statistics.median(times) / args.batch * 1e6
    print(f"python: graspsynth.ik on {args.batch} targets: {per_target_us:.3f} us per target "
          f"(median CPU time of {args.repeats} calls), {solved:.1%} solved")
    if args.cxx:
        cxx = cxx_time_us(args.cxx)
        print(f"c++:    BM_AnalyticIkOneBranch: {cxx:.3f} us per target (median of 5)")
        print(f"ratio:  {per_target_us / cxx:.2f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
