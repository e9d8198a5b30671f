"""Re-exports :mod:`linkage.kinematics.slider_crank` at its 0.1 path (older imports, pickles)."""

from linkage.kinematics.slider_crank import *  # noqa: F403
from linkage.kinematics.slider_crank import __all__ as __all__
