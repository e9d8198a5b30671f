"""Scene files: one study described in TOML, validated with located messages.

The names are those of :mod:`linkage.scene.facade` (``load``, ``parse``, the schema's
constants and types), each imported on first use: the schema (:mod:`linkage.scene.schema`) and
the builders (:mod:`linkage.scene.builders`) can be imported without the build step.
"""

# ruff: noqa: F405 (__all__ lists the facade's names, star-imported for type checkers only)

from __future__ import annotations

from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from linkage.scene.facade import *  # noqa: F403

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


def __getattr__(name: str) -> Any:
    """Return the facade's ``name`` (PEP 562), importing :mod:`linkage.scene.facade` once."""
    if name in __all__:
        from linkage.scene import facade  # noqa: PLC0415 (loaded on first use)

        return getattr(facade, name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def __dir__() -> list[str]:
    """Return the module's names, the facade's included."""
    return sorted(set(globals()) | set(__all__))
