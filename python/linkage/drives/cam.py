"""Disc cams with translating roller or flat-faced followers.

Each gives its pitch curve, profile, pressure angle and radius of curvature, with undercut and
pressure-angle checks.

The follower's motion is a :class:`linkage.drive.Program` in cam angle (radians → length) that
spans exactly one turn. The cam turns counter-clockwise; coordinates are in the cam's frame.

>>> import numpy as np
>>> from linkage.cam import DiscCam, leg_lift_cam
>>> p = leg_lift_cam().profile(361)
>>> round(float(p.displacement.max()), 6), p.undercut
(1.4, False)
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import NDArray

from linkage import _core
from linkage._core import LinkageError
from linkage._shared.arrays import as_count, as_finite, as_length, check_memory
from linkage.drives.drive import Program, Segment

__all__ = ["CamProfile", "DiscCam", "leg_lift", "leg_lift_cam"]

Array = NDArray[np.float64]


@dataclass
class CamProfile:
    """A cam's geometry sampled over one turn."""

    phi: Array
    """Cam angles (rad)."""
    displacement: Array
    """Follower displacement ``s(φ)``."""
    pitch: Array
    """Pitch curve (roller centres; for a flat face, its point on the axis), shape (n, 2)."""
    profile: Array
    """Cam profile, shape (n, 2)."""
    pressure_angle: Array
    """Pressure angle (rad, signed); zero for a flat-faced follower."""
    pitch_radius: Array
    """Signed radius of curvature of the pitch curve (positive where convex)."""
    profile_radius: Array
    """Signed radius of curvature of the profile (a convex part with a negative value is
    undercut)."""
    problems: list[str] = field(default_factory=list)
    """Undercut and pressure-angle findings, in words; empty when the cam is sound."""

    @property
    def undercut(self) -> bool:
        """Whether the profile is undercut (loops or cusps: the follower cannot trace it)."""
        return any(p.startswith("undercut") for p in self.problems)

    @property
    def max_pressure_angle(self) -> float:
        """Largest |pressure angle| (rad)."""
        return float(np.max(np.abs(self.pressure_angle)))

    def check(self) -> CamProfile:
        """Return the profile itself if it is sound, else raise listing its problems.

        Returns
        -------
        CamProfile
            ``self``, when :attr:`problems` is empty.

        Raises
        ------
        LinkageError
            Naming every problem (undercut, pressure angle over the limit).

        Examples
        --------
        A 10 mm cycloidal rise over a quarter turn on a 5 mm base circle is too steep:

        >>> import math
        >>> from linkage.cam import DiscCam
        >>> from linkage.drive import Program, Segment
        >>> rise = Program(0.0, [Segment(math.pi / 2, 10.0, "cycloidal"), Segment(math.pi),
        ...                      Segment(math.pi / 2, -10.0, "cycloidal")])
        >>> DiscCam(rise, 5.0, roller_radius=2.0).profile().check()
        Traceback (most recent call last):
        ...
        linkage.LinkageError: pressure angle 48.9° exceeds the limit 30.0° at cam angle 323.0°; ...
        >>> DiscCam(rise, 40.0, roller_radius=2.0).profile().check().problems
        []
        """
        if self.problems:
            raise LinkageError("; ".join(self.problems))
        return self


class DiscCam:
    """A disc cam driving a translating follower.

    Parameters
    ----------
    program : Program
        Follower displacement against cam angle (rad), spanning one turn (period 2π) and
        returning to its start.
    base_radius : float
        Radius of the cam's base circle (the profile's smallest radius on a dwell at s = 0).
    roller_radius : float, optional
        Radius of a roller follower; omit for a flat-faced follower.
    offset : float
        Offset of a roller follower's axis from the cam centre.
    pressure_limit : float
        Largest acceptable |pressure angle| (rad), 30° by default.
    """

    def __init__(
        self,
        program: Program,
        base_radius: float,
        roller_radius: float | None = None,
        offset: float = 0.0,
        pressure_limit: float = math.radians(30.0),
    ) -> None:
        if not isinstance(program, Program):
            raise TypeError(
                f"program must be a linkage.drive.Program, got {type(program).__name__}"
            )
        if abs(program.period - 2 * math.pi) > 1e-9:
            raise LinkageError(
                f"a cam program must span one turn (2π rad), got {program.period:.9g} rad"
            )
        rise = sum(s.rise for s in program.segments)
        if abs(rise) > 1e-12 * max(1.0, sum(abs(s.rise) for s in program.segments)):
            raise LinkageError(f"a cam program must return to its start, it rises by {rise:g}")
        self.program = program
        self.base_radius = as_length(base_radius, "base_radius")
        self.roller_radius = (
            None if roller_radius is None else as_length(roller_radius, "roller_radius")
        )
        self.offset = as_finite(offset, "offset")
        if (
            self.roller_radius is not None
            and abs(self.offset) >= self.base_radius + self.roller_radius
        ):
            raise LinkageError("offset must be smaller than base_radius + roller_radius")
        self.pressure_limit = as_finite(pressure_limit, "pressure_limit")

    def profile(self, n: int = 721) -> CamProfile:
        """Sample the cam at ``n`` angles over one turn and check it.

        Parameters
        ----------
        n : int, default 721
            Cam angles over the turn, both ends included (at least 8).

        Returns
        -------
        CamProfile
            Displacement, pitch curve, profile, pressure angle and radii of curvature, with the
            problems found (undercut, pressure angle over :attr:`pressure_limit`) in
            :attr:`CamProfile.problems` — listed, not raised (see :meth:`CamProfile.check`).

        Raises
        ------
        LinkageError
            For ``n`` below 8.
        MemoryError
            When ``n`` samples would not fit in memory.

        Examples
        --------
        >>> import math
        >>> from linkage.cam import leg_lift_cam
        >>> p = leg_lift_cam().profile(361)
        >>> p.profile.shape, round(math.degrees(p.max_pressure_angle), 3), p.problems
        ((361, 2), 8.677, [])
        """
        n = as_count(n, "n", 8)
        # Angles, displacement and its rates, the geometry's outputs and temporaries.
        check_memory(n * 8 * 24, f"a cam profile of {n} samples")
        phi = np.linspace(0.0, 2 * math.pi, n)
        s, v, a, _ = self.program.eval(phi)
        y = np.ascontiguousarray(np.c_[s, v, a])
        raw = _core.drive.cam_geometry(phi, y, self.base_radius, self.roller_radius, self.offset)
        prof = CamProfile(
            phi=phi,
            displacement=s,
            pitch=raw.pitch,
            profile=raw.profile,
            pressure_angle=raw.pressure_angle,
            pitch_radius=raw.pitch_radius,
            profile_radius=raw.profile_radius,
        )
        prof.problems = self._problems(prof)
        return prof

    def _problems(self, p: CamProfile) -> list[str]:
        out = []
        deg = np.degrees(p.phi)
        if self.roller_radius is not None:
            convex = p.pitch_radius > 0
            bad = convex & (p.pitch_radius < self.roller_radius)
            if bad.any():
                k = int(np.flatnonzero(bad)[np.argmin(p.pitch_radius[bad])])
                out.append(
                    f"undercut: the pitch curve's radius of curvature {p.pitch_radius[k]:.4g} is "
                    f"smaller than the roller radius {self.roller_radius:g} at cam angle "
                    f"{deg[k]:.1f}°; enlarge the base circle or use a smaller roller"
                )
        else:
            bad = p.profile_radius < 0
            if bad.any():
                k = int(np.argmin(p.profile_radius))
                out.append(
                    f"undercut: the profile's radius of curvature Rb + s + s'' is "
                    f"{p.profile_radius[k]:.4g} < 0 at cam angle {deg[k]:.1f}° (a cusp); "
                    f"enlarge the base circle"
                )
        k = int(np.argmax(np.abs(p.pressure_angle)))
        if abs(p.pressure_angle[k]) > self.pressure_limit:
            out.append(
                f"pressure angle {math.degrees(abs(p.pressure_angle[k])):.1f}° exceeds the "
                f"limit {math.degrees(self.pressure_limit):.1f}° at cam angle {deg[k]:.1f}°; "
                f"enlarge the base circle or lengthen the rise"
            )
        return out


def leg_lift(height: float = 1.4) -> Program:
    """Thesis 2's leg lift, the one model of it that the hexapod walker and its cam share.

    The foot is up by ``height`` at crank angle 0 (the middle of the Hoecken leg's swing), down to
    the ground over a quarter turn with a simple-harmonic law, on the ground for the half turn of
    the stance, and up again over the last quarter turn. Thesis 2 gives the height (1.4 mm) and the
    harmonic law; the quarter-turn ramps keep the foot down over the whole straight part.

    Parameters
    ----------
    height : float, default 1.4
        The lift, in the walker's length unit (thesis 2: 1.4 mm).

    Returns
    -------
    Program
        Foot height against the leg's crank angle (rad), one turn.

    Raises
    ------
    LinkageError
        For a ``height`` that is negative or not finite.
    TypeError
        For a ``height`` that is not a number.

    Examples
    --------
    >>> import math
    >>> from linkage.cam import leg_lift
    >>> p = leg_lift()
    >>> [round(float(x), 6) for x in p.eval([0.0, math.pi / 2, math.pi, 2 * math.pi])[0]]
    [1.4, 0.0, 0.0, 1.4]
    >>> leg_lift(float("nan"))
    Traceback (most recent call last):
    ...
    linkage.LinkageError: height must be finite, got nan
    >>> leg_lift(-1.0)
    Traceback (most recent call last):
    ...
    linkage.LinkageError: height must be a lift of 0 or more, got -1.0
    """
    h = as_finite(height, "height")
    if h < 0:
        raise LinkageError(f"height must be a lift of 0 or more, got {h!r}")
    return Program(
        h,
        [
            Segment(math.pi / 2, -h, "simple-harmonic"),
            Segment(math.pi),
            Segment(math.pi / 2, h, "simple-harmonic"),
        ],
    )


def leg_lift_cam(roller_radius: float = 2.0, base_radius: float = 6.5) -> DiscCam:
    """Thesis 2's leg-lift cam (mm): :func:`leg_lift` as a disc cam.

    The source's drawing gives 13 mm across the cam; read here as the base-circle diameter, with
    a 2 mm roller — both assumptions, as the source does not say.

    Parameters
    ----------
    roller_radius : float, default 2.0
        Radius of the roller follower (mm).
    base_radius : float, default 6.5
        Radius of the base circle (mm).

    Returns
    -------
    DiscCam
        The cam, lifting 1.4 mm.

    Raises
    ------
    LinkageError
        For a radius that is not a positive finite length.

    Examples
    --------
    >>> from linkage.cam import leg_lift_cam
    >>> leg_lift_cam().profile().undercut
    False
    >>> leg_lift_cam(roller_radius=0.0)
    Traceback (most recent call last):
    ...
    linkage.LinkageError: roller_radius must be a positive finite length, got 0.0
    """
    return DiscCam(leg_lift(1.4), base_radius, roller_radius=roller_radius)


# These classes' 0.1 module (a re-export of this one) stays their ``__module__``, for pickles and
# reprs; doctest looks for a class's examples in its ``__module__``: ``__test__`` points here.
__test__: dict[str, type] = {"CamProfile": CamProfile, "DiscCam": DiscCam}
for _cls in __test__.values():
    _cls.__module__ = "linkage.cam"
