"""Geometry of motion: instant centres, curvature, inflection circle, straightness.

The public path is :mod:`linkage.geometry`.
"""

__all__: list[str] = []
