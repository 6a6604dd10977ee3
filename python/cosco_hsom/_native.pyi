"""Type stubs of the native module (see the docstrings in cosco_hsom)."""

from os import PathLike
from typing import Any, Dict, List, Optional, Sequence, Union

import numpy as np
import numpy.typing as npt

_Path = Union[str, PathLike]
_Array2 = Union[npt.ArrayLike, Sequence[Sequence[float]]]

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
        """The configuration as XML (every optional value written out)."""
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
        """Load a model saved by Hsom.save or `cosco train` (.bin or .txt)."""
    def save(self, path: _Path) -> None:
        """Save the model (.bin binary, .txt plain text; written atomically)."""
    def reproduce(self, initial: npt.ArrayLike) -> np.ndarray:
        """Reproduce from an initial posture: one row per step, the first the initial posture."""
    @property
    def columns(self) -> List[str]: ...
    @property
    def config(self) -> Config: ...
    def summary(self) -> Dict[str, Any]:
        """Levels, sizes and quality measures (what `cosco inspect` prints)."""

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

def dtw(a: _Array2, b: _Array2, per_step: bool = False) -> float:
    """DTW with Euclidean local cost: the summed cost of the cheapest path (or per step)."""
