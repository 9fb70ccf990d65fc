"""arcplan.Robot against the CLI (`arcplan robot fk|ik --json`) and against itself by independent
checks: IK solutions reproduce the pose under FK, the Jacobian equals finite differences of FK."""
from xml.etree import ElementTree

import numpy as np
import pytest

import arcplan
from conftest import DATA

Q = np.array([0.3, -1.2, 1.4, -1.7, -1.5, 0.4])


@pytest.fixture(scope="module")
def robot():
    return arcplan.load_robot()


def test_builtin_ur10e_names_and_limits(robot):
    assert robot.name == "ur10e" and robot.dof == 6 and robot.tip_link == "tool0"
    assert robot.joint_names[0] == "shoulder_pan_joint" and robot.joint_names[-1] == "wrist_3_joint"
    # The URDF's <limit> elements, read here with ElementTree (arcplan reads them with urdfdom).
    joints = {j.get("name"): j.find("limit") for j in ElementTree.parse(DATA / "ur10e" / "ur10e.urdf").iter("joint")}
    for column, attribute in enumerate(["lower", "upper", "velocity"]):
        expected = [float(joints[name].get(attribute)) for name in robot.joint_names]
        actual = [robot.lower_limits, robot.upper_limits, robot.velocity_limits][column]
        np.testing.assert_array_equal(actual, expected)
    # UR10e datasheet: 120 deg/s base and shoulder, 180 deg/s the others.
    np.testing.assert_allclose(robot.velocity_limits, np.radians([120, 120, 180, 180, 180, 180]), rtol=1e-3)
    assert robot.lower_limits.dtype == np.float64 and robot.lower_limits.shape == (6,)


def test_fk_equals_cli(robot, cli):
    expected = cli("robot", "fk", "--joints", ",".join(repr(v) for v in Q))
    pose = robot.fk(Q)
    assert pose.shape == (4, 4) and pose.dtype == np.float64
    np.testing.assert_allclose(pose[:3, 3], expected["position"], atol=1e-12)
    np.testing.assert_allclose(pose[:3, :3], expected["rotation"], atol=1e-12)
    np.testing.assert_array_equal(pose[3], [0, 0, 0, 1])


def test_fk_of_a_named_link_is_a_pose_along_the_chain(robot):
    # The shoulder link turns with joint 0 only: its pose at q equals its pose at (q0, 0, ...).
    shoulder = robot.fk(Q, link="shoulder_link")
    np.testing.assert_allclose(shoulder, robot.fk([Q[0], 0, 0, 0, 0, 0], link="shoulder_link"), atol=1e-15)
    assert not np.allclose(shoulder, robot.fk(Q))


def test_every_ik_solution_reproduces_the_pose_and_matches_the_cli(robot, cli):
    xyz_rpy = [0.6, 0.2, 0.5, 3.0, 0.1, -0.4]
    solutions = robot.ik(xyz_rpy)
    expected = cli("robot", "ik", "--pose", ",".join(map(str, xyz_rpy)))
    assert solutions.dtype == np.float64 and solutions.shape == (len(expected["solutions"]), 6)
    np.testing.assert_allclose(solutions, np.array(expected["solutions"]), atol=1e-12)
    target = arcplan.pose_from_xyz_rpy(xyz_rpy)
    for q in solutions:
        np.testing.assert_allclose(robot.fk(q), target, atol=1e-9)
    assert np.all(solutions >= robot.lower_limits) and np.all(solutions <= robot.upper_limits)


def test_ik_nearest_is_the_closest_solution(robot):
    pose = robot.fk(Q)
    nearest = robot.ik_nearest(pose, Q + 0.01)
    np.testing.assert_allclose(nearest, Q, atol=1e-9)
    solutions = robot.ik(pose)
    distances = np.linalg.norm(solutions - (Q + 0.01), axis=1)
    np.testing.assert_allclose(nearest, solutions[np.argmin(distances)], atol=1e-12)
    assert robot.ik_nearest([3.0, 0, 0, 0, 0, 0], Q) is None  # 3 m away: out of reach


def test_jacobian_equals_finite_differences_of_fk(robot):
    jacobian = robot.jacobian(Q)
    assert jacobian.shape == (6, 6) and jacobian.dtype == np.float64
    step = 1e-6
    for j in range(6):
        dq = np.zeros(6)
        dq[j] = step
        ahead, behind = robot.fk(Q + dq), robot.fk(Q - dq)
        np.testing.assert_allclose(jacobian[:3, j], (ahead[:3, 3] - behind[:3, 3]) / (2 * step), atol=1e-7)
        # Angular column: the skew part of dR R^T.
        omega = (ahead[:3, :3] - behind[:3, :3]) / (2 * step) @ robot.fk(Q)[:3, :3].T
        np.testing.assert_allclose(jacobian[3:, j], [omega[2, 1], omega[0, 2], omega[1, 0]], atol=1e-7)


def test_tcp_offset_moves_the_tip(robot):
    offset = arcplan.load_robot(tcp_offset=[0, 0, 0.1, 0, 0, 0])
    assert offset.tip_link == "tcp"
    expected = robot.fk(Q) @ arcplan.pose_from_xyz_rpy([0, 0, 0.1, 0, 0, 0])
    np.testing.assert_allclose(offset.fk(Q), expected, atol=1e-12)


@pytest.mark.parametrize("bad, message", [
    (np.zeros(5), "q: expected 6 joint values, shape (6,), got shape (5,)"),
    (np.zeros((2, 6)), "q: expected 6 joint values, shape (6,), got shape (2, 6)"),
    ([0, 0, float("nan"), 0, 0, 0], "q: element 2 is nan; expected finite numbers"),
    ("abc", "q: expected an array of numbers, got str"),
])
def test_bad_joint_vectors_raise_arcplan_error(robot, bad, message):
    with pytest.raises(arcplan.Error) as raised:
        robot.fk(bad)
    assert str(raised.value) == message


def test_bad_pose_and_files_raise_arcplan_error(robot):
    with pytest.raises(arcplan.Error, match="pose: expected a 4x4 homogeneous matrix"):
        robot.ik(np.zeros(3))
    with pytest.raises(arcplan.Error, match="not a rigid transform"):
        robot.ik(np.ones((4, 4)))
    with pytest.raises(arcplan.Error, match="/no/such.urdf"):
        arcplan.load_robot("/no/such.urdf")
    with pytest.raises(arcplan.Error, match="unknown_link"):
        robot.fk(Q, link="unknown_link")
    assert issubclass(arcplan.Error, RuntimeError)
