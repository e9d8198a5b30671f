"""The binding mirrors the core: `_core` submodules, the 0.1 flat names, typed assembly errors
and the core's constants (crates/linkage-py)."""

import importlib
import sys
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np
import pytest

import linkage
from linkage import _core

FLAT_NAMES = Path(__file__).parent.parent / "crates" / "linkage-py" / "flat_names.tsv"
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


def flat_names() -> list[tuple[str, str, str]]:
    rows = []
    for line in FLAT_NAMES.read_text(encoding="utf-8").splitlines():
        old, dotted = line.split("\t")
        module, name = dotted.split(".")
        rows.append((old, module, name))
    return rows


@pytest.mark.parametrize("name", SUBMODULES)
def test_each_submodule_imports_both_ways(name: str) -> None:
    by_import = importlib.import_module(f"linkage._core.{name}")
    by_from = getattr(__import__("linkage._core", fromlist=[name]), name)
    assert by_import is by_from is getattr(_core, name)
    assert sys.modules[f"linkage._core.{name}"] is by_import
    assert by_import.__name__ == f"linkage._core.{name}"
    assert by_import.__doc__


def test_each_old_flat_name_is_its_submodule_attribute() -> None:
    rows = flat_names()
    assert len({old for old, _, _ in rows}) == len(rows)
    for old, module, name in rows:
        assert module in SUBMODULES, module
        new = getattr(getattr(_core, module), name)
        assert getattr(_core, old) is new, old
        assert new.__module__ == f"linkage._core.{module}", old


def test_every_function_at_top_level_is_in_the_table() -> None:
    listed = {old for old, _, _ in flat_names()}
    functions = {
        n for n in dir(_core) if type(getattr(_core, n)).__name__ == "builtin_function_or_method"
    }
    # The shared helpers (memory wording) are top level by design.
    assert functions - {"size_text_of", "memory_message"} == listed


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


# The core's values (crates/linkage-core), read here from the source so that a change there
# that the binding did not follow fails.
CORE = Path(__file__).parent.parent / "crates" / "linkage-core" / "src"


def core_constant(name: str) -> str:
    for path in CORE.rglob("*.rs"):
        for line in path.read_text(encoding="utf-8").splitlines():
            if line.startswith(f"pub const {name}:"):
                return line.split("=", 1)[1].strip().rstrip(";")
    raise AssertionError(f"no pub const {name} in the core")


@pytest.mark.parametrize(
    ("module", "name", "value"),
    [
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
    ],
)
def test_constants_are_the_cores(module: str, name: str, value: object) -> None:
    got = getattr(getattr(_core, module), name)
    assert got == value
    assert getattr(_core, name) is got
    if name not in ("CAPACITY", "SLIDER_ARC_ENTRY_PARAMS", "FOUR_BARS", "MULTI_LOOP"):
        text = core_constant(name)
        if isinstance(value, (int, float)):
            assert type(value)(text.replace("_", "")) == value, text
        else:
            assert text.replace(" ", "").replace("[", "(").replace("]", ")") == str(
                tuple(value) if isinstance(value, list) else value
            ).replace(" ", ""), text
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


def test_typed_results_keep_the_old_shapes_for_the_flat_names() -> None:
    # 0.1 callers unpack tuples and index dicts; the flat names return the same objects.
    ratio, sign = _core.gear_train_simple([10, 20])
    train = _core.drive.simple_gear_train([10, 20])
    assert isinstance(train, _core.drive.GearRatio)
    assert (ratio, sign) == (train.ratio, train.sign) == train.astuple() == (0.5, -1)
    assert (len(train), train[0], train[-1]) == (2, 0.5, -1)
    found = _core.catalog.linkage("hart")
    mech, names, trace = _core.catalog_linkage("hart")
    assert isinstance(mech, _core.Mechanism)
    assert (names, trace) == (found.joint_names, found.trace)
    assert isinstance(found.mechanism, _core.Mechanism) and found[0] is found.mechanism
    with pytest.raises(IndexError):
        found[3]
    cam = _core.cam_geometry(np.linspace(0.0, 1.0, 3), np.zeros((3, 3)), 2.0)
    assert cam["pitch"] is cam.pitch
    with pytest.raises(KeyError):
        cam["nope"]
    run = _core.straight_run(np.array([[0.0, 0.0], [1.0, 0.0], [2.0, 0.0]]), 1e-9, False)
    assert run is not None and run["count"] == 3
    with pytest.raises(KeyError):
        run["lift"]  # only for a closed path, as the 0.1 dict
