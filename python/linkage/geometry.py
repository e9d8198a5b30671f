"""Re-exports :mod:`linkage.motion.geometry` at its 0.1 path (older imports, pickles)."""

from linkage.motion.geometry import *  # noqa: F403
from linkage.motion.geometry import __all__ as __all__
