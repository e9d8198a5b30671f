"""Caches and atlases a hostile user or a killed process left behind (issue 29 items 2, 3, 6, 10).

The tampered atlas corpus is the table ``TAMPERINGS``: each row makes one atlas folder from a
valid one (``_tampered`` writes it) and gives the message ``Atlas.load`` must refuse it with —
a ``LinkageError`` naming the folder and the file or field, never another exception, a hang
or an abort.
"""

from __future__ import annotations

import json
import os
import re
import resource
import shutil
import subprocess
import sys
import time
import warnings
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np
import pytest

import linkage
from linkage import catalog, synthesis
from linkage.synthesis import Atlas

PYTHON = [sys.executable]


@pytest.fixture(scope="module")
def saved(tmp_path_factory: pytest.TempPathFactory) -> dict[str, Path]:
    """A valid four-bar atlas and a valid arc atlas, saved once."""
    root = tmp_path_factory.mktemp("valid")
    return {
        "fourbar": Atlas.build(64, threads=1).save(root / "fourbar"),
        "arcs": Atlas.build(56, kind="fourbar-arcs", threads=1).save(root / "arcs"),
    }


def _meta(**change: Any) -> Callable[[Path], None]:
    """A tampering that sets (or with ``...``, removes) fields of meta.json."""

    def edit(folder: Path) -> None:
        meta = json.loads((folder / "meta.json").read_text())
        for k, v in change.items():
            if v is ...:
                del meta[k]
            else:
                meta[k] = v
        (folder / "meta.json").write_text(json.dumps(meta))

    return edit


def _meta_text(text: str | bytes) -> Callable[[Path], None]:
    def edit(folder: Path) -> None:
        data = text.encode() if isinstance(text, str) else text
        (folder / "meta.json").write_bytes(data)

    return edit


def _replace(name: str, make: Callable[[Path], None]) -> Callable[[Path], None]:
    """A tampering that removes ``name`` and lets ``make`` put something at its path."""

    def edit(folder: Path) -> None:
        (folder / name).unlink()
        make(folder / name)

    return edit


def _array(name: str, change: Callable[[np.ndarray], Any]) -> Callable[[Path], None]:
    """A tampering that saves ``change(array)`` as the array file ``name``."""

    def edit(folder: Path) -> None:
        a = np.load(folder / name)
        np.save(folder / name, change(a.copy()), allow_pickle=True)

    return edit


def _bytes(name: str, change: Callable[[bytes], bytes]) -> Callable[[Path], None]:
    def edit(folder: Path) -> None:
        (folder / name).write_bytes(change((folder / name).read_bytes()))

    return edit


def _header(name: str, old: bytes, new: bytes) -> Callable[[Path], None]:
    """A tampering of an array file's header text, padded to keep its length."""

    def change(data: bytes) -> bytes:
        assert old in data[:128]
        return data.replace(old, new.ljust(len(old)), 1)

    return _bytes(name, change)


def _deep_header(name: str, depth: int) -> Callable[[Path], None]:
    """A tampering whose header is ``{'descr': `` and ``depth`` nested parentheses, unclosed,
    its length field right (numpy's parser fails on it with ``tokenize.TokenError``, which had
    leaked as exit 3)."""

    def change(data: bytes) -> bytes:
        body = data[10 + int.from_bytes(data[8:10], "little") :]
        header = b"{'descr': " + b"(" * depth + b")" * depth
        return data[:8] + len(header).to_bytes(2, "little") + header + body

    return _bytes(name, change)


def _set(a: np.ndarray, at: tuple[int, ...], v: float) -> np.ndarray:
    a[at] = v
    return a


D, P = "descriptors.npy", "params.npy"
SAMPLES = r"samples must be an int from 8 to 4096, got "

TAMPERINGS: list[tuple[str, str, Callable[[Path], None], str]] = [
    # meta.json: samples (10¹⁰ aborted the process, 10⁷ ran for minutes)
    ("samples-1e10", "fourbar", _meta(samples=10**10), SAMPLES + "10000000000$"),
    ("samples-1e10-float", "fourbar", _meta(samples=1e10), SAMPLES + r"10000000000\.0"),
    ("samples-1e7", "fourbar", _meta(samples=10**7), SAMPLES + "10000000"),
    ("samples-negative", "fourbar", _meta(samples=-5), SAMPLES + "-5"),
    ("samples-4", "fourbar", _meta(samples=4), SAMPLES + "4"),
    ("samples-bool", "fourbar", _meta(samples=True), SAMPLES + "true"),
    ("samples-str", "fourbar", _meta(samples="64"), SAMPLES + '"64"'),
    ("samples-null", "fourbar", _meta(samples=None), SAMPLES + "null"),
    ("samples-missing", "fourbar", _meta(samples=...), SAMPLES + "nothing"),
    ("samples-list", "fourbar", _meta(samples=[64]), SAMPLES + r"\[64\]"),
    ("samples-inf", "fourbar", _meta_text('{"format": 3, "harmonics": 8, "samples": 1e400, '
     '"entries": 64, "kind": "fourbar", "phases": 0}'), SAMPLES + "Infinity"),
    ("samples-huge-int", "fourbar", _meta(samples=10**400), SAMPLES + "1000000000"),
    # harmonics
    ("harmonics-0", "fourbar", _meta(harmonics=0), "harmonics must be an int from 1 to 64, got 0"),
    ("harmonics-1e6", "fourbar", _meta(harmonics=10**6), "harmonics must be .* got 1000000"),
    ("harmonics-float", "fourbar", _meta(harmonics=8.0), r"harmonics must be .* got 8\.0"),
    ("harmonics-missing", "fourbar", _meta(harmonics=...), "harmonics must be .* got nothing"),
    ("harmonics-9", "fourbar", _meta(harmonics=9), r"descriptors must have shape \(entries ≥ 1, 33\)"),
    # entries
    ("entries-65", "fourbar", _meta(entries=65), "entries is 65, but descriptors.npy holds 64"),
    ("entries-0", "fourbar", _meta(entries=0), "entries must be an int from 1 to"),
    ("entries-str", "fourbar", _meta(entries="64"), 'entries must be .* got "64"'),
    ("entries-missing", "fourbar", _meta(entries=...), "entries must be .* got nothing"),
    # format and kind
    ("format-2", "fourbar", _meta(format=2), "format must be 3, got 2"),
    ("format-missing", "fourbar", _meta(format=...), "format must be 3, got null"),
    ("format-str", "fourbar", _meta(format="3"), 'format must be 3, got "3"'),
    ("kind-unknown", "fourbar", _meta(kind="crank"), "kind must be one of .* got \"crank\""),
    ("kind-int", "fourbar", _meta(kind=5), "kind must be one of .* got 5"),
    ("kind-list", "fourbar", _meta(kind=["fourbar"]), r"kind must be one of .* got \[\"fourbar\"\]"),
    ("kind-slider", "fourbar", _meta(kind="slider-crank"), r"params must have shape \(entries ≥ 1, 4\)"),
    ("kind-arcs", "fourbar", _meta(kind="fourbar-arcs", phases=8), r"params must have shape \(entries ≥ 1, 8\)"),
    ("phases-on-fourbar", "fourbar", _meta(phases=3), "phases must be 0 for a fourbar atlas, got 3"),
    ("phases-negative", "fourbar", _meta(phases=-1), "phases must be an int from 0 to 64, got -1"),
    # meta.json as a whole
    ("meta-list", "fourbar", _meta_text("[]"), "meta.json: not a JSON object"),
    ("meta-not-json", "fourbar", _meta_text("{"), "meta.json: the atlas's meta.json is not JSON"),
    ("meta-empty", "fourbar", _meta_text(""), "meta.json: the atlas's meta.json is not JSON"),
    ("meta-deep", "fourbar", _meta_text("[" * 1000 + "]" * 1000), "nests 1000 levels deep, more than 32"),
    ("meta-huge", "fourbar", _meta_text(" " * (1 << 20) + "{}"), "1048578 bytes, more than the 65536"),
    ("meta-not-utf8", "fourbar", _meta_text(b'{"kind": "\xff"}'), "not UTF-8 text"),
    ("meta-missing", "fourbar", lambda f: (f / "meta.json").unlink(), "meta.json: cannot read"),
    ("meta-folder", "fourbar", _replace("meta.json", Path.mkdir), "meta.json is a folder"),
    ("meta-fifo", "fourbar", _replace("meta.json", os.mkfifo), "meta.json is a pipe or socket"),
    ("meta-dev-zero", "fourbar", _replace("meta.json", lambda p: p.symlink_to("/dev/zero")),
     "meta.json is a device"),
    # the arrays' files
    ("desc-missing", "fourbar", lambda f: (f / D).unlink(), "descriptors.npy: cannot read"),
    ("desc-empty", "fourbar", _bytes(D, lambda b: b""), "descriptors are not a .npy array"),
    ("desc-garbage", "fourbar", _bytes(D, lambda b: os.urandom(500)), "not a .npy array"),
    ("desc-truncated", "fourbar", _bytes(D, lambda b: b[: len(b) // 2]), "bytes, but their shape"),
    ("desc-longer", "fourbar", _bytes(D, lambda b: b + b"\0" * 4), "bytes, but their shape"),
    ("desc-huge-shape", "fourbar", _header(D, b"(64, 29)", b"(10000000000000, 29)"),
     r"shape \(10000000000000, 29\) needs 1160000000000000"),
    ("desc-negative-shape", "fourbar", _header(D, b"(64, 29)", b"(-64, 29)"), "not a .npy array"),
    ("desc-bad-descr", "fourbar", _header(D, b"'<f4'", b"'xyz'"), "not a .npy array"),
    ("desc-header-code", "fourbar", _header(D, b"'<f4'", b"__import__('os')"), "not a .npy array"),
    ("desc-float64", "fourbar", _array(D, lambda a: a.astype(np.float64)), "hold float64 values"),
    ("desc-big-endian", "fourbar", _array(D, lambda a: a.astype(">f4")), "hold >f4 values"),
    ("desc-pickled", "fourbar", _array(D, lambda a: a.astype(object)), "hold object values"),
    ("desc-fortran", "fourbar", _array(D, np.asfortranarray), "Fortran order"),
    ("desc-1d", "fourbar", _array(D, np.ravel), r"have shape \(1856,\), not"),
    ("desc-nan", "fourbar", _array(D, lambda a: _set(a, (3, 2), np.nan)),
     "descriptors of entry 3 are not all finite"),
    ("desc-fifo", "fourbar", _replace(D, os.mkfifo), "descriptors are not in a regular file"),
    ("desc-dev-zero", "fourbar", _replace(D, lambda p: p.symlink_to("/dev/zero")),
     "descriptors are not in a regular file"),
    ("params-inf", "fourbar", _array(P, lambda a: _set(a, (5, 0), np.inf)),
     "params of entry 5 are not all finite"),
    ("params-width", "fourbar", _array(P, lambda a: a[:, :5].copy()), r"params must have shape"),
    ("params-fewer", "fourbar", _array(P, lambda a: a[:63].copy()), "params have 63 entries, descriptors 64"),
    ("params-int", "fourbar", _array(P, lambda a: a.astype(np.int64)), "hold int64 values"),
    # found by a hostile re-trial: a folder as an array's file ("3: Is a directory", the file
    # descriptor for the path), a header numpy's parser fails on with tokenize.TokenError (exit 3),
    # and link lengths or flags that are no linkage's (loaded and searched with)
    ("params-folder", "fourbar", _replace(P, Path.mkdir), "parameters are not in a regular file"),
    ("desc-header-deep", "fourbar", _deep_header(D, 95),
     "descriptors are not a .npy array"),
    ("params-negative", "fourbar", _array(P, lambda a: _set(a, (7, 1), -0.5)),
     "params of entry 7: a link length is not a positive normal float"),
    ("params-subnormal", "fourbar", _array(P, lambda a: _set(a, (2, 0), 1e-310)),
     "params of entry 2: a link length is not a positive normal float"),
    ("params-crossed", "fourbar", _array(P, lambda a: _set(a, (9, 5), 0.5)),
     "params of entry 9: the crossed flag 0.5 is not 0 or 1"),
    # arc atlases: phases and the entries' indices
    ("arc-phases-0", "arcs", _meta(phases=0), r"phases must be from 1 to samples \(128\), got 0"),
    ("arc-phases-129", "arcs", _meta(phases=129), "phases must be an int from 0 to 128, got 129"),
    ("arc-samples-16", "arcs", _meta(samples=16, phases=8),
     "samples must be from 32 to 4096 for a fourbar-arcs atlas, got 16"),
    ("arc-phase-index", "arcs", _array(P, lambda a: _set(a, (2, 6), 8.0)), "params of entry 2: the arc's phase 8.0 is not an index below 8"),
    ("arc-half-index", "arcs", _array(P, lambda a: _set(a, (4, 6), 0.5)), "params of entry 4: the arc's phase 0.5"),
    ("arc-fraction-index", "arcs", _array(P, lambda a: _set(a, (1, 7), 7.0)), "entry 1: the arc's fraction 7.0 is not an index below 7"),
    ("arc-as-fourbar", "arcs", _meta(kind="fourbar", phases=0), r"params must have shape \(entries ≥ 1, 6\)"),
]  # fmt: skip


def _tampered(
    saved: dict[str, Path], tmp: Path, name: str, base: str, edit: Callable[[Path], None]
) -> Path:
    folder = tmp / name
    shutil.copytree(saved[base], folder)
    edit(folder)
    return folder


@pytest.mark.parametrize(
    ("name", "base", "edit", "message"), TAMPERINGS, ids=[t[0] for t in TAMPERINGS]
)
def test_a_tampered_atlas_is_refused_naming_the_folder_and_field(
    saved: dict[str, Path],
    tmp_path: Path,
    name: str,
    base: str,
    edit: Callable[[Path], None],
    message: str,
) -> None:
    folder = _tampered(saved, tmp_path, name, base, edit)
    start = time.perf_counter()
    with pytest.raises(linkage.LinkageError) as caught:
        Atlas.load(folder)
    assert time.perf_counter() - start < 5
    text = str(caught.value)
    assert text.startswith(f"{folder} is not a readable atlas: "), text
    assert re.search(message, text), text
    assert "\n" not in text


def test_the_valid_atlases_of_the_corpus_load(saved: dict[str, Path]) -> None:
    assert len(Atlas.load(saved["fourbar"])) == 64
    assert Atlas.load(saved["arcs"]).phases == 8


def _run(args: list[str], timeout: float, **kw: Any) -> subprocess.CompletedProcess[str]:
    """Run Python with ``args`` in a child that sees this package and the environment now."""
    env = {**os.environ, "PYTHONPATH": str(Path(linkage.__file__).parents[1])}
    return subprocess.run(
        [*PYTHON, *args], capture_output=True, text=True, timeout=timeout, env=env, **kw
    )


def _limit_memory() -> None:
    """Two GB of address space: a process reading without bound fails instead of swapping."""
    resource.setrlimit(resource.RLIMIT_AS, (2 << 30, 2 << 30))


@pytest.fixture(scope="module")
def target(tmp_path_factory: pytest.TempPathFactory) -> Path:
    fb = linkage.catalog.hoecken()
    f = tmp_path_factory.mktemp("target") / "foot.csv"
    np.savetxt(f, fb.circuit(13).point[:-1], delimiter=",")
    return f


@pytest.mark.parametrize(
    "name", ["samples-1e10", "samples-1e7", "samples-negative", "harmonics-missing", "desc-empty",
             "desc-pickled", "meta-deep", "params-width", "desc-fifo"]
)  # fmt: skip
def test_the_cli_refuses_a_tampered_atlas_in_one_line(
    saved: dict[str, Path], tmp_path: Path, target: Path, name: str
) -> None:
    """``linkage synth --atlas``: exit 2 and one line naming the folder (10¹⁰ samples aborted
    the process with SIGABRT after a Rust allocation failed, 10⁷ ran for minutes, and the others
    were "internal error", exit 3 — or a hang for the pipe)."""
    base, edit = next((b, e) for n, b, e, _ in TAMPERINGS if n == name)
    folder = _tampered(saved, tmp_path, name, base, edit)
    run = _run(
        ["-m", "linkage", "synth", str(target), "--top", "1", "--quiet", "--atlas", str(folder)],
        timeout=60,
        preexec_fn=_limit_memory,
    )
    assert run.returncode == 2, (run.returncode, run.stderr[-2000:])
    lines = run.stderr.strip().splitlines()
    assert len(lines) == 1 and str(folder) in lines[0] and "internal error" not in lines[0], lines


def test_samples_of_1e10_are_refused_before_anything_is_allocated(
    saved: dict[str, Path], tmp_path: Path, target: Path
) -> None:
    """The search with a 10¹⁰-sample atlas, in a child limited to 2 GB (an abort cannot take
    pytest with it): refused by ``path`` at once, before any circuit is sampled."""
    folder = _tampered(saved, tmp_path, "huge", "fourbar", _meta(samples=10**10))
    code = (
        "import sys, numpy as np, linkage\n"
        "from linkage import synthesis\n"
        f"pts = np.loadtxt({str(target)!r}, delimiter=',')\n"
        "try:\n"
        f"    synthesis.path(pts, atlas={str(folder)!r}, top=1, global_search=False)\n"
        "except linkage.LinkageError as e:\n"
        "    print(e); sys.exit(7)\n"
    )
    start = time.perf_counter()
    run = _run(["-c", code], timeout=60, preexec_fn=_limit_memory)
    assert run.returncode == 7, (run.returncode, run.stderr[-2000:])
    assert "samples must be an int from 8 to 4096, got 10000000000" in run.stdout
    assert time.perf_counter() - start < 30


# -- the public constructor -------------------------------------------------------------------


def _good(**change: Any) -> dict[str, Any]:
    kw: dict[str, Any] = dict(
        descriptors=np.zeros((3, 29), np.float32), params=np.ones((3, 6)), harmonics=8, samples=64
    )
    kw.update(change)
    return kw


@pytest.mark.parametrize(
    ("change", "error", "message"),
    [
        (dict(samples=10**10), linkage.LinkageError, "samples must be from 8 to 4096"),
        (dict(samples=-1), linkage.LinkageError, "samples must be from 8"),
        (dict(samples=64.0), TypeError, "samples must be an int, got float"),
        (dict(harmonics=True), TypeError, "harmonics must be an int, got bool"),
        (dict(harmonics=65), linkage.LinkageError, "harmonics must be from 1 to 64"),
        (dict(kind="crank"), linkage.LinkageError, "kind must be one of"),
        (dict(kind=None), TypeError, "kind must be a str"),
        (dict(phases=2), linkage.LinkageError, "phases must be 0 for a fourbar atlas"),
        (dict(descriptors=[[0.0] * 29] * 3), TypeError, "descriptors must be a numpy array"),
        (dict(descriptors=np.zeros((3, 29))), TypeError, "descriptors must be float32"),
        (dict(params=np.ones((3, 6), np.float32)), TypeError, "params must be float64"),
        (dict(params=np.ones((3, 4))), linkage.LinkageError, r"params must have shape"),
        (dict(params=np.ones((2, 6))), linkage.LinkageError, "params have 2 entries"),
        (dict(params=np.full((3, 6), np.nan)), linkage.LinkageError, "params of entry 0"),
        (dict(params=np.ones((6, 3)).T), linkage.LinkageError, "params must be C-contiguous"),
        (dict(descriptors=np.zeros((0, 29), np.float32), params=np.ones((0, 6))),
         linkage.LinkageError, r"descriptors must have shape \(entries ≥ 1"),
        (dict(kind="fourbar-arcs", params=np.zeros((3, 8)), samples=128, phases=0),
         linkage.LinkageError, "phases must be from 1 to samples"),
    ],
)  # fmt: skip
def test_the_constructor_checks_every_field(
    change: dict[str, Any], error: type, message: str
) -> None:
    with pytest.raises(error, match=message):
        Atlas(**_good(**change))


def test_the_constructor_takes_a_valid_atlas_and_build_keeps_its_bounds() -> None:
    assert len(Atlas(**_good())) == 3
    with pytest.raises(linkage.LinkageError, match="at most 64 harmonics and 4096 samples"):
        Atlas.build(10, samples=4097)


# -- the default atlas -------------------------------------------------------------------------


@pytest.mark.parametrize(
    "name", ["samples-1e10", "harmonics-missing", "samples-str", "desc-empty", "meta-deep", "params-inf"]
)  # fmt: skip
def test_a_corrupt_default_atlas_is_rebuilt_naming_its_folder(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, name: str
) -> None:
    """Whatever is wrong with the cached default atlas, it is rebuilt with a warning naming its
    folder (only ``LinkageError`` was caught: a missing field raised ``KeyError``, and 10¹⁰
    samples were loaded as they were)."""
    monkeypatch.setenv("LINKAGE_CACHE_DIR", str(tmp_path))
    first = synthesis.default_atlas(entries=100)
    (folder,) = [p for p in tmp_path.iterdir() if p.name.startswith("atlas-")]
    _, _, edit, _ = next(t for t in TAMPERINGS if t[0] == name)
    edit(folder)
    with pytest.warns(UserWarning, match=re.escape(str(folder))):
        again = synthesis.default_atlas(entries=100)
    assert again.samples == 64 and np.array_equal(again.params, first.params)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        back = synthesis.default_atlas(entries=100)  # rewritten: read back, no warning
    assert np.array_equal(back.descriptors, first.descriptors)


def test_the_default_atlas_is_keyed_on_the_version_and_the_cores_content(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    """The key was the core library's byte size: a rebuilt core of the same size reused an atlas
    built by the other."""
    before = synthesis._default_folder(None, 8, "fourbar")
    monkeypatch.setattr(synthesis.atlas, "core_identity", lambda: "another build")
    assert synthesis._default_folder(None, 8, "fourbar") != before
    monkeypatch.undo()
    monkeypatch.setattr(synthesis.atlas, "__version__", "0.0.0-other")
    assert synthesis._default_folder(None, 8, "fourbar") != before


# -- temporaries of killed processes -----------------------------------------------------------


def _dead_pid() -> int:
    child = subprocess.Popen([sys.executable, "-c", "pass"])
    child.wait()
    return child.pid


def test_atlas_temporaries_of_dead_processes_are_swept_and_nothing_else(tmp_path: Path) -> None:
    """``Atlas.save``'s ``.<name>.tmp<pid>-<hex>`` folders left by kill -9 (up to ~100 MB)
    were never removed."""
    dead = _dead_pid()
    stale = tmp_path / f".atlas.tmp{dead}-0123abcd"
    stale.mkdir()
    (stale / "descriptors.npy").write_bytes(b"x" * 1000)
    live = tmp_path / f".atlas.tmp{os.getpid()}-0123abcd"  # a save under way
    live.mkdir()
    victim = tmp_path / "victim"
    victim.mkdir()
    (victim / "keep.txt").write_text("mine")
    link = tmp_path / f".atlas.tmp{dead}-89abcdef"
    link.symlink_to(victim)  # matches the name, but a link: left, and nothing followed
    others = [tmp_path / f".atlas.tmp{dead}", tmp_path / f".other.tmp{dead}-0123abcd"]
    for p in others:
        p.mkdir()
    Atlas.build(50, threads=1).save(tmp_path / "atlas")
    assert not stale.exists()
    assert live.is_dir() and link.is_symlink() and (victim / "keep.txt").read_text() == "mine"
    assert all(p.is_dir() for p in others)


def test_the_default_atlas_sweeps_the_cache_folder(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setenv("LINKAGE_CACHE_DIR", str(tmp_path))
    dead = _dead_pid()
    stale = tmp_path / f".atlas-0123456789abcdef.tmp{dead}-0123abcd"
    stale.mkdir()
    mine = tmp_path / f".notes.tmp{dead}-0123abcd"
    mine.mkdir()
    synthesis.default_atlas(entries=100)
    assert not stale.exists() and mine.is_dir()


# -- the catalogue cache -----------------------------------------------------------------------


@pytest.fixture
def cache(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    folder = tmp_path / "cache"
    folder.mkdir()
    monkeypatch.setenv("LINKAGE_CACHE_DIR", str(folder))
    return folder


def _cache_path(samples: int) -> Path:
    check = catalog.check_count(samples)
    return catalog.cache_dir() / f"catalog-{catalog._cache_key(1e-3, samples, check)}.json"


def test_a_link_planted_at_the_catalogue_temporary_is_not_followed(
    cache: Path, tmp_path: Path
) -> None:
    """The cache was written to ``.catalog-<key>.json.<pid>.tmp`` with ``open(..., "w")``: a
    link planted there made the tool overwrite any file the user can write."""
    victim = tmp_path / "victim.txt"
    victim.write_text("precious")
    path = _cache_path(101)
    planted = path.with_name(f".{path.name}.{os.getpid()}.tmp")
    planted.symlink_to(victim)
    rows = catalog.table(samples=101)
    assert victim.read_text() == "precious"
    assert [r.name for r in rows] == list(catalog.names())
    assert json.loads(path.read_text())[0]["name"] == "watt"


def test_a_link_at_the_cache_itself_is_left_alone(cache: Path, tmp_path: Path) -> None:
    victim = tmp_path / "victim.json"
    victim.write_text("[1, 2]")
    path = _cache_path(101)
    path.symlink_to(victim)
    rows = catalog.table(samples=101)
    assert [r.name for r in rows] == list(catalog.names())
    assert path.is_symlink() and victim.read_text() == "[1, 2]"


@pytest.mark.parametrize("kind", ["fifo", "dev-zero"])
def test_a_pipe_or_device_as_the_cache_neither_hangs_nor_grows(cache: Path, kind: str) -> None:
    """A FIFO as the cache file hung the tool; a link to /dev/zero grew its memory without
    bound (the child here is limited to 2 GB and 60 s)."""
    path = _cache_path(101)
    if kind == "fifo":
        os.mkfifo(path)
    else:
        path.symlink_to("/dev/zero")
    code = "from linkage import catalog; print(len(catalog.table(samples=101)))"
    start = time.perf_counter()
    run = _run(["-c", code], timeout=60, preexec_fn=_limit_memory)
    assert run.returncode == 0, run.stderr[-2000:]
    assert int(run.stdout) == len(catalog.names())
    assert time.perf_counter() - start < 30
    assert path.is_fifo() if kind == "fifo" else path.is_symlink()


@pytest.mark.parametrize(
    "junk",
    [
        "[" * 100_000 + "]" * 100_000,  # RecursionError: exit 3 until deleted
        '[{"samples": 1e400}]',
        json.dumps([{"name": 1}]),
    ],
)
def test_a_corrupt_cache_is_recomputed_and_rewritten(cache: Path, junk: str) -> None:
    path = _cache_path(101)
    good = catalog.table(samples=101, cache=False)
    path.write_text(junk)
    assert catalog.table(samples=101) == good
    assert json.loads(path.read_text())[0]["name"] == "watt"


def test_a_cached_row_with_a_huge_count_is_recomputed(cache: Path) -> None:
    path = _cache_path(101)
    good = catalog.table(samples=101)
    rows = json.loads(path.read_text())
    rows[0]["samples"] = 10**400  # int(...) was fine, but float fields overflowed
    rows[1]["size"] = 10**400
    path.write_text(json.dumps(rows))
    assert catalog.table(samples=101) == good


def test_catalogue_temporaries_of_dead_processes_are_swept(cache: Path) -> None:
    dead = _dead_pid()
    path = _cache_path(101)
    old = path.with_name(f".{path.name}.{dead}.tmp")
    new = path.with_name(f".{path.name}.{dead}.k2j_x9.tmp")
    live = path.with_name(f".{path.name}.{os.getpid()}.abc.tmp")
    mine = cache / f".notes.{dead}.tmp"
    for p in (old, new, live, mine):
        p.write_text("{")
    catalog.table(samples=101)
    assert not old.exists() and not new.exists()
    assert live.exists() and mine.exists()


def test_the_catalogue_cache_is_keyed_on_the_cores_content(monkeypatch: pytest.MonkeyPatch) -> None:
    before = catalog._cache_key(1e-3, 101, 51)
    monkeypatch.setattr(catalog, "core_identity", lambda: "another build")
    assert catalog._cache_key(1e-3, 101, 51) != before


@pytest.mark.parametrize("command", ["check", "run"])
def test_a_scenes_tampered_atlas_is_blamed_on_its_atlas_line(
    saved: dict[str, Path], tmp_path: Path, capsys: pytest.CaptureFixture[str], command: str
) -> None:
    """A negative ``samples`` was blamed on ``[synthesis] points`` ("the search failed: can't
    convert negative int to unsigned") by ``run``, and ``check`` said ok."""
    from linkage import cli

    _tampered(saved, tmp_path, "atlas", "fourbar", _meta(samples=-5))
    shutil.copy("examples/foot_path.csv", tmp_path)
    scene = tmp_path / "s.toml"
    scene.write_text(
        'name = "s"\nunits = "mm"\noutputs = ["synthesis"]\n[synthesis]\n'
        'points = "foot_path.csv"\ntop = 1\natlas = "atlas"\n'
    )
    extra = ["--out", str(tmp_path / "out"), "--quiet"] if command == "run" else []
    assert cli.main([command, str(scene), *extra]) == 2
    err = capsys.readouterr().err.strip()
    assert err == (
        f"linkage: error: {scene}:7: [synthesis] atlas: 'atlas' is not a readable atlas: "
        "meta.json: samples must be an int from 8 to 4096, got -5"
    ), err


def test_an_atlas_of_numpy_counts_saves_and_loads(tmp_path: Path) -> None:
    at = Atlas(**_good(harmonics=np.int64(8), samples=np.int32(64)))
    assert len(Atlas.load(at.save(tmp_path / "a"))) == 3
