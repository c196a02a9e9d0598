"""The grasp library, the selection, the synthesis and the simulation from Python, each
against the command line on the same inputs."""

import shutil

import numpy as np
import pytest

from conftest import load_json

THETA = 65.0  # between the library's 60 and 70 deg entries
GATE = ["--perturb", "3", "--seed", "7", "--threads", "2", "--min-robustness", "0.6"]


def without_wall_times(report):
    """The report without the wall times, which differ from run to run."""
    report = dict(report)
    report.pop("timing")
    refinement = report["refinement"] = dict(report["refinement"])
    refinement.pop("time_s")
    for stage in ("ceres", "nlopt"):
        if isinstance(refinement.get(stage), dict):
            refinement[stage] = {k: v for k, v in refinement[stage].items() if k != "time_s"}
    return report


@pytest.fixture(scope="module")
def cli_grasp(cli, tmp_path_factory):
    path = tmp_path_factory.mktemp("grasp") / "grasp.json"
    cli("synthesize", "--theta", THETA, *GATE, "--out", path)
    return path


@pytest.fixture(scope="module")
def grasp(gs):
    return gs.synthesize(None, THETA, perturb=3, seed=7, threads=2, min_robustness=0.6)


def test_the_shipped_library_reads_and_writes_the_same_bytes(gs, repo):
    library = gs.GraspLibrary()
    shipped = repo / "learning_data" / "library.json"
    assert library.source == str(shipped)
    assert library.to_json() == shipped.read_text()
    np.testing.assert_array_equal(library.thetas, np.arange(20.0, 101.0, 10.0))
    entry = library.entries[0]
    assert entry["motion"]["position"].shape[1] == 3
    assert sum(s.selected for s in library.scores) == len(library)
    best = max(library.scores, key=lambda s: s.score)
    assert best.to_dict()["score"] == best.score and 0.0 <= best.ci_low <= best.ci_high <= 1.0
    assert repr(best).startswith("DemoScore(file=")


def test_a_bad_library_raises_with_the_file_named(gs, tmp_path):
    bad = tmp_path / "library.json"
    bad.write_text('{"format": "graspsynth-library/1", "seed": "one"}')
    with pytest.raises(gs.InputError, match=str(bad)):
        gs.GraspLibrary(str(bad))
    with pytest.raises(ValueError, match="not valid JSON"):
        bad.write_text("{")
        gs.synthesize(str(bad), THETA)
    with pytest.raises(gs.InputError, match="no_such.json"):
        gs.GraspLibrary(str(tmp_path / "no_such.json"))


def test_the_synthesized_grasp_equals_the_command_lines(gs, grasp, cli_grasp):
    assert grasp.ok and grasp.passed
    expected = load_json(cli_grasp)
    assert without_wall_times(grasp.report) == without_wall_times(expected)
    samples = expected["trajectory"]["samples"]
    trajectory = grasp.trajectory
    assert len(trajectory) == len(samples)
    # the file rounds joint values and times to 1e-10 (motion/joint_trajectory.hpp).
    np.testing.assert_allclose(trajectory.t, [s["t"] for s in samples], rtol=0, atol=1e-10)
    np.testing.assert_allclose(trajectory.arm, [s["arm"] for s in samples], rtol=0, atol=1e-10)
    np.testing.assert_allclose(trajectory.hand, [s["hand"] for s in samples], rtol=0, atol=1e-10)


def test_a_saved_grasp_reads_back_as_the_same_trajectory(gs, grasp, tmp_path):
    path = tmp_path / "g.json"
    grasp.save(str(path))
    back = gs.Trajectory.load(str(path))
    np.testing.assert_allclose(back.arm, grasp.trajectory.arm, rtol=0, atol=1e-10)


def test_a_grasp_that_fails_the_gate_is_saved_only_when_forced(gs, tmp_path):
    failed = gs.synthesize(None, THETA, perturb=3, seed=7, threads=2, min_robustness=1.0)
    assert failed.ok and not failed.passed
    with pytest.raises(gs.InputError, match="failed the physics gate"):
        failed.save(str(tmp_path / "refused.json"))
    assert not (tmp_path / "refused.json").exists()
    failed.save(str(tmp_path / "forced.json"), force=True)
    assert load_json(tmp_path / "forced.json")["validation"]["forced"]


def test_the_trajectory_arrays_are_read_only_views(grasp):
    trajectory = grasp.trajectory
    assert not trajectory.arm.flags.writeable
    assert trajectory.arm.base is not None  # a view into the trajectory, not a copy
    with pytest.raises(ValueError):
        trajectory.arm[0, 0] = 1.0


def test_an_orientation_outside_the_library_raises(gs):
    with pytest.raises(gs.InputError, match="outside"):
        gs.synthesize(None, 130.0, perturb=0)


def test_bad_arguments_raise_before_any_work(gs, repo):
    with pytest.raises(gs.InputError, match=r"threads: must be \[0, 1024\]"):
        gs.synthesize(None, THETA, threads=-1)
    with pytest.raises(gs.InputError, match="threads"):
        gs.select_representatives(threads=5000)
    with pytest.raises(TypeError, match="library must be"):
        gs.synthesize(42, THETA)
    library = gs.GraspLibrary(repo / "learning_data" / "library.json")  # a Path is a path
    assert len(gs.Synthesizer(library).theta_range) == 2
    t, arm = np.array([0.0, 1.0]), np.zeros((2, 7))
    hand = np.tile(np.clip(0.0, gs.default_robot().hand_lower, gs.default_robot().hand_upper), (2, 1))
    arm[:, 3] = 1.0
    with pytest.raises(gs.InputError, match="theta_deg"):
        gs.Trajectory(t, arm, hand, theta_deg=float("nan"))
    with pytest.raises(gs.InputError, match="increase"):
        gs.Trajectory(np.zeros(2), arm, hand)


def test_a_trial_gives_the_command_lines_outcome(gs, cli, cli_grasp, tmp_path):
    out = tmp_path / "sim.json"
    cli("simulate", cli_grasp, "--out", out, expect=None)
    expected = load_json(out)["nominal"]
    trial = gs.simulate(str(cli_grasp))
    assert trial.outcome.label == expected["outcome"]
    assert isinstance(trial.outcome, gs.TrialOutcome)
    assert trial.success == expected["success"]
    assert trial.reason == expected["reason"]
    assert trial.lift == pytest.approx(expected["lift_m"], abs=1e-8)
    assert trial.max_penetration == pytest.approx(expected["max_penetration_m"], abs=1e-8)
    assert trial.hold.contacts == expected["hold"]["contacts"]
    assert trial.final_object_pose.shape == (4, 4)
    assert trial.statistics.dynamic_steps > 0 and trial.counts.bodies > 0
    assert trial.to_dict()["outcome"] == expected["outcome"]
    assert repr(trial).startswith(f"TrialResult(outcome=TrialOutcome.{trial.outcome.name}")
    assert trial.states == {}  # nothing recorded unless asked


def test_a_grasp_at_a_moved_placement_equals_the_command_lines(gs, cli, repo, tmp_path):
    library = repo / "learning_data" / "placements" / "library.json"
    path = tmp_path / "moved.json"
    cli("synthesize", "--library", library, "--theta", THETA, "--at", "-0.27,0.87", *GATE,
        "--out", path, expect=None)
    expected = load_json(path)
    grasp = gs.synthesize(str(library), THETA, at=(-0.27, 0.87), perturb=3, seed=7, threads=2,
                          min_robustness=0.6)
    assert without_wall_times(grasp.report) == without_wall_times(expected)
    assert expected["object_xy"] == [-0.27, 0.87]
    assert grasp.trajectory.object_xy == (-0.27, 0.87)
    # the trial puts the object where the trajectory says, as `graspsynth simulate` does.
    out = tmp_path / "sim.json"
    cli("simulate", path, "--out", out, expect=None)
    trial = gs.simulate(grasp)
    assert trial.outcome.label == load_json(out)["nominal"]["outcome"]
    with pytest.raises(gs.InputError, match="not on the table"):
        gs.synthesize(str(library), THETA, at=(3.0, 0.9))
    with pytest.raises(gs.InputError, match="at: needs X,Y"):
        gs.synthesize(str(library), THETA, at=(1.0, 2.0, 3.0))
    t = grasp.trajectory
    moved = gs.Trajectory(t.t, t.arm, t.hand, THETA, object_xy=(5.0, 5.0))
    assert moved.object_xy == (5.0, 5.0)
    with pytest.raises(gs.InputError, match="not on the table"):
        gs.simulate(moved)
    moved.object_xy = None
    assert moved.object_xy is None


def test_a_recorded_trial_gives_its_time_series(gs, grasp):
    trial = gs.simulate(grasp, record_interval=0.05)
    states = trial.states
    n = len(states["t"])
    assert n > 10 and np.all(np.diff(states["t"]) > 0)
    assert states["arm"].shape == (n, 7) and states["hand"].shape == (n, 16)
    assert states["object_pose"].shape == (n, 4, 4)
    np.testing.assert_array_equal(states["object_pose"][:, 3], np.tile([0, 0, 0, 1.0], (n, 1)))
    np.testing.assert_allclose(states["object_pose"][-1], trial.final_object_pose,
                               atol=0.02)
    rest_z = states["object_pose"][0, 2, 3]
    assert states["object_pose"][-1, 2, 3] - rest_z == pytest.approx(trial.lift, abs=1e-6)


def test_robustness_equals_the_command_lines_replays(gs, cli, cli_grasp, tmp_path):
    out = tmp_path / "sim.json"
    cli("simulate", cli_grasp, "--perturb", "4", "--seed", "3", "--out", out, expect=None)
    expected = load_json(out)["robustness"]
    result = gs.robustness(cli_grasp, trials=4, seed=3, threads=2)
    assert isinstance(result, gs.RobustnessResult)
    assert result.successes == expected["successes"]
    assert result.score == pytest.approx(expected["score"], abs=1e-6)
    assert [result.ci95.lo, result.ci95.hi] == pytest.approx(expected["ci95"], abs=1e-6)
    assert [r.outcome.label for r in result.trials] == [
        t["outcome"] for t in load_json(out)["trials"]]
    assert [r.index for r in result.trials] == [0, 1, 2, 3]
    assert (result.failure_summary() == "") == (result.successes == len(result.trials))


def test_selection_equals_the_command_lines_library(gs, cli, repo, tmp_path):
    demos = tmp_path / "demos"
    demos.mkdir()
    for name in ["theta060_trial01.csv", "theta060_trial02.csv", "theta070_trial01.csv"]:
        shutil.copy(repo / "learning_data" / "demos" / name, demos / name)
    out = tmp_path / "library.json"
    cli("select", demos, "--out", out, "--perturb", "2", "--threads", "2", expect=None)
    library, report = gs.select_representatives(str(demos), perturb=2, threads=2)
    assert report["logs"] == 3
    assert library.to_json() == out.read_text()
