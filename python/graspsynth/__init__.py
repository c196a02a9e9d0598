"""graspsynth: demonstration-seeded grasp synthesis for the PA-10 arm and the Gifu Hand III.

The same C++ library as the ``graspsynth`` command, with numpy arrays in and out:

- models: :class:`Robot` (URDF), :class:`Scene` (table, object, placement);
- kinematics, batched: :func:`fk`, :func:`ik`, :func:`feasible_arm_angles`, :func:`arm_angle`,
  :func:`branch_of`;
- demonstrations: :func:`read_demo_log`, :func:`read_demo_directory`, :func:`segment`,
  :func:`analyze_demonstrations` (Table I, the wrist line), :func:`fit_wrist_line`;
- the grasp library: :class:`GraspLibrary`, :func:`select_representatives`;
- synthesis: :func:`synthesize` (or a :class:`Synthesizer` for many grasps), giving a
  :class:`Grasp` with its :class:`Trajectory` and its report;
- simulation: :func:`simulate` (one trial), :func:`robustness` (perturbed replays), or a
  :class:`Simulation`; both release the GIL, so Python threads run trials in parallel;
- studies: :func:`run` and :func:`generalize`, whose tables are :class:`Table` objects (lists
  of :class:`StudyRow` or :class:`StudyMethodSummary`, ``to_frame()`` for a pandas DataFrame);
  their outcomes, methods and statuses are enums (:class:`TrialOutcome`,
  :class:`SynthesisMethod`, :class:`SynthesisStatus`, ...).

Every class has a one-line repr of its essentials (numbers to 6 significant digits); every
function lists its options as keyword arguments with their defaults (``help()``,
``inspect.signature``), and a mistyped keyword is a TypeError that names the nearest one.

Units: SI, radians, except object orientations (``theta``, deg). Poses are 4 x 4 homogeneous
matrices in the world frame (the arm's base, z up). Bad input raises :class:`InputError` (a
``ValueError``) with the C++ message, which names the file, field and value at fault.
"""

from __future__ import annotations

import ast
import difflib
import enum
import functools
import inspect
import os
import re
import threading
from typing import Any, Iterable, Optional, Sequence, Union

import numpy as np

from ._core import (
    IK_STATUS_CODES,
    __version__,
    DemoLog,
    DemoScore,
    FallbackKind,
    FallbackReason,
    Grasp,
    GraspLibrary,
    HoldMargin,
    HoldQuality,
    InputError,
    PhysicsDraw,
    PhysicsFactor,
    Interval,
    PhysicsVariation,
    Robot,
    RobustnessResult,
    RobustnessTrial,
    Scene,
    SensitivityCell,
    SensitivityResult,
    SensitivityRow,
    Simulation,
    StepStatistics,
    StudyMethodSummary,
    StudyRow,
    SynthesisMethod,
    SynthesisStatus,
    Synthesizer,
    Trajectory,
    TrialOutcome,
    TrialResult,
    WorldCounts,
    branch_of,
    default_robot,
    default_scene,
    read_demo_directory,
    read_demo_log,
)
from . import _core

__all__ = [
    "InputError", "IkStatus", "Robot", "Scene", "DemoLog", "DemoScore", "Trajectory",
    "TrialResult", "Simulation", "GraspLibrary", "Synthesizer", "Grasp", "Table", "StudyResult",
    "StudyRow", "StudyMethodSummary", "HoldQuality", "HoldMargin", "FallbackReason",
    "PhysicsVariation", "PhysicsDraw", "SensitivityCell", "SensitivityRow", "SensitivityResult",
    "TrialOutcome",
    "RobustnessResult", "RobustnessTrial", "Interval", "StepStatistics", "WorldCounts",
    "SynthesisMethod", "SynthesisStatus", "FallbackKind", "PhysicsFactor",
    "default_robot", "default_scene", "fk", "ik", "feasible_arm_angles", "arm_angle",
    "branch_of", "read_demo_log", "read_demo_directory", "segment", "analyze_demonstrations",
    "fit_wrist_line", "select_representatives", "synthesize", "simulate", "robustness", "run",
    "generalize", "request_options",
]

PathLike = Union[str, "os.PathLike[str]"]


def _reject_unknown_keywords(name: str, parameters: Iterable[str], kwargs: dict) -> None:
    """Raises a short TypeError for a keyword that ``name`` does not take, naming the nearest
    one it does take (Python's own error names no alternative, pybind11's lists the whole
    signature)."""
    known = list(parameters)
    for key in kwargs:
        if key not in known:
            nearest = difflib.get_close_matches(key, known, n=1, cutoff=0.6)
            hint = f"; did you mean '{nearest[0]}'?" if nearest else ""
            raise TypeError(f"{name}() got an unexpected keyword argument '{key}'{hint}")


def _suggest_keywords(function):
    """Makes a mistyped keyword argument of ``function`` a short TypeError with the nearest
    valid keyword (see :func:`_reject_unknown_keywords`)."""
    parameters = inspect.signature(function).parameters
    keywords = [n for n, p in parameters.items() if p.kind in (
        inspect.Parameter.POSITIONAL_OR_KEYWORD, inspect.Parameter.KEYWORD_ONLY)]

    @functools.wraps(function)
    def call(*args: Any, **kwargs: Any) -> Any:
        _reject_unknown_keywords(function.__name__, keywords, kwargs)
        return function(*args, **kwargs)

    return call


def _ik_status_enum() -> type:
    # One member per value of the C++ IkStatus, named by its label in capitals (the extension's
    # IK_STATUS_CODES), so that nothing here mirrors the C++ list.
    members = {label.upper().replace(" ", "_"): code for label, code in IK_STATUS_CODES.items()}
    status = enum.IntEnum("IkStatus", members, module=__name__)
    status.__doc__ = (
        "Outcome of an IK query; the ``status`` arrays of :func:`ik` hold these values. OK: a "
        "solution within every joint limit; UNREACHABLE: the wrist centre is out of the arm's "
        "reach; SINGULAR: the elbow is stretched, the arm angle is undefined; ELBOW_LIMIT: the "
        "elbow angle the target needs is outside its limit; OUT_OF_LIMITS: a solution at this "
        "arm angle and branch breaks a joint limit. ``label`` is the C++ library's name, e.g. "
        "``\"out of limits\"``.")
    labels = {code: label for label, code in IK_STATUS_CODES.items()}
    status.label = property(lambda self: labels[self.value],
                            doc="The C++ library's name of the status, e.g. ``\"out of limits\"``.")
    return status


IkStatus = _ik_status_enum()


class _DefaultText:
    """A default that pybind11 gives as text only (an object's repr): shown as that text."""

    def __init__(self, text: str):
        self.text = text

    def __repr__(self) -> str:
        return self.text


def _split_parameters(text: str) -> list[str]:
    """The comma-separated parts of a parameter list, commas inside brackets kept."""
    parts, depth, start = [], 0, 0
    for i, c in enumerate(text):
        depth += c in "([{"
        depth -= c in ")]}"
        if c == "," and depth == 0:
            parts.append(text[start:i].strip())
            start = i + 1
    if text[start:].strip():
        parts.append(text[start:].strip())
    return parts


def _extension_signature(function: Any) -> Optional[inspect.Signature]:
    """The signature of an extension function, read from the line pybind11 writes at the top of
    its docstring (``fk(self: Robot, q: numpy.ndarray) -> numpy.ndarray``); None when it has
    no such line (an overloaded function)."""
    first = (function.__doc__ or "").lstrip().split("\n", 1)[0]
    match = re.fullmatch(r"[\w.]+\((.*)\) -> (.*)", first)
    if not match:
        return None
    parameters = []
    for part in _split_parameters(match.group(1)):
        name, _, rest = part.partition(":")
        annotation, _, default_text = rest.partition(" = ")
        default: Any = inspect.Parameter.empty
        if default_text:
            try:
                default = ast.literal_eval(default_text)
            except (ValueError, SyntaxError):
                default = _DefaultText(default_text)
        parameters.append(inspect.Parameter(name.strip(), inspect.Parameter.POSITIONAL_OR_KEYWORD,
                                            default=default, annotation=annotation.strip()))
    try:
        return inspect.Signature(parameters, return_annotation=match.group(2))
    except ValueError:  # a line this reading does not understand: left as pybind11 has it
        return None


def _keywords_checked(function: Any, name: str) -> Any:
    """``function`` (of the extension) behind a check of its keyword arguments: a mistyped one
    is a short TypeError naming the nearest (pybind11's own lists every signature), and
    ``inspect.signature`` gives its parameters and defaults. ``__wrapped__`` is the extension's
    function."""
    signature = _extension_signature(function)
    if signature is None:
        return function
    keywords = [p for p in signature.parameters if p != "self"]

    @functools.wraps(function)
    def call(*args: Any, **kwargs: Any) -> Any:
        if kwargs:
            _reject_unknown_keywords(name, keywords, kwargs)
        return function(*args, **kwargs)

    call.__signature__ = signature  # type: ignore[attr-defined]
    return call


def _check_keywords_of_extension_classes() -> None:
    """Puts _keywords_checked on the constructor, methods and static methods of each class of
    the extension (the enums aside: theirs are pybind11's own)."""
    for cls in vars(_core).values():
        if not isinstance(cls, type) or hasattr(cls, "__members__") or issubclass(
                cls, BaseException):
            continue
        for attribute, value in list(vars(cls).items()):
            if attribute.startswith("_") and attribute != "__init__":
                continue
            static = isinstance(value, staticmethod)
            function = value.__func__ if static else value
            if type(function).__name__ not in ("instancemethod", "builtin_function_or_method"):
                continue  # a property, or a method added in Python
            checked = _keywords_checked(function, f"{cls.__name__}.{attribute}".replace(
                ".__init__", ""))
            setattr(cls, attribute, staticmethod(checked) if static else checked)


_check_keywords_of_extension_classes()
branch_of = _keywords_checked(branch_of, "branch_of")
read_demo_log = _keywords_checked(read_demo_log, "read_demo_log")
read_demo_directory = _keywords_checked(read_demo_directory, "read_demo_directory")

_defaults_lock = threading.Lock()


@functools.lru_cache(maxsize=None)
def _cached_simulation() -> Simulation:
    return Simulation(default_robot(), default_scene())


@_suggest_keywords
def fk(q: Any, robot: Optional[Robot] = None) -> np.ndarray:
    """Flange poses of arm configurations ``q`` (shape (7,) or (N, 7), rad): shape (4, 4) or
    (N, 4, 4), world frame, metres. ``robot``: the shipped one by default."""
    return (robot or default_robot()).fk(q)


@_suggest_keywords
def ik(X: Any, psi: Any, branch: Any = None, q_near: Any = None,
       robot: Optional[Robot] = None) -> tuple[np.ndarray, np.ndarray]:
    """Analytic IK of flange targets ``X`` (shape (4, 4) or (N, 4, 4)) at arm angles ``psi``
    (rad, a number or shape (N,)). Returns ``(q, status)``: with a ``branch`` (three signs
    GC2, GC4, GC6, or one row each) q has shape (N, 7) and status (N,); without, every branch:
    q (N, 8, 7) and status (N, 8). ``status`` holds :class:`IkStatus` values; q is NaN where
    the status is not OK. See :meth:`Robot.ik`."""
    return (robot or default_robot()).ik(X, psi, branch, q_near)


@_suggest_keywords
def feasible_arm_angles(X: Any, branch: Any = None, robot: Optional[Robot] = None) -> Any:
    """The arm angles at which each target is reachable within the joint limits: per target an
    array of intervals, shape (K, 2), rad (a list of them for a batch)."""
    return (robot or default_robot()).feasible_arm_angles(X, branch)


@_suggest_keywords
def arm_angle(q: Any, robot: Optional[Robot] = None) -> Any:
    """The arm angle psi of configurations ``q`` (shape (7,) or (N, 7)), rad."""
    return (robot or default_robot()).arm_angle(q)


# The Python type of each kind of option (C++ request::OptionKind, in its order).
_OPTION_TYPES = ["bool", "int", "int", "float", "str", "Sequence[str]",
                 "Optional[Sequence[float]]", "tuple[float, float]"]


# Options whose texts name a member of an enum, which they also take (method=SynthesisMethod.LINE).
_OPTION_ENUMS = {"method": "SynthesisMethod", "methods": "SynthesisMethod"}


def _annotation(option: dict) -> str:
    """The Python type of an option: its kind's (or its enum's as well), Optional[...] where it
    may be None."""
    kind = _OPTION_TYPES[option["kind"]]
    enum_name = _OPTION_ENUMS.get(option["name"])
    if enum_name:
        kind = (f"Union[str, {enum_name}]" if kind == "str"
                else f"Union[str, {enum_name}, Sequence[Union[str, {enum_name}]]]")
    return f"Optional[{kind}]" if option["optional"] else kind


def _with_options(request: str, name: Optional[str] = None):
    """Gives the decorated function the options of ``request`` (:func:`request_options`) as
    explicit keyword arguments: their names, defaults and help come from the
    one description the command's flags and ``--config`` files are made from (C++
    request/option.hpp, :func:`request_options`). A required option (``theta``) is a
    positional argument after the function's own. The function gets the options its caller
    gave as one dict, ``options``; the extension checks them. ``name``: what errors call it
    (``"Synthesizer.synthesize"``; the function's name by default). A keyword that names no
    option is a TypeError naming the nearest option."""
    described = _core.request_options(request)
    names = {o["name"] for o in described}

    def wrap(function):
        own = [p for p in inspect.signature(function).parameters.values() if p.name != "options"]
        leading = [p for p in own if p.kind is inspect.Parameter.POSITIONAL_OR_KEYWORD]
        trailing = [p for p in own if p.kind is not inspect.Parameter.POSITIONAL_OR_KEYWORD]
        required = [inspect.Parameter(o["name"], inspect.Parameter.POSITIONAL_OR_KEYWORD,
                                      annotation=_OPTION_TYPES[o["kind"]])
                    for o in described if o["required"]]
        optional = [inspect.Parameter(o["name"], inspect.Parameter.KEYWORD_ONLY,
                                      default=o["default"], annotation=_annotation(o))
                    for o in described if not o["required"]]
        signature = inspect.Signature(leading + required + trailing + optional,
                                      return_annotation=inspect.signature(function)
                                      .return_annotation)

        keywords = list(signature.parameters)

        @functools.wraps(function)
        def call(*args: Any, **kwargs: Any) -> Any:
            _reject_unknown_keywords(name or function.__name__, keywords, kwargs)
            bound = signature.bind(*args, **kwargs)
            given = {k: v for k, v in bound.arguments.items() if k in names}
            rest = {k: v for k, v in bound.arguments.items() if k not in names}
            return function(**rest, options=given)

        call.__signature__ = signature  # type: ignore[attr-defined]
        if name and "." in name:  # a method: help() and errors call it by its own name
            call.__name__ = name.split(".")[1]
            call.__qualname__ = name
        lines = [f"    {o['name']}: {o['help']}" + (f" (one of {', '.join(o['choices'])})"
                                                     if o["choices"] else "")
                 for o in described]
        call.__doc__ = (function.__doc__ or "") + "\n\nOptions:\n" + "\n".join(lines)
        return call

    return wrap


@_suggest_keywords
def request_options(request: str) -> list[dict]:
    """The options of a request (``"synthesize"``, ``"generalize"``, ``"run"``, ``"select"``,
    ``"simulate"``, ``"robustness"``, ``"analyze"``): name, kind, default, help, choices and
    required, as the command's flags and the keyword arguments of
    :meth:`Synthesizer.synthesize`, :func:`synthesize`, :func:`generalize`, :func:`run`,
    :func:`select_representatives`, :func:`simulate`, :func:`robustness`,
    :func:`analyze_demonstrations` and the methods of :class:`Simulation` show them."""
    return _core.request_options(request)


@_with_options("analyze")
def analyze_demonstrations(directory: Optional[PathLike] = None,
                           scene: Optional[Scene] = None, *, options: dict) -> dict:
    """The Table I analysis of a folder of demonstrations (the scene object's shipped ones by
    default): per orientation the mean pre-grasp and grasp wrist positions relative to the
    object centre (d, eta), the comparison with the paper's Table I (the paper's pan only), the
    wrist-line fit and the radial model: ``graspsynth analyze``. Returns the dict that the
    command writes as JSON."""
    return _core._analyze_demonstrations(None if directory is None else os.fspath(directory),
                                         scene, options)


@_with_options("segment")
def segment(log: DemoLog, scene: Optional[Scene] = None, *, options: dict) -> dict:
    """Segments a log into reach, grasping motion (pre-grasp to grasp) and lift, as ``graspsynth
    analyze`` does. The pre-grasp pose is the first sample with the wrist inside the scene's
    grasp region around the object centre; the grasp is the button press. Returns a dict:
    status ("ok" or why not), message, success (the object rose >= success_lift m), lift, the
    sample indices pregrasp, grasp and end, and motion: the grasping motion as arrays (t,
    position, quaternion, fingers), None when the log could not be segmented."""
    return _core._segment(log, scene, options)


@_with_options("fit_wrist_line")
def fit_wrist_line(points: Any, *, options: dict) -> dict:
    """Fits a line to 2-D points (shape (N, 2), m) by total least squares (Ceres), with the
    robust loss of ``graspsynth analyze --robust-loss`` (``robust_loss``: "none", "huber" or
    "cauchy"; ``loss_scale`` in m), cross-checked with CGAL's fit. Returns a dict with the
    termination, the line (point, direction, angle_deg, residuals, rms, max), the plain and
    CGAL lines and whether they agree."""
    return _core._fit_wrist_line(points, options)


@_with_options("synthesize", "Synthesizer.synthesize")
def _synthesizer_synthesize(self: Synthesizer, options: dict) -> Grasp:
    """A grasp for object orientation ``theta`` (deg), checked in physics: ``graspsynth
    synthesize``. ``at=(x, y)`` puts the object centre elsewhere on the table (m, world); a
    library over placements interpolates between its demonstrated placements. Returns a
    :class:`Grasp`; raises :class:`InputError` for an orientation outside the library (interp),
    a bad start or an option out of its range."""
    return self._synthesize(options)


Synthesizer.synthesize = _synthesizer_synthesize


@_with_options("synthesize")
def synthesize(library: Union[GraspLibrary, PathLike, None], *, robot: Optional[Robot] = None,
               scene: Optional[Scene] = None, options: dict) -> Grasp:
    """A grasp for object orientation ``theta`` (deg) from ``library`` (a :class:`GraspLibrary`,
    a file, or None for the shipped one), checked in physics: ``graspsynth synthesize``. For
    many grasps from one library, build a :class:`Synthesizer` once."""
    synthesizer = Synthesizer(library, robot or default_robot(), scene or default_scene())
    return synthesizer._synthesize(options)


def _trajectory(trajectory: Union[Trajectory, Grasp, PathLike],
                robot: Optional[Robot]) -> Trajectory:
    if isinstance(trajectory, Trajectory):
        return trajectory
    if isinstance(trajectory, Grasp):
        return trajectory.trajectory
    return Trajectory.load(os.fspath(trajectory), robot or default_robot())


def _simulation(robot: Optional[Robot], scene: Optional[Scene]) -> Simulation:
    if robot is None and scene is None:
        with _defaults_lock:
            return _cached_simulation()
    return Simulation(robot or default_robot(), scene or default_scene())


@_with_options("simulate", "Simulation.trial")
def _simulation_trial(self: Simulation, trajectory: Trajectory, options: dict) -> TrialResult:
    """One grasp-and-lift trial of the trajectory (then ``hold`` s holding the object up):
    the nominal trial of ``graspsynth simulate``. ``fidelity``: "fast" (the study's),
    "fast-wrist" or "full"; ``time_step`` 0 takes the fidelity's step; ``record_interval`` > 0
    records the states every so many seconds. Returns a :class:`TrialResult`. Releases the
    GIL."""
    return self._trial(trajectory, options)


@_with_options("robustness", "Simulation.robustness")
def _simulation_robustness(self: Simulation, trajectory: Trajectory,
                           options: dict) -> RobustnessResult:
    """The success rate of ``trials`` perturbed replays of the trajectory (the same replays as
    ``graspsynth simulate --perturb TRIALS --seed SEED``; the result does not depend on
    ``threads``). ``physics=False`` keeps the modelled physics (motion noise only);
    ``noise_scale`` scales the motion noise. Returns a :class:`RobustnessResult`: successes,
    score, ci95 (Wilson), ``failure_summary()``, and ``trials``, one :class:`RobustnessTrial`
    per replay with its outcome and drawn physics. Releases the GIL."""
    return self._robustness(trajectory, options)


Simulation.trial = _simulation_trial
Simulation.robustness = _simulation_robustness


@_with_options("simulate")
def simulate(trajectory: Union[Trajectory, Grasp, PathLike], *, robot: Optional[Robot] = None,
             scene: Optional[Scene] = None, options: dict) -> TrialResult:
    """One grasp-and-lift trial in ODE of a :class:`Trajectory`, a :class:`Grasp` or a
    trajectory or grasp file: the nominal trial of ``graspsynth simulate`` (see
    :meth:`Simulation.trial`). Releases the GIL."""
    return _simulation(robot, scene)._trial(_trajectory(trajectory, robot), options)


@_with_options("robustness")
def robustness(trajectory: Union[Trajectory, Grasp, PathLike], *,
               robot: Optional[Robot] = None, scene: Optional[Scene] = None,
               options: dict) -> RobustnessResult:
    """Perturbed replays of a trajectory: ``graspsynth simulate --perturb N`` (see
    :meth:`Simulation.robustness`). Returns a :class:`RobustnessResult`: each replay
    (:class:`RobustnessTrial`), the successes, the score and its interval. Releases the GIL."""
    return _simulation(robot, scene)._robustness(_trajectory(trajectory, robot), options)


class Table(list):
    """Rows of a table: :class:`StudyRow` or :class:`StudyMethodSummary` objects (or dicts)."""

    def to_frame(self) -> Any:
        """The rows as a pandas DataFrame: each row's ``to_dict()`` (every field; enums as their
        labels), nested results flattened to dotted columns (``nominal_hold.end_tilt``). Needs
        pandas (Debian's python3-pandas)."""
        try:
            import pandas
        except ImportError as e:  # pragma: no cover - depends on the machine
            raise ImportError("Table.to_frame() needs pandas (Debian: python3-pandas)") from e
        return pandas.json_normalize(
            [r.to_dict() if hasattr(r, "to_dict") else r for r in self])


class StudyResult:
    """What :func:`run` found: ``analysis`` (the dict of analysis.json: Table I, the wrist
    line), ``library`` (the selected :class:`GraspLibrary`), ``synthesis`` (the dict of
    synthesis.json), ``rows`` (:class:`StudyRow`) and ``summary`` (:class:`StudyMethodSummary`)
    as :class:`Table`, ``timing``."""

    def __init__(self, parts: dict):
        """Made by :func:`run` from the parts of the study (a dict of the names above)."""
        self.analysis: dict = parts["analysis"]
        self.library: GraspLibrary = parts["library"]
        self.synthesis: dict = parts["synthesis"]
        self.timing: dict = parts["timing"]
        self.rows = Table(parts["rows"])
        self.summary = Table(parts["summary"])
        self.table_i = Table(self.analysis["orientations"])

    def __repr__(self) -> str:
        methods = ", ".join(f"{s.method} {s.nominal_successes}/{s.rows}" for s in self.summary)
        return f"<StudyResult: {len(self.library)} library entries; {methods}>"


@_with_options("run")
def run(demos: Optional[PathLike] = None, *, robot: Optional[Robot] = None,
        scene: Optional[Scene] = None, options: dict) -> StudyResult:
    """The end-to-end study of ``graspsynth run`` on a folder of demonstrations (the shipped
    ones by default): Table I, the representative selection, and a grasp for every orientation
    by each method, validated in physics. ``quick`` is ``run --quick``; the other options are
    the command's flags (``perturb=-1``: the study's default, or ``quick``'s); ``orientations``
    takes a list of numbers or the command line's text (``"20:100:5,33"``). The same options
    give the same analysis, library and synthesis tables as the command, whatever ``threads``
    is. Takes minutes (``quick``: about one)."""
    parts = _core._run(None if demos is None else os.fspath(demos), options, robot, scene)
    return StudyResult(parts)


@_with_options("select")
def select_representatives(directory: Optional[PathLike] = None, *,
                           robot: Optional[Robot] = None, scene: Optional[Scene] = None,
                           options: dict) -> tuple[GraspLibrary, dict]:
    """Ranks every successful demonstration of a folder (the shipped ones by default) by its
    success under ``perturb`` perturbed replays in physics and keeps the best per orientation
    (``graspsynth select``). Returns ``(library, report)``: the :class:`GraspLibrary`, and a
    dict with the logs read, the unsuccessful ones, the issues (files rejected or not
    replayable, with reasons) and the orientations where nothing could be selected. The same
    seed gives the same library whatever ``threads`` is."""
    return _core._select_representatives(None if directory is None else os.fspath(directory),
                                         options, robot, scene)


@_with_options("generalize")
def generalize(library: Union[GraspLibrary, PathLike, None] = None, *,
               robot: Optional[Robot] = None, scene: Optional[Scene] = None,
               options: dict) -> tuple[Table, Table]:
    """Grasps for many orientations from a library by several methods, each validated in
    physics (``graspsynth generalize``). ``orientations``, ``x`` and ``y`` take a list of
    numbers or the command line's text (``"20:100:1,33"``); ``methods`` a list or ``"a,b"``.
    Returns ``(rows, summary)`` as :class:`Table` objects: a :class:`StudyRow` per orientation
    and method, a :class:`StudyMethodSummary` per method."""
    if library is not None and not isinstance(library, GraspLibrary):
        library = os.fspath(library)
    rows, summary = _core._generalize(library, options, robot, scene)
    return Table(rows), Table(summary)

