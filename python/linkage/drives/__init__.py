"""What turns the crank: motion laws, schedules, gear trains (:mod:`linkage.drive`) and cams (:mod:`linkage.cam`)."""

__all__: list[str] = []
