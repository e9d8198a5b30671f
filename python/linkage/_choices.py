"""Re-exports :mod:`linkage._shared.choices` at its 0.1 path (older imports, pickles)."""

from linkage._shared.choices import *  # noqa: F403
from linkage._shared.choices import __all__ as __all__
