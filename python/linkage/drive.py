"""Re-exports :mod:`linkage.drives.drive` at its 0.1 path (older imports, pickles)."""

from linkage.drives.drive import *  # noqa: F403
from linkage.drives.drive import __all__ as __all__
