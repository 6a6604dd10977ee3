from . import gmr as gmr
from ._errors import FileAccessError as FileAccessError
from ._errors import FileError as FileError
from ._errors import MissingFileError as MissingFileError
from ._native import Config as Config, Hsom as Hsom, dtw as dtw, heldout as heldout
from ._native import read_demos as read_demos
from ._native import GestureModel as GestureModel, Recognition as Recognition
from ._native import Recognizer as Recognizer
from ._native import Stepper as Stepper

__all__ = [
    "Config",
    "Hsom",
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
