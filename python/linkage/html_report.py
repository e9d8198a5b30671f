"""Re-exports :mod:`linkage.report.html` at its 0.1 path (older imports, pickles)."""

from linkage.report.html import *  # noqa: F403
from linkage.report.html import __all__ as __all__
from linkage.report.html import (  # private names older code and the tests use
    _ranked_after as _ranked_after,
)
from linkage.report.html import (
    _readout as _readout,
)
from linkage.report.html import (
    _views as _views,
)
