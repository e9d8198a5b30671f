"""Type stubs of ``linkage._core.numeric`` (see crates/linkage-py).

Exact angle reduction.
"""

import numpy as np
from numpy.typing import NDArray

__all__ = [
    "reduce_angle",
]

def reduce_angle(theta: NDArray[np.float64]) -> NDArray[np.float64]: ...
