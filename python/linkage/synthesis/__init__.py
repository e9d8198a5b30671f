"""Dimensional synthesis of four-bars and slider-cranks for path generation.

The linkage sought is one whose coupler curve passes through given points.

``path(points)`` normalises the target's elliptic Fourier descriptors, looks up the nearest
shapes in an :class:`Atlas` of normalised four-bars (``kind="slider-crank"``: of normalised
offset slider-cranks; ``"any"``: both), places each in the target's frame, refines
the best by a least-squares fit of the true point-to-curve distance and, where the atlas does
not cover the target (an open curve, or no close match), searches globally by differential
evolution over the batch evaluator. Every candidate's circuit is swept by the tracker
(``check``) so none switches branch or passes an unassemblable sample; see ``docs/synthesis.md``.

Precision-point synthesis lives here too: :func:`motion` (Burmester, 3 or 4 poses) and
:func:`function` (Freudenstein), with their curves and types (``docs/precision-points.md``).
"""

from __future__ import annotations

import time
from collections.abc import Callable
from typing import Any, TypeVar

from linkage import _core as _core

# Every name of the module linkage.synthesis was, from the module that now holds it (`X as X`:
# re-exported, as mypy and ruff read it); isort would give each aliased name a statement.
# isort: off
from linkage.synthesis.precision_points import (
    centre_point_curve,
    chebyshev_points,
    circle_point_curve,
    Dyad,
    function,
    FunctionGenerator,
    motion,
    MotionCandidate,
)
from linkage.synthesis.kinds import (
    _ARC_KIND as _ARC_KIND,
    ARCS as ARCS,
    _atlas_kind as _atlas_kind,
    DEFAULT_ARC_ENTRIES as DEFAULT_ARC_ENTRIES,
    DEFAULT_ENTRIES as DEFAULT_ENTRIES,
    DEFAULT_SLIDER_ARC_ENTRIES as DEFAULT_SLIDER_ARC_ENTRIES,
    DEFAULT_SLIDER_ENTRIES as DEFAULT_SLIDER_ENTRIES,
    _ENTRY_WIDTH as _ENTRY_WIDTH,
    EXACT as EXACT,
    Float2D as Float2D,
    FOURBAR as FOURBAR,
    _KIND as _KIND,
    _Kind as _Kind,
    _kind as _kind,
    KINDS,
    SLIDER as SLIDER,
    SLIDER_ARCS as SLIDER_ARCS,
    _threads as _threads,
    TIGHT as TIGHT,
)
from linkage.synthesis.targets import (
    clean_target as clean_target,
    _csv_text as _csv_text,
    _DECIMAL_COMMA_SEPARATORS as _DECIMAL_COMMA_SEPARATORS,
    MIN_POINTS,
    _NUMBER_LIKE as _NUMBER_LIKE,
    POINTS_FILE_MAX as POINTS_FILE_MAX,
    read_points,
    rounded_to as rounded_to,
    _SEPARATORS as _SEPARATORS,
    SMALLEST_EXTENT as SMALLEST_EXTENT,
    _target as _target,
    target_size as target_size,
    _utf16_without_bom as _utf16_without_bom,
)
from linkage.synthesis.candidates import (
    _apart as _apart,
    _arms as _arms,
    Candidate,
    Candidates,
    change_point_gap,
    CHANGE_POINT_NEAR,
    _cognates as _cognates,
    CONSTRAINT_NAMES,
    _crossed as _crossed,
    _failed as _failed,
    _forms as _forms,
    _kept as _kept,
    largest_distance as largest_distance,
    _linkage_of as _linkage_of,
    LinkageT as LinkageT,
    _links as _links,
    LONG_LINK as LONG_LINK,
    long_link,
    _longest as _longest,
    longest_link,
    NEAR as NEAR,
    _params_of as _params_of,
    _pins as _pins,
    _ranked as _ranked,
    _same_pivots as _same_pivots,
    source_text,
    _third_pivot as _third_pivot,
    _turned as _turned,
    why_none,
)
from linkage.synthesis.atlas import (
    _ARC_FRACTIONS as _ARC_FRACTIONS,
    Atlas,
    ATLAS_FILES as ATLAS_FILES,
    ATLAS_FORMAT as ATLAS_FORMAT,
    ATLAS_HARMONICS_MAX as ATLAS_HARMONICS_MAX,
    atlas_kinds,
    _atlas_meta as _atlas_meta,
    ATLAS_META_MAX as ATLAS_META_MAX,
    ATLAS_SAMPLES_MAX as ATLAS_SAMPLES_MAX,
    _ATLAS_TEMP as _ATLAS_TEMP,
    _atlas_temps as _atlas_temps,
    AtlasArg as AtlasArg,
    _atlases as _atlases,
    _check_atlas as _check_atlas,
    default_atlas,
    _default_folder as _default_folder,
    _first_false as _first_false,
    is_cached,
    _meta_int as _meta_int,
    missing_atlases,
    _note_builds as _note_builds,
)
from linkage.synthesis.fitting import (
    _arc as _arc,
    _bounds as _bounds,
    _Budget as _Budget,
    _damped_solver as _damped_solver,
    _distinct as _distinct,
    _errors as _errors,
    _finish as _finish,
    _geodesic_lm as _geodesic_lm,
    GUARD as GUARD,
    LATER_EVALUATIONS as LATER_EVALUATIONS,
    LATER_POINTS as LATER_POINTS,
    _matched_curve as _matched_curve,
    _measure as _measure,
    _placed as _placed,
    _refine as _refine,
    _residuals as _residuals,
    SHORTEST_LINK as SHORTEST_LINK,
    _slid_along_curves as _slid_along_curves,
    STALL as STALL,
    STALL_WINDOW as STALL_WINDOW,
)
from linkage.synthesis.stages import (
    _atlas_pool as _atlas_pool,
    _cognate_candidates as _cognate_candidates,
    COGNATES_OF as COGNATES_OF,
    CURVE_EQUATION_POINTS as CURVE_EQUATION_POINTS,
    _equation_pool as _equation_pool,
    EQUATION_STARTS as EQUATION_STARTS,
    _evolution_starts as _evolution_starts,
    _from_parts as _from_parts,
    HOPS as HOPS,
    PART_FITS as PART_FITS,
    PART_GAP as PART_GAP,
    PART_MATCHES as PART_MATCHES,
    PART_POINTS as PART_POINTS,
    _parts as _parts,
    POLISH as POLISH,
    _polish as _polish,
    POLISH_NFEV as POLISH_NFEV,
    _restarts as _restarts,
    _shape_order as _shape_order,
    _shortfall as _shortfall,
    SLID as SLID,
    _slider_cognate as _slider_cognate,
    SLIDER_EQUATION_POINTS as SLIDER_EQUATION_POINTS,
    SLIDES as SLIDES,
    _tried as _tried,
    VALLEY as VALLEY,
    WIDER as WIDER,
)
from linkage.synthesis.search import (
    FAR as FAR,
    FIT_POINTS as FIT_POINTS,
    _moved as _moved,
    _pair as _pair,
    path,
    _progress_bar as _progress_bar,
    _spread as _spread,
    _unit_frame as _unit_frame,
    UNIT_RANGE as UNIT_RANGE,
)
# isort: on

__all__ = [
    "CHANGE_POINT_NEAR",
    "CONSTRAINT_NAMES",
    "KINDS",
    "MIN_POINTS",
    "Atlas",
    "Candidate",
    "Candidates",
    "Dyad",
    "FunctionGenerator",
    "MotionCandidate",
    "atlas_kinds",
    "centre_point_curve",
    "change_point_gap",
    "chebyshev_points",
    "circle_point_curve",
    "default_atlas",
    "function",
    "is_cached",
    "long_link",
    "longest_link",
    "missing_atlases",
    "motion",
    "path",
    "read_points",
    "source_text",
    "why_none",
]


_T = TypeVar("_T")


def timed(fn: Callable[..., _T], *args: Any, **kw: Any) -> tuple[_T, float]:
    """``fn(*args, **kw)`` and its wall time in seconds (for the benchmark and CLI)."""
    t0 = time.perf_counter()
    out = fn(*args, **kw)
    return out, time.perf_counter() - t0


# The public functions say they are linkage.synthesis's, as before the split (as numpy's
# set_module does): reprs, pickles by reference and the docs name the public path.
for _public in (
    atlas_kinds,
    change_point_gap,
    clean_target,
    default_atlas,
    is_cached,
    largest_distance,
    long_link,
    longest_link,
    missing_atlases,
    path,
    read_points,
    rounded_to,
    source_text,
    target_size,
    why_none,
):
    _public.__module__ = __name__
