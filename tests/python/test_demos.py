"""Demonstrations from Python: logs and folders (with the per-file errors), segmentation, the
Table I analysis and the wrist-line fit, against the command line."""

import shutil

import numpy as np
import pytest

from conftest import load_json


@pytest.fixture(scope="module")
def demos(repo):
    return repo / "learning_data" / "demos"


def test_a_log_reads_into_arrays(gs, demos):
    log = gs.read_demo_log(str(demos / "theta060_trial01.csv"))
    n = len(log)
    assert log.theta_deg == 60.0
    assert log.t.shape == (n,) and np.all(np.diff(log.t) > 0)
    assert log.wrist_position.shape == (n, 3)
    np.testing.assert_allclose(np.linalg.norm(log.wrist_quaternion, axis=1), 1.0, atol=1e-3)
    assert log.fingers.shape == (n, 16)
    assert list(np.flatnonzero(log.events == 2)) == [n - 1]
    assert log.object_position.shape == (n, 3)


def test_a_folder_reads_the_good_logs_and_names_the_bad_one(gs, demos, tmp_path):
    for name in ["theta060_trial01.csv", "theta070_trial01.csv"]:
        shutil.copy(demos / name, tmp_path / name)
    (tmp_path / "theta080_broken.csv").write_text("# format: graspsynth-demo/1\nt,x\n1,2\n")
    logs, rejected = gs.read_demo_directory(str(tmp_path))
    assert [log.theta_deg for log in logs] == [60.0, 70.0]
    assert len(rejected) == 1
    assert rejected[0]["file"].endswith("theta080_broken.csv")
    assert "theta080_broken.csv" in rejected[0]["reason"]


def test_a_bad_log_raises_with_the_file_and_line_named(gs, tmp_path):
    bad = tmp_path / "bad.csv"
    bad.write_text("not a log\n")
    with pytest.raises(gs.InputError, match=r"bad\.csv:1"):
        gs.read_demo_log(str(bad))


def test_segmentation_finds_the_grasping_motion(gs, demos):
    # the shipped library's 60 deg demonstration lifted the pan.
    entry = next(e for e in gs.GraspLibrary().entries if e["theta_deg"] == 60.0)
    log = gs.read_demo_log(str(demos / entry["file"]))
    seg = gs.segment(log)
    assert seg["status"] == "ok" and seg["success"]
    # a lift the pan did not reach; a lift out of range is named.
    assert not gs.segment(log, success_lift=5.0)["success"]
    with pytest.raises(gs.InputError, match="success_lift: must be >= 0"):
        gs.segment(log, success_lift=-1.0)
    motion = seg["motion"]
    assert 0 < seg["pregrasp"] < seg["grasp"] < seg["end"] == len(log) - 1
    assert len(motion["t"]) == seg["grasp"] - seg["pregrasp"] + 1
    assert motion["t"][0] == 0.0
    np.testing.assert_array_equal(motion["position"], log.wrist_position[seg["pregrasp"]:seg["grasp"] + 1])
    # the pre-grasp pose is the first sample inside the grasp region around the object.
    region = gs.default_scene().grasp_region
    d = np.linalg.norm(log.wrist_position[:, :2] - log.object_position[0, :2], axis=1)
    assert d[seg["pregrasp"]] <= region["radius"] < d[seg["pregrasp"] - 1]


def test_the_analysis_equals_the_command_lines_report(gs, cli, demos, tmp_path):
    out = tmp_path / "analysis.json"
    cli("analyze", demos, "--out", out)
    expected = load_json(out)
    analysis = gs.analyze_demonstrations(str(demos))
    assert analysis == expected
    assert len(analysis["orientations"]) == 9
    assert analysis["wrist_line"]["rms_m"] < 0.01


def test_the_shipped_demonstrations_are_named_relative_to_the_project_root(gs, repo):
    # the default folder: the committed analysis (experiments/paper_reproduction.sh) on any clone.
    analysis = gs.analyze_demonstrations()
    assert analysis["directory"] == "learning_data/demos"
    assert analysis == load_json(repo / "experiments" / "results" / "analysis.json")
    logs, rejected = gs.read_demo_directory()
    assert rejected == [] and len(logs) == 90
    assert logs[0].source == "learning_data/demos/theta020_trial01.csv"
    # a folder given is named as given.
    logs, _ = gs.read_demo_directory(str(repo / "learning_data" / "demos"))
    assert logs[0].source == str(repo / "learning_data" / "demos" / "theta020_trial01.csv")


def test_the_wrist_line_fit_finds_a_line_through_collinear_points(gs):
    x = np.linspace(-0.2, 0.2, 9)
    points = np.stack([x, 0.5 * x + 0.1], axis=1)
    fit = gs.fit_wrist_line(points)
    assert fit["usable"] and fit["cgal_agrees"]
    assert fit["line"]["rms"] < 1e-9
    assert fit["line"]["angle_deg"] % 180 == pytest.approx(np.degrees(np.arctan(0.5)), abs=1e-6)
    with pytest.raises(gs.InputError, match="robust_loss: 'square' is not one of"):
        gs.fit_wrist_line(points, robust_loss="square")
    with pytest.raises(gs.InputError, match="loss_scale: must be > 0"):
        gs.fit_wrist_line(points, robust_loss="huber", loss_scale=0.0)
    huber = gs.fit_wrist_line(points, robust_loss="huber", loss_scale=0.02)
    assert huber["loss"] == "huber" and huber["loss_scale"] == 0.02
    with pytest.raises(gs.InputError,
                       match="points: row 2, field 1 is not a finite number: 'nan'"):
        gs.fit_wrist_line([[0.0, 0.0], [np.nan, 1.0], [1.0, 1.0]])


def test_paths_may_be_path_objects(gs, demos):
    log = gs.read_demo_log(demos / "theta060_trial01.csv")
    assert log.theta_deg == 60.0
    logs, rejected = gs.read_demo_directory(demos)
    assert len(logs) >= 81 and rejected == []
