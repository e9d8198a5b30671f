"""Walking-leg design search benchmark, printing ratios measured in one run:

1. leg evaluations (four-bar legs, 360 samples, every figure) by the core's batched leg
   figures, legs/s on one core — against an equivalent kinematic fitness in pure numpy
   (vectorised over all legs at once) and one on pylinkage (a leg stepped by
   ``Linkage.step_fast``, its figures in numpy: leggedsnake's stride-style fitness);
2. Dask on this machine: a LocalCluster of 1 and of 2 single-threaded workers against the
   serial evaluator at equal work (overhead, speed-up), per-task scheduler cost, worker memory.

The machine's load (other processes) is printed with the figures: the 1 → 2 worker speed-up
needs a free second core.

    .venv/bin/python bench/design.py [--legs 200000] [--chunk 10000] [--quick]
"""

from __future__ import annotations

import argparse
import math
import os
import time
import warnings

import numpy as np

from linkage import design

SAMPLES = 360
TOL = 2.5e-3


def legs(m: int, seed: int = 1) -> np.ndarray:
    fam = design.family("fourbar")
    rng = np.random.default_rng(seed)
    lo, hi = np.array(fam.lower), np.array(fam.upper)
    return lo + (hi - lo) * rng.random((m, len(lo)))


def best(fn, repeat: int = 3) -> tuple[float, float]:
    """Fastest wall time and its CPU time over ``repeat`` runs."""
    out = (math.inf, math.inf)
    for _ in range(repeat):
        c0, t0 = time.process_time(), time.perf_counter()
        fn()
        t, c = time.perf_counter() - t0, time.process_time() - c0
        if t < out[0]:
            out = (t, c)
    return out


def numpy_fitness(x: np.ndarray) -> np.ndarray:
    """The same figures in pure numpy, vectorised over legs: positions by the closed form,
    velocities by central differences, stance within TOL of the extent of the lowest level."""
    ground, angle, coupler, rocker, along, left = x.T[:, :, None]
    th = np.linspace(0, 2 * np.pi, SAMPLES, endpoint=False)[None, :]
    ax, ay = design.CRANK * np.cos(th), design.CRANK * np.sin(th)
    cx, cy = ground * np.cos(angle), ground * np.sin(angle)
    dx, dy = cx - ax, cy - ay
    d = np.hypot(dx, dy)
    with np.errstate(invalid="ignore", divide="ignore"), warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)  # all-NaN rows of legs that lock up
        a = (d**2 + coupler**2 - rocker**2) / (2 * d)
        h = np.sqrt(coupler**2 - a**2)
        ux, uy = dx / d, dy / d
        bx, by = ax + a * ux - h * uy, ay + a * uy + h * ux
        ex, ey = (bx - ax) / coupler, (by - ay) / coupler
        px, py = ax + along * ex - left * ey, ay + along * ey + left * ex
        step = 2 * np.pi / SAMPLES
        vx = (np.roll(px, -1, 1) - np.roll(px, 1, 1)) / (2 * step)
        vy = (np.roll(py, -1, 1) - np.roll(py, 1, 1)) / (2 * step)
        wx, wy = bx - cx, by - cy
        sin_mu = np.abs((bx - ax) * wy - (by - ay) * wx) / (coupler * rocker)
        full = np.isfinite(px).all(axis=1)
        extent = np.maximum(np.ptp(px, axis=1), np.ptp(py, axis=1))
        low = py.min(axis=1, keepdims=True)
        st = py <= low + TOL * extent[:, None]
        n = st.sum(axis=1)
        xs = np.where(st, px, np.nan)
        stride = np.nanmax(xs, axis=1) - np.nanmin(xs, axis=1)
        vs = np.where(st, vx, np.nan)
        mean = np.nanmean(vs, axis=1)
        var = (np.nanmax(vs, axis=1) - np.nanmin(vs, axis=1)) / np.abs(mean)
        torque = np.nanmax(np.where(st, np.hypot(vx, vy), np.nan), axis=1)
        ys = np.where(st, py, np.nan)
        straight = np.nanmax(ys, axis=1) - np.nanmin(ys, axis=1)
        lift = py.max(axis=1) - low[:, 0]
    return np.column_stack(
        [
            full,
            np.degrees(np.arcsin(sin_mu.min(axis=1))),
            n / SAMPLES,
            stride,
            lift,
            straight,
            var,
            torque,
        ]
    )


def pylinkage_fitness(x: np.ndarray) -> np.ndarray | None:
    """One leg at a time on pylinkage (``step_fast``), figures in numpy."""
    try:
        import pylinkage as pl
    except ImportError:
        return None
    out = []
    th = np.linspace(0, 2 * np.pi, SAMPLES, endpoint=False)
    dt = 2 * np.pi / SAMPLES
    for ground, angle, coupler, rocker, along, left in x:
        try:
            o = pl.Ground(0.0, 0.0)
            c = pl.Ground(ground * math.cos(angle), ground * math.sin(angle))
            a = pl.Crank(o, design.CRANK, angular_velocity=dt, initial_angle=-dt)
            b = pl.RRRDyad(a, c, coupler, rocker, x=ground / 2, y=coupler)
            p = pl.FixedDyad(a, b, math.hypot(along, left), math.atan2(left, along))
            locus = pl.Linkage([o, c, a, b, p]).step_fast(iterations=SAMPLES, dt=1)
            pts = np.asarray(locus)[:, -1, :2]
        except Exception:
            out.append(np.full(8, np.nan))
            continue
        py = pts[:, 1]
        if not np.isfinite(pts).all():
            out.append(np.full(8, np.nan))
            continue
        v = (np.roll(pts, -1, 0) - np.roll(pts, 1, 0)) / (2 * dt)
        ext = np.ptp(pts, axis=0).max()
        st = py <= py.min() + TOL * ext
        vs = v[st, 0]
        out.append(
            np.array(
                [
                    1.0,
                    np.nan,
                    st.mean(),
                    np.ptp(pts[st, 0]),
                    np.ptp(py),
                    np.ptp(py[st]),
                    np.ptp(vs) / abs(vs.mean()),
                    np.hypot(*v[st].T).max(),
                ]
            )
        )
    del th
    return np.array(out)


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--legs", type=int, default=200_000)
    ap.add_argument("--chunk", type=int, default=10_000)
    ap.add_argument("--quick", action="store_true", help="small sizes (a smoke run)")
    args = ap.parse_args()
    if args.quick:
        args.legs, args.chunk = 20_000, 2_000
    load = os.getloadavg()
    print(
        f"machine: {os.cpu_count()} CPUs, load average {load[0]:.2f} / {load[1]:.2f} / "
        f"{load[2]:.2f} (1 / 5 / 15 min) before the run"
    )
    fam = design.family("fourbar")
    s = design.Settings(samples=SAMPLES, stance_tol=TOL)
    x = legs(args.legs)

    # 1. legs per second on one core.
    m1 = min(args.legs, 50_000)
    t, c = best(lambda: fam.evaluate(x[:m1], s, threads=1))
    core_rate, core_cpu = m1 / t, m1 / c
    print(
        f"core leg figures ({SAMPLES} samples, all figures), 1 thread: {core_rate:,.0f} legs/s "
        f"wall, {core_cpu:,.0f} legs per CPU-second"
    )
    m2 = min(args.legs, 5_000)
    tn, cn = best(lambda: numpy_fitness(x[:m2]))
    np_rate, np_cpu = m2 / tn, m2 / cn
    print(
        f"pure numpy fitness (vectorised over legs): {np_rate:,.0f} legs/s wall, "
        f"{np_cpu:,.0f} per CPU-second -> core is {core_rate / np_rate:.0f}x (wall), "
        f"{core_cpu / np_cpu:.0f}x (CPU)"
    )
    m3 = 300
    tp, cp = best(lambda: pylinkage_fitness(x[:m3]), repeat=1)
    if pylinkage_fitness(x[:2]) is None:
        print("pylinkage fitness: pylinkage not installed (pip install 'pylinkage>=1.3')")
    else:
        pl_rate, pl_cpu = m3 / tp, m3 / cp
        print(
            f"pylinkage fitness (step_fast per leg, numpy figures): {pl_rate:,.0f} legs/s "
            f"wall, {pl_cpu:,.0f} per CPU-second -> core is {core_rate / pl_rate:.0f}x "
            f"(wall), {core_cpu / pl_cpu:.0f}x (CPU)"
        )

    # 2. Dask at equal work.
    import distributed

    ts, cs = best(lambda: fam.evaluate(x, s, threads=1), repeat=2)
    print(f"serial evaluator: {args.legs:,} legs in {ts:.2f} s ({args.legs / ts:,.0f} legs/s)")
    study = design.Study(family="fourbar", settings=s, chunk=args.chunk)
    times: dict[int, float] = {}
    cpu: dict[int, float] = {}
    for workers in (1, 2):
        with (
            distributed.LocalCluster(
                n_workers=workers, threads_per_worker=1, processes=True, dashboard_address=None
            ) as cluster,
            distributed.Client(cluster) as client,
        ):
            ev = design.Evaluator(study)
            ev.client = client
            ev(x[: args.chunk])  # warm the workers (imports)

            def worker_cpu(client=client) -> float:
                got = client.run(lambda: sum(__import__("psutil").Process().cpu_times()[:2]))
                return float(sum(got.values()))

            c0 = worker_cpu()
            times[workers], _ = best(lambda ev=ev: ev(x), repeat=2)
            cpu[workers] = (worker_cpu() - c0) / 2  # two runs
            rss = client.run(lambda: __import__("psutil").Process().memory_info().rss)
            if workers == 1:
                # Scheduler cost per task: many tiny tasks (one leg each).
                small = design.Study(family="fourbar", settings=s, chunk=1)
                ev_small = design.Evaluator(small)
                ev_small.client = client
                k = 500
                tt, _ = best(lambda ev_small=ev_small: ev_small(x[:k]), repeat=1)
                per_task = tt / k
        mb = max(rss.values()) / 2**20
        print(
            f"dask LocalCluster, {workers} worker(s), chunks of {args.chunk:,}: "
            f"{times[workers]:.2f} s; worker RSS up to {mb:.0f} MB"
        )
    print(
        f"dask overhead, 1 worker vs serial at equal work: "
        f"{100 * (times[1] - ts) / ts:+.1f} % (target <= 15 %)"
    )
    print(
        f"dask CPU at equal work (workers' CPU time, less sensitive to other processes): "
        f"1 worker {cpu[1]:.2f} s, 2 workers {cpu[2]:.2f} s, serial {cs:.2f} s -> overhead "
        f"{100 * (cpu[1] - cs) / cs:+.1f} % / {100 * (cpu[2] - cs) / cs:+.1f} %"
    )
    print(f"dask 1 -> 2 workers: {times[1] / times[2]:.2f}x (target >= 1.7x on a free core)")
    print(f"scheduler cost per task (1-leg tasks): {1e3 * per_task:.2f} ms")
    load = os.getloadavg()
    print(f"load average after the run: {load[0]:.2f} / {load[1]:.2f} / {load[2]:.2f}")


if __name__ == "__main__":
    main()
