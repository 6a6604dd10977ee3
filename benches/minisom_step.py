"""MiniSom's training step (winner + update) on the map and inputs benches/som_kernel.rs wrote.

usage: minisom_step.py DIR STEPS_PER_BATCH   (DIR holds weights.csv and inputs.csv)
Prints `step_us <median microseconds per step>` and writes DIR/after200.csv: the weights
after 200 steps from the same initial map (for the bench's cross-check).
"""
import sys
import time

import numpy as np
from minisom import MiniSom

d, per_batch = sys.argv[1], int(sys.argv[2])
w0 = np.loadtxt(f"{d}/weights.csv", delimiter=",").reshape(16, 16, 12)
xs = np.loadtxt(f"{d}/inputs.csv", delimiter=",")


def fresh():
    som = MiniSom(16, 16, 12, sigma=2.0, learning_rate=0.1,
                  neighborhood_function="gaussian", topology="rectangular", random_seed=1)
    som._weights = w0.copy()
    return som


def step(som, x):
    # t = 0: sigma 2 and learning rate 0.1, as in the Rust step
    som.update(x, som.winner(x), 0, 1000)


som = fresh()
for i in range(200):
    step(som, xs[i % len(xs)])
np.savetxt(f"{d}/after200.csv", som._weights.reshape(-1, 12), delimiter=",", fmt="%.17g")

som = fresh()
times = []
for b in range(15):
    t = time.perf_counter()
    for i in range(per_batch):
        step(som, xs[i % len(xs)])
    times.append((time.perf_counter() - t) / per_batch)
times.sort()
print(f"step_us {times[len(times) // 2] * 1e6:.3f}")
