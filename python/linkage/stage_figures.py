"""Re-exports :mod:`linkage.report.stage_rows` at its 0.1 path (older imports, pickles)."""

from linkage.report.stage_rows import *  # noqa: F403
from linkage.report.stage_rows import __all__ as __all__
from linkage.report.stage_rows import (  # private names older code and the tests use
    _near_change_point as _near_change_point,
)
from linkage.report.stage_rows import (
    _on_a_line as _on_a_line,
)
