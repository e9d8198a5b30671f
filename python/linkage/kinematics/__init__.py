"""The kinematics API: mechanisms, four-bars, slider-cranks, their sweeps, mobility, batches.

The public names are those of :mod:`linkage` (``linkage.Mechanism``, ``linkage.FourBar``, ...).
"""

__all__: list[str] = []
