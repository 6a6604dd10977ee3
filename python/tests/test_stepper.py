"""The hierarchy in the loop from Python (`Hsom.stepper`, `GestureModel.stepper`): undisturbed
it is its reproduction; held, it re-joins its gesture without a jump and finishes it, where
the plan replayed by its clock (the negative control) jumps; a goal moved half-way is
reached exactly; goal and via-points as `reproduce` takes them; bad input is a ValueError."""

import numpy as np
import pytest

import cosco_hsom
from conftest import GESTURES_XML, SHAPE_XML
from gestures2d import gestures


@pytest.fixture(scope="module")
def shape():
    """A figure eight learned from six demonstrations; the seventh held out."""
    from shape2d import figure_eight

    rng = np.random.default_rng(7)
    demos = [figure_eight(rng) for _ in range(7)]
    cfg = cosco_hsom.Config.from_xml(SHAPE_XML)
    return cosco_hsom.Hsom.fit(cfg, demos[1:], columns=["x", "y"]), demos


def largest_step(path):
    return np.linalg.norm(np.diff(np.asarray(path), axis=0), axis=1).max()


def diagonal(demos):
    rows = np.vstack(demos)
    return np.linalg.norm(rows.max(axis=0) - rows.min(axis=0))


def run(stepper, initial, hold=None, goal_at=None, goal=None, limit=5000):
    """The kinematic loop: the arm goes where it is commanded, except at the ticks `hold`
    (a range) keeps it still; at tick `goal_at` the goal moves to `goal`."""
    arm = np.asarray(initial, dtype=float)
    path = [arm]
    for k in range(limit):
        if k == goal_at:
            stepper.goal = goal
        command = stepper.step(arm)
        arm = arm if hold is not None and (k + 1) in hold else command
        path.append(arm)
        if stepper.done and not (hold is not None and (k + 1) in hold):
            return np.array(path)
    raise AssertionError("the reproduction did not finish")


def test_undisturbed_the_loop_is_the_reproduction(shape):
    model, demos = shape
    initial = demos[0][0]
    plan = model.reproduce(initial)
    s = model.stepper(initial)
    assert not s.done and s.goal is None and s.phase == 0.0
    path = run(s, initial)
    # the path starts at the initial posture, the plan at it read back through the model's
    # normalisation (within an ulp)
    np.testing.assert_array_equal(path[1:], plan[1:])
    np.testing.assert_allclose(path[0], plan[0], rtol=0, atol=1e-12)
    assert s.done and s.phase == 1.0 and s.replans == 0
    assert isinstance(s.step(plan[-1]), np.ndarray)


def test_held_it_rejoins_without_a_jump_and_the_replay_jumps(shape):
    model, demos = shape
    initial = demos[0][0]
    plan = model.reproduce(initial)
    n = len(plan) - 1
    hold = range(round(0.4 * n), round(0.4 * n) + round(0.25 * n))
    release = hold.stop
    scale = max(largest_step(demos[0]), largest_step(plan))
    s = model.stepper(initial)
    path = run(s, initial, hold=hold)
    assert s.replans > 0
    assert largest_step(path[release - 1 :]) <= 2 * scale
    assert np.linalg.norm(path[-1] - plan[-1]) <= 0.02 * diagonal(demos)
    # the negative control: the same plan by its clock, the reading ignored
    replay = [plan[k] if k not in hold else plan[hold.start - 1] for k in range(len(plan))]
    assert largest_step(replay[release - 1 :]) > 2 * scale


def test_a_goal_moved_half_way_is_reached_exactly(shape):
    model, demos = shape
    initial = demos[0][0]
    plan = model.reproduce(initial)
    goal = plan[-1] + 0.1 * diagonal(demos) / np.sqrt(2)
    at = round(0.5 * (len(plan) - 1))
    s = model.stepper(initial)
    path = run(s, initial, goal_at=at, goal=goal)
    np.testing.assert_array_equal(path[1 : at + 1], plan[1 : at + 1])
    assert np.linalg.norm(path[-1] - goal) <= 1e-6 * diagonal(demos)
    np.testing.assert_array_equal(s.goal, goal)
    assert largest_step(path[at:]) <= 2 * max(largest_step(demos[0]), largest_step(plan))


def test_goal_and_via_points_as_reproduce_takes_them(shape):
    model, demos = shape
    initial = demos[0][0]
    plain = model.reproduce(initial)
    goal = plain[-1] + np.array([3.0, -2.0])
    via = [(0.4, plain[len(plain) // 3] + np.array([2.0, 1.0]))]
    bent = model.reproduce(initial, goal=goal, via=via)
    s = model.stepper(initial, goal=goal, via=via)
    path = run(s, initial)
    np.testing.assert_array_equal(path[1:], bent[1:])
    np.testing.assert_array_equal(s.goal, goal)


def test_gesture_model_stepper():
    cfg = cosco_hsom.Config.from_xml(GESTURES_XML)
    taught = gestures(count=3, seed=0)
    model = cosco_hsom.GestureModel.fit(cfg, taught, columns=["x", "y"])
    initial = taught["up"][0][0]
    s = model.stepper("up", initial)
    path = run(s, initial)
    np.testing.assert_array_equal(path[1:], model.reproduce("up", initial)[1:])
    with pytest.raises(ValueError, match="up, right, diag"):
        model.stepper(None, initial)
    with pytest.raises(ValueError, match="nope"):
        model.stepper("nope", initial)


def test_bad_input_is_a_value_error(shape):
    model, demos = shape
    initial = demos[0][0]
    with pytest.raises(ValueError, match="the initial posture has 3 values"):
        model.stepper([0.0, 1.0, 2.0])
    with pytest.raises(ValueError, match="goal"):
        model.stepper(initial, goal=[0.0])
    with pytest.raises(ValueError, match="phase"):
        model.stepper(initial, via=[(1.5, initial)])
    s = model.stepper(initial)
    with pytest.raises(ValueError, match="the observed posture has 1 values"):
        s.step([0.0])
    with pytest.raises(ValueError, match="the observed posture: y is NaN"):
        s.step([0.0, np.nan])
    with pytest.raises(ValueError, match="the goal has 3 values"):
        s.goal = [0.0, 1.0, 2.0]
    with pytest.raises(ValueError, match="observed"):
        s.step("not a posture")
    assert s.goal is None
