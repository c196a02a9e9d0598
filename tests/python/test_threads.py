"""The simulation releases the GIL: Python threads run trials in parallel."""

import concurrent.futures
import os
import threading
import time

import pytest


@pytest.fixture(scope="module")
def trajectory(gs):
    # the 60 deg demonstration as it is: quick to make, and it lifts the pan.
    grasp = gs.synthesize(None, 60.0, method="nearest", refine=False, perturb=0)
    assert grasp.ok
    gs.simulate(grasp.trajectory)  # builds the cached simulation before anything is timed
    return grasp.trajectory


def run_trials(gs, trajectory, count):
    for _ in range(count):
        assert gs.simulate(trajectory).success
    return count


def test_python_runs_while_a_trial_runs(gs, trajectory):
    start = time.perf_counter()
    gs.simulate(trajectory)
    trial_s = time.perf_counter() - start

    with concurrent.futures.ThreadPoolExecutor(1) as pool:
        future = pool.submit(run_trials, gs, trajectory, 3)
        loops, longest = 0, 0.0
        last = time.perf_counter()
        while not future.done():
            now = time.perf_counter()
            longest, last, loops = max(longest, now - last), now, loops + 1
        assert future.result() == 3  # the trials ran and lifted the pan
    # a trial holding the GIL would stop this loop for the whole trial; released, the loop only
    # waits for the worker's Python between trials (the interpreter's 5 ms switch interval).
    assert loops > 1000
    assert longest < 0.5 * trial_s, f"the loop stalled {longest:.3f} s of a {trial_s:.3f} s trial"


@pytest.mark.skipif(len(os.sched_getaffinity(0)) < 2, reason="needs two cores")
def test_two_threads_take_clearly_less_wall_time_than_one(gs, trajectory):
    start = time.perf_counter()
    run_trials(gs, trajectory, 4)
    one_thread = time.perf_counter() - start

    with concurrent.futures.ThreadPoolExecutor(2) as pool:
        start = time.perf_counter()
        futures = [pool.submit(run_trials, gs, trajectory, 2) for _ in range(2)]
        assert [f.result() for f in futures] == [2, 2]
        two_threads = time.perf_counter() - start
    # perfect scaling would halve it; the GIL held would not shorten it at all.
    assert two_threads < 0.8 * one_thread, f"{two_threads:.2f} s on two threads, {one_thread:.2f} s on one"
