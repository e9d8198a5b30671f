"""Type stubs of ``linkage._core.motion`` (see crates/linkage-py).

Instant centres, path curvature and straight runs.
"""

from typing import Any

import numpy as np
from numpy.typing import NDArray
from typing_extensions import final

__all__ = [
    "StraightRun",
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
) -> StraightRun | None: ...

@final
class StraightRun:
    """The longest near-straight run of a path (``linkage_core::StraightPart``)."""

    @property
    def start(self) -> int: ...
    @property
    def count(self) -> int: ...
    @property
    def point(self) -> tuple[float, float]: ...
    @property
    def direction(self) -> tuple[float, float]: ...
    @property
    def max_deviation(self) -> float: ...
    @property
    def length(self) -> float: ...
    @property
    def lift(self) -> float | None: ...
    @property
    def mean_speed(self) -> float | None: ...
    @property
    def speed_variation(self) -> float | None: ...
    def __getitem__(self, key: str, /) -> Any: ...
