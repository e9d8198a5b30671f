"""Re-exports :mod:`linkage.report.stages` at its 0.1 path (older imports, pickles)."""

from linkage.report.stages import *  # noqa: F403
from linkage.report.stages import __all__ as __all__
