"""The search's checkpoint: the optimiser's state as plain arrays, never a pickle.

A checkpoint is a ``.npz`` archive (uncompressed ``zip`` of ``.npy`` arrays) written by
:func:`save` after every generation through :func:`linkage._files.write_atomic`, and read by
:func:`load` through :func:`linkage._files.read_bytes` (a regular file, size capped by the
study). Nothing in it can run code: the archive and every array header are parsed here (no
object arrays, no pickles, exact dtypes, sizes checked against the bytes before an array is
made), and the JSON ``meta`` member holds plain numbers and strings.

It holds what NSGA-II needs to go on exactly as an uninterrupted run would:

- ``x``, ``figures``: every candidate evaluated so far and its figures (the front is theirs);
- ``pop_index``: the surviving population, as rows of ``x`` (its objectives and constraints
  are recomputed from the figures, bit for bit as the search computed them);
- ``pop_rank``, ``pop_crowding``, ``pop_gen``: the survivors' rank and crowding distance (the
  tournaments compare them) and the generation each was born in;
- ``meta``: magic, version, the study's fingerprint, the generation, and the random states
  (pymoo's own generator, and the process-wide ``random`` and ``numpy.random`` generators for
  pymoo releases that draw from those: :func:`linkage.design.search._uses_global_rng`).

Every failure to read or check one is a :class:`LinkageError` naming the file.
"""

from __future__ import annotations

import contextlib
import io
import json
import math
import os
import random
import re
import signal
import stat
import threading
import time
import zipfile
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from linkage._core import LinkageError
from linkage._shared.cache_files import npy_header
from linkage._shared.files import (
    json_depth,
    read_bytes,
    sweep_stale,
    temp_name_pattern,
    write_atomic,
)
from linkage._shared.report_folder import STOP_SIGNALS
from linkage.design.limits import Study
from linkage.walking.legs import FIGURES, family

__all__ = ["MAGIC", "VERSION", "Saved", "load", "restore", "save", "size_limit", "sweep"]

Array = NDArray[np.float64]

MAGIC = "linkage-design-checkpoint"
VERSION = 2
"""Version 1 was a pickle (earlier releases): it is refused, never unpickled."""

_META_LIMIT = 1 << 20
"""The most bytes the JSON ``meta`` member may hold (a few KiB in practice)."""

# member -> (dtype, number of dimensions)
_MEMBERS: dict[str, tuple[np.dtype[Any], int]] = {
    "meta": (np.dtype("u1"), 1),
    "x": (np.dtype("<f8"), 2),
    "figures": (np.dtype("<f8"), 2),
    "pop_index": (np.dtype("<i8"), 1),
    "pop_rank": (np.dtype("<i8"), 1),
    "pop_crowding": (np.dtype("<f8"), 1),
    "pop_gen": (np.dtype("<i8"), 1),
}

_ABSENT_RANK = -1
"""``pop_rank`` of a survivor pymoo gave no rank (its crowding is then NaN)."""


@dataclass
class Saved:
    """A checked checkpoint: the candidates so far and the optimiser's state."""

    generation: int
    x: Array
    figures: Array
    pop_index: NDArray[np.int64]
    pop_rank: NDArray[np.int64]
    pop_crowding: Array
    pop_gen: NDArray[np.int64]
    rng: dict[str, Any] | None
    global_rng: dict[str, Any] | None


def size_limit(study: Study) -> int:
    """Return the most bytes a checkpoint of ``study`` can take (a larger file is refused).

    Every candidate of the budget with its figures, the population's state, and room for the
    archive's headers and the ``meta`` member.

    Examples
    --------
    >>> from linkage.design.checkpoint import size_limit
    >>> from linkage.design.search import Study
    >>> size_limit(Study(population=4, budget=8))
    2102400
    """
    params = len(family(study.family).params)
    rows = study.generations * study.population
    return 8 * rows * (params + len(FIGURES)) + 32 * study.population + 2 * _META_LIMIT + 4096


def sweep(path: Path) -> list[str]:
    """Remove the checkpoint temporaries of processes that died (kill -9) beside ``path``.

    Those of :func:`linkage._files.write_atomic` and the ``..<name>.partial-<pid>`` files of
    earlier releases; a live process's temporaries, links and anything else are left alone.
    Returns the names removed.
    """
    folder = path.parent if str(path.parent) else Path(".")
    old = re.compile(re.escape(f".{path.name}.partial-") + r"(\d+)")
    return sweep_stale(folder, temp_name_pattern(path.name)) + sweep_stale(folder, old)


def save(
    path: Path,
    study: Study,
    algorithm: Any,
    x: Array,
    figures: Array,
    generation: int,
    global_rng: bool,
) -> None:
    """Write the checkpoint of ``algorithm`` after ``generation`` atomically to ``path``.

    Ctrl-C, SIGTERM and SIGHUP wait until it is written (then they stop the search as
    usual): the generation just evaluated is kept, and no temporary is left half written.

    ``x`` and ``figures`` are every candidate so far. The population is stored as rows of
    ``x``: each survivor carries its row as ``candidate`` (set by the search as it evaluates).
    ``global_rng`` also stores the process-wide generators' states (pymoo releases that draw
    from them).
    """
    pop = algorithm.pop
    index = np.array([int(ind.get("candidate")) for ind in pop], dtype="<i8")
    rank = np.array(
        [_ABSENT_RANK if (v := ind.get("rank")) is None else int(v) for ind in pop], dtype="<i8"
    )
    crowding = np.array(
        [math.nan if (v := ind.get("crowding")) is None else float(v) for ind in pop], dtype="<f8"
    )
    born = np.array([int(ind.get("n_gen") or 0) for ind in pop], dtype="<i8")
    state = getattr(algorithm, "random_state", None)
    meta = {
        "magic": MAGIC,
        "version": VERSION,
        "fingerprint": study.fingerprint(),
        "generation": generation,
        "rng": state.bit_generator.state if isinstance(state, np.random.Generator) else None,
        "global_rng": _global_states() if global_rng else None,
    }
    buf = io.BytesIO()
    np.savez(
        buf,
        meta=np.frombuffer(json.dumps(meta).encode(), dtype="u1"),
        x=np.ascontiguousarray(x, dtype="<f8"),
        figures=np.ascontiguousarray(figures, dtype="<f8"),
        pop_index=index,
        pop_rank=rank,
        pop_crowding=crowding,
        pop_gen=born,
    )
    with _signals_deferred():
        write_atomic(path, buf.getvalue())


@contextlib.contextmanager
def _signals_deferred() -> Iterator[None]:
    """Hold Ctrl-C, SIGTERM and SIGHUP until the block is done, then deliver them.

    Unlike ignoring them, a signal that comes meanwhile is not lost. Main thread only
    (elsewhere Python delivers no signals).
    """
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    caught: list[int] = []

    def note(signum: int, frame: object) -> None:
        caught.append(signum)

    previous: dict[int, Any] = {}
    with contextlib.suppress(ValueError, OSError):
        for signum in (signal.SIGINT, *STOP_SIGNALS):
            previous[signum] = signal.signal(signum, note)
    try:
        yield
    finally:
        for signum, was in previous.items():
            signal.signal(signum, was if was is not None else signal.SIG_DFL)
        for signum in dict.fromkeys(caught):
            signal.raise_signal(signum)


def load(path: Path, study: Study) -> Saved | None:
    """Read and check the checkpoint at ``path`` for ``study``; None when there is none.

    Raises
    ------
    LinkageError
        Naming ``path``: a link, not a regular file, too large, not a checkpoint (a pickle of
        an earlier release included), another study's, or any array or number out of place.
    """
    if not os.path.lexists(path):
        return None
    if stat.S_ISLNK(os.lstat(path).st_mode):
        raise LinkageError(
            f"{path}: the checkpoint is a symbolic link; refusing to read or replace it "
            f"(remove it or choose another --checkpoint)"
        )
    data = read_bytes(path, size_limit(study), "design checkpoint")
    if data[:1] == b"\x80":
        raise LinkageError(
            f"{path}: a checkpoint of an earlier linkage release (a pickle, which could run "
            f"code) is never read; remove it to start the search afresh, or choose another "
            f"--checkpoint (nothing was overwritten)"
        )
    try:
        arrays = _archive(data)
        meta = _meta(arrays)
    except _Bad as exc:
        raise LinkageError(
            f"{path} is not a linkage design checkpoint ({exc}); refusing to overwrite it "
            f"(remove it or choose another --checkpoint)"
        ) from None
    try:
        return _check(arrays, meta, study)
    except _Bad as exc:
        raise LinkageError(
            f"{path}: a damaged design checkpoint ({exc}); remove it or choose another "
            f"--checkpoint (nothing was overwritten)"
        ) from None
    except _Other as exc:
        raise LinkageError(f"{path} is the checkpoint of {exc}; {_ADVICE}") from None


_ADVICE = "remove it or choose another --checkpoint"


class _Bad(Exception):
    """A damaged checkpoint."""


class _NotOne(_Bad):
    """A file that is not a checkpoint."""


class _Other(Exception):
    """A checkpoint of another study or release."""


def _archive(data: bytes) -> dict[str, NDArray[Any]]:
    """Parse the ``.npz`` archive ``data`` into its arrays, checked before any is made."""
    try:
        with zipfile.ZipFile(io.BytesIO(data)) as z:
            infos = z.infolist()
            names = sorted(i.filename for i in infos)
            want = sorted(f"{k}.npy" for k in _MEMBERS)
            if names != want:
                raise _Bad(f"members {names[:10]}, not {want}")
            out: dict[str, NDArray[Any]] = {}
            for info in infos:
                if info.compress_type != zipfile.ZIP_STORED or info.flag_bits & 0x1:
                    raise _Bad(f"{info.filename} is compressed or encrypted")
                if info.file_size > len(data) or info.compress_size > len(data):
                    raise _Bad(f"{info.filename} claims more bytes than the file holds")
                name = info.filename[: -len(".npy")]
                out[name] = _npy(z.read(info), *_MEMBERS[name], name)
            return out
    except _Bad:
        raise
    except (zipfile.BadZipFile, zipfile.LargeZipFile, ValueError, OSError, EOFError) as exc:
        raise _Bad(f"not a readable archive: {exc}") from None
    except (RuntimeError, NotImplementedError, KeyError, TypeError) as exc:
        raise _Bad(f"not a readable archive: {type(exc).__name__}: {exc}") from None


def _npy(raw: bytes, dtype: np.dtype[Any], ndim: int, name: str) -> NDArray[Any]:
    """Parse one ``.npy`` member: its header's dtype and shape must fit the bytes after it."""
    try:
        shape, fortran, got, offset = npy_header(io.BytesIO(raw))
    except ValueError as exc:
        raise _Bad(f"{name}: not an array ({exc})") from None
    if got != dtype or fortran or len(shape) != ndim:
        raise _Bad(f"{name}: {got} {'F-ordered ' if fortran else ''}{shape}, not {ndim}-D {dtype}")
    count = math.prod(shape)
    if count * dtype.itemsize != len(raw) - offset:
        raise _Bad(f"{name}: shape {shape} does not fit its {len(raw) - offset} bytes")
    return np.frombuffer(raw, dtype=dtype, count=count, offset=offset).reshape(shape)


def _meta(a: dict[str, NDArray[Any]]) -> dict[str, Any]:
    """Return the ``meta`` member's JSON object if it has the magic (else :class:`_NotOne`)."""
    if len(a["meta"]) > _META_LIMIT:
        raise _Bad(f"meta of {len(a['meta'])} bytes")
    try:
        text = a["meta"].tobytes().decode("utf-8")
        if json_depth(text) > 8:
            raise _Bad("meta nests too deep")
        meta = json.loads(text)
    except (UnicodeDecodeError, ValueError, RecursionError) as exc:
        raise _Bad(f"meta is not JSON: {exc}") from None
    if not isinstance(meta, dict) or meta.get("magic") != MAGIC:
        raise _NotOne("no magic")
    return meta


def _check(a: dict[str, NDArray[Any]], meta: dict[str, Any], study: Study) -> Saved:
    """Check the arrays and the meta of a checkpoint against ``study``."""
    if meta.get("version") != VERSION:
        raise _Other(f"another linkage release (version {meta.get('version')!r}, not {VERSION})")
    if meta.get("fingerprint") != study.fingerprint():
        raise _Other(
            "a different study (family, bounds, objectives, constraints, population or seed "
            "changed, or an earlier version's first population)"
        )
    said: Any = meta.get("generation")
    if not _int(said) or not 1 <= said <= study.generations:
        raise _Bad(f"generation {said!r}, not 1 to {study.generations}")
    gen = int(said)
    fam = family(study.family)
    x, figs = a["x"], a["figures"]
    n = len(x)
    if x.shape[1:] != (len(fam.params),) or figs.shape != (n, len(FIGURES)):
        raise _Bad(f"candidates {x.shape} and figures {figs.shape} for {len(fam.params)} params")
    if not gen <= n <= gen * study.population:
        raise _Bad(f"{n} candidates after {gen} generations of {study.population}")
    xl, xu = study.box()
    if not (np.isfinite(x).all() and ((xl <= x) & (x <= xu)).all()):
        raise _Bad("a candidate outside the study's bounds")
    index, rank, crowd, born = a["pop_index"], a["pop_rank"], a["pop_crowding"], a["pop_gen"]
    m = len(index)
    if not 1 <= m <= study.population or not len(rank) == len(crowd) == len(born) == m:
        raise _Bad(f"a population of {m} (ranks {len(rank)}, crowding {len(crowd)})")
    if not ((0 <= index) & (index < n)).all():
        raise _Bad("a survivor that is no candidate")
    absent = rank == _ABSENT_RANK
    if not ((rank >= 0) | absent).all() or (rank > 2 * study.population).any():
        raise _Bad("a rank out of range")
    if not (absent == np.isnan(crowd)).all() or (crowd[~absent] < 0).any():
        raise _Bad("a crowding distance out of range")
    if not ((1 <= born) & (born <= gen)).all():
        raise _Bad("a survivor born after the checkpoint's generation")
    return Saved(
        generation=gen,
        x=x,
        figures=figs,
        pop_index=index,
        pop_rank=rank,
        pop_crowding=crowd,
        pop_gen=born,
        rng=_dict_or_none(meta.get("rng"), "rng"),
        global_rng=_dict_or_none(meta.get("global_rng"), "global_rng"),
    )


def _int(v: Any) -> bool:
    return isinstance(v, int) and not isinstance(v, bool)


def _dict_or_none(v: Any, what: str) -> dict[str, Any] | None:
    if v is not None and not isinstance(v, dict):
        raise _Bad(f"{what} is not an object")
    return v


def restore(path: Path, saved: Saved, algorithm: Any, f: Array, g: Array) -> None:
    """Put the checked state ``saved`` into ``algorithm`` (set up for the study, not yet run).

    The population is rebuilt from its rows of the candidates, with ``f`` and ``g`` its
    objectives and constraints (the search recomputes them from the survivors' figures, bit for
    bit as it did); the generation counter, the optimum, the termination's progress and the
    random states are set as the uninterrupted run left them.

    Raises
    ------
    LinkageError
        Naming ``path``: a random state that does not fit the generator.
    """
    from pymoo.core.population import Population  # type: ignore[import-untyped]  # noqa: PLC0415

    pop_x = np.array(saved.x[saved.pop_index], dtype=float)
    pop = Population.new("X", pop_x)
    pop.set("F", f, "G", g)
    survivors = zip(pop, saved.pop_index, saved.pop_rank, saved.pop_crowding, saved.pop_gen)
    for ind, k, rank, crowd, born in survivors:
        ind.set("n_gen", int(born))
        ind.set("n_iter", int(born))
        ind.set("candidate", int(k))
        if rank != _ABSENT_RANK:
            ind.set("rank", int(rank))
            ind.set("crowding", np.float64(crowd))
    algorithm.pop = pop
    algorithm.is_initialized = True
    algorithm.start_time = time.time()
    algorithm.n_iter = saved.generation
    algorithm._set_optimum()
    algorithm.termination.update(algorithm)
    algorithm.n_iter = saved.generation + 1
    state = getattr(algorithm, "random_state", None)
    try:
        if saved.rng is not None:
            # Checked whatever this pymoo draws from (0.6.1, the last for Python 3.9, uses the
            # global generators and would otherwise ignore it): set on a fresh bit generator.
            kind = getattr(np.random, str(saved.rng.get("bit_generator")), None)
            if not (isinstance(kind, type) and issubclass(kind, np.random.BitGenerator)):
                raise ValueError(f"no bit generator {saved.rng.get('bit_generator')!r}")
            kind().state = saved.rng
        if isinstance(state, np.random.Generator):
            if (
                saved.rng is None
                or saved.rng.get("bit_generator") != type(state.bit_generator).__name__
            ):
                raise ValueError(f"no state for pymoo's {type(state.bit_generator).__name__}")
            state.bit_generator.state = saved.rng
        if saved.global_rng is not None:
            _set_global_states(saved.global_rng)
    except (ValueError, TypeError, KeyError, OverflowError, IndexError) as exc:
        raise LinkageError(
            f"{path}: a damaged design checkpoint (random state: {exc}); {_ADVICE} "
            f"(nothing was overwritten)"
        ) from None


def _global_states() -> dict[str, Any]:
    version, key, gauss = random.getstate()
    name, mt, pos, has_gauss, cached = np.random.get_state(legacy=True)  # noqa: NPY002
    return {
        "random": [version, list(key), gauss],
        "numpy": [name, [int(v) for v in mt], int(pos), int(has_gauss), float(cached)],
    }


def _set_global_states(s: dict[str, Any]) -> None:
    """Set the process-wide generators from :func:`_global_states`' output, checked."""
    version, key, gauss = s["random"]
    if (
        not _int(version)
        or not isinstance(key, list)
        or len(key) != 625
        or not all(_int(v) and 0 <= v < 2**32 for v in key)
        or not (gauss is None or (isinstance(gauss, float) and math.isfinite(gauss)))
    ):
        raise ValueError("the random module's state is malformed")
    name, mt, pos, has_gauss, cached = s["numpy"]
    if (
        name != "MT19937"
        or not isinstance(mt, list)
        or len(mt) != 624
        or not all(_int(v) and 0 <= v < 2**32 for v in mt)
        or not (_int(pos) and 0 <= pos <= 624)
        or has_gauss not in (0, 1)
        or not (isinstance(cached, float) and math.isfinite(cached))
    ):
        raise ValueError("numpy.random's state is malformed")
    random.setstate((version, tuple(key), gauss))
    np.random.set_state((name, np.array(mt, dtype=np.uint32), pos, has_gauss, cached))  # noqa: NPY002
