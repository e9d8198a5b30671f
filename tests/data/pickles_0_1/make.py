"""Write the pickles of linkage 0.1 objects that tests/test_api_0_1.py loads (run with 0.1).

PYTHONPATH=<0.1 checkout>/python python tests/data/pickles_0_1/make.py
"""

import math
import pickle
from pathlib import Path

import numpy as np

import linkage
from linkage import catalog, drive, forces, geometry

HERE = Path(__file__).parent
fb = linkage.FourBar(ground=20, crank=10, coupler=25, rocker=25, point=(50, 0))
theta = np.linspace(0, 2 * math.pi, 5)
objects = {
    "fourbar": fb,
    "sweep": fb.sweep(theta),
    "mechanism": fb.mechanism(),
    "slider_crank": linkage.SliderCrank(crank=10, coupler=30),
    "walker": catalog.quadruped_hoecken(),
    "leg": catalog.quadruped_hoecken().legs[0],
    "constant_speed": drive.ConstantSpeed(omega=2.0, theta0=1.0),
    "program": drive.Program(0.0, [drive.Segment(1.0, 2.0, "simple-harmonic"), drive.Segment(0.5)]),
    "mobility": geometry.mobility(4, 4),
    "link_mass": forces.LinkMass(1.0, (0.5, 0.0), 0.1),
}
for name, obj in objects.items():
    (HERE / f"{name}.pickle").write_bytes(pickle.dumps(obj, protocol=4))
    print(name, type(obj).__module__, type(obj).__qualname__)
