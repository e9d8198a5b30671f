"""What the caches need beyond :mod:`linkage._files`: the build's identity and guarded arrays.

- :func:`core_identity` keys the caches (the catalogue table, the default atlases) on the
  compiled core's content, not its size: a rebuilt core of equal size does not reuse a stale
  cache.
- :func:`read_npy` opens a ``.npy`` array memory-mapped as :func:`linkage._files.read_bytes`
  opens a file: without blocking, a regular file only, checked on the open descriptor; its
  header is parsed without ``pickle`` and checked against the file's size before anything is
  mapped.
"""

from __future__ import annotations

import functools
import hashlib
import math
import os
import stat
from typing import Any, BinaryIO

import numpy as np
from numpy.lib import format as npy_format

from linkage import _core
from linkage._core import LinkageError

__all__ = ["core_identity", "npy_header", "read_npy"]


@functools.lru_cache(maxsize=1)
def core_identity() -> str:
    """Return the SHA-256 of the compiled core (hex), computed once a process.

    About 15 ms for the 14 MB core here (``time.perf_counter`` around the first call). An
    unreadable core (a frozen application) gives ``""``: the caches are then keyed on the
    version alone.

    Examples
    --------
    >>> from linkage._shared.cache_files import core_identity
    >>> len(core_identity()) in (0, 64)
    True
    """
    path = getattr(_core, "__file__", None)
    if not path:
        return ""
    digest = hashlib.sha256()
    try:
        with open(path, "rb") as f:
            for chunk in iter(lambda: f.read(1 << 20), b""):
                digest.update(chunk)
    except OSError:
        return ""
    return digest.hexdigest()


def npy_header(f: BinaryIO) -> tuple[tuple[int, ...], bool, np.dtype[Any], int]:
    """Read the header of the ``.npy`` array at ``f``'s position, without ``pickle``.

    Returns ``(shape, fortran_order, dtype, offset of the data)``. Whatever numpy's parser raises
    on a damaged header (a literal it cannot evaluate, a short file, an absurd shape, an unknown
    version) is a ``ValueError`` saying what: the one header parser of the caches' arrays and of
    the design search's checkpoints.
    """
    try:
        version = npy_format.read_magic(f)
        if version == (1, 0):
            shape, fortran, dt = npy_format.read_array_header_1_0(f)
        elif version == (2, 0):
            shape, fortran, dt = npy_format.read_array_header_2_0(f)
        else:
            raise ValueError(f"unsupported format version {version}")
        return shape, fortran, dt, f.tell()
    except Exception as exc:  # untrusted bytes: whatever the parser raises
        # (ValueError, SyntaxError, tokenize.TokenError on a deeply nested literal, EOFError,
        # OverflowError, RecursionError, MemoryError...) means the header is not one numpy wrote
        raise ValueError(str(exc) or type(exc).__name__) from None


def read_npy(path: str | os.PathLike[str], dtype: type, what: str) -> np.ndarray:
    """Return the 2-D C-ordered ``dtype`` array of the ``.npy`` file ``path``, memory-mapped.

    Refused with a :class:`LinkageError` naming ``path`` and ``what``: anything but a regular
    file (a FIFO does not block), a damaged or pickled header, another dtype (native byte order
    only), Fortran order, another number of dimensions, or a file whose size is not exactly the
    header's plus the array's bytes.

    Examples
    --------
    >>> import os, tempfile
    >>> import numpy as np
    >>> from linkage._shared.cache_files import read_npy
    >>> tmp = tempfile.mkdtemp()
    >>> p = os.path.join(tmp, "a.npy")
    >>> np.save(p, np.ones((2, 3), dtype=np.float32))
    >>> read_npy(p, np.float32, "descriptors").shape
    (2, 3)
    >>> read_npy(p, np.float64, "params")
    Traceback (most recent call last):
    ...
    linkage.LinkageError: .../a.npy: the params hold float32 values, not float64
    >>> os.unlink(p); os.rmdir(tmp)
    """
    p = os.fspath(path)
    flags = os.O_RDONLY | getattr(os, "O_NONBLOCK", 0) | getattr(os, "O_CLOEXEC", 0)
    try:
        fd = os.open(p, flags)
    except OSError as exc:
        raise LinkageError(f"{p}: cannot read the {what}: {exc.strerror or exc}") from None
    try:
        info = os.fstat(fd)
    except OSError as exc:
        os.close(fd)
        raise LinkageError(f"{p}: cannot read the {what}: {exc.strerror or exc}") from None
    if not stat.S_ISREG(info.st_mode):  # checked before fdopen, which refuses a folder itself
        os.close(fd)
        raise LinkageError(f"{p}: the {what} are not in a regular file")
    size = info.st_size
    with os.fdopen(fd, "rb") as f:
        try:
            shape, fortran, dt, offset = npy_header(f)
        except ValueError as exc:
            raise LinkageError(f"{p}: the {what} are not a .npy array: {exc}") from None
        want = np.dtype(dtype)
        if dt != want or dt.hasobject:
            raise LinkageError(f"{p}: the {what} hold {dt} values, not {want}")
        if fortran:
            raise LinkageError(f"{p}: the {what} are stored in Fortran order, not C order")
        if any(n < 0 for n in shape):
            raise LinkageError(f"{p}: the {what} are not a .npy array: shape {shape}")
        if len(shape) != 2:
            raise LinkageError(f"{p}: the {what} have shape {shape}, not (rows, columns)")
        nbytes = math.prod(shape) * want.itemsize
        if size != offset + nbytes:
            raise LinkageError(
                f"{p}: the {what} hold {size - offset} bytes, but their shape {shape} needs "
                f"{nbytes}"
            )
        if nbytes == 0:
            return np.empty(shape, dtype=want)
        try:
            return np.memmap(f, dtype=want, mode="r", offset=offset, shape=shape)
        except (ValueError, OSError, OverflowError, MemoryError) as exc:
            raise LinkageError(f"{p}: cannot map the {what}: {exc}") from None
