"""The simulation releases the GIL: a Python thread makes progress while trials run on another.

No wall time is compared here (a busy machine would fail it); the speed-up of two threads over
one is a benchmark: benchmarks/python/threads.py."""

import concurrent.futures
import threading
import time

import pytest


@pytest.fixture(scope="module")
def trajectory(gs):
    # the 60 deg demonstration as it is: quick to make, and it lifts the pan.
    grasp = gs.synthesize(None, 60.0, method="nearest", refine=False, perturb=0)
    assert grasp.ok
    gs.simulate(grasp.trajectory)  # builds the cached simulation before anything runs
    return grasp.trajectory


def test_python_runs_while_a_trial_runs(gs, trajectory):
    # the worker marks when each trial starts and ends; this thread counts its own steps
    # meanwhile. A trial that held the GIL would let this thread run only around its call, in
    # the interpreter's switch interval at the start or the end of the trial: never in its
    # middle half. Released, this thread steps through the middle of the trials; of five, one
    # suffices, so that a thread descheduled now and then by a busy machine does not matter.
    marks = []
    stop = threading.Event()

    def trials():
        for _ in range(5):
            start = time.monotonic()
            assert gs.simulate(trajectory).success
            marks.append((start, time.monotonic()))
        stop.set()

    steps = []
    with concurrent.futures.ThreadPoolExecutor(1) as pool:
        future = pool.submit(trials)
        while not stop.is_set():
            steps.append(time.monotonic())
            time.sleep(0.0005)  # a step every half millisecond or so: few enough to keep
        future.result()
    middles = []
    for start, end in marks:
        quarter = (end - start) / 4
        middles.append(sum(1 for t in steps if start + quarter < t < end - quarter))
    assert max(middles) > 0, f"no step in the middle half of any trial: {marks}"
