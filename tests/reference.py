"""High-precision reference solutions (mpmath, 50 digits), independent of the library."""

from __future__ import annotations

import mpmath as mp

mp.mp.dps = 50


def fourbar_reference(g, r, c, k, along, left, theta, open_=True):
    """Joints A, B and the coupler point of a four-bar (O at the origin, C = (g, 0)) in 50-digit
    arithmetic, by the textbook circle intersection — an independent formulation from the
    library's Kahan-area dyad."""
    g, r, c, k, along, left = (mp.mpf(x) for x in (g, r, c, k, along, left))
    th = mp.mpf(theta)
    ax, ay = r * mp.cos(th), r * mp.sin(th)
    dx, dy = g - ax, -ay
    d = mp.sqrt(dx * dx + dy * dy)
    x = (d * d + c * c - k * k) / (2 * d)
    h = mp.sqrt(c * c - x * x)
    ux, uy = dx / d, dy / d
    s = 1 if open_ else -1
    bx, by = ax + x * ux - s * h * uy, ay + x * uy + s * h * ux
    ex, ey = (bx - ax) / c, (by - ay) / c
    px, py = ax + along * ex - left * ey, ay + along * ey + left * ex
    return (ax, ay), (bx, by), (px, py)
