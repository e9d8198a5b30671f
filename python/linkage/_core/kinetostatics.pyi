"""Type stubs of ``linkage._core.kinetostatics`` (see crates/linkage-py).

Joint forces and driving torque over a sweep.
"""

from typing import Any

import numpy as np
from numpy.typing import NDArray

from linkage._core import Mechanism

__all__ = [
    "forces",
]

def forces(
    mech: Mechanism,
    theta: NDArray[np.float64],
    omega: NDArray[np.float64],
    alpha: NDArray[np.float64],
    inertia: list[tuple[float, float, float, float]],
    gravity: tuple[float, float],
    loads: list[tuple[int, int, NDArray[np.float64], NDArray[np.float64]]],
) -> dict[str, Any]: ...
