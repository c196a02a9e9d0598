"""Type stubs of graspsynth._core, the C++ extension behind the package graspsynth.

The docstrings of the compiled module (help(graspsynth.Robot.ik), ...) say more; these stubs
give editors and type checkers the signatures."""

import enum
import os
from typing import Any, Optional, Sequence, Union

import numpy as np
import numpy.typing as npt

ArrayLike = npt.ArrayLike
FloatArray = npt.NDArray[np.float64]
Int8Array = npt.NDArray[np.int8]
PathLike = Union[str, os.PathLike[str]]

__version__: str
IK_STATUS_CODES: dict[str, int]

class InputError(ValueError):
    """Bad input: the message names the file, line, field and value at fault."""

# --- models and kinematics -----------------------------------------------------------------

class Robot:
    """The PA-10 arm and the Gifu Hand III, read from a URDF (the shipped one by default)."""
    def __init__(self, path: Optional[PathLike] = None) -> None: ...
    @property
    def source(self) -> str: ...
    @property
    def joint_lower(self) -> FloatArray:
        """(7,) rad"""
    @property
    def joint_upper(self) -> FloatArray:
        """(7,) rad"""
    @property
    def hand_lower(self) -> FloatArray:
        """(16,) rad"""
    @property
    def hand_upper(self) -> FloatArray:
        """(16,) rad"""
    @property
    def X_FH(self) -> FloatArray:
        """(4, 4): the hand mount (wrist) in the flange frame"""
    @property
    def lengths(self) -> dict[str, float]:
        """d_bs, d_se, d_ew, d_wt, m"""
    def fk(self, q: ArrayLike) -> FloatArray:
        """q (7,) or (N, 7) rad -> flange poses (4, 4) or (N, 4, 4)"""
    def ik(self, X: ArrayLike, psi: ArrayLike, branch: Optional[ArrayLike] = None,
           q_near: Optional[ArrayLike] = None) -> tuple[FloatArray, Int8Array]:
        """-> (q, status): (N, 7), (N,) with a branch; (N, 8, 7), (N, 8) without"""
    def feasible_arm_angles(self, X: ArrayLike,
                            branch: Optional[ArrayLike] = None) -> Union[FloatArray, list[FloatArray]]:
        """-> intervals (K, 2) rad per target"""
    def arm_angle(self, q: ArrayLike) -> Union[float, FloatArray]: ...

def default_robot() -> Robot:
    """the shipped robot, read once"""
def default_scene() -> Scene:
    """the shipped scene, read once"""
def branch_of(q: ArrayLike) -> Int8Array:
    """-> signs (GC2, GC4, GC6), shape (3,) or (N, 3)"""

class Scene:
    """The table, the object and where it stands (models/scene.json by default)."""
    def __init__(self, path: Optional[PathLike] = None, object: Optional[str] = None) -> None: ...
    @property
    def source(self) -> str: ...
    @property
    def object_name(self) -> str: ...
    @property
    def object_source(self) -> str: ...
    @property
    def object_mass(self) -> float: ...
    @property
    def object_centre_xy(self) -> FloatArray: ...
    @property
    def table(self) -> dict[str, Any]: ...
    @property
    def grasp_region(self) -> dict[str, Any]: ...
    def object_pose(self, theta_deg: float) -> FloatArray:
        """(4, 4): the object resting at orientation theta_deg"""

# --- demonstrations ------------------------------------------------------------------------

class DemoLog:
    """A graspsynth-demo/1 log; the arrays are copies, one row per sample."""
    @property
    def source(self) -> str: ...
    @property
    def theta_deg(self) -> float: ...
    @property
    def trial(self) -> Optional[str]: ...
    @property
    def operator_name(self) -> Optional[str]: ...
    @property
    def sample_rate_hz(self) -> Optional[float]: ...
    @property
    def metadata_extra(self) -> dict[str, str]: ...
    def __len__(self) -> int: ...
    @property
    def t(self) -> FloatArray: ...
    @property
    def wrist_position(self) -> FloatArray: ...
    @property
    def wrist_quaternion(self) -> FloatArray:
        """(N, 4), w x y z"""
    @property
    def fingers(self) -> FloatArray: ...
    @property
    def events(self) -> Int8Array:
        """0 none, 1 grasp button, 2 end"""
    @property
    def object_position(self) -> FloatArray: ...

def read_demo_log(path: PathLike) -> DemoLog: ...
def read_demo_directory(directory: Optional[PathLike] = None) -> tuple[list[DemoLog], list[dict[str, str]]]:
    """-> (logs, rejected [{"file", "reason"}])"""
def _segment(log: DemoLog, scene: Optional[Scene], options: dict[str, Any]) -> dict[str, Any]: ...
def _analyze_demonstrations(directory: Optional[str], scene: Optional[Scene],
                            options: dict[str, Any]) -> dict[str, Any]:
    """-> the graspsynth-analysis/1 report: Table I, the wrist line, the radial model"""
def _fit_wrist_line(points: ArrayLike, options: dict[str, Any]) -> dict[str, Any]: ...

# --- trajectories and simulation -----------------------------------------------------------

class Trajectory:
    """A graspsynth-trajectory/1 joint trajectory; t, arm, hand are read-only views."""
    def __init__(self, t: ArrayLike, arm: ArrayLike, hand: ArrayLike, theta_deg: float = 0.0,
                 robot: Optional[Robot] = None,
                 object_xy: Optional[ArrayLike] = None) -> None: ...
    @staticmethod
    def load(path: PathLike, robot: Optional[Robot] = None) -> Trajectory: ...
    @property
    def theta_deg(self) -> float: ...
    @property
    def object_xy(self) -> Optional[tuple[float, float]]: ...
    @object_xy.setter
    def object_xy(self, xy: Optional[ArrayLike]) -> None: ...
    @property
    def duration(self) -> float: ...
    def __len__(self) -> int: ...
    @property
    def t(self) -> FloatArray: ...
    @property
    def arm(self) -> FloatArray: ...
    @property
    def hand(self) -> FloatArray: ...
    @property
    def waypoints(self) -> dict[str, FloatArray]: ...
    def to_json(self) -> str: ...
    def save(self, path: PathLike) -> None: ...

class Interval:
    lo: float
    hi: float
    def to_dict(self) -> dict[str, Any]:
        """every field; enums as their labels, nested results as dicts"""

class WorldCounts:
    bodies: int
    joints: int
    geoms: int
    dynamic_bodies: int
    def to_dict(self) -> dict[str, Any]:
        """every field; enums as their labels, nested results as dicts"""

class StepStatistics:
    dynamic_steps: int
    kinematic_steps: int
    collision_s: float
    solver_s: float
    control_s: float
    max_contacts: int
    def to_dict(self) -> dict[str, Any]:
        """every field; enums as their labels, nested results as dicts"""

class TrialResult:
    outcome: TrialOutcome
    reason: str
    lift: float
    max_lift: float
    max_penetration: float
    simulated_time: float
    planned_time: float
    wall_time: float
    cpu_time: float
    final_object_pose: FloatArray
    hold: HoldQuality
    statistics: StepStatistics
    counts: WorldCounts
    @property
    def success(self) -> bool: ...
    @property
    def states(self) -> dict[str, FloatArray]:
        """t (N,), arm (N, 7), hand (N, 16), object_pose and wrist_pose (N, 4, 4); {} unless recorded"""
    def to_dict(self) -> dict[str, Any]:
        """every field; enums as their labels, nested results as dicts"""

class RobustnessTrial:
    index: int
    time_scale: float
    physics: PhysicsDraw
    outcome: TrialOutcome
    reason: str
    lift: float
    final_object_pose: FloatArray
    hold: HoldQuality
    simulated_time: float
    wall_time: float
    cpu_time: float
    dynamic_steps: int
    kinematic_steps: int
    @property
    def success(self) -> bool: ...
    def to_dict(self) -> dict[str, Any]:
        """every field; enums as their labels, nested results as dicts"""

class RobustnessResult:
    trials: list[RobustnessTrial]
    successes: int
    score: float
    ci95: Interval
    threads: int
    wall_time: float
    simulated_time: float
    cpu_time: float
    def failure_summary(self) -> str: ...
    def to_dict(self) -> dict[str, Any]:
        """every field; enums as their labels, nested results as dicts"""

class Simulation:
    """The ODE world; trial() and robustness() release the GIL."""
    def __init__(self, robot: Optional[Robot] = None, scene: Optional[Scene] = None) -> None: ...
    # Added by graspsynth/__init__.py from request_options("simulate") and
    # request_options("robustness"), which these stubs must match (tests/python/test_package.py
    # checks it).
    def trial(self, trajectory: Trajectory, *, fidelity: str = "fast", time_step: float = 0.0,
              hold: float = 1.0, record_interval: float = 0.0) -> TrialResult: ...
    def robustness(self, trajectory: Trajectory, *, trials: int = 20, seed: int = 1,
                   threads: int = 0, noise_scale: float = 1.0, fidelity: str = "fast",
                   time_step: float = 0.0, hold: float = 1.0, physics: bool = True,
                   friction_spread: float = 0.25,
                   stiffness_range: tuple[float, float] = (0.5, 2.0),
                   damping_range: tuple[float, float] = (0.5, 2.0), mass_spread: float = 0.2,
                   com_offset: float = 0.01, servo_force_spread: float = 0.2,
                   fine_step: float = 0.001,
                   fine_step_probability: float = 0.5) -> RobustnessResult: ...
    def _trial(self, trajectory: Trajectory, options: dict[str, Any]) -> TrialResult: ...
    def _robustness(self, trajectory: Trajectory, options: dict[str, Any]) -> RobustnessResult: ...

# --- the grasp library and the synthesis ---------------------------------------------------

class GraspLibrary:
    def __init__(self, path: Optional[PathLike] = None, object: str = "pan") -> None: ...
    @property
    def source(self) -> str: ...
    @property
    def demo_directory(self) -> str: ...
    @property
    def seed(self) -> int: ...
    @property
    def perturbations(self) -> int: ...
    @property
    def tie_rule(self) -> str: ...
    def __len__(self) -> int: ...
    @property
    def thetas(self) -> FloatArray: ...
    @property
    def entries(self) -> list[dict[str, Any]]: ...
    @property
    def scores(self) -> list[DemoScore]: ...
    def to_json(self) -> str: ...
    def save(self, path: PathLike) -> None: ...

def _select_representatives(directory: Optional[str], options: dict[str, Any],
                            robot: Optional[Robot],
                            scene: Optional[Scene]) -> tuple[GraspLibrary, dict[str, Any]]: ...

class Grasp:
    @property
    def ok(self) -> bool: ...
    @property
    def status(self) -> SynthesisStatus: ...
    @property
    def message(self) -> str: ...
    @property
    def theta_deg(self) -> float: ...
    @property
    def method(self) -> SynthesisMethod:
        """the method asked for"""
    @property
    def method_used(self) -> SynthesisMethod: ...
    @property
    def fallback(self) -> bool: ...
    @property
    def passed(self) -> bool: ...
    @property
    def gate_reason(self) -> str: ...
    @property
    def robustness(self) -> Optional[float]: ...
    @property
    def trajectory(self) -> Trajectory: ...
    @property
    def motion(self) -> dict[str, Any]: ...
    @property
    def unrefined(self) -> dict[str, Any]: ...
    @property
    def report(self) -> dict[str, Any]:
        """the graspsynth-grasp/1 document"""
    def to_json(self, force: bool = False) -> str: ...
    def save(self, path: PathLike, force: bool = False) -> None: ...

class Synthesizer:
    def __init__(self, library: Union[GraspLibrary, PathLike, None] = None,
                 robot: Optional[Robot] = None, scene: Optional[Scene] = None) -> None: ...
    @property
    def theta_range(self) -> tuple[float, float]: ...
    # Added by graspsynth/__init__.py from request_options("synthesize"), which this stub must
    # match (tests/python/test_package.py checks it).
    def synthesize(self, theta: float, *, at: Optional[Sequence[float]] = None,
                   method: Union[str, SynthesisMethod] = "interp", refine: bool = True,
                   reach: str = "auto",
                   clearance_margin: float = 0.005, strict_thresholds: bool = False,
                   grip_slide: bool = False, start: Optional[Sequence[float]] = None,
                   seed: int = 1, perturb: int = 30, threads: int = 0, min_robustness: float = 0.8,
                   physics_fallback: bool = True, physics: bool = True,
                   friction_spread: float = 0.25,
                   stiffness_range: tuple[float, float] = (0.5, 2.0),
                   damping_range: tuple[float, float] = (0.5, 2.0), mass_spread: float = 0.2,
                   com_offset: float = 0.01, servo_force_spread: float = 0.2,
                   fine_step: float = 0.001, fine_step_probability: float = 0.5,
                   engines: str = "ode", mujoco_min_success: float = 0.95,
                   require_hold_margin: bool = False, max_slip_mm: float = 40.0,
                   max_slip_deg: float = 10.0, min_epsilon_weight: float = 0.05,
                   min_load_bearing_links: int = 2,
                   max_friction_use_mean: float = 1.0) -> Grasp: ...
    def _synthesize(self, options: dict[str, Any]) -> Grasp: ...

# --- results and their enums (made from the C++ field lists; read-only) --------------------

# Results: read-only properties (the C++ field lists); to_dict() for pandas. Every class of the
# module has a one-line repr (numbers to 6 significant digits, rounding residues as 0).

class TrialOutcome(enum.Enum):
    SUCCESS = 0
    NOT_LIFTED = 1
    DROPPED = 2
    KNOCKED_OVER = 3
    TOUCHES_OTHER = 4
    TILTED = 5
    COLLISION = 6
    JOINT_LIMIT = 7
    UNSTABLE = 8
    @property
    def label(self) -> str: ...

class SynthesisMethod(enum.Enum):
    INTERP = 0
    LINE = 1
    NEAREST = 2
    @property
    def label(self) -> str: ...

class SynthesisStatus(enum.Enum):
    OK = 0
    OUT_OF_RANGE = 1
    BAD_START = 2
    NO_MODEL = 3
    UNREACHABLE = 4
    @property
    def label(self) -> str: ...

class FallbackKind(enum.Enum):
    NONE = 0
    ROBUST_NEIGHBOUR = 1
    TURNED_DEMO = 2
    LINE_PRINCIPLE = 3
    PLAIN_BLEND = 4
    PARTIAL_BLEND = 5
    @property
    def label(self) -> str: ...

class PhysicsFactor(enum.Enum):
    HAND_FRICTION = 0
    TABLE_FRICTION = 1
    CONTACT_STIFFNESS = 2
    CONTACT_DAMPING = 3
    OBJECT_MASS = 4
    CENTER_OF_MASS = 5
    SERVO_FORCE = 6
    STEP = 7
    @property
    def label(self) -> str: ...

class HoldQuality:
    end_tilt: float  # rad
    max_tilt: float  # rad
    slip: float  # m
    slip_angle: float  # rad
    contacts: int
    load_share: tuple[float, ...]  # the fingers, then the palm
    def to_dict(self) -> dict[str, Any]:
        """every field; enums as their labels, nested results as dicts"""

class HoldMargin:
    measured: bool
    slip_mm: float
    slip_deg: float
    end_tilt_deg: float
    contacts: tuple[int, ...]  # the fingers, then the palm
    load_share: tuple[float, ...]  # the fingers, then the palm
    load_bearing_links: int
    fingertips_only: bool
    epsilon_weight: float  # object weights
    torque_scale_m: float
    friction_use_max: float
    friction_use_mean: float
    normal_force_weight: float  # object weights
    def to_dict(self) -> dict[str, Any]:
        """every field; enums as their labels, nested results as dicts"""

class PhysicsVariation:
    object_hand_friction: float
    object_table_friction: float
    contact_stiffness: float
    contact_damping: float
    object_mass: float
    object_com_offset: tuple[float, float, float]  # object frame, m
    hand_effort: float
    def to_dict(self) -> dict[str, Any]:
        """every field; enums as their labels, nested results as dicts"""

class PhysicsDraw:
    variation: PhysicsVariation
    time_step: float  # s; 0: the trial's own
    def to_dict(self) -> dict[str, Any]:
        """every field; enums as their labels, nested results as dicts"""

class SensitivityCell:
    physics: PhysicsDraw
    trials: int
    successes: int
    failures: str
    def to_dict(self) -> dict[str, Any]:
        """every field; enums as their labels, nested results as dicts"""

class SensitivityRow:
    factor: PhysicsFactor
    low: SensitivityCell
    high: SensitivityCell
    def to_dict(self) -> dict[str, Any]:
        """every field; enums as their labels, nested results as dicts"""

class SensitivityResult:
    trials_per_cell: int
    rows: list[SensitivityRow]
    wall_time: float  # s
    def to_dict(self) -> dict[str, Any]:
        """every field; enums as their labels, nested results as dicts"""

class MujocoSweepSummary:
    runs: int
    successes: int
    success_fraction: float
    slip_median: float  # m
    slip_worst: float  # m
    slip_angle_median: float  # rad
    slip_angle_worst: float  # rad
    failing: str
    def to_dict(self) -> dict[str, Any]:
        """every field; enums as their labels, nested results as dicts"""

class FallbackReason:
    kind: FallbackKind
    bracket_reason: str
    lower_deg: float
    upper_deg: float
    used_deg: float
    robust: bool
    min_psi_width: float  # rad
    line_unreachable: bool
    side: int
    blend_failed: bool
    cell: str
    used_placement: str
    def text(self) -> str: ...
    def to_dict(self) -> dict[str, Any]:
        """every field; enums as their labels, nested results as dicts"""

class StudyRow:
    theta_deg: float
    at: Optional[tuple[float, float]]  # world, m
    method: str
    message: str
    used: Optional[SynthesisMethod]
    fallback: bool
    fallback_reason: FallbackReason
    refined: bool
    gate_run: bool
    status: Optional[SynthesisStatus]  # None: no library
    nominal_success: bool
    nominal_outcome: Optional[TrialOutcome]
    nominal_reason: str
    trials: int
    successes: int
    robustness: float
    ci_low: float
    ci_high: float
    passed: bool
    gate_reason: str
    epsilon: float
    force_closure: bool
    failures: str
    nominal_hold: HoldQuality
    hold_margin: HoldMargin
    hold_margin_shortfall: str
    sensitivity: Optional[SensitivityResult]
    mujoco: Optional[MujocoSweepSummary]
    seed: int
    synthesis_s: float
    gate_s: float
    source_thetas_deg: list[float]
    def to_dict(self) -> dict[str, Any]:
        """every field; enums as their labels, nested results as dicts"""

class StudyMethodSummary:
    method: str
    rows: int
    synthesized: int
    nominal_successes: int
    passed: int
    fallbacks: int
    mean_robustness: float
    mean_robustness_all: float
    def to_dict(self) -> dict[str, Any]:
        """every field; enums as their labels, nested results as dicts"""

class DemoScore:
    file: str
    trial: str
    theta_deg: float
    xy: tuple[float, float]
    trials: int
    successes: int
    score: float
    ci_low: float
    ci_high: float
    nominal_success: bool
    seed: int
    failures: str
    selected: bool
    stopped: str
    def to_dict(self) -> dict[str, Any]:
        """every field; enums as their labels, nested results as dicts"""

# --- studies -------------------------------------------------------------------------------

def _run(demos: Optional[str], options: dict[str, Any], robot: Optional[Robot],
         scene: Optional[Scene]) -> dict[str, Any]:
    """-> analysis, library, synthesis, timing, rows (list[StudyRow]), summary
    (list[StudyMethodSummary])"""
def _generalize(library: Union[GraspLibrary, str, None], options: dict[str, Any],
                robot: Optional[Robot],
                scene: Optional[Scene]) -> tuple[list[StudyRow], list[StudyMethodSummary]]: ...

# --- requests ------------------------------------------------------------------------------

def request_options(request: str) -> list[dict[str, Any]]: ...
