"""Teaching a saved model more from Python: `model.update(demos, label=None)` returns a new
model learned from the model and the new demonstrations alone; nothing taught changes
nothing; a new label adds a gesture without losing the others; bad input is refused."""

import numpy as np
import pytest

import cosco_hsom
from conftest import GESTURES_XML, SHAPE_XML
from gestures2d import APEXES, gestures

LABELS = list(APEXES)


def dtw(a, b):
    """Per-step DTW between two 2-D arrays (Euclidean local cost)."""
    n, m = len(a), len(b)
    cost = np.linalg.norm(a[:, None, :] - b[None, :, :], axis=2)
    acc = np.full((n + 1, m + 1), np.inf)
    steps = np.zeros((n + 1, m + 1))
    acc[0, 0] = 0
    for i in range(1, n + 1):
        for j in range(1, m + 1):
            k = np.argmin([acc[i - 1, j - 1], acc[i - 1, j], acc[i, j - 1]])
            prev = [(i - 1, j - 1), (i - 1, j), (i, j - 1)][k]
            acc[i, j] = cost[i - 1, j - 1] + acc[prev]
            steps[i, j] = steps[prev] + 1
    return acc[n, m] / steps[n, m]


def test_a_gesture_in_two_sittings_and_an_empty_update(demos):
    cfg = cosco_hsom.Config.from_xml(SHAPE_XML)
    first = cosco_hsom.Hsom.fit(cfg, demos[:2], columns=["x", "y"])
    assert first.learned == {"demonstrations": 2, "kept": 2, "updates": 0}
    updated = first.update(demos[2:])
    assert updated.learned == {"demonstrations": 7, "kept": 6, "updates": 1}
    # the model it came from is unchanged; an update with nothing is the same model
    assert first.learned["updates"] == 0
    assert first.update([]).learned == first.learned
    np.testing.assert_array_equal(first.update([]).reproduce(demos[0][0]), first.reproduce(demos[0][0]))
    rep = updated.reproduce(demos[0][0])
    assert rep.shape[1] == 2 and len(rep) > 10
    with pytest.raises(ValueError, match="unlabelled"):
        first.update(demos[2:], label="up")
    with pytest.raises(ValueError, match="columns"):
        first.update([np.zeros((20, 3))])


def test_a_new_gesture_is_added_without_forgetting_the_first():
    cfg = cosco_hsom.Config.from_xml(GESTURES_XML)
    taught = gestures(count=3, seed=0)
    a, b = LABELS[0], LABELS[1]
    one = cosco_hsom.GestureModel.fit(cfg, {a: taught[a]}, columns=["x", "y"])
    two = one.update(taught[b], label=b)
    assert two.labels == [a, b] and one.labels == [a]
    assert two.learned[b] == {"demonstrations": 3, "kept": 3, "updates": 0}
    held = gestures(count=1, seed=7)
    for label in (a, b):
        start = held[label][0][0]
        rep = two.reproduce(label, start)
        own = dtw(rep, held[label][0])
        other = dtw(rep, held[b if label == a else a][0])
        # its own gesture, not the other one (the negative control)
        assert own < 0.5 * other, (label, own, other)
        assert two.recognize(held[label][0]).label == label
    with pytest.raises(ValueError, match="several gestures"):
        two.update(taught[a])


def test_heldout_in_two_sittings_beside_at_once(demos):
    cfg = cosco_hsom.Config.from_xml(SHAPE_XML)
    report = cosco_hsom.heldout(
        cfg, demos[:5], columns=["x", "y"], height_1=False, gmr=False, in_sample=False, sittings=True
    )
    ratios = {r["method"]: r for r in report["sittings"]["against_at_once"]}
    h = ratios["hierarchy"]
    assert h["at_once"] > 0 and h["in_sittings"] > 0
    assert h["ratio"] == pytest.approx(h["in_sittings"] / h["at_once"])
    # ProMP refits on what a model keeps of the first half and the rest: with every
    # demonstration kept, the same fit
    assert ratios["promp"]["ratio"] == pytest.approx(1.0, abs=0.02)
    assert "sittings" not in cosco_hsom.heldout(cfg, demos[:4], columns=["x", "y"], in_sample=False)
