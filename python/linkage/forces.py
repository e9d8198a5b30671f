"""Re-exports :mod:`linkage.kinetostatics.forces` at its 0.1 path (older imports, pickles)."""

from linkage.kinetostatics.forces import *  # noqa: F403
from linkage.kinetostatics.forces import __all__ as __all__
