"""Re-exports :mod:`linkage.kinematics.mobility` at its 0.1 path (older imports, pickles)."""

from linkage.kinematics.mobility import *  # noqa: F403
from linkage.kinematics.mobility import __all__ as __all__
