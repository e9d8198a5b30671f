"""Re-exports :mod:`linkage.walking.legs` at its 0.1 path (older imports, pickles)."""

from linkage.walking.legs import *  # noqa: F403
from linkage.walking.legs import __all__ as __all__
