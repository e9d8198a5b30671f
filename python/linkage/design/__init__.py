"""Walking-leg design search: a Pareto front of leg designs by NSGA-II, evaluated on Dask.

The search covers leg families and their figures from the core, evaluates candidates in chunks
(pymoo's NSGA-II, Dask), with checkpoints and a report.

A *family* is a parametrised leg generator with documented bounds and a reference point (the
design a source chose). A candidate's figures come from the core's leg figures
(``linkage_core::gait``; :func:`linkage._core.walking.four_bar_gaits` for four-bars, batched,
:func:`linkage._core.walking.leg_gait` on a swept foot path for multi-loop legs). The search is
deterministic for a seed: candidates are independent, chunks are gathered in order, and the
four-bar batch gives the same bits for any split, so the front is the same serially, on a
``LocalCluster`` or on a real cluster.

This module needs the optional packages ``pymoo`` and ``dask[distributed]``
(``pip install "linkage-kinematics[design]"``).
"""

from __future__ import annotations

try:
    import distributed  # noqa: F401
    import pymoo  # type: ignore[import-untyped]  # noqa: F401
except ImportError as _exc:
    raise ImportError(
        f"linkage.design needs the optional packages pymoo and dask[distributed] "
        f"(missing: {_exc.name}); install them with: pip install 'linkage-kinematics[design]'"
    ) from None

from linkage.design.report import chosen, main_design, scene_text, write_report
from linkage.design.search import (
    Constraints,
    Evaluator,
    Front,
    Study,
    evaluate_chunk,
    initial_population,
    objectives_and_constraints,
    pareto_front,
    placement,
    reference_figures,
    search,
)
from linkage.design.study_file import StudyFile, load_study
from linkage.walking.legs import (
    CRANK,
    FAMILIES,
    FIGURES,
    JANSEN_HOLY,
    KLANN_REF,
    OBJECTIVES,
    UNITS,
    Family,
    Settings,
    family,
)

__all__ = [
    "CRANK",
    "FAMILIES",
    "FIGURES",
    "JANSEN_HOLY",
    "KLANN_REF",
    "OBJECTIVES",
    "UNITS",
    "Constraints",
    "Evaluator",
    "Family",
    "Front",
    "Settings",
    "Study",
    "StudyFile",
    "chosen",
    "evaluate_chunk",
    "family",
    "initial_population",
    "load_study",
    "main_design",
    "objectives_and_constraints",
    "pareto_front",
    "placement",
    "reference_figures",
    "scene_text",
    "search",
    "write_report",
]
