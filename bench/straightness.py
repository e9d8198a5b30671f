"""Straight-part detection (``linkage.straightness``) against path size: time per call for
10^3 … 10^6 samples of a Hoecken foot path (closed, tol = 0.001 × size), the growth per decade
against n log n, then two comparisons timed in one process by ignored core tests: the direct
O(n·w) scan (kept in the core as the test reference), the segment tree of hulls it used before
(O(log² n) per window check, kept test-only) and the queue of two hulls (O(log n)) on the
4·10^4-sample path, and the last two on the 10^6-sample path.

    python bench/straightness.py            # needs the built extension; cargo for the last part
"""

from __future__ import annotations

import math
import os
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

import linkage

ROOT = Path(__file__).resolve().parent.parent
SIZE = 25.0  # mm, the Hoecken coupler (README table)
TOL = 0.001 * SIZE


def foot_path(n: int) -> np.ndarray:
    fb = linkage.FourBar(ground=20, crank=10, coupler=25, rocker=25, point=(50, 0))
    theta = np.linspace(0.0, 2.0 * np.pi, n, endpoint=False)
    return np.ascontiguousarray(fb.sweep(theta).point)


def best_time(path: np.ndarray, repeats: int) -> tuple[float, float, int]:
    """Best wall and CPU (process) time of a call, and the run's sample count."""
    wall = cpu = math.inf
    count = 0
    for _ in range(repeats):
        t, c = time.perf_counter(), time.process_time()
        part = linkage.straightness(path, TOL, closed=True)
        wall = min(wall, time.perf_counter() - t)
        cpu = min(cpu, time.process_time() - c)
        count = part.count if part is not None else 0
    return wall, cpu, count


def core_timing(path: np.ndarray, test: str) -> str:
    """The first ``n = `` line the ignored core test ``test`` prints on ``path``."""
    cargo = shutil.which("cargo")
    if cargo is None:
        return "cargo not found: not timed"
    with tempfile.TemporaryDirectory() as tmp:
        f = Path(tmp) / "path.txt"
        rows = "\n".join(f"{x!r} {y!r}" for x, y in path.tolist())
        f.write_text(f"{TOL!r} 1\n{rows}\n")
        cmd = [
            cargo,
            "test",
            "-q",
            "-p",
            "linkage-core",
            "--release",
            "--lib",
            f"straightness::tests::{test}",
            "--",
            "--ignored",
            "--exact",
            "--nocapture",
        ]
        env = dict(os.environ, STRAIGHT_BENCH_PATH=str(f))
        out = subprocess.run(cmd, cwd=ROOT, env=env, capture_output=True, text=True, check=False)
    lines = [ln for ln in out.stdout.splitlines() if ln.startswith("n = ")]
    if out.returncode != 0 or not lines:
        return f"{test} failed:\n{out.stdout}\n{out.stderr}"
    return lines[0]


def main() -> int:
    load = ", ".join(f"{x:.1f}" for x in os.getloadavg())
    print(f"Hoecken foot path, closed, tol = {TOL} mm; best of 3 calls (2 at 10^6)")
    print(f"{os.cpu_count()} CPUs, load average {load} (wall times stretch with load)")
    head = f"{'n':>9} {'wall (s)':>10} {'CPU (s)':>10} {'run':>8}"
    print(f"{head} {'CPU x/decade':>13} {'n log2 n x':>11}")
    prev: tuple[int, float] | None = None
    for n in (10**3, 10**4, 4 * 10**4, 10**5, 10**6):
        path = foot_path(n)
        wall, cpu, count = best_time(path, 2 if n >= 10**6 else 3)
        growth = model = ""
        if prev is not None and n == 10 * prev[0]:
            growth = f"{cpu / prev[1]:.1f}"
            model = f"{n * math.log2(n) / (prev[0] * math.log2(prev[0])):.1f}"
        print(f"{n:>9} {wall:>10.4f} {cpu:>10.4f} {count:>8} {growth:>13} {model:>11}")
        if n != 4 * 10**4:
            prev = (n, cpu)
    print()
    print("direct scan, tree check (before) and queue (now), one process, 4*10^4 samples:")
    print(core_timing(foot_path(4 * 10**4), "direct_scan_timing"))
    print("tree check (before) and queue (now), one process, 10^6 samples:")
    print(core_timing(foot_path(10**6), "fast_scan_timing"))
    return 0


if __name__ == "__main__":
    sys.exit(main())
