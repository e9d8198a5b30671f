"""The scene schema and its parser: what a scene file may hold, checked key by key.

This module is private; :mod:`linkage.scene` is the public one. It holds the schema (the
:class:`Scene`, the allowed keys of each section and the ranges of their values, :data:`MEMORY_CAP`
and the other limits) and :func:`parse_only`, which reads a scene's TOML and checks every key's
type and range and the references between sections, with the file, line and key in each message.
It does not build the study: :func:`linkage.scene.parse` and :func:`linkage.scene.load` call it and
then :func:`linkage.build.validate`, which builds the study once, so that whatever
:func:`linkage.runner.run` would reject they reject too.

The split keeps the imports one way: :mod:`linkage.build` (and :mod:`linkage.figures`,
:mod:`linkage.runner`) import this module, and :mod:`linkage.scene` imports :mod:`linkage.build`.
"""

from __future__ import annotations

import difflib
import math
import re
import sys
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, get_args

from linkage import catalog
from linkage._core import LinkageError
from linkage._shared.arrays import choices, one_of
from linkage._shared.choices import PathKind
from linkage._shared.files import TooLarge, read_bytes
from linkage._shared.toml_lines import MAX_NESTING, Locator, NotText, decode, label, nesting
from linkage.drives.drive import LAWS
from linkage.kinematics.mechanism import JOINT_KINDS as _JOINT_KINDS
from linkage.synthesis import limits as _synthesis_limits
from linkage.walking.walker import GAITS

__all__ = [
    "ANGLE_MAX_DEG",
    "CAM",
    "CAM_SEGMENT",
    "COORD_MAX",
    "CYCLES_MAX",
    "DEFAULT_SCENE",
    "DRIVE",
    "DRIVE_KINDS",
    "FILE_MAX",
    "FORMS",
    "JOINT",
    "JOINT_KINDS",
    "LEG",
    "LENGTH_RANGE",
    "LOAD",
    "MASS",
    "MASS_MAX",
    "MECHANISM",
    "MECHANISM_OUTPUTS",
    "MEMORY_CAP",
    "NAME",
    "NUMBERS",
    "PATH_KINDS",
    "POINTS_MAX",
    "REPORT_OUTPUTS",
    "SAMPLES_MAX",
    "SCALE_RANGE",
    "SEED_MAX",
    "SEGMENT",
    "SPEED_RANGE",
    "STUDIES",
    "SYNTHESIS",
    "SYNTHESIS_OUTPUTS",
    "SYNTHESIS_REFINE_MAX",
    "SYNTHESIS_TOP_MAX",
    "TEETH_MAX",
    "TIME_RANGE",
    "TOP",
    "WALKER",
    "WALKER_MODELS",
    "WALKER_OUTPUTS",
    "Scene",
    "SceneError",
    "base_folder",
    "parse_only",
    "read_text",
]

if sys.version_info >= (3, 11):  # pragma: no cover - depends on the interpreter
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib

REPORT_OUTPUTS = (
    "trajectory",
    "velocity",
    "acceleration",
    "instant_centres",
    "curvature",
    "straightness",
    "torque",
    "cam",
    "gait",
    "stability",
    "slip",
    "animation",
    "cad",
    "synthesis",
)

"""What a scene's ``outputs`` can ask for in its report (not :data:`linkage.OUTPUTS`, the
arrays a sweep computes). ``cad`` writes the mechanism at its first pose and every traced path
as ``mechanism.dxf`` and ``mechanism.svg`` (of a ``[synthesis]`` scene: the best candidate);
``synthesis`` is the search of a ``[synthesis]`` scene and its report."""

# `linkage run` with no scene: thesis 1's quadruped under its drive (also
# examples/quadruped_hoecken.toml, kept equal by a test).
DEFAULT_SCENE = """
name = "quadruped-hoecken"
description = "Thesis 1 quadruped, Hoecken legs, 50 rpm motor through 18-15-14 gears"
units = "mm"
outputs = ["trajectory", "gait", "stability", "slip", "animation"]

[walker]
model = "quadruped_hoecken"

[drive]
kind = "constant"
rpm = 50.0
gears = [18, 15, 14]
cycles = 2
samples = 721
"""

WALKER_OUTPUTS = {"gait", "stability", "slip"}
MECHANISM_OUTPUTS = {
    "velocity",
    "acceleration",
    "instant_centres",
    "curvature",
    "straightness",
    "torque",
}
SYNTHESIS_OUTPUTS = ("synthesis", "cad")
"""The outputs of a ``[synthesis]`` scene (``synthesis`` is its default and required)."""
STUDIES = ("mechanism", "walker", "synthesis")
"""The sections of which a scene has exactly one: what it studies."""


# Ranges of the numbers a scene may hold. Outside them a study means nothing (a length of
# 1e308 overflows the first squared distance, one of 5e-324 is below every tolerance), so the
# scene is refused with the range in the message instead of computing garbage.
LENGTH_RANGE = (1e-9, 1e9)
"""Lengths (link lengths, radii, pads, tolerances), in the scene's units."""
COORD_MAX = 1e9
"""Largest magnitude of a coordinate, offset, rise, force or gravity component."""
ANGLE_MAX_DEG = 1e6
"""Largest magnitude of an angle in degrees (phases, starts, rises)."""
TIME_RANGE = (1e-9, 1e9)
"""Durations (s)."""
SPEED_RANGE = (1e-6, 1e9)
"""Magnitude of a motor speed (rpm or rad/s), a crank speed or a foot speed."""
SCALE_RANGE = (1e-6, 1e6)
"""A catalogue linkage's scale factor."""
TEETH_MAX = 100_000
"""Most teeth on one gear."""
MASS_MAX = 1e15
"""Largest mass or moment of inertia."""
CYCLES_MAX = 1e6
"""Most cycles (crank turns or program periods) in one run."""
SAMPLES_MAX = 10**9
"""Most samples in one run (the memory estimate usually refuses far fewer)."""
MEMORY_CAP = 2 * 1024**3
"""Largest estimated memory of a run, in bytes (2 GiB); see
:func:`linkage.build.estimate_memory`."""
FILE_MAX = 1 << 20
"""Largest scene file, in bytes (1 MiB; a scene is a few hundred bytes)."""
SYNTHESIS_TOP_MAX = _synthesis_limits.SYNTHESIS_TOP_MAX
"""Most candidates a ``[synthesis]`` scene may ask for (``top``)."""
SYNTHESIS_REFINE_MAX = _synthesis_limits.SYNTHESIS_REFINE_MAX
"""Most atlas matches a ``[synthesis]`` scene may ask to refine (``refine``; the search's time
grows with it)."""
SEED_MAX = 2**32 - 1
"""Largest random seed of the global search."""
POINTS_MAX = _synthesis_limits.POINTS_MAX
"""Most target points of a ``[synthesis]`` scene (each costs a distance per candidate)."""
NAME = re.compile(r"[a-z0-9][a-z0-9_-]{0,63}")
"""A scene name: a slug, the report folder's name (no '.', '/', spaces or capitals)."""


class SceneError(LinkageError):
    """A malformed or contradictory scene file; the message names the file, line and key."""


@dataclass
class Scene:
    """A validated scene."""

    name: str
    path: Path | None
    outputs: tuple[str, ...]
    mechanism: dict[str, Any] | None = None
    walker: dict[str, Any] | None = None
    drive: dict[str, Any] = field(default_factory=dict)
    masses: dict[str, dict[str, Any]] | None = None
    gravity: tuple[float, float] = (0.0, -9.81)
    loads: list[dict[str, Any]] = field(default_factory=list)
    cam: dict[str, Any] | None = None
    synthesis: dict[str, Any] | None = None
    """The ``[synthesis]`` section as given (points, constraints), or None."""
    description: str = ""
    units: str = ""
    """Length unit label for the report (e.g. "mm"); lengths are used as given."""
    locator: Locator | None = field(default=None, compare=False, repr=False)
    """Where the scene's keys are in its text (None for a scene built in code)."""

    def wants(self, *names: str) -> bool:
        """Whether any of ``names`` is among the outputs.

        Examples
        --------
        >>> from linkage.scene import Scene
        >>> scene = Scene("leg", None, ("trajectory", "velocity"))
        >>> scene.wants("torque", "velocity"), scene.wants("torque"), scene.wants()
        (True, False, False)
        """
        return any(n in self.outputs for n in names)

    def error(self, path: Sequence[str | int], key: str, problem: str) -> SceneError:
        r"""Return a :class:`SceneError` for ``key`` under ``path`` (section names and indices).

        It is located in the scene's file when the scene came from one.

        Examples
        --------
        >>> from linkage.scene import Scene, parse
        >>> Scene("leg", None, ()).error(["drive"], "rpm", "must be positive")
        SceneError('[drive] rpm: must be positive')
        >>> text = 'outputs = ["trajectory"]\n[mechanism]\ncatalog = "hoecken"\n'
        >>> scene = parse(text + '[drive]\nkind = "constant"\nrpm = 50.0\n')
        >>> str(scene.error(["mechanism"], "catalog", "not this one"))
        '<scene>:3: [mechanism] catalog: not this one'
        """
        if self.locator is not None:
            return SceneError(self.locator.message(path, key, problem))
        return SceneError(f"{label(path)}{key}: {problem}")


# Allowed keys per section and the kind of each value: "str", "bool", "int" (samples), "list",
# "table", "tables", "pair" (two coordinates), or a number kind of NUMBERS.
NUMBERS: dict[str, tuple[float, float, str]] = {
    # kind: (low, high, how): "positive" (low ≤ x ≤ high), "signed" (|x| ≤ high),
    # "nonzero" (low ≤ |x| ≤ high), "nonneg" (0 ≤ x ≤ high), "open" (low < x < high).
    "length": (*LENGTH_RANGE, "positive"),
    "coord": (0.0, COORD_MAX, "signed"),
    "angle": (0.0, ANGLE_MAX_DEG, "signed"),
    "angle_span": (1e-9, ANGLE_MAX_DEG, "positive"),
    "time": (*TIME_RANGE, "positive"),
    "speed": (*SPEED_RANGE, "nonzero"),
    "foot_speed": (*SPEED_RANGE, "positive"),
    "scale": (*SCALE_RANGE, "positive"),
    "mass": (0.0, MASS_MAX, "nonneg"),
    "pad": (0.0, LENGTH_RANGE[1], "nonneg"),
    "fraction": (0.0, 1.0, "open"),
    "cycles": (1e-6, CYCLES_MAX, "positive"),
    "pressure": (0.0, 90.0, "open"),
    "transmission": (0.0, 90.0, "nonneg"),
}
TOP = {
    "name": "str",
    "units": "str",
    "description": "str",
    "outputs": "list",
    "mechanism": "table",
    "walker": "table",
    "drive": "table",
    "masses": "table",
    "gravity": "pair",
    "loads": "tables",
    "cam": "table",
    "synthesis": "table",
}
MECHANISM = {
    "catalog": "str",
    "scale": "scale",
    "ground": "length",
    "crank": "length",
    "coupler": "length",
    "rocker": "length",
    "point": "pair",
    "assembly": "str",
    "trace": "str",
    "joints": "tables",
    "reference": "points",
}
FORMS = {
    "catalog": ("catalog", "scale"),
    "ground": ("ground", "crank", "coupler", "rocker", "point", "assembly"),
    "joints": ("joints", "trace"),
}
"""The keys of each way of giving a mechanism."""
JOINT = {
    "name": "str",
    "kind": "str",
    "at": "pair",
    "centre": "str",
    "radius": "length",
    "phase_deg": "angle",
    "p1": "str",
    "p2": "str",
    "r1": "length",
    "r2": "length",
    "side": "str",
    "pivot": "str",
    "r": "length",
    "origin": "str",
    "direction": "pair",
    "link": "list",
    "angle_deg": "angle",
    "reach": "str",
    "on": "list",
    "along": "coord",
    "left": "coord",
}
JOINT_KINDS = _JOINT_KINDS
"""Each joint kind's required and optional keys (besides name and kind): the mechanism's one
registry (:class:`linkage._mechanism.JointKind`)."""
WALKER = {
    "model": "str",
    "legs": "tables",
    "gait": "str",
    "phases_deg": "list",
    "pad": "pad",
    "cg": "pair",
    "ground_tol": "length",
}
WALKER_MODELS = tuple(catalog.WALKERS)
LEG = {
    "name": "str",
    "catalog": "str",
    "scale": "scale",
    "scene": "str",
    "mount": "list",
    "phase_deg": "angle",
    "plane": "str",
    "mirror": "bool",
    "foot_offset": "pair",
    "pad": "pad",
    "lift": "tables",
}
DRIVE = {
    "kind": "str",
    "rpm": "speed",
    "omega": "speed",
    "gears": "list",
    "start_deg": "angle",
    "segments": "tables",
    "foot_speed": "foot_speed",
    "duty_factor": "fraction",
    "duration": "time",
    "cycles": "cycles",
    "samples": "int",
}
SEGMENT = {"duration": "time", "rise_deg": "angle", "law": "str"}
MASS = {"mass": "mass", "centre": "pair", "inertia": "mass"}
LOAD = {"link": "str", "joint": "str", "force": "pair", "torque": "coord"}
CAM = {
    "base_radius": "length",
    "roller_radius": "length",
    "offset": "coord",
    "pressure_limit_deg": "pressure",
    "segments": "tables",
}
CAM_SEGMENT = {"duration_deg": "angle_span", "rise": "coord", "law": "str"}
SYNTHESIS = {
    "points": "points",
    "kind": "str",
    "closed": "bool",
    "top": "int",
    "refine": "int",
    "full_turn": "bool",
    "min_transmission_deg": "transmission",
    "lengths": "list",
    "pivots": "list",
    "tol": "fraction",
    "accept": "length",
    "seed": "int",
    "atlas": "str",
}
"""Keys of ``[synthesis]``: the target (a CSV file relative to the scene's folder, or inline
``[[x, y], …]``), the linkage sought (``"fourbar"``, ``"slider-crank"`` or ``"any"``), whether it
is closed, how many candidates, how many atlas matches are refined, the constraints, the global
search's tolerance (of the target's size) and seed, and an atlas folder (relative to the
scene's folder; default: the one built once into the cache folder)."""
PATH_KINDS: tuple[str, ...] = tuple(k for a in get_args(PathKind) for k in get_args(a) or (a,))
"""The linkages a ``[synthesis]`` scene may seek (its ``kind``): ``fourbar`` (the default),
``slider-crank`` or ``any`` (both, ranked as one list)."""
DRIVE_KINDS = {
    "constant": {"rpm", "omega", "gears"},
    "program": {"start_deg", "segments", "gears"},
    "schedule": {"foot_speed", "duty_factor"},
}


def read_text(path: Path) -> str:
    """Return the text of the scene file ``path``, refusing what cannot be a scene.

    Raises
    ------
    SceneError
        With ``file: problem`` (or ``file:line: problem``) for a file that cannot be read, is
        larger than :data:`FILE_MAX` or is not text.
    """
    try:
        data = read_bytes(path, FILE_MAX, "scene", pipe=True)
    except TooLarge:
        raise SceneError(f"{path}: not a scene: larger than {FILE_MAX // 1024} KiB") from None
    except LinkageError as exc:
        raise SceneError(str(exc)) from None
    try:
        return decode(data)
    except NotText as exc:
        raise SceneError(f"{path}:{exc.line}: {exc.problem}") from None


def parse_only(text: str, path: Path | None = None, name: str | None = None) -> Scene:
    """Check scene ``text`` against the schema and return the scene, without building it.

    Every key's type and range and the references between sections are checked; what only
    building the study finds (a linkage that does not assemble, a run over the memory cap, a
    missing points file) is not: :func:`linkage.scene.parse` adds that.

    ``path`` names it in messages, and a ``[synthesis]`` section's files are relative to its folder
    — else to the working directory; ``name`` is the name when the text gives none.

    Raises
    ------
    SceneError
        With ``file:line: [section] key: problem`` for the first problem found.
    """
    where = Locator(text, str(path) if path else "<scene>")
    deep = nesting(text)
    if deep is not None:
        raise SceneError(
            f"{where.file}:{deep}: not a scene: brackets nested more than {MAX_NESTING} deep"
        )
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        m = re.search(r"line (\d+)", str(exc))
        n = (
            m.group(1)
            if m
            else (str(max(1, len(where.lines))) if "end of document" in str(exc) else "1")
        )
        raise SceneError(f"{where.file}:{n}: not valid TOML: {exc}") from None
    except RecursionError:  # pragma: no cover - the nesting check comes first
        raise SceneError(f"{where.file}:1: not a scene: nested too deep") from None
    except ValueError:  # an integer literal longer than Python converts
        n = next((i + 1 for i, line in enumerate(where.lines) if re.search(r"\d{1000}", line)), 1)
        raise SceneError(
            f"{where.file}:{n}: not a scene: a number of more than "
            f"{sys.get_int_max_str_digits()} digits"
        ) from None
    scene = Scene(name="scene", path=path, outputs=(), locator=where)
    _keys(data, TOP, scene, ())
    studies = [k for k in STUDIES if k in data]
    if len(studies) != 1:
        raise scene.error(
            (),
            studies[0] if studies else "mechanism",
            "give exactly one of [mechanism], [walker] or [synthesis]",
        )
    scene.outputs = _outputs(data, scene, "synthesis" in data)
    has_mech = "mechanism" in data
    scene.name = _name(data, scene, name, path)
    scene.description = str(data.get("description", ""))
    scene.units = str(data.get("units", ""))
    if len(scene.units) > 32 or not scene.units.isprintable():
        raise scene.error(
            (), "units", f"must be a short unit label such as 'mm', got {scene.units!r}"
        )
    if len(scene.description) > 4000:
        raise scene.error((), "description", "must be at most 4000 characters")
    outputs = scene.outputs
    if "synthesis" in data:
        return _synthesis_scene(data, scene)
    if "synthesis" in outputs:
        raise scene.error(
            (),
            "outputs",
            "'synthesis' needs a [synthesis] section (the target points to find a four-bar for)",
        )
    if has_mech:
        scene.mechanism = _mechanism(data["mechanism"], scene)
        bad = sorted(set(outputs) & WALKER_OUTPUTS)
        if bad:
            raise scene.error((), "outputs", f"{bad} need a [walker], not a [mechanism]")
    else:
        scene.walker = _walker(data["walker"], scene)
        bad = sorted(set(outputs) & MECHANISM_OUTPUTS)
        if bad:
            raise scene.error(
                (), "outputs", f"{bad} need a [mechanism]; a walker reports gait, stability, slip"
            )
        for key in ("masses", "loads"):
            if key in data:
                raise scene.error(
                    (), key, "applies to a [mechanism] (for its torque), not to a [walker]"
                )
    if "drive" not in data:
        raise scene.error(
            (), "drive", 'missing: a [drive] section (kind = "constant", "program" or "schedule")'
        )
    scene.drive = _drive(data["drive"], scene)
    if "gravity" in data:
        scene.gravity = _pair(data["gravity"], scene, (), "gravity")
    if "masses" in data:
        scene.masses = {}
        for link, spec in data["masses"].items():
            if not isinstance(spec, Mapping):
                raise scene.error(
                    ("masses",),
                    link,
                    "must be a table {mass = ..., centre = [along, left], inertia = ...}",
                )
            _keys(spec, MASS, scene, ("masses", link))
            if "mass" not in spec:
                raise scene.error(("masses", link), "mass", "missing")
            scene.masses[link] = dict(spec)
    for k, ld in enumerate(data.get("loads", [])):
        _keys(ld, LOAD, scene, ("loads", k))
        for req in ("link", "joint", "force"):
            if req not in ld:
                raise scene.error(("loads", k), req, "missing")
        scene.loads.append(dict(ld))
    if "torque" in outputs and scene.masses is None:
        raise scene.error(
            (),
            "outputs",
            "'torque' needs link masses: add a [masses] section (mass = 0 for a massless link)",
        )
    if "cam" in data:
        scene.cam = _cam(data["cam"], scene)
    if "cam" in outputs and scene.cam is None:
        raise scene.error((), "outputs", "'cam' needs a [cam] section")
    return scene


# -- sections --------------------------------------------------------------------------------


def _outputs(data: Mapping[str, Any], scene: Scene, synthesis: bool) -> tuple[str, ...]:
    outputs = data.get("outputs")
    if outputs is None and synthesis:
        return ("synthesis",)
    if outputs is None:
        raise scene.error(
            (), "outputs", 'missing: list what to compute, e.g. outputs = ["trajectory"]'
        )
    if not outputs:
        raise scene.error((), "outputs", 'is empty: list what to compute, e.g. ["trajectory"]')
    seen: list[str] = []
    for o in outputs:
        if not isinstance(o, str):
            raise scene.error((), "outputs", f"entries must be names, got {o!r}")
        if o not in REPORT_OUTPUTS:
            raise scene.error(
                (), "outputs", f"unknown output {o!r}{_did_you_mean(o, REPORT_OUTPUTS)}"
            )
        if o in seen:
            raise scene.error((), "outputs", f"lists {o!r} twice")
        seen.append(o)
    return tuple(seen)


def _name(data: Mapping[str, Any], scene: Scene, name: str | None, path: Path | None) -> str:
    if "name" in data:
        given = data["name"]
        if not NAME.fullmatch(given):
            raise scene.error(
                (),
                "name",
                "must be a slug of 1 to 64 lower-case letters, digits, '-' or '_', starting "
                f"with a letter or digit (it names the report folder), got {_show(given)}",
            )
        return str(given)
    if name is not None:
        return name
    # No name: the file's stem as a slug ("My Scene.toml" → "my-scene").
    stem = re.sub(r"[^a-z0-9_-]+", "-", path.stem.lower()).strip("-_") if path else ""
    return stem[:64] if stem and NAME.fullmatch(stem[:64]) else "scene"


def _mechanism(m: Mapping[str, Any], scene: Scene) -> dict[str, Any]:
    sec = ("mechanism",)
    _keys(m, MECHANISM, scene, sec)
    forms = [k for k in FORMS if k in m]
    if len(forms) != 1:
        raise scene.error(
            sec,
            forms[1] if len(forms) > 1 else "catalog",
            'give exactly one of catalog = "name", a four-bar (ground, crank, coupler, rocker) '
            "or [[mechanism.joints]]",
        )
    form = forms[0]
    if "reference" in m:
        _points(m["reference"], scene, sec, "reference")
    for k in m:
        if k not in FORMS[form] and k != "reference":
            what = {"catalog": "a catalogue linkage", "ground": "a four-bar", "joints": "joints"}
            owner = next(f for f, keys in FORMS.items() if k in keys)
            raise scene.error(
                sec, k, f"belongs to {what[owner]}, not to a mechanism given by {form!r}"
            )
    if form == "catalog":
        if m["catalog"] not in catalog.names():
            raise scene.error(
                sec,
                "catalog",
                f"unknown catalogue linkage {m['catalog']!r}"
                + _did_you_mean(m["catalog"], catalog.names()),
            )
        if "scale" in m and m["catalog"] not in catalog.FOUR_BARS:
            raise scene.error(
                sec, "scale", f"only catalogue four-bars can be scaled, not {m['catalog']!r}"
            )
    elif form == "ground":
        for k in ("crank", "coupler", "rocker"):
            if k not in m:
                raise scene.error(
                    sec, k, "missing (a four-bar needs ground, crank, coupler, rocker)"
                )
        if m.get("assembly", "open") not in choices("assembly"):
            raise scene.error(
                sec, "assembly", f"must be {one_of('assembly')}, got {m['assembly']!r}"
            )
    else:
        _joints(m["joints"], m.get("trace"), scene)
    return dict(m)


def _joints(joints: Sequence[Mapping[str, Any]], trace: Any, scene: Scene) -> None:
    if not joints:
        raise scene.error(("mechanism",), "joints", "is empty: list the joints in build order")
    names: list[str] = []
    crank: str | None = None
    for idx, j in enumerate(joints):
        jp = ("mechanism", "joints", idx)
        _keys(j, JOINT, scene, jp)
        for req in ("name", "kind"):
            if req not in j:
                raise scene.error(jp, req, "missing")
        if not j["name"] or not j["name"].isprintable() or len(j["name"]) > 64:
            raise scene.error(jp, "name", f"must be a short printable name, got {j['name']!r}")
        if j["name"] in names:
            raise scene.error(jp, "name", f"joint {j['name']!r} is defined twice")
        kind = j["kind"]
        if kind not in JOINT_KINDS:
            raise scene.error(
                jp, "kind", f"unknown kind {kind!r}{_did_you_mean(kind, JOINT_KINDS)}"
            )
        need, optional = JOINT_KINDS[kind].required, JOINT_KINDS[kind].optional
        for req in need:
            if req not in j:
                raise scene.error(jp, req, f"missing (a {kind} needs {', '.join(need)})")
        for k in j:
            if k not in ("name", "kind", *need, *optional):
                raise scene.error(jp, k, f"does not apply to a {kind} joint")
        for ref in ("centre", "p1", "p2", "pivot", "origin"):
            if ref in j and j[ref] not in names:
                raise scene.error(
                    jp,
                    ref,
                    f"unknown joint {j[ref]!r} (defined before it: {', '.join(names) or 'none'})",
                )
        if kind == "crank":
            if crank is not None:
                raise scene.error(
                    jp,
                    "kind",
                    f"a second crank ({crank!r} is the crank); a mechanism has exactly one driver",
                )
            crank = j["name"]
        if kind == "dyad":
            if j["p1"] == j["p2"]:
                raise scene.error(jp, "p2", f"must differ from p1 (both {j['p1']!r})")
            if j.get("side", "left") not in choices("side"):
                raise scene.error(jp, "side", f"must be {one_of('side')}, got {j['side']!r}")
        if kind == "slider":
            _slider_joint(j, names, scene, jp)
        if kind == "point":
            _joint_pair(j, "on", names, scene, jp)
        names.append(j["name"])
    if crank is None:
        raise scene.error(
            ("mechanism",), "joints", 'no crank: one joint must be kind = "crank" (the driver)'
        )
    if trace is not None and trace not in names:
        raise scene.error(
            ("mechanism",),
            "trace",
            f"unknown joint {trace!r}{_did_you_mean(trace, names)} (joints: {', '.join(names)})",
        )


def _slider_joint(
    j: Mapping[str, Any], names: list[str], scene: Scene, jp: tuple[Any, ...]
) -> None:
    """Check a slider joint's line (a fixed ``direction`` or a carrying ``link``) and reach."""
    if ("direction" in j) == ("link" in j):
        raise scene.error(
            jp,
            "direction",
            "give exactly one of direction = [dx, dy] (a fixed line) and link = [from, to] "
            "(a line carried by that link)",
        )
    if "direction" in j:
        if "angle_deg" in j:
            raise scene.error(
                jp, "angle_deg", "turns a line carried by a link: give link = [from, to]"
            )
        dx, dy = j["direction"]
        if dx == 0 and dy == 0:
            raise scene.error(jp, "direction", "must not be zero: the slider's line direction")
    else:
        _joint_pair(j, "link", names, scene, jp)
    if j.get("reach", "ahead") not in choices("reach"):
        raise scene.error(jp, "reach", f"must be {one_of('reach')}, got {j['reach']!r}")


def _joint_pair(
    j: Mapping[str, Any], key: str, names: list[str], scene: Scene, jp: tuple[Any, ...]
) -> None:
    """Check ``j[key]`` names two different joints defined before ``j`` (a link: from, to)."""
    pair = j[key]
    if len(pair) != 2 or not all(isinstance(v, str) for v in pair):
        raise scene.error(jp, key, f"must be two joint names [from, to], got {pair!r}")
    for v in pair:
        if v not in names:
            raise scene.error(
                jp, key, f"unknown joint {v!r} (defined before it: {', '.join(names) or 'none'})"
            )
    if pair[0] == pair[1]:
        raise scene.error(jp, key, f"needs two different joints, got {pair!r}")


def _walker(w: Mapping[str, Any], scene: Scene) -> dict[str, Any]:
    sec = ("walker",)
    _keys(w, WALKER, scene, sec)
    if ("model" in w) == ("legs" in w):
        raise scene.error(
            sec, "model", f"give a model ({', '.join(WALKER_MODELS)}) or [[walker.legs]], not both"
        )
    if "model" in w and w["model"] not in WALKER_MODELS:
        raise scene.error(
            sec,
            "model",
            f"unknown walker {w['model']!r}{_did_you_mean(w['model'], WALKER_MODELS)}",
        )
    if "legs" in w:
        _legs(w["legs"], scene)
    if "gait" in w and "phases_deg" in w:
        raise scene.error(sec, "phases_deg", "give a gait or phases_deg, not both")
    if "gait" in w:
        if w["gait"] not in GAITS:
            raise scene.error(
                sec, "gait", f"unknown gait {w['gait']!r}{_did_you_mean(w['gait'], GAITS)}"
            )
    if "phases_deg" in w:
        for v in w["phases_deg"]:
            _number(v, "angle", scene, sec, "phases_deg")
    return dict(w)


def _legs(legs: Sequence[Mapping[str, Any]], scene: Scene) -> None:

    if not legs:
        raise scene.error(("walker",), "legs", "is empty: a walker needs at least one leg")
    names: list[str] = []
    for idx, leg in enumerate(legs):
        lp = ("walker", "legs", idx)
        _keys(leg, LEG, scene, lp)
        for req in ("name", "mount"):
            if req not in leg:
                raise scene.error(lp, req, "missing")
        if ("catalog" in leg) == ("scene" in leg):
            raise scene.error(
                lp,
                "scene" if "scene" in leg else "catalog",
                'give a catalogue four-bar (catalog = "hoecken") or a [mechanism] scene file '
                '(scene = "candidate-1.toml", relative to this scene), not both'
                if "scene" in leg
                else 'missing: a catalogue four-bar (catalog = "hoecken") or a [mechanism] '
                'scene file (scene = "candidate-1.toml")',
            )
        if not leg["name"] or not leg["name"].isprintable() or len(leg["name"]) > 64:
            raise scene.error(lp, "name", f"must be a short printable name, got {leg['name']!r}")
        if leg["name"] in names:
            raise scene.error(lp, "name", f"leg {leg['name']!r} is defined twice")
        names.append(leg["name"])
        if "scene" in leg:
            f = leg["scene"]
            if not f.strip() or len(f) > 4096 or not f.isprintable():
                raise scene.error(lp, "scene", f"must name a scene file, got {_show(f)}")
            if "scale" in leg:
                raise scene.error(lp, "scale", "only a catalogue leg is scaled (give the lengths)")
        elif leg["catalog"] not in catalog.FOUR_BARS:
            raise scene.error(
                lp,
                "catalog",
                f"a leg must be a catalogue four-bar, got {leg['catalog']!r}"
                + _did_you_mean(leg["catalog"], catalog.FOUR_BARS),
            )
        mount = leg["mount"]
        if len(mount) != 3:
            raise scene.error(lp, "mount", f"must be [x, y, z], got {mount!r}")
        for v in mount:
            _number(v, "coord", scene, lp, "mount")
        plane = leg.get("plane", "sagittal")
        if plane not in ("sagittal", "horizontal"):
            raise scene.error(lp, "plane", f"must be 'sagittal' or 'horizontal', got {plane!r}")
        if plane == "horizontal" and "lift" not in leg:
            raise scene.error(lp, "lift", "a horizontal leg needs a lift program (cam)")
        if "lift" in leg:
            _turn(leg["lift"], scene, lp, "lift")


def _turn(
    segments: Sequence[Mapping[str, Any]], scene: Scene, owner: tuple[Any, ...], key: str
) -> None:
    """Check the segments of a program over one turn: they span 360° and rise back to the start.

    Such programs are a cam and a leg's lift.
    """
    if not segments:
        raise scene.error(owner, key, "is empty: give segments spanning 360°")
    total, rise, size = 0.0, 0.0, 0.0
    for k, s in enumerate(segments):
        sp = (*owner, key, k)
        _keys(s, CAM_SEGMENT, scene, sp)
        if "duration_deg" not in s:
            raise scene.error(sp, "duration_deg", "missing")
        if "law" in s and s["law"] not in LAWS:
            raise scene.error(
                sp, "law", f"unknown motion law {s['law']!r}{_did_you_mean(s['law'], LAWS)}"
            )
        total += s["duration_deg"]
        rise += s.get("rise", 0.0)
        size += abs(s.get("rise", 0.0))
    if abs(total - 360.0) > 1e-9:
        raise scene.error(owner, key, f"the segments must add up to 360°, got {total:g}°")
    if abs(rise) > 1e-12 * max(1.0, size):
        raise scene.error(
            owner, key, f"the rises must add up to 0 (back to the start each turn), got {rise:g}"
        )


def _drive(d: Mapping[str, Any], scene: Scene) -> dict[str, Any]:
    sec = ("drive",)
    _keys(d, DRIVE, scene, sec)
    kind = d.get("kind")
    if kind is None:
        raise scene.error(sec, "kind", 'missing: "constant", "program" or "schedule"')
    if kind not in DRIVE_KINDS:
        raise scene.error(sec, "kind", f"unknown drive {kind!r}{_did_you_mean(kind, DRIVE_KINDS)}")
    for other, keys in DRIVE_KINDS.items():
        if other != kind:
            for k in sorted(keys - DRIVE_KINDS[kind]):
                if k in d:
                    raise scene.error(
                        sec, k, f"belongs to a {other!r} drive, not {kind!r}: contradictory drive"
                    )
    if kind == "constant":
        if ("rpm" in d) == ("omega" in d):
            raise scene.error(
                sec, "rpm", "give exactly one of rpm (motor, rev/min) or omega (rad/s)"
            )
    elif kind == "program":
        if "segments" not in d:
            raise scene.error(
                sec, "segments", "missing: [[drive.segments]] with duration, rise_deg, law"
            )
        if not d["segments"]:
            raise scene.error(sec, "segments", "is empty: give at least one segment")

        for idx, s in enumerate(d["segments"]):
            sp = ("drive", "segments", idx)
            _keys(s, SEGMENT, scene, sp)
            if "duration" not in s:
                raise scene.error(sp, "duration", "missing")
            if "law" in s and s["law"] not in LAWS:
                raise scene.error(
                    sp,
                    "law",
                    f"unknown motion law {s['law']!r}{_did_you_mean(s['law'], LAWS)}",
                )
        period = math.fsum(s["duration"] for s in d["segments"])
        if period > TIME_RANGE[1]:
            raise scene.error(
                sec, "segments", f"the program lasts {period:g} s, more than {TIME_RANGE[1]:g} s"
            )
    else:
        for k in ("foot_speed", "duty_factor"):
            if k not in d:
                raise scene.error(sec, k, "missing (a schedule needs foot_speed and duty_factor)")
    if "gears" in d:
        g = d["gears"]
        if len(g) < 2 or not all(isinstance(z, int) and not isinstance(z, bool) for z in g):
            raise scene.error(
                sec, "gears", f"must list at least two tooth counts in mesh order, got {g!r}"
            )
        if not all(1 <= z <= TEETH_MAX for z in g):
            raise scene.error(
                sec, "gears", f"tooth counts must be between 1 and {TEETH_MAX}, got {g!r}"
            )
    if "duration" in d and "cycles" in d:
        raise scene.error(sec, "cycles", "give duration (s) or cycles, not both")
    samples = d.get("samples", 721)
    if samples < 8:
        raise scene.error(sec, "samples", f"must be at least 8, got {_show(samples)}")
    if samples > SAMPLES_MAX:
        raise scene.error(sec, "samples", f"must be at most {SAMPLES_MAX}, got {_show(samples)}")
    return dict(d)


def _cam(c: Mapping[str, Any], scene: Scene) -> dict[str, Any]:
    sec = ("cam",)
    _keys(c, CAM, scene, sec)
    for req in ("base_radius", "segments"):
        if req not in c:
            raise scene.error(sec, req, "missing")
    _turn(c["segments"], scene, sec, "segments")
    radius = c["base_radius"] + c.get("roller_radius", 0.0)
    if "roller_radius" in c and abs(c.get("offset", 0.0)) >= radius:
        raise scene.error(
            sec, "offset", f"must be smaller than base_radius + roller_radius ({radius:g})"
        )
    return dict(c)


def _synthesis_scene(data: Mapping[str, Any], scene: Scene) -> Scene:
    """Check the rest of a ``[synthesis]`` scene: its outputs, no drive or loads, the section.

    The target points (and atlas) are then read by :func:`linkage.build.validate`.
    """
    bad = [o for o in scene.outputs if o not in SYNTHESIS_OUTPUTS]
    if bad:
        raise scene.error(
            (),
            "outputs",
            f"{bad} need a [mechanism] or a [walker]; a [synthesis] scene reports "
            "'synthesis' and 'cad' (each candidate is exported as a scene to run)",
        )
    if "synthesis" not in scene.outputs:
        raise scene.error(
            (), "outputs", "a [synthesis] scene must list 'synthesis' (the search and its report)"
        )
    for key in ("drive", "masses", "loads", "cam", "gravity"):
        if key in data:
            raise scene.error(
                (),
                key,
                "does not apply to a [synthesis] scene: it searches for a linkage and drives "
                "none (run a candidate's exported scene for that)",
            )
    scene.synthesis = _synthesis(data["synthesis"], scene)
    return scene


def _points(points: Any, scene: Scene, sec: tuple[str, ...], key: str) -> None:
    """Check a points value: a CSV file's name, or at most POINTS_MAX pairs [x, y]."""
    if isinstance(points, str):
        if not points.strip() or len(points) > 4096 or not points.isprintable():
            raise scene.error(sec, key, f"must name a CSV file of x, y, got {_show(points)}")
        return
    if len(points) > POINTS_MAX:
        raise scene.error(sec, key, f"at most {POINTS_MAX} points, got {len(points)}")
    for k, p in enumerate(points):
        ok = (
            isinstance(p, list)
            and len(p) == 2
            and all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in p)
        )
        if not ok:
            raise scene.error(
                sec, key, f"point {k + 1} must be a pair of numbers [x, y], got {_show(p)}"
            )
        if not all(math.isfinite(v) for v in p):
            raise scene.error(sec, key, f"point {k + 1} must be finite, got [{p[0]!r}, {p[1]!r}]")
        for v in p:
            _number(v, "coord", scene, sec, key)


def _synthesis(s: Mapping[str, Any], scene: Scene) -> dict[str, Any]:
    sec = ("synthesis",)
    _keys(s, SYNTHESIS, scene, sec)
    if "points" not in s:
        raise scene.error(
            sec,
            "points",
            "missing: a CSV file of x, y (relative to the scene's folder) or [[x, y], ...]",
        )
    _points(s["points"], scene, sec, "points")
    if s.get("kind", "fourbar") not in PATH_KINDS:
        kinds = ", ".join(repr(k) for k in PATH_KINDS)
        raise scene.error(
            sec,
            "kind",
            f"must be one of {kinds}{_did_you_mean(s['kind'], PATH_KINDS)}, got {_show(s['kind'])}",
        )
    top = s.get("top", 5)
    if not 1 <= top <= SYNTHESIS_TOP_MAX:
        raise scene.error(
            sec, "top", f"must be between 1 and {SYNTHESIS_TOP_MAX}, got {_show(top)}"
        )
    refine = s.get("refine", 8)
    if not 0 <= refine <= SYNTHESIS_REFINE_MAX:
        raise scene.error(
            sec, "refine", f"must be between 0 and {SYNTHESIS_REFINE_MAX}, got {_show(refine)}"
        )
    seed = s.get("seed", 0)
    if not 0 <= seed <= SEED_MAX:
        raise scene.error(sec, "seed", f"must be between 0 and {SEED_MAX}, got {_show(seed)}")
    if "lengths" in s:
        lengths = s["lengths"]
        if len(lengths) != 2:
            raise scene.error(
                sec, "lengths", f"must be [least, greatest] link lengths, got {_show(lengths)}"
            )
        lo, hi = (_number(v, "length", scene, sec, "lengths") for v in lengths)
        if not lo < hi:
            raise scene.error(sec, "lengths", f"least must be below greatest, got [{lo:g}, {hi:g}]")
    if "pivots" in s:
        box = s["pivots"]
        if len(box) != 2 or not all(isinstance(c, list) for c in box):
            raise scene.error(
                sec,
                "pivots",
                f"must be a box [[xmin, ymin], [xmax, ymax]] for both ground pivots, "
                f"got {_show(box)}",
            )
        (x0, y0), (x1, y1) = (_pair(c, scene, sec, "pivots") for c in box)
        if not (x0 < x1 and y0 < y1):
            raise scene.error(
                sec,
                "pivots",
                f"must be [[xmin, ymin], [xmax, ymax]] with xmin < xmax and ymin < ymax, "
                f"got [[{x0:g}, {y0:g}], [{x1:g}, {y1:g}]]",
            )
    if "atlas" in s and (not s["atlas"].strip() or not s["atlas"].isprintable()):
        raise scene.error(sec, "atlas", f"must name an atlas folder, got {_show(s['atlas'])}")
    return dict(s)


def base_folder(scene: Scene) -> Path:
    """Return the folder a scene's relative file names are relative to.

    The scene file's folder, or the working directory for a scene given as text.

    Examples
    --------
    >>> from pathlib import Path
    >>> from linkage.scene import Scene, base_folder
    >>> base_folder(Scene("leg", Path("examples/hoecken.toml"), ())).as_posix()
    'examples'
    >>> base_folder(Scene("leg", None, ())) == Path(".")
    True
    """
    return scene.path.parent if scene.path is not None else Path(".")


# -- checks ----------------------------------------------------------------------------------


def _keys(table: Any, schema: Mapping[str, str], scene: Scene, path: tuple[Any, ...]) -> None:
    if not isinstance(table, Mapping):
        raise scene.error(path[:-1], str(path[-1]) if path else "", "must be a table")
    for key, value in table.items():
        if key not in schema:
            raise scene.error(path, key, f"unknown key{_did_you_mean(key, schema)}")
        _type(value, schema[key], scene, path, key)


def _type(value: Any, kind: str, scene: Scene, path: tuple[Any, ...], key: str) -> None:
    def bad(want: str) -> SceneError:
        return scene.error(path, key, f"must be {want}, got {_show(value)}")

    if kind in NUMBERS:
        _number(value, kind, scene, path, key)
    elif kind == "str" and not isinstance(value, str):
        raise bad("a string")
    elif kind == "bool" and not isinstance(value, bool):
        raise bad("true or false")
    elif kind == "int" and (not isinstance(value, int) or isinstance(value, bool)):
        raise bad("a whole number")
    elif kind == "pair":
        _pair(value, scene, path, key)
    elif kind == "list" and not isinstance(value, list):
        raise bad("a list")
    elif kind == "points" and not isinstance(value, (str, list)):
        raise bad("a CSV file name or a list of [x, y] pairs")
    elif kind == "table" and not isinstance(value, Mapping):
        raise bad("a table")
    elif kind == "tables" and not (
        isinstance(value, list) and all(isinstance(v, Mapping) for v in value)
    ):
        raise bad("a list of tables ([[...]] sections or {…} entries)")


def _number(value: Any, kind: str, scene: Scene, path: tuple[Any, ...], key: str) -> float:
    """``value`` checked as a finite number of ``kind`` (see :data:`NUMBERS`)."""
    if not isinstance(value, (int, float)) or isinstance(value, bool):
        raise scene.error(path, key, f"must be a finite number, got {_show(value)}")
    try:
        x = float(value)
    except OverflowError:
        x = math.inf
    if not math.isfinite(x):
        raise scene.error(path, key, f"must be a finite number, got {_show(value)}")
    lo, hi, how = NUMBERS[kind]
    shown = _show(value)
    if how == "positive":
        if x <= 0:
            raise scene.error(path, key, f"must be positive, got {shown}")
        if not lo <= x <= hi:
            raise scene.error(path, key, f"must be between {lo:g} and {hi:g}, got {shown}")
    elif how == "nonneg":
        if x < 0:
            raise scene.error(path, key, f"must be non-negative, got {shown}")
        if x > hi:
            raise scene.error(path, key, f"must be at most {hi:g}, got {shown}")
    elif how == "signed":
        if abs(x) > hi:
            raise scene.error(path, key, f"must be between {-hi:g} and {hi:g}, got {shown}")
    elif how == "nonzero":
        if x == 0:
            raise scene.error(path, key, "must be non-zero")
        if not lo <= abs(x) <= hi:
            raise scene.error(
                path, key, f"must have a magnitude between {lo:g} and {hi:g}, got {shown}"
            )
    elif not lo < x < hi:
        raise scene.error(path, key, f"must be between {lo:g} and {hi:g} (exclusive), got {shown}")
    return x


def _pair(value: Any, scene: Scene, path: tuple[Any, ...], key: str) -> tuple[float, float]:
    ok = (
        isinstance(value, list)
        and len(value) == 2
        and all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in value)
    )
    if not ok:
        raise scene.error(path, key, f"must be a pair of finite numbers [x, y], got {_show(value)}")
    x, y = (_number(v, "coord", scene, path, key) for v in value)
    return (x, y)


def _show(value: Any) -> str:
    """``type value`` for messages, short even for a huge value."""
    if isinstance(value, int) and not isinstance(value, bool) and value.bit_length() > 64:
        return f"an integer of about {int(value.bit_length() * math.log10(2)) + 1} digits"
    text = repr(value)
    if len(text) > 60:
        text = text[:57] + "..."
    return (
        f"{type(value).__name__} {text}"
        if not isinstance(value, (int, float)) or isinstance(value, bool)
        else text
    )


def _did_you_mean(word: str, choices: Any) -> str:
    close = difflib.get_close_matches(str(word), [str(c) for c in choices], n=1, cutoff=0.6)
    return f" (did you mean {close[0]!r}?)" if close else ""


# These classes' 0.1 module (a re-export of this one) stays their ``__module__``, for pickles and
# reprs; doctest looks for a class's examples in its ``__module__``: ``__test__`` points here.
__test__: dict[str, type] = {"SceneError": SceneError, "Scene": Scene}
for _cls in __test__.values():
    _cls.__module__ = "linkage._schema"
