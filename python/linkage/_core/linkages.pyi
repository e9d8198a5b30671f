"""Type stubs of ``linkage._core.linkages`` (see crates/linkage-py).

The four-bar (uniform and batch sweeps) and the slider-crank.
"""

import numpy as np
from numpy.typing import NDArray

from linkage._core import FourBar as FourBar
from linkage._core import SliderCrank as SliderCrank

__all__ = [
    "MAX_TABLE",
    "FourBar",
    "SliderCrank",
    "min_transmission_angle",
    "sweep_four_bar_batch",
]

MAX_TABLE: int

def sweep_four_bar_batch(
    o: NDArray[np.float64],
    c: NDArray[np.float64],
    crank: NDArray[np.float64],
    coupler: NDArray[np.float64],
    rocker: NDArray[np.float64],
    along: NDArray[np.float64],
    left: NDArray[np.float64],
    crossed: NDArray[np.bool_],
    theta: NDArray[np.float64],
    threads: int = 1,
    out: tuple[NDArray[np.float64], NDArray[np.bool_]] | None = None,
) -> tuple[NDArray[np.float64], NDArray[np.bool_]]: ...
def min_transmission_angle(min_sine: NDArray[np.float64]) -> NDArray[np.float64]: ...
