"""Shared data and paths of the Python tests."""

import os
import pathlib
import shutil
import sys

import numpy as np
import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "python" / "examples"
SHAPE_XML = EXAMPLES / "shape2d.xml"
GESTURES_XML = EXAMPLES / "gestures2d.xml"
sys.path.insert(0, str(EXAMPLES))
from shape2d import figure_eight  # noqa: E402  (the example's data: one generator)


@pytest.fixture
def demos():
    rng = np.random.default_rng(7)
    return [figure_eight(rng) for _ in range(7)]


def write_csv(path, columns, rows):
    """A demonstration file as `cosco` reads it; repr() round-trips every float exactly."""
    with open(path, "w") as f:
        f.write(",".join(columns) + "\n")
        for r in rows:
            f.write(",".join(repr(float(v)) for v in r) + "\n")


def assert_threaded_fits_match_serial(fit, tmp_path, threads=4):
    """Training releases the GIL: `fit()` run in threads at once must still be the seeded,
    deterministic fit (the same saved bytes as a serial one)."""
    import threading

    fit().save(tmp_path / "serial.bin")
    models = [None] * threads

    def work(i):
        models[i] = fit()

    running = [threading.Thread(target=work, args=(i,)) for i in range(threads)]
    for t in running:
        t.start()
    for t in running:
        t.join()
    for i, m in enumerate(models):
        m.save(tmp_path / f"t{i}.bin")
        assert (tmp_path / f"t{i}.bin").read_bytes() == (tmp_path / "serial.bin").read_bytes()


@pytest.fixture(scope="session")
def cosco_bin():
    """The `cosco` binary (COSCO_BIN, set by `make test-python`, or on PATH)."""
    b = os.environ.get("COSCO_BIN") or shutil.which("cosco")
    if not b or not os.path.exists(b):
        pytest.skip("no `cosco` binary: set COSCO_BIN (make test-python does)")
    return b
