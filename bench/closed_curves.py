"""Exact recovery of closed four-bar curves: how many ``linkage.synthesis.path`` fits to within
1e-6 of the target's size, with and without its first stage, the four-bars from the equation
of the curve through the points (without it: the search as it was before that stage).

    .venv/bin/python bench/closed_curves.py [--curves 120] [--seed 5]

Targets: random four-bars (ground 1; crank, coupler, rocker log-uniform in [0.3, 3]; coupler
point ``coupler·(u, v)``, ``u`` in [-1, 2], ``v`` in [-1, 1]; either assembly; as in a new
user's trial, 2026-11-27), 20, 30, 40 or 60 points of ``circuit(2001)`` taken evenly in its
index (crank angles crowd at a rocker's limits) or by arc length, under a random rotation,
scale (10⁻² … 10²) and start point. Each target is searched with ``path``'s defaults (``top=1``,
default atlases), without the curve's equation (``CURVE_EQUATION_POINTS`` beyond any target)
and with it, one after the other in one process. The targets either search leaves above 1e-6
are printed, with both errors (over the target's RMS radius) and wall times, then the counts
and the times.
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
    least = synthesis.stages.CURVE_EQUATION_POINTS
    exact = [0, 0]
    spent = [[], []]
    for i, (fb, n, mode, target) in enumerate(cases):
        size = synthesis.target_size(target)
        errors, times = [], []
        for with_equation in (False, True):
            synthesis.stages.CURVE_EQUATION_POINTS = least if with_equation else 10**9
            t = time.perf_counter()
            found = synthesis.path(target, top=1)
            times.append(time.perf_counter() - t)
            errors.append(found[0].error / size if found else np.inf)
        synthesis.stages.CURVE_EQUATION_POINTS = least
        for k in (0, 1):
            exact[k] += errors[k] <= 1e-6
            spent[k].append(times[k])
        if max(errors) > 1e-6:
            print(
                f"{i:4d} {fb.grashof():14s} {n:3d} {mode:9s} "
                f"without {errors[0]:.1e} in {times[0]:5.2f} s, with {errors[1]:.1e} "
                f"in {times[1]:5.2f} s",
                flush=True,
            )
    ratio = np.median(np.array(spent[1]) / np.array(spent[0]))
    print(
        f"exact to 1e-6 of the size: {exact[0]}/{len(cases)} without the curve's equation, "
        f"{exact[1]} with; median time {np.median(spent[0]):.2f} s without, "
        f"{np.median(spent[1]):.2f} s with (median ratio {ratio:.2f}), "
        f"at most {max(spent[0]):.2f} s and {max(spent[1]):.2f} s"
    )


if __name__ == "__main__":
    main()
