"""Type stubs of ``linkage._core.catalog`` (see crates/linkage-py).

Named classic linkages.
"""

from collections.abc import Iterator
from typing import Any

from typing_extensions import final

from linkage._core import FourBar, Mechanism

__all__ = [
    "FOUR_BARS",
    "MULTI_LOOP",
    "CatalogLinkage",
    "four_bar",
    "linkage",
    "names",
]

def four_bar(name: str) -> FourBar: ...
def linkage(name: str, scale: float = 2.0) -> CatalogLinkage: ...
def names() -> tuple[list[str], list[str]]: ...

FOUR_BARS: list[str]
MULTI_LOOP: list[str]

@final
class CatalogLinkage:
    """A catalogued multi-loop linkage (``linkage_core::catalog::Linkage``)."""

    @property
    def mechanism(self) -> Mechanism: ...
    @property
    def joint_names(self) -> list[str]: ...
    @property
    def trace(self) -> int: ...
    def astuple(self) -> tuple[Mechanism, list[str], int]: ...
    def __len__(self) -> int: ...
    def __getitem__(self, index: int, /) -> Any: ...
    def __iter__(self) -> Iterator[Any]: ...
