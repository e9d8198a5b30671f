"""Re-exports :mod:`linkage.walking.gait_search` at its 0.1 path (older imports, pickles)."""

from linkage.walking.gait_search import *  # noqa: F403
from linkage.walking.gait_search import __all__ as __all__
