"""Reading and cleaning a synthesis target: points from a CSV file or an array, and its size."""

from __future__ import annotations

import math
import os
import re
from pathlib import Path

import numpy as np
from numpy.typing import ArrayLike

from linkage._core import LinkageError
from linkage._shared.arrays import as_real_array
from linkage._shared.size import pow2 as _pow2
from linkage._shared.size import rms_size
from linkage.synthesis.kinds import EXACT, Float2D
from linkage.synthesis.limits import POINTS_MAX

__all__ = [
    "MIN_POINTS",
    "POINTS_FILE_MAX",
    "SMALLEST_EXTENT",
    "clean_target",
    "read_points",
    "rounded_to",
    "target_size",
]

MIN_POINTS = 5
"""Fewest target points: a four-bar's coupler curve has five shape parameters beyond placement."""


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
