"""Type stubs of ``linkage._core.mechanism`` (see crates/linkage-py).

The mechanism builder and its mobility.
"""

from linkage._core import Mechanism as Mechanism

__all__ = [
    "CAPACITY",
    "RATE_MARGIN",
    "Mechanism",
    "degrees_of_freedom",
]

CAPACITY: int
RATE_MARGIN: float

def degrees_of_freedom(links: int, lower_pairs: int, higher_pairs: int) -> int: ...
