"""Re-exports :mod:`linkage.scene.builders` at its 0.1 path (older imports, pickles)."""

from linkage.kinematics.mechanism import JOINT_KINDS as JOINT_KINDS
from linkage.scene.builders import *  # noqa: F403
from linkage.scene.builders import __all__ as __all__
