"""Type stubs of ``linkage._core.kinetostatics`` (see crates/linkage-py).

Joint forces and driving torque over a sweep.
"""

from typing import Any

import numpy as np
from numpy.typing import NDArray
from typing_extensions import final

from linkage._core import Mechanism

__all__ = [
    "JointForces",
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
) -> JointForces: ...

@final
class JointForces:
    """Driving torque and joint reactions of a mechanism over a sweep, one row a sample."""

    @property
    def torque(self) -> NDArray[np.float64]: ...
    @property
    def power_torque(self) -> NDArray[np.float64]: ...
    @property
    def valid(self) -> NDArray[np.bool_]: ...
    @property
    def reactions(self) -> NDArray[np.float64]: ...
    @property
    def couples(self) -> NDArray[np.float64]: ...
    @property
    def reaction_links(self) -> list[tuple[int, int, int]]: ...
    def __getitem__(self, key: str, /) -> Any: ...
