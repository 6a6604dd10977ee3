"""Several gestures in one hierarchy from Python (GestureModel): reproduction on cue and
recognition of held-out demonstrations, each beside a negative control (labels rotated
among the gestures), "unknown" for a gesture never taught, continuing a prefix, save/load,
and bad input."""

import numpy as np
import pytest

import cosco_hsom
from conftest import GESTURES_XML, assert_threaded_fits_match_serial
from gestures2d import APEXES, NEVER_TAUGHT, gestures

LABELS = list(APEXES)


@pytest.fixture(scope="module")
def cfg():
    return cosco_hsom.Config.from_xml(GESTURES_XML)


@pytest.fixture(scope="module")
def taught():
    return gestures(count=3, seed=0)


@pytest.fixture(scope="module")
def model(cfg, taught):
    return cosco_hsom.GestureModel.fit(cfg, taught, columns=["x", "y"])


@pytest.fixture(scope="module")
def rotated(cfg, taught):
    """The negative control: every label given the next gesture's demonstrations."""
    return cosco_hsom.GestureModel.fit(
        cfg, {l: taught[LABELS[(i + 1) % len(LABELS)]] for i, l in enumerate(LABELS)}
    )


@pytest.fixture(scope="module")
def held_out():
    return gestures(count=4, seed=100)


def mean_dtw(path, demos):
    return np.mean([cosco_hsom.dtw(path, d, per_step=True) for d in demos])


def nearest_label(path, taught):
    """The label whose demonstrations the path is closest to (DTW per step)."""
    return min(taught, key=lambda l: mean_dtw(path, taught[l]))


def test_fit_keeps_the_labels_and_columns(model, cfg):
    assert model.labels == LABELS
    assert model.columns == ["x", "y"]
    # every label's branch is the gesture learned alone, with the configuration given
    assert model.config.to_xml() == cfg.to_xml()
    assert repr(model).startswith("GestureModel(") and '"diag"' in repr(model)


def test_the_label_chooses_the_gesture_reproduced(model, rotated, taught):
    # Every gesture starts at the origin: only the label can choose.
    for label in LABELS:
        path = model.reproduce(label, [0.0, 0.0])
        assert isinstance(path, np.ndarray) and path.dtype == np.float64
        assert path.ndim == 2 and path.shape[1] == 2 and len(path) > 40
        np.testing.assert_array_equal(path[0], [0.0, 0.0])
        assert nearest_label(path, taught) == label
    # Negative control: with the labels rotated, the comparison names the other gesture.
    for label in LABELS:
        assert nearest_label(rotated.reproduce(label, np.zeros(2)), taught) != label


def test_held_out_demonstrations_are_recognised(model, rotated, held_out):
    answers = [(truth, model.recognize(d)) for truth, ds in held_out.items() for d in ds]
    assert all(r.label == truth for truth, r in answers), answers
    for truth, r in answers:
        assert not r.unknown and r.best == truth
        assert list(r.scores) == LABELS and list(r.thresholds) == LABELS
        assert r.scores[truth] <= r.thresholds[truth]
        assert 0 < r.decided_at <= r.samples
    # early recognition: the decision is final before the end of the gesture
    assert np.median([r.decided_fraction for _, r in answers]) < 0.9
    # scores() is recognize()'s scores
    d = held_out["right"][0]
    assert model.scores(d) == model.recognize(d).scores
    assert model.scores(d.tolist()) == model.scores(d)
    # Negative control: labels rotated among the gestures, none is recognised as itself.
    assert not any(rotated.recognize(d).label == t for t, ds in held_out.items() for d in ds)


def test_a_gesture_never_taught_is_unknown(model):
    for d in gestures(count=3, seed=200, apexes={"down": NEVER_TAUGHT})["down"]:
        r = model.recognize(d)
        assert r.label is None and r.unknown, r
        assert r.best in LABELS and r.scores[r.best] > r.thresholds[r.best]
        assert r.to_dict()["label"] is None


def test_continue_a_prefix(model, held_out):
    g = held_out["diag"][1]
    label, path = model.continue_prefix(g[:60])
    assert label == "diag"
    np.testing.assert_array_equal(path[:60], g[:60])
    assert path.shape[1] == 2 and len(path) > 80


@pytest.mark.parametrize("ext", ["bin", "txt"])
def test_save_load_round_trip(model, held_out, tmp_path, ext):
    p = tmp_path / f"m.{ext}"
    model.save(p)
    back = cosco_hsom.GestureModel.load(str(p))
    assert back.labels == LABELS and back.columns == ["x", "y"]
    for label in LABELS:
        np.testing.assert_array_equal(back.reproduce(label, [0.0, 0.0]),
                                      model.reproduce(label, [0.0, 0.0]))
    d = held_out["up"][0]
    assert back.recognize(d).to_dict() == model.recognize(d).to_dict()
    back.save(tmp_path / f"again.{ext}")
    assert (tmp_path / f"again.{ext}").read_bytes() == p.read_bytes()
    # Hsom (one gesture) refuses it, saying what to use
    with pytest.raises(ValueError, match=rf"m\.{ext}: a model of several gestures \(up, right, diag\): load it with GestureModel.load"):
        cosco_hsom.Hsom.load(p)


def test_a_single_gesture_file_loads_as_one_unlabelled_gesture(cfg, taught, tmp_path):
    single = cosco_hsom.Hsom.fit(cfg, taught["up"], columns=["x", "y"])
    single.save(tmp_path / "one.bin")
    g = cosco_hsom.GestureModel.load(tmp_path / "one.bin")
    assert g.labels == []
    np.testing.assert_array_equal(g.reproduce(None, [0.0, 0.0]), single.reproduce([0.0, 0.0]))
    g.save(tmp_path / "again.bin")
    assert (tmp_path / "again.bin").read_bytes() == (tmp_path / "one.bin").read_bytes()
    with pytest.raises(ValueError, match="single-gesture model has no labels"):
        g.recognize(taught["up"][0])
    with pytest.raises(ValueError, match=r'no gesture "up" in the model; it holds: no labels'):
        g.reproduce("up", [0.0, 0.0])


def test_levels_report_held_out_accuracy_and_keep_it_when_saved(cfg, taught, tmp_path):
    single = cosco_hsom.Hsom.fit(cfg, taught["up"], columns=["x", "y"])
    levels = single.summary()["levels"]
    for l in levels[1:]:
        for key in ("heldout_prediction_accuracy", "heldout_lookup_accuracy"):
            assert 0.0 <= l[key] <= 1.0, (key, l)
    # held out on level 1 is measured, not a copy of the in-sample figure
    assert levels[1]["heldout_prediction_accuracy"] != levels[1]["prediction_accuracy"]
    single.save(tmp_path / "one.txt")
    assert cosco_hsom.Hsom.load(tmp_path / "one.txt").summary()["levels"] == levels


# ---- bad input: the library's messages (the CLI's; test_cli_parity.py compares them) ----


def test_unknown_or_missing_label_lists_the_labels(model):
    with pytest.raises(ValueError, match=r'^no gesture "wave" in the model; it holds: up, right, diag$'):
        model.reproduce("wave", [0.0, 0.0])
    with pytest.raises(ValueError, match=r"holds several gestures \(up, right, diag\): choose one"):
        model.reproduce(None, [0.0, 0.0])
    # the label is checked before the posture
    with pytest.raises(ValueError, match="wave"):
        model.reproduce("wave", [0.0, 0.0, 0.0])
    with pytest.raises(ValueError, match="the initial posture has 3 values"):
        model.reproduce("up", [0.0, 0.0, 0.0])


@pytest.mark.parametrize("label", ["two words", "", "é", "a/b"])
def test_a_label_that_is_not_a_plain_word(cfg, taught, label):
    with pytest.raises(ValueError, match=r"is not a plain word: use letters, digits, '_' and '-' only"):
        cosco_hsom.GestureModel.fit(cfg, {"up": taught["up"], label: taught["right"]})


def test_a_label_without_demonstrations(cfg, taught):
    with pytest.raises(ValueError, match=r'^gesture "right" has no demonstrations$'):
        cosco_hsom.GestureModel.fit(cfg, {"up": taught["up"], "right": []})
    with pytest.raises(ValueError, match="no demonstrations"):
        cosco_hsom.GestureModel.fit(cfg, {})


def test_mixed_widths_across_labels(cfg, taught):
    wide = [np.hstack([d, d[:, :1]]) for d in taught["right"]]
    msg = r"gestures\['wide'\]\[0\]: 3 state columns but the configured state length is 2"
    with pytest.raises(ValueError, match=msg):
        cosco_hsom.GestureModel.fit(cfg, {"up": taught["up"], "wide": wide})
    with pytest.raises(ValueError, match=msg):
        cosco_hsom.GestureModel.fit(cfg, {"up": taught["up"], "wide": wide}, columns=["x", "y"])
    with pytest.raises(ValueError, match=r"columns: 3 names \(a, b, c\) for demonstrations of 2"):
        cosco_hsom.GestureModel.fit(cfg, taught, columns=["a", "b", "c"])


def test_not_a_mapping_of_lists_of_arrays(cfg, taught):
    for bad in [taught["up"], taught["up"][0], "up", 3]:
        with pytest.raises(ValueError, match="gestures: a mapping label -> list of demonstrations"):
            cosco_hsom.GestureModel.fit(cfg, bad)
    with pytest.raises(ValueError, match=r"the labels must be strings \(plain words\); got 1 of type int"):
        cosco_hsom.GestureModel.fit(cfg, {1: taught["up"]})
    with pytest.raises(ValueError, match=r"gestures\['up'\]: .*wrap it in a list"):
        cosco_hsom.GestureModel.fit(cfg, {"up": taught["up"][0]})
    ragged = taught["right"][1].tolist()
    ragged[5] = ragged[5][:1]
    with pytest.raises(ValueError, match=r"gestures\['right'\]\[1\]: sample 5 has 1 values"):
        cosco_hsom.GestureModel.fit(cfg, {"up": taught["up"], "right": [taught["right"][0], ragged]})
    bad = taught["up"][2].copy()
    bad[7, 0] = np.nan
    with pytest.raises(ValueError, match=r"gestures\['up'\]\[2\]: sample 7, column `x0`"):
        cosco_hsom.GestureModel.fit(cfg, {"up": [taught["up"][0], taught["up"][1], bad]})


def test_the_paper_algorithm_is_refused(taught):
    paper = cosco_hsom.Config.table1().replace(state_length=2, training_steps=100)
    with pytest.raises(ValueError, match="several gestures need algorithm = events"):
        cosco_hsom.GestureModel.fit(paper, taught)


def test_bad_sequences(model, held_out):
    d = held_out["up"][0]
    with pytest.raises(ValueError, match="sequence: a 2-D array"):
        model.recognize(d[:, 0])
    with pytest.raises(ValueError, match="the sequence"):
        model.recognize(np.hstack([d, d]))
    with pytest.raises(ValueError, match="the sequence"):
        model.scores(d[:1])
    bad = d.copy()
    bad[3, 1] = np.inf
    with pytest.raises(ValueError, match="finite"):
        model.recognize(bad)
    with pytest.raises(ValueError, match="prefix: a 2-D array"):
        model.continue_prefix([0.0, 0.0])
    with pytest.raises(ValueError, match="the sequence"):
        model.continue_prefix(d[:1])
    with pytest.raises(ValueError, match="initial: a 1-D array"):
        model.reproduce("up", d)


def test_fits_in_threads_match_the_serial_fit(cfg, taught, tmp_path):
    fit = lambda: cosco_hsom.GestureModel.fit(cfg, taught)  # noqa: E731
    assert_threaded_fits_match_serial(fit, tmp_path, threads=3)
