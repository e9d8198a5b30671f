"""What turns the crank: motion laws, schedules and gear trains (:mod:`linkage.drive`), cams.

The public paths are :mod:`linkage.drive` and :mod:`linkage.cam`.
"""

__all__: list[str] = []
