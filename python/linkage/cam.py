"""Re-exports :mod:`linkage.drives.cam` at its 0.1 path (older imports, pickles)."""

from linkage.drives.cam import *  # noqa: F403
from linkage.drives.cam import __all__ as __all__
