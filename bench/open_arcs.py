"""Exact recovery of open arcs: how many arcs of four-bar coupler curves ``linkage.synthesis.path``
finds a linkage for to within 1e-6 of the target's size, and in what time.

    .venv/bin/python bench/open_arcs.py [--random 40] [--seed 0] [--entries N] [--out rows.csv]
    .venv/bin/python bench/open_arcs.py --kind slider-crank [--random 30] [--seed 0]
    .venv/bin/python bench/open_arcs.py --compare ...   (each target without, then with, the
                                                         curve-equation stage)

Targets: arcs of the catalogue four-bars (Hoecken, Chebyshev, Watt, Roberts, Evans A and B) and
of random four-bars (the test suite's ``random_fourbar``: ground 1, crank, coupler, rocker
log-uniform in [0.3, 3], coupler point near the coupler, either assembly), each an arc of a
uniformly random fraction 1/8 … 3/4 of its circuit from a random start, 40 points evenly spaced
in the circuit parameter, under a random rotation, scale (10⁻² … 10²) and translation. The error is ``path``'s own (largest
distance target point → coupler curve, the true point-to-curve distance at the optimum) over
the target's RMS radius; the search runs with its defaults (``top=1``, default atlas). The arc
atlas is built (or loaded from the cache) before any target is timed, and its build is timed
on its own.

``--kind slider-crank``: arcs of random slider-cranks instead (the tests' ``random_slider_crank``:
crank 1, rod 0.3 … 4, any offset at which it moves, any point, line and reach), matched in the
slider-crank arc atlas (``kind="slider-crank-arcs"``); there is no catalogue part.
"""

from __future__ import annotations

import argparse
import math
import statistics
import sys
import time
from pathlib import Path

import numpy as np

import linkage
from linkage import synthesis

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "tests"))
from test_slider_synthesis import random_slider_crank
from test_synthesis import arc_of, random_fourbar  # the tests' generators


def arc(fb: linkage.FourBar, rng: np.random.Generator) -> np.ndarray:
    """An arc of a random fraction 1/8 … 3/4 of ``fb``'s circuit (the test suite's
    ``arc_of``: 40 points from a random start, placed anywhere at any scale)."""
    return arc_of(fb, rng, rng.uniform(1 / 8, 3 / 4))


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--kind", choices=("fourbar", "slider-crank"), default="fourbar")
    ap.add_argument("--random", type=int, default=None, help="random linkages (40; sliders 30)")
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--entries", type=int, default=None, help="arc atlas entries (default)")
    ap.add_argument("--out", default=None)
    ap.add_argument(
        "--compare",
        action="store_true",
        help="run each target without the curve-equation stage first, then with it",
    )
    args = ap.parse_args()
    rng = np.random.default_rng(args.seed)
    cases = []
    slider = args.kind == "slider-crank"
    if slider:
        for k in range(30 if args.random is None else args.random):
            cases.append((f"random#{k}", arc(random_slider_crank(rng), rng)))
    else:
        for name in ("hoecken", "chebyshev", "watt", "roberts", "evans_a", "evans_b"):
            fb = linkage.catalog.get(name)
            assert isinstance(fb, linkage.FourBar)
            for k in range(3):
                cases.append((f"{name}#{k}", arc(fb, rng)))
        for k in range(40 if args.random is None else args.random):
            cases.append((f"random#{k}", arc(random_fourbar(rng), rng)))

    has_arcs = hasattr(synthesis, "ARCS")
    atlas = None
    if has_arcs:
        t0 = time.perf_counter()
        arcs = synthesis.SLIDER_ARCS if slider else synthesis.ARCS
        default = synthesis.DEFAULT_SLIDER_ARC_ENTRIES if slider else synthesis.DEFAULT_ARC_ENTRIES
        fresh = synthesis.Atlas.build(args.entries or default, kind=arcs)
        build = time.perf_counter() - t0
        mb = (fresh.descriptors.nbytes + fresh.params.nbytes) / 1e6
        print(f"arc atlas: {len(fresh):,} entries built in {build:.1f} s, {mb:.0f} MB")
        atlas = fresh
    import scipy.optimize  # noqa: F401  (one-time import, outside the timed calls)

    errs, times, rows = [], [], []
    off_errs, ratios = [], []
    least = (synthesis.stages.CURVE_EQUATION_POINTS, synthesis.stages.SLIDER_EQUATION_POINTS)

    def run(target: np.ndarray, size: float, with_equation: bool) -> tuple[float, float]:
        # The stage is off when no target has enough points for it.
        on = least if with_equation else (10**9, 10**9)
        synthesis.stages.CURVE_EQUATION_POINTS, synthesis.stages.SLIDER_EQUATION_POINTS = on
        try:
            t0 = time.perf_counter()
            kw = {"atlas": atlas} if atlas is not None else {}
            found = synthesis.path(target, closed=False, top=1, kind=args.kind, **kw)
            dt = time.perf_counter() - t0
        finally:
            synthesis.stages.CURVE_EQUATION_POINTS, synthesis.stages.SLIDER_EQUATION_POINTS = least
        return (found[0].error / size if found else math.inf), dt

    for name, target in cases:
        size = synthesis.target_size(target)
        before = ""
        if args.compare:
            e0, dt0 = run(target, size, False)
            off_errs.append(e0)
            before = f"without the equation {e0:9.2e} {dt0:6.2f} s; with "
        e, dt = run(target, size, True)
        if args.compare:
            ratios.append(dt / dt0)
        errs.append(e)
        times.append(dt)
        rows.append((name, e, dt))
        print(f"{name:14s} {before}{e:9.2e} {dt:6.2f} s", flush=True)
    if args.compare:
        ok = int(np.sum(np.array(off_errs) <= 1e-6))
        print(
            f"without the equation: {ok}/{len(off_errs)} within 1e-6 of the size; time with / "
            f"without: median ratio {statistics.median(ratios):.2f}"
        )
    errs_a = np.array(errs)
    cat = np.array([not n.startswith("random") for n, _, _ in rows])
    for label, mask in (("catalogue", cat), ("random", ~cat), ("all", np.ones_like(cat))):
        if not mask.any():
            continue
        ok = int(np.sum(errs_a[mask] <= 1e-6))
        print(
            f"{label:9s}: {ok}/{int(mask.sum())} within 1e-6 of the size; median error "
            f"{np.median(errs_a[mask]):.1e}"
        )
    print(f"time per target: median {statistics.median(times):.2f} s, max {max(times):.2f} s")
    if args.out:
        with open(args.out, "w") as f:
            for name, e, dt in rows:
                f.write(f"{name},{e:.3e},{dt:.3f}\n")


if __name__ == "__main__":
    main()
