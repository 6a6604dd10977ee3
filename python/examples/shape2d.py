"""Learn a 2-D shape (a figure eight drawn with a pen) from a few demonstrations, reproduce it
from the first demonstration's starting point, compare with the GMM/GMR baseline, and plot
both when matplotlib is installed.

    python python/examples/shape2d.py --out shape2d.png

Needs only numpy and cosco_hsom (`pip install ./python`); matplotlib is optional.
"""

import argparse
import pathlib
import time

import numpy as np

import cosco_hsom

HERE = pathlib.Path(__file__).resolve().parent


def figure_eight(rng, samples=100):
    """One demonstration: a figure eight with a person's variability (size, offset, a
    non-uniform pace and a little tremor), samples x 2 (x, y)."""
    u = np.linspace(0.0, 1.0, samples)
    warp = rng.uniform(-0.08, 0.08)
    s = 2 * np.pi * (u + warp * np.sin(np.pi * u))  # speeds up or slows down mid-stroke
    scale = rng.uniform(0.9, 1.1)
    x = scale * np.sin(s) + rng.normal(0, 0.03)
    y = scale * 0.6 * np.sin(2 * s) + rng.normal(0, 0.03)
    xy = np.column_stack([x, y]) + rng.normal(0, 0.005, (samples, 2))
    return xy


def demonstrations(count=7, samples=100, seed=3):
    rng = np.random.default_rng(seed)
    return [figure_eight(rng, samples) for _ in range(count)]


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", type=pathlib.Path, help="write the figure here (PNG)")
    ap.add_argument("--config", type=pathlib.Path, default=HERE / "shape2d.xml")
    args = ap.parse_args()

    demos = demonstrations()
    config = cosco_hsom.Config.from_xml(args.config)

    t0 = time.perf_counter()
    model = cosco_hsom.Hsom.fit(config, demos, columns=["x", "y"])
    path = model.reproduce(demos[0][0])
    seconds = time.perf_counter() - t0

    baseline = cosco_hsom.gmr.fit(demos, columns=["x", "y"])
    gmr_path = baseline.reproduce()

    def score(p):
        return np.mean([cosco_hsom.dtw(p, d, per_step=True) for d in demos])

    print(f"CoSCo-HSOM: fit + reproduce {seconds * 1000:.1f} ms, {len(path)} postures, "
          f"DTW to the demonstrations {score(path):.4f} per step")
    print(f"GMM/GMR:    {baseline.n_components} components, {len(gmr_path)} postures, "
          f"DTW to the demonstrations {score(gmr_path):.4f} per step")

    if args.out is None:
        return
    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("matplotlib is not installed: no figure (pip install matplotlib)")
        return
    fig, ax = plt.subplots(figsize=(7, 5))
    for i, d in enumerate(demos):
        ax.plot(d[:, 0], d[:, 1], color="0.7", lw=1, label="demonstrations" if i == 0 else None)
    ax.plot(gmr_path[:, 0], gmr_path[:, 1], color="tab:blue", lw=1.5, ls="--", label="GMM/GMR")
    ax.plot(path[:, 0], path[:, 1], color="black", lw=2, label="CoSCo-HSOM reproduction")
    ax.plot(*demos[0][0], "o", color="tab:red", label="initial posture")
    ax.set_aspect("equal")
    ax.set_xlabel("x")
    ax.set_ylabel("y")
    ax.set_title("A figure eight learned from 7 demonstrations")
    ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.13), ncol=4, fontsize=8, frameon=False)
    fig.tight_layout()
    fig.savefig(args.out, dpi=110)
    print(f"figure: {args.out}")


if __name__ == "__main__":
    main()
