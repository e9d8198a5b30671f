"""Scene files: one study described in TOML, validated with located messages.

Every message names the file, the line and the key.

A scene names a mechanism (a catalogue entry, an explicit four-bar, or joint constructions) or a
walker, its drive, optional masses and loads, an optional cam, and the outputs wanted. Only the
stages those outputs need are run (see :mod:`linkage.runner`). A ``[synthesis]`` scene instead
gives target points and searches for four-bars whose coupler curve passes through them (no
drive; see :func:`linkage.synthesis.path`). Example (``examples/*.toml``)::

    name = "hoecken-leg"
    outputs = ["trajectory", "velocity", "curvature", "straightness"]

    [mechanism]
    catalog = "hoecken"

    [drive]
    kind = "constant"
    rpm = 50.0
    gears = [18, 15, 14]
    duration = 0.933

Validation is complete: :func:`load` and :func:`parse` check every key's type and range, the
references between sections, and then build the study once without running it (the linkage,
walker, drive, cam and masses, and the first assembled sample) so that whatever
:func:`linkage.runner.run` would reject is rejected here, with the file, line and key. A scene's
estimated memory (see :func:`linkage.build.estimate_memory`) must stay under
:data:`MEMORY_CAP`.

The schema and the key-by-key checks live in the private ``linkage._schema``, which
:mod:`linkage.build` imports; this module adds the build step on top, so the imports run one way
(``_schema`` ← ``build`` ← ``scene``). Its names are re-exported here unchanged.
"""

from __future__ import annotations

from pathlib import Path

from linkage.scene import builders as build
from linkage.scene import schema as _schema
from linkage.scene.schema import (
    ANGLE_MAX_DEG,
    CAM,
    CAM_SEGMENT,
    COORD_MAX,
    CYCLES_MAX,
    DEFAULT_SCENE,
    DRIVE,
    DRIVE_KINDS,
    FILE_MAX,
    FORMS,
    JOINT,
    JOINT_KINDS,
    LEG,
    LENGTH_RANGE,
    LOAD,
    MASS,
    MASS_MAX,
    MECHANISM,
    MECHANISM_OUTPUTS,
    MEMORY_CAP,
    NAME,
    NUMBERS,
    PATH_KINDS,
    POINTS_MAX,
    REPORT_OUTPUTS,
    SAMPLES_MAX,
    SCALE_RANGE,
    SEED_MAX,
    SEGMENT,
    SPEED_RANGE,
    STUDIES,
    SYNTHESIS,
    SYNTHESIS_OUTPUTS,
    SYNTHESIS_REFINE_MAX,
    SYNTHESIS_TOP_MAX,
    TEETH_MAX,
    TIME_RANGE,
    TOP,
    WALKER,
    WALKER_MODELS,
    WALKER_OUTPUTS,
    Scene,
    SceneError,
    base_folder,
)

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
    "load",
    "parse",
]


def load(path: str | Path) -> Scene:
    r"""Read and validate a scene file.

    Raises
    ------
    SceneError
        With ``file:line: [section] key: problem`` for the first problem found.

    Examples
    --------
    >>> import os, tempfile
    >>> from linkage.scene import load
    >>> tmp = tempfile.TemporaryDirectory()
    >>> path = os.path.join(tmp.name, "leg.toml")
    >>> with open(path, "w") as fh:
    ...     _ = fh.write('outputs = ["trajectory"]\n[mechanism]\ncatalog = "hoecken"\n'
    ...                  '[drive]\nkind = "constant"\nrpm = 50.0\n')
    >>> scene = load(path)
    >>> scene.name, scene.outputs, scene.mechanism
    ('leg', ('trajectory',), {'catalog': 'hoecken'})
    >>> with open(path, "w") as fh:
    ...     _ = fh.write('outputs = ["trajectory"]\n[mechanism]\ncatalog = "hoeken"\n')
    >>> load(path)
    Traceback (most recent call last):
    ...
    linkage._schema.SceneError: ...leg.toml:3: [mechanism] catalog: ... (did you mean 'hoecken'?)
    >>> tmp.cleanup()
    """
    p = Path(path)
    return parse(_schema.read_text(p), p)


def parse(text: str, path: Path | None = None, name: str | None = None) -> Scene:
    r"""Validate scene ``text`` and return the scene.

    ``path`` names it in messages, and a ``[synthesis]`` section's files are relative to its folder
    — else to the working directory; ``name`` is the name when the text gives none.

    Raises
    ------
    SceneError
        With ``file:line: [section] key: problem`` for the first problem found.

    Examples
    --------
    >>> from linkage.scene import parse
    >>> text = 'outputs = ["trajectory"]\n[drive]\nkind = "constant"\nrpm = 50.0\n'
    >>> scene = parse(text + '[mechanism]\ncatalog = "hoecken"\n', name="leg")
    >>> scene.name, scene.drive["rpm"], scene.path
    ('leg', 50.0, None)

    The study is built once (not run), so a four-bar that assembles at no crank angle is refused
    here (coupler and rocker of 4 cannot reach across the ground of 20):

    >>> parse(text + "[mechanism]\nground = 20\ncrank = 10\ncoupler = 4\nrocker = 4\n")
    Traceback (most recent call last):
    ...
    linkage._schema.SceneError: <scene>:6: [mechanism] ground: no sample assembles: ... gap 2)
    """
    scene = _schema.parse_only(text, path, name)
    # Build the study once without running it: whatever `run` would reject is rejected here.
    build.validate(scene)
    return scene
