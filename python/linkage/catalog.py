"""The straight-line linkages of the source documents (``docs/domain.md``), ready to sweep.

Four-bars are placed with the crank pivot ``O`` at the origin and the rocker pivot ``C`` on the +x
axis (lengths in mm, thesis 1 chapter 1 after Norton); multi-loop linkages are
:class:`~linkage.Mechanism` objects whose ``trace`` is the straight-line point.

>>> import linkage
>>> linkage.catalog.hoecken().grashof()
'crank-rocker'
>>> [round(float(x), 1) for x in linkage.catalog.evans_b().input_limits()]
[-1.4, 1.4]
>>> linkage.catalog.get("nope")
Traceback (most recent call last):
...
linkage.LinkageError: unknown catalogue linkage 'nope'; choose from watt, roberts, ...
"""

from __future__ import annotations

import hashlib
import json
import math
import os
import re
import stat
import sys
from collections.abc import Callable
from dataclasses import asdict, dataclass, fields, replace
from pathlib import Path

import numpy as np

from linkage import _core
from linkage._core import LinkageError
from linkage._shared.arrays import as_count, as_finite, check_memory
from linkage._shared.cache_dir import cache_dir
from linkage._shared.cache_files import core_identity
from linkage._shared.files import read_json, sweep_stale, write_atomic
from linkage._shared.version import __version__
from linkage.drives.cam import leg_lift
from linkage.kinematics.fourbar import FourBar
from linkage.kinematics.mechanism import Mechanism
from linkage.motion.geometry import straightness
from linkage.walking.legs import family
from linkage.walking.walker import Leg, Walker, gait_phases

__all__ = [
    "CACHE_FORMAT",
    "FOUR_BARS",
    "MULTI_LOOP",
    "TABLE_SAMPLES",
    "WALKERS",
    "Figures",
    "cache_dir",
    "chebyshev",
    "check_count",
    "evans_a",
    "evans_b",
    "evans_c",
    "figures",
    "format_table",
    "get",
    "hart",
    "hexapod_tripod",
    "hoecken",
    "hoecken_guided",
    "hoecken_pantograph",
    "jansen",
    "klann",
    "names",
    "peaucellier",
    "quadruped_hoecken",
    "roberts",
    "table",
    "watt",
]

FOUR_BARS: tuple[str, ...] = tuple(_core.catalog.FOUR_BARS)
"""Names of the catalogue's four-bars (the core's catalogue)."""
MULTI_LOOP: tuple[str, ...] = tuple(_core.catalog.MULTI_LOOP)
"""Names of the catalogue's multi-loop linkages (the core's catalogue)."""


def _four_bar(name: str) -> FourBar:
    return FourBar._from_core(_core.catalog.four_bar(name))


def _linkage(name: str, scale: float = 2.0) -> Mechanism:
    found = _core.catalog.linkage(name, as_finite(scale, "scale"))
    return Mechanism._from_core(found.mechanism, found.joint_names, found.trace)


def watt() -> FourBar:
    """Watt: ground 40, rockers 20, coupler 10, midpoint trace (triple rocker).

    Returns
    -------
    FourBar
        A new linkage (mm), crank pivot ``O`` at the origin, rocker pivot ``C`` on the +x axis.

    Examples
    --------
    The crank rocks between its toggles; beyond them a sample is NaN:

    >>> import linkage
    >>> fb = linkage.catalog.watt()
    >>> fb.grashof(), [round(float(x), 4) for x in fb.input_limits()]
    ('triple-rocker', [-0.8128, 0.8128])
    >>> s = fb.sweep([0.0, 1.0])
    >>> s.valid, s.point[1]
    (array([ True, False]), array([nan, nan]))
    """
    return _four_bar("watt")


def roberts() -> FourBar:
    """Roberts: ground 40, rockers 40, coupler 20, apex of the isosceles triangle AP = BP = 40.

    Returns
    -------
    FourBar
        A new linkage (mm), crank pivot ``O`` at the origin, rocker pivot ``C`` on the +x axis.

    Examples
    --------
    >>> import linkage
    >>> fb = linkage.catalog.roberts()
    >>> fb.grashof(), [round(x, 4) for x in fb.input_limits()]
    ('double-rocker', [0.5054, 1.6961])
    """
    return _four_bar("roberts")


def chebyshev() -> FourBar:
    """Chebyshev: ground 20, crossed rockers 25, coupler 10, midpoint trace (double rocker).

    Returns
    -------
    FourBar
        A new linkage (mm), crank pivot ``O`` at the origin, rocker pivot ``C`` on the +x axis.

    Examples
    --------
    >>> import linkage
    >>> fb = linkage.catalog.chebyshev()
    >>> fb.grashof(), fb.assembly, [round(x, 4) for x in fb.input_limits()]
    ('double-rocker', 'crossed', [0.6435, 1.7722])
    """
    return _four_bar("chebyshev")


def hoecken() -> FourBar:
    """Hoecken: ground 20, crank 10, coupler = rocker = 25, foot 50 along the coupler line.

    Returns
    -------
    FourBar
        A new linkage (mm), crank pivot ``O`` at the origin, rocker pivot ``C`` on the +x axis.

    Examples
    --------
    >>> import linkage
    >>> fb = linkage.catalog.hoecken()
    >>> fb.grashof(), fb.input_limits(), round(float(fb.sweep([0.0]).point[0, 1]), 6)
    ('crank-rocker', None, 48.989795)
    """
    return _four_bar("hoecken")


def evans_a() -> FourBar:
    """Evans A: 12 / 10 / 16 / 10.39, trace 26.9 along the coupler (input ≈ 27°…333°).

    Returns
    -------
    FourBar
        A new linkage (mm), crank pivot ``O`` at the origin, rocker pivot ``C`` on the +x axis.

    Examples
    --------
    >>> import linkage
    >>> fb = linkage.catalog.evans_a()
    >>> fb.grashof(), [round(x, 4) for x in fb.input_limits()]
    ('triple-rocker', [0.4832, 5.8])
    """
    return _four_bar("evans_a")


def evans_b() -> FourBar:
    """Evans B: 23.05 / 10 / 12 / 11.67, trace 15 along the coupler (input ≈ ±81°).

    Returns
    -------
    FourBar
        A new linkage (mm), crank pivot ``O`` at the origin, rocker pivot ``C`` on the +x axis.

    Examples
    --------
    >>> import linkage
    >>> fb = linkage.catalog.evans_b()
    >>> fb.grashof(), [round(x, 4) for x in fb.input_limits()]
    ('triple-rocker', [-1.4161, 1.4161])
    """
    return _four_bar("evans_b")


def evans_c() -> FourBar:
    """Evans C: 20 / 10 / 10 / 10, trace 10 beyond B on the coupler line (input ≈ ±75°).

    Returns
    -------
    FourBar
        A new linkage (mm), crank pivot ``O`` at the origin, rocker pivot ``C`` on the +x axis.

    Examples
    --------
    >>> import linkage
    >>> fb = linkage.catalog.evans_c()
    >>> fb.grashof(), [round(x, 4) for x in fb.input_limits()]
    ('triple-rocker', [-1.3181, 1.3181])
    """
    return _four_bar("evans_c")


def peaucellier() -> Mechanism:
    """Peaucellier–Lipkin inversor, whose point P runs on the exact line x = 40.

    D at the origin, crank pivot O at (15, 0), crank 15, arms DB = DC = 40, rhombus 20.

    Returns
    -------
    Mechanism
        A new linkage (mm) whose ``trace`` is the straight-line point.

    Examples
    --------
    >>> import numpy as np, linkage
    >>> linkage.catalog.peaucellier().sweep(np.linspace(-1, 1, 5)).point[:, 0]
    array([40., 40., 40., 40., 40.])
    """
    return _linkage("peaucellier")


def hart() -> Mechanism:
    """Hart's inversor (six links, seven revolutes); P runs on the exact line x = 7.5.

    Returns
    -------
    Mechanism
        A new linkage (mm) whose ``trace`` is the straight-line point.

    Examples
    --------
    The crank cannot reach every angle: at 0 the sample is NaN.

    >>> import linkage
    >>> m = linkage.catalog.hart()
    >>> s = m.sweep([0.0, 1.0])
    >>> m.trace, s.valid, s.point[1].round(4)
    ('P', array([False,  True]), array([ 7.5   , 13.7287]))
    """
    return _linkage("hart")


def hoecken_pantograph(scale: float = 2.0) -> Mechanism:
    """Hoecken linkage driving a pantograph that scales its foot path ``T`` by ``scale`` (> 1).

    The pantograph's pivot is Q = (20, 80); the output is ``P = Q + scale·(T − Q)``.

    Parameters
    ----------
    scale : float, default 2.0
        The pantograph's magnification (more than 1).

    Returns
    -------
    Mechanism
        A new linkage (mm) whose ``trace`` is ``P``.

    Raises
    ------
    LinkageError
        For a scale that is not finite or not more than 1.

    Examples
    --------
    >>> import linkage
    >>> linkage.catalog.hoecken_pantograph(2.0).sweep([0.0]).point
    array([[20.        , 17.97958971]])
    >>> linkage.catalog.hoecken_pantograph(1.0)
    Traceback (most recent call last):
    ...
    linkage.LinkageError: pantograph scale must be greater than 1, got 1
    """
    return _linkage("hoecken_pantograph", scale)


def jansen() -> Mechanism:
    """Theo Jansen's Strandbeest leg ("holy numbers"), whose foot F traces a flat-bottomed path.

    Crank 15 about the origin, frame pivot at (−38, −7.8), five dyads in sequence.

    Returns
    -------
    Mechanism
        A new linkage whose ``trace`` is the foot ``F``.

    Examples
    --------
    >>> import linkage
    >>> m = linkage.catalog.jansen()
    >>> m.joint_names, m.trace, m.mobility().degrees_of_freedom
    (('O', 'Q', 'A', 'B', 'C', 'D', 'E', 'F'), 'F', 1)
    """
    return _linkage("jansen")


def hoecken_guided() -> Mechanism:
    """Hoecken's four-bar with its coupler point guided by a hung dyad (Stephenson III six-bar).

    The reference of :mod:`linkage.legs`' ``guided`` family (:data:`linkage.legs.GUIDED_REF`):
    the foot ``F`` sits at the coupler point, so it draws thesis 1's Hoecken foot path, and the
    guide link swings with it.

    >>> import numpy as np, linkage
    >>> m = linkage.catalog.hoecken_guided()
    >>> th = np.linspace(0, 2 * np.pi, 13)
    >>> hoecken = linkage.catalog.hoecken()
    >>> bool(np.allclose(m.sweep(th).point, hoecken.sweep(th).point, atol=1e-12))
    True

    Returns
    -------
    Mechanism
        A new linkage whose ``trace`` is the foot ``F``.
    """
    fam = family("guided")
    m: Mechanism = fam.mechanism(fam.reference)
    return m


def klann() -> Mechanism:
    """Klann-type leg (Stephenson III six-bar), the reference of the ``klann`` leg family.

    The family is :mod:`linkage.legs`' ``klann``. Proportions after Bastien & Birglen (2022), not
    the patent's (see :data:`linkage.legs.KLANN_REF`); the foot is ``F``.

    Returns
    -------
    Mechanism
        A new linkage whose ``trace`` is the foot ``F``.

    Examples
    --------
    >>> import linkage
    >>> m = linkage.catalog.klann()
    >>> m.joint_names, m.trace, bool(m.sweep([0.0, 1.0]).valid.all())
    (('O', 'PA', 'PB', 'C', 'D', 'M', 'E', 'F'), 'F', True)
    """
    fam = family("klann")
    m: Mechanism = fam.mechanism(fam.reference)
    return m


def names() -> tuple[str, ...]:
    """Return every catalogue name: the four-bars, then the multi-loop linkages.

    Returns
    -------
    tuple of str
        The names :func:`get` takes.

    Examples
    --------
    >>> from linkage import catalog
    >>> catalog.names()[:4], catalog.names()[-2:]
    (('watt', 'roberts', 'chebyshev', 'hoecken'), ('hoecken_pantograph', 'jansen'))
    """
    return FOUR_BARS + MULTI_LOOP


def get(name: str) -> FourBar | Mechanism:
    """Build a catalogue linkage by name.

    Parameters
    ----------
    name : str
        One of :func:`names` (the pantograph at its default scale).

    Returns
    -------
    FourBar or Mechanism
        A new linkage.

    Raises
    ------
    LinkageError
        For an unknown name (the message lists the names).
    TypeError
        If ``name`` is not a str.

    Examples
    --------
    >>> from linkage import catalog
    >>> catalog.get("evans_b").input_limits() == catalog.evans_b().input_limits()
    True
    >>> catalog.get(3)
    Traceback (most recent call last):
    ...
    TypeError: name must be a str, got int
    """
    if not isinstance(name, str):
        raise TypeError(f"name must be a str, got {type(name).__name__}")
    if name in FOUR_BARS:
        return _four_bar(name)
    if name in MULTI_LOOP:
        return _linkage(name)
    raise LinkageError(f"unknown catalogue linkage {name!r}; choose from {', '.join(names())}")


@dataclass(frozen=True)
class Figures:
    """Straight-line figures of one catalogue linkage."""

    name: str
    grashof: str
    """Grashof class, or "multi-loop"."""
    input_range: tuple[float, float] | None
    """Crank angles between the toggles (radians), None for a full turn; for a multi-loop
    linkage the contiguous sampled interval that assembles around the straight part."""
    size: float
    """The linkage size: its longest link."""
    tolerance: float
    """The straightness tolerance used, ``rel_tol × size``."""
    straight_length: float
    """Length of the longest part of the traced path within ``tolerance`` of a line."""
    max_deviation: float
    """Largest distance of that part from its best-fit line."""
    speed_variation: float
    """``(max − min)/mean`` of the trace point's speed along that part at constant crank
    speed."""
    samples: int = 0
    """Samples per circuit (or per crank turn) the figures were computed at."""
    straight_length_error: float | None = None
    """Error estimate of :attr:`straight_length` (:func:`table`: its difference from the same
    figure at about half the samples), None when not estimated."""
    max_deviation_error: float | None = None
    """Error estimate of :attr:`max_deviation`, as :attr:`straight_length_error`."""
    speed_variation_error: float | None = None
    """Error estimate of :attr:`speed_variation`, as :attr:`straight_length_error`."""


def figures(rel_tol: float = 1e-3, samples: int = 20001) -> list[Figures]:
    """Compute each catalogue linkage's Grashof class, input range and straight part.

    The straight part of its trace is found within ``rel_tol`` of the linkage size (0.1 % by
    default): its length, deviation and speed variation at constant crank speed.

    Four-bars are traced over their whole circuit (:meth:`FourBar.circuit`); multi-loop
    linkages over one crank turn sampled ``samples`` times, where they assemble.

    Parameters
    ----------
    rel_tol : float, default 1e-3
        The straightness tolerance as a share of each linkage's longest link (positive).
    samples : int, default 20001
        Samples per circuit or crank turn (at least 3).

    Returns
    -------
    list of Figures
        One row per catalogue linkage, in :func:`names` order, without error estimates (see
        :func:`table`).

    Raises
    ------
    LinkageError
        For a ``rel_tol`` that is not positive and finite, or ``samples`` below 3.
    MemoryError
        When the samples would not fit in memory.

    Examples
    --------
    >>> import linkage
    >>> hoecken_row = linkage.catalog.figures(samples=2001)[3]
    >>> hoecken_row.name, round(hoecken_row.straight_length, 2), hoecken_row.tolerance
    ('hoecken', 16.14, 0.025)
    >>> linkage.catalog.figures(rel_tol=0)
    Traceback (most recent call last):
    ...
    linkage.LinkageError: rel_tol must be above 0 and below 1 (a fraction of the size), got 0.0
    """
    rel_tol = as_finite(rel_tol, "rel_tol")
    if not 0 < rel_tol < 1:  # within a whole size of a line, any path is "straight"
        raise LinkageError(
            f"rel_tol must be above 0 and below 1 (a fraction of the size), got {rel_tol}"
        )
    samples = as_count(samples, "samples", 3)
    # Per sample: angles, every joint's position and velocity, flags (Jansen has 8 joints).
    check_memory(samples * 8 * 80, f"catalogue figures at {samples} samples")
    rows = []
    for name in names():
        item = get(name)
        if isinstance(item, FourBar):
            size = max(item.ground, item.crank, item.coupler, item.rocker)
            s = item.circuit(samples)
            # The circuit repeats its first sample last: drop it to close the curve.
            path, vel, closed = s.point[:-1], s.velocity[:-1], True
            grashof, rng = item.grashof(), item.input_limits()
        else:
            theta = np.linspace(-np.pi, np.pi, samples)
            s = item.sweep(theta, omega=1.0, outputs=("point", "joints", "velocity"))
            size = _longest_link(item, s.joints)
            ok = s.valid
            full = bool(ok.all())
            path, vel = (s.point[:-1], s.velocity[:-1]) if full else (s.point, s.velocity)
            closed = full
            grashof = "multi-loop"
        tol = rel_tol * size
        part = straightness(path, tol, closed=closed, velocity=vel)
        if part is None:  # pragma: no cover - every catalogue linkage has a straight part
            raise LinkageError(f"{name}: no straight part within {tol}")
        if not isinstance(item, FourBar):
            rng = None if full else _run_around(theta, ok, int(part.indices[0]))
        rows.append(
            Figures(
                name=name,
                grashof=grashof,
                input_range=rng,
                size=size,
                tolerance=tol,
                straight_length=part.length,
                max_deviation=part.max_deviation,
                speed_variation=float(part.speed_variation or 0.0),
                samples=samples,
            )
        )
    return rows


# -- the `linkage catalog` table: fewer samples with an error estimate, cached -----------------

TABLE_SAMPLES = 20001
"""Samples per circuit of :func:`table`: each figure's error is estimated from a second run at
about half as many. With the O(n log² n) straight-part scan a cold table takes about 1.3 s
here (0.7 s of CPU); a cached one is read back without sweeping."""

CACHE_FORMAT = 2
"""Bumped whenever the cached table's content or meaning changes."""


def check_count(samples: int) -> int:
    """Return about half of ``samples``: the second resolution of the error estimates.

    The grid shares only its ends with theirs (``k − 1`` coprime to ``samples − 1``).

    Parameters
    ----------
    samples : int
        The first resolution.

    Returns
    -------
    int
        ``k``, at least 3.

    Examples
    --------
    >>> from linkage.catalog import check_count
    >>> check_count(4001), check_count(721), check_count(3)
    (2000, 360, 3)
    """
    k = max(3, (samples - 1) // 2 + 1)
    while k > 3 and math.gcd(k - 1, samples - 1) != 1:
        k -= 1
    return k


def _with_errors(fine: list[Figures], coarse: list[Figures]) -> list[Figures]:

    out = []
    for f, c in zip(fine, coarse):
        sv = abs(f.speed_variation - c.speed_variation)
        out.append(
            replace(
                f,
                straight_length_error=abs(f.straight_length - c.straight_length),
                max_deviation_error=abs(f.max_deviation - c.max_deviation),
                speed_variation_error=sv if math.isfinite(sv) else None,
            )
        )
    return out


CACHE_MAX = 1 << 20
"""Largest cached table read back, in bytes (the table is about 5 kB)."""

_CACHE_TEMP = re.compile(r"\.catalog-[0-9a-f]{32}\.json\.(\d+)(?:\.[A-Za-z0-9_]+)?\.tmp")
"""The cache's temporaries: ``linkage._files.write_atomic``'s (``.<name>.<pid>.<random>.tmp``)
and the former ``.<name>.<pid>.tmp``; group 1 is the pid of the process that wrote it."""


def _cache_key(rel_tol: float, samples: int, check: int) -> str:
    """Hash everything the table depends on.

    That is the package version and the compiled core's content
    (:func:`linkage._cache_files.core_identity`), the parameters and the catalogue's names.
    """
    text = json.dumps(
        [
            CACHE_FORMAT,
            str(__version__),
            core_identity(),
            repr(rel_tol),
            samples,
            check,
            list(names()),
        ]
    )
    return hashlib.sha256(text.encode()).hexdigest()[:32]


_FIELDS = {f.name: f.type for f in fields(Figures)}


def _read_cache(path: Path) -> list[Figures] | None:
    """Read the cached table at ``path``; None when absent, unreadable or not a table.

    It is read as :func:`linkage._files.read_json` reads (a regular file of at most
    :data:`CACHE_MAX` bytes, opened without blocking, nesting bounded), and every value is
    checked: a corrupt cache is ignored (and then rewritten).
    """
    try:
        data = read_json(path, CACHE_MAX, "catalogue cache")
    except LinkageError:
        return None
    if not isinstance(data, list):
        return None
    rows = [_cached_row(d) for d in data]
    if any(r is None for r in rows) or [r.name for r in rows if r] != list(names()):
        return None
    return [r for r in rows if r]


_TEXT = ("name", "grashof")
_NUMBERS = ("size", "tolerance", "straight_length", "max_deviation", "speed_variation")
_OPTIONAL = ("straight_length_error", "max_deviation_error", "speed_variation_error")


def _cached_row(d: object) -> Figures | None:
    """Return the row a cached JSON object ``d`` holds; None unless every field is valid."""
    if not isinstance(d, dict) or set(d) != set(_FIELDS):
        return None
    rng, n = d["input_range"], d["samples"]
    if (
        not all(isinstance(d[k], str) for k in _TEXT)
        or not all(_real(d[k]) for k in _NUMBERS)
        or not all(d[k] is None or _real(d[k]) for k in _OPTIONAL)
        or not (rng is None or (isinstance(rng, list) and len(rng) == 2 and all(map(_real, rng))))
        or isinstance(n, bool)
        or not isinstance(n, int)
        or not 3 <= n <= sys.maxsize
    ):
        return None
    return Figures(
        name=d["name"],
        grashof=d["grashof"],
        input_range=None if rng is None else (float(rng[0]), float(rng[1])),
        samples=n,
        **{k: float(d[k]) for k in _NUMBERS},
        straight_length_error=_opt(d["straight_length_error"]),
        max_deviation_error=_opt(d["max_deviation_error"]),
        speed_variation_error=_opt(d["speed_variation_error"]),
    )


def _real(x: object) -> bool:
    """Whether ``x`` is a JSON number (not a bool) a float can hold."""
    if isinstance(x, bool) or not isinstance(x, (int, float)):
        return False
    try:
        float(x)
    except OverflowError:
        return False
    return True


def _opt(x: object) -> float | None:
    return None if x is None else float(x)  # type: ignore[arg-type]


def _write_cache(path: Path, rows: list[Figures]) -> None:
    """Write the table to ``path`` inside the cache folder, atomically.

    Through :func:`linkage._files.write_atomic` (an exclusively created temporary renamed over
    ``path``: no planted link is followed), and only where ``path`` is absent or a regular file
    (this tool's: the name is its own): a link, a pipe, a device or a folder there is left as it
    is, and the table is only kept in memory. Any failure leaves the cache as it was.
    """
    try:
        info = os.lstat(path)
    except FileNotFoundError:
        pass
    except OSError:
        return
    else:
        if not stat.S_ISREG(info.st_mode):
            return
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        write_atomic(path, json.dumps([asdict(r) for r in rows], allow_nan=True))
    except OSError:
        pass


def table(rel_tol: float = 1e-3, samples: int = TABLE_SAMPLES, cache: bool = True) -> list[Figures]:
    """Compute :func:`figures` with error estimates, as ``linkage catalog`` shows them.

    Each figure's error is its difference from the same figure at :func:`check_count` samples. With
    ``cache``, the table is kept in :func:`cache_dir` under a hash of the version, the compiled core
    and the parameters (only that file is written; an unreadable or corrupt one is recomputed and
    rewritten, one that is not a regular file — a link, a pipe, a device — is left alone and the
    table computed; temporaries of runs killed while writing are removed).

    Parameters
    ----------
    rel_tol : float, default 1e-3
        As :func:`figures`.
    samples : int, default :data:`TABLE_SAMPLES`
        As :func:`figures`; the errors compare :func:`check_count` samples.
    cache : bool, default True
        Read and write the cached table.

    Returns
    -------
    list of Figures
        :func:`figures` with the ``*_error`` fields set.

    Raises
    ------
    LinkageError
        As :func:`figures`.

    Examples
    --------
    >>> import linkage
    >>> rows = linkage.catalog.table(samples=73, cache=False)
    >>> rows[0].name, rows[0].samples, rows[0].straight_length_error is not None
    ('watt', 73, True)
    """
    rel_tol = as_finite(rel_tol, "rel_tol")
    samples = as_count(samples, "samples", 3)
    check = check_count(samples)
    path = cache_dir() / f"catalog-{_cache_key(rel_tol, samples, check)}.json"
    if cache:
        sweep_stale(path.parent, _CACHE_TEMP)
        hit = _read_cache(path)
        if hit is not None:
            return hit
    rows = _with_errors(figures(rel_tol, samples), figures(rel_tol, check))
    if cache:
        _write_cache(path, rows)
    return rows


def _err(x: float | None, fmt: str) -> str:
    return "" if x is None else f" ±{x:{fmt}}"


def format_table(rows: list[Figures], rel_tol: float) -> list[str]:
    """Return the lines ``linkage catalog`` prints for ``rows`` (:func:`table`).

    Parameters
    ----------
    rows : list of Figures
        The table's rows.
    rel_tol : float
        The tolerance they were computed with (for the heading).

    Returns
    -------
    list of str
        A heading, the column titles, one line per row and the walker models.

    Examples
    --------
    >>> from linkage import catalog
    >>> rows = catalog.figures(samples=2001)[3:4]
    >>> for line in catalog.format_table(rows, 1e-3)[1:3]:
    ...     print(line)
    linkage  class         input (deg)  size  straight  max dev   speed var
    hoecken  crank-rocker  full turn    25    16.140    2.50e-02  4.1%
    """
    body = []
    for f in rows:
        if f.input_range is None:
            rng = "full turn"
        else:
            rng = f"{math.degrees(f.input_range[0]):.1f} … {math.degrees(f.input_range[1]):.1f}"
        if math.isfinite(f.speed_variation):
            var = f"{100 * f.speed_variation:.1f}%" + _err(
                None if f.speed_variation_error is None else 100 * f.speed_variation_error, ".1f"
            )
        else:
            var = (
                "unbounded (reaches a toggle)"
                if math.isinf(f.speed_variation)
                else "undefined (stands still)"
            )
        body.append(
            (
                f.name,
                f.grashof,
                rng,
                f"{f.size:g}",
                f"{f.straight_length:.3f}" + _err(f.straight_length_error, ".3f"),
                f"{f.max_deviation:.2e}",
                var,
            )
        )
    head = ("linkage", "class", "input (deg)", "size", "straight", "max dev", "speed var")
    widths = [max(len(r[i]) for r in [head, *body]) for i in range(len(head))]
    n = rows[0].samples if rows else 0
    lines = [
        f"straight part: longest run within {rel_tol:g} × size of a line (mm); "
        f"{n} samples per circuit, ± the difference at {check_count(n)}"
    ]
    for r in [head, *body]:
        lines.append("  ".join(c.ljust(w) for c, w in zip(r, widths)).rstrip())
    lines.append(f"walkers: {', '.join(WALKERS)}")
    return lines


def _run_around(theta: np.ndarray, ok: np.ndarray, k: int) -> tuple[float, float]:
    """Return the contiguous interval of assembling samples that contains sample ``k``."""
    lo = hi = k
    while lo > 0 and ok[lo - 1]:
        lo -= 1
    while hi < len(ok) - 1 and ok[hi + 1]:
        hi += 1
    return float(theta[lo]), float(theta[hi])


def _longest_link(m: Mechanism, joints: np.ndarray) -> float:
    """Longest distance between two joints of one moving link, at the first valid sample."""
    row = joints[np.flatnonzero(np.isfinite(joints[:, :, 0]).all(axis=1))[0]]
    return float(m._core.longest_link(np.ascontiguousarray(row, dtype=np.float64)))


def quadruped_hoecken() -> Walker:
    """Thesis 1's quadruped: four Hoecken legs (mm) in vertical planes.

    Each foot is on a vertical bar 100 mm below the coupler point (the prototype's guided legs),
    legs A (left front), B (right front), C (left hind), D (right hind) at x = ±70, y = ±50 mm,
    diagonal pairs A & D and B & C in antiphase, 20 mm square pads (the widened feet), centre of
    gravity at the centre. Body dimensions are this model's assumption; the source gives the legs.

    Returns
    -------
    Walker
        A new walker (mm) in the diagonal gait.

    Examples
    --------
    >>> import linkage
    >>> q = linkage.catalog.quadruped_hoecken()
    >>> [leg.name for leg in q.legs], q.leg_labels()
    (['A', 'B', 'C', 'D'], ('L1', 'R1', 'L2', 'R2'))
    """
    legs = []
    phases = gait_phases("diagonal", ["A", "B", "C", "D"])
    for (name, x, y), phase in zip(
        [("A", 70.0, 50.0), ("B", 70.0, -50.0), ("C", -70.0, 50.0), ("D", -70.0, -50.0)], phases
    ):
        legs.append(
            Leg(
                name,
                hoecken(),
                mount=(x - 20.0, y, 0.0),
                phase=float(phase),
                foot_offset=(0.0, -100.0),
                pad=20.0,
            )
        )
    return Walker(legs, cg=(0.0, 0.0), ground_tol=0.1)


def hexapod_tripod() -> Walker:
    """Thesis 2's hexapod (m): six Hoecken legs in the horizontal plane, in a tripod gait.

    Each leg is the Hoecken four-bar (0.020 / 0.010 / 0.025 / 0.025, foot 0.050 along the coupler),
    the foot lifted 1.4 mm by a simple-harmonic cam during the half turn off the straight part;
    tripod gait {L1, R2, L3} against {R1, L2, R3}. Legs at x = 0.06, 0, −0.06 m and 0.02 m either
    side of the midline, 5 mm pads, centre of gravity at the centre (the body layout is this model's
    assumption).

    Returns
    -------
    Walker
        A new walker (m) in the tripod gait.

    Examples
    --------
    >>> import linkage
    >>> h = linkage.catalog.hexapod_tripod()
    >>> h.leg_labels()
    ('L1', 'L2', 'L3', 'R1', 'R2', 'R3')
    >>> [round(abs(float(p)), 6) for p in h.phases]     # {L1, R2, L3} against {R1, L2, R3}
    [0.0, 3.141593, 0.0, 3.141593, 0.0, 3.141593]
    """
    lift = leg_lift(0.0014)  # the cam's lift (linkage.cam.leg_lift), in m
    names = ["L1", "L2", "L3", "R1", "R2", "R3"]
    phases = gait_phases("tripod", names)
    legs = []
    for name, phase in zip(names, phases):
        x = {"1": 0.06, "2": 0.0, "3": -0.06}[name[1]]
        right = name[0] == "R"
        legs.append(
            Leg(
                name,
                FourBar(ground=0.020, crank=0.010, coupler=0.025, rocker=0.025, point=(0.050, 0.0)),
                mount=(x - 0.020, -0.02 if right else 0.02, 0.0),
                phase=float(phase),
                plane="horizontal",
                mirror=right,
                lift=lift,
                pad=0.005,
            )
        )
    return Walker(legs, cg=(0.0, 0.0), ground_tol=1e-5)


WALKERS: dict[str, Callable[[], Walker]] = {
    "quadruped_hoecken": quadruped_hoecken,
    "hexapod_tripod": hexapod_tripod,
}
"""The walker models, by the name a scene's ``[walker] model`` gives: the one list of them."""
