"""The shipped wheel, installed the way a user installs it (``make wheel-test``).

``make wheel`` writes to ``dist/`` the sdist and the wheel built from it: abi3, manylinux,
stripped. This module checks both files, then, for every Python version the package declares
(the ``Programming Language :: Python :: 3.x`` classifiers, which must run from the
``requires-python`` minimum without a gap), makes one fresh venv in a temporary folder outside
the source tree, installs the wheel's runtime dependencies from PyPI and the wheel itself with
``--no-index``, and from that folder runs ``linkage run`` and a smoke script (import, a sweep
checked against the link lengths, errors mapped to ``LinkageError`` and exit status 2), so the
source tree's ``python/`` is never on the path and nothing but the runtime dependencies is
installed. Then, in the same venv, it adds the wheel's ``test`` extra and runs the whole pytest
suite (``make test``'s run: ``tests/`` and the doctests) against the installed package, from a
copy of the files the tests read, on two workers (pytest-xdist). A version without an
interpreter here fails. The venvs and every cache the runs fill live in temporary folders
removed afterwards.

It runs only when ``LINKAGE_WHEEL_DIST`` names the folder holding the built files
(``make wheel-test`` builds them and sets it); ``make test`` leaves this module out.
"""

from __future__ import annotations

import email.message
import email.parser
import json
import os
import re
import shutil
import struct
import subprocess
import sys
import tarfile
import tempfile
import zipfile
from collections.abc import Iterator
from pathlib import Path

import pytest
from test_readme import TREE_ONLY

try:
    import tomllib
except ModuleNotFoundError:  # Python < 3.11
    import tomli as tomllib

ROOT = Path(__file__).resolve().parent.parent
DIST_ENV = "LINKAGE_WHEEL_DIST"
if not os.environ.get(DIST_ENV):
    pytest.skip(
        f"packaging test: `make wheel-test` builds the wheel and sets {DIST_ENV}",
        allow_module_level=True,
    )
DIST = Path(os.environ[DIST_ENV]).resolve()
PYPROJECT = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))
PROJECT = PYPROJECT["project"]
NAME = PROJECT["name"].replace("-", "_")
TIMEOUT = 600  # seconds for one pip install or one run; a hang fails instead of blocking CI


def declared_minor_versions() -> list[int]:
    """Return the 3.x minor versions named by the classifiers, sorted."""
    found = [
        re.fullmatch(r"Programming Language :: Python :: 3\.(\d+)", c)
        for c in PROJECT["classifiers"]
    ]
    return sorted(int(m.group(1)) for m in found if m)


def requires_python_minimum() -> int:
    """Return N of ``requires-python = ">=3.N"`` (the only form declared)."""
    m = re.fullmatch(r">=\s*3\.(\d+)", PROJECT["requires-python"].strip())
    assert m, f"requires-python {PROJECT['requires-python']!r} is not of the form '>=3.N'"
    return int(m.group(1))


VERSIONS = declared_minor_versions()


def interpreter(minor: int) -> Path | None:
    """Find a CPython 3.<minor> that can make venvs: pyenv's, then the system's."""
    pyenv = Path(os.environ.get("PYENV_ROOT", Path.home() / ".pyenv")) / "versions"
    patch = re.compile(rf"3\.{minor}\.(\d+)")
    builds = sorted(
        (p for p in pyenv.glob(f"3.{minor}.*") if patch.fullmatch(p.name)),
        key=lambda p: int(patch.fullmatch(p.name).group(1)),  # type: ignore[union-attr]
    )
    candidates = [b / "bin" / f"python3.{minor}" for b in reversed(builds)]
    candidates.append(Path(f"/usr/bin/python3.{minor}"))
    for exe in candidates:
        if not exe.is_file():
            continue
        probe = subprocess.run(
            [str(exe), "-c", "import sys, venv, ensurepip; print(sys.version_info[:2])"],
            capture_output=True,
            text=True,
            timeout=60,
        )
        if probe.returncode == 0 and probe.stdout.strip() == f"(3, {minor})":
            return exe
    return None


def only(pattern: str) -> Path:
    """Return the one file in ``dist/`` matching ``pattern`` (fails on none or several)."""
    hits = sorted(DIST.glob(pattern))
    assert len(hits) == 1, f"expected one {pattern} in {DIST}, found {[h.name for h in hits]}"
    return hits[0]


WHEEL = only(f"{NAME}-*.whl")
SDIST = only(f"{NAME}-*.tar.gz")


def wheel_text(member: str) -> str:
    """Return a text file of the wheel."""
    with zipfile.ZipFile(WHEEL) as z:
        return z.read(member).decode("utf-8")


def wheel_metadata() -> email.message.Message:
    """Return the wheel's METADATA, parsed."""
    with zipfile.ZipFile(WHEEL) as z:
        (path,) = [n for n in z.namelist() if n.endswith(".dist-info/METADATA")]
    return email.parser.Parser().parsestr(wheel_text(path))


def elf_section_names(data: bytes) -> list[str]:
    """Return the section names of a 64-bit little-endian ELF file."""
    assert data[:4] == b"\x7fELF" and data[4] == 2 and data[5] == 1, "not a 64-bit LE ELF file"
    (shoff,) = struct.unpack_from("<Q", data, 0x28)
    shentsize, shnum, shstrndx = struct.unpack_from("<HHH", data, 0x3A)
    sections = [struct.unpack_from("<IIQQQQ", data, shoff + i * shentsize) for i in range(shnum)]
    strtab_offset, strtab_size = sections[shstrndx][4], sections[shstrndx][5]
    strtab = data[strtab_offset : strtab_offset + strtab_size]
    return [strtab[s[0] : strtab.index(b"\0", s[0])].decode("ascii") for s in sections]


def clean_env() -> dict[str, str]:
    """Return the environment without anything that would put the source tree on the path."""
    env = {k: v for k, v in os.environ.items() if not k.startswith(("PYTHON", "VIRTUAL_ENV"))}
    env["PATH"] = os.pathsep.join(
        p for p in env.get("PATH", "").split(os.pathsep) if not p.startswith(str(ROOT))
    )
    return env


def run(args: list[str], cwd: Path, timeout: float = TIMEOUT) -> subprocess.CompletedProcess[str]:
    """Run a command outside the tree with a clean environment; return what it did."""
    return subprocess.run(
        args, cwd=cwd, env=clean_env(), capture_output=True, text=True, timeout=timeout
    )


def ok(proc: subprocess.CompletedProcess[str]) -> str:
    """Assert the command succeeded; return its stdout."""
    assert proc.returncode == 0, (
        f"{' '.join(proc.args)} exited {proc.returncode}\n{proc.stdout}\n{proc.stderr}"
    )
    return proc.stdout


def scratch() -> str | None:
    """Return where the temporary venvs go: ``/dev/shm`` if it is a roomy tmpfs, else the default.

    On this machine's disk (ext4 mounted with ``discard``) removing one venv with the test
    dependencies (about 500 MB) takes 50 s; on tmpfs it takes no time. At most one venv and
    pip's cache (about 1 GB) are there at a time.
    """
    shm = "/dev/shm"
    if not (os.path.isdir(shm) and os.access(shm, os.W_OK)):
        return None
    if os.statvfs(shm).f_flag & os.ST_NOEXEC or shutil.disk_usage(shm).free < 4 << 30:
        return None  # the venvs' extension modules must load; room for a venv and the cache
    return shm


@pytest.fixture(scope="module")
def pip_cache() -> Iterator[Path]:
    """Return pip's cache for this module's installs (shared by the versions), removed after."""
    folder = Path(tempfile.mkdtemp(prefix="linkage-wheel-pip-", dir=scratch()))
    yield folder
    shutil.rmtree(folder, ignore_errors=True)


@pytest.fixture
def work(pip_cache: Path, monkeypatch: pytest.MonkeyPatch) -> Iterator[Path]:
    """Return a temporary folder outside the tree for one venv and its runs, removed after.

    What the runs cache (pip's downloads, matplotlib's font list, linkage's synthesis atlas
    and catalogue table, Chromium's profile data) goes into it or into ``pip_cache``: nothing
    is kept between runs, so each is timed as on a fresh machine, and nothing is left behind.
    """
    folder = Path(tempfile.mkdtemp(prefix="linkage-wheel-", dir=scratch())).resolve()
    assert ROOT not in folder.parents, folder
    monkeypatch.setenv("PIP_CACHE_DIR", str(pip_cache))
    monkeypatch.setenv("XDG_CACHE_HOME", str(folder / "cache"))
    monkeypatch.setenv("XDG_CONFIG_HOME", str(folder / "config"))
    for name in ("MPLCONFIGDIR", "LINKAGE_CACHE_DIR", DIST_ENV):
        monkeypatch.delenv(name, raising=False)
    yield folder
    shutil.rmtree(folder, ignore_errors=True)


def test_wheel_is_abi3_manylinux_at_the_declared_minimum() -> None:
    """Check the file name's tags against ``requires-python`` and the WHEEL file."""
    name, version, py, abi, plat = WHEEL.name[: -len(".whl")].split("-")
    assert (name, version) == (NAME, str(wheel_metadata()["Version"]))
    assert py == f"cp3{requires_python_minimum()}", py
    assert abi == "abi3", abi
    platforms = plat.split(".")
    assert platforms and all(p.startswith("manylinux") for p in platforms), plat
    tags = sorted(
        line.split(": ", 1)[1]
        for line in wheel_text(f"{NAME}-{version}.dist-info/WHEEL").splitlines()
        if line.startswith("Tag: ")
    )
    assert tags == sorted(f"{py}-{abi}-{p}" for p in platforms)


def test_auditwheel_reports_the_tagged_manylinux_policy() -> None:
    """Check ``auditwheel show`` finds the extension consistent with the wheel's own tag."""
    auditwheel = shutil.which("auditwheel", path=str(Path(sys.executable).parent))
    assert auditwheel, "auditwheel is missing: pip install --group ship (make wheel does)"
    out = ok(run([auditwheel, "show", str(WHEEL)], cwd=DIST))
    policy = re.search(r'consistent with the following platform tag:\s*"([^"]+)"', out)
    assert policy, out
    assert policy.group(1).startswith("manylinux_"), out
    assert policy.group(1) in WHEEL.name, (policy.group(1), WHEEL.name)


def test_extension_is_one_stripped_abi3_module() -> None:
    """Check the wheel holds one extension, ``linkage/_core.abi3.so``, with no symbols or debug info."""
    with zipfile.ZipFile(WHEEL) as z:
        modules = [n for n in z.namelist() if n.endswith((".so", ".pyd", ".dylib"))]
        assert modules == ["linkage/_core.abi3.so"], modules
        sections = elf_section_names(z.read(modules[0]))
    assert ".text" in sections and ".dynsym" in sections, sections
    assert ".symtab" not in sections, "the extension is not stripped (.symtab present)"
    debug = [s for s in sections if s.startswith((".debug", ".zdebug"))]
    assert not debug, f"the extension carries debug info: {debug}"


def test_metadata_matches_pyproject() -> None:
    """Check name, Python requirement, dependencies, typing marker and the console script."""
    meta = wheel_metadata()
    assert meta["Name"] == PROJECT["name"]
    assert meta["Requires-Python"] == PROJECT["requires-python"]
    runtime = [r for r in meta.get_all("Requires-Dist", []) if "extra ==" not in r]
    assert len(runtime) == len(PROJECT["dependencies"]), runtime
    with zipfile.ZipFile(WHEEL) as z:
        names = set(z.namelist())
    assert {"linkage/py.typed", "linkage/_core.pyi", "linkage/__init__.py"} <= names
    entry = wheel_text(f"{NAME}-{meta['Version']}.dist-info/entry_points.txt")
    assert re.search(r"^linkage\s*=\s*linkage\.cli:main$", entry, re.M), entry


def test_sdist_holds_the_sources_the_wheel_was_built_from() -> None:
    """Check the sdist has the lock file, both crates and every module the wheel ships; no binaries."""
    with tarfile.open(SDIST) as t:
        top = t.getnames()[0].split("/")[0]
        names = {n[len(top) + 1 :] for n in t.getnames()}
    needed = {
        "pyproject.toml",
        "Cargo.toml",
        "Cargo.lock",
        "crates/linkage-core/Cargo.toml",
        "crates/linkage-core/src/lib.rs",
        "crates/linkage-py/Cargo.toml",
        "crates/linkage-py/src/lib.rs",
        "python/linkage/py.typed",
    }
    assert needed <= names, sorted(needed - names)
    assert not [n for n in names if n.endswith((".so", ".pyd", ".whl")) or n.startswith("target/")]
    with zipfile.ZipFile(WHEEL) as z:
        shipped = {n for n in z.namelist() if n.startswith("linkage/") and n.endswith(".py")}
    in_sdist = {n[len("python/") :] for n in names if re.fullmatch(r"python/linkage/.*\.py", n)}
    assert shipped == in_sdist, sorted(shipped ^ in_sdist)


def test_tested_versions_are_the_declared_ones() -> None:
    """Check classifiers run from ``requires-python``'s minimum with no gap, at the abi3 level."""
    minimum = requires_python_minimum()
    assert VERSIONS, "no 'Programming Language :: Python :: 3.x' classifier"
    assert VERSIONS == list(range(minimum, VERSIONS[-1] + 1)), (minimum, VERSIONS)
    binding = (ROOT / "crates" / "linkage-py" / "Cargo.toml").read_text(encoding="utf-8")
    assert re.findall(r'"abi3-py3(\d+)"', binding) == [str(minimum)], "pyo3 abi3 level"
    assert PYPROJECT["tool"]["ruff"]["target-version"] == f"py3{minimum}"


SMOKE = """
import sys
from pathlib import Path

import numpy as np

import linkage
import linkage._core

prefix = Path(sys.prefix).resolve()
for module in (linkage, linkage._core):
    where = Path(module.__file__).resolve()
    assert prefix in where.parents, f"{module.__name__} imported from {where}, not the venv"
assert Path(linkage._core.__file__).name == "_core.abi3.so", linkage._core.__file__
assert linkage.__version__ == sys.argv[1], (linkage.__version__, sys.argv[1])

# A sweep of a crank-rocker: every sample assembles, and each link keeps its length.
theta = np.linspace(0.0, 2.0 * np.pi, 73)
fb = linkage.FourBar(ground=20, crank=10, coupler=25, rocker=25, point=(50, 0))
s = fb.sweep(theta)
assert s.valid.all(), s
o, c, a, b = (s.joint(n) for n in "OCAB")
np.testing.assert_allclose(o, 0.0, atol=0)
np.testing.assert_allclose(c, np.broadcast_to([20.0, 0.0], c.shape), atol=0)
np.testing.assert_allclose(a, 10.0 * np.column_stack([np.cos(theta), np.sin(theta)]), atol=1e-12)
np.testing.assert_allclose(np.linalg.norm(b - a, axis=1), 25.0, rtol=1e-12)
np.testing.assert_allclose(np.linalg.norm(b - c, axis=1), 25.0, rtol=1e-12)

# Bad input is a LinkageError (a ValueError) that names the parameter, raised in Rust.
try:
    linkage.FourBar(ground=-20, crank=10, coupler=25, rocker=25, point=(50, 0))
except linkage.LinkageError as exc:
    assert isinstance(exc, ValueError) and "ground" in str(exc), repr(exc)
else:
    raise AssertionError("a negative ground length was accepted")
print("smoke ok")
"""

BAD_SCENE = """name = "bad"
outputs = ["trajectory"]

[mechanism]
catalog = "hoeken"

[drive]
kind = "constant"
rpm = 50.0
"""


def smoke_runs(work: Path, venv: Path) -> None:
    """Run ``linkage run``, a bad scene and the smoke script from the venv, outside the tree."""
    py, bindir = venv / "bin" / "python", venv / "bin"
    version = str(wheel_metadata()["Version"])

    # The main job, by its console script, into a folder outside the tree.
    out = work / "report"
    stdout = ok(run([str(bindir / "linkage"), "run", "--out", str(out)], cwd=work))
    assert f"report: {out}/" in stdout, stdout
    summary = json.loads((out / "summary.json").read_text(encoding="utf-8"))
    assert (summary["tool"], summary["version"]) == ("linkage", version), summary
    assert {"summary.json", "index.html", "data.csv", "animation.gif"} <= set(summary["files"])
    for name in summary["files"]:
        assert (out / name).stat().st_size > 0, name

    # A mistake in a scene: exit status 2, one located line, no traceback.
    bad = work / "bad.toml"
    bad.write_text(BAD_SCENE, encoding="utf-8")
    refused = run([str(bindir / "linkage"), "run", str(bad), "--out", str(work / "r2")], cwd=work)
    assert refused.returncode == 2, (refused.returncode, refused.stderr)
    lines = refused.stderr.splitlines()
    assert len(lines) == 1 and lines[0].startswith(f"linkage: error: {bad}:5:"), refused.stderr
    assert "hoeken" in lines[0] and not (work / "r2").exists()

    script = work / "smoke.py"
    script.write_text(SMOKE, encoding="utf-8")
    assert ok(run([str(py), "-I", str(script), version], cwd=work)) == "smoke ok\n"


# What the tests read besides themselves: the examples, the docs they check the code against,
# the README and ARCHITECTURE.md (their Python blocks run, their links resolve) and
# pyproject.toml (pytest's options).
# Not python/: the tests import the installed wheel.
SUITE_FILES = ("tests", "examples", "docs", "README.md", "ARCHITECTURE.md", "pyproject.toml")
# Tests that read the source tree (the checkers .ci/layers.py and .ci/long_functions.py, the
# core's constants in crates/), not the installed package: left out of the copy, and of the count
# (test_readme.TREE_ONLY, where the copy's link check reads it too).
SUITE_TIMEOUT = 1800  # seconds for the whole suite on one version (about 2 minutes here)
# The suite runs on this many pytest-xdist workers (CI has 2 cores; `LINKAGE_TEST_WORKERS=0`
# runs it in one process). pytest-xdist is in the `test` extra.
WORKERS = int(os.environ.get("LINKAGE_TEST_WORKERS", "2"))


@pytest.fixture(scope="module")
def suite_size() -> int:
    """How many tests ``make test``'s pytest run collects in the tree (doctests included), but the
    source-tree checks (:data:`TREE_ONLY`)."""
    ignored = [f"--ignore=tests/{name}" for name in ("test_wheel.py", *TREE_ONLY)]
    args = ["tests", "python/linkage", *ignored, "-p", "no:cacheprovider"]
    listed = subprocess.run(
        [sys.executable, "-m", "pytest", "--collect-only", "-q", *args],
        cwd=ROOT,
        capture_output=True,
        text=True,
        timeout=TIMEOUT,
    )
    found = re.search(r"^(\d+) tests? collected", listed.stdout, re.M)
    assert listed.returncode == 0 and found, listed.stdout[-5000:] + listed.stderr
    return int(found.group(1))


def full_suite(work: Path, venv: Path, suite_size: int, minor: int) -> None:
    """Add the ``test`` extra to the venv; run every test against the installed package.

    ``make test``'s pytest run (``tests/`` but this module, and the package's doctests) on a copy
    of the files the tests read, outside the tree, against the installed package: the doctests
    are collected from the venv's ``linkage``, and the run's header (``tests/conftest.py``)
    must name the venv's ``linkage/__init__.py``. Every test must pass, and as many as the tree
    collects: a failure, an error, a skip or a test left uncollected fails this test.
    """
    py, bindir = venv / "bin" / "python", venv / "bin"

    # The test dependencies from PyPI (binary only), our wheel from dist/ and nowhere else.
    version = str(wheel_metadata()["Version"])
    pip = [str(py), "-m", "pip", "install", "--quiet", "--only-binary=:all:"]
    ok(run([*pip, f"{WHEEL}[test]"], cwd=work))
    ok(run([str(py), "-m", "pip", "check"], cwd=work))
    where = ok(run([str(py), "-I", "-c", "import linkage; print(linkage.__file__)"], cwd=work))
    package = Path(where.strip()).parent
    assert venv in package.parents, package

    tree = work / "tree"
    skip = shutil.ignore_patterns("__pycache__", ".hypothesis", "test_wheel.py", *TREE_ONLY)
    for name in SUITE_FILES:
        if (ROOT / name).is_dir():
            shutil.copytree(ROOT / name, tree / name, ignore=skip)
        else:
            shutil.copy2(ROOT / name, tree / name)
    assert not (tree / "python").exists()

    config = ["-c", str(tree / "pyproject.toml"), "--rootdir", str(tree), "-p", "no:cacheprovider"]
    workers = ["-n", str(WORKERS), "--dist", "loadfile"] if WORKERS else []
    suite = run(
        [str(bindir / "pytest"), *config, *workers, "tests", str(package)], tree, SUITE_TIMEOUT
    )
    out = suite.stdout
    assert suite.returncode == 0, (
        f"pytest exited {suite.returncode}:\n{out[-20000:]}\n{suite.stderr}"
    )
    assert f"linkage {version}: {package / '__init__.py'}" in out.splitlines(), out[:2000]
    closing = out.rstrip().splitlines()[-1]
    counts = re.fullmatch(r"=+ (\d+) passed(?:, \d+ warnings?)? in ([\d.]+)s.* =+", closing)
    assert counts, f"not every test passed: {closing}"
    assert int(counts.group(1)) == suite_size, f"{closing}; `make test` collects {suite_size}"
    print(f"Python 3.{minor}: {closing.strip('= ')}, linkage from {package}")


@pytest.mark.parametrize("minor", VERSIONS, ids=[f"py3.{v}" for v in VERSIONS])
def test_wheel_runs_outside_the_tree_and_passes_the_suite(
    minor: int, work: Path, suite_size: int
) -> None:
    """On a fresh venv of 3.<minor>: the wheel with only its runtime dependencies runs ``linkage
    run`` and the smoke script; then, with its ``test`` extra added, the whole suite passes.

    One venv serves both (the runtime dependencies are installed once, matplotlib's font list
    is built once): the smoke runs come first, before anything but the runtime dependencies is
    installed, so a dependency the wheel forgot to declare still fails them.
    """
    exe = interpreter(minor)
    assert exe, f"no CPython 3.{minor} with venv here; it is declared, so it must be tested"
    venv = work / "venv"
    ok(run([str(exe), "-m", "venv", str(venv)], cwd=work))
    py = venv / "bin" / "python"

    # The dependencies from PyPI (binary only: no build of numpy), then our wheel and nothing else.
    meta = wheel_metadata()
    deps = [r for r in meta.get_all("Requires-Dist", []) if "extra ==" not in r]
    pip = [str(py), "-m", "pip", "install", "--quiet", "--only-binary=:all:"]
    ok(run([*pip, *deps], cwd=work))
    ok(
        run(
            [
                *pip,
                "--no-index",
                "--find-links",
                str(DIST),
                f"{PROJECT['name']}=={meta['Version']}",
            ],
            cwd=work,
        )
    )
    ok(run([str(py), "-m", "pip", "check"], cwd=work))
    installed = ok(run([str(py), "-m", "pip", "list", "--format=freeze"], cwd=work))
    assert not re.search(r"^(pytest|hypothesis|mpmath)==", installed, re.M | re.I), installed
    smoke_runs(work, venv)
    full_suite(work, venv, suite_size, minor)
