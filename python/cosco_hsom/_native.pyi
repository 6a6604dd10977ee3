"""Type stubs of the native module (see the docstrings in cosco_hsom)."""

from os import PathLike
from typing import Any, Dict, List, Literal, Mapping, Optional, Sequence, Tuple, Union, overload

import numpy as np
import numpy.typing as npt

_Path = Union[str, PathLike]
_Array2 = Union[npt.ArrayLike, Sequence[Sequence[float]]]
_Point = Tuple[float, float, float]

class Config:
    """A validated CoSCo-HSOM configuration (the XML schema of docs/CONFIG.md)."""

    @staticmethod
    def from_xml(path: _Path) -> "Config":
        """Read and validate an XML configuration file."""
    @staticmethod
    def from_xml_string(text: str, name: str = "<string>") -> "Config":
        """Parse and validate an XML configuration given as text."""
    @staticmethod
    def table1() -> "Config":
        """The paper's Table I (height 6, memory 4, updatePeriod 2, 5000 steps, 6 variables)."""
    @staticmethod
    def nao_gestures() -> "Config":
        """The recommended configuration for the simulated Nao arm (configs/nao-gestures.xml)."""
    def replace(
        self,
        *,
        seed: Optional[int] = None,
        state_length: Optional[int] = None,
        training_steps: Optional[int] = None,
    ) -> "Config":
        """A copy with some settings changed, validated again."""
    def to_xml(self) -> str:
        """The configuration as XML (every setting its algorithm reads written out)."""
    @property
    def seed(self) -> int: ...
    @property
    def state_length(self) -> int: ...
    @property
    def training_steps(self) -> int: ...
    @property
    def height(self) -> int: ...
    @property
    def source(self) -> str: ...

class Hsom:
    """A trained CoSCo-HSOM hierarchy."""

    @staticmethod
    def fit(
        config: Config,
        demos: Sequence[_Array2],
        columns: Optional[Sequence[str]] = None,
    ) -> "Hsom":
        """Train on demonstrations (2-D arrays, samples x variables); releases the GIL."""
    @staticmethod
    def load(path: _Path) -> "Hsom":
        """Load a model saved by Hsom.save or `cosco train` (.bin or .txt); one of several
        gestures is refused (GestureModel.load)."""
    def save(self, path: _Path) -> None:
        """Save the model (.bin binary, .txt plain text; written atomically)."""
    def update(self, demos: Sequence[_Array2], label: Optional[str] = None) -> "Hsom":
        """The model taught `demos` more, from the model and them alone: a new model (this one
        is unchanged); `label` must be None."""
    @property
    def learned(self) -> Dict[str, int]:
        """`{"demonstrations": n, "kept": k, "updates": u}`: what the model learned from."""
    @overload
    def reproduce(
        self,
        initial: npt.ArrayLike,
        *,
        goal: Optional[npt.ArrayLike] = None,
        via: Optional[Sequence[Tuple[float, npt.ArrayLike]]] = None,
        band: Literal[False] = False,
        duration: Optional[float] = None,
        point_at: Optional[_Point] = None,
        look_at: Optional[_Point] = None,
    ) -> np.ndarray: ...
    @overload
    def reproduce(
        self,
        initial: npt.ArrayLike,
        *,
        goal: Optional[npt.ArrayLike] = None,
        via: Optional[Sequence[Tuple[float, npt.ArrayLike]]] = None,
        band: Literal[True],
        duration: Optional[float] = None,
        point_at: Optional[_Point] = None,
        look_at: Optional[_Point] = None,
    ) -> Tuple[np.ndarray, np.ndarray, np.ndarray]: ...
    def reproduce(self, initial: npt.ArrayLike, *, goal: Optional[npt.ArrayLike] = None, via: Optional[Sequence[Tuple[float, npt.ArrayLike]]] = None, band: bool = False, duration: Optional[float] = None, point_at: Optional[_Point] = None, look_at: Optional[_Point] = None) -> Any:  # type: ignore[misc]
        """Reproduce from an initial posture: one row per step, the first the initial posture;
        ending exactly at `goal` and passing each `(phase, posture)` of `via` when given; with
        band=True, (postures, lower, upper): the central 95 % band about them; with `duration`
        (seconds), retimed to last that long at 40 Hz, its path kept (a duration the servos
        cannot follow raises ValueError naming the shortest); `point_at` / `look_at`
        ((x, y, z) metres, torso frame): the held part points / looks there (a target out of
        reach raises ValueError naming the closest direction)."""
    def follow_nearest(self, demos: Sequence[npt.ArrayLike], initial: npt.ArrayLike) -> np.ndarray:
        """The nearest-sequence baseline: of `demos`, the one whose first posture is nearest
        `initial`, its bottom events through this model's bottom code, no level above."""
    def continue_events(self, prefix: npt.ArrayLike) -> np.ndarray:
        """Continue a gesture from its first samples: the prefix pushed up the lists, the
        levels plan the rest; the continuation's postures, from the prefix's last."""
    def resume(self, initial: npt.ArrayLike, reading: npt.ArrayLike) -> np.ndarray:
        """Resume this model's reproduction from `initial` after part of it was executed
        (`reading`: what the encoders read, possibly disturbed): aligned with the plan, its
        events executed for the durations read, re-planned where they surprise the levels;
        the continuation's postures, from the reading's last."""
    def follow_nearest_from(self, demos: Sequence[npt.ArrayLike], prefix: npt.ArrayLike) -> np.ndarray:
        """The nearest-sequence continuation: the demonstration along which the prefix runs
        closest, continued after the prefix's end; from the prefix's last posture."""
    def stepper(
        self,
        initial: npt.ArrayLike,
        goal: Optional[npt.ArrayLike] = None,
        via: Optional[Sequence[Tuple[float, npt.ArrayLike]]] = None,
        *,
        point_at: Optional[_Point] = None,
        look_at: Optional[_Point] = None,
    ) -> "Stepper":
        """The hierarchy in the loop from `initial`, through `goal`, `via`, `point_at` and
        `look_at` as `reproduce` takes them: `step(observed)` gives the next posture to command."""
    @property
    def columns(self) -> List[str]: ...
    @property
    def config(self) -> Config: ...
    def summary(self) -> Dict[str, Any]:
        """Levels, sizes and quality measures (what `cosco inspect` prints)."""

class GestureModel:
    """Several gestures in one model: a branch per label, each the gesture learned alone."""

    @staticmethod
    def fit(
        config: Config,
        gestures: Mapping[str, Sequence[_Array2]],
        columns: Optional[Sequence[str]] = None,
    ) -> "GestureModel":
        """Train on {label: [demonstration, ...]} (labels plain words, in the mapping's order;
        demonstrations 2-D, samples x variables); needs the events algorithm; releases the GIL."""
    @staticmethod
    def load(path: _Path) -> "GestureModel":
        """Load a model saved by GestureModel.save or `cosco train` (a single-gesture file loads
        as one unlabelled gesture)."""
    def save(self, path: _Path) -> None:
        """Save the model (.bin or .txt, atomically): the bytes `cosco train` writes."""
    def update(self, demos: Sequence[_Array2], label: Optional[str] = None) -> "GestureModel":
        """The model taught `demos` as gesture `label` (a new label adds the gesture), from the
        model and them alone: a new model (this one is unchanged)."""
    @property
    def learned(self) -> Dict[str, Dict[str, int]]:
        """Per label, `{"demonstrations": n, "kept": k, "updates": u}`."""
    def reproduce(self, label: Optional[str], initial: npt.ArrayLike, *, duration: Optional[float] = None, point_at: Optional[_Point] = None, look_at: Optional[_Point] = None) -> np.ndarray:
        """Reproduce gesture `label` from an initial posture: one row per step, the first the
        initial posture. None only for a single-gesture model. With `duration` (seconds),
        retimed to last that long at 40 Hz, its path kept; `point_at` / `look_at` aim the held
        part as Hsom.reproduce does."""
    def scores(self, sequence: _Array2) -> Dict[str, float]:
        """Per label, the score of a whole sequence (lower is closer; see Recognition.thresholds)."""
    def recognize(self, sequence: _Array2) -> "Recognition":
        """The label (None when unknown), every score, and the sample the decision held from."""
    def continue_prefix(self, prefix: _Array2) -> Tuple[str, np.ndarray]:
        """The gesture the hierarchy recognises in the prefix, and the prefix continued by it."""
    def recognizer(self) -> "Recognizer":
        """Recognition in the loop: push samples one at a time; it commits to a label or to
        unknown as early as its rule allows and never changes that answer."""
    def stepper(
        self,
        label: Optional[str],
        initial: npt.ArrayLike,
        goal: Optional[npt.ArrayLike] = None,
        via: Optional[Sequence[Tuple[float, npt.ArrayLike]]] = None,
        *,
        point_at: Optional[_Point] = None,
        look_at: Optional[_Point] = None,
    ) -> "Stepper":
        """Gesture `label` in the loop from `initial` (None only for a single-gesture model),
        through `goal` and `via` as `Hsom.reproduce` takes them."""
    @property
    def labels(self) -> List[str]:
        """The gesture labels, in the model's order (empty for a single-gesture model)."""
    @property
    def columns(self) -> List[str]: ...
    @property
    def config(self) -> Config:
        """As trained: with several labels, trainingSteps times the number of labels."""

class Stepper:
    """The hierarchy in the loop (Hsom.stepper, GestureModel.stepper)."""

    def step(self, observed: npt.ArrayLike) -> np.ndarray:
        """The next posture to command, given the posture the encoders read at this tick (the
        first call reads the initial posture). It follows its plan while the arm is where it
        was sent, and re-plans from what the encoders have read when it is not."""
    @property
    def done(self) -> bool:
        """True once the reproduction has ended (its last posture has been commanded)."""
    @property
    def goal(self) -> Optional[np.ndarray]:
        """The goal, or None for the reproduction's own end; setting it moves the goal from
        this tick on (reached exactly, without a jump)."""
    @goal.setter
    def goal(self, goal: npt.ArrayLike) -> None: ...
    @property
    def point_at(self) -> Optional[_Point]:
        """What the held part points at, or None; setting it moves the target from this tick
        on (a stepper made with point_at)."""
    @point_at.setter
    def point_at(self, target: Optional[_Point]) -> None: ...
    @property
    def look_at(self) -> Optional[_Point]:
        """What the top camera looks at during the held part, or None; setting it moves the
        gaze from this tick on (a stepper made with point_at or look_at)."""
    @look_at.setter
    def look_at(self, target: Optional[_Point]) -> None: ...
    @property
    def phase(self) -> float:
        """How far along the reproduction is, 0 to 1."""
    @property
    def replans(self) -> int:
        """How many times it re-planned because the arm was not where it was sent."""

class Recognizer:
    """Recognition in the loop (GestureModel.recognizer()): samples pushed one at a time."""

    def push(self, sample: npt.ArrayLike) -> Optional[str]:
        """Push the next sample (one value per variable): the label committed to, or None
        (before any commitment, and after one to unknown: see `decided`)."""
    @property
    def decided(self) -> bool:
        """True from the sample it committed on (a committed None is unknown)."""
    @property
    def committed_at(self) -> Optional[int]:
        """The samples pushed when it committed (None before)."""
    @property
    def samples(self) -> int:
        """The samples pushed so far."""
    def finish(self) -> "Recognition":
        """What GestureModel.recognize gives on every sample pushed (at least 2)."""

class Recognition:
    """What GestureModel.recognize answers for one sequence."""

    @property
    def label(self) -> Optional[str]:
        """The recognised label, or None (unknown)."""
    @property
    def unknown(self) -> bool: ...
    @property
    def best(self) -> str:
        """The label with the lowest score, below its threshold or not."""
    @property
    def scores(self) -> Dict[str, float]: ...
    @property
    def thresholds(self) -> Dict[str, float]: ...
    @property
    def weighed(self) -> Dict[str, List[Tuple[str, float]]]:
        """Per label, the variables its score weighs most (heaviest first) with their weights."""
    @property
    def decided_at(self) -> int:
        """The earliest sample from which the best label stayed the same."""
    @property
    def samples(self) -> int: ...
    @property
    def decided_fraction(self) -> float: ...
    def to_dict(self) -> Dict[str, Any]:
        """As `cosco recognize --json` writes each file's `recognition`."""

class GmrModel:
    """The GMM/GMR baseline."""

    @staticmethod
    def fit(
        demos: Sequence[_Array2],
        columns: Optional[Sequence[str]] = None,
        components: Optional[int] = None,
        seed: int = 0,
        sample_period: float = 0.025,
    ) -> "GmrModel": ...
    @staticmethod
    def load(path: _Path, sample_period: float = 0.025) -> "GmrModel": ...
    def save(self, path: _Path) -> None: ...
    def reproduce(self, period: Optional[float] = None) -> np.ndarray:
        """The conditional mean at every period over the learned duration, one row per step."""
    @property
    def duration(self) -> float: ...
    @property
    def n_components(self) -> int: ...
    @property
    def columns(self) -> List[str]: ...

def heldout(
    config: Config,
    gestures: Union[Sequence[_Array2], Mapping[str, Sequence[_Array2]]],
    *,
    columns: Optional[Sequence[str]] = None,
    sample_period: float = 0.025,
    height_1: bool = True,
    gmr: bool = True,
    promp: bool = True,
    dmp: bool = True,
    dba: bool = True,
    in_sample: bool = True,
    condition: Optional[Literal["end", "end+mid"]] = None,
    far: Sequence[float] = (),
    sittings: bool = False,
    threads: int = 1,
) -> Dict[str, Any]:
    """Leave-one-out (``cosco heldout``): the JSON document of ``--json`` as a dict."""

def read_demos(
    paths: Sequence[_Path],
    *,
    resample: Optional[float] = None,
) -> Tuple[List[_Array2], List[str]]:
    """Demonstration CSV files as arrays and their columns; ``resample`` (Hz) first."""

def dtw(a: _Array2, b: _Array2, per_step: bool = False) -> float:
    """DTW with Euclidean local cost: the summed cost of the cheapest path (or per step)."""

class Dmp:
    """The discrete dynamic movement primitive baseline, learned from several demonstrations."""
    @staticmethod
    def fit(demos: Sequence[npt.ArrayLike], *, basis: int = 50) -> "Dmp": ...
    def reproduce(self, start: npt.ArrayLike, goal: Optional[npt.ArrayLike] = None) -> np.ndarray:
        """From rest at `start` to `goal` (the demonstrations' mean end when None)."""
    @property
    def samples(self) -> int: ...
