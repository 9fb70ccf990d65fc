"""arcplan.plan against `arcplan plan --json` on the same inputs (the thesis scene), the result's
arrays, and bad input raising arcplan.Error with arcplan's message."""
import json
import os
import subprocess

import numpy as np
import pytest

import arcplan
from conftest import THESIS_SCENE, main_thread_ran_during

CASES = {
    "arc_auto": ("arc", {}, ()),
    "arc_h050": ("arc", {"sagitta": 0.1}, ("--param", "sagitta=0.1")),
    "rrtconnect": ("RRTConnect", {}, ()),
}


@pytest.mark.parametrize("case", CASES)
def test_plan_equals_cli_on_the_thesis_scene(cli, tmp_path, case):
    planner, params, cli_params = CASES[case]
    path_csv = tmp_path / "path.csv"
    expected = cli("plan", "--scene", THESIS_SCENE, "--planner", planner, *cli_params, "--seed", 1, "--vmax", 0.25,
                   "--time", 1, "--path-csv", path_csv)
    result = arcplan.plan(str(THESIS_SCENE), planner=planner, params=params, seed=1, time_limit=1.0, vmax=0.25)
    assert result.status == expected["status"] == "exact"
    assert abs(result.tcp_path_length_m - expected["tcp_path_length_m"]) <= 1e-9
    assert abs(result.execution_time_s - expected["execution_time_s"]) <= 1e-9
    assert result.waypoints == expected["waypoints"] == len(result.path)
    np.testing.assert_allclose(result.path, np.loadtxt(path_csv, delimiter=",", skiprows=1), rtol=0, atol=1e-12)
    document = result.to_dict()
    assert set(document) == set(expected)
    for key, value in expected.items():
        if key not in ("solve_time_s", "simplification_time_s"):  # the measured times
            assert document[key] == pytest.approx(value, abs=1e-9), key


def test_clearance_is_asked_and_judged_as_the_cli_does(cli):
    # The thesis endpoints are farther than 5 cm from the obstacle: no approach zone, so a kept clearance
    # means every dense waypoint at least 5 cm away.
    expected = cli("plan", "--scene", THESIS_SCENE, "--planner", "RRTConnect", "--seed", 1, "--clearance", 0.05)
    result = arcplan.plan(str(THESIS_SCENE), planner="RRTConnect", seed=1, clearance=0.05)
    assert result.clearance_m == expected["clearance_m"] == 0.05
    assert result.clearance_kept is True and expected["clearance_kept"] is True
    assert result.to_dict()["clearance_kept"] is True
    assert result.min_clearance_m >= 0.05


def test_thesis_arc_path_length_is_the_analytic_one():
    # README / docs/planners.md: with sagitta h = 0.5 r = 0.1 m the TCP path is the three-arc detour of
    # the thesis, 0.8825 m (its published measurement: 0.8816 m from sampled waypoints).
    result = arcplan.plan("scenes/thesis_obstacle.yaml", params={"sagitta": 0.1})
    assert result.tcp_path_length_m == pytest.approx(0.8825, abs=5e-5)
    assert result.execution_time_s is None and result.trajectory is None  # no vmax: not time-scaled
    assert result.mode == "arc" and result.planner == "arc" and result.query == "A_to_B"
    assert result.fallback_reason is None  # lines and arcs only
    assert result.parameters["sagitta"] == "0.1"


def test_a_fallback_path_says_why_as_the_cli_does(cli, tmp_path):
    # The wrist on opposite sides of q5 = 0 at start and goal: only the joint-space fallback joins them.
    scene = tmp_path / "wrist_flip.yaml"
    scene.write_text(THESIS_SCENE.read_text().split("queries:")[0].replace("name: thesis_obstacle", "name: wrist_flip") +
                     "queries:\n  - name: flip\n"
                     "    start: {joints: [-1.098, -1.510, 2.351, -2.411, -1.571, -1.098]}\n"
                     "    goal: {joints: [0.399, -1.624, 2.012, -1.958, 1.571, 0.399]}\n")
    expected = cli("plan", "--scene", scene, "--seed", 1)
    result = arcplan.plan(str(scene), seed=1)
    assert result.mode == expected["mode"] == "fallback"
    assert result.fallback_reason == expected["fallback_reason"]
    assert result.fallback_reason.startswith("branch change: start and goal are on different IK branches")


def test_path_arrays_and_endpoints():
    result = arcplan.plan(arcplan.load_scene(THESIS_SCENE), vmax=0.25)
    path = result.path
    assert path.dtype == np.float64 and path.ndim == 2 and path.shape[1] == 6 and path.flags.c_contiguous
    # The path starts at pose A and ends at pose B: the scene file's two `pose:` lines, read here.
    poses = [line.split("[")[1].split("]")[0].split(",") for line in THESIS_SCENE.read_text().splitlines()
             if line.strip().startswith("pose:")]
    assert len(poses) == 2
    robot = arcplan.load_robot()
    for q, pose in ((path[0], poses[0]), (path[-1], poses[1])):
        xyz_rpy = [eval(value, {"pi": np.pi}) for value in pose]  # numbers and "-pi", "pi/2"
        np.testing.assert_allclose(robot.fk(q), arcplan.pose_from_xyz_rpy(xyz_rpy), atol=1e-9)
    # Time-scaled under 0.25 m/s: the trajectory samples and its metrics.
    trajectory = result.trajectory
    assert trajectory.tcp_speed.max() <= 0.25 + 1e-9
    assert trajectory.duration == pytest.approx(result.execution_time_s, abs=1e-12)
    assert trajectory.metrics["tcp_path_length_m"] == result.tcp_path_length_m


def test_a_planner_that_finds_nothing_is_a_result_with_the_clis_reason(tmp_path):
    # A 1 mm detour passes the particle closer than the arc planner's 1 cm clearance.
    result = arcplan.plan(THESIS_SCENE, params={"sagitta": 0.001})
    assert result.status == "failed" and result.path.shape == (0, 6) and result.tcp_path_length_m is None
    run = subprocess.run([os.environ["ARCPLAN_EXECUTABLE"], "plan", "--scene", str(THESIS_SCENE), "--param",
                          "sagitta=0.001", "--json", str(tmp_path / "failed.json")], capture_output=True, text=True)
    assert run.returncode == 1
    assert run.stderr.strip() == "arcplan: error: planner arc found no path: " + result.reason
    expected = json.loads((tmp_path / "failed.json").read_text())
    document = result.to_dict()
    for key in ("solve_time_s", "simplification_time_s", "time_limit_s"):
        del document[key], expected[key]
    assert document == expected
    # A goal out of reach cannot even be set up: an error naming it.
    unreachable = tmp_path / "unreachable.yaml"
    unreachable.write_text(THESIS_SCENE.read_text().replace("[0.5, 0.4, 0.46", "[2.5, 0.4, 0.46"))
    with pytest.raises(arcplan.Error, match="goal"):
        arcplan.plan(unreachable)


def test_planner_names_come_from_the_registry():
    names = arcplan.planner_names()
    assert names[0] == "arc" and "RRTConnect" in names and "PRMstar" in names
    # Any spelling the registry accepts, as on the command line.
    assert arcplan.plan(THESIS_SCENE, planner="rrtconnect", seed=1).planner == "RRTConnect"


@pytest.mark.parametrize("arguments, message", [
    ({"planner": "NoSuchPlanner"}, "NoSuchPlanner"),
    ({"params": {"no_such_parameter": 1}}, "no_such_parameter"),
    ({"params": {"sagitta": "abc"}}, "sagitta"),
    ({"time_limit": 0.0}, "plan: the time limit must be a positive number of seconds"),
    ({"time_limit": float("nan")}, "plan: the time limit must be a positive number of seconds"),
    ({"vmax": -1.0}, "plan: vmax must be a positive TCP speed in m/s"),
    ({"clearance": -0.01}, "plan: the clearance must be a distance >= 0 m"),
    ({"query": "no_such_query"}, "no_such_query"),
])
def test_bad_requests_raise_arcplan_error(arguments, message):
    with pytest.raises(arcplan.Error) as raised:
        arcplan.plan(THESIS_SCENE, **arguments)
    assert message in str(raised.value)


def test_cli_and_python_give_the_same_message():
    with pytest.raises(arcplan.Error) as raised:
        arcplan.plan(THESIS_SCENE, planner="NoSuchPlanner")
    run = subprocess.run([os.environ["ARCPLAN_EXECUTABLE"], "plan", "--scene", str(THESIS_SCENE), "--planner",
                          "NoSuchPlanner"], capture_output=True, text=True)
    assert run.returncode != 0
    assert run.stderr.strip() == "arcplan: error: " + str(raised.value)


def test_missing_or_wrong_scene_raises(tmp_path):
    with pytest.raises(arcplan.Error, match="missing.yaml"):
        arcplan.plan(tmp_path / "missing.yaml")
    with pytest.raises(arcplan.Error) as raised:
        arcplan.plan(42)
    assert str(raised.value) == "scene_file: expected a scene file (str or path) or an arcplan.Scene, got int"


def test_planning_releases_the_gil():
    # RRT* optimises for its whole time limit (0.3 s here): this thread runs meanwhile only if the GIL is free.
    scene = arcplan.load_scene(THESIS_SCENE)
    assert main_thread_ran_during(lambda: arcplan.plan(scene, planner="RRTstar", time_limit=0.3))
