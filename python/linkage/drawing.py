"""What to draw of a linkage or a walker, from its structure.

The drawing is a model independent of any plotting library, shared by the PNG/GIF report
(:mod:`linkage.report`), the HTML report and the CAD export.

API
---
``mechanism_drawing(mech, sweep, units="") -> Drawing``
    A :class:`~linkage.FourBar` or :class:`~linkage.Mechanism` swept by ``mech.sweep(theta)``.
``walker_drawing(walker, sim, view="side" | "top", leg_theta=None, units="") -> Drawing``
    Every leg's linkage on the body at its mount, in the body frame (x forward, y left, z up):
    ``"side"`` draws (x, z) with the ground line, ``"top"`` draws (x, y) with the support polygon
    and the centre of gravity's projection. ``leg_theta`` (N, legs) gives each leg's crank angle
    when it is not the drive's plus the leg's phase (a per-leg crank schedule).
``leg_angles(walker, sim, drive, per_leg_time) -> (N, legs)``
    Each leg's crank angle as :meth:`~linkage.Walker.simulate` ran it (for ``leg_theta``).
``path_window(path, grow=0.5) -> Bounds`` and ``clip_to(points, bounds) -> points``
    A window around a path, and points outside it set to NaN (centres of curvature, instant
    centres: they must never set a plot's limits).

``Drawing`` (frozen dataclass), N samples, J joints, L legs:

- ``joint_names: tuple[str, ...]`` — J names (a walker's are ``"<leg>.<joint>"``, plus
  ``"<leg>.foot"`` joined to the trace point by the bar ``"<leg>.foot bar"`` when the leg has a
  foot offset or a lift);
- ``positions: (N, J, 2)`` — joint positions per sample, NaN where a sample did not assemble;
  ``frame(i)`` is ``positions[i]``; ``len(drawing)`` is N;
- ``links: tuple[LinkShape, ...]`` — ``LinkShape(name, joints, kind, leg)``: ``joints`` index
  ``joint_names``; ``kind`` is ``"ground"`` (the fixed joints: draw nothing but the
  :attr:`pivots`), ``"bar"`` (a binary link, or a link whose joints lie on one line: a polyline
  through ``joints`` in order along it) or ``"plate"`` (three or more joints off one line: a
  filled polygon, ``joints`` in order around it); ``leg`` is the walker leg's index, else None;
- ``pivots: tuple[int, ...]`` — ground pivots (fixed joints a moving link turns about): the
  hatched ground symbol (for a walker, only of legs whose plane is the view's);
- ``sliders: tuple[SliderShape, ...]`` — ``SliderShape(joint, origin, direction)``: a block at
  ``joint`` sliding on the guide line through ``origin`` along the unit ``direction`` (N, 2);
- ``trace: int | None`` — the trace joint; ``paths: dict[str, (N, 2)]`` — traced paths by
  legend label (the trace point's, or each walker foot's);
- ``units: str`` (may be empty), ``axes: (str, str)`` — axis names (``"x"``, ``"y"`` or ``"z"``);
- walkers only (else None / empty): ``ground: float | None`` (height of the ground line, side
  view), ``body: (M, 2)`` (closed outline of the body, static in the body frame),
  ``feet: (N, L, 2)``, ``stance: (N, L) bool``, ``legs: tuple[str, ...]`` (names),
  ``leg_labels: tuple[str, ...]`` (L1…R3, front to rear: :func:`linkage.walker.leg_labels`),
  ``support: (N, K, 2)`` (support polygon, NaN-padded, top view) and ``cg: (x, y)`` (top view);
- ``bounds(margin=0.06) -> (xmin, xmax, ymin, ymax)`` — from the joints, paths, feet, body,
  support polygons and ground line only, grown by ``margin`` of the larger extent.

>>> import numpy as np, linkage
>>> from linkage.drawing import mechanism_drawing
>>> fb = linkage.FourBar(ground=20, crank=10, coupler=25, rocker=25, point=(50, 0))
>>> d = mechanism_drawing(fb, fb.sweep(np.linspace(0, 2 * np.pi, 9)))
>>> for k in d.links:
...     print(k.name, k.kind, "-".join(d.joint_names[j] for j in k.joints))
ground ground O-C
crank bar O-A
coupler bar A-B-P
rocker bar C-B
>>> [d.joint_names[j] for j in d.pivots], d.positions.shape
(['O', 'C'], (9, 5, 2))
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import cached_property
from typing import Any, Literal, get_args

import numpy as np
from numpy.typing import NDArray

from linkage._core import LinkageError
from linkage._shared.arrays import said
from linkage._shared.choices import View
from linkage.drives.drive import Drive
from linkage.kinematics.fourbar import FourBar
from linkage.kinematics.mechanism import Mechanism
from linkage.kinematics.sweep import Sweep
from linkage.walking.walker import Simulation, Walker

Array = NDArray[np.float64]
Bounds = tuple[float, float, float, float]
LinkKind = Literal["ground", "bar", "plate"]

__all__ = [
    "Bounds",
    "Drawing",
    "LinkShape",
    "SliderShape",
    "clip_to",
    "leg_angles",
    "mechanism_drawing",
    "path_window",
    "sagittal_pivots",
    "walker_drawing",
]


@dataclass(frozen=True)
class LinkShape:
    """One rigid link: its joints (indices into :attr:`Drawing.joint_names`) and how to draw it."""

    name: str
    joints: tuple[int, ...]
    kind: LinkKind
    """"ground" (draw its :attr:`Drawing.pivots`), "bar" (polyline) or "plate" (polygon)."""
    leg: int | None = None
    """Index of the walker leg the link belongs to (None for a mechanism)."""


@dataclass(frozen=True)
class SliderShape:
    """A slider block at ``joint`` on the guide through ``origin`` along ``direction``."""

    joint: int
    origin: int
    direction: Array
    """Unit direction of the guide per sample, (N, 2)."""
    leg: int | None = None


@dataclass(frozen=True)
class Drawing:
    """A linkage or a walker view to draw, sample by sample (see the module docstring)."""

    joint_names: tuple[str, ...]
    positions: Array
    links: tuple[LinkShape, ...]
    pivots: tuple[int, ...]
    sliders: tuple[SliderShape, ...] = ()
    trace: int | None = None
    paths: dict[str, Array] = field(default_factory=dict)
    units: str = ""
    axes: tuple[str, str] = ("x", "y")
    ground: float | None = None
    body: Array | None = None
    feet: Array | None = None
    stance: NDArray[np.bool_] | None = None
    legs: tuple[str, ...] = ()
    leg_labels: tuple[str, ...] = ()
    support: Array | None = None
    cg: tuple[float, float] | None = None

    def __len__(self) -> int:
        """Return the number of samples drawn."""
        return int(self.positions.shape[0])

    def frame(self, i: int) -> Array:
        """Joint positions at sample ``i``, (J, 2).

        Examples
        --------
        >>> import numpy as np, linkage
        >>> from linkage.drawing import mechanism_drawing
        >>> fb = linkage.FourBar(ground=20, crank=10, coupler=25, rocker=25, point=(50, 0))
        >>> d = mechanism_drawing(fb, fb.sweep(np.array([0.0, np.pi / 2])))
        >>> d.joint_names, d.frame(1).round(3)
        (('O', 'C', 'A', 'B', 'P'), array([[ 0.,  0.],
               [20.,  0.],
               [ 0., 10.],
               [20., 25.],
               [40., 40.]]))
        """
        f: Array = self.positions[i]
        return f

    def bounds(self, margin: float = 0.06) -> Bounds:
        """Return ``(xmin, xmax, ymin, ymax)`` of everything drawn, grown by ``margin`` a side.

        ``margin`` is a fraction of the larger extent; centres of curvature and instant centres do
        not count.

        Examples
        --------
        >>> import numpy as np, linkage
        >>> from linkage.drawing import mechanism_drawing
        >>> fb = linkage.FourBar(ground=20, crank=10, coupler=25, rocker=25, point=(50, 0))
        >>> d = mechanism_drawing(fb, fb.sweep(np.linspace(0, 2 * np.pi, 9)))
        >>> [round(v, 3) for v in d.bounds(margin=0)]    # the crank circle, the foot path
        [-10.0, 42.926, -10.0, 48.99]
        >>> [round(v, 3) for v in d.bounds()]            # 6 % of the larger extent (58.99) a side
        [-13.539, 46.466, -13.539, 52.529]
        """
        lo, hi = self._box
        return _grow(lo, hi, margin)

    @cached_property
    def _box(self) -> tuple[Array, Array]:
        parts = [self.positions.reshape(-1, 2)]
        parts += [p.reshape(-1, 2) for p in self.paths.values()]
        for extra in (self.feet, self.body, self.support):
            if extra is not None:
                parts.append(extra.reshape(-1, 2))
        pts = np.concatenate(parts)
        pts = pts[np.isfinite(pts).all(axis=1)]
        if not len(pts):
            raise LinkageError("nothing to draw: no sample assembled")
        lo, hi = pts.min(axis=0), pts.max(axis=0)
        if self.ground is not None:
            lo[1], hi[1] = min(lo[1], self.ground), max(hi[1], self.ground)
        if self.cg is not None:
            lo, hi = np.minimum(lo, self.cg), np.maximum(hi, self.cg)
        return lo, hi


def _grow(lo: Array, hi: Array, margin: float) -> Bounds:
    span = float(max(hi[0] - lo[0], hi[1] - lo[1]))
    if not span > 0:
        span = max(1.0, float(np.abs(np.r_[lo, hi]).max()))
    g = margin * span
    return (float(lo[0] - g), float(hi[0] + g), float(lo[1] - g), float(hi[1] + g))


def path_window(path: Array, grow: float = 0.5) -> Bounds:
    """Return the bounding box of a path's finite points, grown on each side by ``grow``.

    ``grow`` is a fraction of its larger extent: the box is the region a plot of the path (with its
    evolute) should show.

    Examples
    --------
    >>> import numpy as np
    >>> from linkage.drawing import path_window
    >>> path_window(np.array([[0.0, 0.0], [10.0, 0.0], [10.0, 5.0], [np.nan, np.nan]]))
    (-5.0, 15.0, -5.0, 10.0)
    >>> path_window(np.full((3, 2), np.nan))
    Traceback (most recent call last):
    ...
    linkage.LinkageError: the path has no finite point
    """
    p = np.asarray(path, dtype=float).reshape(-1, 2)
    p = p[np.isfinite(p).all(axis=1)]
    if not len(p):
        raise LinkageError("the path has no finite point")
    return _grow(p.min(axis=0), p.max(axis=0), grow)


def clip_to(points: Array, bounds: Bounds) -> Array:
    """``points`` (..., 2) with those outside ``bounds`` (or not finite) set to NaN.

    Examples
    --------
    >>> import numpy as np
    >>> from linkage.drawing import clip_to
    >>> clip_to(np.array([[1.0, 1.0], [100.0, 1.0], [np.inf, 0.0]]), (0.0, 10.0, 0.0, 10.0))
    array([[ 1.,  1.],
           [nan, nan],
           [nan, nan]])
    """
    p = np.array(points, dtype=float)
    x0, x1, y0, y1 = bounds
    with np.errstate(invalid="ignore"):
        out = ~((p[..., 0] >= x0) & (p[..., 0] <= x1) & (p[..., 1] >= y0) & (p[..., 1] <= y1))
    p[out] = np.nan
    return p


# -- mechanisms ---------------------------------------------------------------------------------


@dataclass(frozen=True)
class _Structure:
    mechanism: Mechanism
    """The program (a FourBar's as a Mechanism)."""
    names: tuple[str, ...]
    links: tuple[LinkShape, ...]
    pivots: tuple[int, ...]
    sliders: tuple[tuple[int, int], ...]
    """(joint, origin) per slider."""
    trace: int

    def slider_directions(self, positions: Array) -> list[Array]:
        """Return each slider's unit line direction (N, 2) at joint positions (N, J, 2).

        The core computes them (``Mechanism::line_directions``): NaN where undetermined.
        """
        rows = np.ascontiguousarray(positions, dtype=np.float64)
        return [self.mechanism._core.line_directions(j, rows) for j, _ in self.sliders]


def _structure(mech: FourBar | Mechanism, reference: Array) -> _Structure:
    """Find the links, pivots and sliders of ``mech``.

    ``reference`` (J, 2) is one assembled pose, used to order a link's joints along a line or around
    a polygon.
    """
    m = mech.mechanism() if isinstance(mech, FourBar) else mech
    names = m.joint_names
    link_names = m.links
    members = m.link_members()
    index = {n: k for k, n in enumerate(names)}
    links: list[LinkShape] = []
    moving: set[int] = set()
    for name, ms in zip(link_names, members):
        idx = tuple(index[n] for n in ms)
        if name == "ground" and not links:
            links.append(LinkShape(name, idx, "ground"))
            continue
        if len(idx) < 2:  # a slider's block: drawn with its guide
            continue
        moving.update(idx)
        kind, order = _shape(idx, reference)
        links.append(LinkShape(name, order, kind))
    ground = links[0].joints if links and links[0].kind == "ground" else ()
    pivots = tuple(j for j in ground if j in moving)
    sliders = tuple(
        (k, int(c["origin"]))
        for k, c in enumerate(m._core.constructions())
        if c["kind"] == "slider"
    )
    trace = index[m.trace] if m.trace is not None else len(names) - 1
    return _Structure(m, names, tuple(links), pivots, sliders, trace)


def _shape(idx: tuple[int, ...], ref: Array) -> tuple[LinkKind, tuple[int, ...]]:
    """Return a link's kind and joint order.

    Joints are ordered along the line for collinear joints (a bar), around the centroid otherwise (a
    plate).
    """
    if len(idx) == 2:
        return "bar", idx
    p = ref[list(idx)]
    if not np.isfinite(p).all():
        return "plate", idx
    c = p.mean(axis=0)
    d = p - c
    _, sv, vt = np.linalg.svd(d)
    size = float(sv[0]) if len(sv) else 0.0
    thin = len(sv) < 2 or float(sv[1]) <= 1e-6 * max(size, 1e-300)
    if thin:
        along = d @ vt[0]
        return "bar", tuple(idx[k] for k in np.argsort(along, kind="stable"))
    ang = np.arctan2(d[:, 1], d[:, 0])
    return "plate", tuple(idx[k] for k in np.argsort(ang, kind="stable"))


def _first_valid(positions: Array) -> Array:
    ok = np.isfinite(positions).all(axis=(1, 2))
    if not ok.any():
        raise LinkageError("nothing to draw: no sample assembled")
    row: Array = positions[int(np.argmax(ok))]
    return row


def mechanism_drawing(mech: FourBar | Mechanism, sweep: Sweep, units: str = "") -> Drawing:
    """Draw ``mech`` at every sample of ``sweep`` (``mech.sweep(theta)``).

    The drawing holds its links from the program's structure, ground pivots, sliders, and the trace
    point with its path.

    Raises
    ------
    LinkageError
        If ``sweep`` is not a sweep of ``mech`` or no sample assembled.

    Examples
    --------
    >>> import numpy as np, linkage
    >>> from linkage.drawing import mechanism_drawing
    >>> fb = linkage.FourBar(ground=20, crank=10, coupler=25, rocker=25, point=(50, 0))
    >>> d = mechanism_drawing(fb, fb.sweep(np.linspace(0, 2 * np.pi, 9)), units="mm")
    >>> len(d), list(d.paths), d.joint_names[d.trace], d.units
    (9, ['trace P'], 'P', 'mm')

    A four-bar whose coupler and rocker cannot reach across the ground has nothing to draw:

    >>> short = linkage.FourBar(ground=20, crank=10, coupler=4, rocker=4)
    >>> mechanism_drawing(short, short.sweep(np.linspace(0.1, 1.0, 3)))
    Traceback (most recent call last):
    ...
    linkage.LinkageError: nothing to draw: no sample assembled
    """
    if not isinstance(mech, (FourBar, Mechanism)):
        raise TypeError(f"mech must be a FourBar or Mechanism, got {type(mech).__name__}")
    if not isinstance(sweep, Sweep):
        raise TypeError(f"sweep must be a Sweep, got {type(sweep).__name__}")
    pos = np.asarray(sweep.joints, dtype=float)
    if pos.ndim == 2:
        pos = pos[None]
    st = _structure(mech, _first_valid(pos))
    if tuple(sweep.joint_names) != st.names:
        raise LinkageError(
            f"the sweep's joints {sweep.joint_names} are not the mechanism's {st.names}"
        )
    sliders = tuple(
        SliderShape(j, o, d) for (j, o), d in zip(st.sliders, st.slider_directions(pos))
    )
    trace = st.names.index(sweep.trace)
    return Drawing(
        joint_names=st.names,
        positions=pos,
        links=st.links,
        pivots=st.pivots,
        sliders=sliders,
        trace=trace,
        paths={f"trace {sweep.trace}": pos[:, trace].copy()},
        units=units,
    )


# -- walkers ------------------------------------------------------------------------------------


def walker_drawing(
    walker: Walker,
    sim: Simulation,
    view: View = "side",
    leg_theta: Array | None = None,
    units: str = "",
) -> Drawing:
    """Draw the walker ``walker`` over the simulation ``sim`` (``walker.simulate(...)``).

    In the body frame: every leg's linkage at its mount, the foot bar (a foot offset or a lift) to
    the foot, the body outline, the feet with their stance flags and paths, and in the ``"side"``
    view (x, z) the ground line, in the ``"top"`` view (x, y) the support polygons and the centre of
    gravity's projection.

    ``leg_theta`` (N, legs) overrides each leg's crank angle (default: ``sim.theta`` plus the
    leg's phase; give it for a per-leg-time schedule).

    Raises
    ------
    LinkageError
        For an unknown ``view``, a ``leg_theta`` of the wrong shape, or a leg that does not
        assemble at a sample.

    Examples
    --------
    >>> import numpy as np, linkage
    >>> from linkage.drawing import walker_drawing
    >>> w = linkage.catalog.quadruped_hoecken()
    >>> sim = w.simulate(np.linspace(0, 2 * np.pi, 9))
    >>> side = walker_drawing(w, sim, "side", units="mm")
    >>> side.axes, side.ground, side.leg_labels, side.positions.shape
    (('x', 'z'), -60.0, ('L1', 'R1', 'L2', 'R2'), (9, 24, 2))
    >>> side.joint_names[:6]          # leg A's joints and its foot at the end of the foot bar
    ('A.O', 'A.C', 'A.A', 'A.B', 'A.P', 'A.foot')
    >>> top = walker_drawing(w, sim, "top")
    >>> top.axes, top.cg, top.ground
    (('x', 'y'), (0.0, 0.0), None)
    >>> walker_drawing(w, sim, "front")
    Traceback (most recent call last):
    ...
    linkage.LinkageError: view must be 'side' or 'top', got 'front'
    """
    if not isinstance(walker, Walker):
        raise TypeError(f"walker must be a Walker, got {type(walker).__name__}")
    if not isinstance(sim, Simulation):
        raise TypeError(f"sim must be a Simulation, got {type(sim).__name__}")
    if view not in get_args(View):
        raise LinkageError(f"view must be {said(get_args(View))}, got {view!r}")
    n, m = sim.feet.shape[:2]
    if m != len(walker.legs):
        raise LinkageError(f"the simulation has {m} legs, the walker {len(walker.legs)}")
    if leg_theta is None:
        leg_theta = sim.theta[:, None] + walker.phases[None, :]
    leg_theta = np.asarray(leg_theta, dtype=float)
    if leg_theta.shape != (n, m):
        raise LinkageError(f"leg_theta must be ({n}, {m}), got {leg_theta.shape}")
    axes = (0, 2) if view == "side" else (0, 1)
    names: list[str] = []
    links: list[LinkShape] = []
    pivots: list[int] = []
    sliders: list[SliderShape] = []
    blocks: list[Array] = []
    fixed_pts: list[Array] = []
    for li, leg in enumerate(walker.legs):
        s = leg.linkage.sweep(leg_theta[:, li])
        p2 = np.asarray(s.joints, dtype=float)
        if not np.isfinite(p2).all():
            raise LinkageError(f"leg {leg.name!r} does not assemble at every sample")
        st = _structure(leg.linkage, p2[0])
        base = len(names)
        names += [f"{leg.name}.{j}" for j in st.names]
        p3 = _to_body(leg, p2)
        off = np.asarray(leg.foot_offset, dtype=float)
        foot2 = p2[:, st.trace] + off
        foot3 = _to_body(leg, foot2[:, None])[:, 0]
        if leg.lift is not None:
            h, _, _, _ = leg.lift.eval(np.mod(leg_theta[:, li], 2 * math.pi))
            foot3[:, 2] += h
        has_foot = bool(np.any(off != 0) or leg.lift is not None)
        if has_foot:
            names.append(f"{leg.name}.foot")
            p3 = np.concatenate([p3, foot3[:, None]], axis=1)
        blocks.append(p3[:, :, axes])
        for k in st.links:
            joints = tuple(base + j for j in k.joints)
            links.append(LinkShape(f"{leg.name}.{k.name}", joints, k.kind, li))
            if k.kind == "ground":
                fixed_pts.append(p3[0, list(k.joints)])
        if has_foot:
            links.append(
                LinkShape(f"{leg.name}.foot bar", (base + st.trace, len(names) - 1), "bar", li)
            )
        if (leg.plane == "sagittal") == (view == "side"):
            # The ground symbol only where the leg's plane faces the viewer.
            pivots += [base + j for j in st.pivots]
        for (j, o), d in zip(st.sliders, st.slider_directions(p2)):
            d3 = _to_body(leg, d[:, None], vector=True)[:, 0][:, axes]
            sliders.append(SliderShape(base + j, base + o, d3, li))
    pos = np.concatenate(blocks, axis=1)
    feet = sim.feet[:, :, axes]
    labels = walker.leg_labels()
    body = _body_outline(np.concatenate(fixed_pts), walker, axes)
    return Drawing(
        joint_names=tuple(names),
        positions=pos,
        links=tuple(links),
        pivots=tuple(pivots),
        sliders=tuple(sliders),
        trace=None,
        paths={lab: feet[:, i] for i, lab in enumerate(labels)},
        units=units,
        axes=("x", "z") if view == "side" else ("x", "y"),
        ground=float(sim.ground) if view == "side" else None,
        body=body,
        feet=feet,
        stance=sim.stance,
        legs=tuple(sim.legs),
        leg_labels=labels,
        support=sim.support if view == "top" else None,
        cg=(float(walker.cg[0]), float(walker.cg[1])) if view == "top" else None,
    )


def sagittal_pivots(walker: Any, sim: Any) -> Array:
    """Return the fixed pivots of ``walker``'s sagittal legs in the body frame, (k, 3).

    The joints :func:`walker_drawing`'s side view marks as pivots, from one pose of each leg (at
    the run's first sample) instead of the whole run; (0, 3) when no leg is sagittal.
    """
    out = [np.empty((0, 3))]
    for li, leg in enumerate(walker.legs):
        if leg.plane != "sagittal":
            continue
        theta = float(sim.theta[0] + walker.phases[li])
        p2 = np.asarray(leg.linkage.sweep(np.array([theta])).joints, dtype=float)
        if not np.isfinite(p2).all():
            raise LinkageError(f"leg {leg.name!r} does not assemble at every sample")
        st = _structure(leg.linkage, p2[0])
        out.append(_to_body(leg, p2)[0, list(st.pivots)])
    return np.concatenate(out)


def _to_body(leg: Any, p2: Array, vector: bool = False) -> Array:
    """Linkage-plane points (N, J, 2) of ``leg`` in the body frame (N, J, 3)."""
    side = -1.0 if leg.mirror else 1.0
    mx, my, mz = (0.0, 0.0, 0.0) if vector else leg.mount
    out = np.empty((*p2.shape[:2], 3))
    out[..., 0] = mx + p2[..., 0]
    if leg.plane == "sagittal":
        out[..., 1] = my
        out[..., 2] = mz + side * p2[..., 1]
    else:
        out[..., 1] = my + side * p2[..., 1]
        out[..., 2] = mz
    return out


def _body_outline(fixed: Array, walker: Any, axes: tuple[int, int]) -> Array:
    """Return a rectangle over the legs' fixed joints as a closed outline in the view's axes.

    The fixed joints are the frame the legs are mounted on.
    """
    lo, hi = fixed.min(axis=0), fixed.max(axis=0)
    span = float(max(hi[0] - lo[0], 1e-300))
    if axes == (0, 2):
        # Side view: a slab from the body's underside up to the highest fixed joint.
        z0 = min(float(walker.body_underside), float(lo[2]))
        z1 = max(float(hi[2]), z0 + 0.12 * span)
        y0, y1 = z0, z1
    else:
        y0, y1 = float(lo[1]), float(hi[1])
        if y1 - y0 < 0.12 * span:
            mid = 0.5 * (y0 + y1)
            y0, y1 = mid - 0.06 * span, mid + 0.06 * span
    x0, x1 = float(lo[0]), float(hi[0])
    out: Array = np.array([[x0, y0], [x1, y0], [x1, y1], [x0, y1], [x0, y0]])
    return out


def leg_angles(walker: Walker, sim: Simulation, drive: Drive | None, per_leg_time: bool) -> Array:
    """Return each leg's crank angle per sample, (N, legs).

    The drive's angle plus the leg's phase, or with ``per_leg_time`` the drive (a periodic one,
    with a ``period``) run shifted by the phase's share of its period (as
    :meth:`linkage.Walker.simulate` does).

    Raises
    ------
    LinkageError
        With ``per_leg_time`` and a drive that has no period.

    Examples
    --------
    Hoecken's quadruped (legs A and D in phase, B and C half a turn behind) driven by one
    cycloidal turn a second, at a quarter of a second:

    >>> import numpy as np, linkage
    >>> from linkage.drawing import leg_angles
    >>> from linkage.drive import Program, Segment
    >>> w = linkage.catalog.quadruped_hoecken()
    >>> turn = Program(0.0, [Segment(1.0, 2 * np.pi, "cycloidal")])
    >>> sim = w.simulate(time=np.linspace(0.0, 1.0, 5), drive=turn, per_leg_time=True)
    >>> np.degrees(leg_angles(w, sim, turn, per_leg_time=False)[1]).round(1)  # angle + phase
    array([  32.7, -147.3, -147.3,   32.7])
    >>> np.degrees(leg_angles(w, sim, turn, per_leg_time=True)[1]).round(1)   # time + phase
    array([ 32.7, -32.7, -32.7,  32.7])
    >>> leg_angles(w, w.simulate(np.linspace(0, 2 * np.pi, 5)), None, per_leg_time=True)
    Traceback (most recent call last):
    ...
    linkage.LinkageError: per_leg_time needs a periodic drive (with a period)
    """
    if not per_leg_time:
        out: Array = sim.theta[:, None] + walker.phases[None, :]
        return out
    if drive is None or not hasattr(drive, "period"):
        raise LinkageError("per_leg_time needs a periodic drive (with a period)")
    period = float(drive.period)
    cols = []
    for leg in walker.legs:
        shift = leg.phase / (2 * math.pi) * period
        th, _, _ = drive.angles(sim.time + shift)
        cols.append(np.asarray(th, dtype=float))
    return np.stack(cols, axis=1)
