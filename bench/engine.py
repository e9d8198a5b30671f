"""The sweep engine against numpy closed forms: the ratios issue 11 targets, in one process.

Each row times the public API (``FourBar.sweep``, ``Mechanism.sweep``,
``linkage.batch.sweep_fourbars``) and a plain numpy closed form computing the same quantities,
interleaved, and prints the ratio ``numpy time / ours`` (higher is better) with the largest
difference between the two (relative to the linkage size; ∞-norm; for centres relative to
their distance from the coupler point, as far centres are known to a relative accuracy). Times are CPU-time medians
(``time.process_time``: robust to other processes on a shared machine).

- coupler point only, 10⁶ arbitrary angles (Hoecken four-bar) — target ≥ 8×;
- point + velocity + acceleration, 10⁶ angles — target ≥ 8×;
- instant centres + curvature, 10⁶ angles — target ≥ 5×: the two secondary centres (I13, I24;
  ``pairs=``) and the coupler point's curvature and its centre, as numpy computes them; then,
  for reference, every pair of links (all six centres, four of them the pins);
- Jansen's leg, all joints, 2·10⁵ angles (numpy: a chain of its five dyads) — target ≥ 4×;
  (the coupler point and Jansen rows are repeated on evenly spaced angles in order, the
  tracker's best case, for reference; the others use arbitrary angles in arbitrary order);
- one sample per call — target ≥ 3×;
- a batch of 10⁴ four-bars × 360 angles (bench/batch.py's case) — target ≥ 10×.

    .venv/bin/python bench/engine.py [--n 1000000] [--repeat 7] [--quick]

The script imports ``linkage`` from whichever environment runs it, so the same file measures
two builds (e.g. ``/work/main/.venv/bin/python bench/engine.py``).
"""

from __future__ import annotations

import os

# One thread for numpy's BLAS: process CPU time counts every thread, and idle BLAS threads
# spinning after a call would be charged to whichever side ran next.
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import argparse
import statistics
import sys
import time
from collections.abc import Callable
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

import linkage
from linkage import catalog

sys.path.insert(0, str(Path(__file__).resolve().parent))
import batch as batch_bench

F = NDArray[np.float64]

# Hoecken's straight-line four-bar (mm): O (0, 0), C (20, 0), crank 10, coupler 25,
# rocker 25, coupler point 50 along A → B.
G, R, A_LEN, B_LEN, ALONG, LEFT = 20.0, 10.0, 25.0, 25.0, 50.0, 0.0
SIZE = 50.0


def cpu_medians(fs: list[Callable[[], object]], repeat: int) -> list[float]:
    """Median CPU time of each of ``fs``, run interleaved."""
    times: list[list[float]] = [[] for _ in fs]
    for _ in range(repeat):
        for f, ts in zip(fs, times, strict=True):
            t0 = time.process_time()
            f()
            ts.append(time.process_time() - t0)
    return [statistics.median(ts) for ts in times]


def perp(x: F, y: F) -> tuple[F, F]:
    return -y, x


def dyad(p1x: F, p1y: F, p2x: F, p2y: F, r1: float, r2: float, sign: float) -> tuple[F, F]:
    """The joint at ``r1`` from p1 and ``r2`` from p2, on the side ``sign`` (+1 left of p1 → p2)."""
    dx, dy = p2x - p1x, p2y - p1y
    d2 = dx * dx + dy * dy
    d = np.sqrt(d2)
    x = (d2 + r1 * r1 - r2 * r2) / (2.0 * d)
    with np.errstate(invalid="ignore"):
        h = sign * np.sqrt(r1 * r1 - x * x)
    ux, uy = dx / d, dy / d
    return p1x + x * ux - h * uy, p1y + x * uy + h * ux


def fourbar_pos(theta: F) -> tuple[F, F, F, F, F, F]:
    """A, B and P of the Hoecken four-bar (open assembly: B left of A → C)."""
    c, s = np.cos(theta), np.sin(theta)
    ax, ay = R * c, R * s
    bx, by = dyad(ax, ay, np.full_like(ax, G), np.zeros_like(ay), A_LEN, B_LEN, 1.0)
    ux, uy = (bx - ax) / A_LEN, (by - ay) / A_LEN
    px = ax + ALONG * ux - LEFT * uy
    py = ay + ALONG * uy + LEFT * ux
    return ax, ay, bx, by, px, py


def solve2(a11: F, a12: F, a21: F, a22: F, b1: F, b2: F) -> tuple[F, F]:
    det = a11 * a22 - a12 * a21
    return (b1 * a22 - a12 * b2) / det, (a11 * b2 - a21 * b1) / det


def fourbar_rates(
    theta: F, w: float, al: float
) -> tuple[tuple[F, ...], tuple[F, ...], tuple[F, ...]]:
    """Positions, velocities and accelerations of A, B, P by the loop-closure equations:
    (B − A)·(v_B − v_A) = 0, (B − C)·v_B = 0 and their derivatives."""
    ax, ay, bx, by, px, py = fourbar_pos(theta)
    vax, vay = -w * ay, w * ax
    aax, aay = -al * ay - w * w * ax, al * ax - w * w * ay
    ex, ey = bx - ax, by - ay
    fx, fy = bx - G, by
    vbx, vby = solve2(ex, ey, fx, fy, ex * vax + ey * vay, np.zeros_like(ex))
    rvx, rvy = vbx - vax, vby - vay
    abx, aby = solve2(
        ex, ey, fx, fy,
        ex * aax + ey * aay - (rvx * rvx + rvy * rvy),
        -(vbx * vbx + vby * vby),
    )  # fmt: skip
    l2 = A_LEN * A_LEN
    w3 = (ex * rvy - ey * rvx) / l2
    a3 = (ex * (aby - aay) - ey * (abx - aax)) / l2
    qx, qy = px - ax, py - ay
    vpx, vpy = vax - w3 * qy, vay + w3 * qx
    apx = aax - a3 * qy - w3 * w3 * qx
    apy = aay + a3 * qx - w3 * w3 * qy
    return (ax, ay, bx, by, px, py), (vax, vay, vbx, vby, vpx, vpy), (aax, aay, abx, aby, apx, apy)


def meet(ax: F, ay: F, bx: F, by: F, cx: F, cy: F, dx: F, dy: F) -> tuple[F, F]:
    """Intersection of the lines a b and c d."""
    ux, uy, vx, vy = bx - ax, by - ay, dx - cx, dy - cy
    t = ((cx - ax) * vy - (cy - ay) * vx) / (ux * vy - uy * vx)
    return ax + t * ux, ay + t * uy


def fourbar_centres_curvature(theta: F) -> tuple[F, F, F, F, F]:
    """The two secondary instant centres (Kennedy: I13 = OA ∩ CB, I24 = AB ∩ OC; the four
    primary ones are the pins) and the coupler point's path curvature and centre of
    curvature, from rates per unit crank angle."""
    (ax, ay, bx, by, px, py), v, a = fourbar_rates(theta, 1.0, 0.0)
    z = np.zeros_like(ax)
    i13 = meet(z, z, ax, ay, z + G, z, bx, by)
    i24 = meet(ax, ay, bx, by, z, z, z + G, z)
    vx, vy, accx, accy = v[4], v[5], a[4], a[5]
    speed = np.hypot(vx, vy)
    kappa = (vx * accy - vy * accx) / speed**3
    cx = px - vy / speed / kappa
    cy = py + vx / speed / kappa
    return np.stack([*i13, *i24]), kappa, cx, cy, speed


JANSEN = [  # (p1, p2, r1, r2, sign) on joints O, Q, A, B, C, D, E, F
    (2, 1, 50.0, 41.5, -1.0),
    (2, 1, 61.9, 39.3, 1.0),
    (3, 1, 55.8, 40.1, -1.0),
    (5, 4, 39.4, 36.7, -1.0),
    (6, 4, 65.7, 49.0, -1.0),
]


def jansen_numpy(theta: F) -> F:
    """All eight joints (n, 8, 2) of Jansen's leg as a chain of its five dyads."""
    n = theta.shape[0]
    out = np.empty((n, 8, 2))
    out[:, 0] = (0.0, 0.0)
    out[:, 1] = (-38.0, -7.8)
    out[:, 2, 0] = 15.0 * np.cos(theta)
    out[:, 2, 1] = 15.0 * np.sin(theta)
    for k, (i, j, r1, r2, s) in enumerate(JANSEN):
        x, y = dyad(out[:, i, 0], out[:, i, 1], out[:, j, 0], out[:, j, 1], r1, r2, s)
        out[:, 3 + k, 0] = x
        out[:, 3 + k, 1] = y
    return out


def row(
    name: str,
    t_ours: float,
    t_np: float,
    target: float | None,
    diff: float,
    per: int,
    what: str = "max diff/size",
) -> None:
    """Print one case: times, ratio, the target (None: a row for reference) and the difference."""
    ratio = t_np / t_ours
    goal = (
        "(for reference)        "
        if target is None
        else f"(target ≥ {target:g}×, {'met' if ratio >= target else 'MISSED'})"
    )
    print(
        f"  {name:<34} ours {t_ours / per * 1e9:9.1f} ns  numpy {t_np / per * 1e9:9.1f} ns"
        f"  ratio {ratio:6.2f}×  {goal}  {what} {diff:.1e}"
    )


def rel_far(a: F, b: F, origin: F) -> float:
    """Largest ``|a − b|`` relative to the distance of ``b`` from ``origin`` (at least the size):
    centres far from the linkage are known to a relative accuracy, not an absolute one."""
    far = np.maximum(np.linalg.norm(b - origin, axis=-1), SIZE)
    return float(np.nanmax(np.linalg.norm(a - b, axis=-1) / far))


def rel(a: F, b: F, size: float = SIZE) -> float:
    return float(np.nanmax(np.abs(a - b))) / size


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, default=1_000_000)
    ap.add_argument("--repeat", type=int, default=7)
    ap.add_argument("--quick", action="store_true", help="10× fewer samples, 3 repeats")
    args = ap.parse_args()
    n, repeat = args.n, args.repeat
    if args.quick:
        n, repeat = n // 10, 3
    rng = np.random.default_rng(7)
    theta = rng.uniform(-np.pi, 3 * np.pi, n)  # arbitrary angles, unsorted
    fb = linkage.FourBar(ground=G, crank=R, coupler=A_LEN, rocker=B_LEN, point=(ALONG, LEFT))
    print(f"linkage {linkage.__version__} from {Path(linkage.__file__).parent}")
    print(f"CPU-time medians of {repeat} interleaved runs; ratio = numpy / ours")

    # 1. Coupler point only.
    point = ("point",)
    s = fb.sweep(theta, outputs=point)
    _, _, _, _, px, py = fourbar_pos(theta)
    diff = rel(s.point, np.stack([px, py], -1))
    t = cpu_medians(
        [lambda: fb.sweep(theta, outputs=point).point, lambda: fourbar_pos(theta)], repeat
    )
    row(f"coupler point, {n} angles", t[0], t[1], 8, diff, n)

    # 1b. The same on evenly spaced angles in order (the tracker's best case, for reference).
    lin = np.linspace(0.0, 2 * np.pi, n)
    t = cpu_medians([lambda: fb.sweep(lin, outputs=point).point, lambda: fourbar_pos(lin)], repeat)
    row("  (same, linspace angles in order)", t[0], t[1], 8, 0.0, n)

    # 2. Point, velocity, acceleration.
    w, al = 2.0, 0.5
    outs = ("point", "velocity", "acceleration")
    s = fb.sweep(theta, omega=w, alpha=al, outputs=outs)
    _, v, a = fourbar_rates(theta, w, al)
    diff = max(
        rel(s.velocity, np.stack([v[4], v[5]], -1), SIZE * w),
        rel(s.acceleration, np.stack([a[4], a[5]], -1), SIZE * (w * w + al)),
    )
    t = cpu_medians(
        [
            lambda: fb.sweep(theta, omega=w, alpha=al, outputs=outs),
            lambda: fourbar_rates(theta, w, al),
        ],
        repeat,
    )
    row("point + velocity + acceleration", t[0], t[1], 8, diff, n)

    # 3. Instant centres and curvature: the two secondary centres, as numpy computes them.
    outs = ("point", "instant_centres", "curvature")
    two = [("ground", "coupler"), ("crank", "rocker")]  # I13 and I24
    secondary, kappa, cx, cy, _ = fourbar_centres_curvature(theta)
    ok = np.abs(kappa) > 1e-9  # inflections: the centre is at infinity
    cases = ((two, "instant centres + curvature", 5.0), (None, "  (same, every pair: 6)", None))
    for pairs, label, target in cases:
        s = fb.sweep(theta, outputs=outs, pairs=pairs)
        p = s.point
        # Relative to the distance from the point (centres far away carry relative errors).
        diff = max(
            rel_far(s.instant_centre(*two[0]), np.stack([secondary[0], secondary[1]], -1), p),
            rel_far(s.instant_centre(*two[1]), np.stack([secondary[2], secondary[3]], -1), p),
            float(np.nanmax(np.abs(s.curvature - kappa) / np.maximum(np.abs(kappa), 1 / SIZE))),
            rel_far(s.curvature_centre[ok], np.stack([cx, cy], -1)[ok], p[ok]),
        )
        t = cpu_medians(
            [
                lambda p=pairs: fb.sweep(theta, outputs=outs, pairs=p),
                lambda: fourbar_centres_curvature(theta),
            ],
            repeat,
        )
        row(label, t[0], t[1], target, diff, n, "max rel diff")

    # 4. Jansen, all joints.
    nj = max(n // 5, 1)
    th_j = theta[:nj]
    jansen = catalog.jansen()
    s = jansen.sweep(th_j)
    diff = rel(s.joints, jansen_numpy(th_j), 100.0)
    t = cpu_medians([lambda: jansen.sweep(th_j).joints, lambda: jansen_numpy(th_j)], repeat)
    row(f"Jansen all joints, {nj} angles", t[0], t[1], 4, diff, nj)

    lin_j = np.linspace(0.0, 2 * np.pi, nj)
    t = cpu_medians([lambda: jansen.sweep(lin_j).joints, lambda: jansen_numpy(lin_j)], repeat)
    row("  (same, linspace angles in order)", t[0], t[1], 4, 0.0, nj)

    # 5. One sample per call.
    one = np.array([0.7])
    calls = 2000

    def ours_one() -> None:
        for _ in range(calls):
            _ = fb.sweep(one).point

    def numpy_one() -> None:
        for _ in range(calls):
            fourbar_pos(one)

    diff = rel(fb.sweep(one).point, np.stack(fourbar_pos(one)[4:], -1))
    t = cpu_medians([ours_one, numpy_one], repeat)
    row("one sample per call", t[0], t[1], 3, diff, calls)

    # 6. The batch of four-bars (bench/batch.py's case).
    m, nb = (1000, 360) if args.quick else (10_000, 360)
    p = batch_bench.linkages(m)
    th_b = np.random.default_rng(2).uniform(0.0, 2 * np.pi, nb)
    point = np.stack([p["along"], p["left"]], axis=-1)
    assembly = np.where(p["crossed"], "crossed", "open")
    sign = np.where(p["crossed"], -1.0, 1.0)
    args_b = (p["ground"], p["crank"], p["coupler"], p["rocker"], point, th_b, assembly)
    args_n = (p["ground"], p["crank"], p["coupler"], p["rocker"], p["along"], p["left"], sign, th_b)
    pts, _ = batch_bench.sweep_fourbars(*args_b)
    size = float(np.max([p["ground"], p["coupler"], p["rocker"]]))
    diff = rel(pts, batch_bench.numpy_batch(*args_n), size)
    t = cpu_medians(
        [lambda: batch_bench.sweep_fourbars(*args_b), lambda: batch_bench.numpy_batch(*args_n)],
        repeat,
    )
    row(f"batch {m} four-bars × {nb} angles", t[0], t[1], 10, diff, m * nb)


if __name__ == "__main__":
    main()
