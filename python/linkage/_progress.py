"""Re-exports :mod:`linkage._shared.progress` at its 0.1 path (older imports, pickles)."""

from linkage._shared.progress import *  # noqa: F403
from linkage._shared.progress import __all__ as __all__
