"""The ``linkage`` command line: ``linkage run`` (the main job) and ``linkage catalog``."""

from __future__ import annotations

import argparse
import math
import sys
import time
from collections.abc import Sequence

import numpy as np

from linkage import catalog
from linkage._core import LinkageError
from linkage._fourbar import FourBar

MOTOR_RPM = 50.0
"""Thesis 1's motor speed; its 18 → 15 → 14 simple gear train turns the crank 18/14 = 9/7 times
faster (the 15-tooth idler only reverses twice)."""
GEAR_RATIO = 18.0 / 14.0
STRAIGHT_TOL_MM = 0.1


def hoecken_report(samples: int = 3601) -> list[tuple[str, str, str, str]]:
    """Analyse the Hoecken leg under thesis 1's constant-speed drive.

    Returns rows ``(figure, value, unit, error estimate)``; every figure is computed here.
    """
    fb = catalog.hoecken()
    crank_rpm = MOTOR_RPM * GEAR_RATIO
    omega = crank_rpm * 2.0 * math.pi / 60.0
    theta = np.linspace(0.0, 2.0 * np.pi, samples)

    t0 = time.perf_counter()
    s = fb.sweep(theta, omega=omega, outputs=("point", "velocity", "acceleration"))
    t_sweep = time.perf_counter() - t0

    p, v, a, j = s.point, s.velocity, s.acceleration, s.joints
    # Error estimates: loop closure (link lengths) and derivative consistency (analytic
    # velocity against a central difference of positions in time).
    closure = max(
        np.abs(np.linalg.norm(j[:, 3] - j[:, 2], axis=1) - fb.coupler).max(),
        np.abs(np.linalg.norm(j[:, 3] - j[:, 1], axis=1) - fb.rocker).max(),
    )
    dt = (theta[1] - theta[0]) / omega
    fd = (p[2:] - p[:-2]) / (2 * dt)
    vel_err = np.abs(fd - v[1:-1]).max()
    acc_fd = (v[2:] - v[:-2]) / (2 * dt)
    acc_err = np.abs(acc_fd - a[1:-1]).max()
    speed = np.linalg.norm(v, axis=1)
    accel = np.linalg.norm(a, axis=1)

    # Stance: the contiguous run of samples within STRAIGHT_TOL_MM of the lowest point,
    # taken around the lowest sample (the crank angle wraps, so search a doubled cycle).
    y = p[:-1, 1]
    n = len(y)
    low = int(np.argmin(y))
    near = np.concatenate([y, y]) - y.min() <= STRAIGHT_TOL_MM
    lo = low
    while lo > low - n + 1 and near[lo - 1 + n]:
        lo -= 1
    hi = low
    while hi < low + n - 1 and near[(hi + 1) % (2 * n)]:
        hi += 1
    idx = np.arange(lo, hi + 1) % n
    stance = p[idx]
    centred = stance - stance.mean(axis=0)
    direction = np.linalg.svd(centred, full_matrices=False)[2][0]
    normal = np.array([-direction[1], direction[0]])
    deviation = np.abs(centred @ normal).max()
    length = np.ptp(centred @ direction)
    vx = np.abs(v[idx, 0])
    ripple = (vx.max() - vx.min()) / vx.mean()
    lift = p[:, 1].max() - p[:, 1].min()
    mu = fb.transmission_angle(theta)

    def f(x: float, digits: int = 3) -> str:
        return f"{x:.{digits}f}"

    def e(x: float) -> str:
        return f"{x:.1e}"

    rows = [
        ("Grashof class", fb.grashof(), "", "exact"),
        ("crank speed (50 rpm motor, 18→15→14 gears)", f(crank_rpm), "rpm", "exact"),
        (
            "transmission angle min / max",
            f"{math.degrees(np.nanmin(mu)):.2f} / {math.degrees(np.nanmax(mu)):.2f}",
            "deg",
            "sampled 0.1°",
        ),
        (
            "foot path x range",
            f"{f(p[:, 0].min())} … {f(p[:, 0].max())}",
            "mm",
            f"closure {e(closure)}",
        ),
        (
            "foot path y range",
            f"{f(p[:, 1].min())} … {f(p[:, 1].max())}",
            "mm",
            f"closure {e(closure)}",
        ),
        (f"stance (within {STRAIGHT_TOL_MM} mm of lowest) length", f(length), "mm", "sampled 0.1°"),
        ("stance share of crank turn", f(100.0 * len(idx) / n, 1), "%", "sampled 0.1°"),
        ("stance max deviation from best-fit line", f(deviation, 4), "mm", f"closure {e(closure)}"),
        (
            "stance foot speed mean / ripple",
            f"{f(vx.mean(), 1)} / {f(100 * ripple, 1)}%",
            "mm/s",
            f"vel {e(vel_err)}",
        ),
        ("lift height (swing above stance)", f(lift), "mm", f"closure {e(closure)}"),
        ("peak foot speed", f(speed.max(), 1), "mm/s", f"vel {e(vel_err)}"),
        ("peak foot acceleration", f(accel.max(), 1), "mm/s²", f"acc {e(acc_err)}"),
        ("smallest dyad margin (sin transmission)", f(float(np.nanmin(s.margin)), 4), "", "exact"),
        (f"sweep time ({samples} samples, pos+vel+acc)", f(1e3 * t_sweep, 2), "ms", "wall clock"),
    ]
    return rows


def print_table(title: str, rows: Sequence[tuple[str, str, str, str]]) -> None:
    """Print rows as an aligned four-column table."""
    head = ("figure", "value", "unit", "error estimate")
    widths = [max(len(r[i]) for r in [head, *rows]) for i in range(4)]
    line = "  ".join("-" * w for w in widths)
    print(title)
    print(line)
    print("  ".join(h.ljust(w) for h, w in zip(head, widths)))
    print(line)
    for r in rows:
        print("  ".join(c.ljust(w) for c, w in zip(r, widths)))
    print(line)


def _run(args: argparse.Namespace) -> int:
    if args.scene is not None:
        raise LinkageError(
            f"scene files are not supported yet (got {args.scene!r}); "
            "run `linkage run` for the default study"
        )
    rows = hoecken_report(args.samples)
    print_table(
        "Hoecken straight-line leg (thesis 1): "
        "ground 20, crank 10, coupler = rocker = 25, foot 50 mm",
        rows,
    )
    return 0


def _catalog(_: argparse.Namespace) -> int:
    rows = []
    for name in catalog.names():
        item = catalog.get(name)
        if isinstance(item, FourBar):
            lim = item.input_limits()
            rng = (
                "full turn"
                if lim is None
                else f"{math.degrees(lim[0]):.1f}° … {math.degrees(lim[1]):.1f}°"
            )
            rows.append((name, "four-bar", item.grashof(), rng))
        else:
            rows.append((name, f"{len(item)} joints", "multi-loop", f"trace {item.trace}"))
    w = [max(len(r[i]) for r in rows) for i in range(4)]
    for r in rows:
        print("  ".join(c.ljust(x) for c, x in zip(r, w)))
    return 0


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of the ``linkage`` console script."""
    parser = argparse.ArgumentParser(prog="linkage", description=__doc__)
    sub = parser.add_subparsers(dest="command", required=True)
    run = sub.add_parser("run", help="run a study (default: the Hoecken leg analysis)")
    run.add_argument("scene", nargs="?", default=None, help="scene file (not yet supported)")
    run.add_argument(
        "--samples", type=int, default=3601, help="crank angles per turn (default 3601)"
    )
    run.set_defaults(func=_run)
    cat = sub.add_parser("catalog", help="list the built-in linkages")
    cat.set_defaults(func=_catalog)
    args = parser.parse_args(argv)
    if getattr(args, "samples", 3) < 3:
        parser.error("--samples must be at least 3")
    try:
        return int(args.func(args))
    except LinkageError as exc:
        print(f"linkage: error: {exc}", file=sys.stderr)
        return 2


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
