"""The folder the package caches what it builds once in (the catalogue table, the atlases)."""

from __future__ import annotations

import os
import sys
from pathlib import Path

__all__ = ["cache_dir"]


def cache_dir() -> Path:
    r"""Return the folder the catalogue table and the default atlases are cached in.

    ``$LINKAGE_CACHE_DIR``, else the user's cache folder (``$XDG_CACHE_HOME/linkage``,
    ``~/.cache/linkage``; ``~/Library/Caches/linkage`` on macOS, ``%LOCALAPPDATA%\linkage\Cache`` on
    Windows).

    Returns
    -------
    Path
        The folder (not created here).

    Examples
    --------
    >>> import os
    >>> from linkage._shared.cache_dir import cache_dir
    >>> saved = os.environ.pop("LINKAGE_CACHE_DIR", None)
    >>> os.environ["LINKAGE_CACHE_DIR"] = os.path.join("somewhere", "cache")
    >>> cache_dir().parts
    ('somewhere', 'cache')

    Unset or empty, it is the user's cache folder:

    >>> os.environ["LINKAGE_CACHE_DIR"] = ""
    >>> "linkage" in cache_dir().parts, cache_dir().is_absolute()
    (True, True)
    >>> if saved is None:
    ...     del os.environ["LINKAGE_CACHE_DIR"]
    ... else:
    ...     os.environ["LINKAGE_CACHE_DIR"] = saved
    """
    env = os.environ.get("LINKAGE_CACHE_DIR")
    if env:
        return Path(env)
    if sys.platform == "win32" and os.environ.get("LOCALAPPDATA"):
        return Path(os.environ["LOCALAPPDATA"]) / "linkage" / "Cache"
    if sys.platform == "darwin":
        return Path.home() / "Library" / "Caches" / "linkage"
    xdg = os.environ.get("XDG_CACHE_HOME")
    return (Path(xdg) if xdg and os.path.isabs(xdg) else Path.home() / ".cache") / "linkage"
