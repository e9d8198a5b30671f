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
from linkage.drive import Program, Segment
from linkage.forces import LinkMass, PointLoad, forces
from linkage.geometry import foot_path, three_point_centres

MOTOR_RPM = 50.0
"""Thesis 1's motor speed; its 18 → 15 → 14 simple gear train turns the crank 18/14 = 9/7 times
faster (the 15-tooth idler only reverses twice)."""
GEAR_RATIO = 18.0 / 14.0
STRAIGHT_TOL_MM = 0.1
THESIS_TWO_MASSES = {
    "crank": LinkMass(0.0036, (0.005, 0.0), 0.122432e-6),
    "coupler": LinkMass(0.0210, (0.0312566, 0.0), 2.17781e-6),
    "rocker": LinkMass(0.0060, (0.0125, 0.0), 0.774427e-6),
}
"""Thesis 2's link masses (kg), centres of mass (m along each link) and inertias (kg·m²)."""


def hoecken_report(samples: int = 3601) -> list[tuple[str, str, str, str]]:
    """Analyse the Hoecken leg under thesis 1's constant-speed drive.

    Returns rows ``(figure, value, unit, error estimate)``; every figure is computed here.
    """
    fb = catalog.hoecken()
    crank_rpm = MOTOR_RPM * GEAR_RATIO
    omega = crank_rpm * 2.0 * math.pi / 60.0
    theta = np.linspace(0.0, 2.0 * np.pi, samples)

    t0 = time.perf_counter()
    s = fb.sweep(theta, omega=omega, outputs=("point", "velocity", "acceleration", "curvature"))
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

    # Stance and swing: the longest run within STRAIGHT_TOL_MM of a line, on the closed path.
    n = len(p) - 1  # the last sample repeats the first
    fp = foot_path(p[:-1], STRAIGHT_TOL_MM, velocity=v[:-1])
    idx = fp.stance.indices
    mu = fb.transmission_angle(theta)

    # Swing curvature (analytic), and thesis 1 §2.1.1's three-point circumcentre estimate
    # against it at 1° and 0.1° spacing, over the swing.
    swing = np.setdiff1d(np.arange(1, n - 1), idx)
    radius = s.curvature_radius[swing]
    centre = s.curvature_centre
    three_point = {}
    for step in (10, 1):
        est = three_point_centres(p, step)  # aligned with p[step:-step]
        inner = swing[(swing >= step) & (swing < len(p) - step)]
        three_point[step] = float(
            np.nanmax(np.linalg.norm(est[inner - step] - centre[inner], axis=1))
        )

    def f(x: float, digits: int = 3) -> str:
        return f"{x:.{digits}f}"

    def e(x: float) -> str:
        return f"{x:.1e}"

    # Thesis 1's 3-4-5 drive (91° → 271° in 1 s, then on to 451°): peak foot speed and
    # acceleration against time, for comparison with its CAD (262 mm/s, 2204 mm/s²) and listing
    # (297.46 mm/s, 2677 mm/s²).
    program = Program(math.radians(91), [Segment(1.0, math.pi, "3-4-5")] * 2)
    t_law = np.linspace(0.0, 2.0, 4001)
    s_law = fb.sweep(time=t_law, drive=program, outputs=("velocity", "acceleration"))
    law_speed = float(np.linalg.norm(s_law.velocity, axis=1).max())
    law_accel = float(np.linalg.norm(s_law.acceleration, axis=1).max())
    crank_peak = float(np.degrees(program.angles(t_law)[1].max()))

    # Thesis 2's leg (same proportions, metres) at 20 rpm clockwise with its 0.5·9.81 N foot
    # force: crank torque by Newton–Euler, checked by the power method.
    leg_m = FourBar(ground=0.020, crank=0.010, coupler=0.025, rocker=0.025, point=(0.050, 0))
    t1 = time.perf_counter()
    torque = forces(
        leg_m,
        np.radians(np.arange(0.0, 360.0, 0.5)),
        omega=-20 * 2 * math.pi / 60,
        masses=THESIS_TWO_MASSES,
        gravity=(0.0, 0.0),
        loads=[PointLoad("coupler", "P", (0.5 * 9.81, 0.0))],
    )
    t_forces = time.perf_counter() - t1
    torque_check = float(np.abs(torque.torque - torque.power_torque).max())

    stance = fp.stance
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
        (
            f"stride (stance within {STRAIGHT_TOL_MM} mm of a line)",
            f(fp.stride),
            "mm",
            "sampled 0.1°",
        ),
        ("stance share of crank turn", f(100.0 * fp.stance_fraction, 1), "%", "sampled 0.1°"),
        (
            "stance max deviation from its line",
            f(stance.max_deviation, 4),
            "mm",
            f"closure {e(closure)}",
        ),
        (
            "stance foot speed mean / variation",
            f"{f(stance.mean_speed or 0.0, 1)} / {f(100 * (stance.speed_variation or 0.0), 1)}%",
            "mm/s",
            f"vel {e(vel_err)}",
        ),
        ("lift height (swing above stance line)", f(fp.lift_height), "mm", f"closure {e(closure)}"),
        (
            "swing radius of curvature min / max",
            f"{f(radius.min())} / {f(radius.max())}",
            "mm",
            f"acc {e(acc_err)}",
        ),
        (
            "three-point centre error, 1° / 0.1° spacing",
            f"{e(three_point[10])} / {e(three_point[1])}",
            "mm",
            "vs analytic",
        ),
        ("peak foot speed", f(speed.max(), 1), "mm/s", f"vel {e(vel_err)}"),
        ("peak foot acceleration", f(accel.max(), 1), "mm/s²", f"acc {e(acc_err)}"),
        ("smallest dyad margin (sin transmission)", f(float(np.nanmin(s.margin)), 4), "", "exact"),
        ("3-4-5 drive: peak crank speed", f(crank_peak, 1), "deg/s", "exact"),
        (
            "3-4-5 drive: peak foot speed / acceleration",
            f"{f(law_speed, 1)} / {f(law_accel, 0)}",
            "mm/s, mm/s²",
            "sampled 0.5 ms",
        ),
        (
            "thesis 2 leg torque mean |T| / peak",
            f"{torque.mean_abs_torque:.4f} / {torque.peak_torque:.4f}",
            "N·m",
            f"vs power {e(torque_check)}",
        ),
        (
            "torque time (720 samples, Newton–Euler + power)",
            f(1e3 * t_forces, 2),
            "ms",
            "wall clock",
        ),
        (
            f"sweep time ({samples} samples, pos+vel+acc+curv)",
            f(1e3 * t_sweep, 2),
            "ms",
            "wall clock",
        ),
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


def _catalog(args: argparse.Namespace) -> int:
    rows = []
    for f in catalog.figures(rel_tol=args.tol, samples=args.samples):
        if f.input_range is None:
            rng = "full turn"
        else:
            rng = f"{math.degrees(f.input_range[0]):.1f} … {math.degrees(f.input_range[1]):.1f}"
        rows.append(
            (
                f.name,
                f.grashof,
                rng,
                f"{f.size:g}",
                f"{f.straight_length:.3f}",
                f"{f.max_deviation:.2e}",
                f"{100 * f.speed_variation:.1f}%",
            )
        )
    head = ("linkage", "class", "input (deg)", "size", "straight", "max dev", "speed var")
    widths = [max(len(r[i]) for r in [head, *rows]) for i in range(len(head))]
    print(f"straight part: longest run within {args.tol:g} × size of a line (mm)")
    for r in [head, *rows]:
        print("  ".join(c.ljust(w) for c, w in zip(r, widths)))
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
    cat = sub.add_parser(
        "catalog", help="list the built-in linkages with their straight-line figures"
    )
    cat.add_argument("--tol", type=float, default=1e-3, help="straightness tolerance / size")
    cat.add_argument("--samples", type=int, default=20001, help="samples per circuit")
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
