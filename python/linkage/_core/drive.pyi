"""Type stubs of ``linkage._core.drive`` (see crates/linkage-py).

Motion laws, programs, gear trains, schedules and cams.
"""

from collections.abc import Iterator
from typing import Any

import numpy as np
from numpy.typing import NDArray
from typing_extensions import final

__all__ = [
    "CamGeometry",
    "GearRatio",
    "StanceScheduleTable",
    "cam_geometry",
    "compound_gear_train",
    "evaluate_motion_law",
    "evaluate_program",
    "evaluate_schedule",
    "motion_law_names",
    "program_discontinuities",
    "simple_gear_train",
    "stance_schedule",
]

def motion_law_names() -> list[str]: ...
def evaluate_motion_law(name: str, u: NDArray[np.float64]) -> NDArray[np.float64]: ...
def evaluate_program(
    start: float,
    durations: list[float],
    rises: list[float],
    laws: list[str | None],
    t: NDArray[np.float64],
) -> NDArray[np.float64]: ...
def program_discontinuities(
    start: float, durations: list[float], rises: list[float], laws: list[str | None], tol: float
) -> list[tuple[int, int, float]]: ...
def simple_gear_train(teeth: list[int]) -> GearRatio: ...
def compound_gear_train(stages: list[tuple[int, int]]) -> GearRatio: ...
def evaluate_schedule(
    dt: float,
    advance: float,
    theta: NDArray[np.float64],
    omega: NDArray[np.float64],
    t: NDArray[np.float64],
    single: bool,
) -> NDArray[np.float64]: ...
def stance_schedule(
    theta: NDArray[np.float64],
    u: NDArray[np.float64],
    foot_speed: float,
    duty_factor: float,
    samples: int,
) -> StanceScheduleTable: ...
def cam_geometry(
    phi: NDArray[np.float64],
    y: NDArray[np.float64],
    base_radius: float,
    roller_radius: float | None = None,
    offset: float = 0.0,
) -> CamGeometry: ...

@final
class CamGeometry:
    """A cam's geometry sampled at ``n`` cam angles (``linkage_core::CamPoint`` by columns)."""

    @property
    def pitch(self) -> NDArray[np.float64]: ...
    @property
    def profile(self) -> NDArray[np.float64]: ...
    @property
    def pressure_angle(self) -> NDArray[np.float64]: ...
    @property
    def pitch_radius(self) -> NDArray[np.float64]: ...
    @property
    def profile_radius(self) -> NDArray[np.float64]: ...
    def __getitem__(self, key: str, /) -> Any: ...

@final
class GearRatio:
    """The ratio of a gear train (``linkage_core::GearTrain``)."""

    @property
    def ratio(self) -> float: ...
    @property
    def sign(self) -> int: ...
    def astuple(self) -> tuple[float, int]: ...
    def __len__(self) -> int: ...
    def __getitem__(self, index: int, /) -> Any: ...
    def __iter__(self) -> Iterator[Any]: ...

@final
class StanceScheduleTable:
    """A constant-foot-speed crank schedule tabulated at uniform times."""

    @property
    def dt(self) -> float: ...
    @property
    def theta(self) -> NDArray[np.float64]: ...
    @property
    def omega(self) -> NDArray[np.float64]: ...
    @property
    def stance_time(self) -> float: ...
    @property
    def stance_angles(self) -> tuple[float, float]: ...
    def astuple(
        self,
    ) -> tuple[float, NDArray[np.float64], NDArray[np.float64], float, tuple[float, float]]: ...
    def __len__(self) -> int: ...
    def __getitem__(self, index: int, /) -> Any: ...
    def __iter__(self) -> Iterator[Any]: ...
