"""Type stubs of ``linkage._core.synthesis`` (see crates/linkage-py).

Precision-point and path synthesis.
"""

from typing import Any

import numpy as np
from numpy.typing import NDArray

__all__ = [
    "ARC_ENTRY_PARAMS",
    "ARC_FRACTIONS",
    "CURVE_EQUATION_POINTS",
    "ENTRY_PARAMS",
    "FOOT_STARTS",
    "LENGTH_RANGE",
    "MAX_POSES",
    "MIN_CURVE_POINTS",
    "PLACED_PARAMS",
    "QUERY_VARIANTS",
    "SLIDER_ARC_ENTRY_PARAMS",
    "SLIDER_ENTRY_PARAMS",
    "SLIDER_EQUATION_POINTS",
    "SLIDER_PARAMS",
    "arc_entry_frame",
    "build_arc_atlas",
    "build_atlas",
    "build_slider_atlas",
    "burmester_centre_point",
    "burmester_circle_point",
    "burmester_common_pole",
    "burmester_curve",
    "chebyshev_points",
    "circuit_frame",
    "circuit_info",
    "covering_arc",
    "fourbars_from_curve",
    "function_generator",
    "motion_candidates",
    "nearest_entries",
    "path_errors",
    "place_entry",
    "place_slider_entry",
    "polyline_distance",
    "polyline_distance_each",
    "query_descriptors",
    "residuals",
    "slider_circuit_frame",
    "slider_circuit_info",
    "slider_cranks_from_curve",
    "slider_path_errors",
    "slider_residuals",
]

CURVE_EQUATION_POINTS: int
SLIDER_EQUATION_POINTS: int
ENTRY_PARAMS: int
SLIDER_ENTRY_PARAMS: int
ARC_ENTRY_PARAMS: int
SLIDER_ARC_ENTRY_PARAMS: int
ARC_FRACTIONS: list[float]
LENGTH_RANGE: tuple[float, float]
PLACED_PARAMS: int
SLIDER_PARAMS: int
QUERY_VARIANTS: int
MIN_CURVE_POINTS: int
MAX_POSES: int
FOOT_STARTS: int

def burmester_centre_point(
    poses: list[tuple[float, float, float]], circle: tuple[float, float]
) -> tuple[float, float]: ...
def burmester_circle_point(
    poses: list[tuple[float, float, float]], centre: tuple[float, float]
) -> tuple[float, float]: ...
def burmester_common_pole(
    poses: list[tuple[float, float, float]],
) -> tuple[float, float] | None: ...
def burmester_curve(
    poses: list[tuple[float, float, float]], beta: NDArray[np.float64], free: int | None = None
) -> tuple[int, NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]: ...
def motion_candidates(
    poses: list[tuple[float, float, float]],
    crank: NDArray[np.float64],
    rocker: NDArray[np.float64],
) -> dict[str, Any]: ...
def chebyshev_points(x0: float, x1: float, n: int) -> NDArray[np.float64]: ...
def function_generator(
    phi: NDArray[np.float64],
    psi: NDArray[np.float64],
    ground: float,
    samples: NDArray[np.float64],
) -> dict[str, Any]: ...
def build_atlas(
    entries: int, harmonics: int = 8, samples: int = 64, threads: int = 1
) -> tuple[NDArray[np.float32], NDArray[np.float64], NDArray[np.uint64]]: ...
def build_slider_atlas(
    entries: int, harmonics: int = 8, samples: int = 64, threads: int = 1
) -> tuple[NDArray[np.float32], NDArray[np.float64], NDArray[np.uint64]]: ...
def build_arc_atlas(
    entries: int,
    harmonics: int = 8,
    samples: int = 128,
    phases: int = 8,
    threads: int = 1,
    slider: bool = False,
) -> tuple[NDArray[np.float32], NDArray[np.float64], NDArray[np.uint64]]: ...
def arc_entry_frame(
    entry: NDArray[np.float64], harmonics: int, samples: int, phases: int, slider: bool = False
) -> NDArray[np.float64]: ...
def nearest_entries(
    descriptors: NDArray[np.float32], targets: NDArray[np.float32], k: int, threads: int = 1
) -> tuple[NDArray[np.int64], NDArray[np.float32], NDArray[np.int64]]: ...
def query_descriptors(
    points: NDArray[np.float64], harmonics: int, closed: bool
) -> tuple[NDArray[np.float32], NDArray[np.float64]]: ...
def circuit_frame(
    params: NDArray[np.float64], crossed: bool, harmonics: int, samples: int
) -> NDArray[np.float64]: ...
def slider_circuit_frame(
    params: NDArray[np.float64], harmonics: int, samples: int
) -> NDArray[np.float64]: ...
def place_entry(
    entry: NDArray[np.float64],
    curve: NDArray[np.float64],
    target: NDArray[np.float64],
    flip: bool,
) -> NDArray[np.float64]: ...
def place_slider_entry(
    entry: NDArray[np.float64],
    curve: NDArray[np.float64],
    target: NDArray[np.float64],
    flip: bool,
) -> NDArray[np.float64]: ...
def residuals(
    params: NDArray[np.float64],
    crossed: NDArray[np.bool_],
    targets: NDArray[np.float64],
    s: NDArray[np.float64],
) -> NDArray[np.float64]: ...
def slider_residuals(
    params: NDArray[np.float64], targets: NDArray[np.float64], s: NDArray[np.float64]
) -> NDArray[np.float64]: ...
def path_errors(
    params: NDArray[np.float64],
    crossed: NDArray[np.bool_],
    targets: NDArray[np.float64],
    samples: int = 256,
    exact: bool = False,
    closed: bool = True,
    threads: int = 1,
) -> tuple[NDArray[np.float64], NDArray[np.float64]]: ...
def slider_path_errors(
    params: NDArray[np.float64],
    targets: NDArray[np.float64],
    samples: int = 256,
    exact: bool = False,
    closed: bool = True,
    threads: int = 1,
) -> tuple[NDArray[np.float64], NDArray[np.float64]]: ...
def circuit_info(
    params: NDArray[np.float64],
    crossed: bool,
    s_lo: float,
    s_hi: float,
    check_samples: int = 2048,
) -> tuple[str | None, bool, float, float, float, bool]: ...
def slider_circuit_info(
    params: NDArray[np.float64], s_lo: float, s_hi: float, check_samples: int = 2048
) -> tuple[str | None, bool, float, float, float, bool]: ...
def covering_arc(feet: NDArray[np.float64]) -> tuple[float, float] | None: ...
def fourbars_from_curve(
    points: NDArray[np.float64],
) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64], float, float]: ...
def slider_cranks_from_curve(
    points: NDArray[np.float64],
) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64], float, float]: ...
def polyline_distance(
    points: NDArray[np.float64], path: NDArray[np.float64]
) -> NDArray[np.float64]: ...
def polyline_distance_each(
    points: NDArray[np.float64], paths: NDArray[np.float64], stride: int
) -> NDArray[np.float64]: ...
