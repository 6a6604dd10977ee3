"""The paper's baseline, GMM/GMR: a Gaussian mixture over (time, variables), fitted to
idle-trimmed, DTW-aligned, resampled demonstrations, regressed on time to reproduce.

>>> model = cosco_hsom.gmr.fit(demos)          # doctest: +SKIP
>>> path = model.reproduce()                   # doctest: +SKIP
"""

from typing import Optional, Sequence

from ._native import GmrModel

__all__ = ["GmrModel", "fit", "load"]


def fit(
    demos,
    columns: Optional[Sequence[str]] = None,
    components: Optional[int] = None,
    seed: int = 0,
    sample_period: float = 0.025,
) -> GmrModel:
    """Fit the baseline to demonstrations (a list of 2-D arrays, samples x variables).

    ``components``: the number of Gaussians, or None to choose it by BIC over 1..=8.
    ``sample_period``: seconds between samples (the step of :meth:`GmrModel.reproduce`).
    """
    return GmrModel.fit(
        demos,
        columns=None if columns is None else list(columns),
        components=components,
        seed=seed,
        sample_period=sample_period,
    )


def load(path, sample_period: float = 0.025) -> GmrModel:
    """Load a model saved by :meth:`GmrModel.save`."""
    return GmrModel.load(path, sample_period=sample_period)
