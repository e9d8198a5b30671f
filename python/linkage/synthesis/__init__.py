"""Dimensional synthesis of four-bars and slider-cranks for path generation.

The linkage sought is one whose coupler curve passes through given points.

``path(points)`` normalises the target's elliptic Fourier descriptors, looks up the nearest
shapes in an :class:`Atlas` of normalised four-bars (``kind="slider-crank"``: of normalised
offset slider-cranks; ``"any"``: both), places each in the target's frame, refines
the best by a least-squares fit of the true point-to-curve distance and, where the atlas does
not cover the target (an open curve, or no close match), searches globally by differential
evolution over the batch evaluator. Every candidate's circuit is swept by the tracker
(``check``) so none switches branch or passes an unassemblable sample; see ``docs/synthesis.md``.

Precision-point synthesis lives here too: :func:`motion` (Burmester, 3 or 4 poses) and
:func:`function` (Freudenstein), with their curves and types (``docs/precision-points.md``).
"""

from __future__ import annotations

import argparse
import hashlib
import json
import math
import os
import re
import stat
import sys
import time
import warnings
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any, Generic, TypeVar, Union, cast, get_args

import numpy as np
from numpy.typing import ArrayLike, NDArray

from linkage import _core
from linkage._arrays import as_count, as_finite, as_flag, as_point, as_real_array
from linkage._cache_files import core_identity, read_npy
from linkage._choices import AtlasKind, LinkageKind, PathKind
from linkage._core import LinkageError
from linkage._files import read_json, sweep_stale
from linkage._fourbar import FourBar
from linkage.synthesis.precision_points import (
    Dyad,
    FunctionGenerator,
    MotionCandidate,
    centre_point_curve,
    chebyshev_points,
    circle_point_curve,
    function,
    motion,
)
from linkage._progress import Bar
from linkage._schema import POINTS_MAX, SYNTHESIS_REFINE_MAX, SYNTHESIS_TOP_MAX
from linkage._size import mean as _mean
from linkage._size import pow2 as _pow2
from linkage._size import rms_size
from linkage._slider_crank import SliderCrank
from linkage._version import __version__
from linkage.catalog import cache_dir

__all__ = [
    "CHANGE_POINT_NEAR",
    "CONSTRAINT_NAMES",
    "KINDS",
    "MIN_POINTS",
    "Atlas",
    "Candidate",
    "Candidates",
    "Dyad",
    "FunctionGenerator",
    "MotionCandidate",
    "atlas_kinds",
    "centre_point_curve",
    "change_point_gap",
    "chebyshev_points",
    "circle_point_curve",
    "default_atlas",
    "function",
    "is_cached",
    "long_link",
    "longest_link",
    "missing_atlases",
    "motion",
    "path",
    "read_points",
    "source_text",
    "why_none",
]

MIN_POINTS = 5
"""Fewest target points: a four-bar's coupler curve has five shape parameters beyond placement."""

CURVE_EQUATION_POINTS = 16
"""Fewest target points from which a four-bar is sought through the equation of the curve they
lie on (``linkage_core::CURVE_EQUATION_POINTS``: the equation has 16 coefficients)."""

SLIDER_EQUATION_POINTS = 13
"""Fewest target points from which a slider-crank is sought through the equation of the curve
they lie on (``linkage_core::SLIDER_EQUATION_POINTS``: a circular quartic, 13 coefficients)."""

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

_ENTRY_WIDTH = {"fourbar": 6, "slider-crank": 4, ARCS: 8, SLIDER_ARCS: 6}

ATLAS_FORMAT = 3
"""Bumped whenever the stored atlas's content or meaning changes."""

LONG_LINK = 20.0
"""Default ``max_link`` of :func:`path`: candidates with a link longer than this many target
sizes rank after all others (a 25 mm curve drawn with links of metres is no design)."""

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


# -- the atlas ------------------------------------------------------------------------------


ATLAS_FILES = ("descriptors.npy", "params.npy", "meta.json")
"""The files of a saved atlas (:meth:`Atlas.save`), in the order they are moved into place."""

ATLAS_HARMONICS_MAX = 64
"""Most harmonics an atlas may describe its curves with (8 by default): each adds four numbers
to every entry and work to every match."""

ATLAS_SAMPLES_MAX = 4096
"""Most samples of a circuit an atlas may give (64 by default, 128 for arcs): every match
re-samples its entry's circuit this many times to place it (0.3 ms at 64, 0.6 ms at 4096,
0.25 s at 10⁶ — a search places hundreds — and 10¹⁰ would allocate 160 GB)."""

ATLAS_META_MAX = 64 << 10
"""Largest ``meta.json`` an atlas may have, in bytes (:meth:`Atlas.save` writes about 100)."""

_ARC_FRACTIONS = 7  # linkage_core::ARC_FRACTIONS.len(): an arc entry's last column indexes them

_ATLAS_TEMP = r"\.(?:{name})\.tmp(\d+)-[0-9a-f]{{8}}"
""":meth:`Atlas.save`'s temporary folder beside ``name``: ``.<name>.tmp<pid>-<8 hex>``."""


def _atlas_temps(name: str) -> re.Pattern[str]:
    """Return the pattern of :meth:`Atlas.save`'s temporary folders for ``name`` (a regex)."""
    return re.compile(_ATLAS_TEMP.format(name=name))


def _atlas_meta(path: Path) -> bool:
    """Whether ``path`` is an atlas's ``meta.json`` (any format: an old one is replaced)."""
    try:
        meta = read_json(path, ATLAS_META_MAX, "atlas's meta.json")
    except LinkageError:
        return False
    return isinstance(meta, dict) and "format" in meta and "entries" in meta


def _meta_int(
    meta: dict[str, Any], key: str, low: int, high: int, default: int | None = None
) -> int:
    """Return ``meta[key]``, an int (not bool) from ``low`` to ``high``; a message otherwise."""
    v = meta.get(key, default)
    if isinstance(v, bool) or not isinstance(v, int) or not low <= v <= high:
        got = "nothing" if key not in meta else json.dumps(v)[:40]
        raise LinkageError(f"meta.json: {key} must be an int from {low} to {high}, got {got}")
    return v


def _check_atlas(at: Atlas) -> None:
    """Raise unless ``at``'s fields are of their types, in range and agree with its arrays.

    ``TypeError`` for a field of the wrong type, :class:`LinkageError` naming the field
    otherwise; the arrays' values are checked too (finite parameters, arc indices in range).
    """
    for name in ("harmonics", "samples", "phases"):
        v = getattr(at, name)
        if isinstance(v, (bool, np.bool_)) or not isinstance(v, (int, np.integer)):
            raise TypeError(f"{name} must be an int, got {type(v).__name__}")
    if not isinstance(at.kind, str):
        raise TypeError(f"kind must be a str, got {type(at.kind).__name__}")
    if at.kind not in _ENTRY_WIDTH:
        listed = ", ".join(repr(k) for k in _ENTRY_WIDTH)
        raise LinkageError(f"kind must be one of {listed}, got {at.kind!r}")
    arcs = at.kind in _ARC_KIND
    least = 32 if arcs else 8
    if not 1 <= at.harmonics <= ATLAS_HARMONICS_MAX:
        raise LinkageError(f"harmonics must be from 1 to {ATLAS_HARMONICS_MAX}, got {at.harmonics}")
    if not least <= at.samples <= ATLAS_SAMPLES_MAX:
        raise LinkageError(
            f"samples must be from {least} to {ATLAS_SAMPLES_MAX} for a {at.kind} atlas, "
            f"got {at.samples}"
        )
    if arcs and not 1 <= at.phases <= at.samples:
        raise LinkageError(f"phases must be from 1 to samples ({at.samples}), got {at.phases}")
    if not arcs and at.phases != 0:
        raise LinkageError(f"phases must be 0 for a {at.kind} atlas, got {at.phases}")
    width = 1 + 4 * (at.harmonics - 1)
    for name, dtype, cols in (
        ("descriptors", np.float32, width),
        ("params", np.float64, _ENTRY_WIDTH[at.kind]),
    ):
        a = getattr(at, name)
        if not isinstance(a, np.ndarray):
            raise TypeError(f"{name} must be a numpy array, got {type(a).__name__}")
        if a.dtype != dtype:
            raise TypeError(f"{name} must be {np.dtype(dtype)}, got {a.dtype}")
        if a.ndim != 2 or a.shape[1] != cols or a.shape[0] < 1:
            raise LinkageError(
                f"{name} must have shape (entries ≥ 1, {cols}) for a {at.kind} atlas of "
                f"{at.harmonics} harmonics, got {a.shape}"
            )
        if not a.flags.c_contiguous:
            raise LinkageError(f"{name} must be C-contiguous")
    if at.params.shape[0] != at.descriptors.shape[0]:
        raise LinkageError(
            f"params have {at.params.shape[0]} entries, descriptors {at.descriptors.shape[0]}"
        )
    for name in ("descriptors", "params"):
        a = getattr(at, name)
        if not np.isfinite(a).all():  # the whole array at once: per row only to name one
            bad = _first_false(np.isfinite(a).all(axis=1))
            raise LinkageError(f"{name} of entry {bad} are not all finite")
    slider = at.kind in ("slider-crank", SLIDER_ARCS)
    # The links (crank, coupler, rocker; a slider-crank's coupler) are lengths: positive normal
    # floats, as the linkages' constructors require. A four-bar's assembly flag is 0 or 1.
    links = at.params[:, :1] if slider else at.params[:, :3]
    ok = np.asarray((links >= np.finfo(np.float64).tiny).all(axis=1), dtype=bool)
    if not ok.all():
        bad = _first_false(ok)
        raise LinkageError(f"params of entry {bad}: a link length is not a positive normal float")
    if not slider:
        flag = at.params[:, 5]
        ok = np.asarray((flag == 0) | (flag == 1), dtype=bool)
        if not ok.all():
            bad = _first_false(ok)
            raise LinkageError(f"params of entry {bad}: the crossed flag {flag[bad]} is not 0 or 1")
    if arcs:
        for col, high, what in ((-2, at.phases, "phase"), (-1, _ARC_FRACTIONS, "fraction")):
            c = at.params[:, col]
            if c.min() < 0 or c.max() >= high or not (np.floor(c) == c).all():
                ok = (c >= 0) & (c < high) & (np.floor(c) == c)
                bad = _first_false(ok)
                raise LinkageError(
                    f"params of entry {bad}: the arc's {what} {c[bad]} is not an index below {high}"
                )


def _first_false(ok: NDArray[np.bool_]) -> int | None:
    """Return the first index where ``ok`` is False, None if none is."""
    bad = np.flatnonzero(~ok)
    return int(bad[0]) if bad.size else None


@dataclass
class Atlas:
    """Normalised four-bars and the elliptic Fourier descriptors of their coupler curves.

    The four-bars have their ground at ``O = (0, 0)``, ``C = (1, 0)``; the descriptors of their
    circuits' coupler curves are normalised.

    ``descriptors`` is ``(N, D)`` float32 (``D = 1 + 4(harmonics − 1)``), ``params`` ``(N, 6)``
    float64 ``crank, coupler, rocker, along, left, crossed``. Stored as a folder of ``.npy``
    files (memory-mapped on load) and a ``meta.json``.

    An atlas of ``kind="slider-crank"`` holds offset slider-cranks with the crank pivot at
    ``(0, 0)``, crank 1 and the line along ``+x`` (reach ahead); its ``params`` are ``(N, 4)``
    ``coupler, offset, along, left``.

    An atlas of ``kind="fourbar-arcs"`` (:data:`ARCS`) holds open arcs of the four-bars'
    circuits, ``phases`` starts on each times fractions ⅛ … ¾ of the circuit, described as
    open curves; its ``params`` are ``(N, 8)``: the four-bar's six, the arc's start and the
    index of its fraction. One of ``kind="slider-crank-arcs"`` (:data:`SLIDER_ARCS`) holds the
    same arcs of the slider-cranks' circuits; its ``params`` are ``(N, 6)``: the slider-crank's
    four, the start and the fraction.
    """

    descriptors: NDArray[np.float32]
    params: NDArray[np.float64]
    harmonics: int
    samples: int
    kind: AtlasKind = "fourbar"
    phases: int = 0

    def __post_init__(self) -> None:
        """Check every field, against the others and the arrays.

        Raises
        ------
        TypeError
            For a field of the wrong type: arrays not numpy arrays of float32 descriptors and
            float64 params, counts not ints, a kind not a str.
        LinkageError
            Naming the field: an unknown kind; harmonics outside 1 … :data:`ATLAS_HARMONICS_MAX`;
            samples outside 8 (32 for arcs) … :data:`ATLAS_SAMPLES_MAX`; phases not 1 …
            samples for arcs, not 0 otherwise; arrays not C-contiguous, of other shapes than
            ``(N, 1 + 4(harmonics − 1))`` and ``(N, width of the kind)``, with no entry, or
            with values that are not finite; arc indices out of range.

        Examples
        --------
        >>> import numpy as np
        >>> from linkage.synthesis import Atlas
        >>> Atlas(np.zeros((2, 29), np.float32), np.ones((2, 6)), 8, 10**10)
        Traceback (most recent call last):
        ...
        linkage.LinkageError: samples must be from 8 to 4096 for a fourbar atlas, got 10000000000
        >>> Atlas(np.zeros((2, 29), np.float32), np.ones((2, 6)), True, 64)
        Traceback (most recent call last):
        ...
        TypeError: harmonics must be an int, got bool
        """
        _check_atlas(self)

    def __len__(self) -> int:
        """Return the number of entries."""
        return int(self.descriptors.shape[0])

    def __repr__(self) -> str:
        """Return a one-line summary: kind, entries, harmonics and size (not the arrays).

        Examples
        --------
        >>> import linkage
        >>> linkage.synthesis.Atlas.build(1000, threads=1)
        Atlas(kind='fourbar', entries=1_000, harmonics=8, size_mb=0.164)
        """
        mb = (self.descriptors.nbytes + self.params.nbytes) / 1e6
        return (
            f"Atlas(kind={self.kind!r}, entries={len(self):_}, harmonics={self.harmonics}, "
            f"size_mb={mb:.3g})"
        )

    @classmethod
    def build(
        cls,
        entries: int,
        harmonics: int = 8,
        samples: int | None = None,
        threads: int | None = None,
        kind: AtlasKind = "fourbar",
    ) -> Atlas:
        """Build an atlas of ``entries`` entries on ``threads`` threads (default: every core).

        ``kind`` is ``"fourbar"``, ``"slider-crank"``, ``"fourbar-arcs"`` or
        ``"slider-crank-arcs"`` (arcs: then ``samples`` are the circuit's, at least 32, and every
        circuit gives 8 starts × 7 fractions).
        ``samples`` defaults to 64 (128 for arcs), at most :data:`ATLAS_SAMPLES_MAX`;
        ``harmonics`` at most :data:`ATLAS_HARMONICS_MAX`. The result does not depend on
        ``threads``.

        Examples
        --------
        >>> import linkage
        >>> at = linkage.synthesis.Atlas.build(100, harmonics=4, threads=1)
        >>> len(at), at.descriptors.shape, at.params.shape, at.kind
        (100, (100, 13), (100, 6), 'fourbar')
        >>> linkage.synthesis.Atlas.build(100, kind="slider-crank", threads=1).params.shape
        (100, 4)
        >>> linkage.synthesis.Atlas.build(100, kind="crank")
        Traceback (most recent call last):
        ...
        linkage.LinkageError: kind must be 'fourbar', 'slider-crank', 'fourbar-arcs' or \
'slider-crank-arcs', got 'crank'
        """
        n = as_count(entries, "entries")
        h = as_count(harmonics, "harmonics")
        k, arcs = _atlas_kind(kind)
        m = as_count((128 if arcs else 64) if samples is None else samples, "samples", 8)
        if h > ATLAS_HARMONICS_MAX or m > ATLAS_SAMPLES_MAX:
            raise LinkageError(
                f"an atlas has at most {ATLAS_HARMONICS_MAX} harmonics and "
                f"{ATLAS_SAMPLES_MAX} samples, got {h} and {m}"
            )
        if arcs:
            slider = k is SLIDER
            desc, params, _ = _core.synth_arc_atlas_build(n, h, m, 8, _threads(threads), slider)
            return cls(desc, params, h, m, k.arcs, 8)
        build = _core.synth_atlas_build if k is FOURBAR else _core.synth_slider_atlas_build
        desc, params, _ = build(n, h, m, _threads(threads))
        return cls(desc, params, h, m, k.name)

    def save(self, folder: str | os.PathLike[str]) -> Path:
        """Write the atlas to ``folder``: a new or empty folder, or one holding an atlas.

        The files are written beside it first and moved in when complete, so an interrupted
        save leaves what was there (and the temporary folder of a process killed meanwhile,
        ``.<name>.tmp<pid>-<hex>``, is removed by the next save beside it). A folder holding
        anything else — the user's files, or a link or a pipe at an atlas file's name — is a
        :class:`LinkageError`, as are a file or a symbolic link given as the folder.

        Examples
        --------
        >>> import tempfile
        >>> import linkage
        >>> with tempfile.TemporaryDirectory() as tmp:
        ...     saved = linkage.synthesis.Atlas.build(100, threads=1).save(tmp)
        ...     back = linkage.synthesis.Atlas.load(saved)
        ...     print(len(back), back.kind, back.descriptors.dtype)
        100 fourbar float32
        """
        return self._save(Path(folder), cache=False)

    def _save(self, out: Path, cache: bool) -> Path:
        """Write as :meth:`save`; with ``cache``, into the tool's own cache folder ``out``.

        There the atlas files (regular files of those names) are replaced even when corrupt.
        """
        if out.is_symlink():
            raise LinkageError(f"{out} is a symbolic link: save the atlas into a folder")
        if out.exists():
            if not out.is_dir():
                raise LinkageError(f"{out} is a file, not a folder to save the atlas into")
            others = sorted(
                q.name
                for q in out.iterdir()
                if q.name not in ATLAS_FILES or not stat.S_ISREG(q.lstat().st_mode)
            )
            old = out / "meta.json"
            if others or (not cache and old.exists() and not _atlas_meta(old)):
                mine = ", ".join(others[:3]) + (", ..." if len(others) > 3 else "")
                raise LinkageError(
                    f"{out} holds files that are not an atlas's ({mine or 'meta.json'}): "
                    "save into a new or empty folder"
                )
        out.parent.mkdir(parents=True, exist_ok=True)
        sweep_stale(out.parent, _atlas_temps(re.escape(out.name)))
        tmp = out.parent / f".{out.name}.tmp{os.getpid()}-{os.urandom(4).hex()}"
        tmp.mkdir()
        try:
            np.save(tmp / "descriptors.npy", np.ascontiguousarray(self.descriptors))
            np.save(tmp / "params.npy", np.ascontiguousarray(self.params))
            meta = {
                "format": ATLAS_FORMAT,
                "harmonics": int(self.harmonics),  # numpy ints are not JSON
                "samples": int(self.samples),
                "entries": len(self),
                "kind": self.kind,
                "phases": int(self.phases),
            }
            (tmp / "meta.json").write_text(json.dumps(meta))
            if out.exists():
                # meta.json last: a reader that finds it finds the arrays it describes.
                for name in ATLAS_FILES:
                    os.replace(tmp / name, out / name)
                tmp.rmdir()
            else:
                os.rename(tmp, out)
        finally:
            if tmp.exists():
                for name in ATLAS_FILES:
                    (tmp / name).unlink(missing_ok=True)
                tmp.rmdir()
        return out

    @classmethod
    def load(cls, folder: str | os.PathLike[str]) -> Atlas:
        """Open an atlas written by :meth:`save`, memory-mapped.

        Every field of ``meta.json`` and both arrays are checked as :class:`Atlas` checks
        them (see ``__post_init__``) before anything is searched; the files are read as a
        cache's are (regular files only, ``meta.json`` of at most :data:`ATLAS_META_MAX`
        bytes, arrays without pickles and of exactly the size their headers give).

        Raises
        ------
        LinkageError
            ``<folder> is not a readable atlas: <file or field>: <why>``.

        Examples
        --------
        >>> import tempfile
        >>> import linkage
        >>> with tempfile.TemporaryDirectory() as tmp:
        ...     linkage.synthesis.Atlas.load(tmp)
        Traceback (most recent call last):
        ...
        linkage.LinkageError: ... is not a readable atlas: meta.json: cannot read ...
        """
        src = Path(folder)
        try:
            meta = read_json(src / "meta.json", ATLAS_META_MAX, "atlas's meta.json")
            if not isinstance(meta, dict):
                raise LinkageError("meta.json: not a JSON object")
            if meta.get("format") != ATLAS_FORMAT:
                got = json.dumps(meta.get("format"))[:40]
                raise LinkageError(f"meta.json: format must be {ATLAS_FORMAT}, got {got}")
            kind = meta.get("kind", "fourbar")
            if not isinstance(kind, str) or kind not in _ENTRY_WIDTH:
                listed = ", ".join(repr(k) for k in _ENTRY_WIDTH)
                got = json.dumps(kind)[:40]
                raise LinkageError(f"meta.json: kind must be one of {listed}, got {got}")
            harmonics = _meta_int(meta, "harmonics", 1, ATLAS_HARMONICS_MAX)
            samples = _meta_int(meta, "samples", 8, ATLAS_SAMPLES_MAX)
            entries = _meta_int(meta, "entries", 1, sys.maxsize)
            phases = _meta_int(meta, "phases", 0, samples, 0)
            desc = read_npy(src / "descriptors.npy", np.float32, "atlas's descriptors")
            params = read_npy(src / "params.npy", np.float64, "atlas's parameters")
            if desc.shape[0] != entries:
                raise LinkageError(
                    f"meta.json: entries is {entries}, but descriptors.npy holds {desc.shape[0]}"
                )
            known = cast("AtlasKind", kind)  # one of _ENTRY_WIDTH's keys, checked above
            return cls(desc, params, harmonics, samples, known, phases)
        except LinkageError as e:
            why = str(e).replace(f"{src}{os.sep}", "")
            raise LinkageError(f"{src} is not a readable atlas: {why}") from None

    def nearest(
        self, targets: NDArray[np.float32], k: int, threads: int | None = None
    ) -> tuple[NDArray[np.int64], NDArray[np.float32], NDArray[np.int64]]:
        """Find the ``k`` entries nearest any row of ``targets``, nearest first.

        Returns ``(entry, squared distance, target row)``.

        Examples
        --------
        An entry's own descriptors find it, at distance 0:

        >>> import linkage
        >>> at = linkage.synthesis.Atlas.build(100, threads=1)
        >>> at.nearest(at.descriptors[[7]], 1, threads=1)
        (array([7]), array([0.], dtype=float32), array([0]))
        """
        q = np.asarray(targets)
        if q.dtype.kind not in "iuf":
            raise TypeError(f"targets must be a numeric array, got dtype {q.dtype}")
        q = np.ascontiguousarray(np.atleast_2d(q), dtype=np.float32)
        if q.ndim != 2 or q.shape[1] != self.descriptors.shape[1]:
            raise LinkageError(
                f"targets must have shape (m, {self.descriptors.shape[1]}), got {q.shape}"
            )
        return _core.synth_atlas_nearest(self.descriptors, q, as_count(k, "k"), _threads(threads))


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


def default_atlas(
    entries: int | None = None, harmonics: int = 8, kind: AtlasKind = "fourbar"
) -> Atlas:
    """Return the default atlas of ``kind``, built on first use into the cache folder.

    ``entries`` defaults to :data:`DEFAULT_ENTRIES` four-bars,
    :data:`DEFAULT_SLIDER_ENTRIES` slider-cranks, :data:`DEFAULT_ARC_ENTRIES` arcs
    (``kind="fourbar-arcs"``) or :data:`DEFAULT_SLIDER_ARC_ENTRIES` (``"slider-crank-arcs"``).
    The cache folder is ``$LINKAGE_CACHE_DIR``, else the user's cache folder; the atlas is
    memory-mapped from there afterwards. A cached atlas that does not load, whatever is wrong
    with it, is rebuilt with a :class:`UserWarning` naming its folder and what was wrong; the
    temporary folders of saves killed before they finished are removed.
    """
    k, arcs = _atlas_kind(kind)
    entries, folder = _default_folder(entries, harmonics, kind)
    sweep_stale(folder.parent, _atlas_temps(r"atlas-[0-9a-f]{16}"))
    if os.path.lexists(folder):
        try:
            return Atlas.load(folder)
        except LinkageError as exc:
            warnings.warn(f"rebuilding the default {kind} atlas: {exc}", stacklevel=2)
    atlas = Atlas.build(entries, harmonics, kind=k.arcs if arcs else k.name)
    try:
        atlas._save(folder, cache=True)  # written beside it and moved in (over a corrupt one)
    except (OSError, LinkageError):
        pass  # a cache that cannot be written is no error: the atlas is in memory
    return atlas


def atlas_kinds(kind: PathKind, closed: bool) -> tuple[AtlasKind, ...]:
    """Return the kinds of atlas :func:`path` searches for ``kind`` and a closed or open target.

    Examples
    --------
    >>> import linkage
    >>> linkage.synthesis.atlas_kinds("any", closed=False)
    ('fourbar-arcs', 'slider-crank-arcs')
    """
    kinds = list(_KIND.values()) if kind == "any" else [_kind(kind, "any")]
    return tuple(k.name if closed else k.arcs for k in kinds)


def is_cached(kind: AtlasKind) -> bool:
    """Return whether the default atlas of ``kind`` is in the cache folder.

    If not, the first search that needs it builds it (a few seconds).

    Examples
    --------
    >>> import linkage
    >>> linkage.synthesis.is_cached("fourbar") in (True, False)
    True
    """
    return (_default_folder(None, 8, kind)[1] / "meta.json").is_file()


def missing_atlases(kind: PathKind, closed: bool, given: Iterable[str] = ()) -> list[AtlasKind]:
    """Return the default atlases a search of ``kind`` would build first.

    Those it searches (:func:`atlas_kinds`) that are neither ``given`` (kinds of atlases passed
    in) nor in the cache folder.

    Examples
    --------
    >>> import linkage
    >>> linkage.synthesis.missing_atlases("fourbar", closed=True, given=["fourbar"])
    []
    """
    have = set(given)
    return [a for a in atlas_kinds(kind, closed) if a not in have and not is_cached(a)]


def _default_folder(entries: int | None, harmonics: int, kind: AtlasKind) -> tuple[int, Path]:
    """Return the entries of the default atlas of ``kind`` and its cache folder.

    The folder's name hashes what the atlas depends on: its format, size and kind, the
    package's version and the compiled core's content (:func:`~linkage._cache_files.core_identity`),
    so a rebuilt core never reuses an atlas built by another.
    """
    k, arcs = _atlas_kind(kind)
    default = k.arc_entries if arcs else k.default_entries
    entries = default if entries is None else entries
    tag: list[Any] = [ATLAS_FORMAT, entries, harmonics, k.arcs if arcs else k.name]
    tag += [str(__version__), core_identity()]
    key = hashlib.sha256(json.dumps(tag).encode()).hexdigest()[:16]
    return entries, cache_dir() / f"atlas-{key}"


def _note_builds(missing: list[AtlasKind], bar: Bar | None) -> None:
    """Say on the progress bar which default atlases the search is about to build.

    A default atlas not yet in the cache folder is built once, a few seconds before the first
    fit (the arc atlas about 5 s on two cores): one line names them, so the wait is not silent.
    """
    if bar is not None and missing:
        what = " and the ".join(f"{n} atlas" for n in missing)
        bar.update(0, f"building the default {what} (once; cached in {cache_dir()})")


AtlasArg = Union[Atlas, str, "os.PathLike[str]", None]
"""An atlas as :func:`path` takes it: loaded, a folder written by :meth:`Atlas.save`, or None."""


# -- candidates -----------------------------------------------------------------------------


LinkageT = TypeVar("LinkageT", bound=Union[FourBar, SliderCrank])
"""The kind of linkage a :class:`Candidate` holds."""


@dataclass
class Candidate(Generic[LinkageT]):
    """One linkage found by :func:`path`, placed in the target's frame.

    ``linkage`` is a :class:`~linkage.FourBar` or (``kind == "slider-crank"``) a
    :class:`~linkage.SliderCrank`; both sweep (``.sweep``, ``.circuit``) and give a
    :class:`~linkage.Mechanism` (``.mechanism()``). ``error`` and ``rms`` are the largest and
    root-mean-square distance from the target points to the candidate's coupler curve (its
    circuit, traced whole), in the target's units;
    ``back`` the largest distance from the curve back to the target polygon (closed targets:
    the two together bound the Hausdorff distance; NaN for an open target, which matches a
    part of the circuit only). ``crank_range`` is the crank interval
    (radians, absolute) that traces the matched part; ``through_limit`` whether tracing it takes
    the crank through one of its limits (it must reverse there; never for a full-turn crank).
    ``grashof`` is the four-bar's Grashof class, or for a slider-crank ``"crank-slider"`` (the
    crank turns fully, ``|offset| + crank < coupler``) or ``"rocker-slider"`` (it rocks);
    ``min_transmission`` is the transmission angle's least distance from a toggle (a
    slider-crank's: the angle between the rod and the normal to the line) over the matched
    part, or over the whole turn when the crank turns fully (it is driven through all of it).
    ``source`` says where it came from: ``"equation"`` (a four-bar from the equation of the
    curve through the target points, refined), ``"atlas"`` (a match refined), ``"global"``
    (the global search) or
    ``"cognate"`` (a Roberts cognate of an exact fit, or one driven at its other pivot).
    """

    linkage: LinkageT
    error: float
    rms: float
    back: float
    crank_range: tuple[float, float]
    full_turn: bool
    grashof: str
    min_transmission: float
    through_limit: bool
    source: str
    params: NDArray[np.float64] = field(repr=False)
    kind: LinkageKind = "fourbar"

    @property
    def min_transmission_deg(self) -> float:
        """:attr:`min_transmission` in degrees."""
        return math.degrees(self.min_transmission)

    def __eq__(self, other: object) -> bool:
        """Whether ``other`` holds an equal linkage and the same figures (NaN equal to NaN).

        The dataclass's own comparison would say a copy differs (``back`` is NaN for an open
        target) or raise (``params`` is an array).
        """
        if not isinstance(other, Candidate):
            return NotImplemented
        for name in self.__dataclass_fields__:
            a, b = getattr(self, name), getattr(other, name)
            if isinstance(a, (str, FourBar, SliderCrank)) or isinstance(
                b, (str, FourBar, SliderCrank)
            ):
                if a != b:
                    return False
            elif np.shape(a) != np.shape(b) or not np.array_equal(a, b, equal_nan=True):
                return False
        return True

    __hash__ = None  # type: ignore[assignment]  # mutable, as the dataclass is


CONSTRAINT_NAMES = ("full_turn", "min_transmission", "lengths", "pivots")
""":func:`path`'s constraints, in the order :attr:`Candidates.removed` names them."""


class Candidates(list[Candidate[Any]]):
    """:func:`path`'s candidates, best first (a list), and what its constraints removed.

    ``removed`` maps each constraint of :data:`CONSTRAINT_NAMES` that removed a valid fit (one
    that assembles over its circuit on one branch) to the number of fits it removed (a fit
    failing two counts for each); ``closest_removed`` is the removed fit of least error, or
    None, and ``closest_fails`` the constraints it fails. When the list is empty, they say
    which constraint to loosen (:func:`why_none`).
    """

    removed: dict[str, int]
    closest_removed: Candidate[Any] | None
    closest_fails: tuple[str, ...]

    def __init__(
        self,
        found: Iterable[Candidate[Any]] = (),
        removed: dict[str, int] | None = None,
        closest_removed: Candidate[Any] | None = None,
        closest_fails: Sequence[str] = (),
    ) -> None:
        super().__init__(found)
        self.removed = {} if removed is None else removed
        self.closest_removed = closest_removed
        self.closest_fails = tuple(closest_fails)


# -- input ----------------------------------------------------------------------------------


def read_points(points: str | os.PathLike[str] | ArrayLike) -> Float2D:
    """Read target points as an ``(n, 2)`` float64 array, from an array-like or a CSV file.

    A CSV file has two numeric columns and an optional header line (a first line none of whose
    fields starts as a number does: ``x,y``, ``x (mm) y (mm)``). The numbers are separated
    by a comma, semicolon, tab or spaces; with semicolons or tabs, decimal commas are read too
    (``3,5;0,25``: a spreadsheet's export in a locale that writes them).

    Raises
    ------
    TypeError
        For a non-numeric array.
    LinkageError
        For a wrong shape, too few points, a non-finite value or an unreadable file.

    Examples
    --------
    >>> import linkage
    >>> linkage.synthesis.read_points([[0, 0], [1, 2]])
    array([[0., 0.],
           [1., 2.]])
    >>> linkage.synthesis.read_points([[0, 0], [1, float("nan")]])
    Traceback (most recent call last):
    ...
    linkage.LinkageError: points must be finite: points[1] is [1.0, nan]
    """
    if isinstance(points, (str, os.PathLike)):
        p = Path(points)
        rows: list[list[float]] = []
        for k, line in enumerate(_csv_text(p).splitlines(), 1):
            cells = [c for c in _SEPARATORS.split(line.strip()) if c]
            if not cells or cells[0].startswith("#"):
                continue
            if "," in line and (";" in line or "\t" in line):
                # A spreadsheet's export with decimal commas ("3,5;0,25"): with semicolons or
                # tabs between the numbers, a comma inside one can only be its decimal mark.
                decimal = [
                    c.replace(",", ".") for c in _DECIMAL_COMMA_SEPARATORS.split(line.strip())
                ]
                if len([c for c in decimal if c]) == 2:
                    cells = [c for c in decimal if c]
            try:
                row = [float(c) for c in cells]
            except ValueError:
                if k == 1 and not any(_NUMBER_LIKE.match(c) for c in cells):
                    continue  # a header line ("x,y"): a mistyped first point is an error
                raise LinkageError(
                    f"{p}:{k}: not two numbers (x, y; separated by a comma, semicolon, tab or "
                    f"spaces): {line.strip()!r}"
                ) from None
            if len(row) != 2:
                noun = "number" if len(row) == 1 else "numbers"
                raise LinkageError(f"{p}:{k}: {len(row)} {noun}, not two (x, y)")
            if not all(math.isfinite(v) for v in row):
                raise LinkageError(f"{p}:{k}: points must be finite, got {line.strip()!r}")
            rows.append(row)
        if not rows:
            raise LinkageError(f"{p}: no points in it (rows of two numbers x, y)")
        arr = np.array(rows, dtype=np.float64)
    else:
        arr = np.asarray(as_real_array(points, "points"), dtype=np.float64)
        if arr.ndim != 2 or arr.shape[1] != 2:
            raise LinkageError(f"points must have shape (n, 2), got {arr.shape}")
    if not np.all(np.isfinite(arr)):
        k = int(np.argwhere(~np.isfinite(arr))[0][0])
        raise LinkageError(f"points must be finite: points[{k}] is {arr[k].tolist()}")
    return np.ascontiguousarray(arr)


POINTS_FILE_MAX = 4 << 20
"""Largest target points file (4 MiB: :data:`~linkage.scene.POINTS_MAX` lines of two numbers
take about 0.4 MiB)."""

_SEPARATORS = re.compile(r"[,;\s]+")
"""What separates x from y in a points file: commas, semicolons, tabs or spaces."""

_DECIMAL_COMMA_SEPARATORS = re.compile(r"[;\s]+")
"""What separates x from y in a line with decimal commas: semicolons, tabs or spaces."""

_NUMBER_LIKE = re.compile(r"[+-]?\.?\d")
"""A cell that starts as a number does (``2.o``, ``1e``): a first line with one is a point, not a
header, and an error when it does not read."""


def _csv_text(p: Path) -> str:
    """Return the text of the points file ``p``.

    UTF-8 (a byte-order mark allowed) or UTF-16 with its byte-order mark (a spreadsheet's
    "Unicode text"), or without it, its byte order told by where the NUL bytes of the ASCII
    digits lie (:func:`_utf16_without_bom`).

    A folder, a device or pipe, a file over :data:`POINTS_FILE_MAX` and bytes that are no such
    text are :class:`LinkageError`.
    """
    try:
        info = p.stat()
    except OSError as e:
        raise LinkageError(f"cannot read {p}: {e.strerror or e}") from None
    if p.is_dir():
        raise LinkageError(f"{p} is a folder, not a CSV file of x, y")
    if not p.is_file():  # a device or a pipe: it may never end
        raise LinkageError(f"{p} is not a regular file, not a CSV file of x, y")
    if info.st_size > POINTS_FILE_MAX:
        raise LinkageError(
            f"{p} is {info.st_size} bytes, more than the {POINTS_FILE_MAX >> 20} MiB a points file "
            f"may hold (path synthesis takes at most {POINTS_MAX} points): thin the points"
        )
    try:
        data = p.read_bytes()
    except OSError as e:
        raise LinkageError(f"cannot read {p}: {e.strerror or e}") from None
    if data.startswith((b"\xff\xfe", b"\xfe\xff")):
        encoding = "utf-16"
    elif data.startswith(b"\xef\xbb\xbf"):
        encoding = "utf-8-sig"
    else:
        encoding = _utf16_without_bom(data) or "utf-8"
    try:
        return data.decode(encoding)
    except UnicodeDecodeError as exc:
        if encoding in ("utf-16-le", "utf-16-be"):
            raise LinkageError(
                f"{p}: looks like UTF-16 without a byte-order mark (NUL bytes every other byte), "
                f"but is not {encoding.upper()} text (bytes at offset {exc.start}): save it as "
                "UTF-8"
            ) from None
        raise LinkageError(
            f"{p}: not UTF-8 text, nor UTF-16 with a byte-order mark "
            f"(byte 0x{data[exc.start]:02x} at offset {exc.start})"
        ) from None


def _utf16_without_bom(data: bytes) -> str | None:
    """Return ``"utf-16-le"`` or ``"utf-16-be"`` for such text without its byte-order mark.

    Digits, separators and line ends are ASCII: in UTF-16 every other byte of them is NUL, the
    odd ones in little-endian, the even ones in big-endian. Text that UTF-8 reads has no NUL, and
    a points file has none either; ``None`` when the NULs are not so.
    """
    if len(data) < 2 or len(data) % 2 or b"\x00" not in data:
        return None
    even, odd = data[0::2], data[1::2]
    # Most of one half NUL, little of the other: a few non-ASCII characters (a header's "µm")
    # leave NUL out of their high byte.
    if odd.count(0) >= 0.9 * len(odd) and even.count(0) <= 0.1 * len(even):
        return "utf-16-le"
    if even.count(0) >= 0.9 * len(even) and odd.count(0) <= 0.1 * len(odd):
        return "utf-16-be"
    return None


def clean_target(points: Float2D, closed: bool) -> Float2D:
    """Drop repeated consecutive points (and a closing repeat of the first), and check the rest.

    There must be enough points, and a closed target must enclose something. The one cleaning
    of a target, for :func:`path` and for ``[synthesis]`` scenes.

    Raises
    ------
    LinkageError
        For fewer than :data:`MIN_POINTS` distinct points, points that all coincide, a point far
        out of the others' scale (half of them within :data:`EXACT` of its distance from their
        median point), or a closed target whose points are all collinear.

    Examples
    --------
    >>> import numpy as np
    >>> import linkage
    >>> pts = np.array([[0, 0], [1, 0], [1, 0], [1, 1], [0, 1], [0.5, 2], [0, 0.0]])
    >>> linkage.synthesis.clean_target(pts, True)
    array([[0. , 0. ],
           [1. , 0. ],
           [1. , 1. ],
           [0. , 1. ],
           [0.5, 2. ]])
    >>> linkage.synthesis.clean_target(np.c_[np.arange(6.0), np.arange(6.0)], True)
    Traceback (most recent call last):
    ...
    linkage.LinkageError: the points are all collinear: ... (an open path: closed = false)
    """
    keep = np.ones(len(points), dtype=bool)
    keep[1:] = np.any(points[1:] != points[:-1], axis=1)
    pts = points[keep]
    if closed and len(pts) > 1 and np.array_equal(pts[0], pts[-1]):
        pts = pts[:-1]
    # Distinct anywhere, not only from their neighbours: 18 points cycling through 3 positions
    # had passed (and been "fitted exactly"; found by a new-user trial).
    distinct = len(np.unique(pts, axis=0))
    if distinct < MIN_POINTS:
        also = f" ({len(pts)} points repeating them)" if len(pts) > distinct else ""
        raise LinkageError(
            f"path synthesis needs at least {MIN_POINTS} distinct points, got {distinct}{also}"
        )
    # Measured in units of a power of two near the largest coordinate: no sum overflows.
    m = float(np.max(np.abs(pts)))
    unit = _pow2(m) if m > 0 and math.isfinite(m) else 1.0
    q = pts / unit
    # A point far out of the others' scale (1e300 among points within 1): the rest lie within
    # what a fit counted exact (EXACT of the size) may miss them by, or below float64's
    # resolution at that scale, and "collinear" (they are, to 1e-300) would name the wrong cause.
    reach = np.hypot(*(q - np.median(q, axis=0)).T)
    far = int(np.argmax(reach))
    if np.median(reach) < EXACT * reach[far]:
        row = int(np.flatnonzero(np.all(points == pts[far], axis=1))[0])
        raise LinkageError(
            f"points[{row}] = {pts[far].tolist()} is far out of the scale of the others (half "
            f"of them lie within {float(np.median(reach)) * unit:.3g} of their median point): "
            "float64 cannot fit a curve to both scales; a mistyped point?"
        )
    sv = np.linalg.svd(q - q.mean(axis=0), compute_uv=False)
    if sv[0] == 0:
        raise LinkageError("the points all coincide")
    extent = float(np.max(np.ptp(q, axis=0))) * unit
    if extent < SMALLEST_EXTENT:
        # Its linkage's links would be subnormal floats (too few bits for the solver): the
        # constructors refuse them, and the message would have named a link the user never gave.
        raise LinkageError(
            f"the points span {extent:.3g}, below the {SMALLEST_EXTENT:.3g} a target may span "
            "(its linkage's lengths would be subnormal floats): scale the points up"
        )
    if closed and sv[1] <= 1e-12 * sv[0]:
        raise LinkageError(
            "the points are all collinear: a closed curve through them encloses nothing "
            "(an open path: closed = false)"
        )
    return np.ascontiguousarray(pts)


SMALLEST_EXTENT = 2.0**-1000
"""The smallest span (largest coordinate range) of a target, about 9.3e-302: 2²² (4·10⁶) times
the smallest normal float64 (2.2e-308), so that the links of its linkages, down to about 1e-6 of
its span, are normal floats."""


def rounded_to(x: float, size: float, digits: int) -> float:
    """Return ``x`` rounded to ``10**-digits`` of ``size`` (a power of ten), never ``-0.0``.

    Coordinates and lengths of a fitted linkage are printed so: the round-off of an exact fit
    (a pivot at 4.9e-7 on a 34 mm curve) reads 0, while ``digits`` places of the size remain.

    >>> from linkage.synthesis import rounded_to
    >>> rounded_to(4.8993e-7, 34.0, 6), rounded_to(-1e-9, 34.0, 5), rounded_to(12.3456789, 34.0, 5)
    (0.0, 0.0, 12.3457)
    """
    quantum = 10.0 ** (math.floor(math.log10(size)) - digits)
    return round(float(x) / quantum) * quantum + 0.0


def _target(points: str | os.PathLike[str] | ArrayLike, closed: bool) -> Float2D:
    """Read and clean a target (:func:`read_points`, :func:`clean_target`).

    A file's problems, those of its points too, are named after the file.
    """
    try:
        target = clean_target(read_points(points), closed)
        if len(target) > POINTS_MAX:
            raise LinkageError(
                f"path synthesis takes at most {POINTS_MAX} points, got {len(target)}: thin them"
            )
        return target
    except LinkageError as exc:
        if isinstance(points, (str, os.PathLike)) and not str(exc).startswith(str(points)):
            raise LinkageError(f"{points}: {exc}") from None
        raise


def target_size(points: Float2D) -> float:
    """Return the size of a target: the RMS distance of its points from their centroid.

    Errors of candidates are reported against it.

    >>> import numpy as np
    >>> import linkage
    >>> linkage.synthesis.target_size(np.array([[1.0, 0], [-1, 0], [0, 1], [0, -1]]))
    1.0
    """
    p = np.asarray(points, dtype=np.float64)
    if p.ndim != 2 or p.shape[1:] != (2,):
        raise LinkageError(f"target_size takes points of shape (n, 2), got shape {p.shape}")
    bad = ~np.isfinite(p).all(axis=1)
    if bad.any():
        k = int(np.argmax(bad))
        raise LinkageError(f"target_size takes finite points, got {p[k].tolist()} at row {k}")
    # In units of a power of two near the largest offset: no square overflows or underflows.
    return rms_size(p)


# -- the search -----------------------------------------------------------------------------


def _placed(
    entry: NDArray[np.float64],
    frame_t: NDArray[np.float64],
    frame_c: NDArray[np.float64],
    flip: bool,
    kind: _Kind = FOURBAR,
) -> NDArray[np.float64]:
    """Move an atlas entry's linkage by the similarity taking its curve's frame onto the target's.

    The frames are the curves' normalisation frames; ``flip`` takes the other end of the major axis
    (``linkage_core::place_entry``, ``place_slider_entry``).
    """
    place = _core.synth_place if kind is FOURBAR else _core.synth_slider_place
    return place(
        np.ascontiguousarray(entry, dtype=np.float64),
        np.ascontiguousarray(frame_c, dtype=np.float64),
        np.ascontiguousarray(frame_t, dtype=np.float64),
        flip,
    )


def _errors(
    params: Float2D,
    crossed: NDArray[np.bool_],
    target: Float2D,
    closed: bool,
    *,
    samples: int = 256,
    exact: bool = False,
    threads: int = 1,
    kind: _Kind = FOURBAR,
) -> tuple[Float2D, Float2D]:
    p = np.ascontiguousarray(params, dtype=np.float64)
    if kind is SLIDER:
        return _core.synth_slider_errors(
            p, target, samples=samples, exact=exact, closed=closed, threads=threads
        )
    return _core.synth_errors(
        p,
        np.ascontiguousarray(crossed, dtype=bool),
        target,
        samples=samples,
        exact=exact,
        closed=closed,
        threads=threads,
    )


def _residuals(
    kind: _Kind, params: Float2D, crossed: NDArray[np.bool_], target: Float2D, s: Float2D
) -> NDArray[np.float64]:
    """``P_i(s_ij) − target_j`` of placed linkages of ``kind`` (``(M, n, 2)``, NaN unassembled)."""
    p = np.ascontiguousarray(params, dtype=np.float64)
    s = np.ascontiguousarray(s, dtype=np.float64)
    if kind is SLIDER:
        return _core.synth_slider_residuals(p, target, s)
    return _core.synth_residuals(p, np.ascontiguousarray(crossed, dtype=bool), target, s)


def _refine(
    x0: NDArray[np.float64],
    crossed: bool,
    target: Float2D,
    s0: NDArray[np.float64],
    size: float,
    bounds: tuple[NDArray[np.float64], NDArray[np.float64]],
    max_nfev: int,
    kind: _Kind = FOURBAR,
    geodesic: bool = False,
    budget: _Budget | None = None,
) -> NDArray[np.float64]:
    """Fit the true point-to-curve distance by least squares.

    The unknowns are the placed parameters (nine of a four-bar, eight of a slider-crank) and
    each target point's circuit parameter, the residuals ``P(s_i) − t_i`` evaluated in Rust.
    ``geodesic`` (the long fits of open targets) starts with :func:`_geodesic_lm` where only the
    lengths' positivity bounds the fit, then finishes with MINPACK's Levenberg-Marquardt.
    Every residual evaluation is charged to ``budget`` (when given).
    """
    # scipy.optimize costs ~0.3 s to import: only when a fit runs.
    from scipy.optimize import least_squares  # type: ignore[import-untyped]  # noqa: PLC0415

    n = len(target)
    q = kind.params
    penalty = 10.0 * size
    # Length steps scale with the target; an angle's (the slider's line) is in radians. The
    # long fits take fourth-order differences (see jac) at steps near ε^(1/5).
    h = 3e-4 if geodesic else 1e-6
    steps = np.full(q + 1, h * size)
    steps[[*kind.angles, q]] = h

    def batch(rows: NDArray[np.float64]) -> NDArray[np.float64]:
        m = len(rows)
        if budget is not None:
            budget.spent += m
        r = _residuals(kind, rows[:, :q], np.full(m, crossed), target, rows[:, q:]).reshape(m, -1)
        out: NDArray[np.float64] = np.where(np.isfinite(r), r, penalty)
        return out

    def fun(x: NDArray[np.float64]) -> NDArray[np.float64]:
        out: NDArray[np.float64] = batch(x[None, :])[0]
        return out

    def jac(x: NDArray[np.float64]) -> NDArray[np.float64]:
        # Central differences of all q + 1 directions (the q parameters, then every s at once:
        # s_i moves residual i only) in one batched call. The long fits take the fourth-order
        # stencil (8(r(x+h) − r(x−h)) − (r(x+2h) − r(x−2h)))/12h, error O(h⁴) + O(ε/h), about
        # 1e-12 of the Jacobian's scale at h = 3e-4, where the central O(h²) + O(ε/h) at
        # h = 1e-6 is about 2e-10: the long fits' scaled Jacobians span singular values of
        # 10⁷ … 10⁹, and the directions along the valley are the small ones. Two arcs of
        # `bench/open_arcs.py --seed 2` are recovered only so (docs/synthesis.md); the first
        # fits keep the central differences (half the evaluations a Jacobian).
        d = np.zeros((q + 1, q + n))
        d[np.arange(q), np.arange(q)] = steps[:q]
        d[q, q:] = steps[q]
        m = q + 1
        if geodesic:
            r = batch(np.concatenate([x + d, x - d, x + 2 * d, x - 2 * d]))
            g = (8 * (r[:m] - r[m : 2 * m]) - (r[2 * m : 3 * m] - r[3 * m :])) / (
                12 * steps[:, None]
            )
        else:
            r = batch(np.concatenate([x + d, x - d]))
            g = (r[:m] - r[m:]) / (2 * steps[:, None])
        j = np.zeros((2 * n, q + n))
        j[:, :q] = g[:q].T
        rows = np.arange(n)
        j[2 * rows, q + rows] = g[q, 0::2]
        j[2 * rows + 1, q + rows] = g[q, 1::2]
        return j

    lo = np.concatenate([bounds[0], np.full(n, -np.inf)])
    hi = np.concatenate([bounds[1], np.full(n, np.inf)])
    x = np.concatenate([np.clip(x0, bounds[0] + 1e-12 * size, bounds[1] - 1e-12 * size), s0])
    # MINPACK's Levenberg-Marquardt when only the lengths' positivity bounds the fit (a
    # non-positive length gives the penalty residual); the bounded trust region with an
    # iterative solver otherwise. Neither calls a multithreaded LAPACK factorisation, which
    # oversubscribed a shared machine's cores by 50x in a measured run.
    common: dict[str, Any] = dict(
        jac=jac, x_scale="jac", ftol=1e-15, xtol=1e-15, gtol=1e-15, max_nfev=max_nfev
    )
    # A parameter bounded on both sides (by `lengths` or `pivots`) is x = lo + w(1 + sin u)/2
    # in an unbounded u (w = hi − lo), so MINPACK fits it too (the bounded trust region's
    # iterative solver had taken 7-10x as long: 150 s where 20 s was measured, #12). Every
    # other parameter is free but for the lengths' positivity (the penalty residual).
    two = np.flatnonzero(np.isfinite(lo[:q]) & np.isfinite(hi[:q]))
    one = [i for i in range(q) if i not in two]
    positive = [i for i in one if i in kind.lengths]
    free = [i for i in one if i not in kind.lengths]
    # MINPACK needs a residual per unknown (2n ≥ q + n): fewer than q points (a short arc of
    # 5 … 8) leave the fit underdetermined, which only the trust region solves (MINPACK's
    # refusal had left such targets unrefined, at 1e-2 of their size).
    if (
        n >= q
        and np.all(np.isinf(lo[free]))
        and np.all(np.isinf(hi[one]))
        and np.all(lo[positive] < 1e-6 * size)
    ):
        if len(two):
            base, w = lo[two], hi[two] - lo[two]
            # Starts a thousandth of the range inside: at a bound, u's column is zero.
            inner = np.clip(x[two], base + 1e-3 * w, base + (1 - 1e-3) * w)
            x[two] = np.arcsin(2 * (inner - base) / w - 1)
            fun_x, jac_x = fun, jac

            def placed(u: NDArray[np.float64]) -> NDArray[np.float64]:
                v = u.copy()
                v[two] = np.clip(base + w * (1 + np.sin(u[two])) / 2, lo[two], hi[two])
                return v

            def fun(x: NDArray[np.float64]) -> NDArray[np.float64]:
                return fun_x(placed(x))

            def jac(x: NDArray[np.float64]) -> NDArray[np.float64]:
                j = jac_x(placed(x))
                j[:, two] *= w * np.cos(x[two]) / 2
                return j

        if geodesic:
            # Geodesic steps down the valley, then MINPACK's (a fifth as many evaluations more)
            # for the last digits, which its convergence near the answer gives sooner.
            x = _geodesic_lm(fun, jac, x, max_nfev, q)
            common["max_nfev"] = max_nfev // 5

        # SciPy's C MINPACK (1.15 on) reads one element past its copy of the Jacobian when it
        # recomputes the norm of the last column of its pivoted QR: what lies there changes
        # from call to call, and with it a few fits, so one search returned other candidates
        # run to run (valgrind: "Invalid read of size 8 … 0 bytes after a block" in qrfac). So
        # a last unknown y joins, with one residual GUARD·y of its own: its column, the
        # smallest that is not zero, is pivoted after every other but zero ones, no other
        # column's reflection touches it, so its norm is never recomputed (nor is a zero
        # column's), and nothing past the Jacobian is read. The fit keeps full rank and its
        # steps (a column of zeros instead had cost the last digits: 4e-10 of the size where
        # 3e-14 had been reached).
        def fun_g(y: NDArray[np.float64]) -> NDArray[np.float64]:
            return np.append(fun(y[:-1]), GUARD * y[-1])

        def jac_g(y: NDArray[np.float64]) -> NDArray[np.float64]:
            j = jac(y[:-1])
            out = np.zeros((j.shape[0] + 1, j.shape[1] + 1))
            out[:-1, :-1] = j
            out[-1, -1] = GUARD
            return out

        common["jac"] = jac_g
        res = least_squares(fun_g, np.append(x, 0.0), method="lm", **common)
        if len(two):
            res.x[two] = np.clip(base + w * (1 + np.sin(res.x[two])) / 2, lo[two], hi[two])
    else:
        res = least_squares(fun, x, bounds=(lo, hi), method="trf", tr_solver="lsmr", **common)
    out: NDArray[np.float64] = res.x[:q]
    return out


SHORTEST_LINK = 1e-6
"""The shortest link a candidate may have, in target sizes (:data:`EXACT`: a link shorter
than the error a fit is exact to is no link)."""

GUARD = 1e-100
"""The weight of the guard unknown that keeps SciPy's MINPACK inside its Jacobian (:func:`_refine`):
far below any column of a fit's Jacobian, far above the smallest normal number when squared."""


STALL_WINDOW = 100
"""Evaluations over which a long fit (:func:`_geodesic_lm`) must lower its sum of squares by
:data:`STALL`, or stop."""

STALL = 1e-3
"""Least relative decrease of a long fit's sum of squares over :data:`STALL_WINDOW` evaluations.
A fit crawling down a valley to an exact linkage lowers it by far more: random#6 of
``bench/open_arcs.py`` from 1.4e-5 to 1.6e-6 of the size in 1,500 evaluations, a factor of 76
in the sum, 1.3 a window on average."""


def _geodesic_lm(
    fun: Callable[[NDArray[np.float64]], NDArray[np.float64]],
    jac: Callable[[NDArray[np.float64]], NDArray[np.float64]],
    x0: NDArray[np.float64],
    max_nfev: int,
    dense: int | None = None,
) -> NDArray[np.float64]:
    """Minimise ``|fun(x)|²`` by Levenberg-Marquardt with geodesic acceleration.

    Transtrum and Sethna, "Improvements to the Levenberg-Marquardt algorithm for nonlinear
    least-squares minimization" (arXiv:1201.5885, 2012), section 3. In variables scaled by
    ``D = diag(max over iterations of |J_k|²)^½`` (MINPACK's scaling), each iteration solves
    ``(JᵀJ + λD²) v = −Jᵀr`` for the velocity, estimates the second directional derivative
    ``r_vv ≈ (2/h)((r(x + hv) − r(x))/h − Jv)`` (``h = 0.1``), solves
    ``(JᵀJ + λD²) a = −Jᵀr_vv`` for the acceleration and tries ``x + v + a/2`` when
    ``|Da| ≤ 0.75 |Dv|``; both solves by one QR factorisation of ``[J D⁻¹; √λ I]``
    (:func:`_damped_solver`: of its first ``dense`` columns, those of ``J`` that are dense, and
    a reflection of each point's rows; ``None``: all). An accepted
    step divides ``λ`` by 3, a rejected one multiplies it by ``ν`` (2, doubling while rejections
    go on; Nielsen's rule). It stops after ``max_nfev`` evaluations of ``fun`` (two an
    iteration), when a step is below 1e-15 of ``|Dx|``, when ``λ`` reaches 1e30 (no step
    lowers the sum: a minimum to rounding), or when :data:`STALL_WINDOW` evaluations lowered the
    sum by less than the fraction :data:`STALL` of it (a fit of points no linkage draws creeps
    on by hairs: 36 long fits of 1,500 evaluations had taken 48 s of a 75 s search of 100 random
    points, #29).

    The acceleration bends each step along the curved, narrow valley of near-fits that a
    short arc's fit follows (the scaled Jacobian's singular values span 10⁷ … 10⁹), where
    MINPACK's straight steps crawl: from a long fit's start on 0.18 of a triple-rocker's
    circuit (1.4e-5 of the size), one round of MINPACK ended at 2.1e-5 after 5,000
    evaluations, this at 1.6e-6 after 1,500 (docs/synthesis.md).
    """
    x = np.array(x0, dtype=np.float64)
    r = fun(x)
    cost = float(r @ r)
    j = jac(x)
    nfev, m = 1, len(x)
    d2 = np.zeros(m)
    lam, nu = 1e-3, 2.0
    # The sum of squares at the start of the current window of STALL_WINDOW evaluations.
    mark_nfev, mark_cost = nfev, cost
    while nfev < max_nfev:
        if nfev - mark_nfev >= STALL_WINDOW:
            if cost > (1.0 - STALL) * mark_cost:
                break  # stalled: a window of evaluations lowered the sum by less than STALL
            mark_nfev, mark_cost = nfev, cost
        d2 = np.maximum(d2, np.sum(j * j, axis=0))
        d = np.sqrt(np.maximum(d2, 1e-300))
        solve = _damped_solver(j / d, lam, m if dense is None else dense)
        vy = solve(r)
        v = vy / d
        r_h = fun(x + 0.1 * v)
        nfev += 1
        ay = solve((2.0 / 0.1) * ((r_h - r) / 0.1 - j @ v))
        new_cost = math.inf
        if np.linalg.norm(ay) <= 0.75 * np.linalg.norm(vy):
            x_new = x + v + 0.5 * ay / d
            r_new = fun(x_new)
            nfev += 1
            new_cost = float(r_new @ r_new)
        if new_cost < cost:
            x, r, cost = x_new, r_new, new_cost
            j = jac(x)
            lam, nu = max(lam / 3.0, 1e-30), 2.0
            if np.linalg.norm(vy) < 1e-15 * (np.linalg.norm(d * x) + 1e-15):
                break
        else:
            lam, nu = min(lam * nu, 1e30), min(2.0 * nu, 1e3)
            if lam >= 1e30:
                break
    return x


def _damped_solver(
    js: NDArray[np.float64], lam: float, q: int
) -> Callable[[NDArray[np.float64]], NDArray[np.float64]]:
    """Return the solver of ``min |[J; √λ I] y + [b; 0]|`` for right-hand sides ``b``.

    ``J`` (``js``, ``2n × (q + n)``) is a fit's scaled Jacobian: ``q`` dense columns, then one
    column per target point ``i`` whose only entries are in rows ``2i`` and ``2i + 1`` (its
    circuit parameter moves its residual alone). A Householder reflection of each point's three
    rows (its two, and its damping row ``√λ`` in column ``q + i``) leaves that column one entry
    (Golub and Van Loan, *Matrix Computations*, 4th ed., 5.1.2), and a QR of the remaining
    ``(2n + q) × q`` rows solves the dense part, then each point's parameter by substitution:
    orthogonal steps, as a QR of the whole ``(3n + q) × (q + n)`` matrix, in ``O(n q²)`` where
    that takes ``O(n³)`` (the whole QR of 100 points took 2-13 ms, most of a long fit, and
    more threads than a loaded machine had, #29).
    """
    n = js.shape[1] - q
    root = math.sqrt(lam)
    if n == 0:
        # Every column dense: one QR of the (2n + m) × m matrix.
        q0, r0 = np.linalg.qr(np.vstack([js, root * np.eye(q)]))
        qt0 = q0[: len(js)].T

        def solve_dense(b: NDArray[np.float64]) -> NDArray[np.float64]:
            out: NDArray[np.float64] = np.linalg.solve(r0, -(qt0 @ b))
            return out

        return solve_dense
    a = js[:, :q]
    w = np.column_stack(
        [
            js[2 * np.arange(n), q + np.arange(n)],
            js[2 * np.arange(n) + 1, q + np.arange(n)],
            np.full(n, root),
        ]
    )
    sigma = np.linalg.norm(w, axis=1)
    alpha = -np.copysign(sigma, w[:, 0])  # H w = alpha e₁, no cancellation in u₀
    u = w.copy()
    u[:, 0] -= alpha
    beta = 2.0 / np.einsum("ij,ij->i", u, u)  # u ≠ 0: |u₀| ≥ σ ≥ √λ > 0

    def reflect(rows: NDArray[np.float64]) -> NDArray[np.float64]:
        """Apply each point's reflection to its three rows (``(n, 3, ...)``)."""
        c = beta.reshape((n,) + (1,) * (rows.ndim - 2)) * np.einsum("ij,ij...->i...", u, rows)
        out: NDArray[np.float64] = rows - u.reshape(u.shape + (1,) * (rows.ndim - 2)) * c[:, None]
        return out

    blocks = np.zeros((n, 3, q))
    blocks[:, 0], blocks[:, 1] = a[0::2], a[1::2]
    hb = reflect(blocks)
    pivot = hb[:, 0]
    qq, rr = np.linalg.qr(np.vstack([hb[:, 1:].reshape(2 * n, q), root * np.eye(q)]))
    qt = qq[: 2 * n].T

    def solve(b: NDArray[np.float64]) -> NDArray[np.float64]:
        rows = np.zeros((n, 3))
        rows[:, 0], rows[:, 1] = b[0::2], b[1::2]
        hr = reflect(rows)
        yp = np.linalg.solve(rr, -(qt @ hr[:, 1:].reshape(2 * n)))
        ys = -(hr[:, 0] + pivot @ yp) / alpha
        return np.concatenate([yp, ys])

    return solve


def _arc(feet: NDArray[np.float64], closed: bool) -> tuple[float, float]:
    """Return the circuit-parameter arc that holds every foot.

    The whole circuit for a closed target, else the complement of the largest gap between feet
    (``linkage_core::covering_arc``).
    """
    if closed:
        return (0.0, 2 * math.pi)
    arc = _core.synth_arc(np.ascontiguousarray(feet, dtype=np.float64))
    return arc if arc is not None else (math.nan, math.nan)


def _de(
    target: Float2D,
    closed: bool,
    size: float,
    centre: NDArray[np.float64],
    seed: int,
    maxiter: int,
    threads: int,
    bar: Any,
    keep: int = 4,
    kind: _Kind = FOURBAR,
    full_turn: bool = False,
    min_transmission: float = 0.0,
) -> list[tuple[NDArray[np.float64], bool]]:
    """Search by differential evolution over placed linkages (a four-bar's both assemblies).

    The population is evaluated in one batch call per generation. A four-bar's shape
    constraints add their shortfall to the cost (:func:`_shortfall`), so the search heads for
    linkages they admit.
    """
    from scipy.optimize import differential_evolution  # noqa: PLC0415 (as above)

    span = 3.0 * size
    pivot = [(centre[0] - span, centre[0] + span), (centre[1] - span, centre[1] + span)]
    if kind is SLIDER:
        # Crank pivot, line direction and offset, crank, rod, coupler point.
        box = [*pivot, (-math.pi, math.pi), (-span, span), (0.05 * size, 4 * size)]
        box += [(0.05 * size, 6 * size), (-span, span), (-span, span)]
    else:
        box = [*pivot, *pivot, (0.05 * size, 4 * size), (0.05 * size, 6 * size)]
        box += [(0.05 * size, 6 * size), (-span, span), (-span, span)]
    found = []
    for crossed in (False, True) if kind is FOURBAR else (False,):

        def cost(pop: NDArray[np.float64], crossed: bool = crossed) -> NDArray[np.float64]:
            params = np.ascontiguousarray(pop.T)
            e, _ = _errors(
                params,
                np.full(len(params), crossed),
                target,
                closed,
                samples=128,
                threads=threads,
                kind=kind,
            )
            f = np.maximum(e[:, 0], e[:, 2]) if closed else e[:, 0]
            if kind is FOURBAR and (full_turn or min_transmission > 0):
                f = f + size * _shortfall(params, size, full_turn, min_transmission, closed)
            return np.where(np.isfinite(f), f, 100.0 * size)

        def step(*_: Any, **__: Any) -> bool:
            if bar is not None:
                bar.update(1)
            return False

        r = differential_evolution(
            cost,
            box,
            popsize=15,
            maxiter=maxiter,
            tol=1e-12,
            seed=seed + int(crossed),
            vectorized=True,
            updating="deferred",
            polish=False,
            callback=step,
        )
        # The best few distinct members of the last generation, for least squares to finish.
        order = np.argsort(r.population_energies, kind="stable")
        for i in order[:keep]:
            found.append((np.asarray(r.population[i], dtype=np.float64), crossed))
    return found


def _shortfall(
    params: NDArray[np.float64],
    size: float,
    full_turn: bool,
    min_transmission: float,
    closed: bool,
) -> NDArray[np.float64]:
    """Return how far each placed four-bar (rows of ``params``) is from its shape constraints.

    A crank that does not turn fully (if ``full_turn``): the lengths by which the base
    ``|C − A|``, over ``[|g − r|, g + r]``, leaves the dyad's ``[|b − c|, b + c]``, over
    ``size``. The transmission angle (a closed target, whose matched part is the whole
    circuit): ``min_transmission`` less its least distance from a toggle, in radians — reached
    at the base's extremes when the crank turns fully, zero (a toggle) when it rocks.
    """
    g = np.hypot(params[:, 2] - params[:, 0], params[:, 3] - params[:, 1])
    r, b, c = params[:, 4], params[:, 5], params[:, 6]
    lo, hi = np.abs(g - r), g + r
    out = np.zeros(len(params))
    turns = (lo >= np.abs(b - c)) & (hi <= b + c)
    if full_turn:
        out += (np.maximum(0.0, np.abs(b - c) - lo) + np.maximum(0.0, hi - (b + c))) / size
    if closed and min_transmission > 0:
        with np.errstate(invalid="ignore", divide="ignore"):
            mu_lo = np.arccos(np.clip((b * b + c * c - lo * lo) / (2 * b * c), -1.0, 1.0))
            mu_hi = np.arccos(np.clip((b * b + c * c - hi * hi) / (2 * b * c), -1.0, 1.0))
        least = np.where(turns, np.minimum(mu_lo, math.pi - mu_hi), 0.0)
        out += np.maximum(0.0, min_transmission - np.nan_to_num(least))
    return out


def path(
    points: str | os.PathLike[str] | ArrayLike,
    closed: bool = True,
    top: int = 5,
    *,
    kind: PathKind = "fourbar",
    atlas: AtlasArg | Sequence[AtlasArg] = None,
    refine: int = 8,
    global_search: bool | None = None,
    full_turn: bool = False,
    min_transmission: float = 0.0,
    lengths: tuple[float, float] | None = None,
    pivots: tuple[tuple[float, float], tuple[float, float]] | None = None,
    max_link: float | None = LONG_LINK,
    tol: float = 1e-3,
    maxiter: int = 150,
    seed: int = 0,
    threads: int | None = None,
    progress: bool = False,
    accept: float | None = None,
) -> Candidates:
    """Four-bars (or slider-cranks) whose coupler curve passes through ``points``, best first.

    A four-bar search of 16 points or more (:data:`CURVE_EQUATION_POINTS`) starts from the
    equation of the curve through them: its foci are the pivots of the cognates that draw it,
    and its lengths follow from one linear solve (``linkage_core::fourbars_from_curve``). On a
    curve a four-bar draws, closed or an arc that singles the curve out (given to about 8–9
    significant digits), those four-bars, refined, are exact (``source == "equation"``,
    unless the atlas or the cognates found the same linkage: exact fits tie, and each is
    listed once); the atlas matches, refined, and the later stages search on as described
    below and in ``docs/synthesis.md``. A slider-crank search of 13 points or more
    (:data:`SLIDER_EQUATION_POINTS`) starts likewise from the circular quartic through them,
    whose one focus is the crank pivot (``linkage_core::slider_cranks_from_curve``).

    Parameters
    ----------
    points : (n, 2) array_like or path of a CSV file
        Target points in order along the curve, any position, orientation and scale.
    closed : bool
        Whether the points go round a closed curve (else: a part of one, matched anywhere on a
        candidate's circuit).
    top : int
        Most candidates returned.
    kind : {"fourbar", "slider-crank", "any"}
        The linkage sought: a four-bar, an offset slider-crank (crank, rod, slider on a line at
        any angle and offset, coupler point rigid with the rod), or either (both searched, one
        ranking).
    atlas : Atlas, folder, None, or a sequence of them
        The atlas of each kind searched (default: :func:`default_atlas` of that kind); for
        ``kind="any"`` a sequence may give one of each. Open targets search an atlas of open
        arcs, ``kind="fourbar-arcs"`` or ``"slider-crank-arcs"`` (default: the
        :func:`default_atlas` of that kind), which the sequence may give too.
    refine : int
        Atlas matches refined by least squares (of each kind; at most 200): a closed target's
        ``max(refine, top)``, an open target's ``3 × refine`` first fits. The search's time, and
        how good its best candidate can be, grow with it (and so with ``top``).
    global_search : bool or None
        Run differential evolution; ``None``: when no atlas candidate of any kind searched is
        within ``tol`` of the target's size.
    full_turn, min_transmission, lengths, pivots
        Constraints: a crank that turns fully, a transmission angle at least this far from a
        toggle (radians) over the matched part (over the whole turn for a crank that turns
        fully: the motor drives it all), every link length within ``lengths`` (a
        slider-crank's crank and rod) and both sides of the coupler triangle to the point at most
        its greatest, both ground pivots (a slider-crank's crank pivot) inside
        the box ``pivots = ((xmin, ymin), (xmax, ymax))``.
    accept : float or None
        A largest error (target units) that is good enough: the later stages — an open
        target's long fits and further matches, and the global search when ``global_search``
        is None — run only while no admissible candidate is within it (default: they run
        until one is exact, :data:`EXACT` of the size, and the global search while none is
        within ``tol``; an open target's best exact fit above :data:`TIGHT` of the size then
        gets one long fit more). The stages skipped would have found more candidates too: the
        list may hold fewer than ``top``.
    max_link : float or None
        Candidates with a link (or coupler-triangle side) longer than ``max_link`` times the
        target's size (:func:`target_size`) are ranked after every other, whatever their error:
        a fit that runs a link off towards infinity (a coupler of 64,000 for a curve of size 9)
        can beat every buildable one by a hair. They are not removed: they fill the list when
        fewer than ``top`` others are found, and ``max_link=None`` ranks by error alone. Ignored
        when ``lengths`` is given (that bound filters instead).

    Returns
    -------
    Candidates
        A list of :class:`Candidate`; when the constraints removed fits, its ``removed``
        counts them by constraint and ``closest_removed`` is the best of them
        (:func:`why_none` words why a list is empty). At most ``top``, ranked by ``error``
        then ``rms`` (after ``max_link``), except that errors within the refinement's own
        accuracy tie: every fit to within :data:`EXACT` (1e-6) of the target's size counts
        as exact (the long fits of short arcs end some fits of the exact curve at 2e-7 …
        8e-7 of the size, where well-conditioned fits reach 1e-13), and among exact fits a
        crank that turns fully comes first, then the transmission angle farthest from a
        toggle over the matched part (so a buildable linkage is not put after a rocker that
        passes within 0.1° of a toggle by a difference of error nobody can see), then the
        error. The candidates draw different curves: two candidates whose matched parts lie
        within ``max(1e-6·size, error/20)`` of each other both ways are one design and only
        the better is kept, so mirror images of a symmetric curve, the same linkage driven
        from its other pivot, and fits that differ only by a link drifting to a toggle
        appear once. Roberts cognates are the exception: they draw the same curve with
        different links and pivots (another choice of where to put the frame), so each
        cognate found is kept.

    Raises
    ------
    TypeError
        For non-numeric points.
    LinkageError
        For a wrong shape, fewer than :data:`MIN_POINTS` distinct points, non-finite values, a
        closed target whose points are all collinear, an unknown ``kind``, or an atlas of a
        kind not searched.

    Examples
    --------
    Twelve points round the Hoecken curve, matched in a small atlas (the default atlas is built
    once, into the cache folder; ``refine=0`` skips the least squares):

    >>> import linkage
    >>> target = linkage.catalog.hoecken().circuit(13).point[:-1]
    >>> small = linkage.synthesis.Atlas.build(200, threads=1)
    >>> best = linkage.synthesis.path(target, top=1, atlas=small, refine=0, global_search=False)
    >>> len(best), best[0].kind, best[0].source, type(best[0].linkage).__name__
    (1, 'fourbar', 'atlas', 'FourBar')
    >>> linkage.synthesis.path([(0, 0), (1, 1), (2, 2), (3, 3), (4, 4)], atlas=small)
    Traceback (most recent call last):
    ...
    linkage.LinkageError: the points are all collinear: a closed curve through them encloses ...
    """
    kinds = list(_KIND.values()) if kind == "any" else [_kind(kind, "any")]
    closed = as_flag(closed, "closed")
    top = as_count(top, "top")
    if top > SYNTHESIS_TOP_MAX:
        raise LinkageError(f"top must be between 1 and {SYNTHESIS_TOP_MAX}, got {top}")
    refine = as_count(refine, "refine", 0)
    if refine > SYNTHESIS_REFINE_MAX:
        raise LinkageError(f"refine must be between 0 and {SYNTHESIS_REFINE_MAX}, got {refine}")
    maxiter = as_count(maxiter, "maxiter")
    seed = as_count(seed, "seed", 0)
    tol = as_finite(tol, "tol")
    if tol <= 0:
        raise LinkageError(f"tol must be positive (a fraction of the target's size), got {tol}")
    min_transmission = as_finite(min_transmission, "min_transmission")
    if not 0 <= min_transmission <= math.pi / 2:
        hint = (
            f" (radians: did you mean math.radians({min_transmission:g})?)"
            if math.pi < min_transmission <= 90
            else ""
        )
        raise LinkageError(
            "min_transmission must be an angle in radians between 0 and π/2 (90°), "
            f"got {min_transmission:g}{hint}"
        )
    full_turn = as_flag(full_turn, "full_turn")
    progress = as_flag(progress, "progress")
    if global_search is not None:
        global_search = as_flag(global_search, "global_search")
    if accept is not None:
        accept = as_finite(accept, "accept")
        if accept < 0:
            raise LinkageError(f"accept must be a distance, at least 0, got {accept}")
    if max_link is not None:
        max_link = as_finite(max_link, "max_link")
        if max_link <= 0:
            raise LinkageError(f"max_link must be positive, got {max_link}")
    if lengths is not None:
        lengths = _pair(lengths, "lengths")
    if pivots is not None:
        if isinstance(pivots, (str, bytes)) or np.ndim(pivots) == 0 or len(pivots) != 2:
            raise TypeError("pivots must be ((xmin, ymin), (xmax, ymax))")
        pivots = (as_point(pivots[0], "pivots[0]"), as_point(pivots[1], "pivots[1]"))
    target = _target(points, closed)
    size = target_size(target)
    frame = _unit_frame(target, size)
    # The settings a search of a moved or thinned target keeps.
    same: dict[str, Any] = {
        "kind": kind,
        "atlas": atlas,
        "refine": refine,
        "global_search": global_search,
        "full_turn": full_turn,
        "min_transmission": min_transmission,
        "max_link": max_link,
        "tol": tol,
        "maxiter": maxiter,
        "seed": seed,
        "threads": threads,
        "progress": progress,
    }
    if frame is not None:
        # An extreme scale or a far centre: search the target moved to the origin and scaled
        # by a power of two to unit size, and move the candidates back.
        origin, unit = frame
        at_unit = path(
            (target - origin) / unit,
            closed,
            top,
            **same,
            lengths=None if lengths is None else (lengths[0] / unit, lengths[1] / unit),
            pivots=(
                None
                if pivots is None
                else (
                    ((pivots[0][0] - origin[0]) / unit, (pivots[0][1] - origin[1]) / unit),
                    ((pivots[1][0] - origin[0]) / unit, (pivots[1][1] - origin[1]) / unit),
                )
            ),
            accept=None if accept is None else accept / unit,
        )
        gone = at_unit.closest_removed
        return Candidates(
            [_moved(cand, origin, unit) for cand in at_unit],
            at_unit.removed,
            None if gone is None else _moved(gone, origin, unit),
            at_unit.closest_fails,
        )
    nthreads = _threads(threads)
    if len(target) > FIT_POINTS:
        # Many points: search through FIT_POINTS of them spread along the target (a fit's cost
        # grows with the cube of the points it fits), then measure, check and rank the
        # candidates on every point.
        some = path(
            target[_spread(target, closed, FIT_POINTS)],
            closed,
            min(SYNTHESIS_TOP_MAX, 2 * top),
            **same,
            lengths=lengths,
            pivots=pivots,
            accept=accept,
        )

        def on_every_point(c: Candidate[Any]) -> Candidate[Any] | None:
            kind = _KIND[c.kind]
            return _measure(c.params, _crossed(c), target, closed, c.source, nthreads, kind)

        measured = [m for m in map(on_every_point, some) if m is not None]
        gone = some.closest_removed
        thin = Candidates((), some.removed, None if gone is None else on_every_point(gone))
        every, result = _kept(measured, full_turn, min_transmission, lengths, pivots, thin)
        limit = math.inf if lengths is not None or max_link is None else max_link * size
        result.extend(_distinct(_ranked(every, size, limit), target, closed, size, top))
        return result
    centre = target.mean(axis=0)
    fits = refine if closed else 3 * refine
    bar = _bar(progress, fits * len(kinds))
    atlases = _atlases(atlas, kinds)
    _note_builds(missing_atlases(kind, closed, atlases), bar)
    found: list[Candidate[Any]] = []

    def admissible(c: Candidate[Any]) -> bool:
        return not _failed(c, full_turn, min_transmission, lengths, pivots)

    def best(cs: list[Candidate[Any]]) -> float:
        """Return the least error of the admissible candidates (∞ if none is)."""
        return min((c.error for c in cs if admissible(c)), default=math.inf)

    limit = math.inf if lengths is not None or max_link is None else max_link * size
    # The error that ends the search's later stages.
    goal = EXACT * size if accept is None else max(EXACT * size, accept)

    def usable(c: Candidate[Any]) -> bool:
        """Whether ``c`` is admissible and ranks before the long-linked (``max_link``)."""
        return admissible(c) and _longest(c) <= limit

    def best_usable(cs: list[Candidate[Any]]) -> float:
        """Return the least error of the usable candidates.

        An open target's further stages go on while its only exact fits have a link ranked last.
        """
        return min((c.error for c in cs if usable(c)), default=math.inf)

    for k in kinds:
        bounds = _bounds(lengths, pivots, size, k)
        pool = []
        # A four-bar from the equation of the curve through the points, refined: exact for a
        # curve a four-bar draws, closed or an arc that singles it out (docs/synthesis.md,
        # step 0).
        equation = _equation_pool(target, closed, nthreads, k)
        ahead = _finish(
            equation,
            target,
            closed,
            size,
            bounds,
            len(equation),
            nthreads,
            None,
            top,
            k,
            admissible,
            exact_at=1e-10 if accept is None else max(1e-10, accept / size),
        )
        # Open targets are matched against open arcs of the kind's circuits.
        name: AtlasKind | None = k.name if closed else k.arcs
        if name is not None:
            at = atlases.get(name) or default_atlas(kind=name)
            many = 4 * max(top, refine) if closed else 16 * max(top, refine)
            placed = max(refine, top) if closed else 3 * refine
            if full_turn or min_transmission > 0:
                # Refine the best matches whose circuit meets the constraints asked for (a
                # full-turn crank, the transmission angle), from four times as many, first.
                pool = _atlas_pool(k, at, target, 4 * placed, 4 * many, nthreads)
                pool.sort(key=lambda e: _shape_order(e, k, full_turn, min_transmission))
                pool = pool[:placed]
            else:
                pool = _atlas_pool(k, at, target, placed, many, nthreads)
        mine = _finish(
            pool,
            target,
            closed,
            size,
            bounds,
            fits,
            nthreads,
            bar,
            top,
            k,
            admissible,
            exact_at=1e-10 if accept is None else max(1e-10, accept / size),
        )
        mine = ahead + mine
        # Restarts and the global search are judged by the candidates the constraints admit:
        # an exact fit they reject must not end the search for one they admit.
        # The later stages of an open search share one budget of evaluations, smaller the more
        # points a fit has (a target no linkage draws runs them all; #29).
        later = _Budget.of(len(target))
        if not closed and name is not None and mine and best_usable(mine) > goal:
            # An open target no match fitted exactly: long fits of the best, then more matches
            # and long fits of theirs (docs/synthesis.md, step 4).
            polished: list[NDArray[np.float64]] = []
            starts = [c for c in mine if usable(c)] or mine
            mine += _polish(
                starts, polished, target, size, bounds, nthreads, bar, k, usable, budget=later
            )
            if best_usable(mine) > goal and not later.out:
                seen = {x.tobytes() for x, _, _ in pool}
                wider = _atlas_pool(k, at, target, placed + WIDER, 4 * many, nthreads)
                if full_turn or min_transmission > 0:
                    wider.sort(key=lambda e: _shape_order(e, k, full_turn, min_transmission))
                wider = [w for w in wider if w[0].tobytes() not in seen][:WIDER]
                if bar is not None:
                    bar.stage("more matches", len(wider))
                more = _finish(
                    wider,
                    target,
                    False,
                    size,
                    bounds,
                    len(wider),
                    nthreads,
                    bar,
                    1,
                    k,
                    usable,
                    exact_at=EXACT,
                    budget=later,
                )
                mine += more
                if more and best_usable(mine) > goal:
                    starts = [c for c in more if usable(c)] or more
                    mine += _polish(
                        starts,
                        polished,
                        target,
                        size,
                        bounds,
                        nthreads,
                        bar,
                        k,
                        usable,
                        budget=later,
                    )
            if best_usable(mine) > goal and not later.out:
                # The same nearest shapes re-placed along their curves (_slid), ranked again
                # and fitted as the first (docs/synthesis.md, step 4).
                slid = _atlas_pool(k, at, target, 4 * SLID, 4 * many, nthreads, slide=SLIDES)
                if full_turn or min_transmission > 0:
                    slid.sort(key=lambda e: _shape_order(e, k, full_turn, min_transmission))
                slid = slid[:SLID]
                if bar is not None:
                    bar.stage("matches re-placed", len(slid))
                mine += _finish(
                    slid,
                    target,
                    False,
                    size,
                    bounds,
                    len(slid),
                    nthreads,
                    bar,
                    1,
                    k,
                    usable,
                    exact_at=EXACT,
                    budget=later,
                )
        if not closed and mine and best_usable(mine) > goal:
            starts = [c for c in mine if admissible(c)] or mine
            mine += _hops(starts, target, size, bounds, seed, nthreads, k, later)
        if closed and refine > 0 and best_usable(mine) > goal:
            # A closed target no match fitted exactly: parts of it searched as open arcs, their
            # best fits refined on the whole target (docs/synthesis.md, step 4).
            given = atlases.get(k.arcs)
            if given is None:
                _note_builds(missing_atlases(k.name, False), bar)
            arcs = given or default_atlas(kind=k.arcs)
            mine += _from_parts(target, size, bounds, refine, arcs, nthreads, bar, k, usable)
        loose = min((c for c in mine if usable(c)), key=lambda c: c.error, default=None)
        if (
            not closed
            and accept is None
            and loose is not None
            and TIGHT * size < loose.error <= goal
        ):
            # An exact fit (within EXACT) that the first fits left in a valley above round-off
            # (8.9e-7 of the size, links 1e-3 off, where the drawing linkage is at 4e-14): one
            # long fit takes it down (docs/synthesis.md, step 4), and replaces it when better
            # (else the same design would be listed twice, with its cognate measured from it).
            tight = _polish([loose], [], target, size, bounds, nthreads, bar, k, usable, TIGHT)
            if min((c.error for c in tight), default=math.inf) < loose.error:
                mine = [c for c in mine if c is not loose] + tight
        found += mine
    enough = tol * size if accept is None else accept
    run_global = global_search if global_search is not None else best(found) > enough
    if run_global:
        for k in kinds:
            if bar is not None:
                # Generations (of both assemblies for four-bars), then refinements.
                bar.stage(f"global search ({k.name})", (2 if k is FOURBAR else 1) * maxiter + 8)
            de = _de(
                target,
                closed,
                size,
                centre,
                seed,
                maxiter,
                nthreads,
                bar,
                kind=k,
                full_turn=full_turn,
                min_transmission=min_transmission,
            )
            found += _finish(
                [(x, c, "global") for x, c in de],
                target,
                closed,
                size,
                _bounds(lengths, pivots, size, k),
                min(refine, len(de)),
                nthreads,
                bar,
                kind=k,
                admissible=admissible,
            )
    if bar is not None:
        bar.close()
    found += _cognate_candidates(found, target, closed, size, nthreads, top)
    ok, result = _kept(found, full_turn, min_transmission, lengths, pivots)
    result.extend(_distinct(_ranked(ok, size, limit), target, closed, size, top))
    return result


EQUATION_STARTS = 4
"""Linkages from the curve's equation that are refined (four-bars: of up to 6, each on the
better of its assemblies; slider-cranks: of up to 6, each on the better of its reaches; best
first by their unrefined error): for a four-bar's curve its three cognates, for a
slider-crank's the linkage and its cognate, then the next best solves."""


def _equation_pool(
    target: Float2D, closed: bool, threads: int, kind: _Kind = FOURBAR
) -> list[tuple[NDArray[np.float64], bool, str]]:
    """Return starts from the equation of the curve through ``target``.

    Four-bars: ``linkage_core::fourbars_from_curve``, each on the better of its assemblies.
    Slider-cranks: ``linkage_core::slider_cranks_from_curve``, each on the better of its
    reaches (the line reversed: ``angle + π``, ``−offset``). Best first by their error, at most
    :data:`EQUATION_STARTS`; none for fewer than :data:`CURVE_EQUATION_POINTS` (four-bars) or
    :data:`SLIDER_EQUATION_POINTS` points, or points that give no equation.
    """
    slider = kind is SLIDER
    if len(target) < (SLIDER_EQUATION_POINTS if slider else CURVE_EQUATION_POINTS):
        return []
    solve = _core.synth_slider_curve_equation if slider else _core.synth_curve_equation
    try:
        params, _, _, _, _ = solve(np.ascontiguousarray(target))
    except LinkageError:
        return []
    if not len(params):
        return []
    rows = np.repeat(params, 2, axis=0)
    if slider:
        # The other reach of each: the same linkage with its line reversed (no assembly flag).
        rows[1::2, 2] += math.pi
        rows[1::2, 3] *= -1.0
        crossed = np.zeros(len(rows), dtype=bool)
    else:
        crossed = np.tile([False, True], len(params))
    e, _ = _errors(rows, crossed, target, closed, threads=threads, kind=kind)
    chosen: list[int] = []
    for i in np.argsort(e[:, 0], kind="stable"):
        if len(chosen) == EQUATION_STARTS or not np.isfinite(e[i, 0]):
            break
        # One assembly of each four-bar: a double-rocker's two trace one circuit (its two
        # rows fit alike, and would be refined twice). A slider-crank's two rows differ.
        tol = 1e-9 * float(np.max(np.abs(rows[i])))
        if all(np.max(np.abs(rows[i] - rows[j])) > tol for j in chosen):
            chosen.append(int(i))
    return [(rows[i], bool(crossed[i]), "equation") for i in chosen]


COGNATES_OF = 8
"""Most exact four-bar fits whose cognates and reversed drives are measured too (the best
``top`` of them, at most this many: each costs five measurements, about 12 ms)."""


def _cognate_candidates(
    found: list[Candidate[Any]],
    target: Float2D,
    closed: bool,
    size: float,
    threads: int,
    top: int = COGNATES_OF,
) -> list[Candidate[Any]]:
    """Measure the cognates of the best exact fits.

    A four-bar's are its Roberts cognates, each driven at either pivot; a slider-crank's is its
    one cognate (:meth:`SliderCrank.cognate`). They draw the same curve, so they fit as well;
    the search may have stopped at the first exact fit (``top=1``), and a cognate or the other
    drive may turn fully or transmit better, which the ranking prefers. Only those that fit
    exactly are kept.
    """
    exact = sorted((c for c in found if c.error <= EXACT * size), key=lambda c: c.error)
    out: list[Candidate[Any]] = []
    # A tried variant is its parameters and its assembly: the same nine numbers on the other
    # assembly draw another circuit (a cognate's reversed drive on the wrong assembly, 5.6 sizes
    # off, had hidden the exact full-turn cognate with those numbers; found by a new-user trial).
    seen = [(c.params, _crossed(c)) for c in found]
    for c in exact[: min(top, COGNATES_OF)]:
        fb = c.linkage
        if isinstance(fb, SliderCrank):
            out += _slider_cognate(fb, seen, target, closed, size, threads)
            continue
        try:
            first, second = fb.cognates()
            variants = [fb.reversed(), first, second, first.reversed(), second.reversed()]
        except LinkageError:
            continue
        for v in variants:
            x, crossed = _params_of(v), v.assembly == "crossed"
            if _tried(x, crossed, seen, size):
                continue  # found already (a search finds cognates too)
            seen.append((x, crossed))
            cand = _measure(x, crossed, target, closed, "cognate", threads)
            # Exact or nothing: a variant that is not exact traces the curve on another circuit (a
            # crank that rocks over two intervals traces the first; see FourBar.cognates).
            if cand is not None and cand.error <= EXACT * size:
                out.append(cand)
    return out


def _tried(
    x: NDArray[np.float64], crossed: bool, seen: list[tuple[NDArray[np.float64], bool]], size: float
) -> bool:
    """Whether the placed linkage ``x`` on that assembly is in ``seen`` (to 1e-9 of ``size``)."""
    return any(
        f == crossed and q.shape == x.shape and np.max(np.abs(x - q)) <= 1e-9 * size
        for q, f in seen
    )


def _slider_cognate(
    sc: SliderCrank,
    seen: list[tuple[NDArray[np.float64], bool]],
    target: Float2D,
    closed: bool,
    size: float,
    threads: int,
) -> list[Candidate[Any]]:
    """Measure the cognate of an exact slider-crank fit (:meth:`SliderCrank.cognate`).

    Placed on either reach (the line, or the line reversed with the offset negated: a crank
    that turns fully draws the curve on one of them); only an exact fit is kept.
    """
    try:
        cog = sc.cognate()
    except LinkageError:
        return []
    (ox, oy), (along, left) = cog.o, cog.point
    out = []
    for angle, offset in ((cog.angle, cog.offset), (cog.angle + math.pi, -cog.offset)):
        x = np.array([ox, oy, angle, offset, cog.crank, cog.coupler, along, left])
        if _tried(x, False, seen, size):
            continue  # found already
        seen.append((x, False))
        cand = _measure(x, False, target, closed, "cognate", threads, SLIDER)
        if cand is not None and cand.error <= EXACT * size:
            out.append(cand)
    return out


def _shape_order(
    entry: tuple[NDArray[np.float64], bool, str],
    kind: _Kind,
    full_turn: bool,
    min_transmission: float,
) -> tuple[int, float]:
    """Order atlas matches by the shape constraints asked for (a sort key, least first).

    A match whose whole circuit meets them — its crank turns fully (if ``full_turn``) and its
    transmission angle stays ``min_transmission`` from a toggle, properties of the shape known
    before a fit — comes first (in match order, the sort being stable); then the full-turn
    cranks (if asked for) nearest to meeting the transmission bound, as a fit moves the angle;
    then the rest. A match whose circuit passes a toggle may still fit an open target's part
    that avoids it: this only orders the matches to refine.
    """
    x, crossed, _ = entry
    try:
        if kind is SLIDER:
            problem, full, _, _, mu, _ = _core.synth_slider_info(x, 0.0, 2 * math.pi, 64)
        else:
            problem, full, _, _, mu, _ = _core.synth_info(x, crossed, 0.0, 2 * math.pi, 64)
    except LinkageError:
        return (3, 0.0)
    if problem is not None or (full_turn and not full):
        return (2, 0.0)
    return (0, 0.0) if mu >= min_transmission else (1, -float(mu))


WIDER = 48
"""Further arc-atlas matches refined (from four times as many nearest shapes) for an open target
that none of the first fitted exactly."""

POLISH = 6
"""Distinct best fits of an open target refined again at length (:data:`POLISH_NFEV`) when none
is exact."""

POLISH_NFEV = 1500
"""Evaluations in each round of a long fit (:func:`_polish`; a first fit's rounds take 60)."""

LATER_EVALUATIONS = 1_000_000
"""Residual evaluations (of one placed linkage on every point: a Jacobian by differences takes
``2(q + 1)`` or ``4(q + 1)``) the later stages of an open search of up to
:data:`LATER_POINTS` points may spend (:class:`_Budget`). ``bench/open_arcs.py`` with seeds 0
and 1: the arcs those stages recovered spent at most 348,370 (seed 1 random#33), the two misses
616,866 and 886,645."""

LATER_POINTS = 40
"""Points of an open target up to which its later stages have all of :data:`LATER_EVALUATIONS`;
beyond, ``(LATER_POINTS / n)²`` of them."""


@dataclass
class _Budget:
    """The residual evaluations the later stages of an open search may spend, and spent.

    The later stages: long fits, wider and re-placed matches, restarts; :attr:`out` once spent.

    Those stages run on a target no linkage draws, each fit to its end, and an evaluation's
    cost, with the linear algebra of the fit, grows with the points: 100 random points had taken
    75-125 s, 23,928 QR factorisations (#29). With ``(LATER_POINTS / n)²`` of the evaluations
    for ``n`` points the time grows about as ``n``; a target of up to :data:`LATER_POINTS` (the
    40 of ``bench/open_arcs.py``) keeps them all. A stage checks it between fits: the last fit
    may overrun it by one fit's evaluations.
    """

    left: float
    spent: int = 0

    @classmethod
    def of(cls, points: int) -> _Budget:
        """Return the budget of a target of ``points`` points."""
        return cls(LATER_EVALUATIONS * min(1.0, (LATER_POINTS / max(points, 1)) ** 3))

    @property
    def out(self) -> bool:
        """Whether it is spent."""
        return self.spent >= self.left


def _polish(
    found: list[Candidate[Any]],
    polished: list[NDArray[np.float64]],
    target: Float2D,
    size: float,
    bounds: tuple[NDArray[np.float64], NDArray[np.float64]],
    threads: int,
    bar: Any,
    kind: _Kind,
    admissible: Callable[[Candidate[Any]], bool],
    exact: float | None = None,
    closed: bool = False,
    budget: _Budget | None = None,
) -> list[Candidate[Any]]:
    """Refine the best :data:`POLISH` distinct fits at length, stopping at the first exact one.

    Exact is within ``exact`` of the size (default :data:`EXACT`). A short or near-straight arc is
    matched to ~1e-5 … 1e-4 of its size along a long, curved valley of near-fits (the scaled
    Jacobian's singular values span 10⁹ on an eighth of Hoecken's curve): least squares crawls along
    it to the exact linkage, in hundreds to thousands of evaluations where a first fit's rounds stop
    at 60 (measured in docs/synthesis.md). These fits take geodesic acceleration
    (:func:`_geodesic_lm`), whose steps follow the valley's bend. Fits whose parameters all lie
    within 1e-3 of the size of a better one's, or of one in ``polished`` (the starts of earlier
    calls, to which this call's are added), are one start. No start is fitted once ``budget``
    is spent.
    """
    picked: list[Candidate[Any]] = []
    for c in sorted(found, key=lambda c: c.error):
        if len(picked) >= POLISH:
            break
        if all(np.max(np.abs(c.params - p)) > 1e-3 * size for p in polished):
            picked.append(c)
            polished.append(c.params)
    if bar is not None:
        bar.stage("long fits", len(picked))
    out: list[Candidate[Any]] = []
    for c in picked:
        if budget is not None and budget.out:
            break
        crossed = _crossed(c)
        out += _finish(
            [(c.params, crossed, c.source)],
            target,
            closed,
            size,
            bounds,
            1,
            threads,
            bar,
            kind=kind,
            nfev=POLISH_NFEV,
            geodesic=True,
            budget=budget,
        )
        if any(o.error <= (exact or EXACT) * size and admissible(o) for o in out):
            break
    return out


HOPS = 12
"""Perturbed restarts of the least-squares fit for an open target that no arc match fits exactly."""


def _hops(
    found: list[Candidate[Any]],
    target: Float2D,
    size: float,
    bounds: tuple[NDArray[np.float64], NDArray[np.float64]],
    seed: int,
    threads: int,
    kind: _Kind,
    budget: _Budget | None = None,
) -> list[Candidate[Any]]:
    """Refine perturbed copies of the best three fits, stopping at the first exact one.

    No copy is fitted once ``budget`` is spent.
    Every parameter moves by a normal step of 5 %, then 1 %, of the target's size, in turn.
    An arc is matched to ~1e-5 of its size by many linkages; the fit stalls in such a basin,
    and a restart from near it often reaches the exact one (measured in docs/synthesis.md).
    """
    rng = np.random.default_rng(seed)
    starts = sorted(found, key=lambda c: c.error)[:3]
    out: list[Candidate[Any]] = []
    for t in range(HOPS):
        if budget is not None and budget.out:
            break
        c = starts[t % len(starts)]
        step = (0.05 if t % 2 == 0 else 0.01) * size
        x = c.params + step * rng.standard_normal(len(c.params))
        crossed = _crossed(c)
        out += _finish(
            [(x, crossed, "atlas")],
            target,
            False,
            size,
            bounds,
            1,
            threads,
            None,
            kind=kind,
            budget=budget,
        )
        if out and min(o.error for o in out) <= 1e-10 * size:
            break
    return out


PART_GAP = 3.0
"""A closed target is cut into parts (:func:`_parts`) where two consecutive points are more than
this many times the median spacing apart."""

PART_POINTS = 12
"""Fewest points of a part of a closed target searched as an open arc (:func:`_parts`): well
over the nine through which finitely many four-bars pass exactly (Wampler, Morgan and Sommese
1992: 1442 of them), so that a fit exact on a part says something about the whole."""

PART_FITS = 2
"""Best fits of each part refined on the whole closed target (:func:`_from_parts`)."""

PART_MATCHES = 3
"""Fits of each part, in units of ``refine`` (as an open target's first fits): with ``refine``
alone the crescent of the tests ended at 1e-4 … 3e-4 of its size under 8 of 8 placements with
the tests' 200,000-arc atlas, with three times as many at ≤ 5e-12 under 8 of 8."""

VALLEY = 1e-3
"""A closed target's best :data:`PART_FITS` fits from its parts, when none is exact, get long
fits if within this fraction of its size (:func:`_from_parts`): one placement of the tests'
crescent, whose best such fit (1.5e-4) stayed there, was recovered by one at 2.8e-4 (to
3.6e-14; measured with an earlier guard of MINPACK's Jacobian copy, docs/synthesis.md)."""


def _parts(target: Float2D) -> list[NDArray[np.intp]]:
    """Return the indices of the parts of a closed ``target`` searched as open arcs.

    The points are cut where a gap exceeds :data:`PART_GAP` times the median gap (and at the
    largest gap), into runs the curve passes through without a stretch the points leave out;
    a run of ``m`` of the ``n`` points is cut again into ``min(⌊3m/n⌋, ⌊m/PART_POINTS⌋)``
    parts (thirds of a target of 36 or more points with no such gap), consecutive parts sharing
    their end point. Parts of fewer than :data:`PART_POINTS` points are left out; the longest
    come first.
    """
    n = len(target)
    gaps = np.hypot(*(np.roll(target, -1, axis=0) - target).T)
    # Start after the largest gap, so that no run crosses it.
    order = np.roll(np.arange(n), -(int(np.argmax(gaps)) + 1))
    cuts = sorted(set(np.flatnonzero(gaps[order] > PART_GAP * np.median(gaps)).tolist()) | {n - 1})
    out: list[NDArray[np.intp]] = []
    start = 0
    for end in cuts:
        run = order[start : end + 1]
        start = end + 1
        m = max(1, min(3 * len(run) // n, len(run) // PART_POINTS))
        for j in range(m):
            a = j * len(run) // m
            b = (j + 1) * len(run) // m + (1 if j < m - 1 else 0)
            if b - a >= PART_POINTS:
                out.append(run[a:b])
    out.sort(key=len, reverse=True)
    return out


def _from_parts(
    target: Float2D,
    size: float,
    bounds: tuple[NDArray[np.float64], NDArray[np.float64]],
    refine: int,
    arcs: Atlas,
    threads: int,
    bar: Any,
    kind: _Kind,
    admissible: Callable[[Candidate[Any]], bool],
) -> list[Candidate[Any]]:
    """Fit a closed target from fits of its parts, stopping at the first exact one.

    Each part (:func:`_parts`, longest first) is matched against the open-arc atlas ``arcs``,
    its :data:`PART_MATCHES` × ``refine`` best placed matches are fitted to it as an open
    target's first fits are (stopping at one exact on the part), and its best :data:`PART_FITS`
    fits are refined on the whole target. When none of those is exact, the best
    :data:`PART_FITS` within :data:`VALLEY` of the size get long fits (:func:`_polish`). A part
    leaves out the stretches between sparse points, which mislead the closed polygon's
    descriptors, and the rest of the curve; a fit close on a part lies in the basin of the
    linkage that draws the whole more often than the closed matches do (docs/synthesis.md).
    """
    parts = _parts(target)
    if bar is not None:
        bar.stage("parts as arcs", len(parts))
    out: list[Candidate[Any]] = []
    for idx in parts:
        part = target[idx]
        part_size = target_size(part)
        # As an open target's first fits (path): 3 × refine of the 16 × refine nearest.
        pool = _atlas_pool(kind, arcs, part, PART_MATCHES * refine, 16 * refine, threads)
        fits = _finish(
            pool, part, False, part_size, bounds, len(pool), threads, None, 1, kind, exact_at=EXACT
        )
        fits.sort(key=lambda c: c.error)
        for c in fits[:PART_FITS]:
            out += _finish(
                [(c.params, _crossed(c), "atlas")],
                target,
                True,
                size,
                bounds,
                1,
                threads,
                None,
                kind=kind,
                admissible=admissible,
            )
        if bar is not None:
            bar.update(1)
        if any(o.error <= EXACT * size and admissible(o) for o in out):
            return out
    # A near-fit (within VALLEY of the size) may lie in a valley that leads to the exact linkage
    # (step 4): the best PART_FITS get long fits. More cost too much on a target no four-bar
    # draws (a long fit of 60 points took up to 7.6 s), whose fits can come that near too.
    near = sorted((c for c in out if c.error <= VALLEY * size), key=lambda c: c.error)
    polished: list[NDArray[np.float64]] = []
    for c in near[:PART_FITS]:
        out += _polish(
            [c], polished, target, size, bounds, threads, bar, kind, admissible, closed=True
        )
        if any(o.error <= EXACT * size and admissible(o) for o in out):
            break
    return out


def _atlases(given: Any, kinds: list[_Kind]) -> dict[str, Atlas]:
    """Return the atlases given to :func:`path` by kind, loading folders.

    An atlas of a kind not searched is an error.
    """
    items = list(given) if isinstance(given, (list, tuple)) else [given]
    out: dict[str, Atlas] = {}
    for a in items:
        if a is None:
            continue
        at = a if isinstance(a, Atlas) else Atlas.load(a)
        if at.kind not in [k.name for k in kinds] + [k.arcs for k in kinds]:
            searched = " or ".join(repr(k.name) for k in kinds)
            raise LinkageError(f"a {at.kind} atlas was given, but the search is for {searched}")
        out[at.kind] = at
    return out


def _atlas_pool(
    kind: _Kind,
    at: Atlas,
    target: Float2D,
    keep: int,
    k: int,
    threads: int,
    slide: int = 0,
) -> list[tuple[NDArray[np.float64], bool, str]]:
    """Return the ``keep`` best placed atlas matches of ``target``, of the ``k`` nearest shapes.

    Each nearest entry is placed by the similarity between its curve's frame and the target's
    (both ends of the major axis), moved along its curve by ``slide`` rounds of :func:`_slid`
    (an open target's), and scored by the polyline distance both ways (an arc atlas's entries,
    :data:`ARCS` or :data:`SLIDER_ARCS`, against an open target: one way).
    """
    closed = at.kind not in _ARC_KIND
    variants, frame_t = _core.synth_descriptors(target, at.harmonics, closed)
    idx, _, _ = at.nearest(variants, min(max(k, 16), len(at)), threads)
    placed, crossed = [], []
    # An entry near several query variants is listed once for each: place it once.
    for i in dict.fromkeys(idx.tolist()):
        entry = np.asarray(at.params[int(i)], dtype=np.float64)
        try:
            if not closed:
                slider = kind is SLIDER
                cr = not slider and bool(entry[5])
                frame_c = _core.synth_arc_frame(entry, at.harmonics, at.samples, at.phases, slider)
            elif kind is FOURBAR:
                base = np.array([0.0, 0.0, 1.0, 0.0, *entry[:5]])
                cr = bool(entry[5])
                frame_c = _core.synth_frame(base, cr, at.harmonics, at.samples)
            else:
                coupler, offset, along, left = entry[:4]
                base = np.array([0.0, 0.0, 0.0, offset, 1.0, coupler, along, left])
                cr = False
                frame_c = _core.synth_slider_frame(base, at.harmonics, at.samples)
        except LinkageError:
            continue
        for flip in (False, True):
            placed.append(_placed(entry, frame_t, frame_c, flip, kind))
            crossed.append(cr)
    if not placed:
        return []
    p, cr_a = np.array(placed), np.array(crossed)
    if slide:
        p = _slid(kind, p, cr_a, target, slide, threads)
    e, _ = _errors(p, cr_a, target, closed, threads=threads, kind=kind)
    worst = np.maximum(e[:, 0], e[:, 2]) if closed else e[:, 0]
    score = np.where(np.isfinite(worst), worst, np.inf)
    order = np.argsort(score, kind="stable")
    return [(p[j], bool(cr_a[j]), "atlas") for j in order[:keep] if np.isfinite(score[j])]


SLID = 24
"""Matches re-placed by :func:`_slid` and fitted for an open target that no earlier stage fitted
exactly (the best of ``4 × SLID``, from the wider matches' nearest shapes)."""

SLIDES = 3
"""Rounds of :func:`_slid`."""


def _slid(
    kind: _Kind,
    params: NDArray[np.float64],
    crossed: NDArray[np.bool_],
    target: Float2D,
    rounds: int,
    threads: int,
) -> NDArray[np.float64]:
    """Move each placed linkage (rows of ``params``) along its curve onto an open ``target``.

    Each of ``rounds`` rounds (iterative closest points with a similarity) takes every target
    point's nearest point of the linkage's curve (its foot) and the least-squares similarity
    ``z ↦ a·z + b`` (complex ``a``, ``b``; Procrustes, no reflection) from the feet to the
    target points, and moves the linkage by it: its pivots mapped, its lengths scaled by
    ``|a|``, a slider's line turned by ``arg a``. An arc match is placed by the frames of its
    stored arc and of the target, which rarely start and end at the same places of the
    circuit: the target then sits askew along the curve, and its distance can rank a match of
    the right shape below others (docs/synthesis.md, step 4). Rows whose curve does not
    assemble at every foot stay where they are.
    """
    p = np.array(params, dtype=np.float64)
    t = target[:, 0] + 1j * target[:, 1]
    tm = t.mean()
    scaled = list(kind.scaled)
    for _ in range(rounds):
        _, feet = _errors(p, crossed, target, False, threads=threads, kind=kind)
        rows = np.flatnonzero(np.all(np.isfinite(feet), axis=1))
        if not len(rows):
            break
        r = _residuals(kind, p[rows], crossed[rows], target, feet[rows])
        z = (r[..., 0] + target[:, 0]) + 1j * (r[..., 1] + target[:, 1])
        zm = z.mean(axis=1)
        spread = np.sum(np.abs(z - zm[:, None]) ** 2, axis=1)
        ok = np.all(np.isfinite(z), axis=1) & (spread > 0)
        rows, z, zm, spread = rows[ok], z[ok], zm[ok], spread[ok]
        a = np.sum((t - tm)[None, :] * np.conj(z - zm[:, None]), axis=1) / spread
        b = tm - a * zm
        q = p[rows]
        for i, j in kind.pivots:
            w = (q[:, i] + 1j * q[:, j]) * a + b
            q[:, i], q[:, j] = w.real, w.imag
        q[:, scaled] *= np.abs(a)[:, None]
        for i in kind.angles:
            q[:, i] += np.angle(a)
        p[rows] = q
    return p


EXACT = 1e-6
"""Errors below this fraction of the target's size count as exact (a tie) when ranking."""

TIGHT = 1e-10
"""An open target's best fit above this fraction of its size but within :data:`EXACT` (when no
``accept`` is given) gets one long fit, to round-off where the fit is exact."""


def _ranked(found: list[Candidate[Any]], size: float, limit: float) -> list[Candidate[Any]]:
    """Rank candidates: links longer than ``limit`` last, then by error.

    Among exact fits (error ≤ :data:`EXACT` × size: within the refinement's own accuracy,
    where cognates and round-off differ by nothing a designer can see) a crank that turns fully
    comes first, then the transmission angle farthest from a toggle, then the error.
    """

    def key(c: Candidate[Any]) -> tuple[bool, float, bool, float, float, float]:
        exact = c.error <= EXACT * size
        return (
            _longest(c) > limit,
            0.0 if exact else c.error,
            exact and not c.full_turn,
            -c.min_transmission if exact else 0.0,
            c.error,
            c.rms,
        )

    return sorted(found, key=key)


def longest_link(c: Candidate[Any]) -> float:
    """Return a candidate's longest link.

    That is a link length, a side of its coupler triangle, or a slider-crank's offset (the frame
    must reach its line). :func:`path` ranks candidates whose longest link passes ``max_link``
    target sizes last.

    Examples
    --------
    >>> import numpy as np, linkage
    >>> from linkage.synthesis import Candidate, longest_link
    >>> fb = linkage.FourBar(ground=20, crank=10, coupler=25, rocker=25, point=(50, 0))
    >>> longest_link(Candidate(fb, 0.0, 0.0, 0.0, (0.0, 6.3), True, "crank-rocker",
    ...                        0.4, False, "by hand", np.zeros(9)))   # A to P
    50.0
    """
    return _longest(c)


def source_text(source: str) -> str:
    """Word a candidate's ``source`` as the stage that found it.

    Examples
    --------
    >>> from linkage.synthesis import source_text
    >>> [source_text(s) for s in ("equation", "atlas", "global", "cognate")]
    ['curve-equation search', 'atlas search', 'global search', 'cognate search']
    """
    return f"{'curve-equation' if source == 'equation' else source} search"


def long_link(c: Candidate[Any], size: float) -> float | None:
    """Return ``c``'s longest link in target sizes when it passes :data:`LONG_LINK`, else None.

    :func:`path` ranks such candidates after the rest (its ``max_link``); the CLI table, the
    report's figure and its page say so with this ratio.

    Examples
    --------
    >>> import numpy as np, linkage
    >>> from linkage.synthesis import Candidate, long_link
    >>> fb = linkage.FourBar(ground=20, crank=10, coupler=25, rocker=25, point=(50, 0))
    >>> c = Candidate(fb, 0.0, 0.0, 0.0, (0.0, 6.3), True, "crank-rocker", 0.4, False,
    ...               "by hand", np.zeros(9))
    >>> long_link(c, 2.0), long_link(c, 5.0)   # the arm A-P is 50
    (25.0, None)
    """
    ratio = _longest(c) / size
    return ratio if ratio > LONG_LINK else None


CHANGE_POINT_NEAR = 1e-3
"""A candidate whose Grashof sums (a slider-crank's ``|offset| + crank`` and rod) differ by less
than this fraction of the target's size is named near a change point (:func:`change_point_gap`)."""


def change_point_gap(c: Candidate[Any], size: float) -> tuple[float, str] | None:
    """Return ``c``'s distance from a change point and its law, within :data:`CHANGE_POINT_NEAR`.

    The gap between a four-bar's Grashof sums ``s + l`` and ``p + q`` (a slider-crank's
    ``|offset| + crank`` and rod), when less than ``CHANGE_POINT_NEAR · size`` and ``c`` is not
    classed a change point already; else None. Such a linkage turns fully on paper but can flip
    branch where its links lie flat.

    Examples
    --------
    >>> import numpy as np, linkage
    >>> from linkage.synthesis import Candidate, change_point_gap
    >>> fb = linkage.FourBar(ground=20, crank=10, coupler=25, rocker=15.000001)  # 30 vs 30.000001
    >>> c = Candidate(fb, 0.0, 0.0, 0.0, (0.0, 6.3), True, fb.grashof(), 0.0, False, "",
    ...               np.zeros(9))
    >>> gap, law = change_point_gap(c, 30.0)
    >>> print(f"{gap:.1e}", law)
    1.0e-06 s + l = p + q
    >>> change_point_gap(c, 1e-4) is None
    True
    """
    lk = c.linkage
    if isinstance(lk, SliderCrank):
        gap = abs(lk.coupler - (abs(lk.offset) + lk.crank))
        law = "|offset| + crank = rod"
    else:
        short, p, q, long = sorted((lk.ground, lk.crank, lk.coupler, lk.rocker))
        gap = abs(p + q - (short + long))
        law = "s + l = p + q"
    if c.grashof == "change-point" or not gap < CHANGE_POINT_NEAR * size:
        return None
    return gap, law


def _links(fb: FourBar | SliderCrank) -> tuple[float, ...]:
    """Return the link lengths ``lengths`` bounds: a four-bar's four, a slider-crank's two."""
    if isinstance(fb, SliderCrank):
        return fb.crank, fb.coupler
    return fb.ground, fb.crank, fb.coupler, fb.rocker


def _pins(fb: FourBar | SliderCrank) -> tuple[tuple[float, float], ...]:
    """Return the fixed pivots ``pivots`` bounds: a four-bar's O and C, a slider-crank's O."""
    return (fb.o,) if isinstance(fb, SliderCrank) else (fb.o, fb.c)


def _arms(fb: FourBar | SliderCrank) -> tuple[float, float]:
    """Return the coupler triangle's sides to the point: from A and from B (the slider's pin)."""
    along, left = fb.point
    return math.hypot(along, left), math.hypot(fb.coupler - along, left)


def _longest(c: Candidate[Any]) -> float:
    fb: FourBar | SliderCrank = c.linkage
    arms = _arms(fb)
    if isinstance(fb, SliderCrank):
        # The line's distance from the crank pivot counts as a link: the frame must reach it.
        return max(abs(fb.offset), fb.crank, fb.coupler, *arms)
    return max(fb.ground, fb.crank, fb.coupler, fb.rocker, *arms)


def _matched_curve(c: Candidate[Any], target: Float2D, closed: bool, samples: int = 512) -> Float2D:
    """Sample the part of ``c``'s circuit that the target points fall on (closed: all of it)."""
    kind = _KIND[c.kind]
    crossed = np.array([_crossed(c)])
    _, feet = _errors(
        c.params[None, :], crossed, target, closed, samples=2048, exact=True, kind=kind
    )
    lo, hi = _arc(feet[0], closed)
    s = np.linspace(lo, hi, samples)[None, :]
    # Residuals from the origin are the curve points themselves.
    pts = _residuals(kind, c.params[None, :], crossed, np.zeros((samples, 2)), s)
    return np.ascontiguousarray(pts[0])


def _third_pivot(c: Candidate[Any]) -> complex:
    """Roberts' third pivot ``D``: the triangle ``O C D`` is directly similar to ``A B P``."""
    fb = c.linkage
    assert isinstance(fb, FourBar)
    o, cc = complex(*fb.o), complex(*fb.c)
    return o + (cc - o) * complex(*fb.point) / fb.coupler


def _cognates(a: Candidate[Any], b: Candidate[Any], tol: float) -> bool:
    """Whether ``b``'s ground pivots are those of one of ``a``'s Roberts cognates (four-bars)."""
    if not (isinstance(a.linkage, FourBar) and isinstance(b.linkage, FourBar)):
        return False
    o, c, d = complex(*a.linkage.o), complex(*a.linkage.c), _third_pivot(a)
    mine = (complex(*b.linkage.o), complex(*b.linkage.c))
    for pair in ((o, d), (c, d)):
        for p, q in (pair, pair[::-1]):
            if abs(mine[0] - p) <= tol and abs(mine[1] - q) <= tol:
                return True
    return False


def _distinct(
    ranked: list[Candidate[Any]], target: Float2D, closed: bool, size: float, top: int
) -> list[Candidate[Any]]:
    """Return the first ``top`` of ``ranked`` drawing different curves (cognates kept).

    Two candidates draw the same curve when each one's matched part lies within
    ``max(1e-6 size, error / 20)`` of the other's (a difference the target cannot tell); the
    later (worse-ranked) one is dropped unless it is a Roberts cognate of the earlier. Two
    candidates of the same kind and assembly whose parameters agree to :data:`NEAR` of the
    larger of the size and the shorter of their longest links (a slider line's direction to
    :data:`NEAR` radians) are one design, whatever their matched
    curves (one that does not sample finitely included): a near-copy the optimiser left in the
    same valley. So are two four-bars that are one linkage driven at either pivot (the better
    drive is kept), and two rocking slider-cranks that are one linkage with its line reversed.
    """
    kept: list[tuple[Candidate[Any], Float2D, list[tuple[Any, NDArray[np.float64]]]]] = []
    for c in ranked:
        if len(kept) >= top:
            break
        curve = _matched_curve(c, target, closed)
        same = False
        for u, ucurve, forms in kept:
            tol = max(1e-6 * size, min(c.error, u.error) / 20)
            # Near-copies are judged on the scale of the drawing that shows the whole linkage.
            near = max(size, min(_longest(c), _longest(u)))
            if any(
                type(form) is type(c.linkage)
                and getattr(form, "assembly", None) == getattr(c.linkage, "assembly", None)
                and params.shape == c.params.shape
                and _apart(params, c.params, _KIND[c.kind], near) <= NEAR * near
                for form, params in forms
            ):
                same = True
                break
            if (
                largest_distance(curve, ucurve) <= tol
                and largest_distance(ucurve, curve) <= tol
                and (
                    _same_pivots(u, c, 1e-9 * size)
                    or not _cognates(u, c, max(1e-6 * size, 1e-3 * size))
                )
            ):
                same = True
                break
        if not same:
            kept.append((c, curve, _forms(c)))
    return [c for c, _, _ in kept]


def _same_pivots(a: Candidate[Any], b: Candidate[Any], tol: float) -> bool:
    """Whether two four-bars turn about the same two ground pivots (in either order)."""
    if not (isinstance(a.linkage, FourBar) and isinstance(b.linkage, FourBar)):
        return False
    pa = (complex(*a.linkage.o), complex(*a.linkage.c))
    pb = (complex(*b.linkage.o), complex(*b.linkage.c))
    return any(abs(pb[0] - p) <= tol and abs(pb[1] - q) <= tol for p, q in (pa, pa[::-1]))


NEAR = 0.05
"""Two candidates whose placed parameters all agree to this fraction of the target's size, or of
their longest link when both are longer (a slider line's direction to this many radians), are
one design: only the better is listed. A drawing of the whole linkage shows them alike."""


def _apart(a: NDArray[np.float64], b: NDArray[np.float64], kind: _Kind, size: float) -> float:
    """Return the largest difference of two placed parameter vectors of ``kind``, as a length.

    A slider line's direction counts its turn (modulo a full turn) times ``size``.
    """
    d = np.abs(a - b)
    if kind is SLIDER:
        turn = float(d[2]) % (2 * math.pi)
        d[2] = min(turn, 2 * math.pi - turn) * size
    return float(np.max(d, initial=0.0))


def _forms(c: Candidate[Any]) -> list[tuple[Any, NDArray[np.float64]]]:
    """Return ``c``'s linkage and parameters, and the other forms of the same linkage.

    For a four-bar the same driven at its rocker; for a slider-crank whose crank rocks (its
    circuit passes both reaches) the same with its line reversed (direction turned by π, offset
    negated).
    """
    forms: list[tuple[Any, NDArray[np.float64]]] = [(c.linkage, c.params)]
    if isinstance(c.linkage, SliderCrank):
        if not c.linkage.full_turn:
            x = c.params.copy()
            x[2] += math.pi
            x[3] = -x[3]
            forms.append((c.linkage, x))
        return forms
    if isinstance(c.linkage, FourBar):
        try:
            r = c.linkage.reversed()
        except LinkageError:
            return forms
        forms.append((r, _params_of(r)))
    return forms


def _params_of(fb: FourBar) -> NDArray[np.float64]:
    """``fb`` as a placed parameter vector (:data:`FOURBAR`'s layout; its assembly apart)."""
    return np.array(fb._p()[:9], dtype=np.float64)


def largest_distance(points: ArrayLike, path: ArrayLike) -> float:
    """Return the largest distance from the finite ``points`` (n, 2) to the polyline ``path``.

    A sample of ``path`` that is not finite breaks the polyline (no segment is drawn across
    it; ``linkage_core::polyline_distances``); ∞ when no point or no path sample is finite.

    >>> import linkage
    >>> linkage.synthesis.largest_distance([[1.0, 1.0], [float("nan"), 0.0]], [[0, 0], [2, 0]])
    1.0
    """
    p = np.asarray(points, dtype=np.float64).reshape(-1, 2)
    p = np.ascontiguousarray(p[np.all(np.isfinite(p), axis=1)])
    d = _core.polyline_distance(p, np.ascontiguousarray(path, dtype=np.float64).reshape(-1, 2))
    return float(d.max()) if len(d) else math.inf


def _pair(value: Any, name: str) -> tuple[float, float]:
    a, b = as_point(value, name)
    return a, b


def _bounds(
    lengths: tuple[float, float] | None,
    pivots: tuple[tuple[float, float], tuple[float, float]] | None,
    size: float,
    kind: _Kind = FOURBAR,
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    lo = np.full(kind.params, -np.inf)
    hi = np.full(kind.params, np.inf)
    at = list(kind.lengths)
    lo[at] = 1e-9 * size
    if lengths is not None:
        a, b = float(lengths[0]), float(lengths[1])
        if not (0 < a < b):
            raise LinkageError(
                f"lengths must be (least, greatest) with 0 < least < greatest, got {lengths}"
            )
        lo[at], hi[at] = a, b
        # The coupler point within the greatest length of both its joints (see _failed).
        point = [kind.params - 2, kind.params - 1]
        lo[point], hi[point] = -b, b
    if pivots is not None:
        (x0, y0), (x1, y1) = pivots
        if not (x0 < x1 and y0 < y1):
            raise LinkageError(f"pivots must be ((xmin, ymin), (xmax, ymax)), got {pivots}")
        for ix, iy in kind.pivots:
            lo[ix], hi[ix] = x0, x1
            lo[iy], hi[iy] = y0, y1
    return lo, hi


def _bar(progress: bool, total: int) -> Bar | None:
    return Bar("synthesis", total=total) if progress else None


def _finish(
    pool: list[tuple[NDArray[np.float64], bool, str]],
    target: Float2D,
    closed: bool,
    size: float,
    bounds: tuple[NDArray[np.float64], NDArray[np.float64]],
    refine: int,
    threads: int,
    bar: Any,
    enough: int | None = None,
    kind: _Kind = FOURBAR,
    admissible: Callable[[Candidate[Any]], bool] | None = None,
    nfev: int = 60,
    exact_at: float = 1e-10,
    geodesic: bool = False,
    budget: _Budget | None = None,
) -> list[Candidate[Any]]:
    """Refine the first ``refine`` of ``pool``, then measure and check every one.

    Each refinement is up to three rounds of least squares of at most ``nfev`` evaluations each
    (``geodesic``: :func:`_refine`'s).
    Stop early once ``enough`` distinct candidates that are ``admissible`` (meet the caller's
    constraints) draw the target to ``exact_at`` of its size, or once ``budget`` is spent (the
    rest of ``pool`` is left out).
    """
    out: list[Candidate[Any]] = []
    exact: list[NDArray[np.float64]] = []
    for k, (x, crossed, source) in enumerate(pool):
        if enough is not None and len(exact) >= enough:
            break
        if budget is not None and budget.out:
            break
        if k < refine:
            # Rounds of least squares, each from every target point's true nearest curve point
            # (where the curve crosses itself a first guess may put a point on the wrong pass).
            # Least squares lowers the RMS distance, which can raise the largest: the best
            # linkage by largest distance is kept too (an earlier round or the unrefined one).
            best_x, best_e = x, math.inf
            rounds = [x]
            for r in range(4):
                e, feet = _errors(
                    x[None, :],
                    np.array([crossed]),
                    target,
                    closed,
                    samples=512,
                    exact=True,
                    kind=kind,
                )
                err = float(e[0, 0]) if np.isfinite(e[0, 0]) else math.inf
                if err < best_e:
                    best_x, best_e = x, err
                if r == 3 or not np.all(np.isfinite(feet)) or err <= 1e-10 * size:
                    break
                try:
                    x = _refine(
                        x, crossed, target, feet[0], size, bounds, nfev, kind, geodesic, budget
                    )
                except (ValueError, LinkageError):
                    break
                rounds.append(x)
            if bar is not None:
                bar.update(1)
            # The last refinement, and the best by largest distance when that is another (an
            # earlier round or the unrefined one): both are measured, the ranking decides.
            tries = [x] + ([best_x] if best_x is not x else [])
        else:
            tries, rounds = [x], []
        measured = [_measure(xt, crossed, target, closed, source, threads, kind) for xt in tries]
        if admissible is not None and not any(c is not None and admissible(c) for c in measured):
            # Least squares minds the fit, not the constraints: when it left what they admit,
            # the last round (or the start) that they admit is kept too.
            for xr in reversed(rounds):
                if any(xr is xt for xt in tries):
                    continue
                c = _measure(xr, crossed, target, closed, source, threads, kind)
                if c is not None and admissible(c):
                    measured.append(c)
                    break
        for cand in measured:
            if cand is not None:
                out.append(cand)
                if (
                    cand.error <= exact_at * size
                    and (admissible is None or admissible(cand))
                    and all(np.max(np.abs(cand.params - e)) > 1e-6 * size for e in exact)
                ):
                    exact.append(cand.params)
    return out


UNIT_RANGE = (2.0**-64, 2.0**64)
"""Target sizes searched where they are; a target of a size outside is searched moved to the
origin and scaled to unit size (:func:`path`)."""


FAR = 2.0**10
"""A target whose centre is farther from the origin than this many sizes is searched moved to
the origin (:func:`_unit_frame`): coordinates that large would cost the fit their digits."""

FIT_POINTS = 120
"""Most target points a search fits; a target of more is searched through this many spread
along it by arc length, and its candidates measured on every point (:func:`path`)."""


def _spread(target: Float2D, closed: bool, n: int) -> NDArray[np.intp]:
    """Return the indices of ``n`` of ``target``'s points spread evenly by arc length.

    An open target keeps both its ends; a closed one is spread round its loop.
    """
    ring = np.concatenate([target, target[:1]]) if closed else target
    steps = np.hypot(*np.diff(ring, axis=0).T)
    along = np.concatenate([[0.0], np.cumsum(steps)])
    if closed:
        want = np.linspace(0.0, along[-1], n, endpoint=False)
        idx = np.searchsorted(along[:-1], want).clip(0, len(target) - 1)
    else:
        want = np.linspace(0.0, along[-1], n)
        idx = np.searchsorted(along, want).clip(0, len(target) - 1)
        idx[0], idx[-1] = 0, len(target) - 1
    return np.unique(idx)


def _unit_frame(target: Float2D, size: float) -> tuple[NDArray[np.float64], float] | None:
    """Return ``(centre, k)`` that take ``target`` (of size ``size``) to unit size at the origin.

    ``k`` is a power of two (an exact scaling); None when the size is within
    :data:`UNIT_RANGE` and the centre within :data:`FAR` sizes of the origin.
    """
    lo, hi = UNIT_RANGE
    centre = _mean(target)
    if lo <= size <= hi and float(np.max(np.abs(centre))) <= FAR * size:
        return None
    return centre, _pow2(size)


def _moved(c: Candidate[Any], centre: NDArray[np.float64], k: float) -> Candidate[Any]:
    """``c`` (found for a target moved by ``-centre`` and scaled by ``1/k``) moved back."""
    x = np.array(c.params, dtype=np.float64)
    kind = _KIND[c.kind]
    for i, j in kind.pivots:
        x[i], x[j] = centre[0] + k * x[i], centre[1] + k * x[j]
    x[list(kind.scaled)] *= k
    crossed = _crossed(c)
    lk = _linkage_of(x, crossed, kind)
    return replace(c, linkage=lk, error=c.error * k, rms=c.rms * k, back=c.back * k, params=x)


def _crossed(c: Candidate[Any]) -> bool:
    """Whether ``c`` is a four-bar in its crossed assembly (the flag its parameters go with)."""
    return isinstance(c.linkage, FourBar) and c.linkage.assembly == "crossed"


def _linkage_of(x: NDArray[np.float64], crossed: bool, kind: _Kind) -> FourBar | SliderCrank:
    """Return the linkage of the placed parameters ``x`` of ``kind``."""
    if kind is SLIDER:
        ox, oy, angle, offset, crank, coupler, along, left = (float(v) for v in x)
        return SliderCrank(crank, coupler, offset, (along, left), (ox, oy), angle)
    return FourBar(
        crank=x[4],
        coupler=x[5],
        rocker=x[6],
        point=(x[7], x[8]),
        assembly="crossed" if crossed else "open",
        o=(x[0], x[1]),
        c=(x[2], x[3]),
    )


def _turned(lo: float, hi: float) -> tuple[float, float]:
    """Return the crank range ``(lo, hi)`` moved by whole turns to start in [-180°, 180°).

    ``lo`` in [-180.05°, 179.95°): it reads in [-180.0°, 180.0°) to the 0.1° reports print. The
    same crank angles (a fit's angles may have turned past a full turn); every report and
    exported scene then shows ranges near zero (179.99999797° had read "180.0 … 540.0").
    """
    half = math.radians(0.05)
    k = math.floor((lo + math.pi + half) / (2 * math.pi))
    return lo - 2 * math.pi * k, hi - 2 * math.pi * k


def _measure(
    x: NDArray[np.float64],
    crossed: bool,
    target: Float2D,
    closed: bool,
    source: str,
    threads: int,
    kind: _Kind = FOURBAR,
) -> Candidate[Any] | None:
    """Measure and check a candidate.

    ``None`` when its circuit does not assemble throughout or the tracker leaves it, or when a
    link is shorter than :data:`SHORTEST_LINK` of the target's size (a crank of 4e-6 mm on a
    60 mm foot path had been listed as a full-turn crank-rocker drawing a dot).
    """
    links = list(x[list(kind.lengths)])
    if kind is FOURBAR:
        links.append(math.hypot(x[2] - x[0], x[3] - x[1]))  # the ground
    if min(links) < SHORTEST_LINK * target_size(target):
        return None
    e, feet = _errors(
        x[None, :], np.array([crossed]), target, closed, samples=2048, exact=True, kind=kind
    )
    if not np.all(np.isfinite(e[:, :2])):  # (back is NaN for an open target)
        return None
    lo_s, hi_s = _arc(feet[0], closed)
    fb: FourBar | SliderCrank
    try:
        if kind is SLIDER:
            # The line's direction as fitted may have turned past a full turn: the same
            # linkage, reported with its angle in [-π, π] (so are its crank range and scene).
            x = x.copy()
            x[2] = math.remainder(float(x[2]), 2 * math.pi)
            problem, full, th_lo, th_hi, mu, through = _core.synth_slider_info(x, lo_s, hi_s)
            fb = _linkage_of(x, crossed, kind)
            grashof = "crank-slider" if full else "rocker-slider"
        else:
            problem, full, th_lo, th_hi, mu, through = _core.synth_info(x, crossed, lo_s, hi_s)
            fb = _linkage_of(x, crossed, kind)
            grashof = cast(FourBar, fb).grashof()
        if problem is None and full and not closed:
            # A crank that turns fully is driven through the whole turn, not only the matched
            # part: its transmission angle counts over the turn (a candidate that read 53.5°
            # on its matched part came within 0.1° of a toggle elsewhere).
            whole = (
                _core.synth_slider_info(x, 0.0, 2 * math.pi, check_samples=2)
                if kind is SLIDER
                else _core.synth_info(x, crossed, 0.0, 2 * math.pi, check_samples=2)
            )
            mu = min(mu, whole[4])
    except LinkageError:
        return None
    if problem is not None:
        return None
    return Candidate(
        linkage=fb,
        error=float(e[0, 0]),
        rms=float(e[0, 1]),
        back=float(e[0, 2]),
        crank_range=_turned(th_lo, th_hi),
        full_turn=full,
        grashof=grashof,
        min_transmission=mu,
        through_limit=through,
        source=source,
        params=x.copy(),
        kind=kind.name,
    )


def _failed(
    c: Candidate[Any],
    full_turn: bool,
    min_transmission: float,
    lengths: tuple[float, float] | None,
    pivots: tuple[tuple[float, float], tuple[float, float]] | None,
) -> list[str]:
    """Return the names (:data:`CONSTRAINT_NAMES`) of the constraints ``c`` fails."""
    failed = []
    if full_turn and not c.full_turn:
        failed.append("full_turn")
    if c.min_transmission < min_transmission:
        failed.append("min_transmission")
    fb = c.linkage
    if lengths is not None:
        # The coupler triangle's sides to the point are links too (a foot bar): at most the
        # greatest length (a point may lie at a joint, so no least).
        links = _links(fb)
        if any(not (lengths[0] <= v <= lengths[1]) for v in links) or max(_arms(fb)) > lengths[1]:
            failed.append("lengths")
    if pivots is not None:
        (x0, y0), (x1, y1) = pivots
        if any(not (x0 <= px <= x1 and y0 <= py <= y1) for px, py in _pins(fb)):
            failed.append("pivots")
    return failed


def _kept(
    found: Sequence[Candidate[Any]],
    full_turn: bool,
    min_transmission: float,
    lengths: tuple[float, float] | None,
    pivots: tuple[tuple[float, float], tuple[float, float]] | None,
    removed: Candidates | None = None,
) -> tuple[list[Candidate[Any]], Candidates]:
    """Split ``found`` by the constraints.

    Return the candidates that meet them, and an empty :class:`Candidates` that says what the
    constraints removed; ``removed`` (an earlier search's result) adds its own.
    """
    ok: list[Candidate[Any]] = []
    counts: dict[str, int] = dict(removed.removed) if removed is not None else {}
    out = [removed.closest_removed] if removed is not None and removed.closest_removed else []
    for c in found:
        failed = _failed(c, full_turn, min_transmission, lengths, pivots)
        if not failed:
            ok.append(c)
            continue
        out.append(c)
        for name in failed:
            counts[name] = counts.get(name, 0) + 1
    closest = min(out, key=lambda c: c.error, default=None)
    fails = (
        () if closest is None else _failed(closest, full_turn, min_transmission, lengths, pivots)
    )
    counts = {k: counts[k] for k in CONSTRAINT_NAMES if k in counts}
    return ok, Candidates((), counts, closest, fails)


CLI_CONSTRAINTS = {
    "full_turn": "--full-turn",
    "min_transmission": "--min-transmission-deg",
    "lengths": "--lengths",
    "pivots": "--pivots",
    "refine": "--refine",
}
"""``linkage synth``'s options for :func:`path`'s constraints (and ``refine``)."""


def why_none(found: Candidates, names: dict[str, str], unit: str = "") -> tuple[str, str | None]:
    """Say why :func:`path` returned no candidate, naming the constraints by ``names``.

    Return the sentence and the constraint to blame (of :data:`CONSTRAINT_NAMES`: the first
    the closest removed fit fails), or None when no fit was valid at all. ``names`` maps
    :data:`CONSTRAINT_NAMES` and ``"refine"`` to what the caller calls them.

    Examples
    --------
    >>> from linkage.synthesis import Candidates, why_none
    >>> why_none(Candidates(), {})
    ('every linkage tried failed to assemble over its circuit or switched branch', None)
    """
    gone = found.closest_removed
    if gone is None:
        return "every linkage tried failed to assemble over its circuit or switched branch", None
    fails = found.closest_fails
    counts = ", ".join(f"{names[k]}: {n}" for k, n in found.removed.items())
    u = f" {unit}" if unit else ""
    # How far the closest fit is from each constraint it fails: how far to loosen.
    lk = gone.linkage
    links = _links(lk)
    values = {
        "full_turn": f"its crank rocks, {gone.grashof}",
        "min_transmission": f"μ {gone.min_transmission_deg:.1f}°",
        "lengths": f"links {min(links):.3g} … {max(*links, *_arms(lk)):.3g}{u}",
        "pivots": "pivots " + ", ".join(f"({x:.3g}, {y:.3g})" for x, y in _pins(lk)),
    }
    failed = [f"{names[k]} ({values[k]})" for k in fails]
    which = failed[0] if len(failed) == 1 else ", ".join(failed[:-1]) + " and " + failed[-1]
    return (
        f"every valid fit fails a constraint (fits failing {counts}); the closest, error "
        f"{gone.error:.3g}{u}, fails {which}: loosen {'it' if len(fails) == 1 else 'them'}, "
        f"or refine more atlas matches ({names.get('refine', 'refine')})",
        fails[0],
    )


def command(args: argparse.Namespace) -> int:
    """``linkage synth curve.csv``: print the candidates as a table with units."""
    if not 1 <= int(args.top) <= SYNTHESIS_TOP_MAX:
        raise LinkageError(f"--top must be between 1 and {SYNTHESIS_TOP_MAX}, got {args.top}")
    refine = int(getattr(args, "refine", 8))
    if not 0 <= refine <= SYNTHESIS_REFINE_MAX:
        raise LinkageError(f"--refine must be between 0 and {SYNTHESIS_REFINE_MAX}, got {refine}")
    mu = getattr(args, "min_transmission_deg", 0.0)
    if not 0 <= mu <= 90:
        raise LinkageError(f"--min-transmission-deg must be between 0 and 90, got {mu:g}")
    kind = cast(PathKind, getattr(args, "kind", "fourbar"))
    t0 = time.perf_counter()
    # Read once: the search takes the cleaned points, the table rounds to their size.
    target = _target(args.curve, not args.open)
    found = path(
        target,
        closed=not args.open,
        top=int(args.top),
        refine=refine,
        kind=kind,
        full_turn=bool(args.full_turn),
        min_transmission=math.radians(mu),
        lengths=getattr(args, "lengths", None),
        pivots=(
            None if getattr(args, "pivots", None) is None else (args.pivots[:2], args.pivots[2:])
        ),
        seed=getattr(args, "seed", 0),
        tol=getattr(args, "tol", 1e-3),
        atlas=args.atlas,
        progress=not args.quiet,
        accept=getattr(args, "accept", None),
    )
    took = time.perf_counter() - t0
    u = f" {args.units}" if args.units else ""
    what = {"fourbar": "four-bar", "slider-crank": "slider-crank", "any": "linkage"}[kind]
    if not found:
        # One line and status 2, as `linkage run` says it of a scene.
        why, _ = why_none(found, CLI_CONSTRAINTS, args.units or "")
        raise LinkageError(f"no valid {what} found for {args.curve} in {took:.1f} s: {why}")
    print(
        f"{len(found)} {what}(s) for {args.curve}, best first ({took:.1f} s; errors are the "
        f"largest / RMS distance of the target points to the coupler curve{u and ', in' + u}):"
    )
    size = target_size(target)

    def g(x: float) -> str:
        # Coordinates and lengths to 1e-5 of the target's size: an exact fit's round-off reads 0.
        return f"{rounded_to(x, size, 5):.4g}"

    # One table ranked as found; under "any" a column holds a four-bar's or a slider-crank's
    # number, named by both.
    tail = {
        "fourbar": ("C", "crank", "coupler", "rocker", "point (along, left)", "assembly"),
        "slider-crank": (
            "line (deg)",
            "crank",
            "coupler",
            "offset",
            "point (along, left)",
            "reach",
        ),
        "any": (
            "C | line (deg)",
            "crank",
            "coupler",
            "rocker | offset",
            "point (along, left)",
            "assembly | reach",
        ),
    }[kind]
    # A closed target's candidates also say how far their curve strays from the target's
    # polygon (a spur or a loop the points never asked for).
    back = (f"curve→polygon{u}",) if not args.open else ()
    head = (
        "#",
        f"error{u}",
        f"rms{u}",
        *back,
        "class",
        "crank range (deg)",
        "min μ (deg)",
        "O",
        *tail,
        "from",
    )
    rows: list[tuple[str, ...]] = [head]
    for rank, c in enumerate(found, 1):
        fb = c.linkage
        lo, hi = (round(math.degrees(v), 1) + 0.0 for v in c.crank_range)
        row = [
            str(rank),
            f"{c.error:.3g}",
            f"{c.rms:.3g}",
            *((f"{c.back:.3g}",) if not args.open else ()),
            c.grashof,
            f"{lo:.1f} … {hi:.1f}",
            f"{c.min_transmission_deg:.1f}",
            f"({g(fb.o[0])}, {g(fb.o[1])})",
        ]
        if isinstance(fb, SliderCrank):
            # Rounded first: an angle of -1e-12 rad reads 0.00, not -0.00.
            line = round(math.degrees(fb.angle), 2) + 0.0
            row += [f"{line:.2f}", g(fb.crank), g(fb.coupler), g(fb.offset)]
            row += [f"({g(fb.point[0])}, {g(fb.point[1])})", f"slider {fb.reach}"]
        else:
            row += [f"({g(fb.c[0])}, {g(fb.c[1])})", g(fb.crank), g(fb.coupler)]
            row += [g(fb.rocker), f"({g(fb.point[0])}, {g(fb.point[1])})", fb.assembly]
        # The stage that found it (candidates.csv's `source`): equation, atlas, global, cognate.
        row.append(c.source)
        rows.append(tuple(row))
    # Notes: a candidate near a change point, and one ranked after the rest for a link longer
    # than LONG_LINK sizes (max_link: a fit far better than those above it had read as a
    # sorting mistake).
    notes = []
    for c in found:
        note = []
        near = change_point_gap(c, size)
        if near is not None:
            note.append(f"{near[0]:.1e}{u} from a change point: can flip branch")
        k = long_link(c, size)
        if k is not None and getattr(args, "lengths", None) is None:
            note.append(f"link {k:.0f}× size: ranked after")
        notes.append("; ".join(note))
    if any(notes):
        head = (*head, "note")
        rows = [(*rows[0], "note")] + [(*r, n) for r, n in zip(rows[1:], notes)]
    widths = [max(len(r[i]) for r in rows) for i in range(len(head))]
    for r in rows:
        print("  ".join(cell.rjust(w) for cell, w in zip(r, widths)).rstrip())
    return 0


_T = TypeVar("_T")


def timed(fn: Callable[..., _T], *args: Any, **kw: Any) -> tuple[_T, float]:
    """``fn(*args, **kw)`` and its wall time in seconds (for the benchmark and CLI)."""
    t0 = time.perf_counter()
    out = fn(*args, **kw)
    return out, time.perf_counter() - t0
