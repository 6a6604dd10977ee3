"""CoSCo-HSOM: learn a gesture from raw demonstrations and reproduce it from the initial
posture, with hierarchical self-organizing maps (Pierris & Dahl).

The algorithm of the Rust crate ``cosco-hsom``, built without its simulator:

- :class:`Config`: a validated configuration (``Config.from_xml(path)``, ``Config.table1()``).
- :class:`Hsom`: ``Hsom.fit(config, demos, columns=None)``, ``.reproduce(initial)``,
  ``.save(path)`` / ``Hsom.load(path)`` (the files of ``cosco train``), ``.summary()``.
- :class:`GestureModel`: several gestures in one hierarchy,
  ``GestureModel.fit(config, {"wave": [...], "salute": [...]})``, ``.reproduce(label, initial)``,
  ``.recognize(sequence)`` (a :class:`Recognition`: the label or None for unknown, per-label
  scores, the sample the decision held from), ``.scores(sequence)``,
  ``.continue_prefix(prefix)``, ``.recognizer()`` (a :class:`Recognizer`, recognition in the
  loop: ``r.push(sample)`` returns the label committed to or None, ``r.decided`` True from the
  sample it committed on, ``r.finish()`` the :class:`Recognition` of every sample pushed),
  ``.save(path)`` / ``GestureModel.load(path)`` (the
  files of ``cosco train`` on labelled directories).
- :class:`Stepper`: a reproduction in the loop, ``model.stepper(initial, goal=None, via=None)``
  (``GestureModel.stepper(label, initial, ...)``): ``s.step(observed)`` is the next posture
  to command, ``s.done`` True once the reproduction has ended, ``s.goal = posture`` moves the
  goal from this tick on.
- :mod:`cosco_hsom.gmr`: the paper's GMM/GMR baseline.
- :func:`heldout`: leave-one-out on demonstrations (``cosco heldout``): the hierarchy beside
  its nearest-sequence baseline, height 1, GMM/GMR, ProMP and a replay, on the same folds.
- :func:`dtw`: dynamic time warping.
- :func:`read_demos`: demonstration CSV files as arrays, ``resample=HZ`` bringing files
  sampled at different rates (their ``time`` columns) to one.

Demonstrations are 2-D numpy arrays (samples x variables). Bad input raises ``ValueError``
with the message the ``cosco`` CLI prints; for files that cannot be read or written it is
also a ``FileNotFoundError`` / ``PermissionError`` / ``OSError`` (:class:`MissingFileError`,
:class:`FileAccessError`, :class:`FileError`).
"""

from ._errors import FileAccessError, FileError, MissingFileError
from ._native import (
    Config,
    Dmp,
    GestureModel,
    Hsom,
    Recognition,
    Recognizer,
    Stepper,
    dtw,
    heldout,
    read_demos,
)
from . import gmr

__all__ = [
    "Config",
    "Hsom",
    "Dmp",
    "GestureModel",
    "Recognition",
    "Recognizer",
    "Stepper",
    "dtw",
    "heldout",
    "read_demos",
    "gmr",
    "MissingFileError",
    "FileAccessError",
    "FileError",
]
