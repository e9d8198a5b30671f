"""Walking machines: the walker, leg families and gait searches.

The public paths are :mod:`linkage.walker`, :mod:`linkage.legs` and :mod:`linkage.gait_search`.
"""

__all__: list[str] = []
