"""Kutzbach–Gruebler mobility: the count, done by the core, behind :func:`linkage.mobility`."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from linkage import _core
from linkage._core import LinkageError

__all__ = [
    "Mobility",
    "mobility",
]


@dataclass(frozen=True)
class Mobility:
    """Kutzbach–Gruebler count ``F = 3(n − 1) − 2·j1 − j2``."""

    links: int
    """``n``, the ground included."""
    lower_pairs: int
    """``j1``: revolute and prismatic pairs (one freedom each)."""
    higher_pairs: int
    """``j2``: pairs with two freedoms, e.g. a cam contact that rolls and slides."""
    degrees_of_freedom: int
    """``F``, counted by the core."""


def mobility(links: int, lower_pairs: int, higher_pairs: int = 0) -> Mobility:
    """Mobility of a planar linkage by Kutzbach–Gruebler, higher pairs included.

    ``F = 3(n − 1) − 2·j1 − j2``. The count knows nothing of the geometry: an overconstrained
    linkage that moves (a parallelogram with a third parallel link) counts as a structure.

    Parameters
    ----------
    links : int
        ``n``, the ground included (at least 1).
    lower_pairs : int
        ``j1``, revolute and prismatic pairs.
    higher_pairs : int, default 0
        ``j2``, pairs with two freedoms (a cam contact that rolls and slides).

    Returns
    -------
    Mobility
        The counts and ``degrees_of_freedom`` (``F``; 0 for a structure, negative for an
        overconstrained one).

    Raises
    ------
    LinkageError
        For a negative count or no link at all.
    TypeError
        For a count that is not an int.

    Examples
    --------
    >>> from linkage import mobility
    >>> mobility(4, 4).degrees_of_freedom        # four-bar (thesis 2: F = 3(4 − 1) − 2·4)
    1
    >>> mobility(3, 2, 1).degrees_of_freedom     # cam, follower, frame: 2 pins + the contact
    1
    >>> mobility(5, 6).degrees_of_freedom        # a five-bar truss with a pinned diagonal
    0
    >>> mobility(4, -1)
    Traceback (most recent call last):
    ...
    linkage.LinkageError: lower_pairs must be non-negative, got -1
    """
    for name, v in (("links", links), ("lower_pairs", lower_pairs), ("higher_pairs", higher_pairs)):
        if isinstance(v, bool) or not isinstance(v, (int, np.integer)):
            raise TypeError(f"{name} must be an int, got {type(v).__name__}")
        if v < 0:
            raise LinkageError(f"{name} must be non-negative, got {v}")
    if links < 1:
        raise LinkageError("links must count the ground at least")
    n, j1, j2 = int(links), int(lower_pairs), int(higher_pairs)
    return Mobility(n, j1, j2, _core.mechanism.degrees_of_freedom(n, j1, j2))


# These classes' 0.1 module (a re-export of this one) stays their ``__module__``, for pickles and
# reprs; doctest looks for a class's examples in its ``__module__``: ``__test__`` points here.
__test__: dict[str, type] = {"Mobility": Mobility}
for _cls in __test__.values():
    _cls.__module__ = "linkage._mobility"
