"""The binding mirrors the core: `_core` submodules (the 0.1 flat names gone), typed assembly
errors and the core's constants (crates/linkage-py)."""

import ast
import importlib
import sys
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np
import pytest

import linkage
from linkage import _core

# The stubs beside the extension that is imported: the tree's, or the installed wheel's.
STUBS = Path(linkage.__file__).parent
SUBMODULES = (
    "numeric",
    "mechanism",
    "motion",
    "sweep",
    "linkages",
    "drive",
    "kinetostatics",
    "catalog",
    "walking",
    "synthesis",
)


# The 0.1 flat names of `_core` (functions, then the core constants), removed in 0.2: the
# package calls every one by its submodule.
OLD_FLAT_NAMES = (
    "reduce_angle",
    "degrees_of_freedom",
    "curvature_centres",
    "circumcentres",
    "straight_run",
    "sweep_mechanisms",
    "sweep_simd",
    "batch_sweep",
    "motion_law_names",
    "motion_law_eval",
    "program_eval",
    "program_discontinuities",
    "gear_train_simple",
    "gear_train_compound",
    "schedule_eval",
    "stance_schedule",
    "cam_geometry",
    "forces",
    "catalog_four_bar",
    "catalog_linkage",
    "catalog_names",
    "leg_gait",
    "four_bar_gaits",
    "gait_columns",
    "support_margins",
    "burmester_centre_point",
    "burmester_circle_point",
    "burmester_common_pole",
    "burmester_curve",
    "motion_candidates",
    "chebyshev_points",
    "function_generator",
    "synth_atlas_build",
    "synth_slider_atlas_build",
    "synth_arc_atlas_build",
    "synth_arc_frame",
    "synth_atlas_nearest",
    "synth_descriptors",
    "synth_frame",
    "synth_slider_frame",
    "synth_place",
    "synth_slider_place",
    "synth_residuals",
    "synth_slider_residuals",
    "synth_errors",
    "synth_slider_errors",
    "synth_info",
    "synth_slider_info",
    "synth_arc",
    "synth_curve_equation",
    "synth_slider_curve_equation",
    "polyline_distance",
    "polyline_distance_each",
    "FOUR_BARS",
    "MULTI_LOOP",
    "DEFAULT_TOGGLE_MARGIN",
    "MAX_TABLE",
    "CURVE_EQUATION_POINTS",
    "SLIDER_EQUATION_POINTS",
    "ENTRY_PARAMS",
    "SLIDER_ENTRY_PARAMS",
    "ARC_ENTRY_PARAMS",
    "SLIDER_ARC_ENTRY_PARAMS",
    "ARC_FRACTIONS",
    "LENGTH_RANGE",
    "PLACED_PARAMS",
    "SLIDER_PARAMS",
    "QUERY_VARIANTS",
    "MIN_CURVE_POINTS",
    "MAX_POSES",
    "FOOT_STARTS",
)

# `_core`'s own top level: the errors, the three pyclasses whose `__module__` is `linkage._core`,
# the shared items that are no folder's (joint capacity, rate margin, string choices, assembly
# sides, size and memory wording) and the submodules.
TOP_LEVEL = {
    "LinkageError",
    "AssemblyError",
    "Mechanism",
    "FourBar",
    "SliderCrank",
    "CAPACITY",
    "RATE_MARGIN",
    "CHOICES",
    "ASSEMBLY_SIDES",
    "size_text_of",
    "memory_message",
    *SUBMODULES,
}


def stub_all(stub: Path) -> set[str]:
    """The names a stub file's `__all__` lists, each checked to be defined or imported there."""
    tree = ast.parse(stub.read_text(encoding="utf-8"))
    listed: set[str] = set()
    defined: set[str] = set()
    for node in tree.body:
        if isinstance(node, ast.Assign) and any(
            isinstance(t, ast.Name) and t.id == "__all__" for t in node.targets
        ):
            listed = set(ast.literal_eval(node.value))
        elif isinstance(node, ast.AnnAssign) and isinstance(node.target, ast.Name):
            defined.add(node.target.id)
        elif isinstance(node, (ast.FunctionDef, ast.ClassDef)):
            defined.add(node.name)
        elif isinstance(node, ast.ImportFrom):
            defined.update(a.asname for a in node.names if a.asname == a.name)
    assert listed <= defined, (stub, listed - defined)
    return listed


def public(module: object) -> set[str]:
    return {n for n in dir(module) if not n.startswith("_")}


@pytest.mark.parametrize("name", SUBMODULES)
def test_each_submodule_imports_both_ways(name: str) -> None:
    by_import = importlib.import_module(f"linkage._core.{name}")
    by_from = getattr(__import__("linkage._core", fromlist=[name]), name)
    assert by_import is by_from is getattr(_core, name)
    assert sys.modules[f"linkage._core.{name}"] is by_import
    assert by_import.__name__ == f"linkage._core.{name}"
    assert by_import.__doc__


def test_the_old_flat_names_are_gone() -> None:
    assert len(set(OLD_FLAT_NAMES)) == len(OLD_FLAT_NAMES) == 71
    for old in OLD_FLAT_NAMES:
        assert not hasattr(_core, old), old


def test_the_top_level_is_what_its_stub_says() -> None:
    assert public(_core) == stub_all(STUBS / "_core.pyi") == TOP_LEVEL


@pytest.mark.parametrize("name", SUBMODULES)
def test_each_submodule_is_what_its_stub_says(name: str) -> None:
    module = getattr(_core, name)
    assert public(module) == stub_all(STUBS / "_core" / f"{name}.pyi"), name
    for attr in public(module):
        value = getattr(module, attr)
        if callable(value) and not isinstance(value, type):
            assert value.__module__ == f"linkage._core.{name}", attr


def test_classes_and_errors_stay_at_top_level() -> None:
    assert _core.mechanism.Mechanism is _core.Mechanism
    assert _core.linkages.FourBar is _core.FourBar
    assert _core.linkages.SliderCrank is _core.SliderCrank
    # Pickles name the class where 0.1 put it.
    assert _core.FourBar.__module__ == "linkage._core"
    assert issubclass(_core.AssemblyError, _core.LinkageError)
    for name in SUBMODULES:
        assert not hasattr(getattr(_core, name), "AssemblyError")


@pytest.mark.parametrize(
    ("obj", "gap"),
    [
        (lambda: linkage.FourBar(ground=100, crank=1, coupler=2, rocker=3, point=(5, 0)), 94.0),
        (lambda: linkage.SliderCrank(crank=10, coupler=3, offset=60, point=(12, 9)), 47.0),
    ],
)
def test_assembly_error_carries_joint_and_gap(obj: Callable[[], Any], gap: float) -> None:
    # The core's error, as the binding raises it: the joint's index.
    core = obj()._core
    with pytest.raises(_core.AssemblyError) as raw:
        core.circuit(11)
    assert raw.value.joint == 3
    assert raw.value.gap == pytest.approx(gap)
    assert raw.value.reason == str(raw.value).removeprefix("joint 3 ")
    # The Python class names it.
    with pytest.raises(linkage.AssemblyError) as named:
        obj().circuit(11)
    assert named.value.joint == "B"
    assert named.value.gap == raw.value.gap
    assert str(named.value) == f"joint B {raw.value.reason}"


def test_coincident_joints_have_no_gap() -> None:
    m = _core.Mechanism()
    a = m.fixed(0.0, 0.0)
    with pytest.raises(_core.AssemblyError) as info:
        m.dyad(a, a, 1.0, 1.0, "left")
    assert info.value.joint == 1
    assert info.value.gap is None
    assert str(info.value) == f"joint 1 {info.value.reason}"


def test_an_assembly_error_raised_from_python_has_none_attributes() -> None:
    e = _core.AssemblyError("made in Python")
    assert (e.joint, e.gap, e.reason) == (None, None, None)


# The core's constants as the binding exports them (tests/test_binding_constants_source.py
# checks each against the core's source, in the tree).
CONSTANTS = [
    ("synthesis", "CURVE_EQUATION_POINTS", 16),
    ("synthesis", "SLIDER_EQUATION_POINTS", 13),
    ("synthesis", "ENTRY_PARAMS", 6),
    ("synthesis", "SLIDER_ENTRY_PARAMS", 4),
    ("synthesis", "ARC_ENTRY_PARAMS", 8),
    ("synthesis", "SLIDER_ARC_ENTRY_PARAMS", 6),
    ("synthesis", "PLACED_PARAMS", 9),
    ("synthesis", "SLIDER_PARAMS", 8),
    ("synthesis", "LENGTH_RANGE", (0.2, 5.0)),
    ("synthesis", "ARC_FRACTIONS", [0.125, 0.1875, 0.25, 0.375, 0.5, 0.625, 0.75]),
    ("sweep", "DEFAULT_TOGGLE_MARGIN", 0.2),
    ("linkages", "MAX_TABLE", 256),
    ("mechanism", "CAPACITY", 64),
    ("catalog", "FOUR_BARS", list(_core.catalog.names()[0])),
    ("catalog", "MULTI_LOOP", list(_core.catalog.names()[1])),
]


@pytest.mark.parametrize(("module", "name", "value"), CONSTANTS)
def test_constants_are_the_cores(module: str, name: str, value: object) -> None:
    got = getattr(getattr(_core, module), name)
    assert got == value
    if name == "CAPACITY":
        assert _core.CAPACITY is got
    else:
        assert not hasattr(_core, name)
    assert _core.synthesis.SLIDER_ARC_ENTRY_PARAMS == _core.synthesis.SLIDER_ENTRY_PARAMS + 2


def test_one_size_wording() -> None:
    from linkage._shared.arrays import _bytes, check_memory

    assert _core.size_text_of(3 << 30) == "3 GiB (3221225472 bytes)"
    assert _core.size_text_of(1023) == "1023 bytes"
    assert _core.size_text_of(1 << 130) == f"1180591620717411303424 EiB ({1 << 130} bytes)"
    assert (
        _bytes(12_345_678_901)
        == _core.size_text_of(12_345_678_901)
        == "11.5 GiB (12345678901 bytes)"
    )
    with pytest.raises(
        MemoryError, match=r"^a test needs 1 EiB \(1152921504606846976 bytes\), more than"
    ):
        check_memory(1 << 60, "a test")


def test_results_with_a_shape_are_typed() -> None:

    path = np.array([[0.0, 0.0], [1.0, 0.0], [2.0, 0.0], [3.0, 0.0]])
    run = _core.motion.straight_run(path, 1e-9, False)
    assert isinstance(run, _core.motion.StraightRun)
    assert (run.start, run.count, run.length) == (0, 4, 3.0)
    assert (run.lift, run.mean_speed, run.speed_variation) == (None, None, None)
    with pytest.raises(AttributeError):
        run.count = 1  # type: ignore[misc]
    phi = np.linspace(0.0, 1.0, 5)
    cam = _core.drive.cam_geometry(phi, np.zeros((5, 3)), 2.0)
    assert isinstance(cam, _core.drive.CamGeometry)
    assert cam.pitch.shape == cam.profile.shape == (5, 2)
    assert cam.pressure_angle.shape == cam.pitch_radius.shape == cam.profile_radius.shape == (5,)
    assert _core.drive.CamGeometry.__doc__ and _core.motion.StraightRun.length.__doc__


def test_typed_results_keep_the_old_shapes() -> None:
    # 0.1 callers unpack tuples and index dicts; the typed results still allow both.
    ratio, sign = _core.drive.simple_gear_train([10, 20])
    train = _core.drive.simple_gear_train([10, 20])
    assert isinstance(train, _core.drive.GearRatio)
    assert (ratio, sign) == (train.ratio, train.sign) == train.astuple() == (0.5, -1)
    assert (len(train), train[0], train[-1]) == (2, 0.5, -1)
    found = _core.catalog.linkage("hart")
    mech, names, trace = _core.catalog.linkage("hart")
    assert isinstance(mech, _core.Mechanism)
    assert (names, trace) == (found.joint_names, found.trace)
    assert isinstance(found.mechanism, _core.Mechanism) and found[0] is found.mechanism
    with pytest.raises(IndexError):
        found[3]
    cam = _core.drive.cam_geometry(np.linspace(0.0, 1.0, 3), np.zeros((3, 3)), 2.0)
    assert cam["pitch"] is cam.pitch
    with pytest.raises(KeyError):
        cam["nope"]
    run = _core.motion.straight_run(np.array([[0.0, 0.0], [1.0, 0.0], [2.0, 0.0]]), 1e-9, False)
    assert run is not None and run["count"] == 3
    with pytest.raises(KeyError):
        run["lift"]  # only for a closed path, as the 0.1 dict
