"""linkage — kinematics of planar linkages, solved in closed form on a tracked branch.

>>> import numpy as np, linkage
>>> fb = linkage.FourBar(ground=20, crank=10, coupler=25, rocker=25, point=(50, 0))
>>> s = fb.sweep(np.linspace(0, 2 * np.pi, 5))
>>> s.point.shape, s.joints.shape, s.valid.dtype
((5, 2), (5, 5, 2), dtype('bool'))

Conventions: angles in radians, counter-clockwise positive; lengths in any consistent unit.
"""

from __future__ import annotations

from linkage import (
    batch,
    cam,
    catalog,
    drive,
    forces,
    gait_search,
    geometry,
    synthesis,  # path synthesis (scipy imported on first use)
    walker,
)
from linkage._core import AssemblyError, LinkageError
from linkage._shared.choices import Assembly, Output, Reach, Side
from linkage._shared.version import __version__
from linkage.kinematics.fourbar import FourBar
from linkage.kinematics.mechanism import Mechanism
from linkage.kinematics.slider_crank import SliderCrank
from linkage.kinematics.sweep import OUTPUTS, Sweep
from linkage.motion.geometry import (
    circumcentre,
    curvature_centre,
    foot_path,
    inflection_circle,
    mobility,
    straightness,
    three_point_centres,
)
from linkage.walking.gait_search import search_duty_factor
from linkage.walking.walker import Leg, Walker, gait_phases

__all__ = [
    "OUTPUTS",
    "Assembly",
    "AssemblyError",
    "FourBar",
    "Leg",
    "LinkageError",
    "Mechanism",
    "Output",
    "Reach",
    "Side",
    "SliderCrank",
    "Sweep",
    "Walker",
    "__version__",
    "batch",
    "cam",
    "catalog",
    "circumcentre",
    "curvature_centre",
    "drive",
    "foot_path",
    "forces",
    "gait_phases",
    "gait_search",
    "geometry",
    "inflection_circle",
    "mobility",
    "search_duty_factor",
    "straightness",
    "synthesis",
    "three_point_centres",
    "walker",
]
