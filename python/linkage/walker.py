"""Re-exports :mod:`linkage.walking.walker` at its 0.1 path (older imports, pickles)."""

from linkage.walking.walker import *  # noqa: F403
from linkage.walking.walker import __all__ as __all__
