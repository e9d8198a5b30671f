"""Constrained path synthesis: what ``lengths`` and ``pivots`` cost, as the time of each
constrained search over the same target's unconstrained search, run in one process (these
machines are noisy), and the best error each finds (over the target's RMS radius).

    .venv/bin/python bench/constrained.py [--only NAME]

Targets: the open foot path of a designer's trial (a straight stance and lift-off, mm) as a
four-bar (a full-turn crank, transmission ≥ 30°) and a slider-crank, lengths 5 … 120 mm; Hoecken's closed curve and an arc of it, with bounds that hold Hoecken's own
linkage (ground 20, crank 10, coupler and rocker 25, its point 50 from A; pivots (0, 0) and
(20, 0)), so an exact fit exists; the example foot path with a box its pivots are not in.
Default atlases (built or loaded from the cache first, untimed).
"""

from __future__ import annotations

import argparse
import math
import time
from pathlib import Path
from typing import Any

import numpy as np

import linkage
from linkage import synthesis

ROOT = Path(__file__).resolve().parent.parent


def targets() -> list[tuple[str, np.ndarray, dict[str, Any], dict[str, Any]]]:
    """(name, points, the search's settings, the constraints added)."""
    hoecken = linkage.catalog.get("hoecken")
    assert isinstance(hoecken, linkage.FourBar)
    curve = hoecken.circuit(121).point[:-1][::2]
    arc = hoecken.circuit(241).point[:-1][20:90:2]
    foot = synthesis.read_points(ROOT / "examples" / "foot_path.csv")
    # The trial's open foot path (mm): a 60 mm straight stance in 20 points, then the first
    # 30 % of a 20 mm high half-sine swing back over it in 8 (lift-off).
    stance = np.column_stack([np.linspace(0.0, 60.0, 20), np.zeros(20)])
    t = np.linspace(0.0, 0.3, 9)[1:]
    open_foot = np.vstack([stance, np.column_stack([60.0 - 60.0 * t, 20.0 * np.sin(np.pi * t)])])
    mu = math.radians(30)
    lengths = (5.0, 120.0)
    return [
        (
            "open foot, four-bar",
            open_foot,
            dict(closed=False, top=6, full_turn=True, min_transmission=mu),
            dict(lengths=lengths),
        ),
        (
            "open foot, slider-crank",
            open_foot,
            dict(closed=False, top=6, kind="slider-crank"),
            dict(lengths=lengths),
        ),
        (
            "open foot, pivots",
            open_foot,
            dict(closed=False, top=6),
            dict(pivots=((-40, 30), (100, 120))),
        ),
        ("Hoecken, lengths", curve, dict(top=3), dict(lengths=(5, 60))),
        ("Hoecken, pivots", curve, dict(top=3), dict(pivots=((-5, -5), (30, 5)))),
        ("Hoecken arc, lengths", arc, dict(closed=False, top=3), dict(lengths=(5, 60))),
        ("Hoecken arc, pivots", arc, dict(closed=False, top=3), dict(pivots=((-5, -5), (30, 5)))),
        (
            "foot path, pivots",
            foot,
            dict(top=5, full_turn=True),
            dict(pivots=((-40, 30), (100, 120))),
        ),
    ]


def timed(points: np.ndarray, **kw: Any) -> tuple[float, float, int]:
    """(seconds, best error over the size, candidates found)."""
    t = time.perf_counter()
    found = synthesis.path(points, **kw)
    took = time.perf_counter() - t
    best = found[0].error / synthesis.target_size(points) if found else math.nan
    return took, best, len(found)


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--only", default=None, help="targets whose name contains this")
    args = ap.parse_args()
    for kind in ("fourbar", "fourbar-arcs", "slider-crank", "slider-crank-arcs"):
        synthesis.default_atlas(kind=kind)
    print(
        f"{'target':26s} {'free s':>7s} {'error':>9s} {'bound s':>8s} {'error':>9s} "
        f"{'found':>5s} {'time ratio':>10s}"
    )
    ratios = []
    for name, points, kw, bound in targets():
        if args.only and args.only not in name:
            continue
        t0, e0, _ = timed(points, **kw)
        t1, e1, n1 = timed(points, **kw, **bound)
        ratios.append(t1 / t0)
        print(
            f"{name:26s} {t0:7.2f} {e0:9.2e} {t1:8.2f} {e1:9.2e} {n1:5d} {t1 / t0:10.2f}",
            flush=True,
        )
    if ratios:
        print(f"time ratio bound/free: median {np.median(ratios):.2f}, largest {max(ratios):.2f}")


if __name__ == "__main__":
    main()
