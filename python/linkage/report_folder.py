"""Re-exports :mod:`linkage._shared.report_folder` at its 0.1 path (older imports, pickles)."""

import hashlib as hashlib
import os as os

from linkage._core import LinkageError as LinkageError
from linkage._shared.report_folder import *  # noqa: F403
from linkage._shared.report_folder import __all__ as __all__
from linkage._shared.report_folder import (  # private names older code and the tests use
    _sha256 as _sha256,
)
