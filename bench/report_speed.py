"""Speed of the default ``linkage run`` as a whole process against the floor it cannot beat:
starting Python and importing linkage and matplotlib (issue 12: within 2.5×).

Both commands run as fresh processes, alternately (so a busy machine slows both alike), each
``--repeat`` times (at least 5); the medians and their ratio are printed. The run is the
default scene (no scene file) writing its report into a temporary working directory.

    python bench/report_speed.py [--repeat 7] [--scene examples/hoecken.toml]
"""

from __future__ import annotations

import argparse
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

TARGET = 2.5
"""Issue 12's bound on the ratio."""


def timed(cmd: list[str], cwd: str) -> float:
    t0 = time.perf_counter()
    subprocess.run(cmd, cwd=cwd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    return time.perf_counter() - t0


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--repeat", type=int, default=7, help="runs of each command (min 5)")
    ap.add_argument("--scene", help="scene file (default: the built-in default scene)")
    args = ap.parse_args()
    repeat = max(5, args.repeat)
    py = sys.executable
    floor = [py, "-c", "import linkage, matplotlib.pyplot"]
    scene = [str(Path(args.scene).resolve())] if args.scene else []
    with tempfile.TemporaryDirectory() as tmp:
        run = [py, "-m", "linkage", "run", *scene, "--out", "report", "--force"]
        # Warm the file cache and matplotlib's font cache first.
        timed(floor, tmp)
        timed(run, tmp)
        a, b = [], []
        for _ in range(repeat):
            a.append(timed(floor, tmp))
            b.append(timed(run, tmp))
        files = sorted(os.listdir(Path(tmp) / "report"))
    ta, tb = statistics.median(a), statistics.median(b)
    ratio = tb / ta
    print(f"import linkage, matplotlib.pyplot: median {ta:.3f} s over {repeat} runs")
    print(f"linkage run {' '.join(scene) or '(default scene)'}: median {tb:.3f} s")
    print(f"  report: {', '.join(f for f in files if not f.startswith('.'))}")
    print(f"ratio {ratio:.2f} (target ≤ {TARGET}) {'OK' if ratio <= TARGET else 'OVER'}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
