"""The kinds of linkage path synthesis searches, and the tolerances every stage shares.

A four-bar or an offset slider-crank (:class:`_Kind`: its placed parameter vector), the kinds
of atlas of each (whole circuits, open arcs) and their default sizes.
"""

from __future__ import annotations

import os
from dataclasses import dataclass
from typing import Any, get_args

import numpy as np
from numpy.typing import NDArray

from linkage import _core
from linkage._core import LinkageError
from linkage._shared.arrays import as_count
from linkage._shared.choices import AtlasKind, LinkageKind

__all__ = [
    "ARCS",
    "DEFAULT_ARC_ENTRIES",
    "DEFAULT_ENTRIES",
    "DEFAULT_SLIDER_ARC_ENTRIES",
    "DEFAULT_SLIDER_ENTRIES",
    "EXACT",
    "FOURBAR",
    "KINDS",
    "SLIDER",
    "SLIDER_ARCS",
    "TIGHT",
    "Float2D",
]

DEFAULT_ENTRIES = 200_000
"""Entries of the default four-bar atlas (built once into the cache folder)."""

DEFAULT_SLIDER_ENTRIES = 100_000
"""Entries of the default slider-crank atlas (four shape numbers against the four-bar's five)."""

KINDS: tuple[LinkageKind, ...] = get_args(LinkageKind)
"""The kinds of linkage :func:`path` searches (``kind="any"``: both)."""

ARCS: AtlasKind = "fourbar-arcs"
"""The kind of :class:`Atlas` whose entries are open arcs of four-bar circuits: :func:`path`
matches open targets against it (``linkage_core::Atlas::build_arcs``)."""

DEFAULT_ARC_ENTRIES = 560_000
"""Entries of the default arc atlas: 10,000 circuits × 8 starts × 7 fractions of a circuit."""

SLIDER_ARCS: AtlasKind = "slider-crank-arcs"
"""The kind of :class:`Atlas` whose entries are open arcs of slider-crank circuits: :func:`path`
matches open slider-crank targets against it (``linkage_core::Atlas::build_slider_arcs``)."""

DEFAULT_SLIDER_ARC_ENTRIES = 560_000
"""Entries of the default slider-crank arc atlas: 10,000 circuits × 8 starts × 7 fractions, as
many circuits as the four-bar's (5,000 missed three arcs of ``bench/open_arcs.py --kind
slider-crank`` that this finds; docs/synthesis.md)."""

# The columns of an atlas entry of each kind: the core's `*ENTRY_PARAMS`, never copied.
_ENTRY_WIDTH = {
    "fourbar": _core.synthesis.ENTRY_PARAMS,
    "slider-crank": _core.synthesis.SLIDER_ENTRY_PARAMS,
    ARCS: _core.synthesis.ARC_ENTRY_PARAMS,
    SLIDER_ARCS: _core.synthesis.SLIDER_ARC_ENTRY_PARAMS,
}

Float2D = NDArray[np.float64]


@dataclass(frozen=True)
class _Kind:
    """What the search needs to know of a kind of linkage's placed parameter vector."""

    name: LinkageKind
    params: int  # placed parameters
    entry: int  # atlas entry parameters
    lengths: tuple[int, ...]  # indices of the link lengths
    angles: tuple[int, ...]  # indices of angles (radians, not lengths)
    pivots: tuple[tuple[int, int], ...]  # indices of the ground pivots' (x, y)
    default_entries: int
    arcs: AtlasKind  # the kind of its arc atlas, for open targets
    arc_entries: int  # entries of the default arc atlas
    scaled: tuple[int, ...]  # indices of every length (links, offsets, the coupler point)


_Kind.__module__ = "linkage.synthesis"  # as before the split: pickles and reprs name it so


FOURBAR = _Kind(
    "fourbar",
    9,
    6,
    (4, 5, 6),
    (),
    ((0, 1), (2, 3)),
    DEFAULT_ENTRIES,
    ARCS,
    DEFAULT_ARC_ENTRIES,
    (4, 5, 6, 7, 8),
)
"""Placed ``[ox, oy, cx, cy, crank, coupler, rocker, along, left]`` (with an assembly flag)."""

SLIDER = _Kind(
    "slider-crank",
    8,
    4,
    (4, 5),
    (2,),
    ((0, 1),),
    DEFAULT_SLIDER_ENTRIES,
    SLIDER_ARCS,
    DEFAULT_SLIDER_ARC_ENTRIES,
    (3, 4, 5, 6, 7),
)
"""Placed ``[ox, oy, angle, offset, crank, coupler, along, left]`` (reach ahead: the other reach
is the same linkage with the line reversed, so no flag)."""

_KIND = {k.name: k for k in (FOURBAR, SLIDER)}
_ARC_KIND = {k.arcs: k for k in (FOURBAR, SLIDER)}


def _atlas_kind(kind: Any) -> tuple[_Kind, bool]:
    """Return the linkage kind of an atlas kind and whether its entries are open arcs."""
    if isinstance(kind, str) and kind in _ARC_KIND:
        return _ARC_KIND[kind], True
    return _kind(kind, *_ARC_KIND), False


def _kind(kind: Any, *also: str) -> _Kind:
    """Return the linkage kind named ``kind``; an error names the kinds and ``also``.

    ``also`` are the caller's further choices, handled by the caller (``"any"`` for
    :func:`path`, the arc kinds for atlases), so the message lists every name it takes.
    """
    if not isinstance(kind, str):
        raise TypeError(f"kind must be a str, got {type(kind).__name__}")
    if kind not in _KIND:
        names = [repr(k) for k in (*_KIND, *also)]
        listed = ", ".join(names[:-1]) + " or " + names[-1]
        raise LinkageError(f"kind must be {listed}, got {kind!r}")
    return _KIND[kind]


def _threads(threads: int | None) -> int:
    if threads is None:
        return max(1, min(os.cpu_count() or 1, 64))
    return min(as_count(threads, "threads"), 256)


EXACT = 1e-6
"""Errors below this fraction of the target's size count as exact (a tie) when ranking."""

TIGHT = 1e-10
"""An open target's best fit above this fraction of its size but within :data:`EXACT` (when no
``accept`` is given) gets one long fit, to round-off where the fit is exact."""
