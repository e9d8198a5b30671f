"""Type stubs of the compiled extension ``linkage._core`` (see crates/linkage-py)."""

from typing import Any

import numpy as np
from numpy.typing import NDArray
from typing_extensions import final

from linkage._choices import Assembly, Reach, Side, SweepMode

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
    "batch_sweep",
    "burmester_centre_point",
    "burmester_circle_point",
    "burmester_common_pole",
    "burmester_curve",
    "cam_geometry",
    "catalog_four_bar",
    "catalog_linkage",
    "catalog_names",
    "chebyshev_points",
    "circumcentres",
    "curvature_centres",
    "degrees_of_freedom",
    "forces",
    "four_bar_gaits",
    "function_generator",
    "gait_columns",
    "gear_train_compound",
    "gear_train_simple",
    "leg_gait",
    "motion_candidates",
    "motion_law_eval",
    "motion_law_names",
    "polyline_distance",
    "polyline_distance_each",
    "program_discontinuities",
    "program_eval",
    "reduce_angle",
    "schedule_eval",
    "stance_schedule",
    "straight_run",
    "support_margins",
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
]

CAPACITY: int
CHOICES: dict[str, list[str]]
ASSEMBLY_SIDES: dict[str, str]
RATE_MARGIN: float

class LinkageError(ValueError): ...
class AssemblyError(LinkageError): ...

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

def sweep_simd() -> str: ...
def reduce_angle(theta: NDArray[np.float64]) -> NDArray[np.float64]: ...
def sweep_mechanisms(
    mechanisms: list[Mechanism], theta: NDArray[np.float64], threads: int = 1
) -> tuple[NDArray[np.float64], NDArray[np.bool_]]: ...
def batch_sweep(
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
def catalog_names() -> tuple[list[str], list[str]]: ...
def catalog_four_bar(name: str) -> FourBar: ...
def catalog_linkage(name: str, scale: float = 2.0) -> tuple[Mechanism, list[str], int]: ...
def curvature_centres(
    point: NDArray[np.float64], velocity: NDArray[np.float64], acceleration: NDArray[np.float64]
) -> tuple[NDArray[np.float64], NDArray[np.float64]]: ...
def circumcentres(
    p0: NDArray[np.float64], p1: NDArray[np.float64], p2: NDArray[np.float64]
) -> NDArray[np.float64]: ...
def straight_run(
    path: NDArray[np.float64],
    tol: float,
    closed: bool,
    velocity: NDArray[np.float64] | None = None,
) -> dict[str, Any] | None: ...
def motion_law_names() -> list[str]: ...
def motion_law_eval(name: str, u: NDArray[np.float64]) -> NDArray[np.float64]: ...
def program_eval(
    start: float,
    durations: list[float],
    rises: list[float],
    laws: list[str | None],
    t: NDArray[np.float64],
) -> NDArray[np.float64]: ...
def program_discontinuities(
    start: float, durations: list[float], rises: list[float], laws: list[str | None], tol: float
) -> list[tuple[int, int, float]]: ...
def gear_train_simple(teeth: list[int]) -> tuple[float, int]: ...
def gear_train_compound(stages: list[tuple[int, int]]) -> tuple[float, int]: ...
def schedule_eval(
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
) -> dict[str, NDArray[np.float64]]: ...
def degrees_of_freedom(links: int, lower_pairs: int, higher_pairs: int) -> int: ...
def forces(
    mech: Mechanism,
    theta: NDArray[np.float64],
    omega: NDArray[np.float64],
    alpha: NDArray[np.float64],
    inertia: list[tuple[float, float, float, float]],
    gravity: tuple[float, float],
    loads: list[tuple[int, int, NDArray[np.float64], NDArray[np.float64]]],
) -> dict[str, Any]: ...
def support_margins(
    points: NDArray[np.float64], cg: NDArray[np.float64]
) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.uint64]]: ...

# Precision-point synthesis (crates/linkage-py/src/precision.rs).
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
def leg_gait(
    path: NDArray[np.float64],
    rate: NDArray[np.float64],
    tol: float,
    ground: float | None = None,
) -> tuple[dict[str, float], NDArray[np.bool_]]: ...
def four_bar_gaits(
    o: NDArray[np.float64],
    c: NDArray[np.float64],
    crank: NDArray[np.float64],
    coupler: NDArray[np.float64],
    rocker: NDArray[np.float64],
    along: NDArray[np.float64],
    left: NDArray[np.float64],
    crossed: NDArray[np.bool_],
    samples: int,
    rel_tol: float,
    threads: int = 1,
) -> NDArray[np.float64]: ...
def gait_columns() -> list[str]: ...

# -- path synthesis (crates/linkage-py/src/synthesis.rs) --------------------------------------
def synth_atlas_build(
    entries: int, harmonics: int = 8, samples: int = 64, threads: int = 1
) -> tuple[NDArray[np.float32], NDArray[np.float64], NDArray[np.uint64]]: ...
def synth_arc_atlas_build(
    entries: int,
    harmonics: int = 8,
    samples: int = 128,
    phases: int = 8,
    threads: int = 1,
    slider: bool = False,
) -> tuple[NDArray[np.float32], NDArray[np.float64], NDArray[np.uint64]]: ...
def synth_arc_frame(
    entry: NDArray[np.float64], harmonics: int, samples: int, phases: int, slider: bool = False
) -> NDArray[np.float64]: ...
def synth_atlas_nearest(
    descriptors: NDArray[np.float32], targets: NDArray[np.float32], k: int, threads: int = 1
) -> tuple[NDArray[np.int64], NDArray[np.float32], NDArray[np.int64]]: ...
def synth_descriptors(
    points: NDArray[np.float64], harmonics: int, closed: bool
) -> tuple[NDArray[np.float32], NDArray[np.float64]]: ...
def synth_frame(
    params: NDArray[np.float64], crossed: bool, harmonics: int, samples: int
) -> NDArray[np.float64]: ...
def synth_place(
    entry: NDArray[np.float64],
    curve: NDArray[np.float64],
    target: NDArray[np.float64],
    flip: bool,
) -> NDArray[np.float64]: ...
def synth_arc(feet: NDArray[np.float64]) -> tuple[float, float] | None: ...
def synth_curve_equation(
    points: NDArray[np.float64],
) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64], float, float]: ...
def synth_slider_curve_equation(
    points: NDArray[np.float64],
) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64], float, float]: ...
def polyline_distance(
    points: NDArray[np.float64], path: NDArray[np.float64]
) -> NDArray[np.float64]: ...
def polyline_distance_each(
    points: NDArray[np.float64], paths: NDArray[np.float64], stride: int
) -> NDArray[np.float64]: ...
def synth_residuals(
    params: NDArray[np.float64],
    crossed: NDArray[np.bool_],
    targets: NDArray[np.float64],
    s: NDArray[np.float64],
) -> NDArray[np.float64]: ...
def synth_errors(
    params: NDArray[np.float64],
    crossed: NDArray[np.bool_],
    targets: NDArray[np.float64],
    samples: int = 256,
    exact: bool = False,
    closed: bool = True,
    threads: int = 1,
) -> tuple[NDArray[np.float64], NDArray[np.float64]]: ...
def synth_info(
    params: NDArray[np.float64],
    crossed: bool,
    s_lo: float,
    s_hi: float,
    check_samples: int = 2048,
) -> tuple[str | None, bool, float, float, float, bool]: ...
def synth_slider_atlas_build(
    entries: int, harmonics: int = 8, samples: int = 64, threads: int = 1
) -> tuple[NDArray[np.float32], NDArray[np.float64], NDArray[np.uint64]]: ...
def synth_slider_frame(
    params: NDArray[np.float64], harmonics: int, samples: int
) -> NDArray[np.float64]: ...
def synth_slider_place(
    entry: NDArray[np.float64],
    curve: NDArray[np.float64],
    target: NDArray[np.float64],
    flip: bool,
) -> NDArray[np.float64]: ...
def synth_slider_residuals(
    params: NDArray[np.float64], targets: NDArray[np.float64], s: NDArray[np.float64]
) -> NDArray[np.float64]: ...
def synth_slider_errors(
    params: NDArray[np.float64],
    targets: NDArray[np.float64],
    samples: int = 256,
    exact: bool = False,
    closed: bool = True,
    threads: int = 1,
) -> tuple[NDArray[np.float64], NDArray[np.float64]]: ...
def synth_slider_info(
    params: NDArray[np.float64], s_lo: float, s_hi: float, check_samples: int = 2048
) -> tuple[str | None, bool, float, float, float, bool]: ...
