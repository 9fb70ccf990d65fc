"""arcplan.Scene against the CLI (`arcplan robot check --json`) and the vectorised is_valid against
the one-configuration check, state by state."""
import numpy as np
import pytest

import arcplan
from conftest import THESIS_SCENE

# Arm over the table, clear of everything; the upper arm pushed down through the table.
FREE = np.array([0.0, -1.57, 1.57, -1.57, -1.57, 0.0])
IN_TABLE = np.array([0.0, 0.3, 0.0, 0.0, 0.0, 0.0])


@pytest.fixture(scope="module")
def scene():
    return arcplan.load_scene("scenes/thesis_obstacle.yaml")


def joints_text(q):
    return ",".join(repr(float(v)) for v in q)


def test_scene_names(scene):
    assert scene.name == "thesis_obstacle"
    assert scene.source_file == THESIS_SCENE
    assert scene.query_names == ["A_to_B"]
    assert scene.obstacle_names == ["table", "particle"]
    assert "wrist_3_link" in scene.link_names
    assert scene.robot.name == "ur10e" and scene.robot.dof == 6
    # The same scene by its path.
    assert arcplan.load_scene(str(THESIS_SCENE)).obstacle_names == scene.obstacle_names


@pytest.mark.parametrize("q", [FREE, IN_TABLE], ids=["free", "in_table"])
def test_validity_and_distances_equal_cli(scene, cli, q):
    expected = cli("robot", "check", "--scene", THESIS_SCENE, "--joints", joints_text(q))
    assert scene.is_valid(q) is expected["valid"]
    assert sorted(map(list, scene.collisions(q))) == sorted(expected["collisions"])
    distance = scene.distance(q)
    assert distance.obstacle_distance == pytest.approx(expected["obstacle_distance_m"], abs=1e-12)
    assert list(distance.obstacle_pair) == expected["obstacle_pair"]
    assert distance.self_distance == pytest.approx(expected["self_distance_m"], abs=1e-12)
    assert list(distance.self_pair) == expected["self_pair"]
    closest = min(expected["obstacle_distance_m"], expected["self_distance_m"])
    assert distance.minimum == pytest.approx(closest, abs=1e-12)
    # What a clearance is judged by (self pairs count only below 1 mm): robot check's clearance.
    assert distance.clearance == pytest.approx(expected["clearance_m"], abs=1e-12)


def test_in_table_is_a_contact_with_the_table(scene):
    assert scene.is_valid(IN_TABLE) is False
    assert any("table" in pair for pair in scene.collisions(IN_TABLE))
    assert scene.distance(IN_TABLE).obstacle_distance == 0.0


def test_batch_equals_one_by_one(scene):
    rng = np.random.default_rng(7)
    robot = scene.robot
    # Joints 1 and 2 within +-pi around the upright pose: a mix of free and colliding states.
    states = rng.uniform(-np.pi, np.pi, size=(3000, 6)) + FREE
    states = np.clip(states, robot.lower_limits, robot.upper_limits)
    valid = scene.is_valid(states)
    assert valid.dtype == np.bool_ and valid.shape == (3000,)
    expected = np.array([scene.is_valid(q) for q in states])
    np.testing.assert_array_equal(valid, expected)
    assert 0 < valid.sum() < len(valid)  # both kinds are in the sample


def test_batch_takes_any_layout_and_dtype(scene):
    states = np.stack([FREE, IN_TABLE, FREE])
    np.testing.assert_array_equal(scene.is_valid(states), [True, False, True])
    np.testing.assert_array_equal(scene.is_valid(np.asfortranarray(states)), [True, False, True])
    np.testing.assert_array_equal(scene.is_valid(states.astype(np.float32)), [True, False, True])
    np.testing.assert_array_equal(scene.is_valid(states.tolist()), [True, False, True])
    assert scene.is_valid(np.empty((0, 6))).shape == (0,)


@pytest.mark.parametrize("bad, message", [
    (np.zeros((4, 5)), "Q: expected an (N, 6) array of joint vectors, got shape (4, 5)"),
    (np.zeros((2, 6, 1)), "q: expected 6 joint values, shape (6,), got shape (2, 6, 1)"),
    (np.array([FREE, [0, 0, np.inf, 0, 0, 0]]), "Q: element 8 is inf; expected finite numbers"),
    (np.zeros(7), "q: expected 6 joint values, shape (6,), got shape (7,)"),
])
def test_bad_arrays_raise_arcplan_error(scene, bad, message):
    with pytest.raises(arcplan.Error) as raised:
        scene.is_valid(bad)
    assert str(raised.value) == message


def test_bad_scene_files_raise_arcplan_error(tmp_path):
    with pytest.raises(arcplan.Error, match="no_such_scene.yaml"):
        arcplan.load_scene(tmp_path / "no_such_scene.yaml")
    broken = tmp_path / "broken.yaml"
    broken.write_text("name: broken\nobstacles:\n  - name: box\n    cube: {size: [1, 1, 1]}\n")
    with pytest.raises(arcplan.Error, match=r"broken.yaml:\d+"):  # arcplan's file:line
        arcplan.load_scene(broken)
