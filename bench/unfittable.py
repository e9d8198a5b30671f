"""Time of path synthesis on targets no linkage draws: random points, open, against the budgets
of issue 29 (100 points within 15 s, 10,000 within 60 s).

    .venv/bin/python bench/unfittable.py [--points 100 10000] [--repeat 2] [--seed 0] [--closed]

Each target is ``--points`` points uniform in the square [-1, 1]², seeded, searched by
``linkage.synthesis.path(points, closed=False)`` with its defaults (the default arc atlas is
loaded or built first, untimed; SciPy imported first, untimed). Every stage of an open search
runs on such a target, none reaching an exact fit: the longest search there is. Prints the wall
and CPU time of each run, the best error over the target's size, the residual evaluations (of
one placed linkage on every point it is fitted to, counted through ``synthesis._residuals``)
and the ratio of the wall time to the budget (≤ 1 is within it). The machine may be shared:
``--repeat`` and take the least.
"""

from __future__ import annotations

import argparse
import time
from typing import Any

import numpy as np

from linkage import synthesis

EVALUATIONS = [0]
"""Residual evaluations so far (rows of ``synthesis._residuals``)."""
_residuals = synthesis.fitting._residuals


def _counted(kind: Any, params: Any, *rest: Any) -> Any:
    EVALUATIONS[0] += len(params)
    return _residuals(kind, params, *rest)


synthesis.fitting._residuals = _counted  # type: ignore[assignment]

BUDGET = {100: 15.0, 10_000: 60.0}
"""Seconds the issue allows: a 100-point target 15 s, a 10,000-point one 60 s."""


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--points", type=int, nargs="+", default=[100, 10_000])
    ap.add_argument("--repeat", type=int, default=1)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--closed", action="store_true", help="closed targets instead")
    args = ap.parse_args()
    synthesis.default_atlas(kind="fourbar" if args.closed else "fourbar-arcs")
    import scipy.optimize  # type: ignore[import-untyped]  # noqa: F401  (imported untimed)

    worst = 0.0
    for n in args.points:
        pts = np.random.default_rng(args.seed).uniform(-1.0, 1.0, (n, 2))
        budget = BUDGET.get(n, 15.0 + 45.0 * (n - 100) / 9_900)
        walls = []
        for _ in range(args.repeat):
            before = EVALUATIONS[0]
            t0, c0 = time.perf_counter(), time.process_time()
            found = synthesis.path(pts, closed=args.closed)
            wall, cpu = time.perf_counter() - t0, time.process_time() - c0
            spent = EVALUATIONS[0] - before
            walls.append(wall)
            err = found[0].error / synthesis.target_size(pts) if found else float("nan")
            print(
                f"{n:6d} points: wall {wall:6.1f} s, cpu {cpu:6.1f} s, best error {err:.3f} of "
                f"the size, {spent:,} evaluations; wall / budget {wall / budget:.2f} "
                f"(budget {budget:.0f} s)",
                flush=True,
            )
        worst = max(worst, min(walls) / budget)
    print(f"largest ratio of the least wall time to the budget: {worst:.2f}")


if __name__ == "__main__":
    main()
