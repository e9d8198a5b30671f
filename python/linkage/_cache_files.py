"""Re-exports :mod:`linkage._shared.cache_files` at its 0.1 path (older imports, pickles)."""

from linkage._shared.cache_files import *  # noqa: F403
from linkage._shared.cache_files import __all__ as __all__
