"""Re-exports :mod:`linkage._shared.version` at its 0.1 path (older imports, pickles)."""

from linkage._shared.version import *  # noqa: F403
from linkage._shared.version import __all__ as __all__
