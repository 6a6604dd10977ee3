"""Time fitting and reproducing 7 demonstrations of 100 2-D samples from Python (the figure
in docs/BENCHMARKS.md):

    python python/examples/timing.py
"""

import time

import numpy as np

import cosco_hsom
from shape2d import HERE, demonstrations

demos = demonstrations(count=7, samples=100)
config = cosco_hsom.Config.from_xml(HERE / "shape2d.xml")
times = []
for _ in range(20):
    t0 = time.perf_counter()
    model = cosco_hsom.Hsom.fit(config, demos, columns=["x", "y"])
    path = model.reproduce(demos[0][0])
    times.append(time.perf_counter() - t0)
ms = np.array(times) * 1000
print(f"fit + reproduce, 7 x 100 2-D samples: median {np.median(ms):.1f} ms "
      f"(min {ms.min():.1f}, max {ms.max():.1f}) over {len(ms)} runs; {len(path)} postures")
