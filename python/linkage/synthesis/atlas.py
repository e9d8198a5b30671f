"""Atlases of normalised linkages and the descriptors of their curves.

Building, saving, loading and checking an :class:`Atlas`, and the default atlases kept in the
cache folder.
"""

from __future__ import annotations

import hashlib
import json
import os
import re
import stat
import sys
import warnings
from collections.abc import Iterable
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Union, cast

import numpy as np
from numpy.typing import NDArray

from linkage import _core
from linkage._core import LinkageError
from linkage._shared.arrays import as_count
from linkage._shared.cache_dir import cache_dir
from linkage._shared.cache_files import core_identity, read_npy
from linkage._shared.choices import AtlasKind, PathKind
from linkage._shared.files import read_json, sweep_stale
from linkage._shared.progress import Bar
from linkage._shared.version import __version__
from linkage.synthesis.kinds import (
    _ARC_KIND,
    _ENTRY_WIDTH,
    _KIND,
    FOURBAR,
    SLIDER,
    SLIDER_ARCS,
    _atlas_kind,
    _Kind,
    _kind,
    _threads,
)

__all__ = [
    "ATLAS_FILES",
    "ATLAS_FORMAT",
    "ATLAS_HARMONICS_MAX",
    "ATLAS_META_MAX",
    "ATLAS_SAMPLES_MAX",
    "Atlas",
    "AtlasArg",
    "atlas_kinds",
    "default_atlas",
    "is_cached",
    "missing_atlases",
]

ATLAS_FORMAT = 3
"""Bumped whenever the stored atlas's content or meaning changes."""


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

_ARC_FRACTIONS = len(_core.synthesis.ARC_FRACTIONS)  # an arc entry's last column indexes them

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
            desc, params, _ = _core.synthesis.build_arc_atlas(n, h, m, 8, _threads(threads), slider)
            return cls(desc, params, h, m, k.arcs, 8)
        build = _core.synthesis.build_atlas if k is FOURBAR else _core.synthesis.build_slider_atlas
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
        return _core.synthesis.nearest_entries(
            self.descriptors, q, as_count(k, "k"), _threads(threads)
        )


Atlas.__module__ = "linkage.synthesis"  # as before the split: pickles and reprs name it so
# Its doctests are run here: doctest looks for a class in the module the class names.
__test__ = {"Atlas": Atlas}


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
