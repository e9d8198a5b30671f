"""Re-exports :mod:`linkage._shared.size` at its 0.1 path (older imports, pickles)."""

from linkage._shared.size import *  # noqa: F403
from linkage._shared.size import __all__ as __all__
