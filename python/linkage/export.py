"""Re-exports :mod:`linkage.report.export` at its 0.1 path (older imports, pickles)."""

from linkage.report.export import *  # noqa: F403
from linkage.report.export import __all__ as __all__
