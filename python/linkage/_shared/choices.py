"""The string choices of the public API, as ``typing.Literal`` aliases, each defined once.

Signatures (and the extension's stub) say ``assembly: Assembly`` rather than ``str``, so a type
checker catches ``assembly="opne"``; at run time the arguments are still checked, against the
core's names where the core defines them (``linkage._arrays.choices``). The aliases of the
core's choices (``Assembly``, ``Side``, ``Reach``, ``SweepMode``) and of :data:`linkage.drive.LAWS`
are held equal to the core's names by tests/test_choices.py; the others are the one definition
of their names, whose tuples (``OUTPUTS``, ``synthesis.KINDS`` …) are read from them with
``typing.get_args``.
"""

from __future__ import annotations

from typing import Literal

__all__ = [
    "Assembly",
    "AtlasKind",
    "Law",
    "LinkageKind",
    "Objective",
    "Output",
    "PathKind",
    "Plane",
    "Reach",
    "Side",
    "Spacing",
    "SweepMode",
    "View",
]

Assembly = Literal["open", "crossed"]
"""A four-bar's assembly: ``B`` left ("open") or right ("crossed") of the diagonal ``A → C``."""

Side = Literal["left", "right"]
"""The side of the directed line ``p1 → p2`` a dyad's joint is on."""

Reach = Literal["ahead", "behind"]
"""Which intersection of a slider's circle with its line, along the line's direction."""

SweepMode = Literal["trig", "table", "recurrence"]
"""How :meth:`linkage.FourBar.uniform_sweep` makes the crank directions."""

Output = Literal["point", "joints", "velocity", "acceleration", "instant_centres", "curvature"]
"""A name accepted by a sweep's ``outputs=``."""

LinkageKind = Literal["fourbar", "slider-crank"]
"""A kind of linkage an atlas holds and :func:`linkage.synthesis.path` searches."""

AtlasKind = Literal[LinkageKind, "fourbar-arcs", "slider-crank-arcs"]
"""The ``kind`` of a :class:`linkage.synthesis.Atlas`: a linkage kind, or open arcs of its
circuits."""

PathKind = Literal[LinkageKind, "any"]
"""The ``kind`` of :func:`linkage.synthesis.path`: one kind, or ``"any"`` for both."""

Spacing = Literal["chebyshev", "uniform"]
"""Where :func:`linkage.synthesis.function` puts its precision points."""

Objective = Literal["margin", "slip"]
"""What a gait search optimises: the stability margin (maximised) or the slip (minimised)."""

Plane = Literal["sagittal", "horizontal"]
"""The plane a leg's linkage moves in."""

View = Literal["side", "top"]
"""The view of a walker drawing."""

Law = Literal[
    "constant-velocity",
    "constant-acceleration",
    "simple-harmonic",
    "cycloidal",
    "3-4-5",
    "4-5-6-7",
    "modified-trapezoid",
]
"""A motion law's name (:data:`linkage.drive.LAWS`, the core's names)."""
