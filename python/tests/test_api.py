"""The Python API on its own: fitting and reproducing a 2-D shape, the summary, save/load,
GMM/GMR and DTW."""

import numpy as np
import pytest

import cosco_hsom
from conftest import SHAPE_XML, assert_threaded_fits_match_serial


def mean_dtw(path, demos):
    return np.mean([cosco_hsom.dtw(path, d, per_step=True) for d in demos])


def test_reproduction_follows_the_demonstrations(demos):
    cfg = cosco_hsom.Config.from_xml(SHAPE_XML)
    model = cosco_hsom.Hsom.fit(cfg, demos, columns=["x", "y"])
    path = model.reproduce(demos[0][0])
    assert isinstance(path, np.ndarray) and path.dtype == np.float64
    assert path.ndim == 2 and path.shape[1] == 2 and len(path) > 20
    np.testing.assert_allclose(path[0], demos[0][0], rtol=0, atol=1e-12)
    # Negative control: the same shape traversed backwards has the same points but not the
    # gesture; a faithful reproduction is much closer to the demonstrations than it is.
    backwards = demos[0][::-1]
    assert mean_dtw(path, demos) < 0.5 * mean_dtw(backwards, demos[1:])


def test_follow_nearest_retraces_the_demonstration_that_starts_nearest(demos):
    cfg = cosco_hsom.Config.from_xml(SHAPE_XML)
    model = cosco_hsom.Hsom.fit(cfg, demos)
    path = model.follow_nearest(demos, demos[1][0])
    assert isinstance(path, np.ndarray) and path.ndim == 2 and path.shape[1] == 2
    np.testing.assert_allclose(path[0], demos[1][0], rtol=0, atol=1e-12)
    # the baseline follows a demonstration of the shape: as close to them as the
    # reproduction is, and much closer than the shape traversed backwards
    assert mean_dtw(path, demos) < 0.5 * mean_dtw(demos[0][::-1], demos[1:])
    with pytest.raises(ValueError, match="initial posture"):
        model.follow_nearest(demos, [0.0])
    with pytest.raises(ValueError, match="demos"):
        model.follow_nearest(demos[0], demos[0][0])


def test_continuing_a_prefix_both_ways(demos):
    cfg = cosco_hsom.Config.from_xml(SHAPE_XML)
    model = cosco_hsom.Hsom.fit(cfg, demos[1:])
    held = demos[0]
    prefix = held[: len(held) // 2]
    for rest in (model.continue_events(prefix), model.follow_nearest_from(demos[1:], prefix)):
        assert rest.ndim == 2 and rest.shape[1] == 2
        np.testing.assert_allclose(rest[0], prefix[-1], rtol=0, atol=1e-12)
        whole = np.vstack([prefix, rest[1:]])
        # the prefix continued is closer to the held-out demonstration than the prefix held
        # still at its last posture for as long (the control)
        still = np.vstack([prefix, np.repeat(prefix[-1:], len(rest) - 1, axis=0)])
        assert mean_dtw(whole, [held]) < mean_dtw(still, [held])
    with pytest.raises(ValueError, match="prefix"):
        model.continue_events(prefix[:1])


def test_resuming_its_own_reproduction(demos):
    cfg = cosco_hsom.Config.from_xml(SHAPE_XML)
    model = cosco_hsom.Hsom.fit(cfg, demos[1:])
    initial = demos[0][0]
    whole = model.reproduce(initial)
    reading = whole[: len(whole) // 2]
    rest = model.resume(initial, reading)
    np.testing.assert_allclose(rest[0], reading[-1], rtol=0, atol=1e-12)
    again = np.vstack([reading, rest[1:]])
    # read back, the plan goes on as it was; held still for 20 samples, it goes on after
    assert abs(len(again) - len(whole)) <= 1
    assert mean_dtw(again, [whole]) < 0.01 * mean_dtw(whole[::-1], [whole]) + 1e-9
    held = np.vstack([reading, np.repeat(reading[-1:], 20, axis=0)])
    after = np.vstack([held, model.resume(initial, held)[1:]])
    assert abs(len(after) - len(whole) - 20) <= 10
    with pytest.raises(ValueError, match="reading"):
        model.resume(initial, reading[:1])
    with pytest.raises(ValueError, match="initial posture"):
        model.resume([0.0], reading)


def test_same_seed_same_model_other_seed_other_model(demos, tmp_path):
    cfg = cosco_hsom.Config.from_xml(SHAPE_XML)
    a = cosco_hsom.Hsom.fit(cfg, demos)
    b = cosco_hsom.Hsom.fit(cfg, demos)
    c = cosco_hsom.Hsom.fit(cfg.replace(seed=cfg.seed + 1), demos)
    for m, name in [(a, "a"), (b, "b"), (c, "c")]:
        m.save(tmp_path / f"{name}.bin")
    assert (tmp_path / "a.bin").read_bytes() == (tmp_path / "b.bin").read_bytes()
    assert (tmp_path / "a.bin").read_bytes() != (tmp_path / "c.bin").read_bytes()
    assert a.columns == ["x0", "x1"]


@pytest.mark.parametrize("ext", ["bin", "txt"])
def test_save_load_round_trip(demos, tmp_path, ext):
    model = cosco_hsom.Hsom.fit(cosco_hsom.Config.from_xml(SHAPE_XML), demos, columns=["x", "y"])
    p = tmp_path / f"m.{ext}"
    model.save(p)
    back = cosco_hsom.Hsom.load(str(p))
    assert back.columns == ["x", "y"]
    np.testing.assert_array_equal(back.reproduce(demos[2][0]), model.reproduce(demos[2][0]))
    back.save(tmp_path / f"again.{ext}")
    assert (tmp_path / f"again.{ext}").read_bytes() == p.read_bytes()


def test_summary(demos):
    cfg = cosco_hsom.Config.from_xml(SHAPE_XML)
    s = cosco_hsom.Hsom.fit(cfg, demos).summary()
    assert s["state_length"] == 2
    assert [l["level"] for l in s["levels"]] == list(range(cfg.height))
    assert s["demo_lengths"] == [100.0, 100.0, 100.0]
    assert s["levels"][0]["rows"] == 16 and s["levels"][0]["nodes_used"] > 0


def test_config_table1_and_replace():
    t = cosco_hsom.Config.table1()
    assert (t.height, t.state_length, t.training_steps, t.seed) == (6, 6, 5000, 1)
    r = t.replace(state_length=2, training_steps=300)
    assert (r.state_length, r.training_steps) == (2, 300)
    back = cosco_hsom.Config.from_xml_string(r.to_xml())
    assert back.to_xml() == r.to_xml()
    with pytest.raises(ValueError, match="trainingSteps"):
        t.replace(training_steps=0)


def test_gmr_baseline(demos, tmp_path):
    g = cosco_hsom.gmr.fit(demos, columns=["x", "y"], components=6, seed=1)
    assert g.n_components == 6 and g.columns == ["x", "y"]
    path = g.reproduce()
    assert path.shape[1] == 2 and len(path) > 20
    assert mean_dtw(path, demos) < 0.5 * mean_dtw(demos[0][::-1], demos[1:])
    g.save(tmp_path / "g.json")
    np.testing.assert_allclose(cosco_hsom.gmr.load(tmp_path / "g.json").reproduce(), path)
    with pytest.raises(ValueError, match="demonstrations"):
        cosco_hsom.gmr.fit(demos[:1])


def test_dtw_identities(demos):
    a, b = demos[0], demos[1]
    assert cosco_hsom.dtw(a, a) == 0.0
    assert cosco_hsom.dtw(a, b) == cosco_hsom.dtw(b, a) > 0.0
    assert cosco_hsom.dtw(a.tolist(), b) == cosco_hsom.dtw(a, b)
    assert cosco_hsom.dtw(a, b, per_step=True) < cosco_hsom.dtw(a, b)


def test_fits_in_threads_match_the_serial_fit(demos, tmp_path):
    cfg = cosco_hsom.Config.from_xml(SHAPE_XML)
    assert_threaded_fits_match_serial(lambda: cosco_hsom.Hsom.fit(cfg, demos), tmp_path)


def test_native_module_links_no_simulator():
    import shutil
    import subprocess
    import sys

    ldd = shutil.which("ldd")
    if not sys.platform.startswith("linux") or ldd is None:
        pytest.skip("ldd (Linux) is needed to list the linked libraries")
    out = subprocess.run([ldd, cosco_hsom._native.__file__], capture_output=True, text=True).stdout
    assert "libc" in out  # the listing worked
    assert "mujoco" not in out.lower() and "osmesa" not in out.lower(), out


def test_heldout_scores_every_method_on_the_same_folds(demos):
    cfg = cosco_hsom.Config.from_xml(SHAPE_XML)
    doc = cosco_hsom.heldout(cfg, demos[:4], columns=["x", "y"], threads=2)
    (g,) = doc["gestures"]
    assert g["gesture"] == "gesture"
    assert len(g["held_out"]) == 4 and len(g["in_sample"]) == 4
    methods = [r["method"] for r in g["held_out"][0]["runs"]]
    assert methods == ["hierarchy", "nearest_sequence", "height1", "gmm_gmr", "promp", "dmp", "dba", "replay"]
    for fold in g["held_out"]:
        for run in fold["runs"]:
            assert run["error"] is None, run
            assert 0 < run["score"]["relative_dtw"] < 0.5
    summary = {s["method"]: s for s in doc["summary"]}
    assert summary["hierarchy"]["folds"] == 4
    # where each reproduction starts and ends against the fold's training demonstrations
    score = g["held_out"][0]["runs"][0]["score"]
    assert score["start_speed"] > 0 and score["demo_start_speed_max"] > 0
    assert isinstance(score["start_in_range"], bool) and isinstance(score["end_within_spread"], bool)
    assert summary["replay"]["start_in_range"] == 1.0
    assert 0.0 <= summary["hierarchy"]["end_within_spread"] <= 1.0
    # several gestures, by label; a retired setting is no keyword of replace
    two = cosco_hsom.heldout(
        cfg,
        {"a": demos[:3], "b": demos[3:6]},
        height_1=False,
        gmr=False,
        promp=False,
        dmp=False,
        dba=False,
        in_sample=False,
    )
    assert [g["gesture"] for g in two["gestures"]] == ["a", "b"]
    assert all(len(g["in_sample"]) == 0 for g in two["gestures"])
    assert [r["method"] for r in two["gestures"][0]["held_out"][0]["runs"]] == [
        "hierarchy",
        "nearest_sequence",
        "replay",
    ]
    for retired in ("consensus", "plan", "alignment", "knots"):
        with pytest.raises(TypeError):
            cfg.replace(**{retired: "all"})
    with pytest.raises(ValueError, match="at least 3 demonstrations"):
        cosco_hsom.heldout(cfg, demos[:2])
    with pytest.raises(ValueError, match="stateLength is 6"):
        cosco_hsom.heldout(cosco_hsom.Config.nao_gestures(), demos[:3])
    with pytest.raises(ValueError, match="sample_period"):
        cosco_hsom.heldout(cfg, demos[:3], sample_period=0.0)
