"""Re-exports :mod:`linkage.scene.schema` at its 0.1 path (older imports, pickles)."""

from linkage.scene.schema import *  # noqa: F403
from linkage.scene.schema import __all__ as __all__
