"""Exact recovery of closed four-bar curves: how many ``linkage.synthesis.path`` fits to within
1e-6 of the target's size, with and without the search of the target's parts as open arcs.

    .venv/bin/python bench/closed_curves.py [--curves 120] [--seed 5]

Targets: random four-bars (ground 1; crank, coupler, rocker log-uniform in [0.3, 3]; coupler
point ``coupler·(u, v)``, ``u`` in [-1, 2], ``v`` in [-1, 1]; either assembly; as in a new
user's trial, 2026-11-27), 20, 30, 40 or 60 points of ``circuit(2001)`` taken evenly in its
index (crank angles crowd at a rocker's limits) or by arc length, under a random rotation,
scale (10⁻² … 10²) and start point. Each target is searched with ``path``'s defaults (``top=1``,
default atlases) with the parts stage turned off (``PART_POINTS`` beyond any target: the search
before it); a target that is not fitted exactly is searched again with it. Only those are
printed, with both errors (over the target's RMS radius) and wall times.
"""

from __future__ import annotations

import argparse
import time

import numpy as np

import linkage
from linkage import synthesis


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--curves", type=int, default=120)
    ap.add_argument("--seed", type=int, default=5)
    args = ap.parse_args()
    rng = np.random.default_rng(args.seed)
    cases = []
    while len(cases) < args.curves:
        r, c, q = np.exp(rng.uniform(np.log(0.3), np.log(3), 3))
        fb = linkage.FourBar(
            ground=1.0,
            crank=r,
            coupler=c,
            rocker=q,
            point=(rng.uniform(-1, 2) * c, rng.uniform(-1, 1) * c),
            assembly=str(rng.choice(["open", "crossed"])),
        )
        try:
            circ = fb.circuit(2001).point
        except linkage.LinkageError:
            continue
        if not np.isfinite(circ).all():
            continue
        n = int(rng.choice([20, 30, 40, 60]))
        mode = str(rng.choice(["index", "arclength"]))
        if mode == "index":
            pts = circ[np.linspace(0, 2000, n + 1)[:-1].astype(int)]
        else:
            along = np.concatenate([[0], np.cumsum(np.hypot(*np.diff(circ, axis=0).T))])
            want = np.linspace(0, along[-1], n + 1)[:-1]
            pts = circ[np.searchsorted(along, want).clip(0, 2000)]
        a = rng.uniform(0, 2 * np.pi)
        rot = np.array([[np.cos(a), np.sin(a)], [-np.sin(a), np.cos(a)]])
        pts = pts @ rot * 10 ** rng.uniform(-2, 2)
        cases.append((fb, n, mode, np.roll(pts, int(rng.integers(n)), axis=0)))
    synthesis.default_atlas()
    synthesis.default_atlas(kind="fourbar-arcs")
    parts = synthesis.PART_POINTS
    exact = [0, 0]
    for i, (fb, n, mode, target) in enumerate(cases):
        size = synthesis.target_size(target)
        errors, times = [], []
        for with_parts in (False, True):
            synthesis.PART_POINTS = parts if with_parts else 10**9
            t = time.perf_counter()
            found = synthesis.path(target, top=1)
            times.append(time.perf_counter() - t)
            errors.append(found[0].error / size if found else np.inf)
            if errors[0] <= 1e-6:
                errors.append(errors[0])
                break
        synthesis.PART_POINTS = parts
        exact[0] += errors[0] <= 1e-6
        exact[1] += errors[1] <= 1e-6
        if errors[0] > 1e-6:
            print(
                f"{i:4d} {fb.grashof():14s} {n:3d} {mode:9s} "
                f"without {errors[0]:.1e} in {times[0]:5.2f} s, with {errors[1]:.1e} "
                f"in {times[1]:5.2f} s",
                flush=True,
            )
    print(f"exact to 1e-6 of the size: {exact[0]}/{len(cases)} without parts, {exact[1]} with")


if __name__ == "__main__":
    main()
