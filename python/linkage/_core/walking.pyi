"""Type stubs of ``linkage._core.walking`` (see crates/linkage-py).

Gaits of legs and of four-bar legs, support margins.
"""

import numpy as np
from numpy.typing import NDArray

__all__ = [
    "four_bar_gaits",
    "gait_columns",
    "leg_gait",
    "support_margins",
]

def leg_gait(
    path: NDArray[np.float64],
    rate: NDArray[np.float64],
    tol: float,
    ground: float | None = None,
) -> tuple[dict[str, float], NDArray[np.bool_]]: ...
def four_bar_gaits(
    o: NDArray[np.float64],
    c: NDArray[np.float64],
    crank: NDArray[np.float64],
    coupler: NDArray[np.float64],
    rocker: NDArray[np.float64],
    along: NDArray[np.float64],
    left: NDArray[np.float64],
    crossed: NDArray[np.bool_],
    samples: int,
    rel_tol: float,
    threads: int = 1,
) -> NDArray[np.float64]: ...
def gait_columns() -> list[str]: ...
def support_margins(
    points: NDArray[np.float64], cg: NDArray[np.float64]
) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.uint64]]: ...
