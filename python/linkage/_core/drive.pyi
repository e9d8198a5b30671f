"""Type stubs of ``linkage._core.drive`` (see crates/linkage-py).

Motion laws, programs, gear trains, schedules and cams.
"""

import numpy as np
from numpy.typing import NDArray
from typing_extensions import final

__all__ = [
    "CamGeometry",
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
def simple_gear_train(teeth: list[int]) -> tuple[float, int]: ...
def compound_gear_train(stages: list[tuple[int, int]]) -> tuple[float, int]: ...
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
) -> tuple[float, NDArray[np.float64], NDArray[np.float64], float, tuple[float, float]]: ...
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
