"""The ``linkage`` command: the main job prints real figures; errors exit non-zero."""

from __future__ import annotations

import re
import subprocess
import sys

import numpy as np

from linkage.cli import hoecken_report, main


def test_run_prints_hoecken_table(capsys):
    assert main(["run", "--samples", "721"]) == 0
    out = capsys.readouterr().out
    assert "crank-rocker" in out and "64.286" in out
    # The stride: the stance within 0.1 mm of a line covers at least the exact straight points
    # x = 0 … 40 (their bulge between is 0.0975 mm; hand-computed in the core's golden test).
    m = re.search(r"stride \(stance within 0.1 mm of a line\)\s+([0-9.]+)", out)
    assert m and 40.0 < float(m.group(1)) < 48.0


def test_report_figures_are_consistent():
    rows = {r[0]: r for r in hoecken_report(1441)}
    lo, hi = (float(x) for x in rows["foot path y range"][1].split(" … "))
    # Printed to 3 decimals: agree to half a unit of the last digit.
    assert abs(lo - 40.0) <= 5e-4 and abs(hi - 2 * np.sqrt(600)) <= 5e-4
    # The stance line sits within its 0.1 mm tolerance of y = 40, so the lift above it is the
    # path's height less at most that.
    lift = float(rows["lift height (swing above stance line)"][1])
    assert (hi - lo) - 0.1 <= lift <= (hi - lo) + 5e-4


def test_console_script_and_module_agree():
    out = subprocess.run(
        [sys.executable, "-m", "linkage", "catalog"], capture_output=True, text=True, check=True
    ).stdout
    for name in ("hoecken", "evans_a", "peaucellier", "hart", "hoecken_pantograph"):
        assert name in out


def test_run_with_scene_is_a_clear_error(capsys):
    assert main(["run", "scene.toml"]) == 2
    assert "scene files are not supported yet" in capsys.readouterr().err
