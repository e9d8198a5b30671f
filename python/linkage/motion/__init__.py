"""Geometry of motion: instant centres, curvature, inflection circle, straightness (:mod:`linkage.geometry`)."""

__all__: list[str] = []
