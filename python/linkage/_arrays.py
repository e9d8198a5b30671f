"""Re-exports :mod:`linkage._shared.arrays` at its 0.1 path (older imports, pickles)."""

from linkage._shared.arrays import *  # noqa: F403
from linkage._shared.arrays import __all__ as __all__
