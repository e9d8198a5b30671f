"""Re-exports :mod:`linkage._shared.toml_lines` at its 0.1 path (older imports, pickles)."""

from linkage._shared.toml_lines import *  # noqa: F403
from linkage._shared.toml_lines import __all__ as __all__
