"""Path synthesis against the ``four-bar`` crate 7.0.5 (bench/fourbar-peer/examples/synth.rs), in
one run: atlas build time per entry, a 10⁶-entry atlas on 2 threads, a query over it, and on a
few targets each method's best error (our metric for both: the largest distance from the
target points to the linkage's coupler curve, relative to the target's RMS radius) and time.

    .venv/bin/python bench/synthesis.py [--peer-entries 2000] [--skip-million] [--gens 50 --pop 200]

The peer's curve is its own dense sample (3600 points) of its best linkage; our metric on it is
the distance to that polyline (chord error ≲ 1e-6 of the size). Its atlas is built without its
``rayon`` feature (one thread), so per-entry times compare one thread with one thread.
"""

from __future__ import annotations

import argparse
import importlib
import math
import statistics
import subprocess
import tempfile
import time
from pathlib import Path

import numpy as np

import linkage
from linkage import synthesis
from linkage.synthesis import Atlas

ROOT = Path(__file__).resolve().parent.parent
PEER_DIR = ROOT / "target" / "peer"
PEER_BIN = PEER_DIR / "release" / "examples" / "synth"


def build_peer() -> None:
    """Build the peer once, before anything is timed (running it through `cargo run` rebuilt
    the path dependency on linkage-core whenever the working tree changed)."""
    subprocess.run(
        [
            "cargo",
            "build",
            "--quiet",
            "--release",
            "--example",
            "synth",
            "--target-dir",
            str(PEER_DIR),
        ],
        cwd=ROOT / "bench" / "fourbar-peer",
        check=True,
    )


def peer(*args: str) -> str:
    return subprocess.run([str(PEER_BIN), *args], capture_output=True, text=True, check=True).stdout


def size_of(p: np.ndarray) -> float:
    return float(np.sqrt(np.mean(np.sum((p - p.mean(0)) ** 2, 1))))


def polyline_distance(target: np.ndarray, curve: np.ndarray, closed: bool = True) -> float:
    a = curve
    b = np.roll(curve, -1, axis=0) if closed else curve[1:]
    a = a if closed else a[:-1]
    ab = b - a
    worst = 0.0
    for p in target:
        u = np.clip(np.sum((p - a) * ab, 1) / np.maximum(np.sum(ab * ab, 1), 1e-300), 0, 1)
        worst = max(worst, float(np.min(np.hypot(*(a + ab * u[:, None] - p).T))))
    return worst


def targets() -> list[tuple[str, np.ndarray, bool]]:
    out = []
    for name in ("hoecken", "chebyshev", "watt", "roberts", "evans_a"):
        fb = linkage.catalog.get(name)
        assert isinstance(fb, linkage.FourBar)
        out.append(
            (f"{name} (closed)", np.ascontiguousarray(fb.circuit(121).point[:-1][::2]), True)
        )
    t = np.linspace(0, 2 * math.pi, 60, endpoint=False)
    bean = np.c_[np.cos(t) + 0.25 * np.cos(2 * t), 0.6 * np.sin(t) + 0.15 * np.sin(3 * t)]
    out.append(("bean (not a four-bar curve)", bean, True))
    fb = linkage.catalog.get("hoecken")
    assert isinstance(fb, linkage.FourBar)
    out.append(
        ("hoecken arc (open)", np.ascontiguousarray(fb.sweep(np.linspace(1, 4, 40)).point), False)
    )
    return out


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--peer-entries", type=int, default=2000)
    ap.add_argument("--skip-million", action="store_true")
    ap.add_argument("--gens", type=int, default=50)
    ap.add_argument("--pop", type=int, default=200)
    args = ap.parse_args()
    build_peer()

    print("== atlas build (per entry)")
    t0 = time.perf_counter()
    a1 = Atlas.build(50_000, threads=1)
    ours1 = (time.perf_counter() - t0) / len(a1)
    t0 = time.perf_counter()
    a2 = Atlas.build(50_000, threads=2)
    ours2 = (time.perf_counter() - t0) / len(a2)
    assert np.array_equal(a1.descriptors, a2.descriptors)
    line = peer("atlas", str(args.peer_entries)).split()
    theirs = float(line[2]) / int(line[1])
    print(f"ours 1 thread   {ours1 * 1e6:8.1f} µs/entry (50,000 entries, 8 harmonics, 64 points)")
    print(f"ours 2 threads  {ours2 * 1e6:8.1f} µs/entry (bit-identical to 1 thread)")
    print(
        f"four-bar crate  {theirs * 1e6:8.1f} µs/entry ({line[1]} entries, 20 harmonics, 720 points, 1 thread)"
    )
    print(f"ratio (1 thread each): {theirs / ours1:.1f}x faster per entry (target >= 20x)")

    if not args.skip_million:
        print("== 10^6 entries on 2 threads")
        t0 = time.perf_counter()
        big = Atlas.build(1_000_000, threads=2)
        print(f"build {time.perf_counter() - t0:.1f} s (target <= 120 s)")
        q, _ = synthesis._core.synthesis.query_descriptors(targets()[0][1], big.harmonics, True)
        times = []
        for _ in range(7):
            t0 = time.perf_counter()
            big.nearest(q, 40, threads=2)
            times.append(time.perf_counter() - t0)
        print(
            f"query (4 target variants, 40 nearest) median {statistics.median(times) * 1e3:.1f} ms "
            f"over {len(big):,} entries (target <= 50 ms)"
        )
        del big

    print(
        "== targets: error / RMS radius and time (ours: default atlas, loaded; theirs: DE "
        f"{args.gens} generations x {args.pop})"
    )
    atlas = synthesis.default_atlas()
    importlib.import_module("scipy.optimize")  # one-time import, outside the timed calls
    wins = within = 0
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for name, pts, closed in targets():
            size = size_of(pts)
            t0 = time.perf_counter()
            found = synthesis.path(pts, closed=closed, top=1, atlas=atlas)
            t_ours = time.perf_counter() - t0
            e_ours = found[0].error / size if found else math.inf
            # The atlas stage alone (no global search): how soon a first answer comes.
            e_fast, t_fast = math.inf, math.nan
            if closed:
                t0 = time.perf_counter()
                quick = synthesis.path(pts, top=1, atlas=atlas, global_search=False)
                t_fast = time.perf_counter() - t0
                e_fast = quick[0].error / size if quick else math.inf
            f = Path(tmp) / "c.csv"
            np.savetxt(f, pts, delimiter=",")
            out = peer(
                "path", str(f), "closed" if closed else "open", str(args.gens), str(args.pop)
            )
            lines = out.splitlines()
            t_peer = float(lines[0].split()[1])
            curve = np.array([[float(v) for v in ln.split()[1:]] for ln in lines[1:]])
            e_peer = (
                polyline_distance(pts, curve) / size if np.all(np.isfinite(curve)) else math.inf
            )
            # Time to the crate's error: the cheapest of the full run, the atlas stage alone, a
            # run told that error is good enough (accept=, which skips the later stages once a
            # candidate is within it), and independent runs with a global search of 1, 2, 4,
            # ... generations.
            reach = [t for e, t in ((e_ours, t_ours), (e_fast, t_fast)) if e <= e_peer]
            t0 = time.perf_counter()
            enough = synthesis.path(pts, closed=closed, top=1, atlas=atlas, accept=e_peer * size)
            t_enough = time.perf_counter() - t0
            if enough and enough[0].error / size <= e_peer:
                reach.append(t_enough)
            budget = t_peer / 4

            def late() -> bool:
                return not reach or min(reach) > budget

            if closed and late():  # the atlas match as found, unrefined
                t0 = time.perf_counter()
                raw = synthesis.path(pts, top=1, atlas=atlas, global_search=False, refine=0)
                t_raw = time.perf_counter() - t0
                if raw and raw[0].error / size <= e_peer:
                    reach.append(t_raw)
            gens = 1
            while late() and gens <= args.gens:
                for refine in (0, 2):  # the global search's best as it is, or refined
                    t0 = time.perf_counter()
                    short = synthesis.path(
                        pts,
                        closed=closed,
                        top=1,
                        atlas=atlas,
                        global_search=True,
                        maxiter=gens,
                        refine=refine,
                    )
                    t_short = time.perf_counter() - t0
                    if short and short[0].error / size <= e_peer:
                        reach.append(t_short)
                gens *= 2
            t_reach = min(reach) if reach else math.inf
            wins += e_ours < e_peer
            within += t_reach <= t_peer / 4
            rows.append((name, e_ours, t_ours, e_peer, t_peer))
            fast = f"atlas only {e_fast:9.2e} in {t_fast:5.2f} s; " if closed else ""
            print(
                f"{name:28s} ours {e_ours:9.2e} in {t_ours:5.2f} s  crate {e_peer:9.2e} in "
                f"{t_peer:5.2f} s  {fast}crate's error reached in {t_reach:5.2f} s"
            )
    n = len(rows)
    print(
        f"lower error than the crate on {wins}/{n} targets (target >= 80 %); "
        f"reached the crate's error in <= 1/4 of its time on {within}/{n} (time to its error)"
    )


if __name__ == "__main__":
    main()
