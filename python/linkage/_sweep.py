"""The result of a sweep: numpy arrays, one row per crank angle."""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import NDArray

OUTPUTS = ("point", "joints", "velocity", "acceleration")
"""Names accepted by ``outputs=``: the trace point, every joint, and their rates."""


class Sweep:
    """Positions (and, if asked, velocities and accelerations) over a sweep of crank angles.

    Every array has one row per angle, in the order given; a sample that cannot be assembled is
    NaN with ``valid`` False, and ``gap`` says by how much its lengths miss closure.

    Attributes
    ----------
    theta : (N,) float64
        Crank angles, radians.
    joints : (N, J, 2) float64
        Every joint, in ``joint_names`` order.
    valid : (N,) bool
        Whether each sample assembled.
    margin : (N,) float64
        Smallest dyad assembly margin (sine of the angle between the two links at the joint):
        0 at a toggle, where velocities are unbounded. NaN where invalid.
    gap : (N,) float64
        0 where valid; how much the lengths miss closure where not (NaN when undetermined).
    point : (N, 2) float64
        The trace joint (``trace``).
    velocity, acceleration : (N, 2) float64
        Rates of the trace point, when requested in ``outputs``.
    joint_velocities, joint_accelerations : (N, J, 2) float64
        Rates of every joint, when requested.
    """

    def __init__(
        self,
        theta: NDArray[np.float64],
        raw: dict[str, Any],
        joint_names: tuple[str, ...],
        trace: int,
        outputs: tuple[str, ...],
        scalar: bool = False,
    ) -> None:
        self.joint_names = joint_names
        self.trace = joint_names[trace]
        self.outputs = outputs
        self._trace = trace

        def pick(a: Any) -> Any:
            return a[0] if scalar else a

        self.theta: NDArray[np.float64] = pick(theta)
        self.joints: NDArray[np.float64] = pick(raw["joints"])
        self.valid: NDArray[np.bool_] = pick(raw["valid"])
        self.margin: NDArray[np.float64] = pick(raw["margin"])
        self.gap: NDArray[np.float64] = pick(raw["gap"])
        self._rates = {
            k: pick(raw[k]) for k in ("velocity", "acceleration") if k in raw and k in outputs
        }

    def __len__(self) -> int:
        return int(np.size(self.valid))

    def __repr__(self) -> str:
        n, ok = len(self), int(np.count_nonzero(self.valid))
        joints = ", ".join(self.joint_names)
        return f"<Sweep {n} samples ({ok} valid), joints {joints}; outputs {self.outputs}>"

    def joint(self, name: str) -> NDArray[np.float64]:
        """Positions of one joint by name, shape (N, 2)."""
        try:
            i = self.joint_names.index(name)
        except ValueError:
            raise KeyError(f"no joint {name!r}; joints are {', '.join(self.joint_names)}") from None
        return self.joints[..., i, :]

    @property
    def point(self) -> NDArray[np.float64]:
        """The trace point, shape (N, 2)."""
        return self.joints[..., self._trace, :]

    def _rate(self, kind: str) -> NDArray[np.float64]:
        if kind not in self._rates:
            raise AttributeError(
                f"{kind} was not computed: pass outputs=(..., {kind!r}) and omega to sweep()"
            )
        arr: NDArray[np.float64] = self._rates[kind]
        return arr

    @property
    def velocity(self) -> NDArray[np.float64]:
        """Velocity of the trace point, shape (N, 2)."""
        return self._rate("velocity")[..., self._trace, :]

    @property
    def acceleration(self) -> NDArray[np.float64]:
        """Acceleration of the trace point, shape (N, 2)."""
        return self._rate("acceleration")[..., self._trace, :]

    @property
    def joint_velocities(self) -> NDArray[np.float64]:
        """Velocities of every joint, shape (N, J, 2)."""
        return self._rate("velocity")

    @property
    def joint_accelerations(self) -> NDArray[np.float64]:
        """Accelerations of every joint, shape (N, J, 2)."""
        return self._rate("acceleration")
