"""Type stubs of ``linkage._core.motion`` (see crates/linkage-py).

Instant centres, path curvature and straight runs.
"""

from typing import Any

import numpy as np
from numpy.typing import NDArray

__all__ = [
    "circumcentres",
    "curvature_centres",
    "straight_run",
]

def curvature_centres(
    point: NDArray[np.float64], velocity: NDArray[np.float64], acceleration: NDArray[np.float64]
) -> tuple[NDArray[np.float64], NDArray[np.float64]]: ...
def circumcentres(
    p0: NDArray[np.float64], p1: NDArray[np.float64], p2: NDArray[np.float64]
) -> NDArray[np.float64]: ...
def straight_run(
    path: NDArray[np.float64],
    tol: float,
    closed: bool,
    velocity: NDArray[np.float64] | None = None,
) -> dict[str, Any] | None: ...
