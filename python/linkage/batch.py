"""Re-exports :mod:`linkage.kinematics.batch` at its 0.1 path (older imports, pickles)."""

from linkage.kinematics.batch import *  # noqa: F403
from linkage.kinematics.batch import __all__ as __all__
