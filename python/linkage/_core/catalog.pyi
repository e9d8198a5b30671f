"""Type stubs of ``linkage._core.catalog`` (see crates/linkage-py).

Named classic linkages.
"""

from linkage._core import FourBar, Mechanism

__all__ = [
    "four_bar",
    "linkage",
    "names",
]

def four_bar(name: str) -> FourBar: ...
def linkage(name: str, scale: float = 2.0) -> tuple[Mechanism, list[str], int]: ...
def names() -> tuple[list[str], list[str]]: ...
