from . import gmr as gmr
from ._native import Config as Config, Hsom as Hsom, dtw as dtw

__all__ = ["Config", "Hsom", "dtw", "gmr"]
