"""Joint reactions and driver torque (:mod:`linkage.forces`)."""

__all__: list[str] = []
