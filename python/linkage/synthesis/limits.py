"""The largest searches path synthesis takes.

:func:`~linkage.synthesis.path` holds its arguments to them, and a scene's ``[synthesis]``
section its keys.
"""

from __future__ import annotations

__all__ = ["POINTS_MAX", "SYNTHESIS_REFINE_MAX", "SYNTHESIS_TOP_MAX"]

SYNTHESIS_TOP_MAX = 50
"""Most candidates a search may ask for (``top``), of :func:`path` or a ``[synthesis]`` scene."""
SYNTHESIS_REFINE_MAX = 200
"""Most atlas matches a search may ask to refine (``refine``; the search's time grows with it)."""
POINTS_MAX = 10_000
"""Most target points of a search (each costs a distance per candidate)."""
