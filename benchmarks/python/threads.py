#!/usr/bin/env python3
"""Python threads running trials side by side: the wall time of 4 trials on one thread and on
two (2 each), which the GIL's release lets overlap. A figure for benchmarks/README.md, not a
test: a busy machine changes it.

    PYTHONPATH=build/python /usr/bin/python3 benchmarks/python/threads.py [--repeats 5]

Prints the median of --repeats runs of each and their ratio (perfect scaling: 2.0 on two free
cores; the GIL held: 1.0)."""

import argparse
import concurrent.futures
import statistics
import time

import graspsynth


def run_trials(trajectory, count):
    for _ in range(count):
        assert graspsynth.simulate(trajectory).success


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=5)
    args = parser.parse_args()
    grasp = graspsynth.synthesize(None, 60.0, method="nearest", refine=False, perturb=0)
    trajectory = grasp.trajectory
    run_trials(trajectory, 1)  # the cached simulation is built before anything is timed
    one, two = [], []
    for _ in range(args.repeats):
        start = time.perf_counter()
        run_trials(trajectory, 4)
        one.append(time.perf_counter() - start)
        with concurrent.futures.ThreadPoolExecutor(2) as pool:
            start = time.perf_counter()
            for f in [pool.submit(run_trials, trajectory, 2) for _ in range(2)]:
                f.result()
            two.append(time.perf_counter() - start)
    a, b = statistics.median(one), statistics.median(two)
    print(f"4 trials: one thread {a:.3f} s, two threads {b:.3f} s, speed-up {a / b:.2f}x")


if __name__ == "__main__":
    main()
