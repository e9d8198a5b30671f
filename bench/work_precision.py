"""Work-precision benchmark of the four-bar sweep: time per sample against the error from a
50-digit mpmath reference at the same angles, for every sweep mode and the peers a user would
pick instead, in one process (ratios, not just absolute times).

    python bench/work_precision.py [--quick] [--out bench/results]

Timing and error are separate passes: each timing is the median of 7 runs after a warm-up; each
error is the maximum and median over (up to) 300 sample indices spread over the sweep, against
mpmath at the exact intended angles θ₀ + kΔ. Targets (issue "Evidence") are checked at the end
and reported with their figures, met or not.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import subprocess
import sys
import time
from pathlib import Path

import mpmath as mp
import numpy as np

import linkage

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "tests"))
from reference import fourbar_reference  # noqa: E402

mp.mp.dps = 50
G, R, C, K, ALONG = 20.0, 10.0, 25.0, 25.0, 50.0  # the Hoecken linkage, mm
SIZE = 25.0  # its longest link


def median_time(fn, runs: int = 7) -> float:
    fn()  # warm-up
    times = []
    for _ in range(runs):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return float(np.median(times))


def reference_points(theta0: float, dtheta: float, idx: np.ndarray) -> np.ndarray:
    out = np.empty((len(idx), 2))
    for i, k in enumerate(idx):
        angle = mp.mpf(theta0) + int(k) * mp.mpf(dtheta)
        _, _, p = fourbar_reference(G, R, C, K, ALONG, 0.0, angle)
        out[i] = float(p[0]), float(p[1])
    return out


def errors(
    points: np.ndarray, theta0: float, dtheta: float, n: int, cache: dict
) -> tuple[float, float]:
    idx = np.unique(np.linspace(0, n - 1, min(n, 300)).astype(int))
    key = (n, theta0, dtheta)
    if key not in cache:
        cache[key] = (idx, reference_points(theta0, dtheta, idx))
    idx, ref = cache[key]
    e = np.linalg.norm(points[idx] - ref, axis=1)
    return float(e.max()), float(np.median(e))


def numpy_sweep(theta: np.ndarray) -> np.ndarray:
    """The same closed form (Kahan's area) in plain numpy."""
    ax, ay = R * np.cos(theta), R * np.sin(theta)
    dx, dy = G - ax, -ay
    d = np.sqrt(dx * dx + dy * dy)
    hi = np.maximum(d, max(C, K))
    lo = np.minimum(d, min(C, K))
    mid = np.clip(d, min(C, K), max(C, K))
    prod = (hi + (mid + lo)) * (lo - (hi - mid)) * (lo + (hi - mid)) * (hi + (mid - lo))
    h = 0.5 * np.sqrt(prod) / d
    ux, uy = dx / d, dy / d
    x = 0.5 * (d + (C - K) * (C + K) / d)
    ex, ey = (x * ux - h * uy) / C, (x * uy + h * ux) / C
    return np.c_[ax + ALONG * ex, ay + ALONG * ey]


def rust_peer(native: bool) -> dict[str, tuple[float, float]]:
    """Run the four-bar crate comparison (bench/fourbar-peer); name → (ns/sample, error)."""
    env = dict(os.environ)
    target = ROOT / "target" / ("peer-native" if native else "peer")
    if native:
        env["RUSTFLAGS"] = (env.get("RUSTFLAGS", "") + " -C target-cpu=native").strip()
    cmd = ["cargo", "run", "--quiet", "--release", "--example", "peer", "--target-dir", str(target)]
    try:
        out = subprocess.run(
            cmd,
            cwd=ROOT / "bench" / "fourbar-peer",
            env=env,
            capture_output=True,
            text=True,
            check=True,
        ).stdout
    except (OSError, subprocess.CalledProcessError) as exc:
        print(f"  (four-bar crate comparison unavailable: {exc})")
        return {}
    rows = {}
    for line in out.splitlines():
        name, ns, err = line.split()
        rows[name + ("-native" if native else "")] = (float(ns), float(err))
    return rows


def plot(rows: list[dict], out: Path) -> None:
    """The log-log work-precision plot, one distinct colour and line style per method (the
    report's palette: 14 colours, then dashed)."""
    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        return
    from linkage.report import line_style

    fig, ax = plt.subplots(figsize=(7, 5))
    for k, method in enumerate(dict.fromkeys(r["method"] for r in rows)):
        pts = [
            (r["ns_per_sample"], max(r["max_error"], 1e-17))
            for r in rows
            if r["method"] == method and np.isfinite(r["max_error"])
        ]
        if pts:
            x, y = zip(*pts)
            colour, dash = line_style(k)
            ax.loglog(x, y, marker="o", linestyle=dash, color=colour, label=method)
    ax.set_xlabel("time per sample (ns)")
    ax.set_ylabel("max error / longest link")
    ax.set_title("four-bar sweep: work-precision (points: 1e3 … 1e7 samples)")
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(out / "work_precision.png", dpi=110)
    plt.close(fig)


def main() -> int:
    ap = argparse.ArgumentParser()
    ap.add_argument("--quick", action="store_true", help="sample counts up to 1e5 only")
    ap.add_argument("--out", default=str(ROOT / "bench" / "results"))
    ap.add_argument(
        "--replot", action="store_true", help="only redraw the plot from OUT/latest.json"
    )
    args = ap.parse_args()
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    if args.replot:
        plot(json.loads((out / "latest.json").read_text())["rows"], out)
        return 0
    counts = [10**3, 10**4, 10**5] + ([] if args.quick else [10**6, 10**7])
    fb = linkage.catalog.hoecken()
    theta0 = 0.1
    cache: dict = {}
    rows: list[dict] = []

    def record(method: str, n: int, seconds: float, pts: np.ndarray | None) -> None:
        emax, emed = (
            errors(pts, theta0, 2 * math.pi / n, n, cache)
            if pts is not None
            else (math.nan, math.nan)
        )
        rows.append(
            {
                "method": method,
                "n": n,
                "ns_per_sample": 1e9 * seconds / n,
                "max_error": emax / SIZE,
                "median_error": emed / SIZE,
            }
        )
        print(
            f"  {method:<28} n={n:>9,d}  {1e9 * seconds / n:9.2f} ns/sample  max err {emax / SIZE:8.1e}  median {emed / SIZE:8.1e}"
        )

    os.environ.pop("LINKAGE_PORTABLE", None)
    isa = linkage.FourBar.uniform_sweep_isa()
    print(
        "four-bar position sweep, Hoecken linkage; errors relative to the longest link (25 mm);"
        f" fast sweep runs the {isa} build"
    )
    for n in counts:
        dt = 2 * math.pi / n
        theta = theta0 + dt * np.arange(n)
        for mode in ("trig", "table", "recurrence"):
            t = median_time(lambda m=mode: fb.uniform_sweep(theta0, dt, n, m))
            record(f"fast {mode}", n, t, fb.uniform_sweep(theta0, dt, n, mode))
        buf = np.empty((n, 2))
        t = median_time(lambda: fb.uniform_sweep(theta0, dt, n, "table", out=buf))
        record("fast table into out=", n, t, fb.uniform_sweep(theta0, dt, n, "table", out=buf))
        os.environ["LINKAGE_PORTABLE"] = "1"
        t = median_time(lambda: fb.uniform_sweep(theta0, dt, n, "table"))
        record("fast table, portable code", n, t, fb.uniform_sweep(theta0, dt, n, "table"))
        del os.environ["LINKAGE_PORTABLE"]
        t = median_time(lambda: fb.uniform_sweep(theta0, dt, n, "table", threads=2))
        record("fast table, 2 threads", n, t, fb.uniform_sweep(theta0, dt, n, "table", threads=2))
        t = median_time(lambda: fb.sweep(theta))
        record("tracked sweep: position", n, t, fb.sweep(theta).point)
        rates = lambda: fb.sweep(theta, omega=1.0, outputs=("point", "velocity", "acceleration"))
        record("tracked: pos+vel+acc", n, median_time(rates), rates().point)
        centres = lambda: fb.sweep(theta, outputs=("point", "instant_centres", "curvature"))
        record("tracked: +centres+curvature", n, median_time(centres), centres().point)
        t = median_time(lambda: numpy_sweep(theta))
        record("numpy closed form", n, t, numpy_sweep(theta))
        if n <= 10**5:
            try:
                import pylinkage as pl

                o, c = pl.Ground(0, 0), pl.Ground(20, 0)
                a = pl.Crank(o, 10, angular_velocity=dt, initial_angle=theta0 - dt)
                b = pl.RRRDyad(a, c, 25, 25, x=15, y=24)
                p = pl.FixedDyad(b, a, 25, math.pi)
                lk = pl.Linkage([o, c, a, b, p])
                t = median_time(lambda: lk.step_fast(iterations=n, dt=1), runs=3)
                record("pylinkage step_fast", n, t, lk.step_fast(iterations=n, dt=1)[:, -1])
            except ImportError:
                if n == counts[0]:
                    print("  (pylinkage not installed: pip install pylinkage)")

    # Velocity and acceleration error of the tracked sweep against mpmath derivatives.
    sample = np.linspace(0.1, 6.2, 25)
    s = fb.sweep(sample, omega=1.0, outputs=("velocity", "acceleration"))
    verr = aerr = 0.0
    for i, th in enumerate(sample):
        for axis in (0, 1):
            f = lambda t, a=axis: fourbar_reference(G, R, C, K, ALONG, 0.0, t)[2][a]
            verr = max(verr, abs(float(mp.diff(f, th, 1)) - s.velocity[i, axis]))
            aerr = max(aerr, abs(float(mp.diff(f, th, 2)) - s.acceleration[i, axis]))
    print(
        f"tracked sweep rates vs mpmath: velocity {verr / SIZE:.1e}, acceleration {aerr / SIZE:.1e} (per unit crank speed, relative to 25 mm)"
    )

    print("rust peers (bench/fourbar-peer, 1e6 samples, same process per build):")
    peers = rust_peer(native=False)
    peers.update(rust_peer(native=True))
    for name, (ns, err) in peers.items():
        print(f"  {name:<28} {ns:9.2f} ns/sample  (max diff from trig mode {err:.1e} mm)")

    # Targets.
    def at(method: str, n: int) -> dict:
        return next(r for r in rows if r["method"] == method and r["n"] == n)

    n_big = 10**6 if not args.quick else 10**5
    checks = []
    fastest = min(
        (
            r
            for r in rows
            if r["method"].startswith("fast")
            and "threads" not in r["method"]
            and "portable" not in r["method"]
            and r["n"] == n_big
        ),
        key=lambda r: r["ns_per_sample"],
    )
    native_best = min(
        (v[0] for k, v in peers.items() if k.endswith("native") and k.startswith("linkage")),
        default=math.nan,
    )
    checks.append(
        (
            f"fastest mode ≤ 2 ns/sample, error ≤ 1e-13 (wheel from Python, {isa} build)",
            f"{fastest['method']}: {fastest['ns_per_sample']:.2f} ns, {fastest['max_error']:.1e}",
            fastest["ns_per_sample"] <= 2 and fastest["max_error"] <= 1e-13,
        )
    )
    checks.append(
        (
            "fastest mode ≤ 2 ns/sample (native SIMD build, Rust)",
            f"{native_best:.2f} ns",
            native_best <= 2,
        )
    )
    # Both allocate their result here.
    fresh = min(
        (at(f"fast {m}", n_big) for m in ("trig", "table", "recurrence")),
        key=lambda r: r["ns_per_sample"],
    )
    ratio_np = at("numpy closed form", n_big)["ns_per_sample"] / fresh["ns_per_sample"]
    ratio_np2 = (
        at("numpy closed form", n_big)["ns_per_sample"]
        / at("fast table, 2 threads", n_big)["ns_per_sample"]
    )
    checks.append(
        (
            "≥ 10× numpy from Python (1 thread / 2 threads)",
            f"{ratio_np:.1f}× / {ratio_np2:.1f}×",
            ratio_np >= 10,
        )
    )
    if "four-bar-crate" in peers:
        fb_ratio = peers["four-bar-crate"][0] / peers["linkage-table"][0]
        fb_native = (
            peers.get("four-bar-crate-native", (math.nan,))[0]
            / peers.get("linkage-table-native", (math.nan,))[0]
        )
        checks.append(
            (
                "≥ 20× the four-bar crate (portable / native)",
                f"{fb_ratio:.1f}× / {fb_native:.1f}×",
                fb_ratio >= 20,
            )
        )
    speedup = (
        at("fast table", n_big)["ns_per_sample"]
        / at("fast table, 2 threads", n_big)["ns_per_sample"]
    )
    same = bool(
        np.array_equal(
            fb.uniform_sweep(0.1, 1e-5, 100_000, "table", threads=1),
            fb.uniform_sweep(0.1, 1e-5, 100_000, "table", threads=2),
        )
    )
    checks.append(
        (
            "≥ 1.8× on two threads, identical results",
            f"{speedup:.2f}×, identical: {same}",
            speedup >= 1.8 and same,
        )
    )
    print("targets:")
    for name, figure, ok in checks:
        print(f"  [{'met' if ok else 'MISSED'}] {name}: {figure}")

    # Table, JSON and the work-precision plot.
    (out / "latest.json").write_text(
        json.dumps(
            {
                "isa": isa,
                "rows": rows,
                "peers": peers,
                "targets": [(*c[:2], bool(c[2])) for c in checks],
            },
            indent=1,
        )
    )
    lines = ["| method | n | ns/sample | max error | median error |", "|---|---:|---:|---:|---:|"]
    for r in rows:
        if r["n"] == n_big:
            lines.append(
                f"| {r['method']} | {r['n']:.0e} | {r['ns_per_sample']:.2f} | {r['max_error']:.1e} | {r['median_error']:.1e} |"
            )
    (out / "latest.md").write_text("\n".join(lines) + "\n")
    plot(rows, out)
    print(f"wrote {out}/latest.md, latest.json, work_precision.png")
    return 0


if __name__ == "__main__":
    sys.exit(main())
