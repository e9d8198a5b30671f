"""Old path of :mod:`linkage.synthesis.precision_points` (Burmester, Freudenstein)."""

from linkage.synthesis.precision_points import (
    Dyad,
    FunctionGenerator,
    MotionCandidate,
    centre_point_curve,
    chebyshev_points,
    circle_point_curve,
    function,
    motion,
)

__all__ = [
    "Dyad",
    "FunctionGenerator",
    "MotionCandidate",
    "centre_point_curve",
    "chebyshev_points",
    "circle_point_curve",
    "function",
    "motion",
]
