"""Every public name of 0.1 still imports, from the path 0.1 gave it; 0.1's pickles load.

``tests/data/api_0_1.txt`` lists 0.1's public names (``linkage.walker.Walker``, one a line);
:data:`REMOVED` the deprecated aliases removed on purpose since. The pickles under
``tests/data/pickles_0_1/`` were written by 0.1 (``make.py`` there): its classes' paths
(``linkage._fourbar.FourBar``, ``linkage.walker.Walker``, ...) must still resolve.
"""

from __future__ import annotations

import importlib
import pickle
from pathlib import Path

import numpy as np
import pytest

import linkage

DATA = Path(__file__).parent / "data"
NAMES = (DATA / "api_0_1.txt").read_text(encoding="utf-8").split()

# Deprecated aliases of 0.1, removed on purpose (issue 30): each with the name that replaced it.
REMOVED = {
    "linkage.ball_point": "linkage.inflection_circle",
    "linkage.geometry.ball_point": "linkage.geometry.inflection_circle",
    "linkage.forces.forces": "linkage.forces.joint_forces",
    "linkage.scene.OUTPUTS": "linkage.scene.REPORT_OUTPUTS",
    "linkage.walker.search_duty_factor": "linkage.gait_search.search_duty_factor",
    "linkage.walker.search_phases": "linkage.gait_search.search_phases",
}


def resolve(name: str) -> object:
    """The object at a dotted path: the longest importable module, then attributes."""
    parts = name.split(".")
    for k in range(len(parts), 0, -1):
        try:
            obj: object = importlib.import_module(".".join(parts[:k]))
        except ModuleNotFoundError:
            continue
        for attr in parts[k:]:
            obj = getattr(obj, attr)
        return obj
    raise ImportError(name)


def test_the_list_is_0_1s():
    assert len(NAMES) == 434 and NAMES[0] == "linkage"
    assert set(REMOVED) <= set(NAMES)


@pytest.mark.parametrize("name", [n for n in NAMES if n not in REMOVED])
def test_every_public_name_of_0_1_still_imports(name):
    resolve(name)


@pytest.mark.parametrize("name", sorted(REMOVED))
def test_the_removed_aliases_are_gone_and_their_replacements_are_there(name):
    with pytest.raises(AttributeError):
        resolve(name)
    resolve(REMOVED[name])


def pickletools_names(data: bytes) -> set[str]:
    """The module-level names a pickle refers to (its STACK_GLOBAL / GLOBAL opcodes' strings)."""
    import pickletools

    strings = [arg for op, arg, _ in pickletools.genops(data) if isinstance(arg, str)]
    return {s for s in strings if s.startswith("linkage")}


PICKLES = sorted((DATA / "pickles_0_1").glob("*.pickle"))


def test_there_are_pickles_of_0_1():
    assert {p.stem for p in PICKLES} >= {"fourbar", "sweep", "mechanism", "walker", "leg"}


@pytest.mark.parametrize("path", PICKLES, ids=lambda p: p.stem)
def test_a_pickle_of_0_1_loads(path):
    obj = pickle.loads(path.read_bytes())  # our own files, written by make.py
    # The classes (and the sweep's and mechanism's rebuilders) keep their 0.1 module, so a
    # pickle written now names the same paths as 0.1's.
    again = pickle.dumps(obj, protocol=4)
    assert pickle.loads(again).__class__ is obj.__class__
    old_paths = {line for line in pickletools_names(path.read_bytes())}
    assert pickletools_names(again) == old_paths
    if isinstance(obj, linkage.Sweep):
        fb = linkage.FourBar(ground=20, crank=10, coupler=25, rocker=25, point=(50, 0))
        new = fb.sweep(np.linspace(0, 2 * np.pi, 5))
        np.testing.assert_array_equal(obj.point, new.point)


def test_the_classes_keep_their_0_1_module():
    assert linkage.FourBar.__module__ == "linkage._fourbar"
    assert linkage.Sweep.__module__ == "linkage._sweep"
    assert linkage.Mechanism.__module__ == "linkage._mechanism"
    assert linkage.SliderCrank.__module__ == "linkage._slider_crank"
    assert linkage.Walker.__module__ == linkage.Leg.__module__ == "linkage.walker"
    from linkage import drive, forces, scene

    assert drive.Drive.__module__ == drive.ConstantSpeed.__module__ == "linkage.drive"
    assert forces.Forces.__module__ == "linkage.forces"
    assert scene.Scene.__module__ == scene.SceneError.__module__ == "linkage._schema"
