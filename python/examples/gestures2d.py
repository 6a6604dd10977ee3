"""Several 2-D gestures in one hierarchy: teach three out-and-back strokes that all start at
the same point, reproduce each on cue, recognise new demonstrations, and answer "unknown"
for a stroke never taught.

    python python/examples/gestures2d.py

Needs only numpy and cosco_hsom (`pip install ./python`).
"""

import argparse
import pathlib
import time

import numpy as np

import cosco_hsom

HERE = pathlib.Path(__file__).resolve().parent

# Where each gesture goes from the origin before it comes back.
APEXES = {"up": (0.0, 1.0), "right": (1.0, 0.0), "diag": (-0.7, 0.7)}
# A stroke none of them makes (the unknown gesture).
NEVER_TAUGHT = (0.0, -1.0)


def stroke(apex, rng):
    """One demonstration: hold at the origin, go to `apex` and back, hold; the holds, the
    amplitude and a little noise vary (samples x 2)."""
    hold = int(rng.integers(20, 30))
    amp = 1.0 + rng.uniform(-0.05, 0.05)
    ramp = np.arange(40) / 40.0
    t = np.concatenate([np.zeros(hold), ramp, np.ones(hold), 1.0 - ramp, np.zeros(hold)])
    xy = amp * np.outer(t, apex)
    return xy + 0.002 * rng.random(xy.shape)


def gestures(count=3, seed=0, apexes=APEXES):
    """`count` demonstrations of each gesture: {label: [array, ...]}."""
    rng = np.random.default_rng(seed)
    return {label: [stroke(a, rng) for _ in range(count)] for label, a in apexes.items()}


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--config", type=pathlib.Path, default=HERE / "gestures2d.xml")
    args = ap.parse_args()

    config = cosco_hsom.Config.from_xml(args.config)
    t0 = time.perf_counter()
    model = cosco_hsom.GestureModel.fit(config, gestures(), columns=["x", "y"])
    print(f"trained {model.labels} in {time.perf_counter() - t0:.2f} s")

    for label, apex in APEXES.items():
        path = model.reproduce(label, [0.0, 0.0])
        far = path[np.argmax(np.hypot(path[:, 0], path[:, 1]))]
        print(f"reproduce({label!r}): {len(path)} postures, farthest at {far.round(2)} "
              f"(taught {apex})")

    held_out = gestures(count=2, seed=100)
    held_out["never-taught"] = gestures(count=2, seed=101, apexes={"x": NEVER_TAUGHT})["x"]
    for truth, demos in held_out.items():
        for d in demos:
            r = model.recognize(d)
            print(f"{truth:>12} -> {r.label or 'unknown':<8} decided at sample "
                  f"{r.decided_at} of {r.samples}; scores "
                  + ", ".join(f"{k} {v:.2f}" for k, v in r.scores.items()))


if __name__ == "__main__":
    main()
