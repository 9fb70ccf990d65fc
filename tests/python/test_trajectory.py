"""arcplan.scale against `arcplan scale --json --traj-csv` on the same path, and the arrays
checked by independent means: finite differences of q against qd, the TCP speed from FK positions."""
import numpy as np
import pytest

import arcplan
from conftest import THESIS_SCENE


@pytest.fixture(scope="module")
def arc_path():
    return arcplan.plan(THESIS_SCENE, params={"sagitta": 0.1}).path


@pytest.fixture(scope="module")
def robot():
    return arcplan.load_robot()


@pytest.mark.parametrize("options, cli_options", [
    ({"vmax": 0.25}, ()),
    ({"vmax": 0.149, "rise_time": 0.5}, ("--rise", 0.5)),
    ({"vmax": 0.2, "max_tcp_acceleration": 0.5}, ("--max-acc", 0.5)),
])
def test_scale_equals_cli(robot, arc_path, cli, tmp_path, options, cli_options):
    path_csv, samples_csv = tmp_path / "path.csv", tmp_path / "samples.csv"
    np.savetxt(path_csv, arc_path, delimiter=",", header="q0,q1,q2,q3,q4,q5", comments="", fmt="%.17g")
    expected = cli("scale", "--path-csv", path_csv, "--vmax", options["vmax"], *cli_options,
                   "--traj-csv", samples_csv)
    trajectory = arcplan.scale(robot, arc_path, **options)
    for key, value in expected.items():
        if key != "settings":
            assert trajectory.metrics[key] == pytest.approx(value, abs=1e-9), key
    # Samples: t, q0..q5, qd0..qd5, qdd0..qdd5, tcp_speed, tcp_x, tcp_y, tcp_z.
    samples = np.loadtxt(samples_csv, delimiter=",", skiprows=1)
    np.testing.assert_allclose(trajectory.time, samples[:, 0], atol=1e-9)
    np.testing.assert_allclose(trajectory.q, samples[:, 1:7], atol=1e-9)
    np.testing.assert_allclose(trajectory.qd, samples[:, 7:13], atol=1e-9)
    np.testing.assert_allclose(trajectory.qdd, samples[:, 13:19], atol=1e-9)
    np.testing.assert_allclose(trajectory.tcp_speed, samples[:, 19], atol=1e-9)


def test_arrays_shapes_and_independent_checks(robot, arc_path):
    trajectory = arcplan.scale(robot, arc_path, vmax=0.25)
    m = len(trajectory.time)
    for name, shape in [("time", (m,)), ("q", (m, 6)), ("qd", (m, 6)), ("qdd", (m, 6)), ("tcp_speed", (m,)),
                        ("tcp_position", (m, 3))]:
        array = getattr(trajectory, name)
        assert array.shape == shape and array.dtype == np.float64, name
    t, q, qd = trajectory.time, trajectory.q, trajectory.qd
    assert t[0] == 0.0 and t[-1] == pytest.approx(trajectory.duration, abs=1e-12)
    np.testing.assert_allclose(q[0], arc_path[0], atol=1e-12)
    np.testing.assert_allclose(q[-1], arc_path[-1], atol=1e-12)
    np.testing.assert_allclose(qd[[0, -1]], 0.0, atol=1e-12)  # at rest at both ends
    # qd against central differences of q (PCHIP is C1; the grid is 2 ms or finer).
    np.testing.assert_allclose(qd[1:-1], (q[2:] - q[:-2]) / (t[2:] - t[:-2])[:, None], atol=2e-3)
    # The TCP positions are FK of q; the TCP speed is how fast they move.
    for k in range(0, m, 97):
        np.testing.assert_allclose(trajectory.tcp_position[k], robot.fk(q[k])[:3, 3], atol=1e-12)
    steps = np.linalg.norm(np.diff(trajectory.tcp_position, axis=0), axis=1) / np.diff(t)
    np.testing.assert_allclose(steps, (trajectory.tcp_speed[1:] + trajectory.tcp_speed[:-1]) / 2, atol=2e-3)
    # The limit holds; the TCP path length is the FK curve's length.
    assert trajectory.tcp_speed.max() <= 0.25 + 1e-9 and trajectory.tcp_speed_limit == 0.25
    assert trajectory.tcp_path_length == pytest.approx(np.sum(np.linalg.norm(np.diff(
        trajectory.tcp_position, axis=0), axis=1)), rel=1e-3)
    np.testing.assert_array_equal(trajectory.joint_speed_limits, robot.velocity_limits)


@pytest.mark.parametrize("path, options, message", [
    (np.zeros((1, 6)), {}, "2 waypoints"),
    (np.zeros((3, 5)), {}, "path: expected an (N, 6) array of joint vectors, got shape (3, 5)"),
    (np.array([[0.0] * 6, [np.nan] * 6]), {}, "path: element 6 is nan; expected finite numbers"),
    (np.array([[0.0] * 6, [9.0] * 6]), {}, "limit"),
    (None, {"vmax": -0.1}, "maxTcpSpeed must be a positive finite number (m/s), got -0.1"),
    (None, {"rise_time": 0.0}, "riseTime"),
])
def test_bad_input_raises_arcplan_error(robot, arc_path, path, options, message):
    with pytest.raises(arcplan.Error) as raised:
        arcplan.scale(robot, arc_path if path is None else path, **options)
    assert message in str(raised.value)
