"""Kinematics from Python: the robot and scene models, batched FK and IK, and their agreement
with `graspsynth fk` and `graspsynth ik`."""

import json
import os
import re

import numpy as np
import pytest


def random_configurations(gs, n, seed):
    robot = gs.default_robot()
    rng = np.random.default_rng(seed)
    # inside the limits with a margin, away from the stretched elbow (E1 = 0).
    q = rng.uniform(robot.joint_lower * 0.9, robot.joint_upper * 0.9, size=(n, 7))
    q[:, 3] = np.where(np.abs(q[:, 3]) < 0.2, 0.5, q[:, 3])
    return q


def quaternion_matrix(w, x, y, z):
    return np.array([
        [1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
        [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
        [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)],
    ])


def test_robot_model_loads_with_its_limits(gs):
    robot = gs.Robot()
    assert robot.source.endswith("pa10_gifu3.urdf")
    assert robot.joint_lower.shape == (7,) and robot.joint_upper.shape == (7,)
    assert np.all(robot.joint_lower < robot.joint_upper)
    assert robot.hand_lower.shape == (16,)
    assert robot.lengths["d_se"] == pytest.approx(0.45)
    assert robot.X_FH.shape == (4, 4)


def test_a_bad_robot_description_raises_with_the_file_named(gs, tmp_path):
    bad = tmp_path / "broken.urdf"
    bad.write_text("<robot name='x'><link name='a'/>")
    with pytest.raises(gs.InputError, match="broken.urdf"):
        gs.Robot(str(bad))


def test_fk_agrees_with_the_command_line(gs, cli):
    q = random_configurations(gs, 50, seed=1)
    X = gs.fk(q)
    assert X.shape == (50, 4, 4)
    text = "\n".join(" ".join(repr(float(v)) for v in row) for row in q)
    lines = cli("fk", "-", stdin=text).stdout.splitlines()
    assert len(lines) == 50
    for pose, line in zip(X, lines):
        expected = json.loads(line)
        np.testing.assert_allclose(pose[:3, 3], expected["position"], rtol=0, atol=1e-12)
        np.testing.assert_allclose(pose[:3, :3], quaternion_matrix(*expected["quaternion"]),
                                   rtol=0, atol=1e-12)
        np.testing.assert_array_equal(pose[3], [0, 0, 0, 1])


def test_fk_of_one_configuration_has_no_batch_axis(gs):
    q = random_configurations(gs, 3, seed=2)
    np.testing.assert_array_equal(gs.fk(q[1]), gs.fk(q)[1])


def test_ik_agrees_with_the_command_line(gs, cli):
    q = random_configurations(gs, 40, seed=3)
    X = gs.fk(q)
    psi = gs.arm_angle(q)
    solutions, status = gs.ik(X, psi)
    assert solutions.shape == (40, 8, 7) and status.shape == (40, 8)
    intervals = gs.feasible_arm_angles(X)

    lines = []
    for pose, angle in zip(X, psi):
        quat = quaternion_from_matrix(pose[:3, :3])
        lines.append(" ".join(repr(float(v)) for v in [*pose[:3, 3], *quat, angle]))
    out = cli("ik", "-", stdin="\n".join(lines)).stdout.splitlines()
    assert len(out) == 40
    for i, line in enumerate(out):
        expected = json.loads(line)
        # the command parses a quaternion; the module takes the matrix: the targets agree to
        # rounding, so the solutions agree to 1e-12, not bit for bit.
        ok = np.flatnonzero(status[i] == gs.IkStatus.OK)
        assert [list(gs.branch_of(solutions[i, k])) for k in ok] == expected["branches"]
        np.testing.assert_allclose(solutions[i, ok], np.array(expected["solutions"]).reshape(-1, 7),
                                   rtol=0, atol=1e-12)
        np.testing.assert_allclose(intervals[i], np.array(expected["psi_intervals"]).reshape(-1, 2),
                                   rtol=0, atol=1e-12)
        assert np.all(np.isnan(solutions[i, status[i] != gs.IkStatus.OK]))


def quaternion_from_matrix(R):
    # Shepperd's method: the largest of w, x, y, z first.
    t = np.trace(R)
    if t > 0:
        s = np.sqrt(t + 1.0) * 2
        return [0.25 * s, (R[2, 1] - R[1, 2]) / s, (R[0, 2] - R[2, 0]) / s, (R[1, 0] - R[0, 1]) / s]
    i = int(np.argmax(np.diag(R)))
    j, k = (i + 1) % 3, (i + 2) % 3
    s = np.sqrt(1.0 + R[i, i] - R[j, j] - R[k, k]) * 2
    q = [0.0, 0.0, 0.0, 0.0]
    q[0] = (R[k, j] - R[j, k]) / s
    q[1 + i] = 0.25 * s
    q[1 + j] = (R[j, i] + R[i, j]) / s
    q[1 + k] = (R[k, i] + R[i, k]) / s
    return q


def test_ik_on_the_configurations_own_branch_returns_it(gs):
    q = random_configurations(gs, 200, seed=4)
    X = gs.fk(q)
    solutions, status = gs.ik(X, gs.arm_angle(q), branch=gs.branch_of(q), q_near=q)
    assert solutions.shape == (200, 7) and status.shape == (200,)
    assert np.all(status == gs.IkStatus.OK)
    np.testing.assert_allclose(gs.fk(solutions), X, rtol=0, atol=1e-9)
    np.testing.assert_allclose(solutions, q, rtol=0, atol=1e-8)


def test_ik_reports_an_unreachable_target_as_a_status(gs):
    X = np.eye(4)
    X[:3, 3] = [3.0, 0.0, 1.0]
    q, status = gs.ik(X, 0.0, branch=(1, 1, 1))
    assert status == gs.IkStatus.UNREACHABLE
    assert gs.IkStatus(int(status)).label == "unreachable"
    assert np.all(np.isnan(q))
    assert gs.feasible_arm_angles(X).shape == (0, 2)


@pytest.mark.parametrize("call, message", [
    (lambda gs: gs.fk(np.zeros((3, 6))), "q must have shape"),
    (lambda gs: gs.ik(np.zeros((4, 4)), 0.0), "last row"),
    (lambda gs: gs.ik(np.diag([2.0, 2.0, 2.0, 1.0]), 0.0), "orthonormal"),
    (lambda gs: gs.ik(np.eye(4), 4.0), "outside"),
    (lambda gs: gs.ik(np.stack([np.eye(4)] * 2), [0.0, 0.1, 0.2]), "3 values for 2 targets"),
    (lambda gs: gs.ik(np.eye(4), 0.0, branch=(1, 0, 1)), "1 or -1"),
    (lambda gs: gs.ik(np.eye(4), 0.0, branch=(1, 1, 1), q_near=np.full(7, np.nan)),
     "q_near: field 1 is not a finite number: 'nan'"),
    # non-finite configurations and poses, refused as the command line refuses them.
    (lambda gs: gs.fk([0, 0, np.nan, 0, 0, 0, 0]), "q: field 3 is not a finite number: 'nan'"),
    (lambda gs: gs.fk(np.array([np.zeros(7), [0, 0, 0, 0, 0, 0, np.inf]])),
     "q: row 2, field 7 is not a finite number: 'inf'"),
    (lambda gs: gs.arm_angle([0, -np.inf, 0, 0, 0, 0, 0]),
     "q: field 2 is not a finite number: '-inf'"),
    (lambda gs: gs.ik(np.full((4, 4), np.nan), 0.0), "X: field 1 is not a finite number"),
    (lambda gs: gs.feasible_arm_angles(np.full((4, 4), np.inf)),
     "X: field 1 is not a finite number: 'inf'"),
])
def test_bad_kinematics_input_raises_input_error(gs, call, message):
    with pytest.raises(gs.InputError, match=message):
        call(gs)
    assert issubclass(gs.InputError, ValueError)


def test_an_object_file_that_is_not_a_regular_file_is_refused_by_name(gs, tmp_path):
    # read as the command line reads it: refused before a byte is read, never blocking.
    fifo = tmp_path / "object.json"
    os.mkfifo(fifo)
    for path, why in (("/dev/zero", "a character device"), (fifo, "a named pipe (FIFO)"),
                      (tmp_path, "a folder")):
        message = f"cannot read object description '{path}': it is {why}"
        with pytest.raises(gs.InputError, match=re.escape(message)):
            gs.Scene(object=str(path))


def test_scene_model_places_the_object(gs):
    scene = gs.Scene()
    assert scene.object_name == "pan"
    X = scene.object_pose(60.0)
    np.testing.assert_allclose(X[:2, 3], scene.object_centre_xy, atol=1e-12)
    assert scene.grasp_region["shape"] == "cylinder"
    assert gs.Scene(object="mug").object_name == "mug"
    with pytest.raises(gs.InputError, match="no_such_object"):
        gs.Scene(object="no_such_object")
