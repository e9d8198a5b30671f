"""``linkage synth``: path synthesis from the command line (the table of candidates it prints).

Application code over :mod:`linkage.synthesis`, called by :mod:`linkage.cli`; ``command``
searches with :func:`linkage.synthesis.path` unless told otherwise.
"""

from __future__ import annotations

import argparse
import math
import time
from collections.abc import Callable
from typing import cast

from linkage._core import LinkageError
from linkage._shared.choices import PathKind
from linkage.kinematics.slider_crank import SliderCrank
from linkage.synthesis.candidates import Candidates, change_point_gap, long_link, why_none
from linkage.synthesis.limits import SYNTHESIS_REFINE_MAX, SYNTHESIS_TOP_MAX
from linkage.synthesis.search import path
from linkage.synthesis.targets import _target, rounded_to, target_size

__all__ = ["CLI_CONSTRAINTS", "command"]

CLI_CONSTRAINTS = {
    "full_turn": "--full-turn",
    "min_transmission": "--min-transmission-deg",
    "lengths": "--lengths",
    "pivots": "--pivots",
    "refine": "--refine",
}
"""``linkage synth``'s options for :func:`path`'s constraints (and ``refine``)."""


def command(args: argparse.Namespace, search: Callable[..., Candidates] = path) -> int:
    """``linkage synth curve.csv``: print the candidates ``search`` finds as a table with units."""
    if not 1 <= int(args.top) <= SYNTHESIS_TOP_MAX:
        raise LinkageError(f"--top must be between 1 and {SYNTHESIS_TOP_MAX}, got {args.top}")
    refine = int(getattr(args, "refine", 8))
    if not 0 <= refine <= SYNTHESIS_REFINE_MAX:
        raise LinkageError(f"--refine must be between 0 and {SYNTHESIS_REFINE_MAX}, got {refine}")
    mu = getattr(args, "min_transmission_deg", 0.0)
    if not 0 <= mu <= 90:
        raise LinkageError(f"--min-transmission-deg must be between 0 and 90, got {mu:g}")
    kind = cast(PathKind, getattr(args, "kind", "fourbar"))
    t0 = time.perf_counter()
    # Read once: the search takes the cleaned points, the table rounds to their size.
    target = _target(args.curve, not args.open)
    found = search(
        target,
        closed=not args.open,
        top=int(args.top),
        refine=refine,
        kind=kind,
        full_turn=bool(args.full_turn),
        min_transmission=math.radians(mu),
        lengths=getattr(args, "lengths", None),
        pivots=(
            None if getattr(args, "pivots", None) is None else (args.pivots[:2], args.pivots[2:])
        ),
        seed=getattr(args, "seed", 0),
        tol=getattr(args, "tol", 1e-3),
        atlas=args.atlas,
        progress=not args.quiet,
        accept=getattr(args, "accept", None),
    )
    took = time.perf_counter() - t0
    u = f" {args.units}" if args.units else ""
    what = {"fourbar": "four-bar", "slider-crank": "slider-crank", "any": "linkage"}[kind]
    if not found:
        # One line and status 2, as `linkage run` says it of a scene.
        why, _ = why_none(found, CLI_CONSTRAINTS, args.units or "")
        raise LinkageError(f"no valid {what} found for {args.curve} in {took:.1f} s: {why}")
    print(
        f"{len(found)} {what}(s) for {args.curve}, best first ({took:.1f} s; errors are the "
        f"largest / RMS distance of the target points to the coupler curve{u and ', in' + u}):"
    )
    size = target_size(target)

    def g(x: float) -> str:
        # Coordinates and lengths to 1e-5 of the target's size: an exact fit's round-off reads 0.
        return f"{rounded_to(x, size, 5):.4g}"

    # One table ranked as found; under "any" a column holds a four-bar's or a slider-crank's
    # number, named by both.
    tail = {
        "fourbar": ("C", "crank", "coupler", "rocker", "point (along, left)", "assembly"),
        "slider-crank": (
            "line (deg)",
            "crank",
            "coupler",
            "offset",
            "point (along, left)",
            "reach",
        ),
        "any": (
            "C | line (deg)",
            "crank",
            "coupler",
            "rocker | offset",
            "point (along, left)",
            "assembly | reach",
        ),
    }[kind]
    # A closed target's candidates also say how far their curve strays from the target's
    # polygon (a spur or a loop the points never asked for).
    back = (f"curve→polygon{u}",) if not args.open else ()
    head = (
        "#",
        f"error{u}",
        f"rms{u}",
        *back,
        "class",
        "crank range (deg)",
        "min μ (deg)",
        "O",
        *tail,
        "from",
    )
    rows: list[tuple[str, ...]] = [head]
    for rank, c in enumerate(found, 1):
        fb = c.linkage
        lo, hi = (round(math.degrees(v), 1) + 0.0 for v in c.crank_range)
        row = [
            str(rank),
            f"{c.error:.3g}",
            f"{c.rms:.3g}",
            *((f"{c.back:.3g}",) if not args.open else ()),
            c.grashof,
            f"{lo:.1f} … {hi:.1f}",
            f"{c.min_transmission_deg:.1f}",
            f"({g(fb.o[0])}, {g(fb.o[1])})",
        ]
        if isinstance(fb, SliderCrank):
            # Rounded first: an angle of -1e-12 rad reads 0.00, not -0.00.
            line = round(math.degrees(fb.angle), 2) + 0.0
            row += [f"{line:.2f}", g(fb.crank), g(fb.coupler), g(fb.offset)]
            row += [f"({g(fb.point[0])}, {g(fb.point[1])})", f"slider {fb.reach}"]
        else:
            row += [f"({g(fb.c[0])}, {g(fb.c[1])})", g(fb.crank), g(fb.coupler)]
            row += [g(fb.rocker), f"({g(fb.point[0])}, {g(fb.point[1])})", fb.assembly]
        # The stage that found it (candidates.csv's `source`): equation, atlas, global, cognate.
        row.append(c.source)
        rows.append(tuple(row))
    # Notes: a candidate near a change point, and one ranked after the rest for a link longer
    # than LONG_LINK sizes (max_link: a fit far better than those above it had read as a
    # sorting mistake).
    notes = []
    for c in found:
        note = []
        near = change_point_gap(c, size)
        if near is not None:
            note.append(f"{near[0]:.1e}{u} from a change point: can flip branch")
        k = long_link(c, size)
        if k is not None and getattr(args, "lengths", None) is None:
            note.append(f"link {k:.0f}× size: ranked after")
        notes.append("; ".join(note))
    if any(notes):
        head = (*head, "note")
        rows = [(*rows[0], "note")] + [(*r, n) for r, n in zip(rows[1:], notes)]
    widths = [max(len(r[i]) for r in rows) for i in range(len(head))]
    for r in rows:
        print("  ".join(cell.rjust(w) for cell, w in zip(r, widths)).rstrip())
    return 0
