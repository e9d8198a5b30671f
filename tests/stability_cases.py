"""Stiff and extreme cases with 50-digit mpmath references, shared by the CI subset
(tests/test_stability.py) and the full report (bench/stability.py).

Each family returns rows ``(case, max error, error / bound, branch flips, note)`` where the bound
is the error a backward-stable computation is allowed at that conditioning (a few ε of the
coordinates' magnitude, times the condition number where one applies: ``1/margin²`` for rates
near a toggle, where ``margin`` is the sweep's dyad margin).
"""

from __future__ import annotations

import math

import mpmath as mp
import numpy as np

import linkage

EPS = np.finfo(float).eps
mp.mp.dps = 50


def dyad_reference(r1, r2, d):
    """Joint of a dyad on base (0, 0) → (d, 0), left side, in 50 digits."""
    r1, r2, d = mp.mpf(r1), mp.mpf(r2), mp.mpf(d)
    x = (d * d + r1 * r1 - r2 * r2) / (2 * d)
    h = mp.sqrt(r1 * r1 - x * x)
    return float(x), float(h)


def toggle_dyad(deltas, stretched=True, r1=3.0, r2=2.0):
    """A dyad within δ of its toggle: base d = (r1 + r2)(1 − δ) stretched or |r1 − r2|(1 + δ)
    folded. Ours (Kahan's area) against the textbook √(r1² − x²) in plain numpy."""
    rows = []
    for delta in deltas:
        d = (r1 + r2) * (1 - delta) if stretched else abs(r1 - r2) * (1 + delta)
        m = linkage.Mechanism()
        m.fixed("O", (0, 0))
        m.crank("A", "O", radius=d)
        m.dyad("B", "O", "A", r1, r2, side="left")
        b = m.sweep(0.0).point
        x, h = dyad_reference(r1, r2, d)
        err = math.hypot(b[0] - x, b[1] - h)
        xn = (d * d + r1 * r1 - r2 * r2) / (2 * d)
        naive = math.hypot(xn - x, math.sqrt(max(r1 * r1 - xn * xn, 0.0)) - h)
        bound = 8 * EPS * (r1 + r2)
        rows.append(
            (
                f"{'stretched' if stretched else 'folded'} δ={delta:.0e}",
                err,
                err / bound,
                0,
                f"naive √(r²−x²): {naive:.1e}; height {h:.1e}",
            )
        )
    return rows


def four_bar_error(fb, theta, size, open_=True):
    """Largest coupler-point error of ``fb`` at ``theta`` against mpmath (pivots at O)."""
    from reference import fourbar_reference

    s = fb.sweep(theta)
    ox, oy = fb.o
    worst = 0.0
    for i in np.flatnonzero(s.valid):
        _, _, p = fourbar_reference(
            fb.ground, fb.crank, fb.coupler, fb.rocker, fb.point[0], fb.point[1], theta[i], open_
        )
        worst = max(
            worst, abs(float(p[0]) + ox - s.point[i, 0]), abs(float(p[1]) + oy - s.point[i, 1])
        )
    return worst, int(s.valid.sum())


def link_ratios(ratios, samples=40):
    """Crank-rockers whose crank is ``ratio`` times the other links (1e-6 … 1), and whose other
    links are ``ratio`` times a unit crank (1 … 1e6)."""
    rows = []
    theta = np.linspace(0, 2 * np.pi, samples, endpoint=False)
    for ratio in ratios:
        if ratio <= 1:
            fb = linkage.FourBar(ground=2.0, crank=ratio, coupler=2.5, rocker=2.5, point=(5.0, 0.0))
        else:
            fb = linkage.FourBar(
                ground=2.0 * ratio,
                crank=1.0,
                coupler=2.5 * ratio,
                rocker=2.5 * ratio,
                point=(5.0 * ratio, 0.0),
            )
        size = max(fb.ground, fb.coupler, abs(fb.point[0]))
        err, n = four_bar_error(fb, theta, size)
        bound = 16 * EPS * size
        rows.append((f"link ratio {ratio:.0e}", err, err / bound, 0, f"{n} samples"))
    return rows


def far_pivots(offsets, samples=40):
    """The Hoecken linkage with its pivots ``offset`` away from the origin."""
    rows = []
    theta = np.linspace(0, 2 * np.pi, samples, endpoint=False)
    for off in offsets:
        fb = linkage.FourBar(
            crank=10, coupler=25, rocker=25, point=(50, 0), o=(off, off), c=(off + 20, off)
        )
        err, _ = four_bar_error(fb, theta, 50)
        bound = 16 * EPS * (abs(off) + 50)
        rows.append((f"pivots at {off:.0e}", err, err / bound, 0, "bound 16ε·|coordinates|"))
    return rows


def singular_passes(step_deg=(0.5, 10.0, 45.0)):
    """Change-point linkages through their flat positions: a parallelogram must stay a
    parallelogram and an antiparallelogram an antiparallelogram, at any sampling."""
    rows = []
    for step in step_deg:
        theta = np.radians(90 + np.arange(0, 720 + 1e-9, step))
        par = linkage.FourBar(
            ground=3, crank=1, coupler=3, rocker=1, point=(1.5, 0), assembly="open"
        )
        s = par.sweep(theta)
        off = np.linalg.norm(s.joints[:, 3] - s.joints[:, 2] - np.array([3.0, 0.0]), axis=1)
        flips = int(np.count_nonzero(off > 1e-9))
        rows.append(
            (
                f"parallelogram, {step:g}° steps",
                float(off.max()),
                float(off.max()) / (16 * EPS * 4),
                flips,
                f"{len(theta)} samples",
            )
        )
        anti = linkage.FourBar(
            ground=3, crank=1, coupler=3, rocker=1, point=(1.5, 0), assembly="crossed"
        )
        s = anti.sweep(theta)
        # Antiparallelogram: OB stays parallel to AC (the crossed isosceles trapezoid); a flip
        # to the parallelogram away from the flat positions would break it.
        o, c, a, b = s.joints[:, 0], s.joints[:, 1], s.joints[:, 2], s.joints[:, 3]
        u, w = b - o, c - a
        skew = np.abs(u[:, 0] * w[:, 1] - u[:, 1] * w[:, 0]) / (
            np.linalg.norm(u, axis=1) * np.linalg.norm(w, axis=1)
        )
        flat = np.abs(np.sin(theta)) < 1e-9
        flips = int(np.count_nonzero((skew > 1e-9) & ~flat))
        rows.append(
            (
                f"antiparallelogram, {step:g}° steps",
                float(skew[~flat].max()),
                float(skew[~flat].max()) / (16 * EPS),
                flips,
                "OB ∥ AC",
            )
        )
    return rows


def rates_near_toggle(distances):
    """Evans C driven toward its input limit: velocity and acceleration against mpmath
    derivatives, the error scaled by the conditioning (1/margin); margins below 1e-6 are the
    flag for a near-singular Jacobian."""
    from reference import fourbar_reference

    fb = linkage.catalog.evans_c()
    _lo, hi = fb.input_limits()
    rows = []
    for dist in distances:
        th = hi - dist
        s = fb.sweep([th], omega=1.0, outputs=("velocity", "acceleration"))
        margin = float(s.margin[0])
        verr = aerr = 0.0
        vmag = amag = 0.0
        for axis in (0, 1):
            f = lambda t, a=axis: fourbar_reference(
                fb.ground, fb.crank, fb.coupler, fb.rocker, fb.point[0], fb.point[1], t
            )[2][a]
            v, a = float(mp.diff(f, mp.mpf(th), 1)), float(mp.diff(f, mp.mpf(th), 2))
            verr = max(verr, abs(v - s.velocity[0, axis]))
            aerr = max(aerr, abs(a - s.acceleration[0, axis]))
            vmag, amag = max(vmag, abs(v)), max(amag, abs(a))
        # Relative error against the conditioning: the crank pin's rounding (ε) moves the base
        # of the near-flat dyad, which the rates amplify as 1/margin² (margin ~ √distance).
        rel_v = verr / (vmag * EPS / margin**2)
        rel_a = aerr / (amag * EPS / margin**2)
        flag = "flagged (margin < 1e-6)" if margin < 1e-6 else ""
        rows.append(
            (
                f"Evans C {dist:.0e} rad from its limit",
                verr / vmag,
                max(rel_v, rel_a),
                0,
                f"margin {margin:.1e}; acc rel {aerr / amag:.1e} {flag}",
            )
        )
    return rows
