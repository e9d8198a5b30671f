"""Absurd sizes under an address-space limit: each case runs in a child process limited to
2 GiB (``RLIMIT_AS``) and must end in a clean ``MemoryError`` naming the size (or a
``LinkageError`` for a count that cannot be represented) — the child exiting normally, never
killed by SIGABRT (a failed Rust allocation) or SIGKILL, never a panic.

Requests are chosen larger than the machine's memory as well as the limit, so a size check
against either catches them; the ones marked "rlimit" only exceed the address-space limit and
need the allocation itself to fail cleanly (numpy does; Rust aborts unless it checks).
"""

from __future__ import annotations

import json
import os
import re
import signal
import subprocess
import sys
import textwrap

import pytest

resource = pytest.importorskip("resource")  # POSIX only

LIMIT = 2 << 30  # bytes
SIZE = re.compile(r"\d+(\.\d*)?\s*(bytes|[KMGTPE]i?B)\b")

PRELUDE = """
import json, resource, sys
soft, hard = resource.getrlimit(resource.RLIMIT_AS)
limit = {limit}
if hard != resource.RLIM_INFINITY:
    limit = min(limit, hard)
resource.setrlimit(resource.RLIMIT_AS, (limit, hard))
resource.setrlimit(resource.RLIMIT_CORE, (0, 0))  # an abort must not write a 2 GB core file
import math
import numpy as np
import linkage
from linkage import catalog, geometry
from linkage.drive import Program, Segment, crank_schedule, motion_law

def report(outcome, message=""):
    print(json.dumps({{"outcome": outcome, "message": str(message)[:500]}}), flush=True)

try:
{body}
    report("ok")
except MemoryError as exc:
    report("MemoryError", exc)
except linkage.LinkageError as exc:
    report("LinkageError", exc)
except BaseException as exc:
    report(type(exc).__module__ + "." + type(exc).__name__, exc)
"""


def run_limited(body: str, timeout: float = 180.0, all_lines: bool = False):
    code = PRELUDE.format(limit=LIMIT, body=textwrap.indent(textwrap.dedent(body).strip(), "    "))
    env = dict(os.environ, OPENBLAS_NUM_THREADS="1", OMP_NUM_THREADS="1", RUST_BACKTRACE="0")
    proc = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, timeout=timeout, env=env
    )
    if proc.returncode < 0:
        sig = signal.Signals(-proc.returncode).name
        pytest.fail(f"child killed by {sig}; stderr tail:\n{proc.stderr[-1500:]}")
    assert proc.returncode == 0, proc.stderr[-1500:]
    lines = [ln for ln in proc.stdout.splitlines() if ln.startswith("{")]
    assert lines, f"no report from the child; stderr tail:\n{proc.stderr[-1500:]}"
    results = [json.loads(ln) for ln in lines]
    assert results[-1]["outcome"] == "ok" or not all_lines, results[-1]
    return results if all_lines else results[-1]


def expect_memory_error(body: str) -> None:
    r = run_limited(body)
    assert r["outcome"] == "MemoryError", r
    assert SIZE.search(r["message"]), f"the MemoryError does not name the size: {r['message']!r}"


# -- checked in Python (pass today) -----------------------------------------------------------
PYTHON_CASES = {
    "crank_schedule_samples": "crank_schedule(catalog.hoecken(), 100.0, 0.6, samples=10**10)",
    "crank_schedule_resolution": "crank_schedule(catalog.hoecken(), 100.0, 0.6, resolution=10**11)",
    "cam_profile": "linkage.cam.leg_lift_cam().profile(10**10)",
    "walker_simulate": "catalog.quadruped_hoecken().simulate(np.linspace(0, 2 * np.pi, 2 * 10**7))",
    "walker_body_clearance": "catalog.quadruped_hoecken().body_clearance(10**10)",
    "walker_search_phases": "catalog.quadruped_hoecken().search_phases(samples=10**10)",
    "catalogue_figures": "catalog.figures(samples=10**10)",
    "circumcentre_broadcast": (
        "geometry.circumcentre(np.zeros((10**5, 1, 2)), np.ones((1, 10**5, 2)), [0.0, 1.0])"
    ),
    "burmester_curve_samples": (
        "linkage.synthesis.centre_point_curve([(1.0, 1.1, 0.4), (0.3, 1.7, 0.3), "
        "(-0.6, 1.5, 0.5), (-1.0, 1.0, 0.9)], n=2**62)"
    ),
    "motion_rotations": (
        "linkage.synthesis.motion([(1.0, 1.1, 0.4), (0.3, 1.7, 0.3), (-0.6, 1.5, 0.5), "
        "(-1.0, 1.0, 0.9)], n=10**10)"
    ),
    # 20,000 rotations fit; their dyads' ordered pairs (grow as n squared) do not
    "motion_dyad_pairs": (
        "linkage.synthesis.motion([(1.0, 1.1, 0.4), (0.3, 1.7, 0.3), (-0.6, 1.5, 0.5), "
        "(-1.0, 1.0, 0.9)], n=20_000)"
    ),
    "curvature_centre_broadcast": (
        "geometry.curvature_centre(np.broadcast_to(np.ones(2), (10**10, 2)), [0.0, 1.0], [1.0, 0.0])"
    ),
}


UNREPRESENTABLE = {
    "circuit": "catalog.hoecken().circuit(2**64)",
    "uniform_sweep": "catalog.hoecken().uniform_sweep(0.0, 0.1, 10**30)",
    "cam_profile": "linkage.cam.leg_lift_cam().profile(2**63)",
}


@pytest.fixture(scope="module")
def python_checked():
    """Every case checked in Python, run in one limited child (none of them can abort it):
    ``{name: {"outcome": ..., "message": ...}}``."""
    cases = {**PYTHON_CASES, **{f"count:{k}": v for k, v in UNREPRESENTABLE.items()}}
    body = "\n".join(
        f"try:\n    {code}\n    report({name!r} + ':ok')\n"
        f"except MemoryError as exc:\n    report({name!r} + ':MemoryError', exc)\n"
        f"except linkage.LinkageError as exc:\n    report({name!r} + ':LinkageError', exc)"
        for name, code in cases.items()
    )
    out = run_limited(body, all_lines=True)
    return {r["outcome"].rsplit(":", 1)[0]: r for r in out if ":" in r["outcome"]}


@pytest.mark.parametrize("name", sorted(PYTHON_CASES))
def test_python_sizes_are_memory_errors(python_checked, name):
    r = python_checked[name]
    assert r["outcome"] == f"{name}:MemoryError", r
    assert SIZE.search(r["message"]), f"the MemoryError does not name the size: {r['message']!r}"


@pytest.mark.parametrize("name", sorted(UNREPRESENTABLE))
def test_unrepresentable_counts_are_linkage_errors(python_checked, name):
    r = python_checked[f"count:{name}"]
    assert r["outcome"] == f"count:{name}:LinkageError" and "too large" in r["message"], r


# -- allocated by the extension: await A's size checks (abort or panic today) ------------------
def test_sweep_huge_theta_is_memory_error():
    """Awaits A: 2.5e7 angles (0.2 GB, fits) of Jansen's leg asking for every output, ~35 GB."""
    expect_memory_error(
        """
        theta = np.linspace(0, 2 * np.pi, 25_000_000)
        outputs = ("point", "velocity", "acceleration", "instant_centres", "curvature")
        catalog.jansen().sweep(theta, omega=1.0, outputs=outputs)
        """
    )


def test_uniform_sweep_huge_n_is_memory_error():
    """Awaits A (D3): 1e10 points, 160 GB."""
    expect_memory_error("catalog.hoecken().uniform_sweep(0.0, 1e-9, 10**10)")


def test_circuit_huge_n_is_memory_error():
    """Awaits A (D2): 1e10 samples of a circuit, 1.7 TB."""
    expect_memory_error("catalog.evans_b().circuit(10**10)")


def test_program_eval_beyond_the_limit_is_memory_error():
    """Awaits A ("rlimit"): 1.2e8 times (0.96 GB, fits) → 3.8 GB of program values."""
    expect_memory_error(
        """
        p = Program(0.0, [Segment(1.0, 1.0, "cycloidal")])
        p.eval(np.linspace(0.0, 1.0, 120_000_000))
        """
    )


def test_motion_law_beyond_the_limit_is_memory_error():
    """Awaits A ("rlimit"): 1.2e8 points of a motion law, 3.8 GB."""
    expect_memory_error('motion_law("cycloidal", np.linspace(0.0, 1.0, 120_000_000))')


def test_schedule_angles_beyond_the_limit_is_memory_error():
    """Awaits A ("rlimit"): a crank schedule at 1.2e8 times, 2.9 GB."""
    expect_memory_error(
        """
        s = crank_schedule(catalog.hoecken(), 100.0, 0.6, samples=64, resolution=721)
        s.angles(np.linspace(0.0, 1.0, 120_000_000))
        """
    )


def test_uniform_sweep_many_threads():
    """Awaits A (D3): 1e5 threads asked for; under the address-space limit they cannot all
    have stacks. A result (threads capped) or a LinkageError — not a 'failed to spawn thread'
    panic."""
    r = run_limited(
        """
        pts = catalog.hoecken().uniform_sweep(0.0, 1e-3, 100_000, block=1, threads=100_000)
        ref = catalog.hoecken().uniform_sweep(0.0, 1e-3, 100_000, block=1)
        assert np.array_equal(pts, ref, equal_nan=True)
        """
    )
    assert r["outcome"] in ("ok", "LinkageError", "MemoryError"), r


def test_forces_beyond_the_limit_is_memory_error():
    """Awaits A ("rlimit"): kinetostatics at 5e7 angles (θ, ω, α: 1.2 GB, fit): torques and
    every joint reaction, ~5 GB."""
    expect_memory_error(
        """
        from linkage.forces import LinkMass, joint_forces
        masses = {k: LinkMass(1.0) for k in ("crank", "coupler", "rocker")}
        joint_forces(catalog.hoecken(), np.linspace(0, 2 * np.pi, 50_000_000), 1.0, masses=masses)
        """
    )
