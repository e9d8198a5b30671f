"""Re-exports :mod:`linkage.kinematics.sweep` at its 0.1 path (older imports, pickles)."""

from linkage._core import RATE_MARGIN as RATE_MARGIN
from linkage.kinematics.sweep import *  # noqa: F403
from linkage.kinematics.sweep import __all__ as __all__
from linkage.kinematics.sweep import _rebuild as _rebuild  # named by pickles
