"""Recognition in the loop from Python (GestureModel.recognizer()): push one sample at a
time, the committed label never changes, finish() is recognize() on every sample pushed;
held-out demonstrations committed to their own label before their end, a gesture never
taught committed to no label, and the negative control (committing at the first sample to
the label recognize() would then give) failing the wrong-commit bound."""

import numpy as np
import pytest

import cosco_hsom
from conftest import GESTURES_XML
from gestures2d import APEXES, NEVER_TAUGHT, gestures

LABELS = list(APEXES)
WRONG_COMMIT_BOUND = 0.02


@pytest.fixture(scope="module")
def model():
    cfg = cosco_hsom.Config.from_xml(GESTURES_XML)
    return cosco_hsom.GestureModel.fit(cfg, gestures(count=3, seed=0), columns=["x", "y"])


@pytest.fixture(scope="module")
def held_out():
    return [(l, d) for l, ds in gestures(count=4, seed=100).items() for d in ds]


def stream(model, d):
    """Push every sample of `d`: (what each push returned, decided after each, recogniser)."""
    r = model.recognizer()
    out, decided = [], []
    for x in d:
        out.append(r.push(x))
        decided.append(r.decided)
    return out, decided, r


def test_pushes_commit_once_and_finish_is_recognize(model, held_out):
    wrong = 0
    for label, d in held_out:
        out, decided, r = stream(model, d)
        assert decided[-1], (label, r)
        k = decided.index(True)
        # from the sample it committed on, the same answer at every push
        assert all(o is None for o in out[:k])
        assert all(o == out[k] for o in out[k:])
        assert r.committed_at == k + 1 < len(d)
        wrong += out[k] != label
        assert r.samples == len(d)
        whole = model.recognize(d)
        fin = r.finish()
        assert isinstance(fin, cosco_hsom.Recognition)
        assert fin.to_dict() == whole.to_dict()
    assert wrong / len(held_out) <= WRONG_COMMIT_BOUND


def test_a_gesture_never_taught_is_not_committed_to(model):
    for d in gestures(count=3, seed=200, apexes={"down": NEVER_TAUGHT})["down"]:
        out, decided, r = stream(model, d)
        assert all(o is None for o in out), r
        assert r.finish().to_dict() == model.recognize(d).to_dict()


def test_committing_at_the_first_sample_fails_the_wrong_commit_bound(model, held_out):
    """The negative control: every stream committed at its first sample, to the label
    recognize() gives on what has been seen (the first two samples, the fewest it takes)."""
    wrong = sum(model.recognize(d[:2]).label != label for label, d in held_out)
    assert wrong / len(held_out) > WRONG_COMMIT_BOUND


def test_bad_samples_are_refused_and_leave_the_recogniser_as_it_was(model, held_out):
    r = model.recognizer()
    d = held_out[0][1]
    r.push(d[0])
    with pytest.raises(ValueError, match="the stream"):
        r.push([0.0, 0.0, 0.0])
    with pytest.raises(ValueError, match="the stream"):
        r.push([np.nan, 0.0])
    with pytest.raises(ValueError, match="sample"):
        r.push(np.zeros((2, 2)))
    assert r.samples == 1 and not r.decided
    # one sample: finish() refuses as recognize() does
    with pytest.raises(ValueError, match="at least 2"):
        r.finish()
    for x in d[1:]:
        r.push(x)
    assert r.finish().to_dict() == model.recognize(d).to_dict()
    assert repr(r).startswith("Recognizer(")
