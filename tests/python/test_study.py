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
    # the shipped demonstrations named relative to the project root, as the command names them.
    assert study.analysis["directory"] == study.synthesis["demos"] == "learning_data/demos"
    assert [r.method for r in study.rows] == ["interp+refine", "line+refine"]
    assert [s.method for s in study.summary] == [s["method"] for s in study.synthesis["summary"]]
    assert len(study.table_i) == 9
    assert study.timing["format"] == "graspsynth-study-timing/1"


def test_generalize_equals_the_command_lines_table(gs, cli, tmp_path):
    cli("generalize", "--orientations", "55,65", "--methods", "nearest,interp", "--perturb", "2",
        "--threads", "2", "--out", tmp_path)
    with open(tmp_path / "generalization.csv", newline="", encoding="utf-8") as f:
        expected = list(csv.DictReader(f))
    rows, summary = gs.generalize(orientations=[55, 65], methods="nearest,interp", perturb=2,
                                  threads=2)
    assert [(r.theta_deg, r.method) for r in rows] == [
        (float(e["theta_deg"]), e["method"]) for e in expected]
    for row, e in zip(rows, expected):
        assert row.status.label == e["status"] and row.used.label == e["used"]
        assert row.status == gs.SynthesisStatus.OK
        assert row.nominal_success == (e["nominal_success"] == "1")
        assert row.nominal_outcome.label == e["nominal_outcome"]
        assert row.successes == int(e["successes"])
        assert row.robustness == float(e["robustness"])  # 17 digits: the same double
        assert row.passed == (e["passed"] == "1")
    assert [s.method for s in summary] == ["nearest", "interp"]


def test_a_rows_fields_are_its_properties_its_dict_and_its_csv_columns(gs, cli, tmp_path):
    # one field list: each CSV column is a property of the row, and to_dict() has every
    # property; the enums are Python enums whose labels are the files' words.
    cli("generalize", "--orientations", "60", "--methods", "interp", "--perturb", "1",
        "--sensitivity", "1", "--out", tmp_path)
    with open(tmp_path / "generalization.csv", newline="", encoding="utf-8") as f:
        header = next(csv.reader(f))
    rows, summary = gs.generalize(orientations=[60], methods="interp", perturb=1, sensitivity=1)
    row = rows[0]
    as_dict = row.to_dict()
    properties = [name for name, v in vars(gs.StudyRow).items() if isinstance(v, property)]
    assert sorted(properties) == sorted(as_dict)
    assert set(header) <= set(as_dict)
    assert as_dict["status"] == "ok" and isinstance(row.status, gs.SynthesisStatus)
    assert isinstance(row.nominal_outcome, gs.TrialOutcome)
    assert isinstance(row.nominal_hold, gs.HoldQuality) and len(row.nominal_hold.load_share) == 6
    assert [r.factor for r in row.sensitivity.rows] == list(gs.PhysicsFactor.__members__.values())
    assert as_dict["sensitivity"]["rows"][0]["factor"] == "hand_friction"
    assert row.at is None and row.fallback_reason.kind == gs.FallbackKind.NONE
    assert repr(row).startswith("StudyRow(theta_deg=60.0, method='interp', used=SynthesisMethod.INTERP")
    assert repr(summary[0]).startswith("StudyMethodSummary(method='interp', rows=1")
    assert gs.TrialOutcome.NOT_LIFTED.label == "not_lifted"
    with pytest.raises(AttributeError):
        row.passed = True  # read-only


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


def test_leave_one_out_of_a_two_entry_library_names_the_library(gs, tmp_path):
    # the one check of LeaveOneOutTable, with the command line's words.
    import json
    import pathlib
    library = json.loads((pathlib.Path(gs.GraspLibrary().source)).read_text())
    del library["entries"][1:-1]
    two = tmp_path / "two.json"
    two.write_text(json.dumps(library))
    with pytest.raises(gs.InputError, match=r"at least 3 orientations \('.*two.json' has 2\)"):
        gs.generalize(str(two), leave_one_out=True)


@pytest.mark.parametrize("kwargs, message", [
    ({"select_perturb": 0}, "select_perturb: must be >= 1"),
    ({"perturb": -1}, "perturb: must be >= 0"),
    ({"orientations": []}, "orientations: no number given"),
    ({"orientations": "40,40"}, "given twice"),
    ({"orientations": "20:x"}, "orientations"),
    ({"threads": 5000}, "threads"),
    ({"quick": 1}, "quick: needs True or False"),
])
def test_bad_run_options_raise_before_any_work(gs, kwargs, message):
    with pytest.raises(gs.InputError, match=message):
        gs.run(**kwargs)


def test_bad_select_options_raise_before_any_work(gs):
    with pytest.raises(gs.InputError, match="perturb: must be >= 1"):
        gs.select_representatives(perturb=0)
    with pytest.raises(gs.InputError, match="friction_spread"):
        gs.select_representatives(friction_spread=2.0)


def test_the_stubs_list_every_bound_field_and_enum_member(gs):
    # python/graspsynth/_core.pyi in step with the classes the field lists make.
    import ast
    import pathlib
    stubs = ast.parse((pathlib.Path(gs.__file__).parent / "_core.pyi").read_text())
    declared, properties = {}, {}
    for node in stubs.body:
        if isinstance(node, ast.ClassDef):
            declared[node.name] = {
                n.target.id if isinstance(n, ast.AnnAssign) else n.targets[0].id
                for n in node.body if isinstance(n, (ast.AnnAssign, ast.Assign))}
            properties[node.name] = {
                n.name for n in node.body if isinstance(n, ast.FunctionDef)
                and any(isinstance(d, ast.Name) and d.id == "property" for d in n.decorator_list)}
    for name in ("HoldQuality", "PhysicsVariation", "PhysicsDraw", "SensitivityCell",
                 "SensitivityRow", "SensitivityResult", "FallbackReason", "StudyRow",
                 "StudyMethodSummary", "DemoScore", "Interval", "WorldCounts", "StepStatistics",
                 "TrialResult", "RobustnessTrial", "RobustnessResult"):
        cls = getattr(gs, name)
        bound = {n for n, v in vars(cls).items() if isinstance(v, property)}
        assert declared[name] | properties[name] == bound, name
    for name in ("TrialOutcome", "SynthesisMethod", "SynthesisStatus", "FallbackKind",
                 "PhysicsFactor"):
        assert declared[name] == set(getattr(gs, name).__members__), name
