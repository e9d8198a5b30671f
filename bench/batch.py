"""Batch of four-bars: ``linkage.batch.sweep_fourbars`` against a numpy broadcast closed form.

10⁴ random crank-rockers and double cranks × 360 crank angles. The numpy version is the same
closed form (Kahan's area, declared assembly) vectorised over ``(M, N)`` with ``sin``/``cos``
of the ``N`` angles computed once. Median of repeated, interleaved runs in one process; prints
the ratio (fresh outputs, and outputs reused through ``out=``) and the largest difference
between the two, relative to the linkage size.

    .venv/bin/python bench/batch.py [--m 10000] [--n 360] [--repeat 9] [--threads 1]
"""

from __future__ import annotations

import argparse
import statistics
import time
from collections.abc import Callable

import numpy as np
from numpy.typing import NDArray

from linkage.batch import sweep_fourbars


def numpy_batch(
    g: NDArray[np.float64],
    r: NDArray[np.float64],
    r1: NDArray[np.float64],
    r2: NDArray[np.float64],
    along: NDArray[np.float64],
    left: NDArray[np.float64],
    sign: NDArray[np.float64],
    theta: NDArray[np.float64],
) -> NDArray[np.float64]:
    """Coupler points (M, N, 2), O at the origin and C at (g, 0), on the declared assembly."""
    col = (g[:, None], r[:, None], r1[:, None], r2[:, None])
    g, r, r1, r2 = col
    cs, sn = np.cos(theta)[None, :], np.sin(theta)[None, :]
    ax, ay = r * cs, r * sn
    dx, dy = g - ax, -ay
    d = np.sqrt(dx * dx + dy * dy)
    rmax, rmin = np.maximum(r1, r2), np.minimum(r1, r2)
    hi, lo = np.maximum(d, rmax), np.minimum(d, rmin)
    mid = np.clip(d, rmin, rmax)
    with np.errstate(invalid="ignore", divide="ignore"):
        area = 0.25 * np.sqrt(
            (hi + (mid + lo)) * (lo - (hi - mid)) * (lo + (hi - mid)) * (hi + (mid - lo))
        )
        ux, uy = dx / d, dy / d
        x = 0.5 * (d + (r1 - r2) * (r1 + r2) / d)
        h = 2.0 * area / d * sign[:, None]
    ex, ey = (x * ux - h * uy) / r1, (x * uy + h * ux) / r1
    out = np.empty((*d.shape, 2))
    out[..., 0] = ax + along[:, None] * ex - left[:, None] * ey
    out[..., 1] = ay + along[:, None] * ey + left[:, None] * ex
    return out


def linkages(m: int, seed: int = 1) -> dict[str, NDArray[np.float64]]:
    """Random Grashof linkages whose crank turns fully (crank-rockers and double cranks)."""
    rng = np.random.default_rng(seed)
    g = rng.uniform(1.0, 3.0, m)
    r = rng.uniform(0.2, 0.8, m) * np.where(rng.random(m) < 0.8, 1.0, 4.0)
    r = np.where(r > g, g * 0.5, r)
    r1 = rng.uniform(1.5, 3.5, m)
    # rocker so that s + l < p + q with the crank shortest: |g − r1| + r < r2 < g + r1 − r
    lo, hi = np.abs(g - r1) + r, g + r1 - r
    r2 = lo + (hi - lo) * rng.uniform(0.1, 0.9, m)
    return {
        "ground": g,
        "crank": r,
        "coupler": r1,
        "rocker": r2,
        "along": rng.uniform(-1.0, 2.0, m) * r1,
        "left": rng.uniform(-1.0, 1.0, m) * r1,
        "crossed": rng.random(m) < 0.5,
    }


def medians(fs: list[Callable[[], object]], repeat: int) -> list[float]:
    """Median wall time of each of ``fs``, run interleaved (so a change in the machine's load
    falls on all of them alike)."""
    times: list[list[float]] = [[] for _ in fs]
    for _ in range(repeat):
        for f, ts in zip(fs, times, strict=True):
            t0 = time.perf_counter()
            f()
            ts.append(time.perf_counter() - t0)
    return [statistics.median(ts) for ts in times]


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--m", type=int, default=10_000)
    ap.add_argument("--n", type=int, default=360)
    ap.add_argument("--repeat", type=int, default=9)
    ap.add_argument("--threads", type=int, default=1)
    args = ap.parse_args()
    p = linkages(args.m)
    theta = np.random.default_rng(2).uniform(0.0, 2 * np.pi, args.n)  # arbitrary, not uniform
    point = np.stack([p["along"], p["left"]], axis=-1)
    assembly = np.where(p["crossed"], "crossed", "open")
    sign = np.where(p["crossed"], -1.0, 1.0)

    def ours() -> tuple[NDArray[np.float64], NDArray[np.bool_]]:
        return sweep_fourbars(
            p["ground"], p["crank"], p["coupler"], p["rocker"], point, theta, assembly,
            threads=args.threads,
        )  # fmt: skip

    buf = (np.empty((args.m, args.n, 2)), np.empty((args.m, args.n), dtype=bool))

    def ours_out() -> tuple[NDArray[np.float64], NDArray[np.bool_]]:
        return sweep_fourbars(
            p["ground"], p["crank"], p["coupler"], p["rocker"], point, theta, assembly,
            threads=args.threads, out=buf,
        )  # fmt: skip

    def theirs() -> NDArray[np.float64]:
        return numpy_batch(
            p["ground"], p["crank"], p["coupler"], p["rocker"], p["along"], p["left"], sign, theta
        )

    a, valid = ours()
    b = theirs()
    size = np.maximum.reduce([p["ground"], p["coupler"], p["rocker"], np.abs(point).max(-1)])
    diff = float(np.nanmax(np.abs(a - b).max(-1) / size[:, None]))
    t_ours, t_out, t_np = medians([ours, ours_out, theirs], args.repeat)
    samples = args.m * args.n
    print(f"batch of {args.m} four-bars × {args.n} angles, threads={args.threads}")
    print(
        f"  linkage.batch.sweep_fourbars: {t_ours * 1e3:8.2f} ms  {t_ours / samples * 1e9:6.2f} ns/sample"
    )
    print(
        f"  ... into reused out arrays:   {t_out * 1e3:8.2f} ms  {t_out / samples * 1e9:6.2f} ns/sample"
    )
    print(
        f"  numpy broadcast closed form:  {t_np * 1e3:8.2f} ms  {t_np / samples * 1e9:6.2f} ns/sample"
    )
    print(f"  ratio numpy / ours: {t_np / t_ours:.1f}×  (target ≥ 10×)")
    print(f"  ratio numpy / ours with out=: {t_np / t_out:.1f}×")
    print(
        f"  valid samples: {int(valid.sum())} of {samples}; agree with numpy's NaNs: "
        f"{bool((valid == np.isfinite(b[..., 0])).all())}"
    )
    print(f"  max |ours − numpy| / linkage size: {diff:.2e}")


if __name__ == "__main__":
    main()
