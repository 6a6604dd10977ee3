"""Bad input raises a Python exception that names the problem; the interpreter survives."""

import math

import numpy as np
import pytest

import cosco_hsom
from conftest import SHAPE_XML


@pytest.fixture
def cfg():
    return cosco_hsom.Config.from_xml(SHAPE_XML)


def test_ragged_rows(cfg, demos):
    ragged = demos[0].tolist()
    ragged[5] = ragged[5][:1]
    with pytest.raises(ValueError, match=r"demos\[1\]: sample 5 has 1 values but there are 2 columns"):
        cosco_hsom.Hsom.fit(cfg, [demos[1], ragged])


def test_ragged_list_of_demonstrations_of_other_widths(cfg, demos):
    with pytest.raises(ValueError, match=r"demos\[1\]"):
        cosco_hsom.Hsom.fit(cfg, [demos[0], np.hstack([demos[1], demos[1]])])


def test_nan(cfg, demos):
    bad = demos[3].copy()
    bad[10, 1] = np.nan
    with pytest.raises(ValueError, match=r"demos\[1\]: sample 10, column `y`: value `NaN` is not finite"):
        cosco_hsom.Hsom.fit(cfg, [demos[0], bad], columns=["x", "y"])
    with pytest.raises(ValueError, match="finite"):
        cosco_hsom.Hsom.fit(cfg, demos).reproduce([0.0, math.inf])


def test_one_dimensional_arrays(cfg, demos):
    with pytest.raises(ValueError, match=r"demos\[0\]: a 2-D array .* got a 1-D array"):
        cosco_hsom.Hsom.fit(cfg, [demos[0][:, 0]])
    with pytest.raises(ValueError, match=r"demos\[0\]: .*1-D sequence of 100 numbers"):
        cosco_hsom.Hsom.fit(cfg, [list(demos[0][:, 0])])
    with pytest.raises(ValueError, match="wrap it in a list"):
        cosco_hsom.Hsom.fit(cfg, demos[0])
    with pytest.raises(ValueError, match="initial: a 1-D array"):
        cosco_hsom.Hsom.fit(cfg, demos).reproduce(demos[0])


def test_wrong_widths(cfg, demos):
    three = [np.hstack([d, d[:, :1]]) for d in demos]
    with pytest.raises(ValueError, match=r"demos\[0\]: 3 state columns but the configured state length is 2"):
        cosco_hsom.Hsom.fit(cfg, three)
    with pytest.raises(ValueError, match=r"columns: 3 names \(a, b, c\) for demonstrations of 2"):
        cosco_hsom.Hsom.fit(cfg, demos, columns=["a", "b", "c"])
    with pytest.raises(ValueError, match="the initial posture has 3 values; the model in memory learned 2 variables"):
        cosco_hsom.Hsom.fit(cfg, demos).reproduce([0.0, 0.0, 0.0])


def test_no_demonstrations_and_non_numbers(cfg, demos):
    with pytest.raises(ValueError, match="no demonstrations"):
        cosco_hsom.Hsom.fit(cfg, [])
    with pytest.raises(ValueError, match=r"demos\[0\]"):
        cosco_hsom.Hsom.fit(cfg, [[["a", "b"], ["c", "d"]]])
    with pytest.raises(ValueError, match=r"demos\[0\]: the values must be numbers"):
        cosco_hsom.Hsom.fit(cfg, [np.array([["a", "b"], ["c", "d"]])])


def test_files(tmp_path, cfg, demos):
    with pytest.raises(FileNotFoundError, match="cannot read configuration .*nope.xml"):
        cosco_hsom.Config.from_xml(tmp_path / "nope.xml")
    # A missing file is bad input too: the same exception is a ValueError.
    with pytest.raises(ValueError, match="nope.xml") as e:
        cosco_hsom.Config.from_xml(tmp_path / "nope.xml")
    assert isinstance(e.value, cosco_hsom.MissingFileError)
    with pytest.raises(ValueError, match="nope.bin"):
        cosco_hsom.Hsom.load(tmp_path / "nope.bin")
    with pytest.raises(OSError, match="no-such-dir"):
        cosco_hsom.Hsom.fit(cfg, demos).save(tmp_path / "no-such-dir" / "m.bin")
    (tmp_path / "bad.xml").write_text("<hsom version='1'><seed>x</seed></hsom>")
    with pytest.raises(ValueError, match="bad.xml"):
        cosco_hsom.Config.from_xml(tmp_path / "bad.xml")
    with pytest.raises(FileNotFoundError, match="nope.bin"):
        cosco_hsom.Hsom.load(tmp_path / "nope.bin")
    (tmp_path / "junk.bin").write_bytes(b"not a model")
    with pytest.raises(ValueError, match="junk.bin"):
        cosco_hsom.Hsom.load(tmp_path / "junk.bin")
    with pytest.raises(ValueError, match="must end in .bin"):
        cosco_hsom.Hsom.fit(cfg, demos).save(tmp_path / "m.pickle")


def test_dtw_bad_input(demos):
    with pytest.raises(ValueError):
        cosco_hsom.dtw(demos[0], np.hstack([demos[1], demos[1]]))
    with pytest.raises(ValueError, match="a: a 2-D array"):
        cosco_hsom.dtw(demos[0][:, 0], demos[1])
