"""Scene files: one study described in TOML, validated with messages that name the file, the
line and the key.

A scene names a mechanism (a catalogue entry, an explicit four-bar, or joint constructions) or a
walker, its drive, optional masses and loads, an optional cam, and the outputs wanted. Only the
stages those outputs need are run (see :mod:`linkage.runner`). Example (``examples/*.toml``)::

    name = "hoecken-leg"
    outputs = ["trajectory", "velocity", "curvature", "straightness"]

    [mechanism]
    catalog = "hoecken"

    [drive]
    kind = "constant"
    rpm = 50.0
    gears = [18, 15, 14]
    duration = 0.933
"""

from __future__ import annotations

import difflib
import math
import re
import sys
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from linkage._core import LinkageError

if sys.version_info >= (3, 11):  # pragma: no cover - depends on the interpreter
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib

OUTPUTS = (
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
)
"""What a scene can ask for."""

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
    description: str = ""
    units: str = ""
    """Length unit label for the report (e.g. "mm"); lengths are used as given."""

    def wants(self, *names: str) -> bool:
        """Whether any of ``names`` is among the outputs."""
        return any(n in self.outputs for n in names)


# Allowed keys per section: key → (type check, description). Types: "number", "positive",
# "int", "str", "bool", "pair", "list", "table", "tables".
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
}
MECHANISM = {
    "catalog": "str",
    "scale": "positive",
    "ground": "positive",
    "crank": "positive",
    "coupler": "positive",
    "rocker": "positive",
    "point": "pair",
    "assembly": "str",
    "trace": "str",
    "joints": "tables",
}
JOINT = {
    "name": "str",
    "kind": "str",
    "at": "pair",
    "centre": "str",
    "radius": "positive",
    "phase_deg": "number",
    "p1": "str",
    "p2": "str",
    "r1": "positive",
    "r2": "positive",
    "side": "str",
    "on": "list",
    "along": "number",
    "left": "number",
}
WALKER = {
    "model": "str",
    "legs": "tables",
    "gait": "str",
    "phases_deg": "list",
    "pad": "number",
    "cg": "pair",
    "ground_tol": "positive",
}
LEG = {
    "name": "str",
    "catalog": "str",
    "scale": "positive",
    "mount": "list",
    "phase_deg": "number",
    "plane": "str",
    "mirror": "bool",
    "foot_offset": "pair",
    "pad": "number",
    "lift": "tables",
}
DRIVE = {
    "kind": "str",
    "rpm": "number",
    "omega": "number",
    "gears": "list",
    "start_deg": "number",
    "segments": "tables",
    "foot_speed": "positive",
    "duty_factor": "number",
    "duration": "positive",
    "cycles": "positive",
    "samples": "int",
}
SEGMENT = {"duration": "positive", "rise_deg": "number", "law": "str"}
MASS = {"mass": "number", "centre": "pair", "inertia": "number"}
LOAD = {"link": "str", "joint": "str", "force": "pair", "torque": "number"}
CAM = {
    "base_radius": "positive",
    "roller_radius": "positive",
    "offset": "number",
    "pressure_limit_deg": "positive",
    "segments": "tables",
}
CAM_SEGMENT = {"duration_deg": "positive", "rise": "number", "law": "str"}
DRIVE_KINDS = {
    "constant": {"rpm", "omega", "gears"},
    "program": {"start_deg", "segments", "gears"},
    "schedule": {"foot_speed", "duty_factor"},
}


def load(path: str | Path) -> Scene:
    """Read and validate a scene file.

    Raises
    ------
    SceneError
        With ``file:line: [section] key: problem`` for the first problem found.
    """
    p = Path(path)
    try:
        text = p.read_text(encoding="utf-8")
    except OSError as exc:
        raise SceneError(f"{p}: cannot read the scene: {exc.strerror or exc}") from None
    return parse(text, p)


def parse(text: str, path: Path | None = None, name: str | None = None) -> Scene:
    """Validate scene ``text`` (``path`` only names it in messages)."""
    where = _Locator(text, path)
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        m = re.search(r"line (\d+)", str(exc))
        n = (
            m.group(1)
            if m
            else (str(max(1, len(where.lines))) if "end of document" in str(exc) else "")
        )
        line = f"{n}:" if n else ""
        raise SceneError(f"{where.file}:{line} not valid TOML: {exc}") from None
    _keys(data, TOP, where, ())
    outputs = data.get("outputs")
    if outputs is None:
        raise where.error(
            (), "outputs", 'missing: list what to compute, e.g. outputs = ["trajectory"]'
        )
    for o in outputs:
        if not isinstance(o, str):
            raise where.error((), "outputs", f"entries must be names, got {o!r}")
        if o not in OUTPUTS:
            raise where.error((), "outputs", f"unknown output {o!r}{_did_you_mean(o, OUTPUTS)}")
    outputs = tuple(dict.fromkeys(outputs))
    has_mech, has_walker = "mechanism" in data, "walker" in data
    if has_mech == has_walker:
        raise where.error((), "mechanism", "give exactly one of [mechanism] or [walker]")
    scene = Scene(
        name=str(data.get("name") or name or (path.stem if path else "scene")),
        path=path,
        outputs=outputs,
        description=str(data.get("description", "")),
        units=str(data.get("units", "")),
    )
    if not re.fullmatch(r"[A-Za-z0-9_.-]+", scene.name):
        raise where.error(
            (),
            "name",
            f"must be letters, digits, '.', '_' or '-' (a folder name), got {scene.name!r}",
        )
    if has_mech:
        scene.mechanism = _mechanism(data["mechanism"], where)
        bad = sorted(set(outputs) & WALKER_OUTPUTS)
        if bad:
            raise where.error((), "outputs", f"{bad} need a [walker], not a [mechanism]")
    else:
        scene.walker = _walker(data["walker"], where)
        bad = sorted(set(outputs) & MECHANISM_OUTPUTS)
        if bad:
            raise where.error(
                (), "outputs", f"{bad} need a [mechanism]; a walker reports gait, stability, slip"
            )
    if "drive" not in data:
        raise where.error(
            (), "drive", 'missing: a [drive] section (kind = "constant", "program" or "schedule")'
        )
    scene.drive = _drive(data["drive"], where, scene)
    if "gravity" in data:
        scene.gravity = _pair(data["gravity"], where, (), "gravity")
    if "masses" in data:
        masses = data["masses"]
        scene.masses = {}
        for link, spec in masses.items():
            if not isinstance(spec, Mapping):
                raise where.error(
                    ("masses",),
                    link,
                    "must be a table {mass = ..., centre = [along, left], inertia = ...}",
                )
            _keys(spec, MASS, where, ("masses", link))
            if "mass" not in spec:
                raise where.error(("masses", link), "mass", "missing")
            if spec["mass"] < 0 or spec.get("inertia", 0.0) < 0:
                raise where.error(("masses", link), "mass", "mass and inertia must be non-negative")
            scene.masses[link] = dict(spec)
    for k, load in enumerate(data.get("loads", [])):
        _keys(load, LOAD, where, ("loads", k))
        for req in ("link", "joint", "force"):
            if req not in load:
                raise where.error(("loads", k), req, "missing")
        scene.loads.append(dict(load))
    if "torque" in outputs:
        if scene.masses is None:
            raise where.error(
                (),
                "outputs",
                "'torque' needs link masses: add a [masses] section (mass = 0 for a massless link)",
            )
    elif scene.masses is not None or scene.loads:
        pass  # masses without torque are allowed and ignored
    if "cam" in data:
        scene.cam = _cam(data["cam"], where)
    if "cam" in outputs and scene.cam is None:
        raise where.error((), "outputs", "'cam' needs a [cam] section")
    return scene


# -- sections --------------------------------------------------------------------------------


def _mechanism(m: Mapping[str, Any], where: _Locator) -> dict[str, Any]:
    sec = ("mechanism",)
    _keys(m, MECHANISM, where, sec)
    forms = [k for k in ("catalog", "ground", "joints") if k in m]
    if len(forms) != 1:
        raise where.error(
            sec,
            forms[1] if len(forms) > 1 else "catalog",
            'give exactly one of catalog = "name", a four-bar (ground, crank, coupler, rocker) '
            "or [[mechanism.joints]]",
        )
    out = dict(m)
    if "catalog" in m:
        from linkage import catalog

        if m["catalog"] not in catalog.names():
            raise where.error(
                sec,
                "catalog",
                f"unknown catalogue linkage {m['catalog']!r}"
                + _did_you_mean(m["catalog"], catalog.names()),
            )
    elif "ground" in m:
        for k in ("crank", "coupler", "rocker"):
            if k not in m:
                raise where.error(
                    sec, k, "missing (a four-bar needs ground, crank, coupler, rocker)"
                )
        if m.get("assembly", "open") not in ("open", "crossed"):
            raise where.error(
                sec, "assembly", f"must be 'open' or 'crossed', got {m['assembly']!r}"
            )
    else:
        names: list[str] = []
        for idx, j in enumerate(m["joints"]):
            jp = ("mechanism", "joints", idx)
            _keys(j, JOINT, where, jp)
            for req in ("name", "kind"):
                if req not in j:
                    raise where.error(jp, req, "missing")
            kinds = {
                "fixed": ("at",),
                "crank": ("centre", "radius"),
                "dyad": ("p1", "p2", "r1", "r2"),
                "point": ("on", "along"),
            }
            if j["kind"] not in kinds:
                raise where.error(
                    jp,
                    "kind",
                    f"unknown kind {j['kind']!r}{_did_you_mean(j['kind'], kinds)}",
                )
            for req in kinds[j["kind"]]:
                if req not in j:
                    raise where.error(
                        jp,
                        req,
                        f"missing (a {j['kind']} needs {', '.join(kinds[j['kind']])})",
                    )
            for ref in ("centre", "p1", "p2"):
                if ref in j and j[ref] not in names:
                    raise where.error(
                        jp,
                        ref,
                        f"unknown joint {j[ref]!r} "
                        f"(defined before it: {', '.join(names) or 'none'})",
                    )
            names.append(j["name"])
    return out


def _walker(w: Mapping[str, Any], where: _Locator) -> dict[str, Any]:
    sec = ("walker",)
    _keys(w, WALKER, where, sec)
    models = ("quadruped_hoecken", "hexapod_tripod")
    if ("model" in w) == ("legs" in w):
        raise where.error(
            sec, "model", f"give a model ({', '.join(models)}) or [[walker.legs]], not both"
        )
    if "model" in w and w["model"] not in models:
        raise where.error(
            sec, "model", f"unknown walker {w['model']!r}{_did_you_mean(w['model'], models)}"
        )
    if "legs" in w:
        from linkage import catalog
        from linkage.drive import LAWS

        names = []
        for idx, leg in enumerate(w["legs"]):
            lp = ("walker", "legs", idx)
            _keys(leg, LEG, where, lp)
            for req in ("name", "catalog", "mount"):
                if req not in leg:
                    raise where.error(lp, req, "missing")
            if leg["name"] in names:
                raise where.error(lp, "name", f"leg {leg['name']!r} is defined twice")
            names.append(leg["name"])
            if leg["catalog"] not in catalog.FOUR_BARS:
                raise where.error(
                    lp,
                    "catalog",
                    f"a leg must be a catalogue four-bar, got {leg['catalog']!r}"
                    + _did_you_mean(leg["catalog"], catalog.FOUR_BARS),
                )
            mount = leg["mount"]
            if len(mount) != 3 or not all(
                isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v)
                for v in mount
            ):
                raise where.error(lp, "mount", f"must be [x, y, z] finite numbers, got {mount!r}")
            plane = leg.get("plane", "sagittal")
            if plane not in ("sagittal", "horizontal"):
                raise where.error(lp, "plane", f"must be 'sagittal' or 'horizontal', got {plane!r}")
            if plane == "horizontal" and "lift" not in leg:
                raise where.error(lp, "lift", "a horizontal leg needs a lift program (cam)")
            for k, seg in enumerate(leg.get("lift", [])):
                _keys(seg, CAM_SEGMENT, where, (*lp, "lift", k))
                if "law" in seg and seg["law"] not in LAWS:
                    raise where.error(lp, "lift", f"unknown motion law {seg['law']!r}")
            if leg.get("pad", 0.0) < 0:
                raise where.error(lp, "pad", "must be non-negative")
    if "gait" in w and "phases_deg" in w:
        raise where.error(sec, "phases_deg", "give a gait or phases_deg, not both")
    if "gait" in w:
        from linkage.walker import GAITS

        if w["gait"] not in GAITS:
            raise where.error(
                sec, "gait", f"unknown gait {w['gait']!r}{_did_you_mean(w['gait'], GAITS)}"
            )
    if "phases_deg" in w:
        ph = w["phases_deg"]
        if not all(
            isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v) for v in ph
        ):
            raise where.error(sec, "phases_deg", "must be finite numbers (degrees), one per leg")
    if w.get("pad", 0.0) < 0:
        raise where.error(sec, "pad", "must be non-negative")
    return dict(w)


def _drive(d: Mapping[str, Any], where: _Locator, scene: Scene) -> dict[str, Any]:
    sec = ("drive",)
    _keys(d, DRIVE, where, sec)
    kind = d.get("kind")
    if kind is None:
        raise where.error(sec, "kind", 'missing: "constant", "program" or "schedule"')
    if kind not in DRIVE_KINDS:
        raise where.error(sec, "kind", f"unknown drive {kind!r}{_did_you_mean(kind, DRIVE_KINDS)}")
    for other, keys in DRIVE_KINDS.items():
        if other != kind:
            for k in sorted(keys - DRIVE_KINDS[kind]):
                if k in d:
                    raise where.error(
                        sec, k, f"belongs to a {other!r} drive, not {kind!r}: contradictory drive"
                    )
    if kind == "constant":
        if ("rpm" in d) == ("omega" in d):
            raise where.error(
                sec, "rpm", "give exactly one of rpm (motor, rev/min) or omega (rad/s)"
            )
        speed = d.get("rpm", d.get("omega"))
        if speed == 0:
            raise where.error(sec, "rpm" if "rpm" in d else "omega", "must be non-zero")
    elif kind == "program":
        if "segments" not in d:
            raise where.error(
                sec, "segments", "missing: [[drive.segments]] with duration, rise_deg, law"
            )
        from linkage.drive import LAWS

        for idx, s in enumerate(d["segments"]):
            sp = ("drive", "segments", idx)
            _keys(s, SEGMENT, where, sp)
            if "duration" not in s:
                raise where.error(sp, "duration", "missing")
            if "law" in s and s["law"] not in LAWS:
                raise where.error(
                    sp,
                    "law",
                    f"unknown motion law {s['law']!r}{_did_you_mean(s['law'], LAWS)}",
                )
    else:
        for k in ("foot_speed", "duty_factor"):
            if k not in d:
                raise where.error(sec, k, "missing (a schedule needs foot_speed and duty_factor)")
        if not 0 < d["duty_factor"] < 1:
            raise where.error(
                sec, "duty_factor", f"must be between 0 and 1, got {d['duty_factor']}"
            )
    if "gears" in d:
        g = d["gears"]
        if len(g) < 2 or not all(
            isinstance(z, int) and not isinstance(z, bool) and z > 0 for z in g
        ):
            raise where.error(
                sec, "gears", "must list at least two positive tooth counts in mesh order"
            )
    if "duration" in d and "cycles" in d:
        raise where.error(sec, "cycles", "give duration (s) or cycles, not both")
    samples = d.get("samples", 721)
    if samples < 8:
        raise where.error(sec, "samples", f"must be at least 8, got {samples}")
    return dict(d)


def _cam(c: Mapping[str, Any], where: _Locator) -> dict[str, Any]:
    sec = ("cam",)
    _keys(c, CAM, where, sec)
    for req in ("base_radius", "segments"):
        if req not in c:
            raise where.error(sec, req, "missing")
    from linkage.drive import LAWS

    total = 0.0
    for k, s in enumerate(c["segments"]):
        _keys(s, CAM_SEGMENT, where, ("cam", "segments", k))
        if "duration_deg" not in s:
            raise where.error(("cam", "segments", k), "duration_deg", "missing")
        if "law" in s and s["law"] not in LAWS:
            raise where.error(
                ("cam", "segments", k),
                "law",
                f"unknown motion law {s['law']!r}{_did_you_mean(s['law'], LAWS)}",
            )
        total += s["duration_deg"]
    if abs(total - 360.0) > 1e-9:
        raise where.error(
            sec, "segments", f"the cam's segments must add up to 360°, got {total:g}°"
        )
    return dict(c)


# -- checks ----------------------------------------------------------------------------------


def _keys(table: Any, schema: Mapping[str, str], where: _Locator, path: tuple[Any, ...]) -> None:
    if not isinstance(table, Mapping):
        raise where.error(path[:-1], str(path[-1]) if path else "", "must be a table")
    for key, value in table.items():
        if key not in schema:
            raise where.error(path, key, f"unknown key{_did_you_mean(key, schema)}")
        _type(value, schema[key], where, path, key)


def _type(value: Any, kind: str, where: _Locator, path: tuple[Any, ...], key: str) -> None:
    def bad(want: str) -> SceneError:
        return where.error(path, key, f"must be {want}, got {type(value).__name__} {value!r}")

    is_num = isinstance(value, (int, float)) and not isinstance(value, bool)
    if kind == "str" and not isinstance(value, str):
        raise bad("a string")
    if kind == "bool" and not isinstance(value, bool):
        raise bad("true or false")
    if kind == "int" and (not isinstance(value, int) or isinstance(value, bool)):
        raise bad("a whole number")
    if kind in ("number", "positive"):
        if not is_num or not math.isfinite(value):
            raise bad("a finite number")
        if kind == "positive" and value <= 0:
            raise where.error(path, key, f"must be positive, got {value!r}")
    if kind == "pair":
        _pair(value, where, path, key)
    if kind == "list" and not isinstance(value, list):
        raise bad("a list")
    if kind == "table" and not isinstance(value, Mapping):
        raise bad("a table")
    if kind == "tables" and not (
        isinstance(value, list) and all(isinstance(v, Mapping) for v in value)
    ):
        raise bad("a list of tables ([[...]] sections or {…} entries)")


def _pair(value: Any, where: _Locator, path: tuple[Any, ...], key: str) -> tuple[float, float]:
    ok = (
        isinstance(value, list)
        and len(value) == 2
        and all(
            isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v)
            for v in value
        )
    )
    if not ok:
        raise where.error(path, key, f"must be a pair of finite numbers [x, y], got {value!r}")
    return (float(value[0]), float(value[1]))


def _did_you_mean(word: str, choices: Any) -> str:
    close = difflib.get_close_matches(str(word), [str(c) for c in choices], n=1, cutoff=0.6)
    return f" (did you mean {close[0]!r}?)" if close else ""


class _Locator:
    """Finds the line of a key in the scene text, for messages (tomllib keeps no positions)."""

    def __init__(self, text: str, path: Path | None) -> None:
        self.lines = text.splitlines()
        self.file = str(path) if path else "<scene>"

    def line(self, path: Sequence[Any], key: str) -> int | None:
        names = [p for p in path if isinstance(p, str)]
        index = next((p for p in path if isinstance(p, int)), None)
        pattern = re.compile(r"(^|[\s{,])" + re.escape(str(key)) + r"\s*=")
        start, end = 0, len(self.lines)
        if names:
            header = re.compile(r"^\s*\[\[?\s*" + re.escape(".".join(names)) + r"\s*\]\]?\s*$")
            hits = [i for i, line in enumerate(self.lines) if header.match(line)]
            if hits:
                start = hits[min(index or 0, len(hits) - 1)] + 1
                nxt = [
                    i for i in range(start, len(self.lines)) if re.match(r"^\s*\[", self.lines[i])
                ]
                end = nxt[0] if nxt else len(self.lines)
            else:
                # An inline array of tables (`legs = [ {…}, {…} ]`): the entry's own line.
                owner = re.compile(r"(^|[\s{,])" + re.escape(names[-1]) + r"\s*=")
                at = next((i for i, line in enumerate(self.lines) if owner.search(line)), None)
                if at is not None:
                    entry = at
                    if index is not None:
                        braces = [i for i in range(at, len(self.lines)) if "{" in self.lines[i]]
                        entry = braces[index] if index < len(braces) else at
                    line = self.lines[entry]
                    return entry + 1 if pattern.search(line) or index is not None else at + 1
        else:
            first = [i for i, line in enumerate(self.lines) if re.match(r"^\s*\[", line)]
            end = first[0] if first else len(self.lines)
        for i in range(start, end):
            if pattern.search(self.lines[i]):
                return i + 1
        for i in range(len(self.lines)):
            if pattern.search(self.lines[i]):
                return i + 1
        # A missing key: point at its section's header, or the file's first line.
        return start if names and start else 1

    def error(self, path: Sequence[Any], key: str, problem: str) -> SceneError:
        line = self.line(path, key)
        where = f"{self.file}:{line}:" if line else f"{self.file}:"
        section = ".".join(str(p) for p in path if isinstance(p, str))
        idx = [p for p in path if isinstance(p, int)]
        label = (f"[{section}" + (f" #{idx[0] + 1}" if idx else "") + "] ") if section else ""
        return SceneError(f"{where} {label}{key}: {problem}")
