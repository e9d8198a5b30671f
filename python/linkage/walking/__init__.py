"""Walking machines: the walker (:mod:`linkage.walker`), leg families (:mod:`linkage.legs`), gait searches (:mod:`linkage.gait_search`)."""

__all__: list[str] = []
