"""Type stubs of the compiled extension ``linkage._core`` (see crates/linkage-py)."""

from typing import Any

import numpy as np
from numpy.typing import NDArray
from typing_extensions import final

from linkage._choices import Assembly, Reach, Side, SweepMode
from linkage._core import (
    catalog as catalog,
)
from linkage._core import (
    drive as drive,
)
from linkage._core import (
    kinetostatics as kinetostatics,
)
from linkage._core import (
    linkages as linkages,
)
from linkage._core import (
    mechanism as mechanism,
)
from linkage._core import (
    motion as motion,
)
from linkage._core import (
    numeric as numeric,
)
from linkage._core import (
    sweep as sweep,
)
from linkage._core import (
    synthesis as synthesis,
)
from linkage._core import (
    walking as walking,
)

__all__ = [
    "ASSEMBLY_SIDES",
    "CAPACITY",
    "CHOICES",
    "RATE_MARGIN",
    "AssemblyError",
    "FourBar",
    "LinkageError",
    "Mechanism",
    "SliderCrank",
    "catalog",
    "drive",
    "kinetostatics",
    "linkages",
    "mechanism",
    "memory_message",
    "motion",
    "numeric",
    "size_text_of",
    "sweep",
    "synthesis",
    "walking",
]

CAPACITY: int
CHOICES: dict[str, list[str]]
ASSEMBLY_SIDES: dict[str, str]
RATE_MARGIN: float

def size_text_of(n: int) -> str: ...
def memory_message(what: str, nbytes: int, limit: int) -> str: ...

class LinkageError(ValueError): ...

class AssemblyError(LinkageError):
    joint: int | str | None
    """The joint that cannot be placed: the core's index, or its name once named."""
    gap: float | None
    """How far the lengths miss closure (length units); None when the joints coincide."""
    reason: str | None
    """The message after ``joint <joint>``."""

@final
class Mechanism:
    def __new__(cls) -> Mechanism: ...
    def __len__(self) -> int: ...
    @property
    def driver(self) -> int | None: ...
    def fixed(self, x: float, y: float) -> int: ...
    def crank(self, centre: int, radius: float, phase: float = 0.0) -> int: ...
    def dyad(self, p1: int, p2: int, r1: float, r2: float, side: Side) -> int: ...
    def slider(
        self, pivot: int, r: float, origin: int, dx: float, dy: float, reach: Reach
    ) -> int: ...
    def slider_on_link(
        self, pivot: int, r: float, origin: int, from_: int, to: int, angle: float, reach: Reach
    ) -> int: ...
    def point(self, from_: int, to: int, along: float, left: float) -> int: ...
    def describe(self) -> list[str]: ...
    def constructions(self) -> list[dict[str, Any]]: ...
    def line_directions(self, joint: int, joints: NDArray[np.float64]) -> NDArray[np.float64]: ...
    def bodies(self) -> list[list[int]]: ...
    def mobility(self) -> tuple[int, int, int, int]: ...
    def closure_residual(self, joints: NDArray[np.float64]) -> float: ...
    def longest_link(self, pose: NDArray[np.float64]) -> float: ...
    def sweep(
        self,
        theta: NDArray[np.float64],
        omega: NDArray[np.float64] | None = None,
        alpha: NDArray[np.float64] | None = None,
        velocity: bool = False,
        acceleration: bool = False,
        instant_centres: bool = False,
        curvature: bool = False,
        column: int | None = None,
        flags: bool = True,
        pairs: list[tuple[int, int]] | None = None,
        directions: bool = True,
    ) -> dict[str, Any]: ...

@final
class FourBar:
    def __new__(
        cls,
        o: tuple[float, float],
        c: tuple[float, float],
        crank: float,
        coupler: float,
        rocker: float,
        point: tuple[float, float],
        assembly: Assembly,
    ) -> FourBar: ...
    def parameters(
        self,
    ) -> tuple[float, float, float, float, float, float, float, float, float, Assembly]: ...
    def cognates(self) -> tuple[FourBar, FourBar]: ...
    def reversed(self) -> FourBar: ...
    def grashof(self) -> str: ...
    def input_range(
        self,
    ) -> str | tuple[float, float] | tuple[tuple[float, float], tuple[float, float]] | None: ...
    def transmission_angle(self, theta: NDArray[np.float64]) -> NDArray[np.float64]: ...
    def mechanism(self) -> Mechanism: ...
    def uniform_sweep(
        self,
        theta0: float,
        dtheta: float,
        n: int,
        mode: SweepMode = "table",
        block: int = 64,
        threads: int = 1,
        out: NDArray[np.float64] | None = None,
    ) -> NDArray[np.float64]: ...
    def circuit(
        self, n: int
    ) -> tuple[
        NDArray[np.float64], NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]
    ]: ...
    def coupler_inflection(
        self, theta: float
    ) -> (
        tuple[
            tuple[float, float],
            tuple[float, float],
            tuple[float, float],
            float,
            tuple[float, float],
            tuple[float, float],
        ]
        | None
    ): ...

@final
class SliderCrank:
    def __new__(
        cls,
        o: tuple[float, float],
        angle: float,
        offset: float,
        crank: float,
        coupler: float,
        point: tuple[float, float],
        reach: Reach,
    ) -> SliderCrank: ...
    def parameters(
        self,
    ) -> tuple[float, float, float, float, float, float, float, float, Reach, float, float]: ...
    def input_range(
        self,
    ) -> str | tuple[float, float] | tuple[tuple[float, float], tuple[float, float]] | None: ...
    def is_change_point(self) -> bool: ...
    def transmission(self, theta: NDArray[np.float64]) -> NDArray[np.float64]: ...
    def cognate(self) -> SliderCrank: ...
    def mechanism(self) -> Mechanism: ...
    def circuit(
        self, n: int
    ) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]: ...

# Precision-point synthesis (crates/linkage-py/src/precision.rs).

# -- path synthesis (crates/linkage-py/src/synthesis.rs) --------------------------------------
