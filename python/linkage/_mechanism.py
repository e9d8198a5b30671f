"""Re-exports :mod:`linkage.kinematics.mechanism` at its 0.1 path (older imports, pickles)."""

from linkage.kinematics.mechanism import *  # noqa: F403
from linkage.kinematics.mechanism import __all__ as __all__
from linkage.kinematics.mechanism import _rebuild as _rebuild  # named by pickles
