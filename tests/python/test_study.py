"""The study and the generalization table from Python, against the command line."""

import csv

import pytest

from conftest import load_json


def test_the_quick_study_equals_the_command_lines(gs, cli, tmp_path):
    out = tmp_path / "study"
    cli("run", "--quick", "--orientations", "60", "--threads", "2", "--out", out)
    study = gs.run(quick=True, orientations=[60], threads=2)
    assert study.analysis == load_json(out / "analysis.json")
    assert study.library.to_json() == (out / "library.json").read_text()
    assert study.synthesis == load_json(out / "synthesis.json")
    assert [r["method"] for r in study.rows] == ["interp+refine", "line+refine"]
    assert len(study.table_i) == 9
    assert study.timing["format"] == "graspsynth-study-timing/1"


def test_generalize_equals_the_command_lines_table(gs, cli, tmp_path):
    cli("generalize", "--orientations", "55,65", "--methods", "nearest,interp", "--perturb", "2",
        "--threads", "2", "--out", tmp_path)
    with open(tmp_path / "generalization.csv", newline="", encoding="utf-8") as f:
        expected = list(csv.DictReader(f))
    rows, summary = gs.generalize(orientations=[55, 65], methods="nearest,interp", perturb=2,
                                  threads=2)
    assert [(r["theta_deg"], r["method"]) for r in rows] == [
        (float(e["theta_deg"]), e["method"]) for e in expected]
    for row, e in zip(rows, expected):
        assert row["status"] == e["status"] and row["used"] == e["used"]
        assert row["nominal"]["success"] == (e["nominal_success"] == "1")
        assert row["robustness"]["successes"] == int(e["successes"])
        assert row["passed"] == (e["passed"] == "1")
    assert [s["method"] for s in summary] == ["nearest", "interp"]


def test_tables_become_data_frames(gs):
    pandas = pytest.importorskip("pandas")
    table = gs.Table([{"method": "interp", "robustness": {"score": 0.9}},
                      {"method": "line", "robustness": {"score": 0.7}}])
    frame = table.to_frame()
    assert isinstance(frame, pandas.DataFrame)
    assert list(frame["robustness.score"]) == [0.9, 0.7]


@pytest.mark.parametrize("kwargs, message", [
    ({"orientations": "20:x"}, "orientations"),
    ({"methods": "interp,teleport"}, "teleport"),
    ({"methods": "interp,interp"}, "twice"),
    ({"perturb": -1}, "perturb"),
    ({"noise_scale": float("inf")}, "noise_scale"),
    ({"threads": -1}, "threads"),
])
def test_bad_generalize_options_raise(gs, kwargs, message):
    with pytest.raises(gs.InputError, match=message):
        gs.generalize(**kwargs)
