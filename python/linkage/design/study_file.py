"""Study files: a TOML ``[design]`` section read into a :class:`~linkage.design.Study`.

Every mistake is a ``file:line: [section] key: problem`` message.
"""

from __future__ import annotations

import math
import re
import sys
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from linkage._core import LinkageError
from linkage._shared.files import read_bytes
from linkage._shared.toml_lines import MAX_NESTING, Locator, NotText, decode, nesting
from linkage.design.search import Constraints, Study, StudyError
from linkage.walking.legs import FAMILIES, OBJECTIVES, Settings

__all__ = ["STUDY_LIMIT", "StudyFile", "load_study"]

STUDY_LIMIT = 1 << 20
"""The most bytes a study file may hold (a study is a few hundred)."""

if sys.version_info >= (3, 11):  # pragma: no cover - depends on the interpreter
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib

Array = NDArray[np.float64]


# -- study files --------------------------------------------------------------------------

_TOP_KEYS = {
    "family": str,
    "objectives": list,
    "population": int,
    "budget": int,
    "seed": int,
    "workers": int,
    "scheduler": str,
    "chunk": int,
    "samples": int,
    "stance_tol": float,
    "foot_bar": float,
    "choose": int,
    "bounds": dict,
    "constraints": dict,
}
_CONSTRAINT_KEYS = ("min_transmission", "foot_below_hip", "min_lift", "min_duty")


@dataclass(frozen=True)
class StudyFile:
    """A study read from a TOML file, with how many designs to choose and the file it came from.

    ``choose`` is how many front designs to draw and export; ``scheduler_at`` locates the
    scheduler's address (``file:line: [design] scheduler``; empty without one) for messages
    about reaching it.
    """

    study: Study
    choose: int
    path: Path
    scheduler_at: str = ""


def load_study(path: str | Path) -> StudyFile:
    r"""Read a study file.

    The file has a ``[design]`` section (family, objectives, population, budget, seed, workers or
    scheduler, chunk, samples, stance_tol, foot_bar, choose) with ``[design.bounds]`` (``parameter =
    [lower, upper]``) and ``[design.constraints]``. Errors name ``file:line: [section] key``:
    every value is checked here (:class:`~linkage.design.search.Study`: bounds within the
    family's domain, fractions and tolerances in range, the scheduler's address, the search's
    memory), not when the search reaches it.

    Examples
    --------
    >>> import os, tempfile
    >>> from linkage.design.study_file import load_study
    >>> tmp = tempfile.TemporaryDirectory()
    >>> path = os.path.join(tmp.name, "legs.toml")
    >>> with open(path, "w") as fh:
    ...     _ = fh.write("[design]\npopulation = 8\n[design.bounds]\nground = [15.0, 25.0]\n")
    >>> sf = load_study(path)
    >>> sf.study.name, sf.study.population, sf.study.budget, sf.study.bounds, sf.choose
    ('legs', 8, 80, {'ground': (15.0, 25.0)}, 3)

    A mistake is named by file, line, section and key:

    >>> with open(path, "w") as fh:
    ...     _ = fh.write("[design]\npopulation = 8\n[design.bounds]\nground = [25.0, 15.0]\n")
    >>> load_study(path)
    Traceback (most recent call last):
    ...
    linkage.LinkageError: ...legs.toml:4: [design.bounds] ground: must be [lower, upper]...

    A value the family or this machine cannot take, located as well:

    >>> with open(path, "w") as fh:
    ...     _ = fh.write("[design]\npopulation = 1000000\nbudget = 1000000\n")
    >>> load_study(path)
    Traceback (most recent call last):
    ...
    linkage.LinkageError: ...legs.toml:2: [design] population: ... needs 15.5 TiB ...
    >>> tmp.cleanup()
    """
    p = Path(path)
    data = read_bytes(p, STUDY_LIMIT, "study")
    try:
        text = decode(data)
    except NotText as exc:
        raise LinkageError(f"{p}:{exc.line}: {exc.problem}") from None
    deep = nesting(text)
    if deep is not None:  # the TOML parser recurses: a few hundred levels overflow its stack
        raise LinkageError(f"{p}:{deep}: not a study: brackets nested more than {MAX_NESTING} deep")
    try:
        doc = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        line = getattr(exc, "lineno", None) or _line_of(str(exc))
        raise LinkageError(f"{p}:{line}: not valid TOML: {exc}") from None
    loc = Locator(text, str(p))

    def err(section: Sequence[str], key: str, problem: str) -> LinkageError:
        return LinkageError(loc.message(list(section), key, problem))

    name = str(doc.get("name", p.stem)) if isinstance(doc.get("name", ""), str) else p.stem
    for key in doc:
        if key not in ("design", "name"):
            raise err([], key, "unknown key (a study file has name and a [design] section)")
    d = doc.get("design")
    if not isinstance(d, dict):
        raise err([], "design", "missing: a study file needs a [design] section")
    for key, value in d.items():
        want = _TOP_KEYS.get(key)
        if want is None:
            raise err(["design"], key, f"unknown key; expected one of {', '.join(_TOP_KEYS)}")
        ok = (
            isinstance(value, (int, float)) and not isinstance(value, bool)
            if want is float
            else isinstance(value, want) and not isinstance(value, bool)
        )
        if not ok:
            raise err(["design"], key, f"must be {want.__name__}, got {value!r}")
    fam_name = d.get("family", "fourbar")
    if fam_name not in FAMILIES:
        raise err(
            ["design"], "family", f"unknown family {fam_name!r}; choose from {', '.join(FAMILIES)}"
        )
    fam = FAMILIES[fam_name]
    objectives = d.get("objectives", ["stride", "straightness", "speed_variation"])
    for o in objectives:
        if not isinstance(o, str):
            raise err(["design"], "objectives", f"must be a list of names, got {o!r} in it")
        if o not in OBJECTIVES:
            raise err(
                ["design"],
                "objectives",
                f"unknown objective {o!r}; choose from {', '.join(OBJECTIVES)}",
            )
    if not objectives:
        raise err(["design"], "objectives", "needs at least one objective")
    bounds = _bounds(d, fam_name, fam.params, err)
    cons = _constraints(d, err)
    ints = {
        "population": (4, 10**7),
        "budget": (4, 10**12),
        "seed": (0, 2**32 - 1),
        "workers": (0, 4096),
        "chunk": (1, 10**7),
        "samples": (16, 10**6),
        "choose": (0, 50),
    }
    for key, (lo, hi) in ints.items():
        if key in d and not lo <= d[key] <= hi:
            raise err(["design"], key, f"must be between {lo} and {hi}, got {d[key]}")
    for key in ("stance_tol", "foot_bar"):
        if key in d and not (math.isfinite(d[key]) and d[key] >= 0):
            raise err(["design"], key, f"must be a finite number ≥ 0, got {d[key]}")
    if "workers" in d and "scheduler" in d:
        raise err(["design"], "scheduler", "give workers or scheduler, not both")
    population = int(d.get("population", 64))
    budget = int(d.get("budget", 10 * population))
    if budget < population:
        raise err(["design"], "budget", f"must be at least one population ({population})")
    settings = Settings(
        samples=int(d.get("samples", 360)),
        stance_tol=float(d.get("stance_tol", 2.5e-3)),
        foot_bar=float(d.get("foot_bar", 0.0)),
    )
    try:
        study = Study(
            family=fam_name,
            objectives=tuple(objectives),
            bounds=bounds,
            constraints=Constraints(**cons),
            settings=settings,
            population=population,
            budget=budget,
            seed=int(d.get("seed", 1)),
            workers=int(d.get("workers", 0)),
            scheduler=d.get("scheduler"),
            chunk=int(d.get("chunk", 256)),
            name=name,
        )
    except StudyError as exc:
        raise err(exc.section, exc.key, exc.problem) from None
    return StudyFile(
        study=study,
        choose=int(d.get("choose", 3)),
        path=p,
        scheduler_at=f"{p}:{loc.line(['design'], 'scheduler')}: [design] scheduler"
        if "scheduler" in d
        else "",
    )


_Err = Callable[[Sequence[str], str, str], LinkageError]


def _bounds(
    d: dict[str, Any], fam_name: str, params: Sequence[str], err: _Err
) -> dict[str, tuple[float, float]]:
    """Return ``[design.bounds]`` checked: each a parameter of the family, finite lower < upper."""
    bounds: dict[str, tuple[float, float]] = {}
    for key, value in d.get("bounds", {}).items():
        if key not in params:
            raise err(
                ["design", "bounds"],
                key,
                f"family {fam_name!r} has no parameter {key!r}; it has {', '.join(params)}",
            )
        if (
            not isinstance(value, list)
            or len(value) != 2
            or not all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in value)
            or not all(math.isfinite(v) for v in value)
            or not value[0] < value[1]
        ):
            raise err(
                ["design", "bounds"],
                key,
                f"must be [lower, upper] with finite lower < upper, got {value!r}",
            )
        bounds[key] = (float(value[0]), float(value[1]))
    return bounds


def _constraints(d: dict[str, Any], err: _Err) -> dict[str, float]:
    """Return ``[design.constraints]`` checked: each a known constraint, a finite number."""
    cons: dict[str, float] = {}
    for key, value in d.get("constraints", {}).items():
        if key not in _CONSTRAINT_KEYS:
            raise err(
                ["design", "constraints"],
                key,
                f"unknown constraint; expected one of {', '.join(_CONSTRAINT_KEYS)}",
            )
        if (
            not isinstance(value, (int, float))
            or isinstance(value, bool)
            or not math.isfinite(value)
        ):
            raise err(["design", "constraints"], key, f"must be a finite number, got {value!r}")
        cons[key] = float(value)
    return cons


def _line_of(message: str) -> int:

    m = re.search(r"line (\d+)", message)
    return int(m.group(1)) if m else 1
