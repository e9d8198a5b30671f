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
from linkage._core.catalog import (
    FOUR_BARS as FOUR_BARS,
)
from linkage._core.catalog import (
    MULTI_LOOP as MULTI_LOOP,
)
from linkage._core.catalog import (
    four_bar as catalog_four_bar,
)
from linkage._core.catalog import (
    linkage as catalog_linkage,
)
from linkage._core.catalog import (
    names as catalog_names,
)
from linkage._core.drive import (
    cam_geometry as cam_geometry,
)
from linkage._core.drive import (
    compound_gear_train as gear_train_compound,
)
from linkage._core.drive import (
    evaluate_motion_law as motion_law_eval,
)
from linkage._core.drive import (
    evaluate_program as program_eval,
)
from linkage._core.drive import (
    evaluate_schedule as schedule_eval,
)
from linkage._core.drive import (
    motion_law_names as motion_law_names,
)
from linkage._core.drive import (
    program_discontinuities as program_discontinuities,
)
from linkage._core.drive import (
    simple_gear_train as gear_train_simple,
)
from linkage._core.drive import (
    stance_schedule as stance_schedule,
)
from linkage._core.kinetostatics import (
    forces as forces,
)
from linkage._core.linkages import (
    MAX_TABLE as MAX_TABLE,
)
from linkage._core.linkages import (
    sweep_four_bar_batch as batch_sweep,
)
from linkage._core.mechanism import (
    degrees_of_freedom as degrees_of_freedom,
)
from linkage._core.motion import (
    circumcentres as circumcentres,
)
from linkage._core.motion import (
    curvature_centres as curvature_centres,
)
from linkage._core.motion import (
    straight_run as straight_run,
)
from linkage._core.numeric import (
    reduce_angle as reduce_angle,
)
from linkage._core.sweep import (
    DEFAULT_TOGGLE_MARGIN as DEFAULT_TOGGLE_MARGIN,
)
from linkage._core.sweep import (
    instruction_set as sweep_simd,
)
from linkage._core.sweep import (
    sweep_mechanisms as sweep_mechanisms,
)
from linkage._core.synthesis import (
    ARC_ENTRY_PARAMS as ARC_ENTRY_PARAMS,
)
from linkage._core.synthesis import (
    ARC_FRACTIONS as ARC_FRACTIONS,
)
from linkage._core.synthesis import (
    CURVE_EQUATION_POINTS as CURVE_EQUATION_POINTS,
)
from linkage._core.synthesis import (
    ENTRY_PARAMS as ENTRY_PARAMS,
)
from linkage._core.synthesis import (
    FOOT_STARTS as FOOT_STARTS,
)
from linkage._core.synthesis import (
    LENGTH_RANGE as LENGTH_RANGE,
)
from linkage._core.synthesis import (
    MAX_POSES as MAX_POSES,
)
from linkage._core.synthesis import (
    MIN_CURVE_POINTS as MIN_CURVE_POINTS,
)
from linkage._core.synthesis import (
    PLACED_PARAMS as PLACED_PARAMS,
)
from linkage._core.synthesis import (
    QUERY_VARIANTS as QUERY_VARIANTS,
)
from linkage._core.synthesis import (
    SLIDER_ARC_ENTRY_PARAMS as SLIDER_ARC_ENTRY_PARAMS,
)
from linkage._core.synthesis import (
    SLIDER_ENTRY_PARAMS as SLIDER_ENTRY_PARAMS,
)
from linkage._core.synthesis import (
    SLIDER_EQUATION_POINTS as SLIDER_EQUATION_POINTS,
)
from linkage._core.synthesis import (
    SLIDER_PARAMS as SLIDER_PARAMS,
)
from linkage._core.synthesis import (
    arc_entry_frame as synth_arc_frame,
)
from linkage._core.synthesis import (
    build_arc_atlas as synth_arc_atlas_build,
)
from linkage._core.synthesis import (
    build_atlas as synth_atlas_build,
)
from linkage._core.synthesis import (
    build_slider_atlas as synth_slider_atlas_build,
)
from linkage._core.synthesis import (
    burmester_centre_point as burmester_centre_point,
)
from linkage._core.synthesis import (
    burmester_circle_point as burmester_circle_point,
)
from linkage._core.synthesis import (
    burmester_common_pole as burmester_common_pole,
)
from linkage._core.synthesis import (
    burmester_curve as burmester_curve,
)
from linkage._core.synthesis import (
    chebyshev_points as chebyshev_points,
)
from linkage._core.synthesis import (
    circuit_frame as synth_frame,
)
from linkage._core.synthesis import (
    circuit_info as synth_info,
)
from linkage._core.synthesis import (
    covering_arc as synth_arc,
)
from linkage._core.synthesis import (
    fourbars_from_curve as synth_curve_equation,
)
from linkage._core.synthesis import (
    function_generator as function_generator,
)
from linkage._core.synthesis import (
    motion_candidates as motion_candidates,
)
from linkage._core.synthesis import (
    nearest_entries as synth_atlas_nearest,
)
from linkage._core.synthesis import (
    path_errors as synth_errors,
)
from linkage._core.synthesis import (
    place_entry as synth_place,
)
from linkage._core.synthesis import (
    place_slider_entry as synth_slider_place,
)
from linkage._core.synthesis import (
    polyline_distance as polyline_distance,
)
from linkage._core.synthesis import (
    polyline_distance_each as polyline_distance_each,
)
from linkage._core.synthesis import (
    query_descriptors as synth_descriptors,
)
from linkage._core.synthesis import (
    residuals as synth_residuals,
)
from linkage._core.synthesis import (
    slider_circuit_frame as synth_slider_frame,
)
from linkage._core.synthesis import (
    slider_circuit_info as synth_slider_info,
)
from linkage._core.synthesis import (
    slider_cranks_from_curve as synth_slider_curve_equation,
)
from linkage._core.synthesis import (
    slider_path_errors as synth_slider_errors,
)
from linkage._core.synthesis import (
    slider_residuals as synth_slider_residuals,
)
from linkage._core.walking import (
    four_bar_gaits as four_bar_gaits,
)
from linkage._core.walking import (
    gait_columns as gait_columns,
)
from linkage._core.walking import (
    leg_gait as leg_gait,
)
from linkage._core.walking import (
    support_margins as support_margins,
)

__all__ = [
    "ARC_ENTRY_PARAMS",
    "ARC_FRACTIONS",
    "ASSEMBLY_SIDES",
    "CAPACITY",
    "CHOICES",
    "CURVE_EQUATION_POINTS",
    "DEFAULT_TOGGLE_MARGIN",
    "ENTRY_PARAMS",
    "FOOT_STARTS",
    "FOUR_BARS",
    "LENGTH_RANGE",
    "MAX_POSES",
    "MAX_TABLE",
    "MIN_CURVE_POINTS",
    "MULTI_LOOP",
    "PLACED_PARAMS",
    "QUERY_VARIANTS",
    "RATE_MARGIN",
    "SLIDER_ARC_ENTRY_PARAMS",
    "SLIDER_ENTRY_PARAMS",
    "SLIDER_EQUATION_POINTS",
    "SLIDER_PARAMS",
    "AssemblyError",
    "FourBar",
    "LinkageError",
    "Mechanism",
    "SliderCrank",
    "batch_sweep",
    "burmester_centre_point",
    "burmester_circle_point",
    "burmester_common_pole",
    "burmester_curve",
    "cam_geometry",
    "catalog",
    "catalog_four_bar",
    "catalog_linkage",
    "catalog_names",
    "chebyshev_points",
    "circumcentres",
    "curvature_centres",
    "degrees_of_freedom",
    "drive",
    "forces",
    "four_bar_gaits",
    "function_generator",
    "gait_columns",
    "gear_train_compound",
    "gear_train_simple",
    "kinetostatics",
    "leg_gait",
    "linkages",
    "mechanism",
    "memory_message",
    "motion",
    "motion_candidates",
    "motion_law_eval",
    "motion_law_names",
    "numeric",
    "polyline_distance",
    "polyline_distance_each",
    "program_discontinuities",
    "program_eval",
    "reduce_angle",
    "schedule_eval",
    "size_text_of",
    "stance_schedule",
    "straight_run",
    "support_margins",
    "sweep",
    "sweep_mechanisms",
    "sweep_simd",
    "synth_arc",
    "synth_arc_atlas_build",
    "synth_arc_frame",
    "synth_atlas_build",
    "synth_atlas_nearest",
    "synth_curve_equation",
    "synth_descriptors",
    "synth_errors",
    "synth_frame",
    "synth_info",
    "synth_place",
    "synth_residuals",
    "synth_slider_atlas_build",
    "synth_slider_curve_equation",
    "synth_slider_errors",
    "synth_slider_frame",
    "synth_slider_info",
    "synth_slider_place",
    "synth_slider_residuals",
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
