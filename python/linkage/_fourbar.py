"""Re-exports :mod:`linkage.kinematics.fourbar` at its 0.1 path (older imports, pickles)."""

from linkage.kinematics.fourbar import *  # noqa: F403
from linkage.kinematics.fourbar import __all__ as __all__
