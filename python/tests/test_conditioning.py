"""Beyond the demonstrated path from Python: a goal, via-points and the confidence band of a
reproduction, the conditioned held-out study, and the DMP baseline against the package
movement_primitives on the same demonstration."""

import numpy as np
import pytest

import cosco_hsom
from conftest import SHAPE_XML


def at_phase(rows, phase):
    """The posture at `phase`, linear between the two rows about it (as the library reads it)."""
    x = phase * (len(rows) - 1)
    i = min(int(np.floor(x)), len(rows) - 2)
    return rows[i] + (x - i) * (rows[i + 1] - rows[i])


def test_reproduce_meets_a_goal_and_a_via_point_and_gives_its_band(demos):
    cfg = cosco_hsom.Config.from_xml(SHAPE_XML)
    model = cosco_hsom.Hsom.fit(cfg, demos, columns=["x", "y"])
    initial = demos[0][0]
    plain = model.reproduce(initial)
    goal = plain[-1] + np.array([0.3, -0.2])
    via = at_phase(plain, 0.4) + np.array([0.2, 0.1])
    path, lo, hi = model.reproduce(initial, goal=goal, via=[(0.4, via)], band=True)
    scale = np.abs(np.vstack(demos)).max()
    assert np.abs(path[-1] - goal).max() < 1e-9 * scale
    assert np.abs(at_phase(path, 0.4) - via).max() < 1e-9 * scale
    np.testing.assert_allclose(path[0], initial, rtol=0, atol=1e-12)
    # the band is about the reproduction, one row per row, and wider somewhere than nothing
    assert lo.shape == path.shape == hi.shape
    assert np.all(lo <= path + 1e-12) and np.all(path <= hi + 1e-12)
    assert (hi - lo).max() > 0
    # negative control: the reproduction without the conditions misses them
    assert np.abs(plain[-1] - goal).max() > 0.1
    assert np.abs(at_phase(plain, 0.4) - via).max() > 0.1
    # without band=True, the postures alone
    assert isinstance(model.reproduce(initial, goal=goal), np.ndarray)


def test_bad_conditions_are_named_errors(demos):
    cfg = cosco_hsom.Config.from_xml(SHAPE_XML)
    model = cosco_hsom.Hsom.fit(cfg, demos)
    initial = demos[0][0]
    with pytest.raises(ValueError, match="goal"):
        model.reproduce(initial, goal=[0.0, 1.0, 2.0])
    with pytest.raises(ValueError, match="phase"):
        model.reproduce(initial, via=[(1.5, initial)])
    with pytest.raises(ValueError, match="phase 0.5"):
        model.reproduce(initial, via=[(0.5, [0.0, 0.0]), (0.5, [1.0, 1.0])])
    with pytest.raises(ValueError, match="finite"):
        model.reproduce(initial, goal=[np.nan, 0.0])


def test_heldout_conditioned_beside_unconditioned(demos):
    cfg = cosco_hsom.Config.from_xml(SHAPE_XML)
    doc = cosco_hsom.heldout(cfg, demos, gmr=False, height_1=False, in_sample=False, condition="end+mid")
    assert doc["conditioned"]["condition"] == "end+mid"
    summary = {s["method"]: s for s in doc["conditioned"]["summary"]}
    assert summary["hierarchy"]["worst_goal_error"] < 1e-6
    assert summary["hierarchy"]["worst_via_error"] < 1e-6
    plain = {s["method"]: s for s in doc["summary"]}
    assert plain["hierarchy"]["worst_goal_error"] is None
    assert 0.0 < plain["hierarchy"]["coverage"] <= 1.0
    assert "dmp" in plain
    with pytest.raises(ValueError, match="condition"):
        cosco_hsom.heldout(cfg, demos, condition="middle")


def swing(n=120):
    t = np.linspace(0.0, 1.0, n)
    return np.column_stack([np.sin(2 * np.pi * t) * (1 - t) + t, np.cos(3 * t) - 0.5 * t])


def test_the_dmp_agrees_with_movement_primitives():
    dmp_module = pytest.importorskip("movement_primitives.dmp")
    demo = swing()
    period = 1.0 / 40.0
    times = np.arange(len(demo)) * period
    theirs = dmp_module.DMP(2, execution_time=times[-1], dt=period, n_weights_per_dim=50)
    theirs.imitate(times, demo)
    theirs.configure(start_y=demo[0], goal_y=demo[-1])
    _, their_rows = theirs.open_loop(step_function="euler")
    span = np.ptp(demo, axis=0).max()

    def gap(basis):
        ours = cosco_hsom.Dmp.fit([demo], basis=basis).reproduce(demo[0], demo[-1])
        n = min(len(ours), len(their_rows))
        return np.abs(ours[:n] - their_rows[:n]).max() / span

    # the same formulation and weights agree to within 1 % of the motion's range
    agreement = gap(50)
    print(f"DMP against movement_primitives (Euler): {100 * agreement:.3f} % of the range")
    assert agreement < 0.01
    # negative control: too few basis functions to learn the same forcing term
    assert gap(4) > 0.01


def test_a_duration_retimes_the_reproduction_and_keeps_its_path(demos):
    cfg = cosco_hsom.Config.from_xml(SHAPE_XML)
    model = cosco_hsom.Hsom.fit(cfg, demos, columns=["x", "y"])
    initial = demos[0][0]
    plain = model.reproduce(initial)
    own = (len(plain) - 1) / 40.0
    for factor in (0.5, 2.0):
        path = model.reproduce(initial, duration=factor * own)
        assert abs((len(path) - 1) / 40.0 / (factor * own) - 1) <= 0.05
        phases = np.linspace(0, 1, 101)
        gap = np.mean([np.abs(at_phase(path, p) - at_phase(plain, p)).mean() for p in phases])
        assert gap <= 0.05 * np.abs(np.vstack(demos)).max()
        # negative control: the reproduction at its own tempo is not of that duration
        assert abs(len(plain) / len(path) - 1) > 0.05
    path, lo, hi = model.reproduce(initial, band=True, duration=2 * own)
    assert lo.shape == path.shape == hi.shape
    with pytest.raises(ValueError, match="--duration"):
        model.reproduce(initial, duration=-1.0)
