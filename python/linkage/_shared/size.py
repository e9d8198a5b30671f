"""The size of a set of points, shared by path and motion synthesis (which rank by it).

Formed in units of a power of two near the largest coordinate, so no sum or square overflows
or underflows, even near the float range's ends.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

__all__ = [
    "mean",
    "pow2",
    "rms_size",
]


def pow2(m: float) -> float:
    """Return the power of two just above the positive finite ``m`` (an exact divisor)."""
    return math.ldexp(1.0, math.frexp(m)[1])


def mean(points: NDArray[np.float64]) -> NDArray[np.float64]:
    """Return the centroid of ``points``, summed in units of a power of two.

    No sum overflows, even near the largest floats.
    """
    m = float(np.max(np.abs(points))) if points.size else 0.0
    if not m > 0.0 or not math.isfinite(m):
        return np.asarray(points.mean(axis=0), dtype=np.float64)
    k = pow2(m)
    return np.asarray((points / k).mean(axis=0) * k, dtype=np.float64)


def rms_size(points: NDArray[np.float64]) -> float:
    """Return the RMS distance of ``points`` (shaped ``(n, 2)``) from their centroid."""
    centred = points - mean(points)
    m = float(np.max(np.abs(centred))) if centred.size else 0.0
    if not m > 0.0 or not math.isfinite(m):
        return m if centred.size else 0.0
    k = pow2(m)
    return float(np.sqrt(np.mean(np.sum((centred / k) ** 2, axis=1)))) * k
