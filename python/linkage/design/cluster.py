"""Reaching a Dask scheduler: its address checked, every wait on it bounded.

A study's ``scheduler`` is checked when the study is made (:func:`scheduler_address`): Dask's
``tcp://HOST:PORT`` or ``HOST:PORT``, nothing it cannot parse or this tool cannot use. The
connection is then bounded end to end: :func:`connect` asks the scheduler who it is before a
client is made (Dask's own handshake waits without a limit on a peer that accepts and never
answers), under :data:`CONNECT_TIMEOUT` in all; :func:`gather` waits for a generation's chunks
in slices of :data:`POLL`, asking the scheduler between slices whether it is still there
(:data:`CONNECT_TIMEOUT`) and has workers (:data:`NO_WORKERS_TIMEOUT`), and fetches each result
under :data:`RESULT_TIMEOUT`. Every failure is a :class:`SchedulerError` naming the address.
"""

from __future__ import annotations

import asyncio
import ipaddress
import re
import threading
import time
from collections.abc import Callable
from typing import Any, TypeVar

import distributed
import numpy as np
from numpy.typing import NDArray

from linkage._core import LinkageError

__all__ = [
    "CONNECT_TIMEOUT",
    "NO_WORKERS_TIMEOUT",
    "POLL",
    "RESULT_TIMEOUT",
    "SchedulerError",
    "connect",
    "gather",
    "scheduler_address",
]

CONNECT_TIMEOUT = 20.0
"""Seconds to reach the scheduler and hear it answer (connect, handshake, a question)."""
POLL = 5.0
"""Seconds between checks that the scheduler is still there while chunks are evaluated."""
NO_WORKERS_TIMEOUT = 120.0
"""Seconds a search waits on a scheduler without a worker before it gives up."""
RESULT_TIMEOUT = 120.0
"""Seconds to fetch one finished chunk's figures."""

T = TypeVar("T")

_LABEL = r"[A-Za-z0-9](?:[A-Za-z0-9-]{0,61}[A-Za-z0-9])?"
_HOST = re.compile(rf"(?=.{{1,253}}$){_LABEL}(?:\.{_LABEL})*\.?")

_SCHEMES = {
    "tls": "needs certificates, which a study cannot give; use tcp:// (through a tunnel)",
    "inproc": "only reaches a scheduler inside this same process; use tcp://",
    "ucx": "is not supported here; use tcp://",
    "ws": "is not supported here; use tcp://",
    "wss": "is not supported here; use tcp://",
    "http": "is a web address (a dashboard?); the scheduler listens on tcp://HOST:8786",
    "https": "is a web address (a dashboard?); the scheduler listens on tcp://HOST:8786",
}


class SchedulerError(LinkageError):
    """The study's Dask scheduler cannot be reached or used; ``address`` is the one tried."""

    def __init__(self, address: str, problem: str) -> None:
        super().__init__(f"Dask scheduler {address}: {problem}")
        self.address = address
        self.problem = problem


def scheduler_address(text: object) -> str:
    """Return the scheduler address ``text`` as ``tcp://HOST:PORT``, or raise saying why not.

    Examples
    --------
    >>> from linkage.design.cluster import scheduler_address
    >>> scheduler_address("10.0.0.5:8786"), scheduler_address("tcp://[::1]:8786")
    ('tcp://10.0.0.5:8786', 'tcp://[::1]:8786')
    >>> scheduler_address("tls://10.0.0.5:8786")
    Traceback (most recent call last):
    ...
    linkage.LinkageError: 'tls://10.0.0.5:8786': tls:// needs certificates, which a study cannot give; use tcp:// (through a tunnel)
    >>> scheduler_address("garbage")
    Traceback (most recent call last):
    ...
    linkage.LinkageError: 'garbage': not an address: give tcp://HOST:PORT (the scheduler's port is 8786 unless it was started with another)
    """  # noqa: E501
    if not isinstance(text, str):
        raise LinkageError(f"must be a string tcp://HOST:PORT, got {text!r}")
    shown = repr(text) if len(text) <= 80 else repr(text[:77]) + "..."
    if not text:
        raise LinkageError("is empty: give tcp://HOST:PORT, or leave scheduler out")
    if any(ord(c) < 0x21 or 0x7F <= ord(c) <= 0x9F for c in text):
        raise LinkageError(f"{shown}: holds a space or a control character")
    scheme, sep, rest = text.partition("://")
    if not sep:
        scheme, rest = "tcp", text
    if scheme.lower() in _SCHEMES:
        raise LinkageError(f"{shown}: {scheme}:// {_SCHEMES[scheme.lower()]}")
    if scheme != "tcp":
        raise LinkageError(f"{shown}: unknown scheme {scheme}://; use tcp://HOST:PORT")
    m = re.fullmatch(r"(\[[^\]]*\]|[^:/\[\]]*):(\d{1,5})", rest)
    if m is None:
        raise LinkageError(
            f"{shown}: not an address: give tcp://HOST:PORT (the scheduler's port is 8786 "
            f"unless it was started with another)"
        )
    host, port = m.group(1), int(m.group(2))
    if host.startswith("["):
        try:
            ipaddress.IPv6Address(host[1:-1])
        except ValueError:
            raise LinkageError(f"{shown}: {host} is not an IPv6 address") from None
    elif not _HOST.fullmatch(host):
        raise LinkageError(f"{shown}: {host!r} is not a host name or IP address")
    if not 1 <= port <= 65535:
        raise LinkageError(f"{shown}: port {port} is not between 1 and 65535")
    return f"tcp://{host}:{port}"


def _bounded(fn: Callable[[], T], seconds: float) -> T:
    """Run ``fn`` in a thread of its own; its result, its exception, or TimeoutError.

    A call still running at the deadline is left to its (daemon) thread.
    """
    box: dict[str, Any] = {}

    def run() -> None:
        try:
            box["value"] = fn()
        except BaseException as exc:
            box["error"] = exc

    t = threading.Thread(target=run, name="linkage-dask-connect", daemon=True)
    t.start()
    t.join(seconds)
    if t.is_alive():
        raise TimeoutError
    if "error" in box:
        raise box["error"]
    value: T = box["value"]
    return value


async def _identity(address: str, seconds: float) -> Any:
    comm = await distributed.comm.core.connect(address, timeout=seconds)  # type: ignore[no-untyped-call]
    try:
        # No n_workers: older distributed (2024.8, on Python 3.9) refuses the argument.
        await comm.write({"op": "identity", "reply": True})
        return await comm.read()
    finally:
        comm.abort()


def _ask_identity(address: str, seconds: float) -> Any:
    return asyncio.run(asyncio.wait_for(_identity(address, seconds), seconds))


def connect(address: str) -> Any:
    """Return a ``distributed.Client`` of the scheduler at ``address`` (as checked), bounded.

    The scheduler must answer Dask's handshake and say it is a scheduler within
    :data:`CONNECT_TIMEOUT`, and the client must be made within as long again.

    Raises
    ------
    SchedulerError
        No connection, no answer in time, or an answer that is not a Dask scheduler's.
    """
    t0 = time.monotonic()
    try:
        who = _bounded(lambda: _ask_identity(address, CONNECT_TIMEOUT), CONNECT_TIMEOUT + 5.0)
    except (TimeoutError, asyncio.TimeoutError):
        raise SchedulerError(
            address,
            f"no answer within {CONNECT_TIMEOUT:g} s (is a Dask scheduler listening there, "
            f"and is the port its scheduler port rather than its dashboard's?)",
        ) from None
    except OSError as exc:
        raise SchedulerError(address, f"cannot connect: {exc}") from None
    except Exception as exc:
        raise SchedulerError(
            address, f"did not answer as a Dask scheduler ({type(exc).__name__}: {exc})"
        ) from None
    if not isinstance(who, dict) or who.get("type") != "Scheduler":
        kind = who.get("type") if isinstance(who, dict) else type(who).__name__
        raise SchedulerError(address, f"answered, but as {kind!r}, not a Dask scheduler")
    left = max(1.0, CONNECT_TIMEOUT - (time.monotonic() - t0))
    try:
        return _bounded(
            lambda: distributed.Client(address, timeout=left),  # type: ignore[no-untyped-call]
            left + 5.0,
        )
    except (TimeoutError, asyncio.TimeoutError):
        raise SchedulerError(address, f"no client within {CONNECT_TIMEOUT:g} s") from None
    except Exception as exc:
        raise SchedulerError(
            address, f"cannot make a client ({type(exc).__name__}: {exc})"
        ) from None


def gather(client: Any, futures: list[Any], address: str | None) -> list[NDArray[np.float64]]:
    """Wait for ``futures`` in order, bounded as the module says; their results.

    ``address`` is the scheduler's (None for a LocalCluster this process started, which is
    waited on the same way).

    Raises
    ------
    SchedulerError
        The scheduler stopped answering, had no worker for :data:`NO_WORKERS_TIMEOUT`, or a
        result could not be fetched in time.
    """
    where = address or "(local cluster)"
    no_workers_since: float | None = None
    while True:
        try:
            distributed.wait(futures, timeout=POLL)  # type: ignore[no-untyped-call]
            break
        except (TimeoutError, distributed.TimeoutError):
            pass
        try:
            # Every worker listed (no n_workers: older distributed has no such argument)
            info = client.sync(client.scheduler.identity, callback_timeout=CONNECT_TIMEOUT)
        except Exception as exc:
            raise SchedulerError(
                where, f"stopped answering while evaluating ({type(exc).__name__}: {exc})"
            ) from None
        workers = info.get("workers") if isinstance(info, dict) else None
        if workers:
            no_workers_since = None
        else:
            now = time.monotonic()
            no_workers_since = no_workers_since or now
            if now - no_workers_since > NO_WORKERS_TIMEOUT:
                raise SchedulerError(
                    where, f"has had no worker for {NO_WORKERS_TIMEOUT:g} s; start some"
                )
    out = []
    for f in futures:
        try:
            out.append(f.result(timeout=RESULT_TIMEOUT))
        except (TimeoutError, distributed.TimeoutError):
            raise SchedulerError(
                where, f"a chunk's figures did not arrive within {RESULT_TIMEOUT:g} s"
            ) from None
        except LinkageError:
            raise
        except Exception as exc:
            raise SchedulerError(where, f"a chunk failed ({type(exc).__name__}: {exc})") from None
    return out
