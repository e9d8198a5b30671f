"""Type stubs of ``linkage._core.sweep`` (see crates/linkage-py).

Sweeps of mechanisms and the instruction set of the sweep kernels.
"""

import numpy as np
from numpy.typing import NDArray

from linkage._core import Mechanism

__all__ = [
    "DEFAULT_TOGGLE_MARGIN",
    "instruction_set",
    "sweep_mechanisms",
]

DEFAULT_TOGGLE_MARGIN: float

def sweep_mechanisms(
    mechanisms: list[Mechanism], theta: NDArray[np.float64], threads: int = 1
) -> tuple[NDArray[np.float64], NDArray[np.bool_]]: ...
def instruction_set() -> str: ...
