"""The string choices' ``Literal`` aliases (linkage._choices): the names the core takes, the
tuples read from them, and the public signatures that use them."""

from __future__ import annotations

import inspect
from typing import get_args

import pytest

import linkage
import linkage.drawing
from linkage import _choices, drive, synthesis, walker
from linkage._arrays import as_choice, assembly_named, choices
from linkage._sweep import OUTPUTS


@pytest.mark.parametrize(
    ("alias", "kind"),
    [
        (_choices.Assembly, "assembly"),
        (_choices.Side, "side"),
        (_choices.Reach, "reach"),
        (_choices.SweepMode, "mode"),
    ],
)
def test_the_aliases_of_the_core_choices_name_what_the_core_takes(alias, kind):
    assert get_args(alias) == choices(kind)


def test_the_motion_laws_alias_names_the_cores_laws():
    assert get_args(_choices.Law) == drive.LAWS


def test_the_python_choice_tuples_are_read_from_their_alias():
    assert OUTPUTS == get_args(_choices.Output) == linkage.OUTPUTS
    assert synthesis.KINDS == get_args(_choices.LinkageKind) == ("fourbar", "slider-crank")
    assert get_args(_choices.AtlasKind) == (*synthesis.KINDS, synthesis.ARCS, synthesis.SLIDER_ARCS)
    assert walker.PLANES == get_args(_choices.Plane) == ("sagittal", "horizontal")


def test_the_crossed_flag_names_the_crossed_assembly():
    assert (assembly_named(False), assembly_named(True)) == ("open", "crossed")
    fb = linkage.FourBar(ground=20, crank=10, coupler=25, rocker=25, assembly="crossed")
    assert assembly_named(fb.assembly == "crossed") == fb.assembly


def test_as_choice_returns_the_value_and_refuses_others():
    assert as_choice("slip", "objective", get_args(_choices.Objective)) == "slip"
    with pytest.raises(linkage.LinkageError, match="objective must be one of 'margin', 'slip'"):
        as_choice("speed", "objective", get_args(_choices.Objective))
    with pytest.raises(TypeError):
        as_choice(1, "objective", get_args(_choices.Objective))


@pytest.mark.parametrize(
    ("function", "parameter", "alias"),
    [
        (linkage.FourBar, "assembly", "Assembly"),
        (linkage.FourBar.uniform_sweep, "mode", "SweepMode"),
        (linkage.FourBar.sweep, "outputs", "Iterable[Output]"),
        (linkage.Mechanism.sweep, "outputs", "Iterable[Output]"),
        (linkage.Mechanism.dyad, "side", "Side"),
        (linkage.Mechanism.slider, "reach", "Reach"),
        (linkage.SliderCrank, "reach", "Reach"),
        (
            linkage.batch.sweep_fourbars,
            "assembly",
            "Assembly | Sequence[Assembly] | NDArray[np.str_]",
        ),
        (synthesis.path, "kind", "PathKind"),
        (synthesis.Atlas.build, "kind", "AtlasKind"),
        (synthesis.default_atlas, "kind", "AtlasKind"),
        (synthesis.function, "spacing", "Spacing"),
        (linkage.gait_search.search_phases, "objective", "Objective"),
        (linkage.gait_search.search_duty_factor, "objective", "Objective"),
        (linkage.Walker.search_phases, "objective", "Objective"),
        (linkage.Leg, "plane", "Plane"),
        (drive.motion_law, "name", "Law"),
        (drive.Segment, "law", "Law | None"),
        (linkage.drawing.walker_drawing, "view", "View"),
    ],
)
def test_public_signatures_say_the_choice(function, parameter, alias):
    # The modules use `from __future__ import annotations`: annotations are their source text.
    assert inspect.signature(function).parameters[parameter].annotation == alias


def test_the_messages_name_the_choices_of_their_alias():
    # The messages are the ones written out by hand before; the names now come from the alias.
    with pytest.raises(linkage.LinkageError, match=r"^spacing must be 'chebyshev' or 'uniform', "):
        synthesis.function(abs, (1, 2), (0, 1), (1, 2), spacing="random")
    walker = linkage.catalog.quadruped_hoecken()
    sim = walker.simulate([0.0, 1.0])
    with pytest.raises(linkage.LinkageError, match=r"^view must be 'side' or 'top', got 'front'"):
        linkage.drawing.walker_drawing(walker, sim, view="front")
    assert linkage.drawing.walker_drawing(walker, sim, view="top").legs


def test_the_public_choice_types_are_the_checked_ones() -> None:
    # linkage.Assembly etc. are the aliases whose names the tests above hold to the core's.
    for name in ("Assembly", "Output", "Reach", "Side"):
        assert getattr(linkage, name) is getattr(_choices, name), name
        assert name in linkage.__all__, name
