"""The package as a numpy user meets it: every public name documented, a one-line repr on every
class (numbers rounded for the eye, the values themselves untouched), the options of each
function in its signature, a mistyped keyword answered with the nearest one, and enums that
the options take as well as their labels."""

import inspect
import re

import numpy as np
import pytest

# pybind11's signature lines ("fk(self: ..., q: ...) -> ...") and overload headers say nothing
# of their own: a docstring must say more.
SIGNATURE = re.compile(r"^\s*(\d+\.\s*)?[\w.]+\(.*\)( -> .*)?$")


def described(doc):
    lines = [line for line in (doc or "").splitlines() if line.strip()]
    return [line for line in lines
            if not SIGNATURE.match(line) and line.strip() != "Overloaded function."]


def public_names(gs):
    core = {n for n in dir(gs._core) if not n.startswith("_") and n != "IK_STATUS_CODES"}
    return sorted(core | set(gs.__all__))


def is_enum(cls):
    return hasattr(cls, "__members__")


def attribute_docs(cls):
    """(name, docstring) of each public attribute of cls: properties, methods, and the
    constructor of a class a user builds."""
    for name, value in vars(cls).items():
        if name.startswith("_") and name not in ("__init__", "__len__"):
            continue
        if name in getattr(cls, "__members__", {}):
            continue  # an enum's member: checked by its class's doc
        if name == "__init__" and is_enum(cls):
            continue  # an enum's constructor from its number is the enum's own
        if isinstance(value, (staticmethod, classmethod)):
            value = value.__func__
        if isinstance(value, property) or callable(value) or hasattr(value, "__get__"):
            yield name, getattr(value, "__doc__", None)


def test_every_public_class_function_property_and_member_is_documented(gs):
    missing = []
    classes = 0
    for name in public_names(gs):
        obj = getattr(gs, name, None) or getattr(gs._core, name)
        if inspect.isclass(obj):
            classes += 1
            if not described(obj.__doc__):
                missing.append(name)
            for attribute, doc in attribute_docs(obj):
                if not described(doc):
                    missing.append(f"{name}.{attribute}")
            for member in getattr(obj, "__members__", {}):
                # pybind11 lists "NAME : text" in the enum's doc; Python's enums name them in it
                if not re.search(rf"\b{member}\b\s*(:|\()?\s*\S", obj.__doc__ or ""):
                    missing.append(f"{name}.{member}")
        elif callable(obj) and not described(obj.__doc__):
            missing.append(name)
    assert classes >= 30
    assert missing == []


def test_an_enum_member_is_described_in_its_enums_doc(gs):
    doc = gs.TrialOutcome.__doc__
    assert "NOT_LIFTED : the object never left the table" in doc
    assert "LINE : the line principle" in gs.SynthesisMethod.__doc__
    assert gs.TrialOutcome.DROPPED.name == "DROPPED" and gs.TrialOutcome.DROPPED.value == 2
    assert "the member's name" in vars(gs.TrialOutcome)["name"].__doc__
    assert gs.TrialOutcome.DROPPED.label == "dropped"


DEFAULT_REPR = re.compile(r"^<[\w.]+ object at 0x[0-9a-f]+>$")


@pytest.fixture(scope="module")
def instances(gs, repo):
    """One object of every public class a user gets back, made cheaply."""
    grasp = gs.synthesize(None, 60.0, method="nearest", refine=False, perturb=1, threads=1)
    trial = gs.simulate(grasp)
    robust = gs.robustness(grasp, trials=1, threads=1)
    library = gs.GraspLibrary()
    log = gs.read_demo_log(repo / "learning_data" / "demos" / library.entries[0]["file"])
    objects = [gs.default_robot(), gs.default_scene(), gs.Simulation(), gs.Synthesizer(library),
               library, library.scores[0], grasp, grasp.trajectory, trial, trial.hold,
               trial.statistics, trial.counts, robust, robust.ci95, robust.trials[0],
               robust.trials[0].physics, robust.trials[0].physics.variation, log,
               gs.TrialOutcome.SUCCESS, gs.SynthesisMethod.LINE, gs.IkStatus.OK,
               gs.Table([])]
    return objects


def test_no_public_class_has_the_default_object_repr(gs, instances):
    for name in public_names(gs):
        cls = getattr(gs, name, None) or getattr(gs._core, name)
        if inspect.isclass(cls) and not issubclass(cls, BaseException):
            assert cls.__repr__ is not object.__repr__, name
    for obj in instances:
        text = repr(obj)
        assert not DEFAULT_REPR.match(text), text
        assert "\n" not in text and len(text) < 240, text


def test_a_grasps_repr_shows_the_essentials(instances):
    grasp = next(o for o in instances if type(o).__name__ == "Grasp")
    assert re.fullmatch(r"Grasp\(theta_deg=60\.0, method_used=SynthesisMethod\.NEAREST, "
                        r"passed=(True|False), robustness=(0\.0|1\.0)\)", repr(grasp)), repr(grasp)
    assert repr(grasp.trajectory).startswith("Trajectory(theta_deg=60.0, samples=")


def test_reprs_round_numbers_and_show_residues_as_zero(gs, instances):
    trial = next(o for o in instances if type(o).__name__ == "TrialResult")
    numbers = re.findall(r"=(-?[\d.]+(?:e[-+]\d+)?)", repr(trial))
    assert numbers
    for text in numbers:
        digits = re.sub(r"e.*$", "", text).replace("-", "").replace(".", "").lstrip("0")
        assert len(digits) <= 6, (text, repr(trial))
    # the repr rounds; the property is the computed value
    lift = re.search(r"lift=([^,)]+)", repr(trial)).group(1)
    assert lift == f"{trial.lift:.6g}" and trial.lift == trial.to_dict()["lift"]
    # a rounding residue where 0 is meant: shown as 0, kept to the bit in the value itself
    trajectory = next(o for o in instances if type(o).__name__ == "Trajectory")
    trajectory.object_xy = (5.551115123125783e-17, 0.85)
    assert "object_xy=(0.0, 0.85)" in repr(trajectory)
    assert trajectory.object_xy[0] == 5.551115123125783e-17
    trajectory.object_xy = (-0.2500000000000001, 0.85)
    assert "object_xy=(-0.25, 0.85)" in repr(trajectory)
    trajectory.object_xy = None
    assert "object_xy" not in repr(trajectory)
    interval = next(o for o in instances if type(o).__name__ == "Interval")
    assert re.fullmatch(r"Interval\(lo=[\d.e-]+, hi=[\d.e-]+\)", repr(interval))


def option_callables(gs):
    """Every function that takes a request's options, with the request and a call that fails
    on its keywords before doing any work."""
    return [
        ("synthesize", gs.synthesize, lambda **kw: gs.synthesize(None, 60.0, **kw)),
        ("synthesize", gs.Synthesizer.synthesize,
         lambda **kw: gs.Synthesizer.synthesize(None, 60.0, **kw)),
        ("generalize", gs.generalize, lambda **kw: gs.generalize(**kw)),
        ("run", gs.run, lambda **kw: gs.run(**kw)),
        ("select", gs.select_representatives, lambda **kw: gs.select_representatives(**kw)),
        ("simulate", gs.simulate, lambda **kw: gs.simulate(None, **kw)),
        ("simulate", gs.Simulation.trial, lambda **kw: gs.Simulation.trial(None, None, **kw)),
        ("robustness", gs.robustness, lambda **kw: gs.robustness(None, **kw)),
        ("robustness", gs.Simulation.robustness,
         lambda **kw: gs.Simulation.robustness(None, None, **kw)),
        ("analyze", gs.analyze_demonstrations, lambda **kw: gs.analyze_demonstrations(**kw)),
        ("segment", gs.segment, lambda **kw: gs.segment(None, **kw)),
        ("fit_wrist_line", gs.fit_wrist_line, lambda **kw: gs.fit_wrist_line(None, **kw)),
    ]


def test_every_option_is_an_explicit_keyword_with_its_default(gs):
    for request, function, _ in option_callables(gs):
        parameters = inspect.signature(function).parameters
        for option in gs.request_options(request):
            assert option["name"] in parameters, (function.__qualname__, option["name"])
            p = parameters[option["name"]]
            if option["required"]:
                assert p.default is inspect.Parameter.empty
            else:
                assert p.kind is inspect.Parameter.KEYWORD_ONLY
                assert p.default == option["default"], (function.__qualname__, p.name)
        assert not any(p.kind is inspect.Parameter.VAR_KEYWORD for p in parameters.values())
    method = inspect.signature(gs.synthesize).parameters["method"]
    assert method.default == "interp" and "SynthesisMethod" in str(method.annotation)


def mistype(name):
    """A plausible typo of an option's name: a letter doubled."""
    return name[:2] + name[1] + name[2:]


def test_a_mistyped_keyword_names_itself_and_the_nearest_option(gs):
    for request, function, call in option_callables(gs):
        option = next(o["name"] for o in gs.request_options(request) if not o["required"])
        typo = mistype(option)
        with pytest.raises(TypeError) as caught:
            call(**{typo: 1})
        message = str(caught.value)
        assert f"unexpected keyword argument '{typo}'; did you mean '{option}'?" in message
        assert "\n" not in message and len(message) < 160, message
    with pytest.raises(TypeError, match=r"^fk\(\) got an unexpected keyword argument 'robt'; "
                                        r"did you mean 'robot'\?$"):
        gs.fk(np.zeros(7), robt=None)
    with pytest.raises(TypeError, match="'frobnicate'$"):  # nothing near: no suggestion
        gs.synthesize(None, 60.0, frobnicate=1)


def test_a_method_is_an_enum_member_or_its_label(gs):
    by_label = gs.synthesize(None, 60.0, method="nearest", refine=False, perturb=0)
    by_member = gs.synthesize(None, 60.0, method=gs.SynthesisMethod.NEAREST, refine=False,
                              perturb=0)
    assert by_member.method == gs.SynthesisMethod.NEAREST
    assert by_member.method_used == gs.SynthesisMethod.NEAREST
    assert by_member.method_used.label == "nearest"
    assert by_member.status == gs.SynthesisStatus.OK
    np.testing.assert_array_equal(by_member.trajectory.arm, by_label.trajectory.arm)
    line = gs.Synthesizer().synthesize(60.0, method=gs.SynthesisMethod.LINE, refine=False,
                                       perturb=0)
    assert line.method_used == gs.SynthesisMethod.LINE
    with pytest.raises(gs.InputError, match=r"method: needs a text, got 1"):
        gs.synthesize(None, 60.0, method=1)
    with pytest.raises(gs.InputError, match=r"method.*'success'"):
        gs.synthesize(None, 60.0, method=gs.TrialOutcome.SUCCESS)


def test_methods_take_members_labels_or_both(gs):
    rows, summary = gs.generalize(orientations=[60], methods=[gs.SynthesisMethod.NEAREST, "line"],
                                  perturb=0)
    assert [r.method for r in rows] == ["nearest", "line"]
    assert [r.used for r in rows] == [gs.SynthesisMethod.NEAREST, gs.SynthesisMethod.LINE]
    rows, _ = gs.generalize(orientations=[60], methods=gs.SynthesisMethod.NEAREST, perturb=0)
    assert [r.method for r in rows] == ["nearest"]


def extension_callables(gs):
    """(display name, callable, call) of every constructor, method and static method of the
    extension's classes and of its functions, the enums aside."""
    found = []
    for name in public_names(gs):
        cls = getattr(gs, name, None) or getattr(gs._core, name)
        if not inspect.isclass(cls) or is_enum(cls) or issubclass(cls, BaseException):
            continue
        for attribute, value in vars(cls).items():
            if attribute.startswith("_") and attribute != "__init__":
                continue
            static = isinstance(value, staticmethod)
            function = value.__func__ if static else value
            if inspect.unwrap(function) is function:
                continue  # a property, a constructor-less result, or a method added in Python
            if attribute == "__init__":
                found.append((name, cls, lambda cls=cls, **kw: cls(**kw)))
            elif static:
                found.append((f"{name}.{attribute}", function, function))
            else:
                found.append((f"{name}.{attribute}", function,
                              lambda function=function, **kw: function(None, **kw)))
    for name in ("branch_of", "read_demo_log", "read_demo_directory"):
        found.append((name, getattr(gs, name), getattr(gs, name)))
    return found


def test_the_extensions_functions_show_their_keywords_and_catch_a_typo(gs):
    checked = 0
    for name, function, call in extension_callables(gs):
        parameters = [p for p in inspect.signature(function).parameters.values()
                      if p.name != "self"]
        assert not any(p.kind in (p.VAR_POSITIONAL, p.VAR_KEYWORD) for p in parameters), name
        if not parameters:
            continue
        keyword = max((p.name for p in parameters), key=len)
        typo = mistype(keyword) if len(keyword) > 2 else keyword + "x"
        with pytest.raises(TypeError) as caught:
            call(**{typo: 1})
        message = str(caught.value)
        assert message == (f"{name}() got an unexpected keyword argument '{typo}'; "
                           f"did you mean '{keyword}'?"), message
        checked += 1
    assert checked >= 15
    library = inspect.signature(gs.GraspLibrary).parameters
    assert library["path"].default is None and library["object"].default == "pan"
    ik = inspect.signature(gs.Robot.ik).parameters
    assert list(ik) == ["self", "X", "psi", "branch", "q_near"] and ik["branch"].default is None


def test_the_checked_functions_still_take_their_keywords(gs, repo):
    library = gs.GraspLibrary(path=repo / "learning_data" / "library.json", object="pan")
    assert len(library) == len(gs.GraspLibrary())
    trajectory = gs.Trajectory.load(path=repo / "examples" / "grasp_60deg.json")
    assert trajectory.theta_deg == 60.0
    q0 = np.array([0.1, 0.5, 0.2, 1.0, 0.3, 0.4, 0.1])
    X = gs.Robot().fk(q=q0)
    np.testing.assert_array_equal(X, gs.fk(q0))
    robot = gs.default_robot()
    q, status = robot.ik(X=X, psi=robot.arm_angle(q=q0), branch=gs.branch_of(q=q0))
    assert status == gs.IkStatus.OK
    np.testing.assert_allclose(q, q0, atol=1e-9)
