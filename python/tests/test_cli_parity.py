"""Python and `cosco` are the same program: the same inputs give byte-identical model files
and the same reproduction, and a model saved by one loads in the other."""

import csv
import json
import subprocess

import numpy as np
import pytest

import cosco_hsom
from conftest import GESTURES_XML, SHAPE_XML, write_csv
from gestures2d import gestures


def run(*args):
    return subprocess.run([str(a) for a in args], capture_output=True, text=True)


@pytest.fixture
def demo_dir(demos, tmp_path):
    d = tmp_path / "demos"
    d.mkdir()
    for i, rows in enumerate(demos):
        write_csv(d / f"demo_{i + 1:02}.csv", ["x", "y"], rows)
    return d


def read_reproduction(path):
    with open(path) as f:
        rows = list(csv.reader(f))
    assert rows[0] == ["step", "x", "y"]
    return np.array([[float(v) for v in r[1:]] for r in rows[1:]])


@pytest.mark.parametrize("ext", ["bin", "txt"])
def test_same_model_file_and_reproduction(cosco_bin, demos, demo_dir, tmp_path, ext):
    cli_model = tmp_path / f"cli.{ext}"
    r = run(cosco_bin, "train", "--config", SHAPE_XML, "--demos", demo_dir, "--out", cli_model)
    assert r.returncode == 0, r.stderr

    py = cosco_hsom.Hsom.fit(cosco_hsom.Config.from_xml(str(SHAPE_XML)), demos, columns=["x", "y"])
    py_model = tmp_path / f"py.{ext}"
    py.save(py_model)
    assert py_model.read_bytes() == cli_model.read_bytes()

    rep = tmp_path / "rep.csv"
    r = run(cosco_bin, "reproduce", "--model", py_model,
            "--initial-from", demo_dir / "demo_01.csv", "--out", rep)
    assert r.returncode == 0, r.stderr
    cli_path = read_reproduction(rep)
    np.testing.assert_array_equal(py.reproduce(demos[0][0]), cli_path)
    np.testing.assert_array_equal(cosco_hsom.Hsom.load(cli_model).reproduce(demos[0][0]), cli_path)
    # A negative control: another seed is another model, and the comparison notices.
    other = cosco_hsom.Hsom.fit(cosco_hsom.Config.from_xml(SHAPE_XML).replace(seed=2), demos,
                                columns=["x", "y"])
    other.save(tmp_path / f"other.{ext}")
    assert (tmp_path / f"other.{ext}").read_bytes() != cli_model.read_bytes()


def test_cli_inspects_a_python_model(cosco_bin, demos, tmp_path):
    m = cosco_hsom.Hsom.fit(cosco_hsom.Config.from_xml(SHAPE_XML), demos, columns=["x", "y"])
    m.save(tmp_path / "m.bin")
    r = run(cosco_bin, "inspect", tmp_path / "m.bin")
    assert r.returncode == 0, r.stderr
    assert str(m) in r.stdout


def cli_error(result):
    assert result.returncode != 0
    line = result.stderr.strip().splitlines()[-1]
    assert line.startswith("Error: ")
    return line[len("Error: "):]


def test_same_messages_as_the_cli(cosco_bin, demos, demo_dir, tmp_path):
    missing = tmp_path / "missing.xml"
    cli = cli_error(run(cosco_bin, "train", "--config", missing, "--demos", demo_dir,
                        "--out", tmp_path / "m.bin"))
    with pytest.raises(FileNotFoundError) as e:
        cosco_hsom.Config.from_xml(missing)
    assert str(e.value) == cli

    cli = cli_error(run(cosco_bin, "train", "--config", SHAPE_XML, "--demos", demo_dir,
                        "--out", tmp_path / "m.json"))
    m = cosco_hsom.Hsom.fit(cosco_hsom.Config.from_xml(SHAPE_XML), demos)
    with pytest.raises(ValueError) as e:
        m.save(tmp_path / "m.json")
    assert str(e.value) == cli

    m.save(tmp_path / "m.bin")
    cli = cli_error(run(cosco_bin, "reproduce", "--model", tmp_path / "m.bin",
                        "--initial", "1,2,3", "--out", tmp_path / "r.csv"))
    with pytest.raises(ValueError) as e:
        cosco_hsom.Hsom.load(tmp_path / "m.bin").reproduce([1.0, 2.0, 3.0])
    assert str(e.value) == cli


# ---- several gestures: `cosco train` on labelled directories and GestureModel ----


@pytest.fixture
def labelled():
    return gestures(count=3, seed=0)


def write_labelled(root, sets):
    """demos/<label>/demo_XX.csv, as `cosco demos --gesture all` records them."""
    for label, demos in sets.items():
        (root / label).mkdir(parents=True)
        for i, rows in enumerate(demos):
            write_csv(root / label / f"demo_{i + 1:02}.csv", ["x", "y"], rows)
    return root


@pytest.mark.parametrize("ext", ["bin", "txt"])
def test_same_gesture_model_file_reproduction_and_recognition(cosco_bin, labelled, tmp_path, ext):
    demo_dir = write_labelled(tmp_path / "demos", labelled)
    cli_model = tmp_path / f"cli.{ext}"
    r = run(cosco_bin, "train", "--config", GESTURES_XML, "--demos", demo_dir, "--out", cli_model)
    assert r.returncode == 0, r.stderr

    cfg = cosco_hsom.Config.from_xml(GESTURES_XML)
    # `cosco train` takes the label directories in sorted order
    ordered = {label: labelled[label] for label in sorted(labelled)}
    py = cosco_hsom.GestureModel.fit(cfg, ordered, columns=["x", "y"])
    py_model = tmp_path / f"py.{ext}"
    py.save(py_model)
    assert py_model.read_bytes() == cli_model.read_bytes()
    assert cosco_hsom.GestureModel.load(cli_model).labels == sorted(labelled)
    # Negative controls: the labels in another order, or another seed, is another model.
    for other, name in [
        (cosco_hsom.GestureModel.fit(cfg, labelled, columns=["x", "y"]), "order"),
        (cosco_hsom.GestureModel.fit(cfg.replace(seed=2), ordered, columns=["x", "y"]), "seed"),
    ]:
        other.save(tmp_path / f"{name}.{ext}")
        assert (tmp_path / f"{name}.{ext}").read_bytes() != cli_model.read_bytes(), name

    # reproduction on cue: `cosco reproduce --gesture` on the Python model
    rep = tmp_path / "rep.csv"
    r = run(cosco_bin, "reproduce", "--model", py_model, "--gesture", "diag",
            "--initial-from", demo_dir / "diag" / "demo_01.csv", "--out", rep)
    assert r.returncode == 0, r.stderr
    np.testing.assert_array_equal(py.reproduce("diag", labelled["diag"][0][0]),
                                  read_reproduction(rep))

    # recognition: `cosco recognize --json` on held-out files, answer for answer
    held_dir = write_labelled(tmp_path / "held", gestures(count=2, seed=100))
    out = tmp_path / "answers.json"
    r = run(cosco_bin, "recognize", "--model", cli_model, "--demos", held_dir, "--json", out)
    assert r.returncode == 0, r.stderr
    answers = json.loads(out.read_text())
    assert len(answers) == 6
    for a in answers:
        rows = np.loadtxt(a["file"], delimiter=",", skiprows=1)
        got = py.recognize(rows).to_dict()
        assert got == a["recognition"]
        assert got["label"] == a["expected"]


def test_same_gesture_messages_as_the_cli(cosco_bin, labelled, tmp_path):
    cfg = cosco_hsom.Config.from_xml(GESTURES_XML)
    py = cosco_hsom.GestureModel.fit(cfg, {l: labelled[l] for l in sorted(labelled)})
    py.save(tmp_path / "m.bin")
    m = cosco_hsom.GestureModel.load(tmp_path / "m.bin")
    for extra, label in [(["--gesture", "wave"], "wave"), ([], None)]:
        cli = cli_error(run(cosco_bin, "reproduce", "--model", tmp_path / "m.bin", *extra,
                            "--initial", "0,0", "--out", tmp_path / "r.csv"))
        with pytest.raises(ValueError) as e:
            m.reproduce(label, [0.0, 0.0])
        assert str(e.value) == cli
        assert "diag, right, up" in cli
    cli = cli_error(run(cosco_bin, "reproduce", "--model", tmp_path / "m.bin", "--gesture", "up",
                        "--initial", "1,2,3", "--out", tmp_path / "r.csv"))
    with pytest.raises(ValueError) as e:
        m.reproduce("up", [1.0, 2.0, 3.0])
    assert str(e.value) == cli
