"""Old path of :mod:`linkage.synthesis.precision_points` (Burmester, Freudenstein)."""

from linkage.synthesis.precision_points import *  # noqa: F403
from linkage.synthesis.precision_points import __all__ as __all__
