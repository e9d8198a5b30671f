"""The straight-line linkages of the source documents (DOMAIN.md), ready to sweep.

Four-bars are placed with the crank pivot ``O`` at the origin and the rocker pivot ``C`` on the
+x axis (lengths in mm, thesis 1 chapter 1 after Norton); multi-loop linkages are
:class:`~linkage.Mechanism`\\ s whose ``trace`` is the straight-line point.

>>> import linkage
>>> linkage.catalog.hoecken().grashof()
'crank-rocker'
>>> [round(float(x), 1) for x in linkage.catalog.evans_b().input_limits()]
[-1.4, 1.4]
>>> linkage.catalog.get("nope")
Traceback (most recent call last):
...
linkage.LinkageError: unknown catalogue linkage 'nope'; choose from watt, roberts, ...
"""

from __future__ import annotations

from linkage import _core
from linkage._core import LinkageError
from linkage._fourbar import FourBar
from linkage._mechanism import Mechanism

FOUR_BARS: tuple[str, ...] = tuple(_core.catalog_names()[0])
MULTI_LOOP: tuple[str, ...] = tuple(_core.catalog_names()[1])


def _four_bar(name: str) -> FourBar:
    return FourBar._from_core(_core.catalog_four_bar(name))


def _linkage(name: str, scale: float = 2.0) -> Mechanism:
    core, names, trace = _core.catalog_linkage(name, scale)
    return Mechanism._from_core(core, names, trace)


def watt() -> FourBar:
    """Watt: ground 40, rockers 20, coupler 10, midpoint trace (triple rocker)."""
    return _four_bar("watt")


def roberts() -> FourBar:
    """Roberts: ground 40, rockers 40, coupler 20, apex of the isosceles triangle AP = BP = 40."""
    return _four_bar("roberts")


def chebyshev() -> FourBar:
    """Chebyshev: ground 20, crossed rockers 25, coupler 10, midpoint trace (double rocker)."""
    return _four_bar("chebyshev")


def hoecken() -> FourBar:
    """Hoecken: ground 20, crank 10, coupler = rocker = 25, foot 50 along the coupler line."""
    return _four_bar("hoecken")


def evans_a() -> FourBar:
    """Evans A: 12 / 10 / 16 / 10.39, trace 26.9 along the coupler (input ≈ 27°…333°)."""
    return _four_bar("evans_a")


def evans_b() -> FourBar:
    """Evans B: 23.05 / 10 / 12 / 11.67, trace 15 along the coupler (input ≈ ±81°)."""
    return _four_bar("evans_b")


def evans_c() -> FourBar:
    """Evans C: 20 / 10 / 10 / 10, trace 10 beyond B on the coupler line (input ≈ ±75°)."""
    return _four_bar("evans_c")


def peaucellier() -> Mechanism:
    """Peaucellier–Lipkin inversor: D at the origin, crank pivot O at (15, 0), crank 15, arms
    DB = DC = 40, rhombus 20; P runs on the exact line x = 40."""
    return _linkage("peaucellier")


def hart() -> Mechanism:
    """Hart's inversor (six links, seven revolutes); P runs on the exact line x = 7.5."""
    return _linkage("hart")


def hoecken_pantograph(scale: float = 2.0) -> Mechanism:
    """The Hoecken linkage driving a pantograph that scales its foot path ``T`` by ``scale``
    (> 1) about the pivot Q = (20, 80); the output is ``P = Q + scale·(T − Q)``."""
    return _linkage("hoecken_pantograph", scale)


def names() -> tuple[str, ...]:
    """Every catalogue name."""
    return FOUR_BARS + MULTI_LOOP


def get(name: str) -> FourBar | Mechanism:
    """A catalogue linkage by name."""
    if name in FOUR_BARS:
        return _four_bar(name)
    if name in MULTI_LOOP:
        return _linkage(name)
    raise LinkageError(f"unknown catalogue linkage {name!r}; choose from {', '.join(names())}")
