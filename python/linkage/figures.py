"""Re-exports :mod:`linkage.report.figures` at its 0.1 path (older imports, pickles)."""

from linkage.report.figures import *  # noqa: F403
from linkage.report.figures import __all__ as __all__
