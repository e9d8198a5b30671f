"""The installed package's version (``linkage.__version__``), in a module of its own.

Modules that record the version (report metadata, cache keys) import it from here, so none of
them needs the package's ``__init__``, which imports them.
"""

from __future__ import annotations

from importlib.metadata import PackageNotFoundError, version

try:
    __version__ = version("linkage-kinematics")
except PackageNotFoundError:  # pragma: no cover - running from a source tree
    __version__ = "0+unknown"

__all__ = ["__version__"]
